//! `subdiv tessellate` from the command line: a closed cage gives a closed
//! mesh within the tolerance, its `--params` are the points `subdiv eval`
//! reads and give back the mesh's own vertices, and bad arguments are
//! refused with a message. (The library's checks against a dense uniform
//! refinement are in `src/subdiv/tess/tests.rs`.)
#![cfg(feature = "cli")]

mod common;
use common::*;
use std::collections::HashMap;
use std::path::Path;
use std::process::{Command, Output};

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_subdiv")).args(args).output().expect("subdiv runs")
}

fn s(p: &Path) -> &str {
    p.to_str().expect("a UTF-8 path")
}

/// `key=value` fields of a `--stats` line.
fn field(text: &str, key: &str) -> String {
    let at = text.find(&format!("{key}=")).unwrap_or_else(|| panic!("no {key} in {text}"));
    text[at + key.len() + 1..].split_whitespace().next().unwrap_or("").to_string()
}

#[test]
fn a_closed_cage_gives_a_closed_mesh_within_the_tolerance_and_its_params() {
    let dir = scratch_dir("tessellate");
    let (out, params, eval) = (dir.join("torus.obj"), dir.join("torus.params"), dir.join("torus.eval"));
    let r = run(&["tessellate", "bundled:torus.obj", s(&out), "-t", "2e-3x", "--stats", "--params", s(&params)]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert!(r.status.success(), "{err}");
    assert_eq!(field(&err, "met"), "true", "{err}");
    let measured: f64 = field(&err, "measured").parse().expect("a number");
    let tolerance: f64 = field(&err, "tolerance").parse().expect("a number");
    assert!(measured <= tolerance && tolerance > 0.0, "{err}");
    let mesh = subdiv::bundled::load(&out).expect("the output reads back as a manifold mesh");
    let mut edges: HashMap<(u32, u32), u32> = HashMap::new();
    for c in 0..mesh.ct.num_corners() as u32 {
        let (a, b) = (mesh.ct.vtx(subdiv::mesh::n(c)), mesh.ct.vtx(subdiv::mesh::p(c)));
        *edges.entry((a.min(b), a.max(b))).or_default() += 1;
    }
    assert!(edges.values().all(|&k| k == 2), "a closed cage gives a closed mesh");
    // the params evaluated again are the vertices
    let r = run(&["eval", "bundled:torus.obj", s(&params), s(&eval)]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let rows = std::fs::read_to_string(&eval).expect("eval wrote");
    assert_eq!(rows.lines().count(), mesh.positions.len());
    for (line, p) in rows.lines().zip(&mesh.positions) {
        let x: Vec<f32> = line.split_whitespace().take(3).map(|t| t.parse().expect("a number")).collect();
        assert!((glam::Vec3::new(x[0], x[1], x[2]) - *p).length() < 1e-4, "{line} against {p}");
    }
}

#[test]
fn bad_tolerances_and_schemes_are_refused_by_name() {
    let out = scratch_dir("tessellate").join("bad.obj");
    for t in ["0", "-1", "nan", "x", "1e-3y"] {
        let r = run(&["tessellate", "bundled:torus.obj", s(&out), "-t", t]);
        assert!(!r.status.success(), "tolerance {t} accepted");
        assert!(String::from_utf8_lossy(&r.stderr).contains("positive distance"), "tolerance {t}");
    }
    let r = run(&["tessellate", "bundled:torus.obj", s(&out), "-s", "butterfly"]);
    assert!(!r.status.success());
    assert!(String::from_utf8_lossy(&r.stderr).contains("butterfly"), "{}", String::from_utf8_lossy(&r.stderr));
}
