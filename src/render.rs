//! The pipeline, end to end: scene → transform → clip → raster →
//! framebuffer → blit, into a [`Frame`].
//!
//! A [`Renderer`] owns the framebuffer and the frame and reuses them, so
//! rendering frame after frame allocates nothing once the size is stable.
//! [`render`] is the one-call form for tests and tools.
//!
//! Per-vertex colours are interpolated perspective-correctly: the
//! rasterizer's screen-space weights `e_i` are divided by each vertex's `w`
//! and renormalised. A triangle of one colour is written without any
//! interpolation.

use glam::{Mat4, Vec3, Vec4};

use crate::blit::{self, GlyphMode};
use crate::clip::{ClipVertex, Clipped, Clipper, Polygon};
use crate::color::{ColorDepth, Rgb};
use crate::frame::Frame;
use crate::framebuffer::Framebuffer;
use crate::raster::{Cull, Grid, RasterStats, Setup, Traversal};
use crate::scene::Scene;
use crate::transform;

/// Everything about a frame that is not the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderOptions {
    pub cols: u16,
    pub rows: u16,
    pub glyphs: GlyphMode,
    pub color: ColorDepth,
    /// A cell's width over its height, physically (about 0.5 in most
    /// terminals).
    pub cell_aspect: f32,
    pub traversal: Traversal,
    /// Turns the whole scene about the world origin: degrees about x
    /// (pitch), then y (yaw), then z (roll). What `spin` animates.
    pub turn: Vec3,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            cols: 80,
            rows: 24,
            glyphs: GlyphMode::default(),
            color: ColorDepth::default(),
            cell_aspect: 0.5,
            traversal: Traversal::default(),
            turn: Vec3::ZERO,
        }
    }
}

impl RenderOptions {
    /// The physical aspect of the whole view, `(cols·cell_w)/(rows·cell_h)`:
    /// what the projection is given.
    pub fn aspect(&self) -> f32 {
        self.cols as f32 * self.cell_aspect / self.rows.max(1) as f32
    }
}

/// What one frame cost.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameStats {
    /// Triangles handed to the pipeline.
    pub triangles_in: u64,
    /// Triangles the clip stage cut.
    pub clipped: u64,
    /// Triangles the clip stage removed entirely (outside, or not finite).
    pub clip_rejected: u64,
    pub raster: RasterStats,
}

/// A reusable renderer.
#[derive(Debug)]
pub struct Renderer {
    fb: Framebuffer,
    frame: Frame,
    stats: FrameStats,
}

impl Default for Renderer {
    fn default() -> Self {
        Renderer::new()
    }
}

/// A triangle after the divide: screen positions in samples, `1/w`, and
/// colours.
struct ScreenTriangle {
    xy: [[f32; 2]; 3],
    inv_w: [f32; 3],
    color: [Vec3; 3],
}

impl Renderer {
    pub fn new() -> Renderer {
        Renderer {
            fb: Framebuffer::new(Grid::new(0, 0)),
            frame: Frame::default(),
            stats: FrameStats::default(),
        }
    }

    /// Renders `scene` and returns the frame.
    pub fn render(&mut self, scene: &Scene, opts: &RenderOptions) -> &Frame {
        let grid = opts.glyphs.grid(opts.cols, opts.rows);
        self.fb.reset(grid);
        self.stats = FrameStats::default();

        let vp = scene.camera.view_projection(opts.aspect()) * transform::rotation(opts.turn);
        let viewport = transform::viewport(grid.width as f32, grid.height as f32);
        let clipper = Clipper::new(grid.width, grid.height);
        let mut poly = Polygon::default();
        for tri in &scene.triangles {
            let colors = tri.color.at_vertices();
            let verts = [0, 1, 2].map(|i| ClipVertex {
                pos: vp * tri.vertices[i].extend(1.0),
                color: Vec3::from(colors[i].to_f32()),
            });
            self.draw(
                &verts,
                &clipper,
                &viewport,
                &mut poly,
                Cull::None,
                opts.traversal,
            );
        }
        blit::blit(
            &self.fb,
            opts.glyphs,
            opts.color,
            scene.background,
            &mut self.frame,
        );
        &self.frame
    }

    /// Clips, divides and rasterizes one clip-space triangle.
    fn draw(
        &mut self,
        verts: &[ClipVertex; 3],
        clipper: &Clipper,
        viewport: &Mat4,
        poly: &mut Polygon,
        cull: Cull,
        traversal: Traversal,
    ) {
        self.stats.triangles_in += 1;
        match clipper.clip(verts, poly) {
            Clipped::Rejected => {
                self.stats.clip_rejected += 1;
                return;
            }
            Clipped::Clipped => self.stats.clipped += 1,
            Clipped::Inside => {}
        }
        for tri in poly.triangles() {
            let screen = to_screen(&tri, viewport);
            self.raster(&screen, cull, traversal);
        }
    }

    fn raster(&mut self, t: &ScreenTriangle, cull: Cull, traversal: Traversal) {
        let grid = self.fb.grid();
        let setup = match Setup::new(t.xy, grid, cull) {
            Ok(s) => s,
            Err(r) => {
                self.stats.raster.count_rejected(r);
                return;
            }
        };
        let stats = &mut self.stats.raster;
        stats.triangles_drawn += 1;
        let fb = &mut self.fb;
        let mut covered = 0u64;
        let flat = t.color[0] == t.color[1] && t.color[1] == t.color[2];
        let tested = if flat {
            let c = Rgb::from_f32(t.color[0].to_array());
            setup.walk(grid, traversal, |x, y, _| {
                covered += 1;
                fb.set(x, y, c);
            })
        } else {
            // Perspective-correct weights: e_i / w_i, renormalised.
            let [a, b, c] = t.inv_w;
            let [ca, cb, cc] = t.color;
            setup.walk(grid, traversal, |x, y, e| {
                covered += 1;
                let (wa, wb, wc) = (e[0] as f32 * a, e[1] as f32 * b, e[2] as f32 * c);
                let col = (ca * wa + cb * wb + cc * wc) / (wa + wb + wc);
                fb.set(x, y, Rgb::from_f32(col.to_array()));
            })
        };
        stats.samples_tested += tested;
        stats.samples_covered += covered;
    }

    pub fn frame(&self) -> &Frame {
        &self.frame
    }

    pub fn framebuffer(&self) -> &Framebuffer {
        &self.fb
    }

    pub fn stats(&self) -> &FrameStats {
        &self.stats
    }
}

fn to_screen(tri: &[ClipVertex; 3], viewport: &Mat4) -> ScreenTriangle {
    let mut xy = [[0.0; 2]; 3];
    let mut inv_w = [0.0; 3];
    for (i, v) in tri.iter().enumerate() {
        let (x, y, w) = (v.pos.x, v.pos.y, v.pos.w);
        inv_w[i] = 1.0 / w;
        let s = *viewport * Vec4::new(x * inv_w[i], y * inv_w[i], 0.0, 1.0);
        xy[i] = [s.x, s.y];
    }
    ScreenTriangle {
        xy,
        inv_w,
        color: tri.map(|v| v.color),
    }
}

/// Renders one frame of `scene`.
pub fn render(scene: &Scene, opts: &RenderOptions) -> Frame {
    Renderer::new().render(scene, opts).clone()
}
