//! The limit surface to a tolerance: an adaptive, crack-free triangle mesh
//! whose vertices lie on the exact limit surface and whose triangles stay
//! within a distance `T` of it (docs/tessellation.md).
//!
//! The domain is the evaluator's (`domain.rs`): Loop's control triangles,
//! Catmull-Clark's ptex faces. Each patch gets an interior rate `n` and
//! each edge of the domain a rate of its own, the larger of what the
//! patches on either side ask for, so that the two sides share its points
//! (`grid.rs` stitches a patch's inside to whatever its sides hold). The
//! rates come from the surface itself (`rates.rs`): the patch's second
//! derivatives, sampled, give the first guess, and then every triangle is
//! measured against the exact limit at its centre and the midpoints of its
//! edges; a patch with a triangle over `T` is made finer, until none is.
//! Every vertex is evaluated once, so shared edges are shared vertices: a
//! closed cage gives a closed, watertight mesh.

mod domain;
mod grid;
mod rates;
mod session;
mod view;

use crate::clock::Instant;
use crate::mesh::Mesh;
use crate::mesh::poly::PolyMesh;
use crate::subdiv::eval::Evaluator;
use crate::subdiv::{Options, Scheme};
use crate::{Error, Result};
use domain::Domain;
use glam::DVec3;
use grid::Pt;
use rayon::prelude::*;
pub use session::Tessellator;
pub use view::{ScreenTolerance, Tolerance};

/// What [`tessellate`] made.
#[derive(Clone, Debug)]
pub struct Tessellation {
    /// Points on the exact limit surface.
    pub positions: Vec<DVec3>,
    /// The limit surface's unit normal at each point, on the side the
    /// control faces' winding makes their front.
    pub normals: Vec<DVec3>,
    /// Triangles, counter-clockwise seen from the front of the control
    /// faces.
    pub triangles: Vec<[u32; 3]>,
    /// Each triangle's control face (Loop: control triangle; Catmull-Clark:
    /// ptex face).
    pub faces: Vec<u32>,
    /// Each vertex's control face and `(u, v)` on it, as
    /// [`Evaluator::eval`] takes them (Loop: control triangle; Catmull-Clark:
    /// ptex face), for evaluating attributes later without refining.
    pub params: Vec<(u32, f64, f64)>,
    /// How it went.
    pub stats: TessellationStats,
    /// Each triangle's corners' `(u, v)` on its control face (`faces`):
    /// where a point of the triangle lies on the limit's domain (a vertex
    /// shared by two control faces has one `params` entry but a corner in
    /// each).
    pub corners: Vec<[(f64, f64); 3]>,
    /// The scheme, which says what `faces` number, and its options.
    scheme: Scheme,
    opts: Options,
}

impl Tessellation {
    /// The limit of data given per control vertex (`values`, one per vertex
    /// of `mesh`, the mesh tessellated: colours, say) at each output vertex,
    /// by the same exact evaluation as the positions: vertex-varying data
    /// subdivide as the points do.
    ///
    /// # Errors
    /// [`Error::Usage`] when `values` has not one value per vertex of `mesh`.
    pub fn vertex_values(&self, mesh: &Mesh, values: &[DVec3]) -> Result<Vec<DVec3>> {
        if values.len() != mesh.positions.len() {
            let vertices = mesh.positions.len();
            return Err(Error::Usage(format!("{} values for the {vertices} vertices", values.len())));
        }
        let ev = Evaluator::new_f64(mesh, values, self.scheme, &self.opts)?;
        let at: Vec<(usize, f64, f64)> = self.params.iter().map(|&(f, u, v)| (f as usize, u, v)).collect();
        ev.eval_map(&at, false, |s| s.position)
    }

    /// Texture coordinates of the output, three per triangle in the order
    /// of [`Tessellation::triangles`], from the control mesh's `uv` (one
    /// per corner of `mesh` in V order, as [`crate::mesh::Attributes::uv`] holds
    /// them): interpolated linearly over each control face, as OpenSubdiv's
    /// face-varying `FVAR_LINEAR_ALL` and Blender's "UV Smooth: None" do, so
    /// that the seams stay where the file has them and a shared edge gets
    /// the same values from both sides where the file's agree. A
    /// Catmull-Clark ptex face of an n-gon's corner reads the first level's
    /// linear values (the edges' midpoints, the face's average).
    ///
    /// # Errors
    /// [`Error::Usage`] when `uv` has not one value per corner of `mesh`.
    pub fn uvs(&self, mesh: &Mesh, uv: &[glam::Vec2]) -> Result<Vec<glam::Vec2>> {
        if uv.len() != mesh.ct.num_corners() {
            let corners = mesh.ct.num_corners();
            return Err(Error::Usage(format!("{} texture coordinates for the {corners} corners", uv.len())));
        }
        let lerp = |(s, t): (f64, f64), q: &[glam::Vec2; 4]| {
            let (s, t) = (s as f32, t as f32);
            q[0] * ((1.0 - s) * (1.0 - t)) + q[1] * (s * (1.0 - t)) + q[2] * (s * t) + q[3] * ((1.0 - s) * t)
        };
        let faces = self.faces.iter().zip(&self.corners);
        if self.scheme != Scheme::CatmullClark {
            let bary = |f: u32, (s, t): (f64, f64)| {
                let c = |k: u32| uv[(3 * f + k) as usize];
                c(0) * (1.0 - s - t) as f32 + c(1) * s as f32 + c(2) * t as f32
            };
            return Ok(faces.flat_map(|(&f, corners)| corners.map(|st| bary(f, st))).collect());
        }
        let attrs = crate::mesh::Attributes { uv: Some(uv.to_vec()), ..Default::default() };
        let (pm, attrs) = PolyMesh::from_mesh_with_attributes(mesh, &attrs);
        let puv = attrs.uv.unwrap_or_default();
        let ptex = crate::subdiv::eval::catmark::ptex_faces(&pm.pt);
        let quad = |p: u32| {
            let (f, corner) = ptex[p as usize];
            let cs = pm.pt.face_corners(f);
            let at = |k: u32| puv[(cs.start + k) as usize];
            if corner == crate::subdiv::eval::catmark::QUAD {
                return [at(0), at(1), at(2), at(3)];
            }
            let (n, k) = (cs.end - cs.start, corner);
            let centre = (0..n).map(at).sum::<glam::Vec2>() / n as f32;
            [at(k), 0.5 * (at(k) + at((k + 1) % n)), centre, 0.5 * (at((k + n - 1) % n) + at(k))]
        };
        Ok(faces
            .flat_map(|(&p, corners)| {
                let q = quad(p);
                corners.map(|st| lerp(st, &q))
            })
            .collect())
    }
}

/// What [`tessellate`] found.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TessellationStats {
    /// The tolerance asked for (absolute); with a [`Tolerance::Screen`],
    /// the smallest of the patches' (the one nearest the eye).
    pub tolerance: f64,
    /// The largest distance measured between a triangle and the limit
    /// surface (at its centre and its edges' midpoints, from the same
    /// `(u, v)`): at most `tolerance` unless `met` is false (with a
    /// [`Tolerance::Screen`], each patch's within its own).
    pub measured: f64,
    /// The largest measured distance of a patch over its own tolerance: at
    /// most 1 when `met` (on screen, times the pixels asked for: the
    /// largest distance on screen).
    pub worst: f64,
    /// Whether every measured distance is within its tolerance.
    pub met: bool,
    /// Rounds of measuring and refining.
    pub rounds: u32,
    /// Limit points evaluated, vertices and measurements together.
    pub evaluations: u64,
    /// The largest interior rate of a patch.
    pub max_rate: u32,
    /// Seconds spent.
    pub seconds: f64,
}

/// Rounds of measuring before the result is given as it is (`met` false).
const MAX_ROUNDS: u32 = 16;

/// The limit surface of `mesh` (control points `control`, f64, one per
/// vertex) under `scheme` (Loop or Catmull-Clark) and `opts`, tessellated
/// so that every triangle is within `tolerance` of it (a distance in the
/// model's units, or pixels on the screen of a view), within the memory
/// budget (`opts.max_memory`, else 80 % of the available memory). A
/// [`Tessellator`] does the same and keeps what it made for the next call
/// (after an edit, only what the edit reaches is made again).
///
/// # Errors
/// [`Error::Usage`] for a scheme without an exact evaluation, a tolerance
/// that is not a positive finite number (or a view without pixels or an
/// inverse), a face the evaluator refuses (naming it), or a tessellation
/// that would need more memory than the budget.
pub fn tessellate(
    mesh: &Mesh,
    control: &[DVec3],
    scheme: Scheme,
    opts: &Options,
    tolerance: Tolerance,
) -> Result<Tessellation> {
    Ok(rounds_from(mesh, control, (scheme, opts), tolerance, |_, _| None)?.0)
}

/// The tessellation, from what `warm` gives for the evaluator and the
/// resolved tolerance (`None`: from nothing); with the rounds' state, the
/// points' layout and the resolved tolerance.
fn rounds_from(
    mesh: &Mesh,
    control: &[DVec3],
    (scheme, opts): (Scheme, &Options),
    tolerance: Tolerance,
    warm: impl FnOnce(&Evaluator, &Tolerance) -> Option<Result<Start>>,
) -> Result<(Tessellation, Rounds, Layout, Tolerance)> {
    let start = Instant::now();
    let tolerance = tolerance.resolve(control)?;
    let ev = Evaluator::new_f64(mesh, control, scheme, opts)?;
    let first = match warm(&ev, &tolerance) {
        Some(first) => first?,
        None => Start::cold(&ev, mesh, scheme, &tolerance)?,
    };
    let (out, rounds, layout) = run(&ev, first, (opts, &tolerance), start)?.tessellation(scheme, opts);
    Ok((out, rounds, layout, tolerance))
}

/// What the rounds start from: the domain, each patch's tolerance, rate and
/// largest measured distance (where it is not `dirty`), and the points of
/// an earlier tessellation that still hold.
struct Start {
    domain: Domain,
    tol: Vec<f64>,
    rate: Vec<u32>,
    errors: Vec<f64>,
    before: Option<Earlier>,
    /// Limit points evaluated to get here.
    evaluations: u64,
}

impl Start {
    /// From nothing: the domain of `mesh` under `scheme`, every patch's
    /// tolerance and first rate.
    fn cold(ev: &Evaluator, mesh: &Mesh, scheme: Scheme, tolerance: &Tolerance) -> Result<Start> {
        let domain = match scheme {
            Scheme::CatmullClark => domain::ptex(&PolyMesh::from_mesh(mesh)),
            _ => domain::triangles(mesh),
        };
        if let Some(p) = domain.patches.iter().find(|p| !ev.accepts(p.face as usize)) {
            let what = if p.quad { "ptex face" } else { "face" };
            let why = "it touches an interior vertex of valence 2, which has no limit surface";
            return Err(Error::Usage(format!("cannot tessellate {what} {}: {why}", p.face)));
        }
        let all: Vec<usize> = (0..domain.patches.len()).collect();
        let (tol, evaluated) = view::per_patch(ev, &domain, tolerance, &all)?;
        let (rate, sampled) = rates::initial(ev, &domain, &tol, &all)?;
        let errors = vec![0.0; all.len()];
        Ok(Start { domain, tol, rate, errors, before: None, evaluations: evaluated + sampled })
    }
}

/// What the rounds made, and what a [`Tessellator`] keeps of it.
struct Done {
    built: Built,
    faces: Vec<u32>,
    stats: TessellationStats,
    rounds: Rounds,
}

/// The state of the last round (with its points' [`Layout`]): what the next
/// tessellation of the same cage can start from.
struct Rounds {
    domain: Domain,
    tol: Vec<f64>,
    rate: Vec<u32>,
    errors: Vec<f64>,
}

impl Done {
    /// The tessellation for the caller, the rounds' state and the points'
    /// layout.
    fn tessellation(self, scheme: Scheme, opts: &Options) -> (Tessellation, Rounds, Layout) {
        let Done { built, faces, stats, rounds } = self;
        let triangles = built.triangles.iter().map(|(_, t)| t.map(|p| p.id)).collect();
        let corners = built.triangles.iter().map(|(_, t)| t.map(|p| p.uv)).collect();
        let t = Tessellation {
            positions: built.positions,
            normals: built.normals,
            triangles,
            faces,
            params: built.params,
            stats,
            scheme,
            opts: *opts,
            corners,
        };
        (t, rounds, built.layout)
    }
}

/// The rounds: measures the tessellation at the current rates, makes finer
/// the patches over their tolerance, until none is (or [`MAX_ROUNDS`]
/// rounds), from `first`; `start` is when the call began.
fn run(ev: &Evaluator, first: Start, (opts, tolerance): (&Options, &Tolerance), start: Instant) -> Result<Done> {
    let Start { domain, tol, mut rate, mut errors, mut before, mut evaluations } = first;
    let smallest = tol.iter().copied().fold(f64::INFINITY, f64::min);
    let scale = match tolerance {
        Tolerance::Screen(s) => s.pixels,
        Tolerance::Distance(_) | Tolerance::Fraction(_) => 1.0,
    };
    let mut stats = TessellationStats { tolerance: smallest, ..TessellationStats::default() };
    // a patch is measured again only where its rate or a side's changed
    // (and its points are evaluated again only there)
    loop {
        stats.rounds += 1;
        rates::check_budget(&domain, &rate, opts.max_memory, smallest)?;
        let edge_rate = rates::edge_rates(&domain, &rate);
        let last = before.as_ref().map(|b| (&b.layout.rate[..], &b.layout.edge_rate[..]));
        let dirty = rates::changed(&domain, (&rate, &edge_rate), last);
        let (built, evaluated) = build(ev, &domain, (&rate, &edge_rate), before.as_ref())?;
        evaluations += evaluated + rates::measure(ev, (&domain, &tol), &built, &dirty, &mut errors)?;
        stats.measured = errors.iter().copied().fold(0.0, f64::max);
        stats.worst = errors.iter().zip(&tol).map(|(e, t)| e / t).fold(0.0, f64::max) * scale;
        let over = errors.iter().zip(&tol).filter(|(e, t)| e > t).count();
        stats.met = over == 0;
        log::debug!(
            "round {}: {} triangles, largest distance {:e}, {over} patches over their tolerance",
            stats.rounds,
            built.triangles.len(),
            stats.measured
        );
        if stats.met || stats.rounds == MAX_ROUNDS {
            stats.evaluations = evaluations;
            stats.max_rate = rate.iter().copied().max().unwrap_or(0);
            stats.seconds = start.elapsed().as_secs_f64();
            let faces = built.triangles.iter().map(|(p, _)| domain.patches[*p as usize].face).collect();
            return Ok(Done { built, faces, stats, rounds: Rounds { domain, tol, rate, errors } });
        }
        // the round's triangles go; its points and their layout stay for the next
        before = Some(Earlier::of(built));
        rates::refine(&mut rate, &errors, &tol);
    }
}

/// One tessellation at given rates: the points, evaluated, and the
/// triangles with their corners' `(u, v)` on their patch.
struct Built {
    positions: Vec<DVec3>,
    normals: Vec<DVec3>,
    params: Vec<(u32, f64, f64)>,
    /// Each triangle's patch and corners.
    triangles: Vec<(u32, [Pt; 3])>,
    /// Where the points of each part lie in `positions`, and the rates
    /// they were made at.
    layout: Layout,
}

/// What a round keeps of the round before: its points and their layout
/// (and which of its keys no longer hold, after an edit).
struct Earlier {
    layout: Layout,
    positions: Vec<DVec3>,
    normals: Vec<DVec3>,
    stale_keys: Vec<bool>,
}

impl Earlier {
    /// The points of `built`, all of them holding.
    fn of(built: Built) -> Earlier {
        Earlier { layout: built.layout, positions: built.positions, normals: built.normals, stale_keys: Vec::new() }
    }

    /// Forgets the points that lie on the patches `stale` only (their
    /// corners, sides and insides, where no other patch holds them): the
    /// limit there may have moved. A point a patch not `stale` holds stays
    /// (the surface is one across a side, so it did not move). The
    /// forgotten parts' rates are set to 0, which no rate equals, so that
    /// they are evaluated and measured again.
    fn forget(&mut self, domain: &Domain, stale: &[bool]) {
        let layout = &mut self.layout;
        let (mut held_key, mut held_edge) = (vec![false; layout.keys], vec![false; domain.edges.len()]);
        for (p, patch) in domain.patches.iter().enumerate() {
            if stale[p] {
                layout.rate[p] = 0;
                continue;
            }
            for k in 0..patch.sides() {
                let side = patch.sides[k];
                held_key[layout.key_id[patch.corners[k] as usize] as usize] = true;
                if side.count == 2 {
                    held_key[layout.key_id[junction(domain, patch, k) as usize] as usize] = true;
                }
                for &(e, _) in &side.parts[..side.count as usize] {
                    held_edge[e as usize] = true;
                }
            }
        }
        for (rate, _) in layout.edge_rate.iter_mut().zip(&held_edge).filter(|(_, held)| !**held) {
            *rate = 0;
        }
        self.stale_keys = held_key.into_iter().map(|held| !held).collect();
    }
}

/// The order of a tessellation's points: first the keys (the domain's
/// corners and junctions, in the same order at any rates), then each
/// edge's inside points, then each patch's.
struct Layout {
    keys: usize,
    /// The point of each key of the domain.
    key_id: Vec<u32>,
    edge_first: Vec<u32>,
    inside_first: Vec<u32>,
    rate: Vec<u32>,
    edge_rate: Vec<u32>,
    uniform: Vec<bool>,
}

impl Layout {
    /// The points of edge `e` and of patch `p`'s inside, as ranges of
    /// `positions` (`total` of them in all).
    fn edge(&self, e: usize) -> std::ops::Range<usize> {
        let first = self.edge_first[e] as usize;
        first..first + self.edge_rate[e].saturating_sub(1) as usize
    }

    fn inside(&self, p: usize, total: usize) -> std::ops::Range<usize> {
        let end = self.inside_first.get(p + 1).map_or(total, |&i| i as usize);
        self.inside_first[p] as usize..end
    }

    /// Copies into `points` (positions and normals, laid out as `self`)
    /// the points of `before` that are the same here (their part made at
    /// the same rates), and clears their `fresh` flags.
    fn copy_same(&self, before: &Earlier, points: (&mut [DVec3], &mut [DVec3]), fresh: &mut [bool]) {
        let (positions, normals) = points;
        let (total, before_total) = (positions.len(), before.positions.len());
        let mut copy = |to: std::ops::Range<usize>, from: std::ops::Range<usize>| {
            for (t, f) in to.zip(from) {
                positions[t] = before.positions[f];
                normals[t] = before.normals[f];
                fresh[t] = false;
            }
        };
        let was = &before.layout;
        match before.stale_keys.is_empty() {
            true => copy(0..self.keys, 0..was.keys),
            false => (0..self.keys).filter(|&k| !before.stale_keys[k]).for_each(|k| copy(k..k + 1, k..k + 1)),
        }
        for e in 0..self.edge_rate.len() {
            if self.edge_rate[e] == was.edge_rate[e] {
                copy(self.edge(e), was.edge(e));
            }
        }
        for p in 0..self.rate.len() {
            if self.rate[p] == was.rate[p] && self.uniform[p] == was.uniform[p] {
                copy(self.inside(p, total), was.inside(p, before_total));
            }
        }
    }
}

/// The points and triangles of `domain` at the patches' rates `rate` and
/// the edges' `edge_rate`, and how many points were evaluated: those of
/// the parts whose rates changed since `before`, the rest copied from it.
fn build(
    ev: &Evaluator,
    domain: &Domain,
    (rate, edge_rate): (&[u32], &[u32]),
    before: Option<&Earlier>,
) -> Result<(Built, u64)> {
    let mut points = Points { params: Vec::new(), key_id: vec![u32::MAX; domain.num_keys] };
    let uniform: Vec<bool> =
        (0..domain.patches.len()).map(|p| rates::is_uniform(&domain.patches[p], rate[p], edge_rate)).collect();
    // the corners (and the midpoints where a side is two halves)
    for p in &domain.patches {
        for k in 0..p.sides() {
            points.key(p.corners[k], p.face, p.corner_uv(k));
            if p.sides[k].count == 2 {
                points.key(junction(domain, p, k), p.face, p.side_uv(k, 0.5));
            }
        }
    }
    let keys = points.params.len();
    // the points inside the domain's edges, each evaluated on its owner
    let mut edge_first = Vec::with_capacity(domain.edges.len());
    for (e, edge) in domain.edges.iter().enumerate() {
        edge_first.push(points.params.len() as u32);
        let (owner, s, part) = edge.owner;
        let patch = &domain.patches[owner as usize];
        let side = patch.sides[s as usize];
        for i in 1..edge_rate[e] {
            let t = side_fraction(side, part as usize, f64::from(i) / f64::from(edge_rate[e]));
            let (u, v) = patch.side_uv(s as usize, t);
            points.params.push((patch.face, u, v));
        }
    }
    // the inside of each patch
    let mut inside_first = Vec::with_capacity(domain.patches.len());
    for (p, patch) in domain.patches.iter().enumerate() {
        inside_first.push(points.params.len() as u32);
        for (u, v) in grid::interior(patch.quad, rate[p], uniform[p]) {
            points.params.push((patch.face, u, v));
        }
    }
    if points.params.len() > u32::MAX as usize {
        return Err(Error::Usage("the tessellation has more than 2^32 vertices: raise the tolerance".into()));
    }
    let (rate, edge_rate) = (rate.to_vec(), edge_rate.to_vec());
    let layout = Layout { keys, key_id: points.key_id, edge_first, inside_first, rate, edge_rate, uniform };
    let (positions, normals, evaluated) = evaluate(ev, &points.params, &layout, before)?;
    let sides = Sides { domain, edge_rate: &layout.edge_rate, edge_first: &layout.edge_first, key_id: &layout.key_id };
    let triangles = (0..domain.patches.len())
        .into_par_iter()
        .with_min_len(64)
        .flat_map_iter(|p| {
            let patch = &domain.patches[p];
            let lists: Vec<Vec<Pt>> = (0..patch.sides()).map(|s| sides.points(patch, s)).collect();
            let mut out = Vec::new();
            grid::triangulate(
                patch.quad,
                (layout.rate[p], layout.uniform[p]),
                &lists,
                layout.inside_first[p],
                &mut out,
            );
            out.into_iter().map(move |t| (p as u32, t))
        })
        .collect();
    Ok((Built { positions, normals, params: points.params, triangles, layout }, evaluated))
}

/// The limit points and normals at `params` (laid out as `layout` says),
/// those that `before` holds copied from it; how many were evaluated.
fn evaluate(
    ev: &Evaluator,
    params: &[(u32, f64, f64)],
    layout: &Layout,
    before: Option<&Earlier>,
) -> Result<(Vec<DVec3>, Vec<DVec3>, u64)> {
    let (mut positions, mut fresh) = (vec![DVec3::NAN; params.len()], vec![true; params.len()]);
    let mut normals = vec![DVec3::NAN; params.len()];
    if let Some(b) = &before {
        layout.copy_same(b, (&mut positions, &mut normals), &mut fresh);
    }
    let todo: Vec<usize> = (0..params.len()).filter(|&i| fresh[i]).collect();
    let at: Vec<(usize, f64, f64)> = todo.iter().map(|&i| (params[i].0 as usize, params[i].1, params[i].2)).collect();
    for (&i, (p, n)) in todo.iter().zip(ev.eval_map(&at, false, |s| (s.position, s.normal))?) {
        positions[i] = p;
        normals[i] = n;
    }
    Ok((positions, normals, todo.len() as u64))
}

/// The points made so far, and the vertex of each key.
struct Points {
    params: Vec<(u32, f64, f64)>,
    key_id: Vec<u32>,
}

impl Points {
    /// The vertex of `key`, made at `(u, v)` of `face` the first time.
    fn key(&mut self, key: u32, face: u32, (u, v): (f64, f64)) {
        if self.key_id[key as usize] == u32::MAX {
            self.key_id[key as usize] = self.params.len() as u32;
            self.params.push((face, u, v));
        }
    }
}

/// The key between the two halves of side `s` of `patch`.
fn junction(domain: &Domain, patch: &domain::Patch, s: usize) -> u32 {
    let (e, reversed) = patch.sides[s].parts[0];
    domain.edges[e as usize].ends[usize::from(!reversed)]
}

/// Where fraction `f` of part `part` (from its `ends[0]`) lies along its
/// side.
fn side_fraction(side: domain::Side, part: usize, f: f64) -> f64 {
    let f = if side.parts[part].1 { 1.0 - f } else { f };
    (part as f64 + f) / f64::from(side.count)
}

/// What a patch's sides are made of.
struct Sides<'a> {
    domain: &'a Domain,
    edge_rate: &'a [u32],
    edge_first: &'a [u32],
    key_id: &'a [u32],
}

impl Sides<'_> {
    /// Side `s` of `patch`: its points from corner `s` to corner `s + 1`.
    fn points(&self, patch: &domain::Patch, s: usize) -> Vec<Pt> {
        let side = patch.sides[s];
        let corner =
            |k: usize| Pt { id: self.key_id[patch.corners[k % patch.sides()] as usize], uv: patch.corner_uv(k) };
        let mut out = vec![corner(s)];
        for part in 0..side.count as usize {
            if part == 1 {
                let id = self.key_id[junction(self.domain, patch, s) as usize];
                out.push(Pt { id, uv: patch.side_uv(s, 0.5) });
            }
            let e = side.parts[part].0 as usize;
            let r = self.edge_rate[e];
            let from_end = side.parts[part].1;
            for k in 1..r {
                let i = if from_end { r - k } else { k };
                let t = side_fraction(side, part, f64::from(i) / f64::from(r));
                out.push(Pt { id: self.edge_first[e] + i - 1, uv: patch.side_uv(s, t) });
            }
        }
        out.push(corner(s + 1));
        out
    }
}

#[cfg(test)]
mod tests;
