//! The `springwater` command line: a thin layer over the library (its contract:
//! `cli/README.md`).
//!
//! Every failure ends with one line on stderr and a non-zero exit code.

/// `println!` for a command's report on stdout, written through [`write_out`]: in a function
/// that returns [`args::CliResult`], it never panics.
macro_rules! say {
    ($($arg:tt)*) => {
        $crate::write_out(format_args!("{}\n", format_args!($($arg)*)))?
    };
}

mod args;
mod bake;
mod bench;
mod boats;
mod export;
mod help;
mod image;
mod interrupt;
mod memory;
mod output;
mod progress;
mod render;
mod simulate;
mod start;

use std::process::ExitCode;

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("springwater: error: {message}");
            ExitCode::from(2)
        }
    }
}

/// Writes to stdout. A reader that has gone away (`springwater bench | head -1`) is not an
/// error: the rest of the report is dropped and the command still does all its work (the
/// files it was asked to write are written). Any other write error is reported.
fn write_out(text: std::fmt::Arguments) -> args::CliResult<()> {
    use std::io::Write;
    match std::io::stdout().lock().write_fmt(text) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
            Err(format!("cannot write to standard output: {e}"))
        }
        _ => Ok(()),
    }
}

fn run() -> args::CliResult<()> {
    let mut p = lexopt::Parser::from_env();
    // No command, `-h` and `--help` are the `help` command.
    let command = match args::next_flag(&mut p)? {
        Some(args::Flag::Value(v)) => v.to_string_lossy().into_owned(),
        Some(args::Flag::Short('h')) | None => "help".to_owned(),
        Some(args::Flag::Long(l)) if l == "help" => "help".to_owned(),
        Some(args::Flag::Short('V')) => return write_out(format_args!("{}", help::version())),
        Some(args::Flag::Long(l)) if l == "version" => {
            return write_out(format_args!("{}", help::version()))
        }
        Some(other) => return Err(args::unexpected(other, "springwater")),
    };
    // `springwater CMD --help` (anywhere after the command) and `springwater help CMD`.
    let rest: Vec<std::ffi::OsString> = std::env::args_os().skip(2).collect();
    let asks_help = rest.iter().any(|a| a == "--help" || a == "-h");
    let topic = match command.as_str() {
        "help" => Some(rest.first().map(|c| c.to_string_lossy().into_owned())),
        _ if asks_help => Some(Some(command.clone())),
        _ => None,
    };
    if let Some(topic) = topic {
        let text =
            help::text(topic.as_deref()).ok_or_else(|| unknown(topic.as_deref().unwrap_or("")))?;
        return write_out(format_args!("{text}"));
    }
    args::each_once(&rest)?;
    // Signals are heard before any output is started (see `interrupt`).
    match command.as_str() {
        "simulate" => interrupt::install(true),
        "render" | "export" | "bake" => interrupt::install(false),
        _ => {}
    }
    match command.as_str() {
        "simulate" => simulate::run(&mut p),
        "bench" => bench::run(&mut p),
        "render" => render::run(&mut p),
        "export" => export::run(&mut p),
        "bake" => bake::run(&mut p),
        other => Err(unknown(other)),
    }
}

fn unknown(command: &str) -> String {
    format!(
        "unknown command '{command}' (render, simulate, bench, export, bake; see springwater --help)"
    )
}
