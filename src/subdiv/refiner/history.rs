//! The undo and redo history of a [`Refiner`]: each step stores what
//! changed (the moved vertices' positions before and after, or the tags
//! before and after), not the mesh.

use super::Refiner;
use crate::mesh::sharpness::Tags;
use glam::{DVec3, Vec3};

/// One change of a [`Refiner`]'s history.
#[derive(Clone, Debug)]
pub(super) enum Step {
    /// Control vertices moved: their ids, positions before and after (and
    /// in f64, where the refiner keeps f64 points).
    Move { ids: Vec<u32>, before: Vec<Vec3>, after: Vec<Vec3>, precise: Option<Box<Moved64>> },
    /// The sharpness tags before and after.
    Tags { before: Tags, after: Tags },
}

/// A move's f64 control positions before and after.
type Moved64 = (Vec<DVec3>, Vec<DVec3>);

/// Undo and redo stacks.
#[derive(Clone, Debug, Default)]
pub(super) struct History {
    pub(super) done: Vec<Step>,
    pub(super) undone: Vec<Step>,
}

impl Refiner {
    /// A move's step of the history (`after64`: its f64 positions, where
    /// the refiner keeps f64 points).
    pub(super) fn push_move(&mut self, ids: &[u32], to: &[Vec3], after64: Option<Vec<DVec3>>) {
        let before = ids.iter().map(|&v| self.points[0][v as usize]).collect();
        let precise = self
            .precise
            .as_ref()
            .zip(after64)
            .map(|(levels, after)| Box::new((ids.iter().map(|&v| levels[0][v as usize]).collect(), after)));
        self.history.done.push(Step::Move { ids: ids.to_vec(), before, after: to.to_vec(), precise });
        self.history.undone.clear();
    }

    /// Undoes the last step; whether there was one.
    pub fn undo(&mut self) -> bool {
        let Some(step) = self.history.done.pop() else { return false };
        self.redo_or_undo(&step, true);
        self.history.undone.push(step);
        true
    }

    /// Redoes the last undone step; whether there was one.
    pub fn redo(&mut self) -> bool {
        let Some(step) = self.history.undone.pop() else { return false };
        self.redo_or_undo(&step, false);
        self.history.done.push(step);
        true
    }

    fn redo_or_undo(&mut self, step: &Step, undo: bool) {
        match step {
            Step::Move { ids, before, after, precise } => {
                let to64 = precise.as_deref().map(|(b, a)| if undo { &b[..] } else { &a[..] });
                self.place(ids, if undo { before } else { after }, to64);
            }
            Step::Tags { before, after } => {
                // the tags were valid when the step was made on this cage
                if let Err(e) = self.apply_tags(if undo { before } else { after }) {
                    log::warn!("undo of a sharpness change: {e}");
                }
            }
        }
    }

    /// Steps that can be undone and redone.
    pub fn history_len(&self) -> (usize, usize) {
        (self.history.done.len(), self.history.undone.len())
    }
}
