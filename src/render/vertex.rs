//! The vertex stage, one vertex at a time: each mesh vertex is
//! transformed once per frame (not once per face that uses it), to its
//! clip-space position, world position and normal, its clip outcode, and,
//! when it is inside every clip plane, its screen position (snapped once
//! here, not once per triangle), depth and `1/w`. Lighting
//! ([`crate::shade`]) is evaluated per vertex for smooth shading. Its
//! twin, four vertices at a time in SIMD lanes, is `vertex_lanes.rs`, with
//! the same arithmetic per lane and so the same bits.
//!
//! **What is kept.** Every face reads a vertex's centre key (its first
//! test), and the faces past that test its outcode and snapped position:
//! [`Vert`], kept as three arrays ([`Core`], 14 bytes a vertex).
//! A face that covers a sample also reads its depth, `1/w` and light
//! ([`Deep`]); some faces read its world position, normal and unsnapped
//! position (flat shading, falling-off lights, rims, highlights,
//! textures, alpha, maps, the general and clip paths and back faces:
//! ([`Rest`]). Those go, with the [`Deep`], to two more buffers ([`Kept`]:
//! 20 and 32 bytes a vertex) for a mesh the plan says may read them, or
//! one with a vertex off the common path; a lit, culled, matte mesh inside
//! the view with few vertices for the frame's samples keeps the [`Deep`]
//! alone, all its faces read (`Plan::vertex_extras`, [`crate::plan::Extras`]).
//! A large lit, culled, matte model seen small keeps
//! 14 bytes a vertex, and the [`Deep`] of the corners of a face that
//! covers a sample is found again at set-up ([`Lazy`], by the very
//! operations the stage uses, so the bits are the same): most of its
//! vertices are never the corner of such a face, so finding it there costs
//! less than finding it for every vertex, where there are many more
//! vertices than samples (and more where there are fewer: the plan
//! decides, by [`crate::Plan::DEFER_PER_SAMPLE`]).
//!
//! **The types, by how often they are read.** The values: [`Vert`] (every
//! face), [`Deep`] (every face that covers a sample), [`Rest`] (the faces
//! of some scenes) and [`More`], the two together as the stage finds them.
//! Where they live: [`Core`] and [`Kept`], each split into arrays by the
//! same reads, borrowed as [`CoreRef`] and [`KeptRef`] for one mesh. How a
//! face reads them: [`Verts`], a mesh's vertices, and [`V`], one corner,
//! whichever buffer holds it or [`Lazy`] finds it. A value a new effect
//! needs at each vertex is a field of [`Deep`] if every covering face reads
//! it, else of [`Rest`]; it is found in [`vertex`] (and [`deep`], if a
//! [`Deep`]), and by the same operations, lane for lane, in
//! `vertex_lanes.rs` (`four`, `deep4`), whose property test compares the
//! two field by field; [`V`] gives it to the fill.

use glam::{DMat4, Mat3, Mat4, Vec3};

use super::{Painter, Stage, vertex_lanes};
use crate::fixed::{Fixed, FixedPoint};
use crate::plan::Effect;
use crate::plan::Extras;
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

/// A vertex after the vertex stage: what every face reads of it, its clip
/// outcode and, inside every plane, its snapped position and centre key.
/// Kept as three arrays ([`Core`], 14 bytes a vertex); what a face that
/// covers a sample reads of it beyond these is in [`More`], kept only
/// where the plan reads it, or found again at set-up ([`Lazy`]).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Vert {
    /// The screen position snapped, once per vertex rather than once per
    /// triangle; kept in `i32` (a snapped coordinate is at most
    /// `MAX_COORD · 256` = 2^29 in magnitude) and widened where read
    /// ([`Vert::fixed`]).
    pub(super) fixed32: [i32; 2],
    /// Where `fixed` lies among sample centres, for the face loop's first
    /// test.
    pub(super) key: CentreKey,
    /// Clip outcode, with [`F64_PATH`] and [`BAD_NORMAL`]: 0 when inside
    /// every plane with a finite normal (then the fields above are valid).
    pub(super) code: u16,
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

/// Every vertex's [`Vert`], kept as three arrays (structure of arrays):
/// its centre key, which every face reads first, its snapped position and
/// its outcode, which the faces past that test read. 14 bytes a vertex
/// ([`Core::BYTES`]), and each read is one load at a scaled index (a
/// 16-byte [`Vert`] needs its index shifted first); the lanes store four
/// keys or four positions at once. The face loop's first test reads the
/// keys alone: 4 bytes a vertex, where most faces of a detailed model
/// seen small end.
#[derive(Clone, Debug, Default)]
pub(super) struct Core {
    keys: Vec<CentreKey>,
    fixed: Vec<[i32; 2]>,
    codes: Vec<u16>,
}

impl Core {
    /// The bytes a vertex takes: its centre key, snapped position and
    /// outcode.
    pub(super) const BYTES: usize =
        size_of::<CentreKey>() + size_of::<[i32; 2]>() + size_of::<u16>();

    /// How many vertices are kept.
    pub(super) fn len(&self) -> usize {
        self.keys.len()
    }

    /// Empty, keeping the memory.
    pub(super) fn clear(&mut self) {
        self.truncate(0);
    }

    /// The first `n` vertices kept.
    pub(super) fn truncate(&mut self, n: usize) {
        self.keys.truncate(n);
        self.fixed.truncate(n);
        self.codes.truncate(n);
    }

    /// Room for `n` more.
    pub(super) fn reserve(&mut self, n: usize) {
        self.keys.reserve(n);
        self.fixed.reserve(n);
        self.codes.reserve(n);
    }

    /// Appends `v`.
    #[inline(always)]
    pub(super) fn push(&mut self, v: Vert) {
        self.keys.push(v.key);
        self.fixed.push(v.fixed32);
        self.codes.push(v.code);
    }

    /// Appends four vertices inside every plane: their keys and snapped
    /// positions (outcodes 0).
    #[inline(always)]
    pub(super) fn push4(&mut self, keys: [CentreKey; 4], fixed: [[i32; 2]; 4]) {
        self.keys.extend_from_slice(&keys);
        self.fixed.extend_from_slice(&fixed);
        self.codes.extend_from_slice(&[0; 4]);
    }

    /// The vertices in `r`.
    pub(super) fn range(&self, r: std::ops::Range<usize>) -> CoreRef<'_> {
        CoreRef {
            keys: &self.keys[r.clone()],
            fixed: &self.fixed[r.clone()],
            codes: &self.codes[r],
        }
    }

    /// All of them.
    pub(super) fn all(&self) -> CoreRef<'_> {
        self.range(0..self.len())
    }

    /// Each vertex kept, in order (for the tests).
    #[cfg(test)]
    pub(super) fn to_vec(&self) -> Vec<Vert> {
        let all = self.all();
        (0..self.len() as u32).map(|i| all.get(i)).collect()
    }
}

/// One mesh's [`Core`].
#[derive(Clone, Copy, Debug)]
pub(super) struct CoreRef<'a> {
    pub(super) keys: &'a [CentreKey],
    fixed: &'a [[i32; 2]],
    codes: &'a [u16],
}

impl CoreRef<'_> {
    /// Vertex `i`.
    #[inline(always)]
    pub(super) fn get(&self, i: u32) -> Vert {
        let i = i as usize;
        Vert {
            fixed32: self.fixed[i],
            key: self.keys[i],
            code: self.codes[i],
        }
    }

    /// Vertex `i`'s outcode.
    #[inline(always)]
    pub(super) fn code(&self, i: u32) -> u16 {
        self.codes[i as usize]
    }

    /// Vertex `i`'s snapped position.
    #[inline(always)]
    pub(super) fn fixed(&self, i: u32) -> FixedPoint {
        let [x, y] = self.fixed[i as usize];
        FixedPoint {
            x: Fixed(i64::from(x)),
            y: Fixed(i64::from(y)),
        }
    }

    /// The same, each array cut to the keys' length (as it is), once a
    /// run: an index that passes the face loop's check on the keys then
    /// needs none on the others.
    #[inline(always)]
    fn trimmed(self) -> Self {
        let n = self.keys.len();
        CoreRef {
            keys: self.keys,
            fixed: &self.fixed[..n],
            codes: &self.codes[..n],
        }
    }
}

/// What a face that covers a sample reads of a vertex inside every plane:
/// its depth, `1/w`, and under smooth shading the light reaching it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct Deep {
    /// The light reaching the front of the vertex (smooth shading only).
    pub(super) light: Vec3,
    pub(super) z: f32,
    pub(super) inv_w: f32,
}

/// What a face reads of a vertex beyond [`Vert`] and its [`Deep`]: its
/// world position, normal and unsnapped screen position (32 bytes), read
/// only by some scenes' faces (flat shading, falling-off lights, rims,
/// highlights, textures, alpha, maps, the general and clip paths and back
/// faces).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Rest {
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

impl Rest {
    /// Where a face that reads none of it finds it: NaN.
    const NAN: Rest = Rest {
        world: Vec3::NAN,
        normal: Vec3::NAN,
        xy: [f32::NAN; 2],
    };
}

/// What the vertex stage finds of a vertex beyond [`Vert`]: its [`Deep`]
/// and its [`Rest`] (52 bytes), kept as the plan says
/// ([`crate::Plan::vertex_extras`], or all of it for a mesh with a vertex
/// off the common path), in [`Kept`].
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct More {
    /// Depth, `1/w` and light (inside every plane only).
    pub(super) deep: Deep,
    /// World position, normal and unsnapped position.
    pub(super) rest: Rest,
}

/// The extras the vertex stage keeps, in two buffers beside the vertices:
/// each kept vertex's [`Deep`], and where the plan says faces may read
/// them, its [`Rest`] too (a lit, culled, matte mesh inside the view keeps
/// 20 bytes a vertex here, or none where the corners' [`Deep`] is found
/// again at set-up).
#[derive(Clone, Debug, Default)]
pub(super) struct Kept {
    pub(super) deep: Vec<Deep>,
    pub(super) rest: Vec<Rest>,
}

impl Kept {
    /// Empty, keeping the memory.
    pub(super) fn clear(&mut self) {
        self.deep.clear();
        self.rest.clear();
    }

    /// How many of each are kept (where a mesh's begin or end).
    pub(super) fn marks(&self) -> [usize; 2] {
        [self.deep.len(), self.rest.len()]
    }

    /// Those kept between two [`Kept::marks`].
    pub(super) fn between(&self, from: [usize; 2], to: [usize; 2]) -> KeptRef<'_> {
        KeptRef {
            deep: &self.deep[from[0]..to[0]],
            rest: &self.rest[from[1]..to[1]],
        }
    }

    /// All of them.
    pub(super) fn all(&self) -> KeptRef<'_> {
        self.between([0; 2], self.marks())
    }

    /// Appends `m`, its [`Rest`] too if `rest`.
    #[inline(always)]
    pub(super) fn push(&mut self, m: &More, rest: bool) {
        self.deep.push(m.deep);
        if rest {
            self.rest.push(m.rest);
        }
    }
}

/// One mesh's kept extras ([`Kept`]): every vertex's [`Deep`] or none,
/// and every vertex's [`Rest`] or none.
#[derive(Clone, Copy, Debug)]
pub(super) struct KeptRef<'a> {
    pub(super) deep: &'a [Deep],
    pub(super) rest: &'a [Rest],
}

impl KeptRef<'_> {
    /// What is kept, as the plan names it.
    #[inline(always)]
    pub(super) fn extras(&self) -> Extras {
        if self.deep.is_empty() {
            Extras::Found
        } else if self.rest.is_empty() {
            Extras::Deep
        } else {
            Extras::All
        }
    }
}

/// A vertex as the triangle stage reads it: its [`Vert`] (its fields read
/// through `Deref`), its [`Deep`] kept or found again into a face's
/// scratch, and its [`Rest`] kept or, where the plan reads none of it
/// ([`crate::Plan::vertex_extras`]), NaN.
#[derive(Clone, Copy, Debug)]
pub(super) struct V<'a> {
    at: Vert,
    deep: &'a Deep,
    rest: &'a Rest,
}

impl std::ops::Deref for V<'_> {
    type Target = Vert;
    #[inline(always)]
    fn deref(&self) -> &Vert {
        &self.at
    }
}

impl V<'_> {
    /// Depth, `1/w` and light.
    #[inline(always)]
    pub(super) fn deep(&self) -> &Deep {
        self.deep
    }

    /// [`Rest::world`].
    #[inline(always)]
    pub(super) fn world(&self) -> Vec3 {
        self.rest.world
    }

    /// [`Rest::normal`].
    #[inline(always)]
    pub(super) fn normal(&self) -> Vec3 {
        self.rest.normal
    }

    /// [`Rest::xy`].
    #[inline(always)]
    pub(super) fn xy(&self) -> [f32; 2] {
        self.rest.xy
    }
}

/// One mesh's vertices after the vertex stage: every vertex's [`Vert`],
/// and what it keeps of the rest ([`KeptRef`]; where no [`Deep`], each
/// corner's is found again from `lazy`).
#[derive(Clone, Copy)]
pub(super) struct Verts<'a> {
    pub(super) core: CoreRef<'a>,
    pub(super) kept: KeptRef<'a>,
    pub(super) lazy: Lazy<'a>,
}

/// What the vertex stage read, for finding a vertex's [`Deep`] again at
/// set-up: its positions and normals, matrices and stage. For a mesh of
/// many more vertices than the faces that cover a sample have corners
/// (a large model seen small), finding it for those corners alone costs
/// less than finding it for every vertex and keeping it: the vertex
/// stage keeps 14 bytes a vertex, not 34. The same operations find it both
/// ways ([`deep`] one at a time, `vertex_lanes::deep4` in lanes, as the
/// stage itself does), so the bits are the same.
#[derive(Clone, Copy)]
pub(super) struct Lazy<'a> {
    pub(super) positions: &'a [Vec3],
    pub(super) normals: &'a [Vec3],
    pub(super) transforms: &'a Transforms,
    pub(super) stage: &'a Stage<'a>,
}

impl Deep {
    /// A face's scratch for the [`Deep`] of corners not kept
    /// ([`Verts::of`]).
    pub(super) const SCRATCH: [Deep; 3] = [Deep {
        light: Vec3::ZERO,
        z: 0.0,
        inv_w: 0.0,
    }; 3];
}

impl Lazy<'_> {
    /// The [`Deep`] of `face`'s corners, into `scratch` (out of line: the
    /// face loop of a mesh that keeps its extras stays as short as it was).
    /// Three at once in lanes where they are the common case (the fourth
    /// lane a copy of the third).
    #[inline(never)]
    fn deep3(&self, face: [u32; 3], scratch: &mut [Deep; 3]) {
        let [a, b, c] = face.map(|i| i as usize);
        let p = [a, b, c, c].map(|i| self.positions[i]);
        let n = [a, b, c, c].map(|i| self.normals[i]);
        if let Some([d0, d1, d2, _]) = vertex_lanes::deep4(self.stage, self.transforms, &p, &n) {
            *scratch = [d0, d1, d2];
            return;
        }
        for (m, i) in scratch.iter_mut().zip(face) {
            let i = i as usize;
            *m = deep(
                self.stage,
                self.transforms,
                self.positions[i],
                self.normals[i],
            );
        }
    }
}

impl<'a> Verts<'a> {
    /// A mesh's vertices after the vertex stage, which read `vertices`
    /// (positions and normals) through `transforms`.
    pub(super) fn new(
        (core, kept): (CoreRef<'a>, KeptRef<'a>),
        (positions, normals): (&'a [Vec3], &'a [Vec3]),
        transforms: &'a Transforms,
        stage: &'a Stage<'a>,
    ) -> Verts<'a> {
        Verts {
            core,
            kept,
            lazy: Lazy {
                positions,
                normals,
                transforms,
                stage,
            },
        }
    }

    /// The corners of `face`, their [`Deep`] found into `scratch` where
    /// it is not kept.
    #[inline(always)]
    pub(super) fn of<'s>(&self, face: [u32; 3], scratch: &'s mut [Deep; 3]) -> [V<'s>; 3]
    where
        'a: 's,
    {
        match self.kept.extras() {
            Extras::Found => self.of_as::<{ Extras::Found as u8 }>(face, scratch),
            Extras::Deep => self.of_as::<{ Extras::Deep as u8 }>(face, scratch),
            Extras::All => self.of_as::<{ Extras::All as u8 }>(face, scratch),
        }
    }

    /// [`Verts::of`] where `KEEP` is what is kept (an [`Extras`] as `u8`, of
    /// [`KeptRef::extras`]), known where the face loop is compiled (one
    /// loop for each: a loop over kept vertices carries no trace of
    /// finding them again).
    #[inline(always)]
    pub(super) fn of_as<'s, const KEEP: u8>(
        &self,
        face: [u32; 3],
        scratch: &'s mut [Deep; 3],
    ) -> [V<'s>; 3]
    where
        'a: 's,
    {
        // Written out, not `map`ped: the face loop is large enough that
        // `array::map` is not always inlined into it.
        if KEEP == Extras::Found as u8 {
            self.lazy.deep3(face, scratch);
            let scratch: &'s [Deep; 3] = scratch;
            let v = |k: usize| V {
                at: self.core.get(face[k]),
                deep: &scratch[k],
                rest: &Rest::NAN,
            };
            return [v(0), v(1), v(2)];
        }
        let v = |i: u32| V {
            at: self.core.get(i),
            deep: &self.kept.deep[i as usize],
            rest: if KEEP == Extras::All as u8 {
                &self.kept.rest[i as usize]
            } else {
                &Rest::NAN
            },
        };
        [v(face[0]), v(face[1]), v(face[2])]
    }

    /// The same, each buffer `KEEP` reads cut to the vertices' count (as
    /// it is, or the vertex stage is wrong: then this panics), once a run:
    /// an index that passes the face loop's check on [`Verts::core`] then
    /// needs none on the others.
    #[inline(always)]
    pub(super) fn trimmed<const KEEP: u8>(self) -> Verts<'a> {
        let n = self.core.keys.len();
        let mut v = self;
        v.core = self.core.trimmed();
        if KEEP != Extras::Found as u8 {
            v.kept.deep = &self.kept.deep[..n];
        }
        if KEEP == Extras::All as u8 {
            v.kept.rest = &self.kept.rest[..n];
        }
        v
    }

    /// Whether the corners' [`Deep`] is found at set-up (lit there, for
    /// the counts).
    #[inline(always)]
    pub(super) fn lazy(&self) -> bool {
        self.kept.deep.is_empty()
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

    /// Counts the lights of a face's corners found at set-up ([`Lazy`]).
    #[inline(always)]
    pub(super) fn count_lazy(&mut self, stage: &Stage<'_>, verts: &Verts<'_>) {
        if verts.lazy() && stage.plan.shading == Shading::Smooth {
            self.stats.lighting_evaluations += 3;
        }
    }

    /// Transforms `positions` (with `normals`), appending them to
    /// `self.verts`, and their extras to `self.kept` as `keep` says, or
    /// all of them where a vertex is off the common path all the same
    /// (outside a clip plane, or taking the f64 path: its faces take the
    /// clip path, which reads them); then the stage runs again, keeping
    /// them (rare: all are kept wherever clip tests run).
    pub(super) fn vertex_stage(
        &mut self,
        stage: &Stage<'_>,
        t: &Transforms,
        (positions, normals): (&[Vec3], &[Vec3]),
        clip_tests: bool,
        keep: Extras,
    ) {
        let start = (self.verts.len(), self.kept.marks());
        let mut done = vertex_lanes::vertices(
            stage,
            t,
            (positions, normals),
            clip_tests,
            self.verts,
            (self.kept, keep),
        );
        if keep != Extras::All && done.off_path > 0 {
            self.verts.truncate(start.0);
            self.kept.deep.truncate(start.1[0]);
            done = vertex_lanes::vertices(
                stage,
                t,
                (positions, normals),
                clip_tests,
                self.verts,
                (self.kept, Extras::All),
            );
        }
        debug_assert!({
            let n = self.verts.len() - start.0;
            let kept = self.kept.marks();
            (0..2).all(|k| kept[k] == start.1[k] || kept[k] - start.1[k] == n)
        });
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

/// A vertex's unit normal in the turned world (smooth shading: zero
/// otherwise), world position (flat shading and falling-off lights: zero
/// otherwise) and the light reaching it (smooth shading: zero otherwise).
#[inline(always)]
fn lit(stage: &Stage<'_>, t: &Transforms, p: Vec3, n: Vec3) -> (Vec3, Vec3, Vec3) {
    let smooth = stage.plan.shading == Shading::Smooth;
    // World positions serve flat shading and point and spot lights (the
    // clip path finds its own from the model).
    let falloff = stage.plan[Effect::Falloff].run;
    let flat = stage.plan.shading == Shading::Flat;
    // Only smooth shading reads vertex normals.
    let normal = if smooth {
        transform::direction(t.normal * n)
    } else {
        Vec3::ZERO
    };
    let world = if flat || falloff {
        t.model.transform_point3(p)
    } else {
        Vec3::ZERO
    };
    let light = if !smooth {
        Vec3::ZERO
    } else if falloff {
        Vec3::from(stage.lights.lambert_at(normal, world))
    } else {
        stage.lights.lambert(normal)
    };
    (normal, world, light)
}

/// `1/w` and depth of a clip position.
#[inline(always)]
fn depth(clip: glam::Vec4) -> (f32, f32) {
    let inv_w = 1.0 / clip.w;
    (inv_w, clip.z * inv_w)
}

/// The [`Deep`] of a vertex inside every plane, as [`vertex`] finds it:
/// for a mesh whose vertex stage keeps none ([`Lazy`]).
#[inline(always)]
pub(super) fn deep(stage: &Stage<'_>, t: &Transforms, p: Vec3, n: Vec3) -> Deep {
    let (inv_w, z) = depth(t.mvp * p.extend(1.0));
    Deep {
        light: lit(stage, t, p, n).2,
        z,
        inv_w,
    }
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
    let clip = t.mvp * p.extend(1.0);
    // Inside bounds need no test: every plane's code is 0.
    let code = if !clip.is_finite() {
        F64_PATH
    } else if clip_tests {
        u16::from(stage.clipper.outcode(clip))
    } else {
        0
    };
    let (normal, world, light) = lit(stage, t, p, n);
    let mut more = More {
        deep: Deep {
            light,
            ..Deep::default()
        },
        rest: Rest {
            world,
            normal,
            xy: [0.0; 2],
        },
    };
    let mut v = Vert {
        code,
        ..Vert::default()
    };
    if code == 0 {
        let (inv_w, z) = depth(clip);
        more.deep.inv_w = inv_w;
        more.deep.z = z;
        more.rest.xy = stage.viewport.apply(clip.x * inv_w, clip.y * inv_w);
        match FixedPoint::snap(more.rest.xy) {
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
    if v.code != 0 {
        v.key = CentreKey::NEVER_EMPTY;
    }
    (v, more)
}
