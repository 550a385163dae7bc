//! The `rastty` command: parse the command line, run, report errors in one
//! line. Everything else lives in the library.

mod cli;

use std::io::{self, Write};
use std::process::ExitCode;

use clap::Parser as _;

use cli::{Cli, Command, RenderArgs, SpinArgs, ViewArgs};
use rastty::animate::{self, Player, Spin};
use rastty::encode::Encoder;
use rastty::plan::Pipeline;
use rastty::terminal::{self, Exit};
use rastty::{RenderOptions, Renderer, Scene, encode};

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return usage_error(e),
    };
    match try_main(cli) {
        Ok(code) => code,
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

fn stdout_error(e: io::Error) -> rastty::Error {
    rastty::Error::io("<stdout>".as_ref(), e)
}

fn try_main(cli: Cli) -> rastty::Result<ExitCode> {
    let command = match cli.command {
        Some(c) => c,
        // Bare `rastty`: spin in a terminal, one frame otherwise, with every
        // option at its default.
        None => {
            let sub = if terminal::stdout_is_terminal() {
                "spin"
            } else {
                "render"
            };
            Cli::try_parse_from(["rastty", sub])
                .ok()
                .and_then(|c| c.command)
                .expect("the defaults parse")
        }
    };
    match command {
        Command::Render(args) => render(&args).map(|()| ExitCode::SUCCESS),
        Command::Spin(args) => spin(&args),
        Command::Bench(args) => bench(&args).map(|()| ExitCode::SUCCESS),
    }
}

fn bench(args: &cli::BenchArgs) -> rastty::Result<()> {
    let workloads = rastty::bench::workloads(&args.models);
    let report = rastty::bench::run(&workloads, args.reps as usize);
    let mut out = io::stdout().lock();
    writeln!(
        out,
        "Time per frame at 200×60 cells (median of {} frames; rendering, or encoding for quantisation), and each knob's error.",
        args.reps
    )
    .and_then(|()| write!(out, "{}", report.markdown()))
    .map_err(stdout_error)?;
    report
        .svg(&args.svg)
        .map_err(|e| rastty::Error::Invalid(format!("{}: {e}", args.svg.display())))?;
    eprintln!("wrote {}", args.svg.display());
    Ok(())
}

fn scene(path: Option<&std::path::Path>) -> rastty::Result<Scene> {
    match path {
        Some(p) => Scene::open(p),
        None => Ok(rastty::default_scene()),
    }
}

fn render(args: &RenderArgs) -> rastty::Result<()> {
    let scene = scene(args.scene.as_deref())?;
    let opts = options(&args.view, 1);
    let mut renderer = Renderer::new();
    let frame = renderer.render(&scene, &opts);
    let mut stdout = io::stdout().lock();
    let mut buf = Vec::new();
    let start = std::time::Instant::now();
    encode::write_lines(frame, opts.color, args.view.rep(), &mut buf, &mut stdout)
        .and_then(|()| stdout.flush())
        .map_err(stdout_error)?;
    if args.explain {
        let encode = start.elapsed();
        eprint!(
            "{}",
            rastty::plan::explain(&scene, &opts, &renderer, encode, buf.len())
        );
    }
    Ok(())
}

fn spin(args: &SpinArgs) -> rastty::Result<ExitCode> {
    let scene = scene(args.scene.as_deref())?;
    let opts = options(&args.view, 0);
    let spin = Spin {
        axis: args.axis,
        step: args.step,
    };
    let encoder = Encoder::new(opts.color).with_rep(args.view.rep());
    if !terminal::stdout_is_terminal() {
        // Not a terminal: the frames as one deterministic ANSI stream.
        let Some(frames) = args.frames else {
            return Err(rastty::Error::Invalid(
                "spin: stdout is not a terminal; give --frames N to write N frames, or use `rastty render`".into(),
            ));
        };
        let mut out = io::stdout().lock();
        animate::play(&scene, &opts, spin, frames, encoder, &mut out).map_err(stdout_error)?;
        return Ok(ExitCode::SUCCESS);
    }
    terminal::install_panic_hook();
    let mut player = Player::new(scene, opts, spin, encoder).with_hud(args.hud);
    match terminal::run(&mut player, args.fps, args.frames).map_err(stdout_error)? {
        Exit::Quit | Exit::Done => Ok(ExitCode::SUCCESS),
        Exit::Signal(sig) => Ok(ExitCode::from((128 + sig).clamp(0, 255) as u8)),
    }
}

/// Resolves sizes and colour against the terminal; `spare_rows` are left
/// free below the frame (for the shell prompt after `render`).
fn options(view: &ViewArgs, spare_rows: u16) -> RenderOptions {
    let tty = terminal::stdout_is_terminal();
    let term = if tty { terminal::size() } else { None };
    let cols = view
        .cols
        .or(term.map(|t| t.0))
        .unwrap_or(80)
        .min(cli::MAX_CELLS);
    let rows = view
        .rows
        .or(term.map(|t| t.1.saturating_sub(spare_rows).max(1)))
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
        glyphs: view.glyphs,
        color,
        cell_aspect,
        traversal: view.traversal,
        turn: glam::Vec3::new(view.pitch, view.yaw, view.roll),
        shading: view.shading,
        cull: view.cull,
        pipeline: if view.full_pipeline {
            Pipeline::Full
        } else {
            Pipeline::Planned
        },
        aa: view.aa,
        interpolation: view.interpolation,
        split: view.split,
    }
}
