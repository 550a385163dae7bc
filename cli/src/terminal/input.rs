//! What the terminal sends: keys, and the answers to the queries rastty
//! makes (cursor position reports, mode reports, status reports), parsed
//! from the raw bytes of the tty.
//!
//! rastty reads the tty itself rather than through crossterm: crossterm's
//! `/dev/tty` source never reads on a zero timeout (a loop that is late
//! polls with zero and so never sees a key), and it offers no way to read
//! the answer to a query within a deadline, which the glyph probe needs.
//! Only what `spin` uses is decoded; every other sequence is read whole and
//! reported as [`Key::Other`], so it can never be mistaken for a key.
//!
//! A lone ESC is ambiguous (the Esc key, or the start of a sequence still
//! arriving): [`Parser::feed`] keeps it pending, and [`Parser::flush`], called
//! when no byte followed within a few milliseconds, makes it the Esc key.

/// A key, as far as `spin` tells keys apart.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Key {
    /// A printable character.
    Char(char),
    /// A control character: Ctrl and a letter (lower case) or `\`.
    Ctrl(char),
    Esc,
    Enter,
    Up,
    Down,
    Left,
    Right,
    /// Anything else (function keys, Alt combinations…).
    Other,
}

/// A mouse button.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Button {
    Left,
    Middle,
    Right,
}

/// What the mouse did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MouseKind {
    /// A button went down.
    Press(Button),
    /// A button came up (the legacy encoding does not say which).
    Release,
    /// The pointer moved with a button held.
    Drag(Button),
    /// The wheel turned away from the user (`true`) or towards.
    Wheel(bool),
    /// The pointer moved with no button held (any-event tracking only).
    Move,
}

/// A mouse report: what happened, where (0-based cell), and whether Shift
/// was held.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mouse {
    pub kind: MouseKind,
    pub col: u16,
    pub row: u16,
    pub shift: bool,
}

impl Mouse {
    /// A report from its button byte (xterm's: the button in the low two
    /// bits, Shift 4, Meta 8, Control 16, motion 32, wheel 64), 1-based
    /// cell, and whether the SGR encoding said it was a release.
    fn decode(cb: u32, col: u32, row: u32, released: bool) -> Mouse {
        let button = match cb & 3 {
            0 => Some(Button::Left),
            1 => Some(Button::Middle),
            2 => Some(Button::Right),
            _ => None,
        };
        let kind = if cb & 64 != 0 {
            MouseKind::Wheel(cb & 1 == 0)
        } else if released {
            MouseKind::Release
        } else {
            match (button, cb & 32 != 0) {
                (Some(b), false) => MouseKind::Press(b),
                (Some(b), true) => MouseKind::Drag(b),
                (None, false) => MouseKind::Release,
                (None, true) => MouseKind::Move,
            }
        };
        let cell = |v: u32| v.saturating_sub(1).min(u32::from(u16::MAX)) as u16;
        Mouse {
            kind,
            col: cell(col),
            row: cell(row),
            shift: cb & 4 != 0,
        }
    }
}

/// One thing read from the terminal.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Input {
    Key(Key),
    /// A cursor position report (`CSI row ; col R`), 1-based.
    CursorPosition {
        row: u16,
        col: u16,
    },
    /// A DEC private mode report (`CSI ? mode ; value $ y`).
    ModeReport {
        mode: u16,
        value: u8,
    },
    /// A mouse report: SGR (`CSI < b ; x ; y M` or `m`, mode 1006) or, from
    /// a terminal without it, the legacy `CSI M b x y` (each byte 32 more
    /// than its value).
    Mouse(Mouse),
    /// The answer to a device status report (`CSI 0 n`): everything sent
    /// before the query has been processed.
    StatusOk,
    /// An answer on 24-bit colour: to DECRQSS of the SGR after setting
    /// colour 1;2;3 (`DCS 1 $ r … 38;2;1;2;3 … m ST` keeps it: `true`;
    /// mapped to a palette or refused: `false`), or to XTGETTCAP of `RGB`
    /// (`DCS 1 + r 524742 … ST`: `true`; `DCS 0 + r …`: `false`).
    RgbSupport(bool),
    /// The answer to a kitty graphics query (`APC G i=… ; OK ST`: the
    /// protocol is drawn; any other message: it is not).
    KittyGraphics(bool),
    /// Primary device attributes (`CSI ? … c`): whether they list 4,
    /// sixel graphics. Every terminal answers them, last of a batch.
    DeviceAttributes {
        sixel: bool,
    },
    /// XTSMGRAPHICS's answer on sixel colour registers (`CSI ? 1 ; 0 ; n
    /// S`): how many the terminal has.
    SixelRegisters(u16),
    /// The size of a cell (`CSI 6 ; h ; w t`) or of the text area (`CSI 4
    /// ; h ; w t`) in pixels.
    CellPixels {
        width: u16,
        height: u16,
    },
    WindowPixels {
        width: u16,
        height: u16,
    },
    /// The default background colour (OSC 11's answer, `rgb:RRRR/GGGG/BBBB`).
    Background(rastty::color::Rgb),
}

/// The longest escape sequence kept; longer ones are dropped whole.
const MAX_SEQUENCE: usize = 64;

/// Bytes to inputs, across reads (a sequence may be split between two).
#[derive(Clone, Debug, Default)]
pub struct Parser {
    pending: Vec<u8>,
}

impl Parser {
    pub fn new() -> Parser {
        Parser {
            pending: Vec::with_capacity(MAX_SEQUENCE),
        }
    }

    /// Whether bytes are waiting for more (a lone ESC, a partial sequence
    /// or character).
    pub fn is_pending(&self) -> bool {
        !self.pending.is_empty()
    }

    /// Parses `bytes`, appending what they complete to `out`.
    pub fn feed(&mut self, bytes: &[u8], out: &mut Vec<Input>) {
        for &b in bytes {
            self.pending.push(b);
            self.step(out);
            if self.pending.len() > MAX_SEQUENCE {
                self.pending.clear();
                out.push(Input::Key(Key::Other));
            }
        }
    }

    /// Nothing more came: a pending lone ESC is the Esc key, anything else
    /// pending is dropped as [`Key::Other`].
    pub fn flush(&mut self, out: &mut Vec<Input>) {
        match self.pending.as_slice() {
            [] => return,
            [0x1b] => out.push(Input::Key(Key::Esc)),
            _ => out.push(Input::Key(Key::Other)),
        }
        self.pending.clear();
    }

    /// Tries to complete an input from `self.pending`.
    fn step(&mut self, out: &mut Vec<Input>) {
        let p = self.pending.as_slice();
        let done = match p {
            [0x1b] => return,
            // The legacy mouse report: three raw bytes after `CSI M`.
            [0x1b, b'[', b'M', rest @ ..] => match rest {
                [b, x, y] => Input::Mouse(Mouse::decode(
                    u32::from(b.wrapping_sub(32)),
                    u32::from(x.wrapping_sub(32)),
                    u32::from(y.wrapping_sub(32)),
                    false,
                )),
                _ => return,
            },
            [0x1b, b'[', rest @ ..] => match rest.last() {
                Some(&f) if (0x40..=0x7e).contains(&f) => csi(&rest[..rest.len() - 1], f),
                _ => return,
            },
            // DCS … ST (or BEL): a terminal's answer to DECRQSS or
            // XTGETTCAP.
            [0x1b, b'P', rest @ ..] => {
                let body = match rest {
                    [body @ .., 0x1b, b'\\'] | [body @ .., 0x07] => body,
                    _ => return,
                };
                dcs(body)
            }
            // APC … ST: a kitty graphics answer.
            [0x1b, b'_', rest @ ..] => {
                let body = match rest {
                    [body @ .., 0x1b, b'\\'] => body,
                    _ => return,
                };
                match body {
                    [b'G', keys @ ..] => {
                        let msg = keys.splitn(2, |&b| b == b';').nth(1).unwrap_or(b"");
                        Input::KittyGraphics(msg == b"OK")
                    }
                    _ => Input::Key(Key::Other),
                }
            }
            // OSC … ST (or BEL): the answer to OSC 11.
            [0x1b, b']', rest @ ..] => {
                let body = match rest {
                    [body @ .., 0x1b, b'\\'] | [body @ .., 0x07] => body,
                    _ => return,
                };
                osc(body)
            }
            [0x1b, b'O'] => return,
            [0x1b, b'O', f] => match f {
                b'A' => Input::Key(Key::Up),
                b'B' => Input::Key(Key::Down),
                b'C' => Input::Key(Key::Right),
                b'D' => Input::Key(Key::Left),
                _ => Input::Key(Key::Other),
            },
            // ESC ESC: the first is the Esc key; the second may start a
            // sequence.
            [0x1b, 0x1b] => {
                out.push(Input::Key(Key::Esc));
                self.pending.remove(0);
                return;
            }
            // ESC and a character: Alt and that key.
            [0x1b, _, ..] => match std::str::from_utf8(&p[1..]) {
                Ok(_) => Input::Key(Key::Other),
                Err(e) if e.error_len().is_none() => return,
                Err(_) => Input::Key(Key::Other),
            },
            [b] if *b < 0x80 => Input::Key(control_or_char(*b)),
            _ => match std::str::from_utf8(p) {
                Ok(s) => Input::Key(s.chars().next().map_or(Key::Other, Key::Char)),
                Err(e) if e.error_len().is_none() => return,
                Err(_) => Input::Key(Key::Other),
            },
        };
        out.push(done);
        self.pending.clear();
    }
}

fn control_or_char(b: u8) -> Key {
    match b {
        b'\r' | b'\n' => Key::Enter,
        0x01..=0x1a => Key::Ctrl((b'a' + b - 1) as char),
        0x1c => Key::Ctrl('\\'),
        0x20..=0x7e => Key::Char(b as char),
        _ => Key::Other,
    }
}

/// An OSC answer's body: `11;rgb:R/G/B`, each 1 to 4 hex digits.
fn osc(body: &[u8]) -> Input {
    let colour = std::str::from_utf8(body).ok().and_then(|s| {
        let spec = s.strip_prefix("11;rgb:")?;
        let mut parts = spec.split('/').map(|h| {
            let v = u32::from_str_radix(h, 16).ok()?;
            let max = (1u32 << (4 * h.len().clamp(1, 4))) - 1;
            Some(((v * 255 + max / 2) / max) as u8)
        });
        let (r, g, b) = (parts.next()??, parts.next()??, parts.next()??);
        parts
            .next()
            .is_none()
            .then_some(rastty::color::Rgb([r, g, b]))
    });
    match colour {
        Some(c) => Input::Background(c),
        None => Input::Key(Key::Other),
    }
}

/// A DCS answer's body (between `ESC P` and ST).
fn dcs(body: &[u8]) -> Input {
    let contains = |needle: &[u8]| body.windows(needle.len()).any(|w| w == needle);
    match body {
        [b'1', b'$', b'r', sgr @ ..] => {
            let has = |n: &[u8]| sgr.windows(n.len()).any(|w| w == n);
            Input::RgbSupport(has(b"2;1;2;3") || has(b"2:1:2:3") || has(b"2::1:2:3"))
        }
        [b'0', b'$', b'r', ..] => Input::RgbSupport(false),
        [b'1', b'+', b'r', ..] if contains(b"524742") || contains(b"5463") => {
            Input::RgbSupport(true)
        }
        [b'0', b'+', b'r', ..] => Input::RgbSupport(false),
        _ => Input::Key(Key::Other),
    }
}

/// A CSI sequence: parameter and intermediate bytes, and the final byte.
fn csi(body: &[u8], f: u8) -> Input {
    if let [b'<', params @ ..] = body {
        return sgr_mouse(params, f);
    }
    let private = body.first() == Some(&b'?');
    let (params, inter) = {
        let digits = if private { &body[1..] } else { body };
        let end = digits
            .iter()
            .position(|b| !(b.is_ascii_digit() || *b == b';'))
            .unwrap_or(digits.len());
        (&digits[..end], &digits[end..])
    };
    // Device attributes list any number of features.
    if (f, private, inter) == (b'c', true, &[][..]) {
        return Input::DeviceAttributes {
            sixel: params.split(|&b| b == b';').skip(1).any(|p| p == b"4"),
        };
    }
    let mut nums = [0u32; 3];
    let mut n = 0;
    for part in params.split(|&b| b == b';').take(3) {
        nums[n] = part.iter().fold(0u32, |v, d| {
            v.saturating_mul(10).saturating_add((d - b'0') as u32)
        });
        n += 1;
    }
    let clamp = |v: u32| v.min(u16::MAX as u32) as u16;
    match (f, private, inter) {
        (b'A', false, []) => Input::Key(Key::Up),
        (b'B', false, []) => Input::Key(Key::Down),
        (b'C', false, []) => Input::Key(Key::Right),
        (b'D', false, []) => Input::Key(Key::Left),
        (b'R', false, []) if n == 2 => Input::CursorPosition {
            row: clamp(nums[0]),
            col: clamp(nums[1]),
        },
        (b'n', false, []) if n == 1 && nums[0] == 0 => Input::StatusOk,
        (b'y', true, b"$") if n == 2 => Input::ModeReport {
            mode: clamp(nums[0]),
            value: nums[1].min(255) as u8,
        },
        (b'S', true, []) if n == 3 && nums[0] == 1 && nums[1] == 0 => {
            Input::SixelRegisters(clamp(nums[2]))
        }
        (b't', false, []) if n == 3 && nums[0] == 6 => Input::CellPixels {
            width: clamp(nums[2]),
            height: clamp(nums[1]),
        },
        (b't', false, []) if n == 3 && nums[0] == 4 => Input::WindowPixels {
            width: clamp(nums[2]),
            height: clamp(nums[1]),
        },
        _ => Input::Key(Key::Other),
    }
}

/// An SGR mouse report's parameters (`b;x;y`) and final byte (`M` press
/// or motion, `m` release).
fn sgr_mouse(params: &[u8], f: u8) -> Input {
    let mut nums = [0u32; 3];
    let mut parts = params.split(|&b| b == b';');
    for n in &mut nums {
        let Some(part) = parts.next() else {
            return Input::Key(Key::Other);
        };
        if part.is_empty() || !part.iter().all(u8::is_ascii_digit) {
            return Input::Key(Key::Other);
        }
        *n = part.iter().fold(0u32, |v, d| {
            v.saturating_mul(10).saturating_add(u32::from(d - b'0'))
        });
    }
    match (f, parts.next()) {
        (b'M' | b'm', None) => Input::Mouse(Mouse::decode(nums[0], nums[1], nums[2], f == b'm')),
        _ => Input::Key(Key::Other),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(chunks: &[&[u8]]) -> Vec<Input> {
        let mut p = Parser::new();
        let mut out = Vec::new();
        for c in chunks {
            p.feed(c, &mut out);
        }
        p.flush(&mut out);
        out
    }

    #[test]
    fn answers_on_24_bit_colour_are_read() {
        assert_eq!(
            parse(&[b"\x1bP1$r0;38;2;1;2;3m\x1b\\"]),
            [Input::RgbSupport(true)]
        );
        assert_eq!(
            parse(&[b"\x1bP1$r38:2::1:2:3m\x1b", b"\\"]),
            [Input::RgbSupport(true)]
        );
        assert_eq!(
            parse(&[b"\x1bP1$r0;38;5;16m\x1b\\"]),
            [Input::RgbSupport(false)]
        );
        assert_eq!(parse(&[b"\x1bP0$r\x1b\\"]), [Input::RgbSupport(false)]);
        assert_eq!(
            parse(&[b"\x1bP1+r524742=382F382F38\x07"]),
            [Input::RgbSupport(true)]
        );
        assert_eq!(
            parse(&[b"\x1bP0+r524742\x1b\\"]),
            [Input::RgbSupport(false)]
        );
    }

    fn keys(k: &[Key]) -> Vec<Input> {
        k.iter().map(|&k| Input::Key(k)).collect()
    }

    #[test]
    fn keys_and_controls() {
        assert_eq!(
            parse(&[b"q \x03\x0c\x1a\x1c\r"]),
            keys(&[
                Key::Char('q'),
                Key::Char(' '),
                Key::Ctrl('c'),
                Key::Ctrl('l'),
                Key::Ctrl('z'),
                Key::Ctrl('\\'),
                Key::Enter
            ])
        );
        assert_eq!(parse(&["é".as_bytes()]), keys(&[Key::Char('é')]));
    }

    #[test]
    fn arrows_in_both_forms_and_split_across_reads() {
        assert_eq!(
            parse(&[b"\x1b[A\x1bOB\x1b[1;5C", b"\x1b", b"[", b"D"]),
            keys(&[Key::Up, Key::Down, Key::Right, Key::Left])
        );
    }

    #[test]
    fn a_lone_esc_waits_for_flush() {
        let mut p = Parser::new();
        let mut out = Vec::new();
        p.feed(b"\x1b", &mut out);
        assert!(out.is_empty() && p.is_pending());
        p.flush(&mut out);
        assert_eq!(out, keys(&[Key::Esc]));
        assert_eq!(parse(&[b"\x1b\x1b[A"]), keys(&[Key::Esc, Key::Up]));
    }

    #[test]
    fn reports_are_not_keys() {
        assert_eq!(
            parse(&[b"\x1b[12;41R\x1b[?2026;2$y\x1b[0nq"]),
            vec![
                Input::CursorPosition { row: 12, col: 41 },
                Input::ModeReport {
                    mode: 2026,
                    value: 2
                },
                Input::StatusOk,
                Input::Key(Key::Char('q')),
            ]
        );
        // Function keys and bracketed paste markers are read whole and
        // never become keys that do something.
        assert_eq!(
            parse(&[b"\x1b[15~\x1b[200~"]),
            keys(&[Key::Other, Key::Other])
        );
    }

    fn mouse(kind: MouseKind, col: u16, row: u16, shift: bool) -> Input {
        Input::Mouse(Mouse {
            kind,
            col,
            row,
            shift,
        })
    }

    #[test]
    fn sgr_mouse_reports_in_any_split() {
        use MouseKind::*;
        let bytes =
            b"\x1b[<0;3;4M\x1b[<32;5;4M\x1b[<0;5;4m\x1b[<6;1;1M\x1b[<64;10;2M\x1b[<65;10;2Mq";
        let want = vec![
            mouse(Press(Button::Left), 2, 3, false),
            mouse(Drag(Button::Left), 4, 3, false),
            mouse(Release, 4, 3, false),
            mouse(Press(Button::Right), 0, 0, true),
            mouse(Wheel(true), 9, 1, false),
            mouse(Wheel(false), 9, 1, false),
            Input::Key(Key::Char('q')),
        ];
        assert_eq!(parse(&[bytes]), want);
        for cut in 1..bytes.len() {
            assert_eq!(parse(&[&bytes[..cut], &bytes[cut..]]), want, "cut at {cut}");
        }
        // Malformed ones are not keys and do not eat what follows.
        assert_eq!(
            parse(&[b"\x1b[<0;3M\x1b[<0;3;4;5M\x1b[<;1;1Mq"]),
            keys(&[Key::Other, Key::Other, Key::Other, Key::Char('q')])
        );
    }

    #[test]
    fn legacy_mouse_reports_are_read_where_sgr_is_not_given() {
        use MouseKind::*;
        // Press left at column 3, row 4; drag right to 5; release; shift
        // and right button; wheel up.
        let bytes = b"\x1b[M #$\x1b[M@%$\x1b[M#%$\x1b[M&!!\x1b[M`**q";
        assert_eq!(
            parse(&[bytes]),
            vec![
                mouse(Press(Button::Left), 2, 3, false),
                mouse(Drag(Button::Left), 4, 3, false),
                mouse(Release, 4, 3, false),
                mouse(Press(Button::Right), 0, 0, true),
                mouse(Wheel(true), 9, 9, false),
                Input::Key(Key::Char('q')),
            ]
        );
    }

    #[test]
    fn endless_sequences_are_cut() {
        let mut long = b"\x1b[".to_vec();
        long.extend(std::iter::repeat_n(b'1', 200));
        // The first 64 bytes are dropped as one unknown input; the rest are
        // plain digits, and the parser is back in step for the `q`.
        let out = parse(&[&long, b"q"]);
        assert_eq!(out[0], Input::Key(Key::Other));
        assert_eq!(out.last(), Some(&Input::Key(Key::Char('q'))));
        assert!(out.len() < 200);
    }
}
