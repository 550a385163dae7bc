//! SGR bytes: the shortest colour change from one pen to the next, its
//! cost counted before it is written, digits from a table; REP and
//! characters.

use super::*;

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
pub(super) fn push_num(buf: &mut Vec<u8>, n: u32) {
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

pub(super) fn digits(n: u32) -> usize {
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
pub(super) static BYTE_DIGITS: [([u8; 4], u8); 256] = {
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
pub(super) struct SgrBytes {
    pub(super) bytes: [u8; 48],
    pub(super) len: usize,
}

impl SgrBytes {
    /// Nothing yet.
    #[inline(always)]
    pub(super) fn new() -> SgrBytes {
        SgrBytes {
            bytes: [0; 48],
            len: 0,
        }
    }

    /// Appends a byte's digits and a `;`.
    #[inline(always)]
    pub(super) fn byte(&mut self, v: u8) {
        let (d, n) = BYTE_DIGITS[v as usize];
        self.bytes[self.len..self.len + 4].copy_from_slice(&d);
        self.len += n as usize;
    }

    /// Appends a constant prefix.
    #[inline(always)]
    pub(super) fn put(&mut self, s: &[u8; 5]) {
        self.bytes[self.len..self.len + 5].copy_from_slice(s);
        self.len += 5;
    }

    /// Appends the SGR parameters of one plane and a `;`: `fg` for the
    /// foreground (30–39, 90–97), else the background (40–49, 100–107).
    /// `ink` is packed ([`pack_ink`]).
    #[inline(always)]
    pub(super) fn ink(&mut self, fg: bool, ink: u32) {
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
    pub(super) fn inks(&mut self, from: Inks, to: Inks) {
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
    pub(super) fn glyph(&mut self, ch: u32) {
        self.len += glyph(ch)
            .encode_utf8(&mut self.bytes[self.len..self.len + 4])
            .len();
    }

    /// Appends what was assembled to `buf`.
    #[inline(always)]
    pub(super) fn append_to(&self, buf: &mut Vec<u8>) {
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
pub(super) fn ink_cost(base: u32, ink: u32) -> usize {
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

/// The length of what `push_sgr` appends.
#[inline(always)]
pub(super) fn sgr_cost(from: Inks, to: Inks) -> usize {
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
pub(super) fn push_sgr(buf: &mut Vec<u8>, from: Pen, to: Pen) {
    push_inks(buf, Inks::of(from), Inks::of(to));
}

/// `push_sgr` for packed pens.
#[inline(always)]
pub(super) fn push_inks(buf: &mut Vec<u8>, from: Inks, to: Inks) {
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
