//! The egui side panel, the 3D area's mouse and keyboard handling, and the
//! file browser.

use super::doc::{Doc, MAX_LEVEL};
use crate::anim::tweak::Tweak;
use crate::render::export::{ExportStyle, ExportTarget};
use crate::render::{Camera, Look, Surface};
use crate::subdiv::LoopBeta;
use crate::{Scheme, error::human_bytes};
use egui::{Color32, Key, PointerButton, RichText, Sense};
use glam::Vec2;
use std::path::PathBuf;
use std::sync::atomic::Ordering;

/// Keyboard help shown at the bottom of the panel.
pub const HELP: &str = "Mouse: left drag orbit, right/middle or shift+drag pan, wheel zoom to cursor. \
Keys: W wireframe, S shading, +/- level, F fit, R reset, O ortho, C control mesh, N normals, \
B side by side, T turntable, Space play/pause, Left/Right step frame, P screenshot.";

/// View state owned by the window (not by the document).
pub struct UiState {
    /// Shared camera of the viewports.
    pub camera: Camera,
    /// Face fill.
    pub surface: Surface,
    /// Wireframe on.
    pub wireframe: bool,
    /// Control mesh overlay.
    pub control: bool,
    /// Vertex normals.
    pub normals: bool,
    /// Control mesh and result in two viewports.
    pub side_by_side: bool,
    /// Set to refit the camera on the next frame.
    pub fit: bool,
    /// Set to reset the camera direction and fit.
    pub reset: bool,
    /// A screenshot was asked for (P).
    pub screenshot: bool,
    /// Path typed in the Open field.
    pub open_path: String,
    /// File browser open, and its directory.
    pub browser: Option<PathBuf>,
    /// Bundled model files.
    pub bundled: Vec<PathBuf>,
    /// Export file or directory.
    pub export_path: String,
    /// Export image side.
    pub export_size: u32,
    /// Smoothed frame time, ms.
    pub frame_ms: f64,
    /// Time of the last GPU upload, ms.
    pub upload_ms: f64,
    /// A file is hovering over the window.
    pub hovering_file: bool,
    /// Adapter description.
    pub adapter: String,
    /// The 3D area (points), set each frame.
    pub scene_rect: egui::Rect,
    /// Multisampling on.
    pub msaa: bool,
    /// Clicks in the 3D area pick control-mesh edges.
    pub pick: bool,
    /// The picked corner whose highlight is uploaded.
    pub highlighted: Option<u32>,
    /// Taubin steps per click.
    pub smooth_steps: u32,
    /// The camera turns around the model.
    pub turntable: bool,
    /// The adapter offers multisampling.
    pub msaa_available: bool,
    /// How many times the 3D viewports were rendered (they are cached between changes).
    pub scene_renders: u64,
    /// CPU time to record the last 3D render, ms.
    pub encode_ms: f64,
}

impl UiState {
    /// Defaults; `bundled` lists the models compiled into the binary.
    pub fn new(wireframe: bool) -> UiState {
        let bundled = crate::bundled::MODELS.iter().map(|m| PathBuf::from(m.cli_name())).collect();
        UiState {
            camera: Camera::default(),
            surface: Surface::Smooth,
            wireframe,
            control: false,
            normals: false,
            side_by_side: false,
            fit: true,
            reset: false,
            screenshot: false,
            open_path: String::new(),
            browser: None,
            bundled,
            export_path: "subdiv-animation.gif".into(),
            export_size: 480,
            frame_ms: 0.0,
            upload_ms: 0.0,
            hovering_file: false,
            adapter: String::new(),
            scene_rect: egui::Rect::NOTHING,
            msaa: false,
            pick: false,
            highlighted: None,
            smooth_steps: 10,
            turntable: false,
            msaa_available: false,
            scene_renders: 0,
            encode_ms: 0.0,
        }
    }

    /// The look of the result viewport.
    pub fn look(&self) -> Look {
        Look {
            surface: self.surface,
            wireframe: self.wireframe,
            control: self.control,
            normals: self.normals,
            colors: false,
            uv_checker: false,
        }
    }
}

fn sep(n: u64) -> String {
    let s = n.to_string();
    let mut out = String::new();
    for (i, ch) in s.chars().enumerate() {
        if i > 0 && (s.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(ch);
    }
    out
}

/// Draws the panel and handles input; returns the 3D area in points.
pub fn show(ui: &mut egui::Ui, doc: &mut Doc, st: &mut UiState) -> egui::Rect {
    egui::Panel::left("controls").default_size(300.0).resizable(true).show(ui, |ui| {
        egui::ScrollArea::vertical().show(ui, |ui| {
            ui.heading("subdiv");
            model_section(ui, doc, st);
            ui.separator();
            subdivision_section(ui, doc);
            ui.separator();
            display_section(ui, st);
            ui.separator();
            animation_section(ui, doc, st);
            ui.separator();
            tools_section(ui, doc, st);
            ui.separator();
            stats_section(ui, doc, st);
            ui.separator();
            ui.label(RichText::new(HELP).small().weak());
        });
    });
    let rect = ui.available_rect_before_wrap();
    st.scene_rect = rect;
    scene_input(ui, rect, doc, st);
    overlay(ui, rect, doc, st);
    file_browser(ui.ctx(), doc, st);
    rect
}

fn curve_section(ui: &mut egui::Ui, doc: &mut Doc) {
    let Some(c) = &mut doc.curve else { return };
    ui.label(
        RichText::new(format!(
            "Bezier curve: {} ({} control points, degree {})",
            c.name,
            c.control.len(),
            c.control.len() - 1
        ))
        .strong(),
    );
    let mut changed = ui.add(egui::Slider::new(&mut c.segments, 1..=512).text("segments")).changed();
    changed |= ui.checkbox(&mut c.construction, "de Casteljau construction").changed();
    changed |= ui.add_enabled(c.construction, egui::Slider::new(&mut c.t, 0.0..=1.0).text("t")).changed();
    let back = ui.button("Back to the mesh").clicked();
    if back {
        doc.curve = None;
    }
    if changed || back {
        doc.curve_changed = true;
    }
    ui.separator();
}

fn model_section(ui: &mut egui::Ui, doc: &mut Doc, st: &mut UiState) {
    curve_section(ui, doc);
    ui.label(RichText::new(format!("Model: {}", doc.name)).strong());
    let current = doc.path.clone();
    egui::ComboBox::from_id_salt("model").selected_text("Bundled models").show_ui(ui, |ui| {
        if ui.selectable_label(current.is_none(), "tetrahedron (built in)").clicked() {
            doc.open_builtin();
        }
        for p in st.bundled.clone() {
            let name = p.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
            if ui.selectable_label(current.as_ref() == Some(&p), name).clicked() {
                doc.open(p);
            }
        }
    });
    ui.horizontal(|ui| {
        let edit =
            ui.add(egui::TextEdit::singleline(&mut st.open_path).hint_text("path/to/model.obj").desired_width(170.0));
        let enter = edit.lost_focus() && ui.input(|i| i.key_pressed(Key::Enter));
        if (ui.button("Open").clicked() || enter) && !st.open_path.trim().is_empty() {
            doc.open(PathBuf::from(st.open_path.trim()));
        }
        if ui.button("Browse…").clicked() {
            let start = doc.path.as_ref().and_then(|p| p.parent().map(|d| d.to_path_buf()));
            st.browser = Some(start.or_else(|| std::env::current_dir().ok()).unwrap_or_else(|| PathBuf::from("/")));
        }
    });
    ui.label(RichText::new("…or drop a file on the window (.obj, .ct, .bez patches, .bzc curves)").small().weak());
    ui.checkbox(&mut doc.repair_on_open, "Repair on open").on_hover_text(
        "split non-manifold edges and vertices, orient faces consistently, drop degenerate and duplicate faces",
    );
    if let Some(p) = doc.failed.clone()
        && ui.button("Repair and open").on_hover_text(p.display().to_string()).clicked()
    {
        doc.error = None;
        doc.failed = None;
        doc.open_with(p, true);
    }
    if let Some(b) = &doc.loading {
        ui.horizontal(|ui| {
            ui.spinner();
            ui.label(&b.what);
        });
    }
}

fn subdivision_section(ui: &mut egui::Ui, doc: &mut Doc) {
    let mut changed = false;
    egui::ComboBox::from_label("Scheme").selected_text(doc.scheme.name()).show_ui(ui, |ui| {
        for s in Scheme::ALL {
            changed |= ui.selectable_value(&mut doc.scheme, s, s.name()).changed();
        }
    });
    match doc.scheme {
        Scheme::Loop => {
            let mut warren = doc.opts.loop_beta == LoopBeta::Warren;
            if ui.checkbox(&mut warren, "Warren's beta").changed() {
                doc.opts.loop_beta = if warren { LoopBeta::Warren } else { LoopBeta::Loop };
                changed = true;
            }
        }
        Scheme::ModifiedButterfly => {
            changed |= ui.add(egui::Slider::new(&mut doc.opts.tension, -0.05..=0.1).text("tension w")).drag_stopped();
        }
        _ => {}
    }
    let max = doc.max_level();
    ui.horizontal(|ui| {
        if ui.add_enabled(doc.level > 0, egui::Button::new("−")).clicked() {
            doc.level -= 1;
            changed = true;
        }
        let slider = ui.add(egui::Slider::new(&mut doc.level, 0..=max).text("level"));
        changed |= slider.changed();
        if ui.add_enabled(doc.level < max, egui::Button::new("+")).clicked() {
            doc.level += 1;
            changed = true;
        }
    });
    let faces = doc.predicted_faces(doc.level);
    ui.label(format!("level {}: {} triangles", doc.level, sep(faces)));
    if max < MAX_LEVEL {
        let why = doc.level_refusal(max + 1).unwrap_or_default();
        ui.label(
            RichText::new(format!("levels above {max} are disabled: {why}"))
                .small()
                .color(Color32::from_rgb(230, 170, 60)),
        );
    } else if let Some(limit) = doc.limit {
        ui.label(RichText::new(format!("memory limit {}", human_bytes(limit))).small().weak());
    }
    if let Some(b) = &doc.subdividing {
        ui.horizontal(|ui| {
            ui.spinner();
            let d = b.done.load(Ordering::Relaxed);
            ui.add(
                egui::ProgressBar::new(d as f32 / b.total.max(1) as f32).text(format!("{} ({d}/{})", b.what, b.total)),
            );
        });
    }
    if changed {
        doc.request_subdivision();
    }
}

fn display_section(ui: &mut egui::Ui, st: &mut UiState) {
    ui.horizontal(|ui| {
        ui.label("Shading");
        ui.selectable_value(&mut st.surface, Surface::Smooth, "Phong");
        ui.selectable_value(&mut st.surface, Surface::Flat, "Flat");
        ui.selectable_value(&mut st.surface, Surface::Hidden, "None");
    });
    ui.horizontal_wrapped(|ui| {
        ui.checkbox(&mut st.wireframe, "Wireframe (W)");
        ui.checkbox(&mut st.control, "Control mesh (C)");
        ui.checkbox(&mut st.normals, "Normals (N)");
        ui.checkbox(&mut st.side_by_side, "Side by side (B)");
        ui.checkbox(&mut st.camera.orthographic, "Orthographic (O)");
        ui.checkbox(&mut st.turntable, "Turntable (T)");
        if st.msaa_available {
            ui.checkbox(&mut st.msaa, "Anti-aliasing (MSAA)")
                .on_hover_text("4x multisampling; costly on a software rasteriser with big meshes");
        }
    });
    ui.horizontal(|ui| {
        st.fit |= ui.button("Fit (F)").clicked();
        st.reset |= ui.button("Reset camera (R)").clicked();
        st.screenshot |= ui.button("Screenshot (P)").clicked();
    });
}

fn tools_section(ui: &mut egui::Ui, doc: &mut Doc, st: &mut UiState) {
    use super::doc::{Coloring, NormalMode};
    ui.label(RichText::new("Surface and tools").strong());
    let mut refresh = false;
    egui::ComboBox::from_label("Normals").selected_text(doc.normal_mode.name()).show_ui(ui, |ui| {
        for m in NormalMode::ALL {
            refresh |= ui.selectable_value(&mut doc.normal_mode, m, m.name()).changed();
        }
    });
    refresh |= ui
        .checkbox(&mut doc.snap_limit, "Snap to Loop limit positions")
        .on_hover_text("move every vertex to its limit point on the Loop surface")
        .changed();
    egui::ComboBox::from_label("Colour").selected_text(doc.coloring.name()).show_ui(ui, |ui| {
        for c in Coloring::ALL {
            refresh |= ui.selectable_value(&mut doc.coloring, c, c.name()).changed();
        }
    });
    match doc.coloring {
        Coloring::Shells => {
            ui.label(RichText::new(format!("dark: level 0 vertices … bright: level {}", doc.result_level)).small());
        }
        Coloring::Displacement => {
            ui.label(RichText::new(format!("dark: on the control mesh … bright: {:.4} away", doc.color_max)).small());
        }
        Coloring::File if doc.file_attrs.colors.is_none() => {
            ui.label(RichText::new("this model has no vertex colours (OBJ `v x y z r g b`)").small());
        }
        Coloring::Checker if doc.file_attrs.uv.is_none() => {
            ui.label(RichText::new("this model has no texture coordinates (OBJ `vt`); try models/cube_uv.obj").small());
        }
        Coloring::Checker => {
            ui.label(RichText::new("UVs per corner (seams kept), linear inside each triangle").small());
        }
        Coloring::File | Coloring::None => {}
    }
    if refresh {
        doc.refresh_result();
    }
    ui.horizontal(|ui| {
        ui.add(egui::DragValue::new(&mut st.smooth_steps).range(1..=200).suffix(" steps"));
        if ui.button("Smooth (Taubin)").on_hover_text("lambda 0.6307, mu -0.6732 on the control mesh").clicked() {
            doc.smooth(st.smooth_steps);
        }
        if ui.add_enabled(doc.original.is_some(), egui::Button::new("Revert")).clicked() {
            doc.revert();
        }
    });
    ui.checkbox(&mut st.pick, "Pick control edges (click)");
    if let Some((a, b)) = doc.picked_edge() {
        ui.horizontal(|ui| {
            ui.label(format!("edge ({a}, {b})"));
            if ui.button("Flip").clicked() {
                doc.flip_picked();
            }
            if ui.button("Split").clicked() {
                doc.split_picked();
            }
        });
    }
}

fn animation_section(ui: &mut egui::Ui, doc: &mut Doc, st: &mut UiState) {
    ui.label(RichText::new("Animation").strong());
    ui.label(RichText::new(format!("paths: {}", doc.paths_source)).small().weak());
    ui.horizontal(|ui| {
        let playing = doc.anim.as_ref().is_some_and(|a| a.clock.playing);
        if ui.button(if playing { "Pause" } else { "Play" }).on_hover_text("Space").clicked() {
            toggle_play(doc);
        }
        if ui.button("< Step").on_hover_text("step back (Left)").clicked() {
            step(doc, -1);
        }
        if ui.button("Step >").on_hover_text("step forward (Right)").clicked() {
            step(doc, 1);
        }
        if ui.add_enabled(doc.animating, egui::Button::new("Stop")).clicked() {
            doc.stop_animation();
        }
    });
    let mut rebuild = false;
    ui.horizontal(|ui| {
        rebuild |= ui.add(egui::Slider::new(&mut doc.refine, 0..=8).text("refine n")).changed();
    });
    egui::ComboBox::from_label("Tweak").selected_text(doc.tweak.name()).show_ui(ui, |ui| {
        for t in Tweak::ALL {
            rebuild |= ui.selectable_value(&mut doc.tweak, t, t.name()).changed();
        }
    });
    if rebuild && doc.animating {
        doc.request_animation();
    }
    if let Some(a) = &mut doc.anim {
        ui.checkbox(&mut a.clock.looping, "Loop");
        ui.add(egui::Slider::new(&mut a.clock.fps, 1.0..=120.0).text("frames/s"));
        let mut f = a.clock.frame();
        let n = a.clock.frames();
        if ui.add(egui::Slider::new(&mut f, 0..=n - 1).text(format!("frame of {n}"))).changed() {
            a.clock.set_frame(f);
        }
        let (plan, normals) = a.player.last_timing;
        ui.label(format!(
            "per frame: plan {:.2} ms + normals {:.2} ms ({} triangles)",
            plan.as_secs_f64() * 1e3,
            normals.as_secs_f64() * 1e3,
            sep(a.player.topology().num_triangles() as u64)
        ));
    } else if let Some(b) = &doc.building {
        ui.horizontal(|ui| {
            ui.spinner();
            ui.label(&b.what);
        });
    }
    ui.horizontal(|ui| {
        ui.label("Export");
        ui.add(egui::TextEdit::singleline(&mut st.export_path).desired_width(150.0));
    });
    ui.horizontal(|ui| {
        egui::ComboBox::from_id_salt("export size").selected_text(format!("{0}×{0}", st.export_size)).show_ui(
            ui,
            |ui| {
                for s in [240, 320, 480, 640, 800] {
                    ui.selectable_value(&mut st.export_size, s, format!("{s}×{s}"));
                }
            },
        );
        let style = ExportStyle { size: (st.export_size, st.export_size), look: st.look(), fps: 30.0 };
        let busy = doc.exporting.is_some();
        if ui.add_enabled(!busy, egui::Button::new("GIF")).on_hover_text("all K*2^n frames as one GIF").clicked() {
            let mut p = PathBuf::from(st.export_path.trim());
            if p.extension().is_none_or(|e| e != "gif") {
                p.set_extension("gif");
            }
            doc.export(ExportTarget::Gif(p), style);
        }
        if ui
            .add_enabled(!busy, egui::Button::new("PNG frames"))
            .on_hover_text("numbered PNGs in a directory")
            .clicked()
        {
            doc.export(ExportTarget::Frames(PathBuf::from(st.export_path.trim()).with_extension("")), style);
        }
    });
    if let Some(b) = &doc.exporting {
        let d = b.done.load(Ordering::Relaxed);
        let mut cancel = false;
        ui.horizontal(|ui| {
            ui.add(
                egui::ProgressBar::new(d as f32 / b.total.max(1) as f32)
                    .text(format!("{d}/{} frames", b.total))
                    .desired_width(180.0),
            );
            cancel = ui.button("Cancel").clicked();
        });
        if cancel {
            doc.cancel_export();
        }
    }
}

fn stats_section(ui: &mut egui::Ui, doc: &mut Doc, st: &UiState) {
    let t = &doc.result.topo;
    let c = &doc.control.topo;
    ui.label(RichText::new("Statistics").strong());
    egui::Grid::new("stats").num_columns(3).striped(true).show(ui, |ui| {
        ui.label("");
        ui.label("control");
        ui.label(format!("level {}", doc.result_level));
        ui.end_row();
        for (name, a, b) in [
            ("vertices", c.vertices, t.vertices),
            ("edges", c.edges, t.edges),
            ("faces", c.faces, t.faces),
            ("boundary loops", c.boundary_loops, t.boundary_loops),
            ("components", c.components, t.components),
        ] {
            ui.label(name);
            ui.label(sep(a as u64));
            ui.label(sep(b as u64));
            ui.end_row();
        }
        ui.label("genus");
        ui.label(c.genus.to_string());
        ui.label(t.genus.to_string());
        ui.end_row();
    });
    if let Some(s) = &doc.stats {
        ui.label(format!(
            "{} ×{}: {:.1} ms (split+O {:.1}, edge points {:.1}, vertex points {:.1}); job {:.1} ms",
            doc.result_scheme.name(),
            doc.result_level,
            s.total_ms,
            s.split_ms,
            s.edge_ms,
            s.vertex_ms,
            doc.job_ms
        ));
    }
    ui.label(format!(
        "frame {:.1} ms ({:.0} fps), last upload {:.1} ms",
        st.frame_ms,
        1000.0 / st.frame_ms.max(0.01),
        st.upload_ms
    ));
    ui.label(RichText::new(format!("{} · 3D renders {}", st.adapter, st.scene_renders)).small().weak());
    if let Some(e) = doc.error.clone() {
        ui.horizontal_wrapped(|ui| {
            ui.label(RichText::new(e).color(Color32::from_rgb(255, 110, 90)));
            if ui.small_button("dismiss").clicked() {
                doc.error = None;
            }
        });
    }
    if let Some(n) = doc.notice.clone() {
        ui.horizontal_wrapped(|ui| {
            ui.label(RichText::new(n).color(Color32::from_rgb(120, 220, 130)));
            if ui.small_button("ok").clicked() {
                doc.notice = None;
            }
        });
    }
}

/// Space: starts the animation mode, or toggles play/pause.
pub fn toggle_play(doc: &mut Doc) {
    match &mut doc.anim {
        Some(a) => a.clock.playing = !a.clock.playing,
        None if !doc.animating => doc.request_animation(),
        None => {}
    }
}

fn step(doc: &mut Doc, d: i64) {
    match &mut doc.anim {
        Some(a) => {
            a.clock.playing = false;
            a.clock.step(d);
        }
        None if !doc.animating => doc.request_animation(),
        None => {}
    }
}

fn scene_input(ui: &mut egui::Ui, rect: egui::Rect, doc: &mut Doc, st: &mut UiState) {
    let resp = ui.allocate_rect(rect, Sense::click_and_drag());
    let shift = ui.input(|i| i.modifiers.shift);
    let delta = resp.drag_delta();
    let d = Vec2::new(delta.x, delta.y);
    let aspect = viewport_aspect(rect, st.side_by_side);
    if resp.dragged_by(PointerButton::Primary) && !shift {
        st.camera.orbit(d);
    } else if resp.dragged_by(PointerButton::Secondary)
        || resp.dragged_by(PointerButton::Middle)
        || resp.dragged_by(PointerButton::Primary)
    {
        st.camera.pan(d, rect.height());
    }
    if resp.double_clicked() {
        st.fit = true;
    } else if resp.clicked()
        && st.pick
        && let Some(pos) = resp.interact_pointer_pos()
    {
        let ndc = cursor_ndc(rect, st.side_by_side, pos).extend(0.0);
        let inv = st.camera.view_proj(aspect).inverse();
        let near = inv.project_point3(ndc);
        let far = inv.project_point3(ndc.with_z(1.0));
        doc.picked = super::doc::pick_edge(&doc.control.mesh, near, (far - near).normalize_or_zero());
    }
    if let Some(pos) = resp.hover_pos() {
        let (scroll, zoom) = ui.input(|i| (i.smooth_scroll_delta.y, i.zoom_delta()));
        let factor = (-scroll * 0.0025).exp() / zoom;
        if (factor - 1.0).abs() > 1e-4 {
            st.camera.zoom_to(factor, cursor_ndc(rect, st.side_by_side, pos), aspect);
        }
    }
    if ui.ctx().egui_wants_keyboard_input() {
        return;
    }
    let pressed = |k: Key| ui.input(|i| i.key_pressed(k));
    if pressed(Key::W) {
        st.wireframe = !st.wireframe;
    }
    if pressed(Key::S) {
        st.surface = match st.surface {
            Surface::Smooth => Surface::Flat,
            Surface::Flat => Surface::Hidden,
            Surface::Hidden => Surface::Smooth,
        };
        if st.surface == Surface::Hidden {
            st.wireframe = true;
        }
    }
    if pressed(Key::C) {
        st.control = !st.control;
    }
    if pressed(Key::N) {
        st.normals = !st.normals;
    }
    if pressed(Key::B) {
        st.side_by_side = !st.side_by_side;
    }
    if pressed(Key::O) {
        st.camera.orthographic = !st.camera.orthographic;
    }
    if pressed(Key::F) {
        st.fit = true;
    }
    if pressed(Key::T) {
        st.turntable = !st.turntable;
    }
    if pressed(Key::R) {
        st.reset = true;
    }
    if pressed(Key::P) {
        st.screenshot = true;
    }
    if pressed(Key::Space) {
        toggle_play(doc);
    }
    if pressed(Key::ArrowRight) {
        step(doc, 1);
    }
    if pressed(Key::ArrowLeft) {
        step(doc, -1);
    }
    let up = pressed(Key::Plus) || pressed(Key::Equals);
    let down = pressed(Key::Minus);
    if up && doc.level < doc.max_level() {
        doc.level += 1;
        doc.request_subdivision();
    } else if up {
        doc.error = doc.level_refusal(doc.level + 1).or(Some(format!("level {} is the highest offered", MAX_LEVEL)));
    }
    if down && doc.level > 0 {
        doc.level -= 1;
        doc.request_subdivision();
    }
}

/// The cursor in the normalised device coordinates of the viewport under it
/// (the left or right half in side-by-side mode).
pub fn cursor_ndc(rect: egui::Rect, side_by_side: bool, pos: egui::Pos2) -> Vec2 {
    let mut vp = rect;
    if side_by_side {
        vp.set_width(rect.width() / 2.0);
        if pos.x > vp.right() {
            vp = vp.translate(egui::vec2(vp.width(), 0.0));
        }
    }
    Vec2::new((pos.x - vp.left()) / vp.width() * 2.0 - 1.0, 1.0 - (pos.y - vp.top()) / vp.height() * 2.0)
}

/// Aspect of one viewport of the 3D area.
pub fn viewport_aspect(rect: egui::Rect, side_by_side: bool) -> f32 {
    let w = if side_by_side { rect.width() / 2.0 } else { rect.width() };
    w / rect.height().max(1.0)
}

fn overlay(ui: &mut egui::Ui, rect: egui::Rect, doc: &Doc, st: &UiState) {
    let painter = ui.painter_at(rect);
    let font = egui::FontId::proportional(14.0);
    let weak = Color32::from_gray(170);
    let label = if let Some(c) = &doc.curve {
        format!("{}: Bezier curve of degree {}", c.name, c.control.len().saturating_sub(1))
    } else if doc.animating {
        match &doc.anim {
            Some(a) => format!(
                "{} level {} — frame {}/{}",
                doc.scheme.name(),
                doc.level,
                a.clock.frame() + 1,
                a.clock.frames()
            ),
            None => "building the animation…".into(),
        }
    } else {
        format!("{} level {}", doc.result_scheme.name(), doc.result_level)
    };
    if st.side_by_side {
        let half = rect.width() / 2.0;
        painter.text(
            rect.left_top() + egui::vec2(10.0, 8.0),
            egui::Align2::LEFT_TOP,
            "control mesh",
            font.clone(),
            weak,
        );
        painter.text(rect.left_top() + egui::vec2(half + 10.0, 8.0), egui::Align2::LEFT_TOP, label, font.clone(), weak);
        painter.line_segment(
            [rect.center_top() + egui::vec2(0.0, 0.0), rect.center_bottom()],
            egui::Stroke::new(1.0, Color32::from_gray(60)),
        );
    } else {
        painter.text(rect.left_top() + egui::vec2(10.0, 8.0), egui::Align2::LEFT_TOP, label, font.clone(), weak);
    }
    if let Some(b) = doc.subdividing.as_ref().or(doc.loading.as_ref()).or(doc.building.as_ref()) {
        let secs = b.since.elapsed().as_secs_f32();
        if secs > 0.15 {
            painter.text(
                rect.right_top() + egui::vec2(-10.0, 8.0),
                egui::Align2::RIGHT_TOP,
                format!("{}… {:.1} s", b.what, secs),
                font.clone(),
                Color32::from_rgb(240, 200, 90),
            );
        }
    }
    if st.hovering_file {
        painter.rect_filled(rect.shrink(20.0), 8.0, Color32::from_black_alpha(150));
        painter.text(
            rect.center(),
            egui::Align2::CENTER_CENTER,
            "Drop to open",
            egui::FontId::proportional(28.0),
            Color32::WHITE,
        );
    }
}

fn file_browser(ctx: &egui::Context, doc: &mut Doc, st: &mut UiState) {
    let Some(dir) = st.browser.clone() else { return };
    let mut open = true;
    let mut next: Option<PathBuf> = None;
    let mut chosen: Option<PathBuf> = None;
    egui::Window::new("Open a model").open(&mut open).default_size([420.0, 420.0]).show(ctx, |ui| {
        ui.label(dir.display().to_string());
        if let Some(parent) = dir.parent()
            && ui.button("Up: parent folder").clicked()
        {
            next = Some(parent.to_path_buf());
        }
        egui::ScrollArea::vertical().max_height(340.0).show(ui, |ui| match std::fs::read_dir(&dir) {
            Ok(rd) => {
                let mut entries: Vec<PathBuf> = rd.filter_map(|e| e.ok().map(|e| e.path())).collect();
                entries.sort_by_key(|p| (!p.is_dir(), p.file_name().map(|n| n.to_ascii_lowercase())));
                for p in entries {
                    let name = p.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
                    if name.starts_with('.') {
                        continue;
                    }
                    if p.is_dir() {
                        if ui.selectable_label(false, format!("[dir] {name}/")).clicked() {
                            next = Some(p);
                        }
                    } else if matches!(p.extension().and_then(|e| e.to_str()), Some("obj" | "ct" | "bez" | "bzc"))
                        && ui.selectable_label(false, name).clicked()
                    {
                        chosen = Some(p);
                    }
                }
            }
            Err(e) => {
                ui.label(RichText::new(format!("cannot list: {e}")).color(Color32::from_rgb(255, 110, 90)));
            }
        });
    });
    if let Some(p) = chosen {
        st.open_path = p.display().to_string();
        doc.open(p);
        open = false;
    }
    st.browser = if open { Some(next.unwrap_or(dir)) } else { None };
}
