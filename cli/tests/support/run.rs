//! Running the `rastty` binary and taking its own peak memory (`wait4`),
//! for the tests that hold a program to a memory bound.
//!
//! A child's peak as the kernel reports it starts from its parent's
//! resident size when it was spawned (the address space it was made from
//! counts until `exec`): a test that measures keeps its own memory small
//! (big inputs are written to files in pieces, not held).

#![allow(dead_code)]

use std::io::Read;
use std::os::unix::process::ExitStatusExt;
use std::process::{Command, Stdio};

/// What a run of the binary gave.
pub struct Run {
    /// The exit code (`None`: ended by a signal).
    pub code: Option<i32>,
    /// The signal that ended it, if one did.
    pub signal: Option<i32>,
    pub stdout: Vec<u8>,
    pub stderr: String,
    /// The child's own peak resident memory, in bytes.
    pub peak: u64,
}

/// Runs `rastty ARGS` with `TERM=xterm-256color`, its stdout and stderr
/// read, and its own resource use taken with `wait4`.
pub fn run(args: &[&str]) -> Run {
    run_with(args, |_| {})
}

pub fn run_with(args: &[&str], setup: impl FnOnce(&mut Command)) -> Run {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_rastty"));
    cmd.args(args)
        .env("TERM", "xterm-256color")
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    setup(&mut cmd);
    // Reaped by wait4 below, which gives its resource use.
    #[allow(clippy::zombie_processes)]
    let mut child = cmd.spawn().unwrap();
    let mut out = child.stdout.take();
    let mut err = child.stderr.take();
    let reader = std::thread::spawn(move || {
        let mut o = Vec::new();
        if let Some(out) = out.as_mut() {
            out.read_to_end(&mut o).unwrap();
        }
        o
    });
    let mut stderr = Vec::new();
    if let Some(err) = err.as_mut() {
        err.read_to_end(&mut stderr).unwrap();
    }
    let stdout = reader.join().unwrap();
    let mut status = 0;
    // SAFETY: a zeroed rusage is valid; wait4 fills it for this child.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: waiting for our own child, with pointers to live values.
    let pid = unsafe { libc::wait4(child.id() as i32, &mut status, 0, &mut usage) };
    assert_eq!(pid, child.id() as i32);
    let status = std::process::ExitStatus::from_raw(status);
    Run {
        code: status.code(),
        signal: status.signal(),
        stdout,
        stderr: String::from_utf8(stderr).unwrap(),
        peak: usage.ru_maxrss as u64 * 1024,
    }
}
