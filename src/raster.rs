//! Stage 4: rasterization as sampling, exact.
//!
//! `inside(tri, x, y)` is the notes' three cross products, evaluated at the
//! sample centre `(x + 0.5, y + 0.5)`. To make it exact, as D3D10+ and
//! Vulkan are, every vertex is snapped once to 1/256 of a sample
//! ([`Fixed`], 8 fractional bits, round to nearest) and the edge functions
//! are evaluated in `i64`:
//!
//! * Samples exactly on an edge are decided by the **top-left rule** (y up,
//!   so "top" is larger y): with the triangle counter-clockwise, an edge is
//!   *top* if it is horizontal and runs towards −x, *left* if it runs
//!   towards −y. A sample on a top or left edge is inside; on any other edge
//!   it is not. Two triangles sharing an edge see it with opposite
//!   directions, so exactly one of them owns each sample on it: no cracks,
//!   no double hits.
//! * Either winding is accepted: a clockwise triangle's edges are taken in
//!   the reverse direction, which is the same triangle. Culling by winding is
//!   a separate, explicit [`Cull`] choice.
//! * A triangle of zero area after snapping draws nothing; one with a NaN or
//!   infinite coordinate, or one beyond [`MAX_COORD`], is dropped and
//!   counted in [`RasterStats`].
//!
//! **Bit widths.** Vertices lie within ±[`MAX_COORD`] = ±2^21 samples, so a
//! snapped coordinate is below 2^29 in magnitude; sample centres inside the
//! grid (at most [`MAX_GRID`] = 2^16 a side) are too. A difference of two
//! coordinates is below 2^30, each product in
//! `E(p) = (b.x − a.x)(p.y − a.y) − (b.y − a.y)(p.x − a.x)` below 2^60, and
//! `E` itself below 2^61: two bits to spare in an `i64`. The incremental
//! traversal only ever holds values of `E` at sample centres inside the
//! grid (or one step past its edge), so the same bound covers it. The clip
//! stage keeps every vertex inside ±`MAX_COORD` (its guard band); the
//! rasterizer checks it anyway and drops what is outside rather than risk an
//! overflow.
//!
//! **Traversals** ([`Traversal`]), all visiting the same samples in the same
//! order (rows bottom to top, left to right) and so giving identical
//! coverage: `Scan` tests every sample of the grid (the notes' first method),
//! `BoundingBox` only those in the triangle's bounding box (the second),
//! `Incremental` steps the three edge values by constant deltas over the
//! bounding box (the third: two additions per edge per sample instead of
//! two multiplications), and `Spans`, the default, visits only the covered
//! samples of each row: along a row each edge value is linear in the
//! column, so each edge bounds the covered run from one side, found exactly
//! by one integer division per edge and row, and the values are stepped
//! along the run. A large triangle's box is mostly outside it (`rastty
//! render --cols 1000 --rows 300 --explain`: the torus's boxes hold 281,866
//! samples for 103,164 covered), which `Spans` skips for a division an edge
//! a row instead of a test a sample. Every traversal
//! counts the samples whose coverage it decided: those of the grid for
//! `Scan`, of the bounding box for the others, so that the counts do not
//! depend on the traversal of a triangle's part in a band.
//!
//! **Small triangles.** Most triangles of a detailed model seen small have
//! a bounding box of a few samples and cover none of them; many hold
//! no sample centre at all, which the vertices' centre keys (computed once
//! per vertex) tell in a few comparisons, once the signed area (culling,
//! zero area) is known. `SmallSetup`
//! tests each sample of a box of at most [`SMALL_BOX`] once, at set-up,
//! and keeps only the vertices and a bit per covered sample: a triangle
//! that covers nothing is known without a [`Setup`] built (a couple of
//! hundred bytes) or walked, and the weights of the few it covers are
//! found again from the vertices. It finds what the set-up and the
//! bounding-box or incremental walk find (a property test compares them),
//! but not what the full-grid scan counts, so that traversal never uses it.
//!
//! The rasterizer knows nothing of colours or glyphs: it reports each
//! covered sample, with its three edge values (the unnormalised barycentric
//! weights), to a closure.

use crate::fixed::{FRAC_BITS, Fixed, FixedPoint, MAX_COORD, ONE, SnappedLanes};
use crate::scene::Cull;
use crate::transform::{Band, Grid, MAX_GRID, Rect};
use wide::i32x4;

/// How the rasterizer walks the samples. All give identical coverage.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Traversal {
    /// Every sample of the grid.
    Scan,
    /// Every sample of the triangle's bounding box, each edge evaluated
    /// afresh.
    BoundingBox,
    /// The bounding box with the edge values stepped by constant deltas.
    Incremental,
    /// Each row of the bounding box, only where it is covered: the run of
    /// covered samples is found from the edge values at the row's start
    /// (each edge bounds it from one side, by an exact integer division),
    /// and the values are stepped along it. The samples the incremental
    /// walk finds, with the same weights, visiting none it does not cover.
    #[default]
    Spans,
}

crate::choice::choice!(Traversal {
    Scan => "scan": "Every sample of the grid",
    BoundingBox => "bounding-box": "Every sample of the triangle's bounding box, each edge evaluated afresh",
    Incremental => "incremental": "The bounding box with the edge values stepped by constant deltas",
    Spans => "spans": "Each row of the bounding box, only where it is covered: the run of covered samples is found from the edge values at the row's start (each edge bounds it from one side, by an exact integer division), and the values are stepped along it",
});

/// What the rasterizer did, summed over the triangles it was given.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RasterStats {
    /// Triangles set up and walked.
    pub triangles_drawn: u64,
    /// Dropped for a NaN or infinite coordinate.
    pub dropped_non_finite: u64,
    /// Dropped for a coordinate beyond [`MAX_COORD`].
    pub dropped_out_of_range: u64,
    /// Zero area after snapping.
    pub dropped_degenerate: u64,
    /// Dropped by [`Cull`].
    pub culled: u64,
    /// Samples whose coverage was decided: each sample of the grid
    /// ([`Traversal::Scan`]) or of the triangle's bounding box (the
    /// others; [`Traversal::Spans`] decides a row's samples at once, from
    /// the edge values at its start). The same for every split of the frame
    /// into bands.
    pub samples_tested: u64,
    /// Samples found inside.
    pub samples_covered: u64,
}

impl RasterStats {
    /// Adds another's counts to these.
    pub fn add(&mut self, o: &RasterStats) {
        self.triangles_drawn += o.triangles_drawn;
        self.dropped_non_finite += o.dropped_non_finite;
        self.dropped_out_of_range += o.dropped_out_of_range;
        self.dropped_degenerate += o.dropped_degenerate;
        self.culled += o.culled;
        self.samples_tested += o.samples_tested;
        self.samples_covered += o.samples_covered;
    }
}

/// One edge function `E(p) = (q − p0) × (p − p0)` in fixed point, oriented
/// so that the triangle's interior is positive.
#[derive(Clone, Copy, Debug)]
struct Edge {
    from: FixedPoint,
    /// `q − p0`.
    dx: i64,
    dy: i64,
    /// Smallest value of `E` that counts as inside: 0 on a top or left edge,
    /// 1 elsewhere.
    min: i64,
}

impl Edge {
    /// An edge that accepts nothing, for a set-up triangle whose bounding
    /// box holds no sample centre (its edges are never evaluated).
    const NONE: Edge = Edge {
        from: FixedPoint {
            x: Fixed(0),
            y: Fixed(0),
        },
        dx: 0,
        dy: 0,
        min: 1,
    };

    fn new(from: FixedPoint, to: FixedPoint) -> Edge {
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
    fn at(&self, px: i64, py: i64) -> i64 {
        self.dx * (py - self.from.y.0) - self.dy * (px - self.from.x.0)
    }

    /// Change of `E` for one sample step in +x.
    fn step_x(&self) -> i64 {
        -self.dy * ONE
    }

    /// Change of `E` for one sample step in +y.
    fn step_y(&self) -> i64 {
        self.dx * ONE
    }
}

/// The first sample whose centre `i·256 + 128` is at or right of (above)
/// `lo`, in fixed point: a bounding box's first candidate.
#[inline(always)]
fn first_sample(lo: i64) -> i64 {
    (lo - ONE / 2 + ONE - 1).div_euclid(ONE)
}

/// The last sample whose centre is at or left of (below) `hi`.
#[inline(always)]
fn last_sample(hi: i64) -> i64 {
    (hi - ONE / 2).div_euclid(ONE)
}

/// Whether a snapped triangle's bounding box, clamped to `grid`'s columns
/// and `band`'s rows, holds no sample centre (the same box
/// [`Setup::from_fixed_in`] finds): the slow twin [`CentreKey`]'s test is
/// checked against.
#[cfg(test)]
fn box_is_empty(p: &[FixedPoint; 3], grid: Grid, band: Band) -> bool {
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
/// a grid or a band). Computed once per vertex by the vertex stage, four
/// at a time in integer lanes ([`CentreKey::of4`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct CentreKey(u64);

impl CentreKey {
    /// The key of a snapped point.
    #[inline(always)]
    pub(crate) fn of(p: FixedPoint) -> CentreKey {
        let axis = |v: i64| {
            let d = v - ONE / 2;
            // An arithmetic shift is a division rounding down.
            ((d >> FRAC_BITS) * 2 + (d & (ONE - 1) == 0) as i64) as u32
        };
        CentreKey((axis(p.x.0) as u64) << 32 | axis(p.y.0) as u64)
    }

    /// The keys of four snapped points, computed in integer lanes: the
    /// same as [`CentreKey::of`] of each (the coordinates fit in an `i32`,
    /// and an arithmetic shift is the same division in either width).
    #[inline(always)]
    pub(crate) fn of4(p: &SnappedLanes) -> [CentreKey; 4] {
        let axis = |v: i32x4| -> i32x4 {
            let d = v - i32x4::splat((ONE / 2) as i32);
            // All ones (−1) where the point is on a centre.
            let on = (d & i32x4::splat((ONE - 1) as i32)).simd_eq(i32x4::ZERO);
            ((d >> FRAC_BITS) << 1) - on
        };
        let (x, y) = (axis(p.x).to_array(), axis(p.y).to_array());
        std::array::from_fn(|i| CentreKey((x[i] as u32 as u64) << 32 | y[i] as u32 as u64))
    }

    /// Whether the keys of a triangle's vertices show that its bounding box
    /// holds no sample centre (`false` says nothing).
    #[inline(always)]
    pub(crate) fn box_is_empty(k: [CentreKey; 3]) -> bool {
        let [a, b, c] = k.map(|k| k.0);
        // Zero in an axis's half exactly when the three are equal there and
        // even.
        let m = (a ^ b) | (a ^ c) | (a & (1 << 32 | 1));
        m >> 32 == 0 || m as u32 == 0
    }
}

/// Whether every coordinate is within ±[`MAX_COORD`] samples, as the
/// vertex stage's snapped vertices are (checked in debug builds where a
/// set-up relies on it).
fn snapped_in_range(p: &[FixedPoint; 3]) -> bool {
    let limit = (MAX_COORD as i64) * ONE;
    p.iter()
        .all(|q| q.x.0.abs() <= limit && q.y.0.abs() <= limit)
}

/// A snapped triangle's extent in fixed point: `[min x, max x, min y,
/// max y]`.
#[inline(always)]
fn extent(p: &[FixedPoint; 3]) -> [i64; 4] {
    let (min_x, max_x) = min_max(p.map(|q| q.x.0));
    let (min_y, max_y) = min_max(p.map(|q| q.y.0));
    [min_x, max_x, min_y, max_y]
}

/// A snapped triangle's bounding box in samples, `[x0, x1, y0, y1]`
/// inclusive, clamped to `grid`'s columns and `band`'s rows; empty when
/// `x0 > x1` or `y0 > y1`.
#[inline(always)]
fn clamped_box(extent: &[i64; 4], grid: Grid, band: Band) -> [i64; 4] {
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
fn oriented(p: &[FixedPoint; 3], ccw: bool) -> ([Edge; 3], [usize; 3]) {
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
fn edges(p: &[FixedPoint; 3], ccw: bool) -> [Edge; 3] {
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

/// A triangle set up for rasterization: snapped, oriented, bounded.
#[derive(Clone, Copy, Debug)]
pub struct Setup {
    /// `edges[k]` is the edge opposite vertex `order[k]`, so its value at a
    /// sample is the (unnormalised) barycentric weight of that vertex.
    edges: [Edge; 3],
    /// The vertices in the order the edges follow: a rotation of the
    /// caller's, starting from the lowest vertex.
    order: [usize; 3],
    /// Twice the snapped area in fixed-point units squared (> 0); the sum of
    /// the three edge values at any point.
    pub area2: i64,
    /// Whether the triangle is counter-clockwise on screen (front-facing).
    pub ccw: bool,
    /// Inclusive sample bounds, clamped to the grid; empty when `x0 > x1` or
    /// `y0 > y1`.
    x0: i64,
    x1: i64,
    y0: i64,
    y1: i64,
}

/// Why a triangle produced no [`Setup`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rejected {
    /// A coordinate is NaN or infinite.
    NonFinite,
    /// A coordinate lies beyond [`MAX_COORD`].
    OutOfRange,
    /// Its area is zero after snapping.
    Degenerate,
    /// Its winding is culled.
    Culled,
}

impl Setup {
    /// Snaps and sets up a triangle given in samples.
    pub fn new(v: [[f32; 2]; 3], grid: Grid, cull: Cull) -> Result<Setup, Rejected> {
        if v.iter().flatten().any(|c| !c.is_finite()) {
            return Err(Rejected::NonFinite);
        }
        let snap = |p| FixedPoint::snap(p).ok_or(Rejected::OutOfRange);
        let p = [snap(v[0])?, snap(v[1])?, snap(v[2])?];
        Setup::from_fixed(p, grid, cull)
    }

    /// Sets up a triangle already snapped. One whose bounding box holds no
    /// sample centre (most triangles of a detailed model seen small) is
    /// set up without its edges: nothing will evaluate them.
    #[inline]
    pub fn from_fixed(p: [FixedPoint; 3], grid: Grid, cull: Cull) -> Result<Setup, Rejected> {
        Setup::from_fixed_in(p, grid, grid.all_rows(), cull)
    }

    /// [`Setup::from_fixed`] with the bounding box clamped to `band`'s rows
    /// as well: the part of the triangle one band of a parallel frame
    /// draws. The edge values at a sample are exact integers, whatever row
    /// the walk starts from, so the bands together cover exactly the
    /// samples the whole grid's set-up covers, with the same weights.
    #[inline]
    pub fn from_fixed_in(
        p: [FixedPoint; 3],
        grid: Grid,
        band: Band,
        cull: Cull,
    ) -> Result<Setup, Rejected> {
        // Twice the signed area, the same from any starting vertex: cull
        // and drop degenerates before anything else.
        let extent = extent(&p);
        let area2 = Setup::signed_area2_in(&p, &extent, cull)?;
        Ok(Setup::with_area(p, &extent, area2, grid, band))
    }

    /// [`Setup::from_fixed_in`] of a triangle the vertex stage snapped
    /// (every coordinate within ±[`MAX_COORD`] samples), whose
    /// [`Setup::signed_area2`] is `area2`: the same set-up.
    #[inline(always)]
    pub(crate) fn from_snapped(p: [FixedPoint; 3], area2: i64, grid: Grid, band: Band) -> Setup {
        debug_assert!(snapped_in_range(&p));
        Setup::with_area(p, &extent(&p), area2, grid, band)
    }

    /// The set-up of a triangle whose extent and signed area (not zero) are
    /// known.
    #[inline(always)]
    fn with_area(
        p: [FixedPoint; 3],
        extent: &[i64; 4],
        area2: i64,
        grid: Grid,
        band: Band,
    ) -> Setup {
        let ccw = area2 > 0;
        let [x0, x1, y0, y1] = clamped_box(extent, grid, band);
        if x0 > x1 || y0 > y1 {
            // A return of its own rather than one `Ok(Setup { .. })` below
            // with the edges chosen by an `if`: 3 % fewer instructions on a
            // Tux frame (callgrind).
            return Setup {
                edges: [Edge::NONE; 3],
                order: [0, 1, 2],
                area2: area2.abs(),
                ccw,
                x0,
                x1,
                y0,
                y1,
            };
        }
        let (edges, order) = oriented(&p, ccw);
        Setup {
            edges,
            order,
            area2: area2.abs(),
            ccw,
            x0,
            x1,
            y0,
            y1,
        }
    }

    /// Twice the signed area of a snapped triangle (positive when
    /// counter-clockwise), or why [`Setup::from_fixed`] rejects it before
    /// looking at its bounding box: a coordinate out of range, no area, or
    /// culled.
    #[inline(always)]
    pub fn signed_area2(p: &[FixedPoint; 3], cull: Cull) -> Result<i64, Rejected> {
        Setup::signed_area2_in(p, &extent(p), cull)
    }

    /// [`Setup::signed_area2`] of a triangle whose [`extent`] is known.
    #[inline(always)]
    fn signed_area2_in(p: &[FixedPoint; 3], e: &[i64; 4], cull: Cull) -> Result<i64, Rejected> {
        // Every coordinate within ±limit: the extent's ends are.
        let limit = (MAX_COORD as i64) * ONE;
        if e[0] < -limit || e[1] > limit || e[2] < -limit || e[3] > limit {
            return Err(Rejected::OutOfRange);
        }
        Setup::signed_area2_in_range(p, cull)
    }

    /// [`Setup::signed_area2`] of a triangle whose coordinates are known to
    /// be within ±[`MAX_COORD`] samples.
    #[inline(always)]
    pub(crate) fn signed_area2_in_range(p: &[FixedPoint; 3], cull: Cull) -> Result<i64, Rejected> {
        let area2 = Edge::new(p[0], p[1]).at(p[2].x.0, p[2].y.0);
        if area2 == 0 {
            return Err(Rejected::Degenerate);
        }
        match (cull, area2 > 0) {
            (Cull::Back, false) | (Cull::Front, true) => Err(Rejected::Culled),
            _ => Ok(area2),
        }
    }

    /// Whether the sample centre `(x + 0.5, y + 0.5)` is inside, with its
    /// three edge values.
    #[inline(always)]
    pub fn inside(&self, x: u32, y: u32) -> Option<[i64; 3]> {
        let (px, py) = (Fixed::sample_centre(x).0, Fixed::sample_centre(y).0);
        let e = self.edges.map(|e| e.at(px, py));
        self.accepts(e).then_some(e)
    }

    #[inline(always)]
    fn accepts(&self, e: [i64; 3]) -> bool {
        // Each (e − min) is ≥ 0 exactly when its edge accepts the sample; the
        // OR of the three is non-negative only when all are.
        ((e[0] - self.edges[0].min) | (e[1] - self.edges[1].min) | (e[2] - self.edges[2].min)) >= 0
    }

    /// The caller's vertex index behind each edge value: `e[k]` in
    /// [`Setup::walk`] weighs vertex `order()[k]`. A rotation, so the
    /// winding is unchanged.
    pub fn order(&self) -> [usize; 3] {
        self.order
    }

    /// Number of samples in the clamped bounding box.
    pub fn bbox_samples(&self) -> u64 {
        if self.x0 > self.x1 || self.y0 > self.y1 {
            0
        } else {
            ((self.x1 - self.x0 + 1) * (self.y1 - self.y0 + 1)) as u64
        }
    }

    /// Walks the samples with `traversal`, calling `hit(x, y, e)` for each
    /// covered sample, where `e[k]` is the weight of vertex `order()[k]` (the
    /// three sum to [`Setup::area2`]). Returns the number of samples tested.
    #[inline(always)]
    pub fn walk<F: FnMut(u32, u32, [i64; 3])>(
        &self,
        grid: Grid,
        traversal: Traversal,
        mut hit: F,
    ) -> u64 {
        match traversal {
            Traversal::Spans => {
                if self.bbox_samples() == 0 {
                    return 0;
                }
                let (mut row, sx, sy) = self.steps();
                let last = self.x1 - self.x0;
                for y in self.y0..=self.y1 {
                    let (lo, hi) = self.span(row, sx, last);
                    if lo <= hi {
                        let mut e = [0, 1, 2].map(|k| row[k] + lo * sx[k]);
                        for x in self.x0 + lo..=self.x0 + hi {
                            hit(x as u32, y as u32, e);
                            e = [e[0] + sx[0], e[1] + sx[1], e[2] + sx[2]];
                        }
                    }
                    row = [row[0] + sy[0], row[1] + sy[1], row[2] + sy[2]];
                }
                // Every sample of the box was decided, those outside the
                // runs without a test of their own.
                self.bbox_samples()
            }
            // The others are comparison modes: a function of their own, so
            // that `hit` is inlined into the default walk alone.
            _ => self.walk_other(grid, traversal, &mut hit),
        }
    }

    /// [`Setup::walk`] for the traversals but [`Traversal::Spans`].
    #[inline(never)]
    fn walk_other<F: FnMut(u32, u32, [i64; 3])>(
        &self,
        grid: Grid,
        traversal: Traversal,
        hit: &mut F,
    ) -> u64 {
        match traversal {
            Traversal::Scan => {
                for y in 0..grid.height {
                    for x in 0..grid.width {
                        if let Some(e) = self.inside(x, y) {
                            hit(x, y, e);
                        }
                    }
                }
                grid.len() as u64
            }
            Traversal::BoundingBox => {
                for y in self.y0..=self.y1 {
                    for x in self.x0..=self.x1 {
                        if let Some(e) = self.inside(x as u32, y as u32) {
                            hit(x as u32, y as u32, e);
                        }
                    }
                }
                self.bbox_samples()
            }
            // (`walk` takes the spans itself.)
            Traversal::Incremental | Traversal::Spans => {
                if self.bbox_samples() == 0 {
                    return 0;
                }
                let (mut row, sx, sy) = self.steps();
                for y in self.y0..=self.y1 {
                    let mut e = row;
                    for x in self.x0..=self.x1 {
                        if self.accepts(e) {
                            hit(x as u32, y as u32, e);
                        }
                        e = [e[0] + sx[0], e[1] + sx[1], e[2] + sx[2]];
                    }
                    row = [row[0] + sy[0], row[1] + sy[1], row[2] + sy[2]];
                }
                self.bbox_samples()
            }
        }
    }

    /// The edge values at the box's first sample, and their steps along x
    /// and y: what the stepping walks start from.
    #[inline(always)]
    fn steps(&self) -> ([i64; 3], [i64; 3], [i64; 3]) {
        let (px, py) = (
            Fixed::sample_centre(self.x0 as u32).0,
            Fixed::sample_centre(self.y0 as u32).0,
        );
        (
            self.edges.map(|e| e.at(px, py)),
            self.edges.map(|e| e.step_x()),
            self.edges.map(|e| e.step_y()),
        )
    }

    /// The covered samples of a row of the box, `[lo, hi]` counted from
    /// its first (empty when `lo > hi`): `row` holds the edge values at the
    /// first sample, `sx` their steps along the row, `last` the last
    /// sample's offset. Edge `k` accepts offset `t` when `row[k] + t·sx[k]
    /// ≥ min`, a bound on `t` from below (`sx[k] > 0`) or above
    /// (`sx[k] < 0`), found exactly by integer division.
    #[inline(always)]
    fn span(&self, row: [i64; 3], sx: [i64; 3], last: i64) -> (i64, i64) {
        let (mut lo, mut hi) = (0, last);
        for k in 0..3 {
            let (r, s, m) = (row[k], sx[k], self.edges[k].min);
            if s > 0 {
                // t ≥ ⌈(m − r) / s⌉
                lo = lo.max(-(r - m).div_euclid(s));
            } else if s < 0 {
                // t ≤ ⌊(r − m) / −s⌋
                hi = hi.min((r - m).div_euclid(-s));
            } else if r < m {
                hi = -1;
            }
        }
        (lo, hi)
    }
}

/// The largest bounding box (in samples) [`Coverage::covers_any`] tests
/// sample by sample: most triangles of a detailed model seen small have a
/// box of one to four samples and cover none of them.
pub const SMALL_BOX: u64 = 8;

/// A triangle whose clamped bounding box holds at most [`SMALL_BOX`]
/// samples, set up by testing each of them once: which it covers. Most
/// triangles of a detailed model seen small are such, and most of those
/// cover nothing: that is then known without a [`Setup`] built and walked.
/// Small, so that it stays in registers: the vertices and which samples
/// are covered, whose weights the walk finds again. The same samples,
/// weights and counts as [`Setup::from_fixed_in`] and its walk (a test
/// compares the two).
#[derive(Clone, Copy, Debug)]
pub(crate) struct SmallSetup {
    /// The vertices in `order`.
    p: [FixedPoint; 3],
    order: [u8; 3],
    ccw: bool,
    area2: i64,
    /// The box's first sample, its width and height.
    x0: u32,
    y0: u32,
    w: u8,
    h: u8,
    /// Samples in the clamped box, all tested.
    tested: u8,
    /// Bit k: the box's sample k (rows bottom to top, left to right) is
    /// covered.
    covered: u8,
}

impl SmallSetup {
    /// Sets up a snapped triangle as [`Setup::from_fixed_in`] does, when
    /// its box clamped to `grid`'s columns and `band`'s rows holds at most
    /// [`SMALL_BOX`] samples: `Ok(None)` when it holds more, and the same
    /// rejection otherwise. The twin [`SmallSetup::new_snapped`] is
    /// tested against.
    #[cfg(test)]
    pub fn new(
        p: [FixedPoint; 3],
        grid: Grid,
        band: Band,
        cull: Cull,
    ) -> Result<Option<SmallSetup>, Rejected> {
        let extent = extent(&p);
        let area2 = Setup::signed_area2_in(&p, &extent, cull)?;
        Ok(SmallSetup::with_area(p, &extent, area2, grid, band))
    }

    /// [`SmallSetup::new`] for vertices the vertex stage snapped (each
    /// coordinate is within ±[`MAX_COORD`] samples: `Fixed::snap` accepts no
    /// other), whose [`Setup::signed_area2`] is `area2`, found by the caller
    /// before anything else: `None` when its box holds more than
    /// [`SMALL_BOX`] samples.
    #[inline(always)]
    pub(crate) fn new_snapped(
        p: [FixedPoint; 3],
        area2: i64,
        grid: Grid,
        band: Band,
    ) -> Option<SmallSetup> {
        debug_assert!(snapped_in_range(&p));
        SmallSetup::with_area(p, &extent(&p), area2, grid, band)
    }

    #[inline(always)]
    fn with_area(
        p: [FixedPoint; 3],
        extent: &[i64; 4],
        area2: i64,
        grid: Grid,
        band: Band,
    ) -> Option<SmallSetup> {
        let ccw = area2 > 0;
        let [x0, x1, y0, y1] = clamped_box(extent, grid, band);
        if x0 > x1 || y0 > y1 {
            return Some(SmallSetup {
                p,
                order: [0, 1, 2],
                ccw,
                area2: area2.abs(),
                x0: 0,
                y0: 0,
                w: 0,
                h: 0,
                tested: 0,
                covered: 0,
            });
        }
        let (w, n) = (x1 - x0 + 1, (x1 - x0 + 1) * (y1 - y0 + 1));
        if n as u64 > SMALL_BOX {
            return None;
        }
        let (edges, order) = oriented(&p, ccw);
        let accepts = |x: i64, y: i64| {
            let (px, py) = (x * ONE + ONE / 2, y * ONE + ONE / 2);
            edges.iter().all(|e| e.at(px, py) >= e.min)
        };
        let covered = if n == 1 {
            // Most boxes of a detailed model seen small: one sample.
            u8::from(accepts(x0, y0))
        } else {
            let (mut covered, mut bit) = (0, 1);
            for y in y0..=y1 {
                for x in x0..=x1 {
                    if accepts(x, y) {
                        covered |= bit;
                    }
                    bit <<= 1;
                }
            }
            covered
        };
        Some(SmallSetup {
            p: order.map(|i| p[i]),
            order: order.map(|i| i as u8),
            ccw,
            area2: area2.abs(),
            x0: x0 as u32,
            y0: y0 as u32,
            w: w as u8,
            h: (y1 - y0 + 1) as u8,
            tested: n as u8,
            covered,
        })
    }
}

impl Coverage for SmallSetup {
    type Weights = [i64; 3];

    fn order(&self) -> [usize; 3] {
        self.order.map(usize::from)
    }

    fn inv_area(&self) -> f32 {
        1.0 / self.area2 as f32
    }

    fn ccw(&self) -> bool {
        self.ccw
    }

    fn bbox_samples(&self) -> u64 {
        self.tested as u64
    }

    #[inline(always)]
    fn bounds(&self) -> Rect {
        Rect {
            x0: self.x0,
            x1: self.x0 + self.w as u32,
            y0: self.y0,
            y1: self.y0 + self.h as u32,
        }
    }

    fn covers_any(&self) -> bool {
        self.covered != 0
    }

    #[inline(always)]
    fn f32(w: [i64; 3]) -> [f32; 3] {
        w.map(|e| e as f32)
    }

    /// The covered samples found at set-up, with their weights: what the
    /// bounding-box and incremental walks find. Not the full-grid scan,
    /// which tests every sample.
    #[inline(always)]
    fn walk_samples<F: FnMut(u32, u32, [i64; 3])>(
        &self,
        _grid: Grid,
        traversal: Traversal,
        mut hit: F,
    ) -> u64 {
        debug_assert!(traversal != Traversal::Scan);
        let edges = edges(&self.p, self.ccw);
        let mut covered = self.covered;
        while covered != 0 {
            let k = covered.trailing_zeros();
            covered &= covered - 1;
            let (x, y) = (self.x0 + k % self.w as u32, self.y0 + k / self.w as u32);
            let (px, py) = (Fixed::sample_centre(x).0, Fixed::sample_centre(y).0);
            hit(x, y, edges.map(|e| e.at(px, py)));
        }
        self.tested as u64
    }
}

/// An inclusive box of samples, `[x0, x1] × [y0, y1]` (clamped to the
/// grid, so not negative where not empty), as a [`Rect`].
#[inline(always)]
fn box_rect(x0: i64, x1: i64, y0: i64, y1: i64) -> Rect {
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

fn min_max(v: [i64; 3]) -> (i64, i64) {
    (v[0].min(v[1]).min(v[2]), v[0].max(v[1]).max(v[2]))
}

/// How edge functions are evaluated: the exact fixed point (the default),
/// or the notes' rasterizer without the snap, in f64 or f32, for measuring
/// what exactness costs and what it buys (`rastty bench`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Precision {
    /// Vertices snapped to 1/256 of a sample, edge functions in `i64`:
    /// exact, watertight.
    #[default]
    Fixed,
    /// Unsnapped positions, edge functions in f64: exact for most inputs,
    /// not for all.
    F64,
    /// Unsnapped positions, edge functions in f32: cracks and double hits
    /// where edges pass through sample centres.
    F32,
}

crate::choice::choice!(Precision {
    Fixed => "fixed": "Vertices snapped to 1/256 of a sample, edge functions in `i64`: exact, watertight",
    F64 => "f64": "Unsnapped positions, edge functions in f64: exact for most inputs, not for all",
    F32 => "f32": "Unsnapped positions, edge functions in f32: cracks and double hits where edges pass through sample centres",
});

/// What the renderer needs of a set-up triangle, whatever arithmetic its
/// edge functions use: the vertex order behind the weights, and a walk
/// over the covered samples that hands out the weights.
pub trait Coverage {
    /// The three edge values at a sample (unnormalised barycentrics).
    type Weights: Copy;
    /// The caller's vertex behind each weight.
    fn order(&self) -> [usize; 3];
    /// One over the sum of the weights (twice the area).
    fn inv_area(&self) -> f32;
    /// Whether the triangle is counter-clockwise on screen.
    fn ccw(&self) -> bool;
    /// Samples in the clamped bounding box.
    fn bbox_samples(&self) -> u64;
    /// The clamped bounding box: every sample the walk hits lies in it.
    fn bounds(&self) -> Rect;
    /// Whether any sample may be covered: `false` only when it is certain
    /// that none is (cheap to tell for a small box; a large box says
    /// `true`).
    fn covers_any(&self) -> bool {
        true
    }
    /// The weights as f32.
    fn f32(w: Self::Weights) -> [f32; 3];
    /// Calls `hit` for each covered sample; returns the samples tested.
    fn walk_samples<F: FnMut(u32, u32, Self::Weights)>(
        &self,
        grid: Grid,
        traversal: Traversal,
        hit: F,
    ) -> u64;
}

impl Coverage for Setup {
    type Weights = [i64; 3];

    fn order(&self) -> [usize; 3] {
        self.order
    }

    fn inv_area(&self) -> f32 {
        1.0 / self.area2 as f32
    }

    fn ccw(&self) -> bool {
        self.ccw
    }

    fn bbox_samples(&self) -> u64 {
        Setup::bbox_samples(self)
    }

    #[inline(always)]
    fn bounds(&self) -> Rect {
        box_rect(self.x0, self.x1, self.y0, self.y1)
    }

    /// Each sample of a box of at most [`SMALL_BOX`] samples tested
    /// directly, stopping at the first inside.
    #[inline(always)]
    fn covers_any(&self) -> bool {
        if self.bbox_samples() > SMALL_BOX {
            return true;
        }
        (self.y0..=self.y1)
            .any(|y| (self.x0..=self.x1).any(|x| self.inside(x as u32, y as u32).is_some()))
    }

    #[inline(always)]
    fn f32(w: [i64; 3]) -> [f32; 3] {
        w.map(|e| e as f32)
    }

    #[inline(always)]
    fn walk_samples<F: FnMut(u32, u32, [i64; 3])>(
        &self,
        grid: Grid,
        traversal: Traversal,
        hit: F,
    ) -> u64 {
        self.walk(grid, traversal, hit)
    }
}

/// f32 or f64, for [`FloatSetup`].
pub trait Real:
    Copy
    + PartialOrd
    + std::ops::Add<Output = Self>
    + std::ops::Sub<Output = Self>
    + std::ops::Mul<Output = Self>
{
    /// Zero.
    const ZERO: Self;
    /// From an f64, rounded to nearest.
    fn from_f64(v: f64) -> Self;
    /// To an f64.
    fn to_f64(self) -> f64;
}

impl Real for f32 {
    const ZERO: f32 = 0.0;
    fn from_f64(v: f64) -> f32 {
        v as f32
    }
    fn to_f64(self) -> f64 {
        self as f64
    }
}

impl Real for f64 {
    const ZERO: f64 = 0.0;
    fn from_f64(v: f64) -> f64 {
        v
    }
    fn to_f64(self) -> f64 {
        self
    }
}

/// A triangle set up with unsnapped floating-point edge functions: the
/// notes' rasterizer taken literally, each sample's three cross products
/// evaluated afresh over the bounding box, the top-left rule for exact
/// zeros. What [`Precision::F64`] and [`Precision::F32`] draw with.
#[derive(Clone, Copy, Debug)]
pub struct FloatSetup<T> {
    /// Each edge as `(a, b)`, from and to, oriented counter-clockwise, and
    /// whether it is a top or left edge.
    edges: [([T; 2], [T; 2], bool); 3],
    order: [usize; 3],
    area2: T,
    ccw: bool,
    x0: i64,
    x1: i64,
    y0: i64,
    y1: i64,
}

impl<T: Real> FloatSetup<T> {
    /// Sets up a triangle given in samples.
    pub fn new(v: [[f64; 2]; 3], grid: Grid, cull: Cull) -> Result<FloatSetup<T>, Rejected> {
        if v.iter().flatten().any(|c| !c.is_finite()) {
            return Err(Rejected::NonFinite);
        }
        let p = v.map(|q| q.map(T::from_f64));
        let cross = |a: [T; 2], b: [T; 2], c: [T; 2]| {
            (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        };
        let area2 = cross(p[0], p[1], p[2]);
        if area2 == T::ZERO {
            return Err(Rejected::Degenerate);
        }
        let ccw = area2 > T::ZERO;
        match (cull, ccw) {
            (Cull::Back, false) | (Cull::Front, true) => return Err(Rejected::Culled),
            _ => {}
        }
        // The lowest vertex first, as `Setup` does.
        let key = |q: [T; 2]| (q[1].to_f64(), q[0].to_f64());
        let r = (0..3)
            .min_by(|&i, &j| {
                key(p[i])
                    .partial_cmp(&key(p[j]))
                    .unwrap_or(std::cmp::Ordering::Equal)
            })
            .unwrap_or(0);
        let order = [r, (r + 1) % 3, (r + 2) % 3];
        let p = order.map(|i| p[i]);
        let edge = |i: usize| {
            let (a, b) = (p[(i + 1) % 3], p[(i + 2) % 3]);
            let (a, b) = if ccw { (a, b) } else { (b, a) };
            let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
            let top_left = dy < T::ZERO || (dy == T::ZERO && dx < T::ZERO);
            (a, b, top_left)
        };
        let f = |k: usize, hi: bool| {
            let vals = p.map(|q| q[k].to_f64());
            if hi {
                vals.iter().copied().fold(f64::NEG_INFINITY, f64::max)
            } else {
                vals.iter().copied().fold(f64::INFINITY, f64::min)
            }
        };
        let first = |lo: f64| (lo - 0.5).ceil().max(-1.0) as i64;
        let last = |hi: f64| (hi - 0.5).floor().min(MAX_GRID as f64) as i64;
        Ok(FloatSetup {
            edges: [edge(0), edge(1), edge(2)],
            order,
            area2: if ccw { area2 } else { T::ZERO - area2 },
            ccw,
            x0: first(f(0, false)).max(0),
            x1: last(f(0, true)).min(grid.width as i64 - 1),
            y0: first(f(1, false)).max(0),
            y1: last(f(1, true)).min(grid.height as i64 - 1),
        })
    }
}

impl<T: Real> Coverage for FloatSetup<T> {
    type Weights = [T; 3];

    fn order(&self) -> [usize; 3] {
        self.order
    }

    fn inv_area(&self) -> f32 {
        1.0 / self.area2.to_f64() as f32
    }

    fn ccw(&self) -> bool {
        self.ccw
    }

    fn bbox_samples(&self) -> u64 {
        if self.x0 > self.x1 || self.y0 > self.y1 {
            0
        } else {
            ((self.x1 - self.x0 + 1) * (self.y1 - self.y0 + 1)) as u64
        }
    }

    fn bounds(&self) -> Rect {
        box_rect(self.x0, self.x1, self.y0, self.y1)
    }

    fn f32(w: [T; 3]) -> [f32; 3] {
        w.map(|e| e.to_f64() as f32)
    }

    fn walk_samples<F: FnMut(u32, u32, [T; 3])>(&self, _: Grid, _: Traversal, mut hit: F) -> u64 {
        let half = T::from_f64(0.5);
        for y in self.y0..=self.y1 {
            for x in self.x0..=self.x1 {
                let s = [T::from_f64(x as f64) + half, T::from_f64(y as f64) + half];
                let e = self
                    .edges
                    .map(|(a, b, _)| (b[0] - a[0]) * (s[1] - a[1]) - (b[1] - a[1]) * (s[0] - a[0]));
                let inside = (0..3).all(|k| e[k] > T::ZERO || (e[k] == T::ZERO && self.edges[k].2));
                if inside {
                    hit(x as u32, y as u32, e);
                }
            }
        }
        Coverage::bbox_samples(self)
    }
}

/// Rasterizes one triangle given in samples: sets it up, walks it, and
/// counts what happened in `stats`. The convenience entry point for tests
/// and tools; the renderer calls [`Setup`] directly.
pub fn rasterize<F: FnMut(u32, u32, [i64; 3])>(
    v: [[f32; 2]; 3],
    grid: Grid,
    cull: Cull,
    traversal: Traversal,
    stats: &mut RasterStats,
    mut hit: F,
) {
    match Setup::new(v, grid, cull) {
        Ok(setup) => {
            stats.triangles_drawn += 1;
            let mut covered = 0;
            stats.samples_tested += setup.walk(grid, traversal, |x, y, e| {
                covered += 1;
                hit(x, y, e)
            });
            stats.samples_covered += covered;
        }
        Err(r) => stats.count_rejected(r),
    }
}

impl RasterStats {
    /// Counts a rejected triangle under its reason.
    pub fn count_rejected(&mut self, r: Rejected) {
        match r {
            Rejected::NonFinite => self.dropped_non_finite += 1,
            Rejected::OutOfRange => self.dropped_out_of_range += 1,
            Rejected::Degenerate => self.dropped_degenerate += 1,
            Rejected::Culled => self.culled += 1,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    proptest::proptest! {
        /// `covers_any` says no only of triangles the walk finds no sample
        /// of, and says so of every small one that covers none.
        #[test]
        fn covers_any_is_false_exactly_for_small_triangles_covering_nothing(
            c in proptest::array::uniform6(-300i64..1800),
        ) {
            let p = [0, 2, 4].map(|i| FixedPoint { x: Fixed(c[i]), y: Fixed(c[i + 1]) });
            let grid = Grid::new(6, 5);
            if let Ok(s) = Setup::from_fixed(p, grid, Cull::None) {
                let mut hits = 0;
                s.walk(grid, Traversal::Incremental, |_, _, _| hits += 1);
                let small = s.bbox_samples() <= SMALL_BOX;
                proptest::prop_assert_eq!(s.covers_any(), hits > 0 || !small);
            }
        }
    }

    proptest::proptest! {
        /// A small triangle's one-pass set-up finds what the set-up and its
        /// walk find: the same rejection, vertex order, winding, area,
        /// samples tested, and covered samples with the same weights, in
        /// the same order; and it declines exactly the boxes of more than
        /// `SMALL_BOX` samples.
        #[test]
        fn small_setup_finds_what_the_setup_and_its_walk_find(
            // Half the coordinates on a multiple of half a sample, so that
            // edges run through sample centres (the top-left rule's case).
            c in proptest::array::uniform6(proptest::prop_oneof![
                -300i64..1800,
                proptest::strategy::Strategy::prop_map(-2i64..14, |k| k * 128),
            ]),
            rows in (0u32..5, 0u32..5),
            cull in proptest::sample::select(vec![Cull::None, Cull::Back, Cull::Front]),
        ) {
            let p = [0, 2, 4].map(|i| FixedPoint { x: Fixed(c[i]), y: Fixed(c[i + 1]) });
            let grid = Grid::new(6, 5);
            let band = Band { y0: rows.0.min(rows.1), y1: rows.0.max(rows.1) + 1 };
            // In range, the snapped vertices' set-up is the same.
            proptest::prop_assert_eq!(
                format!("{:?}", Setup::signed_area2_in_range(&p, cull)
                    .map(|a| SmallSetup::new_snapped(p, a, grid, band))),
                format!("{:?}", SmallSetup::new(p, grid, band, cull))
            );
            proptest::prop_assert_eq!(
                format!("{:?}", Setup::signed_area2_in_range(&p, cull)
                    .map(|a| Setup::from_snapped(p, a, grid, band))),
                format!("{:?}", Setup::from_fixed_in(p, grid, band, cull))
            );
            match (SmallSetup::new(p, grid, band, cull), Setup::from_fixed_in(p, grid, band, cull)) {
                (Err(a), Err(b)) => proptest::prop_assert_eq!(a, b),
                (Ok(None), Ok(s)) => proptest::prop_assert!(s.bbox_samples() > SMALL_BOX),
                (Ok(Some(small)), Ok(s)) => {
                    proptest::prop_assert!(s.bbox_samples() <= SMALL_BOX);
                    proptest::prop_assert_eq!(Coverage::bbox_samples(&small), s.bbox_samples());
                    proptest::prop_assert_eq!(small.inv_area().to_bits(), s.inv_area().to_bits());
                    proptest::prop_assert_eq!(Coverage::ccw(&small), s.ccw);
                    let (tested, hits) = walk(&s, grid);
                    if !hits.is_empty() {
                        // The order matters only to a triangle that is filled.
                        proptest::prop_assert_eq!(Coverage::order(&small), s.order());
                    }
                    proptest::prop_assert_eq!(small.covers_any(), !hits.is_empty());
                    let found = walk(&small, grid);
                    proptest::prop_assert_eq!(found, (tested, hits));
                }
                (a, b) => proptest::prop_assert!(false, "{a:?} against {b:?}"),
            }
        }
    }

    proptest::proptest! {
        /// The span walk hits the samples the incremental walk covers, with
        /// the same weights, in the same order, and counts the same samples
        /// decided: large and thin triangles, edges through sample centres,
        /// huge coordinates (edge values near 2^60), bands and culling.
        #[test]
        fn spans_hit_what_the_incremental_walk_covers(
            c in proptest::array::uniform6(proptest::prop_oneof![
                -3000i64..12000,
                proptest::strategy::Strategy::prop_map(-20i64..90, |k| k * 128),
                -(1i64 << 29)..(1i64 << 29),
            ]),
            rows in (0u32..40, 0u32..40),
            cull in proptest::sample::select(vec![Cull::None, Cull::Back, Cull::Front]),
        ) {
            let p = [0, 2, 4].map(|i| FixedPoint { x: Fixed(c[i]), y: Fixed(c[i + 1]) });
            let grid = Grid::new(37, 40);
            let band = Band { y0: rows.0.min(rows.1), y1: rows.0.max(rows.1) + 1 };
            if let Ok(s) = Setup::from_fixed_in(p, grid, band, cull) {
                let mut incremental = Vec::new();
                s.walk(grid, Traversal::Incremental, |x, y, e| incremental.push((x, y, e)));
                let mut spans = Vec::new();
                let tested = s.walk(grid, Traversal::Spans, |x, y, e| spans.push((x, y, e)));
                proptest::prop_assert_eq!(tested, s.bbox_samples());
                proptest::prop_assert_eq!(spans, incremental);
            }
        }
    }

    proptest::proptest! {
        /// Where the vertices' keys say a box holds no sample centre, it
        /// holds none, clamped to any grid and band; and for a box inside
        /// the grid they say so of every box that holds none (vertices on a
        /// centre's column or row, or half a sample short of one, included).
        #[test]
        fn keys_tell_boxes_without_a_sample_centre(
            c in proptest::array::uniform6(proptest::prop_oneof![
                -700i64..2200,
                proptest::strategy::Strategy::prop_map(-3i64..18, |k| k * 128),
                proptest::strategy::Strategy::prop_map(-3i64..18, |k| k * 256 + 127),
            ]),
            rows in (0u32..8, 0u32..8),
        ) {
            let p = [0, 2, 4].map(|i| FixedPoint { x: Fixed(c[i]), y: Fixed(c[i + 1]) });
            let keys = p.map(CentreKey::of);
            let band = Band { y0: rows.0.min(rows.1), y1: rows.0.max(rows.1) + 1 };
            let (grid, big) = (Grid::new(7, 8), Grid::new(1 << 12, 1 << 12));
            let empty = CentreKey::box_is_empty(keys);
            if empty {
                proptest::prop_assert!(box_is_empty(&p, grid, band));
            }
            // Moved well inside a large grid: the box is not clamped.
            let far = p.map(|q| FixedPoint { x: Fixed(q.x.0 + (1 << 18)), y: Fixed(q.y.0 + (1 << 18)) });
            proptest::prop_assert_eq!(CentreKey::box_is_empty(far.map(CentreKey::of)), empty);
            proptest::prop_assert_eq!(empty, box_is_empty(&far, big, big.all_rows()));
        }
    }

    proptest::proptest! {
        /// The keys computed in lanes from four snapped points are each
        /// point's own key: points on a sample centre's column or row, a
        /// 256th either side of one, at both ends of the range and either
        /// side of zero.
        #[test]
        fn keys_in_lanes_are_each_points_key(
            c in proptest::array::uniform8(proptest::prop_oneof![
                -MAX_COORD..=MAX_COORD,
                -40f32..40.0,
                proptest::strategy::Strategy::prop_map(
                    (-6000i32..6000, -1i32..=1),
                    |(k, d)| k as f32 * 0.5 + d as f32 / 256.0,
                ),
                proptest::sample::select(vec![MAX_COORD, -MAX_COORD, 0.0, -0.0, 0.5, -0.5]),
            ]),
        ) {
            let (x, y) = ([c[0], c[1], c[2], c[3]], [c[4], c[5], c[6], c[7]]);
            let lanes = FixedPoint::snap4(glam::Vec4::from_array(x), glam::Vec4::from_array(y));
            let lanes = lanes.expect("within the range");
            proptest::prop_assert_eq!(CentreKey::of4(&lanes), lanes.points().map(CentreKey::of));
        }
    }

    /// Samples tested, and the covered samples with their weights.
    fn walk<C: Coverage<Weights = [i64; 3]>>(
        c: &C,
        grid: Grid,
    ) -> (u64, Vec<(u32, u32, [i64; 3])>) {
        let mut hits = Vec::new();
        let tested = c.walk_samples(grid, Traversal::Incremental, |x, y, e| hits.push((x, y, e)));
        (tested, hits)
    }

    fn coverage(v: [[f32; 2]; 3], grid: Grid, t: Traversal) -> Vec<u8> {
        let mut out = vec![0u8; grid.len()];
        let mut stats = RasterStats::default();
        rasterize(v, grid, Cull::None, t, &mut stats, |x, y, _| {
            out[(y * grid.width + x) as usize] += 1
        });
        out
    }

    #[test]
    fn diagonal_split_square_follows_the_top_left_rule() {
        // The D3D example: a 5×5 square split along its diagonal. The lower
        // triangle owns the 5 diagonal samples (its diagonal edge is a left
        // edge): 15 and 10.
        let g = Grid::new(5, 5);
        let lower = coverage(
            [[0.0, 0.0], [5.0, 0.0], [5.0, 5.0]],
            g,
            Traversal::Incremental,
        );
        let upper = coverage(
            [[0.0, 0.0], [5.0, 5.0], [0.0, 5.0]],
            g,
            Traversal::Incremental,
        );
        assert_eq!(lower.iter().map(|&c| c as u32).sum::<u32>(), 15);
        assert_eq!(upper.iter().map(|&c| c as u32).sum::<u32>(), 10);
        for i in 0..25 {
            assert_eq!(lower[i] + upper[i], 1, "sample {i}");
        }
    }

    #[test]
    fn winding_does_not_change_coverage_and_cull_selects_it() {
        let g = Grid::new(8, 8);
        let ccw = [[0.3, 0.2], [7.1, 1.0], [2.0, 6.6]];
        let cw = [ccw[0], ccw[2], ccw[1]];
        assert_eq!(
            coverage(ccw, g, Traversal::Incremental),
            coverage(cw, g, Traversal::Incremental)
        );
        let mut stats = RasterStats::default();
        rasterize(
            cw,
            g,
            Cull::Back,
            Traversal::Incremental,
            &mut stats,
            |_, _, _| panic!("culled"),
        );
        rasterize(
            ccw,
            g,
            Cull::Front,
            Traversal::Incremental,
            &mut stats,
            |_, _, _| panic!("culled"),
        );
        assert_eq!(stats.culled, 2);
    }

    #[test]
    fn rejects_are_counted_not_drawn() {
        let g = Grid::new(4, 4);
        let mut stats = RasterStats::default();
        let never = |_: u32, _: u32, _: [i64; 3]| panic!("must not draw");
        rasterize(
            [[0.0, 0.0], [f32::NAN, 1.0], [1.0, 0.0]],
            g,
            Cull::None,
            Traversal::Scan,
            &mut stats,
            never,
        );
        rasterize(
            [[0.0, 0.0], [f32::INFINITY, 1.0], [1.0, 0.0]],
            g,
            Cull::None,
            Traversal::Scan,
            &mut stats,
            never,
        );
        rasterize(
            [[0.0, 0.0], [1e30, 1.0], [1.0, 0.0]],
            g,
            Cull::None,
            Traversal::Scan,
            &mut stats,
            never,
        );
        rasterize(
            [[0.0, 0.0], [2.0, 2.0], [4.0, 4.0]],
            g,
            Cull::None,
            Traversal::Scan,
            &mut stats,
            never,
        );
        // Distinct in f32, equal after the snap: zero area.
        rasterize(
            [[1.0, 1.0], [1.0001, 3.0], [1.0, 3.0]],
            g,
            Cull::None,
            Traversal::Scan,
            &mut stats,
            never,
        );
        assert_eq!(stats.dropped_non_finite, 2);
        assert_eq!(stats.dropped_out_of_range, 1);
        assert_eq!(stats.dropped_degenerate, 2);
        assert_eq!(stats.triangles_drawn, 0);
    }

    #[test]
    fn edge_values_are_barycentric_weights() {
        let g = Grid::new(16, 16);
        let v = [[0.0, 0.0], [16.0, 0.0], [0.0, 16.0]];
        let setup = Setup::new(v, g, Cull::None).unwrap();
        assert_eq!(setup.area2, 256 * 256 * 256);
        let e = setup.inside(0, 0).unwrap();
        assert_eq!(e.iter().sum::<i64>(), setup.area2);
        // At sample (0,0), centre (0.5,0.5): weights of b and c are 0.5/16.
        let weight = |vertex: usize| e[setup.order().iter().position(|&i| i == vertex).unwrap()];
        assert_eq!(weight(1), setup.area2 / 32);
        assert_eq!(weight(2), setup.area2 / 32);
    }

    #[test]
    fn bounding_box_excludes_samples_outside_and_clamps_to_grid() {
        let g = Grid::new(10, 10);
        // Vertices far off the grid: bbox clamps.
        let s = Setup::new(
            [[-100.0, -100.0], [100.0, -100.0], [0.0, 100.0]],
            g,
            Cull::None,
        )
        .unwrap();
        assert_eq!(s.bbox_samples(), 100);
        // A triangle between sample centres in x touches no column.
        let s = Setup::new([[0.6, 0.0], [1.4, 0.0], [1.0, 5.0]], g, Cull::None).unwrap();
        assert_eq!(s.bbox_samples(), 0);
        assert_eq!(s.walk(g, Traversal::Incremental, |_, _, _| panic!()), 0);
    }
}
