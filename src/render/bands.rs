//! A frame drawn in bands of whole cell rows, one thread each (rayon),
//! where the plan says so ([`crate::Plan::bands`]: frames of 600×180 cells
//! or more, with the `parallel` feature).
//!
//! The vertex stage runs once, on the calling thread; then each band
//! clears its own framebuffer of its rows, draws every triangle with its
//! box clamped to them, copies them into the renderer's framebuffer and
//! blits them into its rows of the frame. A sample sees the same triangles
//! in the same order as with one thread, and the fixed-point edge values
//! are exact integers from any starting row, so the frame is the same bit
//! for bit. The costs: each band sets up every triangle that reaches it (a
//! triangle across two bands is set up, and may be lit, twice), the copy,
//! and a second framebuffer's memory, which is why small frames stay on
//! one thread ([`crate::PARALLEL_CELLS`]; what bands save is in
//! docs/figures.md and docs/planner.md).

use std::time::Duration;

use glam::Mat4;

use super::stats::FrameStats;
use super::triangle::Faces;
use super::vertex::Transforms;
use super::{Renderer, Stage};
use crate::blit;
use crate::color::Lin;
use crate::frame::{Cell, Frame, Known};
use crate::options::RenderOptions;
use crate::scene::Scene;
use crate::transform::{Band, Rect};

impl Renderer {
    /// Draws the frame in bands of whole cell rows, each on a thread of its
    /// own (with the `parallel` feature): every vertex is transformed once,
    /// here; then each band clears its rows, draws every triangle that
    /// reaches them, copies them into this renderer's framebuffer and blits
    /// them into their rows of `frame`. Band k holds cell rows
    /// `[k·m, (k+1)·m)` from the bottom, `m` rows a band (the top band may
    /// hold fewer).
    pub(super) fn draw_bands(
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
}
