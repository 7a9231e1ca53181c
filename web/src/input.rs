//! From typed arrays to the library's validated tables, and back: the
//! renumbering that keeps the caller's vertex order and carries the
//! vertices no face uses (as Python's `subdiv.subdivide` does).

use crate::names::Settings;
use crate::{Msg, Refined, bytemuck_flat};
use glam::Vec3;
use subdiv::mesh::{CreaseTag, PolyMesh, PolyTable, Tags};
use subdiv::{CornerTable, Mesh};

/// The control mesh as the library holds it.
pub enum Control {
    /// A triangle corner table (the triangle schemes).
    Tri(Mesh),
    /// A polygon table (Catmull-Clark, bilinear).
    Poly(PolyMesh),
}

/// The control mesh and how its vertex ids map back to the caller's.
pub struct Cage {
    pub control: Control,
    pub remap: Remap,
}

/// How the library's vertex ids map back to the caller's.
pub struct Remap {
    /// Vertices the caller passed.
    pub n_input: usize,
    /// The caller's id of each control vertex the library kept, when it
    /// dropped some (`None`: the same ids).
    pub kept: Option<Vec<u32>>,
}

impl Remap {
    /// The caller's id of the library's vertex `j` (new vertices follow the
    /// caller's `n_input`).
    pub fn id(&self, j: u32) -> u32 {
        match &self.kept {
            None => j,
            Some(k) if (j as usize) < k.len() => k[j as usize],
            Some(k) => j - k.len() as u32 + self.n_input as u32,
        }
    }

    /// The points `fine` (library numbering) as flat rows in the caller's,
    /// the vertices no face uses carried from `input` (flat) unchanged.
    pub fn positions(&self, fine: &[Vec3], input: &[f32]) -> Vec<f32> {
        let Some(kept) = &self.kept else { return bytemuck_flat(fine).to_vec() };
        let nk = kept.len().min(fine.len());
        let mut out = Vec::with_capacity(3 * (self.n_input + fine.len() - nk));
        out.extend_from_slice(&input[..3 * self.n_input]);
        for (j, &i) in kept.iter().enumerate().take(nk) {
            out[3 * i as usize..3 * i as usize + 3].copy_from_slice(&fine[j].to_array());
        }
        out.extend_from_slice(bytemuck_flat(&fine[nk..]));
        out
    }

    /// The library's id of each of the caller's vertices (`None`: in no face).
    pub fn inverse(&self) -> Vec<Option<u32>> {
        match &self.kept {
            None => (0..self.n_input as u32).map(Some).collect(),
            Some(k) => {
                let mut inv = vec![None; self.n_input];
                for (j, &i) in k.iter().enumerate() {
                    inv[i as usize] = Some(j as u32);
                }
                inv
            }
        }
    }
}

/// The flat positions as points.
///
/// # Errors
/// A length that is no multiple of 3, or more vertices than 32-bit ids allow.
pub fn points(flat: &[f32]) -> Result<Vec<Vec3>, Msg> {
    if !flat.len().is_multiple_of(3) {
        return Err(format!("positions must hold 3 coordinates per vertex, got {} numbers", flat.len()));
    }
    if flat.len() / 3 >= u32::MAX as usize {
        return Err(format!("{} vertices: more than 32-bit vertex ids allow", flat.len() / 3));
    }
    Ok(flat.chunks_exact(3).map(Vec3::from_slice).collect())
}

/// The offsets of the faces of `sizes` corners each, over `corners` corners.
///
/// # Errors
/// A face of no corner, or sizes that do not add up to the corners given.
fn starts(sizes: &[u32], corners: usize) -> Result<Vec<u32>, Msg> {
    let mut starts = Vec::with_capacity(sizes.len() + 1);
    let mut at = 0u64;
    starts.push(0);
    for (f, &k) in sizes.iter().enumerate() {
        if k == 0 {
            return Err(format!("face {f} has no corners (faceSizes[{f}] is 0)"));
        }
        at += u64::from(k);
        if at > corners as u64 {
            break;
        }
        starts.push(at as u32);
    }
    if at != corners as u64 {
        return Err(format!("faceSizes add up to {at} corners, but indices holds {corners}"));
    }
    Ok(starts)
}

/// The validated control mesh of the arrays for `s`'s scheme.
///
/// # Errors
/// The library's message for a mesh it refuses; polygons for a triangle
/// scheme; a crease or hole out of range.
pub fn cage(positions: &[f32], indices: &[u32], s: &Settings) -> Result<Cage, Msg> {
    let points = points(positions)?;
    let n_input = points.len();
    let msg = |e: subdiv::MeshError| e.to_string();
    let poly = s.scheme.is_polygonal();
    let starts = match &s.face_sizes {
        Some(sizes) => starts(sizes, indices.len())?,
        None if !indices.len().is_multiple_of(3) => {
            return Err(format!("indices must hold 3 corners per triangle (or pass faceSizes), got {}", indices.len()));
        }
        None => (0..=indices.len() as u32 / 3).map(|f| 3 * f).collect(),
    };
    let m = starts.len() - 1;
    if !poly && s.face_sizes.as_ref().is_some_and(|k| k.iter().any(|&k| k != 3)) {
        return Err(format!("the {} scheme takes triangles; use catmull-clark or bilinear for polygons", s.scheme));
    }
    if let Some((k, &f)) = s.holes.iter().enumerate().find(|&(_, &f)| f as usize >= m) {
        return Err(format!("hole {k} names face {f}, but there are {m} faces"));
    }
    let (control, kept) = if poly {
        let (pt, _, kept) = PolyTable::build(n_input, &starts, indices, Some(&points)).map_err(msg)?;
        let pt = if s.holes.is_empty() { pt } else { pt.with_holes(s.holes.clone()) };
        (Control::Poly(PolyMesh { pt, positions: kept_points(points, kept.as_deref()) }), kept)
    } else {
        let (ct, _, kept) = CornerTable::build(n_input, indices, Some(&points)).map_err(msg)?;
        let ct = if s.holes.is_empty() { ct } else { ct.with_holes(s.holes.clone()) };
        (Control::Tri(Mesh { ct, positions: kept_points(points, kept.as_deref()) }), kept)
    };
    let remap = Remap { n_input, kept };
    let tags = tags(&s.creases, &remap)?;
    let control = match control {
        _ if tags.creases.is_empty() => control,
        Control::Tri(Mesh { ct, positions }) => Control::Tri(Mesh { ct: ct.with_tags(&tags).map_err(msg)?, positions }),
        Control::Poly(PolyMesh { pt, positions }) => {
            Control::Poly(PolyMesh { pt: pt.with_tags(&tags).map_err(msg)?, positions })
        }
    };
    Ok(Cage { control, remap })
}

/// The points of the kept vertices.
fn kept_points(points: Vec<Vec3>, kept: Option<&[u32]>) -> Vec<Vec3> {
    match kept {
        Some(k) => k.iter().map(|&i| points[i as usize]).collect(),
        None => points,
    }
}

/// The creases as the library's tags, in its vertex ids.
fn tags(creases: &[(u32, u32, f32)], remap: &Remap) -> Result<Tags, Msg> {
    let to_lib = remap.inverse();
    let mut tags = Tags::default();
    for (k, &(a, b, sharpness)) in creases.iter().enumerate() {
        let lib = |v: u32| to_lib.get(v as usize).copied();
        match (lib(a), lib(b)) {
            (Some(Some(v0)), Some(Some(v1))) => tags.creases.push(CreaseTag { v0, v1, sharpness }),
            (None, _) | (_, None) => {
                return Err(format!("crease {k} names vertex ({a}, {b}), but there are {} vertices", remap.n_input));
            }
            _ => return Err(format!("crease ({a}, {b}) is not an edge of the mesh: no face uses one of its vertices")),
        }
    }
    Ok(tags)
}

/// The polygon control mesh itself (levels 0), the holes left out, in the
/// caller's numbering.
pub fn polygons(mesh: &PolyMesh, remap: &Remap, input: &[f32]) -> Refined {
    let pt = &mesh.pt;
    let holes = pt.holes();
    let (mut indices, mut sizes) = (Vec::with_capacity(pt.num_corners()), Vec::with_capacity(pt.num_faces()));
    for f in 0..pt.num_faces() as u32 {
        if holes.binary_search(&f).is_err() {
            let c = pt.face_corners(f);
            indices.extend(pt.v_table()[c.start as usize..c.end as usize].iter().map(|&v| remap.id(v)));
            sizes.push(pt.face_size(f));
        }
    }
    Refined { positions: remap.positions(&mesh.positions, input), indices, face_sizes: Some(sizes) }
}
