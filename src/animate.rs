//! The animation loop's core, without a terminal: a scene turning about an
//! axis, frame `k` turned by `k · step` degrees, each frame rendered and
//! sent through the diffing encoder to any `io::Write`.
//!
//! A [`Player`] holds everything that changes while a scene spins (the
//! frame number, the view, the settings the keys cycle through) and reacts
//! to [`Command`]s; it knows nothing of clocks or keys. `rastty spin` drives
//! it from the terminal (`terminal::run`: a clock, keys, signals and
//! resizes); tests and the byte-count table drive it headless ([`play`]),
//! so that what they measure is exactly what a terminal receives.

use std::io::{self, Write};

use glam::Vec3;

use crate::GlyphMode;
use crate::color::{ColorDepth, Rgb};
use crate::encode::Encoder;
use crate::frame::{Cell, Frame};
use crate::render::{RenderOptions, Renderer};
use crate::scene::{Camera, Scene};
use crate::shade::Shading;

/// A world axis to turn about.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, clap::ValueEnum)]
pub enum Axis {
    X,
    #[default]
    Y,
    Z,
}

impl Axis {
    pub fn unit(self) -> Vec3 {
        match self {
            Axis::X => Vec3::X,
            Axis::Y => Vec3::Y,
            Axis::Z => Vec3::Z,
        }
    }
}

/// A turn of `step` degrees per frame about `axis`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spin {
    pub axis: Axis,
    pub step: f32,
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

/// What a key (or the terminal) asks of a running animation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Command {
    Quit,
    TogglePause,
    /// Move the eye around the target: degrees of yaw and pitch.
    Orbit {
        yaw: f32,
        pitch: f32,
    },
    /// Multiply the eye's distance from the target.
    Zoom(f32),
    NextGlyphs,
    NextColor,
    NextShading,
    /// The terminal's new size in cells.
    Resize {
        cols: u16,
        rows: u16,
    },
    /// Send the next frame in full.
    Redraw,
}

/// A spinning scene and everything that changes while it spins.
#[derive(Debug)]
pub struct Player {
    scene: Scene,
    base: Camera,
    opts: RenderOptions,
    spin: Spin,
    /// Frames played while not paused: the angle's frame number.
    k: u64,
    paused: bool,
    orbit: (f32, f32),
    zoom: f32,
    hud: bool,
    renderer: Renderer,
    encoder: Encoder,
    last_bytes: usize,
    status: String,
}

impl Player {
    pub fn new(scene: Scene, opts: RenderOptions, spin: Spin, encoder: Encoder) -> Player {
        Player {
            base: scene.camera,
            scene,
            opts,
            spin,
            k: 0,
            paused: false,
            orbit: (0.0, 0.0),
            zoom: 1.0,
            hud: false,
            renderer: Renderer::new(),
            encoder,
            last_bytes: 0,
            status: String::new(),
        }
    }

    /// Shows a status line over the frame's last row.
    pub fn with_hud(mut self, on: bool) -> Player {
        self.hud = on;
        self
    }

    pub fn options(&self) -> &RenderOptions {
        &self.opts
    }

    pub fn frame_number(&self) -> u64 {
        self.k
    }

    pub fn is_paused(&self) -> bool {
        self.paused
    }

    /// Applies a command; `false` when it asks to quit.
    pub fn apply(&mut self, cmd: Command) -> bool {
        match cmd {
            Command::Quit => return false,
            Command::TogglePause => self.paused = !self.paused,
            Command::Orbit { yaw, pitch } => {
                self.orbit.0 += yaw;
                self.orbit.1 = (self.orbit.1 + pitch).clamp(-85.0, 85.0);
            }
            Command::Zoom(f) => self.zoom = (self.zoom * f).clamp(0.05, 20.0),
            Command::NextGlyphs => self.opts.glyphs = next(&GlyphMode::ALL, self.opts.glyphs),
            Command::NextColor => {
                self.opts.color = next(&ColorDepth::ALL, self.opts.color);
                self.encoder.set_depth(self.opts.color);
            }
            Command::NextShading => self.opts.shading = next(&Shading::ALL, self.opts.shading),
            Command::Resize { cols, rows } => {
                self.opts.cols = cols.max(1);
                self.opts.rows = rows.max(1);
                self.encoder.invalidate();
            }
            Command::Redraw => self.encoder.invalidate(),
        }
        true
    }

    /// Moves on by `frames` frames (none while paused).
    pub fn advance(&mut self, frames: u64) {
        if !self.paused {
            self.k += frames;
        }
    }

    /// The camera after orbiting and zooming.
    fn camera(&self) -> Camera {
        let c = self.base;
        let offset = (c.eye - c.target) * self.zoom;
        let yaw = glam::Quat::from_axis_angle(c.up.normalize_or_zero(), self.orbit.0.to_radians());
        let right = offset.cross(c.up).normalize_or_zero();
        let pitch = glam::Quat::from_axis_angle(right, self.orbit.1.to_radians());
        Camera {
            eye: c.target + yaw * (pitch * offset),
            ..c
        }
    }

    /// Renders the current frame, sends it to `out`, and returns the bytes
    /// written.
    pub fn show(&mut self, out: &mut impl Write, fps: f32) -> io::Result<usize> {
        self.scene.camera = self.camera();
        let opts = RenderOptions {
            turn: self.spin.turn(self.opts.turn, self.k),
            ..self.opts
        };
        self.renderer.render(&self.scene, &opts);
        if self.hud {
            use std::fmt::Write as _;
            let stats = *self.renderer.stats();
            // The status line's text is rebuilt in the same buffer each
            // frame: no allocation once it has grown.
            self.status.clear();
            let _ = write!(
                self.status,
                " {fps:.1} fps · {} triangles drawn · {} B/frame · {:?} · {:?} · {:?}{} ",
                stats.raster.triangles_drawn,
                self.last_bytes,
                opts.glyphs,
                opts.color,
                opts.shading,
                if self.paused { " · paused" } else { "" },
            );
            overlay_status(self.renderer.frame_mut(), &self.status);
        }
        self.last_bytes = self.encoder.encode(self.renderer.frame(), out)?;
        Ok(self.last_bytes)
    }
}

/// Writes `text` over the last row of `frame`, white on black.
fn overlay_status(frame: &mut Frame, text: &str) {
    let row = frame.rows().saturating_sub(1);
    let mut chars = text.chars();
    for col in 0..frame.cols() {
        frame.set(
            col,
            row,
            Cell {
                ch: chars.next().unwrap_or(' '),
                fg: Some(Rgb::WHITE),
                bg: Some(Rgb::BLACK),
            },
        );
    }
}

fn next<T: Copy + PartialEq>(all: &[T], current: T) -> T {
    let i = all.iter().position(|&x| x == current).unwrap_or(0);
    all[(i + 1) % all.len()]
}

/// Renders frames `0..frames` of `spin` and writes each through `encoder`
/// to `out`: what `rastty spin --frames N` writes when stdout is not a
/// terminal. Returns the bytes sent for each frame.
pub fn play(
    scene: &Scene,
    opts: &RenderOptions,
    spin: Spin,
    frames: u64,
    encoder: Encoder,
    out: &mut impl Write,
) -> io::Result<Vec<usize>> {
    let mut player = Player::new(scene.clone(), *opts, spin, encoder);
    let mut sizes = Vec::with_capacity(frames as usize);
    for _ in 0..frames {
        sizes.push(player.show(out, 0.0)?);
        player.advance(1);
    }
    Ok(sizes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_k_is_turned_by_k_steps() {
        let spin = Spin {
            axis: Axis::Z,
            step: 6.0,
        };
        assert_eq!(spin.turn(Vec3::ZERO, 0), Vec3::ZERO);
        assert_eq!(spin.turn(Vec3::ZERO, 10), Vec3::new(0.0, 0.0, 60.0));
        assert_eq!(
            spin.turn(Vec3::new(1.0, 2.0, 3.0), 61),
            Vec3::new(1.0, 2.0, 9.0)
        );
        let y = Spin {
            axis: Axis::Y,
            step: -1.5,
        };
        assert_eq!(y.turn(Vec3::ZERO, 2), Vec3::new(0.0, 357.0, 0.0));
    }

    #[test]
    fn commands_cycle_settings_and_pause_stops_the_clock() {
        let scene = crate::default_scene();
        let mut p = Player::new(
            scene,
            RenderOptions::default(),
            Spin {
                axis: Axis::Y,
                step: 3.0,
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
        assert!(p.show(&mut out, 30.0).unwrap() > 0);
        assert!(!p.apply(Command::Quit));
    }
}
