//! `subdivide_model`, the one entry that chooses the path, gives what the
//! path's own function gives: for triangle and polygon schemes, with and
//! without attributes, in f32 and f64, for destinations that take faces
//! alone or need the tables (`Refiner`, `subdivide`, `subdivide_f64`,
//! `subdivide_faces`, `subdivide_faces_f64` called directly).

mod common;
use common::*;
use glam::DVec3;
use subdiv::mesh::{Attributes, BoundaryInterpolation, PolyMesh};
use subdiv::{
    Destination, FacesOnly, Mesh, Model, Options, Refinement, Refiner, Scheme, Subdivided, Surface, subdivide,
    subdivide_f64, subdivide_faces, subdivide_faces_f64, subdivide_model,
};

/// An open 4 x 3 grid of quads with a texture coordinate per vertex,
/// read as the CLI reads it (the quads fanned, their diagonals hidden).
fn quad_grid() -> (Mesh, Attributes) {
    let (n, m) = (5, 4);
    let mut obj = String::new();
    for j in 0..m {
        for i in 0..n {
            let (x, y) = (i as f32, j as f32);
            obj += &format!("v {} {} {}\nvt {} {}\n", x + 0.1 * y, y, 0.2 * (x * y).sin(), x / 4.0, y / 3.0);
        }
    }
    for j in 0..m - 1 {
        for i in 0..n - 1 {
            let k = |i: usize, j: usize| j * n + i + 1;
            let (a, b, c, d) = (k(i, j), k(i + 1, j), k(i + 1, j + 1), k(i, j + 1));
            obj += &format!("f {a}/{a} {b}/{b} {c}/{c} {d}/{d}\n");
        }
    }
    with_attributes(obj.as_bytes(), "grid.obj").expect("the grid reads")
}

/// The f64 control points of `mesh`: its f32 ones moved by less than an
/// f32 ulp, so a path that rounded them first would differ.
fn precise(mesh: &Mesh) -> Vec<DVec3> {
    mesh.positions.iter().map(|p| p.as_dvec3() + DVec3::new(1e-9, -2e-9, 3e-9)).collect()
}

fn how(scheme: Scheme, levels: u32, f64: bool, faces: FacesOnly) -> Refinement {
    let dest = Destination { faces, creases: true, holes: false };
    Refinement { scheme, levels, opts: Options::default(), f64, dest }
}

fn refined(mesh: &Mesh, attrs: &Attributes, control: &[DVec3], how: &Refinement) -> Subdivided {
    let model = Model { precise: Some(control), ..Model::new(mesh, attrs) };
    subdivide_model(&model, how).unwrap_or_else(|e| panic!("{how:?}: {e}"))
}

fn assert_triangles(r: &Subdivided, want: &Mesh, what: &str) {
    let Surface::Triangles(got) = &r.surface else { panic!("{what}: not triangles: {:?}", r.surface) };
    assert_eq!(got.ct.v_table(), want.ct.v_table(), "{what}: faces");
    assert_eq!(got.positions, want.positions, "{what}: positions");
}

fn assert_polygons(r: &Subdivided, want: &PolyMesh, what: &str) {
    let Surface::Polygons(got) = &r.surface else { panic!("{what}: not polygons: {:?}", r.surface) };
    assert_eq!(got.pt.v_table(), want.pt.v_table(), "{what}: faces");
    assert_eq!(got.positions, want.positions, "{what}: positions");
}

fn assert_faces(r: &Subdivided, want: &subdiv::mesh::Faces, what: &str) {
    let Surface::Faces(got) = &r.surface else { panic!("{what}: not faces alone: {:?}", r.surface) };
    assert_eq!(got, want, "{what}");
}

/// The f64 points of a refiner's finest level from `control`.
fn refiner_f64(r: &Refiner, control: &[DVec3]) -> Vec<DVec3> {
    let flat: Vec<f64> = control.iter().flat_map(|p| p.to_array()).collect();
    r.refine(&flat, 3).unwrap().chunks_exact(3).map(DVec3::from_slice).collect()
}

#[test]
fn triangle_scheme_paths_match_their_functions() {
    let (mesh, attrs) = quad_grid();
    assert!(attrs.uv.is_some(), "the grid has texture coordinates");
    let none = Attributes::default();
    let control = precise(&mesh);
    let (s, o) = (Scheme::Loop, Options::default());
    for levels in [1, 2] {
        // with attributes: a Refiner, in f32 and in f64, whatever the destination
        let r = Refiner::new(&mesh, s, levels, &o).unwrap();
        let want_attrs = r.attributes(&attrs).unwrap();
        for faces in [FacesOnly::Never, FacesOnly::Written, FacesOnly::Always] {
            let got = refined(&mesh, &attrs, &control, &how(s, levels, false, faces));
            assert_triangles(&got, &r.mesh(), "f32 with attributes");
            assert_eq!(got.attrs, want_attrs, "f32 attributes");
            assert!(got.positions_f64.is_none());
            let got = refined(&mesh, &attrs, &control, &how(s, levels, true, faces));
            let pos = refiner_f64(&r, &control);
            assert_eq!(got.positions_f64.as_deref(), Some(&pos[..]), "f64 points with attributes");
            let rounded = Mesh { positions: pos.iter().map(|p| p.as_vec3()).collect(), ..r.mesh() };
            assert_triangles(&got, &rounded, "f64 with attributes");
            assert_eq!(got.attrs, want_attrs, "f64 attributes");
        }
        // without: the tables, or the faces alone where the destination takes them
        let (fine, _) = subdivide(&mesh, s, levels, &o).unwrap();
        let (faces, _) = subdivide_faces(&mesh, s, levels, &o, |j| j).unwrap();
        assert_triangles(&refined(&mesh, &none, &control, &how(s, levels, false, FacesOnly::Never)), &fine, "tables");
        for f in [FacesOnly::Written, FacesOnly::Always] {
            assert_faces(&refined(&mesh, &none, &control, &how(s, levels, false, f)), &faces, "faces alone");
        }
        let (fine, pos) = subdivide_f64(&mesh, &control, s, levels, &o).unwrap();
        for f in [FacesOnly::Never, FacesOnly::Written] {
            let got = refined(&mesh, &none, &control, &how(s, levels, true, f));
            assert_triangles(&got, &fine, "f64 tables");
            assert_eq!(got.positions_f64.as_deref(), Some(&pos[..]), "f64 points");
        }
        let (want, _) = subdivide_faces_f64(&mesh, &control, s, levels, &o, |j| j).unwrap();
        let got = refined(&mesh, &none, &control, &how(s, levels, true, FacesOnly::Always));
        let Surface::FacesF64(got) = &got.surface else { panic!("f64 faces alone: {:?}", got.surface) };
        assert_eq!(got, &want, "f64 faces alone");
    }
}

#[test]
fn polygon_scheme_paths_match_their_functions() {
    let (mesh, attrs) = quad_grid();
    let (pm, pattrs) = PolyMesh::from_mesh_with_attributes(&mesh, &attrs);
    assert_eq!(pm.pt.num_faces(), 12, "the grid's quads");
    let none = Attributes::default();
    let control = precise(&mesh);
    let (s, o) = (Scheme::CatmullClark, Options::default());
    for levels in [1, 2] {
        let r = Refiner::new(&pm, s, levels, &o).unwrap();
        let want_attrs = r.attributes(&pattrs).unwrap();
        let pt = r.polygons().expect("refined polygons").clone();
        for faces in [FacesOnly::Never, FacesOnly::Written, FacesOnly::Always] {
            let got = refined(&mesh, &attrs, &control, &how(s, levels, false, faces));
            assert_polygons(
                &got,
                &PolyMesh { pt: pt.clone(), positions: r.positions().to_vec() },
                "f32 with attributes",
            );
            assert_eq!(got.attrs, want_attrs, "f32 attributes");
            let got = refined(&mesh, &attrs, &control, &how(s, levels, true, faces));
            let pos = refiner_f64(&r, &control);
            assert_eq!(got.positions_f64.as_deref(), Some(&pos[..]), "f64 points with attributes");
            let rounded = PolyMesh { pt: pt.clone(), positions: pos.iter().map(|p| p.as_vec3()).collect() };
            assert_polygons(&got, &rounded, "f64 with attributes");
            assert_eq!(got.attrs, want_attrs, "f64 attributes");
        }
        let (fine, _) = subdivide(&pm, s, levels, &o).unwrap();
        let (faces, _) = subdivide_faces(&pm, s, levels, &o, |j| j).unwrap();
        assert_polygons(&refined(&mesh, &none, &control, &how(s, levels, false, FacesOnly::Never)), &fine, "tables");
        for f in [FacesOnly::Written, FacesOnly::Always] {
            assert_faces(&refined(&mesh, &none, &control, &how(s, levels, false, f)), &faces, "faces alone");
        }
        // f64 polygons keep their tables whatever the destination
        let (fine, pos) = subdivide_f64(&pm, &control, s, levels, &o).unwrap();
        for f in [FacesOnly::Never, FacesOnly::Written, FacesOnly::Always] {
            let got = refined(&mesh, &none, &control, &how(s, levels, true, f));
            assert_polygons(&got, &fine, "f64 tables");
            assert_eq!(got.positions_f64.as_deref(), Some(&pos[..]), "f64 points");
        }
    }
    // a PolyMesh given as it is takes the same path as the mesh it came from
    let model = Model { control: subdiv::Control::Polygons(&pm), attrs: &pattrs, precise: None };
    let got = subdivide_model(&model, &how(s, 1, false, FacesOnly::Never)).unwrap();
    let r = Refiner::new(&pm, s, 1, &o).unwrap();
    assert_polygons(&got, &PolyMesh { pt: r.polygons().unwrap().clone(), positions: r.positions().to_vec() }, "poly");
    // and a triangle scheme on polygons is refused, naming the scheme
    let err = subdivide_model(&model, &how(Scheme::Loop, 1, false, FacesOnly::Never)).unwrap_err();
    assert!(err.to_string().contains("loop"), "{err}");
}

#[test]
fn written_faces_only_where_a_file_would_be_the_same() {
    let (mesh, _) = quad_grid();
    let none = Attributes::default();
    let control = precise(&mesh);
    // no levels: the control mesh, which keeps its holes as tags
    let got = refined(&mesh, &none, &control, &how(Scheme::Loop, 0, false, FacesOnly::Written));
    assert_triangles(&got, &mesh, "level 0");
    assert_eq!(got.num_faces(), mesh.ct.num_triangles());
    // holes: the tables, the holes left out of the faces written
    let holed = Mesh { ct: mesh.ct.clone().with_holes(vec![0, 1]), ..mesh.clone() };
    let got = refined(&holed, &none, &control, &how(Scheme::Loop, 1, false, FacesOnly::Written));
    let (fine, _) = subdivide(&holed, Scheme::Loop, 1, &Options::default()).unwrap();
    assert_triangles(&got, &fine, "holes");
    assert_eq!(got.num_faces(), fine.ct.num_triangles() - fine.ct.holes().len());
    assert!(!fine.ct.holes().is_empty());
    // sharp corners a format keeps: the tables; one that keeps none: the faces
    let mut h = how(Scheme::Loop, 1, false, FacesOnly::Written);
    h.opts.boundary = BoundaryInterpolation::EdgeAndCorner;
    assert!(matches!(refined(&mesh, &none, &control, &h).surface, Surface::Triangles(_)));
    h.dest.creases = false;
    assert!(matches!(refined(&mesh, &none, &control, &h).surface, Surface::Faces(_)));
    // the destination a file's format states
    let faces = |p: &str| subdiv::io::destination(std::path::Path::new(p)).faces;
    assert_eq!(faces("out.obj"), FacesOnly::Written);
    assert_eq!(faces("out.ct"), FacesOnly::Never);
}
