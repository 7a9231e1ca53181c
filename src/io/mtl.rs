//! MTL material libraries (the `mtllib` files of an OBJ): per `newmtl`,
//! the diffuse colour `Kd` (three values, or one for a grey, as the format
//! allows) and the diffuse texture `map_Kd` with its options (`-clamp on`,
//! `-o u v w`, ...) read past to the file name. Other statements are read
//! past. A line that cannot be read is a warning naming the library and the
//! line, and the statement is skipped: a library never stops a model from
//! opening.

use super::Warnings;
use crate::mesh::attributes::Wrap;
use glam::Vec3;

/// One `newmtl` entry, as far as it is read.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Entry {
    /// Its name.
    pub name: String,
    /// `Kd`, when given.
    pub diffuse: Option<Vec3>,
    /// `map_Kd`'s file name, as written.
    pub texture: Option<String>,
    /// `map_Kd -clamp on`.
    pub wrap: Wrap,
}

/// The entries of the library `text` (`lib` names it in warnings, as part
/// of `file`).
pub(crate) fn parse(text: &str, lib: &str, warnings: &Warnings) -> Vec<Entry> {
    let mut out: Vec<Entry> = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        let (key, rest) = line.split_once(char::is_whitespace).unwrap_or((line, ""));
        let rest = rest.trim();
        let warn = |msg: &str| warnings.warn("unreadable MTL lines", format!("{lib}:{}: {msg}", i + 1));
        match key {
            "newmtl" if rest.is_empty() => warn("newmtl without a name"),
            "newmtl" => out.push(Entry { name: rest.to_string(), diffuse: None, texture: None, wrap: Wrap::Repeat }),
            "Kd" | "map_Kd" if out.is_empty() => warn(&format!("{key} before any newmtl")),
            "Kd" => match colour(rest) {
                Some(c) => out.last_mut().into_iter().for_each(|m| m.diffuse = Some(c)),
                None => warn(&format!("Kd '{}' is not one or three numbers", crate::error::clean(rest, 40))),
            },
            "map_Kd" => match texture_map(rest) {
                Some((name, wrap)) => out.last_mut().into_iter().for_each(|m| {
                    m.texture = Some(name.to_string());
                    m.wrap = wrap;
                }),
                None => warn("map_Kd without a file name"),
            },
            _ => {}
        }
    }
    out
}

/// `Kd r g b`, or `Kd g` for a grey; finite values.
fn colour(rest: &str) -> Option<Vec3> {
    let v: Vec<f32> = rest.split_whitespace().map(str::parse).collect::<Result<_, _>>().ok()?;
    let c = match v.as_slice() {
        [g] => Vec3::splat(*g),
        [r, g, b] => Vec3::new(*r, *g, *b),
        _ => return None,
    };
    c.is_finite().then_some(c)
}

/// The file name of a texture map statement after its options, and whether
/// it clamps. The options and how many values each takes (the MTL
/// specification; `-o`, `-s` and `-t` take one to three numbers).
fn texture_map(rest: &str) -> Option<(&str, Wrap)> {
    let mut wrap = Wrap::Repeat;
    let mut s = rest.trim_start();
    while let Some(opt) = s.strip_prefix('-') {
        let (name, mut after) = opt.split_once(char::is_whitespace).unwrap_or((opt, ""));
        let takes = match name {
            "blendu" | "blendv" | "cc" | "clamp" | "imfchan" | "texres" | "boost" | "bm" | "type" => 1,
            "mm" => 2,
            "o" | "s" | "t" => 3,
            _ => break, // a file name that starts with '-'
        };
        for k in 0..takes {
            after = after.trim_start();
            let (value, tail) = after.split_once(char::is_whitespace).unwrap_or((after, ""));
            // -o, -s, -t take 1 to 3 numbers: stop at the first non-number
            if k > 0 && takes == 3 && value.parse::<f32>().is_err() {
                break;
            }
            if name == "clamp" {
                wrap = if value == "on" { Wrap::Clamp } else { Wrap::Repeat };
            }
            after = tail;
        }
        s = after.trim_start();
    }
    let name = s.trim();
    (!name.is_empty()).then_some((name, wrap))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grey_colours_texture_options_and_bad_lines() {
        let w = Warnings::new("m.obj", 300);
        let text = "newmtl a\nKd 0.5\nmap_Kd -clamp on -o 0.1 0.2 file name.png\nnewmtl b\nKd 1 0 0\nKd x\n\
                    map_Kd -s 2 -mm 0 1 tex.jpg\nnewmtl\n";
        let m = parse(text, "lib.mtl", &w);
        assert_eq!(m.len(), 2);
        assert_eq!(m[0].diffuse, Some(Vec3::splat(0.5)));
        assert_eq!((m[0].texture.as_deref(), m[0].wrap), (Some("file name.png"), Wrap::Clamp));
        assert_eq!((m[1].diffuse, m[1].texture.as_deref()), (Some(Vec3::X), Some("tex.jpg")));
        let lines = w.finish();
        assert_eq!(lines.len(), 2, "{lines:?}");
        assert!(lines[0].starts_with("lib.mtl:6: Kd 'x'"), "{lines:?}");
    }
}
