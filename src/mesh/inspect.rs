//! Per-vertex inspection values for a refined mesh: the level that created
//! each vertex, its displacement from the control mesh's piecewise-linear
//! surface, and a perceptual colour ramp to show either.
//!
//! Vertex numbering through a 1-to-4 split ([`crate::mesh::split`]): old
//! vertices keep their ids and the vertex on edge `e` gets id `V + e`
//! (`V` = the old vertex count). So after levels `1..=L` the ids are layered:
//! `0 .. V_0` are the control vertices, `V_0 .. V_1` were created by level 1,
//! and so on, where `V_{l+1} = V_l + E_l`, `E_{l+1} = 2 E_l + 3 F_l`,
//! `F_{l+1} = 4 F_l` (docs/schemes.md §1; `E` counts border edges once). Every
//! scheme uses the same split, so this holds for all of them.

use super::{CornerTable, Mesh};
use crate::{Error, Result};
use glam::Vec3;

/// Vertex counts `[V_0, V_1, ..., V_levels]` of `levels` 1-to-4 splits of
/// `ct`, predicted from `V' = V + E`, `E' = 2E + 3F`, `F' = 4F` (saturating).
pub fn vertex_counts_per_level(ct: &CornerTable, levels: u32) -> Vec<usize> {
    let mut c = super::counts::Counts::of_triangles(ct);
    let mut out = vec![c.vertices as usize];
    for _ in 0..levels {
        c = c.triangle_split();
        out.push(usize::try_from(c.vertices).unwrap_or(usize::MAX));
    }
    out
}

/// The level that created each of the `nv` vertices, given the vertex count
/// after each level, `nv_per_level = [V_0, V_1, ...]` (increasing; see
/// [`vertex_counts_per_level`]): vertex `i` gets the smallest `l` with
/// `i < V_l` (0 = control vertex). Ids beyond the last count get
/// `nv_per_level.len()`; levels saturate at 255.
pub fn vertex_creation_level(nv_per_level: &[usize], nv: usize) -> Vec<u8> {
    (0..nv).map(|i| nv_per_level.partition_point(|&c| c <= i).min(255) as u8).collect()
}

/// Distance of each vertex of `fine` from the corresponding point of the
/// control mesh's piecewise-linear surface: `|fine_i - mid_i|`, where `mid`
/// is `control` refined `levels` times by midpoint subdivision. Midpoint
/// points lie on the control triangles and every scheme uses the same split,
/// so `mid_i` is the point of the control surface that vertex `i` comes from
/// (with the same parameter): the value is the scheme's displacement, an upper
/// bound on the distance to the nearest point of the control surface.
///
/// # Errors
/// [`Error::CountMismatch`] when `fine` does not have the vertex and
/// triangle counts of `control` refined `levels` times.
pub fn displacement_from_control(control: &Mesh, fine: &Mesh, levels: u32) -> Result<Vec<f32>> {
    let want = vertex_counts_per_level(&control.ct, levels).last().copied().unwrap_or(0);
    if fine.positions.len() != want || fine.ct.num_triangles() != control.ct.num_triangles() << (2 * levels.min(15)) {
        return Err(Error::CountMismatch {
            what: format!(
                "displacement: the fine mesh ({} triangles) against {levels} levels of the control mesh",
                fine.ct.num_triangles()
            ),
            unit: "vertices",
            expected: want,
            found: fine.positions.len(),
        });
    }
    let mid = super::split::refine_linear(control, levels);
    Ok(fine.positions.iter().zip(&mid.positions).map(|(a, b)| a.distance(*b)).collect())
}

/// A perceptual colour ramp (viridis: dark blue, green, yellow) for `t` in
/// `[0, 1]` (clamped; NaN gives 0), as linear-ish sRGB components in `[0, 1]`.
///
/// A degree-6 polynomial fit of matplotlib's viridis table by Matt Zucker
/// ("mattz", CC0, <https://www.shadertoy.com/view/WlfXRN>), evaluated by
/// Horner's rule: `c0 + t (c1 + t (c2 + ... + t c6))`, coefficients below;
/// it stays within 0.02 of the table (unit test) and its luminance increases
/// monotonically.
pub fn colormap(t: f32) -> [f32; 3] {
    const C: [Vec3; 7] = [
        Vec3::new(0.277_727_33, 0.005_407_344_5, 0.334_099_8),
        Vec3::new(0.105_093_04, 1.404_613_5, 1.384_590_2),
        Vec3::new(-0.330_861_83, 0.214_847_56, 0.095_095_16),
        Vec3::new(-4.634_230_5, -5.799_101, -19.332_441),
        Vec3::new(6.228_27, 14.179_933, 56.690_55),
        Vec3::new(4.776_385, -13.745_145, -65.353_035),
        Vec3::new(-5.435_456, 4.645_852_6, 26.312_435),
    ];
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let c = C.iter().rev().fold(Vec3::ZERO, |acc, &k| acc * t + k);
    c.clamp(Vec3::ZERO, Vec3::ONE).to_array()
}

/// Rossignac's operators at corner `c` of a triangle table (`src/mesh`'s
/// definitions: `n`, `p` next and previous in the triangle, `o` across the
/// opposite edge, `l = o(n)`, `r = o(p)`, `s = n(o(n))` the swing, `u =
/// p(o(p))` the unswing); `None` across a border.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CornerOps {
    /// The corner.
    pub corner: u32,
    /// Its triangle, `c / 3`.
    pub triangle: u32,
    /// Its vertex.
    pub vertex: u32,
    /// The next corner of the triangle.
    pub n: u32,
    /// The previous corner of the triangle.
    pub p: u32,
    /// The opposite corner.
    pub o: Option<u32>,
    /// The left neighbour `o(n)`.
    pub l: Option<u32>,
    /// The right neighbour `o(p)`.
    pub r: Option<u32>,
    /// The swing `n(o(n))`.
    pub s: Option<u32>,
    /// The unswing `p(o(p))`.
    pub u: Option<u32>,
}

/// The operators at corner `c` of `ct`, `None` for a corner out of range.
pub fn corner_ops(ct: &CornerTable, c: u32) -> Option<CornerOps> {
    ((c as usize) < ct.num_corners()).then(|| CornerOps {
        corner: c,
        triangle: c / 3,
        vertex: ct.vtx(c),
        n: super::n(c),
        p: super::p(c),
        o: ct.o(c),
        l: ct.l(c),
        r: ct.r(c),
        s: ct.s(c),
        u: ct.u(c),
    })
}

/// The polygon table's operators at corner `c`: its face, vertex, the
/// next and previous corners of the face, the twin (the corner across the
/// edge leaving `c`, at its other end) and the swing (the next corner around
/// the vertex, across the edge entering `c`); `None` across a border.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PolyCornerOps {
    /// The corner.
    pub corner: u32,
    /// Its face.
    pub face: u32,
    /// Its vertex.
    pub vertex: u32,
    /// The next corner of the face.
    pub next: u32,
    /// The previous corner of the face.
    pub prev: u32,
    /// The twin.
    pub twin: Option<u32>,
    /// The swing.
    pub swing: Option<u32>,
}

/// The operators at corner `c` of `pt`, `None` for a corner out of range.
pub fn poly_corner_ops(pt: &super::poly::PolyTable, c: u32) -> Option<PolyCornerOps> {
    ((c as usize) < pt.num_corners()).then(|| PolyCornerOps {
        corner: c,
        face: pt.face(c),
        vertex: pt.vtx(c),
        next: pt.next(c),
        prev: pt.prev(c),
        twin: pt.twin(c),
        swing: pt.swing(c),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn creation_levels_from_counts() {
        assert_eq!(vertex_creation_level(&[3, 6, 15], 15), vec![0, 0, 0, 1, 1, 1, 2, 2, 2, 2, 2, 2, 2, 2, 2]);
        assert_eq!(vertex_creation_level(&[2], 4), vec![0, 0, 1, 1]);
        assert!(vertex_creation_level(&[], 3).iter().all(|&l| l == 0));
    }

    #[test]
    fn colormap_matches_viridis_table() {
        // matplotlib viridis at 0, 0.25, 0.5, 0.75, 1
        let table = [
            (0.0, [0.267_004, 0.004_874, 0.329_415]),
            (0.25, [0.229_739, 0.322_361, 0.545_706]),
            (0.5, [0.127_568, 0.566_949, 0.550_556]),
            (0.75, [0.369_214, 0.788_888, 0.382_914]),
            (1.0, [0.993_248, 0.906_157, 0.143_936]),
        ];
        for (t, want) in table {
            let got = colormap(t);
            for k in 0..3 {
                assert!((got[k] - want[k]).abs() < 0.02, "t = {t}: {got:?} vs {want:?}");
            }
        }
        assert_eq!(colormap(f32::NAN), colormap(0.0));
        assert_eq!(colormap(-3.0), colormap(0.0));
        assert_eq!(colormap(7.0), colormap(1.0));
    }

    #[test]
    fn colormap_luminance_increases() {
        // perceptual ramp: Rec. 709 luminance strictly increasing
        let lum = |c: [f32; 3]| 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
        let mut prev = -1.0;
        for i in 0..=100 {
            let l = lum(colormap(i as f32 / 100.0));
            assert!(l > prev, "luminance not increasing at {i}");
            prev = l;
        }
    }
}
