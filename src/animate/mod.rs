//! The animation loop's core, without a terminal: a scene turning about an
//! axis, frame `k` turned by `k · step` degrees, each frame rendered and
//! sent through the diffing encoder to any `io::Write`.
//!
//! A [`Player`] holds everything that changes while a scene spins (the
//! frame number, the view, the settings the keys cycle through) and reacts
//! to [`Command`]s; it knows nothing of clocks, keys or mice (a drag comes
//! as cells moved, turned into angles by [`crate::scene::View::drag`]).
//! `rastty spin` drives it from the terminal (the CLI's `live` loop: a
//! clock, keys, mouse reports, signals and resizes); tests and the
//! byte-count table drive it headless ([`play`]), so that what they
//! measure is exactly what a terminal receives. What it writes over the
//! frame (the status line, a notice, the help box) is `hud.rs`'s.

use crate::choice::Choice;
use std::io::{self, Write};

use glam::Vec3;

use crate::blit::GlyphMode;
use crate::color::ColorDepth;
use crate::encode::Encoder;
use crate::options::{RenderOptions, Wire};
use crate::render::Renderer;
use crate::scene::{Camera, Scene, View};
use crate::shade::Shading;

use crate::transform::Axis;

mod hud;
#[cfg(feature = "graphics")]
mod pixels;

/// A turn of `step` degrees per frame about `axis`, and a clip played
/// meanwhile.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spin {
    /// The axis turned about.
    pub axis: Axis,
    /// Degrees per frame.
    pub step: f32,
    /// The clip the scene's moving models play, if any.
    pub play: Option<Playback>,
    /// Where the viewer starts (and `r` goes back to): orbit, zoom, pan.
    pub view: View,
}

/// A clip played frame by frame: frame `k` shows the clip at
/// `k / fps · speed` seconds (wrapped into the clip as it loops).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Playback {
    /// The clip, an index into the moving models' clips.
    pub clip: usize,
    /// Seconds of the clip a second of frames shows (1: as recorded).
    pub speed: f64,
    /// Frames a second.
    pub fps: f64,
}

impl Playback {
    /// The clip's time at frame `k`.
    pub fn time(&self, k: u64) -> f64 {
        k as f64 / self.fps * self.speed
    }
}

impl Spin {
    /// The turn (degrees about x, y, z; see [`RenderOptions::turn`]) of frame
    /// `k`, starting from `base`. The angle is reduced modulo 360 in f64 so
    /// that it stays exact however long the loop runs.
    pub fn turn(&self, base: Vec3, k: u64) -> Vec3 {
        let angle = (k as f64 * self.step as f64).rem_euclid(360.0) as f32;
        base + self.axis.unit() * angle
    }
}

/// The keys and mouse gestures `spin` knows, and what each does: one list
/// for the help box (`?`), `rastty spin --help` and the README's table
/// (a test holds the README to it).
pub const KEYS: &[(&str, &str)] = &[
    ("q, Esc, Ctrl-C", "quit"),
    ("space", "pause (the turn and the clip)"),
    ("t", "stop turning, or turn again (the clip plays on)"),
    ("drag", "orbit: the model follows the pointer"),
    (
        "right- or shift-drag",
        "pan: the picture follows the pointer",
    ),
    ("wheel", "zoom in / out"),
    ("arrows", "orbit the camera around its target"),
    ("+ / -", "zoom in / out"),
    (
        "r, double-click",
        "reset the view (orbit, zoom, pan and turn)",
    ),
    ("[ / ]", "previous / next clip of a model that moves"),
    (
        "m",
        "next glyph mode (skipping those the terminal cannot draw)",
    ),
    ("c", "next colour depth (truecolor included)"),
    ("s", "next shading"),
    ("w", "next of solid, wireframe lines, solid with edges"),
    ("?", "show or hide these keys"),
    ("Ctrl-L", "redraw"),
    ("Ctrl-Z", "suspend (fg resumes)"),
];

/// [`KEYS`] as lines of text, the keys in a column: `spin --help`'s list.
pub fn keys_text() -> String {
    let width = KEYS
        .iter()
        .map(|(k, _)| k.chars().count())
        .max()
        .unwrap_or(0);
    // Padded by hand, not by `format!`: `spin --help` is built whenever any
    // command's arguments are parsed, and `format!`'s padding is a
    // noticeable share of a command as small as `render cube`.
    let mut out = String::with_capacity(1024);
    out.push_str("Keys and mouse:");
    for (k, what) in KEYS {
        out.push_str("\n  ");
        out.push_str(k);
        out.extend(std::iter::repeat_n(' ', width - k.chars().count() + 3));
        out.push_str(what);
    }
    out
}

/// What a key (or the terminal) asks of a running animation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Command {
    /// End the animation.
    Quit,
    /// Stop turning and playing, or go on.
    TogglePause,
    /// Stop turning (the clip plays on), or turn again.
    ToggleTurn,
    /// Play the next clip (or the previous, with `-1`), from its start.
    Clip(i8),
    /// Move the eye around the target: degrees of yaw and pitch.
    Orbit {
        /// Degrees about the up axis.
        yaw: f32,
        /// Degrees towards the up axis.
        pitch: f32,
    },
    /// Multiply the eye's distance from the target.
    Zoom(f32),
    /// Draw with the next glyph mode.
    NextGlyphs,
    /// Send colours at the next colour depth.
    NextColor,
    /// Shade with the next shading.
    NextShading,
    /// Draw the next of faces, lines, faces with edges ([`crate::Wire`]).
    NextWire,
    /// The terminal's new size in cells.
    Resize {
        /// Columns.
        cols: u16,
        /// Rows.
        rows: u16,
    },
    /// Send the next frame in full.
    Redraw,
    /// A drag of the mouse by `cells` (columns right, rows down): the eye
    /// turned around the target, or with `pan` the picture moved (see
    /// [`View::drag`]).
    Drag {
        /// How far, in cells.
        cells: glam::Vec2,
        /// Move the picture instead of turning the eye.
        pan: bool,
    },
    /// Put the view back where it started (orbit, zoom, pan and the turn).
    Reset,
    /// Show the keys over the frame, or stop showing them.
    ToggleHelp,
}

/// What the live loop knows that the player does not: the measured frame
/// rate and the link's drain rate, for the status line.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LiveStatus {
    /// Frames shown per second, measured.
    pub fps: f32,
    /// Bytes per second the terminal drains, measured (`None`: not known).
    pub link: Option<f64>,
}

/// A spinning scene and everything that changes while it spins.
#[derive(Debug)]
pub struct Player {
    scene: Scene,
    base: Camera,
    opts: RenderOptions,
    spin: Spin,
    /// Frames played while not paused.
    k: u64,
    /// Frames turned: the angle's frame number.
    turned: u64,
    /// Frames of the clip played.
    played: u64,
    paused: bool,
    turning: bool,
    /// The status line's parts, highest priority first (reused buffers).
    hud_parts: [String; 10],
    /// How the viewer has moved the view, and where `r` puts it back.
    view: View,
    start: View,
    hud: bool,
    /// Whether the help box is shown over the frame.
    help: bool,
    renderer: Renderer,
    encoder: Encoder,
    last_bytes: usize,
    status: String,
    /// Which glyph modes `m` may pick (in [`Choice::ALL`] order).
    usable: [bool; 7],
    /// The deepest colour `c` may pick.
    max_depth: ColorDepth,
    /// A short message over the last row, and a number that changes with
    /// every new one (so that a loop can time how long it has shown).
    notice: Option<String>,
    notice_serial: u64,
    /// The clip the status line names, and how (escaped once, not each
    /// frame).
    clip_label: Option<(usize, String)>,
    /// Where frames go as pixels, when they do.
    #[cfg(feature = "graphics")]
    screen: Option<pixels::Screen>,
}

impl Player {
    /// A player of `scene` drawn with `opts`, turned by `spin` each frame and
    /// sent through `encoder`.
    pub fn new(scene: Scene, opts: RenderOptions, spin: Spin, encoder: Encoder) -> Player {
        Player {
            base: scene.camera,
            scene,
            opts,
            spin,
            k: 0,
            turned: 0,
            played: 0,
            paused: false,
            turning: true,
            hud_parts: Default::default(),
            view: spin.view,
            start: spin.view,
            hud: false,
            help: false,
            renderer: Renderer::new(),
            encoder,
            last_bytes: 0,
            status: String::new(),
            usable: [true; 7],
            max_depth: ColorDepth::TrueColor,
            notice: None,
            notice_serial: 0,
            clip_label: None,
            #[cfg(feature = "graphics")]
            screen: None,
        }
    }

    /// Shows a status line over the frame's last row.
    pub fn with_hud(mut self, on: bool) -> Player {
        self.hud = on;
        self
    }

    /// How the viewer has moved the view.
    pub fn view(&self) -> &View {
        &self.view
    }

    /// Whether the help box is shown.
    pub fn shows_help(&self) -> bool {
        self.help
    }

    /// Limits the modes `m` cycles through to those for which `usable` is
    /// true (the current mode stays as it is).
    pub fn set_usable_glyphs(&mut self, usable: impl Fn(GlyphMode) -> bool) {
        self.usable = std::array::from_fn(|i| usable(GlyphMode::ALL[i]));
    }

    /// Switches to colour depth `depth`.
    pub fn set_color(&mut self, depth: ColorDepth) {
        self.opts.color = depth;
        self.encoder.set_depth(depth);
    }

    /// Limits the depths `c` cycles through to `max` and below.
    pub fn set_max_depth(&mut self, max: ColorDepth) {
        self.max_depth = max;
    }

    /// Switches to another glyph mode (a fallback), with a notice.
    pub fn set_glyphs(&mut self, glyphs: GlyphMode) {
        self.opts.glyphs = glyphs;
    }

    /// The options the next frame is drawn with.
    pub fn options(&self) -> &RenderOptions {
        &self.opts
    }

    /// The encoder, to change how frames are sent.
    pub fn encoder_mut(&mut self) -> &mut Encoder {
        &mut self.encoder
    }

    /// The number of the next frame (0 for the first).
    pub fn frame_number(&self) -> u64 {
        self.k
    }

    /// Whether the turn is paused.
    pub fn is_paused(&self) -> bool {
        self.paused
    }

    /// Whether the picture changes by itself as the clock ticks: not while
    /// paused or turning by nothing. A loop renders a still player only
    /// when something else changes (a key, a resize, a notice ending), so
    /// a paused `spin` costs nothing.
    pub fn moves(&self) -> bool {
        let turns = self.turning && self.spin.step != 0.0;
        let plays = self.spin.play.is_some_and(|p| {
            self.scene
                .meshes
                .iter()
                .any(|m| m.rig.as_ref().is_some_and(|r| r.moves(p.clip)))
        });
        !self.paused && (turns || plays)
    }

    /// The notice shown over the last row, if any.
    pub fn notice(&self) -> Option<&str> {
        self.notice.as_deref()
    }

    /// Changes with every new notice.
    pub fn notice_serial(&self) -> u64 {
        self.notice_serial
    }

    /// Shows `text` over the last row until [`Player::clear_notice`].
    pub fn set_notice(&mut self, text: impl Into<String>) {
        self.notice = Some(text.into());
        self.notice_serial += 1;
    }

    /// Forgets the notice shown on the status line.
    pub fn clear_notice(&mut self) {
        self.notice = None;
    }

    /// Applies a command; `false` when it asks to quit. A change of glyphs,
    /// colour or shading shows a notice naming the new setting.
    pub fn apply(&mut self, cmd: Command) -> bool {
        match cmd {
            Command::Quit => return false,
            Command::TogglePause => self.paused = !self.paused,
            Command::ToggleTurn => {
                self.turning = !self.turning;
                self.set_notice(if self.turning {
                    "turning"
                } else {
                    "turn stopped"
                });
            }
            Command::Clip(d) => {
                let n = self.scene.clips().len();
                if let Some(p) = &mut self.spin.play
                    && n > 0
                {
                    p.clip = (p.clip as i64 + i64::from(d)).rem_euclid(n as i64) as usize;
                    let clip = p.clip;
                    self.played = 0;
                    let name = clip_name(&self.scene.clips()[clip].name);
                    self.set_notice(format!("clip {clip}{name}"));
                }
            }
            Command::Orbit { yaw, pitch } => self.view.orbit(yaw, pitch),
            Command::Zoom(f) => self.view.zoom(f),
            Command::Drag { cells, pan } => {
                let rows = self.opts.rows - u16::from(self.hud && self.opts.rows > 1);
                self.view.drag(cells, rows, self.opts.cell_aspect, pan);
            }
            Command::Reset => {
                self.view = self.start;
                self.turned = 0;
                self.set_notice("view reset");
            }
            Command::ToggleHelp => {
                self.help = !self.help;
                // The box covers part of the picture: sent whole when it
                // goes (the encoder's diff sends only what changed).
            }
            Command::NextGlyphs => {
                let usable = self.usable;
                self.opts.glyphs = next_where(GlyphMode::ALL, self.opts.glyphs, |i, _| usable[i]);
                self.set_notice(format!("glyphs {}", self.opts.glyphs.name()));
            }
            Command::NextColor => {
                let max = self.max_depth;
                self.opts.color = next_where(&ColorDepth::ALL, self.opts.color, |_, d| d <= max);
                self.encoder.set_depth(self.opts.color);
                self.set_notice(format!("color {}", self.opts.color.name()));
            }
            Command::NextShading => {
                self.opts.shading = next_where(Shading::ALL, self.opts.shading, |_, _| true);
                self.set_notice(format!("shading {}", self.opts.shading.name()));
            }
            Command::NextWire => {
                self.opts.wire = next_where(Wire::ALL, self.opts.wire, |_, _| true);
                self.set_notice(format!("wire {}", self.opts.wire.name()));
            }
            Command::Resize { cols, rows } => {
                self.opts.cols = cols.clamp(1, crate::options::MAX_CELLS);
                self.opts.rows = rows.clamp(1, crate::options::MAX_CELLS);
                self.invalidate();
            }
            Command::Redraw => self.invalidate(),
        }
        true
    }

    /// Sends the next frame whole: the terminal's screen is not known.
    fn invalidate(&mut self) {
        self.encoder.invalidate();
        #[cfg(feature = "graphics")]
        if let Some(s) = &mut self.screen {
            s.invalidate();
        }
    }

    /// Moves on by `frames` frames (none while paused).
    pub fn advance(&mut self, frames: u64) {
        if !self.paused {
            self.k += frames;
            if self.turning {
                self.turned += frames;
            }
            self.played += frames;
        }
    }

    /// The camera after orbiting, zooming and panning.
    fn camera(&self) -> Camera {
        self.view.apply(&self.base)
    }

    /// Renders the current frame and encodes it; returns the bytes to send
    /// (empty when nothing changed).
    pub fn prepare(&mut self, live: LiveStatus) -> &[u8] {
        self.scene.camera = self.camera();
        let turn = self.spin.turn(self.opts.turn, self.turned);
        if let Some(p) = self.spin.play {
            self.scene.set_pose(p.clip, p.time(self.played));
        }
        // The status line takes a row of its own: the model is drawn in
        // the rows above it, never under it. Pixels always leave that row
        // (an image that reaches the last row scrolls a sixel terminal).
        let hud_row = (self.hud || self.shows_pixels()) && self.opts.rows > 1;
        // Framed to fit however it turns about the spin's axis.
        let opts = within_budget(RenderOptions {
            turn,
            turn_axis: self.spin.axis,
            rows: self.opts.rows - u16::from(hud_row),
            ..self.opts
        });
        #[cfg(feature = "graphics")]
        if self.screen.is_some() {
            return self.prepare_pixels(&opts, turn, live);
        }
        if let Err(e) = self.renderer.try_render(&self.scene, &opts) {
            // Not within the budgets even at one cell (a scene of too many
            // triangles): an empty frame, and why.
            self.renderer.frame_mut().resize(0, 0);
            self.notice = Some(e.to_string());
        }
        if (opts.cols, opts.rows) != (self.opts.cols, self.opts.rows) {
            // Blank cells around a frame cut to its budget, and a row
            // below for the status line.
            self.renderer
                .frame_mut()
                .resize(self.opts.cols, self.opts.rows);
        }
        if let Some(full_row) = self.status_line(&opts, turn, live) {
            hud::overlay(self.renderer.frame_mut(), &self.status, full_row);
        }
        if self.help {
            hud::help_box(self.renderer.frame_mut(), KEYS);
        }
        self.encoder.prepare(self.renderer.frame());
        self.last_bytes = self.encoder.last_bytes().len();
        self.encoder.last_bytes()
    }

    /// The protocol and cell size frames are sent in as pixels, for the
    /// status line (`None`: character cells).
    fn pixel_protocol(&self) -> Option<String> {
        #[cfg(feature = "graphics")]
        if let (Some(s), Some([w, h])) = (&self.screen, self.opts.cell_pixels) {
            return Some(format!("{} {w}×{h}px", s.protocol().name()));
        }
        None
    }

    /// Whether frames are sent as pixels (`Player::set_graphics`).
    pub fn shows_pixels(&self) -> bool {
        #[cfg(feature = "graphics")]
        return self.screen.is_some();
        #[cfg(not(feature = "graphics"))]
        false
    }

    /// Writes the status line (with the HUD) or the notice into
    /// `self.status`; `Some(full_row)` where there is one to show.
    fn status_line(&mut self, opts: &RenderOptions, turn: Vec3, live: LiveStatus) -> Option<bool> {
        if self.hud {
            use std::fmt::Write as _;
            let stats = *self.renderer.stats();
            // Anti-aliasing draws every triangle once per pass.
            let drawn = stats.raster.triangles_drawn / opts.aa.passes();
            // Parts by priority, each kept whole: the status line holds as
            // many as the width has room for. Rebuilt in the same buffers
            // each frame: no allocation once they have grown.
            let angle = self.spin.axis.unit().dot(turn).rem_euclid(360.0);
            let pixels = self.pixel_protocol();
            let p = &mut self.hud_parts;
            p.iter_mut().for_each(String::clear);
            if let Some(n) = &self.notice {
                p[0].push_str(n);
            }
            if self.paused {
                p[1].push_str("paused");
            }
            // The view's angles as `render --orbit` and `--pan` take them
            // (shortest exact decimals: the frame can be drawn again).
            let v = &self.view;
            let _ = write!(
                p[2],
                "{} {angle:.1}° orbit {},{} ×{:.2}",
                self.spin.axis.angle_name(),
                v.yaw,
                v.pitch,
                1.0 / v.distance
            );
            if v.shift != glam::Vec2::ZERO {
                let _ = write!(p[2], " pan {},{}", v.shift.x, v.shift.y);
            }
            let _ = match pixels {
                Some(name) => write!(p[3], "{name} · {}", opts.shading.name()),
                None => write!(
                    p[3],
                    "{} · {} · {}",
                    opts.glyphs.name(),
                    opts.color.name(),
                    opts.shading.name()
                ),
            };
            if let Some(play) = self.spin.play
                && let Some(clip) = self.scene.clips().get(play.clip)
            {
                if self
                    .clip_label
                    .as_ref()
                    .is_none_or(|(c, _)| *c != play.clip)
                {
                    self.clip_label = Some((play.clip, clip_name(&clip.name)));
                }
                let label = self.clip_label.as_ref().map_or("", |(_, l)| l);
                let _ = write!(
                    p[4],
                    "clip {}{label} {:.2}/{:.2} s",
                    play.clip,
                    clip.local(play.time(self.played)),
                    clip.length
                );
            }
            let _ = write!(p[5], "{:.1} fps", live.fps);
            let _ = write!(p[6], "{drawn} triangles");
            let _ = write!(p[7], "{} B/frame", self.last_bytes);
            let _ = match live.link {
                Some(rate) => write!(p[8], "link {:.1} kB/s", rate / 1e3),
                None => write!(p[8], "link ?"),
            };
            let _ = write!(
                p[9],
                "sync {}",
                if self.encoder.sync() { "on" } else { "off" }
            );
            hud::fit_status(&mut self.status, &self.hud_parts, usize::from(opts.cols));
            Some(true)
        } else if let Some(n) = &self.notice {
            self.status.clear();
            self.status.push(' ');
            self.status.push_str(n);
            self.status.push(' ');
            Some(false)
        } else {
            None
        }
    }

    /// Renders the current frame, sends it to `out`, and returns the bytes
    /// written.
    pub fn show(&mut self, out: &mut impl Write, live: LiveStatus) -> io::Result<usize> {
        let bytes = self.prepare(live);
        out.write_all(bytes)?;
        out.flush()?;
        Ok(bytes.len())
    }
}

/// A clip's name for the status line, escaped, after a space (nothing for
/// a clip without one).
fn clip_name(name: &str) -> String {
    if name.is_empty() {
        String::new()
    } else {
        format!(" {}", crate::text::name(name, 24))
    }
}

/// The entry after `current` in `all` (cyclically) for which `allowed`
/// holds; `current` if none does.
fn next_where<T: Copy + PartialEq>(all: &[T], current: T, allowed: impl Fn(usize, T) -> bool) -> T {
    let i = all.iter().position(|&x| x == current).unwrap_or(0);
    (1..=all.len())
        .map(|d| (i + d) % all.len())
        .find(|&j| allowed(j, all[j]))
        .map_or(current, |j| all[j])
}

/// Renders frames `0..frames` of `spin` and writes each through `encoder`
/// to `out`: what `rastty spin --frames N` writes when stdout is not a
/// terminal. Calls `sent` with the bytes of each frame.
pub fn play(
    scene: &Scene,
    opts: &RenderOptions,
    spin: Spin,
    frames: u64,
    encoder: Encoder,
    out: &mut impl Write,
    mut sent: impl FnMut(usize),
) -> io::Result<()> {
    let mut player = Player::new(scene.clone(), *opts, spin, encoder);
    for _ in 0..frames {
        sent(player.show(out, LiveStatus::default())?);
        player.advance(1);
    }
    Ok(())
}

/// `opts` with its frame cut, keeping its shape, to as many cells as its
/// sample budget allows ([`RenderOptions::max_samples`]): a terminal larger
/// than the budget is drawn in its top left part, where a still frame
/// would be refused.
fn within_budget(mut opts: RenderOptions) -> RenderOptions {
    let (cols, rows) = (u64::from(opts.cols), u64::from(opts.rows));
    let (w, h) = opts.cell_samples();
    let per_cell = u64::from(w * h) * opts.aa.passes();
    let cells = opts.max_samples / per_cell.max(1);
    if cols * rows <= cells {
        return opts;
    }
    let k = (cells as f64 / (cols * rows) as f64).sqrt();
    let (mut c, mut r) = (
        ((cols as f64 * k) as u64).max(1),
        ((rows as f64 * k) as u64).max(1),
    );
    while c * r > cells && (c > 1 || r > 1) {
        if c >= r { c -= 1 } else { r -= 1 }
    }
    (opts.cols, opts.rows) = (c as u16, r as u16);
    opts
}

#[cfg(test)]
mod tests {
    use super::hud::fit_status;
    use super::*;

    #[test]
    fn frame_k_is_turned_by_k_steps() {
        let spin = Spin {
            view: Default::default(),
            axis: Axis::Z,
            step: 6.0,
            play: None,
        };
        assert_eq!(spin.turn(Vec3::ZERO, 0), Vec3::ZERO);
        assert_eq!(spin.turn(Vec3::ZERO, 10), Vec3::new(0.0, 0.0, 60.0));
        assert_eq!(
            spin.turn(Vec3::new(1.0, 2.0, 3.0), 61),
            Vec3::new(1.0, 2.0, 9.0)
        );
        let y = Spin {
            view: Default::default(),
            axis: Axis::Y,
            step: -1.5,
            play: None,
        };
        assert_eq!(y.turn(Vec3::ZERO, 2), Vec3::new(0.0, 357.0, 0.0));
    }

    #[test]
    fn the_status_line_keeps_whole_parts_by_priority() {
        let parts = [
            "",
            "paused",
            "yaw 12.0° pitch 5° zoom 1.00×",
            "half · 256 · smooth",
            "30.0 fps",
        ]
        .map(String::from);
        let mut out = String::new();
        fit_status(&mut out, &parts, 80);
        assert_eq!(
            out,
            " paused · yaw 12.0° pitch 5° zoom 1.00× · half · 256 · smooth · 30.0 fps "
        );
        fit_status(&mut out, &parts, 62);
        assert_eq!(
            out,
            " paused · yaw 12.0° pitch 5° zoom 1.00× · half · 256 · smooth "
        );
        fit_status(&mut out, &parts, 30);
        assert_eq!(out, " paused ");
        fit_status(&mut out, &parts, 3);
        assert_eq!(
            out, " paused ",
            "the first part is kept, and cut where it is drawn"
        );
    }

    #[test]
    fn the_status_line_has_a_row_of_its_own() {
        let opts = RenderOptions {
            cols: 40,
            rows: 12,
            color: ColorDepth::TrueColor,
            ..RenderOptions::default()
        };
        let spin = Spin {
            view: Default::default(),
            axis: Axis::Y,
            step: 3.0,
            play: None,
        };
        let screen = |opts: RenderOptions, hud: bool| {
            let mut p = Player::new(
                crate::scene::default_scene(),
                opts,
                spin,
                Encoder::new(ColorDepth::TrueColor),
            )
            .with_hud(hud);
            let nz = |n| std::num::NonZeroU16::new(n).unwrap();
            let mut vt = vt100::Parser::new(nz(12), nz(40), 0);
            vt.process(p.prepare(LiveStatus::default()));
            vt
        };
        let with = screen(opts, true);
        let without = screen(RenderOptions { rows: 11, ..opts }, false);
        for row in 0..11 {
            for col in 0..40 {
                assert_eq!(
                    with.screen().cell(row, col),
                    without.screen().cell(row, col),
                    "({row}, {col})"
                );
            }
        }
        let status = with.screen().contents_between(11, 0, 11, 40);
        assert!(
            status.starts_with(" yaw 0.0° orbit 0,0 ×1.00"),
            "{status:?}"
        );
    }

    #[test]
    fn a_paused_or_unturning_player_does_not_move() {
        let spin = |step| Spin {
            view: Default::default(),
            axis: Axis::Y,
            step,
            play: None,
        };
        let player = |step| {
            Player::new(
                crate::scene::default_scene(),
                RenderOptions::default(),
                spin(step),
                Encoder::new(ColorDepth::TrueColor),
            )
        };
        let mut p = player(3.0);
        assert!(p.moves());
        p.apply(Command::TogglePause);
        assert!(!p.moves());
        assert!(!player(0.0).moves());
    }

    #[test]
    fn commands_cycle_settings_and_pause_stops_the_clock() {
        let scene = crate::scene::default_scene();
        let mut p = Player::new(
            scene,
            RenderOptions::default(),
            Spin {
                view: Default::default(),
                axis: Axis::Y,
                step: 3.0,
                play: None,
            },
            Encoder::new(ColorDepth::None),
        );
        assert!(p.apply(Command::NextGlyphs));
        assert_eq!(p.options().glyphs, GlyphMode::Quadrant);
        p.apply(Command::NextShading);
        assert_eq!(p.options().shading, Shading::None);
        p.advance(5);
        p.apply(Command::TogglePause);
        p.advance(5);
        assert_eq!(p.frame_number(), 5);
        p.apply(Command::Resize { cols: 10, rows: 4 });
        let mut out = Vec::new();
        assert!(p.show(&mut out, LiveStatus::default()).unwrap() > 0);
        assert!(!p.apply(Command::Quit));
        // A terminal's size is clamped as the command line's is.
        p.apply(Command::Resize {
            cols: 60_000,
            rows: 0,
        });
        assert_eq!(
            (p.options().cols, p.options().rows),
            (crate::options::MAX_CELLS, 1)
        );
    }

    #[test]
    fn m_and_c_skip_what_the_terminal_cannot_show_and_say_what_they_chose() {
        let mut p = Player::new(
            crate::scene::default_scene(),
            RenderOptions {
                glyphs: GlyphMode::Sextant,
                color: ColorDepth::Ansi16,
                ..RenderOptions::default()
            },
            Spin {
                view: Default::default(),
                axis: Axis::Y,
                step: 3.0,
                play: None,
            },
            Encoder::new(ColorDepth::Ansi16),
        );
        p.set_usable_glyphs(|m| !matches!(m, GlyphMode::Octant | GlyphMode::Braille));
        p.set_max_depth(ColorDepth::Ansi256);
        p.apply(Command::NextGlyphs);
        assert_eq!(
            p.options().glyphs,
            GlyphMode::Ascii,
            "octant and braille skipped"
        );
        assert_eq!(p.notice(), Some("glyphs ascii"));
        let serial = p.notice_serial();
        p.apply(Command::NextColor);
        assert_eq!(p.options().color, ColorDepth::Ansi256);
        p.apply(Command::NextColor);
        assert_eq!(
            p.options().color,
            ColorDepth::None,
            "no truecolor beyond 256"
        );
        assert_eq!(p.notice(), Some("color none"));
        assert!(p.notice_serial() > serial);
        // The notice is drawn over the last row, even without the HUD.
        p.apply(Command::Resize { cols: 20, rows: 4 });
        p.prepare(LiveStatus::default());
        let text = p.renderer.frame().to_string();
        assert!(
            text.lines().last().unwrap().starts_with(" color none "),
            "{text}"
        );
        p.clear_notice();
        p.prepare(LiveStatus::default());
        assert!(!p.renderer.frame().to_string().contains("color"));
    }
}
