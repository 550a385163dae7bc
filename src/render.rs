//! The pipeline, end to end: scene → transform → clip → raster → fill →
//! framebuffer → blit, into a [`Frame`].
//!
//! A [`Renderer`] owns the framebuffer, the frame and a per-vertex scratch
//! buffer and reuses them, so rendering frame after frame allocates nothing
//! once the sizes are stable. [`render`] is the one-call form for tests and
//! tools.
//!
//! **Vertex stage.** Each mesh vertex is transformed once per frame (not
//! once per face that uses it): clip-space position, world position and
//! normal, its clip outcode, and, when it is inside every clip plane, its
//! screen position, depth and `1/w`. Lighting ([`crate::shade`]) is
//! evaluated per vertex for smooth shading, per face for flat. Vertices go
//! through it four at a time in SIMD lanes where all four are the common
//! case (`render/vertices.rs`), with the same arithmetic per lane as one at
//! a time, so the same bits.
//!
//! **Triangles.** A triangle whose three vertices are inside every clip
//! plane goes straight to the rasterizer; one that is not is clipped in
//! homogeneous space first ([`crate::clip`]). Culling is decided on the
//! snapped screen-space winding, exactly. Where the plan says so
//! ([`Plan::lean`]), untextured triangles inside every plane take a lean
//! path: no clip-path arguments are gathered, the signed area (culled,
//! no area) is found first and handed on, a bounding box of at most
//! eight samples is tested sample by sample at set-up
//! (`raster::SmallSetup`), and a triangle that covers no sample is
//! neither lit nor filled, nor are its colours read. The trade-off: a
//! second code path beside the general one, kept equal to it by tests of
//! the set-up (`raster`), of the planned pipeline against the full one and
//! of one band against several (`tests/plan.rs`).
//!
//! **Fragments** are the fill stage's ([`crate::fill`]): depth in screen
//! space, tested per sample (larger is nearer; of equal depths the first
//! drawn wins), colours in linear light ([`crate::color`]) interpolated
//! through `1/w`, written only where the depth test lets them. A camera
//! that frames a model is placed for the view's aspect first
//! ([`crate::scene::Camera::resolved`]).
//!
//! **Textures.** A triangle whose material has a texture (as the plan says:
//! [`Plan::texture`]) multiplies its lit colour by the texture at each
//! sample. Its texture coordinates over `w`, and `1/w`, are planes over the
//! screen, set up once per triangle; at a sample their quotient is the
//! perspective-correct coordinate and the quotient rule gives its exact
//! steps to the next sample along x and y, from which the sampler picks
//! its mipmap level ([`crate::texture`]). Clipping carries the coordinates
//! along cut edges like colours.
//!
//! **Bands.** Where the plan says so ([`Plan::bands`]: frames of 600×180
//! cells or more, with the `parallel` feature), the frame is drawn in bands
//! of whole cell rows, one thread each (rayon). The vertex stage runs once,
//! on the calling thread; then each band clears its own framebuffer of its
//! rows, draws every triangle with its box clamped to them, copies them into
//! the renderer's framebuffer and blits them into its rows of the frame. A
//! sample sees the same triangles in the same order as with one thread, and
//! the fixed-point edge values are exact integers from any starting row, so
//! the frame is the same bit for bit. The costs: each band sets up every
//! triangle that reaches it (a triangle across two bands is set up, and may
//! be lit, twice), the copy, and a second framebuffer's memory, which is
//! why small frames stay on one thread ([`crate::PARALLEL_CELLS`]; what
//! bands save is in docs/figures.md and docs/planner.md).

mod explain;
mod vertices;

use std::time::{Duration, Instant};

use glam::{DMat4, Mat3, Mat4, Vec2, Vec3, Vec3A};

use crate::blit;
use crate::clip::{ClipVertex, Clipped, Clipper, Polygon, Snapped};
use crate::color::{Lin, Rgb};
use crate::fill::{self, Attributes, ScreenTriangle, UvPlanes};
use crate::fixed::FixedPoint;
use crate::frame::{Cell, Frame, Known};
use crate::framebuffer::Framebuffer;
use crate::options::{Aa, RenderOptions};
use crate::plan::Plan;
use crate::raster::{
    CentreKey, Coverage, FloatSetup, Precision, RasterStats, Rejected, Setup, SmallSetup, Traversal,
};
use crate::scene::{Camera, Cull, Mesh, Projection, Scene};
use crate::shade::{Lights, Shading};
use crate::texture::{Sampler, Texture};
use crate::transform::{self, Band, Grid, Rect};

/// What one frame cost.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameStats {
    /// Triangles handed to the pipeline.
    pub triangles_in: u64,
    /// Vertices transformed.
    pub vertices: u64,
    /// Triangles the clip stage cut.
    pub clipped: u64,
    /// Triangles the clip stage removed entirely (outside, or not finite).
    pub clip_rejected: u64,
    /// Lambert evaluations (per vertex or per face).
    pub lighting_evaluations: u64,
    /// Per-sample depth comparisons.
    pub depth_tests: u64,
    /// Samples written with an interpolated colour (not a flat write): a
    /// sample the depth test hides is not coloured, so not counted.
    pub interpolated_samples: u64,
    /// Samples written with a texel (read only for those).
    pub textured_samples: u64,
    /// Of those, samples interpolated through `1/w`.
    pub perspective_samples: u64,
    /// Vertices tested against the clip planes.
    pub clip_tests: u64,
    /// Triangles dropped for a NaN or infinite normal.
    pub dropped_non_finite_normals: u64,
    /// What the rasterizer did.
    pub raster: RasterStats,
}

impl FrameStats {
    /// Adds one band's counts (see [`crate::Plan::bands`]) to a frame
    /// drawn in bands. Every band sees every triangle, so the triangle
    /// counts are the first band's; samples belong to one band each, so
    /// their counts are the sums, and equal one thread's. Lighting per face
    /// is each band's own work, summed: a triangle may be lit by two bands,
    /// or by none where each band's part of its box is small enough to be
    /// found empty before lighting (one thread tests only small boxes).
    fn add_band(&mut self, band: &FrameStats, first: bool) {
        if first {
            self.triangles_in += band.triangles_in;
            self.clipped += band.clipped;
            self.clip_rejected += band.clip_rejected;
            self.dropped_non_finite_normals += band.dropped_non_finite_normals;
            // The loose triangles' vertices, transformed by every band.
            self.vertices += band.vertices;
            self.clip_tests += band.clip_tests;
            let r = &band.raster;
            self.raster.triangles_drawn += r.triangles_drawn;
            self.raster.dropped_non_finite += r.dropped_non_finite;
            self.raster.dropped_out_of_range += r.dropped_out_of_range;
            self.raster.dropped_degenerate += r.dropped_degenerate;
            self.raster.culled += r.culled;
        }
        self.lighting_evaluations += band.lighting_evaluations;
        self.depth_tests += band.depth_tests;
        self.interpolated_samples += band.interpolated_samples;
        self.textured_samples += band.textured_samples;
        self.perspective_samples += band.perspective_samples;
        self.raster.samples_tested += band.raster.samples_tested;
        self.raster.samples_covered += band.raster.samples_covered;
    }
}

/// Where one frame's time went (wall clock; kept apart from
/// [`FrameStats`], which is deterministic).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameTimes {
    /// Planning.
    pub plan: Duration,
    /// Transforms, clip tests and per-vertex lighting.
    pub vertices: Duration,
    /// Setup, clipping, per-face lighting, traversal, depth tests,
    /// interpolation and writes; for a frame drawn in bands, everything
    /// the bands do, their blits included.
    pub triangles: Duration,
    /// Turning samples into cells (zero for a frame drawn in bands, whose
    /// bands blit their own rows).
    pub blit: Duration,
}

/// One group's matrices, computed once per frame: model to clip space (in
/// f32 for the vertex stage, and the same matrix in f64 for the clip path,
/// where coordinates up to f32's largest must neither overflow nor cancel),
/// model to world, and the normals' (the inverse transpose).
#[derive(Clone, Copy, Debug)]
struct Transforms {
    mvp: Mat4,
    mvp64: DMat4,
    model: Mat4,
    normal: Mat3,
}

impl Transforms {
    fn new(vp: Mat4, model: Mat4) -> Transforms {
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
struct Vert {
    /// Position in the turned world, where lights live (flat shading only:
    /// zero otherwise).
    world: Vec3,
    /// Unit normal in the turned world (smooth shading only: zero
    /// otherwise).
    normal: Vec3,
    /// The light reaching the front of the vertex (smooth shading only).
    light: Vec3,
    /// Clip outcode, with [`F64_PATH`] and [`BAD_NORMAL`]: 0 when inside
    /// every plane with a finite normal (then the fields below are valid).
    code: u16,
    xy: [f32; 2],
    /// `xy` snapped, once per vertex rather than once per triangle.
    fixed: FixedPoint,
    /// Where `fixed` lies among sample centres, for the face loop's first
    /// test.
    key: CentreKey,
    z: f32,
    inv_w: f32,
}

/// An outcode bit of no clip plane: the vertex's f32 clip position is not
/// finite (coordinates near f32's largest overflow in the product) or its
/// screen position could not be snapped; it takes the clip path, which
/// works in f64. Never a reason to reject a triangle outright.
const F64_PATH: u16 = 1 << 7;
/// The outcode bits of the clip planes.
const PLANES: u16 = F64_PATH - 1;
/// A bit of no clip plane: the vertex's normal (as given) is NaN or
/// infinite, and its triangles are dropped. In the code, so that one test
/// tells a triangle that takes the common path.
const BAD_NORMAL: u16 = 1 << 8;

/// Where a triangle's model-space vertices are, and the matrix taking them
/// to clip space: read only if it must be clipped.
#[derive(Clone, Copy)]
struct Model<'a> {
    positions: &'a [Vec3],
    face: [u32; 3],
    mvp: &'a DMat4,
    /// Model to the turned world, where facing is told.
    world: &'a Mat4,
}

/// A triangle's texture, how to read it, and its vertices' coordinates.
#[derive(Clone, Copy)]
struct Tex<'a> {
    texture: &'a Texture,
    sampler: Sampler,
    uv: [Vec2; 3],
}

/// One mesh's faces as the triangle stage needs them.
struct Faces<'a> {
    mesh: &'a Mesh,
    transforms: &'a Transforms,
    cull: Cull,
}

/// Per-frame constants of the vertex and triangle stages.
#[derive(Clone, Copy)]
struct Stage<'a> {
    /// Accumulate exact area coverage instead of sampling.
    exact: bool,
    clipper: Clipper,
    viewport: transform::Viewport,
    lights: Lights,
    traversal: Traversal,
    precision: Precision,
    /// What the stages do: depth-test or not, interpolate (through 1/w) or
    /// not, which shading, which groups are clip-tested, the full pipeline
    /// (light before culling, interpolate one-colour triangles).
    plan: &'a Plan,
    /// Where the viewer is, to tell which side of a face is seen: a point
    /// (perspective) or a direction towards the viewer (parallel views).
    eye: Eye,
}

#[derive(Clone, Copy)]
enum Eye {
    At(Vec3),
    Towards(Vec3),
}

impl Eye {
    fn to_eye(self, p: Vec3) -> Vec3 {
        match self {
            Eye::At(e) => e - p,
            Eye::Towards(d) => d,
        }
    }
}

/// A reusable renderer.
#[derive(Debug)]
pub struct Renderer {
    fb: Framebuffer,
    frame: Frame,
    verts: Vec<Vert>,
    poly: Polygon,
    stats: FrameStats,
    plan: Option<Plan>,
    times: FrameTimes,
    /// Anti-aliasing's per-sample sums: red, green, blue, weight.
    acc: Vec<[f32; 4]>,
    /// The last frame's anti-aliasing.
    aa: Aa,
    /// The bands of the last frame drawn in parallel, each a renderer of
    /// its own with a framebuffer of its rows (empty until one is).
    bands: Vec<Renderer>,
    /// The last camera resolved, the aspect it was resolved for, and the
    /// result ([`Camera::resolved`]).
    camera: Option<(Camera, u32, Camera)>,
    /// Where each mesh's vertices are in `verts`, and its matrices, for a
    /// frame drawn in bands.
    meshes: Vec<(std::ops::Range<usize>, Transforms)>,
    /// What a band's blit knows of its cells (a frame drawn in bands).
    known: Known,
}

impl Default for Renderer {
    fn default() -> Self {
        Renderer::new()
    }
}

impl Renderer {
    /// A renderer with no memory yet: the first frame allocates it.
    pub fn new() -> Renderer {
        Renderer {
            fb: Framebuffer::new(Grid::new(0, 0)),
            frame: Frame::default(),
            verts: Vec::new(),
            poly: Polygon::default(),
            stats: FrameStats::default(),
            plan: None,
            times: FrameTimes::default(),
            acc: Vec::new(),
            aa: Aa::None,
            bands: Vec::new(),
            camera: None,
            meshes: Vec::new(),
            known: Known::default(),
        }
    }

    /// Renders `scene` and returns the frame, kept in the renderer.
    pub fn render(&mut self, scene: &Scene, opts: &RenderOptions) -> &Frame {
        let mut frame = std::mem::take(&mut self.frame);
        self.render_into(scene, opts, &mut frame);
        self.frame = frame;
        &self.frame
    }

    /// Renders `scene` into the caller's `frame`, resizing it to the
    /// options' `cols × rows`. The renderer keeps only its working memory
    /// (samples, depths, vertices, the plan) between calls: once the sizes
    /// are stable, a frame allocates nothing. (A frame drawn in bands hands
    /// its work to rayon, whose queue for jobs from outside its pool takes
    /// a block of 63 slots every 63 frames.)
    ///
    /// ```
    /// use rastty::{Frame, RenderOptions, Renderer, Rgb, Scene};
    ///
    /// let scene = Scene::of_mesh(rastty::scene::Shape::Cube.mesh(Rgb::WHITE));
    /// let opts = RenderOptions { cols: 40, rows: 12, ..Default::default() };
    /// let (mut renderer, mut frame) = (Renderer::new(), Frame::default());
    /// for yaw in [0.0, 10.0, 20.0] {
    ///     let opts = RenderOptions { turn: rastty::glam::Vec3::new(0.0, yaw, 0.0), ..opts };
    ///     renderer.render_into(&scene, &opts, &mut frame);
    /// }
    /// assert_eq!((frame.cols(), frame.rows()), (40, 12));
    /// assert!(frame.cells().iter().any(|c| c.ch != ' '));
    /// ```
    pub fn render_into(&mut self, scene: &Scene, opts: &RenderOptions, frame: &mut Frame) {
        let grid = opts.glyphs.grid(opts.cols, opts.rows);
        frame.set_plain(matches!(
            opts.glyphs,
            blit::GlyphMode::Ascii | blit::GlyphMode::Braille
        ));
        self.stats = FrameStats::default();
        self.times = FrameTimes::default();
        let mut clock = Instant::now();
        let mut lap = move || {
            let now = Instant::now();
            let t = now - clock;
            clock = now;
            t
        };

        let turn = transform::rotation(opts.turn);
        // A camera that frames a model is placed for this view's aspect
        // (a few hundred thousand instructions), once while neither changes.
        let cam = &self.resolved(&scene.camera, opts.aspect());
        let vp = cam.view_projection(opts.aspect());
        let clipper = Clipper::for_projection(grid.width, grid.height, &cam.projection);
        // The plan is taken out of `self` for the frame (the stages borrow
        // it) and put back: replanning reuses its memory.
        let mut plan = self.plan.take();
        let p: &Plan = match &mut plan {
            Some(p) => {
                p.replan(scene, opts, vp, turn, &clipper);
                p
            }
            None => plan.insert(Plan::new(scene, opts, vp, turn, &clipper)),
        };
        let eye = match cam.projection {
            Projection::Perspective { .. } => Eye::At(cam.eye),
            Projection::Orthographic { .. } => Eye::Towards(cam.eye - cam.target),
            Projection::None => Eye::Towards(Vec3::Z),
        };
        let stage = Stage {
            exact: false,
            clipper,
            plan: p,
            viewport: transform::Viewport::new(grid.width as f32, grid.height as f32),
            lights: {
                let lights = Lights::new(if p.lighting.run { &scene.lights } else { &[] });
                match opts.rim {
                    Some(c) if p.rim.run => lights.with_rim(c, cam.eye - cam.target),
                    _ if p.rim.run => lights.with_rim(Rgb::BLACK, cam.eye - cam.target),
                    _ => lights,
                }
            },
            traversal: opts.traversal,
            precision: opts.precision,
            eye,
        };

        self.times.plan += lap();
        self.aa = opts.aa;
        let n = grid.len();
        let mut banded = false;
        match opts.aa {
            Aa::None if p.bands.count > 1 => {
                self.draw_bands(scene, opts, &stage, (vp, turn), frame, &mut lap);
                banded = true;
            }
            Aa::None => {
                self.fb.reset(grid, p.depth.run);
                self.geometry(scene, opts, &stage, vp, turn, &mut lap);
            }
            Aa::X4 | Aa::X16 => {
                // One pass per sub-sample position, the geometry shifted so
                // that sample centres land on it; the passes are averaged.
                self.acc.clear();
                self.acc.resize(n, [0.0; 4]);
                let offsets = opts.aa.offsets();
                for &(ox, oy) in offsets {
                    self.fb.reset(grid, p.depth.run);
                    let shifted = Stage {
                        viewport: transform::Viewport::new(grid.width as f32, grid.height as f32)
                            .shifted(0.5 - ox, 0.5 - oy),
                        ..stage
                    };
                    self.geometry(scene, opts, &shifted, vp, turn, &mut lap);
                    for (a, s) in self.acc.iter_mut().zip(self.fb.samples()) {
                        if let Some(c) = s {
                            let [r, g, b] = c.to_f32();
                            *a = [a[0] + r, a[1] + g, a[2] + b, a[3] + 1.0];
                        }
                    }
                }
                self.resolve(offsets.len() as f32, scene.background);
            }
            Aa::Exact => {
                self.acc.clear();
                self.acc.resize(n, [0.0; 4]);
                self.fb.reset(grid, p.depth.run);
                let exact = Stage {
                    exact: true,
                    ..stage
                };
                self.geometry(scene, opts, &exact, vp, turn, &mut lap);
                self.resolve(1.0, scene.background);
            }
        }
        self.times.triangles += lap();
        // Bands blit their own rows.
        if !banded {
            blit::blit(
                &self.fb,
                opts.glyphs,
                opts.color,
                scene.background,
                opts.split,
                frame,
            );
            self.times.blit += lap();
        }
        self.plan = plan;
    }

    /// `camera` resolved for `aspect`: the last frame's result when both are
    /// the same (bit for bit), otherwise found afresh.
    fn resolved(&mut self, camera: &Camera, aspect: f32) -> Camera {
        match self.camera {
            Some((c, a, resolved)) if c.same_bits(camera) && a == aspect.to_bits() => resolved,
            _ => {
                let resolved = camera.resolved(aspect);
                self.camera = Some((*camera, aspect.to_bits(), resolved));
                resolved
            }
        }
    }

    /// Draws every mesh and loose triangle into the framebuffer (or, for
    /// exact coverage, the accumulator).
    fn geometry(
        &mut self,
        scene: &Scene,
        opts: &RenderOptions,
        stage: &Stage<'_>,
        vp: Mat4,
        turn: Mat4,
        lap: &mut impl FnMut() -> Duration,
    ) {
        let p = stage.plan;
        for (i, mesh) in scene.meshes.iter().enumerate() {
            let transforms = Transforms::new(vp, turn * mesh.model);
            self.verts.clear();
            self.vertex_stage(
                stage,
                &transforms,
                &mesh.positions,
                &mesh.normals,
                p.clip_tests(i),
            );
            self.times.vertices += lap();
            let faces = Faces {
                mesh,
                transforms: &transforms,
                cull: opts.cull.unwrap_or(mesh.cull),
            };
            // Borrowed out of `self` for the loop, and put back.
            let verts = std::mem::take(&mut self.verts);
            self.faces(stage, &faces, &verts);
            self.verts = verts;
            self.times.triangles += lap();
        }
        self.loose(scene, opts, stage, vp, turn);
    }

    /// Draws the frame in bands of whole cell rows, each on a thread of its
    /// own (with the `parallel` feature): every vertex is transformed once,
    /// here; then each band clears its rows, draws every triangle that
    /// reaches them, copies them into this renderer's framebuffer and blits
    /// them into their rows of `frame`. Band k holds cell rows
    /// `[k·m, (k+1)·m)` from the bottom, `m` rows a band (the top band may
    /// hold fewer).
    fn draw_bands(
        &mut self,
        scene: &Scene,
        opts: &RenderOptions,
        stage: &Stage<'_>,
        (vp, turn): (Mat4, Mat4),
        frame: &mut Frame,
        lap: &mut impl FnMut() -> Duration,
    ) {
        let p = stage.plan;
        let depth = p.depth.run;
        let grid = opts.glyphs.grid(opts.cols, opts.rows);
        let (cell_w, cell_h) = opts.glyphs.cell_size();
        let (cols, rows) = (grid.width / cell_w, grid.height / cell_h);
        let per = rows.div_ceil(p.bands.count as u32).max(1);
        let n = rows.div_ceil(per) as usize;
        // The vertex stage, every mesh's vertices one after another.
        self.verts.clear();
        self.meshes.clear();
        for (i, mesh) in scene.meshes.iter().enumerate() {
            let transforms = Transforms::new(vp, turn * mesh.model);
            let start = self.verts.len();
            let (positions, normals) = (&mesh.positions, &mesh.normals);
            self.vertex_stage(stage, &transforms, positions, normals, p.clip_tests(i));
            self.meshes.push((start..self.verts.len(), transforms));
        }
        self.times.vertices += lap();
        let mut bands = std::mem::take(&mut self.bands);
        bands.resize_with(n, Renderer::new);
        // Cleared where the last frame drew; each band copies in only
        // where it drew.
        self.fb.reset(grid, depth);
        frame.resize(cols as u16, rows as u16);
        let (verts, meshes) = (&self.verts, &self.meshes);
        let job = |k: usize,
                   band: &mut Renderer,
                   samples: &mut [Option<Lin>],
                   depths: &mut [f32],
                   cells: &mut [Cell]| {
            band.stats = FrameStats::default();
            let y0 = k as u32 * per * cell_h;
            let y1 = (y0 + per * cell_h).min(grid.height);
            band.fb.reset_band(grid, Band { y0, y1 }, depth);
            for (i, mesh) in scene.meshes.iter().enumerate() {
                let (range, transforms) = &meshes[i];
                let faces = Faces {
                    mesh,
                    transforms,
                    cull: opts.cull.unwrap_or(mesh.cull),
                };
                band.faces(stage, &faces, &verts[range.clone()]);
            }
            band.loose(scene, opts, stage, vp, turn);
            band.fb.copy_drawn_into(samples, depth.then_some(depths));
            band.known = blit::blit_band(
                &band.fb,
                opts.glyphs,
                opts.color,
                scene.background,
                opts.split,
                cells,
            );
        };
        let band_samples = (per * cell_h * grid.width) as usize;
        let band_cells = (per * cols) as usize;
        let (samples, depths) = self.fb.parts_mut();
        let cells = frame.cells_mut();
        // Cells are stored from the top: the bottom band's are the last.
        // The same zip twice, rayon's and the standard library's: their
        // iterators have the same shape but not the same types.
        #[cfg(feature = "parallel")]
        {
            use rayon::prelude::*;
            bands
                .par_iter_mut()
                .zip(samples.par_chunks_mut(band_samples))
                .zip(depths.par_chunks_mut(band_samples))
                .zip(cells.par_rchunks_mut(band_cells))
                .enumerate()
                .for_each(|(k, (((band, s), d), c))| job(k, band, s, d, c));
        }
        #[cfg(not(feature = "parallel"))]
        bands
            .iter_mut()
            .zip(samples.chunks_mut(band_samples))
            .zip(depths.chunks_mut(band_samples))
            .zip(cells.rchunks_mut(band_cells))
            .enumerate()
            .for_each(|(k, (((band, s), d), c))| job(k, band, s, d, c));
        let (mut drawn, mut known) = (
            Rect::EMPTY,
            bands.first().map_or(Known::default(), |b| b.known),
        );
        for (k, band) in bands.iter().enumerate() {
            self.stats.add_band(&band.stats, k == 0);
            drawn = drawn.union(band.fb.drawn());
            known.rect = known.rect.union(band.known.rect);
        }
        self.fb.touch(drawn);
        frame.set_known(known);
        self.bands = bands;
    }

    /// Draws one mesh's faces, whose vertices went through the vertex stage
    /// into `verts`.
    fn faces(&mut self, stage: &Stage<'_>, f: &Faces<'_>, verts: &[Vert]) {
        let p = stage.plan;
        let mesh = f.mesh;
        for run in mesh.runs(Lin::from_srgb(mesh.color)) {
            let texture = p.texture(run.texture);
            // The plan's path; a run with a texture takes the general one,
            // which on the lean path skips (and counts) a triangle that
            // covers no sample once it is set up.
            let lean = p.lean.run && texture.is_none();
            // Converted to lanes once a run, not once a face.
            let run_color = run.color.to_lanes();
            // Every face is handed to the pipeline: counted once a run.
            self.stats.triangles_in += run.faces.len() as u64;
            for face in &mesh.faces[run.faces] {
                let v = face.map(|i| &verts[i as usize]);
                let inside = v[0].code | v[1].code | v[2].code == 0;
                let base = || match &mesh.colors {
                    Some(c) => face.map(|i| c[i as usize].to_lanes()),
                    None => [run_color; 3],
                };
                if inside && lean {
                    // Culled or without area: rejected before anything
                    // else, as its set-up would reject it (snapped, so in
                    // range).
                    let area2 = match Setup::signed_area2_in_range(&v.map(|v| v.fixed), f.cull) {
                        Ok(a) => a,
                        Err(r) => {
                            self.stats.raster.count_rejected(r);
                            continue;
                        }
                    };
                    self.stats.raster.triangles_drawn += 1;
                    // No sample centre in its box, known from its vertices'
                    // keys: nothing more to count. The colours are read
                    // only if it covers a sample.
                    if !CentreKey::box_is_empty(v.map(|v| v.key)) {
                        self.inside_triangle(stage, v, base, area2);
                    }
                    continue;
                }
                let base = base();
                let tex = texture.map(|(texture, sampler)| Tex {
                    texture,
                    sampler,
                    uv: match &mesh.uvs {
                        Some(uv) => face.map(|i| uv[i as usize]),
                        None => [Vec2::ZERO; 3],
                    },
                });
                let model = Model {
                    positions: &mesh.positions,
                    face: *face,
                    mvp: &f.transforms.mvp64,
                    world: &f.transforms.model,
                };
                self.triangle(stage, v, base, f.cull, model, tex);
            }
        }
    }

    /// Draws the loose triangles, each through the vertex stage on its own.
    fn loose(
        &mut self,
        scene: &Scene,
        opts: &RenderOptions,
        stage: &Stage<'_>,
        vp: Mat4,
        turn: Mat4,
    ) {
        let p = stage.plan;
        let cull = opts.cull.unwrap_or(Cull::None);
        let loose = Transforms::new(vp, turn);
        let loose_tests = p.clip_tests(scene.meshes.len());
        self.stats.triangles_in += scene.triangles.len() as u64;
        for tri in &scene.triangles {
            let [a, b, c] = tri.vertices;
            let normal = transform::face_normal(a, b, c);
            self.verts.clear();
            self.vertex_stage(stage, &loose, &tri.vertices, &[normal; 3], loose_tests);
            let verts = std::mem::take(&mut self.verts);
            self.triangle(
                stage,
                [&verts[0], &verts[1], &verts[2]],
                tri.color
                    .at_vertices()
                    .map(|c| Lin::from_srgb(c).to_lanes()),
                cull,
                Model {
                    positions: &tri.vertices,
                    face: [0, 1, 2],
                    mvp: &loose.mvp64,
                    world: &loose.model,
                },
                p.texture(None).map(|(texture, sampler)| Tex {
                    texture,
                    sampler,
                    uv: [Vec2::ZERO; 3],
                }),
            );
            self.verts = verts;
        }
    }

    /// Turns the accumulated colour sums and weights into samples: weight
    /// over `total` is the coverage, which blends the mean colour with the
    /// background (where there is none, a sample at least half covered
    /// shows its colour, the rest the terminal's).
    fn resolve(&mut self, total: f32, background: Option<Rgb>) {
        let grid = self.fb.grid();
        let bg = background.map(|c| Vec3::from(Lin::from_srgb(c).to_f32()));
        for (i, a) in self.acc.iter().enumerate() {
            let (x, y) = (i as u32 % grid.width, i as u32 / grid.width);
            let weight = a[3];
            if weight <= 0.0 {
                continue;
            }
            let coverage = (weight / total).min(1.0);
            let mean = Vec3::new(a[0], a[1], a[2]) / weight;
            let c = match bg {
                Some(bg) => mean * coverage + bg * (1.0 - coverage),
                None if coverage >= 0.5 => mean,
                None => continue,
            };
            self.fb.set(x, y, Lin::from_f32(c.to_array()));
        }
    }

    /// Transforms `positions` (with `normals`), appending them to
    /// `self.verts`.
    fn vertex_stage(
        &mut self,
        stage: &Stage<'_>,
        t: &Transforms,
        positions: &[Vec3],
        normals: &[Vec3],
        clip_tests: bool,
    ) {
        self.count_vertices(stage, positions.len(), clip_tests);
        vertices::vertices(stage, t, positions, normals, clip_tests, &mut self.verts);
    }

    /// Counts what the vertex stage does for `n` vertices.
    fn count_vertices(&mut self, stage: &Stage<'_>, n: usize, clip_tests: bool) {
        let n = n as u64;
        self.stats.vertices += n;
        if stage.plan.shading == Shading::Smooth {
            self.stats.lighting_evaluations += n;
        }
        if clip_tests {
            self.stats.clip_tests += n;
        }
    }

    /// Sets up, lights, clips if it must, and rasterizes one triangle;
    /// `model` is its vertices' model-space positions and the matrix taking
    /// them to clip space, for the clip path. The caller counts it in
    /// [`FrameStats::triangles_in`].
    fn triangle(
        &mut self,
        stage: &Stage<'_>,
        v: [&Vert; 3],
        base: [Vec3A; 3],
        cull: Cull,
        model: Model<'_>,
        tex: Option<Tex<'_>>,
    ) {
        let (texture, uv) = match tex {
            Some(t) => (Some((t.texture, t.sampler)), t.uv),
            None => (None, [Vec2::ZERO; 3]),
        };
        if (v[0].code | v[1].code | v[2].code) & BAD_NORMAL != 0 {
            self.stats.dropped_non_finite_normals += 1;
            return;
        }
        if v[0].code & v[1].code & v[2].code & PLANES != 0 {
            self.stats.clip_rejected += 1;
            return;
        }
        if v[0].code | v[1].code | v[2].code == 0 {
            // Inside every clip plane: set up first, so that culled
            // triangles and those covering no sample are never lit (the
            // full pipeline lights them all, first).
            let early = stage
                .plan
                .full
                .then(|| self.shade(stage, v, base, !front_facing(v)));
            let fixed = v.map(|v| v.fixed);
            let xy = v.map(|v| v.xy.map(f64::from));
            let screen = |color| ScreenTriangle {
                xy,
                z: v.map(|v| v.z),
                inv_w: v.map(|v| v.inv_w),
                color,
                uv,
            };
            let grid = self.fb.grid();
            match stage.precision {
                Precision::Fixed => {
                    let setup = Setup::from_fixed_in(fixed, grid, self.fb.band(), cull);
                    if let Some(s) = self.setup(&setup, stage.exact) {
                        // On the lean path (textured and loose triangles), a small
                        // triangle between sample centres is not lit or
                        // filled (the full pipeline fills it anyway: the
                        // same nothing). Counted as its walk would count it.
                        if stage.plan.lean.run && !s.covers_any() {
                            self.stats.raster.samples_tested += s.bbox_samples();
                            return;
                        }
                        let c = early.unwrap_or_else(|| self.shade(stage, v, base, !s.ccw));
                        self.fill(s, &screen(c), stage, texture);
                    }
                }
                Precision::F64 => {
                    let setup = FloatSetup::<f64>::new(xy, grid, cull);
                    if let Some(s) = self.setup(&setup, stage.exact) {
                        let c = early.unwrap_or_else(|| self.shade(stage, v, base, !s.ccw()));
                        self.fill(s, &screen(c), stage, texture);
                    }
                }
                Precision::F32 => {
                    let setup = FloatSetup::<f32>::new(xy, grid, cull);
                    if let Some(s) = self.setup(&setup, stage.exact) {
                        let c = early.unwrap_or_else(|| self.shade(stage, v, base, !s.ccw()));
                        self.fill(s, &screen(c), stage, texture);
                    }
                }
            }
            return;
        }
        // Clipped: lit before clipping (colours are interpolated along the
        // cut edges), facing told in the world.
        let Model {
            positions,
            face,
            mvp,
            world,
        } = model;
        let w = face.map(|i| world.transform_point3(positions[i as usize]));
        let normal = transform::face_normal(w[0], w[1], w[2]);
        let back = normal.dot(transform::direction(stage.eye.to_eye(w[0]))) < 0.0;
        let color = self.shade(stage, v, base, back);
        let verts = [0, 1, 2].map(|i| ClipVertex {
            pos: positions[face[i] as usize].as_dvec3().extend(1.0),
            color: color[i],
            uv: uv[i],
            snapped: (v[i].code == 0).then_some(Snapped {
                fixed: v[i].fixed,
                xy: v[i].xy,
                z: v[i].z,
                inv_w: v[i].inv_w,
            }),
        });
        let mut poly = self.poly;
        match stage.clipper.clip(&verts, mvp, &stage.viewport, &mut poly) {
            Clipped::Rejected => self.stats.clip_rejected += 1,
            Clipped::Clipped | Clipped::Inside => {
                self.stats.clipped += 1;
                for tri in poly.triangles() {
                    let screen = ScreenTriangle {
                        xy: tri.map(|v| v.xy),
                        z: tri.map(|v| v.z),
                        inv_w: tri.map(|v| v.inv_w),
                        color: tri.map(|v| v.color),
                        uv: tri.map(|v| v.uv),
                    };
                    let grid = self.fb.grid();
                    match stage.precision {
                        Precision::Fixed => {
                            let setup = Setup::from_fixed_in(
                                tri.map(|v| v.fixed),
                                grid,
                                self.fb.band(),
                                cull,
                            );
                            if let Some(s) = self.setup(&setup, stage.exact) {
                                self.fill(s, &screen, stage, texture);
                            }
                        }
                        Precision::F64 => {
                            let setup = FloatSetup::<f64>::new(screen.xy, grid, cull);
                            if let Some(s) = self.setup(&setup, stage.exact) {
                                self.fill(s, &screen, stage, texture);
                            }
                        }
                        Precision::F32 => {
                            let setup = FloatSetup::<f32>::new(screen.xy, grid, cull);
                            if let Some(s) = self.setup(&setup, stage.exact) {
                                self.fill(s, &screen, stage, texture);
                            }
                        }
                    }
                }
            }
        }
        self.poly = poly;
    }

    /// What a triangle inside every clip plane without a texture takes on
    /// the plan's lean path ([`Plan::lean`]), once it is counted as drawn
    /// with signed area `area2`: set it up, and light and fill it only if
    /// it covers a sample.
    #[inline(always)]
    fn inside_triangle(
        &mut self,
        stage: &Stage<'_>,
        v: [&Vert; 3],
        base: impl Fn() -> [Vec3A; 3],
        area2: i64,
    ) {
        let (grid, band) = (self.fb.grid(), self.fb.band());
        let fixed = v.map(|v| v.fixed);
        match SmallSetup::new_snapped(fixed, area2, grid, band) {
            Some(s) => self.inside_fill(stage, v, &base, &s),
            None => {
                let s = Setup::from_snapped(fixed, area2, grid, band);
                self.inside_fill(stage, v, &base, &s);
            }
        }
    }

    /// Lights and fills a set-up triangle of [`Renderer::inside_triangle`]
    /// if it covers a sample; counts its box's samples as tested if not.
    #[inline(always)]
    fn inside_fill<C: Coverage>(
        &mut self,
        stage: &Stage<'_>,
        v: [&Vert; 3],
        base: &impl Fn() -> [Vec3A; 3],
        s: &C,
    ) {
        if !s.covers_any() {
            self.stats.raster.samples_tested += s.bbox_samples();
            return;
        }
        let color = self.shade(stage, v, base(), !s.ccw());
        let a = Attributes::new(
            s.order(),
            s.inv_area(),
            [v.map(|v| v.z), v.map(|v| v.inv_w)],
            color,
            stage.plan.perspective.run,
        );
        let flat = !stage.plan.interpolates(&color);
        self.fill_colour(s, &a, flat, stage);
    }

    /// The triangle's colour at each vertex. `back`: seen from behind, so
    /// lit on its other side (two-sided lighting).
    /// Colours are linear light in [0, 65535], rounded to whole steps, so
    /// that interpolating three equal colours gives back exactly that
    /// colour (the full pipeline's interpolation of a one-colour triangle
    /// then matches the planned pipeline's plain write, bit for bit).
    #[inline(always)]
    fn shade(
        &mut self,
        stage: &Stage<'_>,
        v: [&Vert; 3],
        base: [Vec3A; 3],
        back: bool,
    ) -> [Vec3; 3] {
        let round = |c: Vec3A| Vec3::from(Lin::round_lanes(c));
        let c = self.light(stage, v, base, back);
        [round(c[0]), round(c[1]), round(c[2])]
    }

    /// [`Renderer::shade`] before rounding, in SIMD lanes (the same
    /// operations per channel as three f32s).
    #[inline(always)]
    fn light(
        &mut self,
        stage: &Stage<'_>,
        v: [&Vert; 3],
        base: [Vec3A; 3],
        back: bool,
    ) -> [Vec3A; 3] {
        let b = |i: usize| base[i];
        match stage.plan.shading {
            Shading::None => [b(0), b(1), b(2)],
            Shading::Flat => {
                self.stats.lighting_evaluations += 1;
                let side = if back { -1.0 } else { 1.0 };
                let face = transform::face_normal(v[0].world, v[1].world, v[2].world);
                let light = stage.lights.lambert_a(face * side);
                let lit = [b(0) * light, b(1) * light, b(2) * light];
                if !stage.plan.rim.run {
                    return lit;
                }
                let rim = stage.lights.rim_a(face * side);
                lit.map(|c| c + rim)
            }
            Shading::Smooth if back => {
                self.stats.lighting_evaluations += 3;
                let rim = stage.plan.rim.run;
                let l = |i: usize| {
                    let lit = b(i) * stage.lights.lambert_a(-v[i].normal);
                    if rim {
                        lit + stage.lights.rim_a(-v[i].normal)
                    } else {
                        lit
                    }
                };
                [l(0), l(1), l(2)]
            }
            Shading::Smooth if stage.plan.rim.run => {
                // The rim from each corner's normal, here rather than in the
                // vertex stage: a frame without a rim keeps its vertices as
                // small and its vertex loop as short as before.
                let l = |i: usize| b(i) * Vec3A::from(v[i].light) + stage.lights.rim_a(v[i].normal);
                [l(0), l(1), l(2)]
            }
            Shading::Smooth => {
                let l = |i: usize| b(i) * Vec3A::from(v[i].light);
                [l(0), l(1), l(2)]
            }
        }
    }

    /// A set-up screen triangle, counted; `None` when it was rejected or
    /// covers no sample.
    /// Borrowed, not moved: a set-up triangle is a few hundred bytes.
    #[inline(always)]
    fn setup<'s, C: Coverage>(
        &mut self,
        setup: &'s Result<C, Rejected>,
        exact: bool,
    ) -> Option<&'s C> {
        match setup {
            Ok(s) => {
                self.stats.raster.triangles_drawn += 1;
                // Exact coverage counts area, which a triangle between
                // sample centres still has.
                (s.bbox_samples() > 0 || exact).then_some(s)
            }
            Err(r) => {
                self.stats.raster.count_rejected(*r);
                None
            }
        }
    }

    /// Walks a set-up triangle and writes its samples: depth-tested, or
    /// (when the plan skips depth) only where still empty; one colour, or
    /// interpolated, through `1/w` where the plan asks for it; times its
    /// texture, where it has one.
    fn fill<C: Coverage>(
        &mut self,
        setup: &C,
        t: &ScreenTriangle,
        stage: &Stage,
        texture: Option<(&Texture, Sampler)>,
    ) {
        if stage.exact {
            let done = fill::accumulate_exact(&mut self.acc, self.fb.grid(), t, texture);
            self.stats.textured_samples += done.written;
            self.stats.raster.samples_covered += done.covered;
            self.stats.raster.samples_tested += done.tested;
            return;
        }
        let o = setup.order();
        let a = Attributes::new(
            o,
            setup.inv_area(),
            [t.z, t.inv_w],
            t.color,
            stage.plan.perspective.run,
        );
        let flat = !stage.plan.interpolates(&t.color);
        match texture {
            Some((texture, sampler)) => {
                // Texture coordinates are planes over the screen, found
                // from the triangle as given (their order does not matter).
                let planes = UvPlanes::new(t, stage.plan.perspective.run);
                let done = self
                    .sink(stage)
                    .textured(setup, &a, flat, (texture, sampler, &planes));
                self.stats.textured_samples += done.written;
                // Texture coordinates are interpolated, whatever the colour.
                self.count_fill(stage, done);
            }
            None => self.fill_colour(setup, &a, flat, stage),
        }
    }

    /// Where a triangle's samples go, as the plan says to test them.
    #[inline(always)]
    fn sink(&mut self, stage: &Stage) -> fill::Sink<'_> {
        fill::Sink {
            fb: &mut self.fb,
            depth: stage.plan.depth.run,
            traversal: stage.traversal,
        }
    }

    /// [`Renderer::fill`] of a triangle without a texture, counted.
    #[inline(always)]
    fn fill_colour<C: Coverage>(&mut self, setup: &C, a: &Attributes, flat: bool, stage: &Stage) {
        let done = self.sink(stage).colour(setup, a, flat);
        self.count_fill(stage, done);
    }

    /// Counts what one fill did: `covered` samples, each depth-tested where
    /// the plan tests depth, of which `written` were written with an
    /// interpolated colour; `tested` samples tested for coverage.
    #[inline(always)]
    fn count_fill(&mut self, stage: &Stage, done: fill::Filled) {
        let fill::Filled {
            covered,
            written: interpolated,
            tested,
        } = done;
        let stats = &mut self.stats;
        if stage.plan.depth.run {
            stats.depth_tests += covered;
        }
        stats.interpolated_samples += interpolated;
        if stage.plan.perspective.run {
            stats.perspective_samples += interpolated;
        }
        stats.raster.samples_tested += tested;
        stats.raster.samples_covered += covered;
    }

    /// The last frame [`Renderer::render`] drew (not one drawn with
    /// [`Renderer::render_into`]).
    pub fn frame(&self) -> &Frame {
        &self.frame
    }

    /// The last frame, to draw over (a status line, say).
    pub fn frame_mut(&mut self) -> &mut Frame {
        &mut self.frame
    }

    /// The samples of the last frame.
    pub fn framebuffer(&self) -> &Framebuffer {
        &self.fb
    }

    /// How much of each sample's square the last frame covered, in [0, 1],
    /// row by row from the bottom, before it became a colour: 0 or 1
    /// without anti-aliasing, the share of sub-samples hit with `4x` and
    /// `16x`, the summed area (capped at 1) with `exact`. What `rastty
    /// bench` measures the coverage knob by.
    pub fn coverage(&self, out: &mut Vec<f32>) {
        out.clear();
        match self.aa {
            Aa::None => out.extend(
                self.fb
                    .samples()
                    .iter()
                    .map(|s| if s.is_some() { 1.0 } else { 0.0 }),
            ),
            aa => {
                let passes = aa.passes() as f32;
                out.extend(self.acc.iter().map(|a| (a[3] / passes).min(1.0)));
            }
        }
    }

    /// What the last frame cost.
    pub fn stats(&self) -> &FrameStats {
        &self.stats
    }

    /// The plan of the last frame.
    pub fn plan(&self) -> Option<&Plan> {
        self.plan.as_ref()
    }

    /// Where the last frame's time went.
    pub fn times(&self) -> &FrameTimes {
        &self.times
    }
}

/// One vertex through the vertex stage: its clip position and outcode
/// and, inside every plane, its screen position, snapped, depth and `1/w`;
/// its world position (flat shading) or normal and light (smooth).
#[inline(always)]
fn vertex(stage: &Stage<'_>, t: &Transforms, p: Vec3, n: Vec3, clip_tests: bool) -> Vert {
    let smooth = stage.plan.shading == Shading::Smooth;
    // World positions serve flat shading only (the clip path finds its own
    // from the model).
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
        world: if flat {
            t.model.transform_point3(p)
        } else {
            Vec3::ZERO
        },
        normal,
        code,
        ..Vert::default()
    };
    if smooth {
        v.light = stage.lights.lambert(normal);
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

/// Whether the snapped screen triangle is counter-clockwise (the same
/// test `Setup` makes).
fn front_facing(v: [&Vert; 3]) -> bool {
    let [a, b, c] = v.map(|v| v.fixed);
    (b.x.0 - a.x.0) * (c.y.0 - a.y.0) - (b.y.0 - a.y.0) * (c.x.0 - a.x.0) > 0
}

/// Renders one frame of `scene`.
#[must_use]
pub fn render(scene: &Scene, opts: &RenderOptions) -> Frame {
    Renderer::new().render(scene, opts).clone()
}
