//! What `spin` writes over its frames: the status line (the parts that
//! fit, by priority), a notice, and the help box listing the keys. Drawn
//! into the frame's cells after rendering, so the encoder sends them as it
//! sends the picture (only what changed); every text that may come from a
//! file is escaped.

use crate::color::Rgb;
use crate::frame::{Cell, Frame};

/// Joins the first non-empty `parts` (highest priority first) with ` · `
/// into `out`: as many as fit `width` cells, a part never cut (the first
/// is cut only where it alone is wider, by [`overlay`]).
pub(super) fn fit_status(out: &mut String, parts: &[String], width: usize) {
    out.clear();
    let mut len = 1;
    for text in parts.iter().filter(|t| !t.is_empty()) {
        let add = text.chars().count() + if out.is_empty() { 1 } else { 3 };
        if !out.is_empty() && len + add > width {
            break;
        }
        out.push_str(if out.is_empty() { " " } else { " · " });
        out.push_str(text);
        len += add;
    }
    out.push(' ');
}

/// Writes `text` over the last row of `frame`, white on black; across the
/// whole row with `full_row`, else over as many cells as the text needs.
/// A notice may name what came from a file: it is escaped, never drawn raw.
pub(super) fn overlay(frame: &mut Frame, text: &str, full_row: bool) {
    let row = frame.rows().saturating_sub(1);
    let text = crate::text::escape(text);
    let mut chars = text.chars();
    for col in 0..frame.cols() {
        let ch = match chars.next() {
            Some(c) => c,
            None if full_row => ' ',
            None => break,
        };
        frame.set(
            col,
            row,
            Cell {
                ch,
                fg: Some(Rgb::WHITE),
                bg: Some(Rgb::BLACK),
            },
        );
    }
}

/// Draws `keys` (each a key and what it does) in a box over the middle of
/// `frame`, light on dark grey, cut to the frame where it is smaller.
/// Nothing is allocated: each row's characters are chained as drawn.
pub(super) fn help_box(frame: &mut Frame, keys: &[(&str, &str)]) {
    const TITLE: &str = "keys (? hides)";
    let len = |s: &str| s.chars().count();
    let key_width = keys.iter().map(|(k, _)| len(k)).max().unwrap_or(0);
    let inner = keys
        .iter()
        .map(|(_, what)| key_width + 2 + len(what))
        .max()
        .unwrap_or(0)
        .max(len(TITLE));
    let (cols, rows) = (usize::from(frame.cols()), usize::from(frame.rows()));
    let width = (inner + 4).min(cols);
    let height = (keys.len() + 3).min(rows);
    let (left, top) = ((cols - width) / 2, (rows - height) / 2);
    let cell = |ch| Cell {
        ch,
        fg: Some(Rgb::new(0xee, 0xee, 0xee)),
        bg: Some(Rgb::new(0x30, 0x30, 0x30)),
    };
    for r in 0..height {
        let y = (top + r) as u16;
        for c in 0..width {
            frame.set((left + c) as u16, y, cell(' '));
        }
        // Two cells of margin each side; a blank row, the title, the keys.
        let mut put = |from: usize, text: &str| {
            for (c, ch) in (2 + from..width.saturating_sub(2)).zip(text.chars()) {
                frame.set((left + c) as u16, y, cell(ch));
            }
        };
        match r {
            0 => {}
            1 => put(0, TITLE),
            _ => {
                if let Some((k, what)) = keys.get(r - 2) {
                    put(0, k);
                    put(key_width + 2, what);
                }
            }
        }
    }
}
