//! The command line: clap's derive structs. The settings themselves are the
//! library's enums, parsed by their [`Choice`] names through [`named`]; only
//! `--color auto` is the command line's own. Nothing here renders.

use rastty::Choice;
use std::path::PathBuf;

use std::ffi::OsStr;
use std::marker::PhantomData;

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use clap::{Args, Parser, Subcommand, ValueEnum};

use rastty::Shading;
use rastty::Split;
use rastty::color::{ColorSpace, Dither};
use rastty::encode::Rep;
use rastty::picture::CellPx;
use rastty::transform::Axis;
use rastty::{Aa, Highlights, Interpolation, Wire};
use rastty::{GlyphMode, color::ColorDepth, raster::Traversal};
use rastty::{raster::Precision, scene::Cull};

use rastty::MAX_CELLS;
use rastty::scene::Scene;
use std::process::ExitCode;

use crate::say::say_lines;
use rastty::texture::FilterMode;

#[derive(Parser, Debug)]
#[command(
    name = "rastty",
    version,
    about = "The terminal's character grid as a raster display"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
}

impl Cli {
    /// The command bare `rastty` runs: `spin` in a terminal, `render`
    /// otherwise, with every option at its default.
    pub fn default_command() -> Command {
        let sub = if crate::terminal::stdout_is_terminal() {
            "spin"
        } else {
            "render"
        };
        Cli::try_parse_from(["rastty", sub])
            .ok()
            .and_then(|c| c.command)
            .expect("the defaults parse")
    }
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Print one frame of a scene or model to stdout.
    Render(RenderArgs),
    /// Spin a scene or model in the terminal (q quits).
    #[command(after_help = rastty::animate::keys_text())]
    Spin(SpinArgs),
    /// Measure what accuracy costs: every accuracy knob's time per frame
    /// and error, as a Markdown table on stdout and an SVG plot.
    Bench(BenchArgs),
}

#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Where to find models to time (bunny, teapot, fox, shiba-inu,
    /// linux-mascot-tux; those missing are left out with a note) [default:
    /// ../shared/models, or the built-in scenes alone when it is missing]
    #[arg(long, value_name = "DIR")]
    pub models: Option<PathBuf>,
    /// Where to write the plot of error against time. An existing file is
    /// replaced only when the run has succeeded; a device, a pipe or
    /// /dev/stdout is written through
    #[arg(long, value_name = "PATH", default_value = "bench.svg")]
    pub svg: PathBuf,
    /// Frames timed per measurement (the median is reported)
    #[arg(long, value_name = "N", default_value_t = 7, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub reps: u32,
}

#[derive(Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    pub view: ViewArgs,
    #[command(flatten)]
    pub input: InputArgs,
    /// After the frame, print the plan to stderr: each stage, run or
    /// skipped, why, what it did and how long it took
    #[arg(long, help_heading = "Output")]
    pub explain: bool,
    /// For a file manager's preview: each note and error is one line within
    /// --cols characters (the file's name, then what is wrong, cut with …)
    #[arg(long, help_heading = "Output")]
    pub preview: bool,
    /// Write the frame to PATH instead of stdout, in the format its
    /// extension names: .png or .svg (a picture: each cell painted at
    /// --cell-px, no font needed), .ans (the ANSI frame) or .txt (plain
    /// text). --color auto is truecolor for these, none for .txt. An
    /// existing file is replaced only when the run has succeeded (no
    /// --force needed, as with cp); a device, a pipe or /dev/stdout is
    /// written through; a file the model reads is refused
    #[arg(help_heading = "Output", long, short = 'o', value_name = "PATH")]
    pub output: Option<PathBuf>,
    /// Also write the frame as a one-frame asciicast v2 recording, written
    /// as --output is
    #[arg(help_heading = "Output", long, value_name = "FILE.cast")]
    pub record: Option<PathBuf>,
    /// Draw a model that moves at this many seconds into its clip
    /// [default: 0, or a scene file's own]
    #[arg(help_heading = "Model", long, value_name = "SECONDS", allow_negative_numbers = true, value_parser = parse_seconds)]
    pub time: Option<f64>,
    #[command(flatten)]
    pub knobs: KnobArgs,
    #[command(flatten)]
    pub budgets: BudgetArgs,
}

#[derive(Args, Debug, Default)]
pub struct SpinArgs {
    #[command(flatten)]
    pub view: ViewArgs,
    /// The world axis to turn about
    #[arg(long, value_parser = named::<Axis>(), default_value = Axis::Y.name(), help_heading = "Spin")]
    pub axis: Axis,
    /// Degrees turned per frame
    #[arg(help_heading = "Spin", long, value_name = "DEG", default_value_t = 3.0, allow_negative_numbers = true, value_parser = parse_angle)]
    pub step: f32,
    /// Degrees turned per second, whatever the frame rate (0 stands
    /// still); instead of --step
    #[arg(help_heading = "Spin", long, value_name = "DEG/s", allow_negative_numbers = true, value_parser = parse_angle, conflicts_with = "step")]
    pub turn: Option<f32>,
    /// Frames per second
    #[arg(help_heading = "Spin", long, value_name = "N", default_value_t = 30, value_parser = clap::value_parser!(u32).range(1..=240))]
    pub fps: u32,
    /// Stop after N frames (needed when stdout is not a terminal: the frames
    /// are then written as one ANSI stream)
    #[arg(help_heading = "Spin", long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    pub frames: Option<u64>,
    /// Seconds of a moving model's clip played a second (0 holds it at
    /// its start)
    #[arg(help_heading = "Spin", long, value_name = "X", default_value_t = 1.0, allow_negative_numbers = true, value_parser = parse_seconds)]
    pub speed: f64,
    /// Show a status line: fps, link rate, triangles drawn, bytes per
    /// frame, the settings, the angle and the clip's time
    #[arg(help_heading = "Spin", long)]
    pub hud: bool,
    /// Do not ask the terminal which glyphs it draws (by default spin
    /// checks, within 150 ms, and falls back from modes it cannot draw)
    #[arg(help_heading = "Spin", long)]
    pub no_probe: bool,
    #[command(flatten)]
    pub input: InputArgs,
    /// Record the frames as asciicast v2 (asciinema play FILE replays
    /// them): in a terminal, what was shown, when it was shown; otherwise
    /// (with --frames N) frame k at k/fps seconds, and nothing on stdout.
    /// An existing file is replaced only when the run ends well (q, its
    /// frame count, or a signal that quits); a device, a pipe or
    /// /dev/stdout is written through; a file the model reads is refused
    #[arg(long, value_name = "FILE.cast", help_heading = "Output")]
    pub record: Option<PathBuf>,
    #[command(flatten)]
    pub knobs: KnobArgs,
    #[command(flatten)]
    pub budgets: BudgetArgs,
}

/// What is drawn.
#[derive(Args, Debug, Default)]
#[command(next_help_heading = "Model")]
pub struct InputArgs {
    /// A scene file (.toml), a model (.obj with its .mtl, .stl, .gltf,
    /// .glb, .ply, .3mf; told by its first bytes where its name says
    /// nothing) or
    /// a built-in shape (cube, sphere, torus); without it, the built-in
    /// default scene.
    pub scene: Option<PathBuf>,
    /// A model's up axis [default: z for STL and 3MF, y otherwise]
    #[arg(long, value_parser = named::<Axis>())]
    pub up: Option<Axis>,
    /// Faces meeting at a sharper angle keep their own normals along the
    /// edge (computed normals only)
    #[arg(long, value_name = "DEG", default_value_t = rastty::scene::DEFAULT_CREASE, value_parser = parse_crease)]
    pub crease: f32,
    /// How MTL Kd colours are read: linear light (as Blender and most
    /// exporters write them) or sRGB
    #[arg(long, value_parser = named::<ColorSpace>(), default_value = ColorSpace::Linear.name())]
    pub mtl_colors: ColorSpace,
    /// The clip a model that moves plays, by name or number (from 0), or
    /// all: every clip at once, looping at the longest [default: its
    /// first, or a scene file's own]
    #[arg(long, value_name = "NAME|N|all")]
    pub clip: Option<String>,
    /// What metals reflect: a neutral studio, nothing, or an
    /// equirectangular Radiance .hdr image [default: studio]
    #[arg(long, value_name = "none|studio|FILE.hdr", value_parser = parse_environment)]
    pub environment: Option<EnvironmentArg>,
}

/// `--environment`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum EnvironmentArg {
    None,
    Studio,
    File(PathBuf),
}

fn parse_environment(s: &str) -> Result<EnvironmentArg, String> {
    Ok(match s {
        "none" => EnvironmentArg::None,
        "studio" => EnvironmentArg::Studio,
        "" => return Err("an empty name: none, studio or a .hdr file".into()),
        path => EnvironmentArg::File(PathBuf::from(path)),
    })
}

/// The accuracy and speed knobs: each changes how a frame is computed, and
/// is measured by `rastty bench`.
#[derive(Args, Debug, Default)]
#[command(next_help_heading = "Accuracy and speed knobs")]
pub struct KnobArgs {
    /// How the rasterizer walks samples (all give the same picture)
    #[arg(long, value_parser = named::<Traversal>(), default_value = Traversal::Spans.name())]
    pub traversal: Traversal,
    /// How attributes are interpolated (affine is wrong under perspective:
    /// for comparison)
    #[arg(long, value_parser = named::<Interpolation>(), default_value = Interpolation::Perspective.name())]
    pub interpolation: Interpolation,
    /// Where a shining material's highlight is found (vertex dims or loses
    /// highlights smaller than a triangle: for comparison)
    #[arg(long, value_parser = named::<Highlights>(), default_value = Highlights::Sample.name())]
    pub highlights: Highlights,
    /// How cells of more than two colours are split (widest-channel is
    /// chafa's fast path: for comparison)
    #[arg(long, value_parser = named::<Split>(), default_value = Split::Exhaustive.name())]
    pub split: Split,
    /// How edge functions are evaluated (f64 and f32 skip the snap and are
    /// not watertight: for comparison)
    #[arg(long, value_parser = named::<Precision>(), default_value = Precision::Fixed.name())]
    pub precision: Precision,
    /// Run every pipeline stage on every primitive, even those the scene
    /// does not need (the same picture, slower: for comparison)
    #[arg(long)]
    pub full_pipeline: bool,
    /// Threads drawing each frame, a band of rows each (the same picture
    /// with any count): auto uses every core for frames of 600×180 cells
    /// or more, one thread below
    #[arg(long, value_name = "N|auto", default_value = "auto")]
    pub threads: rastty::Threads,
}

/// Budgets: limits on what a file or a frame may cost, refused before the
/// work.
#[derive(Args, Debug, Default)]
#[command(next_help_heading = "Budgets")]
pub struct BudgetArgs {
    /// The largest scene or model file read, in bytes or with a unit (K, M,
    /// G, T: powers of 1024) [default: 1G]
    #[arg(long, value_name = "SIZE", value_parser = parse_size)]
    pub max_file_size: Option<u64>,
    /// The most texels decoded across a scene's images, read from each
    /// image's header and refused before it is decoded (an 8192² image is
    /// 64M) [default: 64M]
    #[arg(long, value_name = "N", value_parser = parse_count)]
    pub max_texels: Option<u64>,
    /// The most triangles a scene may place, each glTF node and scene mesh
    /// counted as often as it is placed, before any is expanded [default:
    /// 256M]
    #[arg(long, value_name = "N", value_parser = parse_count)]
    pub max_triangles: Option<u64>,
    /// The most sample tests a frame may make (cells × samples a cell ×
    /// anti-aliasing passes), refused before any work [default: 64M]
    #[arg(long, value_name = "N", value_parser = parse_count)]
    pub max_samples: Option<u64>,
    /// The largest side of a texture kept: auto, what the frame can show
    /// (render: its samples or pixels, at --zoom, twice over; spin, which
    /// zooms up to 20×: 2048), full (2048), or a number of texels
    /// [default: auto]
    #[arg(long, value_name = "auto|full|N", value_parser = parse_texture_size)]
    pub texture_size: Option<TextureSize>,
}

/// `--texture-size`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TextureSize {
    Auto,
    Full,
    Side(u32),
}

fn parse_texture_size(s: &str) -> Result<TextureSize, String> {
    match s {
        "auto" => Ok(TextureSize::Auto),
        "full" => Ok(TextureSize::Full),
        n => n
            .parse::<u32>()
            .ok()
            .filter(|&n| n >= 1)
            .map(TextureSize::Side)
            .ok_or_else(|| format!("{s:?} is not auto, full or a side in texels (1 or more)")),
    }
}

/// How a frame is laid out and drawn.
#[derive(Args, Debug, Default)]
#[command(next_help_heading = "View")]
pub struct ViewArgs {
    /// Width in cells [default: the terminal's, or 80]
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=MAX_CELLS as i64))]
    pub cols: Option<u16>,
    /// Height in cells [default: the terminal's (less one for render), or 24]
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=MAX_CELLS as i64))]
    pub rows: Option<u16>,
    /// How samples become glyphs (samples per cell: ascii and block 1,
    /// half 2, quadrant 4, sextant 6, octant and braille 8) [default: half,
    /// or ascii when TERM is dumb]
    #[arg(long, value_parser = named::<GlyphMode>())]
    pub glyphs: Option<GlyphMode>,
    /// Paint the cells the scene leaves uncovered #rrggbb (a dark model on
    /// a dark terminal shows against a lighter one), or `terminal` to keep
    /// the terminal's own [default: the scene file's, or the terminal's]
    #[arg(long, value_name = "COLOR", value_parser = parse_background)]
    pub background: Option<Background>,
    /// Outline the model's silhouette with a rim light of #rrggbb, added
    /// where its surface turns away from you: a dark model shows against a
    /// dark background [default: none]
    #[arg(long, value_name = "COLOR", value_parser = parse_rgb)]
    pub rim: Option<rastty::color::Rgb>,
    /// Colour depth; auto reads NO_COLOR, COLORTERM and TERM
    #[arg(long, value_enum, default_value_t = ColorArg::Auto)]
    pub color: ColorArg,
    /// Send runs of identical cells with REP (CSI n b), for terminals that
    /// have it
    #[arg(long)]
    pub rep: bool,
    /// Draw real pixels where the terminal shows images: the kitty graphics
    /// protocol, sixel or iTerm2's inline images; auto picks the best the
    /// terminal answers for, cells where none answers (or stdout is not a
    /// terminal)
    #[arg(long, value_enum, default_value_t = GraphicsArg::Auto)]
    pub graphics: GraphicsArg,
    /// Pixels of one cell, W×H (or WxH): of pixel graphics (--graphics;
    /// default: as the terminal says, else 10×20, said on stderr), and of
    /// .png and .svg pictures of cells (default 8×16)
    #[arg(long, value_name = "W×H", visible_alias = "cell-px")]
    pub cell_size: Option<CellPx>,
    /// A cell's width over its height [default: the terminal's, or 0.5]
    #[arg(long, value_name = "R", value_parser = parse_aspect)]
    pub cell_aspect: Option<f32>,
    /// Draw colours between palette entries as patterns of entries (auto:
    /// ordered in 16 and 256 colours; none sends each colour's nearest)
    #[arg(long, value_parser = named::<Dither>(), default_value = Dither::Auto.name())]
    pub dither: Dither,
    /// How surfaces are lit (by the scene's lights)
    #[arg(long, value_parser = named::<Shading>(), default_value = Shading::Smooth.name())]
    pub shading: Shading,
    /// Which faces to discard [default: back faces of meshes, none of loose
    /// triangles]
    #[arg(long, value_parser = named::<Cull>())]
    pub cull: Option<Cull>,
    /// Draw the faces, their edges as lines one sample wide (every edge),
    /// or the faces with their edges in black (edges behind a face hidden)
    #[arg(long, value_parser = named::<Wire>(), default_value = Wire::Solid.name())]
    pub wire: Wire,
    /// Turn the scene about the world's y axis, in degrees
    #[arg(long, value_name = "DEG", default_value_t = 0.0, allow_negative_numbers = true, value_parser = parse_angle)]
    pub yaw: f32,
    /// Turn the scene about the world's x axis, in degrees
    #[arg(long, value_name = "DEG", default_value_t = 0.0, allow_negative_numbers = true, value_parser = parse_angle)]
    pub pitch: f32,
    /// Turn the scene about the world's z axis, in degrees
    #[arg(long, value_name = "DEG", default_value_t = 0.0, allow_negative_numbers = true, value_parser = parse_angle)]
    pub roll: f32,
    /// Move the eye around its target: degrees of yaw (about the camera's
    /// up axis) and pitch (towards it, within ±85), as a drag or the
    /// arrows do in spin [default: 0,0]
    #[arg(long, value_name = "YAW,PITCH", allow_hyphen_values = true, value_parser = parse_orbit, help_heading = "Camera")]
    pub orbit: Option<[f32; 2]>,
    /// Draw the scene X times larger, the eye brought nearer its target
    /// (0.05 to 20), as the wheel and + / - do in spin [default: 1]
    #[arg(long, value_name = "X", value_parser = parse_zoom, help_heading = "Camera")]
    pub zoom: Option<f32>,
    /// Move the picture by X,Y view heights (right, up), as a right-drag
    /// does in spin [default: 0,0]
    #[arg(long, value_name = "X,Y", allow_hyphen_values = true, value_parser = parse_pair, help_heading = "Camera")]
    pub pan: Option<[f32; 2]>,
    /// The point the eye looks at and orbits, X,Y,Z in the scene's units
    /// [default: the scene file's target, or the model's centre]
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true, value_parser = parse_point, help_heading = "Camera")]
    pub target: Option<[f32; 3]>,
    /// The eye's distance from its target, in the scene's units (a model
    /// shown alone is scaled into a sphere of radius 1, and otherwise
    /// placed so that it fits the view)
    #[arg(long, value_name = "D", value_parser = parse_distance, help_heading = "Camera")]
    pub distance: Option<f32>,
    /// The camera's vertical field of view, in degrees (a perspective
    /// camera's) [default: the scene file's, or 45]
    #[arg(long, value_name = "DEG", value_parser = parse_fov, help_heading = "Camera")]
    pub fov: Option<f32>,
    /// Anti-aliasing: 4 or 16 sub-samples per sample, or each triangle's
    /// exact area in the sample's square
    #[arg(long, value_parser = named::<Aa>(), default_value = Aa::None.name())]
    pub aa: Aa,
    /// Texture filtering for every texture (default: as each model's
    /// sampler says; trilinear where it says nothing)
    #[arg(long, value_parser = named::<FilterMode>())]
    pub filter: Option<FilterMode>,
}

impl ViewArgs {
    pub fn rep(&self) -> Rep {
        if self.rep { Rep::On } else { Rep::Off }
    }
}

/// `--graphics`: pixels in a protocol, character cells, or the best the
/// terminal has.
#[derive(ValueEnum, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum GraphicsArg {
    #[default]
    Auto,
    /// Character cells (--glyphs), whatever the terminal shows
    Cells,
    /// The kitty graphics protocol (kitty, Ghostty, WezTerm, Konsole)
    Kitty,
    /// Sixel (foot, WezTerm, xterm -ti vt340, Konsole, Windows Terminal)
    Sixel,
    /// iTerm2's inline images (iTerm2, WezTerm, VS Code)
    Iterm,
}

impl GraphicsArg {
    /// The protocol asked for by name (`None`: auto or cells).
    pub fn protocol(self) -> Option<rastty::graphics::Protocol> {
        use rastty::graphics::Protocol;
        match self {
            GraphicsArg::Kitty => Some(Protocol::Kitty),
            GraphicsArg::Sixel => Some(Protocol::Sixel),
            GraphicsArg::Iterm => Some(Protocol::Iterm),
            GraphicsArg::Auto | GraphicsArg::Cells => None,
        }
    }
}

#[derive(ValueEnum, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ColorArg {
    #[default]
    Auto,
    None,
    #[value(name = "16")]
    Ansi16,
    #[value(name = "256")]
    Ansi256,
    /// 24-bit colour (also `24bit`, `direct`, as `COLORTERM` and terminfo
    /// call it)
    #[value(alias = "24bit", alias = "direct")]
    Truecolor,
}

impl ColorArg {
    /// The explicit depth, or `None` for auto.
    pub fn depth(self) -> Option<ColorDepth> {
        match self {
            ColorArg::Auto => None,
            ColorArg::None => Some(ColorDepth::None),
            ColorArg::Ansi16 => Some(ColorDepth::Ansi16),
            ColorArg::Ansi256 => Some(ColorDepth::Ansi256),
            ColorArg::Truecolor => Some(ColorDepth::TrueColor),
        }
    }
}

fn parse_angle(s: &str) -> Result<f32, String> {
    parse_finite(s, "angle")
}

/// A finite number (of seconds, or a speed).
fn parse_seconds(s: &str) -> Result<f64, String> {
    parse_finite(s, "number")
}

/// A number that is finite; `what` names it in the message.
fn parse_finite<T: std::str::FromStr + Into<f64> + Copy>(s: &str, what: &str) -> Result<T, String> {
    let x: T = s.parse().map_err(|_| format!("{s:?} is not a number"))?;
    if x.into().is_finite() {
        Ok(x)
    } else {
        Err(format!("{s} is not a finite {what}"))
    }
}

/// A size in bytes: digits with an optional unit K, M, G or T (powers of
/// 1024; `KiB`, `kb` and the like are read the same).
fn parse_size(s: &str) -> Result<u64, String> {
    let units = [
        ("", 0),
        ("b", 0),
        ("k", 10),
        ("kb", 10),
        ("kib", 10),
        ("m", 20),
        ("mb", 20),
        ("mib", 20),
        ("g", 30),
        ("gb", 30),
        ("gib", 30),
        ("t", 40),
        ("tb", 40),
        ("tib", 40),
    ];
    parse_scaled(s, &units, "a size (like 4096, 512M or 4G)")
}

/// What `--background` asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Background {
    /// The terminal's own background.
    Terminal,
    /// This colour.
    Color(rastty::color::Rgb),
}

fn parse_background(s: &str) -> Result<Background, String> {
    if s == "terminal" {
        return Ok(Background::Terminal);
    }
    s.parse()
        .map(Background::Color)
        .map_err(|_| format!("{s:?} is not a colour: #rrggbb, or `terminal`"))
}

fn parse_rgb(s: &str) -> Result<rastty::color::Rgb, String> {
    s.parse()
        .map_err(|_| format!("{s:?} is not a colour: #rrggbb"))
}

/// A count, plain or with K, M or G (powers of 1024: 64M is 2^26).
fn parse_count(s: &str) -> Result<u64, String> {
    let units = [("", 0), ("k", 10), ("m", 20), ("g", 30)];
    parse_scaled(s, &units, "a count (like 1000000, 64M or 1G)")
}

/// A number followed by one of `units` (case aside), each a power of two.
fn parse_scaled(s: &str, units: &[(&str, u32)], what: &str) -> Result<u64, String> {
    let t = s.trim();
    let digits = t.bytes().take_while(u8::is_ascii_digit).count();
    let (number, unit) = t.split_at(digits);
    let unit = unit.trim().to_ascii_lowercase();
    let shift = units
        .iter()
        .find(|(u, _)| *u == unit)
        .map(|&(_, shift)| shift)
        .ok_or_else(|| format!("{s:?} is not {what}"))?;
    let n: u64 = number.parse().map_err(|_| format!("{s:?} is not {what}"))?;
    n.checked_mul(1 << shift)
        .ok_or_else(|| format!("{s} is too large"))
}

fn parse_crease(s: &str) -> Result<f32, String> {
    let d: f32 = s.parse().map_err(|_| format!("{s:?} is not a number"))?;
    if (0.0..=180.0).contains(&d) {
        Ok(d)
    } else {
        Err(format!("{s} is not between 0 and 180"))
    }
}

/// Comma-separated finite numbers, exactly `N` of them.
fn parse_numbers<const N: usize>(s: &str, what: &str) -> Result<[f32; N], String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    if parts.len() != N {
        return Err(format!("{s:?} is not {what}"));
    }
    let mut out = [0.0; N];
    for (o, p) in out.iter_mut().zip(parts) {
        *o = p
            .parse::<f32>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| format!("{p:?} in {s:?} is not a finite number"))?;
    }
    Ok(out)
}

fn parse_orbit(s: &str) -> Result<[f32; 2], String> {
    parse_numbers(s, "YAW,PITCH (two angles in degrees, as 30,-10)")
}

fn parse_pair(s: &str) -> Result<[f32; 2], String> {
    parse_numbers(s, "X,Y (two numbers, as 0.1,-0.2)")
}

fn parse_point(s: &str) -> Result<[f32; 3], String> {
    parse_numbers(s, "X,Y,Z (three numbers, as 0,1.5,0)")
}

fn parse_zoom(s: &str) -> Result<f32, String> {
    let z: f32 = parse_finite(s, "zoom")?;
    let (lo, hi) = rastty::scene::View::DISTANCE;
    if (lo..=hi).contains(&z) {
        Ok(z)
    } else {
        Err(format!("{s} is not between {lo} and {hi}"))
    }
}

fn parse_distance(s: &str) -> Result<f32, String> {
    let d: f32 = parse_finite(s, "distance")?;
    if d > 0.0 {
        Ok(d)
    } else {
        Err(format!("{s} is not a distance above 0"))
    }
}

fn parse_fov(s: &str) -> Result<f32, String> {
    let f: f32 = parse_finite(s, "angle")?;
    if f > 0.0 && f < 180.0 {
        Ok(f)
    } else {
        Err(format!("{s} is not between 0 and 180 degrees"))
    }
}

fn parse_aspect(s: &str) -> Result<f32, String> {
    let r: f32 = s.parse().map_err(|_| format!("{s:?} is not a number"))?;
    if r.is_finite() && (0.05..=20.0).contains(&r) {
        Ok(r)
    } else {
        Err(format!("{s} is not between 0.05 and 20"))
    }
}

/// A clap parser for one of the library's settings ([`Choice`]): its names,
/// each with its one line of help, listed in `--help` and in the error for
/// a name that is not one of them.
#[derive(Clone, Copy, Debug)]
pub struct Named<T>(PhantomData<T>);

/// The parser of setting `T`'s names.
pub fn named<T>() -> Named<T> {
    Named(PhantomData)
}

impl<T: Choice + Send + Sync> Named<T> {
    fn values() -> impl Iterator<Item = PossibleValue> {
        T::ALL
            .iter()
            .map(|v| PossibleValue::new(v.name()).help(v.about()))
    }
}

impl<T: Choice + Send + Sync> TypedValueParser for Named<T> {
    type Value = T;

    fn parse_ref(
        &self,
        cmd: &clap::Command,
        arg: Option<&clap::Arg>,
        value: &OsStr,
    ) -> Result<T, clap::Error> {
        let name = PossibleValuesParser::new(Self::values()).parse_ref(cmd, arg, value)?;
        // The parser above accepts only the names of `T::ALL`.
        T::ALL
            .iter()
            .copied()
            .find(|v| v.name() == name)
            .ok_or_else(|| clap::Error::new(clap::error::ErrorKind::InvalidValue).with_cmd(cmd))
    }

    fn possible_values(&self) -> Option<Box<dyn Iterator<Item = PossibleValue> + '_>> {
        Some(Box::new(Self::values()))
    }
}

/// `--help` and `--version` print as clap has them; a usage error prints
/// clap's message (with the possible values, and a suggestion where one is
/// close) and exits with 2. A model or scene named where a command belongs
/// (`rastty bunny.obj`) gets the command that shows it.
pub fn usage_error(e: clap::Error) -> ExitCode {
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
