//! Reading text formats (OBJ, MTL, ASCII STL) line by line, through a
//! buffer of 64 KiB, never the whole file: a line longer than [`MAX_LINE`]
//! is an error rather than an allocation sized by the file; and the words
//! and numbers of a line, with the column of each for errors.

use std::io::Read;

use super::file::human;

/// The longest line a text format may have: 64 MiB (a face of a few
/// million corners).
pub const MAX_LINE: usize = 64 << 20;

/// A text file's lines, one at a time, each without its line ending; a
/// UTF-8 byte order mark at the start is skipped. A line is handed out
/// straight from a 64 KiB buffer (its end found with SIMD `memchr`); the
/// buffer grows only for a line longer than itself, up to [`MAX_LINE`].
/// A reader with a faster way to read a line may take it straight from
/// [`Lines::window`] and say so with [`Lines::skip`].
pub struct Lines<R> {
    reader: R,
    buf: Vec<u8>,
    /// The bytes read and not yet handed out: `buf[start..end]`, followed
    /// by [`SLACK`] NUL bytes.
    start: usize,
    end: usize,
    /// Where the search for the next line ending resumes.
    scanned: usize,
    eof: bool,
    /// The number of the last line (from 1).
    pub number: usize,
}

impl<R: Read> Lines<R> {
    pub fn new(reader: R) -> Lines<R> {
        Lines {
            reader,
            buf: vec![0; (64 << 10) + SLACK],
            start: 0,
            end: 0,
            scanned: 0,
            eof: false,
            number: 0,
        }
    }

    /// The next line and its number; `Ok(None)` at the end. An error is an
    /// I/O error or a line longer than [`MAX_LINE`]: the line's number and
    /// a message, for the caller to place.
    #[allow(clippy::type_complexity)]
    pub fn next_line(&mut self) -> std::result::Result<Option<(usize, &[u8])>, (usize, String)> {
        let number = self.number + 1;
        let (from, to) = loop {
            let unread = &self.buf[self.scanned..self.end];
            if let Some(k) = memchr::memchr(b'\n', unread) {
                let line = (self.start, self.scanned + k);
                self.start = line.1 + 1;
                self.scanned = self.start;
                break line;
            }
            if self.eof {
                if self.start == self.end {
                    return Ok(None);
                }
                let line = (self.start, self.end);
                self.start = self.end;
                self.scanned = self.end;
                break line;
            }
            self.fill().map_err(|e| (number, e))?;
        };
        self.number = number;
        let mut line = &self.buf[from..to];
        if number == 1 {
            line = line.strip_prefix(b"\xef\xbb\xbf").unwrap_or(line);
        }
        if let [rest @ .., b'\r'] = line {
            line = rest;
        }
        Ok(Some((number, line)))
    }

    /// The bytes not yet handed out, then [`SLACK`] NUL bytes: a line
    /// there that ends in `\n` is whole. Empty of lines until
    /// [`Lines::next_line`] has read the first.
    pub fn window(&self) -> &[u8] {
        &self.buf[self.start..self.end + SLACK]
    }

    /// Hands out the next `len` bytes of [`Lines::window`], `count` lines
    /// with their `\n`s, as read by the caller.
    pub fn skip_lines(&mut self, len: usize, count: usize) {
        debug_assert!(
            count == 0 || (self.start + len <= self.end && self.buf[self.start + len - 1] == b'\n')
        );
        self.start += len;
        self.scanned = self.start;
        self.number += count;
    }

    /// Reads more: the unread bytes moved to the front, the buffer doubled
    /// if they fill it, the slack after them cleared.
    fn fill(&mut self) -> std::result::Result<(), String> {
        let unread = self.end - self.start;
        self.buf.copy_within(self.start..self.end, 0);
        self.scanned -= self.start;
        (self.start, self.end) = (0, unread);
        if unread == self.buf.len() - SLACK {
            if unread > MAX_LINE {
                return Err(format!(
                    "the line is longer than {}",
                    human(MAX_LINE as u64)
                ));
            }
            self.buf.resize(unread * 2 + SLACK, 0);
        }
        let room = self.buf.len() - SLACK;
        let read = loop {
            match self.reader.read(&mut self.buf[self.end..room]) {
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
                read => break read,
            }
        };
        match read {
            Ok(0) => self.eof = true,
            Ok(n) => self.end += n,
            Err(e) => return Err(e.to_string()),
        }
        self.buf[self.end..self.end + SLACK].fill(0);
        Ok(())
    }
}

/// The NUL bytes after the unread ones in [`Lines`]' buffer, so that a
/// reader may look 8 bytes past any byte it has read (a NUL ends every
/// item).
pub const SLACK: usize = 16;

/// Whether `b` separates words: every control character and the space
/// (tabs, a stray carriage return), in one compare.
#[inline]
fn blank(b: u8) -> bool {
    b <= b' '
}

/// A cursor over one line: its words, numbers and indices, taken in one
/// pass over the bytes, up to a `#` comment. Each item comes with the byte
/// offset where it starts (for [`column()`], when an error needs it).
#[derive(Clone, Copy)]
pub struct Cursor<'l> {
    line: &'l [u8],
    pos: usize,
}

impl<'l> Cursor<'l> {
    pub fn new(line: &'l [u8]) -> Cursor<'l> {
        Cursor { line, pos: 0 }
    }

    /// The line.
    pub fn line(&self) -> &'l [u8] {
        self.line
    }

    /// Skips blanks; whether an item follows (not the end, not a comment).
    #[inline]
    pub fn more(&mut self) -> bool {
        while self.pos < self.line.len() && blank(self.line[self.pos]) {
            self.pos += 1;
        }
        self.pos < self.line.len() && self.line[self.pos] != b'#'
    }

    /// Whether the byte at `i` ends an item.
    #[inline]
    fn ends(&self, i: usize) -> bool {
        i == self.line.len() || blank(self.line[i]) || self.line[i] == b'#'
    }

    /// The next word and where it starts.
    pub fn word(&mut self) -> Option<(&'l [u8], usize)> {
        if !self.more() {
            return None;
        }
        let start = self.pos;
        while !self.ends(self.pos) {
            self.pos += 1;
        }
        Some((&self.line[start..self.pos], start))
    }

    /// The rest of the line, trimmed, up to a comment: a name that may hold
    /// spaces. Empty at the end.
    pub fn rest(&mut self) -> &'l [u8] {
        if !self.more() {
            return b"";
        }
        let tail = &self.line[self.pos..];
        let end = memchr::memchr(b'#', tail).unwrap_or(tail.len());
        self.pos = self.line.len();
        tail[..end].trim_ascii_end()
    }

    /// The next number: `None` at the end, `Some(Err((word, offset)))` for
    /// a word that is not one. The common short decimals (`-0.008366`) are
    /// read as they are scanned, eight digits at a time, exactly (Clinger's
    /// fast path: digits below 2^24 and at most 10 decimals make an exact
    /// integer and an exact power of ten, so one division rounds
    /// correctly); anything else (exponents, long mantissas, `inf`) goes
    /// to `fast-float2`, also correctly rounded.
    #[inline]
    pub fn number(&mut self) -> Option<std::result::Result<f32, (&'l [u8], usize)>> {
        if !self.more() {
            return None;
        }
        let (s, start) = (self.line, self.pos);
        let mut i = start;
        let neg = s[i] == b'-';
        i += (neg || s[i] == b'+') as usize;
        let (mut m, whole) = digits(&s[i..]);
        i += whole;
        let mut decimals = 0;
        if i < s.len() && s[i] == b'.' {
            let (f, n) = digits(&s[i + 1..]);
            decimals = n;
            i += 1 + n;
            // Exact while it matters: below 2^24 with at most 10 decimals.
            m = if n <= 10 {
                m.saturating_mul(POW10_INT[n]).saturating_add(f)
            } else {
                u64::MAX
            };
        }
        if self.ends(i) && whole + decimals > 0 && decimals <= 10 && m < 1 << 24 {
            self.pos = i;
            return Some(Ok(exact_decimal(m, decimals, neg)));
        }
        self.slow_number()
    }

    /// [`Cursor::number`] for what is not a short decimal.
    #[cold]
    #[inline(never)]
    fn slow_number(&mut self) -> Option<std::result::Result<f32, (&'l [u8], usize)>> {
        let (w, at) = self.word()?;
        Some(fast_float2::parse::<f32, _>(w).map_err(|_| (w, at)))
    }

    /// The next face corner `v[/[vt][/vn]]` as up to three signed indices
    /// (`None`: the part is absent): `None` at the end,
    /// `Some(Err((word, offset)))` when the word is not one.
    #[inline]
    #[allow(clippy::type_complexity)]
    pub fn corner(&mut self) -> Option<std::result::Result<[Option<i64>; 3], (&'l [u8], usize)>> {
        if !self.more() {
            return None;
        }
        let (s, start) = (self.line, self.pos);
        let mut i = start;
        let mut out = [None; 3];
        let mut ok = true;
        for (k, slot) in out.iter_mut().enumerate() {
            let neg = i < s.len() && s[i] == b'-';
            i += (neg || (i < s.len() && s[i] == b'+')) as usize;
            let (v, n) = digits(&s[i..]);
            i += n;
            if n > 18 {
                ok = false;
                break;
            } else if n > 0 {
                *slot = Some(if neg { -(v as i64) } else { v as i64 });
            } else if neg || k == 0 {
                ok = false;
                break;
            }
            if k == 2 || i == s.len() || s[i] != b'/' {
                break;
            }
            i += 1;
        }
        if ok && self.ends(i) {
            self.pos = i;
            return Some(Ok(out));
        }
        let (w, at) = self.word()?;
        Some(Err((w, at)))
    }
}

/// Powers of ten exact in f32 (5^10 < 2^24).
const POW10: [f32; 11] = [1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10];
/// The same powers as integers.
pub const POW10_INT: [u64; 11] = [
    1,
    10,
    100,
    1_000,
    10_000,
    100_000,
    1_000_000,
    10_000_000,
    100_000_000,
    1_000_000_000,
    10_000_000_000,
];

/// The number `±m / 10^decimals`, correctly rounded when `m < 2^24` and
/// `decimals <= 10` (Clinger's fast path: an exact integer divided by an
/// exact power of ten, rounded once).
#[inline]
pub fn exact_decimal(m: u64, decimals: usize, neg: bool) -> f32 {
    debug_assert!(m < 1 << 24 && decimals <= 10);
    let v = m as f32 / POW10[decimals];
    if neg { -v } else { v }
}

/// The decimal digits `s` starts with: their value (saturated at
/// `u64::MAX` past 19 digits) and how many there are. Eight bytes at a time
/// where eight are there (Lemire's SWAR method: which bytes are digits
/// found by two additions, their value by three multiplications), byte by
/// byte in a line's last few bytes.
#[inline]
fn digits(s: &[u8]) -> (u64, usize) {
    let Some(chunk) = s.first_chunk::<8>() else {
        let mut value = 0;
        for (k, &b) in s.iter().enumerate() {
            let d = b.wrapping_sub(b'0');
            if d > 9 {
                return (value, k);
            }
            value = value * 10 + d as u64;
        }
        return (value, s.len());
    };
    match short_digits(*chunk) {
        Some(value) => value,
        None => many_digits(s),
    }
}

/// The decimal digits `chunk` starts with, their value and how many there
/// are, when a byte of it is not a digit (`None` when all eight are).
#[inline]
pub fn short_digits(chunk: [u8; 8]) -> Option<(u64, usize)> {
    let (t, not_digit) = digit_bytes(chunk);
    if not_digit == 0 {
        return None;
    }
    let k = (not_digit.trailing_zeros() / 8) as usize;
    if k == 0 {
        return Some((0, 0));
    }
    Some((digits_value(t, k), k))
}

/// `chunk`'s bytes less `'0'` (a digit's value in each digit's byte), and
/// the top bit of each byte that is not a digit: exact for every byte up
/// to the first of `0x80` or more (only such a byte carries into the next),
/// so for all eight where the text is ASCII.
#[inline]
pub fn digit_bytes(chunk: [u8; 8]) -> (u64, u64) {
    let t = u64::from_le_bytes(chunk) ^ 0x3030_3030_3030_3030;
    // A byte is not a digit when its top bit is set, or when it is 10 or
    // more (then adding 0x76 sets it).
    let not_digit = (t | t.wrapping_add(0x7676_7676_7676_7676)) & 0x8080_8080_8080_8080;
    (t, not_digit)
}

/// The value of the first `k` (1 to 8) bytes of `t`, each a digit's value
/// (Lemire's SWAR: three multiplications).
#[inline]
pub fn digits_value(t: u64, k: usize) -> u64 {
    debug_assert!((1..=8).contains(&k));
    // The k digits, as the low-order end of an 8-digit number.
    let x = t << (8 * (8 - k));
    let x = (x.wrapping_mul(10) + (x >> 8)) & 0x00ff_00ff_00ff_00ff;
    let x = (x.wrapping_mul(100) + (x >> 16)) & 0x0000_ffff_0000_ffff;
    (x.wrapping_mul(10000) + (x >> 32)) & 0xffff_ffff
}

/// [`digits`] for eight or more.
#[cold]
#[inline(never)]
fn many_digits(s: &[u8]) -> (u64, usize) {
    let k = s.iter().take_while(|b| b.is_ascii_digit()).count();
    let value = s[..k].iter().try_fold(0u64, |v, &b| {
        v.checked_mul(10)?.checked_add((b - b'0') as u64)
    });
    (value.unwrap_or(u64::MAX), k)
}

/// The column (from 1, in characters) of byte `offset` of `line`.
pub fn column(line: &[u8], offset: usize) -> usize {
    let before = &line[..offset.min(line.len())];
    if before.is_ascii() {
        offset + 1
    } else {
        String::from_utf8_lossy(before).chars().count() + 1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_across_two_reads_is_whole() {
        // A reader that hands out 3 bytes at a time.
        struct Trickle<'a>(&'a [u8]);
        impl Read for Trickle<'_> {
            fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
                let n = self.0.len().min(3).min(buf.len());
                buf[..n].copy_from_slice(&self.0[..n]);
                self.0 = &self.0[n..];
                Ok(n)
            }
        }
        let mut l = Lines::new(Trickle(b"v 1 2 3\nf 1 2 3\n"));
        assert_eq!(l.next_line().unwrap(), Some((1, &b"v 1 2 3"[..])));
        assert_eq!(l.next_line().unwrap(), Some((2, &b"f 1 2 3"[..])));
        assert_eq!(l.next_line().unwrap(), None);
    }

    #[test]
    fn lines_drop_endings_and_a_bom() {
        let mut l = Lines::new(&b"\xef\xbb\xbfv 1\r\n\nf 1 2 3"[..]);
        assert_eq!(l.next_line().unwrap(), Some((1, &b"v 1"[..])));
        assert_eq!(l.next_line().unwrap(), Some((2, &b""[..])));
        assert_eq!(l.next_line().unwrap(), Some((3, &b"f 1 2 3"[..])));
        assert_eq!(l.next_line().unwrap(), None);
    }

    #[test]
    fn a_cursor_stops_at_a_comment_and_knows_its_columns() {
        let mut c = Cursor::new(b"f\t1 2  3# tri");
        let mut w = Vec::new();
        while let Some(word) = c.word() {
            w.push(word);
        }
        assert_eq!(
            w,
            vec![
                (&b"f"[..], 0),
                (&b"1"[..], 2),
                (&b"2"[..], 4),
                (&b"3"[..], 7)
            ]
        );
        assert_eq!(column("é x".as_bytes(), 3), 3);
        let mut c = Cursor::new(b"v -0.5 1e3 +2. .25 x7 # c");
        let n: Vec<_> = std::iter::from_fn(|| c.number()).collect();
        assert_eq!(
            n,
            vec![
                Err((&b"v"[..], 0)),
                Ok(-0.5),
                Ok(1000.0),
                Ok(2.0),
                Ok(0.25),
                Err((&b"x7"[..], 19))
            ]
        );
        let mut c = Cursor::new(b"5/1/2 -1//3 7/8 4 1/2/3/4 /2");
        let k: Vec<_> = std::iter::from_fn(|| c.corner()).collect();
        assert_eq!(
            k,
            vec![
                Ok([Some(5), Some(1), Some(2)]),
                Ok([Some(-1), None, Some(3)]),
                Ok([Some(7), Some(8), None]),
                Ok([Some(4), None, None]),
                Err((&b"1/2/3/4"[..], 18)),
                Err((&b"/2"[..], 26)),
            ]
        );
    }

    #[test]
    fn digits_are_read_eight_at_a_time_exactly() {
        for s in [
            "",
            "x",
            "0",
            "7/",
            "12345678",
            "123456789 ",
            "00000000000000000001",
            "9999999999999999999",
            "18446744073709551615",
            "99999999999999999999",
            "1:",
            "5/",
            "42.5",
        ] {
            let n = s.bytes().take_while(u8::is_ascii_digit).count();
            let want = s[..n]
                .parse::<u64>()
                .unwrap_or(if n > 0 { u64::MAX } else { 0 });
            assert_eq!(digits(s.as_bytes()), (want, n), "{s:?}");
        }
    }
}
