//! Stage 8: the terminal itself: its size and cell shape, the colours it
//! shows, what it draws (a probe of its glyph widths), raw mode and the alternate screen, and
//! reading its input (a byte parser for keys and answers).
//!
//! rastty talks to the tty directly (through `rustix`), not through
//! crossterm: the interactive loop must read keys whatever its pacing, read
//! the answers to its queries within a deadline, write without blocking on a
//! slow link, and give signals back when it ends (see `signals.rs`).
//!
//! **The controlling terminal.** Keys are read from `/dev/tty`, so `spin`
//! needs a controlling terminal even when stdout is one (`setsid rastty
//! spin` has none, and is told so). Frames go to the terminal stdout names,
//! through a descriptor of rastty's own (opened anew, so that making it
//! non-blocking never touches the shell's stdout).
//!
//! **Restoring.** [`Screen`] puts the terminal in raw mode on the alternate
//! screen with the cursor hidden, and puts everything back when dropped, on
//! a panic ([`install_panic_hook`]), and before a suspend. The restoring
//! bytes start with CAN, which ends any escape sequence a frame cut short
//! left open, and end synchronized output, in case the cut frame began it.

pub(crate) mod input;
pub(crate) mod probe;
pub(crate) mod signals;

use std::io::{self, IsTerminal};
use std::os::fd::{AsFd, AsRawFd, BorrowedFd, OwnedFd, RawFd};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use rustix::fs::{Mode, OFlags};
use rustix::termios::{self, OptionalActions, Termios};

use rastty::MAX_CELLS;
use rastty::color::ColorDepth;

/// Whether stdout is a terminal.
pub fn stdout_is_terminal() -> bool {
    io::stdout().is_terminal()
}

/// Whether standard descriptor `fd` (0, 1 or 2) is open. The standard
/// library, before `main`, opens `/dev/null` in place of a standard
/// descriptor that was closed (`>&-`) and then takes every write as done;
/// which ones were closed is recorded before that, by [`CLOSED_AT_START`]'s
/// constructor, so that a closed stdout is told from one that is
/// `/dev/null` (a shell's `> /dev/null`, `1<>/dev/null`, Python's
/// `subprocess.DEVNULL`, systemd's `StandardOutput=null`), whatever its
/// mode.
pub fn is_open(fd: i32) -> bool {
    let closed = CLOSED_AT_START.load(std::sync::atomic::Ordering::Relaxed);
    if (0..3).contains(&fd) && closed & (1 << fd) != 0 {
        return false;
    }
    // SAFETY: fcntl reads the descriptor's flags and changes nothing; a
    // closed descriptor gives -1.
    unsafe { libc::fcntl(fd, libc::F_GETFD) != -1 }
}

/// Bit `fd` set for each standard descriptor that was closed when the
/// process started.
static CLOSED_AT_START: std::sync::atomic::AtomicU8 = std::sync::atomic::AtomicU8::new(0);

/// Records which standard descriptors are closed. Run by the loader before
/// `main` and before the standard library's start-up code, from the
/// initializer list below.
extern "C" fn record_closed_descriptors() {
    let mut closed = 0;
    for fd in 0..3 {
        // SAFETY: as in `is_open`.
        if unsafe { libc::fcntl(fd, libc::F_GETFD) } == -1 {
            closed |= 1 << fd;
        }
    }
    CLOSED_AT_START.store(closed, std::sync::atomic::Ordering::Relaxed);
}

/// The initializer that runs [`record_closed_descriptors`]: in ELF's
/// `.init_array` (Linux, the BSDs) or Mach-O's `__mod_init_func` (macOS).
#[cfg(any(
    target_os = "linux",
    target_os = "android",
    target_os = "freebsd",
    target_os = "netbsd",
    target_os = "openbsd",
    target_os = "dragonfly"
))]
#[used]
#[unsafe(link_section = ".init_array")]
static RECORD_CLOSED: extern "C" fn() = record_closed_descriptors;

#[cfg(target_vendor = "apple")]
#[used]
#[unsafe(link_section = "__DATA,__mod_init_func")]
static RECORD_CLOSED: extern "C" fn() = record_closed_descriptors;

/// Ends the process by `sig`'s default action (a core dump for SIGXCPU
/// and SIGXFSZ, as if the signal had not been caught), for a program that
/// caught it to restore the terminal first. Returns only if the default
/// action is not to end the process.
pub fn die_by(sig: i32) {
    // SAFETY: setting the default action and raising the signal; nothing
    // is shared with a handler.
    unsafe {
        libc::signal(sig, libc::SIG_DFL);
        libc::raise(sig);
    }
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
    fn of(fd: BorrowedFd<'_>) -> Option<WindowSize> {
        let ws = termios::tcgetwinsize(fd).ok()?;
        (ws.ws_col > 0 && ws.ws_row > 0).then_some(WindowSize {
            cols: ws.ws_col,
            rows: ws.ws_row,
            width_px: ws.ws_xpixel,
            height_px: ws.ws_ypixel,
        })
    }

    /// The size in cells, each side clamped to [`MAX_CELLS`].
    pub fn cells(&self) -> (u16, u16) {
        (self.cols.min(MAX_CELLS), self.rows.min(MAX_CELLS))
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

/// The size of the terminal stdout writes to, if it is one.
pub fn stdout_size() -> Option<WindowSize> {
    let out = io::stdout();
    if !out.is_terminal() {
        return None;
    }
    WindowSize::of(out.as_fd())
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
/// empty or `dumb`): it gets plain lines, no escape sequences.
pub fn is_dumb(term: Option<&str>) -> bool {
    matches!(term, None | Some("" | "dumb"))
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
///
/// Returns the depth and why: the rule that decided, as `--explain` says it
/// (the environment's values escaped).
pub fn detect_color_why(
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
    if is_dumb(term.as_deref()) {
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

/// The controlling terminal, open for reading keys, and the terminal stdout
/// names, open for writing frames; both non-blocking.
pub struct Tty {
    input: OwnedFd,
    /// A descriptor of our own for stdout's terminal, when it is not the
    /// controlling one (`None`: frames go to `input`, the same terminal).
    output: Option<OwnedFd>,
    /// The terminal's modes before raw mode.
    saved: Termios,
}

impl Tty {
    /// Opens `/dev/tty`, and stdout's terminal if it is another one.
    pub fn open() -> Result<Tty, TtyError> {
        let flags = OFlags::RDWR | OFlags::NOCTTY | OFlags::CLOEXEC | OFlags::NONBLOCK;
        let input = rustix::fs::open("/dev/tty", flags, Mode::empty())
            .map_err(|e| TtyError::NoControllingTerminal(e.into()))?;
        let saved =
            termios::tcgetattr(&input).map_err(|e| tty_err("reading its modes")(e.into()))?;
        let stdout = io::stdout();
        let same = || -> Option<bool> {
            let a = rustix::fs::fstat(&input).ok()?;
            let b = rustix::fs::fstat(stdout.as_fd()).ok()?;
            Some(a.st_rdev == b.st_rdev)
        };
        let output = if stdout.is_terminal() && same() == Some(false) {
            let name = termios::ttyname(stdout.as_fd(), Vec::new())
                .map_err(|e| tty_err("naming stdout's terminal")(e.into()))?;
            let flags = OFlags::WRONLY | OFlags::NOCTTY | OFlags::CLOEXEC | OFlags::NONBLOCK;
            Some(
                rustix::fs::open(name.as_c_str(), flags, Mode::empty())
                    .map_err(|e| tty_err("opening stdout's terminal")(e.into()))?,
            )
        } else {
            None
        };
        Ok(Tty {
            input,
            output,
            saved,
        })
    }

    /// Where keys are read from.
    pub fn input_fd(&self) -> BorrowedFd<'_> {
        self.input.as_fd()
    }

    /// Where frames are written.
    pub fn output_fd(&self) -> BorrowedFd<'_> {
        self.output.as_ref().unwrap_or(&self.input).as_fd()
    }

    /// The terminal's size.
    pub fn size(&self) -> Option<WindowSize> {
        WindowSize::of(self.output_fd()).or_else(|| WindowSize::of(self.input_fd()))
    }

    /// Raw mode: keys one at a time, no echo, no signals from keys (Ctrl-C
    /// and Ctrl-Z arrive as bytes). With `output_processing`, `\n` still
    /// starts a new line at column 0 (for plain lines on a dumb terminal).
    pub fn raw_mode(&self, output_processing: bool) -> io::Result<()> {
        let mut t = self.saved.clone();
        t.make_raw();
        if output_processing {
            t.output_modes |= termios::OutputModes::OPOST | termios::OutputModes::ONLCR;
        }
        termios::tcsetattr(&self.input, OptionalActions::Drain, &t)?;
        Ok(())
    }

    /// The modes the terminal had when it was opened.
    pub fn cooked_mode(&self) -> io::Result<()> {
        termios::tcsetattr(&self.input, OptionalActions::Now, &self.saved)?;
        Ok(())
    }

    /// Reads what the terminal sent, without waiting.
    pub fn read(&self, buf: &mut [u8]) -> Read {
        loop {
            return match rustix::io::read(&self.input, &mut *buf) {
                Ok(0) => Read::Gone,
                Ok(n) => Read::Bytes(n),
                Err(rustix::io::Errno::AGAIN) => Read::Nothing,
                Err(rustix::io::Errno::INTR) => continue,
                Err(_) => Read::Gone,
            };
        }
    }

    /// Writes what the terminal takes now, without waiting; `Ok(0)` when
    /// it takes nothing.
    pub fn write(&self, buf: &[u8]) -> io::Result<usize> {
        loop {
            return match rustix::io::write(self.output_fd(), buf) {
                Ok(n) => Ok(n),
                Err(rustix::io::Errno::AGAIN) => Ok(0),
                Err(rustix::io::Errno::INTR) => continue,
                Err(e) => Err(e.into()),
            };
        }
    }

    /// Writes all of `buf`, waiting for the terminal at most `timeout`.
    pub fn write_all(&self, mut buf: &[u8], timeout: Duration) -> io::Result<()> {
        let deadline = Instant::now() + timeout;
        while !buf.is_empty() {
            let n = self.write(buf)?;
            buf = &buf[n..];
            if n == 0 {
                let left = deadline.saturating_duration_since(Instant::now());
                if left.is_zero() {
                    return Err(io::Error::new(
                        io::ErrorKind::TimedOut,
                        "the terminal stopped reading",
                    ));
                }
                wait_writable(self.output_fd(), left)?;
            }
        }
        Ok(())
    }
}

/// Waits until `fd` can be written, or `timeout`.
fn wait_writable(fd: BorrowedFd<'_>, timeout: Duration) -> io::Result<()> {
    poll(&[(fd, Interest::Write)], timeout).map(|_| ())
}

/// Waits until `fd` has input, or `timeout`.
pub fn wait_readable(fd: BorrowedFd<'_>, timeout: Duration) -> io::Result<()> {
    poll(&[(fd, Interest::Read)], timeout).map(|_| ())
}

/// What [`poll`] waits for on a descriptor.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interest {
    /// Readable.
    Read,
    /// Writable.
    Write,
}

/// Waits until one of `fds` is ready as asked, or `timeout`; returns, per
/// descriptor, whether it is ready (a hang-up or an error counts as ready:
/// the next read or write says what happened). At most 8 descriptors.
pub fn poll(fds: &[(BorrowedFd<'_>, Interest)], timeout: Duration) -> io::Result<[bool; 8]> {
    let mut ready = [false; 8];
    let mut list = [libc::pollfd {
        fd: -1,
        events: 0,
        revents: 0,
    }; 8];
    let n = fds.len().min(list.len());
    for (p, (fd, interest)) in list.iter_mut().zip(fds) {
        p.fd = fd.as_raw_fd();
        p.events = match interest {
            Interest::Read => libc::POLLIN,
            Interest::Write => libc::POLLOUT,
        };
    }
    // Rounded up: a wait of half a millisecond must not become a busy loop.
    let ms = timeout.as_micros().div_ceil(1000).min(i32::MAX as u128) as i32;
    // SAFETY: `list` holds `n` initialised pollfds of live, borrowed fds.
    let r = unsafe { libc::poll(list.as_mut_ptr(), n as libc::nfds_t, ms) };
    if r < 0 {
        let e = io::Error::last_os_error();
        return if e.kind() == io::ErrorKind::Interrupted {
            Ok(ready)
        } else {
            Err(e)
        };
    }
    for (r, p) in ready.iter_mut().zip(&list[..n]) {
        *r = p.revents != 0;
    }
    Ok(ready)
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

/// How long restoring may wait for a terminal that has stopped reading.
const RESTORE_TIMEOUT: Duration = Duration::from_millis(500);

/// What the panic hook needs to put the terminal back.
#[derive(Clone, Copy)]
struct Restore {
    input: RawFd,
    output: RawFd,
    full_screen: bool,
}

/// The terminal to restore if the program panics while a [`Screen`] is up.
static ON_PANIC: Mutex<Option<(Restore, Termios)>> = Mutex::new(None);

/// The terminal as `spin` uses it: raw mode and, unless the terminal is
/// dumb, the alternate screen with the cursor hidden; all undone on drop.
pub struct Screen {
    tty: Tty,
    /// Alternate screen and cursor (false on a dumb terminal).
    full_screen: bool,
    /// Whether the terminal is in our modes now (not while suspended).
    entered: bool,
}

impl Screen {
    /// Takes over the terminal.
    pub fn enter(tty: Tty, full_screen: bool) -> io::Result<Screen> {
        let mut s = Screen {
            tty,
            full_screen,
            entered: false,
        };
        s.resume()?;
        Ok(s)
    }

    /// The terminal's descriptor.
    pub fn tty(&self) -> &Tty {
        &self.tty
    }

    /// Puts the terminal back as it was (for a suspend; [`Screen::resume`]
    /// takes it over again).
    pub fn suspend(&mut self) {
        if !self.entered {
            return;
        }
        self.entered = false;
        if self.full_screen {
            let _ = self.tty.write_all(LEAVE, RESTORE_TIMEOUT);
        }
        let _ = self.tty.cooked_mode();
        if let Ok(mut g) = ON_PANIC.lock() {
            *g = None;
        }
    }

    /// Takes the terminal over (again): raw mode, alternate screen, cursor
    /// hidden.
    pub fn resume(&mut self) -> io::Result<()> {
        self.tty.raw_mode(!self.full_screen)?;
        if let Ok(mut g) = ON_PANIC.lock() {
            let restore = Restore {
                input: self.tty.input_fd().as_raw_fd(),
                output: self.tty.output_fd().as_raw_fd(),
                full_screen: self.full_screen,
            };
            *g = Some((restore, self.tty.saved.clone()));
        }
        self.entered = true;
        if self.full_screen {
            self.tty.write_all(ENTER, RESTORE_TIMEOUT)?;
        }
        Ok(())
    }
}

impl Drop for Screen {
    fn drop(&mut self) {
        self.suspend();
    }
}

/// Puts the terminal back before a panic's message is printed, if a
/// [`Screen`] had taken it over.
pub fn install_panic_hook() {
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let taken = ON_PANIC.lock().ok().and_then(|mut g| g.take());
        if let Some((r, saved)) = taken {
            // SAFETY: the descriptors belong to the live Screen (the hook runs
            // before unwinding drops it); borrowed only for these calls.
            let (input, output) = unsafe {
                (
                    BorrowedFd::borrow_raw(r.input),
                    BorrowedFd::borrow_raw(r.output),
                )
            };
            if r.full_screen {
                let _ = wait_writable(output, RESTORE_TIMEOUT);
                let _ = rustix::io::write(output, LEAVE);
            }
            let _ = termios::tcsetattr(input, OptionalActions::Now, &saved);
        }
        previous(info);
    }));
}

#[cfg(test)]
mod tests {
    use super::*;

    fn detect_color(stdout_is_tty: bool, env: impl Fn(&str) -> Option<String>) -> ColorDepth {
        detect_color_why(stdout_is_tty, env).0
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
        let why = |vars: &[(&str, &str)]| detect_color_why(true, env(vars)).1;
        assert_eq!(why(&[("NO_COLOR", "1")]), "NO_COLOR is set");
        assert_eq!(
            detect_color_why(false, env(&[])).1,
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
