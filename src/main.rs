//! The `rastty` command: parse the command line, run, report errors in one
//! line. Everything else lives in the library.

mod cli;

use std::io::{self, Write};
use std::process::ExitCode;

use clap::Parser as _;

use cli::{Cli, Command, RenderArgs, ViewArgs};
use rastty::{RenderOptions, Renderer, Scene, encode, terminal};

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return usage_error(e),
    };
    match try_main(cli) {
        Ok(()) => ExitCode::SUCCESS,
        // A closed pipe (`rastty render | head`) is not an error.
        Err(e) if is_broken_pipe(&e) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// `--help` and `--version` print as clap has them; a usage error prints
/// its first line only (`error: invalid value '0' for '--cols <N>': …`) and
/// exits with 2.
fn usage_error(e: clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
        let _ = e.print();
        return ExitCode::SUCCESS;
    }
    let text = e.render().to_string();
    eprintln!(
        "{}",
        text.lines().next().unwrap_or("error: invalid arguments")
    );
    ExitCode::from(2)
}

fn is_broken_pipe(e: &rastty::Error) -> bool {
    matches!(e, rastty::Error::Io { source, .. } if source.kind() == io::ErrorKind::BrokenPipe)
}

fn try_main(cli: Cli) -> rastty::Result<()> {
    match cli.command {
        Some(Command::Render(args)) => render(&args),
        None => render(&RenderArgs::default()),
    }
}

fn render(args: &RenderArgs) -> rastty::Result<()> {
    let scene = match &args.scene {
        Some(path) => Scene::load(path)?,
        None => rastty::default_scene(),
    };
    let opts = options(&args.view);
    let mut renderer = Renderer::new();
    let frame = renderer.render(&scene, &opts);
    let mut stdout = io::stdout().lock();
    let mut buf = Vec::new();
    encode::write_lines(frame, opts.color, args.view.rep(), &mut buf, &mut stdout)
        .and_then(|()| stdout.flush())
        .map_err(|e| rastty::Error::io("<stdout>".as_ref(), e))
}

/// Resolves sizes and colour against the terminal.
fn options(view: &ViewArgs) -> RenderOptions {
    let tty = terminal::stdout_is_terminal();
    let term = if tty { terminal::size() } else { None };
    let cols = view
        .cols
        .or(term.map(|t| t.0))
        .unwrap_or(80)
        .min(cli::MAX_CELLS);
    // One row fewer than the terminal's, so the prompt does not scroll the
    // top row away.
    let rows = view
        .rows
        .or(term.map(|t| t.1.saturating_sub(1).max(1)))
        .unwrap_or(24)
        .min(cli::MAX_CELLS);
    let color = view
        .color
        .depth()
        .unwrap_or_else(|| terminal::detect_color(tty, |k| std::env::var(k).ok()));
    let cell_aspect = view
        .cell_aspect
        .or_else(|| if tty { terminal::cell_aspect() } else { None })
        .unwrap_or(0.5);
    RenderOptions {
        cols,
        rows,
        glyphs: view.glyphs.into(),
        color,
        cell_aspect,
        traversal: view.traversal.into(),
        turn: glam::Vec3::new(view.pitch, view.yaw, view.roll),
    }
}
