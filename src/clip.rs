//! Stage 3: clipping, for the few triangles that need it.
//!
//! Almost every triangle is inside every clip plane and skips this stage
//! (the vertex stage's outcodes say so, in f32, at seven comparisons a
//! vertex; the planner skips even that for geometry whose bounding box is
//! inside). The rest are clipped here against seven planes:
//!
//! * `w ≥ W_MIN`: nothing is ever divided by a `w` that is zero, negative or
//!   denormal, whatever the caller feeds in;
//! * near `z ≤ w` and far `z ≥ −w`: the canonical cube's z range (larger z
//!   nearer); for a perspective camera the near plane also means
//!   `w ≥ near > 0`, so geometry behind the eye disappears instead of being
//!   mirrored onto the screen;
//! * the guard band `|x| ≤ g_x·w`, `|y| ≤ g_y·w`: 2^20 samples from the
//!   grid's centre, far outside any screen, so that every vertex the
//!   rasterizer sees is inside the range where its `i64` edge functions
//!   cannot overflow (see `raster`). The screen's own edges are never
//!   clipped against: the rasterizer's bounding box does that for free and
//!   exactly.
//!
//! **Far-away endpoints cannot cancel.** The textbook new vertex,
//! `a + (b − a)·t`, fails when both endpoints are far away and the new
//! vertex is near: a floor reaching 1e16 units cut by the near plane, a
//! triangle whose vertices are 1e20 samples out with an edge across the
//! screen. `t` rounds, the product cancels, and the edge moves by a long way
//! (or the triangle vanishes). Even f64 is not enough: the clip-space
//! coordinates of a far vertex, rounded once, already carry an error larger
//! than the whole scene near the eye.
//!
//! So clipping happens in the model's own homogeneous space, where the
//! inputs are exact (f32 positions, `w = 1`), against the planes pulled
//! back through the model-view-projection matrix (`π·M`). The new vertex
//! where the edge `a → b` crosses plane `π` is `(π·a)·b − (π·b)·a`, written
//! out per coordinate as `Σ_j π_j·(a_j·b_k − a_k·b_j)`: the 2×2 minors of the
//! two endpoints (the line's Plücker coordinates), each taken by Kahan's
//! fused-multiply-add algorithm, accurate to its own last bit however large
//! the products it cancels, then summed with compensation. The huge terms
//! cancel exactly inside the minors, so the error is relative to the new
//! vertex, not to how far away its endpoints are. The point stays
//! homogeneous (no division), rescaled by a power of two after each plane
//! so it never overflows. Only the final vertices, inside the guard band,
//! are taken to clip space and divided. Vertices anywhere up to f32's
//! largest, 3.4e38, place their edges on screen as exactly as the snap to
//! 1/256 of a sample allows (`tests/render/hard_cases.rs` sweeps 1e2 to 3.4e38 in
//! all three projections, end to end).
//!
//! **Watertight.** Where two triangles share an edge that crosses a plane,
//! both compute the same new vertex: the arithmetic always goes from the
//! inside endpoint to the outside one, whatever direction the triangle
//! walks the edge. A vertex inside every plane keeps the position the
//! vertex stage snapped, so a clipped triangle meets its unclipped
//! neighbours exactly.
//!
//! The result is a convex polygon of at most [`MAX_POLYGON`] vertices, in a
//! fixed array (no allocation), fanned into triangles.

use glam::{DMat4, DVec4, Mat4, Vec2, Vec3, Vec4};

use crate::fixed::FixedPoint;
use crate::scene::Projection;
use crate::transform::Viewport;

/// Smallest `w` that survives clipping.
pub const W_MIN: f64 = 1e-5;
/// Half-width of the guard band in samples, measured from the grid's centre.
pub const GUARD_SAMPLES: f64 = (1u32 << 20) as f64;
/// Largest number of vertices a triangle clipped by seven planes can have.
pub const MAX_POLYGON: usize = 10;

/// A triangle's vertex going into the clipper.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ClipVertex {
    /// Position in model space (`w = 1` for a vertex of a mesh).
    pub pos: DVec4,
    /// Colour channels, linear light in [0, 65535].
    pub color: Vec3,
    /// Texture coordinates (zero when untextured).
    pub uv: Vec2,
    /// Its weights in the triangle it belongs to (a corner's are one 1 and
    /// two 0s), carried to each cut so that attributes the clipper does
    /// not carry (the normal and position per-sample shading reads) can be
    /// found for the pieces.
    pub weights: Vec3,
    /// Where the vertex stage put it, when it is inside every clip plane:
    /// kept as it is, so that neighbours that were not clipped meet it.
    pub snapped: Option<Snapped>,
}

/// A vertex as the vertex stage placed it on screen.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Snapped {
    /// Its position, snapped.
    pub fixed: FixedPoint,
    /// Its position in samples.
    pub xy: [f32; 2],
    /// Depth in the canonical cube.
    pub z: f32,
    /// `1/w`, for perspective-correct interpolation.
    pub inv_w: f32,
}

/// A vertex of the clipped polygon, on screen.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ScreenVertex {
    /// Its position, snapped.
    pub fixed: FixedPoint,
    /// Position in samples (unsnapped).
    pub xy: [f64; 2],
    /// Depth in the canonical cube.
    pub z: f32,
    /// `1/w`, for perspective-correct interpolation.
    pub inv_w: f32,
    /// Its colour, linear light in [0, 65535].
    pub color: Vec3,
    /// Its texture coordinates.
    pub uv: Vec2,
    /// Its weights in the triangle that was clipped.
    pub weights: Vec3,
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
    verts: [ScreenVertex; MAX_POLYGON],
    len: usize,
}

impl Default for Polygon {
    fn default() -> Self {
        Polygon {
            verts: [ScreenVertex::default(); MAX_POLYGON],
            len: 0,
        }
    }
}

impl Polygon {
    /// The polygon's vertices, in order around it.
    pub fn vertices(&self) -> &[ScreenVertex] {
        &self.verts[..self.len]
    }

    /// The polygon as a fan of triangles around its first vertex (correct:
    /// it is convex).
    pub fn triangles(&self) -> impl Iterator<Item = [ScreenVertex; 3]> + '_ {
        (1..self.len.saturating_sub(1)).map(|i| [self.verts[0], self.verts[i], self.verts[i + 1]])
    }
}

/// The clip planes for a grid of `width × height` samples.
#[derive(Clone, Copy, Debug)]
pub struct Clipper {
    /// The guard band in NDC, per axis: `|x| ≤ gx·w` is `G` samples from
    /// the centre.
    gx: f64,
    gy: f64,
    /// The smallest `w` kept.
    w_min: f64,
}

/// A vertex during clipping: model-space homogeneous position, colour.
#[derive(Clone, Copy, Debug, Default)]
struct V {
    pos: [f64; 4],
    color: Vec3,
    uv: Vec2,
    weights: Vec3,
    snapped: Option<Snapped>,
}

impl Clipper {
    /// The clip planes for a grid of `width × height` samples, keeping `w` down
    /// to [`W_MIN`].
    pub fn new(width: u32, height: u32) -> Clipper {
        // The viewport maps NDC x to (x + 1)·W/2, so |x_screen − W/2| ≤ G
        // samples is |x_ndc| ≤ 2G/W.
        Clipper {
            gx: 2.0 * GUARD_SAMPLES / width.max(1) as f64,
            gy: 2.0 * GUARD_SAMPLES / height.max(1) as f64,
            w_min: W_MIN,
        }
    }

    /// The clip planes for a grid seen through `projection`: the smallest
    /// `w` a clipped vertex may keep is [`W_MIN`], or for a perspective
    /// camera whose near plane is closer than that, half the near distance
    /// (the scene is tiny: what matters is `w` relative to `near`).
    pub fn for_projection(width: u32, height: u32, projection: &Projection) -> Clipper {
        let w_min = match *projection {
            Projection::Perspective { near, .. } => W_MIN.min(near as f64 * 0.5),
            _ => W_MIN,
        };
        Clipper::new(width, height).with_w_min(w_min)
    }

    /// Keeps `w` down to `w_min` (≤ [`W_MIN`]) rather than [`W_MIN`]: for a
    /// perspective camera whose near plane is nearer than that.
    pub fn with_w_min(self, w_min: f64) -> Clipper {
        Clipper {
            w_min: w_min.clamp(f32::MIN_POSITIVE as f64, W_MIN),
            ..self
        }
    }

    /// Bit `i` set when the point is outside plane `i` (w, near, far, then
    /// the guard band's right, left, top and bottom). A NaN coordinate is
    /// outside every plane. In f32: the vertex stage's trivial accept.
    #[inline]
    pub fn outcode(&self, p: Vec4) -> u8 {
        let out = |d: f32| (d.is_nan() || d < 0.0) as u8;
        let (gxw, gyw) = (self.gx as f32 * p.w, self.gy as f32 * p.w);
        out(p.w - self.w_min as f32)
            | out(p.w - p.z) << 1
            | out(p.z + p.w) << 2
            | out(gxw - p.x) << 3
            | out(p.x + gxw) << 4
            | out(gyw - p.y) << 5
            | out(p.y + gyw) << 6
    }

    /// Whether four clip positions, their x, y, z and w each in the lanes
    /// of a vector, all get outcode 0 from [`Clipper::outcode`]: the same
    /// operations per lane, and a NaN is outside here too.
    #[inline]
    pub(crate) fn inside4(&self, x: Vec4, y: Vec4, z: Vec4, w: Vec4) -> bool {
        let (gxw, gyw) = (
            Vec4::splat(self.gx as f32) * w,
            Vec4::splat(self.gy as f32) * w,
        );
        let ok = |d: Vec4| d.cmpge(Vec4::ZERO);
        (ok(w - Vec4::splat(self.w_min as f32))
            & ok(w - z)
            & ok(z + w)
            & ok(gxw - x)
            & ok(x + gxw)
            & ok(gyw - y)
            & ok(y + gyw))
        .all()
    }

    /// Whether every point of the box `lo..=hi` gets outcode 0 when the
    /// vertex stage transforms it, `mvp * p.extend(1.0)` in f32 and then
    /// [`Clipper::outcode`], whatever that product's rounding: then testing
    /// each vertex, as the full pipeline does, finds every one inside.
    ///
    /// The corners' clip positions are found in f64 from the same f32
    /// numbers (products of two f32 are exact there), and each plane must
    /// hold at every corner with room for the f32 error of any point of the
    /// box (at most 8 units in the last place of the sum of its terms'
    /// magnitudes, per coordinate) and for the rounding of `gx·w`. A plane's
    /// value is linear, so the corners bound it over the box. A model far
    /// from the origin whose turn brings it back near the camera cancels
    /// large numbers in f32: then the room is wide, and its vertices are
    /// tested.
    pub fn box_inside(&self, mvp: Mat4, lo: Vec3, hi: Vec3) -> bool {
        const U: f64 = f32::EPSILON as f64 / 2.0;
        let rows = [0, 1, 2, 3].map(|k| mvp.row(k).to_array().map(f64::from));
        let big = [
            (lo.x.abs().max(hi.x.abs())) as f64,
            (lo.y.abs().max(hi.y.abs())) as f64,
            (lo.z.abs().max(hi.z.abs())) as f64,
            1.0,
        ];
        // Per clip coordinate, the largest f32 error of any point of the box.
        let err = rows.map(|r| 8.0 * U * (0..4).map(|j| (r[j] * big[j]).abs()).sum::<f64>());
        let [ex, ey, ez, ew] = err;
        let (gx, gy) = (self.gx as f32 as f64, self.gy as f32 as f64);
        let w_min = self.w_min as f32 as f64;
        (0..8).all(|i| {
            let p = [
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
                1.0,
            ]
            .map(f64::from);
            let [x, y, z, w] = rows.map(|r| (0..4).map(|j| r[j] * p[j]).sum::<f64>());
            // The smallest `w` any nearby point may have, and the smallest
            // `g·w` its f32 product may round to.
            let w_lo = w - ew;
            let (gxw, gyw) = (gx * w_lo * (1.0 - U), gy * w_lo * (1.0 - U));
            [
                w_lo - w_min,
                w_lo - (z + ez),
                (z - ez) + w_lo,
                gxw - (x + ex),
                (x - ex) + gxw,
                gyw - (y + ey),
                (y - ey) + gyw,
            ]
            .iter()
            // A tiny absolute room for the f64 sums themselves.
            .all(|&d| d.is_finite() && d > 1e-30)
        })
    }

    /// The seven planes pulled back into model space through `mvp`, in
    /// outcode order: `π·p ≥ 0` inside.
    fn planes(&self, mvp: &DMat4) -> [[f64; 4]; 7] {
        let r = [0, 1, 2, 3].map(|k| mvp.row(k).to_array());
        let comb = |a: f64, i: usize, b: f64, j: usize| -> [f64; 4] {
            std::array::from_fn(|n| a * r[i][n] + b * r[j][n])
        };
        let mut w = r[3];
        // w − W_MIN, where a model point's own w is its fourth coordinate.
        w[3] -= self.w_min;
        [
            w,
            comb(1.0, 3, -1.0, 2),
            comb(1.0, 3, 1.0, 2),
            comb(self.gx, 3, -1.0, 0),
            comb(self.gx, 3, 1.0, 0),
            comb(self.gy, 3, -1.0, 1),
            comb(self.gy, 3, 1.0, 1),
        ]
    }

    /// Clips a triangle given in model space, drawn with `mvp` through
    /// `viewport`, into `out` (cleared first).
    pub fn clip(
        &self,
        tri: &[ClipVertex; 3],
        mvp: &DMat4,
        viewport: &Viewport,
        out: &mut Polygon,
    ) -> Clipped {
        out.len = 0;
        if tri.iter().any(|v| !v.pos.is_finite()) || !mvp.is_finite() {
            return Clipped::Rejected;
        }
        let mut a = [V::default(); MAX_POLYGON];
        let mut b = [V::default(); MAX_POLYGON];
        for (d, v) in a.iter_mut().zip(tri) {
            *d = V {
                pos: v.pos.to_array(),
                color: v.color,
                uv: v.uv,
                weights: v.weights,
                snapped: v.snapped,
            };
        }
        let mut n = 3;
        let mut cut = false;
        for plane in self.planes(mvp) {
            let inside = |v: &V| v.snapped.is_some() || dot(&plane, &v.pos) >= 0.0;
            let outside = a[..n].iter().filter(|v| !inside(v)).count();
            if outside == 0 {
                continue;
            }
            if outside == n {
                return Clipped::Rejected;
            }
            cut = true;
            n = clip_polygon(&plane, &a[..n], &mut b, inside);
            std::mem::swap(&mut a, &mut b);
            if n < 3 {
                return Clipped::Rejected;
            }
        }
        let rows = [0, 1, 2, 3].map(|k| mvp.row(k).to_array());
        for v in &a[..n] {
            let sv = match v.snapped {
                Some(s) => ScreenVertex {
                    fixed: s.fixed,
                    xy: s.xy.map(f64::from),
                    z: s.z,
                    inv_w: s.inv_w,
                    color: v.color,
                    uv: v.uv,
                    weights: v.weights,
                },
                None => {
                    let Some(p) = on_screen(&rows, &v.pos, viewport) else {
                        return Clipped::Rejected;
                    };
                    ScreenVertex {
                        color: v.color,
                        uv: v.uv,
                        weights: v.weights,
                        ..p
                    }
                }
            };
            out.verts[out.len] = sv;
            out.len += 1;
        }
        if cut {
            Clipped::Clipped
        } else {
            Clipped::Inside
        }
    }
}

impl Clipper {
    /// Clips the segment from `a` to `b` (model space), drawn with `mvp`
    /// through `viewport`, to every plane (Liang–Barsky, in f64): its ends
    /// on screen, or `None` where nothing of it remains. What a wireframe's
    /// edges go through.
    pub fn clip_segment(
        &self,
        [a, b]: [DVec4; 2],
        mvp: &DMat4,
        viewport: &Viewport,
    ) -> Option<[ScreenVertex; 2]> {
        if !(a.is_finite() && b.is_finite() && mvp.is_finite()) {
            return None;
        }
        let (pa, pb) = (a.to_array(), b.to_array());
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        for plane in self.planes(mvp) {
            let (da, db) = (dot(&plane, &pa), dot(&plane, &pb));
            match (da < 0.0, db < 0.0) {
                (true, true) => return None,
                (true, false) => t0 = t0.max(da / (da - db)),
                (false, true) => t1 = t1.min(da / (da - db)),
                (false, false) => {}
            }
        }
        // NaN (a degenerate plane) fails too.
        if t0.partial_cmp(&t1).is_none_or(|o| o.is_gt()) {
            return None;
        }
        let rows = [0, 1, 2, 3].map(|k| mvp.row(k).to_array());
        let at = |t: f64| {
            let p = if t == 0.0 {
                pa
            } else if t == 1.0 {
                pb
            } else {
                std::array::from_fn(|k| pa[k] + (pb[k] - pa[k]) * t)
            };
            on_screen(&rows, &p, viewport)
        };
        Some([at(t0)?, at(t1)?])
    }
}

/// A point in model space (`pos`, homogeneous), through the rows of the
/// model-view-projection matrix and the viewport, on screen: snapped, its
/// depth and `1/w` (colour and texture coordinates zero); `None` behind
/// the eye or where it cannot be snapped.
fn on_screen(rows: &[[f64; 4]; 4], pos: &[f64; 4], viewport: &Viewport) -> Option<ScreenVertex> {
    let (half_w, half_h) = viewport.half();
    let (dx, dy) = viewport.offset();
    // Clip space, at the point's own homogeneous scale.
    let c = rows.map(|r| dot(&r, pos));
    if !(c[3] > 0.0 && pos[3] > 0.0) {
        return None;
    }
    let xy = [
        c[0] / c[3] * half_w + half_w + dx,
        c[1] / c[3] * half_h + half_h + dy,
    ];
    Some(ScreenVertex {
        fixed: FixedPoint::snap64(xy)?,
        xy,
        z: (c[2] / c[3]) as f32,
        inv_w: (pos[3] / c[3]) as f32,
        ..ScreenVertex::default()
    })
}

/// `a + b` as an unevaluated sum `(s, e)`, exactly (Knuth's two-sum).
#[inline]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// `a·b` as an unevaluated sum `(p, e)`, exactly.
#[inline]
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// `a·b − c·d` to within an ulp and a half of the result, however much the
/// two products cancel (Kahan's algorithm).
#[inline]
fn diff_of_products(a: f64, b: f64, c: f64, d: f64) -> f64 {
    let w = c * d;
    let e = (-c).mul_add(d, w);
    let f = a.mul_add(b, -w);
    f + e
}

/// `Σ a_i·b_i`, as accurate as if computed in twice the precision and then
/// rounded (Ogita, Rump and Oishi's Dot2).
fn dot(a: &[f64; 4], b: &[f64; 4]) -> f64 {
    let (mut s, mut c) = two_prod(a[0], b[0]);
    for i in 1..4 {
        let (p, pe) = two_prod(a[i], b[i]);
        let (t, te) = two_sum(s, p);
        s = t;
        c += pe + te;
    }
    s + c
}

/// Where the edge from `a` (inside `plane`) to `b` (outside) crosses it:
/// `(π·a)·b − (π·b)·a`, per coordinate `Σ_j π_j·(a_j·b_k − a_k·b_j)`,
/// rescaled by a power of two.
fn cross(plane: &[f64; 4], a: &V, b: &V) -> V {
    let mut pos = [0.0; 4];
    for (k, p) in pos.iter_mut().enumerate() {
        let minors: [f64; 4] =
            std::array::from_fn(|j| diff_of_products(a.pos[j], b.pos[k], a.pos[k], b.pos[j]));
        *p = dot(plane, &minors);
    }
    // A homogeneous point is the same point at any positive scale: keep it
    // near 1 so that chains of clips never overflow. Exact (a power of 2).
    let max = pos.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if max.is_normal() {
        let e = ((max.to_bits() >> 52) & 0x7ff) as i32 - 1023;
        // 2^-e, exact even where it is subnormal (e = 1023).
        let scale = 2f64.powi(-e);
        pos = pos.map(|v| v * scale);
    }
    let (da, db) = (dot(plane, &a.pos).max(0.0), dot(plane, &b.pos));
    let t = (da / (da - db)) as f32;
    V {
        pos,
        color: a.color + (b.color - a.color) * t,
        uv: a.uv + (b.uv - a.uv) * t,
        weights: a.weights + (b.weights - a.weights) * t,
        snapped: None,
    }
}

fn clip_polygon(
    plane: &[f64; 4],
    input: &[V],
    out: &mut [V; MAX_POLYGON],
    inside: impl Fn(&V) -> bool,
) -> usize {
    let mut len = 0;
    for i in 0..input.len() {
        let a = &input[i];
        let b = &input[(i + 1) % input.len()];
        if inside(a) {
            out[len] = *a;
            len += 1;
        }
        if inside(a) != inside(b) {
            // From the inside endpoint to the outside one, so that a shared
            // edge yields the same vertex in both triangles.
            out[len] = if inside(a) {
                cross(plane, a, b)
            } else {
                cross(plane, b, a)
            };
            len += 1;
        }
    }
    len
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64, z: f64, w: f64) -> ClipVertex {
        ClipVertex {
            pos: DVec4::new(x, y, z, w),
            color: Vec3::ZERO,
            uv: Vec2::ZERO,
            weights: Vec3::ZERO,
            snapped: None,
        }
    }

    fn vp() -> Viewport {
        Viewport::new(80.0, 48.0)
    }

    /// Clips with the identity as the model-view-projection: model space is
    /// clip space.
    fn clip(tri: &[ClipVertex; 3], out: &mut Polygon) -> Clipped {
        Clipper::new(80, 48).clip(tri, &DMat4::IDENTITY, &vp(), out)
    }

    #[test]
    fn inside_triangle_is_untouched() {
        let tri = [
            v(0.0, 0.0, 0.0, 1.0),
            v(1.0, 0.0, 0.0, 1.0),
            v(0.0, 1.0, 0.5, 1.0),
        ];
        let mut out = Polygon::default();
        assert_eq!(clip(&tri, &mut out), Clipped::Inside);
        let xy: Vec<[f64; 2]> = out.vertices().iter().map(|v| v.xy).collect();
        assert_eq!(xy, vec![[40.0, 24.0], [80.0, 24.0], [40.0, 48.0]]);
        let c = Clipper::new(80, 48);
        assert!(tri.iter().all(|v| c.outcode(v.pos.as_vec4()) == 0));
    }

    #[test]
    fn behind_the_eye_disappears_and_crossing_the_near_plane_splits() {
        let mut out = Polygon::default();
        // All three with w < 0.
        let behind = [
            v(0.0, 0.0, 0.0, -1.0),
            v(1.0, 0.0, 0.0, -2.0),
            v(0.0, 1.0, 0.0, -1.0),
        ];
        assert_eq!(clip(&behind, &mut out), Clipped::Rejected);
        assert_eq!(out.triangles().count(), 0);
        // One vertex past the near plane (z > w): a quad, two triangles.
        let one = [
            v(0.0, 0.0, 2.0, 1.0),
            v(1.0, 0.0, 0.0, 1.0),
            v(0.0, 1.0, 0.0, 1.0),
        ];
        assert_eq!(clip(&one, &mut out), Clipped::Clipped);
        assert_eq!(out.triangles().count(), 2);
        // Two vertices past it: one triangle, on or in front of the plane.
        let two = [
            v(0.0, 0.0, 2.0, 1.0),
            v(1.0, 0.0, 2.0, 1.0),
            v(0.0, 1.0, 0.0, 1.0),
        ];
        assert_eq!(clip(&two, &mut out), Clipped::Clipped);
        assert_eq!(out.triangles().count(), 1);
        for p in out.vertices() {
            assert!(p.z <= 1.0 && p.inv_w > 0.0, "{p:?}");
        }
    }

    #[test]
    fn nothing_left_has_w_at_or_below_zero() {
        let mut out = Polygon::default();
        for w in [-1.0, 0.0, 1e-30, 1e-6] {
            let tri = [
                v(0.0, 0.0, 0.0, w),
                v(1.0, 0.0, 0.0, 1.0),
                v(0.0, 1.0, 0.0, 1.0),
            ];
            clip(&tri, &mut out);
            for p in out.vertices() {
                assert!(
                    p.inv_w > 0.0 && p.inv_w <= (1.0 / W_MIN) as f32 * 1.001,
                    "w = {w}: {p:?}"
                );
            }
        }
    }

    #[test]
    fn outcode_agrees_with_the_planes() {
        let c = Clipper::new(80, 48);
        let planes = c.planes(&DMat4::IDENTITY);
        let mut x = 0x9e37_79b9u32;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            (x as f32 / u32::MAX as f32 - 0.5) * 200.0
        };
        for _ in 0..10_000 {
            let p = Vec4::new(next(), next(), next(), next() * 0.05);
            let slow = planes.iter().enumerate().fold(0u8, |code, (i, pl)| {
                code | (((dot(pl, &p.as_dvec4().to_array()) as f32) < 0.0) as u8) << i
            });
            assert_eq!(c.outcode(p), slow, "{p}");
        }
        assert_eq!(c.outcode(Vec4::new(f32::NAN, 0.0, 0.0, 1.0)), 0b0001_1000);
    }

    #[test]
    fn nan_and_infinity_are_rejected() {
        let mut out = Polygon::default();
        for bad in [f64::NAN, f64::INFINITY] {
            let tri = [
                v(bad, 0.0, 0.0, 1.0),
                v(1.0, 0.0, 0.0, 1.0),
                v(0.0, 1.0, 0.0, 1.0),
            ];
            assert_eq!(clip(&tri, &mut out), Clipped::Rejected);
        }
    }

    #[test]
    fn a_shared_edge_clips_to_the_same_vertex_from_both_sides() {
        let (a, b) = (v(0.3, -0.2, 3.0, 1.0), v(-0.4, 0.7, -0.5, 1.0));
        let mut p1 = Polygon::default();
        let mut p2 = Polygon::default();
        clip(&[a, b, v(0.9, 0.9, 0.0, 1.0)], &mut p1);
        clip(&[b, a, v(-0.9, -0.9, 0.0, 1.0)], &mut p2);
        let new1: Vec<_> = p1.vertices().iter().map(|p| p.xy).collect();
        let new2: Vec<_> = p2.vertices().iter().map(|p| p.xy).collect();
        assert!(
            new1.iter().filter(|p| new2.contains(p)).count() >= 2,
            "{new1:?} vs {new2:?}"
        );
    }

    #[test]
    fn far_endpoints_do_not_move_the_edge() {
        // The hypotenuse from (s, −s) to (−s, s) passes through the centre
        // for every s: so must the clipped edge, to the last bit of the
        // snap: its two ends are exact mirror images about the centre.
        let centre = FixedPoint::snap([40.0, 24.0]).unwrap();
        let mut out = Polygon::default();
        for s in [1e5, 1e9, 1e16, 1e20, 1e30, 3.4e38] {
            let tri = [v(-s, -s, 0.0, 1.0), v(s, -s, 0.0, 1.0), v(-s, s, 0.0, 1.0)];
            assert_eq!(clip(&tri, &mut out), Clipped::Clipped, "{s}");
            let vs = out.vertices();
            let mirrored = vs.iter().any(|a| {
                vs.iter().any(|b| {
                    a.fixed.x.0 > centre.x.0
                        && a.fixed.x.0 + b.fixed.x.0 == 2 * centre.x.0
                        && a.fixed.y.0 + b.fixed.y.0 == 2 * centre.y.0
                })
            });
            assert!(mirrored, "s = {s}: {vs:?}");
        }
    }
}
