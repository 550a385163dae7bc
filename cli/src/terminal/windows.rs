//! The terminal on Windows 10 and later (Windows Terminal, conhost), all
//! through crossterm: VT processing turned on (frames are the same ANSI
//! bytes as on unix), raw mode (Ctrl-C then arrives as a key), the
//! console's input records read as events (keys, mouse, resizes:
//! `events.rs` makes them rastty's inputs), mouse capture, the window's
//! size. A console hands over no answers to queries, so there is no glyph
//! probe and no status request after each frame: frames are paced by the
//! writes, which wait for the console.
//!
//! **Restoring.** [`Session`] leaves the alternate screen, turns mouse
//! capture and raw mode off when dropped and on a panic. Closing the
//! window (or logging off) calls the console control handler on a thread
//! of its own, and the process ends when the handler returns: the handler
//! marks the loop to stop and waits (at most a few seconds) until the
//! console is restored.

use std::io::{self, IsTerminal, Write};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

use crossterm::event::{self, DisableMouseCapture, EnableMouseCapture};

use super::events::{Happened, happened};
use super::input::{Input, Parser};
use super::probe::Capabilities;
use super::{ENTER, LEAVE, Read, TtyError, WindowSize, tty_err};

/// Signal numbers, as the loop knows them: unix's numbers, for what a
/// console's control events stand for (the exit status is 128 + the
/// number, as on unix).
pub mod sig {
    pub const HUP: i32 = 1;
    pub const INT: i32 = 2;
    pub const QUIT: i32 = 3;
    pub const TERM: i32 = 15;
    pub const USR1: i32 = 10;
    pub const USR2: i32 = 12;
    pub const ALRM: i32 = 14;
    pub const PIPE: i32 = 13;
    pub const XCPU: i32 = 24;
    pub const XFSZ: i32 = 25;
    pub const TSTP: i32 = 20;
    pub const CONT: i32 = 18;
    pub const WINCH: i32 = 28;
}

/// Whether standard descriptor `fd` is open: the standard library's handles
/// say so by failing a write, so it is taken as open.
pub fn is_open(_fd: i32) -> bool {
    true
}

/// No signal has a default action to take on Windows: returns.
pub fn die_by(_sig: i32) {}

/// The size of the console stdout writes to, if it is one (cells; a
/// console says nothing of pixels).
pub fn stdout_size() -> Option<WindowSize> {
    if !io::stdout().is_terminal() {
        return None;
    }
    super::crossterm_size()
}

/// Whether the console takes VT sequences (turning the mode on where it
/// can: Windows 10 from 1703, and every Windows Terminal).
pub fn vt_enabled() -> bool {
    crossterm::ansi_support::supports_ansi()
}

/// Signals (as [`sig`] numbers) that came and were not yet taken: the
/// console's control events, and resizes.
static PENDING: AtomicU64 = AtomicU64::new(0);
/// Set once the console is restored, for a control handler that waits.
static RESTORED: AtomicBool = AtomicBool::new(true);
/// Whether a [`Session`] has the console (for the panic hook).
static TAKEN: AtomicBool = AtomicBool::new(false);
/// Whether the taken console is on the alternate screen.
static FULL_SCREEN: AtomicBool = AtomicBool::new(false);

/// The console's control handler: Ctrl-Break, closing the window, logging
/// off, shutting down. Marks the loop to stop; for those after which the
/// process is ended, waits until the console is restored.
unsafe extern "system" fn on_control(event: u32) -> i32 {
    use winapi::um::wincon::{
        CTRL_BREAK_EVENT, CTRL_C_EVENT, CTRL_CLOSE_EVENT, CTRL_LOGOFF_EVENT, CTRL_SHUTDOWN_EVENT,
    };
    let sig = match event {
        CTRL_C_EVENT | CTRL_BREAK_EVENT => sig::INT,
        CTRL_CLOSE_EVENT => sig::HUP,
        CTRL_LOGOFF_EVENT | CTRL_SHUTDOWN_EVENT => sig::TERM,
        _ => return 0,
    };
    PENDING.fetch_or(1 << sig, Ordering::SeqCst);
    if sig != sig::INT {
        let end = Instant::now() + Duration::from_secs(4);
        while !RESTORED.load(Ordering::SeqCst) && Instant::now() < end {
            std::thread::sleep(Duration::from_millis(10));
        }
    }
    1
}

/// Puts the console back: the main screen, the cursor, mouse capture off,
/// raw mode off.
fn restore() {
    let mut out = io::stdout();
    if FULL_SCREEN.load(Ordering::SeqCst) {
        let _ = crossterm::execute!(out, DisableMouseCapture);
        let _ = out.write_all(LEAVE);
        let _ = out.flush();
    }
    let _ = crossterm::terminal::disable_raw_mode();
    TAKEN.store(false, Ordering::SeqCst);
    RESTORED.store(true, Ordering::SeqCst);
}

/// Puts the console back before a panic's message is printed, if a
/// [`Session`] had taken it.
pub fn install_panic_hook() {
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        if TAKEN.load(Ordering::SeqCst) {
            restore();
        }
        previous(info);
    }));
}

/// The console as the interactive loop has it.
pub struct Session {
    full_screen: bool,
}

impl Session {
    /// Takes the console over: VT output, raw mode, the control handler,
    /// and with `full_screen` the alternate screen and mouse capture.
    pub fn open(full_screen: bool, _handled: &[i32]) -> Result<Session, TtyError> {
        if !io::stdout().is_terminal() || !io::stdin().is_terminal() {
            return Err(TtyError::NoControllingTerminal(io::Error::other(
                "stdin and stdout are not both the console",
            )));
        }
        if !vt_enabled() {
            return Err(tty_err("turning VT processing on")(io::Error::other(
                "this console does not take VT sequences (Windows 10 1703 or later, or Windows Terminal, is needed)",
            )));
        }
        PENDING.store(0, Ordering::SeqCst);
        RESTORED.store(false, Ordering::SeqCst);
        crossterm::terminal::enable_raw_mode().map_err(tty_err("entering raw mode"))?;
        FULL_SCREEN.store(full_screen, Ordering::SeqCst);
        TAKEN.store(true, Ordering::SeqCst);
        // SAFETY: registering a handler that touches only atomics.
        unsafe {
            winapi::um::consoleapi::SetConsoleCtrlHandler(Some(on_control), 1);
        }
        let session = Session { full_screen };
        if full_screen {
            let mut out = io::stdout();
            out.write_all(ENTER)
                .and_then(|()| crossterm::execute!(out, EnableMouseCapture))
                .map_err(tty_err("entering the alternate screen"))?;
        }
        Ok(session)
    }

    /// A console hands over no answers to queries.
    pub fn reads_answers(&self) -> bool {
        false
    }

    /// No probe: the console answers nothing.
    pub fn probe(
        &mut self,
        _parser: &mut Parser,
        _early: &mut Vec<Input>,
    ) -> io::Result<Capabilities> {
        Ok(Capabilities::default())
    }

    /// Reads the console's events that are waiting into `inputs` (a resize
    /// is kept as [`sig::WINCH`]): whether any came.
    pub fn read(&mut self, _parser: &mut Parser, inputs: &mut Vec<Input>) -> Read {
        let mut got = Read::Nothing;
        loop {
            match event::poll(Duration::ZERO) {
                Ok(true) => {}
                Ok(false) => return got,
                Err(_) => return Read::Gone,
            }
            let Ok(e) = event::read() else {
                return Read::Gone;
            };
            got = Read::Bytes(1);
            match happened(&e) {
                Some(Happened::Input(i)) => inputs.push(i),
                Some(Happened::Resized(..)) => {
                    PENDING.fetch_or(1 << sig::WINCH, Ordering::SeqCst);
                }
                None => {}
            }
        }
    }

    /// Writes all of `buf` (the console takes it at once).
    pub fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let mut out = io::stdout().lock();
        out.write_all(buf)?;
        out.flush()?;
        Ok(buf.len())
    }

    /// Writes all of `buf`.
    pub fn write_all(&mut self, buf: &[u8], _timeout: Duration) -> io::Result<()> {
        self.write(buf).map(|_| ())
    }

    /// The console's size.
    pub fn size(&self) -> Option<WindowSize> {
        super::crossterm_size()
    }

    /// Waits for an event, at most `timeout` (a control event is seen at
    /// the next wake).
    pub fn wait(&self, _sending: bool, timeout: Duration) -> io::Result<()> {
        event::poll(timeout).map(|_| ())
    }

    /// Waits at most `timeout` for an event.
    pub fn wait_input(&self, timeout: Duration) -> io::Result<()> {
        self.wait(false, timeout)
    }

    /// The control events and resizes since the last call, a bit each.
    pub fn take_signals(&self) -> u64 {
        PENDING.swap(0, Ordering::SeqCst)
    }

    /// Puts what was taken back, for the next take.
    pub fn keep_signals(&self, mask: u64) {
        PENDING.fetch_or(mask, Ordering::SeqCst);
    }

    /// A console has no job control: Ctrl-Z does nothing.
    pub fn can_suspend(&self) -> bool {
        false
    }

    /// Nothing to stop.
    pub fn stop(&mut self) -> io::Result<()> {
        Ok(())
    }

    /// Nothing to take back.
    pub fn resume(&mut self) -> io::Result<()> {
        let _ = self.full_screen;
        Ok(())
    }
}

impl Drop for Session {
    fn drop(&mut self) {
        restore();
        // SAFETY: removing the handler registered in `open`.
        unsafe {
            winapi::um::consoleapi::SetConsoleCtrlHandler(Some(on_control), 0);
        }
    }
}
