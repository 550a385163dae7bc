//! Wavefront OBJ, with the diffuse colours (`Kd`) and textures (`map_Kd`)
//! of the MTL files it names.
//!
//! Read in one pass over the bytes, a line at a time through a buffer
//! (never the whole file in memory). The lines that make up nearly all of
//! a large file (`v`, `vn`, `vt`, and `f` with positive indices) are read
//! by a fast path (`fast.rs`) straight from the buffer; every other line,
//! and any line the fast path is unsure of, is scanned once by a `Cursor`,
//! which reads short decimals eight digits at a time and converts them
//! exactly (others go to `fast-float2`), and every error names the file,
//! line and column of what is wrong. rastty's
//! own parser rather than `tobj`, which reports no positions and costs
//! several times the instructions (the load's cost is in docs/figures.md,
//! "Loading").
//!
//! What is read: `v` (with an optional `w`, and vertex colours `v x y z r g
//! b`), `vn`, `vt`, `f` (any number of corners, `v`, `v/vt`, `v//vn` or
//! `v/vt/vn`, indices from 1 or negative from the end), `usemtl`, `mtllib`
//! (one or more files; of each material its `Kd` and its `map_Kd` image,
//! PNG or JPEG, with the `-clamp` option; other options are skipped). A
//! material's image is decoded when a `usemtl` first selects it (with the
//! `textures` feature; without it, the loader says the textures were not
//! read); only faces of a textured material keep their `vt`, so a vertex
//! is split only where its texture coordinates differ. `l` and `p`
//! (lines and points) are not faces: they are skipped and counted, and a
//! file of nothing else has no faces. Other statements (`o`, `g`, `s`, …)
//! are ignored. A face's corners become vertices and triangles in `faces.rs`;
//! polygons are cut by the polygon triangulator (`polygon.rs`).
//!
//! Normals come from the file when every corner names one; otherwise they
//! are computed (see [`Geometry::compute_normals`](super::Geometry::compute_normals)). A vertex that is not a finite number
//! is not an error, but the faces that use it are not drawn, and the loader
//! says so.

mod faces;
mod fast;
mod mtl;

use std::path::Path;

use std::sync::Arc;

use glam::{Vec2, Vec3};
use rustc_hash::{FxHashMap, FxHashSet};

use super::LoadOptions;
use super::file::{self, FileId, Files};
use super::lines::{self, Cursor, Lines};
use super::mesh::{Geometry, MaterialRun};
use super::polygon::{self, Point, Triangulator};
use crate::color::{ColorSpace, Lin};
use crate::error::{Error, Result};
use crate::texture::{Sampler, Texture, Wrap};
use mtl::{Map, Material, mtl};

/// A vertex colour `r g b` as a `v` line gives it: sRGB-encoded, as 8-bit
/// ones are.
fn vertex_color(c: [f32; 3]) -> Lin {
    ColorSpace::Srgb.decode(c)
}

/// A model read from a file, and what the reader has to tell.
#[derive(Debug)]
pub struct Loaded {
    /// The triangles read.
    pub geometry: Geometry,
    /// Things read but not drawn: non-finite vertices, lines and points.
    pub notes: Vec<String>,
}

impl Loaded {
    /// What `load` loads with a fresh set of files of at most `max_bytes`
    /// each, and what reading them said among its notes.
    pub(crate) fn with_files(
        max_bytes: u64,
        load: impl FnOnce(&Files) -> Result<Loaded>,
    ) -> Result<Loaded> {
        let files = Files::new(max_bytes);
        let mut loaded = load(&files)?;
        loaded.notes.extend(files.take_notes());
        Ok(loaded)
    }
}

/// Loads an OBJ file (and its MTL files, found beside it).
pub fn load(path: &Path, options: &LoadOptions) -> Result<Loaded> {
    Loaded::with_files(options.max_bytes, |files| load_in(path, options, files))
}

/// [`load`], every file opened through `files`.
pub(crate) fn load_in(path: &Path, options: &LoadOptions, files: &Files) -> Result<Loaded> {
    let file = files.open(path)?;
    read(
        file,
        &path.display().to_string(),
        path.parent().unwrap_or(Path::new(".")),
        options,
        files,
    )
}

/// Parses OBJ bytes; `name` is used in messages, material libraries are
/// looked for in `dir`.
pub fn parse(src: &[u8], name: &str, dir: &Path) -> Result<Loaded> {
    let options = LoadOptions::default();
    Loaded::with_files(options.max_bytes, |files| {
        read(src, name, dir, &options, files)
    })
}

/// No index (a corner without a normal).
const NONE: u32 = u32::MAX;
/// The bit that marks a vertex made while cutting a polygon, numbered apart
/// until the end of the file.
const MADE: u32 = 1 << 31;
/// The bit that marks a vertex whose `v` was already paired with another
/// normal, numbered apart until the end of the file.
const EXTRA: u32 = 1 << 30;
/// The most `v` a file may have: their indices stay clear of the bits.
const MAX_VERTICES: usize = EXTRA as usize;
/// No corner has used the `v` yet.
const UNSET: u64 = u64::MAX;

/// A corner's texture coordinate and normal, as one key.
fn attrs(vt: u32, vn: u32) -> u64 {
    u64::from(vt) << 32 | u64::from(vn)
}

/// Everything gathered while reading.
struct Reader<'a> {
    name: &'a str,
    dir: &'a Path,
    options: &'a LoadOptions,
    /// Where every file is opened.
    files: &'a Files,
    /// The material libraries read so far (one named again is not read
    /// again).
    libraries: FxHashSet<FileId>,
    /// The file's `v`, `vn`, `vt` (`v` flipped to run down the image) and
    /// vertex colours.
    pos: Vec<Vec3>,
    /// Where each non-finite `v` is (line), counted.
    bad_pos: Vec<u32>,
    /// Whether a `v` or `vn` so far is not finite (only then are corners
    /// checked).
    any_bad: bool,
    colors: Vec<Lin>,
    vn: Vec<Vec3>,
    vt: Vec<Vec2>,
    /// For each `v`, the texture coordinate and normal the first corner to
    /// use it named (`attrs(vt, vn)`; `UNSET`: none yet): that corner's
    /// vertex is the `v` itself. Empty until a corner names one.
    attr_of: Vec<u64>,
    /// Vertices of a `v` with a second (third, …) texture coordinate and
    /// normal: `(v, attrs)`, and where each pair is in the list.
    extra: Vec<(u32, u64)>,
    extra_ids: FxHashMap<(u32, u64), u32>,
    /// Vertices made between corners: position, colour, normal, UV.
    made: Vec<(Vec3, Lin, Vec3, Vec2)>,
    triangles: Vec<[u32; 3]>,
    materials: Vec<MaterialRun>,
    library: FxHashMap<Vec<u8>, Material>,
    /// The images decoded so far, and which file each came from.
    textures: Vec<Arc<Texture>>,
    #[cfg_attr(not(feature = "textures"), allow(dead_code))]
    texture_ids: FxHashMap<FileId, u32>,
    /// What is left of the texel budget.
    #[cfg_attr(not(feature = "textures"), allow(dead_code))]
    texels_left: u64,
    /// The largest side of a texture's finest level.
    #[cfg_attr(not(feature = "textures"), allow(dead_code))]
    max_texture_side: u32,
    /// Notes on the files named (absolute paths, paths out of the folder).
    reference_notes: Vec<String>,
    /// The names `usemtl` gave that no library read defines, and the
    /// first of them, said where it was.
    unknown_materials: FxHashSet<Vec<u8>>,
    first_unknown: Option<String>,
    /// Whether the faces now being read are textured (then their corners
    /// keep their `vt`).
    textured: bool,
    /// Materials whose textures were not read (built without them).
    unread_textures: usize,
    /// Whether every corner so far named a normal.
    all_normals: bool,
    lines_and_points: usize,
    dropped_faces: usize,
    cutter: Triangulator,
    /// The corners of the face being read: `v`, `vt`, `vn`.
    corners: Vec<[u32; 3]>,
    ids: Vec<u32>,
    corner_pos: Vec<Vec3>,
    cut: Vec<[Point; 3]>,
}

fn read(
    src: impl std::io::Read,
    name: &str,
    dir: &Path,
    options: &LoadOptions,
    files: &Files,
) -> Result<Loaded> {
    read_with(src, name, dir, options, files, true)
}

/// [`read`], with the fast path (`fast.rs`) or without it.
fn read_with(
    src: impl std::io::Read,
    name: &str,
    dir: &Path,
    options: &LoadOptions,
    files: &Files,
    fast: bool,
) -> Result<Loaded> {
    let mut r = Reader::new(name, dir, options, files);
    let mut lines = Lines::new(src);
    loop {
        // The first line goes to the general reader (a byte order mark);
        // then the fast path takes what it can of the buffer, and the
        // general reader the line it stopped at.
        if fast && lines.number > 0 {
            let (len, count) = r.fast_lines(lines.window(), lines.number + 1);
            lines.skip_lines(len, count);
        }
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
        r.statement(Cursor::new(line), n)?;
    }
    r.finish(lines.number)
}

impl<'a> Reader<'a> {
    fn new(name: &'a str, dir: &'a Path, options: &'a LoadOptions, files: &'a Files) -> Reader<'a> {
        Reader {
            name,
            dir,
            options,
            files,
            libraries: FxHashSet::default(),
            pos: Vec::new(),
            bad_pos: Vec::new(),
            any_bad: false,
            colors: Vec::new(),
            vn: Vec::new(),
            vt: Vec::new(),
            attr_of: Vec::new(),
            extra: Vec::new(),
            extra_ids: FxHashMap::default(),
            made: Vec::new(),
            triangles: Vec::new(),
            materials: Vec::new(),
            library: FxHashMap::default(),
            textures: Vec::new(),
            texture_ids: FxHashMap::default(),
            texels_left: options.max_texels,
            max_texture_side: options.max_texture_side,
            reference_notes: Vec::new(),
            unknown_materials: FxHashSet::default(),
            first_unknown: None,
            textured: false,
            unread_textures: 0,
            all_normals: true,
            lines_and_points: 0,
            dropped_faces: 0,
            cutter: Triangulator::new(),
            corners: Vec::new(),
            ids: Vec::new(),
            corner_pos: Vec::new(),
            cut: Vec::new(),
        }
    }

    /// An error at byte `offset` of line `n`'s text `line`.
    fn at_byte(&self, line: &[u8], n: usize, offset: usize, message: impl Into<String>) -> Error {
        self.at(n, lines::column(line, offset), message)
    }

    fn at(&self, line: usize, column: usize, message: impl Into<String>) -> Error {
        Error::Parse {
            path: self.name.to_string(),
            line,
            column,
            message: message.into(),
        }
    }

    /// Up to `N` numbers of a `keyword` statement, and how many there were.
    #[inline]
    fn numbers<const N: usize>(
        &self,
        c: &mut Cursor,
        n: usize,
        keyword: &str,
    ) -> Result<([f32; N], usize)> {
        let mut v = [0.0f32; N];
        let mut k = 0;
        while let Some(x) = c.number() {
            let x = x.map_err(|(w, at)| self.at_byte(c.line(), n, at, not_number(keyword, w)))?;
            if k == N {
                return Err(self.at(n, 1, format!("`{keyword}` takes at most {N} numbers")));
            }
            v[k] = x;
            k += 1;
        }
        Ok((v, k))
    }

    fn statement(&mut self, mut c: Cursor, n: usize) -> Result<()> {
        let Some((keyword, _)) = c.word() else {
            return Ok(());
        };
        match keyword {
            b"v" => {
                let (v, k) = self.numbers::<7>(&mut c, n, "v")?;
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
                if self.pos.len() == MAX_VERTICES {
                    return Err(self.at(n, 1, format!("more than {MAX_VERTICES} vertices")));
                }
                if color.is_some_and(|c| c.iter().any(|x| !x.is_finite())) {
                    return Err(self.at(n, 1, "a vertex colour is not a finite number"));
                }
                let color = color.map(vertex_color);
                self.position(Vec3::new(v[0], v[1], v[2]), color, n);
            }
            b"vn" => {
                let (v, k) = self.numbers::<3>(&mut c, n, "vn")?;
                if k != 3 {
                    return Err(self.at(n, 1, format!("`vn` needs 3 numbers, found {k}")));
                }
                let normal = Vec3::from(v);
                self.any_bad |= !normal.is_finite();
                self.vn.push(normal);
            }
            b"vt" => {
                let (t, k) = self.numbers::<3>(&mut c, n, "vt")?;
                if k == 0 {
                    return Err(self.at(n, 1, "`vt` needs at least 1 number"));
                }
                if self.vt.len() == MAX_VERTICES {
                    return Err(self.at(n, 1, format!("more than {MAX_VERTICES} `vt`")));
                }
                self.vt.push(Vec2::new(t[0], 1.0 - t[1]));
            }
            b"f" => self.face(c, n)?,
            b"l" | b"p" => self.lines_and_points += 1,
            b"usemtl" => {
                let name = c.rest();
                let material = match self.library.get(name) {
                    Some(m) => m.clone(),
                    None => {
                        self.unknown_material(name, c.line(), n);
                        Material::default()
                    }
                };
                let finish = material.finish();
                let texture = match material.map {
                    Some(map) => self.texture(map)?,
                    None => None,
                };
                self.textured = texture.is_some();
                let run = MaterialRun {
                    first: self.triangles.len() as u32,
                    color: material.color,
                    texture,
                    finish,
                };
                match self.materials.last_mut() {
                    Some(last) if last.first == run.first => *last = run,
                    _ => self.materials.push(run),
                }
            }
            b"mtllib" => self.mtllib(c, n)?,
            _ => {}
        }
        Ok(())
    }

    /// A `usemtl` of line `n` (`line`) naming a material no library read
    /// defines: kept for a note, where a library was read (without one,
    /// its own note says the faces are drawn in the default colour).
    fn unknown_material(&mut self, name: &[u8], line: &[u8], n: usize) {
        if self.library.is_empty() || !self.unknown_materials.insert(name.to_vec()) {
            return;
        }
        if self.first_unknown.is_none() {
            let offset = name.as_ptr() as usize - line.as_ptr() as usize;
            let at = self.at_byte(line, n, offset, "");
            self.first_unknown = Some(format!(
                "{at}material {} is in none of the material libraries read",
                crate::text::name(&lossy(name), 80)
            ));
        }
    }

    /// A `v` of line `n` (checked: below the limit, a finite colour).
    #[inline]
    fn position(&mut self, p: Vec3, color: Option<Lin>, n: usize) {
        // Finite: `0·x` is ±0 for each coordinate, and NaN for an infinity
        // or a NaN (one branch, where `is_finite` takes three).
        let d = p * 0.0;
        if d.x + d.y + d.z != 0.0 {
            self.bad_pos.push(n as u32);
            self.any_bad = true;
        }
        self.finite_position(p, color);
    }

    /// [`Reader::position`] for one known to be finite.
    #[inline]
    pub(super) fn finite_position(&mut self, p: Vec3, color: Option<Lin>) {
        if let Some(c) = color {
            // Vertices before the first coloured one were white.
            self.colors.resize(self.pos.len(), Lin::WHITE);
            self.colors.push(c);
        } else if !self.colors.is_empty() {
            self.colors.push(Lin::WHITE);
        }
        self.pos.push(p);
    }

    /// One face: its corners resolved and checked, cut into triangles.
    fn face(&mut self, mut c: Cursor, n: usize) -> Result<()> {
        let line = c.line();
        self.corners.clear();
        let counts = [self.pos.len(), self.vt.len(), self.vn.len()];
        while let Some(corner) = c.corner() {
            let (parts, col) = match corner {
                Ok(parts) => (parts, 0),
                Err((w, col)) => return Err(self.bad_corner(line, n, w, col)),
            };
            let mut idx = [NONE; 3];
            for (k, part) in parts.into_iter().enumerate() {
                let Some(i) = part else { continue };
                let count = counts[k] as i64;
                let resolved = if i < 0 { count + i } else { i - 1 };
                if i == 0 || resolved < 0 || resolved >= count {
                    // Found again to place the message: errors are rare.
                    let col = col + corner_offset(line, self.corners.len());
                    let what = ["vertex", "texture coordinate", "normal"][k];
                    let message = if count == 0 {
                        format!("face {what} index {i}: no {what} is given before it")
                    } else {
                        format!("face {what} index {i} is out of range (1 to {count} so far)")
                    };
                    return Err(self.at_byte(line, n, col, message));
                }
                idx[k] = resolved as u32;
            }
            let [v, vt, vn] = idx;
            // Texture coordinates matter only where a texture is read.
            let vt = if self.textured { vt } else { NONE };
            self.corners.push([v, vt, vn]);
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
        self.add_face();
        Ok(())
    }

    /// The error for a face corner that is not `v[/[vt][/vn]]`.
    fn bad_corner(&self, line: &[u8], n: usize, w: &[u8], col: usize) -> Error {
        let parts = w.split(|&b| b == b'/').count();
        let message = if parts > 3 {
            format!("face vertex {:?} has more than 3 parts", lossy(w))
        } else {
            format!("face vertex {:?} is not an index", lossy(w))
        };
        self.at_byte(line, n, col, message)
    }

    /// The texture a material's `map_Kd` names, decoded the first time a
    /// `usemtl` selects it; an image that cannot be read is an error at
    /// the MTL line that names it.
    fn texture(&mut self, map: Map) -> Result<Option<u32>> {
        #[cfg(feature = "textures")]
        {
            let at_map = |message: String| Error::Parse {
                path: map.mtl.clone(),
                line: map.line,
                column: map.column,
                message: file::explain(map.why.as_deref(), message),
            };
            let opened = self
                .files
                .open(&map.path)
                .map_err(|e| at_map(e.to_string()))?;
            if let Some(&id) = self.texture_ids.get(opened.id()) {
                return Ok(Some(id));
            }
            let key = opened.id().clone();
            let budget = (self.texels_left, self.max_texture_side);
            let texture =
                super::image::load(opened, &map.path, map.sampler, budget).map_err(at_map)?;
            let (w, h) = texture.original_size();
            self.texels_left -= u64::from(w) * u64::from(h);
            let id = self.textures.len() as u32;
            self.textures.push(Arc::new(texture));
            self.texture_ids.insert(key, id);
            Ok(Some(id))
        }
        #[cfg(not(feature = "textures"))]
        {
            let _ = (
                &map.path,
                &map.sampler,
                &map.mtl,
                map.line,
                map.column,
                &map.why,
            );
            self.unread_textures += 1;
            Ok(None)
        }
    }

    /// `mtllib a.mtl b.mtl`: each file read in turn (or, if the names do
    /// not each exist, the whole rest of the line as one name with spaces).
    fn mtllib(&mut self, c: Cursor, n: usize) -> Result<()> {
        let line = c.line();
        let whole = c.clone().rest();
        let mut each = c;
        let words: Vec<(&[u8], usize)> = std::iter::from_fn(|| each.word()).collect();
        let found = |w: &[u8]| {
            file::reference(self.dir, self.name, &lossy(w))
                .path
                .exists()
        };
        let each_exists = words.iter().all(|(w, _)| found(w));
        let files: Vec<(&[u8], usize)> = if each_exists || words.is_empty() {
            words
        } else {
            vec![(whole, words[0].1)]
        };
        if files.is_empty() {
            return Err(self.at(n, 1, "`mtllib` names no file"));
        }
        for (file, col) in files {
            let r = file::reference(self.dir, self.name, &lossy(file));
            if !r.path.exists() {
                // Downloaded models often come without their library: the
                // faces are drawn in the default colour, and it is said.
                let at = self.at_byte(line, n, col, "");
                let what = match r.why {
                    Some(why) => format!("{why}; material library"),
                    None => format!("material library {}", crate::text::name(&lossy(file), 80)),
                };
                self.reference_notes
                    .push(format!("{at}{what} not found: drawn in the default colour"));
                continue;
            }
            // A library named again (on this line or another) is read once.
            let opened = self.files.open(&r.path)?;
            if !self.libraries.insert(opened.id().clone()) {
                continue;
            }
            self.reference_notes.extend(r.note);
            let (mtl, notes) = mtl(opened, &r.path, self.options)?;
            self.library.extend(mtl);
            self.reference_notes.extend(notes);
        }
        Ok(())
    }

    fn finish(mut self, last_line: usize) -> Result<Loaded> {
        let mut notes = std::mem::take(&mut self.reference_notes);
        if let Some(first) = self.first_unknown.take() {
            let more = match self.unknown_materials.len() - 1 {
                0 => String::new(),
                1 => " (nor is 1 other name `usemtl` gives)".to_string(),
                k => format!(" (nor are {k} other names `usemtl` gives)"),
            };
            notes.push(format!("{first}{more}: drawn in the default colour"));
        }
        notes.extend(polygon::fallback_note(self.name, &self.cutter));
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
        if self.unread_textures > 0 {
            notes.push(format!(
                "{}: {} textures not read (rastty was built without the `textures` feature)",
                self.name, self.unread_textures
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
        // Output vertices: the file's `v`, then the extra (v, vn) pairs,
        // then the vertices made while cutting polygons.
        let colored = !self.colors.is_empty();
        let keep_normals = self.all_normals;
        let vn = std::mem::take(&mut self.vn);
        // An attribute key's normal and texture coordinate.
        let normal = |a: u64| vn.get(a as u32 as usize).copied().unwrap_or(Vec3::Z);
        let vt = std::mem::take(&mut self.vt);
        let uv = |a: u64| vt.get((a >> 32) as usize).copied().unwrap_or(Vec2::ZERO);
        self.attr_of.resize(self.pos.len(), UNSET);
        let mut normals = Vec::new();
        if keep_normals {
            normals.reserve_exact(self.pos.len() + self.extra.len() + self.made.len());
            normals.extend(self.attr_of.iter().map(|&a| normal(a)));
            normals.extend(self.extra.iter().map(|&(_, a)| normal(a)));
            normals.extend(self.made.iter().map(|m| m.2));
        }
        let uvs = (!self.textures.is_empty()).then(|| {
            let mut uvs = Vec::with_capacity(self.pos.len() + self.extra.len() + self.made.len());
            uvs.extend(self.attr_of.iter().map(|&a| uv(a)));
            uvs.extend(self.extra.iter().map(|&(_, a)| uv(a)));
            uvs.extend(self.made.iter().map(|m| m.3));
            uvs
        });
        drop((vn, vt));
        self.attr_of = Vec::new();
        let mut positions = std::mem::take(&mut self.pos);
        let extra_base = positions.len() as u32;
        let made_base = extra_base + self.extra.len() as u32;
        positions.reserve_exact(self.extra.len() + self.made.len());
        for &(v, _) in &self.extra {
            positions.push(positions[v as usize]);
        }
        positions.extend(self.made.iter().map(|m| m.0));
        let colors = colored.then(|| {
            let mut c = std::mem::take(&mut self.colors);
            c.resize(extra_base as usize, Lin::WHITE);
            for &(v, _) in &self.extra {
                c.push(c[v as usize]);
            }
            c.extend(self.made.iter().map(|m| m.1));
            c
        });
        if !self.extra.is_empty() || !self.made.is_empty() {
            for i in self.triangles.iter_mut().flatten() {
                if *i & MADE != 0 {
                    *i = made_base + (*i & !MADE);
                } else if *i & EXTRA != 0 {
                    *i = extra_base + (*i & !EXTRA);
                }
            }
        }
        (self.extra, self.extra_ids, self.made) = Default::default();
        let mut g = Geometry::new_raw(self.name, positions, std::mem::take(&mut self.triangles));
        g.colors = colors;
        g.uvs = uvs;
        g.textures = self.textures;
        g.materials = self.materials;
        if keep_normals {
            g.normals = normals
                .into_iter()
                .map(crate::transform::direction)
                .collect();
            g.analyze();
        } else {
            g.compute_normals(self.options.crease);
        }
        Ok(Loaded { geometry: g, notes })
    }
}

/// The byte offset of the `k`th word after the keyword of `line` (a face
/// corner), for an error message.
fn corner_offset(line: &[u8], k: usize) -> usize {
    let mut c = Cursor::new(line);
    c.word();
    (0..k).for_each(|_| {
        c.word();
    });
    c.word().map_or(0, |(_, at)| at)
}

/// The `k`th word of `line` (from 0) and its offset.
fn c_word_at(line: &[u8], k: usize) -> (&[u8], usize) {
    let mut c = Cursor::new(line);
    (0..k).for_each(|_| {
        c.word();
    });
    c.word().unwrap_or((b"", line.len()))
}

/// A number, the whole of `w`, as the reader reads it.
#[cfg(test)]
fn number(w: &[u8]) -> Option<f32> {
    let mut c = Cursor::new(w);
    let x = c.number()?.ok();
    x.filter(|_| !c.more())
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
        assert_eq!(e(""), "t.obj:1:1: no faces in the file");
        assert_eq!(e("v 0 0 0\n"), "t.obj:1:1: no faces in the file");
    }
}
