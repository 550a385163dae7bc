//! The set-up of a triangle whose box holds at most [`SMALL_BOX`] samples
//! (most triangles of a detailed model seen small): every sample of the
//! box tested at once, the covered ones kept as bits.

use super::*;

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
/// weights and counts as [`Setup::of`] and its walk (a test
/// compares the two).
#[derive(Clone, Copy, Debug)]
pub(crate) struct SmallSetup {
    /// The vertices in `order`.
    pub(super) p: [FixedPoint; 3],
    pub(super) order: [u8; 3],
    pub(super) ccw: bool,
    pub(super) area2: i64,
    /// The box's first sample, its width and height.
    pub(super) x0: u32,
    pub(super) y0: u32,
    pub(super) w: u8,
    pub(super) h: u8,
    /// Samples in the clamped box, all tested.
    pub(super) tested: u8,
    /// Bit k: the box's sample k (rows bottom to top, left to right) is
    /// covered.
    pub(super) covered: u8,
}

impl SmallSetup {
    /// Sets up an accepted triangle as [`Setup::of`] does, when its box
    /// clamped to `grid`'s columns and `band`'s rows holds at most
    /// [`SMALL_BOX`] samples: `None` when it holds more.
    #[inline(always)]
    pub(crate) fn of(t: &SnappedTriangle, grid: Grid, band: Band) -> Option<SmallSetup> {
        let (p, area2) = (t.vertices(), t.signed_area2());
        let extent = &extent(&p);
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
