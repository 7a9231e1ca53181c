//! The finest level's one-rings and unit vertex normals of a [`Refiner`]:
//! made on first use, then kept up to date by every edit (all of them, or
//! those around the changed finest points).

use super::Refiner;
use glam::Vec3;
use rayon::prelude::*;
use std::sync::OnceLock;

impl Refiner {
    /// The finest level's rings, made on first use.
    fn rings(&self) -> Option<&(Vec<u32>, Vec<u32>)> {
        self.rings
            .get_or_init(|| match &self.topo.fine_poly {
                Some(pt) => crate::mesh::normals::ring_lists(pt),
                None => crate::mesh::normals::ring_lists(self.topo.fine()),
            })
            .as_ref()
    }

    /// Every normal of the finest level.
    fn all_normals(&self) -> Vec<Vec3> {
        let pos = self.positions();
        match self.rings() {
            Some((offsets, ids)) => (0..pos.len())
                .into_par_iter()
                .with_min_len(4096)
                .map(|v| ring_normal(pos, v as u32, &ids[offsets[v] as usize..offsets[v + 1] as usize]))
                .collect(),
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
        let Some((offsets, ids)) = self.rings.get().and_then(Option::as_ref) else {
            self.update_normals(&[]);
            return None;
        };
        let last = self.points.len() - 1;
        let t = &mut self.edit.as_mut()?.touched;
        t.begin();
        for &v in changed {
            t.mark(last, v);
            let (a, b) = (offsets[v as usize] as usize, offsets[v as usize + 1] as usize);
            for &w in &ids[a..b] {
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
        let Some((offsets, ids)) = self.rings.get().and_then(Option::as_ref) else {
            let all = self.all_normals();
            self.normals = OnceLock::from(all);
            return;
        };
        let pos = self.points.last().map_or(&[][..], Vec::as_slice);
        let Some(normals) = self.normals.get_mut() else { return };
        let normal = |v: u32| ring_normal(pos, v, &ids[offsets[v as usize] as usize..offsets[v as usize + 1] as usize]);
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
            Some((offsets, ids)) => normals.par_iter_mut().enumerate().with_min_len(4096).for_each(|(v, n)| {
                *n = ring_normal(pos, v as u32, &ids[offsets[v] as usize..offsets[v + 1] as usize]);
            }),
            None => self.update_normals(&[]),
        }
    }
}

/// The area-weighted unit normal of `v` from its ring (`Vec3::Z` where the
/// ring has no area).
fn ring_normal(pos: &[Vec3], v: u32, ring: &[u32]) -> Vec3 {
    let p = pos[v as usize];
    let n: Vec3 = ring.windows(2).map(|w| (pos[w[0] as usize] - p).cross(pos[w[1] as usize] - p)).sum();
    n.try_normalize().unwrap_or(Vec3::Z)
}
