//! The parts of a scene refined each by its own rules and joined: a USD
//! stage whose prims state different schemes or options (a Loop prim
//! beside a Catmull-Clark one, a `subdivisionScheme none` prim kept as it
//! is) comes out as one polygon mesh whose faces keep their prims.

use super::{Options, Scheme, Stats};
use crate::Result;
use crate::mesh::Mesh;
use crate::mesh::attributes::Attributes;
use crate::mesh::poly::PolyMesh;
use crate::mesh::poly::join::Piece;

/// One part of a scene and how to refine it.
#[derive(Clone, Copy, Debug)]
pub struct Part<'a> {
    /// Its mesh (polygons as the readers fan them).
    pub mesh: &'a Mesh,
    /// Its attributes (texture coordinates, colours, material groups and
    /// the scene they belong to).
    pub attrs: &'a Attributes,
    /// Its scheme; `None`: it is not subdivided (USD's
    /// `subdivisionScheme none`: the cage is the surface at every level).
    pub scheme: Option<Scheme>,
    /// Its levels.
    pub levels: u32,
    /// Its options.
    pub opts: Options,
}

/// Every part refined by its own scheme, levels and options, its
/// attributes refined with it (as [`crate::Refiner::attributes`] serves
/// them), all joined into one polygon mesh: a triangle scheme's triangles,
/// a polygon scheme's quads and an unrefined part's polygons side by side,
/// each face in its part's material groups. A refined part's holes are
/// left out unless `keep_holes` (USD's `holeIndices` keep them at every
/// level); an unrefined part keeps them. The stats add up the parts'.
///
/// # Errors
/// A part that does not fit in memory (the options' budget), or nothing
/// left to join.
pub fn subdivide_parts(parts: &[Part], keep_holes: bool) -> Result<(PolyMesh, Attributes, Stats)> {
    let t0 = crate::clock::Instant::now();
    let mut stats = Stats::default();
    let mut pieces = Vec::with_capacity(parts.len());
    for p in parts {
        let (mesh, attrs, st) = refined_part(p)?;
        add(&mut stats, &st);
        let refined = p.scheme.is_some() && p.levels > 0;
        pieces.push(Piece { mesh, attrs, keep_holes: keep_holes || !refined });
    }
    let (mesh, attrs) = PolyMesh::join(pieces).map_err(crate::Error::Invalid)?;
    stats.finish(t0);
    Ok((mesh, attrs, stats))
}

/// One part's finest level as polygons, with its attributes.
fn refined_part(p: &Part) -> Result<(PolyMesh, Attributes, Stats)> {
    let Some(scheme) = p.scheme.filter(|_| p.levels > 0) else {
        let (mesh, attrs) = PolyMesh::from_mesh_with_attributes(p.mesh, p.attrs);
        return Ok((mesh, attrs, Stats::default()));
    };
    if scheme.is_polygonal() {
        let (control, pattrs) = PolyMesh::from_mesh_with_attributes(p.mesh, p.attrs);
        let r = crate::Refiner::new(&control, scheme, p.levels, &p.opts)?;
        let pt = r.polygons().cloned().unwrap_or_else(|| control.pt.clone());
        let fine = PolyMesh { pt, positions: r.positions().to_vec() };
        return Ok((fine, r.attributes(&pattrs)?, r.stats().clone()));
    }
    let r = crate::Refiner::new(p.mesh, scheme, p.levels, &p.opts)?;
    let attrs = r.attributes(p.attrs)?;
    let (fine, attrs) = PolyMesh::from_mesh_with_attributes(&r.mesh(), &attrs);
    Ok((fine, attrs, r.stats().clone()))
}

/// `b`'s phase times added to `a`'s.
fn add(a: &mut Stats, b: &Stats) {
    a.split_ms += b.split_ms;
    a.numbering_ms += b.numbering_ms;
    a.edge_ms += b.edge_ms;
    a.vertex_ms += b.vertex_ms;
    a.faces_per_level.extend_from_slice(&b.faces_per_level);
}

/// The prims of `mesh` (its scene's, in `attrs`) as one mesh for each set
/// of options they state, in order of first use, each with its attributes
/// (its options theirs): the parts [`subdivide_parts`] refines apart.
/// Empty when every prim states the same options (or there is no scene):
/// then the mesh is refined as one.
///
/// # Errors
/// A part that is not a valid mesh of its own (it is, when `mesh` is).
pub fn parts_by_options(mesh: &Mesh, attrs: &Attributes) -> Result<Vec<(Mesh, Attributes)>> {
    if !attrs.scene().is_some_and(|s| s.mixed()) {
        return Ok(Vec::new());
    }
    let raw = crate::io::RawMesh::of_mesh(mesh, attrs);
    raw.by_options()
        .into_iter()
        .map(|part| {
            let (mesh, attrs, _) = part.build("a prim", crate::io::Topology::Refuse, true)?;
            Ok((mesh, attrs))
        })
        .collect()
}
