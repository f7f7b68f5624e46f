//! The command line: the only code that sees clap or prints. It turns arguments into the
//! library's options, shows progress, and writes what each command returns.

pub mod args;
mod cluster;
mod progress;

pub use args::{Cli, Command};

use crate::error::UsageError;
use crate::{archive, report, runner, scene, verify};
use anyhow::Result;
use args::{ArchiveArgs, CheckArgs, ExploreArgs, ReportArgs, RunArgs, SolveArgs, VerifyArgs};
use std::io::Write;
use std::process::ExitCode;
use std::sync::Arc;

/// Exit status for an error: 2 for bad usage or input, 1 for a failed run.
pub fn exit_code(err: &anyhow::Error) -> u8 {
    if err.chain().any(|c| {
        c.is::<UsageError>()
            || c.is::<crate::manifest::ManifestError>()
            || c.is::<crate::plan::PlanTooLarge>()
            || c.is::<crate::report::data::RunDirError>()
            || c.is::<crate::report::checks::TableError>()
            || c.is::<crate::store::ColumnTypeError>()
    }) {
        2
    } else {
        1
    }
}

/// Runs a parsed command line.
pub fn run(cli: Cli) -> Result<ExitCode> {
    runner::remove_partial_output_on_interrupt()?;
    match cli.command {
        Command::Solve(args) => solve(&args),
        Command::Run(args) => run_study(&args),
        Command::Check(args) => check(&args),
        Command::Report(args) => render(&args),
        Command::Archive(args) => pack(&args),
        Command::Verify(args) => check_archive(&args),
        Command::Merge(args) => cluster::merge(&args),
        Command::Slurm(args) => cluster::slurm(&args),
        Command::Explore(args) => explore(&args),
    }
}

/// Writes text to standard output; a closed pipe (e.g. `| head`) is not an error.
fn print_out(text: &str) -> Result<()> {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|_| out.flush()) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        Err(e) => Err(e.into()),
        Ok(()) => Ok(()),
    }
}

fn solve(args: &SolveArgs) -> Result<ExitCode> {
    let scene = args.scene()?;
    let sol = scene::solve(&scene);
    let text = if args.json {
        serde_json::to_string_pretty(&sol)? + "\n"
    } else {
        scene::summary(&sol)
    };
    print_out(&text)?;
    Ok(ExitCode::SUCCESS)
}

/// Where a command shows its progress: nowhere with --quiet, else a bar on standard error.
fn shown(quiet: bool) -> Arc<dyn crate::progress::Progress> {
    if quiet {
        Arc::new(crate::progress::Silent)
    } else {
        Arc::new(progress::Shown::on_stderr())
    }
}

fn run_study(args: &RunArgs) -> Result<ExitCode> {
    let opts = args.options(shown(args.quiet))?;
    let summary = match &args.shard {
        Some(s) => crate::shard::run_shard(&opts, crate::shard::Shard::parse("--shard", s)?)?,
        None => runner::run_study(&opts)?,
    };
    report_run(&summary);
    Ok(ExitCode::SUCCESS)
}

/// The closing lines of a run, a shard or a merge.
fn report_run(summary: &runner::RunSummary) {
    let cases = |n: u64| {
        if n == 1 {
            "1 case".to_string()
        } else {
            format!("{n} cases")
        }
    };
    eprintln!(
        "{} ({} ok, {} failed) in {:.2} s; written to {}",
        cases(summary.info.cases.total),
        summary.info.cases.ok,
        summary.info.cases.error,
        summary.wall_s,
        summary.dir.display()
    );
    if summary.info.cases.error > 0 {
        eprintln!(
            "warning: {} failed; their rows carry status `error` and a message",
            cases(summary.info.cases.error)
        );
    }
}

fn check(args: &CheckArgs) -> Result<ExitCode> {
    let summary = runner::check(&args.study)?;
    print_out(&format!(
        "{}manifest sha256: {}\n",
        summary.plan, summary.manifest_sha256
    ))?;
    Ok(ExitCode::SUCCESS)
}

fn render(args: &ReportArgs) -> Result<ExitCode> {
    let s = report::render_run(&args.run_dir)?;
    eprintln!(
        "{} figures; wrote {} and {}",
        s.figures,
        s.html.display(),
        s.markdown.display()
    );
    Ok(ExitCode::SUCCESS)
}

fn pack(args: &ArchiveArgs) -> Result<ExitCode> {
    let s = archive::write_archive_with(&args.run_dir, args.output.as_deref(), args.force)?;
    for k in &s.skipped {
        eprintln!(
            "warning: {k} was left out: only the regular files a run writes are archived, \
             never a symbolic link or a file added by hand"
        );
    }
    eprintln!(
        "{} files and {} under {}/ ({} bytes) written to {}",
        s.files,
        archive::SUMS_FILE,
        s.top,
        s.bytes,
        s.path.display()
    );
    Ok(ExitCode::SUCCESS)
}

fn check_archive(args: &VerifyArgs) -> Result<ExitCode> {
    let opts = args.options()?;
    let mut out = std::io::stdout().lock();
    let agrees = verify::verify(&opts, &mut out)?;
    out.flush()?;
    Ok(if agrees {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

fn explore(args: &ExploreArgs) -> Result<ExitCode> {
    let server = crate::explore::start(&crate::explore::ExploreOptions {
        run_dir: args.run_dir.clone(),
        host: args.host.clone(),
        port: args.port,
    })
    .map_err(|e| match e.downcast::<crate::explore::ListenError>() {
        Ok(l) if l.port_at_fault() => anyhow::Error::new(UsageError::new(
            "--port",
            args.port,
            format!(
                "a free port this user may take ({}); --port 0 takes any free one",
                l.reason
            ),
        )),
        Ok(l) => anyhow::Error::new(UsageError::new(
            "--host",
            &args.host,
            format!(
                "an address of this machine, e.g. 127.0.0.1 or 0.0.0.0 ({})",
                l.reason
            ),
        )),
        Err(e) => e,
    })?;
    let loopback = server.addr().ip().is_loopback();
    if !loopback {
        eprintln!(
            "warning: listening on {}: other machines that reach it can use this server \
             (it is read-only, but every request runs analyses on this machine)",
            args.host
        );
    }
    print_out(&format!(
        "archstudy explore: serving {} (Ctrl-C to stop)\n",
        server.url()
    ))?;
    if args.open {
        let opener = if cfg!(target_os = "macos") {
            "open"
        } else {
            "xdg-open"
        };
        if std::process::Command::new(opener)
            .arg(server.url())
            .spawn()
            .is_err()
        {
            eprintln!(
                "warning: could not start {opener}; open {} yourself",
                server.url()
            );
        }
    }
    server.wait()?;
    Ok(ExitCode::SUCCESS)
}
