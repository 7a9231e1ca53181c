//! The model: the control mesh, its subdivision and what is shown of it.
//!
//! ```text
//! control --(worker: subdivide)--> raw (+ proxy, + refined attributes)
//!    raw --(display options: limit snapping, normals, colours)--> result
//! ```
//! Every artefact the window uploads carries a version ([`Versioned`]),
//! bumped whenever it is replaced; the window compares the versions with
//! those it uploaded and uploads only what changed, and of a mesh that a
//! drag moved, only the rows the move changed.

use super::display::{Coloring, Display, NormalMode};
use crate::mesh::attributes::Attributes;
use crate::mesh::poly::{PolyMesh, PolyTable};
use crate::mesh::topology::{Topology, topology};
use crate::subdiv::Stats;
use crate::{Error, Mesh, Scheme};
use glam::{Vec2, Vec3};
use std::path::PathBuf;
use std::sync::Arc;

/// A value with a counter bumped on every change, so that a consumer (the
/// window's GPU copies) can tell whether what it holds is current; and,
/// for the last few versions that changed only some rows of it (a drag),
/// which rows, so that the consumer can copy those alone.
#[derive(Clone, Debug)]
pub(crate) struct Versioned<T> {
    value: T,
    version: u64,
    /// The rows each of the latest versions changed from the one before,
    /// oldest first and ending at `version` (at most [`ROW_STEPS`]);
    /// emptied by a change of the whole.
    rows: Vec<Arc<[u32]>>,
}

/// How many versions back [`Versioned::rows_since`] can answer.
const ROW_STEPS: usize = 8;

impl<T> Versioned<T> {
    /// A first version (1; a consumer that has seen nothing holds 0).
    pub(crate) fn new(value: T) -> Versioned<T> {
        Versioned { value, version: 1, rows: Vec::new() }
    }
    /// The current version.
    pub(crate) fn version(&self) -> u64 {
        self.version
    }
    /// Replaces the value (a new version).
    pub(crate) fn set(&mut self, value: T) {
        self.value = value;
        self.version += 1;
        self.rows.clear();
    }
    /// Replaces the value by one that differs from it only at `rows`
    /// (sorted, each once; for a mesh, the vertices whose position or
    /// normal changed: the counts, the topology and everything else
    /// the same).
    pub(crate) fn set_rows(&mut self, value: T, rows: Arc<[u32]>) {
        self.value = value;
        self.version += 1;
        if self.rows.len() == ROW_STEPS {
            self.rows.remove(0);
        }
        self.rows.push(rows);
    }
    /// The rows changed since version `seen` (sorted, each once), when
    /// every version since changed rows only and is still recorded;
    /// `None` when something else may have changed.
    pub(crate) fn rows_since(&self, seen: u64) -> Option<Vec<u32>> {
        let back = usize::try_from(self.version.checked_sub(seen)?).ok()?;
        let steps = self.rows.get(self.rows.len().checked_sub(back)?..)?;
        let mut rows: Vec<u32> = steps.iter().flat_map(|r| r.iter().copied()).collect();
        if steps.len() > 1 {
            rows.sort_unstable();
            rows.dedup();
        }
        Some(rows)
    }
}

impl<T> std::ops::Deref for Versioned<T> {
    type Target = T;
    fn deref(&self) -> &T {
        &self.value
    }
}

/// A mesh with its normals and counts, ready to upload. Cloning shares the
/// arrays.
#[derive(Clone)]
pub(crate) struct Shown {
    /// The mesh.
    pub(crate) mesh: Arc<Mesh>,
    /// Unit vertex normals (fan-averaged unless a display option chose others).
    pub(crate) normals: Arc<Vec<Vec3>>,
    /// V/E/F, genus, boundary loops...
    pub(crate) topo: Topology,
    /// Where the mesh has sharp edges: how it is drawn (see [`Creased`]).
    pub(crate) creased: Option<Arc<Creased>>,
}

/// A mesh with sharp edges as it is drawn: cut open along them
/// ([`crate::mesh::cut`]), so that each side of a crease gets its own
/// normal and a crease shows as a crease, not as a smeared highlight.
pub(crate) struct Creased {
    /// The cut table (same corners; the extra vertices are copies).
    pub(crate) ct: crate::CornerTable,
    /// For cut vertex `nv + i`, the vertex it is a copy of.
    pub(crate) copies: Vec<u32>,
    /// Fan-averaged normals of the cut mesh: per side along the creases.
    pub(crate) normals: Vec<Vec3>,
}

impl Creased {
    /// `values` (one per vertex of the uncut mesh) extended to the copies.
    pub(crate) fn extend<T: Copy>(&self, values: &[T]) -> Vec<T> {
        let mut out = Vec::with_capacity(values.len() + self.copies.len());
        out.extend_from_slice(values);
        out.extend(self.copies.iter().map(|&v| values[v as usize]));
        out
    }
}

impl Shown {
    /// Computes the fan-averaged normals and the topology, and the cut
    /// mesh of a mesh with sharp edges (worker threads do this).
    pub(crate) fn new(mesh: Arc<Mesh>) -> Shown {
        let normals = Arc::new(mesh.vertex_normals());
        let topo = topology(&mesh.ct);
        let creased = mesh.ct.cut_at_sharp_edges().map(|cut| {
            let normals = crate::mesh::normals::vertex_normals(&cut.table, &cut.positions(&mesh.positions));
            Arc::new(Creased { ct: cut.table, copies: cut.copies, normals })
        });
        Shown { mesh, normals, topo, creased }
    }
}

/// A planar Bezier curve opened from a `.bzc` file, shown instead of the mesh.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Curve {
    /// File name.
    pub(crate) name: String,
    /// Control points.
    pub(crate) control: Vec<Vec2>,
    /// Polyline segments drawn.
    pub(crate) segments: usize,
    /// Parameter of the de Casteljau construction shown.
    pub(crate) t: f32,
    /// Show the construction at `t`.
    pub(crate) construction: bool,
}

/// How the subdivision output came about: what the panel reports about it.
#[derive(Clone, Debug, Default)]
pub(crate) struct Made {
    /// Level of the output.
    pub(crate) level: u32,
    /// Scheme of the output.
    pub(crate) scheme: Scheme,
    /// The options of the output (what limit snapping must use: Loop's
    /// weights, Catmull-Clark's creasing and boundary).
    pub(crate) opts: crate::Options,
    /// Phase times of the subdivision.
    pub(crate) stats: Option<Stats>,
    /// Wall time of the subdivision job, ms.
    pub(crate) job_ms: f64,
    /// Whether its prims were refined apart, each by its file's scheme,
    /// and joined (the output is then no one refinement of the cage).
    pub(crate) by_prim: bool,
}

/// What the 3D view shows of the subdivision output.
#[derive(Clone)]
pub(crate) struct Shaded {
    /// Mesh, normals and topology after the display options.
    pub(crate) shown: Shown,
    /// Per-vertex colours (with the colouring), linear RGB.
    pub(crate) colors: Option<Vec<Vec3>>,
    /// Per-vertex values instead of colours (the curvature colourings):
    /// each over `color_max`, NaN where not evaluated, coloured per pixel
    /// on the diverging map (where the isolines are drawn).
    pub(crate) values: Option<Vec<f32>>,
    /// Largest value behind the colours (levels, or a distance), for the
    /// legend; a curvature colouring's half-width.
    pub(crate) color_max: f32,
    /// A curvature colouring's range: its half-width and whether it was
    /// set by hand, for the colour bar.
    pub(crate) scale: Option<crate::subdiv::eval::color::Scale>,
}

/// What a colouring gives each vertex of the result: colours or values
/// (see [`Shaded`]) and the largest value behind them.
#[derive(Default)]
struct Painted {
    colors: Option<Vec<Vec3>>,
    values: Option<Vec<f32>>,
    max: f32,
    scale: Option<crate::subdiv::eval::color::Scale>,
}

impl Painted {
    fn colors(colors: Option<Vec<Vec3>>, max: f32) -> Painted {
        Painted { colors, values: None, max, scale: None }
    }
}

/// The curvature last evaluated at the vertices of the result, with what
/// it depends on: a new range (or snapping, or normals) colours the same
/// values again without evaluating the limit anew.
pub(crate) struct Curvatures {
    /// The subdivision output they were evaluated for (compared by identity).
    raw: Arc<Mesh>,
    /// The control mesh's version.
    control: u64,
    /// The scheme, level and options of the output.
    made: (Scheme, u32, crate::Options),
    /// Which curvature.
    kind: crate::subdiv::eval::color::CurvatureKind,
    /// One per vertex of `raw`.
    values: Arc<Vec<f64>>,
}

/// Vertex colours and corner texture coordinates: of the control mesh (from
/// its file) and refined to the subdivision output.
#[derive(Clone, Debug, Default)]
pub(crate) struct Attrs {
    /// The control mesh's, from its file.
    pub(crate) file: Attributes,
    /// `file` refined to the subdivision output.
    pub(crate) refined: Attributes,
}

/// The control mesh, its subdivision and what is shown of them.
pub(crate) struct Model {
    /// Display name of the model.
    pub(crate) name: String,
    /// File it came from (None: built in).
    pub(crate) path: Option<PathBuf>,
    /// The control mesh.
    pub(crate) control: Versioned<Shown>,
    /// The control mesh as loaded, before smoothing or edge edits.
    pub(crate) original: Option<Arc<Mesh>>,
    /// The subdivision output (the control mesh at level 0).
    pub(crate) raw: Shown,
    /// How `raw` was made.
    pub(crate) made: Made,
    /// A lower level of the same subdivision (at most
    /// [`super::jobs::PROXY_FACES`] triangles), drawn instead of a big result
    /// while the camera moves; it changes with `result`.
    pub(crate) proxy: Option<Shown>,
    /// What is shown of `raw`.
    pub(crate) result: Versioned<Shaded>,
    /// Colours and texture coordinates.
    pub(crate) attrs: Attrs,
    /// A picked control-mesh corner: the edge opposite it is selected.
    pub(crate) picked: Versioned<Option<u32>>,
    /// The picked point of the surface (a click when edge picking is off).
    pub(crate) probe: Option<super::probe::Probe>,
    /// A Bezier curve shown instead of the mesh.
    pub(crate) curve: Versioned<Option<Curve>>,
    /// The last curvature colouring's values (see [`Curvatures`]).
    pub(crate) curvatures: Option<Curvatures>,
    /// The control points in f64 as the file wrote them, and the control
    /// mesh they belong to (see [`Model::precise_control`]).
    pub(crate) precise: Option<(Arc<Mesh>, Arc<Vec<glam::DVec3>>)>,
    /// The adaptive display's tessellation (drawn instead of `raw` while
    /// it is on) and what it was last asked for.
    pub(crate) adaptive: super::adaptive::Adaptive,
}

impl Model {
    /// The control points in f64 as the file wrote them, while the control
    /// mesh is the one read: an edit makes a new control mesh, whose f32
    /// points are then all there is.
    pub(crate) fn precise_control(&self) -> Option<&[glam::DVec3]> {
        let (of, points) = self.precise.as_ref()?;
        Arc::ptr_eq(of, &self.control.mesh).then_some(points.as_slice())
    }

    /// The control points in f64: the file's own digits for every vertex
    /// still where the file put it (its f32 point is the file's, rounded),
    /// the f32 point for one an edit moved. So after an edit only the moved
    /// points differ from the last (the adaptive display makes again only
    /// what they reach).
    pub(crate) fn control_f64(&self) -> Vec<glam::DVec3> {
        let mesh = &self.control.mesh;
        let file = self.precise.as_ref().map(|(_, p)| p.as_slice()).filter(|p| p.len() == mesh.positions.len());
        let point = |(i, q): (usize, &glam::Vec3)| match file {
            Some(p) if p[i].as_vec3() == *q => p[i],
            _ => q.as_dvec3(),
        };
        mesh.positions.iter().enumerate().map(point).collect()
    }

    /// A model of `mesh` at level 0, shown plainly.
    pub(crate) fn new(name: String, mesh: Mesh) -> Model {
        let shown = Shown::new(Arc::new(mesh));
        Model {
            name,
            path: None,
            control: Versioned::new(shown.clone()),
            original: None,
            raw: shown.clone(),
            made: Made::default(),
            proxy: None,
            result: Versioned::new(Shaded { shown, colors: None, values: None, color_max: 0.0, scale: None }),
            attrs: Attrs::default(),
            picked: Versioned::new(None),
            probe: None,
            curve: Versioned::new(None),
            curvatures: None,
            precise: None,
            adaptive: Default::default(),
        }
    }

    /// Rebuilds the shown result from the subdivision output and `display`
    /// (limit snapping, normals, colours); an error of the colouring is
    /// returned (the result is then shown uncoloured). `rows`: the
    /// subdivision output differs from the one the result was last shaded
    /// from only at these vertices (positions and normals; sorted), so a
    /// result drawn as it is differs at them too (see [`result_rows`]).
    pub(crate) fn reshade(&mut self, display: &Display, rows: Option<Arc<[u32]>>) -> Option<Error> {
        if let Some(t) = self.adaptive.drawn.as_ref().filter(|_| display.adaptive) {
            // the limit for the view, with its exact normals, and its exact
            // curvature where that is the colouring (the others are not drawn on it)
            let shown = t.shown.clone();
            let p = adaptive_colors(t, display);
            self.result.set(Shaded { shown, colors: None, values: p.values, color_max: p.max, scale: p.scale });
            return None;
        }
        let creased = self.raw.creased.clone();
        let shown = match creased {
            // the normals are the cut mesh's (creased_view)
            Some(_) => Shown { mesh: snapped(&self.raw, display, &self.made), ..self.raw.clone() },
            None => snapped_and_normals(&self.raw, display, &self.made),
        };
        let (painted, error) = match result_colors(self, &shown.mesh, display) {
            Ok(p) => (p, None),
            Err(e) => (Painted::default(), Some(e)),
        };
        let Painted { mut colors, mut values, max: color_max, scale } = painted;
        let shown = match &creased {
            Some(cr) => {
                (colors, values) = (colors.map(|c| cr.extend(&c)), values.map(|v| cr.extend(&v)));
                creased_view(&self.raw, &shown, cr, display, &self.made)
            }
            None => shown,
        };
        let shaded = Shaded { shown, colors, values, color_max, scale };
        let polygons = self.made.scheme.is_polygonal() && self.made.level > 0;
        match rows.and_then(|rows| result_rows(rows, creased.as_deref().map(|c| (c, polygons)), display)) {
            Some(rows) => self.result.set_rows(shaded, rows),
            None => self.result.set(shaded),
        }
        error
    }

    /// The curvature `kind` of the exact limit at every vertex of the
    /// subdivision output, evaluated once for the output (see
    /// [`Curvatures`]).
    ///
    /// # Errors
    /// A scheme without curvature colours, or the evaluation's errors.
    fn curvatures(&mut self, kind: crate::subdiv::eval::color::CurvatureKind) -> crate::Result<Arc<Vec<f64>>> {
        use crate::subdiv::eval::color::vertex_curvatures;
        let made = (self.made.scheme, self.made.level, self.made.opts);
        let control = self.control.version();
        if let Some(c) = &self.curvatures
            && Arc::ptr_eq(&c.raw, &self.raw.mesh)
            && (c.control, c.made, c.kind) == (control, made, kind)
        {
            return Ok(c.values.clone());
        }
        let values = Arc::new(vertex_curvatures(&self.control.mesh, &self.raw.mesh, (made.0, made.1, &made.2), kind)?);
        self.curvatures = Some(Curvatures { raw: self.raw.mesh.clone(), control, made, kind, values: values.clone() });
        Ok(values)
    }

    /// The vertex ids of the picked edge.
    pub(crate) fn picked_edge(&self) -> Option<(u32, u32)> {
        let c = (*self.picked)?;
        let ct = &self.control.mesh.ct;
        ((c as usize) < ct.num_corners())
            .then(|| (ct.v_table()[crate::mesh::n(c) as usize], ct.v_table()[crate::mesh::p(c) as usize]))
    }

    /// Whether the face of the picked edge or the one across it is a hole.
    pub(crate) fn picked_face_is_hole(&self) -> bool {
        self.hole_beside_pick().is_some()
    }

    /// The hole at the picked edge: its own triangle, or the one across it.
    pub(crate) fn hole_beside_pick(&self) -> Option<u32> {
        let c = (*self.picked)?;
        let ct = &self.control.mesh.ct;
        if c as usize >= ct.num_corners() {
            return None;
        }
        [Some(c), ct.o(c)].into_iter().flatten().map(|x| x / 3).find(|&t| ct.is_hole(t))
    }
}

/// The rows of the shown result that change when the subdivision output
/// changes at `rows` (positions and normals), where the result shows the
/// output's points and normals as they are and colours that do not depend
/// on the points (`None` otherwise: snapped points, limit or butterfly
/// normals, displacement or curvature colours reach further).
///
/// Drawn cut open along creases (`creased`), a vertex's copies change
/// with it. Their fan normals (of the cut triangles) change with any
/// corner of their triangles, which `rows` covers (it holds the moved
/// points' triangle rings) except on a polygon level (`true`), whose own
/// normals follow rings of edge neighbours and not the quads' diagonals:
/// there the cut's triangle rings are taken as well.
fn result_rows(rows: Arc<[u32]>, creased: Option<(&Creased, bool)>, display: &Display) -> Option<Arc<[u32]>> {
    let colors_move = matches!(display.coloring, Coloring::Displacement | Coloring::Curvature(_));
    if display.snap_limit || display.normal_mode != NormalMode::FanAverage || colors_move {
        return None;
    }
    let Some((cr, polygons)) = creased else { return Some(rows) };
    let nv = cr.ct.num_vertices() - cr.copies.len();
    let copies = cr.copies.iter().enumerate().filter(|(_, v)| rows.binary_search(v).is_ok());
    let mut out: Vec<u32> = rows.iter().copied().chain(copies.map(|(i, _)| (nv + i) as u32)).collect();
    if polygons {
        let ring: Vec<u32> = out.iter().flat_map(|&v| cr.ct.ring(v)).collect();
        out.extend(ring);
    }
    out.sort_unstable();
    out.dedup();
    Some(out.into())
}

/// `raw` with its points moved to the limit when asked, and the normals of
/// the normal mode.
fn snapped_and_normals(raw: &Shown, display: &Display, made: &Made) -> Shown {
    use crate::subdiv::rules::limit::butterfly_normals;
    let mesh = snapped(raw, display, made);
    let normals = match display.normal_mode {
        // the worker's fan normals, unless the points moved to the limit
        NormalMode::FanAverage if !display.snap_limit => raw.normals.clone(),
        NormalMode::FanAverage => Arc::new(mesh.vertex_normals()),
        NormalMode::Limit => Arc::new(limit_normals(&raw.mesh, &mesh, made)),
        NormalMode::Butterfly => Arc::new(butterfly_normals(&mesh)),
    };
    // snapping moves points, not connectivity: the topology is the raw one
    Shown { mesh, normals, topo: raw.topo.clone(), creased: raw.creased.clone() }
}

/// `raw`'s mesh, with its points moved to the limit of the scheme that made
/// it when asked: Loop's (with its weights) for the triangle schemes,
/// Catmull-Clark's (refining on where a semi-sharp feature is left); a
/// bilinear level is its own limit.
fn snapped(raw: &Shown, display: &Display, made: &Made) -> Arc<Mesh> {
    use crate::subdiv::eval::catmark_limit::limit_frames;
    use crate::subdiv::rules::limit::loop_limit_positions_with;
    if !display.snap_limit {
        return raw.mesh.clone();
    }
    let positions = match made.scheme {
        Scheme::Bilinear => return raw.mesh.clone(),
        Scheme::CatmullClark => {
            let poly =
                PolyMesh { pt: PolyTable::from_corner_table(&raw.mesh.ct), positions: raw.mesh.positions.clone() };
            match limit_frames(&poly, &made.opts) {
                Ok(frames) => frames.iter().map(|f| f.position).collect(),
                Err(_) => return raw.mesh.clone(),
            }
        }
        _ => loop_limit_positions_with(&raw.mesh, made.opts.loop_beta),
    };
    Arc::new(Mesh { ct: raw.mesh.ct.clone(), positions })
}

/// The limit normals of the level `level` (its own points; `shown` is the
/// same table, its points maybe snapped): Catmull-Clark's tangent masks on
/// a Catmull-Clark level (fan normals where a face is not a quad), Loop's
/// on `shown` for the triangle schemes, fan normals on a bilinear level.
fn limit_normals(level: &Mesh, shown: &Mesh, made: &Made) -> Vec<Vec3> {
    use crate::subdiv::eval::catmark_limit::frames_at;
    match made.scheme {
        Scheme::CatmullClark => {
            let pt = PolyTable::from_corner_table(&level.ct);
            let fan = level.vertex_normals();
            let frames = frames_at(&pt, &level.positions, made.opts.creasing);
            frames.iter().zip(fan).map(|(f, n)| if f.normal() == Vec3::ZERO { n } else { f.normal() }).collect()
        }
        Scheme::Bilinear => shown.vertex_normals(),
        _ => crate::subdiv::rules::limit::loop_limit_normals(shown),
    }
}

/// `shown` (the raw result after snapping, uncut) drawn cut open along its
/// creases: positions copied to the cut's extra vertices, normals per side
/// (the worker's fan normals when nothing moved the points; else the
/// normal mode's, computed on the cut mesh, where a crease vertex is a
/// boundary vertex of each side).
fn creased_view(raw: &Shown, shown: &Shown, cr: &Creased, display: &Display, made: &Made) -> Shown {
    use crate::subdiv::rules::limit::butterfly_normals;
    let mesh = Arc::new(Mesh { ct: cr.ct.clone(), positions: cr.extend(&shown.mesh.positions) });
    let normals = match display.normal_mode {
        NormalMode::FanAverage if !display.snap_limit => cr.normals.clone(),
        NormalMode::FanAverage => mesh.vertex_normals(),
        NormalMode::Limit => {
            let level = Mesh { ct: cr.ct.clone(), positions: cr.extend(&raw.mesh.positions) };
            limit_normals(&level, &mesh, made)
        }
        NormalMode::Butterfly => butterfly_normals(&mesh),
    };
    Shown { mesh, normals: Arc::new(normals), topo: shown.topo.clone(), creased: None }
}

/// The adaptive display's colouring: the curvature the tessellation was
/// evaluated for, where that is the display's colouring (nothing else).
fn adaptive_colors(t: &super::adaptive::Tessellated, display: &Display) -> Painted {
    use crate::subdiv::eval::color::{Scale, normalized};
    match (display.coloring, &t.curvature) {
        (Coloring::Curvature(kind), Some((made, values))) if kind == *made => {
            let mesh = &t.shown.mesh;
            let scale = Scale::choose(display.range, values, &mesh.ct, &mesh.positions);
            let values = Some(normalized(values, scale.half));
            Painted { colors: None, values, max: scale.half as f32, scale: Some(scale) }
        }
        _ => Painted::default(),
    }
}

/// The per-vertex colours (or values) of `mesh` (the shown result of
/// `model`) for the display's colouring, and the largest value behind them
/// (for curvature, the half-width of the symmetric range, the display's
/// or the default).
fn result_colors(model: &mut Model, mesh: &Mesh, display: &Display) -> crate::Result<Painted> {
    use crate::mesh::inspect::colormap;
    use crate::subdiv::inspect::{creation_levels, displacement};
    let nv = mesh.positions.len();
    let (level, scheme) = (model.made.level, model.made.scheme);
    let ramp = |t: &[f32]| t.iter().map(|&t| Vec3::from(colormap(t))).collect::<Vec<_>>();
    Ok(match display.coloring {
        Coloring::None | Coloring::Checker | Coloring::Material => Painted::default(),
        Coloring::Shells => {
            let lv = creation_levels(&model.control.mesh, scheme, level, nv);
            let t: Vec<f32> = lv.iter().map(|&l| f32::from(l) / level.max(1) as f32).collect();
            Painted::colors(Some(ramp(&t)), level as f32)
        }
        Coloring::File => Painted::colors(model.attrs.refined.colors.clone().filter(|c| c.len() == nv), 1.0),
        Coloring::Displacement => {
            let d = displacement(&model.control.mesh, mesh, scheme, level)?;
            let max = d.iter().fold(0.0f32, |a, &b| a.max(b));
            let t: Vec<f32> = d.iter().map(|&x| if max > 0.0 { x / max } else { 0.0 }).collect();
            Painted::colors(Some(ramp(&t)), max)
        }
        Coloring::Curvature(kind) => {
            use crate::subdiv::eval::color::{Scale, normalized};
            let values = model.curvatures(kind)?;
            let scale = Scale::choose(display.range, &values, &mesh.ct, &mesh.positions);
            Painted {
                colors: None,
                values: Some(normalized(&values, scale.half)),
                max: scale.half as f32,
                scale: Some(scale),
            }
        }
    })
}
