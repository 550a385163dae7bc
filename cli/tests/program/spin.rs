//! `rastty spin`: the frames it writes when stdout is not a terminal, and
//! the terminal it leaves behind when it is one (a pseudo-terminal run by
//! `expectrl`), whichever way it ends.

use crate::common;

use std::io::{Read, Write};
use std::process::Command;
use std::time::Duration;

use common::{as_displayed, cells, terminal};
use expectrl::Expect;
use expectrl::session::OsSession as Session;

const BIN: &str = env!("CARGO_BIN_EXE_rastty");
/// The repository's root, where the README's commands run and the models live.
const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/..");

fn run(args: &[&str]) -> Vec<u8> {
    let out = Command::new(BIN)
        .args(args)
        .current_dir(ROOT)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
}

/// The view both `spin` and `render` draw in, to compare their frames.
const VIEW: [&str; 8] = [
    "--cols",
    "40",
    "--rows",
    "12",
    "--color",
    "truecolor",
    "--glyphs",
    "half",
];

#[test]
fn spin_frames_replayed_end_on_render_at_the_last_angle() {
    let view = VIEW;
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

/// A model that moves: frame k of `spin` shows its clip at k / fps
/// seconds, as `render --time` draws it.
#[test]
fn spin_frames_of_a_moving_model_end_on_render_at_their_time() {
    let view = VIEW;
    let arm = "examples/models/arm.glb";
    // Frame 45 at 30 frames a second is 1.5 s in; the turn held still.
    let stream = run(&[&["spin", arm, "--frames", "46", "--step", "0"][..], &view].concat());
    let mut spun = terminal(12, 40);
    spun.process(&stream);
    let at = |time: &str| {
        let lines = run(&[&["render", arm, "--time", time][..], &view].concat());
        let mut rendered = terminal(12, 40);
        rendered.process(&as_displayed(&lines));
        cells(rendered.screen())
    };
    assert_eq!(cells(spun.screen()), at("1.5"));
    assert_ne!(at("1.5"), at("0"));
    // Half speed: frame 45 is 0.75 s in.
    let slow = run(&[
        &[
            "spin", arm, "--frames", "46", "--step", "0", "--speed", "0.5",
        ][..],
        &view,
    ]
    .concat());
    let mut spun = terminal(12, 40);
    spun.process(&slow);
    assert_eq!(cells(spun.screen()), at("0.75"));
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
        .args(args)
        .current_dir(ROOT);
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
    assert_eq!(
        vt.screen().mouse_protocol_mode(),
        vt100::MouseProtocolMode::None,
        "mouse reports are off"
    );
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
fn a_recording_in_a_terminal_replays_to_the_render_at_the_last_angle() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("live-cast");
    std::fs::create_dir_all(&dir).unwrap();
    let cast = dir.join("live.cast");
    let _ = std::fs::remove_file(&cast);
    let view = ["--color", "truecolor", "--glyphs", "half", "--step", "7.5"];
    let mut s = spawn(
        &[
            &["--frames", "16", "--fps", "60", "--no-probe", "--record"][..],
            &[cast.to_str().unwrap()],
            &view,
        ]
        .concat(),
    );
    drain(&mut s, Vec::new());
    assert_eq!(exit_code(&s), 0);

    let text = std::fs::read_to_string(&cast).unwrap();
    let mut lines = text.lines();
    let header: serde_json::Value = serde_json::from_str(lines.next().unwrap()).unwrap();
    assert_eq!(
        (
            header["version"].as_u64(),
            header["width"].as_u64(),
            header["height"].as_u64()
        ),
        (Some(2), Some(60), Some(20))
    );
    // One more row than the recording: its end moves the cursor below
    // the picture and shows it.
    let mut vt = terminal(21, 60);
    let mut last = 0.0;
    let mut end = String::new();
    for line in lines {
        let (t, code, data): (f64, String, String) = serde_json::from_str(line).unwrap();
        assert_eq!(code, "o");
        assert!(t >= last, "times go forward: {last} then {t}");
        last = t;
        vt.process(data.as_bytes());
        end = data;
    }
    assert_eq!(end, "\x1b[0m\x1b[20;1H\r\n\x1b[?25h");
    assert_eq!(vt.screen().cursor_position(), (20, 0));
    assert!(!vt.screen().hide_cursor());
    // Frames the loop was late for may be missing, the last never is: it
    // is turned by 15 · 7.5 = 112.5 degrees.
    let lines = run(&[
        "render",
        "--yaw",
        "112.5",
        "--cols",
        "60",
        "--rows",
        "20",
        "--color",
        "truecolor",
        "--glyphs",
        "half",
    ]);
    let mut rendered = terminal(21, 60);
    rendered.process(&as_displayed(&lines));
    assert_eq!(cells(vt.screen()), cells(rendered.screen()));
}

#[test]
fn c_reaches_truecolor_where_the_environment_says_256() {
    let mut cmd = Command::new(BIN);
    cmd.args([
        "spin",
        "--cols",
        "60",
        "--rows",
        "20",
        "--step",
        "0",
        "--no-probe",
    ])
    .env("TERM", "xterm-256color")
    .env_remove("COLORTERM")
    .env_remove("NO_COLOR");
    let mut s = Session::spawn(cmd).expect("a pty");
    s.get_process_mut().set_window_size(80, 24).unwrap();
    s.set_expect_timeout(Some(Duration::from_secs(20)));
    let first = first_frame(&mut s);
    assert!(
        !String::from_utf8_lossy(&first).contains("[38;2;"),
        "256 colours at first"
    );
    s.send("c").unwrap();
    s.expect("[38;2;").expect("truecolor after c");
    s.send("q").unwrap();
    drain(&mut s, Vec::new());
    assert_eq!(exit_code(&s), 0);
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
fn other_signals_restore_the_terminal_then_take_their_default_action() {
    use expectrl::process::unix::{Signal, WaitStatus};
    for signal in [Signal::SIGUSR1, Signal::SIGALRM, Signal::SIGXFSZ] {
        let mut s = spawn(&[]);
        let seen = first_frame(&mut s);
        s.get_process_mut().signal(signal).unwrap();
        let out = drain(&mut s, seen);
        match s.get_process().wait().unwrap() {
            WaitStatus::Signaled(_, sig, _) => assert_eq!(sig, signal),
            other => panic!("{signal:?}: {other:?}"),
        }
        assert_restored(&out);
    }
}

#[test]
fn a_suspended_spin_ends_on_kill_without_taking_the_terminal_back() {
    // A shell with job control, as a user has: Ctrl-Z stops spin, and
    // `kill %1` sends SIGTERM (and SIGCONT) to the stopped job.
    let mut cmd = Command::new("bash");
    cmd.args(["--norc", "--noprofile", "-i"])
        .env("TERM", "xterm-256color")
        .env("PS1", "$ ");
    let mut s = Session::spawn(cmd).expect("a pty");
    s.get_process_mut().set_window_size(80, 24).unwrap();
    s.set_expect_timeout(Some(Duration::from_secs(20)));
    s.send_line(format!("{BIN} spin --cols 60 --rows 20"))
        .unwrap();
    s.expect("\x1b[?2026l").expect("a first frame");
    s.send("\x1a").unwrap();
    let stopped = s.expect("Stopped").expect("spin stopped");
    // Suspended, it gave the terminal back: main screen, no mouse reports.
    let mut vt = terminal(24, 80);
    vt.process(stopped.before());
    assert!(!vt.screen().alternate_screen());
    assert_eq!(
        vt.screen().mouse_protocol_mode(),
        vt100::MouseProtocolMode::None
    );
    let bash = s.get_process().pid().as_raw() as u32;
    let spin = children(bash)[0];
    assert_eq!(process_state(spin), Some('T'), "stopped");
    s.send_line("kill %1").unwrap();
    // Ended (gone, or a zombie for bash to reap): not stopped again, as it
    // was when it took the terminal back from the background.
    let end = std::time::Instant::now() + Duration::from_secs(20);
    while !matches!(process_state(spin), None | Some('Z')) {
        assert!(
            std::time::Instant::now() < end,
            "spin is still there, in state {:?}",
            process_state(spin)
        );
    }
    s.send_line("exit").unwrap();
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

/// A terminal played by the test: it reads what `spin` writes (at most
/// `rate` bytes a second, if given), answers its status requests and
/// cursor position requests as told, and records when each byte arrived.
struct Fake {
    session: Session,
    seen: Vec<u8>,
    /// Where the next query is looked for.
    scanned: usize,
    /// Columns to report for successive position requests (then 2).
    cpr_cols: Vec<u16>,
    /// Whether position and status requests are answered at all.
    answer: bool,
    /// How DECRQSS of the SGR after a 24-bit colour is answered: keeping
    /// it (`Some(true)`), mapped to the 256-colour palette (`Some(false)`),
    /// or not at all.
    rgb: Option<bool>,
    rate: Option<f64>,
    /// Bytes the rate allows now, and when that was reckoned.
    tokens: f64,
    last_pump: f64,
    start: std::time::Instant,
    eof: bool,
}

impl Fake {
    fn spawn(args: &[&str], answer: bool, cpr_cols: &[u16], rate: Option<f64>) -> Fake {
        let mut cmd = Command::new(BIN);
        cmd.arg("spin").args(args).current_dir(ROOT);
        cmd.env("TERM", "xterm-256color").env_remove("COLORTERM");
        let mut session = Session::spawn(cmd).expect("a pty");
        session.get_process_mut().set_window_size(80, 24).unwrap();
        Fake {
            session,
            seen: Vec::new(),
            scanned: 0,
            cpr_cols: cpr_cols.iter().rev().copied().collect(),
            answer,
            rgb: None,
            rate,
            tokens: 0.0,
            last_pump: 0.0,
            start: std::time::Instant::now(),
            eof: false,
        }
    }

    fn elapsed(&self) -> Duration {
        self.start.elapsed()
    }

    /// Reads what is there (within the rate), answers new queries; returns
    /// whether anything was read.
    fn pump(&mut self) -> bool {
        let mut buf = [0u8; 4096];
        let budget = match self.rate {
            // A token bucket holding 50 ms of the rate: an idle link does
            // not save up for a burst.
            Some(r) => {
                let now = self.elapsed().as_secs_f64();
                self.tokens = (self.tokens + (now - self.last_pump) * r).min(r * 0.05);
                self.last_pump = now;
                (self.tokens as usize).min(buf.len())
            }
            None => buf.len(),
        };
        if self.eof {
            return false;
        }
        if budget == 0 {
            // The slow link is slow in real time, as `spin` measures it:
            // the time until the bucket holds a byte. (How the rate is
            // measured is tested on a fake clock, in `live`.)
            let r = self.rate.unwrap_or(f64::INFINITY);
            std::thread::sleep(Duration::from_secs_f64((1.0 - self.tokens).max(0.0) / r));
            return false;
        }
        let n = match self.session.try_read(&mut buf[..budget]) {
            Ok(0) => {
                self.eof = true;
                0
            }
            Ok(n) => n,
            Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => 0,
            Err(_) => {
                self.eof = true;
                0
            }
        };
        if n == 0 {
            // Nothing yet: wait until the program writes (or 50 ms pass,
            // for the caller to look at its own time limit).
            self.wait_readable(Duration::from_millis(50));
            return false;
        }
        self.tokens -= n as f64;
        self.seen.extend_from_slice(&buf[..n]);
        self.answer_queries();
        true
    }

    /// Waits until the terminal has something to read, at most `timeout`.
    fn wait_readable(&self, timeout: Duration) {
        use std::os::fd::AsRawFd;
        let mut fd = libc::pollfd {
            fd: self.session.as_raw_fd(),
            events: libc::POLLIN,
            revents: 0,
        };
        // SAFETY: one valid pollfd, for the call's duration.
        unsafe { libc::poll(&mut fd, 1, timeout.as_millis() as libc::c_int) };
    }

    fn answer_queries(&mut self) {
        loop {
            let rest = &self.seen[self.scanned..];
            let next = [&b"\x1b[6n"[..], b"\x1b[5n", b"\x1bP$qm"]
                .iter()
                .filter_map(|q| find(rest, q).map(|i| (i, q.len(), q[2])))
                .min();
            let Some((i, len, kind)) = next else {
                self.scanned = self.seen.len().saturating_sub(5).max(self.scanned);
                return;
            };
            self.scanned += i + len;
            if !self.answer {
                continue;
            }
            let reply = match kind {
                b'6' => format!("\x1b[1;{}R", self.cpr_cols.pop().unwrap_or(2)),
                b'5' => "\x1b[0n".to_string(),
                _ => match self.rgb {
                    Some(true) => "\x1bP1$r0;38;2;1;2;3m\x1b\\".to_string(),
                    Some(false) => "\x1bP1$r0;38;5;16m\x1b\\".to_string(),
                    None => continue,
                },
            };
            self.session.write_all(reply.as_bytes()).unwrap();
        }
    }

    /// Pumps until `pattern` has been seen after byte `from`, or `timeout`;
    /// returns where it ends.
    fn wait_for(&mut self, pattern: &[u8], from: usize, timeout: Duration) -> Option<usize> {
        let end = self.elapsed() + timeout;
        loop {
            if let Some(i) = find(&self.seen[from.min(self.seen.len())..], pattern) {
                return Some(from + i + pattern.len());
            }
            if self.eof || self.elapsed() > end {
                return None;
            }
            self.pump();
        }
    }

    /// Pumps until the program has exited and closed the terminal.
    fn wait_exit(&mut self, timeout: Duration) -> bool {
        let end = self.elapsed() + timeout;
        while !self.eof {
            if self.elapsed() > end {
                return false;
            }
            self.pump();
        }
        true
    }

    fn send(&mut self, bytes: &[u8]) {
        self.session.write_all(bytes).unwrap();
    }
}

fn find(hay: &[u8], needle: &[u8]) -> Option<usize> {
    hay.windows(needle.len()).position(|w| w == needle)
}

const FRAME_END: &[u8] = b"\x1b[?2026l";

/// Frames begun in `bytes`.
fn frames_begun(bytes: &[u8]) -> usize {
    bytes.windows(8).filter(|w| w == b"\x1b[?2026h").count()
}

/// `q` is heard between frames even when every frame is late: after it is
/// sent, at most the frame being drawn and one already on its way begin
/// (order of events, not the wall clock: a loop that drew its backlog of
/// late frames first would begin many).
#[test]
fn q_is_heard_between_frames_when_frames_run_late() {
    // Sixteen passes of anti-aliasing at 240 frames a second: every frame
    // is late.
    let mut t = Fake::spawn(
        &[
            "tests/models/bunny.obj",
            "--aa",
            "16x",
            "--fps",
            "240",
            "--cols",
            "60",
            "--rows",
            "20",
        ],
        true,
        &[],
        None,
    );
    let first = t
        .wait_for(FRAME_END, 0, Duration::from_secs(20))
        .expect("a frame");
    // A few more late frames.
    let mut at = first;
    for _ in 0..3 {
        at = t
            .wait_for(FRAME_END, at, Duration::from_secs(20))
            .expect("frames");
    }
    let sent = t.seen.len();
    t.send(b"q");
    assert!(t.wait_exit(Duration::from_secs(20)));
    let after = frames_begun(&t.seen[sent..]);
    assert!(after <= 2, "{after} frames begun after q");
    assert_eq!(exit_code(&t.session), 0);
    assert_restored(&t.seen);
}

/// Whether `bytes` hold a character of the octant block or of the sextant
/// block.
fn has_chars_in(bytes: &[u8], range: std::ops::RangeInclusive<u32>) -> bool {
    String::from_utf8_lossy(bytes)
        .chars()
        .any(|c| range.contains(&(c as u32)))
}

const OCTANTS: std::ops::RangeInclusive<u32> = 0x1CD00..=0x1CDE5;
const SEXTANTS: std::ops::RangeInclusive<u32> = 0x1FB00..=0x1FB3B;

#[test]
fn octants_fall_back_to_sextants_when_the_terminal_does_not_draw_them_one_cell_wide() {
    // Position reports for the probe glyphs in order: quadrant, sextant,
    // the three octant glyphs, braille. An octant glyph that leaves the
    // cursor in column 1 (no width) or column 3 (two cells) is unusable.
    for octant_col in [1, 3] {
        let mut t = Fake::spawn(
            &[
                "--glyphs", "octant", "--cols", "60", "--rows", "20", "--hud",
            ],
            true,
            &[2, 2, octant_col, 2, 2, 2],
            None,
        );
        let frame = t
            .wait_for(FRAME_END, 0, Duration::from_secs(20))
            .expect("a frame");
        let frame = t
            .wait_for(FRAME_END, frame, Duration::from_secs(20))
            .expect("a frame");
        t.send(b"q");
        assert!(t.wait_exit(Duration::from_secs(20)));
        // The frames, after the probe (which writes octants to test them).
        let frames = &t.seen[find(&t.seen, b"\x1b[2J").unwrap()..frame];
        assert!(!has_chars_in(frames, OCTANTS), "no octant is drawn");
        assert!(has_chars_in(frames, SEXTANTS), "sextants instead");
        // Said on the status line, and once more after the terminal is back.
        let text = String::from_utf8_lossy(&t.seen);
        let restored = text.find("\x1b[?1049l").expect("restored");
        assert!(text[..restored].contains("octant glyphs are not one cell wide here: sextant"));
        let after = &text[restored..];
        assert_eq!(
            after.matches("note: this terminal does not draw octant glyphs one cell wide, so sextant was used").count(),
            1,
            "{after:?}"
        );
        assert_restored(&t.seen);
    }
}

#[test]
fn a_terminal_that_draws_octants_gets_octants() {
    let mut t = Fake::spawn(
        &["--glyphs", "octant", "--cols", "60", "--rows", "20"],
        true,
        &[],
        None,
    );
    let frame = t
        .wait_for(FRAME_END, 0, Duration::from_secs(20))
        .expect("a frame");
    t.send(b"q");
    assert!(t.wait_exit(Duration::from_secs(20)));
    let frames = &t.seen[find(&t.seen, b"\x1b[2J").unwrap()..frame];
    assert!(has_chars_in(frames, OCTANTS));
    assert!(!String::from_utf8_lossy(&t.seen).contains("note:"));
}

/// A terminal that answers nothing: the probe gives up (the first frame
/// comes with no answer given) and does not ask again after each frame.
/// How long the probe waits (its `DEADLINE`) is tested on a fake clock, by
/// the probe's unit tests (`terminal::probe`).
#[test]
fn a_terminal_that_answers_nothing_gets_frames_and_is_not_asked_again() {
    let mut t = Fake::spawn(
        &["--glyphs", "octant", "--cols", "60", "--rows", "20"],
        false,
        &[],
        None,
    );
    let asked = t
        .wait_for(b"\x1b[5n", 0, Duration::from_secs(20))
        .expect("the probe asks");
    let frame = t
        .wait_for(FRAME_END, asked, Duration::from_secs(20))
        .expect("a frame");
    t.send(b"q");
    assert!(t.wait_exit(Duration::from_secs(20)));
    // Nothing known against octants: they are drawn; and a terminal that
    // does not answer is not asked again after each frame.
    assert!(has_chars_in(&t.seen[asked..frame], OCTANTS));
    assert!(find(&t.seen[asked..], b"\x1b[5n").is_none());
    assert_restored(&t.seen);
}

#[test]
fn truecolor_is_used_where_the_terminal_says_it_draws_it() {
    for (rgb, truecolor) in [(Some(true), true), (Some(false), false), (None, false)] {
        let mut t = Fake::spawn(
            &["--cols", "60", "--rows", "20", "--frames", "3"],
            true,
            &[],
            None,
        );
        t.rgb = rgb;
        assert!(t.wait_exit(Duration::from_secs(20)));
        let text = String::from_utf8_lossy(&t.seen);
        let frames = &text[text.find("\x1b[2J").unwrap()..];
        assert_eq!(frames.contains("[38;2;"), truecolor, "{rgb:?}");
        assert_eq!(frames.contains("[38;5;"), !truecolor, "{rgb:?}");
        assert_eq!(
            text.contains("note: colour: truecolor, as the terminal answered"),
            truecolor,
            "{rgb:?}"
        );
        assert_eq!(exit_code(&t.session), 0);
    }
}

#[test]
fn inside_tmux_truecolor_is_what_tmux_says_its_client_draws() {
    // A `tmux` on PATH that answers as tmux 3.3 does for a client in a
    // truecolor terminal, and one for a 256-colour terminal.
    for (features, truecolor) in [("256,RGB,title,usstyle", true), ("256,title", false)] {
        let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
            .join(format!("fake-tmux-{truecolor}"));
        std::fs::create_dir_all(&dir).unwrap();
        let tmux = dir.join("tmux");
        std::fs::write(&tmux, format!("#!/bin/sh\necho '{features}'\n")).unwrap();
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&tmux, std::fs::Permissions::from_mode(0o755)).unwrap();
        let path = format!(
            "{}:{}",
            dir.display(),
            std::env::var("PATH").unwrap_or_default()
        );
        let mut cmd = Command::new(BIN);
        cmd.args([
            "spin",
            "--cols",
            "40",
            "--rows",
            "10",
            "--frames",
            "2",
            "--no-probe",
        ])
        .env("TERM", "tmux-256color")
        .env("TMUX", "/tmp/tmux-0/default,1,0")
        .env("PATH", path)
        .env_remove("COLORTERM")
        .env_remove("NO_COLOR");
        let mut s = Session::spawn(cmd).expect("a pty");
        s.get_process_mut().set_window_size(80, 24).unwrap();
        let out = String::from_utf8_lossy(&drain(&mut s, Vec::new())).into_owned();
        assert_eq!(out.contains("[38;2;"), truecolor, "{features}");
        assert_eq!(out.contains("[38;5;"), !truecolor, "{features}");
        assert_eq!(exit_code(&s), 0);
    }
}

#[test]
fn no_probe_asks_nothing() {
    let mut t = Fake::spawn(
        &[
            "--no-probe",
            "--cols",
            "60",
            "--rows",
            "20",
            "--frames",
            "3",
        ],
        true,
        &[],
        None,
    );
    assert!(t.wait_exit(Duration::from_secs(20)));
    assert!(find(&t.seen, b"\x1b[6n").is_none());
    assert_eq!(exit_code(&t.session), 0);
}

/// The state of process `pid` from /proc (`R`, `S`, `T` for stopped…).
fn process_state(pid: u32) -> Option<char> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    stat.rsplit(')').next()?.trim_start().chars().next()
}

/// The children of process `pid`.
fn children(pid: u32) -> Vec<u32> {
    std::fs::read_to_string(format!("/proc/{pid}/task/{pid}/children"))
        .unwrap_or_default()
        .split_whitespace()
        .filter_map(|s| s.parse().ok())
        .collect()
}

/// A screen after everything seen so far.
fn screen_of(bytes: &[u8]) -> vt100::Parser {
    let mut vt = terminal(24, 80);
    vt.process(bytes);
    vt
}

#[test]
fn ctrl_z_and_sigtstp_suspend_and_fg_resumes_with_the_terminal_sane_at_each_step() {
    // A real shell with job control runs spin, as a user's would.
    let mut cmd = Command::new("bash");
    cmd.args(["--norc", "--noprofile", "-i"]);
    cmd.env("TERM", "xterm-256color").env("PS1", "$ ");
    let mut session = Session::spawn(cmd).expect("a pty");
    session.get_process_mut().set_window_size(80, 24).unwrap();
    let bash = session.get_process().pid().as_raw() as u32;
    let mut t = Fake {
        session,
        seen: Vec::new(),
        scanned: 0,
        cpr_cols: Vec::new(),
        answer: true,
        rgb: None,
        rate: None,
        tokens: 0.0,
        last_pump: 0.0,
        start: std::time::Instant::now(),
        eof: false,
    };
    let long = Duration::from_secs(20);
    t.wait_for(b"$ ", 0, long).expect("a prompt");
    t.send(format!("{BIN} spin --cols 60 --rows 20\r").as_bytes());
    let frame = t.wait_for(FRAME_END, 0, long).expect("a frame");
    let spin = children(bash)[0];
    let sane_stopped = |t: &mut Fake, from: usize| {
        let prompt = t.wait_for(b"$ ", from, long).expect("the shell's prompt");
        let end = std::time::Instant::now() + long;
        while process_state(spin) != Some('T') {
            assert!(std::time::Instant::now() < end, "spin stopped");
            t.pump();
        }
        let vt = screen_of(&t.seen);
        assert!(!vt.screen().alternate_screen(), "main screen while stopped");
        assert!(!vt.screen().hide_cursor(), "cursor shown while stopped");
        prompt
    };
    let sane_running = |t: &mut Fake, from: usize| {
        let redraw = t.wait_for(b"\x1b[2J", from, long).expect("a full redraw");
        let frame = t.wait_for(FRAME_END, redraw, long).expect("a frame");
        let vt = screen_of(&t.seen);
        assert!(vt.screen().alternate_screen() && vt.screen().hide_cursor());
        frame
    };

    // Ctrl-Z, then fg.
    t.send(b"\x1a");
    let at = sane_stopped(&mut t, frame);
    t.send(b"fg\r");
    let at = sane_running(&mut t, at);
    // SIGTSTP from elsewhere, then fg.
    unsafe { libc::kill(spin as i32, libc::SIGTSTP) };
    let at = sane_stopped(&mut t, at);
    t.send(b"fg\r");
    let at = sane_running(&mut t, at);
    // Raw mode is back: q quits without Enter.
    t.send(b"q");
    t.wait_for(b"$ ", at, long).expect("back at the prompt");
    let vt = screen_of(&t.seen);
    assert!(!vt.screen().alternate_screen() && !vt.screen().hide_cursor());
    t.send(b"exit\r");
    assert!(t.wait_exit(long));
}

/// The last row of the screen after `bytes`.
fn status_line(bytes: &[u8], rows: u16, cols: u16) -> String {
    let mut vt = terminal(rows, cols);
    vt.process(bytes);
    vt.screen().rows(0, cols).last().unwrap_or_default()
}

/// The number after `key` in `line` (`"yaw 12.5°"` → 12.5).
fn number_after(line: &str, key: &str) -> Option<f64> {
    let rest = &line[line.find(key)? + key.len()..];
    let num: String = rest
        .trim_start()
        .chars()
        .take_while(|c| c.is_ascii_digit() || *c == '.')
        .collect();
    num.parse().ok()
}

#[test]
fn a_slow_link_lowers_the_frame_rate_keeps_the_angle_current_and_still_hears_q() {
    // Tux at 200×60 read at 16 kB/s: a frame takes a good part of a second
    // to get through, against a clock of 10 frames a second.
    let step = 0.5;
    let mut t = Fake::spawn(
        &[
            "tests/models/linux-mascot-tux.obj",
            "--cols",
            "200",
            "--rows",
            "60",
            "--hud",
            "--fps",
            "10",
            "--step",
            "0.5",
        ],
        true,
        &[],
        Some(16_000.0),
    );
    t.session
        .get_process_mut()
        .set_window_size(200, 60)
        .unwrap();
    let pid = t.session.get_process().pid().as_raw() as u32;
    let long = Duration::from_secs(30);
    // (where the frame begins in the output, the frame number the status
    // line shows)
    let mut frames: Vec<(usize, f64)> = Vec::new();
    let mut at = 0;
    let mut rates = Vec::new();
    while frames.len() < 8 {
        let begin = t.wait_for(b"\x1b[?2026h", at, long).expect("a frame") - 8;
        at = t.wait_for(FRAME_END, begin, long).expect("its end");
        let line = status_line(&t.seen[..at], 60, 200);
        let angle = number_after(&line, "yaw").expect("the angle on the status line");
        frames.push((begin, angle / step));
        rates.extend(number_after(&line, "link"));
    }
    // Each frame is drawn at the clock's angle when it is sent, so the
    // frame numbers rise, and by more than one a frame: frames were
    // dropped, not queued (a queue would show 1, 2, 3, …).
    let ks: Vec<f64> = frames.iter().map(|&(_, k)| k).collect();
    assert!(ks.windows(2).all(|w| w[1] > w[0]), "{frames:?}");
    assert!(ks[ks.len() - 1] - ks[0] > ks.len() as f64, "{frames:?}");
    // The status line shows the rate the terminal drains at (measured by
    // `Link`, whose unit tests check the figure on a clock of their own).
    let rate = *rates.last().expect("a link rate");
    assert!(rate > 0.0, "link {rate} kB/s: {rates:?}");

    // q is heard while the link is behind: the process ends with at most
    // the frame on its way begun after it, while the link is still slow.
    let sent = t.seen.len();
    t.send(b"q");
    while process_state(pid) != Some('Z') {
        t.pump();
        let after = frames_begun(&t.seen[sent..]);
        assert!(after <= 1, "{after} frames begun after q");
    }
    t.rate = None;
    assert!(t.wait_exit(long));
    assert_restored(&t.seen);
}

#[test]
fn a_dumb_terminal_gets_plain_ascii_lines_and_no_escape_sequence() {
    let mut cmd = Command::new(BIN);
    cmd.args(["spin", "--cols", "30", "--rows", "8", "--frames", "3"]);
    cmd.env("TERM", "dumb").env_remove("COLORTERM");
    let mut session = Session::spawn(cmd).expect("a pty");
    let out = drain(&mut session, Vec::new());
    assert_eq!(exit_code(&session), 0);
    assert!(!out.contains(&0x1b), "{:?}", String::from_utf8_lossy(&out));
    let text = String::from_utf8(out).unwrap().replace("\r\n", "\n");
    // Three frames of eight lines, the first the plain ascii render.
    assert_eq!(text.lines().count(), 24, "{text}");
    let first = String::from_utf8(run(&[
        "render", "--cols", "30", "--rows", "8", "--glyphs", "ascii", "--color", "none",
    ]))
    .unwrap();
    assert!(text.starts_with(&first), "{text}\n{first}");
}

#[test]
fn without_a_controlling_terminal_spin_says_so() {
    // setsid: a new session, no controlling terminal; stdout is still the
    // pseudo-terminal.
    let mut cmd = Command::new("setsid");
    cmd.args(["-w", BIN, "spin"]);
    let mut session = Session::spawn(cmd).expect("a pty");
    let out = String::from_utf8(drain(&mut session, Vec::new())).unwrap();
    assert_eq!(exit_code(&session), 1);
    assert!(
        out.starts_with("error: spin: no controlling terminal to read keys from (/dev/tty: "),
        "{out}"
    );
    assert!(!out.contains("\x1b[?1049h"));
}

/// A moving model in a terminal: the status line shows its clip and the
/// clip's time; `t` stops the turn while the clip plays on; `]` goes to
/// the next clip (the arm has one: itself, from its start).
#[test]
fn the_status_line_shows_the_clip_and_t_stops_the_turn_while_it_plays() {
    let mut t = Fake::spawn(
        &[
            "examples/models/arm.glb",
            "--cols",
            "80",
            "--rows",
            "24",
            "--hud",
            "--no-probe",
        ],
        true,
        &[],
        None,
    );
    let long = Duration::from_secs(20);
    let line_after = |t: &mut Fake, from: usize| {
        let begin = t.wait_for(b"\x1b[?2026h", from, long).expect("a frame") - 8;
        let end = t.wait_for(FRAME_END, begin, long).expect("its end");
        (status_line(&t.seen[..end], 24, 80), end)
    };
    let (line, at) = line_after(&mut t, 0);
    assert!(line.contains("clip 0 \"wave\""), "{line}");
    assert!(number_after(&line, "\"wave\"").is_some(), "{line}");
    t.send(b"t");
    let at = t.wait_for(b"turn stopped", at, long).expect("the notice");
    // Two frames drawn after it: the angle holds, the clip's time moves.
    let (first, at) = line_after(&mut t, at);
    let mut at = at;
    let mut later = first.clone();
    while number_after(&later, "\"wave\"") == number_after(&first, "\"wave\"") {
        (later, at) = line_after(&mut t, at);
    }
    assert_eq!(
        number_after(&first, "yaw"),
        number_after(&later, "yaw"),
        "{first} / {later}"
    );
    // The next clip is the first again, and says so ahead of the rest.
    t.send(b"]");
    let mut line = String::new();
    while !line.trim_start().starts_with("clip 0 \"wave\" ·") {
        (line, at) = line_after(&mut t, at);
    }
    t.send(b"q");
    assert!(t.wait_exit(long));
    assert_restored(&t.seen);
}

/// The frame `render ARGS` draws in the mouse tests' view (40×16 cells of
/// half blocks, cells half as wide as high), as a terminal shows it.
fn rendered(args: &[&str]) -> Vec<(String, vt100::Color, vt100::Color)> {
    let lines = run(&[&["render"][..], args, &MOUSE_VIEW].concat());
    let mut vt = terminal(16, 40);
    vt.process(&as_displayed(&lines));
    cells(vt.screen())
}

const MOUSE_VIEW: [&str; 10] = [
    "--cols",
    "40",
    "--rows",
    "16",
    "--cell-aspect",
    "0.5",
    "--color",
    "truecolor",
    "--glyphs",
    "half",
];

/// Spawns a still `spin` in the mouse tests' view, in a terminal played by
/// the test, and waits for its first frame.
fn still_spin(extra: &[&str]) -> Fake {
    let mut t = Fake::spawn(
        &[&["--turn", "0", "--no-probe"][..], &MOUSE_VIEW, extra].concat(),
        true,
        &[],
        None,
    );
    t.rgb = Some(true);
    t.wait_for(FRAME_END, 0, Duration::from_secs(20))
        .expect("a first frame");
    t
}

/// Pumps until the screen (an 80×24 terminal's top left 40×16 cells) is
/// as `want` says, or 20 s pass; whether it came to be.
fn until(t: &mut Fake, want: impl Fn(&vt100::Screen) -> bool) -> bool {
    let end = t.elapsed() + Duration::from_secs(20);
    loop {
        let mut vt = terminal(16, 40);
        vt.process(&t.seen);
        if want(vt.screen()) {
            return true;
        }
        if t.eof || t.elapsed() > end {
            return false;
        }
        t.pump();
    }
}

/// Pumps until the screen shows `want`, or 20 s pass; whether it did.
fn shows(t: &mut Fake, want: &[(String, vt100::Color, vt100::Color)]) -> bool {
    until(t, |s| cells(s) == want)
}

/// Pumps until the screen has `text`, or 20 s pass; whether it did.
fn says(t: &mut Fake, text: &str) -> bool {
    until(t, |s| s.contents().contains(text))
}

/// A drag of 8 cells to the right over a view 16 rows high of cells half
/// as wide as high (8 × 0.5 / 16: a quarter of the view's height) turns
/// the eye a quarter of 180° the other way: the frame is
/// `render --orbit -45,0`. Sent in the SGR encoding, a cell a report.
/// `r` puts the first frame back, and the wheel zooms as `+` does.
#[test]
fn a_drag_turns_the_view_by_its_cells_and_r_resets_it() {
    let start = rendered(&[]);
    let turned = rendered(&["--orbit", "-45,0"]);
    assert_ne!(start, turned);
    let mut t = still_spin(&[]);
    assert!(shows(&mut t, &start), "the first frame is render's");
    let mut drag = b"\x1b[<0;11;6M".to_vec();
    for col in 12..=19 {
        drag.extend_from_slice(format!("\x1b[<32;{col};6M").as_bytes());
    }
    drag.extend_from_slice(b"\x1b[<0;19;6m");
    t.send(&drag);
    assert!(
        shows(&mut t, &turned),
        "dragged 8 cells: render --orbit -45,0"
    );
    t.send(b"r");
    assert!(shows(&mut t, &start), "r: the first frame again");
    // Down and to the left, in the legacy encoding (a terminal without
    // SGR reports): 4 cells left is +22.5°, 2 down is a pitch of
    // 2 / 16 · 180 = 22.5°.
    t.send(b"\x1b[M +&\x1b[M@'(\x1b[M#'(");
    assert!(
        shows(&mut t, &rendered(&["--orbit", "22.5,22.5"])),
        "render --orbit 22.5,22.5"
    );
    // A double click resets too.
    t.send(b"\x1b[<0;5;5M\x1b[<0;5;5m\x1b[<0;5;5M\x1b[<0;5;5m");
    assert!(
        shows(&mut t, &start),
        "a double click: the first frame again"
    );
    t.send(b"q");
    assert!(t.wait_exit(Duration::from_secs(20)));
    assert_restored(&t.seen);
}

/// The wheel zooms by the `+` and `-` keys' factor (the status line says
/// how much), and a right-drag moves the picture with the pointer: the
/// frame is `render --pan`.
#[test]
fn the_wheel_zooms_and_a_right_drag_pans() {
    let mut t = still_spin(&["--hud"]);
    t.send(b"\x1b[<64;3;3M\x1b[<64;3;3M");
    assert!(
        says(&mut t, "orbit 0,0 ×1.23"),
        "two notches in: 1/0.9² = 1.23 times larger"
    );
    t.send(b"\x1b[<65;3;3M");
    assert!(says(&mut t, "orbit 0,0 ×1.11"), "one notch out");
    t.send(b"q");
    assert!(t.wait_exit(Duration::from_secs(20)));
    assert_restored(&t.seen);

    // 4 columns right (4 × 0.5 / 16 = 0.125 view heights), 2 rows up
    // (0.125).
    let mut t = still_spin(&[]);
    t.send(b"\x1b[<2;11;6M\x1b[<34;15;4M\x1b[<2;15;4m");
    assert!(
        shows(&mut t, &rendered(&["--pan", "0.125,0.125"])),
        "render --pan 0.125,0.125"
    );
    t.send(b"q");
    assert!(t.wait_exit(Duration::from_secs(20)));
}

/// `?` shows the keys over the frame (the first of them: a 40×16 frame
/// cuts the box) and hides them again.
#[test]
fn question_mark_shows_the_help_box_and_hides_it_again() {
    let start = rendered(&[]);
    let mut t = still_spin(&[]);
    let from = t.seen.len();
    t.send(b"?");
    t.wait_for(b"keys (? hides)", from, Duration::from_secs(20))
        .expect("the help box");
    let end = t
        .wait_for(FRAME_END, from, Duration::from_secs(20))
        .unwrap();
    let mut vt = terminal(16, 40);
    vt.process(&t.seen[..end]);
    let text = vt.screen().contents();
    for (key, _) in rastty::animate::KEYS.iter().take(3) {
        assert!(text.contains(key), "{key} in\n{text}");
    }
    t.send(b"?");
    assert!(shows(&mut t, &start), "hidden: the frame as it was");
    t.send(b"q");
    assert!(t.wait_exit(Duration::from_secs(20)));
}

/// `w` cycles solid, lines and edges: each frame is `render --wire`'s.
#[test]
fn w_cycles_the_wireframe_as_render_draws_it() {
    let mut t = still_spin(&[]);
    for wire in ["lines", "edges", "solid"] {
        t.send(b"w");
        assert!(
            shows(&mut t, &rendered(&["--wire", wire])),
            "render --wire {wire}"
        );
    }
    t.send(b"q");
    assert!(t.wait_exit(Duration::from_secs(20)));
}

/// A burst of mouse reports (a drag over a slow link arrives so) does not
/// hold up a `q` that follows it: every report is applied before the next
/// frame read with it, and `q` ends the loop when it is read, with mouse
/// reports off.
#[test]
fn a_burst_of_drags_does_not_starve_q() {
    let mut t = still_spin(&[]);
    let mut burst = b"\x1b[<0;10;5M".to_vec();
    for k in 0..3000u32 {
        let col = 10 + k % 20;
        burst.extend_from_slice(format!("\x1b[<32;{col};5M").as_bytes());
    }
    burst.extend_from_slice(b"q");
    t.send(&burst);
    assert!(t.wait_exit(Duration::from_secs(20)), "q was heard");
    assert_restored(&t.seen);
}

#[test]
fn pixels_follow_a_cell_whose_pixels_change_with_the_window() {
    // The window's size in pixels gives the cell: 80×24 cells of 10×20,
    // then the font zoomed out to 100×30 cells of 8×16 in the same window.
    let mut t = Fake::spawn(
        &["tests/models/fox.obj", "--graphics", "kitty"],
        true,
        &[],
        None,
    );
    let size = |t: &Fake, cols: u16, rows: u16| {
        use std::os::fd::AsRawFd;
        let ws = libc::winsize {
            ws_row: rows,
            ws_col: cols,
            ws_xpixel: 800,
            ws_ypixel: 480,
        };
        // SAFETY: a valid winsize for the pty's master, for the call.
        assert_eq!(
            unsafe { libc::ioctl(t.session.as_raw_fd(), libc::TIOCSWINSZ, &ws) },
            0
        );
    };
    size(&t, 80, 24);
    let long = Duration::from_secs(30);
    t.wait_for(b"\x1b_Ga=T,i=", 0, long).expect("pixels first");
    let first = t
        .wait_for(b"c=80,r=23", 0, long)
        .expect("the first image over 80x23 cells");
    size(&t, 100, 30);
    let again = t
        .wait_for(b"\x1b_Ga=T,i=", first, long)
        .expect("a new image");
    let keys = String::from_utf8_lossy(&t.seen[again..again + 44]).into_owned();
    assert!(
        keys.starts_with("7496051,p=1,f=32,o=z,s=800,v=464,c=100,r=29,"),
        "{keys}"
    );
    t.send(b"q");
    assert!(t.wait_exit(long));
    assert_restored(&t.seen);
}

#[test]
fn pixels_over_a_link_too_slow_for_them_step_down_to_a_smaller_image_fewer_frames_then_cells() {
    // The fox in kitty pixels read at 16 kB/s: a frame of its pixels needs
    // far more than that at 10 frames a second, even a quarter of them.
    let mut t = Fake::spawn(
        &[
            "tests/models/fox.obj",
            "--graphics",
            "kitty",
            "--cell-size",
            "8x16",
            "--fps",
            "10",
        ],
        true,
        &[],
        Some(16_000.0),
    );
    let long = Duration::from_secs(60);
    let placed = t.wait_for(b"\x1b_Ga=T,i=", 0, long).expect("pixels first");
    let keys =
        |t: &Fake, from: usize| String::from_utf8_lossy(&t.seen[from..from + 48]).into_owned();
    assert!(
        keys(&t, placed).starts_with("7496051,p=1,f=32,o=z,s=640,v=368,c=80,r=23,"),
        "{}",
        keys(&t, placed)
    );
    let half = t
        .wait_for(b": a half-size image", placed, long)
        .expect("the first step said on the status line");
    // The image placed again at half the pixels over the same cells.
    let smaller = t
        .wait_for(b"\x1b_Ga=T,i=", placed, long)
        .expect("a smaller image");
    assert!(
        keys(&t, smaller).starts_with("7496051,p=1,f=32,o=z,s=320,v=184,c=80,r=23,"),
        "{}",
        keys(&t, smaller)
    );
    let fewer = t
        .wait_for(b": half the frames a second", half.max(smaller), long)
        .expect("the second step");
    let cells_said = t
        .wait_for(b": character cells", fewer, long)
        .expect("the third step");
    let deleted = t
        .wait_for(b"\x1b_Ga=d,d=I,i=", fewer, long)
        .expect("the image taken away");
    assert!(deleted < cells_said, "the image goes before the cells come");
    // Cells from then on: half blocks, and no more images.
    let cells = t.wait_for("▀".as_bytes(), cells_said, long).expect("cells");
    t.send(b"q");
    t.rate = None;
    assert!(t.wait_exit(long));
    let after = String::from_utf8_lossy(&t.seen[cells..]);
    assert!(
        !after.contains("\x1b_Ga=f") && !after.contains("\x1b_Ga=T"),
        "no image after the step down"
    );
    assert_restored(&t.seen);
}
