//! Exact evaluation of the faces near a boundary or a sharp feature, by
//! local subdivision (the second construction of docs/evaluation.md).
//!
//! ```text
//! region   the faces around the point's face F: those incident to F's
//!          vertices or their neighbours, with the sharpness they carry,
//!          positions in f64 relative to F's centre
//! step     one Loop level of the region by the library's own rule code
//!          (the rows the stencil plans record: boundary, crease, corner,
//!          semi-sharp and Chaikin rules exactly as `subdivide` runs them),
//!          applied in f64 with each row's weights summing to one; the
//!          point moves to the child of F that holds it; the next region
//!          is cut around that child
//! stop     1. F's three vertices are regular: smooth with valence 6, or
//!             on exactly two infinitely sharp edges (a border or a crease)
//!             with three faces on F's side: F is the quartic box spline of
//!             its 12 lattice points, where a point missing beyond a sharp
//!             edge (a, b) of a triangle (a, b, r) is the phantom
//!             a + b - r (OpenSubdiv's regular boundary patches,
//!             `far/patchBasis.cpp`, `adjustBoxSplineTriBoundaryWeights`);
//!          2. one vertex is a smooth extraordinary vertex and the other two
//!             are smooth with valence 6: the power table of its valence
//!             (`extraordinary.rs`), however close the point is;
//!          3. the point is at a corner of F (or nearer to it than the
//!             levels left could tell apart) whose vertex is a border,
//!             crease or corner vertex, and no semi-sharp feature is left
//!             in the region: the vertex's limit masks (`sector.rs`);
//!          4. otherwise another level; after MAX_LEVELS the point is
//!             within 2^-60 of the face's size from an irregular vertex on
//!             a sharp feature (a dart, a cone): its position is the face's
//!             (closer to the limit than a double resolves), its normal the
//!             face's (the control face's where that degenerates), the
//!             derivatives and curvature NaN.
//! ```
//!
//! A region's rim (vertices whose faces are not all in it) is subdivided
//! with wrong rules, but nothing the next region keeps depends on the rim:
//! the vertex points of F's vertices and their neighbours and the edge
//! points of edges touching them read only the region's faces. Semi-sharp
//! features decay in at most [`crate::mesh::sharpness::INFINITE`] levels;
//! infinitely sharp ones are stationary, and a face touching them stops by
//! rule 1 as soon as its corners are regular.

use super::Sample;
use super::extraordinary::Extraordinary;
use super::finish::{Affine, finish};
use super::level1::walk;
use super::loop_surface::{near_vertex, rotation};
use super::patch::{self, BoxSpline, SUPPORT};
use super::sector::{at_corner, finite_normal, stationary, vertex_limit};
use crate::mesh::sharpness::{INFINITE, Sharpness};
use crate::mesh::{CornerTable, Mesh, n, p};
use crate::subdiv::rules::features::with_boundary_corners;
use crate::subdiv::tables::plan::record_one_level;
use crate::subdiv::tables::rows::LevelPlan;
use crate::subdiv::{Options, Scheme};
use glam::DVec3;
use std::borrow::Cow;

/// Levels of local subdivision before rule 3's last resort (module docs).
pub(crate) const MAX_LEVELS: u32 = 60;

/// The control mesh as the local subdivision reads it.
pub(crate) struct Base<'a> {
    ct: Cow<'a, CornerTable>,
    pos: Cow<'a, [DVec3]>,
    opts: Options,
}

impl Base<'static> {
    /// `mesh`'s table with its boundary corners tagged as `opts` asks, and
    /// the control positions `pos` (f64), copied.
    pub(crate) fn new(mesh: &Mesh, pos: &[DVec3], opts: &Options) -> Base<'static> {
        let ct = with_boundary_corners(&mesh.ct, opts.boundary).into_owned();
        Base { ct: Cow::Owned(ct), pos: Cow::Owned(pos.to_vec()), opts: *opts }
    }
}

impl<'a> Base<'a> {
    /// `mesh`'s table with its boundary corners tagged as `opts` asks,
    /// borrowed where no corner is tagged, and the positions `pos`.
    pub(crate) fn borrowed(mesh: &'a Mesh, pos: &'a [DVec3], opts: &Options) -> Base<'a> {
        let ct = with_boundary_corners(&mesh.ct, opts.boundary);
        Base { ct, pos: Cow::Borrowed(pos), opts: *opts }
    }
}

/// The tables a patch is evaluated with.
pub(crate) struct Tables<'a> {
    pub(crate) spline: &'a BoxSpline,
    pub(crate) valences: &'a [Option<Extraordinary>],
}

/// The faces around the point's face `face`, positions relative to `origin`.
pub(crate) struct Region {
    ct: CornerTable,
    pos: Vec<DVec3>,
    origin: DVec3,
    face: u32,
}

/// The root of `x` in the union-find forest `root` (halving the path).
fn find(root: &mut [u32], mut x: u32) -> u32 {
    while root[x as usize] != x {
        root[x as usize] = root[root[x as usize] as usize];
        x = root[x as usize];
    }
    x
}

/// A region's vertices: the local vertex of each of its corners, the
/// global id of each local vertex, and the region's sharpness.
pub(super) struct Fans {
    pub(super) corners: Vec<u32>,
    pub(super) verts: Vec<u32>,
    pub(super) sharp: Option<Sharpness>,
}

/// The [`Fans`] of a region whose corners are `global` (corner ids of the
/// whole table, `vtx` their vertices, `swing(c)` the region's corner after
/// `c` around its vertex, if in the region): corners joined by swings share
/// a local vertex, so a vertex whose faces here form two fans (on the rim
/// only) becomes two and the region is a manifold table. The sharpness of
/// an edge goes with the corner naming it, a vertex's with each copy.
pub(super) fn fans(
    global: &[u32],
    vtx: impl Fn(u32) -> u32,
    swing: impl Fn(u32) -> Option<u32>,
    sharpness: Option<&Sharpness>,
) -> Fans {
    let mut root: Vec<u32> = (0..global.len() as u32).collect();
    for (lc, &c) in global.iter().enumerate() {
        if let Some(j) = swing(c) {
            let (a, b) = (find(&mut root, lc as u32), find(&mut root, j));
            root[a as usize] = b;
        }
    }
    let mut id = vec![u32::MAX; global.len()];
    let (mut corners, mut verts) = (Vec::with_capacity(global.len()), Vec::new());
    for (lc, &c) in global.iter().enumerate() {
        let r = find(&mut root, lc as u32) as usize;
        if id[r] == u32::MAX {
            id[r] = verts.len() as u32;
            verts.push(vtx(c));
        }
        corners.push(id[r]);
    }
    let sharp = sharpness.and_then(|s| {
        let edges = global.iter().enumerate().map(|(lc, &c)| (lc as u32, s.corner(c))).filter(|x| x.1 > 0.0).collect();
        let vertices = verts.iter().enumerate().map(|(l, &g)| (l as u32, s.vertex(g))).filter(|x| x.1 > 0.0).collect();
        Sharpness::from_lists(edges, vertices)
    });
    Fans { corners, verts, sharp }
}

/// The region around triangle `face` of `ct` (positions `pos`, relative to
/// `origin`), recentred on the face, its rim vertices split by [`fans`].
/// `None` if the table cannot be built.
fn extract(ct: &CornerTable, pos: impl Fn(u32) -> DVec3, origin: DVec3, face: u32) -> Option<Region> {
    let mut near: Vec<u32> = Vec::with_capacity(32);
    for c in 3 * face..3 * face + 3 {
        near.push(ct.vtx(c));
        near.extend(ct.ring(ct.vtx(c)));
    }
    near.sort_unstable();
    near.dedup();
    let mut faces: Vec<u32> = near.iter().flat_map(|&v| ct.fan(v).map(|c| c / 3)).collect();
    faces.sort_unstable();
    faces.dedup();
    let local = |t: u32| faces.binary_search(&t).ok().map(|i| i as u32);
    let global: Vec<u32> = faces.iter().flat_map(|&t| 3 * t..3 * t + 3).collect();
    let swing = |c: u32| ct.s(c).and_then(|s| Some(3 * local(s / 3)? + s % 3));
    let Fans { corners: tris, verts, sharp } = fans(&global, |c| ct.vtx(c), swing, ct.sharpness());
    let centre = (0..3).map(|i| pos(ct.vtx(3 * face + i))).sum::<DVec3>() / 3.0;
    let (table, _, remap) = CornerTable::build(verts.len(), &tris, None).ok()?;
    // every vertex is used and the triangles keep their order and corners
    if remap.is_some() || table.v_table() != tris.as_slice() {
        return None;
    }
    Some(Region {
        ct: table.with_sharpness(sharp),
        pos: verts.iter().map(|&g| pos(g) - centre).collect(),
        origin: origin + centre,
        face: local(face)?,
    })
}

/// One Loop level of `r` in f64: the split table and its positions.
fn subdivide(r: &Region, opts: &Options) -> (CornerTable, Vec<DVec3>) {
    let (plan, fine) = record_one_level(&r.ct, Scheme::Loop, opts);
    (fine, apply_rows(&plan, &r.pos))
}

/// The rows of `plan` (a level whose old vertices have rows of their own)
/// on `pos` in f64, each row's weights scaled to sum to one.
pub(super) fn apply_rows(plan: &LevelPlan, pos: &[DVec3]) -> Vec<DVec3> {
    plan.offsets
        .windows(2)
        .map(|w| {
            let (a, b) = (w[0] as usize, w[1] as usize);
            let total: f64 = plan.weights[a..b].iter().map(|&x| f64::from(x)).sum();
            let sum: DVec3 = (a..b).map(|i| pos[plan.indices[i] as usize] * f64::from(plan.weights[i])).sum();
            sum / total
        })
        .collect()
}

/// The child of triangle `face` (of `nt`) holding `(u, v)` in the split's
/// layout (`src/mesh/split.rs`: the corner child of corner `j` is triangle
/// `nt (j + 1) + face` with corners `(v_j, mid(j, j+1), mid(j, j+2))`, the
/// central child keeps the id with corners `(mid12, mid20, mid01)`), and the
/// map to its `(s, t)`.
fn child_in_split(face: u32, nt: u32, (u, v): (f64, f64)) -> (u32, Affine) {
    let a = |j, b| Affine { j, b };
    if u + v <= 0.5 {
        (nt + face, a([[2.0, 0.0], [0.0, 2.0]], [0.0, 0.0]))
    } else if u >= 0.5 {
        (2 * nt + face, a([[0.0, 2.0], [-2.0, -2.0]], [0.0, 2.0]))
    } else if v >= 0.5 {
        (3 * nt + face, a([[-2.0, -2.0], [2.0, 0.0]], [2.0, 0.0]))
    } else {
        (face, a([[-2.0, 0.0], [0.0, -2.0]], [1.0, 1.0]))
    }
}

/// What the vertex of a corner of F is for the stopping rules.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    /// Smooth, valence 6.
    Regular,
    /// On exactly two infinitely sharp edges, three faces on F's side.
    Crease,
    /// Smooth, interior, valence `k >= 3`, not 6.
    Extraordinary(u32),
    /// Anything else: a corner, a dart, a semi-sharp feature, another
    /// number of faces on a crease.
    Other,
}

fn kind(ct: &CornerTable, c: u32) -> Kind {
    let v = ct.vtx(c);
    if ct.sharpness().is_some_and(|s| s.vertex(v) > 0.0) {
        return Kind::Other;
    }
    // the edge (v, v(n(x))) is opposite p(x) for each corner x of the fan;
    // a boundary fan's last edge is a border
    let mut sharp = u32::from(ct.is_boundary_vertex(v));
    for x in ct.fan(v) {
        match ct.edge_sharpness(p(x)) {
            s if s >= INFINITE => sharp += 1,
            s if s > 0.0 => return Kind::Other,
            _ => {}
        }
    }
    match (sharp, ct.valence(v)) {
        (0, 6) => Kind::Regular,
        (0, k) if k >= 3 => Kind::Extraordinary(k),
        (2, _) if side_faces(ct, c) == 3 => Kind::Crease,
        _ => Kind::Other,
    }
}

/// The faces around `v(c)` between the sharp edges on either side of `c`.
fn side_faces(ct: &CornerTable, c: u32) -> u32 {
    let mut count = 1;
    for forward in [true, false] {
        let mut x = c;
        loop {
            let edge = if forward { n(x) } else { p(x) };
            if ct.edge_sharpness(edge) > 0.0 {
                break;
            }
            match if forward { ct.s(x) } else { ct.u(x) } {
                Some(y) if y != c => (x, count) = (y, count + 1),
                _ => return u32::MAX,
            }
        }
    }
    count
}

type Coord = (i32, i32);

fn add(a: Coord, b: Coord, r: Coord) -> Coord {
    (a.0 + b.0 - r.0, a.1 + b.1 - r.1)
}

/// The 12 points of F's box spline in walk order (`patch.rs`): the
/// vertices of the faces around F's corners laid on the lattice from F's
/// corners `(0,0) (1,0) (1,1)`, without crossing a sharp edge at a corner
/// of F; a point missing beyond such an edge `(a, b)` of the triangle
/// `(a, b, r)` is the phantom `a + b - r`. `None` if the faces do not lie
/// on the lattice or a point is missing.
fn lattice_support(ct: &CornerTable, pos: impl Fn(u32) -> DVec3, face: u32) -> Option<[DVec3; 12]> {
    let corners = [ct.vtx(3 * face), ct.vtx(3 * face + 1), ct.vtx(3 * face + 2)];
    let mut coord: Vec<(u32, Coord)> = vec![(corners[0], (0, 0)), (corners[1], (1, 0)), (corners[2], (1, 1))];
    let mut phantoms: Vec<(Coord, DVec3)> = Vec::new();
    let (mut queue, mut seen) = (vec![face], vec![face]);
    let at = |coord: &[(u32, Coord)], v: u32| coord.iter().find(|x| x.0 == v).map(|x| x.1);
    while let Some(t) = queue.pop() {
        for c in 3 * t..3 * t + 3 {
            let (a, b, r) = (ct.vtx(n(c)), ct.vtx(p(c)), ct.vtx(c));
            let (ca, cb, cr) = (at(&coord, a)?, at(&coord, b)?, at(&coord, r)?);
            let x = add(ca, cb, cr);
            let touches = corners.contains(&a) || corners.contains(&b);
            if touches && ct.edge_sharpness(c) > 0.0 {
                phantoms.push((x, pos(a) + pos(b) - pos(r)));
                continue;
            }
            let Some(o) = ct.o(c) else { continue };
            let w = ct.vtx(o);
            let allowed = (3 * (o / 3)..3 * (o / 3) + 3).any(|y| corners.contains(&ct.vtx(y)));
            match at(&coord, w) {
                Some(have) if have != x => return None,
                Some(_) => {}
                None if allowed => coord.push((w, x)),
                None => continue,
            }
            if allowed && !seen.contains(&(o / 3)) {
                seen.push(o / 3);
                queue.push(o / 3);
            }
        }
    }
    let mut out = [DVec3::ZERO; 12];
    for (o, &want) in out.iter_mut().zip(&SUPPORT) {
        *o = match coord.iter().find(|x| x.1 == want) {
            Some(&(v, _)) => pos(v),
            None => phantoms.iter().find(|x| x.0 == want)?.1,
        };
    }
    Some(out)
}

/// Where rules 1 and 2 look: a table, its points (relative to `origin`) and
/// the point's face.
struct At<'a, P: Fn(u32) -> DVec3> {
    ct: &'a CornerTable,
    pos: P,
    origin: DVec3,
    face: u32,
}

/// Rules 1 and 2 of the module docs at the point `st` of `r`'s face, `jac`
/// the derivative of `st` with respect to the control face's `(u, v)`.
fn try_patch<P: Fn(u32) -> DVec3>(
    r: &At<P>,
    st: (f64, f64),
    jac: [[f64; 2]; 2],
    tables: &Tables,
    second: bool,
) -> Option<Sample> {
    let kinds = [0, 1, 2].map(|i| kind(r.ct, 3 * r.face + i));
    let mut sample = if kinds.iter().all(|k| matches!(k, Kind::Regular | Kind::Crease)) {
        let pts = lattice_support(r.ct, &r.pos, r.face)?;
        let jet = patch::jet(&tables.spline.basis, &pts, st.0, st.1, second);
        finish(&jet, DVec3::ZERO, 1.0, jac, 1.0, second)
    } else {
        let mut odd = kinds.iter().enumerate().filter(|(_, k)| **k != Kind::Regular);
        let (i, &Kind::Extraordinary(k)) = odd.next()? else { return None };
        if odd.next().is_some() {
            return None;
        }
        let table = tables.valences.get(k as usize)?.as_ref()?;
        let mut pts = Vec::with_capacity(k as usize + 6);
        walk(r.ct, 3 * r.face + i as u32, |v| pts.push((r.pos)(v)));
        let mut tmp = vec![DVec3::ZERO; pts.len()];
        let first = Affine { j: jac, b: [0.0; 2] };
        near_vertex(table, (&mut pts, &mut tmp), st, (rotation(i), first), second)
    };
    sample.position += r.origin;
    Some(sample)
}

/// The local subdivision of the last face evaluated, kept for the next
/// point (points come sorted by face, and a face's points share its first
/// levels): level `i` is a region `R` and, once made, its subdivision `F`;
/// each level's region is the child its predecessor's subdivision gave the
/// last point, so a point reuses the levels while its children agree with
/// the last point's. Loop's here, Catmull-Clark's in `catmark.rs`.
pub(crate) struct Memo<R, F> {
    levels: Vec<MemoLevel<R, F>>,
}

struct MemoLevel<R, F> {
    /// The face the region is cut around (a face of the control mesh at
    /// level 0, of the subdivision of the level before after it).
    key: u32,
    region: R,
    fine: Option<F>,
}

impl<R, F> Default for Memo<R, F> {
    fn default() -> Self {
        Memo { levels: Vec::new() }
    }
}

impl<R, F> Memo<R, F> {
    /// Whether level `i` is the region cut around `key`.
    fn holds(&self, i: usize, key: u32) -> bool {
        self.levels.get(i).is_some_and(|l| l.key == key)
    }

    /// Makes `region` (cut around `key`) level `i`, forgetting the levels
    /// after it; `i` at most the number of levels held.
    fn set(&mut self, i: usize, key: u32, region: R) {
        self.levels.truncate(i);
        self.levels.push(MemoLevel { key, region, fine: None });
    }

    /// Level `i`'s region (held: [`Memo::set`] made it).
    pub(super) fn region(&self, i: usize) -> &R {
        &self.levels[i].region
    }

    /// Makes level 0 the region `cut` makes around control face `key`,
    /// unless it is held; false when `cut` cannot.
    pub(super) fn start(&mut self, key: u32, cut: impl FnOnce() -> Option<R>) -> bool {
        if self.holds(0, key) {
            return true;
        }
        let Some(region) = cut() else { return false };
        self.set(0, key, region);
        true
    }

    /// Makes level `i + 1` the region `cut` makes around face `child` of
    /// level `i`'s subdivision (made by `subdivide` once), unless it is
    /// held; false when `cut` cannot.
    pub(super) fn descend(
        &mut self,
        i: usize,
        child: u32,
        subdivide: impl FnOnce(&R) -> F,
        cut: impl FnOnce(&R, &F) -> Option<R>,
    ) -> bool {
        if self.holds(i + 1, child) {
            return true;
        }
        let l = &mut self.levels[i];
        let region = &l.region;
        let Some(next) = cut(region, l.fine.get_or_insert_with(|| subdivide(region))) else { return false };
        self.set(i + 1, child, next);
        true
    }
}

/// Loop's local subdivision kept between points.
pub(crate) type LoopMemo = Memo<Region, (CornerTable, Vec<DVec3>)>;

/// The limit surface at `(u, v)` of control face `f` (checked by the
/// caller) by local subdivision, the levels of `f` kept in `memo`.
pub(crate) fn eval(
    base: &Base,
    tables: &Tables,
    f: u32,
    (u, v): (f64, f64),
    second: bool,
    memo: &mut LoopMemo,
) -> Sample {
    let control = |v: u32| base.pos[v as usize];
    let (mut st, mut jac) = ((u, v), Affine::IDENTITY.j);
    // a face already regular needs no region
    let at = At { ct: &base.ct, pos: control, origin: DVec3::ZERO, face: f };
    if let Some(sample) = try_patch(&at, st, jac, tables, second).or_else(|| at_sharp_vertex(&at, st, 0)) {
        return sample;
    }
    if !memo.start(f, || extract(&base.ct, control, DVec3::ZERO, f)) {
        return Sample::NAN;
    }
    for level in 0..=MAX_LEVELS {
        let (i, r) = (level as usize, memo.region(level as usize));
        if level > 0 {
            let at = At { ct: &r.ct, pos: |v: u32| r.pos[v as usize], origin: r.origin, face: r.face };
            if let Some(sample) = try_patch(&at, st, jac, tables, second).or_else(|| at_sharp_vertex(&at, st, level)) {
                return sample;
            }
        }
        if level == MAX_LEVELS {
            break;
        }
        let (child, map) = child_in_split(r.face, r.ct.num_triangles() as u32, st);
        let (s, t) = map.apply(st);
        let (s, t) = (s.clamp(0.0, 1.0), t.clamp(0.0, 1.0));
        st = if s + t > 1.0 { (s / (s + t), t / (s + t)) } else { (s, t) };
        jac = map.after(&Affine { j: jac, b: [0.0; 2] });
        let cut =
            |r: &Region, (fine, pos): &(CornerTable, Vec<DVec3>)| extract(fine, |v| pos[v as usize], r.origin, child);
        if !memo.descend(i, child, |r| subdivide(r, &base.opts), cut) {
            return Sample::NAN;
        }
    }
    let region = memo.region(MAX_LEVELS as usize);
    let corner = |i: u32| region.pos[region.ct.vtx(3 * region.face + i) as usize];
    let (a, b, c) = (corner(0), corner(1), corner(2));
    let position = region.origin + a * (1.0 - st.0 - st.1) + b * st.0 + c * st.1;
    let control_face = [0, 1, 2].map(|i| control(base.ct.vtx(3 * f + i)));
    let normal = (b - a).cross(c - a).try_normalize().unwrap_or(DVec3::NAN);
    let fallback = (control_face[1] - control_face[0]).cross(control_face[2] - control_face[0]);
    Sample { position, normal: finite_normal(normal, [fallback]), ..Sample::NAN }
}

/// The sample at a corner of `at`'s face when the point `st` is within
/// reach of it (nearer than the levels left to the cap could tell apart)
/// and its vertex is on a sharp feature that [`vertex_limit`] evaluates,
/// on a level whose features are all infinitely sharp.
fn at_sharp_vertex<P: Fn(u32) -> DVec3>(at: &At<P>, (s, t): (f64, f64), level: u32) -> Option<Sample> {
    if !stationary(at.ct.sharpness()) {
        return None;
    }
    let reach = 0.5f64.powi((MAX_LEVELS - level) as i32);
    let i = at_corner(&[s + t, 1.0 - s, 1.0 - t], reach)?;
    let (position, normal) = vertex_limit(at.ct, &at.pos, 3 * at.face + i as u32)?;
    Some(Sample { position: at.origin + position, normal, ..Sample::NAN })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes;

    #[test]
    fn a_regular_face_gathers_the_walk_support_from_the_lattice() {
        let mesh = shapes::icosphere(2);
        let ct = &mesh.ct;
        let pos: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
        let f = (0..ct.num_triangles() as u32).find(|&f| (0..3).all(|i| ct.valence(ct.vtx(3 * f + i)) == 6)).unwrap();
        let mut want = Vec::new();
        walk(ct, 3 * f, |v| want.push(pos[v as usize]));
        let got = lattice_support(ct, |v| pos[v as usize], f).unwrap();
        assert_eq!(got.to_vec(), want);
    }

    #[test]
    fn the_region_keeps_the_face_and_its_corners() {
        let mesh = shapes::icosphere(1);
        let pos: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
        let r = extract(&mesh.ct, |v| pos[v as usize], DVec3::ZERO, 7).unwrap();
        for i in 0..3 {
            let here = r.pos[r.ct.vtx(3 * r.face + i) as usize] + r.origin;
            assert!((here - pos[mesh.ct.vtx(21 + i) as usize]).length() < 1e-12);
            assert_eq!(r.ct.valence(r.ct.vtx(3 * r.face + i)), mesh.ct.valence(mesh.ct.vtx(21 + i)));
        }
    }
}
