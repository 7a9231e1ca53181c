//! The viewer in the page (feature `viewer`): the desktop app's code on a
//! canvas (`subdiv::app::page`). The page's script starts it, hands it the
//! files the user picks, drops or names by URL, and tells it what failed.

use wasm_bindgen::prelude::*;

/// Starts the viewer on `canvas`, with what `query` (the address after
/// `?`: `model`, `level`, `scheme`, `shading`, `backend=webgl2`, `play`)
/// asks for. Returns at once; the device arrives later (WebGPU, else
/// WebGL2), and until then, or where there is none, the page's `#status`
/// element says so.
#[wasm_bindgen(js_name = startViewer)]
pub fn start_viewer(canvas: web_sys::HtmlCanvasElement, query: &str) -> Result<(), JsError> {
    subdiv::app::page::run_in_page(canvas, query).map_err(|e| JsError::new(&e.to_string()))
}

/// Opens the bytes of the file `name` (its extension chooses the format)
/// in the running viewer.
#[wasm_bindgen(js_name = openFile)]
pub fn open_file(name: &str, bytes: Vec<u8>) -> Result<(), JsError> {
    subdiv::app::page::open_bytes(name, bytes).map_err(|e| JsError::new(&e.to_string()))
}

/// Shows `message` as the viewer's error (a fetch of the page failed).
#[wasm_bindgen(js_name = reportProblem)]
pub fn report_problem(message: &str) {
    subdiv::app::page::report_problem(message);
}
