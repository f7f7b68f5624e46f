//! The `archstudy` binary: a thin layer over the library's command-line module.

use archstudy::app::Cli;
use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = Cli::parse();
    match archstudy::app::run(cli) {
        Ok(code) => code,
        Err(err) => {
            eprintln!("error: {err}");
            for cause in err.chain().skip(1) {
                eprintln!("  caused by: {cause}");
            }
            ExitCode::from(archstudy::app::exit_code(&err))
        }
    }
}
