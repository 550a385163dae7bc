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
//!   counted in [`RasterStats`]. Range, area and culling are decided in one
//!   place, [`SnappedTriangle`], from which every fixed-point set-up
//!   derives.
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
//! tests each sample of a box of at most `SMALL_BOX` (8) once, at set-up,
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

#[cfg(doc)]
use crate::fixed::SnappedLanes;
use crate::fixed::{FRAC_BITS, Fixed, FixedPoint, MAX_COORD, ONE};
use crate::scene::Cull;
use crate::transform::{Band, Grid, MAX_GRID, Rect};
use wide::i32x4;

mod edge;
mod float;
mod setup;
mod small;
mod snapped;

use edge::*;

pub(crate) use edge::CentreKey;
pub(crate) use float::FloatSetup;
pub use setup::{Rejected, Setup};
pub(crate) use small::SMALL_BOX;
pub(crate) use small::SmallSetup;
pub(crate) use snapped::Culling;
pub use snapped::SnappedTriangle;
pub(crate) use snapped::signed_area2;

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
    /// Dropped unseen: the snapped vertices show that the bounding box
    /// holds no sample centre, before the area or the winding is looked at
    /// (on the lean path: `crate::Effect::Lean`).
    pub found_empty: u64,
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
        self.found_empty += o.found_empty;
        self.samples_tested += o.samples_tested;
        self.samples_covered += o.samples_covered;
    }
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
    /// Whether any sample may be covered: the one test of "covers
    /// nothing" the renderer acts on (the plan's lean path lights and
    /// fills only triangles it passes). `false` exactly when the box holds
    /// no sample centre or, for a box of at most `SMALL_BOX` samples, when
    /// the walk would find none inside; a larger box says `true` and is
    /// walked. (The vertex stage's `CentreKey` tells an empty box before
    /// set-up; a property test holds it to the set-up's box.) The f32 and
    /// f64 set-ups, which only the comparison modes use, always say `true`.
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
    pub(crate) fn count_rejected(&mut self, r: Rejected) {
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
            // In range, the vertex stage's acceptance is the same.
            proptest::prop_assert_eq!(SnappedTriangle::in_range(p, cull), SnappedTriangle::new(p, cull));
            let t = SnappedTriangle::new(p, cull);
            match (t.map(|t| SmallSetup::of(&t, grid, band)), t.map(|t| Setup::of(&t, grid, band))) {
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
            if let Ok(s) = SnappedTriangle::new(p, cull).map(|t| Setup::of(&t, grid, band)) {
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
            proptest::prop_assert_eq!(CentreKey::of4(lanes.pairs()), lanes.points().map(CentreKey::of));
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
