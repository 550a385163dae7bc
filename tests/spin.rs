//! `rastty spin`: the frames it writes when stdout is not a terminal, and
//! the terminal it leaves behind when it is one (a pseudo-terminal run by
//! `expectrl`), whichever way it ends.

mod common;

use std::io::Read;
use std::process::Command;
use std::time::Duration;

use common::{as_displayed, terminal};
use expectrl::Expect;
use expectrl::session::OsSession as Session;

const BIN: &str = env!("CARGO_BIN_EXE_rastty");

fn run(args: &[&str]) -> Vec<u8> {
    let out = Command::new(BIN)
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
}

/// The cells of a screen as text, foreground and background.
fn cells(screen: &vt100::Screen) -> Vec<(String, vt100::Color, vt100::Color)> {
    let (rows, cols) = screen.size();
    let mut v = Vec::new();
    for r in 0..rows.get() {
        for c in 0..cols.get() {
            let cell = screen.cell(r, c).unwrap();
            let text = if cell.contents().is_empty() {
                " ".to_string()
            } else {
                cell.contents().to_string()
            };
            let fg = if text == " " {
                vt100::Color::Default
            } else {
                cell.fgcolor()
            };
            v.push((text, fg, cell.bgcolor()));
        }
    }
    v
}

#[test]
fn spin_frames_replayed_end_on_render_at_the_last_angle() {
    let view = [
        "--cols",
        "40",
        "--rows",
        "12",
        "--color",
        "truecolor",
        "--glyphs",
        "half",
    ];
    let stream = run(&[
        &["spin", "--frames", "12", "--step", "7.5", "--axis", "y"][..],
        &view,
    ]
    .concat());
    let mut spun = terminal(12, 40);
    spun.process(&stream);

    // Frame 11 is turned by 11 · 7.5 = 82.5 degrees.
    let lines = run(&[&["render", "--yaw", "82.5"][..], &view].concat());
    let mut rendered = terminal(12, 40);
    rendered.process(&as_displayed(&lines));

    assert_eq!(cells(spun.screen()), cells(rendered.screen()));
    // And the stream is deterministic.
    assert_eq!(
        stream,
        run(&[
            &["spin", "--frames", "12", "--step", "7.5", "--axis", "y"][..],
            &view
        ]
        .concat())
    );
}

#[test]
fn spin_without_a_terminal_needs_frames() {
    let out = Command::new(BIN).args(["spin"]).output().unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.starts_with("error: spin: stdout is not a terminal"),
        "{err}"
    );
}

/// Spawns `rastty spin ARGS` in an 80×24 pseudo-terminal.
fn spawn(args: &[&str]) -> Session {
    let mut cmd = Command::new(BIN);
    cmd.args(["spin", "--cols", "60", "--rows", "20"])
        .args(args);
    cmd.env("TERM", "xterm-256color");
    let mut session = Session::spawn(cmd).expect("a pty");
    session.get_process_mut().set_window_size(80, 24).unwrap();
    session.set_expect_timeout(Some(Duration::from_secs(20)));
    session
}

/// Reads everything the session writes until it closes.
fn drain(session: &mut Session, mut seen: Vec<u8>) -> Vec<u8> {
    let mut buf = [0u8; 4096];
    loop {
        match session.read(&mut buf) {
            Ok(0) | Err(_) => return seen,
            Ok(n) => seen.extend_from_slice(&buf[..n]),
        }
    }
}

/// The exit code, after the output is drained.
fn exit_code(session: &Session) -> i32 {
    match session.get_process().wait().unwrap() {
        expectrl::process::unix::WaitStatus::Exited(_, code) => code,
        other => panic!("{other:?}"),
    }
}

/// The terminal the output leaves: main screen, cursor shown.
fn assert_restored(output: &[u8]) {
    let mut vt = terminal(24, 80);
    vt.process(output);
    assert!(!vt.screen().alternate_screen(), "left the alternate screen");
    assert!(!vt.screen().hide_cursor(), "the cursor is shown");
    let text = String::from_utf8_lossy(output);
    assert!(
        text.contains("\x1b[?1049h"),
        "it entered the alternate screen"
    );
    assert!(text.contains("\x1b[?2026h"), "it drew frames");
}

/// Waits for the first frame; returns what was read so far.
fn first_frame(session: &mut Session) -> Vec<u8> {
    let found = session.expect("\x1b[?2026l").expect("a first frame");
    found
        .before()
        .iter()
        .chain(found.get(0).unwrap())
        .copied()
        .collect()
}

#[test]
fn spin_for_twenty_frames_in_a_terminal_exits_and_restores_it() {
    let mut s = spawn(&["--frames", "20", "--fps", "60"]);
    let out = drain(&mut s, Vec::new());
    assert_eq!(exit_code(&s), 0);
    assert_restored(&out);
}

#[test]
fn q_quits_and_restores_the_terminal() {
    let mut s = spawn(&[]);
    let seen = first_frame(&mut s);
    s.send("q").unwrap();
    let out = drain(&mut s, seen);
    assert_eq!(exit_code(&s), 0);
    assert_restored(&out);
}

#[test]
fn sigterm_and_sighup_restore_the_terminal() {
    for (signal, code) in [
        (expectrl::process::unix::Signal::SIGTERM, 128 + 15),
        (expectrl::process::unix::Signal::SIGHUP, 128 + 1),
    ] {
        let mut s = spawn(&["--hud"]);
        let seen = first_frame(&mut s);
        s.get_process_mut().signal(signal).unwrap();
        let out = drain(&mut s, seen);
        assert_eq!(exit_code(&s), code, "{signal:?}");
        assert_restored(&out);
    }
}

#[test]
fn a_bad_model_is_reported_before_the_terminal_is_touched() {
    let mut s = spawn(&["tests/data/short-face.obj"]);
    let out = drain(&mut s, Vec::new());
    assert_eq!(exit_code(&s), 1);
    let text = String::from_utf8_lossy(&out);
    assert!(
        text.contains("error: tests/data/short-face.obj:4:1: a face needs at least 3 vertices"),
        "{text:?}"
    );
    assert!(
        !text.contains("\x1b[?1049h"),
        "the alternate screen was never entered"
    );
    assert!(!text.contains("\x1b[?25l"), "the cursor was never hidden");
}
