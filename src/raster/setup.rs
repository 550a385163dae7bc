//! The general fixed-point set-up: any snapped triangle, culled and
//! oriented, its edges stepped incrementally over its clamped box with the
//! top-left rule, by any traversal.

use super::*;

/// A triangle set up for rasterization: snapped, oriented, bounded.
#[derive(Clone, Copy, Debug)]
pub struct Setup {
    /// `edges[k]` is the edge opposite vertex `order[k]`, so its value at a
    /// sample is the (unnormalised) barycentric weight of that vertex.
    pub(super) edges: [Edge; 3],
    /// The vertices in the order the edges follow: a rotation of the
    /// caller's, starting from the lowest vertex.
    pub(super) order: [usize; 3],
    /// Twice the snapped area in fixed-point units squared (> 0); the sum of
    /// the three edge values at any point.
    pub(super) area2: i64,
    /// Whether the triangle is counter-clockwise on screen (front-facing).
    pub(super) ccw: bool,
    /// Inclusive sample bounds, clamped to the grid; empty when `x0 > x1` or
    /// `y0 > y1`.
    pub(super) x0: i64,
    pub(super) x1: i64,
    pub(super) y0: i64,
    pub(super) y1: i64,
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

    /// Sets up a triangle already snapped, or says why it draws nothing
    /// ([`SnappedTriangle::new`]).
    #[inline]
    pub fn from_fixed(p: [FixedPoint; 3], grid: Grid, cull: Cull) -> Result<Setup, Rejected> {
        Ok(Setup::of(
            &SnappedTriangle::new(p, cull)?,
            grid,
            grid.all_rows(),
        ))
    }

    /// The set-up of an accepted triangle, its bounding box clamped to
    /// `grid`'s columns and `band`'s rows: the part of the triangle one band
    /// of a parallel frame draws (`grid.all_rows()` for the whole). The
    /// edge values at a sample are exact integers, whatever row the walk
    /// starts from, so the bands together cover exactly the samples the
    /// whole grid's set-up covers, with the same weights. One whose box
    /// holds no sample centre (most triangles of a detailed model seen
    /// small) is set up without its edges: nothing will evaluate them.
    #[inline(always)]
    pub fn of(t: &SnappedTriangle, grid: Grid, band: Band) -> Setup {
        let (p, area2) = (t.vertices(), t.signed_area2());
        let ccw = area2 > 0;
        let [x0, x1, y0, y1] = clamped_box(&extent(&p), grid, band);
        if x0 > x1 || y0 > y1 {
            // A return of its own rather than one `Setup { .. }` below
            // with the edges chosen by an `if`, which the compiler keeps
            // off the common path.
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

    /// Whether the sample centre `(x + 0.5, y + 0.5)` is inside, with its
    /// three edge values.
    #[inline(always)]
    pub fn inside(&self, x: u32, y: u32) -> Option<[i64; 3]> {
        let (px, py) = (Fixed::sample_centre(x).0, Fixed::sample_centre(y).0);
        let e = self.edges.map(|e| e.at(px, py));
        self.accepts(e).then_some(e)
    }

    #[inline(always)]
    pub(super) fn accepts(&self, e: [i64; 3]) -> bool {
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
    /// three sum to twice the area). Returns the number of samples tested.
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
                        // Written out: `map`'s closure was not always
                        // inlined here (a call a row).
                        let mut e = [
                            row[0] + lo * sx[0],
                            row[1] + lo * sx[1],
                            row[2] + lo * sx[2],
                        ];
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
    pub(super) fn walk_other<F: FnMut(u32, u32, [i64; 3])>(
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
    pub(super) fn steps(&self) -> ([i64; 3], [i64; 3], [i64; 3]) {
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
    pub(super) fn span(&self, row: [i64; 3], sx: [i64; 3], last: i64) -> (i64, i64) {
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

    /// Each sample of a box of at most `SMALL_BOX` (8) samples tested
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
