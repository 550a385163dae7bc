//! `rastty render`: one frame of a scene, to stdout or a file, and a
//! recording of it; `--explain`'s report.

use std::io::Write;
use std::time::Duration;

use crate::cli::RenderArgs;
use crate::pixels::{self, Graphics};
use crate::say::{say, say_lines, stdout, stdout_error};
use crate::setup::{check_outputs, clip, colour_line, options, scene, with_view};
use crate::terminal::{self, probe::Capabilities};
use rastty::cast::{self, Recorder};
use rastty::encode::{self, Encoder};
use rastty::outfile::OutFile;
use rastty::picture::{self, Format, Theme};
use rastty::scene::View;
use rastty::{Choice, Renderer, color::ColorDepth};

/// The scene `args` ask for, posed and viewed as they say.
fn posed_scene(
    args: &RenderArgs,
    scene: rastty::scene::Scene,
) -> rastty::Result<rastty::scene::Scene> {
    let mut s = scene;
    // A scene file's own poses stand unless a clip or time is asked.
    if (args.input.clip.is_some() || args.time.is_some())
        && let Some(c) = clip(&mut s, args.input.clip.as_deref())?
    {
        s.set_pose(c, args.time.unwrap_or(0.0));
    }
    let (mut s, view) = with_view(s, &args.view)?;
    // The view as `spin` applies it, where one is asked for (else the
    // camera as it is, to the bit).
    if view != View::AS_GIVEN {
        s.camera = view.apply(&s.camera);
    }
    Ok(s)
}

/// One frame as pixels in `g`'s protocol, to stdout (or an `.ans` file),
/// or the pixels themselves as a `.png`.
fn render_pixels(args: &RenderArgs, format: Option<Format>, g: Graphics) -> rastty::Result<()> {
    use rastty::graphics::{Protocol, iterm, kitty, sixel};
    if !matches!(format, None | Some(Format::Png | Format::Ans)) {
        return Err(rastty::Error::Invalid(
            "--graphics: pixels are written to stdout, as .png (the pixels) or as .ans (the terminal's bytes); --graphics cells draws character cells".into(),
        ));
    }
    if args.record.is_some() {
        return Err(rastty::Error::Invalid(
            "--record: a recording holds character cells; add --graphics cells".into(),
        ));
    }
    let mut opts = options(&args.view, &args.knobs, &args.budgets, 1);
    opts.cell_pixels = Some(g.cell);
    opts.check()?;
    let mut output = args.output.as_deref().map(OutFile::create).transpose()?;
    let scene = scene(&args.input, &args.budgets, still_frame(&opts, &args.view))?;
    check_outputs(&scene, &[output.as_ref()])?;
    let scene = posed_scene(args, scene)?;
    let mut renderer = Renderer::new();
    let mut px = rastty::Pixels::new();
    renderer.try_render_pixels(&scene, &opts, &mut px)?;
    let start = std::time::Instant::now();
    let mut bytes = Vec::new();
    if format == Some(Format::Png) {
        bytes = iterm::png_of(&px)?;
    } else {
        match g.protocol {
            Protocol::Kitty => kitty::still(&px, opts.cols, opts.rows, &mut bytes),
            Protocol::Sixel => sixel::Encoder::new(g.registers).encode(&px, &mut bytes),
            Protocol::Iterm => iterm::still(&px, opts.cols, opts.rows, &mut bytes)?,
        }
        bytes.push(b'\n');
    }
    match &mut output {
        Some(out) => out
            .write_all(&bytes)
            .map_err(|e| rastty::Error::io(out.path(), e))?,
        None => {
            let mut stdout = stdout()?;
            stdout
                .write_all(&bytes)
                .and_then(|()| stdout.flush())
                .map_err(stdout_error)?;
        }
    }
    if let Some(file) = output {
        file.commit()?;
    }
    if args.explain {
        let mut lines = renderer.explain(&scene, &opts, start.elapsed(), bytes.len());
        lines.push_str(&format!(
            "output: {} pixels ({}×{}, cells of {}×{})\n",
            g.protocol.name(),
            px.width(),
            px.height(),
            g.cell[0],
            g.cell[1]
        ));
        say_lines(&lines);
    }
    Ok(())
}

/// Draws the frame `args` ask for and writes it where they say.
pub fn render(args: &RenderArgs) -> rastty::Result<()> {
    let format = args.output.as_deref().map(Format::of).transpose()?;
    // Pixels where asked by name, or (auto) where stdout is a terminal
    // that shows them; a picture file of cells stays one.
    let tty = format.is_none() && terminal::stdout_is_terminal();
    let choice = pixels::choose(
        args.view.graphics,
        args.view.cell_size,
        tty,
        &|k| std::env::var(k).ok(),
        terminal::stdout_size(),
        &Capabilities::default(),
    );
    if let Some(g) = choice.graphics {
        for note in &choice.notes {
            say("note", note);
        }
        return render_pixels(args, format, g);
    }
    let mut opts = options(&args.view, &args.knobs, &args.budgets, 1);
    if let Some(format) = format {
        // A file is not the terminal: sizes and colours are its own.
        opts.color = args.view.color.depth().unwrap_or(if format.has_color() {
            ColorDepth::TrueColor
        } else {
            ColorDepth::None
        });
        if matches!(format, Format::Png | Format::Svg) && args.view.cell_aspect.is_none() {
            opts.cell_aspect = args.view.cell_size.unwrap_or_default().aspect();
        }
        if matches!(format, Format::Png | Format::Svg) {
            picture::check_size(
                opts.cols,
                opts.rows,
                args.view.cell_size.unwrap_or_default(),
            )?;
        }
    }
    // Everything that can be refused is refused before the work: the
    // frame's size, the files to write, then the scene, and a file to
    // write that the scene is read from.
    opts.check()?;
    let mut output = args.output.as_deref().map(OutFile::create).transpose()?;
    let mut record = args.record.as_deref().map(OutFile::create).transpose()?;
    let scene = scene(&args.input, &args.budgets, still_frame(&opts, &args.view))?;
    check_outputs(&scene, &[output.as_ref(), record.as_ref()])?;
    let scene = posed_scene(args, scene)?;
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
        (Some(out), Some(format)) => picture::write(
            frame,
            out,
            format,
            palette,
            Theme::default(),
            args.view.cell_size.unwrap_or_default(),
        )?,
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

/// The frame a still is drawn at, for the textures it can show: its
/// samples (pixels in the pixel mode) and how far `--zoom` brings it in.
fn still_frame(
    opts: &rastty::RenderOptions,
    view: &crate::cli::ViewArgs,
) -> Option<((u32, u32), f32)> {
    let grid = opts.grid();
    Some(((grid.width, grid.height), view.zoom.unwrap_or(1.0)))
}
