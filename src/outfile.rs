//! The files rastty writes (a picture, a recording, a plot): nothing a
//! user has is lost, whatever happens to the run.
//!
//! * **A regular file, or a new name**, is written to a new temporary file
//!   beside it (`.NAME.rastty-PID-N.tmp`, created exclusively) and renamed
//!   over it by [`OutFile::commit`], the last step of a run that has
//!   succeeded; a run that fails (or an `OutFile` dropped uncommitted)
//!   removes only its temporary file. A symbolic link is followed: the
//!   file it points to is replaced and the link kept. The replaced file's
//!   permissions are kept.
//! * **Anything else** (a device such as `/dev/null`, a FIFO, a terminal;
//!   on Windows `NUL`, `CON` and the device namespace) is written through
//!   as a stream, never renamed over or removed; so is a name for one of
//!   the process's descriptors (`/dev/stdout`, `/dev/stderr`, `/dev/fd/N`,
//!   `/proc/self/fd/N`), which writes to that descriptor as it is
//!   (appending where the shell opened it with `>>`).
//! * **A file the scene was read from** (the model, its MTL library, a
//!   texture, a glTF buffer, a scene's models) is never a target:
//!   [`OutFile::check`] refuses it by identity (device and inode), so a
//!   link, a second name or `./model.obj` is caught as well as the name
//!   itself.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU32, Ordering};

use crate::error::{Error, Result};
use crate::scene::{FileId, Source};

/// A file being written (see the module's docs).
#[derive(Debug)]
pub struct OutFile {
    /// As the user named it, for messages.
    path: PathBuf,
    /// The file it writes over, where there is one (its identity).
    replaces: Option<FileId>,
    how: How,
}

#[derive(Debug)]
enum How {
    /// Written through.
    Stream(BufWriter<File>),
    /// Written to `temp`, renamed over `target` when committed.
    Staged {
        file: BufWriter<File>,
        temp: PathBuf,
        target: PathBuf,
        /// The replaced file's permissions, given to the new one.
        permissions: Option<std::fs::Permissions>,
    },
    /// Committed, or removed.
    Done,
}

/// The most symbolic links followed from a target to the file it names.
const MAX_LINKS: usize = 40;

impl OutFile {
    /// Starts writing `path` as the module's docs say: a temporary file
    /// beside a regular file or a new name, or the stream a device, a FIFO
    /// or a descriptor's name opens. Nothing at `path` changes until
    /// [`OutFile::commit`].
    pub fn create(path: &Path) -> Result<OutFile> {
        let io = |e| Error::io(path, e);
        if cfg!(windows) && crate::scene::file::windows_device(path).is_some() {
            // `NUL`, `CON`: Windows' devices, written through.
            let file = std::fs::OpenOptions::new()
                .write(true)
                .open(path)
                .map_err(io)?;
            return Ok(OutFile {
                path: path.to_path_buf(),
                replaces: None,
                how: How::Stream(BufWriter::new(file)),
            });
        }
        if let Some(file) = descriptor(path).map_err(io)? {
            let replaces = file.metadata().ok().map(|m| FileId::of(&m, path));
            return Ok(OutFile {
                path: path.to_path_buf(),
                replaces,
                how: How::Stream(BufWriter::new(file)),
            });
        }
        let target = resolve(path).map_err(io)?;
        match std::fs::metadata(&target) {
            Ok(meta) if meta.is_dir() => Err(Error::Invalid(format!(
                "{}: is a directory, not a file to write",
                path.display()
            ))),
            Ok(meta) if !meta.is_file() => {
                // A device, a FIFO: written through, as it is.
                let file = std::fs::OpenOptions::new()
                    .write(true)
                    .open(&target)
                    .map_err(io)?;
                Ok(OutFile {
                    path: path.to_path_buf(),
                    replaces: Some(FileId::of(&meta, &target)),
                    how: How::Stream(BufWriter::new(file)),
                })
            }
            Ok(meta) => OutFile::staged(path, target, Some(meta)),
            Err(e) if e.kind() == io::ErrorKind::NotFound => OutFile::staged(path, target, None),
            Err(e) => Err(io(e)),
        }
    }

    /// A temporary file beside `target` (which `path` names), to be renamed
    /// over it; `meta` is the file there now, if any.
    fn staged(path: &Path, target: PathBuf, meta: Option<std::fs::Metadata>) -> Result<OutFile> {
        let dir = match target.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let name = target
            .file_name()
            .map(|n| n.to_string_lossy().chars().take(64).collect::<String>())
            .ok_or_else(|| Error::Invalid(format!("{}: names no file to write", path.display())))?;
        static COUNT: AtomicU32 = AtomicU32::new(0);
        let (file, temp) = loop {
            let n = COUNT.fetch_add(1, Ordering::Relaxed);
            let temp = dir.join(format!(".{name}.rastty-{}-{n}.tmp", std::process::id()));
            match std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(&temp)
            {
                Ok(file) => break (file, temp),
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
                // No such folder: said as any file not found is.
                Err(e) if e.kind() == io::ErrorKind::NotFound => {
                    return Err(Error::io(path, e));
                }
                Err(e) => {
                    return Err(Error::Invalid(format!(
                        "{}: cannot write a new file in {} to put in its place: {e}",
                        path.display(),
                        dir.display()
                    )));
                }
            }
        };
        Ok(OutFile {
            path: path.to_path_buf(),
            replaces: meta.as_ref().map(|m| FileId::of(m, &target)),
            how: How::Staged {
                file: BufWriter::new(file),
                temp,
                target,
                permissions: meta.map(|m| m.permissions()),
            },
        })
    }

    /// The path as it was given.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Whether it is written through as a stream (a device, a FIFO, a
    /// descriptor) rather than replaced when committed.
    pub fn is_stream(&self) -> bool {
        matches!(self.how, How::Stream(_))
    }

    /// Refuses a target that is one of the files `sources` names (a scene's
    /// [`Scene::sources`](crate::scene::Scene::sources)), by identity, or
    /// the same file as `others` (another file this run writes).
    pub fn check(&self, sources: &[Source], others: &[&OutFile]) -> Result<()> {
        if let Some(id) = &self.replaces
            && let Some(source) = sources.iter().find(|s| &s.id == id)
        {
            let what = if source.path == self.path {
                "the scene is read from it".to_string()
            } else {
                format!(
                    "it is {}, which the scene is read from",
                    source.path.display()
                )
            };
            return Err(Error::Invalid(format!(
                "{}: {what}; rastty writes nothing over a file it reads (name another)",
                self.path.display()
            )));
        }
        for other in others {
            if std::ptr::eq(*other, self) {
                continue;
            }
            let same = match (&self.replaces, &other.replaces) {
                (Some(a), Some(b)) => a == b,
                _ => match (&self.how, &other.how) {
                    (How::Staged { target: a, .. }, How::Staged { target: b, .. }) => {
                        same_place(a, b)
                    }
                    _ => false,
                },
            };
            if same && !(self.is_stream() && other.is_stream()) {
                return Err(Error::Invalid(format!(
                    "{} and {} name the same file: give each output its own",
                    self.path.display(),
                    other.path.display()
                )));
            }
        }
        Ok(())
    }

    /// Ends the write: a stream is flushed; a temporary file is flushed to
    /// the disk and renamed over its target, the last step of a run.
    pub fn commit(mut self) -> Result<()> {
        let io = |e| Error::io(&self.path, e);
        match std::mem::replace(&mut self.how, How::Done) {
            How::Stream(mut w) => w.flush().map_err(io),
            How::Staged {
                file,
                temp,
                target,
                permissions,
            } => {
                let done = file
                    .into_inner()
                    .map_err(io::IntoInnerError::into_error)
                    .and_then(|f| {
                        if let Some(p) = permissions {
                            f.set_permissions(p)?;
                        }
                        f.sync_all()
                    })
                    .and_then(|()| std::fs::rename(&temp, &target));
                if done.is_err() {
                    let _ = std::fs::remove_file(&temp);
                }
                done.map_err(io)
            }
            How::Done => Ok(()),
        }
    }

    fn writer(&mut self) -> &mut BufWriter<File> {
        match &mut self.how {
            How::Stream(w) | How::Staged { file: w, .. } => w,
            How::Done => unreachable!("an OutFile is written only before it is committed"),
        }
    }
}

impl Write for OutFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.writer().write(buf)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.writer().flush()
    }
}

impl Drop for OutFile {
    /// Uncommitted: the temporary file is removed, and the target is as it
    /// was.
    fn drop(&mut self) {
        if let How::Staged { temp, .. } = &self.how {
            let _ = std::fs::remove_file(temp);
        }
    }
}

/// Whether `a` and `b`, neither of which need exist, name one place: the
/// same name in the same folder.
fn same_place(a: &Path, b: &Path) -> bool {
    let folder = |p: &Path| {
        let dir = p.parent().filter(|d| !d.as_os_str().is_empty());
        std::fs::canonicalize(dir.unwrap_or(Path::new("."))).ok()
    };
    a.file_name() == b.file_name() && folder(a).is_some() && folder(a) == folder(b)
}

/// The file `path` names once symbolic links are followed, whether or not
/// it exists: a link to a missing file names that file.
fn resolve(path: &Path) -> io::Result<PathBuf> {
    let mut at = path.to_path_buf();
    for _ in 0..MAX_LINKS {
        match std::fs::symlink_metadata(&at) {
            Ok(m) if m.file_type().is_symlink() => {
                let to = std::fs::read_link(&at)?;
                at = match at.parent() {
                    Some(dir) => dir.join(to),
                    None => to,
                };
            }
            Ok(_) => return Ok(at),
            Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(at),
            Err(e) => return Err(e),
        }
    }
    Err(io::Error::other(format!(
        "more than {MAX_LINKS} symbolic links to follow"
    )))
}

/// The descriptor a name such as `/dev/stdout` or `/dev/fd/3` stands for,
/// opened anew on it (`None`: not such a name).
fn descriptor(path: &Path) -> io::Result<Option<File>> {
    #[cfg(unix)]
    {
        let Some(s) = path.to_str() else {
            return Ok(None);
        };
        let fd = match s {
            "/dev/stdout" => 1,
            "/dev/stderr" => 2,
            _ => match s
                .strip_prefix("/dev/fd/")
                .or_else(|| s.strip_prefix("/proc/self/fd/"))
                .map(str::parse::<i32>)
            {
                Some(Ok(fd)) if fd >= 0 => fd,
                _ => return Ok(None),
            },
        };
        // SAFETY: duplicating a descriptor number makes a new descriptor
        // (or fails, for one that is not open); the new one is this File's.
        let new = unsafe { libc::fcntl(fd, libc::F_DUPFD_CLOEXEC, 3) };
        if new < 0 {
            return Err(io::Error::last_os_error());
        }
        use std::os::fd::FromRawFd;
        // SAFETY: `new` is open and owned by nothing else.
        Ok(Some(unsafe { File::from_raw_fd(new) }))
    }
    #[cfg(not(unix))]
    {
        let _ = path;
        Ok(None)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("rastty-outfile-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    fn names(d: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn an_existing_file_is_replaced_only_when_committed() {
        let d = dir("replace");
        let target = d.join("out.txt");
        std::fs::write(&target, "old").unwrap();
        let mut out = OutFile::create(&target).unwrap();
        out.write_all(b"new").unwrap();
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "old");
        assert_eq!(names(&d).len(), 2, "the temporary file beside it");
        out.commit().unwrap();
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "new");
        assert_eq!(names(&d), ["out.txt"]);
    }

    #[test]
    fn an_uncommitted_file_leaves_nothing_behind() {
        let d = dir("drop");
        let target = d.join("out.txt");
        std::fs::write(&target, "old").unwrap();
        let mut out = OutFile::create(&target).unwrap();
        out.write_all(b"new").unwrap();
        drop(out);
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "old");
        assert_eq!(names(&d), ["out.txt"]);
        let fresh = d.join("fresh.txt");
        drop(OutFile::create(&fresh).unwrap());
        assert_eq!(names(&d), ["out.txt"]);
    }

    #[cfg(unix)]
    #[test]
    fn a_link_is_kept_and_the_file_it_names_replaced() {
        let d = dir("link");
        std::fs::write(d.join("real.txt"), "old").unwrap();
        std::os::unix::fs::symlink("real.txt", d.join("link.txt")).unwrap();
        let mut out = OutFile::create(&d.join("link.txt")).unwrap();
        out.write_all(b"new").unwrap();
        out.commit().unwrap();
        assert!(
            std::fs::symlink_metadata(d.join("link.txt"))
                .unwrap()
                .file_type()
                .is_symlink()
        );
        assert_eq!(std::fs::read_to_string(d.join("real.txt")).unwrap(), "new");
    }

    #[cfg(unix)]
    #[test]
    fn a_device_is_written_through_and_never_removed() {
        let mut out = OutFile::create(Path::new("/dev/null")).unwrap();
        assert!(out.is_stream());
        out.write_all(b"x").unwrap();
        drop(out);
        assert!(Path::new("/dev/null").exists());
    }

    #[test]
    fn a_source_of_the_scene_is_refused_by_identity() {
        let d = dir("source");
        let model = d.join("m.obj");
        std::fs::write(&model, "v 0 0 0").unwrap();
        let sources = [Source {
            path: model.clone(),
            id: FileId::at(&model).unwrap(),
        }];
        let out = OutFile::create(&d.join(".").join("m.obj")).unwrap();
        let e = out.check(&sources, &[]).unwrap_err().to_string();
        assert!(
            e.contains("rastty writes nothing over a file it reads"),
            "{e}"
        );
        drop(out);
        assert_eq!(std::fs::read_to_string(&model).unwrap(), "v 0 0 0");
        assert_eq!(names(&d), ["m.obj"]);
    }
}
