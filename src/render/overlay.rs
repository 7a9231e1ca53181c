//! Marks drawn over a picture of the surface: the inspector's arrows,
//! discs and labels (see [`super::inspect`]), the same in the window and in
//! a PNG.
//!
//! ```text
//! Overlay (marks at world points, sizes in pixels; a caption)
//!   --project(camera, viewport)-->  Prim (2D lines, triangles, circles, text)
//!   --paint(RgbaImage)-->           pixels (`subdiv render --corner/--stencil`)
//!   --the viewer's egui painter-->  the 3D area (src/app/panel/overlay.rs)
//! ```
//! Both ends draw the same primitives: only the text's font differs (egui's
//! in the window, the pixel font of `super::colorbar`, in capitals, in a
//! PNG). Marks are drawn over the surface, never hidden by it.

use super::Camera;
use super::colorbar::text_from;
use glam::{Vec2, Vec3};
use image::{Rgba, RgbaImage};

/// A colour, sRGB with alpha.
pub(crate) type Rgba8 = [u8; 4];

/// Dark halo under lines and around discs, so that marks read on any surface.
pub(crate) const HALO: Rgba8 = [20, 20, 24, 220];

/// One mark at world points; sizes are in pixels at scale 1.
#[derive(Clone, Debug, PartialEq)]
pub enum Mark {
    /// An arrow from `from` to `to`, labelled beside its middle.
    Arrow {
        /// Tail.
        from: Vec3,
        /// Head.
        to: Vec3,
        /// Colour of the arrow and its label.
        color: Rgba8,
        /// Label.
        label: String,
    },
    /// A segment `width` pixels wide.
    Segment {
        /// One end.
        a: Vec3,
        /// The other end.
        b: Vec3,
        /// Colour.
        color: Rgba8,
        /// Width, pixels.
        width: f32,
    },
    /// A filled disc with a dark rim, labelled at its right.
    Disc {
        /// Centre.
        at: Vec3,
        /// Radius, pixels.
        radius: f32,
        /// Fill.
        color: Rgba8,
        /// Label beside it.
        label: Option<String>,
    },
    /// A ring (a circle's outline, 2 pixels wide, with a halo).
    Ring {
        /// Centre.
        at: Vec3,
        /// Radius, pixels.
        radius: f32,
        /// Colour.
        color: Rgba8,
    },
    /// Text centred at a point.
    Text {
        /// Centre.
        at: Vec3,
        /// Text.
        text: String,
        /// Colour.
        color: Rgba8,
    },
}

/// What an inspector draws: marks, and caption lines for the picture's
/// top-left corner.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Overlay {
    /// The marks, drawn in order.
    pub marks: Vec<Mark>,
    /// Lines of text at the top left.
    pub caption: Vec<String>,
}

/// Where a text's position is on its box.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Anchor {
    /// The middle of the left side.
    LeftCenter,
    /// The middle of the right side.
    RightCenter,
    /// The centre.
    Center,
    /// The top-left corner.
    LeftTop,
}

/// A 2D primitive in pixels (window points or image pixels).
#[derive(Clone, Debug, PartialEq)]
pub enum Prim {
    /// A segment with round ends.
    Line {
        /// One end.
        a: Vec2,
        /// The other end.
        b: Vec2,
        /// Width.
        width: f32,
        /// Colour.
        color: Rgba8,
    },
    /// A filled triangle.
    Triangle {
        /// Corners.
        p: [Vec2; 3],
        /// Colour.
        color: Rgba8,
    },
    /// A filled circle.
    Circle {
        /// Centre.
        c: Vec2,
        /// Radius.
        r: f32,
        /// Colour.
        color: Rgba8,
    },
    /// A circle's outline.
    CircleStroke {
        /// Centre.
        c: Vec2,
        /// Radius.
        r: f32,
        /// Width.
        width: f32,
        /// Colour.
        color: Rgba8,
    },
    /// Text on a dark box.
    Text {
        /// Where the anchor is.
        at: Vec2,
        /// Which point of the box `at` is.
        anchor: Anchor,
        /// Text.
        text: String,
        /// Colour.
        color: Rgba8,
    },
}

/// The picture marks are drawn on: its rectangle (pixels or points) and the
/// pixels per point of sizes (a screenshot's scale).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Viewport {
    /// Top-left corner.
    pub min: Vec2,
    /// Width and height.
    pub size: Vec2,
    /// Sizes (widths, radii, arrowheads, the pixel font) are multiplied by this.
    pub scale: f32,
}

impl Viewport {
    /// A whole image of `width` x `height` pixels at `scale`.
    pub fn image(width: u32, height: u32, scale: f32) -> Viewport {
        Viewport { min: Vec2::ZERO, size: Vec2::new(width as f32, height as f32), scale }
    }

    /// The position of world point `p` seen by `camera`, `None` behind the
    /// eye or beyond the far plane.
    pub fn to_screen(&self, camera: &Camera, p: Vec3) -> Option<Vec2> {
        let ndc = camera.project(p, self.size.x / self.size.y.max(1.0));
        ((0.0..=1.0).contains(&ndc.z) && ndc.is_finite())
            .then(|| self.min + Vec2::new((ndc.x + 1.0) * 0.5 * self.size.x, (1.0 - ndc.y) * 0.5 * self.size.y))
    }
}

/// The caption of `overlay` at the top left, below `caption_top` points
/// (the window's label is above it), then its marks as 2D primitives in
/// `vp` (those at points that cannot be seen are left out). A label goes
/// where it overlaps no label placed before it and no disc, when one of a
/// few places beside its mark is free, else where it overlaps least.
pub fn project(overlay: &Overlay, camera: &Camera, vp: &Viewport, caption_top: f32) -> Vec<Prim> {
    let (mut shapes, mut labels) = (Vec::new(), Labels::new(vp));
    let k = vp.scale;
    let at = |p: Vec3| vp.to_screen(camera, p);
    // the caption first: the marks are drawn over it, their labels beside it
    for (i, text) in overlay.caption.iter().enumerate() {
        let at = vp.min + Vec2::new(10.0 * k, (caption_top + i as f32 * 14.0) * k);
        labels.taken.push(labels.boxed(at, Anchor::LeftTop, text));
        shapes.push(Prim::Text { at, anchor: Anchor::LeftTop, text: text.clone(), color: [235, 235, 235, 255] });
    }
    for m in &overlay.marks {
        if let Mark::Disc { at: p, radius, .. } = m
            && let Some(c) = at(*p)
        {
            labels.taken.push((c - Vec2::splat(radius * k), c + Vec2::splat(radius * k)));
        }
    }
    for m in &overlay.marks {
        match m {
            Mark::Arrow { from, to, color, label } => {
                if let (Some(a), Some(b)) = (at(*from), at(*to)) {
                    arrow(&mut shapes, &mut labels, (a, b), *color, label);
                }
            }
            Mark::Segment { a, b, color, width } => {
                if let (Some(a), Some(b)) = (at(*a), at(*b)) {
                    shapes.push(Prim::Line { a, b, width: (width + 2.0) * k, color: HALO });
                    shapes.push(Prim::Line { a, b, width: width * k, color: *color });
                }
            }
            Mark::Disc { at: p, radius, color, label } => {
                let Some(c) = at(*p) else { continue };
                shapes.push(Prim::Circle { c, r: (radius + 1.5) * k, color: HALO });
                shapes.push(Prim::Circle { c, r: radius * k, color: *color });
                if let Some(text) = label {
                    labels.place(&disc_spots(c, radius * k, k), text, *color);
                }
            }
            Mark::Ring { at: p, radius, color } => {
                let Some(c) = at(*p) else { continue };
                shapes.push(Prim::CircleStroke { c, r: radius * k, width: 4.0 * k, color: HALO });
                shapes.push(Prim::CircleStroke { c, r: radius * k, width: 2.0 * k, color: *color });
            }
            Mark::Text { at: p, text, color } => {
                if let Some(c) = at(*p) {
                    let d = Vec2::new(0.0, 12.0 * k);
                    labels.place(
                        &[(c, Anchor::Center), (c - d, Anchor::Center), (c + d, Anchor::Center)],
                        text,
                        *color,
                    );
                }
            }
        }
    }
    shapes.extend(labels.placed);
    shapes
}

/// Where a disc's label may go: right, left, above, below, then the
/// diagonals on the right.
fn disc_spots(c: Vec2, r: f32, k: f32) -> [(Vec2, Anchor); 6] {
    let (dx, dy) = (r + 5.0 * k, r + 9.0 * k);
    [
        (c + Vec2::new(dx, 0.0), Anchor::LeftCenter),
        (c - Vec2::new(dx, 0.0), Anchor::RightCenter),
        (c - Vec2::new(0.0, dy), Anchor::Center),
        (c + Vec2::new(0.0, dy), Anchor::Center),
        (c + Vec2::new(dx, -dy), Anchor::LeftCenter),
        (c + Vec2::new(dx, dy), Anchor::LeftCenter),
    ]
}

/// Labels placed so far and the boxes they and the discs take.
struct Labels {
    placed: Vec<Prim>,
    taken: Vec<(Vec2, Vec2)>,
    /// The viewport's corners.
    bounds: (Vec2, Vec2),
    scale: f32,
}

impl Labels {
    fn new(vp: &Viewport) -> Labels {
        Labels { placed: Vec::new(), taken: Vec::new(), bounds: (vp.min, vp.min + vp.size), scale: vp.scale }
    }

    /// The box a label takes, estimated (8 points a character, 14 tall:
    /// the pixel font at twice its size; egui's 14-point font is close).
    fn boxed(&self, at: Vec2, anchor: Anchor, text: &str) -> (Vec2, Vec2) {
        let size = Vec2::new(text.chars().count() as f32 * 8.0 + 4.0, 14.0) * self.scale;
        let min = match anchor {
            Anchor::LeftCenter => at - Vec2::new(0.0, size.y * 0.5),
            Anchor::RightCenter => at - Vec2::new(size.x, size.y * 0.5),
            Anchor::Center => at - size * 0.5,
            Anchor::LeftTop => at,
        };
        (min, min + size)
    }

    /// How much of the box `b` the boxes taken (and the space beyond the
    /// picture's edges) cover.
    fn clash(&self, b: (Vec2, Vec2)) -> f32 {
        let overlap = |o: &(Vec2, Vec2)| {
            let d = (b.1.min(o.1) - b.0.max(o.0)).max(Vec2::ZERO);
            d.x * d.y
        };
        let inside = (b.1.min(self.bounds.1) - b.0.max(self.bounds.0)).max(Vec2::ZERO);
        let size = b.1 - b.0;
        self.taken.iter().map(overlap).sum::<f32>() + (size.x * size.y - inside.x * inside.y)
    }

    /// Places `text` at the first of `spots` that is free, else at the
    /// one that clashes least.
    fn place(&mut self, spots: &[(Vec2, Anchor)], text: &str, color: Rgba8) {
        let mut best: Option<((Vec2, Anchor), f32)> = None;
        for &(at, anchor) in spots {
            let clash = self.clash(self.boxed(at, anchor, text));
            if best.is_none_or(|(_, b)| clash < b) {
                best = Some(((at, anchor), clash));
            }
            if clash <= 0.0 {
                break;
            }
        }
        let Some(((at, anchor), _)) = best else { return };
        self.taken.push(self.boxed(at, anchor, text));
        self.placed.push(Prim::Text { at, anchor, text: text.into(), color });
    }
}

/// An arrow from `a` to `b` (shortened a little at both ends, so that a
/// corner's dot stays visible), its head a triangle, its label beside it.
fn arrow(out: &mut Vec<Prim>, labels: &mut Labels, (a, b): (Vec2, Vec2), color: Rgba8, label: &str) {
    let k = labels.scale;
    let d = b - a;
    let len = d.length();
    if len < 8.0 * k {
        // the two corners fall together on the screen: the label alone
        let dx = Vec2::new(6.0 * k, 0.0);
        labels.place(&[(b + dx, Anchor::LeftCenter), (b - dx, Anchor::RightCenter)], label, color);
        return;
    }
    let u = d / len;
    let side = Vec2::new(u.y, -u.x);
    let (tail, tip) = (a + u * (4.0 * k).min(len * 0.2), b - u * (3.0 * k).min(len * 0.2));
    let head = (11.0 * k).min(len * 0.4);
    let base = tip - u * head;
    let halo_head = [tip + u * k, base + side * (head * 0.5 + k), base - side * (head * 0.5 + k)];
    out.push(Prim::Line { a: tail, b: base, width: 4.5 * k, color: HALO });
    out.push(Prim::Triangle { p: halo_head, color: HALO });
    out.push(Prim::Line { a: tail, b: base, width: 2.5 * k, color });
    out.push(Prim::Triangle { p: [tip, base + side * head * 0.45, base - side * head * 0.45], color });
    let off = side * (10.0 * k);
    let spots: Vec<(Vec2, Anchor)> = [0.5, 0.7, 0.35, 0.85]
        .map(|t| a + d * t)
        .into_iter()
        .flat_map(|m| [(m + off, Anchor::Center), (m - off, Anchor::Center)])
        .collect();
    labels.place(&spots, label, color);
}

/// Draws `prims` into `img` (alpha-blended, anti-aliased over about a
/// pixel); text in the pixel font, `2 scale` pixels per font pixel.
pub fn paint(img: &mut RgbaImage, prims: &[Prim], scale: f32) {
    for p in prims {
        match p {
            Prim::Line { a, b, width, color } => {
                let r = width * 0.5;
                fill(img, a.min(*b) - Vec2::splat(r + 1.0), a.max(*b) + Vec2::splat(r + 1.0), *color, |q| {
                    r + 0.5 - distance_to_segment(q, *a, *b)
                });
            }
            Prim::Triangle { p, color } => {
                let (lo, hi) = (p[0].min(p[1]).min(p[2]), p[0].max(p[1]).max(p[2]));
                fill(img, lo, hi, *color, |q| inside_triangle(q, p));
            }
            Prim::Circle { c, r, color } => {
                fill(img, *c - Vec2::splat(r + 1.0), *c + Vec2::splat(r + 1.0), *color, |q| r + 0.5 - q.distance(*c));
            }
            Prim::CircleStroke { c, r, width, color } => {
                let out = r + width * 0.5 + 1.0;
                fill(img, *c - Vec2::splat(out), *c + Vec2::splat(out), *color, |q| {
                    width * 0.5 + 0.5 - (q.distance(*c) - r).abs()
                });
            }
            Prim::Text { at, anchor, text, color } => label(img, *at, *anchor, text, *color, scale),
        }
    }
}

/// The size in image pixels of `text` in the pixel font at `scale`.
pub(crate) fn text_size(text: &str, scale: f32) -> Vec2 {
    let s = font_scale(scale) as f32;
    Vec2::new((text.chars().count() as f32 * 4.0 - 1.0).max(0.0) * s, 5.0 * s)
}

fn font_scale(scale: f32) -> i64 {
    (2.0 * scale).round().max(1.0) as i64
}

/// `text` in capitals on a dark box.
fn label(img: &mut RgbaImage, at: Vec2, anchor: Anchor, text: &str, color: Rgba8, scale: f32) {
    let text = text.to_uppercase();
    let size = text_size(&text, scale);
    let min = match anchor {
        Anchor::LeftCenter => at - Vec2::new(0.0, size.y * 0.5),
        Anchor::RightCenter => at - Vec2::new(size.x, size.y * 0.5),
        Anchor::Center => at - size * 0.5,
        Anchor::LeftTop => at,
    }
    .round();
    let pad = font_scale(scale) as f32 * 1.5;
    fill(img, min - Vec2::splat(pad), min + size + Vec2::splat(pad), [12, 12, 16, 170], |_| 1.0);
    let ink = Rgba([color[0], color[1], color[2], 255]);
    text_from(img, &text, (min.x as i64, min.y as i64), font_scale(scale), ink);
}

/// Blends `color` into the pixels of the box `lo..hi` with the coverage
/// `cover(pixel centre)` clamped to 0..1.
fn fill(img: &mut RgbaImage, lo: Vec2, hi: Vec2, color: Rgba8, cover: impl Fn(Vec2) -> f32) {
    let (w, h) = (img.width() as f32, img.height() as f32);
    let (x0, y0) = (lo.x.floor().max(0.0) as u32, lo.y.floor().max(0.0) as u32);
    let (x1, y1) = (hi.x.ceil().min(w) as u32, hi.y.ceil().min(h) as u32);
    for y in y0..y1 {
        for x in x0..x1 {
            let a = cover(Vec2::new(x as f32 + 0.5, y as f32 + 0.5)).clamp(0.0, 1.0) * f32::from(color[3]) / 255.0;
            if a > 0.0 {
                blend(img.get_pixel_mut(x, y), color, a);
            }
        }
    }
}

fn blend(px: &mut Rgba<u8>, color: Rgba8, a: f32) {
    for (p, &c) in px.0.iter_mut().zip(&color).take(3) {
        *p = (f32::from(c) * a + f32::from(*p) * (1.0 - a)).round() as u8;
    }
    px.0[3] = (255.0 * a + f32::from(px.0[3]) * (1.0 - a)).round() as u8;
}

fn distance_to_segment(q: Vec2, a: Vec2, b: Vec2) -> f32 {
    let d = b - a;
    let s = ((q - a).dot(d) / d.length_squared().max(1e-12)).clamp(0.0, 1.0);
    (a + d * s).distance(q)
}

/// How far `q` is inside the triangle `p` (either orientation), in pixels
/// from its nearest side, plus half a pixel: the coverage's ramp.
fn inside_triangle(q: Vec2, p: &[Vec2; 3]) -> f32 {
    let area = (p[1] - p[0]).perp_dot(p[2] - p[0]);
    let sign = if area < 0.0 { -1.0 } else { 1.0 };
    (0..3)
        .map(|i| {
            let (a, b) = (p[i], p[(i + 1) % 3]);
            sign * (b - a).perp_dot(q - a) / (b - a).length().max(1e-6)
        })
        .fold(f32::MAX, f32::min)
        + 0.5
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lit(img: &RgbaImage, x: u32, y: u32) -> bool {
        img.get_pixel(x, y).0[..3] != [0, 0, 0]
    }

    #[test]
    fn lines_triangles_circles_and_text_cover_their_pixels_only() {
        let mut img = RgbaImage::from_pixel(100, 60, Rgba([0, 0, 0, 255]));
        let red = [255, 0, 0, 255];
        let prims = [
            Prim::Line { a: Vec2::new(10.0, 10.0), b: Vec2::new(50.0, 10.0), width: 3.0, color: red },
            Prim::Circle { c: Vec2::new(80.0, 40.0), r: 5.0, color: red },
            Prim::Triangle { p: [Vec2::new(10.0, 50.0), Vec2::new(30.0, 50.0), Vec2::new(10.0, 30.0)], color: red },
        ];
        paint(&mut img, &prims, 1.0);
        assert_eq!(img.get_pixel(30, 10).0, [255, 0, 0, 255]);
        assert!(!lit(&img, 30, 14) && !lit(&img, 55, 10));
        assert_eq!(img.get_pixel(80, 40).0, [255, 0, 0, 255]);
        assert!(!lit(&img, 80, 47));
        assert!(lit(&img, 13, 46) && !lit(&img, 28, 33));
        let text = Prim::Text { at: Vec2::new(60.0, 5.0), anchor: Anchor::LeftTop, text: "o 27".into(), color: red };
        paint(&mut img, &[text], 1.0);
        let red_px = (60..100)
            .flat_map(|x| (5..15).map(move |y| (x, y)))
            .filter(|&(x, y)| img.get_pixel(x, y).0 == [255, 0, 0, 255]);
        assert!(red_px.count() > 15, "the glyphs are drawn");
    }

    #[test]
    fn an_arrow_has_a_head_at_its_target_and_its_label_beside_it() {
        let vp = Viewport::image(200, 100, 1.0);
        let (mut out, mut labels) = (Vec::new(), Labels::new(&vp));
        let (a, b, ink) = (Vec2::new(0.0, 50.0), Vec2::new(100.0, 50.0), [1, 2, 3, 255]);
        arrow(&mut out, &mut labels, (a, b), ink, "n 5");
        let heads: Vec<Vec2> =
            out.iter().filter_map(|p| if let Prim::Triangle { p, .. } = p { Some(p[0]) } else { None }).collect();
        assert!(heads.iter().any(|t| (t.x - 97.0).abs() < 1.0), "{heads:?}");
        let spot = |l: &Labels, name: &str| {
            l.placed.iter().find_map(|p| match p {
                Prim::Text { at, text, .. } if text == name => Some(*at),
                _ => None,
            })
        };
        assert!((spot(&labels, "n 5").unwrap().x - 50.0).abs() < 1.0, "beside the middle");
        // a second arrow along the same line puts its label elsewhere
        arrow(&mut out, &mut labels, (a, b), ink, "p 3");
        let (n, p) = (labels.taken[0], labels.taken[1]);
        assert!(n.1.x <= p.0.x || p.1.x <= n.0.x || n.1.y <= p.0.y || p.1.y <= n.0.y, "{n:?} {p:?} overlap");
        let before = out.len();
        arrow(&mut out, &mut labels, (Vec2::ZERO, Vec2::new(2.0, 0.0)), ink, "o 1");
        assert_eq!((out.len(), labels.placed.len()), (before, 3), "too short for an arrow: the label alone");
    }
}
