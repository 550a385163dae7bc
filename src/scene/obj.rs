//! Wavefront OBJ, with the diffuse colours (`Kd`) of the MTL files it names.
//!
//! Read in one pass over the bytes, a line at a time through a buffer
//! (never the whole file in memory), numbers parsed by `fast-float2`, every
//! error naming the file, line and column of what is wrong. rastty's own
//! parser rather than `tobj`: tobj parses Tux (41k triangles) in 209M
//! instructions and reports no positions, where this parser needs a
//! fraction of that and knows where everything is.
//!
//! What is read: `v` (with an optional `w`, and vertex colours `v x y z r g
//! b`), `vn`, `vt` (checked; textures are not drawn), `f` (any number of
//! corners, `v`, `v/vt`, `v//vn` or `v/vt/vn`, indices from 1 or negative
//! from the end), `usemtl`, `mtllib` (one or more files). `l` and `p`
//! (lines and points) are not faces: they are skipped and counted, and a
//! file of nothing else has no faces. Other statements (`o`, `g`, `s`, …)
//! are ignored. Polygons are cut into triangles by [`super::polygon`].
//!
//! Normals come from the file when every corner names one; otherwise they
//! are computed (see [`super::mesh`]). A vertex that is not a finite number
//! is not an error, but the faces that use it are not drawn, and the loader
//! says so.

use std::path::Path;

use glam::Vec3;
use rustc_hash::FxHashMap;

use super::file::{self, Limits, Lines};
use super::mesh::{Geometry, MaterialRun};
use super::polygon::{Point, Triangulator};
use crate::color::Rgb;
use crate::error::{Error, Result};

/// A model read from a file, and what the reader has to tell.
#[derive(Debug)]
pub struct Loaded {
    pub geometry: Geometry,
    /// Things read but not drawn: non-finite vertices, lines and points.
    pub notes: Vec<String>,
}

/// Loads an OBJ file (and its MTL files, found beside it).
pub fn load(path: &Path, limits: &Limits) -> Result<Loaded> {
    let (file, _) = file::open(path, limits)?;
    read(
        file,
        &path.display().to_string(),
        path.parent().unwrap_or(Path::new(".")),
        limits,
    )
}

/// Parses OBJ bytes; `name` is used in messages, material libraries are
/// looked for in `dir`.
pub fn parse(src: &[u8], name: &str, dir: &Path) -> Result<Loaded> {
    read(src, name, dir, &Limits::default())
}

/// No index (a corner without a normal).
const NONE: u32 = u32::MAX;
/// The bit that marks a vertex made while cutting a polygon, numbered apart
/// until the end of the file.
const MADE: u32 = 1 << 31;

/// Everything gathered while reading.
struct Reader<'a> {
    name: &'a str,
    dir: &'a Path,
    limits: &'a Limits,
    /// The file's `v`, `vn` and vertex colours, and how many `vt`.
    pos: Vec<Vec3>,
    /// Where each non-finite `v` is (line), counted.
    bad_pos: Vec<u32>,
    colors: Vec<Rgb>,
    vn: Vec<Vec3>,
    vt: usize,
    /// Output vertices as `v | vn << 32`, once a corner names a normal
    /// (until then a vertex is its `v`).
    keys: Option<(Vec<u64>, FxHashMap<u64, u32>)>,
    /// Vertices made between corners: position, colour, normal.
    made: Vec<(Vec3, Rgb, Vec3)>,
    triangles: Vec<[u32; 3]>,
    materials: Vec<MaterialRun>,
    library: FxHashMap<Vec<u8>, Option<Rgb>>,
    /// Whether every corner so far named a normal.
    all_normals: bool,
    lines_and_points: usize,
    dropped_faces: usize,
    cutter: Triangulator,
    corners: Vec<(u32, u32)>,
    ids: Vec<u32>,
    corner_pos: Vec<Vec3>,
    cut: Vec<[Point; 3]>,
}

fn read(src: impl std::io::Read, name: &str, dir: &Path, limits: &Limits) -> Result<Loaded> {
    let mut r = Reader {
        name,
        dir,
        limits,
        pos: Vec::new(),
        bad_pos: Vec::new(),
        colors: Vec::new(),
        vn: Vec::new(),
        vt: 0,
        keys: None,
        made: Vec::new(),
        triangles: Vec::new(),
        materials: Vec::new(),
        library: FxHashMap::default(),
        all_normals: true,
        lines_and_points: 0,
        dropped_faces: 0,
        cutter: Triangulator::new(),
        corners: Vec::new(),
        ids: Vec::new(),
        corner_pos: Vec::new(),
        cut: Vec::new(),
    };
    let mut lines = Lines::new(src);
    loop {
        let (n, line) = match lines.next_line() {
            Ok(Some(next)) => next,
            Ok(None) => break,
            Err((n, e)) => return Err(r.at(n, 1, e)),
        };
        // A binary file is seldom text for long: say so at its first line
        // that starts with a NUL, rather than what it is not.
        if line.first() == Some(&0) {
            return Err(r.at(n, 1, "a NUL byte: not a text file"));
        }
        r.statement(line, n)?;
    }
    r.finish(lines.number)
}

impl Reader<'_> {
    /// An error at byte `offset` of line `n`'s text `line`.
    fn at_byte(&self, line: &[u8], n: usize, offset: usize, message: impl Into<String>) -> Error {
        self.at(n, file::column(line, offset), message)
    }

    fn at(&self, line: usize, column: usize, message: impl Into<String>) -> Error {
        Error::Parse {
            path: self.name.to_string(),
            line,
            column,
            message: message.into(),
        }
    }

    fn statement(&mut self, line: &[u8], n: usize) -> Result<()> {
        let mut words = file::words(line);
        let Some((keyword, _)) = words.next() else {
            return Ok(());
        };
        match keyword {
            b"v" => {
                let mut v = [0.0f32; 7];
                let mut k = 0;
                for (w, col) in words {
                    if k == 7 {
                        return Err(self.at_byte(line, n, col, "`v` takes at most 7 numbers"));
                    }
                    v[k] =
                        number(w).ok_or_else(|| self.at_byte(line, n, col, not_number("v", w)))?;
                    k += 1;
                }
                let color = match k {
                    3 | 4 => None,
                    6 => Some([v[3], v[4], v[5]]),
                    7 => Some([v[4], v[5], v[6]]),
                    _ => {
                        return Err(self.at(
                            n,
                            1,
                            format!(
                                "`v` takes x y z, with an optional w or a colour r g b, found {k} numbers"
                            ),
                        ));
                    }
                };
                let p = Vec3::new(v[0], v[1], v[2]);
                if !p.is_finite() {
                    self.bad_pos.push(n as u32);
                }
                if let Some(c) = color {
                    if c.iter().any(|x| !x.is_finite()) {
                        return Err(self.at(n, 1, "a vertex colour is not a finite number"));
                    }
                    // Vertices before the first coloured one were white.
                    self.colors.resize(self.pos.len(), Rgb::WHITE);
                    self.colors
                        .push(Rgb::from_f32(c.map(|x| x.clamp(0.0, 1.0) * 255.0)));
                } else if !self.colors.is_empty() {
                    self.colors.push(Rgb::WHITE);
                }
                self.pos.push(p);
            }
            b"vn" => {
                let mut v = [0.0f32; 3];
                let mut k = 0;
                for (w, col) in words {
                    if k == 3 {
                        return Err(self.at_byte(line, n, col, "`vn` takes 3 numbers"));
                    }
                    v[k] =
                        number(w).ok_or_else(|| self.at_byte(line, n, col, not_number("vn", w)))?;
                    k += 1;
                }
                if k != 3 {
                    return Err(self.at(n, 1, format!("`vn` needs 3 numbers, found {k}")));
                }
                self.vn.push(Vec3::from(v));
            }
            b"vt" => {
                let mut k = 0;
                for (w, col) in words {
                    if k == 3 {
                        return Err(self.at_byte(line, n, col, "`vt` takes at most 3 numbers"));
                    }
                    number(w).ok_or_else(|| self.at_byte(line, n, col, not_number("vt", w)))?;
                    k += 1;
                }
                if k == 0 {
                    return Err(self.at(n, 1, "`vt` needs at least 1 number"));
                }
                self.vt += 1;
            }
            b"f" => self.face(line, words, n)?,
            b"l" | b"p" => self.lines_and_points += 1,
            b"usemtl" => {
                let name = rest_of(line, words);
                let color = self.library.get(name).copied().flatten();
                let first = self.triangles.len() as u32;
                if let Some(last) = self.materials.last_mut().filter(|r| r.first == first) {
                    last.color = color;
                } else {
                    self.materials.push(MaterialRun { first, color });
                }
            }
            b"mtllib" => self.mtllib(line, words, n)?,
            _ => {}
        }
        Ok(())
    }

    /// One face: its corners resolved and checked, cut into triangles.
    fn face<'w>(
        &mut self,
        line: &[u8],
        words: impl Iterator<Item = (&'w [u8], usize)>,
        n: usize,
    ) -> Result<()> {
        self.corners.clear();
        let mut dropped = false;
        for (w, col) in words {
            let mut parts = w.split(|&b| b == b'/');
            let mut idx = [NONE; 3];
            let counts = [self.pos.len(), self.vt, self.vn.len()];
            for (k, part) in parts.by_ref().take(3).enumerate() {
                if part.is_empty() && k > 0 {
                    continue;
                }
                let i = index(part).ok_or_else(|| {
                    self.at_byte(
                        line,
                        n,
                        col,
                        format!("face vertex {:?} is not an index", lossy(w)),
                    )
                })?;
                let count = counts[k] as i64;
                let resolved = if i < 0 { count + i } else { i - 1 };
                if i == 0 || resolved < 0 || resolved >= count {
                    let what = ["vertex", "texture coordinate", "normal"][k];
                    return Err(self.at_byte(
                        line,
                        n,
                        col,
                        format!("face {what} index {i} is out of range (1 to {count} so far)"),
                    ));
                }
                idx[k] = resolved as u32;
            }
            if parts.next().is_some() {
                return Err(self.at_byte(
                    line,
                    n,
                    col,
                    format!("face vertex {:?} has more than 3 parts", lossy(w)),
                ));
            }
            let (v, vn) = (idx[0], idx[2]);
            dropped |= !self.pos[v as usize].is_finite()
                || (vn != NONE && !self.vn[vn as usize].is_finite());
            self.corners.push((v, vn));
        }
        if self.corners.len() < 3 {
            return Err(self.at(
                n,
                1,
                format!(
                    "a face needs at least 3 vertices, found {}",
                    self.corners.len()
                ),
            ));
        }
        if dropped {
            self.dropped_faces += 1;
            return Ok(());
        }
        // Output vertices: the `v` itself until a corner names a normal,
        // then (v, vn) pairs.
        let named = self.corners.iter().any(|&(_, vn)| vn != NONE);
        self.all_normals &= self.corners.iter().all(|&(_, vn)| vn != NONE);
        if named && self.keys.is_none() {
            let keys: Vec<u64> = (0..self.pos.len() as u64)
                .map(|v| v | (NONE as u64) << 32)
                .collect();
            let map = keys
                .iter()
                .enumerate()
                .map(|(i, &k)| (k, i as u32))
                .collect();
            self.keys = Some((keys, map));
        }
        let corners = std::mem::take(&mut self.corners);
        let mut ids = std::mem::take(&mut self.ids);
        ids.clear();
        for &(v, vn) in &corners {
            ids.push(self.vertex(v, vn));
        }
        self.corner_pos.clear();
        self.corner_pos
            .extend(corners.iter().map(|&(v, _)| self.pos[v as usize]));
        if corners.len() == 3 {
            self.triangles.push([ids[0], ids[1], ids[2]]);
        } else {
            self.cut.clear();
            self.cutter.triangulate(&self.corner_pos, &mut self.cut);
            for tri in std::mem::take(&mut self.cut) {
                let t = tri.map(|p| match p {
                    Point::Corner(i) => ids[i as usize],
                    Point::Between { a, b, t } => self.between(&corners, a as usize, b as usize, t),
                });
                self.triangles.push(t);
            }
        }
        self.corners = corners;
        self.ids = ids;
        Ok(())
    }

    /// The output vertex of a corner.
    fn vertex(&mut self, v: u32, vn: u32) -> u32 {
        match &mut self.keys {
            None => v,
            Some((keys, map)) => {
                let key = v as u64 | (vn as u64) << 32;
                let next = keys.len() as u32;
                let id = *map.entry(key).or_insert(next);
                if id == next {
                    keys.push(key);
                }
                id
            }
        }
    }

    /// A vertex made on the edge between corners `a` and `b`.
    fn between(&mut self, corners: &[(u32, u32)], a: usize, b: usize, t: f32) -> u32 {
        let ((va, na), (vb, nb)) = (corners[a], corners[b]);
        let p = self.pos[va as usize].lerp(self.pos[vb as usize], t);
        let color = if self.colors.is_empty() {
            Rgb::WHITE
        } else {
            let (ca, cb) = (
                self.colors[va as usize].to_f32(),
                self.colors[vb as usize].to_f32(),
            );
            Rgb::from_f32(std::array::from_fn(|k| ca[k] + (cb[k] - ca[k]) * t))
        };
        let normal = if na != NONE && nb != NONE {
            self.vn[na as usize].lerp(self.vn[nb as usize], t)
        } else {
            Vec3::Z
        };
        self.made.push((p, color, normal));
        MADE | (self.made.len() as u32 - 1)
    }

    /// `mtllib a.mtl b.mtl`: each file read in turn (or, if the names do
    /// not each exist, the whole rest of the line as one name with spaces).
    fn mtllib<'w>(
        &mut self,
        line: &[u8],
        words: impl Iterator<Item = (&'w [u8], usize)>,
        n: usize,
    ) -> Result<()> {
        let words: Vec<(&[u8], usize)> = words.collect();
        let whole = rest_of(line, std::iter::empty());
        let each_exists = words.iter().all(|(w, _)| self.dir.join(lossy(w)).is_file());
        let files: Vec<(&[u8], usize)> = if each_exists || words.is_empty() {
            words
        } else {
            vec![(whole, words[0].1)]
        };
        if files.is_empty() {
            return Err(self.at(n, 1, "`mtllib` names no file"));
        }
        for (file, col) in files {
            let path = self.dir.join(lossy(file));
            if !path.is_file() {
                return Err(self.at_byte(
                    line,
                    n,
                    col,
                    format!("material library {:?} not found", lossy(file)),
                ));
            }
            let mtl = mtl(&path, self.limits)?;
            self.library.extend(mtl);
        }
        Ok(())
    }

    fn finish(mut self, last_line: usize) -> Result<Loaded> {
        let mut notes = Vec::new();
        if let Some(&first) = self.bad_pos.first() {
            notes.push(format!(
                "{}:{first}: {} vertices are not finite numbers; the {} faces that use them are not drawn",
                self.name,
                self.bad_pos.len(),
                self.dropped_faces
            ));
        } else if self.dropped_faces > 0 {
            notes.push(format!(
                "{}: {} faces use normals that are not finite numbers and are not drawn",
                self.name, self.dropped_faces
            ));
        }
        if self.lines_and_points > 0 {
            notes.push(format!(
                "{}: {} line and point elements (`l`, `p`) are not faces and are not drawn",
                self.name, self.lines_and_points
            ));
        }
        if self.triangles.is_empty() {
            let why = if self.lines_and_points > 0 {
                format!(
                    "no faces in the file (only {} line and point elements)",
                    self.lines_and_points
                )
            } else if self.dropped_faces > 0 {
                "no face left: every face uses a vertex that is not a finite number".into()
            } else {
                "no faces in the file".into()
            };
            return Err(self.at(last_line.max(1), 1, why));
        }
        // Output vertices: positions (and colours, normals) gathered.
        let colored = !self.colors.is_empty();
        self.colors.resize(self.pos.len(), Rgb::WHITE);
        let (mut positions, mut colors, mut normals) = match self.keys.take() {
            None => (
                std::mem::take(&mut self.pos),
                std::mem::take(&mut self.colors),
                Vec::new(),
            ),
            Some((keys, _)) => {
                let v = |k: u64| (k & 0xffff_ffff) as usize;
                let vn = |k: u64| (k >> 32) as u32;
                (
                    keys.iter().map(|&k| self.pos[v(k)]).collect(),
                    keys.iter().map(|&k| self.colors[v(k)]).collect(),
                    if self.all_normals {
                        keys.iter()
                            .map(|&k| self.vn.get(vn(k) as usize).copied().unwrap_or(Vec3::Z))
                            .collect()
                    } else {
                        Vec::new()
                    },
                )
            }
        };
        let base = positions.len() as u32;
        for &(p, c, n) in &self.made {
            positions.push(p);
            colors.push(c);
            if !normals.is_empty() {
                normals.push(n);
            }
        }
        for t in &mut self.triangles {
            for i in t {
                if *i & MADE != 0 {
                    *i = base + (*i & !MADE);
                }
            }
        }
        let keep_normals = self.all_normals && !normals.is_empty();
        let mut g = Geometry::new_raw(self.name, positions, std::mem::take(&mut self.triangles));
        g.colors = colored.then_some(colors);
        g.materials = self.materials;
        if keep_normals {
            g.normals = normals
                .into_iter()
                .map(crate::transform::direction)
                .collect();
        } else {
            g.compute_normals(super::mesh::DEFAULT_CREASE);
        }
        g.analyze();
        Ok(Loaded { geometry: g, notes })
    }
}

/// A material library: each material's diffuse colour (`None`: it has no
/// `Kd`).
fn mtl(path: &Path, limits: &Limits) -> Result<FxHashMap<Vec<u8>, Option<Rgb>>> {
    let (file, _) = file::open(path, limits)?;
    let name = path.display().to_string();
    let at = |line: usize, column: usize, message: String| Error::Parse {
        path: name.clone(),
        line,
        column,
        message,
    };
    let at_byte = |text: &[u8], line: usize, offset: usize, message: String| {
        at(line, file::column(text, offset), message)
    };
    let mut out = FxHashMap::default();
    let mut current: Option<Vec<u8>> = None;
    let mut lines = Lines::new(file);
    loop {
        let (n, line) = match lines.next_line() {
            Ok(Some(next)) => next,
            Ok(None) => break,
            Err((n, e)) => return Err(at(n, 1, e)),
        };
        let mut words = file::words(line);
        match words.next() {
            Some((b"newmtl", _)) => {
                let m = rest_of(line, words).to_vec();
                out.insert(m.clone(), None);
                current = Some(m);
            }
            Some((b"Kd", kcol)) => {
                let mut c = [0.0f32; 3];
                let mut k = 0;
                for (w, col) in words.take(3) {
                    c[k] = number(w).filter(|v| v.is_finite()).ok_or_else(|| {
                        at_byte(
                            line,
                            n,
                            col,
                            format!("`Kd`: {:?} is not a colour component", lossy(w)),
                        )
                    })?;
                    k += 1;
                }
                if k == 1 {
                    c = [c[0]; 3];
                } else if k != 3 {
                    return Err(at_byte(
                        line,
                        n,
                        kcol,
                        format!("`Kd` needs 3 numbers, found {k}"),
                    ));
                }
                let Some(m) = &current else {
                    return Err(at_byte(line, n, kcol, "`Kd` before any `newmtl`".into()));
                };
                out.insert(
                    m.clone(),
                    Some(Rgb::from_f32(c.map(|v| v.clamp(0.0, 1.0) * 255.0))),
                );
            }
            _ => {}
        }
    }
    Ok(out)
}

/// The rest of a line after the words taken so far, trimmed, up to a
/// comment: a name that may hold spaces.
fn rest_of<'l, 'w>(line: &'l [u8], mut words: impl Iterator<Item = (&'w [u8], usize)>) -> &'l [u8] {
    let end = line.iter().position(|&b| b == b'#').unwrap_or(line.len());
    match words.next() {
        Some((_, at)) => line[at..end].trim_ascii(),
        None => {
            // After the keyword: skip it and the blanks.
            let line = line[..end].trim_ascii_start();
            let k = line
                .iter()
                .position(|b| b.is_ascii_whitespace())
                .unwrap_or(line.len());
            line[k..].trim_ascii()
        }
    }
}

/// A number; the common short decimals (`-0.008366`) by the exact fast
/// path, everything else by `fast-float2`.
fn number(w: &[u8]) -> Option<f32> {
    short_decimal(w).or_else(|| fast_float2::parse::<f32, _>(w).ok())
}

/// Powers of ten exact in f32 (5^10 < 2^24).
const POW10: [f32; 11] = [1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10];

/// `[-]digits[.digits]` whose digits, read as an integer, are below 2^24,
/// with at most 10 decimals: the integer and the power of ten are both
/// exact in f32, so one division rounds correctly (Clinger's fast path).
/// `None` for anything else.
#[inline]
fn short_decimal(w: &[u8]) -> Option<f32> {
    let (neg, s) = match w {
        [b'-', rest @ ..] => (true, rest),
        [b'+', rest @ ..] => (false, rest),
        _ => (false, w),
    };
    if s.is_empty() || s.len() > 19 {
        return None;
    }
    let mut m = 0u64;
    let mut i = 0;
    while i < s.len() && s[i].is_ascii_digit() {
        m = m * 10 + (s[i] - b'0') as u64;
        i += 1;
    }
    let whole = i;
    let mut decimals = 0;
    if i < s.len() && s[i] == b'.' {
        i += 1;
        let from = i;
        while i < s.len() && s[i].is_ascii_digit() {
            m = m * 10 + (s[i] - b'0') as u64;
            i += 1;
        }
        decimals = i - from;
    }
    if i != s.len() || whole + decimals == 0 || decimals > 10 || m >= 1 << 24 {
        return None;
    }
    let v = m as f32 / POW10[decimals];
    Some(if neg { -v } else { v })
}

fn index(w: &[u8]) -> Option<i64> {
    let (neg, digits) = match w {
        [b'-', rest @ ..] => (true, rest),
        [b'+', rest @ ..] => (false, rest),
        _ => (false, w),
    };
    if digits.is_empty() || digits.len() > 18 {
        return None;
    }
    let mut v = 0i64;
    for &d in digits {
        if !d.is_ascii_digit() {
            return None;
        }
        v = v * 10 + (d - b'0') as i64;
    }
    Some(if neg { -v } else { v })
}

fn lossy(w: &[u8]) -> String {
    String::from_utf8_lossy(w).into_owned()
}

fn not_number(keyword: &str, w: &[u8]) -> String {
    format!("`{keyword}`: {:?} is not a number", lossy(w))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn load_str(src: &str) -> Result<Loaded> {
        parse(src.as_bytes(), "t.obj", Path::new("."))
    }

    #[test]
    fn the_fast_path_parses_as_fast_float_does() {
        let mut x = 0x1234_5678u32;
        for _ in 0..100_000 {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            let digits = x % 10_000_000;
            let decimals = (x >> 24) % 11;
            let s = if decimals == 0 {
                format!("{digits}")
            } else {
                let t = format!("{digits:0>width$}", width = decimals as usize + 1);
                format!(
                    "-{}.{}",
                    &t[..t.len() - decimals as usize],
                    &t[t.len() - decimals as usize..]
                )
            };
            assert_eq!(
                number(s.as_bytes()),
                fast_float2::parse::<f32, _>(&s).ok(),
                "{s}"
            );
        }
        for s in [
            "0", "-0.0", "1.", ".5", "0.008366", "12345678", "1e5", "nan", "-inf", "1.5.2", "-",
            ".",
        ] {
            assert_eq!(
                number(s.as_bytes()).map(f32::to_bits),
                fast_float2::parse::<f32, _>(s).ok().map(f32::to_bits),
                "{s}"
            );
        }
    }

    #[test]
    fn quads_and_polygons_are_triangulated() {
        let m = load_str("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n").unwrap();
        assert_eq!(m.geometry.faces.len(), 2);
        assert!(m.geometry.materials.is_empty());
        assert!(
            m.geometry
                .normals
                .iter()
                .all(|n| (*n - Vec3::Z).length() < 1e-6)
        );
    }

    #[test]
    fn errors_name_the_line_and_column() {
        let e = |s: &str| load_str(s).unwrap_err().to_string();
        assert_eq!(
            e("v 0 0 0\nv 1 zero 0\n"),
            "t.obj:2:5: `v`: \"zero\" is not a number"
        );
        assert_eq!(
            e("v 0 0 0\nv 1 0 0\nf 1 2\n"),
            "t.obj:3:1: a face needs at least 3 vertices, found 2"
        );
        assert_eq!(
            e("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"),
            "t.obj:4:7: face vertex index 4 is out of range (1 to 3 so far)"
        );
        assert_eq!(
            e("mtllib missing.mtl\nv 0 0 0\n"),
            "t.obj:1:8: material library \"missing.mtl\" not found"
        );
        assert_eq!(e(""), "t.obj:1:1: no faces in the file");
        assert_eq!(e("v 0 0 0\n"), "t.obj:1:1: no faces in the file");
    }
}
