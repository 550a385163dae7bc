//! STL, binary and ASCII, read with `stl_io` (which merges the corners that
//! share a position, so the mesh is indexed and its normals smooth).
//!
//! stl_io's errors carry no line number; for ASCII files the facet where
//! reading stopped is found by reading the facets one by one, and its line
//! is reported.

use std::io::Cursor;
use std::path::Path;

use glam::Vec3;

use super::mesh::Mesh;
use crate::color::Rgb;
use crate::error::{Error, Result};

/// Loads an STL file; every face gets `color`.
pub fn load(path: &Path, color: Rgb) -> Result<Mesh> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    parse(&bytes, &path.display().to_string(), color)
}

/// Parses STL bytes, binary or ASCII; `name` is used in messages.
pub fn parse(bytes: &[u8], name: &str, color: Rgb) -> Result<Mesh> {
    let name = name.to_string();
    if bytes.is_empty() {
        return Err(Error::Parse {
            path: name,
            line: 1,
            column: 1,
            message: "empty file".into(),
        });
    }
    let mesh = stl_io::read_stl(&mut Cursor::new(bytes)).map_err(|e| locate(&name, bytes, e))?;
    let positions: Vec<Vec3> = mesh.vertices.iter().map(|v| Vec3::from(v.0)).collect();
    let faces: Vec<[u32; 3]> = mesh
        .faces
        .iter()
        .map(|f| f.vertices.map(|i| i as u32))
        .collect();
    if faces.is_empty() {
        return Err(Error::Parse {
            path: name,
            line: 1,
            column: 1,
            message: "no facets in the file".into(),
        });
    }
    Ok(Mesh::new(name, positions, faces, color))
}

/// An stl_io error, with the line of the failing facet for ASCII files.
fn locate(name: &str, bytes: &[u8], e: std::io::Error) -> Error {
    let ascii = bytes.starts_with(b"solid") && std::str::from_utf8(bytes).is_ok();
    let message = match e.kind() {
        std::io::ErrorKind::UnexpectedEof => {
            "the file ends in the middle of a facet (truncated?)".to_string()
        }
        _ => e.to_string(),
    };
    if !ascii {
        return Error::Parse {
            path: name.into(),
            line: 1,
            column: 1,
            message: format!("binary STL: {message}"),
        };
    }
    // Count the facets read before the error, then find that facet's line.
    let good = stl_io::create_stl_reader(&mut Cursor::new(bytes))
        .map(|it| it.take_while(|t| t.is_ok()).count())
        .unwrap_or(0);
    let text = std::str::from_utf8(bytes).unwrap_or("");
    let facet = text
        .match_indices("facet")
        .filter(|(i, _)| !text[..*i].ends_with("end"))
        .nth(good)
        .map_or(0, |(i, _)| i);
    // Within the facet, the first line with a number that does not parse.
    let mut offset = facet;
    for line in text[facet..].split_inclusive('\n') {
        let words: Vec<&str> = line.split_whitespace().collect();
        let numbers = match words.as_slice() {
            ["vertex", rest @ ..] | ["facet", "normal", rest @ ..] => rest,
            _ => &[],
        };
        if numbers
            .iter()
            .any(|w| w.parse::<f32>().map_or(true, |v| !v.is_finite()))
        {
            return Error::parse_at(name, text, offset, format!("{message}: {:?}", line.trim()));
        }
        if words.first() == Some(&"endfacet") {
            break;
        }
        offset += line.len();
    }
    Error::parse_at(name, text, facet, message)
}
