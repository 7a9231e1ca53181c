//! The Inspect mode's Split view: the picked face of level `L` traced to
//! its parent at level `L - 1`, the parent's children, the new vertices
//! with the rules that made them, and every child corner's O entry (twin,
//! for quads) as the split derives it from the parent's, symbol by symbol
//! and in numbers, beside the child table's real entry.
//!
//! ```text
//! triangles (src/mesh/split.rs; nt parent triangles, A(c) = 3 nt (c % 3 + 1) + 3 (c / 3))
//!   child triangle x: central x < nt (parent t = x), else corner triangle of
//!   corner 3t + k, t = x % nt, k = x / nt - 1; children of t: t, nt + t, 2nt + t, 3nt + t
//!   O'[c] = A(c)   O'[A(c)] = c
//!   O'[n(A(c))] = p(A(n(O[n(c)])))   O'[p(A(c))] = n(A(p(O[p(c)])))   (border stays border)
//! quads (src/mesh/poly/split.rs): child face c is parent corner c (corners 4c .. 4c + 3)
//!   T'[4c] = 4 next(T[c]) + 3   T'[4c + 1] = 4 next(c) + 2
//!   T'[4c + 2] = 4 prev(c) + 1  T'[4c + 3] = 4 T[prev(c)]
//! ```
//! The parent level is split again from the control mesh (topology only,
//! as `subdivide` splits it), on the inspector's worker.

use crate::mesh::poly::PolyTable;
use crate::mesh::{CornerTable, Mesh, n, p};
use crate::render::inspect::{ACCENT, rule_short};
use crate::render::overlay::{Mark, Overlay};
use crate::subdiv::stencil::stencil;
use crate::{Error, Options, Result, Scheme};
use glam::Vec3;

/// One child corner's entry: the formula, worked out, and the table's.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Row {
    /// The child corner.
    pub(crate) corner: u32,
    /// The formula, in symbols (`O'[n(A(c))] = p(A(n(O[n(c)])))`).
    pub(crate) formula: &'static str,
    /// The formula with the parent's numbers (`p(A(n(O[4]))) = ...`).
    pub(crate) worked: String,
    /// What the formula gives (`None`: a border).
    pub(crate) derived: Option<u32>,
    /// The child table's entry.
    pub(crate) table: Option<u32>,
}

/// Whether the split shown is the triangle or the quad split.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    /// The 1-to-4 split of the triangle table.
    Triangles,
    /// The quad split of the polygon table.
    Quads,
}

/// What the Split view shows of one picked face.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct SplitView {
    /// Triangles or quads.
    pub(crate) kind: Kind,
    /// The child level `L`.
    pub(crate) level: u32,
    /// The face picked at level `L`.
    pub(crate) picked: u32,
    /// Its parent at level `L - 1`.
    pub(crate) parent: u32,
    /// The parent's corners at level `L - 1` (`c` of the formulas).
    pub(crate) parent_corners: Vec<u32>,
    /// The parent's children at level `L`.
    pub(crate) children: Vec<u32>,
    /// The vertices the split made in the parent (ids of level `L`) with
    /// the rule that made each.
    pub(crate) new_vertices: Vec<(u32, String)>,
    /// The parent's own vertices (their ids stay).
    pub(crate) old_vertices: Vec<u32>,
    /// The parent's outline through old and new vertices (ids of level `L`).
    pub(crate) outline: Vec<u32>,
    /// The children's edges inside the parent (vertex pairs of level `L`).
    pub(crate) inner: Vec<(u32, u32)>,
    /// Each child's vertices, for its label at its centroid.
    pub(crate) child_vertices: Vec<Vec<u32>>,
    /// Every child corner's entry.
    pub(crate) rows: Vec<Row>,
}

/// `A(c)`, the first corner of the corner triangle of parent corner `c`.
fn a_of(nt: u32, c: u32) -> u32 {
    3 * nt * (c % 3 + 1) + 3 * (c / 3)
}

/// The Split view of triangle `x` of `shown` (level `level >= 1` of
/// `scheme` over `control`).
///
/// # Errors
/// Level 0, a triangle out of range, or the memory the parent level needs.
pub(crate) fn triangle_split(
    control: &Mesh,
    shown: &Mesh,
    (scheme, level, opts): (Scheme, u32, &Options),
    x: u32,
) -> Result<SplitView> {
    let child = &shown.ct;
    check(level, x, child.num_triangles())?;
    // the parent level, as the level builder makes it (topology only)
    let old = crate::subdiv::refine::build::tables(&control.ct, (scheme, level - 1, opts))?.1;
    let nt = old.num_triangles() as u32;
    if child.num_triangles() != 4 * nt as usize {
        return Err(not_the_split(child.num_triangles(), 4 * nt as usize));
    }
    let t = if x < nt { x } else { x % nt };
    let cs = [3 * t, 3 * t + 1, 3 * t + 2];
    let w = cs.map(|c| child.vtx(c));
    let v = cs.map(|c| old.vtx(c));
    let new_vertices = rules_of(control, (scheme, level, opts), &w)?;
    let rows = cs.iter().flat_map(|&c| triangle_rows(&old, child, nt, c)).collect();
    let children: Vec<u32> = (0..4).map(|i| i * nt + t).collect();
    let child_vertices = children.iter().map(|&f| (0..3).map(|i| child.vtx(3 * f + i)).collect()).collect();
    Ok(SplitView {
        kind: Kind::Triangles,
        level,
        picked: x,
        parent: t,
        parent_corners: cs.to_vec(),
        children,
        new_vertices,
        old_vertices: v.to_vec(),
        // W[c] lies on the edge opposite c: between V[c0] and V[c1] is W[c2]
        outline: vec![v[0], w[2], v[1], w[0], v[2], w[1]],
        inner: vec![(w[0], w[1]), (w[1], w[2]), (w[2], w[0])],
        child_vertices,
        rows,
    })
}

fn check(level: u32, x: u32, faces: usize) -> Result<()> {
    if level == 0 {
        return Err(Error::Usage("the split view needs level 1 or more: a face of level 0 has no parent".into()));
    }
    if x as usize >= faces {
        return Err(Error::Usage(format!("face {x} out of range: the level has {faces}")));
    }
    Ok(())
}

/// Why a level is not the split of the one below (a subdivision that left
/// faces out has another numbering).
fn not_the_split(faces: usize, split: usize) -> Error {
    Error::Usage(format!(
        "the level shown has {faces} faces, not the {split} of the split of the level below: no split to show"
    ))
}

/// The rule that made each vertex of `ids` at its level.
fn rules_of(control: &Mesh, (scheme, level, opts): (Scheme, u32, &Options), ids: &[u32]) -> Result<Vec<(u32, String)>> {
    ids.iter()
        .map(|&id| {
            let st = stencil(control, scheme, level, opts, id)?;
            Ok((id, st.rules.last().map(|r| r.1.clone()).unwrap_or_default()))
        })
        .collect()
}

/// The four child corners of parent corner `c` and their O entries.
fn triangle_rows(old: &CornerTable, child: &CornerTable, nt: u32, c: u32) -> [Row; 4] {
    let a = a_of(nt, c);
    let row = |corner: u32, formula: &'static str, worked: String, derived: Option<u32>| Row {
        corner,
        formula,
        worked,
        derived,
        table: child.o(corner),
    };
    // O[d] for d = n(c) or p(c), then A of its inner step, then the outer step
    type Step = (fn(u32) -> u32, &'static str);
    let across = |d: u32, (inner, i_name): Step, (outer, o_name): Step| -> (String, Option<u32>) {
        match old.o(d) {
            None => (format!("O[{d}] = border"), None),
            Some(o) => {
                let (i, ai) = (inner(o), a_of(nt, inner(o)));
                (
                    format!("O[{d}] = {o}: {o_name}(A({i_name}({o}))) = {o_name}(A({i})) = {o_name}({ai})"),
                    Some(outer(ai)),
                )
            }
        }
    };
    let (wn, dn) = across(n(c), (n, "n"), (p, "p"));
    let (wp, dp) = across(p(c), (p, "p"), (n, "n"));
    [
        row(c, "O'[c] = A(c)", format!("A({c}) = 3·{nt}·{} + 3·{} = {a}", c % 3 + 1, c / 3), Some(a)),
        row(a, "O'[A(c)] = c", format!("{c}"), Some(c)),
        row(n(a), "O'[n(A(c))] = p(A(n(O[n(c)])))", wn, dn),
        row(p(a), "O'[p(A(c))] = n(A(p(O[p(c)])))", wp, dp),
    ]
}

/// The Split view of quad `x` of `shown` (level `level >= 1` of a polygon
/// scheme over `control`); `child` is the shown level's quad table.
///
/// # Errors
/// As [`triangle_split`].
pub(crate) fn quad_split(
    control: &Mesh,
    child: &PolyTable,
    (scheme, level, opts): (Scheme, u32, &Options),
    x: u32,
) -> Result<SplitView> {
    check(level, x, child.num_faces())?;
    let cage = PolyTable::from_corner_table(&control.ct);
    let old = crate::subdiv::refine::build::tables(&cage, (scheme, level - 1, opts))?.1;
    if child.num_faces() != old.num_corners() {
        return Err(not_the_split(child.num_faces(), old.num_corners()));
    }
    let f = old.face(x);
    let cs: Vec<u32> = old.face_corners(f).collect();
    // child quad c has the corners 4c .. 4c + 3 (the formulas' numbering)
    let at = |c: u32, k: u32| child.vtx(4 * c + k);
    let edge_points: Vec<u32> = cs.iter().map(|&c| at(c, 1)).collect();
    let face_point = at(cs[0], 2);
    let ids: Vec<u32> = edge_points.iter().copied().chain([face_point]).collect();
    let new_vertices = rules_of(control, (scheme, level, opts), &ids)?;
    let old_vertices: Vec<u32> = cs.iter().map(|&c| old.vtx(c)).collect();
    let outline = cs.iter().flat_map(|&c| [at(c, 0), at(c, 1)]).collect();
    let rows = cs.iter().flat_map(|&c| quad_rows(&old, child, c)).collect();
    let child_vertices = cs.iter().map(|&c| (0..4).map(|k| at(c, k)).collect()).collect();
    Ok(SplitView {
        kind: Kind::Quads,
        level,
        picked: x,
        parent: f,
        parent_corners: cs.clone(),
        children: cs,
        new_vertices,
        old_vertices,
        outline,
        inner: edge_points.iter().map(|&e| (e, face_point)).collect(),
        child_vertices,
        rows,
    })
}

/// The four child corners of parent corner `c` and their twins.
fn quad_rows(old: &PolyTable, child: &PolyTable, c: u32) -> [Row; 4] {
    let row = |corner: u32, formula: &'static str, worked: String, derived: Option<u32>| Row {
        corner,
        formula,
        worked,
        derived,
        table: child.twin(corner),
    };
    let (nx, pv) = (old.next(c), old.prev(c));
    let first = match old.twin(c) {
        None => (format!("T[{c}] = border"), None),
        Some(t) => (format!("T[{c}] = {t}; 4·next({t}) + 3 = 4·{} + 3", old.next(t)), Some(4 * old.next(t) + 3)),
    };
    let last = match old.twin(pv) {
        None => (format!("prev({c}) = {pv}; T[{pv}] = border"), None),
        Some(t) => (format!("prev({c}) = {pv}; 4·T[{pv}] = 4·{t}"), Some(4 * t)),
    };
    [
        row(4 * c, "T'[4c] = 4 next(T[c]) + 3", first.0, first.1),
        row(4 * c + 1, "T'[4c+1] = 4 next(c) + 2", format!("4·next({c}) + 2 = 4·{nx} + 2"), Some(4 * nx + 2)),
        row(4 * c + 2, "T'[4c+2] = 4 prev(c) + 1", format!("4·prev({c}) + 1 = 4·{pv} + 1"), Some(4 * pv + 1)),
        row(4 * c + 3, "T'[4c+3] = 4 T[prev(c)]", last.0, last.1),
    ]
}

impl SplitView {
    /// Whether every entry the formulas give is the child table's.
    pub(crate) fn all_agree(&self) -> bool {
        self.rows.iter().all(|r| r.derived == r.table)
    }

    /// The face's name at a level (`triangle`, `quad`; the parent of a
    /// level-1 quad is the file's polygon).
    pub(crate) fn face_words(&self) -> (&'static str, &'static str) {
        match self.kind {
            Kind::Triangles => ("triangle", "triangle"),
            Kind::Quads if self.level == 1 => ("quad", "face"),
            Kind::Quads => ("quad", "quad"),
        }
    }

    /// The marks on the shown level (`positions`: its drawn points): the
    /// parent's outline, the children's inner edges, the old and new
    /// vertices with their ids (and the rules of the new ones), each child's
    /// id at its centroid.
    pub(crate) fn overlay(&self, positions: &[Vec3]) -> Overlay {
        let at = |v: u32| positions.get(v as usize).copied().unwrap_or(Vec3::NAN);
        let mut marks = Vec::new();
        let k = self.outline.len();
        for i in 0..k {
            let (a, b) = (at(self.outline[i]), at(self.outline[(i + 1) % k]));
            marks.push(Mark::Segment { a, b, color: ACCENT, width: 3.0 });
        }
        for &(a, b) in &self.inner {
            marks.push(Mark::Segment { a: at(a), b: at(b), color: [235, 235, 235, 255], width: 2.0 });
        }
        let (child_word, parent_word) = self.face_words();
        for (f, vs) in self.children.iter().zip(&self.child_vertices) {
            let centroid = vs.iter().map(|&v| at(v)).sum::<Vec3>() / vs.len().max(1) as f32;
            let color = if *f == self.picked { ACCENT } else { [200, 200, 200, 255] };
            marks.push(Mark::Text { at: centroid, text: format!("{} {f}", &child_word[..1]), color });
        }
        for &v in &self.old_vertices {
            marks.push(Mark::Disc { at: at(v), radius: 5.0, color: ACCENT, label: Some(v.to_string()) });
        }
        let new = [90, 200, 255, 255];
        for (v, rule) in &self.new_vertices {
            let label = Some(format!("{v}: {}", rule_short(rule)));
            marks.push(Mark::Disc { at: at(*v), radius: 5.0, color: new, label });
        }
        let caption = vec![
            format!(
                "{child_word} {} of level {}: a child of {parent_word} {} of level {}",
                self.picked,
                self.level,
                self.parent,
                self.level - 1
            ),
            format!("children {:?}", self.children),
        ];
        Overlay { marks, caption }
    }
}
