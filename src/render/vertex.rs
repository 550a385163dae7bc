//! The vertex stage, one vertex at a time: each mesh vertex is
//! transformed once per frame (not once per face that uses it), to its
//! clip-space position, world position and normal, its clip outcode, and,
//! when it is inside every clip plane, its screen position (snapped once
//! here, not once per triangle), depth and `1/w`. Lighting
//! ([`crate::shade`]) is evaluated per vertex for smooth shading. Its
//! twin, four vertices at a time in SIMD lanes, is `vertex_lanes.rs`, with
//! the same arithmetic per lane and so the same bits.
//!
//! **What is kept.** Every face reads a vertex's outcode and snapped
//! position, and a face that covers a sample its depth, `1/w` and light:
//! [`Vert`], 40 bytes. World position, normal and unsnapped position
//! ([`More`], 32 bytes) are read only by flat shading, falling-off lights,
//! rims, highlights, textures, alpha, maps, the general and clip paths and
//! back faces; they go to a second buffer only for a mesh the plan says
//! may need them, or one with a vertex off the common path, so a large
//! lit, culled, matte model keeps 40 bytes a vertex rather than 72.

use glam::{DMat4, Mat3, Mat4, Vec3};

use super::{Painter, Stage, vertex_lanes};
use crate::fixed::{Fixed, FixedPoint};
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

/// A vertex after the vertex stage: what every face reads of it (its clip
/// outcode and, inside every plane, its snapped position and centre key)
/// and what a face that covers a sample reads (depth, `1/w`, and under
/// smooth shading the light reaching it). 40 bytes; what only some
/// scenes' faces read is in [`More`], kept only where the plan reads it.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Vert {
    /// The light reaching the front of the vertex (smooth shading only).
    pub(super) light: Vec3,
    /// Clip outcode, with [`F64_PATH`] and [`BAD_NORMAL`]: 0 when inside
    /// every plane with a finite normal (then the fields below are valid).
    pub(super) code: u16,
    /// The screen position snapped, once per vertex rather than once per
    /// triangle; kept in `i32` (a snapped coordinate is at most
    /// `MAX_COORD · 256` = 2^29 in magnitude) and widened where read
    /// ([`Vert::fixed`]).
    pub(super) fixed32: [i32; 2],
    /// Where `fixed` lies among sample centres, for the face loop's first
    /// test.
    pub(super) key: CentreKey,
    pub(super) z: f32,
    pub(super) inv_w: f32,
}

impl Vert {
    /// The snapped screen position.
    #[inline(always)]
    pub(super) fn fixed(&self) -> FixedPoint {
        FixedPoint {
            x: Fixed(i64::from(self.fixed32[0])),
            y: Fixed(i64::from(self.fixed32[1])),
        }
    }

    /// Keeps `f`, a snapped position (in range: see [`Vert::fixed32`]).
    #[inline(always)]
    pub(super) fn set_fixed(&mut self, f: FixedPoint) {
        self.fixed32 = [f.x.0 as i32, f.y.0 as i32];
    }
}

/// What some scenes' faces read of a vertex beyond [`Vert`]: world
/// position, normal and unsnapped screen position (32 bytes). Kept, in a
/// buffer beside the vertices, for a mesh whose faces may read it
/// ([`crate::Plan::vertex_extras`], or a vertex off the common path), and
/// not otherwise: a lit, culled, matte mesh inside the view (the common
/// large model) keeps 40 bytes a vertex rather than 72.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct More {
    /// Position in the turned world, where lights live (flat shading, and
    /// point and spot lights, only: zero otherwise).
    pub(super) world: Vec3,
    /// Unit normal in the turned world (smooth shading only: zero
    /// otherwise).
    pub(super) normal: Vec3,
    /// The screen position in samples, before snapping (inside every
    /// plane only).
    pub(super) xy: [f32; 2],
}

/// A vertex as the triangle stage reads it: its [`Vert`] (its fields read
/// through `Deref`) and its [`More`], where kept.
#[derive(Clone, Copy, Debug)]
pub(super) struct V<'a> {
    at: &'a Vert,
    more: Option<&'a More>,
}

impl std::ops::Deref for V<'_> {
    type Target = Vert;
    #[inline(always)]
    fn deref(&self) -> &Vert {
        self.at
    }
}

impl V<'_> {
    #[inline(always)]
    fn more(&self) -> &More {
        // The plan keeps a mesh's extras wherever its faces read them
        // (`Plan::vertex_extras`), and the vertex stage keeps them for a
        // mesh with any vertex off the common path.
        self.more
            .expect("vertex extras are kept wherever they are read")
    }

    /// [`More::world`].
    #[inline(always)]
    pub(super) fn world(&self) -> Vec3 {
        self.more().world
    }

    /// [`More::normal`].
    #[inline(always)]
    pub(super) fn normal(&self) -> Vec3 {
        self.more().normal
    }

    /// [`More::xy`].
    #[inline(always)]
    pub(super) fn xy(&self) -> [f32; 2] {
        self.more().xy
    }
}

/// One mesh's vertices after the vertex stage: every vertex's [`Vert`],
/// and every vertex's [`More`] or none.
#[derive(Clone, Copy, Debug)]
pub(super) struct Verts<'a> {
    pub(super) core: &'a [Vert],
    pub(super) more: &'a [More],
}

impl<'a> Verts<'a> {
    /// The corners of `face`.
    #[inline(always)]
    pub(super) fn of(&self, face: [u32; 3]) -> [V<'a>; 3] {
        face.map(|i| V {
            at: &self.core[i as usize],
            more: self.more.get(i as usize),
        })
    }
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
    /// [`Painter::vertex_stage`] for mesh `i`, culled as `cull`: tested
    /// against the clip planes and keeping its extras as the plan says.
    pub(super) fn mesh_vertices(
        &mut self,
        stage: &Stage<'_>,
        t: &Transforms,
        vertices: (&[Vec3], &[Vec3]),
        i: usize,
        cull: crate::scene::Cull,
    ) {
        let p = stage.plan;
        self.vertex_stage(
            stage,
            t,
            vertices,
            p.clip_tests(i),
            p.vertex_extras(i, cull),
        );
    }

    /// Transforms `positions` (with `normals`), appending them to
    /// `self.verts`, and their extras to `self.more` where `keep` says, or
    /// where a vertex is off the common path all the same (outside a clip
    /// plane, or taking the f64 path: its faces take the clip path, which
    /// reads them); then the stage runs again, keeping them (rare: `keep`
    /// holds wherever clip tests run).
    pub(super) fn vertex_stage(
        &mut self,
        stage: &Stage<'_>,
        t: &Transforms,
        (positions, normals): (&[Vec3], &[Vec3]),
        clip_tests: bool,
        keep: bool,
    ) {
        let start = (self.verts.len(), self.more.len());
        let more = keep.then_some(&mut *self.more);
        let mut done =
            vertex_lanes::vertices(stage, t, (positions, normals), clip_tests, self.verts, more);
        if !keep && done.off_path > 0 {
            self.verts.truncate(start.0);
            done = vertex_lanes::vertices(
                stage,
                t,
                (positions, normals),
                clip_tests,
                self.verts,
                Some(self.more),
            );
        }
        debug_assert!(
            self.more.len() == start.1 || self.more.len() - start.1 == self.verts.len() - start.0
        );
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
    /// Of those, off the common path: outside a clip plane, or taking the
    /// f64 path (not counted in [`super::FrameStats`]).
    pub(super) off_path: u64,
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
) -> (Vert, More) {
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
    let mut more = More {
        world: if flat || falloff {
            t.model.transform_point3(p)
        } else {
            Vec3::ZERO
        },
        normal,
        xy: [0.0; 2],
    };
    let mut v = Vert {
        code,
        ..Vert::default()
    };
    if smooth {
        v.light = if falloff {
            Vec3::from(stage.lights.lambert_at(normal, more.world))
        } else {
            stage.lights.lambert(normal)
        };
    }
    if code == 0 {
        v.inv_w = 1.0 / clip.w;
        more.xy = stage.viewport.apply(clip.x * v.inv_w, clip.y * v.inv_w);
        v.z = clip.z * v.inv_w;
        match FixedPoint::snap(more.xy) {
            Some(f) => {
                v.set_fixed(f);
                v.key = CentreKey::of(f);
            }
            // Cannot happen inside the guard band; if it did, the clip path
            // deals with it.
            None => v.code = F64_PATH,
        }
    }
    if !n.is_finite() {
        v.code |= BAD_NORMAL;
    }
    (v, more)
}
