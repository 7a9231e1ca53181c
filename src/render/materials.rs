//! Materials of an OBJ's MTL drawn on the surface: each corner gets its
//! triangle's material colour, the diffuse colour `Kd` times the diffuse
//! texture `map_Kd` sampled at the corner's (refined) texture coordinate.
//!
//! The texture is sampled per corner of the drawn mesh and the colour
//! interpolated across each triangle (the renderer has no texture binding
//! yet), so detail finer than the refined triangles is lost: the texture
//! sharpens with each subdivision level. Textures are decoded with `image`
//! (PNG, JPEG and GIF), once per file, sRGB to linear, sampled
//! bilinearly with wrapping and `v` pointing up (OBJ's convention).

use crate::mesh::attributes::MaterialGroups;
use glam::{Vec2, Vec3};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Decoded textures by file, `None` for one that could not be read (warned once).
#[derive(Default)]
pub struct Textures {
    cache: HashMap<PathBuf, Option<image::Rgb32FImage>>,
}

impl Textures {
    /// The texture in `path`, decoded and converted to linear RGB.
    pub fn get(&mut self, path: &Path) -> Option<&image::Rgb32FImage> {
        self.cache
            .entry(path.to_path_buf())
            .or_insert_with(|| match image::open(path) {
                Ok(img) => {
                    let mut t = img.to_rgb32f();
                    t.pixels_mut().for_each(|p| p.0 = p.0.map(srgb_to_linear));
                    (t.width() > 0 && t.height() > 0).then_some(t)
                }
                Err(e) => {
                    log::warn!("texture {}: {e}", path.display());
                    None
                }
            })
            .as_ref()
    }
}

fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
}

/// Bilinear sample of `t` at `uv` (wrapping; `v` = 0 at the bottom row).
pub fn sample(t: &image::Rgb32FImage, uv: Vec2) -> Vec3 {
    let (w, h) = (t.width() as f32, t.height() as f32);
    let x = uv.x.rem_euclid(1.0) * w - 0.5;
    let y = (1.0 - uv.y.rem_euclid(1.0)) * h - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let at = |i: f32, j: f32| {
        let (i, j) = (i.rem_euclid(w) as u32, j.rem_euclid(h) as u32);
        Vec3::from(t.get_pixel(i.min(t.width() - 1), j.min(t.height() - 1)).0)
    };
    let top = at(x0, y0).lerp(at(x0 + 1.0, y0), fx);
    let bottom = at(x0, y0 + 1.0).lerp(at(x0 + 1.0, y0 + 1.0), fx);
    top.lerp(bottom, fy)
}

/// The colour of every corner (three per triangle) of a mesh with these
/// material groups and, when given, per-corner texture coordinates.
pub fn corner_colors(groups: &MaterialGroups, uv: Option<&[Vec2]>, textures: &mut Textures) -> Vec<Vec3> {
    let uv = uv.filter(|u| u.len() == 3 * groups.face.len());
    let mut out = Vec::with_capacity(3 * groups.face.len());
    for (t, &m) in groups.face.iter().enumerate() {
        let Some(mat) = groups.list.get(m as usize) else {
            out.extend([Vec3::splat(0.8); 3]);
            continue;
        };
        let tex = match (&mat.diffuse_texture, uv) {
            (Some(p), Some(_)) => textures.get(p),
            _ => None,
        };
        for k in 0..3 {
            let c = match (tex, uv) {
                (Some(tex), Some(uv)) => mat.diffuse * sample(tex, uv[3 * t + k]),
                _ => mat.diffuse,
            };
            out.push(c.clamp(Vec3::ZERO, Vec3::ONE));
        }
    }
    out
}
