//! The docs name files that exist: every repository path that a Markdown
//! doc (all but `CHANGELOG.md`, which is history), a comment in the Rust
//! sources (`src/`, `tests/`, `examples/`, `benches/`, `python/src/`) or
//! the command line's `--help` names, and every local Markdown link, must
//! resolve in the working tree. A failure lists which doc names which
//! missing path.
//!
//! A path is recognised by its shape: a token starting with one of the
//! repository's top folders (`src/`, `docs/`, ... [`TOP`]), or a bare
//! `<name>.md`. `#anchors` and `:line` suffixes are not part of it, trailing
//! dots are sentence ends, and a token followed by `*`, `<` or `{` (a glob
//! or a placeholder: `src/io/<format>.rs`, `tests/fixtures/catmark/*.osd.txt`)
//! only needs some file that starts with it. An example or bench named as
//! its Cargo target (`examples/phases`) is its `.rs` file; a path through a
//! `target` folder is a build output, never in the tree, and is not
//! checked; [`ELSEWHERE`] lists the paths that name another project's
//! files. A path resolves against the
//! repository root or the doc's own folder (and `python/` for the Python
//! package's files); a bare `<name>.md` also against `docs/`; a Markdown link
//! against the doc's folder only, as a Markdown viewer resolves it.

use std::path::{Path, PathBuf};

/// The repository's top folders: a token starting with one of these and a
/// slash is a path.
const TOP: [&str; 11] =
    ["src", "tests", "docs", "scripts", "benches", "examples", "models", "paths", "shaders", "python", ".ci"];

/// Paths that name files of another project, by the file naming them:
/// (file, path, whose).
const ELSEWHERE: [(&str, &str, &str); 1] = [("src/app/surface.rs", "examples/features/src/framework.rs", "wgpu's")];

/// Folders never searched for docs (build outputs, environments, caches).
const SKIPPED_DIRS: [&str; 6] = ["target", "venv", "node_modules", "__pycache__", "shared", "dist"];

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A character that can continue a path token.
fn path_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || matches!(c, '_' | '.' | '/' | '-')
}

/// One path a text names.
#[derive(Debug, PartialEq)]
struct Named {
    /// As written, without anchor, line suffix or trailing dots.
    path: String,
    /// A glob or placeholder follows: any file starting with `path` will do.
    prefix: bool,
    /// A bare `<name>.md` (resolved against `docs/` too).
    bare_md: bool,
}

/// The paths `text` names by shape (see the module docs).
fn named_paths(text: &str) -> Vec<Named> {
    let mut out = Vec::new();
    let chars: Vec<(usize, char)> = text.char_indices().collect();
    for (k, &(i, _)) in chars.iter().enumerate() {
        if k > 0 && path_char(chars[k - 1].1) {
            continue;
        }
        let rest = &text[i..];
        let len = rest.find(|c: char| !path_char(c)).unwrap_or(rest.len());
        let token = &rest[..len];
        let next = rest[len..].chars().next();
        let prefix = matches!(next, Some('*' | '<' | '{'));
        let rooted = TOP.iter().any(|t| token.strip_prefix(t).is_some_and(|r| r.starts_with('/')));
        let trimmed = if prefix { token } else { token.trim_end_matches('.') };
        let bare_md = !rooted && !trimmed.contains('/') && trimmed.len() > 3 && trimmed.ends_with(".md");
        if rooted || bare_md {
            out.push(Named { path: trimmed.to_string(), prefix, bare_md });
        }
    }
    out
}

/// The targets of the Markdown links in `text` (`[text](target)` and
/// reference definitions `[name]: target`) that are local files: no
/// scheme, not only an anchor; the anchor and any title dropped.
fn local_links(text: &str) -> Vec<String> {
    let mut targets = Vec::new();
    let mut rest = text;
    while let Some(at) = rest.find("](") {
        rest = &rest[at + 2..];
        if let Some(end) = rest.find(')') {
            targets.push(rest[..end].to_string());
        }
    }
    for line in text.lines() {
        let t = line.trim_start();
        if t.starts_with('[')
            && let Some(at) = t.find("]: ")
        {
            targets.push(t[at + 3..].to_string());
        }
    }
    targets
        .into_iter()
        .filter_map(|t| {
            let t = t.trim().trim_start_matches('<').trim_end_matches('>');
            let t = t.split_whitespace().next()?; // a title follows a space
            let t = t.split('#').next()?;
            (!t.is_empty() && !t.contains("://") && !t.starts_with("mailto:")).then(|| t.to_string())
        })
        .collect()
}

/// Whether `path` exists under one of `bases` (as a file or folder, or, for
/// a prefix, as the start of some file's path there).
fn resolves(bases: &[PathBuf], path: &str, prefix: bool) -> bool {
    bases.iter().any(|b| {
        if !prefix {
            return b.join(path).exists();
        }
        let (dir, start) = path.rsplit_once('/').unwrap_or(("", path));
        std::fs::read_dir(b.join(dir)).is_ok_and(|entries| {
            entries.flatten().any(|e| e.file_name().to_str().is_some_and(|n| n.starts_with(start)))
        })
    })
}

/// The folders a path named in the file `doc` (relative to the
/// repository) resolves against.
fn bases_of(doc: &Path) -> Vec<PathBuf> {
    let root = repo();
    let mut bases = vec![root.clone()];
    if let Some(dir) = doc.parent().filter(|d| !d.as_os_str().is_empty()) {
        bases.push(root.join(dir));
    }
    if doc.starts_with("python") {
        bases.push(root.join("python"));
    }
    bases
}

/// The missing paths `text` (from `doc`) names, as `doc: names PATH`
/// lines; `markdown` adds the check of its local links.
fn missing_in(doc: &Path, text: &str, markdown: bool) -> Vec<String> {
    let bases = bases_of(doc);
    let mut docs_too = bases.clone();
    docs_too.push(repo().join("docs"));
    let mut missing = Vec::new();
    for n in named_paths(text) {
        let target = |p: &str| p.starts_with("examples/") || p.starts_with("benches/");
        let found = if n.bare_md {
            resolves(&docs_too, &n.path, false)
        } else {
            resolves(&bases, &n.path, n.prefix)
                || (target(&n.path) && !n.prefix && resolves(&bases, &format!("{}.rs", n.path), false))
                || n.path.split('/').any(|part| part == "target")
                || ELSEWHERE.iter().any(|&(file, path, _)| Path::new(file) == doc && path == n.path)
        };
        if !found {
            missing.push(format!("{}: names {}{}", doc.display(), n.path, if n.prefix { "*" } else { "" }));
        }
    }
    if markdown {
        let dir = repo().join(doc.parent().unwrap_or(Path::new("")));
        for target in local_links(text) {
            if !dir.join(&target).exists() {
                missing.push(format!("{}: links to {target}", doc.display()));
            }
        }
    }
    missing
}

/// Every file under `dir` (relative to the repository) whose name ends
/// with `ext`, skipping build outputs, hidden folders and the vendored
/// crates (`vendor/NAME/`: another project's docs; `vendor/README.md` is
/// ours).
fn files_under(dir: &str, ext: &str) -> Vec<PathBuf> {
    fn walk(root: &Path, rel: &Path, ext: &str, out: &mut Vec<PathBuf>) {
        let Ok(entries) = std::fs::read_dir(root.join(rel)) else { return };
        for e in entries.flatten() {
            let name = e.file_name().to_string_lossy().to_string();
            let path = rel.join(&name);
            let Ok(kind) = e.file_type() else { continue };
            if kind.is_dir() {
                let vendored = rel == Path::new("vendor");
                if !name.starts_with('.') && !SKIPPED_DIRS.contains(&name.as_str()) && !vendored {
                    walk(root, &path, ext, out);
                }
            } else if name.ends_with(ext) {
                out.push(path);
            }
        }
    }
    let mut out = Vec::new();
    walk(&repo(), Path::new(dir), ext, &mut out);
    out.sort();
    out
}

/// The comments of a Rust file: each `//` line comment (doc comments
/// included) and the comment after code on a line (a `//` outside a
/// string, by an even count of quotes before it).
fn rust_comments(source: &str) -> String {
    let mut out = String::new();
    for line in source.lines() {
        let t = line.trim_start();
        let comment = if t.starts_with("//") {
            Some(t)
        } else {
            line.match_indices("//")
                .find(|&(at, _)| line[..at].matches('"').count() % 2 == 0)
                .map(|(at, _)| &line[at..])
        };
        if let Some(c) = comment {
            out.push_str(c);
            out.push('\n');
        }
    }
    out
}

/// Asserts that `missing` is empty, listing every entry.
fn assert_none_missing(what: &str, missing: &[String]) {
    assert!(missing.is_empty(), "{what} name files that do not exist:\n  {}", missing.join("\n  "));
}

#[test]
fn markdown_docs_name_only_files_that_exist() {
    let mut docs = files_under("", ".md");
    docs.retain(|d| d != Path::new("CHANGELOG.md"));
    for must in ["README.md", "ARCHITECTURE.md", "docs/design.md", "docs/cli.md", "python/README.md"] {
        assert!(docs.iter().any(|d| d == Path::new(must)), "{must} not among the docs checked: {docs:?}");
    }
    let mut missing = Vec::new();
    for doc in &docs {
        let text = std::fs::read_to_string(repo().join(doc)).unwrap();
        missing.extend(missing_in(doc, &text, true));
    }
    assert_none_missing("Markdown docs", &missing);
}

#[test]
fn source_comments_name_only_files_that_exist() {
    let mut sources = Vec::new();
    for dir in ["src", "tests", "examples", "benches", "python/src"] {
        sources.extend(files_under(dir, ".rs"));
    }
    assert!(sources.iter().any(|s| s == Path::new("src/lib.rs")) && sources.len() > 100, "{sources:?}");
    let mut missing = Vec::new();
    for file in &sources {
        let text = std::fs::read_to_string(repo().join(file)).unwrap();
        missing.extend(missing_in(file, &rust_comments(&text), false));
    }
    assert_none_missing("Source comments", &missing);
    // each exception is still needed
    for (file, path, whose) in ELSEWHERE {
        let text = std::fs::read_to_string(repo().join(file)).unwrap_or_default();
        assert!(rust_comments(&text).contains(path), "{file} no longer names {whose} {path}: drop it from ELSEWHERE");
    }
}

#[cfg(feature = "cli")]
#[test]
fn help_texts_name_only_files_that_exist() {
    use std::process::Command;
    let help = |args: &[&str]| {
        let o = Command::new(env!("CARGO_BIN_EXE_subdiv")).args(args).output().unwrap();
        assert!(o.status.success(), "{args:?}: {}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8(o.stdout).unwrap()
    };
    let top = help(&["--help"]);
    // the commands are the lines `  NAME  what it does` after `Commands:`
    let commands: Vec<String> = top
        .lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next().map(str::to_string))
        .filter(|c| c != "help")
        .collect();
    assert!(commands.len() >= 10 && commands.iter().any(|c| c == "render"), "{top}");
    let mut missing = missing_in(Path::new("subdiv --help"), &top, false);
    for cmd in &commands {
        let doc = format!("subdiv {cmd} --help");
        missing.extend(missing_in(Path::new(&doc), &help(&[cmd, "--help"]), false));
    }
    assert_none_missing("Help texts", &missing);
}

#[test]
fn the_check_finds_missing_paths_and_allows_anchors_lines_and_placeholders() {
    let text = "See src/lib.rs:12, docs/design.md#1-one-crate, (src/subdiv/eval/), \
                src/subdiv/rules/<scheme>.rs, tests/fixtures/catmark/*.osd.txt, src/mesh/mod.rs. \
                Not src/gone.rs, nor tests/fixtures/nothing*.txt, nor gone.md, \
                nor [a link](missing/page.md#x); [a good one](docs/cli.md#info), \
                <https://example.com/src/x.rs> and [web](https://example.com/a.md) are fine.";
    let missing = missing_in(Path::new("NOTE.md"), text, true);
    assert_eq!(
        missing,
        [
            "NOTE.md: names src/gone.rs",
            "NOTE.md: names tests/fixtures/nothing*",
            "NOTE.md: names gone.md",
            "NOTE.md: links to missing/page.md",
        ],
    );
    // an example by its target name, a build output, another project's file
    let text = "examples/phases, examples/nothing, python/target/wheels, examples/features/src/framework.rs";
    assert_eq!(
        missing_in(Path::new("src/x.rs"), text, false),
        ["src/x.rs: names examples/nothing", "src/x.rs: names examples/features/src/framework.rs"]
    );
    assert!(missing_in(Path::new(ELSEWHERE[0].0), ELSEWHERE[0].1, false).is_empty());
    // a doc in a folder: links from there, bare names there or in docs/
    let missing = missing_in(Path::new("docs/x.md"), "[up](../README.md), [sib](cli.md), design.md", true);
    assert!(missing.is_empty(), "{missing:?}");
    // comments only, not code or strings
    let src = "let a = \"src/nowhere.rs\"; // see src/lib.rs\n/// and src/missing.rs\nfn f() {}\n";
    assert_eq!(missing_in(Path::new("src/x.rs"), &rust_comments(src), false), ["src/x.rs: names src/missing.rs"]);
}
