//! Keyframes and their interpolation: glTF's animation samplers.
//!
//! A sampler holds increasing key times and, for each key, one value of
//! `width` numbers (3 for a translation or a scale, 4 for a rotation's
//! quaternion, one a morph target for weights); a cubic spline's key holds
//! three values, in-tangent, value and out-tangent, as the format stores
//! them. Sampling takes the clip's local time, already wrapped into the
//! clip's length in f64, so that a time a million seconds into a loop is
//! as exact as one second in; the fraction of a segment is found in f64,
//! and the values are combined in f64 and rounded once to f32.
//!
//! Before its first key a sampler holds its first value; after its last,
//! its last (a channel shorter than its clip waits for the clip's end).
//! Rotations are interpolated along the sphere (LINEAR: slerp, the shorter
//! way round, as the specification says) and normalised after a cubic
//! spline.

use glam::{DQuat, Quat};

/// How values between keys are found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interpolation {
    /// The value of the last key at or before the time.
    Step,
    /// A straight line between the keys (rotations: spherical).
    Linear,
    /// A cubic Hermite spline through the keys, with the keys' tangents.
    CubicSpline,
}

impl Interpolation {
    /// The name glTF gives it.
    pub fn name(self) -> &'static str {
        match self {
            Interpolation::Step => "STEP",
            Interpolation::Linear => "LINEAR",
            Interpolation::CubicSpline => "CUBICSPLINE",
        }
    }
}

/// One channel's keyframes.
#[derive(Clone, Debug, PartialEq)]
pub struct Sampler {
    /// Key times in seconds, strictly increasing.
    times: Vec<f64>,
    /// The keys' values, `width` numbers each (three values each for a
    /// cubic spline: in-tangent, value, out-tangent).
    values: Vec<f32>,
    width: usize,
    interpolation: Interpolation,
}

/// Why keyframes were refused.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Invalid {
    /// No keys.
    Empty,
    /// A key time or value that is not a finite number.
    NotFinite,
    /// Key `k`'s time is not after key `k − 1`'s.
    NotIncreasing(usize),
    /// The values are not `keys × width` numbers (× 3 for a cubic spline).
    Count {
        /// How many numbers there are.
        values: usize,
        /// How many the keys call for.
        expected: usize,
    },
}

impl std::fmt::Display for Invalid {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Invalid::Empty => write!(f, "it has no keyframes"),
            Invalid::NotFinite => write!(f, "a key time or value is not a finite number"),
            Invalid::NotIncreasing(k) => {
                write!(f, "key {k}'s time is not after key {}'s", k - 1)
            }
            Invalid::Count { values, expected } => write!(
                f,
                "it has {values} output numbers where its keys call for {expected}"
            ),
        }
    }
}

impl Sampler {
    /// Keyframes at `times`, `width` numbers a value, checked: times finite
    /// and strictly increasing, values finite and as many as the keys and
    /// the interpolation call for.
    pub fn new(
        times: Vec<f64>,
        values: Vec<f32>,
        width: usize,
        interpolation: Interpolation,
    ) -> Result<Sampler, Invalid> {
        if times.is_empty() || width == 0 {
            return Err(Invalid::Empty);
        }
        if !times.iter().all(|t| t.is_finite()) || !values.iter().all(|v| v.is_finite()) {
            return Err(Invalid::NotFinite);
        }
        if let Some(k) = (1..times.len()).find(|&k| times[k] <= times[k - 1]) {
            return Err(Invalid::NotIncreasing(k));
        }
        let per_key = if interpolation == Interpolation::CubicSpline {
            3 * width
        } else {
            width
        };
        let expected = times.len() * per_key;
        if values.len() != expected {
            return Err(Invalid::Count {
                values: values.len(),
                expected,
            });
        }
        Ok(Sampler {
            times,
            values,
            width,
            interpolation,
        })
    }

    /// The last key's time: how long the channel runs.
    pub fn end(&self) -> f64 {
        self.times[self.times.len() - 1]
    }

    /// How many numbers a value holds.
    pub fn width(&self) -> usize {
        self.width
    }

    /// How many keys there are.
    pub fn keys(&self) -> usize {
        self.times.len()
    }

    /// The interpolation between keys.
    pub fn interpolation(&self) -> Interpolation {
        self.interpolation
    }

    /// Key `k`'s value (for a cubic spline, the value between its
    /// tangents).
    fn value(&self, k: usize) -> &[f32] {
        let w = self.width;
        match self.interpolation {
            Interpolation::CubicSpline => &self.values[(3 * k + 1) * w..(3 * k + 2) * w],
            _ => &self.values[k * w..(k + 1) * w],
        }
    }

    /// Where `t` falls: the key at or before it and the fraction of the
    /// way to the next, or a key to hold (before the first, at or after
    /// the last).
    fn segment(&self, t: f64) -> Result<(usize, f64), usize> {
        let n = self.times.len();
        if n == 1 || t <= self.times[0] {
            return Err(0);
        }
        if t >= self.times[n - 1] {
            return Err(n - 1);
        }
        // The last key at or before t: 0 ≤ k < n − 1.
        let k = self.times.partition_point(|&k| k <= t) - 1;
        let (t0, t1) = (self.times[k], self.times[k + 1]);
        Ok((k, (t - t0) / (t1 - t0)))
    }

    /// The value at local time `t` (seconds into the clip) into `out`
    /// (`width` numbers), as numbers: translations, scales and weights.
    pub fn sample(&self, t: f64, out: &mut [f32]) {
        let w = self.width;
        let (k, u) = match self.segment(t) {
            Err(k) => {
                out[..w].copy_from_slice(self.value(k));
                return;
            }
            Ok(s) => s,
        };
        match self.interpolation {
            Interpolation::Step => out[..w].copy_from_slice(self.value(k)),
            Interpolation::Linear => {
                let (a, b) = (self.value(k), self.value(k + 1));
                for i in 0..w {
                    out[i] = ((1.0 - u) * f64::from(a[i]) + u * f64::from(b[i])) as f32;
                }
            }
            Interpolation::CubicSpline => {
                let dt = self.times[k + 1] - self.times[k];
                let v = &self.values;
                // Key k: [in, value, out]; key k + 1 likewise.
                let p0 = &v[(3 * k + 1) * w..];
                let m0 = &v[(3 * k + 2) * w..];
                let m1 = &v[(3 * k + 3) * w..];
                let p1 = &v[(3 * k + 4) * w..];
                let (u2, u3) = (u * u, u * u * u);
                let h00 = 2.0 * u3 - 3.0 * u2 + 1.0;
                let h10 = u3 - 2.0 * u2 + u;
                let h01 = -2.0 * u3 + 3.0 * u2;
                let h11 = u3 - u2;
                for i in 0..w {
                    out[i] = (h00 * f64::from(p0[i])
                        + h10 * dt * f64::from(m0[i])
                        + h01 * f64::from(p1[i])
                        + h11 * dt * f64::from(m1[i])) as f32;
                }
            }
        }
    }

    /// The rotation at local time `t`: a unit quaternion (a sampler of
    /// width 4, `[x, y, z, w]`).
    pub fn sample_rotation(&self, t: f64) -> Quat {
        let q = |s: &[f32]| DQuat::from_xyzw(s[0].into(), s[1].into(), s[2].into(), s[3].into());
        match (self.segment(t), self.interpolation) {
            (Err(k), _) => q(self.value(k)).normalize().as_quat(),
            (Ok((k, _)), Interpolation::Step) => q(self.value(k)).normalize().as_quat(),
            (Ok((k, u)), Interpolation::Linear) => slerp(
                q(self.value(k)).normalize(),
                q(self.value(k + 1)).normalize(),
                u,
            )
            .as_quat(),
            (Ok(_), Interpolation::CubicSpline) => {
                let mut out = [0.0; 4];
                self.sample(t, &mut out);
                // A spline may pass through zero between keys: no rotation.
                let q = q(&out);
                if q.length_squared() > 0.0 {
                    q.normalize().as_quat()
                } else {
                    Quat::IDENTITY
                }
            }
        }
    }
}

/// Spherical linear interpolation from `a` to `b` (unit quaternions) by
/// `u`, the shorter way round, in f64.
fn slerp(a: DQuat, b: DQuat, u: f64) -> DQuat {
    let (b, d) = match a.dot(b) {
        d if d < 0.0 => (-b, -d),
        d => (b, d),
    };
    if d > 1.0 - 1e-12 {
        // Nearly the same: a straight line is the arc.
        return (a * (1.0 - u) + b * u).normalize();
    }
    let theta = d.acos();
    let s = theta.sin();
    (a * (((1.0 - u) * theta).sin() / s) + b * ((u * theta).sin() / s)).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(s: &Sampler, t: f64) -> Vec<f32> {
        let mut out = vec![0.0; s.width()];
        s.sample(t, &mut out);
        out
    }

    #[test]
    fn step_holds_each_key_until_the_next() {
        let s = Sampler::new(
            vec![0.0, 1.0, 2.0],
            vec![1.0, 5.0, -3.0],
            1,
            Interpolation::Step,
        )
        .unwrap();
        assert_eq!(at(&s, 0.0), [1.0]);
        assert_eq!(at(&s, 0.999), [1.0]);
        assert_eq!(at(&s, 1.0), [5.0]);
        assert_eq!(at(&s, 1.5), [5.0]);
        assert_eq!(at(&s, 2.0), [-3.0]);
        // Before the first key and after the last, held.
        assert_eq!(at(&s, -1.0), [1.0]);
        assert_eq!(at(&s, 7.0), [-3.0]);
    }

    #[test]
    fn linear_is_exact_at_keys_and_a_straight_line_between() {
        let s = Sampler::new(
            vec![0.0, 2.0, 4.0],
            vec![0.0, 10.0, 4.0, 8.0, -4.0, 0.0],
            2,
            Interpolation::Linear,
        )
        .unwrap();
        assert_eq!(at(&s, 0.0), [0.0, 10.0]);
        assert_eq!(at(&s, 2.0), [4.0, 8.0]);
        assert_eq!(at(&s, 4.0), [-4.0, 0.0]);
        // A quarter of the first segment: 0 + 4/4, 10 − 2/4.
        assert_eq!(at(&s, 0.5), [1.0, 9.5]);
        // Three quarters of the second: 4 − 8·3/4, 8 − 8·3/4.
        assert_eq!(at(&s, 3.5), [-2.0, 2.0]);
    }

    #[test]
    fn a_cubic_spline_passes_its_keys_with_their_tangents() {
        // One number; keys at 0 and 2 with values 1 and 3, out-tangent of
        // the first 4, in-tangent of the second −2 (per second).
        let s = Sampler::new(
            vec![0.0, 2.0],
            vec![9.0, 1.0, 4.0, -2.0, 3.0, 9.0],
            1,
            Interpolation::CubicSpline,
        )
        .unwrap();
        assert_eq!(at(&s, 0.0), [1.0]);
        assert_eq!(at(&s, 2.0), [3.0]);
        // Halfway, u = 1/2: h00 = h01 = 1/2, h10 = 1/8, h11 = −1/8, and the
        // tangents scaled by the segment's 2 s: 1/2 + 1/8·8 + 3/2 − 1/8·(−4)
        // = 1/2 + 1 + 3/2 + 1/2 = 3.5.
        assert_eq!(at(&s, 1.0), [3.5]);
        // A quarter, u = 1/4: h00 = 27/32, h10 = 9/64, h01 = 5/32,
        // h11 = −3/64: 27/32 + 9/64·8 + 15/32 − 3/64·(−4)
        // = 27/32 + 36/32 + 15/32 + 6/32 = 84/32 = 2.625.
        assert_eq!(at(&s, 0.5), [2.625]);
    }

    #[test]
    fn a_linear_rotation_turns_along_the_shorter_arc() {
        let half = std::f32::consts::FRAC_1_SQRT_2;
        // 0° and 90° about z; the second given with its sign flipped (the
        // same rotation), which slerp must take the short way.
        let s = Sampler::new(
            vec![0.0, 1.0],
            vec![0.0, 0.0, 0.0, 1.0, 0.0, 0.0, -half, -half],
            4,
            Interpolation::Linear,
        )
        .unwrap();
        let q = s.sample_rotation(0.5);
        let want = Quat::from_rotation_z(std::f32::consts::FRAC_PI_4);
        assert!(q.dot(want).abs() > 1.0 - 1e-6, "{q:?}");
        assert_eq!(s.sample_rotation(0.0), Quat::IDENTITY);
        // A third of the way: 30°.
        let q = s.sample_rotation(1.0 / 3.0);
        let want = Quat::from_rotation_z(std::f32::consts::FRAC_PI_6);
        assert!(q.dot(want).abs() > 1.0 - 1e-6, "{q:?}");
    }

    #[test]
    fn bad_keyframes_are_refused_with_the_reason() {
        let lin = Interpolation::Linear;
        assert_eq!(
            Sampler::new(vec![0.0, 1.0, 1.0], vec![0.0; 3], 1, lin),
            Err(Invalid::NotIncreasing(2))
        );
        assert_eq!(
            Sampler::new(vec![0.0, f64::NAN], vec![0.0; 2], 1, lin),
            Err(Invalid::NotFinite)
        );
        assert_eq!(
            Sampler::new(vec![0.0, 1.0], vec![0.0; 3], 1, lin),
            Err(Invalid::Count {
                values: 3,
                expected: 2
            })
        );
        assert_eq!(
            Sampler::new(vec![0.0, 1.0], vec![0.0; 2], 1, Interpolation::CubicSpline),
            Err(Invalid::Count {
                values: 2,
                expected: 6
            })
        );
        assert_eq!(
            Sampler::new(Vec::new(), Vec::new(), 1, lin),
            Err(Invalid::Empty)
        );
    }
}
