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

/// The colour depth `--color auto` picks: none when `NO_COLOR` is set and
/// non-empty or stdout is not a terminal, truecolor otherwise. `env` looks
/// up an environment variable (a parameter so that tests need not touch the
/// process's environment).
pub fn detect_color(stdout_is_tty: bool, env: impl Fn(&str) -> Option<String>) -> ColorDepth {
    let no_color = env("NO_COLOR").is_some_and(|v| !v.is_empty());
    if no_color || !stdout_is_tty {
        ColorDepth::None
    } else {
        ColorDepth::TrueColor
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn auto_colour_rules() {
        let none = |_: &str| None;
        let no_color = |k: &str| (k == "NO_COLOR").then(|| "1".to_string());
        let empty_no_color = |k: &str| (k == "NO_COLOR").then(String::new);
        assert_eq!(detect_color(false, none), ColorDepth::None);
        assert_eq!(detect_color(true, no_color), ColorDepth::None);
        assert_eq!(detect_color(true, empty_no_color), ColorDepth::TrueColor);
        assert_eq!(detect_color(true, none), ColorDepth::TrueColor);
    }
}
