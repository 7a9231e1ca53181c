//! The subdivision options a model file can state (OpenSubdiv's shape tags
//! in OBJ: `t interpolateboundary`, `t facevaryinginterpolateboundary`,
//! `t smoothtriangles`, `t creasemethod`), kept with the mesh's attributes
//! so a file round-trips and a command can let its flags override them.

use super::attributes::UvInterpolation;
use super::sharpness::{BoundaryInterpolation, Creasing};

/// How Catmull-Clark refines the triangles of a mesh (OpenSubdiv's
/// `Sdc::Options::TriangleSubdivision`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum TriangleSubdivision {
    /// Catmull-Clark's own rules (`TRI_SUB_CATMARK`).
    #[default]
    Catmark,
    /// OpenSubdiv's smooth triangle rule (`TRI_SUB_SMOOTH`, from Hbr): an
    /// interior edge of a triangle takes its face points with weight
    /// `w = (w0 + w1) / 2` each, `w_i` 0.47 for a triangle and 1/4 for
    /// another face, and its ends `(1 - 2 w) / 2` each (`catmarkScheme.h`,
    /// `assignSmoothMaskForEdge`).
    Smooth,
}

impl TriangleSubdivision {
    /// Its name (`catmark`, `smooth`), as [`std::str::FromStr`] reads it.
    pub fn name(self) -> &'static str {
        match self {
            TriangleSubdivision::Catmark => "catmark",
            TriangleSubdivision::Smooth => "smooth",
        }
    }
}

impl std::str::FromStr for TriangleSubdivision {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "catmark" | "catmull-clark" => Ok(TriangleSubdivision::Catmark),
            "smooth" => Ok(TriangleSubdivision::Smooth),
            _ => Err(format!("unknown triangle subdivision '{s}' (expected catmark or smooth)")),
        }
    }
}

/// The subdivision scheme a file states (USD's `subdivisionScheme`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum FileScheme {
    /// `catmullClark` (USD's default).
    #[default]
    CatmullClark,
    /// `loop`.
    Loop,
    /// `bilinear`.
    Bilinear,
    /// `none`: the polygons are the surface (no subdivision).
    None,
}

impl FileScheme {
    /// USD's token for it.
    pub fn token(self) -> &'static str {
        match self {
            FileScheme::CatmullClark => "catmullClark",
            FileScheme::Loop => "loop",
            FileScheme::Bilinear => "bilinear",
            FileScheme::None => "none",
        }
    }

    /// The scheme USD's token names.
    pub(crate) fn of_token(t: &str) -> Option<FileScheme> {
        [FileScheme::CatmullClark, FileScheme::Loop, FileScheme::Bilinear, FileScheme::None]
            .into_iter()
            .find(|s| s.token() == t)
    }
}

/// The options a file states, each `None` where it says nothing (the
/// command's flag, or the default, then decides).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct ShapeOptions {
    /// `t interpolateboundary 1/0/0 k`: 0 none, 1 edge-and-corner, 2 edge
    /// (RenderMan's and OpenSubdiv's regression shapes' numbering).
    pub boundary: Option<BoundaryInterpolation>,
    /// `t facevaryinginterpolateboundary 1/0/0 k`: 0 none, 1 corners-only,
    /// 2 corners-plus1, 3 corners-plus2, 4 boundaries, 5 all (the order of
    /// OpenSubdiv's `FVarLinearInterpolation`).
    pub fvar: Option<UvInterpolation>,
    /// `t smoothtriangles 0/0/1 catmark|smooth`.
    pub triangles: Option<TriangleSubdivision>,
    /// `t creasemethod 0/0/1 normal|chaikin`.
    pub creasing: Option<Creasing>,
    /// The subdivision scheme (USD's `subdivisionScheme`; OBJ states none).
    pub scheme: Option<FileScheme>,
}

impl ShapeOptions {
    /// These options with the ones `over` states taking their place
    /// (a command's flags over the file's tags).
    pub fn overridden_by(self, over: ShapeOptions) -> ShapeOptions {
        ShapeOptions {
            boundary: over.boundary.or(self.boundary),
            fvar: over.fvar.or(self.fvar),
            triangles: over.triangles.or(self.triangles),
            creasing: over.creasing.or(self.creasing),
            scheme: over.scheme.or(self.scheme),
        }
    }

    /// Only the options that differ from OpenSubdiv's defaults (what a
    /// writer writes).
    pub(crate) fn not_default(self) -> ShapeOptions {
        fn keep<T: Default + PartialEq>(x: Option<T>) -> Option<T> {
            x.filter(|v| *v != T::default())
        }
        ShapeOptions {
            boundary: keep(self.boundary),
            fvar: keep(self.fvar),
            triangles: keep(self.triangles),
            creasing: keep(self.creasing),
            scheme: self.scheme,
        }
    }

    /// The value of `t interpolateboundary` for `b`.
    pub(crate) fn boundary_code(b: BoundaryInterpolation) -> u32 {
        match b {
            BoundaryInterpolation::None => 0,
            BoundaryInterpolation::EdgeAndCorner => 1,
            BoundaryInterpolation::EdgeOnly => 2,
        }
    }

    /// The boundary interpolation `t interpolateboundary` names by `k`.
    pub(crate) fn boundary_of(k: u32) -> Option<BoundaryInterpolation> {
        [BoundaryInterpolation::None, BoundaryInterpolation::EdgeAndCorner, BoundaryInterpolation::EdgeOnly]
            .get(k as usize)
            .copied()
    }

    /// The value of `t facevaryinginterpolateboundary` for `m`.
    pub(crate) fn fvar_code(m: UvInterpolation) -> u32 {
        UvInterpolation::ALL.iter().position(|&x| x == m).unwrap_or(1) as u32
    }

    /// The face-varying mode `t facevaryinginterpolateboundary` names by `k`.
    pub(crate) fn fvar_of(k: u32) -> Option<UvInterpolation> {
        UvInterpolation::ALL.get(k as usize).copied()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_round_trip_and_follow_opensubdivs_numbering() {
        for k in 0..3 {
            let b = ShapeOptions::boundary_of(k).unwrap();
            assert_eq!(ShapeOptions::boundary_code(b), k);
        }
        assert_eq!(ShapeOptions::boundary_of(1), Some(BoundaryInterpolation::EdgeAndCorner));
        assert_eq!(ShapeOptions::boundary_of(3), None);
        for k in 0..6 {
            assert_eq!(ShapeOptions::fvar_code(ShapeOptions::fvar_of(k).unwrap()), k);
        }
        assert_eq!(ShapeOptions::fvar_of(5), Some(UvInterpolation::Linear));
        assert_eq!(ShapeOptions::fvar_of(6), None);
    }

    #[test]
    fn flags_override_tags_and_writers_skip_defaults() {
        let file = ShapeOptions {
            boundary: Some(BoundaryInterpolation::None),
            creasing: Some(Creasing::Chaikin),
            ..Default::default()
        };
        let flags = ShapeOptions { boundary: Some(BoundaryInterpolation::EdgeOnly), ..Default::default() };
        let both = file.overridden_by(flags);
        assert_eq!(both.boundary, Some(BoundaryInterpolation::EdgeOnly));
        assert_eq!(both.creasing, Some(Creasing::Chaikin));
        let written = both.not_default();
        assert_eq!(written.boundary, None);
        assert_eq!(written.creasing, Some(Creasing::Chaikin));
    }
}
