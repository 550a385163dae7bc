//! The coverage knob: samples per cell and anti-aliasing against the
//! analytic area of random triangles in each cell.

use super::*;

/// Random triangles over a `w × h` cell area, a third each small (about a
/// cell), medium and large.
pub(super) fn random_triangles(n: usize, w: f64, h: f64) -> Vec<[[f64; 2]; 3]> {
    let mut rng = Rng(0x2545_F491_4F6C_DD1D);
    (0..n)
        .map(|i| {
            let size = [1.5, 6.0, 25.0][i % 3];
            let (cx, cy) = (rng.next() * w, rng.next() * h);
            std::array::from_fn(|_| {
                [
                    cx + (rng.next() - 0.5) * size,
                    cy + (rng.next() - 0.5) * size * 0.5,
                ]
            })
        })
        .collect()
}

/// How many random triangles the coverage knob is measured on.
pub(super) const COVERAGE_TRIANGLES: usize = 300;

/// The coverage knob's error measures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CoverageError {
    /// Mean and largest absolute error of a cell's coverage, each triangle
    /// alone.
    pub mean: f64,
    /// Largest absolute error of a cell's coverage, each triangle alone.
    pub max: f64,
    /// Largest error where two triangles overlap (the union's coverage):
    /// what `--aa exact`, which ignores depth, gets wrong.
    pub overlap_max: f64,
}

/// `tris` (in cells, y up, on a 40×12-cell screen) rendered by the
/// renderer in `glyphs` with `aa`: every cell's coverage (the mean of its
/// samples' coverage as [`Renderer::coverage`] reports it) against the
/// exact area, each triangle alone, then overlapping a copy of itself moved
/// by a third of a cell, against the exact area of their union.
pub fn coverage_error(tris: &[[[f64; 2]; 3]], glyphs: GlyphMode, aa: Aa) -> CoverageError {
    let (cols, rows) = (40u16, 12u16);
    let opts = RenderOptions {
        cols,
        rows,
        glyphs,
        aa,
        color: ColorDepth::TrueColor,
        ..RenderOptions::default()
    };
    let (w, h) = glyphs.cell_size();
    let grid = glyphs.grid(cols, rows);
    let ndc = |t: &[[f64; 2]; 3]| {
        t.map(|[x, y]| {
            Vec3::new(
                (2.0 * x / cols as f64 - 1.0) as f32,
                (2.0 * y / rows as f64 - 1.0) as f32,
                0.0,
            )
        })
    };
    // What the renderer was given, back in cells (its f32 rounding is part
    // of the scene, not of the error).
    let cells = |v: [Vec3; 3]| {
        v.map(|p| {
            [
                (p.x as f64 + 1.0) * cols as f64 / 2.0,
                (p.y as f64 + 1.0) * rows as f64 / 2.0,
            ]
        })
    };
    let mut renderer = Renderer::new();
    let mut cov = Vec::new();
    let mut measure = |tris: &[[Vec3; 3]], exact: &dyn Fn([f64; 2], [f64; 2]) -> f64| {
        let scene = Scene::in_canonical_cube(
            tris.iter()
                .map(|&vertices| Triangle {
                    vertices,
                    color: TriangleColor::Flat(Rgb::WHITE),
                })
                .collect(),
        );
        renderer.render(&scene, &opts);
        renderer.coverage(&mut cov);
        let mut errors = Vec::new();
        for cy in 0..rows as u32 {
            for cx in 0..cols as u32 {
                let mut sum = 0.0;
                for y in cy * h..(cy + 1) * h {
                    for x in cx * w..(cx + 1) * w {
                        sum += cov[(y * grid.width + x) as usize] as f64;
                    }
                }
                let estimate = sum / (w * h) as f64;
                let want = exact([cx as f64, cy as f64], [cx as f64 + 1.0, cy as f64 + 1.0]);
                if want > 0.0 || estimate > 0.0 {
                    errors.push((estimate - want).abs());
                }
            }
        }
        errors
    };
    let (mut sum, mut n, mut max) = (0.0, 0usize, 0.0f64);
    for t in tris {
        let v = ndc(t);
        let c = cells(v);
        for e in measure(&[v], &|lo, hi| area_in_rect(c, lo, hi)) {
            sum += e;
            n += 1;
            max = max.max(e);
        }
    }
    let mut overlap_max = 0.0f64;
    for t in tris {
        // The triangle and itself moved by a third of a cell: they overlap
        // everywhere but along a thin band at their edges.
        let moved = t.map(|[x, y]| [x + 1.0 / 3.0, y + 0.25]);
        let (a, b) = (ndc(t), ndc(&moved));
        let (pa, pb) = (Poly::new(&cells(a)), Poly::new(&cells(b)));
        let both = pa.intersect(&pb);
        if both.area() == 0.0 {
            continue;
        }
        let union = |lo, hi| {
            pa.in_rect(lo, hi).area() + pb.in_rect(lo, hi).area() - both.in_rect(lo, hi).area()
        };
        for e in measure(&[a, b], &union) {
            overlap_max = overlap_max.max(e);
        }
    }
    CoverageError {
        mean: sum / n.max(1) as f64,
        max,
        overlap_max,
    }
}
