//! Display options: how the document is drawn, never what it contains.
//!
//! Most options only change the look of the 3D viewports (`Display::look`);
//! three of them change the shown result itself (its positions, normals or
//! colours, `Display::reshades_result`), and applying those recomputes it
//! from the subdivision output.

pub(crate) use crate::render::Coloring;
use crate::render::{Look, Stripes, Surface, WireEdges};
use crate::subdiv::eval::color::HalfWidth;

/// Which normals shade the result.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub(crate) enum NormalMode {
    /// Area-weighted average of the face normals around each vertex.
    #[default]
    FanAverage,
    /// Exact normals of the limit surface (tangent masks): Catmull-Clark's
    /// on its levels, Loop's on the triangle schemes'.
    Limit,
    /// Butterfly tangent masks.
    Butterfly,
}

impl NormalMode {
    /// All modes, in menu order.
    pub(crate) const ALL: [NormalMode; 3] = [NormalMode::FanAverage, NormalMode::Limit, NormalMode::Butterfly];
    /// Menu label.
    pub(crate) fn name(self) -> &'static str {
        match self {
            NormalMode::FanAverage => "fan-averaged",
            NormalMode::Limit => "limit surface",
            NormalMode::Butterfly => "butterfly masks",
        }
    }
}

/// Contour lines over the curvature colours (the panel's checkbox and
/// slider, `--isolines N`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Isolines {
    /// Drawn (with a curvature colouring).
    pub(crate) on: bool,
    /// Levels per side of zero, evenly spaced short of the colour range's
    /// ends (see [`crate::render::Look::isolines`]),
    /// 1..=[`crate::subdiv::eval::color::MAX_ISOLINES`].
    pub(crate) count: u8,
}

impl Default for Isolines {
    fn default() -> Self {
        Isolines { on: false, count: 5 }
    }
}

/// Everything the panel's display and surface controls (and their keys) set.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Display {
    /// Face fill.
    pub(crate) surface: Surface,
    /// Wireframe on.
    pub(crate) wireframe: bool,
    /// Control mesh overlay.
    pub(crate) control: bool,
    /// Vertex normals as segments.
    pub(crate) normals: bool,
    /// Control mesh and result in two viewports.
    pub(crate) side_by_side: bool,
    /// The camera turns around the model.
    pub(crate) turntable: bool,
    /// Multisampling on.
    pub(crate) msaa: bool,
    /// The FXAA pass over a single-sampled frame (edges smoothed cheaply).
    pub(crate) fxaa: bool,
    /// Clicks in the 3D area pick control-mesh edges.
    pub(crate) pick: bool,
    /// Shading normals of the result.
    pub(crate) normal_mode: NormalMode,
    /// Show the limit positions instead of the level's points.
    pub(crate) snap_limit: bool,
    /// Per-vertex colouring of the result.
    pub(crate) coloring: Coloring,
    /// Sharp edges (creases) drawn in their own colour.
    pub(crate) sharp_edges: bool,
    /// With `pick`, a click also toggles the picked edge's crease.
    pub(crate) click_creases: bool,
    /// Which edges the wireframe draws (all, control only, up to a level).
    pub(crate) wire_edges: WireEdges,
    /// The zebra's and the isophotes' stripes.
    pub(crate) stripes: Stripes,
    /// Isolines over the curvature colours.
    pub(crate) isolines: Isolines,
    /// The half-width of the curvature colours' range, set by hand (`None`:
    /// the default percentile, [`crate::subdiv::eval::color::auto_range`]).
    pub(crate) range: Option<HalfWidth>,
    /// Draw the limit surface tessellated for the view (within half a
    /// pixel, see [`super::adaptive`]) instead of the uniform level.
    pub(crate) adaptive: bool,
}

impl Display {
    /// Defaults, with the wireframe on or off.
    pub(crate) fn new(wireframe: bool) -> Display {
        Display {
            surface: Surface::Smooth,
            wireframe,
            control: false,
            normals: false,
            side_by_side: false,
            turntable: false,
            msaa: false,
            fxaa: true,
            pick: false,
            normal_mode: NormalMode::default(),
            snap_limit: false,
            coloring: Coloring::default(),
            sharp_edges: true,
            click_creases: false,
            wire_edges: WireEdges::All,
            stripes: Stripes::default(),
            isolines: Isolines::default(),
            range: None,
            adaptive: false,
        }
    }

    /// The look of the result viewport, without colours (what an export draws).
    pub(crate) fn plain_look(&self) -> Look {
        Look {
            surface: self.surface,
            wireframe: self.wireframe,
            control: self.control,
            normals: self.normals,
            colors: false,
            uv_checker: false,
            materials: false,
            sharp: self.sharp_edges,
            wire_edges: self.wire_edges,
            stripes: self.stripes,
            values: false,
            isolines: 0,
        }
    }

    /// The look of the result viewport in the window, with the colouring
    /// (and the isolines of a curvature colouring, when on).
    pub(crate) fn look(&self) -> Look {
        let values = matches!(self.coloring, Coloring::Curvature(_));
        Look {
            colors: self.coloring != Coloring::None,
            uv_checker: self.coloring == Coloring::Checker,
            materials: self.coloring == Coloring::Material,
            values,
            isolines: if values && self.isolines.on { self.isolines.count } else { 0 },
            ..self.plain_look()
        }
    }

    /// Whether going from `self` to `next` changes the shown result (its
    /// points, normals or colours), not only how it is drawn.
    pub(crate) fn reshades_result(&self, next: &Display) -> bool {
        let range = matches!(next.coloring, Coloring::Curvature(_)) && self.range != next.range;
        range
            || self.adaptive != next.adaptive
            || (self.normal_mode, self.snap_limit, self.coloring) != (next.normal_mode, next.snap_limit, next.coloring)
    }

    /// The next face fill of the S key; hiding the faces turns the wireframe on.
    pub(crate) fn cycle_surface(&mut self) {
        self.surface = match self.surface {
            Surface::Smooth => Surface::Flat,
            Surface::Flat => Surface::Studio,
            Surface::Studio => Surface::Zebra,
            Surface::Zebra | Surface::Isophotes => Surface::Hidden,
            Surface::Hidden => Surface::Smooth,
        };
        if self.surface == Surface::Hidden {
            self.wireframe = true;
        }
    }
}

impl Default for Display {
    fn default() -> Self {
        Display::new(false)
    }
}
