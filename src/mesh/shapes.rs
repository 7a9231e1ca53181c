//! Generated meshes for benchmarks, examples and the viewer: icosphere and
//! planar grid.

use super::Mesh;
use glam::Vec3;

/// Regular icosahedron on the unit sphere.
pub(crate) fn icosahedron() -> Mesh {
    let t = (1.0 + 5f32.sqrt()) / 2.0;
    let pos: Vec<Vec3> = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| Vec3::new(x, y, z).normalize())
    .collect();
    let tris = [
        0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3, 9, 4, 3,
        4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1,
    ];
    // the table above is a valid closed manifold: proven by the unit test below
    Mesh::from_triangles(pos, &tris).unwrap_or_default()
}

/// Icosahedron refined `levels` times by midpoint split, each level projected
/// onto the unit sphere (`20 * 4^levels` triangles).
pub fn icosphere(levels: u32) -> Mesh {
    let mut m = icosahedron();
    for _ in 0..levels {
        let mut f = super::split::split_linear(&m);
        for p in &mut f.positions {
            *p = p.normalize();
        }
        m = f;
    }
    m
}

#[cfg(test)]
/// A planar `n x n` grid of unit squares, each cut along the same diagonal.
pub(crate) fn grid(n: usize) -> Mesh {
    let n = n.max(1);
    let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let pos = (0..=n).flat_map(|j| (0..=n).map(move |i| Vec3::new(i as f32, j as f32, 0.0))).collect();
    let mut tris = Vec::with_capacity(6 * n * n);
    for j in 0..n {
        for i in 0..n {
            tris.extend_from_slice(&[
                id(i, j),
                id(i + 1, j),
                id(i + 1, j + 1),
                id(i, j),
                id(i + 1, j + 1),
                id(i, j + 1),
            ]);
        }
    }
    Mesh::from_triangles(pos, &tris).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn shapes_are_valid() {
        let ico = icosahedron();
        assert_eq!((ico.positions.len(), ico.ct.num_triangles()), (12, 20));
        assert!(ico.ct.valences().iter().all(|&k| k == 5));
        assert_eq!(icosphere(2).ct.num_triangles(), 320);
        assert_eq!(grid(3).ct.num_triangles(), 18);
    }
}
