//! One Loop step of the whole control mesh in f64, so that every face of
//! level 1 has at most one extraordinary vertex (Stam 1998 §3 assumes
//! it). Control face `f` has the children `4f + k`, level-1 corners
//! `12f + 3k + i`:
//!
//! ```text
//!            v2                 k = 0: (v0, e01, e20)   (s, t) = (2u, 2v)
//!           /  \                k = 1: (e01, v1, e12)   (s, t) = (2u - 1, 2v)
//!        e20 -- e12             k = 2: (e20, e12, v2)   (s, t) = (2u, 2v - 1)
//!        / \    / \             k = 3: (e01, e12, e20)  (s, t) = (2u + 2v - 1, 1 - 2u)
//!      v0 -- e01 -- v1
//! ```
//!
//! Vertex points use Loop's interior rule with the chosen beta (boundary
//! vertices the boundary rule), edge points `3/8, 3/8, 1/8, 1/8` (border
//! edges the midpoint), as [`crate::subdiv::rules::loop_`] does; only the
//! faces whose three control vertices are interior and free of sharp
//! features are evaluated, and their level-1 neighbourhoods use nothing
//! else.
//!
//! Level 1's connectivity is never built: [`Level1`] answers `vtx` and the
//! opposite corner of a level-1 corner from the control table, by the
//! layout above. Inside a face, the corner at `v_k` of child `k` faces
//! child 3 (`(0,0)-(3,1)`, `(1,1)-(3,2)`, `(2,2)-(3,0)`). The other corners
//! of the corner children face half of a control edge: corner `i` of child
//! `(i+1) % 3` the half at the next vertex of control corner `i`'s
//! opposite edge, corner `i` of child `(i+2) % 3` the half at the previous
//! one; across the edge, with `o(3f + i) = 3g + j`, the next half of `i`
//! faces the previous half of `j` (the edge runs the other way there).

use crate::mesh::split::EdgeIds;
use crate::mesh::{BORDER, CornerTable, Mesh, n, owns_edge, p};
use crate::subdiv::LoopBeta;
use crate::{Error, Result};
use glam::DVec3;

/// No extraordinary corner.
pub(crate) const REGULAR: u8 = u8::MAX;

/// What a support walk reads of a corner table.
pub(crate) trait Walk {
    /// The vertex of corner `c`.
    fn vtx(&self, c: u32) -> u32;
    /// The swing `n(o(n(c)))`, `None` at a border.
    fn s(&self, c: u32) -> Option<u32>;
}

impl Walk for CornerTable {
    #[inline]
    fn vtx(&self, c: u32) -> u32 {
        CornerTable::vtx(self, c)
    }
    #[inline]
    fn s(&self, c: u32) -> Option<u32> {
        CornerTable::s(self, c)
    }
}

/// Appends the support of the triangle of corner `c` in walk order (the
/// patch module docs): `c0`, the ring of `c0` from `c1`, the outer
/// neighbours of `c1` (its ring from `c2`: `c2 c0 z o1 o2 o3`) and of `c2`
/// (from `c0`: `c0 c1 o3 o4 o5`).
pub(crate) fn walk(ct: &impl Walk, c: u32, mut out: impl FnMut(u32)) {
    out(ct.vtx(c));
    let mut x = c;
    loop {
        out(ct.vtx(n(x)));
        match ct.s(x) {
            Some(next) if next != c => x = next,
            _ => break,
        }
    }
    for (start, take) in [(n(c), 3), (p(c), 2)] {
        let mut x = start;
        for i in 0..3 + take {
            if i >= 3 {
                out(ct.vtx(n(x)));
            }
            x = ct.s(x).unwrap_or(x);
        }
    }
}

/// The edge id of every corner (the edge opposite it), the project's
/// numbering ([`EdgeIds`]), and their count.
fn edge_ids(ct: &CornerTable) -> (Vec<u32>, u32) {
    let o = ct.o_table();
    let ids = EdgeIds::new(o);
    ((0..o.len() as u32).map(|c| ids.edge(c, o[c as usize])).collect(), ids.count())
}

fn vertex_points(ct: &CornerTable, pos: &[DVec3], beta: LoopBeta, out: &mut [DVec3]) {
    for v in 0..ct.num_vertices() as u32 {
        let x = pos[v as usize];
        out[v as usize] = match ct.boundary_neighbours(v) {
            Some((a, b)) => x * 0.75 + (pos[a as usize] + pos[b as usize]) * 0.125,
            None => {
                let k = ct.valence(v);
                let b = beta.beta(k);
                let sum: DVec3 = ct.ring(v).map(|w| pos[w as usize]).sum();
                x * (1.0 - f64::from(k) * b) + sum * b
            }
        };
    }
}

/// Where corner `i` of child `k` sits (module docs): `(true, j)` the
/// vertex of control corner `j`, `(false, j)` the edge point of the edge
/// opposite control corner `j`.
const LAYOUT: [[(bool, u32); 3]; 4] = [
    [(true, 0), (false, 2), (false, 1)],
    [(false, 2), (true, 1), (false, 0)],
    [(false, 1), (false, 0), (true, 2)],
    [(false, 2), (false, 0), (false, 1)],
];

/// Valences below this have block templates ([`Level1::block`]).
pub(crate) const TEMPLATE_VALENCE: u32 = 16;

/// The longest block: three vertex points and three rings.
pub(crate) const BLOCK: usize = 3 + 3 * (TEMPLATE_VALENCE as usize - 1);

/// The number of block keys (valence triples).
const KEYS: usize = (TEMPLATE_VALENCE * TEMPLATE_VALENCE * TEMPLATE_VALENCE) as usize;

/// The block key of a face whose corners have the valences `n`, if they
/// are all below [`TEMPLATE_VALENCE`].
fn key(n: [u32; 3]) -> Option<usize> {
    n.iter().try_fold(0, |key, &k| (k < TEMPLATE_VALENCE).then_some(key * TEMPLATE_VALENCE as usize + k as usize))
}

/// The corner a support walk of a level-1 face with extraordinary corner
/// `corner` ([`REGULAR`] if none) starts from.
pub(crate) fn walk_start(corner: u8) -> u32 {
    if corner == REGULAR { 0 } else { u32::from(corner) }
}

/// The supports of the four children of a face, as places in its block
/// ([`Level1::block`]), with each child's extraordinary corner
/// ([`REGULAR`] if none): the same for every face of the same valences.
pub(crate) struct Template {
    pub(crate) children: [(u8, Vec<u8>); 4],
}

/// Level 1 of a control mesh: its f64 points (the vertex points, then the
/// edge points by edge id) and its connectivity read off the control
/// table (module docs), which it keeps a copy of.
#[derive(Default)]
pub(crate) struct Level1 {
    /// The control table's `V` and `O` and valences.
    v: Vec<u32>,
    o: Vec<u32>,
    valence: Vec<u32>,
    /// The edge id of each control corner (the edge opposite it).
    ids: Vec<u32>,
    pos: Vec<DVec3>,
    /// The children's supports by the valences of a face's corners (see
    /// [`Level1::block`]), learnt from the mesh's own faces.
    templates: Vec<Option<Box<Template>>>,
}

impl Level1 {
    /// Level 1 of `mesh` under Loop's rules with `beta`, from the control
    /// positions `pos` (one per vertex, in f64).
    ///
    /// # Errors
    /// [`Error::Usage`] when level 1 has more than `u32::MAX` corners.
    pub(crate) fn new(mesh: &Mesh, pos: &[DVec3], beta: LoopBeta) -> Result<Level1> {
        let ct = &mesh.ct;
        if ct.num_corners().checked_mul(4).is_none_or(|x| x > u32::MAX as usize) {
            return Err(Error::Usage("the mesh is too large to evaluate (level 1 over 2^32 corners)".into()));
        }
        let nv = ct.num_vertices();
        let (ids, ne) = edge_ids(ct);
        let mut out = vec![DVec3::ZERO; nv + ne as usize];
        vertex_points(ct, pos, beta, &mut out[..nv]);
        // each edge once, at its owner corner
        for c in (0..ct.num_corners() as u32).filter(|&c| owns_edge(c, ct.o_table()[c as usize])) {
            let (a, b) = (pos[ct.vtx(n(c)) as usize], pos[ct.vtx(p(c)) as usize]);
            out[nv + ids[c as usize] as usize] = match ct.o(c) {
                Some(x) => (a + b) * 0.375 + (pos[ct.vtx(c) as usize] + pos[ct.vtx(x) as usize]) * 0.125,
                None => (a + b) * 0.5,
            };
        }
        Ok(Level1 {
            v: ct.v_table().to_vec(),
            o: ct.o_table().to_vec(),
            valence: ct.valences().to_vec(),
            ids,
            pos: out,
            templates: Vec::new(),
        })
    }

    /// The valence of level-1 vertex `v` where it is interior: a vertex
    /// point keeps its control vertex's, an interior edge point has 6.
    #[inline]
    fn valence(&self, v: u32) -> u32 {
        self.valence.get(v as usize).copied().unwrap_or(6)
    }

    /// Level-1 face `g`'s extraordinary corner ([`REGULAR`] if none) and
    /// the size of its support (valence + 6). Only for the children of a
    /// control face whose edges are all interior.
    #[inline]
    pub(crate) fn shape(&self, g: u32) -> (u8, usize) {
        for i in 0..3 {
            let k = self.valence(self.vtx(3 * g + i));
            if k != 6 {
                return (i as u8, k as usize + 6);
            }
        }
        (REGULAR, 12)
    }

    /// The level-1 point `v`.
    #[inline]
    pub(crate) fn point(&self, v: u32) -> DVec3 {
        self.pos[v as usize]
    }

    /// Writes the support of level-1 face `g` in walk order from its
    /// `corner` (as [`Level1::shape`] gives them) to `out`.
    #[inline]
    pub(crate) fn support(&self, g: u32, corner: u8, out: &mut [DVec3]) {
        let mut k = 0;
        walk(self, 3 * g + walk_start(corner), |v| {
            if let Some(o) = out.get_mut(k) {
                *o = self.pos[v as usize];
            }
            k += 1;
        });
    }

    /// The block of control face `f`: the level-1 vertices its children's
    /// supports read, in a fixed layout (its three vertex points, then for
    /// each corner `v_k` the edge points of its edges, swinging from the
    /// edge `v_k v_(k+1)`), and the key of its corners' valences `N_k`;
    /// `None` unless the three vertices are interior with valence below
    /// [`TEMPLATE_VALENCE`] and no two of them are joined by an edge other
    /// than `f`'s. Then the layout is the same for every face of the same
    /// valences: the supports are read through the key's [`Template`].
    pub(crate) fn block(&self, f: u32, ids: &mut [u32; BLOCK]) -> Option<(usize, usize)> {
        let c0 = 3 * f;
        let v = [0, 1, 2].map(|i| self.v[(c0 + i) as usize]);
        if v[0] == v[1] || v[1] == v[2] || v[2] == v[0] {
            return None;
        }
        ids[..3].copy_from_slice(&v);
        let nv = self.valence.len() as u32;
        let (mut len, mut valences) = (3, [0; 3]);
        for k in 0..3u32 {
            let c = c0 + k;
            let others = (v[((k + 1) % 3) as usize], v[((k + 2) % 3) as usize]);
            let (mut x, mut steps, mut met) = (c, 0, 0);
            loop {
                // the edge from v_k to the vertex of n(x) is opposite p(x)
                let w = self.v[n(x) as usize];
                met += u32::from(w == others.0 || w == others.1);
                *ids.get_mut(len)? = nv + self.ids[p(x) as usize];
                (len, steps) = (len + 1, steps + 1);
                x = match self.o[n(x) as usize] {
                    BORDER => return None,
                    o => n(o),
                };
                if x == c {
                    break;
                }
                if steps == TEMPLATE_VALENCE - 1 {
                    return None;
                }
            }
            // both other corners are neighbours through f; met once each
            if met != 2 {
                return None;
            }
            valences[k as usize] = steps;
        }
        Some((key(valences)?, len))
    }

    /// The template of block key `key`, if one was learnt.
    #[inline]
    pub(crate) fn template(&self, key: usize) -> Option<&Template> {
        self.templates.get(key)?.as_deref()
    }

    /// Learns a template for the valences of every control face `smooth`
    /// says is evaluated here (interior corners, no sharp features), from
    /// the first such face of each key: its children's supports walked on
    /// level 1 and found in its block.
    pub(crate) fn learn_templates(&mut self, smooth: impl Fn(usize) -> bool) {
        let mut templates: Vec<Option<Box<Template>>> = Vec::new();
        templates.resize_with(KEYS, || None);
        let mut ids = [0u32; BLOCK];
        for f in 0..self.v.len() / 3 {
            if !smooth(f) {
                continue;
            }
            // the key from the valences alone: most faces' is known
            let known = key([0, 1, 2].map(|i| self.valence[self.v[3 * f + i] as usize]));
            if known.is_some_and(|key| templates[key].is_some()) {
                continue;
            }
            let Some((key, len)) = self.block(f as u32, &mut ids) else { continue };
            if templates[key].is_none() {
                templates[key] = self.learn(f as u32, &ids[..len]).map(Box::new);
            }
        }
        self.templates = templates;
    }

    /// Face `f`'s children's supports as places in its block `ids`.
    fn learn(&self, f: u32, ids: &[u32]) -> Option<Template> {
        let mut children: [(u8, Vec<u8>); 4] = Default::default();
        for (k, child) in children.iter_mut().enumerate() {
            let g = 4 * f + k as u32;
            let (corner, _) = self.shape(g);
            let mut places = Vec::new();
            let mut lost = false;
            walk(self, 3 * g + walk_start(corner), |v| match ids.iter().position(|&x| x == v) {
                // a block holds at most BLOCK entries
                Some(i) => places.push(i as u8),
                None => lost = true,
            });
            if lost {
                return None;
            }
            *child = (corner, places);
        }
        Some(Template { children })
    }

    /// Level-1 corner `c`'s opposite corner.
    #[inline]
    fn o(&self, c: u32) -> Option<u32> {
        let (f, k, i) = (c / 12, (c % 12) / 3, c % 3);
        if k == 3 {
            // child 3's corner i faces the corner child (i + 2) % 3 at its vertex
            return Some(12 * f + 4 * ((i + 2) % 3));
        }
        if k == i {
            return Some(12 * f + 9 + (i + 1) % 3);
        }
        let g = self.o[(3 * f + i) as usize];
        if g == BORDER {
            return None;
        }
        let (h, j) = (g / 3, g % 3);
        // the next half of i (child (i + 1) % 3) faces the previous half of j
        let kk = if k == (i + 1) % 3 { (j + 2) % 3 } else { (j + 1) % 3 };
        Some(12 * h + 3 * kk + j)
    }
}

impl Walk for Level1 {
    #[inline]
    fn vtx(&self, c: u32) -> u32 {
        let (f, k, i) = (c / 12, (c % 12) / 3, c % 3);
        let (vertex, j) = LAYOUT[k as usize][i as usize];
        let c0 = (3 * f + j) as usize;
        if vertex { self.v[c0] } else { self.valence.len() as u32 + self.ids[c0] }
    }
    #[inline]
    fn s(&self, c: u32) -> Option<u32> {
        self.o(n(c)).map(n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes;
    use glam::Vec3;

    fn wide(mesh: &Mesh) -> Vec<DVec3> {
        mesh.positions.iter().map(|p| p.as_dvec3()).collect()
    }

    /// Level 1's table built the general way: the layout's triangles handed
    /// to the corner-table builder, which matches edges by their vertices.
    fn built(mesh: &Mesh) -> CornerTable {
        let ct = &mesh.ct;
        let (ids, _) = edge_ids(ct);
        let nv = ct.num_vertices() as u32;
        let mut tris = Vec::new();
        for c in (0..ct.num_corners() as u32).step_by(3) {
            let [v0, v1, v2] = [ct.vtx(c), ct.vtx(c + 1), ct.vtx(c + 2)];
            let e = |corner: u32| nv + ids[corner as usize];
            let (e01, e12, e20) = (e(c + 2), e(c), e(c + 1));
            tris.extend([v0, e01, e20, e01, v1, e12, e20, e12, v2, e01, e12, e20]);
        }
        let n = (nv + ids.iter().max().map_or(0, |&x| x + 1)) as usize;
        let (table, _, remap) = CornerTable::build(n, &tris, None).expect("level 1 is a manifold");
        assert!(remap.is_none(), "every level-1 vertex is used");
        table
    }

    fn tetrahedron() -> Mesh {
        let pos = vec![Vec3::X, Vec3::Y, Vec3::Z, Vec3::ONE];
        Mesh::from_triangles(pos, &[0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2]).expect("a closed tetrahedron")
    }

    #[test]
    fn every_face_reads_through_its_template_what_a_walk_finds() {
        let critter = crate::bundled::load(std::path::Path::new("bundled:critter.obj")).expect("bundled");
        for mesh in [shapes::icosphere(2), shapes::grid(5), tetrahedron(), shapes::icosahedron(), critter] {
            let mut l1 = Level1::new(&mesh, &wide(&mesh), LoopBeta::Loop).expect("small");
            l1.learn_templates(|_| true);
            let mut used = 0;
            let mut ids = [0u32; BLOCK];
            for f in 0..mesh.ct.num_triangles() as u32 {
                let Some((key, len)) = l1.block(f, &mut ids) else { continue };
                let template = l1.template(key).expect("a template for every key met");
                for (k, (corner, places)) in template.children.iter().enumerate() {
                    let g = 4 * f + k as u32;
                    assert_eq!(*corner, l1.shape(g).0, "face {f} child {k}");
                    let mut walked = Vec::new();
                    walk(&l1, 3 * g + walk_start(*corner), |v| walked.push(v));
                    let read: Vec<u32> = places.iter().map(|&i| ids[..len][usize::from(i)]).collect();
                    assert_eq!(read, walked, "face {f} child {k}");
                }
                used += 1;
            }
            assert!(used > 0, "no face has a template");
        }
    }

    #[test]
    fn the_level_1_read_off_the_control_table_is_the_one_built_from_its_triangles() {
        for mesh in [shapes::icosphere(2), shapes::grid(5), tetrahedron(), shapes::icosahedron()] {
            let l1 = Level1::new(&mesh, &wide(&mesh), LoopBeta::Loop).expect("small");
            let want = built(&mesh);
            assert_eq!(want.num_corners(), 4 * mesh.ct.num_corners());
            for c in 0..want.num_corners() as u32 {
                assert_eq!(l1.vtx(c), want.vtx(c), "vertex of level-1 corner {c}");
                assert_eq!(l1.o(c), want.o(c), "opposite of level-1 corner {c}");
                assert_eq!(Walk::s(&l1, c), want.s(c), "swing of level-1 corner {c}");
            }
            for v in 0..want.num_vertices() as u32 {
                if !want.is_boundary_vertex(v) {
                    assert_eq!(l1.valence(v), want.valence(v), "valence of level-1 vertex {v}");
                }
            }
        }
    }
}
