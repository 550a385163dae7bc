//! The pipeline, end to end: scene → transform → clip → raster → fill →
//! framebuffer → blit, into a [`Frame`].
//!
//! A [`Renderer`] owns the framebuffer, the frame and a per-vertex scratch
//! buffer and reuses them, so rendering frame after frame allocates nothing
//! once the sizes are stable. [`render`] is the one-call form for tests and
//! tools.
//!
//! The stages, each in a file: the vertex stage (`vertex.rs`, and its
//! lane twin `vertex_lanes.rs`), the triangle stage (`triangle.rs`: clip,
//! cull, set-up, light, then [`crate::fill`]; its out-of-line paths for
//! mapped, masked and blended runs in `mapped.rs`), the edge stage of
//! wireframes (`wire.rs`: edges as lines one sample wide through the same
//! set-up), anti-aliasing (`aa.rs`),
//! bands (`bands.rs`); what a frame cost is `crate::stats`'s. This file holds
//! the renderer and the frame: the plan made (or remade) first, then the
//! stages as it says. Fragments are the fill stage's ([`crate::fill`]):
//! depth in screen space, tested per sample (larger is nearer; of equal
//! depths the first drawn wins), colours in linear light
//! ([`crate::color`]) interpolated through `1/w`, written only where the
//! depth test lets them. A camera that frames a model is placed for the
//! view's aspect first ([`crate::scene::Camera::resolved`]).

mod aa;
mod bands;
mod explain;
mod lean;
mod mapped;
mod surface;
mod triangle;
mod vertex;
mod vertex_lanes;
mod wire;

use surface::Surface;

use crate::plan::Effect;
use crate::stats::{FrameStats, FrameTimes};

use std::sync::Arc;
use std::time::{Duration, Instant};

use glam::{Mat4, Vec3};

use crate::clip::{Clipper, Polygon};
use crate::color::Rgb;
use crate::error::Result;
use crate::fill::Eye;
use crate::frame::Frame;
use crate::framebuffer::{Framebuffer, Target};
use crate::options::{Aa, RenderOptions};
use crate::output::Output;
use crate::pixels::Pixels;
use crate::plan::Plan;
use crate::raster::{Precision, Traversal};
use crate::scene::anim::{Pose, Posed};
use crate::scene::{Camera, Geometry, Projection, Scene};
use crate::shade::Lights;
use crate::transform::{self, Grid};
use mapped::Ids;
use triangle::Faces;
use vertex::{Core, Kept, Transforms, Verts};

/// Per-frame constants of the vertex and triangle stages.
#[derive(Clone, Copy)]
struct Stage<'a> {
    /// Accumulate exact area coverage instead of sampling.
    exact: bool,
    clipper: Clipper,
    viewport: transform::Viewport,
    lights: Lights,
    traversal: Traversal,
    /// Where highlights are found.
    highlights: crate::options::Highlights,
    precision: Precision,
    /// What the stages do: depth-test or not, interpolate (through 1/w) or
    /// not, which shading, which groups are clip-tested, the full pipeline
    /// (light before culling, interpolate one-colour triangles).
    plan: &'a Plan,
    /// Where the viewer is, to tell which side of a face is seen: a point
    /// (perspective) or a direction towards the viewer (parallel views).
    eye: Eye,
    /// What a blended sample with nothing under it is composited over: the
    /// scene's background, or black.
    behind: crate::color::Lin,
    /// How much nearer edges over faces are drawn ([`crate::Wire::Edges`]).
    edge_bias: wire::EdgeBias,
    /// What metals reflect, where the plan draws it.
    environment: Option<&'a crate::scene::environment::EnvMap>,
}

/// Which runs a pass over the meshes draws: blended runs are drawn after
/// every other, back to front.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Pass {
    /// Every run but the blended ones.
    Opaque,
    /// The blended runs alone.
    Blend,
}

/// The meshes with a blended material (none unless the plan draws alpha),
/// the farthest first: by the depth of their bounding sphere's centre, in
/// the order a back-to-front pass draws them.
fn blended_meshes(scene: &Scene, plan: &Plan, vp: Mat4, turn: Mat4) -> Vec<usize> {
    use crate::scene::AlphaMode;
    if !plan[Effect::Alpha].run {
        return Vec::new();
    }
    let mut order: Vec<(f32, usize)> = (scene.meshes.iter().enumerate())
        .filter(|(_, m)| {
            m.geometry
                .materials
                .iter()
                .any(|r| r.finish.alpha.mode == AlphaMode::Blend)
        })
        .map(|(i, m)| {
            let centre = m
                .geometry
                .bounding_sphere()
                .map_or(Vec3::ZERO, |(c, _)| c.as_vec3());
            let clip = vp * turn * m.model * centre.extend(1.0);
            (clip.z / clip.w, i)
        })
        .collect();
    // Larger depth is nearer: the smallest first.
    order.sort_by(|a, b| a.0.total_cmp(&b.0));
    order.into_iter().map(|(_, i)| i).collect()
}

/// A blended run's faces, back to front: scratch memory kept from frame
/// to frame.
#[derive(Debug, Default)]
struct Sorted {
    /// Their indices in the mesh.
    ids: Vec<u32>,
    /// The faces themselves, in the same order.
    faces: Vec<[u32; 3]>,
}

/// Faces `run` of the mesh into `out`, the farthest first: by the depth of
/// each face's centre, as the model-view-projection puts it (larger depth
/// is nearer). Faces whose depths tie keep their order.
fn back_to_front(run: std::ops::Range<usize>, f: &Faces<'_>, out: &mut Sorted) {
    let mvp = f.transforms.mvp;
    let faces = &f.mesh.faces;
    let depth = |id: &u32| {
        let c = faces[*id as usize].map(|i| f.positions[i as usize]);
        let clip = mvp * ((c[0] + c[1] + c[2]) / 3.0).extend(1.0);
        clip.z / clip.w
    };
    out.ids.clear();
    out.ids.extend(run.start as u32..run.end as u32);
    out.ids.sort_by(|a, b| depth(a).total_cmp(&depth(b)));
    out.faces.clear();
    out.faces.extend(out.ids.iter().map(|&i| faces[i as usize]));
}

/// Mesh `i`'s model-space positions and normals for this frame: posed,
/// where the plan poses it, else its own.
fn vertices_of<'a>(
    posed: &'a [PosedMesh],
    plan: &Plan,
    i: usize,
    mesh: &'a crate::scene::Mesh,
) -> (&'a [Vec3], &'a [Vec3]) {
    match posed.get(i) {
        Some(m) if plan.poses(i) => (&m.positions, &m.normals),
        _ => (&mesh.positions, &mesh.normals),
    }
}

/// A reusable renderer.
#[derive(Debug)]
pub struct Renderer {
    fb: Framebuffer,
    frame: Frame,
    verts: Core,
    /// The extras of the vertices whose mesh keeps them.
    kept: Kept,
    poly: Polygon,
    /// A blended run's faces, back to front (scratch).
    sorted: Sorted,
    /// A mapped run's maps and face (scratch).
    mapping: mapped::Mapping,
    stats: FrameStats,
    plan: Option<Plan>,
    times: FrameTimes,
    /// Anti-aliasing's per-sample sums: red, green, blue, weight.
    acc: Vec<[f32; 4]>,
    /// The last frame's anti-aliasing.
    aa: Aa,
    /// What each band of the last frame drawn in parallel kept (empty
    /// until one is).
    bands: Vec<bands::BandWork>,
    /// The last camera resolved, the aspect it was resolved for, and the
    /// result ([`Camera::resolved`]).
    camera: Option<(Camera, FramingKey, Camera)>,
    /// Where each mesh's vertices are in `verts` and `more`, and its
    /// matrices, for a frame drawn in bands.
    meshes: Vec<MeshVerts>,
    /// Each mesh's vertices at its pose, where the plan poses it.
    posed: Vec<PosedMesh>,
}

/// A renderer's parts while a frame is drawn ([`Renderer::drawing`]).
struct Drawing<'a> {
    painter: Painter<'a>,
    times: &'a mut FrameTimes,
    posed: &'a [PosedMesh],
    meshes: &'a mut Vec<MeshVerts>,
}

/// A mesh's positions and normals at a pose, kept from frame to frame: a
/// clip paused at one time is posed once.
#[derive(Debug, Default)]
struct PosedMesh {
    /// The geometry and pose they are of (the geometry held, so that its
    /// address is not another's).
    of: Option<(Arc<Geometry>, Pose)>,
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    work: Posed,
}

/// What the vertex, triangle and fill stages draw with: the samples drawn
/// into (the framebuffer, or one band of its rows) and the counts and
/// scratch memory of whoever draws (the renderer, or one band's thread).
struct Painter<'a> {
    fb: Target<'a>,
    /// The finish of the run of faces being drawn.
    surface: Surface,
    stats: &'a mut FrameStats,
    poly: &'a mut Polygon,
    /// A blended run's faces, back to front.
    sorted: &'a mut Sorted,
    /// The mapped run being drawn's maps and face (none for other runs).
    mapping: &'a mut mapped::Mapping,
    verts: &'a mut Core,
    kept: &'a mut Kept,
    acc: &'a mut Vec<[f32; 4]>,
}

/// What a resolved camera was found for besides the camera itself: the
/// aspect, the turn's fixed angles (bits) and its axis.
type FramingKey = (u32, [u32; 3], transform::Axis);

/// Where one mesh's vertices are in a frame's vertex buffers, and its
/// matrices (for a frame drawn in bands, which keeps every mesh's).
#[derive(Debug)]
struct MeshVerts {
    core: std::ops::Range<usize>,
    /// Where its extras are in `kept` ([`Kept::marks`] before and after).
    kept: [[usize; 2]; 2],
    transforms: Transforms,
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
            verts: Core::default(),
            kept: Kept::default(),
            poly: Polygon::default(),
            sorted: Sorted::default(),
            mapping: mapped::Mapping::default(),
            stats: FrameStats::default(),
            plan: None,
            times: FrameTimes::default(),
            acc: Vec::new(),
            aa: Aa::None,
            bands: Vec::new(),
            camera: None,
            meshes: Vec::new(),
            posed: Vec::new(),
        }
    }

    /// Renders `scene` and returns the frame, kept in the renderer.
    ///
    /// # Panics
    ///
    /// With [`Renderer::try_render`]'s error, where it gives one.
    pub fn render(&mut self, scene: &Scene, opts: &RenderOptions) -> &Frame {
        if let Err(e) = check(scene, opts) {
            panic!("{e}");
        }
        self.render_checked(scene, opts)
    }

    /// [`Renderer::render`], or an error for options or a scene over their
    /// budgets: a frame side over [`MAX_CELLS`](crate::MAX_CELLS) cells,
    /// more sample tests than [`RenderOptions::max_samples`], a scene of
    /// more triangles or vertices than [`RenderOptions::max_triangles`]
    /// (see [`RenderOptions::check`]). Nothing is drawn or allocated then.
    pub fn try_render(&mut self, scene: &Scene, opts: &RenderOptions) -> Result<&Frame> {
        check(scene, opts)?;
        Ok(self.render_checked(scene, opts))
    }

    fn render_checked(&mut self, scene: &Scene, opts: &RenderOptions) -> &Frame {
        let mut frame = std::mem::take(&mut self.frame);
        self.render_to(scene, opts, &mut frame);
        self.frame = frame;
        &self.frame
    }

    /// [`Renderer::render_into`], or [`Renderer::try_render`]'s error.
    pub fn try_render_into(
        &mut self,
        scene: &Scene,
        opts: &RenderOptions,
        frame: &mut Frame,
    ) -> Result<()> {
        check(scene, opts)?;
        self.render_to(scene, opts, frame);
        Ok(())
    }

    /// Renders `scene` into the caller's `frame`, resizing it to the
    /// options' `cols × rows`. The renderer keeps only its working memory
    /// (samples, depths, vertices, the plan) between calls: once the sizes
    /// are stable, a frame allocates nothing. (A frame drawn in bands hands
    /// its work to rayon, whose queue for jobs from outside its pool takes
    /// a block of 63 slots every 63 frames.)
    ///
    /// ```
    /// use rastty::{Frame, RenderOptions, Renderer, color::Rgb, scene::Scene};
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
    ///
    /// # Panics
    ///
    /// With [`Renderer::try_render`]'s error, where it gives one.
    pub fn render_into(&mut self, scene: &Scene, opts: &RenderOptions, frame: &mut Frame) {
        if let Err(e) = check(scene, opts) {
            panic!("{e}");
        }
        self.render_to(scene, opts, frame);
    }

    /// Renders `scene` into `pixels`, one sample a pixel of the options'
    /// grid ([`RenderOptions::cell_pixels`] sizes a cell in pixels), rows
    /// from the top; pixels nothing covers are the scene's background, or
    /// transparent. The same samples a frame of cells is made of, through
    /// the same stages: only what they become differs.
    ///
    /// # Panics
    ///
    /// With [`Renderer::try_render`]'s error, where it gives one.
    pub fn render_pixels(&mut self, scene: &Scene, opts: &RenderOptions, pixels: &mut Pixels) {
        if let Err(e) = self.try_render_pixels(scene, opts, pixels) {
            panic!("{e}");
        }
    }

    /// [`Renderer::render_pixels`], or [`Renderer::try_render`]'s error.
    pub fn try_render_pixels(
        &mut self,
        scene: &Scene,
        opts: &RenderOptions,
        pixels: &mut Pixels,
    ) -> Result<()> {
        check(scene, opts)?;
        self.render_to(scene, opts, pixels);
        Ok(())
    }

    /// Draws `scene` (checked already) on the options' grid of samples and
    /// hands the samples to `out`, the one path from the stages to any
    /// output ([`crate::output`]): a frame drawn in bands fills each
    /// band's rows of `out` on the band's thread, any other all at once.
    pub(crate) fn render_to<O: Output>(
        &mut self,
        scene: &Scene,
        opts: &RenderOptions,
        out: &mut O,
    ) {
        let grid = opts.grid();
        let fill = out.begin(opts, scene.background);
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
        let cam = &self.resolved(&scene.camera, opts);
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
                let lights = Lights::new(if p[Effect::Lighting].run {
                    &scene.lights
                } else {
                    &[]
                });
                match opts.rim {
                    Some(c) if p[Effect::Rim].run => lights.with_rim(c, cam.eye - cam.target),
                    _ if p[Effect::Rim].run => lights.with_rim(Rgb::BLACK, cam.eye - cam.target),
                    _ => lights,
                }
            },
            traversal: opts.traversal,
            highlights: opts.highlights,
            precision: opts.precision,
            eye,
            behind: scene
                .background
                .map_or(crate::color::Lin::BLACK, crate::color::Lin::from_srgb),
            edge_bias: wire::EdgeBias::of(&cam.projection),
            // Prefiltered (the studio, once a process) only where a metal
            // reflects it.
            environment: if p[Effect::Environment].run {
                scene.environment.maps()
            } else {
                None
            },
        };

        self.pose(scene, p);
        self.times.plan += lap();
        self.aa = opts.aa;
        let mut banded = false;
        match opts.aa {
            Aa::None if p.bands.count > 1 => {
                self.draw_bands(scene, opts, &stage, (vp, turn), (out, &fill), &mut lap);
                banded = true;
            }
            Aa::None => {
                self.fb.reset(grid, p[Effect::Depth].run);
                self.geometry(scene, opts, &stage, vp, turn, &mut lap);
            }
            Aa::X4 | Aa::X16 | Aa::Exact => {
                self.antialiased(scene, opts, &stage, (vp, turn), &mut lap);
            }
        }
        self.times.triangles += lap();
        // Bands fill their own rows.
        if !banded {
            let done = O::fill(&fill, self.fb.view(), out.units_mut());
            out.end(done);
            self.times.blit += lap();
        }
        self.plan = plan;
    }

    /// The renderer taken apart for drawing a frame: a painter of its own
    /// framebuffer, and what the loops around the painter need.
    fn drawing(&mut self) -> Drawing<'_> {
        Drawing {
            painter: Painter {
                fb: self.fb.target(),
                surface: Surface::default(),
                stats: &mut self.stats,
                poly: &mut self.poly,
                sorted: &mut self.sorted,
                mapping: &mut self.mapping,
                verts: &mut self.verts,
                kept: &mut self.kept,
                acc: &mut self.acc,
            },
            times: &mut self.times,
            posed: &self.posed,
            meshes: &mut self.meshes,
        }
    }

    /// Poses every mesh the plan poses, unless it is at the pose it was
    /// posed at last frame (a paused clip costs nothing).
    fn pose(&mut self, scene: &Scene, plan: &Plan) {
        if self.posed.len() < scene.meshes.len() {
            self.posed
                .resize_with(scene.meshes.len(), PosedMesh::default);
        }
        for (i, mesh) in scene.meshes.iter().enumerate() {
            let (Some(rig), Some(pose)) = (&mesh.rig, mesh.pose) else {
                continue;
            };
            if !plan.poses(i) {
                continue;
            }
            let slot = &mut self.posed[i];
            let same = slot.of.as_ref().is_some_and(|(g, at)| {
                Arc::ptr_eq(g, &mesh.geometry)
                    && at.clip == pose.clip
                    && at.time.to_bits() == pose.time.to_bits()
            });
            if same {
                continue;
            }
            slot.positions.clear();
            slot.positions.extend_from_slice(&mesh.positions);
            slot.normals.clear();
            slot.normals.extend_from_slice(&mesh.normals);
            // The full pipeline poses every part; a planned frame only
            // those the clip moves (the rest stand at rest in the copy).
            let (p, n, work) = (&mut slot.positions, &mut slot.normals, &mut slot.work);
            self.stats.posed_vertices += if plan.full {
                rig.pose_into(Some(pose), work, p, n)
            } else {
                rig.pose_moving_into(pose, work, p, n)
            };
            slot.of = Some((mesh.geometry.clone(), pose));
        }
    }

    /// `camera` resolved for the view and turn of `opts`
    /// ([`Camera::resolved_turning`]): the last frame's result when the
    /// camera, the aspect and the turn's fixed angles are the same (bit
    /// for bit), otherwise found afresh. The angle about the turn's axis,
    /// which `spin` changes every frame, is swept through, so not looked at.
    fn resolved(&mut self, camera: &Camera, opts: &RenderOptions) -> Camera {
        let t = opts.turn;
        let fixed = match opts.turn_axis {
            transform::Axis::X => Vec3::new(0.0, t.y, t.z),
            transform::Axis::Y => Vec3::new(t.x, 0.0, t.z),
            transform::Axis::Z => Vec3::new(t.x, t.y, 0.0),
        };
        let key = (
            opts.aspect().to_bits(),
            fixed.to_array().map(f32::to_bits),
            opts.turn_axis,
        );
        match self.camera {
            Some((c, k, resolved)) if c.same_bits(camera) && k == key => resolved,
            _ => {
                let resolved = camera.resolved_turning(opts.aspect(), fixed, opts.turn_axis);
                self.camera = Some((*camera, key, resolved));
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
        let Drawing {
            mut painter,
            times,
            posed,
            ..
        } = self.drawing();
        for (i, mesh) in scene.meshes.iter().enumerate() {
            let transforms = Transforms::new(vp, turn * mesh.model);
            painter.verts.clear();
            painter.kept.clear();
            let (positions, normals) = vertices_of(posed, p, i, mesh);
            let cull = p.cull(i);
            painter.mesh_vertices(stage, &transforms, (positions, normals), i, cull);
            times.vertices += lap();
            let faces = Faces {
                mesh,
                positions,
                transforms: &transforms,
                cull,
            };
            // Borrowed out of the painter for the loop, and put back.
            let (verts, kept) = (std::mem::take(painter.verts), std::mem::take(painter.kept));
            if p[Effect::Faces].run {
                let v = Verts::new(
                    (verts.all(), kept.all()),
                    (positions, normals),
                    &transforms,
                    stage,
                );
                painter.faces(stage, &faces, v, Pass::Opaque);
            }
            if p[Effect::Edges].run {
                painter.edges(stage, mesh, positions, &transforms, opts.wire);
            }
            if p[Effect::Lines].run {
                painter.lines(stage, mesh, positions, &transforms);
            }
            (*painter.verts, *painter.kept) = (verts, kept);
            times.triangles += lap();
        }
        painter.loose(scene, opts, stage, vp, turn);
        // Blended runs last, the farthest mesh first, each mesh's vertices
        // found again (one mesh's are kept at a time).
        for i in blended_meshes(scene, p, vp, turn)
            .into_iter()
            .filter(|_| p[Effect::Faces].run)
        {
            let mesh = &scene.meshes[i];
            let transforms = Transforms::new(vp, turn * mesh.model);
            painter.verts.clear();
            painter.kept.clear();
            let (positions, normals) = vertices_of(posed, p, i, mesh);
            let cull = p.cull(i);
            // Counted once, in the first pass (as bands, which keep every
            // mesh's vertices, count them).
            let counted = *painter.stats;
            painter.mesh_vertices(stage, &transforms, (positions, normals), i, cull);
            *painter.stats = counted;
            let faces = Faces {
                mesh,
                positions,
                transforms: &transforms,
                cull,
            };
            let (verts, kept) = (std::mem::take(painter.verts), std::mem::take(painter.kept));
            let v = Verts::new(
                (verts.all(), kept.all()),
                (positions, normals),
                &transforms,
                stage,
            );
            painter.faces(stage, &faces, v, Pass::Blend);
            (*painter.verts, *painter.kept) = (verts, kept);
        }
        times.triangles += lap();
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

/// Renders one frame of `scene`.
///
/// # Panics
///
/// With [`try_render`]'s error, where it gives one.
#[must_use]
pub fn render(scene: &Scene, opts: &RenderOptions) -> Frame {
    Renderer::new().render(scene, opts).clone()
}

/// [`render`], or an error for options or a scene over their budgets, as
/// [`Renderer::try_render`] gives.
pub fn try_render(scene: &Scene, opts: &RenderOptions) -> Result<Frame> {
    Ok(Renderer::new().try_render(scene, opts)?.clone())
}

/// Refuses what no frame is drawn from: options [`RenderOptions::check`]
/// refuses, or a scene larger than the triangle budget (each mesh counted
/// by the larger of its faces and its vertices, which size the vertex
/// buffers).
fn check(scene: &Scene, opts: &RenderOptions) -> Result<()> {
    opts.check()?;
    let size = scene.triangles.len() as u64
        + scene
            .meshes
            .iter()
            .map(|m| m.faces.len().max(m.positions.len()) as u64)
            .sum::<u64>();
    if size > opts.max_triangles {
        return Err(crate::error::Error::Invalid(format!(
            "the scene has {size} triangles (or vertices), more than the triangle budget of {} (--max-triangles, RenderOptions::max_triangles, raises it)",
            opts.max_triangles
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb;
    use crate::scene::Shape;

    /// The vertices' extras are kept exactly where the plan says a face
    /// may read them, and the frame is the same either way.
    #[test]
    fn vertex_extras_are_kept_only_where_read() {
        let scene = Scene::of_mesh(Shape::Torus.mesh(Rgb::WHITE));
        let n = scene.meshes[0].positions.len();
        let draw = |opts: &RenderOptions| {
            let mut r = Renderer::new();
            let frame = r.render(&scene, opts).clone();
            let kept = r.kept.marks();
            (r.verts.len(), kept[0], kept[1], frame)
        };
        assert_eq!(
            (
                vertex::Core::BYTES,
                size_of::<vertex::Deep>(),
                size_of::<vertex::More>()
            ),
            (14, 20, 52),
            "the sizes the docs say"
        );
        // Lit, culled at the back, matte, inside the view, of more
        // vertices a sample than `Plan::DEFER_PER_SAMPLE`: none (the depth
        // and light of a face's corners found again at set-up).
        let lean = RenderOptions {
            cols: 8,
            rows: 4,
            ..RenderOptions::default()
        };
        let grid = lean.grid();
        assert!(n > Plan::DEFER_PER_SAMPLE * (grid.width * grid.height) as usize);
        let (verts, deep, rest, plain) = draw(&lean);
        assert_eq!((verts, deep, rest), (n, 0, 0));
        // Of fewer vertices a sample: their depth and light kept, all a
        // lean face reads.
        let near = RenderOptions {
            cols: 80,
            rows: 24,
            ..lean
        };
        let (verts, deep, rest, _) = draw(&near);
        assert_eq!((verts, deep, rest), (n, n, 0));
        // A rim reads each corner's normal; both sides drawn, the back's.
        let rim = RenderOptions {
            rim: Some(Rgb::BLACK),
            ..lean
        };
        assert_eq!(draw(&rim), (n, n, n, plain.clone()));
        let both = RenderOptions {
            cull: Some(crate::scene::Cull::None),
            ..lean
        };
        assert_eq!(draw(&both), (n, n, n, plain.clone()));
        // The full pipeline keeps them, and draws the same.
        let full = RenderOptions {
            pipeline: crate::options::Pipeline::Full,
            ..lean
        };
        assert_eq!(draw(&full), (n, n, n, plain));
        // Near, the frame is the one the full pipeline draws, which keeps
        // them all.
        let near_full = RenderOptions {
            pipeline: crate::options::Pipeline::Full,
            ..near
        };
        assert_eq!(draw(&near).3, draw(&near_full).3);
    }

    /// `--explain` says, mesh by mesh, whether the corners' depth and light
    /// are found at set-up (as the plan decides, by the threshold it
    /// names), why, and what is kept a vertex.
    #[test]
    fn explain_says_where_corners_are_lit() {
        let scene = Scene::of_mesh(Shape::Torus.mesh(Rgb::WHITE));
        let report = |cols: u16, rows: u16| {
            let opts = RenderOptions {
                cols,
                rows,
                ..RenderOptions::default()
            };
            let mut r = Renderer::new();
            r.render(&scene, &opts);
            r.explain(&scene, &opts, std::time::Duration::ZERO, 0)
        };
        let n = Plan::DEFER_PER_SAMPLE;
        let far = report(8, 4);
        assert!(
            far.contains(&format!(
                "lazy vertices  run   more than {n} vertices a sample"
            )),
            "{far}"
        );
        assert!(far.contains("14 bytes a vertex kept"), "{far}");
        let near = report(80, 24);
        assert!(
            near.contains(&format!(
                "lazy vertices  skip  at most {n} vertices a sample"
            )),
            "{near}"
        );
        assert!(near.contains("34 bytes a vertex kept"), "{near}");
    }
}
