//! The `rastty` command: parse the command line, run, report errors in one
//! line. Everything else lives in the library.

mod bench;
mod cli;
mod gesture;
mod live;
mod terminal;

use rastty::Choice;
use std::io::{self, Write};
use std::path::Path;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use clap::Parser as _;

use cli::{Cli, Command, RenderArgs, SpinArgs, ViewArgs};
use live::{Exit, LiveOptions};
use rastty::Pipeline;
use rastty::animate;
use rastty::animate::{Player, Spin};
use rastty::cast::{self, Recorder};
use rastty::encode::Encoder;
use rastty::outfile::OutFile;
use rastty::picture::{self, Format, Theme};
use rastty::scene::{Projection, Scene, View};
use rastty::{GlyphMode, RenderOptions, Renderer, color::ColorDepth, encode};

/// glibc's malloc raises its mmap threshold to the size of each large
/// block freed (up to 32 MiB): after the loader frees its connectivity
/// tables, blocks that large come from the heap, and stay resident when
/// freed. A fixed threshold (its default, 128 KiB) keeps every large block
/// mapped and given back when freed: the frame's vertex buffers then
/// reuse memory the loader returned rather than lying beside it (the
/// peak memory of docs/figures.md's loading rows).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
fn keep_large_blocks_mapped() {
    // SAFETY: mallopt only sets a parameter of the allocator; called
    // first thing in main, before any other thread exists.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 128 * 1024);
    }
}

#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
fn keep_large_blocks_mapped() {}

fn main() -> ExitCode {
    keep_large_blocks_mapped();
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return usage_error(e),
    };
    // A preview of a given width gets notes and errors that fit it.
    if let Some(Command::Render(args)) = &cli.command
        && args.preview
        && let Some(w) = args.view.cols
    {
        let _ = FIT.set((usize::from(w), args.input.scene.clone()));
    }
    let code = match try_main(cli) {
        Ok(code) => code,
        // A closed pipe (`rastty render | head`) is not an error.
        Err(e) if is_broken_pipe(&e) => ExitCode::SUCCESS,
        Err(e) => {
            say("error", &e.to_string());
            ExitCode::FAILURE
        }
    };
    if UNSAID.load(Ordering::Relaxed) {
        // Something to say was lost (stderr full or closed).
        return ExitCode::FAILURE;
    }
    code
}

/// For `render --preview --cols N`: the width every line on stderr is cut
/// to, and the model's path (shortened to its file name where a line is
/// wider).
static FIT: std::sync::OnceLock<(usize, Option<std::path::PathBuf>)> = std::sync::OnceLock::new();

/// `line` in `width` characters: the model's path shortened to its file
/// name where the line is wider, then the end cut off with `…` (the start
/// says which file and what is wrong).
fn fitted(line: &str, width: usize, path: Option<&Path>) -> String {
    let width = width.max(1);
    let mut line = line.to_string();
    if line.chars().count() > width
        && let Some(path) = path
        && let Some(name) = path.file_name()
    {
        let (full, name) = (path.to_string_lossy(), name.to_string_lossy());
        line = line.replacen(full.as_ref(), name.as_ref(), 1);
    }
    if line.chars().count() <= width {
        return line;
    }
    let mut cut: String = line.chars().take(width - 1).collect();
    cut.push('…');
    cut
}

/// Set when a line for stderr could not be written.
static UNSAID: AtomicBool = AtomicBool::new(false);

/// Writes `message` on stderr as one line after `label` (`error`,
/// `note`), escaped and cut as [`rastty::text::line()`] does: a name from a
/// file never drives the terminal. A stderr that cannot be written (full,
/// closed) is not a reason to panic, and not a success: the exit status
/// is 1.
fn say(label: &str, message: &str) {
    say_lines(&format!("{label}: {}", rastty::text::line(message)));
}

/// Writes `text` on stderr line by line, each escaped (for messages of
/// several lines: clap's, `--explain`'s).
fn say_lines(text: &str) {
    let mut err = io::stderr().lock();
    let mut ok = terminal::is_open(2);
    for l in text.lines() {
        let l = rastty::text::escape(l);
        let l = match FIT.get() {
            Some((width, path)) => fitted(&l, *width, path.as_deref()).into(),
            None => l,
        };
        ok &= writeln!(err, "{l}").is_ok();
    }
    ok &= err.flush().is_ok();
    if !ok {
        UNSAID.store(true, Ordering::Relaxed);
    }
}

/// Stdout, refused when it is closed (`>&-`): the standard library would
/// take every write to it as done.
fn stdout() -> rastty::Result<io::StdoutLock<'static>> {
    if !terminal::is_open(1) {
        #[cfg(unix)]
        let closed = io::Error::from_raw_os_error(libc::EBADF);
        #[cfg(not(unix))]
        let closed = io::Error::other("stdout is closed");
        return Err(stdout_error(closed));
    }
    Ok(io::stdout().lock())
}

/// `--help` and `--version` print as clap has them; a usage error prints
/// clap's message (with the possible values, and a suggestion where one is
/// close) and exits with 2. A model or scene named where a command belongs
/// (`rastty bunny.obj`) gets the command that shows it.
fn usage_error(e: clap::Error) -> ExitCode {
    use clap::error::{ContextKind, ContextValue, ErrorKind};
    if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
        let _ = e.print();
        return ExitCode::SUCCESS;
    }
    let named = match e.get(ContextKind::InvalidSubcommand) {
        Some(ContextValue::String(arg)) if e.kind() == ErrorKind::InvalidSubcommand => Some(arg),
        _ => None,
    };
    if let Some(arg) = named {
        let path = std::path::Path::new(arg);
        if path.exists() || Scene::is_model(path) || arg.ends_with(".toml") {
            let arg = rastty::text::line(arg);
            say_lines(&format!(
                "error: '{arg}' is not a command; to show it, run\n\n  rastty spin {arg}\n\nor `rastty render {arg}` for one frame (rastty --help lists the commands)"
            ));
            return ExitCode::from(2);
        }
    }
    // clap's message without its colours, each line escaped: it quotes
    // the arguments it refuses.
    say_lines(&e.render().to_string());
    // `rastty --hud`: an option of a command given before any command.
    let args: Vec<String> = std::env::args().skip(1).collect();
    if e.kind() == ErrorKind::UnknownArgument
        && args.first().is_some_and(|a| a.starts_with('-'))
        && !args
            .iter()
            .any(|a| matches!(a.as_str(), "render" | "spin" | "bench"))
    {
        say_lines(&format!(
            "hint: options follow a command: rastty spin {}",
            rastty::text::line(&args.join(" "))
        ));
    }
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
    // The plot's file is begun before the work, which takes minutes.
    let mut svg = OutFile::create(&args.svg)?;
    let models = match &args.models {
        Some(dir) if !dir.is_dir() => {
            return Err(rastty::Error::Invalid(format!(
                "{}: not a folder of models (--models)",
                dir.display()
            )));
        }
        Some(dir) => dir.clone(),
        None => std::path::PathBuf::from("../shared/models"),
    };
    let (workloads, notes) = if models.is_dir() {
        bench::workloads(&models)
    } else {
        (
            bench::workloads(&models).0,
            vec![format!(
                "{}: not found: the built-in scenes alone are timed (--models names a folder)",
                models.display()
            )],
        )
    };
    for note in &notes {
        say("note", note);
    }
    let mut out = stdout()?;
    let report = bench::run(&workloads, args.reps as usize);
    writeln!(
        out,
        "Time per frame at 200×60 cells (median of {} frames; rendering, or encoding for quantisation), and each knob's error.",
        args.reps
    )
    .and_then(|()| write!(out, "{}", report.markdown()))
    .map_err(stdout_error)?;
    let plot = report
        .svg()
        .map_err(|e| rastty::Error::Invalid(format!("{}: {e}", args.svg.display())))?;
    svg.write_all(plot.as_bytes())
        .map_err(|e| rastty::Error::io(&args.svg, e))?;
    svg.commit()?;
    say_lines(&format!(
        "wrote {}",
        rastty::text::line(&args.svg.display().to_string())
    ));
    Ok(())
}

/// The scene to draw; what the loaders read but cannot draw is said on
/// stderr.
fn scene(input: &cli::InputArgs, budgets: &cli::BudgetArgs) -> rastty::Result<Scene> {
    let mut options = rastty::scene::LoadOptions {
        up: input.up,
        crease: input.crease,
        mtl_colors: input.mtl_colors,
        ..Default::default()
    };
    if let Some(max) = budgets.max_file_size {
        options.max_bytes = max;
    }
    if let Some(max) = budgets.max_texels {
        options.max_texels = max;
    }
    if let Some(max) = budgets.max_triangles {
        options.max_triangles = max;
    }
    let scene = match &input.scene {
        Some(p) => Scene::open_within(p, &options)?,
        None => rastty::scene::default_scene(),
    };
    for note in &scene.notes {
        say("note", note);
    }
    Ok(scene)
}

/// The clip `--clip` names (a number from 0, or a name), the first by
/// default; `None` when no model moves.
fn clip(scene: &Scene, named: Option<&str>) -> rastty::Result<Option<usize>> {
    let clips = scene.clips();
    if clips.is_empty() {
        return match named {
            Some(_) => Err(rastty::Error::Invalid(
                "--clip: no model of the scene has clips".into(),
            )),
            None => Ok(None),
        };
    }
    let Some(named) = named else {
        return Ok(Some(0));
    };
    if let Ok(n) = named.parse::<usize>() {
        return if n < clips.len() {
            Ok(Some(n))
        } else {
            Err(rastty::Error::Invalid(format!(
                "--clip {n}: the model has {} clips, 0 to {}",
                clips.len(),
                clips.len() - 1
            )))
        };
    }
    clips
        .iter()
        .position(|c| c.name == named)
        .map(Some)
        .ok_or_else(|| {
            let names: Vec<String> = clips
                .iter()
                .enumerate()
                .map(|(i, c)| format!("{i} {}", rastty::text::name(&c.name, 40)))
                .collect();
            rastty::Error::Invalid(format!(
                "--clip {}: no clip of that name; the clips are {}",
                rastty::text::name(named, 40),
                names.join(", ")
            ))
        })
}

fn render(args: &RenderArgs) -> rastty::Result<()> {
    let format = args.output.as_deref().map(Format::of).transpose()?;
    let mut opts = options(&args.view, &args.knobs, &args.budgets, 1);
    if let Some(format) = format {
        // A file is not the terminal: sizes and colours are its own.
        opts.color = args.view.color.depth().unwrap_or(if format.has_color() {
            ColorDepth::TrueColor
        } else {
            ColorDepth::None
        });
        if matches!(format, Format::Png | Format::Svg) && args.view.cell_aspect.is_none() {
            opts.cell_aspect = args.cell_px.aspect();
        }
        if matches!(format, Format::Png | Format::Svg) {
            picture::check_size(opts.cols, opts.rows, args.cell_px)?;
        }
    }
    // Everything that can be refused is refused before the work: the
    // frame's size, the files to write, then the scene, and a file to
    // write that the scene is read from.
    opts.check()?;
    let mut output = args.output.as_deref().map(OutFile::create).transpose()?;
    let mut record = args.record.as_deref().map(OutFile::create).transpose()?;
    let scene = scene(&args.input, &args.budgets)?;
    check_outputs(&scene, &[output.as_ref(), record.as_ref()])?;
    let scene = {
        let mut s = scene;
        // A scene file's own poses stand unless a clip or time is asked.
        if (args.input.clip.is_some() || args.time.is_some())
            && let Some(c) = clip(&s, args.input.clip.as_deref())?
        {
            s.set_pose(c, args.time.unwrap_or(0.0));
        }
        let (mut s, view) = with_view(s, &args.view)?;
        // The view as `spin` applies it, where one is asked for (else
        // the camera as it is, to the bit).
        if view != View::AS_GIVEN {
            s.camera = view.apply(&s.camera);
        }
        s
    };
    let mut renderer = Renderer::new();
    let frame = renderer.try_render(&scene, &opts)?;
    let palette = rastty::color::Palette {
        depth: opts.color,
        dither: args.view.dither,
        ..Default::default()
    };
    let start = std::time::Instant::now();
    let mut buf = Vec::new();
    let written = match (&mut output, format) {
        (Some(out), Some(format)) => {
            picture::write(frame, out, format, palette, Theme::default(), args.cell_px)?
        }
        _ => {
            let mut stdout = stdout()?;
            encode::write_lines(frame, palette, args.view.rep(), &mut buf, &mut stdout)
                .and_then(|()| stdout.flush())
                .map_err(stdout_error)?;
            buf.len()
        }
    };
    let record = match record.take() {
        Some(file) => {
            let path = file.path().to_path_buf();
            let mut encoder = Encoder::new(opts.color).with_dither(args.view.dither);
            let rec = Recorder::new(file, opts.cols, opts.rows, &cast::Terminal::from_env())
                .and_then(|mut rec| {
                    encoder.prepare(frame);
                    rec.output(Duration::ZERO, encoder.last_bytes())?;
                    rec.end()?;
                    rec.finish()
                })
                .map_err(|e| rastty::Error::io(&path, e))?;
            Some(rec)
        }
        None => None,
    };
    // The last step: each file written takes its place.
    for file in output.into_iter().chain(record) {
        file.commit()?;
    }
    if args.explain {
        let encode = start.elapsed();
        let mut lines = renderer.explain(&scene, &opts, encode, written);
        lines.push_str(&colour_line(&args.view, palette));
        say_lines(&lines);
    }
    Ok(())
}

/// Refuses files to write that the scene is read from, or that name one
/// file twice.
fn check_outputs(scene: &Scene, outputs: &[Option<&OutFile>]) -> rastty::Result<()> {
    let outputs: Vec<&OutFile> = outputs.iter().flatten().copied().collect();
    for out in &outputs {
        out.check(&scene.sources, &outputs)?;
    }
    Ok(())
}

/// `scene` with the background and camera the view's flags ask for
/// (`--background`, `--fov`, `--target`, `--distance`), and the view
/// `--orbit`, `--zoom` and `--pan` ask for, which `render` applies to the
/// camera and `spin` starts from.
fn with_view(mut scene: Scene, view: &ViewArgs) -> rastty::Result<(Scene, View)> {
    match view.background {
        Some(cli::Background::Terminal) => scene.background = None,
        Some(cli::Background::Color(c)) => scene.background = Some(c),
        None => {}
    }
    let cam = &mut scene.camera;
    if let Some(fov) = view.fov {
        match &mut cam.projection {
            Projection::Perspective { fov_y, .. } => *fov_y = fov,
            _ => {
                return Err(rastty::Error::Invalid(
                    "--fov: the scene's camera is not a perspective one".into(),
                ));
            }
        }
    }
    if let Some(t) = view.target {
        let offset = cam.eye - cam.target;
        cam.target = glam::Vec3::from(t);
        cam.eye = cam.target + offset;
    }
    if let Some(d) = view.distance {
        // A distance of its own: the model is no longer placed to fit.
        let back = (cam.eye - cam.target).normalize_or(glam::Vec3::Z);
        cam.eye = cam.target + back * d;
        cam.fit = None;
        // The far plane well behind the target, however far the eye is.
        if let Projection::Perspective { far, .. } | Projection::Orthographic { far, .. } =
            &mut cam.projection
        {
            *far = far.max(d * 4.0);
        }
    }
    cam.check()
        .map_err(|e| rastty::Error::Invalid(format!("camera: {e}")))?;
    let [yaw, pitch] = view.orbit.unwrap_or([0.0; 2]);
    let mut v = View::AS_GIVEN;
    v.orbit(yaw, pitch);
    if let Some(z) = view.zoom {
        v.distance = 1.0 / z;
    }
    v.shift = glam::Vec2::from(view.pan.unwrap_or([0.0; 2]));
    Ok((scene, v))
}

fn spin(args: &SpinArgs) -> rastty::Result<ExitCode> {
    let opts = options(&args.view, &args.knobs, &args.budgets, 0);
    opts.check()?;
    let record = args.record.as_deref().map(OutFile::create).transpose()?;
    let scene = scene(&args.input, &args.budgets)?;
    check_outputs(&scene, &[record.as_ref()])?;
    let (scene, view) = with_view(scene, &args.view)?;
    let spin = Spin {
        axis: args.axis,
        step: args
            .turn
            .map_or(args.step, |per_second| per_second / args.fps as f32),
        view,
        play: match &args.input.clip {
            Some(named) => clip(&scene, Some(named))?,
            // The scene's own clip (a scene file's), else the first.
            None => scene
                .meshes
                .iter()
                .find_map(|m| m.pose.map(|p| p.clip))
                .or(clip(&scene, None)?),
        }
        .map(|clip| animate::Playback {
            clip,
            speed: args.speed,
            fps: f64::from(args.fps),
        }),
    };
    let dumb = is_dumb();
    let encoder = if dumb {
        Encoder::lines(opts.color).with_dither(args.view.dither)
    } else {
        Encoder::new(opts.color)
            .with_rep(args.view.rep())
            .with_dither(args.view.dither)
    };
    if !terminal::stdout_is_terminal() {
        // Not a terminal: the frames as one deterministic ANSI stream.
        let Some(frames) = args.frames else {
            return Err(rastty::Error::Invalid(
                "spin: stdout is not a terminal; give --frames N to write N frames, or use `rastty render`".into(),
            ));
        };
        if let Some(file) = record {
            // A recording moves the cursor whatever TERM says (its player
            // does) and, as a file for any terminal, has colour unless told.
            let opts = RenderOptions {
                color: args.view.color.depth().unwrap_or(ColorDepth::TrueColor),
                ..opts
            };
            let encoder = Encoder::new(opts.color).with_dither(args.view.dither);
            let path = file.path().to_path_buf();
            let file = Recorder::new(file, opts.cols, opts.rows, &cast::Terminal::from_env())
                .and_then(|mut rec| {
                    cast::play(&scene, &opts, spin, frames, args.fps, encoder, &mut rec)?;
                    rec.finish()
                })
                .map_err(|e| rastty::Error::io(&path, e))?;
            file.commit()?;
            return Ok(ExitCode::SUCCESS);
        }
        let mut out = stdout()?;
        animate::play(&scene, &opts, spin, frames, encoder, &mut out, |_| {})
            .map_err(stdout_error)?;
        return Ok(ExitCode::SUCCESS);
    }
    terminal::install_panic_hook();
    // `c` cycles every depth, truecolor included: the detection reads an
    // environment that tmux and ssh often strip, and the user may know
    // better.
    let max_depth = ColorDepth::TrueColor;
    let mut player = Player::new(scene, opts, spin, encoder).with_hud(args.hud);
    let live_opts = LiveOptions {
        fps: args.fps,
        frames: args.frames,
        probe: !args.no_probe,
        full_screen: !dumb,
        max_depth,
        detect_truecolor: args.view.color == cli::ColorArg::Auto
            && !matches!(opts.color, ColorDepth::None | ColorDepth::TrueColor),
    };
    let mut rec = match record {
        Some(file) => {
            let o = player.options();
            let path = file.path().to_path_buf();
            let rec = Recorder::new(file, o.cols, o.rows, &cast::Terminal::from_env())
                .map_err(|e| rastty::Error::io(&path, e))?;
            Some((rec, path))
        }
        None => None,
    };
    let record = rec.as_mut().map(|(r, _)| r as &mut Recorder<dyn Write>);
    let outcome = live::run(&mut player, &live_opts, record)
        .map_err(|e| rastty::Error::Invalid(format!("spin: {e}")))?;
    // A run ended by a key, its frame count or a signal that quits is a
    // whole recording: it takes its place.
    if let Some((mut rec, path)) = rec {
        rec.end()
            .and_then(|()| rec.finish())
            .map_err(|e| rastty::Error::io(&path, e))?
            .commit()?;
    }
    for m in &outcome.messages {
        say("note", m);
    }
    Ok(match outcome.exit {
        Exit::Quit | Exit::Done => ExitCode::SUCCESS,
        Exit::Signal(sig) => {
            if !matches!(
                sig,
                terminal::sig::INT | terminal::sig::TERM | terminal::sig::HUP | terminal::sig::QUIT
            ) {
                // The terminal is restored: now the signal's own action.
                terminal::die_by(sig);
            }
            ExitCode::from((128 + sig).clamp(0, 255) as u8)
        }
    })
}

/// Whether `TERM` says the terminal cannot move its cursor.
fn is_dumb() -> bool {
    terminal::is_dumb(std::env::var("TERM").ok().as_deref())
}

/// The colour depth `--color auto` gives: the environment's, raised to
/// truecolor inside tmux when tmux says its client's terminal draws it.
fn auto_color(tty: bool) -> (ColorDepth, String) {
    let (env, why) = terminal::detect_color_why(tty, |k| std::env::var(k).ok());
    if matches!(env, ColorDepth::Ansi16 | ColorDepth::Ansi256)
        && terminal::tmux_truecolor() == Some(true)
    {
        return (
            ColorDepth::TrueColor,
            "inside tmux, whose client features list RGB".into(),
        );
    }
    (env, why)
}

/// `--explain`'s line on colour: the depth and why, and how a palette's
/// colours are sent.
fn colour_line(view: &ViewArgs, palette: rastty::color::Palette) -> String {
    let (depth, why) = color_choice(view);
    let mut line = format!("colour: {} ({why})", depth.name());
    if matches!(depth, ColorDepth::Ansi16 | ColorDepth::Ansi256) {
        let q = rastty::color::Quantizer::of(palette);
        line += &format!(
            ", matched in {}, dithering {}",
            q.metric().name(),
            q.dither().name()
        );
    }
    line.push('\n');
    line
}

/// The colour depth `view` asks for, or the detected one, and why.
fn color_choice(view: &ViewArgs) -> (ColorDepth, String) {
    match view.color.depth() {
        Some(depth) => (depth, "--color says so".into()),
        None => auto_color(terminal::stdout_is_terminal()),
    }
}

/// Resolves sizes, glyphs and colour against the terminal; `spare_rows`
/// are left free below the frame (for the shell prompt after `render`).
fn options(
    view: &ViewArgs,
    knobs: &cli::KnobArgs,
    budgets: &cli::BudgetArgs,
    spare_rows: u16,
) -> RenderOptions {
    let tty = terminal::stdout_is_terminal();
    let term = terminal::stdout_size();
    let cells = term.map(|t| t.cells());
    let cols = view
        .cols
        .or(cells.map(|t| t.0))
        .unwrap_or(80)
        .min(rastty::MAX_CELLS);
    let rows = view
        .rows
        .or(cells.map(|t| t.1.saturating_sub(spare_rows).max(1)))
        .unwrap_or(24)
        .min(rastty::MAX_CELLS);
    let color = color_choice(view).0;
    let cell_aspect = view
        .cell_aspect
        .or_else(|| term.and_then(|t| t.cell_aspect()))
        .unwrap_or(0.5);
    let glyphs = view.glyphs.unwrap_or(if is_dumb() && tty {
        GlyphMode::Ascii
    } else {
        GlyphMode::Half
    });
    RenderOptions {
        cols,
        rows,
        glyphs,
        color,
        cell_aspect,
        traversal: knobs.traversal,
        turn: glam::Vec3::new(view.pitch, view.yaw, view.roll),
        // `--yaw`'s axis; spin's loop sets its own.
        turn_axis: rastty::transform::Axis::Y,
        shading: view.shading,
        cull: view.cull,
        pipeline: if knobs.full_pipeline {
            Pipeline::Full
        } else {
            Pipeline::Planned
        },
        wire: view.wire,
        aa: view.aa,
        interpolation: knobs.interpolation,
        highlights: knobs.highlights,
        split: knobs.split,
        precision: knobs.precision,
        filter: view.filter,
        threads: knobs.threads,
        rim: view.rim,
        max_samples: budgets.max_samples.unwrap_or(rastty::DEFAULT_MAX_SAMPLES),
        max_triangles: budgets
            .max_triangles
            .unwrap_or(rastty::scene::DEFAULT_MAX_TRIANGLES),
    }
}
