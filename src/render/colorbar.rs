//! A colour bar drawn into a rendered picture: the diverging curvature map
//! from `-range` (bottom, blue) to `range` (top, red) at the right edge,
//! with its three numbers in a small built-in pixel font (digits, `.`, `-`,
//! `+` and `e`), so a PNG says what its colours mean without a font file.

use crate::subdiv::eval::color::diverging;
use image::{Rgba, RgbaImage};

/// 3 x 5 glyphs, one row per entry, bit 2 = left column.
fn glyph(c: char) -> [u8; 5] {
    match c {
        '0' => [7, 5, 5, 5, 7],
        '1' => [2, 6, 2, 2, 7],
        '2' => [7, 1, 7, 4, 7],
        '3' => [7, 1, 7, 1, 7],
        '4' => [5, 5, 7, 1, 1],
        '5' => [7, 4, 7, 1, 7],
        '6' => [7, 4, 7, 5, 7],
        '7' => [7, 1, 1, 1, 1],
        '8' => [7, 5, 7, 5, 7],
        '9' => [7, 5, 7, 1, 7],
        '.' => [0, 0, 0, 0, 2],
        '-' => [0, 0, 7, 0, 0],
        '+' => [0, 2, 7, 2, 0],
        'e' => [0, 7, 7, 4, 7],
        _ => [0; 5],
    }
}

fn srgb8(x: f32) -> u8 {
    let s = if x <= 0.003_130_8 { 12.92 * x } else { 1.055 * x.powf(1.0 / 2.4) - 0.055 };
    (s.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// Writes `text` with its top-right corner at `(right, top)`, `scale`
/// pixels per font pixel, in `ink`.
fn text(img: &mut RgbaImage, text: &str, (right, top): (i64, i64), scale: i64, ink: Rgba<u8>) {
    let width = text.chars().count() as i64 * 4 * scale;
    for (i, c) in text.chars().enumerate() {
        let x0 = right - width + i as i64 * 4 * scale;
        for (row, bits) in glyph(c).iter().enumerate() {
            for col in 0..3 {
                if bits >> (2 - col) & 1 == 1 {
                    for dy in 0..scale {
                        for dx in 0..scale {
                            let (x, y) = (x0 + col * scale + dx, top + row as i64 * scale + dy);
                            if x >= 0 && y >= 0 && x < i64::from(img.width()) && y < i64::from(img.height()) {
                                img.put_pixel(x as u32, y as u32, ink);
                            }
                        }
                    }
                }
            }
        }
    }
}

/// Draws the bar and its numbers (`-range`, `0`, `range`) at the right
/// edge of `img`, with a tick left of the bar at each of `isolines` levels
/// per side of zero (the levels of [`crate::render::Look::isolines`]; none
/// for 0), the zero tick longer.
pub fn draw(img: &mut RgbaImage, range: f64, isolines: u8) {
    let (w, h) = (i64::from(img.width()), i64::from(img.height()));
    let scale = (h / 240).clamp(1, 4);
    let (bar_w, bar_h) = (6 * scale, h * 3 / 5);
    let (x0, y0) = (w - bar_w - 4 * scale, (h - bar_h) / 2);
    if x0 < 0 || bar_h < 4 {
        return;
    }
    for y in 0..bar_h {
        let t = 1.0 - 2.0 * (y as f32 + 0.5) / bar_h as f32;
        let c = diverging(t);
        let px = Rgba([srgb8(c.x), srgb8(c.y), srgb8(c.z), 255]);
        for x in 0..bar_w {
            img.put_pixel((x0 + x) as u32, (y0 + y) as u32, px);
        }
    }
    let n = i64::from(isolines);
    for k in (-n..=n).filter(|_| n > 0) {
        // level k / (n + 1) of the range, from the bar's middle row
        let y = y0 + bar_h * (n + 1 - k) / (2 * n + 2);
        let len = if k == 0 { bar_w } else { bar_w / 2 };
        for x in x0..x0 + len {
            img.put_pixel(x as u32, y as u32, Rgba([10, 10, 10, 255]));
        }
    }
    let ink = Rgba([235, 235, 235, 255]);
    let right = x0 - 2 * scale;
    text(img, &format!("{range:.2e}"), (right, y0), scale, ink);
    text(img, "0", (right, y0 + bar_h / 2 - 2 * scale), scale, ink);
    text(img, &format!("{:.2e}", -range), (right, y0 + bar_h - 5 * scale), scale, ink);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_bar_runs_from_blue_to_red_with_its_numbers_beside_it() {
        let mut img = RgbaImage::from_pixel(320, 240, Rgba([0, 0, 0, 255]));
        draw(&mut img, 0.5, 0);
        let x = 320 - 6 - 4 + 3;
        let (top, bottom) = (img.get_pixel(x, 50).0, img.get_pixel(x, 190).0);
        assert!(top[0] > top[2] + 80 && bottom[2] > bottom[0] + 80, "{top:?} {bottom:?}");
        // the numbers: light pixels left of the bar
        let ink = (0..300).flat_map(|x| (40..60).map(move |y| (x, y))).filter(|&(x, y)| img.get_pixel(x, y).0[0] > 200);
        assert!(ink.count() > 20);
        // ticks: dark rows across the bar, 2 per side and zero for 2 isolines
        // (the bar's rows: 48 to 191)
        let dark_rows =
            |img: &RgbaImage| (48..192).filter(|&y| img.get_pixel(x - 2, y).0[..3].iter().all(|&c| c < 40)).count();
        assert_eq!(dark_rows(&img), 0);
        draw(&mut img, 0.5, 2);
        assert_eq!(dark_rows(&img), 5);
    }
}
