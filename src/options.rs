//! What a frame is drawn with, apart from the scene: its size in cells,
//! glyphs, colour depth, and every accuracy knob ([`Aa`],
//! [`Interpolation`], [`Split`], [`Precision`], [`Traversal`]) with its
//! default at the exact, lecture-faithful setting. The planner and the
//! renderer both read these; neither owns them.

use crate::choice::Choice;
use glam::Vec3;

use crate::blit::{GlyphMode, Split};
use crate::color::{ColorDepth, Rgb};
use crate::raster::{Precision, Traversal};
use crate::scene::Cull;
use crate::shade::Shading;
use crate::texture::FilterMode;
use crate::transform::Axis;

/// Largest frame side, in cells: a bigger terminal is drawn at this size
/// (4096×4096 cells is already 16 M cells, 128 M samples in octant mode).
pub const MAX_CELLS: u16 = 4096;

/// Largest side of a cell in pixels ([`RenderOptions::cell_pixels`]).
pub const MAX_CELL_PIXELS: u16 = 256;

/// Everything about a frame that is not the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderOptions {
    /// Columns of the frame.
    pub cols: u16,
    /// Rows of the frame.
    pub rows: u16,
    /// How a cell's samples become a glyph.
    pub glyphs: GlyphMode,
    /// One sample a pixel: each cell a block of this many pixels across
    /// and down (a terminal that shows images; [`crate::Pixels`]), or
    /// `None`, the glyph mode's samples. With it, the view's aspect is
    /// the pixels' and `cell_aspect` is not read.
    pub cell_pixels: Option<[u16; 2]>,
    /// How many colours the frame may use.
    pub color: ColorDepth,
    /// A cell's width over its height, physically (about 0.5 in most
    /// terminals).
    pub cell_aspect: f32,
    /// How the rasterizer walks the samples (all give the same coverage).
    pub traversal: Traversal,
    /// Turns the whole scene about the world origin: degrees about x
    /// (pitch), then y (yaw), then z (roll). What `spin` animates. Lights
    /// and camera stay put.
    pub turn: Vec3,
    /// The axis `turn` turns about from frame to frame (`spin --axis`; y
    /// for a still frame, as `--yaw` turns it): a model framed by its
    /// camera ([`crate::scene::Camera::resolved_turning`]) fits the view
    /// turned any way about it, `turn`'s other two angles as they are.
    pub turn_axis: Axis,
    /// How surfaces are lit.
    pub shading: Shading,
    /// Culling for everything, overriding each mesh's own (`None`: meshes
    /// cull as their scene says, loose triangles never).
    pub cull: Option<Cull>,
    /// Whether the planner may skip stages the scene does not need.
    pub pipeline: Pipeline,
    /// Anti-aliasing: sub-samples per sample, or exact area coverage.
    pub aa: Aa,
    /// How interpolated attributes are weighted.
    pub interpolation: Interpolation,
    /// Where a shining material's highlight is found.
    pub highlights: Highlights,
    /// How two-colour cells split their samples.
    pub split: Split,
    /// How edge functions are evaluated.
    pub precision: Precision,
    /// Texture filtering for every texture (`None`: as each file's sampler
    /// says).
    pub filter: Option<FilterMode>,
    /// How many threads may draw the frame, each a band of its rows (the
    /// same frame, bit for bit, with any number).
    pub threads: Threads,
    /// A rim light of this colour, or none (the default): light added (not
    /// multiplied by the surface's colour) where a lit surface turns away
    /// from the eye, so that a dark model's silhouette shows against a dark
    /// background (see `shade.rs`; `--rim COLOR`).
    pub rim: Option<Rgb>,
    /// Faces, their edges as lines, or both (`--wire`, `w` in `spin`).
    pub wire: Wire,
    /// The most sample tests a frame may make ([`RenderOptions::sample_tests`];
    /// [`DEFAULT_MAX_SAMPLES`]): the frame's memory and time grow with it.
    pub max_samples: u64,
    /// The most triangles (and vertices) a scene drawn may have, each mesh
    /// counted by the larger of its faces and its vertices
    /// ([`crate::scene::DEFAULT_MAX_TRIANGLES`]): the renderer's vertex
    /// buffers grow with it.
    pub max_triangles: u64,
}

/// How many threads draw a frame. Each draws one band of the sample rows;
/// the frame is the same, bit for bit, whatever the count (a test renders
/// random scenes with 1 to 7). Only the fixed-point set-up without
/// anti-aliasing or a full-grid scan draws in bands; otherwise the plan
/// says why it draws on one thread ([`crate::Plan::bands`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Threads {
    /// As many as the machine has, for frames of at least
    /// [`PARALLEL_CELLS`] cells (or [`PARALLEL_PIXELS`] pixels); one for
    /// smaller frames, where splitting costs more than it gains.
    #[default]
    Auto,
    /// This many bands, at most [`MAX_THREADS`] and one per cell row, for
    /// any frame size. Without the `parallel` feature the bands are drawn
    /// one after another on the calling thread.
    Exactly(u16),
}

/// The most bands a frame is split into.
pub const MAX_THREADS: u16 = 64;

/// The smallest frame, in cells, that [`Threads::Auto`] draws in parallel
/// (600×180). Below it the per-band work (each band sets up every triangle
/// that reaches it, and copies its rows), the vertex stage left on one
/// thread and handing the bands to rayon outweigh the gain (docs/figures.md's
/// Bands section times one band against two at four sizes).
pub const PARALLEL_CELLS: u32 = 600 * 180;

/// The smallest frame of pixels ([`RenderOptions::cell_pixels`]), in
/// samples, that [`Threads::Auto`] draws in parallel (640×360): a
/// 960×540 frame of Tux draws a fifth faster in two bands than in one.
pub const PARALLEL_PIXELS: u32 = 640 * 360;

impl std::str::FromStr for Threads {
    type Err = String;

    /// `auto`, or a count from 1 to [`MAX_THREADS`].
    fn from_str(s: &str) -> Result<Threads, String> {
        if s == "auto" {
            return Ok(Threads::Auto);
        }
        match s.parse::<u16>() {
            Ok(n @ 1..=MAX_THREADS) => Ok(Threads::Exactly(n)),
            _ => Err(format!("expected auto or a count from 1 to {MAX_THREADS}")),
        }
    }
}

/// What of a mesh is drawn: its faces, its edges as lines one sample wide,
/// or both. Each edge is drawn once however many faces share it (edges
/// between vertices at the same positions are one), as two triangles
/// through the same exact rasterizer, so a line's samples follow the
/// top-left rule as a face's do.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Wire {
    /// The faces alone.
    #[default]
    Solid,
    /// The edges alone, in each mesh's colour, unlit: every edge shows,
    /// the nearest where they cross.
    Lines,
    /// The faces, then their edges in black over them: an edge behind a
    /// face is hidden by the depth test (edges are drawn as if 1 % of
    /// their distance nearer, so that a face does not hide its own).
    Edges,
}

crate::choice::choice!(Wire {
    Solid => "solid": "The faces alone",
    Lines => "lines": "The edges alone, one sample wide, in each mesh's colour: every edge shows",
    Edges => "edges": "The faces, and their edges in black over them; edges behind a face are hidden",
});

/// Where a shining material's specular highlight is found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Highlights {
    /// At each sample, from the normal and position interpolated there: a
    /// highlight smaller than a triangle is drawn where it is.
    #[default]
    Sample,
    /// At each vertex, then interpolated (Gouraud): cheaper, and a
    /// highlight smaller than a triangle dims or vanishes (for measuring
    /// what per-sample costs).
    Vertex,
}

crate::choice::choice!(Highlights {
    Sample => "sample": "At each sample, from the normal and position interpolated there",
    Vertex => "vertex": "At each vertex, then interpolated: cheaper, and a highlight smaller than a triangle dims or vanishes (for comparison)",
});

/// How attributes are interpolated across a triangle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Interpolation {
    /// Screen-space weights divided by `w` (correct under perspective).
    #[default]
    Perspective,
    /// Screen-space weights as they are: cheaper, and wrong under
    /// perspective (for measuring what correctness costs).
    Affine,
}

crate::choice::choice!(Interpolation {
    Perspective => "perspective": "Screen-space weights divided by `w` (correct under perspective)",
    Affine => "affine": "Screen-space weights as they are: cheaper, and wrong under perspective (for measuring what correctness costs)",
});

/// How a sample's colour is found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Aa {
    /// One test at the sample's centre: the lecture's sampling.
    #[default]
    None,
    /// Four sub-samples in the rotated-grid pattern, averaged.
    X4,
    /// Sixteen sub-samples on an ordered 4×4 grid, averaged.
    X16,
    /// The exact area of each triangle inside the sample's square.
    Exact,
}

crate::choice::choice!(Aa {
    None => "none": "One test at the sample's centre: the lecture's sampling",
    X4 => "4x": "Four sub-samples in the rotated-grid pattern, averaged",
    X16 => "16x": "Sixteen sub-samples on an ordered 4×4 grid, averaged",
    Exact => "exact": "The exact area of each triangle inside the sample's square",
});

/// The rotated-grid pattern of 4× anti-aliasing, in a sample's square.
const RGSS: [(f32, f32); 4] = [
    (0.375, 0.125),
    (0.875, 0.375),
    (0.125, 0.625),
    (0.625, 0.875),
];

/// The ordered 4×4 grid of 16× anti-aliasing.
const ORDERED_16: [(f32, f32); 16] = {
    let mut g = [(0.0, 0.0); 16];
    let mut i = 0;
    while i < 16 {
        g[i] = (((i % 4) as f32 + 0.5) / 4.0, ((i / 4) as f32 + 0.5) / 4.0);
        i += 1;
    }
    g
};

impl Aa {
    /// How many times a frame's geometry is drawn.
    pub fn passes(self) -> u64 {
        self.offsets().len() as u64
    }

    /// The sub-sample positions inside a sample's unit square.
    pub fn offsets(self) -> &'static [(f32, f32)] {
        match self {
            Aa::None | Aa::Exact => &[(0.5, 0.5)],
            Aa::X4 => &RGSS,
            Aa::X16 => &ORDERED_16,
        }
    }
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            cols: 80,
            rows: 24,
            glyphs: GlyphMode::default(),
            color: ColorDepth::default(),
            cell_aspect: 0.5,
            cell_pixels: None,
            traversal: Traversal::default(),
            turn: Vec3::ZERO,
            turn_axis: Axis::Y,
            shading: Shading::default(),
            cull: None,
            pipeline: Pipeline::default(),
            aa: Aa::None,
            interpolation: Interpolation::default(),
            highlights: Highlights::default(),
            split: Split::default(),
            precision: Precision::default(),
            filter: None,
            threads: Threads::Auto,
            rim: None,
            wire: Wire::Solid,
            max_samples: DEFAULT_MAX_SAMPLES,
            max_triangles: crate::scene::DEFAULT_MAX_TRIANGLES,
        }
    }
}

/// The default budget of sample tests in one frame (64 Mi): a 1,024 × 512
/// octant frame at 16× anti-aliasing, far past any terminal; see
/// [`RenderOptions::sample_tests`].
pub const DEFAULT_MAX_SAMPLES: u64 = 1 << 26;

impl RenderOptions {
    /// The sample tests one frame makes: cells × samples a cell × the
    /// anti-aliasing passes. Time grows with it, and memory with the
    /// samples (about 12 bytes each, 28 with anti-aliasing).
    pub fn sample_tests(&self) -> u64 {
        let (w, h) = self.cell_samples();
        u64::from(self.cols) * u64::from(self.rows) * u64::from(w * h) * self.aa.passes()
    }

    /// Refuses, before any work, a frame of more than `max` sample tests,
    /// with the error naming the budget and how to raise it.
    pub fn check_samples(&self, max: u64) -> crate::error::Result<()> {
        let n = self.sample_tests();
        if n <= max {
            return Ok(());
        }
        Err(crate::error::Error::Invalid(format!(
            "a frame of {}×{} cells at {} samples a cell and {} pass(es) of --aa {} is {n} sample tests, more than the budget of {max} (--max-samples raises it)",
            self.cols,
            self.rows,
            self.cell_samples().0 * self.cell_samples().1,
            self.aa.passes(),
            self.aa.name()
        )))
    }

    /// Refuses options no frame can be drawn with: a side of more than
    /// [`MAX_CELLS`] cells, more sample tests than
    /// [`RenderOptions::max_samples`], a cell aspect that is not a finite
    /// number above 0, or a turn that is not finite. The renderer's `try_`
    /// forms return this error; the others panic with it.
    pub fn check(&self) -> crate::error::Result<()> {
        let bad = |m: String| Err(crate::error::Error::Invalid(m));
        if self.cols > MAX_CELLS || self.rows > MAX_CELLS {
            return bad(format!(
                "a frame of {}×{} cells: each side may be at most {MAX_CELLS} cells",
                self.cols, self.rows
            ));
        }
        if !(self.cell_aspect.is_finite() && self.cell_aspect > 0.0) {
            return bad(format!(
                "a cell aspect of {}: it must be a finite number above 0",
                self.cell_aspect
            ));
        }
        if let Some([w, h]) = self.cell_pixels
            && !((1..=MAX_CELL_PIXELS).contains(&w) && (1..=MAX_CELL_PIXELS).contains(&h))
        {
            return bad(format!(
                "cells of {w}×{h} pixels: each side must be from 1 to {MAX_CELL_PIXELS}"
            ));
        }
        if !self.turn.is_finite() {
            return bad(format!("a turn of {}: it must be finite", self.turn));
        }
        self.check_samples(self.max_samples)
    }

    /// Samples a cell holds, across and down: its pixels
    /// ([`RenderOptions::cell_pixels`]), else the glyph mode's grid
    /// ([`GlyphMode::cell_size`]).
    pub fn cell_samples(&self) -> (u32, u32) {
        match self.cell_pixels {
            Some([w, h]) => (u32::from(w), u32::from(h)),
            None => self.glyphs.cell_size(),
        }
    }

    /// The frame's grid of samples: its cells, each of
    /// [`RenderOptions::cell_samples`]. Every stage draws on it, whatever
    /// the frame's samples then become (character cells, pixels).
    pub fn grid(&self) -> crate::transform::Grid {
        let (w, h) = self.cell_samples();
        crate::transform::Grid::new(u32::from(self.cols) * w, u32::from(self.rows) * h)
    }

    /// The physical aspect of the whole view, `(cols·cell_w)/(rows·cell_h)`:
    /// what the projection is given.
    pub fn aspect(&self) -> f32 {
        let cell = match self.cell_pixels {
            Some([w, h]) => f32::from(w) / f32::from(h.max(1)),
            None => self.cell_aspect,
        };
        self.cols as f32 * cell / self.rows.max(1) as f32
    }
}

/// How wide a wireframe's line is, in samples.
pub(crate) const LINE_WIDTH: f64 = 1.0;

/// Whether the planner may skip stages.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Pipeline {
    /// Run only the stages the scene calls for.
    #[default]
    Planned,
    /// Run every stage on every primitive (`--full-pipeline`): the
    /// reference the planned frames are checked against.
    Full,
}

crate::choice::choice!(Pipeline {
    Planned => "planned": "Run only the stages the scene calls for",
    Full => "full": "Run every stage on every primitive (`--full-pipeline`): the reference the planned frames are checked against",
});
