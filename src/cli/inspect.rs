//! `subdiv info --corner C` and `--stencil V`: the corner table's operators
//! at a corner, and a refined vertex's weights over the control vertices
//! with the rule that made it at each level.

use super::args::SubdivArgs;
use super::print_json;
use serde::Serialize;
use std::path::Path;
use subdiv::mesh::PolyMesh;
use subdiv::mesh::{corner_ops, poly_corner_ops};
use subdiv::rules::stencil;
use subdiv::{Error, Mesh, Result};

/// `info --corner --json` of a triangle table.
#[derive(Serialize)]
struct CornerJson {
    corner: u32,
    triangle: u32,
    vertex: u32,
    n: u32,
    p: u32,
    o: Option<u32>,
    l: Option<u32>,
    r: Option<u32>,
    s: Option<u32>,
    u: Option<u32>,
}

/// `info --corner --json` of a polygon table.
#[derive(Serialize)]
struct PolyCornerJson {
    corner: u32,
    face: u32,
    vertex: u32,
    next: u32,
    prev: u32,
    twin: Option<u32>,
    swing: Option<u32>,
}

/// `info --stencil --json`.
#[derive(Serialize)]
struct StencilJson {
    vertex: u32,
    level: u32,
    scheme: String,
    position: [f64; 3],
    weights: Vec<(u32, f64)>,
    rules: Vec<RuleJson>,
}

#[derive(Serialize)]
struct RuleJson {
    level: u32,
    rule: String,
}

/// A corner id shown, `-` across a border.
fn shown(x: Option<u32>) -> String {
    x.map_or_else(|| "-".to_string(), |c| c.to_string())
}

/// `info --corner c`: the polygon table's operators for a file of polygons
/// (corners in the file's order), else the triangle table's (corner `c % 3`
/// of triangle `c / 3`).
pub(crate) fn corner(input: &Path, mesh: &Mesh, c: u32, json: bool) -> Result<()> {
    let out_of_range = |n: usize| Error::Usage(format!("corner {c} out of range: {} has {n} corners", input.display()));
    if PolyMesh::is_polygonal(mesh) {
        let pm = PolyMesh::from_mesh(mesh);
        let x = poly_corner_ops(&pm.pt, c).ok_or_else(|| out_of_range(pm.pt.num_corners()))?;
        if json {
            let (corner, face, vertex, next, prev, twin, swing) =
                (x.corner, x.face, x.vertex, x.next, x.prev, x.twin, x.swing);
            return print_json(&PolyCornerJson { corner, face, vertex, next, prev, twin, swing });
        }
        println!("corner {} of polygon {} (vertex {}), the polygon table's operators:", x.corner, x.face, x.vertex);
        println!("  next {}  prev {}  twin {}  swing {}", x.next, x.prev, shown(x.twin), shown(x.swing));
        return Ok(());
    }
    let x = corner_ops(&mesh.ct, c).ok_or_else(|| out_of_range(mesh.ct.num_corners()))?;
    if json {
        let (corner, triangle, vertex, n, p) = (x.corner, x.triangle, x.vertex, x.n, x.p);
        return print_json(&CornerJson { corner, triangle, vertex, n, p, o: x.o, l: x.l, r: x.r, s: x.s, u: x.u });
    }
    println!("corner {} of triangle {} (vertex {}), `-` across a border:", x.corner, x.triangle, x.vertex);
    println!("  n {}  p {}  o {}  l = o(n) {}  r = o(p) {}", x.n, x.p, shown(x.o), shown(x.l), shown(x.r));
    println!("  s = n(o(n)) {}  u = p(o(p)) {}", shown(x.s), shown(x.u));
    Ok(())
}

/// `info --stencil v --levels L`: the weights of refined vertex `v` over
/// the control vertices and the rules that made it.
pub(crate) fn stencil_of(mesh: &Mesh, sub: &SubdivArgs, v: u32, json: bool) -> Result<()> {
    let s = &sub.scheme;
    let levels = sub.levels_or(1);
    let st = stencil(mesh, s.scheme(), levels, &s.options(), v)?;
    let total: f64 = st.weights.iter().map(|w| w.1).sum();
    if json {
        return print_json(&StencilJson {
            vertex: st.vertex,
            level: st.level,
            scheme: st.scheme.to_string(),
            position: st.position.to_array(),
            weights: st.weights,
            rules: st.rules.into_iter().map(|(level, rule)| RuleJson { level, rule }).collect(),
        });
    }
    println!(
        "vertex {} of level {} of {}: {} control vertices, weights summing to {total}",
        v,
        levels,
        s.scheme(),
        st.weights.len()
    );
    println!("position: {} {} {}", st.position.x, st.position.y, st.position.z);
    for (level, rule) in &st.rules {
        println!("  level {level}: {rule}");
    }
    for (j, w) in &st.weights {
        println!("  {j:>8}  {w}");
    }
    Ok(())
}
