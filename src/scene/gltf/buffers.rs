//! A glTF document's buffers and the bytes its URIs name: the binary
//! chunk, `data:` URIs decoded, files named relative to the model opened
//! and read as the model itself was (`file::reference`, `file::read`,
//! under the same byte budget); nothing fetched from the network. Each
//! buffer at least as long as it says.

use super::*;
use crate::scene::file::{FileId, Files};
use ::gltf::buffer::Data;

/// A buffer's bytes, shared by every buffer that names the same file.
pub(super) type Buffer = Arc<[u8]>;

/// The document's buffers, read as the model was read (data URIs decoded,
/// files found beside the model with [`file::reference`], each file read
/// once however many buffers name it), each at least as long as it says;
/// every buffer view is checked to lie inside its buffer. The buffers
/// `unread` names are left empty (see `meshopt`).
pub(super) fn buffers(
    document: &::gltf::Document,
    mut blob: Option<Vec<u8>>,
    base: Option<&Path>,
    owner: &str,
    files: &Files,
    notes: &mut Vec<String>,
    unread: &[usize],
) -> std::result::Result<Vec<Buffer>, String> {
    let mut out: Vec<Buffer> = Vec::new();
    let mut read: FxHashMap<FileId, Buffer> = FxHashMap::default();
    for b in document.buffers() {
        let what = format!("buffer {}", b.index());
        // A buffer not to be read (see `meshopt`): empty here.
        if unread.contains(&b.index()) {
            out.push(Arc::from(Vec::new()));
            continue;
        }
        let data: Buffer = match b.source() {
            ::gltf::buffer::Source::Bin => padded(
                blob.take()
                    .ok_or_else(|| format!("{what}: the file has no binary chunk"))?,
            ),
            ::gltf::buffer::Source::Uri(uri) => {
                match locate(uri, base, owner, files, notes).map_err(|e| format!("{what}: {e}"))? {
                    Located::Bytes(bytes) => padded(bytes),
                    Located::File(opened, r) => match read.get(opened.id()) {
                        Some(data) => Arc::clone(data),
                        None => {
                            let id = opened.id().clone();
                            let data = padded(r.read(opened).map_err(|e| format!("{what}: {e}"))?);
                            read.insert(id, Arc::clone(&data));
                            data
                        }
                    },
                }
            }
        };
        if data.len() < b.length() {
            return Err(format!(
                "{what} has {} bytes, fewer than its byteLength of {}",
                data.len(),
                b.length()
            ));
        }
        out.push(data);
    }
    for v in document.views() {
        let len = v.buffer().length();
        if v.offset()
            .checked_add(v.length())
            .is_none_or(|end| end > len)
        {
            return Err(format!(
                "buffer view {} ({} bytes at offset {}) runs past the {len} bytes of buffer {}",
                v.index(),
                v.length(),
                v.offset(),
                v.buffer().index()
            ));
        }
    }
    Ok(out)
}

/// `data` padded with zeros to a multiple of four bytes, as the gltf
/// crate's readers expect.
pub(super) fn padded(mut data: Vec<u8>) -> Buffer {
    data.resize(data.len().next_multiple_of(4), 0);
    data.into()
}

/// Where the bytes a URI names are: in the URI (a `data:` URI, decoded),
/// or in a file, opened and not yet read.
pub(super) enum Located<'f> {
    Bytes(Vec<u8>),
    File(file::Opened<'f>, file::Reference),
}

impl file::Reference {
    /// All of `opened` (this reference's file); an error says where the
    /// file was looked for and why, where that is not where its name
    /// points.
    pub(super) fn read(
        &self,
        mut opened: file::Opened<'_>,
    ) -> std::result::Result<Vec<u8>, String> {
        use std::io::Read;
        let mut bytes = Vec::with_capacity(usize::try_from(opened.size()).unwrap_or(0));
        opened
            .read_to_end(&mut bytes)
            .map_err(|e| file::explain(self.why.as_deref(), Error::io(&self.path, e)))?;
        Ok(bytes)
    }
}

/// Where the bytes a buffer's or an image's URI names are: a `data:` URI
/// decoded, or the file it names beside the model (percent-encoding
/// decoded, `file:` taken as a path), opened as the model itself was.
/// Nothing is fetched from the network.
pub(super) fn locate<'f>(
    uri: &str,
    base: Option<&Path>,
    owner: &str,
    files: &'f Files,
    notes: &mut Vec<String>,
) -> std::result::Result<Located<'f>, String> {
    if uri.starts_with("data:") {
        return Data::from_source(::gltf::buffer::Source::Uri(uri), None)
            .map(|d| Located::Bytes(d.0))
            .map_err(|e| describe(&e));
    }
    let shown = crate::text::name(uri, 80);
    let path = if let Some(rest) = uri
        .strip_prefix("file://")
        .or_else(|| uri.strip_prefix("file:"))
    {
        rest
    } else if let Some(scheme) = scheme(uri) {
        return Err(
            if matches!(scheme.to_ascii_lowercase().as_str(), "http" | "https") {
                format!(
                    "{shown} is on the network: rastty fetches nothing (download it beside the model)"
                )
            } else {
                format!(
                    "{shown}: rastty reads data: URIs and files, not {} URIs",
                    crate::text::name(scheme, 20)
                )
            },
        );
    } else {
        uri
    };
    let path = urlencoding::decode(path)
        .map_err(|_| format!("{shown}: its percent-encoding is not UTF-8"))?;
    let Some(base) = base else {
        return Err(format!(
            "{shown} names a file, and the model was not read from one"
        ));
    };
    let r = file::reference(base, owner, &path);
    let opened = files
        .open(&r.path)
        .map_err(|e| file::explain(r.why.as_deref(), e))?;
    notes.extend(r.note.clone());
    Ok(Located::File(opened, r))
}

/// A URI's scheme (`http` of `http://…`), if it has one; a drive letter
/// (`C:\x`) is not one.
pub(super) fn scheme(uri: &str) -> Option<&str> {
    let (scheme, _) = uri.split_once(':')?;
    let mut chars = scheme.chars();
    let ok = chars.next().is_some_and(|c| c.is_ascii_alphabetic())
        && chars.all(|c| c.is_ascii_alphanumeric() || matches!(c, '+' | '-' | '.'));
    (ok && scheme.len() > 1).then_some(scheme)
}

/// Checks that `acc` has a type the reader expects and that every byte
/// it names lies inside its buffer view and buffer.
pub(super) fn check(
    acc: &Accessor,
    buffers: &[Buffer],
    types: &[DataType],
    dims: &[Dimensions],
    what: &str,
) -> std::result::Result<(), String> {
    let at = || format!("{what} (accessor {})", acc.index());
    if !types.contains(&acc.data_type()) || !dims.contains(&acc.dimensions()) {
        return Err(format!(
            "{} is {:?} {:?}, not a type rastty reads there",
            at(),
            acc.data_type(),
            acc.dimensions()
        ));
    }
    if acc.sparse().is_some() {
        return Err(format!(
            "{} is sparse, which rastty does not read there",
            at()
        ));
    }
    let Some(view) = acc.view() else {
        return Err(format!("{} has no buffer view", at()));
    };
    check_range(acc, &view, buffers, &at).map(|_| ())
}

/// The bytes of `acc`'s elements in `view` (from its first element's
/// first byte to its last's last), and the stride between elements,
/// once every byte it names is found inside its buffer view and buffer.
pub(super) fn check_range<'b>(
    acc: &Accessor,
    view: &::gltf::buffer::View,
    buffers: &'b [Buffer],
    at: &dyn Fn() -> String,
) -> std::result::Result<(&'b [u8], usize), String> {
    let buffer = buffers
        .get(view.buffer().index())
        .ok_or_else(|| format!("{}: its buffer is missing", at()))?;
    let elem = acc.size();
    if view.stride().is_some_and(|s| s < elem) {
        return Err(format!(
            "{}: buffer view {} has a byteStride of {}, less than its {elem}-byte elements",
            at(),
            view.index(),
            view.stride().unwrap_or(0)
        ));
    }
    let stride = view.stride().unwrap_or(elem);
    let count = acc.count();
    let need = match count {
        // The spec's minimum; the gltf crate's iterators take count − 1.
        0 => {
            return Err(format!(
                "{} has a count of 0 (glTF requires at least 1)",
                at()
            ));
        }
        n => (n - 1)
            .checked_mul(stride)
            .and_then(|b| b.checked_add(acc.offset()))
            .and_then(|b| b.checked_add(elem))
            .ok_or_else(|| format!("{} is too large", at()))?,
    };
    let view_end = view.offset().checked_add(view.length());
    if need > view.length() || view_end.is_none_or(|end| end > buffer.len()) {
        return Err(format!(
            "{} is out of range: it needs {need} bytes of buffer view {} ({} bytes at offset {} of a {}-byte buffer)",
            at(),
            view.index(),
            view.length(),
            view.offset(),
            buffer.len()
        ));
    }
    let start = view.offset() + acc.offset();
    Ok((&buffer[start..view.offset() + need], stride))
}
