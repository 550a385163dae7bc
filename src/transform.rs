//! Stage 2: the transforms of GAMES101 Lectures 4–5, written as the notes
//! derive them: model, view, projection into the canonical cube
//! [-1,1]^3, and the viewport onto the sample grid.
//!
//! Conventions (the lecture's): right-handed, the camera looks down −z, the
//! near and far planes `n` and `f` are negative z values with `n > f`, and in
//! the canonical cube a larger z is nearer.
//!
//! One departure in form, not in meaning: the notes' perspective matrix
//! `M_ortho · M_persp→ortho` leaves `w = z`, which is negative in front of
//! the camera. Multiplying a homogeneous matrix by −1 describes the same
//! projective map, so [`perspective`] returns the negated matrix: then
//! `w = −z_eye`, the distance in front of the eye, positive for everything
//! visible, and clipping can ask for `w > 0` (see `clip`). The canonical-cube
//! coordinates after the divide are identical.
//!
//! Matrices are `glam::Mat4` in f32: screen coordinates up to the guard band
//! (2^21 samples) keep at least 1/8-sample precision in f32, and the snap to
//! 1/256 of a sample in `raster` is exact for the ±2^12-sample screens a
//! terminal has.

use glam::{DMat4, DVec3, Mat4, Vec3, Vec4};

/// An axis of a coordinate system: one to turn about, or a model's up.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Axis {
    /// x.
    X,
    #[default]
    /// y.
    Y,
    /// z.
    Z,
}

crate::choice::choice!(Axis {
    X => "x": "x",
    Y => "y": "y",
    Z => "z": "z",
});

impl Axis {
    /// The name of a turn about this axis, as the command line has it
    /// (`--pitch`, `--yaw`, `--roll`).
    pub fn angle_name(self) -> &'static str {
        match self {
            Axis::X => "pitch",
            Axis::Y => "yaw",
            Axis::Z => "roll",
        }
    }

    /// The unit vector along the axis.
    pub fn unit(self) -> Vec3 {
        match self {
            Axis::X => Vec3::X,
            Axis::Y => Vec3::Y,
            Axis::Z => Vec3::Z,
        }
    }
}

/// The view frustum's planes as the notes name them: `l, r, b, t` on the
/// near plane, `n` and `f` as (negative) z values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frustum {
    /// Left, on the near plane.
    pub l: f32,
    /// Right.
    pub r: f32,
    /// Bottom.
    pub b: f32,
    /// Top.
    pub t: f32,
    /// Near (a negative z).
    pub n: f32,
    /// Far (a negative z, below `n`).
    pub f: f32,
}

impl Frustum {
    /// The symmetric frustum of a vertical field of view and an aspect
    /// ratio, as the notes derive it: `tan(fovY/2) = t / |n|` and
    /// `aspect = r / t`, with `l = −r`, `b = −t`. `near` and `far` are
    /// distances in front of the eye (> 0); the planes sit at `z = −near` and
    /// `z = −far`.
    pub fn from_fov(fov_y_degrees: f32, aspect: f32, near: f32, far: f32) -> Self {
        let n = -near;
        let t = (fov_y_degrees.to_radians() / 2.0).tan() * n.abs();
        let r = aspect * t;
        Frustum {
            l: -r,
            r,
            b: -t,
            t,
            n,
            f: -far,
        }
    }

    /// The orthographic box of a given height (`t − b`) and aspect.
    pub fn orthographic_box(height: f32, aspect: f32, near: f32, far: f32) -> Self {
        let t = height / 2.0;
        let r = aspect * t;
        Frustum {
            l: -r,
            r,
            b: -t,
            t,
            n: -near,
            f: -far,
        }
    }
}

/// A matrix written row by row, as the notes print it.
fn rows(m: [[f32; 4]; 4]) -> Mat4 {
    Mat4::from_cols_array_2d(&m).transpose()
}

/// `M_ortho`: translate the box's centre to the origin, then scale it to
/// [-1,1]^3. `[l,r]×[b,t]×[f,n]` maps onto the canonical cube, `n ↦ 1`.
pub fn orthographic(fr: &Frustum) -> Mat4 {
    let Frustum { l, r, b, t, n, f } = *fr;
    rows([
        [2.0 / (r - l), 0.0, 0.0, -(r + l) / (r - l)],
        [0.0, 2.0 / (t - b), 0.0, -(t + b) / (t - b)],
        [0.0, 0.0, 2.0 / (n - f), -(n + f) / (n - f)],
        [0.0, 0.0, 0.0, 1.0],
    ])
}

/// `M_persp→ortho`: squeezes the frustum into the box `[l,r]×[b,t]×[f,n]`,
/// keeping the near plane and the far plane's z.
pub(crate) fn persp_to_ortho(n: f32, f: f32) -> Mat4 {
    rows([
        [n, 0.0, 0.0, 0.0],
        [0.0, n, 0.0, 0.0],
        [0.0, 0.0, n + f, -n * f],
        [0.0, 0.0, 1.0, 0.0],
    ])
}

/// `M_persp = M_ortho · M_persp→ortho`, negated so that `w = −z_eye > 0` in
/// front of the camera (the same projective map; see the module doc).
pub fn perspective(fr: &Frustum) -> Mat4 {
    -(orthographic(fr) * persp_to_ortho(fr.n, fr.f))
}

/// `M_viewport`: `[-1,1]^2` onto `[0,width]×[0,height]`, z untouched.
pub fn viewport(width: f32, height: f32) -> Mat4 {
    rows([
        [width / 2.0, 0.0, 0.0, width / 2.0],
        [0.0, height / 2.0, 0.0, height / 2.0],
        [0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ])
}

/// `M_viewport` applied to a point of the canonical square, without the
/// matrix product: the same sums (`width/2 · x + width/2`), so the result is
/// bit for bit what the matrix gives.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Viewport {
    half_w: f32,
    half_h: f32,
    dx: f32,
    dy: f32,
}

impl Viewport {
    /// The viewport onto a grid of `width × height` samples.
    pub fn new(width: f32, height: f32) -> Viewport {
        Viewport {
            half_w: width / 2.0,
            half_h: height / 2.0,
            dx: 0.0,
            dy: 0.0,
        }
    }

    /// The same viewport moved by `(dx, dy)` samples (anti-aliasing's
    /// sub-sample passes).
    pub fn shifted(self, dx: f32, dy: f32) -> Viewport {
        Viewport { dx, dy, ..self }
    }

    /// Half the grid's width and height, in samples.
    pub fn half(&self) -> (f64, f64) {
        (self.half_w as f64, self.half_h as f64)
    }

    /// The shift of [`Viewport::shifted`].
    pub fn offset(&self) -> (f64, f64) {
        (self.dx as f64, self.dy as f64)
    }

    /// Canonical `(x, y)` to samples.
    #[inline(always)]
    pub fn apply(&self, x: f32, y: f32) -> [f32; 2] {
        [
            self.half_w * x + self.half_w + self.dx,
            self.half_h * y + self.half_h + self.dy,
        ]
    }

    /// [`Viewport::apply`] to four points, their x and y each in the lanes
    /// of a vector: the same operations per lane.
    #[inline(always)]
    pub(crate) fn apply4(&self, x: Vec4, y: Vec4) -> [Vec4; 2] {
        let (hw, hh) = (Vec4::splat(self.half_w), Vec4::splat(self.half_h));
        [
            hw * x + hw + Vec4::splat(self.dx),
            hh * y + hh + Vec4::splat(self.dy),
        ]
    }
}

/// The same view transform in f64: the eye may be 1e30 away, or 1e-30 from
/// its target (f32 would overflow or underflow normalising the direction).
pub(crate) fn view64(eye: DVec3, target: DVec3, up: DVec3) -> DMat4 {
    let f = (target - eye).normalize();
    let s = f.cross(up).normalize();
    let u = s.cross(f);
    DMat4::from_cols_array_2d(&[
        [s.x, s.y, s.z, -s.dot(eye)],
        [u.x, u.y, u.z, -u.dot(eye)],
        [-f.x, -f.y, -f.z, f.dot(eye)],
        [0.0, 0.0, 0.0, 1.0],
    ])
    .transpose()
}

/// The perspective projection of [`perspective`] and [`Frustum::from_fov`],
/// in f64 (a near distance of 1e-38 neither underflows nor overflows).
pub(crate) fn perspective64(fov_y_degrees: f64, aspect: f64, near: f64, far: f64) -> DMat4 {
    let (n, f) = (-near, -far);
    let t = (fov_y_degrees.to_radians() / 2.0).tan() * near;
    let r = aspect * t;
    // M_ortho · M_persp→ortho, multiplied out (l = −r, b = −t), negated.
    let m = [
        [2.0 * n / (2.0 * r), 0.0, 0.0, 0.0],
        [0.0, 2.0 * n / (2.0 * t), 0.0, 0.0],
        [0.0, 0.0, (n + f) / (n - f), -2.0 * n * f / (n - f)],
        [0.0, 0.0, 1.0, 0.0],
    ];
    -DMat4::from_cols_array_2d(&m).transpose()
}

/// The orthographic projection of [`orthographic`] and
/// [`Frustum::orthographic_box`], in f64.
pub(crate) fn orthographic64(height: f64, aspect: f64, near: f64, far: f64) -> DMat4 {
    let (t, n, f) = (height / 2.0, -near, -far);
    let r = aspect * t;
    let m = [
        [1.0 / r, 0.0, 0.0, 0.0],
        [0.0, 1.0 / t, 0.0, 0.0],
        [0.0, 0.0, 2.0 / (n - f), -(n + f) / (n - f)],
        [0.0, 0.0, 0.0, 1.0],
    ];
    DMat4::from_cols_array_2d(&m).transpose()
}

/// The view transform `M_view = R_view · T_view`: the eye to the origin,
/// looking down −z with `up` along +y. This is exactly glam's right-handed
/// `camera::rh::view::look_at_mat4`.
pub fn view(eye: Vec3, target: Vec3, up: Vec3) -> Mat4 {
    glam::camera::rh::view::look_at_mat4(eye, target, up)
}

/// The model transform: scale, then rotate about x, then y, then z (degrees),
/// then translate.
pub fn model(scale: Vec3, rotate_degrees: Vec3, translate: Vec3) -> Mat4 {
    Mat4::from_translation(translate) * rotation(rotate_degrees) * Mat4::from_scale(scale)
}

/// Rotation about x, then y, then z, in degrees: `Rz · Ry · Rx`.
pub fn rotation(degrees: Vec3) -> Mat4 {
    let r = degrees * (std::f32::consts::PI / 180.0);
    Mat4::from_rotation_z(r.z) * Mat4::from_rotation_y(r.y) * Mat4::from_rotation_x(r.x)
}

/// `v` scaled by the power of two that brings its largest component into
/// [1, 2): exact, so that what is computed from it next (a cross product, a
/// length) neither underflows for a scene 1e-30 across nor overflows for
/// one 1e30 across, and comes out the same, bit for bit, at any
/// power-of-two scale. Zero and non-finite vectors are returned as they are.
pub(crate) fn pow2_unit(v: Vec3) -> Vec3 {
    match pow2_factors(v.abs().max_element()) {
        Some((a, b)) => v * a * b,
        None => v,
    }
}

/// The two powers of two whose product brings `max` into [1, 2), for
/// [`pow2_unit`] (which multiplies by one, then the other); `None` when
/// `max` is zero, subnormal or not finite.
#[inline(always)]
pub(crate) fn pow2_factors(max: f32) -> Option<(f32, f32)> {
    if !max.is_normal() {
        return None;
    }
    let e = ((max.to_bits() >> 23) & 0xff) as i32 - 127;
    // 2^-e in two factors, each a normal f32 (2^-127 alone is not).
    let (a, b) = (-e / 2, -e - (-e / 2));
    Some((pow2(a), pow2(b)))
}

/// 2^e for −126 ≤ e ≤ 127.
fn pow2(e: i32) -> f32 {
    f32::from_bits(((e + 127) as u32) << 23)
}

/// The unit normal of triangle `a, b, c` (counter-clockwise seen from its
/// front), or zero for a degenerate one; scale-free (see [`pow2_unit`]).
pub(crate) fn face_normal(a: Vec3, b: Vec3, c: Vec3) -> Vec3 {
    let n = pow2_unit(b - a).cross(pow2_unit(c - a));
    pow2_unit(n).normalize_or_zero()
}

/// `v` in unit length, or zero; scale-free (see [`pow2_unit`]).
pub(crate) fn direction(v: Vec3) -> Vec3 {
    pow2_unit(v).normalize_or_zero()
}

/// Largest grid side, in samples (2^16).
pub const MAX_GRID: u32 = 1 << 16;

/// The sample grid: `width × height` samples, sample `(x, y)` centred on
/// `(x + 0.5, y + 0.5)`, y up.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Grid {
    /// Samples across.
    pub width: u32,
    /// Samples up.
    pub height: u32,
}

impl Grid {
    /// A grid; each side is clamped to [`MAX_GRID`].
    pub fn new(width: u32, height: u32) -> Grid {
        Grid {
            width: width.min(MAX_GRID),
            height: height.min(MAX_GRID),
        }
    }

    /// Samples in all.
    pub fn len(&self) -> usize {
        self.width as usize * self.height as usize
    }

    /// Whether the grid has no sample.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Every row of the grid, as one band.
    pub fn all_rows(&self) -> Band {
        Band {
            y0: 0,
            y1: self.height,
        }
    }
}

/// A band of whole sample rows, `y0 ≤ y < y1` (y up): the part of the grid
/// one thread draws when a frame is drawn in parallel bands.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Band {
    /// The first row.
    pub y0: u32,
    /// One past the last row.
    pub y1: u32,
}

impl Band {
    /// Rows in the band.
    pub fn height(&self) -> u32 {
        self.y1.saturating_sub(self.y0)
    }
}

/// A rectangle of samples or of cells, `[x0, x1) × [y0, y1)`: where
/// something was drawn. Empty when `x0 >= x1` or `y0 >= y1`; the empty
/// rectangle [`Rect::EMPTY`] is the identity of [`Rect::union`], so that a
/// union is four comparisons.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Rect {
    /// The first column.
    pub x0: u32,
    /// One past the last column.
    pub x1: u32,
    /// The first row.
    pub y0: u32,
    /// One past the last row.
    pub y1: u32,
}

impl Rect {
    /// Nothing.
    pub const EMPTY: Rect = Rect {
        x0: u32::MAX,
        x1: 0,
        y0: u32::MAX,
        y1: 0,
    };

    /// Every column and row of a `width × height` grid.
    pub const fn all(width: u32, height: u32) -> Rect {
        Rect {
            x0: 0,
            x1: width,
            y0: 0,
            y1: height,
        }
    }

    /// The one sample or cell `(x, y)`.
    #[inline(always)]
    pub const fn at(x: u32, y: u32) -> Rect {
        Rect {
            x0: x,
            x1: x + 1,
            y0: y,
            y1: y + 1,
        }
    }

    /// Whether it holds nothing.
    pub const fn is_empty(&self) -> bool {
        self.x0 >= self.x1 || self.y0 >= self.y1
    }

    /// The smallest rectangle holding both.
    #[inline(always)]
    pub fn union(self, o: Rect) -> Rect {
        Rect {
            x0: self.x0.min(o.x0),
            x1: self.x1.max(o.x1),
            y0: self.y0.min(o.y0),
            y1: self.y1.max(o.y1),
        }
    }

    /// The part of it inside `o` (empty, though perhaps not
    /// [`Rect::EMPTY`], when they do not meet).
    #[inline(always)]
    pub fn intersect(self, o: Rect) -> Rect {
        Rect {
            x0: self.x0.max(o.x0),
            x1: self.x1.min(o.x1),
            y0: self.y0.max(o.y0),
            y1: self.y1.min(o.y1),
        }
    }

    /// The columns `[x0, x1)` of row `y` it holds, as a range (empty when
    /// the row is outside it).
    #[inline(always)]
    pub fn columns(&self, y: u32) -> std::ops::Range<usize> {
        if self.is_empty() || y < self.y0 || y >= self.y1 {
            0..0
        } else {
            self.x0 as usize..self.x1 as usize
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The homogeneous divide: clip space to the canonical cube.
    fn divide(clip: Vec4) -> Vec3 {
        clip.truncate() / clip.w
    }

    fn close(a: f32, b: f32) -> bool {
        (a - b).abs() <= 1e-5 * (1.0 + a.abs().max(b.abs()))
    }

    fn close3(a: Vec3, b: Vec3) -> bool {
        close(a.x, b.x) && close(a.y, b.y) && close(a.z, b.z)
    }

    #[test]
    fn frustum_from_fov_and_aspect_follows_the_notes() {
        // fovY = 90°: tan(45°) = 1, so t = |n|; aspect 2: r = 2t.
        let fr = Frustum::from_fov(90.0, 2.0, 0.5, 10.0);
        assert!(close(fr.t, 0.5));
        assert!(close(fr.b, -0.5));
        assert!(close(fr.r, 1.0));
        assert!(close(fr.l, -1.0));
        assert_eq!(fr.n, -0.5);
        assert_eq!(fr.f, -10.0);
        assert!(fr.n > fr.f, "n > f: both negative, n nearer");
        // fovY = 60°: t = tan(30°)·|n|.
        let fr = Frustum::from_fov(60.0, 1.5, 2.0, 10.0);
        assert!(close(fr.t, (30f32).to_radians().tan() * 2.0));
        assert!(close(fr.r / fr.t, 1.5));
    }

    #[test]
    fn pow2_unit_brings_any_vector_to_one_and_two() {
        for e in [-126, -100, 0, 100, 126, 127] {
            let k = 2f64.powi(e) as f32;
            let v = Vec3::new(1.5, -0.75, 0.25) * k;
            assert_eq!(pow2_unit(v), Vec3::new(1.5, -0.75, 0.25), "2^{e}");
        }
        assert_eq!(pow2_unit(Vec3::ZERO), Vec3::ZERO);
    }

    #[test]
    fn the_f64_projections_are_the_notes_matrices() {
        for (fov, aspect, n, f) in [(45.0, 1.5, 0.1, 100.0), (90.0, 0.5, 2.0, 30.0)] {
            let a = perspective(&Frustum::from_fov(fov, aspect, n, f)).as_dmat4();
            let b = perspective64(fov as f64, aspect as f64, n as f64, f as f64);
            assert!(a.abs_diff_eq(b, 1e-5), "{a} {b}");
            let a = orthographic(&Frustum::orthographic_box(3.0, aspect, n, f)).as_dmat4();
            let b = orthographic64(3.0, aspect as f64, n as f64, f as f64);
            assert!(a.abs_diff_eq(b, 1e-6), "{a} {b}");
        }
        let v = view(Vec3::new(1.0, 2.0, 3.0), Vec3::ZERO, Vec3::Y).as_dmat4();
        let v64 = view64(DVec3::new(1.0, 2.0, 3.0), DVec3::ZERO, DVec3::Y);
        assert!(v.abs_diff_eq(v64, 1e-6));
    }

    #[test]
    fn viewport_entries_are_the_notes() {
        let m = viewport(80.0, 48.0);
        let expected = [
            [40.0, 0.0, 0.0, 40.0],
            [0.0, 24.0, 0.0, 24.0],
            [0.0, 0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ];
        for (r, row) in expected.iter().enumerate() {
            assert_eq!(m.row(r).to_array(), *row, "row {r}");
        }
        // Corners of [-1,1]^2 land on the corners of [0,W]×[0,H]; z untouched.
        assert_eq!(
            m.transform_point3(Vec3::new(-1.0, -1.0, 0.3)),
            Vec3::new(0.0, 0.0, 0.3)
        );
        assert_eq!(
            m.transform_point3(Vec3::new(1.0, 1.0, -0.7)),
            Vec3::new(80.0, 48.0, -0.7)
        );
    }

    #[test]
    fn viewport_struct_is_the_matrix_bit_for_bit() {
        let m = viewport(83.0, 47.0);
        let v = Viewport::new(83.0, 47.0);
        for (x, y) in [
            (-1.0, -1.0),
            (0.3, -0.71),
            (0.999_999, 0.123_456_7),
            (1.7, -2.5),
        ] {
            let p = m * Vec4::new(x, y, 0.0, 1.0);
            assert_eq!(v.apply(x, y), [p.x, p.y]);
        }
    }

    #[test]
    fn near_and_far_planes_map_to_the_cube_faces_larger_z_nearer() {
        let fr = Frustum::from_fov(45.0, 1.0, 1.0, 50.0);
        let p = perspective(&fr);
        let near = divide(p * Vec4::new(0.0, 0.0, -1.0, 1.0));
        let far = divide(p * Vec4::new(0.0, 0.0, -50.0, 1.0));
        let mid = divide(p * Vec4::new(0.0, 0.0, -5.0, 1.0));
        assert!(close(near.z, 1.0), "{near}");
        assert!(close(far.z, -1.0), "{far}");
        assert!(mid.z < near.z && mid.z > far.z);
        // w is the distance in front of the eye.
        assert!(close((p * Vec4::new(0.0, 0.0, -5.0, 1.0)).w, 5.0));

        let o = orthographic(&Frustum::orthographic_box(2.0, 1.0, 1.0, 50.0));
        assert!(close(o.transform_point3(Vec3::new(0.0, 0.0, -1.0)).z, 1.0));
        assert!(close(
            o.transform_point3(Vec3::new(0.0, 0.0, -50.0)).z,
            -1.0
        ));
    }

    #[test]
    fn frustum_top_edge_lands_on_y_equals_height_and_centre_on_the_middle() {
        let (w, h) = (80.0, 48.0);
        let aspect = 1.7;
        let fr = Frustum::from_fov(45.0, aspect, 0.1, 100.0);
        let mvp = viewport(w, h) * perspective(&fr);
        let screen = |p: Vec3| {
            let c = mvp * p.extend(1.0);
            c.truncate() / c.w
        };
        // A point on the frustum's top edge at depth d: y = t·d/|n|.
        for d in [0.1f32, 1.0, 7.5, 99.0] {
            let y = fr.t * d / fr.n.abs();
            let x = fr.r * d / fr.n.abs();
            let top = screen(Vec3::new(0.0, y, -d));
            assert!(close(top.y, h), "depth {d}: {top}");
            assert!(close(top.x, w / 2.0));
            let corner = screen(Vec3::new(-x, -y, -d));
            assert!(close3(corner, Vec3::new(0.0, 0.0, corner.z)), "{corner}");
            let centre = screen(Vec3::new(0.0, 0.0, -d));
            assert!(close(centre.x, w / 2.0) && close(centre.y, h / 2.0));
        }
    }

    #[test]
    fn view_puts_the_eye_at_the_origin_looking_down_minus_z() {
        let v = view(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y);
        assert!(close3(
            v.transform_point3(Vec3::new(0.0, 0.0, 5.0)),
            Vec3::ZERO
        ));
        assert!(close3(
            v.transform_point3(Vec3::ZERO),
            Vec3::new(0.0, 0.0, -5.0)
        ));
        let side = view(Vec3::new(3.0, 0.0, 0.0), Vec3::ZERO, Vec3::Y);
        // Looking down −x from +x with y up, right is forward × up = −z:
        // world +z is on the camera's left.
        assert!(close3(
            side.transform_point3(Vec3::Z),
            Vec3::new(-1.0, 0.0, -3.0)
        ));
    }

    #[test]
    fn model_scales_then_rotates_then_translates() {
        let m = model(
            Vec3::splat(2.0),
            Vec3::new(0.0, 0.0, 90.0),
            Vec3::new(1.0, 0.0, 0.0),
        );
        // (1,0,0) → scaled (2,0,0) → rotated about z (0,2,0) → moved (1,2,0).
        assert!(close3(
            m.transform_point3(Vec3::X),
            Vec3::new(1.0, 2.0, 0.0)
        ));
        // x first, then y: (0,1,0) → about x by 90° → (0,0,1) → about y by 90° → (1,0,0).
        let r = rotation(Vec3::new(90.0, 90.0, 0.0));
        assert!(close3(r.transform_point3(Vec3::Y), Vec3::X));
    }
}
