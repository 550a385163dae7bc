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
    // At most 3 + 4 vertices after four clips.
    let mut a = [[0.0; 2]; 8];
    let mut b = [[0.0; 2]; 8];
    a[..3].copy_from_slice(&t);
    let mut n = 3;
    // (axis, bound, keep the side below the bound?)
    for (axis, bound, below) in [
        (0, lo[0], false),
        (0, hi[0], true),
        (1, lo[1], false),
        (1, hi[1], true),
    ] {
        let inside = |p: &[f64; 2]| {
            if below {
                p[axis] <= bound
            } else {
                p[axis] >= bound
            }
        };
        let mut m = 0;
        for i in 0..n {
            let (p, q) = (a[i], a[(i + 1) % n]);
            if inside(&p) {
                b[m] = p;
                m += 1;
            }
            if inside(&p) != inside(&q) {
                let s = (bound - p[axis]) / (q[axis] - p[axis]);
                let mut r = [p[0] + (q[0] - p[0]) * s, p[1] + (q[1] - p[1]) * s];
                r[axis] = bound;
                b[m] = r;
                m += 1;
            }
        }
        std::mem::swap(&mut a, &mut b);
        n = m;
        if n < 3 {
            return 0.0;
        }
    }
    let twice: f64 = (0..n)
        .map(|i| a[i][0] * a[(i + 1) % n][1] - a[(i + 1) % n][0] * a[i][1])
        .sum();
    twice.abs() / 2.0
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
}
