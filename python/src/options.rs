//! The names Python passes (scheme, beta, boundary, fvar, triangles,
//! creasing) as the library's options, each parsed by the library's own
//! `FromStr` (the command line's names, its error listing the known ones).

use crate::guard::Msg;
use subdiv::clean_error as clean;
use subdiv::mesh::{BoundaryInterpolation, Creasing, TriangleSubdivision, UvInterpolation};
use subdiv::{LoopBeta, Options, Scheme};

/// The option names as Python passes them: scheme, beta, boundary, fvar,
/// triangles, creasing.
pub type Names = (String, String, String, String, String, String);

/// `name` parsed as a `T` by the library (the message with the name made
/// one short printable line: a hostile name could be megabytes).
///
/// # Errors
/// The library's message: the name and the known ones.
pub fn parse<T: std::str::FromStr<Err = String>>(name: &str) -> Result<T, Msg> {
    name.parse::<T>().map_err(|e| e.replace(name, &clean(name, 40)))
}

/// The scheme called `name` (the command line's names and aliases).
///
/// # Errors
/// An unknown name, listing the known ones.
pub fn scheme(name: &str) -> Result<Scheme, Msg> {
    parse(name)
}

/// The library's options for `beta` and `boundary`, the others at their
/// defaults (memory limit: the library's default, a share of the memory
/// available).
///
/// # Errors
/// An unknown name.
pub fn options(beta_name: &str, boundary_name: &str) -> Result<Options, Msg> {
    Ok(Options {
        loop_beta: parse::<LoopBeta>(beta_name)?,
        boundary: parse::<BoundaryInterpolation>(boundary_name)?,
        ..Options::default()
    })
}

/// The scheme and options `names` name.
///
/// # Errors
/// An unknown name.
pub fn named(names: &Names) -> Result<(Scheme, Options), Msg> {
    let (scheme_name, beta, boundary, fvar, triangles, creasing) = names;
    let opts = Options {
        uv: parse::<UvInterpolation>(fvar)?,
        triangles: parse::<TriangleSubdivision>(triangles)?,
        creasing: parse::<Creasing>(creasing)?,
        ..options(beta, boundary)?
    };
    Ok((scheme(scheme_name)?, opts))
}
