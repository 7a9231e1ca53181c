//! Whole-mesh topology: Euler characteristic, boundary loops, connected
//! components, genus and the valence histogram.

use super::{BORDER, CornerTable, n, p};

/// Summary of a mesh's topology (what `subdiv info` prints).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Topology {
    /// Vertices.
    pub vertices: usize,
    /// Edges.
    pub edges: usize,
    /// Triangles.
    pub faces: usize,
    /// Border edges.
    pub border_edges: usize,
    /// Closed loops of border edges.
    pub boundary_loops: usize,
    /// Connected components (through shared edges; vertices are manifold).
    pub components: usize,
    /// `V - E + F`.
    pub euler: i64,
    /// Genus of the closed surface obtained by capping each boundary loop,
    /// summed over components: `sum (2 - chi_i - b_i) / 2`.
    pub genus: i64,
    /// `histogram[k]` = number of vertices with `k` edges.
    pub valence_histogram: Vec<usize>,
    /// Inner diagonals of polygons drawn as triangles (edges of generation
    /// [`super::Generations::HIDDEN`]): the mesh stands for
    /// `faces - diagonals` polygons.
    pub diagonals: usize,
}

impl Topology {
    /// Is the mesh closed (no border edge)?
    pub fn is_closed(&self) -> bool {
        self.border_edges == 0
    }
}

/// Computes the [`Topology`] of a table in O(n).
pub fn topology(ct: &CornerTable) -> Topology {
    let nv = ct.num_vertices();
    let nf = ct.num_triangles();
    let border_edges = ct.num_border_edges();
    let edges = ct.num_edges();
    // components over triangles
    let comp_of_tri = triangle_components(ct);
    let components = comp_of_tri.iter().copied().max().map_or(0, |m| m as usize + 1);
    let mut cv = vec![0i64; components];
    let mut ce = vec![0i64; components];
    let mut cf = vec![0i64; components];
    let mut cb = vec![0i64; components];
    for (t, &k) in comp_of_tri.iter().enumerate() {
        cf[k as usize] += 1;
        for c in 3 * t as u32..3 * t as u32 + 3 {
            if super::owns_edge(c, ct.o_table()[c as usize]) {
                ce[k as usize] += 1;
            }
        }
    }
    for v in 0..nv {
        cv[comp_of_tri[ct.c_table()[v] as usize / 3] as usize] += 1;
    }
    // boundary loops: follow border edges; the border edge leaving vertex a is
    // the one opposite p(C[a]) (C[a] starts the fan at the border).
    let mut seen = vec![false; ct.num_corners()];
    let mut boundary_loops = 0;
    for c0 in 0..ct.num_corners() as u32 {
        if ct.o_table()[c0 as usize] != BORDER || seen[c0 as usize] {
            continue;
        }
        boundary_loops += 1;
        cb[comp_of_tri[c0 as usize / 3] as usize] += 1;
        let mut c = c0;
        loop {
            seen[c as usize] = true;
            // edge opposite c runs v(n(c)) -> v(p(c)); the next starts at v(p(c))
            let b = ct.vtx(p(c));
            let next = p(ct.c_table()[b as usize]);
            if seen[next as usize] {
                break;
            }
            c = next;
        }
    }
    let genus = (0..components).map(|k| (2 - (cv[k] - ce[k] + cf[k]) - cb[k]) / 2).sum();
    let maxval = ct.valences().iter().copied().max().unwrap_or(0) as usize;
    let mut valence_histogram = vec![0; maxval + 1];
    for &k in ct.valences() {
        valence_histogram[k as usize] += 1;
    }
    Topology {
        vertices: nv,
        edges,
        faces: nf,
        border_edges,
        boundary_loops,
        components,
        euler: nv as i64 - edges as i64 + nf as i64,
        genus,
        valence_histogram,
        diagonals: diagonals(ct),
    }
}

/// The inner diagonals of `ct`'s polygons (none without edge generations).
pub(crate) fn diagonals(ct: &CornerTable) -> usize {
    if !ct.generations().is_some_and(super::Generations::may_hide) {
        return 0;
    }
    (0..ct.num_corners() as u32)
        .filter(|&c| {
            let o = ct.o_table()[c as usize];
            o != BORDER && super::owns_edge(c, o) && ct.edge_generation(c) == super::Generations::HIDDEN
        })
        .count()
}

/// Component id of every triangle (0-based, in order of first triangle).
pub(crate) fn triangle_components(ct: &CornerTable) -> Vec<u32> {
    let nf = ct.num_triangles();
    let mut comp = vec![u32::MAX; nf];
    let mut next = 0u32;
    let mut stack = Vec::new();
    for t0 in 0..nf {
        if comp[t0] != u32::MAX {
            continue;
        }
        comp[t0] = next;
        stack.push(t0 as u32);
        while let Some(t) = stack.pop() {
            for c in 3 * t..3 * t + 3 {
                if let Some(x) = ct.o(c) {
                    let tx = (x / 3) as usize;
                    if comp[tx] == u32::MAX {
                        comp[tx] = next;
                        stack.push(tx as u32);
                    }
                }
            }
        }
        next += 1;
    }
    comp
}

/// Checks every corner-table identity; returns the first violation.
/// Used by tests after every split.
///
/// # Errors
/// A description of the first identity that fails.
pub fn check_invariants(ct: &CornerTable) -> Result<(), String> {
    let nc = ct.num_corners() as u32;
    for c in 0..nc {
        if let Some(x) = ct.o(c) {
            if x >= nc || ct.o(x) != Some(c) {
                return Err(format!("o(o({c})) != {c}"));
            }
            if ct.vtx(n(x)) != ct.vtx(p(c)) || ct.vtx(p(x)) != ct.vtx(n(c)) {
                return Err(format!("orientation identity fails at corner {c}"));
            }
        }
        if let Some(s) = ct.s(c)
            && (ct.vtx(s) != ct.vtx(c) || ct.u(s) != Some(c))
        {
            return Err(format!("swing identity fails at corner {c}"));
        }
    }
    for v in 0..ct.num_vertices() as u32 {
        let c = ct.c_table()[v as usize];
        if ct.vtx(c) != v {
            return Err(format!("C[{v}] is not a corner of {v}"));
        }
        if ct.is_boundary_vertex(v) && ct.u(c).is_some() {
            return Err(format!("C[{v}] is not the first corner of its boundary fan"));
        }
        let corners = ct.fan(v).count() as u32;
        let want = corners + u32::from(ct.is_boundary_vertex(v));
        if ct.valences()[v as usize] != want {
            return Err(format!("valence of {v} is {} but its fan has {want} edges", ct.valences()[v as usize]));
        }
    }
    Ok(())
}
