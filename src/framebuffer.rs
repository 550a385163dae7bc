//! Stage 5: the framebuffer, one colour and one depth per sample.
//!
//! A sample holds `Some(colour)` once something was drawn on it and `None`
//! while it shows the background; colours are linear light (16 bits a
//! channel, 8 bytes a sample with the depth), encoded to sRGB only when the
//! blitter turns a cell's samples into its two colours. Keeping "nothing drawn" apart from any
//! colour lets the blitters draw shapes even where a triangle has the
//! background's colour, and lets a scene without a background keep the
//! terminal's own. Depth is the canonical cube's z (larger is nearer),
//! cleared to −∞. Rows are stored bottom to top (y up, as the notes have
//! it); the blitters turn them over.
//!
//! A framebuffer may hold one [`Band`] of its grid's rows only: what one
//! thread draws of a frame drawn in parallel. Its samples keep the grid's
//! coordinates (an index subtracts the band's first row).

use crate::color::Lin;
use crate::transform::{Band, Grid};

/// A `width × height` grid of samples, or one band of its rows.
#[derive(Clone, Debug, PartialEq)]
pub struct Framebuffer {
    grid: Grid,
    band: Band,
    samples: Vec<Option<Lin>>,
    depth: Vec<f32>,
}

impl Framebuffer {
    /// An empty framebuffer of `grid`'s samples.
    pub fn new(grid: Grid) -> Framebuffer {
        Framebuffer {
            grid,
            band: grid.all_rows(),
            samples: vec![None; grid.len()],
            depth: vec![f32::NEG_INFINITY; grid.len()],
        }
    }

    /// The sample grid.
    pub fn grid(&self) -> Grid {
        self.grid
    }

    /// The rows held: every row of the grid, or one band of them.
    pub fn band(&self) -> Band {
        self.band
    }

    /// Clears every sample to the background and, with `depth`, every depth
    /// to −∞ (a frame without a depth test leaves the depth buffer alone);
    /// resizes if the grid changed (the only time it allocates).
    pub fn reset(&mut self, grid: Grid, depth: bool) {
        self.reset_band(grid, grid.all_rows(), depth);
    }

    /// [`Framebuffer::reset`] to hold only `band`'s rows of `grid` (clamped
    /// to the grid).
    pub fn reset_band(&mut self, grid: Grid, band: Band, depth: bool) {
        let y1 = band.y1.min(grid.height);
        self.band = Band {
            y0: band.y0.min(y1),
            y1,
        };
        self.grid = grid;
        let len = grid.width as usize * self.band.height() as usize;
        if self.samples.len() == len {
            // Eight at a time: `fill` stores one tag at a time.
            let mut chunks = self.samples.chunks_exact_mut(8);
            for c in &mut chunks {
                c.copy_from_slice(&[None; 8]);
            }
            chunks.into_remainder().fill(None);
        } else {
            self.samples.clear();
            self.samples.resize(len, None);
        }
        if self.depth.len() != len {
            self.depth.clear();
            self.depth.resize(len, f32::NEG_INFINITY);
        } else if depth {
            // Eight at a time: `fill` of one f32 stores one at a time.
            let mut chunks = self.depth.chunks_exact_mut(8);
            for c in &mut chunks {
                c.copy_from_slice(&[f32::NEG_INFINITY; 8]);
            }
            chunks.into_remainder().fill(f32::NEG_INFINITY);
        }
    }

    /// Holds every row of `grid`, its contents left as they are (or, where
    /// it grows, cleared): for a frame whose every row is about to be
    /// copied in from bands.
    pub(crate) fn fit(&mut self, grid: Grid) {
        self.grid = grid;
        self.band = grid.all_rows();
        if self.samples.len() != grid.len() {
            self.samples.clear();
            self.samples.resize(grid.len(), None);
        }
        if self.depth.len() != grid.len() {
            self.depth.clear();
            self.depth.resize(grid.len(), f32::NEG_INFINITY);
        }
    }

    /// Copies the samples held into `samples` and, where given, the
    /// depths into `depths` (each as long as what is held).
    pub(crate) fn copy_into(&self, samples: &mut [Option<Lin>], depths: Option<&mut [f32]>) {
        samples.copy_from_slice(&self.samples);
        if let Some(d) = depths {
            d.copy_from_slice(&self.depth);
        }
    }

    /// The samples and depths held, to write a band of rows each.
    pub(crate) fn parts_mut(&mut self) -> (&mut [Option<Lin>], &mut [f32]) {
        (&mut self.samples, &mut self.depth)
    }

    #[inline(always)]
    /// Where sample `(x, y)` is stored (rows from the bottom).
    pub fn index(&self, x: u32, y: u32) -> usize {
        debug_assert!(x < self.grid.width && y >= self.band.y0 && y < self.band.y1);
        (y - self.band.y0) as usize * self.grid.width as usize + x as usize
    }

    #[inline(always)]
    /// Colours sample `(x, y)`.
    pub fn set(&mut self, x: u32, y: u32, c: Lin) {
        let i = self.index(x, y);
        self.samples[i] = Some(c);
    }

    /// Where sample `(x, y)` is stored, if depth `z` is nearer than what it
    /// holds (strictly, as [`Framebuffer::set_if_nearer`] decides).
    #[inline(always)]
    pub(crate) fn nearer(&self, x: u32, y: u32, z: f32) -> Option<usize> {
        let i = self.index(x, y);
        (z > self.depth[i]).then_some(i)
    }

    /// Where sample `(x, y)` is stored, if nothing is drawn on it yet.
    #[inline(always)]
    pub(crate) fn empty(&self, x: u32, y: u32) -> Option<usize> {
        let i = self.index(x, y);
        self.samples[i].is_none().then_some(i)
    }

    /// Writes colour `c` and depth `z` at index `i` (from
    /// [`Framebuffer::nearer`]).
    #[inline(always)]
    pub(crate) fn write(&mut self, i: usize, z: f32, c: Lin) {
        self.depth[i] = z;
        self.samples[i] = Some(c);
    }

    /// Writes colour `c` at index `i` (from [`Framebuffer::empty`]).
    #[inline(always)]
    pub(crate) fn write_color(&mut self, i: usize, c: Lin) {
        self.samples[i] = Some(c);
    }

    /// Writes `c` at depth `z` if `z` is nearer than what the sample holds
    /// (strictly: of two equal depths the first drawn stays). Returns
    /// whether it was written.
    #[inline(always)]
    pub fn set_if_nearer(&mut self, x: u32, y: u32, z: f32, c: Lin) -> bool {
        let i = self.index(x, y);
        if z > self.depth[i] {
            self.depth[i] = z;
            self.samples[i] = Some(c);
            true
        } else {
            false
        }
    }

    /// Writes `c` if nothing was drawn on the sample yet: what the depth
    /// test does for primitives of equal depth. Returns whether it wrote.
    #[inline(always)]
    pub fn set_if_empty(&mut self, x: u32, y: u32, c: Lin) -> bool {
        let i = self.index(x, y);
        let empty = self.samples[i].is_none();
        if empty {
            self.samples[i] = Some(c);
        }
        empty
    }

    #[inline(always)]
    /// Sample `(x, y)`'s colour; `None` where nothing was drawn.
    pub fn get(&self, x: u32, y: u32) -> Option<Lin> {
        self.samples[self.index(x, y)]
    }

    /// The depth at a sample (−∞ where nothing was depth-tested).
    #[inline(always)]
    pub fn depth(&self, x: u32, y: u32) -> f32 {
        self.depth[self.index(x, y)]
    }

    /// Sample row `y` (y up: row 0 is the bottom of the screen).
    pub fn row(&self, y: u32) -> &[Option<Lin>] {
        let w = self.grid.width as usize;
        let i = (y - self.band.y0) as usize * w;
        &self.samples[i..i + w]
    }

    /// All samples held, row by row from the bottom.
    pub fn samples(&self) -> &[Option<Lin>] {
        &self.samples
    }
}
