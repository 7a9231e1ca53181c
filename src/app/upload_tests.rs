//! What the GPU mirror sends after an edit of the cage: a drag moves a few
//! rows of the drawn level, and only those rows (positions, normals, normal
//! segments) are written into the buffers already on the GPU, which then
//! hold what a whole upload of the document would hold, bit for bit.

use super::edit::EditAction;
use super::gpu_scene::GpuScene;
use super::tests::{settle, subdivide};
use super::{Command, Viewer};
use crate::Scheme;
use crate::mesh::sharpness::{CreaseTag, Tags};
use crate::render::{GpuMesh, Offscreen};
use glam::{Vec2, Vec3};

/// A device, or `None` (the test skips) where there is none and
/// `SUBDIV_REQUIRE_GPU` is unset.
fn device() -> Option<Offscreen> {
    match Offscreen::new(8, 8) {
        Ok(o) => Some(o),
        Err(e) if std::env::var_os("SUBDIV_REQUIRE_GPU").is_none() => {
            eprintln!("SKIPPED: {e}");
            None
        }
        Err(e) => panic!("SUBDIV_REQUIRE_GPU is set but {e}"),
    }
}

/// A mesh's buffers as the GPU holds them, as bits (so that equality is
/// exact): positions, normals, normal segments.
fn bits(m: Option<&GpuMesh>, off: &Offscreen) -> Vec<Vec<[u32; 3]>> {
    let m = m.expect("a mesh on the GPU");
    let (device, queue) = (&off.gpu.device, &off.gpu.queue);
    let (positions, normals) = m.read_back(device, queue).expect("read back");
    let lines = m.read_normal_lines(device, queue).expect("read back");
    [positions, normals, lines].iter().map(|a| a.iter().map(|p| p.to_array().map(f32::to_bits)).collect()).collect()
}

/// The icosphere of 2,562 vertices (or, with `quads`, the 10,240 quads of
/// a smaller one refined once by Catmull-Clark), and the vertex to move:
/// with quads, one of valence 4 whose quads' far corners have valence 4
/// too (a point of an edge of the smaller sphere), so that the moved
/// level's support ends, beyond those corners, at quads of which it holds
/// one corner only. The edge from that vertex to a neighbour is infinitely
/// sharp when `creased` (the level is then drawn cut open along it).
fn sphere(quads: bool, creased: bool) -> (crate::Mesh, u32) {
    let (mut mesh, moved) = match quads {
        false => (crate::mesh::shapes::icosphere(4), 0),
        true => {
            let ico = crate::mesh::shapes::icosphere(3);
            let mesh = crate::subdivide(&ico, Scheme::CatmullClark, 1, &Default::default()).expect("quads").0;
            (mesh, ico.positions.len() as u32)
        }
    };
    if creased {
        // an edge of a quad, not its hidden diagonal
        let ct = &mesh.ct;
        let c = (0..ct.num_corners() as u32)
            .find(|&c| ct.vtx(crate::mesh::n(c)) == moved && ct.edge_generation(c) != crate::mesh::Generations::HIDDEN)
            .expect("an edge at the vertex");
        let v1 = ct.vtx(crate::mesh::p(c));
        let tags = Tags { creases: vec![CreaseTag { v0: moved, v1, sharpness: 10.0 }], corners: Vec::new() };
        mesh.ct = mesh.ct.with_tags(&tags).expect("an edge");
    }
    (mesh, moved)
}

/// A mesh's positions and normals, as bits.
fn snapshot(shown: &super::model::Shown) -> Vec<[u32; 6]> {
    let bits = |p: &Vec3| p.to_array().map(f32::to_bits);
    let (p, n) = (shown.mesh.positions.iter().map(bits), shown.normals.iter().map(bits));
    p.zip(n).map(|(p, n)| [p[0], p[1], p[2], n[0], n[1], n[2]]).collect()
}

/// Every vertex of `now` whose position or normal differs from `before`
/// (same count) is in `rows`.
fn assert_covers(rows: &[u32], before: &[[u32; 6]], now: &super::model::Shown, what: &str) {
    let now = snapshot(now);
    assert_eq!(now.len(), before.len(), "{what}: the same vertices");
    let missed: Vec<usize> =
        (0..now.len()).filter(|&i| now[i] != before[i] && rows.binary_search(&(i as u32)).is_err()).collect();
    assert!(missed.is_empty(), "{what}: vertices {missed:?} changed outside the rows recorded");
}

/// A viewer in the edit mode on `mesh` at `level` of `scheme`, the normal
/// segments shown.
fn editing(mesh: crate::Mesh, scheme: Scheme, level: u32) -> Viewer {
    let mut v = Viewer::new();
    v.doc.adopt("sphere.obj".into(), mesh, None);
    subdivide(&mut v, scheme, level);
    settle(&mut v);
    let mut d = v.doc.display;
    d.normals = true;
    v.apply(Command::SetDisplay(d));
    v.apply(Command::Edit(EditAction::Toggle));
    v
}

#[test]
fn a_one_vertex_drag_writes_only_its_rows_and_the_gpu_holds_what_a_whole_upload_holds() {
    let Some(off) = device() else { return };
    let (device, queue) = (&off.gpu.device, &off.gpu.queue);
    // a polygon level cut open along a crease: its normals and the cut's
    // reach differently (over the quads' diagonals)
    let cases = [
        (Scheme::Loop, 2, false, false),
        (Scheme::Loop, 2, false, true),
        (Scheme::CatmullClark, 2, false, true),
        (Scheme::CatmullClark, 2, true, true),
        (Scheme::Loop, 0, false, true),
        (Scheme::CatmullClark, 0, true, true),
    ];
    for (scheme, level, quads, creased) in cases {
        let case = format!("{scheme} level {level}, quads {quads}, creased {creased}");
        let (mesh, moved) = sphere(quads, creased);
        let mut v = editing(mesh, scheme, level);
        assert_eq!(v.doc.model.raw.creased.is_some(), creased, "{case}: drawn cut open along the crease");
        let mut scene = GpuScene::default();
        scene.sync(device, queue, &v.doc, 0.05);
        let nv = v.doc.model.result.shown.mesh.positions.len();
        // the level's positions and normals alone
        let level_bytes = (nv * 24) as u64;
        assert!(scene.uploaded_bytes >= level_bytes, "{case}: the first upload is whole");
        // the moved vertex is on the crease: its support reaches the cut's copies
        v.apply(Command::Edit(EditAction::Select { ids: vec![moved], add: false }));
        v.apply(Command::Edit(EditAction::Grab { anchor: Vec2::ZERO }));
        let steps: [&[f32]; 3] = [&[0.02], &[0.05, 0.08], &[0.1]];
        for (k, moves) in steps.iter().enumerate() {
            // the second step moves twice before the mirror looks
            let (result, control) = (snapshot(&v.doc.model.result.shown), snapshot(&v.doc.model.control));
            let seen = (v.doc.model.result.version(), v.doc.model.control.version());
            for &d in *moves {
                v.apply(Command::Edit(EditAction::GrabTo(Vec3::new(d, -d, 0.5 * d))));
            }
            // what the document says changed covers what did
            let model = &v.doc.model;
            let rows = model.result.rows_since(seen.0).expect("a move changes rows of the result only");
            assert!(rows.len() < nv / 20, "{case}, step {k}: {} rows of {nv}", rows.len());
            assert_covers(&rows, &result, &model.result.shown, &format!("{case}, step {k}, the level"));
            let rows = model.control.rows_since(seen.1).expect("a move changes rows of the cage only");
            assert_covers(&rows, &control, &model.control, &format!("{case}, step {k}, the cage"));
            let before = scene.uploaded_bytes;
            scene.sync(device, queue, &v.doc, 0.05);
            let sent = scene.uploaded_bytes - before;
            assert!(sent > 0, "{case}, step {k}: the move was uploaded");
            assert!(sent * 20 < level_bytes, "{case}, step {k}: {sent} bytes for one vertex of {nv} ({level_bytes})");
            let mut whole = GpuScene::default();
            whole.sync(device, queue, &v.doc, 0.05);
            assert_eq!(bits(scene.result.as_ref(), &off), bits(whole.result.as_ref(), &off), "{case}, step {k}");
            assert_eq!(bits(scene.control.as_ref(), &off), bits(whole.control.as_ref(), &off), "{case}, step {k}");
            let doc = &v.doc.model.result.shown;
            let drawn = bits(scene.result.as_ref(), &off);
            let held: Vec<[u32; 3]> = doc.mesh.positions.iter().map(|p| p.to_array().map(f32::to_bits)).collect();
            assert_eq!(drawn[0], held, "{case}, step {k}: the document's positions are drawn");
        }
        // confirmed and undone: the undo is a move back, written by rows too
        v.apply(Command::Edit(EditAction::Confirm));
        v.apply(Command::Edit(EditAction::Undo));
        let before = scene.uploaded_bytes;
        scene.sync(device, queue, &v.doc, 0.05);
        assert!(scene.uploaded_bytes - before < level_bytes / 20, "{case}: the undo");
        let mut whole = GpuScene::default();
        whole.sync(device, queue, &v.doc, 0.05);
        assert_eq!(bits(scene.result.as_ref(), &off), bits(whole.result.as_ref(), &off), "{case}: after the undo");
    }
}

/// The minimum and the median of `xs`.
fn min_median(xs: &mut [f64]) -> (f64, f64) {
    xs.sort_by(f64::total_cmp);
    (xs[0], xs[xs.len() / 2])
}

/// What one frame of a drag costs on a big level (docs/performance.md,
/// "Editing"): `SUBDIV_DRAG_MODEL` (a file; else the icosphere of 10,242
/// vertices) at Loop level `SUBDIV_DRAG_LEVEL` (default 3), one control
/// vertex dragged in 24 steps. Per step: the document's edit (the refiner,
/// the drawn level's copies and shading), the mirror's sync (the upload),
/// the bytes it sent, and a 1280x800 render of the level with its cage
/// (submitted, waited for, read back); the minimum and the median.
#[test]
#[ignore = "a measurement: cargo test --release --lib drag_cost -- --ignored --nocapture"]
fn drag_cost() {
    use std::time::Instant;
    let Some(_) = device() else { return };
    let mut off = Offscreen::new(1280, 800).expect("a device");
    let mesh = match std::env::var_os("SUBDIV_DRAG_MODEL") {
        Some(p) => {
            let opts = crate::io::ReadOptions { topology: crate::io::Topology::Repair, ..Default::default() };
            crate::io::read(crate::io::Source::File(std::path::Path::new(&p)), &opts).expect("the model").mesh
        }
        None => crate::mesh::shapes::icosphere(5),
    };
    let level = std::env::var("SUBDIV_DRAG_LEVEL").ok().and_then(|l| l.parse().ok()).unwrap_or(3);
    let mut v = Viewer::new();
    let picked = mesh.positions.len() as u32 / 3;
    v.doc.adopt("drag.obj".into(), mesh, None);
    subdivide(&mut v, Scheme::Loop, level);
    settle(&mut v);
    v.apply(Command::Edit(EditAction::Toggle));
    let mut scene = GpuScene::default();
    scene.sync(&off.gpu.device, &off.gpu.queue, &v.doc, 0.05);
    let (lo, hi) = v.doc.model.control.mesh.bounds();
    let camera = crate::render::Camera::framing(lo, hi, 1.6);
    let step = lo.distance(hi) * 2e-3;
    v.apply(Command::Edit(EditAction::Select { ids: vec![picked], add: false }));
    v.apply(Command::Edit(EditAction::Grab { anchor: Vec2::ZERO }));
    let (mut edit, mut upload, mut render, mut sent) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for k in 1..=24 {
        let t = Instant::now();
        v.apply(Command::Edit(EditAction::GrabTo(Vec3::splat(step * k as f32))));
        edit.push(t.elapsed().as_secs_f64() * 1e3);
        let (t, before) = (Instant::now(), scene.uploaded_bytes);
        scene.sync(&off.gpu.device, &off.gpu.queue, &v.doc, 0.05);
        upload.push(t.elapsed().as_secs_f64() * 1e3);
        sent.push((scene.uploaded_bytes - before) as f64);
        let t = Instant::now();
        let look = v.doc.display.look();
        off.render_one(camera, scene.result.as_ref().expect("the level"), scene.control.as_ref(), look)
            .expect("a frame");
        render.push(t.elapsed().as_secs_f64() * 1e3);
    }
    let shown = &v.doc.model.result.shown.mesh;
    let whole = (shown.positions.len() * 24) as f64;
    assert!(sent.iter().all(|&b| b > 0.0), "every step was uploaded");
    let [e, u, r, b] = [&mut edit, &mut upload, &mut render, &mut sent].map(|xs| min_median(xs));
    println!(
        "drag_cost level={level} triangles={} vertices={} control={} edit_ms={:.2}/{:.2} upload_ms={:.2}/{:.2} \
         uploaded_kb={:.1}/{:.1} level_kb={:.0} render_ms={:.1}/{:.1} frame_ms={:.1} (min/median)",
        shown.ct.num_triangles(),
        shown.positions.len(),
        v.doc.model.control.mesh.positions.len(),
        e.0,
        e.1,
        u.0,
        u.1,
        b.0 / 1024.0,
        b.1 / 1024.0,
        whole / 1024.0,
        r.0,
        r.1,
        e.1 + u.1 + r.1
    );
}
