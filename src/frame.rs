//! The frame: a grid of terminal cells, each one glyph with a foreground and
//! a background colour. The blitters make it, the encoder sends it.
//!
//! Its `Display` is the plain text of the frame, rows top to bottom, each
//! ending in a newline: what `--color none` prints, and what a test
//! snapshots with `insta::assert_snapshot!(frame.to_string())`.

use std::fmt;

use crate::color::Rgb;
use crate::transform::Rect;

/// One terminal cell. `None` colours are the terminal's defaults.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Cell {
    /// The glyph.
    pub ch: char,
    /// The glyph's colour.
    pub fg: Option<Rgb>,
    /// The cell's background.
    pub bg: Option<Rgb>,
}

impl Cell {
    /// A space in the terminal's default colours.
    pub const BLANK: Cell = Cell {
        ch: ' ',
        fg: None,
        bg: None,
    };
}

impl Default for Cell {
    fn default() -> Self {
        Cell::BLANK
    }
}

/// `cols × rows` cells, row 0 at the top of the terminal.
///
/// A frame also knows a rectangle outside which every cell is one and the
/// same: the blitter knows it from where samples were
/// drawn, and the encoder then compares only that rectangle's cells with
/// what the terminal shows. Every way of writing cells keeps it true.
#[derive(Clone, Debug, Default)]
pub struct Frame {
    cols: u16,
    rows: u16,
    cells: Vec<Cell>,
    known: Known,
    /// Whether a cell of one colour may be sent as two halves (`▀`).
    plain: bool,
}

/// Every cell of a [`Frame`] outside `rect` (columns and rows of cells,
/// row 0 at the top) is `fill`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Known {
    pub rect: Rect,
    pub fill: Cell,
}

impl Default for Known {
    fn default() -> Known {
        Known {
            rect: Rect::EMPTY,
            fill: Cell::BLANK,
        }
    }
}

/// The same cells, whatever each frame knows of them.
impl PartialEq for Frame {
    fn eq(&self, o: &Frame) -> bool {
        self.cols == o.cols && self.rows == o.rows && self.cells == o.cells
    }
}

impl Eq for Frame {}

impl Frame {
    /// A blank frame of `cols × rows` cells.
    pub fn new(cols: u16, rows: u16) -> Frame {
        Frame {
            cols,
            rows,
            cells: vec![Cell::BLANK; cols as usize * rows as usize],
            known: Known::default(),
            plain: false,
        }
    }

    /// Whether the frame's characters are its picture (ascii and braille
    /// frames): a dithering palette then sends each cell's characters as
    /// they are, never splitting a cell of one colour into two halves
    /// (`▀`), which it does where cells are block elements.
    pub fn plain(&self) -> bool {
        self.plain
    }

    /// Says whether the frame's characters are its picture (see
    /// [`Frame::plain`]); the renderer says so for ascii and braille.
    pub fn set_plain(&mut self, plain: bool) {
        self.plain = plain;
    }

    /// Resizes to `cols × rows` and blanks every cell (allocates only when it
    /// grows).
    pub fn reset(&mut self, cols: u16, rows: u16) {
        self.cols = cols;
        self.rows = rows;
        self.cells.clear();
        self.cells
            .resize(cols as usize * rows as usize, Cell::BLANK);
        self.known = Known::default();
    }

    /// Resizes to `cols × rows` keeping whatever cells are there (blank
    /// where it grows): for a caller about to overwrite every cell.
    pub fn resize(&mut self, cols: u16, rows: u16) {
        self.cols = cols;
        self.rows = rows;
        self.cells
            .resize(cols as usize * rows as usize, Cell::BLANK);
        self.known.rect = self.all();
    }

    /// Every cell.
    fn all(&self) -> Rect {
        Rect::all(self.cols as u32, self.rows as u32)
    }

    /// A rectangle outside which every cell is the same, and that cell.
    pub(crate) fn known(&self) -> Known {
        self.known
    }

    /// Says that every cell outside `known.rect` is `known.fill` (the
    /// caller has made it so).
    pub(crate) fn set_known(&mut self, known: Known) {
        debug_assert!(self.cells.iter().enumerate().all(|(i, c)| {
            let w = self.cols.max(1) as usize;
            let (x, y) = (i % w, (i / w) as u32);
            *c == known.fill || known.rect.columns(y).contains(&x)
        }));
        self.known = known;
    }

    /// Columns.
    pub fn cols(&self) -> u16 {
        self.cols
    }

    /// Rows.
    pub fn rows(&self) -> u16 {
        self.rows
    }

    /// Every cell, row by row from the top.
    pub fn cells(&self) -> &[Cell] {
        &self.cells
    }

    /// The cell at column `col` of row `row` (row 0 at the top).
    pub fn get(&self, col: u16, row: u16) -> Cell {
        self.cells[row as usize * self.cols as usize + col as usize]
    }

    /// Puts `cell` at column `col` of row `row` (row 0 at the top).
    pub fn set(&mut self, col: u16, row: u16, cell: Cell) {
        let i = row as usize * self.cols as usize + col as usize;
        self.cells[i] = cell;
        if cell != self.known.fill {
            self.known.rect = self.known.rect.union(Rect::at(col as u32, row as u32));
        }
    }

    /// Every cell, row by row from the top, to write (the caller says what
    /// it knows of them afterwards with [`Frame::set_known`]).
    pub(crate) fn cells_mut(&mut self) -> &mut [Cell] {
        self.known.rect = self.all();
        &mut self.cells
    }

    /// Row `row` (0 at the top), to write.
    pub fn row_mut(&mut self, row: u16) -> &mut [Cell] {
        let w = self.cols as usize;
        let whole_row = Rect {
            y0: row as u32,
            y1: row as u32 + 1,
            ..self.all()
        };
        self.known.rect = self.known.rect.union(whole_row);
        &mut self.cells[row as usize * w..(row as usize + 1) * w]
    }

    /// Row `row` (0 at the top).
    pub fn row(&self, row: u16) -> &[Cell] {
        let w = self.cols as usize;
        &self.cells[row as usize * w..(row as usize + 1) * w]
    }

    /// The frame as text with its colours, for snapshots a colour change
    /// fails: the glyphs row by row (as [`Frame`]'s `Display` writes them),
    /// then each row's runs of cells of one foreground and background, as
    /// ratatui's `Buffer` shows its styles. `-` is the terminal's default
    /// colour; a run is `first..end fg/bg` in columns:
    ///
    /// ```text
    /// ▗▄▖
    /// ▝▀▘
    /// colours (columns fg/bg):
    /// 0: 0..3 #ffa040/-
    /// 1: 0..1 #ffa040/- 1..2 #ffa040/#102030 2..3 #ffa040/-
    /// ```
    ///
    /// One line a row, so an insta diff shows which rows changed colour.
    #[must_use]
    pub fn with_colors(&self) -> WithColors<'_> {
        WithColors(self)
    }
}

/// A [`Frame`] written as its glyphs and its runs of colour
/// ([`Frame::with_colors`]).
#[derive(Clone, Copy, Debug)]
pub struct WithColors<'a>(&'a Frame);

impl fmt::Display for WithColors<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let frame = self.0;
        write!(f, "{frame}")?;
        f.write_str("colours (columns fg/bg):\n")?;
        let colour = |c: Option<Rgb>| c.map_or_else(|| "-".to_string(), |c| c.to_string());
        for r in 0..frame.rows {
            write!(f, "{r}:")?;
            let row = frame.row(r);
            let mut start = 0;
            for end in 1..=row.len() {
                let (a, b) = (row[start], row.get(end));
                if b.is_some_and(|b| (b.fg, b.bg) == (a.fg, a.bg)) {
                    continue;
                }
                write!(f, " {start}..{end} {}/{}", colour(a.fg), colour(a.bg))?;
                start = end;
            }
            f.write_str("\n")?;
        }
        Ok(())
    }
}

impl fmt::Display for Frame {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for r in 0..self.rows {
            for c in self.row(r) {
                fmt::Write::write_char(f, c.ch)?;
            }
            f.write_str("\n")?;
        }
        Ok(())
    }
}
