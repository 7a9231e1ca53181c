//! Animation along split-and-tweak paths (DESIGN.md 4).
