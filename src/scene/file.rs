//! Opening model and scene files safely, and reading them line by line.
//!
//! A path is checked before a byte is read: a directory, a FIFO (which would
//! block forever), a device (`/dev/zero`, which never ends), a socket are
//! refused at once, and so is a regular file larger than the limit
//! ([`DEFAULT_MAX_BYTES`], 1 GiB, raised by `--max-file-size`), so a sparse
//! 4 GB file is an error in a millisecond, not two minutes and 8 GB of
//! memory. Lines are read through a buffer of 64 KiB, never the whole file,
//! and a line longer than [`MAX_LINE`] is an error rather than an
//! allocation sized by the file.

use std::fs::File;
use std::io::{BufRead, BufReader, Read};

use std::path::Path;

use crate::error::{Error, Result};

/// The largest file read unless the caller says otherwise: 1 GiB.
pub const DEFAULT_MAX_BYTES: u64 = 1 << 30;
/// The longest line a text format may have: 64 MiB (a face of a few
/// million corners).
pub const MAX_LINE: usize = 64 << 20;

/// What a file may be.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// The largest file read, in bytes.
    pub max_bytes: u64,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            max_bytes: DEFAULT_MAX_BYTES,
        }
    }
}

/// Opens `path` for reading if it is a regular file within `limits`;
/// returns it and its size.
pub fn open(path: &Path, limits: &Limits) -> Result<(File, u64)> {
    use std::os::unix::fs::FileTypeExt;
    let io = |e| Error::io(path, e);
    let meta = std::fs::metadata(path).map_err(io)?;
    let kind = meta.file_type();
    let what = if kind.is_dir() {
        Some("a directory")
    } else if kind.is_fifo() {
        Some("a named pipe")
    } else if kind.is_char_device() || kind.is_block_device() {
        Some("a device")
    } else if kind.is_socket() {
        Some("a socket")
    } else {
        None
    };
    if let Some(what) = what {
        return Err(Error::Invalid(format!(
            "{}: is {what}, not a file",
            path.display()
        )));
    }
    if meta.len() > limits.max_bytes {
        return Err(Error::Invalid(format!(
            "{}: {} is more than the limit of {} (--max-file-size raises it)",
            path.display(),
            human(meta.len()),
            human(limits.max_bytes)
        )));
    }
    Ok((File::open(path).map_err(io)?, meta.len()))
}

/// A size in bytes, readably.
pub fn human(n: u64) -> String {
    const UNITS: [(&str, u64); 3] = [("GiB", 1 << 30), ("MiB", 1 << 20), ("KiB", 1 << 10)];
    for (unit, size) in UNITS {
        if n >= size {
            return format!("{:.1} {unit}", n as f64 / size as f64);
        }
    }
    format!("{n} bytes")
}

/// A text file's lines, one at a time, each without its line ending; a
/// UTF-8 byte order mark at the start is skipped. A line is handed out
/// straight from the reader's 64 KiB buffer (found with SIMD `memchr`);
/// only a line that straddles two reads is copied.
pub struct Lines<R> {
    reader: BufReader<R>,
    /// Bytes of the reader's buffer handed out as the last line, to
    /// consume before the next.
    used: usize,
    /// A line that straddled two reads.
    buf: Vec<u8>,
    /// The number of the last line (from 1).
    pub number: usize,
}

impl<R: Read> Lines<R> {
    pub fn new(reader: R) -> Lines<R> {
        Lines {
            reader: BufReader::with_capacity(64 << 10, reader),
            used: 0,
            buf: Vec::new(),
            number: 0,
        }
    }

    /// The next line and its number; `Ok(None)` at the end. An error is an
    /// I/O error or a line longer than [`MAX_LINE`]: the line's number and
    /// a message, for the caller to place.
    #[allow(clippy::type_complexity)]
    pub fn next_line(&mut self) -> std::result::Result<Option<(usize, &[u8])>, (usize, String)> {
        self.reader.consume(std::mem::take(&mut self.used));
        let number = self.number + 1;
        let io = |e: std::io::Error| (number, e.to_string());
        let avail = self.reader.fill_buf().map_err(io)?;
        if avail.is_empty() {
            return Ok(None);
        }
        self.number = number;
        let whole = match memchr::memchr(b'\n', avail) {
            Some(k) => {
                // The common case: the line is in the buffer.
                self.used = k + 1;
                None
            }
            None => {
                // Straddling: gather it.
                self.buf.clear();
                loop {
                    let avail = self.reader.fill_buf().map_err(io)?;
                    if avail.is_empty() {
                        break;
                    }
                    let (take, end) = match memchr::memchr(b'\n', avail) {
                        Some(k) => (k + 1, true),
                        None => (avail.len(), false),
                    };
                    self.buf.extend_from_slice(&avail[..take]);
                    self.reader.consume(take);
                    if self.buf.len() > MAX_LINE {
                        return Err((
                            number,
                            format!("the line is longer than {}", human(MAX_LINE as u64)),
                        ));
                    }
                    if end {
                        break;
                    }
                }
                Some(())
            }
        };
        let mut line = match whole {
            None => &self.reader.buffer()[..self.used],
            Some(()) => self.buf.as_slice(),
        };
        if number == 1 {
            line = line.strip_prefix(b"\xef\xbb\xbf").unwrap_or(line);
        }
        while let [rest @ .., b'\n' | b'\r'] = line {
            line = rest;
        }
        Ok(Some((number, line)))
    }
}

/// The words of a line up to a `#` comment, with the byte offset where
/// each starts (for [`column`], when an error needs it). One pass over the
/// bytes; words are separated by spaces and control characters (tabs, a
/// stray carriage return).
pub fn words(line: &[u8]) -> impl Iterator<Item = (&[u8], usize)> {
    let mut i = 0;
    let mut done = false;
    std::iter::from_fn(move || {
        if done {
            return None;
        }
        // Blanks are every control character and the space: one compare.
        while i < line.len() && line[i] <= b' ' {
            i += 1;
        }
        if i == line.len() || line[i] == b'#' {
            done = true;
            return None;
        }
        let start = i;
        while i < line.len() && line[i] > b' ' && line[i] != b'#' {
            i += 1;
        }
        Some((&line[start..i], start))
    })
}

/// The column (from 1, in characters) of byte `offset` of `line`.
pub fn column(line: &[u8], offset: usize) -> usize {
    let before = &line[..offset.min(line.len())];
    if before.is_ascii() {
        offset + 1
    } else {
        String::from_utf8_lossy(before).chars().count() + 1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_across_two_reads_is_whole() {
        // A reader that hands out 3 bytes at a time.
        struct Trickle<'a>(&'a [u8]);
        impl Read for Trickle<'_> {
            fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
                let n = self.0.len().min(3).min(buf.len());
                buf[..n].copy_from_slice(&self.0[..n]);
                self.0 = &self.0[n..];
                Ok(n)
            }
        }
        let mut l = Lines::new(Trickle(b"v 1 2 3\nf 1 2 3\n"));
        assert_eq!(l.next_line().unwrap(), Some((1, &b"v 1 2 3"[..])));
        assert_eq!(l.next_line().unwrap(), Some((2, &b"f 1 2 3"[..])));
        assert_eq!(l.next_line().unwrap(), None);
    }

    #[test]
    fn lines_drop_endings_and_a_bom() {
        let mut l = Lines::new(&b"\xef\xbb\xbfv 1\r\n\nf 1 2 3"[..]);
        assert_eq!(l.next_line().unwrap(), Some((1, &b"v 1"[..])));
        assert_eq!(l.next_line().unwrap(), Some((2, &b""[..])));
        assert_eq!(l.next_line().unwrap(), Some((3, &b"f 1 2 3"[..])));
        assert_eq!(l.next_line().unwrap(), None);
    }

    #[test]
    fn words_stop_at_a_comment_and_know_their_columns() {
        let w: Vec<_> = words(b"f\t1 2  3# tri").collect();
        assert_eq!(
            w,
            vec![
                (&b"f"[..], 0),
                (&b"1"[..], 2),
                (&b"2"[..], 4),
                (&b"3"[..], 7)
            ]
        );
        assert_eq!(column("é x".as_bytes(), 3), 3);
    }

    #[test]
    fn what_is_not_a_regular_file_is_refused_at_once() {
        let limits = Limits::default();
        for (path, what) in [("/dev/zero", "a device"), ("/tmp", "a directory")] {
            let e = open(Path::new(path), &limits).unwrap_err().to_string();
            assert_eq!(e, format!("{path}: is {what}, not a file"));
        }
        let e = open(Path::new("Cargo.toml"), &Limits { max_bytes: 10 })
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("is more than the limit of 10 bytes (--max-file-size raises it)"),
            "{e}"
        );
    }
}
