//! `Refiner`: a control mesh refined once, then its control vertices moved
//! and its edges creased as often as wanted, only what an edit reaches
//! evaluated again, with undo and redo (the library's [`subdiv::Refiner`]).

use crate::input::{Cage, Control, Remap, cage, points};
use crate::{Msg, SubdivideOptions, names, thrown};
use wasm_bindgen::prelude::*;

/// A refined mesh that can be edited.
#[wasm_bindgen]
pub struct Refiner {
    inner: subdiv::Refiner,
    remap: Remap,
    /// The library's id of each caller's vertex (`None`: in no face).
    to_library: Vec<Option<u32>>,
    /// The caller's positions, where the library dropped vertices no face
    /// uses (they are carried into `positions` unchanged).
    input: Vec<f32>,
    /// Corners of a finest face (3, or 4 for the polygon schemes).
    sides: u32,
}

/// A library error as a message.
fn msg(e: impl std::fmt::Display) -> Msg {
    e.to_string()
}

impl Refiner {
    fn build(positions: &[f32], indices: &[u32], levels: f64, scheme: &str, o: Option<&JsValue>) -> Result<Self, Msg> {
        let levels = names::levels(levels)?;
        let settings = names::Settings::read(scheme, o)?;
        let Cage { control, remap } = cage(positions, indices, &settings)?;
        let mesh = match control {
            Control::Tri(mesh) => mesh,
            Control::Poly(mesh) => mesh.triangulated(),
        };
        let mut inner = subdiv::Refiner::new(&mesh, settings.scheme, levels, &settings.opts).map_err(msg)?;
        let sides = if inner.polygons().is_some() { 4 } else { 3 };
        // the first edit then costs what later ones do
        inner.prepare_edits();
        let to_library = remap.inverse();
        let input = if remap.kept.is_some() { positions.to_vec() } else { Vec::new() };
        Ok(Refiner { inner, remap, to_library, input, sides })
    }

    /// The library's id of the caller's vertex `i`.
    fn library_id(&self, i: u32) -> Result<u32, Msg> {
        match self.to_library.get(i as usize) {
            Some(Some(j)) => Ok(*j),
            Some(None) => Err(format!("vertex {i} is in no face: moving it changes no surface")),
            None => Err(format!("vertex {i} is not one of the {} vertices", self.remap.n_input)),
        }
    }

    /// The rows the last edit changed, in the caller's numbering.
    fn changed(&self) -> Vec<u32> {
        self.inner.last_changed().iter().map(|&j| self.remap.id(j)).collect()
    }
}

#[wasm_bindgen]
impl Refiner {
    /// Refines the mesh `levels` times with `scheme`; `options` as for
    /// `subdivide`.
    ///
    /// # Errors
    /// As `subdivide`.
    #[wasm_bindgen(constructor)]
    pub fn new(
        positions: &[f32],
        indices: &[u32],
        levels: f64,
        scheme: &str,
        options: Option<SubdivideOptions>,
    ) -> Result<Refiner, JsError> {
        Refiner::build(positions, indices, levels, scheme, options.as_ref().map(|o| o.as_ref())).map_err(thrown)
    }

    /// The finest points, flat `x y z` rows, in the caller's numbering.
    #[wasm_bindgen(getter)]
    pub fn positions(&self) -> Vec<f32> {
        self.remap.positions(self.inner.positions(), &self.input)
    }

    /// The finest faces, flat (`faceSize` corners each), holes left out.
    #[wasm_bindgen(getter)]
    pub fn indices(&self) -> Vec<u32> {
        let (v, holes) = match self.inner.polygons() {
            Some(pt) => (pt.v_table(), pt.holes()),
            None => (self.inner.topology().v_table(), self.inner.topology().holes()),
        };
        let k = self.sides as usize;
        let mut out = Vec::with_capacity(v.len());
        for (f, face) in v.chunks_exact(k).enumerate() {
            if holes.binary_search(&(f as u32)).is_err() {
                out.extend(face.iter().map(|&j| self.remap.id(j)));
            }
        }
        out
    }

    /// Corners of every finest face: 3 (triangle schemes) or 4.
    #[wasm_bindgen(getter, js_name = faceSize)]
    pub fn face_size(&self) -> u32 {
        self.sides
    }

    /// Moves the control vertices `ids` to `to` (flat `x y z` rows, one
    /// per id); returns the finest rows that changed.
    ///
    /// # Errors
    /// An id out of range or in no face, a row count that differs, a
    /// non-finite coordinate.
    #[wasm_bindgen(js_name = "move")]
    pub fn move_vertices(&mut self, ids: &[u32], to: &[f32]) -> Result<Vec<u32>, JsError> {
        let mut run = || -> Result<Vec<u32>, Msg> {
            let to = points(to)?;
            if to.len() != ids.len() {
                return Err(format!("{} ids but {} positions: one x y z row per id", ids.len(), to.len()));
            }
            let lib: Vec<u32> = ids.iter().map(|&i| self.library_id(i)).collect::<Result<_, _>>()?;
            self.inner.move_vertices(&lib, &to).map_err(msg)?;
            Ok(self.changed())
        };
        run().map_err(thrown)
    }

    /// Sets the sharpness of the edge `a`-`b` (0: smooth, 10 or more:
    /// infinitely sharp); returns the finest rows that changed.
    ///
    /// # Errors
    /// A vertex out of range, no such edge, a bad sharpness.
    #[wasm_bindgen(js_name = setSharpness)]
    pub fn set_sharpness(&mut self, a: u32, b: u32, sharpness: f64) -> Result<Vec<u32>, JsError> {
        let mut run = || -> Result<Vec<u32>, Msg> {
            let s = subdiv::mesh::checked_sharpness(sharpness).map_err(|e| format!("edge {a}-{b} has {e}"))?;
            let (la, lb) = (self.library_id(a)?, self.library_id(b)?);
            // the library names its own ids
            let caller = |e: subdiv::Error| msg(e).replace(&format!("{la}-{lb}"), &format!("{a}-{b}"));
            self.inner.set_edge_sharpness(la, lb, s).map_err(caller)?;
            Ok(self.changed())
        };
        run().map_err(thrown)
    }

    /// Undoes the last edit; `false` when there is none.
    pub fn undo(&mut self) -> bool {
        self.inner.undo()
    }

    /// Redoes the last undone edit; `false` when there is none.
    pub fn redo(&mut self) -> bool {
        self.inner.redo()
    }
}
