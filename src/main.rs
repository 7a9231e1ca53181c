//! The `subdiv` binary: the command line of [`cli`] (feature `cli`).

mod cli;

fn main() -> std::process::ExitCode {
    cli::main()
}
