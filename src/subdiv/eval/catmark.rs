//! Exact evaluation of the Catmull-Clark limit surface by local
//! subdivision, the way `local.rs` evaluates Loop near sharp features.
//!
//! ```text
//! point    (p, u, v): p a ptex face (OpenSubdiv's numbering: a quad is one,
//!          a face of n != 4 corners is n, one per corner, in face order),
//!          (u, v) in [0, 1]^2: a quad's corners 0 1 2 3 at (0,0) (1,0)
//!          (1,1) (0,1); the sub-face of corner k of an n-gon is the quad
//!          of its first level (corner vertex, edge leaving, face point,
//!          edge entering) at the same four corners
//! step     one Catmull-Clark level of the faces around the point's quad F
//!          by the library's own rule code (the rows the polygon stencil
//!          plans record: creases, corners, semi-sharp and Chaikin rules),
//!          in f64, each row's weights summing to one; the point moves to
//!          the quadrant that holds it (the split makes quad c of corner c)
//! stop     F's four vertices are regular: smooth with valence 4 and
//!          quads around; on two infinitely sharp edges (border or crease)
//!          with two quads on F's side; or a corner (infinitely sharp, or
//!          on three or more such edges) with F alone on its side. F is
//!          then the bicubic B-spline of its 4 x 4 lattice points, a point
//!          missing beyond a sharp edge extrapolated as 2 b - i along its
//!          row or column (OpenSubdiv's regular boundary and corner
//!          patches, `far/patchBasis.cpp`, `adjustBSplineBoundaryWeights`)
//! vertex   the point at a corner of F (or nearer than the levels left
//!          could tell apart) whose vertex is a border, crease or corner
//!          vertex, on an all-quad level with no semi-sharp feature left:
//!          the vertex's limit masks (`sector.rs`)
//! cap      after MAX_LEVELS the point is within 2^-60 of the quad's size
//!          from an extraordinary or irregular vertex: the position is the
//!          quad's, the normal its diagonals' (the control face's where
//!          that degenerates), derivatives and curvature NaN
//! ```
//!
//! Near an extraordinary vertex the levels grow as log2 of 1 / distance
//! (there is no power table for Catmull-Clark yet), bounded by the cap.

use super::finish::{Affine, finish};
use super::local::{Fans, MAX_LEVELS, Memo, apply_rows, fans};
use super::patch::Jet;
use super::points::EDGE_SLACK;
use super::sector::{at_corner, finite_normal, stationary, vertex_limit};
use super::{Limit, Sample};
use crate::mesh::edges::EdgeTable;
use crate::mesh::poly::{PolyMesh, PolyTable};
use crate::mesh::sharpness::INFINITE;
use crate::subdiv::Options;
use crate::subdiv::rules::features::boundary_tagged;
use crate::subdiv::tables::poly_plan::record_one_catmark_level;
use crate::{Error, Result};
use glam::DVec3;

/// Catmull-Clark's local subdivision kept between points.
pub(crate) type CatmarkMemo = Memo<Region, (PolyTable, Vec<DVec3>)>;

/// Ptex faces: `(face, corner)`, the corner [`QUAD`] for a quad.
pub const QUAD: u32 = u32::MAX;

/// The control polygons as the local subdivision reads them.
pub(crate) struct Poly {
    pt: PolyTable,
    pos: Vec<DVec3>,
    opts: Options,
    /// Every ptex face's polygon and corner.
    ptex: Vec<(u32, u32)>,
}

/// The ptex faces of `pt` (module docs).
pub fn ptex_faces(pt: &PolyTable) -> Vec<(u32, u32)> {
    let mut out = Vec::with_capacity(pt.num_faces());
    for f in 0..pt.num_faces() as u32 {
        match pt.face_size(f) {
            4 => out.push((f, QUAD)),
            n => out.extend((0..n).map(|k| (f, k))),
        }
    }
    out
}

impl Poly {
    /// `mesh` with its boundary corners tagged as `opts` asks, the control
    /// positions `pos` (f64, one per vertex).
    pub(crate) fn new(mesh: &PolyMesh, pos: Vec<DVec3>, opts: &Options) -> Poly {
        let pt = boundary_tagged(&mesh.pt, opts.boundary).unwrap_or_else(|| mesh.pt.clone());
        let ptex = ptex_faces(&pt);
        Poly { pt, pos, opts: *opts, ptex }
    }

    /// Ptex faces.
    pub(crate) fn num_faces(&self) -> usize {
        self.ptex.len()
    }

    /// The limit surface at ptex face `p`, `(u, v)` in the unit square
    /// (checked by the caller), the levels of its face kept in `memo`.
    pub(crate) fn eval(&self, p: usize, (u, v): (f64, f64), second: bool, memo: &mut CatmarkMemo) -> Sample {
        let (f, corner) = self.ptex[p];
        let (mut st, mut jac) = ((u, v), Affine::IDENTITY.j);
        // a quad already regular needs no region
        if corner == QUAD
            && let Some(sample) = try_patch(&self.pt, &self.pos, (f, DVec3::ZERO), (st, jac), second)
        {
            return sample;
        }
        let subdivide = |r: &Region| subdivide(r, &self.opts);
        let cut = |child: u32| {
            move |r: &Region, (fine, pos): &(PolyTable, Vec<DVec3>)| extract(fine, |x| pos[x as usize], r.origin, child)
        };
        if !memo.start(f, || extract(&self.pt, |x| self.pos[x as usize], DVec3::ZERO, f)) {
            return Sample::NAN;
        }
        // the sub-face of a corner of an n-gon is the corner's quad of the first level
        let first = usize::from(corner != QUAD);
        if corner != QUAD {
            let child = memo.region(0).pt.face_corners(memo.region(0).face).start + corner;
            if !memo.descend(0, child, subdivide, cut(child)) {
                return Sample::NAN;
            }
        }
        for level in 0..MAX_LEVELS {
            let (i, region) = (first + level as usize, memo.region(first + level as usize));
            if let Some(sample) = try_patch(&region.pt, &region.pos, (region.face, region.origin), (st, jac), second)
                .or_else(|| at_sharp_vertex(region, st, level))
            {
                return sample;
            }
            let (k, map) = quadrant(st);
            let child = region.pt.face_corners(region.face).start + k;
            let (s, t) = map.apply(st);
            st = (s.clamp(0.0, 1.0), t.clamp(0.0, 1.0));
            jac = map.after(&Affine { j: jac, b: [0.0; 2] });
            if !memo.descend(i, child, subdivide, cut(child)) {
                return Sample::NAN;
            }
        }
        let region = memo.region(first + MAX_LEVELS as usize);
        let corners: Vec<DVec3> =
            region.pt.face_corners(region.face).map(|c| region.pos[region.pt.vtx(c) as usize]).collect();
        let (s, t) = st;
        let position = region.origin
            + corners[0] * ((1.0 - s) * (1.0 - t))
            + corners[1] * (s * (1.0 - t))
            + corners[2] * (s * t)
            + corners[3] * ((1.0 - s) * t);
        let normal = (corners[2] - corners[0]).cross(corners[3] - corners[1]).try_normalize().unwrap_or(DVec3::NAN);
        let control: Vec<DVec3> = self.pt.face_corners(f).map(|c| self.pos[self.pt.vtx(c) as usize]).collect();
        let k = control.len();
        let fallback = (0..k).map(|i| control[i].cross(control[(i + 1) % k])).sum::<DVec3>();
        Sample { position, normal: finite_normal(normal, [fallback]), ..Sample::NAN }
    }
}

impl Limit for Poly {
    fn faces(&self) -> usize {
        self.num_faces()
    }

    fn accepts(&self, f: usize) -> bool {
        f < self.num_faces()
    }

    #[inline]
    fn fits(&self, f: usize, u: f64, v: f64) -> bool {
        f < self.num_faces() && in_square(u, v)
    }

    #[inline]
    fn onto_domain(&self, u: f64, v: f64) -> (f64, f64) {
        (u.min(1.0), v.min(1.0))
    }

    /// Loop's `check_point` (`loop_surface.rs`) for a ptex face's unit square.
    fn check(&self, f: usize, u: f64, v: f64) -> Result<(f64, f64)> {
        let faces = self.num_faces();
        if f >= faces {
            return Err(Error::Usage(format!("ptex face {f} out of range (the mesh has {faces})")));
        }
        if !in_square(u, v) {
            return Err(Error::Usage(format!("({u}, {v}) is not in the unit square")));
        }
        Ok(self.onto_domain(u, v))
    }

    fn eval_checked(&self, f: usize, uv: (f64, f64), second: bool) -> Sample {
        self.eval(f, uv, second, &mut CatmarkMemo::default())
    }

    /// Each thread keeps a [`CatmarkMemo`]: consecutive points of one face
    /// share its first levels.
    fn eval_sorted<T: Send>(
        &self,
        sorted: &[(usize, (f64, f64))],
        second: bool,
        keep: impl Fn(&Sample) -> T + Sync,
    ) -> Vec<T> {
        super::in_parallel(sorted, CatmarkMemo::default, |memo, f, uv| keep(&self.eval(f, uv, second, memo)))
    }
}

/// `u` and `v` in `[0, 1]` with [`EDGE_SLACK`] (false for NaN).
#[inline]
fn in_square(u: f64, v: f64) -> bool {
    let unit = 0.0..=1.0 + EDGE_SLACK;
    unit.contains(&u) && unit.contains(&v)
}

/// The sample at a corner of the region's quad when the point `st` is
/// within reach of it (nearer than the levels left to the cap could tell
/// apart) and its vertex is on a sharp feature that [`vertex_limit`]
/// evaluates, on an all-quad level whose features are all infinitely sharp.
fn at_sharp_vertex(region: &Region, (s, t): (f64, f64), level: u32) -> Option<Sample> {
    if !region.pt.is_quads() || !stationary(region.pt.sharpness()) {
        return None;
    }
    let reach = 0.5f64.powi((MAX_LEVELS - level) as i32);
    let i = at_corner(&[s.max(t), (1.0 - s).max(t), (1.0 - s).max(1.0 - t), s.max(1.0 - t)], reach)?;
    let c = region.pt.face_corners(region.face).start + i as u32;
    let (position, normal) = vertex_limit(&region.pt, |x| region.pos[x as usize], c)?;
    Some(Sample { position: region.origin + position, normal, ..Sample::NAN })
}

/// The quadrant of a quad holding `(u, v)`: its corner `k` (whose child
/// quad the split numbers by that corner) and the map to the child's
/// `(s, t)` (the child's corners: the vertex, the edge leaving, the face
/// point, the edge entering).
fn quadrant((u, v): (f64, f64)) -> (u32, Affine) {
    let a = |j, b| Affine { j, b };
    match (u > 0.5, v > 0.5) {
        (false, false) => (0, a([[2.0, 0.0], [0.0, 2.0]], [0.0, 0.0])),
        (true, false) => (1, a([[0.0, 2.0], [-2.0, 0.0]], [0.0, 2.0])),
        (true, true) => (2, a([[-2.0, 0.0], [0.0, -2.0]], [2.0, 2.0])),
        (false, true) => (3, a([[0.0, -2.0], [2.0, 0.0]], [2.0, 0.0])),
    }
}

/// The faces around the point's face, positions relative to `origin`.
pub(crate) struct Region {
    pt: PolyTable,
    pos: Vec<DVec3>,
    origin: DVec3,
    face: u32,
}

/// The faces of `pt` at the vertices of face `face` or their neighbours,
/// recentred on the face, its rim vertices split by [`fans`]. `None` if the
/// table cannot be built.
fn extract(pt: &PolyTable, pos: impl Fn(u32) -> DVec3, origin: DVec3, face: u32) -> Option<Region> {
    let own: Vec<u32> = pt.face_corners(face).map(|c| pt.vtx(c)).collect();
    let mut near = own.clone();
    for &v in &own {
        pt.each_edge_at(v, &mut |_, w| near.push(w));
    }
    near.sort_unstable();
    near.dedup();
    let mut faces: Vec<u32> = near.iter().flat_map(|&v| pt.fan(v).map(|c| pt.face(c))).collect();
    faces.sort_unstable();
    faces.dedup();
    let local = |f: u32| faces.binary_search(&f).ok().map(|i| i as u32);
    let mut starts = vec![0u32];
    let mut global: Vec<u32> = Vec::new();
    for &f in &faces {
        global.extend(pt.face_corners(f));
        starts.push(global.len() as u32);
    }
    let lc_of = |c: u32| -> Option<u32> {
        let i = local(pt.face(c))? as usize;
        Some(starts[i] + (c - pt.face_corners(faces[i]).start))
    };
    let Fans { corners, verts, sharp } = fans(&global, |c| pt.vtx(c), |c| pt.swing(c).and_then(lc_of), pt.sharpness());
    let centre = own.iter().map(|&v| pos(v)).sum::<DVec3>() / own.len() as f64;
    let (table, _, kept) = PolyTable::build(verts.len(), &starts, &corners, None).ok()?;
    if kept.is_some() || table.v_table() != corners.as_slice() {
        return None;
    }
    Some(Region {
        pt: table.with_sharpness(sharp),
        pos: verts.iter().map(|&g| pos(g) - centre).collect(),
        origin: origin + centre,
        face: local(face)?,
    })
}

/// One Catmull-Clark level of `r` in f64.
fn subdivide(r: &Region, opts: &Options) -> (PolyTable, Vec<DVec3>) {
    let (plan, fine) = record_one_catmark_level(&r.pt, opts);
    (fine, apply_rows(&plan, &r.pos))
}

/// Whether the vertex of corner `c` of F keeps F a regular patch (module
/// docs).
fn regular(pt: &PolyTable, c: u32) -> bool {
    let v = pt.vtx(c);
    let sv = pt.sharpness().map_or(0.0, |s| s.vertex(v));
    if sv > 0.0 && sv < INFINITE {
        return false;
    }
    let (mut sharp, mut finite) = (0, false);
    pt.each_edge_at(v, &mut |e, _| match pt.edge_sharpness(e) {
        s if s >= INFINITE => sharp += 1,
        s if s > 0.0 => finite = true,
        _ => {}
    });
    if finite {
        return false;
    }
    match (sv >= INFINITE || sharp >= 3, sharp) {
        (true, _) => side_faces(pt, c) == Some(1),
        (false, 2) => side_faces(pt, c) == Some(2),
        (false, 0) => pt.valence(v) == 4 && pt.fan(v).all(|x| pt.face_size(pt.face(x)) == 4),
        _ => false,
    }
}

/// The faces around `V[c]` between the sharp edges on either side of
/// `c`, if they are all quads.
fn side_faces(pt: &PolyTable, c: u32) -> Option<u32> {
    let mut count = 1;
    let quad = |x: u32| pt.face_size(pt.face(x)) == 4;
    for forward in [true, false] {
        let mut x = c;
        loop {
            // forward crosses the edge entering x, backward the one leaving it
            let edge = if forward { pt.prev(x) } else { x };
            if pt.edge_sharpness(edge) > 0.0 {
                break;
            }
            let y = if forward { pt.swing(x) } else { pt.twin(x).map(|t| pt.next(t)) };
            match y {
                Some(y) if y != c && quad(y) => (x, count) = (y, count + 1),
                _ => return None,
            }
        }
    }
    quad(c).then_some(count)
}

type Coord = (i32, i32);

/// The 4 x 4 points of F's bicubic B-spline, row by row from `(-1, -1)`:
/// the vertices of the quads at F's corners laid on the lattice from F's
/// corners `(0,0) (1,0) (1,1) (0,1)` without crossing a sharp edge at a
/// corner of F, a missing point extrapolated along its row, then its
/// column. `None` off the lattice or with a point missing.
fn grid(pt: &PolyTable, pos: &[DVec3], face: u32) -> Option<[DVec3; 16]> {
    let own: Vec<u32> = pt.face_corners(face).map(|c| pt.vtx(c)).collect();
    if own.len() != 4 {
        return None;
    }
    let mut coord: Vec<(u32, Coord)> = own.iter().copied().zip([(0, 0), (1, 0), (1, 1), (0, 1)]).collect();
    let (mut queue, mut seen) = (vec![face], vec![face]);
    let at = |coord: &[(u32, Coord)], v: u32| coord.iter().find(|x| x.0 == v).map(|x| x.1);
    while let Some(f) = queue.pop() {
        for c in pt.face_corners(f) {
            let (a, b) = (pt.vtx(c), pt.vtx(pt.next(c)));
            if (own.contains(&a) || own.contains(&b)) && pt.edge_sharpness(c) > 0.0 {
                continue;
            }
            let Some(x) = pt.twin(c) else { continue };
            let g = pt.face(x);
            if seen.contains(&g) || !pt.face_corners(g).any(|y| own.contains(&pt.vtx(y))) {
                continue;
            }
            if pt.face_size(g) != 4 {
                return None;
            }
            // across the edge a -> b of (d, a, b, e): (b, a, 2a - d, 2b - e)
            let (ca, cb) = (at(&coord, a)?, at(&coord, b)?);
            let (cd, ce) = (at(&coord, pt.vtx(pt.prev(c)))?, at(&coord, pt.vtx(pt.next(pt.next(c))))?);
            let want = [
                (pt.next(pt.next(x)), (2 * ca.0 - cd.0, 2 * ca.1 - cd.1)),
                (pt.prev(x), (2 * cb.0 - ce.0, 2 * cb.1 - ce.1)),
            ];
            for (y, w) in want {
                match at(&coord, pt.vtx(y)) {
                    Some(have) if have != w => return None,
                    Some(_) => {}
                    None => coord.push((pt.vtx(y), w)),
                }
            }
            seen.push(g);
            queue.push(g);
        }
    }
    let mut pts: [Option<DVec3>; 16] = [None; 16];
    for &(v, (x, y)) in &coord {
        if (-1..=2).contains(&x) && (-1..=2).contains(&y) {
            pts[((y + 1) * 4 + x + 1) as usize] = Some(pos[v as usize]);
        }
    }
    // rows, then columns: a corner's phantom comes from its row's phantoms
    for (step, lines) in [(1usize, [0usize, 4, 8, 12]), (4, [0, 1, 2, 3])] {
        for first in lines {
            let i = |k: usize| first + k * step;
            if pts[i(0)].is_none() {
                pts[i(0)] = Some(pts[i(1)]? * 2.0 - pts[i(2)]?);
            }
            if pts[i(3)].is_none() {
                pts[i(3)] = Some(pts[i(2)]? * 2.0 - pts[i(1)]?);
            }
        }
    }
    let mut out = [DVec3::ZERO; 16];
    for (o, p) in out.iter_mut().zip(pts) {
        *o = p?;
    }
    Some(out)
}

/// The cubic B-spline basis at `t` and its first and second derivatives.
fn basis(t: f64) -> [[f64; 4]; 3] {
    let (t2, t3) = (t * t, t * t * t);
    [
        [
            (1.0 - 3.0 * (t - t2) - t3) / 6.0,
            (4.0 - 6.0 * t2 + 3.0 * t3) / 6.0,
            (1.0 + 3.0 * (t + t2 - t3)) / 6.0,
            t3 / 6.0,
        ],
        [-0.5 * t2 + t - 0.5, 1.5 * t2 - 2.0 * t, -1.5 * t2 + t + 0.5, 0.5 * t2],
        [1.0 - t, 3.0 * t - 2.0, 1.0 - 3.0 * t, t],
    ]
}

/// The bicubic B-spline of `pts` (row by row) at `(s, t)`.
fn bspline(pts: &[DVec3; 16], s: f64, t: f64) -> Jet {
    let (bs, bt) = (basis(s), basis(t));
    let sum = |a: usize, b: usize| -> DVec3 {
        let mut out = DVec3::ZERO;
        for (row, &wt) in bt[b].iter().enumerate() {
            for (col, &ws) in bs[a].iter().enumerate() {
                out += pts[row * 4 + col] * (ws * wt);
            }
        }
        out
    };
    Jet { p: sum(0, 0), ds: sum(1, 0), dt: sum(0, 1), dss: sum(2, 0), dst: sum(1, 1), dtt: sum(0, 2) }
}

/// The regular patch of `face` of `pt` (points `pos` relative to
/// `origin`) at `st` if the face is one, `jac` the derivative of `st` with
/// respect to the ptex face's `(u, v)`.
fn try_patch(
    pt: &PolyTable,
    pos: &[DVec3],
    (face, origin): (u32, DVec3),
    (st, jac): ((f64, f64), [[f64; 2]; 2]),
    second: bool,
) -> Option<Sample> {
    if !pt.face_corners(face).all(|c| regular(pt, c)) {
        return None;
    }
    let pts = grid(pt, pos, face)?;
    let mut sample = finish(&bspline(&pts, st.0, st.1), DVec3::ZERO, 1.0, jac, 1.0, second);
    sample.position += origin;
    Some(sample)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_basis_is_a_partition_of_unity_and_its_derivatives_sum_to_zero() {
        for t in [0.0, 0.3, 1.0] {
            let b = basis(t);
            assert!((b[0].iter().sum::<f64>() - 1.0).abs() < 1e-15);
            assert!(b[1].iter().sum::<f64>().abs() < 1e-15 && b[2].iter().sum::<f64>().abs() < 1e-15);
        }
    }

    #[test]
    fn a_bilinear_grid_is_reproduced() {
        let mut pts = [DVec3::ZERO; 16];
        for (i, p) in pts.iter_mut().enumerate() {
            *p = DVec3::new((i % 4) as f64 - 1.0, (i / 4) as f64 - 1.0, 0.0);
        }
        let j = bspline(&pts, 0.25, 0.6);
        assert!((j.p - DVec3::new(0.25, 0.6, 0.0)).length() < 1e-14);
        assert!((j.ds - DVec3::X).length() < 1e-14 && (j.dt - DVec3::Y).length() < 1e-14);
    }
}
