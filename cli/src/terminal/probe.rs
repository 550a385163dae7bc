//! Asking the terminal what it draws, before drawing with it.
//!
//! Each family of glyphs a mode needs is written at the top-left corner and
//! the cursor position read back (DSR 6, answered by a CPR), all in one
//! write; the library's [`GlyphSupport`] reads the answers (why, and the
//! fallbacks, are in its module).
//!
//! The same round trip asks whether synchronized output (DEC mode 2026) is
//! supported (DECRQM) and whether 24-bit colour is drawn (a colour set,
//! then DECRQSS of the SGR: a terminal that keeps 38;2;1;2;3 has it; and
//! XTGETTCAP `RGB`): `COLORTERM`, which says so in the environment, does
//! not survive tmux or ssh, but the queries reach the real terminal over
//! ssh. It ends with a device status report (DSR 5), which
//! every terminal that answers anything answers last: once it is in, no
//! other answer is coming, so a terminal that ignores DECRQM costs no
//! waiting. A terminal that answers nothing (a pipe, a multiplexer that
//! swallows queries) costs the deadline, [`DEADLINE`], and nothing more:
//! every family is then taken as usable, as without the probe. The
//! waiting is [`listen`]'s, over an [`Answers`] that brings the clock
//! with the bytes, so that tests run it on a fake clock.

use std::io;
use std::time::Duration;
#[cfg(unix)]
use std::time::Instant;

#[cfg(unix)]
use super::Tty;
use super::input::{Input, Parser};
use rastty::{GlyphFamily, GlyphMode, GlyphSupport};

/// The longest the probe waits for answers, in total, from a terminal
/// that has answered nothing.
pub const DEADLINE: Duration = Duration::from_millis(150);

/// The longest it waits for the last answer from a terminal that has
/// begun to answer (a terminal just opened, or over a slow link, may take
/// longer than [`DEADLINE`] to answer every query).
pub const ANSWERING: Duration = Duration::from_millis(1000);

/// What the terminal said it can do; `None` where it did not answer.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Capabilities {
    /// Which glyph families it draws one cell wide.
    pub glyphs: GlyphSupport,
    /// Whether synchronized output (mode 2026) is recognised.
    pub sync: Option<bool>,
    /// Whether it answered the status report: it answers queries, so one
    /// can be sent after each frame to learn when the frame was drawn.
    pub answers_status: bool,
    /// How long the round trip took (with `answers_status`).
    pub round_trip: Option<Duration>,
    /// Whether it draws 24-bit colour, by its answers to DECRQSS and
    /// XTGETTCAP (any "yes" wins: a terminal may know one query and not
    /// the other).
    pub truecolor: Option<bool>,
    /// Whether it draws the kitty graphics protocol (it answered the
    /// query `a=q` with OK).
    pub kitty: Option<bool>,
    /// Whether its device attributes list sixel graphics.
    pub sixel: Option<bool>,
    /// Its sixel colour registers, by XTSMGRAPHICS.
    pub sixel_registers: Option<u16>,
    /// A cell's size in pixels (`CSI 16 t`), or the text area's (`CSI 14
    /// t`), across and down.
    pub cell_px: Option<[u16; 2]>,
    pub window_px: Option<[u16; 2]>,
    /// Its default background colour (OSC 11).
    pub background: Option<rastty::color::Rgb>,
}

impl Capabilities {
    /// Whether `mode`'s glyphs are drawn one cell wide (or not known not to
    /// be).
    pub fn usable(&self, mode: GlyphMode) -> bool {
        self.glyphs.usable(mode)
    }

    /// `mode`, or the best usable mode it falls back to.
    pub fn best(&self, mode: GlyphMode) -> GlyphMode {
        self.glyphs.best(mode)
    }

    /// Reads the answers to [`query`], in the order they came.
    pub fn from_answers(answers: &[Input]) -> Capabilities {
        let mut caps = Capabilities::default();
        let columns: Vec<u16> = answers
            .iter()
            .filter_map(|a| match *a {
                Input::CursorPosition { col, .. } => Some(col),
                _ => None,
            })
            .collect();
        caps.glyphs = GlyphSupport::from_columns(&columns);
        for a in answers {
            match *a {
                Input::ModeReport { mode: 2026, value } => {
                    caps.sync = Some(matches!(value, 1..=3));
                }
                Input::StatusOk => caps.answers_status = true,
                Input::RgbSupport(yes) => {
                    caps.truecolor = Some(yes || caps.truecolor == Some(true));
                }
                Input::KittyGraphics(ok) => caps.kitty = Some(ok),
                Input::Background(c) => caps.background = Some(c),
                Input::DeviceAttributes { sixel } => caps.sixel = Some(sixel),
                Input::SixelRegisters(n) => caps.sixel_registers = Some(n),
                Input::CellPixels { width, height } if width > 0 && height > 0 => {
                    caps.cell_px = Some([width, height]);
                }
                Input::WindowPixels { width, height } if width > 0 && height > 0 => {
                    caps.window_px = Some([width, height]);
                }
                _ => {}
            }
        }
        caps
    }
}

/// The bytes of the probe: each glyph at the top-left corner followed by a
/// position request, the synchronized-output query, the status request,
/// and the line cleared again.
pub fn query() -> Vec<u8> {
    let mut q = Vec::new();
    for f in GlyphFamily::ALL {
        for &c in f.probes() {
            q.extend_from_slice(b"\x1b[H");
            let mut utf8 = [0; 4];
            q.extend_from_slice(c.encode_utf8(&mut utf8).as_bytes());
            q.extend_from_slice(b"\x1b[6n");
        }
    }
    // 24-bit colour: set one, ask what SGR is now (DECRQSS), ask for the
    // `RGB` capability (XTGETTCAP), reset.
    q.extend_from_slice(b"\x1b[38;2;1;2;3m\x1bP$qm\x1b\\\x1bP+q524742\x1b\\\x1b[0m");
    // Pixels: the kitty graphics query (a 1×1 image checked, not kept),
    // sixel's colour registers (XTSMGRAPHICS), the cell's and the text
    // area's sizes in pixels, and the device attributes (4: sixel).
    // And the default background colour (OSC 11), which sixel frames paint
    // where nothing is drawn.
    q.extend_from_slice(b"\x1b_Gi=31,s=1,v=1,a=q,t=d,f=24;AAAA\x1b\\\x1b[?1;1;0S\x1b[16t\x1b[14t\x1b]11;?\x1b\\\x1b[c");
    q.extend_from_slice(b"\x1b[?2026$p\x1b[5n\x1b[H\x1b[2K");
    q
}

/// Where the probe's answers come from, and its clock: the terminal and
/// the wall clock, or a test's script and a fake clock.
pub trait Answers {
    /// The time since the probe was sent.
    fn elapsed(&self) -> Duration;
    /// Waits at most `left` for input and reads what came into `buf`:
    /// `Some(n)` bytes (0 when nothing came), `None` once the terminal is
    /// gone.
    fn read(&mut self, left: Duration, buf: &mut [u8]) -> io::Result<Option<usize>>;
}

/// The terminal's answers, timed by the wall clock from `start`.
#[cfg(unix)]
struct FromTty<'t> {
    tty: &'t Tty,
    start: Instant,
}

#[cfg(unix)]
impl Answers for FromTty<'_> {
    fn elapsed(&self) -> Duration {
        self.start.elapsed()
    }

    fn read(&mut self, left: Duration, buf: &mut [u8]) -> io::Result<Option<usize>> {
        super::wait_readable(self.tty.input_fd(), left)?;
        Ok(match self.tty.read(buf) {
            super::Read::Bytes(n) => Some(n),
            super::Read::Nothing => Some(0),
            super::Read::Gone => None,
        })
    }
}

/// Sends the probe and reads the answers until the status report comes
/// back or `deadline` passes. Keys read meanwhile are appended to `keys`,
/// for the caller to act on.
#[cfg(unix)]
pub fn probe(
    tty: &Tty,
    parser: &mut Parser,
    keys: &mut Vec<Input>,
    deadline: Duration,
) -> io::Result<Capabilities> {
    let start = Instant::now();
    tty.write_all(&query(), deadline)?;
    listen(&mut FromTty { tty, start }, parser, keys, deadline)
}

/// Reads answers from `from` until the status report comes (the last
/// answer of any terminal that answers) or `deadline` passes on its clock,
/// whichever is first; keys are appended to `keys`.
pub fn listen(
    from: &mut impl Answers,
    parser: &mut Parser,
    keys: &mut Vec<Input>,
    deadline: Duration,
) -> io::Result<Capabilities> {
    let mut answers = Vec::new();
    let mut inputs = Vec::new();
    let mut buf = [0u8; 256];
    let mut round_trip = None;
    'read: loop {
        let limit = if answers.is_empty() {
            deadline
        } else {
            deadline.max(ANSWERING)
        };
        let left = limit.saturating_sub(from.elapsed());
        if left.is_zero() {
            break;
        }
        match from.read(left, &mut buf)? {
            Some(n) => parser.feed(&buf[..n], &mut inputs),
            None => break,
        }
        for input in inputs.drain(..) {
            match input {
                Input::Key(_) => keys.push(input),
                Input::StatusOk => {
                    answers.push(input);
                    round_trip = Some(from.elapsed());
                    break 'read;
                }
                answer => answers.push(answer),
            }
        }
    }
    let mut caps = Capabilities::from_answers(&answers);
    caps.round_trip = round_trip;
    Ok(caps)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rastty::Choice;

    fn cpr(col: u16) -> Input {
        Input::CursorPosition { row: 1, col }
    }

    #[test]
    fn any_yes_on_24_bit_colour_wins() {
        let caps = |a: &[Input]| Capabilities::from_answers(a).truecolor;
        assert_eq!(caps(&[]), None);
        assert_eq!(caps(&[Input::RgbSupport(false)]), Some(false));
        assert_eq!(
            caps(&[Input::RgbSupport(true), Input::RgbSupport(false)]),
            Some(true)
        );
        assert_eq!(
            caps(&[Input::RgbSupport(false), Input::RgbSupport(true)]),
            Some(true)
        );
    }

    #[test]
    fn a_glyph_that_does_not_advance_one_cell_is_unusable() {
        // Quadrant, sextant, then the three octant probes, braille.
        let answers = [
            cpr(2),
            cpr(2),
            cpr(2),
            cpr(1),
            cpr(2),
            cpr(2),
            Input::StatusOk,
        ];
        let caps = Capabilities::from_answers(&answers);
        assert_eq!(
            caps.glyphs.families,
            [Some(true), Some(true), Some(false), Some(true)]
        );
        assert!(caps.answers_status);
        assert_eq!(caps.sync, None);
        assert!(!caps.usable(GlyphMode::Octant));
        assert_eq!(caps.best(GlyphMode::Octant), GlyphMode::Sextant);
        assert_eq!(caps.best(GlyphMode::Braille), GlyphMode::Braille);
        // Two cells wide is as bad as none.
        let mut wide = answers;
        wide[3] = cpr(3);
        assert_eq!(
            Capabilities::from_answers(&wide).best(GlyphMode::Octant),
            GlyphMode::Sextant
        );
    }

    #[test]
    fn falls_back_down_the_chain_and_silence_changes_nothing() {
        let caps = Capabilities {
            glyphs: GlyphSupport {
                families: [Some(true), Some(false), Some(false), Some(false)],
            },
            ..Capabilities::default()
        };
        assert_eq!(caps.best(GlyphMode::Octant), GlyphMode::Quadrant);
        assert_eq!(caps.best(GlyphMode::Braille), GlyphMode::Quadrant);
        let none = Capabilities {
            glyphs: GlyphSupport {
                families: [Some(false); 4],
            },
            ..Capabilities::default()
        };
        assert_eq!(none.best(GlyphMode::Octant), GlyphMode::Half);
        assert_eq!(none.best(GlyphMode::Ascii), GlyphMode::Ascii);
        let silent = Capabilities::from_answers(&[]);
        assert_eq!(silent.glyphs.families, [None; 4]);
        assert!(GlyphMode::ALL.iter().all(|&m| silent.best(m) == m));
    }

    #[test]
    fn the_sync_report_is_read() {
        let r = |value| Capabilities::from_answers(&[Input::ModeReport { mode: 2026, value }]).sync;
        assert_eq!(r(2), Some(true));
        assert_eq!(r(0), Some(false));
        assert_eq!(r(4), Some(false));
    }

    /// A terminal that sends `script`'s bytes, each at its time on a fake
    /// clock, which moves only by the waits the probe makes.
    struct Scripted {
        now: Duration,
        script: Vec<(Duration, &'static [u8])>,
        /// How many times the probe waited.
        waits: usize,
    }

    impl Answers for Scripted {
        fn elapsed(&self) -> Duration {
            self.now
        }

        fn read(&mut self, left: Duration, buf: &mut [u8]) -> io::Result<Option<usize>> {
            self.waits += 1;
            match self.script.first() {
                Some(&(at, bytes)) if at <= self.now + left => {
                    self.now = self.now.max(at);
                    self.script.remove(0);
                    buf[..bytes.len()].copy_from_slice(bytes);
                    Ok(Some(bytes.len()))
                }
                _ => {
                    self.now += left;
                    Ok(Some(0))
                }
            }
        }
    }

    fn listen_to(script: Vec<(Duration, &'static [u8])>) -> (Capabilities, Vec<Input>, Scripted) {
        let mut from = Scripted {
            now: Duration::ZERO,
            script,
            waits: 0,
        };
        let mut keys = Vec::new();
        let caps = listen(&mut from, &mut Parser::default(), &mut keys, DEADLINE).unwrap();
        (caps, keys, from)
    }

    const MS: Duration = Duration::from_millis(1);

    #[test]
    fn a_silent_terminal_costs_the_deadline_and_nothing_more() {
        let (caps, keys, from) = listen_to(Vec::new());
        // One wait, the whole deadline, then the probe gives up.
        assert_eq!((from.now, from.waits), (DEADLINE, 1));
        assert!(!caps.answers_status && caps.round_trip.is_none());
        assert_eq!(caps.glyphs.families, [None; 4]);
        assert!(keys.is_empty());
    }

    #[test]
    fn the_status_report_ends_the_wait_and_keys_meanwhile_are_kept() {
        let (caps, keys, from) = listen_to(vec![
            (10 * MS, b"q"),
            (25 * MS, b"\x1b[?2026;2$y"),
            (40 * MS, b"\x1b[0n"),
            (60 * MS, b"x"),
        ]);
        // Stopped at the report, 40 ms in: the key after it is not read.
        assert_eq!(from.now, 40 * MS);
        assert_eq!(from.script.len(), 1);
        assert_eq!(caps.round_trip, Some(40 * MS));
        assert!(caps.answers_status);
        assert_eq!(caps.sync, Some(true));
        assert_eq!(keys.len(), 1);
    }

    #[test]
    fn a_terminal_that_has_begun_to_answer_is_waited_for_up_to_a_second() {
        let late = DEADLINE + MS;
        let (caps, _, from) = listen_to(vec![(5 * MS, b"\x1b[1;2R"), (late, b"\x1b[0n")]);
        assert_eq!(from.now, late);
        assert!(caps.answers_status);
        let too_late = ANSWERING + MS;
        let (caps, _, from) = listen_to(vec![(5 * MS, b"\x1b[1;2R"), (too_late, b"\x1b[0n")]);
        assert_eq!(from.now, ANSWERING);
        assert_eq!(from.script.len(), 1);
        assert!(!caps.answers_status && caps.round_trip.is_none());
    }

    #[test]
    fn the_query_asks_once_per_probe_glyph() {
        let q = String::from_utf8(query()).unwrap();
        let glyphs: usize = GlyphFamily::ALL.iter().map(|f| f.probes().len()).sum();
        assert_eq!(q.matches("\x1b[6n").count(), glyphs);
        assert!(q.contains("\x1b[?2026$p") && q.contains("\x1b[5n"));
    }
}
