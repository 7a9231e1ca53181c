//! Mesh generators shared by the integration tests (everything is generated
//! or bundled in `models/`; nothing outside the repository is needed).
#![allow(dead_code)]

use glam::Vec3;
use std::path::PathBuf;
use subdiv::Mesh;

/// A fresh directory for one test's files: `name`, the process id and the
/// time the process first asked keep tests and runs apart (a process id
/// alone comes back in a later run, with that run's files still there).
pub fn scratch_dir(name: &str) -> PathBuf {
    static RUN: std::sync::OnceLock<u128> = std::sync::OnceLock::new();
    let run = RUN
        .get_or_init(|| std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_nanos()));
    let d = std::env::temp_dir().join(format!("subdiv-{name}-{}-{run}", std::process::id()));
    std::fs::create_dir_all(&d).expect("temporary directory");
    d
}

/// An offscreen renderer, or `None` (with a SKIPPED line) when no GPU
/// adapter exists and `SUBDIV_REQUIRE_GPU` is unset; with it set (as in CI)
/// a missing adapter fails the test.
#[cfg(feature = "viewer")]
pub fn offscreen(w: u32, h: u32) -> Option<subdiv::render::Offscreen> {
    or_skip(subdiv::render::Offscreen::new(w, h))
}

/// [`offscreen`] with `samples` MSAA samples (see `Offscreen::with_samples`).
#[cfg(feature = "viewer")]
pub fn offscreen_with_samples(w: u32, h: u32, samples: u32) -> Option<subdiv::render::Offscreen> {
    or_skip(subdiv::render::Offscreen::with_samples(w, h, samples))
}

#[cfg(feature = "viewer")]
fn or_skip(made: subdiv::Result<subdiv::render::Offscreen>) -> Option<subdiv::render::Offscreen> {
    match made {
        Ok(o) => Some(o),
        Err(e) if std::env::var_os("SUBDIV_REQUIRE_GPU").is_none() => {
            eprintln!("SKIPPED: no GPU adapter ({e}); set SUBDIV_REQUIRE_GPU=1 to make this a failure");
            None
        }
        Err(e) => panic!("SUBDIV_REQUIRE_GPU is set but {e}"),
    }
}

/// The share of pixels of `a` and `b` (the same size) whose red, green and
/// blue each differ by at most `tol` levels.
pub fn share_within(a: &image::RgbaImage, b: &image::RgbaImage, tol: u8) -> f64 {
    assert_eq!(a.dimensions(), b.dimensions(), "images of one size");
    let close = a.pixels().zip(b.pixels()).filter(|(p, q)| (0..3).all(|i| p.0[i].abs_diff(q.0[i]) <= tol)).count();
    close as f64 / (a.width() * a.height()).max(1) as f64
}

pub fn model_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("models").join(name)
}

pub fn bundled(name: &str) -> Mesh {
    subdiv::bundled::load(&model_path(name)).expect("bundled model loads")
}

pub const BUNDLED: [&str; 4] = ["tetrahedron.obj", "cube.obj", "torus.obj", "lprism.obj"];

/// An `n x m` grid of squares, each split by the diagonal (i,j)-(i+1,j+1):
/// the affine image of a regular triangular lattice. Vertex (i, j) is
/// `i * (m + 1) + j`... stored row-major with `(m + 1)` columns; position
/// given by `f(i, j)`.
pub fn grid(n: usize, m: usize, f: impl Fn(f32, f32) -> Vec3) -> Mesh {
    let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut pos = Vec::new();
    for j in 0..=m {
        for i in 0..=n {
            pos.push(f(i as f32, j as f32));
        }
    }
    let mut tris = Vec::new();
    for j in 0..m {
        for i in 0..n {
            tris.extend_from_slice(&[id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            tris.extend_from_slice(&[id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    Mesh::from_triangles(pos, &tris).expect("grid is valid")
}

/// Flat grid in the plane z = 0 with unit spacing.
pub fn flat_grid(n: usize) -> Mesh {
    grid(n, n, |i, j| Vec3::new(i, j, 0.0))
}

/// Regular icosahedron (0, +-1, +-phi) and cyclic permutations.
pub fn icosahedron() -> Mesh {
    let t = (1.0 + 5f32.sqrt()) / 2.0;
    let pos = vec![
        Vec3::new(-1.0, t, 0.0),
        Vec3::new(1.0, t, 0.0),
        Vec3::new(-1.0, -t, 0.0),
        Vec3::new(1.0, -t, 0.0),
        Vec3::new(0.0, -1.0, t),
        Vec3::new(0.0, 1.0, t),
        Vec3::new(0.0, -1.0, -t),
        Vec3::new(0.0, 1.0, -t),
        Vec3::new(t, 0.0, -1.0),
        Vec3::new(t, 0.0, 1.0),
        Vec3::new(-t, 0.0, -1.0),
        Vec3::new(-t, 0.0, 1.0),
    ];
    let tris = [
        0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3, 9, 4, 3,
        4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1,
    ];
    Mesh::from_triangles(pos, &tris).expect("icosahedron is valid")
}

/// Icosahedron refined `levels` times by midpoint split, projected to the unit sphere.
pub fn icosphere(levels: u32) -> Mesh {
    let mut m = icosahedron();
    for p in &mut m.positions {
        *p = p.normalize();
    }
    for _ in 0..levels {
        let (mut f, _) = subdiv::subdivide(&m, subdiv::Scheme::Midpoint, 1, &Default::default()).unwrap();
        for p in &mut f.positions {
            *p = p.normalize();
        }
        m = f;
    }
    m
}

/// Upper part of an icosphere (z > -0.15): an open mesh with an irregular boundary.
pub fn hemisphere() -> Mesh {
    let s = icosphere(2);
    let mut tris = Vec::new();
    for tri in s.ct.v_table().chunks_exact(3) {
        if tri.iter().all(|&v| s.positions[v as usize].z > -0.15) {
            tris.extend_from_slice(tri);
        }
    }
    Mesh::from_triangles(s.positions.clone(), &tris).expect("hemisphere is valid")
}

/// An open curved disk: a centre of valence `k` and `rings` rings of `k` vertices.
pub fn disk_fan(k: usize, rings: usize) -> Mesh {
    let mut pos = vec![Vec3::new(0.0, 0.0, 0.3)];
    for r in 1..=rings {
        for i in 0..k {
            let a = std::f32::consts::TAU * (i as f32 + 0.5 * (r % 2) as f32) / k as f32;
            let rad = r as f32 / rings as f32;
            pos.push(Vec3::new(rad * a.cos(), rad * a.sin(), 0.3 * (1.0 - rad * rad)));
        }
    }
    let ring = |r: usize, i: usize| (1 + (r - 1) * k + i % k) as u32;
    let mut tris = Vec::new();
    for i in 0..k {
        tris.extend_from_slice(&[0, ring(1, i), ring(1, i + 1)]);
    }
    for r in 1..rings {
        for i in 0..k {
            if r % 2 == 1 {
                tris.extend_from_slice(&[ring(r, i), ring(r + 1, i), ring(r + 1, i + 1)]);
                tris.extend_from_slice(&[ring(r, i), ring(r + 1, i + 1), ring(r, i + 1)]);
            } else {
                tris.extend_from_slice(&[ring(r, i), ring(r + 1, i), ring(r, i + 1)]);
                tris.extend_from_slice(&[ring(r, i + 1), ring(r + 1, i), ring(r + 1, i + 1)]);
            }
        }
    }
    Mesh::from_triangles(pos, &tris).expect("disk fan is valid")
}

/// Two triangles glued back to back (`f 1 2 3`, `f 1 3 2`): a closed
/// "pillow" whose three vertices are interior with valence 2, the only way
/// an interior vertex of valence 2 can occur in a manifold mesh.
pub fn pillow() -> Mesh {
    Mesh::from_triangles(vec![Vec3::ZERO, Vec3::X, Vec3::Y], &[0, 1, 2, 0, 2, 1]).expect("pillow is valid")
}

/// Regular octahedron: every vertex interior with valence 4.
pub fn octahedron() -> Mesh {
    let pos = vec![Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z];
    let tris = [0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5];
    Mesh::from_triangles(pos, &tris).expect("octahedron is valid")
}

/// Closed meshes with interior vertices of valence 2, 3 and 4, alone and (after
/// one midpoint split) beside regular valence-6 vertices; positions moved off
/// their symmetric places so that no stencil term cancels by accident.
pub fn low_valence_meshes() -> Vec<(String, Mesh)> {
    let mut rng = Rng(0x2545f4914f6cdd1d);
    let mut out = Vec::new();
    for (name, m) in [("pillow", pillow()), ("tetrahedron", bundled("tetrahedron.obj")), ("octahedron", octahedron())] {
        let mut m = m;
        for p in &mut m.positions {
            *p += rng.vec3() * 0.2;
        }
        let split = subdiv::mesh::split_linear(&m);
        out.push((format!("{name} (valence {})", m.ct.valence(0)), m));
        out.push((format!("{name} split once"), split));
    }
    out
}

/// Every test mesh: bundled models plus open ones.
pub fn all_meshes() -> Vec<(String, Mesh)> {
    let mut v: Vec<(String, Mesh)> = BUNDLED.iter().map(|n| (n.to_string(), bundled(n))).collect();
    v.push(("grid".into(), grid(6, 5, |i, j| Vec3::new(i + 0.3 * j, j, 0.1 * (i * j).sin()))));
    v.push(("hemisphere".into(), hemisphere()));
    v.push(("disk_fan".into(), disk_fan(16, 3)));
    v.push(("icosahedron".into(), icosahedron()));
    v.push(("single_triangle".into(), Mesh::from_triangles(vec![Vec3::ZERO, Vec3::X, Vec3::Y], &[0, 1, 2]).unwrap()));
    v
}

/// Tiny deterministic PRNG (xorshift) for reproducible random tests.
pub struct Rng(pub u64);
impl Rng {
    /// The next state (xorshift64).
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    pub fn next_f32(&mut self) -> f32 {
        ((self.next_u64() >> 40) as f32) / ((1u64 << 24) as f32) * 2.0 - 1.0
    }
    pub fn vec3(&mut self) -> Vec3 {
        Vec3::new(self.next_f32(), self.next_f32(), self.next_f32())
    }
    /// A double in `[0, 1)` (53 random bits).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}

// ---- raw triangle soups (possibly invalid) for the corpus and repair tests ----

/// Positions and a flat triangle list, before any validation.
#[derive(Clone, Debug, Default)]
pub struct Soup {
    pub positions: Vec<Vec3>,
    pub triangles: Vec<u32>,
}

impl Soup {
    pub fn of(mesh: &Mesh) -> Soup {
        Soup { positions: mesh.positions.clone(), triangles: mesh.ct.v_table().to_vec() }
    }
    pub fn faces(&self) -> usize {
        self.triangles.len() / 3
    }
    /// Appends `other` (re-indexed) moved by `offset`: a separate component.
    pub fn append(&mut self, other: &Soup, offset: Vec3) {
        let base = self.positions.len() as u32;
        self.positions.extend(other.positions.iter().map(|&q| q + offset));
        self.triangles.extend(other.triangles.iter().map(|&i| i + base));
    }
    /// Reverses the orientation of face `f`.
    pub fn flip(&mut self, f: usize) {
        self.triangles.swap(3 * f + 1, 3 * f + 2);
    }
}

/// `k` triangles on the edge (0, 1), alternating orientation (a "fin" / book).
pub fn soup_fin(k: usize) -> Soup {
    let mut s = Soup { positions: vec![Vec3::ZERO, Vec3::X], triangles: Vec::new() };
    for i in 0..k {
        let a = std::f32::consts::TAU * i as f32 / k as f32;
        s.positions.push(Vec3::new(0.5, a.cos(), a.sin()));
        let w = 2 + i as u32;
        s.triangles.extend(if i % 2 == 0 { [0, 1, w] } else { [1, 0, w] });
    }
    s
}

/// A closed tetrahedron on vertices `a, b, c, d` (outward orientation for a
/// right-handed `a, b, c, d`).
pub fn tet_faces(a: u32, b: u32, c: u32, d: u32) -> [u32; 12] {
    [a, c, b, a, d, c, a, b, d, b, c, d]
}

/// Two closed tetrahedra sharing the edge (0, 1): four faces on one edge.
pub fn soup_two_tets_on_edge() -> Soup {
    let positions = vec![
        Vec3::ZERO,
        Vec3::X,
        Vec3::new(0.5, 1.0, 0.2),
        Vec3::new(0.5, 0.5, 1.0),
        Vec3::new(0.5, -1.0, 0.2),
        Vec3::new(0.5, -0.5, -1.0),
    ];
    let mut triangles = tet_faces(0, 1, 2, 3).to_vec();
    triangles.extend(tet_faces(0, 1, 4, 5));
    Soup { positions, triangles }
}

/// Two closed tetrahedra sharing only vertex 0 (a closed bowtie).
pub fn soup_two_tets_on_vertex() -> Soup {
    let positions = vec![
        Vec3::ZERO,
        Vec3::new(1.0, 0.2, 0.1),
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(1.0, 0.5, 1.0),
        Vec3::new(-1.0, 0.2, 0.1),
        Vec3::new(-1.0, -1.0, 0.0),
        Vec3::new(-1.0, 0.5, -1.0),
    ];
    let mut triangles = tet_faces(0, 1, 2, 3).to_vec();
    triangles.extend(tet_faces(0, 4, 5, 6));
    Soup { positions, triangles }
}

/// Two open fans (hexagonal disks) meeting at their centre, vertex 0.
pub fn soup_bowtie_disks() -> Soup {
    let mut s = Soup { positions: vec![Vec3::ZERO], triangles: Vec::new() };
    for (side, z) in [(0u32, 1.0f32), (1, -1.0)] {
        let base = 1 + 6 * side;
        for i in 0..6 {
            let a = std::f32::consts::TAU * i as f32 / 6.0;
            s.positions.push(Vec3::new(a.cos(), a.sin(), z));
        }
        // a fan of 5 triangles (open between the last and the first rim vertex)
        for i in 0..5 {
            s.triangles.extend([0, base + i, base + i + 1]);
        }
    }
    s
}

/// A strip of `k` quads closed into a Möbius band (non-orientable).
pub fn soup_mobius(k: u32) -> Soup {
    let mut s = Soup::default();
    for i in 0..k {
        let a = std::f32::consts::TAU * i as f32 / k as f32;
        let tw = a / 2.0;
        for sgn in [1.0f32, -1.0] {
            let r = 1.0 + sgn * 0.3 * tw.cos();
            s.positions.push(Vec3::new(r * a.cos(), r * a.sin(), sgn * 0.3 * tw.sin()));
        }
    }
    for i in 0..k {
        let (a, b) = (2 * i, 2 * i + 1);
        let (c, d) = if i + 1 < k { (2 * i + 2, 2 * i + 3) } else { (1, 0) };
        s.triangles.extend([a, c, b, b, c, d]);
    }
    s
}

/// A closed cylinder whose caps are fans around a centre of valence `k`.
pub fn soup_cylinder_fans(k: u32, rings: u32) -> Soup {
    let mut s = Soup::default();
    for r in 0..=rings {
        for i in 0..k {
            let a = std::f32::consts::TAU * i as f32 / k as f32;
            s.positions.push(Vec3::new(a.cos(), a.sin(), r as f32 / rings as f32));
        }
    }
    let id = |r: u32, i: u32| r * k + i % k;
    for r in 0..rings {
        for i in 0..k {
            s.triangles.extend([id(r, i), id(r, i + 1), id(r + 1, i + 1), id(r, i), id(r + 1, i + 1), id(r + 1, i)]);
        }
    }
    let (bot, top) = (s.positions.len() as u32, s.positions.len() as u32 + 1);
    s.positions.push(Vec3::ZERO);
    s.positions.push(Vec3::new(0.0, 0.0, 1.0));
    for i in 0..k {
        s.triangles.extend([bot, id(0, i + 1), id(0, i)]);
        s.triangles.extend([top, id(rings, i), id(rings, i + 1)]);
    }
    s
}

/// An `n x m` torus grid whose last row is glued to the first reflected: a
/// Klein bottle (closed, non-orientable, every vertex interior).
pub fn soup_klein(n: u32, m: u32) -> Soup {
    let mut s = Soup::default();
    for j in 0..m {
        for i in 0..n {
            let (a, b) = (std::f32::consts::TAU * i as f32 / n as f32, std::f32::consts::TAU * j as f32 / m as f32);
            s.positions.push(Vec3::new((2.0 + a.cos()) * b.cos(), (2.0 + a.cos()) * b.sin(), a.sin()));
        }
    }
    let id = |i: u32, j: u32| if j == m { (n - i % n) % n } else { j * n + i % n };
    for j in 0..m {
        for i in 0..n {
            s.triangles.extend([id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    s
}

/// Reads `bytes` called `name` (its extension picks the format) through
/// the one reading pipeline, with `topology` and the default budget.
pub fn read_bytes_as(bytes: &[u8], name: &str, topology: subdiv::io::Topology) -> subdiv::Result<subdiv::io::Loaded> {
    let opts = subdiv::io::ReadOptions { topology, ..Default::default() };
    subdiv::io::read(subdiv::io::Source::Bytes { bytes, name, folder: None }, &opts)
}

/// [`read_bytes_as`], refusing invalid topology.
pub fn read_bytes(bytes: &[u8], name: &str) -> subdiv::Result<subdiv::io::Loaded> {
    read_bytes_as(bytes, name, subdiv::io::Topology::Refuse)
}

/// The mesh in `bytes` called `name`.
pub fn mesh_of(bytes: &[u8], name: &str) -> subdiv::Result<Mesh> {
    read_bytes(bytes, name).map(|l| l.mesh)
}

/// The mesh in `bytes` called `name` with its attributes.
pub fn with_attributes(bytes: &[u8], name: &str) -> subdiv::Result<(Mesh, subdiv::mesh::Attributes)> {
    read_bytes(bytes, name).map(|l| (l.mesh, l.attributes))
}

/// The mesh in `bytes` called `name`, repaired, with the repair's report.
pub fn repaired_of(bytes: &[u8], name: &str) -> subdiv::Result<(Mesh, subdiv::mesh::RepairReport)> {
    let l = read_bytes_as(bytes, name, subdiv::io::Topology::Repair)?;
    Ok((l.mesh, l.notes.repair.unwrap_or_default()))
}

/// Reads the file `path` through the pipeline with `topology`.
pub fn read_file_as(path: &std::path::Path, topology: subdiv::io::Topology) -> subdiv::Result<subdiv::io::Loaded> {
    let opts = subdiv::io::ReadOptions { topology, ..Default::default() };
    subdiv::io::read(subdiv::io::Source::File(path), &opts)
}

/// The mesh in the file `path` with its attributes (materials found beside it).
pub fn load_with_attributes(path: &std::path::Path) -> (Mesh, subdiv::mesh::Attributes) {
    let l = read_file_as(path, subdiv::io::Topology::Refuse).unwrap_or_else(|e| panic!("{e}"));
    (l.mesh, l.attributes)
}

/// The file `path` repaired, with the repair's report.
pub fn load_repaired(path: &std::path::Path) -> subdiv::Result<(Mesh, subdiv::mesh::RepairReport)> {
    let l = read_file_as(path, subdiv::io::Topology::Repair)?;
    Ok((l.mesh, l.notes.repair.unwrap_or_default()))
}

/// The file `path` analysed: every problem listed.
pub fn analyze(path: &std::path::Path) -> subdiv::Result<(Mesh, subdiv::mesh::RepairReport)> {
    let l = read_file_as(path, subdiv::io::Topology::Analyze)?;
    Ok((l.mesh, l.notes.repair.unwrap_or_default()))
}

/// The `v x y z` lines of a file (an OpenSubdiv fixture).
pub fn read_points(path: &std::path::Path) -> Vec<Vec3> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let c: Vec<f32> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            Vec3::new(c[0], c[1], c[2])
        })
        .collect()
}

/// Every point of `ours` has a point of `theirs` within `tol` and the
/// matching is one to one (OpenSubdiv numbers edge vertices differently).
pub fn assert_same_points(ours: &[Vec3], theirs: &[Vec3], tol: f32, what: &str) {
    assert_eq!(ours.len(), theirs.len(), "{what}: vertex counts");
    let mut used = vec![false; theirs.len()];
    let mut worst = 0.0f32;
    for (i, p) in ours.iter().enumerate() {
        let (j, d) = theirs
            .iter()
            .enumerate()
            .filter(|&(j, _)| !used[j])
            .map(|(j, q)| (j, p.distance(*q)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap();
        assert!(d <= tol, "{what}: our vertex {i} at {p} has no OpenSubdiv point within {tol} (nearest {d})");
        used[j] = true;
        worst = worst.max(d);
    }
    eprintln!("{what}: {} points, worst distance {worst:.2e}", ours.len());
}

/// Every face corner of an OBJ text as (position, texture coordinate), in
/// f64 (faces written `f v/vt ...`).
pub fn obj_corners(text: &str) -> Vec<([f64; 3], [f64; 2])> {
    let num = |l: &str| -> Vec<f64> { l.split_whitespace().map(|x| x.parse().unwrap()).collect() };
    let v: Vec<Vec<f64>> = text.lines().filter_map(|l| l.strip_prefix("v ")).map(num).collect();
    let t: Vec<Vec<f64>> = text.lines().filter_map(|l| l.strip_prefix("vt ")).map(num).collect();
    let corner = |c: &str| {
        let mut ids = c.split('/').map(|x| x.parse::<usize>().unwrap() - 1);
        let (a, b) = (ids.next().unwrap(), ids.next().unwrap());
        ([v[a][0], v[a][1], v[a][2]], [t[b][0], t[b][1]])
    };
    text.lines().filter_map(|l| l.strip_prefix("f ")).flat_map(|l| l.split_whitespace().map(corner)).collect()
}
