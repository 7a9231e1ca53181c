//! `subdiv info` (meshes and `.bzc` curves) and `subdiv models`.

use super::args::{InputArgs, SubdivArgs};
use super::print_json;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use subdiv::io::{ReadOptions, Topology};
use subdiv::mesh::BoundaryInterpolation;
use subdiv::mesh::{PolyMesh, PolyTable};
use subdiv::mesh::{Topology as MeshTopology, topology};
use subdiv::rules;
use subdiv::rules::Summary;
use subdiv::{Error, Mesh, MeshError, Result, bundled};

/// `subdiv info` arguments.
#[derive(clap::Args)]
pub struct InfoArgs {
    /// Input model: a mesh file, a .bzc curve or bundled:NAME (see `subdiv models`).
    input: PathBuf,
    /// Print as JSON.
    #[arg(long)]
    json: bool,
    /// `--repair`: always analyse and describe the repaired mesh, even when the input is valid.
    #[command(flatten)]
    from: InputArgs,
    /// The sharp features counted (`--crease-angle`, `--boundary`); the
    /// scheme, its options and `--levels` are those of `--stencil`.
    #[command(flatten)]
    sub: SubdivArgs,
    /// Print Rossignac's corner operators at corner C (n, p, o, l, r, s, u;
    /// corner C % 3 of triangle C / 3), or the polygon table's (next, prev,
    /// twin, swing) for a file of polygons, corners in the file's order.
    #[arg(long, value_name = "C", conflicts_with = "stencil")]
    corner: Option<u32>,
    /// Print the weights of vertex V of level --levels (numbered as
    /// `subdivide` writes that level) over the control vertices, exact, and
    /// the rule that made it at each level.
    #[arg(long, value_name = "V")]
    stencil: Option<u32>,
}

/// What `info --json` says of the file's records (flattened into
/// [`MeshInfo`]).
#[derive(Serialize)]
struct FileRecords {
    /// The format read.
    format: &'static str,
    /// Faces in the file, before polygons are fanned.
    file_faces: usize,
    /// Faces of the file by corner count (8 stands for 8 or more).
    face_sizes: BTreeMap<usize, usize>,
    /// Polygons fanned into triangles for the triangle schemes.
    polygons_fanned: usize,
}

/// `subdiv info --json` of a mesh. `edges`, `faces` and `valence` are the
/// file's own (polygons as the file has them); a file with polygons adds
/// the triangles the triangle schemes refine as `triangulated`.
#[derive(Serialize)]
struct MeshInfo {
    file: String,
    vertices: usize,
    edges: usize,
    faces: usize,
    closed: bool,
    boundary_loops: usize,
    border_edges: usize,
    components: usize,
    euler: i64,
    genus: i64,
    unreferenced_dropped: usize,
    non_manifold_edges: usize,
    non_manifold_vertices: usize,
    repaired: bool,
    #[serde(flatten)]
    records: FileRecords,
    /// Faces tagged as holes (`t hole`): left out of the surface.
    holes: usize,
    #[serde(flatten)]
    sharp: SharpInfo,
    valence: BTreeMap<usize, usize>,
    /// The fanned triangles, when the file has polygons.
    #[serde(skip_serializing_if = "Option::is_none")]
    triangulated: Option<Counts>,
    /// What a USD stage says of its prims, units and time.
    #[serde(skip_serializing_if = "Option::is_none")]
    stage: Option<StageInfo>,
}

/// `info` of a stage: its prims, units and time.
#[derive(Serialize)]
struct StageInfo {
    prims: Vec<PrimInfo>,
    up_axis: Option<&'static str>,
    meters_per_unit: Option<f64>,
    /// The time code the points were read at (null: default values).
    time: Option<f64>,
    /// The time codes the points are sampled at.
    time_samples: Vec<f64>,
}

/// One prim of [`StageInfo`].
#[derive(Serialize)]
struct PrimInfo {
    path: String,
    /// `subdivisionScheme`.
    scheme: &'static str,
    /// Whether it is subdivided (`none` is not: the cage is its surface).
    subdivided: bool,
    faces: usize,
}

impl StageInfo {
    /// What `attrs`' scene says, the faces of each prim counted on `mesh`'s polygons.
    fn of(mesh: &Mesh, attrs: &subdiv::mesh::Attributes) -> Option<StageInfo> {
        let scene = attrs.scene()?;
        let (_, pattrs) = PolyMesh::from_mesh_with_attributes(mesh, attrs);
        let mut faces = vec![0usize; scene.prims.len()];
        for &g in pattrs.materials.iter().flat_map(|m| &m.face) {
            if let Some(n) = scene.prim_of.get(g as usize).and_then(|&p| faces.get_mut(p as usize)) {
                *n += 1;
            }
        }
        let prims = scene
            .prims
            .iter()
            .zip(faces)
            .map(|(p, faces)| {
                let scheme = p.options.scheme.unwrap_or_default();
                let subdivided = scheme != subdiv::mesh::FileScheme::None;
                PrimInfo { path: p.path.clone(), scheme: scheme.token(), subdivided, faces }
            })
            .collect();
        let up_axis = scene.up_axis.map(|u| if u == subdiv::mesh::UpAxis::Z { "Z" } else { "Y" });
        let (meters_per_unit, time, time_samples) = (scene.meters_per_unit, scene.time, scene.times.clone());
        Some(StageInfo { prims, up_axis, meters_per_unit, time, time_samples })
    }

    /// The lines `info` prints.
    fn print(&self) {
        for p in &self.prims {
            let what = match p.subdivided {
                true => format!("subdivisionScheme {}", p.scheme),
                false => "subdivisionScheme none: not subdivided, the cage is its surface at every level".into(),
            };
            println!("prim:            {} ({} faces; {what})", p.path, p.faces);
        }
        if self.up_axis.is_some() || self.meters_per_unit.is_some() {
            let up = self.up_axis.map_or(String::new(), |u| format!("upAxis {u}"));
            let m = self.meters_per_unit.map_or(String::new(), |m| format!(" metersPerUnit {m}"));
            println!("stage:           {}", format!("{up}{m}").trim());
        }
        if let Some(t) = self.time {
            let n = self.time_samples.len();
            let (first, last) =
                (self.time_samples.first().copied().unwrap_or(t), self.time_samples.last().copied().unwrap_or(t));
            println!("time:            points at time {t} ({n} samples, {first} to {last}; --time T reads another)");
        }
    }
}

/// Edges, faces and the valence histogram (valence -> vertices) of a mesh.
#[derive(Serialize)]
struct Counts {
    edges: usize,
    faces: usize,
    valence: BTreeMap<usize, usize>,
    /// Faces tagged as holes.
    #[serde(skip)]
    holes: usize,
}

impl Counts {
    /// The counts of a polygon table.
    fn polygons(pt: &PolyTable) -> Counts {
        Counts {
            edges: pt.num_edges(),
            faces: pt.num_faces(),
            valence: histogram(pt.valences().iter().map(|&k| k as usize)),
            holes: pt.holes().len(),
        }
    }

    /// The counts of the triangle table itself.
    fn triangles(t: &MeshTopology, holes: usize) -> Counts {
        let valence = t.valence_histogram.iter().enumerate().filter(|&(_, &c)| c > 0).map(|(k, &c)| (k, c)).collect();
        Counts { edges: t.edges, faces: t.faces, valence, holes }
    }
}

/// The counts `info` gives of `mesh` (whose topology is `t`): its own
/// edges, faces and valences, the fan's when it stands for polygons, and
/// its sharp features. Euler characteristic, genus, borders and components
/// are the same for the polygons and their fans; edges, faces, valences and
/// one-face corners are the polygons'.
fn own_counts(mesh: &Mesh, t: &MeshTopology, boundary: BoundaryInterpolation) -> (Counts, Option<Counts>, Summary) {
    if !PolyMesh::is_polygonal(mesh) {
        return (Counts::triangles(t, mesh.ct.holes().len()), None, rules::summary(&mesh.ct, boundary));
    }
    // the triangles joined back across the hidden diagonals (PolyMesh::from_mesh)
    let pt = PolyTable::from_corner_table(&mesh.ct);
    (Counts::polygons(&pt), Some(Counts::triangles(t, mesh.ct.holes().len())), rules::poly_summary(&pt, boundary))
}

/// How many of `values` are each value.
fn histogram(values: impl Iterator<Item = usize>) -> BTreeMap<usize, usize> {
    let mut h = BTreeMap::new();
    for k in values {
        *h.entry(k).or_insert(0) += 1;
    }
    h
}

/// The sharp-feature counts of [`MeshInfo`] (flattened into it).
#[derive(Serialize)]
struct SharpInfo {
    sharp_edges: usize,
    infinitely_sharp_edges: usize,
    sharp_vertices: usize,
    corners: usize,
    darts: usize,
    crease_vertices: usize,
}

/// `subdiv info --json` of a curve.
#[derive(Serialize)]
struct CurveInfo {
    file: String,
    kind: &'static str,
    control_points: usize,
    degree: usize,
    length: f32,
}

/// Is this load error a topology problem that the repair analysis can describe?
fn is_topology_error(e: &Error) -> bool {
    let source = match e {
        Error::Mesh { source, .. } | Error::Invalid(source) => source,
        _ => return false,
    };
    matches!(
        source,
        MeshError::NonManifoldEdge { .. }
            | MeshError::NonManifoldVertex { .. }
            | MeshError::InconsistentOrientation { .. }
            | MeshError::DegenerateFace { .. }
    )
}

/// `subdiv models`: one line per bundled model, its command-line name and what it is.
pub(crate) fn models() {
    let width = bundled::MODELS.iter().map(|m| m.cli_name().len()).max().unwrap_or(0);
    for m in bundled::MODELS {
        println!("{:<width$}  {}", m.cli_name(), m.what);
    }
}

/// Is this model argument a `.bzc` curve (a file or a bundled one)?
fn is_curve(input: &Path) -> bool {
    input.extension().is_some_and(|e| e.eq_ignore_ascii_case("bzc"))
}

/// `subdiv info` of a `.bzc` Bezier curve: control points, degree, ends,
/// the point at t = 1/2 and the polyline length.
fn curve_info(input: &Path, limits: &subdiv::io::Limits, json: bool) -> Result<()> {
    let control = bundled::load_curve(input, limits)?;
    let at = |t: f32| subdiv::io::bezier::de_casteljau(&control, t).unwrap_or_default();
    let (first, mid, last) = (at(0.0), at(0.5), at(1.0));
    let length: f32 =
        subdiv::io::bezier::curve_polyline(&control, 256).windows(2).map(|w| (w[1] - w[0]).length()).sum();
    let degree = control.len().saturating_sub(1);
    if json {
        let file = input.display().to_string();
        return print_json(&CurveInfo { file, kind: "bezier_curve", control_points: control.len(), degree, length });
    }
    println!("file:            {}", input.display());
    println!("kind:            Bezier curve (.bzc), not a mesh: no faces to subdivide (`subdiv view` draws it)");
    println!("control points:  {} (degree {degree})", control.len());
    println!("ends:            ({:.4}, {:.4}) .. ({:.4}, {:.4})", first.x, first.y, last.x, last.y);
    println!("point at t=1/2:  ({:.4}, {:.4})", mid.x, mid.y);
    println!("length:          {length:.4}");
    Ok(())
}

/// The subdivision options given to `info` without `--stencil`, where they
/// would change nothing (info alone counts the control mesh).
fn unused_subdivision_option(a: &InfoArgs) -> Option<&'static str> {
    let s = &a.sub.scheme;
    let given = [
        ("--scheme", s.scheme_flag.is_some()),
        ("--levels", a.sub.levels.is_some()),
        ("--warren", s.warren),
        ("--tension", s.tension != 0.0),
        ("--max-memory", s.max_memory.is_some()),
        ("--uv", s.uv.is_some()),
        ("--triangles", s.triangles.is_some()),
        ("--creasing", s.features.creasing.is_some()),
    ];
    given.into_iter().find(|g| g.1).map(|g| g.0)
}

/// The mesh `info` describes: as the file has it, or, when its topology
/// is invalid (or with `--repair`), analysed and repaired.
fn load(a: &InfoArgs, input: &Path) -> Result<subdiv::io::Loaded> {
    let read = |topology| {
        // the attributes: a stage's prims ride on them
        let opts = ReadOptions { topology, attributes: true, ..a.from.options(false)? };
        bundled::read(input, &opts)
    };
    match if a.from.repair { None } else { Some(read(Topology::Refuse)) } {
        Some(Ok(l)) => Ok(l),
        Some(Err(e)) if !is_topology_error(&e) => Err(e),
        _ => read(Topology::Analyze),
    }
}

/// `subdiv info`.
pub(crate) fn info(a: &InfoArgs) -> Result<()> {
    let input = a.input.as_path();
    if let Some(name) = unused_subdivision_option(a).filter(|_| a.stencil.is_none()) {
        return Err(Error::Usage(format!(
            "{name} applies to --stencil: info alone counts the control mesh and refines nothing"
        )));
    }
    if is_curve(input) {
        return curve_info(input, &a.from.limits.limits()?, a.json);
    }
    let loaded = load(a, input)?;
    let notes = loaded.notes;
    let (mesh, records, report) = (loaded.mesh, notes.vertex_records, notes.repair.clone());
    let dropped = report.as_ref().map_or(notes.unreferenced, |r| r.unreferenced_vertices.count);
    let face_sizes: BTreeMap<usize, usize> =
        notes.face_sizes.iter().enumerate().filter(|&(_, &c)| c > 0).map(|(k, &c)| (k, c)).collect();
    let sub = SubdivArgs { scheme: a.sub.scheme.over(loaded.attributes.options), ..a.sub.clone() };
    let mesh = sub.scheme.features.apply(mesh);
    let stage = StageInfo::of(&mesh, &loaded.attributes);
    if let Some(c) = a.corner {
        return super::inspect::corner(input, &mesh, c, a.json);
    }
    if let Some(v) = a.stencil {
        return super::inspect::stencil_of(&mesh, &sub, v, a.json);
    }
    let (nm_edges, nm_vertices) =
        report.as_ref().map_or((0, 0), |r| (r.non_manifold_edges.count, r.non_manifold_vertices.count));
    let t = topology(&mesh.ct);
    let (own, triangulated, sharp) = own_counts(&mesh, &t, sub.scheme.features.sharp.boundary.unwrap_or_default());
    if a.json {
        return print_json(&MeshInfo {
            file: input.display().to_string(),
            vertices: t.vertices,
            edges: own.edges,
            faces: own.faces,
            closed: t.is_closed(),
            boundary_loops: t.boundary_loops,
            border_edges: t.border_edges,
            components: t.components,
            euler: t.euler,
            genus: t.genus,
            unreferenced_dropped: dropped,
            non_manifold_edges: nm_edges,
            non_manifold_vertices: nm_vertices,
            repaired: report.is_some(),
            records: FileRecords {
                format: loaded.format.name,
                file_faces: notes.faces,
                face_sizes,
                polygons_fanned: notes.fanned,
            },
            holes: own.holes,
            sharp: SharpInfo::of(&sharp),
            valence: own.valence,
            triangulated,
            stage,
        });
    }
    println!("file:            {}", input.display());
    println!("format:          {}", loaded.format.name);
    println!("vertices:        {} ({records} records, {dropped} unreferenced dropped)", t.vertices);
    println!("edges:           {}", own.edges);
    if triangulated.is_some() {
        let sizes: Vec<String> =
            face_sizes.iter().map(|(k, c)| format!("{k}{}:{c}", if *k == 8 { "+" } else { "" })).collect();
        println!("faces:           {} (by corners {}; fanned for the triangle schemes)", own.faces, sizes.join(" "));
    } else {
        println!("faces:           {}", own.faces);
    }
    if own.holes > 0 {
        println!("holes:           {} (faces tagged as holes: left out of the surface)", own.holes);
    }
    println!("closed:          {}", if t.is_closed() { "yes" } else { "no" });
    println!("boundary loops:  {} ({} border edges)", t.boundary_loops, t.border_edges);
    println!("components:      {}", t.components);
    println!("euler:           {}", t.euler);
    println!("genus:           {}", t.genus);
    print_manifold(report.as_ref(), nm_edges, nm_vertices);
    println!(
        "sharp features:  {} sharp edges ({} infinitely sharp), {} sharp vertices; {} corners, {} darts, {} crease vertices",
        sharp.sharp_edges,
        sharp.infinite_edges,
        sharp.sharp_vertices,
        sharp.corners,
        sharp.darts,
        sharp.crease_vertices
    );
    let hist: Vec<String> = own.valence.iter().map(|(k, c)| format!("{k}:{c}")).collect();
    println!("valence:         {}", hist.join(" "));
    let (lo, hi) = mesh.bounds();
    println!("bounds:          [{:.4} {:.4} {:.4}] .. [{:.4} {:.4} {:.4}]", lo.x, lo.y, lo.z, hi.x, hi.y, hi.z);
    if let Some(s) = &stage {
        s.print();
    }
    if let Some(r) = &report {
        print!("{r}");
    }
    Ok(())
}

impl SharpInfo {
    /// The counts of `s`.
    fn of(s: &Summary) -> SharpInfo {
        SharpInfo {
            sharp_edges: s.sharp_edges,
            infinitely_sharp_edges: s.infinite_edges,
            sharp_vertices: s.sharp_vertices,
            corners: s.corners,
            darts: s.darts,
            crease_vertices: s.crease_vertices,
        }
    }
}

/// The manifold line of `info`, with the offending ids when there are any.
fn print_manifold(report: Option<&subdiv::mesh::RepairReport>, nm_edges: usize, nm_vertices: usize) {
    let Some(r) = report else {
        println!("manifold:        yes (0 non-manifold edges, 0 non-manifold vertices)");
        return;
    };
    let b = r.id_base;
    println!(
        "manifold:        {} ({nm_edges} non-manifold edges, {nm_vertices} non-manifold vertices; counts above are of the repaired mesh)",
        if nm_edges + nm_vertices == 0 { "yes" } else { "no" }
    );
    if nm_edges > 0 {
        let ids = r.non_manifold_edges.examples.iter().map(|e| format!("{}-{}", e[0] + b, e[1] + b));
        println!("non-manifold edges:    {}", some_of(ids, nm_edges));
    }
    if nm_vertices > 0 {
        let ids = r.non_manifold_vertices.examples.iter().map(|v| (v + b).to_string());
        println!("non-manifold vertices: {}", some_of(ids, nm_vertices));
    }
}

/// The first [`LISTED`] of `ids` of `total`, and how many more: one line
/// of bounded length however broken the mesh.
fn some_of(ids: impl Iterator<Item = String>, total: usize) -> String {
    let shown: Vec<String> = ids.take(LISTED).collect();
    match total.saturating_sub(shown.len()) {
        0 => shown.join(" "),
        more => format!("{} ... and {more} more", shown.join(" ")),
    }
}

/// Ids listed on one line of `info`.
const LISTED: usize = 20;
