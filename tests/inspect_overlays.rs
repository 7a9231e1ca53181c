//! `subdiv render --corner C` and `--stencil V`: the inspector's overlays
//! drawn into the PNG where they belong (the picked corner's dot at its
//! corner point, an arrow's colour along it, a disc in its weight's colour
//! at every control vertex of the stencil) and nowhere without the flag;
//! corners and vertices out of range refused in one line. Skips only
//! without a GPU adapter when SUBDIV_REQUIRE_GPU is unset.
#![cfg(all(feature = "viewer", feature = "cli"))]

mod common;
use common::{model_path, scratch_dir};
use glam::{Vec2, Vec3};
use image::RgbaImage;
use std::path::PathBuf;
use std::process::{Command, Output};
use subdiv::render::Viewport;
use subdiv::render::{RenderOptions, default_camera};
use subdiv::render::{op_color, triangle_corner_point, weight_color};
use subdiv::{Mesh, Options, Scheme};

const W: u32 = 480;
const H: u32 = 360;

fn tmp(name: &str) -> PathBuf {
    scratch_dir("inspect-overlays").join(name)
}

/// Runs the binary; `None` when it failed only for want of an adapter (and that may skip).
fn run(args: &[&str]) -> Option<Output> {
    let out = Command::new(env!("CARGO_BIN_EXE_subdiv")).args(args).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    if !out.status.success() && err.contains("no graphics adapter") {
        assert!(std::env::var_os("SUBDIV_REQUIRE_GPU").is_none(), "SUBDIV_REQUIRE_GPU is set: {err}");
        eprintln!("SKIPPED: no GPU adapter");
        return None;
    }
    Some(out)
}

/// `render MODEL OUT -s S -n L --size WxH EXTRA...` as an image.
fn render(model: &str, scheme: &str, level: u32, extra: &[&str], out: &str) -> Option<RgbaImage> {
    let (m, o) = (model_path(model), tmp(out));
    let (n, size) = (level.to_string(), format!("{W}x{H}"));
    let mut args = vec!["render", m.to_str().unwrap(), o.to_str().unwrap(), "-s", scheme, "-n", &n, "--size", &size];
    args.extend_from_slice(extra);
    let r = run(&args)?;
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    Some(image::open(&o).unwrap().to_rgba8())
}

/// Where the render puts world point `p`: its camera framing `frame`.
fn screen(frame: &Mesh, p: Vec3) -> Vec2 {
    let opts = RenderOptions { width: W, height: H, ..Default::default() };
    Viewport::image(W, H, 1.0).to_screen(&default_camera(frame, &opts), p).expect("in front of the camera")
}

/// Whether some pixel within `r` of `at` has the colour `want` (within `tol` per channel).
fn colour_near(img: &RgbaImage, at: Vec2, r: i32, want: [u8; 4], tol: u8) -> bool {
    (-r..=r).flat_map(|dy| (-r..=r).map(move |dx| (dx, dy))).any(|(dx, dy)| {
        let (x, y) = (at.x as i32 + dx, at.y as i32 + dy);
        (0..W as i32).contains(&x)
            && (0..H as i32).contains(&y)
            && (0..3).all(|i| img.get_pixel(x as u32, y as u32).0[i].abs_diff(want[i]) <= tol)
    })
}

/// Pixels that differ by more than 24 in some channel.
fn changed(a: &RgbaImage, b: &RgbaImage) -> Vec<(u32, u32)> {
    a.enumerate_pixels()
        .filter(|(x, y, p)| (0..3).any(|i| p.0[i].abs_diff(b.get_pixel(*x, *y).0[i]) > 24))
        .map(|(x, y, _)| (x, y))
        .collect()
}

#[test]
fn a_corner_is_drawn_as_a_dot_with_its_operators_arrows() {
    let Some(plain) = render("tetrahedron.obj", "loop", 1, &[], "plain.png") else { return };
    let c = 4u32;
    let marked = render("tetrahedron.obj", "loop", 1, &["--corner", &c.to_string()], "corner.png").unwrap();
    let control = subdiv::bundled::load(&model_path("tetrahedron.obj")).unwrap();
    let (fine, _) = subdiv::subdivide(&control, Scheme::Loop, 1, &Options::default()).unwrap();
    let at = |k: u32| triangle_corner_point(fine.ct.v_table(), &fine.positions, k);
    let dot = screen(&fine, at(c));
    assert!(colour_near(&marked, dot, 2, [255, 255, 255, 255], 20), "the white dot at corner {c}'s point {dot}");
    assert!(!colour_near(&plain, dot, 2, [255, 255, 255, 255], 20), "no dot without --corner");
    // each arrow in its colour partway to its target
    let ops = subdiv::mesh::corner_ops(&fine.ct, c).unwrap();
    let mut seen = 0;
    for (name, target) in [("n", Some(ops.n)), ("p", Some(ops.p)), ("o", ops.o), ("r", ops.r)] {
        let tip = screen(&fine, at(target.unwrap()));
        if (tip - dot).length() > 30.0 {
            // somewhere along it (another arrow or a label may cross it)
            let along = [0.25, 0.4, 0.55, 0.7, 0.85].map(|t| dot + (tip - dot) * t);
            assert!(along.iter().any(|&q| colour_near(&marked, q, 2, op_color(name), 40)), "{name}'s arrow to {tip}");
            seen += 1;
        }
    }
    assert!(seen >= 2, "arrows long enough to see: {seen}");
    // the marks stay near the corner and the caption; the rest is the plain render
    let diff = changed(&plain, &marked);
    // the arrows from the dot and the outline of the corner's triangle
    let targets = [ops.n, ops.p, ops.o.unwrap(), ops.l.unwrap(), ops.r.unwrap(), ops.s.unwrap(), ops.u.unwrap()];
    let mut segments: Vec<(Vec2, Vec2)> = targets.iter().map(|&t| (dot, screen(&fine, at(t)))).collect();
    let corners = [0, 1, 2].map(|i| screen(&fine, fine.positions[fine.ct.vtx(3 * (c / 3) + i) as usize]));
    segments.extend((0..3).map(|i| (corners[i], corners[(i + 1) % 3])));
    let near_marks = |x: u32, y: u32| {
        let q = Vec2::new(x as f32, y as f32);
        let near = |&(a, b): &(Vec2, Vec2)| {
            let d = b - a;
            let s = ((q - a).dot(d) / d.length_squared().max(1.0)).clamp(0.0, 1.0);
            (a + d * s).distance(q) < 40.0
        };
        segments.iter().any(near) || y < 45
    };
    assert!(diff.len() > 200, "the overlay draws: {} pixels", diff.len());
    let stray: Vec<_> = diff.iter().filter(|&&(x, y)| !near_marks(x, y)).collect();
    assert!(stray.is_empty(), "pixels changed away from the marks: {:?}", &stray[..stray.len().min(5)]);
}

#[test]
fn a_stencil_is_drawn_as_discs_in_its_weights_colours_at_the_control_vertices() {
    let Some(plain) = render("cube.obj", "butterfly", 1, &["--control"], "cube.png") else { return };
    let control = subdiv::bundled::load(&model_path("cube.obj")).unwrap();
    // an edge point of the 8-point butterfly: weights of both signs
    let (v, opts) = (8 + 3, Options::default());
    let st = subdiv::rules::stencil(&control, Scheme::Butterfly, 1, &opts, v).unwrap();
    assert!(st.weights.iter().any(|w| w.1 < 0.0) && st.weights.iter().any(|w| w.1 > 0.0), "{:?}", st.weights);
    let marked = render("cube.obj", "butterfly", 1, &["--stencil", &v.to_string()], "stencil.png").unwrap();
    let max = st.weights.iter().fold(0.0f64, |m, w| m.max(w.1.abs()));
    let mut seen = Vec::new();
    for &(j, w) in &st.weights {
        let at = screen(&control, control.positions[j as usize]);
        let want = weight_color(w, max);
        assert!(!colour_near(&plain, at, 1, want, 12), "no disc of vertex {j} without --stencil");
        if colour_near(&marked, at, 1, want, 12) {
            seen.push(j);
        }
    }
    // discs are drawn over the caption; one may hide behind another
    assert!(seen.len() + 1 >= st.weights.len(), "discs seen at {seen:?} of {:?}", st.weights);
    // the control vertices outside the stencil get no disc
    for j in (0..control.positions.len() as u32).filter(|j| st.weights.iter().all(|w| w.0 != *j)) {
        let at = screen(&control, control.positions[j as usize]);
        let px = marked.get_pixel(at.x as u32, at.y as u32).0;
        let plain_px = plain.get_pixel(at.x as u32, at.y as u32).0;
        let same = (0..3).all(|i| px[i].abs_diff(plain_px[i]) < 40);
        assert!(same || at.y < 60.0, "vertex {j}: {px:?} {plain_px:?}");
    }
}

#[test]
fn a_corner_or_vertex_out_of_range_is_refused_in_one_line() {
    let out = tmp("refused.png");
    let tet = model_path("tetrahedron.obj");
    for (flag, value, scheme, words) in [
        ("--corner", "48", "loop", "corner 48 out of range: level 1 of loop has 48 corners"),
        ("--stencil", "10", "loop", "vertex 10 out of range: level 1 of loop has 10 vertices"),
        ("--corner", "48", "catmull-clark", "corner 48 out of range: level 1 of catmull-clark has 48 corners"),
    ] {
        let o = Command::new(env!("CARGO_BIN_EXE_subdiv"))
            .args(["render", tet.to_str().unwrap(), out.to_str().unwrap(), "-n", "1", "-s", scheme, flag, value])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success() && err.contains(words), "{flag} {value}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(!out.exists(), "nothing written");
    }
    let o = Command::new(env!("CARGO_BIN_EXE_subdiv"))
        .args(["render", tet.to_str().unwrap(), out.to_str().unwrap(), "--corner", "1", "--stencil", "1"])
        .output()
        .unwrap();
    assert!(!o.status.success(), "one overlay at a time");
}

#[test]
fn the_quad_table_corner_is_drawn_for_catmull_clark() {
    let Some(plain) = render("critter.obj", "catmull-clark", 1, &[], "critter.png") else { return };
    let marked = render("critter.obj", "catmull-clark", 1, &["--corner", "1000"], "critter-corner.png").unwrap();
    let control = subdiv::bundled::load(&model_path("critter.obj")).unwrap();
    let (fine, _) = subdiv::subdivide(&control, Scheme::CatmullClark, 1, &Options::default()).unwrap();
    let pm = subdiv::mesh::PolyMesh::from_mesh(&fine);
    let dot = screen(&fine, subdiv::render::polygon_corner_point(&pm.pt, &fine.positions, 1000));
    assert!(colour_near(&marked, dot, 2, [255, 255, 255, 255], 20), "the dot at quad corner 1000: {dot}");
    assert!(changed(&plain, &marked).len() > 100);
}
