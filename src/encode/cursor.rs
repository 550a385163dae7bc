//! Cursor moves: the cheapest way from where the cursor is to the next
//! changed cell (relative, absolute, or writing the cells between), with
//! the pending-wrap state tracked.

use super::*;

/// Where the cursor is: a cell, or just past the last column of a row (the
/// "pending wrap" state, where only absolute horizontal moves are safe).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Cursor {
    pub(super) row: u16,
    pub(super) col: u16,
}

/// The vertical part of a cursor move.
#[derive(Clone, Copy, Debug)]
pub(super) enum Vertical {
    Stay,
    /// `\r\n` repeated: down `n` rows to column 0.
    CrLf(u16),
    /// CUD or CUU by `n` rows (column kept).
    Relative(i32),
    /// VPA to the row (column kept).
    Absolute(u16),
}

/// The horizontal part of a cursor move.
#[derive(Clone, Copy, Debug)]
pub(super) enum Horizontal {
    Stay,
    Cr,
    /// CUF or CUB.
    Relative(i32),
    /// CHA.
    Absolute(u16),
}

/// The length of `CSI n X`, where n = 1 is left out.
pub(super) fn csi_cost(n: u32) -> usize {
    3 + if n == 1 { 0 } else { digits(n) }
}

pub(super) fn horizontal(from: Option<u16>, to: u16, cols: u16) -> (usize, Horizontal) {
    let mut best = (csi_cost(to as u32 + 1), Horizontal::Absolute(to));
    if to == 0 {
        best = (1, Horizontal::Cr);
    }
    if let Some(c) = from.filter(|&c| c < cols) {
        if c == to {
            return (0, Horizontal::Stay);
        }
        let d = to as i32 - c as i32;
        let cost = csi_cost(d.unsigned_abs());
        if cost < best.0 {
            best = (cost, Horizontal::Relative(d));
        }
    }
    best
}

/// The cheapest way from `from` (unknown: `None`) to `to`, and its length;
/// `None` as the plan means CUP.
pub(super) fn plan_move(
    from: Option<Cursor>,
    to: Cursor,
    cols: u16,
) -> (usize, Option<(Vertical, Horizontal)>) {
    if from == Some(to) {
        // The next cell written is the one the cursor is on: most often.
        return (0, Some((Vertical::Stay, Horizontal::Stay)));
    }
    // CUP: `CSI row ; col H`, with `; 1` and a lone `1` left out.
    let cup = 3 + match (to.row, to.col) {
        (0, 0) => 0,
        (r, 0) => digits(r as u32 + 1),
        (r, c) => digits(r as u32 + 1) + 1 + digits(c as u32 + 1),
    };
    let Some(from) = from else {
        return (cup, None);
    };
    let mut best = (cup, None);
    let mut consider = |v: Vertical, v_cost: usize, col_after: Option<u16>| {
        let (h_cost, h) = horizontal(col_after, to.col, cols);
        if v_cost + h_cost < best.0 {
            best = (v_cost + h_cost, Some((v, h)));
        }
    };
    let dr = to.row as i32 - from.row as i32;
    if dr == 0 {
        consider(Vertical::Stay, 0, Some(from.col));
    } else {
        if dr > 0 && dr <= 4 {
            consider(Vertical::CrLf(dr as u16), 2 * dr as usize, Some(0));
        }
        // From the pending-wrap position only absolute columns are safe.
        let col = Some(from.col).filter(|&c| c < cols);
        consider(Vertical::Relative(dr), csi_cost(dr.unsigned_abs()), col);
        consider(Vertical::Absolute(to.row), csi_cost(to.row as u32 + 1), col);
    }
    best
}

pub(super) fn push_csi(buf: &mut Vec<u8>, n: u32, end: u8) {
    buf.extend_from_slice(b"\x1b[");
    if n != 1 {
        push_num(buf, n);
    }
    buf.push(end);
}

pub(super) fn push_move(buf: &mut Vec<u8>, plan: Option<(Vertical, Horizontal)>, to: Cursor) {
    let Some((v, h)) = plan else {
        buf.extend_from_slice(b"\x1b[");
        if to.row > 0 || to.col > 0 {
            push_num(buf, to.row as u32 + 1);
        }
        if to.col > 0 {
            buf.push(b';');
            push_num(buf, to.col as u32 + 1);
        }
        buf.push(b'H');
        return;
    };
    match v {
        Vertical::Stay => {}
        Vertical::CrLf(n) => (0..n).for_each(|_| buf.extend_from_slice(b"\r\n")),
        Vertical::Relative(d) => push_csi(buf, d.unsigned_abs(), if d > 0 { b'B' } else { b'A' }),
        Vertical::Absolute(r) => push_csi(buf, r as u32 + 1, b'd'),
    }
    match h {
        Horizontal::Stay => {}
        Horizontal::Cr => buf.push(b'\r'),
        Horizontal::Relative(d) => push_csi(buf, d.unsigned_abs(), if d > 0 { b'C' } else { b'D' }),
        Horizontal::Absolute(c) => push_csi(buf, c as u32 + 1, b'G'),
    }
}

/// Takes the cursor from `from` to `to`, cell `i` of `next`, in the fewest
/// bytes: the cheapest move, or, on the same row, the unchanged cells in
/// between written again where that is shorter (they must fit the pen as
/// they are or turned round). `next` holds the cells of its row from
/// index `lo` on; those before are blanks in the default colours.
#[inline(never)]
pub(super) fn move_to(
    buf: &mut Vec<u8>,
    (next, lo, i): (&[Packed], usize, usize),
    cols: u16,
    from: Option<Cursor>,
    to: Cursor,
    pen: Inks,
) {
    let (move_cost, plan) = plan_move(from, to, cols);
    let cell = |k: usize| if k >= lo { next[k] } else { Packed::BLANK };
    let gap = match from {
        Some(c) if c.row == to.row && c.col < to.col && move_cost > 0 => {
            // Each cell is at least a byte.
            let gap = (to.col - c.col) as usize;
            let cells = i - gap.min(move_cost)..i;
            let cost: usize = cells.clone().map(|k| cell(k).len()).sum();
            (gap < move_cost
                && cost < move_cost
                && cells.clone().all(|k| cell(k).fitting(pen).is_some()))
            .then_some(cells)
        }
        _ => None,
    };
    match gap {
        Some(cells) => cells
            .filter_map(|k| cell(k).fitting(pen))
            .for_each(|c| push_char(buf, glyph(c.ch))),
        None => push_move(buf, plan, to),
    }
}
