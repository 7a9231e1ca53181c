//! The `subdiv` command line: view | animate | subdivide | batch | edit | smooth |
//! limit | eval | tessellate | repair | info | render | models | completions. Every command
//! that reads a model takes a file or `bundled:NAME`, a model compiled into the binary
//! (`subdiv models` lists them), through `subdiv::bundled`.
//!
//! One file per command or group; the option groups every command shares
//! are in [`args`], the log backend in [`logging`], progress bars in
//! [`progress`].

pub(crate) mod args;
mod batch;
mod draw;
mod edit;
mod eval;
mod info;
mod inspect;
pub(crate) mod logging;
mod mesh_ops;
pub(crate) mod progress;
mod tessellate;
mod view;

use clap::{CommandFactory, Parser, Subcommand};
use std::process::ExitCode;
use subdiv::Result;

/// The command line.
#[derive(Parser)]
#[command(name = "subdiv", version, about = "Subdivision surfaces (triangle and polygon schemes): viewer and command line", long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    cmd: Option<Cmd>,
    /// Worker threads (default: all cores).
    #[arg(long, global = true)]
    threads: Option<usize>,
    /// Print errors only (no warnings, repair reports or progress bars).
    #[arg(long, short, global = true, conflicts_with = "verbose")]
    quiet: bool,
    /// More log output on stderr: -v info, -vv debug, -vvv trace (RUST_LOG=LEVEL also works).
    #[arg(long, short, global = true, action = clap::ArgAction::Count)]
    verbose: u8,
}

#[derive(Subcommand)]
enum Cmd {
    /// Open the viewer (the default when no command is given).
    View(view::ViewArgs),
    /// Render the split-and-tweak animation to a GIF or numbered PNGs.
    Animate(draw::AnimateArgs),
    /// Subdivide a mesh and write the result (format by the output's extension).
    Subdivide(mesh_ops::SubdivideArgs),
    /// Subdivide many models (files, folders, globs) as `subdivide` does each, several at once within the memory budget, into one folder with a manifest.jsonl; run again, it skips what is done.
    ///
    /// Exit code 0 when every file is done (or was before), 1 when some
    /// failed (each named in the manifest), 2 for bad arguments.
    Batch(batch::BatchArgs),
    /// Taubin lambda/mu smoothing (no shrinkage), or plain Laplacian with --laplacian.
    Smooth(mesh_ops::SmoothArgs),
    /// Move every vertex to its limit position on the Loop or Catmull-Clark surface (after `subdivide`).
    Limit(mesh_ops::LimitCmdArgs),
    /// The exact Loop or Catmull-Clark limit surface at points `f u v`: position and normal (and curvature).
    Eval(eval::EvalArgs),
    /// The exact Loop or Catmull-Clark limit surface as a crack-free triangle mesh whose every triangle is within a tolerance of it (adaptive: fine only where the surface bends).
    Tessellate(tessellate::TessellateArgs),
    /// Edit the cage: move control vertices, set edge and vertex sharpness (in order), and write the edited cage (or, with --levels, its refined surface).
    Edit(edit::EditArgs),
    /// Repair a mesh into a valid manifold one and write it (format by extension).
    ///
    /// Drops degenerate and duplicate faces, cuts non-manifold edges, makes the
    /// orientation consistent, gives every fan of a non-manifold vertex its own
    /// copy and drops unreferenced vertices; prints what changed.
    Repair(mesh_ops::RepairArgs),
    /// Print counts, boundary, components, genus, valences and problems.
    ///
    /// A mesh that does not build (non-manifold, inconsistent orientation,
    /// degenerate faces) is analysed instead: every non-manifold edge and
    /// vertex is listed, and the counts are those of the repaired mesh. A
    /// .bzc Bezier curve is described as a curve (control points, degree).
    Info(info::InfoArgs),
    /// List the bundled models (open any of them as bundled:NAME).
    Models,
    /// Render a mesh offscreen to a PNG.
    Render(draw::RenderArgs),
    /// Print a shell completion script (e.g. `subdiv completions bash > /etc/bash_completion.d/subdiv`).
    Completions {
        /// bash, zsh, fish, elvish or powershell.
        shell: clap_complete::Shell,
    },
}

/// Runs the command line; the process's exit code.
pub(crate) fn main() -> ExitCode {
    // Like other Unix tools, end quietly when the reader of our output goes away
    // (`subdiv info big.obj | head`) instead of panicking on a broken pipe.
    // SAFETY: setting a signal disposition to the default before any thread starts.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let cli = Cli::parse();
    logging::init(cli.quiet, cli.verbose);
    if !matches!(cli.cmd, None | Some(Cmd::View(_))) {
        // a batch command: freed levels are reused, not unmapped (mem.rs)
        subdiv::mem::keep_freed_memory();
    }
    if let Some(n) = cli.threads
        && let Err(e) = rayon::ThreadPoolBuilder::new().num_threads(n.max(1)).build_global()
    {
        eprintln!("subdiv: cannot set {n} threads: {e}");
        return ExitCode::from(2);
    }
    match run(cli.cmd) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("subdiv: error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// Runs `cmd`: its exit code, or its error.
fn run(cmd: Option<Cmd>) -> Result<ExitCode> {
    let done = match cmd {
        None => view::first_launch(),
        Some(Cmd::View(args)) => view::view(args),
        Some(Cmd::Animate(args)) => draw::animate(args),
        Some(Cmd::Subdivide(args)) => mesh_ops::subdivide(&args),
        // its exit code says more than success (its errors are its own lines)
        Some(Cmd::Batch(args)) => return Ok(batch::batch(&args)),
        Some(Cmd::Repair(args)) => mesh_ops::repair(&args),
        Some(Cmd::Edit(args)) => edit::edit(&args),
        Some(Cmd::Smooth(args)) => mesh_ops::smooth(&args),
        Some(Cmd::Limit(args)) => mesh_ops::limit(&args),
        Some(Cmd::Eval(args)) => eval::eval(&args),
        Some(Cmd::Tessellate(args)) => tessellate::tessellate(&args),
        Some(Cmd::Info(args)) => info::info(&args),
        Some(Cmd::Models) => {
            info::models();
            Ok(())
        }
        Some(Cmd::Render(args)) => draw::render(&args),
        Some(Cmd::Completions { shell }) => {
            clap_complete::generate(shell, &mut Cli::command(), "subdiv", &mut std::io::stdout());
            Ok(())
        }
    };
    done.map(|()| ExitCode::SUCCESS)
}

/// Prints `value` as one line of JSON on stdout.
fn print_json(value: &impl serde::Serialize) -> Result<()> {
    let s = serde_json::to_string(value).map_err(|e| subdiv::Error::Usage(format!("JSON output: {e}")))?;
    println!("{s}");
    Ok(())
}
