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
    let files = file::Files::new(options.max_bytes);
    let mut loaded = load_in(path, options, &files)?;
    loaded.notes.extend(files.take_notes());
    Ok(loaded)
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
    let ply_error = |e: ply_rs_bw::parser::ParseError| bad(one_line(&e.to_string()));
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
    let mut g = Geometry::new_raw(name, positions, triangles);
    g.colors = colors;
    match normals {
        Some(ns) if !added => g.normals = ns,
        _ => g.compute_normals(crease),
    }
    g.analyze();
    notes.extend(polygon::fallback_note(name, cutter.fallbacks));
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

/// The parser's message on one line, without the line it quotes (a
/// `String: '…'` part, which may be megabytes of the file).
fn one_line(message: &str) -> String {
    let mut kept = String::new();
    let mut rest = message;
    while let Some(i) = rest.find("\n\tString: '") {
        kept.push_str(&rest[..i]);
        rest = rest[i..].find("\n\tError: ").map_or("", |j| &rest[i + j..]);
    }
    kept.push_str(rest);
    kept.split('\n')
        .map(|part| {
            part.trim()
                .trim_start_matches("Error: ")
                .trim_end_matches('.')
        })
        .filter(|part| !part.is_empty())
        .collect::<Vec<_>>()
        .join(": ")
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
