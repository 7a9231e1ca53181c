//! Playback: refined key paths, the per-frame re-evaluation through a stencil
//! plan, and a frame clock.
//!
//! Per frame only two things happen: the stencil plan is applied to the
//! frame's control positions (topology, O and weights are reused), and the
//! vertex normals are recomputed into reused buffers. Nothing is allocated
//! after the first frame. The plan is recorded in a locality order of the
//! control mesh ([`StencilPlan::build_local`]): the subdivided mesh is
//! numbered in that order, so that the neighbours each point gathers lie
//! near it in memory.

use super::paths::Paths;
use super::tweak::{Tweak, refine_closed};
use crate::clock::Instant;
use crate::mesh::normals::{VertexFaces, VertexRings, face_normals_into};
use crate::subdiv::tables::{PlanScratch, StencilPlan};
use crate::{CornerTable, Error, Mesh, Options, Result, Scheme};
use glam::Vec3;
use rayon::prelude::*;
use std::time::Duration;

/// Most refined path samples held in memory (frames x control vertices).
const MAX_SAMPLES: usize = 64 << 20;

/// A ready-to-play animation of one model.
pub struct Animation {
    plan: StencilPlan,
    frames: usize,
    nv: usize,
    /// Frame-major refined paths: `curves[f * nv + v]`.
    curves: Vec<Vec3>,
    scratch: PlanScratch,
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    normals_by: NormalsBy,
    /// Time of the last [`Animation::evaluate`]: (stencils, normals).
    pub last_timing: (Duration, Duration),
    /// Time [`Animation::new`] took to record the plan and its normal rings.
    pub plan_time: Duration,
    /// The last [`RECENT`] evaluation times (stencils plus normals), a ring.
    recent: Box<[Duration]>,
    evaluations: usize,
}

/// Evaluation times kept for [`Animation::frame_ms`].
const RECENT: usize = 64;

/// How the per-frame normals are gathered.
enum NormalsBy {
    /// Straight from the positions through packed one-rings (the usual case).
    Rings(VertexRings),
    /// Face normals gathered per vertex (a vertex whose polygon has more
    /// than 255 entries): a face-normal buffer and the faces around every
    /// vertex.
    Faces(Vec<Vec3>, VertexFaces),
}

impl Animation {
    /// Refines every key polygon `refine` times with `tweak` (K keys give
    /// `K * 2^refine` frames) and records the stencil plan of `level` levels of
    /// `scheme` on the model's topology.
    ///
    /// # Errors
    /// Paths that do not match the model, too many frames to hold, or a level
    /// that does not fit in memory.
    pub fn new(
        control: &Mesh,
        paths: &Paths,
        tweak: Tweak,
        refine: u32,
        scheme: Scheme,
        level: u32,
        opts: &Options,
    ) -> Result<Self> {
        paths.check_model(control, "paths")?;
        let nv = control.positions.len();
        let frames = paths.keys_per_vertex.checked_shl(refine).filter(|&f| f > 0 && refine < 24).unwrap_or(usize::MAX);
        if frames.saturating_mul(nv) > MAX_SAMPLES {
            return Err(Error::Usage(format!(
                "{} keys refined {refine} times give {frames} frames for {nv} vertices: too many samples to hold; use a smaller --refine",
                paths.keys_per_vertex
            )));
        }
        let per_vertex: Vec<Vec<Vec3>> =
            (0..nv).into_par_iter().map(|v| refine_closed(paths.polygon(v), tweak, refine)).collect();
        let mut curves = vec![Vec3::ZERO; frames * nv];
        curves.par_chunks_mut(nv).enumerate().for_each(|(f, row)| {
            for (v, slot) in row.iter_mut().enumerate() {
                *slot = per_vertex[v][f];
            }
        });
        let t0 = Instant::now();
        let plan = StencilPlan::build_local(&control.ct, scheme, level, opts)?;
        // a polygon scheme's normals from its quads' rings of edge neighbours
        let rings = match plan.polygons() {
            Some(pt) => VertexRings::new(pt),
            None => VertexRings::new(&plan.ct),
        };
        let normals_by = match rings {
            Some(r) => NormalsBy::Rings(r),
            None => NormalsBy::Faces(Vec::new(), VertexFaces::new(&plan.ct)),
        };
        let plan_time = t0.elapsed();
        // every buffer a frame writes, allocated now
        let fine = plan.ct.num_vertices();
        let scratch = PlanScratch::for_plan(&plan);
        Ok(Animation {
            plan,
            frames,
            nv,
            curves,
            scratch,
            positions: crate::mem::zeroed(fine),
            normals: crate::mem::zeroed(fine),
            normals_by,
            last_timing: Default::default(),
            plan_time,
            recent: vec![Duration::ZERO; RECENT].into_boxed_slice(),
            evaluations: 0,
        })
    }

    /// Number of frames (`K * 2^refine`).
    pub fn frame_count(&self) -> usize {
        self.frames
    }
    /// Control positions of frame `f` (taken modulo the frame count).
    pub fn control(&self, f: usize) -> &[Vec3] {
        let f = f % self.frames;
        &self.curves[f * self.nv..(f + 1) * self.nv]
    }
    /// Topology of the evaluated (finest) mesh. Its faces and vertices are
    /// numbered in the plan's locality order ([`StencilPlan::build_local`],
    /// [`StencilPlan::order`]), not as [`crate::subdivide`] numbers them: the
    /// same surface, evaluated faster.
    pub fn topology(&self) -> &CornerTable {
        &self.plan.ct
    }
    /// The recorded plan.
    pub fn plan(&self) -> &StencilPlan {
        &self.plan
    }

    /// Positions and unit normals of the subdivided mesh at frame `f`.
    pub fn evaluate(&mut self, f: usize) -> (&[Vec3], &[Vec3]) {
        let f = f % self.frames;
        let t0 = Instant::now();
        let control = &self.curves[f * self.nv..(f + 1) * self.nv];
        self.plan.apply(control, &mut self.scratch, &mut self.positions);
        let t1 = Instant::now();
        self.normals.resize(self.positions.len(), Vec3::ZERO);
        match &mut self.normals_by {
            NormalsBy::Rings(r) => r.normals_into(&self.positions, &mut self.normals),
            NormalsBy::Faces(fnorm, faces) => {
                fnorm.resize(self.plan.ct.num_triangles(), Vec3::ZERO);
                face_normals_into(&self.plan.ct, &self.positions, fnorm);
                faces.normals_into(fnorm, &mut self.normals);
            }
        }
        self.last_timing = (t1 - t0, t1.elapsed());
        self.recent[self.evaluations % RECENT] = t0.elapsed();
        self.evaluations += 1;
        (&self.positions, &self.normals)
    }

    /// Positions and unit normals of the last [`Animation::evaluate`]
    /// (empty before the first).
    pub(crate) fn evaluated(&self) -> (&[Vec3], &[Vec3]) {
        (&self.positions, &self.normals)
    }

    /// Milliseconds [`Animation::new`] took to record the plan.
    pub fn plan_ms(&self) -> f64 {
        self.plan_time.as_secs_f64() * 1e3
    }

    /// Median milliseconds of the last (up to 64) evaluations, positions and
    /// normals together; `None` before the first.
    pub fn frame_ms(&self) -> Option<f64> {
        let n = self.evaluations.min(RECENT);
        if n == 0 {
            return None;
        }
        let mut t = [Duration::ZERO; RECENT];
        let t = &mut t[..n];
        t.copy_from_slice(&self.recent[..n]);
        t.sort_unstable();
        Some(t[n / 2].as_secs_f64() * 1e3)
    }

    /// [`Animation::evaluate`] with the topology, borrowed together (for a
    /// first upload).
    pub fn evaluate_with_topology(&mut self, f: usize) -> (&CornerTable, &[Vec3], &[Vec3]) {
        self.evaluate(f);
        (&self.plan.ct, &self.positions, &self.normals)
    }
}

/// A frame clock: play/pause, speed, loop, step.
#[derive(Clone, Debug)]
pub struct Clock {
    /// Advancing with time.
    pub playing: bool,
    /// Frames per second.
    pub fps: f32,
    /// Wrap at the end (otherwise stop on the last frame).
    pub looping: bool,
    pos: f64,
    frames: usize,
}

impl Clock {
    /// A paused looping clock over `frames` frames at 30 fps.
    pub(crate) fn new(frames: usize) -> Self {
        Clock { playing: false, fps: 30.0, looping: true, pos: 0.0, frames: frames.max(1) }
    }
    /// Number of frames.
    pub(crate) fn frames(&self) -> usize {
        self.frames
    }
    /// Current frame.
    pub(crate) fn frame(&self) -> usize {
        (self.pos.floor() as usize).min(self.frames - 1)
    }
    /// Jumps to frame `f` (clamped).
    pub(crate) fn set_frame(&mut self, f: usize) {
        self.pos = f.min(self.frames - 1) as f64;
    }
    /// Steps by `d` frames (wrapping when looping).
    pub(crate) fn step(&mut self, d: i64) {
        let n = self.frames as i64;
        let f = self.frame() as i64 + d;
        self.pos = if self.looping { f.rem_euclid(n) } else { f.clamp(0, n - 1) } as f64;
    }
    /// Advances by `dt` seconds when playing; returns the current frame.
    pub(crate) fn tick(&mut self, dt: f64) -> usize {
        if self.playing {
            self.pos += dt * f64::from(self.fps);
            let n = self.frames as f64;
            if self.pos >= n {
                if self.looping {
                    self.pos %= n;
                } else {
                    self.pos = n - 1.0;
                    self.playing = false;
                }
            }
        }
        self.frame()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clock_loops_steps_and_stops() {
        let mut c = Clock::new(8);
        assert_eq!(c.tick(1.0), 0, "paused");
        c.playing = true;
        c.fps = 4.0;
        assert_eq!(c.tick(0.5), 2);
        assert_eq!(c.tick(2.0), 2, "wraps: 2 + 8 = 10 -> 2");
        c.step(-3);
        assert_eq!(c.frame(), 7);
        c.looping = false;
        c.tick(10.0);
        assert_eq!((c.frame(), c.playing), (7, false));
    }
}
