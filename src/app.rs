//! What each subcommand does, callable from Rust; the binary only parses and reports.

use crate::cli::{Cli, Command, ReportArgs, SolveArgs, UsageError};
use crate::scene;
use anyhow::Result;
use std::io::Write;
use std::process::ExitCode;

/// Exit status for an error: 2 for bad usage or input, 1 for a failed run.
pub fn exit_code(err: &anyhow::Error) -> u8 {
    if err.chain().any(|c| {
        c.is::<UsageError>()
            || c.is::<crate::manifest::ManifestError>()
            || c.is::<crate::plan::PlanTooLarge>()
            || c.is::<crate::report::data::RunDirError>()
    }) {
        2
    } else {
        1
    }
}

/// Runs a parsed command line.
pub fn run(cli: Cli) -> Result<ExitCode> {
    match cli.command {
        Command::Solve(args) => solve(&args),
        Command::Run(args) => crate::runner::run_command(&args),
        Command::Check(args) => crate::runner::check_command(&args),
        Command::Report(args) => report(&args),
        Command::Archive(args) => crate::archive::archive_command(&args),
        Command::Verify(args) => crate::verify::verify_command(&args),
    }
}

fn report(args: &ReportArgs) -> Result<ExitCode> {
    let s = crate::report::render_run(&args.run_dir)?;
    eprintln!(
        "{} figures; wrote {} and {}",
        s.figures,
        s.html.display(),
        s.markdown.display()
    );
    Ok(ExitCode::SUCCESS)
}

fn solve(args: &SolveArgs) -> Result<ExitCode> {
    let scene = args.scene()?;
    let sol = scene::solve(&scene);
    let text = if args.json {
        serde_json::to_string_pretty(&sol)? + "\n"
    } else {
        scene::summary(&sol)
    };
    let mut out = std::io::stdout().lock();
    // A closed pipe (e.g. `| head`) is not an error worth a panic.
    match out.write_all(text.as_bytes()).and_then(|_| out.flush()) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => {}
        Err(e) => return Err(e.into()),
        Ok(()) => {}
    }
    Ok(ExitCode::SUCCESS)
}
