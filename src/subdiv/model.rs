//! One way to refine a model: its mesh, its attributes and, where asked,
//! f64 control points, under a scheme, its levels and options, for a
//! destination that keeps what it keeps. The path is chosen here, once for
//! every caller (the CLI, Python): a [`Refiner`] when attributes ride on
//! the levels, the faces alone when the destination needs nothing else,
//! the polygons of a polygon scheme, the f64 passes when asked.

use super::{Options, Refiner, Scheme, Stats, subdivide, subdivide_f64, subdivide_faces, subdivide_faces_f64};
use crate::clock::Instant;
use crate::mesh::attributes::Attributes;
use crate::mesh::poly::PolyMesh;
use crate::mesh::{BoundaryInterpolation, Faces, Mesh, VertexId};
use crate::{Error, Result};
use glam::{DVec3, Vec3};

/// A model's control mesh: triangles (a polygon scheme reads the polygons
/// their hidden diagonals stand for, as the readers fan them) or polygons.
#[derive(Clone, Copy, Debug)]
pub enum Control<'a> {
    /// A triangle table (a mesh read from a file).
    Triangles(&'a Mesh),
    /// A polygon table, for a polygon scheme.
    Polygons(&'a PolyMesh),
}

/// What [`subdivide_model`] refines: the control mesh, its attributes
/// (a [`Control::Polygons`]'s per polygon corner) and, for an f64
/// refinement, the control points in f64 (else the f32 ones widened).
#[derive(Clone, Copy, Debug)]
pub struct Model<'a> {
    /// The control mesh.
    pub control: Control<'a>,
    /// Its texture coordinates, colours and materials (none: empty).
    pub attrs: &'a Attributes,
    /// Its control points in f64 (a file's own digits), one per vertex.
    pub precise: Option<&'a [DVec3]>,
}

impl<'a> Model<'a> {
    /// The model of `mesh` with `attrs`, without f64 points.
    pub fn new(mesh: &'a Mesh, attrs: &'a Attributes) -> Model<'a> {
        Model { control: Control::Triangles(mesh), attrs, precise: None }
    }
}

/// When the destination takes the finest level as faces alone (their
/// vertices, without adjacency tables: a third less memory written).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FacesOnly {
    /// Never: it needs the tables (`.ct`, a caller that keeps the mesh).
    #[default]
    Never,
    /// Where the file written from the faces is the one the tables would
    /// write ([`crate::io::writes_faces`]): f32, refined levels, no
    /// attributes, no holes, no sharp features the format keeps.
    Written,
    /// Whenever the faces that are no holes are all it takes (a caller
    /// that copies arrays): a triangle scheme's levels (f32 or f64), a
    /// polygon scheme's refined levels in f32; never with attributes.
    Always,
}

/// What a refinement's destination keeps ([`crate::io::destination`] for
/// a file).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Destination {
    /// When it takes faces alone.
    pub faces: FacesOnly,
    /// It keeps sharp features (creases, sharp corners): a sharp mesh then
    /// needs its tables.
    pub creases: bool,
    /// It keeps a refined level's holes (USD's `holeIndices`).
    pub holes: bool,
}

/// How to refine a model: the scheme, levels and options, the precision
/// and the destination.
#[derive(Clone, Debug, Default)]
pub struct Refinement {
    /// The scheme.
    pub scheme: Scheme,
    /// Levels (0: the control mesh as it is).
    pub levels: u32,
    /// The options.
    pub opts: Options,
    /// Compute in f64 (from [`Model::precise`]).
    pub f64: bool,
    /// What the result goes to.
    pub dest: Destination,
}

/// The refined surface of a [`subdivide_model`].
#[derive(Clone, Debug)]
pub enum Surface<I = u32> {
    /// Triangles (a triangle scheme's), their tables kept.
    Triangles(Mesh),
    /// Polygons (a polygon scheme's), their tables kept.
    Polygons(PolyMesh),
    /// Faces alone, f32 positions.
    Faces(Faces<I>),
    /// Faces alone, f64 positions.
    FacesF64(Faces<I, DVec3>),
}

/// What [`subdivide_model`] gives: the surface, its attributes, the f64
/// positions of an f64 refinement of tables, and the stats.
#[derive(Clone, Debug)]
pub struct Subdivided<I = u32> {
    /// The finest level (its positions f32; an f64 refinement's rounded).
    pub surface: Surface<I>,
    /// Its attributes (the model's refined with it; unrefined ones as given).
    pub attrs: Attributes,
    /// An f64 refinement's positions, for [`Surface::Triangles`] and
    /// [`Surface::Polygons`] (faces alone hold their own).
    pub positions_f64: Option<Vec<DVec3>>,
    /// What refining took.
    pub stats: Stats,
    /// The levels made (0: the control mesh, whose holes are kept as tags
    /// where a format holds them).
    pub levels: u32,
}

impl<I> Subdivided<I> {
    /// The vertices of the surface.
    pub fn num_vertices(&self) -> usize {
        match &self.surface {
            Surface::Triangles(m) => m.positions.len(),
            Surface::Polygons(m) => m.positions.len(),
            Surface::Faces(f) => f.positions.len(),
            Surface::FacesF64(f) => f.positions.len(),
        }
    }

    /// The faces written: a refined level's holes left out (faces alone
    /// have none).
    pub fn num_faces(&self) -> usize {
        let refined = self.levels > 0;
        match &self.surface {
            Surface::Triangles(m) => m.ct.num_triangles() - if refined { m.ct.holes().len() } else { 0 },
            Surface::Polygons(m) => m.pt.num_faces() - if refined { m.pt.holes().len() } else { 0 },
            Surface::Faces(f) => f.corners.len() / f.sides.max(1),
            Surface::FacesF64(f) => f.corners.len() / f.sides.max(1),
        }
    }
}

/// Refines `model` as `how` says, the path chosen for it: the attributes
/// ride on a [`Refiner`]'s levels; a destination that takes faces alone
/// gets them without the last level's tables ([`subdivide_faces`]); a
/// polygon scheme refines the polygons (a triangle mesh's, its attributes
/// per corner, [`PolyMesh::from_mesh_with_attributes`]); an f64 refinement
/// computes from [`Model::precise`] ([`subdivide_f64`]).
///
/// # Errors
/// As [`subdivide`], [`subdivide_f64`] and [`Refiner::attributes`]; a
/// triangle scheme on [`Control::Polygons`].
pub fn subdivide_model(model: &Model, how: &Refinement) -> Result<Subdivided> {
    subdivide_model_as(model, how, |j| j)
}

/// [`subdivide_model`] with faces alone written with every vertex id `j`
/// as `id(j)` (see [`subdivide_faces`]); the tables keep `u32`.
///
/// # Errors
/// As [`subdivide_model`].
pub fn subdivide_model_as<I: VertexId>(
    model: &Model,
    how: &Refinement,
    id: impl Fn(u32) -> I + Sync,
) -> Result<Subdivided<I>> {
    let (surface, attrs, positions_f64, stats) = match model.control {
        Control::Triangles(mesh) if how.scheme.is_polygonal() => {
            let (control, pattrs) = PolyMesh::from_mesh_with_attributes(mesh, model.attrs);
            let m = Model { control: Control::Polygons(&control), attrs: &pattrs, precise: model.precise };
            return subdivide_model_as(&m, how, id);
        }
        Control::Polygons(_) if !how.scheme.is_polygonal() => {
            return Err(Error::Usage(format!("{} subdivides triangles: fan the polygons first", how.scheme)));
        }
        Control::Triangles(mesh) if how.f64 => triangles_f64(mesh, model, how, id)?,
        Control::Polygons(pm) if how.f64 => polygons_f64(pm, model, how)?,
        Control::Triangles(mesh) => triangles(mesh, model.attrs, how, id)?,
        Control::Polygons(pm) => polygons(pm, model.attrs, how, id)?,
    };
    Ok(Subdivided { surface, attrs, positions_f64, stats, levels: how.levels })
}

/// What one path makes.
type Made<I> = (Surface<I>, Attributes, Option<Vec<DVec3>>, Stats);

/// Whether the faces alone do: the destination takes them, nothing is lost.
/// `sharp`: the control mesh's creases; `holes`: its holes.
fn faces_only(how: &Refinement, sharp: bool, holes: bool, polygonal: bool) -> bool {
    let o = &how.opts;
    match how.dest.faces {
        FacesOnly::Never => false,
        // a triangle scheme's levels, a polygon scheme's refined ones in f32
        FacesOnly::Always => !polygonal || (!how.f64 && how.levels > 0),
        FacesOnly::Written => {
            // the format writes the sharp features of the result, the boundary's corners too
            let corners = o.boundary == BoundaryInterpolation::EdgeAndCorner;
            // a mesh with holes goes the whole way: its attributes follow the faces left out
            let holes = holes || o.boundary == BoundaryInterpolation::None;
            !how.f64 && how.levels > 0 && !holes && !((sharp || corners) && how.dest.creases)
        }
    }
}

/// A triangle scheme's levels in f32.
fn triangles<I: VertexId>(
    mesh: &Mesh,
    attrs: &Attributes,
    how: &Refinement,
    id: impl Fn(u32) -> I + Sync,
) -> Result<Made<I>> {
    let (scheme, levels, opts) = (how.scheme, how.levels, &how.opts);
    if levels > 0 && !attrs.is_empty() {
        // the attributes ride on the refinement that makes the level: colours
        // through its rows, texture coordinates and materials through its
        // kept tables
        let t0 = Instant::now();
        let r = Refiner::new(mesh, scheme, levels, opts)?;
        let (fine, fine_attrs) = (r.mesh(), r.attributes(attrs)?);
        return Ok((Surface::Triangles(fine), fine_attrs, None, refiner_stats(&r, t0)));
    }
    if attrs.is_empty() && faces_only(how, mesh.ct.sharpness().is_some(), !mesh.ct.holes().is_empty(), false) {
        let (fine, st) = subdivide_faces(mesh, scheme, levels, opts, id)?;
        return Ok((Surface::Faces(fine), attrs.clone(), None, st));
    }
    let (fine, st) = subdivide(mesh, scheme, levels, opts)?;
    Ok((Surface::Triangles(fine), attrs.clone(), None, st))
}

/// A polygon scheme's levels in f32, straight on the polygons (their
/// attributes per corner).
fn polygons<I: VertexId>(
    control: &PolyMesh,
    pattrs: &Attributes,
    how: &Refinement,
    id: impl Fn(u32) -> I + Sync,
) -> Result<Made<I>> {
    let (scheme, levels, opts) = (how.scheme, how.levels, &how.opts);
    if levels > 0 && !pattrs.is_empty() {
        // as for the triangle schemes: the attributes ride on the refinement
        let t0 = Instant::now();
        let r = Refiner::new(control, scheme, levels, opts)?;
        let fine = refined_polygons(&r, r.positions().to_vec());
        let fine_attrs = r.attributes(pattrs)?;
        return Ok((Surface::Polygons(fine), fine_attrs, None, refiner_stats(&r, t0)));
    }
    let (sharp, holes) = (control.pt.sharpness().is_some(), !control.pt.holes().is_empty());
    if pattrs.is_empty() && faces_only(how, sharp, holes, true) {
        let (fine, st) = subdivide_faces(control, scheme, levels, opts, id)?;
        return Ok((Surface::Faces(fine), pattrs.clone(), None, st));
    }
    let (fine, st) = subdivide(control, scheme, levels, opts)?;
    Ok((Surface::Polygons(fine), pattrs.clone(), None, st))
}

/// The f64 control points of `model` (its f32 ones widened where it has none).
fn control_f64(model: &Model, positions: &[Vec3]) -> Vec<DVec3> {
    match model.precise {
        Some(p) => p.to_vec(),
        None => positions.iter().map(|p| p.as_dvec3()).collect(),
    }
}

/// A triangle scheme's levels in f64.
fn triangles_f64<I: VertexId>(
    mesh: &Mesh,
    model: &Model,
    how: &Refinement,
    id: impl Fn(u32) -> I + Sync,
) -> Result<Made<I>> {
    let (scheme, levels, opts, attrs) = (how.scheme, how.levels, &how.opts, model.attrs);
    let t0 = Instant::now();
    let control = control_f64(model, &mesh.positions);
    let made = if attrs.is_empty() && faces_only(how, false, false, false) {
        let (fine, _) = subdivide_faces_f64(mesh, &control, scheme, levels, opts, id)?;
        (Surface::FacesF64(fine), attrs.clone(), None)
    } else if attrs.is_empty() || levels == 0 {
        let (fine, pos) = subdivide_f64(mesh, &control, scheme, levels, opts)?;
        (Surface::Triangles(fine), attrs.clone(), Some(pos))
    } else {
        // the attributes ride on the same refinement as the f64 points
        let r = Refiner::new(mesh, scheme, levels, opts)?;
        let pos = refined_f64(&r, &control)?;
        let fine = Mesh { positions: pos.iter().map(|p| p.as_vec3()).collect(), ..r.mesh() };
        (Surface::Triangles(fine), r.attributes(attrs)?, Some(pos))
    };
    let st = Stats { total_ms: t0.elapsed().as_secs_f64() * 1e3, ..Default::default() };
    Ok((made.0, made.1, made.2, st))
}

/// A polygon scheme's levels in f64 (their tables kept).
fn polygons_f64<I>(pm: &PolyMesh, model: &Model, how: &Refinement) -> Result<Made<I>> {
    let (scheme, levels, opts, pattrs) = (how.scheme, how.levels, &how.opts, model.attrs);
    let t0 = Instant::now();
    let control = control_f64(model, &pm.positions);
    let (fine, pos, fa) = if pattrs.is_empty() || levels == 0 {
        let (fine, pos) = subdivide_f64(pm, &control, scheme, levels, opts)?;
        (fine, pos, pattrs.clone())
    } else {
        // the attributes ride on the same refinement as the f64 points
        let r = Refiner::new(pm, scheme, levels, opts)?;
        let pos = refined_f64(&r, &control)?;
        let rounded = pos.iter().map(|p| p.as_vec3()).collect();
        (refined_polygons(&r, rounded), pos, r.attributes(pattrs)?)
    };
    let st = Stats { total_ms: t0.elapsed().as_secs_f64() * 1e3, ..Default::default() };
    Ok((Surface::Polygons(fine), fa, Some(pos), st))
}

/// The refiner's finest polygons with `positions`, or (no levels) its cage.
fn refined_polygons(r: &Refiner, positions: Vec<Vec3>) -> PolyMesh {
    match r.polygons() {
        Some(pt) => PolyMesh { pt: pt.clone(), positions },
        None => PolyMesh::from_mesh(&Mesh { positions, ..r.cage() }),
    }
}

/// The refiner's finest points from the f64 control points `control`.
fn refined_f64(r: &Refiner, control: &[DVec3]) -> Result<Vec<DVec3>> {
    let flat: Vec<f64> = control.iter().flat_map(|p| p.to_array()).collect();
    Ok(r.refine(&flat, 3)?.chunks_exact(3).map(DVec3::from_slice).collect())
}

/// The stats of a refiner's levels, its attributes too: the time since `t0`.
fn refiner_stats(r: &Refiner, t0: Instant) -> Stats {
    Stats { total_ms: t0.elapsed().as_secs_f64() * 1e3, ..r.stats().clone() }
}
