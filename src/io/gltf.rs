//! glTF 2.0 in (`.gltf` with its buffers embedded as `data:` URIs or in files
//! beside it, and binary `.glb`), `.glb` out.
//!
//! Read through the `gltf` crate (the Khronos format's reference Rust
//! implementation, kept by the gfx-rs group; its JSON is validated on
//! parsing). Every triangle primitive (triangles, strips and fans) of every
//! mesh node of the default scene (or of every root node when there is no
//! scene) is taken with its node's world transform (a mirroring transform
//! flips the winding back), with `TEXCOORD_0` (per corner), `COLOR_0` and
//! the material index per triangle kept (primitives without them get
//! defaults). glTF's `v` runs down the image: it is flipped on reading and
//! on writing, so texture coordinates follow OBJ's convention everywhere.
//! glTF splits vertices at every normal and UV seam, so coincident vertices
//! are welded ([`RawMesh::weld`]) to make the surface connected again.
//! Every accessor's range is checked against its buffer view and buffer
//! before it is read; sparse accessors are refused.
//!
//! Written: one mesh, one primitive with `POSITION`, `NORMAL`, `TEXCOORD_0`
//! and `COLOR_0` when the mesh has them (corners become vertices when there
//! are texture coordinates, since glTF's are per vertex), `u32` indices.

use super::raw::{RawMesh, format_err};
use super::resolve::Scope;
use super::{Format, Input, Keeps};
use crate::mesh::Mesh;
use crate::mesh::attributes::{Attributes, Material, Wrap};
use crate::{Error, Result};
use glam::{Mat4, Vec2, Vec3};
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Mode;
use rayon::prelude::*;
use std::borrow::Cow;
use std::path::Path;

/// The glTF row of [`super::FORMATS`].
pub(crate) const FORMAT: Format = Format {
    name: "glTF 2.0",
    extensions: &["gltf", "glb"],
    sniff: |b| b.starts_with(b"glTF") || b.trim_ascii_start().starts_with(b"{"),
    reader: Some(read),
    writer: Some(save),
    written_as: &["glb"],
    poly_writer: None,
    faces_writer: Some(|path, positions, corners, _, attrs| save_faces(path, positions, corners, attrs)),
    // material groups (a stage's prims among them) as meshes, one a group
    keeps: Keeps { uv: true, colors: true, materials: true, creases: false, holes: false },
};

/// Reads a `.gltf` or `.glb` file; buffers and images it names are found
/// beside it, inside its folder only.
///
/// # Errors
/// [`Error::Format`] naming the file and the element (buffer, accessor,
/// mesh, node); over the budget (node visits, vertices, faces, bytes).
fn read(input: &Input) -> Result<RawMesh> {
    let file = input.file;
    let g = document(input.bytes, file)?;
    let buffers = load_buffers(&g, input)?;
    let roots: Vec<usize> = match g.default_scene().or_else(|| g.scenes().next()) {
        Some(s) => s.nodes().map(|n| n.index()).collect(),
        None => {
            let mut child = vec![false; g.nodes().len()];
            for n in g.nodes() {
                for c in n.children() {
                    child[c.index()] = true;
                }
            }
            (0..child.len()).filter(|&n| !child[n]).collect()
        }
    };
    let nodes: Vec<gltf::Node> = g.nodes().collect();
    let mut walk = Walk { raw: None, buffers: &buffers, input };
    walk.nodes(&nodes, &roots)?;
    let mut raw = walk.raw.ok_or_else(|| format_err(file, "scene", "no mesh node with triangles"))?;
    raw.weld();
    if raw.materials.is_some() {
        input.budget.check("materials", g.materials().len() as u64, file, "materials")?;
        raw.material_list = g.materials().map(|m| material(&m, &buffers, input)).collect();
    }
    Ok(raw)
}

/// What is drawn of a glTF material: its base colour factor (linear RGB) as
/// the diffuse colour and its base colour texture (a file inside the
/// model's folder, or an image in a buffer view), with its sampler's wrap modes.
fn material(m: &gltf::Material, buffers: &[Vec<u8>], input: &Input) -> Material {
    let pbr = m.pbr_metallic_roughness();
    let [r, g, b, _] = pbr.base_color_factor();
    let name = format!("material {}", m.index().unwrap_or(0));
    let mut out = Material { diffuse: Vec3::new(r, g, b), ..Material::named(&name) };
    let Some(info) = pbr.base_color_texture() else { return out };
    let tex = info.texture();
    let wrap = |mode| match mode {
        gltf::texture::WrappingMode::ClampToEdge => Wrap::Clamp,
        gltf::texture::WrappingMode::MirroredRepeat => Wrap::Mirror,
        gltf::texture::WrappingMode::Repeat => Wrap::Repeat,
    };
    out.wrap = [wrap(tex.sampler().wrap_s()), wrap(tex.sampler().wrap_t())];
    let at = format!("image {}", tex.source().index());
    let warn = |e: &dyn std::fmt::Display| input.warnings.warn("textures that cannot be read", e.to_string());
    match tex.source().source() {
        gltf::image::Source::Uri { uri, .. } if uri.starts_with("data:") => {
            warn(&format!("{}: {at}: data URIs are not decoded", input.file));
        }
        gltf::image::Source::Uri { uri, .. } => match input.refs.resolve(uri, Scope::Folder, &at) {
            Ok(path) => {
                if input.textures {
                    out.texture = super::texture::load(input, &path, &at);
                }
                out.diffuse_texture = Some(path);
            }
            Err(e) => warn(&e),
        },
        gltf::image::Source::View { view, .. } if input.textures => {
            let bytes = buffers.get(view.buffer().index()).and_then(|b| {
                let end = view.offset().checked_add(view.length())?;
                b.get(view.offset()..end)
            });
            let decoded = match bytes {
                Some(b) => super::texture::decode(b, input.budget, input.file, &at),
                None => Err(format_err(input.file, &at, "its buffer view lies outside its buffer")),
            };
            match decoded {
                Ok(t) => out.texture = Some(std::sync::Arc::new(t)),
                Err(e) => warn(&format!("{e}; drawn without it")),
            }
        }
        gltf::image::Source::View { .. } => {}
    }
    out
}

/// Parses and validates the JSON. The POSITION accessor of every primitive
/// is checked first: `gltf-json` 1.4's validation indexes it unchecked and
/// panics on a missing one (found by `tests/io.rs`'s fuzzing).
fn document(bytes: &[u8], file: &str) -> Result<gltf::Gltf> {
    let err = |e: gltf::Error| format_err(file, "document", e.to_string());
    let g = gltf::Gltf::from_slice_without_validation(bytes).map_err(err)?;
    let json = g.document.into_json();
    for (m, mesh) in json.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            let pos = prim.attributes.get(&gltf::json::validation::Checked::Valid(gltf::Semantic::Positions));
            if let Some(i) = pos.filter(|i| i.value() >= json.accessors.len()) {
                let at = format!("mesh {m} primitive {p}");
                return Err(format_err(file, at, format!("POSITION accessor {} does not exist", i.value())));
            }
        }
    }
    Ok(gltf::Gltf { document: gltf::Document::from_json(json).map_err(err)?, blob: g.blob })
}

struct Walk<'a> {
    raw: Option<RawMesh>,
    buffers: &'a [Vec<u8>],
    input: &'a Input<'a>,
}

impl Walk<'_> {
    /// Takes every mesh node under `roots` with its world transform, depth
    /// first without recursion (a legal hierarchy may be thousands of nodes
    /// deep); every visit counts against `node-visits`, so a node graph
    /// that shares children, repeats roots or has a cycle ends there.
    fn nodes(&mut self, nodes: &[gltf::Node], roots: &[usize]) -> Result<()> {
        let max = self.input.budget.limits().node_visits;
        let mut stack: Vec<(usize, Mat4)> = roots.iter().rev().map(|&n| (n, Mat4::IDENTITY)).collect();
        let mut visits = 0u64;
        while let Some((index, parent)) = stack.pop() {
            let Some(node) = nodes.get(index) else { continue };
            visits += 1;
            if visits > max {
                let (file, element) = (self.input.file.to_string(), format!("node {index}"));
                return Err(Error::OverBudget { file, element, limit: "node-visits", value: visits, max });
            }
            let m = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
            if let Some(mesh) = node.mesh() {
                for prim in mesh.primitives() {
                    let at = format!("mesh {} primitive {}", mesh.index(), prim.index());
                    if let Some(p) = self.primitive(&prim, m, &at)? {
                        match &mut self.raw {
                            Some(r) => r.append(p),
                            None => self.raw = Some(p),
                        }
                    }
                }
            }
            let first = stack.len();
            stack.extend(node.children().map(|c| (c.index(), m)));
            stack[first..].reverse();
        }
        Ok(())
    }

    /// The counts a primitive adds, after checking its accessors: vertices
    /// and indices.
    fn counts(&self, prim: &gltf::Primitive) -> Result<(usize, usize)> {
        let file = self.input.file;
        for (semantic, acc) in prim.attributes() {
            check_accessor(&acc, self.buffers, file)?;
            check_kind(&semantic, &acc, file)?;
        }
        let nv = prim.get(&gltf::Semantic::Positions).map_or(0, |a| a.count());
        let Some(acc) = prim.indices() else { return Ok((nv, nv)) };
        check_accessor(&acc, self.buffers, file)?;
        let ok = matches!(acc.data_type(), DataType::U8 | DataType::U16 | DataType::U32)
            && acc.dimensions() == Dimensions::Scalar;
        if !ok {
            let what = format!("{:?} {:?} indices (unsigned scalars needed)", acc.data_type(), acc.dimensions());
            return Err(format_err(file, format!("accessor {}", acc.index()), what));
        }
        Ok((nv, acc.count()))
    }

    fn primitive(&self, prim: &gltf::Primitive, m: Mat4, at: &str) -> Result<Option<RawMesh>> {
        let file = self.input.file;
        if !matches!(prim.mode(), Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan) {
            log::info!("{file}: {at}: skipped ({:?}, not triangles)", prim.mode());
            return Ok(None);
        }
        // what this instance adds, counted before any of it is read
        let (nv, ni) = self.counts(prim)?;
        self.input.budget.take_vertices(nv as u64, file, at)?;
        let nt = if prim.mode() == Mode::Triangles { ni / 3 } else { ni.saturating_sub(2) };
        self.input.budget.take_faces(nt as u64, file, at)?;
        let reader = prim.reader(|b| self.buffers.get(b.index()).map(|v| v.as_slice()));
        let missing = || format_err(file, at, "no readable POSITION attribute");
        let positions: Vec<Vec3> =
            reader.read_positions().ok_or_else(missing)?.map(|p| m.transform_point3(p.into())).collect();
        if let Some(v) = positions.iter().position(|p| !p.is_finite()) {
            return Err(format_err(file, format!("{at} vertex {v}"), "non-finite position"));
        }
        let nv = positions.len() as u32;
        let list: Vec<u32> = match reader.read_indices() {
            Some(ix) => ix.into_u32().collect(),
            None => (0..nv).collect(),
        };
        if let Some(&bad) = list.iter().find(|&&i| i >= nv) {
            return Err(format_err(file, at, format!("index {bad}, but there are only {nv} vertices")));
        }
        let mut triangles = triangulate(prim.mode(), &list);
        if m.determinant() < 0.0 {
            triangles.chunks_exact_mut(3).for_each(|t| t.swap(1, 2));
        }
        // glTF's v runs down the image, OBJ's (and ours) up
        let uv: Option<Vec<Vec2>> =
            reader.read_tex_coords(0).map(|t| t.into_f32().map(|[u, v]| Vec2::new(u, 1.0 - v)).collect());
        let uv = uv.filter(|u| u.len() == positions.len()).map(|u| triangles.iter().map(|&i| u[i as usize]).collect());
        let colors: Option<Vec<Vec3>> = reader.read_colors(0).map(|c| c.into_rgb_f32().map(Vec3::from).collect());
        let colors = colors.filter(|c| c.len() == positions.len());
        let materials = prim.material().index().map(|i| vec![i as u32; triangles.len() / 3]);
        let mut raw = RawMesh::from_triangles(positions, triangles);
        (raw.uv, raw.colors, raw.materials) = (uv, colors, materials);
        Ok(Some(raw))
    }
}

/// Triangles of a primitive's index list in `mode` (strips alternate their
/// winding back, fans share the first vertex).
fn triangulate(mode: Mode, ix: &[u32]) -> Vec<u32> {
    match mode {
        Mode::TriangleStrip => (0..ix.len().saturating_sub(2))
            .flat_map(|i| if i % 2 == 0 { [ix[i], ix[i + 1], ix[i + 2]] } else { [ix[i + 1], ix[i], ix[i + 2]] })
            .collect(),
        Mode::TriangleFan => (1..ix.len().saturating_sub(1)).flat_map(|i| [ix[0], ix[i], ix[i + 1]]).collect(),
        _ => ix[..ix.len() / 3 * 3].to_vec(),
    }
}

/// Refuses an attribute accessor whose component type and dimensions the
/// glTF spec does not allow for its semantic (the `gltf` crate's readers
/// reach `unreachable!` on those; found by fuzzing).
fn check_kind(semantic: &gltf::Semantic, acc: &gltf::Accessor, file: &str) -> Result<()> {
    use DataType::{F32, U8, U16};
    let (t, d) = (acc.data_type(), acc.dimensions());
    let ok = match semantic {
        gltf::Semantic::Positions | gltf::Semantic::Normals => (t, d) == (F32, Dimensions::Vec3),
        gltf::Semantic::TexCoords(_) => matches!(t, F32 | U8 | U16) && d == Dimensions::Vec2,
        gltf::Semantic::Colors(_) => matches!(t, F32 | U8 | U16) && matches!(d, Dimensions::Vec3 | Dimensions::Vec4),
        _ => true,
    };
    if ok {
        return Ok(());
    }
    let what = format!("{t:?} {d:?} is not allowed for {semantic:?}");
    Err(format_err(file, format!("accessor {}", acc.index()), what))
}

/// Refuses an accessor whose bytes are not all inside its view and buffer
/// (checked arithmetic: no count can overflow) or that is sparse.
fn check_accessor(acc: &gltf::Accessor, buffers: &[Vec<u8>], file: &str) -> Result<()> {
    let at = format!("accessor {}", acc.index());
    if acc.sparse().is_some() {
        return Err(format_err(file, at, "sparse accessors are not supported"));
    }
    let view = acc.view().ok_or_else(|| format_err(file, &at, "no buffer view"))?;
    let buf = buffers.get(view.buffer().index()).ok_or_else(|| format_err(file, &at, "no buffer"))?;
    let size = acc.size();
    let stride = view.stride().unwrap_or(size);
    if stride < size {
        return Err(format_err(
            file,
            at,
            format!("buffer view {} has a byte stride of {stride}, less than its {size}-byte elements", view.index()),
        ));
    }
    let bytes = match acc.count() {
        0 => Some(0),
        n => (n - 1).checked_mul(stride).and_then(|b| b.checked_add(size)),
    };
    let end_in_view = bytes.and_then(|b| b.checked_add(acc.offset()));
    let view_end = view.offset().checked_add(view.length());
    match (end_in_view, view_end) {
        (Some(e), Some(ve)) if e <= view.length() && ve <= buf.len() => Ok(()),
        _ => Err(format_err(
            file,
            at,
            format!(
                "{} elements do not fit in buffer view {} of buffer {} ({} bytes)",
                acc.count(),
                view.index(),
                view.buffer().index(),
                buf.len()
            ),
        )),
    }
}

/// The bytes of every buffer: the GLB's binary chunk, `data:` URIs, or files
/// inside the model's folder (at most `byteLength` bytes of each).
fn load_buffers(g: &gltf::Gltf, input: &Input) -> Result<Vec<Vec<u8>>> {
    let file = input.file;
    g.buffers()
        .map(|b| {
            let at = format!("buffer {}", b.index());
            let data = match b.source() {
                gltf::buffer::Source::Bin => g.blob.clone().ok_or_else(|| format_err(file, &at, "no binary chunk"))?,
                gltf::buffer::Source::Uri(uri) => match uri.strip_prefix("data:") {
                    Some(d) => {
                        let (_, b64) =
                            d.split_once(";base64,").ok_or_else(|| format_err(file, &at, "data URI is not base64"))?;
                        base64(b64).ok_or_else(|| format_err(file, &at, "bad base64 in data URI"))?
                    }
                    None => {
                        let path = input.refs.resolve(uri, Scope::Folder, &at)?;
                        input.refs.read(&path, Some(b.length() as u64), &at)?
                    }
                },
            };
            if data.len() < b.length() {
                return Err(format_err(file, at, format!("{} bytes, but {} declared", data.len(), b.length())));
            }
            Ok(data)
        })
        .collect()
}

/// Standard base64 (padding optional); `None` on a bad character.
fn base64(s: &str) -> Option<Vec<u8>> {
    let val = |c: u8| -> Option<u32> {
        Some(match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' | b'-' => 62,
            b'/' | b'_' => 63,
            _ => return None,
        } as u32)
    };
    let s = s.trim_end_matches('=').as_bytes();
    let mut out = Vec::with_capacity(s.len() / 4 * 3 + 3);
    for chunk in s.chunks(4) {
        let mut acc = 0u32;
        for (k, &c) in chunk.iter().enumerate() {
            acc |= val(c)? << (18 - 6 * k);
        }
        let n = match chunk.len() {
            4 => 3,
            3 => 2,
            2 => 1,
            _ => return None,
        };
        out.extend_from_slice(&acc.to_be_bytes()[1..1 + n]);
    }
    Some(out)
}

/// One array of the primitive written: its attribute name (`None`: the
/// indices), its bytes, its element count, glTF type and component type,
/// and extra accessor JSON (bounds).
struct View<'a> {
    /// The attribute; `None`: the indices of the mesh called `mesh`.
    name: Option<&'static str>,
    mesh: String,
    bytes: Cow<'a, [u8]>,
    count: usize,
    ty: &'static str,
    ctype: u32,
    extra: String,
}

/// Little-endian bytes of plain values: their memory as it lies on a
/// little-endian machine; on a big-endian one, `to_le` of each, in parallel.
fn le_bytes<T: bytemuck::Pod + Sync>(a: &[T], to_le: impl Fn(&T) -> Vec<u8> + Sync + Send) -> Cow<'_, [u8]> {
    if cfg!(target_endian = "little") {
        Cow::Borrowed(bytemuck::cast_slice(a))
    } else {
        Cow::Owned(a.par_iter().flat_map_iter(to_le).collect())
    }
}

/// Points as little-endian bytes: per vertex, or picked per corner
/// (`per_corner`, the V table) in parallel.
fn points<'a>(a: &'a [Vec3], per_corner: Option<&[u32]>) -> Cow<'a, [u8]> {
    match per_corner {
        Some(v) => Cow::Owned(
            v.par_iter().flat_map_iter(|&i| a[i as usize].to_array().map(f32::to_le_bytes)).flatten().collect(),
        ),
        None => le_bytes(a, |p: &Vec3| p.to_array().iter().flat_map(|x| x.to_le_bytes()).collect()),
    }
}

/// Saves `mesh` as binary glTF (`.glb`) with vertex normals, and texture
/// coordinates and colours when `attrs` has them.
///
/// Every array's offset is known before any is written, so the file is
/// written in pieces of about 1 MB, in parallel, each at its offset;
/// positions, normals and indices go from memory as they lie when there are
/// no texture coordinates.
///
/// # Errors
/// I/O errors naming `path`; a mesh too large for a `.glb` (4 GiB).
pub(crate) fn save(path: &Path, mesh: &Mesh, attrs: &Attributes) -> Result<()> {
    save_faces(path, &mesh.positions, mesh.ct.v_table(), attrs)
}

/// [`save`] of the triangles `v` (a V table) over the vertices `positions`.
///
/// # Errors
/// As [`save`].
pub(crate) fn save_faces(path: &Path, positions: &[Vec3], v: &[u32], attrs: &Attributes) -> Result<()> {
    let normals = crate::mesh::normals::face_vertex_normals(v, positions);
    let uv = attrs.uv.as_ref().filter(|u| u.len() == v.len());
    let colors = attrs.colors.as_ref().filter(|c| c.len() == positions.len());
    // with per-corner UVs every corner is its own vertex
    let per_corner = uv.map(|_| v);
    let (lo, hi) = crate::mesh::bounds_of(positions);
    let minmax = format!(",\"min\":[{},{},{}],\"max\":[{},{},{}]", lo.x, lo.y, lo.z, hi.x, hi.y, hi.z);
    let n = if uv.is_some() { v.len() } else { positions.len() };
    let view =
        |name, bytes, count, ty, ctype, extra| View { name, bytes, count, ty, ctype, extra, mesh: String::new() };
    let mut views = vec![
        view(Some("POSITION"), points(positions, per_corner), n, "VEC3", 5126, minmax),
        view(Some("NORMAL"), points(&normals, per_corner), n, "VEC3", 5126, String::new()),
    ];
    if let Some(uv) = uv {
        let flipped = uv.par_iter().flat_map_iter(|t| [t.x, 1.0 - t.y].map(f32::to_le_bytes)).flatten().collect();
        views.push(view(Some("TEXCOORD_0"), Cow::Owned(flipped), n, "VEC2", 5126, String::new()));
    }
    if let Some(c) = colors {
        views.push(view(Some("COLOR_0"), points(c, per_corner), n, "VEC3", 5126, String::new()));
    }
    match meshes(v.len() / 3, attrs) {
        None => {
            let indices = match uv {
                Some(_) => Cow::Owned((0..v.len() as u32).into_par_iter().flat_map_iter(u32::to_le_bytes).collect()),
                None => le_bytes(v, |i: &u32| i.to_le_bytes().to_vec()),
            };
            views.push(view(None, indices, v.len(), "SCALAR", 5125, String::new()));
        }
        Some(groups) => {
            // one mesh a group, each with the indices of its triangles
            for (name, tris) in groups {
                let index = |c: u32| if uv.is_some() { c } else { v[c as usize] };
                let bytes: Vec<u8> =
                    tris.iter().flat_map(|&t| (3 * t..3 * t + 3).flat_map(|c| index(c).to_le_bytes())).collect();
                let mut w = view(None, Cow::Owned(bytes), 3 * tris.len(), "SCALAR", 5125, String::new());
                w.mesh = name;
                views.push(w);
            }
        }
    }
    let (head, offsets) = glb_head(&views, path)?;
    // pieces: the head, then every array in slices of about 1 MB
    const SLICE: usize = 1 << 20;
    let mut pieces: Vec<(u64, &[u8])> = vec![(0, &head[..])];
    for (w, &at) in views.iter().zip(&offsets) {
        pieces.extend(w.bytes.chunks(SLICE).enumerate().map(|(k, b)| ((head.len() + at + k * SLICE) as u64, b)));
    }
    super::atomic_write_pieces(path, pieces.len(), |k| (pieces[k].0, Cow::Borrowed(pieces[k].1)))
}

/// The meshes of triangles to write, when the material groups make more
/// than one: a scene's prims (named by their paths), else the groups
/// (named by their materials), each with its triangles.
fn meshes(nt: usize, attrs: &Attributes) -> Option<Vec<(String, Vec<u32>)>> {
    let m = attrs.materials.as_ref().filter(|m| m.face.len() == nt)?;
    let scene = m.scene.as_deref().filter(|s| s.prim_of.len() == m.list.len());
    let (names, of): (Vec<String>, Box<dyn Fn(u32) -> usize>) = match scene {
        Some(s) => (s.prims.iter().map(|p| p.path.clone()).collect(), Box::new(|g| s.prim_of[g as usize] as usize)),
        None => (m.list.iter().map(|x| x.name.clone()).collect(), Box::new(|g| g as usize)),
    };
    let mut out: Vec<(String, Vec<u32>)> = names.into_iter().map(|n| (n, Vec::new())).collect();
    for (t, &g) in m.face.iter().enumerate() {
        if let Some(x) = out.get_mut(of(g)) {
            x.1.push(t as u32);
        }
    }
    out.retain(|x| !x.1.is_empty());
    (out.len() > 1).then_some(out)
}

/// A JSON string literal of `s`.
fn json_string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 => out.push_str(&format!("\\u{:04x}", c as u32)),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// The `.glb` header, JSON chunk and binary chunk header for `views` laid
/// out one after the other (each a multiple of 4 bytes), and each view's
/// offset in the binary chunk.
fn glb_head(views: &[View], path: &Path) -> Result<(Vec<u8>, Vec<usize>)> {
    let (mut json_views, mut accessors, mut attributes, mut offsets) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut indices = Vec::new();
    let mut offset = 0usize;
    for (i, w) in views.iter().enumerate() {
        let (len, target) = (w.bytes.len(), if w.name.is_some() { 34962 } else { 34963 });
        json_views.push(format!("{{\"buffer\":0,\"byteOffset\":{offset},\"byteLength\":{len},\"target\":{target}}}"));
        accessors.push(format!(
            "{{\"bufferView\":{i},\"componentType\":{},\"count\":{},\"type\":\"{}\"{}}}",
            w.ctype, w.count, w.ty, w.extra
        ));
        match w.name {
            Some(name) => attributes.push(format!("\"{name}\":{i}")),
            None => indices.push((i, w.mesh.as_str())),
        }
        offsets.push(offset);
        offset += len;
    }
    let attributes = attributes.join(",");
    let named = |name: &str| if name.is_empty() { String::new() } else { format!("\"name\":{},", json_string(name)) };
    let meshes: Vec<String> = indices
        .iter()
        .map(|(i, name)| {
            format!(
                "{{{}\"primitives\":[{{\"attributes\":{{{attributes}}},\"indices\":{i},\"mode\":4}}]}}",
                named(name)
            )
        })
        .collect();
    let nodes: Vec<String> =
        indices.iter().enumerate().map(|(k, (_, name))| format!("{{{}\"mesh\":{k}}}", named(name))).collect();
    let roots: Vec<String> = (0..nodes.len()).map(|k| k.to_string()).collect();
    let json = format!(
        "{{\"asset\":{{\"version\":\"2.0\",\"generator\":\"subdiv\"}},\"scene\":0,\"scenes\":[{{\"nodes\":[{}]}}],\"nodes\":[{}],\"meshes\":[{}],\"buffers\":[{{\"byteLength\":{offset}}}],\"bufferViews\":[{}],\"accessors\":[{}]}}",
        roots.join(","),
        nodes.join(","),
        meshes.join(","),
        json_views.join(","),
        accessors.join(",")
    );
    let mut json = json.into_bytes();
    json.resize(json.len().next_multiple_of(4), b' ');
    // every view holds 4-byte values, so the binary chunk needs no padding
    let total = 12 + 8 + json.len() + 8 + offset;
    let too_large = || Error::Usage(format!("{}: too large for a .glb (4 GiB)", path.display()));
    let total = u32::try_from(total).map_err(|_| too_large())?;
    let bin_len = u32::try_from(offset).map_err(|_| too_large())?;
    let mut head = Vec::with_capacity(28 + json.len());
    head.extend_from_slice(b"glTF");
    head.extend_from_slice(&2u32.to_le_bytes());
    head.extend_from_slice(&total.to_le_bytes());
    head.extend_from_slice(&(json.len() as u32).to_le_bytes());
    head.extend_from_slice(b"JSON");
    head.extend_from_slice(&json);
    head.extend_from_slice(&bin_len.to_le_bytes());
    head.extend_from_slice(b"BIN\0");
    Ok((head, offsets))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_glb_written_in_parallel_pieces_reads_back_as_the_mesh() {
        // every array in several 1 MB slices, and a last partial one
        let m = crate::mesh::shapes::icosphere(7);
        assert!(m.ct.v_table().len() * 4 > 3 << 20 && m.positions.len() * 12 > 1 << 20);
        let dir = crate::io::TestDir::new("glb-pieces");
        let path = dir.0.join("m.glb");
        save(&path, &m, &Attributes::default()).expect("saved");
        let bytes = std::fs::read(&path).expect("read back");
        let src = crate::io::Source::Bytes { bytes: &bytes, name: "m.glb", folder: None };
        let back = crate::io::read(src, &Default::default()).expect("a valid glb").mesh;
        // the icosphere has no coincident vertices, so nothing is welded
        assert!(back.positions == m.positions, "positions");
        assert!(back.ct.v_table() == m.ct.v_table(), "triangles");
        // the normals: the binary chunk's second array, after the positions
        let json_len = u32::from_le_bytes(bytes[12..16].try_into().expect("4 bytes")) as usize;
        let at = 20 + json_len + 8 + 12 * m.positions.len();
        let normals: Vec<f32> = bytes[at..at + 12 * m.positions.len()]
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect();
        for (n, p) in normals.chunks_exact(3).zip(&m.positions) {
            // a sphere's vertex normal points along the vertex
            assert!(Vec3::from_slice(n).dot(p.normalize()) > 0.999);
        }
    }
}
