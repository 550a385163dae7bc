//! Stage 8: the terminal, through crossterm: its size, its cells' shape,
//! what colour it can show, and the interactive animation loop.
//!
//! [`run`] puts the terminal in raw mode on the alternate screen with the
//! cursor hidden, and restores it on every way out: `q`, Esc, Ctrl-C, an
//! error (the [`Session`] guard's `Drop`), a panic ([`install_panic_hook`]),
//! and SIGTERM, SIGHUP (a dropped ssh link) and SIGINT, which set a flag the
//! loop checks at least once a frame. Frames are paced by the clock: frame
//! `k` is due at `k / fps` seconds; when the terminal is slow, the frames
//! it missed are skipped (the angle jumps ahead) rather than queued.

use std::io::{self, IsTerminal, Write};
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use crossterm::event::{self, Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers};

use crate::animate::{Command, Player};
use crate::color::ColorDepth;

/// Whether stdout is a terminal.
pub fn stdout_is_terminal() -> bool {
    std::io::stdout().is_terminal()
}

/// The terminal's size in cells, if it reports one.
pub fn size() -> Option<(u16, u16)> {
    crossterm::terminal::size()
        .ok()
        .filter(|&(c, r)| c > 0 && r > 0)
}

/// A cell's width over its height, from the terminal's pixel size where it
/// reports one (many do not, and ssh often reports zero).
pub fn cell_aspect() -> Option<f32> {
    let ws = crossterm::terminal::window_size().ok()?;
    if ws.width == 0 || ws.height == 0 || ws.columns == 0 || ws.rows == 0 {
        return None;
    }
    let cell_w = ws.width as f32 / ws.columns as f32;
    let cell_h = ws.height as f32 / ws.rows as f32;
    Some(cell_w / cell_h).filter(|a| a.is_finite() && *a > 0.0)
}

/// The colour depth `--color auto` picks, first rule that applies:
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
pub fn detect_color(stdout_is_tty: bool, env: impl Fn(&str) -> Option<String>) -> ColorDepth {
    let set = |k: &str| env(k).filter(|v| !v.is_empty());
    if set("NO_COLOR").is_some() || !stdout_is_tty {
        return ColorDepth::None;
    }
    let term = set("TERM").unwrap_or_default();
    if term.is_empty() || term == "dumb" {
        return ColorDepth::None;
    }
    let colorterm = set("COLORTERM").unwrap_or_default().to_ascii_lowercase();
    if colorterm == "truecolor"
        || colorterm == "24bit"
        || term.ends_with("-direct")
        || term.ends_with("-truecolor")
    {
        ColorDepth::TrueColor
    } else if term.contains("256color") {
        ColorDepth::Ansi256
    } else {
        ColorDepth::Ansi16
    }
}

/// The terminal in raw mode, on the alternate screen, cursor hidden, until
/// dropped.
pub struct Session(());

impl Session {
    pub fn enter() -> io::Result<Session> {
        crossterm::terminal::enable_raw_mode()?;
        let session = Session(());
        let mut out = io::stdout();
        crossterm::execute!(
            out,
            crossterm::terminal::EnterAlternateScreen,
            crossterm::cursor::Hide
        )?;
        Ok(session)
    }
}

impl Drop for Session {
    fn drop(&mut self) {
        restore();
    }
}

/// Puts the terminal back: colours reset, cursor shown, main screen, cooked
/// mode. Safe to call more than once, and when the terminal is gone.
pub fn restore() {
    let mut out = io::stdout();
    let _ = out.write_all(b"\x1b[m");
    let _ = crossterm::execute!(
        out,
        crossterm::cursor::Show,
        crossterm::terminal::LeaveAlternateScreen
    );
    let _ = crossterm::terminal::disable_raw_mode();
}

/// Restores the terminal before a panic's message is printed.
pub fn install_panic_hook() {
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        restore();
        previous(info);
    }));
}

/// How the loop ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Exit {
    /// A key asked to quit.
    Quit,
    /// The last of `--frames` was shown.
    Done,
    /// A signal (its number) asked to stop.
    Signal(i32),
}

/// Whether stdin has hung up (its terminal closed). crossterm (read through
/// `/dev/tty`, its `use-dev-tty` source, which at least returns on an end
/// of file) does not report it, so the loop asks once a frame.
fn input_hung_up() -> bool {
    let mut fd = libc::pollfd {
        fd: libc::STDIN_FILENO,
        events: libc::POLLIN,
        revents: 0,
    };
    // SAFETY: one valid pollfd, a zero timeout.
    let n = unsafe { libc::poll(&mut fd, 1, 0) };
    n > 0 && fd.revents & (libc::POLLHUP | libc::POLLERR | libc::POLLNVAL) != 0
}

/// The command a key asks for.
pub fn command_for(key: KeyEvent) -> Option<Command> {
    if key.kind != KeyEventKind::Press {
        return None;
    }
    let ctrl = key.modifiers.contains(KeyModifiers::CONTROL);
    Some(match key.code {
        KeyCode::Char('c') if ctrl => Command::Quit,
        KeyCode::Char('l') if ctrl => Command::Redraw,
        KeyCode::Char('q') | KeyCode::Esc => Command::Quit,
        KeyCode::Char(' ') => Command::TogglePause,
        KeyCode::Left => Command::Orbit {
            yaw: -5.0,
            pitch: 0.0,
        },
        KeyCode::Right => Command::Orbit {
            yaw: 5.0,
            pitch: 0.0,
        },
        KeyCode::Up => Command::Orbit {
            yaw: 0.0,
            pitch: 5.0,
        },
        KeyCode::Down => Command::Orbit {
            yaw: 0.0,
            pitch: -5.0,
        },
        KeyCode::Char('+') | KeyCode::Char('=') => Command::Zoom(0.9),
        KeyCode::Char('-') | KeyCode::Char('_') => Command::Zoom(1.0 / 0.9),
        KeyCode::Char('m') => Command::NextGlyphs,
        KeyCode::Char('c') => Command::NextColor,
        KeyCode::Char('s') => Command::NextShading,
        _ => return None,
    })
}

/// Spins `player` in the terminal at `fps` until a key, a signal, or (with
/// `frames`) the last frame. The terminal is restored before it returns.
pub fn run(player: &mut Player, fps: u32, frames: Option<u64>) -> io::Result<Exit> {
    let signal = Arc::new(AtomicUsize::new(0));
    for sig in [
        signal_hook::consts::SIGTERM,
        signal_hook::consts::SIGHUP,
        signal_hook::consts::SIGINT,
    ] {
        signal_hook::flag::register_usize(sig, Arc::clone(&signal), sig as usize)?;
    }
    let _session = Session::enter()?;
    let mut out = io::stdout().lock();
    let fps = fps.max(1) as f64;
    let start = Instant::now();
    let mut shown: Option<u64> = None;
    let mut last_show = Instant::now();
    let mut measured = fps as f32;
    loop {
        match signal.load(Ordering::Relaxed) {
            0 => {}
            sig => return Ok(Exit::Signal(sig as i32)),
        }
        let tick = (start.elapsed().as_secs_f64() * fps) as u64;
        if shown != Some(tick) {
            // Frames the terminal was too slow for are skipped, not queued.
            let mut step = shown.map_or(0, |s| tick - s);
            if let Some(n) = frames {
                step = step.min((n - 1).saturating_sub(player.frame_number()));
            }
            player.advance(step);
            let now = Instant::now();
            let dt = now.duration_since(last_show).as_secs_f32();
            if shown.is_some() && dt > 0.0 {
                measured = 0.9 * measured + 0.1 / dt;
            }
            last_show = now;
            player.show(&mut out, measured)?;
            shown = Some(tick);
            if frames.is_some_and(|n| player.frame_number() + 1 >= n && !player.is_paused()) {
                return Ok(Exit::Done);
            }
        }
        let next = start + Duration::from_secs_f64((tick + 1) as f64 / fps);
        let wait = next.saturating_duration_since(Instant::now());
        if input_hung_up() {
            // The terminal is gone (a closed ssh link, a killed tmux) and
            // no SIGHUP came.
            return Ok(Exit::Signal(signal_hook::consts::SIGHUP));
        }
        if event::poll(wait)? {
            let cmd = match event::read()? {
                Event::Key(key) => command_for(key),
                Event::Resize(cols, rows) => Some(Command::Resize { cols, rows }),
                _ => None,
            };
            if let Some(cmd) = cmd {
                if !player.apply(cmd) {
                    return Ok(Exit::Quit);
                }
                // Show the change at once, at the same angle.
                player.show(&mut out, measured)?;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_map_to_commands() {
        let key = |code| KeyEvent::new(code, KeyModifiers::NONE);
        assert_eq!(command_for(key(KeyCode::Char('q'))), Some(Command::Quit));
        assert_eq!(command_for(key(KeyCode::Esc)), Some(Command::Quit));
        assert_eq!(
            command_for(KeyEvent::new(KeyCode::Char('c'), KeyModifiers::CONTROL)),
            Some(Command::Quit)
        );
        assert_eq!(
            command_for(key(KeyCode::Char('c'))),
            Some(Command::NextColor)
        );
        assert_eq!(
            command_for(key(KeyCode::Char(' '))),
            Some(Command::TogglePause)
        );
        assert_eq!(
            command_for(key(KeyCode::Char('m'))),
            Some(Command::NextGlyphs)
        );
        assert_eq!(
            command_for(key(KeyCode::Char('s'))),
            Some(Command::NextShading)
        );
        assert_eq!(
            command_for(key(KeyCode::Left)),
            Some(Command::Orbit {
                yaw: -5.0,
                pitch: 0.0
            })
        );
        assert_eq!(
            command_for(key(KeyCode::Char('+'))),
            Some(Command::Zoom(0.9))
        );
        assert_eq!(command_for(key(KeyCode::Char('x'))), None);
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
}
