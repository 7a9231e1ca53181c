//! The pieces of a scene a file holds: a USD stage's Mesh prims, each with
//! its own subdivision options and transform, and what the stage says of
//! its units and axes.
//!
//! A scene rides on the mesh's material groups
//! ([`super::attributes::MaterialGroups`]): every group belongs to one
//! prim ([`Scene::prim_of`]), so every face knows its prim at every level
//! (children keep their parent's group) and nothing else needs carrying.
//! A prim whose `displayColor` is per face has one group per colour (the
//! group's diffuse colour is the face's).

use super::options::ShapeOptions;

/// One Mesh prim.
#[derive(Clone, Debug, PartialEq)]
pub struct Prim {
    /// Its path (`/World/Body`).
    pub path: String,
    /// The subdivision options it states (USD's defaults where unauthored).
    pub options: ShapeOptions,
    /// Its local-to-world transform, column-major (glam's `DMat4`): the
    /// positions are read through it, and a writer that keeps prims writes
    /// them back in the prim's own space under it.
    pub transform: [f64; 16],
    /// Whether its `displayColor` is per face (held as its groups'
    /// diffuse colours, written back per face).
    pub face_colors: bool,
}

/// The stage's up axis (`upAxis`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UpAxis {
    /// `Y`.
    Y,
    /// `Z`.
    Z,
}

/// A scene's prims and its stage's metadata.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scene {
    /// The prims, in the stage's namespace order.
    pub prims: Vec<Prim>,
    /// The prim (into `prims`) of every material group.
    pub prim_of: Vec<u32>,
    /// `upAxis`, where the stage states it.
    pub up_axis: Option<UpAxis>,
    /// `metersPerUnit`, where the stage states it.
    pub meters_per_unit: Option<f64>,
    /// The time code the points were read at; `None`: their default
    /// values (nothing in the stage is sampled over time).
    pub time: Option<f64>,
    /// Every time code at which the points (or a transform) are sampled,
    /// sorted: the frames of the stage's animation.
    pub times: Vec<f64>,
}

impl Scene {
    /// The prim of material group `group`.
    pub fn prim_of_group(&self, group: u32) -> Option<&Prim> {
        self.prim_of.get(group as usize).and_then(|&p| self.prims.get(p as usize))
    }

    /// Whether the prims state more than one set of options (then each
    /// set is refined on its own).
    pub fn mixed(&self) -> bool {
        self.prims.windows(2).any(|w| w[0].options != w[1].options)
    }

    /// The distinct options of the prims, in order of first use, with the
    /// prims that state each.
    pub fn groups(&self) -> Vec<(ShapeOptions, Vec<u32>)> {
        let mut out: Vec<(ShapeOptions, Vec<u32>)> = Vec::new();
        for (k, p) in self.prims.iter().enumerate() {
            match out.iter_mut().find(|(o, _)| *o == p.options) {
                Some((_, ids)) => ids.push(k as u32),
                None => out.push((p.options, vec![k as u32])),
            }
        }
        out
    }

    /// This scene with only the prims `keep` (renumbered in that order)
    /// and the groups `groups` (the old ids of the groups kept, in their
    /// new order).
    pub(crate) fn restricted(&self, keep: &[u32], groups: &[u32]) -> Scene {
        let new_id = |p: u32| keep.iter().position(|&k| k == p).unwrap_or(0) as u32;
        Scene {
            prims: keep.iter().filter_map(|&k| self.prims.get(k as usize).cloned()).collect(),
            prim_of: groups.iter().map(|&g| new_id(self.prim_of.get(g as usize).copied().unwrap_or(0))).collect(),
            times: self.times.clone(),
            ..*self
        }
    }
}

impl Default for Prim {
    fn default() -> Prim {
        Prim { path: "/Mesh".into(), options: ShapeOptions::default(), transform: IDENTITY, face_colors: false }
    }
}

/// The identity transform.
pub(crate) const IDENTITY: [f64; 16] = [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0];
