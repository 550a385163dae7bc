//! Colour: how it is written, computed and sent.
//!
//! **The pipeline works in linear light.** Colours as users write them
//! (`"#ff8800"` in a scene, vertex colours in a model) are sRGB-encoded
//! [`Rgb`]: their numbers are not proportional to light, and mixing them
//! as numbers darkens every blend (a surface lit at 60°, half the light,
//! would show sRGB 128, which is a fifth of the light). So each colour is
//! decoded once, to [`Lin`] (16 bits of linear light a channel; the
//! loaders store model colours decoded, the renderer decodes a scene's few
//! colours once a frame), and lighting, interpolation, anti-aliasing and a
//! cell's two-colour split all add and average linear light. The blit
//! encodes each cell's colours back to sRGB once (by tables in `srgb.rs`): a white
//! surface lit head-on shows `#ffffff`, lit at 60° `#bcbcbc`. MTL `Kd`
//! values, which exporters such as Blender write in linear light, are
//! taken as linear (a scene can say otherwise). Where a *perceptual*
//! measure is meant (which palette entry is nearest, which glyph ramp step
//! a brightness gets) the measure is OKLab, from the encoded colour.
//!
//! **Sending** a colour to a terminal of 16 or 256 colours is the palette's work ([`Palette`], [`Quantizer`]):
//! matching in OKLCh and ordered dithering.

pub(crate) mod palette;
pub(crate) mod srgb;

pub use palette::{
    ANSI16, Dither, GREY_CHROMA, Metric, Palette, Quantizer, chroma, nearest, oklab_distance,
    xterm256,
};

use std::fmt;
use std::str::FromStr;

/// An sRGB colour, 8 bits per channel. In scene files: `"#rrggbb"`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Deserialize)]
#[serde(try_from = "String")]
pub struct Rgb(pub [u8; 3]);

impl Rgb {
    /// Black.
    pub const BLACK: Rgb = Rgb([0, 0, 0]);
    /// White.
    pub const WHITE: Rgb = Rgb([255, 255, 255]);

    /// A colour from its sRGB bytes.
    pub const fn new(r: u8, g: u8, b: u8) -> Self {
        Rgb([r, g, b])
    }

    /// Luma in [0, 1]: the Rec. 709 weights on the encoded values, which
    /// are near-perceptual (for ranking brightness on glyph ramps).
    pub fn luma(self) -> f32 {
        let [r, g, b] = self.0;
        (0.2126 * r as f32 + 0.7152 * g as f32 + 0.0722 * b as f32) / 255.0
    }

    /// The channels as floats in [0, 255].
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

/// Linear light, 16 bits a channel (0 is black, 65535 the full
/// intensity of the sRGB primary): what the pipeline adds and averages.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Lin(pub [u16; 3]);

impl Lin {
    /// No light.
    pub const BLACK: Lin = Lin([0; 3]);
    /// Full light.
    pub const WHITE: Lin = Lin([65535; 3]);

    /// Decodes an sRGB colour (a table lookup).
    #[inline]
    pub fn from_srgb(c: Rgb) -> Lin {
        Lin(c.0.map(|v| srgb::DECODE[v as usize]))
    }

    /// Encodes to sRGB, correctly rounded (a table lookup).
    #[inline]
    pub fn to_srgb(self) -> Rgb {
        Rgb(self.0.map(|v| srgb::ENCODE[v as usize]))
    }

    /// Linear values in [0, 1] (an MTL `Kd`), clamped; NaN is 0.
    pub fn from_unit(c: [f32; 3]) -> Lin {
        Lin::from_f32(c.map(|v| v * 65535.0))
    }

    /// The channels as floats in [0, 65535], for lighting and
    /// interpolation.
    #[inline]
    pub fn to_f32(self) -> [f32; 3] {
        self.0.map(|v| v as f32)
    }

    /// Rounds (halves up) and clamps float channels in [0, 65535]; a NaN
    /// channel becomes 0.
    #[inline]
    pub fn from_f32(c: [f32; 3]) -> Lin {
        // `as u16` truncates, saturates and maps NaN to 0.
        Lin(c.map(|v| (v + 0.5) as u16))
    }

    /// [`Lin::from_f32`] of the three lanes of `c`, bit for bit, in SIMD
    /// lanes: the pipeline's colours are `Vec3A`, and the saturating
    /// conversion, channel by channel, was most of the cost of rounding
    /// them. The rounded value `k` is found as a float ([`Lin::round_lanes`]),
    /// and `k + 2^23`, exact, has `k` in its low bits.
    #[inline(always)]
    pub(crate) fn from_lanes(c: glam::Vec3A) -> Lin {
        let [r, g, b] = (Lin::round_lanes(c) + TWO_23).to_array();
        Lin([r, g, b].map(|v| v.to_bits() as u16))
    }

    /// [`Lin::to_f32`] in SIMD lanes, as the renderer lights and
    /// interpolates colours.
    #[inline(always)]
    pub(crate) fn to_lanes(self) -> glam::Vec3A {
        glam::Vec3A::from_array(self.to_f32())
    }

    /// `Lin::from_f32(c).to_f32()` in SIMD lanes, bit for bit: each lane
    /// rounded (halves up) and clamped to a whole number in [0, 65535], a
    /// NaN lane 0.
    #[inline(always)]
    pub(crate) fn round_lanes(c: glam::Vec3A) -> glam::Vec3A {
        use glam::Vec3A;
        let x = c + Vec3A::splat(0.5);
        // Below zero and NaN (whose comparisons are false) to 0, on every
        // architecture (SIMD max's NaN rule is not the same on all).
        let x = Vec3A::select(x.cmpge(Vec3A::ZERO), x, Vec3A::ZERO).min(Vec3A::splat(65535.0));
        // The whole number nearest x (ties to even), exactly: at 2^23 a
        // float's step is 1. One less where that is above x: x's floor,
        // which is `as u16`'s truncation of x ≥ 0.
        let t = (x + TWO_23) - TWO_23;
        t - Vec3A::select(t.cmpgt(x), Vec3A::ONE, Vec3A::ZERO)
    }
}

/// 2^23, where an `f32`'s step is 1.
const TWO_23: f32 = 8_388_608.0;

impl From<Rgb> for Lin {
    fn from(c: Rgb) -> Lin {
        Lin::from_srgb(c)
    }
}

/// How colour numbers in a file are to be read.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ColorSpace {
    /// Proportional to light (what Blender and most exporters write for
    /// MTL `Kd`).
    #[default]
    Linear,
    /// sRGB-encoded, as `#rrggbb` is.
    Srgb,
}

crate::choice::choice!(ColorSpace {
    Linear => "linear": "Proportional to light (what Blender and most exporters write for MTL `Kd`)",
    Srgb => "srgb": "sRGB-encoded, as `#rrggbb` is",
});

impl ColorSpace {
    /// Values in [0, 1] in this space, as linear light (clamped; NaN is 0).
    pub fn decode(self, c: [f32; 3]) -> Lin {
        match self {
            ColorSpace::Linear => Lin::from_unit(c),
            ColorSpace::Srgb => Lin::from_unit(c.map(|v| {
                let v = v.clamp(0.0, 1.0);
                if v <= 0.04045 {
                    v / 12.92
                } else {
                    ((v + 0.055) / 1.055).powf(2.4)
                }
            })),
        }
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
    /// Every depth, from the most colours to none.
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
    /// The terminal's own default colour.
    Default,
    /// An entry of the terminal's palette (0–15 the ANSI colours, 16–255
    /// xterm's cube and greys).
    Indexed(u8),
    /// A 24-bit colour.
    Rgb(Rgb),
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
    fn linear_light_round_trips_and_halves_to_bc() {
        for v in 0..=255u8 {
            let c = Rgb([v, 255 - v, v / 2]);
            assert_eq!(Lin::from_srgb(c).to_srgb(), c);
        }
        // Half the light of white is sRGB 188 (#bcbcbc), not 128.
        assert_eq!(Lin::from_f32([32767.5; 3]).to_srgb(), Rgb([188; 3]));
        assert_eq!(Lin::from_unit([1.0, 0.5, f32::NAN]), Lin([65535, 32768, 0]));
        // An sRGB value in [0, 1] decodes as its byte does.
        for v in [0u8, 1, 10, 128, 188, 254, 255] {
            let unit = v as f32 / 255.0;
            assert_eq!(
                ColorSpace::Srgb.decode([unit; 3]),
                Lin::from_srgb(Rgb([v; 3])),
                "{v}"
            );
        }
    }

    #[test]
    fn in_lanes_is_from_f32_bit_for_bit() {
        use glam::Vec3A;
        let mut values = vec![
            f32::NAN,
            -f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::MAX,
            f32::MIN,
            f32::MIN_POSITIVE,
            -f32::MIN_POSITIVE,
            f32::from_bits(1),
            -0.0,
            0.0,
            1e9,
            -1e9,
        ];
        // Every half-way point, its neighbours, and the steps between.
        for k in -4..=65540 {
            let h = k as f32 + 0.5;
            values.extend([h, h.next_up(), h.next_down(), k as f32, k as f32 + 0.25]);
        }
        // And 65,536 scattered bit patterns (NaNs, subnormals, huge values
        // among them).
        values.extend((0..1u32 << 16).map(|i| f32::from_bits(i.wrapping_mul(0x9e37_79b9) | 1)));
        for v in values.chunks(3) {
            let c = [v[0], v[1 % v.len()], v[2 % v.len()]];
            let want = Lin::from_f32(c);
            let lanes = Vec3A::from_array(c);
            assert_eq!(Lin::from_lanes(lanes), want, "{c:?}");
            let got = Lin::round_lanes(lanes).to_array().map(f32::to_bits);
            assert_eq!(got, want.to_f32().map(f32::to_bits), "{c:?}");
        }
    }

    #[test]
    fn from_f32_rounds_clamps_and_survives_nan() {
        assert_eq!(Rgb::from_f32([0.4, 254.6, 300.0]), Rgb([0, 255, 255]));
        assert_eq!(Rgb::from_f32([f32::NAN, -5.0, 127.5]), Rgb([0, 0, 128]));
        assert_eq!(Rgb::from_f32([2.5, 2.4999, 254.5]), Rgb([3, 2, 255]));
    }
}
