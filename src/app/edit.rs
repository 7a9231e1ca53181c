//! Shaping the cage: the edit mode's selection and grab, the history of
//! every change to the control mesh (undo, redo), saving, and the recovery
//! file that survives a crash.
//!
//! A grab moves the selected control vertices (and, with proportional
//! editing, those within its radius by a smooth falloff) through the
//! [`Refiner`] of the drawn level: only the rows of each level that a moved
//! vertex reaches are evaluated again, with the normals around them.
//! Every committed change is a [`Step`] that stores what changed (moved
//! vertices' positions before and after; the meshes before and after an
//! edit of the topology or the tags, shared, not copied) and is written at
//! once to a recovery file in the user's state folder, which a save or a
//! discard removes.

use super::doc::{Doc, Problem};
use super::model::Shown;
use super::recovery::Recovery;
use crate::{Mesh, Refiner, Scheme};
use glam::Vec3;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A world axis a grab is held to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Axis {
    /// X.
    X,
    /// Y.
    Y,
    /// Z.
    Z,
}

impl Axis {
    /// The unit vector.
    pub(crate) fn unit(self) -> Vec3 {
        match self {
            Axis::X => Vec3::X,
            Axis::Y => Vec3::Y,
            Axis::Z => Vec3::Z,
        }
    }
}

/// What the edit mode is asked to do (the panel's and the keys').
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum EditAction {
    /// Edit mode on or off.
    Toggle,
    /// Select these control vertices (replacing the selection, or
    /// toggling each in it with `add`); an empty list with `add` off
    /// clears it.
    Select {
        /// The vertices.
        ids: Vec<u32>,
        /// Shift: add or remove instead of replacing.
        add: bool,
    },
    /// Every control vertex selected.
    SelectAll,
    /// Start a grab of the selection; `anchor` is the cursor (NDC).
    Grab {
        /// The cursor where the grab starts, in the viewport's NDC.
        anchor: glam::Vec2,
    },
    /// The grab's offset from the mouse (world units, before the axis).
    GrabTo(Vec3),
    /// Hold the grab to an axis (again: free).
    Constrain(Axis),
    /// The distance typed during a grab ("" clears it).
    Typed(String),
    /// Confirm the grab (one step of the history).
    Confirm,
    /// Cancel the grab (the vertices go back).
    Cancel,
    /// Proportional editing on or off.
    SetProportional(bool),
    /// Scale the proportional radius by this factor.
    ScaleRadius(f32),
    /// The sharpness of the picked edge, or of the selected vertices
    /// when no edge is picked.
    Sharpness(f32),
    /// Undo the last step.
    Undo,
    /// Redo the last undone step.
    Redo,
    /// Save the control mesh to its file (asks for a path when it has
    /// none, or its format cannot hold what the mesh has).
    Save,
    /// Ask for a path to save to (Save As).
    AskPath,
    /// Save to this path and make it the model's file.
    SaveAs(PathBuf),
    /// Recover the edits found in the recovery file.
    Recover,
    /// Discard them (the recovery file is removed).
    DiscardRecovery,
}

/// A grab in progress.
#[derive(Clone, Debug)]
pub(crate) struct Grab {
    /// The cursor where it started (NDC).
    pub(crate) anchor: glam::Vec2,
    /// Centroid of the selection when it started (where the mouse's
    /// motion is measured).
    pub(crate) centroid: Vec3,
    /// Every control position when it started.
    start: Arc<Vec<Vec3>>,
    /// The vertices that move and how much (1 for the selection).
    ids: Vec<u32>,
    weights: Vec<f32>,
    /// The mouse's offset.
    pub(crate) mouse: Vec3,
    /// The axis it is held to.
    pub(crate) axis: Option<Axis>,
    /// A typed distance (along the axis, X when none).
    pub(crate) typed: String,
}

impl Grab {
    /// The offset now: the typed distance along the axis, or the mouse's
    /// offset projected on it.
    pub(crate) fn offset(&self) -> Vec3 {
        let axis = self.axis.map(Axis::unit);
        match (self.typed.trim().parse::<f32>().ok().filter(|d| d.is_finite()), axis) {
            (Some(d), a) => a.unwrap_or(Vec3::X) * d,
            (None, Some(a)) => a * self.mouse.dot(a),
            (None, None) => self.mouse,
        }
    }

    /// The moving vertices' positions for the current offset.
    fn targets(&self) -> Vec<Vec3> {
        let d = self.offset();
        self.ids.iter().zip(&self.weights).map(|(&v, &w)| self.start[v as usize] + d * w).collect()
    }
}

/// One change of the control mesh.
#[derive(Clone)]
pub(crate) enum Step {
    /// Control vertices moved.
    Move {
        /// What the history list shows.
        what: String,
        /// The vertices.
        ids: Vec<u32>,
        /// Their positions before.
        before: Vec<Vec3>,
        /// And after.
        after: Vec<Vec3>,
    },
    /// The animation's keys before and after.
    Paths {
        /// What the history list shows.
        what: String,
        /// Before.
        before: Box<crate::anim::paths::Paths>,
        /// After.
        after: Box<crate::anim::paths::Paths>,
    },
    /// Any other change (tags, smoothing, a flip, a split, a hole, a
    /// revert): the meshes before and after, shared with the document.
    Control {
        /// What the history list shows.
        what: String,
        /// Before.
        before: Arc<Mesh>,
        /// After.
        after: Arc<Mesh>,
    },
}

impl Step {
    /// Its line in the history list.
    pub(crate) fn label(&self) -> &str {
        match self {
            Step::Move { what, .. } | Step::Control { what, .. } | Step::Paths { what, .. } => what,
        }
    }
}

/// Undo and redo stacks; each step has an id so that the saved state is
/// known after any undo.
#[derive(Clone, Default)]
pub(crate) struct History {
    /// Steps done, oldest first.
    pub(crate) done: Vec<(u64, Step)>,
    /// Steps undone, the next to redo last.
    pub(crate) undone: Vec<(u64, Step)>,
    next: u64,
    /// The id of the last step done when the file was last written (0:
    /// the file as opened).
    saved: u64,
}

impl History {
    fn top(&self) -> u64 {
        self.done.last().map_or(0, |(id, _)| *id)
    }
    /// Whether the control mesh differs from its file.
    pub(crate) fn dirty(&self) -> bool {
        self.top() != self.saved
    }
    /// Records a step (clearing what was undone).
    pub(crate) fn push_step(&mut self, step: Step) {
        self.push(step);
    }
    fn push(&mut self, step: Step) {
        self.next += 1;
        self.done.push((self.next, step));
        self.undone.clear();
    }
}

/// The edit mode's state, the history and the recovery file.
pub(crate) struct Edit {
    /// Edit mode on.
    pub(crate) on: bool,
    /// Selected control vertices, sorted.
    pub(crate) selected: Vec<u32>,
    /// A grab in progress.
    pub(crate) grab: Option<Grab>,
    /// Proportional editing.
    pub(crate) proportional: bool,
    /// Its radius, world units.
    pub(crate) radius: f32,
    /// The history of the control mesh.
    pub(crate) history: History,
    /// The drawn level's refiner and what it was built for.
    refiner: Option<(RefinerKey, Refiner)>,
    /// The level that refiner drew last: a move changed only some of its
    /// rows while it is still the drawn one (weak: a level replaced is not
    /// kept for this; its address is, so no other mesh is taken for it).
    drawn: Option<std::sync::Weak<Mesh>>,
    /// Bumped whenever the control mesh's topology or tags change.
    pub(crate) topology: u64,
    /// Where recovery copies go (`None`: nowhere).
    pub(crate) recovery: Option<Recovery>,
    /// A recovery copy was found for the opened model: it is offered.
    pub(crate) offer: bool,
    /// Save As was asked for (the panel shows its field).
    pub(crate) ask_path: bool,
    /// What waits for an answer about unsaved changes.
    pub(crate) pending: Option<Pending>,
}

/// What a refiner was built for.
#[derive(Clone, Copy, PartialEq)]
struct RefinerKey {
    topology: u64,
    scheme: Scheme,
    level: u32,
    opts: crate::Options,
}

impl Default for Edit {
    fn default() -> Self {
        Edit {
            on: false,
            selected: Vec::new(),
            grab: None,
            proportional: false,
            radius: 0.5,
            history: History::default(),
            refiner: None,
            drawn: None,
            topology: 0,
            // the unit tests name their own folder: they never write the user's
            recovery: if cfg!(test) { None } else { Recovery::for_user() },
            offer: false,
            ask_path: false,
            pending: None,
        }
    }
}

/// Vertices `ids` of `ct` and their ring neighbours, sorted, each once.
fn moved_rows(ct: &crate::CornerTable, ids: &[u32]) -> Arc<[u32]> {
    let mut rows: Vec<u32> = ids.iter().flat_map(|&v| std::iter::once(v).chain(ct.ring(v))).collect();
    rows.sort_unstable();
    rows.dedup();
    rows.into()
}

/// The smooth falloff of proportional editing at distance `d` of radius
/// `r`: 1 at the centre, 0 at the radius, flat at both (Blender's
/// "smooth", `3t^2 - 2t^3` of `t = 1 - d/r`).
pub(crate) fn falloff(d: f32, r: f32) -> f32 {
    let t = (1.0 - d / r.max(1e-12)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

impl Edit {
    /// Forgets the selection, the grab and the refiner (a new model).
    pub(crate) fn reset(&mut self) {
        self.selected.clear();
        self.grab = None;
        self.refiner = None;
        self.drawn = None;
        self.history = History::default();
        self.topology += 1;
        self.offer = false;
    }

    /// The moving vertices of a grab of the selection from `start`, with
    /// their weights.
    fn moving(&self, start: &[Vec3]) -> (Vec<u32>, Vec<f32>) {
        if !self.proportional {
            return (self.selected.clone(), vec![1.0; self.selected.len()]);
        }
        let sel: Vec<Vec3> = self.selected.iter().map(|&v| start[v as usize]).collect();
        let (mut ids, mut w) = (Vec::new(), Vec::new());
        for (v, p) in start.iter().enumerate() {
            let d = sel.iter().map(|s| s.distance(*p)).fold(f32::MAX, f32::min);
            let weight = if self.selected.binary_search(&(v as u32)).is_ok() { 1.0 } else { falloff(d, self.radius) };
            if weight > 0.0 {
                ids.push(v as u32);
                w.push(weight);
            }
        }
        (ids, w)
    }
}

/// What the panel asks before closing the window or opening another model
/// with unsaved changes.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Pending {
    /// Close the window.
    Close,
    /// Open this model.
    Open(super::jobs::Input),
}

/// The answer to [`Pending`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Answer {
    /// Save first, then go on.
    Save,
    /// Go on without saving (the recovery file is removed).
    Discard,
    /// Stay.
    Cancel,
}

impl Doc {
    /// Carries out an edit-mode action.
    pub(crate) fn edit(&mut self, action: EditAction) {
        match action {
            EditAction::Toggle => {
                self.cancel_grab();
                self.edit.on = !self.edit.on;
                self.display.control |= self.edit.on;
                self.edit_surface();
            }
            EditAction::Select { ids, add } => self.select(&ids, add),
            EditAction::SelectAll => self.edit.selected = (0..self.model.control.mesh.positions.len() as u32).collect(),
            EditAction::Grab { anchor } => self.start_grab(anchor),
            EditAction::GrabTo(offset) => self.with_grab(|g| g.mouse = offset),
            EditAction::Constrain(axis) => self.with_grab(|g| g.axis = (g.axis != Some(axis)).then_some(axis)),
            EditAction::Typed(text) => self.with_grab(|g| g.typed = text),
            EditAction::Confirm => self.confirm_grab(),
            EditAction::Cancel => self.cancel_grab(),
            EditAction::SetProportional(on) => self.edit.proportional = on,
            EditAction::ScaleRadius(f) => self.scale_radius(f),
            EditAction::Sharpness(s) => self.sharpen(s),
            EditAction::Undo => self.undo(),
            EditAction::Redo => self.redo(),
            EditAction::Save => self.save(),
            EditAction::AskPath => self.edit.ask_path = true,
            EditAction::SaveAs(path) => self.save_as(path),
            EditAction::Recover => self.recover(),
            EditAction::DiscardRecovery => {
                if std::mem::take(&mut self.edit.offer)
                    && let Some(store) = &self.edit.recovery
                {
                    store.remove(self.model.path.as_deref());
                }
            }
        }
    }

    fn select(&mut self, ids: &[u32], add: bool) {
        let n = self.model.control.mesh.positions.len() as u32;
        let sel = &mut self.edit.selected;
        if !add {
            sel.clear();
        }
        for &v in ids.iter().filter(|&&v| v < n) {
            match sel.binary_search(&v) {
                Ok(i) if add => _ = sel.remove(i),
                Ok(_) => {}
                Err(i) => sel.insert(i, v),
            }
        }
    }

    fn start_grab(&mut self, anchor: glam::Vec2) {
        if self.edit.selected.is_empty() {
            self.status.notice = Some("select control vertices to grab (click, Shift+click, A)".into());
            return;
        }
        self.cancel_grab();
        let start = Arc::new(self.model.control.mesh.positions.clone());
        let (ids, weights) = self.edit.moving(&start);
        let sel = &self.edit.selected;
        let centroid = sel.iter().map(|&v| start[v as usize]).sum::<Vec3>() / sel.len() as f32;
        let g = Grab { anchor, centroid, start, ids, weights, mouse: Vec3::ZERO, axis: None, typed: String::new() };
        self.edit.grab = Some(g);
    }

    fn with_grab(&mut self, f: impl FnOnce(&mut Grab)) {
        let Some(g) = self.edit.grab.as_mut() else { return };
        f(g);
        let (ids, to) = (g.ids.clone(), g.targets());
        self.place(&ids, &to);
    }

    /// A new radius; during a grab the moving set follows (vertices that
    /// leave it go back to where the grab found them).
    fn scale_radius(&mut self, factor: f32) {
        if factor.is_finite() && factor > 0.0 {
            self.edit.radius = (self.edit.radius * factor).clamp(1e-6, 1e6);
        }
        let Some(g) = self.edit.grab.as_ref() else { return };
        let (ids, weights) = self.edit.moving(&g.start);
        let left: Vec<u32> = g.ids.iter().copied().filter(|v| ids.binary_search(v).is_err()).collect();
        let back: Vec<Vec3> = left.iter().map(|&v| g.start[v as usize]).collect();
        self.place(&left, &back);
        self.with_grab(|g| (g.ids, g.weights) = (ids, weights));
    }

    fn confirm_grab(&mut self) {
        let Some(g) = self.edit.grab.take() else { return };
        let after = g.targets();
        let before: Vec<Vec3> = g.ids.iter().map(|&v| g.start[v as usize]).collect();
        if before == after {
            return;
        }
        let what = match g.ids.len() {
            1 => format!("move vertex {}", g.ids[0]),
            n => format!("move {n} vertices"),
        };
        self.edit.history.push(Step::Move { what, ids: g.ids, before, after });
        self.after_change();
        if self.jobs.busy.subdividing.is_some() {
            // a level on its way was made from the cage before the move
            self.request_subdivision();
        }
    }

    /// Puts the grabbed vertices back.
    pub(crate) fn cancel_grab(&mut self) {
        let Some(g) = self.edit.grab.take() else { return };
        let back: Vec<Vec3> = g.ids.iter().map(|&v| g.start[v as usize]).collect();
        self.place(&g.ids, &back);
    }

    /// The picked edge's sharpness, or the selected vertices' (corners).
    fn sharpen(&mut self, s: f32) {
        if let Some(c) = *self.model.picked {
            return self.set_sharpness(c, s);
        }
        if self.edit.selected.is_empty() {
            self.status.notice = Some("pick an edge or select vertices to set their sharpness".into());
            return;
        }
        let s = match crate::mesh::checked_sharpness(f64::from(s)) {
            Ok(s) => s,
            Err(e) => {
                let e = crate::Error::Usage(format!("the selected vertices' {e}"));
                return self.fail(Problem::Other(e));
            }
        };
        let ct = &self.model.control.mesh.ct;
        let mut tags = ct.sharpness().map(|t| t.to_tags(ct)).unwrap_or_default();
        let sel = &self.edit.selected;
        tags.corners.retain(|t| sel.binary_search(&t.vertex).is_err());
        if s > 0.0 {
            tags.corners.extend(sel.iter().map(|&vertex| crate::mesh::sharpness::CornerTag { vertex, sharpness: s }));
        }
        self.set_control_tags(&tags);
    }

    /// Moves control vertices (no history): the cage, and the drawn level
    /// through the refiner. Both record the rows they changed, so that the
    /// GPU mirror writes only those.
    fn place(&mut self, ids: &[u32], to: &[Vec3]) {
        if ids.is_empty() {
            return;
        }
        let control = &self.model.control.mesh;
        let mut positions = control.positions.clone();
        for (&v, &p) in ids.iter().zip(to) {
            positions[v as usize] = p;
        }
        let mesh = Arc::new(Mesh { ct: control.ct.clone(), positions });
        // the moved vertices and their ring neighbours: every normal that
        // changes (a fan normal reads only the triangles around it)
        let rows = moved_rows(&mesh.ct, ids);
        // at level 0 the drawn level is the cage: it changed at the same rows
        let m = &mut self.model;
        let level0 = Arc::ptr_eq(&m.raw.mesh, &m.control.mesh).then(|| rows.clone());
        if m.original.is_none() {
            m.original = Some(m.control.mesh.clone());
        }
        m.control.set_rows(Shown::new(mesh), rows.clone());
        m.proxy = None;
        let rows = self.follow_surface(ids, to, level0);
        self.reshade_rows(rows);
    }
}

/// The drawn level following moved control vertices, history and files.
impl Doc {
    /// In the edit mode, the drawn level is the refiner's (built now, not
    /// on the first move), so that undoing a move gives back exactly the
    /// surface the edit started from.
    pub(crate) fn edit_surface(&mut self) {
        if self.edit.on && self.model.made.level > 0 {
            self.follow_surface(&[], &[], None);
            self.reshade();
        }
    }

    /// The drawn level after control vertices `ids` moved to `to`: the
    /// control mesh itself at level 0 (which changed from the level drawn
    /// at `cage_rows`, if known), else the refiner of the drawn level
    /// (built on first use, on the cage as it now is) moved locally.
    /// Returns the rows of the level that changed (positions or normals,
    /// sorted), where only those did.
    fn follow_surface(&mut self, ids: &[u32], to: &[Vec3], cage_rows: Option<Arc<[u32]>>) -> Option<Arc<[u32]>> {
        if self.model.made.level == 0 {
            self.model.raw = (*self.model.control).clone();
            return cage_rows;
        }
        let key = self.refiner_key();
        let fresh = match self.edit.refiner.take() {
            Some((k, mut r)) if k == key => r.set_vertices(ids, to).map(|_| (r, false)),
            // the first (even empty) move evaluates the levels by their
            // rows, as every later move and undo does
            _ => Refiner::new(&*self.model.control.mesh, key.scheme, key.level, &key.opts)
                .and_then(|mut r| r.set_vertices(ids, to).map(|_| (r, true))),
        };
        let (r, built) = match fresh {
            Ok(x) => x,
            Err(e) => {
                self.fail(Problem::Other(e));
                return None;
            }
        };
        let raw = &self.model.raw;
        let same = !built || r.topology().v_table() == raw.mesh.ct.v_table();
        // the rows it changed, when the level drawn is the one it drew
        // last (not the worker's, a retagged one or one just built)
        let drew = self.edit.drawn.as_ref().is_some_and(|d| std::ptr::eq(d.as_ptr(), Arc::as_ptr(&raw.mesh)));
        let rows = r.changed_rows().filter(|_| !built && drew).map(|rows| {
            let mut rows = rows.to_vec();
            rows.sort_unstable();
            Arc::<[u32]>::from(rows)
        });
        let mesh = Arc::new(r.mesh());
        self.model.raw = if same {
            let creased = raw.creased.as_ref().map(|cr| {
                let normals = crate::mesh::normals::vertex_normals(&cr.ct, &cr.extend(&mesh.positions));
                Arc::new(super::model::Creased { ct: cr.ct.clone(), copies: cr.copies.clone(), normals })
            });
            Shown { mesh, normals: Arc::new(r.normals().to_vec()), topo: raw.topo.clone(), creased }
        } else {
            // a level numbered otherwise than the worker's: its refined
            // attributes no longer match it
            self.model.attrs.refined = Default::default();
            Shown::new(mesh)
        };
        self.edit.refiner = Some((key, r));
        self.edit.drawn = Some(Arc::downgrade(&self.model.raw.mesh));
        rows
    }

    /// Takes over the refiner that made the drawn level, when it was built
    /// on the control mesh as it now is: the edit mode then starts without
    /// refining again.
    pub(crate) fn adopt_refiner(&mut self, refiner: Option<(Arc<crate::Mesh>, Refiner)>) {
        if let Some((_, r)) = refiner.filter(|(on, _)| Arc::ptr_eq(on, &self.model.control.mesh)) {
            self.edit.refiner = Some((self.refiner_key(), r));
        }
    }

    /// The refiner held for the drawn level, when one is (one built for
    /// another level, scheme or cage does not count).
    #[cfg(test)]
    pub(crate) fn edit_refiner(&self) -> Option<&Refiner> {
        let key = self.refiner_key();
        self.edit.refiner.as_ref().filter(|(k, _)| *k == key).map(|(_, r)| r)
    }

    /// What the drawn level's refiner must have been built for.
    fn refiner_key(&self) -> RefinerKey {
        let made = &self.model.made;
        RefinerKey { topology: self.edit.topology, scheme: made.scheme, level: made.level, opts: made.opts }
    }

    /// In the edit mode, new tags (`mesh`: the cage with them) re-record
    /// the drawn level's refiner where they reach instead of subdividing
    /// anew (one step of the history); `mesh` is handed back where that
    /// cannot be done (no refiner of the drawn level, a tag it refuses).
    pub(crate) fn retag_surface(&mut self, tags: &crate::mesh::Tags, mesh: Mesh) -> Option<Mesh> {
        let key = self.refiner_key();
        let fits =
            self.edit.on && self.model.made.level > 0 && self.edit.refiner.as_ref().is_some_and(|(k, _)| *k == key);
        let Some((_, r)) = self.edit.refiner.as_mut().filter(|_| fits) else { return Some(mesh) };
        if r.set_tags(tags).is_err() {
            return Some(mesh);
        }
        let raw = Shown::new(Arc::new(r.mesh()));
        let (before, after) = (self.model.control.mesh.clone(), Arc::new(mesh));
        self.model.control.set(Shown::new(after.clone()));
        self.model.raw = raw;
        self.edit.history.push(Step::Control { what: "sharpness".into(), before, after });
        self.reshade();
        self.after_change();
        None
    }

    /// Undoes the last change of the control mesh.
    pub(crate) fn undo(&mut self) {
        self.cancel_grab();
        let Some((id, step)) = self.edit.history.done.pop() else { return };
        self.apply_step(&step, true);
        self.edit.history.undone.push((id, step));
        self.after_change();
    }

    /// Redoes the last undone change.
    pub(crate) fn redo(&mut self) {
        self.cancel_grab();
        let Some((id, step)) = self.edit.history.undone.pop() else { return };
        self.apply_step(&step, false);
        self.edit.history.done.push((id, step));
        self.after_change();
    }

    fn apply_step(&mut self, step: &Step, undo: bool) {
        match step {
            Step::Move { ids, before, after, .. } => self.place(ids, if undo { before } else { after }),
            Step::Paths { before, after, .. } => {
                self.install_paths(if undo { (**before).clone() } else { (**after).clone() })
            }
            Step::Control { before, after, .. } => {
                let picked = *self.model.picked;
                self.install_control(if undo { before.clone() } else { after.clone() });
                self.model.picked.set(picked);
            }
        }
    }

    /// Records a change of the control mesh (the document calls it for
    /// every edit that is not a move).
    pub(crate) fn record(&mut self, what: &str, before: Arc<Mesh>, after: Arc<Mesh>) {
        self.edit.history.push(Step::Control { what: what.to_string(), before, after });
        self.edit.topology += 1;
    }

    /// After each change: the recovery file written while the mesh differs
    /// from its file, removed once it does not.
    pub(crate) fn after_change(&mut self) {
        let Some(store) = self.edit.recovery.clone() else { return };
        let model = self.model.path.as_deref();
        if !self.edit.history.dirty() {
            store.remove(model);
            return;
        }
        if let Err(e) = store.write(model, &self.model.control.mesh, &self.model.attrs.file) {
            self.status.notice = Some(format!("could not write the recovery copy: {e}"));
        }
    }

    /// Offers the recovery copy of the model just opened, if there is one.
    pub(crate) fn look_for_recovery(&mut self) {
        self.edit.offer = self.edit.recovery.as_ref().is_some_and(|s| s.exists(self.model.path.as_deref()));
    }

    /// Replaces the control mesh by the recovery copy's (one step: the
    /// model is then unsaved).
    fn recover(&mut self) {
        if !std::mem::take(&mut self.edit.offer) {
            return;
        }
        let Some(store) = &self.edit.recovery else { return };
        match store.read(self.model.path.as_deref()) {
            Some(Ok(mesh)) => self.replace_control("recover unsaved edits", mesh),
            Some(Err(e)) => self.fail(Problem::Open(e)),
            None => {}
        }
    }

    /// Whether the model's own file can take the control mesh with all it
    /// has (tags, texture coordinates, materials).
    fn file_holds_it(&self, path: &Path) -> bool {
        let (mesh, attrs) = (&self.model.control.mesh, &self.model.attrs.file);
        crate::bundled::from_arg(path).is_none()
            && crate::io::Format::for_output(path).is_some_and(|f| {
                (mesh.ct.sharpness().is_none() || f.keeps.creases)
                    && (attrs.uv.is_none() || f.keeps.uv)
                    && (attrs.materials.is_none() || f.keeps.materials)
            })
    }

    /// Saves to the model's file, or asks for a path.
    pub(crate) fn save(&mut self) {
        // the page saves by download, always as OBJ (it keeps tags, UVs)
        #[cfg(target_arch = "wasm32")]
        if let Some(p) = self.model.path.clone() {
            _ = self.write_to(&p);
            return;
        }
        match self.model.path.clone().filter(|p| self.file_holds_it(p)) {
            Some(p) => _ = self.write_to(&p),
            None => self.edit.ask_path = true,
        }
    }

    /// Saves to `path`, which becomes the model's file.
    fn save_as(&mut self, path: PathBuf) {
        let old = self.model.path.clone();
        if self.write_to(&path) {
            if let Some(store) = &self.edit.recovery {
                store.remove(old.as_deref());
            }
            self.model.name = path.file_name().map_or_else(String::new, |n| n.to_string_lossy().into_owned());
            self.model.path = Some(path);
            self.edit.ask_path = false;
        }
    }

    /// Writes the control mesh (atomically); a failure keeps the edits and
    /// says why. Whether it was written.
    fn write_to(&mut self, path: &Path) -> bool {
        #[cfg(not(target_arch = "wasm32"))]
        let written = crate::io::save_with(path, &*self.model.control.mesh, &self.model.attrs.file);
        #[cfg(target_arch = "wasm32")]
        let (written, path) = {
            let name = path.file_stem().map_or_else(|| "model".into(), |s| s.to_string_lossy().into_owned());
            let name = PathBuf::from(format!("{}.obj", name.trim_start_matches(crate::bundled::PREFIX)));
            let obj = super::recovery::obj_bytes(&self.model.control.mesh, &self.model.attrs.file);
            (obj.and_then(|bytes| super::page::download(&name.to_string_lossy(), &bytes)), name)
        };
        #[cfg(target_arch = "wasm32")]
        let path = path.as_path();
        match written {
            Ok(()) => {
                self.edit.history.saved = self.edit.history.top();
                if let Some(store) = &self.edit.recovery {
                    store.remove(Some(path));
                }
                self.status.notice = Some(format!("saved {}", path.display()));
                true
            }
            Err(e) => {
                self.fail(Problem::Other(crate::Error::Usage(format!("not saved, the edits are kept: {e}"))));
                false
            }
        }
    }

    /// Opens `path`, or first asks what to do with unsaved changes.
    pub(crate) fn open_asking(&mut self, input: super::jobs::Input) {
        match self.edit.history.dirty() {
            true => self.edit.pending = Some(Pending::Open(input)),
            false => self.open(input),
        }
    }

    /// The answer to closing or opening with unsaved changes; whether to
    /// go on.
    pub(crate) fn answer(&mut self, answer: Answer) -> bool {
        match answer {
            Answer::Save => {
                self.save();
                !self.edit.history.dirty()
            }
            Answer::Discard => {
                if let Some(store) = &self.edit.recovery {
                    store.remove(self.model.path.as_deref());
                }
                true
            }
            Answer::Cancel => false,
        }
    }
}
