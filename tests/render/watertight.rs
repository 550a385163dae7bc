//! Shared edges are drawn exactly once: random fans and jittered quad grids
//! that tile the screen cover every sample exactly once, counted per sample
//! (not by the final colour). And the three traversals agree sample for
//! sample.

use proptest::prelude::*;
use rastty::Choice;
use rastty::raster::{RasterStats, rasterize};
use rastty::transform::Grid;
use rastty::{raster::Traversal, scene::Cull};

const W: u32 = 24;
const H: u32 = 16;

/// A coordinate on the 1/256 lattice.
fn fx(v: i32) -> f32 {
    v as f32 / 256.0
}

/// Rounds a lattice coordinate to a multiple of `g`/256. Coarse lattices
/// put vertices on sample centres and edges through them, where the
/// tie-breaking rule is what decides; arbitrary 1/256 positions rarely do.
fn coarsen(v: i32, g: i32) -> i32 {
    v.div_euclid(g) * g + if g == 256 { 128 } else { 0 }
}

/// A lattice granularity: anything, quarter samples, half samples, or
/// sample centres.
fn granularity() -> impl Strategy<Value = i32> {
    prop::sample::select(vec![1, 64, 128, 256])
}

/// Per-sample hit counts for a list of triangles.
fn counts(tris: &[[[f32; 2]; 3]], traversal: Traversal) -> Vec<u32> {
    let grid = Grid::new(W, H);
    let mut count = vec![0u32; grid.len()];
    let mut stats = RasterStats::default();
    for t in tris {
        rasterize(*t, grid, Cull::None, traversal, &mut stats, |x, y, _| {
            count[(y * W + x) as usize] += 1
        });
    }
    count
}

fn assert_exactly_once(count: &[u32]) -> Result<(), TestCaseError> {
    for (i, &c) in count.iter().enumerate() {
        prop_assert_eq!(
            c,
            1,
            "sample ({}, {}) hit {} times",
            i as u32 % W,
            i as u32 / W,
            c
        );
    }
    Ok(())
}

/// A point on the perimeter of the rectangle `[x0,x1]×[y0,y1]` (in 1/256
/// units) at parameter `t` along it, counter-clockwise from (x0, y0).
fn perimeter_point(t: i64, x0: i64, y0: i64, x1: i64, y1: i64) -> [i64; 2] {
    let (w, h) = (x1 - x0, y1 - y0);
    let t = t.rem_euclid(2 * (w + h));
    if t < w {
        [x0 + t, y0]
    } else if t < w + h {
        [x1, y0 + (t - w)]
    } else if t < 2 * w + h {
        [x1 - (t - w - h), y1]
    } else {
        [x0, y1 - (t - 2 * w - h)]
    }
}

/// Triangles fanned around a centre inside the screen out to the perimeter
/// of a rectangle enclosing it, its four corners included, so that their
/// union covers the whole screen. `flips` reverses some triangles' winding.
fn fan(centre: [i32; 2], cuts: Vec<i64>, flips: Vec<bool>, g: i32) -> Vec<[[f32; 2]; 3]> {
    let (x0, y0, x1, y1) = (
        -512i64,
        -256,
        (W * 256) as i64 + 256,
        (H * 256) as i64 + 512,
    );
    let (w, h) = (x1 - x0, y1 - y0);
    let mut ts: Vec<i64> = cuts
        .into_iter()
        .map(|c| coarsen(c.rem_euclid(2 * (w + h)) as i32, g) as i64)
        .collect();
    ts.extend([0, w, w + h, 2 * w + h]);
    ts.sort();
    ts.dedup();
    let c = [fx(coarsen(centre[0], g)), fx(coarsen(centre[1], g))];
    let pts: Vec<[f32; 2]> = ts
        .iter()
        .map(|&t| {
            let p = perimeter_point(t, x0, y0, x1, y1);
            [fx(p[0] as i32), fx(p[1] as i32)]
        })
        .collect();
    (0..pts.len())
        .map(|i| {
            let (a, b) = (pts[i], pts[(i + 1) % pts.len()]);
            if flips[i % flips.len()] {
                [c, b, a]
            } else {
                [c, a, b]
            }
        })
        .collect()
}

/// A grid of quads over a rectangle enclosing the screen, each inner
/// vertex jittered by less than a quarter of the spacing (so that every quad
/// stays convex: at each corner the cross product of the two edges is at
/// least (s/2)² − (s/2)² = 0), each quad split along
/// a diagonal chosen by `diagonals` (either works: the quads stay convex),
/// with windings flipped by `flips`.
fn quad_grid(
    nx: usize,
    ny: usize,
    jitter: Vec<(i32, i32)>,
    diagonals: Vec<bool>,
    flips: Vec<bool>,
    g: i32,
) -> Vec<[[f32; 2]; 3]> {
    let (x0, y0) = (-256 - 77, -256 - 13);
    let (x1, y1) = ((W * 256) as i32 + 99, (H * 256) as i32 + 301);
    let sx = (x1 - x0) / nx as i32;
    let sy = (y1 - y0) / ny as i32;
    let vertex = |i: usize, j: usize| -> [f32; 2] {
        let (mut x, mut y) = (x0 + i as i32 * sx, y0 + j as i32 * sy);
        if i == nx {
            x = x1;
        }
        if j == ny {
            y = y1;
        }
        if i > 0 && i < nx && j > 0 && j < ny {
            let (jx, jy) = jitter[(j * (nx + 1) + i) % jitter.len()];
            // Coarsening moves a vertex by up to `g` more; keeping the total
            // under a quarter of the spacing keeps every quad convex.
            let (ax, ay) = ((sx / 4 - g - 1).max(0), (sy / 4 - g - 1).max(0));
            x += jx * ax / 1000;
            y += jy * ay / 1000;
        }
        // Every vertex is coarsened, the outer ones too, so that a column
        // (row) of unjittered vertices stays a straight line.
        [fx(coarsen(x, g)), fx(coarsen(y, g))]
    };
    let mut tris = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let k = j * nx + i;
            let (a, b, c, d) = (
                vertex(i, j),
                vertex(i + 1, j),
                vertex(i + 1, j + 1),
                vertex(i, j + 1),
            );
            let pair = if diagonals[k % diagonals.len()] {
                [[a, b, c], [a, c, d]]
            } else {
                [[a, b, d], [b, c, d]]
            };
            for (n, t) in pair.into_iter().enumerate() {
                let flip = flips[(2 * k + n) % flips.len()];
                tris.push(if flip { [t[0], t[2], t[1]] } else { t });
            }
        }
    }
    tris
}

proptest! {
    // 200 cases by default; PROPTEST_CASES=N runs more.
    #![proptest_config(ProptestConfig::with_cases(
        std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(200)
    ))]

    #[test]
    fn fans_cover_every_sample_exactly_once(
        cx in 1..(W as i32 * 256 - 1),
        cy in 1..(H as i32 * 256 - 1),
        cuts in prop::collection::vec(any::<i64>(), 0..40),
        flips in prop::collection::vec(any::<bool>(), 1..8),
        g in granularity(),
    ) {
        let tris = fan([cx, cy], cuts, flips, g);
        assert_exactly_once(&counts(&tris, Traversal::Incremental))?;
    }

    #[test]
    fn jittered_quad_grids_cover_every_sample_exactly_once(
        nx in 1usize..12,
        ny in 1usize..9,
        jitter in prop::collection::vec((-1000i32..=1000, -1000i32..=1000), 1..64),
        diagonals in prop::collection::vec(any::<bool>(), 1..16),
        flips in prop::collection::vec(any::<bool>(), 1..16),
        g in granularity(),
    ) {
        let tris = quad_grid(nx, ny, jitter, diagonals, flips, g);
        assert_exactly_once(&counts(&tris, Traversal::Incremental))?;
    }

    #[test]
    fn traversals_visit_the_same_samples_with_the_same_edge_values(
        v in prop::array::uniform3((-2000i32..(W as i32 * 256 + 2000), -2000i32..(H as i32 * 256 + 2000))),
        scale in prop::sample::select(vec![1i32, 16, 256]),
        g in granularity(),
    ) {
        let grid = Grid::new(W, H);
        // Scaling about the grid's centre gives tiny triangles and large ones.
        let c = [(W * 128) as i32, (H * 128) as i32];
        let tri = v.map(|(x, y)| {
            [fx(coarsen(c[0] + (x - c[0]) / scale, g)), fx(coarsen(c[1] + (y - c[1]) / scale, g))]
        });
        let mut seen = Vec::new();
        for &t in Traversal::ALL {
            let mut hits = Vec::new();
            let mut stats = RasterStats::default();
            rasterize(tri, grid, Cull::None, t, &mut stats, |x, y, e| hits.push((x, y, e)));
            seen.push(hits);
        }
        prop_assert_eq!(&seen[0], &seen[1]);
        prop_assert_eq!(&seen[1], &seen[2]);
    }
}

#[test]
fn a_fan_around_a_sample_centre_covers_it_once() {
    // The centre sits exactly on sample (5, 5)'s centre: every triangle has
    // it as a vertex, exactly one owns it.
    let tris = fan(
        [5 * 256 + 128, 5 * 256 + 128],
        vec![100, 2000, 7000, 9000, 11111],
        vec![false, true],
        1,
    );
    assert_eq!(
        counts(&tris, Traversal::Incremental)
            .iter()
            .filter(|&&c| c != 1)
            .count(),
        0
    );
}
