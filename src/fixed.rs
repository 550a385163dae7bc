//! Fixed point: screen coordinates snapped to 1/256 of a sample.
//!
//! The clip stage snaps the vertices it makes and the rasterizer evaluates
//! its edge functions on snapped coordinates, so both share these types.
//! Snapping is round-to-nearest with ties away from zero, done without a
//! library call and exactly (see [`Fixed::snap`]); a coordinate that is not
//! finite or lies beyond [`MAX_COORD`] does not snap, which is how the
//! rasterizer's `i64` bit-width argument is kept (see [`crate::raster`]).
//! The vertex stage snaps four vertices at once (`FixedPoint::snap4`):
//! truncation and the step of one in `i32` lanes (the `wide` crate, SSE2
//! where there is SSE2), which the range allows, with the same results as
//! one at a time (a test compares them).

use glam::Vec4;
use wide::{bytemuck::cast, f32x4, i32x4};

/// Fractional bits of a snapped coordinate.
pub const FRAC_BITS: u32 = 8;
/// One sample in fixed-point units.
pub const ONE: i64 = 1 << FRAC_BITS;
/// Largest vertex coordinate magnitude accepted, in samples (2^21).
pub const MAX_COORD: f32 = (1u32 << 21) as f32;

/// A coordinate in samples, snapped to 1/256 of a sample.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Fixed(pub(crate) i64);

impl Fixed {
    /// Snaps a coordinate in samples to the nearest 1/256 (ties away from
    /// zero). `None` for NaN, infinity, or a magnitude beyond [`MAX_COORD`].
    pub fn snap(v: f32) -> Option<Fixed> {
        // NaN and the infinities fail the comparison too.
        if v.abs() <= MAX_COORD {
            Some(Fixed(round_half_away(v * ONE as f32)))
        } else {
            None
        }
    }

    /// Snaps a coordinate given in f64 (the clip path's), as
    /// [`Fixed::snap`] does.
    pub fn snap64(v: f64) -> Option<Fixed> {
        if v.is_finite() && v.abs() <= MAX_COORD as f64 {
            // Exact: a power-of-two scale, then truncation and a difference
            // of nearby values, as in `round_half_away`.
            let s = v * ONE as f64;
            let t = s as i64;
            let frac = s - t as f64;
            Some(Fixed(t + (frac >= 0.5) as i64 - (frac <= -0.5) as i64))
        } else {
            None
        }
    }

    /// The centre of sample `i`: `i + 0.5`.
    pub const fn sample_centre(i: u32) -> Fixed {
        Fixed(i as i64 * ONE + ONE / 2)
    }

    /// The coordinate in samples.
    pub fn to_f32(self) -> f32 {
        self.0 as f32 / ONE as f32
    }
}

/// `s` rounded to the nearest integer, ties away from zero, as
/// `f32::round` does but without its library call (x86-64's baseline has no
/// rounding instruction). Exact: `s · 256` is exact in f32 (a power-of-two
/// scale), truncation is exact, and so is `s − trunc(s)`, a difference of
/// two floats less than 1 apart in the same binade or below.
#[inline(always)]
fn round_half_away(s: f32) -> i64 {
    let t = s as i64;
    let frac = s - t as f32;
    t + (frac >= 0.5) as i64 - (frac <= -0.5) as i64
}

/// [`round_half_away`] of `v · 256` in four integer lanes, for `|v|` at
/// most [`MAX_COORD`] (so that each fits in an `i32`, and the fast
/// truncation, SSE2's where there is SSE2, is exact).
#[inline(always)]
fn round4(v: Vec4) -> i32x4 {
    let s = f32x4::from((v * Vec4::splat(ONE as f32)).to_array());
    let t = s.fast_trunc_int();
    let frac = s - t.round_float();
    // All ones (−1) in a lane whose fraction takes it one up (down).
    let up: i32x4 = cast(frac.simd_ge(f32x4::splat(0.5)));
    let down: i32x4 = cast(frac.simd_le(f32x4::splat(-0.5)));
    t - up + down
}

/// Four snapped points, in fixed-point units, their x and y each in the
/// lanes of an `i32` vector: what [`FixedPoint::snap4`] gives, for the
/// vertex stage to read both the points and their centre keys from
/// (`raster::CentreKey::of4`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct SnappedLanes {
    pub(crate) x: i32x4,
    pub(crate) y: i32x4,
}

impl SnappedLanes {
    /// The four points' coordinates in pairs, `[x0, y0, x1, y1]` and
    /// `[x2, y2, x3, y3]`: as the vertex stage keeps them, and as their
    /// centre keys are found (`raster::CentreKey::of4`).
    #[inline(always)]
    pub(crate) fn pairs(&self) -> [i32x4; 2] {
        let (x, y) = (self.x.to_array(), self.y.to_array());
        [
            i32x4::new([x[0], y[0], x[1], y[1]]),
            i32x4::new([x[2], y[2], x[3], y[3]]),
        ]
    }

    /// The four points (for the tests, which compare them with
    /// [`FixedPoint::snap`]'s).
    #[cfg(test)]
    pub(crate) fn points(&self) -> [FixedPoint; 4] {
        let (x, y) = (self.x.to_array(), self.y.to_array());
        std::array::from_fn(|i| FixedPoint {
            x: Fixed(i64::from(x[i])),
            y: Fixed(i64::from(y[i])),
        })
    }
}

/// A snapped point on the sample grid.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct FixedPoint {
    /// x, in samples.
    pub x: Fixed,
    /// y, in samples (up).
    pub y: Fixed,
}

impl FixedPoint {
    /// Snaps a point given in samples; `None` when either coordinate cannot
    /// be snapped (see [`Fixed::snap`]).
    pub fn snap(p: [f32; 2]) -> Option<FixedPoint> {
        Some(FixedPoint {
            x: Fixed::snap(p[0])?,
            y: Fixed::snap(p[1])?,
        })
    }

    /// [`FixedPoint::snap`] for four points, their x and y each in the
    /// lanes of a vector; `None` when any of them cannot be snapped. The
    /// same numbers: `v · 256` is exact, truncation in lanes is exact (the
    /// magnitudes are below 2^29, and from 2^23 on a float has no fraction),
    /// and so are the fraction and the step of one where there is one
    /// (below 2^23, in integer lanes).
    #[inline(always)]
    pub(crate) fn snap4(x: Vec4, y: Vec4) -> Option<SnappedLanes> {
        let limit = Vec4::splat(MAX_COORD);
        // NaN and the infinities fail the comparison too.
        if !(x.abs().cmple(limit) & y.abs().cmple(limit)).all() {
            return None;
        }
        Some(SnappedLanes {
            x: round4(x),
            y: round4(y),
        })
    }

    /// Snaps a point given in samples, in f64.
    pub fn snap64(p: [f64; 2]) -> Option<FixedPoint> {
        Some(FixedPoint {
            x: Fixed::snap64(p[0])?,
            y: Fixed::snap64(p[1])?,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fast_rounding_is_f32_round() {
        let mut x = 0x1234_5678u32;
        for _ in 0..100_000 {
            // xorshift over coordinates within the accepted range.
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            let v = (x as f32 / u32::MAX as f32 - 0.5) * 2.0 * MAX_COORD;
            for s in [v * ONE as f32, (v * 8.0).round() / 16.0] {
                assert_eq!(round_half_away(s), s.round() as i64, "{s}");
            }
        }
        for s in [
            0.5f32, -0.5, 1.5, -1.5, 2.4999998, -2.4999998, 8388607.5, -8388607.5, 0.0, -0.0,
        ] {
            assert_eq!(round_half_away(s), s.round() as i64, "{s}");
        }
    }

    #[test]
    fn four_snapped_in_lanes_are_each_snapped_alone() {
        let mut x = 0x2545_f491u32;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            let v = (x as f32 / u32::MAX as f32 - 0.5) * 2.0 * MAX_COORD;
            // Every other one a tie: a multiple of half of 1/256.
            if x.is_multiple_of(2) {
                v
            } else {
                (v * 512.0).round() / 512.0
            }
        };
        let special = [
            0.5 / 256.0,
            -0.5 / 256.0,
            0.0,
            -0.0,
            MAX_COORD,
            -MAX_COORD,
            8388607.5 / 256.0,
        ];
        for i in 0..20_000 {
            let mut xs: [f32; 4] = std::array::from_fn(|_| next());
            let ys: [f32; 4] = std::array::from_fn(|_| next());
            xs[i % 4] = special[i % special.len()];
            let alone: [Option<FixedPoint>; 4] =
                std::array::from_fn(|k| FixedPoint::snap([xs[k], ys[k]]));
            let lanes =
                FixedPoint::snap4(Vec4::from_array(xs), Vec4::from_array(ys)).map(|l| l.points());
            assert_eq!(
                lanes,
                alone
                    .iter()
                    .copied()
                    .collect::<Option<Vec<_>>>()
                    .map(|v| { [v[0], v[1], v[2], v[3]] }),
                "{xs:?} {ys:?}"
            );
        }
        // Beyond the range or not finite in one lane: none of the four.
        for bad in [MAX_COORD * 1.01, f32::NAN, f32::INFINITY] {
            assert_eq!(
                FixedPoint::snap4(Vec4::new(0.0, bad, 0.0, 0.0), Vec4::ZERO).map(|l| l.points()),
                None
            );
            assert_eq!(
                FixedPoint::snap4(Vec4::ZERO, Vec4::new(0.0, 0.0, 0.0, -bad)).map(|l| l.points()),
                None
            );
        }
    }

    #[test]
    fn snap_rounds_to_the_nearest_256th() {
        assert_eq!(Fixed::snap(1.0), Some(Fixed(256)));
        assert_eq!(Fixed::snap(0.5 / 256.0), Some(Fixed(1)));
        assert_eq!(Fixed::snap(0.49 / 256.0), Some(Fixed(0)));
        assert_eq!(Fixed::snap(-1.5 / 256.0), Some(Fixed(-2)));
        assert_eq!(Fixed::snap(f32::NAN), None);
        assert_eq!(Fixed::snap(f32::INFINITY), None);
        assert_eq!(Fixed::snap(MAX_COORD * 2.0), None);
        assert_eq!(Fixed::sample_centre(3), Fixed(3 * 256 + 128));
    }
}
