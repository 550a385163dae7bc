//! crossterm's events as rastty's inputs: how a Windows console's keys,
//! mouse and resizes reach the loop (`windows.rs` reads them), in the same
//! [`Input`]s the unix byte parser makes. Pure, so it is tested on every
//! platform.
//!
//! A key counts once a press: a console reports a press and a release for
//! every key, and a key held down repeats its press (both kept, as a
//! terminal's autorepeat is); releases are dropped. Ctrl with a letter or
//! `\` is the control key the byte parser reads from a tty.

use crossterm::event::{
    Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};

use super::input::{Button, Input, Key, Mouse, MouseKind};

/// What an event is for the loop.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Happened {
    /// A key or a mouse report.
    Input(Input),
    /// The window is now this many columns and rows.
    Resized(u16, u16),
}

/// `event` as the loop reads it; `None` for what it does not use (a key's
/// release, focus, a paste).
pub fn happened(event: &Event) -> Option<Happened> {
    match event {
        Event::Key(k) => key(k).map(|k| Happened::Input(Input::Key(k))),
        Event::Mouse(m) => mouse(m).map(|m| Happened::Input(Input::Mouse(m))),
        Event::Resize(cols, rows) => Some(Happened::Resized(*cols, *rows)),
        _ => None,
    }
}

/// A key press (or its repeat) as [`Key`].
fn key(k: &KeyEvent) -> Option<Key> {
    if k.kind == KeyEventKind::Release {
        return None;
    }
    let ctrl = k.modifiers.contains(KeyModifiers::CONTROL);
    let alt = k.modifiers.contains(KeyModifiers::ALT);
    Some(match k.code {
        // Ctrl and Alt together is AltGr on many keyboards: the character.
        KeyCode::Char(c) if ctrl && !alt && (c.is_ascii_alphabetic() || c == '\\') => {
            Key::Ctrl(c.to_ascii_lowercase())
        }
        KeyCode::Char(_) if alt && !ctrl => Key::Other,
        KeyCode::Char(c) => Key::Char(c),
        KeyCode::Esc => Key::Esc,
        KeyCode::Enter => Key::Enter,
        KeyCode::Up => Key::Up,
        KeyCode::Down => Key::Down,
        KeyCode::Left => Key::Left,
        KeyCode::Right => Key::Right,
        _ => Key::Other,
    })
}

/// A mouse event as [`Mouse`].
fn mouse(m: &MouseEvent) -> Option<Mouse> {
    let button = |b: MouseButton| match b {
        MouseButton::Left => Button::Left,
        MouseButton::Middle => Button::Middle,
        MouseButton::Right => Button::Right,
    };
    let kind = match m.kind {
        MouseEventKind::Down(b) => MouseKind::Press(button(b)),
        MouseEventKind::Up(_) => MouseKind::Release,
        MouseEventKind::Drag(b) => MouseKind::Drag(button(b)),
        MouseEventKind::Moved => MouseKind::Move,
        MouseEventKind::ScrollUp => MouseKind::Wheel(true),
        MouseEventKind::ScrollDown => MouseKind::Wheel(false),
        MouseEventKind::ScrollLeft | MouseEventKind::ScrollRight => return None,
    };
    Some(Mouse {
        kind,
        col: m.column,
        row: m.row,
        shift: m.modifiers.contains(KeyModifiers::SHIFT),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::live::{Action, action_for};
    use crossterm::event::KeyEventState;
    use rastty::animate::Command;

    fn press(code: KeyCode, modifiers: KeyModifiers, kind: KeyEventKind) -> Event {
        Event::Key(KeyEvent {
            code,
            modifiers,
            kind,
            state: KeyEventState::NONE,
        })
    }

    /// The command a console's key event gives, as the loop applies it.
    fn command(e: &Event) -> Option<Command> {
        match happened(e)? {
            Happened::Input(Input::Key(k)) => match action_for(k)? {
                Action::Player(c) => Some(c),
                Action::Suspend => None,
            },
            _ => None,
        }
    }

    #[test]
    fn a_console_key_counts_once_a_press_and_maps_to_its_command() {
        use KeyEventKind::{Press, Release, Repeat};
        let none = KeyModifiers::NONE;
        // A press and its release: one command.
        let q = [
            press(KeyCode::Char('q'), none, Press),
            press(KeyCode::Char('q'), none, Release),
        ];
        let commands: Vec<_> = q.iter().filter_map(command).collect();
        assert_eq!(commands, [Command::Quit]);
        // Held: each repeat orbits again.
        let held = [
            press(KeyCode::Left, none, Press),
            press(KeyCode::Left, none, Repeat),
            press(KeyCode::Left, none, Release),
        ];
        assert_eq!(held.iter().filter_map(command).count(), 2);
        // Ctrl-C, as raw mode delivers it (a key, not a signal), quits.
        let ctrl_c = press(KeyCode::Char('c'), KeyModifiers::CONTROL, Press);
        assert_eq!(command(&ctrl_c), Some(Command::Quit));
        assert_eq!(
            happened(&ctrl_c),
            Some(Happened::Input(Input::Key(Key::Ctrl('c'))))
        );
        // Shift gives the character the console reports.
        let plus = press(KeyCode::Char('+'), KeyModifiers::SHIFT, Press);
        assert_eq!(command(&plus), Some(Command::Zoom(0.9)));
        // AltGr (Ctrl and Alt) types its character; Alt alone is nothing.
        let altgr = press(
            KeyCode::Char('['),
            KeyModifiers::CONTROL | KeyModifiers::ALT,
            Press,
        );
        assert_eq!(command(&altgr), Some(Command::Clip(-1)));
        let alt = press(KeyCode::Char('q'), KeyModifiers::ALT, Press);
        assert_eq!(command(&alt), None);
        assert_eq!(
            command(&press(KeyCode::Esc, none, Press)),
            Some(Command::Quit)
        );
        assert_eq!(
            happened(&press(KeyCode::F(5), none, Press)),
            Some(Happened::Input(Input::Key(Key::Other)))
        );
    }

    #[test]
    fn console_mouse_events_are_the_reports_a_terminal_sends() {
        let at = |kind, modifiers| {
            happened(&Event::Mouse(MouseEvent {
                kind,
                column: 12,
                row: 3,
                modifiers,
            }))
        };
        let m = |kind, shift| {
            Some(Happened::Input(Input::Mouse(Mouse {
                kind,
                col: 12,
                row: 3,
                shift,
            })))
        };
        let none = KeyModifiers::NONE;
        assert_eq!(
            at(MouseEventKind::Down(MouseButton::Left), none),
            m(MouseKind::Press(Button::Left), false)
        );
        assert_eq!(
            at(
                MouseEventKind::Drag(MouseButton::Right),
                KeyModifiers::SHIFT
            ),
            m(MouseKind::Drag(Button::Right), true)
        );
        assert_eq!(
            at(MouseEventKind::Up(MouseButton::Left), none),
            m(MouseKind::Release, false)
        );
        assert_eq!(
            at(MouseEventKind::ScrollUp, none),
            m(MouseKind::Wheel(true), false)
        );
        assert_eq!(
            at(MouseEventKind::ScrollDown, none),
            m(MouseKind::Wheel(false), false)
        );
        assert_eq!(at(MouseEventKind::ScrollLeft, none), None);
        assert_eq!(
            happened(&Event::Resize(120, 40)),
            Some(Happened::Resized(120, 40))
        );
        assert_eq!(happened(&Event::FocusLost), None);
    }

    #[test]
    fn a_console_drag_orbits_as_a_terminals_does() {
        // The same drag through the byte parser's reports and through the
        // console's events gives the same commands.
        let t0 = std::time::Instant::now();
        let ev = |kind, col, row| {
            Event::Mouse(MouseEvent {
                kind,
                column: col,
                row,
                modifiers: KeyModifiers::NONE,
            })
        };
        let console = [
            ev(MouseEventKind::Down(MouseButton::Left), 10, 5),
            ev(MouseEventKind::Drag(MouseButton::Left), 14, 5),
            ev(MouseEventKind::Up(MouseButton::Left), 14, 5),
        ];
        let mut parsed = Vec::new();
        super::super::input::Parser::new()
            .feed(b"\x1b[<0;11;6M\x1b[<32;15;6M\x1b[<0;15;6m", &mut parsed);
        let commands = |inputs: Vec<Input>| {
            let mut p = crate::gesture::Pointer::default();
            inputs
                .into_iter()
                .filter_map(|i| match i {
                    Input::Mouse(m) => p.command(m, t0),
                    _ => None,
                })
                .collect::<Vec<_>>()
        };
        let from_console = console
            .iter()
            .filter_map(|e| match happened(e) {
                Some(Happened::Input(i)) => Some(i),
                _ => None,
            })
            .collect();
        assert_eq!(commands(from_console), commands(parsed.clone()));
        assert!(!commands(parsed).is_empty());
    }
}
