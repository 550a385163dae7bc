//! Frames as pictures: PNG and SVG, with no font.
//!
//! A picture shows what a terminal would: each cell's colours are the inks
//! the encoder would send at the palette's depth (so a 256-colour picture
//! shows the 256-colour palette's entries, dithering included), and the
//! terminal's default colours are a [`Theme`]'s. Each cell is a fixed
//! [`CellPx`] rectangle painted with its background, then with its glyph's
//! shape in the foreground, drawn geometrically:
//!
//! - block elements (half, quadrant, sextant, octant, and the other
//!   one-quarter blocks the octant mode uses) as the sub-cells they cover.
//!   A cell of `W` pixels split into `n` parts has its part edges at
//!   `⌊i·W/n⌋`, in the PNG and the SVG alike, so a sextant's three rows are
//!   5, 5 and 6 pixels high at 16 pixels a cell;
//! - braille as round dots centred in the 2×4 sub-cells;
//! - the shade blocks `░ ▒ ▓` as 1/4, 2/4, 3/4 of the foreground over the
//!   background (mixed in linear light), and any other character (the
//!   ascii ramp, a status line) as text in SVG and, in PNG, as a block of
//!   its coverage: the ramp's `k`-th of ten characters at `k/9`, other text
//!   at 1/2.
//!
//! Trade-offs: painting shapes rather than a font makes pictures identical
//! on every machine and exact to test (a sub-cell's pixels are the glyph's
//! pattern), at the price of text looking like blocks in PNG. The pixel
//! count is bounded ([`MAX_PIXELS`]) before anything is allocated.

use std::fmt::Write as _;
use std::io::{self, Write as _};
use std::path::Path;
use std::sync::OnceLock;

use rustc_hash::FxHashMap;

use crate::blit::GlyphMode;
use crate::blit::glyphs::{ASCII_RAMP, BRAILLE_DOT, SHADE_RAMP};
use crate::color::{Ink, Lin, Palette, Quantizer, Rgb, xterm256};
use crate::encode::{Rep, TermCell, write_lines};
use crate::error::{Error, Result};
use crate::frame::Frame;
use crate::outfile::OutFile;

/// The most pixels a picture may have (8,192 × 8,192).
pub const MAX_PIXELS: u64 = 1 << 26;
/// The largest cell, in pixels, either way.
pub const MAX_CELL_PX: u16 = 256;

/// The size of a cell in pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CellPx {
    /// Width.
    pub w: u16,
    /// Height.
    pub h: u16,
}

impl Default for CellPx {
    /// 8×16, a common terminal cell (its aspect is 0.5, the renderer's
    /// default cell aspect).
    fn default() -> Self {
        CellPx { w: 8, h: 16 }
    }
}

impl CellPx {
    /// The cell's width over its height: the `cell_aspect` a frame drawn
    /// for this picture should have.
    pub fn aspect(self) -> f32 {
        f32::from(self.w) / f32::from(self.h)
    }
}

impl std::str::FromStr for CellPx {
    type Err = String;

    /// `W×H` or `WxH`, each from 1 to [`MAX_CELL_PX`].
    fn from_str(s: &str) -> std::result::Result<CellPx, String> {
        let (w, h) = s
            .split_once(['x', 'X', '×'])
            .ok_or_else(|| format!("'{s}' is not W×H (8×16, or 8x16)"))?;
        let side = |t: &str| -> std::result::Result<u16, String> {
            match t.trim().parse::<u16>() {
                Ok(n) if (1..=MAX_CELL_PX).contains(&n) => Ok(n),
                _ => Err(format!(
                    "'{t}' in '{s}' is not a whole number of pixels from 1 to {MAX_CELL_PX}"
                )),
            }
        };
        Ok(CellPx {
            w: side(w)?,
            h: side(h)?,
        })
    }
}

/// The terminal's default colours, for cells that use them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Theme {
    /// The default foreground.
    pub fg: Rgb,
    /// The default background.
    pub bg: Rgb,
}

impl Default for Theme {
    /// xterm's light grey (ANSI 7) on black.
    fn default() -> Self {
        Theme {
            fg: Rgb([229, 229, 229]),
            bg: Rgb::BLACK,
        }
    }
}

impl Theme {
    /// The colour a terminal with this theme shows for `ink`.
    pub fn color(self, ink: Ink, foreground: bool) -> Rgb {
        match ink {
            Ink::Default if foreground => self.fg,
            Ink::Default => self.bg,
            Ink::Indexed(i) => xterm256(i),
            Ink::Rgb(c) => c,
        }
    }
}

/// How a character is painted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    /// `w × h` sub-cells, bit `r·w + c` set where the foreground covers
    /// (as [`GlyphMode::glyph`] numbers them).
    Blocks {
        /// Sub-cells across.
        w: u8,
        /// Sub-cells down.
        h: u8,
        /// The covered sub-cells.
        mask: u8,
    },
    /// Braille dots, as a 2×4 mask in the same order.
    Dots(u8),
    /// Foreground over background at `n/36` (a shade block, or a
    /// character drawn as text in SVG when `text`).
    Cover {
        /// Coverage in 36ths.
        n: u8,
        /// Drawn as a character in SVG.
        text: bool,
    },
}

/// How `ch` is painted (see the module doc).
pub fn shape(ch: char) -> Shape {
    static SHAPES: OnceLock<FxHashMap<char, Shape>> = OnceLock::new();
    let map = SHAPES.get_or_init(|| {
        let mut map = FxHashMap::default();
        // The coarsest grid that draws a character describes it.
        for mode in [
            GlyphMode::Half,
            GlyphMode::Quadrant,
            GlyphMode::Sextant,
            GlyphMode::Octant,
        ] {
            let (w, h) = mode.cell_size();
            for mask in 0..=((1u16 << (w * h)) - 1) as u8 {
                map.entry(mode.glyph(mask)).or_insert(Shape::Blocks {
                    w: w as u8,
                    h: h as u8,
                    mask,
                });
            }
        }
        for (k, &c) in SHADE_RAMP.iter().enumerate().skip(1).take(3) {
            map.insert(
                c,
                Shape::Cover {
                    n: 9 * k as u8,
                    text: false,
                },
            );
        }
        for (k, &c) in ASCII_RAMP.iter().enumerate().skip(1) {
            map.insert(
                c,
                Shape::Cover {
                    n: 4 * k as u8,
                    text: true,
                },
            );
        }
        map
    });
    if let Some(&s) = map.get(&ch) {
        return s;
    }
    let u = ch as u32;
    if (0x2800..=0x28ff).contains(&u) {
        let dots = (u - 0x2800) as u8;
        let mask = (0..8).fold(0u8, |m, i| m | (((dots >> BRAILLE_DOT[i]) & 1) << i));
        return Shape::Dots(mask);
    }
    Shape::Cover { n: 18, text: true }
}

/// The pixel edges of `parts` equal parts of `px` pixels: `⌊i·px/parts⌋`.
fn edge(i: u32, px: u32, parts: u32) -> u32 {
    i * px / parts
}

/// One cell as the terminal shows it: a character and two colours.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Shown {
    ch: char,
    fg: Rgb,
    bg: Rgb,
}

/// The frame's cells as a terminal with `theme` would show them at
/// `palette`.
fn shown(frame: &Frame, palette: Palette, theme: Theme) -> Vec<Shown> {
    let mut q = Quantizer::of(palette);
    let cols = frame.cols().max(1) as usize;
    (0..frame.cells().len())
        .map(|i| {
            let t = TermCell::at(frame, &mut q, (i % cols) as u16, (i / cols) as u16);
            Shown {
                ch: t.ch,
                fg: theme.color(t.fg, true),
                bg: theme.color(t.bg, false),
            }
        })
        .collect()
}

/// `fg` over `bg` at `n/36`, mixed in linear light.
fn cover(fg: Rgb, bg: Rgb, n: u8) -> Rgb {
    let (f, b) = (Lin::from_srgb(fg).to_f32(), Lin::from_srgb(bg).to_f32());
    let t = f32::from(n) / 36.0;
    Lin::from_f32(std::array::from_fn(|i| b[i] + (f[i] - b[i]) * t)).to_srgb()
}

/// The picture's size in pixels, checked against [`MAX_PIXELS`].
fn size(frame: &Frame, cell: CellPx) -> Result<(u32, u32)> {
    check_size(frame.cols(), frame.rows(), cell)
}

/// The size in pixels of a picture of `cols`×`rows` cells, refused when
/// over [`MAX_PIXELS`]: a program checks it before it renders the frame.
pub fn check_size(cols: u16, rows: u16, cell: CellPx) -> Result<(u32, u32)> {
    let w = u32::from(cols) * u32::from(cell.w);
    let h = u32::from(rows) * u32::from(cell.h);
    if u64::from(w) * u64::from(h) > MAX_PIXELS {
        return Err(Error::Invalid(format!(
            "a picture of {cols}×{rows} cells at {}×{} pixels a cell would be {w}×{h} pixels, more than {MAX_PIXELS}: use fewer cells or smaller ones (--cell-px)",
            cell.w, cell.h
        )));
    }
    Ok((w, h))
}

/// An RGB image of a frame.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Picture {
    width: u32,
    height: u32,
    /// Row-major from the top-left, 3 bytes a pixel.
    rgb: Vec<u8>,
}

impl Picture {
    /// Paints `frame` as a terminal with `theme` would show it at
    /// `palette`, `cell` pixels a cell. Fails (before allocating) when the
    /// picture would have more than [`MAX_PIXELS`].
    pub fn paint(frame: &Frame, palette: Palette, theme: Theme, cell: CellPx) -> Result<Picture> {
        let (width, height) = size(frame, cell)?;
        let mut pic = Picture {
            width,
            height,
            rgb: vec![0; width as usize * height as usize * 3],
        };
        let (cw, ch) = (u32::from(cell.w), u32::from(cell.h));
        let cols = u32::from(frame.cols());
        for (i, s) in shown(frame, palette, theme).into_iter().enumerate() {
            let (x0, y0) = ((i as u32 % cols) * cw, (i as u32 / cols) * ch);
            let rect = |c0: u32, c1: u32, r0: u32, r1: u32| (x0 + c0, x0 + c1, y0 + r0, y0 + r1);
            match shape(s.ch) {
                Shape::Blocks { w, h, mask } => {
                    let (w, h) = (u32::from(w), u32::from(h));
                    for r in 0..h {
                        for c in 0..w {
                            let on = mask >> (r * w + c) & 1 == 1;
                            pic.fill(
                                rect(
                                    edge(c, cw, w),
                                    edge(c + 1, cw, w),
                                    edge(r, ch, h),
                                    edge(r + 1, ch, h),
                                ),
                                if on { s.fg } else { s.bg },
                            );
                        }
                    }
                }
                Shape::Dots(mask) => {
                    pic.fill(rect(0, cw, 0, ch), s.bg);
                    for k in 0..8u32 {
                        if mask >> k & 1 == 1 {
                            let (c, r) = (k % 2, k / 2);
                            pic.dot(
                                (x0 + edge(c, cw, 2), x0 + edge(c + 1, cw, 2)),
                                (y0 + edge(r, ch, 4), y0 + edge(r + 1, ch, 4)),
                                s.fg,
                            );
                        }
                    }
                }
                Shape::Cover { n, .. } => {
                    let color = if s.ch == ' ' {
                        s.bg
                    } else {
                        cover(s.fg, s.bg, n)
                    };
                    pic.fill(rect(0, cw, 0, ch), color);
                }
            }
        }
        Ok(pic)
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The pixel at column `x`, row `y` from the top-left.
    pub fn pixel(&self, x: u32, y: u32) -> Rgb {
        let i = (y as usize * self.width as usize + x as usize) * 3;
        Rgb([self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]])
    }

    /// The pixels, row-major from the top-left, 3 bytes (R, G, B) each.
    pub fn rgb(&self) -> &[u8] {
        &self.rgb
    }

    /// Fills `x0..x1 × y0..y1`.
    fn fill(&mut self, (x0, x1, y0, y1): (u32, u32, u32, u32), c: Rgb) {
        for y in y0..y1 {
            let row = (y as usize * self.width as usize) * 3;
            for px in self.rgb[row + x0 as usize * 3..row + x1 as usize * 3].chunks_exact_mut(3) {
                px.copy_from_slice(&c.0);
            }
        }
    }

    /// A round dot centred in the box `xs × ys`, its diameter 0.7 of the
    /// box's smaller side (a pixel at least): a pixel is painted when its
    /// centre is inside.
    fn dot(&mut self, xs: (u32, u32), ys: (u32, u32), c: Rgb) {
        let (cx, cy) = ((xs.0 + xs.1) as f32 / 2.0, (ys.0 + ys.1) as f32 / 2.0);
        let r = (0.35 * (xs.1 - xs.0).min(ys.1 - ys.0) as f32).max(0.5);
        for y in ys.0..ys.1 {
            for x in xs.0..xs.1 {
                let (dx, dy) = (x as f32 + 0.5 - cx, y as f32 + 0.5 - cy);
                if dx * dx + dy * dy <= r * r {
                    self.fill((x, x + 1, y, y + 1), c);
                }
            }
        }
    }

    /// Writes the picture as an 8-bit RGB PNG.
    pub fn write_png(&self, out: impl io::Write) -> io::Result<()> {
        let mut enc = png::Encoder::new(out, self.width, self.height);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_compression(png::Compression::High);
        let mut w = enc.write_header().map_err(io::Error::other)?;
        w.write_image_data(&self.rgb).map_err(io::Error::other)?;
        w.finish().map_err(io::Error::other)
    }
}

/// How faithfully one picture of a frame shows another (a palette's
/// against truecolor's), as an eye a little way off sees them: both are
/// averaged in linear light over blocks of 2×2 cells (a dithering pattern
/// blends within one) and each block pair is compared in OKLab.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Fidelity {
    /// Mean OKLab distance (ΔE) over every block (about 0.02 is just
    /// noticeable).
    pub mean: f64,
    /// The 95th percentile of ΔE over the blocks.
    pub p95: f64,
    /// Mean hue difference in degrees over the chromatic blocks (OKLab
    /// chroma of the reference at least [`CHROMATIC`]); a block shown grey
    /// has the hue its residue happens to have, which is as good as none.
    pub hue_error: f64,
    /// The shown chroma over the reference's, summed over the chromatic
    /// blocks: 1 keeps saturation, below 1 greys it.
    pub chroma_kept: f64,
    /// Blocks the reference draws distinguishably from `background` (ΔE
    /// over 0.02) that are shown as the background itself (ΔE under
    /// 0.005): a dark region lost.
    pub lost: usize,
    /// How many blocks were compared.
    pub blocks: usize,
}

/// The OKLab chroma from which [`Fidelity`] counts a block as having a
/// hue worth keeping (a pale tan is about 0.05; the palette's own grey line
/// is 0.03).
pub const CHROMATIC: f32 = 0.05;

/// Compares `shown` with `reference`, two pictures of one frame at the
/// same cell size `cell` (see [`Fidelity`]); `background` is the colour of
/// the cells the scene leaves uncovered.
///
/// # Panics
///
/// When the pictures' sizes differ.
pub fn fidelity(reference: &Picture, shown: &Picture, cell: CellPx, background: Rgb) -> Fidelity {
    assert_eq!(
        (reference.width, reference.height),
        (shown.width, shown.height),
        "pictures of one frame"
    );
    let (bw, bh) = (u32::from(cell.w) * 2, u32::from(cell.h) * 2);
    let lab = |p: &Picture, bx: u32, by: u32| {
        let mut sum = [0.0f64; 3];
        let (x1, y1) = ((bx + bw).min(p.width), (by + bh).min(p.height));
        for y in by..y1 {
            for x in bx..x1 {
                let l = Lin::from_srgb(p.pixel(x, y)).to_f32();
                (0..3).for_each(|i| sum[i] += f64::from(l[i]));
            }
        }
        let n = f64::from((x1 - bx) * (y1 - by)) * 65535.0;
        oklab_linear(sum.map(|v| (v / n) as f32))
    };
    let bg = oklab_linear(Lin::from_srgb(background).to_f32().map(|v| v / 65535.0));
    let dist = |p: [f32; 3], q: [f32; 3]| {
        f64::from(((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt())
    };
    let mut de = Vec::new();
    let (mut hue, mut chromatic, mut lost) = (0.0f64, 0usize, 0usize);
    let (mut want_c, mut got_c) = (0.0f64, 0.0f64);
    for by in (0..reference.height).step_by(bh as usize) {
        for bx in (0..reference.width).step_by(bw as usize) {
            let (want, got) = (lab(reference, bx, by), lab(shown, bx, by));
            de.push(dist(want, got));
            let (cw, cg) = (want[1].hypot(want[2]), got[1].hypot(got[2]));
            if cw >= CHROMATIC {
                let turn = (got[2].atan2(got[1]) - want[2].atan2(want[1])).to_degrees();
                let t = ((turn + 540.0).rem_euclid(360.0) - 180.0).abs();
                if t > 30.0 {
                    eprintln!(
                        "HUE {} {} {t:.0} want {want:?} got {got:?}",
                        bx / bw,
                        by / bh
                    );
                }
                hue += f64::from(t);
                chromatic += 1;
                (want_c, got_c) = (want_c + f64::from(cw), got_c + f64::from(cg));
            }
            if dist(want, bg) > 0.02 && dist(got, bg) < 0.005 {
                eprintln!("LOST {} {} want {want:?}", bx / bw, by / bh);
                lost += 1;
            }
        }
    }
    let blocks = de.len();
    de.sort_by(f64::total_cmp);
    let p95 = de
        .get((blocks * 95).div_ceil(100).saturating_sub(1))
        .copied()
        .unwrap_or(0.0);
    Fidelity {
        mean: de.iter().sum::<f64>() / blocks.max(1) as f64,
        p95,
        hue_error: hue / chromatic.max(1) as f64,
        chroma_kept: if want_c > 0.0 { got_c / want_c } else { 1.0 },
        lost,
        blocks,
    }
}

/// OKLab of a linear-light colour with channels in [0, 1].
fn oklab_linear([r, g, b]: [f32; 3]) -> [f32; 3] {
    let l = oklab::linear_srgb_to_oklab(oklab::LinearRgb { r, g, b });
    [l.l, l.a, l.b]
}

/// `frame` as an SVG document, painted as [`Picture::paint`] paints it:
/// backgrounds as rectangles (a run of equal cells in a row as one),
/// block sub-cells as one path per run of cells of the same colour, dots as
/// circles, and other characters as text in a monospace font.
pub fn svg(frame: &Frame, palette: Palette, theme: Theme, cell: CellPx) -> Result<String> {
    let (width, height) = size(frame, cell)?;
    let (cw, ch) = (u32::from(cell.w), u32::from(cell.h));
    let cells = shown(frame, palette, theme);
    let cols = usize::from(frame.cols()).max(1);
    let mut s = String::with_capacity(cells.len() * 48 + 512);
    let _ = write!(
        s,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" viewBox=\"0 0 {width} {height}\" shape-rendering=\"crispEdges\">\n\
         <rect width=\"{width}\" height=\"{height}\" fill=\"{}\"/>\n",
        theme.bg
    );
    for (y, row) in cells.chunks(cols).enumerate() {
        let y0 = y as u32 * ch;
        // Backgrounds: runs of one colour, the theme's left out.
        let mut x = 0;
        while x < row.len() {
            let bg = row[x].bg;
            let run = row[x..].iter().take_while(|c| c.bg == bg).count();
            if bg != theme.bg {
                let _ = writeln!(
                    s,
                    "<rect x=\"{}\" y=\"{y0}\" width=\"{}\" height=\"{ch}\" fill=\"{bg}\"/>",
                    x as u32 * cw,
                    run as u32 * cw
                );
            }
            x += run;
        }
        // Foregrounds: consecutive block cells of one colour share a path.
        let mut path: Option<Rgb> = None;
        for (x, c) in row.iter().enumerate() {
            let x0 = x as u32 * cw;
            let shape = if c.ch == ' ' {
                Shape::Blocks {
                    w: 1,
                    h: 1,
                    mask: 0,
                }
            } else {
                shape(c.ch)
            };
            match shape {
                Shape::Blocks { w, h, mask } => {
                    if mask == 0 {
                        continue;
                    }
                    if path != Some(c.fg) {
                        if path.is_some() {
                            s.push_str("\"/>\n");
                        }
                        let _ = write!(s, "<path fill=\"{}\" d=\"", c.fg);
                        path = Some(c.fg);
                    }
                    let (w, h) = (u32::from(w), u32::from(h));
                    for r in 0..h {
                        for k in 0..w {
                            if mask >> (r * w + k) & 1 == 1 {
                                let (a, b) = (edge(k, cw, w), edge(k + 1, cw, w));
                                let (t, u) = (edge(r, ch, h), edge(r + 1, ch, h));
                                let _ = write!(
                                    s,
                                    "M{} {}h{}v{}h-{}z",
                                    x0 + a,
                                    y0 + t,
                                    b - a,
                                    u - t,
                                    b - a
                                );
                            }
                        }
                    }
                }
                other => {
                    if path.take().is_some() {
                        s.push_str("\"/>\n");
                    }
                    svg_other(&mut s, other, c, (x0, y0), (cw, ch));
                }
            }
        }
        if path.is_some() {
            s.push_str("\"/>\n");
        }
    }
    s.push_str("</svg>\n");
    Ok(s)
}

/// A cell drawn with dots, a shade or a character.
fn svg_other(s: &mut String, shape: Shape, c: &Shown, (x0, y0): (u32, u32), (cw, ch): (u32, u32)) {
    match shape {
        Shape::Dots(mask) => {
            for k in 0..8u32 {
                if mask >> k & 1 == 1 {
                    let (col, row) = (k % 2, k / 2);
                    let (a, b) = (edge(col, cw, 2), edge(col + 1, cw, 2));
                    let (t, u) = (edge(row, ch, 4), edge(row + 1, ch, 4));
                    let r = (0.35 * (b - a).min(u - t) as f32).max(0.5);
                    let _ = writeln!(
                        s,
                        "<circle cx=\"{}\" cy=\"{}\" r=\"{r}\" fill=\"{}\"/>",
                        (2 * x0 + a + b) as f32 / 2.0,
                        (2 * y0 + t + u) as f32 / 2.0,
                        c.fg
                    );
                }
            }
        }
        Shape::Cover { text: false, n } => {
            let _ = writeln!(
                s,
                "<rect x=\"{x0}\" y=\"{y0}\" width=\"{cw}\" height=\"{ch}\" fill=\"{}\"/>",
                cover(c.fg, c.bg, n)
            );
        }
        Shape::Cover { text: true, .. } | Shape::Blocks { .. } => {
            let _ = write!(
                s,
                "<text x=\"{}\" y=\"{}\" font-family=\"monospace\" font-size=\"{}\" text-anchor=\"middle\" fill=\"{}\">",
                x0 as f32 + cw as f32 / 2.0,
                y0 as f32 + ch as f32 * 0.8,
                ch as f32 * 0.9,
                c.fg
            );
            match c.ch {
                '&' => s.push_str("&amp;"),
                '<' => s.push_str("&lt;"),
                '>' => s.push_str("&gt;"),
                ch if ch.is_control() => s.push('?'),
                ch => s.push(ch),
            }
            s.push_str("</text>\n");
        }
    }
}

/// What a frame can be saved as, named by a file's extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// `.png`: a [`Picture`].
    Png,
    /// `.svg`: [`svg`].
    Svg,
    /// `.ans`: the ANSI frame, as `rastty render` prints it.
    Ans,
    /// `.txt`: the plain text (the frame's `Display`).
    Txt,
}

impl Format {
    /// The format a path's extension names (in any case).
    pub fn of(path: &Path) -> Result<Format> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("png") => Ok(Format::Png),
            Some("svg") => Ok(Format::Svg),
            Some("ans") => Ok(Format::Ans),
            Some("txt") => Ok(Format::Txt),
            _ => Err(Error::Invalid(format!(
                "{}: the output format comes from the extension: .png, .svg, .ans or .txt",
                path.display()
            ))),
        }
    }

    /// Whether the format has colour (all but text).
    pub fn has_color(self) -> bool {
        self != Format::Txt
    }
}

/// Writes `frame` to `path` in `format`: pictures at `cell` pixels a cell
/// in `theme`'s default colours, colours as `palette` sends them. Returns
/// the bytes written. The file is written as [`OutFile`] writes: an
/// existing one is replaced only once the whole picture is written.
pub fn save(
    frame: &Frame,
    path: &Path,
    format: Format,
    palette: Palette,
    theme: Theme,
    cell: CellPx,
) -> Result<usize> {
    let mut out = OutFile::create(path)?;
    let n = write(frame, &mut out, format, palette, theme, cell)?;
    out.commit()?;
    Ok(n)
}

/// Writes `frame` to `out` (a file named `out.path()`) in `format`, as
/// [`save`] does, without committing it. Returns the bytes written.
pub fn write(
    frame: &Frame,
    out: &mut OutFile,
    format: Format,
    palette: Palette,
    theme: Theme,
    cell: CellPx,
) -> Result<usize> {
    // Made in memory first: a refusal writes nothing.
    let mut body = Vec::new();
    match format {
        Format::Png => Picture::paint(frame, palette, theme, cell)?.write_png(&mut body),
        Format::Svg => {
            body = svg(frame, palette, theme, cell)?.into_bytes();
            Ok(())
        }
        Format::Ans => write_lines(frame, palette, Rep::Off, &mut Vec::new(), &mut body),
        Format::Txt => write!(body, "{frame}"),
    }
    .map_err(|e| Error::io(out.path(), e))?;
    out.write_all(&body).map_err(|e| Error::io(out.path(), e))?;
    Ok(body.len())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::choice::Choice;

    #[test]
    fn cell_sizes_parse_with_either_cross_and_refuse_zero_and_huge() {
        assert_eq!("8x16".parse(), Ok(CellPx { w: 8, h: 16 }));
        assert_eq!("10×20".parse(), Ok(CellPx { w: 10, h: 20 }));
        assert!("0x16".parse::<CellPx>().is_err());
        assert!("8x257".parse::<CellPx>().is_err());
        assert!("8".parse::<CellPx>().is_err());
    }

    #[test]
    fn every_glyph_has_the_coarsest_shape_that_draws_it() {
        assert_eq!(
            shape('▀'),
            Shape::Blocks {
                w: 1,
                h: 2,
                mask: 1
            }
        );
        assert_eq!(
            shape('▐'),
            Shape::Blocks {
                w: 2,
                h: 2,
                mask: 0b1010
            }
        );
        assert_eq!(
            shape('\u{1FB00}'),
            Shape::Blocks {
                w: 2,
                h: 3,
                mask: 1
            }
        );
        assert_eq!(
            shape('\u{1FB82}'),
            Shape::Blocks {
                w: 2,
                h: 4,
                mask: 3
            }
        );
        // Braille dot 1 (bit 0) is sample 0, dot 4 (bit 3) sample 1, dot 7
        // (bit 6) sample 6.
        assert_eq!(shape('\u{2801}'), Shape::Dots(1));
        assert_eq!(shape('\u{2808}'), Shape::Dots(2));
        assert_eq!(shape('\u{2840}'), Shape::Dots(64));
        assert_eq!(shape('@'), Shape::Cover { n: 36, text: true });
        assert_eq!(shape('▒'), Shape::Cover { n: 18, text: false });
        assert_eq!(shape('x'), Shape::Cover { n: 18, text: true });
        for mode in [GlyphMode::Sextant, GlyphMode::Octant] {
            let (w, h) = mode.cell_size();
            for mask in 0..=((1u16 << (w * h)) - 1) as u8 {
                // Whatever grid describes it, the same area is covered.
                let Shape::Blocks {
                    w: sw,
                    h: sh,
                    mask: m,
                } = shape(mode.glyph(mask))
                else {
                    panic!("{mask}")
                };
                for r in 0..h {
                    for c in 0..w {
                        let (sc, sr) = (c * u32::from(sw) / w, r * u32::from(sh) / h);
                        assert_eq!(
                            mask >> (r * w + c) & 1,
                            m >> (sr * u32::from(sw) + sc) & 1,
                            "{} {mask:#x}",
                            mode.name()
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn too_many_pixels_are_refused_before_allocating() {
        let frame = Frame::new(1000, 1000);
        let big = CellPx { w: 16, h: 32 };
        let err = Picture::paint(&frame, Palette::default(), Theme::default(), big).unwrap_err();
        assert!(err.to_string().contains("16000×32000 pixels"), "{err}");
        assert!(svg(&frame, Palette::default(), Theme::default(), big).is_err());
    }
}
