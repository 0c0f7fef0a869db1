//! `gcs`: the command line of the gcs compiler. It is the only place that reads files, prints
//! and chooses an exit code.

use clap::{Parser, Subcommand};
use codespan_reporting::term::{self, termcolor};
use gcs_lang::{Diagnostic, SourceFile};
use std::path::PathBuf;
use std::process::ExitCode;

/// Compiles geometric constraint models (.gcs) into specialised solvers.
#[derive(Debug, Parser)]
#[command(name = "gcs", version, about)]
struct Cli {
    /// When to colour diagnostics: auto, always or never.
    #[arg(long, global = true, default_value = "auto")]
    color: String,
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Parse and analyse a model; print its diagnostics and DOF summary. Exits 0 only without
    /// errors.
    Check {
        /// The .gcs file.
        file: PathBuf,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let color = match cli.color.as_str() {
        "always" => termcolor::ColorChoice::Always,
        "never" => termcolor::ColorChoice::Never,
        _ if std::env::var_os("NO_COLOR").is_some() => termcolor::ColorChoice::Never,
        _ if !std::io::IsTerminal::is_terminal(&std::io::stderr()) => termcolor::ColorChoice::Never,
        _ => termcolor::ColorChoice::Auto,
    };
    match cli.command {
        Command::Check { file } => check(&file, color),
    }
}

fn check(path: &PathBuf, color: termcolor::ColorChoice) -> ExitCode {
    let name = path.display().to_string();
    let bytes = match std::fs::read(path) {
        Ok(b) => b,
        Err(e) => {
            eprintln!("error: cannot read `{name}`: {e}");
            return ExitCode::from(2);
        }
    };
    let (source, model, diags) = gcs_lang::load(&name, &bytes);
    emit(&source, &diags, color);
    match model {
        Some(model) => {
            print!("{}", gcs_compiler::nominal::report(&model));
            ExitCode::SUCCESS
        }
        None => {
            let errors = diags.iter().filter(|d| d.is_error()).count();
            eprintln!(
                "error: could not check `{name}` due to {errors} previous error{}",
                if errors == 1 { "" } else { "s" }
            );
            ExitCode::FAILURE
        }
    }
}

/// Renders diagnostics to stderr, with colour when the terminal has it.
fn emit(source: &SourceFile, diags: &[Diagnostic], color: termcolor::ColorChoice) {
    let file = gcs_lang::diagnostic::codespan_file(source);
    let writer = termcolor::StandardStream::stderr(color);
    let mut lock = writer.lock();
    let config = term::Config::default();
    for d in diags {
        if term::emit_to_write_style(&mut lock, &config, &file, &d.to_codespan()).is_err() {
            eprintln!("error: {}", d.message);
        }
    }
}
