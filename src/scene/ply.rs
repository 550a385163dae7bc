//! PLY models (ASCII, binary little- and big-endian), through `ply-rs-bw`,
//! the maintained fork of `ply-rs` (whose unbounded preallocation from a
//! header's count it fixed: counts no longer size allocations).
//!
//! Read: the `vertex` element's `x`, `y`, `z`, its normals `nx`, `ny`, `nz`
//! when every vertex has them (else normals are computed as for OBJ) and
//! its colours `red`, `green`, `blue` (bytes, or floats in [0, 1]; sRGB, as
//! scanners write them) when every vertex has them; the `face` element's
//! `vertex_indices` (or `vertex_index`) lists, each polygon cut into
//! triangles as OBJ's are (a quad along the diagonal that keeps both halves
//! facing one way, larger polygons by constrained Delaunay triangulation).
//! Other elements and properties are said in a note. A PLY file without
//! faces (a point cloud) has nothing to draw and is refused.

use std::cell::Cell;
use std::io::{self, BufRead, BufReader, Read};
use std::path::Path;
use std::rc::Rc;

use glam::Vec3;
use ply_rs_bw::parser::{Parser, Reader};
use ply_rs_bw::ply::{Encoding, Property, PropertyAccess, PropertyAccessResult};

use super::LoadOptions;
use super::file;
use super::mesh::Geometry;
use super::obj::Loaded;
use super::polygon::{self, Point, Triangulator};
use crate::color::{Lin, Rgb};
use crate::error::{Error, Result};

/// Loads a PLY file.
pub fn load(path: &Path, options: &LoadOptions) -> Result<Loaded> {
    Loaded::with_files(options.max_bytes, |files| load_in(path, options, files))
}

/// [`load`], the file opened through `files`.
pub(crate) fn load_in(path: &Path, options: &LoadOptions, files: &file::Files) -> Result<Loaded> {
    let file = files.open(path)?;
    read(
        BufReader::new(file),
        &path.display().to_string(),
        options.crease,
    )
}

/// Parses PLY bytes; `name` is used in messages.
pub fn parse(bytes: &[u8], name: &str) -> Result<Loaded> {
    read(bytes, name, LoadOptions::default().crease)
}

fn read(r: impl Read, name: &str, crease: f32) -> Result<Loaded> {
    let bad = |what: String| Error::Invalid(format!("{name}: {what}"));
    let ply_error = |e: ply_rs_bw::parser::ParseError| in_words(name, &e);
    let ascii = Rc::new(Cell::new(true));
    let mut reader = Reader::new(LineCap {
        inner: BufReader::new(r),
        run: 0,
        lines: 0,
        on: Rc::clone(&ascii),
    });
    let header = Parser::<Skip>::new()
        .read_header(&mut reader)
        .map_err(ply_error)?;
    ascii.set(header.encoding == Encoding::Ascii);
    let mut notes = Vec::new();
    let (mut vertices, mut faces, mut others) = (None, None, Vec::new());
    for (key, def) in &header.elements {
        match key.as_str() {
            "vertex" if vertices.is_none() => {
                vertices = Some(
                    Parser::<Vertex>::new()
                        .read_payload_for_element(&mut reader, def, &header)
                        .map_err(ply_error)?,
                );
            }
            "face" if faces.is_none() => {
                faces = Some(
                    Parser::<Face>::new()
                        .read_payload_for_element(&mut reader, def, &header)
                        .map_err(ply_error)?,
                );
            }
            other => {
                Parser::<Skip>::new()
                    .read_payload_for_element(&mut reader, def, &header)
                    .map_err(ply_error)?;
                others.push(other);
            }
        }
    }
    let vertices = vertices.ok_or_else(|| bad("no vertex element".into()))?;
    let mut positions = Vec::with_capacity(vertices.len());
    for (i, v) in vertices.iter().enumerate() {
        if v.has & Vertex::POSITION != Vertex::POSITION {
            return Err(bad(format!("vertex {i} has no numeric x, y and z")));
        }
        positions.push(Vec3::from(v.position));
    }
    let normals: Option<Vec<Vec3>> = vertices
        .iter()
        .all(|v| v.has & Vertex::NORMAL == Vertex::NORMAL)
        .then(|| {
            vertices
                .iter()
                .map(|v| Vec3::from(v.normal))
                .map(|n| {
                    if n.is_finite() {
                        n.normalize_or_zero()
                    } else {
                        Vec3::NAN
                    }
                })
                .collect()
        })
        .filter(|ns: &Vec<Vec3>| ns.iter().all(|n| n.is_finite()));
    let colors: Option<Vec<Lin>> = vertices
        .iter()
        .all(|v| v.has & Vertex::COLOR == Vertex::COLOR)
        .then(|| {
            vertices
                .iter()
                .map(|v| Lin::from_srgb(Rgb(v.color)))
                .collect()
        });
    drop(vertices);
    let faces =
        faces.ok_or_else(|| bad("no face element: a point cloud has nothing to draw".into()))?;
    let n = positions.len();
    let mut colors = colors;
    let mut triangles = Vec::with_capacity(faces.len());
    let mut cutter = Triangulator::new();
    let (mut corners, mut corner_pos, mut cut) = (Vec::new(), Vec::new(), Vec::new());
    for (f, face) in faces.iter().enumerate() {
        let Some(list) = &face.corners else {
            return Err(bad(format!(
                "face {f} has no vertex_indices list of integers"
            )));
        };
        corners.clear();
        corners.extend_from_slice(list);
        if corners.iter().any(|&i| i as usize >= n) {
            return Err(bad(format!(
                "face {f} names a vertex out of range (there are {n} vertices)"
            )));
        }
        let quad = match corners[..] {
            [a, b, c, d] => polygon::quad([a, b, c, d].map(|i| positions[i as usize])),
            _ => None,
        };
        match (&corners[..], quad) {
            ([] | [_] | [_, _], _) => {
                return Err(bad(format!("face {f} has fewer than 3 vertices")));
            }
            (&[a, b, c], _) => triangles.push([a, b, c]),
            (&[a, b, c, d], Some(k)) => {
                let q = [a, b, c, d];
                let [a, b, c, e] = [k, k + 1, k + 2, (k + 3) % 4].map(|j| q[j]);
                triangles.push([a, b, c]);
                triangles.push([a, c, e]);
            }
            _ => {
                corner_pos.clear();
                corner_pos.extend(corners.iter().map(|&i| positions[i as usize]));
                cut.clear();
                cutter.triangulate(&corner_pos, &mut cut);
                for tri in cut.drain(..) {
                    let t = tri.map(|p| match p {
                        Point::Corner(i) => corners[i as usize],
                        Point::Between { a, b, t } => {
                            // A new vertex on the edge: its position, normal and
                            // colour interpolated.
                            let (a, b) =
                                (corners[a as usize] as usize, corners[b as usize] as usize);
                            positions.push(positions[a].lerp(positions[b], t));
                            if let Some(cs) = &mut colors {
                                let (ca, cb) =
                                    (Vec3::from(cs[a].to_f32()), Vec3::from(cs[b].to_f32()));
                                cs.push(Lin::from_f32(ca.lerp(cb, t).to_array()));
                            }
                            (positions.len() - 1) as u32
                        }
                    });
                    triangles.push(t);
                }
            }
        }
    }
    if !others.is_empty() {
        notes.push(format!(
            "{name}: not drawn: the element{} {}",
            if others.len() > 1 { "s" } else { "" },
            others.join(", ")
        ));
    }
    let added = positions.len() > n;
    // A position that is not a finite number takes its faces with it, as
    // in OBJ files.
    let dropped = super::mesh::drop_unfinite_faces(&positions, &mut triangles, &mut []);
    notes.extend(super::mesh::unfinite_note(name, dropped));
    if triangles.is_empty() {
        return Err(bad(if dropped.1 > 0 {
            "no faces to draw: every one has a vertex that is not a finite number".into()
        } else {
            "no faces to draw".into()
        }));
    }
    let mut g = Geometry::new_raw(name, positions, triangles);
    g.colors = colors;
    match normals {
        Some(ns) if !added => g.normals = ns,
        _ => g.compute_normals(crease),
    }
    g.analyze();
    notes.extend(polygon::fallback_note(name, &cutter));
    Ok(Loaded { geometry: g, notes })
}

/// The longest line of an ASCII PLY file (header or element), 4 MiB: a
/// face of about 500,000 corners. A longer one is refused as it is read,
/// because the parser holds a line and its tokens at once (up to 11 times
/// the line's bytes for one-digit tokens): this bounds what one line can
/// cost to about 45 MiB whatever the file.
pub const MAX_LINE: usize = 4 << 20;

/// A reader that refuses a line longer than [`MAX_LINE`] while `on` (the
/// header, and an ASCII body; a binary body has no lines).
struct LineCap<R> {
    inner: R,
    /// Bytes since the last newline.
    run: usize,
    /// Newlines consumed, while `on`.
    lines: usize,
    on: Rc<Cell<bool>>,
}

impl<R: BufRead> Read for LineCap<R> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let n = {
            let have = self.fill_buf()?;
            let n = have.len().min(buf.len());
            buf[..n].copy_from_slice(&have[..n]);
            n
        };
        self.consume(n);
        Ok(n)
    }
}

impl<R: BufRead> BufRead for LineCap<R> {
    fn fill_buf(&mut self) -> io::Result<&[u8]> {
        if self.on.get() && self.run > MAX_LINE {
            return Err(io::Error::new(
                io::ErrorKind::InvalidData,
                format!("line {}: longer than {MAX_LINE} bytes", self.lines + 1),
            ));
        }
        self.inner.fill_buf()
    }

    fn consume(&mut self, amt: usize) {
        if let Ok(buf) = self.inner.fill_buf() {
            let taken = &buf[..amt.min(buf.len())];
            if self.on.get() {
                self.lines += memchr::memchr_iter(b'\n', taken).count();
            }
            self.run = match memchr::memrchr(b'\n', taken) {
                Some(k) => taken.len() - k - 1,
                None => self.run + taken.len(),
            };
        }
        self.inner.consume(amt);
    }
}

/// The parser's error in words, at its line (and column, where the parser
/// gives one): what is wrong and what was expected, never the parser's own
/// types (`ParseError { location: LineCol { … } }`, `ParseIntError { kind:
/// … }`), nor the line it quotes (which may be megabytes of the file).
fn in_words(name: &str, e: &ply_rs_bw::parser::ParseError) -> Error {
    let text = e.to_string();
    let text = match (e.line(), text.split_once(": ")) {
        (Some(_), Some((head, rest))) if head.starts_with("Line ") => rest,
        _ => &text,
    };
    // The message, then `\n\tString: '…'`, `\n\tValue: '…'`, `\n\tError: …`.
    let mut parts = text.split("\n\t");
    let head = parts.next().unwrap_or("").trim();
    let (mut value, mut inner) = ("", "");
    for part in parts {
        if let Some(v) = part.strip_prefix("Value: '") {
            value = v.trim_end_matches(", ").trim_end_matches('\'');
        } else if let Some(e) = part.strip_prefix("Error: ") {
            inner = e.trim().trim_end_matches(',');
        }
    }
    let mut column = None;
    let what = if head.starts_with("Expected magic number") {
        "not a PLY file: its first line is not `ply`".to_string()
    } else if head == "Couldn't parse line." {
        let (at, expected) = peg_error(inner);
        column = at;
        format!("not a header line PLY knows (expected {expected})")
    } else if head == "Unexpected 'ply' found." {
        "a second `ply` line".into()
    } else if head.starts_with("Found contradicting format definition") {
        "a second `format` line, unlike the first".into()
    } else if head == "Invalid version" {
        "the format's version is not 1.0".into()
    } else if head == "Invalid element" {
        "not an element line PLY knows (`element NAME COUNT`)".into()
    } else if head.starts_with("Property '") {
        "a property before any element".into()
    } else if head.starts_with("Unexpected end of file while reading header") {
        "the file ends before the header's end_header line".into()
    } else if head == "Parse error." {
        format!("{} {}", shown(value), not_a(inner))
    } else if let Some(rest) = head.strip_prefix("Couldn't parse element at index ") {
        let (i, err) = rest.split_once(": ").unwrap_or((rest, ""));
        format!("item {i} of a list {}", not_a(err))
    } else if head.starts_with("Couldn't read element line.")
        || head.starts_with("Couldn't parse element line.")
    {
        // The cause, one level down.
        if !value.is_empty() {
            format!("{} {}", shown(value), not_a(inner))
        } else if let Some(rest) = inner.strip_prefix("Couldn't parse element at index ") {
            let (i, err) = rest.split_once(": ").unwrap_or((rest, ""));
            format!("item {i} of a list {}", not_a(err))
        } else if let Some(rest) = inner.strip_prefix("error at ") {
            // The element grammar's error: `error at 1:3: expected one of …`.
            let (at, list) = rest.split_once(": ").unwrap_or((rest, ""));
            column = at.split(':').nth(1).and_then(|c| c.parse().ok());
            let list = list
                .trim_start_matches("expected one of ")
                .trim_start_matches("expected ");
            format!(
                "not a number where one belongs (expected {})",
                expected_words(list.split(", ").map(str::to_string))
            )
        } else if let Some(rest) = inner.strip_prefix("Expected ") {
            let numbers: Vec<&str> = rest
                .split(|c: char| !c.is_ascii_digit())
                .filter(|n| !n.is_empty())
                .collect();
            match numbers[..] {
                [n, m] if rest.contains("list elements") => {
                    format!("a list that says it has {n} items has {m}")
                }
                _ => "the line ends before the element's last property".into(),
            }
        } else {
            format!("an element line that cannot be read: {}", scrubbed(inner))
        }
    } else if head.starts_with("Expected element of type") {
        "the line ends before the element's last property".into()
    } else if let Some(rest) = head.strip_prefix("PLY property '") {
        let property = rest.split('\'').next().unwrap_or("");
        format!(
            "property {} has a type rastty does not read there",
            shown(property)
        )
    } else {
        scrubbed(head)
    };
    match e.line() {
        Some(line) => Error::Parse {
            path: name.to_string(),
            line,
            column: column.unwrap_or(1),
            message: what,
        },
        None => Error::Invalid(format!("{name}: {what}")),
    }
}

/// A value from the file, quoted and cut.
fn shown(value: &str) -> String {
    crate::text::name(value, 40)
}

/// What a number that failed to parse is not, from the standard library's
/// error (`ParseIntError { kind: InvalidDigit }`).
fn not_a(error: &str) -> &'static str {
    if error.contains("PosOverflow") || error.contains("NegOverflow") {
        "is too large for its type"
    } else if error.contains("ParseIntError") {
        "is not a whole number of its type"
    } else if error.contains("ParseFloatError") {
        "is not a number"
    } else {
        "cannot be read"
    }
}

/// The column and the expected tokens of a header grammar's error
/// (`ParseError { location: LineCol { line: 1, column: 16, offset: 15 },
/// expected: ExpectedSet { expected: {"['0'..='9']", …} } }`), in words.
fn peg_error(debug: &str) -> (Option<usize>, String) {
    let column = debug
        .split_once("column: ")
        .and_then(|(_, r)| r.split(|c: char| !c.is_ascii_digit()).next())
        .and_then(|n| n.parse().ok());
    let set = debug
        .split_once("expected: {")
        .map_or("", |(_, r)| r.split('}').next().unwrap_or(""));
    // Each token as its Debug shows it, `"\"comment\""`: the outer quotes
    // off, then the escapes undone.
    let tokens = set.split(", ").map(|t| {
        let t = t.strip_prefix('"').unwrap_or(t);
        let t = t.strip_suffix('"').unwrap_or(t);
        t.replace("\\\"", "\"").replace("\\\\", "\\")
    });
    (column, expected_words(tokens))
}

/// A grammar's expected tokens (`['0'..='9']`, `"\r\n"`, `EOF`) in words.
fn expected_words(tokens: impl Iterator<Item = String>) -> String {
    let mut words: Vec<String> = tokens
        .map(|t| t.trim().to_string())
        .filter(|t| !t.is_empty())
        .map(|t| match t.as_str() {
            "['0'..='9']" => "a digit".to_string(),
            "['-'|'+']" => "a sign".to_string(),
            "[' '|'\\t']" | "[' ' | '\\t']" => "a space".to_string(),
            "EOF" | "\"\\r\\n\"" | "['\\n'|'\\r']" => "the end of the line".to_string(),
            _ if t.starts_with('"') => format!("`{}`", t.trim_matches('"')),
            _ => "another character".to_string(),
        })
        .collect();
    words.sort();
    words.dedup();
    match words.len() {
        0 => "something else".to_string(),
        1 => words.remove(0),
        _ => {
            let last = words.pop().unwrap_or_default();
            format!("{} or {last}", words.join(", "))
        }
    }
}

/// A message of the parser's with any type shown by its `Debug` (`Name {
/// … }`, `Name(…)`) and tabs and line breaks taken out.
fn scrubbed(message: &str) -> String {
    let one: String = message
        .split(['\n', '\t'])
        .map(str::trim)
        .filter(|p| !p.is_empty() && !p.starts_with("String: "))
        .collect::<Vec<_>>()
        .join(": ");
    match one.find(" {").or_else(|| one.find('(')) {
        Some(i) => one[..i]
            .trim_end_matches(|c: char| c.is_alphanumeric() || c == '\'')
            .trim_end()
            .trim_end_matches(':')
            .to_string(),
        None => one.trim_end_matches('.').to_string(),
    }
}

/// A `vertex` element as read: only what is drawn, 28 bytes.
#[derive(Clone, Copy, Debug)]
struct Vertex {
    position: [f32; 3],
    normal: [f32; 3],
    color: [u8; 3],
    /// Which coordinates were found, one bit each.
    has: u16,
}

impl Vertex {
    const POSITION: u16 = 0b111;
    const NORMAL: u16 = 0b111 << 3;
    const COLOR: u16 = 0b111 << 6;
}

impl PropertyAccess for Vertex {
    fn new() -> Self {
        Vertex {
            position: [0.0; 3],
            normal: [0.0; 3],
            color: [0; 3],
            has: 0,
        }
    }

    fn set_property(&mut self, key: &str, p: Property) -> PropertyAccessResult {
        let bit = match key {
            "x" | "y" | "z" | "nx" | "ny" | "nz" => {
                let Some(v) = p.to_f32_lossy() else {
                    return PropertyAccessResult::Ignored;
                };
                let k = match key {
                    "x" => 0,
                    "y" => 1,
                    "z" => 2,
                    "nx" => 3,
                    "ny" => 4,
                    _ => 5,
                };
                if k < 3 {
                    self.position[k] = v;
                } else {
                    self.normal[k - 3] = v;
                }
                k
            }
            "red" | "green" | "blue" => {
                let Some(v) = p.to_u8_color_lossy() else {
                    return PropertyAccessResult::Ignored;
                };
                let k = match key {
                    "red" => 0,
                    "green" => 1,
                    _ => 2,
                };
                self.color[k] = v;
                6 + k
            }
            _ => return PropertyAccessResult::Ignored,
        };
        self.has |= 1 << bit;
        PropertyAccessResult::Set
    }
}

/// A `face` element as read: its corners (`None` without a list of
/// integers); a negative index is kept as `u32::MAX`, out of range.
#[derive(Clone, Debug)]
struct Face {
    corners: Option<Vec<u32>>,
}

impl PropertyAccess for Face {
    fn new() -> Self {
        Face { corners: None }
    }

    fn set_property(&mut self, key: &str, p: Property) -> PropertyAccessResult {
        if key != "vertex_indices" && key != "vertex_index" {
            return PropertyAccessResult::Ignored;
        }
        fn list<T: Copy>(v: &[T], f: impl Fn(T) -> i64) -> Vec<u32> {
            v.iter()
                .map(|&i| u32::try_from(f(i)).unwrap_or(u32::MAX))
                .collect()
        }
        self.corners = match &p {
            Property::ListInt(v) => Some(list(v, i64::from)),
            Property::ListUInt(v) => Some(list(v, i64::from)),
            Property::ListShort(v) => Some(list(v, i64::from)),
            Property::ListUShort(v) => Some(list(v, i64::from)),
            Property::ListChar(v) => Some(list(v, i64::from)),
            Property::ListUChar(v) => Some(list(v, i64::from)),
            _ => return PropertyAccessResult::Ignored,
        };
        PropertyAccessResult::Set
    }
}

/// An element that is not drawn: read past, nothing kept.
struct Skip;

impl PropertyAccess for Skip {
    fn new() -> Self {
        Skip
    }
}
