//! Where a face of a refined level lies in the control mesh: its control
//! face and the parameters of its corners there. Pure topology: the splits
//! number their children by formula, so the way back is arithmetic, with
//! no table kept per level.
//!
//! The 1-to-4 split of triangles ([`super::split`]), `nt` triangles before
//! it: the central child keeps its parent's id `t`, its corners the midpoints
//! of the edges opposite the parent's corners 0, 1, 2; the child at corner
//! `j` is `nt (j + 1) + t`, corners `(c_j, mid(c_j, c_j+1), mid(c_j, c_j+2))`.
//! Going up one level: `t < nt` is the central child of `t`, else
//! `j = t / nt - 1` and the parent is `t % nt`. A control triangle's
//! parameters are `c0 = (0, 0)`, `c1 = (1, 0)`, `c2 = (0, 1)` (the point
//! `(1 - u - v) c0 + u c1 + v c2`).
//!
//! The quad split of polygons ([`super::poly::split`]): old corner `c`
//! becomes quad `c`, so from level 1 on a level's quads are its parent's
//! corners, and a quad mesh's corner `c` lies in face `c / 4`; drawn as
//! triangles ([`super::poly::PolyTable::triangulated`]), quad `q` is
//! triangles `2q` and `2q + 1`.

/// The parameters of a control triangle's corners.
pub(crate) const CONTROL_CORNERS: [[f64; 2]; 3] = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];

/// Triangle `t` of level `levels` of the 1-to-4 split of a table of
/// `control_faces` triangles: its control triangle and the `(u, v)` of its
/// three corners there, in its own corner order; `None` when there is no
/// such triangle.
pub(crate) fn triangle_origin(t: u32, control_faces: usize, levels: u32) -> Option<(u32, [[f64; 2]; 3])> {
    let mut nt = u64::try_from(control_faces).ok()?.checked_mul(1u64.checked_shl(2 * levels)?)?;
    let mut t = u64::from(t);
    if t >= nt {
        return None;
    }
    // the child taken at each level, finest first: 3 central, j corner j
    let mut path = Vec::with_capacity(levels as usize);
    for _ in 0..levels {
        nt /= 4;
        path.push(if t < nt { 3 } else { (t / nt - 1) as usize });
        t %= nt;
    }
    let mid = |a: [f64; 2], b: [f64; 2]| [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
    let mut c = CONTROL_CORNERS;
    for &j in path.iter().rev() {
        c = match j {
            3 => [mid(c[1], c[2]), mid(c[2], c[0]), mid(c[0], c[1])],
            j => [c[j], mid(c[j], c[(j + 1) % 3]), mid(c[j], c[(j + 2) % 3])],
        };
    }
    Some((t as u32, c))
}

#[cfg(test)]
/// Triangle `t` of the triangulated level `levels >= 1` of the quad split:
/// the control polygon corner whose level-1 quad holds it (that quad is the
/// part of the control face nearest the corner's vertex).
pub(crate) fn quad_origin(t: u32, levels: u32) -> u32 {
    let mut q = t / 2;
    for _ in 1..levels {
        q /= 4;
    }
    q
}

/// The parameters of a quad's corners: the vertex, the edge leaving it, the
/// face point, the edge entering it (a level-1 quad's corners in the split).
pub(crate) const QUAD_CORNERS: [[f64; 2]; 4] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];

/// The point `(s, t)` of child quad `k` of a quad (the child of its corner
/// `k`) in the parent's parameters: the inverse of the quadrant maps
/// (child `k` covers the parent's quarter at its corner `k`).
pub(crate) fn quad_parent(k: u32, [s, t]: [f64; 2]) -> [f64; 2] {
    match k % 4 {
        0 => [s / 2.0, t / 2.0],
        1 => [1.0 - t / 2.0, s / 2.0],
        2 => [1.0 - s / 2.0, 1.0 - t / 2.0],
        _ => [t / 2.0, 1.0 - s / 2.0],
    }
}

/// The point of barycentrics `(b1, b2)` in triangle `t` of the triangulated
/// level `levels >= 1` of the quad split: the control corner whose level-1
/// quad holds it ([`quad_origin`]) and its `(u, v)` in that quad (corners
/// [`QUAD_CORNERS`]). Quad `q` is drawn as triangles `2q` (corners 0 1 2)
/// and `2q + 1` (corners 0 2 3).
pub(crate) fn quad_point(t: u32, levels: u32, b1: f64, b2: f64) -> (u32, [f64; 2]) {
    let c = QUAD_CORNERS;
    let tri = if t.is_multiple_of(2) { [c[0], c[1], c[2]] } else { [c[0], c[2], c[3]] };
    let (mut q, mut uv) = (t / 2, barycentric(&tri, b1, b2));
    for _ in 1..levels {
        uv = quad_parent(q % 4, uv);
        q /= 4;
    }
    (q, uv)
}

/// The point `(1 - b1 - b2) a + b1 b + b2 c` of the parameters `[a, b, c]`.
pub(crate) fn barycentric(corners: &[[f64; 2]; 3], b1: f64, b2: f64) -> [f64; 2] {
    let b0 = 1.0 - b1 - b2;
    let [a, b, c] = corners;
    [b0 * a[0] + b1 * b[0] + b2 * c[0], b0 * a[1] + b1 * b[1] + b2 * c[1]]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Mesh;
    use crate::mesh::split::refine_linear;
    use glam::Vec3;

    /// Positions that are their own parameters: the control triangle (0,0),
    /// (1,0), (0,1) and a second one, split `levels` times at midpoints, so
    /// each vertex of triangle 0's descendants sits at its `(u, v)`.
    fn midpoint_levels(levels: u32) -> Mesh {
        let pos = vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 0.0)];
        let m = Mesh::from_triangles(pos, &[0, 1, 2, 1, 3, 2]).expect("two triangles");
        refine_linear(&m, levels)
    }

    #[test]
    fn a_triangle_of_any_level_finds_its_corners_parameters() {
        // triangle 0 of the control mesh is (0,0) (1,0) (0,1): its
        // parameters are the positions' x and y
        for levels in 0..4 {
            let m = midpoint_levels(levels);
            for t in 0..m.ct.num_triangles() as u32 {
                let (f, c) = triangle_origin(t, 2, levels).expect("a triangle of the level");
                assert_eq!(f, t % 2, "the control face of triangle {t} at level {levels}");
                if f == 0 {
                    for (k, uv) in c.iter().enumerate() {
                        let p = m.positions[m.ct.vtx(3 * t + k as u32) as usize];
                        assert_eq!([p.x as f64, p.y as f64], *uv, "corner {k} of triangle {t}, level {levels}");
                    }
                }
            }
            assert_eq!(triangle_origin(m.ct.num_triangles() as u32, 2, levels), None);
        }
    }

    #[test]
    fn quads_go_back_to_their_control_corner() {
        // level 1 quad q is corner q; its four level-2 children are 4q..4q+3
        assert_eq!(quad_origin(2 * 7, 1), 7);
        assert_eq!(quad_origin(2 * 7 + 1, 1), 7);
        assert_eq!(quad_origin(2 * (4 * 7 + 3) + 1, 2), 7);
        assert_eq!(quad_origin(2 * (16 * 7 + 9), 3), 7);
    }

    #[test]
    fn barycentric_combines_the_corners() {
        let c = [[0.5, 0.0], [0.5, 0.5], [0.0, 0.5]];
        let [u, v] = barycentric(&c, 1.0 / 3.0, 1.0 / 3.0);
        assert!((u - 1.0 / 3.0).abs() < 1e-15 && (v - 1.0 / 3.0).abs() < 1e-15);
        assert_eq!(barycentric(&CONTROL_CORNERS, 0.25, 0.5), [0.25, 0.5]);
    }
}
