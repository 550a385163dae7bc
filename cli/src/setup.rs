//! What `render` and `spin` share: the scene read and said, the clip
//! chosen, the camera and view the flags ask for, the frame's options and
//! colours resolved against the terminal, and the files to write checked
//! against the scene.

use rastty::Choice;

use crate::cli::{self, ViewArgs};
use crate::say::say;
use crate::terminal;
use rastty::outfile::OutFile;
use rastty::scene::environment::Environment;
use rastty::scene::{Projection, Scene, View};
use rastty::{GlyphMode, Pipeline, RenderOptions, color::ColorDepth};

/// The scene to draw; what the loaders read but cannot draw is said on
/// stderr. `frame` is the frame a still is drawn at (its samples, and how
/// many times the view is zoomed in), which bounds the textures kept
/// (`--texture-size auto`); `None` for `spin`, which zooms up to 20×.
pub fn scene(
    input: &cli::InputArgs,
    budgets: &cli::BudgetArgs,
    frame: Option<((u32, u32), f32)>,
) -> rastty::Result<Scene> {
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
    options.max_texture_side = match (budgets.texture_size, frame) {
        (Some(cli::TextureSize::Side(n)), _) => n.min(rastty::texture::MAX_SIDE),
        (Some(cli::TextureSize::Full), _) | (_, None) => rastty::texture::MAX_SIDE,
        (_, Some((samples, zoom))) => rastty::scene::texture_side_for(samples, zoom),
    };
    let mut scene = match &input.scene {
        Some(p) => Scene::open_within(p, &options)?,
        None => rastty::scene::default_scene(),
    };
    match &input.environment {
        None => {}
        Some(cli::EnvironmentArg::None) => scene.environment = Environment::None,
        Some(cli::EnvironmentArg::Studio) => scene.environment = Environment::Studio,
        #[cfg(feature = "textures")]
        Some(cli::EnvironmentArg::File(p)) => {
            let (environment, source) = rastty::scene::environment::load(p, &options)?;
            scene.environment = environment;
            scene.sources.push(source);
        }
        #[cfg(not(feature = "textures"))]
        Some(cli::EnvironmentArg::File(p)) => {
            return Err(rastty::Error::Invalid(format!(
                "--environment {}: built without the textures feature, which reads images",
                rastty::text::name(&p.display().to_string(), 80)
            )));
        }
    }
    for note in &scene.notes {
        say("note", note);
    }
    Ok(scene)
}

/// The clip `--clip` names (a number from 0, or a name), the first by
/// default; `None` when no model moves.
pub fn clip(scene: &mut Scene, named: Option<&str>) -> rastty::Result<Option<usize>> {
    if named == Some("all") && !scene.clips().is_empty() {
        return Ok(scene.add_all_clips());
    }
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

/// Refuses files to write that the scene is read from, or that name one
/// file twice.
pub fn check_outputs(scene: &Scene, outputs: &[Option<&OutFile>]) -> rastty::Result<()> {
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
pub fn with_view(mut scene: Scene, view: &ViewArgs) -> rastty::Result<(Scene, View)> {
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

/// Whether `TERM` says the terminal cannot move its cursor.
pub fn is_dumb() -> bool {
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
pub fn colour_line(view: &ViewArgs, palette: rastty::color::Palette) -> String {
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
pub fn options(
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
        // Pixels are `--graphics`'s, chosen where the terminal is known.
        cell_pixels: None,
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

/// glibc's malloc raises its mmap threshold to the size of each large
/// block freed (up to 32 MiB): after the loader frees its connectivity
/// tables, blocks that large come from the heap, and stay resident when
/// freed. A fixed threshold (its default, 128 KiB) keeps every large block
/// mapped and given back when freed: the frame's vertex buffers then
/// reuse memory the loader returned rather than lying beside it (the
/// peak memory of docs/figures.md's loading rows).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
pub fn keep_large_blocks_mapped() {
    // SAFETY: mallopt only sets a parameter of the allocator; called
    // first thing in main, before any other thread exists.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 128 * 1024);
    }
}

#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
pub fn keep_large_blocks_mapped() {}
