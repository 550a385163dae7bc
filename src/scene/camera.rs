//! The camera: where the eye is, what it looks at, its projection, and a
//! camera that frames a model, placed for the view's aspect when drawn.

use super::*;
use crate::transform::Axis;
use glam::Vec2;

/// Where the viewer stands and how the view is projected.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// How the view is projected.
    pub projection: Projection,
    /// Where the eye is.
    pub eye: Vec3,
    /// What it looks at.
    pub target: Vec3,
    /// Which way is up.
    pub up: Vec3,
    /// Frame a model: with this, `eye − target` is a direction and a zoom
    /// (length 1: the model just fits), and the eye's distance is chosen
    /// for each view's aspect ([`Camera::resolved`]).
    pub fit: Option<Fit>,
    /// The picture moved across the view, in view heights (x right, y
    /// up), as a lens is shifted: what dragging with the right button
    /// does in `spin`. The eye does not move, so nothing turns.
    pub shift: Vec2,
}

/// What a camera frames: a model's outline, as the points of the model
/// farthest out both ways along 13 axes (the coordinate axes, the face
/// diagonals and the space diagonals of a cube: a 26-sided hull that hugs
/// the model's convex hull, found with additions alone), so that the
/// model's projected extent can be found for any view in a few hundred
/// operations.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fit {
    /// The outline's points.
    pub points: [Vec3; Fit::POINTS],
}

/// The extremes of [`Fit::of`] so far, axis `4k + i` in lane `i` of
/// group `k` (the last three lanes padding): the least and greatest
/// extents, and the index of the first point at each, its bits kept in an
/// f32 lane (a select moves bits, it does no arithmetic).
struct Extremes {
    lo: [Vec4; 4],
    hi: [Vec4; 4],
    lo_at: [Vec4; 4],
    hi_at: [Vec4; 4],
}

impl Extremes {
    /// None yet, each at point `first`.
    fn new(first: usize) -> Extremes {
        let start = Vec4::splat(f32::from_bits(first as u32));
        Extremes {
            lo: [Vec4::INFINITY; 4],
            hi: [Vec4::NEG_INFINITY; 4],
            lo_at: [start; 4],
            hi_at: [start; 4],
        }
    }

    /// Each axis's least and greatest extent so far, each in all four
    /// lanes.
    #[inline]
    fn splats(&self) -> ([Vec4; 13], [Vec4; 13]) {
        let splat = |v: &[Vec4; 4]| std::array::from_fn(|a| Vec4::splat(v[a / 4][a % 4]));
        (splat(&self.lo), splat(&self.hi))
    }

    /// Point `i`, `p`, in order: the extremes it moves, if any.
    #[inline]
    fn add(&mut self, i: usize, p: Vec3) {
        // Along each axis, unnormalised (only the order matters), in four
        // groups of four lanes, so that the comparisons go four at a
        // time: each lane `(x·a + y·b) + z·c` with a, b, c in {−1, 0, 1},
        // the sums a lane at a time in that order (so the same as adding
        // the coordinates themselves, but for the sign of a zero, which no
        // comparison below tells apart).
        const A: [Vec4; 4] = [
            Vec4::new(1.0, 0.0, 0.0, 1.0),
            Vec4::new(1.0, 1.0, 1.0, 0.0),
            Vec4::new(0.0, 1.0, 1.0, 1.0),
            Vec4::new(-1.0, 0.0, 0.0, 0.0),
        ];
        const B: [Vec4; 4] = [
            Vec4::new(0.0, 1.0, 0.0, 1.0),
            Vec4::new(-1.0, 0.0, 0.0, 1.0),
            Vec4::new(1.0, 1.0, 1.0, -1.0),
            Vec4::new(1.0, 0.0, 0.0, 0.0),
        ];
        const C: [Vec4; 4] = [
            Vec4::new(0.0, 0.0, 1.0, 0.0),
            Vec4::new(0.0, 1.0, -1.0, 1.0),
            Vec4::new(-1.0, 1.0, -1.0, 1.0),
            Vec4::new(1.0, 0.0, 0.0, 0.0),
        ];
        if !p.is_finite() {
            return;
        }
        let (x, y, z) = (Vec4::splat(p.x), Vec4::splat(p.y), Vec4::splat(p.z));
        let s: [Vec4; 4] = std::array::from_fn(|k| (x * A[k] + y * B[k]) + z * C[k]);
        let (lo, hi) = (&mut self.lo, &mut self.hi);
        // Most points move no extreme: told first, for all sixteen lanes
        // at once, and passed by (then the steps below would change
        // nothing).
        let beyond = (0..4).fold(glam::BVec4A::FALSE, |m, k| {
            m | s[k].cmplt(lo[k]) | s[k].cmpgt(hi[k])
        });
        if !beyond.any() {
            return;
        }
        let at = Vec4::splat(f32::from_bits(i as u32));
        for (k, s) in s.into_iter().enumerate() {
            let (below, above) = (s.cmplt(lo[k]), s.cmpgt(hi[k]));
            // SSE's `min` and `max` keep the second where the first is not
            // strictly beyond it (no extent is NaN: a finite point's sums
            // overflow only one way): the selects by `below` and `above`,
            // in one operation each.
            lo[k] = s.min(lo[k]);
            self.lo_at[k] = Vec4::select(below, at, self.lo_at[k]);
            hi[k] = s.max(hi[k]);
            self.hi_at[k] = Vec4::select(above, at, self.hi_at[k]);
        }
    }
}

impl Fit {
    /// How many extreme points are kept: two for each of 13 axes.
    pub const POINTS: usize = 26;
    /// The share of the view's limiting dimension a framed model fills.
    pub const FILL: f32 = 0.9;

    /// The outline of `points` (at least one).
    pub fn of(points: &[Vec3]) -> Fit {
        // Where each extreme is starts at the first finite point (the first
        // point where none is): a finite point's extent can be infinite
        // (1e38 + 3e38 overflows), and where every finite point's extent
        // is, the first is the extreme, though no comparison with ±∞
        // moves it there.
        let first = points.iter().position(|p| p.is_finite()).unwrap_or(0);
        let mut e = Extremes::new(first);
        // Four points at a time, a point a lane, each axis's extent of the
        // four compared with that axis's extremes so far: most fours move
        // none, and are passed by, as each of their points would be; the
        // others are taken a point at a time. (The extents are the sums
        // `Extremes::add` finds, whose products by 0 and ±1 are exact, up
        // to the sign of a zero, which no comparison tells apart; a point
        // that is not finite can only send its four the long way.)
        let (mut lo, mut hi) = e.splats();
        let (fours, rest) = points.as_chunks::<4>();
        for (g, four) in fours.iter().enumerate() {
            let m = Mat4::from_cols(
                four[0].extend(0.0),
                four[1].extend(0.0),
                four[2].extend(0.0),
                four[3].extend(0.0),
            )
            .transpose();
            let (x, y, z) = (m.x_axis, m.y_axis, m.z_axis);
            let (sum, difference) = (x + y, x - y);
            let s = [
                x,
                y,
                z,
                sum,
                difference,
                x + z,
                x - z,
                y + z,
                y - z,
                sum + z,
                sum - z,
                difference + z,
                (y - x) + z,
            ];
            let beyond = (0..13).fold(glam::BVec4A::FALSE, |b, a| {
                b | s[a].cmplt(lo[a]) | s[a].cmpgt(hi[a])
            });
            if !beyond.any() {
                continue;
            }
            for (j, &p) in four.iter().enumerate() {
                e.add(g * 4 + j, p);
            }
            (lo, hi) = e.splats();
        }
        for (j, &p) in rest.iter().enumerate() {
            e.add(fours.len() * 4 + j, p);
        }
        let index = |lanes: &[Vec4; 4], axis: usize| lanes[axis / 4][axis % 4].to_bits();
        let at = |i: u32| points.get(i as usize).copied().unwrap_or(Vec3::ZERO);
        Fit {
            points: std::array::from_fn(|i| {
                if i < 13 {
                    at(index(&e.lo_at, i))
                } else {
                    at(index(&e.hi_at, i - 13))
                }
            }),
        }
    }

    /// The outline moved by `m`; exact for a turn that takes the 13 axes
    /// to themselves (a model's up axis turned onto y).
    pub fn transformed(self, m: Mat4) -> Fit {
        Fit {
            points: self.points.map(|p| m.transform_point3(p)),
        }
    }
}

/// The projection into the canonical cube.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// `fov_y` in degrees; `near` and `far` are distances in front of the
    /// eye, `0 < near < far`.
    Perspective {
        /// The vertical field of view, in degrees.
        fov_y: f32,
        /// The near plane's distance.
        near: f32,
        /// The far plane's distance.
        far: f32,
    },
    /// A box `height` tall, as wide as the aspect makes it.
    Orthographic {
        /// The box's height in world units.
        height: f32,
        /// The near plane's distance.
        near: f32,
        /// The far plane's distance.
        far: f32,
    },
    /// The vertices are in the canonical cube already; eye, target and up
    /// are ignored.
    None,
}

/// How a viewer has moved the view from where the scene put it: the eye
/// turned around the target, brought nearer or taken farther, the picture
/// shifted. What `spin`'s mouse and keys change and `--orbit`, `--zoom`
/// and `--shift` set, the same in both, so that a frame of `spin` after a
/// drag is the frame `render` draws with the angles the drag came to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// Degrees the eye is turned about the camera's up axis.
    pub yaw: f32,
    /// Degrees the eye is turned towards the up axis (within ±85).
    pub pitch: f32,
    /// The eye's distance from the target as a multiple of the scene's
    /// (below 1 nearer: the model drawn larger), within 0.05 to 20.
    pub distance: f32,
    /// The picture moved across the view, in view heights (x right, y up).
    pub shift: Vec2,
}

impl Default for View {
    fn default() -> Self {
        View::AS_GIVEN
    }
}

impl View {
    /// The view as the scene gives it: not turned, moved or shifted.
    pub const AS_GIVEN: View = View {
        yaw: 0.0,
        pitch: 0.0,
        distance: 1.0,
        shift: Vec2::ZERO,
    };

    /// The steepest pitch, in degrees: short of straight down or up, where
    /// the camera's up axis would no longer tell which way is up.
    pub const MAX_PITCH: f32 = 85.0;
    /// The nearest and farthest distances, as multiples of the scene's.
    pub const DISTANCE: (f32, f32) = (0.05, 20.0);
    /// Degrees a drag across the view's height turns the eye: a model
    /// framed by its height turns half round when dragged from top to
    /// bottom, on any terminal.
    pub const DRAG_DEGREES: f32 = 180.0;

    /// `camera` seen from this view.
    #[must_use]
    pub fn apply(&self, camera: &Camera) -> Camera {
        let c = camera.orbited(self.yaw, self.pitch, self.distance);
        Camera {
            shift: camera.shift + self.shift,
            ..c
        }
    }

    /// Turns the eye by `yaw` and `pitch` degrees (the pitch kept within
    /// [`View::MAX_PITCH`]).
    pub fn orbit(&mut self, yaw: f32, pitch: f32) {
        self.yaw += yaw;
        self.pitch = (self.pitch + pitch).clamp(-Self::MAX_PITCH, Self::MAX_PITCH);
    }

    /// Multiplies the eye's distance by `factor` (kept within
    /// [`View::DISTANCE`]).
    pub fn zoom(&mut self, factor: f32) {
        let (lo, hi) = Self::DISTANCE;
        self.distance = (self.distance * factor).clamp(lo, hi);
    }

    /// A drag of the mouse by `cells` (columns right, rows down) over a
    /// view `rows` cells high whose cells are `cell_aspect` as wide as
    /// high: the eye turned (the model following the pointer: a drag
    /// across the view's height turns it [`View::DRAG_DEGREES`]) or, with
    /// `pan`, the picture moved with the pointer. Cells are measured by
    /// their shape, so a drag turns a model the same on any terminal.
    pub fn drag(&mut self, cells: Vec2, rows: u16, cell_aspect: f32, pan: bool) {
        let heights = Vec2::new(cells.x * cell_aspect, cells.y) / f32::from(rows.max(1));
        if pan {
            self.shift += Vec2::new(heights.x, -heights.y);
        } else {
            self.orbit(
                -heights.x * Self::DRAG_DEGREES,
                heights.y * Self::DRAG_DEGREES,
            );
        }
    }
}

impl Default for Camera {
    fn default() -> Self {
        Camera {
            projection: Projection::Perspective {
                fov_y: 45.0,
                near: 0.1,
                far: 100.0,
            },
            eye: Vec3::new(0.0, 0.0, 5.0),
            target: Vec3::ZERO,
            up: Vec3::Y,
            fit: None,
            shift: Vec2::ZERO,
        }
    }
}

impl Camera {
    /// This camera moved around its target: the eye turned `yaw` degrees
    /// about the up axis and `pitch` degrees towards it, and its distance
    /// from the target multiplied by `zoom`. What `spin`'s arrow keys and
    /// the ratatui viewer's mouse do.
    #[must_use]
    pub fn orbited(&self, yaw: f32, pitch: f32, zoom: f32) -> Camera {
        let offset = (self.eye - self.target) * zoom;
        let yaw = glam::Quat::from_axis_angle(self.up.normalize_or_zero(), yaw.to_radians());
        let right = offset.cross(self.up).normalize_or_zero();
        let pitch = glam::Quat::from_axis_angle(right, pitch.to_radians());
        // The far plane goes out with an eye taken farther (and a framed
        // camera's planes follow its eye when it is resolved): what was in
        // view stays in view.
        let mut projection = self.projection;
        if self.fit.is_none()
            && zoom > 1.0
            && let Projection::Perspective { far, .. } | Projection::Orthographic { far, .. } =
                &mut projection
        {
            *far *= zoom;
        }
        Camera {
            eye: self.target + yaw * (pitch * offset),
            projection,
            ..*self
        }
    }

    /// Whether two cameras are the same bit for bit (`==` takes −0 for 0):
    /// then [`Camera::resolved`] gives the same camera for both.
    pub(crate) fn same_bits(&self, o: &Camera) -> bool {
        let v = |v: Vec3| v.to_array().map(f32::to_bits);
        let p = |p: Projection| match p {
            Projection::Perspective { fov_y, near, far } => {
                [1, fov_y.to_bits(), near.to_bits(), far.to_bits()]
            }
            Projection::Orthographic { height, near, far } => {
                [2, height.to_bits(), near.to_bits(), far.to_bits()]
            }
            Projection::None => [0; 4],
        };
        let fit = |f: Option<Fit>| f.map(|f| f.points.map(v));
        p(self.projection) == p(o.projection)
            && [self.eye, self.target, self.up].map(v) == [o.eye, o.target, o.up].map(v)
            && self.shift.to_array().map(f32::to_bits) == o.shift.to_array().map(f32::to_bits)
            && fit(self.fit) == fit(o.fit)
    }

    /// This camera for a view of `aspect` (width over height): where it
    /// frames a model ([`Camera::fit`]), the eye moved along `eye − target`
    /// to the distance at which the model's outline, turned any way about
    /// the y axis (as `spin` and `--yaw` turn it), fills 90 % of
    /// the view's height or width, whichever limits, times the length of
    /// `eye − target` (the zoom); and moved up or down to centre it (not
    /// sideways, so that the turn's axis stays in the middle). Every frame
    /// of a turn is then framed the same and none is cut off; a model
    /// round about its axis fills 90 %, a long one less in any one view.
    /// Otherwise the camera as it is.
    pub fn resolved(&self, aspect: f32) -> Camera {
        self.resolved_turning(aspect, Vec3::ZERO, Axis::Y)
    }

    /// [`Camera::resolved`] for a model turned by `turn` (degrees about x,
    /// then y, then z, as [`crate::RenderOptions::turn`]) that turns
    /// about `axis` from frame to frame: the outline is swept every way
    /// about `axis`, with `turn`'s other two angles as they are (its angle
    /// about `axis` is any), so that a tilted model, or one turning about
    /// x or z, is not cut off either. About y and untilted it is
    /// [`Camera::resolved`].
    pub fn resolved_turning(&self, aspect: f32, turn: Vec3, axis: Axis) -> Camera {
        const SWEPT: usize = 16 * Fit::POINTS;
        let (Some(fit), Projection::Perspective { fov_y, .. }) = (self.fit, self.projection) else {
            return Camera { fit: None, ..*self };
        };
        let offset = self.eye - self.target;
        let zoom = offset.length();
        let back = offset / zoom;
        let right = back.cross(self.up).normalize_or_zero();
        let right = if right == Vec3::ZERO { Vec3::X } else { right };
        let up = right.cross(back);
        let t = (fov_y.to_radians() / 2.0).tan() * Fit::FILL;
        let (kx, ky) = (t * aspect.max(1e-6), t);
        // The outline turned every way about y (as `spin` turns it), 16
        // steps a turn: the framing holds for every frame. Each point's
        // depth along `back`, its height along `up`, and the distance its
        // width needs are found once here; the passes below change only
        // the lift, and fold the same values in the same order as a pass
        // over the points themselves would.
        let mut depth = [0.0f32; SWEPT];
        let mut height = [0.0f32; SWEPT];
        let mut wide = [0.0f32; SWEPT];
        let sweep = Sweep::new(turn, axis);
        for (k, turned) in depth.chunks_exact_mut(Fit::POINTS).enumerate() {
            let turn = sweep.at(std::f32::consts::TAU * k as f32 / 16.0);
            for (j, (z, &p)) in turned.iter_mut().zip(&fit.points).enumerate() {
                let p = turn * p - self.target;
                let i = k * Fit::POINTS + j;
                *z = p.dot(back);
                height[i] = p.dot(up);
                wide[i] = *z + p.dot(right).abs() / kx;
            }
        }
        let points = || depth.iter().zip(&height).zip(&wide);
        // A point p at distance d projects to x / (d − z), which must stay
        // within kx (and y within ky): d ≥ z + |x| / kx. Seen from above
        // (or below) the projection is lopsided, so the view is also moved
        // up or down by `lift`, to centre it (not sideways: the turn's axis
        // stays in the middle).
        let fits = |lift: f32| {
            points().fold(0.0f32, |d, ((&z, &y), &w)| {
                d.max(w).max(z + (y - lift).abs() / ky)
            })
        };
        let mut lift = 0.0f32;
        let mut d = fits(lift);
        for _ in 0..4 {
            // Where the projection's top and bottom are at this distance,
            // as heights at the target's depth.
            let (lo, hi) = points().fold((f32::MAX, f32::MIN), |(lo, hi), ((&z, &y), _)| {
                let y = (y - lift) * d / (d - z);
                (lo.min(y), hi.max(y))
            });
            if !(lo.is_finite() && hi.is_finite()) {
                break;
            }
            lift += (lo + hi) / 2.0;
            d = fits(lift);
        }
        let (d, lift) = if d.is_finite() && d > 0.0 && lift.is_finite() {
            (d, lift)
        } else {
            (1.0, 0.0)
        };
        let target = self.target + up * lift;
        let distance = d * zoom;
        // The planes follow the eye: the far one moved out past the
        // model's farthest point, the near one in before its nearest, where
        // the eye so placed would leave part of it outside (a narrow field
        // of view, or a zoom out, puts the eye far away).
        let (near_z, far_z) = depth
            .iter()
            .fold((f32::MIN, f32::MAX), |(hi, lo), &z| (hi.max(z), lo.min(z)));
        let (nearest, farthest) = (distance - near_z, distance - far_z);
        let mut projection = self.projection;
        if let Projection::Perspective { near, far, .. } = &mut projection {
            if farthest.is_finite() && farthest * 1.01 >= *far {
                *far = farthest * 1.01;
            }
            if nearest.is_finite() && nearest > 0.0 && nearest * 0.99 <= *near {
                *near = (nearest * 0.5).max(*far * 1e-6);
            }
        }
        Camera {
            eye: target + back * d * zoom,
            target,
            projection,
            fit: None,
            ..*self
        }
    }

    /// `M_projection · M_view` for a view whose physical width/height ratio
    /// is `aspect`, composed in f64 and rounded once to f32 (so that an eye
    /// 1e30 away, or a scene 1e-30 across, loses nothing in the product).
    pub fn view_projection(&self, aspect: f32) -> Mat4 {
        self.view_projection64(aspect).as_mat4()
    }

    /// [`Camera::view_projection`] in f64.
    pub fn view_projection64(&self, aspect: f32) -> glam::DMat4 {
        let view = transform::view64(
            self.eye.as_dvec3(),
            self.target.as_dvec3(),
            self.up.as_dvec3(),
        );
        let aspect = aspect as f64;
        let projection = match self.projection {
            Projection::Perspective { fov_y, near, far } => {
                transform::perspective64(fov_y as f64, aspect, near as f64, far as f64)
            }
            Projection::Orthographic { height, near, far } => {
                transform::orthographic64(height as f64, aspect, near as f64, far as f64)
            }
            Projection::None => return glam::DMat4::IDENTITY,
        };
        if self.shift == Vec2::ZERO {
            return projection * view;
        }
        // Moved in normalised device coordinates, where the view is 2 high
        // and 2 wide: x' = x + t·w, so the same move at every depth.
        let shift = self.shift.as_dvec2() * 2.0;
        let t = glam::DVec3::new(shift.x / aspect.max(1e-6), shift.y, 0.0);
        glam::DMat4::from_translation(t) * projection * view
    }

    /// Why this camera cannot be used, if it cannot. Judged by direction and
    /// by relative size (in f64), never by absolute size: an eye 1e30 away
    /// and one 1e-30 from its target are both fine.
    pub fn check(&self) -> std::result::Result<(), String> {
        let finite = [self.eye, self.target, self.up]
            .iter()
            .all(|v| v.is_finite());
        if !finite {
            return Err("camera eye, target and up must be finite".into());
        }
        let (near, far) = match self.projection {
            Projection::None => return Ok(()),
            Projection::Perspective { fov_y, near, far } => {
                if !(fov_y > 0.0 && fov_y < 180.0) {
                    return Err(format!(
                        "fov_y must be between 0 and 180 degrees, not {fov_y}"
                    ));
                }
                if near.is_nan() || near <= 0.0 {
                    return Err(format!(
                        "near must be > 0 for a perspective camera, not {near}"
                    ));
                }
                if near < f32::MIN_POSITIVE {
                    return Err(format!(
                        "near = {near:e} is subnormal: f32 keeps no precision there; use a near of at least {:e} (scale the scene up if it is that small)",
                        f32::MIN_POSITIVE
                    ));
                }
                (near, far)
            }
            Projection::Orthographic { height, near, far } => {
                if !(height > 0.0 && height.is_finite()) {
                    return Err(format!("height must be > 0, not {height}"));
                }
                if height < MIN_HEIGHT {
                    return Err(format!(
                        "height = {height:e} is too small: the projection's scale 2/height overflows f32 in a narrow view; use a height of at least {MIN_HEIGHT:e} (scale the scene up if it is that small)"
                    ));
                }
                (near, far)
            }
        };
        if !(far > near && far.is_finite() && near.is_finite()) {
            return Err(format!(
                "far ({far}) must be finite and greater than near ({near})"
            ));
        }
        let (eye, target, up) = (
            self.eye.as_dvec3(),
            self.target.as_dvec3(),
            self.up.as_dvec3(),
        );
        let forward = target - eye;
        if forward == glam::DVec3::ZERO {
            return Err(format!(
                "camera eye and target are the same point, {}",
                self.eye
            ));
        }
        if up == glam::DVec3::ZERO {
            return Err("camera up must not be zero".into());
        }
        // The angle between up and the view direction, scale-free.
        let sin = forward.normalize().cross(up.normalize()).length();
        if sin.is_nan() || sin <= 1e-6 {
            return Err(
                "camera up must not be parallel to the view direction (target − eye)".into(),
            );
        }
        Ok(())
    }
}

/// The turns [`Camera::resolved_turning`] sweeps a model's outline
/// through: about `axis` by any angle, between the turns about the other
/// two axes that stay put (`Rz · Ry · Rx`, as [`crate::transform::rotation`]
/// composes them).
struct Sweep {
    axis: Axis,
    /// The fixed turns applied before and after the swept one.
    before: Option<glam::Quat>,
    after: Option<glam::Quat>,
}

impl Sweep {
    fn new(turn: Vec3, axis: Axis) -> Sweep {
        let r = turn * (std::f32::consts::PI / 180.0);
        let (x, y, z) = (
            glam::Quat::from_rotation_x(r.x),
            glam::Quat::from_rotation_y(r.y),
            glam::Quat::from_rotation_z(r.z),
        );
        // A turn of no angle is left out: untilted, the sweep about y is
        // the one [`Camera::resolved`] has always made, bit for bit.
        let (before, after) = match axis {
            Axis::X => (None, Some(z * y)),
            Axis::Y => (Some(x), Some(z)),
            Axis::Z => (Some(y * x), None),
        };
        let some = |q: Option<glam::Quat>| q.filter(|q| *q != glam::Quat::IDENTITY);
        Sweep {
            axis,
            before: some(before),
            after: some(after),
        }
    }

    /// The turn by `angle` (radians) about the axis, between the fixed ones.
    fn at(&self, angle: f32) -> glam::Quat {
        let swept = match self.axis {
            Axis::X => glam::Quat::from_rotation_x(angle),
            Axis::Y => glam::Quat::from_rotation_y(angle),
            Axis::Z => glam::Quat::from_rotation_z(angle),
        };
        let swept = match self.before {
            Some(b) => swept * b,
            None => swept,
        };
        match self.after {
            Some(a) => a * swept,
            None => swept,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    proptest::proptest! {
        // Enough cases that a four passed by wrongly on one axis alone (a
        // wrong sum for that axis) is found.
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(3000))]
        /// The outline keeps, on each of the 13 axes, the first point of
        /// least and of greatest extent, as one axis and one point at a
        /// time finds them (four at a time where none moves); points that
        /// are not finite are passed over.
        #[test]
        fn the_outline_is_the_first_extreme_point_on_each_axis(
            raw in proptest::collection::vec((0u8..6, -3i8..4, -3i8..4, -3i8..4), 1..60),
        ) {
            let points: Vec<Vec3> = raw
                .iter()
                .map(|&(kind, x, y, z)| match kind {
                    0 => Vec3::new(f32::NAN, y as f32, z as f32),
                    1 => Vec3::new(x as f32 * 1e38, y as f32 * 1e38, z as f32),
                    _ => Vec3::new(x as f32, y as f32, z as f32) * 0.5,
                })
                .collect();
            let axes: [fn(Vec3) -> f32; 13] = [
                |p| p.x,
                |p| p.y,
                |p| p.z,
                |p| p.x + p.y,
                |p| p.x - p.y,
                |p| p.x + p.z,
                |p| p.x - p.z,
                |p| p.y + p.z,
                |p| p.y - p.z,
                |p| p.x + p.y + p.z,
                |p| p.x + p.y - p.z,
                |p| p.x - p.y + p.z,
                |p| -p.x + p.y + p.z,
            ];
            let first = |axis: fn(Vec3) -> f32, better: fn(f32, f32) -> bool| {
                let finite = points.iter().copied().filter(|p| p.is_finite());
                finite.fold(None, |best: Option<Vec3>, p| match best {
                    Some(b) if !better(axis(p), axis(b)) => Some(b),
                    _ => Some(p),
                })
                .unwrap_or(points[0])
            };
            let want: Vec<Vec3> = axes
                .iter()
                .map(|&a| first(a, |s, t| s < t))
                .chain(axes.iter().map(|&a| first(a, |s, t| s > t)))
                .collect();
            let got = Fit::of(&points).points;
            proptest::prop_assert_eq!(
                got.iter().map(|p| p.to_array().map(f32::to_bits)).collect::<Vec<_>>(),
                want.iter().map(|p| p.to_array().map(f32::to_bits)).collect::<Vec<_>>()
            );
        }
        /// A framed camera's distance and lift are what the passes over
        /// the outline turned 16 ways about y give, each pass over every
        /// turned point in order, as the framing is defined (depths,
        /// heights and widths found from the point at each pass): the same
        /// bits, for outlines and views of any shape, seen from anywhere.
        #[test]
        fn framing_folds_every_turned_point_as_defined(
            raw in proptest::collection::vec((-40i16..40, -40i16..40, -40i16..40), 1..30),
            eye in (-20i16..20, -20i16..20, -20i16..20),
            aspect in 0.05f32..20.0,
        ) {
            let points: Vec<Vec3> = raw
                .iter()
                .map(|&(x, y, z)| Vec3::new(x as f32, y as f32, z as f32) * 0.37)
                .collect();
            let camera = Camera {
                eye: Vec3::new(eye.0 as f32, eye.1 as f32, eye.2 as f32 + 0.5),
                fit: Some(Fit::of(&points)),
                ..Camera::default()
            };
            let fit = camera.fit.unwrap();
            let Projection::Perspective { fov_y, .. } = camera.projection else {
                unreachable!("the default camera is a perspective one")
            };
            // The definition, point by point.
            let offset = camera.eye - camera.target;
            let back = offset / offset.length();
            let right = back.cross(camera.up).normalize_or_zero();
            let right = if right == Vec3::ZERO { Vec3::X } else { right };
            let up = right.cross(back);
            let t = (fov_y.to_radians() / 2.0).tan() * Fit::FILL;
            let (kx, ky) = (t * aspect.max(1e-6), t);
            let swept: Vec<Vec3> = (0..16)
                .flat_map(|k| {
                    let turn = glam::Quat::from_rotation_y(std::f32::consts::TAU * k as f32 / 16.0);
                    fit.points.map(|p| turn * p - camera.target)
                })
                .collect();
            let fits = |lift: f32| {
                swept.iter().fold(0.0f32, |d, p| {
                    let z = p.dot(back);
                    d.max(z + p.dot(right).abs() / kx)
                        .max(z + (p.dot(up) - lift).abs() / ky)
                })
            };
            let (mut lift, mut d) = (0.0f32, fits(0.0));
            for _ in 0..4 {
                let (lo, hi) = swept.iter().fold((f32::MAX, f32::MIN), |(lo, hi), p| {
                    let y = (p.dot(up) - lift) * d / (d - p.dot(back));
                    (lo.min(y), hi.max(y))
                });
                if !(lo.is_finite() && hi.is_finite()) {
                    break;
                }
                lift += (lo + hi) / 2.0;
                d = fits(lift);
            }
            let (d, lift) = if d.is_finite() && d > 0.0 && lift.is_finite() {
                (d, lift)
            } else {
                (1.0, 0.0)
            };
            let target = camera.target + up * lift;
            let want = Camera {
                eye: target + back * d * offset.length(),
                target,
                fit: None,
                ..camera
            };
            // The planes follow the eye (checked apart, below).
            let got = Camera {
                projection: camera.projection,
                ..camera.resolved(aspect)
            };
            proptest::prop_assert!(got.same_bits(&want), "{:?} against {:?}", got, want);
        }
    }

    #[test]
    fn a_drag_turns_by_the_view_heights_it_crosses() {
        // 8 columns of cells half as wide as high, on 16 rows: a quarter
        // of the height, a quarter of 180°, the eye going the other way.
        let mut v = View::AS_GIVEN;
        v.drag(Vec2::new(8.0, 0.0), 16, 0.5, false);
        assert_eq!((v.yaw, v.pitch), (-45.0, 0.0));
        // 4 rows down: the eye rises 45°; far more stops short of overhead.
        v.drag(Vec2::new(0.0, 4.0), 16, 0.5, false);
        assert_eq!((v.yaw, v.pitch), (-45.0, 45.0));
        v.drag(Vec2::new(0.0, 40.0), 16, 0.5, false);
        assert_eq!(v.pitch, View::MAX_PITCH);
        // Panning moves the picture with the pointer: right and up.
        let mut p = View::AS_GIVEN;
        p.drag(Vec2::new(4.0, -2.0), 16, 0.5, true);
        assert_eq!(p.shift, Vec2::new(0.125, 0.125));
        assert_eq!((p.yaw, p.pitch), (0.0, 0.0));
    }

    #[test]
    fn zoom_stays_within_its_range_and_apply_orbits_and_shifts() {
        let mut v = View::AS_GIVEN;
        for _ in 0..100 {
            v.zoom(0.5);
        }
        assert_eq!(v.distance, View::DISTANCE.0);
        let cam = Camera::default();
        let v = View {
            yaw: 90.0,
            pitch: 0.0,
            distance: 2.0,
            shift: Vec2::new(0.25, 0.0),
        };
        let seen = v.apply(&cam);
        // The eye a quarter turn about y, twice as far: +x (from +z).
        assert!(
            (seen.eye - Vec3::new(10.0, 0.0, 0.0)).length() < 1e-5,
            "{seen:?}"
        );
        assert_eq!(seen.shift, Vec2::new(0.25, 0.0));
        // The shift moves the target's image a quarter of the height right
        // (half a unit of normalised device coordinates over the aspect).
        let aspect = 2.0;
        let at = |c: &Camera| c.view_projection(aspect).project_point3(c.target);
        let moved = at(&seen)
            - at(&Camera {
                shift: Vec2::ZERO,
                ..seen
            });
        assert!(
            (moved - Vec3::new(0.25, 0.0, 0.0)).length() < 1e-6,
            "{moved}"
        );
    }
}
