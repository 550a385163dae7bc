//! glTF 2.0 and GLB models, through the `gltf` crate.
//!
//! The default scene (else the first) is walked from its roots, each node's
//! transform (matrix or TRS) composed down the tree, and every mesh
//! primitive drawn as triangles is put in world space into one
//! [`Geometry`]: triangle lists, strips and fans (turned into triangles,
//! the strip's alternate ones rewound), with or without indices. A node
//! whose transform mirrors (negative determinant) has its triangles
//! rewound, so that counter-clockwise is the front everywhere, as the
//! format says. Read: `POSITION`, `NORMAL` (when every primitive has them;
//! otherwise normals are computed as for OBJ), `COLOR_0`, and the
//! material's `baseColorFactor` (glTF colours are linear light already).
//! Buffers come from the GLB's binary chunk, data URIs, or files beside the
//! `.gltf`.
//!
//! Not read, and said in one note: points and lines, textures, skins,
//! morph targets, animations, cameras, and extensions. An extension the file
//! marks as required is an error, since the model cannot be drawn right
//! without it.
//!
//! Trade-offs: the crate parses and validates the JSON and resolves
//! buffers; the byte ranges of the accessors used are checked here before
//! anything is read, so a file whose accessors point past their buffers is
//! refused with the accessor named, never read out of bounds.

use std::collections::BTreeMap;
use std::io::Read as _;
use std::path::Path;

use ::gltf::accessor::{DataType, Dimensions};
use ::gltf::buffer::Data;
use ::gltf::mesh::Mode;
use ::gltf::{Accessor, Gltf, Semantic};
use glam::{Mat3, Mat4, Vec3};

use super::LoadOptions;
use super::file;
use super::mesh::{Geometry, MaterialRun};
use super::obj::Loaded;
use crate::color::Lin;
use crate::error::{Error, Result};

/// The deepest node hierarchy walked (the format has no cycles; a broken
/// file might).
const MAX_DEPTH: usize = 256;

/// Loads a `.gltf` (with the files it names, beside it) or `.glb` file.
pub fn load(path: &Path, options: &LoadOptions) -> Result<Loaded> {
    let (mut file, size) = file::open(path, options.max_bytes)?;
    let mut bytes = Vec::with_capacity(size as usize);
    file.read_to_end(&mut bytes)
        .map_err(|e| Error::io(path, e))?;
    parse(&bytes, path.parent(), &path.display().to_string(), options)
}

/// Parses glTF or GLB bytes; files it names are looked for in `base`;
/// `name` is used in messages.
pub fn parse(
    bytes: &[u8],
    base: Option<&Path>,
    name: &str,
    options: &LoadOptions,
) -> Result<Loaded> {
    let bad = |what: String| Error::Invalid(format!("{name}: {what}"));
    let gltf = Gltf::from_slice(bytes).map_err(|e| bad(describe(&e)))?;
    let required: Vec<&str> = gltf.extensions_required().collect();
    if !required.is_empty() {
        return Err(bad(format!(
            "needs the extension{} {}, which rastty does not read",
            if required.len() > 1 { "s" } else { "" },
            required.join(", ")
        )));
    }
    let Gltf { document, blob } = gltf;
    // Files it names, checked first so that the one missing is named.
    for b in document.buffers() {
        if let ::gltf::buffer::Source::Uri(uri) = b.source()
            && !uri.starts_with("data:")
        {
            let file = base.unwrap_or(Path::new(".")).join(uri);
            if let Err(e) = std::fs::metadata(&file) {
                return Err(bad(format!(
                    "buffer {}: {}: {e}",
                    b.index(),
                    file.display()
                )));
            }
        }
    }
    let buffers = ::gltf::import_buffers(&document, base, blob).map_err(|e| bad(describe(&e)))?;

    let mut ignored: BTreeMap<&str, usize> = BTreeMap::new();
    let mut out = Parts::default();
    let scene = document
        .default_scene()
        .or_else(|| document.scenes().next())
        .ok_or_else(|| bad("no scene to draw".into()))?;
    let mut stack: Vec<(::gltf::Node, Mat4, usize)> =
        scene.nodes().map(|n| (n, Mat4::IDENTITY, 0)).collect();
    while let Some((node, parent, depth)) = stack.pop() {
        if depth > MAX_DEPTH {
            return Err(bad(format!(
                "node {} is more than {MAX_DEPTH} levels deep (a cycle?)",
                node.index()
            )));
        }
        let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
        if node.skin().is_some() {
            *ignored.entry("skins").or_default() += 1;
        }
        if node.camera().is_some() {
            *ignored.entry("cameras").or_default() += 1;
        }
        if let Some(mesh) = node.mesh() {
            for prim in mesh.primitives() {
                out.primitive(&prim, world, &buffers, &mut ignored)
                    .map_err(|e| {
                        bad(format!(
                            "mesh {} primitive {}: {e}",
                            mesh.index(),
                            prim.index()
                        ))
                    })?;
            }
        }
        stack.extend(node.children().map(|c| (c, world, depth + 1)));
    }
    let animations = document.animations().count();
    if animations > 0 {
        ignored.insert("animations", animations);
    }
    let mut notes = Vec::new();
    let mut what: Vec<String> = ignored.iter().map(|(k, n)| format!("{n} {k}")).collect();
    what.extend(document.extensions_used().map(|e| format!("extension {e}")));
    if !what.is_empty() {
        notes.push(format!("{name}: not drawn: {}", what.join(", ")));
    }
    if out.faces.is_empty() {
        return Err(bad("no triangles to draw".into()));
    }
    Ok(Loaded {
        geometry: out.geometry(name, options.crease),
        notes,
    })
}

/// A `gltf` error in words (its own, with the JSON path for validation).
fn describe(e: &::gltf::Error) -> String {
    match e {
        ::gltf::Error::Validation(errors) => errors
            .iter()
            .map(|(path, err)| format!("{path}: {err}"))
            .collect::<Vec<_>>()
            .join("; "),
        other => other.to_string(),
    }
}

/// The primitives gathered so far, in world space.
#[derive(Default)]
struct Parts {
    positions: Vec<Vec3>,
    /// Normals, while every primitive so far has them.
    normals: Vec<Vec3>,
    normals_missing: bool,
    /// Per-vertex colours, once a primitive has them; earlier vertices get
    /// their material's colour.
    colors: Option<Vec<Lin>>,
    /// Each vertex's material colour (white without a material), for
    /// vertices of primitives without `COLOR_0` once colours exist.
    base: Vec<Lin>,
    faces: Vec<[u32; 3]>,
    materials: Vec<MaterialRun>,
}

impl Parts {
    fn primitive(
        &mut self,
        prim: &::gltf::Primitive,
        world: Mat4,
        buffers: &[Data],
        ignored: &mut BTreeMap<&'static str, usize>,
    ) -> std::result::Result<(), String> {
        let mode = prim.mode();
        if matches!(
            mode,
            Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip
        ) {
            *ignored.entry("point and line primitives").or_default() += 1;
            return Ok(());
        }
        if prim.morph_targets().next().is_some() {
            *ignored.entry("morph targets").or_default() += 1;
        }
        let material = prim.material();
        if material
            .pbr_metallic_roughness()
            .base_color_texture()
            .is_some()
        {
            *ignored.entry("textures").or_default() += 1;
        }
        let positions = prim.get(&Semantic::Positions).ok_or("it has no POSITION")?;
        check(
            &positions,
            buffers,
            &[DataType::F32],
            &[Dimensions::Vec3],
            "POSITION",
        )?;
        let normals = prim.get(&Semantic::Normals);
        if let Some(n) = &normals {
            check(n, buffers, &[DataType::F32], &[Dimensions::Vec3], "NORMAL")?;
            if n.count() != positions.count() {
                return Err(format!(
                    "NORMAL has {} entries for {} positions",
                    n.count(),
                    positions.count()
                ));
            }
        }
        let colors = prim.get(&Semantic::Colors(0));
        if let Some(c) = &colors {
            check(
                c,
                buffers,
                &[DataType::F32, DataType::U8, DataType::U16],
                &[Dimensions::Vec3, Dimensions::Vec4],
                "COLOR_0",
            )?;
            if c.count() != positions.count() {
                return Err(format!(
                    "COLOR_0 has {} entries for {} positions",
                    c.count(),
                    positions.count()
                ));
            }
        }
        if let Some(i) = prim.indices() {
            check(
                &i,
                buffers,
                &[DataType::U8, DataType::U16, DataType::U32],
                &[Dimensions::Scalar],
                "the indices",
            )?;
        }
        let reader = prim.reader(|b| buffers.get(b.index()).map(|d| &d.0[..]));
        let first = self.positions.len() as u32;
        let n = positions.count();
        let start = self.positions.len();
        self.positions.extend(
            reader
                .read_positions()
                .into_iter()
                .flatten()
                .map(|p| world.transform_point3(Vec3::from(p))),
        );
        if self.positions.len() - start != n {
            return Err("POSITION could not be read".into());
        }
        // Normals: kept while every primitive has them.
        match reader.read_normals() {
            Some(ns) if !self.normals_missing => {
                let m = Mat3::from_mat4(world).inverse().transpose();
                self.normals
                    .extend(ns.map(|v| (m * Vec3::from(v)).normalize_or_zero()));
            }
            _ => self.normals_missing = true,
        }
        let factor = material.pbr_metallic_roughness().base_color_factor();
        let base = Lin::from_unit([factor[0], factor[1], factor[2]]);
        let own = material.index().is_some();
        self.base
            .extend(std::iter::repeat_n(if own { base } else { Lin::WHITE }, n));
        if let Some(cs) = reader.read_colors(0) {
            let all = self
                .colors
                .get_or_insert_with(|| self.base[..start].to_vec());
            let f = Vec3::from_slice(&factor[..3]);
            all.extend(cs.into_rgb_f32().map(|c| {
                let c = Vec3::from(c) * if own { f } else { Vec3::ONE };
                Lin::from_unit(c.to_array())
            }));
        } else if let Some(all) = &mut self.colors {
            all.extend_from_slice(&self.base[start..]);
        }

        let indices: Vec<u32> = match reader.read_indices() {
            Some(i) => i.into_u32().collect(),
            None => (0..n as u32).collect(),
        };
        if let Some(&bad) = indices.iter().find(|&&i| i as usize >= n) {
            return Err(format!("index {bad} is out of range for {n} vertices"));
        }
        let flip = world.determinant() < 0.0;
        let faces_before = self.faces.len();
        let mut push = |a: u32, b: u32, c: u32| {
            if a != b && b != c && a != c {
                let (a, b, c) = (first + a, first + b, first + c);
                self.faces.push(if flip { [a, c, b] } else { [a, b, c] });
            }
        };
        match mode {
            Mode::TriangleStrip => {
                for (k, w) in indices.windows(3).enumerate() {
                    if k % 2 == 0 {
                        push(w[0], w[1], w[2]);
                    } else {
                        push(w[1], w[0], w[2]);
                    }
                }
            }
            Mode::TriangleFan => {
                if let Some((&hub, rest)) = indices.split_first() {
                    for w in rest.windows(2) {
                        push(hub, w[0], w[1]);
                    }
                }
            }
            _ => {
                for t in indices.chunks_exact(3) {
                    push(t[0], t[1], t[2]);
                }
            }
        }
        if self.faces.len() > faces_before {
            let color = own.then_some(base);
            if self.materials.last().map(|m| m.color) != Some(color) {
                self.materials.push(MaterialRun {
                    first: faces_before as u32,
                    color,
                });
            }
        }
        Ok(())
    }

    fn geometry(self, name: &str, crease: f32) -> Geometry {
        let mut g = Geometry::new_raw(name, self.positions, self.faces);
        // Runs that are all "the mesh's colour" say nothing.
        if self.materials.iter().any(|m| m.color.is_some()) {
            g.materials = self.materials;
        }
        g.colors = self.colors;
        if !self.normals_missing && self.normals.len() == g.positions.len() {
            g.normals = self.normals;
        } else {
            g.compute_normals(crease);
        }
        g.analyze();
        g
    }
}

/// Checks that `acc` has a type the reader expects and that every byte
/// it names lies inside its buffer view and buffer.
fn check(
    acc: &Accessor,
    buffers: &[Data],
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
        return Err(format!("{} is sparse, which rastty does not read", at()));
    }
    let Some(view) = acc.view() else {
        return Err(format!("{} has no buffer view", at()));
    };
    let buffer = buffers
        .get(view.buffer().index())
        .ok_or_else(|| format!("{}: its buffer is missing", at()))?;
    let elem = acc.size();
    let stride = view.stride().unwrap_or(elem).max(elem);
    let count = acc.count();
    let need = match count {
        0 => 0,
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
    Ok(())
}
