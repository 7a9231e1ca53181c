//! A tessellation kept for the next: when the next call is for the same
//! cage, scheme, options and tolerance with some control points moved,
//! only the patches whose limit surface those points reach are evaluated,
//! measured and made finer again; every other patch keeps its rate and its
//! points.
//!
//! A control point's basis function reaches the faces that share a vertex
//! with a face holding it (two rings of faces, for Loop and Catmull-Clark
//! alike, creases and boundaries included: every rule of a level reads a
//! vertex's faces only). A moved patch starts from the larger of its last
//! rate and its new first guess, so a small move usually needs one round;
//! a patch is never made coarser by an edit (the next call with another
//! tolerance starts afresh).

use super::domain::Domain;
use super::{Earlier, Start, Tessellation, Tolerance, rates, rounds_from, view};
use crate::Result;
use crate::mesh::poly::PolyTable;
use crate::mesh::{CornerTable, Mesh};
use crate::subdiv::eval::Evaluator;
use crate::subdiv::eval::catmark::ptex_faces;
use crate::subdiv::{Options, Scheme};
use glam::DVec3;

/// [`crate::tessellate`] that keeps its last tessellation, so that the next
/// one, after control points moved (an edit, a frame of an animation),
/// evaluates and measures again only the patches their moves reach. The
/// result is a tessellation of the new points within the tolerance, as
/// [`crate::tessellate`]'s is; it may be finer than a fresh one where the
/// surface flattened (an edit never makes a patch coarser). It holds a
/// copy of the last tessellation's points.
#[derive(Default)]
pub struct Tessellator {
    last: Option<Box<Last>>,
}

impl std::fmt::Debug for Tessellator {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let points = self.last.as_ref().map_or(0, |l| l.earlier.positions.len());
        f.debug_struct("Tessellator").field("kept_points", &points).finish()
    }
}

/// What the last call was for and what it made.
struct Last {
    scheme: Scheme,
    opts: Options,
    /// Resolved.
    tolerance: Tolerance,
    ct: CornerTable,
    control: Vec<DVec3>,
    domain: Domain,
    tol: Vec<f64>,
    rate: Vec<u32>,
    errors: Vec<f64>,
    earlier: Earlier,
}

impl Tessellator {
    /// A tessellator holding nothing yet.
    pub fn new() -> Tessellator {
        Tessellator::default()
    }

    /// [`crate::tessellate`]'s tessellation, made from the last one where
    /// the cage (`mesh`'s connectivity and sharpness), scheme, options and
    /// tolerance are the same: only the patches the moved control points
    /// reach are made again. Otherwise, and after an error, from nothing.
    ///
    /// # Errors
    /// As [`crate::tessellate`].
    pub fn tessellate(
        &mut self,
        mesh: &Mesh,
        control: &[DVec3],
        scheme: Scheme,
        opts: &Options,
        tolerance: Tolerance,
    ) -> Result<Tessellation> {
        let last = self.last.take();
        let same = |l: &Last, t: &Tolerance| {
            (l.scheme, l.opts, l.tolerance) == (scheme, *opts, *t)
                && l.control.len() == control.len()
                && l.ct == mesh.ct
        };
        let warm = |ev: &Evaluator, t: &Tolerance| last.filter(|l| same(l, t)).map(|l| (*l).warm(ev, mesh, control, t));
        let (out, rounds, layout, tolerance) = rounds_from(mesh, control, (scheme, opts), tolerance, warm)?;
        let earlier =
            Earlier { layout, positions: out.positions.clone(), normals: out.normals.clone(), stale_keys: Vec::new() };
        self.last = Some(Box::new(Last {
            scheme,
            opts: *opts,
            tolerance,
            ct: mesh.ct.clone(),
            control: control.to_vec(),
            domain: rounds.domain,
            tol: rounds.tol,
            rate: rounds.rate,
            errors: rounds.errors,
            earlier,
        }));
        Ok(out)
    }
}

impl Last {
    /// The rounds' start for the points `control`: the patches the moved
    /// points reach get their tolerance and first rate again and their
    /// points forgotten; the rest stand.
    fn warm(self, ev: &Evaluator, mesh: &Mesh, control: &[DVec3], tolerance: &Tolerance) -> Result<Start> {
        let Last { scheme, control: was, domain, mut tol, mut rate, errors, mut earlier, .. } = self;
        let moved: Vec<bool> = was.iter().zip(control).map(|(a, b)| a != b).collect();
        let stale = reached(mesh, &domain, scheme, &moved);
        let which: Vec<usize> = (0..stale.len()).filter(|&p| stale[p]).collect();
        let (t, evaluated) = view::per_patch(ev, &domain, tolerance, &which)?;
        let (first, sampled) = rates::initial(ev, &domain, &t, &which)?;
        for ((&p, t), n) in which.iter().zip(t).zip(first) {
            tol[p] = t;
            rate[p] = rate[p].max(n);
        }
        earlier.forget(&domain, &stale);
        Ok(Start { domain, tol, rate, errors, before: Some(earlier), evaluations: evaluated + sampled })
    }
}

/// The patches of `domain` whose limit surface the control points `moved`
/// reach: those of the control faces sharing a vertex with a face that
/// holds one.
fn reached(mesh: &Mesh, domain: &Domain, scheme: Scheme, moved: &[bool]) -> Vec<bool> {
    if scheme == Scheme::CatmullClark {
        let pt = PolyTable::from_corner_table(&mesh.ct);
        let corners = (0..pt.num_corners() as u32).map(|c| (pt.face(c), pt.vtx(c)));
        let faces = two_rings(pt.num_faces(), corners, moved);
        let ptex = ptex_faces(&pt);
        return domain.patches.iter().map(|p| faces[ptex[p.face as usize].0 as usize]).collect();
    }
    let ct = &mesh.ct;
    let faces = two_rings(ct.num_triangles(), (0..ct.num_corners() as u32).map(|c| (c / 3, ct.vtx(c))), moved);
    domain.patches.iter().map(|p| faces[p.face as usize]).collect()
}

/// Of `faces` faces with `corners` (each corner's face and vertex), those
/// sharing a vertex with a face that holds a vertex of `moved`.
fn two_rings(faces: usize, corners: impl Iterator<Item = (u32, u32)> + Clone, moved: &[bool]) -> Vec<bool> {
    let vertices = moved.len();
    let spread = |marked: &[bool], size: usize, from_face: bool| {
        let mut out = vec![false; size];
        for (f, v) in corners.clone() {
            let (from, to) = if from_face { (f, v) } else { (v, f) };
            // a vertex past the control points (none in a valid cage) counts as moved
            if marked.get(from as usize).copied().unwrap_or(true)
                && let Some(x) = out.get_mut(to as usize)
            {
                *x = true;
            }
        }
        out
    };
    let holding = spread(moved, faces, false);
    let near = spread(&holding, vertices, true);
    spread(&near, faces, false)
}
