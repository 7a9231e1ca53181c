//! The bundled models: every file in the repository's `models/` is compiled
//! into the binary, and an installed `subdiv`, run far from any checkout,
//! lists and opens every one of them from memory.

use std::path::{Path, PathBuf};
use subdiv::bundled::MODELS;

fn checkout() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn every_file_in_models_is_bundled_with_its_bytes() {
    let mut files: Vec<String> = std::fs::read_dir(checkout().join("models"))
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        // documentation and hidden files are not models
        .filter(|f| f != "README.md" && !f.starts_with('.'))
        .collect();
    files.sort();
    assert!(files.len() >= 10, "models/ has only {files:?}");
    for f in &files {
        let m =
            MODELS.iter().find(|m| m.file_name == f).unwrap_or_else(|| panic!("models/{f} is not in bundled::MODELS"));
        assert_eq!(m.bytes, std::fs::read(checkout().join("models").join(f)).unwrap(), "{f}: bundled bytes differ");
        assert!(!m.what.is_empty(), "{f}: no description");
    }
    for m in MODELS {
        assert!(files.iter().any(|f| f == m.file_name), "bundled {} is not in models/", m.file_name);
    }
}

#[test]
fn nothing_in_src_finds_files_through_the_build_machine() {
    // an installed binary has no checkout: the library and the binary must
    // not look for models/ or paths/ where the build ran
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() { walk(&p, out) } else { out.push(p) }
        }
    }
    let mut files = Vec::new();
    walk(&checkout().join("src"), &mut files);
    assert!(files.len() > 20);
    let needle = ["CARGO", "MANIFEST", "DIR"].join("_");
    for f in files {
        let text = std::fs::read_to_string(&f).unwrap_or_default();
        assert!(!text.contains(&needle), "{} uses {needle}", f.display());
    }
}

/// The installed binary (needs the `cli` feature).
#[cfg(feature = "cli")]
mod installed {
    use super::*;
    use std::process::{Command, Output};
    /// The built binary copied into a fresh directory, run from there.
    struct Installed {
        dir: PathBuf,
        exe: PathBuf,
    }

    impl Installed {
        fn new() -> Installed {
            let dir = std::env::temp_dir().join(format!("subdiv-installed-{}", std::process::id()));
            let _ = std::fs::remove_dir_all(&dir);
            std::fs::create_dir_all(&dir).unwrap();
            let exe = dir.join("subdiv");
            std::fs::copy(env!("CARGO_BIN_EXE_subdiv"), &exe).unwrap();
            Installed { dir, exe }
        }
        fn run(&self, args: &[&str]) -> Output {
            Command::new(&self.exe).args(args).current_dir(&self.dir).env_remove("CARGO_MANIFEST_DIR").output().unwrap()
        }
        fn ok(&self, args: &[&str]) -> String {
            let o = self.run(args);
            assert!(o.status.success(), "{args:?}: {}", String::from_utf8_lossy(&o.stderr));
            String::from_utf8(o.stdout).unwrap()
        }
    }

    impl Drop for Installed {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.dir);
        }
    }

    /// The number after `key` on the line starting with `key` in `info` output.
    fn field(info: &str, key: &str) -> usize {
        let line = info.lines().find(|l| l.starts_with(key)).unwrap_or_else(|| panic!("no '{key}' in\n{info}"));
        line[key.len()..].split_whitespace().next().unwrap().parse().unwrap()
    }

    #[test]
    fn an_installed_binary_lists_and_opens_every_bundled_model() {
        let bin = Installed::new();
        assert!(!bin.dir.join("models").exists());
        // `subdiv models`: one line per model, `bundled:NAME  description`
        let listing = bin.ok(&["models"]);
        let listed: Vec<(&str, &str)> = listing
            .lines()
            .map(|l| l.split_once("  ").map(|(n, w)| (n, w.trim())).expect("NAME  description"))
            .collect();
        let expected: Vec<(String, &str)> = MODELS.iter().map(|m| (m.cli_name(), m.what)).collect();
        assert_eq!(listed.len(), expected.len(), "{listing}");
        for ((name, what), (want_name, want_what)) in listed.iter().zip(&expected) {
            assert_eq!((*name, *what), (want_name.as_str(), *want_what));
        }
        for m in MODELS {
            let name = m.cli_name();
            if m.is_curve() {
                let info = bin.ok(&["info", &name]);
                let points = m.bytes.split(|b| b.is_ascii_whitespace()).find(|t| !t.is_empty()).unwrap();
                let n: usize = std::str::from_utf8(points).unwrap().parse().unwrap();
                assert!(info.contains("Bezier curve"), "{info}");
                assert_eq!(field(&info, "control points:"), n, "{info}");
                assert!(info.contains(&format!("(degree {})", n - 1)), "{info}");
                // where a mesh is needed it is refused by name, not misread as OBJ
                let o = bin.run(&["subdivide", &name, "out.obj"]);
                let err = String::from_utf8_lossy(&o.stderr);
                assert!(!o.status.success() && err.contains(&name) && err.contains("not a mesh"), "{err}");
                continue;
            }
            let needs_repair = m.what.contains("needs repair");
            let args: Vec<&str> = if needs_repair { vec!["info", "--repair", &name] } else { vec!["info", &name] };
            let info = bin.ok(&args);
            assert!(info.starts_with(&format!("file:            {name}\n")), "{info}");
            let faces = field(&info, "faces:");
            assert!(faces > 0 && field(&info, "vertices:") > 0, "{info}");
            if !needs_repair {
                assert!(info.contains("manifold:        yes"), "{name}: {info}");
            }
            // a description that gives the triangle or quad count tells the truth
            for kind in [" triangles", " quads"] {
                let count = m.what.split(kind).next().and_then(|s| s.rsplit(' ').next()?.parse::<usize>().ok());
                if let Some(k) = count.filter(|_| m.what.contains(kind)) {
                    assert_eq!(faces, k, "{name}: described as {k}{kind}");
                }
            }
            // the triangles Loop refines: the faces, or their fans for a file of polygons
            let mut json_args = args.clone();
            json_args.push("--json");
            let v: serde_json::Value = serde_json::from_str(&bin.ok(&json_args)).unwrap();
            let triangles = v.get("triangulated").unwrap_or(&v)["faces"].as_u64().unwrap() as usize;
            assert_eq!(v["faces"].as_u64(), Some(faces as u64), "{name}: {v}");
            // and it subdivides from memory, the output written where we run
            let out = format!("{}-1.obj", m.file_name.replace('.', "_"));
            let mut args = vec!["subdivide", &name, &out, "-n", "1"];
            if needs_repair {
                args.push("--repair");
            }
            bin.ok(&args);
            let fine = subdiv::bundled::load(&bin.dir.join(&out)).unwrap();
            assert_eq!(fine.ct.num_triangles(), 4 * triangles, "{name}");
        }
        let o = bin.run(&["info", "bundled:no-such.obj"]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            !o.status.success() && err.contains("no bundled model 'no-such.obj'") && err.contains("subdiv models"),
            "{err}"
        );
    }
}
