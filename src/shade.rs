//! Shading: how a surface's colour is lit, evaluated once per vertex (or
//! per face) in the vertex stage; the rasterizer then only interpolates.
//!
//! The model is Lambert's: each light adds its colour times
//! `ambient + (1 − ambient)·max(0, n·(−d))`, and the sum multiplies the
//! surface colour. Lighting is two-sided: a face seen from behind (a mesh
//! drawn without culling, an open model like the teapot) is lit as seen
//! from its visible side.

use glam::Vec3;

use crate::scene::Light;

/// How surfaces are shaded.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, clap::ValueEnum)]
pub enum Shading {
    /// Surface colours as they are, unlit.
    None,
    /// One Lambert term per face, from its geometric normal.
    Flat,
    /// Gouraud: a Lambert term per vertex from its normal, interpolated.
    #[default]
    Smooth,
}

impl Shading {
    pub const ALL: [Shading; 3] = [Shading::None, Shading::Flat, Shading::Smooth];
}

/// The light reaching a surface of unit normal `n`, per channel (1.0 is
/// the full colour of one white light).
#[inline]
pub fn lambert(n: Vec3, lights: &[Light]) -> Vec3 {
    let mut sum = Vec3::ZERO;
    for l in lights {
        let c = Vec3::from(l.color.to_f32()) / 255.0;
        let direct = n.dot(-l.direction).max(0.0);
        sum += c * (l.ambient + (1.0 - l.ambient) * direct);
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb;

    #[test]
    fn lambert_is_ambient_plus_cosine() {
        let light = Light {
            direction: Vec3::NEG_Z,
            color: Rgb::WHITE,
            ambient: 0.2,
        };
        assert_eq!(lambert(Vec3::Z, &[light]), Vec3::ONE);
        assert_eq!(lambert(Vec3::NEG_Z, &[light]), Vec3::splat(0.2));
        let half = lambert(Vec3::new(0.0, 0.6, 0.8), &[light]);
        assert!((half.x - (0.2 + 0.8 * 0.8)).abs() < 1e-6);
        assert_eq!(lambert(Vec3::Z, &[]), Vec3::ZERO);
    }
}
