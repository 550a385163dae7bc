//! `rastty spin`: a scene turning in the terminal ([`crate::live`]), or,
//! when stdout is not one, its frames as one ANSI stream or a recording.

use std::io::Write;
use std::process::ExitCode;

use crate::cli::{self, SpinArgs};
use crate::live::{self, Exit, LiveOptions};
use crate::say::{say, stdout, stdout_error};
use crate::setup::{check_outputs, clip, is_dumb, options, scene, with_view};
use crate::terminal;
use rastty::animate::{self, Player, Spin};
use rastty::cast::{self, Recorder};
use rastty::encode::Encoder;
use rastty::outfile::OutFile;
use rastty::{RenderOptions, color::ColorDepth};

/// Spins the scene `args` ask for; the exit code says how it ended.
pub fn spin(args: &SpinArgs) -> rastty::Result<ExitCode> {
    let opts = options(&args.view, &args.knobs, &args.budgets, 0);
    opts.check()?;
    let record = args.record.as_deref().map(OutFile::create).transpose()?;
    let scene = scene(&args.input, &args.budgets, None)?;
    check_outputs(&scene, &[record.as_ref()])?;
    let (mut scene, view) = with_view(scene, &args.view)?;
    let spin = Spin {
        axis: args.axis,
        step: args
            .turn
            .map_or(args.step, |per_second| per_second / args.fps as f32),
        view,
        play: match &args.input.clip {
            Some(named) => clip(&mut scene, Some(named))?,
            // The scene's own clip (a scene file's), else the first.
            None => scene
                .meshes
                .iter()
                .find_map(|m| m.pose.map(|p| p.clip))
                .or(clip(&mut scene, None)?),
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
        // Pixels by name: frame k in the protocol, as a terminal gets it.
        let choice = crate::pixels::choose(
            args.view.graphics,
            args.view.cell_size,
            false,
            &|k| std::env::var(k).ok(),
            None,
            &terminal::probe::Capabilities::default(),
        );
        if let Some(g) = choice.graphics {
            for note in &choice.notes {
                say("note", note);
            }
            let mut player = Player::new(scene, opts, spin, encoder);
            player.set_graphics(g.protocol, g.cell, g.registers, g.background);
            for _ in 0..frames {
                player
                    .show(&mut out, animate::LiveStatus::default())
                    .map_err(stdout_error)?;
                player.advance(1);
            }
            let mut bye = Vec::new();
            player.goodbye(&mut bye);
            out.write_all(&bye).map_err(stdout_error)?;
            return Ok(ExitCode::SUCCESS);
        }
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
        graphics: args.view.graphics,
        cell_size: args.view.cell_size,
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
