//! The precision and traversal knobs: cracks and double hits of each
//! precision on random tilings, and traversals against the default.

use super::*;

/// Tilings of a 64×48-sample screen, each drawn by the renderer (as a
/// flat scene in the canonical cube, one sample a cell) with `precision`:
/// samples covered no times (cracks: left empty) and more than once (double
/// hits: the renderer's covered count beyond the samples drawn). Half are
/// jittered quad grids (vertices anywhere, either diagonal), where edges
/// seldom pass near a sample centre; half are fans around a sample centre
/// whose spokes run through further sample centres (their far ends, at
/// thirds of a sample, are not exact in binary): there the unsnapped edge
/// functions of two neighbours round differently.
pub fn precision_errors(precision: Precision) -> (u64, u64) {
    let (w, h) = (64u32, 48u32);
    let grid = Grid::new(w, h);
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let mut tilings = Vec::new();
    for _ in 0..10 {
        let (nx, ny) = (23usize, 17usize);
        let (sx, sy) = ((w as f64 + 6.0) / nx as f64, (h as f64 + 6.0) / ny as f64);
        let mut v = vec![[0.0f32; 2]; (nx + 1) * (ny + 1)];
        for j in 0..=ny {
            for i in 0..=nx {
                let inner = i > 0 && i < nx && j > 0 && j < ny;
                let (jx, jy) = if inner {
                    (
                        (rng.next() - 0.5) * 0.45 * sx,
                        (rng.next() - 0.5) * 0.45 * sy,
                    )
                } else {
                    (0.0, 0.0)
                };
                v[j * (nx + 1) + i] = [
                    (-3.0 + i as f64 * sx + jx) as f32,
                    (-3.0 + j as f64 * sy + jy) as f32,
                ];
            }
        }
        let mut tris = Vec::new();
        for j in 0..ny {
            for i in 0..nx {
                let at = |i: usize, j: usize| v[j * (nx + 1) + i];
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                if rng.next() < 0.5 {
                    tris.push([a, b, c]);
                    tris.push([a, c, d]);
                } else {
                    tris.push([a, b, d]);
                    tris.push([b, c, d]);
                }
            }
        }
        tilings.push(tris);
    }
    for k in 0..10u32 {
        let centre = [(20 + 2 * k) as f32 + 0.5, (14 + k) as f32 + 0.5];
        // Primitive directions (p, q), |p|, |q| ≤ 3, by angle.
        let mut dirs: Vec<(i32, i32)> = (-3..=3)
            .flat_map(|p| (-3..=3).map(move |q| (p, q)))
            .filter(|&(p, q): &(i32, i32)| {
                (p, q) != (0, 0) && gcd(p.unsigned_abs(), q.unsigned_abs()) == 1
            })
            .collect();
        dirs.sort_by(|a, b| {
            (a.1 as f64)
                .atan2(a.0 as f64)
                .total_cmp(&(b.1 as f64).atan2(b.0 as f64))
        });
        let s = (200 + k) as f32 / 3.0;
        let ends: Vec<[f32; 2]> = dirs
            .iter()
            .map(|&(p, q)| [centre[0] + s * p as f32, centre[1] + s * q as f32])
            .collect();
        tilings.push(
            (0..ends.len())
                .map(|i| [centre, ends[i], ends[(i + 1) % ends.len()]])
                .collect(),
        );
    }
    let opts = RenderOptions {
        cols: w as u16,
        rows: h as u16,
        glyphs: GlyphMode::Block,
        precision,
        ..RenderOptions::default()
    };
    let mut renderer = Renderer::new();
    let (mut cracks, mut doubles) = (0, 0);
    for tris in &tilings {
        let scene = Scene::in_canonical_cube(
            tris.iter()
                .map(|t| Triangle {
                    vertices: t.map(|[x, y]| {
                        Vec3::new(2.0 * x / w as f32 - 1.0, 2.0 * y / h as f32 - 1.0, 0.0)
                    }),
                    color: TriangleColor::Flat(Rgb::WHITE),
                })
                .collect(),
        );
        renderer.render(&scene, &opts);
        let drawn = renderer
            .framebuffer()
            .samples()
            .iter()
            .filter(|s| s.is_some())
            .count() as u64;
        cracks += grid.len() as u64 - drawn;
        doubles += renderer.stats().raster.samples_covered - drawn;
    }
    (cracks, doubles)
}

pub(super) fn gcd(a: u32, b: u32) -> u32 {
    if b == 0 { a } else { gcd(b, a % b) }
}

/// Samples of every workload's frame drawn differently by `traversal` than
/// by the default one (spans).
pub(super) fn traversal_mismatch(workloads: &[Workload], traversal: Traversal) -> u64 {
    samples_unlike(workloads, |opts| RenderOptions { traversal, ..opts })
}

/// Samples of every workload's frame (80×24 cells) drawn differently with
/// the options `change` makes of the base ones than with the base ones.
pub(super) fn samples_unlike(
    workloads: &[Workload],
    change: impl Fn(RenderOptions) -> RenderOptions,
) -> u64 {
    let opts = RenderOptions {
        cols: 80,
        rows: 24,
        ..base()
    };
    workloads
        .iter()
        .map(|w| {
            let mut a = Renderer::new();
            let mut b = Renderer::new();
            a.render(&w.scene, &opts);
            b.render(&w.scene, &change(opts));
            a.framebuffer()
                .samples()
                .iter()
                .zip(b.framebuffer().samples())
                .filter(|(x, y)| x != y)
                .count() as u64
        })
        .sum()
}
