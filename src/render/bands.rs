//! A frame drawn in bands of whole cell rows, one thread each (rayon),
//! where the plan says so ([`crate::Plan::bands`]: frames of 600×180 cells
//! or more, with the `parallel` feature).
//!
//! The vertex stage runs once, on the calling thread; then each band
//! draws every triangle with its box clamped to its rows, into its rows of
//! the one framebuffer (a [`Target`] split off it: no copy, no second
//! framebuffer), and blits them into its rows of the frame. A sample sees
//! the same triangles in the same order as with one thread, and the
//! fixed-point edge values are exact integers from any starting row, so
//! the frame is the same bit for bit. The cost: each band sets up every
//! triangle that reaches it (a triangle across two bands is set up, and
//! may be lit, twice), which is why small frames stay on one thread
//! ([`crate::PARALLEL_CELLS`]; what bands save is in docs/figures.md and
//! docs/planner.md).

use std::time::Duration;

use glam::Mat4;

use super::triangle::Faces;
use super::vertex::{Core, Kept, Transforms, Verts};
use super::{Painter, Renderer, Sorted, Stage};
use crate::clip::Polygon;
use crate::framebuffer::Target;
use crate::options::RenderOptions;
use crate::output::Output;
use crate::plan::Effect;
use crate::scene::Scene;
use crate::stats::FrameStats;
use crate::transform::{Band, Rect};

/// What one band's thread keeps from frame to frame: its counts, its
/// scratch memory, and what it drew and blitted.
#[derive(Debug)]
pub(super) struct BandWork {
    stats: FrameStats,
    poly: Polygon,
    /// A blended run's faces, back to front (scratch).
    sorted: Sorted,
    /// A mapped run's maps and face (scratch).
    mapping: super::mapped::Mapping,
    /// The loose triangles' vertices, one triangle at a time.
    verts: Core,
    kept: Kept,
    /// Unused: bands are not anti-aliased.
    acc: Vec<[f32; 4]>,
    /// Where the band drew this frame.
    drawn: Rect,
}

impl Default for BandWork {
    fn default() -> BandWork {
        BandWork {
            stats: FrameStats::default(),
            poly: Polygon::default(),
            sorted: Sorted::default(),
            mapping: Default::default(),
            verts: Core::default(),
            kept: Kept::default(),
            acc: Vec::new(),
            drawn: Rect::EMPTY,
        }
    }
}

impl Renderer {
    /// Draws the frame in bands of whole cell rows, each on a thread of its
    /// own (with the `parallel` feature): every vertex is transformed once,
    /// here; then each band draws every triangle that reaches its rows
    /// into its rows of the one framebuffer, and blits them into its rows
    /// of `frame`. Band k holds cell rows `[k·m, (k+1)·m)` from the
    /// bottom, `m` rows a band (the top band may hold fewer).
    pub(super) fn draw_bands<O: Output>(
        &mut self,
        scene: &Scene,
        opts: &RenderOptions,
        stage: &Stage<'_>,
        (vp, turn): (Mat4, Mat4),
        (out, fill): (&mut O, &O::Fill),
        lap: &mut impl FnMut() -> Duration,
    ) {
        let p = stage.plan;
        let depth = p[Effect::Depth].run;
        let grid = opts.grid();
        // Bands are whole rows of the output's units.
        let (unit_w, unit_h) = O::unit(opts);
        let (cols, rows) = (grid.width / unit_w, grid.height / unit_h);
        let per = rows.div_ceil(p.bands.count as u32).max(1);
        let n = rows.div_ceil(per) as usize;
        // Cleared where the last frame drew.
        self.fb.reset(grid, depth);
        // The vertex stage, every mesh's vertices one after another.
        self.verts.clear();
        self.kept.clear();
        self.meshes.clear();
        let super::Drawing {
            mut painter,
            times,
            posed,
            meshes,
        } = self.drawing();
        for (i, mesh) in scene.meshes.iter().enumerate() {
            let transforms = Transforms::new(vp, turn * mesh.model);
            let start = (painter.verts.len(), painter.kept.marks());
            let (positions, normals) = super::vertices_of(posed, p, i, mesh);
            let cull = p.cull(i);
            painter.mesh_vertices(stage, &transforms, (positions, normals), i, cull);
            meshes.push(super::MeshVerts {
                core: start.0..painter.verts.len(),
                kept: [start.1, painter.kept.marks()],
                transforms,
            });
        }
        times.vertices += lap();
        let mut bands = std::mem::take(&mut self.bands);
        bands.resize_with(n, BandWork::default);
        let (verts, kept, meshes, posed) = (&self.verts, &self.kept, &self.meshes, &self.posed);
        let blended = super::blended_meshes(scene, p, vp, turn);
        let job = |k: usize,
                   band: &mut BandWork,
                   samples: &mut [Option<crate::color::Lin>],
                   depths: &mut [f32],
                   units: &mut [O::Unit]|
         -> O::Done {
            band.stats = FrameStats::default();
            band.drawn = Rect::EMPTY;
            let y0 = k as u32 * per * unit_h;
            let y1 = (y0 + per * unit_h).min(grid.height);
            let mut painter = Painter {
                fb: Target::of_band(grid, Band { y0, y1 }, samples, depths, &mut band.drawn),
                surface: Default::default(),
                stats: &mut band.stats,
                poly: &mut band.poly,
                sorted: &mut band.sorted,
                mapping: &mut band.mapping,
                verts: &mut band.verts,
                kept: &mut band.kept,
                acc: &mut band.acc,
            };
            let of = |i: usize| {
                let m = &meshes[i];
                let (positions, normals) = super::vertices_of(posed, p, i, &scene.meshes[i]);
                let kept = (
                    verts.range(m.core.clone()),
                    kept.between(m.kept[0], m.kept[1]),
                );
                Verts::new(kept, (positions, normals), &m.transforms, stage)
            };
            for (i, mesh) in scene.meshes.iter().enumerate() {
                let transforms = &meshes[i].transforms;
                let faces = Faces {
                    mesh,
                    positions: super::vertices_of(posed, p, i, mesh).0,
                    transforms,
                    cull: p.cull(i),
                };
                if p[Effect::Faces].run {
                    painter.faces(stage, &faces, of(i), super::Pass::Opaque);
                }
                if p[Effect::Edges].run {
                    painter.edges(stage, mesh, faces.positions, transforms, opts.wire);
                }
                if p[Effect::Lines].run {
                    painter.lines(stage, mesh, faces.positions, transforms);
                }
            }
            painter.loose(scene, opts, stage, vp, turn);
            for &i in blended.iter().filter(|_| p[Effect::Faces].run) {
                let mesh = &scene.meshes[i];
                let transforms = &meshes[i].transforms;
                let faces = Faces {
                    mesh,
                    positions: super::vertices_of(posed, p, i, mesh).0,
                    transforms,
                    cull: p.cull(i),
                };
                painter.faces(stage, &faces, of(i), super::Pass::Blend);
            }
            O::fill(fill, painter.fb.view(), units)
        };
        let band_samples = (per * unit_h * grid.width) as usize;
        let band_units = (per * cols) as usize;
        let (samples, depths) = self.fb.parts_mut();
        let units = out.units_mut();
        // Units are stored from the top: the bottom band's are the last.
        // The same zip twice, rayon's and the standard library's: their
        // iterators have the same shape but not the same types.
        #[cfg(feature = "parallel")]
        let done = {
            use rayon::prelude::*;
            bands
                .par_iter_mut()
                .zip(samples.par_chunks_mut(band_samples))
                .zip(depths.par_chunks_mut(band_samples))
                .zip(units.par_rchunks_mut(band_units))
                .enumerate()
                .map(|(k, (((band, s), d), u))| job(k, band, s, d, u))
                .reduce_with(O::merge)
        };
        #[cfg(not(feature = "parallel"))]
        let done = bands
            .iter_mut()
            .zip(samples.chunks_mut(band_samples))
            .zip(depths.chunks_mut(band_samples))
            .zip(units.rchunks_mut(band_units))
            .enumerate()
            .map(|(k, (((band, s), d), u))| job(k, band, s, d, u))
            .reduce(O::merge);
        let mut drawn = Rect::EMPTY;
        for (k, band) in bands.iter().enumerate() {
            self.stats.add_band(&band.stats, k == 0);
            drawn = drawn.union(band.drawn);
        }
        self.fb.touch(drawn);
        if let Some(done) = done {
            out.end(done);
        }
        self.bands = bands;
    }
}
