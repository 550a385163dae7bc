//! Cells as the terminal holds them: a frame's cells quantised for the
//! colour depth ([`TermCell`]) and packed into integers for
//! comparing and choosing ([`Packed`]), and the glyphs with a complement
//! (a cell may be sent the other way round when that is shorter).

use super::*;

/// The colours the terminal currently draws with (the tests' form of
/// [`Inks`]).
#[cfg(test)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Pen {
    /// The foreground.
    pub fg: Ink,
    /// The background.
    pub bg: Ink,
}

/// A cell as the terminal is told it: a character and two inks. A blank's
/// foreground is always [`Ink::Default`] (it shows nothing).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TermCell {
    /// The character.
    pub ch: char,
    /// Its foreground.
    pub fg: Ink,
    /// Its background.
    pub bg: Ink,
}

impl TermCell {
    /// A space in the default colours.
    pub const BLANK: TermCell = TermCell {
        ch: ' ',
        fg: Ink::Default,
        bg: Ink::Default,
    };

    /// How the frame's `cell`, at column `x` and row `y` of its frame (which
    /// anchor the dithering pattern), is told to a terminal whose colours
    /// `q` maps to: what every frame this encoder sends is made of, and
    /// what other back ends (the ratatui widget) take to show the same.
    ///
    /// Dithered, a cell is two square halves, top and bottom, each with its
    /// own place in the pattern (rows `2y` and `2y + 1` of the matrix): a
    /// cell of one colour whose halves get different entries is sent as `▀`
    /// with the top's entry over the bottom's, so that a 2×2-cell area
    /// shows eight entries of a colour's pattern, not four; a cell of two
    /// colours keeps its glyph, its foreground taking the top's place and
    /// its background the bottom's.
    ///
    /// This is for a cell of a frame of block elements; [`TermCell::at`]
    /// asks the frame.
    #[inline]
    pub fn of(cell: &Cell, q: &mut Quantizer, x: u16, y: u16) -> TermCell {
        TermCell::of_cell(cell, q, x, y, false)
    }

    /// [`TermCell::of`] for the cell of `frame` at column `x`, row `y`,
    /// which keeps the characters of a [`Frame::plain`] frame as they are
    /// (never splitting a cell in halves).
    #[inline]
    pub fn at(frame: &Frame, q: &mut Quantizer, x: u16, y: u16) -> TermCell {
        TermCell::of_cell(&frame.get(x, y), q, x, y, frame.plain())
    }

    /// [`TermCell::of`], splitting cells unless `plain`.
    #[inline]
    pub(super) fn of_cell(cell: &Cell, q: &mut Quantizer, x: u16, y: u16, plain: bool) -> TermCell {
        if q.dithers() {
            return TermCell::dithered(cell, q, x, y, plain);
        }
        TermCell {
            ch: cell.ch,
            fg: if cell.ch == ' ' {
                Ink::Default
            } else {
                q.ink_at(cell.fg, x, y)
            },
            bg: q.ink_at(cell.bg, x, y),
        }
    }

    /// [`TermCell::of`] where the quantizer dithers.
    #[inline(never)]
    pub(super) fn dithered(
        cell: &Cell,
        q: &mut Quantizer,
        x: u16,
        y: u16,
        plain: bool,
    ) -> TermCell {
        let top = y.wrapping_mul(2);
        let bottom = top.wrapping_add(1);
        let whole = match cell.ch {
            _ if plain => None,
            ' ' => cell.bg,
            '█' => cell.fg,
            _ => None,
        };
        if let Some(c) = whole {
            let (a, b) = (q.ink_at(Some(c), x, top), q.ink_at(Some(c), x, bottom));
            if a != b {
                return TermCell {
                    ch: '▀',
                    fg: a,
                    bg: b,
                };
            }
        }
        if cell.ch == ' ' {
            return TermCell {
                ch: ' ',
                fg: Ink::Default,
                bg: q.ink_at(cell.bg, x, bottom),
            };
        }
        // A colour alone in its cell (the other side is the terminal's
        // background) may be a thin edge: it is never shown black there.
        let (fg, bg) = match (cell.fg, cell.bg) {
            (Some(_), Some(_)) => (q.ink_at(cell.fg, x, top), q.ink_at(cell.bg, x, bottom)),
            _ => (
                q.ink_alone(cell.fg, x, top),
                q.ink_alone(cell.bg, x, bottom),
            ),
        };
        TermCell {
            ch: cell.ch,
            fg,
            bg,
        }
    }

    /// Whether the terminal shows the same picture for both cells, in
    /// either orientation.
    pub fn same_picture(&self, other: &TermCell) -> bool {
        Packed::of(*self).same_picture(&Packed::of(*other))
    }
}

/// A [`TermCell`] as the encoder keeps it: the character and each ink as
/// a word ([`pack_ink`]). The hundreds of thousands of unchanged cells of a
/// large frame are compared in three integer comparisons (an [`Ink`]'s
/// derived equality matches on its variant first), and the choices made for
/// a changed cell (which way round, which SGR) are integer tests too.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Packed {
    pub(super) ch: u32,
    pub(super) fg: u32,
    pub(super) bg: u32,
}

/// A pen (foreground and background) as the encoder keeps it, each ink packed by [`pack_ink`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct Inks {
    pub(super) fg: u32,
    pub(super) bg: u32,
}

impl Inks {
    #[cfg(test)]
    pub(super) fn of(pen: Pen) -> Inks {
        Inks {
            fg: pack_ink(pen.fg),
            bg: pack_ink(pen.bg),
        }
    }
}

/// The default ink, packed.
pub(super) const DEFAULT: u32 = 0;

/// An ink as a word: the variant in the top byte (0 the default, 1 a
/// palette index, 2 a 24-bit colour) and its value below.
#[inline(always)]
pub(super) fn pack_ink(ink: Ink) -> u32 {
    match ink {
        Ink::Default => DEFAULT,
        Ink::Indexed(i) => 1 << 24 | i as u32,
        Ink::Rgb(rgb) => pack_rgb(rgb),
    }
}

/// A 24-bit colour, packed.
#[inline(always)]
pub(super) fn pack_rgb(Rgb([r, g, b]): Rgb) -> u32 {
    2 << 24 | (r as u32) << 16 | (g as u32) << 8 | b as u32
}

/// The glyph `ch` as a `char` (a packed cell is only made from one).
#[inline(always)]
pub(super) fn glyph(ch: u32) -> char {
    char::from_u32(ch).unwrap_or(' ')
}

pub(super) const SPACE: u32 = ' ' as u32;
pub(super) const FULL_BLOCK: u32 = FULL as u32;
pub(super) const UPPER_HALF: u32 = '▀' as u32;
pub(super) const LOWER_HALF: u32 = '▄' as u32;

impl Packed {
    /// A space in the default colours.
    pub(super) const BLANK: Packed = Packed {
        ch: SPACE,
        fg: DEFAULT,
        bg: DEFAULT,
    };

    /// The frame's `cell` told to a 24-bit terminal: [`TermCell::of`] for
    /// [`ColorDepth::TrueColor`], packed straight from the colours' bytes.
    #[inline(always)]
    pub(super) fn truecolor(cell: &Cell) -> Packed {
        let ink = |c: Option<Rgb>| c.map_or(DEFAULT, pack_rgb);
        Packed {
            ch: cell.ch as u32,
            fg: if cell.ch == ' ' {
                DEFAULT
            } else {
                ink(cell.fg)
            },
            bg: ink(cell.bg),
        }
    }

    #[inline(always)]
    pub(super) fn of(t: TermCell) -> Packed {
        Packed {
            ch: t.ch as u32,
            fg: pack_ink(t.fg),
            bg: pack_ink(t.bg),
        }
    }

    /// The bytes of the glyph in UTF-8.
    #[inline(always)]
    pub(super) fn len(&self) -> usize {
        match self.ch {
            0..=0x7f => 1,
            0x80..=0x7ff => 2,
            0x800..=0xffff => 3,
            _ => 4,
        }
    }

    /// The pen this cell needs, given the current one: a blank keeps the
    /// current foreground, a full block the current background.
    #[inline(always)]
    pub(super) fn pen(&self, current: Inks) -> Inks {
        match self.ch {
            SPACE => Inks {
                fg: current.fg,
                bg: self.bg,
            },
            FULL_BLOCK => Inks {
                fg: self.fg,
                bg: current.bg,
            },
            _ => Inks {
                fg: self.fg,
                bg: self.bg,
            },
        }
    }

    /// Whether the cell can be written with `pen` as it is.
    #[inline(always)]
    pub(super) fn fits(&self, pen: Inks) -> bool {
        self.pen(pen) == pen
    }

    /// The cell with the colours a blank or a full block does not show set
    /// to the default, so that equal pictures compare equal.
    #[inline(always)]
    pub(super) fn normalized(self) -> Packed {
        match self.ch {
            SPACE => Packed {
                fg: DEFAULT,
                ..self
            },
            FULL_BLOCK => Packed {
                bg: DEFAULT,
                ..self
            },
            _ => self,
        }
    }

    /// The same picture drawn the other way round, when there is one: the
    /// complementary block element with foreground and background swapped
    /// (`▀` on blue in red is `▄` on red in blue; a blank in red is `█` in
    /// red). Neither colour may be the terminal's default, which is a
    /// different colour as a foreground than as a background; braille and
    /// the ramps have no complement.
    pub(super) fn flipped(&self) -> Option<Packed> {
        let shown_default = match self.ch {
            SPACE => self.bg == DEFAULT,
            FULL_BLOCK => self.fg == DEFAULT,
            _ => self.fg == DEFAULT || self.bg == DEFAULT,
        };
        if shown_default {
            return None;
        }
        // The half blocks, most of all, without the general look-up.
        let ch = match self.ch {
            UPPER_HALF => LOWER_HALF,
            LOWER_HALF => UPPER_HALF,
            ch => complement(glyph(ch))? as u32,
        };
        let (fg, bg) = match self.ch {
            SPACE => (self.bg, DEFAULT),
            FULL_BLOCK => (DEFAULT, self.fg),
            _ => (self.bg, self.fg),
        };
        Some(Packed { ch, fg, bg }.normalized())
    }

    /// Zero exactly when the cells are equal: their words' differences.
    #[inline(always)]
    pub(super) fn differs(&self, other: &Packed) -> u32 {
        (self.ch ^ other.ch) | (self.fg ^ other.fg) | (self.bg ^ other.bg)
    }

    /// Whether the terminal shows the same picture for both cells, in
    /// either orientation.
    #[inline(always)]
    pub(super) fn same_picture(&self, other: &Packed) -> bool {
        self == other || self.differs_only_in_form(other)
    }

    /// [`Packed::same_picture`] for cells that are not equal.
    #[inline(always)]
    pub(super) fn differs_only_in_form(&self, other: &Packed) -> bool {
        if self.ch == other.ch {
            // The same glyph, not equal: a different picture, but for the
            // colour a blank or a full block does not show.
            return match self.ch {
                SPACE => self.bg == other.bg,
                FULL_BLOCK => self.fg == other.fg,
                _ => false,
            };
        }
        self.flips_to(other)
    }

    /// Whether `other` is this cell drawn the other way round.
    #[inline(never)]
    pub(super) fn flips_to(&self, other: &Packed) -> bool {
        self.flipped() == Some(other.normalized())
    }

    /// The form of this cell (itself or [`Packed::flipped`]) that costs the
    /// fewest bytes written `count` times from `pen`: the SGR and the
    /// characters (a space is one byte, a block element three).
    /// `count` is asked for only when the choice is open.
    #[inline]
    pub(super) fn cheapest_from(&self, pen: Inks, count: impl FnOnce() -> usize) -> Packed {
        // A cell that fits is cheapest, unless it is a full block whose
        // blank (a third of its bytes) would pay for an SGR over a run.
        if self.fits(pen) && self.ch != FULL_BLOCK {
            return *self;
        }
        // The block elements but the full one (half blocks, quadrants) pair
        // with a complement of their own length and the colours swapped:
        // when neither form keeps a colour of the pen, the cell stays as it
        // is (below), known before the complement is looked up.
        let keeps_either =
            self.fg == pen.fg || self.bg == pen.bg || self.bg == pen.fg || self.fg == pen.bg;
        if (0x2580..=0x259f).contains(&self.ch) && self.ch != FULL_BLOCK && !keeps_either {
            return *self;
        }
        let Some(f) = self.flipped() else {
            return *self;
        };
        if f.len() == self.len() {
            // Two glyphs of two colours (a blank and a full block differ in
            // length).
            return self.cheaper_of_two_colours(f, pen);
        }
        // Glyphs of different lengths: the copies count.
        let count = count();
        let cost = |c: &Packed| sgr_cost(pen, c.pen(pen)) + count * c.len();
        if cost(&f) < cost(self) { f } else { *self }
    }

    /// [`Packed::cheapest_from`] for a glyph of two colours whose flip `f`
    /// is another: both are the same length, so only the SGR counts, and
    /// each form sets whichever of its two colours the pen lacks. A form
    /// that keeps more of the pen's colours costs fewer bytes (one colour
    /// written costs at least 5 bytes, two at least 8, and a colour's
    /// parameters differ in length between the planes by at most one);
    /// when each keeps one, the lengths of the one colour each sets decide.
    /// On a tie, or when neither keeps a colour, the cell stays as it is.
    #[inline(always)]
    pub(super) fn cheaper_of_two_colours(&self, f: Packed, pen: Inks) -> Packed {
        let kept = |c: &Packed| (c.fg == pen.fg) as u8 + (c.bg == pen.bg) as u8;
        match (kept(self), kept(&f)) {
            (a, b) if a != b => {
                if b > a {
                    f
                } else {
                    *self
                }
            }
            (1, 1) => {
                // The one colour each form writes, in its plane.
                let set = |c: &Packed| {
                    if c.fg != pen.fg {
                        ink_cost(30, c.fg)
                    } else {
                        ink_cost(40, c.bg)
                    }
                };
                if set(&f) < set(self) { f } else { *self }
            }
            // Both set both colours: the same bytes, but for a bright
            // palette colour's one digit more as a background; the cell
            // stays as it is without counting.
            _ => *self,
        }
    }

    /// The form of this cell that can be written with `pen` as it is, if
    /// either can.
    pub(super) fn fitting(&self, pen: Inks) -> Option<Packed> {
        if self.fits(pen) {
            return Some(*self);
        }
        self.flipped().filter(|f| f.fits(pen))
    }
}

/// The full block, which shows only its foreground.
pub(super) const FULL: char = '█';

/// The block element that draws the samples `ch` leaves out, for the glyphs
/// of the two-colour modes (half, quadrant, sextant, octant; the space and
/// `█` are each other's); `None` for any other character.
pub fn complement(ch: char) -> Option<char> {
    use crate::blit::glyphs::{OCTANT_ELSEWHERE, octant, sextant};
    Some(match ch {
        ' ' => FULL,
        FULL => ' ',
        // Half blocks and quadrants, the most common, without a search.
        '▀' => '▄',
        '▄' => '▀',
        '▌' => '▐',
        '▐' => '▌',
        '▖' => '▜',
        '▜' => '▖',
        '▗' => '▛',
        '▛' => '▗',
        '▘' => '▟',
        '▟' => '▘',
        '▝' => '▙',
        '▙' => '▝',
        '▚' => '▞',
        '▞' => '▚',
        '\u{1FB00}'..='\u{1FB3B}' => {
            // The sextants skip the masks of the left and right halves.
            let mut mask = ch as u32 - 0x1FB00 + 1;
            mask += (mask >= 0x15) as u32;
            mask += (mask >= 0x2a) as u32;
            sextant(!(mask as u8) & 0x3f)
        }
        '\u{1CD00}'..='\u{1CDE5}' => {
            // The octants skip the masks drawn by older characters.
            let mut mask = ch as u32 - 0x1CD00;
            for &(m, _) in &OCTANT_ELSEWHERE {
                mask += (m as u32 <= mask) as u32;
            }
            octant(!(mask as u8))
        }
        _ => OCTANT_ELSEWHERE
            .iter()
            .find(|&&(_, c)| c == ch)
            .map(|&(m, _)| octant(!m))?,
    })
}
