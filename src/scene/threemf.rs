//! 3MF: the 3D Manufacturing Format slicers save (PrusaSlicer, Bambu
//! Studio, Cura): a zip archive (the `zip` crate) whose model part is XML
//! (the `roxmltree` crate), found through the archive's relationships.
//!
//! Read: the core spec's objects (meshes of vertices and triangles),
//! components (objects placed in objects, to any depth without a cycle),
//! build items and their transforms, base materials and the materials
//! extension's colour groups (a triangle's colour, or each corner's), and
//! the model's unit, turned into metres. 3MF is z-up, as STL is. Not
//! drawn, and said in one note: beam lattices, slices, textures,
//! composite and multi-property materials, and parts in other model files
//! (the production extension).
//!
//! Trade-offs. The archive is untrusted: a part's declared size is held to
//! the byte budget before it is decompressed, and the decompression is cut
//! at that size (a zip bomb is refused, not inflated); parts are read by
//! name from the archive and nothing is written anywhere; the XML is
//! parsed without a DTD (no entity expansion). The triangles the build
//! places are counted against the triangle budget before any is made.

use std::io::Read;
use std::path::Path;

use glam::{Mat4, Vec3, Vec4};
use rustc_hash::FxHashMap;

use super::{Geometry, LoadOptions, file};
use crate::color::{Lin, Rgb};
use crate::error::{Error, Result};
use crate::scene::obj::Loaded;

/// The relationship type of a 3MF package's model part.
const MODEL_RELATIONSHIP: &str = "http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel";

/// The core namespace.
const CORE: &str = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02";

/// The materials extension's namespace.
const MATERIALS: &str = "http://schemas.microsoft.com/3dmanufacturing/material/2015/02";

/// How deep components may nest.
const MAX_DEPTH: usize = 32;

/// Loads a 3MF file, opened through `files`.
pub(crate) fn load_in(path: &Path, options: &LoadOptions, files: &file::Files) -> Result<Loaded> {
    let bytes = files.read(path)?;
    read(&bytes, &path.display().to_string(), options)
}

/// Parses 3MF bytes (the whole archive); `name` is used in messages.
pub fn parse(bytes: &[u8], name: &str) -> Result<Loaded> {
    parse_with(bytes, name, &LoadOptions::default())
}

/// [`parse`] under `options`' budgets.
pub fn parse_with(bytes: &[u8], name: &str, options: &LoadOptions) -> Result<Loaded> {
    read(bytes, name, options)
}

fn read(bytes: &[u8], name: &str, options: &LoadOptions) -> Result<Loaded> {
    let bad = |what: String| Error::Invalid(format!("{name}: {what}"));
    let mut zip = zip::ZipArchive::new(std::io::Cursor::new(bytes))
        .map_err(|e| bad(format!("not a 3MF archive (a zip): {e}")))?;
    let mut budget = options.max_bytes;
    let rels = part(&mut zip, "_rels/.rels", &mut budget).map_err(bad)?;
    let model_path = model_part(&rels).map_err(|e| bad(format!("_rels/.rels: {e}")))?;
    // The root model part, then each part its components name (the
    // production extension's), each read once.
    let mut model = Model::new(model_path.clone());
    let mut i = 0;
    while let Some(part_name) = model.parts.get(i).cloned() {
        let text = part(&mut zip, &part_name, &mut budget).map_err(bad)?;
        let at = |e: String| bad(format!("{part_name}{e}"));
        let doc = roxmltree::Document::parse(&text).map_err(|e| at(format!(": {e}")))?;
        model.read_part(&doc, i).map_err(at)?;
        i += 1;
    }
    let at = |e: String| bad(format!("{model_path}{e}"));
    let mut notes = Vec::new();
    if !model.unread.is_empty() {
        notes.push(format!("{name}: not drawn: {}", model.unread.join(", ")));
    }
    let geometry = model.build(name, options).map_err(at)?;
    Ok(Loaded { geometry, notes })
}

/// Part `name` of the archive as text, its declared size held to (and
/// taken from) `budget` before it is decompressed, and the decompression
/// cut there.
fn part(
    zip: &mut zip::ZipArchive<std::io::Cursor<&[u8]>>,
    name: &str,
    budget: &mut u64,
) -> std::result::Result<String, String> {
    // Part names are case-insensitive (OPC).
    let index = zip
        .index_for_name_raw(name.as_bytes())
        .or_else(|| (zip.file_names_raw()).position(|n| n.eq_ignore_ascii_case(name.as_bytes())))
        .ok_or_else(|| format!("the archive has no part {name}"))?;
    let mut entry = zip.by_index(index).map_err(|e| format!("{name}: {e}"))?;
    let size = entry.size();
    if size > *budget {
        return Err(format!(
            "{name} unpacks to {size} bytes, more than the budget of {budget} (--max-bytes raises it)"
        ));
    }
    *budget -= size;
    let mut text = String::new();
    (&mut entry)
        .take(size)
        .read_to_string(&mut text)
        .map_err(|e| format!("{name}: {e}"))?;
    Ok(text)
}

/// The model part's name in the archive, from the package's
/// relationships (a leading `/` dropped; a name that leaves the archive's
/// root refused).
fn model_part(rels: &str) -> std::result::Result<String, String> {
    let doc = roxmltree::Document::parse(rels).map_err(|e| e.to_string())?;
    let target = (doc.descendants())
        .filter(|n| n.has_tag_name("Relationship"))
        .find(|n| n.attribute("Type") == Some(MODEL_RELATIONSHIP))
        .and_then(|n| n.attribute("Target"))
        .ok_or("no relationship names a 3D model part")?;
    let name = target.trim_start_matches('/');
    if name.is_empty() || name.split(['/', '\\']).any(|c| c == ".." || c.is_empty()) {
        return Err(format!(
            "the model part's name {target:?} is not a name inside the archive"
        ));
    }
    Ok(name.to_owned())
}

/// A property a triangle's corner may have: a colour, linear.
type Colour = Lin;

/// An object: a mesh, or components.
enum Object {
    Mesh {
        positions: Vec<Vec3>,
        /// Each triangle's corners and their colours (`None`: the
        /// object's, if any).
        triangles: Vec<([u32; 3], Option<[Colour; 3]>)>,
        /// The object's own colour.
        colour: Option<Colour>,
    },
    Components(Vec<(Key, Mat4)>),
}

/// An object's part (an index into [`Model::parts`]) and id.
type Key = (usize, u32);

/// What the model part says.
struct Model {
    /// Metres a unit (the root part's).
    unit: f32,
    /// The model parts read or to read: the root's first.
    parts: Vec<String>,
    objects: FxHashMap<Key, Object>,
    /// The build's items: objects and their transforms.
    items: Vec<(Key, Mat4)>,
    /// What is not drawn.
    unread: Vec<String>,
}

/// `node`'s place in the text, as `:line:column`.
fn place(doc: &roxmltree::Document, node: roxmltree::Node) -> String {
    let p = doc.text_pos_at(node.range().start);
    format!(":{}:{}", p.row, p.col)
}

/// The index of model part `path` (a component's or item's `p:path`) in
/// `parts`, added if new; a name that leaves the archive's root refused.
fn part_index(parts: &mut Vec<String>, path: &str) -> std::result::Result<usize, String> {
    let name = path.trim_start_matches('/');
    if name.is_empty() || name.split(['/', '\\']).any(|c| c == ".." || c.is_empty()) {
        return Err(format!(": {path:?} is not a part inside the archive"));
    }
    Ok(match parts.iter().position(|p| p == name) {
        Some(i) => i,
        None => {
            parts.push(name.to_owned());
            parts.len() - 1
        }
    })
}

impl Model {
    fn new(root: String) -> Model {
        Model {
            unit: 1e-3,
            parts: vec![root],
            objects: FxHashMap::default(),
            items: Vec::new(),
            unread: Vec::new(),
        }
    }

    /// Reads model part `part`'s resources (and, for the root, its unit
    /// and build).
    fn read_part(
        &mut self,
        doc: &roxmltree::Document,
        part: usize,
    ) -> std::result::Result<(), String> {
        let root = doc.root_element();
        if root.tag_name().name() != "model" {
            return Err(format!(
                "{}: the root element is not a model",
                place(doc, root)
            ));
        }
        let unit = match root.attribute("unit").unwrap_or("millimeter") {
            "micron" => 1e-6,
            "millimeter" => 1e-3,
            "centimeter" => 1e-2,
            "inch" => 0.0254,
            "foot" => 0.3048,
            "meter" => 1.0,
            other => {
                return Err(format!(
                    "{}: unit {:?} is not one of 3MF's",
                    place(doc, root),
                    crate::text::name(other, 40)
                ));
            }
        };
        if part == 0 {
            self.unit = unit;
        }
        let unread = &mut self.unread;
        let mut note = |what: &str| {
            if !unread.iter().any(|u| u == what) {
                unread.push(what.to_owned());
            }
        };
        // Property groups: base materials and colour groups, by id.
        let mut groups: FxHashMap<u32, Vec<Colour>> = FxHashMap::default();
        let id = |n: roxmltree::Node, key: &str| -> std::result::Result<u32, String> {
            let v = n
                .attribute(key)
                .ok_or_else(|| format!("{}: no {key}", place(doc, n)))?;
            v.trim()
                .parse()
                .map_err(|_| format!("{}: {key} {v:?} is not a whole number", place(doc, n)))
        };
        for n in root.descendants().filter(|n| n.is_element()) {
            let tag = n.tag_name();
            match (tag.namespace(), tag.name()) {
                (Some(CORE), "basematerials") | (Some(MATERIALS), "colorgroup") => {
                    let colours = n
                        .children()
                        .filter(|c| c.is_element())
                        .map(|c| {
                            let key = if c.tag_name().name() == "base" {
                                "displaycolor"
                            } else {
                                "color"
                            };
                            let v = c.attribute(key).unwrap_or("#FFFFFF");
                            colour(v).ok_or_else(|| {
                                format!("{}: {key} {v:?} is not #RRGGBB", place(doc, c))
                            })
                        })
                        .collect::<std::result::Result<Vec<_>, _>>()?;
                    groups.insert(id(n, "id")?, colours);
                }
                (Some(MATERIALS), "texture2dgroup" | "texture2d") => note("textures"),
                (Some(MATERIALS), "compositematerials" | "multiproperties") => {
                    note("composite and multi-property materials")
                }
                (_, "beamlattice") => note("beam lattices"),
                (_, "slicestack" | "slice") => note("slices"),
                _ => {}
            }
        }
        let property =
            |groups: &FxHashMap<u32, Vec<Colour>>, pid: Option<u32>, index: Option<&str>| {
                let pid = pid?;
                let index: usize = index?.trim().parse().ok()?;
                groups.get(&pid)?.get(index).copied()
            };
        let resources = root
            .children()
            .find(|c| c.has_tag_name((CORE, "resources")));
        for o in resources
            .iter()
            .flat_map(|r| r.children())
            .filter(|c| c.has_tag_name((CORE, "object")))
        {
            let oid = id(o, "id")?;
            let pid = o.attribute("pid").and_then(|p| p.trim().parse().ok());
            let colour = property(&groups, pid, o.attribute("pindex"));
            let object = if let Some(mesh) = o.children().find(|c| c.has_tag_name((CORE, "mesh"))) {
                let mut positions = Vec::new();
                let mut triangles = Vec::new();
                for part in mesh.children().filter(|c| c.is_element()) {
                    match part.tag_name().name() {
                        "vertices" => {
                            for v in part.children().filter(|c| c.has_tag_name((CORE, "vertex"))) {
                                let c = |k: &str| number(doc, v, k);
                                positions.push(Vec3::new(c("x")?, c("y")?, c("z")?));
                            }
                        }
                        "triangles" => {
                            for t in part
                                .children()
                                .filter(|c| c.has_tag_name((CORE, "triangle")))
                            {
                                let corners = [id(t, "v1")?, id(t, "v2")?, id(t, "v3")?];
                                if let Some(bad) =
                                    corners.iter().find(|&&i| i as usize >= positions.len())
                                {
                                    return Err(format!(
                                        "{}: vertex {bad} is out of range ({} vertices)",
                                        place(doc, t),
                                        positions.len()
                                    ));
                                }
                                let tpid = t
                                    .attribute("pid")
                                    .and_then(|p| p.trim().parse().ok())
                                    .or(pid);
                                let p1 = t.attribute("p1").or(if t.attribute("pid").is_none() {
                                    o.attribute("pindex")
                                } else {
                                    None
                                });
                                let first = property(&groups, tpid, p1);
                                let corner =
                                    |k: &str| property(&groups, tpid, t.attribute(k)).or(first);
                                let colours = first.map(|f| {
                                    [f, corner("p2").unwrap_or(f), corner("p3").unwrap_or(f)]
                                });
                                triangles.push((corners, colours));
                            }
                        }
                        _ => {}
                    }
                }
                Object::Mesh {
                    positions,
                    triangles,
                    colour,
                }
            } else if let Some(cs) = o.children().find(|c| c.has_tag_name((CORE, "components"))) {
                let mut list = Vec::new();
                for c in cs
                    .children()
                    .filter(|c| c.has_tag_name((CORE, "component")))
                {
                    let p = match c.attributes().find(|a| a.name() == "path") {
                        Some(path) => part_index(&mut self.parts, path.value())?,
                        None => part,
                    };
                    list.push(((p, id(c, "objectid")?), transform(doc, c)?));
                }
                Object::Components(list)
            } else {
                continue;
            };
            self.objects.insert((part, oid), object);
        }
        let build = root.children().find(|c| c.has_tag_name((CORE, "build")));
        let items = build
            .iter()
            .flat_map(|b| b.children())
            .filter(|_| part == 0);
        for item in items.filter(|c| c.has_tag_name((CORE, "item"))) {
            let p = match item.attributes().find(|a| a.name() == "path") {
                Some(path) => part_index(&mut self.parts, path.value())?,
                None => 0,
            };
            self.items
                .push(((p, id(item, "objectid")?), transform(doc, item)?));
        }
        Ok(())
    }

    /// The build's triangles in metres, counted against the budget first.
    fn build(&self, name: &str, options: &LoadOptions) -> std::result::Result<Geometry, String> {
        let (mut total, mut visits) = (0u128, 0u128);
        let mut memo = FxHashMap::default();
        for &(id, _) in &self.items {
            let (t, v) = self.count(id, 0, &mut memo)?;
            (total, visits) = (total.saturating_add(t), visits.saturating_add(v));
        }
        // Objects placed many times over through components, each a
        // visit, are held to the same budget as triangles.
        if total.max(visits) > u128::from(options.max_triangles) {
            return Err(format!(
                ": its build places {total} triangles, more than the budget of {} (--max-triangles raises it)",
                options.max_triangles
            ));
        }
        if total == 0 {
            return Err(match self.unread.is_empty() {
                true => ": its build places no triangles".into(),
                false => format!(
                    ": its build places no triangles ({} are not drawn)",
                    self.unread.join(", ")
                ),
            });
        }
        let mut out = Parts::default();
        let units = Mat4::from_scale(Vec3::splat(self.unit));
        for &(id, m) in &self.items {
            self.place(id, units * m, &mut out)?;
        }
        let mut g = Geometry::new_raw(name, out.positions, out.faces);
        if out.coloured {
            g.colors = Some(out.colours);
        }
        g.compute_normals(options.crease);
        g.analyze();
        Ok(g)
    }

    /// The triangles object `id` places and the objects it visits, at
    /// component depth `depth`, each object's found once (`memo`).
    fn count(
        &self,
        id: Key,
        depth: usize,
        memo: &mut FxHashMap<Key, (u128, u128)>,
    ) -> std::result::Result<(u128, u128), String> {
        if let Some(&n) = memo.get(&id) {
            return Ok(n);
        }
        if depth > MAX_DEPTH {
            return Err(format!(
                ": components nest deeper than {MAX_DEPTH} (a cycle?) at object {} of {}",
                id.1, self.parts[id.0]
            ));
        }
        let n = match self.objects.get(&id) {
            None => {
                return Err(format!(
                    ": object {} of {} does not exist",
                    id.1, self.parts[id.0]
                ));
            }
            Some(Object::Mesh { triangles, .. }) => (triangles.len() as u128, 1),
            Some(Object::Components(list)) => {
                let mut n = (0u128, 1u128);
                for &(c, _) in list {
                    let (t, v) = self.count(c, depth + 1, memo)?;
                    n = (n.0.saturating_add(t), n.1.saturating_add(v));
                }
                n
            }
        };
        memo.insert(id, n);
        Ok(n)
    }

    /// Adds object `id`'s triangles, placed by `m`, to `out` (its depth
    /// held by [`Model::count`] first).
    fn place(&self, id: Key, m: Mat4, out: &mut Parts) -> std::result::Result<(), String> {
        match self.objects.get(&id) {
            None => Err(format!(
                ": object {} of {} does not exist",
                id.1, self.parts[id.0]
            )),
            Some(Object::Components(list)) => {
                for &(c, t) in list {
                    self.place(c, m * t, out)?;
                }
                Ok(())
            }
            Some(Object::Mesh {
                positions,
                triangles,
                colour,
            }) => {
                let own = *colour;
                let start = out.positions.len();
                out.positions
                    .extend(positions.iter().map(|&p| m.transform_point3(p)));
                if out.coloured {
                    out.colours.resize(out.positions.len(), grey());
                }
                // A vertex takes the colour of the first corner that names
                // it; a corner of another colour gets a vertex of its own.
                let mut first: Vec<Option<Colour>> = vec![None; positions.len()];
                let mirror = m.determinant() < 0.0;
                for &(corners, colours) in triangles {
                    let colours = colours.or(own.map(|c| [c; 3]));
                    if colours.is_some() && !out.coloured {
                        // Every vertex so far in the default colour.
                        out.coloured = true;
                        out.colours.resize(out.positions.len(), grey());
                    }
                    let mut face = corners.map(|i| (start + i as usize) as u32);
                    if let Some(cs) = colours {
                        for k in 0..3 {
                            let v = corners[k] as usize;
                            match first[v] {
                                None => {
                                    first[v] = Some(cs[k]);
                                    out.colours[start + v] = cs[k];
                                }
                                Some(c) if c == cs[k] => {}
                                Some(_) => {
                                    face[k] = out.positions.len() as u32;
                                    out.positions.push(out.positions[start + v]);
                                    out.colours.push(cs[k]);
                                }
                            }
                        }
                    }
                    if mirror {
                        face.swap(1, 2);
                    }
                    out.faces.push(face);
                }
                if out.coloured {
                    out.colours.resize(out.positions.len(), grey());
                }
                Ok(())
            }
        }
    }
}

/// The build's triangles as they are gathered.
#[derive(Default)]
struct Parts {
    positions: Vec<Vec3>,
    faces: Vec<[u32; 3]>,
    colours: Vec<Lin>,
    /// Whether any triangle has a colour (then every vertex has one).
    coloured: bool,
}

/// The colour of a vertex the file gives none, where others have one.
fn grey() -> Lin {
    Lin::from_srgb(super::DEFAULT_MESH_COLOR)
}

/// Number `key` of element `n`, finite.
fn number(
    doc: &roxmltree::Document,
    n: roxmltree::Node,
    key: &str,
) -> std::result::Result<f32, String> {
    let v = n
        .attribute(key)
        .ok_or_else(|| format!("{}: no {key}", place(doc, n)))?;
    v.trim()
        .parse::<f32>()
        .ok()
        .filter(|x| x.is_finite())
        .ok_or_else(|| {
            format!(
                "{}: {key} {:?} is not a finite number",
                place(doc, n),
                crate::text::name(v, 40)
            )
        })
}

/// Element `n`'s `transform` (3MF's twelve numbers, rows of a 4×3 matrix
/// applied to row vectors), or the identity.
fn transform(doc: &roxmltree::Document, n: roxmltree::Node) -> std::result::Result<Mat4, String> {
    let Some(t) = n.attribute("transform") else {
        return Ok(Mat4::IDENTITY);
    };
    let v: Vec<f32> = t
        .split_ascii_whitespace()
        .map_while(|x| x.parse().ok())
        .collect();
    match v[..] {
        [a, b, c, d, e, f, g, h, i, j, k, l] if v.iter().all(|x| x.is_finite()) => {
            Ok(Mat4::from_cols(
                Vec4::new(a, b, c, 0.0),
                Vec4::new(d, e, f, 0.0),
                Vec4::new(g, h, i, 0.0),
                Vec4::new(j, k, l, 1.0),
            ))
        }
        _ => Err(format!(
            "{}: transform {:?} is not twelve finite numbers",
            place(doc, n),
            crate::text::name(t, 60)
        )),
    }
}

/// A 3MF colour, `#RRGGBB` or `#RRGGBBAA` (sRGB; the alpha is not drawn),
/// linear.
fn colour(v: &str) -> Option<Colour> {
    let hex = v.trim().strip_prefix('#')?;
    if !(hex.len() == 6 || hex.len() == 8) || !hex.is_ascii() {
        return None;
    }
    let byte = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).ok();
    Some(Lin::from_srgb(Rgb::new(byte(0)?, byte(2)?, byte(4)?)))
}
