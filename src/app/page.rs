//! The viewer in a web page (`wasm32-unknown-unknown`): the same [`App`]
//! on a canvas, with what the page does differently from the desktop.
//!
//! - The device comes asynchronously: the window (the canvas) opens at
//!   once, the adapter and device are asked for in a future, and the
//!   answer arrives as [`PageEvent::Connected`]. WebGPU where the browser
//!   has an adapter, WebGL2 otherwise (`backend=webgl2` forces it).
//! - Files come as bytes ([`open_bytes`], called by the page's script for a
//!   file picked, dropped or fetched): [`Command::OpenBytes`].
//! - Recovery copies live in `localStorage` ([`storage_set`]); a save is a
//!   download ([`download`]).
//!
//! Everything else (the panel, the renderer, the commands, the workers'
//! tasks, which run one per frame here) is the desktop's code.

use super::page_query::PageQuery;
use super::surface::SurfaceWrapper;
use super::window::Win;
use super::{App, Command};
use crate::render::{Gpu, Shading};
use crate::{Error, Result};
use std::cell::RefCell;
use std::sync::Arc;
use wasm_bindgen::JsCast;
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, EventLoop, EventLoopProxy};
use winit::platform::web::{EventLoopExtWebSys, WindowAttributesExtWebSys};
use winit::window::{Window, WindowId};

/// What reaches the viewer from outside its event loop.
pub(crate) enum PageEvent {
    /// The device and the configured surface, or why there are none.
    Connected(Box<Result<(Gpu, SurfaceWrapper)>>),
    /// A file's bytes (picked, dropped or fetched by the page).
    Open {
        /// Its name (the extension chooses the format).
        name: String,
        /// Its content.
        bytes: Vec<u8>,
    },
    /// Something the page could not do (a failed fetch), for the panel.
    Problem(String),
}

thread_local! {
    /// The running viewer's mailbox (one viewer per page).
    static PROXY: RefCell<Option<EventLoopProxy<PageEvent>>> = const { RefCell::new(None) };
}

/// Sends `event` to the running viewer; whether there is one.
fn send(event: PageEvent) -> bool {
    PROXY.with_borrow(|p| p.as_ref().is_some_and(|p| p.send_event(event).is_ok()))
}

/// Opens the bytes of a file named `name` in the running viewer (through
/// the same reading pipeline and budget as a file on the desktop).
///
/// # Errors
/// When no viewer runs on the page.
pub fn open_bytes(name: &str, bytes: Vec<u8>) -> Result<()> {
    match send(PageEvent::Open { name: name.to_string(), bytes }) {
        true => Ok(()),
        false => Err(Error::Usage("no viewer runs on this page (start it first)".into())),
    }
}

/// Opens the browser's file picker (the page's `<input type="file"
/// id="file">`, whose change the page's script hands to [`open_bytes`]).
pub(crate) fn pick_file() {
    let input = web_sys::window().and_then(|w| w.document()).and_then(|d| d.get_element_by_id("file"));
    match input.and_then(|i| i.dyn_into::<web_sys::HtmlElement>().ok()) {
        Some(input) => input.click(),
        None => report_problem("this page has no file picker (#file)"),
    }
}

/// Shows `message` as the viewer's error (a fetch the page made failed).
pub fn report_problem(message: &str) {
    send(PageEvent::Problem(message.to_string()));
}

/// The viewer of the page: the desktop's [`App`], the canvas it draws on,
/// and the window while its device is on its way.
struct PageApp {
    app: App,
    canvas: web_sys::HtmlCanvasElement,
    webgl2: bool,
    window: Option<Arc<Window>>,
    /// Frames drawn.
    frames: u64,
    /// The loading notice was taken away (the first frame with a device).
    shown: bool,
}

impl PageApp {
    /// What the viewer shows, as the canvas's `data-` attributes, so that
    /// the page's script and its tests read the state instead of guessing
    /// it: `frames`, `busy`, `model`, `level`, `triangles`, `adapter`,
    /// `error`, `notice`, `unsaved`, `steps` (the undo history's length), `offer` (a
    /// recovery copy is offered), `playing` (the animation), `adaptive` (a
    /// tessellation for the view is drawn).
    fn report(&mut self) {
        let (doc, view) = (&self.app.viewer.doc, &self.app.viewer.view);
        let error = doc.status.error.as_ref().map(|p| p.to_string()).unwrap_or_default();
        let pairs = [
            ("frames", self.frames.to_string()),
            ("busy", doc.busy().to_string()),
            ("model", doc.model.name.clone()),
            ("level", doc.model.made.level.to_string()),
            ("triangles", doc.model.result.shown.mesh.ct.num_triangles().to_string()),
            ("adapter", view.stats.adapter.clone()),
            ("error", error),
            ("notice", doc.status.notice.clone().unwrap_or_default()),
            ("unsaved", doc.edit.history.dirty().to_string()),
            ("steps", doc.edit.history.done.len().to_string()),
            ("offer", doc.edit.offer.to_string()),
            ("playing", doc.anim.playing().to_string()),
            ("adaptive", doc.adaptive_shown().is_some().to_string()),
        ];
        for (k, v) in pairs {
            let _ = self.canvas.set_attribute(&format!("data-{k}"), &v);
        }
        if self.app.win.is_some() && !self.shown {
            self.shown = true;
            show_in_page("");
        }
    }
}

/// Starts the viewer on `canvas` with what `query` (the page's address
/// after `?`) asks for; returns at once, the viewer runs in the page's
/// event loop.
///
/// # Errors
/// A bad address, a bundled model that cannot be read, no event loop.
pub fn run_in_page(canvas: web_sys::HtmlCanvasElement, query: &str) -> Result<()> {
    let q = PageQuery::parse(query)?;
    // a level the cage refuses (the built-in one past the budget: a file's
    // model clamps its level to what fits) opens at level 0 and says why
    let mut app = match App::new(q.view_options()) {
        Ok(app) => app,
        Err(e) => {
            let mut app = App::new(super::ViewOptions { level: 0, ..q.view_options() })?;
            app.viewer.doc.fail(e.into());
            app
        }
    };
    if let Some(name) = q.unknown_model() {
        let known: Vec<&str> = crate::bundled::MODELS.iter().map(|m| m.file_name).collect();
        let why = format!("no bundled model {name} (a URL needs / or a scheme); bundled: {}", known.join(", "));
        app.viewer.doc.fail(Error::Usage(why).into());
    }
    if let Some(look) = q.shading.map(Shading::look) {
        app.viewer.doc.display.surface = look.surface;
        app.viewer.doc.display.wireframe = look.wireframe;
        app.viewer.doc.reshade();
    }
    let event_loop = EventLoop::<PageEvent>::with_user_event()
        .build()
        .map_err(|e| Error::Gpu(format!("no event loop in this page: {e}")))?;
    PROXY.set(Some(event_loop.create_proxy()));
    event_loop.spawn_app(PageApp { app, canvas, webgl2: q.webgl2, window: None, frames: 0, shown: false });
    Ok(())
}

/// The adapter, the device and the surface on `window` (WebGPU where the
/// browser gives an adapter, else WebGL2).
async fn connect(window: Arc<Window>, webgl2: bool) -> Result<(Gpu, SurfaceWrapper)> {
    let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
    desc.backends = if webgl2 { wgpu::Backends::GL } else { wgpu::Backends::BROWSER_WEBGPU | wgpu::Backends::GL };
    let instance = wgpu::util::new_instance_with_webgpu_detection(desc).await;
    let surface = instance
        .create_surface(window.clone())
        .map_err(|e| Error::Gpu(format!("this browser gives the page neither WebGPU nor WebGL2: {e}")))?;
    let gpu = Gpu::with_instance(instance, Some(&surface)).await?;
    let size = window.inner_size();
    let surface = SurfaceWrapper::new(surface, &gpu, size.width, size.height)?;
    Ok((gpu, surface))
}

impl ApplicationHandler<PageEvent> for PageApp {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.window.is_some() {
            return;
        }
        let attrs = Window::default_attributes().with_canvas(Some(self.canvas.clone())).with_prevent_default(true);
        let window = match event_loop.create_window(attrs) {
            Ok(w) => Arc::new(w),
            Err(e) => return self.app.viewer.doc.fail(Error::Gpu(format!("cannot use the canvas: {e}")).into()),
        };
        self.window = Some(window.clone());
        let webgl2 = self.webgl2;
        wasm_bindgen_futures::spawn_local(async move {
            let connected = connect(window, webgl2).await;
            send(PageEvent::Connected(Box::new(connected)));
        });
    }

    fn user_event(&mut self, _: &ActiveEventLoop, event: PageEvent) {
        let viewer = &mut self.app.viewer;
        match event {
            PageEvent::Connected(connected) => {
                let Some(window) = self.window.clone() else { return };
                match connected.and_then(|(gpu, surface)| Win::from_parts(window.clone(), gpu, surface, viewer)) {
                    Ok(win) => self.app.win = Some(win),
                    Err(e) => show_in_page(&format!("subdiv cannot draw here: {e}")),
                }
                window.request_redraw();
            }
            PageEvent::Open { name, bytes } => viewer.apply(Command::OpenBytes { name, bytes: bytes.into() }),
            PageEvent::Problem(message) => viewer.doc.fail(Error::Usage(message).into()),
        }
        if let Some(w) = &self.window {
            w.request_redraw();
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, id: WindowId, event: WindowEvent) {
        let redraw = matches!(event, WindowEvent::RedrawRequested);
        if let (true, Some(e)) = (redraw, self.app.fatal.take()) {
            self.app.viewer.doc.fail(e.into());
        }
        // the canvas's first sizes arrive before its device: follow it here
        if let (true, Some(win), Some(w)) = (redraw, &mut self.app.win, &self.window) {
            let size = w.inner_size();
            win.resize(size.width, size.height);
        }
        ApplicationHandler::<()>::window_event(&mut self.app, event_loop, id, event);
        if redraw {
            self.frames += 1;
            self.report();
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        ApplicationHandler::<()>::about_to_wait(&mut self.app, event_loop);
    }

    fn new_events(&mut self, event_loop: &ActiveEventLoop, cause: winit::event::StartCause) {
        ApplicationHandler::<()>::new_events(&mut self.app, event_loop, cause);
    }
}

/// Puts `message` where the canvas would draw (no device: no panel either),
/// in the element `#status` when the page has one, and in the console.
fn show_in_page(message: &str) {
    if !message.is_empty() {
        web_sys::console::error_1(&message.into());
    }
    let status = web_sys::window().and_then(|w| w.document()).and_then(|d| d.get_element_by_id("status"));
    if let Some(el) = status {
        el.set_text_content(Some(message));
        let _ = el.set_attribute("data-state", if message.is_empty() { "ready" } else { "error" });
    }
}

/// The page's `localStorage`, where there is one.
fn storage() -> Option<web_sys::Storage> {
    web_sys::window()?.local_storage().ok()?
}

/// The stored value of `key`.
pub(crate) fn storage_get(key: &str) -> Option<String> {
    storage()?.get_item(key).ok()?
}

/// Stores `value` as `key`.
///
/// # Errors
/// No storage, or the browser refuses (its quota, about 5 MB a site).
pub(crate) fn storage_set(key: &str, value: &str) -> Result<()> {
    let store = storage().ok_or_else(|| Error::Usage("this page has no local storage".into()))?;
    store.set_item(key, value).map_err(|e| Error::Usage(format!("the browser refused to store {key}: {e:?}")))
}

/// Forgets `key`.
pub(crate) fn storage_remove(key: &str) {
    if let Some(s) = storage() {
        let _ = s.remove_item(key);
    }
}

/// Hands `bytes` to the browser as a download named `name`.
///
/// # Errors
/// When the page has no document or the browser refuses the blob.
pub(crate) fn download(name: &str, bytes: &[u8]) -> Result<()> {
    let fail = |what: &str| Error::Usage(format!("cannot download {name}: {what}"));
    let doc = web_sys::window().and_then(|w| w.document()).ok_or_else(|| fail("no document"))?;
    let parts = js_sys::Array::of1(&js_sys::Uint8Array::from(bytes));
    let blob = web_sys::Blob::new_with_u8_array_sequence(&parts).map_err(|_| fail("no blob"))?;
    let url = web_sys::Url::create_object_url_with_blob(&blob).map_err(|_| fail("no object URL"))?;
    let a: web_sys::HtmlAnchorElement =
        doc.create_element("a").ok().and_then(|e| e.dyn_into().ok()).ok_or_else(|| fail("no link element"))?;
    a.set_href(&url);
    a.set_download(name);
    a.click();
    let _ = web_sys::Url::revoke_object_url(&url);
    Ok(())
}
