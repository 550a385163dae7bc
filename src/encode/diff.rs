//! What changed: the cells of the next frame unequal to those the
//! terminal shows, eight at a time where they are equal, and truecolor
//! quantisation fused with it.

use super::*;

/// Lists in `changes` the indices of the cells of `region` (of a frame
/// `cols` wide) unequal between `next` and `shown`, in order, and returns
/// how many. Eight equal cells, most of a large frame, cost one test; in a
/// chunk with a difference, each cell costs a few word comparisons and no
/// branch: every index is written, and the count advanced only past those
/// that differ.
pub(super) fn unequal_cells(
    shown: &[Packed],
    next: &[Packed],
    changes: &mut Vec<u32>,
    cols: usize,
    region: Rect,
) -> usize {
    let n = shown.len().min(next.len());
    if changes.len() < n {
        changes.resize(n, 0);
    }
    let slots = &mut changes[..n];
    let mut len = 0;
    for y in region.y0..region.y1 {
        let span = region.columns(y);
        let row = y as usize * cols + span.start;
        let (shown, next) = (&shown[row..][..span.len()], &next[row..][..span.len()]);
        // Eight cells at a time: where all are equal, one test; otherwise
        // each is listed if it differs.
        for (k, (a, b)) in shown.chunks(8).zip(next.chunks(8)).enumerate() {
            if a.len() == 8 && a.iter().zip(b).fold(0, |d, (p, q)| d | p.differs(q)) == 0 {
                continue;
            }
            for (j, (p, q)) in a.iter().zip(b).enumerate() {
                slots[len] = (row + k * 8 + j) as u32;
                len += (p.differs(q) != 0) as usize;
            }
        }
    }
    len
}

/// [`quantize_in`] and [`unequal_cells`] in one pass for 24-bit colour,
/// where a cell packs straight from its bytes (no palette, no dithering):
/// each cell is compared with `shown`'s while it is in registers.
#[inline]
pub(super) fn quantize_truecolor(
    frame: &Frame,
    shown: &[Packed],
    next: &mut Vec<Packed>,
    changes: &mut Vec<u32>,
    region: Rect,
) -> usize {
    let cells = frame.cells();
    let n = cells.len().min(shown.len());
    next.resize(cells.len(), Packed::BLANK);
    if changes.len() < n {
        changes.resize(n, 0);
    }
    let slots = &mut changes[..n];
    let cols = frame.cols() as usize;
    let mut len = 0;
    for y in region.y0..region.y1 {
        let span = region.columns(y);
        let row = y as usize * cols + span.start;
        let m = span.len();
        let (cells, shown, next) = (
            &cells[row..][..m],
            &shown[row..][..m],
            &mut next[row..][..m],
        );
        for (i, ((out, c), s)) in next.iter_mut().zip(cells).zip(shown).enumerate() {
            let p = Packed::truecolor(c);
            *out = p;
            slots[len] = (row + i) as u32;
            len += (p.differs(s) != 0) as usize;
        }
    }
    len
}

/// Keeps, of the cells `candidates` lists, those whose picture differs
/// between `shown` and `next` (the same picture drawn the other way round
/// is no change), in order.
#[inline]
pub(super) fn changed_cells<'a>(
    shown: &[Packed],
    next: &[Packed],
    candidates: &'a mut [u32],
) -> &'a [u32] {
    let mut kept = 0;
    for k in 0..candidates.len() {
        let i = candidates[k] as usize;
        candidates[kept] = i as u32;
        kept += !shown[i].differs_only_in_form(&next[i]) as usize;
    }
    &candidates[..kept]
}
