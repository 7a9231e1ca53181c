//! How the drawn result is coloured: the colourings the viewer's panel,
//! `render --color` and `view --color` name, and the one a model opens
//! with.

use crate::subdiv::eval::color::CurvatureKind;

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
