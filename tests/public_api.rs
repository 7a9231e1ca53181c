//! The public API is a reviewed list, not a count: `docs/public-api.txt`
//! holds every public item of the library (modules, types, functions and
//! their signatures, fields, variants, methods, trait impls), one a line,
//! and this test makes the same list from the built crate (rustdoc's JSON
//! output, through `cargo rustdoc` in `target/public-api`) and fails on
//! any difference, printing it. A change of the API is then a diff of that
//! file: run `SUBDIV_BLESS_API=1 cargo test --release --test public_api`
//! to write the new list, and review it.
//!
//! rustdoc's JSON is unstable output: `RUSTC_BOOTSTRAP=1` lets the stable
//! toolchain give it (format version checked below).
#![cfg(all(feature = "viewer", feature = "cli"))]

use serde_json::Value;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// The format versions this reader knows.
const FORMATS: std::ops::RangeInclusive<u64> = 50..=70;

fn checkout() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The crate's rustdoc JSON, built (or found fresh) in `target/public-api`.
fn rustdoc_json() -> Value {
    let dir = checkout().join("target").join("public-api");
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = std::process::Command::new(cargo)
        .current_dir(checkout())
        .env("RUSTC_BOOTSTRAP", "1")
        .env_remove("RUSTDOCFLAGS")
        .args(["rustdoc", "--lib", "--quiet", "--target-dir"])
        .arg(&dir)
        .args(["--", "-Z", "unstable-options", "--output-format", "json"])
        .output()
        .expect("cargo runs");
    assert!(out.status.success(), "cargo rustdoc failed: {}", String::from_utf8_lossy(&out.stderr));
    let text = std::fs::read_to_string(dir.join("doc").join("subdiv.json")).expect("rustdoc wrote its JSON");
    serde_json::from_str(&text).expect("JSON")
}

/// Walks the JSON from the crate root, collecting one line per public item.
struct Walk<'a> {
    index: &'a serde_json::Map<String, Value>,
    lines: BTreeSet<String>,
    seen: BTreeSet<(String, String)>,
}

impl Walk<'_> {
    fn item(&self, id: &Value) -> Option<&Value> {
        self.index.get(&id.as_u64()?.to_string())
    }

    fn public(item: &Value) -> bool {
        item["visibility"] == "public"
    }

    /// The items of module `m` at `path`.
    fn module(&mut self, m: &Value, path: &str) {
        for id in m["inner"]["module"]["items"].as_array().into_iter().flatten() {
            let Some(item) = self.item(id).cloned() else { continue };
            if !Self::public(&item) {
                continue;
            }
            if let Some(u) = item["inner"].get("use") {
                let Some(target) = u.get("id").and_then(|t| self.item(t)).cloned() else {
                    // a re-export of another crate's item
                    self.lines.insert(format!("use {path}::{} = {}", u["name"].as_str().unwrap_or(""), u["source"]));
                    continue;
                };
                match (u["is_glob"].as_bool(), target["inner"].get("module")) {
                    (Some(true), Some(_)) => self.module(&target, path),
                    _ => self.named(&target, &format!("{path}::{}", u["name"].as_str().unwrap_or(""))),
                }
                continue;
            }
            let name = item["name"].as_str().unwrap_or("").to_string();
            self.named(&item, &format!("{path}::{name}"));
        }
    }

    /// `item` under the public path `path`.
    fn named(&mut self, item: &Value, path: &str) {
        let inner = &item["inner"];
        let kind = inner.as_object().and_then(|o| o.keys().next()).cloned().unwrap_or_default();
        if !self.seen.insert((kind.clone(), path.to_string())) {
            return;
        }
        let v = &inner[&kind];
        match kind.as_str() {
            "module" => {
                self.lines.insert(format!("mod {path}"));
                self.module(item, path);
            }
            "function" => {
                self.lines.insert(format!("fn {path}{}", signature(v)));
            }
            "struct" => {
                self.lines.insert(format!("struct {path}{}", generics(&v["generics"])));
                for f in v["kind"]["plain"]["fields"].as_array().into_iter().flatten() {
                    self.field(f, path);
                }
                for f in v["kind"]["tuple"].as_array().into_iter().flatten() {
                    self.field(f, path);
                }
                self.impls(&v["impls"], path);
            }
            "enum" => {
                self.lines.insert(format!("enum {path}{}", generics(&v["generics"])));
                for id in v["variants"].as_array().into_iter().flatten() {
                    if let Some(var) = self.item(id) {
                        self.lines.insert(format!("variant {path}::{}", var["name"].as_str().unwrap_or("")));
                    }
                }
                self.impls(&v["impls"], path);
            }
            "trait" => {
                self.lines.insert(format!("trait {path}{}", generics(&v["generics"])));
                for id in v["items"].as_array().into_iter().flatten() {
                    if let Some(m) = self.item(id).cloned() {
                        let name = m["name"].as_str().unwrap_or("");
                        match m["inner"].get("function") {
                            Some(f) => self.lines.insert(format!("fn {path}::{name}{}", signature(f))),
                            None => self.lines.insert(format!("item {path}::{name}")),
                        };
                    }
                }
            }
            "constant" | "static" => {
                let ty = ty(v.get("type").unwrap_or(&Value::Null));
                self.lines.insert(format!("{kind} {path}: {ty}"));
            }
            "type_alias" => {
                self.lines.insert(format!("type {path} = {}", ty(&v["type"])));
            }
            other => {
                self.lines.insert(format!("{other} {path}"));
            }
        }
    }

    fn field(&mut self, id: &Value, path: &str) {
        if let Some(f) = self.item(id).filter(|f| Self::public(f)) {
            let name = f["name"].as_str().unwrap_or("");
            self.lines.insert(format!("field {path}::{name}: {}", ty(&f["inner"]["struct_field"])));
        }
    }

    /// The inherent methods and the written trait impls of the type at `path`.
    fn impls(&mut self, impls: &Value, path: &str) {
        for id in impls.as_array().into_iter().flatten() {
            let Some(imp) = self.item(id).cloned() else { continue };
            let i = &imp["inner"]["impl"];
            if i["is_synthetic"] == true || !i["blanket_impl"].is_null() {
                continue;
            }
            match i["trait"].as_object() {
                Some(t) => {
                    let name = last(t["path"].as_str().unwrap_or(""));
                    self.lines.insert(format!("impl {name}{} for {path}", args(&t["args"])));
                }
                None => {
                    for m in i["items"].as_array().into_iter().flatten() {
                        let Some(m) = self.item(m).cloned().filter(Self::public) else { continue };
                        let name = m["name"].as_str().unwrap_or("");
                        match m["inner"].get("function") {
                            Some(f) => self.lines.insert(format!("fn {path}::{name}{}", signature(f))),
                            None => self.lines.insert(format!("item {path}::{name}")),
                        };
                    }
                }
            }
        }
    }
}

/// The last segment of a path (`crate::mesh::Mesh` -> `Mesh`).
fn last(p: &str) -> &str {
    p.rsplit("::").next().unwrap_or(p)
}

/// `<T, U>` of generics' type parameters.
fn generics(g: &Value) -> String {
    let names: Vec<&str> = g["params"]
        .as_array()
        .into_iter()
        .flatten()
        .filter(|p| p["kind"].get("type").is_some())
        .filter_map(|p| p["name"].as_str())
        .collect();
    if names.is_empty() { String::new() } else { format!("<{}>", names.join(", ")) }
}

/// `(a: A, b: B) -> R` of a function.
fn signature(f: &Value) -> String {
    let inputs: Vec<String> = f["sig"]["inputs"]
        .as_array()
        .into_iter()
        .flatten()
        .map(|p| format!("{}: {}", p[0].as_str().unwrap_or("_"), ty(&p[1])))
        .collect();
    let out = match &f["sig"]["output"] {
        Value::Null => String::new(),
        t => format!(" -> {}", ty(t)),
    };
    format!("{}({}){out}", generics(&f["generics"]), inputs.join(", "))
}

/// `<A, B>` of a path's type arguments (lifetimes left out).
fn args(a: &Value) -> String {
    let list: Vec<String> = a["angle_bracketed"]["args"]
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(|x| x.get("type").map(ty).or_else(|| x.get("const").map(|_| "_".into())))
        .collect();
    if list.is_empty() { String::new() } else { format!("<{}>", list.join(", ")) }
}

/// A type as written, paths by their last segment.
fn ty(t: &Value) -> String {
    let Some((kind, v)) = t.as_object().and_then(|o| o.iter().next()) else { return "_".into() };
    match kind.as_str() {
        "resolved_path" => format!("{}{}", last(v["path"].as_str().unwrap_or("")), args(&v["args"])),
        "primitive" | "generic" => v.as_str().unwrap_or("_").to_string(),
        "borrowed_ref" => format!("&{}{}", if v["is_mutable"] == true { "mut " } else { "" }, ty(&v["type"])),
        "raw_pointer" => format!("*{} {}", if v["is_mutable"] == true { "mut" } else { "const" }, ty(&v["type"])),
        "slice" => format!("[{}]", ty(v)),
        "array" => format!("[{}; {}]", ty(&v["type"]), v["len"].as_str().unwrap_or("_")),
        "tuple" => format!("({})", v.as_array().into_iter().flatten().map(ty).collect::<Vec<_>>().join(", ")),
        "impl_trait" | "dyn_trait" => {
            let bounds = if kind == "dyn_trait" { &v["traits"] } else { v };
            let names: Vec<String> = bounds
                .as_array()
                .into_iter()
                .flatten()
                .filter_map(|b| {
                    let p = b.get("trait_bound").map_or(b, |tb| tb);
                    let path = p.get("trait").unwrap_or(p);
                    path["path"].as_str().map(|s| format!("{}{}", last(s), args(&path["args"])))
                })
                .collect();
            format!("{} {}", if kind == "dyn_trait" { "dyn" } else { "impl" }, names.join(" + "))
        }
        "qualified_path" => format!("{}::{}", ty(&v["self_type"]), v["name"].as_str().unwrap_or("")),
        "function_pointer" => "fn(..)".into(),
        _ => kind.clone(),
    }
}

/// The public API of the built crate, one line an item, sorted.
fn built_api() -> String {
    let doc = rustdoc_json();
    let version = doc["format_version"].as_u64().unwrap_or(0);
    assert!(FORMATS.contains(&version), "rustdoc JSON format {version}: update this reader");
    let index = doc["index"].as_object().expect("an index");
    let root = index.get(&doc["root"].as_u64().expect("a root").to_string()).expect("the root module");
    let mut walk = Walk { index, lines: BTreeSet::new(), seen: BTreeSet::new() };
    walk.module(root, "subdiv");
    walk.lines.into_iter().map(|l| l + "\n").collect()
}

#[test]
fn the_public_api_is_the_reviewed_list() {
    let file = checkout().join("docs").join("public-api.txt");
    let built = built_api();
    if std::env::var_os("SUBDIV_BLESS_API").is_some() {
        std::fs::write(&file, &built).expect("written");
        return;
    }
    let listed = std::fs::read_to_string(&file).unwrap_or_default();
    if listed == built {
        return;
    }
    let (a, b): (BTreeSet<&str>, BTreeSet<&str>) = (listed.lines().collect(), built.lines().collect());
    let gone: Vec<&&str> = a.difference(&b).collect();
    let new: Vec<&&str> = b.difference(&a).collect();
    panic!(
        "the built crate's API differs from {}:\n  not built any more: {gone:#?}\n  built, not listed: {new:#?}\nrun SUBDIV_BLESS_API=1 cargo test --release --test public_api and review the diff",
        Path::new("docs/public-api.txt").display()
    );
}
