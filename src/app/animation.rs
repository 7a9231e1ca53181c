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
pub const GENERATED: &str = "generated (small loops around each vertex)";

/// A built plan and its clock.
pub struct Playback {
    /// Evaluator (stencil plan and refined paths).
    pub player: player::Animation,
    /// Frame clock.
    pub clock: Clock,
    /// Identifies this plan (a new one for every build), so the window knows
    /// when its animated mesh must be rebuilt rather than updated.
    pub id: u64,
}

/// The animation mode.
pub struct Animation {
    /// Animation paths for the control mesh (file or generated).
    pub paths: Paths,
    /// Where the paths came from.
    pub paths_source: String,
    /// Path refinement count n (K * 2^n frames).
    pub refine: u32,
    /// Path tweak.
    pub tweak: Tweak,
    /// Whether the animation mode is on (the plan may still be building).
    pub active: bool,
    /// The plan when built.
    pub playback: Option<Playback>,
    /// Evaluate the frames with the GPU's compute passes when it has them
    /// (`render::gpu_anim`), else on the CPU.
    pub gpu_eval: bool,
    /// Whether the window's adapter can (set by the window; `None` before
    /// its first frame).
    pub gpu_compute: Option<bool>,
    /// Whether the frame shown was evaluated on the GPU (set by the window
    /// each frame it evaluates one).
    pub on_gpu: bool,
    builds: u64,
}

impl Animation {
    /// Off, with these paths.
    pub fn new(paths: Paths, paths_source: String) -> Animation {
        Animation {
            paths,
            paths_source,
            refine: 5,
            tweak: Tweak::Jarek,
            active: false,
            playback: None,
            gpu_eval: true,
            gpu_compute: None,
            on_gpu: false,
            builds: 0,
        }
    }

    /// Whether the clock runs.
    pub fn playing(&self) -> bool {
        self.playback.as_ref().is_some_and(|p| p.clock.playing)
    }

    /// Takes a freshly built plan: the first one starts playing, a rebuilt
    /// one keeps the clock's settings and its place.
    pub fn adopt(&mut self, player: player::Animation) {
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

    /// Leaves the mode.
    pub fn stop(&mut self) {
        self.active = false;
        self.playback = None;
    }

    /// Paths generated for a control mesh that has none (or no longer fits them).
    pub fn generate_paths(&mut self, mesh: &crate::Mesh) {
        self.paths = Paths::generated(mesh, 4);
        self.paths_source = GENERATED.into();
    }
}
