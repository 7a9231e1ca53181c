//! What every reader produces: [`RawMesh`], a polygon list as read (faces
//! of any size, kept as they are) with optional per-corner texture
//! coordinates, per-vertex colours, per-face materials, sharpness tags, a
//! stored opposite table (`.ct`) and where each record came from. One place
//! turns it into a [`Mesh`] ([`RawMesh::build`]): polygons fanned into
//! triangles for the triangle schemes, then validated, repaired or analysed
//! as the load options ask, with errors naming the file and the record.

use crate::mesh::attributes::{Attributes, Material, MaterialGroups};
use crate::mesh::repair::{RepairReport, repair_with_cap};
use crate::mesh::sharpness::{CornerTag, CreaseTag, Tags};
use crate::mesh::{BORDER, CornerTable, Generations, Mesh};
use crate::{Error, MeshError, Result};
use glam::{Vec2, Vec3};

/// A polygon mesh as read, before validation.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RawMesh {
    /// Vertex positions, in file order.
    pub positions: Vec<Vec3>,
    /// Where each face's corners start in `corners`, and after the last
    /// face where its corners end (`faces + 1` entries from 0; empty for no
    /// face).
    pub face_starts: Vec<u32>,
    /// The vertex of every face corner, counter-clockwise seen from outside.
    pub corners: Vec<u32>,
    /// Texture coordinates, one per corner.
    pub uv: Option<Vec<Vec2>>,
    /// Linear RGB colours in [0, 1], one per vertex.
    pub colors: Option<Vec<Vec3>>,
    /// Material id of each face (into `material_list`).
    pub materials: Option<Vec<u32>>,
    /// The file's materials (ids past its end are drawn as a grey default).
    pub material_list: Vec<Material>,
    /// `mtllib` names as written (OBJ writes them back).
    pub libraries: Vec<String>,
    /// Sharpness tags (vertex ids of this list).
    pub tags: Tags,
    /// The faces that are holes (OpenSubdiv's `t hole`: 0-based ids of this
    /// list's faces), with the line of each tag.
    pub holes: Vec<(u32, u32)>,
    /// The subdivision options the file states (OBJ's shape tags).
    pub options: crate::mesh::options::ShapeOptions,
    /// The positions at the precision the file holds them, where that is
    /// more than f32 (OBJ's text, PLY's `double` properties): one per
    /// vertex record, or empty (then `positions` are what the file holds).
    pub precise: Vec<glam::DVec3>,
    /// An opposite table stored in the file (`.ct`), one entry per corner of
    /// an all-triangle mesh, [`BORDER`] for none: it must be the table the
    /// faces define.
    pub opposite: Option<Vec<u32>>,
    /// A twin table stored in the file (`.ct` polygons: the corner across
    /// the edge leaving each corner, [`BORDER`] for none): it must be the
    /// table the faces define.
    pub twins: Option<Vec<u32>>,
    /// Where the records are in the file, for messages.
    pub sources: Sources,
    /// The prims the material groups stand for, with their own options
    /// and transforms, and the stage's metadata (USD).
    pub scene: Option<crate::mesh::Scene>,
}

/// Where the records of a [`RawMesh`] are in their file, for messages: the
/// 1-based line of each face, vertex, tag (creases then corners) and stored
/// opposite row, where the format has lines (each list may be empty), and
/// the number of the file's first vertex (1 for OBJ).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Sources {
    /// Line of every face.
    pub face_lines: Vec<u32>,
    /// Line of every vertex.
    pub vertex_lines: Vec<u32>,
    /// Line of every crease tag, then every corner tag.
    pub tag_lines: Vec<u32>,
    /// Line of every row of the stored opposite table.
    pub opposite_lines: Vec<u32>,
    /// What the file calls its first vertex (0, or 1 for OBJ).
    pub id_base: u32,
}

/// What [`RawMesh::build`] does with a mesh whose topology is not a valid
/// manifold.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Topology {
    /// Refuse it with the first problem, naming the record.
    #[default]
    Refuse,
    /// Repair it (see [`crate::mesh::repair()`]); attributes and tags are
    /// dropped, since the repair renumbers and cuts.
    Repair,
    /// Repair it and list every problem found (no cap on the ids): what
    /// `subdiv info` describes.
    Analyze,
}

/// What [`RawMesh::build`] found on the way.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BuildNotes {
    /// Faces in the file.
    pub faces: usize,
    /// How many faces of each size (index = corners; sizes past 8 counted at 8).
    pub face_sizes: [usize; 9],
    /// Polygons (faces of more than 3 corners) fanned into triangles.
    pub fanned: usize,
    /// Vertex records in the file.
    pub vertex_records: usize,
    /// Vertices dropped because no face uses them.
    pub unreferenced: usize,
    /// The repair's report, when asked for one.
    pub repair: Option<RepairReport>,
}

impl RawMesh {
    /// Faces read.
    pub fn num_faces(&self) -> usize {
        self.face_starts.len().saturating_sub(1)
    }

    /// The corners of face `f`.
    pub(crate) fn face(&self, f: usize) -> &[u32] {
        &self.corners[self.face_starts[f] as usize..self.face_starts[f + 1] as usize]
    }

    /// Appends a face with corners `vertices`.
    pub(crate) fn push_face(&mut self, vertices: &[u32]) {
        if self.face_starts.is_empty() {
            self.face_starts.push(0);
        }
        self.corners.extend_from_slice(vertices);
        self.face_starts.push(self.corners.len() as u32);
    }

    /// A mesh of triangles `triangles` (three vertex ids each) on `positions`.
    pub(crate) fn from_triangles(positions: Vec<Vec3>, triangles: Vec<u32>) -> RawMesh {
        let n = triangles.len() / 3;
        let face_starts = if n == 0 { Vec::new() } else { (0..=n as u32).map(|f| 3 * f).collect() };
        let mut corners = triangles;
        corners.truncate(3 * n);
        RawMesh { positions, face_starts, corners, ..Default::default() }
    }

    /// Whether every face is a triangle.
    pub(crate) fn is_triangles(&self) -> bool {
        self.corners.len() == 3 * self.num_faces()
    }

    /// The faces fanned into triangles (face `f` of `k` corners gives
    /// `(c0, ck, ck+1)` for `k` in 1..n-1), with the face of every
    /// triangle; `None` for that map when every face already is one.
    pub(crate) fn fanned(&self) -> (std::borrow::Cow<'_, [u32]>, Option<Vec<u32>>) {
        if self.is_triangles() {
            return (std::borrow::Cow::Borrowed(&self.corners), None);
        }
        let nt = self.corners.len() - 2 * self.num_faces();
        let (mut tris, mut of) = (Vec::with_capacity(3 * nt), Vec::with_capacity(nt));
        for f in 0..self.num_faces() {
            let p = self.face(f);
            for k in 1..p.len().saturating_sub(1) {
                tris.extend_from_slice(&[p[0], p[k], p[k + 1]]);
                of.push(f as u32);
            }
        }
        (std::borrow::Cow::Owned(tris), Some(of))
    }

    /// The per-corner values `v` of the faces, in the corner order of
    /// [`RawMesh::fanned`].
    fn fan_corners<T: Copy>(&self, v: &[T]) -> Vec<T> {
        if self.is_triangles() {
            return v.to_vec();
        }
        let mut out = Vec::with_capacity(3 * (self.corners.len() - 2 * self.num_faces()));
        for f in 0..self.num_faces() {
            let s = self.face_starts[f] as usize;
            let n = self.face_starts[f + 1] as usize - s;
            for k in 1..n.saturating_sub(1) {
                out.extend_from_slice(&[v[s], v[s + k], v[s + k + 1]]);
            }
        }
        out
    }

    /// The file's positions in f64 for the vertices [`RawMesh::build`]
    /// keeps (the referenced ones, in order), when the file holds more than
    /// f32 and the build does not repair (a repair renumbers): what a
    /// computation in double precision starts from.
    pub(crate) fn kept_precise(&self, topology: Topology) -> Option<Vec<glam::DVec3>> {
        if topology != Topology::Refuse || self.precise.len() != self.positions.len() {
            return None;
        }
        let mut used = vec![false; self.positions.len()];
        for &v in &self.corners {
            if let Some(u) = used.get_mut(v as usize) {
                *u = true;
            }
        }
        Some(self.precise.iter().zip(&used).filter(|(_, u)| **u).map(|(p, _)| *p).collect())
    }

    /// Validates (or repairs, or analyses, as `topology` says) into a
    /// triangle mesh, fanning polygons; with `attributes` the texture
    /// coordinates, colours and material groups come along (not after a
    /// repair, which renumbers and cuts). Errors name `file` and the line of
    /// the record where the format has lines; vertex ids in them are the
    /// file's own (from `Sources::id_base`).
    ///
    /// # Errors
    /// [`Error::Mesh`] or [`Error::Parse`] naming `file`.
    pub fn build(self, file: &str, topology: Topology, attributes: bool) -> Result<(Mesh, Attributes, BuildNotes)> {
        let mut notes = self.notes();
        let (triangles, tri_face) = self.fanned();
        let triangles = triangles.into_owned();
        let locate = Locate { file, sources: &self.sources, tri_face: tri_face.as_deref() };
        if topology != Topology::Refuse {
            let cap = if topology == Topology::Analyze { usize::MAX } else { crate::mesh::repair::EXAMPLES };
            let (mut mesh, mut report) =
                repair_with_cap(self.positions, &triangles, cap).map_err(|e| locate.mesh_error(e))?;
            if let Some(of) = tri_face.as_ref().filter(|_| mesh.ct.v_table() == &triangles[..]) {
                // the repair kept every triangle where it was: the polygons
                // stay joinable, as the plain build keeps them
                let Mesh { ct, positions } = mesh;
                mesh = Mesh { ct: ct.with_generations(Some(fan_generations(of))), positions };
            }
            report.id_base = self.sources.id_base;
            notes.vertex_records = report.vertices_in;
            notes.repair = Some(report);
            return Ok((mesh, Attributes { options: self.options, ..Default::default() }, notes));
        }
        let nrec = self.positions.len();
        let used = used_vertices(nrec, &triangles);
        let uv = match &self.uv {
            Some(u) if attributes && u.len() == self.corners.len() => Some(self.fan_corners(u)),
            _ => None,
        };
        let (mut mesh, report) =
            Mesh::from_triangles_report(self.positions, &triangles).map_err(|e| locate.mesh_error(e))?;
        notes.unreferenced = report.unreferenced;
        if let Some(of) = &tri_face {
            // the fans' diagonals are no edges of the file's faces: marked,
            // they are not drawn, and the polygon schemes join them back
            let Mesh { ct, positions } = mesh;
            mesh = Mesh { ct: ct.with_generations(Some(fan_generations(of))), positions };
        }
        if let Some(stored) = &self.opposite {
            check_opposite(&mesh.ct, stored, notes.unreferenced, &locate)?;
        }
        if let Some(stored) = &self.twins {
            check_twins(&self.face_starts, &self.corners, nrec, stored, &locate)?;
        }
        if !self.tags.is_empty() {
            let Mesh { ct, positions } = mesh;
            mesh = Mesh { ct: apply_tags(ct, &self.tags, &used, &locate)?, positions };
        }
        if !self.holes.is_empty() {
            let Mesh { ct, positions } = mesh;
            let holes = hole_triangles(&self.holes, notes.faces, tri_face.as_deref(), file)?;
            mesh = Mesh { ct: ct.with_holes(holes), positions };
        }
        if !attributes {
            return Ok((mesh, Attributes { options: self.options, ..Default::default() }, notes));
        }
        let colors = self
            .colors
            .filter(|c| c.len() == nrec)
            .map(|c| c.into_iter().zip(&used).filter(|(_, u)| **u).map(|(c, _)| c).collect());
        let materials = self.materials.filter(|m| m.len() == notes.faces).map(|per_face| {
            let face = match &tri_face {
                Some(of) => of.iter().map(|&f| per_face[f as usize]).collect(),
                None => per_face,
            };
            let mut list = self.material_list;
            let n = face.iter().max().map_or(0, |&m| m as usize + 1);
            while list.len() < n {
                list.push(Material::named(&format!("material {}", list.len())));
            }
            MaterialGroups { face, list, libraries: self.libraries, scene: self.scene.map(std::sync::Arc::new) }
        });
        Ok((mesh, Attributes { uv, colors, materials, options: self.options }, notes))
    }

    /// The counts [`RawMesh::build`] reports before it builds anything.
    fn notes(&self) -> BuildNotes {
        let mut face_sizes = [0usize; 9];
        for w in self.face_starts.windows(2) {
            face_sizes[((w[1] - w[0]) as usize).min(8)] += 1;
        }
        let fanned = face_sizes[4..].iter().sum();
        BuildNotes {
            faces: self.num_faces(),
            face_sizes,
            fanned,
            vertex_records: self.positions.len(),
            ..Default::default()
        }
    }

    /// Merges vertices at exactly the same position (bit for bit, `-0` and
    /// `0` alike) into one, so a triangle soup (STL) or a mesh split at its
    /// texture seams (glTF) becomes connected. Texture coordinates are per
    /// corner and stay as they are; a merged vertex keeps its first colour.
    pub(crate) fn weld(&mut self) {
        let key = |p: Vec3| p.to_array().map(|x| if x == 0.0 { 0 } else { x.to_bits() });
        let mut first = std::collections::HashMap::with_capacity(self.positions.len());
        let mut remap = Vec::with_capacity(self.positions.len());
        let (mut positions, mut colors) = (Vec::new(), self.colors.as_ref().map(|_| Vec::new()));
        for (i, &p) in self.positions.iter().enumerate() {
            let next = positions.len() as u32;
            let id = *first.entry(key(p)).or_insert(next);
            if id == next {
                positions.push(p);
                if let (Some(out), Some(c)) = (&mut colors, &self.colors) {
                    out.push(c[i]);
                }
            }
            remap.push(id);
        }
        for t in &mut self.corners {
            // out-of-range indices stay out of range, to be reported by the build
            *t = remap.get(*t as usize).copied().unwrap_or(u32::MAX);
        }
        self.positions = positions;
        self.colors = colors;
    }

    /// Appends `other`, renumbering its vertices; an attribute that either
    /// side has is kept, the side without it getting defaults (texture
    /// coordinates (0, 0), white, material 0).
    pub(crate) fn append(&mut self, other: RawMesh) {
        let base = self.positions.len() as u32;
        let (nc0, nv0, nf0) = (self.corners.len(), self.positions.len(), self.num_faces());
        let start = self.corners.len() as u32;
        if self.face_starts.is_empty() && !other.face_starts.is_empty() {
            self.face_starts.push(0);
        }
        self.face_starts.extend(other.face_starts.iter().skip(1).map(|&s| s + start));
        self.corners.extend(other.corners.iter().map(|&i| i.saturating_add(base)));
        merge(&mut self.uv, other.uv, nc0, other.corners.len(), Vec2::ZERO);
        merge(&mut self.colors, other.colors, nv0, other.positions.len(), Vec3::ONE);
        merge(&mut self.materials, other.materials, nf0, other.face_starts.len().saturating_sub(1), 0);
        self.positions.extend(other.positions);
    }
}

impl RawMesh {
    /// The polygons `mesh` stands for (its fans joined back) with
    /// `attrs`: texture coordinates per polygon corner, colours, material
    /// groups and their scene, sharp features, holes and options.
    pub(crate) fn of_mesh(mesh: &Mesh, attrs: &Attributes) -> RawMesh {
        let (pm, pa) = crate::mesh::poly::PolyMesh::from_mesh_with_attributes(mesh, attrs);
        let pt = &pm.pt;
        let mut raw = RawMesh { positions: pm.positions.clone(), options: attrs.options, ..Default::default() };
        for f in pm.faces() {
            raw.push_face(f);
        }
        raw.uv = pa.uv.filter(|u| u.len() == pt.num_corners());
        raw.colors = pa.colors.filter(|c| c.len() == pm.positions.len());
        if let Some(m) = pa.materials.filter(|m| m.face.len() == pt.num_faces()) {
            raw.materials = Some(m.face);
            raw.material_list = m.list;
            raw.libraries = m.libraries;
            raw.scene = m.scene.map(|s| (*s).clone());
        }
        raw.tags = pt.sharpness().map(|s| s.to_tags(pt)).unwrap_or_default();
        raw.holes = pt.holes().iter().map(|&h| (h, 0)).collect();
        raw
    }

    /// The prims of a scene whose prims state different options, as one
    /// mesh per set of options (in order of first use; each holding its
    /// prims' faces, vertices, attributes, tags and holes, renumbered, and
    /// its options); empty when every prim states the same ones.
    pub(crate) fn by_options(&self) -> Vec<RawMesh> {
        let Some(scene) = self.scene.as_ref().filter(|s| s.mixed()) else { return Vec::new() };
        let Some(groups_of_face) = self.materials.as_ref().filter(|m| m.len() == self.num_faces()) else {
            return Vec::new();
        };
        scene
            .groups()
            .into_iter()
            .map(|(options, prims)| {
                // the material groups of these prims, in order, and their new ids
                let groups: Vec<u32> =
                    (0..scene.prim_of.len() as u32).filter(|&g| prims.contains(&scene.prim_of[g as usize])).collect();
                let mut new_group = vec![u32::MAX; scene.prim_of.len()];
                for (k, &g) in groups.iter().enumerate() {
                    new_group[g as usize] = k as u32;
                }
                let group = |f: usize| new_group.get(groups_of_face[f] as usize).copied().unwrap_or(u32::MAX);
                let faces: Vec<usize> = (0..self.num_faces()).filter(|&f| group(f) != u32::MAX).collect();
                let mut part = self.faces_only(&faces);
                part.materials = Some(faces.iter().map(|&f| group(f)).collect());
                part.options = options;
                part.material_list =
                    groups.iter().filter_map(|&g| self.material_list.get(g as usize).cloned()).collect();
                part.libraries = self.libraries.clone();
                part.scene = Some(scene.restricted(&prims, &groups));
                part
            })
            .collect()
    }

    /// The faces `faces` (ids, ascending) on the vertices they use
    /// (renumbered in order), with their texture coordinates, colours,
    /// tags and holes.
    fn faces_only(&self, faces: &[usize]) -> RawMesh {
        let mut new_id = vec![u32::MAX; self.positions.len()];
        let mut kept = Vec::new();
        for &f in faces {
            for &v in self.face(f) {
                if let Some(slot) = new_id.get_mut(v as usize).filter(|s| **s == u32::MAX) {
                    *slot = kept.len() as u32;
                    kept.push(v as usize);
                }
            }
        }
        let mut out = RawMesh { positions: kept.iter().map(|&v| self.positions[v]).collect(), ..Default::default() };
        let mut corner_ids = Vec::new();
        for &f in faces {
            let c = self.face_starts[f] as usize..self.face_starts[f + 1] as usize;
            out.push_face(&self.corners[c.clone()].iter().map(|&v| new_id[v as usize]).collect::<Vec<_>>());
            corner_ids.extend(c);
        }
        if self.precise.len() == self.positions.len() {
            out.precise = kept.iter().map(|&v| self.precise[v]).collect();
        }
        out.uv = self
            .uv
            .as_ref()
            .filter(|u| u.len() == self.corners.len())
            .map(|u| corner_ids.iter().map(|&c| u[c]).collect());
        out.colors = self
            .colors
            .as_ref()
            .filter(|c| c.len() == self.positions.len())
            .map(|c| kept.iter().map(|&v| c[v]).collect());
        let id = |v: u32| new_id.get(v as usize).copied().filter(|&n| n != u32::MAX);
        for c in &self.tags.creases {
            if let (Some(v0), Some(v1)) = (id(c.v0), id(c.v1)) {
                out.tags.creases.push(CreaseTag { v0, v1, ..*c });
            }
        }
        for c in &self.tags.corners {
            if let Some(vertex) = id(c.vertex) {
                out.tags.corners.push(CornerTag { vertex, ..*c });
            }
        }
        for &(h, line) in &self.holes {
            if let Ok(k) = faces.binary_search(&(h as usize)) {
                out.holes.push((k as u32, line));
            }
        }
        out
    }
}

/// The edge generations of fanned faces (the face of every triangle in
/// `of`, each face's triangles consecutive, fanned from its first corner):
/// every edge 0 but the diagonals between a face's triangles,
/// [`Generations::HIDDEN`] (triangle `j` of a fan shares its corner `+1`'s
/// edge with the next triangle and its corner `+2`'s with the previous one).
fn fan_generations(of: &[u32]) -> Generations {
    let mut g = vec![0u8; 3 * of.len()];
    for (t, w) in of.iter().enumerate() {
        let first = t == 0 || of[t - 1] != *w;
        let last = t + 1 == of.len() || of[t + 1] != *w;
        if !last {
            g[3 * t + 1] = Generations::HIDDEN;
        }
        if !first {
            g[3 * t + 2] = Generations::HIDDEN;
        }
    }
    Generations::explicit(g, 0)
}

/// Turns the build's errors into errors naming the file and the record.
struct Locate<'a> {
    file: &'a str,
    sources: &'a Sources,
    /// The face of every triangle, when polygons were fanned.
    tri_face: Option<&'a [u32]>,
}

impl Locate<'_> {
    /// The face of triangle `t`.
    fn face(&self, t: usize) -> usize {
        self.tri_face.map_or(t, |of| of.get(t).map_or(t, |&f| f as usize))
    }

    /// [`Error::Mesh`] for `e` (triangle ids become face ids, vertex ids the
    /// file's own), at the line of its face or vertex record.
    fn mesh_error(&self, e: MeshError) -> Error {
        let s = self.sources;
        let line = e
            .face()
            .and_then(|t| s.face_lines.get(self.face(t)))
            .or_else(|| e.vertex().and_then(|v| s.vertex_lines.get(v)))
            .map(|&l| l as usize);
        let e = match e {
            MeshError::IndexOutOfRange { face, index, len } => {
                MeshError::IndexOutOfRange { face: self.face(face), index, len }
            }
            MeshError::DegenerateFace { face, vertex } => MeshError::DegenerateFace { face: self.face(face), vertex },
            MeshError::NonManifoldEdge { v0, v1, faces, examples } => MeshError::NonManifoldEdge {
                v0,
                v1,
                faces,
                examples: examples.into_iter().map(|t| self.face(t)).collect(),
            },
            MeshError::InconsistentOrientation { v0, v1, f0, f1 } => {
                MeshError::InconsistentOrientation { v0, v1, f0: self.face(f0), f1: self.face(f1) }
            }
            other => other,
        };
        Error::Mesh { file: self.file.to_string(), line, source: e.shift_vertices(s.id_base) }
    }

    /// [`Error::Parse`] at the line of tag `i`, or [`Error::Mesh`] without a
    /// line where the format has none.
    fn tag_error(&self, i: usize, msg: String) -> Error {
        match self.sources.tag_lines.get(i) {
            Some(&l) => Error::Parse { file: self.file.to_string(), line: l as usize, msg },
            None => {
                Error::Mesh { file: self.file.to_string(), line: None, source: MeshError::BadTag { index: i, msg } }
            }
        }
    }
}

/// Refuses a stored opposite table that is not the one the faces define
/// (a valid involution can still be wrong: an interior edge marked as a
/// border on both sides is a slit the faces do not have).
fn check_opposite(ct: &CornerTable, stored: &[u32], unreferenced: usize, at: &Locate) -> Result<()> {
    let file = at.file.to_string();
    if unreferenced > 0 {
        let msg = "unused vertices in a file with an opposite table".to_string();
        return Err(Error::Mesh { file, line: None, source: MeshError::BadOppositeTable { corner: 0, msg } });
    }
    let built = ct.o_table();
    let Some(c) = (0..built.len().max(stored.len())).find(|&c| built.get(c) != stored.get(c)) else {
        return Ok(());
    };
    let show = |x: Option<&u32>| match x {
        Some(&BORDER) => "-1 (border)".to_string(),
        Some(x) => x.to_string(),
        None => "nothing".to_string(),
    };
    let msg = format!("stored {}, but the faces give {}", show(stored.get(c)), show(built.get(c)));
    let line = at.sources.opposite_lines.get(c / 3).map(|&l| l as usize);
    Err(Error::Mesh { file, line, source: MeshError::BadOppositeTable { corner: c, msg } })
}

/// Refuses a stored twin table (polygon `.ct`) that is not the one the
/// faces define.
fn check_twins(starts: &[u32], corners: &[u32], nv: usize, stored: &[u32], at: &Locate) -> Result<()> {
    let file = at.file.to_string();
    let (pt, _, _) = crate::mesh::poly::PolyTable::build(nv, starts, corners, None).map_err(|source| Error::Mesh {
        file: file.clone(),
        line: None,
        source,
    })?;
    let Some(c) = (0..pt.num_corners().max(stored.len())).find(|&c| pt.t_table().get(c) != stored.get(c)) else {
        return Ok(());
    };
    let show = |x: Option<&u32>| match x {
        Some(&BORDER) => "-1 (border)".to_string(),
        Some(x) => x.to_string(),
        None => "nothing".to_string(),
    };
    let msg = format!("stored twin {}, but the faces give {}", show(stored.get(c)), show(pt.t_table().get(c)));
    let line = at.sources.opposite_lines.get(pt.face(c as u32) as usize).map(|&l| l as usize);
    Err(Error::Mesh { file, line, source: MeshError::BadTwinTable { corner: c, msg } })
}

/// The triangles of the faces tagged as holes (`(face, line)`, faces of the
/// file, `faces` of them; `tri_face` the face of every triangle when
/// polygons were fanned).
///
/// # Errors
/// [`Error::Parse`] at the tag's line for a face out of range.
fn hole_triangles(holes: &[(u32, u32)], faces: usize, tri_face: Option<&[u32]>, file: &str) -> Result<Vec<u32>> {
    if let Some(&(f, line)) = holes.iter().find(|h| h.0 as usize >= faces) {
        let msg = format!("hole tag: face {f} out of range (the file has {faces} faces; ids are 0-based)");
        return Err(Error::Parse { file: file.to_string(), line: line as usize, msg });
    }
    let mut is_hole = vec![false; faces];
    holes.iter().for_each(|&(f, _)| is_hole[f as usize] = true);
    Ok(match tri_face {
        Some(of) => (0..of.len() as u32).filter(|&t| is_hole[of[t as usize] as usize]).collect(),
        None => holes.iter().map(|h| h.0).collect(),
    })
}

/// `ct` with the sharpness of `tags`, whose vertex ids are records of the
/// file (`used` says which the build kept, in order).
fn apply_tags(ct: CornerTable, tags: &Tags, used: &[bool], at: &Locate) -> Result<CornerTable> {
    // record id -> vertex id (the build keeps the used records in order)
    let mut new_id = vec![u32::MAX; used.len()];
    let mut next = 0;
    for (i, &u) in used.iter().enumerate() {
        if u {
            new_id[i] = next;
            next += 1;
        }
    }
    let map = |i: usize, v: u32| -> Result<u32> {
        match new_id.get(v as usize) {
            Some(&x) if x != u32::MAX => Ok(x),
            Some(_) => Err(at.tag_error(i, format!("tag: vertex {v} is used by no face"))),
            None => Err(at.tag_error(
                i,
                format!("tag: vertex {v} does not exist ({} vertices, tag ids are 0-based)", used.len()),
            )),
        }
    };
    let mut mapped = Tags::default();
    for (i, t) in tags.creases.iter().enumerate() {
        mapped.creases.push(CreaseTag { v0: map(i, t.v0)?, v1: map(i, t.v1)?, ..*t });
    }
    for (j, t) in tags.corners.iter().enumerate() {
        mapped.corners.push(CornerTag { vertex: map(tags.creases.len() + j, t.vertex)?, ..*t });
    }
    ct.with_tags(&mapped).map_err(|e| match e {
        MeshError::BadTag { index, msg } => at.tag_error(index, msg),
        other => at.mesh_error(other),
    })
}

/// Concatenates optional per-element arrays: `a` (of `na` elements) then `b`
/// (of `nb`), filling the side that has none with `fill`.
fn merge<T: Copy>(a: &mut Option<Vec<T>>, b: Option<Vec<T>>, na: usize, nb: usize, fill: T) {
    match (a.as_mut(), b) {
        (None, None) => {}
        (Some(a), None) => a.resize(a.len() + nb, fill),
        (Some(a), Some(b)) => a.extend(b),
        (None, Some(b)) => {
            let mut v = vec![fill; na];
            v.extend(b);
            *a = Some(v);
        }
    }
}

/// Which of `n` vertices some triangle uses.
fn used_vertices(n: usize, triangles: &[u32]) -> Vec<bool> {
    let mut u = vec![false; n];
    for &i in triangles {
        if let Some(slot) = u.get_mut(i as usize) {
            *slot = true;
        }
    }
    u
}

/// A [`Error::Format`] on `file` at `element`.
pub(crate) fn format_err(file: &str, element: impl Into<String>, msg: impl Into<String>) -> Error {
    Error::Format { file: file.to_string(), element: element.into(), msg: msg.into() }
}

/// Checks that `count` records of at least `min_bytes` each fit in the
/// `available` bytes left, before a vector of `count` is allocated: a header
/// that claims more elements than the file could hold is refused.
///
/// # Errors
/// [`Error::Format`] naming `file` and `what`.
pub(crate) fn check_count(file: &str, what: &str, count: u64, min_bytes: u64, available: usize) -> Result<usize> {
    let need = count.saturating_mul(min_bytes.max(1));
    if need > available as u64 || count > u64::from(u32::MAX) {
        return Err(format_err(
            file,
            what,
            format!(
                "the header claims {count} elements, but only {available} bytes follow (at least {min_bytes} each needed)"
            ),
        ));
    }
    Ok(count as usize)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polygons_are_kept_and_fanned_once() {
        let mut raw = RawMesh { positions: vec![Vec3::ZERO; 5], ..Default::default() };
        raw.push_face(&[0, 1, 2, 3]);
        raw.push_face(&[0, 3, 4]);
        assert_eq!((raw.num_faces(), raw.face(0), raw.face(1)), (2, &[0, 1, 2, 3][..], &[0, 3, 4][..]));
        let (tris, of) = raw.fanned();
        assert_eq!(&tris[..], &[0, 1, 2, 0, 2, 3, 0, 3, 4]);
        assert_eq!(of, Some(vec![0, 0, 1]));
        let tri = RawMesh::from_triangles(vec![Vec3::ZERO; 3], vec![0, 1, 2]);
        assert!(tri.is_triangles() && tri.fanned().1.is_none());
    }

    #[test]
    fn append_renumbers_vertices_and_faces() {
        let mut a = RawMesh::from_triangles(vec![Vec3::ZERO; 3], vec![0, 1, 2]);
        let mut b = RawMesh { positions: vec![Vec3::ONE; 4], ..Default::default() };
        b.push_face(&[0, 1, 2, 3]);
        b.materials = Some(vec![7]);
        a.append(b);
        assert_eq!(a.num_faces(), 2);
        assert_eq!(a.face(1), &[3, 4, 5, 6]);
        assert_eq!(a.materials, Some(vec![0, 7]));
    }
}
