//! Stage 5: the framebuffer, one colour per sample.
//!
//! A sample holds `Some(colour)` once something was drawn on it and `None`
//! while it shows the background. Keeping "nothing drawn" apart from any
//! colour lets the blitters draw shapes even where a triangle has the
//! background's colour, and lets a scene without a background keep the
//! terminal's own. Rows are stored bottom to top (y up, as the notes have
//! it); the blitters turn them over.

use crate::color::Rgb;
use crate::raster::Grid;

/// A `width × height` grid of samples.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Framebuffer {
    grid: Grid,
    samples: Vec<Option<Rgb>>,
}

impl Framebuffer {
    pub fn new(grid: Grid) -> Framebuffer {
        Framebuffer {
            grid,
            samples: vec![None; grid.len()],
        }
    }

    pub fn grid(&self) -> Grid {
        self.grid
    }

    /// Clears every sample to the background, resizing if the grid changed
    /// (the only time it allocates).
    pub fn reset(&mut self, grid: Grid) {
        self.grid = grid;
        self.samples.clear();
        self.samples.resize(grid.len(), None);
    }

    #[inline(always)]
    fn index(&self, x: u32, y: u32) -> usize {
        debug_assert!(x < self.grid.width && y < self.grid.height);
        y as usize * self.grid.width as usize + x as usize
    }

    #[inline(always)]
    pub fn set(&mut self, x: u32, y: u32, c: Rgb) {
        let i = self.index(x, y);
        self.samples[i] = Some(c);
    }

    #[inline(always)]
    pub fn get(&self, x: u32, y: u32) -> Option<Rgb> {
        self.samples[self.index(x, y)]
    }

    /// Sample row `y` (y up: row 0 is the bottom of the screen).
    pub fn row(&self, y: u32) -> &[Option<Rgb>] {
        let w = self.grid.width as usize;
        &self.samples[y as usize * w..(y as usize + 1) * w]
    }
}
