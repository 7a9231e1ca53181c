//! A colour bar drawn into a rendered picture: the diverging curvature map
//! from `-range` (bottom, blue) to `range` (top, red) at the right edge,
//! with its three numbers and a caption above it (what is coloured, the
//! range and where it came from) in a small built-in pixel font (digits,
//! capitals and `. - + e ± % ( ) : , / = [ ] ' ^ _ # ;`), so a PNG says
//! what its colours mean without a font file; the inspector's overlays
//! ([`super::overlay`]) write their labels with it too.

use crate::subdiv::eval::color::{diverging, short};
use image::{Rgba, RgbaImage};

/// 3 x 5 glyphs, one row per entry, bit 2 = left column.
pub(crate) fn glyph(c: char) -> [u8; 5] {
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
        '±' => [2, 7, 2, 0, 7],
        '%' => [5, 1, 2, 4, 5],
        '(' => [1, 2, 2, 2, 1],
        ')' => [4, 2, 2, 2, 4],
        ':' => [0, 2, 0, 2, 0],
        ',' => [0, 0, 0, 2, 4],
        '/' => [1, 1, 2, 4, 4],
        '=' => [0, 7, 0, 7, 0],
        '[' => [3, 2, 2, 2, 3],
        ']' => [6, 2, 2, 2, 6],
        '\'' => [2, 2, 0, 0, 0],
        '^' => [2, 5, 0, 0, 0],
        '_' => [0, 0, 0, 0, 7],
        '#' => [5, 7, 5, 7, 5],
        ';' => [0, 2, 0, 2, 4],
        'A'..='Z' => letter(c),
        _ => [0; 5],
    }
}

/// 3 x 5 capitals.
fn letter(c: char) -> [u8; 5] {
    const LETTERS: [[u8; 5]; 26] = [
        [2, 5, 7, 5, 5], // A
        [6, 5, 6, 5, 6], // B
        [3, 4, 4, 4, 3], // C
        [6, 5, 5, 5, 6], // D
        [7, 4, 6, 4, 7], // E
        [7, 4, 6, 4, 4], // F
        [3, 4, 5, 5, 3], // G
        [5, 5, 7, 5, 5], // H
        [7, 2, 2, 2, 7], // I
        [1, 1, 1, 5, 2], // J
        [5, 5, 6, 5, 5], // K
        [4, 4, 4, 4, 7], // L
        [5, 7, 7, 5, 5], // M
        [6, 5, 5, 5, 5], // N
        [2, 5, 5, 5, 2], // O
        [6, 5, 6, 4, 4], // P
        [2, 5, 5, 6, 3], // Q
        [6, 5, 6, 5, 5], // R
        [3, 4, 2, 1, 6], // S
        [7, 2, 2, 2, 2], // T
        [5, 5, 5, 5, 7], // U
        [5, 5, 5, 5, 2], // V
        [5, 5, 7, 7, 5], // W
        [5, 5, 2, 5, 5], // X
        [5, 5, 2, 2, 2], // Y
        [7, 1, 2, 4, 7], // Z
    ];
    LETTERS[(c as u8 - b'A') as usize]
}

fn srgb8(x: f32) -> u8 {
    let s = if x <= 0.003_130_8 { 12.92 * x } else { 1.055 * x.powf(1.0 / 2.4) - 0.055 };
    (s.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// Writes `text` with its top-right corner at `(right, top)`, `scale`
/// pixels per font pixel, in `ink`.
fn text(img: &mut RgbaImage, text: &str, (right, top): (i64, i64), scale: i64, ink: Rgba<u8>) {
    let width = text.chars().count() as i64 * 4 * scale;
    text_from(img, text, (right - width, top), scale, ink);
}

/// Writes `text` with its top-left corner at `(left, top)`, `scale` pixels
/// per font pixel, in `ink` (4 `scale` pixels a character, 5 `scale` tall).
pub(crate) fn text_from(img: &mut RgbaImage, text: &str, (left, top): (i64, i64), scale: i64, ink: Rgba<u8>) {
    for (i, c) in text.chars().enumerate() {
        let x0 = left + i as i64 * 4 * scale;
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
/// for 0), the zero tick longer, and the lines of `caption` above it (in
/// capitals), right-aligned with it: say what is coloured and the range
/// (`Scale::describe` of `crate::subdiv::eval::color`).
pub fn draw(img: &mut RgbaImage, range: f64, isolines: u8, caption: &[String]) {
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
    text(img, &short(range), (right, y0), scale, ink);
    text(img, "0", (right, y0 + bar_h / 2 - 2 * scale), scale, ink);
    text(img, &short(-range), (right, y0 + bar_h - 5 * scale), scale, ink);
    let lines = caption.len() as i64;
    for (i, line) in caption.iter().enumerate() {
        let top = y0 - (lines - i as i64) * 7 * scale - 2 * scale;
        text(img, &line.to_uppercase(), (x0 + bar_w, top), scale, ink);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_bar_runs_from_blue_to_red_with_its_numbers_beside_it() {
        let mut img = RgbaImage::from_pixel(320, 240, Rgba([0, 0, 0, 255]));
        draw(&mut img, 0.5, 0, &["mean curvature".into(), "±0.500 (set)".into()]);
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
        draw(&mut img, 0.5, 2, &[]);
        assert_eq!(dark_rows(&img), 5);
        // the caption: two lines of light pixels above the bar, right-aligned with it
        let lit = |y: std::ops::Range<u32>| {
            y.flat_map(|y| (0..320).map(move |x| (x, y))).filter(|&(x, y)| img.get_pixel(x, y).0[0] > 200).count()
        };
        assert!(lit(32..37) > 20 && lit(39..44) > 20, "caption lines: {} {}", lit(32..37), lit(39..44));
        let outside = (32..44).flat_map(|y| (0..320).map(move |x| (x, y))).filter(|&(x, _)| !(250..316).contains(&x));
        assert!(outside.into_iter().all(|(x, y)| img.get_pixel(x, y).0[0] <= 200), "ends at the bar's right edge");
    }
}
