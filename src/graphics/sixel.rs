//! Sixel: a DCS sequence (`ESC P 0;1;0 q … ESC \`) whose pixels are colour
//! register numbers, six rows at a time. The terminal has a fixed number of
//! registers (XTSMGRAPHICS tells; VT340s had 16, xterm has up to 1024), so
//! the frame's colours are mapped onto xterm's 256-colour palette (or the
//! 16 ANSI colours where the terminal has fewer than 256 registers) by
//! rastty's own quantizer: OKLCh distance and ordered dithering anchored to
//! the screen, the mapping the character cells use at those depths (its
//! fidelity is measured in docs/usage.md). Only the registers a frame uses
//! are defined, each once (and chosen again after it is defined: xterm
//! otherwise draws the band with what the register held before). The
//! second parameter 1 leaves pixels nothing
//! paints as they are: a transparent pixel is not painted, so the model
//! sits on the terminal's background.
//!
//! A pixel's channels are first resolved to [`resolved`]'s 64 levels (and
//! every level a palette entry has): the dither's sixteenths between
//! neighbouring entries are steps of 2.5 or more where the palette is
//! densest, so the picture keeps its colours, while a frame of smooth
//! shading has a few thousand colours for the quantizer to place rather
//! than tens of thousands.
//!
//! Each band of six rows is one pass over its pixels, which sets the bits
//! of each colour's sixels in a row of its own; each colour present is then
//! written from its first to its last column, runs of one sixel as
//! `!count` (run-length encoding), and `$` returns to the band's start for
//! the next colour, `-` goes to the next band.

use std::io::Write as _;

use crate::color::palette::{Metric, Quantizer, xterm256};
use crate::color::{ColorDepth, Ink, Rgb};
use crate::pixels::Pixels;

/// The colour a pixel is quantized as: each channel a palette's own level
/// (xterm's 256 colours and the 16 ANSI colours), kept, or else the middle
/// of its group of four values, within 2 of the channel.
pub fn resolved(c: Rgb) -> Rgb {
    static LEVELS: std::sync::OnceLock<[u8; 256]> = std::sync::OnceLock::new();
    let levels = LEVELS.get_or_init(|| {
        let mut own = [false; 256];
        for i in 0..=255u8 {
            for v in xterm256(i).0 {
                own[v as usize] = true;
            }
        }
        std::array::from_fn(|v| if own[v] { v as u8 } else { (v as u8 & !3) + 2 })
    });
    Rgb(c.0.map(|v| levels[v as usize]))
}

/// How a frame's colours are mapped onto registers.
#[derive(Clone, Debug)]
pub struct Encoder {
    quantizer: Quantizer,
    /// A register's sixels across the band, by slot.
    rows: Vec<u8>,
    /// Each register's slot in `rows` in this band (u16::MAX: absent), and
    /// its first and last column.
    slot: Vec<u16>,
    span: Vec<(u32, u32)>,
    /// The registers present in this band, in order of first appearance.
    present: Vec<u8>,
    /// Each pixel's register plus one (0: not painted), for a band.
    band: Vec<u16>,
    /// What a transparent pixel is painted (`None`: not painted).
    background: Option<Rgb>,
}

impl Encoder {
    /// An encoder for a terminal with `registers` colour registers: 256
    /// or more get xterm's 256 colours, fewer the 16 ANSI colours.
    pub fn new(registers: u16) -> Encoder {
        let depth = if registers >= 256 {
            ColorDepth::Ansi256
        } else {
            ColorDepth::Ansi16
        };
        Encoder {
            // A frame of pixels has far more colours than one of cells.
            quantizer: Quantizer::new(depth, Metric::Oklch).with_cache_bits(16),
            rows: Vec::new(),
            slot: vec![u16::MAX; 256],
            span: vec![(0, 0); 256],
            present: Vec::new(),
            band: Vec::new(),
            background: None,
        }
    }

    /// Paints transparent pixels `c` (the terminal's own background, as it
    /// answers OSC 11): an animation's frames then cover the last frame's
    /// pixels, which sixel has no way to take away. `None` leaves them
    /// unpainted, showing what is there.
    pub fn with_background(mut self, c: Option<Rgb>) -> Encoder {
        self.background = c;
        self
    }

    /// How many registers a frame may define.
    pub fn registers(&self) -> u16 {
        match self.quantizer.depth() {
            ColorDepth::Ansi256 => 256,
            _ => 16,
        }
    }

    /// The register of a pixel at `(x, y)` from the top left (`None`:
    /// transparent, not painted).
    fn register(&mut self, p: [u8; 4], x: u32, y: u32) -> Option<u8> {
        let c = if p[3] < 128 {
            self.background?
        } else {
            Rgb([p[0], p[1], p[2]])
        };
        let c = resolved(c);
        match self.quantizer.ink_at(Some(c), x as u16, y as u16) {
            Ink::Indexed(i) => Some(i),
            _ => unreachable!("a palette quantizer gives palette entries"),
        }
    }

    /// Appends `pixels` as one sixel image at the cursor.
    pub fn encode(&mut self, pixels: &Pixels, out: &mut Vec<u8>) {
        let (w, h) = (pixels.width(), pixels.height());
        // Raster attributes: a 1:1 pixel aspect, and the size.
        let _ = write!(out, "\x1bP0;1;0q\"1;1;{w};{h}");
        // Registers are defined where first used; `defined` says which.
        let mut defined = [false; 256];
        let wu = w as usize;
        self.band.resize(wu * 6, 0);
        for top in (0..h).step_by(6) {
            let n = (h - top).min(6);
            // The band's registers.
            for r in 0..n {
                let y = top + r;
                for (x, &p) in pixels.row(y).iter().enumerate() {
                    let reg = self
                        .register(p, x as u32, y)
                        .map_or(0, |i| u16::from(i) + 1);
                    self.band[r as usize * wu + x] = reg;
                }
            }
            // Each register's sixels, one pass.
            self.present.clear();
            for r in 0..n as usize {
                for x in 0..wu {
                    let reg = self.band[r * wu + x];
                    if reg == 0 {
                        continue;
                    }
                    let i = (reg - 1) as usize;
                    if self.slot[i] == u16::MAX {
                        self.slot[i] = self.present.len() as u16;
                        self.present.push(i as u8);
                        self.rows.resize(self.present.len() * wu, 0);
                        self.rows[(self.present.len() - 1) * wu..].fill(0);
                        self.span[i] = (x as u32, x as u32);
                    }
                    let s = self.slot[i] as usize;
                    self.rows[s * wu + x] |= 1 << r;
                    let span = &mut self.span[i];
                    span.0 = span.0.min(x as u32);
                    span.1 = span.1.max(x as u32);
                }
            }
            for (k, &i) in self.present.iter().enumerate() {
                if !defined[i as usize] {
                    defined[i as usize] = true;
                    let Rgb([r, g, b]) = xterm256(i);
                    let pc = |v: u8| (u32::from(v) * 100 + 127) / 255;
                    // Defined, then chosen: xterm draws with what a
                    // register held before until it is chosen again.
                    let _ = write!(out, "#{i};2;{};{};{}#{i}", pc(r), pc(g), pc(b));
                } else {
                    let _ = write!(out, "#{i}");
                }
                let (x0, x1) = self.span[i as usize];
                let row = &self.rows[k * wu..(k + 1) * wu];
                if x0 > 0 {
                    run(out, b'?', x0);
                }
                let mut x = x0 as usize;
                while x <= x1 as usize {
                    let v = row[x];
                    let mut end = x + 1;
                    while end <= x1 as usize && row[end] == v {
                        end += 1;
                    }
                    run(out, b'?' + v, (end - x) as u32);
                    x = end;
                }
                out.push(b'$');
            }
            for &i in &self.present {
                self.slot[i as usize] = u16::MAX;
            }
            if top + 6 < h {
                out.push(b'-');
            }
        }
        out.extend_from_slice(b"\x1b\\");
    }
}

/// Appends `count` copies of sixel `c`, as `!count c` where that is
/// shorter.
fn run(out: &mut Vec<u8>, c: u8, count: u32) {
    if count > 3 {
        let _ = write!(out, "!{count}");
        out.push(c);
    } else {
        for _ in 0..count {
            out.push(c);
        }
    }
}
