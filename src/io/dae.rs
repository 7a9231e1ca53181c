//! COLLADA (`.dae`) in: the `<triangles>`, `<polylist>` and `<polygons>` of
//! every `<geometry>`'s `<mesh>`, with the first `TEXCOORD` input kept per
//! corner (primitives without one get (0, 0)). Geometries are taken as stored
//! (instancing and node transforms are not applied; the original projects'
//! COLLADA files hold one geometry in place). XML through `roxmltree`
//! (read-only, no dependencies, kept up to date); the COLLADA structure by
//! hand, since the `collada` crate has had no release since 2019 and
//! `dae-parser` pulls in a DOM and many more crates. Errors name the file and
//! the element (`geometry 'Cube-mesh' triangles 0`). Polygons are kept as
//! polygons; a polygon with holes (`<ph>`) is refused, since a face cannot
//! hold one. The text of an element is all of its text (a comment inside
//! `<p>` splits it, and every part counts).

use super::raw::{RawMesh, format_err};
use super::{Format, Input as Read, Keeps};
use crate::Result;
use glam::{Vec2, Vec3};
use roxmltree::{Document, Node};
use std::collections::HashMap;

/// A `<source>`: its floats and the accessor's stride.
struct Source {
    floats: Vec<f32>,
    stride: usize,
}

/// An `<input>` of a primitive.
struct Input {
    /// `VERTEX`, `TEXCOORD`, ...
    semantic: String,
    /// Its index within each corner's indices.
    offset: usize,
    /// The id of its `<source>` (or `<vertices>`), without the `#`.
    source: String,
}

/// The COLLADA row of [`super::FORMATS`].
pub(crate) const FORMAT: Format = Format {
    name: "COLLADA",
    extensions: &["dae"],
    sniff: |b| b.trim_ascii_start().starts_with(b"<"),
    reader: Some(read),
    writer: None,
    written_as: &[],
    poly_writer: None,
    faces_writer: None,
    keeps: Keeps { uv: false, colors: false, materials: false, creases: false, holes: false },
};

/// Reads a COLLADA file.
///
/// # Errors
/// [`crate::Error::Format`] naming the file and element; XML errors with
/// their position; over the budget.
fn read(input: &Read) -> Result<RawMesh> {
    let file = input.file;
    let text = input.text()?;
    let doc = Document::parse(text).map_err(|e| format_err(file, "XML", e.to_string()))?;
    let mut raw: Option<RawMesh> = None;
    for (g, geom) in doc.descendants().filter(|n| n.has_tag_name("geometry")).enumerate() {
        let name = geom.attribute("id").map_or_else(|| format!("geometry {g}"), |id| format!("geometry '{id}'"));
        let Some(mesh) = child(geom, "mesh") else { continue };
        let part = read_mesh(mesh, file, &name)?;
        input.budget.take_vertices(part.positions.len() as u64, file, &name)?;
        input.budget.take_faces(part.num_faces() as u64, file, &name)?;
        match &mut raw {
            Some(r) => r.append(part),
            None => raw = Some(part),
        }
    }
    raw.filter(|r| r.num_faces() > 0).ok_or_else(|| format_err(file, "library_geometries", "no faces in any geometry"))
}

/// All the text inside `n` (text split by comments or CDATA is joined with
/// spaces).
fn all_text(n: Node) -> String {
    let mut out = String::new();
    for t in n.descendants().filter(|d| d.is_text()) {
        out.push_str(t.text().unwrap_or(""));
        out.push(' ');
    }
    out
}

fn child<'a>(n: Node<'a, 'a>, tag: &str) -> Option<Node<'a, 'a>> {
    n.children().find(|c| c.has_tag_name(tag))
}

fn read_sources(mesh: Node, file: &str, at: &str) -> Result<HashMap<String, Source>> {
    let mut out = HashMap::new();
    for s in mesh.children().filter(|c| c.has_tag_name("source")) {
        let id = s.attribute("id").unwrap_or("").to_string();
        let Some(arr) = child(s, "float_array") else { continue };
        let floats = numbers::<f32>(&all_text(arr))
            .map_err(|t| format_err(file, format!("{at} source '{id}'"), format!("'{t}' is not a number")))?;
        let stride = child(s, "technique_common")
            .and_then(|t| child(t, "accessor"))
            .and_then(|a| a.attribute("stride"))
            .and_then(|s| s.parse().ok())
            .unwrap_or(3usize)
            .max(1);
        out.insert(id, Source { floats, stride });
    }
    Ok(out)
}

fn numbers<T: std::str::FromStr>(s: &str) -> std::result::Result<Vec<T>, String> {
    s.split_ascii_whitespace().map(|t| t.parse().map_err(|_| t.chars().take(20).collect())).collect()
}

/// `#id` to `id`.
fn target(n: Node) -> String {
    n.attribute("source").unwrap_or("").trim_start_matches('#').to_string()
}

fn read_mesh(mesh: Node, file: &str, at: &str) -> Result<RawMesh> {
    let sources = read_sources(mesh, file, at)?;
    // <vertices id> -> its POSITION source
    let mut vertices: HashMap<String, String> = HashMap::new();
    for v in mesh.children().filter(|c| c.has_tag_name("vertices")) {
        if let Some(p) = v.children().find(|i| i.has_tag_name("input") && i.attribute("semantic") == Some("POSITION")) {
            vertices.insert(v.attribute("id").unwrap_or("").to_string(), target(p));
        }
    }
    let mut raw = RawMesh::default();
    let mut pos_source: Option<String> = None;
    let mut uv: Option<Vec<Vec2>> = Some(Vec::new());
    let mut has_uv = false;
    for (k, prim) in
        mesh.children().filter(|c| matches!(c.tag_name().name(), "triangles" | "polylist" | "polygons")).enumerate()
    {
        let here = format!("{at} {} {k}", prim.tag_name().name());
        let err = |msg: String| format_err(file, &here, msg);
        let (inputs, stride) = read_inputs(prim, file, &here)?;
        let Input { offset: voff, source: vsrc, .. } =
            inputs.iter().find(|i| i.semantic == "VERTEX").ok_or_else(|| err("no VERTEX input".into()))?;
        let psrc = vertices.get(vsrc).cloned().unwrap_or_else(|| vsrc.clone());
        if pos_source.get_or_insert_with(|| psrc.clone()) != &psrc {
            return Err(err("primitives of one mesh use different position sources".into()));
        }
        let tex = inputs.iter().find(|i| i.semantic == "TEXCOORD");
        has_uv |= tex.is_some();
        let polys = polygons(prim, stride, file, &here)?;
        let ix_err = |t: String| err(format!("'{t}' is not an index"));
        let mut corners: Vec<u32> = Vec::new();
        for p in polys {
            let p: Vec<u32> = numbers(&p).map_err(ix_err)?;
            if !p.len().is_multiple_of(stride) {
                return Err(err(format!("a polygon of {} indices, not a multiple of {stride} per corner", p.len())));
            }
            corners.clear();
            for c in p.chunks_exact(stride) {
                corners.push(c[*voff]);
                if let (Some(out), None) = (&mut uv, tex) {
                    out.push(Vec2::ZERO);
                } else if let (Some(out), Some(Input { source: src, offset, .. })) = (&mut uv, tex) {
                    let s = sources.get(src).ok_or_else(|| err(format!("no source '{src}'")))?;
                    let t = (c[*offset] as usize)
                        .checked_mul(s.stride)
                        .and_then(|at| s.floats.get(at..at.checked_add(2)?))
                        .ok_or_else(|| err(format!("texture coordinate {} out of range", c[*offset])))?;
                    out.push(Vec2::new(t[0], t[1]));
                }
            }
            if corners.len() < 3 {
                return Err(err(format!("a polygon of {} corners (3 or more needed)", corners.len())));
            }
            raw.push_face(&corners);
        }
    }
    let psrc = pos_source.unwrap_or_default();
    let s = sources.get(&psrc).ok_or_else(|| format_err(file, at, format!("no position source '{psrc}'")))?;
    if s.stride < 3 {
        return Err(format_err(file, at, "positions need 3 coordinates"));
    }
    raw.positions = s.floats.chunks_exact(s.stride).map(|c| Vec3::new(c[0], c[1], c[2])).collect();
    if let Some(v) = raw.positions.iter().position(|p| !p.is_finite()) {
        return Err(format_err(file, format!("{at} vertex {v}"), "non-finite position"));
    }
    let nv = raw.positions.len();
    if let Some(&i) = raw.corners.iter().find(|&&i| i as usize >= nv) {
        return Err(format_err(file, at, format!("vertex index {i}, but there are only {nv} positions")));
    }
    raw.uv = uv.filter(|u| u.len() == raw.corners.len() && has_uv);
    Ok(raw)
}

/// A primitive's `<input>`s, and the number of indices per corner (the
/// largest offset + 1).
///
/// # Errors
/// An offset that is not a number, or one so large that the corner size
/// does not fit in a `usize`, naming the input; a primitive without inputs.
fn read_inputs(prim: Node, file: &str, at: &str) -> Result<(Vec<Input>, usize)> {
    let mut inputs = Vec::new();
    for (k, i) in prim.children().filter(|i| i.has_tag_name("input")).enumerate() {
        let semantic = i.attribute("semantic").unwrap_or("").to_string();
        let off = match i.attribute("offset") {
            None => 0,
            Some(o) => o.trim().parse::<usize>().map_err(|_| {
                format_err(file, format!("{at} input {k} ({semantic})"), format!("offset '{o}' is not an index"))
            })?,
        };
        inputs.push(Input { semantic, offset: off, source: target(i) });
    }
    let Some(max) = inputs.iter().map(|i| i.offset).max() else {
        return Err(format_err(file, at, "no <input> (every primitive needs a VERTEX input)"));
    };
    let stride = max.checked_add(1).ok_or_else(|| {
        format_err(file, at, format!("input offset {max} is too large (the indices per corner overflow)"))
    })?;
    Ok((inputs, stride))
}

/// The index text of each polygon of a primitive: `<triangles>` three
/// corners at a time, `<polylist>` by its `<vcount>`, `<polygons>` one `<p>`
/// each; `stride` indices per corner (at least 1). The indices must be
/// exactly what the counts say: none left over, none missing.
fn polygons(prim: Node, stride: usize, file: &str, at: &str) -> Result<Vec<String>> {
    let name = prim.tag_name().name();
    if child(prim, "ph").is_some() {
        return Err(format_err(file, at, "polygons with holes (<ph>) are not supported"));
    }
    let ps: Vec<String> = prim.children().filter(|c| c.has_tag_name("p")).map(all_text).collect();
    let declared = prim.attribute("count").map(|c| c.trim().parse::<usize>());
    let check_declared = |n: usize| match declared {
        Some(Ok(d)) if d != n => {
            Err(format_err(file, at, format!("count=\"{d}\", but the primitive holds {n} polygons")))
        }
        Some(Err(_)) => Err(format_err(file, at, "its count attribute is not a number")),
        _ => Ok(()),
    };
    if name == "polygons" {
        check_declared(ps.len())?;
        return Ok(ps);
    }
    let stride = stride.max(1);
    let words: Vec<&str> = ps.iter().flat_map(|p| p.split_ascii_whitespace()).collect();
    let counts: Vec<usize> = if name == "polylist" {
        let vc = child(prim, "vcount").map(all_text).unwrap_or_default();
        numbers(&vc).map_err(|t| format_err(file, at, format!("vcount '{t}' is not a count")))?
    } else {
        if !words.len().is_multiple_of(3 * stride) {
            let msg = format!("{} indices, not a whole number of triangles of {stride} indices a corner", words.len());
            return Err(format_err(file, at, msg));
        }
        vec![3; words.len() / stride / 3]
    };
    check_declared(counts.len())?;
    let mut out = Vec::with_capacity(counts.len());
    let mut i = 0usize;
    for (k, &n) in counts.iter().enumerate() {
        let end = n.checked_mul(stride).and_then(|w| w.checked_add(i)).filter(|&e| e <= words.len());
        let end = end.ok_or_else(|| format_err(file, format!("{at} polygon {k}"), "more indices than <p> holds"))?;
        out.push(words[i..end].join(" "));
        i = end;
    }
    if i != words.len() {
        let msg = format!("<p> holds {} indices, but <vcount> accounts for {i}", words.len());
        return Err(format_err(file, at, msg));
    }
    Ok(out)
}
