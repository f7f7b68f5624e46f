//! The `archstudy` binary: a thin layer over the library's command-line module.

use archstudy::app::Cli;
use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = Cli::parse();
    match archstudy::app::run(cli) {
        Ok(code) => code,
        Err(err) => {
            // An error raised because the interrupt handler removed the run's files is the
            // interrupt itself: the handler is about to exit with 128 + the signal.
            if let Some(sig) = archstudy::runner::interrupted_by() {
                std::process::exit(128 + sig);
            }
            eprintln!("error: {err}");
            for cause in err.chain().skip(1) {
                eprintln!("  caused by: {cause}");
            }
            ExitCode::from(archstudy::app::exit_code(&err))
        }
    }
}
