//! The animation section: playback, path refinement, clock, export.

use super::{PanelState, sep};
use crate::anim::tweak::Tweak;
use crate::app::command::Command;
use crate::app::display::Display;
use crate::app::doc::Doc;
use crate::render::export::{Evaluation, ExportStyle, ExportTarget};
use egui::RichText;
use std::path::PathBuf;
use std::sync::atomic::Ordering;

/// Play/step/stop, refinement and tweak, the clock of a built plan, export.
pub(crate) fn animation_section(
    ui: &mut egui::Ui,
    doc: &Doc,
    panel: &mut PanelState,
    display: &Display,
) -> Vec<Command> {
    let anim = &doc.anim;
    ui.label(RichText::new(format!("paths: {}", anim.paths_source)).small().weak());
    let mut out = Vec::new();
    ui.horizontal(|ui| {
        if ui.button(if anim.playing() { "Pause" } else { "Play" }).on_hover_text("Space").clicked() {
            out.push(Command::TogglePlay);
        }
        if ui.button("< Step").on_hover_text("step back (Left)").clicked() {
            out.push(Command::Step(-1));
        }
        if ui.button("Step >").on_hover_text("step forward (Right)").clicked() {
            out.push(Command::Step(1));
        }
        if ui.add_enabled(anim.active, egui::Button::new("Stop")).clicked() {
            out.push(Command::StopAnimation);
        }
    });
    let (mut refine, mut tweak) = (anim.refine, anim.tweak);
    let mut rebuild = false;
    ui.horizontal(|ui| {
        rebuild |= ui.add(egui::Slider::new(&mut refine, 0..=8).text("refine n")).changed();
    });
    egui::ComboBox::from_label("Tweak").selected_text(tweak.name()).show_ui(ui, |ui| {
        for t in Tweak::ALL {
            rebuild |= ui.selectable_value(&mut tweak, t, t.name()).changed();
        }
    });
    if rebuild {
        out.push(Command::SetPathRefinement { refine, tweak });
    }
    out.extend(key_rows(ui, doc, panel));
    out.extend(clock_rows(ui, doc));
    out.extend(export_rows(ui, doc, panel, display));
    out
}

/// The keys the paths run through: insert one from the cage (I), set or
/// delete key k, save them as a `.paths` file.
fn key_rows(ui: &mut egui::Ui, doc: &Doc, panel: &mut PanelState) -> Vec<Command> {
    use crate::app::keys::KeyAction;
    let mut out = Vec::new();
    let k = doc.anim.paths.keys_per_vertex;
    let who = if doc.edit.selected.is_empty() {
        "all vertices".to_string()
    } else {
        format!("{} selected", doc.edit.selected.len())
    };
    ui.horizontal(|ui| {
        ui.label(format!("{k} keys"));
        if ui.button("Insert key (I)").on_hover_text(format!("the cage's positions of {who}")).clicked() {
            out.push(Command::Key(KeyAction::Insert));
        }
    });
    panel.key_index = panel.key_index.min(k.saturating_sub(1));
    ui.horizontal(|ui| {
        ui.add(egui::Slider::new(&mut panel.key_index, 0..=k.saturating_sub(1)).text("key"));
        if ui.button("Set").on_hover_text(format!("key it again from the cage ({who})")).clicked() {
            out.push(Command::Key(KeyAction::Set(panel.key_index)));
        }
        if ui.add_enabled(k > 1, egui::Button::new("Delete")).clicked() {
            out.push(Command::Key(KeyAction::Delete(panel.key_index)));
        }
    });
    ui.horizontal(|ui| {
        ui.text_edit_singleline(&mut panel.paths_path);
        if ui.button("Save paths").clicked() {
            out.push(Command::Key(KeyAction::Save(PathBuf::from(&panel.paths_path))));
        }
    });
    out
}

/// Loop, rate and frame of a built plan, and its cost per frame; a spinner while it builds.
fn clock_rows(ui: &mut egui::Ui, doc: &Doc) -> Vec<Command> {
    let mut out = Vec::new();
    if let Some(p) = &doc.anim.playback {
        let (mut looping, mut fps, mut f) = (p.clock.looping, p.clock.fps, p.clock.frame());
        if ui.checkbox(&mut looping, "Loop").changed() {
            out.push(Command::SetLooping(looping));
        }
        if ui.add(egui::Slider::new(&mut fps, 1.0..=120.0).text("frames/s")).changed() {
            out.push(Command::SetFps(fps));
        }
        let n = p.clock.frames();
        if ui.add(egui::Slider::new(&mut f, 0..=n - 1).text(format!("frame of {n}"))).changed() {
            out.push(Command::SetFrame(f));
        }
        let compute = doc.anim.gpu_compute == Some(true);
        let mut gpu = doc.anim.gpu_eval && compute;
        let tip = if compute {
            "stencils and normals as compute passes into the drawn buffers"
        } else {
            "this adapter has no compute shaders"
        };
        if ui.add_enabled(compute, egui::Checkbox::new(&mut gpu, "Evaluate on the GPU")).on_hover_text(tip).changed() {
            out.push(Command::SetGpuEval(gpu));
        }
        if doc.anim.on_gpu {
            ui.label(RichText::new("frames evaluated on the GPU; the figures below are the CPU's last").small().weak());
        }
        let (plan, normals) = p.player.last_timing;
        ui.label(format!(
            "plan_ms {:.1}  frame_ms {:.2} (CPU median, {} triangles)",
            p.player.plan_ms(),
            p.player.frame_ms().unwrap_or(0.0),
            sep(p.player.topology().num_triangles() as u64)
        ))
        .on_hover_text("plan_ms: recording the stencil plan; frame_ms: positions and normals per frame, the median of the last 64, as `subdiv animate --stats` prints");
        ui.label(
            RichText::new(format!(
                "last frame: stencils {:.2} ms + normals {:.2} ms",
                plan.as_secs_f64() * 1e3,
                normals.as_secs_f64() * 1e3
            ))
            .small()
            .weak(),
        );
    } else if let Some(b) = &doc.jobs.busy.building {
        ui.horizontal(|ui| {
            ui.spinner();
            ui.label(&b.what);
        });
    }
    out
}

/// Where and how big to export, the GIF and PNG buttons, progress and cancel.
fn export_rows(ui: &mut egui::Ui, doc: &Doc, panel: &mut PanelState, display: &Display) -> Vec<Command> {
    let mut out = Vec::new();
    if cfg!(target_arch = "wasm32") {
        ui.label(egui::RichText::new("Export: `subdiv animate` on the desktop writes GIFs and frames").small().weak());
        return out;
    }
    ui.horizontal(|ui| {
        ui.label("Export");
        ui.add(egui::TextEdit::singleline(&mut panel.export_path).desired_width(150.0));
    });
    ui.horizontal(|ui| {
        egui::ComboBox::from_id_salt("export size").selected_text(format!("{0}×{0}", panel.export_size)).show_ui(
            ui,
            |ui| {
                for s in [240, 320, 480, 640, 800] {
                    ui.selectable_value(&mut panel.export_size, s, format!("{s}×{s}"));
                }
            },
        );
        // exported as shown: on the GPU when the frames are evaluated there
        let on_gpu = doc.anim.gpu_eval && doc.anim.gpu_compute == Some(true);
        let eval = if on_gpu { Evaluation::Gpu } else { Evaluation::Cpu };
        let size = (panel.export_size, panel.export_size);
        let style = ExportStyle { size, look: display.plain_look(), fps: 30.0, eval };
        let busy = doc.jobs.busy.exporting.is_some();
        if ui.add_enabled(!busy, egui::Button::new("GIF")).on_hover_text("all K*2^n frames as one GIF").clicked() {
            let mut p = PathBuf::from(panel.export_path.trim());
            if p.extension().is_none_or(|e| e != "gif") {
                p.set_extension("gif");
            }
            out.push(Command::Export(ExportTarget::Gif(p), style));
        }
        if ui
            .add_enabled(!busy, egui::Button::new("PNG frames"))
            .on_hover_text("numbered PNGs in a directory")
            .clicked()
        {
            let dir = PathBuf::from(panel.export_path.trim()).with_extension("");
            out.push(Command::Export(ExportTarget::Frames(dir), style));
        }
    });
    if let Some(b) = &doc.jobs.busy.exporting {
        let d = b.done.load(Ordering::Relaxed);
        ui.horizontal(|ui| {
            ui.add(
                egui::ProgressBar::new(d as f32 / b.total.max(1) as f32)
                    .text(format!("{d}/{} frames", b.total))
                    .desired_width(180.0),
            );
            if ui.button("Cancel").clicked() {
                out.push(Command::CancelExport);
            }
        });
    }
    out
}
