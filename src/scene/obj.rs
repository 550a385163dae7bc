//! Wavefront OBJ, read with `tobj`, materials' diffuse colours (`Kd`) from
//! the MTL files it names.
//!
//! tobj parses; this module checks. tobj's errors carry no line number, and
//! it accepts faces of fewer than three vertices, so a light line-by-line
//! pass first finds what a user needs to be told and where: a number that
//! does not parse, a face of fewer than three vertices, an index out of
//! range, a material library that is missing. Faces of more than three
//! vertices are triangulated here by ear clipping (tobj's own
//! triangulation is a fan, wrong for non-convex polygons).

use std::path::Path;

use glam::Vec3;

use super::mesh::{Mesh, triangulate, vertex_normals};
use crate::color::Rgb;
use crate::error::{Error, Result};
use crate::raster::Cull;

/// Loads an OBJ file into one mesh; faces without a material get `color`.
pub fn load(path: &Path, color: Rgb) -> Result<Mesh> {
    let src = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    parse(
        &src,
        &path.display().to_string(),
        path.parent().unwrap_or(Path::new(".")),
        color,
    )
}

/// Parses OBJ bytes; `name` is used in messages, material libraries are
/// looked for in `dir`.
pub fn parse(src: &[u8], name: &str, dir: &Path, color: Rgb) -> Result<Mesh> {
    let name = name.to_string();
    let text = String::from_utf8_lossy(src);
    check(&text, &name, dir)?;

    let opts = tobj::LoadOptions {
        single_index: true,
        triangulate: false,
        ignore_points: true,
        ignore_lines: true,
    };
    let dir = dir.to_path_buf();
    let (models, materials) = tobj::load_obj_buf(&mut text.as_bytes(), &opts, |mtl| {
        tobj::load_mtl(dir.join(mtl))
    })
    .map_err(|e| Error::parse_at(&name, &text, 0, e.to_string()))?;
    let materials = materials.map_err(|e| {
        Error::parse_at(
            &name,
            &text,
            mtllib_offset(&text),
            format!("material library: {e}"),
        )
    })?;

    let mut positions = Vec::new();
    let mut normals = Vec::new();
    let mut colors: Vec<Rgb> = Vec::new();
    let mut faces = Vec::new();
    let mut face_colors = Vec::new();
    let mut any_normals = true;
    let mut any_colors = true;
    for model in &models {
        let m = &model.mesh;
        let base = positions.len() as u32;
        positions.extend(
            m.positions
                .chunks_exact(3)
                .map(|p| Vec3::new(p[0], p[1], p[2])),
        );
        any_normals &= m.normals.len() == m.positions.len();
        normals.extend(
            m.normals
                .chunks_exact(3)
                .map(|n| Vec3::new(n[0], n[1], n[2]).normalize_or_zero()),
        );
        any_colors &= m.vertex_color.len() == m.positions.len();
        colors.extend(
            m.vertex_color
                .chunks_exact(3)
                .map(|c| Rgb::from_f32([c[0] * 255.0, c[1] * 255.0, c[2] * 255.0])),
        );
        let material = m.material_id.and_then(|id| materials.get(id));
        if let Some(kd) = material
            .and_then(|mat| mat.diffuse)
            .filter(|kd| kd.iter().any(|v| !v.is_finite()))
        {
            let mat = material.map_or("", |m| m.name.as_str());
            return Err(Error::parse_at(
                &name,
                &text,
                mtllib_offset(&text),
                format!("material {mat:?}: Kd {kd:?} is not a colour"),
            ));
        }
        if m.vertex_color.iter().any(|v| !v.is_finite()) {
            return Err(Error::parse_at(
                &name,
                &text,
                0,
                "a vertex colour is not a finite number",
            ));
        }
        let face_color = material
            .and_then(|mat| mat.diffuse)
            .map_or(color, |kd| Rgb::from_f32(kd.map(|v| v * 255.0)));
        let before = faces.len();
        if m.face_arities.is_empty() {
            faces.extend(
                m.indices
                    .chunks_exact(3)
                    .map(|f| [f[0] + base, f[1] + base, f[2] + base]),
            );
        } else {
            let mut next = 0usize;
            let mut polygon = Vec::new();
            for &arity in &m.face_arities {
                let idx = &m.indices[next..next + arity as usize];
                next += arity as usize;
                polygon.clear();
                polygon.extend(idx.iter().map(|&i| i + base));
                triangulate(&positions, &polygon, &mut faces);
            }
        }
        face_colors.resize(faces.len(), face_color);
        debug_assert!(faces.len() >= before);
    }
    if faces.is_empty() {
        return Err(Error::parse_at(
            &name,
            &text,
            text.len(),
            "no faces in the file",
        ));
    }
    let normals = if any_normals
        && normals.len() == positions.len()
        && normals.iter().all(|n| *n != Vec3::ZERO)
    {
        normals
    } else {
        vertex_normals(&positions, &faces)
    };
    let mut mesh = Mesh {
        name,
        positions,
        normals,
        colors: (any_colors && !colors.is_empty()).then_some(colors),
        faces,
        face_colors,
        model: glam::Mat4::IDENTITY,
        cull: Cull::Back,
        shape: Default::default(),
    };
    mesh.analyze();
    Ok(mesh)
}

/// The byte offset of the first `mtllib` statement.
fn mtllib_offset(text: &str) -> usize {
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        if line.trim_start().starts_with("mtllib") {
            return offset + (line.len() - line.trim_start().len());
        }
        offset += line.len();
    }
    0
}

/// The line-by-line check (see the module doc).
fn check(text: &str, name: &str, dir: &Path) -> Result<()> {
    let mut counts = [0i64; 3]; // v, vt, vn seen so far
    let mut offset = 0usize;
    for line in text.split_inclusive('\n') {
        let here = offset;
        offset += line.len();
        let body = line.split('#').next().unwrap_or("").trim();
        let mut words = body.split_whitespace();
        let Some(keyword) = words.next() else {
            continue;
        };
        let err = |msg: String| Err(Error::parse_at(name, text, here, msg));
        match keyword {
            "v" | "vt" | "vn" => {
                let need = if keyword == "vt" { 1 } else { 3 };
                let nums: Vec<&str> = words.collect();
                if nums.len() < need {
                    return err(format!(
                        "`{keyword}` needs {need} numbers, found {}",
                        nums.len()
                    ));
                }
                if let Some(bad) = nums.iter().find(|w| w.parse::<f32>().is_err()) {
                    return err(format!("`{keyword}`: {bad:?} is not a number"));
                }
                counts[match keyword {
                    "v" => 0,
                    "vt" => 1,
                    _ => 2,
                }] += 1;
            }
            "f" => {
                let refs: Vec<&str> = words.collect();
                if refs.len() < 3 {
                    return err(format!(
                        "a face needs at least 3 vertices, found {}",
                        refs.len()
                    ));
                }
                for r in refs {
                    for (k, part) in r.split('/').enumerate().take(3) {
                        if part.is_empty() && k > 0 {
                            continue;
                        }
                        let Ok(i) = part.parse::<i64>() else {
                            return err(format!("face vertex {r:?} is not an index"));
                        };
                        let n = counts[k];
                        if i == 0 || i > n || i < -n {
                            let what = ["vertex", "texture coordinate", "normal"][k];
                            return err(format!(
                                "face {what} index {i} is out of range (1 to {n} so far)"
                            ));
                        }
                    }
                }
            }
            "mtllib" => {
                let file: Vec<&str> = words.collect();
                let file = file.join(" ");
                if !dir.join(&file).is_file() {
                    return err(format!("material library {file:?} not found"));
                }
            }
            _ => {}
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn load_str(src: &str) -> Result<Mesh> {
        let dir = std::env::temp_dir().join(format!("rastty-obj-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(format!("t{}.obj", src.len()));
        std::fs::write(&path, src).unwrap();
        let r = load(&path, Rgb::WHITE);
        std::fs::remove_file(&path).ok();
        r
    }

    #[test]
    fn quads_and_polygons_are_triangulated() {
        let m = load_str("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n").unwrap();
        assert_eq!(m.faces.len(), 2);
        assert_eq!(m.face_colors, vec![Rgb::WHITE; 2]);
        assert!(m.normals.iter().all(|n| (*n - Vec3::Z).length() < 1e-6));
    }

    #[test]
    fn errors_name_the_line() {
        let e = |s: &str| load_str(s).unwrap_err().to_string();
        assert!(
            e("v 0 0 0\nv 1 zero 0\n").contains(":2:1: `v`: \"zero\" is not a number"),
            "{}",
            e("v 0 0 0\nv 1 zero 0\n")
        );
        assert!(
            e("v 0 0 0\nv 1 0 0\nf 1 2\n")
                .contains(":3:1: a face needs at least 3 vertices, found 2")
        );
        assert!(
            e("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n")
                .contains(":4:1: face vertex index 4 is out of range (1 to 3 so far)")
        );
        assert!(
            e("mtllib missing.mtl\nv 0 0 0\n")
                .contains(":1:1: material library \"missing.mtl\" not found")
        );
        assert!(e("").contains("no faces"));
        assert!(e("v 0 0 0\n").contains("no faces"));
    }
}
