//! Opening model and scene files safely, and reading them line by line.
//! Every path rastty reads goes through [`open`]: the model, the scene
//! file, every file a model refers to (MTL libraries, textures, glTF
//! buffers and images, found by [`reference()`]) and the first bytes a
//! format is told by.
//!
//! A path is looked at before it is opened: a directory, a FIFO (which
//! would block forever), a device (`/dev/zero`, which never ends; opening
//! some devices does something), a socket are refused at once, and so is a
//! regular file larger than the limit ([`DEFAULT_MAX_BYTES`], 1 GiB,
//! raised by `--max-file-size`), so a sparse 4 GB file is an error in a
//! millisecond. It is then opened without waiting (`O_NONBLOCK`, cleared
//! once the file is known to be regular) and looked at again through the
//! open file: a FIFO or device swapped in between is refused there, never
//! waited on. The size the open file has then is the most that is ever
//! read: a file that grows while it is read is read to that size, with a
//! note; one that shrinks is an error. Text is read line by line
//! ([`super::lines`]).
//!
//! One load's files are opened through [`Files`], which knows each by its
//! identity (device and inode): a file named twice is read once, and the
//! scene can say which files it read ([`Source`]), so that nothing rastty
//! writes replaces one of them.

use std::cell::RefCell;
use std::fs::File;
use std::io::{self, Read};

use std::path::{Path, PathBuf};

use crate::error::{Error, Result};

/// The largest file read unless the caller says otherwise: 1 GiB.
pub const DEFAULT_MAX_BYTES: u64 = 1 << 30;

/// A file's identity: two names of one file (a link, `./a` and `a`) have
/// the same. On unix its device and inode; elsewhere its full path.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct FileId(Id);

#[cfg(unix)]
type Id = (u64, u64);
#[cfg(not(unix))]
type Id = PathBuf;

impl FileId {
    /// The identity of the file `meta` describes, found at `path`.
    pub fn of(meta: &std::fs::Metadata, path: &Path) -> FileId {
        #[cfg(unix)]
        {
            use std::os::unix::fs::MetadataExt;
            let _ = path;
            FileId((meta.dev(), meta.ino()))
        }
        #[cfg(not(unix))]
        {
            let _ = meta;
            FileId(std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf()))
        }
    }

    /// The identity of the file at `path` (following links), if there is one.
    pub fn at(path: &Path) -> Option<FileId> {
        std::fs::metadata(path).ok().map(|m| FileId::of(&m, path))
    }
}

/// A file a scene was read from: the model or scene file, or a file it
/// names (an MTL library, a texture, a glTF buffer or image).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Source {
    /// Where it was read.
    pub path: PathBuf,
    /// Which file it is.
    pub id: FileId,
}

/// What a path names, when it is not a regular file: `None` for one.
fn not_a_file(kind: std::fs::FileType) -> Option<&'static str> {
    #[cfg(unix)]
    use std::os::unix::fs::FileTypeExt;
    if kind.is_dir() {
        return Some("a directory");
    }
    #[cfg(unix)]
    {
        if kind.is_fifo() {
            return Some("a named pipe");
        } else if kind.is_char_device() || kind.is_block_device() {
            return Some("a device");
        } else if kind.is_socket() {
            return Some("a socket");
        }
    }
    (!kind.is_file()).then_some("not a regular file")
}

/// What `path` names on Windows that is not a file, in words: a reserved
/// device name (`CON`, `PRN`, `AUX`, `NUL`, `COM0` to `COM9`, `LPT0` to
/// `LPT9`, `CONIN$`, `CONOUT$`, in any case, whatever extension and
/// trailing dots or spaces follow: `nul.obj` is the null device there), or
/// a path into the device namespace (`\\.\…`, `\\?\GLOBALROOT\…`).
/// `None` for a file's name. A pure function of the name, tested on every
/// platform; applied where Windows opens such names as devices.
pub fn windows_device(path: &Path) -> Option<String> {
    let text = path.to_string_lossy();
    let lower = text.to_ascii_lowercase().replace('/', "\\");
    if lower.starts_with("\\\\.\\") || lower.starts_with("\\\\?\\globalroot") {
        return Some("a path into the device namespace".into());
    }
    let last = lower.rsplit('\\').next().unwrap_or("");
    let stem = last
        .split('.')
        .next()
        .unwrap_or("")
        .trim_end_matches([' ', '.']);
    let numbered = |prefix: &str| {
        stem.strip_prefix(prefix).is_some_and(|n| {
            let mut c = n.chars();
            matches!(
                (c.next(), c.next()),
                (Some('0'..='9' | '¹' | '²' | '³'), None)
            )
        })
    };
    let device = matches!(stem, "con" | "prn" | "aux" | "nul" | "conin$" | "conout$")
        || numbered("com")
        || numbered("lpt");
    device.then(|| format!("{}, a device name on Windows", stem.to_ascii_uppercase()))
}

/// Opens `path` for reading without waiting: a FIFO or a device opens at
/// once (and is then refused), never blocks the open.
fn open_at_once(path: &Path) -> io::Result<File> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        std::fs::OpenOptions::new()
            .read(true)
            .custom_flags(libc::O_NONBLOCK | libc::O_NOCTTY)
            .open(path)
    }
    #[cfg(not(unix))]
    {
        File::open(path)
    }
}

/// Reads of `file` wait again, as a regular file's always did.
fn wait_again(file: &File) -> io::Result<()> {
    #[cfg(unix)]
    {
        use std::os::fd::AsRawFd;
        let fd = file.as_raw_fd();
        // SAFETY: fcntl on a descriptor `file` owns, with the flags it has.
        let flags = unsafe { libc::fcntl(fd, libc::F_GETFL) };
        if flags < 0 || unsafe { libc::fcntl(fd, libc::F_SETFL, flags & !libc::O_NONBLOCK) } < 0 {
            return Err(io::Error::last_os_error());
        }
    }
    #[cfg(not(unix))]
    let _ = file;
    Ok(())
}

/// A regular file opened by [`open`], read to at most the size it had
/// when opened (see the module's docs).
#[derive(Debug)]
pub struct Opened<'f> {
    file: File,
    path: PathBuf,
    id: FileId,
    /// Its size when opened.
    size: u64,
    /// Bytes not yet read.
    left: u64,
    /// Whether the end has been looked past.
    probed: bool,
    /// Where a note that the file grew goes.
    files: Option<&'f Files>,
}

impl Opened<'_> {
    /// Its size when opened: the most that is read.
    pub fn size(&self) -> u64 {
        self.size
    }

    /// Which file it is.
    pub fn id(&self) -> &FileId {
        &self.id
    }

    /// Past the size it had: one byte more means it grew (a note) or that
    /// its size was never its length (a `/proc` file: an error).
    fn probe(&mut self) -> io::Result<()> {
        let mut one = [0u8; 1];
        let more = loop {
            match self.file.read(&mut one) {
                Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
                r => break r?,
            }
        };
        if more == 0 {
            return Ok(());
        }
        let now = self.file.metadata()?.len();
        if now <= self.size {
            return Err(io::Error::new(
                io::ErrorKind::InvalidData,
                format!(
                    "has more than the {} bytes its size says (a /proc or /sys file?)",
                    self.size
                ),
            ));
        }
        if let Some(files) = self.files {
            files.notes.borrow_mut().push(format!(
                "{}: grew while it was read: its first {} bytes, its size when opened, were read",
                self.path.display(),
                self.size
            ));
        }
        Ok(())
    }
}

impl Read for Opened<'_> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        if self.left == 0 || buf.is_empty() {
            if self.left == 0 && !self.probed {
                self.probed = true;
                self.probe()?;
            }
            return Ok(0);
        }
        let want = buf
            .len()
            .min(usize::try_from(self.left).unwrap_or(usize::MAX));
        let n = self.file.read(&mut buf[..want])?;
        if n == 0 {
            return Err(io::Error::new(
                io::ErrorKind::UnexpectedEof,
                format!(
                    "shrank while it was read: it ends after {} of the {} bytes it had",
                    self.size - self.left,
                    self.size
                ),
            ));
        }
        self.left -= n as u64;
        Ok(n)
    }
}

/// Opens `path` for reading if it is a regular file of at most
/// `max_bytes` (see the module's docs): the one way rastty opens a file.
pub fn open(path: &Path, max_bytes: u64) -> Result<Opened<'static>> {
    let io = |e| Error::io(path, e);
    let refuse = |what: &str| Error::Invalid(format!("{}: is {what}, not a file", path.display()));
    if cfg!(windows)
        && let Some(what) = windows_device(path)
    {
        return Err(refuse(&what));
    }
    // Looked at first: a device is never opened.
    let meta = std::fs::metadata(path).map_err(io)?;
    if let Some(what) = not_a_file(meta.file_type()) {
        return Err(refuse(what));
    }
    if meta.len() > max_bytes {
        return Err(too_large(path, &human(meta.len()), max_bytes));
    }
    let file = open_at_once(path).map_err(io)?;
    // What was opened is what is read: a regular file (not swapped for a
    // pipe or a device in between), of the size it has now.
    let meta = file.metadata().map_err(io)?;
    if let Some(what) = not_a_file(meta.file_type()) {
        return Err(Error::Invalid(format!(
            "{}: changed while being opened: it is now {what}",
            path.display()
        )));
    }
    if meta.len() > max_bytes {
        return Err(too_large(path, &human(meta.len()), max_bytes));
    }
    wait_again(&file).map_err(io)?;
    Ok(Opened {
        id: FileId::of(&meta, path),
        file,
        path: path.to_path_buf(),
        size: meta.len(),
        left: meta.len(),
        probed: false,
        files: None,
    })
}

/// Reads all of `opened`, which names `path` in errors.
fn read_all(mut opened: Opened<'_>, path: &Path) -> Result<Vec<u8>> {
    let mut bytes = Vec::with_capacity(usize::try_from(opened.size).unwrap_or(0));
    opened
        .read_to_end(&mut bytes)
        .map_err(|e| Error::io(path, e))?;
    Ok(bytes)
}

/// Up to the first `n` bytes of the file at `path`, opened as [`open`]
/// opens any file (`None` when it cannot be: the loader will say why).
pub fn head(path: &Path, n: u64) -> Option<Vec<u8>> {
    let opened = open(path, u64::MAX).ok()?;
    let mut head = Vec::new();
    opened.take(n).read_to_end(&mut head).ok()?;
    Some(head)
}

/// The files one load opens, each through [`open`] with the load's size
/// limit: which files they are ([`Files::sources`]) and what reading them
/// had to say (a file that grew).
#[derive(Debug, Default)]
pub struct Files {
    max_bytes: u64,
    sources: RefCell<Vec<Source>>,
    notes: RefCell<Vec<String>>,
}

impl Files {
    /// Files of at most `max_bytes` each.
    pub fn new(max_bytes: u64) -> Files {
        Files {
            max_bytes,
            ..Files::default()
        }
    }

    /// Opens `path` as [`open`] does, and counts it among the load's files.
    pub fn open(&self, path: &Path) -> Result<Opened<'_>> {
        let mut opened = open(path, self.max_bytes)?;
        opened.files = Some(self);
        let mut sources = self.sources.borrow_mut();
        if !sources.iter().any(|s| s.id == opened.id) {
            sources.push(Source {
                path: path.to_path_buf(),
                id: opened.id.clone(),
            });
        }
        Ok(opened)
    }

    /// Reads all of the file at `path`, opened as [`Files::open`] opens it.
    pub fn read(&self, path: &Path) -> Result<Vec<u8>> {
        read_all(self.open(path)?, path)
    }

    /// The files opened so far, each once, in the order first opened.
    pub fn sources(&self) -> Vec<Source> {
        self.sources.borrow().clone()
    }

    /// What reading had to say, taken.
    pub fn take_notes(&self) -> Vec<String> {
        std::mem::take(&mut self.notes.borrow_mut())
    }
}

fn too_large(path: &Path, size: &str, max_bytes: u64) -> Error {
    Error::Invalid(format!(
        "{}: {size} is more than the limit of {} (--max-file-size raises it)",
        path.display(),
        human(max_bytes)
    ))
}

/// A file a model refers to (an MTL library, a texture, a glTF buffer),
/// found beside the model, and what to tell the user about where it was
/// looked for.
#[derive(Debug)]
pub struct Reference {
    /// Where to read it.
    pub path: PathBuf,
    /// Said in a `note:`: the name was absolute (or `file://`) and was
    /// looked for beside the model instead, or it leads out of the
    /// model's folder.
    pub note: Option<String>,
    /// The same, without the owner's name, for an error about the file
    /// (which names its owner itself).
    pub why: Option<String>,
}

/// `message` about a file a model names, after where it was looked for
/// and why ([`Reference::why`]), when that is not where the name points.
#[cfg_attr(not(feature = "textures"), allow(dead_code))]
pub fn explain(why: Option<&str>, message: impl std::fmt::Display) -> String {
    match why {
        Some(why) => format!("{why}; {message}"),
        None => message.to_string(),
    }
}

/// Where the file that `owner` (a model or material file in `dir`, named
/// so in messages) names as `name` is read: relative names in `dir` (`..`
/// included: asset packs share folders, with a note when the path leaves
/// the folder); an absolute name (`/x/y.png`, `C:\\x\\y.png`) is not read
/// where it points, but its last part in `dir`, as common loaders do,
/// with a note. A backslash separates folders, as Windows tools write
/// them (`maps\\t.png`), unless a file of the name as written is there;
/// and a name not found is looked for in another case, with a note.
pub fn reference(dir: &Path, owner: &str, name: &str) -> Reference {
    let shown = crate::text::name(name, 80);
    let slashed;
    let name = if name.contains('\\') && !dir.join(name).exists() {
        slashed = name.replace('\\', "/");
        &slashed
    } else {
        name
    };
    let bytes = name.as_bytes();
    let windows_absolute = bytes.len() >= 3
        && bytes[0].is_ascii_alphabetic()
        && bytes[1] == b':'
        && matches!(bytes[2], b'/' | b'\\');
    if name.starts_with('/') || name.starts_with('\\') || windows_absolute {
        let last = name.rsplit(['/', '\\']).next().unwrap_or("");
        let why = format!(
            "{shown} is an absolute path: {} beside it is read instead",
            crate::text::name(last, 80)
        );
        return found(dir, owner, (last, &shown), Some(why));
    }
    // Lexically: whether the path climbs above the folder.
    let mut depth: i64 = 0;
    let mut outside = false;
    for part in Path::new(name).components() {
        match part {
            std::path::Component::ParentDir => depth -= 1,
            std::path::Component::Normal(_) => depth += 1,
            _ => {}
        }
        outside |= depth < 0;
    }
    let why = outside.then(|| format!("{shown} is read from outside its folder"));
    found(dir, owner, (name, &shown), why)
}

/// [`reference`]'s answer for `rel` below `dir` (`shown` as the name was
/// written), `why` it is read there: where no file has that name but one
/// has it in another case (a model made where case does not matter),
/// that one, with a note.
fn found(dir: &Path, owner: &str, (rel, shown): (&str, &str), why: Option<String>) -> Reference {
    let mut path = dir.join(rel);
    let mut why = why;
    if !path.exists()
        && let Some(other) = in_any_case(dir, Path::new(rel))
    {
        let as_found = other.strip_prefix(dir).unwrap_or(&other);
        let as_found = crate::text::name(&as_found.to_string_lossy(), 80);
        why = Some(match why {
            Some(why) => format!("{why}, as {as_found}, its name in another case"),
            None => format!("{shown} is read as {as_found}, its name in another case"),
        });
        path = other;
    }
    Reference {
        path,
        note: why.as_ref().map(|why| format!("{owner}: {why}")),
        why,
    }
}

/// `rel` below `dir`, each of its parts that is not there matched to an
/// entry of its folder whose name differs only in case (the least such
/// name); `None` where a part matches none. At most [`CASE_ENTRIES`]
/// entries are read, over all the folders.
fn in_any_case(dir: &Path, rel: &Path) -> Option<PathBuf> {
    let mut left = CASE_ENTRIES;
    let mut at = dir.to_path_buf();
    for part in rel.components() {
        let std::path::Component::Normal(part) = part else {
            at.push(part);
            continue;
        };
        let exact = at.join(part);
        if exact.exists() {
            at = exact;
            continue;
        }
        let want = part.to_str()?.to_lowercase();
        let name = std::fs::read_dir(&at)
            .ok()?
            .take_while(|_| left.checked_sub(1).map(|l| left = l).is_some())
            .filter_map(|e| e.ok()?.file_name().into_string().ok())
            .filter(|n| n.to_lowercase() == want)
            .min()?;
        at.push(name);
    }
    Some(at)
}

/// How many folder entries [`in_any_case`] reads at most.
const CASE_ENTRIES: usize = 4096;

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn windows_device_names_are_known_whatever_their_case_and_extension() {
        let device = |p: &str| windows_device(Path::new(p));
        for (name, what) in [
            ("CON", "CON, a device name on Windows"),
            ("nul.obj", "NUL, a device name on Windows"),
            ("models/Com3.glb", "COM3, a device name on Windows"),
            ("C:\\x\\lpt1 .stl", "LPT1, a device name on Windows"),
            ("aux.tar.gz", "AUX, a device name on Windows"),
            ("conout$", "CONOUT$, a device name on Windows"),
            ("\\\\.\\PhysicalDrive0", "a path into the device namespace"),
            ("//./pipe/x", "a path into the device namespace"),
        ] {
            assert_eq!(device(name).as_deref(), Some(what), "{name}");
        }
        for name in [
            "console.obj",
            "com10.obj",
            "nullable.ply",
            "lpt.stl",
            "x/con/y.obj",
            "\\\\?\\C:\\m.obj",
        ] {
            assert_eq!(device(name), None, "{name}");
        }
    }

    #[test]
    fn a_missing_file_and_a_directory_give_their_message() {
        let dir = std::env::temp_dir();
        let e = open(&dir, DEFAULT_MAX_BYTES).unwrap_err().to_string();
        assert_eq!(e, format!("{}: is a directory, not a file", dir.display()));
        let missing = dir.join("rastty-no-such-model.obj");
        let e = open(&missing, DEFAULT_MAX_BYTES).unwrap_err();
        assert!(
            matches!(&e, Error::Io { source, .. } if source.kind() == io::ErrorKind::NotFound),
            "{e}"
        );
        assert!(
            e.to_string()
                .starts_with(&format!("{}: ", missing.display()))
        );
    }

    #[cfg(unix)]
    #[test]
    fn what_is_not_a_regular_file_is_refused_at_once() {
        for (path, what) in [("/dev/zero", "a device"), ("/tmp", "a directory")] {
            let e = open(Path::new(path), DEFAULT_MAX_BYTES)
                .unwrap_err()
                .to_string();
            assert_eq!(e, format!("{path}: is {what}, not a file"));
        }
        let e = open(Path::new("Cargo.toml"), 10).unwrap_err().to_string();
        assert!(
            e.contains("is more than the limit of 10 bytes (--max-file-size raises it)"),
            "{e}"
        );
    }
}
