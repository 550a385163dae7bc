//! The interactive loop of `rastty spin`: a [`Player`] driven by the clock,
//! the keys, the signals and the link to the terminal.
//!
//! **Never deaf.** One `poll` waits on the keyboard, the signal pipe and
//! (while a frame is being sent) the terminal's readiness to take more, so
//! a key is read the moment it arrives whatever the pacing: a late loop
//! loses frames, never keys. The only wait that is not interruptible is the
//! rendering of one frame.
//!
//! **Pacing.** Frame `k` is due at `k / fps` seconds; a frame the loop was
//! too late for is skipped (the angle jumps ahead), never queued.
//!
//! **Slow links.** Frames are written without blocking, a piece at a time
//! as the terminal takes them. After each frame comes a device status
//! request (`CSI 5 n`), which the terminal answers once it has drawn the
//! frame: that is how rastty learns how fast the terminal really drains
//! what it is sent (the link rate, kB/s on the HUD). A new frame is
//! rendered only when the terminal has room for it: while it keeps up, as
//! many frames may be on their way as the round trip's own latency covers
//! (one or two); once it falls behind, one at a time, so each frame is
//! rendered at the clock's angle just before it is sent and a slow link
//! lowers the frame rate instead of building a queue of stale frames. A
//! terminal that never answers (it said nothing to the probe, or nothing
//! within a second) is paced by the writes alone.
//!
//! **Signals and suspend.** SIGINT, SIGTERM, SIGHUP and SIGQUIT end the
//! loop (the caller exits with 128 + the signal); so do SIGUSR1, SIGUSR2,
//! SIGALRM, SIGPIPE, SIGXCPU and SIGXFSZ, whose default action would kill
//! the process with the terminal left raw and on the alternate screen (the
//! caller restores it, then takes the default action: see
//! [`Exit::Signal`]). Ctrl-Z and SIGTSTP restore the terminal and stop the
//! process; SIGCONT takes the terminal over again and redraws in full,
//! unless a signal that ends the loop came while it was stopped (`kill %1`
//! sends SIGTERM and SIGCONT to a stopped job): then the loop ends without
//! taking the terminal back, which from the background would stop the
//! process again. SIGWINCH resizes. The handlers are the loop's own and are
//! given back when it returns.

use rastty::Choice;
use std::io::Write;
use std::time::{Duration, Instant};

use crate::gesture::Pointer;
use crate::link::Link;
use crate::terminal::input::{Input, Key, Parser};
use crate::terminal::probe::Capabilities;
use crate::terminal::{Read, Session, TtyError, has_signal, sig};
use rastty::animate::{Command, LiveStatus, Player};
use rastty::cast::Recorder;
use rastty::color::ColorDepth;

/// How the loop runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LiveOptions {
    /// Frames per second asked for.
    pub fps: u32,
    /// Stop after this many frames.
    pub frames: Option<u64>,
    /// Ask the terminal what it draws before drawing (the terminal's glyph probe).
    pub probe: bool,
    /// Alternate screen and cursor moves (`false`: plain lines, for a dumb
    /// terminal).
    pub full_screen: bool,
    /// The deepest colour the `c` key may pick.
    pub max_depth: ColorDepth,
    /// Whether to switch to truecolor where the probe finds the terminal
    /// draws it (the depth was left to detection, and the environment
    /// said less).
    pub detect_truecolor: bool,
    /// Pixels or cells (`--graphics`), and a cell's pixels (`--cell-size`).
    pub graphics: crate::cli::GraphicsArg,
    pub cell_size: Option<rastty::picture::CellPx>,
}

/// How the loop ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Exit {
    /// A key asked to quit.
    Quit,
    /// The last of `--frames` was shown.
    Done,
    /// A signal (its number) asked to stop, or the terminal went away
    /// (SIGHUP). The terminal is restored by the time the caller sees it;
    /// for the signals whose default action is not a plain ending (the
    /// [`ENDING`] ones past SIGQUIT) the caller may then take that action
    /// ([`crate::terminal::die_by`]).
    Signal(i32),
}

/// How the loop ended, and what to tell the user once the terminal is back
/// (a glyph mode the terminal cannot draw, say).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Outcome {
    /// How the loop ended.
    pub exit: Exit,
    /// What to tell the user.
    pub messages: Vec<String>,
}

/// What a key asks for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Action {
    /// A command for the player (quitting included).
    Player(Command),
    /// Restore the terminal and stop (Ctrl-Z).
    Suspend,
}

/// The action a key asks for.
pub fn action_for(key: Key) -> Option<Action> {
    let cmd = match key {
        Key::Char('q') | Key::Esc | Key::Ctrl('c') | Key::Ctrl('\\') => Command::Quit,
        // Job control is unix's: a console has none.
        Key::Ctrl('z') if cfg!(unix) => return Some(Action::Suspend),
        Key::Ctrl('l') => Command::Redraw,
        Key::Char(' ') => Command::TogglePause,
        Key::Char('t') => Command::ToggleTurn,
        Key::Char('[') => Command::Clip(-1),
        Key::Char(']') => Command::Clip(1),
        Key::Left => Command::Orbit {
            yaw: -5.0,
            pitch: 0.0,
        },
        Key::Right => Command::Orbit {
            yaw: 5.0,
            pitch: 0.0,
        },
        Key::Up => Command::Orbit {
            yaw: 0.0,
            pitch: 5.0,
        },
        Key::Down => Command::Orbit {
            yaw: 0.0,
            pitch: -5.0,
        },
        Key::Char('+' | '=') => Command::Zoom(0.9),
        Key::Char('-' | '_') => Command::Zoom(1.0 / 0.9),
        Key::Char('m') => Command::NextGlyphs,
        Key::Char('c') => Command::NextColor,
        Key::Char('s') => Command::NextShading,
        Key::Char('r') => Command::Reset,
        Key::Char('w') => Command::NextWire,
        Key::Char('?') => Command::ToggleHelp,
        _ => return None,
    };
    Some(Action::Player(cmd))
}

/// Signals that end the loop (on Windows, the console's control events
/// stand for the first four).
pub const ENDING: [i32; 10] = [
    sig::INT,
    sig::TERM,
    sig::HUP,
    sig::QUIT,
    sig::USR1,
    sig::USR2,
    sig::ALRM,
    sig::PIPE,
    sig::XCPU,
    sig::XFSZ,
];

/// The first of [`ENDING`] in a mask of pending signals.
fn ending(sigs: u64) -> Option<i32> {
    ENDING.into_iter().find(|&s| has_signal(sigs, s))
}

/// Signals the loop handles: those that end it, and those that suspend,
/// continue and resize it.
const HANDLED: [i32; ENDING.len() + 3] = {
    let mut all = [
        sig::TSTP,
        sig::CONT,
        sig::WINCH,
        0,
        0,
        0,
        0,
        0,
        0,
        0,
        0,
        0,
        0,
    ];
    let mut i = 0;
    while i < ENDING.len() {
        all[3 + i] = ENDING[i];
        i += 1;
    }
    all
};

/// How long a notice (a new glyph mode…) stays up.
const NOTICE_TIME: Duration = Duration::from_secs(2);
/// How long a lone ESC waits for the rest of a sequence.
const ESC_WAIT: Duration = Duration::from_millis(25);
/// The status request that follows each frame.
const STATUS_REQUEST: &[u8] = b"\x1b[5n";
/// How long the last frame of `--frames` may take to write.
const LAST_WRITE: Duration = Duration::from_secs(5);
/// How long the loop waits, before it stops or suspends, for the answers
/// to the status requests still out: an answer that came later would be
/// read by the shell (as `^[[0n`, or by readline as a key).
const LAST_ANSWERS: Duration = Duration::from_millis(250);

fn io_err(what: &'static str) -> impl FnOnce(std::io::Error) -> TtyError {
    move |source| TtyError::Io { what, source }
}

/// Spins `player` in the terminal until a key, a signal, or (with
/// `frames`) the last frame. The terminal and the signal handlers are
/// restored before it returns. With `record`, every frame sent is recorded
/// at the loop's clock (frames skipped are missing there too), and every
/// resize.
pub fn run(
    player: &mut Player,
    opts: &LiveOptions,
    record: Option<&mut Recorder<dyn Write + '_>>,
) -> Result<Outcome, TtyError> {
    let session = Session::open(opts.full_screen, &HANDLED)?;
    let mut live = Live {
        session,
        player,
        opts: *opts,
        parser: Parser::new(),
        pointer: Pointer::default(),
        inputs: Vec::with_capacity(64),
        out: Vec::new(),
        written: 0,
        messages: Vec::new(),
        last_input: Instant::now(),
        record,
        start: Instant::now(),
        slow_frames: 0,
        steps_down: 0,
        window_cell: None,
        every: 1,
    };
    let exit = live.run().map_err(io_err("writing frames"))?;
    let messages = std::mem::take(&mut live.messages);
    drop(live);
    Ok(Outcome { exit, messages })
}

/// The loop's state.
struct Live<'a, 'b> {
    session: Session,
    player: &'a mut Player,
    opts: LiveOptions,
    parser: Parser,
    /// The mouse between reports (a drag's last cell, a first click).
    pointer: Pointer,
    inputs: Vec<Input>,
    /// The frame being sent, and how much of it is written.
    out: Vec<u8>,
    written: usize,
    messages: Vec<String>,
    last_input: Instant,
    /// Where frames are recorded, and the time they count from.
    record: Option<&'a mut Recorder<dyn Write + 'b>>,
    start: Instant,
    /// Frames in a row whose pixels the link could not carry at the rate.
    slow_frames: u32,
    /// How many times pixels stepped down for the link.
    steps_down: u32,
    /// A cell's pixels as the window's size last said.
    window_cell: Option<[u16; 2]>,
    /// A frame is drawn every this many ticks (2: pixels at half the rate,
    /// over a slow link).
    every: u64,
}

/// Frames in a row too large for the link before pixels step down.
const SLOW_FRAMES: u32 = 5;

impl Live<'_, '_> {
    /// Runs the loop; before returning, collects the answers still due.
    fn run(&mut self) -> std::io::Result<Exit> {
        let mut link = None;
        let exit = self.frames(&mut link);
        // An image left on the screen goes with it (kitty keeps it until
        // told), whatever ended the loop.
        let mut bye = Vec::new();
        self.player.goodbye(&mut bye);
        if !bye.is_empty() {
            let rest = &self.out[self.written.min(self.out.len())..];
            if !rest.is_empty() {
                // A frame cut short: CAN ends the sequence it left open.
                bye.insert(0, 0x18);
            }
            let _ = self.session.write_all(&bye, LAST_WRITE);
        }
        let exit = exit?;
        if let Some(link) = &mut link {
            self.collect_answers(link);
        }
        Ok(exit)
    }

    /// Reads (and drops, keys included) what the terminal sends until every
    /// status request is answered or [`LAST_ANSWERS`] passes.
    fn collect_answers(&mut self, link: &mut Link) {
        let end = Instant::now() + LAST_ANSWERS;
        while link.outstanding() > 0 {
            let left = end.saturating_duration_since(Instant::now());
            if left.is_zero() || self.session.wait_input(left).is_err() {
                return;
            }
            if self.session.read(&mut self.parser, &mut self.inputs) == Read::Gone {
                return;
            }
            let now = Instant::now();
            for input in self.inputs.drain(..) {
                if input == Input::StatusOk {
                    link.acked(now);
                }
            }
        }
    }

    fn frames(&mut self, link_out: &mut Option<Link>) -> std::io::Result<Exit> {
        let asks = self.session.reads_answers();
        let caps = if self.opts.probe && self.opts.full_screen && asks {
            let mut early = Vec::new();
            let caps = self.session.probe(&mut self.parser, &mut early)?;
            self.inputs.extend(early);
            caps
        } else {
            Capabilities::default()
        };
        self.adopt(&caps);
        // Where answers cannot be read, none is asked for: the link is
        // paced by the writes, as for a terminal that answered no probe.
        let link = link_out.insert(Link::new(
            self.opts.fps,
            &caps,
            (self.opts.probe && self.opts.full_screen) || !asks,
        ));
        let fps = self.opts.fps.max(1) as f64;
        let start = Instant::now();
        self.start = start;
        let mut shown: Option<u64> = None;
        let mut dirty = true;
        let mut measured = fps as f32;
        let mut last_frame: Option<Instant> = None;
        let mut notice = (self.player.notice_serial(), Instant::now());
        loop {
            // Signals.
            let mut sigs = self.session.take_signals();
            if let Some(s) = ending(sigs) {
                return Ok(Exit::Signal(s));
            }
            if has_signal(sigs, sig::TSTP) {
                if let Some(s) = self.suspend(link)? {
                    return Ok(Exit::Signal(s));
                }
                // The SIGCONT that woke us is handled by now.
                sigs = (sigs | self.session.take_signals()) & !(1 << sig::CONT);
                dirty = true;
            }
            if has_signal(sigs, sig::CONT) {
                self.session.resume()?;
                self.abandon_frame(link);
                self.player.apply(Command::Redraw);
                dirty = true;
            }
            let resized = has_signal(sigs, sig::WINCH) || has_signal(sigs, sig::CONT);
            if let Some(ws) = self.session.size().filter(|_| resized) {
                let (cols, rows) = ws.cells();
                let o = self.player.options();
                if (o.cols, o.rows) != (cols, rows) {
                    self.resize(cols, rows)?;
                    dirty = true;
                }
                self.follow_the_cell(ws.cell_pixels());
            }

            // Keys and answers.
            match self.session.read(&mut self.parser, &mut self.inputs) {
                Read::Bytes(_) => self.last_input = Instant::now(),
                Read::Nothing => {}
                Read::Gone => return Ok(Exit::Signal(sig::HUP)),
            }
            if self.parser.is_pending() && self.last_input.elapsed() >= ESC_WAIT {
                self.parser.flush(&mut self.inputs);
            }
            let now = Instant::now();
            let mut suspend = false;
            for input in self.inputs.drain(..) {
                match input {
                    Input::Key(key) => match action_for(key) {
                        Some(Action::Player(cmd)) => {
                            if !self.player.apply(cmd) {
                                return Ok(Exit::Quit);
                            }
                            dirty = true;
                        }
                        Some(Action::Suspend) => suspend = self.session.can_suspend(),
                        None => {}
                    },
                    Input::Mouse(m) => {
                        if let Some(cmd) = self.pointer.command(m, now) {
                            self.player.apply(cmd);
                            dirty = true;
                        }
                    }
                    Input::StatusOk => link.acked(now),
                    _ => {}
                }
            }
            if suspend {
                if let Some(s) = self.suspend(link)? {
                    return Ok(Exit::Signal(s));
                }
                dirty = true;
            }
            if self.player.notice_serial() != notice.0 {
                notice = (self.player.notice_serial(), now);
            } else if self.player.notice().is_some() && now - notice.1 >= NOTICE_TIME {
                self.player.clear_notice();
                dirty = true;
            }

            // The frame on its way.
            if self.written < self.out.len() {
                match self.session.write(&self.out[self.written..]) {
                    Ok(n) => self.written += n,
                    Err(_) => return Ok(Exit::Signal(sig::HUP)),
                }
                if self.written == self.out.len() {
                    link.written(Instant::now());
                }
            }

            // The next frame, when it is due and the terminal has room.
            let now = Instant::now();
            let tick = ((now - start).as_secs_f64() * fps) as u64 / self.every * self.every;
            let idle = self.written == self.out.len();
            // A still picture is drawn again only when something changed
            // (`--frames` counts ticks, so it keeps them).
            let ticks = self.player.moves() || self.opts.frames.is_some();
            if !ticks && shown.is_some() {
                // Still: the ticks go by undrawn, and are not made up later.
                shown = Some(tick);
            }
            if idle && ((ticks && shown != Some(tick)) || dirty) && link.can_send(now) {
                // Frames the loop was too late for are skipped, not queued.
                let mut step = shown.map_or(0, |s| tick.saturating_sub(s));
                if let Some(n) = self.opts.frames {
                    step = step.min((n - 1).saturating_sub(self.player.frame_number()));
                }
                self.player.advance(step);
                if let Some(t) = last_frame {
                    let dt = now.duration_since(t).as_secs_f32();
                    if dt > 0.0 {
                        measured = 0.9 * measured + 0.1 / dt;
                    }
                }
                last_frame = Some(now);
                let status = LiveStatus {
                    fps: measured,
                    link: link.rate(),
                };
                let bytes = self.player.prepare(status);
                self.out.clear();
                self.out.extend_from_slice(bytes);
                if let Some(r) = self.record.as_deref_mut() {
                    r.output(now - start, &self.out)?;
                }
                self.written = 0;
                self.fit_the_link(link, fps);
                if !self.out.is_empty() {
                    if link.wants_acks() && self.opts.full_screen {
                        self.out.extend_from_slice(STATUS_REQUEST);
                    }
                    link.sent(now, self.out.len());
                }
                shown = Some(tick);
                dirty = false;
                let last = self.opts.frames.is_some_and(|n| {
                    self.player.frame_number() + 1 >= n && !self.player.is_paused()
                });
                if last {
                    let rest = self.written;
                    self.session.write_all(&self.out[rest..], LAST_WRITE)?;
                    return Ok(Exit::Done);
                }
                continue;
            }

            // Wait for a key, a signal, room to write, or the next frame.
            let sending = self.written < self.out.len();
            let mut wait = if sending {
                Duration::from_millis(100)
            } else {
                let next = start + Duration::from_secs_f64((tick + self.every) as f64 / fps);
                next.saturating_duration_since(Instant::now())
                    .min(Duration::from_millis(100))
            };
            if self.parser.is_pending() {
                wait = wait.min(ESC_WAIT);
            }
            self.session.wait(sending, wait)?;
        }
    }

    /// Takes in what the probe found: a glyph mode the terminal cannot draw
    /// falls back (said once, on the status line now and on stderr at the
    /// end), `m` skips such modes, synchronized output is left out where
    /// the terminal said it does not know it.
    fn adopt(&mut self, caps: &Capabilities) {
        let choice = crate::pixels::choose(
            self.opts.graphics,
            self.opts.cell_size,
            self.opts.full_screen,
            &|k| std::env::var(k).ok(),
            self.session.size(),
            caps,
        );
        self.messages.extend(choice.notes);
        self.window_cell = self.session.size().and_then(|ws| ws.cell_pixels());
        if let Some(g) = choice.graphics {
            self.player
                .set_graphics(g.protocol, g.cell, g.registers, g.background);
            self.player.set_notice(format!(
                "{} pixels, cells of {}×{}",
                g.protocol.name(),
                g.cell[0],
                g.cell[1]
            ));
        }
        self.player.set_usable_glyphs(|m| caps.usable(m));
        self.player.set_max_depth(self.opts.max_depth);
        if caps.sync == Some(false) {
            self.player.encoder_mut().set_sync(false);
        }
        if self.opts.detect_truecolor && caps.truecolor == Some(true) {
            self.player.set_color(ColorDepth::TrueColor);
            self.player
                .set_notice("color truecolor: the terminal says it draws 24-bit colour");
            self.messages.push(
                "colour: truecolor, as the terminal answered (COLORTERM does not say so here; --color chooses)".into(),
            );
        }
        let asked = self.player.options().glyphs;
        let best = caps.best(asked);
        if best != asked {
            self.player.set_glyphs(best);
            self.player.set_notice(format!(
                "{} glyphs are not one cell wide here: {}",
                asked.name(),
                best.name()
            ));
            self.messages.push(format!(
                "this terminal does not draw {} glyphs one cell wide, so {} was used (--no-probe draws them anyway)",
                asked.name(),
                best.name()
            ));
        }
    }

    /// Pixels over a link too slow for them ([`SLOW_FRAMES`] frames in a row
    /// needing more than its measured rate) step down, each step said on
    /// the status line: a half-size image where the protocol scales it,
    /// then half the frames a second, then character cells.
    fn fit_the_link(&mut self, link: &Link, fps: f64) {
        let Some(rate) = link.rate().filter(|_| self.player.shows_pixels()) else {
            return;
        };
        let fps = fps / self.every as f64;
        let need = self.out.len() as f64 * fps;
        self.slow_frames = if need > rate { self.slow_frames + 1 } else { 0 };
        if self.slow_frames < SLOW_FRAMES {
            return;
        }
        self.slow_frames = 0;
        let (rate, need) = (rate / 1e3, need / 1e3);
        self.steps_down += 1;
        let step = if self.steps_down == 1 && self.player.halve_pixels() {
            "a half-size image"
        } else if self.every == 1 {
            self.every = 2;
            "half the frames a second"
        } else {
            self.player.stop_graphics(&mut self.out);
            "character cells"
        };
        let why = format!("pixels at {fps:.0} fps need {need:.0} kB/s, the link {rate:.0}: {step}");
        self.player.set_notice(why.clone());
        self.messages.push(why);
    }

    /// A cell whose pixels changed under pixels (the font or its zoom, seen
    /// in the window's size in pixels) is followed: the next frame is drawn
    /// at the new cell, unless `--cell-size` fixed it or the link made the
    /// image smaller.
    fn follow_the_cell(&mut self, cell: Option<[u16; 2]>) {
        let was = std::mem::replace(&mut self.window_cell, cell);
        let fixed = self.opts.cell_size.is_some() || self.steps_down > 0;
        if let (Some(c), Some(was)) = (cell, was)
            && c != was
            && !fixed
            && self.player.shows_pixels()
        {
            self.player.set_cell_pixels(c);
        }
    }

    /// Resizes the player, and records the resize when recording.
    fn resize(&mut self, cols: u16, rows: u16) -> std::io::Result<()> {
        self.player.apply(Command::Resize { cols, rows });
        match self.record.as_deref_mut() {
            Some(r) => r.resize(self.start.elapsed(), cols, rows),
            None => Ok(()),
        }
    }

    /// Drops the rest of a frame cut short (the terminal is restored with
    /// CAN first, which ends any sequence it left open).
    fn abandon_frame(&mut self, link: &mut Link) {
        self.out.clear();
        self.written = 0;
        link.forget_inflight();
    }

    /// Ctrl-Z or SIGTSTP: the terminal restored, the process stopped; when
    /// continued, the terminal taken over again and redrawn in full. A
    /// signal that ends the loop, come while stopped, is returned instead
    /// (the terminal is left as the shell has it).
    fn suspend(&mut self, link: &mut Link) -> std::io::Result<Option<i32>> {
        self.collect_answers(link);
        self.session.stop()?;
        // Handlers run before raise() returns: what came while stopped is
        // pending now. Keep the rest (SIGCONT, SIGWINCH) for the loop.
        let sigs = self.session.take_signals();
        if let Some(s) = ending(sigs) {
            return Ok(Some(s));
        }
        self.session.keep_signals(sigs);
        self.session.resume()?;
        self.abandon_frame(link);
        self.player.apply(Command::Redraw);
        if let Some(ws) = self.session.size() {
            let (cols, rows) = ws.cells();
            self.resize(cols, rows)?;
        }
        Ok(None)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_map_to_actions() {
        let cmd = |k| {
            action_for(k).and_then(|a| match a {
                Action::Player(c) => Some(c),
                Action::Suspend => None,
            })
        };
        assert_eq!(cmd(Key::Char('q')), Some(Command::Quit));
        assert_eq!(cmd(Key::Esc), Some(Command::Quit));
        assert_eq!(cmd(Key::Ctrl('c')), Some(Command::Quit));
        assert_eq!(cmd(Key::Char('c')), Some(Command::NextColor));
        assert_eq!(cmd(Key::Char(' ')), Some(Command::TogglePause));
        assert_eq!(cmd(Key::Char('m')), Some(Command::NextGlyphs));
        assert_eq!(cmd(Key::Char('s')), Some(Command::NextShading));
        assert_eq!(cmd(Key::Ctrl('l')), Some(Command::Redraw));
        assert_eq!(
            cmd(Key::Left),
            Some(Command::Orbit {
                yaw: -5.0,
                pitch: 0.0
            })
        );
        assert_eq!(cmd(Key::Char('+')), Some(Command::Zoom(0.9)));
        assert_eq!(action_for(Key::Ctrl('z')), Some(Action::Suspend));
        assert_eq!(action_for(Key::Char('x')), None);
        assert_eq!(action_for(Key::Other), None);
    }
}
