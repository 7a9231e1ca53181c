//! `subdiv render` and `subdiv animate`: files written whole, right sizes and
//! frame counts; refusals leave existing files alone; `animate --eval gpu`
//! writes the CPU's frames. Skips only without a GPU
//! adapter when SUBDIV_REQUIRE_GPU is unset.
#![cfg(all(feature = "viewer", feature = "cli"))]

mod common;
use common::{model_path, scratch_dir, share_within};
use std::path::PathBuf;
use std::process::{Command, Output};

fn tmp(name: &str) -> PathBuf {
    let d = scratch_dir("cli-render");
    d.join(name)
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

#[test]
fn render_writes_a_png_of_the_requested_size() {
    let out = tmp("torus.png");
    let tor = model_path("torus.obj");
    let Some(o) = run(&[
        "render",
        tor.to_str().unwrap(),
        out.to_str().unwrap(),
        "-s",
        "loop",
        "-n",
        "1",
        "--shading",
        "phong+wire",
        "--size",
        "123x77",
    ]) else {
        return;
    };
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let img = image::open(&out).unwrap();
    assert_eq!((img.width(), img.height()), (123, 77));
}

#[test]
fn animate_writes_k_times_two_to_the_n_frames() {
    let gif = tmp("tetra.gif");
    let Some(o) = run(&["animate", "--level", "2", "--refine", "1", "--size", "64x64", "--gif", gif.to_str().unwrap()])
    else {
        return;
    };
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let frames = image::AnimationDecoder::into_frames(
        image::codecs::gif::GifDecoder::new(std::io::BufReader::new(std::fs::File::open(&gif).unwrap())).unwrap(),
    );
    assert_eq!(frames.count(), 4 * 2, "4 keys refined once");

    let dir = tmp("frames");
    let paths = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("paths/tetrahedron.paths");
    let tet = model_path("tetrahedron.obj");
    let o = run(&[
        "animate",
        "--model",
        tet.to_str().unwrap(),
        "--paths",
        paths.to_str().unwrap(),
        "--level",
        "1",
        "--refine",
        "2",
        "--size",
        "32x32",
        "--frames-dir",
        dir.to_str().unwrap(),
    ])
    .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let mut names: Vec<String> =
        std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    assert_eq!(names.len(), 16);
    assert_eq!((names[0].as_str(), names[15].as_str()), ("frame_0000.png", "frame_0015.png"));

    // A model without paths animates along generated loops.
    let cube_gif = tmp("cube.gif");
    let cube = model_path("cube.obj");
    let o = run(&[
        "animate",
        "--model",
        cube.to_str().unwrap(),
        "--level",
        "1",
        "--refine",
        "0",
        "--size",
        "32x32",
        "--gif",
        cube_gif.to_str().unwrap(),
    ])
    .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// The PNG frames `animate --eval EVAL` writes for `extra`, and its stdout.
fn animate_frames(eval: &str, extra: &[&str]) -> Option<(Vec<image::RgbaImage>, String)> {
    let dir = tmp(&format!("frames-{eval}"));
    let _ = std::fs::remove_dir_all(&dir);
    let args = ["animate", "--eval", eval, "--size", "96x96", "--frames-dir", dir.to_str().unwrap()];
    let o = run(&[&args[..], extra].concat())?;
    assert!(o.status.success(), "--eval {eval}: {}", String::from_utf8_lossy(&o.stderr));
    let mut names: Vec<PathBuf> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()).collect();
    names.sort();
    let frames = names.iter().map(|p| image::open(p).unwrap().to_rgba8()).collect();
    Some((frames, String::from_utf8_lossy(&o.stdout).into_owned()))
}

#[test]
fn animate_eval_gpu_writes_the_cpus_frames() {
    // the bundled tetrahedron, Loop level 3, its 4 keys refined once: 8 frames
    let extra = ["--level", "3", "--refine", "1", "--shading", "phong+wire", "--control"];
    let Some((cpu, cpu_out)) = animate_frames("cpu", &extra) else { return };
    let (gpu, gpu_out) = animate_frames("gpu", &extra).unwrap();
    assert!(cpu_out.contains("evaluated on the CPU"), "{cpu_out}");
    assert!(gpu_out.contains("wrote 8 frames") && gpu_out.contains("evaluated on the GPU"), "{gpu_out}");
    assert_eq!((cpu.len(), gpu.len()), (8, 8));
    for (f, (c, g)) in cpu.iter().zip(&gpu).enumerate() {
        let share = share_within(c, g, 8);
        assert!(share >= 0.995, "frame {f}: only {:.2}% of the pixels within 8 levels", share * 100.0);
    }
    // the GPU's frames move: each differs from the one before
    for f in 1..gpu.len() {
        let moved = 1.0 - share_within(&gpu[f - 1], &gpu[f], 8);
        assert!(moved > 0.01, "GPU frame {f} is frame {} ({:.3}% of the pixels moved)", f - 1, moved * 100.0);
    }
    // a GIF too, and --stats with an output says only what it measured
    let gif = tmp("tetra-gpu.gif");
    let args = ["animate", "--eval", "gpu", "-l", "2", "--refine", "1", "--size", "48x48", "--stats"];
    let o = run(&[&args[..], &["--gif", gif.to_str().unwrap()][..]].concat()).unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("plan_ms=") && !out.contains("frame_ms="), "{out}");
    let frames = image::AnimationDecoder::into_frames(
        image::codecs::gif::GifDecoder::new(std::io::BufReader::new(std::fs::File::open(&gif).unwrap())).unwrap(),
    );
    assert_eq!(frames.count(), 8);
}

#[test]
fn refused_animations_leave_existing_files_alone() {
    let gif = tmp("keep.gif");
    std::fs::write(&gif, b"previous").unwrap();
    let cube = model_path("cube.obj");
    let tet_paths = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("paths/tetrahedron.paths");
    for args in [
        vec!["animate", "--tweak", "wobbly", "--gif", gif.to_str().unwrap()],
        // The tetrahedron's 4-vertex paths do not fit the 8-vertex cube.
        vec![
            "animate",
            "--model",
            cube.to_str().unwrap(),
            "--paths",
            tet_paths.to_str().unwrap(),
            "--gif",
            gif.to_str().unwrap(),
        ],
        vec!["animate", "--level", "40", "--gif", gif.to_str().unwrap()],
    ] {
        let o = Command::new(env!("CARGO_BIN_EXE_subdiv")).args(&args).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success() && !err.contains("panicked"), "{args:?}: {err}");
        assert!(err.contains("error"), "{err}");
        assert_eq!(std::fs::read(&gif).unwrap(), b"previous");
    }
}

#[test]
fn render_takes_repair_levels_alias_and_color() {
    let fin = tmp("fin.obj");
    std::fs::write(&fin, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n").unwrap();
    let out = tmp("fin.png");
    let (f, o) = (fin.to_str().unwrap(), out.to_str().unwrap());
    let Some(r) = run(&["render", f, o, "--size", "32x32"]) else { return };
    assert!(!r.status.success(), "a non-manifold model is refused without --repair");
    let Some(r) = run(&["render", f, o, "--size", "32x32", "--repair", "--level", "1"]) else { return };
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    // --color shells paints the level-2 vertices in the colour ramp: the picture changes
    let img = |color: &str| {
        let out = tmp(&format!("torus-{color}.png"));
        let tor = model_path("torus.obj");
        let r = run(&[
            "render",
            tor.to_str().unwrap(),
            out.to_str().unwrap(),
            "-l",
            "2",
            "--size",
            "96x64",
            "--color",
            color,
        ])
        .unwrap();
        assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
        image::open(&out).unwrap().to_rgba8()
    };
    let (plain, shells) = (img("none"), img("shells"));
    let differ = plain.pixels().zip(shells.pixels()).filter(|(a, b)| a != b).count();
    assert!(differ > 500, "only {differ} pixels changed");
    let Some(r) = run(&["render", model_path("torus.obj").to_str().unwrap(), o, "--color", "file"]) else { return };
    let e = String::from_utf8_lossy(&r.stderr);
    assert!(!r.status.success() && e.contains("no colors"), "{e}");
}

#[test]
fn render_takes_a_wire_level_a_scale_and_a_transparent_background() {
    let out = tmp("torus-shot.png");
    let tor = model_path("torus.obj");
    let args = ["render", tor.to_str().unwrap(), out.to_str().unwrap(), "-n", "2", "--shading", "phong+wire"];
    let extra = ["--wire-level", "control", "--transparent", "--scale", "2", "--size", "100x80"];
    let Some(o) = run(&[&args[..], &extra[..]].concat()) else { return };
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let img = image::open(&out).unwrap().to_rgba8();
    assert_eq!(img.dimensions(), (200, 160));
    assert_eq!(img.get_pixel(0, 0).0[3], 0);
    let bad = run(&[&args[..], &["--wire-level", "fine"][..]].concat()).unwrap();
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("unknown wire level 'fine'"));
}

#[test]
fn curvature_colours_a_torus_red_outside_blue_inside_with_a_colour_bar() {
    let out = tmp("torus-gaussian.png");
    let torus = model_path("torus.obj");
    let args = ["render", torus.to_str().unwrap(), out.to_str().unwrap(), "-n", "2", "--color", "gaussian-curvature"];
    let Some(r) = run(&[&args[..], &["--size", "480x360", "--ortho"]].concat()) else { return };
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let img = image::open(&out).unwrap().to_rgba8();
    let (mut red, mut blue) = (0, 0);
    for p in img.pixels() {
        let [r, g, b, _] = p.0.map(i32::from);
        red += usize::from(r > b + 12 && r > g + 8);
        blue += usize::from(b > r + 40 && b > g + 10);
    }
    // K > 0 on the outer half (pale red: the range is set by the larger
    // |K| around the hole), K < 0 around the hole (blue), and the bar at the
    // right edge holds both ends of the map
    assert!(red > 2000 && blue > 500, "red {red}, blue {blue}");
    let x = img.width() - 8;
    let top = img.get_pixel(x, img.height() / 5 + 4).0;
    let bottom = img.get_pixel(x, img.height() * 4 / 5 - 4).0;
    assert!(top[0] > top[2] + 60 && bottom[2] > bottom[0] + 60, "bar {top:?} {bottom:?}");
    // a scheme without an exact limit is refused, naming those with one
    let r = run(&[&args[..], &["-s", "butterfly"]].concat()).unwrap();
    assert!(!r.status.success() && String::from_utf8_lossy(&r.stderr).contains("loop"));
}

/// Pixels of `img` (off the colour bar at the right edge) much darker than
/// the lightest opaque pixel within 4 px across or along them, with every
/// pixel within 4 px opaque (off the silhouette, where shading may fall
/// fast): the dark valley of a line, not a slope of the shading.
fn line_pixels(img: &image::RgbaImage) -> Vec<(i64, i64)> {
    let (w, h) = (i64::from(img.width()), i64::from(img.height()));
    let lum = |x: i64, y: i64| {
        let [r, g, b, a] = img.get_pixel(x as u32, y as u32).0.map(f64::from);
        (a == 255.0).then_some(0.2126 * r + 0.7152 * g + 0.0722 * b)
    };
    let mut out = Vec::new();
    for y in 4..h - 4 {
        for x in 4..w - 60 {
            let Some(l) = lum(x, y) else { continue };
            let around: Option<Vec<f64>> =
                (-4..=4).flat_map(|d| [lum(x + d, y), lum(x, y + d), lum(x + d, y + d), lum(x + d, y - d)]).collect();
            let Some(around) = around else { continue };
            if l < 0.5 * around.iter().fold(0.0f64, |a, &b| a.max(b)) {
                out.push((x, y));
            }
        }
    }
    out
}

#[test]
fn isolines_trace_the_zero_of_gaussian_curvature_between_red_and_blue() {
    let torus = model_path("torus.obj");
    let render = |extra: &[&str]| {
        let out = tmp(&format!("torus-iso{}.png", extra.join("")));
        let args =
            ["render", torus.to_str().unwrap(), out.to_str().unwrap(), "-n", "2", "--color", "gaussian-curvature"];
        let r = run(&[&args[..], &["--size", "640x480", "--transparent"], extra].concat())?;
        assert!(r.status.success(), "{extra:?}: {}", String::from_utf8_lossy(&r.stderr));
        Some(image::open(&out).unwrap().to_rgba8())
    };
    let Some(off) = render(&[]) else { return };
    let (on, dense) = (render(&["--isolines", "2"]).unwrap(), render(&["--isolines", "6"]).unwrap());
    // dark valleys: many with isolines, none without
    let (lines_off, valleys_on) = (line_pixels(&off), line_pixels(&on));
    assert!(lines_off.is_empty(), "no isolines asked, {} line pixels", lines_off.len());
    assert!(valleys_on.len() > 300, "{} line pixels with 2 levels per side", valleys_on.len());
    // darkened from the plain colouring (the same picture but for the
    // lines): more with more levels
    let darker = |img: &image::RgbaImage| {
        let lum = |p: &image::Rgba<u8>| 0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2]);
        let (w, h) = (i64::from(img.width()), i64::from(img.height()));
        (0..h)
            .flat_map(|y| (0..w - 60).map(move |x| (x, y)))
            .filter(|&(x, y)| {
                let (a, b) = (off.get_pixel(x as u32, y as u32), img.get_pixel(x as u32, y as u32));
                a[3] == 255 && b[3] == 255 && lum(b) < lum(a) - 20.0
            })
            .collect::<Vec<_>>()
    };
    let (lines_on, lines_dense) = (darker(&on), darker(&dense));
    eprintln!("darkened pixels: {} with 2 levels per side, {} with 6", lines_on.len(), lines_dense.len());
    assert!(
        lines_dense.len() * 2 > lines_on.len() * 3,
        "6 levels {} vs 2 levels {}",
        lines_dense.len(),
        lines_on.len()
    );
    // K = 0 where the colours turn from red (outside, K > 0) to blue
    // (around the hole): opaque pixels of the plain colouring redder than
    // blue next to one bluer than red (the map is white at 0, the shading
    // scales it). Each has a line pixel of the isolined picture within 3 px.
    let sign = |x: i64, y: i64| {
        let [r, _, b, a] = off.get_pixel(x as u32, y as u32).0.map(i32::from);
        if a < 255 { 0 } else { (r - b).signum() }
    };
    let (w, h) = (i64::from(off.width()), i64::from(off.height()));
    let near = |p: (i64, i64), set: &[(i64, i64)], d: i64| {
        set.iter().any(|q| (q.0 - p.0).abs() <= d && (q.1 - p.1).abs() <= d)
    };
    let boundary: Vec<(i64, i64)> = (2..h - 2)
        .flat_map(|y| (2..w - 60).map(move |x| (x, y)))
        .filter(|&(x, y)| sign(x, y) == 1 && (-1..=1).any(|dy| (-1..=1).any(|dx| sign(x + dx, y + dy) == -1)))
        .collect();
    let traced = boundary.iter().filter(|&&p| near(p, &lines_on, 3)).count();
    eprintln!("{traced} of {} red-blue boundary pixels by a line", boundary.len());
    assert!(boundary.len() > 50, "the red-blue boundary: {} pixels", boundary.len());
    assert!(traced * 10 >= boundary.len() * 9, "{traced} of {} boundary pixels by a line", boundary.len());
    // and the zero line is there only: the plain colouring's boundary is not dark
    assert!(!boundary.iter().any(|&p| near(p, &lines_off, 3)));
}

/// Pixels off the colour bar (the right 80 columns) tinted red and blue.
fn hues(img: &image::RgbaImage) -> (usize, usize) {
    let (mut red, mut blue) = (0, 0);
    for (x, _, p) in img.enumerate_pixels() {
        if x + 80 >= img.width() || p.0[3] < 255 {
            continue;
        }
        let [r, g, b, _] = p.0.map(i32::from);
        red += usize::from(r > b + 30 && r > g + 25);
        blue += usize::from(b > r + 30 && b > g + 10);
    }
    (red, blue)
}

#[test]
fn catmull_clark_curvature_colours_the_critter_over_a_range_the_bar_states() {
    let critter = model_path("critter.obj");
    let render = |name: &str, extra: &[&str]| {
        let out = tmp(name);
        let args = ["render", critter.to_str().unwrap(), out.to_str().unwrap(), "-s", "catmull-clark", "-n", "3"];
        let r = run(&[&args[..], &["--size", "480x360", "--transparent"], extra].concat())?;
        let err = String::from_utf8_lossy(&r.stderr).into_owned();
        Some((r.status.success(), err, out))
    };
    let Some((ok, err, auto)) = render("critter-cc-mean.png", &["--color", "mean-curvature"]) else { return };
    assert!(ok, "{err}");
    let auto = image::open(auto).unwrap().to_rgba8();
    // the body coloured: the mean curvature is positive on most of the
    // critter (red); its Gaussian curvature has both signs' hues, red on the
    // snout and the paws, blue where the legs, neck and tail meet the body
    let (red, _) = hues(&auto);
    let (ok, err, gaussian) = render("critter-cc-gaussian.png", &["--color", "gaussian-curvature"]).unwrap();
    assert!(ok, "{err}");
    let (k_red, k_blue) = hues(&image::open(gaussian).unwrap().to_rgba8());
    eprintln!("default range: mean {red} red pixels; Gaussian {k_red} red, {k_blue} blue");
    assert!(red > 3000 && k_red > 300 && k_blue > 1000, "mean: red {red}; Gaussian: red {k_red}, blue {k_blue}");
    // a range set by hand changes the picture: twice as wide, paler
    let (ok, err, wide) = render("critter-cc-wide.png", &["--color", "mean-curvature", "--range", "8"]).unwrap();
    assert!(ok, "{err}");
    let wide = image::open(wide).unwrap().to_rgba8();
    let (red_wide, _) = hues(&wide);
    assert!(red_wide * 2 < red, "--range 8: {red_wide} red pixels, {red} by default");
    // the caption above the bar says which range: it differs between the two
    let w = auto.width();
    let caption = |img: &image::RgbaImage| -> Vec<(u32, u32)> {
        // the bar's ink, exactly
        let ink = |x: u32, y: u32| img.get_pixel(x, y).0 == [235, 235, 235, 255];
        (40..72).flat_map(|y| (w - 240..w).map(move |x| (x, y))).filter(|&(x, y)| ink(x, y)).collect()
    };
    let (said_auto, said_set) = (caption(&auto), caption(&wide));
    assert!(said_auto.len() > 100 && said_set.len() > 50, "{} {}", said_auto.len(), said_set.len());
    assert_ne!(said_auto, said_set, "the caption states the range");
    // bad ranges and a range without a curvature: one line each
    for (extra, says) in [
        (&["--color", "mean-curvature", "--range", "-1"][..], "--range '-1'"),
        (&["--color", "mean-curvature", "--range", "0"], "--range '0'"),
        (&["--color", "mean-curvature", "--range", "NaN"], "--range 'NaN'"),
        (&["--color", "shells", "--range", "2"], "--range sets the span of a curvature"),
    ] {
        let (ok, err, _) = render("critter-bad.png", extra).unwrap();
        assert!(!ok && err.contains(says) && err.trim().lines().count() == 1, "{extra:?}: {err}");
    }
    // schemes without curvature colours: refused, naming those with them
    for scheme in ["bilinear", "butterfly"] {
        let out = tmp("critter-refused.png");
        let args = ["render", critter.to_str().unwrap(), out.to_str().unwrap(), "-s", scheme, "-n", "1"];
        let r = run(&[&args[..], &["--color", "gaussian-curvature"]].concat()).unwrap();
        let err = String::from_utf8_lossy(&r.stderr);
        assert!(!r.status.success() && err.contains("loop and catmull-clark") && err.contains(scheme), "{err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
    }
}

/// Pixels of two images of one size whose colours differ by more than
/// `by` in some channel.
fn differing(a: &image::RgbaImage, b: &image::RgbaImage, by: u8) -> usize {
    assert_eq!(a.dimensions(), b.dimensions());
    a.pixels().zip(b.pixels()).filter(|(p, q)| p.0.iter().zip(q.0).any(|(x, y)| x.abs_diff(y) > by)).count()
}

#[test]
fn the_adaptive_limit_draws_as_a_fine_uniform_level_does() {
    let tor = model_path("torus.obj");
    let shot = |name: &str, extra: &[&str]| {
        let out = tmp(name);
        let mut args = vec!["render", tor.to_str().unwrap(), out.to_str().unwrap(), "-s", "loop", "--size", "400x300"];
        args.extend_from_slice(extra);
        let o = run(&args)?;
        assert!(o.status.success(), "{args:?}: {}", String::from_utf8_lossy(&o.stderr));
        Some(image::open(&out).unwrap().to_rgba8())
    };
    // level 5 stands in for the limit (its vertices within a fraction of a
    // pixel of it here); the adaptive mesh is framed as level 5 is
    let Some(fine) = shot("u5.png", &["-n", "5"]) else { return };
    let adaptive = shot("adaptive.png", &["-n", "5", "--adaptive", "0.5"]).unwrap();
    let rough = shot("adaptive8.png", &["-n", "5", "--adaptive", "8"]).unwrap();
    let total = (fine.width() * fine.height()) as usize;
    // (measured on lavapipe: 76 and 1,979 of 120,000 pixels)
    let (a, r) = (differing(&adaptive, &fine, 8), differing(&rough, &fine, 8));
    assert!(a * 200 < total, "adaptive: {a} of {total} pixels differ");
    // and the comparison sees a coarser tessellation
    assert!(r > 10 * a.max(1), "8 pixels: {r} differ, half a pixel: {a}");
}
