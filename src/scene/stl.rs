//! STL, binary and ASCII, read in one pass.
//!
//! **Which kind.** A binary file is an 80-byte header, a facet count and 50
//! bytes a facet, so its size says what it is: a file of exactly `84 + 50·n`
//! bytes, `n` its count, is binary even when its header starts with
//! `solid` (many exporters write that); anything else that starts with
//! `solid` (in any case: some exporters write `SOLID`, and their keywords
//! in capitals) is ASCII. The size is checked before the facets are read, so a
//! truncated file is an error at once and a facet count is never trusted as
//! an allocation.
//!
//! **Welding.** An STL facet lists its three corners by position; corners
//! at the same position become one vertex (a hash of the position's bits),
//! so the mesh is indexed, closed where the model is, and smooth where its
//! faces meet at less than the crease angle.
//!
//! ASCII errors name the line and column; the name after `solid` is
//! optional, and facet normals are read and checked but not used (they are
//! recomputed from the corners, which is what the winding says anyway).

use std::io::Read;
use std::path::Path;

use glam::Vec3;

use super::LoadOptions;
use super::file;
use super::lines::{self, Cursor, Lines};
use super::mesh::Geometry;
use super::obj::Loaded;
use super::topology::PositionSet;
use crate::error::{Error, Result};

/// Loads an STL file.
pub fn load(path: &Path, options: &LoadOptions) -> Result<Loaded> {
    Loaded::with_files(options.max_bytes, |files| load_in(path, options, files))
}

/// [`load`], the file opened through `files`.
pub(crate) fn load_in(path: &Path, options: &LoadOptions, files: &file::Files) -> Result<Loaded> {
    let mut file = files.open(path)?;
    let size = file.size();
    let name = path.display().to_string();
    let mut head = [0u8; 84];
    let n = read_up_to(&mut file, &mut head).map_err(|e| Error::io(path, e))?;
    read(&head[..n], file, size, &name, options.crease)
}

/// Parses STL bytes, binary or ASCII; `name` is used in messages.
pub fn parse(bytes: &[u8], name: &str) -> Result<Loaded> {
    let n = bytes.len().min(84);
    let crease = LoadOptions::default().crease;
    read(&bytes[..n], &bytes[n..], bytes.len() as u64, name, crease)
}

fn read_up_to(r: &mut impl Read, buf: &mut [u8]) -> std::io::Result<usize> {
    let mut n = 0;
    while n < buf.len() {
        match r.read(&mut buf[n..])? {
            0 => break,
            k => n += k,
        }
    }
    Ok(n)
}

fn error(name: &str, line: usize, column: usize, message: impl Into<String>) -> Error {
    Error::Parse {
        path: name.to_string(),
        line,
        column,
        message: message.into(),
    }
}

/// `head` is the file's first 84 bytes (or all of it), `rest` the others.
fn read(head: &[u8], rest: impl Read, size: u64, name: &str, crease: f32) -> Result<Loaded> {
    if size == 0 {
        return Err(error(name, 1, 1, "empty file"));
    }
    let count =
        (head.len() == 84).then(|| u32::from_le_bytes([head[80], head[81], head[82], head[83]]));
    let binary_size = count.map(|c| 84 + 50 * c as u64);
    let solid = head
        .get(..5)
        .is_some_and(|h| h.eq_ignore_ascii_case(b"solid"));
    if binary_size == Some(size) || !solid {
        return binary(head, rest, size, name, count).and_then(|w| w.finish(name, crease));
    }
    ascii(head.chain(rest), name).and_then(|w| w.finish(name, crease))
}

/// Corners welded by position into an indexed mesh.
struct Welder {
    positions: Vec<Vec3>,
    set: PositionSet,
    faces: Vec<[u32; 3]>,
    /// Facets dropped for a corner that is not a finite number.
    dropped: usize,
}

impl Welder {
    fn new() -> Welder {
        Welder {
            positions: Vec::new(),
            set: PositionSet::with_capacity(0),
            faces: Vec::new(),
            dropped: 0,
        }
    }

    fn facet(&mut self, corners: [Vec3; 3]) {
        let f = corners.map(|p| {
            let next = self.positions.len() as u32;
            let positions = &self.positions;
            let (id, new) = self.set.get_or_insert(p, next, |i| positions[i as usize]);
            if new {
                self.positions.push(p);
            }
            id
        });
        self.faces.push(f);
    }

    fn finish(self, name: &str, crease: f32) -> Result<Loaded> {
        let dropped = self.dropped;
        if self.faces.is_empty() {
            let why = if dropped > 0 {
                "no facet left: every facet has a corner that is not a finite number"
            } else {
                "no facets in the file"
            };
            return Err(error(name, 1, 1, why));
        }
        let notes = if dropped > 0 {
            vec![format!(
                "{name}: {dropped} facets have a corner that is not a finite number and are not drawn"
            )]
        } else {
            Vec::new()
        };
        let mut geometry = Geometry::new_raw(name, self.positions, self.faces);
        geometry.compute_normals(crease);
        Ok(Loaded { geometry, notes })
    }
}

fn binary(
    head: &[u8],
    mut rest: impl Read,
    size: u64,
    name: &str,
    count: Option<u32>,
) -> Result<Welder> {
    let Some(count) = count else {
        return Err(error(
            name,
            1,
            1,
            "binary STL: the file ends in its 84-byte header (truncated?)",
        ));
    };
    let want = 84 + 50 * count as u64;
    if size != want {
        return Err(error(
            name,
            1,
            1,
            format!(
                "binary STL: its header says {count} facets ({want} bytes), but the file has {size} bytes (truncated?)"
            ),
        ));
    }
    debug_assert_eq!(head.len(), 84);
    let mut w = Welder::new();
    let mut buf = vec![0u8; 50 * 1024];
    let mut left = count as usize;
    while left > 0 {
        let k = left.min(1024);
        rest.read_exact(&mut buf[..50 * k])
            .map_err(|e| error(name, 1, 1, format!("binary STL: {e}")))?;
        for facet in buf[..50 * k].chunks_exact(50) {
            let f =
                |o: usize| f32::from_le_bytes([facet[o], facet[o + 1], facet[o + 2], facet[o + 3]]);
            let corner = |k: usize| Vec3::new(f(12 + 12 * k), f(16 + 12 * k), f(20 + 12 * k));
            let corners = [corner(0), corner(1), corner(2)];
            if corners.iter().all(|p| p.is_finite()) {
                w.facet(corners);
            } else {
                w.dropped += 1;
            }
        }
        left -= k;
    }
    Ok(w)
}

/// `word` in lower case, in `buf`, if it is no longer than a keyword
/// (some exporters write `SOLID`, `FACET NORMAL`); else `word` as it is.
fn lower<'a>(word: &'a [u8], buf: &'a mut [u8; 8]) -> &'a [u8] {
    match buf.get_mut(..word.len()) {
        Some(b) => {
            b.copy_from_slice(word);
            b.make_ascii_lowercase();
            b
        }
        None => word,
    }
}

/// What the ASCII reader expects next.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Want {
    Solid,
    Facet,
    OuterLoop,
    Vertex(usize),
    EndLoop,
    EndFacet,
    Done,
}

fn ascii(src: impl Read, name: &str) -> Result<Welder> {
    let mut lines = Lines::new(src);
    let mut w = Welder::new();
    let mut want = Want::Solid;
    let mut corners = [Vec3::ZERO; 3];
    loop {
        let (n, line) = match lines.next_line() {
            Ok(Some(next)) => next,
            Ok(None) => break,
            Err((n, e)) => return Err(error(name, n, 1, e)),
        };
        let mut words = Cursor::new(line);
        let Some((keyword, kcol)) = words.word() else {
            continue;
        };
        let (written, mut buf) = (keyword, [0; 8]);
        let keyword = lower(keyword, &mut buf);
        let at = |offset: usize, msg: String| error(name, n, lines::column(line, offset), msg);
        let numbers = |words: &mut Cursor, what: &str| -> Result<Vec3> {
            let mut v = [0.0f32; 3];
            for (k, slot) in v.iter_mut().enumerate() {
                *slot = match words.number() {
                    None => return Err(at(kcol, format!("`{what}` needs 3 numbers, found {k}"))),
                    Some(Ok(x)) => x,
                    Some(Err((word, col))) => {
                        return Err(at(
                            col,
                            format!(
                                "`{what}`: {:?} is not a number",
                                String::from_utf8_lossy(word)
                            ),
                        ));
                    }
                };
            }
            Ok(Vec3::from(v))
        };
        want = match (want, keyword) {
            (Want::Solid, b"solid") => Want::Facet,
            (Want::Facet, b"facet") => {
                match words
                    .word()
                    .map(|(w, col)| (w.eq_ignore_ascii_case(b"normal"), col))
                {
                    Some((true, _)) => {
                        numbers(&mut words, "facet normal")?;
                    }
                    other => {
                        return Err(at(
                            other.map_or(kcol, |o| o.1),
                            "expected `facet normal nx ny nz`".into(),
                        ));
                    }
                }
                Want::OuterLoop
            }
            (Want::Facet, b"endsolid") => Want::Done,
            (Want::OuterLoop, b"outer") => {
                if !words
                    .word()
                    .is_some_and(|(w, _)| w.eq_ignore_ascii_case(b"loop"))
                {
                    return Err(at(kcol, "expected `outer loop`".into()));
                }
                Want::Vertex(0)
            }
            (Want::Vertex(k), b"vertex") => {
                corners[k] = numbers(&mut words, "vertex")?;
                if k == 2 {
                    Want::EndLoop
                } else {
                    Want::Vertex(k + 1)
                }
            }
            (Want::EndLoop, b"endloop") => Want::EndFacet,
            (Want::EndFacet, b"endfacet") => {
                if corners.iter().all(|p| p.is_finite()) {
                    w.facet(corners);
                } else {
                    w.dropped += 1;
                }
                Want::Facet
            }
            (Want::Done, _) => {
                // A second solid in the same file.
                if keyword == b"solid" {
                    Want::Facet
                } else {
                    Want::Done
                }
            }
            (want, _) => {
                let expected = match want {
                    Want::Solid => "`solid`",
                    Want::Facet => "`facet` or `endsolid`",
                    Want::OuterLoop => "`outer loop`",
                    Want::Vertex(_) => "`vertex`",
                    Want::EndLoop => "`endloop`",
                    Want::EndFacet => "`endfacet`",
                    Want::Done => unreachable!(),
                };
                return Err(at(
                    kcol,
                    format!(
                        "expected {expected}, found {:?}",
                        String::from_utf8_lossy(written)
                    ),
                ));
            }
        };
    }
    if !matches!(want, Want::Facet | Want::Done) {
        return Err(error(
            name,
            lines.number.max(1),
            1,
            "the file ends in the middle of a facet (truncated?)",
        ));
    }
    Ok(w)
}

#[cfg(test)]
mod tests {
    use super::*;

    const FACET: &str = "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";

    #[test]
    fn ascii_keywords_in_capitals_are_read() {
        let src = format!("SOLID T\n{}ENDSOLID T\n", FACET.to_uppercase());
        let m = parse(src.as_bytes(), "t.stl").unwrap();
        assert_eq!(m.geometry.faces.len(), 1);
        let src = format!("Solid t\n{FACET}Bogus\n");
        let e = parse(src.as_bytes(), "t.stl").unwrap_err().to_string();
        assert_eq!(
            e,
            "t.stl:9:1: expected `facet` or `endsolid`, found \"Bogus\""
        );
    }

    #[test]
    fn ascii_with_or_without_a_name_and_binary_starting_with_solid() {
        for head in ["solid\n", "solid cube\n", "solid  \n"] {
            let src = format!("{head}{FACET}endsolid\n");
            let m = parse(src.as_bytes(), "t.stl").unwrap();
            assert_eq!(m.geometry.faces.len(), 1);
        }
        // A binary file whose header starts with "solid".
        let mut bin = b"solid from an exporter that writes that".to_vec();
        bin.resize(80, b' ');
        bin.extend(1u32.to_le_bytes());
        for v in [
            0.0f32, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0,
        ] {
            bin.extend(v.to_le_bytes());
        }
        bin.extend([0, 0]);
        let m = parse(&bin, "t.stl").unwrap();
        assert_eq!(m.geometry.faces.len(), 1);
    }

    #[test]
    fn errors_name_line_and_column() {
        let e = |s: &str| parse(s.as_bytes(), "t.stl").unwrap_err().to_string();
        assert_eq!(
            e("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 zero 0\n"),
            "t.stl:4:10: `vertex`: \"zero\" is not a number"
        );
        assert_eq!(
            e("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"),
            "t.stl:4:1: the file ends in the middle of a facet (truncated?)"
        );
        let mut bin = vec![0u8; 80];
        bin.extend(1000u32.to_le_bytes());
        assert!(
            parse(&bin, "t.stl")
                .unwrap_err()
                .to_string()
                .contains("its header says 1000 facets (50084 bytes), but the file has 84 bytes")
        );
    }
}
