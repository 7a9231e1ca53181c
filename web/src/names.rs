//! The options object JavaScript passes, read and checked: the names are
//! parsed by the library's own `FromStr` (the command line's and Python's
//! names, the error listing the known ones), the arrays copied once.

use crate::Msg;
use js_sys::{Array, Float32Array, Object, Reflect, Uint32Array};
use subdiv::clean_error as clean;
use subdiv::mesh::{BoundaryInterpolation, Creasing, TriangleSubdivision, UvInterpolation};
use subdiv::{LoopBeta, Options, Scheme};
use wasm_bindgen::{JsCast, JsValue};

/// The keys an options object may have.
const KEYS: [&str; 9] =
    ["faceSizes", "beta", "boundary", "fvar", "triangles", "creasing", "creases", "holes", "maxMemory"];

/// Bytes the library may use unless `maxMemory` says otherwise: half of
/// wasm32's 4 GiB address space.
pub const DEFAULT_MAX_MEMORY: u64 = 2 << 30;

/// What the scheme name and the options object say.
pub struct Settings {
    /// The scheme.
    pub scheme: Scheme,
    /// The library's options.
    pub opts: Options,
    /// Corners of each face (`None`: triangles).
    pub face_sizes: Option<Vec<u32>>,
    /// Creases `(v0, v1, sharpness)`, checked by the library.
    pub creases: Vec<(u32, u32, f32)>,
    /// Faces left out.
    pub holes: Vec<u32>,
}

/// `name` parsed as a `T` by the library (a hostile name shortened in the
/// message).
fn parse<T: std::str::FromStr<Err = String>>(name: &str) -> Result<T, Msg> {
    name.parse::<T>().map_err(|e| e.replace(name, &clean(name, 40)))
}

/// The level count: a whole number from 0 up.
///
/// # Errors
/// A negative, fractional or non-finite number.
pub fn levels(levels: f64) -> Result<u32, Msg> {
    if levels.is_finite() && levels >= 0.0 && levels.fract() == 0.0 && levels <= f64::from(u32::MAX) {
        Ok(levels as u32)
    } else {
        Err(format!("levels must be a whole number from 0 up, got {levels}"))
    }
}

impl Settings {
    /// The settings of `scheme` and the options object `o` (`None` or
    /// `undefined`: every default).
    ///
    /// # Errors
    /// An unknown scheme, key or name, a value of the wrong type.
    pub fn read(scheme: &str, o: Option<&JsValue>) -> Result<Settings, Msg> {
        let scheme = parse::<Scheme>(scheme)?;
        let o = match o {
            Some(v) if !v.is_undefined() && !v.is_null() => v,
            _ => return Ok(Settings::defaults(scheme)),
        };
        if !o.is_object() {
            return Err("options must be an object".into());
        }
        for key in Object::keys(o.unchecked_ref::<Object>()).iter() {
            let key = key.as_string().unwrap_or_default();
            if !KEYS.contains(&key.as_str()) {
                return Err(format!("unknown option {:?}; the options are {}", clean(&key, 40), KEYS.join(", ")));
            }
        }
        let name = |key: &str, default: &str| -> Result<String, Msg> {
            match get(o, key) {
                v if v.is_undefined() => Ok(default.to_string()),
                v => v.as_string().ok_or_else(|| format!("options.{key} must be a string")),
            }
        };
        let max_memory = match get(o, "maxMemory") {
            v if v.is_undefined() => DEFAULT_MAX_MEMORY,
            v => match v.as_f64() {
                Some(b) if b.is_finite() && b >= 0.0 => b as u64,
                _ => return Err("options.maxMemory must be a number of bytes".into()),
            },
        };
        let opts = Options {
            loop_beta: parse::<LoopBeta>(&name("beta", "loop")?)?,
            boundary: parse::<BoundaryInterpolation>(&name("boundary", "edge")?)?,
            uv: parse::<UvInterpolation>(&name("fvar", "corners-only")?)?,
            triangles: parse::<TriangleSubdivision>(&name("triangles", "catmark")?)?,
            creasing: parse::<Creasing>(&name("creasing", "uniform")?)?,
            max_memory: Some(max_memory),
            ..Options::default()
        };
        let face_sizes = optional(o, "faceSizes", u32s)?;
        let holes = optional(o, "holes", u32s)?.unwrap_or_default();
        let creases = optional(o, "creases", creases)?.unwrap_or_default();
        Ok(Settings { scheme, opts, face_sizes, creases, holes })
    }

    /// Every default.
    fn defaults(scheme: Scheme) -> Settings {
        let opts = Options { max_memory: Some(DEFAULT_MAX_MEMORY), ..Options::default() };
        Settings { scheme, opts, face_sizes: None, creases: Vec::new(), holes: Vec::new() }
    }
}

/// `o[key]` (`undefined` when missing or unreadable).
fn get(o: &JsValue, key: &str) -> JsValue {
    Reflect::get(o, &JsValue::from_str(key)).unwrap_or(JsValue::UNDEFINED)
}

/// `o[key]` read by `f`, `None` when absent.
fn optional<T>(o: &JsValue, key: &str, f: impl Fn(&JsValue, &str) -> Result<T, Msg>) -> Result<Option<T>, Msg> {
    match get(o, key) {
        v if v.is_undefined() || v.is_null() => Ok(None),
        v => f(&v, key).map(Some),
    }
}

/// A `Uint32Array` or an array of whole numbers in `u32`.
fn u32s(v: &JsValue, what: &str) -> Result<Vec<u32>, Msg> {
    if let Some(a) = v.dyn_ref::<Uint32Array>() {
        return Ok(a.to_vec());
    }
    let Some(a) = v.dyn_ref::<Array>() else { return Err(format!("{what} must be a Uint32Array or an array")) };
    a.iter()
        .enumerate()
        .map(|(k, x)| match x.as_f64() {
            Some(n) if n >= 0.0 && n.fract() == 0.0 && n <= f64::from(u32::MAX) => Ok(n as u32),
            _ => Err(format!("{what}[{k}] must be a whole number from 0 up")),
        })
        .collect()
}

/// A `Float32Array` or an array of numbers.
fn f32s(v: &JsValue, what: &str) -> Result<Vec<f64>, Msg> {
    if let Some(a) = v.dyn_ref::<Float32Array>() {
        return Ok(a.to_vec().into_iter().map(f64::from).collect());
    }
    let Some(a) = v.dyn_ref::<Array>() else { return Err(format!("{what} must be a Float32Array or an array")) };
    a.iter().enumerate().map(|(k, x)| x.as_f64().ok_or_else(|| format!("{what}[{k}] must be a number"))).collect()
}

/// `{edges, sharpness}`: two vertex ids and one sharpness per crease, the
/// sharpness checked by the library.
fn creases(v: &JsValue, what: &str) -> Result<Vec<(u32, u32, f32)>, Msg> {
    let edges = optional(v, "edges", |v, _| u32s(v, "creases.edges"))?;
    let sharpness = optional(v, "sharpness", |v, _| f32s(v, "creases.sharpness"))?;
    let (Some(edges), Some(sharpness)) = (edges, sharpness) else {
        return Err(format!("{what} must be {{ edges, sharpness }}"));
    };
    if edges.len() != 2 * sharpness.len() {
        return Err(format!("{} crease edges but {} sharpness values", edges.len() as f64 / 2.0, sharpness.len()));
    }
    let mut out = Vec::with_capacity(sharpness.len());
    for (k, (e, &s)) in edges.chunks_exact(2).zip(&sharpness).enumerate() {
        let s = subdiv::mesh::checked_sharpness(s).map_err(|e| format!("crease {k} has {e}"))?;
        out.push((e[0], e[1], s));
    }
    Ok(out)
}
