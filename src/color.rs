//! Colours shared by every stage: an 8-bit sRGB triple, its parsing from
//! `#rrggbb` and its brightness.
//!
//! Colours are interpolated and averaged in sRGB byte space, as a GPU does
//! without sRGB render targets: cheap, and what a user choosing hex colours
//! expects to see blended.

use std::fmt;
use std::str::FromStr;

/// An sRGB colour, 8 bits per channel. In scene files: `"#rrggbb"`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Deserialize)]
#[serde(try_from = "String")]
pub struct Rgb(pub [u8; 3]);

impl Rgb {
    pub const BLACK: Rgb = Rgb([0, 0, 0]);
    pub const WHITE: Rgb = Rgb([255, 255, 255]);

    pub const fn new(r: u8, g: u8, b: u8) -> Self {
        Rgb([r, g, b])
    }

    /// Relative luminance in [0, 1] with the Rec. 709 weights on the sRGB
    /// values (no linearisation: it only ranks brightness for glyph ramps).
    pub fn luma(self) -> f32 {
        let [r, g, b] = self.0;
        (0.2126 * r as f32 + 0.7152 * g as f32 + 0.0722 * b as f32) / 255.0
    }

    /// The channels as floats in [0, 255], for interpolation.
    pub fn to_f32(self) -> [f32; 3] {
        let [r, g, b] = self.0;
        [r as f32, g as f32, b as f32]
    }

    /// Rounds (halves up) and clamps float channels in [0, 255]; a NaN
    /// channel becomes 0.
    #[inline]
    pub fn from_f32(c: [f32; 3]) -> Self {
        // `as u8` truncates, saturates and maps NaN to 0; adding a half
        // first rounds without `f32::round`'s library call (negative
        // values all end at 0 either way).
        Rgb(c.map(|v| (v + 0.5) as u8))
    }
}

impl fmt::Display for Rgb {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let [r, g, b] = self.0;
        write!(f, "#{r:02x}{g:02x}{b:02x}")
    }
}

/// Why a colour string was refused.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("invalid colour {0:?}: expected \"#rrggbb\"")]
pub struct ParseRgbError(pub String);

impl FromStr for Rgb {
    type Err = ParseRgbError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let err = || ParseRgbError(s.to_string());
        let hex = s.strip_prefix('#').ok_or_else(err)?;
        if hex.len() != 6 || !hex.bytes().all(|b| b.is_ascii_hexdigit()) {
            return Err(err());
        }
        let channel = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).map_err(|_| err());
        Ok(Rgb([channel(0)?, channel(2)?, channel(4)?]))
    }
}

impl TryFrom<String> for Rgb {
    type Error = ParseRgbError;
    fn try_from(s: String) -> Result<Self, Self::Error> {
        s.parse()
    }
}

/// How many colours the terminal shows, fewest first.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum ColorDepth {
    /// Glyphs only: no colour escape sequence at all.
    None,
    /// The 16 ANSI colours (SGR 30–37, 90–97 and 40–47, 100–107).
    Ansi16,
    /// The xterm 256-colour palette's 6×6×6 cube and 24 greys
    /// (`38;5;n`).
    Ansi256,
    /// 24-bit SGR (`38;2;r;g;b`).
    #[default]
    TrueColor,
}

impl ColorDepth {
    pub const ALL: [ColorDepth; 4] = [
        ColorDepth::None,
        ColorDepth::Ansi16,
        ColorDepth::Ansi256,
        ColorDepth::TrueColor,
    ];

    /// The name the command line uses (`--color 256`).
    pub const fn name(self) -> &'static str {
        match self {
            ColorDepth::None => "none",
            ColorDepth::Ansi16 => "16",
            ColorDepth::Ansi256 => "256",
            ColorDepth::TrueColor => "truecolor",
        }
    }

    /// Whether cells carry colours at all.
    pub fn has_color(self) -> bool {
        self != ColorDepth::None
    }
}

/// A colour as the terminal is told it: its default, a palette index, or
/// 24-bit.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Ink {
    #[default]
    Default,
    Indexed(u8),
    Rgb(Rgb),
}

/// How "nearest" is measured when a colour is mapped onto a palette.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Metric {
    /// Squared distance of the sRGB bytes: cheap, and visibly wrong for
    /// darks and blues.
    Rgb,
    /// Squared distance in OKLab, a perceptually uniform space.
    #[default]
    Oklab,
}

/// The xterm defaults for the 16 ANSI colours (terminals differ; these are
/// what "nearest" is measured against).
pub const ANSI16: [Rgb; 16] = [
    Rgb([0, 0, 0]),
    Rgb([205, 0, 0]),
    Rgb([0, 205, 0]),
    Rgb([205, 205, 0]),
    Rgb([0, 0, 238]),
    Rgb([205, 0, 205]),
    Rgb([0, 205, 205]),
    Rgb([229, 229, 229]),
    Rgb([127, 127, 127]),
    Rgb([255, 0, 0]),
    Rgb([0, 255, 0]),
    Rgb([255, 255, 0]),
    Rgb([92, 92, 255]),
    Rgb([255, 0, 255]),
    Rgb([0, 255, 255]),
    Rgb([255, 255, 255]),
];

/// The levels of the xterm 6×6×6 cube.
const CUBE: [u8; 6] = [0, 95, 135, 175, 215, 255];

/// The RGB value of xterm palette index `i` (16–255; 0–15 are
/// [`ANSI16`]).
pub fn xterm256(i: u8) -> Rgb {
    match i {
        0..=15 => ANSI16[i as usize],
        16..=231 => {
            let k = i - 16;
            Rgb([
                CUBE[(k / 36) as usize],
                CUBE[(k / 6 % 6) as usize],
                CUBE[(k % 6) as usize],
            ])
        }
        _ => {
            let v = 8 + 10 * (i - 232);
            Rgb([v, v, v])
        }
    }
}

fn oklab(c: Rgb) -> [f32; 3] {
    let [r, g, b] = c.0;
    let l = oklab::srgb_to_oklab(oklab::Rgb { r, g, b });
    [l.l, l.a, l.b]
}

/// The distance between two colours in OKLab (about 0.02 is a just
/// noticeable difference).
pub fn oklab_distance(a: Rgb, b: Rgb) -> f32 {
    let (p, q) = (oklab(a), oklab(b));
    ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
}

/// The 256 palette colours in OKLab, computed once.
fn palette_oklab() -> &'static [[f32; 3]; 256] {
    static TABLE: std::sync::OnceLock<[[f32; 3]; 256]> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| std::array::from_fn(|i| oklab(xterm256(i as u8))))
}

/// The palette index nearest to `c`: among the cube and greys (16–255) for
/// [`ColorDepth::Ansi256`], among [`ANSI16`] for [`ColorDepth::Ansi16`].
/// Ties go to the lower index.
pub fn nearest(depth: ColorDepth, metric: Metric, c: Rgb) -> u8 {
    let range = match depth {
        ColorDepth::Ansi16 => 0..=15u8,
        _ => 16..=255u8,
    };
    let table = palette_oklab();
    let p = match metric {
        Metric::Rgb => c.to_f32(),
        Metric::Oklab => oklab(c),
    };
    let mut best = (f32::INFINITY, *range.start());
    for i in range {
        let q = match metric {
            Metric::Rgb => xterm256(i).to_f32(),
            Metric::Oklab => table[i as usize],
        };
        let d = (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2);
        if d < best.0 {
            best = (d, i);
        }
    }
    best.1
}

/// Maps colours to [`Ink`] for one depth, remembering recent answers (the
/// nearest-palette search is 240 distance evaluations; a frame has few
/// distinct colours). The cache is direct-mapped and allocated once.
#[derive(Clone, Debug)]
pub struct Quantizer {
    depth: ColorDepth,
    metric: Metric,
    /// `(rgb | VALID, index)`.
    cache: Vec<(u32, u8)>,
}

const CACHE_BITS: u32 = 12;
const VALID: u32 = 1 << 24;

impl Quantizer {
    pub fn new(depth: ColorDepth, metric: Metric) -> Quantizer {
        Quantizer {
            depth,
            metric,
            cache: Vec::new(),
        }
    }

    pub fn depth(&self) -> ColorDepth {
        self.depth
    }

    /// The ink for a colour (`None`: the terminal's default).
    pub fn ink(&mut self, c: Option<Rgb>) -> Ink {
        let Some(c) = c else { return Ink::Default };
        match self.depth {
            ColorDepth::None => Ink::Default,
            ColorDepth::TrueColor => Ink::Rgb(c),
            depth => {
                if self.cache.is_empty() {
                    self.cache = vec![(0, 0); 1 << CACHE_BITS];
                }
                let [r, g, b] = c.0;
                let key = (r as u32) << 16 | (g as u32) << 8 | b as u32;
                let slot = (key.wrapping_mul(0x9E37_79B1) >> (32 - CACHE_BITS)) as usize;
                let (k, v) = self.cache[slot];
                if k == key | VALID {
                    return Ink::Indexed(v);
                }
                let v = nearest(depth, self.metric, c);
                self.cache[slot] = (key | VALID, v);
                Ink::Indexed(v)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_prints_hex() {
        assert_eq!("#ff8800".parse::<Rgb>(), Ok(Rgb([255, 136, 0])));
        assert_eq!("#FF8800".parse::<Rgb>(), Ok(Rgb([255, 136, 0])));
        assert_eq!(Rgb([255, 136, 0]).to_string(), "#ff8800");
        for bad in ["ff8800", "#ff880", "#ff88000", "#gg8800", "", "#"] {
            assert!(bad.parse::<Rgb>().is_err(), "{bad:?}");
        }
    }

    #[test]
    fn luma_orders_black_grey_white() {
        assert_eq!(Rgb::BLACK.luma(), 0.0);
        assert!((Rgb::WHITE.luma() - 1.0).abs() < 1e-6);
        assert!(Rgb::new(0, 0, 255).luma() < Rgb::new(255, 0, 0).luma());
    }

    #[test]
    fn xterm_palette_values() {
        assert_eq!(xterm256(16), Rgb([0, 0, 0]));
        assert_eq!(xterm256(196), Rgb([255, 0, 0]));
        assert_eq!(xterm256(231), Rgb([255, 255, 255]));
        assert_eq!(xterm256(232), Rgb([8, 8, 8]));
        assert_eq!(xterm256(255), Rgb([238, 238, 238]));
    }

    #[test]
    fn nearest_finds_exact_palette_colours() {
        for i in 16..=255u8 {
            let c = xterm256(i);
            let j = nearest(ColorDepth::Ansi256, Metric::Oklab, c);
            assert_eq!(xterm256(j), c, "index {i}");
        }
        for (i, &c) in ANSI16.iter().enumerate() {
            assert_eq!(nearest(ColorDepth::Ansi16, Metric::Rgb, c), i as u8);
        }
        assert_eq!(
            nearest(ColorDepth::Ansi16, Metric::Oklab, Rgb([250, 10, 10])),
            9
        );
    }

    #[test]
    fn quantizer_caches_without_changing_answers() {
        let mut q = Quantizer::new(ColorDepth::Ansi256, Metric::Oklab);
        for c in [Rgb([1, 2, 3]), Rgb([200, 100, 50]), Rgb([1, 2, 3])] {
            assert_eq!(
                q.ink(Some(c)),
                Ink::Indexed(nearest(ColorDepth::Ansi256, Metric::Oklab, c))
            );
        }
        assert_eq!(q.ink(None), Ink::Default);
        let mut t = Quantizer::new(ColorDepth::TrueColor, Metric::Oklab);
        assert_eq!(t.ink(Some(Rgb([1, 2, 3]))), Ink::Rgb(Rgb([1, 2, 3])));
    }

    #[test]
    fn from_f32_rounds_clamps_and_survives_nan() {
        assert_eq!(Rgb::from_f32([0.4, 254.6, 300.0]), Rgb([0, 255, 255]));
        assert_eq!(Rgb::from_f32([f32::NAN, -5.0, 127.5]), Rgb([0, 0, 128]));
        assert_eq!(Rgb::from_f32([2.5, 2.4999, 254.5]), Rgb([3, 2, 255]));
    }
}
