//! Stage 7: the encoder, from a [`Frame`] to the bytes a terminal reads, for
//! any `io::Write`.
//!
//! Colours are first mapped to what the terminal is told ([`Ink`]: 24-bit,
//! a palette index, or its default) by a [`Quantizer`] for the colour
//! depth. The encoder then keeps track of the terminal's state, its pen
//! (current foreground and background) and its cursor, and writes the fewest
//! bytes it can:
//!
//! * **SGR only where a colour changes**, foreground and background in one
//!   sequence, and `CSI m` (3 bytes) to go back to the defaults. A blank cell
//!   shows only its background and `█` only its foreground, so the other
//!   plane never forces an SGR.
//! * **Cells drawn the way round that keeps the pen**: a block element of
//!   the two-colour modes shows the same picture as its complement with the
//!   colours swapped (`▀` red on blue is `▄` blue on red; a blank in red is
//!   `█` in red), so each changed cell is written in whichever form costs
//!   fewer bytes from the current pen, counted over the run of copies of it
//!   that follow. The choice is greedy, cell by cell: it never looks further
//!   ahead. On the turning square this alone took half mode's later frames
//!   from 1,328 bytes to 966 and octant's from 2,089 to 1,478. Neither colour
//!   may be the terminal's default, which differs as a foreground and as a
//!   background; braille and the ramps have no complement. Frames are
//!   compared by picture, so a cell the blitter turned round is no change.
//! * **The cheapest cursor move**: of CUP, CHA, CUF, CUB, CUD, CUU, VPA, CR
//!   and CR LF (and their combinations), the shortest that reaches the next
//!   cell to write; nothing at all when it is the adjacent one. A short gap
//!   of unchanged cells that need no SGR is rewritten instead when that is
//!   shorter than any move.
//! * **Only what changed** ([`Encoder`]): the frame the terminal shows is
//!   kept, and a new frame sends only the cells that differ. A frame from
//!   the renderer knows a rectangle outside which every cell is the same
//!   (the cells that show no drawn sample); where that cell is a blank in
//!   the default colours, only the cells of that rectangle and of the last
//!   frame's are compared: a model in a corner of a large terminal costs
//!   its own cells. The encoder
//!   keeps cells packed, a word for the glyph and one for each ink, so
//!   that finding the changes in a large frame is integer comparisons,
//!   eight cells at a time where all eight are equal; the choices for a
//!   changed cell (which way round, which SGR, how many copies follow)
//!   are integer tests on the same words. Nothing is allocated per frame
//!   once the buffers have grown. The first frame, a
//!   resize, a change of colour depth, or [`Encoder::invalidate`] give a
//!   full redraw: the screen is cleared and the frame's non-blank cells
//!   written.
//! * **REP** (`CSI n b`, repeat the last character) for runs of identical
//!   cells, off by default ([`Rep`]): not every terminal has it.
//! * Every frame is bracketed in synchronized output (DEC mode 2026), so a
//!   terminal that supports it shows it at once, and ends with the
//!   attributes reset. A frame with nothing to change writes nothing.
//!
//! Bytes are gathered in a buffer kept between frames and written with one
//! `write_all`.
//!
//! [`write_lines`] prints a frame as lines of text instead, for
//! `rastty render`: each row ends with an attribute reset (so no colour
//! bleeds into the rest of the line or the shell prompt) and a newline. With
//! [`ColorDepth::None`] it writes the frame's plain text and no escape
//! sequence at all.

use std::io::{self, Write};

use crate::color::{ColorDepth, Dither, Ink, Metric, Palette, Quantizer, Rgb};
use crate::frame::{Cell, Frame};
use crate::transform::Rect;

/// Synchronized output: begin and end.
pub(crate) const SYNC_BEGIN: &[u8] = b"\x1b[?2026h";
/// Synchronized output: end.
pub(crate) const SYNC_END: &[u8] = b"\x1b[?2026l";

mod cell;
mod cursor;
mod diff;
mod lines;
mod sgr;

use cell::*;
use cursor::*;
use diff::*;
use lines::*;
use sgr::*;

pub use cell::{TermCell, complement};
pub use lines::write_lines;
pub use sgr::Rep;
pub(crate) use sgr::push_char;

/// Sends frames to a terminal, each as the difference from the last.
///
/// ```
/// use rastty::{color::ColorDepth, encode::Encoder, Frame, RenderOptions, Renderer, color::Rgb, scene::Scene};
/// use rastty::glam::Vec3;
///
/// let scene = Scene::of_mesh(rastty::scene::Shape::Cube.mesh(Rgb::WHITE));
/// let (mut renderer, mut frame) = (Renderer::new(), Frame::default());
/// let mut encoder = Encoder::new(ColorDepth::TrueColor);
/// let mut sent = Vec::new();
/// for yaw in [0.0, 2.0] {
///     let opts = RenderOptions { turn: Vec3::new(0.0, yaw, 0.0), ..Default::default() };
///     renderer.render_into(&scene, &opts, &mut frame);
///     sent.push(encoder.encode(&frame, &mut Vec::new()).unwrap());
/// }
/// // The first frame is drawn in full, the second only where it changed.
/// assert!(sent[1] < sent[0] / 2, "{sent:?}");
/// // Nothing changed: nothing is sent.
/// assert_eq!(encoder.encode(&frame, &mut Vec::new()).unwrap(), 0);
/// ```
#[derive(Debug)]
pub struct Encoder {
    quantizer: Quantizer,
    /// The dithering asked for (`auto` resolves per depth).
    dither: Dither,
    rep: Rep,
    cols: u16,
    rows: u16,
    /// What the terminal shows, when `synced`.
    shown: Vec<Packed>,
    /// Every cell of `shown` outside it is a blank in the default colours.
    shown_drawn: Rect,
    /// The frame being sent, in the cells compared with `shown`.
    next: Vec<Packed>,
    /// The indices of the cells that changed, in order (scratch space).
    changes: Vec<u32>,
    synced: bool,
    buf: Vec<u8>,
    /// Bracket frames in synchronized output.
    sync: bool,
    /// Every frame in full as plain lines (a terminal that cannot move its
    /// cursor), rather than as the difference from the last.
    lines: bool,
}

impl Encoder {
    /// An encoder for `depth`, with synchronized output and the default palette
    /// matching; the first frame is drawn in full.
    pub fn new(depth: ColorDepth) -> Encoder {
        Encoder {
            quantizer: Quantizer::of(depth.into()),
            dither: Dither::Auto,
            rep: Rep::Off,
            cols: 0,
            rows: 0,
            shown: Vec::new(),
            shown_drawn: Rect::EMPTY,
            next: Vec::new(),
            changes: Vec::new(),
            synced: false,
            buf: Vec::new(),
            sync: true,
            lines: false,
        }
    }

    /// An encoder that writes each frame in full as lines of text, for a
    /// terminal that cannot move its cursor (`TERM=dumb`): no cursor moves,
    /// no screen clearing, no synchronized output.
    pub fn lines(depth: ColorDepth) -> Encoder {
        Encoder {
            lines: true,
            sync: false,
            ..Encoder::new(depth)
        }
    }

    /// Whether frames are bracketed in synchronized output (on by default;
    /// terminals that do not know it ignore it, at 16 bytes a frame).
    pub fn with_sync(mut self, on: bool) -> Encoder {
        self.set_sync(on);
        self
    }

    /// See [`Encoder::with_sync`].
    pub fn set_sync(&mut self, on: bool) {
        self.sync = on && !self.lines;
    }

    /// Whether frames are bracketed in synchronized output.
    pub fn sync(&self) -> bool {
        self.sync
    }

    /// Measures "nearest" palette colours with `metric` (OKLCh by default).
    pub fn with_metric(mut self, metric: Metric) -> Encoder {
        self.quantizer = Quantizer::of(Palette {
            metric,
            ..self.palette()
        });
        self
    }

    /// Dithers as `dither` says (`auto` by default: ordered in 16 and 256 colours).
    pub fn with_dither(mut self, dither: Dither) -> Encoder {
        self.dither = dither;
        self.quantizer = Quantizer::of(self.palette());
        self
    }

    /// How colours are sent (`auto` dithering resolved).
    pub fn palette(&self) -> Palette {
        Palette {
            depth: self.quantizer.depth(),
            metric: self.quantizer.metric(),
            dither: self.dither,
        }
    }

    /// Sends runs of identical cells with REP when `rep` is [`Rep::On`].
    pub fn with_rep(mut self, rep: Rep) -> Encoder {
        self.rep = rep;
        self
    }

    /// The colour depth frames are sent at.
    pub fn depth(&self) -> ColorDepth {
        self.quantizer.depth()
    }

    /// Changes the colour depth; the next frame is a full redraw.
    pub fn set_depth(&mut self, depth: ColorDepth) {
        if depth != self.depth() {
            self.quantizer = Quantizer::of(Palette {
                depth,
                ..self.palette()
            });
            self.invalidate();
        }
    }

    /// Forgets what the terminal shows: the next frame is a full redraw.
    pub fn invalidate(&mut self) {
        self.synced = false;
    }

    /// The bytes of the last frame encoded.
    pub fn last_bytes(&self) -> &[u8] {
        &self.buf
    }

    /// Encodes `frame` and writes it; returns the number of bytes written.
    pub fn encode(&mut self, frame: &Frame, out: &mut impl Write) -> io::Result<usize> {
        self.prepare(frame);
        out.write_all(&self.buf)?;
        out.flush()?;
        Ok(self.buf.len())
    }

    /// Encodes `frame` into [`Encoder::last_bytes`] without writing it, and
    /// takes it as shown.
    pub fn prepare(&mut self, frame: &Frame) {
        self.buf.clear();
        if self.lines {
            quantize(frame, &mut self.quantizer, &mut self.next);
            let depth = self.depth();
            push_lines(
                &self.next,
                frame.cols(),
                frame.rows(),
                depth,
                self.rep,
                &mut self.buf,
            );
            return;
        }
        if self.sync {
            self.buf.extend_from_slice(SYNC_BEGIN);
        }
        let full = !self.synced || frame.cols() != self.cols || frame.rows() != self.rows;
        let mut cursor = None;
        if full {
            self.cols = frame.cols();
            self.rows = frame.rows();
            self.shown.clear();
            self.shown.resize(frame.cells().len(), Packed::BLANK);
            self.shown_drawn = Rect::EMPTY;
            // Home, default colours, clear: the screen is now all blanks.
            self.buf.extend_from_slice(b"\x1b[H\x1b[m\x1b[2J");
            cursor = Some(Cursor { row: 0, col: 0 });
        }
        // Only the cells that are not blank in the frame or on the screen
        // (as far as either knows) can differ.
        let all = Rect::all(self.cols as u32, self.rows as u32);
        let known = frame.known();
        let drawn = if known.fill == Cell::BLANK {
            known.rect.intersect(all)
        } else {
            all
        };
        let region = drawn.union(self.shown_drawn).intersect(all);
        let candidates = if self.quantizer.depth() == ColorDepth::TrueColor {
            quantize_truecolor(
                frame,
                &self.shown,
                &mut self.next,
                &mut self.changes,
                region,
            )
        } else {
            quantize_in(frame, &mut self.quantizer, &mut self.next, region);
            let cols = self.cols as usize;
            unequal_cells(&self.shown, &self.next, &mut self.changes, cols, region)
        };
        let start = self.buf.len();
        self.write_changes(candidates, cursor, region);
        if self.buf.len() == start && !full {
            // Nothing changed: nothing to send.
            self.buf.clear();
        } else if self.sync {
            self.buf.extend_from_slice(SYNC_END);
        }
        // The terminal now shows the frame.
        let cols = self.cols as usize;
        for y in region.y0..region.y1 {
            let span = region.columns(y);
            let row = y as usize * cols;
            self.shown[row..][span.clone()].copy_from_slice(&self.next[row..][span]);
        }
        self.shown_drawn = drawn;
        self.synced = true;
    }

    /// Appends the changed cells to the buffer, ending with the pen reset.
    /// `candidates`: the number of cells listed in `self.changes` as
    /// unequal to the cell shown, all in `region`, outside which no cell
    /// changed (and `self.next` holds nothing).
    fn write_changes(&mut self, candidates: usize, mut cursor: Option<Cursor>, region: Rect) {
        let cols = self.cols as usize;
        let buf = &mut self.buf;
        let changes = changed_cells(&self.shown, &self.next, &mut self.changes[..candidates]);
        let (shown, next) = (&self.shown, &self.next);
        let mut pen = Inks::default();
        // Index of the first cell not yet written (REP runs write ahead).
        let mut done = 0usize;
        // The end of the last run of changed copies counted, and its cell:
        // a cell inside it has the rest of the run as its copies.
        let mut counted = (0usize, Packed::BLANK);
        for &i in changes {
            let i = i as usize;
            if i < done {
                continue;
            }
            let packed = next[i];
            let to = Cursor {
                row: (i / cols) as u16,
                col: (i % cols) as u16,
            };
            // Most often the next cell written is the one the cursor is on.
            if cursor != Some(to) {
                let lo = to.row as usize * cols + region.x0 as usize;
                move_to(buf, (next, lo, i), self.cols, cursor, to, pen);
            }
            // The copies and REP runs end where the region does: no cell
            // changed beyond it.
            let row_end = to.row as usize * cols + region.x1 as usize;
            // With REP, identical cells that follow on the row are sent as
            // one run, up to the last changed one among them.
            let run = if self.rep == Rep::On {
                let same = next[i + 1..row_end]
                    .iter()
                    .take_while(|c| **c == packed)
                    .count();
                1 + (0..same)
                    .rev()
                    .find(|&k| !shown[i + 1 + k].same_picture(&next[i + 1 + k]))
                    .map_or(0, |k| k + 1)
            } else {
                1
            };
            // Of the cell and its flip, the one that costs least over the
            // changed copies of it that follow (counted once a run).
            let copies = || {
                if i < counted.0 && counted.1 == packed {
                    return counted.0 - i;
                }
                let n = 1
                    + (i + 1..row_end)
                        .take_while(|&k| next[k] == packed && !shown[k].same_picture(&next[k]))
                        .count();
                counted = (i + n, packed);
                n
            };
            let form = packed.cheapest_from(pen, copies);
            pen = push_run(buf, pen, &form, run, self.rep, true);
            done = i + run;
            cursor = Some(Cursor {
                row: to.row,
                col: to.col + run as u16,
            });
        }
        push_inks(buf, pen, Inks::default());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::Cell;
    use proptest::prelude::*;

    /// Inks from a small set, so that equal ones are drawn often.
    fn ink() -> impl Strategy<Value = Ink> {
        prop_oneof![
            Just(Ink::Default),
            (0u8..3).prop_map(Ink::Indexed),
            (0u8..3).prop_map(|v| Ink::Rgb(Rgb([v, 0, 2 - v]))),
        ]
    }

    /// Cells of the glyphs that have complements and of one that has not.
    fn term_cell() -> impl Strategy<Value = TermCell> {
        let ch = prop::sample::select(vec![' ', FULL, '▀', '▄', '⣿']);
        (ch, ink(), ink()).prop_map(|(ch, fg, bg)| TermCell { ch, fg, bg })
    }

    proptest! {
        // The cases where the plane decides are rare: many cases, each fast.
        #![proptest_config(ProptestConfig::with_cases(4096))]

        /// A glyph of two colours and its complement of the same length are
        /// chosen between by the colours of the pen each keeps, as the
        /// bytes each would cost choose (a tie, or two forms that set both
        /// colours, keeps the cell as it is): over inks of every kind,
        /// bright palette colours (one digit longer as a background)
        /// included, and glyphs whose complement is longer or shorter.
        #[test]
        fn the_form_kept_is_the_one_of_fewer_bytes(
            inks in prop::array::uniform4(prop_oneof![
                Just(Ink::Default),
                (0u8..20).prop_map(Ink::Indexed),
                (0u8..3).prop_map(|v| Ink::Rgb(Rgb([v * 100, 7, 250 - v]))),
            ]),
            ch in prop::sample::select(vec!['▀', '▄', '▌', '▐', '▖', '▜', '\u{1FB00}', '\u{1FB3B}', '\u{1CD00}', '\u{1CDE5}', '\u{1FBE6}']),
        ) {
            let [fg, bg, pf, pb] = inks;
            let cell = Packed::of(TermCell { ch, fg, bg });
            let pen = Inks::of(Pen { fg: pf, bg: pb });
            if let Some(f) = cell.flipped().filter(|f| f.len() == cell.len() && !cell.fits(pen)) {
                let cost = |c: &Packed| sgr_cost(pen, c.pen(pen));
                let keeps = |c: &Packed| c.fg == pen.fg || c.bg == pen.bg;
                let cheaper = if !keeps(&cell) && !keeps(&f) || cost(&f) >= cost(&cell) { cell } else { f };
                prop_assert_eq!(cell.cheaper_of_two_colours(f, pen), cheaper);
            }
        }
    }

    proptest! {
        /// Two inks pack to the same word exactly when they are equal, and
        /// cells compare equal packed exactly when they do unpacked.
        #[test]
        fn packed_inks_and_cells_are_equal_exactly_when_they_are(
            a in ink(), b in ink(), p in term_cell(), q in term_cell(),
        ) {
            prop_assert_eq!(pack_ink(a) == pack_ink(b), a == b);
            prop_assert_eq!(Packed::of(p) == Packed::of(q), p == q);
        }

        /// The changed cells, found eight at a time, are exactly the cells
        /// of the region compared whose picture differs, in order, for rows
        /// of any length (not only multiples of eight) and with changes
        /// anywhere in a chunk.
        #[test]
        fn changed_cells_are_the_cells_whose_picture_differs(
            (cols, rows) in (1usize..20, 1usize..5),
            cells in prop::collection::vec((term_cell(), term_cell(), 0u8..4), 100),
            corners in (0u32..20, 0u32..20, 0u32..5, 0u32..5),
        ) {
            let cells = &cells[..cols * rows];
            let (a, b, c, d) = corners;
            let region = Rect { x0: a.min(b), x1: a.max(b), y0: c.min(d), y1: c.max(d) }
                .intersect(Rect::all(cols as u32, rows as u32));
            // A quarter of the cells change; the rest are equal.
            let shown: Vec<TermCell> = cells.iter().map(|c| c.0).collect();
            let next: Vec<TermCell> =
                cells.iter().map(|&(a, b, k)| if k == 0 { b } else { a }).collect();
            let pack = |v: &[TermCell]| v.iter().map(|&c| Packed::of(c)).collect::<Vec<_>>();
            let (shown_p, next_p) = (pack(&shown), pack(&next));
            let mut scratch = vec![7; 3];
            let n = unequal_cells(&shown_p, &next_p, &mut scratch, cols, region);
            let found = changed_cells(&shown_p, &next_p, &mut scratch[..n]).to_vec();
            let expected: Vec<u32> = (0..shown.len())
                .filter(|&i| region.columns((i / cols) as u32).contains(&(i % cols)))
                .filter(|&i| !shown[i].same_picture(&next[i]))
                .map(|i| i as u32)
                .collect();
            prop_assert_eq!(found, expected);
        }
    }

    proptest! {
        /// Quantizing 24-bit colour and listing the unequal cells in one
        /// pass gives the cells and the list the two passes give, for any
        /// frame shape, region compared and with changes anywhere.
        #[test]
        fn one_pass_in_truecolor_is_the_two_passes(
            (cols, rows) in (1u16..20, 1u16..5),
            seed in prop::collection::vec((0usize..5, 0u8..4, 0u8..4, 0u8..3), 100),
            corners in (0u32..20, 0u32..20, 0u32..5, 0u32..5),
        ) {
            let rgb = |k: u8| (k > 0).then(|| Rgb([k, 0, 3 - k]));
            let mut frame = Frame::default();
            frame.resize(cols, rows);
            let chars = [' ', FULL, '▀', '▄', '⣿'];
            for (c, &(ch, fg, bg, _)) in frame.cells_mut().iter_mut().zip(seed.iter().cycle()) {
                *c = Cell { ch: chars[ch], fg: rgb(fg), bg: rgb(bg) };
            }
            // What is shown: the frame's own cells, a third of them changed.
            let mut q = Quantizer::of(ColorDepth::TrueColor.into());
            let mut shown = Vec::new();
            quantize(&frame, &mut q, &mut shown);
            for (p, &(_, fg, _, k)) in shown.iter_mut().zip(seed.iter().rev().cycle()) {
                if k == 0 {
                    p.bg = pack_ink(Ink::Indexed(fg));
                }
            }
            // A region of the frame, the rest left alone.
            let (a, b, c, d) = corners;
            let region = Rect { x0: a.min(b), x1: a.max(b), y0: c.min(d), y1: c.max(d) }
                .intersect(Rect::all(cols as u32, rows as u32));
            let (mut two, mut two_list) = (Vec::new(), Vec::new());
            quantize_in(&frame, &mut q, &mut two, region);
            let n = unequal_cells(&shown, &two, &mut two_list, cols as usize, region);
            let (mut one, mut one_list) = (vec![Packed::BLANK; 3], vec![9; 2]);
            let m = quantize_truecolor(&frame, &shown, &mut one, &mut one_list, region);
            let inside = |v: &[Packed]| -> Vec<Packed> {
                (0..v.len())
                    .filter(|&i| region.columns((i / cols as usize) as u32).contains(&(i % cols as usize)))
                    .map(|i| v[i])
                    .collect()
            };
            prop_assert_eq!(inside(&one), inside(&two));
            prop_assert_eq!(&one_list[..m], &two_list[..n]);
        }
    }

    fn sgr(from: Pen, to: Pen) -> String {
        let mut b = Vec::new();
        push_sgr(&mut b, from, to);
        String::from_utf8(b).unwrap()
    }

    #[test]
    fn byte_digits_are_the_decimal_numbers_and_a_semicolon() {
        for v in 0..=255u8 {
            let mut sgr = SgrBytes {
                bytes: [0; 48],
                len: 0,
            };
            sgr.byte(v);
            assert_eq!(sgr.bytes[..sgr.len], *format!("{v};").as_bytes());
        }
    }

    #[test]
    fn sgr_writes_only_what_changes() {
        let red = Ink::Rgb(Rgb::new(255, 0, 0));
        let blue = Ink::Rgb(Rgb::new(0, 0, 255));
        let d = Ink::Default;
        let p = |fg, bg| Pen { fg, bg };
        assert_eq!(sgr(p(red, blue), p(red, blue)), "");
        assert_eq!(sgr(p(d, d), p(red, d)), "\x1b[38;2;255;0;0m");
        assert_eq!(sgr(p(red, d), p(red, blue)), "\x1b[48;2;0;0;255m");
        assert_eq!(
            sgr(p(d, d), p(red, blue)),
            "\x1b[38;2;255;0;0;48;2;0;0;255m"
        );
        assert_eq!(sgr(p(red, blue), p(red, d)), "\x1b[49m");
        assert_eq!(sgr(p(red, blue), p(d, d)), "\x1b[m");
        assert_eq!(
            sgr(p(d, d), p(Ink::Indexed(196), Ink::Indexed(3))),
            "\x1b[38;5;196;43m"
        );
        assert_eq!(
            sgr(p(d, d), p(Ink::Indexed(9), Ink::Indexed(12))),
            "\x1b[91;104m"
        );
    }

    #[test]
    fn lines_reset_at_each_end_and_plain_text_has_no_escapes() {
        let mut f = Frame::new(3, 2);
        let red = Some(Rgb::new(255, 0, 0));
        f.set(
            1,
            0,
            Cell {
                ch: ' ',
                fg: None,
                bg: red,
            },
        );
        f.set(
            2,
            0,
            Cell {
                ch: ' ',
                fg: None,
                bg: red,
            },
        );
        f.set(
            0,
            1,
            Cell {
                ch: '@',
                fg: red,
                bg: None,
            },
        );
        let mut buf = Vec::new();
        let mut out = Vec::new();
        write_lines(&f, ColorDepth::TrueColor, Rep::Off, &mut buf, &mut out).unwrap();
        assert_eq!(
            String::from_utf8(out).unwrap(),
            " \x1b[48;2;255;0;0m  \x1b[m\n\x1b[38;2;255;0;0m@  \x1b[m\n"
        );
        let mut out = Vec::new();
        write_lines(&f, ColorDepth::None, Rep::On, &mut buf, &mut out).unwrap();
        assert_eq!(String::from_utf8(out).unwrap(), f.to_string());
    }

    /// A one-row frame of `n` copies of a cell, written as lines with REP.
    fn lines_with_rep(n: u16, cell: Cell) -> String {
        let mut f = Frame::new(n, 1);
        (0..n).for_each(|c| f.set(c, 0, cell));
        let mut out = Vec::new();
        write_lines(
            &f,
            ColorDepth::TrueColor,
            Rep::On,
            &mut Vec::new(),
            &mut out,
        )
        .unwrap();
        String::from_utf8(out).unwrap()
    }

    #[test]
    fn rep_replaces_long_runs_only() {
        let white = Cell {
            ch: '▀',
            fg: Some(Rgb::WHITE),
            bg: None,
        };
        assert_eq!(
            lines_with_rep(12, white),
            "\x1b[38;2;255;255;255m▀\x1b[11b\x1b[m\n"
        );
        let x = Cell {
            ch: 'x',
            fg: None,
            bg: None,
        };
        assert_eq!(lines_with_rep(2, x), "xx\n");
    }

    #[test]
    fn moves_are_the_shortest_form() {
        let mv = |from: Option<(u16, u16)>, to: (u16, u16)| {
            let from = from.map(|(row, col)| Cursor { row, col });
            let to = Cursor {
                row: to.0,
                col: to.1,
            };
            let (cost, plan) = plan_move(from, to, 80);
            let mut b = Vec::new();
            push_move(&mut b, plan, to);
            assert_eq!(b.len(), cost);
            String::from_utf8(b).unwrap()
        };
        assert_eq!(mv(None, (0, 0)), "\x1b[H");
        assert_eq!(mv(None, (4, 0)), "\x1b[5H");
        assert_eq!(mv(None, (4, 9)), "\x1b[5;10H");
        assert_eq!(mv(Some((3, 5)), (3, 5)), "");
        assert_eq!(mv(Some((3, 5)), (3, 6)), "\x1b[C");
        // CHA and CUF cost the same here; CHA is taken.
        assert_eq!(mv(Some((3, 5)), (3, 17)), "\x1b[18G");
        assert_eq!(mv(Some((3, 5)), (3, 9)), "\x1b[4C");
        assert_eq!(mv(Some((3, 5)), (3, 0)), "\r");
        assert_eq!(mv(Some((3, 50)), (3, 1)), "\x1b[2G");
        assert_eq!(mv(Some((3, 50)), (4, 0)), "\r\n");
        assert_eq!(mv(Some((3, 50)), (4, 50)), "\x1b[B");
        // Past the last column only absolute columns are safe.
        assert_eq!(mv(Some((3, 80)), (4, 79)), "\x1b[5;80H");
        assert_eq!(mv(Some((3, 80)), (3, 2)), "\x1b[3G");
        assert_eq!(mv(Some((20, 5)), (2, 5)), "\x1b[3d");
        assert_eq!(mv(Some((20, 5)), (18, 5)), "\x1b[2A");
    }

    #[test]
    fn an_unchanged_frame_sends_nothing_and_a_change_sends_one_cell() {
        let mut e = Encoder::new(ColorDepth::TrueColor);
        let mut f = Frame::new(4, 2);
        let first = e.encode(&f, &mut Vec::new()).unwrap();
        assert_eq!(
            &e.last_bytes()[..first],
            b"\x1b[?2026h\x1b[H\x1b[m\x1b[2J\x1b[?2026l"
        );
        assert_eq!(e.encode(&f, &mut Vec::new()).unwrap(), 0);
        f.set(
            2,
            1,
            Cell {
                ch: 'x',
                fg: Some(Rgb::WHITE),
                bg: None,
            },
        );
        let mut out = Vec::new();
        e.encode(&f, &mut out).unwrap();
        let s = String::from_utf8(out).unwrap();
        assert_eq!(
            s,
            "\x1b[?2026h\x1b[2;3H\x1b[38;2;255;255;255mx\x1b[m\x1b[?2026l"
        );
        // A resize redraws in full.
        let f = Frame::new(5, 2);
        e.encode(&f, &mut Vec::new()).unwrap();
        assert!(e.last_bytes().windows(4).any(|w| w == b"\x1b[2J"));
    }

    #[test]
    fn complements_draw_the_other_samples_in_every_two_colour_mode() {
        use crate::blit::GlyphMode;
        for mode in [
            GlyphMode::Half,
            GlyphMode::Quadrant,
            GlyphMode::Sextant,
            GlyphMode::Octant,
        ] {
            let all = ((1u16 << mode.samples()) - 1) as u8;
            for mask in 0..=all {
                let ch = mode.glyph(mask);
                assert_eq!(
                    complement(ch),
                    Some(mode.glyph(!mask & all)),
                    "{mode:?} {mask:#x}"
                );
            }
        }
        for ch in [
            'a',
            '@',
            '░',
            '\u{2800}',
            '\u{28FF}',
            '\u{1FB3C}',
            '\u{1CDE6}',
        ] {
            assert_eq!(complement(ch), None, "{ch:?}");
        }
    }

    #[test]
    fn sgr_cost_is_the_length_of_the_sgr() {
        let inks = [
            Ink::Default,
            Ink::Indexed(0),
            Ink::Indexed(7),
            Ink::Indexed(8),
            Ink::Indexed(15),
            Ink::Indexed(16),
            Ink::Indexed(99),
            Ink::Indexed(255),
            Ink::Rgb(Rgb::new(0, 9, 10)),
            Ink::Rgb(Rgb::new(99, 100, 255)),
        ];
        let pens: Vec<Pen> = inks
            .iter()
            .flat_map(|&fg| inks.iter().map(move |&bg| Pen { fg, bg }))
            .collect();
        for &from in &pens {
            for &to in &pens {
                assert_eq!(
                    sgr_cost(Inks::of(from), Inks::of(to)),
                    sgr(from, to).len(),
                    "{from:?} → {to:?}"
                );
            }
        }
    }

    #[test]
    fn a_cell_is_drawn_the_other_way_round_when_that_keeps_the_pen() {
        let red = Some(Rgb::new(255, 0, 0));
        let blue = Some(Rgb::new(0, 0, 255));
        let cell = |ch, fg, bg| Cell { ch, fg, bg };
        let mut f = Frame::new(4, 1);
        f.set(0, 0, cell('▀', red, blue));
        f.set(1, 0, cell('▀', blue, red));
        f.set(2, 0, cell(' ', None, red));
        f.set(3, 0, cell('▘', blue, red));
        let mut e = Encoder::new(ColorDepth::TrueColor).with_sync(false);
        e.prepare(&f);
        // One SGR for the row: `▀` blue on red is `▄` red on blue, a blank in
        // red is `█` in red, `▘` blue on red is `▟` red on blue.
        assert_eq!(
            String::from_utf8(e.last_bytes().to_vec()).unwrap(),
            "\x1b[H\x1b[m\x1b[2J\x1b[38;2;255;0;0;48;2;0;0;255m▀▄█▟\x1b[m"
        );
        // The same picture drawn the other way round is no change.
        let mut g = Frame::new(4, 1);
        g.set(0, 0, cell('▄', blue, red));
        g.set(1, 0, cell('▄', red, blue));
        g.set(2, 0, cell('█', red, None));
        g.set(3, 0, cell('▟', red, blue));
        e.prepare(&g);
        assert_eq!(e.last_bytes(), b"");
        // A default colour is not the same as a foreground and as a
        // background: such a cell is never flipped.
        let mut h = Frame::new(2, 1);
        h.set(0, 0, cell('▀', red, blue));
        h.set(1, 0, cell('▀', blue, None));
        e.prepare(&h);
        assert!(
            e.last_bytes()
                .ends_with("\x1b[38;2;0;0;255;49m▀\x1b[m".as_bytes())
        );
    }
}
