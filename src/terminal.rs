//! Stage 8: the terminal, through crossterm: its size, its cells' shape,
//! and what colour it can show.

use std::io::IsTerminal;

use crate::color::ColorDepth;

/// Whether stdout is a terminal.
pub fn stdout_is_terminal() -> bool {
    std::io::stdout().is_terminal()
}

/// The terminal's size in cells, if it reports one.
pub fn size() -> Option<(u16, u16)> {
    crossterm::terminal::size()
        .ok()
        .filter(|&(c, r)| c > 0 && r > 0)
}

/// A cell's width over its height, from the terminal's pixel size where it
/// reports one (many do not, and ssh often reports zero).
pub fn cell_aspect() -> Option<f32> {
    let ws = crossterm::terminal::window_size().ok()?;
    if ws.width == 0 || ws.height == 0 || ws.columns == 0 || ws.rows == 0 {
        return None;
    }
    let cell_w = ws.width as f32 / ws.columns as f32;
    let cell_h = ws.height as f32 / ws.rows as f32;
    Some(cell_w / cell_h).filter(|a| a.is_finite() && *a > 0.0)
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
pub fn detect_color(stdout_is_tty: bool, env: impl Fn(&str) -> Option<String>) -> ColorDepth {
    let set = |k: &str| env(k).filter(|v| !v.is_empty());
    if set("NO_COLOR").is_some() || !stdout_is_tty {
        return ColorDepth::None;
    }
    let term = set("TERM").unwrap_or_default();
    if term.is_empty() || term == "dumb" {
        return ColorDepth::None;
    }
    let colorterm = set("COLORTERM").unwrap_or_default().to_ascii_lowercase();
    if colorterm == "truecolor"
        || colorterm == "24bit"
        || term.ends_with("-direct")
        || term.ends_with("-truecolor")
    {
        ColorDepth::TrueColor
    } else if term.contains("256color") {
        ColorDepth::Ansi256
    } else {
        ColorDepth::Ansi16
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
