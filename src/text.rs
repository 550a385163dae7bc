//! Untrusted text made safe for a terminal: one sanitiser for every byte
//! that comes from a file or a command line and is shown to a person
//! (errors, notes, `--explain`, the status line).
//!
//! A model's names, URIs and paths, a scene file's keys and a user's
//! arguments are untrusted: written raw, `ESC ] 52` writes the clipboard,
//! `ESC ] 0` sets the window title, `ESC [ 2 J` clears the screen, a C1
//! `U+009B` is a CSI on many terminals, and `U+202E` turns the rest of a
//! line around. [`escape`] shows every C0 control, DEL and C1 control as
//! `\xNN` or `\u{NN}`, and the invisible characters that reorder or hide
//! text (bidi embeddings, overrides and isolates, zero-width characters,
//! line and paragraph separators, the byte order mark) as `\u{…}`; the
//! rest of Unicode passes as it is, so a name in Japanese reads as
//! itself. The escapes are printable and themselves pass unchanged, so
//! escaping twice is escaping once, and a message may be escaped where it
//! is built and again where it is shown.
//!
//! [`line()`] does that to a whole message that is to take one line
//! (newlines are escaped too) and cuts it to [`MAX_LINE_CHARS`] characters,
//! keeping its start (the file, line and column) and its end (what is
//! wrong) and saying how much was cut between: a 100 MB key in a TOML file
//! gives a 300-character error, not a 100 MB one.
//!
//! Trade-off: a backslash is not escaped, so a file named `a\x1bb` and a
//! file named `a` ESC `b` print alike; what reaches the terminal is safe
//! either way, and the messages stay readable.

use std::borrow::Cow;
use std::fmt::Write as _;

/// The longest line [`line()`] gives, in characters.
pub const MAX_LINE_CHARS: usize = 300;

/// Whether `c` must not reach a terminal as it is: a control character
/// (C0, DEL, C1) or a character that reorders or hides text.
pub fn is_unsafe(c: char) -> bool {
    c.is_control()
        || matches!(
            c,
            '\u{061c}'                // Arabic letter mark
            | '\u{200b}'..='\u{200f}' // zero-width space, joiners, LRM, RLM
            | '\u{2028}'..='\u{202e}' // separators, bidi embeddings and overrides
            | '\u{2060}'..='\u{2069}' // word joiner, invisible operators, bidi isolates
            | '\u{feff}'              // byte order mark, zero-width no-break space
            | '\u{fff9}'..='\u{fffb}' // interlinear annotations
        )
}

/// `s` with every unsafe character (see [`is_unsafe`]) shown as an escape:
/// `\x1b` below U+0080, `\u{9b}` above. Borrowed when nothing needed it.
pub fn escape(s: &str) -> Cow<'_, str> {
    if !s.chars().any(is_unsafe) {
        return Cow::Borrowed(s);
    }
    let mut out = String::with_capacity(s.len() + 8);
    for c in s.chars() {
        push_escaped(&mut out, c);
    }
    Cow::Owned(out)
}

fn push_escaped(out: &mut String, c: char) {
    if !is_unsafe(c) {
        out.push(c);
    } else if (c as u32) < 0x80 {
        let _ = write!(out, "\\x{:02x}", c as u32);
    } else {
        let _ = write!(out, "\\u{{{:x}}}", c as u32);
    }
}

/// `s` as one safe line: escaped (newlines included) and, if longer than
/// [`MAX_LINE_CHARS`] characters once escaped, cut in the middle with the
/// number of characters cut said there. Only what is kept is copied, so a
/// 100 MB message costs a pass over it, not a second 100 MB.
pub fn line(s: &str) -> String {
    cut(s, MAX_LINE_CHARS)
}

/// [`line()`] for a part of a line: escaped and cut to at most `max`
/// characters (at least 40), keeping about two thirds from its start and
/// a quarter from its end.
pub fn cut(s: &str, max: usize) -> String {
    let max = max.max(40);
    let (head_max, tail_max) = (max * 5 / 8, max / 4);
    let width = |c: char| if is_unsafe(c) { escaped_len(c) } else { 1 };
    let n: usize = s.chars().map(width).sum();
    let mut out = String::new();
    if n <= max {
        s.chars().for_each(|c| push_escaped(&mut out, c));
        return out;
    }
    // Whole escapes only: an escape is never cut in two.
    let (mut head, mut head_len) = (String::new(), 0);
    let mut escaped = String::new();
    for c in s.chars() {
        escaped.clear();
        push_escaped(&mut escaped, c);
        let w = escaped.chars().count();
        if head_len + w > head_max {
            break;
        }
        head.push_str(&escaped);
        head_len += w;
    }
    let (mut back, mut tail_len) = (Vec::new(), 0);
    for c in s.chars().rev() {
        let w = width(c);
        if tail_len + w > tail_max {
            break;
        }
        back.push(c);
        tail_len += w;
    }
    let mut tail = String::new();
    back.iter().rev().for_each(|&c| push_escaped(&mut tail, c));
    let _ = write!(
        out,
        "{head} … [{} characters cut] … {tail}",
        n - head_len - tail_len
    );
    out
}

/// The characters `c`'s escape takes.
fn escaped_len(c: char) -> usize {
    if (c as u32) < 0x80 {
        4
    } else {
        // \u{ + hex digits + }
        4 + (32 - (c as u32).leading_zeros() as usize).div_ceil(4)
    }
}

/// `s` shown as a quoted name: escaped and, if long, cut to `max`
/// characters with its length said (for a name inside a message that says
/// more after it).
pub fn name(s: &str, max: usize) -> String {
    let escaped = escape(s);
    let n = escaped.chars().count();
    if n <= max {
        return format!("\"{escaped}\"");
    }
    let head: String = escaped.chars().take(max).collect();
    format!("\"{head}…\" ({} characters)", s.chars().count())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn controls_c1_and_bidi_are_escaped_and_the_rest_passes() {
        assert_eq!(
            escape("a\x1b]52;c;SGVsbG8=\x07b\u{9b}2Jc\u{202e}d\u{7f}e"),
            "a\\x1b]52;c;SGVsbG8=\\x07b\\u{9b}2Jc\\u{202e}d\\x7fe"
        );
        assert_eq!(escape("bunny.obj 兔子 é"), "bunny.obj 兔子 é");
        assert!(matches!(escape("plain"), Cow::Borrowed(_)));
        assert_eq!(escape("a\nb\tc"), "a\\x0ab\\x09c");
        for c in ['\u{200b}', '\u{2066}', '\u{2069}', '\u{feff}', '\u{85}'] {
            assert!(is_unsafe(c), "{c:?}");
        }
    }

    #[test]
    fn escaping_twice_is_escaping_once() {
        let s = "x\x1b[2J\u{202e}\u{9b}";
        assert_eq!(escape(&escape(s)), escape(s));
        assert_eq!(line(&line(s)), line(s));
    }

    #[test]
    fn a_long_line_is_cut_in_the_middle_with_its_length_said() {
        let s = format!("file.toml:1:5: unknown key `{}` here", "k".repeat(100_000));
        let l = line(&s);
        assert!(l.chars().count() <= MAX_LINE_CHARS, "{}", l.chars().count());
        assert!(l.starts_with("file.toml:1:5: unknown key `kkk"), "{l}");
        assert!(l.ends_with("kkk` here"), "{l}");
        assert!(l.contains(" … [99772 characters cut] … "), "{l}");
        // Escapes count as what they show.
        let l = line(&"\x1b".repeat(1000));
        assert!(l.chars().count() <= MAX_LINE_CHARS);
        assert!(!l.contains('\x1b'));
        assert_eq!(line("short"), "short");
    }

    #[test]
    fn a_long_name_is_cut_with_its_length() {
        assert_eq!(name("ab\x1b", 10), "\"ab\\x1b\"");
        assert_eq!(name(&"n".repeat(50), 4), "\"nnnn…\" (50 characters)");
    }
}
