//! Writing a mesh as a USD layer (`.usda` text, `.usdc` crate, `.usdz`
//! package of one crate layer): one Mesh prim per material group whose
//! name is a prim path (the prims a stage was read from), else one
//! `/Mesh`, each with its own vertices, the options as USD's attributes
//! (written even where they are USD's defaults, since ours differ),
//! creases and corners at the mesh's level, holes, `primvars:st`
//! (faceVarying, indexed) and `primvars:displayColor` (vertex, or uniform
//! where the prim's colours are per face); a scene's prims keep their
//! paths, options and transforms (see the module above).

use crate::io::atomic_write;
use crate::mesh::Mesh;
use crate::mesh::attributes::Attributes;
use crate::mesh::options::{FileScheme, ShapeOptions, TriangleSubdivision};
use crate::mesh::poly::PolyMesh;
use crate::mesh::scene::{Prim, UpAxis};
use crate::mesh::sharpness::{BoundaryInterpolation, Tags};
use crate::{Error, Result};
use glam::{DMat4, Vec2, Vec3};
use openusd::gf;
use openusd::sdf::{self, ChildrenKey, FieldKey, SpecType, Specifier, Value, Variability};
use std::path::Path;

/// A mesh as the writer sees it: polygons with their corners' vertices.
struct Faces<'a> {
    positions: &'a [Vec3],
    /// Corners of each face (`n + 1` offsets).
    starts: Vec<usize>,
    corners: &'a [u32],
    tags: Tags,
    holes: &'a [u32],
}

impl Faces<'_> {
    /// Whether vertex `v` belongs to exactly one face.
    fn one_face(&self, v: u32) -> bool {
        self.corners.iter().filter(|&&x| x == v).take(2).count() == 1
    }
}

/// Saves a triangle mesh (a polygon one goes through [`save_poly`]).
///
/// # Errors
/// An I/O error or one from the USD writer, naming `path`.
pub(super) fn save(path: &Path, mesh: &Mesh, attrs: &Attributes) -> Result<()> {
    let n = mesh.ct.num_triangles();
    let tags = mesh.ct.sharpness().map(|s| s.to_tags(&mesh.ct)).unwrap_or_default();
    let faces = Faces {
        positions: &mesh.positions,
        starts: (0..=n).map(|f| 3 * f).collect(),
        corners: mesh.ct.v_table(),
        tags,
        holes: mesh.ct.holes(),
    };
    write(path, &faces, attrs)
}

/// Saves a polygon mesh.
///
/// # Errors
/// As [`save`].
pub(super) fn save_poly(path: &Path, mesh: &PolyMesh, attrs: &Attributes) -> Result<()> {
    let pt = &mesh.pt;
    let mut starts: Vec<usize> = (0..pt.num_faces() as u32).map(|f| pt.face_corners(f).start as usize).collect();
    starts.push(pt.num_corners());
    let tags = pt.sharpness().map(|s| s.to_tags(pt)).unwrap_or_default();
    let faces = Faces { positions: &mesh.positions, starts, corners: pt.v_table(), tags, holes: pt.holes() };
    write(path, &faces, attrs)
}

/// The layer's bytes in the format `path`'s extension names, written atomically.
fn write(path: &Path, faces: &Faces, attrs: &Attributes) -> Result<()> {
    let data = layer(faces, attrs).map_err(|e| usd_err(path, e))?;
    let ext = crate::io::ext(path);
    let bytes = match ext.as_str() {
        "usda" => openusd::usda::TextWriter::write_to_string(&data).map(String::into_bytes),
        _ => {
            let mut crate_bytes = std::io::Cursor::new(Vec::new());
            openusd::usdc::CrateWriter::write(&data, &mut crate_bytes).map(|_| crate_bytes.into_inner())
        }
    }
    .map_err(|e| usd_err(path, e))?;
    let bytes = if ext == "usdz" { package(&bytes).map_err(|e| usd_err(path, e))? } else { bytes };
    atomic_write(path, |w| w.write_all(&bytes).map_err(|e| Error::io(path, e)))
}

fn usd_err(path: &Path, e: anyhow::Error) -> Error {
    Error::Usage(format!("{}: USD writer: {}", path.display(), crate::error::clean(&format!("{e:#}"), 200)))
}

/// A `.usdz` package holding the crate layer `bytes`.
fn package(bytes: &[u8]) -> anyhow::Result<Vec<u8>> {
    let mut w = openusd::usdz::ArchiveWriter::new(std::io::Cursor::new(Vec::new()));
    w.add_layer("mesh.usdc", bytes)?;
    Ok(w.finish()?.into_inner())
}

/// One prim to write: its path, its faces and what the scene says of it
/// (its options, transform and colours; a mesh from another format has
/// none: then the mesh's options, no transform).
struct Written<'a> {
    path: String,
    faces: Vec<usize>,
    prim: Option<&'a Prim>,
}

/// The prims to write: the scene's (each face's by its material group),
/// else one per group named by a prim path (a stage written before scenes
/// were kept), else one `/Mesh`.
fn prims<'a>(faces: &Faces, attrs: &'a Attributes) -> Vec<Written<'a>> {
    let nf = faces.starts.len() - 1;
    let groups = attrs.materials.as_ref().filter(|m| m.face.len() == nf && !m.list.is_empty());
    let whole = || vec![Written { path: "/Mesh".to_string(), faces: (0..nf).collect(), prim: None }];
    let Some(m) = groups else { return whole() };
    let scene = m.scene.as_deref().filter(|s| s.prim_of.len() == m.list.len());
    let mut out: Vec<Written> = match scene {
        Some(s) => s.prims.iter().map(|p| Written { path: p.path.clone(), faces: Vec::new(), prim: Some(p) }).collect(),
        None if m.list.iter().all(|x| x.name.starts_with('/') && sdf::path(&x.name).is_ok()) => {
            m.list.iter().map(|x| Written { path: x.name.clone(), faces: Vec::new(), prim: None }).collect()
        }
        None => return whole(),
    };
    for (f, &g) in m.face.iter().enumerate() {
        let k = scene.map_or(g, |s| s.prim_of[g as usize]);
        if let Some(p) = out.get_mut(k as usize) {
            p.faces.push(f);
        }
    }
    out.retain(|p| !p.faces.is_empty() && sdf::path(&p.path).is_ok());
    out
}

/// The layer: every prim's ancestors as Xforms, then its Mesh.
fn layer(faces: &Faces, attrs: &Attributes) -> anyhow::Result<sdf::Data> {
    let mut data = sdf::Data::new();
    let root = sdf::Path::abs_root();
    data.create_spec(root.clone(), SpecType::PseudoRoot);
    let prims = prims(faces, attrs);
    for (k, w) in prims.iter().enumerate() {
        let path = sdf::path(&w.path)?;
        define(&mut data, &path, "Mesh")?;
        if k == 0 {
            let top = w.path.trim_start_matches('/').split('/').next().unwrap_or("Mesh").to_string();
            if let Some(s) = data.spec_mut(&root) {
                s.add(FieldKey::DefaultPrim, Value::Token(top.into()));
            }
        }
        mesh(&mut data, &path, faces, w, attrs)?;
    }
    let scene = attrs.materials.as_ref().and_then(|m| m.scene.as_deref());
    if let (Some(s), Some(spec)) = (scene, data.spec_mut(&root)) {
        if let Some(up) = s.up_axis {
            spec.add("upAxis", Value::Token(if up == UpAxis::Z { "Z" } else { "Y" }.into()));
        }
        if let Some(m) = s.meters_per_unit {
            spec.add("metersPerUnit", Value::Double(m));
        }
    }
    Ok(data)
}

/// Defines the prim `path` of type `ty` and any missing ancestor (as Xform).
fn define(data: &mut sdf::Data, path: &sdf::Path, ty: &str) -> anyhow::Result<()> {
    let parent = path.parent().unwrap_or_else(sdf::Path::abs_root);
    if parent != sdf::Path::abs_root() && data.spec(&parent).is_none() {
        define(data, &parent, "Xform")?;
    }
    let name = path.name().unwrap_or_default().to_string();
    if let Some(p) = data.spec_mut(&parent) {
        let mut children = match p.get(ChildrenKey::PrimChildren.as_str()) {
            Some(Value::TokenVec(v)) => v.clone(),
            _ => Vec::new(),
        };
        children.push(name.into());
        p.add(ChildrenKey::PrimChildren, Value::TokenVec(children));
    }
    let spec = data.create_spec(path.clone(), SpecType::Prim);
    spec.add(FieldKey::Specifier, Value::Specifier(Specifier::Def));
    spec.add(FieldKey::TypeName, Value::Token(ty.into()));
    Ok(())
}

/// One attribute of `prim`, listed among its properties.
fn attribute(
    data: &mut sdf::Data,
    prim: &sdf::Path,
    name: &str,
    ty: &str,
    value: Value,
    uniform: bool,
) -> anyhow::Result<()> {
    add_attribute(data, prim, name, ty, value, uniform, None)
}

/// As [`attribute`], with the primvar `interpolation` when given.
fn add_attribute(
    data: &mut sdf::Data,
    prim: &sdf::Path,
    name: &str,
    ty: &str,
    value: Value,
    uniform: bool,
    interpolation: Option<&str>,
) -> anyhow::Result<()> {
    if let Some(p) = data.spec_mut(prim) {
        let mut props = match p.get(ChildrenKey::PropertyChildren.as_str()) {
            Some(Value::TokenVec(v)) => v.clone(),
            _ => Vec::new(),
        };
        props.push(name.into());
        p.add(ChildrenKey::PropertyChildren, Value::TokenVec(props));
    }
    let spec = data.create_spec(prim.append_property(name)?, SpecType::Attribute);
    spec.add(FieldKey::TypeName, Value::Token(ty.into()));
    spec.add(FieldKey::Custom, Value::Bool(false));
    if uniform {
        spec.add(FieldKey::Variability, Value::Variability(Variability::Uniform));
    }
    if let Some(i) = interpolation {
        spec.add("interpolation", Value::Token(i.into()));
    }
    spec.add(FieldKey::Default, value);
    Ok(())
}

/// The Mesh at `prim`: the faces of `w` on their own vertices, in the
/// prim's own space under its transform.
fn mesh(data: &mut sdf::Data, prim: &sdf::Path, faces: &Faces, w: &Written, attrs: &Attributes) -> anyhow::Result<()> {
    let fs = &w.faces[..];
    // the prim's vertices in their order in the mesh
    let mut local_ids = vec![u32::MAX; faces.positions.len()];
    for &f in fs {
        for &v in &faces.corners[faces.starts[f]..faces.starts[f + 1]] {
            local_ids[v as usize] = 0;
        }
    }
    let mut used = Vec::new();
    for (v, l) in local_ids.iter_mut().enumerate() {
        if *l == 0 {
            *l = used.len() as u32;
            used.push(v);
        }
    }
    let v3 = |p: Vec3| gf::Vec3f { x: p.x, y: p.y, z: p.z };
    let world = w.prim.map_or(DMat4::IDENTITY, |p| DMat4::from_cols_array(&p.transform));
    let local = world.inverse();
    let moved = world != DMat4::IDENTITY && local.is_finite();
    let point = |p: Vec3| if moved { local.transform_point3(p.as_dvec3()).as_vec3() } else { p };
    let points = used.iter().map(|&v| v3(point(faces.positions[v]))).collect();
    let counts = fs.iter().map(|&f| (faces.starts[f + 1] - faces.starts[f]) as i32).collect();
    let corner_ids: Vec<usize> = fs.iter().flat_map(|&f| faces.starts[f]..faces.starts[f + 1]).collect();
    let indices = corner_ids.iter().map(|&c| local_ids[faces.corners[c] as usize] as i32).collect();
    attribute(data, prim, "points", "point3f[]", Value::Vec3fVec(points), false)?;
    attribute(data, prim, "faceVertexCounts", "int[]", Value::IntVec(counts), false)?;
    attribute(data, prim, "faceVertexIndices", "int[]", Value::IntVec(indices), false)?;
    if moved {
        let m = Value::Matrix4d(gf::Matrix4d(world.to_cols_array()));
        attribute(data, prim, "xformOp:transform", "matrix4d", m, false)?;
        let order = Value::TokenVec(vec!["xformOp:transform".into()]);
        attribute(data, prim, "xformOpOrder", "token[]", order, true)?;
    }
    let options_of = w.prim.map_or(attrs.options, |p| p.options);
    options(data, prim, options_of)?;
    sharp(data, prim, faces, fs, &local_ids, options_of)?;
    if let Some(uv) = attrs.uv.as_ref().filter(|u| u.len() == faces.corners.len()) {
        // one value per vertex and texture coordinate: the seams the
        // surface was refined with (see weld_uvs)
        let corner_vertex: Vec<u32> = corner_ids.iter().map(|&c| faces.corners[c]).collect();
        let corner_uv: Vec<Vec2> = corner_ids.iter().map(|&c| uv[c]).collect();
        let (values, index) = crate::mesh::attributes::weld_uvs(&corner_vertex, &corner_uv);
        let st = values.iter().map(|t| gf::Vec2f { x: t.x, y: t.y }).collect();
        add_attribute(data, prim, "primvars:st", "texCoord2f[]", Value::Vec2fVec(st), false, Some("faceVarying"))?;
        let index = index.into_iter().map(|i| i as i32).collect();
        attribute(data, prim, "primvars:st:indices", "int[]", Value::IntVec(index), false)?;
    }
    // a prim's colours per face are its groups'; the others' per vertex
    if let Some(m) = attrs.materials.as_ref().filter(|_| w.prim.is_some_and(|p| p.face_colors)) {
        let col =
            fs.iter().map(|&f| v3(m.list.get(m.face[f] as usize).map_or(Vec3::splat(0.8), |x| x.diffuse))).collect();
        add_attribute(data, prim, "primvars:displayColor", "color3f[]", Value::Vec3fVec(col), false, Some("uniform"))?;
    } else if let Some(c) = attrs.colors.as_ref().filter(|c| c.len() == faces.positions.len()) {
        let col = used.iter().map(|&v| v3(c[v])).collect();
        add_attribute(data, prim, "primvars:displayColor", "color3f[]", Value::Vec3fVec(col), false, Some("vertex"))?;
    }
    Ok(())
}

/// The subdivision attributes: every one written, since USD's defaults
/// (edgeAndCorner, cornersPlus1) are not ours.
fn options(data: &mut sdf::Data, prim: &sdf::Path, o: ShapeOptions) -> anyhow::Result<()> {
    let token = |t: &str| Value::Token(t.into());
    let boundary = match o.boundary.unwrap_or_default() {
        BoundaryInterpolation::None => "none",
        BoundaryInterpolation::EdgeOnly => "edgeOnly",
        BoundaryInterpolation::EdgeAndCorner => "edgeAndCorner",
    };
    let fvar = o.fvar.unwrap_or_default();
    let fvar = super::read::FVAR.iter().find(|(_, m)| *m == fvar).map_or("cornersOnly", |(t, _)| t);
    let tri = match o.triangles.unwrap_or_default() {
        TriangleSubdivision::Catmark => "catmullClark",
        TriangleSubdivision::Smooth => "smooth",
    };
    let scheme = o.scheme.unwrap_or(FileScheme::CatmullClark).token();
    attribute(data, prim, "subdivisionScheme", "token", token(scheme), true)?;
    attribute(data, prim, "interpolateBoundary", "token", token(boundary), false)?;
    attribute(data, prim, "faceVaryingLinearInterpolation", "token", token(fvar), false)?;
    attribute(data, prim, "triangleSubdivisionRule", "token", token(tri), false)?;
    attribute(data, prim, "orientation", "token", token("rightHanded"), true)
}

/// Creases (one per sharp edge), corners and holes of the faces `fs`.
fn sharp(
    data: &mut sdf::Data,
    prim: &sdf::Path,
    faces: &Faces,
    fs: &[usize],
    local: &[u32],
    options: ShapeOptions,
) -> anyhow::Result<()> {
    let id = |v: u32| local.get(v as usize).copied().filter(|&l| l != u32::MAX);
    let mut creases = (Vec::new(), Vec::new());
    for c in &faces.tags.creases {
        if let (Some(a), Some(b)) = (id(c.v0), id(c.v1)) {
            creases.0.extend([a as i32, b as i32]);
            creases.1.push(c.sharpness);
        }
    }
    if !creases.1.is_empty() {
        let lengths = vec![2; creases.1.len()];
        attribute(data, prim, "creaseIndices", "int[]", Value::IntVec(creases.0), false)?;
        attribute(data, prim, "creaseLengths", "int[]", Value::IntVec(lengths), false)?;
        attribute(data, prim, "creaseSharpnesses", "float[]", Value::FloatVec(creases.1), false)?;
    }
    // edgeAndCorner's own corners (a vertex of one face) are not written: USD adds them
    let implied = |v: u32| options.boundary == Some(BoundaryInterpolation::EdgeAndCorner) && faces.one_face(v);
    let corners: Vec<(i32, f32)> = faces
        .tags
        .corners
        .iter()
        .filter(|c| !(c.sharpness >= crate::mesh::sharpness::INFINITE && implied(c.vertex)))
        .filter_map(|c| Some((id(c.vertex)? as i32, c.sharpness)))
        .collect();
    if !corners.is_empty() {
        let (ids, s): (Vec<i32>, Vec<f32>) = corners.into_iter().unzip();
        attribute(data, prim, "cornerIndices", "int[]", Value::IntVec(ids), false)?;
        attribute(data, prim, "cornerSharpnesses", "float[]", Value::FloatVec(s), false)?;
    }
    let mut hole = vec![false; faces.starts.len()];
    for &h in faces.holes {
        if let Some(x) = hole.get_mut(h as usize) {
            *x = true;
        }
    }
    let holes: Vec<i32> = fs.iter().enumerate().filter(|(_, f)| hole[**f]).map(|(k, _)| k as i32).collect();
    if !holes.is_empty() {
        attribute(data, prim, "holeIndices", "int[]", Value::IntVec(holes), false)?;
    }
    Ok(())
}
