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
