//! The command line: outputs, --stats, and bad input giving one clear message,
//! a non-zero exit, no panic and no half-written file.
#![cfg(feature = "cli")]

mod common;
use common::*;
use std::path::{Path, PathBuf};
use std::process::Command;

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_subdiv"))
}

fn tmp(name: &str) -> PathBuf {
    let d = scratch_dir("cli");
    d.join(name)
}

fn write(name: &str, text: &str) -> PathBuf {
    let p = tmp(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn run_fail(args: &[&str]) -> String {
    let out = bin().args(args).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(!out.status.success(), "expected failure for {args:?}");
    assert!(!err.contains("panicked"), "panic for {args:?}: {err}");
    assert_eq!(err.trim().lines().count(), 1, "one clear line expected: {err}");
    err
}

#[test]
fn subdivide_writes_every_format_with_stats() {
    let input = model_path("cube.obj");
    for ext in ["obj", "ply", "ct"] {
        let out = tmp(&format!("cube2.{ext}"));
        let o = bin()
            .args([
                "subdivide",
                input.to_str().unwrap(),
                out.to_str().unwrap(),
                "--scheme",
                "loop",
                "--levels",
                "2",
                "--stats",
            ])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let stdout = String::from_utf8_lossy(&o.stdout);
        let ms: f64 =
            stdout.lines().find_map(|l| l.strip_prefix("subdivide_ms=")).expect("subdivide_ms line").parse().unwrap();
        assert!(ms >= 0.0);
        assert!(stdout.contains("edge_points_ms=") && stdout.contains("split_and_o_ms="));
        // the page size the refinement's arrays were given (src/mem.rs)
        assert!(stdout.contains(" pages=2MiB") || stdout.contains(" pages=4KiB"), "{stdout}");
        if ext != "ply" {
            let m = subdiv::bundled::load(&out).unwrap();
            assert_eq!(m.ct.num_triangles(), 12 * 16);
        } else {
            let bytes = std::fs::read(&out).unwrap();
            assert!(bytes.starts_with(b"ply\nformat binary_little_endian 1.0\n"));
        }
    }
    // the f64 path makes no record of its phases: it names no page size
    let out = tmp("cube2_f64.ply");
    let o = bin()
        .args(["subdivide", input.to_str().unwrap(), out.to_str().unwrap(), "-n", "2", "--precision", "f64", "--stats"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("subdivide_ms=") && !stdout.contains("pages="), "{stdout}");
    let o = bin().args(["info", model_path("torus.obj").to_str().unwrap()]).output().unwrap();
    let s = String::from_utf8_lossy(&o.stdout);
    assert!(s.contains("genus:           1") && s.contains("6:512"), "{s}");
}

#[test]
fn bad_input_is_refused_clearly() {
    let out = tmp("never.obj");
    let o = out.to_str().unwrap();
    let cases: Vec<(PathBuf, &str)> = vec![
        (write("garbage.obj", "\u{1}\u{2}\u{3} this is not a mesh\n"), "garbage.obj:1:"),
        (write("empty.obj", ""), "no triangles"),
        (write("nan.obj", "v 0 0 0\nv nan 1 0\nv 0 1 0\nf 1 2 3\n"), "nan.obj:2:"),
        (write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"), "range.obj:4:"),
        (
            write("fin.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n"),
            "non-manifold edge",
        ),
        (write("bowtie.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 2 1 0\nv 2 2 0\nf 1 2 3\nf 3 4 5\n"), "non-manifold vertex"),
        (PathBuf::from("/nonexistent/dir/x.obj"), "No such file"),
    ];
    for (input, want) in cases {
        let err = run_fail(&["subdivide", input.to_str().unwrap(), o, "--levels", "1"]);
        assert!(err.contains(want), "{}: {err}", input.display());
        assert!(err.contains(input.file_name().unwrap().to_str().unwrap()), "names the file: {err}");
        assert!(!out.exists(), "no output file after a failure");
    }
    // too many levels for memory: refused before allocating, with the predicted size
    let err = run_fail(&["subdivide", model_path("torus.obj").to_str().unwrap(), o, "--levels", "14"]);
    assert!(err.contains("would need about"), "{err}");
    let err =
        run_fail(&["subdivide", model_path("torus.obj").to_str().unwrap(), o, "--levels", "3", "--max-memory", "1M"]);
    assert!(err.contains("level 1") || err.contains("level 2") || err.contains("level 3"), "{err}");
    assert!(!out.exists());
    // an existing output is never truncated by a failure
    std::fs::write(&out, "keep me").unwrap();
    run_fail(&["subdivide", model_path("torus.obj").to_str().unwrap(), o, "--levels", "14"]);
    run_fail(&["subdivide", model_path("cube.obj").to_str().unwrap(), tmp("x.unknown").to_str().unwrap()]);
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "keep me");
    let _ = std::fs::remove_file(&out);
    assert!(!Path::new(&tmp("x.unknown")).exists());
}

const FIN_OBJ: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n";
const BOWTIE_OBJ: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 2 1 0\nv 2 2 0\nf 1 2 3\nf 3 4 5\n";

#[test]
fn non_manifold_models_are_refused_analysed_and_repaired() {
    // `subdivide` refuses them; `info` analyses them instead of failing and
    // lists the offending elements; `--repair` makes them subdivide. The
    // inputs are written here; the shared corpus's copies are checked too
    // when it is present, never instead.
    let mut cases = vec![
        (write("gen-fin.obj", FIN_OBJ), "non-manifold edge", "non-manifold edges:    1-2"),
        (write("gen-bowtie.obj", BOWTIE_OBJ), "non-manifold vertex", "non-manifold vertices: 3"),
    ];
    let shared = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/models/procedural");
    for (f, want, listed) in [
        ("fin_nonmanifold.obj", "non-manifold edge", "non-manifold edges:    1-2"),
        ("bowtie_nonmanifold.obj", "non-manifold vertex", "non-manifold vertices: 1"),
    ] {
        if shared.join(f).exists() {
            cases.push((shared.join(f), want, listed));
        }
    }
    for (p, want, listed) in cases {
        let f = p.file_name().unwrap().to_str().unwrap().to_string();
        let out = tmp(&format!("repaired-{f}"));
        let err = run_fail(&["subdivide", p.to_str().unwrap(), out.to_str().unwrap()]);
        assert!(err.contains(want) && err.contains(&f), "{err}");
        let o = bin().args(["info", p.to_str().unwrap()]).output().unwrap();
        let s = String::from_utf8_lossy(&o.stdout);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert!(s.contains("manifold:        no") && s.contains(listed), "{f}: {s}");
        let o = bin().args(["subdivide", "--repair", p.to_str().unwrap(), out.to_str().unwrap()]).output().unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert!(String::from_utf8_lossy(&o.stderr).contains("repair:"));
        let m = subdiv::bundled::load(&out).expect("the repaired, subdivided output is valid");
        assert!(m.ct.num_triangles() >= 8, "{f}: {} triangles", m.ct.num_triangles());
    }
}

#[test]
fn repair_command_and_flags() {
    let fin = write("rfin.obj", FIN_OBJ);
    let bow = write("rbow.obj", BOWTIE_OBJ);
    // repair IN OUT: report on stdout, a valid mesh written
    let out = tmp("rfin-fixed.obj");
    let o = bin().args(["repair", fin.to_str().unwrap(), out.to_str().unwrap()]).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let s = String::from_utf8_lossy(&o.stdout);
    assert!(s.contains("non-manifold edges cut:         1 (1-2)"), "{s}");
    let m = subdiv::bundled::load(&out).unwrap();
    assert_eq!((m.ct.num_triangles(), m.positions.len(), m.ct.num_border_edges()), (3, 9, 9));
    // info lists the bowtie vertex (1-based) instead of failing
    let o = bin().args(["info", bow.to_str().unwrap()]).output().unwrap();
    let s = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success() && s.contains("non-manifold vertices: 3"), "{s}");
    let o = bin().args(["info", "--json", bow.to_str().unwrap()]).output().unwrap();
    let s = String::from_utf8_lossy(&o.stdout);
    assert!(s.contains("\"non_manifold_vertices\":1") && s.contains("\"repaired\":true"), "{s}");
    // a valid mesh: info --repair finds nothing to repair
    let o = bin().args(["info", "--repair", model_path("cube.obj").to_str().unwrap()]).output().unwrap();
    assert!(String::from_utf8_lossy(&o.stdout).contains("nothing to repair"));
    // subdivide --repair: stdout stays the JSON summary, the report goes to stderr
    let out = tmp("rbow-sub.obj");
    let o = bin()
        .args(["subdivide", "--repair", "--json", bow.to_str().unwrap(), out.to_str().unwrap(), "-n", "2"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stdout).contains("\"faces\":32"));
    assert!(String::from_utf8_lossy(&o.stderr).contains("vertices split:                 1 (3)"));
    // parse errors stay errors with the line, even with --repair
    let nan = write("rnan.obj", "v 0 0 0\nv nan 1 0\nv 0 1 0\nf 1 2 3\n");
    let err = run_fail(&["repair", nan.to_str().unwrap(), out.to_str().unwrap()]);
    assert!(err.contains("rnan.obj:2:"), "{err}");
}

#[test]
fn smooth_and_limit_keep_the_topology() {
    let input = model_path("torus.obj");
    let before = subdiv::bundled::load(&input).unwrap();
    for (cmd, extra) in [("smooth", vec!["-n", "3"]), ("limit", vec![])] {
        let out = tmp(&format!("torus-{cmd}.obj"));
        let mut args = vec![cmd, input.to_str().unwrap(), out.to_str().unwrap()];
        args.extend(extra);
        let o = bin().args(&args).output().unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let after = subdiv::bundled::load(&out).unwrap();
        assert_eq!(after.ct.v_table(), before.ct.v_table());
        assert!(
            after.positions.iter().zip(&before.positions).any(|(a, b)| (*a - *b).length() > 1e-4),
            "{cmd} moved nothing"
        );
    }
    let err = run_fail(&["smooth", input.to_str().unwrap(), tmp("x.obj").to_str().unwrap(), "--mu", "0.5"]);
    assert!(err.contains("mu < -lambda"), "{err}");
}

#[test]
fn crease_options_tag_subdivide_and_count() {
    // --crease-angle makes the cube's 12 edges sharp: the output keeps them
    // as tags and every point on the cube's faces
    let out = tmp("cube_sharp.obj");
    let o = bin()
        .args(["subdivide", "bundled:cube.obj", out.to_str().unwrap(), "--levels", "2", "--crease-angle", "40"])
        .args(["--scheme", "loop", "--boundary", "edge-and-corner", "--creasing", "chaikin"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(&out).unwrap();
    assert_eq!(text.lines().filter(|l| l.starts_with("t crease 2/1/0 ")).count(), 12 * 4, "each edge in 4 pieces");
    let back = subdiv::bundled::load(&out).unwrap();
    for q in &back.positions {
        let on_face = (0..3).any(|k| q[k].abs() < 1e-5 || (q[k] - 1.0).abs() < 1e-5);
        assert!(on_face, "{q} is inside the cube");
    }
    let info = bin().args(["info", "bundled:cube.obj", "--crease-angle", "40"]).output().unwrap();
    let info = String::from_utf8_lossy(&info.stdout).to_string();
    assert!(info.contains("12 sharp edges (12 infinitely sharp)") && info.contains("8 corners"), "{info}");
    let o = bin()
        .args(["subdivide", "bundled:cube.obj", out.to_str().unwrap(), "--boundary", "sideways"])
        .output()
        .unwrap();
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && e.contains("sideways") && e.contains("edge-and-corner"), "{e}");
    let e = clap_refuses(&["subdivide", "bundled:cube.obj", out.to_str().unwrap(), "--crease-angle", "400"]);
    assert!(e.contains("--crease-angle"), "{e}");
}

/// Runs a command line that clap must refuse (exit status 2, a usage error,
/// no panic); its stderr.
fn clap_refuses(args: &[&str]) -> String {
    let out = bin().args(args).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(out.status.code(), Some(2), "a usage error expected for {args:?}: {err}");
    assert!(err.starts_with("error: ") && !err.contains("panicked"), "{args:?}: {err}");
    err
}

#[test]
fn crease_angles_outside_0_to_180_are_refused_by_every_command() {
    let out = tmp("angle.obj");
    let o = out.to_str().unwrap();
    for deg in ["-1", "180.5", "400", "nan", "inf"] {
        let e = clap_refuses(&["subdivide", "bundled:cube.obj", o, "--crease-angle", deg]);
        assert!(e.contains(&format!("'{deg}' is not an angle from 0 to 180 degrees")), "{deg}: {e}");
        assert!(!out.exists());
        // view too: refused before a model is read or a window opened
        let e = clap_refuses(&["view", "bundled:cube.obj", "--frames", "1", "--crease-angle", deg]);
        assert!(e.contains("not an angle from 0 to 180"), "view {deg}: {e}");
        let e = clap_refuses(&["info", "bundled:cube.obj", "--crease-angle", deg]);
        assert!(e.contains("not an angle from 0 to 180"), "info {deg}: {e}");
    }
    // the ends of the range are angles
    for deg in ["0", "180"] {
        let r = bin().args(["subdivide", "bundled:cube.obj", o, "--crease-angle", deg]).output().unwrap();
        assert!(r.status.success(), "{deg}: {}", String::from_utf8_lossy(&r.stderr));
    }
}

#[test]
fn options_that_would_change_nothing_are_refused() {
    // info counts the control mesh's features and refines nothing: how
    // semi-sharp creases decay per level, the scheme and the levels have a
    // meaning only for --stencil
    for opt in [&["--creasing", "chaikin"][..], &["--levels", "2"], &["-s", "catmull-clark"], &["--warren"]] {
        let args: Vec<&str> = ["info", "bundled:cube.obj"].iter().chain(opt).copied().collect();
        let e = run_fail(&args);
        assert!(e.contains(opt[0]) && e.contains("applies to --stencil"), "{e}");
        let with: Vec<&str> = args.iter().copied().chain(["--stencil", "0"]).collect();
        let o = bin().args(&with).output().unwrap();
        assert!(o.status.success(), "{with:?}: {}", String::from_utf8_lossy(&o.stderr));
    }
    let o = bin().args(["info", "bundled:cube.obj", "--boundary", "edge-and-corner"]).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // repair always repairs
    let fin = write("noop-fin.obj", FIN_OBJ);
    let out = tmp("noop-fixed.obj");
    let e = clap_refuses(&["repair", "--repair", fin.to_str().unwrap(), out.to_str().unwrap()]);
    assert!(e.contains("unexpected argument '--repair'"), "{e}");
    assert!(!out.exists());
}

#[test]
fn every_mesh_command_takes_repair_and_levels_has_its_aliases() {
    let fin = write("opt-fin.obj", FIN_OBJ);
    let f = fin.to_str().unwrap();
    for cmd in ["subdivide", "smooth", "limit"] {
        let out = tmp(&format!("opt-{cmd}.obj"));
        let o = out.to_str().unwrap();
        let err = run_fail(&[cmd, f, o]);
        assert!(err.contains("non-manifold edge"), "{cmd} without --repair: {err}");
        let r = bin().args([cmd, f, o, "--repair"]).output().unwrap();
        assert!(r.status.success(), "{cmd} --repair: {}", String::from_utf8_lossy(&r.stderr));
        assert!(String::from_utf8_lossy(&r.stderr).contains("repair:"), "{cmd}: the report on stderr");
        assert!(subdiv::bundled::load(&out).is_ok());
    }
    // --levels, --level, -n and -l are one option
    let faces = |args: &[&str]| -> u64 {
        let out = tmp("opt-levels.obj");
        let mut all = vec!["subdivide", "bundled:cube.obj", out.to_str().unwrap(), "--json"];
        all.extend_from_slice(args);
        let o = bin().args(&all).output().unwrap();
        assert!(o.status.success(), "{args:?}: {}", String::from_utf8_lossy(&o.stderr));
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        v["faces"].as_u64().unwrap()
    };
    assert_eq!(faces(&[]), 12 * 4, "subdivide's default is one level");
    for args in [["--levels", "2"], ["--level", "2"], ["-n", "2"], ["-l", "2"]] {
        assert_eq!(faces(&args), 12 * 16, "{args:?}");
    }
}

#[test]
fn json_output_is_valid_for_any_file_name() {
    // a quote, a backslash, a control character and a newline in the name
    let name = "we\"ird\\\u{1}\n.obj";
    let input = tmp(name);
    std::fs::copy(model_path("cube.obj"), &input).unwrap();
    let o = bin().args(["info", "--json", input.to_str().unwrap()]).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("info --json is JSON");
    assert_eq!(v["file"].as_str().unwrap(), input.to_str().unwrap());
    let cube = subdiv::bundled::load(&model_path("cube.obj")).unwrap();
    let hist = subdiv::mesh::topology(&cube.ct).valence_histogram;
    assert_eq!(v["faces"].as_u64(), Some(12));
    for (k, &n) in hist.iter().enumerate().filter(|(_, n)| **n > 0) {
        assert_eq!(v["valence"][k.to_string()].as_u64(), Some(n as u64), "valence {k}");
    }
    let out = tmp("json-out\u{7}.ply");
    let o = bin().args(["subdivide", "--json", input.to_str().unwrap(), out.to_str().unwrap()]).output().unwrap();
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("subdivide --json is JSON");
    assert_eq!(v["output"].as_str().unwrap(), out.to_str().unwrap());
    assert_eq!(v["faces"].as_u64(), Some(48));
    let o = bin().args(["info", "--json", "bundled:curve.bzc"]).output().unwrap();
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("curve info --json is JSON");
    assert_eq!(v["kind"], "bezier_curve");
}

#[test]
fn completions_for_each_shell_name_the_commands_and_options() {
    for shell in ["bash", "zsh", "fish"] {
        let o = bin().args(["completions", shell]).output().unwrap();
        assert!(o.status.success(), "{shell}: {}", String::from_utf8_lossy(&o.stderr));
        let s = String::from_utf8_lossy(&o.stdout);
        for word in ["subdivide", "render", "completions", "levels", "crease-angle", "repair"] {
            assert!(s.contains(word), "{shell} completion lacks {word}");
        }
    }
    let o = bin().args(["completions", "tcsh"]).output().unwrap();
    assert!(!o.status.success());
}

#[test]
fn quiet_and_verbose_set_what_stderr_shows() {
    let fin = write("q-fin.obj", FIN_OBJ);
    let out = tmp("q-out.obj");
    let args = ["subdivide", "--repair", fin.to_str().unwrap(), out.to_str().unwrap()];
    let stderr = |pre: &[&str]| {
        let o = bin().args(pre).args(args).env_remove("RUST_LOG").output().unwrap();
        assert!(o.status.success());
        String::from_utf8_lossy(&o.stderr).to_string()
    };
    let normal = stderr(&[]);
    assert!(normal.contains("repair:") && !normal.contains("subdiv: info:"), "{normal}");
    let quiet = stderr(&["-q"]);
    assert!(quiet.is_empty(), "-q: {quiet}");
    let verbose = stderr(&["-v"]);
    assert!(verbose.contains("subdiv: info: [subdiv::bundled] read ") && verbose.contains("9 vertices"), "{verbose}");
    // errors are printed whatever the level
    let o = bin().args(["-q", "subdivide", "/nonexistent.obj", out.to_str().unwrap()]).output().unwrap();
    assert!(String::from_utf8_lossy(&o.stderr).contains("No such file"));
}

#[test]
fn animate_stats_times_every_frame_without_writing() {
    let o = bin().args(["animate", "--level", "3", "--refine", "2", "--stats"]).output().unwrap();
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{out} {}", String::from_utf8_lossy(&o.stderr));
    let field = |k: &str| -> f64 {
        let v = out.split_whitespace().find_map(|w| w.strip_prefix(k)).unwrap_or_else(|| panic!("{k} in {out}"));
        v.parse().unwrap()
    };
    assert!(field("plan_ms=") > 0.0 && field("frame_ms=") > 0.0, "{out}");
    // the bundled tetrahedron: 4 keys x 2^2 frames, 4 x 4^3 triangles, at least 32 evaluations
    assert_eq!((field("frames=") as u32, field("triangles=") as u32, field("evaluations=") as u32), (16, 256, 32));
    // without --stats an output is still required
    assert!(!bin().args(["animate", "--level", "1"]).output().unwrap().status.success());
}

/// `limit --scheme catmull-clark` keeps the polygons and moves every vertex
/// to OpenSubdiv's limit (faces of 3 to 6: through one level, whose first
/// vertices are the control's); a scheme without limit masks is refused.
#[test]
fn limit_on_catmull_clark_keeps_polygons_and_gives_opensubdivs_limit() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/catmark");
    let input = dir.join("ngons.obj");
    let out = tmp("ngons-limit.obj");
    let o = bin().args(["limit", input.to_str().unwrap(), out.to_str().unwrap(), "-s", "catmark"]).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(&out).unwrap();
    let sizes: Vec<usize> =
        text.lines().filter(|l| l.starts_with("f ")).map(|l| l.split_whitespace().count() - 1).collect();
    assert!(sizes.contains(&6) && sizes.contains(&5) && sizes.contains(&3), "polygons kept: {sizes:?}");
    let after = subdiv::bundled::load(&out).unwrap();
    let osd: Vec<glam::Vec3> = std::fs::read_to_string(dir.join("ngons.limit.uniform.L1.osd.txt"))
        .unwrap()
        .lines()
        .filter_map(|l| l.strip_prefix("l "))
        .map(|l| {
            let x: Vec<f32> = l.split_whitespace().map(|t| t.parse().unwrap()).collect();
            glam::Vec3::new(x[3], x[4], x[5])
        })
        .collect();
    for (v, p) in after.positions.iter().enumerate() {
        assert!(p.distance(osd[v]) < 1e-5, "vertex {v}: {p} against {}", osd[v]);
    }
    let err = run_fail(&["limit", input.to_str().unwrap(), out.to_str().unwrap(), "-s", "butterfly"]);
    assert!(err.contains("butterfly"), "{err}");
}

#[test]
fn eval_writes_one_line_per_point_and_refuses_bad_points_by_line() {
    // a point past the tetrahedron's 4 faces is refused by its line
    let points = write("eval-points.txt", "# f u v\n0 0 0\n3 0.5 0.5\n7 0.2 0.3\n");
    let out = tmp("eval-out.txt");
    let model = "bundled:tetrahedron.obj";
    let ok = bin().args(["eval", model, points.to_str().unwrap(), out.to_str().unwrap()]).output().unwrap();
    assert!(!ok.status.success(), "the tetrahedron has 4 faces: face 7 is refused");
    let err = String::from_utf8_lossy(&ok.stderr);
    assert!(err.contains("eval-points.txt:4:") && err.contains("face 7 out of range"), "{err}");
    assert!(!out.exists(), "nothing written for a refused point");

    let points = write("eval-points.txt", "0 0 0\n3 0.5 0.5\n2 0.2 0.3\n");
    for (curv, columns) in [(false, 6), (true, 8)] {
        let mut args = vec!["eval", model, points.to_str().unwrap(), out.to_str().unwrap()];
        if curv {
            args.push("--curvature");
        }
        let r = bin().args(&args).output().unwrap();
        assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
        let text = std::fs::read_to_string(&out).unwrap();
        let rows: Vec<Vec<f64>> =
            text.lines().map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect()).collect();
        assert_eq!(rows.len(), 3);
        for row in &rows {
            assert_eq!(row.len(), columns, "{row:?}");
            let n = (row[3] * row[3] + row[4] * row[4] + row[5] * row[5]).sqrt();
            assert!((n - 1.0).abs() < 1e-12, "unit normals");
        }
        // the limit of a corner is the vertex's limit position (2/5 v + 1/5 ring at valence 3)
        let mesh = bundled("tetrahedron.obj");
        let lim = subdiv::eval::loop_limit_positions(&mesh)[mesh.ct.vtx(0) as usize];
        assert!((rows[0][0] - f64::from(lim.x)).abs() < 1e-6 && (rows[0][1] - f64::from(lim.y)).abs() < 1e-6);
        if curv {
            // at an extraordinary vertex the curvature is undefined; elsewhere H > 0 (convex, outward)
            assert!(rows[0][6].is_nan() && rows[2][6] > 0.0 && rows[2][7] > 0.0, "{rows:?}");
        }
    }
    for (text, line, what) in [
        ("0 0.1 0.1\n0 -0.2 0.1\n", 2, "u = -0.2"),
        ("0 0.7 0.7\n", 1, "outside the triangle"),
        ("0 nan 0.1\n", 1, "u = NaN"),
        ("x 0.1 0.1\n", 1, "not a non-negative integer"),
    ] {
        let p = write("eval-bad.txt", text);
        let err = run_fail(&["eval", model, p.to_str().unwrap(), out.to_str().unwrap()]);
        assert!(err.contains(&format!("eval-bad.txt:{line}:")) && err.contains(what), "{text:?}: {err}");
    }
    let err = run_fail(&["eval", model, points.to_str().unwrap(), out.to_str().unwrap(), "-s", "butterfly"]);
    assert!(err.contains("butterfly"), "{err}");
}

#[test]
fn eval_takes_catmull_clark_ptex_faces_in_the_unit_square() {
    let dir = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/catmark");
    let model = dir.join("ngons.obj");
    let mesh = subdiv::mesh::PolyMesh::from_mesh(&subdiv::bundled::load(&model).unwrap());
    let ptex = subdiv::eval::ptex_faces(&mesh.pt).len();
    assert!(ptex > mesh.pt.num_faces(), "the n-gons have a ptex face per corner");
    let out = tmp("eval-cc-out.txt");
    // (0.7, 0.7) is outside a triangle but inside a square
    let points = write("eval-cc.txt", &format!("0 0.7 0.7\n{} 1 1\n", ptex - 1));
    let args =
        ["eval", model.to_str().unwrap(), points.to_str().unwrap(), out.to_str().unwrap(), "-s", "catmull-clark"];
    let r = bin().args(args).output().unwrap();
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let text = std::fs::read_to_string(&out).unwrap();
    assert_eq!(text.lines().count(), 2);
    // ptex face `ptex` is one past the last; (1.2, 0) is outside the square
    for (text, what) in
        [(format!("{ptex} 0.5 0.5\n"), "out of range"), ("0 1.2 0\n".to_string(), "outside the unit square")]
    {
        let p = write("eval-cc-bad.txt", &text);
        let err = run_fail(&[
            "eval",
            model.to_str().unwrap(),
            p.to_str().unwrap(),
            out.to_str().unwrap(),
            "-s",
            "catmull-clark",
        ]);
        assert!(err.contains("eval-cc-bad.txt:1:") && err.contains(what), "{text:?}: {err}");
    }
    let err =
        run_fail(&["eval", model.to_str().unwrap(), points.to_str().unwrap(), out.to_str().unwrap(), "-s", "bilinear"]);
    assert!(err.contains("bilinear"), "{err}");
}

#[cfg(feature = "viewer")]
#[test]
fn isolines_take_a_count_from_1_to_50_on_a_curvature_colouring_only() {
    let m = model_path("torus.obj");
    let out = tmp("iso.png");
    let (m, o) = (m.to_str().unwrap(), out.to_str().unwrap());
    for bad in ["0", "-3", "ten", "2.5", "51", ""] {
        let err = run_fail(&["render", m, o, "--color", "mean-curvature", "--isolines", bad]);
        assert!(err.contains("--isolines") && err.contains("1 to 50"), "{bad}: {err}");
    }
    let err = run_fail(&["render", m, o, "--color", "shells", "--isolines", "4"]);
    assert!(err.contains("curvature"), "{err}");
    let err = run_fail(&["view", m, "--isolines", "4"]);
    assert!(err.contains("curvature"), "{err}");
    assert!(!out.exists(), "nothing is written on a refusal");
    let help = bin().args(["render", "--help"]).output().unwrap();
    assert!(String::from_utf8_lossy(&help.stdout).contains("--isolines <N>"));
}

/// The help text of `option` in `subdiv CMD --help` (on the option's line,
/// or the paragraph under it in the long form).
fn option_help(cmd: &str, option: &str) -> String {
    let o = bin().args([cmd, "--help"]).output().unwrap();
    let help = String::from_utf8(o.stdout).unwrap();
    let mut lines = help.lines().skip_while(|l| !l.trim_start().starts_with(option));
    let first = lines.next().unwrap_or_else(|| panic!("{cmd} --help has no {option}:\n{help}"));
    let rest = first.trim_start()[option.len()..].trim();
    if !rest.is_empty() {
        return rest.to_string();
    }
    lines.take_while(|l| !l.trim().is_empty()).collect::<Vec<_>>().join(" ")
}

/// The single-word values a help text lists: its items (split at commas,
/// colons, semicolons, full stops and "or") once the parenthesised remarks
/// and clap's `[default: ...]` are dropped.
fn listed_values(help: &str) -> Vec<String> {
    let mut bare = String::new();
    let mut depth = 0;
    for c in help.chars() {
        match c {
            '(' | '[' => depth += 1,
            ')' | ']' => depth -= 1,
            _ if depth == 0 => bare.push(c),
            _ => {}
        }
    }
    bare.split([',', ':', ';', '.'])
        .flat_map(|item| item.split(" or "))
        .map(str::trim)
        .filter(|w| !w.is_empty() && w.chars().all(|c| c.is_ascii_lowercase() || c == '-'))
        .map(str::to_string)
        .collect()
}

#[cfg(feature = "viewer")]
#[test]
fn the_help_of_color_lists_every_colouring_it_takes() {
    use subdiv::render::Coloring;
    for cmd in ["render", "view"] {
        let help = option_help(cmd, "--color <COLOR>");
        let values = listed_values(&help);
        assert!(values.iter().any(|v| v == "auto"), "{cmd}: {help}");
        let mut named = Vec::new();
        for v in values.iter().filter(|v| *v != "auto") {
            let c: Coloring = v.parse().unwrap_or_else(|e| panic!("{cmd} --color lists {v}: {e}"));
            named.push(c);
        }
        for c in Coloring::ALL {
            assert!(named.contains(&c), "{cmd} --help leaves out the colouring {c:?} ({}): {help}", c.name());
        }
        for curvature in ["mean-curvature", "gaussian-curvature", "min-curvature", "max-curvature"] {
            assert!(values.iter().any(|v| v == curvature), "{cmd}: {help}");
        }
    }
}

#[test]
fn the_help_of_scheme_and_limit_lists_every_name() {
    for cmd in ["view", "subdivide", "render", "animate", "eval"] {
        let values = listed_values(&option_help(cmd, "-s, --scheme <SCHEME>"));
        // eval takes the schemes with an exact evaluation, and names no other
        let taken =
            |s: subdiv::Scheme| cmd != "eval" || matches!(s, subdiv::Scheme::Loop | subdiv::Scheme::CatmullClark);
        for s in subdiv::Scheme::ALL {
            let listed = values.iter().any(|v| v == s.name());
            assert_eq!(listed, taken(s), "{cmd} --scheme and {s}: {values:?}");
        }
        for v in &values {
            assert!(v.parse::<subdiv::Scheme>().is_ok(), "{cmd} --scheme lists {v}");
        }
    }
    let values = listed_values(&option_help("info", "--limit <NAME=VALUE>"));
    for (name, _) in subdiv::io::LIMIT_NAMES {
        assert!(values.iter().any(|v| v == name), "--limit leaves out {name}: {values:?}");
    }
}

/// The faces, distinct undirected edges and valence histogram (vertex
/// count by number of edges) of the OBJ text `obj`, read here directly.
fn obj_polygon_counts(obj: &str) -> (usize, usize, std::collections::BTreeMap<usize, usize>) {
    use std::collections::{BTreeMap, BTreeSet};
    let mut faces = 0;
    let mut edges = BTreeSet::new();
    for line in obj.lines() {
        let Some(rest) = line.strip_prefix("f ") else { continue };
        faces += 1;
        let ids: Vec<u32> = rest.split_whitespace().map(|t| t.split('/').next().unwrap().parse().unwrap()).collect();
        for (k, &a) in ids.iter().enumerate() {
            let b = ids[(k + 1) % ids.len()];
            edges.insert((a.min(b), a.max(b)));
        }
    }
    let mut degree: BTreeMap<u32, usize> = BTreeMap::new();
    for &(a, b) in &edges {
        *degree.entry(a).or_default() += 1;
        *degree.entry(b).or_default() += 1;
    }
    let mut valence = BTreeMap::new();
    for &d in degree.values() {
        *valence.entry(d).or_insert(0) += 1;
    }
    (faces, edges.len(), valence)
}

#[test]
fn info_counts_the_files_own_polygons_first() {
    let obj = std::fs::read_to_string(model_path("critter.obj")).unwrap();
    let (faces, edges, valence) = obj_polygon_counts(&obj);
    assert_eq!(faces, 172, "the critter is 172 quads");
    assert!(obj.lines().filter(|l| l.starts_with("f ")).all(|l| l.split_whitespace().count() == 5), "all quads");
    let o = bin().args(["info", "bundled:critter.obj"]).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let s = String::from_utf8(o.stdout).unwrap();
    let hist: Vec<String> = valence.iter().map(|(k, c)| format!("{k}:{c}")).collect();
    assert!(s.contains(&format!("\nedges:           {edges}\n")), "{s}");
    assert!(s.contains("\nfaces:           172 (by corners 4:172"), "{s}");
    assert!(s.contains(&format!("\nvalence:         {}\n", hist.join(" "))), "{s}");
    // the fan's edges (a diagonal more per quad) are not what info gives
    assert!(!s.contains(&(edges + faces).to_string()), "{s}");
    // --json: the file's own counts on top, the fan's under `triangulated`
    let o = bin().args(["info", "--json", "bundled:critter.obj"]).output().unwrap();
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("info --json is JSON");
    assert_eq!((v["faces"].as_u64(), v["edges"].as_u64()), (Some(172), Some(edges as u64)), "{v}");
    for (k, &n) in &valence {
        assert_eq!(v["valence"][k.to_string()].as_u64(), Some(n as u64), "valence {k}: {v}");
    }
    assert_eq!(v["valence"].as_object().unwrap().len(), valence.len(), "{v}");
    let t = &v["triangulated"];
    assert_eq!((t["faces"].as_u64(), t["edges"].as_u64()), (Some(344), Some((edges + faces) as u64)), "{v}");
    // a file of triangles has no `triangulated`, and its counts are its own
    let o = bin().args(["info", "--json", "bundled:torus.obj"]).output().unwrap();
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(v.get("triangulated").is_none() && v["faces"].as_u64() == Some(1024), "{v}");
    // one-face corners are the polygons': a 3x4 quad grid has four
    let grid = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/catmark/grid.obj");
    let o = bin().args(["info", grid.to_str().unwrap(), "--boundary", "edge-and-corner"]).output().unwrap();
    let s = String::from_utf8(o.stdout).unwrap();
    assert!(s.contains("4 sharp vertices; 4 corners"), "{s}");
}

#[test]
fn info_prints_the_corner_operators_and_a_stencil_as_json() {
    let json = |args: &[&str]| -> serde_json::Value {
        let o = bin().args(args).output().unwrap();
        assert!(o.status.success(), "{args:?}: {}", String::from_utf8_lossy(&o.stderr));
        serde_json::from_slice(&o.stdout).unwrap()
    };
    // a triangle file: corner c is corner c % 3 of the file's triangle c / 3
    let obj = write("corner-open.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n");
    let f = obj.to_str().unwrap();
    let v = json(&["info", f, "--corner", "4", "--json"]);
    let keys = ["corner", "triangle", "vertex", "n", "p", "o", "l", "r", "s", "u"];
    assert_eq!(v.as_object().unwrap().keys().collect::<Vec<_>>().len(), keys.len(), "{v}");
    for k in keys {
        assert!(v.get(k).is_some(), "{k} missing: {v}");
    }
    // triangle 1 is (1, 3, 4) in the file: corner 4 is its second, vertex 3 (0-based 2)
    assert_eq!((v["triangle"].as_u64(), v["vertex"].as_u64()), (Some(1), Some(2)), "{v}");
    assert_eq!((v["n"].as_u64(), v["p"].as_u64()), (Some(5), Some(3)), "{v}");
    // corner 4 faces the border edge (4, 1): o is null; its n faces the diagonal
    assert!(v["o"].is_null() && v["r"].is_null(), "{v}");
    assert_eq!(v["l"].as_u64(), Some(1), "{v}");
    let text = bin().args(["info", f, "--corner", "4"]).output().unwrap();
    assert!(String::from_utf8_lossy(&text.stdout).contains("s = n(o(n))"));
    let e = run_fail(&["info", f, "--corner", "6"]);
    assert!(e.contains("corner 6 out of range") && e.contains("6 corners"), "{e}");
    // a file of polygons: the polygon table's operators, the file's corners
    let v = json(&["info", "bundled:critter.obj", "--corner", "5", "--json"]);
    assert_eq!((v["face"].as_u64(), v["next"].as_u64(), v["prev"].as_u64()), (Some(1), Some(6), Some(4)), "{v}");
    // a stencil: weights summing to one, the rules by level
    let v = json(&["info", "bundled:cube.obj", "--stencil", "30", "--levels", "2", "--json"]);
    assert_eq!((v["vertex"].as_u64(), v["level"].as_u64(), v["scheme"].as_str()), (Some(30), Some(2), Some("loop")));
    let total: f64 = v["weights"].as_array().unwrap().iter().map(|p| p[1].as_f64().unwrap()).sum();
    assert!((total - 1.0).abs() < 1e-12, "{v}");
    assert_eq!(v["position"].as_array().unwrap().len(), 3);
    assert_eq!(v["rules"][0]["level"].as_u64(), Some(2), "{v}");
    let v = json(&["info", "bundled:critter.obj", "--stencil", "0", "-n", "1", "-s", "catmull-clark", "--json"]);
    assert!(v["rules"][1]["rule"].as_str().unwrap().contains("vertex point"), "{v}");
}

#[test]
fn edit_moves_vertices_and_tags_edges_in_a_script() {
    let quad = write(
        "edit-in.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 2 0\nvt 2 1\n\
         f 1/1 2/2 3/3 4/4\nf 2/2 5/5 6/6 3/3\n",
    );
    let out = tmp("edit-out.obj");
    let status = bin()
        .args(["edit", quad.to_str().unwrap(), out.to_str().unwrap(), "--move", "0=0,0,1", "--offset", "4=0,0,-0.5"])
        .args(["--crease", "1,2=2.5", "--corner", "5=10"])
        .status()
        .unwrap();
    assert!(status.success());
    let text = std::fs::read_to_string(&out).unwrap();
    let edited = subdiv::bundled::load(&out).unwrap();
    assert_eq!(edited.positions[0], glam::Vec3::new(0.0, 0.0, 1.0));
    assert_eq!(edited.positions[4], glam::Vec3::new(2.0, 0.0, -0.5));
    assert_eq!(text.lines().filter(|l| l.starts_with("f ")).count(), 2, "still two quads:\n{text}");
    assert!(text.contains("vt "), "texture coordinates kept:\n{text}");
    assert!(text.contains("t crease 2/1/0 1 2 2.5") && text.contains("t corner 1/1/0 5 10"), "{text}");
    // the refined level of the edited cage equals subdividing the edited file
    let fine = tmp("edit-fine.obj");
    let args =
        ["edit", quad.to_str().unwrap(), fine.to_str().unwrap(), "-n", "2", "-s", "catmull-clark", "--move", "0=0,0,1"];
    assert!(bin().args(args).status().unwrap().success());
    let moved = write("edit-moved.obj", "v 0 0 1\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\nf 1 2 3 4\nf 2 5 6 3\n");
    let reference = tmp("edit-reference.obj");
    let args = ["subdivide", moved.to_str().unwrap(), reference.to_str().unwrap(), "-n", "2", "-s", "catmull-clark"];
    assert!(bin().args(args).status().unwrap().success());
    let (a, b) = (subdiv::bundled::load(&fine).unwrap(), subdiv::bundled::load(&reference).unwrap());
    assert_eq!(a.positions.len(), b.positions.len());
    let d = a.positions.iter().zip(&b.positions).map(|(p, q)| p.distance(*q)).fold(0.0, f32::max);
    assert!(d < 1e-5, "{d}");
    // refused in one line each
    let bad = run_fail(&["edit", quad.to_str().unwrap(), out.to_str().unwrap(), "--move", "9=0,0,0"]);
    assert!(bad.contains("vertex 9 is not a control vertex"), "{bad}");
    let bad = run_fail(&["edit", quad.to_str().unwrap(), out.to_str().unwrap(), "--crease", "0,2=1"]);
    assert!(bad.contains("0-2 is a diagonal of a polygon"), "{bad}");
    let bad = run_fail(&["edit", quad.to_str().unwrap(), out.to_str().unwrap(), "--crease", "0,5=1"]);
    assert!(bad.contains("no edge (0, 5)"), "{bad}");
    // clap's own refusal of a malformed value (with its usual hint line)
    let bad =
        bin().args(["edit", quad.to_str().unwrap(), out.to_str().unwrap(), "--move", "1=nan,0,0"]).output().unwrap();
    assert!(!bad.status.success() && String::from_utf8_lossy(&bad.stderr).contains("three finite numbers"));
}
