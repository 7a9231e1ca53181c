//! The files of a batch: the inputs expanded (folders walked, globs
//! matched) and each given its output in the batch's folder.

use std::collections::HashMap;
use std::path::{Component, Path, PathBuf};

/// One model of a batch and where its refinement goes.
pub(super) struct Item {
    pub(super) input: PathBuf,
    pub(super) output: PathBuf,
}

/// The models `inputs` name, in order, each with its output in `out` (the
/// batch's folder, made later where it is missing): a file (or anything that is not a folder: the
/// library then says what is wrong with it) as itself, written as
/// `out/NAME`; a folder walked for the models in it (every extension a
/// reader takes; hidden entries, links to folders and `out` itself left
/// out), written at the same relative path under `out`; a path with `*`,
/// `?` or `[...]` that names nothing as the paths it matches; `bundled:NAME`
/// as `out/NAME`. Each output has the extension `format`, else its input's
/// where that format is written, else `obj`. The same input named twice
/// counts once.
///
/// # Errors
/// A glob that matches nothing, a folder that cannot be read, two inputs
/// with one output, an output that is its own input.
pub(super) fn gather(inputs: &[PathBuf], out: &Path, format: Option<&str>) -> Result<Vec<Item>, String> {
    let walk = Walk { out: out.canonicalize().ok(), models: subdiv::io::read_extensions().collect() };
    let mut named = Vec::new();
    for arg in inputs {
        let is_bundled = arg.to_str().is_some_and(|s| s.starts_with(subdiv::bundled::PREFIX));
        if is_bundled || std::fs::symlink_metadata(arg).is_ok() {
            walk.named(arg, &mut named)?;
        } else if arg.to_str().is_some_and(has_wildcard) {
            let found = glob(arg);
            if found.is_empty() {
                return Err(format!("'{}' matches no file", arg.display()));
            }
            for path in found {
                walk.named(&path, &mut named)?;
            }
        } else {
            // a file that is not there: the library names it in the manifest
            named.push((arg.clone(), file_name(arg)));
        }
    }
    outputs(named, out, format)
}

/// Where the models are looked for.
struct Walk {
    /// The batch's folder, never walked.
    out: Option<PathBuf>,
    /// The extensions of models.
    models: Vec<&'static str>,
}

impl Walk {
    /// `path` (named on the command line or matched by a glob) as models
    /// with their names under the output folder: a folder's models, else
    /// `path` itself.
    fn named(&self, path: &Path, named: &mut Vec<(PathBuf, PathBuf)>) -> Result<(), String> {
        match std::fs::metadata(path) {
            Ok(m) if m.is_dir() => self.folder(path, Path::new(""), named),
            _ => {
                named.push((path.to_path_buf(), file_name(path)));
                Ok(())
            }
        }
    }

    /// The models in `root/rel`, sorted by name, with their paths relative
    /// to `root`: an entry with a model's extension is a model whatever it
    /// is (a folder named `x.obj` is refused by the library, by name), a
    /// folder is walked.
    fn folder(&self, root: &Path, rel: &Path, named: &mut Vec<(PathBuf, PathBuf)>) -> Result<(), String> {
        let dir = root.join(rel);
        if self.out.is_some() && dir.canonicalize().ok() == self.out {
            return Ok(());
        }
        let read = std::fs::read_dir(&dir)
            .map_err(|e| format!("{}: {e}", subdiv::clean_error(&dir.display().to_string(), 80)))?;
        let mut names: Vec<_> = read.filter_map(|e| e.ok().map(|e| e.file_name())).collect();
        names.sort();
        for name in names {
            if name.to_string_lossy().starts_with('.') {
                continue;
            }
            let (path, rel) = (dir.join(&name), rel.join(&name));
            let ext = path.extension().map(|e| e.to_string_lossy().to_lowercase());
            if ext.is_some_and(|e| self.models.contains(&e.as_str())) {
                named.push((path, rel));
            } else if std::fs::symlink_metadata(&path).is_ok_and(|m| m.is_dir()) {
                self.folder(root, &rel, named)?;
            }
        }
        Ok(())
    }
}

/// The name of `path` under the output folder: its file name (a bundled
/// model's own name).
fn file_name(path: &Path) -> PathBuf {
    let s = path.to_string_lossy();
    match s.strip_prefix(subdiv::bundled::PREFIX) {
        Some(name) => PathBuf::from(name),
        None => path.file_name().map_or_else(|| PathBuf::from("model"), PathBuf::from),
    }
}

/// Each input with its output, duplicates dropped, clashes refused.
fn outputs(named: Vec<(PathBuf, PathBuf)>, out: &Path, format: Option<&str>) -> Result<Vec<Item>, String> {
    let written: Vec<&str> = subdiv::io::write_extensions().collect();
    let mut by_output: HashMap<PathBuf, PathBuf> = HashMap::new();
    let mut items = Vec::new();
    for (input, rel) in named {
        let own = rel.extension().map(|e| e.to_string_lossy().to_lowercase()).filter(|e| written.contains(&e.as_str()));
        let ext = format.map(str::to_string).or(own).unwrap_or_else(|| "obj".into());
        let output = out.join(rel).with_extension(ext);
        if let Some(first) = by_output.get(&output) {
            if *first == input {
                continue;
            }
            return Err(format!(
                "{} and {} would both be written to {}: refine them into separate --out folders",
                first.display(),
                input.display(),
                output.display()
            ));
        }
        let same = |a: &Path, b: &Path| a.canonicalize().ok().is_some_and(|a| b.canonicalize().ok() == Some(a));
        if same(&input, &output) {
            return Err(format!("{} would be written over itself: choose another --out", input.display()));
        }
        by_output.insert(output.clone(), input.clone());
        items.push(Item { input, output });
    }
    Ok(items)
}

/// Whether `s` has glob characters.
fn has_wildcard(s: &str) -> bool {
    s.contains(['*', '?', '['])
}

/// The existing paths `pattern` matches, sorted: each component with `*`,
/// `?` or `[...]` matched against the names in the folders matched so far
/// (a hidden name only by a component that starts with `.`).
fn glob(pattern: &Path) -> Vec<PathBuf> {
    let mut found = vec![PathBuf::new()];
    for comp in pattern.components() {
        let wild = match comp {
            Component::Normal(name) => name.to_str().filter(|s| has_wildcard(s)),
            _ => None,
        };
        let Some(wild) = wild else {
            found.iter_mut().for_each(|f| f.push(comp));
            continue;
        };
        let pat: Vec<char> = wild.chars().collect();
        let mut next = Vec::new();
        for base in &found {
            let dir = if base.as_os_str().is_empty() { Path::new(".") } else { base.as_path() };
            let Ok(read) = std::fs::read_dir(dir) else { continue };
            let mut names: Vec<String> = read.filter_map(|e| e.ok()?.file_name().into_string().ok()).collect();
            names.sort();
            for name in names {
                let hidden_ok = !name.starts_with('.') || wild.starts_with('.');
                if hidden_ok && matches(&pat, &name.chars().collect::<Vec<_>>()) {
                    next.push(base.join(name));
                }
            }
        }
        found = next;
    }
    found.retain(|p| std::fs::symlink_metadata(p).is_ok());
    found
}

/// Whether the name `s` matches the glob `p`: `*` any run of characters,
/// `?` one, `[abc]`, `[a-z]`, `[!a]` (or `[^a]`) one of a class; any other
/// character itself.
fn matches(p: &[char], s: &[char]) -> bool {
    match p.split_first() {
        None => s.is_empty(),
        Some(('*', rest)) => (0..=s.len()).any(|k| matches(rest, &s[k..])),
        Some(('?', rest)) => !s.is_empty() && matches(rest, &s[1..]),
        Some(('[', rest)) => {
            let Some((&c, tail)) = s.split_first() else { return false };
            match class(rest, c) {
                Some((hit, after)) => hit && matches(after, tail),
                // no closing bracket: a plain '['
                None => c == '[' && matches(rest, tail),
            }
        }
        Some((c, rest)) => s.first() == Some(c) && matches(rest, &s[1..]),
    }
}

/// The class at the start of `p` (after its `[`): whether `c` is in it, and
/// the pattern after its `]`; `None` without a `]`.
fn class(p: &[char], c: char) -> Option<(bool, &[char])> {
    let negated = matches!(p.first(), Some('!' | '^'));
    let body = if negated { &p[1..] } else { p };
    // a ']' first is a member
    let end = body.iter().skip(1).position(|&x| x == ']')? + 1;
    let (members, after) = (&body[..end], &body[end + 1..]);
    let mut hit = false;
    let mut k = 0;
    while k < members.len() {
        if k + 2 < members.len() && members[k + 1] == '-' {
            hit |= (members[k]..=members[k + 2]).contains(&c);
            k += 3;
        } else {
            hit |= members[k] == c;
            k += 1;
        }
    }
    Some((hit != negated, after))
}

#[cfg(test)]
mod tests {
    use super::matches;

    fn m(p: &str, s: &str) -> bool {
        matches(&p.chars().collect::<Vec<_>>(), &s.chars().collect::<Vec<_>>())
    }

    #[test]
    fn globs_match_as_the_shell_does() {
        assert!(m("*.obj", "torus.obj") && m("*.obj", ".obj") && !m("*.obj", "torus.ply"));
        assert!(m("t?rus.*", "torus.ct") && !m("t?rus.*", "trus.ct"));
        assert!(m("[tc]*", "cube.obj") && m("[a-d]ube.obj", "cube.obj") && !m("[!c]ube.obj", "cube.obj"));
        assert!(m("[^x]ube.obj", "cube.obj") && m("[]]", "]") && !m("[]]", "a"));
        assert!(m("a[b", "a[b") && !m("a[b", "ab"), "an unclosed bracket is itself");
        assert!(m("**x*", "axbx") && !m("*x", "xa") && m("", "") && !m("", "a"));
    }
}
