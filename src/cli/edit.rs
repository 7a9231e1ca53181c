//! `subdiv edit`: the cage's edits from the command line, for scripts:
//! control vertices moved to a point or by an offset, edges and vertices
//! given a sharpness, applied in order on the library's refiner. The
//! edited cage is written with its faces, texture coordinates, materials
//! and tags; with `--levels` the refined surface of the edited cage.

use super::args::{InputArgs, SubdivArgs};
use glam::Vec3;
use std::path::PathBuf;
use subdiv::mesh::Tags;
use subdiv::mesh::{CornerTag, CreaseTag};
use subdiv::{Error, Refiner, Result, io};

/// `subdiv edit` arguments.
#[derive(clap::Args)]
pub struct EditArgs {
    /// Input model: a mesh file or bundled:NAME (see `subdiv models`).
    input: PathBuf,
    /// Output mesh (format by extension; written atomically).
    output: PathBuf,
    #[command(flatten)]
    from: InputArgs,
    #[command(flatten)]
    sub: SubdivArgs,
    /// Move control vertex V to X,Y,Z (repeatable): `--move 3=0,0,0.25`.
    #[arg(long = "move", value_name = "V=X,Y,Z", value_parser = parse_move)]
    moves: Vec<(u32, Vec3)>,
    /// Move control vertex V by DX,DY,DZ (repeatable): `--offset 3=0,0,0.25`.
    #[arg(long = "offset", value_name = "V=DX,DY,DZ", value_parser = parse_move)]
    offsets: Vec<(u32, Vec3)>,
    /// Set the sharpness of the edge A-B (repeatable; 0 smooth, 10 infinitely sharp): `--crease 0,1=2.5`.
    #[arg(long = "crease", value_name = "A,B=S", value_parser = parse_crease)]
    creases: Vec<(u32, u32, f32)>,
    /// Set the sharpness of vertex V (a corner; repeatable): `--corner 4=10`.
    #[arg(long = "corner", value_name = "V=S", value_parser = parse_corner)]
    corners: Vec<(u32, f32)>,
}

fn parse_move(s: &str) -> std::result::Result<(u32, Vec3), String> {
    let (v, p) = s.split_once('=').ok_or("expected V=X,Y,Z")?;
    let v = v.trim().parse().map_err(|_| format!("{v:?} is not a vertex id"))?;
    let c: Vec<f32> = p
        .split(',')
        .map(|x| x.trim().parse::<f32>())
        .collect::<std::result::Result<_, _>>()
        .map_err(|e| e.to_string())?;
    match c[..] {
        [x, y, z] if c.iter().all(|x| x.is_finite()) => Ok((v, Vec3::new(x, y, z))),
        _ => Err(format!("{p:?} is not three finite numbers X,Y,Z")),
    }
}

fn parse_crease(s: &str) -> std::result::Result<(u32, u32, f32), String> {
    let (e, w) = s.split_once('=').ok_or("expected A,B=S")?;
    let (a, b) = e.split_once(',').ok_or("expected A,B=S")?;
    let id = |x: &str| x.trim().parse::<u32>().map_err(|_| format!("{x:?} is not a vertex id"));
    Ok((id(a)?, id(b)?, sharpness(w)?))
}

fn parse_corner(s: &str) -> std::result::Result<(u32, f32), String> {
    let (v, w) = s.split_once('=').ok_or("expected V=S")?;
    Ok((v.trim().parse().map_err(|_| format!("{v:?} is not a vertex id"))?, sharpness(w)?))
}

fn sharpness(w: &str) -> std::result::Result<f32, String> {
    w.trim()
        .parse::<f32>()
        .ok()
        .filter(|s| s.is_finite() && *s >= 0.0)
        .ok_or_else(|| format!("{w:?} is not a sharpness (0 or more)"))
}

/// `subdiv edit`.
pub(crate) fn edit(a: &EditArgs) -> Result<()> {
    let loaded = a.from.read(&a.input, false)?;
    let (mesh, attrs) = (loaded.mesh, loaded.attributes);
    let s = a.sub.scheme.over(attrs.options);
    let levels = a.sub.levels_or(0);
    let mut r = Refiner::new(&mesh, s.scheme(), levels, &s.options())?;
    let mut changed = 0;
    for &(v, p) in &a.moves {
        changed += r.move_vertices(&[v], &[p])?;
    }
    for &(v, d) in &a.offsets {
        let p = r.control().get(v as usize).copied().unwrap_or(Vec3::ZERO) + d;
        changed += r.move_vertices(&[v], &[p])?;
    }
    if !a.creases.is_empty() || !a.corners.is_empty() {
        let mut tags = r.tags();
        for &(v0, v1, sharpness) in &a.creases {
            tags.creases.retain(|t| (t.v0.min(t.v1), t.v0.max(t.v1)) != (v0.min(v1), v0.max(v1)));
            tags.creases.push(CreaseTag { v0, v1, sharpness });
        }
        for &(vertex, sharpness) in &a.corners {
            tags.corners.retain(|t| t.vertex != vertex);
            tags.corners.push(CornerTag { vertex, sharpness });
        }
        tags.creases.retain(|t| t.sharpness > 0.0);
        tags.corners.retain(|t| t.sharpness > 0.0);
        r.set_tags(&Tags { creases: tags.creases, corners: tags.corners })
            .map_err(|e| Error::Usage(format!("{}: {e}", a.input.display())))?;
    }
    let (what, out) = if levels == 0 {
        io::save_with(&a.output, &r.cage(), &attrs)?;
        ("cage", r.cage())
    } else {
        io::save(&a.output, &r.mesh())?;
        ("level", r.mesh())
    };
    println!(
        "{} -> {}: {} moves, {} sharpness tags; {what} of {} vertices ({changed} refined vertices moved)",
        a.input.display(),
        a.output.display(),
        a.moves.len() + a.offsets.len(),
        a.creases.len() + a.corners.len(),
        out.positions.len(),
    );
    Ok(())
}
