//! The single-pass wireframe, asserted on pixels of offscreen 640x480 renders
//! (like tests/render.rs): readable over the shading at level 3, visible at
//! level 0, anti-aliased, filtered by edge generation. Skips only when no
//! adapter exists and SUBDIV_REQUIRE_GPU is unset.
//!
//! "Hidden" is the share of the object's pixels (those that differ from the
//! background in the Phong image) whose luminance changes by more than 60
//! when the wire is drawn over the shading.
#![cfg(feature = "viewer")]

mod common;

use common::bundled;
use image::RgbaImage;
use subdiv::render::{Look, Offscreen, RenderOptions, Shading, WireEdges, default_camera};
use subdiv::{Mesh, Options, Scheme, subdivide};

const W: u32 = 640;
const H: u32 = 480;

fn offscreen() -> Option<Offscreen> {
    common::offscreen(W, H)
}

/// `name` refined `levels` times with Loop, with its control mesh.
fn level(name: &str, levels: u32) -> (Mesh, Mesh) {
    let control = bundled(name);
    let fine = subdivide(&control, Scheme::Loop, levels, &Options::default()).unwrap().0;
    (control, fine)
}

/// Renders `mesh` framed by `control` with each look.
fn renders(off: &mut Offscreen, control: &Mesh, mesh: &Mesh, looks: &[Look]) -> Vec<RgbaImage> {
    let opts = RenderOptions { width: W, height: H, ..Default::default() };
    let cam = default_camera(control, &opts);
    let gm = off.upload(mesh).unwrap();
    looks.iter().map(|&look| off.render_one(cam, &gm, None, look).unwrap()).collect()
}

fn luminance(p: &image::Rgba<u8>) -> f64 {
    0.2126 * f64::from(p.0[0]) + 0.7152 * f64::from(p.0[1]) + 0.0722 * f64::from(p.0[2])
}

/// Pixels of `img` that differ from the first pixel of their row (the
/// background: a vertical gradient).
fn object_mask(img: &RgbaImage) -> Vec<bool> {
    img.enumerate_pixels().map(|(_, y, p)| (0..3).any(|i| p.0[i].abs_diff(img.get_pixel(0, y).0[i]) > 2)).collect()
}

/// Share of the object's pixels (in `plain`) whose luminance changes by
/// more than `by` in `wired`.
fn changed_share(plain: &RgbaImage, wired: &RgbaImage, by: f64) -> f64 {
    let object = object_mask(plain);
    let total = object.iter().filter(|&&o| o).count();
    assert!(total > 1000, "the object covers only {total} pixels");
    let changed = plain
        .pixels()
        .zip(wired.pixels())
        .zip(&object)
        .filter(|&((p, q), &o)| o && (luminance(p) - luminance(q)).abs() > by)
        .count();
    changed as f64 / total as f64
}

fn wire(edges: WireEdges) -> Look {
    Look { wire_edges: edges, ..Shading::PhongWire.look() }
}

#[test]
fn the_wire_hides_at_most_40_percent_of_the_shaded_torus_at_level_3() {
    let Some(mut off) = offscreen() else { return };
    let (control, fine) = level("torus.obj", 3);
    let [phong, wired] =
        renders(&mut off, &control, &fine, &[Shading::Phong.look(), wire(WireEdges::All)]).try_into().unwrap();
    let hidden = changed_share(&phong, &wired, 60.0);
    let touched = changed_share(&phong, &wired, 8.0);
    eprintln!("torus L3: hidden {:.1}%, touched {:.1}%", 100.0 * hidden, 100.0 * touched);
    assert!(hidden <= 0.40, "the wire hides {:.1}% of the torus", 100.0 * hidden);
    // readable does not mean gone: the coarser generations still show
    assert!(touched > 0.05, "the wire changes only {:.1}% of the torus", 100.0 * touched);
}

#[test]
fn the_wire_is_clearly_visible_at_level_0() {
    let Some(mut off) = offscreen() else { return };
    for name in ["tetrahedron.obj", "cube.obj", "torus.obj"] {
        let control = bundled(name);
        let [phong, wired] =
            renders(&mut off, &control, &control, &[Shading::Phong.look(), wire(WireEdges::All)]).try_into().unwrap();
        let changed = changed_share(&phong, &wired, 30.0);
        eprintln!("{name} L0: {:.1}% of the object changes by more than 30", 100.0 * changed);
        // the fit fills 90% of the view, so the object has about twice the
        // pixels of the bounding-sphere fit this bound was set with
        assert!(changed > 0.008, "{name}: the level-0 wire changes {:.2}% of the object", 100.0 * changed);
    }
}

#[test]
fn wire_lines_are_anti_aliased() {
    // Wire only: one ink over the background, so every shade between the two
    // comes from the smoothstep across the lines' edges.
    let Some(mut off) = offscreen() else { return };
    let (control, fine) = level("cube.obj", 1);
    let [img] = renders(&mut off, &control, &fine, &[Shading::Wire.look()]).try_into().unwrap();
    // above the background of its row (a vertical gradient), by how much
    let above: Vec<f64> =
        img.enumerate_pixels().map(|(_, y, p)| luminance(p) - luminance(img.get_pixel(0, y))).collect();
    let ink = above.iter().cloned().fold(0.0, f64::max);
    assert!(ink > 60.0, "no line brighter than the background (at most {ink:.0} above it)");
    let line: Vec<f64> = above.iter().cloned().filter(|&l| l > 4.0).collect();
    let mut distinct: Vec<i64> = line.iter().map(|&l| l.round() as i64).collect();
    distinct.sort_unstable();
    distinct.dedup();
    let lit = line.len();
    let partial = line.iter().filter(|&&l| l < ink - 4.0).count();
    eprintln!("{} distinct shades above the background, {partial} of {lit} line pixels partly covered", distinct.len());
    assert!(distinct.len() >= 40, "only {} distinct luminances", distinct.len());
    assert!(partial * 3 > lit, "{partial} of {lit} line pixels are intermediate shades");
}

#[test]
fn control_edges_only_draw_fewer_wire_pixels_than_all_edges() {
    let Some(mut off) = offscreen() else { return };
    // at level 2 of the cube every generation is far enough apart to show
    let (control, fine) = level("cube.obj", 2);
    let looks = [Shading::Phong.look(), wire(WireEdges::All), wire(WireEdges::UpTo(1)), wire(WireEdges::UpTo(0))];
    let [phong, all, up_to_1, control_only] = renders(&mut off, &control, &fine, &looks).try_into().unwrap();
    let [a, b, c] = [&all, &up_to_1, &control_only].map(|img| changed_share(&phong, img, 8.0));
    eprintln!("wire pixels: all {:.1}%, up to level 1 {:.1}%, control {:.1}%", 100.0 * a, 100.0 * b, 100.0 * c);
    assert!(c > 0.02, "the control edges draw {:.2}% of the object", 100.0 * c);
    assert!(c < b && b < a, "the filter does not thin the wire: {a} {b} {c}");
}

#[test]
fn a_transparent_shot_has_alpha_0_around_an_opaque_object_and_scale_2_twice_the_size() {
    use subdiv::render::{Shot, render_image};
    if offscreen().is_none() {
        return;
    }
    let (_, fine) = level("cube.obj", 2);
    let opts =
        |shot| RenderOptions { width: 160, height: 120, shading: Shading::PhongWire, shot, ..Default::default() };
    let plain = render_image(&fine, None, &opts(Shot::default())).unwrap();
    let shot = render_image(&fine, None, &opts(Shot { scale: 2, transparent: true })).unwrap();
    assert_eq!(plain.dimensions(), (160, 120));
    assert_eq!(shot.dimensions(), (320, 240));
    assert_eq!(plain.get_pixel(0, 0).0[3], 255, "an ordinary render is opaque");
    for (x, y) in [(0, 0), (319, 0), (0, 239), (319, 239)] {
        assert_eq!(shot.get_pixel(x, y).0[3], 0, "corner ({x},{y})");
    }
    assert_eq!(shot.get_pixel(160, 120).0[3], 255, "the object is opaque");
    let opaque = shot.pixels().filter(|p| p.0[3] == 255).count();
    let object = object_mask(&plain).iter().filter(|&&o| o).count();
    // the object covers four times the pixels at twice the size
    let ratio = opaque as f64 / object as f64;
    assert!((3.6..4.4).contains(&ratio), "opaque {opaque} vs object {object} at scale 1");
}

#[test]
fn a_window_screenshot_renders_its_viewports_at_n_times_their_size() {
    // what P does in the window: the same draws, offscreen on the window's device
    use subdiv::render::shoot;
    use subdiv::render::{Shot, ViewportDraw};
    let Some(off) = offscreen() else { return };
    let (control, fine) = level("tetrahedron.obj", 2);
    let gm = off.upload(&fine).unwrap();
    let gc = off.upload(&control).unwrap();
    let opts = RenderOptions { width: 200, height: 100, ..Default::default() };
    let look = Look { control: true, ..Shading::PhongWire.look() };
    let shot = Shot { scale: 2, transparent: true };
    let (w, h) = shot.size(200, 100);
    let draws = [ViewportDraw {
        rect: [0.0, 0.0, w as f32, h as f32],
        camera: default_camera(&control, &opts),
        mesh: Some(&gm),
        control: Some(&gc),
        look,
    }];
    let img = shoot(&off.gpu.device, &off.gpu.queue, 1, (w, h), shot, &draws).unwrap();
    assert_eq!(img.dimensions(), (400, 200));
    assert_eq!(img.get_pixel(0, 0).0[3], 0);
    assert_eq!(img.get_pixel(200, 100).0[3], 255);
}

/// The brightest wire ink (luminance above the background of its row) in a
/// 5x5 block around the projection of `p`.
fn ink_at(img: &RgbaImage, cam: &subdiv::render::Camera, p: glam::Vec3) -> f64 {
    let ndc = cam.project(p, W as f32 / H as f32);
    let (x, y) = (((ndc.x + 1.0) * 0.5 * W as f32) as i64, ((1.0 - ndc.y) * 0.5 * H as f32) as i64);
    let mut ink = 0.0f64;
    for yy in (y - 2).max(0)..=(y + 2).min(H as i64 - 1) {
        for xx in (x - 2).max(0)..=(x + 2).min(W as i64 - 1) {
            let row = luminance(img.get_pixel(0, yy as u32));
            ink = ink.max(luminance(img.get_pixel(xx as u32, yy as u32)) - row);
        }
    }
    ink
}

/// A quad grid draws its quads' edges and never the diagonals its
/// triangles are drawn with, at level 0 (fanned from the file) and through
/// Catmull-Clark; the same grid read as triangles draws them, so the
/// samples can tell.
#[test]
fn a_quad_wire_renders_without_diagonals() {
    let Some(mut off) = offscreen() else { return };
    let mut quads = String::new();
    let mut triangles = String::new();
    for j in 0..3 {
        for i in 0..3 {
            let line = format!("v {} {} {}\n", i as f32, j as f32, 0.1 * ((i * j) % 2) as f32);
            quads.push_str(&line);
            triangles.push_str(&line);
        }
    }
    for j in 0..2 {
        for i in 0..2 {
            let (a, b, c, d) = (1 + i + 3 * j, 2 + i + 3 * j, 5 + i + 3 * j, 4 + i + 3 * j);
            quads.push_str(&format!("f {a} {b} {c} {d}\n"));
            triangles.push_str(&format!("f {a} {b} {c}\nf {a} {c} {d}\n"));
        }
    }
    let read = |text: &str, name: &str| common::read_bytes(text.as_bytes(), name).unwrap().mesh;
    let (q, t) = (read(&quads, "quads.obj"), read(&triangles, "triangles.obj"));
    let opts = RenderOptions { width: W, height: H, ..Default::default() };
    let cam = default_camera(&q, &opts);
    let look = Shading::Wire.look();
    let draw = |off: &mut Offscreen, m: &Mesh| {
        let gm = off.upload(m).unwrap();
        off.render_one(cam, &gm, None, look).unwrap()
    };
    let cc = subdivide(&q, Scheme::CatmullClark, 1, &Options::default()).unwrap().0;
    let (img_q, img_t, img_cc) = (draw(&mut off, &q), draw(&mut off, &t), draw(&mut off, &cc));
    let at = |img: &RgbaImage, x: f32, y: f32| ink_at(img, &cam, glam::Vec3::new(x, y, 0.05));
    for (x, y) in [(0.5, 0.5), (1.5, 0.5), (0.5, 1.5), (1.5, 1.5)] {
        // the centre of each quad lies on its diagonal (a quarter of the way
        // along it, for Catmull-Clark's quads); the inner edges x = 1 and
        // y = 1 pass beside it
        let (diag_t, diag_q) = (at(&img_t, x, y), at(&img_q, x, y));
        eprintln!("quad ({x}, {y}): ink on the diagonal {diag_t:.0} as triangles, {diag_q:.0} as a quad");
        assert!(diag_t > 40.0, "the triangles' diagonal at ({x}, {y}) is drawn ({diag_t:.0})");
        assert!(diag_q < 10.0, "no diagonal drawn in the quad at ({x}, {y}) ({diag_q:.0})");
        assert!(at(&img_q, 1.0, y) > 40.0 && at(&img_q, x, 1.0) > 40.0, "the inner edges by ({x}, {y}) are drawn");
        let quarter = at(&img_cc, x - 0.25, y - 0.25);
        assert!(quarter < 10.0, "no diagonal in Catmull-Clark's quads near ({x}, {y}) ({quarter:.0})");
    }
}
