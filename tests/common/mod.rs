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

/// Little-endian bytes of floats.
pub fn f32s(v: &[f32]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_le_bytes()).collect()
}

/// A GLB file of `json` and the binary chunk `bin`.
pub fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let mut j = json.as_bytes().to_vec();
    while !j.len().is_multiple_of(4) {
        j.push(b' ');
    }
    let mut b = bin.to_vec();
    while !b.len().is_multiple_of(4) {
        b.push(0);
    }
    let total = 12 + 8 + j.len() + 8 + b.len();
    let mut out = Vec::new();
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(j.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&j);
    out.extend_from_slice(&(b.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&b);
    out
}

/// A unit quad with a colour at each corner, in one PLY encoding.
pub fn quad_ply(format: &str) -> Vec<u8> {
    let mut out = format!(
        "ply\nformat {format} 1.0\ncomment made by rastty's tests\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
    )
    .into_bytes();
    let v = [
        ([0.0f32, 0.0, 0.0], [255u8, 0, 0]),
        ([1.0, 0.0, 0.0], [0, 255, 0]),
        ([1.0, 1.0, 0.0], [0, 0, 255]),
        ([0.0, 1.0, 0.0], [255, 255, 255]),
    ];
    match format {
        "ascii" => {
            for (p, c) in v {
                out.extend(
                    format!("{} {} {} {} {} {}\n", p[0], p[1], p[2], c[0], c[1], c[2]).bytes(),
                );
            }
            out.extend(b"4 0 1 2 3\n");
        }
        _ => {
            let be = format == "binary_big_endian";
            for (p, c) in v {
                for x in p {
                    out.extend(if be { x.to_be_bytes() } else { x.to_le_bytes() });
                }
                out.extend(c);
            }
            out.push(4);
            for i in 0i32..4 {
                out.extend(if be { i.to_be_bytes() } else { i.to_le_bytes() });
            }
        }
    }
    out
}
