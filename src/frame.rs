//! The frame: a grid of terminal cells, each one glyph with a foreground and
//! a background colour. The blitters make it, the encoder sends it.
//!
//! Its `Display` is the plain text of the frame, rows top to bottom, each
//! ending in a newline: what `--color none` prints, and what a test
//! snapshots with `insta::assert_snapshot!(frame.to_string())`.

use std::fmt;

use crate::color::Rgb;

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
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Frame {
    cols: u16,
    rows: u16,
    cells: Vec<Cell>,
}

impl Frame {
    /// A blank frame of `cols × rows` cells.
    pub fn new(cols: u16, rows: u16) -> Frame {
        Frame {
            cols,
            rows,
            cells: vec![Cell::BLANK; cols as usize * rows as usize],
        }
    }

    /// Resizes to `cols × rows` and blanks every cell (allocates only when it
    /// grows).
    pub fn reset(&mut self, cols: u16, rows: u16) {
        self.cols = cols;
        self.rows = rows;
        self.cells.clear();
        self.cells
            .resize(cols as usize * rows as usize, Cell::BLANK);
    }

    /// Resizes to `cols × rows` keeping whatever cells are there (blank
    /// where it grows): for a caller about to overwrite every cell.
    pub fn resize(&mut self, cols: u16, rows: u16) {
        self.cols = cols;
        self.rows = rows;
        self.cells
            .resize(cols as usize * rows as usize, Cell::BLANK);
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
    }

    /// Every cell, row by row from the top, to write.
    pub(crate) fn cells_mut(&mut self) -> &mut [Cell] {
        &mut self.cells
    }

    /// Row `row` (0 at the top), to write.
    pub fn row_mut(&mut self, row: u16) -> &mut [Cell] {
        let w = self.cols as usize;
        &mut self.cells[row as usize * w..(row as usize + 1) * w]
    }

    /// Row `row` (0 at the top).
    pub fn row(&self, row: u16) -> &[Cell] {
        let w = self.cols as usize;
        &self.cells[row as usize * w..(row as usize + 1) * w]
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
