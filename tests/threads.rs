//! The result must not depend on the thread count: every scheme, on a closed
//! and an open mesh big enough that every parallel pass really splits its
//! work (the split's chunks, the ring sums' and the normals' accumulators),
//! gives the same V and O tables, C, valences and the same bits of every
//! position and normal with 1, 2 and 3 threads: a pass that sums in parts
//! cuts them by the size of its input, never by the threads that run it.

mod common;
use common::*;
use glam::Vec3;
use subdiv::{Mesh, Options, Scheme, subdivide};

fn in_pool(threads: usize, m: &Mesh, s: Scheme, levels: u32) -> Mesh {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    pool.install(|| subdivide(m, s, levels, &Options::default()).unwrap().0)
}

/// The first point whose bits differ between two lists, and how many differ.
fn differ(a: &[Vec3], b: &[Vec3]) -> Option<(usize, usize)> {
    let bits = |p: &Vec3| p.to_array().map(f32::to_bits);
    let mut d = a.iter().zip(b).enumerate().filter(|(_, (p, q))| bits(p) != bits(q)).map(|(i, _)| i);
    d.next().map(|first| (first, 1 + d.count()))
}

#[test]
fn same_result_for_any_thread_count() {
    // 20,480 and 2 x 110 x 110 = 24,200 faces: level 2 reads ~250k corners
    let meshes = [
        ("icosphere5", icosphere(5)),
        ("wavy_grid", grid(110, 110, |i, j| Vec3::new(i + 0.3 * j, j, (0.3 * i * j).sin()) / 110.0)),
    ];
    for (name, m) in &meshes {
        for s in Scheme::TRIANGLE {
            let one = in_pool(1, m, s, 2);
            for threads in [2, 3] {
                let many = in_pool(threads, m, s, 2);
                let what = format!("{name} {s} with {threads} threads");
                assert_eq!(one.ct.v_table(), many.ct.v_table(), "V differs: {what}");
                assert_eq!(one.ct.o_table(), many.ct.o_table(), "O differs: {what}");
                assert_eq!(one.ct.c_table(), many.ct.c_table(), "C differs: {what}");
                assert_eq!(one.ct.valences(), many.ct.valences(), "valences differ: {what}");
                assert_eq!(one.positions.len(), many.positions.len(), "{what}");
                assert_eq!(differ(&one.positions, &many.positions), None, "positions (first, count) differ: {what}");
            }
        }
    }
}

#[test]
fn vertex_sums_split_over_threads_agree() {
    // Loop's vertex points scatter the ring sums over threads only from
    // 2^20 corners a level: level 3 of an icosphere of 81,920 faces reads
    // 3.9 M corners
    let m = icosphere(6);
    let one = in_pool(1, &m, Scheme::Loop, 3);
    for threads in [2, 3] {
        let many = in_pool(threads, &m, Scheme::Loop, 3);
        assert_eq!(one.ct.v_table(), many.ct.v_table());
        let d = differ(&one.positions, &many.positions);
        assert_eq!(d, None, "positions (first, count) differ with {threads} threads");
        let normals = |m: &Mesh| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| m.vertex_normals())
        };
        let n1 = {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
            pool.install(|| one.vertex_normals())
        };
        assert_eq!(differ(&n1, &normals(&many)), None, "normals (first, count) differ with {threads} threads");
    }
}

#[test]
fn catmull_clark_is_the_same_on_any_thread_count() {
    // a wavy 120 x 120 grid of quads, and the same grid cut into triangles
    // (the first level's polygon path): level 2 reads 230 k corners (the
    // triangles' level 0 already 86 k), which the vertex points scatter over
    // two parts
    let n = 120u32;
    let positions: Vec<Vec3> = (0..=n)
        .flat_map(|j| (0..=n).map(move |i| Vec3::new(i as f32, j as f32, (0.3 * (i * j) as f32).sin()) / n as f32))
        .collect();
    let at = |i: u32, j: u32| j * (n + 1) + i;
    let quads: Vec<u32> = (0..n)
        .flat_map(|j| (0..n).flat_map(move |i| [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]))
        .collect();
    let triangles: Vec<u32> = quads.chunks(4).flat_map(|q| [q[0], q[1], q[2], q[0], q[2], q[3]]).collect();
    for (corners, k) in [(quads, 4), (triangles, 3)] {
        let starts: Vec<u32> = (0..=corners.len() as u32 / k).map(|f| k * f).collect();
        let (m, _) = subdiv::mesh::PolyMesh::from_faces(positions.clone(), &starts, &corners).unwrap();
        let run = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| subdiv::subdivide(&m, Scheme::CatmullClark, 2, &Options::default()).unwrap().0)
        };
        let one = run(1);
        for threads in [2, 3] {
            let many = run(threads);
            assert_eq!(one.pt.v_table(), many.pt.v_table(), "faces of {k}, {threads} threads");
            let d = differ(&one.positions, &many.positions);
            assert_eq!(d, None, "faces of {k}: positions (first, count) differ with {threads} threads");
        }
    }
}
