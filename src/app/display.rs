//! Display options: how the document is drawn, never what it contains.
//!
//! Most options only change the look of the 3D viewports (`Display::look`);
//! three of them change the shown result itself (its positions, normals or
//! colours, `Display::reshades_result`), and applying those recomputes it
//! from the subdivision output.

use crate::render::{Look, Stripes, Surface, WireEdges};
use crate::subdiv::eval::color::{CurvatureKind, HalfWidth};

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

/// Per-vertex colouring of the result.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Coloring {
    /// The material colour.
    #[default]
    None,
    /// The level that created each vertex ("shells").
    Shells,
    /// Distance from the control mesh's surface.
    Displacement,
    /// The colours of the file (`v x y z r g b`), refined with the scheme's weights.
    File,
    /// A checker texture through the file's texture coordinates (`vt`).
    Checker,
    /// The OBJ's MTL materials per group: `Kd` times `map_Kd` through the
    /// refined texture coordinates (see `crate::render::materials`).
    Material,
    /// A curvature of the exact limit surface (Loop's or Catmull-Clark's)
    /// at each drawn vertex, on a diverging map (see
    /// `crate::subdiv::eval::color`).
    Curvature(CurvatureKind),
}

impl Coloring {
    /// All modes, in menu order.
    pub const ALL: [Coloring; 10] = [
        Coloring::None,
        Coloring::Shells,
        Coloring::Displacement,
        Coloring::File,
        Coloring::Checker,
        Coloring::Material,
        Coloring::Curvature(CurvatureKind::Mean),
        Coloring::Curvature(CurvatureKind::Gaussian),
        Coloring::Curvature(CurvatureKind::Min),
        Coloring::Curvature(CurvatureKind::Max),
    ];
    /// The colouring a model opens with: the one asked for, or with none
    /// asked (`--color auto`) its MTL materials when it has them, else the
    /// plain front colour. An explicit [`Coloring::None`] stays none.
    pub fn initial(asked: Option<Coloring>, has_materials: bool) -> Coloring {
        asked.unwrap_or(if has_materials { Coloring::Material } else { Coloring::None })
    }
    /// Menu label.
    pub fn name(self) -> &'static str {
        match self {
            Coloring::None => "none",
            Coloring::Shells => "level shells",
            Coloring::Displacement => "displacement from control",
            Coloring::File => "colours of the file",
            Coloring::Checker => "texture (checker through vt)",
            Coloring::Material => "materials (MTL Kd and map_Kd)",
            Coloring::Curvature(CurvatureKind::Mean) => "mean curvature (exact)",
            Coloring::Curvature(CurvatureKind::Gaussian) => "Gaussian curvature (exact)",
            Coloring::Curvature(CurvatureKind::Min) => "minimum curvature (exact)",
            Coloring::Curvature(CurvatureKind::Max) => "maximum curvature (exact)",
        }
    }
}

impl std::str::FromStr for Coloring {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<Self, String> {
        match s {
            "" | "none" => Ok(Coloring::None),
            "shells" | "levels" => Ok(Coloring::Shells),
            "displacement" => Ok(Coloring::Displacement),
            "file" | "colors" | "colours" => Ok(Coloring::File),
            "checker" | "uv" | "texture" => Ok(Coloring::Checker),
            "material" | "materials" | "mtl" => Ok(Coloring::Material),
            "mean-curvature" | "mean" => Ok(Coloring::Curvature(CurvatureKind::Mean)),
            "gaussian-curvature" | "gaussian" => Ok(Coloring::Curvature(CurvatureKind::Gaussian)),
            "min-curvature" => Ok(Coloring::Curvature(CurvatureKind::Min)),
            "max-curvature" => Ok(Coloring::Curvature(CurvatureKind::Max)),
            _ => Err(format!(
                "unknown colouring '{s}' (none, shells, displacement, file, checker, material, mean-curvature, gaussian-curvature, min-curvature, max-curvature)"
            )),
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

#[cfg(test)]
mod tests {
    use super::Coloring;

    #[test]
    fn none_asked_stays_none_and_auto_follows_the_materials() {
        assert_eq!(Coloring::initial(Some(Coloring::None), true), Coloring::None, "--color none on a model with MTL");
        assert_eq!(Coloring::initial(None, true), Coloring::Material);
        assert_eq!(Coloring::initial(None, false), Coloring::None);
        assert_eq!(Coloring::initial(Some(Coloring::Shells), true), Coloring::Shells);
    }
}
