//! Stage 3: clipping in homogeneous space, before the perspective divide.
//!
//! A triangle is clipped (Sutherland–Hodgman) against seven planes, each a
//! half-space `dist(p) ≥ 0` of clip-space points:
//!
//! * `w ≥ W_MIN`: nothing is ever divided by a `w` that is zero, negative or
//!   denormal, whatever the caller feeds in;
//! * near `z ≤ w` and far `z ≥ −w`: the canonical cube's z range (larger z
//!   nearer); for a perspective camera the near plane also means
//!   `w ≥ near > 0`, so geometry behind the eye disappears instead of being
//!   mirrored onto the screen;
//! * the guard band `|x| ≤ g_x·w`, `|y| ≤ g_y·w`: far outside the screen
//!   (±2^20 samples), so almost nothing is ever clipped by it, but every
//!   vertex the rasterizer sees stays inside the range where its `i64`
//!   edge functions cannot overflow (see `raster`). The screen edges
//!   themselves are never clipped against: the rasterizer's bounding box
//!   does that for free and exactly.
//!
//! The result is a convex polygon of at most 10 vertices, held in a fixed
//! array (no allocation), fanned into triangles.
//!
//! **Watertight clipping.** Where two triangles share an edge that crosses a
//! plane, both must compute the same new vertex. The intersection is always
//! computed from the inside endpoint towards the outside one, whatever the
//! direction the triangle walks the edge, so the arithmetic, and the f32
//! result, are identical for both.
//!
//! The cost, for scenes that do not need it: seven comparisons per vertex
//! for the trivial accept test ([`Clipper::outcode`]); the planner skips even
//! that for geometry whose bounding box is inside.

use glam::{Vec3, Vec4};

/// Smallest `w` that survives clipping.
pub const W_MIN: f32 = 1e-5;
/// Half-width of the guard band in samples, measured from the grid's centre.
pub const GUARD_SAMPLES: f32 = (1u32 << 20) as f32;
/// Largest number of vertices a triangle clipped by seven planes can have.
pub const MAX_POLYGON: usize = 10;

/// A clip-space vertex and the attribute interpolated across it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ClipVertex {
    pub pos: Vec4,
    /// Colour channels in [0, 255].
    pub color: Vec3,
}

impl ClipVertex {
    fn lerp(a: &ClipVertex, b: &ClipVertex, t: f32) -> ClipVertex {
        ClipVertex {
            pos: a.pos + (b.pos - a.pos) * t,
            color: a.color + (b.color - a.color) * t,
        }
    }
}

/// A plane `dist(p) = n·p + d`, inside where `dist ≥ 0`, and how to put a
/// point exactly onto it: coordinate `axis` becomes `k·w` (or, for the `w`
/// axis, `k`).
#[derive(Clone, Copy, Debug)]
struct Plane {
    n: Vec4,
    d: f32,
    axis: usize,
    k: f32,
}

impl Plane {
    #[inline(always)]
    fn dist(&self, p: Vec4) -> f32 {
        self.n.dot(p) + self.d
    }

    /// Moves `p` onto the plane along one axis. A vertex made by clipping
    /// lands there only up to rounding, and with far-away endpoints (1e30)
    /// that rounding is as large as the guard band itself; set exactly, the
    /// plane's own coordinate is right whatever the endpoints.
    fn put_on(&self, p: &mut Vec4) {
        if self.axis == 3 {
            p.w = self.k;
        } else {
            p[self.axis] = self.k * p.w;
        }
    }
}

/// The seven clip planes for a grid of `width × height` samples.
#[derive(Clone, Copy, Debug)]
pub struct Clipper {
    planes: [Plane; 7],
    gx: f32,
    gy: f32,
}

impl Clipper {
    pub fn new(width: u32, height: u32) -> Clipper {
        // The viewport maps NDC x to (x + 1)·W/2, so |x_screen − W/2| ≤ G
        // samples is |x_ndc| ≤ 2G/W.
        let gx = 2.0 * GUARD_SAMPLES / width.max(1) as f32;
        let gy = 2.0 * GUARD_SAMPLES / height.max(1) as f32;
        let p = |x, y, z, w, d, axis, k| Plane {
            n: Vec4::new(x, y, z, w),
            d,
            axis,
            k,
        };
        Clipper {
            planes: [
                p(0.0, 0.0, 0.0, 1.0, -W_MIN, 3, W_MIN),
                p(0.0, 0.0, -1.0, 1.0, 0.0, 2, 1.0),
                p(0.0, 0.0, 1.0, 1.0, 0.0, 2, -1.0),
                p(-1.0, 0.0, 0.0, gx, 0.0, 0, gx),
                p(1.0, 0.0, 0.0, gx, 0.0, 0, -gx),
                p(0.0, -1.0, 0.0, gy, 0.0, 1, gy),
                p(0.0, 1.0, 0.0, gy, 0.0, 1, -gy),
            ],
            gx,
            gy,
        }
    }

    /// Bit `i` set when the point is outside plane `i`. A NaN coordinate is
    /// outside every plane.
    #[inline]
    pub fn outcode(&self, p: Vec4) -> u8 {
        // The seven planes' distances written out (the same sums as
        // `Plane::dist`, whose zero terms add nothing): this runs for every
        // vertex of every frame.
        let out = |d: f32| (d.is_nan() || d < 0.0) as u8;
        let (gxw, gyw) = (self.gx * p.w, self.gy * p.w);
        out(p.w - W_MIN)
            | out(p.w - p.z) << 1
            | out(p.z + p.w) << 2
            | out(gxw - p.x) << 3
            | out(p.x + gxw) << 4
            | out(gyw - p.y) << 5
            | out(p.y + gyw) << 6
    }

    /// Clips a triangle into `out` (cleared first). Returns what happened.
    pub fn clip(&self, tri: &[ClipVertex; 3], out: &mut Polygon) -> Clipped {
        out.len = 0;
        let codes = tri.map(|v| self.outcode(v.pos));
        if codes[0] & codes[1] & codes[2] != 0 {
            return Clipped::Rejected;
        }
        out.verts[..3].copy_from_slice(tri);
        out.len = 3;
        if codes[0] | codes[1] | codes[2] == 0 {
            return Clipped::Inside;
        }
        if tri.iter().any(|v| !v.pos.is_finite()) {
            out.len = 0;
            return Clipped::Rejected;
        }
        let mut scratch = Polygon::default();
        for (i, plane) in self.planes.iter().enumerate() {
            if (codes[0] | codes[1] | codes[2]) & (1 << i) == 0 {
                continue;
            }
            clip_polygon(plane, out, &mut scratch);
            std::mem::swap(out, &mut scratch);
            if out.len < 3 {
                out.len = 0;
                return Clipped::Rejected;
            }
        }
        Clipped::Clipped
    }
}

/// The outcome of clipping one triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Clipped {
    /// Entirely inside: the polygon is the triangle itself.
    Inside,
    /// Cut by at least one plane: the polygon is what remains.
    Clipped,
    /// Nothing remains (or a coordinate was NaN or infinite).
    Rejected,
}

/// A convex polygon of at most [`MAX_POLYGON`] vertices.
#[derive(Clone, Copy, Debug)]
pub struct Polygon {
    verts: [ClipVertex; MAX_POLYGON],
    len: usize,
}

impl Default for Polygon {
    fn default() -> Self {
        Polygon {
            verts: [ClipVertex::default(); MAX_POLYGON],
            len: 0,
        }
    }
}

impl Polygon {
    pub fn vertices(&self) -> &[ClipVertex] {
        &self.verts[..self.len]
    }

    /// The polygon as a fan of triangles around its first vertex (correct:
    /// it is convex).
    pub fn triangles(&self) -> impl Iterator<Item = [ClipVertex; 3]> + '_ {
        (1..self.len.saturating_sub(1)).map(|i| [self.verts[0], self.verts[i], self.verts[i + 1]])
    }
}

fn clip_polygon(plane: &Plane, input: &Polygon, out: &mut Polygon) {
    out.len = 0;
    let n = input.len;
    for i in 0..n {
        let a = &input.verts[i];
        let b = &input.verts[(i + 1) % n];
        let (da, db) = (plane.dist(a.pos), plane.dist(b.pos));
        if da >= 0.0 {
            out.verts[out.len] = *a;
            out.len += 1;
        }
        if (da >= 0.0) != (db >= 0.0) {
            // From the inside endpoint towards the outside one, so that a
            // shared edge yields the same vertex in both triangles.
            let (inside, outside, di, dout) = if da >= 0.0 {
                (a, b, da, db)
            } else {
                (b, a, db, da)
            };
            let mut v = ClipVertex::lerp(inside, outside, di / (di - dout));
            plane.put_on(&mut v.pos);
            out.verts[out.len] = v;
            out.len += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f32, y: f32, z: f32, w: f32) -> ClipVertex {
        ClipVertex {
            pos: Vec4::new(x, y, z, w),
            color: Vec3::ZERO,
        }
    }

    #[test]
    fn inside_triangle_is_untouched() {
        let c = Clipper::new(80, 48);
        let tri = [
            v(0.0, 0.0, 0.0, 1.0),
            v(1.0, 0.0, 0.0, 1.0),
            v(0.0, 1.0, 0.5, 1.0),
        ];
        let mut out = Polygon::default();
        assert_eq!(c.clip(&tri, &mut out), Clipped::Inside);
        assert_eq!(out.vertices(), &tri[..]);
        assert!(tri.iter().all(|v| c.outcode(v.pos) == 0));
    }

    #[test]
    fn behind_the_eye_disappears_and_crossing_the_near_plane_splits() {
        let c = Clipper::new(80, 48);
        let mut out = Polygon::default();
        // All three with w < 0.
        let behind = [
            v(0.0, 0.0, 0.0, -1.0),
            v(1.0, 0.0, 0.0, -2.0),
            v(0.0, 1.0, 0.0, -1.0),
        ];
        assert_eq!(c.clip(&behind, &mut out), Clipped::Rejected);
        assert_eq!(out.triangles().count(), 0);
        // One vertex past the near plane (z > w): a quad, two triangles.
        let one = [
            v(0.0, 0.0, 2.0, 1.0),
            v(1.0, 0.0, 0.0, 1.0),
            v(0.0, 1.0, 0.0, 1.0),
        ];
        assert_eq!(c.clip(&one, &mut out), Clipped::Clipped);
        assert_eq!(out.triangles().count(), 2);
        // Two vertices past it: one triangle.
        let two = [
            v(0.0, 0.0, 2.0, 1.0),
            v(1.0, 0.0, 2.0, 1.0),
            v(0.0, 1.0, 0.0, 1.0),
        ];
        assert_eq!(c.clip(&two, &mut out), Clipped::Clipped);
        assert_eq!(out.triangles().count(), 1);
        for p in out.vertices() {
            assert!(p.pos.z <= p.pos.w + 1e-6 && p.pos.w > 0.0);
        }
    }

    #[test]
    fn nothing_left_has_w_at_or_below_zero() {
        let c = Clipper::new(80, 48);
        let mut out = Polygon::default();
        for w in [-1.0, 0.0, 1e-30, 1e-6] {
            let tri = [
                v(0.0, 0.0, 0.0, w),
                v(1.0, 0.0, 0.0, 1.0),
                v(0.0, 1.0, 0.0, 1.0),
            ];
            c.clip(&tri, &mut out);
            for p in out.vertices() {
                assert!(p.pos.w >= W_MIN * 0.999, "w = {w}: {p:?}");
            }
        }
    }

    #[test]
    fn outcode_agrees_with_the_planes() {
        let c = Clipper::new(80, 48);
        let mut x = 0x9e37_79b9u32;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            (x as f32 / u32::MAX as f32 - 0.5) * 200.0
        };
        for _ in 0..10_000 {
            let p = Vec4::new(next(), next(), next(), next() * 0.05);
            let slow = c.planes.iter().enumerate().fold(0u8, |code, (i, pl)| {
                code | (((pl.dist(p).is_nan() || pl.dist(p) < 0.0) as u8) << i)
            });
            assert_eq!(c.outcode(p), slow, "{p}");
        }
        assert_eq!(c.outcode(Vec4::new(f32::NAN, 0.0, 0.0, 1.0)), 0b0001_1000);
    }

    #[test]
    fn nan_is_rejected() {
        let c = Clipper::new(80, 48);
        let mut out = Polygon::default();
        let tri = [
            v(f32::NAN, 0.0, 0.0, 1.0),
            v(1.0, 0.0, 0.0, 1.0),
            v(0.0, 1.0, 0.0, 1.0),
        ];
        assert_eq!(c.clip(&tri, &mut out), Clipped::Rejected);
        let tri = [
            v(f32::INFINITY, 0.0, 0.0, 1.0),
            v(1.0, 0.0, 0.0, 1.0),
            v(0.0, 1.0, 0.0, 1.0),
        ];
        assert_eq!(c.clip(&tri, &mut out), Clipped::Rejected);
    }

    #[test]
    fn a_shared_edge_clips_to_the_same_vertex_from_both_sides() {
        let c = Clipper::new(80, 48);
        let (a, b) = (v(0.3, -0.2, 3.0, 1.0), v(-0.4, 0.7, -0.5, 1.0));
        let mut p1 = Polygon::default();
        let mut p2 = Polygon::default();
        c.clip(&[a, b, v(0.9, 0.9, 0.0, 1.0)], &mut p1);
        c.clip(&[b, a, v(-0.9, -0.9, 0.0, 1.0)], &mut p2);
        let new1: Vec<_> = p1
            .vertices()
            .iter()
            .filter(|p| *p != &a && *p != &b)
            .map(|p| p.pos)
            .collect();
        let new2: Vec<_> = p2
            .vertices()
            .iter()
            .filter(|p| *p != &a && *p != &b)
            .map(|p| p.pos)
            .collect();
        assert!(
            new1.iter().any(|p| new2.contains(p)),
            "{new1:?} vs {new2:?}"
        );
    }
}
