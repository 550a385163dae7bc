//! Stage 7: the encoder, from a [`Frame`] to the bytes a terminal reads, for
//! any `io::Write`.
//!
//! Colours are first mapped to what the terminal is told ([`Ink`]: 24-bit,
//! a palette index, or its default) by a [`Quantizer`] for the colour
//! depth. The encoder then keeps track of the terminal's state, its pen
//! (current foreground and background) and its cursor, and writes the fewest
//! bytes it can:
//!
//! * **SGR only where a colour changes**, foreground and background in one
//!   sequence, and `CSI m` (3 bytes) to go back to the defaults. A blank cell
//!   shows only its background and `█` only its foreground, so the other
//!   plane never forces an SGR.
//! * **Cells drawn the way round that keeps the pen**: a block element of
//!   the two-colour modes shows the same picture as its complement with the
//!   colours swapped (`▀` red on blue is `▄` blue on red; a blank in red is
//!   `█` in red), so each changed cell is written in whichever form costs
//!   fewer bytes from the current pen, counted over the run of copies of it
//!   that follow. The choice is greedy, cell by cell: it never looks further
//!   ahead. On the turning square this alone took half mode's later frames
//!   from 1,328 bytes to 966 and octant's from 2,089 to 1,478. Neither colour
//!   may be the terminal's default, which differs as a foreground and as a
//!   background; braille and the ramps have no complement. Frames are
//!   compared by picture, so a cell the blitter turned round is no change.
//! * **The cheapest cursor move**: of CUP, CHA, CUF, CUB, CUD, CUU, VPA, CR
//!   and CR LF (and their combinations), the shortest that reaches the next
//!   cell to write; nothing at all when it is the adjacent one. A short gap
//!   of unchanged cells that need no SGR is rewritten instead when that is
//!   shorter than any move.
//! * **Only what changed** ([`Encoder`]): the frame the terminal shows is
//!   kept, and a new frame sends only the cells that differ. A frame from
//!   the renderer knows a rectangle outside which every cell is the same
//!   (the cells that show no drawn sample); where that cell is a blank in
//!   the default colours, only the cells of that rectangle and of the last
//!   frame's are compared: a model in a corner of a large terminal costs
//!   its own cells. The encoder
//!   keeps cells packed, a word for the glyph and one for each ink, so
//!   that finding the changes in a large frame is integer comparisons,
//!   eight cells at a time where all eight are equal; the choices for a
//!   changed cell (which way round, which SGR, how many copies follow)
//!   are integer tests on the same words. Nothing is allocated per frame
//!   once the buffers have grown. The first frame, a
//!   resize, a change of colour depth, or [`Encoder::invalidate`] give a
//!   full redraw: the screen is cleared and the frame's non-blank cells
//!   written.
//! * **REP** (`CSI n b`, repeat the last character) for runs of identical
//!   cells, off by default ([`Rep`]): not every terminal has it.
//! * Every frame is bracketed in synchronized output (DEC mode 2026), so a
//!   terminal that supports it shows it at once, and ends with the
//!   attributes reset. A frame with nothing to change writes nothing.
//!
//! Bytes are gathered in a buffer kept between frames and written with one
//! `write_all`.
//!
//! [`write_lines`] prints a frame as lines of text instead, for
//! `rastty render`: each row ends with an attribute reset (so no colour
//! bleeds into the rest of the line or the shell prompt) and a newline. With
//! [`ColorDepth::None`] it writes the frame's plain text and no escape
//! sequence at all.

use std::io::{self, Write};

use crate::color::{ColorDepth, Dither, Ink, Metric, Palette, Quantizer, Rgb};
use crate::frame::{Cell, Frame};
use crate::transform::Rect;

/// Synchronized output: begin and end.
pub const SYNC_BEGIN: &[u8] = b"\x1b[?2026h";
/// Synchronized output: end.
pub const SYNC_END: &[u8] = b"\x1b[?2026l";

/// The colours the terminal currently draws with.
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
    fn of_cell(cell: &Cell, q: &mut Quantizer, x: u16, y: u16, plain: bool) -> TermCell {
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
    fn dithered(cell: &Cell, q: &mut Quantizer, x: u16, y: u16, plain: bool) -> TermCell {
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
struct Packed {
    ch: u32,
    fg: u32,
    bg: u32,
}

/// A [`Pen`] as the encoder keeps it, each ink packed by [`pack_ink`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Inks {
    fg: u32,
    bg: u32,
}

impl Inks {
    #[cfg(test)]
    fn of(pen: Pen) -> Inks {
        Inks {
            fg: pack_ink(pen.fg),
            bg: pack_ink(pen.bg),
        }
    }
}

/// The default ink, packed.
const DEFAULT: u32 = 0;

/// An ink as a word: the variant in the top byte (0 the default, 1 a
/// palette index, 2 a 24-bit colour) and its value below.
#[inline(always)]
fn pack_ink(ink: Ink) -> u32 {
    match ink {
        Ink::Default => DEFAULT,
        Ink::Indexed(i) => 1 << 24 | i as u32,
        Ink::Rgb(rgb) => pack_rgb(rgb),
    }
}

/// A 24-bit colour, packed.
#[inline(always)]
fn pack_rgb(Rgb([r, g, b]): Rgb) -> u32 {
    2 << 24 | (r as u32) << 16 | (g as u32) << 8 | b as u32
}

/// The glyph `ch` as a `char` (a packed cell is only made from one).
#[inline(always)]
fn glyph(ch: u32) -> char {
    char::from_u32(ch).unwrap_or(' ')
}

const SPACE: u32 = ' ' as u32;
const FULL_BLOCK: u32 = FULL as u32;
const UPPER_HALF: u32 = '▀' as u32;
const LOWER_HALF: u32 = '▄' as u32;

impl Packed {
    /// A space in the default colours.
    const BLANK: Packed = Packed {
        ch: SPACE,
        fg: DEFAULT,
        bg: DEFAULT,
    };

    /// The frame's `cell` told to a 24-bit terminal: [`TermCell::of`] for
    /// [`ColorDepth::TrueColor`], packed straight from the colours' bytes.
    #[inline(always)]
    fn truecolor(cell: &Cell) -> Packed {
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
    fn of(t: TermCell) -> Packed {
        Packed {
            ch: t.ch as u32,
            fg: pack_ink(t.fg),
            bg: pack_ink(t.bg),
        }
    }

    /// The bytes of the glyph in UTF-8.
    #[inline(always)]
    fn len(&self) -> usize {
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
    fn pen(&self, current: Inks) -> Inks {
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
    fn fits(&self, pen: Inks) -> bool {
        self.pen(pen) == pen
    }

    /// The cell with the colours a blank or a full block does not show set
    /// to the default, so that equal pictures compare equal.
    #[inline(always)]
    fn normalized(self) -> Packed {
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
    fn flipped(&self) -> Option<Packed> {
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
    fn differs(&self, other: &Packed) -> u32 {
        (self.ch ^ other.ch) | (self.fg ^ other.fg) | (self.bg ^ other.bg)
    }

    /// Whether the terminal shows the same picture for both cells, in
    /// either orientation.
    #[inline(always)]
    fn same_picture(&self, other: &Packed) -> bool {
        self == other || self.differs_only_in_form(other)
    }

    /// [`Packed::same_picture`] for cells that are not equal.
    #[inline(always)]
    fn differs_only_in_form(&self, other: &Packed) -> bool {
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
    fn flips_to(&self, other: &Packed) -> bool {
        self.flipped() == Some(other.normalized())
    }

    /// The form of this cell (itself or [`Packed::flipped`]) that costs the
    /// fewest bytes written `count` times from `pen`: the SGR and the
    /// characters (a space is one byte, a block element three).
    /// `count` is asked for only when the choice is open.
    fn cheapest_from(&self, pen: Inks, count: impl FnOnce() -> usize) -> Packed {
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
    fn cheaper_of_two_colours(&self, f: Packed, pen: Inks) -> Packed {
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
    fn fitting(&self, pen: Inks) -> Option<Packed> {
        if self.fits(pen) {
            return Some(*self);
        }
        self.flipped().filter(|f| f.fits(pen))
    }
}

/// The full block, which shows only its foreground.
const FULL: char = '█';

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

/// Whether runs of identical cells may be sent with REP (`CSI n b`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Rep {
    #[default]
    /// Every cell written out (the default).
    Off,
    /// Runs sent with REP where that is shorter.
    On,
}

crate::choice::choice!(Rep {
    Off => "off": "Every cell written out (the default)",
    On => "on": "Runs sent with REP where that is shorter",
});

/// Appends the decimal digits of `n`.
fn push_num(buf: &mut Vec<u8>, n: u32) {
    let mut digits = [0u8; 10];
    let mut i = digits.len();
    let mut n = n;
    loop {
        i -= 1;
        digits[i] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    buf.extend_from_slice(&digits[i..]);
}

fn digits(n: u32) -> usize {
    match n {
        0..=9 => 1,
        10..=99 => 2,
        100..=999 => 3,
        1000..=9999 => 4,
        _ => 5 + digits(n / 100_000),
    }
}

/// The decimal digits of every byte value followed by `;`, and how many
/// bytes that is: a colour channel is written by copying four bytes and
/// advancing by the count, not by dividing.
static BYTE_DIGITS: [([u8; 4], u8); 256] = {
    let mut t = [([0u8; 4], 0u8); 256];
    let mut n = 0;
    while n < 256 {
        let (h, te, o) = ((n / 100) as u8, (n / 10 % 10) as u8, (n % 10) as u8);
        t[n] = match n {
            0..=9 => ([b'0' + o, b';', 0, 0], 2),
            10..=99 => ([b'0' + te, b'0' + o, b';', 0], 3),
            _ => ([b'0' + h, b'0' + te, b'0' + o, b';'], 4),
        };
        n += 1;
    }
    t
};

/// What one run of cells appends, an SGR and its first glyph, assembled
/// on the stack (the longest, two 24-bit colours and a four-byte glyph, is
/// 40 bytes) and appended to the buffer in one copy of constant length.
struct SgrBytes {
    bytes: [u8; 48],
    len: usize,
}

impl SgrBytes {
    /// Nothing yet.
    #[inline(always)]
    fn new() -> SgrBytes {
        SgrBytes {
            bytes: [0; 48],
            len: 0,
        }
    }

    /// Appends a byte's digits and a `;`.
    #[inline(always)]
    fn byte(&mut self, v: u8) {
        let (d, n) = BYTE_DIGITS[v as usize];
        self.bytes[self.len..self.len + 4].copy_from_slice(&d);
        self.len += n as usize;
    }

    /// Appends a constant prefix.
    #[inline(always)]
    fn put(&mut self, s: &[u8; 5]) {
        self.bytes[self.len..self.len + 5].copy_from_slice(s);
        self.len += 5;
    }

    /// Appends the SGR parameters of one plane and a `;`: `fg` for the
    /// foreground (30–39, 90–97), else the background (40–49, 100–107).
    /// `ink` is packed ([`pack_ink`]).
    #[inline(always)]
    fn ink(&mut self, fg: bool, ink: u32) {
        let base = if fg { 30 } else { 40 };
        let [_, r, g, b] = ink.to_be_bytes();
        match ink >> 24 {
            0 => self.byte(base + 9),
            1 => match b {
                0..=7 => self.byte(base + b),
                8..=15 => self.byte(base + 60 + (b - 8)),
                _ => {
                    self.put(if fg { b"38;5;" } else { b"48;5;" });
                    self.byte(b);
                }
            },
            _ => {
                self.put(if fg { b"38;2;" } else { b"48;2;" });
                self.byte(r);
                self.byte(g);
                self.byte(b);
            }
        }
    }

    /// Appends the shortest SGR taking the terminal from `from` to `to`;
    /// nothing when they are equal.
    #[inline(always)]
    fn inks(&mut self, from: Inks, to: Inks) {
        if from == to {
            return;
        }
        if to == Inks::default() {
            // `CSI m` resets both planes in three bytes.
            self.bytes[self.len..self.len + 3].copy_from_slice(b"\x1b[m");
            self.len += 3;
            return;
        }
        self.bytes[self.len..self.len + 2].copy_from_slice(b"\x1b[");
        self.len += 2;
        if from.fg != to.fg {
            self.ink(true, to.fg);
        }
        if from.bg != to.bg {
            self.ink(false, to.bg);
        }
        // Each plane ended with `;`: the last becomes the final `m`.
        self.bytes[self.len - 1] = b'm';
    }

    /// Appends a packed cell's glyph in UTF-8.
    #[inline(always)]
    fn glyph(&mut self, ch: u32) {
        self.len += glyph(ch)
            .encode_utf8(&mut self.bytes[self.len..self.len + 4])
            .len();
    }

    /// Appends what was assembled to `buf`.
    #[inline(always)]
    fn append_to(&self, buf: &mut Vec<u8>) {
        // A copy of constant length (stores, not a call to `memcpy`), cut
        // back.
        let end = buf.len() + self.len;
        buf.extend_from_slice(&self.bytes);
        buf.truncate(end);
    }
}

/// The length of [`SgrBytes::ink`]'s parameters for a packed ink, without
/// the `;`.
#[inline(always)]
fn ink_cost(base: u32, ink: u32) -> usize {
    let [_, r, g, b] = ink.to_be_bytes();
    let d = |v: u8| BYTE_DIGITS[v as usize].1 as usize;
    match ink >> 24 {
        0 => 2,
        1 => match b {
            0..=7 => 2,
            8..=15 => digits(base + 60),
            _ => 4 + d(b),
        },
        _ => 4 + d(r) + d(g) + d(b),
    }
}

/// The length of what [`push_sgr`] appends.
#[inline(always)]
fn sgr_cost(from: Inks, to: Inks) -> usize {
    if from == to {
        return 0;
    }
    if to == Inks::default() {
        return 3;
    }
    match (from.fg != to.fg, from.bg != to.bg) {
        (true, true) => 4 + ink_cost(30, to.fg) + ink_cost(40, to.bg),
        (true, false) => 3 + ink_cost(30, to.fg),
        _ => 3 + ink_cost(40, to.bg),
    }
}

/// Appends the shortest SGR taking the terminal from `from` to `to`;
/// nothing when they are equal: the unpacked twin the packed pens' path
/// is tested against.
#[cfg(test)]
fn push_sgr(buf: &mut Vec<u8>, from: Pen, to: Pen) {
    push_inks(buf, Inks::of(from), Inks::of(to));
}

/// [`push_sgr`] for packed pens.
#[inline(always)]
fn push_inks(buf: &mut Vec<u8>, from: Inks, to: Inks) {
    let mut sgr = SgrBytes::new();
    sgr.inks(from, to);
    sgr.append_to(buf);
}

/// Appends a character as UTF-8.
#[inline]
pub fn push_char(buf: &mut Vec<u8>, ch: char) {
    let mut utf8 = [0; 4];
    let n = ch.encode_utf8(&mut utf8).len();
    // Slices of a constant length: stores, not a call to `memcpy`.
    match n {
        1 => buf.push(utf8[0]),
        2 => buf.extend_from_slice(&[utf8[0], utf8[1]]),
        3 => buf.extend_from_slice(&[utf8[0], utf8[1], utf8[2]]),
        _ => buf.extend_from_slice(&utf8),
    }
}

/// Maps a frame's cells to terminal cells for one depth, into `out`.
fn quantize(frame: &Frame, q: &mut Quantizer, out: &mut Vec<Packed>) {
    let all = Rect::all(frame.cols() as u32, frame.rows() as u32);
    quantize_in(frame, q, out, all);
}

/// [`quantize`] of the cells of `region` only (`out` holds every cell).
fn quantize_in(frame: &Frame, q: &mut Quantizer, out: &mut Vec<Packed>, region: Rect) {
    out.resize(frame.cells().len(), Packed::BLANK);
    let cols = frame.cols() as usize;
    let truecolor = q.depth() == ColorDepth::TrueColor;
    for y in region.y0..region.y1 {
        let span = region.columns(y);
        let row = y as usize * cols;
        let (cells, out) = (
            &frame.cells()[row..][span.clone()],
            &mut out[row..][span.clone()],
        );
        if truecolor {
            // No palette, no dithering: where a cell is does not matter.
            for (o, c) in out.iter_mut().zip(cells) {
                *o = Packed::truecolor(c);
            }
            continue;
        }
        let plain = frame.plain();
        for ((o, c), x) in out.iter_mut().zip(cells).zip(span) {
            *o = Packed::of(TermCell::of_cell(c, q, x as u16, y as u16, plain));
        }
    }
}

/// Appends `cell` written `count` times (at least once) from pen `pen`,
/// with the SGR it needs (when `color`) and, when allowed and shorter, REP
/// for the repeats. Returns the pen afterwards.
#[inline(always)]
fn push_run(
    buf: &mut Vec<u8>,
    pen: Inks,
    cell: &Packed,
    count: usize,
    rep: Rep,
    color: bool,
) -> Inks {
    let mut sgr = SgrBytes::new();
    let pen = if color {
        let want = cell.pen(pen);
        sgr.inks(pen, want);
        want
    } else {
        pen
    };
    sgr.glyph(cell.ch);
    sgr.append_to(buf);
    let ch = glyph(cell.ch);
    let repeats = count.saturating_sub(1);
    if repeats > 0 && rep == Rep::On && csi_cost(repeats as u32) < repeats * cell.len() {
        push_csi(buf, repeats as u32, b'b');
    } else {
        (0..repeats).for_each(|_| push_char(buf, ch));
    }
    pen
}

/// Writes `frame` as lines of text (see the module doc). `buf` is scratch
/// space, cleared first and kept for the next call.
pub fn write_lines(
    frame: &Frame,
    palette: impl Into<Palette>,
    rep: Rep,
    buf: &mut Vec<u8>,
    out: &mut impl Write,
) -> io::Result<()> {
    let palette = palette.into();
    let depth = palette.depth;
    let mut q = Quantizer::of(palette);
    let mut cells = Vec::with_capacity(frame.cells().len());
    quantize(frame, &mut q, &mut cells);
    buf.clear();
    push_lines(&cells, frame.cols(), frame.rows(), depth, rep, buf);
    out.write_all(buf)?;
    out.flush()
}

/// Appends `cells` (`cols × rows`) as lines of text.
fn push_lines(
    cells: &[Packed],
    cols: u16,
    rows: u16,
    depth: ColorDepth,
    rep: Rep,
    buf: &mut Vec<u8>,
) {
    // Plain text means no escape sequence at all, REP included.
    let rep = if depth.has_color() { rep } else { Rep::Off };
    for row in cells.chunks(cols.max(1) as usize).take(rows as usize) {
        let mut pen = Inks::default();
        let mut rest = row;
        while let Some(cell) = rest.first() {
            let run = rest.iter().take_while(|c| *c == cell).count();
            pen = push_run(buf, pen, cell, run, rep, depth.has_color());
            rest = &rest[run..];
        }
        push_inks(buf, pen, Inks::default());
        buf.push(b'\n');
    }
}

/// Where the cursor is: a cell, or just past the last column of a row (the
/// "pending wrap" state, where only absolute horizontal moves are safe).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Cursor {
    row: u16,
    col: u16,
}

/// The vertical part of a cursor move.
#[derive(Clone, Copy, Debug)]
enum Vertical {
    Stay,
    /// `\r\n` repeated: down `n` rows to column 0.
    CrLf(u16),
    /// CUD or CUU by `n` rows (column kept).
    Relative(i32),
    /// VPA to the row (column kept).
    Absolute(u16),
}

/// The horizontal part of a cursor move.
#[derive(Clone, Copy, Debug)]
enum Horizontal {
    Stay,
    Cr,
    /// CUF or CUB.
    Relative(i32),
    /// CHA.
    Absolute(u16),
}

/// The length of `CSI n X`, where n = 1 is left out.
fn csi_cost(n: u32) -> usize {
    3 + if n == 1 { 0 } else { digits(n) }
}

fn horizontal(from: Option<u16>, to: u16, cols: u16) -> (usize, Horizontal) {
    let mut best = (csi_cost(to as u32 + 1), Horizontal::Absolute(to));
    if to == 0 {
        best = (1, Horizontal::Cr);
    }
    if let Some(c) = from.filter(|&c| c < cols) {
        if c == to {
            return (0, Horizontal::Stay);
        }
        let d = to as i32 - c as i32;
        let cost = csi_cost(d.unsigned_abs());
        if cost < best.0 {
            best = (cost, Horizontal::Relative(d));
        }
    }
    best
}

/// The cheapest way from `from` (unknown: `None`) to `to`, and its length;
/// `None` as the plan means CUP.
fn plan_move(
    from: Option<Cursor>,
    to: Cursor,
    cols: u16,
) -> (usize, Option<(Vertical, Horizontal)>) {
    if from == Some(to) {
        // The next cell written is the one the cursor is on: most often.
        return (0, Some((Vertical::Stay, Horizontal::Stay)));
    }
    // CUP: `CSI row ; col H`, with `; 1` and a lone `1` left out.
    let cup = 3 + match (to.row, to.col) {
        (0, 0) => 0,
        (r, 0) => digits(r as u32 + 1),
        (r, c) => digits(r as u32 + 1) + 1 + digits(c as u32 + 1),
    };
    let Some(from) = from else {
        return (cup, None);
    };
    let mut best = (cup, None);
    let mut consider = |v: Vertical, v_cost: usize, col_after: Option<u16>| {
        let (h_cost, h) = horizontal(col_after, to.col, cols);
        if v_cost + h_cost < best.0 {
            best = (v_cost + h_cost, Some((v, h)));
        }
    };
    let dr = to.row as i32 - from.row as i32;
    if dr == 0 {
        consider(Vertical::Stay, 0, Some(from.col));
    } else {
        if dr > 0 && dr <= 4 {
            consider(Vertical::CrLf(dr as u16), 2 * dr as usize, Some(0));
        }
        // From the pending-wrap position only absolute columns are safe.
        let col = Some(from.col).filter(|&c| c < cols);
        consider(Vertical::Relative(dr), csi_cost(dr.unsigned_abs()), col);
        consider(Vertical::Absolute(to.row), csi_cost(to.row as u32 + 1), col);
    }
    best
}

fn push_csi(buf: &mut Vec<u8>, n: u32, end: u8) {
    buf.extend_from_slice(b"\x1b[");
    if n != 1 {
        push_num(buf, n);
    }
    buf.push(end);
}

fn push_move(buf: &mut Vec<u8>, plan: Option<(Vertical, Horizontal)>, to: Cursor) {
    let Some((v, h)) = plan else {
        buf.extend_from_slice(b"\x1b[");
        if to.row > 0 || to.col > 0 {
            push_num(buf, to.row as u32 + 1);
        }
        if to.col > 0 {
            buf.push(b';');
            push_num(buf, to.col as u32 + 1);
        }
        buf.push(b'H');
        return;
    };
    match v {
        Vertical::Stay => {}
        Vertical::CrLf(n) => (0..n).for_each(|_| buf.extend_from_slice(b"\r\n")),
        Vertical::Relative(d) => push_csi(buf, d.unsigned_abs(), if d > 0 { b'B' } else { b'A' }),
        Vertical::Absolute(r) => push_csi(buf, r as u32 + 1, b'd'),
    }
    match h {
        Horizontal::Stay => {}
        Horizontal::Cr => buf.push(b'\r'),
        Horizontal::Relative(d) => push_csi(buf, d.unsigned_abs(), if d > 0 { b'C' } else { b'D' }),
        Horizontal::Absolute(c) => push_csi(buf, c as u32 + 1, b'G'),
    }
}

/// Takes the cursor from `from` to `to`, cell `i` of `next`, in the fewest
/// bytes: the cheapest move, or, on the same row, the unchanged cells in
/// between written again where that is shorter (they must fit the pen as
/// they are or turned round). `next` holds the cells of its row from
/// index `lo` on; those before are blanks in the default colours.
#[inline(never)]
fn move_to(
    buf: &mut Vec<u8>,
    (next, lo, i): (&[Packed], usize, usize),
    cols: u16,
    from: Option<Cursor>,
    to: Cursor,
    pen: Inks,
) {
    let (move_cost, plan) = plan_move(from, to, cols);
    let cell = |k: usize| if k >= lo { next[k] } else { Packed::BLANK };
    let gap = match from {
        Some(c) if c.row == to.row && c.col < to.col && move_cost > 0 => {
            // Each cell is at least a byte.
            let gap = (to.col - c.col) as usize;
            let cells = i - gap.min(move_cost)..i;
            let cost: usize = cells.clone().map(|k| cell(k).len()).sum();
            (gap < move_cost
                && cost < move_cost
                && cells.clone().all(|k| cell(k).fitting(pen).is_some()))
            .then_some(cells)
        }
        _ => None,
    };
    match gap {
        Some(cells) => cells
            .filter_map(|k| cell(k).fitting(pen))
            .for_each(|c| push_char(buf, glyph(c.ch))),
        None => push_move(buf, plan, to),
    }
}

/// Lists in `changes` the indices of the cells of `region` (of a frame
/// `cols` wide) unequal between `next` and `shown`, in order, and returns
/// how many. Eight equal cells, most of a large frame, cost one test; in a
/// chunk with a difference, each cell costs a few word comparisons and no
/// branch: every index is written, and the count advanced only past those
/// that differ.
fn unequal_cells(
    shown: &[Packed],
    next: &[Packed],
    changes: &mut Vec<u32>,
    cols: usize,
    region: Rect,
) -> usize {
    let n = shown.len().min(next.len());
    if changes.len() < n {
        changes.resize(n, 0);
    }
    let slots = &mut changes[..n];
    let mut len = 0;
    for y in region.y0..region.y1 {
        let span = region.columns(y);
        let row = y as usize * cols + span.start;
        let (shown, next) = (&shown[row..][..span.len()], &next[row..][..span.len()]);
        // Eight cells at a time: where all are equal, one test; otherwise
        // each is listed if it differs.
        for (k, (a, b)) in shown.chunks(8).zip(next.chunks(8)).enumerate() {
            if a.len() == 8 && a.iter().zip(b).fold(0, |d, (p, q)| d | p.differs(q)) == 0 {
                continue;
            }
            for (j, (p, q)) in a.iter().zip(b).enumerate() {
                slots[len] = (row + k * 8 + j) as u32;
                len += (p.differs(q) != 0) as usize;
            }
        }
    }
    len
}

/// [`quantize_in`] and [`unequal_cells`] in one pass for 24-bit colour,
/// where a cell packs straight from its bytes (no palette, no dithering):
/// each cell is compared with `shown`'s while it is in registers.
fn quantize_truecolor(
    frame: &Frame,
    shown: &[Packed],
    next: &mut Vec<Packed>,
    changes: &mut Vec<u32>,
    region: Rect,
) -> usize {
    let cells = frame.cells();
    let n = cells.len().min(shown.len());
    next.resize(cells.len(), Packed::BLANK);
    if changes.len() < n {
        changes.resize(n, 0);
    }
    let slots = &mut changes[..n];
    let cols = frame.cols() as usize;
    let mut len = 0;
    for y in region.y0..region.y1 {
        let span = region.columns(y);
        let row = y as usize * cols + span.start;
        let m = span.len();
        let (cells, shown, next) = (
            &cells[row..][..m],
            &shown[row..][..m],
            &mut next[row..][..m],
        );
        for (i, ((out, c), s)) in next.iter_mut().zip(cells).zip(shown).enumerate() {
            let p = Packed::truecolor(c);
            *out = p;
            slots[len] = (row + i) as u32;
            len += (p.differs(s) != 0) as usize;
        }
    }
    len
}

/// Keeps, of the cells `candidates` lists, those whose picture differs
/// between `shown` and `next` (the same picture drawn the other way round
/// is no change), in order.
fn changed_cells<'a>(shown: &[Packed], next: &[Packed], candidates: &'a mut [u32]) -> &'a [u32] {
    let mut kept = 0;
    for k in 0..candidates.len() {
        let i = candidates[k] as usize;
        candidates[kept] = i as u32;
        kept += !shown[i].differs_only_in_form(&next[i]) as usize;
    }
    &candidates[..kept]
}

/// Sends frames to a terminal, each as the difference from the last.
///
/// ```
/// use rastty::{ColorDepth, Encoder, Frame, RenderOptions, Renderer, Rgb, Scene};
/// use rastty::glam::Vec3;
///
/// let scene = Scene::of_mesh(rastty::scene::Shape::Cube.mesh(Rgb::WHITE));
/// let (mut renderer, mut frame) = (Renderer::new(), Frame::default());
/// let mut encoder = Encoder::new(ColorDepth::TrueColor);
/// let mut sent = Vec::new();
/// for yaw in [0.0, 2.0] {
///     let opts = RenderOptions { turn: Vec3::new(0.0, yaw, 0.0), ..Default::default() };
///     renderer.render_into(&scene, &opts, &mut frame);
///     sent.push(encoder.encode(&frame, &mut Vec::new()).unwrap());
/// }
/// // The first frame is drawn in full, the second only where it changed.
/// assert!(sent[1] < sent[0] / 2, "{sent:?}");
/// // Nothing changed: nothing is sent.
/// assert_eq!(encoder.encode(&frame, &mut Vec::new()).unwrap(), 0);
/// ```
#[derive(Debug)]
pub struct Encoder {
    quantizer: Quantizer,
    /// The dithering asked for (`auto` resolves per depth).
    dither: Dither,
    rep: Rep,
    cols: u16,
    rows: u16,
    /// What the terminal shows, when `synced`.
    shown: Vec<Packed>,
    /// Every cell of `shown` outside it is a blank in the default colours.
    shown_drawn: Rect,
    /// The frame being sent, in the cells compared with `shown`.
    next: Vec<Packed>,
    /// The indices of the cells that changed, in order (scratch space).
    changes: Vec<u32>,
    synced: bool,
    buf: Vec<u8>,
    /// Bracket frames in synchronized output.
    sync: bool,
    /// Every frame in full as plain lines (a terminal that cannot move its
    /// cursor), rather than as the difference from the last.
    lines: bool,
}

impl Encoder {
    /// An encoder for `depth`, with synchronized output and the default palette
    /// matching; the first frame is drawn in full.
    pub fn new(depth: ColorDepth) -> Encoder {
        Encoder {
            quantizer: Quantizer::of(depth.into()),
            dither: Dither::Auto,
            rep: Rep::Off,
            cols: 0,
            rows: 0,
            shown: Vec::new(),
            shown_drawn: Rect::EMPTY,
            next: Vec::new(),
            changes: Vec::new(),
            synced: false,
            buf: Vec::new(),
            sync: true,
            lines: false,
        }
    }

    /// An encoder that writes each frame in full as lines of text, for a
    /// terminal that cannot move its cursor (`TERM=dumb`): no cursor moves,
    /// no screen clearing, no synchronized output.
    pub fn lines(depth: ColorDepth) -> Encoder {
        Encoder {
            lines: true,
            sync: false,
            ..Encoder::new(depth)
        }
    }

    /// Whether frames are bracketed in synchronized output (on by default;
    /// terminals that do not know it ignore it, at 16 bytes a frame).
    pub fn with_sync(mut self, on: bool) -> Encoder {
        self.set_sync(on);
        self
    }

    /// See [`Encoder::with_sync`].
    pub fn set_sync(&mut self, on: bool) {
        self.sync = on && !self.lines;
    }

    /// Whether frames are bracketed in synchronized output.
    pub fn sync(&self) -> bool {
        self.sync
    }

    /// Measures "nearest" palette colours with `metric` (OKLCh by default).
    pub fn with_metric(mut self, metric: Metric) -> Encoder {
        self.quantizer = Quantizer::of(Palette {
            metric,
            ..self.palette()
        });
        self
    }

    /// Dithers as `dither` says (`auto` by default: ordered in 16 and 256 colours).
    pub fn with_dither(mut self, dither: Dither) -> Encoder {
        self.dither = dither;
        self.quantizer = Quantizer::of(self.palette());
        self
    }

    /// How colours are sent (`auto` dithering resolved).
    pub fn palette(&self) -> Palette {
        Palette {
            depth: self.quantizer.depth(),
            metric: self.quantizer.metric(),
            dither: self.dither,
        }
    }

    /// Sends runs of identical cells with REP when `rep` is [`Rep::On`].
    pub fn with_rep(mut self, rep: Rep) -> Encoder {
        self.rep = rep;
        self
    }

    /// The colour depth frames are sent at.
    pub fn depth(&self) -> ColorDepth {
        self.quantizer.depth()
    }

    /// Changes the colour depth; the next frame is a full redraw.
    pub fn set_depth(&mut self, depth: ColorDepth) {
        if depth != self.depth() {
            self.quantizer = Quantizer::of(Palette {
                depth,
                ..self.palette()
            });
            self.invalidate();
        }
    }

    /// Forgets what the terminal shows: the next frame is a full redraw.
    pub fn invalidate(&mut self) {
        self.synced = false;
    }

    /// The bytes of the last frame encoded.
    pub fn last_bytes(&self) -> &[u8] {
        &self.buf
    }

    /// Encodes `frame` and writes it; returns the number of bytes written.
    pub fn encode(&mut self, frame: &Frame, out: &mut impl Write) -> io::Result<usize> {
        self.prepare(frame);
        out.write_all(&self.buf)?;
        out.flush()?;
        Ok(self.buf.len())
    }

    /// Encodes `frame` into [`Encoder::last_bytes`] without writing it, and
    /// takes it as shown.
    pub fn prepare(&mut self, frame: &Frame) {
        self.buf.clear();
        if self.lines {
            quantize(frame, &mut self.quantizer, &mut self.next);
            let depth = self.depth();
            push_lines(
                &self.next,
                frame.cols(),
                frame.rows(),
                depth,
                self.rep,
                &mut self.buf,
            );
            return;
        }
        if self.sync {
            self.buf.extend_from_slice(SYNC_BEGIN);
        }
        let full = !self.synced || frame.cols() != self.cols || frame.rows() != self.rows;
        let mut cursor = None;
        if full {
            self.cols = frame.cols();
            self.rows = frame.rows();
            self.shown.clear();
            self.shown.resize(frame.cells().len(), Packed::BLANK);
            self.shown_drawn = Rect::EMPTY;
            // Home, default colours, clear: the screen is now all blanks.
            self.buf.extend_from_slice(b"\x1b[H\x1b[m\x1b[2J");
            cursor = Some(Cursor { row: 0, col: 0 });
        }
        // Only the cells that are not blank in the frame or on the screen
        // (as far as either knows) can differ.
        let all = Rect::all(self.cols as u32, self.rows as u32);
        let known = frame.known();
        let drawn = if known.fill == Cell::BLANK {
            known.rect.intersect(all)
        } else {
            all
        };
        let region = drawn.union(self.shown_drawn).intersect(all);
        let candidates = if self.quantizer.depth() == ColorDepth::TrueColor {
            quantize_truecolor(
                frame,
                &self.shown,
                &mut self.next,
                &mut self.changes,
                region,
            )
        } else {
            quantize_in(frame, &mut self.quantizer, &mut self.next, region);
            let cols = self.cols as usize;
            unequal_cells(&self.shown, &self.next, &mut self.changes, cols, region)
        };
        let start = self.buf.len();
        self.write_changes(candidates, cursor, region);
        if self.buf.len() == start && !full {
            // Nothing changed: nothing to send.
            self.buf.clear();
        } else if self.sync {
            self.buf.extend_from_slice(SYNC_END);
        }
        // The terminal now shows the frame.
        let cols = self.cols as usize;
        for y in region.y0..region.y1 {
            let span = region.columns(y);
            let row = y as usize * cols;
            self.shown[row..][span.clone()].copy_from_slice(&self.next[row..][span]);
        }
        self.shown_drawn = drawn;
        self.synced = true;
    }

    /// Appends the changed cells to the buffer, ending with the pen reset.
    /// `candidates`: the number of cells listed in `self.changes` as
    /// unequal to the cell shown, all in `region`, outside which no cell
    /// changed (and `self.next` holds nothing).
    fn write_changes(&mut self, candidates: usize, mut cursor: Option<Cursor>, region: Rect) {
        let cols = self.cols as usize;
        let buf = &mut self.buf;
        let changes = changed_cells(&self.shown, &self.next, &mut self.changes[..candidates]);
        let (shown, next) = (&self.shown, &self.next);
        let mut pen = Inks::default();
        // Index of the first cell not yet written (REP runs write ahead).
        let mut done = 0usize;
        // The end of the last run of changed copies counted, and its cell:
        // a cell inside it has the rest of the run as its copies.
        let mut counted = (0usize, Packed::BLANK);
        for &i in changes {
            let i = i as usize;
            if i < done {
                continue;
            }
            let packed = next[i];
            let to = Cursor {
                row: (i / cols) as u16,
                col: (i % cols) as u16,
            };
            // Most often the next cell written is the one the cursor is on.
            if cursor != Some(to) {
                let lo = to.row as usize * cols + region.x0 as usize;
                move_to(buf, (next, lo, i), self.cols, cursor, to, pen);
            }
            // The copies and REP runs end where the region does: no cell
            // changed beyond it.
            let row_end = to.row as usize * cols + region.x1 as usize;
            // With REP, identical cells that follow on the row are sent as
            // one run, up to the last changed one among them.
            let run = if self.rep == Rep::On {
                let same = next[i + 1..row_end]
                    .iter()
                    .take_while(|c| **c == packed)
                    .count();
                1 + (0..same)
                    .rev()
                    .find(|&k| !shown[i + 1 + k].same_picture(&next[i + 1 + k]))
                    .map_or(0, |k| k + 1)
            } else {
                1
            };
            // Of the cell and its flip, the one that costs least over the
            // changed copies of it that follow (counted once a run).
            let copies = || {
                if i < counted.0 && counted.1 == packed {
                    return counted.0 - i;
                }
                let n = 1
                    + (i + 1..row_end)
                        .take_while(|&k| next[k] == packed && !shown[k].same_picture(&next[k]))
                        .count();
                counted = (i + n, packed);
                n
            };
            let form = packed.cheapest_from(pen, copies);
            pen = push_run(buf, pen, &form, run, self.rep, true);
            done = i + run;
            cursor = Some(Cursor {
                row: to.row,
                col: to.col + run as u16,
            });
        }
        push_inks(buf, pen, Inks::default());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::Cell;
    use proptest::prelude::*;

    /// Inks from a small set, so that equal ones are drawn often.
    fn ink() -> impl Strategy<Value = Ink> {
        prop_oneof![
            Just(Ink::Default),
            (0u8..3).prop_map(Ink::Indexed),
            (0u8..3).prop_map(|v| Ink::Rgb(Rgb([v, 0, 2 - v]))),
        ]
    }

    /// Cells of the glyphs that have complements and of one that has not.
    fn term_cell() -> impl Strategy<Value = TermCell> {
        let ch = prop::sample::select(vec![' ', FULL, '▀', '▄', '⣿']);
        (ch, ink(), ink()).prop_map(|(ch, fg, bg)| TermCell { ch, fg, bg })
    }

    proptest! {
        // The cases where the plane decides are rare: many cases, each fast.
        #![proptest_config(ProptestConfig::with_cases(4096))]

        /// A glyph of two colours and its complement of the same length are
        /// chosen between by the colours of the pen each keeps, as the
        /// bytes each would cost choose (a tie, or two forms that set both
        /// colours, keeps the cell as it is): over inks of every kind,
        /// bright palette colours (one digit longer as a background)
        /// included, and glyphs whose complement is longer or shorter.
        #[test]
        fn the_form_kept_is_the_one_of_fewer_bytes(
            inks in prop::array::uniform4(prop_oneof![
                Just(Ink::Default),
                (0u8..20).prop_map(Ink::Indexed),
                (0u8..3).prop_map(|v| Ink::Rgb(Rgb([v * 100, 7, 250 - v]))),
            ]),
            ch in prop::sample::select(vec!['▀', '▄', '▌', '▐', '▖', '▜', '\u{1FB00}', '\u{1FB3B}', '\u{1CD00}', '\u{1CDE5}', '\u{1FBE6}']),
        ) {
            let [fg, bg, pf, pb] = inks;
            let cell = Packed::of(TermCell { ch, fg, bg });
            let pen = Inks::of(Pen { fg: pf, bg: pb });
            if let Some(f) = cell.flipped().filter(|f| f.len() == cell.len() && !cell.fits(pen)) {
                let cost = |c: &Packed| sgr_cost(pen, c.pen(pen));
                let keeps = |c: &Packed| c.fg == pen.fg || c.bg == pen.bg;
                let cheaper = if !keeps(&cell) && !keeps(&f) || cost(&f) >= cost(&cell) { cell } else { f };
                prop_assert_eq!(cell.cheaper_of_two_colours(f, pen), cheaper);
            }
        }
    }

    proptest! {
        /// Two inks pack to the same word exactly when they are equal, and
        /// cells compare equal packed exactly when they do unpacked.
        #[test]
        fn packed_inks_and_cells_are_equal_exactly_when_they_are(
            a in ink(), b in ink(), p in term_cell(), q in term_cell(),
        ) {
            prop_assert_eq!(pack_ink(a) == pack_ink(b), a == b);
            prop_assert_eq!(Packed::of(p) == Packed::of(q), p == q);
        }

        /// The changed cells, found eight at a time, are exactly the cells
        /// of the region compared whose picture differs, in order, for rows
        /// of any length (not only multiples of eight) and with changes
        /// anywhere in a chunk.
        #[test]
        fn changed_cells_are_the_cells_whose_picture_differs(
            (cols, rows) in (1usize..20, 1usize..5),
            cells in prop::collection::vec((term_cell(), term_cell(), 0u8..4), 100),
            corners in (0u32..20, 0u32..20, 0u32..5, 0u32..5),
        ) {
            let cells = &cells[..cols * rows];
            let (a, b, c, d) = corners;
            let region = Rect { x0: a.min(b), x1: a.max(b), y0: c.min(d), y1: c.max(d) }
                .intersect(Rect::all(cols as u32, rows as u32));
            // A quarter of the cells change; the rest are equal.
            let shown: Vec<TermCell> = cells.iter().map(|c| c.0).collect();
            let next: Vec<TermCell> =
                cells.iter().map(|&(a, b, k)| if k == 0 { b } else { a }).collect();
            let pack = |v: &[TermCell]| v.iter().map(|&c| Packed::of(c)).collect::<Vec<_>>();
            let (shown_p, next_p) = (pack(&shown), pack(&next));
            let mut scratch = vec![7; 3];
            let n = unequal_cells(&shown_p, &next_p, &mut scratch, cols, region);
            let found = changed_cells(&shown_p, &next_p, &mut scratch[..n]).to_vec();
            let expected: Vec<u32> = (0..shown.len())
                .filter(|&i| region.columns((i / cols) as u32).contains(&(i % cols)))
                .filter(|&i| !shown[i].same_picture(&next[i]))
                .map(|i| i as u32)
                .collect();
            prop_assert_eq!(found, expected);
        }
    }

    proptest! {
        /// Quantizing 24-bit colour and listing the unequal cells in one
        /// pass gives the cells and the list the two passes give, for any
        /// frame shape, region compared and with changes anywhere.
        #[test]
        fn one_pass_in_truecolor_is_the_two_passes(
            (cols, rows) in (1u16..20, 1u16..5),
            seed in prop::collection::vec((0usize..5, 0u8..4, 0u8..4, 0u8..3), 100),
            corners in (0u32..20, 0u32..20, 0u32..5, 0u32..5),
        ) {
            let rgb = |k: u8| (k > 0).then(|| Rgb([k, 0, 3 - k]));
            let mut frame = Frame::default();
            frame.resize(cols, rows);
            let chars = [' ', FULL, '▀', '▄', '⣿'];
            for (c, &(ch, fg, bg, _)) in frame.cells_mut().iter_mut().zip(seed.iter().cycle()) {
                *c = Cell { ch: chars[ch], fg: rgb(fg), bg: rgb(bg) };
            }
            // What is shown: the frame's own cells, a third of them changed.
            let mut q = Quantizer::of(ColorDepth::TrueColor.into());
            let mut shown = Vec::new();
            quantize(&frame, &mut q, &mut shown);
            for (p, &(_, fg, _, k)) in shown.iter_mut().zip(seed.iter().rev().cycle()) {
                if k == 0 {
                    p.bg = pack_ink(Ink::Indexed(fg));
                }
            }
            // A region of the frame, the rest left alone.
            let (a, b, c, d) = corners;
            let region = Rect { x0: a.min(b), x1: a.max(b), y0: c.min(d), y1: c.max(d) }
                .intersect(Rect::all(cols as u32, rows as u32));
            let (mut two, mut two_list) = (Vec::new(), Vec::new());
            quantize_in(&frame, &mut q, &mut two, region);
            let n = unequal_cells(&shown, &two, &mut two_list, cols as usize, region);
            let (mut one, mut one_list) = (vec![Packed::BLANK; 3], vec![9; 2]);
            let m = quantize_truecolor(&frame, &shown, &mut one, &mut one_list, region);
            let inside = |v: &[Packed]| -> Vec<Packed> {
                (0..v.len())
                    .filter(|&i| region.columns((i / cols as usize) as u32).contains(&(i % cols as usize)))
                    .map(|i| v[i])
                    .collect()
            };
            prop_assert_eq!(inside(&one), inside(&two));
            prop_assert_eq!(&one_list[..m], &two_list[..n]);
        }
    }

    fn sgr(from: Pen, to: Pen) -> String {
        let mut b = Vec::new();
        push_sgr(&mut b, from, to);
        String::from_utf8(b).unwrap()
    }

    #[test]
    fn byte_digits_are_the_decimal_numbers_and_a_semicolon() {
        for v in 0..=255u8 {
            let mut sgr = SgrBytes {
                bytes: [0; 48],
                len: 0,
            };
            sgr.byte(v);
            assert_eq!(sgr.bytes[..sgr.len], *format!("{v};").as_bytes());
        }
    }

    #[test]
    fn sgr_writes_only_what_changes() {
        let red = Ink::Rgb(Rgb::new(255, 0, 0));
        let blue = Ink::Rgb(Rgb::new(0, 0, 255));
        let d = Ink::Default;
        let p = |fg, bg| Pen { fg, bg };
        assert_eq!(sgr(p(red, blue), p(red, blue)), "");
        assert_eq!(sgr(p(d, d), p(red, d)), "\x1b[38;2;255;0;0m");
        assert_eq!(sgr(p(red, d), p(red, blue)), "\x1b[48;2;0;0;255m");
        assert_eq!(
            sgr(p(d, d), p(red, blue)),
            "\x1b[38;2;255;0;0;48;2;0;0;255m"
        );
        assert_eq!(sgr(p(red, blue), p(red, d)), "\x1b[49m");
        assert_eq!(sgr(p(red, blue), p(d, d)), "\x1b[m");
        assert_eq!(
            sgr(p(d, d), p(Ink::Indexed(196), Ink::Indexed(3))),
            "\x1b[38;5;196;43m"
        );
        assert_eq!(
            sgr(p(d, d), p(Ink::Indexed(9), Ink::Indexed(12))),
            "\x1b[91;104m"
        );
    }

    #[test]
    fn lines_reset_at_each_end_and_plain_text_has_no_escapes() {
        let mut f = Frame::new(3, 2);
        let red = Some(Rgb::new(255, 0, 0));
        f.set(
            1,
            0,
            Cell {
                ch: ' ',
                fg: None,
                bg: red,
            },
        );
        f.set(
            2,
            0,
            Cell {
                ch: ' ',
                fg: None,
                bg: red,
            },
        );
        f.set(
            0,
            1,
            Cell {
                ch: '@',
                fg: red,
                bg: None,
            },
        );
        let mut buf = Vec::new();
        let mut out = Vec::new();
        write_lines(&f, ColorDepth::TrueColor, Rep::Off, &mut buf, &mut out).unwrap();
        assert_eq!(
            String::from_utf8(out).unwrap(),
            " \x1b[48;2;255;0;0m  \x1b[m\n\x1b[38;2;255;0;0m@  \x1b[m\n"
        );
        let mut out = Vec::new();
        write_lines(&f, ColorDepth::None, Rep::On, &mut buf, &mut out).unwrap();
        assert_eq!(String::from_utf8(out).unwrap(), f.to_string());
    }

    /// A one-row frame of `n` copies of a cell, written as lines with REP.
    fn lines_with_rep(n: u16, cell: Cell) -> String {
        let mut f = Frame::new(n, 1);
        (0..n).for_each(|c| f.set(c, 0, cell));
        let mut out = Vec::new();
        write_lines(
            &f,
            ColorDepth::TrueColor,
            Rep::On,
            &mut Vec::new(),
            &mut out,
        )
        .unwrap();
        String::from_utf8(out).unwrap()
    }

    #[test]
    fn rep_replaces_long_runs_only() {
        let white = Cell {
            ch: '▀',
            fg: Some(Rgb::WHITE),
            bg: None,
        };
        assert_eq!(
            lines_with_rep(12, white),
            "\x1b[38;2;255;255;255m▀\x1b[11b\x1b[m\n"
        );
        let x = Cell {
            ch: 'x',
            fg: None,
            bg: None,
        };
        assert_eq!(lines_with_rep(2, x), "xx\n");
    }

    #[test]
    fn moves_are_the_shortest_form() {
        let mv = |from: Option<(u16, u16)>, to: (u16, u16)| {
            let from = from.map(|(row, col)| Cursor { row, col });
            let to = Cursor {
                row: to.0,
                col: to.1,
            };
            let (cost, plan) = plan_move(from, to, 80);
            let mut b = Vec::new();
            push_move(&mut b, plan, to);
            assert_eq!(b.len(), cost);
            String::from_utf8(b).unwrap()
        };
        assert_eq!(mv(None, (0, 0)), "\x1b[H");
        assert_eq!(mv(None, (4, 0)), "\x1b[5H");
        assert_eq!(mv(None, (4, 9)), "\x1b[5;10H");
        assert_eq!(mv(Some((3, 5)), (3, 5)), "");
        assert_eq!(mv(Some((3, 5)), (3, 6)), "\x1b[C");
        // CHA and CUF cost the same here; CHA is taken.
        assert_eq!(mv(Some((3, 5)), (3, 17)), "\x1b[18G");
        assert_eq!(mv(Some((3, 5)), (3, 9)), "\x1b[4C");
        assert_eq!(mv(Some((3, 5)), (3, 0)), "\r");
        assert_eq!(mv(Some((3, 50)), (3, 1)), "\x1b[2G");
        assert_eq!(mv(Some((3, 50)), (4, 0)), "\r\n");
        assert_eq!(mv(Some((3, 50)), (4, 50)), "\x1b[B");
        // Past the last column only absolute columns are safe.
        assert_eq!(mv(Some((3, 80)), (4, 79)), "\x1b[5;80H");
        assert_eq!(mv(Some((3, 80)), (3, 2)), "\x1b[3G");
        assert_eq!(mv(Some((20, 5)), (2, 5)), "\x1b[3d");
        assert_eq!(mv(Some((20, 5)), (18, 5)), "\x1b[2A");
    }

    #[test]
    fn an_unchanged_frame_sends_nothing_and_a_change_sends_one_cell() {
        let mut e = Encoder::new(ColorDepth::TrueColor);
        let mut f = Frame::new(4, 2);
        let first = e.encode(&f, &mut Vec::new()).unwrap();
        assert_eq!(
            &e.last_bytes()[..first],
            b"\x1b[?2026h\x1b[H\x1b[m\x1b[2J\x1b[?2026l"
        );
        assert_eq!(e.encode(&f, &mut Vec::new()).unwrap(), 0);
        f.set(
            2,
            1,
            Cell {
                ch: 'x',
                fg: Some(Rgb::WHITE),
                bg: None,
            },
        );
        let mut out = Vec::new();
        e.encode(&f, &mut out).unwrap();
        let s = String::from_utf8(out).unwrap();
        assert_eq!(
            s,
            "\x1b[?2026h\x1b[2;3H\x1b[38;2;255;255;255mx\x1b[m\x1b[?2026l"
        );
        // A resize redraws in full.
        let f = Frame::new(5, 2);
        e.encode(&f, &mut Vec::new()).unwrap();
        assert!(e.last_bytes().windows(4).any(|w| w == b"\x1b[2J"));
    }

    #[test]
    fn complements_draw_the_other_samples_in_every_two_colour_mode() {
        use crate::blit::GlyphMode;
        for mode in [
            GlyphMode::Half,
            GlyphMode::Quadrant,
            GlyphMode::Sextant,
            GlyphMode::Octant,
        ] {
            let all = ((1u16 << mode.samples()) - 1) as u8;
            for mask in 0..=all {
                let ch = mode.glyph(mask);
                assert_eq!(
                    complement(ch),
                    Some(mode.glyph(!mask & all)),
                    "{mode:?} {mask:#x}"
                );
            }
        }
        for ch in [
            'a',
            '@',
            '░',
            '\u{2800}',
            '\u{28FF}',
            '\u{1FB3C}',
            '\u{1CDE6}',
        ] {
            assert_eq!(complement(ch), None, "{ch:?}");
        }
    }

    #[test]
    fn sgr_cost_is_the_length_of_the_sgr() {
        let inks = [
            Ink::Default,
            Ink::Indexed(0),
            Ink::Indexed(7),
            Ink::Indexed(8),
            Ink::Indexed(15),
            Ink::Indexed(16),
            Ink::Indexed(99),
            Ink::Indexed(255),
            Ink::Rgb(Rgb::new(0, 9, 10)),
            Ink::Rgb(Rgb::new(99, 100, 255)),
        ];
        let pens: Vec<Pen> = inks
            .iter()
            .flat_map(|&fg| inks.iter().map(move |&bg| Pen { fg, bg }))
            .collect();
        for &from in &pens {
            for &to in &pens {
                assert_eq!(
                    sgr_cost(Inks::of(from), Inks::of(to)),
                    sgr(from, to).len(),
                    "{from:?} → {to:?}"
                );
            }
        }
    }

    #[test]
    fn a_cell_is_drawn_the_other_way_round_when_that_keeps_the_pen() {
        let red = Some(Rgb::new(255, 0, 0));
        let blue = Some(Rgb::new(0, 0, 255));
        let cell = |ch, fg, bg| Cell { ch, fg, bg };
        let mut f = Frame::new(4, 1);
        f.set(0, 0, cell('▀', red, blue));
        f.set(1, 0, cell('▀', blue, red));
        f.set(2, 0, cell(' ', None, red));
        f.set(3, 0, cell('▘', blue, red));
        let mut e = Encoder::new(ColorDepth::TrueColor).with_sync(false);
        e.prepare(&f);
        // One SGR for the row: `▀` blue on red is `▄` red on blue, a blank in
        // red is `█` in red, `▘` blue on red is `▟` red on blue.
        assert_eq!(
            String::from_utf8(e.last_bytes().to_vec()).unwrap(),
            "\x1b[H\x1b[m\x1b[2J\x1b[38;2;255;0;0;48;2;0;0;255m▀▄█▟\x1b[m"
        );
        // The same picture drawn the other way round is no change.
        let mut g = Frame::new(4, 1);
        g.set(0, 0, cell('▄', blue, red));
        g.set(1, 0, cell('▄', red, blue));
        g.set(2, 0, cell('█', red, None));
        g.set(3, 0, cell('▟', red, blue));
        e.prepare(&g);
        assert_eq!(e.last_bytes(), b"");
        // A default colour is not the same as a foreground and as a
        // background: such a cell is never flipped.
        let mut h = Frame::new(2, 1);
        h.set(0, 0, cell('▀', red, blue));
        h.set(1, 0, cell('▀', blue, None));
        e.prepare(&h);
        assert!(
            e.last_bytes()
                .ends_with("\x1b[38;2;0;0;255;49m▀\x1b[m".as_bytes())
        );
    }
}
