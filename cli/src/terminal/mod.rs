//! Stage 8: the terminal itself: its size and cell shape, the colours it
//! shows, what it draws (a probe of its glyph widths), raw mode and the
//! alternate screen, and reading its input.
//!
//! **Which layer does what.** crossterm is the terminal layer wherever it
//! does the job: raw mode and the window's size on every platform, and on
//! Windows everything (VT output turned on, the console's keys, mouse and
//! resizes as events, mouse capture; `windows.rs`). On unix (Linux, macOS,
//! the BSDs) the interactive loop reads the tty's bytes itself and parses
//! them (`input.rs`), writes frames without blocking, and waits on keys,
//! signals and room to write in one `poll` (`unix.rs`, `signals.rs`):
//! crossterm's reader hands over no answers to queries (the glyph probe,
//! the status request that paces frames) and does not read on a zero
//! timeout. Both platforms give the loop one [`Session`] with the same
//! methods, and one form of input ([`input::Input`]: `events.rs` turns
//! crossterm's events into it). The alternate screen and mouse reports are
//! asked for with rastty's own sequences ([`ENTER`]): crossterm's mouse
//! capture asks for every motion too, which floods a slow link (on
//! Windows, where capture is the console's mode, crossterm's is used).
//!
//! The restoring bytes start with CAN, which ends any escape sequence a
//! frame cut short left open, and end synchronized output, in case the cut
//! frame began it.

// Windows reads its input as crossterm's events; the conversion is tested
// on every platform.
#[cfg_attr(not(windows), allow(dead_code))]
pub(crate) mod events;
// The byte parser and the probe read a tty's bytes: unix's. On Windows the
// console's input arrives as events (`events.rs`), in the parser's `Input`.
#[cfg_attr(windows, allow(dead_code))]
pub(crate) mod input;
#[cfg_attr(windows, allow(dead_code))]
pub(crate) mod probe;
#[cfg(unix)]
pub(crate) mod signals;
#[cfg(unix)]
mod unix;
#[cfg(windows)]
mod windows;

#[cfg(unix)]
pub use unix::*;
#[cfg(windows)]
pub use windows::*;

use std::io::{self, IsTerminal};

use rastty::MAX_CELLS;
use rastty::color::ColorDepth;

/// Whether stdout is a terminal.
pub fn stdout_is_terminal() -> bool {
    io::stdout().is_terminal()
}

/// A terminal's size: cells, and pixels where it reports them (0 if not).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct WindowSize {
    /// Columns.
    pub cols: u16,
    /// Rows.
    pub rows: u16,
    /// Width in pixels (0 when the terminal does not say).
    pub width_px: u16,
    /// Height in pixels (0 when the terminal does not say).
    pub height_px: u16,
}

impl WindowSize {
    /// The size in cells, each side clamped to [`MAX_CELLS`].
    pub fn cells(&self) -> (u16, u16) {
        (self.cols.min(MAX_CELLS), self.rows.min(MAX_CELLS))
    }

    /// A cell's pixels (across, down), where the terminal reports pixels.
    pub fn cell_pixels(&self) -> Option<[u16; 2]> {
        let (w, h) = (
            self.width_px / self.cols.max(1),
            self.height_px / self.rows.max(1),
        );
        (w > 0 && h > 0).then_some([w, h])
    }

    /// A cell's width over its height, where the terminal reports pixels
    /// (many do not, and ssh often reports zero).
    pub fn cell_aspect(&self) -> Option<f32> {
        if self.width_px == 0 || self.height_px == 0 {
            return None;
        }
        let w = self.width_px as f32 / self.cols as f32;
        let h = self.height_px as f32 / self.rows as f32;
        Some(w / h).filter(|a| a.is_finite() && *a > 0.0)
    }
}

/// The window's size as crossterm finds it: cells and pixels where the
/// platform says (not on Windows), else cells alone.
fn crossterm_size() -> Option<WindowSize> {
    let size = match crossterm::terminal::window_size() {
        Ok(w) => WindowSize {
            cols: w.columns,
            rows: w.rows,
            width_px: w.width,
            height_px: w.height,
        },
        Err(_) => {
            let (cols, rows) = crossterm::terminal::size().ok()?;
            WindowSize {
                cols,
                rows,
                ..WindowSize::default()
            }
        }
    };
    (size.cols > 0 && size.rows > 0).then_some(size)
}

/// Whether a signal mask ([`Session::take_signals`]) holds `sig`.
pub fn has_signal(mask: u64, sig: i32) -> bool {
    mask >> (sig as u64 & 63) & 1 == 1
}

/// Inside tmux (`TMUX` set), whether the terminal tmux's client runs in
/// draws 24-bit colour, as tmux says (`tmux display -p
/// '#{client_termfeatures}'` lists `RGB`). tmux answers neither DECRQSS
/// nor XTGETTCAP itself, and sets no `COLORTERM`. `None` outside tmux or
/// where it cannot be asked (no client attached says nothing).
pub fn tmux_truecolor() -> Option<bool> {
    std::env::var_os("TMUX").filter(|v| !v.is_empty())?;
    let out = std::process::Command::new("tmux")
        .args(["display", "-p", "#{client_termfeatures}"])
        .stdin(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .output()
        .ok()
        .filter(|o| o.status.success())?;
    let features = String::from_utf8_lossy(&out.stdout);
    Some(features.trim().split(',').any(|f| f == "RGB"))
}

/// Whether `TERM` names a terminal that cannot move its cursor (unset,
/// empty or `dumb`; on Windows, where consoles set no `TERM`, only `dumb`):
/// it gets plain lines, no escape sequences.
pub fn is_dumb(term: Option<&str>) -> bool {
    if cfg!(windows) {
        return term == Some("dumb");
    }
    matches!(term, None | Some("" | "dumb"))
}

/// The colour depth `--color auto` picks, and why: the platform's rules
/// ([`unix_colour_rule`], [`windows_colour_rule`]) on this process's
/// environment.
pub fn detect_color_why(
    stdout_is_tty: bool,
    env: impl Fn(&str) -> Option<String>,
) -> (ColorDepth, String) {
    #[cfg(windows)]
    return windows_colour_rule(stdout_is_tty, env, stdout_is_tty && vt_enabled());
    #[cfg(not(windows))]
    unix_colour_rule(stdout_is_tty, env)
}

/// The colour depth `--color auto` picks on Windows, first rule that
/// applies:
///
/// 1. `NO_COLOR` set and non-empty: none;
/// 2. stdout not a terminal: none;
/// 3. `TERM` is `dumb`: none;
/// 4. `COLORTERM` is `truecolor` or `24bit`: truecolor;
/// 5. `WT_SESSION` is set (Windows Terminal): truecolor;
/// 6. the console takes VT sequences (`vt`: conhost from Windows 10 1703
///    does, and draws 24-bit colour): truecolor;
/// 7. a `TERM` (a terminal such as mintty that sets one): unix's rules;
/// 8. otherwise: 16.
#[cfg_attr(not(windows), allow(dead_code))]
pub fn windows_colour_rule(
    stdout_is_tty: bool,
    env: impl Fn(&str) -> Option<String>,
    vt: bool,
) -> (ColorDepth, String) {
    let set = |k: &str| env(k).filter(|v| !v.is_empty());
    if set("NO_COLOR").is_some() {
        return (ColorDepth::None, "NO_COLOR is set".into());
    }
    if !stdout_is_tty {
        return (ColorDepth::None, "stdout is not a terminal".into());
    }
    let term = set("TERM");
    if term.as_deref() == Some("dumb") {
        return (ColorDepth::None, "TERM is dumb".into());
    }
    let colorterm = set("COLORTERM").unwrap_or_default().to_ascii_lowercase();
    if colorterm == "truecolor" || colorterm == "24bit" {
        return (
            ColorDepth::TrueColor,
            format!("COLORTERM is {}", rastty::text::cut(&colorterm, 40)),
        );
    }
    if set("WT_SESSION").is_some() {
        return (
            ColorDepth::TrueColor,
            "WT_SESSION is set: Windows Terminal".into(),
        );
    }
    if vt {
        return (
            ColorDepth::TrueColor,
            "the console takes VT sequences, and with them 24-bit colour".into(),
        );
    }
    if term.is_some() {
        return unix_colour_rule(true, env);
    }
    (
        ColorDepth::Ansi16,
        "the console takes no VT sequences".into(),
    )
}

/// The colour depth `--color auto` picks on unix, first rule that applies:
///
/// 1. `NO_COLOR` set and non-empty: none;
/// 2. stdout not a terminal: none;
/// 3. `TERM` unset or `dumb`: none;
/// 4. `COLORTERM` is `truecolor` or `24bit`, or `TERM` ends in `-direct` or
///    `-truecolor`: truecolor;
/// 5. `TERM` contains `256color`: 256;
/// 6. otherwise: 16.
///
/// ssh forwards `TERM` but not `COLORTERM`, so over ssh a truecolor
/// terminal shows as 256 colours unless the client sends it
/// (`SendEnv COLORTERM`, with `AcceptEnv COLORTERM` on the server) or
/// `--color truecolor` is given. `env` looks up a variable (a parameter so
/// that tests need not touch the process's environment).
///
/// Returns the depth and why: the rule that decided, as `--explain` says it
/// (the environment's values escaped).
pub fn unix_colour_rule(
    stdout_is_tty: bool,
    env: impl Fn(&str) -> Option<String>,
) -> (ColorDepth, String) {
    let set = |k: &str| env(k).filter(|v| !v.is_empty());
    if set("NO_COLOR").is_some() {
        return (ColorDepth::None, "NO_COLOR is set".into());
    }
    if !stdout_is_tty {
        return (ColorDepth::None, "stdout is not a terminal".into());
    }
    let term = set("TERM");
    // A value from the environment, quoted, escaped and cut: a TERM of
    // thousands of characters is said in a few dozen.
    let shown = |v: &str| rastty::text::cut(v, 40);
    if matches!(term.as_deref(), None | Some("dumb")) {
        let why = match &term {
            None => "TERM is unset".to_string(),
            Some(t) => format!("TERM is {}", shown(t)),
        };
        return (ColorDepth::None, why);
    }
    let term = term.unwrap_or_default();
    let colorterm = set("COLORTERM").unwrap_or_default().to_ascii_lowercase();
    if colorterm == "truecolor" || colorterm == "24bit" {
        (
            ColorDepth::TrueColor,
            format!("COLORTERM is {}", shown(&colorterm)),
        )
    } else if term.ends_with("-direct") || term.ends_with("-truecolor") {
        (ColorDepth::TrueColor, format!("TERM is {}", shown(&term)))
    } else if term.contains("256color") {
        (
            ColorDepth::Ansi256,
            format!(
                "TERM is {} and COLORTERM does not say truecolor",
                shown(&term)
            ),
        )
    } else {
        (
            ColorDepth::Ansi16,
            format!(
                "TERM is {}, which says neither 256 colours nor truecolor",
                shown(&term)
            ),
        )
    }
}

/// Why the terminal could not be used.
#[derive(Debug, thiserror::Error)]
pub enum TtyError {
    /// No controlling terminal to read keys from.
    #[error(
        "no controlling terminal to read keys from (/dev/tty: {0}); run spin in a terminal, or redirect stdout and give --frames N for a stream of frames"
    )]
    NoControllingTerminal(io::Error),
    /// Any other failure, with what was being done.
    #[error("the terminal: {what}: {source}")]
    Io {
        /// What was being done.
        what: &'static str,
        #[source]
        /// What went wrong.
        source: io::Error,
    },
}

fn tty_err(what: &'static str) -> impl FnOnce(io::Error) -> TtyError {
    move |source| TtyError::Io { what, source }
}

/// What one non-blocking read gave.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Read {
    /// This many bytes.
    Bytes(usize),
    /// Nothing yet.
    Nothing,
    /// The terminal is gone (end of file, or an error such as EIO after a
    /// hang-up).
    Gone,
}

/// Enters the alternate screen, hides the cursor and asks for mouse
/// reports: presses, releases and drags (1000, 1002; no motion without a
/// button, which would flood a slow link), in the SGR encoding (1006),
/// which has no limit on the column and says which button came up; a
/// terminal without 1006 sends the legacy encoding, which is read too.
pub const ENTER: &[u8] = b"\x1b[?1049h\x1b[?25l\x1b[?1000h\x1b[?1002h\x1b[?1006h";
/// Undoes [`ENTER`] and whatever a cut-short frame left: CAN ends an open
/// escape sequence, then attributes reset, synchronized output ended,
/// mouse reports off, the cursor shown, the main screen back.
pub const LEAVE: &[u8] =
    b"\x18\x1b[m\x1b[?2026l\x1b[?1006l\x1b[?1002l\x1b[?1000l\x1b[?25h\x1b[?1049l";

#[cfg(test)]
mod tests {
    use super::*;

    fn detect_color(stdout_is_tty: bool, env: impl Fn(&str) -> Option<String>) -> ColorDepth {
        unix_colour_rule(stdout_is_tty, env).0
    }

    fn env<'a>(vars: &'a [(&'a str, &'a str)]) -> impl Fn(&str) -> Option<String> + 'a {
        move |k| {
            vars.iter()
                .find(|(n, _)| *n == k)
                .map(|(_, v)| v.to_string())
        }
    }

    #[test]
    fn auto_colour_rules_in_order() {
        let xterm = ("TERM", "xterm-256color");
        assert_eq!(
            detect_color(true, env(&[("NO_COLOR", "1"), xterm])),
            ColorDepth::None
        );
        assert_eq!(
            detect_color(false, env(&[xterm, ("COLORTERM", "truecolor")])),
            ColorDepth::None
        );
        assert_eq!(detect_color(true, env(&[])), ColorDepth::None);
        assert_eq!(
            detect_color(true, env(&[("TERM", "dumb")])),
            ColorDepth::None
        );
        assert_eq!(
            detect_color(true, env(&[("NO_COLOR", ""), xterm])),
            ColorDepth::Ansi256
        );
        assert_eq!(
            detect_color(true, env(&[xterm, ("COLORTERM", "truecolor")])),
            ColorDepth::TrueColor
        );
        assert_eq!(
            detect_color(true, env(&[xterm, ("COLORTERM", "24bit")])),
            ColorDepth::TrueColor
        );
        assert_eq!(
            detect_color(true, env(&[("TERM", "xterm-direct")])),
            ColorDepth::TrueColor
        );
        assert_eq!(
            detect_color(true, env(&[("TERM", "foot-truecolor")])),
            ColorDepth::TrueColor
        );
        assert_eq!(
            detect_color(true, env(&[("TERM", "screen-256color")])),
            ColorDepth::Ansi256
        );
        assert_eq!(
            detect_color(true, env(&[("TERM", "xterm")])),
            ColorDepth::Ansi16
        );
        assert_eq!(
            detect_color(true, env(&[("TERM", "linux"), ("COLORTERM", "yes")])),
            ColorDepth::Ansi16
        );
    }

    #[test]
    fn the_colour_rule_that_decided_is_said_with_its_values_escaped() {
        let why = |vars: &[(&str, &str)]| unix_colour_rule(true, env(vars)).1;
        assert_eq!(why(&[("NO_COLOR", "1")]), "NO_COLOR is set");
        assert_eq!(
            unix_colour_rule(false, env(&[])).1,
            "stdout is not a terminal"
        );
        assert_eq!(why(&[]), "TERM is unset");
        assert_eq!(
            why(&[("TERM", "screen-256color")]),
            "TERM is screen-256color and COLORTERM does not say truecolor"
        );
        assert_eq!(
            why(&[("TERM", "x\x1b]0;owned\x07")]),
            "TERM is x\\x1b]0;owned\\x07, which says neither 256 colours nor truecolor"
        );
        assert_eq!(
            why(&[("TERM", "xterm"), ("COLORTERM", "24BIT")]),
            "COLORTERM is 24bit"
        );
    }

    #[test]
    fn a_windows_console_is_told_by_what_it_takes_not_by_term() {
        let rule = |vars: &[(&str, &str)], vt| windows_colour_rule(true, env(vars), vt);
        // A console sets no TERM: that is not a dumb terminal there.
        assert_eq!(
            rule(&[], true),
            (
                ColorDepth::TrueColor,
                "the console takes VT sequences, and with them 24-bit colour".into()
            )
        );
        assert_eq!(
            rule(&[("WT_SESSION", "4d2c")], false),
            (
                ColorDepth::TrueColor,
                "WT_SESSION is set: Windows Terminal".into()
            )
        );
        assert_eq!(
            rule(&[], false),
            (
                ColorDepth::Ansi16,
                "the console takes no VT sequences".into()
            )
        );
        assert_eq!(rule(&[("NO_COLOR", "1")], true).0, ColorDepth::None);
        assert_eq!(rule(&[("TERM", "dumb")], true).0, ColorDepth::None);
        assert_eq!(
            rule(&[("TERM", "xterm-256color")], false).0,
            ColorDepth::Ansi256
        );
        assert_eq!(
            windows_colour_rule(false, env(&[]), true).0,
            ColorDepth::None
        );
    }

    #[test]
    fn sizes_are_clamped_and_aspect_needs_pixels() {
        let ws = WindowSize {
            cols: 5000,
            rows: 60,
            width_px: 0,
            height_px: 0,
        };
        assert_eq!(ws.cells(), (MAX_CELLS, 60));
        assert_eq!(ws.cell_aspect(), None);
        let ws = WindowSize {
            cols: 100,
            rows: 50,
            width_px: 800,
            height_px: 800,
        };
        assert_eq!(ws.cell_aspect(), Some(0.5));
    }
}
