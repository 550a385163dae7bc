//! Signal handlers that exist only while the interactive loop runs.
//!
//! `signal-hook` cannot give a signal back: after its last action is
//! unregistered its handler stays installed and the signal is ignored, so a
//! library caller's Ctrl-C would stop working once `spin` returns. These
//! handlers are installed with `sigaction`, the previous actions saved, and
//! put back on drop. A handler does the two async-signal-safe things it
//! must: it sets the signal's bit in a pending mask and writes one byte to a
//! pipe, which wakes the loop's `poll` at once.

use std::io;
use std::os::fd::{AsFd, BorrowedFd, FromRawFd, OwnedFd};
use std::sync::atomic::{AtomicBool, AtomicI32, AtomicU64, Ordering};

/// Signals that arrived and were not yet taken, one bit per signal number.
static PENDING: AtomicU64 = AtomicU64::new(0);
/// The write end of the wake-up pipe (−1: none).
static WAKE: AtomicI32 = AtomicI32::new(-1);
/// Whether a [`Signals`] is alive (there can be one at a time).
static INSTALLED: AtomicBool = AtomicBool::new(false);

/// Where this thread's `errno` is: each libc names it its own way.
fn errno_location() -> *mut libc::c_int {
    // SAFETY: each returns the calling thread's errno, always valid.
    unsafe {
        #[cfg(any(target_os = "linux", target_os = "emscripten", target_os = "redox"))]
        return libc::__errno_location();
        #[cfg(any(
            target_vendor = "apple",
            target_os = "freebsd",
            target_os = "dragonfly"
        ))]
        return libc::__error();
        #[cfg(any(target_os = "android", target_os = "netbsd", target_os = "openbsd"))]
        return libc::__errno();
        #[cfg(any(target_os = "solaris", target_os = "illumos"))]
        return libc::___errno();
    }
}

extern "C" fn on_signal(sig: libc::c_int) {
    // SAFETY: errno is thread-local; saving and restoring it keeps the
    // interrupted code's value. write(2) is async-signal-safe.
    unsafe {
        let errno = *errno_location();
        PENDING.fetch_or(1 << (sig as u64 & 63), Ordering::SeqCst);
        let fd = WAKE.load(Ordering::SeqCst);
        if fd >= 0 {
            let byte = sig as u8;
            libc::write(fd, (&byte as *const u8).cast(), 1);
        }
        *errno_location() = errno;
    }
}

/// Our handlers for a set of signals, the previous ones restored on drop.
pub struct Signals {
    read: OwnedFd,
    /// Kept open for the handler (which writes to it by number).
    _write: OwnedFd,
    saved: Vec<(libc::c_int, libc::sigaction)>,
}

impl Signals {
    /// Installs handlers for `signals`. Fails if another `Signals` is alive.
    pub fn install(signals: &[libc::c_int]) -> io::Result<Signals> {
        if INSTALLED.swap(true, Ordering::SeqCst) {
            return Err(io::Error::other("signal handlers are already installed"));
        }
        let (read, write) = match wake_pipe() {
            Ok(ends) => ends,
            Err(e) => {
                INSTALLED.store(false, Ordering::SeqCst);
                return Err(e);
            }
        };
        let fds = [fd_of(&read), fd_of(&write)];
        WAKE.store(fds[1], Ordering::SeqCst);
        PENDING.store(0, Ordering::SeqCst);
        let mut s = Signals {
            read,
            _write: write,
            saved: Vec::with_capacity(signals.len()),
        };
        for &sig in signals {
            let old = set_action(sig, on_signal as *const () as libc::sighandler_t)?;
            s.saved.push((sig, old));
        }
        Ok(s)
    }

    /// The signals that arrived since the last call, as a bit mask
    /// (bit `n` for signal `n`); empties the wake-up pipe.
    pub fn take(&self) -> u64 {
        let mut buf = [0u8; 64];
        // SAFETY: reading into a local buffer from our own non-blocking fd.
        while unsafe { libc::read(fd_of(&self.read), buf.as_mut_ptr().cast(), buf.len()) } > 0 {}
        PENDING.swap(0, Ordering::SeqCst)
    }

    /// Puts signals taken by [`Signals::take`] back, for the next take.
    pub fn keep(&self, mask: u64) {
        PENDING.fetch_or(mask, Ordering::SeqCst);
    }

    /// What `poll` waits on: readable when a signal arrived.
    pub fn fd(&self) -> BorrowedFd<'_> {
        self.read.as_fd()
    }

    /// Stops the process as the default action of SIGTSTP would, and
    /// returns once it is continued (SIGCONT), with our handler back.
    pub fn stop_self(&self) -> io::Result<()> {
        let ours = set_action(libc::SIGTSTP, libc::SIG_DFL)?;
        // SAFETY: raising a signal whose action is now the default (stop).
        let r = unsafe { libc::raise(libc::SIGTSTP) };
        // Continued: put our handler back, whatever raise said.
        // SAFETY: restoring the action read above.
        unsafe { libc::sigaction(libc::SIGTSTP, &ours, std::ptr::null_mut()) };
        if r != 0 {
            return Err(io::Error::last_os_error());
        }
        Ok(())
    }
}

impl Drop for Signals {
    fn drop(&mut self) {
        for (sig, old) in self.saved.drain(..).rev() {
            // SAFETY: putting back the action that was there before us.
            unsafe { libc::sigaction(sig, &old, std::ptr::null_mut()) };
        }
        WAKE.store(-1, Ordering::SeqCst);
        INSTALLED.store(false, Ordering::SeqCst);
    }
}

/// A pipe whose ends close on exec and never block (POSIX `pipe`, then
/// `fcntl`: macOS has no `pipe2`).
fn wake_pipe() -> io::Result<(OwnedFd, OwnedFd)> {
    let mut fds = [0; 2];
    // SAFETY: a valid two-element array; both ends are owned below.
    if unsafe { libc::pipe(fds.as_mut_ptr()) } != 0 {
        return Err(io::Error::last_os_error());
    }
    // SAFETY: pipe returned two fresh descriptors that nothing else owns.
    let ends = unsafe { (OwnedFd::from_raw_fd(fds[0]), OwnedFd::from_raw_fd(fds[1])) };
    for fd in fds {
        // SAFETY: flags of descriptors owned by `ends`.
        let ok = unsafe {
            libc::fcntl(fd, libc::F_SETFD, libc::FD_CLOEXEC) == 0
                && libc::fcntl(
                    fd,
                    libc::F_SETFL,
                    libc::fcntl(fd, libc::F_GETFL) | libc::O_NONBLOCK,
                ) == 0
        };
        if !ok {
            return Err(io::Error::last_os_error());
        }
    }
    Ok(ends)
}

fn fd_of(fd: &OwnedFd) -> libc::c_int {
    use std::os::fd::AsRawFd;
    fd.as_raw_fd()
}

/// Sets the action of `sig` to `handler` (a function or `SIG_DFL`) and
/// returns the previous action.
fn set_action(sig: libc::c_int, handler: libc::sighandler_t) -> io::Result<libc::sigaction> {
    // SAFETY: zeroed sigaction structs are valid; the mask is emptied before
    // use and the handler is an extern "C" fn(c_int) or SIG_DFL.
    unsafe {
        let mut new: libc::sigaction = std::mem::zeroed();
        new.sa_sigaction = handler;
        new.sa_flags = libc::SA_RESTART;
        libc::sigemptyset(&mut new.sa_mask);
        let mut old: libc::sigaction = std::mem::zeroed();
        if libc::sigaction(sig, &new, &mut old) != 0 {
            return Err(io::Error::last_os_error());
        }
        Ok(old)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn handlers_catch_and_are_given_back() {
        // SIGUSR2's default action would end the test process: while
        // installed it is caught; after drop the previous action is back.
        let before = unsafe {
            let mut old: libc::sigaction = std::mem::zeroed();
            libc::sigaction(libc::SIGUSR2, std::ptr::null(), &mut old);
            old.sa_sigaction
        };
        let s = Signals::install(&[libc::SIGUSR2]).unwrap();
        assert!(Signals::install(&[libc::SIGUSR2]).is_err(), "one at a time");
        unsafe { libc::raise(libc::SIGUSR2) };
        let mask = s.take();
        assert!(super::super::has_signal(mask, libc::SIGUSR2));
        assert_eq!(s.take(), 0);
        drop(s);
        let after = unsafe {
            let mut old: libc::sigaction = std::mem::zeroed();
            libc::sigaction(libc::SIGUSR2, std::ptr::null(), &mut old);
            old.sa_sigaction
        };
        assert_eq!(after, before);
        assert!(Signals::install(&[]).is_ok(), "free again");
    }
}
