//! The Inspect mode driven headless through the real `Viewer`: keys and
//! clicks through egui, commands through `Viewer::apply`, picks answered
//! by the worker; every id checked against the library's own answer
//! (`corner_ops`, `poly_corner_ops`, `stencil`, the child table's O).

use crate::app::inspect::split::{quad_split, triangle_split};
use crate::app::inspect::{Action, Mode, Table};
use crate::app::{Command, Viewer};
use crate::mesh::inspect::{corner_ops, poly_corner_ops};
use crate::mesh::poly::PolyTable;
use crate::render::overlay::Mark;
use crate::subdiv::stencil::stencil;
use crate::{Mesh, Scheme};
use std::path::PathBuf;
use std::time::{Duration, Instant};

fn key(k: egui::Key) -> egui::Event {
    egui::Event::Key { key: k, physical_key: None, pressed: true, repeat: false, modifiers: Default::default() }
}

fn frame(ctx: &egui::Context, v: &mut Viewer, events: Vec<egui::Event>) {
    let raw = egui::RawInput {
        screen_rect: Some(egui::Rect::from_min_size(egui::Pos2::ZERO, egui::vec2(1280.0, 800.0))),
        events,
        ..Default::default()
    };
    ctx.run_ui(raw, |ui| {
        v.ui(ui);
    })
    .drop_without_applying_deltas();
}

fn settle(v: &mut Viewer) {
    let t0 = Instant::now();
    loop {
        v.poll();
        if !v.doc.busy() {
            return;
        }
        assert!(t0.elapsed() < Duration::from_secs(60), "worker did not finish");
        std::thread::sleep(Duration::from_millis(2));
    }
}

/// A click at `pos` (press, release), half a second of egui's clock after
/// the last, then the worker's answer.
fn click(ctx: &egui::Context, v: &mut Viewer, pos: egui::Pos2) {
    for _ in 0..30 {
        frame(ctx, v, vec![]);
    }
    let button = |pressed| egui::Event::PointerButton {
        pos,
        button: egui::PointerButton::Primary,
        pressed,
        modifiers: Default::default(),
    };
    frame(ctx, v, vec![egui::Event::PointerMoved(pos), button(true)]);
    frame(ctx, v, vec![button(false)]);
    settle(v);
}

fn open(v: &mut Viewer, path: PathBuf, scheme: Scheme, level: u32) {
    v.apply(Command::Open(path));
    settle(v);
    v.apply(Command::Subdivide(crate::app::doc::Request { scheme, level, ..v.doc.request }));
    settle(v);
    assert!(v.doc.status.error.is_none(), "{:?}", v.doc.status.error.as_ref().map(ToString::to_string));
}

fn bundled(name: &str) -> PathBuf {
    PathBuf::from(format!("{}{name}", crate::bundled::PREFIX))
}

/// A 3 x 3 grid of quads in the plane z = 0 (a border all round), as OBJ.
fn grid_obj(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("subdiv-inspect-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut s = String::new();
    for j in 0..4 {
        for i in 0..4 {
            s += &format!("v {} {} 0\n", i as f32 - 1.5, j as f32 - 1.5);
        }
    }
    for j in 0..3 {
        for i in 0..3 {
            let a = 4 * j + i + 1;
            s += &format!("f {} {} {} {}\n", a, a + 1, a + 5, a + 4);
        }
    }
    let path = dir.join(name);
    std::fs::write(&path, s).unwrap();
    path
}

fn picked_corner(v: &Viewer) -> u32 {
    v.doc.inspect.corner.as_ref().expect("a corner is picked").corner
}

#[test]
fn q_clicks_a_corner_and_the_letter_keys_walk_its_operators() {
    let ctx = egui::Context::default();
    let mut v = Viewer::new();
    open(&mut v, bundled("cube.obj"), Scheme::Loop, 1);
    frame(&ctx, &mut v, vec![key(egui::Key::Q)]);
    assert!(v.doc.inspect.on && v.doc.inspect.mode == Mode::Corners);
    let rect = v.view.scene_rect;
    click(&ctx, &mut v, rect.center() + egui::vec2(9.0, -6.0));
    assert!(v.doc.model.probe.is_none(), "a click picks for the inspector, not the surface");
    let c = picked_corner(&v);
    let raw = v.doc.model.raw.mesh.clone();
    // the corner lies in the triangle under the cursor, at its vertex nearest the hit
    let ray = crate::app::probe::ray_at(&v.view.camera, rect, false, rect.center() + egui::vec2(9.0, -6.0));
    let hit = crate::mesh::pick::nearest_hit(&raw, ray.origin, ray.dir).expect("the cube is under the cursor");
    assert_eq!(c / 3, hit.triangle);
    let d = |k: u32| raw.positions[raw.ct.vtx(k) as usize].distance(hit.point);
    assert!((3 * hit.triangle..3 * hit.triangle + 3).all(|k| d(c) <= d(k)));
    let (normals, ortho) = (v.doc.display.normals, v.view.camera.orthographic);
    let mut want = c;
    for (k, op) in
        [(egui::Key::N, 'n'), (egui::Key::O, 'o'), (egui::Key::S, 's'), (egui::Key::U, 'u'), (egui::Key::L, 'l')]
    {
        let ops = corner_ops(&raw.ct, want).unwrap();
        want = match op {
            'n' => ops.n,
            'o' => ops.o.unwrap(),
            's' => ops.s.unwrap(),
            'u' => ops.u.unwrap(),
            _ => ops.l.unwrap(),
        };
        frame(&ctx, &mut v, vec![key(k)]);
        assert_eq!(picked_corner(&v), want, "after {op}");
    }
    assert_eq!((v.doc.display.normals, v.view.camera.orthographic), (normals, ortho), "N and O walked, not toggled");
    assert!(!v.view.screenshot);
    // s then u comes back; the overlay draws the seven arrows from the corner
    let overlay = v.doc.inspect_overlay().expect("drawn");
    let arrows = overlay.marks.iter().filter(|m| matches!(m, Mark::Arrow { .. })).count();
    assert_eq!(arrows, 7, "a closed mesh: every operator has a target");
    assert!(overlay.caption[0].contains(&format!("corner {want} ")), "{:?}", overlay.caption);
    // in another mode the letters are the display keys again; Esc leaves Inspect
    v.apply(Command::Inspect(Action::SetMode(Mode::Stencil)));
    frame(&ctx, &mut v, vec![key(egui::Key::N)]);
    assert!(v.doc.display.normals != normals && picked_corner(&v) == want);
    frame(&ctx, &mut v, vec![key(egui::Key::Escape)]);
    assert!(!v.doc.inspect.on && v.doc.inspect_overlay().is_none());
}

#[test]
fn a_step_across_a_border_does_nothing_and_says_so() {
    let ctx = egui::Context::default();
    let mut v = Viewer::new();
    open(&mut v, grid_obj("grid.obj"), Scheme::Loop, 0);
    let raw = v.doc.model.raw.mesh.clone();
    // a corner facing a border edge, picked as a click would
    let c = (0..raw.ct.num_corners() as u32).find(|&c| raw.ct.o(c).is_none()).unwrap();
    v.apply(Command::Inspect(Action::Toggle));
    v.doc.inspect.adopt(
        raw.clone(),
        crate::app::inspect::Found::Corner(crate::app::inspect::PickedCorner {
            corner: c,
            table: Table::Triangles(raw.clone()),
        }),
    );
    frame(&ctx, &mut v, vec![key(egui::Key::O)]);
    assert_eq!(picked_corner(&v), c, "no step across a border");
    let msg = v.doc.inspect.message.clone().unwrap_or_default();
    assert!(msg.contains("border") && msg.contains(&format!("o({c})")), "{msg}");
    let overlay = v.doc.inspect_overlay().unwrap();
    assert!(overlay.caption.iter().any(|l| l.contains("across a border: o")), "{:?}", overlay.caption);
    frame(&ctx, &mut v, vec![key(egui::Key::N)]);
    assert_eq!(picked_corner(&v), crate::mesh::n(c));
    assert!(v.doc.inspect.message.is_none());
}

#[test]
fn catmull_clark_picks_and_walks_the_quad_table() {
    let ctx = egui::Context::default();
    let mut v = Viewer::new();
    open(&mut v, bundled("critter.obj"), Scheme::CatmullClark, 1);
    v.apply(Command::Inspect(Action::Toggle));
    frame(&ctx, &mut v, vec![]);
    let rect = v.view.scene_rect;
    click(&ctx, &mut v, rect.center());
    let picked = v.doc.inspect.corner.clone().expect("the critter is under the centre");
    let Table::Polygons(pt) = &picked.table else { panic!("a polygon scheme picks in the quad table") };
    let again = PolyTable::from_corner_table(&v.doc.model.raw.mesh.ct);
    assert_eq!(pt.v_table(), again.v_table());
    let c = picked.corner;
    let ops = poly_corner_ops(pt, c).unwrap();
    frame(&ctx, &mut v, vec![key(egui::Key::N)]);
    assert_eq!(picked_corner(&v), ops.next);
    frame(&ctx, &mut v, vec![key(egui::Key::S)]);
    assert_eq!(Some(picked_corner(&v)), poly_corner_ops(pt, ops.next).unwrap().swing);
    let before = picked_corner(&v);
    frame(&ctx, &mut v, vec![key(egui::Key::L)]);
    assert_eq!(picked_corner(&v), before);
    assert!(v.doc.inspect.message.as_deref().is_some_and(|m| m.contains("next, prev, twin and swing")));
    let arrows = v.doc.inspect_overlay().unwrap().marks.iter().filter(|m| matches!(m, Mark::Arrow { .. })).count();
    assert_eq!(arrows, 4, "next, prev, twin, swing of an inner corner");
}

#[test]
fn a_stencil_is_listed_summing_to_one_and_drawn_on_the_cage() {
    let ctx = egui::Context::default();
    let mut v = Viewer::new();
    open(&mut v, bundled("torus.obj"), Scheme::Loop, 2);
    v.apply(Command::Inspect(Action::SetMode(Mode::Stencil)));
    v.apply(Command::Inspect(Action::Toggle));
    assert!(!v.doc.display.control);
    frame(&ctx, &mut v, vec![]);
    let rect = v.view.scene_rect;
    // the torus's tube, left of its hole
    click(&ctx, &mut v, rect.center() - egui::vec2(rect.width() * 0.3, 0.0));
    let st = v.doc.inspect.stencil.clone().expect("a vertex is picked");
    let d = &v.doc;
    let want = stencil(&d.model.control.mesh, Scheme::Loop, 2, &d.model.made.opts, st.vertex).unwrap();
    assert_eq!(*st, want);
    let sum: f64 = st.weights.iter().map(|w| w.1).sum();
    assert!((sum - 1.0).abs() < 1e-12, "{sum}");
    assert_eq!(st.rules.last().map(|r| r.0), Some(2), "the rules run up to the level shown");
    assert!(d.display.control, "the cage the stencil is drawn on is shown");
    let text = crate::app::panel::stencil_text(&st);
    assert!(text.contains("weights summing to 1") && text.lines().count() == 1 + st.rules.len() + st.weights.len());
    let overlay = d.inspect_overlay().unwrap();
    let discs: Vec<_> =
        overlay.marks.iter().filter_map(|m| if let Mark::Disc { at, .. } = m { Some(*at) } else { None }).collect();
    assert_eq!(discs.len(), st.weights.len() + 1, "one per control vertex and the refined vertex");
    for &(j, _) in &st.weights {
        assert!(discs.contains(&d.model.control.mesh.positions[j as usize]), "control vertex {j}");
    }
}

#[test]
fn the_split_view_derives_every_child_o_entry_from_the_parent() {
    let ctx = egui::Context::default();
    let mut v = Viewer::new();
    open(&mut v, bundled("cube.obj"), Scheme::Loop, 2);
    v.apply(Command::Inspect(Action::SetMode(Mode::Split)));
    v.apply(Command::Inspect(Action::Toggle));
    frame(&ctx, &mut v, vec![]);
    let centre = v.view.scene_rect.center();
    click(&ctx, &mut v, centre);
    let s = v.doc.inspect.split.clone().expect("a face is picked");
    let raw = v.doc.model.raw.mesh.clone();
    let nt = raw.ct.num_triangles() as u32 / 4;
    assert_eq!((s.level, s.parent, s.children.len()), (2, s.picked % nt, 4));
    assert!(s.children.contains(&s.picked));
    assert_eq!(s.rows.len(), 12);
    for r in &s.rows {
        assert_eq!(r.table, raw.ct.o(r.corner), "the child table's own entry");
        assert_eq!(r.derived, r.table, "corner {}: {} gives {:?}", r.corner, r.worked, r.derived);
    }
    let opts = v.doc.model.made.opts;
    for (id, rule) in &s.new_vertices {
        let st = stencil(&v.doc.model.control.mesh, Scheme::Loop, 2, &opts, *id).unwrap();
        assert_eq!(Some(rule), st.rules.last().map(|r| &r.1));
        assert_eq!(st.rules.last().unwrap().0, 2, "made by level 2");
    }
    let drawn = v.doc.inspect_overlay().unwrap();
    let segments = drawn.marks.iter().filter(|m| matches!(m, Mark::Segment { .. })).count();
    assert_eq!(segments, 6 + 3, "the parent's outline through six vertices, three inner edges");
    // level 0 has no parent
    v.apply(Command::Subdivide(crate::app::doc::Request { level: 0, ..v.doc.request }));
    settle(&mut v);
    assert!(v.doc.inspect_overlay().is_none(), "the pick was on another level");
    click(&ctx, &mut v, centre);
    assert!(v.doc.inspect.message.as_deref().is_some_and(|m| m.contains("level 1 or more")));
}

/// Every face of levels 1 to 3, closed and with a border, triangles and quads.
#[test]
fn the_split_formulas_give_every_entry_of_the_child_tables() {
    let opts = crate::Options::default();
    let grid = crate::bundled::read(&grid_obj("grid2.obj"), &Default::default()).unwrap().mesh;
    let cube = crate::bundled::read(&bundled("cube.obj"), &Default::default()).unwrap().mesh;
    let critter = crate::bundled::read(&bundled("critter.obj"), &Default::default()).unwrap().mesh;
    for (name, control) in [("grid", &grid), ("cube", &cube)] {
        for level in 1..=2 {
            let (fine, _) = crate::subdivide(control, Scheme::Loop, level, &opts).unwrap();
            for x in 0..fine.ct.num_triangles() as u32 {
                let s = triangle_split(control, &fine, (Scheme::Loop, level, &opts), x).unwrap();
                assert!(s.all_agree(), "{name} level {level} triangle {x}: {:?}", s.rows);
            }
        }
    }
    for (name, control) in [("grid", &grid), ("critter", &critter)] {
        for level in 1..=2 {
            let (fine, _): (Mesh, _) = crate::subdivide(control, Scheme::CatmullClark, level, &opts).unwrap();
            let pt = PolyTable::from_corner_table(&fine.ct);
            for x in (0..pt.num_faces() as u32).step_by(7) {
                let s = quad_split(control, &pt, (Scheme::CatmullClark, level, &opts), x).unwrap();
                assert!(s.all_agree(), "{name} level {level} quad {x}: {:?}", s.rows);
                assert_eq!(
                    s.rows.iter().filter(|r| r.table.is_none()).count(),
                    s.rows.iter().filter(|r| r.derived.is_none()).count()
                );
            }
        }
    }
    // borders are there to be derived
    let (fine, _) = crate::subdivide(&grid, Scheme::Loop, 1, &opts).unwrap();
    let borders = (0..fine.ct.num_triangles() as u32)
        .flat_map(|x| triangle_split(&grid, &fine, (Scheme::Loop, 1, &opts), x).unwrap().rows)
        .filter(|r| r.derived.is_none())
        .count();
    assert!(borders > 0);
}
