//! What accuracy costs: the exact measures that the accuracy knobs are
//! judged by (`rastty bench`).
//!
//! The reference for coverage is analytic: the area of a triangle inside a
//! square (a sample's or a cell's), found by clipping the triangle to the
//! square in f64 (Sutherland–Hodgman against four axis-aligned lines) and
//! taking the polygon's area (the shoelace formula). `--aa exact` draws
//! with the same function.

/// The area of triangle `t` inside the unit square at `corner` (its lower
/// left), in f64.
pub fn area_in_square(t: [[f64; 2]; 3], corner: [f64; 2]) -> f64 {
    area_in_rect(t, corner, [corner[0] + 1.0, corner[1] + 1.0])
}

/// The area of triangle `t` inside the rectangle `[lo, hi]`.
pub fn area_in_rect(t: [[f64; 2]; 3], lo: [f64; 2], hi: [f64; 2]) -> f64 {
    polygon_area_in_rect(&t, lo, hi)
}

/// Most vertices a clipped polygon here can have.
const MAX: usize = 16;

/// A convex polygon of at most 16 vertices, on the stack.
#[derive(Clone, Copy, Debug)]
pub struct Poly {
    v: [[f64; 2]; MAX],
    n: usize,
}

impl Poly {
    /// A polygon from its vertices (at most 16), in either winding.
    pub fn new(points: &[[f64; 2]]) -> Poly {
        let mut p = Poly {
            v: [[0.0; 2]; MAX],
            n: points.len().min(MAX),
        };
        p.v[..p.n].copy_from_slice(&points[..p.n]);
        if p.signed_area2() < 0.0 {
            p.v[..p.n].reverse();
        }
        p
    }

    /// The corners, counter-clockwise.
    pub fn vertices(&self) -> &[[f64; 2]] {
        &self.v[..self.n]
    }

    fn signed_area2(&self) -> f64 {
        let v = self.vertices();
        (0..v.len())
            .map(|i| {
                let (a, b) = (v[i], v[(i + 1) % v.len()]);
                a[0] * b[1] - b[0] * a[1]
            })
            .sum()
    }

    /// The area.
    pub fn area(&self) -> f64 {
        if self.n < 3 {
            0.0
        } else {
            self.signed_area2().abs() / 2.0
        }
    }

    /// What is left on the side of `keep(p) ≥ 0`, for an affine `keep`
    /// (Sutherland–Hodgman against one line).
    fn clip(&self, keep: impl Fn([f64; 2]) -> f64) -> Poly {
        let mut out = Poly {
            v: [[0.0; 2]; MAX],
            n: 0,
        };
        let v = self.vertices();
        for i in 0..v.len() {
            let (p, q) = (v[i], v[(i + 1) % v.len()]);
            let (dp, dq) = (keep(p), keep(q));
            if dp >= 0.0 && out.n < MAX {
                out.v[out.n] = p;
                out.n += 1;
            }
            if (dp >= 0.0) != (dq >= 0.0) && out.n < MAX {
                let t = dp / (dp - dq);
                out.v[out.n] = [p[0] + (q[0] - p[0]) * t, p[1] + (q[1] - p[1]) * t];
                out.n += 1;
            }
        }
        out
    }

    /// The part inside the rectangle `[lo, hi]`.
    pub fn in_rect(&self, lo: [f64; 2], hi: [f64; 2]) -> Poly {
        self.clip(|p| p[0] - lo[0])
            .clip(|p| hi[0] - p[0])
            .clip(|p| p[1] - lo[1])
            .clip(|p| hi[1] - p[1])
    }

    /// The part inside another convex polygon.
    pub fn intersect(&self, other: &Poly) -> Poly {
        let mut out = *self;
        let w = other.vertices();
        for i in 0..w.len() {
            let (a, b) = (w[i], w[(i + 1) % w.len()]);
            // Counter-clockwise: inside is to the left of each edge.
            out = out.clip(|p| (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]));
            if out.n < 3 {
                break;
            }
        }
        out
    }
}

/// The area of a convex polygon inside the rectangle `[lo, hi]`.
pub fn polygon_area_in_rect(points: &[[f64; 2]], lo: [f64; 2], hi: [f64; 2]) -> f64 {
    Poly::new(points).in_rect(lo, hi).area()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_shapes_have_their_areas() {
        // A triangle covering the whole square, and more.
        assert_eq!(
            area_in_square([[-1.0, -1.0], [5.0, -1.0], [-1.0, 5.0]], [0.0, 0.0]),
            1.0
        );
        // A half-covered cell: the diagonal through it.
        assert_eq!(
            area_in_square([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]], [0.0, 0.0]),
            0.5
        );
        assert_eq!(
            area_in_square([[-3.0, -3.0], [4.0, -3.0], [4.0, 4.0]], [0.0, 0.0]),
            0.5
        );
        // A triangle over the cell's corner: the right triangle with legs
        // 0.5 and 0.25 inside it, 1/16 of the cell.
        let corner = [[0.5, 1.0], [1.0, 1.0], [1.0, 0.75]];
        assert!((area_in_square(corner, [0.0, 0.0]) - 0.0625).abs() < 1e-15);
        // The same triangle extended beyond the corner: only the part
        // inside counts (legs 0.5 and 0.25 again).
        let beyond = [[0.5, 1.0], [1.5, 1.0], [1.0, 0.75]];
        let inside_part = area_in_square(beyond, [0.0, 0.0]);
        assert!((inside_part - 0.0625).abs() < 1e-15, "{inside_part}");
        // Outside: nothing. Either winding: the same.
        assert_eq!(
            area_in_square([[2.0, 2.0], [3.0, 2.0], [2.0, 3.0]], [0.0, 0.0]),
            0.0
        );
        assert_eq!(
            area_in_square([[0.0, 0.0], [1.0, 1.0], [1.0, 0.0]], [0.0, 0.0]),
            0.5
        );
        // A strip a quarter high across the square.
        // A wide triangle over a 2 × 0.25 rectangle: its width at height y
        // is 20·(1 − 2y) ≥ 2 for y ≤ 0.45, so it covers the rectangle: 0.5.
        assert_eq!(
            area_in_rect(
                [[-10.0, 0.0], [10.0, 0.0], [0.0, 0.5]],
                [-1.0, 0.0],
                [1.0, 0.25]
            ),
            0.5
        );
    }

    #[test]
    fn two_triangles_overlap_by_their_common_part() {
        // Two right triangles over the unit square, one on each diagonal:
        // they share a quarter of it.
        let a = Poly::new(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
        let b = Poly::new(&[[1.0, 0.0], [1.0, 1.0], [0.0, 0.0]]);
        assert!((a.intersect(&b).area() - 0.25).abs() < 1e-15);
        assert!((a.intersect(&b).in_rect([0.0, 0.0], [0.5, 0.5]).area() - 0.125).abs() < 1e-15);
        // Disjoint: nothing.
        let c = Poly::new(&[[2.0, 2.0], [3.0, 2.0], [2.0, 3.0]]);
        assert_eq!(a.intersect(&c).area(), 0.0);
    }
}
