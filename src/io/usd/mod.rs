//! USD stages in (`.usda`, `.usdc`, `.usdz`) and out (`.usda`, `.usdc`,
//! `.usdz`), through the `openusd` crate (pure Rust, no C++).
//!
//! Read: every Mesh prim of the composed stage (sublayers, references and
//! payloads followed, inside the stage's folder only; instanceable prims
//! expanded under their own paths; a PointInstancer refused by name) with
//! its parent transforms applied, joined into one [`RawMesh`] whose
//! material groups are the prims: a [`crate::mesh::Scene`] holds each
//! prim's path, transform and options (`subdivisionScheme`,
//! `interpolateBoundary`, `faceVaryingLinearInterpolation`,
//! `triangleSubdivisionRule`; USD's defaults where unauthored), so every
//! face keeps its prim at every level and prims that state different
//! options are refined apart ([`crate::io::Loaded::groups`]). Points are
//! read at the time asked for, else the stage's `startTimeCode`, else
//! their first sample; the stage's `upAxis` and `metersPerUnit` are kept.
//! `leftHanded` prims and mirroring transforms have their faces reversed.
//! Creases, corners, holes, `primvars:st` (per corner) and
//! `primvars:displayColor` (per vertex, or per face as the groups'
//! colours) come along.
//!
//! Written: one Mesh per prim (one `/Mesh` for a mesh from another format),
//! its points in its own space under its transform (`xformOp:transform`),
//! with the topology, its options, creases and corners at the output's
//! level (decayed), holes, `st` (faceVarying, indexed: one value per
//! vertex and coordinate, so the seams are the ones refined) and
//! `displayColor` (vertex, or uniform); the stage's `upAxis` and
//! `metersPerUnit`.

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
    keeps: Keeps { uv: true, colors: true, materials: true, creases: true, holes: true },
};

/// Reads every Mesh prim of the stage.
///
/// # Errors
/// One line naming the file and the prim or layer.
fn read(input: &Input) -> Result<RawMesh> {
    read::read(input, input.refs.folder())
}
