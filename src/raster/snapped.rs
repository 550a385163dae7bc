//! A snapped triangle the rasterizer accepts: the one place a fixed-point
//! triangle's signed area is computed and its range, zero area and
//! culling decided. Every fixed-point set-up ([`Setup`], `SmallSetup`)
//! derives from one, so they cannot disagree on which triangles they
//! draw; the renderer's lean path builds one from the vertex stage's
//! snapped vertices without the range check they have already passed.

use super::*;

/// A triangle snapped to 1/256 of a sample ([`FixedPoint`]) and accepted
/// by the rasterizer: every coordinate within ±[`MAX_COORD`] samples, an
/// area that is not zero, a winding that is not culled.
///
/// ```
/// use rastty::fixed::FixedPoint;
/// use rastty::raster::{Rejected, SnappedTriangle};
/// use rastty::scene::Cull;
///
/// let p = [[0.0, 0.0], [4.0, 0.0], [0.0, 4.0]].map(|v| FixedPoint::snap(v).unwrap());
/// let t = SnappedTriangle::new(p, Cull::Back).unwrap();
/// assert!(t.ccw());
/// assert_eq!(t.signed_area2(), 16 * 256 * 256);
/// let clockwise = [p[0], p[2], p[1]];
/// assert_eq!(SnappedTriangle::new(clockwise, Cull::Back), Err(Rejected::Culled));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SnappedTriangle {
    p: [FixedPoint; 3],
    area2: i64,
}

impl SnappedTriangle {
    /// Accepts three snapped vertices, or says why not: a coordinate
    /// beyond ±[`MAX_COORD`] samples, no area, or a culled winding (in
    /// that order).
    #[inline(always)]
    pub fn new(p: [FixedPoint; 3], cull: Cull) -> Result<SnappedTriangle, Rejected> {
        if !snapped_in_range(&p) {
            return Err(Rejected::OutOfRange);
        }
        SnappedTriangle::in_range(p, cull)
    }

    /// [`SnappedTriangle::new`] of vertices the vertex stage snapped, each
    /// coordinate within range already (`FixedPoint::snap` accepts no
    /// other; checked in debug builds).
    #[inline(always)]
    pub(crate) fn in_range(p: [FixedPoint; 3], cull: Cull) -> Result<SnappedTriangle, Rejected> {
        SnappedTriangle::culled_by(p, Culling::of(cull))
    }

    /// [`SnappedTriangle::in_range`] with the culling found once for many
    /// triangles ([`Culling::of`]).
    #[inline(always)]
    pub(crate) fn culled_by(p: [FixedPoint; 3], c: Culling) -> Result<SnappedTriangle, Rejected> {
        debug_assert!(snapped_in_range(&p));
        let area2 = signed_area2(&p);
        if area2 == 0 {
            return Err(Rejected::Degenerate);
        }
        if c.culls(area2) {
            return Err(Rejected::Culled);
        }
        Ok(SnappedTriangle { p, area2 })
    }

    /// The vertices, as given.
    pub fn vertices(&self) -> [FixedPoint; 3] {
        self.p
    }

    /// Twice the signed area in fixed-point units squared: positive when
    /// counter-clockwise, never zero.
    pub fn signed_area2(&self) -> i64 {
        self.area2
    }

    /// Whether the triangle is counter-clockwise on screen (front-facing).
    pub fn ccw(&self) -> bool {
        self.area2 > 0
    }
}

/// Twice the signed area of three snapped points within range, positive
/// when counter-clockwise: the first edge's function at the third point.
#[inline(always)]
pub(crate) fn signed_area2(p: &[FixedPoint; 3]) -> i64 {
    Edge::new(p[0], p[1]).at(p[2].x.0, p[2].y.0)
}

/// A [`Cull`] as two numbers, so that a face's test is one comparison: a
/// triangle of signed area `a` (never zero) is culled when
/// `a ^ flip < below`. Back: `a < 0`; front: `!a < 0`, which is `a > 0`;
/// none: below `i64::MIN`, never.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Culling {
    flip: i64,
    below: i64,
}

impl Culling {
    /// The culling of `cull`.
    pub(crate) fn of(cull: Cull) -> Culling {
        match cull {
            Cull::None => Culling {
                flip: 0,
                below: i64::MIN,
            },
            Cull::Back => Culling { flip: 0, below: 0 },
            Cull::Front => Culling { flip: -1, below: 0 },
        }
    }

    /// Whether a triangle of signed area `area2` (not zero) is culled.
    #[inline(always)]
    pub(crate) fn culls(self, area2: i64) -> bool {
        area2 ^ self.flip < self.below
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The one comparison culls what the winding rule says, for areas of
    /// either sign out to the largest.
    #[test]
    fn culling_is_the_winding_rule() {
        let areas = [i64::MIN + 1, -(1 << 61), -2, -1, 1, 2, 1 << 61, i64::MAX];
        for cull in [Cull::None, Cull::Back, Cull::Front] {
            let c = Culling::of(cull);
            for a in areas {
                let rule = match cull {
                    Cull::None => false,
                    Cull::Back => a < 0,
                    Cull::Front => a > 0,
                };
                assert_eq!(c.culls(a), rule, "{cull:?} {a}");
            }
        }
    }
}
