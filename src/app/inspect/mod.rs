//! The Inspect mode (`Q`, the panel's Inspect section): the corner table
//! and the rules made visible on the level shown.
//!
//! ```text
//! Corners   a click picks the corner of the triangle under the cursor whose
//!           vertex is nearest the hit (the shown level's triangle table; for
//!           Catmull-Clark and bilinear its quad table); its operators are
//!           drawn as arrows (render/inspect.rs) and the keys n p o l r s u
//!           walk them (the quad table's next prev twin swing: n p o s)
//! Stencil   a click picks the nearest vertex of the shown level; its weights
//!           over the control vertices are drawn on the cage
//! Split     a click picks a face of level L >= 1: its parent at L - 1, the
//!           four children, the new vertices' rules, the O (twin) entries by
//!           formula (split.rs)
//! ```
//! A pick is computed on the inspector's worker (`Jobs::inspect`: a
//! stencil, a parent level, a quad table can take a while on a big mesh);
//! walking a picked corner reads its table directly. Picks belong to the
//! output they were made on (compared by identity): a new level or model
//! leaves them stale, and they are neither drawn nor listed.

pub(crate) mod split;

use super::doc::Doc;
use super::probe::{Ray, Target};
use crate::mesh::inspect::{CornerOps, PolyCornerOps, corner_ops, poly_corner_ops};
use crate::mesh::poly::PolyTable;
use crate::render::inspect as shapes;
use crate::render::overlay::Overlay;
use crate::subdiv::stencil::{Stencil, stencil};
use crate::{Error, Mesh, Options, Result, Scheme};
use std::sync::Arc;

pub(crate) use split::SplitView;

/// What a click picks while Inspect is on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub(crate) enum Mode {
    /// A corner and its operators.
    #[default]
    Corners,
    /// A refined vertex and its stencil.
    Stencil,
    /// A face, its parent and the split between them.
    Split,
}

impl Mode {
    /// The modes, in the panel's order.
    pub(crate) const ALL: [Mode; 3] = [Mode::Corners, Mode::Stencil, Mode::Split];
    /// The panel's name.
    pub(crate) fn name(self) -> &'static str {
        match self {
            Mode::Corners => "Corners",
            Mode::Stencil => "Stencil",
            Mode::Split => "Split",
        }
    }
}

/// What the panel and the keys ask of the inspector.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Action {
    /// Inspect on or off (`Q`).
    Toggle,
    /// Inspect off (`Esc`).
    Leave,
    /// Pick the corner, vertex or face of this sub-mode.
    SetMode(Mode),
    /// Pick under a ray.
    Pick(Ray),
    /// Walk the picked corner along an operator (`n p o l r s u`).
    Walk(char),
}

/// The table a picked corner belongs to.
#[derive(Clone)]
pub(crate) enum Table {
    /// The shown level's triangle table.
    Triangles(Arc<Mesh>),
    /// The shown level's quad (polygon) table.
    Polygons(Arc<PolyTable>),
}

/// A picked corner.
#[derive(Clone)]
pub(crate) struct PickedCorner {
    /// The corner.
    pub(crate) corner: u32,
    /// Its table.
    pub(crate) table: Table,
}

/// A corner's operators, of either table.
pub(crate) enum Ops {
    /// Rossignac's `n p o l r s u`.
    Triangle(CornerOps),
    /// The polygon table's `next prev twin swing`.
    Polygon(PolyCornerOps),
}

impl PickedCorner {
    /// Its operators (the library's).
    pub(crate) fn ops(&self) -> Option<Ops> {
        match &self.table {
            Table::Triangles(m) => corner_ops(&m.ct, self.corner).map(Ops::Triangle),
            Table::Polygons(pt) => poly_corner_ops(pt, self.corner).map(Ops::Polygon),
        }
    }

    /// The operators as (name, target) rows.
    pub(crate) fn rows(&self) -> Vec<(&'static str, Option<u32>)> {
        match self.ops() {
            Some(Ops::Triangle(x)) => shapes::corner_rows(&x),
            Some(Ops::Polygon(x)) => shapes::poly_corner_rows(&x),
            None => Vec::new(),
        }
    }

    /// The corner the key `key` walks to, or why it walks nowhere.
    pub(crate) fn step(&self, key: char) -> std::result::Result<u32, String> {
        let name = match (&self.table, key) {
            (Table::Triangles(_), 'n' | 'p' | 'o' | 'l' | 'r' | 's' | 'u') => key.to_string(),
            (Table::Polygons(_), 'n') => "next".into(),
            (Table::Polygons(_), 'p') => "prev".into(),
            (Table::Polygons(_), 'o') => "twin".into(),
            (Table::Polygons(_), 's') => "swing".into(),
            (Table::Polygons(_), _) => {
                return Err(format!("{key}: the quad table's operators are next, prev, twin and swing (keys n p o s)"));
            }
            _ => return Err(format!("{key} is not an operator")),
        };
        let row = self.rows().into_iter().find(|r| r.0 == name);
        match row {
            Some((_, Some(c))) => Ok(c),
            _ => Err(format!("{name}({}) is across a border: nothing to walk to", self.corner)),
        }
    }

    /// The arrows of its operators on the drawn points `positions`.
    pub(crate) fn overlay(&self, positions: &[glam::Vec3]) -> Option<Overlay> {
        Some(match (&self.table, self.ops()?) {
            (Table::Triangles(m), Ops::Triangle(x)) => shapes::triangle_corner_overlay(m.ct.v_table(), positions, &x),
            (Table::Polygons(pt), Ops::Polygon(x)) => shapes::poly_corner_overlay(pt, positions, &x),
            _ => return None,
        })
    }
}

/// What the worker asks about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Ask {
    /// The corner at `vertex` of the face holding drawn triangle `triangle`.
    Corner {
        /// The drawn triangle.
        triangle: u32,
        /// Its vertex nearest the hit.
        vertex: u32,
    },
    /// The stencil of a vertex.
    Stencil(u32),
    /// The split of the face holding a drawn triangle.
    Split(u32),
}

/// What the worker found.
pub(crate) enum Found {
    /// A corner.
    Corner(PickedCorner),
    /// A stencil.
    Stencil(Box<Stencil>),
    /// A split.
    Split(Box<SplitView>),
}

/// One pick for the worker.
pub(crate) struct InspectJob {
    /// What is asked.
    pub(crate) ask: Ask,
    /// The control mesh.
    pub(crate) control: Arc<Mesh>,
    /// The shown level (the subdivision output, uncut).
    pub(crate) shown: Arc<Mesh>,
    /// How it was made.
    pub(crate) made: (Scheme, u32, Options),
    /// The shown level's quad table, when one was built for it already.
    pub(crate) quads: Option<Arc<PolyTable>>,
}

impl InspectJob {
    /// Answers the pick (on the worker).
    ///
    /// # Errors
    /// A vertex or face that the tables do not have, or the memory a
    /// stencil's levels need.
    pub(crate) fn run(&self) -> Result<Found> {
        let (scheme, level, opts) = self.made;
        let quads = || self.quads.clone().unwrap_or_else(|| Arc::new(PolyTable::from_corner_table(&self.shown.ct)));
        match self.ask {
            Ask::Stencil(v) => Ok(Found::Stencil(Box::new(stencil(&self.control, scheme, level, &opts, v)?))),
            Ask::Corner { triangle, vertex } if scheme.is_polygonal() => {
                let pt = quads();
                let face = face_of_triangle(&pt, &self.shown, triangle)?;
                let corner = pt.face_corners(face).find(|&c| pt.vtx(c) == vertex).ok_or_else(|| {
                    Error::Usage(format!("vertex {vertex} is not a corner of face {face} of the quad table"))
                })?;
                Ok(Found::Corner(PickedCorner { corner, table: Table::Polygons(pt) }))
            }
            Ask::Corner { triangle, vertex } => {
                let ct = &self.shown.ct;
                let corner = (3 * triangle..3 * triangle + 3).find(|&c| ct.vtx(c) == vertex).unwrap_or(3 * triangle);
                Ok(Found::Corner(PickedCorner { corner, table: Table::Triangles(self.shown.clone()) }))
            }
            Ask::Split(triangle) if scheme.is_polygonal() => {
                let pt = quads();
                let face = face_of_triangle(&pt, &self.shown, triangle)?;
                Ok(Found::Split(Box::new(split::quad_split(&self.control, &pt, (scheme, level, &opts), face)?)))
            }
            Ask::Split(triangle) => {
                let view = split::triangle_split(&self.control, &self.shown, (scheme, level, &opts), triangle)?;
                Ok(Found::Split(Box::new(view)))
            }
        }
    }
}

/// The face of `pt` that holds triangle `t` of `mesh` (the same level fanned
/// into triangles): the face at its first vertex with all three vertices.
fn face_of_triangle(pt: &PolyTable, mesh: &Mesh, t: u32) -> Result<u32> {
    let tri = [0, 1, 2].map(|i| mesh.ct.vtx(3 * t + i));
    pt.fan(tri[0])
        .map(|c| pt.face(c))
        .find(|&f| tri.iter().all(|&x| pt.face_corners(f).any(|c| pt.vtx(c) == x)))
        .ok_or_else(|| Error::Usage(format!("triangle {t} lies in no face of the quad table")))
}

/// The inspector's state.
#[derive(Default)]
pub(crate) struct Inspect {
    /// Inspect is on: clicks pick for it, its marks are drawn.
    pub(crate) on: bool,
    /// What a click picks.
    pub(crate) mode: Mode,
    /// The output the picks below were made on.
    pub(crate) shown: Option<Arc<Mesh>>,
    /// The picked corner.
    pub(crate) corner: Option<PickedCorner>,
    /// The picked vertex's stencil.
    pub(crate) stencil: Option<Box<Stencil>>,
    /// The picked face's split.
    pub(crate) split: Option<Box<SplitView>>,
    /// What the last pick or step said (a border, a level without a parent).
    pub(crate) message: Option<String>,
}

impl Inspect {
    /// Whether the picks belong to `shown` (the current output).
    pub(crate) fn current(&self, shown: &Arc<Mesh>) -> bool {
        self.shown.as_ref().is_some_and(|s| Arc::ptr_eq(s, shown))
    }

    /// Takes a worker's answer for the output `shown` (picks made on
    /// another output are dropped).
    pub(crate) fn adopt(&mut self, shown: Arc<Mesh>, found: Found) {
        if !self.current(&shown) {
            (self.corner, self.stencil, self.split) = (None, None, None);
            self.shown = Some(shown);
        }
        match found {
            Found::Corner(c) => self.corner = Some(c),
            Found::Stencil(s) => self.stencil = Some(s),
            Found::Split(s) => self.split = Some(s),
        }
    }

    /// The quad table of a picked corner of `shown`, for the next pick.
    fn quads(&self, shown: &Arc<Mesh>) -> Option<Arc<PolyTable>> {
        match self.corner.as_ref().map(|c| &c.table) {
            Some(Table::Polygons(pt)) if self.current(shown) => Some(pt.clone()),
            _ => None,
        }
    }
}

impl Doc {
    /// Carries out an inspector action.
    pub(crate) fn inspect(&mut self, action: Action) {
        let i = &mut self.inspect;
        match action {
            Action::Toggle => i.on = !i.on,
            Action::Leave => i.on = false,
            Action::SetMode(mode) => {
                i.mode = mode;
                i.message = None;
            }
            Action::Pick(ray) => self.inspect_pick(ray),
            Action::Walk(key) => self.inspect_walk(key),
        }
    }

    /// Picks for the inspector's mode under `ray` (a miss forgets that
    /// mode's pick).
    fn inspect_pick(&mut self, ray: Ray) {
        let i = &mut self.inspect;
        i.on = true;
        i.message = None;
        if self.model.curve.is_some() || self.anim.active {
            i.message = Some("Inspect works on a static mesh (stop the animation)".into());
            return;
        }
        if ray.target == Target::Control {
            i.message = Some("Inspect picks in the result's viewport (on the right)".into());
            return;
        }
        let m = &self.model;
        let (drawn, raw) = (&m.result.shown.mesh, &m.raw.mesh);
        let Some(hit) = crate::mesh::pick::nearest_hit(drawn, ray.origin, ray.dir) else {
            match i.mode {
                Mode::Corners => i.corner = None,
                Mode::Stencil => i.stencil = None,
                Mode::Split => i.split = None,
            }
            return;
        };
        let t = hit.triangle;
        // the raw table's ids (a creased result is drawn cut open, with copies)
        let vertex = (0..3)
            .map(|k| raw.ct.vtx(3 * t + k))
            .min_by(|&a, &b| {
                let d = |v: u32| drawn.positions[v as usize].distance(hit.point);
                d(a).total_cmp(&d(b))
            })
            .unwrap_or(0);
        let ask = match i.mode {
            Mode::Corners => Ask::Corner { triangle: t, vertex },
            Mode::Stencil => Ask::Stencil(vertex),
            Mode::Split if m.made.level == 0 => {
                i.message = Some("Split needs level 1 or more: a face of level 0 has no parent".into());
                return;
            }
            Mode::Split => Ask::Split(t),
        };
        let job = InspectJob {
            ask,
            control: m.control.mesh.clone(),
            shown: raw.clone(),
            made: (m.made.scheme, m.made.level, m.made.opts),
            quads: i.quads(raw),
        };
        self.jobs.inspect(job);
    }

    /// Walks the picked corner along the operator of `key`.
    fn inspect_walk(&mut self, key: char) {
        let raw = &self.model.raw.mesh;
        let i = &mut self.inspect;
        let Some(corner) = i.corner.as_mut().filter(|_| i.shown.as_ref().is_some_and(|s| Arc::ptr_eq(s, raw))) else {
            i.message = Some("pick a corner first (click near a vertex inside a face)".into());
            return;
        };
        match corner.step(key) {
            Ok(c) => {
                corner.corner = c;
                i.message = None;
            }
            Err(why) => i.message = Some(why),
        }
    }

    /// What the inspector draws over the result now (its mode's current
    /// pick), if anything.
    pub(crate) fn inspect_overlay(&self) -> Option<Overlay> {
        let (i, m) = (&self.inspect, &self.model);
        if !i.on || !i.current(&m.raw.mesh) || m.curve.is_some() || self.anim.active {
            return None;
        }
        let drawn = &m.result.shown.mesh.positions;
        match i.mode {
            Mode::Corners => i.corner.as_ref()?.overlay(drawn),
            Mode::Stencil => {
                let st = i.stencil.as_ref()?;
                let at = *drawn.get(st.vertex as usize)?;
                Some(shapes::stencil_overlay(&m.control.mesh.positions, st, at))
            }
            Mode::Split => Some(i.split.as_ref()?.overlay(drawn)),
        }
    }
}
