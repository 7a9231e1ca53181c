//! What the inspector draws, in one place for the viewer's Inspect mode and
//! `subdiv render --corner C | --stencil V`: the marks of a corner's
//! operators and of a refined vertex's stencil (drawn by [`super::overlay`]).
//!
//! ```text
//! corner     the picked corner's face outlined, the corner a white dot at its corner point, each operator
//!            an arrow to its target's corner point, labelled `o 27`; a corner
//!            point lies inside its face near its vertex: v + 0.45 (centroid - v)
//!            (0.7 v + 0.15 of the other two in a triangle)
//! stencil    each control vertex of the stencil a disc, radius by |weight|,
//!            colour by sign (the diverging map: red positive, blue negative),
//!            its weight beside it (a dyadic fraction when it is one); the
//!            refined vertex a ring; the caption names the rule of each level
//!            (without its weights: `rule_short`)
//! ```
//! The facts come from the library ([`crate::mesh::inspect::corner_ops`],
//! [`crate::mesh::inspect::poly_corner_ops`], `crate::subdiv::stencil`);
//! this only places them.

use super::overlay::{Mark, Overlay, Rgba8};
use crate::mesh::inspect::{CornerOps, PolyCornerOps};
use crate::mesh::poly::PolyTable;
use crate::subdiv::stencil::Stencil;
use glam::Vec3;

/// The picked corner's dot.
pub(crate) const PICKED: Rgba8 = [255, 255, 255, 255];
/// The refined vertex's ring and the split's outline.
pub(crate) const ACCENT: Rgba8 = [255, 200, 40, 255];

/// The colour of an operator's arrow (`n p o l r s u`, and the polygon
/// table's `next prev twin swing`).
pub fn op_color(name: &str) -> Rgba8 {
    match name {
        "n" | "next" => [255, 160, 40, 255],
        "p" | "prev" => [190, 130, 255, 255],
        "o" | "twin" => [255, 80, 80, 255],
        "l" => [70, 200, 255, 255],
        "r" => [90, 225, 120, 255],
        "s" | "swing" => [255, 230, 60, 255],
        "u" => [255, 120, 200, 255],
        _ => [220, 220, 220, 255],
    }
}

/// The point standing for a corner at `vertex` of a face with the vertex
/// positions `face`: `vertex + 0.45 (centroid - vertex)`.
pub(crate) fn corner_point(vertex: Vec3, face: &[Vec3]) -> Vec3 {
    let centroid = face.iter().copied().sum::<Vec3>() / face.len().max(1) as f32;
    vertex + 0.45 * (centroid - vertex)
}

/// The corner point of triangle corner `c` (V table `v_table`).
pub fn triangle_corner_point(v_table: &[u32], positions: &[Vec3], c: u32) -> Vec3 {
    let t = 3 * (c / 3) as usize;
    let face = [0, 1, 2].map(|i| positions[v_table[t + i] as usize]);
    corner_point(positions[v_table[c as usize] as usize], &face)
}

/// The corner point of polygon corner `c` of `pt`.
pub fn polygon_corner_point(pt: &PolyTable, positions: &[Vec3], c: u32) -> Vec3 {
    let face: Vec<Vec3> = pt.face_corners(pt.face(c)).map(|k| positions[pt.vtx(k) as usize]).collect();
    corner_point(positions[pt.vtx(c) as usize], &face)
}

/// The triangle table's operators as rows: `n p o l r s u` and their
/// targets (`None` across a border).
pub(crate) fn corner_rows(x: &CornerOps) -> Vec<(&'static str, Option<u32>)> {
    vec![("n", Some(x.n)), ("p", Some(x.p)), ("o", x.o), ("l", x.l), ("r", x.r), ("s", x.s), ("u", x.u)]
}

/// The polygon table's operators as rows: `next prev twin swing`.
pub(crate) fn poly_corner_rows(x: &PolyCornerOps) -> Vec<(&'static str, Option<u32>)> {
    vec![("next", Some(x.next)), ("prev", Some(x.prev)), ("twin", x.twin), ("swing", x.swing)]
}

/// The operators of corner `x` of a triangle table (`v_table`, the shown
/// positions) as arrows.
pub fn triangle_corner_overlay(v_table: &[u32], positions: &[Vec3], x: &CornerOps) -> Overlay {
    let title = format!("corner {} of triangle {} (vertex {})", x.corner, x.triangle, x.vertex);
    let face: Vec<Vec3> = (0..3).map(|i| positions[v_table[(3 * x.triangle + i) as usize] as usize]).collect();
    corner_overlay((x.corner, &face), title, &corner_rows(x), |c| triangle_corner_point(v_table, positions, c))
}

/// The operators of corner `x` of a polygon table as arrows.
pub fn poly_corner_overlay(pt: &PolyTable, positions: &[Vec3], x: &PolyCornerOps) -> Overlay {
    let title = format!("corner {} of face {} (vertex {})", x.corner, x.face, x.vertex);
    let face: Vec<Vec3> = pt.face_corners(x.face).map(|c| positions[pt.vtx(c) as usize]).collect();
    corner_overlay((x.corner, &face), title, &poly_corner_rows(x), |c| polygon_corner_point(pt, positions, c))
}

/// The picked corner's face outlined, its dot, an arrow per operator.
fn corner_overlay(
    (corner, face): (u32, &[Vec3]),
    title: String,
    rows: &[(&str, Option<u32>)],
    at: impl Fn(u32) -> Vec3,
) -> Overlay {
    let from = at(corner);
    let outline = (0..face.len()).map(|i| Mark::Segment {
        a: face[i],
        b: face[(i + 1) % face.len()],
        color: [255, 255, 255, 150],
        width: 1.5,
    });
    let mut marks: Vec<Mark> = outline.collect();
    marks.extend(rows.iter().filter_map(|&(name, target)| {
        let t = target?;
        Some(Mark::Arrow { from, to: at(t), color: op_color(name), label: format!("{name} {t}") })
    }));
    marks.push(Mark::Disc { at: from, radius: 5.0, color: PICKED, label: Some(format!("c {corner}")) });
    let border: Vec<&str> = rows.iter().filter(|r| r.1.is_none()).map(|r| r.0).collect();
    let mut caption = vec![title];
    if !border.is_empty() {
        caption.push(format!("across a border: {}", border.join(", ")));
    }
    Overlay { marks, caption }
}

/// `w` as a fraction `k/2^m` when it is one with `2^m <= 4096`, else in
/// four decimals (`43/128`, `-1/16`, `0.2143`).
pub(crate) fn weight_text(w: f64) -> String {
    for m in 0..=12 {
        let d = f64::from(1u32 << m);
        let k = w * d;
        if k == k.round() && k.abs() < 1e9 {
            return if m == 0 { format!("{k}") } else { format!("{k}/{}", 1u32 << m) };
        }
    }
    format!("{w:.4}")
}

/// The name of a rule without its parenthesis (`interior edge` of
/// `interior edge (3/8 its ends, ...)`).
pub(crate) fn rule_short(rule: &str) -> &str {
    rule.split(" (").next().unwrap_or(rule)
}

/// The colour of weight `w` of a stencil whose largest weight magnitude
/// is `max`: the curvature colours' diverging map, red positive, blue
/// negative, pale near zero.
pub fn weight_color(w: f64, max: f64) -> Rgba8 {
    let t = if max > 0.0 { (w / max) as f32 } else { 0.0 };
    let c = crate::subdiv::eval::color::diverging(t.signum() * (0.35 + 0.65 * t.abs()));
    let s = |x: f32| {
        let s = if x <= 0.003_130_8 { 12.92 * x } else { 1.055 * x.powf(1.0 / 2.4) - 0.055 };
        (s.clamp(0.0, 1.0) * 255.0).round() as u8
    };
    [s(c.x), s(c.y), s(c.z), 255]
}

/// The radius in pixels of a disc of weight `w` (largest magnitude `max`):
/// 3 to 14 pixels by the square root of `|w| / max`, so that the area
/// follows the weight.
pub(crate) fn weight_radius(w: f64, max: f64) -> f32 {
    3.0 + 11.0 * if max > 0.0 { (w.abs() / max).sqrt() as f32 } else { 0.0 }
}

/// The stencil `st` drawn on the control mesh (`control`: its positions):
/// a disc per control vertex with its weight, the refined vertex (drawn at
/// `at`) ringed and labelled, the rules in the caption.
pub fn stencil_overlay(control: &[Vec3], st: &Stencil, at: Vec3) -> Overlay {
    let max = st.weights.iter().fold(0.0f64, |m, w| m.max(w.1.abs()));
    let mut order: Vec<&(u32, f64)> = st.weights.iter().collect();
    // the big discs first, so the small ones stay visible on top
    order.sort_by(|a, b| b.1.abs().total_cmp(&a.1.abs()));
    let mut marks: Vec<Mark> = order
        .iter()
        .map(|&&(j, w)| Mark::Disc {
            at: control[j as usize],
            radius: weight_radius(w, max),
            color: weight_color(w, max),
            label: Some(format!("{j}: {}", weight_text(w))),
        })
        .collect();
    marks.push(Mark::Ring { at, radius: 9.0, color: ACCENT });
    marks.push(Mark::Disc { at, radius: 3.0, color: ACCENT, label: Some(format!("v{}", st.vertex)) });
    let sum: f64 = st.weights.iter().map(|w| w.1).sum();
    let mut caption = vec![
        format!("vertex {} of {} level {}", st.vertex, st.scheme, st.level),
        format!("{} control vertices, weights sum {}", st.weights.len(), weight_text(sum)),
    ];
    // the rules by name (their weights are the panel's and `info --stencil`'s)
    caption.extend(st.rules.iter().map(|(l, r)| format!("level {l}: {}", rule_short(r))));
    Overlay { marks, caption }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_read_as_dyadic_fractions_when_they_are() {
        assert_eq!(weight_text(0.3359375), "43/128");
        assert_eq!(weight_text(-0.0625), "-1/16");
        assert_eq!(weight_text(1.0), "1");
        assert_eq!(weight_text(3.0 / 14.0), "0.2143");
    }

    #[test]
    fn a_corner_point_lies_inside_its_triangle_near_its_vertex() {
        let (a, b, c) = (Vec3::ZERO, Vec3::X, Vec3::Y);
        let p = corner_point(a, &[a, b, c]);
        assert!((p - Vec3::new(0.15, 0.15, 0.0)).length() < 1e-6, "{p}");
    }

    #[test]
    fn signs_colour_and_magnitudes_size_the_discs() {
        let (pos, neg) = (weight_color(0.5, 0.5), weight_color(-0.1, 0.5));
        assert!(pos[0] > pos[2] + 80 && neg[2] > neg[0] + 40, "{pos:?} {neg:?}");
        assert!(weight_radius(0.5, 0.5) > weight_radius(-0.1, 0.5));
        assert_eq!(rule_short("interior edge (3/8 its ends)"), "interior edge");
    }
}
