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

/// A bumped grid of `n` x `n` quads whose texture coordinates are the
/// vertices' `(x, y) / n` (one chart, no seam).
fn uv_grid(n: usize) -> String {
    let mut obj = String::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f32, j as f32);
            obj += &format!("v {x} {y} {}\nvt {} {}\n", (0.9 * x).sin() * (0.7 * y).cos(), x / n as f32, y / n as f32);
        }
    }
    let id = |i: usize, j: usize| j * (n + 1) + i + 1;
    for j in 0..n {
        for i in 0..n {
            let [a, b, c, d] = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            obj += &format!("f {a}/{a} {b}/{b} {c}/{c} {d}/{d}\n");
        }
    }
    obj
}

#[test]
fn texture_coordinates_come_along_linear_over_each_control_face_and_colours_at_their_limit() {
    let dir = scratch_dir("tessellate-uv");
    let grid = dir.join("grid.obj");
    let n = 4;
    std::fs::write(&grid, uv_grid(n)).expect("writes");
    let read = |p: &Path| subdiv::io::read(subdiv::io::Source::File(p), &Default::default()).expect("reads");
    let input = read(&grid);
    let (cage, cage_uv) = (&input.mesh, input.attributes.uv.as_ref().expect("the grid's uv"));
    let polys = subdiv::mesh::PolyMesh::from_mesh(cage);
    for scheme in ["loop", "catmull-clark"] {
        let (out, params) = (dir.join(format!("{scheme}.obj")), dir.join(format!("{scheme}.params")));
        let r = run(&["tessellate", s(&grid), s(&out), "-s", scheme, "-t", "1e-3x", "--params", s(&params)]);
        assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
        let got = read(&out);
        let uv = got.attributes.uv.as_ref().expect("the output has texture coordinates");
        assert_eq!(uv.len(), got.mesh.ct.num_corners());
        // each vertex's (face, u, v), and the chart there from the cage's own corners
        let rows = std::fs::read_to_string(&params).expect("params written");
        let at: Vec<(usize, f32, f32)> = rows
            .lines()
            .map(|l| {
                let t: Vec<&str> = l.split_whitespace().collect();
                (t[0].parse().expect("a face"), t[1].parse().expect("u"), t[2].parse().expect("v"))
            })
            .collect();
        assert_eq!(at.len(), got.mesh.positions.len());
        let want = |(f, u, v): (usize, f32, f32)| -> glam::Vec2 {
            if scheme == "loop" {
                let c = |k: usize| cage_uv[3 * f + k];
                c(0) * (1.0 - u - v) + c(1) * u + c(2) * v
            } else {
                // every face a quad: ptex face f is the quad, corners in face order
                let corners: Vec<u32> = polys.pt.face_corners(f as u32).collect();
                let c = |k: usize| xy(&polys.positions[polys.pt.vtx(corners[k]) as usize]) / n as f32;
                c(0) * ((1.0 - u) * (1.0 - v)) + c(1) * (u * (1.0 - v)) + c(2) * (u * v) + c(3) * ((1.0 - u) * v)
            }
        };
        for (c, t) in uv.iter().enumerate() {
            let vertex = got.mesh.ct.vtx(c as u32) as usize;
            let w = want(at[vertex]);
            assert!(
                (*t - w).length() < 1e-5,
                "{scheme}: corner {c} (vertex {vertex} at {:?}): {t} for {w}",
                at[vertex]
            );
        }
    }
    // the cube's charts keep their seams: a vertex on one has two coordinates
    let out = dir.join("cube.obj");
    let r = run(&["tessellate", "models/cube_uv.obj", s(&out), "-s", "catmull-clark", "-t", "1e-2x"]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let got = read(&out);
    let uv = got.attributes.uv.expect("uv");
    assert!(uv.iter().all(|t| (-1e-6..=1.0 + 1e-6).contains(&t.x) && (-1e-6..=1.0 + 1e-6).contains(&t.y)));
    let mut first: HashMap<u32, glam::Vec2> = HashMap::new();
    let seams = (0..uv.len())
        .filter(|&c| {
            let v = got.mesh.ct.vtx(c as u32);
            (*first.entry(v).or_insert(uv[c]) - uv[c]).length() > 1e-3
        })
        .count();
    assert!(seams > 0, "the charts' seams are kept");
    // its colours are 0.15 + 0.7 x position at the cage: the limit of
    // vertex data is affine in it, so the same holds at every output vertex
    let colors = got.attributes.colors.expect("the output has colours");
    for (c, p) in colors.iter().zip(&got.mesh.positions) {
        assert!((*c - (glam::Vec3::splat(0.15) + 0.7 * *p)).abs().max_element() < 1e-5, "{c} at {p}");
    }
}

fn xy(p: &glam::Vec3) -> glam::Vec2 {
    glam::Vec2::new(p.x, p.y)
}
