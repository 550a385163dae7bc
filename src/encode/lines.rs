//! Frames as whole lines (no cursor moves, no diff): for pipes, files and
//! the first frame; runs of cells of one pen share one SGR.

use super::*;

/// Maps a frame's cells to terminal cells for one depth, into `out`.
pub(super) fn quantize(frame: &Frame, q: &mut Quantizer, out: &mut Vec<Packed>) {
    let all = Rect::all(frame.cols() as u32, frame.rows() as u32);
    quantize_in(frame, q, out, all);
}

/// [`quantize`] of the cells of `region` only (`out` holds every cell).
pub(super) fn quantize_in(frame: &Frame, q: &mut Quantizer, out: &mut Vec<Packed>, region: Rect) {
    out.resize(frame.cells().len(), Packed::BLANK);
    let cols = frame.cols() as usize;
    let truecolor = q.depth() == ColorDepth::TrueColor;
    for y in region.y0..region.y1 {
        let span = region.columns(y);
        let row = y as usize * cols;
        let (cells, out) = (
            &frame.cells()[row..][span.clone()],
            &mut out[row..][span.clone()],
        );
        if truecolor {
            // No palette, no dithering: where a cell is does not matter.
            for (o, c) in out.iter_mut().zip(cells) {
                *o = Packed::truecolor(c);
            }
            continue;
        }
        let plain = frame.plain();
        for ((o, c), x) in out.iter_mut().zip(cells).zip(span) {
            *o = Packed::of(TermCell::of_cell(c, q, x as u16, y as u16, plain));
        }
    }
}

/// Appends `cell` written `count` times (at least once) from pen `pen`,
/// with the SGR it needs (when `color`) and, when allowed and shorter, REP
/// for the repeats. Returns the pen afterwards.
#[inline]
pub(super) fn push_run(
    buf: &mut Vec<u8>,
    pen: Inks,
    cell: &Packed,
    count: usize,
    rep: Rep,
    color: bool,
) -> Inks {
    let mut sgr = SgrBytes::new();
    let pen = if color {
        let want = cell.pen(pen);
        sgr.inks(pen, want);
        want
    } else {
        pen
    };
    sgr.glyph(cell.ch);
    sgr.append_to(buf);
    let ch = glyph(cell.ch);
    let repeats = count.saturating_sub(1);
    if repeats > 0 && rep == Rep::On && csi_cost(repeats as u32) < repeats * cell.len() {
        push_csi(buf, repeats as u32, b'b');
    } else {
        (0..repeats).for_each(|_| push_char(buf, ch));
    }
    pen
}

/// Writes `frame` as lines of text (see the module doc). `buf` is scratch
/// space, cleared first and kept for the next call.
pub fn write_lines(
    frame: &Frame,
    palette: impl Into<Palette>,
    rep: Rep,
    buf: &mut Vec<u8>,
    out: &mut impl Write,
) -> io::Result<()> {
    let palette = palette.into();
    let depth = palette.depth;
    let mut q = Quantizer::of(palette);
    let mut cells = Vec::with_capacity(frame.cells().len());
    quantize(frame, &mut q, &mut cells);
    buf.clear();
    push_lines(&cells, frame.cols(), frame.rows(), depth, rep, buf);
    out.write_all(buf)?;
    out.flush()
}

/// Appends `cells` (`cols × rows`) as lines of text.
pub(super) fn push_lines(
    cells: &[Packed],
    cols: u16,
    rows: u16,
    depth: ColorDepth,
    rep: Rep,
    buf: &mut Vec<u8>,
) {
    // Plain text means no escape sequence at all, REP included.
    let rep = if depth.has_color() { rep } else { Rep::Off };
    for row in cells.chunks(cols.max(1) as usize).take(rows as usize) {
        let mut pen = Inks::default();
        let mut rest = row;
        while let Some(cell) = rest.first() {
            let run = rest.iter().take_while(|c| *c == cell).count();
            pen = push_run(buf, pen, cell, run, rep, depth.has_color());
            rest = &rest[run..];
        }
        push_inks(buf, pen, Inks::default());
        buf.push(b'\n');
    }
}
