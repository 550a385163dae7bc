//! The `rastty` command: parse the command line, run the command, report
//! errors in one line and map them to an exit code. Each command is a
//! module of its own; everything else lives in the library.

mod bench;
mod cli;
mod commands;
mod gesture;
mod link;
mod live;
mod pixels;
mod say;
mod setup;
mod terminal;

use std::process::ExitCode;

use clap::Parser as _;

use cli::{Cli, Command};

fn main() -> ExitCode {
    setup::keep_large_blocks_mapped();
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return cli::usage_error(e),
    };
    say::fit_previews(&cli);
    let code = match run(cli) {
        Ok(code) => code,
        // A closed pipe (`rastty render | head`) is not an error.
        Err(e) if say::is_broken_pipe(&e) => ExitCode::SUCCESS,
        Err(e) => {
            say::say("error", &e.to_string());
            ExitCode::FAILURE
        }
    };
    if say::unsaid() {
        return ExitCode::FAILURE;
    }
    code
}

/// Runs the command (bare `rastty`: `spin` in a terminal, one frame
/// otherwise, with every option at its default).
fn run(cli: Cli) -> rastty::Result<ExitCode> {
    match cli.command.unwrap_or_else(Cli::default_command) {
        Command::Render(args) => commands::render::render(&args).map(|()| ExitCode::SUCCESS),
        Command::Spin(args) => commands::spin::spin(&args),
        Command::Bench(args) => commands::bench::bench(&args).map(|()| ExitCode::SUCCESS),
    }
}
