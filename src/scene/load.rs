//! Reading a model file: its format from its extension or, where that is
//! missing or lies, its first bytes; the loader for it, under the loading
//! budgets; large text files parsed in chunks.

use super::*;

/// A file's format, as its extension says or, where that is missing or
/// lies, as its first bytes say.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Wavefront OBJ.
    Obj,
    /// STL, binary or ASCII.
    Stl,
    /// glTF, as JSON or GLB.
    Gltf,
    /// PLY.
    Ply,
    /// 3MF.
    ThreeMf,
    /// A scene file.
    Toml,
    /// A built-in shape named without an extension.
    Shape(Shape),
}

impl Format {
    /// The format of `path`, and a note when its first bytes overrule its
    /// extension. An extension is believed unless the file starts with
    /// another format's signature (GLB's `glTF`, PLY's `ply`, a binary
    /// STL whose facet count gives its exact size, glTF's JSON object);
    /// without one, a name like a shape's is the shape (when no such
    /// file exists), and a file is told by its first bytes (OBJ
    /// statements, `solid`, a TOML table or key). A file that is none of
    /// them, or a shape misspelt, is an error saying so.
    pub fn of(path: &Path) -> Result<(Format, Option<String>)> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let named = match ext.as_deref() {
            Some("obj") => Some(Format::Obj),
            Some("stl") => Some(Format::Stl),
            #[cfg(feature = "gltf")]
            Some("gltf" | "glb") => Some(Format::Gltf),
            #[cfg(feature = "ply")]
            Some("ply") => Some(Format::Ply),
            #[cfg(feature = "threemf")]
            Some("3mf") => Some(Format::ThreeMf),
            Some("toml") => Some(Format::Toml),
            _ => None,
        };
        let regular = std::fs::metadata(path).is_ok_and(|m| m.is_file());
        let head = if regular {
            file::head(path, 512).unwrap_or_default()
        } else {
            Vec::new()
        };
        let (signed, guessed) = sniff(&head);
        match (named, ext.as_deref()) {
            (Some(named), _) => match signed {
                Some(actual) if actual != named && readable(actual) => Ok((
                    actual,
                    Some(format!(
                        "{}: read as {} (its first bytes say so), not as its name says",
                        path.display(),
                        actual.name()
                    )),
                )),
                _ => Ok((named, None)),
            },
            (None, Some(other)) if signed.is_none() => Err(Error::Invalid(format!(
                "{}: rastty does not read .{other} files; it reads models ({MODELS}), scenes (.toml) and the shapes cube, sphere and torus",
                path.display()
            ))),
            (None, _) => {
                if !path.exists() {
                    if let Some(shape) = path.to_str().and_then(Shape::from_name) {
                        return Ok((Format::Shape(shape), None));
                    }
                    if let Some(near) = path.to_str().and_then(Shape::nearest) {
                        return Err(Error::Invalid(format!(
                            "{}: no such file or shape; did you mean {}?",
                            path.display(),
                            near.name()
                        )));
                    }
                    // Not there: reading it as a scene says so.
                    return Ok((Format::Toml, None));
                }
                match signed.or(guessed) {
                    Some(f) if readable(f) => Ok((
                        f,
                        ext.map(|_| {
                            format!(
                                "{}: read as {} (its first bytes say so), not as its name says",
                                path.display(),
                                f.name()
                            )
                        }),
                    )),
                    Some(f) => Err(Error::Invalid(format!(
                        "{}: a {} file, which this build of rastty does not read",
                        path.display(),
                        f.name()
                    ))),
                    None if !regular => Ok((Format::Toml, None)),
                    None => Err(Error::Invalid(format!(
                        "{}: not a model or a scene: its first bytes are not OBJ, STL, PLY, glTF or TOML",
                        path.display()
                    ))),
                }
            }
        }
    }

    /// The format's name in messages.
    pub fn name(self) -> &'static str {
        match self {
            Format::Obj => "OBJ",
            Format::Stl => "STL",
            Format::Gltf => "glTF",
            Format::Ply => "PLY",
            Format::ThreeMf => "3MF",
            Format::Toml => "TOML scene",
            Format::Shape(_) => "built-in shape",
        }
    }
}

/// Whether this build reads `f`.
pub(super) fn readable(f: Format) -> bool {
    !matches!(f, Format::Gltf if !cfg!(feature = "gltf"))
        && !matches!(f, Format::Ply if !cfg!(feature = "ply"))
        && !matches!(f, Format::ThreeMf if !cfg!(feature = "threemf"))
}

/// What a file's first bytes say: a signature (a format that cannot be
/// mistaken), and else a guess from its first statement.
pub(super) fn sniff(head: &[u8]) -> (Option<Format>, Option<Format>) {
    if head.starts_with(b"glTF") {
        return (Some(Format::Gltf), None);
    }
    if head.starts_with(b"ply\n") || head.starts_with(b"ply\r\n") {
        return (Some(Format::Ply), None);
    }
    // A zip archive: a 3MF package, if any model is.
    if head.starts_with(b"PK\x03\x04") {
        return (None, Some(Format::ThreeMf));
    }
    let text = head.trim_ascii_start();
    if text.starts_with(b"{") {
        // glTF's JSON must hold an `asset` object, which exporters write
        // first; a brace without it in the first bytes is only a guess (an
        // STL header may start with one).
        let asset = head.windows(7).any(|w| w == b"\"asset\"");
        return if asset {
            (Some(Format::Gltf), None)
        } else {
            (None, Some(Format::Gltf))
        };
    }
    if text.starts_with(b"solid") {
        return (None, Some(Format::Stl));
    }
    // The first line that is not blank or a comment.
    let first = head
        .split(|&b| b == b'\n')
        .map(<[u8]>::trim_ascii)
        .find(|l| !l.is_empty() && !l.starts_with(b"#"));
    let guess = first.and_then(|l| {
        let word = l.split(|b| b.is_ascii_whitespace()).next().unwrap_or(l);
        match word {
            b"v" | b"vn" | b"vt" | b"f" | b"o" | b"g" | b"s" | b"mtllib" | b"usemtl" | b"l"
            | b"p" => Some(Format::Obj),
            _ if l.starts_with(b"[") || l.contains(&b'=') => Some(Format::Toml),
            _ => None,
        }
    });
    (None, guess)
}

/// What a path names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A model file or a built-in shape.
    Model,
    /// A scene file.
    Scene,
}

/// About how much scene text is deserialized at once.
pub(super) const CHUNK: usize = 64 << 10;

/// The scene text cut into runs of whole top-level tables of about `size`
/// bytes: `(start, end)` offsets. A table starts at a `[` that begins a
/// line outside any string or array; strings (basic, literal, multi-line),
/// comments, arrays and inline tables are stepped over, so a `[` inside
/// one never starts a table.
pub(super) fn chunks(src: &str, size: usize) -> Vec<(usize, usize)> {
    let b = src.as_bytes();
    let mut starts = vec![0usize];
    let (mut i, mut depth, mut line_start) = (0usize, 0usize, true);
    let find = |from: usize, pat: &[u8]| {
        b[from..]
            .windows(pat.len())
            .position(|w| w == pat)
            .map_or(b.len(), |k| from + k + pat.len())
    };
    while i < b.len() {
        let c = b[i];
        match c {
            b'\n' => {
                line_start = true;
                i += 1;
                continue;
            }
            b' ' | b'\t' | b'\r' => {
                i += 1;
                continue;
            }
            b'#' => {
                i = b[i..]
                    .iter()
                    .position(|&c| c == b'\n')
                    .map_or(b.len(), |k| i + k);
                continue;
            }
            b'"' if b[i..].starts_with(b"\"\"\"") => {
                // To the closing """, past escaped quotes.
                let mut j = i + 3;
                loop {
                    j = find(j, b"\"\"\"");
                    if j >= b.len() || b[j - 4] != b'\\' {
                        break;
                    }
                }
                i = j;
            }
            b'\'' if b[i..].starts_with(b"\'\'\'") => i = find(i + 3, b"\'\'\'"),
            b'"' => {
                let mut j = i + 1;
                while j < b.len() && b[j] != b'"' && b[j] != b'\n' {
                    j += if b[j] == b'\\' { 2 } else { 1 };
                }
                i = j + 1;
            }
            b'\'' => {
                i = b[i + 1..]
                    .iter()
                    .position(|&c| c == b'\'' || c == b'\n')
                    .map_or(b.len(), |k| i + 1 + k + 1);
            }
            b'[' if line_start && depth == 0 => {
                let line = src[..i].rfind('\n').map_or(0, |k| k + 1);
                starts.push(line);
                // The header's own brackets.
                i = b[i..]
                    .iter()
                    .position(|&c| c == b'\n')
                    .map_or(b.len(), |k| i + k);
            }
            b'[' | b'{' => {
                depth += 1;
                i += 1;
            }
            b']' | b'}' => {
                depth = depth.saturating_sub(1);
                i += 1;
            }
            _ => i += 1,
        }
        line_start = false;
    }
    starts.dedup();
    let mut out = Vec::new();
    let mut from = 0;
    for (k, &s) in starts.iter().enumerate().skip(1) {
        if s - from >= size {
            out.push((from, s));
            from = s;
        }
        let _ = k;
    }
    out.push((from, src.len()));
    out
}

/// The model formats read, in words.
pub(super) const MODELS: &str = formats(
    cfg!(feature = "gltf"),
    cfg!(feature = "ply"),
    cfg!(feature = "threemf"),
);

/// [`MODELS`] for the loaders built.
const fn formats(gltf: bool, ply: bool, threemf: bool) -> &'static str {
    match (gltf, ply, threemf) {
        (true, true, true) => ".obj with its .mtl, .stl, .gltf, .glb, .ply, .3mf",
        (true, true, false) => ".obj with its .mtl, .stl, .gltf, .glb, .ply",
        (true, false, true) => ".obj with its .mtl, .stl, .gltf, .glb, .3mf",
        (true, false, false) => ".obj with its .mtl, .stl, .gltf, .glb",
        (false, true, true) => ".obj with its .mtl, .stl, .ply, .3mf",
        (false, true, false) => ".obj with its .mtl, .stl, .ply",
        (false, false, true) => ".obj with its .mtl, .stl, .3mf",
        (false, false, false) => ".obj with its .mtl, .stl",
    }
}

/// Loads a model file by its extension, or a built-in shape by its name:
/// its geometry, and what the loader has to tell.
pub fn load_geometry(path: &Path, options: &LoadOptions) -> Result<(Arc<Geometry>, Vec<String>)> {
    let files = file::Files::new(options.max_bytes);
    let (geometry, mut notes) = load_geometry_in(path, options, &files)?;
    notes.extend(files.take_notes());
    Ok((geometry, notes))
}

/// [`load_geometry`], every file opened through `files`.
pub(super) fn load_geometry_in(
    path: &Path,
    options: &LoadOptions,
    files: &file::Files,
) -> Result<(Arc<Geometry>, Vec<String>)> {
    let (format, note) = Format::of(path)?;
    load_as(path, format, note, options, files)
}

/// [`load_geometry`] of a file whose format is known (`note`: what telling
/// it said, if anything), every file opened through `files`.
pub(super) fn load_as(
    path: &Path,
    format: Format,
    note: Option<String>,
    options: &LoadOptions,
    files: &file::Files,
) -> Result<(Arc<Geometry>, Vec<String>)> {
    let mut loaded = match format {
        Format::Obj => obj::load_in(path, options, files)?,
        Format::Stl => stl::load_in(path, options, files)?,
        #[cfg(feature = "gltf")]
        Format::Gltf => gltf::load_in(path, options, files)?,
        #[cfg(feature = "ply")]
        Format::Ply => ply::load_in(path, options, files)?,
        #[cfg(feature = "threemf")]
        Format::ThreeMf => threemf::load_in(path, options, files)?,
        Format::Shape(shape) => {
            let mut g = shape.geometry();
            if options.crease != mesh::DEFAULT_CREASE {
                Arc::make_mut(&mut g).compute_normals(options.crease);
            }
            return Ok((g, Vec::new()));
        }
        #[allow(unreachable_patterns)]
        _ => {
            return Err(Error::Invalid(format!(
                "{}: not a model: expected a model file ({MODELS}), or one of cube, sphere, torus",
                path.display()
            )));
        }
    };
    loaded.notes.splice(0..0, note);
    Ok((Arc::new(loaded.geometry), loaded.notes))
}
