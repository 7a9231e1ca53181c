//! Offscreen rendering, asserted on pixels. Runs on any wgpu adapter (Mesa's
//! lavapipe or llvmpipe in CI). Skips only when no adapter exists and
//! SUBDIV_REQUIRE_GPU is unset; CI sets it, so there a missing adapter fails.
#![cfg(feature = "viewer")]

mod common;

use common::{bundled, hemisphere, offscreen};
use glam::Vec3;
use image::RgbaImage;
use subdiv::render::background_srgb8_at;
use subdiv::render::{Camera, Look, Offscreen, Shading, Surface, default_camera};
use subdiv::{Mesh, Options, Scheme, subdivide};

fn render(off: &mut Offscreen, mesh: &Mesh, control: Option<&Mesh>, look: Look, ortho: bool) -> RgbaImage {
    let (w, h) = off.size();
    let opts = subdiv::render::RenderOptions { width: w, height: h, orthographic: ortho, ..Default::default() };
    let cam = default_camera(control.unwrap_or(mesh), &opts);
    let gm = off.upload(mesh).unwrap();
    let gc = control.map(|c| off.upload(c).unwrap());
    off.render_one(cam, &gm, gc.as_ref(), look).unwrap()
}

/// Whether pixel (x, y) shows the background: the vertical gradient's value
/// in its row.
fn is_background(img: &RgbaImage, x: u32, y: u32) -> bool {
    let bg = background_srgb8_at(y, img.height());
    let p = img.get_pixel(x, y).0;
    (0..3).all(|i| (i32::from(p[i]) - i32::from(bg[i])).abs() <= 1)
}

fn luminance(p: [u8; 4]) -> f64 {
    0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2])
}

fn differing_pixels(a: &RgbaImage, b: &RgbaImage) -> usize {
    a.pixels().zip(b.pixels()).filter(|(p, q)| (0..3).any(|i| p.0[i].abs_diff(q.0[i]) > 8)).count()
}

fn fine(name: &str, scheme: Scheme, levels: u32) -> (Mesh, Mesh) {
    let m = bundled(name);
    let f = subdivide(&m, scheme, levels, &Options::default()).unwrap().0;
    (m, f)
}

#[test]
fn every_bundled_model_covers_the_centre_and_leaves_the_corners_background() {
    // An odd width exercises the 256-byte row padding of the readback.
    let Some(mut off) = offscreen(161, 120) else { return };
    for name in common::BUNDLED {
        let (control, mesh) = fine(name, Scheme::Loop, 2);
        let img = render(&mut off, &mesh, Some(&control), Shading::Phong.look(), false);
        assert_eq!(img.dimensions(), (161, 120));
        for (x, y) in [(0, 0), (160, 0), (0, 119), (160, 119)] {
            assert!(is_background(&img, x, y), "{name}: corner ({x},{y}) is {:?}", img.get_pixel(x, y));
        }
        let covered = (-3..=3).flat_map(|dx| (-3..=3).map(move |dy| (80 + dx, 60 + dy)));
        let hits = covered.filter(|&(x, y)| !is_background(&img, x as u32, y as u32)).count();
        // The torus has a hole in the middle, so ask for the centre region to be mostly covered elsewhere.
        if name == "torus.obj" {
            let object = img.enumerate_pixels().filter(|&(x, y, _)| !is_background(&img, x, y)).count();
            assert!(object > 161 * 120 / 8, "{name}: only {object} object pixels");
        } else {
            assert!(hits >= 40, "{name}: centre not covered ({hits}/49)");
        }
    }
}

#[test]
fn wireframe_flat_and_phong_differ() {
    let Some(mut off) = offscreen(200, 160) else { return };
    let (_, mesh) = fine("cube.obj", Scheme::Butterfly, 2);
    let phong = render(&mut off, &mesh, None, Shading::Phong.look(), false);
    let flat = render(&mut off, &mesh, None, Shading::Flat.look(), false);
    let wire = render(&mut off, &mesh, None, Shading::Wire.look(), false);
    let both = render(&mut off, &mesh, None, Shading::PhongWire.look(), false);
    let area = 200 * 160;
    assert!(differing_pixels(&phong, &wire) > area / 20, "wire vs phong");
    assert!(differing_pixels(&phong, &both) > area / 50, "phong+wire vs phong");
    assert!(differing_pixels(&phong, &flat) > area / 100, "flat vs phong");
    // Wire only: the inside of the object is mostly background between lines, unlike Phong.
    let bg_inside = |img: &RgbaImage| {
        (80..120).flat_map(|x| (60..100).map(move |y| (x, y))).filter(|&(x, y)| is_background(img, x, y)).count()
    };
    assert!(bg_inside(&wire) > 400, "wireframe interior should show the background between edges");
    assert_eq!(bg_inside(&phong), 0, "the shaded cube covers its interior");
}

#[test]
fn the_lit_side_is_brighter_than_the_far_side() {
    // The key light comes from the upper left of the default view (and a
    // headlight from the eye): on a sphere the upper-left limb must be
    // brighter than the lower-right one.
    let Some(mut off) = offscreen(200, 200) else { return };
    let sphere = subdiv::mesh::icosphere(4);
    let img = render(&mut off, &sphere, None, Shading::Phong.look(), true);
    let mean = |x0: u32, y0: u32| {
        let mut s = 0.0;
        let mut n = 0;
        for x in x0..x0 + 20 {
            for y in y0..y0 + 20 {
                if !is_background(&img, x, y) {
                    s += luminance(img.get_pixel(x, y).0);
                    n += 1;
                }
            }
        }
        assert!(n > 100, "region at ({x0},{y0}) is off the sphere");
        s / f64::from(n)
    };
    let (upper_left, lower_right) = (mean(55, 55), mean(125, 125));
    eprintln!("lit {upper_left:.1} far {lower_right:.1}");
    assert!(upper_left > lower_right + 15.0, "upper left {upper_left:.1} vs lower right {lower_right:.1}");
}

#[test]
fn orthographic_and_perspective_images_differ() {
    let Some(mut off) = offscreen(160, 160) else { return };
    let (_, mesh) = fine("lprism.obj", Scheme::Midpoint, 1);
    let persp = render(&mut off, &mesh, None, Shading::Phong.look(), false);
    let ortho = render(&mut off, &mesh, None, Shading::Phong.look(), true);
    assert!(differing_pixels(&persp, &ortho) > 160 * 160 / 100);
}

#[test]
fn the_control_overlay_draws_orange_lines_and_open_meshes_show_their_back() {
    let Some(mut off) = offscreen(200, 160) else { return };
    let (control, mesh) = fine("tetrahedron.obj", Scheme::Loop, 3);
    let orange = |img: &RgbaImage| {
        img.pixels().filter(|p| p.0[0] > 180 && p.0[2] < 80 && p.0[0].saturating_sub(p.0[1]) > 60).count()
    };
    let without = render(&mut off, &mesh, Some(&control), Shading::Phong.look(), false);
    let with = render(&mut off, &mesh, Some(&control), Look { control: true, ..Shading::Phong.look() }, false);
    assert_eq!(orange(&without), 0);
    assert!(orange(&with) > 100, "{} orange pixels", orange(&with));
    // Two-sided lighting: looking into an open hemisphere shows its warm back faces.
    let cup = hemisphere();
    let (lo, hi) = cup.bounds();
    let mut cam = Camera::framing(lo, hi, 1.25);
    // The opening faces -z: from a diagonal behind it the outside and, through the opening, the inside show.
    cam.yaw = 0.75 * std::f32::consts::PI;
    cam.pitch = 0.2;
    let g = off.upload(&cup).unwrap();
    let img = off.render_one(cam, &g, None, Look { surface: Surface::Smooth, ..Look::default() }).unwrap();
    let warm = img.pixels().filter(|p| p.0[0].saturating_sub(p.0[2]) > 20).count();
    let cool = img.pixels().filter(|p| p.0[2].saturating_sub(p.0[0]) > 20).count();
    eprintln!("warm {warm} cool {cool}");
    assert!(warm > 50 && cool > 50, "back faces {warm}, front faces {cool}");
}

#[test]
fn animation_frames_update_in_place_and_move() {
    use subdiv::anim::{Animation, Paths, Tweak};
    let Some(mut off) = offscreen(128, 128) else { return };
    let control = bundled("tetrahedron.obj");
    let paths = Paths::load(
        &std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("paths/tetrahedron.paths"),
        &Default::default(),
    )
    .unwrap();
    let mut anim = Animation::new(&control, &paths, Tweak::Jarek, 2, Scheme::Loop, 3, &Options::default()).unwrap();
    let (topo, p, n) = anim.evaluate_with_topology(0);
    let mut g = subdiv::render::GpuMesh::new(&off.gpu.device, topo, p, n).unwrap();
    let (lo, hi) = subdiv::render::motion_bounds(&anim);
    let cam = Camera::framing(lo, hi, 1.0);
    let first = off.render_one(cam, &g, None, Look::default()).unwrap();
    let (p, n) = anim.evaluate(anim.frame_count() / 2);
    g.update(&off.gpu.queue, p, n);
    let middle = off.render_one(cam, &g, None, Look::default()).unwrap();
    assert!(differing_pixels(&first, &middle) > 50, "the animation does not move");
}

#[test]
fn per_vertex_colours_replace_the_material_only_when_asked() {
    let Some(mut off) = offscreen(120, 120) else { return };
    let (control, mesh) = fine("cube.obj", Scheme::Loop, 1);
    let opts = subdiv::render::RenderOptions { width: 120, height: 120, ..Default::default() };
    let cam = default_camera(&control, &opts);
    let mut g = off.upload(&mesh).unwrap();
    g.set_colors(&off.gpu.device, &vec![Vec3::new(0.8, 0.02, 0.02); mesh.positions.len()]);
    let red = |img: &RgbaImage| {
        img.pixels().filter(|p| p.0[0].saturating_sub(p.0[1]) > 60 && p.0[0].saturating_sub(p.0[2]) > 60).count()
    };
    let plain = off.render_one(cam, &g, None, Look::default()).unwrap();
    let coloured = off.render_one(cam, &g, None, Look { colors: true, ..Look::default() }).unwrap();
    assert_eq!(red(&plain), 0);
    assert!(red(&coloured) > 1000, "{} red pixels", red(&coloured));
}

#[test]
fn the_checker_texture_follows_per_corner_uvs() {
    let Some(mut off) = offscreen(160, 160) else { return };
    let (control, attrs) = common::load_with_attributes(&common::model_path("cube_uv.obj"));
    let uv = attrs.uv.expect("cube_uv.obj has vt");
    let (fine, _) = subdivide(&control, Scheme::Loop, 2, &Options::default()).unwrap();
    let fuv = subdiv::mesh::refine_corner_uvs(&uv, 2);
    let attr: Vec<Vec3> = fuv.iter().map(|t| t.extend(0.0)).collect();
    let g =
        subdiv::render::GpuMesh::unwelded(&off.gpu.device, &fine.ct, &fine.positions, &fine.vertex_normals(), &attr)
            .unwrap();
    let opts = subdiv::render::RenderOptions { width: 160, height: 160, ..Default::default() };
    let cam = default_camera(&fine, &opts);
    let img = off.render_one(cam, &g, None, Look { colors: true, uv_checker: true, ..Look::default() }).unwrap();
    let blue = img.pixels().filter(|p| p.0[2].saturating_sub(p.0[0]) > 40).count();
    let light = img.pixels().filter(|p| p.0[0] > 150 && p.0[1] > 150).count();
    assert!(blue > 500 && light > 500, "checker squares: {blue} dark blue, {light} light");
    let plain = off.render_one(cam, &g, None, Look::default()).unwrap();
    assert!(differing_pixels(&img, &plain) > 2000);
}

/// The lighting model of shaders/mesh.wgsl's header, evaluated on the CPU:
/// ambient 0.12, per light 0.75 diffuse + 0.35 white Blinn-Phong specular
/// (shininess 48), for unit normal `n`, direction to the eye `v` and the
/// headlight's direction `head`; linear RGB.
fn documented_shading(n: Vec3, v: Vec3, head: Vec3) -> Vec3 {
    use subdiv::render::{FILL_INTENSITY, FILL_LIGHT, FRONT, HEADLIGHT_INTENSITY, KEY_INTENSITY, KEY_LIGHT};
    let base = FRONT.truncate();
    let light = |l: Vec3, intensity: f32| {
        let d = n.dot(l).max(0.0);
        let s = if d > 0.0 { n.dot((l + v).normalize()).max(0.0).powf(48.0) } else { 0.0 };
        intensity * (0.75 * d * base + Vec3::splat(0.35 * s))
    };
    0.12 * base
        + light(head, HEADLIGHT_INTENSITY)
        + light(KEY_LIGHT.normalize(), KEY_INTENSITY)
        + light(FILL_LIGHT.normalize(), FILL_INTENSITY)
}

#[test]
fn a_face_seen_head_on_is_lit_by_the_headlight_from_the_eye() {
    // A square facing an orthographic camera: n = v everywhere, so the
    // headlight (along v) gives full diffuse and its full specular highlight.
    let Some(mut off) = offscreen(96, 96) else { return };
    let quad = Mesh::from_triangles(
        vec![
            Vec3::new(-1.0, -1.0, 0.0),
            Vec3::new(1.0, -1.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(-1.0, 1.0, 0.0),
        ],
        &[0, 1, 2, 0, 2, 3],
    )
    .unwrap();
    let mut cam = Camera { yaw: 0.0, pitch: 0.0, orthographic: true, ..Camera::default() };
    cam.fit(Vec3::new(-1.0, -1.0, 0.0), Vec3::new(1.0, 1.0, 0.0), 1.0);
    let g = off.upload(&quad).unwrap();
    let img = off.render_one(cam, &g, None, Look::default()).unwrap();
    let v = -cam.forward();
    let want = documented_shading(Vec3::Z, v, v).clamp(Vec3::ZERO, Vec3::ONE);
    let srgb = |c: f32| if c <= 0.0031308 { c * 12.92 } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 };
    let got = img.get_pixel(48, 48).0;
    for i in 0..3 {
        let w = (srgb(want[i]) * 255.0).round();
        assert!((f32::from(got[i]) - w).abs() <= 2.0, "channel {i}: rendered {got:?}, documented {want} ({w})");
    }
}

#[test]
fn studio_differs_from_phong_and_the_background_is_a_quiet_vertical_gradient() {
    let Some(mut off) = offscreen(160, 120) else { return };
    let (control, mesh) = fine("torus.obj", Scheme::Loop, 2);
    let phong = render(&mut off, &mesh, Some(&control), Shading::Phong.look(), false);
    let studio = render(&mut off, &mesh, Some(&control), Shading::Studio.look(), false);
    assert!(differing_pixels(&phong, &studio) > 160 * 120 / 10, "studio looks like Phong");
    // the studio clay is neutral, Phong's material blue
    let bluish = |img: &RgbaImage| img.pixels().filter(|p| p.0[2].saturating_sub(p.0[0]) > 25).count();
    assert!(bluish(&studio) * 4 < bluish(&phong), "studio {} vs phong {}", bluish(&studio), bluish(&phong));
    let (top, bottom) = (luminance(phong.get_pixel(0, 0).0), luminance(phong.get_pixel(0, 119).0));
    assert!(top > bottom + 15.0 && top < bottom + 60.0, "background top {top:.0}, bottom {bottom:.0}");
}

/// The cube drawn flat without and with the FXAA pass, and how many pixels differ.
fn fxaa_change(off: &mut Offscreen) -> (RgbaImage, RgbaImage, usize) {
    let (control, mesh) = fine("cube.obj", Scheme::Loop, 1);
    off.renderer.fxaa = false;
    let aliased = render(off, &mesh, Some(&control), Shading::Flat.look(), false);
    off.renderer.fxaa = true;
    let smoothed = render(off, &mesh, Some(&control), Shading::Flat.look(), false);
    let changed =
        aliased.pixels().zip(smoothed.pixels()).filter(|(p, q)| (0..3).any(|i| p.0[i].abs_diff(q.0[i]) > 3)).count();
    (aliased, smoothed, changed)
}

#[test]
fn without_msaa_the_fxaa_pass_smooths_silhouettes() {
    // one sample whatever the adapter's default, so the pass runs everywhere
    let Some(mut off) = common::offscreen_with_samples(160, 120, 1) else { return };
    assert_eq!(off.renderer.samples, 1);
    let (aliased, smoothed, changed) = fxaa_change(&mut off);
    // the pass touches the edges only: a few hundred pixels, not the faces
    assert!(changed > 50 && changed < 160 * 120 / 10, "{changed} pixels changed");
    // and it keeps flat regions: the centre of a face is the same
    assert_eq!(aliased.get_pixel(80, 60), smoothed.get_pixel(80, 60));
    // with MSAA the pass is skipped: the same picture with it on or off
    let mut msaa = Offscreen::with_samples(160, 120, 4).unwrap();
    if msaa.renderer.samples > 1 {
        let (.., changed) = fxaa_change(&mut msaa);
        assert_eq!(changed, 0, "{}x MSAA: the FXAA pass changed {changed} pixels", msaa.renderer.samples);
    } else {
        eprintln!("NOTE: this adapter has no MSAA; only the single-sample half of the FXAA test ran");
    }
}

/// Dark-to-light and light-to-dark changes along a line of pixels of the
/// object (dark: luminance below 100, light above 160; the anti-aliased
/// pixels between them and the background count for neither).
fn transitions(img: &RgbaImage, line: impl Iterator<Item = (u32, u32)>) -> usize {
    let mut last = None;
    let mut n = 0;
    for (x, y) in line.filter(|&(x, y)| !is_background(img, x, y)) {
        let l = luminance(img.get_pixel(x, y).0);
        let now = if l < 100.0 {
            Some(false)
        } else if l > 160.0 {
            Some(true)
        } else {
            None
        };
        if let Some(now) = now {
            if last.is_some_and(|was| was != now) {
                n += 1;
            }
            last = Some(now);
        }
    }
    n
}

#[test]
fn zebra_stripes_follow_their_count_and_angle() {
    let Some(mut off) = offscreen(240, 240) else { return };
    let sphere = subdiv::mesh::icosphere(4);
    let zebra = |count, angle| Look {
        surface: Surface::Zebra,
        stripes: subdiv::render::Stripes { count, angle },
        ..Look::default()
    };
    let row = |img: &RgbaImage| transitions(img, (0..240).map(|x| (x, 120)));
    let column = |img: &RgbaImage| transitions(img, (0..240).map(|y| (120, y)));
    let few = render(&mut off, &sphere, None, zebra(8, 0), false);
    let many = render(&mut off, &sphere, None, zebra(24, 0), false);
    let turned = render(&mut off, &sphere, None, zebra(24, 90), false);
    // vertical light bars: the stripes cross the middle row, not the middle column
    assert!(row(&few) >= 4, "{} changes across 8 stripes", row(&few));
    assert!(row(&many) >= 2 * row(&few), "24 stripes {} against 8 stripes {}", row(&many), row(&few));
    assert!(column(&many) <= 2, "{} changes down the middle of vertical bars", column(&many));
    // turned a quarter: the same stripes cross the middle column instead
    assert!(
        column(&turned) >= row(&many) / 2 && row(&turned) <= 2,
        "turned: row {} column {}",
        row(&turned),
        column(&turned)
    );
}

#[test]
fn isophotes_are_rings_around_the_view_direction() {
    let Some(mut off) = offscreen(240, 240) else { return };
    let sphere = subdiv::mesh::icosphere(4);
    let look = Look { surface: Surface::Isophotes, ..Look::default() };
    let img = render(&mut off, &sphere, None, look, true);
    let row = transitions(&img, (0..240).map(|x| (x, 120)));
    let column = transitions(&img, (0..240).map(|y| (120, y)));
    // concentric bands: as many changes across as down, and several of them
    assert!(row >= 6 && row.abs_diff(column) <= 2, "row {row} column {column}");
}

/// The box of the pixels that are not background: `(x0, y0, x1, y1)`.
fn object_box(img: &RgbaImage) -> (u32, u32, u32, u32) {
    let (mut b, (w, h)) = ((u32::MAX, u32::MAX, 0, 0), img.dimensions());
    for y in 0..h {
        for x in 0..w {
            if !is_background(img, x, y) {
                b = (b.0.min(x), b.1.min(y), b.2.max(x), b.3.max(y));
            }
        }
    }
    b
}

/// The fit centres the model's pixels and fits both its width and its
/// height, at any size and aspect, in perspective and orthographically.
#[test]
fn the_fit_centres_the_model_at_every_size() {
    for (w, h) in [(700, 768), (640, 400), (240, 600), (800, 200)] {
        let Some(mut off) = offscreen(w, h) else { return };
        for name in ["torus.obj", "tetrahedron.obj", "critter.obj"] {
            let (_, mesh) = fine(name, Scheme::Loop, 2);
            for ortho in [false, true] {
                let img = render(&mut off, &mesh, None, Shading::Phong.look(), ortho);
                let (x0, y0, x1, y1) = object_box(&img);
                let what = format!("{name} {w}x{h} ortho {ortho}: pixels {x0}..{x1} x {y0}..{y1}");
                assert!(x0 > 0 && y0 > 0 && x1 < w - 1 && y1 < h - 1, "{what}: cut by an edge");
                // centred to a pixel or two (the rasterised silhouette)
                let (cx, cy) = (f64::from(x0 + x1) / 2.0, f64::from(y0 + y1) / 2.0);
                let (ex, ey) = (cx - f64::from(w - 1) / 2.0, cy - f64::from(h - 1) / 2.0);
                assert!(ex.abs() <= 2.5 && ey.abs() <= 2.5, "{what}: off centre by ({ex}, {ey})");
                // the tighter side filled to about 90%
                let fill = (f64::from(x1 - x0 + 1) / f64::from(w)).max(f64::from(y1 - y0 + 1) / f64::from(h));
                assert!(fill > 0.85 && fill < 0.93, "{what}: fills {fill}");
            }
        }
    }
}
