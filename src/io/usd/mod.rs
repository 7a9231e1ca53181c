//! USD stages in (`.usda`, `.usdc`, `.usdz`) and out (`.usda`, `.usdc`,
//! `.usdz`), through the `openusd` crate (pure Rust, no C++).
//!
//! Read: every Mesh prim of the composed stage (sublayers, references and
//! payloads followed, inside the stage's folder only) with its parent
//! transforms applied, joined into one [`RawMesh`] whose material groups
//! are the prims (named by their paths, so the writer puts each face back
//! in its prim at every level); `leftHanded` prims and mirroring
//! transforms have their faces reversed. The first prim's
//! `subdivisionScheme`, `interpolateBoundary`,
//! `faceVaryingLinearInterpolation` and `triangleSubdivisionRule` are the
//! options (USD's defaults where unauthored; a prim whose attributes differ
//! is a warning); creases, corners, holes, `primvars:st` (per corner) and
//! `primvars:displayColor` (per vertex) come along.
//!
//! Written: one Mesh per prim (one `/Mesh` for a mesh from another format)
//! with the topology, the options, creases and corners at the output's
//! level (decayed), holes, `st` (faceVarying) and `displayColor` (vertex).

mod read;
mod stage;
mod write;

use super::raw::RawMesh;
use super::{Format, Input, Keeps};
use crate::Result;

/// The USD row of [`super::FORMATS`].
pub(crate) const FORMAT: Format = Format {
    name: "USD",
    extensions: &["usda", "usdc", "usdz", "usd"],
    sniff: |b| b.starts_with(b"#usda ") || b.starts_with(openusd::usdc::MAGIC),
    reader: Some(read),
    writer: Some(write::save),
    written_as: &["usda", "usdc", "usdz"],
    poly_writer: Some(write::save_poly),
    faces_writer: None,
    keeps: Keeps { uv: true, colors: true, materials: true, creases: true },
};

/// Reads every Mesh prim of the stage.
///
/// # Errors
/// One line naming the file and the prim or layer.
fn read(input: &Input) -> Result<RawMesh> {
    read::read(input, input.refs.folder())
}
