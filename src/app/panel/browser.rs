//! A small file browser window for "Browse…".

use super::PanelState;
use crate::app::command::Command;
use egui::{Color32, RichText};
use std::path::{Path, PathBuf};

/// Whether the viewer opens `p` (a model or curve file of any format the
/// readers know, [`crate::io::FORMATS`]).
pub(crate) fn opens(p: &Path) -> bool {
    crate::io::Format::by_extension(p).is_some()
}

/// The browser window while it is open: folders to walk into, model files to open.
pub(crate) fn file_browser(ctx: &egui::Context, panel: &mut PanelState) -> Option<Command> {
    let dir = panel.browser.clone()?;
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
        egui::ScrollArea::vertical().max_height(340.0).show(ui, |ui| list_folder(ui, &dir, &mut next, &mut chosen));
    });
    let command = chosen.map(|p| {
        panel.open_path = p.display().to_string();
        open = false;
        Command::Open(p)
    });
    panel.browser = if open { Some(next.unwrap_or(dir)) } else { None };
    command
}

/// The entries of `dir`, folders first, hidden ones left out.
fn list_folder(ui: &mut egui::Ui, dir: &Path, next: &mut Option<PathBuf>, chosen: &mut Option<PathBuf>) {
    let rd = match std::fs::read_dir(dir) {
        Ok(rd) => rd,
        Err(e) => {
            ui.label(RichText::new(format!("cannot list: {e}")).color(Color32::from_rgb(255, 110, 90)));
            return;
        }
    };
    let mut entries: Vec<PathBuf> = rd.filter_map(|e| e.ok().map(|e| e.path())).collect();
    entries.sort_by_key(|p| (!p.is_dir(), p.file_name().map(|n| n.to_ascii_lowercase())));
    for p in entries {
        let name = p.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        if name.starts_with('.') {
            continue;
        }
        if p.is_dir() {
            if ui.selectable_label(false, format!("[dir] {name}/")).clicked() {
                *next = Some(p);
            }
        } else if opens(&p) && ui.selectable_label(false, name).clicked() {
            *chosen = Some(p);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::opens;
    use std::path::Path;

    #[test]
    fn the_browser_lists_every_readable_format_in_any_case() {
        for f in ["a.obj", "a.ct", "a.bez", "a.bzc", "a.ply", "a.STL", "a.off", "a.gltf", "a.Glb", "a.dae"] {
            assert!(opens(Path::new(f)), "{f}");
        }
        for f in ["a.png", "a", "a.paths", "a.mtl"] {
            assert!(!opens(Path::new(f)), "{f}");
        }
    }
}
