//! Every glyph table, in one place.
//!
//! A pattern is a bit mask over a cell's samples, numbered row-major from
//! the top-left: bit `i` is column `i % w`, row `i / w` from the top. A set
//! bit is drawn in the foreground colour, a clear bit in the background.
//! Every character here is a single-width block element (a test checks it).

/// Half blocks, 1×2:
///
/// ```text
/// ┌───┐
/// │ 0 │
/// │ 1 │
/// └───┘
/// ```
pub const HALF: [char; 4] = [' ', '▀', '▄', '█'];

/// Quadrants, 2×2, from the block elements U+2580–U+259F:
///
/// ```text
/// ┌─────┐
/// │ 0 1 │
/// │ 2 3 │
/// └─────┘
/// ```
pub const QUADRANT: [char; 16] = [
    ' ', '▘', '▝', '▀', '▖', '▌', '▞', '▛', '▗', '▚', '▐', '▜', '▄', '▙', '▟', '█',
];

/// Sextants, 2×3:
///
/// ```text
/// ┌─────┐
/// │ 0 1 │
/// │ 2 3 │
/// │ 4 5 │
/// └─────┘
/// ```
///
/// U+1FB00–U+1FB3B hold the 60 patterns that are neither empty, full, nor a
/// left or right half, in the order of their masks; those four are the
/// space, `█`, `▌` and `▐`.
pub fn sextant(mask: u8) -> char {
    match mask & 0x3f {
        0 => ' ',
        0x15 => '▌',
        0x2a => '▐',
        0x3f => '█',
        m => {
            let skipped = (m > 0x15) as u32 + (m > 0x2a) as u32;
            char::from_u32(0x1FB00 + m as u32 - 1 - skipped).unwrap_or('?')
        }
    }
}

/// Octants, 2×4:
///
/// ```text
/// ┌─────┐
/// │ 0 1 │
/// │ 2 3 │
/// │ 4 5 │
/// │ 6 7 │
/// └─────┘
/// ```
///
/// Unicode 16 encodes 230 of the 256 patterns from U+1CD00 (BLOCK
/// OCTANT-…, in the order of their masks); the other 26 already had a
/// character, listed in [`OCTANT_ELSEWHERE`].
pub fn octant(mask: u8) -> char {
    match OCTANT_ELSEWHERE.binary_search_by_key(&mask, |&(m, _)| m) {
        Ok(i) => OCTANT_ELSEWHERE[i].1,
        Err(below) => char::from_u32(0x1CD00 + mask as u32 - below as u32).unwrap_or('?'),
    }
}

/// The octant patterns that are not in U+1CD00–U+1CDE5, with the character
/// that draws each, sorted by mask.
pub const OCTANT_ELSEWHERE: [(u8, char); 26] = [
    (0x00, ' '),
    (0x01, '\u{1CEA8}'), // LEFT HALF UPPER ONE QUARTER BLOCK
    (0x02, '\u{1CEAB}'), // RIGHT HALF UPPER ONE QUARTER BLOCK
    (0x03, '\u{1FB82}'), // UPPER ONE QUARTER BLOCK
    (0x05, '▘'),
    (0x0a, '▝'),
    (0x0f, '▀'),
    (0x14, '\u{1FBE6}'), // MIDDLE LEFT ONE QUARTER BLOCK
    (0x28, '\u{1FBE7}'), // MIDDLE RIGHT ONE QUARTER BLOCK
    (0x3f, '\u{1FB85}'), // UPPER THREE QUARTERS BLOCK
    (0x40, '\u{1CEA3}'), // LEFT HALF LOWER ONE QUARTER BLOCK
    (0x50, '▖'),
    (0x55, '▌'),
    (0x5a, '▞'),
    (0x5f, '▛'),
    (0x80, '\u{1CEA0}'), // RIGHT HALF LOWER ONE QUARTER BLOCK
    (0xa0, '▗'),
    (0xa5, '▚'),
    (0xaa, '▐'),
    (0xaf, '▜'),
    (0xc0, '▂'), // LOWER ONE QUARTER BLOCK
    (0xf0, '▄'),
    (0xf5, '▙'),
    (0xfa, '▟'),
    (0xfc, '▆'), // LOWER THREE QUARTERS BLOCK
    (0xff, '█'),
];

/// Braille, 2×4, one colour per cell. Sample bit `i` (as above) raises
/// braille dot `BRAILLE_DOT[i]`; the character is U+2800 plus the dots.
///
/// ```text
/// samples   dots (bit)
/// ┌─────┐   ┌─────┐
/// │ 0 1 │   │ 0 3 │
/// │ 2 3 │   │ 1 4 │
/// │ 4 5 │   │ 2 5 │
/// │ 6 7 │   │ 6 7 │
/// └─────┘   └─────┘
/// ```
pub const BRAILLE_DOT: [u8; 8] = [0, 3, 1, 4, 2, 5, 6, 7];

pub fn braille(mask: u8) -> char {
    let mut dots = 0u32;
    for (i, &d) in BRAILLE_DOT.iter().enumerate() {
        dots |= (((mask >> i) & 1) as u32) << d;
    }
    char::from_u32(0x2800 + dots).unwrap_or('?')
}

/// The ascii brightness ramp, darkest first.
pub const ASCII_RAMP: [char; 10] = [' ', '.', ':', '-', '=', '+', '*', '#', '%', '@'];
/// The shade ramp `block` uses without colour, darkest first.
pub const SHADE_RAMP: [char; 5] = [' ', '░', '▒', '▓', '█'];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sextants_are_the_unicode_order() {
        // U+1FB00 BLOCK SEXTANT-1, U+1FB01 SEXTANT-2, U+1FB02 SEXTANT-12,
        // U+1FB13 SEXTANT-35 (mask 0b10100 = 20), U+1FB14 SEXTANT-235 (22,
        // after the skipped left half 21), U+1FB3B SEXTANT-23456 (62).
        assert_eq!(sextant(0b1), '\u{1FB00}');
        assert_eq!(sextant(0b10), '\u{1FB01}');
        assert_eq!(sextant(0b11), '\u{1FB02}');
        assert_eq!(sextant(20), '\u{1FB13}');
        assert_eq!(sextant(22), '\u{1FB14}');
        assert_eq!(sextant(62), '\u{1FB3B}');
        let all: std::collections::HashSet<char> = (0..64).map(sextant).collect();
        assert_eq!(all.len(), 64);
    }

    #[test]
    fn octants_are_the_unicode_order() {
        // U+1CD00 BLOCK OCTANT-3 (mask 0b100), U+1CDE5 BLOCK OCTANT-2345678.
        assert_eq!(octant(0b100), '\u{1CD00}');
        assert_eq!(octant(0xfe), '\u{1CDE5}');
        // U+1CD01 BLOCK OCTANT-23 (0b110).
        assert_eq!(octant(0b110), '\u{1CD01}');
        let all: std::collections::HashSet<char> = (0..=255).map(octant).collect();
        assert_eq!(all.len(), 256);
        assert!(OCTANT_ELSEWHERE.windows(2).all(|w| w[0].0 < w[1].0));
    }

    #[test]
    fn quadrants_draw_their_mask() {
        assert_eq!(QUADRANT[0b0011], '▀');
        assert_eq!(QUADRANT[0b0101], '▌');
        assert_eq!(QUADRANT[0b1001], '▚');
        assert_eq!(QUADRANT[0b1110], '▟');
    }

    #[test]
    fn braille_dots() {
        assert_eq!(braille(0), '\u{2800}');
        assert_eq!(braille(0xff), '\u{28FF}');
        assert_eq!(braille(0b1), '⠁'); // dot 1, top-left
        assert_eq!(braille(0b10), '⠈'); // dot 4, top-right
        assert_eq!(braille(0b0100_0000), '⡀'); // dot 7, bottom-left
    }

    #[test]
    fn every_glyph_is_single_width() {
        use unicode_width::UnicodeWidthChar;
        let all = HALF
            .iter()
            .chain(&QUADRANT)
            .chain(&ASCII_RAMP)
            .chain(&SHADE_RAMP)
            .copied()
            .chain((0..64).map(sextant))
            .chain((0..=255).map(octant))
            .chain((0..=255).map(braille));
        for c in all {
            assert_eq!(c.width(), Some(1), "{c:?} U+{:04X}", c as u32);
        }
    }
}
