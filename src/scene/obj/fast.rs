//! The OBJ reader's fast path: the lines that make up nearly all of a
//! large file (`v x y z`, `vn x y z`, `vt u v [w]`, and `f` with positive
//! indices in any of the four corner forms), read straight from the line
//! buffer in one pass, with no line split first and no word split at all.
//!
//! It is a shortcut, never a second reading: a line is taken only when it
//! is exactly what the general reader ([`Reader::statement`]) would read
//! the same way, and its effect is made by the same code (a `v` through
//! `Reader::position`, or past its finiteness test for short numbers,
//! which are finite; a face through `Reader::add_face`, or its part for a
//! triangle or quad). Whatever else it meets (a sign `+`, an exponent,
//! eight digits in a row, a comment, a negative or out-of-range index, a
//! line that the buffer has not yet read to its end) it hands back,
//! untouched, to the general reader, which also places every error. The
//! property test below holds the two readers to the same models and the
//! same errors.
//!
//! The commonest shapes are tried first, with no loop over gaps: a `v`
//! (also with a colour), `vn` or `vt` line of short numbers after single
//! spaces (each number and the byte after it from one look at 9 bytes),
//! and a face of three or four corners that are all bare position indices
//! (`f 1 2 3 4`), all `v/vt/vn` or all `v//vn` (`f 1/1/1 2/2/2 3/3/3`,
//! `f 1//1 2//2 3//3`, as most exporters write), each index and the byte
//! after it from one 8-byte look, added without the corner list. Each
//! takes the line's first bytes as one fixed-size array that holds every
//! byte it may look at (48 or 80 for numbers, 40 or 100 for faces: more
//! than such a line can have), so that the looks need no bounds checks of
//! their own; a line with fewer bytes left in the window (the last few of
//! a buffer), or of any other shape, goes the general way of this module.
//!
//! What parsing costs a byte is in docs/figures.md ("Memory, loading and
//! start-up"); the property test holds both ways to the general reader.
//!
//! The bytes after the buffer's unread ones are NUL (`lines::SLACK`, 16, of
//! them), and no item takes a NUL, so every 8-byte look ahead stays
//! inside the window and a line that is cut off is never taken.

use glam::{Vec2, Vec3};

use super::{MAX_VERTICES, NONE, Reader, vertex_color};
use crate::scene::lines::{POW10_INT, digit_bytes, digits_value, exact_decimal, short_digits};

/// A position in the buffer's window.
struct Scan<'w> {
    w: &'w [u8],
    i: usize,
}

/// Whether `b` separates items on a fast line (a subset of what the
/// general reader calls blank).
#[inline]
fn gap(b: u8) -> bool {
    b == b' ' || b == b'\t' || b == b'\r'
}

impl Scan<'_> {
    /// The byte at the position (NUL past the window).
    #[inline]
    fn byte(&self) -> u8 {
        self.byte_at(self.i)
    }

    /// The byte at `at` (NUL past the window).
    #[inline]
    fn byte_at(&self, at: usize) -> u8 {
        self.w.get(at).copied().unwrap_or(0)
    }

    /// The digits at `at`, their value and how many there are (fewer than
    /// eight; `None` for eight in a row).
    #[inline]
    fn digits(&self, at: usize) -> Option<(u64, usize)> {
        short_digits(*self.w.get(at..)?.first_chunk::<8>()?)
    }

    /// Past the gaps; `Some(true)` at the line's end (the position then
    /// after its `\n`), `Some(false)` before another item, `None` if an item
    /// does not end here.
    #[inline]
    fn next(&mut self) -> Option<bool> {
        let start = self.i;
        // Nearly always: the line's end, or one space before an item.
        match self.byte() {
            b'\n' => {
                self.i += 1;
                return Some(true);
            }
            b' ' if !gap(self.byte_at(self.i + 1)) && self.byte_at(self.i + 1) != b'\n' => {
                self.i += 1;
                return Some(false);
            }
            _ => {}
        }
        while gap(self.byte()) {
            self.i += 1;
        }
        if self.byte() == b'\n' {
            self.i += 1;
            return Some(true);
        }
        (self.i > start).then_some(false)
    }

    /// A decimal `[-]digits[.digits]` that the general reader reads
    /// exactly (fewer than eight digits on each side, below 2^24 in all).
    /// One 8-byte look finds the point and the end, and reads a number of
    /// up to 8 bytes (`-0.008366`, `12.125`, `1500`) with the point
    /// taken out; a longer one takes a look on each side of the point.
    #[inline]
    fn decimal(&mut self) -> Option<f32> {
        let neg = self.byte() == b'-';
        self.i += neg as usize;
        let (t, not_digit) = digit_bytes(*self.w.get(self.i..)?.first_chunk::<8>()?);
        // Where the first byte that is not a digit is (8: none).
        let d = (not_digit.trailing_zeros() / 8) as usize;
        if d < 8 && (t >> (8 * d)) as u8 == b'.' ^ b'0' {
            // The second (8: none), its byte exact as the point does not carry.
            let e = ((not_digit & (not_digit - 1)).trailing_zeros() / 8) as usize;
            if e < 8 || !self.byte_at(self.i + 8).is_ascii_digit() {
                let (n, decimals) = (e - 1, e - d - 1);
                if n == 0 {
                    return None;
                }
                // The digits after the point moved down over it.
                let low = (1u64 << (8 * d)) - 1;
                let m = digits_value((t & low) | ((t >> 8) & !low), n);
                self.i += e;
                return Some(exact_decimal(m, decimals, neg));
            }
        } else if (1..8).contains(&d) {
            self.i += d;
            return Some(exact_decimal(digits_value(t, d), 0, neg));
        }
        self.long_decimal(neg)
    }

    /// The `N` numbers of a usual `v`, `vn` or `vt` line, each after one
    /// space and the last before the line's end, each read by
    /// [`short_decimal`] from the `W` bytes at the position (48 for up to
    /// three such numbers, whose line has at most 32 from there; 80 for
    /// six, at most 62): `None` (the position unchanged) for any other
    /// line, or one too near the window's end, for [`Scan::decimals`] to
    /// read.
    #[inline(always)]
    fn short<const N: usize, const W: usize>(&mut self) -> Option<[f32; N]> {
        let line = self.w.get(self.i..)?.first_chunk::<W>()?;
        let (mut v, mut at) = ([0.0; N], 0);
        for (k, x) in v.iter_mut().enumerate() {
            let (value, after, next) = short_decimal(line, at)?;
            if after != if k + 1 == N { b'\n' } else { b' ' } {
                return None;
            }
            (*x, at) = (value, next);
        }
        self.i += at;
        Some(v)
    }

    /// [`Scan::decimal`] for one of more than 8 bytes (after its sign).
    #[inline(never)]
    fn long_decimal(&mut self, neg: bool) -> Option<f32> {
        let (mut m, whole) = self.digits(self.i)?;
        self.i += whole;
        let mut decimals = 0;
        if self.byte() == b'.' {
            let (f, n) = self.digits(self.i + 1)?;
            m = m * POW10_INT[n] + f;
            decimals = n;
            self.i += 1 + n;
        }
        (whole + decimals > 0 && m < 1 << 24).then(|| exact_decimal(m, decimals, neg))
    }

    /// Up to `N` decimals and the line's end, if there are at least `least`;
    /// the numbers and how many.
    #[inline]
    fn decimals<const N: usize>(&mut self, least: usize) -> Option<([f32; N], usize)> {
        // A copy, whose position stays in a register.
        let mut s = Scan {
            w: self.w,
            i: self.i,
        };
        let mut v = [0.0; N];
        for (k, x) in v.iter_mut().enumerate() {
            *x = s.decimal()?;
            if s.next()? {
                self.i = s.i;
                return (k + 1 >= least).then_some((v, k + 1));
            }
        }
        None
    }

    /// A positive index, resolved from 1 (`count` is how many there are).
    #[inline]
    fn index(&mut self, count: usize) -> Option<u32> {
        let (i, n) = self.digits(self.i)?;
        self.i += n;
        (i >= 1 && i <= count as u64).then(|| i as u32 - 1)
    }
}

/// The usual number at `at` in `line`, `[-]digits.digits` or `[-]digits`
/// of up to 8 bytes after its sign with a digit first, read from one look
/// at the 9 bytes after its sign: the number [`Scan::decimal`] reads where
/// the byte after it is not a digit (where it is, the number goes on, and
/// the caller must not take it), that byte, and the position past it;
/// `None` for any other. Called at positions at least 28 bytes short of
/// the end of `line`, so every index stays inside it.
#[inline(always)]
fn short_decimal<const W: usize>(line: &[u8; W], at: usize) -> Option<(f32, u8, usize)> {
    let neg = line[at] == b'-';
    // The number's bytes from the first after its sign.
    let rest = line.get(at + neg as usize..)?.first_chunk::<9>()?;
    let (t, not_digit) = digit_bytes(*rest.first_chunk::<8>()?);
    // Where the first byte that is not a digit is: at least one digit
    // before it (`.5` goes the general way), and not 8.
    let d = (not_digit.trailing_zeros() / 8) as usize;
    if !(1..8).contains(&d) {
        return None;
    }
    let (m, decimals, end) = if (t >> (8 * d)) as u8 == b'.' ^ b'0' {
        // The second (8: none), its byte exact as the point does not carry.
        let e = ((not_digit & (not_digit - 1)).trailing_zeros() / 8) as usize;
        // The digits after the point moved down over it.
        let low = (1u64 << (8 * d)) - 1;
        (
            digits_value((t & low) | ((t >> 8) & !low), e - 1),
            e - d - 1,
            e,
        )
    } else {
        (digits_value(t, d), 0, d)
    };
    // At most 6 decimals (the `& 7` changes nothing; it spares the powers'
    // table a bounds check).
    let value = exact_decimal(m, decimals & 7, neg);
    Some((value, rest[end], at + neg as usize + end + 1))
}

/// An index at `at` in `line` (1 to 7 digits, from 1 to `count`), read
/// from one 8-byte look: the index (from 0), the byte after it and the
/// position past that byte. Called at positions at most 8 bytes short of
/// the line's end, so every index stays inside it.
#[inline(always)]
fn plain_corner<const N: usize>(line: &[u8; N], at: usize, count: u64) -> Option<(u32, u8, usize)> {
    let (t, not_digit) = digit_bytes(*line.get(at..)?.first_chunk::<8>()?);
    let d = (not_digit.trailing_zeros() / 8) as usize;
    if d == 0 || d == 8 {
        return None;
    }
    let x = digits_value(t, d).wrapping_sub(1);
    (x < count).then_some((x as u32, (t >> (8 * d)) as u8 ^ b'0', at + d + 1))
}

/// A face corner `v/vt/vn` (or, without `VT`, `v//vn`) at `at` in `line`
/// (each index as [`plain_corner`] reads it, within `counts`): the three
/// indices (`vt` `NONE` without `VT`), the byte after the last and the
/// position past that byte. Called at positions at most 24 bytes short of
/// the line's end.
#[inline(always)]
fn full_corner<const VT: bool>(
    line: &[u8; 100],
    at: usize,
    counts: [u64; 3],
) -> Option<([u32; 3], u8, usize)> {
    let Some((v, b'/', at)) = plain_corner(line, at, counts[0]) else {
        return None;
    };
    let (vt, at) = if VT {
        let Some((vt, b'/', at)) = plain_corner(line, at, counts[1]) else {
            return None;
        };
        (vt, at)
    } else if line[at] == b'/' {
        (NONE, at + 1)
    } else {
        return None;
    };
    let (vn, after, at) = plain_corner(line, at, counts[2])?;
    Some(([v, vt, vn], after, at))
}

impl Reader<'_> {
    /// Reads the fast lines at the start of `window` ([`Reader::fast_line`]),
    /// the first numbered `n`, up to the first that is not: returns the
    /// bytes and the lines read.
    pub(super) fn fast_lines(&mut self, window: &[u8], n: usize) -> (usize, usize) {
        let (mut at, mut count) = (0, 0);
        while let Some(len) = window.get(at..).and_then(|w| self.fast_line(w, n + count)) {
            at += len;
            count += 1;
        }
        (at, count)
    }

    /// Reads the line at the start of `window` (the line buffer's unread
    /// bytes and their NUL slack), numbered `n`, if it is a fast line:
    /// returns its length with its `\n`, or `None` (nothing changed) for
    /// the general reader to read.
    #[inline]
    pub(super) fn fast_line(&mut self, window: &[u8], n: usize) -> Option<usize> {
        // The commonest shapes of `v` and `f` lines, told by their first
        // two bytes; any other line of theirs goes the general way below
        // (which tries none of them again).
        let mut s = Scan { w: window, i: 2 };
        match window.first_chunk::<2>()? {
            b"v " => {
                if let Some(p) = s.short::<3, 48>()
                    && self.pos.len() < MAX_VERTICES
                {
                    // Short numbers are finite.
                    self.finite_position(Vec3::from(p), None);
                    return Some(s.i);
                }
                if let Some(len) = self.fast_color_vertex(window) {
                    return Some(len);
                }
            }
            b"f "
                if self.fast_plain_face(&mut s)
                    || self.fast_full_face::<true>(&mut s)
                    || self.fast_full_face::<false>(&mut s) =>
            {
                return Some(s.i);
            }
            _ => {}
        }
        let key = *window.first_chunk::<3>()?;
        let (skip, kind) = match key {
            [b'v', b, _] if gap(b) => (1, b'v'),
            [b'v', b'n', b] if gap(b) => (2, b'n'),
            [b'v', b't', b] if gap(b) => (2, b't'),
            [b'f', b, _] if gap(b) => (1, b'f'),
            _ => return None,
        };
        let mut s = Scan { w: window, i: skip };
        if s.next()? {
            return None;
        }
        match kind {
            b'v' => {
                // Not tried again where it was tried above (`v ` then no
                // other gap: a `v` with colours, say).
                let tried = window[1] == b' ' && s.i == 2;
                let short = if tried { None } else { s.short::<3, 48>() };
                let [x, y, z] = match short {
                    Some(v) => v,
                    None => s.decimals::<3>(3)?.0,
                };
                if self.pos.len() == MAX_VERTICES {
                    return None;
                }
                self.position(Vec3::new(x, y, z), None, n);
            }
            b'n' => {
                let v = match s.short::<3, 48>() {
                    Some(v) => v,
                    None => s.decimals::<3>(3)?.0,
                };
                self.vn.push(Vec3::from(v));
            }
            b't' => {
                let [u, v] = match s.short::<2, 48>() {
                    Some(uv) => uv,
                    None => {
                        let ([u, v, _], _) = s.decimals::<3>(2)?;
                        [u, v]
                    }
                };
                if self.vt.len() == MAX_VERTICES {
                    return None;
                }
                self.vt.push(Vec2::new(u, 1.0 - v));
            }
            _ => {
                self.fast_corners(&mut s)?;
                self.add_face();
            }
        }
        Some(s.i)
    }

    /// A `v` line with a colour (`v x y z r g b`, as scans write them), of
    /// six short numbers after single spaces ([`Scan::short`], from the 80
    /// bytes at the first: such a line has at most 62): its length, or
    /// `None` (nothing changed). Out of line, so that the usual `v` line's
    /// code is laid out as it was (inlined, parsing the torus of
    /// docs/figures.md cost a twentieth more).
    #[inline(never)]
    fn fast_color_vertex(&mut self, window: &[u8]) -> Option<usize> {
        let mut s = Scan { w: window, i: 2 };
        let [x, y, z, r, g, b] = s.short::<6, 80>()?;
        if self.pos.len() == MAX_VERTICES {
            return None;
        }
        // Short numbers are finite, the colour's too.
        self.finite_position(Vec3::new(x, y, z), Some(vertex_color([r, g, b])));
        Some(s.i)
    }

    /// A face of three or four corners that name positions alone, each
    /// after one space and the last before the line's end (`f 1 2 3 4`),
    /// read by [`plain_corner`] from the 40 bytes at the position (such a
    /// line has at most 32) and added ([`Reader::add_plain_face`]): `true`,
    /// the position then past the line. `false` (nothing read or changed)
    /// for any other face, or one too near the window's end, which
    /// [`Reader::fast_corners`] then reads.
    #[inline(always)]
    fn fast_plain_face(&mut self, s: &mut Scan) -> bool {
        let Some(line) = s.w.get(s.i..).and_then(|w| w.first_chunk::<40>()) else {
            return false;
        };
        let count = self.pos.len() as u64;
        // Unrolled (as a loop it is not), the separators told after: a
        // corner read past a wrong one is read in vain, not wrongly.
        let Some((a, b' ', at)) = plain_corner(line, 0, count) else {
            return false;
        };
        let Some((b, b' ', at)) = plain_corner(line, at, count) else {
            return false;
        };
        match plain_corner(line, at, count) {
            Some((c, b'\n', at)) => {
                self.add_plain_face([a, b, c]);
                s.i += at;
            }
            Some((c, b' ', at)) => {
                let Some((d, b'\n', at)) = plain_corner(line, at, count) else {
                    return false;
                };
                self.add_plain_face([a, b, c, d]);
                s.i += at;
            }
            _ => return false,
        }
        true
    }
    /// A face of three or four corners `v/vt/vn` (or, without `VT`,
    /// `v//vn`), each after one space and the last before the line's end
    /// (`f 1/1/1 2/2/2 3/3/3` or `f 1//1 2//2 3//3`, as most exporters
    /// write a face), read by [`full_corner`] from the 100 bytes at the
    /// position (such a line has at most 96) and added
    /// ([`Reader::add_small_face`], with its `vt` only where textured):
    /// `true`, the position then past the line. `false` (nothing read or
    /// changed) for any other face, or one too near the window's end.
    #[inline(always)]
    fn fast_full_face<const VT: bool>(&mut self, s: &mut Scan) -> bool {
        let Some(line) = s.w.get(s.i..).and_then(|w| w.first_chunk::<100>()) else {
            return false;
        };
        let counts = [self.pos.len(), self.vt.len(), self.vn.len()].map(|n| n as u64);
        // Texture coordinates matter only where a texture is read.
        let keep =
            |[v, vt, vn]: [u32; 3], textured: bool| [v, if textured { vt } else { NONE }, vn];
        let Some((a, b' ', at)) = full_corner::<VT>(line, 0, counts) else {
            return false;
        };
        let Some((b, b' ', at)) = full_corner::<VT>(line, at, counts) else {
            return false;
        };
        let t = self.textured;
        match full_corner::<VT>(line, at, counts) {
            Some((c, b'\n', at)) => {
                self.add_small_face([keep(a, t), keep(b, t), keep(c, t)]);
                s.i += at;
            }
            Some((c, b' ', at)) => {
                let Some((d, b'\n', at)) = full_corner::<VT>(line, at, counts) else {
                    return false;
                };
                self.add_small_face([keep(a, t), keep(b, t), keep(c, t), keep(d, t)]);
                s.i += at;
            }
            _ => return false,
        }
        true
    }

    /// A face's corners into `corners`, to the line's end, if every one is
    /// `v`, `v/vt`, `v//vn` or `v/vt/vn` with positive indices in range,
    /// and there are at least 3. A `v` alone is read in one 8-byte look
    /// that also holds the byte after it, so that one space and the next
    /// corner are taken without a second look.
    #[inline]
    fn fast_corners(&mut self, s: &mut Scan) -> Option<()> {
        let counts = [self.pos.len(), self.vt.len(), self.vn.len()];
        self.corners.clear();
        loop {
            let (t, not_digit) = digit_bytes(*s.w.get(s.i..)?.first_chunk::<8>()?);
            let d = (not_digit.trailing_zeros() / 8) as usize;
            if d == 0 {
                // Not a digit: gaps other than one space, or the line's end.
                if s.next()? {
                    break;
                }
                continue;
            }
            if d == 8 {
                return None;
            }
            let i = digits_value(t, d);
            let v = (i >= 1 && i <= counts[0] as u64).then(|| i as u32 - 1)?;
            s.i += d;
            let mut after = (t >> (8 * d)) as u8 ^ b'0';
            let (mut vt, mut vn) = (NONE, NONE);
            if after == b'/' {
                s.i += 1;
                if s.byte() != b'/' {
                    vt = s.index(counts[1])?;
                }
                if s.byte() == b'/' {
                    s.i += 1;
                    vn = s.index(counts[2])?;
                }
                // Texture coordinates matter only where a texture is read.
                if !self.textured {
                    vt = NONE;
                }
                after = s.byte();
            }
            self.corners.push([v, vt, vn]);
            match after {
                // The next corner, or (not a digit) gaps or the end, above.
                b' ' => s.i += 1,
                b'\n' => {
                    s.i += 1;
                    break;
                }
                _ if s.next()? => break,
                _ => {}
            }
        }
        (self.corners.len() >= 3).then_some(())
    }
}

#[cfg(test)]
mod tests {
    use std::io::Read;
    use std::path::Path;

    use proptest::prelude::*;

    use super::super::{LoadOptions, Reader, read_with};
    use crate::scene::file::Files;
    use crate::scene::lines::Cursor;

    /// A reader that hands out `step` bytes at a time, so that lines are
    /// cut at every place by the line buffer's ends.
    struct Trickle<'a>(&'a [u8], usize);

    impl Read for Trickle<'_> {
        fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
            let n = self.0.len().min(self.1).min(buf.len());
            buf[..n].copy_from_slice(&self.0[..n]);
            self.0 = &self.0[n..];
            Ok(n)
        }
    }

    /// The model or the error, as text (`{:?}` writes every float so that
    /// it reads back to the same bits), read with or without the fast path.
    fn read(src: &[u8], step: usize, fast: bool) -> String {
        let options = LoadOptions::default();
        let files = Files::new(options.max_bytes);
        match read_with(
            Trickle(src, step),
            "t.obj",
            Path::new("."),
            &options,
            &files,
            fast,
        ) {
            Ok(loaded) => format!("{loaded:?}"),
            Err(e) => format!("error: {e}"),
        }
    }

    /// How many lines of `src` the fast path takes, each read from a
    /// window that holds it, `after` (as the following lines would be)
    /// and the NUL slack.
    fn fast_lines(src: &[u8], after: &[u8]) -> usize {
        let options = LoadOptions::default();
        let files = Files::new(options.max_bytes);
        let mut r = Reader::new("t.obj", Path::new("."), &options, &files);
        for line in ["v 0 0 0", "v 1 0 0", "v 0 1 0", "vt 0 0", "vn 0 0 1"] {
            r.statement(Cursor::new(line.as_bytes()), 1).unwrap();
        }
        let mut n = 0;
        for line in src.split_inclusive(|&b| b == b'\n') {
            let mut window = line.to_vec();
            window.extend(after);
            window.extend([0; crate::scene::lines::SLACK]);
            n += r.fast_line(&window, 2).is_some() as usize;
        }
        n
    }

    /// `usual` mostly, sometimes `odd`, and (in a noisy model) seldom `bad`.
    fn mix<T: std::fmt::Debug + 'static>(
        noisy: bool,
        usual: BoxedStrategy<T>,
        odd: BoxedStrategy<T>,
        bad: BoxedStrategy<T>,
    ) -> BoxedStrategy<T> {
        if noisy {
            prop_oneof![40 => usual, 8 => odd, 1 => bad].boxed()
        } else {
            prop_oneof![5 => usual, 1 => odd].boxed()
        }
    }

    fn strings(s: &[&'static str]) -> BoxedStrategy<String> {
        prop::sample::select(s.to_vec())
            .prop_map(String::from)
            .boxed()
    }

    /// A number in the shapes files use (short decimals, long ones,
    /// integers, odd but valid forms), or one the reader refuses.
    fn number(noisy: bool) -> BoxedStrategy<String> {
        let short =
            (-3000i32..3000, 0usize..7).prop_map(|(m, k)| format!("{:.*}", k, m as f64 / 997.0));
        let long = (-99_999_999i64..99_999_999, 0usize..12)
            .prop_map(|(m, k)| format!("{:.*}", k, m as f64 / 1e5));
        let odd = strings(&[
            "1e3",
            "+1.5",
            ".5",
            "-.25",
            "5.",
            "-0",
            "-0.0",
            "00000000001",
            "12345678",
            "16777216",
            "16777217",
            "1.6777217",
            "9999999.9",
            "0.00000001",
            "1234567.",
            "inf",
        ]);
        let usual = prop_oneof![3 => short, 1 => long].boxed();
        mix(
            noisy,
            usual,
            odd,
            strings(&["-", ".", "1.2.3", "0x1", "1-2"]),
        )
    }

    /// A face corner in one of the four forms, or odd forms, or one out
    /// of range.
    fn corner(noisy: bool) -> BoxedStrategy<String> {
        let index = mix(
            noisy,
            (1i32..13).boxed(),
            (-4i32..0).boxed(),
            prop_oneof![Just(0), Just(13)].boxed(),
        );
        let form = mix(noisy, (0u8..4).boxed(), (4u8..6).boxed(), Just(6).boxed());
        (index.clone(), index.clone(), index, form)
            .prop_map(|(v, t, n, form)| match form {
                0 => format!("{v}"),
                1 => format!("{v}/{t}"),
                2 => format!("{v}//{n}"),
                3 => format!("{v}/{t}/{n}"),
                4 => format!("{v}/{t}/"),
                5 => format!("{v}//"),
                _ => format!("/{t}"),
            })
            .boxed()
    }

    /// A line: `v`, `vn`, `vt` and `f` in their usual and unusual shapes,
    /// gaps and endings of every kind, and other statements.
    fn line(noisy: bool) -> BoxedStrategy<String> {
        let gap = mix(
            noisy,
            strings(&[" "]),
            strings(&["\t", "  ", " \r", "\x0b"]),
            strings(&[""]),
        );
        let end = mix(
            noisy,
            strings(&["\n"]),
            strings(&[" \n", "\r\n", " # c\n", "\t\n"]),
            strings(&["\n\n"]),
        );
        let items =
            move |key: &'static str, items: BoxedStrategy<String>, n: BoxedStrategy<usize>| {
                let (gap, end) = (gap.clone(), end.clone());
                n.prop_flat_map(move |n| {
                    (
                        prop::collection::vec((gap.clone(), items.clone()), n),
                        end.clone(),
                    )
                })
                .prop_map(move |(items, end)| {
                    let body: String = items.into_iter().map(|(g, x)| format!("{g}{x}")).collect();
                    format!("{key}{body}{end}")
                })
                .boxed()
            };
        let count = |usual: usize, odd: &[usize], bad: &[usize]| {
            let pick = |n: &[usize]| prop::sample::select(n.to_vec()).boxed();
            mix(noisy, Just(usual).boxed(), pick(odd), pick(bad))
        };
        prop_oneof![
            6 => items("v", number(noisy), count(3, &[4, 6, 7], &[2, 5, 8])),
            2 => items("vn", number(noisy), count(3, &[3], &[2, 4])),
            2 => items("vt", number(noisy), count(2, &[1, 3], &[0, 4])),
            6 => items("f", corner(noisy), count(3, &[4, 4, 4, 5, 8], &[1, 2])),
            1 => strings(&["\n", "# x\n", "o a b\n", "usemtl m\n", "l 1 2\n", "vx 1 2 3\n", "\u{feff}v 1 2 3\n"]),
        ]
        .boxed()
    }

    /// A model of enough vertices, normals and texture coordinates for most
    /// corners, then random lines (free of errors in half the models), and
    /// how many bytes the reader gets at a time.
    fn model() -> impl Strategy<Value = (String, usize)> {
        any::<bool>()
            .prop_flat_map(|noisy| {
                (
                    prop::collection::vec(line(noisy), 1..40),
                    prop_oneof![1usize..80, Just(1 << 20)],
                )
            })
            .prop_map(|(lines, step)| {
                let mut text = String::new();
                for k in 0..12 {
                    text += &format!("v {k}.5 {} -{k}.25\nvn 0 0 1\nvt 0.{k} 0.5\n", k * k);
                }
                text += &lines.concat();
                (text, step)
            })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(600))]
        /// Whatever the lines and wherever the buffer cuts them, the fast
        /// path reads the same model, or the same error, as the general
        /// reader alone.
        #[test]
        fn the_fast_path_reads_what_the_general_reader_reads((text, step) in model()) {
            let src = text.as_bytes();
            let a = read(src, step, true);
            prop_assert_eq!(a, read(src, step, false));
        }
    }

    /// Faces of a textured material, read by the general reader and by
    /// the fast path: the same model (their `v/vt/vn` corners keep their
    /// `vt`, and `v//vn` corners name none).
    #[test]
    fn textured_faces_read_the_same_either_way() {
        let faces = [
            "f 1/1/1 2/2/1 3/3/1",
            "f 1//1 2//1 3//1 4//1",
            "f 4/4/1 3/3/1 2/2/1",
        ];
        let later = b"f 1 2 3\n".repeat(16);
        let read = |fast: bool| {
            let options = LoadOptions::default();
            let files = Files::new(options.max_bytes);
            let mut r = Reader::new("t.obj", Path::new("."), &options, &files);
            for line in [
                "v 0 0 0", "v 1 0 0", "v 1 1 0", "v 0 1 0", "vt 0 0", "vt 1 0", "vt 1 1", "vt 0 1",
                "vn 0 0 1",
            ] {
                r.statement(Cursor::new(line.as_bytes()), 1).unwrap();
            }
            r.textured = true;
            for face in faces {
                if fast {
                    let mut window = format!("{face}\n").into_bytes();
                    window.extend(&later);
                    window.extend([0; crate::scene::lines::SLACK]);
                    assert!(r.fast_line(&window, 2).is_some(), "{face}");
                } else {
                    r.statement(Cursor::new(face.as_bytes()), 2).unwrap();
                }
            }
            format!("{:?}", r.finish(3).unwrap())
        };
        assert_eq!(read(true), read(false));
    }

    #[test]
    fn the_fast_path_takes_the_common_lines_and_leaves_the_rest() {
        let taken = b"v 1.349972 0.004398 -0.000000\nv -12.5 7 0.125\nvn 0.6265 -0.7116 0.3180\n\
            vt 0.742686 0.551393\nvt 0.5 0.5 0\nf 1 2 3\nf 1/1 2/1 3/1\nf 1//1 2//1 3//1 \r\nf 1//1 2//1 3//1\n\
            f 1/1/1 2/1/1 3/1/1 1/1/1\nf\t1  2\t3\nv 1234567.8 -0.0000001 1.\n";
        // Alone in their window, and with the lines after them (where the
        // commonest shapes take their own way).
        let later = b"f 1 2 3\n".repeat(16);
        for after in [&b""[..], &later] {
            assert_eq!(fast_lines(taken, after), 12);
        }
        // A `v` with a colour, only where its 80 bytes are in the window.
        let colored = b"v 1 2 3 1 0 0.5\n";
        assert_eq!(fast_lines(colored, b""), 0);
        assert_eq!(fast_lines(colored, &later), 1);
        let left =
            b"v +1 2 3\nv 1e3 2 3\nv 1 2 3 # c\nv 1 2 3 1 0\nv 1 2 3 1 0 0 0\nv 12345678 0 0\nv 0.12345678 0 0\n\
            v 1 2\nvn 1 2\nvt 1\nf -1 2 3\nf 1 2\nf 1 2 9\nf 1 2 4\nf 4 1 2 3\nf 1/ 2 3\nf 1/1/ 2 3\nf 0 1 2\n\
            f 1//2 2//1 3//1\nf 1/2 2/1 3/1\nf 1 2 3 4 5 6 7 8 9\nf 1/2/1 2/1/1 3/1/1\n\
            f 1/1/2 2/1/1 3/1/1\nf 1/1/1 4/1/1 3/1/1\nvx 1 2 3\n v 1 2 3\nv 1 2 3";
        for after in [&b""[..], &later] {
            assert_eq!(fast_lines(left, after), 0);
        }
    }
}
