//! Mouse reports to the player's commands: a drag turns the view (with the
//! right button, or Shift held, it pans), the wheel zooms, a double click
//! resets.
//!
//! A drag is sent as the cells moved since the last report, so that many
//! reports read in one go (a slow link delivers them in bursts) are each a
//! small [`Command::Drag`], all applied before the next frame is drawn: a
//! burst costs one frame, and a `q` read in the same burst is heard as
//! soon as it is reached. The conversion of cells to angles is the
//! library's ([`rastty::scene::View::drag`]), so the ratatui viewer's drags
//! turn a model as `spin`'s do.

use std::time::{Duration, Instant};

use crate::terminal::input::{Button, Mouse, MouseKind};
use rastty::animate::Command;

/// Two presses of the left button on one cell within this long are a
/// double click.
pub const DOUBLE_CLICK: Duration = Duration::from_millis(400);

/// The factor a notch of the wheel multiplies the eye's distance by (the
/// `+` key's).
pub const WHEEL_ZOOM: f32 = 0.9;

/// What the mouse is doing between reports.
#[derive(Clone, Copy, Debug, Default)]
pub struct Pointer {
    /// The cell of the last report of a held button, and whether it pans.
    held: Option<(u16, u16, bool)>,
    /// The last press of the left button: when and where.
    last_press: Option<(Instant, u16, u16)>,
}

impl Pointer {
    /// The command a report asks for, if any, `now` being when it was read.
    pub fn command(&mut self, m: Mouse, now: Instant) -> Option<Command> {
        match m.kind {
            MouseKind::Press(button) => {
                let pan = button != Button::Left || m.shift;
                if button == Button::Left {
                    let double = self.last_press.is_some_and(|(t, col, row)| {
                        now.duration_since(t) <= DOUBLE_CLICK && (col, row) == (m.col, m.row)
                    });
                    if double {
                        self.last_press = None;
                        self.held = None;
                        return Some(Command::Reset);
                    }
                    self.last_press = Some((now, m.col, m.row));
                }
                self.held = Some((m.col, m.row, pan));
                None
            }
            MouseKind::Drag(button) => {
                let pan = button != Button::Left || m.shift;
                // A drag whose press was not seen (it began before spin
                // asked for reports) starts where it is first seen.
                let (col, row, pan) = self.held.unwrap_or((m.col, m.row, pan));
                self.held = Some((m.col, m.row, pan));
                // Moved: no longer a click.
                self.last_press = None;
                let cells = rastty::glam::Vec2::new(
                    f32::from(m.col) - f32::from(col),
                    f32::from(m.row) - f32::from(row),
                );
                (cells != rastty::glam::Vec2::ZERO).then_some(Command::Drag { cells, pan })
            }
            MouseKind::Release => {
                self.held = None;
                None
            }
            MouseKind::Wheel(away) => Some(Command::Zoom(if away {
                WHEEL_ZOOM
            } else {
                1.0 / WHEEL_ZOOM
            })),
            MouseKind::Move => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rastty::glam::Vec2;

    fn at(kind: MouseKind, col: u16, row: u16) -> Mouse {
        Mouse {
            kind,
            col,
            row,
            shift: false,
        }
    }

    #[test]
    fn a_drag_is_the_cells_moved_since_the_last_report() {
        let mut p = Pointer::default();
        let t = Instant::now();
        let left = Button::Left;
        assert_eq!(p.command(at(MouseKind::Press(left), 10, 5), t), None);
        assert_eq!(
            p.command(at(MouseKind::Drag(left), 13, 5), t),
            Some(Command::Drag {
                cells: Vec2::new(3.0, 0.0),
                pan: false
            })
        );
        assert_eq!(
            p.command(at(MouseKind::Drag(left), 12, 7), t),
            Some(Command::Drag {
                cells: Vec2::new(-1.0, 2.0),
                pan: false
            })
        );
        // No move, no command.
        assert_eq!(p.command(at(MouseKind::Drag(left), 12, 7), t), None);
        assert_eq!(p.command(at(MouseKind::Release, 12, 7), t), None);
        // The right button, or Shift, pans.
        p.command(at(MouseKind::Press(Button::Right), 0, 0), t);
        assert_eq!(
            p.command(at(MouseKind::Drag(Button::Right), 1, 0), t),
            Some(Command::Drag {
                cells: Vec2::new(1.0, 0.0),
                pan: true
            })
        );
        p.command(at(MouseKind::Release, 1, 0), t);
        let shifted = |kind| Mouse {
            shift: true,
            ..at(kind, 4, 4)
        };
        p.command(shifted(MouseKind::Press(left)), t);
        let moved = Mouse {
            col: 6,
            ..shifted(MouseKind::Drag(left))
        };
        assert_eq!(
            p.command(moved, t),
            Some(Command::Drag {
                cells: Vec2::new(2.0, 0.0),
                pan: true
            })
        );
    }

    #[test]
    fn two_clicks_on_one_cell_reset_and_the_wheel_zooms() {
        let mut p = Pointer::default();
        let t = Instant::now();
        let press = at(MouseKind::Press(Button::Left), 3, 3);
        let release = at(MouseKind::Release, 3, 3);
        assert_eq!(p.command(press, t), None);
        p.command(release, t);
        assert_eq!(
            p.command(press, t + Duration::from_millis(200)),
            Some(Command::Reset)
        );
        // Too slow, or elsewhere, or after a drag: not a double click.
        let mut p = Pointer::default();
        p.command(press, t);
        assert_eq!(p.command(press, t + Duration::from_millis(500)), None);
        let mut p = Pointer::default();
        p.command(press, t);
        assert_eq!(p.command(at(MouseKind::Press(Button::Left), 4, 3), t), None);
        let mut p = Pointer::default();
        p.command(press, t);
        p.command(at(MouseKind::Drag(Button::Left), 5, 3), t);
        p.command(release, t);
        assert_eq!(p.command(press, t), None);
        assert_eq!(
            p.command(at(MouseKind::Wheel(true), 0, 0), t),
            Some(Command::Zoom(WHEEL_ZOOM))
        );
        assert_eq!(
            p.command(at(MouseKind::Wheel(false), 0, 0), t),
            Some(Command::Zoom(1.0 / WHEEL_ZOOM))
        );
    }
}
