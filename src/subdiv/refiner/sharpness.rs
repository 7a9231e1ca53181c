//! Sharpness edits of a [`Refiner`]: the public setters (an edge's, a
//! vertex's, all tags at once), one step of the history each, applied by
//! recording again the rows they reach ([`super::retag`]) or, where the
//! tags decide holes, by refining every level anew into the buffers held.

use super::Refiner;
use super::history::Step;
use crate::mesh::sharpness::{CornerTag, CreaseTag, Tags, checked_sharpness};
use crate::{CornerTable, Error, Mesh, Result};

impl Refiner {
    /// The control mesh's tags now.
    pub fn tags(&self) -> Tags {
        self.cage.sharpness().map(|s| s.to_tags(&self.cage)).unwrap_or_default()
    }

    /// Sets the sharpness of the control edge `a`-`b` (0 smooth, 10 and
    /// above infinitely sharp), records the stencils again and
    /// re-evaluates. One step of the history.
    ///
    /// # Errors
    /// [`Error::Usage`] when `a`-`b` is not an edge of the cage, or for a
    /// sharpness that is not finite and at least 0
    /// ([`crate::mesh::checked_sharpness`]); nothing is changed then.
    pub fn set_edge_sharpness(&mut self, a: u32, b: u32, sharpness: f32) -> Result<()> {
        let s = checked_sharpness(f64::from(sharpness)).map_err(|e| Error::Usage(format!("edge {a}-{b} has {e}")))?;
        if self.cage.corner_opposite(a, b).is_none() && self.cage.corner_opposite(b, a).is_none() {
            return Err(Error::Usage(format!("{a}-{b} is not an edge of the control mesh")));
        }
        let mut tags = self.tags();
        tags.creases.retain(|t| (t.v0.min(t.v1), t.v0.max(t.v1)) != (a.min(b), a.max(b)));
        if s > 0.0 {
            tags.creases.push(CreaseTag { v0: a, v1: b, sharpness: s });
        }
        self.retag(tags)
    }

    /// Sets the sharpness of control vertex `v` (a corner; 0 smooth).
    ///
    /// # Errors
    /// [`Error::Usage`] when `v` is not a control vertex, or for a
    /// sharpness that is not finite and at least 0 (as
    /// [`Refiner::set_edge_sharpness`]); nothing is changed then.
    pub fn set_vertex_sharpness(&mut self, v: u32, sharpness: f32) -> Result<()> {
        let s = checked_sharpness(f64::from(sharpness)).map_err(|e| Error::Usage(format!("vertex {v} has {e}")))?;
        if v as usize >= self.points[0].len() {
            return Err(Error::Usage(format!("vertex {v} is not a control vertex")));
        }
        let mut tags = self.tags();
        tags.corners.retain(|t| t.vertex != v);
        if s > 0.0 {
            tags.corners.push(CornerTag { vertex: v, sharpness: s });
        }
        self.retag(tags)
    }

    /// Gives the cage `tags` (replacing its sharp edges and vertices);
    /// one step of the history, re-recorded where it reaches as
    /// [`Refiner::set_edge_sharpness`].
    ///
    /// # Errors
    /// A tag naming no edge or vertex of the cage.
    pub fn set_tags(&mut self, tags: &Tags) -> Result<()> {
        self.retag(tags.clone())
    }

    fn retag(&mut self, after: Tags) -> Result<()> {
        // a fanned polygon's diagonals are no edges of the surface
        let hidden = |a: u32, b: u32| {
            let c = self.cage.corner_opposite(a, b).or_else(|| self.cage.corner_opposite(b, a));
            c.is_some_and(|c| self.cage.edge_generation(c) == crate::mesh::Generations::HIDDEN)
        };
        if let Some(t) = after.creases.iter().find(|t| hidden(t.v0, t.v1)) {
            return Err(Error::Usage(format!("{}-{} is a diagonal of a polygon, not an edge", t.v0, t.v1)));
        }
        let before = self.tags();
        self.apply_tags(&after)?;
        self.history.done.push(Step::Tags { before, after });
        self.history.undone.clear();
        Ok(())
    }

    /// The cage with `tags`: the rows the change reaches recorded again
    /// ([`retag`]) and evaluated with what follows from them (or, where
    /// the tags decide holes, every level recorded again).
    pub(super) fn apply_tags(&mut self, tags: &Tags) -> Result<()> {
        let cage = self.cage.clone().with_tags(tags).map_err(Error::Invalid)?;
        match self.retag_locally(tags)? {
            Some(redone) => {
                self.cage = cage;
                self.touch(&[], &redone);
                self.evaluate_touched();
            }
            None => self.rebuild(cage)?,
        }
        self.face_varying = Default::default();
        Ok(())
    }

    /// Every level refined anew on `cage` (the same faces, new tags), into
    /// the buffers already held: the points stay where they are (a view of
    /// them outlives the change), the f64 ones too, and the history.
    ///
    /// # Errors
    /// As [`Refiner::new`]; [`Error::Usage`] if the levels came out of
    /// other sizes (tags change no counts: a bug), nothing changed then.
    fn rebuild(&mut self, cage: CornerTable) -> Result<()> {
        let control = Mesh { ct: cage, positions: self.control().to_vec() };
        let mut fresh = Refiner::new(&control, self.scheme(), self.levels(), self.options())?;
        if fresh.level_counts() != self.level_counts() {
            return Err(Error::Usage("refined anew, the levels have other sizes (a bug)".into()));
        }
        for (old, new) in self.points.iter_mut().zip(&fresh.points) {
            old.copy_from_slice(new);
        }
        fresh.points = std::mem::take(&mut self.points);
        fresh.history = std::mem::take(&mut self.history);
        fresh.from_polygons = self.from_polygons;
        fresh.precise = self.precise.take();
        *self = fresh;
        // evaluated by the rows, as after every edit
        self.edit_tables();
        if self.precise.is_some() {
            self.evaluate_all_f64(None);
        }
        let n = self.positions().len() as u32;
        if let Some(edit) = self.edit.as_mut() {
            edit.evaluated = (0..n).collect();
            edit.changed = None;
        }
        Ok(())
    }
}
