//! The animation loop's core, without a terminal: a scene turning about an
//! axis, frame `k` turned by `k · step` degrees, each frame rendered and
//! sent through the diffing encoder to any `io::Write`.
//!
//! `rastty spin` drives this from the terminal (with a clock, keys and
//! resizes); tests and the byte-count table drive it headless, so that
//! what they measure is exactly what a terminal receives.

use std::io::{self, Write};

use glam::Vec3;

use crate::encode::Encoder;
use crate::render::{RenderOptions, Renderer};
use crate::scene::Scene;

/// A world axis to turn about.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
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
    /// `k`, starting from `base`. The angle is reduced modulo 360 so that it
    /// stays exact however long the loop runs.
    pub fn turn(&self, base: Vec3, k: u64) -> Vec3 {
        let angle = (k as f64 * self.step as f64).rem_euclid(360.0) as f32;
        base + self.axis.unit() * angle
    }
}

/// Renders frames `0..frames` of `spin` and writes each through `encoder`
/// to `out`. Returns the bytes sent for each frame.
pub fn play(
    scene: &Scene,
    opts: &RenderOptions,
    spin: Spin,
    frames: u64,
    encoder: &mut Encoder,
    out: &mut impl Write,
) -> io::Result<Vec<usize>> {
    let mut renderer = Renderer::new();
    let mut sizes = Vec::with_capacity(frames as usize);
    for k in 0..frames {
        let opts = RenderOptions {
            turn: spin.turn(opts.turn, k),
            ..*opts
        };
        let frame = renderer.render(scene, &opts);
        sizes.push(encoder.encode(frame, out)?);
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
}
