//! Animation along split-and-tweak paths (docs/design.md §7): every control vertex
//! follows a closed polygon of key positions, refined `n` times by split and
//! tweak (`tweak`); frame `f` puts each vertex at point `f` of its refined
//! polygon, and the mesh is re-evaluated through a recorded
//! [`crate::subdiv::tables::StencilPlan`] (`player`).

pub(crate) mod paths;
pub(crate) mod player;
pub(crate) mod tweak;

pub use paths::Paths;
pub use player::{Animation, Clock};
pub use tweak::Tweak;
