//! The finest level's one-rings and unit vertex normals of a [`Refiner`]:
//! made on first use, then kept up to date by every edit (all of them, or
//! those around the changed finest points).
//!
//! A normal is twice the vector area of the polygon its ring spans (the
//! animation's normals, `mesh::normals::VertexRings`: two cross products
//! for a valence-6 vertex instead of one per fan triangle), each one
//! function of its polygon ([`polygon_normal`]), so a whole pass and a
//! local update give the same bits. (Walking the vertices in a
//! breadth-first order instead of by id was tried and was slower: the
//! normals are then written all over their buffer.)

use super::Refiner;
use crate::mesh::normals::{fan_polygon, polygon_normal};
use glam::Vec3;
use rayon::prelude::*;
use std::sync::OnceLock;

/// Vertices per parallel piece of a whole pass.
const CHUNK: usize = 4096;

/// The finest level's ring polygons by vertex (a closed ring's neighbours;
/// an open ring's with the vertex first, `mesh::normals::fan_polygon`):
/// vertex `v`'s is `ids[offsets[v]..offsets[v + 1]]`.
pub(super) struct Rings {
    offsets: Vec<u32>,
    ids: Vec<u32>,
}

impl Rings {
    /// The polygons of the chained rings `(offsets, ids)` (`ring_lists`).
    fn of((offsets, ids): (Vec<u32>, Vec<u32>)) -> Option<Rings> {
        let n = offsets.len().checked_sub(1)?;
        let (mut out_offsets, mut out_ids) = (Vec::with_capacity(n + 1), Vec::with_capacity(ids.len()));
        out_offsets.push(0);
        let mut poly = Vec::new();
        for v in 0..n {
            poly.clear();
            poly.extend_from_slice(&ids[offsets[v] as usize..offsets[v + 1] as usize]);
            fan_polygon(v as u32, &mut poly);
            out_ids.extend_from_slice(&poly);
            out_offsets.push(u32::try_from(out_ids.len()).ok()?);
        }
        Some(Rings { offsets: out_offsets, ids: out_ids })
    }

    /// The polygon of vertex `v` (its ring neighbours, and itself where the
    /// ring is open).
    pub(super) fn of_vertex(&self, v: u32) -> &[u32] {
        &self.ids[self.offsets[v as usize] as usize..self.offsets[v as usize + 1] as usize]
    }

    /// Every normal of positions `pos` into `out` (one per vertex each), in
    /// parallel pieces.
    ///
    /// # Panics
    /// If `out` has not one entry per vertex, or `pos` fewer (a caller bug).
    fn normals_into(&self, pos: &[Vec3], out: &mut [Vec3]) {
        assert_eq!(out.len() + 1, self.offsets.len(), "one normal per vertex");
        out.par_chunks_mut(CHUNK).enumerate().for_each(|(k, out)| normals_of(self, pos, k * CHUNK, out));
    }
}

crate::cpu::multiversion! {
    /// The normals of vertices `first..first + out.len()` into `out`.
    fn normals_of(rings: &Rings, pos: &[Vec3], first: usize, out: &mut [Vec3]) {
        for (k, n) in out.iter_mut().enumerate() {
            *n = polygon_normal(pos, rings.of_vertex((first + k) as u32));
        }
    }
}

impl Refiner {
    /// The finest level's rings, made on first use.
    pub(super) fn rings(&self) -> Option<&Rings> {
        self.rings
            .get_or_init(|| {
                let lists = match &self.topo.fine_poly {
                    Some(pt) => crate::mesh::normals::ring_lists(pt),
                    None => crate::mesh::normals::ring_lists(self.topo.fine()),
                };
                Rings::of(lists?)
            })
            .as_ref()
    }

    /// Every normal of the finest level.
    fn all_normals(&self) -> Vec<Vec3> {
        let pos = self.positions();
        match self.rings() {
            Some(rings) => {
                let mut out = vec![Vec3::ZERO; pos.len()];
                rings.normals_into(pos, &mut out);
                out
            }
            None => crate::mesh::normals::vertex_normals(self.topo.fine(), pos),
        }
    }

    /// The finest level's unit vertex normals (area-weighted over its
    /// faces; for a polygon scheme, over the polygons' rings of edge
    /// neighbours).
    pub fn normals(&self) -> &[Vec3] {
        self.normals.get_or_init(|| self.all_normals())
    }

    /// The normals of the changed finest points and their neighbours;
    /// returns the points whose position or normal changed (`None`: every
    /// normal was made again, or none is made yet).
    pub(super) fn update_normals_around(&mut self, changed: &[u32]) -> Option<Vec<u32>> {
        // none made yet: all of them made when first asked for
        self.normals.get()?;
        let Some(rings) = self.rings.get().and_then(Option::as_ref) else {
            self.update_normals(&[]);
            return None;
        };
        let last = self.points.len() - 1;
        let t = &mut self.edit.as_mut()?.touched;
        t.begin();
        for &v in changed {
            t.mark(last, v);
            for &w in rings.of_vertex(v) {
                t.mark(last, w);
            }
        }
        let around = std::mem::take(&mut t.lists[last]);
        self.update_normals(&around);
        Some(around)
    }

    /// The normals of the finest points `which` (all of them, without
    /// rings: the fan-averaged normals of the whole level).
    fn update_normals(&mut self, which: &[u32]) {
        if self.normals.get().is_none() {
            return;
        }
        let Some(rings) = self.rings.get().and_then(Option::as_ref) else {
            let all = self.all_normals();
            self.normals = OnceLock::from(all);
            return;
        };
        let pos = self.points.last().map_or(&[][..], Vec::as_slice);
        let Some(normals) = self.normals.get_mut() else { return };
        let normal = |v: u32| polygon_normal(pos, rings.of_vertex(v));
        if which.len() > 4096 {
            let values: Vec<Vec3> = which.par_iter().map(|&v| normal(v)).collect();
            which.iter().zip(values).for_each(|(&v, n)| normals[v as usize] = n);
        } else {
            which.iter().for_each(|&v| normals[v as usize] = normal(v));
        }
    }

    /// Every normal made so far, into the buffer already held (none if
    /// none is made yet).
    pub(super) fn remake_normals(&mut self) {
        let pos = self.points.last().map_or(&[][..], Vec::as_slice);
        let Some(normals) = self.normals.get_mut() else { return };
        match self.rings.get().and_then(Option::as_ref) {
            Some(rings) => rings.normals_into(pos, normals),
            None => self.update_normals(&[]),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::normals::VertexRings;
    use crate::subdiv::{Options, Scheme};

    #[test]
    fn every_normal_equals_the_animations_bit_for_bit_after_a_full_update_too() {
        let models = [("critter.obj", Scheme::Loop, 2), ("lprism.obj", Scheme::CatmullClark, 3)];
        for (name, scheme, levels) in models {
            let mut mesh = crate::bundled::load(std::path::Path::new(&format!("bundled:{name}"))).unwrap();
            // uneven positions: differences of every size, cancellations
            for (i, p) in mesh.positions.iter_mut().enumerate() {
                *p += Vec3::new((i % 7) as f32, (i % 3) as f32, (i % 11) as f32) * 1e-3;
            }
            let mut r = Refiner::new(&mesh, scheme, levels, &Options::default()).unwrap();
            assert!(r.rings().is_some(), "{name}: the rings chain");
            let control: Vec<Vec3> = r.control().iter().map(|p| *p * 1.5).collect();
            for step in 0..2 {
                let pos = r.positions();
                let rings = match r.polygons() {
                    Some(pt) => VertexRings::new(pt),
                    None => VertexRings::new(r.topology()),
                };
                let mut want = vec![Vec3::ZERO; pos.len()];
                rings.unwrap().normals_into(pos, &mut want);
                let bits = |n: &[Vec3]| n.iter().map(|n| n.to_array().map(f32::to_bits)).collect::<Vec<_>>();
                assert_eq!(bits(r.normals()), bits(&want), "{name}: step {step}");
                // the full update into the buffer held
                r.set_control(&control);
            }
        }
    }
}
