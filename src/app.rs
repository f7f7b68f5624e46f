//! What each subcommand does, callable from Rust; the binary only parses and reports.

use crate::cli::{Cli, Command, SolveArgs, UsageError};
use crate::scene;
use anyhow::Result;
use std::process::ExitCode;

/// Exit status for an error: 2 for bad usage or input, 1 for a failed run.
pub fn exit_code(err: &anyhow::Error) -> u8 {
    if err.chain().any(|c| c.is::<UsageError>()) {
        2
    } else {
        1
    }
}

/// Runs a parsed command line.
pub fn run(cli: Cli) -> Result<ExitCode> {
    match cli.command {
        Command::Solve(args) => solve(&args),
        Command::Run(_) | Command::Check(_) => {
            anyhow::bail!("study manifests are not supported yet")
        }
    }
}

fn solve(args: &SolveArgs) -> Result<ExitCode> {
    let scene = args.scene()?;
    let sol = scene::solve(&scene);
    if args.json {
        println!("{}", serde_json::to_string_pretty(&sol)?);
    } else {
        print!("{}", scene::summary(&sol));
    }
    Ok(ExitCode::SUCCESS)
}
