//! Reading a stage's Mesh prims into one [`RawMesh`]: each prim's points
//! (at the time read) through its world transform, its faces (reversed for
//! `leftHanded`, and for a mirroring transform), creases, corners, holes,
//! `st` per corner and `displayColor` per vertex or face; each prim one
//! material group (one per colour where its colours are per face) and one
//! prim of the [`Scene`] with its own options and transform, the first
//! prim's options the mesh's.

use super::stage::{Confined, guarded};
use crate::io::Input;
use crate::io::raw::{RawMesh, format_err};
use crate::mesh::attributes::{Material, UvInterpolation};
use crate::mesh::options::{FileScheme, ShapeOptions, TriangleSubdivision};
use crate::mesh::scene::{self, Scene, UpAxis};
use crate::mesh::sharpness::{BoundaryInterpolation, CornerTag, CreaseTag};
use crate::{Error, Result};
use glam::{DMat4, DVec3, Vec2, Vec3};
use openusd::schemas::geom;
use openusd::sdf::Value;
use openusd::usd::{PrimPredicate, Stage};

/// Reads every Mesh prim of the stage in `input`.
///
/// # Errors
/// One line naming the file and the prim or layer: a refused reference, a
/// cycle, a file the crate cannot read, a prim with bad topology, over the
/// budget.
pub(super) fn read(input: &Input, folder: Option<&std::path::Path>) -> Result<RawMesh> {
    if input.bytes.starts_with(openusd::usdc::MAGIC) {
        super::stage::check_crate(input.bytes, input.file)?;
    }
    let refs = Confined::new(input, folder);
    let file = input.file;
    let outcome = guarded(file, || {
        let stage = Stage::builder()
            .resolver(refs.clone())
            .open(refs.root_id())
            .map_err(|e| format_err(file, "stage", format!("{e:#}")));
        let stage = match (stage, refs.refusal()) {
            (_, Some(e)) => return Err(e),
            (s, None) => s?,
        };
        let raw = meshes(&stage, input)?;
        if let Some(e) = refs.refusal() {
            return Err(e);
        }
        if let Some(e) = stage.composition_errors().first() {
            return Err(format_err(file, "stage", e.to_string()));
        }
        Ok(raw)
    });
    // a refusal recorded on the way says more than the crate's own error
    outcome.map_err(|e| refs.refusal().unwrap_or(e))
}

/// Every Mesh prim of `stage` (instances expanded), in namespace order,
/// joined, with the scene: each prim's options and transform, the stage's
/// units and axis, the time the points were read at and the times they
/// are sampled at.
fn meshes(stage: &Stage, input: &Input) -> Result<RawMesh> {
    let file = input.file;
    let usd = |e: anyhow::Error| format_err(file, "stage", format!("{e:#}"));
    let mut paths = Vec::new();
    let mut visits = 0u64;
    // instance proxies: an instanceable prim's meshes are read under its own path
    stage
        .traverse(PrimPredicate::DEFAULT_PROXIES, |p| {
            visits += 1;
            paths.push(p.clone());
        })
        .map_err(usd)?;
    input.budget.check("node-visits", visits, file, "prims")?;
    let mut found = Vec::new();
    for path in paths {
        if geom::PointInstancer::get(stage, path.clone()).map_err(usd)?.is_some() {
            let at = crate::error::clean(path.as_str(), 80);
            return Err(format_err(
                file,
                format!("prim {at}"),
                "a PointInstancer, whose instances are not read (expand them into meshes, or leave the prim out)",
            ));
        }
        if let Some(mesh) = geom::Mesh::get(stage, path.clone()).map_err(usd)? {
            found.push((path, mesh));
        }
    }
    if found.is_empty() {
        return Err(format_err(file, "stage", "no Mesh prim"));
    }
    let times = sample_times(&found, input)?;
    let time = input.time.or_else(|| (!times.is_empty()).then(|| first_frame(stage, &times)));
    let mut raw = RawMesh::default();
    let mut scene = Scene { time, times, ..Default::default() };
    for (path, mesh) in &found {
        let at = format!("prim {}", crate::error::clean(path.as_str(), 80));
        let prim = Prim { mesh, stage, file, at: &at, time, start: stage.start_time_code() };
        let read = prim.append(&mut raw, input)?;
        let id = scene.prims.len() as u32;
        let groups = read.groups.len();
        for (k, c) in read.groups.into_iter().enumerate() {
            let mut m = Material::named(path.as_str());
            if let Some(c) = c {
                m.diffuse = c;
                if groups > 1 {
                    m.name = format!("{} color {k}", path.as_str());
                }
            }
            raw.material_list.push(m);
            scene.prim_of.push(id);
        }
        scene.prims.push(read.prim);
    }
    raw.options = scene.prims[0].options;
    (scene.up_axis, scene.meters_per_unit) = stage_units(stage, file)?;
    raw.scene = Some(scene);
    Ok(raw)
}

/// The time codes at which any prim's points are sampled, sorted.
fn sample_times(found: &[(openusd::sdf::Path, geom::Mesh)], input: &Input) -> Result<Vec<f64>> {
    let mut times = Vec::new();
    for (path, mesh) in found {
        let t = mesh.attribute("points").time_sample_times();
        let t = t.map_err(|e| format_err(input.file, format!("prim {}", path.as_str()), format!("points: {e:#}")))?;
        times.extend(t.into_iter().filter(|t| t.is_finite()));
        input.budget.check("node-visits", times.len() as u64, input.file, "time samples")?;
    }
    times.sort_by(f64::total_cmp);
    times.dedup();
    Ok(times)
}

/// The frame a stage opens at: its `startTimeCode` where the stage
/// states a time range, else its first sample (as usdview does).
fn first_frame(stage: &Stage, times: &[f64]) -> f64 {
    match stage.has_authored_time_code_range() {
        true => stage.start_time_code(),
        false => times[0],
    }
}

/// The stage's `upAxis` and `metersPerUnit`, where stated.
fn stage_units(stage: &Stage, file: &str) -> Result<(Option<UpAxis>, Option<f64>)> {
    let meta = |name: &str| stage.stage_metadata(name).map_err(|e| format_err(file, "stage", format!("{name}: {e:#}")));
    let up = match meta("upAxis")? {
        Some(Value::Token(t)) if t.as_str() == "Y" => Some(UpAxis::Y),
        Some(Value::Token(t)) if t.as_str() == "Z" => Some(UpAxis::Z),
        Some(Value::String(t)) if t == "Y" => Some(UpAxis::Y),
        Some(Value::String(t)) if t == "Z" => Some(UpAxis::Z),
        None => None,
        Some(other) => return Err(format_err(file, "stage", format!("upAxis {other:?} is neither Y nor Z"))),
    };
    let meters = match meta("metersPerUnit")? {
        None => None,
        Some(v) => match v.try_as_double() {
            Some(m) if m.is_finite() && m > 0.0 => Some(m),
            _ => return Err(format_err(file, "stage", "metersPerUnit is not a positive number")),
        },
    };
    Ok((up, meters))
}

/// One Mesh prim being read.
struct Prim<'a> {
    mesh: &'a geom::Mesh,
    stage: &'a Stage,
    file: &'a str,
    at: &'a str,
    /// The time code the points are read at (`None`: default values).
    time: Option<f64>,
    /// The stage's start time, where transforms are read without a time.
    start: f64,
}

/// What one prim adds to the scene: the prim, and its material groups'
/// colours (one group without a colour, or one per face colour).
struct Read {
    prim: scene::Prim,
    groups: Vec<Option<Vec3>>,
}

impl Prim<'_> {
    /// The composed default value of `name`, if authored.
    fn value(&self, name: &str) -> Result<Option<Value>> {
        self.mesh.attribute(name).get::<Value>().map_err(|e| self.err(format!("{name}: {e:#}")))
    }

    /// The value of `name` at the time being read (its default value
    /// when nothing is sampled, or where it is not).
    fn value_now(&self, name: &str) -> Result<Option<Value>> {
        let Some(t) = self.time else { return self.value(name) };
        let attr = self.mesh.attribute(name);
        let at = attr.get_at::<Value>(openusd::usd::TimeCode::new(t));
        at.map_err(|e| self.err(format!("{name} at time {t}: {e:#}")))
    }

    /// The `interpolation` metadata of the primvar `name`.
    fn interpolation(&self, name: &str) -> Option<String> {
        match self.mesh.attribute(name).get_metadata::<Value>("interpolation").ok()?? {
            Value::Token(t) => Some(t.as_str().to_string()),
            Value::String(s) => Some(s),
            _ => None,
        }
    }

    /// A token attribute's value.
    fn token(&self, name: &str) -> Result<Option<String>> {
        Ok(match self.value(name)? {
            Some(Value::Token(t)) => Some(t.as_str().to_string()),
            Some(Value::String(s)) => Some(s),
            _ => None,
        })
    }

    /// An `int[]` attribute (empty when not authored).
    fn ints(&self, name: &str) -> Result<Vec<i32>> {
        match self.value(name)? {
            None => Ok(Vec::new()),
            Some(Value::IntVec(v)) => Ok(v),
            Some(_) => Err(self.err(format!("{name} is not an int[]"))),
        }
    }

    /// A `float[]` attribute (empty when not authored).
    fn floats(&self, name: &str) -> Result<Vec<f32>> {
        match self.value(name)? {
            None => Ok(Vec::new()),
            Some(Value::FloatVec(v)) => Ok(v),
            Some(Value::DoubleVec(v)) => Ok(v.into_iter().map(|x| x as f32).collect()),
            Some(_) => Err(self.err(format!("{name} is not a float[]"))),
        }
    }

    fn err(&self, msg: impl Into<String>) -> Error {
        format_err(self.file, self.at, msg)
    }

    /// Appends this prim to `raw`: its points, faces, texture
    /// coordinates, colours, tags and material groups (one, or one per
    /// face colour); gives the prim and its groups' colours.
    fn append(&self, raw: &mut RawMesh, input: &Input) -> Result<Read> {
        let points = self.points()?;
        let counts = self.ints("faceVertexCounts")?;
        let indices = self.ints("faceVertexIndices")?;
        input.budget.take_vertices(points.len() as u64, self.file, self.at)?;
        input.budget.take_faces(counts.len() as u64, self.file, self.at)?;
        let corners = self.topology(&counts, &indices, points.len(), input.budget.limits().face_size)?;
        let world = self.world()?;
        let flip = (self.token("orientation")?.as_deref() == Some("leftHanded")) != (world.determinant() < 0.0);
        let (v0, f0) = (raw.positions.len() as u32, raw.num_faces() as u32);
        let (nv0, nc0) = (raw.positions.len(), raw.corners.len());
        raw.positions.extend(points.iter().map(|p| world.transform_point3(*p).as_vec3()));
        // the file's corner of each of our corners: reversed after the first for a flip
        let mut order = Vec::with_capacity(indices.len());
        let mut start = 0usize;
        for &n in &counts {
            let n = n as usize;
            order.push(start);
            order.extend((1..n).map(|k| if flip { start + n - k } else { start + k }));
            let face: Vec<u32> = order[start..start + n].iter().map(|&c| v0 + corners[c]).collect();
            raw.push_face(&face);
            start += n;
        }
        let uv = self.st(&order, &corners, points.len(), counts.len())?;
        if let Some(uv) = uv {
            raw.uv.get_or_insert_with(|| vec![Vec2::ZERO; nc0]).extend(uv);
        } else if let Some(all) = &mut raw.uv {
            all.resize(raw.corners.len(), Vec2::ZERO);
        }
        let colors = self.colors(points.len(), counts.len(), input)?;
        if let Colors::Vertex(c) = &colors {
            raw.colors.get_or_insert_with(|| vec![Vec3::splat(0.8); nv0]).extend(c);
        } else if let Some(all) = &mut raw.colors {
            all.resize(raw.positions.len(), Vec3::splat(0.8));
        }
        self.tags(raw, (v0, f0), points.len(), counts.len())?;
        let (id, nf) = (raw.material_list.len() as u32, raw.num_faces());
        let groups = raw.materials.get_or_insert_with(Vec::new);
        let (face_colors, colours) = match colors {
            Colors::Face(palette, of) => {
                groups.extend(of.iter().map(|&k| id + k));
                (true, palette.into_iter().map(Some).collect())
            }
            _ => {
                groups.resize(nf, id);
                (false, vec![None])
            }
        };
        let prim = scene::Prim {
            path: self.mesh.path().as_str().to_string(),
            options: self.options()?,
            transform: world.to_cols_array(),
            face_colors,
        };
        Ok(Read { prim, groups: colours })
    }

    /// The `points`, in double precision.
    fn points(&self) -> Result<Vec<DVec3>> {
        let v3 = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
        match self.value_now("points")? {
            Some(Value::Vec3fVec(p)) => Ok(p.iter().map(|p| v3(p.x as f64, p.y as f64, p.z as f64)).collect()),
            Some(Value::Vec3dVec(p)) => Ok(p.iter().map(|p| v3(p.x, p.y, p.z)).collect()),
            Some(Value::Vec3hVec(p)) => Ok(p.iter().map(|p| v3(p.x.to_f64(), p.y.to_f64(), p.z.to_f64())).collect()),
            None => Err(self.err("no points")),
            Some(_) => Err(self.err("points is not a point3f[]")),
        }
    }

    /// The vertex of every corner, checked against the counts and points.
    fn topology(&self, counts: &[i32], indices: &[i32], nv: usize, face_size: u64) -> Result<Vec<u32>> {
        let mut total = 0usize;
        for (f, &n) in counts.iter().enumerate() {
            if n < 3 || n as u64 > face_size {
                return Err(self.err(format!("face {f} has {n} corners (3 to {face_size} are read)")));
            }
            total += n as usize;
        }
        if total != indices.len() {
            return Err(self.err(format!(
                "faceVertexCounts add up to {total} corners but faceVertexIndices has {}",
                indices.len()
            )));
        }
        indices
            .iter()
            .enumerate()
            .map(|(c, &v)| match usize::try_from(v) {
                Ok(v) if v < nv => Ok(v as u32),
                _ => Err(self.err(format!("faceVertexIndices[{c}] = {v} names no point (of {nv})"))),
            })
            .collect()
    }

    /// The local-to-world transform (column vectors): the prim's and its
    /// ancestors' xformOps, up to a `!resetXformStack!`.
    fn world(&self) -> Result<DMat4> {
        use geom::Xformable;
        let usd = |e: anyhow::Error| self.err(format!("xformOps: {e:#}"));
        let mut m = DMat4::IDENTITY;
        let mut path = Some(self.mesh.path().clone());
        let t = openusd::usd::TimeCode::new(self.time.unwrap_or(self.start));
        while let Some(p) = path {
            let (local, resets) = if let Some(x) = geom::Xform::get(self.stage, p.clone()).map_err(usd)? {
                (x.local_to_parent_transform(t).map_err(usd)?, x.resets_xform_stack().map_err(usd)?)
            } else if let Some(x) = geom::Mesh::get(self.stage, p.clone()).map_err(usd)? {
                (x.local_to_parent_transform(t).map_err(usd)?, x.resets_xform_stack().map_err(usd)?)
            } else {
                (openusd::gf::Matrix4d::IDENTITY, false)
            };
            // USD's row-major array of row vectors is glam's column-major array
            m = DMat4::from_cols_array(&local.0) * m;
            if !m.is_finite() {
                return Err(self.err("its transform is not finite"));
            }
            path = if resets { None } else { p.parent() };
        }
        Ok(m)
    }

    /// `primvars:st` per corner (in `order`), from faceVarying, vertex or
    /// varying values, indexed or not.
    fn st(&self, order: &[usize], corners: &[u32], nv: usize, nf: usize) -> Result<Option<Vec<Vec2>>> {
        let name = "primvars:st";
        let values: Vec<Vec2> = match self.value(name)? {
            None => return Ok(None),
            Some(Value::Vec2fVec(v)) => v.iter().map(|t| Vec2::new(t.x, t.y)).collect(),
            Some(Value::Vec2dVec(v)) => v.iter().map(|t| Vec2::new(t.x as f32, t.y as f32)).collect(),
            Some(Value::Vec2hVec(v)) => v.iter().map(|t| Vec2::new(t.x.to_f32(), t.y.to_f32())).collect(),
            Some(_) => return Err(self.err(format!("{name} is not a texCoord2f[]"))),
        };
        let indices = self.ints("primvars:st:indices")?;
        let per = |k: usize| -> Result<Vec2> {
            let i = if indices.is_empty() { Some(k) } else { indices.get(k).and_then(|&i| usize::try_from(i).ok()) };
            i.and_then(|i| values.get(i).copied()).ok_or_else(|| self.err(format!("{name}: element {k} has no value")))
        };
        let interpolation = self.interpolation(name).unwrap_or_else(|| "constant".into());
        let n = if indices.is_empty() { values.len() } else { indices.len() };
        match interpolation.as_str() {
            "faceVarying" if n == corners.len() => order.iter().map(|&c| per(c)).collect::<Result<_>>().map(Some),
            "vertex" | "varying" if n == nv => {
                order.iter().map(|&c| per(corners[c] as usize)).collect::<Result<_>>().map(Some)
            }
            "uniform" if n == nf => Err(self.err(format!("{name}: uniform texture coordinates are not read"))),
            other => Err(self.err(format!("{name}: {n} values do not fit {other} interpolation"))),
        }
    }

    /// `primvars:displayColor` (indexed or not): per vertex (vertex,
    /// varying, or one constant colour for every vertex) or per face
    /// (uniform: a palette and each face's entry); per corner is left out
    /// with a warning.
    fn colors(&self, nv: usize, nf: usize, input: &Input) -> Result<Colors> {
        let name = "primvars:displayColor";
        let values: Vec<Vec3> = match self.value(name)? {
            None => return Ok(Colors::None),
            Some(Value::Vec3fVec(v)) => v.iter().map(|c| Vec3::new(c.x, c.y, c.z)).collect(),
            Some(Value::Vec3dVec(v)) => v.iter().map(|c| Vec3::new(c.x as f32, c.y as f32, c.z as f32)).collect(),
            Some(_) => return Err(self.err(format!("{name} is not a color3f[]"))),
        };
        let values: Vec<Vec3> = values.into_iter().map(|c| c.clamp(Vec3::ZERO, Vec3::ONE)).collect();
        let indices = self.ints("primvars:displayColor:indices")?;
        let n = if indices.is_empty() { values.len() } else { indices.len() };
        // element k's value
        let at = |k: usize| -> Result<usize> {
            let i = if indices.is_empty() { Some(k) } else { indices.get(k).and_then(|&i| usize::try_from(i).ok()) };
            i.filter(|&i| i < values.len()).ok_or_else(|| self.err(format!("{name}: element {k} has no value")))
        };
        match (self.interpolation(name).as_deref().unwrap_or("constant"), n) {
            ("vertex" | "varying", n) if n == nv => {
                Ok(Colors::Vertex((0..nv).map(|k| Ok(values[at(k)?])).collect::<Result<_>>()?))
            }
            ("constant", 1) => Ok(Colors::Vertex(vec![values[at(0)?]; nv])),
            ("uniform", n) if n == nf => {
                // the palette: each distinct colour once, in order of first use
                let mut palette: Vec<Vec3> = Vec::new();
                let mut of = Vec::with_capacity(nf);
                for f in 0..nf {
                    let c = values[at(f)?];
                    let k = palette.iter().position(|&p| p == c).unwrap_or_else(|| {
                        palette.push(c);
                        palette.len() - 1
                    });
                    of.push(k as u32);
                }
                input.budget.check("materials", palette.len() as u64, self.file, self.at)?;
                Ok(Colors::Face(palette, of))
            }
            ("faceVarying", n) if n == self.ints("faceVertexIndices")?.len() => {
                input.warnings.warn(
                    "colours per face corner",
                    format!("{}: {}: {name} per face corner is not kept", self.file, self.at),
                );
                Ok(Colors::None)
            }
            (other, n) => Err(self.err(format!("{name}: {n} values do not fit {other} interpolation"))),
        }
    }

    /// Creases, corners and holes, their ids moved by the prim's first
    /// vertex and face.
    fn tags(&self, raw: &mut RawMesh, (v0, f0): (u32, u32), nv: usize, nf: usize) -> Result<()> {
        let vertex = |name: &str, v: i32| match usize::try_from(v) {
            Ok(v) if v < nv => Ok(v0 + v as u32),
            _ => Err(self.err(format!("{name}: {v} names no point (of {nv})"))),
        };
        let sharp = |name: &str, s: f32| {
            crate::mesh::sharpness::checked_sharpness(f64::from(s)).map_err(|e| self.err(format!("{name}: {e}")))
        };
        let (ci, cl, cs) =
            (self.ints("creaseIndices")?, self.ints("creaseLengths")?, self.floats("creaseSharpnesses")?);
        let edges: usize = cl.iter().map(|&l| (l.max(1) - 1) as usize).sum();
        let per_edge = cs.len() == edges && cs.len() != cl.len();
        if !(cs.len() == cl.len() || per_edge) {
            return Err(self.err(format!("{} creaseSharpnesses for {} creases of {edges} edges", cs.len(), cl.len())));
        }
        let (mut at, mut e) = (0usize, 0usize);
        for (k, &len) in cl.iter().enumerate() {
            let len = usize::try_from(len).ok().filter(|&l| l >= 2 && at + l <= ci.len());
            let len = len.ok_or_else(|| self.err(format!("creaseLengths[{k}] does not fit creaseIndices")))?;
            for w in ci[at..at + len].windows(2) {
                let s = sharp("creaseSharpnesses", cs[if per_edge { e } else { k }])?;
                let (a, b) = (vertex("creaseIndices", w[0])?, vertex("creaseIndices", w[1])?);
                raw.tags.creases.push(CreaseTag { v0: a, v1: b, sharpness: s });
                e += 1;
            }
            at += len;
        }
        let (vi, vs) = (self.ints("cornerIndices")?, self.floats("cornerSharpnesses")?);
        if vi.len() != vs.len() {
            return Err(self.err(format!("{} cornerIndices but {} cornerSharpnesses", vi.len(), vs.len())));
        }
        for (&v, &s) in vi.iter().zip(&vs) {
            let t = CornerTag { vertex: vertex("cornerIndices", v)?, sharpness: sharp("cornerSharpnesses", s)? };
            raw.tags.corners.push(t);
        }
        for h in self.ints("holeIndices")? {
            match usize::try_from(h) {
                Ok(f) if f < nf => raw.holes.push((f0 + f as u32, 0)),
                _ => return Err(self.err(format!("holeIndices: {h} names no face (of {nf})"))),
            }
        }
        raw.tags.creases.retain(|c| c.sharpness > 0.0);
        raw.tags.corners.retain(|c| c.sharpness > 0.0);
        Ok(())
    }

    /// The subdivision attributes as options, USD's defaults where unauthored
    /// (`interpolateBoundary` edgeAndCorner, `faceVaryingLinearInterpolation`
    /// cornersPlus1, `triangleSubdivisionRule` catmullClark).
    fn options(&self) -> Result<ShapeOptions> {
        let unknown =
            |name: &str, t: &str| self.err(format!("{name} '{}' is not one of USD's", crate::error::clean(t, 40)));
        let token = |name: &str, default: &str| -> Result<String> {
            Ok(self.token(name)?.unwrap_or_else(|| default.to_string()))
        };
        let scheme = token("subdivisionScheme", "catmullClark")?;
        let scheme = FileScheme::of_token(&scheme).ok_or_else(|| unknown("subdivisionScheme", &scheme))?;
        let boundary = match token("interpolateBoundary", "edgeAndCorner")?.as_str() {
            "none" => BoundaryInterpolation::None,
            "edgeOnly" => BoundaryInterpolation::EdgeOnly,
            "edgeAndCorner" => BoundaryInterpolation::EdgeAndCorner,
            t => return Err(unknown("interpolateBoundary", t)),
        };
        let fvar = token("faceVaryingLinearInterpolation", "cornersPlus1")?;
        let fvar = FVAR.iter().find(|(t, _)| *t == fvar).map(|&(_, m)| m);
        let fvar = fvar.ok_or_else(|| unknown("faceVaryingLinearInterpolation", "?"))?;
        let triangles = match token("triangleSubdivisionRule", "catmullClark")?.as_str() {
            "catmullClark" => TriangleSubdivision::Catmark,
            "smooth" => TriangleSubdivision::Smooth,
            t => return Err(unknown("triangleSubdivisionRule", t)),
        };
        Ok(ShapeOptions {
            boundary: Some(boundary),
            fvar: Some(fvar),
            triangles: Some(triangles),
            creasing: None,
            scheme: Some(scheme),
        })
    }
}

/// A prim's `displayColor`.
enum Colors {
    None,
    /// One per vertex.
    Vertex(Vec<Vec3>),
    /// A palette and each face's entry.
    Face(Vec<Vec3>, Vec<u32>),
}

/// USD's `faceVaryingLinearInterpolation` tokens and our modes.
pub(super) const FVAR: [(&str, UvInterpolation); 6] = [
    ("none", UvInterpolation::None),
    ("cornersOnly", UvInterpolation::Smooth),
    ("cornersPlus1", UvInterpolation::CornersPlus1),
    ("cornersPlus2", UvInterpolation::CornersPlus2),
    ("boundaries", UvInterpolation::Boundaries),
    ("all", UvInterpolation::Linear),
];
