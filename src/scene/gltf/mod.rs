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
//! otherwise normals are computed as for OBJ), `COLOR_0`, `TEXCOORD_0`
//! (quantized or sparse too: `accessor.rs`),
//! and the material's `baseColorFactor` (glTF colours are linear light
//! already; its alpha, with `alphaMode` and `alphaCutoff`, see
//! [`crate::scene::Alpha`]) and `baseColorTexture` with its sampler (filters and wrap
//! modes; an unset filter is trilinear). Buffers and images come from the
//! GLB's binary chunk, data URIs, or files beside the `.gltf`; images are
//! PNG or JPEG, sRGB-encoded, decoded once each however many materials
//! use them (see [`crate::texture`]).
//!
//! A model that moves (skins, morph targets or animations) keeps its node
//! tree, skins, morph targets and clips in a [`crate::scene::anim::Rig`],
//! each primitive as its node places it a part of it; its geometry holds
//! the rest pose, written by the code that poses it (`rig.rs`).
//!
//! A material's normal, metallic-roughness, occlusion and emissive
//! textures are its maps ([`crate::scene::Maps`]: normal, MR and occlusion
//! images decoded as numbers, not sRGB), with the file's `TANGENT`s or
//! MikkTSpace's (`scene/tangents.rs`); `KHR_texture_transform` moves the
//! coordinates once, at load (`material.rs`).
//!
//! Line and point primitives are the geometry's lines
//! ([`Geometry::lines`], drawn one sample wide); `EXT_mesh_gpu_instancing`
//! draws a node's mesh once an instance (`instances.rs`).
//!
//! A material's textures are read through one coordinate set, its base
//! colour's (or first map's) `texCoord`, any `TEXCOORD_n`.
//!
//! Not read, and said in one note: a material's textures on another
//! coordinate set than that one, cameras, and extensions other than
//! unlit, emissive strength, punctual lights, texture transform and
//! specular-glossiness (its diffuse colour and texture, specular colour
//! and glossiness; not its specular-glossiness texture). One of
//! those others that the file marks as required is an error, since the
//! model cannot be drawn right without it.
//!
//! Trade-offs: the crate parses and validates the JSON and resolves
//! buffers; the byte ranges of the accessors used are checked here before
//! anything is read, so a file whose accessors point past their buffers is
//! refused with the accessor named, never read out of bounds.

mod accessor;
mod budget;
mod buffers;
mod draco;
mod meshopt;
mod instances;
mod document;
mod material;
mod numbers;
mod rig;

use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Arc;

use ::gltf::accessor::{DataType, Dimensions};
use ::gltf::mesh::Mode;
use ::gltf::{Accessor, Gltf, Semantic};
use buffers::Buffer;
use glam::{Mat3, Mat4, Vec2, Vec3, Vec4};
use rustc_hash::FxHashMap;

use super::LoadOptions;
use super::file::{self, FileId, Files};
use super::light::Light;
use super::mesh::{Geometry, MaterialRun};
use super::obj::Loaded;
use crate::color::Lin;
use crate::error::{Error, Result};
use crate::scene::anim::Posed;
use crate::texture::Texture;
use budget::{placed, shown};
use buffers::{buffers, check};
use document::{DRAWN_EXTENSIONS, describe, semantic_name, validated};
use material::{Decode, finish, light_of};
use rig::{Placement, RigParts, local};

/// The deepest node hierarchy walked (the format has no cycles; a broken
/// file might).
const MAX_DEPTH: usize = 256;

/// Loads a `.gltf` (with the files it names, beside it) or `.glb` file.
pub fn load(path: &Path, options: &LoadOptions) -> Result<Loaded> {
    Loaded::with_files(options.max_bytes, |files| load_in(path, options, files))
}

/// [`load`], every file opened through `files`.
pub(crate) fn load_in(path: &Path, options: &LoadOptions, files: &Files) -> Result<Loaded> {
    let bytes = files.read(path)?;
    parse_in(
        &bytes,
        path.parent(),
        &path.display().to_string(),
        options,
        files,
    )
}

/// Parses glTF or GLB bytes; files it names are looked for in `base`;
/// `name` is used in messages.
pub fn parse(
    bytes: &[u8],
    base: Option<&Path>,
    name: &str,
    options: &LoadOptions,
) -> Result<Loaded> {
    Loaded::with_files(options.max_bytes, |files| {
        parse_in(bytes, base, name, options, files)
    })
}

/// [`parse`], every file it names opened through `files`.
fn parse_in(
    bytes: &[u8],
    base: Option<&Path>,
    name: &str,
    options: &LoadOptions,
    files: &Files,
) -> Result<Loaded> {
    let bad = |what: String| Error::Invalid(format!("{name}: {what}"));
    if !bytes.starts_with(b"glTF") && !bytes.trim_ascii_start().starts_with(b"{") {
        return Err(bad(
            "not glTF: a GLB starts with `glTF` and a .gltf file is a JSON object".into(),
        ));
    }
    // The gltf crate subtracts the 12-byte header from the GLB's length
    // unchecked (a panic where overflow is checked): shorter is refused here.
    if let Some(length) = bytes.get(..12).filter(|b| b.starts_with(b"glTF")) {
        let length = u32::from_le_bytes([length[8], length[9], length[10], length[11]]);
        if length < 12 {
            return Err(bad(format!(
                "a GLB whose header gives its length as {length} bytes, less than the header's 12"
            )));
        }
    }
    let Gltf { document, blob } =
        Gltf::from_slice_without_validation(bytes).map_err(|e| bad(describe(&e)))?;
    if let Some(json) = numbers::json_of(bytes) {
        numbers::check(json).map_err(bad)?;
    }
    let root = document.into_json();
    // Those it draws may be required: only the others are refused.
    let required: Vec<&str> = (root.extensions_required.iter())
        .map(String::as_str)
        .filter(|e| !DRAWN_EXTENSIONS.contains(e))
        .collect();
    if !required.is_empty() {
        return Err(bad(format!(
            "needs the extension{} {}, which rastty does not read",
            if required.len() > 1 { "s" } else { "" },
            required.join(", ")
        )));
    }
    // What is left is read here, whether the crate knows it or not (it
    // refuses a required extension it does not know).
    let mut root = root;
    root.extensions_required.clear();
    // The crate's own validation indexes the accessor a POSITION names
    // before it checks that it exists.
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            for (semantic, index) in &prim.attributes {
                if index.value() >= root.accessors.len() {
                    return Err(bad(format!(
                        "mesh {m} primitive {p}: attribute {} names accessor {}, which does not exist",
                        crate::text::name(&semantic_name(semantic), 40),
                        index.value()
                    )));
                }
            }
        }
    }
    // Compressed views pointed at buffers of their own, decoded once the
    // buffers are read.
    let compressed = meshopt::rewrite(&mut root, options.max_bytes).map_err(bad)?;
    let document = validated(root).map_err(|e| bad(describe(&e)))?;
    let mut notes = Vec::new();
    let unread = &compressed.unread;
    let mut buffers =
        buffers(&document, blob, base, name, files, &mut notes, unread).map_err(bad)?;
    meshopt::decode(&compressed, &mut buffers).map_err(bad)?;

    let scene = document
        .default_scene()
        .or_else(|| document.scenes().next())
        .ok_or_else(|| bad("no scene to draw".into()))?;
    let (placed, triangles) = placed(&document, &scene).map_err(bad)?;
    if placed.max(triangles) > u128::from(options.max_triangles) {
        return Err(bad(format!(
            "its node tree places {} triangles in {} nodes, more than the budget of {} (--max-triangles raises it)",
            shown(triangles),
            shown(placed),
            options.max_triangles
        )));
    }

    let mut ignored: BTreeMap<&str, usize> = BTreeMap::new();
    let mut out = Parts {
        images: Images {
            base,
            owner: name,
            files: Some(files),
            texels_left: options.max_texels,
            max_side: options.max_texture_side,
            root: Some(document.as_json()),
            notes: Vec::new(),
            decoded: FxHashMap::default(),
            files_decoded: FxHashMap::default(),
        },
        budget: options.max_bytes,
        ..Parts::default()
    };
    // A model that moves keeps its nodes, skins, morph targets and clips.
    let animated = document.skins().len() > 0
        || document.animations().len() > 0
        || document
            .meshes()
            .any(|m| m.primitives().any(|p| p.morph_targets().len() > 0));
    let mut rig = animated.then(|| RigParts::new(options.max_bytes));
    // Nodes whose rotation is four zeros, drawn unrotated.
    let mut unrotated: Vec<usize> = Vec::new();
    let mut stack: Vec<(::gltf::Node, Mat4, usize, Option<u32>)> = scene
        .nodes()
        .map(|n| (n, Mat4::IDENTITY, 0, None))
        .collect();
    while let Some((node, parent, depth, rig_parent)) = stack.pop() {
        if depth > MAX_DEPTH {
            return Err(bad(format!(
                "node {} is more than {MAX_DEPTH} levels deep",
                node.index()
            )));
        }
        let world = parent * local(&node, &mut unrotated);
        let me = rig.as_mut().map(|r| r.node(&node, rig_parent));
        if node.camera().is_some() {
            *ignored.entry("cameras").or_default() += 1;
        }
        if let Some(light) = node.light() {
            if out.lights.len() == crate::scene::MAX_LIGHTS {
                *ignored.entry("lights beyond the eighth").or_default() += 1;
            } else {
                out.lights.push(light_of(&light, world).map_err(|e| {
                    bad(format!(
                        "node {}: light {}: {e}",
                        node.index(),
                        light.index()
                    ))
                })?);
            }
        }
        // Instanced (EXT_mesh_gpu_instancing): the mesh drawn once an
        // instance, each placed in the node's space; a model that moves
        // draws its first instance alone.
        let mut each = instances::of(&node, &document, &buffers, options.max_bytes)
            .map_err(|e| bad(format!("node {}: {e}", node.index())))?;
        if rig.is_some() && each.len() > 1 {
            *ignored
                .entry("instances of moving meshes past the first")
                .or_default() += each.len() - 1;
            each.truncate(1);
        }
        for instance in each.iter().filter(|_| node.mesh().is_some()) {
            let world = world * *instance;
            let Some(mesh) = node.mesh() else { continue };
            for prim in mesh.primitives() {
                let placed = match (&mut rig, me) {
                    (Some(r), Some(at)) => Some((
                        r,
                        Placement {
                            node: at,
                            skin: node.skin().map(|s| s.index()),
                        },
                    )),
                    _ => None,
                };
                out.primitive(&prim, world, &buffers, &mut ignored, placed, &document)
                    .map_err(|e| {
                        bad(format!(
                            "mesh {} primitive {}: {e}",
                            mesh.index(),
                            prim.index()
                        ))
                    })?;
            }
        }
        stack.extend(node.children().map(|c| (c, world, depth + 1, me)));
    }
    let rig = match rig {
        Some(r) => {
            let rig = r.finish(&document, &buffers, &mut notes).map_err(bad)?;
            // The rest pose, by the code that poses every frame.
            rig.pose_into(
                None,
                &mut Posed::default(),
                &mut out.positions,
                &mut out.normals,
            );
            Some(rig)
        }
        None => None,
    };
    notes.append(&mut out.images.notes);
    unrotated.sort_unstable();
    unrotated.dedup();
    if let Some(first) = unrotated.first() {
        notes.push(format!(
            "{name}: node {first}{} has a rotation of four zeros, which is no rotation: drawn unrotated",
            match unrotated.len() - 1 {
                0 => String::new(),
                k => format!(" (and {k} more)"),
            }
        ));
    }
    let mut what: Vec<String> = ignored.iter().map(|(k, n)| format!("{n} {k}")).collect();
    what.extend(
        document
            .extensions_used()
            .filter(|e| !DRAWN_EXTENSIONS.contains(e))
            .map(|e| format!("extension {}", crate::text::name(e, 80))),
    );
    if !what.is_empty() {
        notes.push(format!("{name}: not drawn: {}", what.join(", ")));
    }
    // A position that is not a finite number (in the file, or placed by a
    // node) takes its faces with it, as in OBJ files.
    let dropped =
        super::mesh::drop_unfinite_faces(&out.positions, &mut out.faces, &mut out.materials);
    notes.extend(super::mesh::unfinite_note(name, dropped));
    if out.faces.is_empty() && out.lines.is_empty() {
        return Err(bad(if dropped.1 > 0 {
            "no triangles to draw: every one has a vertex that is not a finite number".into()
        } else {
            "no triangles to draw".into()
        }));
    }
    let lights = std::mem::take(&mut out.lights);
    let mut geometry = out.geometry(name, options.crease);
    geometry.lights = lights;
    geometry.rig = rig.map(Arc::new);
    Ok(Loaded { geometry, notes })
}

/// The images of a document, decoded when a material first uses them.
#[derive(Default)]
struct Images<'a> {
    base: Option<&'a Path>,
    /// The model's name, for messages.
    owner: &'a str,
    /// Where every file is opened (always set: an option only for
    /// `Default`).
    files: Option<&'a Files>,
    /// What is left of the texel budget.
    texels_left: u64,
    /// The largest side of a texture's finest level.
    max_side: u32,
    /// The document, for what the crate's `Image::source` would panic on.
    root: Option<&'a ::gltf::json::Root>,
    /// Notes on the files read.
    notes: Vec<String>,
    /// The texture made of each glTF texture's colour (and alpha: `true`),
    /// as an index into `textures` (`None`: an image without alpha).
    decoded: FxHashMap<(usize, Decode), Option<u32>>,
    /// The same, for each image file decoded, each way and with each
    /// sampler (by its index in the document).
    files_decoded: FxHashMap<(FileId, Decode, Option<usize>), Option<u32>>,
}

/// The primitives gathered so far, in world space.
#[derive(Default)]
struct Parts<'a> {
    images: Images<'a>,
    textures: Vec<Arc<Texture>>,
    /// Texture coordinates, once a primitive has them (earlier vertices
    /// get zeros: they are not textured).
    uvs: Option<Vec<Vec2>>,
    /// The second set's, where a map reads one.
    uvs2: Option<Vec<Vec2>>,
    positions: Vec<Vec3>,
    /// Normals, while every primitive so far has them.
    normals: Vec<Vec3>,
    normals_missing: bool,
    /// Tangents (`TANGENT`), while every primitive so far has them.
    tangents: Vec<Vec4>,
    tangents_missing: bool,
    /// Per-vertex colours, once a primitive has them; earlier vertices get
    /// their material's colour.
    colors: Option<Vec<Lin>>,
    /// Each vertex's material colour (white without a material), for
    /// vertices of primitives without `COLOR_0` once colours exist.
    base: Vec<Lin>,
    faces: Vec<[u32; 3]>,
    materials: Vec<MaterialRun>,
    /// The lights its nodes place (`KHR_lights_punctual`), in the world.
    lights: Vec<Light>,
    /// Line and point primitives' lines (see [`Geometry::lines`]).
    lines: Vec<([u32; 2], Option<Lin>)>,
    /// The load's byte budget, for what no buffer bounds.
    budget: u64,
}

impl Parts<'_> {
    fn primitive(
        &mut self,
        prim: &::gltf::Primitive,
        world: Mat4,
        buffers: &[Buffer],
        ignored: &mut BTreeMap<&'static str, usize>,
        placed: Option<(&mut RigParts, Placement)>,
        document: &::gltf::Document,
    ) -> std::result::Result<(), String> {
        let mode = prim.mode();
        let lines = matches!(
            mode,
            Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip
        );
        if lines && placed.is_some() {
            *ignored
                .entry("point and line primitives of moving meshes")
                .or_default() += 1;
            return Ok(());
        }
        if prim.morph_targets().next().is_some() && placed.is_none() {
            *ignored.entry("morph targets").or_default() += 1;
        }
        let material = prim.material();
        if material.transmission().is_some() {
            *ignored
                .entry("transmissive primitives' refraction (drawn see-through)")
                .or_default() += 1;
        }
        let mut finish = finish(&material);
        let material::Sets {
            texture,
            uv_transform,
            chosen: uv_set,
            second,
        } = self.textures_of(&material, &mut finish, buffers, ignored)?;
        let wants_uvs = texture.is_some() || !finish.maps.is_empty();
        let positions = prim.get(&Semantic::Positions).ok_or("it has no POSITION")?;
        let n = positions.count();
        // A Draco stream holds the attributes it names and the indices.
        let mut draco = draco::decode(prim, document, buffers)?;
        // Each attribute as floats, whatever its components (quantized
        // too) and sparse or not; every one as long as POSITION.
        let read = |sem: Semantic, what: &str, types: &[DataType], dims: &[Dimensions]| {
            let Some(acc) = prim.get(&sem) else {
                return Ok(None);
            };
            if acc.count() != n && sem != Semantic::Positions {
                return Err(format!(
                    "{what} has {} entries for {n} positions",
                    acc.count()
                ));
            }
            if let Some((values, k)) = draco.as_ref().and_then(|d| d.get(what)) {
                if k != dims[0].multiplicity() {
                    return Err(format!("its Draco {what} has {k} components"));
                }
                return Ok(Some(values.to_vec()));
            }
            accessor::floats(&acc, buffers, types, dims, what, self.budget).map(Some)
        };
        let uv_name = format!("TEXCOORD_{uv_set}");
        let tex_coords = read(
            Semantic::TexCoords(uv_set),
            &uv_name,
            &accessor::QUANTIZED,
            &[Dimensions::Vec2],
        )?;
        if wants_uvs && tex_coords.is_none() {
            return Err(format!("it has a texture but no {uv_name}"));
        }
        let second_name = second.map(|(set, _)| format!("TEXCOORD_{set}"));
        let tex_coords2 = match &second_name {
            Some(name) => Some(
                read(
                    Semantic::TexCoords(second.map_or(0, |s| s.0)),
                    name,
                    &accessor::QUANTIZED,
                    &[Dimensions::Vec2],
                )?
                .ok_or_else(|| format!("it has a texture on {name} but no {name}"))?,
            ),
            None => None,
        };
        let file_positions = read(
            Semantic::Positions,
            "POSITION",
            &accessor::QUANTIZED,
            &[Dimensions::Vec3],
        )?
        .unwrap_or_default();
        let file_normals = read(
            Semantic::Normals,
            "NORMAL",
            &accessor::SIGNED,
            &[Dimensions::Vec3],
        )?;
        let file_tangents = read(
            Semantic::Tangents,
            "TANGENT",
            &accessor::SIGNED,
            &[Dimensions::Vec4],
        )?;
        let colors = prim.get(&Semantic::Colors(0));
        let draco_colors = draco.as_ref().and_then(|d| d.get("COLOR_0"));
        if let Some(c) = colors.as_ref().filter(|_| draco_colors.is_none()) {
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
        if let Some(i) = prim.indices().filter(|_| draco.is_none()) {
            check(
                &i,
                buffers,
                &[DataType::U8, DataType::U16, DataType::U32],
                &[Dimensions::Scalar],
                "the indices",
            )?;
        }
        let reader = prim.reader(|b| buffers.get(b.index()).map(|d| &d[..]));
        let first = self.positions.len() as u32;
        let start = self.positions.len();
        let vec3s =
            |fs: &[f32]| -> Vec<Vec3> { fs.chunks_exact(3).map(Vec3::from_slice).collect() };
        // A part of a model that moves keeps its own space's positions and
        // normals; the geometry's are its rest pose, written once the rig
        // is read.
        let local: Option<(Vec<Vec3>, Option<Vec<Vec3>>)> = placed
            .as_ref()
            .map(|_| (vec3s(&file_positions), file_normals.as_deref().map(vec3s)));
        match &local {
            Some((ps, _)) => self.positions.extend_from_slice(ps),
            None => self.positions.extend(
                file_positions
                    .chunks_exact(3)
                    .map(|p| world.transform_point3(Vec3::from_slice(p))),
            ),
        }
        if self.positions.len() - start != n {
            return Err("POSITION could not be read".into());
        }
        // Normals: kept while every primitive has them (a moving part's
        // are computed where the file gives none).
        match &file_normals {
            _ if local.is_some() => self.normals.resize(start + n, Vec3::ZERO),
            Some(ns) if !self.normals_missing => {
                let m = Mat3::from_mat4(world).inverse().transpose();
                self.normals.extend(
                    ns.chunks_exact(3)
                        .map(|v| (m * Vec3::from_slice(v)).normalize_or_zero()),
                );
            }
            _ => self.normals_missing = true,
        }
        // Tangents turn with the node (a mirroring node turns the
        // bitangent's sign with them); a moving part keeps its own.
        match file_tangents.as_deref().map(|t| t.chunks_exact(4)) {
            Some(ts) if !self.tangents_missing => {
                let m = Mat3::from_mat4(if local.is_some() {
                    Mat4::IDENTITY
                } else {
                    world
                });
                let sign = if m.determinant() < 0.0 { -1.0 } else { 1.0 };
                self.tangents.extend(ts.map(|t| {
                    let xyz = (m * Vec3::from_slice(&t[..3])).normalize_or_zero();
                    xyz.extend(if t[3] < 0.0 { -sign } else { sign })
                }));
                if self.tangents.len() != start + n {
                    return Err("TANGENT could not be read".into());
                }
            }
            _ => self.tangents_missing = true,
        }
        let factor = material::base_color(&material).0;
        let base = Lin::from_unit([factor[0], factor[1], factor[2]]);
        let own = material.index().is_some();
        self.base
            .extend(std::iter::repeat_n(if own { base } else { Lin::WHITE }, n));
        let file_colors: Option<Vec<[f32; 3]>> = match draco_colors {
            Some((cs, k @ (3 | 4))) => {
                Some(cs.chunks_exact(k).map(|c| [c[0], c[1], c[2]]).collect())
            }
            Some((_, k)) => return Err(format!("its Draco COLOR_0 has {k} components")),
            None => reader.read_colors(0).map(|cs| cs.into_rgb_f32().collect()),
        };
        if let Some(cs) = file_colors {
            let all = self
                .colors
                .get_or_insert_with(|| self.base[..start].to_vec());
            let f = Vec3::from_slice(&factor[..3]);
            all.extend(cs.into_iter().map(|c| {
                let c = Vec3::from(c) * if own { f } else { Vec3::ONE };
                Lin::from_unit(c.to_array())
            }));
        } else if let Some(all) = &mut self.colors {
            all.extend_from_slice(&self.base[start..]);
        }

        let second_transform = second.and_then(|s| s.1);
        extend_uvs(
            &mut self.uvs,
            (start, n),
            tex_coords.as_deref(),
            uv_transform,
        );
        extend_uvs(
            &mut self.uvs2,
            (start, n),
            tex_coords2.as_deref(),
            second_transform,
        );
        let indices: Vec<u32> = match (draco.as_mut(), reader.read_indices()) {
            (Some(d), _) => std::mem::take(&mut d.indices),
            (None, Some(i)) => i.into_u32().collect(),
            (None, None) => (0..n as u32).collect(),
        };
        if let Some(&bad) = indices.iter().find(|&&i| i as usize >= n) {
            return Err(format!("index {bad} is out of range for {n} vertices"));
        }
        if lines {
            // Each line in its first end's colour: its vertex colour where
            // the file has them, else its material's.
            let color = |i: u32| match &self.colors {
                Some(c) => c.get((first + i) as usize).copied(),
                None => own.then_some(base),
            };
            let ends: Vec<[u32; 2]> = match mode {
                Mode::Points => indices.iter().map(|&i| [i, i]).collect(),
                Mode::Lines => indices.chunks_exact(2).map(|w| [w[0], w[1]]).collect(),
                Mode::LineStrip => indices.windows(2).map(|w| [w[0], w[1]]).collect(),
                _ => (indices.iter().copied())
                    .zip(indices.iter().copied().cycle().skip(1))
                    .take(if indices.len() > 1 { indices.len() } else { 0 })
                    .map(|(a, b)| [a, b])
                    .collect(),
            };
            self.lines.extend(
                ends.into_iter()
                    .map(|[a, b]| ([first + a, first + b], color(a))),
            );
            return Ok(());
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
        if let (Some((rig, place)), Some((positions, normals))) = (placed, local) {
            let faces: Vec<[u32; 3]> = self.faces[faces_before..]
                .iter()
                .map(|f| f.map(|i| i - first))
                .collect();
            let normals = normals.unwrap_or_else(|| rig::smooth_normals(&positions, &faces, flip));
            let vertices = (first, positions, normals);
            rig.part(prim, place, (buffers, draco.as_ref()), vertices, document)?;
        }
        if self.faces.len() > faces_before {
            let run = MaterialRun {
                first: faces_before as u32,
                color: own.then_some(base),
                texture,
                finish,
            };
            if self.materials.last().is_none_or(|m| {
                (m.color, m.texture, m.finish) != (run.color, run.texture, run.finish)
            }) {
                self.materials.push(run);
            }
        }
        Ok(())
    }

    fn geometry(mut self, name: &str, crease: f32) -> Geometry {
        // Sides said once for the whole where every material says the
        // same; else each run keeps its own.
        let sides = self.materials.first().map(|m| m.finish.sides);
        let uniform = sides.filter(|&s| self.materials.iter().all(|m| m.finish.sides == s));
        if uniform.is_some() {
            for m in &mut self.materials {
                m.finish.sides = crate::scene::Sides::Unsaid;
            }
        }
        let mut g = Geometry::new_raw(name, self.positions, self.faces);
        g.sides = uniform.unwrap_or_default();
        g.lines = self.lines;
        // Runs that are all "the mesh's colour", untextured, say nothing.
        let maps = self.materials.iter().any(|m| !m.finish.maps.is_empty());
        if maps || self.materials.iter().any(|m| m.texture.is_some()) {
            g.uvs = self.uvs;
            g.uvs2 = self.uvs2;
            g.textures = self.textures;
        }
        if self.materials.iter().any(|m| {
            m.color.is_some()
                || m.texture.is_some()
                || !m.finish.maps.is_empty()
                || m.finish.sides != crate::scene::Sides::Unsaid
        }) {
            g.materials = self.materials;
        }
        g.colors = self.colors;
        let file_normals = !self.normals_missing && self.normals.len() == g.positions.len();
        if file_normals {
            g.normals = self.normals;
        } else {
            g.compute_normals(crease);
        }
        g.analyze();
        if g.materials.iter().any(|m| m.finish.maps.normal.is_some()) {
            // The file's tangents go with its normals (computed normals
            // split vertices at creases: then MikkTSpace's, from them).
            let file = (file_normals && !self.tangents_missing)
                .then_some(self.tangents)
                .filter(|t| t.len() == g.positions.len());
            g.tangents = Some(super::tangents::of(&g, file.as_deref()));
        }
        g
    }
}

/// A primitive's `n` coordinates `coords` (two floats each), moved by
/// `transform`, added to `all` at vertex `start` (earlier vertices given
/// zeros); zeros where it has none and `all` exists.
fn extend_uvs(
    all: &mut Option<Vec<Vec2>>,
    (start, n): (usize, usize),
    coords: Option<&[f32]>,
    transform: Option<glam::Affine2>,
) {
    let Some(coords) = coords else {
        if let Some(all) = all {
            all.resize(start + n, Vec2::ZERO);
        }
        return;
    };
    let all = all.get_or_insert_with(|| vec![Vec2::ZERO; start]);
    let uvs = coords.chunks_exact(2).map(Vec2::from_slice);
    match transform {
        Some(m) => all.extend(uvs.map(|t| m.transform_point2(t))),
        None => all.extend(uvs),
    }
}

/// How many positions a primitive has (0 without them).
fn positions_count(prim: &::gltf::Primitive) -> usize {
    prim.get(&Semantic::Positions).map_or(0, |a| a.count())
}
