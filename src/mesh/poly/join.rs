//! Polygon meshes side by side as one: the pieces of a scene refined each
//! by its own rules (a Loop prim's triangles beside a Catmull-Clark prim's
//! quads) joined into one mesh to draw and to write, each piece's faces,
//! vertices, attributes, sharp features and holes renumbered after the
//! pieces before it.

use super::{PolyMesh, PolyTable};
use crate::mesh::attributes::{Attributes, MaterialGroups};
use crate::mesh::scene::Scene;
use crate::mesh::sharpness::{CornerTag, CreaseTag, Tags};
use glam::{Vec2, Vec3};
use std::sync::Arc;

/// One piece to join: the mesh, its attributes (per polygon corner, vertex
/// and face, as [`PolyMesh::from_mesh_with_attributes`] gives them) and
/// whether its holes are kept as holes (else their faces are left out).
pub(crate) struct Piece {
    pub(crate) mesh: PolyMesh,
    pub(crate) attrs: Attributes,
    pub(crate) keep_holes: bool,
}

impl PolyMesh {
    /// `pieces` as one mesh (they share no vertex): faces, then vertices,
    /// in the pieces' order; texture coordinates, colours and material
    /// groups kept where any piece has them (the others get (0, 0), grey
    /// and a group of their own); the scenes' prims concatenated; the
    /// options the first piece's.
    ///
    /// # Errors
    /// [`crate::MeshError`] when the pieces leave no face.
    pub(crate) fn join(pieces: Vec<Piece>) -> Result<(PolyMesh, Attributes), crate::MeshError> {
        let mut out = Joined::default();
        for p in &pieces {
            out.add(p);
        }
        let nv = out.positions.len();
        let (pt, _, kept) = PolyTable::build(nv, &out.starts, &out.corners, Some(&out.positions))?;
        // every vertex of a piece is on one of its faces but a hole's own
        let old = |v: u32| kept.as_ref().map_or(v, |k| k[v as usize]);
        let mut new_id = vec![u32::MAX; nv];
        for v in 0..pt.num_vertices() as u32 {
            new_id[old(v) as usize] = v;
        }
        let tags = out.tags(&new_id);
        let pt = pt.with_tags(&tags)?.with_holes(out.holes.clone());
        let positions = (0..pt.num_vertices() as u32).map(|v| out.positions[old(v) as usize]).collect();
        let colors = out.colors.map(|c| (0..pt.num_vertices() as u32).map(|v| c[old(v) as usize]).collect());
        let options = pieces.first().map(|p| p.attrs.options).unwrap_or_default();
        let materials = out.groups.map(|face| MaterialGroups {
            face,
            list: out.list,
            libraries: out.libraries,
            scene: out.scene.map(Arc::new),
        });
        Ok((PolyMesh { pt, positions }, Attributes { uv: out.uv, colors, materials, options }))
    }
}

/// The pieces added so far.
#[derive(Default)]
struct Joined {
    positions: Vec<Vec3>,
    starts: Vec<u32>,
    corners: Vec<u32>,
    uv: Option<Vec<Vec2>>,
    colors: Option<Vec<Vec3>>,
    groups: Option<Vec<u32>>,
    list: Vec<crate::mesh::attributes::Material>,
    libraries: Vec<String>,
    scene: Option<Scene>,
    creases: Vec<CreaseTag>,
    corner_tags: Vec<CornerTag>,
    holes: Vec<u32>,
}

impl Joined {
    /// Appends `p` after what is there.
    fn add(&mut self, p: &Piece) {
        let (pt, a) = (&p.mesh.pt, &p.attrs);
        let (v0, c0, f0) = (self.positions.len() as u32, self.corners.len(), self.face_count());
        if self.starts.is_empty() {
            self.starts.push(0);
        }
        let uv = a.uv.as_ref().filter(|u| u.len() == pt.num_corners());
        let groups = a.materials.as_ref().filter(|m| m.face.len() == pt.num_faces());
        let g0 = self.list.len() as u32;
        let mut kept_faces = 0u32;
        for f in 0..pt.num_faces() as u32 {
            if pt.is_hole(f) && !p.keep_holes {
                continue;
            }
            let r = pt.face_corners(f);
            self.corners.extend(pt.v_table()[r.start as usize..r.end as usize].iter().map(|&v| v + v0));
            self.starts.push(self.corners.len() as u32);
            if let Some(uv) = uv {
                let all = self.uv.get_or_insert_with(|| vec![Vec2::ZERO; c0]);
                all.extend_from_slice(&uv[r.start as usize..r.end as usize]);
            } else if let Some(all) = &mut self.uv {
                all.resize(self.corners.len(), Vec2::ZERO);
            }
            let g = groups.map_or(0, |m| m.face[f as usize]);
            let all = self.groups.get_or_insert_with(|| vec![0; f0]);
            all.push(g0 + g);
            if pt.is_hole(f) {
                self.holes.push(f0 as u32 + kept_faces);
            }
            kept_faces += 1;
        }
        self.positions.extend_from_slice(&p.mesh.positions);
        match (&mut self.colors, a.colors.as_ref().filter(|c| c.len() == p.mesh.positions.len())) {
            (Some(all), Some(c)) => all.extend_from_slice(c),
            (Some(all), None) => all.resize(self.positions.len(), Vec3::splat(0.8)),
            (None, Some(c)) => {
                let mut all = vec![Vec3::splat(0.8); v0 as usize];
                all.extend_from_slice(c);
                self.colors = Some(all);
            }
            (None, None) => {}
        }
        self.add_groups(groups);
        if let Some(s) = pt.sharpness() {
            let t = s.to_tags(pt);
            self.creases.extend(t.creases.iter().map(|c| CreaseTag { v0: c.v0 + v0, v1: c.v1 + v0, ..*c }));
            self.corner_tags.extend(t.corners.iter().map(|c| CornerTag { vertex: c.vertex + v0, ..*c }));
        }
    }

    /// The material groups of a piece (one unnamed group where it has
    /// none), and its scene's prims.
    fn add_groups(&mut self, groups: Option<&MaterialGroups>) {
        let Some(m) = groups else {
            self.list.push(crate::mesh::attributes::Material::named(&format!("material {}", self.list.len())));
            return;
        };
        if let Some(s) = &m.scene {
            let all = self.scene.get_or_insert_with(|| Scene { prim_of: vec![0; self.list.len()], ..(**s).clone() });
            let p0 = all.prims.len() as u32;
            all.prims.extend(s.prims.iter().cloned());
            all.prim_of.extend((0..m.list.len()).map(|g| p0 + s.prim_of.get(g).copied().unwrap_or(0)));
        } else if let Some(all) = &mut self.scene {
            all.prim_of.resize(self.list.len() + m.list.len(), 0);
        }
        self.list.extend(m.list.iter().cloned());
        for l in &m.libraries {
            if !self.libraries.contains(l) {
                self.libraries.push(l.clone());
            }
        }
    }

    fn face_count(&self) -> usize {
        self.starts.len().saturating_sub(1)
    }

    /// The sharp features, on the built table's vertex ids.
    fn tags(&self, new_id: &[u32]) -> Tags {
        let id = |v: u32| new_id.get(v as usize).copied().filter(|&n| n != u32::MAX);
        Tags {
            creases: self
                .creases
                .iter()
                .filter_map(|c| Some(CreaseTag { v0: id(c.v0)?, v1: id(c.v1)?, ..*c }))
                .collect(),
            corners: self.corner_tags.iter().filter_map(|c| Some(CornerTag { vertex: id(c.vertex)?, ..*c })).collect(),
        }
    }
}
