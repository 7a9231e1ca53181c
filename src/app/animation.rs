//! Animation state: the split-and-tweak paths of the control vertices, the
//! plan built from them (on a worker) and the playback clock.
//!
//! The mode can be on while its plan is still building ([`Animation::active`]
//! with no [`Animation::playback`]). A rebuilt plan keeps the clock's
//! settings and its place, scaled to the new frame count.

use crate::anim::paths::Paths;
use crate::anim::player::{self, Clock};
use crate::anim::tweak::Tweak;

/// Where [`Animation::paths`] came from when they are generated.
pub(crate) const GENERATED: &str = "generated (small loops around each vertex)";

/// A built plan and its clock.
pub(crate) struct Playback {
    /// Evaluator (stencil plan and refined paths).
    pub(crate) player: player::Animation,
    /// Frame clock.
    pub(crate) clock: Clock,
    /// Identifies this plan (a new one for every build), so the window knows
    /// when its animated mesh must be rebuilt rather than updated.
    pub(crate) id: u64,
}

/// The animation mode.
pub(crate) struct Animation {
    /// Animation paths for the control mesh (file or generated).
    pub(crate) paths: Paths,
    /// Where the paths came from.
    pub(crate) paths_source: String,
    /// Path refinement count n (K * 2^n frames).
    pub(crate) refine: u32,
    /// Path tweak.
    pub(crate) tweak: Tweak,
    /// Whether the animation mode is on (the plan may still be building).
    pub(crate) active: bool,
    /// The plan when built.
    pub(crate) playback: Option<Playback>,
    /// Evaluate the frames with the GPU's compute passes when it has them
    /// (`render::gpu_anim`), else on the CPU.
    pub(crate) gpu_eval: bool,
    /// Whether the window's adapter can (reported by the GPU mirror; `None`
    /// before its first frame, and without a window).
    pub(crate) gpu_compute: Option<bool>,
    /// The plan whose compute passes the GPU mirror has built (reported by
    /// it): frames of that plan may be evaluated there.
    pub(crate) gpu_ready: Option<u64>,
    /// Whether the frame shown was evaluated on the GPU (reported by the
    /// GPU mirror each frame it evaluates one).
    pub(crate) on_gpu: bool,
    /// The frame made current by [`Animation::advance`].
    pub(crate) shown: Option<ShownFrame>,
    builds: u64,
}

/// The current frame of the animation: which plan, which frame, and
/// whether the CPU evaluated it (its positions and normals are then the
/// player's last evaluation) or the GPU is to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct ShownFrame {
    /// The plan ([`Playback::id`]).
    pub(crate) id: u64,
    /// The frame.
    pub(crate) frame: usize,
    /// Evaluated on the CPU.
    pub(crate) on_cpu: bool,
}

impl Animation {
    /// Off, with these paths.
    pub(crate) fn new(paths: Paths, paths_source: String) -> Animation {
        Animation {
            paths,
            paths_source,
            refine: 5,
            tweak: Tweak::Jarek,
            active: false,
            playback: None,
            gpu_eval: true,
            gpu_compute: None,
            gpu_ready: None,
            on_gpu: false,
            shown: None,
            builds: 0,
        }
    }

    /// Whether the clock runs.
    pub(crate) fn playing(&self) -> bool {
        self.playback.as_ref().is_some_and(|p| p.clock.playing)
    }

    /// Takes a freshly built plan: the first one starts playing, a rebuilt
    /// one keeps the clock's settings and its place.
    pub(crate) fn adopt(&mut self, player: player::Animation) {
        let mut clock = Clock::new(player.frame_count());
        if let Some(old) = &self.playback {
            clock.playing = old.clock.playing;
            clock.fps = old.clock.fps;
            clock.looping = old.clock.looping;
            clock.set_frame(old.clock.frame() * player.frame_count() / old.clock.frames().max(1));
        } else {
            clock.playing = true;
        }
        self.builds += 1;
        self.playback = Some(Playback { player, clock, id: self.builds });
    }

    /// Advances the clock by `dt` seconds and makes its frame current:
    /// evaluated here, on the CPU, unless the GPU evaluates it (see
    /// [`Animation::gpu_next`]). `normals`: the normal segments are shown
    /// (they are kept current by the CPU's evaluation). Whether the frame
    /// changed.
    pub(crate) fn advance(&mut self, dt: f64, normals: bool) -> bool {
        let on_gpu = self.gpu_next(normals);
        let Some(p) = &mut self.playback else {
            self.shown = None;
            return false;
        };
        let frame = p.clock.tick(dt);
        if self.shown.is_some_and(|s| s.id == p.id && s.frame == frame) {
            return false;
        }
        if !on_gpu {
            p.player.evaluate(frame);
        }
        self.shown = Some(ShownFrame { id: p.id, frame, on_cpu: !on_gpu });
        true
    }

    /// Whether the next frame goes to the GPU's compute passes: asked for,
    /// the adapter has them, the mirror has built them for this plan, and
    /// no normal segments are shown.
    pub(crate) fn gpu_next(&self, normals: bool) -> bool {
        let ready = self.playback.as_ref().is_some_and(|p| self.gpu_ready == Some(p.id));
        self.gpu_eval && self.gpu_compute == Some(true) && ready && !normals
    }

    /// Leaves the mode.
    pub(crate) fn stop(&mut self) {
        self.active = false;
        self.playback = None;
    }

    /// Paths generated for a control mesh that has none (or no longer fits them).
    pub(crate) fn generate_paths(&mut self, mesh: &crate::Mesh) {
        self.paths = Paths::generated(mesh, 4);
        self.paths_source = GENERATED.into();
    }
}
