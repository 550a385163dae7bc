//! Helpers shared by the integration tests that read rastty's output back
//! through the `vt100` terminal emulator.

#![allow(dead_code)]

use std::num::NonZeroU16;

/// A vt100 parser of `rows × cols` cells, no scrollback.
pub fn terminal(rows: u16, cols: u16) -> vt100::Parser {
    vt100::Parser::new(nz(rows), nz(cols), 0)
}

pub fn nz(n: u16) -> NonZeroU16 {
    NonZeroU16::new(n).expect("a non-zero size")
}

/// What a terminal's output processing (ONLCR) makes of lines written with
/// `\n`, without the last newline (so that `n` lines fill an `n`-row
/// terminal without scrolling).
pub fn as_displayed(lines: &[u8]) -> Vec<u8> {
    let lines = lines.strip_suffix(b"\n").unwrap_or(lines);
    let mut out = Vec::with_capacity(lines.len() + lines.len() / 40);
    for &b in lines {
        if b == b'\n' {
            out.push(b'\r');
        }
        out.push(b);
    }
    out
}

/// The cells of a screen as text, foreground and background.
pub fn cells(screen: &vt100::Screen) -> Vec<(String, vt100::Color, vt100::Color)> {
    let (rows, cols) = screen.size();
    let mut v = Vec::new();
    for r in 0..rows.get() {
        for c in 0..cols.get() {
            let cell = screen.cell(r, c).unwrap();
            let text = if cell.contents().is_empty() {
                " ".to_string()
            } else {
                cell.contents().to_string()
            };
            let fg = if text == " " {
                vt100::Color::Default
            } else {
                cell.fgcolor()
            };
            v.push((text, fg, cell.bgcolor()));
        }
    }
    v
}
