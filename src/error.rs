//! Error types. Every failure that comes from a file, the user or the machine's
//! limits is a typed error with the element ids that caused it; nothing from
//! outside the crate may panic.
//!
//! Every message is one printable line of about 300 characters at most,
//! whatever a file puts in it: the parts that come from outside (file
//! names, elements, what was read) are shown through [`clean`], which
//! escapes control characters and shortens long text, and lists of ids are
//! cut to [`MAX_EXAMPLES`].

use std::borrow::Cow;
use std::path::Path;

/// Characters of a file name in a message (longer ones keep their end,
/// which names the file).
const FILE_CHARS: usize = 80;
/// Characters of an element (`mesh 3 primitive 0`) in a message.
const ELEMENT_CHARS: usize = 48;
/// Characters of the description of a problem in a message.
const MSG_CHARS: usize = 160;
/// Ids an error lists (a non-manifold edge's faces): the rest are counted.
pub(crate) const MAX_EXAMPLES: usize = 8;

/// `s` as one printable line of at most `max` characters: control
/// characters escaped (`\n`, `\0`, `\u{1b}`), and a longer text cut in
/// the middle with `...` (both ends usually say the most).
pub fn clean(s: &str, max: usize) -> Cow<'_, str> {
    let plain = s.chars().all(|c| !c.is_control()) && s.chars().nth(max).is_none();
    if plain {
        return Cow::Borrowed(s);
    }
    let escaped: Vec<char> = s.chars().flat_map(char::escape_debug_plain).collect();
    if escaped.len() <= max {
        return Cow::Owned(escaped.into_iter().collect());
    }
    let keep = max.saturating_sub(3);
    let (head, tail) = (keep - keep / 2, keep / 2);
    let mut out: String = escaped[..head].iter().collect();
    out.push_str("...");
    out.extend(&escaped[escaped.len() - tail..]);
    Cow::Owned(out)
}

/// Escapes a character as `escape_debug` does, but leaves quotes and
/// non-ASCII letters as they are.
trait EscapePlain {
    fn escape_debug_plain(self) -> Vec<char>;
}

impl EscapePlain for char {
    fn escape_debug_plain(self) -> Vec<char> {
        if self.is_control() { self.escape_debug().collect() } else { vec![self] }
    }
}

/// The first [`MAX_EXAMPLES`] of `ids` of `total`, and how many more.
fn list(ids: &[usize], total: usize) -> String {
    let shown: Vec<String> = ids.iter().take(MAX_EXAMPLES).map(usize::to_string).collect();
    let more = total.saturating_sub(shown.len());
    if more > 0 { format!("{} and {more} more", shown.join(", ")) } else { shown.join(", ") }
}

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
    IndexOutOfRange {
        /// The face id (input order, 0-based).
        face: usize,
        /// The index as written.
        index: i64,
        /// How many there are.
        len: usize,
    },
    /// A face uses the same vertex twice (it has no area and no valid corners).
    #[error("face {face} is degenerate: it uses vertex {vertex} twice")]
    DegenerateFace {
        /// The face id (input order, 0-based).
        face: usize,
        /// The vertex id.
        vertex: u32,
    },
    /// A coordinate is NaN or infinite.
    #[error("vertex {vertex} has a non-finite coordinate (NaN or infinity)")]
    NonFinite {
        /// The vertex id.
        vertex: usize,
    },
    /// More than two faces share an edge.
    #[error("non-manifold edge ({v0}, {v1}): shared by {faces} faces (faces {})", list(examples, *faces))]
    NonManifoldEdge {
        /// First vertex of the edge.
        v0: u32,
        /// Second vertex of the edge.
        v1: u32,
        /// How many faces share it.
        faces: usize,
        /// Some of those faces (at most `MAX_EXAMPLES`).
        examples: Vec<usize>,
    },
    /// Two faces traverse an edge in the same direction.
    #[error("inconsistent orientation: faces {f0} and {f1} both run along edge ({v0} -> {v1}); flip one of them")]
    InconsistentOrientation {
        /// First vertex of the edge.
        v0: u32,
        /// Second vertex of the edge.
        v1: u32,
        /// The first face.
        f0: usize,
        /// The second face.
        f1: usize,
    },
    /// A vertex joins two or more separate fans of faces ("bowtie").
    #[error("non-manifold vertex {vertex}: its faces form {fans} separate fans")]
    NonManifoldVertex {
        /// The vertex id.
        vertex: u32,
        /// How many separate fans.
        fans: usize,
    },
    /// A vertex that no triangle uses, where every vertex must be used (a
    /// corner table given as V and O; [`crate::CornerTable::build`] drops
    /// such vertices instead).
    #[error("vertex {vertex} is used by no triangle")]
    UnusedVertex {
        /// The vertex id.
        vertex: u32,
    },
    /// An index or count does not fit the 32-bit corner table.
    #[error("mesh too large for 32-bit corner ids: {}", clean(what, MSG_CHARS))]
    TooManyElements {
        /// What does not fit.
        what: String,
    },
    /// A crease or corner tag names something that does not exist, or an
    /// invalid sharpness. `index` counts the crease tags first, then the
    /// corner tags, in file order.
    #[error("sharpness tag {index}: {}", clean(msg, MSG_CHARS))]
    BadTag {
        /// The index as written.
        index: usize,
        /// What is wrong.
        msg: String,
    },
    /// The opposite table stored in a file contradicts the triangles.
    #[error("stored opposite table is inconsistent at corner {corner}: {}", clean(msg, MSG_CHARS))]
    BadOppositeTable {
        /// The corner id.
        corner: usize,
        /// What is wrong.
        msg: String,
    },
    /// The twin table stored in a `.ct` polygon file contradicts the faces.
    #[error("stored twin table is inconsistent at corner {corner}: {}", clean(msg, MSG_CHARS))]
    BadTwinTable {
        /// The polygon corner id.
        corner: usize,
        /// What is wrong.
        msg: String,
    },
}

impl MeshError {
    /// The input face this error is about, when there is exactly one.
    pub(crate) fn face(&self) -> Option<usize> {
        match self {
            MeshError::IndexOutOfRange { face, .. } | MeshError::DegenerateFace { face, .. } => Some(*face),
            MeshError::NonManifoldEdge { examples, .. } => examples.first().copied(),
            MeshError::InconsistentOrientation { f1, .. } => Some(*f1),
            _ => None,
        }
    }
    /// The same error with vertex ids shifted by `d` (1 gives OBJ's 1-based
    /// numbering in messages).
    pub(crate) fn shift_vertices(self, d: u32) -> MeshError {
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
    pub(crate) fn vertex(&self) -> Option<usize> {
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
    #[error("{}: {}", clean(path, FILE_CHARS), clean(&source.to_string(), MSG_CHARS))]
    Io {
        /// The file.
        path: String,
        /// The operating system's error.
        #[source]
        source: std::io::Error,
    },
    /// A file could not be parsed.
    #[error("{}:{line}: {}", clean(file, FILE_CHARS), clean(msg, MSG_CHARS))]
    Parse {
        /// The file.
        file: String,
        /// The line (1-based).
        line: usize,
        /// What is wrong.
        msg: String,
    },
    /// A binary or structured file (PLY, STL, glTF, COLLADA) is malformed:
    /// `element` names where ("vertex 12", "header", "accessor 3").
    #[error("{}: {}: {}", clean(file, FILE_CHARS), clean(element, ELEMENT_CHARS), clean(msg, MSG_CHARS))]
    Format {
        /// The file.
        file: String,
        /// The element of the file that is wrong.
        element: String,
        /// What is wrong with it.
        msg: String,
    },
    /// The mesh in a file is not a valid manifold triangle mesh.
    #[error("{}{}: {source}", clean(file, FILE_CHARS), line.map(|l| format!(":{l}")).unwrap_or_default())]
    Mesh {
        /// The file.
        file: String,
        /// The line of the offending record, where the format has lines.
        line: Option<usize>,
        /// What is wrong with the mesh.
        #[source]
        source: MeshError,
    },
    /// A mesh given in memory is invalid.
    #[error(transparent)]
    Invalid(#[from] MeshError),
    /// A file would make us read or hold more than the read's budget allows
    /// (see [`crate::io::Limits`]).
    #[error(
        "{}: {}: {value} is over the {limit} limit of {max} (raise it with --limit {limit}=N)",
        clean(file, FILE_CHARS),
        clean(element, ELEMENT_CHARS)
    )]
    OverBudget {
        /// The file.
        file: String,
        /// What in it asked for too much.
        element: String,
        /// The limit's name ([`crate::io::LIMIT_NAMES`]).
        limit: &'static str,
        /// What was asked for.
        value: u64,
        /// The limit.
        max: u64,
    },
    /// The next subdivision level would need more memory than allowed.
    #[error("level {level} would need about {} but the limit is {} ({faces} faces); use fewer levels or raise --max-memory", human_bytes(*bytes), human_bytes(*limit))]
    TooLarge {
        /// The level that would not fit.
        level: u32,
        /// How many faces share it.
        faces: u64,
        /// The bytes it would need.
        bytes: u64,
        /// The limit in force.
        limit: u64,
    },
    /// An argument is out of its range, or options that do not go together.
    #[error("{}", clean(.0, MSG_CHARS))]
    Usage(String),
    /// The work was cancelled before it finished (by the user, or by a newer
    /// request that superseded it).
    #[error("{} cancelled", clean(what, MSG_CHARS))]
    Cancelled {
        /// What was cancelled ("export", "subdivision").
        what: String,
    },
    /// Encoding an image or an animation failed.
    #[error("{}: {format} encoding failed: {}", clean(path, FILE_CHARS), clean(msg, MSG_CHARS))]
    Encode {
        /// The file being written.
        path: String,
        /// The format ("PNG", "GIF").
        format: &'static str,
        /// The encoder's message.
        msg: String,
    },
    /// Waiting for a result ran past its limit.
    #[error("{}: did not finish within {seconds} s", clean(what, MSG_CHARS))]
    Timeout {
        /// What was waited for.
        what: String,
        /// The limit.
        seconds: f64,
    },
    /// Two things that must have the same count do not.
    #[error("{}: {found} {unit}, but {expected} expected", clean(what, MSG_CHARS))]
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
    #[error("{}: unknown {direction} format '.{}' (use {known})", clean(path, FILE_CHARS), clean(ext, 16))]
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
    #[error("{}: this is {what}, not a mesh (it has no faces to subdivide)", clean(file, FILE_CHARS))]
    NotAMesh {
        /// The file.
        file: String,
        /// What it holds ("a Bezier curve (.bzc)").
        what: &'static str,
    },
    /// A `bundled:NAME` argument that names no bundled model.
    #[error("no bundled model '{}' (bundled: {known}; `subdiv models` lists them)", clean(name, 40))]
    NoSuchBundled {
        /// The name after `bundled:`.
        name: String,
        /// The bundled file names, comma-separated.
        known: String,
    },
    /// Something our own code should have made impossible: a bug in subdiv.
    #[error("internal error: {} (this is a bug in subdiv, please report it)", clean(.0, MSG_CHARS))]
    Internal(String),
    /// No GPU adapter or device (the renderer and the window need one).
    #[error("graphics: {}", clean(.0, MSG_CHARS))]
    Gpu(String),
}

impl Error {
    /// An I/O error on `path`.
    pub(crate) fn io(path: &Path, source: std::io::Error) -> Self {
        Error::Io { path: path.display().to_string(), source }
    }
    /// [`Error::Cancelled`] for `what`.
    pub(crate) fn cancelled(what: &str) -> Self {
        Error::Cancelled { what: what.to_string() }
    }
    /// [`Error::Encode`] of `format` into `path`.
    pub(crate) fn encode(path: &Path, format: &'static str, msg: impl std::fmt::Display) -> Self {
        Error::Encode { path: path.display().to_string(), format, msg: msg.to_string() }
    }
}

/// `Result` with this crate's [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Bytes as a short human-readable string (`1.5 GiB`).
pub(crate) fn human_bytes(b: u64) -> String {
    const U: [&str; 5] = ["B", "KiB", "MiB", "GiB", "TiB"];
    let mut x = b as f64;
    let mut i = 0;
    while x >= 1024.0 && i < U.len() - 1 {
        x /= 1024.0;
        i += 1;
    }
    if i == 0 { format!("{b} B") } else { format!("{x:.1} {}", U[i]) }
}
