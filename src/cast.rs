//! Recordings: frames as an asciicast v2 file, which the asciinema player
//! and `asciinema play` replay.
//!
//! The file is JSON lines: a header (`version`, `width`, `height`,
//! `timestamp`, `env` with `TERM` and `SHELL`), then one event a line,
//! `[seconds, "o", text]` for output and `[seconds, "r", "COLSxROWS"]` for
//! a resize. serde_json writes them, so every escape and control byte is
//! encoded as JSON requires; the text is the encoder's bytes, which are
//! UTF-8.
//!
//! Times are the caller's: the live loop gives its pacing clock (a replay
//! runs at the speed shown, and frames the terminal was too late for are
//! missing from the file as they were from the screen), [`play`] gives
//! frame `k` at `k / fps` seconds, so a recording made without a terminal
//! is the same file every time (with `SOURCE_DATE_EPOCH` set, its header
//! too). Times are rounded to microseconds and never go back.

use std::io::{self, Write};
use std::time::{Duration, SystemTime, UNIX_EPOCH};

use serde::Serialize;

use crate::animate::{LiveStatus, Player, Spin};
use crate::encode::Encoder;
use crate::options::RenderOptions;
use crate::scene::Scene;

/// Hides the cursor: the first event starts with it, as the live loop's
/// screen does.
const HIDE_CURSOR: &str = "\x1b[?25l";

/// Shows the cursor: the last event ends with it.
const SHOW_CURSOR: &str = "\x1b[?25h";

/// The header line.
#[derive(Serialize)]
struct Header<'a> {
    version: u8,
    width: u16,
    height: u16,
    #[serde(skip_serializing_if = "Option::is_none")]
    timestamp: Option<u64>,
    env: Env<'a>,
}

#[derive(Serialize)]
#[serde(rename_all = "UPPERCASE")]
struct Env<'a> {
    term: &'a str,
    shell: &'a str,
}

/// The terminal a recording says it was made in.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Terminal {
    /// `TERM` (the player's emulation does not depend on it).
    pub term: String,
    /// `SHELL`.
    pub shell: String,
    /// When it was made, in seconds since 1970; `None` leaves it out.
    pub timestamp: Option<u64>,
}

impl Terminal {
    /// This process's: `TERM` and `SHELL` from the environment
    /// (`xterm-256color` and `/bin/sh` when unset), the time now, or
    /// `SOURCE_DATE_EPOCH` when it is set, for files that are the same
    /// every time.
    pub fn from_env() -> Terminal {
        let var = |k: &str, or: &str| std::env::var(k).unwrap_or_else(|_| or.to_string());
        let timestamp = match std::env::var("SOURCE_DATE_EPOCH") {
            Ok(s) => s.trim().parse().ok(),
            Err(_) => SystemTime::now()
                .duration_since(UNIX_EPOCH)
                .ok()
                .map(|d| d.as_secs()),
        };
        Terminal {
            term: var("TERM", "xterm-256color"),
            shell: var("SHELL", "/bin/sh"),
            timestamp,
        }
    }
}

/// Writes an asciicast v2 recording event by event.
#[derive(Debug)]
pub struct Recorder<W: Write + ?Sized> {
    /// Microseconds of the last event.
    last: u64,
    started: bool,
    /// The terminal's height, for [`Recorder::end`].
    rows: u16,
    line: Vec<u8>,
    out: W,
}

impl<W: Write> Recorder<W> {
    /// Starts a recording of a `width × height` terminal: writes the header.
    pub fn new(
        mut out: W,
        width: u16,
        height: u16,
        terminal: &Terminal,
    ) -> io::Result<Recorder<W>> {
        let header = Header {
            version: 2,
            width,
            height,
            timestamp: terminal.timestamp,
            env: Env {
                term: &terminal.term,
                shell: &terminal.shell,
            },
        };
        serde_json::to_writer(&mut out, &header)?;
        out.write_all(b"\n")?;
        Ok(Recorder {
            last: 0,
            started: false,
            rows: height,
            line: Vec::new(),
            out,
        })
    }

    /// Flushes and returns the writer.
    pub fn finish(mut self) -> io::Result<W> {
        self.out.flush()?;
        Ok(self.out)
    }
}

impl<W: Write + ?Sized> Recorder<W> {
    /// Flushes what is recorded so far to the writer.
    pub fn flush(&mut self) -> io::Result<()> {
        self.out.flush()
    }

    /// Records `data` written to the terminal at `at` from the start.
    /// Nothing is recorded for no data.
    pub fn output(&mut self, at: Duration, data: &[u8]) -> io::Result<()> {
        if data.is_empty() {
            return Ok(());
        }
        let text = String::from_utf8_lossy(data);
        if self.started {
            self.event(at, "o", &text)
        } else {
            self.started = true;
            self.event(at, "o", &format!("{HIDE_CURSOR}{text}"))
        }
    }

    /// Records that the terminal became `cols × rows` at `at`.
    pub fn resize(&mut self, at: Duration, cols: u16, rows: u16) -> io::Result<()> {
        self.rows = rows;
        self.event(at, "r", &format!("{cols}x{rows}"))
    }

    /// Ends the recording as a program ends on a terminal: colours reset,
    /// the cursor on a new line below the picture and shown again, so that
    /// a player (`asciinema play`) leaves a usable shell. At the last
    /// event's time; nothing for a recording of nothing.
    pub fn end(&mut self) -> io::Result<()> {
        if !self.started {
            return Ok(());
        }
        let at = Duration::from_micros(self.last);
        self.event(
            at,
            "o",
            &format!("\x1b[0m\x1b[{};1H\r\n{SHOW_CURSOR}", self.rows),
        )
    }

    fn event(&mut self, at: Duration, code: &str, data: &str) -> io::Result<()> {
        // Microseconds, never before the last event.
        let us = (at.as_micros().min(u128::from(u64::MAX)) as u64).max(self.last);
        self.last = us;
        let seconds = us as f64 / 1e6;
        self.line.clear();
        serde_json::to_writer(&mut self.line, &(seconds, code, data))?;
        self.line.push(b'\n');
        self.out.write_all(&self.line)
    }
}

/// Records frames `0..frames` of `spin` as [`crate::animate::play`] draws
/// them, frame `k` at `k / fps` seconds, into a `opts.cols × opts.rows`
/// recording: what `rastty spin --frames N --record FILE` writes when
/// stdout is not a terminal. Frames that change nothing add no event.
#[allow(clippy::too_many_arguments)]
pub fn play<W: Write>(
    scene: &Scene,
    opts: &RenderOptions,
    spin: Spin,
    frames: u64,
    fps: u32,
    encoder: Encoder,
    recorder: &mut Recorder<W>,
) -> io::Result<()> {
    let mut player = Player::new(scene.clone(), *opts, spin, encoder);
    let fps = u64::from(fps.max(1));
    for k in 0..frames {
        let at = Duration::from_micros(k * 1_000_000 / fps);
        recorder.output(at, player.prepare(LiveStatus::default()))?;
        player.advance(1);
    }
    recorder.end()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn terminal() -> Terminal {
        Terminal {
            term: "xterm".into(),
            shell: "/bin/bash".into(),
            timestamp: Some(1_700_000_000),
        }
    }

    #[test]
    fn header_and_events_are_json_lines_with_escapes_encoded() {
        let mut rec = Recorder::new(Vec::new(), 80, 24, &terminal()).unwrap();
        rec.output(
            Duration::from_millis(0),
            b"\x1b[H\"a\\b\"\n\x7f\xe2\x96\x80",
        )
        .unwrap();
        rec.output(Duration::from_micros(33_333), b"").unwrap();
        rec.resize(Duration::from_micros(33_334), 100, 30).unwrap();
        // DEL needs no escape in JSON; time never goes back.
        rec.output(Duration::from_micros(10), b"x").unwrap();
        let text = String::from_utf8(rec.finish().unwrap()).unwrap();
        assert_eq!(
            text,
            "{\"version\":2,\"width\":80,\"height\":24,\"timestamp\":1700000000,\"env\":{\"TERM\":\"xterm\",\"SHELL\":\"/bin/bash\"}}\n\
             [0.0,\"o\",\"\\u001b[?25l\\u001b[H\\\"a\\\\b\\\"\\n\u{7f}▀\"]\n\
             [0.033334,\"r\",\"100x30\"]\n\
             [0.033334,\"o\",\"x\"]\n"
        );
    }
}
