//! The library's errors: each says what went wrong and where (the file, and
//! the line and column where the format has lines). What an error shows
//! is escaped ([`crate::text::escape`]): a path or a name from a file in
//! it never reaches a terminal raw, whoever prints it.

use std::io;
use std::path::Path;

use crate::text::escape;

/// Everything the library can refuse.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A file could not be read.
    #[error("{}: {source}", escape(path))]
    Io {
        /// The file.
        path: String,
        #[source]
        /// What went wrong.
        source: io::Error,
    },
    /// A file was read but its contents are wrong.
    #[error("{}:{line}:{column}: {}", escape(path), escape(message))]
    Parse {
        /// The file.
        path: String,
        /// The line, from 1.
        line: usize,
        /// The column, from 1.
        column: usize,
        /// What is wrong there.
        message: String,
    },
    /// A setting out of range.
    #[error("{}", escape(.0))]
    Invalid(String),
}

impl Error {
    /// A file that could not be read, named by its path.
    pub fn io(path: &Path, source: io::Error) -> Error {
        Error::Io {
            path: path.display().to_string(),
            source,
        }
    }

    /// A parse error at byte `offset` of `src`.
    pub fn parse_at(path: &str, src: &str, offset: usize, message: impl AsRef<str>) -> Error {
        let (line, column) = line_col(src, offset);
        Error::Parse {
            path: path.to_string(),
            line,
            column,
            // A file's text in a message (a key, a value) may be
            // megabytes: it is kept escaped and cut, as it will be shown.
            message: crate::text::cut(message.as_ref(), 200),
        }
    }
}

/// 1-based line and column (in characters) of a byte offset.
pub fn line_col(src: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(src.len());
    let before = &src.as_bytes()[..offset];
    let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
    let line_start = before
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |i| i + 1);
    let column = String::from_utf8_lossy(&before[line_start..])
        .chars()
        .count()
        + 1;
    (line, column)
}

/// rastty's result: [`Error`] unless said otherwise.
pub type Result<T, E = Error> = std::result::Result<T, E>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_col_counts_from_one() {
        let s = "ab\ncd\n\u{e9}f";
        assert_eq!(line_col(s, 0), (1, 1));
        assert_eq!(line_col(s, 1), (1, 2));
        assert_eq!(line_col(s, 3), (2, 1));
        assert_eq!(line_col(s, 8), (3, 2));
        assert_eq!(line_col(s, 999), (3, 3));
    }
}
