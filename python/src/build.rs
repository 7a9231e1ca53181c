//! From checked arrays to the library's validated tables, and back: the
//! renumbering that keeps the input's vertex order and carries the vertices
//! no face uses.

use crate::arrays::{Faces, flat_f64, ids_i64};
use crate::guard::{Msg, msg};
use glam::Vec3;
use subdiv::io::{RawMesh, Topology};
use subdiv::mesh::{CreaseTag, Tags};
use subdiv::mesh::{PolyMesh, PolyTable};
use subdiv::{CornerTable, Mesh, Scheme};

/// The control mesh as the library holds it.
pub enum Control {
    /// A triangle corner table (the triangle schemes).
    Tri(Mesh),
    /// A polygon table (Catmull-Clark, bilinear).
    Poly(PolyMesh),
}

/// How the library's vertex ids map back to the caller's.
#[derive(Clone, Debug, Default)]
pub struct Remap {
    /// Vertices the caller passed (or the repaired mesh has).
    pub n_input: usize,
    /// The caller's id of each control vertex the library kept, when it
    /// dropped some (`None`: the same ids).
    pub kept: Option<Vec<u32>>,
}

impl Remap {
    /// Control vertices the library holds.
    fn n_kept(&self) -> usize {
        self.kept.as_ref().map_or(self.n_input, Vec::len)
    }
    /// The caller's id of the library's vertex `j` (new vertices follow
    /// the caller's `n_input`).
    pub fn id(&self, j: u32) -> i64 {
        let nk = self.n_kept();
        match &self.kept {
            Some(k) if (j as usize) < nk => i64::from(k[j as usize]),
            _ if (j as usize) < nk => i64::from(j),
            _ => (j as usize - nk + self.n_input) as i64,
        }
    }
    /// Every vertex id of `v` in the caller's numbering.
    pub fn ids(&self, v: &[u32]) -> Vec<i64> {
        if self.kept.is_none() {
            return ids_i64(v, i64::from);
        }
        ids_i64(v, |j| self.id(j))
    }
    /// The refined positions `fine` as flat rows in the caller's numbering,
    /// the vertices no face uses carried from `input` (flat) unchanged.
    pub fn positions<P: crate::arrays::Point>(&self, fine: &[P], input: &[f64]) -> Vec<f64> {
        let Some(kept) = &self.kept else { return flat_f64(fine) };
        let nk = kept.len();
        let mut out = Vec::with_capacity(3 * (self.n_input + fine.len().saturating_sub(nk)));
        out.extend_from_slice(&input[..3 * self.n_input]);
        for (j, &i) in kept.iter().enumerate() {
            out[3 * i as usize..3 * i as usize + 3].copy_from_slice(&fine[j].xyz());
        }
        out.extend(flat_f64(&fine[nk.min(fine.len())..]));
        out
    }
    /// The control positions in f64 as the library numbers them: the
    /// caller's rows `input` (flat) of the kept vertices, or, with `own`
    /// (after a repair, which renumbers, or for float32 input), the mesh's
    /// own `positions` widened.
    pub fn control_f64(&self, input: &[f64], positions: &[Vec3], own: bool) -> Vec<glam::DVec3> {
        if own {
            return positions.iter().map(|p| p.as_dvec3()).collect();
        }
        let row = |i: usize| glam::DVec3::from_slice(&input[3 * i..3 * i + 3]);
        match &self.kept {
            Some(k) => k.iter().map(|&i| row(i as usize)).collect(),
            None => (0..positions.len()).map(row).collect(),
        }
    }
    /// The caller's id to the library's (`None`: a vertex no face uses).
    pub fn inverse(&self) -> impl Fn(u32) -> Option<u32> + '_ {
        let mut inv = Vec::new();
        if let Some(k) = &self.kept {
            inv = vec![u32::MAX; self.n_input];
            for (j, &i) in k.iter().enumerate() {
                inv[i as usize] = j as u32;
            }
        }
        move |i| match &self.kept {
            None => Some(i),
            Some(_) => inv.get(i as usize).copied().filter(|&j| j != u32::MAX),
        }
    }
}

/// What to build: the scheme decides between triangles and polygons.
pub struct Request<'a> {
    /// The positions, checked.
    pub positions: Vec<Vec3>,
    /// The faces, checked.
    pub faces: &'a Faces,
    /// Whether a polygon table is wanted (Catmull-Clark, bilinear).
    pub scheme: Scheme,
    /// Repair instead of refusing a non-manifold mesh.
    pub repair: bool,
    /// Creases `(v0, v1, sharpness)` in the caller's ids, and the faces
    /// that are holes (the caller's face ids, checked).
    pub tags: (&'a [(u32, u32, f32)], &'a [u32]),
}

/// The corners of the faces of `v` (`k` each) that are no holes (`holes`
/// sorted, as the tables keep them), in the caller's numbering: the
/// faces the library's faces-only levels give.
pub fn face_ids(remap: &Remap, v: &[u32], k: usize, holes: &[u32]) -> Vec<i64> {
    if holes.is_empty() || k == 0 {
        return remap.ids(v);
    }
    let mut out = Vec::with_capacity(v.len());
    for (f, face) in v.chunks_exact(k).enumerate() {
        if holes.binary_search(&(f as u32)).is_err() {
            out.extend(face.iter().map(|&j| remap.id(j)));
        }
    }
    out
}

/// The validated (or repaired) control mesh and its renumbering.
///
/// # Errors
/// The library's message for a mesh it refuses; polygons for a triangle
/// scheme; creases with `repair`.
pub fn control(req: Request<'_>) -> Result<(Control, Remap), Msg> {
    let poly = req.scheme.is_polygonal();
    if !poly && !req.faces.all_triangles() {
        return Err(format!(
            "the {} scheme takes triangles (faces of shape (m, 3)); use catmull-clark or bilinear for polygons",
            req.scheme
        ));
    }
    let (creases, holes) = req.tags;
    if req.repair {
        if !creases.is_empty() || !holes.is_empty() {
            return Err("creases and holes cannot be combined with repair=True (the repair renumbers)".into());
        }
        return repaired(req.positions, req.faces, poly);
    }
    let n_input = req.positions.len();
    let (c, kept) = if poly {
        let (pt, _, kept) =
            PolyTable::build(n_input, &req.faces.starts, &req.faces.corners, Some(&req.positions)).map_err(msg)?;
        let pt = if holes.is_empty() { pt } else { pt.with_holes(holes.to_vec()) };
        (Control::Poly(PolyMesh { pt, positions: kept_positions(req.positions, kept.as_deref()) }), kept)
    } else {
        let (ct, _, kept) = CornerTable::build(n_input, &req.faces.corners, Some(&req.positions)).map_err(msg)?;
        let ct = if holes.is_empty() { ct } else { ct.with_holes(holes.to_vec()) };
        (Control::Tri(Mesh { ct, positions: kept_positions(req.positions, kept.as_deref()) }), kept)
    };
    let remap = Remap { n_input, kept };
    let tags = tags(creases, &remap)?;
    let c = if tags.is_empty() {
        c
    } else {
        match c {
            Control::Tri(Mesh { ct, positions }) => {
                Control::Tri(Mesh { ct: ct.with_tags(&tags).map_err(msg)?, positions })
            }
            Control::Poly(PolyMesh { pt, positions }) => {
                Control::Poly(PolyMesh { pt: pt.with_tags(&tags).map_err(msg)?, positions })
            }
        }
    };
    Ok((c, remap))
}

/// The positions of the kept vertices.
fn kept_positions(positions: Vec<Vec3>, kept: Option<&[u32]>) -> Vec<Vec3> {
    match kept {
        Some(k) => k.iter().map(|&i| positions[i as usize]).collect(),
        None => positions,
    }
}

/// The creases as the library's tags, in its vertex ids.
fn tags(creases: &[(u32, u32, f32)], remap: &Remap) -> Result<Tags, Msg> {
    let to_lib = remap.inverse();
    let mut tags = Tags::default();
    for &(a, b, sharpness) in creases {
        match (to_lib(a), to_lib(b)) {
            (Some(v0), Some(v1)) => tags.creases.push(CreaseTag { v0, v1, sharpness }),
            _ => return Err(format!("crease ({a}, {b}) is not an edge of the mesh: no face uses one of its vertices")),
        }
    }
    Ok(tags)
}

/// The repaired mesh (its own vertex ids).
fn repaired(positions: Vec<Vec3>, faces: &Faces, poly: bool) -> Result<(Control, Remap), Msg> {
    let raw =
        RawMesh { positions, face_starts: faces.starts.clone(), corners: faces.corners.clone(), ..RawMesh::default() };
    let (mesh, _, _) = raw.build("the arrays", Topology::Repair, false).map_err(msg)?;
    let remap = Remap { n_input: mesh.positions.len(), kept: None };
    let c = if poly { Control::Poly(PolyMesh::from_mesh(&mesh)) } else { Control::Tri(mesh) };
    Ok((c, remap))
}
