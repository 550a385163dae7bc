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
//! The fill stage writes through a [`Target`]: the framebuffer's rows, or
//! one [`Band`] of them split off for one thread of a frame drawn in
//! parallel, so that bands draw into the one framebuffer rather than into
//! copies of their own (tiny-skia's `SubPixmapMut`). The blitters read a
//! [`View`]. Samples keep the grid's coordinates (an index subtracts the
//! band's first row). A framebuffer may itself hold one band of its
//! grid's rows only ([`Framebuffer::reset_band`]).
//!
//! It keeps the rectangle where anything was drawn since it was cleared:
//! every sample outside it is empty. A model
//! seen small covers a corner of a large frame, and then clearing the
//! framebuffer, blitting it and encoding its cells touch only that
//! rectangle's samples; the rest is known to be background. The fills
//! widen it once per triangle, by the triangle's bounding box, rather than
//! once per sample.

use crate::color::Lin;
use crate::transform::{Band, Grid, Rect};

/// A `width × height` grid of samples, or one band of its rows.
#[derive(Clone, Debug)]
pub struct Framebuffer {
    grid: Grid,
    band: Band,
    samples: Vec<Option<Lin>>,
    depth: Vec<f32>,
    /// Where anything was drawn since the framebuffer was cleared: every
    /// sample outside it is empty (it may hold empty samples too).
    drawn: Rect,
    /// Every depth outside it and `drawn` is −∞ (depths are written with
    /// samples, and a frame without a depth test does not clear them).
    depth_drawn: Rect,
}

/// Equal samples and depths, over the same rows of the same grid.
impl PartialEq for Framebuffer {
    fn eq(&self, o: &Framebuffer) -> bool {
        self.grid == o.grid
            && self.band == o.band
            && self.samples == o.samples
            && self.depth == o.depth
    }
}

impl Framebuffer {
    /// An empty framebuffer of `grid`'s samples.
    pub fn new(grid: Grid) -> Framebuffer {
        Framebuffer {
            grid,
            band: grid.all_rows(),
            samples: vec![None; grid.len()],
            depth: vec![f32::NEG_INFINITY; grid.len()],
            drawn: Rect::EMPTY,
            depth_drawn: Rect::EMPTY,
        }
    }

    /// Widens the rectangle where anything was drawn by `r`.
    #[inline(always)]
    pub(crate) fn touch(&mut self, r: Rect) {
        self.drawn = self.drawn.union(r);
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
        let band = Band {
            y0: band.y0.min(y1),
            y1,
        };
        let len = grid.width as usize * band.height() as usize;
        self.debug_assert_empty_outside_drawn();
        let same = self.grid == grid && self.band == band;
        self.band = band;
        self.grid = grid;
        if !same || self.samples.len() != len || self.depth.len() != len {
            self.samples.clear();
            self.samples.resize(len, None);
            self.depth.clear();
            self.depth.resize(len, f32::NEG_INFINITY);
            self.depth_drawn = Rect::EMPTY;
        } else {
            // Only where anything was drawn.
            let drawn = self.drawn;
            self.rows_of(drawn, |s, _| clear(s, None));
            self.depth_drawn = self.depth_drawn.union(drawn);
            if depth {
                let dirty = self.depth_drawn;
                self.rows_of(dirty, |_, d| clear(d, f32::NEG_INFINITY));
                self.depth_drawn = Rect::EMPTY;
            }
        }
        self.drawn = Rect::EMPTY;
    }

    /// Calls `f` with the samples and depths of `r`'s part of each row held.
    fn rows_of(&mut self, r: Rect, mut f: impl FnMut(&mut [Option<Lin>], &mut [f32])) {
        let w = self.grid.width as usize;
        let r = r.intersect(Rect::all(self.grid.width, self.band.y1));
        for y in r.y0.max(self.band.y0)..r.y1 {
            let start = (y - self.band.y0) as usize * w;
            let span = start + r.x0 as usize..start + r.x1 as usize;
            f(&mut self.samples[span.clone()], &mut self.depth[span]);
        }
    }

    /// Checks, in debug builds, that every sample outside
    /// the drawn rectangle is empty.
    fn debug_assert_empty_outside_drawn(&self) {
        if cfg!(debug_assertions)
            && self.samples.len() == self.grid.width as usize * self.band.height() as usize
        {
            let w = self.grid.width.max(1) as usize;
            for (i, s) in self.samples.iter().enumerate() {
                let (x, y) = ((i % w) as u32, (i / w) as u32 + self.band.y0);
                let inside = self.drawn.columns(y).contains(&(x as usize));
                debug_assert!(
                    inside || s.is_none(),
                    "sample ({x}, {y}) drawn outside {:?}",
                    self.drawn
                );
            }
        }
    }

    /// The samples and depths held, to split into bands of rows
    /// ([`Target::of_band`]).
    pub(crate) fn parts_mut(&mut self) -> (&mut [Option<Lin>], &mut [f32]) {
        (&mut self.samples, &mut self.depth)
    }

    /// The samples held, to draw into: every row held, widening the drawn
    /// rectangle as they are written.
    pub(crate) fn target(&mut self) -> Target<'_> {
        Target {
            grid: self.grid,
            band: self.band,
            samples: &mut self.samples,
            depth: &mut self.depth,
            drawn: &mut self.drawn,
        }
    }

    /// What the blitters read: the samples held and where anything was
    /// drawn.
    pub(crate) fn view(&self) -> View<'_> {
        View {
            grid: self.grid,
            band: self.band,
            samples: &self.samples,
            drawn: self.drawn,
        }
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
        self.touch(Rect::at(x, y));
        self.samples[i] = Some(c);
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

/// Samples to draw into: a framebuffer's rows, or one band of them, with
/// the rectangle that holds everything drawn. The fill stage writes
/// through it; a frame drawn in bands gives each thread one band's target
/// of the one framebuffer.
#[derive(Debug)]
pub(crate) struct Target<'a> {
    grid: Grid,
    band: Band,
    samples: &'a mut [Option<Lin>],
    depth: &'a mut [f32],
    drawn: &'a mut Rect,
}

impl<'a> Target<'a> {
    /// Band `band` of `grid`'s rows, split off a framebuffer's
    /// [`Framebuffer::parts_mut`] (the samples and depths of those rows,
    /// row by row from the bottom), widening `drawn` as it is written.
    pub(crate) fn of_band(
        grid: Grid,
        band: Band,
        samples: &'a mut [Option<Lin>],
        depth: &'a mut [f32],
        drawn: &'a mut Rect,
    ) -> Target<'a> {
        let len = grid.width as usize * band.height() as usize;
        assert!(samples.len() == len && depth.len() == len);
        Target {
            grid,
            band,
            samples,
            depth,
            drawn,
        }
    }

    /// The sample grid.
    #[inline(always)]
    pub(crate) fn grid(&self) -> Grid {
        self.grid
    }

    /// The rows held.
    #[inline(always)]
    pub(crate) fn band(&self) -> Band {
        self.band
    }

    /// The same target, borrowed for a while.
    #[inline(always)]
    pub(crate) fn reborrow(&mut self) -> Target<'_> {
        Target {
            grid: self.grid,
            band: self.band,
            samples: self.samples,
            depth: self.depth,
            drawn: self.drawn,
        }
    }

    /// What the blitters read of it.
    pub(crate) fn view(&self) -> View<'_> {
        View {
            grid: self.grid,
            band: self.band,
            samples: self.samples,
            drawn: *self.drawn,
        }
    }

    /// Widens the drawn rectangle by `r`: for a caller that wrote the
    /// samples of `r` by index ([`Target::split_mut`]).
    #[inline(always)]
    pub(crate) fn touch(&mut self, r: Rect) {
        *self.drawn = self.drawn.union(r);
    }

    /// Where each sample is, and the samples and depths, for the fill
    /// stage's loops to test and write directly (locals in a loop keep
    /// their pointers in registers, where a struct's are loaded again for
    /// every sample).
    #[inline(always)]
    pub(crate) fn split_mut(&mut self) -> (At, &mut [Option<Lin>], &mut [f32]) {
        let at = At {
            width: self.grid.width as usize,
            y0: self.band.y0,
        };
        (at, self.samples, self.depth)
    }
}

/// Where sample `(x, y)` of a [`Target`] is stored: rows from the bottom,
/// the first row held at index 0.
#[derive(Clone, Copy, Debug)]
pub(crate) struct At {
    width: usize,
    y0: u32,
}

impl At {
    /// The index of sample `(x, y)`, one of the rows held.
    #[inline(always)]
    pub(crate) fn of(self, x: u32, y: u32) -> usize {
        debug_assert!(y >= self.y0 && (x as usize) < self.width);
        (y - self.y0) as usize * self.width + x as usize
    }
}

/// Samples as the blitters read them: a framebuffer's rows, or one band
/// of them, and the rectangle outside which every sample is empty.
#[derive(Clone, Copy, Debug)]
pub(crate) struct View<'a> {
    grid: Grid,
    band: Band,
    samples: &'a [Option<Lin>],
    drawn: Rect,
}

impl<'a> View<'a> {
    /// The sample grid.
    pub(crate) fn grid(&self) -> Grid {
        self.grid
    }

    /// The rows held.
    pub(crate) fn band(&self) -> Band {
        self.band
    }

    /// Every sample outside it is empty.
    pub(crate) fn drawn(&self) -> Rect {
        self.drawn
    }

    /// Sample row `y` (y up), one of those held.
    #[inline(always)]
    pub(crate) fn row(&self, y: u32) -> &'a [Option<Lin>] {
        let w = self.grid.width as usize;
        let i = (y - self.band.y0) as usize * w;
        &self.samples[i..i + w]
    }
}

/// Sets every element of `s` to `v`, eight at a time (`fill` of an
/// `Option` stores one tag at a time).
#[inline(always)]
fn clear<T: Copy>(s: &mut [T], v: T) {
    let mut chunks = s.chunks_exact_mut(8);
    for c in &mut chunks {
        c.copy_from_slice(&[v; 8]);
    }
    chunks.into_remainder().fill(v);
}
