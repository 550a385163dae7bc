//! The vertex stage, one vertex at a time: each mesh vertex is
//! transformed once per frame (not once per face that uses it), to its
//! clip-space position, world position and normal, its clip outcode, and,
//! when it is inside every clip plane, its screen position (snapped once
//! here, not once per triangle), depth and `1/w`. Lighting
//! ([`crate::shade`]) is evaluated per vertex for smooth shading. Its
//! twin, four vertices at a time in SIMD lanes, is `vertex_lanes.rs`, with
//! the same arithmetic per lane and so the same bits.

use glam::{DMat4, Mat3, Mat4, Vec3};

use super::{Painter, Stage, vertex_lanes};
use crate::fixed::FixedPoint;
use crate::raster::CentreKey;
use crate::shade::Shading;
use crate::transform;

/// One group's matrices, computed once per frame: model to clip space (in
/// f32 for the vertex stage, and the same matrix in f64 for the clip path,
/// where coordinates up to f32's largest must neither overflow nor cancel),
/// model to world, and the normals' (the inverse transpose).
#[derive(Clone, Copy, Debug)]
pub(super) struct Transforms {
    pub(super) mvp: Mat4,
    pub(super) mvp64: DMat4,
    pub(super) model: Mat4,
    pub(super) normal: Mat3,
}

impl Transforms {
    pub(super) fn new(vp: Mat4, model: Mat4) -> Transforms {
        // Composed in f64: a model scaled towards f32's largest would
        // overflow the f32 product (its vertices then take the f64 path).
        let mvp64 = vp.as_dmat4() * model.as_dmat4();
        Transforms {
            mvp: mvp64.as_mat4(),
            mvp64,
            model,
            normal: Mat3::from_mat4(model).inverse().transpose(),
        }
    }
}

/// A vertex after the vertex stage.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Vert {
    /// Position in the turned world, where lights live (flat shading, and
    /// point and spot lights, only: zero otherwise).
    pub(super) world: Vec3,
    /// Unit normal in the turned world (smooth shading only: zero
    /// otherwise).
    pub(super) normal: Vec3,
    /// The light reaching the front of the vertex (smooth shading only).
    pub(super) light: Vec3,
    /// Clip outcode, with [`F64_PATH`] and [`BAD_NORMAL`]: 0 when inside
    /// every plane with a finite normal (then the fields below are valid).
    pub(super) code: u16,
    pub(super) xy: [f32; 2],
    /// `xy` snapped, once per vertex rather than once per triangle.
    pub(super) fixed: FixedPoint,
    /// Where `fixed` lies among sample centres, for the face loop's first
    /// test.
    pub(super) key: CentreKey,
    pub(super) z: f32,
    pub(super) inv_w: f32,
}

/// An outcode bit of no clip plane: the vertex's f32 clip position is not
/// finite (coordinates near f32's largest overflow in the product) or its
/// screen position could not be snapped; it takes the clip path, which
/// works in f64. Never a reason to reject a triangle outright.
pub(super) const F64_PATH: u16 = 1 << 7;
/// The outcode bits of the clip planes.
pub(super) const PLANES: u16 = F64_PATH - 1;
/// A bit of no clip plane: the vertex's normal (as given) is NaN or
/// infinite, and its triangles are dropped. In the code, so that one test
/// tells a triangle that takes the common path.
pub(super) const BAD_NORMAL: u16 = 1 << 8;

impl Painter<'_> {
    /// Transforms `positions` (with `normals`), appending them to
    /// `self.verts`.
    pub(super) fn vertex_stage(
        &mut self,
        stage: &Stage<'_>,
        t: &Transforms,
        positions: &[Vec3],
        normals: &[Vec3],
        clip_tests: bool,
    ) {
        let done = vertex_lanes::vertices(stage, t, positions, normals, clip_tests, self.verts);
        self.stats.vertices += done.vertices;
        self.stats.lighting_evaluations += done.lit;
        self.stats.clip_tests += done.clip_tested;
    }
}

/// What the vertex stage did, counted where it did it (for
/// [`super::FrameStats`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct VertexWork {
    /// Vertices transformed.
    pub(super) vertices: u64,
    /// Of those, lit (smooth shading lights every vertex).
    pub(super) lit: u64,
    /// Of those, tested against the clip planes.
    pub(super) clip_tested: u64,
}

/// One vertex through the vertex stage: its clip position and outcode
/// and, inside every plane, its screen position, snapped, depth and `1/w`;
/// its world position (flat shading) or normal and light (smooth).
#[inline(always)]
pub(super) fn vertex(
    stage: &Stage<'_>,
    t: &Transforms,
    p: Vec3,
    n: Vec3,
    clip_tests: bool,
) -> Vert {
    let smooth = stage.plan.shading == Shading::Smooth;
    // World positions serve flat shading and point and spot lights (the
    // clip path finds its own from the model).
    let falloff = stage.plan.falloff.run;
    let flat = stage.plan.shading == Shading::Flat;
    let clip = t.mvp * p.extend(1.0);
    // Inside bounds need no test: every plane's code is 0.
    let code = if !clip.is_finite() {
        F64_PATH
    } else if clip_tests {
        u16::from(stage.clipper.outcode(clip))
    } else {
        0
    };
    // Only smooth shading reads vertex normals.
    let normal = if smooth {
        transform::direction(t.normal * n)
    } else {
        Vec3::ZERO
    };
    let mut v = Vert {
        world: if flat || falloff {
            t.model.transform_point3(p)
        } else {
            Vec3::ZERO
        },
        normal,
        code,
        ..Vert::default()
    };
    if smooth {
        v.light = if falloff {
            Vec3::from(stage.lights.lambert_at(normal, v.world))
        } else {
            stage.lights.lambert(normal)
        };
    }
    if code == 0 {
        v.inv_w = 1.0 / clip.w;
        v.xy = stage.viewport.apply(clip.x * v.inv_w, clip.y * v.inv_w);
        v.z = clip.z * v.inv_w;
        match FixedPoint::snap(v.xy) {
            Some(f) => (v.fixed, v.key) = (f, CentreKey::of(f)),
            // Cannot happen inside the guard band; if it did, the clip path
            // deals with it.
            None => v.code = F64_PATH,
        }
    }
    if !n.is_finite() {
        v.code |= BAD_NORMAL;
    }
    v
}
