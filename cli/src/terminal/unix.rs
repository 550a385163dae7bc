//! The terminal on unix (Linux, macOS, the BSDs): raw mode and sizes by
//! crossterm; keys, mouse reports and the answers to queries read as bytes
//! from `/dev/tty` by rastty itself, and frames written to the terminal
//! without blocking; one `poll` waits on both and on the signal pipe.
//!
//! **Why rastty reads the tty itself.** The loop must read a key whatever
//! its pacing, read the answers to its queries within a deadline (the glyph
//! probe, the status request after each frame), write without blocking on
//! a slow link, and hand signals back when it ends (`signals.rs`).
//! crossterm's event reader does none of the first two (its `/dev/tty`
//! source does not read on a zero timeout, and it offers no way to read a
//! query's answer within a deadline), so here it is used for what it does
//! (raw mode, the window's size) and the bytes are rastty's.
//!
//! **The controlling terminal.** Keys are read from `/dev/tty`, so `spin`
//! needs a controlling terminal even when stdout is one (`setsid rastty
//! spin` has none, and is told so). Frames go to the terminal stdout names,
//! through a descriptor of rastty's own (opened anew, so that making it
//! non-blocking never touches the shell's stdout).
//!
//! **Restoring.** [`Screen`] puts the terminal in raw mode on the alternate
//! screen with the cursor hidden, and puts everything back when dropped, on
//! a panic ([`install_panic_hook`]), and before a suspend.

use std::io;
use std::os::fd::{AsFd, AsRawFd, BorrowedFd, OwnedFd, RawFd};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use rustix::fs::{Mode, OFlags};
use rustix::termios;

use super::input::{Input, Parser};
use super::probe::{self, Capabilities};
use super::signals::Signals;
use super::{ENTER, LEAVE, Read, TtyError, WindowSize, tty_err};

/// Signal numbers, as the loop knows them.
pub mod sig {
    pub const HUP: i32 = libc::SIGHUP;
    pub const INT: i32 = libc::SIGINT;
    pub const QUIT: i32 = libc::SIGQUIT;
    pub const TERM: i32 = libc::SIGTERM;
    pub const USR1: i32 = libc::SIGUSR1;
    pub const USR2: i32 = libc::SIGUSR2;
    pub const ALRM: i32 = libc::SIGALRM;
    pub const PIPE: i32 = libc::SIGPIPE;
    pub const XCPU: i32 = libc::SIGXCPU;
    pub const XFSZ: i32 = libc::SIGXFSZ;
    pub const TSTP: i32 = libc::SIGTSTP;
    pub const CONT: i32 = libc::SIGCONT;
    pub const WINCH: i32 = libc::SIGWINCH;
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

/// The size of the terminal `fd` is, if it is one.
fn size_of(fd: BorrowedFd<'_>) -> Option<WindowSize> {
    let ws = termios::tcgetwinsize(fd).ok()?;
    (ws.ws_col > 0 && ws.ws_row > 0).then_some(WindowSize {
        cols: ws.ws_col,
        rows: ws.ws_row,
        width_px: ws.ws_xpixel,
        height_px: ws.ws_ypixel,
    })
}

/// The controlling terminal, open for reading keys, and the terminal stdout
/// names, open for writing frames; both non-blocking.
pub struct Tty {
    input: OwnedFd,
    /// A descriptor of our own for stdout's terminal, when it is not the
    /// controlling one (`None`: frames go to `input`, the same terminal).
    output: Option<OwnedFd>,
}

impl Tty {
    /// Opens `/dev/tty`, and stdout's terminal if it is another one.
    pub fn open() -> Result<Tty, TtyError> {
        use std::io::IsTerminal;
        let flags = OFlags::RDWR | OFlags::NOCTTY | OFlags::CLOEXEC | OFlags::NONBLOCK;
        let input = rustix::fs::open("/dev/tty", flags, Mode::empty())
            .map_err(|e| TtyError::NoControllingTerminal(e.into()))?;
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
        Ok(Tty { input, output })
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
        size_of(self.output_fd()).or_else(|| size_of(self.input_fd()))
    }

    /// Raw mode (crossterm's): keys one at a time, no echo, no signals from
    /// keys (Ctrl-C and Ctrl-Z arrive as bytes). With `output_processing`,
    /// `\n` still starts a new line at column 0 (for plain lines on a dumb
    /// terminal).
    pub fn raw_mode(&self, output_processing: bool) -> io::Result<()> {
        crossterm::terminal::enable_raw_mode()?;
        if output_processing {
            let mut t = termios::tcgetattr(&self.input)?;
            t.output_modes |= termios::OutputModes::OPOST | termios::OutputModes::ONLCR;
            termios::tcsetattr(&self.input, termios::OptionalActions::Now, &t)?;
        }
        Ok(())
    }

    /// The modes the terminal had before raw mode.
    pub fn cooked_mode(&self) -> io::Result<()> {
        crossterm::terminal::disable_raw_mode()
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

/// How long restoring may wait for a terminal that has stopped reading.
const RESTORE_TIMEOUT: Duration = Duration::from_millis(500);

/// What the panic hook needs to put the terminal back.
#[derive(Clone, Copy)]
struct Restore {
    output: RawFd,
    full_screen: bool,
}

/// The terminal to restore if the program panics while a [`Screen`] is up.
static ON_PANIC: Mutex<Option<Restore>> = Mutex::new(None);

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
            *g = Some(Restore {
                output: self.tty.output_fd().as_raw_fd(),
                full_screen: self.full_screen,
            });
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
        if let Some(r) = taken {
            // SAFETY: the descriptor belongs to the live Screen (the hook
            // runs before unwinding drops it); borrowed only for this call.
            let output = unsafe { BorrowedFd::borrow_raw(r.output) };
            if r.full_screen {
                let _ = wait_writable(output, RESTORE_TIMEOUT);
                let _ = rustix::io::write(output, LEAVE);
            }
            let _ = crossterm::terminal::disable_raw_mode();
        }
        previous(info);
    }));
}

/// The terminal as the interactive loop has it: the [`Screen`], and the
/// signal handlers that exist while it runs (dropped after the screen, so
/// the terminal is restored while the handlers are still ours).
pub struct Session {
    screen: Screen,
    signals: Signals,
}

impl Session {
    /// Opens the terminal, installs handlers for `handled`, and takes the
    /// terminal over (the alternate screen with `full_screen`).
    pub fn open(full_screen: bool, handled: &[i32]) -> Result<Session, TtyError> {
        let tty = Tty::open()?;
        let signals = Signals::install(handled).map_err(tty_err("installing signal handlers"))?;
        let screen = Screen::enter(tty, full_screen).map_err(tty_err("entering raw mode"))?;
        Ok(Session { screen, signals })
    }

    /// Whether the terminal's answers to queries can be read (they come as
    /// bytes with the keys).
    pub fn reads_answers(&self) -> bool {
        true
    }

    /// Asks the terminal what it draws ([`probe::probe`]); what else it
    /// sent meanwhile goes to `early`.
    pub fn probe(
        &mut self,
        parser: &mut Parser,
        early: &mut Vec<Input>,
    ) -> io::Result<Capabilities> {
        probe::probe(self.screen.tty(), parser, early, probe::DEADLINE)
    }

    /// Reads what the terminal sent, without waiting, into `inputs`
    /// (through `parser`): whether anything came, or the terminal is gone.
    pub fn read(&mut self, parser: &mut Parser, inputs: &mut Vec<Input>) -> Read {
        let mut buf = [0u8; 1024];
        let mut got = Read::Nothing;
        loop {
            match self.screen.tty().read(&mut buf) {
                Read::Bytes(n) => {
                    parser.feed(&buf[..n], inputs);
                    got = Read::Bytes(n);
                }
                Read::Nothing => return got,
                Read::Gone => return Read::Gone,
            }
        }
    }

    /// Writes what the terminal takes now, without waiting.
    pub fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.screen.tty().write(buf)
    }

    /// Writes all of `buf`, waiting for the terminal at most `timeout`.
    pub fn write_all(&mut self, buf: &[u8], timeout: Duration) -> io::Result<()> {
        self.screen.tty().write_all(buf, timeout)
    }

    /// The terminal's size.
    pub fn size(&self) -> Option<WindowSize> {
        self.screen.tty().size()
    }

    /// Waits for a key, a signal, or (while `sending`) room to write, at
    /// most `timeout`.
    pub fn wait(&self, sending: bool, timeout: Duration) -> io::Result<()> {
        let tty = self.screen.tty();
        let fds = [
            (tty.input_fd(), Interest::Read),
            (self.signals.fd(), Interest::Read),
            (tty.output_fd(), Interest::Write),
        ];
        poll(&fds[..if sending { 3 } else { 2 }], timeout).map(|_| ())
    }

    /// Waits at most `timeout` for something to read.
    pub fn wait_input(&self, timeout: Duration) -> io::Result<()> {
        wait_readable(self.screen.tty().input_fd(), timeout)
    }

    /// The signals that came since the last call, a bit each
    /// ([`super::has_signal`]).
    pub fn take_signals(&self) -> u64 {
        self.signals.take()
    }

    /// Puts signals taken back, for the next [`Session::take_signals`].
    pub fn keep_signals(&self, mask: u64) {
        self.signals.keep(mask);
    }

    /// Whether the process can be suspended (job control).
    pub fn can_suspend(&self) -> bool {
        true
    }

    /// Restores the terminal and stops the process, as Ctrl-Z would;
    /// returns once it is continued, the terminal still restored.
    pub fn stop(&mut self) -> io::Result<()> {
        self.screen.suspend();
        self.signals.stop_self()
    }

    /// Takes the terminal over again after [`Session::stop`], or after a
    /// SIGCONT.
    pub fn resume(&mut self) -> io::Result<()> {
        self.screen.resume()
    }
}

/// The size of the terminal stdout writes to, if it is one: its own (cells
/// and pixels, asked of stdout's descriptor, which may be another terminal
/// than the controlling one), else crossterm's.
pub fn stdout_size() -> Option<WindowSize> {
    use std::io::IsTerminal;
    let out = io::stdout();
    if !out.is_terminal() {
        return None;
    }
    size_of(out.as_fd()).or_else(super::crossterm_size)
}
