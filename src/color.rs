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

    /// Rounds and clamps float channels in [0, 255]; a NaN channel becomes 0.
    pub fn from_f32(c: [f32; 3]) -> Self {
        // `as u8` saturates and maps NaN to 0.
        Rgb(c.map(|v| v.round() as u8))
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
    fn from_f32_rounds_clamps_and_survives_nan() {
        assert_eq!(Rgb::from_f32([0.4, 254.6, 300.0]), Rgb([0, 255, 255]));
        assert_eq!(Rgb::from_f32([f32::NAN, -5.0, 127.5]), Rgb([0, 0, 128]));
    }
}

/// How many colours the terminal shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ColorDepth {
    /// Glyphs only, no escape sequences at all.
    None,
    /// 24-bit SGR (`38;2;r;g;b`).
    #[default]
    TrueColor,
}

impl ColorDepth {
    /// Whether cells carry colours at all.
    pub fn has_color(self) -> bool {
        self != ColorDepth::None
    }
}
