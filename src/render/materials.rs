//! Materials drawn on the surface, the CPU's part: what the GPU needs to
//! draw each material group with its texture sampled per pixel
//! ([`super::textures`], shaders/mesh.wgsl `material_color`).
//!
//! * [`mip_chain`]: a texture and its smaller versions (mipmaps), each half
//!   the size of the one before, averaged in linear light (a 2 x 2 box in
//!   sRGB bytes would darken every edge between light and dark) and
//!   stored as sRGB bytes again, which the GPU decodes to linear when it
//!   samples (an `Rgba8UnormSrgb` texture).
//! * [`material_runs`]: the triangles' corners ordered by material, so each
//!   group is one draw of a range of that order with its texture bound.
//! * [`sample`]: the texture at a texture coordinate on the CPU, bilinear
//!   in linear light, as the GPU samples the full-size level: a reference
//!   for tests and for code without a GPU.
//!
//! Texture coordinates follow OBJ's convention, `v` pointing up from the
//! bottom row of the image (glTF's are flipped on reading).

use crate::mesh::attributes::{Texture, Wrap};
use glam::{Vec2, Vec3, Vec4};

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

/// A linear value in 0..=1 as an sRGB byte.
fn linear_to_srgb8(c: f32) -> u8 {
    let c = c.clamp(0.0, 1.0);
    let s = if c <= 0.003_130_8 { c * 12.92 } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 };
    (s * 255.0).round() as u8
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

/// Bilinear sample of `t` at `uv` (linear RGB; `v` = 0 at the bottom row)
/// with the wrap modes along `u` and `v`.
pub fn sample(t: &Texture, uv: Vec2, wrap: [Wrap; 2]) -> Vec3 {
    let lin = srgb_to_linear_table();
    let (w, h) = (t.width as f32, t.height as f32);
    let x = uv.x * w - 0.5;
    let y = (1.0 - uv.y) * h - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let at = |i: f32, j: f32| {
        let (i, j) = (wrap_index(i, t.width, wrap[0]), wrap_index(j, t.height, wrap[1]));
        let k = 4 * (j as usize * t.width as usize + i as usize);
        Vec3::new(lin[t.rgba[k] as usize], lin[t.rgba[k + 1] as usize], lin[t.rgba[k + 2] as usize])
    };
    let top = at(x0, y0).lerp(at(x0 + 1.0, y0), fx);
    let bottom = at(x0, y0 + 1.0).lerp(at(x0 + 1.0, y0 + 1.0), fx);
    top.lerp(bottom, fy)
}

/// The pixel `(x, y)` of `t` in linear light (alpha as stored).
fn linear_pixel(t: &Texture, x: usize, y: usize) -> Vec4 {
    let lin = srgb_to_linear_table();
    let k = 4 * (y * t.width as usize + x);
    let p = &t.rgba[k..k + 4];
    Vec4::new(lin[p[0] as usize], lin[p[1] as usize], lin[p[2] as usize], f32::from(p[3]) / 255.0)
}

/// `t` at half its size (at least one pixel a side; an odd side's pixels
/// shared by the two halves), each pixel the average in linear light of
/// the pixels it covers.
pub(crate) fn downsample(t: &Texture) -> Texture {
    let (w, h) = (t.width as usize, t.height as usize);
    let (nw, nh) = ((w / 2).max(1), (h / 2).max(1));
    // the source pixels of output pixel i of n along a side of m pixels
    let span = |i: usize, n: usize, m: usize| (i * m / n)..((i + 1) * m).div_ceil(n).min(m);
    let mut rgba = Vec::with_capacity(4 * nw * nh);
    for y in 0..nh {
        for x in 0..nw {
            let (xs, ys) = (span(x, nw, w), span(y, nh, h));
            let count = (xs.len() * ys.len()) as f32;
            let sum: Vec4 = ys.flat_map(|j| xs.clone().map(move |i| (i, j))).map(|(i, j)| linear_pixel(t, i, j)).sum();
            let c = sum / count;
            rgba.extend([linear_to_srgb8(c.x), linear_to_srgb8(c.y), linear_to_srgb8(c.z)]);
            rgba.push((c.w * 255.0).round().clamp(0.0, 255.0) as u8);
        }
    }
    Texture { width: nw as u32, height: nh as u32, rgba }
}

/// The mipmaps of `t`: the largest level whose sides are at most
/// `max_side` pixels (a texture larger than the device holds starts at a
/// smaller level), then each level half the one before, down to one pixel.
pub(crate) fn mip_chain(t: &Texture, max_side: u32) -> Vec<Texture> {
    let mut levels: Vec<Texture> = Vec::new();
    let mut fits = t.width <= max_side && t.height <= max_side;
    if fits {
        levels.push(t.clone());
    }
    let mut last = t.clone();
    while last.width > 1 || last.height > 1 {
        last = downsample(&last);
        fits |= last.width <= max_side && last.height <= max_side;
        if fits {
            levels.push(last.clone());
        }
    }
    if levels.is_empty() {
        levels.push(last);
    }
    levels
}

/// A range of the corner order drawn with one material.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Run {
    /// The material's index in the group's list (`list.len()` for ids that
    /// name no material: drawn grey).
    pub material: usize,
    /// Positions in the corner order.
    pub corners: std::ops::Range<u32>,
}

/// The corners of the triangles (three per triangle, as the V table
/// lists them) ordered by the material of their triangle, and the run of
/// each material in that order; `face` holds the material of each
/// triangle, `count` how many materials there are (larger ids share one
/// run, numbered `count`).
pub(crate) fn material_runs(face: &[u32], count: usize) -> (Vec<u32>, Vec<Run>) {
    let slot = |m: u32| (m as usize).min(count);
    let mut sizes = vec![0u32; count + 1];
    for &m in face {
        sizes[slot(m)] += 3;
    }
    let mut start = Vec::with_capacity(count + 1);
    let mut runs = Vec::new();
    let mut at = 0u32;
    for (material, &n) in sizes.iter().enumerate() {
        start.push(at);
        if n > 0 {
            runs.push(Run { material, corners: at..at + n });
        }
        at += n;
    }
    let mut order = vec![0u32; 3 * face.len()];
    for (t, &m) in face.iter().enumerate() {
        let s = &mut start[slot(m)];
        for k in 0..3 {
            order[(*s + k) as usize] = 3 * t as u32 + k;
        }
        *s += 3;
    }
    (order, runs)
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

    #[test]
    fn mipmaps_average_in_linear_light_down_to_one_pixel() {
        // black and white columns: their average is a linear 0.5, sRGB 188,
        // not the 128 of averaging the bytes
        let rgba = (0..8 * 4).flat_map(|i| if i % 2 == 0 { [0, 0, 0, 255] } else { [255; 4] }).collect();
        let t = Texture { width: 8, height: 4, rgba };
        let chain = mip_chain(&t, 4096);
        let sizes: Vec<(u32, u32)> = chain.iter().map(|l| (l.width, l.height)).collect();
        assert_eq!(sizes, [(8, 4), (4, 2), (2, 1), (1, 1)]);
        assert!(chain[1].rgba.chunks(4).all(|p| p == [188, 188, 188, 255]), "{:?}", &chain[1].rgba[..8]);
        // an odd side keeps every pixel: 3 x 1 -> 1 x 1 averages all three
        let odd = Texture { width: 3, height: 1, rgba: [[255, 0, 0, 255], [255, 0, 0, 255], [0; 4]].concat() };
        assert_eq!(downsample(&odd).rgba[..2], [linear_to_srgb8(2.0 / 3.0), 0]);
        // a texture larger than the device holds starts at a level that fits
        assert_eq!(mip_chain(&t, 2).first().map(|l| (l.width, l.height)), Some((2, 1)));
    }

    #[test]
    fn corners_are_ordered_by_material() {
        let (order, runs) = material_runs(&[1, 0, 1, 9], 2);
        assert_eq!(order, [3, 4, 5, 0, 1, 2, 6, 7, 8, 9, 10, 11]);
        assert_eq!(
            runs,
            [
                Run { material: 0, corners: 0..3 },
                Run { material: 1, corners: 3..9 },
                Run { material: 2, corners: 9..12 }
            ]
        );
        assert_eq!(material_runs(&[], 3), (vec![], vec![]));
    }
}
