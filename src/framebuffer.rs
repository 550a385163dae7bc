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

use crate::color::Lin;
use crate::transform::Grid;

/// A `width × height` grid of samples.
#[derive(Clone, Debug, PartialEq)]
pub struct Framebuffer {
    grid: Grid,
    samples: Vec<Option<Lin>>,
    depth: Vec<f32>,
}

impl Framebuffer {
    /// An empty framebuffer of `grid`'s samples.
    pub fn new(grid: Grid) -> Framebuffer {
        Framebuffer {
            grid,
            samples: vec![None; grid.len()],
            depth: vec![f32::NEG_INFINITY; grid.len()],
        }
    }

    /// The sample grid.
    pub fn grid(&self) -> Grid {
        self.grid
    }

    /// Clears every sample to the background and, with `depth`, every depth
    /// to −∞ (a frame without a depth test leaves the depth buffer alone);
    /// resizes if the grid changed (the only time it allocates).
    pub fn reset(&mut self, grid: Grid, depth: bool) {
        self.grid = grid;
        self.samples.clear();
        self.samples.resize(grid.len(), None);
        if depth || self.depth.len() != grid.len() {
            self.depth.clear();
            self.depth.resize(grid.len(), f32::NEG_INFINITY);
        }
    }

    #[inline(always)]
    /// Where sample `(x, y)` is stored (rows from the bottom).
    pub fn index(&self, x: u32, y: u32) -> usize {
        debug_assert!(x < self.grid.width && y < self.grid.height);
        y as usize * self.grid.width as usize + x as usize
    }

    #[inline(always)]
    /// Colours sample `(x, y)`.
    pub fn set(&mut self, x: u32, y: u32, c: Lin) {
        let i = self.index(x, y);
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
        &self.samples[y as usize * w..(y as usize + 1) * w]
    }

    /// All samples, row by row from the bottom.
    pub fn samples(&self) -> &[Option<Lin>] {
        &self.samples
    }
}
