//! What a scheme's levels will hold, predicted from the control mesh's
//! counts alone (so the viewer can say it every frame and refuse a level
//! before any work): the triangle schemes split every triangle in four,
//! the polygon schemes every `k`-gon into `k` quads.
//!
//! ```text
//! triangles   F' = 4F      E' = 2E + 3F     V' = V + E
//! polygons    H' = 4H      E' = 2E + H      V' = V + E + F     F' = H
//! ```
//! (`H`: polygon corners, the sum of the face sizes; from level 1 on every
//! face is a quad, drawn as two triangles.)

use crate::mesh::CornerTable;
use crate::mesh::counts::Counts;
use crate::mesh::poly::PolyTable;
use crate::mesh::topology::{Topology, diagonals};
use crate::{Result, Scheme};

/// The counts of a control mesh that predict its levels: its triangles and
/// the polygons they stand for (triangles joined across their hidden
/// diagonals, [`crate::mesh::Generations::HIDDEN`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ControlCounts {
    /// Vertices.
    pub vertices: u64,
    /// Edges of the triangles, diagonals included.
    pub edges: u64,
    /// Triangles.
    pub triangles: u64,
    /// Hidden diagonals: inner edges of polygons drawn as triangles.
    pub diagonals: u64,
}

impl ControlCounts {
    /// The counts of `ct` (one pass over its corners when it has edge
    /// generations; none otherwise).
    pub fn of(ct: &CornerTable) -> ControlCounts {
        ControlCounts {
            vertices: ct.num_vertices() as u64,
            edges: ct.num_edges() as u64,
            triangles: ct.num_triangles() as u64,
            diagonals: diagonals(ct) as u64,
        }
    }

    /// The counts of the polygon table `pt`, as those of its faces fanned
    /// into triangles (a `k`-gon is `k - 2` triangles and `k - 3` hidden
    /// diagonals).
    pub fn of_poly(pt: &PolyTable) -> ControlCounts {
        let (h, f) = (pt.num_corners() as u64, pt.num_faces() as u64);
        // every face has at least three corners: h >= 3f
        let diagonals = h.saturating_sub(3 * f);
        ControlCounts {
            vertices: pt.num_vertices() as u64,
            edges: pt.num_edges() as u64 + diagonals,
            triangles: h.saturating_sub(2 * f),
            diagonals,
        }
    }

    /// The counts [`topology`](crate::mesh::topology::topology) found.
    pub(crate) fn of_topology(t: &Topology) -> ControlCounts {
        ControlCounts {
            vertices: t.vertices as u64,
            edges: t.edges as u64,
            triangles: t.faces as u64,
            diagonals: t.diagonals as u64,
        }
    }

    /// Faces of the polygon mesh (each diagonal joins two triangles).
    pub(crate) fn polygons(&self) -> u64 {
        self.triangles - self.diagonals
    }

    /// Polygon corners: the sum of the face sizes.
    pub(crate) fn polygon_corners(&self) -> u64 {
        3 * self.triangles - 2 * self.diagonals
    }

    /// Faces after `levels` levels of `scheme`: triangles for a triangle
    /// scheme, polygons (quads from level 1 on) for a polygon scheme.
    pub fn faces_at(&self, scheme: Scheme, levels: u32) -> u64 {
        self.counts(scheme).after(scheme.is_polygonal(), levels).faces
    }

    /// Vertices after `levels` levels of `scheme` (saturating): a triangle
    /// level adds one per edge, a polygon level one per edge and face.
    pub fn vertices_at(&self, scheme: Scheme, levels: u32) -> u64 {
        self.counts(scheme).after(scheme.is_polygonal(), levels).vertices
    }

    /// The counts a level of `scheme` splits: the polygons' (the fans'
    /// diagonals no edges) or the triangles'.
    fn counts(&self, scheme: Scheme) -> Counts {
        match scheme.is_polygonal() {
            true => Counts {
                vertices: self.vertices,
                edges: self.edges - self.diagonals,
                faces: self.polygons(),
                corners: self.polygon_corners(),
            },
            false => Counts {
                vertices: self.vertices,
                edges: self.edges,
                faces: self.triangles,
                corners: 3 * self.triangles,
            },
        }
    }

    /// Triangles drawn after `levels` levels of `scheme` (a quad is two).
    pub(crate) fn triangles_at(&self, scheme: Scheme, levels: u32) -> u64 {
        match (scheme.is_polygonal(), levels) {
            (true, 1..) => self.faces_at(scheme, levels).saturating_mul(2),
            _ if scheme.is_polygonal() => self.triangles,
            _ => self.faces_at(scheme, levels),
        }
    }

    /// Checks that `levels` levels of `scheme` fit in `limit` bytes and in
    /// 32-bit ids at every level, each level kept as a [`crate::Refiner`]
    /// keeps them.
    ///
    /// # Errors
    /// [`crate::Error::TooLarge`] naming the first level that does not fit.
    pub(crate) fn check(&self, scheme: Scheme, levels: u32, limit: Option<u64>) -> Result<()> {
        super::refine::build::check(self.counts(scheme), scheme.is_polygonal(), levels, limit, true)
    }

    /// The peak bytes that `levels` levels of `scheme` are predicted to
    /// need, by the walk that refuses a level over `--max-memory`
    /// ([`crate::Options::max_memory`]): the largest level's peak, with the
    /// levels before it held too when they are `kept` (as a
    /// [`crate::Refiner`] and the refinements that carry attributes keep
    /// them; a plain [`crate::subdivide`] does not). `u64::MAX` where a
    /// level's ids would not fit in 32 bits. A caller running many
    /// refinements at once (`subdiv batch`) admits one when this fits.
    pub fn peak_bytes(&self, scheme: Scheme, levels: u32, kept: bool) -> u64 {
        use super::refine::{LevelCounts, level_peaks};
        fn peak<C: LevelCounts>(counts: C, levels: u32, kept: bool) -> u64 {
            let peaks = level_peaks(counts, levels, kept);
            peaks.map(|(_, c, bytes)| if c.ids_overflow() { u64::MAX } else { bytes }).max().unwrap_or(0)
        }
        let counts = self.counts(scheme);
        match scheme.is_polygonal() {
            true => peak(super::refine::poly::PolygonCounts(counts), levels, kept),
            false => peak(super::refine::TriangleCounts(counts), levels, kept),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::poly::PolyMesh;
    use crate::subdiv::{Options, subdivide_poly};
    use glam::Vec3;

    /// A quad, a pentagon and a triangle sharing edges, refined: the
    /// predicted counts are the refined mesh's own.
    #[test]
    fn predicted_polygon_levels_are_the_refined_counts() {
        let positions: Vec<Vec3> = (0..8).map(|i| Vec3::new(i as f32, (i * i % 5) as f32, (i % 3) as f32)).collect();
        let (pm, _) = PolyMesh::from_faces(positions, &[0, 4, 9, 12], &[0, 1, 2, 3, 1, 4, 5, 6, 2, 2, 6, 7]).unwrap();
        let counts = ControlCounts::of(&pm.triangulated().ct);
        assert_eq!((counts.polygons(), counts.polygon_corners()), (3, 12));
        assert_eq!(ControlCounts::of_poly(&pm.pt), counts, "the polygon table's counts are its fan's");
        for levels in 0..4 {
            let (fine, _) = subdivide_poly(&pm, Scheme::CatmullClark, levels, &Options::default()).unwrap();
            assert_eq!(counts.faces_at(Scheme::CatmullClark, levels), fine.pt.num_faces() as u64, "L{levels}");
            assert_eq!(counts.vertices_at(Scheme::CatmullClark, levels), fine.pt.num_vertices() as u64, "L{levels}");
            let drawn = fine.triangulated();
            assert_eq!(counts.triangles_at(Scheme::Bilinear, levels), drawn.ct.num_triangles() as u64);
            let again = ControlCounts::of(&drawn.ct);
            assert_eq!(again.polygons(), fine.pt.num_faces() as u64, "L{levels}: quads joined again");
        }
        assert!(counts.check(Scheme::CatmullClark, 3, Some(1 << 30)).is_ok());
        assert!(counts.check(Scheme::CatmullClark, 12, Some(1 << 30)).is_err());
        assert_eq!(counts.faces_at(Scheme::Loop, 2), 16 * counts.triangles);
    }

    /// The predicted peak is the smallest budget the check admits, kept or
    /// not, for both kinds of table; levels past 32-bit ids need everything.
    #[test]
    fn the_peak_is_the_least_budget_that_fits() {
        use crate::mesh::counts::Counts;
        use crate::mesh::shapes::{grid, icosphere};
        use crate::subdiv::refine::build::check;
        for mesh in [icosphere(2), grid(5)] {
            let counts = ControlCounts::of(&mesh.ct);
            let pm = PolyMesh::from_mesh(&mesh);
            for levels in 1..5 {
                for scheme in [Scheme::Loop, Scheme::CatmullClark] {
                    let kept = counts.peak_bytes(scheme, levels, true);
                    assert!(counts.check(scheme, levels, Some(kept)).is_ok(), "{scheme} L{levels}");
                    assert!(counts.check(scheme, levels, Some(kept - 1)).is_err(), "{scheme} L{levels}");
                    let plain = counts.peak_bytes(scheme, levels, false);
                    assert!(plain <= kept && (levels == 1 || plain < kept), "{scheme} L{levels}: {plain} {kept}");
                    // the builder's own check of the tables
                    let fits = |limit| match scheme.is_polygonal() {
                        true => check(Counts::of_polygons(&pm.pt), true, levels, Some(limit), false).is_ok(),
                        false => check(Counts::of_triangles(&mesh.ct), false, levels, Some(limit), false).is_ok(),
                    };
                    assert!(fits(plain) && !fits(plain - 1), "{scheme} L{levels}: not kept");
                }
            }
            assert_eq!(counts.peak_bytes(Scheme::Loop, 0, true), 0);
            assert_eq!(counts.peak_bytes(Scheme::Loop, 20, false), u64::MAX, "ids overflow");
        }
    }

    /// A closed and an open triangle mesh refined by Loop: the predicted
    /// vertex counts are the refined meshes' own.
    #[test]
    fn predicted_triangle_vertices_are_the_refined_counts() {
        use crate::mesh::shapes::{grid, icosphere};
        for mesh in [icosphere(1), grid(3)] {
            let counts = ControlCounts::of(&mesh.ct);
            for levels in 0..4 {
                let (fine, _) = crate::subdiv::subdivide(&mesh, Scheme::Loop, levels, &Options::default()).unwrap();
                assert_eq!(counts.vertices_at(Scheme::Loop, levels), fine.ct.num_vertices() as u64, "L{levels}");
            }
            assert_eq!(counts.vertices_at(Scheme::Loop, 40), u64::MAX, "saturates");
        }
    }
}
