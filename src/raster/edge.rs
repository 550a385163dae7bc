//! Edge functions in fixed point and what is known of a snapped triangle
//! before its set-up: where samples start and end, the centre keys that
//! tell an empty box at once, the extent and its clamping to the grid.

use super::*;

/// One edge function `E(p) = (q − p0) × (p − p0)` in fixed point, oriented
/// so that the triangle's interior is positive.
#[derive(Clone, Copy, Debug)]
pub(super) struct Edge {
    pub(super) from: FixedPoint,
    /// `q − p0`.
    pub(super) dx: i64,
    pub(super) dy: i64,
    /// Smallest value of `E` that counts as inside: 0 on a top or left edge,
    /// 1 elsewhere.
    pub(super) min: i64,
}

impl Edge {
    /// An edge that accepts nothing, for a set-up triangle whose bounding
    /// box holds no sample centre (its edges are never evaluated).
    pub(super) const NONE: Edge = Edge {
        from: FixedPoint {
            x: Fixed(0),
            y: Fixed(0),
        },
        dx: 0,
        dy: 0,
        min: 1,
    };

    pub(super) fn new(from: FixedPoint, to: FixedPoint) -> Edge {
        let dx = to.x.0 - from.x.0;
        let dy = to.y.0 - from.y.0;
        // Counter-clockwise, y up: a left edge runs down, a top edge is
        // horizontal and runs towards −x.
        let top_left = dy < 0 || (dy == 0 && dx < 0);
        Edge {
            from,
            dx,
            dy,
            min: if top_left { 0 } else { 1 },
        }
    }

    /// `E` at a point, directly (two multiplications).
    #[inline(always)]
    pub(super) fn at(&self, px: i64, py: i64) -> i64 {
        self.dx * (py - self.from.y.0) - self.dy * (px - self.from.x.0)
    }

    /// Change of `E` for one sample step in +x.
    pub(super) fn step_x(&self) -> i64 {
        -self.dy * ONE
    }

    /// Change of `E` for one sample step in +y.
    pub(super) fn step_y(&self) -> i64 {
        self.dx * ONE
    }
}

/// The first sample whose centre `i·256 + 128` is at or right of (above)
/// `lo`, in fixed point: a bounding box's first candidate.
#[inline(always)]
pub(super) fn first_sample(lo: i64) -> i64 {
    (lo - ONE / 2 + ONE - 1).div_euclid(ONE)
}

/// The last sample whose centre is at or left of (below) `hi`.
#[inline(always)]
pub(super) fn last_sample(hi: i64) -> i64 {
    (hi - ONE / 2).div_euclid(ONE)
}

/// Whether a snapped triangle's bounding box, clamped to `grid`'s columns
/// and `band`'s rows, holds no sample centre (the same box
/// [`Setup::of`] finds): the slow twin [`CentreKey`]'s test is
/// checked against.
#[cfg(test)]
pub(super) fn box_is_empty(p: &[FixedPoint; 3], grid: Grid, band: Band) -> bool {
    let [x0, x1, y0, y1] = clamped_box(&extent(p), grid, band);
    x0 > x1 || y0 > y1
}

/// Where a snapped point lies among the sample centres, for telling at
/// once that a triangle's bounding box holds none, before its extent or
/// area is looked at (many of the triangles of a detailed model seen
/// small). On each axis, twice the index of the last centre at or before
/// the point, plus one if the point is on it: three vertices whose keys
/// on an axis are equal and even lie strictly between two neighbouring
/// centres there, so their box holds no centre (nor does it once clamped to
/// a grid or a band). Each axis in 16 bits, x in the low half (as the
/// vertex stage keeps a point's coordinates, x first), clamped to `i16`'s
/// range for a point more than 16,383 samples from the origin (in the
/// guard band): the largest key, 32,767, is odd, so it never tells a box
/// empty, and the least, −32,768, is kept only by points left of (below)
/// the grid, so three of them do hold no centre of it. Computed once per
/// vertex by the vertex stage, four at a time in integer lanes
/// ([`CentreKey::of4`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct CentreKey(u32);

impl CentreKey {
    /// The key of a vertex outside a clip plane or not snapped: odd on
    /// both axes, so a face with such a vertex is never told empty (and
    /// the face loop tells an empty box before it looks at outcodes).
    pub(crate) const NEVER_EMPTY: CentreKey = CentreKey(u32::MAX);

    /// The key of a snapped point.
    #[inline(always)]
    pub(crate) fn of(p: FixedPoint) -> CentreKey {
        let axis = |v: i64| {
            let d = v - ONE / 2;
            // An arithmetic shift is a division rounding down.
            let k = (d >> FRAC_BITS) * 2 + (d & (ONE - 1) == 0) as i64;
            k.clamp(i16::MIN.into(), i16::MAX.into()) as u16 as u32
        };
        CentreKey(axis(p.x.0) | axis(p.y.0) << 16)
    }

    /// The keys of four snapped points, computed in integer lanes from
    /// their coordinates in pairs ([`SnappedLanes::pairs`]): the same as
    /// [`CentreKey::of`] of each (the coordinates fit in an `i32`, and an
    /// arithmetic shift is the same division in either width). Both axes
    /// at once: a pair's two lanes are one point's x and y.
    #[inline(always)]
    pub(crate) fn of4(pairs: [i32x4; 2]) -> [CentreKey; 4] {
        use wide::bytemuck::cast;
        let axis = |v: i32x4| -> i32x4 {
            let d = v - i32x4::splat((ONE / 2) as i32);
            // All ones (−1) where the point is on a centre.
            let on = (d & i32x4::splat((ONE - 1) as i32)).simd_eq(i32x4::ZERO);
            ((d >> FRAC_BITS) << 1) - on
        };
        // SSE2's saturating pack, the clamp of [`CentreKey::of`], leaves
        // each point's x and y side by side: its key, x in the low half.
        let k = wide::i16x8::from_i32x8_saturate(cast(pairs.map(axis)));
        cast::<_, [u32; 4]>(k).map(CentreKey)
    }

    /// Whether the keys of a triangle's vertices show that its bounding box
    /// holds no sample centre (`false` says nothing).
    #[inline(always)]
    pub(crate) fn box_is_empty(k: [CentreKey; 3]) -> bool {
        let [a, b, c] = k.map(|k| k.0);
        // Zero in an axis's half exactly when the three are equal there and
        // even.
        let m = (a ^ b) | (a ^ c) | (a & 0x0001_0001);
        m >> 16 == 0 || m & 0xffff == 0
    }
}

/// Whether every coordinate is within ±[`MAX_COORD`] samples, as the
/// vertex stage's snapped vertices are: what [`SnappedTriangle::new`]
/// checks first.
#[inline(always)]
pub(super) fn snapped_in_range(p: &[FixedPoint; 3]) -> bool {
    let range = -(MAX_COORD as i64) * ONE..=(MAX_COORD as i64) * ONE;
    p.iter()
        .all(|q| range.contains(&q.x.0) && range.contains(&q.y.0))
}

/// A snapped triangle's extent in fixed point: `[min x, max x, min y,
/// max y]`.
#[inline(always)]
pub(super) fn extent(p: &[FixedPoint; 3]) -> [i64; 4] {
    let (min_x, max_x) = min_max(p.map(|q| q.x.0));
    let (min_y, max_y) = min_max(p.map(|q| q.y.0));
    [min_x, max_x, min_y, max_y]
}

/// A snapped triangle's bounding box in samples, `[x0, x1, y0, y1]`
/// inclusive, clamped to `grid`'s columns and `band`'s rows; empty when
/// `x0 > x1` or `y0 > y1`.
#[inline(always)]
pub(super) fn clamped_box(extent: &[i64; 4], grid: Grid, band: Band) -> [i64; 4] {
    let [min_x, max_x, min_y, max_y] = *extent;
    [
        first_sample(min_x).max(0),
        last_sample(max_x).min(grid.width as i64 - 1),
        first_sample(min_y).max(band.y0 as i64),
        last_sample(max_y).min(band.y1 as i64 - 1),
    ]
}

/// A triangle's edges, each oriented so that the interior is positive, and
/// the vertex order they follow: `edges[k]` is opposite vertex `order[k]`.
#[inline(always)]
pub(super) fn oriented(p: &[FixedPoint; 3], ccw: bool) -> ([Edge; 3], [usize; 3]) {
    // Start from the lowest vertex (then leftmost): ABC, BCA and CAB are
    // then one and the same triangle to everything below, so a frame does
    // not depend on which vertex a file lists first. The first of the
    // lowest (then leftmost), as `min_by_key` would find it, in two
    // comparisons.
    let below = |a: usize, b: usize| (p[a].y.0, p[a].x.0) < (p[b].y.0, p[b].x.0);
    let r = if below(1, 0) { 1 } else { 0 };
    let r = if below(2, r) { 2 } else { r };
    let order = [r, (r + 1) % 3, (r + 2) % 3];
    (edges(&order.map(|i| p[i]), ccw), order)
}

/// The edges of a triangle whose vertices are in set-up order: edge `i`
/// is opposite vertex `i`, oriented so that the interior is positive.
#[inline(always)]
pub(super) fn edges(p: &[FixedPoint; 3], ccw: bool) -> [Edge; 3] {
    // Edge opposite vertex i runs from i+1 to i+2 when counter-clockwise; a
    // clockwise triangle takes each edge the other way round.
    let edge = |i: usize| {
        let (a, b) = (p[(i + 1) % 3], p[(i + 2) % 3]);
        if ccw {
            Edge::new(a, b)
        } else {
            Edge::new(b, a)
        }
    };
    [edge(0), edge(1), edge(2)]
}

/// An inclusive box of samples, `[x0, x1] × [y0, y1]` (clamped to the
/// grid, so not negative where not empty), as a [`Rect`].
#[inline(always)]
pub(super) fn box_rect(x0: i64, x1: i64, y0: i64, y1: i64) -> Rect {
    if x0 > x1 || y0 > y1 {
        Rect::EMPTY
    } else {
        Rect {
            x0: x0 as u32,
            x1: x1 as u32 + 1,
            y0: y0 as u32,
            y1: y1 as u32 + 1,
        }
    }
}

pub(super) fn min_max(v: [i64; 3]) -> (i64, i64) {
    (v[0].min(v[1]).min(v[2]), v[0].max(v[1]).max(v[2]))
}
