//! The lean path's set-up ([`crate::Effect::Lean`]): a triangle inside
//! every clip plane, without a texture, accepted and counted as drawn, is
//! set up first (a box of a few samples tested sample by sample,
//! `raster::SmallSetup`), and its corners read, lit and filled only if it
//! covers a sample. Where the vertex stage kept no depth or light for its corners
//! ([`crate::plan::Extras::Found`], a large model seen small), they are
//! found only then too: most faces with a sample centre in their box
//! cover none. The trade-off: a second entry beside the kept corners',
//! whose code is left alone by it (its face loop is the frame's hottest).

use glam::Vec3A;

use super::triangle::{Faces, Model, base_colors, corners};
use super::vertex::{Deep, V, Verts};
use super::{Painter, Stage};
use crate::fill::Attributes;
use crate::plan::Effect;
use crate::plan::Extras;
use crate::raster::{Coverage, Setup, SmallSetup, SnappedTriangle};
use crate::shade::Shading;

impl Painter<'_> {
    /// What a triangle inside every clip plane without a texture takes on
    /// the plan's lean path ([`crate::Effect::Lean`]), once it is accepted
    /// and counted as drawn: set it up, and light and fill it only if it
    /// covers a sample.
    #[inline(always)]
    pub(super) fn inside_triangle<const KEEP: u8>(
        &mut self,
        stage: &Stage<'_>,
        (verts, face, scratch): (&Verts<'_>, &[u32; 3], &mut [Deep; 3]),
        (base, shine): (impl Fn() -> [Vec3A; 3], Option<Model<'_>>),
        t: &SnappedTriangle,
    ) {
        let (grid, band) = (self.fb.grid(), self.fb.band());
        // Its corners read only once it covers a sample.
        match SmallSetup::of(t, grid, band) {
            Some(s) if !s.covers_any() => self.stats.raster.samples_tested += s.bbox_samples(),
            Some(s) => {
                let v = verts.of_as::<KEEP>(*face, scratch);
                self.inside_fill(stage, v, (&base, shine), &s);
            }
            None => {
                let s = Setup::of(t, grid, band);
                let v = verts.of_as::<KEEP>(*face, scratch);
                self.inside_fill(stage, v, (&base, shine), &s);
            }
        }
    }

    /// Lights and fills a set-up triangle of [`Painter::inside_triangle`]
    /// if it covers a sample; counts its box's samples as tested if not.
    #[inline(always)]
    pub(super) fn inside_fill<'v, C: Coverage>(
        &mut self,
        stage: &Stage<'_>,
        v: [V<'v>; 3],
        (base, shine): (&impl Fn() -> [Vec3A; 3], Option<Model<'_>>),
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
            [v.map(|v| v.deep().z), v.map(|v| v.deep().inv_w)],
            color,
            stage.plan[Effect::Perspective].run,
        );
        let flat = !stage.plan.interpolates(&color);
        // A shining run's corners in the set-up's order.
        let order = s.order();
        let shining = shine.and_then(|m| {
            let model = Model {
                face: order.map(|k| m.face[k]),
                ..m
            };
            corners(true, stage, order.map(|k| v[k]), &model)
        });
        match shining {
            Some(corners) => self.fill_shiny(s, &a, flat, (None, corners), stage),
            None => self.fill_colour(s, &a, flat, stage),
        }
    }

    /// A face of a mesh whose corners' depth and light the vertex stage did
    /// not keep ([`crate::plan::Extras::Found`]: matte, so no shine), as
    /// [`Painter::inside_triangle`] takes it, its corners found only once
    /// it covers a sample; its colours those of its corners or of its run
    /// (`run_color`, `diffuse`). Out of line: the face loops of kept
    /// corners stay the code they were.
    #[inline(never)]
    pub(super) fn lean_found(
        &mut self,
        stage: &Stage<'_>,
        f: &Faces<'_>,
        (verts, face, scratch): (&Verts<'_>, &[u32; 3], &mut [Deep; 3]),
        (run_color, diffuse): (Vec3A, f32),
        t: &SnappedTriangle,
    ) {
        let (grid, band) = (self.fb.grid(), self.fb.band());
        let base = || base_colors(f.mesh, face, run_color, diffuse);
        let corners = move || {
            let scratch = scratch;
            verts.of_as::<{ Extras::Found as u8 }>(*face, scratch)
        };
        match SmallSetup::of(t, grid, band) {
            Some(s) if !s.covers_any() => self.stats.raster.samples_tested += s.bbox_samples(),
            Some(s) => self.found_fill(stage, corners, &base, &s),
            None => self.found_fill(stage, corners, &base, &Setup::of(t, grid, band)),
        }
    }

    /// Finds a covering triangle's corners (counted as lit, under smooth
    /// shading) and fills it ([`Painter::inside_fill`], without a shine).
    #[inline(always)]
    fn found_fill<'v, C: Coverage>(
        &mut self,
        stage: &Stage<'_>,
        corners: impl FnOnce() -> [V<'v>; 3],
        base: &impl Fn() -> [Vec3A; 3],
        s: &C,
    ) {
        if stage.plan.shading == Shading::Smooth {
            self.stats.lighting_evaluations += 3;
        }
        self.inside_fill(stage, corners(), (base, None), s);
    }
}
