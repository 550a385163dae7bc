//! The f64 and f32 set-ups: the same edge functions in floating point,
//! for measuring what fixed point buys (comparison modes, `--precision`).

use super::*;

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
    pub(super) edges: [([T; 2], [T; 2], bool); 3],
    pub(super) order: [usize; 3],
    pub(super) area2: T,
    pub(super) ccw: bool,
    pub(super) x0: i64,
    pub(super) x1: i64,
    pub(super) y0: i64,
    pub(super) y1: i64,
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
