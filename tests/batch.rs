//! `subdiv batch`: a folder of good, huge and hostile files gives each good
//! output byte for byte as `subdiv subdivide` gives it, names every failure
//! in the manifest and the exit code, keeps the files in flight within
//! `--max-memory`, survives `kill -9` with whole files and whole lines, and
//! resumes without redoing what is done.
#![cfg(feature = "cli")]

mod common;
use common::*;
use glam::Vec3;
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_subdiv"))
}

fn run(args: &[&str]) -> Output {
    bin().args(args).output().expect("subdiv runs")
}

fn s(p: &Path) -> &str {
    p.to_str().expect("a UTF-8 path")
}

/// A fresh folder `name` in this run's scratch folder.
fn fresh(name: &str) -> PathBuf {
    let d = scratch_dir("batch").join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The manifest's lines by input; every line parses.
fn manifest(out: &Path) -> BTreeMap<String, Value> {
    let text = std::fs::read_to_string(out.join("manifest.jsonl")).expect("a manifest");
    let mut lines = BTreeMap::new();
    for l in text.lines() {
        let v: Value = serde_json::from_str(l).unwrap_or_else(|e| panic!("a line that does not parse ({e}): {l}"));
        let input = v["input"].as_str().expect("input").to_string();
        assert!(lines.insert(input.clone(), v).is_none(), "{input} has two lines");
    }
    lines
}

/// Every file under `dir` whose name says it is a temporary one.
fn temporaries(dir: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        let name = p.file_name().unwrap().to_string_lossy().into_owned();
        if p.is_dir() {
            found.extend(temporaries(&p));
        } else if name.starts_with(".subdiv-") || name.ends_with(".tmp") || name.ends_with(".new") {
            found.push(p);
        }
    }
    found
}

/// `subdiv subdivide input` with `args` into `dir`, named as `like`: its
/// bytes, or its one-line error.
fn serial(input: &Path, like: &Path, dir: &Path, args: &[&str]) -> Result<Vec<u8>, String> {
    let out = dir.join(like.file_name().unwrap());
    let o = bin().args(["subdivide", s(input), s(&out)]).args(args).output().unwrap();
    match o.status.success() {
        true => Ok(std::fs::read(&out).unwrap()),
        false => {
            let err = String::from_utf8_lossy(&o.stderr).trim().to_string();
            Err(err.strip_prefix("subdiv: error: ").unwrap_or(&err).to_string())
        }
    }
}

/// A wavy grid of `n x n` squares (2n^2 triangles).
fn wavy(n: usize) -> subdiv::Mesh {
    grid(n, n, |i, j| Vec3::new(i, j, (i * 0.37).sin() + (j * 0.21).cos()))
}

/// Good, huge and hostile files in one folder: the good ones refined as
/// `subdivide` refines each (same bytes, same counts), every failure named
/// with the library's message (the huge one with `subdivide`'s
/// `--max-memory` refusal), exit code 1, a summary in JSON, no temporary
/// file left.
#[test]
fn a_folder_of_good_huge_and_hostile_files() {
    let root = fresh("mixed");
    let (input, out, single) = (root.join("in"), root.join("out"), root.join("single"));
    std::fs::create_dir_all(input.join("sub")).unwrap();
    std::fs::create_dir_all(&single).unwrap();
    for name in ["torus.obj", "cube.ct", "critter.obj", "cube_uv.obj", "lprism.ct"] {
        std::fs::copy(model_path(name), input.join(name)).unwrap();
    }
    std::fs::copy(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/usd/two.usda"), input.join("two.usda"))
        .unwrap();
    subdiv::io::save(&input.join("sub/ico.ply"), &icosphere(2)).unwrap();
    subdiv::io::save(&input.join("sub/hemi.off"), &hemisphere()).unwrap();
    // huge: level 2 of 80 000 triangles does not fit in 24 MB
    subdiv::io::save(&input.join("huge.obj"), &wavy(200)).unwrap();
    // hostile
    let mut rng = 0x9e37_79b9_7f4a_7c15u64;
    let garbage: Vec<u8> = (0..4000)
        .map(|_| {
            rng ^= rng << 13;
            rng ^= rng >> 7;
            rng ^= rng << 17;
            rng as u8
        })
        .collect();
    std::fs::write(input.join("garbage.obj"), garbage).unwrap();
    let torus = std::fs::read(model_path("torus.obj")).unwrap();
    std::fs::write(input.join("truncated.obj"), &torus[..torus.len() / 2 + 7]).unwrap();
    std::fs::write(input.join("fin.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n")
        .unwrap();
    std::fs::create_dir_all(input.join("folder.obj")).unwrap();
    std::os::unix::fs::symlink(root.join("nowhere.obj"), input.join("gone.obj")).unwrap();
    let fifo = std::ffi::CString::new(s(&input.join("pipe.obj"))).unwrap();
    // SAFETY: a NUL-terminated path that lives across the call
    assert_eq!(unsafe { libc::mkfifo(fifo.as_ptr(), 0o644) }, 0, "mkfifo");
    std::fs::write(input.join("notes.txt"), "not a model").unwrap();

    let args = ["-n", "2", "--max-memory", "24M"];
    let o = bin()
        .args(["batch", s(&input), "bundled:teapot.bez", "--out", s(&out), "--threads", "2", "--json"])
        .args(args)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "some failed: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    let lines = manifest(&out);
    let failing = ["garbage.obj", "truncated.obj", "fin.obj", "folder.obj", "gone.obj", "pipe.obj", "huge.obj"];
    let good =
        ["torus.obj", "cube.ct", "critter.obj", "cube_uv.obj", "lprism.ct", "two.usda", "sub/ico.ply", "sub/hemi.off"];
    assert_eq!(lines.len(), failing.len() + good.len() + 1, "one line per model, notes.txt left out: {lines:#?}");
    for name in good {
        let path = input.join(name);
        let line = &lines[s(&path)];
        assert_eq!(line["status"], "done", "{name}: {line}");
        let output = PathBuf::from(line["output"].as_str().unwrap());
        assert_eq!(output, out.join(name), "{name}: its own format, at its path under --out");
        let expected = serial(&path, &output, &single, &args).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(std::fs::read(&output).unwrap() == expected, "{name}: not the bytes of subdivide");
        assert_eq!(line["output_bytes"], expected.len(), "{name}");
        let counts = subdiv::bundled::load(&output).unwrap();
        assert_eq!(line["vertices"], counts.positions.len(), "{name}");
        assert!(line["hash"].as_str().unwrap().starts_with("xxh3-128:"), "{name}");
        assert_eq!(
            line["options"],
            serde_json::json!({"levels": ["2"]}),
            "--max-memory is not an option of the output"
        );
    }
    for name in failing {
        let path = input.join(name);
        let line = &lines[s(&path)];
        assert_eq!(line["status"], "failed", "{name}: {line}");
        let error = line["error"].as_str().unwrap();
        let file = path.file_name().unwrap().to_str().unwrap();
        // the refusal of a level too big names the level (the line names the file)
        assert!(name == "huge.obj" || error.contains(file), "{name}: the error names the file: {error}");
        assert!(!out.join(name).exists(), "{name}: no output");
        // the library's message, as subdivide gives it
        let expected = serial(&path, &out.join(name), &single, &args).unwrap_err();
        assert_eq!(error, expected, "{name}");
    }
    assert!(lines[s(&input.join("huge.obj"))]["error"].as_str().unwrap().contains("memory"));
    let teapot = &lines["bundled:teapot.bez"];
    assert_eq!(teapot["status"], "failed");
    assert_eq!(teapot["output"], s(&out.join("teapot.obj")), "a format that is not written becomes OBJ");
    let summary: Value = serde_json::from_slice(&o.stdout).expect("--json");
    assert_eq!(summary["files"], lines.len());
    assert_eq!((summary["done"].as_u64(), summary["failed"].as_u64()), (Some(8), Some(8)));
    assert_eq!(summary["skipped"], 0);
    let faces: u64 = lines.values().filter_map(|l| l["faces"].as_u64()).sum();
    assert_eq!(summary["faces"], faces);
    assert!(summary["seconds"].as_f64().unwrap() > 0.0);
    assert_eq!(temporaries(&out), Vec::<PathBuf>::new());
}

/// A run killed with SIGKILL once its first file is in the manifest
/// leaves whole outputs, whole lines and no temporary file; the same
/// command again skips what was done (its outputs untouched), finishes the
/// rest as the serial runs do and exits 0; a torn last line is ignored.
#[test]
fn a_killed_run_leaves_whole_files_and_resumes() {
    use std::os::unix::process::ExitStatusExt;
    let root = fresh("killed");
    let (input, out, single) = (root.join("in"), root.join("out"), root.join("single"));
    std::fs::create_dir_all(&input).unwrap();
    std::fs::create_dir_all(&single).unwrap();
    let names: Vec<String> = (0..10).map(|k| format!("grid{k}.ply")).collect();
    for (k, name) in names.iter().enumerate() {
        let mesh = grid(120 + k, 120, |i, j| Vec3::new(i, j, ((i + j) * 0.1 + k as f32).sin()));
        subdiv::io::save(&input.join(name), &mesh).unwrap();
    }
    let args = ["-n", "2", "--threads", "2"];
    let command = |extra: &[&str]| {
        let mut c = bin();
        c.args(["batch", s(&input), "--out", s(&out), "-q"]).args(args).args(extra);
        c
    };
    let mut child = command(&[]).spawn().unwrap();
    // wait for the first finished file's line, then kill at once
    let deadline = Instant::now() + Duration::from_secs(120);
    loop {
        let text = std::fs::read_to_string(out.join("manifest.jsonl")).unwrap_or_default();
        if text.contains("\"status\":\"done\"") {
            break;
        }
        assert!(Instant::now() < deadline, "no file done in two minutes");
        assert!(child.try_wait().unwrap().is_none(), "the batch ended before its first line was seen");
        std::thread::sleep(Duration::from_millis(2));
    }
    child.kill().unwrap();
    let status = child.wait().unwrap();
    assert_eq!(status.signal(), Some(libc::SIGKILL), "killed midway, not finished: {status:?}");

    let text = std::fs::read_to_string(out.join("manifest.jsonl")).unwrap();
    let whole: Vec<&str> = text.split_inclusive('\n').filter(|l| l.ends_with('\n')).collect();
    let mut done_before = BTreeMap::new();
    for l in &whole {
        let v: Value = serde_json::from_str(l).unwrap_or_else(|e| panic!("a whole line parses ({e}): {l}"));
        assert_eq!(v["status"], "done", "{l}");
        done_before.insert(v["output"].as_str().unwrap().to_string(), ());
    }
    assert!(!done_before.is_empty() && done_before.len() < names.len(), "killed midway: {} done", done_before.len());
    assert_eq!(temporaries(&out), Vec::<PathBuf>::new(), "no temporary file after kill -9");
    let expected: BTreeMap<String, Vec<u8>> =
        names.iter().map(|n| (n.clone(), serial(&input.join(n), &out.join(n), &single, &args).unwrap())).collect();
    let mut mtimes = BTreeMap::new();
    for (name, bytes) in &expected {
        let output = out.join(name);
        if let Ok(got) = std::fs::read(&output) {
            assert!(got == *bytes, "{name}: an output after kill -9 is whole");
            mtimes.insert(name.clone(), std::fs::metadata(&output).unwrap().modified().unwrap());
        }
    }
    for done in done_before.keys() {
        assert!(mtimes.contains_key(Path::new(done).file_name().unwrap().to_str().unwrap()), "{done} is there");
    }

    let o = command(&[]).output().unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    let lines = manifest(&out);
    assert_eq!(lines.len(), names.len());
    for (name, bytes) in &expected {
        let line = &lines[s(&input.join(name))];
        let output = out.join(name);
        assert!(std::fs::read(&output).unwrap() == *bytes, "{name}: the serial output");
        if done_before.contains_key(s(&output)) {
            assert_eq!(line["status"], "skipped", "{name}: done before");
            assert_eq!(std::fs::metadata(&output).unwrap().modified().unwrap(), mtimes[name], "{name}: not rewritten");
        } else {
            assert_eq!(line["status"], "done", "{name}");
        }
    }
    assert_eq!(temporaries(&out), Vec::<PathBuf>::new());

    // a torn last line (a kill inside a write) is ignored; everything is skipped
    let mut torn = std::fs::read(out.join("manifest.jsonl")).unwrap();
    torn.extend_from_slice(b"{\"input\":\"half a li");
    std::fs::write(out.join("manifest.jsonl"), torn).unwrap();
    let o = command(&["--json"]).output().unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    let summary: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!((summary["skipped"].as_u64(), summary["done"].as_u64()), (Some(names.len() as u64), Some(0)));
    assert_eq!(manifest(&out).len(), names.len(), "the torn line is gone");
}

/// What a later run redoes: an input whose contents changed, an output
/// that is gone or not the size it was written with, and every file when
/// the options change.
#[test]
fn changed_inputs_outputs_and_options_are_done_again() {
    let root = fresh("changed");
    let (input, out) = (root.join("in"), root.join("out"));
    std::fs::create_dir_all(&input).unwrap();
    for name in ["torus.obj", "cube.obj", "lprism.obj", "tetrahedron.obj"] {
        std::fs::copy(model_path(name), input.join(name)).unwrap();
    }
    let batch = |args: &[&str]| {
        let o = bin().args(["batch", s(&input), "--out", s(&out), "-q"]).args(args).output().unwrap();
        assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
        let lines = manifest(&out);
        let status = |name: &str| lines[s(&input.join(name))]["status"].as_str().unwrap().to_string();
        ["torus.obj", "cube.obj", "lprism.obj", "tetrahedron.obj"].map(status)
    };
    assert_eq!(batch(&["-n", "2"]), ["done"; 4]);
    assert_eq!(batch(&["-n", "2"]), ["skipped"; 4]);
    // the same contents written again count as the same; other contents do not
    std::fs::copy(model_path("torus.obj"), input.join("torus.obj")).unwrap();
    let mut cube = std::fs::read_to_string(model_path("cube.obj")).unwrap();
    cube.push_str("# touched\n");
    std::fs::write(input.join("cube.obj"), cube).unwrap();
    std::fs::remove_file(out.join("lprism.obj")).unwrap();
    let tet = out.join("tetrahedron.obj");
    let mut bytes = std::fs::read(&tet).unwrap();
    bytes.truncate(bytes.len() - 5);
    std::fs::write(&tet, bytes).unwrap();
    assert_eq!(batch(&["-n", "2"]), ["skipped", "done", "done", "done"]);
    assert_eq!(batch(&["--levels", "1"]), ["done"; 4], "other options");
    assert_eq!(batch(&["--levels", "1", "--max-memory", "1G"]), ["skipped"; 4], "--max-memory changes no output");
}

/// With a budget that holds one file's refinement but not two, two
/// workers never refine two files at once (the manifest's admission and
/// finish times do not overlap), and every file is done.
#[test]
fn the_memory_budget_keeps_refinements_apart() {
    let root = fresh("budget");
    let (input, out) = (root.join("in"), root.join("out"));
    std::fs::create_dir_all(&input).unwrap();
    let mesh = wavy(60);
    let peak = subdiv::rules::ControlCounts::of(&mesh.ct).peak_bytes(subdiv::Scheme::Loop, 3, true);
    for k in 0..6 {
        subdiv::io::save(&input.join(format!("w{k}.ply")), &mesh).unwrap();
    }
    // one file's reservation (its peak and 16 MiB for the writer) fits, two do not
    let one = peak + (16 << 20);
    let budget = (2 * one - 1).to_string();
    let o = run(&["batch", s(&input), "--out", s(&out), "-n", "3", "--threads", "3", "--max-memory", &budget, "-q"]);
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    let mut spans: Vec<(f64, f64)> = manifest(&out)
        .values()
        .map(|l| {
            assert_eq!(l["status"], "done", "{l}");
            (l["admitted_at"].as_f64().unwrap(), l["finished_at"].as_f64().unwrap())
        })
        .collect();
    spans.sort_by(|a, b| a.0.total_cmp(&b.0));
    assert_eq!(spans.len(), 6);
    for w in spans.windows(2) {
        assert!(w[1].0 >= w[0].1, "two refinements at once: {spans:?}");
    }
}

/// Globs are matched by subdiv; bad arguments are usage errors (exit code
/// 2) in one line, before any file is written.
#[test]
fn globs_and_usage_errors() {
    let root = fresh("globs");
    let (input, out) = (root.join("in"), root.join("out"));
    std::fs::create_dir_all(&input).unwrap();
    for name in ["torus.obj", "cube.obj", "cube.ct"] {
        std::fs::copy(model_path(name), input.join(name)).unwrap();
    }
    let o = run(&["batch", &format!("{}/*.obj", s(&input)), "--out", s(&out), "-q"]);
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    let lines = manifest(&out);
    let inputs: Vec<&String> = lines.keys().collect();
    assert_eq!(inputs, [s(&input.join("cube.obj")), s(&input.join("torus.obj"))]);
    let fails = |args: &[&str], what: &str| {
        let o = run(args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(err.contains(what), "{args:?}: {err}");
    };
    let other = root.join("other");
    fails(&["batch", s(&input), "--out", s(&other), "--format", "ply"], "would both be written to");
    fails(&["batch", &format!("{}/*.stl", s(&input)), "--out", s(&other)], "matches no file");
    fails(&["batch", s(&input), "--out", s(&other), "--format", "xyz"], "--format xyz");
    assert!(!other.join("manifest.jsonl").exists(), "nothing written");
}
