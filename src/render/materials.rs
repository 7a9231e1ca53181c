//! Materials drawn on the surface: each corner gets its triangle's material
//! colour, the diffuse colour `Kd` times the diffuse texture sampled at the
//! corner's (refined) texture coordinate.
//!
//! The texture is sampled per corner of the drawn mesh and the colour
//! interpolated across each triangle (the renderer has no texture binding
//! yet), so detail finer than the refined triangles is lost: the texture
//! sharpens with each subdivision level. Textures arrive decoded with the
//! model (`io::ReadOptions::textures`, within the read's budget); here they
//! are sampled bilinearly, sRGB to linear, with the material's wrap mode
//! and `v` pointing up (OBJ's convention).

use crate::mesh::attributes::{MaterialGroups, Texture, Wrap};
use glam::{Vec2, Vec3};

/// sRGB bytes to linear values.
fn srgb_to_linear_table() -> &'static [f32; 256] {
    static TABLE: std::sync::OnceLock<[f32; 256]> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        std::array::from_fn(|i| {
            let c = i as f32 / 255.0;
            if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
        })
    })
}

/// The pixel column or row `i` of `n` for `wrap`.
fn wrap_index(i: f32, n: u32, wrap: Wrap) -> u32 {
    let n = n as i64;
    let i = i as i64;
    let k = match wrap {
        Wrap::Repeat => i.rem_euclid(n),
        Wrap::Clamp => i.clamp(0, n - 1),
        Wrap::Mirror => {
            let m = i.rem_euclid(2 * n);
            if m < n { m } else { 2 * n - 1 - m }
        }
    };
    k as u32
}

/// Bilinear sample of `t` at `uv` (linear RGB; `v` = 0 at the bottom row).
pub fn sample(t: &Texture, uv: Vec2, wrap: Wrap) -> Vec3 {
    let lin = srgb_to_linear_table();
    let (w, h) = (t.width as f32, t.height as f32);
    let x = uv.x * w - 0.5;
    let y = (1.0 - uv.y) * h - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let at = |i: f32, j: f32| {
        let (i, j) = (wrap_index(i, t.width, wrap), wrap_index(j, t.height, wrap));
        let k = 4 * (j as usize * t.width as usize + i as usize);
        Vec3::new(lin[t.rgba[k] as usize], lin[t.rgba[k + 1] as usize], lin[t.rgba[k + 2] as usize])
    };
    let top = at(x0, y0).lerp(at(x0 + 1.0, y0), fx);
    let bottom = at(x0, y0 + 1.0).lerp(at(x0 + 1.0, y0 + 1.0), fx);
    top.lerp(bottom, fy)
}

/// The colour of every corner (three per triangle) of a mesh with these
/// material groups and, when given, per-corner texture coordinates.
pub fn corner_colors(groups: &MaterialGroups, uv: Option<&[Vec2]>) -> Vec<Vec3> {
    let uv = uv.filter(|u| u.len() == 3 * groups.face.len());
    let mut out = Vec::with_capacity(3 * groups.face.len());
    for (t, &m) in groups.face.iter().enumerate() {
        let Some(mat) = groups.list.get(m as usize) else {
            out.extend([Vec3::splat(0.8); 3]);
            continue;
        };
        for k in 0..3 {
            let c = match (&mat.texture, uv) {
                (Some(tex), Some(uv)) => mat.diffuse * sample(tex, uv[3 * t + k], mat.wrap),
                _ => mat.diffuse,
            };
            out.push(c.clamp(Vec3::ZERO, Vec3::ONE));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_modes_map_pixels_as_named() {
        assert_eq!([-1.0, 0.0, 3.0, 4.0].map(|i| wrap_index(i, 4, Wrap::Repeat)), [3, 0, 3, 0]);
        assert_eq!([-1.0, 0.0, 3.0, 4.0].map(|i| wrap_index(i, 4, Wrap::Clamp)), [0, 0, 3, 3]);
        assert_eq!([-1.0, 0.0, 3.0, 4.0, 8.0].map(|i| wrap_index(i, 4, Wrap::Mirror)), [0, 0, 3, 3, 0]);
    }
}
