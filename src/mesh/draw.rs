//! What the renderer draws of a table, as flat arrays: each edge once (as
//! vertex pairs, or as corner pairs for a mesh with one vertex per
//! corner), the sharp edges, and the edge generations packed per triangle
//! for the wire shader. The walks over corners live here, so that the
//! renderer only uploads arrays.

use super::{CornerTable, Generations, n, p};

/// The sharp edges (sharpness > 0, borders excluded unless tagged) as pairs
/// of vertex ids.
pub(crate) fn sharp_edge_indices(ct: &CornerTable) -> Vec<u32> {
    let Some(s) = ct.sharpness() else { return Vec::new() };
    s.sharp_corners()
        .iter()
        .filter(|&&(c, _)| super::owns_edge(c, ct.o_entry(c)))
        .flat_map(|&(c, _)| [ct.vtx(n(c)), ct.vtx(p(c))])
        .collect()
}

/// [`sharp_edge_indices`] for a mesh with one GPU vertex per corner: the
/// pairs of corners that end each sharp edge.
pub(crate) fn sharp_corner_pairs(ct: &CornerTable) -> Vec<u32> {
    let Some(s) = ct.sharpness() else { return Vec::new() };
    s.sharp_corners()
        .iter()
        .filter(|&&(c, _)| super::owns_edge(c, ct.o_entry(c)))
        .flat_map(|&(c, _)| [n(c), p(c)])
        .collect()
}

/// The edges drawn: each once, by its owner corner, without the
/// diagonals inside polygons ([`Generations::HIDDEN`]).
fn drawn_edges(ct: &CornerTable) -> impl Iterator<Item = u32> + '_ {
    let hidden = ct.generations().is_some();
    // an edge of holes alone is no edge of the surface
    let of_holes = move |c: u32| ct.is_hole(c / 3) && ct.o(c).is_none_or(|x| ct.is_hole(x / 3));
    ct.edge_owners()
        .filter(move |&c| !hidden || ct.edge_generation(c) != Generations::HIDDEN)
        .filter(move |&c| ct.holes().is_empty() || !of_holes(c))
}

/// The V table as drawn: a hole's triangles collapsed to a point (the same
/// vertex three times, which rasterises to nothing), so every triangle
/// keeps its place for the buffers indexed by triangle.
pub(crate) fn drawn_triangles(ct: &CornerTable) -> std::borrow::Cow<'_, [u32]> {
    if ct.holes().is_empty() {
        return std::borrow::Cow::Borrowed(ct.v_table());
    }
    let mut v = ct.v_table().to_vec();
    for &t in ct.holes() {
        let t = 3 * t as usize;
        (v[t + 1], v[t + 2]) = (v[t], v[t]);
    }
    std::borrow::Cow::Owned(v)
}

/// Each edge once as a pair of vertex ids (see [`CornerTable::edge_owners`]),
/// diagonals inside polygons left out.
pub(crate) fn edge_indices(ct: &CornerTable) -> Vec<u32> {
    drawn_edges(ct).flat_map(|c| [ct.v_table()[n(c) as usize], ct.v_table()[p(c) as usize]]).collect()
}

/// Per triangle `t`, one word as the wire shader reads it (one load per
/// vertex instead of three): five bits for each corner `k` of the triangle,
/// the generation of the edge opposite it (see [`crate::mesh::Generations`])
/// at bit `5k`, and the lowest generation of the edges at its vertex at bit
/// `15 + 5k`. Generations are below 31 (level 30 is far past any memory);
/// 31 marks a hidden diagonal ([`Generations::HIDDEN`]), which the shader
/// never draws.
pub(crate) fn packed_generations(ct: &CornerTable) -> Vec<u32> {
    let nc = ct.num_corners();
    let mut words = vec![0u32; nc / 3];
    let Some(g) = ct.generations() else { return words };
    let corner = g.corners();
    // the edge opposite c ends at v(n(c)) and v(p(c))
    let mut at_vertex = vec![u8::MAX; ct.num_vertices()];
    for (c, &e) in corner.iter().enumerate() {
        for end in [n(c as u32), p(c as u32)] {
            let v = &mut at_vertex[ct.vtx(end) as usize];
            *v = (*v).min(e);
        }
    }
    for (c, &e) in corner.iter().enumerate() {
        let k = 5 * (c % 3) as u32;
        let at_v = at_vertex[ct.vtx(c as u32) as usize];
        words[c / 3] |= u32::from(e.min(31)) << k | u32::from(at_v.min(31)) << (15 + k);
    }
    words
}

/// [`edge_indices`] for a mesh with one GPU vertex per corner: each edge
/// once as the pair of corners that end it on its owner's side.
pub(crate) fn edge_corner_pairs(ct: &CornerTable) -> Vec<u32> {
    drawn_edges(ct).flat_map(|c| [n(c), p(c)]).collect()
}
