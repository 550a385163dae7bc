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

use std::io::{BufReader, Read};
use std::path::Path;

use glam::Vec3;
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{DefaultElement, Property};

use super::LoadOptions;
use super::file;
use super::mesh::Geometry;
use super::obj::Loaded;
use super::polygon::{self, Point, Triangulator};
use crate::color::{Lin, Rgb};
use crate::error::{Error, Result};

/// Loads a PLY file.
pub fn load(path: &Path, options: &LoadOptions) -> Result<Loaded> {
    let (file, _) = file::open(path, options.max_bytes)?;
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

fn read(mut r: impl Read, name: &str, crease: f32) -> Result<Loaded> {
    let bad = |what: String| Error::Invalid(format!("{name}: {what}"));
    let ply = Parser::<DefaultElement>::new()
        .read_ply(&mut r)
        .map_err(|e| bad(e.to_string()))?;
    let mut notes = Vec::new();
    let vertices = ply
        .payload
        .get("vertex")
        .ok_or_else(|| bad("no vertex element".into()))?;
    let scalar = |e: &DefaultElement, k: &str| e.get(k).and_then(Property::to_f32_lossy);
    let mut positions = Vec::with_capacity(vertices.len());
    for (i, v) in vertices.iter().enumerate() {
        let p = [scalar(v, "x"), scalar(v, "y"), scalar(v, "z")];
        let [Some(x), Some(y), Some(z)] = p else {
            return Err(bad(format!("vertex {i} has no numeric x, y and z")));
        };
        positions.push(Vec3::new(x, y, z));
    }
    let all = |keys: [&str; 3]| {
        vertices
            .iter()
            .map(|v| {
                let [a, b, c] = keys.map(|k| v.get(k));
                Some([a?, b?, c?])
            })
            .collect::<Option<Vec<[&Property; 3]>>>()
    };
    let normals: Option<Vec<Vec3>> = all(["nx", "ny", "nz"]).and_then(|ns| {
        ns.into_iter()
            .map(|n| {
                Some(Vec3::from(
                    n.map(Property::to_f32_lossy).map(|c| c.unwrap_or(f32::NAN)),
                ))
            })
            .map(|n| n.filter(|n| n.is_finite()).map(Vec3::normalize_or_zero))
            .collect()
    });
    let colors: Option<Vec<Lin>> = all(["red", "green", "blue"]).and_then(|cs| {
        cs.into_iter()
            .map(|c| {
                let [r, g, b] = c.map(Property::to_u8_color_lossy);
                Some(Lin::from_srgb(Rgb([r?, g?, b?])))
            })
            .collect()
    });

    let faces = ply
        .payload
        .get("face")
        .ok_or_else(|| bad("no face element: a point cloud has nothing to draw".into()))?;
    let n = positions.len();
    let mut colors = colors;
    let mut triangles = Vec::with_capacity(faces.len());
    let mut cutter = Triangulator::new();
    let (mut corners, mut corner_pos, mut cut) = (Vec::new(), Vec::new(), Vec::new());
    for (f, face) in faces.iter().enumerate() {
        let list = face
            .get("vertex_indices")
            .or_else(|| face.get("vertex_index"));
        corners.clear();
        let ok = match list {
            Some(Property::ListInt(v)) => v.iter().all(|&i| push(&mut corners, i64::from(i), n)),
            Some(Property::ListUInt(v)) => v.iter().all(|&i| push(&mut corners, i64::from(i), n)),
            Some(Property::ListShort(v)) => v.iter().all(|&i| push(&mut corners, i64::from(i), n)),
            Some(Property::ListUShort(v)) => v.iter().all(|&i| push(&mut corners, i64::from(i), n)),
            Some(Property::ListChar(v)) => v.iter().all(|&i| push(&mut corners, i64::from(i), n)),
            Some(Property::ListUChar(v)) => v.iter().all(|&i| push(&mut corners, i64::from(i), n)),
            _ => {
                return Err(bad(format!(
                    "face {f} has no vertex_indices list of integers"
                )));
            }
        };
        if !ok {
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
    let others: Vec<&str> = ply
        .payload
        .keys()
        .map(String::as_str)
        .filter(|k| *k != "vertex" && *k != "face")
        .collect();
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
    Ok(Loaded { geometry: g, notes })
}

/// Pushes index `i` when it names one of `n` vertices.
fn push(corners: &mut Vec<u32>, i: i64, n: usize) -> bool {
    let ok = i >= 0 && (i as u64) < n as u64;
    if ok {
        corners.push(i as u32);
    }
    ok
}
