//! Shading: how a surface's colour is lit, evaluated once per vertex (or
//! per face) in the vertex stage; the rasterizer then only interpolates.
//!
//! The model is Lambert's: each light adds its colour times
//! `ambient + (1 − ambient)·max(0, n·(−d))`, and the sum multiplies the
//! surface colour. Lighting is two-sided: a face seen from behind (a mesh
//! drawn without culling, an open model like the teapot) is lit as seen
//! from its visible side.
//!
//! A **highlight** ([`Lights::specular_a`], for materials that shine) is
//! glTF's metallic-roughness specular, found per sample by the specular
//! fill (`fill.rs`) and added to the lit colour; [`specular_reference`] is
//! the same lobe in f64, which the bench and tests measure it against.
//!
//! **Layers** (a material's clear coat and sheen) are found per sample
//! by the mapped fill: a clear coat is the same GGX lobe of reflectance
//! 0.04, and sheen the Charlie lobe of `sheen.rs`.
//!
//! A **rim light** (`RenderOptions::rim`) is added, not multiplied: its
//! colour times `(1 − max(0, n·v))³`, where `v` is the direction towards
//! the eye, so it is nothing on a surface facing the viewer and its whole
//! colour where the surface turns edge-on, whatever the surface's own
//! colour: a black model gets a lit outline, which Lambert's term (black
//! times any light) cannot give it. `v` is one direction for the frame,
//! from the camera's target to its eye: exact for parallel views, and for
//! a perspective view the outline a parallel view would have, which differs
//! from the true silhouette by the angle the model subtends.

use glam::{Vec3, Vec3A, Vec4};

use crate::scene::{Light, LightKind, MAX_LIGHTS};

pub(crate) mod sheen;

pub use sheen::{sheen_albedo_reference, sheen_reference};

/// How surfaces are shaded.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Shading {
    /// Surface colours as they are, unlit.
    None,
    /// One Lambert term per face, from its geometric normal.
    Flat,
    /// Gouraud: a Lambert term per vertex from its normal, interpolated.
    #[default]
    Smooth,
}

crate::choice::choice!(Shading {
    None => "none": "Surface colours as they are, unlit",
    Flat => "flat": "One Lambert term per face, from its geometric normal",
    Smooth => "smooth": "Gouraud: a Lambert term per vertex from its normal, interpolated",
});

/// A scene's lights, ready for shading: towards the light, colour in
/// [0, 1]. Fixed-size, so a frame sets it up without allocating.
#[derive(Clone, Copy, Debug, Default)]
pub struct Lights {
    towards: [Vec3; MAX_LIGHTS],
    /// In SIMD lanes: the same operations on each channel as three f32s,
    /// so the same results, in fewer instructions.
    color: [Vec3A; MAX_LIGHTS],
    ambient: [f32; MAX_LIGHTS],
    /// Where each point or spot light is and how its light falls off.
    reach: [Reach; MAX_LIGHTS],
    /// Whether any light is a point or a spot (then lighting needs
    /// positions: [`Lights::lambert_at`]).
    positional: bool,
    len: usize,
    /// The first four lights' directions towards them (x, y, z) and
    /// ambient shares, one light a lane, for [`Lights::specular_far4`].
    towards4: [Vec4; 3],
    ambient4: Vec4,
    /// The rim light's colour, in the renderer's linear units (0–65535 a
    /// channel), zero for none.
    rim: Vec3A,
    /// Towards the eye, for the rim light.
    to_eye: Vec3,
}

impl Lights {
    /// The first [`MAX_LIGHTS`] of `lights`.
    pub fn new(lights: &[Light]) -> Lights {
        let mut l = Lights::default();
        for (i, light) in lights.iter().take(MAX_LIGHTS).enumerate() {
            l.towards[i] = -light.direction;
            // Light adds in linear values: the colour decoded from sRGB.
            l.color[i] = Vec3A::from(
                Vec3::from(crate::color::Lin::from_srgb(light.color).to_f32()) / 65535.0,
            );
            // Times the intensity (1 for most lights: the same bits).
            l.color[i] *= light.intensity;
            l.ambient[i] = light.ambient;
            l.reach[i] = Reach::of(light);
        }
        l.len = lights.len().min(MAX_LIGHTS);
        let lane = |f: &dyn Fn(usize) -> f32| Vec4::from_array(std::array::from_fn(f));
        l.towards4 = [0, 1, 2].map(|c| lane(&|i| l.towards[i][c]));
        l.ambient4 = lane(&|i| l.ambient[i]);
        l.positional = l.reach[..l.len].iter().any(|r| !matches!(r, Reach::Far));
        l
    }

    /// Whether a light is a point or a spot, whose light depends on where
    /// the surface is ([`Lights::lambert_at`]).
    pub fn positional(&self) -> bool {
        self.positional
    }

    /// The unit direction towards light `i` from `p` and the share of its
    /// light that arrives there (1 for a directional light; for a point or
    /// a spot, the inverse square of the distance, times the range's
    /// window and the cone's).
    #[inline(always)]
    fn incident(&self, i: usize, p: Vec3) -> (Vec3, f32) {
        let (t, share) = self.incident_a(i, Vec3A::from(p));
        (Vec3::from(t), share)
    }

    /// [`Lights::incident`] in SIMD lanes (the same operations per
    /// coordinate, so the same bits).
    #[inline(always)]
    fn incident_a(&self, i: usize, p: Vec3A) -> (Vec3A, f32) {
        match self.reach[i] {
            Reach::Far => (Vec3A::from(self.towards[i]), 1.0),
            Reach::Near {
                position,
                inv_range4,
                cone,
            } => {
                let d = Vec3A::from(position) - p;
                let d2 = d.length_squared();
                if d2.is_nan() || d2 <= 0.0 {
                    return (Vec3A::ZERO, 0.0);
                }
                let t = d / d2.sqrt();
                let mut share = 1.0 / d2;
                if inv_range4 > 0.0 {
                    share *= (1.0 - d2 * d2 * inv_range4).clamp(0.0, 1.0);
                }
                if let Some((scale, offset)) = cone {
                    // The cosine between the spot's axis (where its light
                    // travels, −towards) and the way to `p` (−t).
                    let cd = Vec3A::from(self.towards[i]).dot(t);
                    let s = (cd * scale + offset).clamp(0.0, 1.0);
                    share *= s * s;
                }
                (t, share)
            }
        }
    }

    /// The same with a rim light of `color` for an eye in direction
    /// `to_eye` (any length; zero or not finite: straight down −z's
    /// opposite, +z).
    pub fn with_rim(mut self, color: crate::color::Rgb, to_eye: Vec3) -> Lights {
        self.rim = Vec3A::from(Vec3::from(crate::color::Lin::from_srgb(color).to_f32()));
        self.to_eye = to_eye.try_normalize().unwrap_or(Vec3::Z);
        self
    }

    /// The rim light added to a surface of unit normal `n` (seen from the
    /// side `n` points to), in the renderer's linear units.
    #[inline(always)]
    pub(crate) fn rim_a(&self, n: Vec3) -> Vec3A {
        let edge = 1.0 - n.dot(self.to_eye).max(0.0);
        self.rim * (edge * edge * edge)
    }

    /// Whether there is no light.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The light reaching a surface of unit normal `n`, per channel (1.0 is
    /// the full colour of one white light).
    #[inline]
    pub fn lambert(&self, n: Vec3) -> Vec3 {
        Vec3::from(self.lambert_a(n))
    }

    /// The light reaching a surface of unit normal `n` at `p` (in the world
    /// the lights are in), for every kind of light: for directional lights
    /// alone the same bits as [`Lights::lambert`] (their share is 1, and a
    /// product by 1 is exact).
    #[inline(always)]
    pub fn lambert_at(&self, n: Vec3, p: Vec3) -> Vec3A {
        let mut sum = Vec3A::ZERO;
        for i in 0..self.len {
            let (t, share) = self.incident(i, p);
            let direct = n.dot(t).max(0.0);
            sum += self.color[i] * ((self.ambient[i] + (1.0 - self.ambient[i]) * direct) * share);
        }
        sum
    }

    /// [`Lights::lambert_at`] with each light's ambient share times
    /// `occlusion` (a material's occlusion map: 1 lets all of it in).
    #[inline(always)]
    pub(crate) fn lambert_occluded(&self, n: Vec3, p: Vec3, occlusion: f32) -> Vec3A {
        let mut sum = Vec3A::ZERO;
        for i in 0..self.len {
            let (t, share) = self.incident(i, p);
            let direct = n.dot(t).max(0.0);
            let ambient = self.ambient[i];
            sum += self.color[i] * ((ambient * occlusion + (1.0 - ambient) * direct) * share);
        }
        sum
    }

    /// [`Lights::lambert`] in SIMD lanes, for the renderer.
    #[inline(always)]
    pub(crate) fn lambert_a(&self, n: Vec3) -> Vec3A {
        let mut sum = Vec3A::ZERO;
        for i in 0..self.len {
            let direct = n.dot(self.towards[i]).max(0.0);
            sum += self.color[i] * (self.ambient[i] + (1.0 - self.ambient[i]) * direct);
        }
        sum
    }

    /// The specular light reflected towards the eye from a surface of unit
    /// normal `n` (seen from the side it points to) and unit direction to
    /// the eye `v`, per channel in the units of [`Lights::lambert`]: glTF's
    /// metallic-roughness specular (GGX distribution, Smith's
    /// height-correlated visibility, Schlick's Fresnel from `f0`) times
    /// `π` (the factor that makes Lambert's `1/π` lobe the plain `n·l`
    /// used here) and each light's direct share. `a2` is α², roughness to
    /// the fourth; `p` where the surface is (for point and spot lights).
    /// Zero where the eye or a light is behind the surface.
    #[inline(always)]
    pub(crate) fn specular_a(&self, n: Vec3A, v: Vec3A, p: Vec3A, f0: Vec3A, a2: f32) -> Vec3A {
        // Directional lights alone skip the positional match per light
        // (their share of 1 folds away); up to four of them are found one
        // a lane, the same bits.
        if self.positional {
            self.specular_near(n, v, p, f0, a2)
        } else if self.len <= 4 {
            self.specular_far4(n, v, f0, a2)
        } else {
            self.specular_from(n, v, f0, a2, |i| (Vec3A::from(self.towards[i]), 1.0))
        }
    }

    /// [`Lights::specular_a`] with point or spot lights, out of line: the
    /// fill that inlines the directional loop stays short.
    #[inline(never)]
    fn specular_near(&self, n: Vec3A, v: Vec3A, p: Vec3A, f0: Vec3A, a2: f32) -> Vec3A {
        self.specular_from(n, v, f0, a2, |i| self.incident_a(i, p))
    }

    /// [`Lights::specular_from`] of at most four directional lights, one a
    /// lane: the same operations on each light's numbers, in the same
    /// order, so the same bits (a test compares the two); the lights that
    /// reach the surface are then added in their order, as there. A
    /// directional light's share of 1 is left out: times 1 is exact.
    #[inline(always)]
    fn specular_far4(&self, n: Vec3A, v: Vec3A, f0: Vec3A, a2: f32) -> Vec3A {
        let nv = n.dot(v);
        let mut sum = Vec3A::ZERO;
        // Written so that a NaN (a degenerate normal) counts as behind.
        if nv.is_nan() || nv <= 0.0 {
            return sum;
        }
        let s = Vec4::splat;
        let [tx, ty, tz] = self.towards4;
        let (nx, ny, nz) = (s(n.x), s(n.y), s(n.z));
        // `Vec3A::dot`'s order: (x·x' + y·y') + z·z'.
        let nl = nx * tx + ny * ty + nz * tz;
        // A NaN fails the comparison: behind, as there. A lane past the
        // last light points nowhere (zero), so is never lit.
        let lit = nl.cmpgt(Vec4::ZERO).bitmask();
        if lit == 0 {
            return sum;
        }
        // `(l + v).normalize_or_zero()`.
        let (vx, vy, vz) = (s(v.x), s(v.y), s(v.z));
        let (hx, hy, hz) = (tx + vx, ty + vy, tz + vz);
        let rcp = Vec4::ONE / (hx * hx + hy * hy + hz * hz).sqrt();
        let unit = rcp.is_finite_mask() & rcp.cmpgt(Vec4::ZERO);
        let h = |c: Vec4| Vec4::select(unit, c * rcp, Vec4::ZERO);
        let (hx, hy, hz) = (h(hx), h(hy), h(hz));
        // `Vec4::max` keeps its second operand for a NaN, as `f32::max`
        // does; a zero's sign is lost below either way.
        let nh = (nx * hx + ny * hy + nz * hz).max(Vec4::ZERO);
        let vh = (vx * hx + vy * hy + vz * hz).max(Vec4::ZERO);
        let k = nh * nh * s(a2 - 1.0) + Vec4::ONE;
        let pi_d = s(a2) / (k * k);
        let eye = (nv * nv * (1.0 - a2) + a2).sqrt();
        let vis = s(0.5) / (nl * s(eye) + s(nv) * (nl * nl * s(1.0 - a2) + s(a2)).sqrt());
        let m = Vec4::ONE - vh;
        let m5 = ((m * m) * (m * m) * m).to_array();
        let share = (pi_d * vis * nl * (Vec4::ONE - self.ambient4)).to_array();
        for i in 0..self.len {
            if lit & 1 << i != 0 {
                let f = f0 + (Vec3A::ONE - f0) * m5[i];
                sum += self.color[i] * f * share[i];
            }
        }
        sum
    }

    /// [`Lights::specular_a`] with `incident` giving each light's unit
    /// direction and share.
    #[inline(always)]
    fn specular_from(
        &self,
        n: Vec3A,
        v: Vec3A,
        f0: Vec3A,
        a2: f32,
        incident: impl Fn(usize) -> (Vec3A, f32),
    ) -> Vec3A {
        let nv = n.dot(v);
        let mut sum = Vec3A::ZERO;
        // Written so that a NaN (a degenerate normal) counts as behind.
        if nv.is_nan() || nv <= 0.0 {
            return sum;
        }
        for i in 0..self.len {
            let (l, share) = incident(i);
            let nl = n.dot(l);
            if nl.is_nan() || nl <= 0.0 {
                continue;
            }
            let h = (l + v).normalize_or_zero();
            let nh = n.dot(h).max(0.0);
            let vh = v.dot(h).max(0.0);
            let k = nh * nh * (a2 - 1.0) + 1.0;
            // π·D, with D = α² / (π k²).
            let pi_d = a2 / (k * k);
            let vis = 0.5
                / (nl * (nv * nv * (1.0 - a2) + a2).sqrt()
                    + nv * (nl * nl * (1.0 - a2) + a2).sqrt());
            let m = 1.0 - vh;
            let m5 = (m * m) * (m * m) * m;
            let f = f0 + (Vec3A::ONE - f0) * m5;
            sum += self.color[i] * f * (pi_d * vis * nl * (1.0 - self.ambient[i]) * share);
        }
        sum
    }

    /// [`Lights::lambert`] for four unit normals, given as their x, y and z
    /// each in the lanes of a vector; returns the red, green and blue of the
    /// four. The same operations per lane, in the same order, so the same
    /// results bit for bit.
    #[inline(always)]
    pub(crate) fn lambert4(&self, n: [Vec4; 3]) -> [Vec4; 3] {
        let mut sum = [Vec4::ZERO; 3];
        for i in 0..self.len {
            let t = self.towards[i];
            // `f32::max` and the lanes' max differ only for a NaN (never
            // here: the normals are finite) and in the sign of a zero, which
            // the sum with the ambient term below loses either way.
            let direct = (n[0] * t.x + n[1] * t.y + n[2] * t.z).max(Vec4::ZERO);
            let a = self.ambient[i];
            let s = Vec4::splat(a) + Vec4::splat(1.0 - a) * direct;
            for (c, sum) in sum.iter_mut().enumerate() {
                *sum += Vec4::splat(self.color[i][c]) * s;
            }
        }
        sum
    }
}

/// How a light's share falls off, set up once a frame.
#[derive(Clone, Copy, Debug, Default)]
enum Reach {
    /// A directional light: all of it everywhere.
    #[default]
    Far,
    /// A point or a spot light.
    Near {
        position: Vec3,
        /// 1/range⁴, 0 for no range.
        inv_range4: f32,
        /// A spot's cone as glTF's scale and offset of the cosine:
        /// `1 / (cos inner − cos outer)` and `−cos outer` times it.
        cone: Option<(f32, f32)>,
    },
}

impl Reach {
    fn of(light: &Light) -> Reach {
        let inv_range4 = |r: Option<f32>| r.map_or(0.0, |r| 1.0 / (r * r * r * r));
        match light.kind {
            LightKind::Directional => Reach::Far,
            LightKind::Point { position, range } => Reach::Near {
                position,
                inv_range4: inv_range4(range),
                cone: None,
            },
            LightKind::Spot {
                position,
                range,
                inner,
                outer,
            } => {
                let scale = 1.0 / (inner.cos() - outer.cos()).max(1e-3);
                Reach::Near {
                    position,
                    inv_range4: inv_range4(range),
                    cone: Some((scale, -outer.cos() * scale)),
                }
            }
        }
    }
}

/// The highlight's lobe (glTF's metallic-roughness specular times π and
/// `n·l`, as the renderer adds it) for one white light without ambient, in
/// f64: what the f32 evaluation is measured against
/// (`rastty bench`, the tests). `n`, `l` and `v` unit vectors.
pub fn specular_reference(n: glam::DVec3, l: glam::DVec3, v: glam::DVec3, f0: f64, a2: f64) -> f64 {
    let (nv, nl) = (n.dot(v), n.dot(l));
    if !(nv > 0.0 && nl > 0.0) {
        return 0.0;
    }
    let h = (l + v).normalize_or_zero();
    let (nh, vh) = (n.dot(h).max(0.0), v.dot(h).max(0.0));
    let k = nh * nh * (a2 - 1.0) + 1.0;
    let vis =
        0.5 / (nl * (nv * nv * (1.0 - a2) + a2).sqrt() + nv * (nl * nl * (1.0 - a2) + a2).sqrt());
    let f = f0 + (1.0 - f0) * (1.0 - vh).powi(5);
    a2 / (k * k) * vis * nl * f
}

/// The light a metal of unit normal `n`, seen from unit `v`, of
/// reflectance `f0` and α² `a2`, reflects of `radiance` towards the eye,
/// in f64: the renderer's lobe ([`crate::specular_reference`], over π)
/// integrated over the sphere on a grid of `steps × 2·steps` directions.
/// What [`crate::scene::environment::EnvMap::reflect`] is measured against.
pub fn reflection_reference(
    radiance: &dyn Fn(glam::DVec3) -> f64,
    n: glam::DVec3,
    v: glam::DVec3,
    f0: f64,
    a2: f64,
    steps: usize,
) -> f64 {
    let (w, h) = (2 * steps, steps);
    let mut sum = 0.0;
    for i in 0..w * h {
        let (x, y) = ((i % w) as f64 + 0.5, (i / w) as f64 + 0.5);
        let l = crate::scene::environment::direction(x, y, w, h);
        let solid = (y / h as f64 * std::f64::consts::PI).sin()
            * (std::f64::consts::TAU / w as f64)
            * (std::f64::consts::PI / h as f64);
        let lobe = specular_reference(n, l, v, f0, a2);
        if lobe > 0.0 {
            sum += radiance(l) * lobe * solid;
        }
    }
    sum / std::f64::consts::PI
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb;

    #[test]
    fn the_rim_is_nothing_facing_the_eye_and_all_of_its_colour_edge_on() {
        let l = Lights::new(&[]).with_rim(Rgb::WHITE, Vec3::new(0.0, 0.0, 2.0));
        assert_eq!(l.rim_a(Vec3::Z), Vec3A::ZERO);
        assert_eq!(l.rim_a(Vec3::X), Vec3A::splat(65535.0));
        assert_eq!(l.rim_a(-Vec3::Z), Vec3A::splat(65535.0));
        // At 60° from the eye, (1 − cos 60°)³ = 1/8 of the colour.
        let n = Vec3::new(60f32.to_radians().sin(), 0.0, 60f32.to_radians().cos());
        let r = l.rim_a(n);
        assert!((r.x - 65535.0 / 8.0).abs() < 0.1, "{r}");
    }

    proptest::proptest! {
        /// Up to four directional lights' highlights found one a lane are
        /// the highlights found one light at a time, bit for bit.
        #[test]
        fn specular_in_lanes_is_specular_one_light_at_a_time(
            d in proptest::collection::vec(
                (proptest::array::uniform3(-1.0f32..1.0), proptest::array::uniform3(0.0f32..1.0), 0.0f32..0.5),
                1..=4,
            ),
            n in proptest::array::uniform3(-1.0f32..1.0),
            v in proptest::array::uniform3(-1.0f32..1.0),
            f0 in proptest::array::uniform3(0.0f32..1.0),
            roughness in 0.0f32..1.0,
        ) {
            let lights: Vec<Light> = d
                .iter()
                .map(|&(dir, c, ambient)| Light {
                    direction: Vec3::from(dir).normalize_or(Vec3::Z),
                    color: Rgb::new((c[0] * 255.0) as u8, (c[1] * 255.0) as u8, (c[2] * 255.0) as u8),
                    ambient,
                    ..Light::default()
                })
                .collect();
            let l = Lights::new(&lights);
            let (n, v) = (Vec3A::from(n).normalize_or_zero(), Vec3A::from(v).normalize_or_zero());
            let (f0, a2) = (Vec3A::from(f0), roughness.powi(4));
            let one_at_a_time = l.specular_from(n, v, f0, a2, |i| (Vec3A::from(l.towards[i]), 1.0));
            let lanes = l.specular_far4(n, v, f0, a2);
            proptest::prop_assert_eq!(lanes.to_array().map(f32::to_bits), one_at_a_time.to_array().map(f32::to_bits));
        }
    }

    #[test]
    fn lambert_is_ambient_plus_cosine() {
        let light = Light {
            direction: Vec3::NEG_Z,
            color: Rgb::WHITE,
            ambient: 0.2,
            ..Light::default()
        };
        let lights = Lights::new(&[light]);
        assert_eq!(lights.lambert(Vec3::Z), Vec3::ONE);
        assert_eq!(lights.lambert(Vec3::NEG_Z), Vec3::splat(0.2));
        let half = lights.lambert(Vec3::new(0.0, 0.6, 0.8));
        assert!((half.x - (0.2 + 0.8 * 0.8)).abs() < 1e-6);
        assert_eq!(Lights::new(&[]).lambert(Vec3::Z), Vec3::ZERO);
    }
}
