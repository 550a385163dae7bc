//! What the program says on stderr (`error:`, `note:`, `--explain`'s
//! report), and stdout as the program writes to it.

use std::io::{self, Write};
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};

use crate::terminal;

/// For `render --preview --cols N`: the width every line on stderr is cut
/// to, and the model's path (shortened to its file name where a line is
/// wider).
pub static FIT: std::sync::OnceLock<(usize, Option<std::path::PathBuf>)> =
    std::sync::OnceLock::new();

/// `line` in `width` characters: the model's path shortened to its file
/// name where the line is wider, then the end cut off with `…` (the start
/// says which file and what is wrong).
fn fitted(line: &str, width: usize, path: Option<&Path>) -> String {
    let width = width.max(1);
    let mut line = line.to_string();
    if line.chars().count() > width
        && let Some(path) = path
        && let Some(name) = path.file_name()
    {
        let (full, name) = (path.to_string_lossy(), name.to_string_lossy());
        line = line.replacen(full.as_ref(), name.as_ref(), 1);
    }
    if line.chars().count() <= width {
        return line;
    }
    let mut cut: String = line.chars().take(width - 1).collect();
    cut.push('…');
    cut
}

/// For `render --preview --cols N`, cuts every line said to N columns.
pub fn fit_previews(cli: &crate::cli::Cli) {
    if let Some(crate::cli::Command::Render(args)) = &cli.command
        && args.preview
        && let Some(w) = args.view.cols
    {
        let _ = FIT.set((usize::from(w), args.input.scene.clone()));
    }
}

/// Set when a line for stderr could not be written.
static UNSAID: AtomicBool = AtomicBool::new(false);

/// Writes `message` on stderr as one line after `label` (`error`,
/// `note`), escaped and cut as [`rastty::text::line()`] does: a name from a
/// file never drives the terminal. A stderr that cannot be written (full,
/// closed) is not a reason to panic, and not a success: the exit status
/// is 1.
pub fn say(label: &str, message: &str) {
    say_lines(&format!("{label}: {}", rastty::text::line(message)));
}

/// Writes `text` on stderr line by line, each escaped (for messages of
/// several lines: clap's, `--explain`'s).
pub fn say_lines(text: &str) {
    let mut err = io::stderr().lock();
    let mut ok = terminal::is_open(2);
    for l in text.lines() {
        let l = rastty::text::escape(l);
        let l = match FIT.get() {
            Some((width, path)) => fitted(&l, *width, path.as_deref()).into(),
            None => l,
        };
        ok &= writeln!(err, "{l}").is_ok();
    }
    ok &= err.flush().is_ok();
    if !ok {
        UNSAID.store(true, Ordering::Relaxed);
    }
}

/// Stdout, refused when it is closed (`>&-`): the standard library would
/// take every write to it as done.
pub fn stdout() -> rastty::Result<io::StdoutLock<'static>> {
    if !terminal::is_open(1) {
        #[cfg(unix)]
        let closed = io::Error::from_raw_os_error(libc::EBADF);
        #[cfg(not(unix))]
        let closed = io::Error::other("stdout is closed");
        return Err(stdout_error(closed));
    }
    Ok(io::stdout().lock())
}

/// Whether something to say was lost (stderr full or closed): then the
/// exit status is 1.
pub fn unsaid() -> bool {
    UNSAID.load(Ordering::Relaxed)
}

pub fn is_broken_pipe(e: &rastty::Error) -> bool {
    matches!(e, rastty::Error::Io { source, .. } if source.kind() == io::ErrorKind::BrokenPipe)
}

pub fn stdout_error(e: io::Error) -> rastty::Error {
    rastty::Error::io("<stdout>".as_ref(), e)
}
