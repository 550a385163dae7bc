//! Lights: directional, point and spot (glTF's `KHR_lights_punctual`),
//! as a scene or a model file gives them ([`Light::check`] says what is
//! usable), moved with the model they came with. A scene has at most
//! [`MAX_LIGHTS`]: the shading keeps them in an array of that size and
//! evaluates each one per vertex or sample, so the bound is also one on
//! that cost.

use glam::{Mat4, Vec3};

use crate::color::Rgb;

/// Most lights a scene may have.
pub const MAX_LIGHTS: usize = 8;

/// A light: directional (from far away, the same everywhere), or a point
/// or a spot at a position, whose light falls off with the square of the
/// distance (glTF's `KHR_lights_punctual`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light {
    /// The direction the light travels (unit length): a directional
    /// light's everywhere, a spot's along the middle of its cone; a point
    /// light's is not read.
    pub direction: Vec3,
    /// Its colour.
    pub color: Rgb,
    /// The share of the light that reaches every surface whatever its
    /// facing, in [0, 1].
    pub ambient: f32,
    /// What kind of light, and where.
    pub kind: LightKind,
    /// Its strength: the colour times this (at distance 1 for a point or a
    /// spot), at least 0.
    pub intensity: f32,
}

/// Where a [`Light`] comes from.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum LightKind {
    /// From far away: one direction everywhere, no falloff.
    #[default]
    Directional,
    /// From a point, in every direction.
    Point {
        /// Where, in the world.
        position: Vec3,
        /// Beyond this distance it gives no light (glTF's smooth window,
        /// `clamp(1 − (d/range)⁴, 0, 1)`); `None`: it reaches everywhere.
        range: Option<f32>,
    },
    /// From a point, in a cone about [`Light::direction`].
    Spot {
        /// Where, in the world.
        position: Vec3,
        /// As for a point.
        range: Option<f32>,
        /// Radians from the cone's middle within which the light is whole.
        inner: f32,
        /// Radians from the cone's middle beyond which there is none; more
        /// than `inner`, at most π/2.
        outer: f32,
    },
}

impl LightKind {
    /// Where the light is, for a point or a spot.
    pub fn position(&self) -> Option<Vec3> {
        match *self {
            LightKind::Directional => None,
            LightKind::Point { position, .. } | LightKind::Spot { position, .. } => Some(position),
        }
    }
}

impl Default for Light {
    /// A white light from the upper right, in front, with a little
    /// ambient.
    fn default() -> Self {
        Light {
            direction: Vec3::new(-0.5, -1.0, -0.7).normalize(),
            color: Rgb::WHITE,
            ambient: 0.15,
            kind: LightKind::Directional,
            intensity: 1.0,
        }
    }
}

impl Light {
    /// Whether this light can be drawn: a finite, non-zero direction
    /// (unless it is a point light), an ambient share between 0 and 1, a
    /// finite intensity of at least 0, a finite position, a positive range
    /// and cone angles with 0 ≤ inner < outer ≤ π/2. The message says what
    /// is wrong.
    pub fn check(&self) -> std::result::Result<(), String> {
        let d = self.direction;
        let point = matches!(self.kind, LightKind::Point { .. });
        if !point && (!d.is_finite() || d.length_squared() == 0.0) {
            return Err("light direction must be a finite, non-zero vector".into());
        }
        if !(0.0..=1.0).contains(&self.ambient) {
            return Err(format!(
                "light ambient must be between 0 and 1, not {}",
                self.ambient
            ));
        }
        if !(self.intensity.is_finite() && self.intensity >= 0.0) {
            return Err(format!(
                "light intensity must be a finite number of at least 0, not {}",
                self.intensity
            ));
        }
        let (range, cone) = match self.kind {
            LightKind::Directional => return Ok(()),
            LightKind::Point { range, .. } => (range, None),
            LightKind::Spot {
                range,
                inner,
                outer,
                ..
            } => (range, Some((inner, outer))),
        };
        if !self.kind.position().is_some_and(|p| p.is_finite()) {
            return Err("light position must be finite".into());
        }
        if let Some(r) = range
            && !(r.is_finite() && r > 0.0)
        {
            return Err(format!(
                "light range must be a finite number above 0, not {r}"
            ));
        }
        if let Some((inner, outer)) = cone
            && !(inner >= 0.0 && inner < outer && outer <= std::f32::consts::FRAC_PI_2)
        {
            return Err(format!(
                "spot cone angles must be 0 <= inner < outer <= 90°, not {}° and {}°",
                inner.to_degrees(),
                outer.to_degrees()
            ));
        }
        Ok(())
    }

    /// The same light seen through `m`, a model-to-world matrix that
    /// scales evenly by `scale`: its direction and position carried by it,
    /// its range scaled, and its intensity by `scale²`, so that a point
    /// light lights its scaled model as it lit the model.
    pub fn transformed(&self, m: Mat4, scale: f32) -> Light {
        let kind = match self.kind {
            LightKind::Directional => LightKind::Directional,
            LightKind::Point { position, range } => LightKind::Point {
                position: m.transform_point3(position),
                range: range.map(|r| r * scale),
            },
            LightKind::Spot {
                position,
                range,
                inner,
                outer,
            } => LightKind::Spot {
                position: m.transform_point3(position),
                range: range.map(|r| r * scale),
                inner,
                outer,
            },
        };
        let positional = kind.position().is_some();
        Light {
            direction: m.transform_vector3(self.direction).normalize_or_zero(),
            kind,
            intensity: if positional {
                self.intensity * scale * scale
            } else {
                self.intensity
            },
            ..*self
        }
    }

    /// The lights of a model shown alone: a key light from the upper left
    /// in front (0.8 of white, in linear light, 0.12 of it ambient) and a
    /// fill from the right, a little below (0.3 of white): a white face
    /// turned to the key shows 0.8 of its light (sRGB 231), one turned
    /// from the key to the fill about 0.4 (sRGB 170), one turned from both
    /// 0.1 (sRGB 87): shape reads without the lit side washing out or the
    /// dark side going black.
    pub fn rig() -> [Light; 2] {
        [
            Light {
                direction: Vec3::new(0.6, -0.9, -0.6).normalize(),
                color: Rgb::new(0xe7, 0xe7, 0xe7),
                ambient: 0.12,
                ..Light::default()
            },
            Light {
                direction: Vec3::new(-0.9, 0.3, -0.3).normalize(),
                color: Rgb::new(0x95, 0x95, 0x95),
                ambient: 0.0,
                ..Light::default()
            },
        ]
    }
}
