//! Stage 6: blitters, from a cell's samples to one glyph and its colours.
//!
//! A [`GlyphMode`] fixes how many samples a cell holds (`w × h`) and how
//! they become a [`Cell`]. Blitters know nothing of ANSI: they produce
//! characters and 24-bit sRGB colours; the encoder decides how to send
//! them. Samples are linear light: the split and the means below add light
//! as the eye does, and each cell's colours are encoded to sRGB once, here. The glyph tables live in [`glyphs`], which draws each one's bit
//! layout: sample `i` of a cell is column `i % w`, row `i / w` counted from
//! the top.
//!
//! **Two colours per cell** (half, quadrant, sextant, octant). A cell of one
//! colour is a space on that background. A cell of two colours is split
//! exactly. A cell of more (an edge between two shaded faces, a smooth
//! gradient) is split into a foreground set and a background set so as to
//! minimise the squared colour error, each side drawn in its mean: every
//! split is tried (at most 2^7 = 128 for 8 samples, stepped in Gray-code
//! order so that each try updates the sums by one sample). Of the two ways
//! to draw a split (a pattern or its complement with the colours swapped)
//! the one whose background is the scene's background is taken, else the
//! one whose background covers more samples, so that runs of cells share
//! colours and the encoder writes fewer SGR sequences.
//!
//! Undrawn samples show the scene's background; where the scene has none
//! they keep the terminal's own, which only a cell's background can show,
//! so the drawn samples become the foreground (in their mean colour).
//!
//! **Braille** is one colour per cell: dots where the samples differ from
//! the background, in the mean of their colours.
//!
//! **Without colour** ([`ColorDepth::None`]) the glyph alone carries the
//! picture: the sub-cell modes draw the drawn samples' pattern, `block`
//! picks a shade from ` ░▒▓█` and `ascii` a character from
//! ` .:-=+*#%@`, both by brightness; any drawn sample gets at least the
//! first non-blank step, so a dark triangle still shows.
//!
//! **Speed.** Every cell of every frame passes here (300,000 at 1000×300
//! cells), so the commonest case, half blocks in colour with the
//! exhaustive split, has a loop of its own that reads a cell's two samples
//! from two rows side by side and writes the cell out without the general
//! path's dispatch; a property test keeps it equal to the general path.
//! Without a scene background, the runs of cells whose two samples are both
//! undrawn (most of a frame around a model) are found by the samples' tags
//! alone and filled with blanks at once. Cells outside
//! the framebuffer's drawn rectangle show undrawn samples only: they are
//! all one cell, found once (the mode's own cell of undrawn samples) and
//! written row by row without reading a sample, and the frame is told so
//! for the encoder ([`Frame::known`]).

pub mod glyphs;
mod support;

pub use support::{GlyphFamily, GlyphSupport};

use crate::color::{ColorDepth, Lin, Rgb};
use crate::frame::{Cell, Known};
use crate::framebuffer::View;
use crate::transform::{Grid, Rect};

/// How samples become glyphs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum GlyphMode {
    /// 1×1: a character of a brightness ramp.
    Ascii,
    /// 1×1: the whole cell in one colour.
    Block,
    /// 1×2: `▀ ▄ █` and space, foreground and background.
    #[default]
    Half,
    /// 2×2: the quadrant block elements.
    Quadrant,
    /// 2×3: the Unicode 13 sextants.
    Sextant,
    /// 2×4: the Unicode 16 octants.
    Octant,
    /// 2×4: braille dots, one colour per cell.
    Braille,
}

crate::choice::choice!(GlyphMode {
    Ascii => "ascii": "1×1: a character of a brightness ramp",
    Block => "block": "1×1: the whole cell in one colour",
    Half => "half": "1×2: `▀ ▄ █` and space, foreground and background",
    Quadrant => "quadrant": "2×2: the quadrant block elements",
    Sextant => "sextant": "2×3: the Unicode 13 sextants",
    Octant => "octant": "2×4: the Unicode 16 octants",
    Braille => "braille": "2×4: braille dots, one colour per cell",
});

impl GlyphMode {
    /// Samples per cell, `(w, h)`.
    pub const fn cell_size(self) -> (u32, u32) {
        match self {
            GlyphMode::Ascii | GlyphMode::Block => (1, 1),
            GlyphMode::Half => (1, 2),
            GlyphMode::Quadrant => (2, 2),
            GlyphMode::Sextant => (2, 3),
            GlyphMode::Octant | GlyphMode::Braille => (2, 4),
        }
    }

    /// Samples per cell.
    pub const fn samples(self) -> usize {
        let (w, h) = self.cell_size();
        (w * h) as usize
    }

    /// The sample grid behind `cols × rows` cells.
    pub fn grid(self, cols: u16, rows: u16) -> Grid {
        let (w, h) = self.cell_size();
        Grid::new(cols as u32 * w, rows as u32 * h)
    }

    /// The glyph for a pattern of foreground samples.
    pub fn glyph(self, mask: u8) -> char {
        match self {
            GlyphMode::Half => glyphs::HALF[(mask & 3) as usize],
            GlyphMode::Quadrant => glyphs::QUADRANT[(mask & 15) as usize],
            GlyphMode::Sextant => glyphs::sextant(mask),
            GlyphMode::Octant => glyphs::octant(mask),
            GlyphMode::Braille => glyphs::braille(mask),
            GlyphMode::Ascii | GlyphMode::Block => {
                if mask & 1 == 0 {
                    ' '
                } else {
                    '█'
                }
            }
        }
    }

    /// The pattern of foreground samples a glyph of this mode draws (the
    /// inverse of [`GlyphMode::glyph`]); `None` for a character the mode
    /// does not draw with. A search: for tools, not for frames.
    pub fn pattern(self, ch: char) -> Option<u8> {
        let n = self.samples();
        let masks = 0..=((1u16 << n) - 1) as u8;
        match self {
            GlyphMode::Ascii | GlyphMode::Block => None,
            _ => masks.into_iter().find(|&m| self.glyph(m) == ch),
        }
    }

    /// One cell from its samples (see the module doc for their order), with
    /// the exact two-colour split.
    pub fn cell(self, samples: &[Option<Lin>], depth: ColorDepth, background: Option<Lin>) -> Cell {
        self.cell_split(samples, depth, background, Split::Exhaustive)
    }

    /// One cell, its two colours split by `split`.
    pub fn cell_split(
        self,
        samples: &[Option<Lin>],
        depth: ColorDepth,
        background: Option<Lin>,
        split: Split,
    ) -> Cell {
        let n = samples.len();
        debug_assert_eq!(n, self.samples());
        let drawn = samples
            .iter()
            .enumerate()
            .fold(0u8, |m, (i, s)| m | ((s.is_some() as u8) << i));
        if !depth.has_color() {
            let ch = match self {
                GlyphMode::Ascii => {
                    samples[0].map_or(' ', |c| ramp(&glyphs::ASCII_RAMP, c.to_srgb()))
                }
                GlyphMode::Block => {
                    samples[0].map_or(' ', |c| ramp(&glyphs::SHADE_RAMP, c.to_srgb()))
                }
                _ => self.glyph(drawn),
            };
            return Cell {
                ch,
                fg: None,
                bg: None,
            };
        }
        match self {
            GlyphMode::Ascii => match samples[0] {
                None => blank(background),
                Some(c) => {
                    let c = c.to_srgb();
                    Cell {
                        ch: ramp(&glyphs::ASCII_RAMP, c),
                        fg: Some(c),
                        bg: encode(background),
                    }
                }
            },
            GlyphMode::Block => blank(samples[0].or(background)),
            GlyphMode::Braille => {
                let mut dots = 0u8;
                let mut sum = Sum::default();
                for (i, s) in samples.iter().enumerate() {
                    if let Some(c) = s.filter(|&c| Some(c) != background) {
                        dots |= 1 << i;
                        sum.add(c);
                    }
                }
                if dots == 0 {
                    blank(background)
                } else {
                    Cell {
                        ch: self.glyph(dots),
                        fg: Some(sum.mean().to_srgb()),
                        bg: encode(background),
                    }
                }
            }
            GlyphMode::Half | GlyphMode::Quadrant | GlyphMode::Sextant | GlyphMode::Octant => {
                self.two_colour(samples, drawn, background, split)
            }
        }
    }

    fn two_colour(
        self,
        samples: &[Option<Lin>],
        drawn: u8,
        background: Option<Lin>,
        how: Split,
    ) -> Cell {
        let n = samples.len();
        let full = ((1u16 << n) - 1) as u8;
        let Some(bg_color) = background.or(if drawn == full { samples[0] } else { None }) else {
            // No scene background and some samples undrawn: those keep the
            // terminal's default, the drawn ones are the foreground.
            if drawn == 0 {
                return Cell::BLANK;
            }
            let mut sum = Sum::default();
            samples.iter().flatten().for_each(|&c| sum.add(c));
            return Cell {
                ch: self.glyph(drawn),
                fg: Some(sum.mean().to_srgb()),
                bg: None,
            };
        };
        let mut colors = [Lin::BLACK; 8];
        for (c, s) in colors.iter_mut().zip(samples) {
            *c = s.unwrap_or(bg_color);
        }
        let colors = &colors[..n];
        if n == 2 && how == Split::Exhaustive {
            return half(colors[0], colors[1], background);
        }
        let mask = match how {
            Split::Exhaustive => split(colors),
            Split::WidestChannel => split_widest_channel(colors),
        };
        if mask == 0 {
            return blank(Some(colors[0]));
        }
        let (mut fg_sum, mut bg_sum) = (Sum::default(), Sum::default());
        for (i, &c) in colors.iter().enumerate() {
            if mask >> i & 1 == 1 {
                fg_sum.add(c)
            } else {
                bg_sum.add(c)
            }
        }
        let (fg, bg) = (fg_sum.mean().to_srgb(), bg_sum.mean().to_srgb());
        if fg == bg {
            return Cell {
                ch: ' ',
                fg: None,
                bg: Some(bg),
            };
        }
        // Orientation: the scene's background stays the cell's background;
        // otherwise the larger side is.
        let in_fg = background.is_some_and(|b| {
            colors
                .iter()
                .enumerate()
                .any(|(i, &c)| c == b && mask >> i & 1 == 1)
        });
        let in_bg = background.is_some_and(|b| {
            colors
                .iter()
                .enumerate()
                .any(|(i, &c)| c == b && mask >> i & 1 == 0)
        });
        let swap = match (in_fg, in_bg) {
            (true, false) => true,
            (false, true) => false,
            _ => fg_sum.n > bg_sum.n,
        };
        if swap {
            Cell {
                ch: self.glyph(!mask & full),
                fg: Some(bg),
                bg: Some(fg),
            }
        } else {
            Cell {
                ch: self.glyph(mask),
                fg: Some(fg),
                bg: Some(bg),
            }
        }
    }
}

/// A half-block cell of two colours, top and bottom, written out: what
/// [`GlyphMode::two_colour`]'s general path decides for two samples,
/// without its sums.
#[inline(always)]
fn half(top: Lin, bottom: Lin, background: Option<Lin>) -> Cell {
    let (t, b) = (top.to_srgb(), bottom.to_srgb());
    if t == b {
        blank(Some(top))
    } else if background == Some(bottom) {
        Cell {
            ch: '▀',
            fg: Some(t),
            bg: Some(b),
        }
    } else {
        Cell {
            ch: '▄',
            fg: Some(b),
            bg: Some(t),
        }
    }
}

/// A blank cell in `bg`, encoded.
fn blank(bg: Option<Lin>) -> Cell {
    Cell {
        ch: ' ',
        fg: None,
        bg: encode(bg),
    }
}

/// A colour encoded to sRGB, for the frame.
#[inline]
fn encode(c: Option<Lin>) -> Option<Rgb> {
    c.map(Lin::to_srgb)
}

/// A running sum of linear colours.
#[derive(Clone, Copy, Debug, Default)]
struct Sum {
    rgb: [u32; 3],
    n: u32,
}

impl Sum {
    fn add(&mut self, c: Lin) {
        for (s, v) in self.rgb.iter_mut().zip(c.0) {
            *s += v as u32;
        }
        self.n += 1;
    }

    /// The rounded mean.
    fn mean(&self) -> Lin {
        let n = self.n.max(1);
        Lin(self.rgb.map(|s| ((s + n / 2) / n) as u16))
    }
}

/// The split of `colors` into a foreground set (the returned mask) and a
/// background set that minimises the total squared distance (in linear
/// light) of each colour to its set's mean. 0 when all colours are equal.
/// Exhaustive: the exact answer, in integers (8 × 65535 summed and squared
/// fits an i64 with room).
pub fn split(colors: &[Lin]) -> u8 {
    let n = colors.len();
    let first = colors[0];
    let Some(other) = colors.iter().copied().find(|&c| c != first) else {
        return 0;
    };
    if colors.iter().all(|&c| c == first || c == other) {
        // Two colours: the split is exact.
        return colors
            .iter()
            .enumerate()
            .fold(0, |m, (i, &c)| m | (((c == other) as u8) << i));
    }
    // Minimising the squared error is maximising |S_fg|²/n_fg + |S_bg|²/n_bg
    // (the sum of all |c|² is fixed). The last sample stays in the
    // background (a split and its complement are the same split), and
    // Gray-code order changes one sample per step.
    let total = colors.iter().fold([0i64; 3], |mut s, c| {
        for (a, v) in s.iter_mut().zip(c.0) {
            *a += v as i64;
        }
        s
    });
    let mut fg = [0i64; 3];
    let mut n_fg = 0i64;
    let mut mask = 0u8;
    let (mut best, mut best_num, mut best_den) = (0u8, -1i64, 1i64);
    for k in 1u32..(1 << (n - 1)) {
        // Gray code k ^ (k >> 1) differs from the previous one in the bit of
        // k's lowest set bit.
        let bit = k.trailing_zeros() as usize;
        let c = colors[bit].0;
        if mask >> bit & 1 == 0 {
            mask |= 1 << bit;
            n_fg += 1;
            (0..3).for_each(|i| fg[i] += c[i] as i64);
        } else {
            mask &= !(1 << bit);
            n_fg -= 1;
            (0..3).for_each(|i| fg[i] -= c[i] as i64);
        }
        let n_bg = n as i64 - n_fg;
        let sq = |s: [i64; 3]| s[0] * s[0] + s[1] * s[1] + s[2] * s[2];
        let bg = [total[0] - fg[0], total[1] - fg[1], total[2] - fg[2]];
        // score = sq(fg)/n_fg + sq(bg)/n_bg = num/den.
        let num = sq(fg) * n_bg + sq(bg) * n_fg;
        let den = n_fg * n_bg;
        if num * best_den > best_num * den {
            (best, best_num, best_den) = (mask, num, den);
        }
    }
    best
}

/// How a cell of more than two colours is split into two.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Split {
    /// Every split tried: the least squared error (at most 128 tries).
    #[default]
    Exhaustive,
    /// chafa's fast path: the channel with the widest range, cut at its
    /// mean.
    WidestChannel,
}

crate::choice::choice!(Split {
    Exhaustive => "exhaustive": "Every split tried: the least squared error (at most 128 tries)",
    WidestChannel => "widest-channel": "chafa's fast path: the channel with the widest range, cut at its mean",
});

/// The cheaper split: samples above the mean of the widest channel are the
/// foreground. 0 when all colours are equal.
pub fn split_widest_channel(colors: &[Lin]) -> u8 {
    let (lo, hi) = colors
        .iter()
        .fold(([u16::MAX; 3], [0u16; 3]), |(lo, hi), c| {
            (
                std::array::from_fn(|k| lo[k].min(c.0[k])),
                std::array::from_fn(|k| hi[k].max(c.0[k])),
            )
        });
    let k = (0..3).max_by_key(|&k| hi[k] - lo[k]).unwrap_or(0);
    if hi[k] == lo[k] {
        return 0;
    }
    let mean = colors.iter().map(|c| c.0[k] as u32).sum::<u32>() as f32 / colors.len() as f32;
    colors
        .iter()
        .enumerate()
        .fold(0, |m, (i, c)| m | (((c.0[k] as f32 > mean) as u8) << i))
}

/// The ramp step for a drawn sample: never the blank first step.
fn ramp(steps: &[char], c: Rgb) -> char {
    let top = (steps.len() - 2) as f32;
    steps[1 + (c.luma() * top).round() as usize]
}

/// The cells (columns, and rows from the top of the frame) that show a
/// sample of `fb`'s drawn rectangle in `mode`: every
/// other cell shows undrawn samples only.
pub(crate) fn drawn_cells(fb: View<'_>, mode: GlyphMode) -> Rect {
    let d = fb.drawn();
    let grid = fb.grid();
    let d = d.intersect(Rect::all(grid.width, grid.height));
    if d.is_empty() {
        return Rect::EMPTY;
    }
    let (w, h) = mode.cell_size();
    let (cols, rows) = (grid.width / w, grid.height / h);
    // Sample row y shows in cell row (H − 1 − y) / h, counted from the top.
    let r = Rect {
        x0: d.x0 / w,
        x1: (d.x1 - 1) / w + 1,
        y0: (grid.height - d.y1) / h,
        y1: (grid.height - 1 - d.y0) / h + 1,
    };
    r.intersect(Rect::all(cols, rows))
}

/// [`blit`] of the cell rows whose samples `fb` holds (a band of whole
/// cell rows) into `cells`, those rows' cells,
/// top row first. Cells that show no drawn sample (outside
/// [`drawn_cells`]) are all the same cell, written at once; returns what
/// that says of the frame's cells.
pub(crate) fn blit_band(
    fb: View<'_>,
    mode: GlyphMode,
    depth: ColorDepth,
    background: Option<Rgb>,
    split: Split,
    cells: &mut [Cell],
) -> Known {
    let blank_when_uniform =
        depth.has_color() && !matches!(mode, GlyphMode::Ascii | GlyphMode::Braille);
    let args = (
        fb,
        mode,
        depth,
        background.map(Lin::from_srgb),
        split,
        blank_when_uniform,
    );
    let drawn = drawn_cells(fb, mode);
    let fill = if mode == GlyphMode::Half && depth.has_color() && split == Split::Exhaustive {
        blit_half(fb, depth, background.map(Lin::from_srgb), drawn, cells)
    } else {
        // One copy of the loop per cell size, so that gathering a cell's
        // samples is constant indexing.
        match mode.cell_size() {
            (1, 1) => blit_cells::<1, 1>(args, drawn, cells),
            (1, 2) => blit_cells::<1, 2>(args, drawn, cells),
            (2, 2) => blit_cells::<2, 2>(args, drawn, cells),
            (2, 3) => blit_cells::<2, 3>(args, drawn, cells),
            _ => blit_cells::<2, 4>(args, drawn, cells),
        }
    };
    Known { rect: drawn, fill }
}

/// Calls `cell` for each of `drawn`'s cells of the band's rows, `out` being
/// the row's cells from the top (row `first + i` of the frame) and the
/// range its cells in `drawn`, after filling the rest of the row with
/// `fill`.
#[inline(always)]
fn rows_drawn(
    cells: &mut [Cell],
    cols: usize,
    first: usize,
    drawn: Rect,
    fill: Cell,
    mut row: impl FnMut(usize, &mut [Cell], std::ops::Range<usize>),
) {
    for (i, out) in cells.chunks_exact_mut(cols).enumerate() {
        let span = drawn.columns((first + i) as u32);
        if span.is_empty() {
            out.fill(fill);
            continue;
        }
        out[..span.start].fill(fill);
        out[span.end..].fill(fill);
        row(i, out, span);
    }
}

type BlitArgs<'a> = (View<'a>, GlyphMode, ColorDepth, Option<Lin>, Split, bool);

/// [`blit_cells`] of half blocks in colour with the exhaustive split, the
/// commonest cells written out: each cell reads its two samples from two
/// rows side by side, and a cell of two drawn colours (or one on the
/// scene's background) is [`half`] without the general path's dispatch.
/// The same cells (a test compares every case with the general path).
/// Returns the cell of two undrawn samples, written outside `drawn`.
fn blit_half(
    fb: View<'_>,
    depth: ColorDepth,
    background: Option<Lin>,
    drawn: Rect,
    cells: &mut [Cell],
) -> Cell {
    let fill = half_cell(None, None, background, depth);
    let (grid, band) = (fb.grid(), fb.band());
    let cols = grid.width as usize;
    if cols == 0 {
        return fill;
    }
    let first = (grid.height - band.y1) as usize / 2;
    rows_drawn(cells, cols, first, drawn, fill, |i, out, span| {
        let top = grid.height - 1 - ((first + i) * 2) as u32;
        let (upper, lower) = (&fb.row(top)[span.clone()], &fb.row(top - 1)[span.clone()]);
        let out = &mut out[span];
        if background.is_none() {
            blit_half_runs(upper, lower, depth, out);
            return;
        }
        for ((cell, &t), &b) in out.iter_mut().zip(upper).zip(lower) {
            *cell = half_cell(t, b, background, depth);
        }
    });
    fill
}

/// A row of [`blit_half`] without a scene background: runs of cells whose
/// two samples are both undrawn (most of a frame around a model) are
/// found by their tags alone and filled with blanks at once.
#[inline(always)]
fn blit_half_runs(
    upper: &[Option<Lin>],
    lower: &[Option<Lin>],
    depth: ColorDepth,
    out: &mut [Cell],
) {
    let n = out.len().min(upper.len()).min(lower.len());
    let (upper, lower, out) = (&upper[..n], &lower[..n], &mut out[..n]);
    let mut x = 0;
    while x < n {
        let empty = upper[x..]
            .iter()
            .zip(&lower[x..])
            .take_while(|(t, b)| t.is_none() && b.is_none())
            .count();
        out[x..x + empty].fill(Cell::BLANK);
        x += empty;
        while x < n && (upper[x].is_some() || lower[x].is_some()) {
            out[x] = half_cell(upper[x], lower[x], None, depth);
            x += 1;
        }
    }
}

/// The half-block cell of samples `t` over `b` (see [`blit_half`]).
#[inline(always)]
fn half_cell(t: Option<Lin>, b: Option<Lin>, background: Option<Lin>, depth: ColorDepth) -> Cell {
    if t == b {
        return blank(t.or(background));
    }
    match (t.or(background), b.or(background)) {
        (Some(t), Some(b)) => half(t, b, background),
        // No scene background, one sample undrawn.
        _ => GlyphMode::Half.cell_split(&[t, b], depth, None, Split::Exhaustive),
    }
}

/// Blits the cells of `drawn` cell by cell, and fills the rest with the
/// cell of undrawn samples, which it returns.
fn blit_cells<const W: usize, const H: usize>(
    (fb, mode, depth, background, split, blank_when_uniform): BlitArgs,
    drawn: Rect,
    cells: &mut [Cell],
) -> Cell {
    // Most cells are one colour (or all background): in the modes that
    // draw such a cell as a blank, no split, no glyph table.
    let cell = |samples: &[Option<Lin>]| {
        let first = samples[0];
        if blank_when_uniform && samples[1..].iter().all(|&s| s == first) {
            blank(first.or(background))
        } else {
            mode.cell_split(samples, depth, background, split)
        }
    };
    let fill = cell(&[None; 8][..W * H]);
    let (grid, band) = (fb.grid(), fb.band());
    let cols = grid.width as usize / W;
    if cols == 0 {
        return fill;
    }
    // The band's cell rows, counted from the top of the frame.
    let first = (grid.height - band.y1) as usize / H;
    let mut samples = [None; 8];
    rows_drawn(cells, cols, first, drawn, fill, |i, out, span| {
        // The cell's sample rows, top first.
        let top = grid.height as usize - 1 - (first + i) * H;
        let lines: [&[Option<Lin>]; H] = std::array::from_fn(|dy| fb.row((top - dy) as u32));
        for col in span {
            let x = col * W;
            for (i, s) in samples[..W * H].iter_mut().enumerate() {
                *s = lines[i / W][x + i % W];
            }
            out[col] = cell(&samples[..W * H]);
        }
    });
    fill
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::choice::Choice;
    use crate::frame::Frame;
    use crate::framebuffer::Framebuffer;

    /// `fb` into `frame` (resized to fit), cell by cell, as the renderer's
    /// output does.
    fn blit(
        fb: &Framebuffer,
        mode: GlyphMode,
        depth: ColorDepth,
        background: Option<Rgb>,
        split: Split,
        frame: &mut Frame,
    ) {
        let (w, h) = mode.cell_size();
        let grid = fb.grid();
        frame.resize((grid.width / w) as u16, (grid.height / h) as u16);
        let known = blit_band(fb.view(), mode, depth, background, split, frame.cells_mut());
        frame.set_known(known);
    }

    const RED: Rgb = Rgb::new(255, 0, 0);
    const BLUE: Rgb = Rgb::new(0, 0, 255);
    /// The same in linear light, as samples hold them.
    const L_RED: Lin = Lin([65535, 0, 0]);
    const L_BLUE: Lin = Lin([0, 0, 65535]);
    const L_BLACK: Option<Lin> = Some(Lin::BLACK);

    proptest::proptest! {
        /// Half blocks written out give the cells the general path gives:
        /// random samples of a few colours, some undrawn, with and without
        /// a scene background, in a band of rows or the whole grid.
        #[test]
        fn half_blocks_written_out_are_the_general_path(
            picks in proptest::collection::vec(0usize..5, 4 * 6),
            background in proptest::option::of(0usize..4),
            banded: bool,
        ) {
            let palette = [L_RED, L_BLUE, Lin::BLACK, Lin([100, 200, 300])];
            let grid = Grid::new(4, 6);
            let band = if banded { crate::transform::Band { y0: 2, y1: 4 } } else { grid.all_rows() };
            let mut fb = Framebuffer::new(grid);
            fb.reset_band(grid, band, false);
            for y in band.y0..band.y1 {
                for x in 0..grid.width {
                    if let Some(&c) = palette.get(picks[(y * grid.width + x) as usize]) {
                        fb.set(x, y, c);
                    }
                }
            }
            let background = background.map(|i| palette[i].to_srgb());
            let rows = ((band.y1 - band.y0) / 2) as usize;
            let (mut fast, mut general) = (vec![Cell::BLANK; 4 * rows], vec![Cell::BLANK; 4 * rows]);
            for depth in [ColorDepth::TrueColor, ColorDepth::Ansi256] {
                blit_band(fb.view(), GlyphMode::Half, depth, background, Split::Exhaustive, &mut fast);
                let args = (fb.view(), GlyphMode::Half, depth, background.map(Lin::from_srgb), Split::Exhaustive, true);
                blit_cells::<1, 2>(args, Rect::all(4, 3), &mut general);
                proptest::prop_assert_eq!(&fast, &general);
            }
        }
    }

    #[test]
    fn pattern_inverts_glyph() {
        for mode in [
            GlyphMode::Half,
            GlyphMode::Quadrant,
            GlyphMode::Sextant,
            GlyphMode::Octant,
            GlyphMode::Braille,
        ] {
            for m in 0..=((1u16 << mode.samples()) - 1) as u8 {
                assert_eq!(mode.pattern(mode.glyph(m)), Some(m), "{mode:?} {m:#x}");
            }
        }
        assert_eq!(GlyphMode::Half.pattern('x'), None);
    }

    #[test]
    fn ramps_skip_blank_for_drawn_samples() {
        assert_eq!(ramp(&glyphs::ASCII_RAMP, Rgb::BLACK), '.');
        assert_eq!(ramp(&glyphs::ASCII_RAMP, Rgb::WHITE), '@');
        assert_eq!(ramp(&glyphs::SHADE_RAMP, Rgb::BLACK), '░');
        assert_eq!(ramp(&glyphs::SHADE_RAMP, Rgb::WHITE), '█');
    }

    #[test]
    fn terminal_row_zero_shows_the_top_sample_row() {
        let mut fb = Framebuffer::new(Grid::new(2, 3));
        fb.set(0, 2, Lin::WHITE); // top-left
        fb.set(1, 0, Lin::WHITE); // bottom-right
        let mut frame = Frame::default();
        blit(
            &fb,
            GlyphMode::Ascii,
            ColorDepth::None,
            None,
            Split::Exhaustive,
            &mut frame,
        );
        assert_eq!(frame.to_string(), "@ \n  \n @\n");
        // Half blocks: the top sample of the cell is bit 0.
        let mut fb = Framebuffer::new(Grid::new(1, 4));
        fb.set(0, 3, Lin::WHITE);
        fb.set(0, 0, Lin::WHITE);
        blit(
            &fb,
            GlyphMode::Half,
            ColorDepth::None,
            None,
            Split::Exhaustive,
            &mut frame,
        );
        assert_eq!(frame.to_string(), "▀\n▄\n");
    }

    #[test]
    fn blit_agrees_with_cell_in_every_mode() {
        let red = Some(L_RED);
        for &mode in GlyphMode::ALL {
            for depth in [ColorDepth::None, ColorDepth::TrueColor] {
                for background in [None, Some(Rgb::BLACK)] {
                    let grid = mode.grid(3, 2);
                    let mut fb = Framebuffer::new(grid);
                    // Column 0 full, column 1 half, column 2 empty.
                    for y in 0..grid.height {
                        let (w, _) = mode.cell_size();
                        for x in 0..w {
                            fb.set(x, y, L_RED);
                            if y % 2 == 0 {
                                fb.set(w + x, y, L_BLUE);
                            }
                        }
                    }
                    let mut frame = Frame::default();
                    blit(&fb, mode, depth, background, Split::Exhaustive, &mut frame);
                    let n = mode.samples();
                    let full = vec![red; n];
                    let background = background.map(Lin::from_srgb);
                    assert_eq!(
                        frame.get(0, 0),
                        mode.cell(&full, depth, background),
                        "{mode:?} {depth:?}"
                    );
                    assert_eq!(
                        frame.get(2, 0),
                        mode.cell(&vec![None; n], depth, background),
                        "{mode:?} {depth:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn one_sample_modes_put_colour_on_the_right_plane() {
        let (bg, black) = (L_BLACK, Some(Rgb::BLACK));
        let block = GlyphMode::Block.cell(&[Some(L_RED)], ColorDepth::TrueColor, bg);
        assert_eq!(
            block,
            Cell {
                ch: ' ',
                fg: None,
                bg: Some(RED)
            }
        );
        let ascii = GlyphMode::Ascii.cell(&[Some(L_RED)], ColorDepth::TrueColor, bg);
        assert_eq!((ascii.fg, ascii.bg), (Some(RED), black));
        let empty = GlyphMode::Block.cell(&[None], ColorDepth::TrueColor, bg);
        assert_eq!(
            empty,
            Cell {
                ch: ' ',
                fg: None,
                bg: black
            }
        );
        let plain = GlyphMode::Ascii.cell(&[Some(L_RED)], ColorDepth::None, bg);
        assert_eq!((plain.fg, plain.bg), (None, None));
    }

    #[test]
    fn the_half_block_shortcut_agrees_with_the_general_split() {
        // The general path, reached through the widest-channel split's
        // sibling: an exhaustive split of two colours, taken the long way
        // round by a quadrant cell whose columns repeat them.
        let colors = [Lin::BLACK, Lin::WHITE, L_RED, L_BLUE, Lin([10, 20000, 300])];
        for &a in &colors {
            for &b in &colors {
                for bg in [None, L_BLACK, Some(L_RED)] {
                    let half = GlyphMode::Half.cell(&[Some(a), Some(b)], ColorDepth::TrueColor, bg);
                    let quad = GlyphMode::Quadrant.cell(
                        &[Some(a), Some(a), Some(b), Some(b)],
                        ColorDepth::TrueColor,
                        bg,
                    );
                    // ▀ is quadrant mask 0b0011, ▄ is 0b1100: the same picture.
                    let as_quad = |c: Cell| match c.ch {
                        '▀' => Cell { ch: '▀', ..c },
                        '▄' => Cell { ch: '▄', ..c },
                        _ => c,
                    };
                    assert_eq!(as_quad(half), quad, "{a:?} over {b:?}, background {bg:?}");
                }
            }
        }
    }

    #[test]
    fn half_blocks_two_colours_and_one() {
        let (bg, black) = (L_BLACK, Some(Rgb::BLACK));
        let c = GlyphMode::Half.cell(&[Some(L_RED), None], ColorDepth::TrueColor, bg);
        assert_eq!(
            c,
            Cell {
                ch: '▀',
                fg: Some(RED),
                bg: black
            }
        );
        let c = GlyphMode::Half.cell(&[None, Some(L_RED)], ColorDepth::TrueColor, bg);
        assert_eq!(
            c,
            Cell {
                ch: '▄',
                fg: Some(RED),
                bg: black
            }
        );
        let c = GlyphMode::Half.cell(&[Some(L_RED), Some(L_RED)], ColorDepth::TrueColor, bg);
        assert_eq!(c, blank(Some(L_RED)));
        let c = GlyphMode::Half.cell(&[Some(L_RED), Some(L_BLUE)], ColorDepth::TrueColor, bg);
        assert!(
            c == Cell {
                ch: '▀',
                fg: Some(RED),
                bg: Some(BLUE)
            } || c
                == Cell {
                    ch: '▄',
                    fg: Some(BLUE),
                    bg: Some(RED)
                }
        );
        // Without a scene background, undrawn samples keep the terminal's.
        let c = GlyphMode::Half.cell(&[None, Some(L_RED)], ColorDepth::TrueColor, None);
        assert_eq!(
            c,
            Cell {
                ch: '▄',
                fg: Some(RED),
                bg: None
            }
        );
        assert_eq!(
            GlyphMode::Half.cell(&[None, None], ColorDepth::TrueColor, None),
            Cell::BLANK
        );
    }

    #[test]
    fn split_is_exact_for_two_colours_and_best_for_more() {
        assert_eq!(split(&[L_RED, L_RED, L_RED, L_RED]), 0);
        assert_eq!(split(&[L_RED, L_BLUE, L_BLUE, L_RED]), 0b0110);
        // Three colours: the two near reds go together.
        let near = Lin([64000, 700, 0]);
        let m = split(&[L_RED, near, L_BLUE, L_BLUE]);
        assert!(m == 0b1100 || m == 0b0011, "{m:#b}");
        // Brute force agrees on a gradient.
        let grad: Vec<Lin> = (0..8u16)
            .map(|i| Lin([i * 8000, 65535 - i * 5000, i * i * 900]))
            .collect();
        let sse = |m: u8| {
            let mut s = [Sum::default(), Sum::default()];
            grad.iter()
                .enumerate()
                .for_each(|(i, &c)| s[(m >> i & 1) as usize].add(c));
            grad.iter()
                .enumerate()
                .map(|(i, c)| {
                    let sum = &s[(m >> i & 1) as usize];
                    (0..3)
                        .map(|k| {
                            let mean = sum.rgb[k] as f64 / sum.n as f64;
                            (c.0[k] as f64 - mean).powi(2)
                        })
                        .sum::<f64>()
                })
                .sum::<f64>()
        };
        let best = (1u8..=255).map(sse).fold(f64::INFINITY, f64::min);
        assert!((sse(split(&grad)) - best).abs() < 1e-9);
    }

    #[test]
    fn braille_is_one_colour_dots_on_the_background() {
        let mut s = [None; 8];
        s[0] = Some(L_RED);
        s[7] = Some(L_BLUE);
        let c = GlyphMode::Braille.cell(&s, ColorDepth::TrueColor, L_BLACK);
        assert_eq!(c.ch, '⢁');
        // Red and blue mixed in light: half of each, #bc00bc.
        assert_eq!(c.fg, Some(Rgb::new(188, 0, 188)));
        assert_eq!(c.bg, Some(Rgb::BLACK));
    }
}
