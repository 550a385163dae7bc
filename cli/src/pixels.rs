//! Pixels or character cells: which protocol frames are sent in, and how
//! many pixels a cell holds, from `--graphics`, `--cell-size`, what the
//! terminal answered to the probe and, where it was not asked (`render`),
//! what the environment says.
//!
//! `auto` takes the best the terminal has: the kitty graphics protocol
//! where it answers the kitty query (or, unasked, where kitty, Ghostty or
//! WezTerm say so in the environment), sixel where its device attributes
//! list it (or foot, unasked), iTerm2's images where iTerm2 says so, and
//! character cells everywhere else: where stdout is not a terminal, and
//! inside tmux, where rastty sends pixels only as sixel that tmux draws
//! itself (its own device attributes list sixel: tmux 3.4 and later, built
//! with it); the outer terminal's kitty or iTerm2 images would pass
//! through tmux only with `allow-passthrough` on, at the outer terminal's
//! cursor rather than the pane's, and stay as the pane scrolls: said on
//! stderr. A cell's pixels
//! are `--cell-size`, else the terminal's answer (`CSI 16 t`, else `14 t`
//! over the cells), else the window size's pixel fields, else assumed
//! (10×20, said).

use rastty::graphics::Protocol;
use rastty::picture::CellPx;

use crate::cli::GraphicsArg;
use crate::terminal::WindowSize;
use crate::terminal::probe::Capabilities;

/// A cell's pixels where nothing says: a common monospace cell at 100 %.
pub const ASSUMED_CELL: [u16; 2] = [10, 20];

/// Frames as pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Graphics {
    pub protocol: Protocol,
    /// A cell's pixels, across and down.
    pub cell: [u16; 2],
    /// Sixel colour registers (256 where the terminal did not say).
    pub registers: u16,
    /// The terminal's default background, where it said (OSC 11).
    pub background: Option<rastty::color::Rgb>,
}

/// What `--graphics` chose, and what to tell the user about it.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Choice {
    pub graphics: Option<Graphics>,
    pub notes: Vec<String>,
}

/// Chooses: `asked` and `cell_size` are the flags, `tty` whether stdout is
/// a terminal, `env` the environment, `size` the window's size and `caps`
/// the probe's answers (all `None` where it was not run).
pub fn choose(
    asked: GraphicsArg,
    cell_size: Option<CellPx>,
    tty: bool,
    env: &dyn Fn(&str) -> Option<String>,
    size: Option<WindowSize>,
    caps: &Capabilities,
) -> Choice {
    let mut notes = Vec::new();
    let protocol = match asked {
        GraphicsArg::Cells => None,
        GraphicsArg::Auto if !tty => None,
        // Inside tmux the device attributes are tmux's own: a sixel there
        // is one tmux draws itself (3.4 and later, built with it), in its
        // pane, kept as it scrolls.
        GraphicsArg::Auto if env("TMUX").is_some() && caps.sixel == Some(true) => {
            Some(Protocol::Sixel)
        }
        GraphicsArg::Auto => {
            let found = detect(env, caps);
            if found.is_some() && env("TMUX").is_some() {
                notes.push(
                    "inside tmux rastty draws character cells: tmux passes the outer terminal's images on only with allow-passthrough on, wrapped, and places them at its own cursor rather than the pane's (tmux 3.4 built with sixel draws sixel itself, and is used where it says so)".into(),
                );
                None
            } else {
                found
            }
        }
        explicit => explicit.protocol(),
    };
    let Some(protocol) = protocol else {
        return Choice {
            graphics: None,
            notes,
        };
    };
    let cell = match cell_size {
        Some(c) => [c.w, c.h],
        None => match terminal_cell(size, caps) {
            Some(c) => c,
            None => {
                notes.push(format!(
                    "the terminal does not say how many pixels a cell is: {}×{} assumed (--cell-size W×H)",
                    ASSUMED_CELL[0], ASSUMED_CELL[1]
                ));
                ASSUMED_CELL
            }
        },
    };
    Choice {
        graphics: Some(Graphics {
            protocol,
            cell,
            registers: caps.sixel_registers.unwrap_or(256),
            background: caps.background,
        }),
        notes,
    }
}

/// The protocol the terminal answered for, or its environment names.
fn detect(env: &dyn Fn(&str) -> Option<String>, caps: &Capabilities) -> Option<Protocol> {
    if caps.kitty == Some(true) {
        return Some(Protocol::Kitty);
    }
    if caps.sixel == Some(true) {
        return Some(Protocol::Sixel);
    }
    let is = |k: &str, v: &str| env(k).is_some_and(|x| x == v);
    let term = env("TERM").unwrap_or_default();
    let program = env("TERM_PROGRAM").unwrap_or_default();
    if is("TERM_PROGRAM", "iTerm.app") || is("LC_TERMINAL", "iTerm2") {
        return Some(Protocol::Iterm);
    }
    // Where the probe ran and the terminal answered without a yes, the
    // environment (which ssh and sudo carry) is not taken over it.
    if caps.kitty == Some(false) && caps.sixel.is_some() {
        return None;
    }
    if env("KITTY_WINDOW_ID").is_some()
        || term == "xterm-kitty"
        || term == "xterm-ghostty"
        || program == "ghostty"
        || program == "WezTerm"
    {
        return Some(Protocol::Kitty);
    }
    if term.starts_with("foot") {
        return Some(Protocol::Sixel);
    }
    None
}

/// A cell's pixels as the terminal says: its answer to `CSI 16 t`, else
/// its text area's over its cells, else the window size's pixel fields.
fn terminal_cell(size: Option<WindowSize>, caps: &Capabilities) -> Option<[u16; 2]> {
    if let Some(c) = caps.cell_px {
        return Some(c);
    }
    let cells = size
        .map(|s| (s.cols, s.rows))
        .filter(|&(c, r)| c > 0 && r > 0)?;
    let [w, h] = caps.window_px.or_else(|| {
        size.filter(|s| s.width_px > 0 && s.height_px > 0)
            .map(|s| [s.width_px, s.height_px])
    })?;
    let cell = [w / cells.0, h / cells.1];
    (cell[0] > 0 && cell[1] > 0).then_some(cell)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn env_of(pairs: &'static [(&'static str, &'static str)]) -> impl Fn(&str) -> Option<String> {
        move |k| {
            pairs
                .iter()
                .find(|(n, _)| *n == k)
                .map(|(_, v)| v.to_string())
        }
    }

    fn size(cols: u16, rows: u16, w: u16, h: u16) -> Option<WindowSize> {
        Some(WindowSize {
            cols,
            rows,
            width_px: w,
            height_px: h,
        })
    }

    #[test]
    fn answers_choose_the_protocol_and_the_cell() {
        let none = env_of(&[]);
        let kitty = Capabilities {
            kitty: Some(true),
            sixel: Some(false),
            cell_px: Some([9, 18]),
            ..Default::default()
        };
        let c = choose(
            GraphicsArg::Auto,
            None,
            true,
            &none,
            size(80, 24, 0, 0),
            &kitty,
        );
        assert_eq!(
            c.graphics,
            Some(Graphics {
                protocol: Protocol::Kitty,
                cell: [9, 18],
                registers: 256,
                background: None,
            })
        );
        assert!(c.notes.is_empty());
        let sixel = Capabilities {
            kitty: Some(false),
            sixel: Some(true),
            sixel_registers: Some(16),
            window_px: Some([800, 480]),
            ..Default::default()
        };
        let c = choose(
            GraphicsArg::Auto,
            None,
            true,
            &none,
            size(80, 24, 0, 0),
            &sixel,
        );
        assert_eq!(
            c.graphics,
            Some(Graphics {
                protocol: Protocol::Sixel,
                cell: [10, 20],
                registers: 16,
                background: None,
            })
        );
        // Neither: cells, even where the environment says kitty.
        let neither = Capabilities {
            kitty: Some(false),
            sixel: Some(false),
            ..Default::default()
        };
        let kitty_env = env_of(&[("TERM", "xterm-kitty")]);
        assert_eq!(
            choose(GraphicsArg::Auto, None, true, &kitty_env, None, &neither),
            Choice::default()
        );
        // No answer at all (render asks nothing): the environment.
        let c = choose(
            GraphicsArg::Auto,
            None,
            true,
            &kitty_env,
            size(100, 50, 1000, 1000),
            &Capabilities::default(),
        );
        assert_eq!(
            c.graphics.map(|g| (g.protocol, g.cell)),
            Some((Protocol::Kitty, [10, 20]))
        );
        let c = choose(
            GraphicsArg::Auto,
            None,
            true,
            &env_of(&[("LC_TERMINAL", "iTerm2")]),
            None,
            &Capabilities::default(),
        );
        assert_eq!(c.graphics.map(|g| g.protocol), Some(Protocol::Iterm));
        assert_eq!(c.notes.len(), 1, "{:?}", c.notes);
        assert!(c.notes[0].contains("10×20 assumed"), "{:?}", c.notes);
    }

    #[test]
    fn cells_where_stdout_is_not_a_terminal_inside_tmux_and_when_asked() {
        let kitty = Capabilities {
            kitty: Some(true),
            ..Default::default()
        };
        let none = env_of(&[]);
        assert_eq!(
            choose(GraphicsArg::Auto, None, false, &none, None, &kitty),
            Choice::default()
        );
        assert_eq!(
            choose(GraphicsArg::Cells, None, true, &none, None, &kitty),
            Choice::default()
        );
        let tmux = env_of(&[("TMUX", "/tmp/tmux-0/default,1,0")]);
        let c = choose(GraphicsArg::Auto, None, true, &tmux, None, &kitty);
        assert_eq!(c.graphics, None);
        assert!(c.notes[0].contains("inside tmux"), "{:?}", c.notes);
        // Asked by name, and sized by the flag: whatever the terminal says.
        let c = choose(
            GraphicsArg::Sixel,
            Some(CellPx { w: 7, h: 15 }),
            false,
            &tmux,
            None,
            &Capabilities::default(),
        );
        assert_eq!(
            c.graphics,
            Some(Graphics {
                protocol: Protocol::Sixel,
                cell: [7, 15],
                registers: 256,
                background: None,
            })
        );
    }

    /// What fake terminals answer to the probe, as bytes through the
    /// parser: the choice each gets.
    #[test]
    fn fake_terminals_answers_choose_as_each_terminal_can_draw() {
        use crate::terminal::input::Parser;
        let caps_of = |bytes: &[u8]| {
            let (mut parser, mut inputs) = (Parser::new(), Vec::new());
            parser.feed(bytes, &mut inputs);
            Capabilities::from_answers(&inputs)
        };
        let none = env_of(&[]);
        let pick = |bytes: &[u8], env: &dyn Fn(&str) -> Option<String>| {
            choose(
                GraphicsArg::Auto,
                None,
                true,
                env,
                size(80, 24, 0, 0),
                &caps_of(bytes),
            )
        };
        // kitty: the query answered OK, its cell size, attributes without 4.
        let kitty = b"\x1b_Gi=31;OK\x1b\\\x1b[6;20;10t\x1b[4;480;800t\x1b[?62;22c\x1b[0n";
        let c = pick(kitty, &none);
        assert_eq!(
            c.graphics.map(|g| (g.protocol, g.cell)),
            Some((Protocol::Kitty, [10, 20]))
        );
        // xterm as a VT340: no kitty answer, 4 in its attributes, 1024
        // registers, the text area's pixels alone.
        let xterm = b"\x1b[?1;0;1024S\x1b[4;480;800t\x1b]11;rgb:ffff/ffff/ffff\x1b\\\x1b[?63;1;2;4;6;9;15;22c\x1b[0n";
        let c = pick(xterm, &none);
        assert_eq!(
            c.graphics,
            Some(Graphics {
                protocol: Protocol::Sixel,
                cell: [10, 20],
                registers: 1024,
                background: Some(rastty::color::Rgb([255, 255, 255])),
            })
        );
        // A terminal with neither, whose environment claims kitty.
        let plain = b"\x1b_Gi=31;ENOTSUPPORTED:no\x1b\\\x1b[?62;22c\x1b[0n";
        let claims = env_of(&[("TERM", "xterm-kitty")]);
        assert_eq!(pick(plain, &claims), Choice::default());
        // tmux: the kitty query does not reach the terminal (tmux passes it
        // on only with allow-passthrough on), and tmux answers the
        // attributes itself: 3.3 without sixel, in a kitty window...
        let tmux = env_of(&[
            ("TMUX", "/tmp/tmux-0/default,1,0"),
            ("TERM", "tmux-256color"),
            ("KITTY_WINDOW_ID", "1"),
        ]);
        let c = pick(b"\x1b[?1;2c\x1b[0n", &tmux);
        assert_eq!(c.graphics, None);
        assert!(c.notes[0].contains("allow-passthrough"), "{:?}", c.notes);
        // ...and 3.4 built with sixel, which it draws in its pane.
        let c = pick(b"\x1b[?1;2;4c\x1b[0n", &tmux);
        assert_eq!(c.graphics.map(|g| g.protocol), Some(Protocol::Sixel));
        // No answer at all: the environment, else cells.
        assert_eq!(pick(b"", &none), Choice::default());
        assert_eq!(
            pick(b"", &claims).graphics.map(|g| g.protocol),
            Some(Protocol::Kitty)
        );
    }
}
