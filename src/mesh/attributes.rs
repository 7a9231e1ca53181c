//! Attributes of a mesh: per-corner texture coordinates and per-vertex
//! colours, and the linear refinement of UVs through the 1-to-4 split. The
//! colours' refinement by a scheme's weights is in
//! [`crate::subdiv::tables::attributes`].
//!
//! * **Colours** (one per vertex) use the scheme's own weights: they are
//!   refined by the same stencil plan as the positions (so a colour that is
//!   an affine function of position stays that function wherever the scheme
//!   reproduces it), then clamped to [0, 1] since the interpolating schemes'
//!   negative weights can overshoot.
//! * **Texture coordinates** are stored per corner, so a UV seam (one vertex,
//!   different UVs in the triangles around it) stays sharp. Inside each
//!   triangle they are refined **linearly**: the new corner on the edge
//!   opposite corner `c` gets the midpoint `(uv[n(c)] + uv[p(c)]) / 2` of
//!   that triangle's own corners, in the split layout of docs/schemes.md §7.4
//!   (central triangle `t` keeps corner ids; the corner triangle of `v(c)`
//!   starts at `A(c) = 3nt(c%3 + 1) + 3(c/3)`). Charts are therefore
//!   parameterised piecewise linearly over the control mesh, whatever the
//!   scheme does to positions; the texture follows the surface without
//!   swimming at seams.

use super::{n, p};
use glam::{Vec2, Vec3};
use rayon::prelude::*;

/// How the polygon schemes refine texture coordinates (OpenSubdiv's
/// `Sdc::Options::FVarLinearInterpolation`; the triangle schemes always
/// interpolate them linearly in each triangle).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum UvInterpolation {
    /// Bilinear in every face, so every seam and chart stays where it was
    /// (`FVAR_LINEAR_ALL`).
    Linear,
    /// The scheme's own rules on the UV charts, their borders following the
    /// boundary rule and their one-face corners kept (`FVAR_LINEAR_CORNERS_ONLY`,
    /// Blender's "Keep Corners"): textures stay smooth across faces.
    #[default]
    Smooth,
    /// The scheme's rules everywhere, the charts' corners smooth too
    /// (`FVAR_LINEAR_NONE`).
    None,
    /// As [`UvInterpolation::Smooth`], and every value where three or more
    /// charts meet kept too (`FVAR_LINEAR_CORNERS_PLUS1`).
    CornersPlus1,
    /// As [`UvInterpolation::CornersPlus1`], and darts and the other value
    /// of a vertex where a chart has a corner kept too
    /// (`FVAR_LINEAR_CORNERS_PLUS2`).
    CornersPlus2,
    /// Linear along the charts' borders, smooth inside
    /// (`FVAR_LINEAR_BOUNDARIES`).
    Boundaries,
}

impl UvInterpolation {
    /// Every mode, in OpenSubdiv's order (`FVarLinearInterpolation`).
    pub const ALL: [UvInterpolation; 6] = [
        UvInterpolation::None,
        UvInterpolation::Smooth,
        UvInterpolation::CornersPlus1,
        UvInterpolation::CornersPlus2,
        UvInterpolation::Boundaries,
        UvInterpolation::Linear,
    ];

    /// Its command-line name (OpenSubdiv's, in kebab case).
    pub fn name(self) -> &'static str {
        match self {
            UvInterpolation::None => "none",
            UvInterpolation::Smooth => "corners-only",
            UvInterpolation::CornersPlus1 => "corners-plus1",
            UvInterpolation::CornersPlus2 => "corners-plus2",
            UvInterpolation::Boundaries => "boundaries",
            UvInterpolation::Linear => "all",
        }
    }
}

impl std::str::FromStr for UvInterpolation {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "all" | "linear" | "linear-all" => Ok(UvInterpolation::Linear),
            "corners-only" | "smooth" | "corners" | "keep-corners" => Ok(UvInterpolation::Smooth),
            "none" => Ok(UvInterpolation::None),
            "corners-plus1" => Ok(UvInterpolation::CornersPlus1),
            "corners-plus2" => Ok(UvInterpolation::CornersPlus2),
            "boundaries" => Ok(UvInterpolation::Boundaries),
            _ => Err(format!(
                "unknown face-varying interpolation '{s}' (expected none, corners-only, corners-plus1, corners-plus2, boundaries or all; smooth and linear for corners-only and all)"
            )),
        }
    }
}

/// Optional attributes of a mesh.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Attributes {
    /// Texture coordinates, one per corner (three per triangle, in V order).
    pub uv: Option<Vec<Vec2>>,
    /// Linear RGB colours in [0, 1], one per vertex.
    pub colors: Option<Vec<Vec3>>,
    /// Material groups: which material each triangle uses.
    pub materials: Option<MaterialGroups>,
    /// The subdivision options the file states (OBJ's shape tags), which
    /// writers that hold them write back where they are not the defaults.
    pub options: crate::mesh::options::ShapeOptions,
}

impl Attributes {
    /// Whether there is anything to carry per vertex, corner or face (the
    /// options are not carried: they describe the whole mesh).
    pub fn is_empty(&self) -> bool {
        self.uv.is_none() && self.colors.is_none() && self.materials.is_none()
    }

    /// These attributes stating `options`, for the whole mesh and for every
    /// prim of its scene (what a writer writes of a refined level: the
    /// options it was made with).
    pub fn with_options(mut self, options: crate::mesh::options::ShapeOptions) -> Attributes {
        self.options = options;
        if let Some(scene) = self.materials.as_mut().and_then(|m| m.scene.as_mut()) {
            for p in &mut std::sync::Arc::make_mut(scene).prims {
                p.options = options;
            }
        }
        self
    }

    /// The scene whose prims the material groups belong to (a USD stage's).
    pub fn scene(&self) -> Option<&crate::mesh::Scene> {
        self.materials.as_ref().and_then(|m| m.scene.as_deref())
    }
}

/// Texture coordinates per corner as shared values: one value per vertex
/// and coordinate (the same bits), in order of first use, and the value of
/// every corner. This is the face-varying topology the schemes refine (a
/// seam is a vertex whose corners hold different values), and what the
/// writers that share coordinates between corners keep (USD's
/// `primvars:st:indices`, OBJ's `vt` records).
pub(crate) fn weld_uvs(corner_vertex: &[u32], uv: &[Vec2]) -> (Vec<Vec2>, Vec<u32>) {
    let mut ids = std::collections::HashMap::with_capacity(uv.len() / 2);
    let mut values = Vec::new();
    let index = corner_vertex
        .iter()
        .zip(uv)
        .map(|(&v, &t)| {
            *ids.entry((v, t.x.to_bits(), t.y.to_bits())).or_insert_with(|| {
                values.push(t);
                values.len() as u32 - 1
            })
        })
        .collect();
    (values, index)
}

/// One material (an OBJ's MTL entry, a glTF material): what is drawn of it.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Its name (`newmtl`, `usemtl`).
    pub name: String,
    /// Diffuse colour `Kd` (linear RGB; 0.8 grey when the library has none).
    pub diffuse: Vec3,
    /// Diffuse texture `map_Kd` (glTF: base colour texture), resolved
    /// against the folder of the file that names it.
    pub diffuse_texture: Option<std::path::PathBuf>,
    /// How the texture repeats outside [0, 1], along `u` and along `v`
    /// (glTF's `wrapS` and `wrapT`; MTL's `-clamp on` clamps both).
    pub wrap: [Wrap; 2],
    /// The texture's pixels, when the load asked for textures and it could
    /// be decoded within the budget.
    pub texture: Option<std::sync::Arc<Texture>>,
}

impl Material {
    /// A material with only a name (its library was not found or lacks it).
    pub fn named(name: &str) -> Material {
        Material {
            name: name.to_string(),
            diffuse: Vec3::splat(0.8),
            diffuse_texture: None,
            wrap: [Wrap::Repeat; 2],
            texture: None,
        }
    }
}

/// How texture coordinates outside [0, 1] are mapped into the image.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Wrap {
    /// The image repeats (OBJ's default, glTF `REPEAT`).
    #[default]
    Repeat,
    /// The edge pixels extend (OBJ `-clamp on`, glTF `CLAMP_TO_EDGE`).
    Clamp,
    /// The image repeats mirrored (glTF `MIRRORED_REPEAT`).
    Mirror,
}

/// A decoded texture: `width * height` pixels, row 0 at the top, four
/// sRGB-encoded bytes each (red, green, blue, alpha).
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    /// Pixels per row.
    pub width: u32,
    /// Rows.
    pub height: u32,
    /// `4 * width * height` bytes.
    pub rgba: Vec<u8>,
}

/// Material groups of a mesh: a material id per triangle, the materials,
/// and the library files named by the OBJ (`mtllib`, written back as given).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MaterialGroups {
    /// Index into `list` of every triangle.
    pub face: Vec<u32>,
    /// The materials.
    pub list: Vec<Material>,
    /// The `mtllib` names, as in the file.
    pub libraries: Vec<String>,
    /// The scene whose prims the groups belong to (a USD stage's Mesh
    /// prims: [`crate::mesh::Scene::prim_of`] names each group's), so
    /// every face knows its prim at every level.
    pub scene: Option<std::sync::Arc<crate::mesh::Scene>>,
}

/// Per-triangle ids after `levels` 1-to-4 splits: every child triangle
/// inherits its parent's id. In the split layout (docs/schemes.md §7.4) triangle
/// `t` of `nt` keeps its id for the central child and its corner children
/// are `nt * (k + 1) + t` for k = 0, 1, 2, so each level repeats the list four times.
pub fn refine_face_ids(ids: &[u32], levels: u32) -> Vec<u32> {
    let mut out = ids.to_vec();
    for _ in 0..levels {
        let n = out.len();
        out.reserve(3 * n);
        for _ in 0..3 {
            out.extend_from_within(..n);
        }
    }
    out
}

/// Corner UVs after one 1-to-4 split (linear inside each triangle).
pub(crate) fn split_corner_uvs(uv: &[Vec2]) -> Vec<Vec2> {
    let nt = uv.len() / 3;
    let mut out = vec![Vec2::ZERO; 12 * nt];
    let (central, corners) = out.split_at_mut(3 * nt);
    central.par_chunks_mut(3).zip(uv.par_chunks_exact(3)).for_each(|(o, t)| {
        // corner k of the central triangle lies on the edge opposite corner k
        o[0] = 0.5 * (t[1] + t[2]);
        o[1] = 0.5 * (t[2] + t[0]);
        o[2] = 0.5 * (t[0] + t[1]);
    });
    // corner triangle of v(c): A(c) = 3nt(k+1) + 3t holds uv[c], then the
    // midpoints on the edges opposite p(c) and n(c)
    for k in 0..3usize {
        let block = &mut corners[3 * nt * k..3 * nt * (k + 1)];
        block.par_chunks_mut(3).enumerate().for_each(|(t, o)| {
            let c = (3 * t + k) as u32;
            let mid = |e: u32| 0.5 * (uv[n(e) as usize] + uv[p(e) as usize]);
            o[0] = uv[c as usize];
            o[1] = mid(p(c));
            o[2] = mid(n(c));
        });
    }
    out
}

/// Corner UVs after `levels` splits.
pub fn refine_corner_uvs(uv: &[Vec2], levels: u32) -> Vec<Vec2> {
    let mut cur = uv.to_vec();
    for _ in 0..levels {
        cur = split_corner_uvs(&cur);
    }
    cur
}
