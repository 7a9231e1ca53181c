//! The subdiv library as a JavaScript package: `subdivide`, `limit`,
//! `load` and the `Refiner`, compiled to WebAssembly by wasm-bindgen.
//!
//! Every entry takes typed arrays (`Float32Array` positions, `Uint32Array`
//! indices), checks them with the library's own validation (the same as the
//! command line's and Python's) and hands the work to the library in
//! single precision. Every refusal reaches JavaScript as an `Error` with the
//! library's message; nothing here panics on any input, and a panic (a bug)
//! is reported on the console by the hook [`start`] sets before the module
//! traps.
//!
//! Without threads (`wasm32-unknown-unknown`) rayon's global pool runs
//! every parallel loop on the calling thread.

mod input;
mod names;
mod refiner;
#[cfg(feature = "viewer")]
mod viewer;

use input::{Cage, Control};
use js_sys::{Float32Array, Object, Reflect, Uint32Array};
use subdiv::io::{ReadOptions, Source, Topology};
use subdiv::mesh::PolyMesh;
use wasm_bindgen::prelude::*;

pub use refiner::Refiner;

#[wasm_bindgen(typescript_custom_section)]
const TS_TYPES: &'static str = r#"
/** Options of `subdivide`, `limit` and `new Refiner` (the names and values of the command line and of Python's `subdiv.subdivide`). */
export interface SubdivideOptions {
  /** Corners of each face when `indices` holds polygons (catmull-clark, bilinear); without it, triangles. */
  faceSizes?: Uint32Array | number[];
  /** Loop's vertex weights: "loop" (default) or "warren". */
  beta?: string;
  /** "edge" (default), "edge-and-corner" or "none". */
  boundary?: string;
  /** Face-varying interpolation: "corners-only" (default), "none", "corners-plus1", "corners-plus2", "boundaries", "all". */
  fvar?: string;
  /** Catmull-Clark on triangles: "catmark" (default) or "smooth". */
  triangles?: string;
  /** How semi-sharp creases decay: "uniform" (default) or "chaikin". */
  creasing?: string;
  /** Creased edges: vertex pairs (flat, two per edge) and one sharpness per edge (10 or more: infinitely sharp). */
  creases?: { edges: Uint32Array | number[]; sharpness: Float32Array | number[] };
  /** Faces (their rank in the input) left out of the surface. */
  holes?: Uint32Array | number[];
  /** Most bytes the library may use (default 2 GiB, half the wasm32 address space). */
  maxMemory?: number;
}

/** A refined mesh: flat xyz rows, flat face corners, and for the polygon schemes each face's corner count. */
export interface Mesh {
  positions: Float32Array;
  indices: Uint32Array;
  faceSizes?: Uint32Array;
}

/** What `load` read: the faces as polygons (`indices` + `faceSizes`, when not all triangles) and as triangles. */
export interface Loaded extends Mesh {
  triangles: Uint32Array;
  /** The creased edges the file tags, as `subdivide` takes them. */
  creases?: { edges: Uint32Array; sharpness: Float32Array };
  /** The faces the file marks as holes (ranks in `faceSizes` when polygonal, else triangles). */
  holes?: Uint32Array;
  warnings: string[];
}

/** Loop limit positions and unit normals, flat xyz rows, one per input vertex. */
export interface Limit {
  positions: Float32Array;
  normals: Float32Array;
}
"#;

#[wasm_bindgen]
extern "C" {
    /// The options object (checked by [`names::Settings::read`]).
    #[wasm_bindgen(typescript_type = "SubdivideOptions")]
    pub type SubdivideOptions;
    #[wasm_bindgen(typescript_type = "Mesh")]
    pub type MeshResult;
    #[wasm_bindgen(typescript_type = "Loaded")]
    pub type LoadedResult;
    #[wasm_bindgen(typescript_type = "Limit")]
    pub type LimitResult;
    #[wasm_bindgen(js_namespace = console, js_name = error)]
    fn console_error(s: &str);
    #[wasm_bindgen(js_namespace = performance, js_name = now)]
    fn performance_now() -> f64;
}

/// A library message as the JavaScript `Error` thrown.
pub(crate) type Msg = String;

/// The `Error` thrown for `m`, the command line's flag named as the option
/// this package takes.
pub(crate) fn thrown(m: Msg) -> JsError {
    JsError::new(&m.replace("--max-memory", "options.maxMemory"))
}

/// Reports a panic (a bug: every input is checked) on the console before
/// the module traps; the trap itself reaches JavaScript as a
/// `WebAssembly.RuntimeError`.
#[wasm_bindgen(start)]
pub fn start() {
    std::panic::set_hook(Box::new(|info| {
        console_error(&format!("internal error (a bug in subdiv, please report it): {info}"));
    }));
}

/// The library's version.
#[wasm_bindgen]
pub fn version() -> String {
    env!("CARGO_PKG_VERSION").to_string()
}

/// Subdivides the mesh `levels` times with `scheme` ("loop", "midpoint",
/// "butterfly", "modified-butterfly", "jarek", "catmull-clark",
/// "bilinear"). Row `i` of the result's positions is the refined input
/// vertex `i`; vertices no face uses are carried unchanged.
///
/// # Errors
/// An `Error` with the library's message for a mesh it refuses (naming
/// the face, vertex or edge), an unknown name, a level count past memory.
#[wasm_bindgen(unchecked_return_type = "Mesh")]
pub fn subdivide(
    positions: &[f32],
    indices: &[u32],
    levels: f64,
    scheme: &str,
    options: Option<SubdivideOptions>,
) -> Result<MeshResult, JsError> {
    let mesh = refine(positions, indices, levels, scheme, options.as_ref()).map_err(thrown)?;
    Ok(mesh.to_js().unchecked_into())
}

/// The refined mesh in the caller's numbering.
pub(crate) struct Refined {
    pub positions: Vec<f32>,
    pub indices: Vec<u32>,
    pub face_sizes: Option<Vec<u32>>,
}

impl Refined {
    /// As a JavaScript object `{positions, indices, faceSizes?}`.
    fn to_js(&self) -> Object {
        let o = Object::new();
        set(&o, "positions", &Float32Array::from(&self.positions[..]));
        set(&o, "indices", &Uint32Array::from(&self.indices[..]));
        if let Some(s) = &self.face_sizes {
            set(&o, "faceSizes", &Uint32Array::from(&s[..]));
        }
        o
    }
}

/// `o[key] = value` (a plain object: cannot fail).
pub(crate) fn set(o: &Object, key: &str, value: &JsValue) {
    let _ = Reflect::set(o, &JsValue::from_str(key), value);
}

fn refine(
    positions: &[f32],
    indices: &[u32],
    levels: f64,
    scheme: &str,
    options: Option<&SubdivideOptions>,
) -> Result<Refined, Msg> {
    let levels = names::levels(levels)?;
    let settings = names::Settings::read(scheme, options.map(|o| o.as_ref()))?;
    let Cage { control, remap } = input::cage(positions, indices, &settings)?;
    // the library chooses the path (faces alone wherever they do), writing
    // the caller's ids in the split
    let model = subdiv::Model {
        control: match &control {
            Control::Tri(mesh) => subdiv::Control::Triangles(mesh),
            Control::Poly(mesh) => subdiv::Control::Polygons(mesh),
        },
        attrs: &subdiv::mesh::Attributes::default(),
        precise: None,
    };
    let dest = subdiv::Destination { faces: subdiv::FacesOnly::Always, ..Default::default() };
    let how = subdiv::Refinement { scheme: settings.scheme, levels, opts: settings.opts, f64: false, dest };
    let fine = subdiv::subdivide_model_as(&model, &how, |j| remap.id(j)).map_err(|e| e.to_string())?;
    match fine.surface {
        subdiv::Surface::Faces(f) => {
            let face_sizes =
                matches!(control, Control::Poly(_)).then(|| vec![f.sides as u32; f.corners.len() / f.sides.max(1)]);
            Ok(Refined { positions: remap.positions(&f.positions, positions), indices: f.corners, face_sizes })
        }
        // a polygon scheme's control mesh as it is (its faces of any size)
        subdiv::Surface::Polygons(mesh) => Ok(input::polygons(&mesh, &remap, positions)),
        subdiv::Surface::Triangles(_) | subdiv::Surface::FacesF64(_) => {
            Err("internal error: f32 faces were asked for and not given".into())
        }
    }
}

/// Loop limit positions and unit normals of every vertex (a vertex no face
/// uses keeps its position, normal zero); `options` as for [`subdivide`]
/// (beta, boundary, creases, holes).
///
/// # Errors
/// As [`subdivide`].
#[wasm_bindgen(unchecked_return_type = "Limit")]
pub fn limit(positions: &[f32], indices: &[u32], options: Option<SubdivideOptions>) -> Result<LimitResult, JsError> {
    let run = || -> Result<Object, Msg> {
        let settings = names::Settings::read("loop", options.as_ref().map(|o| o.as_ref()))?;
        let Cage { control, remap } = input::cage(positions, indices, &settings)?;
        let Control::Tri(mesh) = control else { return Err("Loop built a polygon table (a bug)".into()) };
        let ct = subdiv::rules::with_boundary_corners(&mesh.ct, settings.opts.boundary).into_owned();
        let mesh = subdiv::Mesh { ct, positions: mesh.positions };
        let normals = subdiv::eval::loop_limit_normals(&mesh);
        let limit = subdiv::eval::loop_limit_positions_with(&mesh, settings.opts.loop_beta);
        let o = Object::new();
        set(&o, "positions", &Float32Array::from(&remap.positions(&limit, positions)[..]));
        let zeros = vec![0.0; positions.len()];
        set(&o, "normals", &Float32Array::from(&remap.positions(&normals, &zeros)[..]));
        Ok(o)
    };
    Ok(run().map_err(thrown)?.unchecked_into())
}

/// Reads a mesh file given as bytes, in any format the library reads
/// (OBJ, PLY, OFF, STL, glTF/GLB, COLLADA, USD, ...), the extension of
/// `fileName` choosing the format. The files it names (materials,
/// textures, buffers) cannot be reached and are skipped with a warning
/// where the format allows.
///
/// # Errors
/// An `Error` with the reader's message (file, line or element, problem).
#[wasm_bindgen(unchecked_return_type = "Loaded")]
pub fn load(bytes: &[u8], #[wasm_bindgen(js_name = fileName)] file_name: &str) -> Result<LoadedResult, JsError> {
    let opts = ReadOptions { topology: Topology::Refuse, attributes: false, ..ReadOptions::default() };
    let source = Source::Bytes { bytes, name: file_name, folder: None };
    let loaded = subdiv::io::read(source, &opts).map_err(|e| JsError::new(&e.to_string()))?;
    let mesh = &loaded.mesh;
    let o = Object::new();
    set(&o, "positions", &Float32Array::from(bytemuck_flat(&mesh.positions)));
    set(&o, "triangles", &Uint32Array::from(mesh.triangles()));
    let poly = PolyMesh::is_polygonal(mesh).then(|| PolyMesh::from_mesh(mesh));
    if let Some(pm) = &poly {
        let sizes: Vec<u32> = (0..pm.pt.num_faces() as u32).map(|f| pm.pt.face_size(f)).collect();
        set(&o, "indices", &Uint32Array::from(pm.pt.v_table()));
        set(&o, "faceSizes", &Uint32Array::from(&sizes[..]));
    } else {
        set(&o, "indices", &Uint32Array::from(mesh.triangles()));
    }
    let holes = poly.as_ref().map_or(mesh.ct.holes(), |pm| pm.pt.holes());
    if !holes.is_empty() {
        set(&o, "holes", &Uint32Array::from(holes));
    }
    if let Some(tags) = mesh.ct.sharpness().map(|s| s.to_tags(&mesh.ct)).filter(|t| !t.creases.is_empty()) {
        let edges: Vec<u32> = tags.creases.iter().flat_map(|c| [c.v0, c.v1]).collect();
        let sharpness: Vec<f32> = tags.creases.iter().map(|c| c.sharpness).collect();
        let c = Object::new();
        set(&c, "edges", &Uint32Array::from(&edges[..]));
        set(&c, "sharpness", &Float32Array::from(&sharpness[..]));
        set(&o, "creases", &c);
    }
    let warnings = js_sys::Array::new();
    for w in &loaded.warnings {
        warnings.push(&JsValue::from_str(w));
    }
    set(&o, "warnings", &warnings);
    Ok(o.unchecked_into())
}

/// Points as flat `x y z` values.
pub(crate) fn bytemuck_flat(points: &[glam::Vec3]) -> &[f32] {
    bytemuck::cast_slice(points)
}

/// Milliseconds of the library's subdivision alone, as the command line's
/// `subdivide_ms` times it: the cage built before the clock starts, the
/// result dropped after it stops, nothing copied to JavaScript. For
/// `web/bench.mjs`; not in the typings.
///
/// # Errors
/// As [`subdivide`].
#[wasm_bindgen(js_name = _subdivideMs, skip_typescript)]
pub fn subdivide_ms(positions: &[f32], indices: &[u32], levels: f64, scheme: &str) -> Result<f64, JsError> {
    let levels = names::levels(levels).map_err(thrown)?;
    let s = names::Settings::read(scheme, None).map_err(thrown)?;
    let Cage { control, .. } = input::cage(positions, indices, &s).map_err(thrown)?;
    let t0 = performance_now();
    let fine = match &control {
        Control::Tri(m) => subdiv::subdivide_faces(m, s.scheme, levels, &s.opts, |j| j),
        Control::Poly(m) => subdiv::subdivide_faces(m, s.scheme, levels, &s.opts, |j| j),
    };
    let ms = performance_now() - t0;
    fine.map_err(|e| thrown(e.to_string()))?;
    Ok(ms)
}
