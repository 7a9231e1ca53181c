//! Picking the subdivision surface (`subdiv::pick`): a ray through a
//! known point of a control face comes back as that face and its `(u, v)`;
//! on a curved Loop surface the exact limit at the reported `(f, u, v)` lies
//! within the level's known distance of the hit; a ray past the surface is
//! no pick; the nearest control vertex has its valence.

mod common;
use common::*;
use glam::{DVec3, Vec3};
use subdiv::eval::vertex_samples;
use subdiv::pick::nearest_hit;
use subdiv::pick::{ControlFace, Level, Limit, Pick, pick};
use subdiv::{Mesh, Options, Scheme, subdivide};

/// `control` refined by `scheme` to `level`, picked along a ray.
fn pick_on(control: &Mesh, scheme: Scheme, level: u32, origin: Vec3, dir: Vec3) -> (Mesh, Option<Pick>) {
    let (drawn, _) = subdivide(control, scheme, level, &Options::default()).expect("subdivides");
    let lv = Level { control, drawn: &drawn, scheme, level, precise: None };
    let picked = pick(&lv, &Options::default(), origin, dir.normalize()).expect("the level matches");
    (drawn, picked)
}

/// The point `(1 - u - v) c0 + u c1 + v c2` of control face `f`.
fn point_of(m: &Mesh, f: u32, u: f32, v: f32) -> Vec3 {
    let c = |k: u32| m.positions[m.ct.vtx(3 * f + k) as usize];
    c(0) * (1.0 - u - v) + c(1) * u + c(2) * v
}

/// A face in the middle of an 8 x 8 planar grid: all its vertices interior
/// of valence 6, far from the grid's corners (where Loop's boundary rule
/// pulls the points in), so every level of Loop is the plane with the
/// same parameters (the box spline reproduces linear functions).
const MIDDLE: u32 = 2 * (4 * 8 + 4);

#[test]
fn the_centroid_of_a_flat_face_is_that_face_at_a_third_a_third() {
    let grid = flat_grid(8);
    let centroid = point_of(&grid, MIDDLE, 1.0 / 3.0, 1.0 / 3.0);
    for (scheme, level) in [(Scheme::Loop, 0), (Scheme::Loop, 2), (Scheme::Loop, 3), (Scheme::Butterfly, 2)] {
        let (_, picked) = pick_on(&grid, scheme, level, centroid + Vec3::Z * 5.0, -Vec3::Z);
        let p = picked.unwrap_or_else(|| panic!("{scheme} level {level}: the ray hits"));
        let ControlFace::Triangle { face, u, v } = p.face else { panic!("a triangle scheme names a triangle") };
        assert_eq!(face, MIDDLE, "{scheme} level {level}");
        assert!((u - 1.0 / 3.0).abs() < 1e-5 && (v - 1.0 / 3.0).abs() < 1e-5, "{scheme} level {level}: ({u}, {v})");
        assert!((p.point - centroid).length() < 1e-5);
        assert!((p.distance - 5.0).abs() < 1e-5);
        match (scheme, &p.limit) {
            (Scheme::Loop, Limit::Exact(s)) => {
                assert!((s.position - centroid.as_dvec3()).length() < 1e-6, "the limit of a plane is the plane");
                assert!((s.normal - DVec3::Z).length() < 1e-9);
                assert!(s.mean.abs() < 1e-9 && s.gaussian.abs() < 1e-9);
            }
            (Scheme::Butterfly, Limit::Unavailable(why)) => assert!(why.contains("interpolating"), "{why}"),
            (_, limit) => panic!("{scheme}: {limit:?}"),
        }
    }
}

#[test]
fn any_point_of_a_flat_face_comes_back_with_its_parameters() {
    let grid = flat_grid(8);
    for (u, v) in [(0.1f32, 0.2f32), (0.6, 0.3), (0.05, 0.9), (0.45, 0.05)] {
        let at = point_of(&grid, MIDDLE, u, v);
        let (_, picked) = pick_on(&grid, Scheme::Loop, 3, at + Vec3::new(0.3, -0.2, 4.0), Vec3::new(-0.3, 0.2, -4.0));
        let p = picked.expect("the ray hits");
        let ControlFace::Triangle { face, u: pu, v: pv } = p.face else { panic!("a triangle") };
        assert_eq!(face, MIDDLE);
        assert!(
            (pu - f64::from(u)).abs() < 1e-5 && (pv - f64::from(v)).abs() < 1e-5,
            "({u}, {v}) came back as ({pu}, {pv})"
        );
    }
}

/// The largest distance from a level's vertices to the limit at their own
/// parameters, plus the sag of the limit between them (half the largest
/// principal curvature times the square of the longest edge): how far the
/// level's surface lies from the limit at the same parameters.
fn level_to_limit(control: &Mesh, drawn: &Mesh, level: u32) -> f64 {
    let samples = vertex_samples(control, drawn, Scheme::Loop, level, &Options::default()).expect("evaluates");
    let mut vertex = 0.0f64;
    let mut curvature = 0.0f64;
    for (s, p) in samples.iter().zip(&drawn.positions) {
        if s.position.is_finite() {
            vertex = vertex.max((s.position - p.as_dvec3()).length());
        }
        if s.k1.is_finite() {
            curvature = curvature.max(s.k1.abs()).max(s.k2.abs());
        }
    }
    let edge = drawn
        .ct
        .edge_owners()
        .map(|c| {
            let a = drawn.positions[drawn.ct.vtx(subdiv::mesh::n(c)) as usize];
            let b = drawn.positions[drawn.ct.vtx(subdiv::mesh::p(c)) as usize];
            f64::from(a.distance(b))
        })
        .fold(0.0, f64::max);
    vertex + 0.5 * curvature * edge * edge
}

#[test]
fn the_limit_at_the_reported_point_lies_near_the_hit() {
    let ico = icosahedron();
    let torus = bundled("torus.obj");
    let mut rng = Rng(7);
    for (name, control) in [("icosahedron", &ico), ("torus", &torus)] {
        let (lo, hi) = control.bounds();
        let centre = (lo + hi) * 0.5;
        let far = (hi - lo).length() * 2.0;
        let mut errors = Vec::new();
        for level in [2, 4] {
            let (drawn, _) = subdivide(control, Scheme::Loop, level, &Options::default()).unwrap();
            let bound = level_to_limit(control, &drawn, level);
            let lv = Level { control, drawn: &drawn, scheme: Scheme::Loop, level, precise: None };
            let mut worst = 0.0f64;
            let mut hits = 0;
            for _ in 0..40 {
                let dir = rng.vec3().normalize();
                let aim = centre + rng.vec3() * 0.1 * (hi - lo).length();
                let Some(p) = pick(&lv, &Options::default(), aim - dir * far, dir).unwrap() else { continue };
                hits += 1;
                let Limit::Exact(s) = &p.limit else { panic!("{name}: a closed smooth mesh evaluates: {:?}", p.limit) };
                let d = (s.position - p.point.as_dvec3()).length();
                assert!(d <= bound, "{name} level {level}: the limit is {d} from the hit, more than {bound}");
                worst = worst.max(d);
            }
            assert!(hits > 20, "{name}: most rays at the middle hit ({hits})");
            errors.push((worst, bound));
        }
        // four times finer in each direction per two levels: the distance shrinks
        assert!(errors[1].0 < errors[0].0 / 4.0, "{name}: {errors:?}");
    }
}

#[test]
fn a_ray_past_the_surface_picks_nothing() {
    let ico = icosahedron();
    for level in [0, 2] {
        let (_, away) = pick_on(&ico, Scheme::Loop, level, Vec3::new(0.0, 0.0, 5.0), Vec3::Z);
        assert!(away.is_none(), "pointing away");
        let (_, beside) = pick_on(&ico, Scheme::Loop, level, Vec3::new(3.0, 0.0, 5.0), -Vec3::Z);
        assert!(beside.is_none(), "passing beside");
    }
}

#[test]
fn the_nearest_control_vertex_has_its_valence() {
    // the icosahedron's vertices all have valence 5: aim just beside vertex 0
    let ico = icosahedron();
    let v0 = ico.positions[0];
    let (_, p) = pick_on(&ico, Scheme::Loop, 3, v0 * 4.0 + Vec3::new(0.05, 0.0, 0.0), -v0);
    let p = p.expect("hits near vertex 0");
    assert_eq!((p.vertex.id, p.vertex.valence, p.vertex.boundary), (0, 5, false));
    // the grid: the middle face's corners have valence 6, the corner (0, 0) 3 on the boundary
    let grid = flat_grid(8);
    let c1 = grid.ct.vtx(3 * MIDDLE + 1);
    let near = point_of(&grid, MIDDLE, 0.8, 0.1);
    let (_, p) = pick_on(&grid, Scheme::Loop, 2, near + Vec3::Z, -Vec3::Z);
    let p = p.expect("hits");
    assert_eq!((p.vertex.id, p.vertex.valence, p.vertex.boundary), (c1, 6, false));
    let (_, p) = pick_on(&grid, Scheme::Loop, 0, Vec3::new(0.2, 0.1, 1.0), -Vec3::Z);
    let p = p.expect("hits the corner square");
    assert_eq!((p.vertex.position, p.vertex.valence, p.vertex.boundary), (Vec3::ZERO, 3, true));
    // a face at the border is evaluated too: on the flat grid, in its plane
    let Limit::Exact(s) = &p.limit else { panic!("a border face is evaluated: {:?}", p.limit) };
    assert!(s.position.z.abs() < 1e-12 && s.normal.z.abs() > 1.0 - 1e-12, "{s:?}");
}

#[test]
fn polygon_schemes_name_the_polygon_and_the_corner_of_its_quarter() {
    // every interior grid vertex is the centre of a point-symmetric ring, so
    // Catmull-Clark leaves it in place: a point near it stays in its quarter
    let grid = flat_grid(8);
    let near = point_of(&grid, MIDDLE, 0.85, 0.1);
    for level in [0, 1, 3] {
        let (_, p) = pick_on(&grid, Scheme::CatmullClark, level, near + Vec3::Z, -Vec3::Z);
        let p = p.expect("hits");
        // the grid has no polygons: each triangle is a face of its own
        let ControlFace::Polygon { face, size, corner, ptex } = p.face else { panic!("a polygon: {:?}", p.face) };
        assert_eq!((face, size, corner), (MIDDLE, 3, 1), "level {level}");
        assert_eq!(p.vertex.id, grid.ct.vtx(3 * MIDDLE + 1));
        match (&p.limit, ptex) {
            // a triangle drawn unrefined has no ptex point (its ptex faces are its level-1 quads)
            (Limit::Unavailable(why), None) => assert!(level == 0 && why.contains("unrefined"), "{why}"),
            (Limit::Exact(s), Some((q, u, v))) => {
                // the flat grid's limit is flat; the ptex face is triangle MIDDLE's corner 1
                assert!(s.position.z.abs() < 1e-9 && s.normal.z.abs() > 1.0 - 1e-9, "{s:?}");
                assert_eq!(q, 3 * MIDDLE + 1);
                assert!((0.0..=1.0).contains(&u) && (0.0..=1.0).contains(&v));
            }
            other => panic!("level {level}: {other:?}"),
        }
    }
    // a quad file: a cube of six quads, fanned on reading, joined again
    let obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
               f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
    let cube = read_bytes_as(obj.as_bytes(), "cube.obj", subdiv::io::Topology::Refuse).unwrap().mesh;
    assert_eq!(cube.ct.num_triangles(), 12);
    for level in [0, 2] {
        // onto the top face z = 1 near its corner (1, 1, 1), the file's vertex 7 (id 6)
        let (_, p) = pick_on(&cube, Scheme::CatmullClark, level, Vec3::new(0.65, 0.7, 5.0), -Vec3::Z);
        let p = p.expect("hits the top");
        let ControlFace::Polygon { face, size, corner, ptex } = p.face else { panic!("a polygon: {:?}", p.face) };
        assert_eq!((face, size, corner), (1, 4, 2), "level {level}");
        assert_eq!((p.vertex.id, p.vertex.valence), (6, 3), "every cube vertex has three edges");
        // every face a quad: ptex face = face; the hit (0.65, 0.7) of the top
        // quad (1 0 1) (1 1 1) ... drawn at its corner 2 side; the exact
        // limit lies below the hit, inside the cube, closer at level 2
        let (q, u, v) = ptex.expect("a quad has a ptex point");
        assert_eq!(q, 1);
        assert!(u > 0.5 && v > 0.5, "({u}, {v}) in corner 2's quarter");
        let Limit::Exact(s) = &p.limit else { panic!("Catmull-Clark is evaluated: {:?}", p.limit) };
        let gap = (s.position - p.point.as_dvec3()).length();
        assert!(s.normal.z > 0.7 && gap < if level == 0 { 0.3 } else { 0.05 }, "level {level}: gap {gap}, {s:?}");
    }
}

#[test]
fn a_faces_neighbourhood_has_the_same_limit_as_the_whole_mesh() {
    use subdiv::Evaluator;
    use subdiv::pick::neighbourhood;
    let mut rng = Rng(11);
    let (torus, ico) = (bundled("torus.obj"), icosahedron());
    let (lumpy, _) = subdivide(&bundled("cube.obj"), Scheme::Loop, 1, &Options::default()).unwrap();
    for (name, mesh) in [("torus", &torus), ("icosahedron", &ico), ("cube level 1", &lumpy)] {
        let whole = Evaluator::new(mesh, Scheme::Loop, &Options::default()).unwrap();
        let mut local_count = 0;
        for f in 0..mesh.ct.num_triangles() as u32 {
            let Some(local) = neighbourhood(mesh, f) else { continue };
            local_count += 1;
            let part = Evaluator::new(&local, Scheme::Loop, &Options::default()).unwrap();
            assert!(part.accepts(0), "{name}: face {f} is interior in its neighbourhood");
            for _ in 0..3 {
                let (a, b) = (rng.next_f32().abs() as f64, rng.next_f32().abs() as f64);
                let (u, v) = if a + b > 1.0 { (1.0 - a, 1.0 - b) } else { (a, b) };
                let (x, y) = (whole.eval(f as usize, u, v).unwrap(), part.eval(0, u, v).unwrap());
                let d = (x.position - y.position).length() + (x.normal - y.normal).length();
                assert!(d < 1e-12, "{name} face {f} at ({u}, {v}): {d}");
                assert!((x.mean - y.mean).abs() < 1e-9 * (1.0 + x.mean.abs()), "{name} face {f}: H");
                assert!((x.gaussian - y.gaussian).abs() < 1e-9 * (1.0 + x.gaussian.abs()), "{name} face {f}: K");
            }
        }
        assert!(local_count * 2 > mesh.ct.num_triangles(), "{name}: most faces have a neighbourhood of their own");
    }
}

#[test]
fn a_drawn_mesh_of_another_level_is_refused() {
    let ico = icosahedron();
    let (drawn, _) = subdivide(&ico, Scheme::Loop, 2, &Options::default()).unwrap();
    let lv = Level { control: &ico, drawn: &drawn, scheme: Scheme::Loop, level: 3, precise: None };
    assert!(pick(&lv, &Options::default(), Vec3::Z * 5.0, -Vec3::Z).is_err());
}

#[test]
fn the_text_block_says_what_was_found() {
    let ico = icosahedron();
    let (_, p) = pick_on(&ico, Scheme::Loop, 2, Vec3::new(0.1, 0.2, 5.0), -Vec3::Z);
    let text = p.expect("hits").to_string();
    for line in
        ["control face:", "u v:", "nearest control vertex:", "valence 5", "limit position:", "mean curvature H:"]
    {
        assert!(text.contains(line), "{line} missing from\n{text}");
    }
    let (_, p) = pick_on(&ico, Scheme::Butterfly, 1, Vec3::new(0.1, 0.2, 5.0), -Vec3::Z);
    let text = p.expect("hits").to_string();
    assert!(text.contains("limit evaluation: not available for butterfly"), "{text}");
}

/// How long a ray takes against a million triangles (run with --ignored
/// --nocapture in release).
#[test]
#[ignore = "a timing, not a check"]
fn time_a_ray_against_a_million_triangles() {
    let torus = bundled("torus.obj");
    let mut level = 0;
    while torus.ct.num_triangles() << (2 * level) < 1_000_000 {
        level += 1;
    }
    let (drawn, _) = subdivide(&torus, Scheme::Loop, level, &Options::default()).unwrap();
    let t0 = std::time::Instant::now();
    let mut hits = 0;
    for i in 0..20 {
        let origin = Vec3::new(0.05 * i as f32, 0.3, 10.0);
        hits += usize::from(nearest_hit(&drawn, origin, -Vec3::Z).is_some());
    }
    let ms = t0.elapsed().as_secs_f64() * 1e3 / 20.0;
    let lv = Level { control: &torus, drawn: &drawn, scheme: Scheme::Loop, level, precise: None };
    let origin =
        (0..20).map(|i| Vec3::new(0.05 * i as f32, 0.3, 10.0)).find(|&o| nearest_hit(&drawn, o, -Vec3::Z).is_some());
    let t1 = std::time::Instant::now();
    let p = pick(&lv, &Options::default(), origin.expect("a ray hits"), -Vec3::Z).unwrap();
    let pick_ms = t1.elapsed().as_secs_f64() * 1e3;
    println!(
        "{} triangles: {ms:.2} ms a ray ({hits} hits of 20) on {} threads; a whole pick with its limit {pick_ms:.2} ms ({:?})",
        drawn.ct.num_triangles(),
        rayon::current_num_threads(),
        p.map(|p| p.limit)
    );
    // the same million triangles as a control mesh: the limit needs its evaluator
    let lv = Level { control: &drawn, drawn: &drawn, scheme: Scheme::Loop, level: 0, precise: None };
    let t2 = std::time::Instant::now();
    let p = pick(&lv, &Options::default(), origin.expect("a ray hits"), -Vec3::Z).unwrap();
    println!(
        "a pick on a control mesh of a million triangles: {:.1} ms ({})",
        t2.elapsed().as_secs_f64() * 1e3,
        p.is_some()
    );
}
