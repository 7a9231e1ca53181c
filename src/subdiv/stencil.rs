//! The stencil of one refined vertex: its weights over the control
//! vertices, exact in f64, and the rule that made it at each level
//! (`subdiv info --stencil`, the viewer's Inspect mode).
//!
//! ```text
//! levels    the level tables are split as `subdivide` splits them (its
//!           numbering: old vertices keep their ids, then one point per
//!           edge in owner order, then, for the polygon schemes, one per
//!           face), the rows recorded by the rule code the refinement runs
//!           (`tables::plan`, `tables::poly_plan`), weights kept in f64
//! compose   w_L = e_V; from level L down to 1, w_{l-1} = sum_i w_l[i] row_l(i)
//!           (only the rows of the vertices in the support are recorded)
//! lineage   V is an old vertex at level l when V < vertices(l - 1), else
//!           the level made it as an edge (or face) point: the rules named
//!           are the one that made it and the vertex rule of every level
//!           after
//! ```

use super::Scheme;
use super::refine::build::{Table, tables};
use super::rules::features::{Features, Mask, Rule};
use super::tables::plan::{LevelTable, LevelTables, record_rows_of};
use super::tables::poly_plan::record_poly_level;
use super::tables::rows::LevelPlan;
use crate::mesh::poly::PolyTable;
use crate::mesh::{CornerTable, Mesh};
use crate::{Error, Options, Result};
use glam::DVec3;
use std::collections::BTreeMap;

/// A refined vertex's stencil over the control vertices.
#[derive(Clone, Debug, PartialEq)]
pub struct Stencil {
    /// The vertex, numbered as `subdivide` numbers its level.
    pub vertex: u32,
    /// The level.
    pub level: u32,
    /// The scheme.
    pub scheme: Scheme,
    /// The weights, sorted by control vertex (zeros left out).
    pub weights: Vec<(u32, f64)>,
    /// The weighted sum of the control positions, in f64.
    pub position: DVec3,
    /// The rule that made the vertex at each level from the one that
    /// created it (0: a control vertex) to `level`.
    pub rules: Vec<(u32, String)>,
}

impl LevelTable<'_> {
    fn num_vertices(&self) -> usize {
        match self {
            LevelTable::Triangles(ct, _) => ct.num_vertices(),
            LevelTable::Polygons(pt) => pt.num_vertices(),
        }
    }
}

/// The stencil of vertex `vertex` of level `levels` of `scheme` on `mesh`
/// with `opts` (boundary, creasing, Loop's beta, tension).
///
/// # Errors
/// [`Error::Usage`] for a vertex out of range; [`Error::TooLarge`] when the
/// levels would not fit in memory.
pub fn stencil(mesh: &Mesh, scheme: Scheme, levels: u32, opts: &Options, vertex: u32) -> Result<Stencil> {
    let held = level_tables(mesh, scheme, levels, opts)?;
    let tables: Vec<LevelTable> = (0..held.len()).filter_map(|i| held.level(i)).collect();
    let fine = tables.last().map_or(mesh.positions.len(), next_count);
    if vertex as usize >= fine {
        return Err(Error::Usage(format!(
            "vertex {vertex} out of range: level {levels} of {scheme} has {fine} vertices"
        )));
    }
    let mut w: BTreeMap<u32, f64> = BTreeMap::from([(vertex, 1.0)]);
    for t in tables.iter().rev() {
        w = step_down(&w, t, scheme, opts);
    }
    let weights: Vec<(u32, f64)> = w.into_iter().filter(|&(_, x)| x != 0.0).collect();
    let position = weights.iter().map(|&(j, x)| mesh.positions[j as usize].as_dvec3() * x).sum();
    let rules = lineage(&tables, scheme, opts, vertex);
    Ok(Stencil { vertex, level: levels, scheme, weights, position, rules })
}

/// The tables of levels `0..levels` (the last one's split is the level
/// asked for), as the level builder makes them for `subdivide`.
fn level_tables(mesh: &Mesh, scheme: Scheme, levels: u32, opts: &Options) -> Result<LevelTables> {
    let how = (scheme, levels, opts);
    Ok(match scheme.is_polygonal() {
        true => Table::into_tables(tables(&PolyTable::from_corner_table(&mesh.ct), how)?.0),
        false => Table::into_tables(tables(&mesh.ct, how)?.0),
    })
}

/// Vertices of the level split from `t`.
fn next_count(t: &LevelTable) -> usize {
    match t {
        LevelTable::Triangles(ct, owners) => ct.num_vertices() + owners.len(),
        LevelTable::Polygons(pt) => pt.num_vertices() + pt.num_edges() + pt.num_faces(),
    }
}

/// Whether the new vertex `v` of the level split from `t` is an old vertex
/// the scheme copies unchanged.
fn copied(t: &LevelTable, scheme: Scheme, v: u32) -> bool {
    let old = (v as usize) < t.num_vertices();
    old && matches!(scheme, Scheme::Midpoint | Scheme::Butterfly | Scheme::ModifiedButterfly | Scheme::Bilinear)
}

/// The weights over level `t`'s vertices of the weights `w` over the level
/// split from it (level `l + 1`).
fn step_down(w: &BTreeMap<u32, f64>, t: &LevelTable, scheme: Scheme, opts: &Options) -> BTreeMap<u32, f64> {
    let ids: Vec<u32> = w.keys().copied().filter(|&v| !copied(t, scheme, v)).collect();
    let plan: LevelPlan<f64> = match t {
        LevelTable::Triangles(ct, owners) => record_rows_of(ct, owners, (scheme, opts), &ids),
        LevelTable::Polygons(pt) => record_poly_level(pt, scheme, opts, Some(&ids)),
    };
    let mut out: BTreeMap<u32, f64> = BTreeMap::new();
    let mut k = 0;
    for (&v, &x) in w {
        if copied(t, scheme, v) {
            *out.entry(v).or_insert(0.0) += x;
            continue;
        }
        let (a, b) = (plan.offsets[k] as usize, plan.offsets[k + 1] as usize);
        for (&j, &wj) in plan.indices[a..b].iter().zip(&plan.weights[a..b]) {
            *out.entry(j).or_insert(0.0) += x * wj;
        }
        k += 1;
    }
    out
}

/// The rule that made `vertex` at each level (see the module docs).
fn lineage(tables: &[LevelTable], scheme: Scheme, opts: &Options, vertex: u32) -> Vec<(u32, String)> {
    // levels below the one that made it: those it is not yet a vertex of
    let created = tables.iter().filter(|t| vertex as usize >= t.num_vertices()).count();
    let mut out = Vec::with_capacity(tables.len() + 1);
    if created == 0 {
        out.push((0, "control vertex".to_string()));
    }
    for (l, t) in tables.iter().enumerate().skip(created.saturating_sub(1)) {
        let level = l + 1;
        let name = if level == created {
            new_point_rule(t, scheme, opts, vertex)
        } else {
            vertex_rule(t, scheme, opts, vertex)
        };
        out.push((level as u32, name));
    }
    out
}

/// The rule of the vertex point of old vertex `v` of `t`.
fn vertex_rule(t: &LevelTable, scheme: Scheme, opts: &Options, v: u32) -> String {
    if copied(t, scheme, v) {
        return "kept (the scheme interpolates its vertices)".into();
    }
    let (features, boundary, valence) = match t {
        LevelTable::Triangles(ct, _) => (Features::of(*ct, opts.creasing), ct.is_boundary_vertex(v), ct.valence(v)),
        LevelTable::Polygons(pt) => {
            (Features::of(*pt, opts.creasing), pt.is_boundary_vertex(v), pt.valences()[v as usize])
        }
    };
    if let Some(f) = features.as_ref().and_then(|f| f.vertex(v)).filter(|f| f.parent != Mask::Smooth) {
        let parent = mask_name(f.parent);
        return if f.parent == f.child || f.weight >= 1.0 {
            format!("{parent} vertex")
        } else {
            format!("{parent} vertex blended into {}, weight {}", mask_name(f.child), f.weight)
        };
    }
    let dart = features.as_ref().and_then(|f| f.vertex(v)).is_some_and(|f| f.rule == Rule::Dart);
    match (scheme, boundary) {
        (_, true) => "boundary vertex (3/4 v + 1/8 of its two boundary neighbours)".into(),
        (Scheme::Loop, false) => {
            let beta = opts.loop_beta.beta(valence);
            format!("vertex point of valence {valence} (beta {beta}){}", if dart { ", a dart" } else { "" })
        }
        (Scheme::CatmullClark, false) => {
            format!(
                "vertex point of valence {valence} ((n-2)/n v + edge and face points / n^2){}",
                if dart { ", a dart" } else { "" }
            )
        }
        (Scheme::Jarek, false) => {
            format!("vertex point of valence {valence} (v + d_v, d_v = (mean of the ring - v) / 8)")
        }
        _ => format!("vertex point of valence {valence}"),
    }
}

fn mask_name(m: Mask) -> &'static str {
    match m {
        Mask::Smooth => "smooth",
        Mask::Crease(..) => "crease",
        Mask::Corner => "corner",
    }
}

/// The rule of the point the split of `t` made as new vertex `v`.
fn new_point_rule(t: &LevelTable, scheme: Scheme, opts: &Options, v: u32) -> String {
    match t {
        LevelTable::Triangles(ct, owners) => {
            let c = owners[v as usize - ct.num_vertices()];
            edge_rule(ct, scheme, opts, c)
        }
        LevelTable::Polygons(pt) => {
            let (nv, ne) = (pt.num_vertices(), pt.num_edges());
            let i = v as usize - nv;
            if i >= ne {
                let f = (i - ne) as u32;
                return format!("face point of a {}-gon (the mean of its corners)", pt.face_size(f));
            }
            let c = pt.edge_owners().nth(i).unwrap_or(0);
            let features = Features::of(*pt, opts.creasing);
            if let Some(w) = features.as_ref().and_then(|f| f.edge(c)) {
                return crease_edge_name(w, "(1/2, 1/2)");
            }
            match (scheme, pt.twin(c)) {
                (Scheme::Bilinear, _) => "edge point (the midpoint)".into(),
                (_, None) => "boundary edge point (the midpoint)".into(),
                _ => "edge point (its ends and the two face points, 1/4 each)".into(),
            }
        }
    }
}

/// A crease edge's rule by its crease weight `w`.
fn crease_edge_name(w: f32, curve: &str) -> String {
    if w == 1.0 {
        format!("crease edge {curve}")
    } else {
        format!("semi-sharp edge: crease {curve} blended with the smooth rule, weight {w}")
    }
}

/// The rule of the point of the triangle edge owned by `c`.
fn edge_rule(ct: &CornerTable, scheme: Scheme, opts: &Options, c: u32) -> String {
    let butterfly = matches!(scheme, Scheme::Butterfly | Scheme::ModifiedButterfly);
    let curve = if butterfly { "(the 4-point curve rule)" } else { "(1/2, 1/2)" };
    if let Some(w) = Features::of(ct, opts.creasing).as_ref().and_then(|f| f.edge(c)) {
        return crease_edge_name(w, curve);
    }
    let (a, b) = (ct.vtx(crate::mesh::n(c)), ct.vtx(crate::mesh::p(c)));
    let Some(_) = ct.o(c) else {
        return match scheme {
            Scheme::Butterfly | Scheme::ModifiedButterfly => "boundary edge (the 4-point rule along the border)".into(),
            _ => "boundary edge (the midpoint)".into(),
        };
    };
    match scheme {
        Scheme::Midpoint => "edge midpoint".into(),
        Scheme::Loop => "interior edge (3/8 its ends, 1/8 the two opposite vertices)".into(),
        Scheme::Jarek => "edge point (the midpoint minus the mean of its ends' displacements)".into(),
        Scheme::Butterfly => "8-point butterfly (1/2, 1/8, -1/16; ghosts across borders)".into(),
        Scheme::ModifiedButterfly => modified_butterfly_rule(ct, a, b, opts.tension),
        _ => "edge point".into(),
    }
}

/// Which of Zorin's cases the modified butterfly takes on the interior
/// edge `(a, b)`.
fn modified_butterfly_rule(ct: &CornerTable, a: u32, b: u32, tension: f32) -> String {
    let ev = |x: u32| !ct.is_boundary_vertex(x) && ct.valence(x) != 6;
    let (ka, kb) = (ct.valence(a), ct.valence(b));
    if ct.is_boundary_vertex(a) || ct.is_boundary_vertex(b) {
        return "interior edge at the border (Zorin's boundary cases)".into();
    }
    match (ev(a), ev(b)) {
        (true, true) => format!("the mean of the extraordinary rules of its ends (valences {ka} and {kb})"),
        (true, false) => format!("the extraordinary rule of its valence-{ka} end"),
        (false, true) => format!("the extraordinary rule of its valence-{kb} end"),
        (false, false) => format!("regular 10-point butterfly (tension {tension})"),
    }
}
