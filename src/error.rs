//! Error types. Every failure that comes from a file, the user or the machine's
//! limits is a typed error with the element ids that caused it; nothing from
//! outside the crate may panic.

use std::path::Path;

/// A problem found while building a corner table from a triangle list.
///
/// Vertex and face ids are those of the input (as read from the file, 0-based),
/// not of the compacted table.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MeshError {
    /// The mesh has no triangles.
    #[error("the mesh has no triangles")]
    Empty,
    /// A face refers to a vertex that does not exist.
    #[error("face {face} uses vertex index {index}, but there are only {len} vertices")]
    IndexOutOfRange { face: usize, index: i64, len: usize },
    /// A face uses the same vertex twice (it has no area and no valid corners).
    #[error("face {face} is degenerate: it uses vertex {vertex} twice")]
    DegenerateFace { face: usize, vertex: u32 },
    /// A coordinate is NaN or infinite.
    #[error("vertex {vertex} has a non-finite coordinate (NaN or infinity)")]
    NonFinite { vertex: usize },
    /// More than two faces share an edge.
    #[error("non-manifold edge ({v0}, {v1}): shared by {faces} faces (faces {examples:?})")]
    NonManifoldEdge { v0: u32, v1: u32, faces: usize, examples: Vec<usize> },
    /// Two faces traverse an edge in the same direction.
    #[error("inconsistent orientation: faces {f0} and {f1} both run along edge ({v0} -> {v1}); flip one of them")]
    InconsistentOrientation { v0: u32, v1: u32, f0: usize, f1: usize },
    /// A vertex joins two or more separate fans of faces ("bowtie").
    #[error("non-manifold vertex {vertex}: its faces form {fans} separate fans")]
    NonManifoldVertex { vertex: u32, fans: usize },
    /// A vertex that no triangle uses, where every vertex must be used (a
    /// corner table given as V and O; [`crate::CornerTable::build`] drops
    /// such vertices instead).
    #[error("vertex {vertex} is used by no triangle")]
    UnusedVertex { vertex: u32 },
    /// An index or count does not fit the 32-bit corner table.
    #[error("mesh too large for 32-bit corner ids: {what}")]
    TooManyElements { what: String },
    /// A crease or corner tag names something that does not exist, or an
    /// invalid sharpness. `index` counts the crease tags first, then the
    /// corner tags, in file order.
    #[error("sharpness tag {index}: {msg}")]
    BadTag { index: usize, msg: String },
    /// The opposite table stored in a file contradicts the triangles.
    #[error("stored opposite table is inconsistent at corner {corner}: {msg}")]
    BadOppositeTable { corner: usize, msg: String },
}

impl MeshError {
    /// The input face this error is about, when there is exactly one.
    pub fn face(&self) -> Option<usize> {
        match self {
            MeshError::IndexOutOfRange { face, .. } | MeshError::DegenerateFace { face, .. } => Some(*face),
            MeshError::NonManifoldEdge { examples, .. } => examples.first().copied(),
            MeshError::InconsistentOrientation { f1, .. } => Some(*f1),
            _ => None,
        }
    }
    /// The same error with vertex ids shifted by `d` (1 gives OBJ's 1-based
    /// numbering in messages).
    pub fn shift_vertices(self, d: u32) -> MeshError {
        use MeshError as E;
        match self {
            E::IndexOutOfRange { face, index, len } => E::IndexOutOfRange { face, index: index + i64::from(d), len },
            E::DegenerateFace { face, vertex } => E::DegenerateFace { face, vertex: vertex + d },
            E::NonManifoldEdge { v0, v1, faces, examples } => {
                E::NonManifoldEdge { v0: v0 + d, v1: v1 + d, faces, examples }
            }
            E::InconsistentOrientation { v0, v1, f0, f1 } => {
                E::InconsistentOrientation { v0: v0 + d, v1: v1 + d, f0, f1 }
            }
            E::NonManifoldVertex { vertex, fans } => E::NonManifoldVertex { vertex: vertex + d, fans },
            E::UnusedVertex { vertex } => E::UnusedVertex { vertex: vertex + d },
            E::NonFinite { vertex } => E::NonFinite { vertex: vertex + d as usize },
            other => other,
        }
    }

    /// The input vertex this error is about, when there is exactly one.
    pub fn vertex(&self) -> Option<usize> {
        match self {
            MeshError::NonFinite { vertex } => Some(*vertex),
            MeshError::NonManifoldVertex { vertex, .. } | MeshError::UnusedVertex { vertex } => Some(*vertex as usize),
            _ => None,
        }
    }
}

/// Everything the library can fail with.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// Reading or writing a file failed.
    #[error("{path}: {source}")]
    Io {
        path: String,
        #[source]
        source: std::io::Error,
    },
    /// A file could not be parsed.
    #[error("{file}:{line}: {msg}")]
    Parse { file: String, line: usize, msg: String },
    /// A binary or structured file (PLY, STL, glTF, COLLADA) is malformed:
    /// `element` names where ("vertex 12", "header", "accessor 3").
    #[error("{file}: {element}: {msg}")]
    Format {
        /// The file.
        file: String,
        /// The element of the file that is wrong.
        element: String,
        /// What is wrong with it.
        msg: String,
    },
    /// The mesh in a file is not a valid manifold triangle mesh.
    #[error("{file}{}: {source}", line.map(|l| format!(":{l}")).unwrap_or_default())]
    Mesh {
        file: String,
        line: Option<usize>,
        #[source]
        source: MeshError,
    },
    /// A mesh given in memory is invalid.
    #[error(transparent)]
    Invalid(#[from] MeshError),
    /// The next subdivision level would need more memory than allowed.
    #[error("level {level} would need about {} but the limit is {} ({faces} faces); use fewer levels or raise --max-memory", human_bytes(*bytes), human_bytes(*limit))]
    TooLarge { level: u32, faces: u64, bytes: u64, limit: u64 },
    /// An argument is out of its range, or options that do not go together.
    #[error("{0}")]
    Usage(String),
    /// The work was cancelled before it finished (by the user, or by a newer
    /// request that superseded it).
    #[error("{what} cancelled")]
    Cancelled {
        /// What was cancelled ("export", "subdivision").
        what: String,
    },
    /// Encoding an image or an animation failed.
    #[error("{path}: {format} encoding failed: {msg}")]
    Encode {
        /// The file being written.
        path: String,
        /// The format ("PNG", "GIF").
        format: &'static str,
        /// The encoder's message.
        msg: String,
    },
    /// Waiting for a result ran past its limit.
    #[error("{what}: did not finish within {seconds} s")]
    Timeout {
        /// What was waited for.
        what: String,
        /// The limit.
        seconds: f64,
    },
    /// Two things that must have the same count do not.
    #[error("{what}: {found} {unit}, but {expected} expected")]
    CountMismatch {
        /// Where the counts come from (a file, a pair of meshes).
        what: String,
        /// What is counted ("vertices").
        unit: &'static str,
        /// The count that was needed.
        expected: usize,
        /// The count that was found.
        found: usize,
    },
    /// A file's extension names no format this build reads or writes.
    #[error("{path}: unknown {direction} format '.{ext}' (use {known})")]
    UnknownFormat {
        /// The file.
        path: String,
        /// Its extension, lower case (may be empty).
        ext: String,
        /// "input" or "output".
        direction: &'static str,
        /// The extensions that are known.
        known: &'static str,
    },
    /// A file that holds something other than a triangle mesh (a `.bzc`
    /// Bezier curve) was given where a mesh is needed.
    #[error("{file}: this is {what}, not a mesh (it has no faces to subdivide)")]
    NotAMesh {
        /// The file.
        file: String,
        /// What it holds ("a Bezier curve (.bzc)").
        what: &'static str,
    },
    /// A `bundled:NAME` argument that names no bundled model.
    #[error("no bundled model '{name}' (bundled: {known}; `subdiv models` lists them)")]
    NoSuchBundled {
        /// The name after `bundled:`.
        name: String,
        /// The bundled file names, comma-separated.
        known: String,
    },
    /// Something our own code should have made impossible: a bug in subdiv.
    #[error("internal error: {0} (this is a bug in subdiv, please report it)")]
    Internal(String),
    /// No GPU adapter or device (the renderer and the window need one).
    #[error("graphics: {0}")]
    Gpu(String),
}

impl Error {
    /// An I/O error on `path`.
    pub fn io(path: &Path, source: std::io::Error) -> Self {
        Error::Io { path: path.display().to_string(), source }
    }
    /// [`Error::Cancelled`] for `what`.
    pub fn cancelled(what: &str) -> Self {
        Error::Cancelled { what: what.to_string() }
    }
    /// [`Error::Encode`] of `format` into `path`.
    pub fn encode(path: &Path, format: &'static str, msg: impl std::fmt::Display) -> Self {
        Error::Encode { path: path.display().to_string(), format, msg: msg.to_string() }
    }
}

/// `Result` with this crate's [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Bytes as a short human-readable string (`1.5 GiB`).
pub fn human_bytes(b: u64) -> String {
    const U: [&str; 5] = ["B", "KiB", "MiB", "GiB", "TiB"];
    let mut x = b as f64;
    let mut i = 0;
    while x >= 1024.0 && i < U.len() - 1 {
        x /= 1024.0;
        i += 1;
    }
    if i == 0 { format!("{b} B") } else { format!("{x:.1} {}", U[i]) }
}
