//! Stage 7: the encoder, from a [`Frame`] to the bytes a terminal reads.
//!
//! It writes to any `io::Write` and keeps track of the colours the terminal
//! already has (the "pen"), so that an SGR sequence is written only where
//! the next cell needs a different foreground or background, both changes
//! in one sequence. A blank cell shows only its background, so its
//! foreground never forces an SGR. Bytes are gathered in a buffer kept
//! between frames and handed to the writer in one `write_all`.
//!
//! [`write_lines`] prints a frame as lines of text, for `rastty render`:
//! each row ends with an attribute reset (so no colour bleeds into the
//! rest of the line or the shell prompt) and a newline. With
//! [`ColorDepth::None`] it writes the frame's plain text and no escape
//! sequence at all.

use std::io::{self, Write};

use crate::color::{ColorDepth, Rgb};
use crate::frame::{Cell, Frame};

/// The colours the terminal currently draws with; `None` is its default.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Pen {
    pub fg: Option<Rgb>,
    pub bg: Option<Rgb>,
}

impl Pen {
    /// The pen a cell needs. A blank keeps whatever foreground is current.
    fn for_cell(self, cell: &Cell) -> Pen {
        Pen {
            fg: if cell.ch == ' ' { self.fg } else { cell.fg },
            bg: cell.bg,
        }
    }
}

/// Appends the decimal digits of `n`.
fn push_u8(buf: &mut Vec<u8>, n: u8) {
    if n >= 100 {
        buf.push(b'0' + n / 100);
    }
    if n >= 10 {
        buf.push(b'0' + (n / 10) % 10);
    }
    buf.push(b'0' + n % 10);
}

/// Appends the SGR parameters of one colour plane: `base` is 38 for the
/// foreground, 48 for the background.
fn push_color(buf: &mut Vec<u8>, base: u8, c: Option<Rgb>) {
    match c {
        None => push_u8(buf, base + 1),
        Some(Rgb([r, g, b])) => {
            push_u8(buf, base);
            buf.extend_from_slice(b";2;");
            push_u8(buf, r);
            buf.push(b';');
            push_u8(buf, g);
            buf.push(b';');
            push_u8(buf, b);
        }
    }
}

/// Appends the shortest SGR taking the terminal from `from` to `to`;
/// nothing when they are equal.
pub fn push_sgr(buf: &mut Vec<u8>, from: Pen, to: Pen) {
    if from == to {
        return;
    }
    buf.extend_from_slice(b"\x1b[");
    if to == Pen::default() {
        // `CSI m` resets both planes in three bytes.
        buf.push(b'm');
        return;
    }
    let fg = from.fg != to.fg;
    if fg {
        push_color(buf, 38, to.fg);
    }
    if from.bg != to.bg {
        if fg {
            buf.push(b';');
        }
        push_color(buf, 48, to.bg);
    }
    buf.push(b'm');
}

/// Appends a character as UTF-8.
pub fn push_char(buf: &mut Vec<u8>, ch: char) {
    let mut utf8 = [0; 4];
    buf.extend_from_slice(ch.encode_utf8(&mut utf8).as_bytes());
}

/// Writes `frame` as lines of text (see the module doc). `buf` is scratch
/// space, cleared first and kept for the next call.
pub fn write_lines(
    frame: &Frame,
    depth: ColorDepth,
    buf: &mut Vec<u8>,
    out: &mut impl Write,
) -> io::Result<()> {
    buf.clear();
    for r in 0..frame.rows() {
        let mut pen = Pen::default();
        for cell in frame.row(r) {
            if depth.has_color() {
                let next = pen.for_cell(cell);
                push_sgr(buf, pen, next);
                pen = next;
            }
            push_char(buf, cell.ch);
        }
        push_sgr(buf, pen, Pen::default());
        buf.push(b'\n');
    }
    out.write_all(buf)?;
    out.flush()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sgr(from: Pen, to: Pen) -> String {
        let mut b = Vec::new();
        push_sgr(&mut b, from, to);
        String::from_utf8(b).unwrap()
    }

    #[test]
    fn sgr_writes_only_what_changes() {
        let red = Some(Rgb::new(255, 0, 0));
        let blue = Some(Rgb::new(0, 0, 255));
        let p = |fg, bg| Pen { fg, bg };
        assert_eq!(sgr(p(red, blue), p(red, blue)), "");
        assert_eq!(sgr(p(None, None), p(red, None)), "\x1b[38;2;255;0;0m");
        assert_eq!(sgr(p(red, None), p(red, blue)), "\x1b[48;2;0;0;255m");
        assert_eq!(
            sgr(p(None, None), p(red, blue)),
            "\x1b[38;2;255;0;0;48;2;0;0;255m"
        );
        assert_eq!(sgr(p(red, blue), p(red, None)), "\x1b[49m");
        assert_eq!(sgr(p(red, blue), p(None, None)), "\x1b[m");
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
        write_lines(&f, ColorDepth::TrueColor, &mut buf, &mut out).unwrap();
        assert_eq!(
            String::from_utf8(out).unwrap(),
            " \x1b[48;2;255;0;0m  \x1b[m\n\x1b[38;2;255;0;0m@  \x1b[m\n"
        );
        let mut out = Vec::new();
        write_lines(&f, ColorDepth::None, &mut buf, &mut out).unwrap();
        assert_eq!(String::from_utf8(out).unwrap(), f.to_string());
    }
}
