//! The names Python passes (scheme, beta, boundary) as the library's options.

use crate::guard::Msg;
use subdiv::clean_error as clean;
use subdiv::mesh::BoundaryInterpolation;
use subdiv::{LoopBeta, Options, Scheme};

/// The scheme called `name` (the command line's names and aliases).
///
/// # Errors
/// An unknown name, listing the known ones.
pub fn scheme(name: &str) -> Result<Scheme, Msg> {
    name.parse::<Scheme>().map_err(|_| {
        format!(
            "unknown scheme '{}' (expected one of: midpoint, loop, butterfly, modified-butterfly, jarek, catmull-clark, bilinear)",
            clean(name, 40)
        )
    })
}

/// Loop's vertex weights called `name`: `"loop"` or `"warren"`.
///
/// # Errors
/// An unknown name.
pub fn beta(name: &str) -> Result<LoopBeta, Msg> {
    match name {
        "loop" => Ok(LoopBeta::Loop),
        "warren" => Ok(LoopBeta::Warren),
        _ => Err(format!("unknown beta '{}' (expected loop or warren)", clean(name, 40))),
    }
}

/// The boundary rule called `name`: `"edge"` or `"edge-and-corner"`.
///
/// # Errors
/// An unknown name.
pub fn boundary(name: &str) -> Result<BoundaryInterpolation, Msg> {
    match name {
        "edge" => Ok(BoundaryInterpolation::EdgeOnly),
        "edge-and-corner" => Ok(BoundaryInterpolation::EdgeAndCorner),
        _ => Err(format!("unknown boundary '{}' (expected edge or edge-and-corner)", clean(name, 40))),
    }
}

/// The library's options for `beta` and `boundary` (memory limit: the
/// library's default, a share of the memory available).
///
/// # Errors
/// An unknown name.
pub fn options(beta_name: &str, boundary_name: &str) -> Result<Options, Msg> {
    Ok(Options { loop_beta: beta(beta_name)?, boundary: boundary(boundary_name)?, ..Options::default() })
}
