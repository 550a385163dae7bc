//! Stage 1: the scene, and its TOML file format.
//!
//! The format is a contract (keep these names):
//!
//! ```toml
//! background = "#000000"          # optional; without it, uncovered cells keep the terminal's own background
//!
//! [camera]
//! projection = "perspective"      # "perspective" | "orthographic" | "none"
//! fov_y = 45.0                    # degrees, vertical field of view (perspective)
//! near = 0.1                      # distances in front of the eye (> 0 for perspective)
//! far = 100.0
//! eye = [0.0, 0.0, 5.0]
//! target = [0.0, 0.0, 0.0]
//! up = [0.0, 1.0, 0.0]
//! height = 2.0                    # orthographic: height of the view volume
//!
//! [[triangle]]                    # world coordinates
//! vertices = [[-0.5, -0.5, 0.0], [0.5, -0.5, 0.0], [0.0, 0.5, 0.0]]
//! color = "#ff8800"               # one colour, or:
//! # colors = ["#ff0000", "#00ff00", "#0000ff"]   # one per vertex, interpolated
//! ```
//!
//! Every key of `[camera]` is optional and defaults to the values above; a
//! file without `[camera]` gets that default camera. A triangle without a
//! colour is white. With `projection = "none"` vertices are already in the
//! canonical cube (x right, y up, larger z nearer).
//!
//! Meshes and lights:
//!
//! ```toml
//! [[mesh]]
//! path = "models/fox.obj"         # .obj (with its .mtl) or .stl, relative to the scene file
//! # shape = "torus"               # or a built-in shape instead of a path
//! color = "#cccccc"               # used where the file gives no colour
//! translate = [0.0, 0.0, 0.0]
//! rotate = [0.0, 30.0, 0.0]       # degrees about x, y, z
//! scale = 1.0
//! cull = "back"                   # "none" | "back" | "front"
//! clip = "walk"                   # a glTF model that moves: its clip, by name or number (default 0)
//! time = 1.5                      # seconds into the clip (default 0)
//!
//! [[light]]
//! direction = [-1.0, -1.0, -1.0]  # the direction the light travels
//! color = "#ffffff"
//! ambient = 0.15
//! intensity = 1.0                 # times the colour (at distance 1 for a point or a spot)
//!
//! [[light]]
//! kind = "spot"                   # "directional" (the default) | "point" | "spot"
//! position = [0.0, 3.0, 0.0]      # a point's or a spot's
//! direction = [0.0, -1.0, 0.0]    # a spot's: the middle of its cone
//! range = 10.0                    # optional: no light beyond
//! inner_cone = 10.0               # degrees: whole light within
//! outer_cone = 30.0               # degrees: none beyond (at most 90)
//! ```
//!
//! Parsing is strict: unknown keys, wrong types, a colour that is not
//! `#rrggbb`, non-finite numbers and impossible cameras are errors that
//! name the file, line and column. Mesh files' own errors name their file
//! and line.

pub mod anim;
pub mod environment;
mod load_options;
mod builder;
mod camera;
pub(crate) mod file;
mod lines;
mod finish;
mod load;
mod light;
mod mesh;
mod normals;
mod topology;
#[cfg(feature = "gltf")]
pub mod gltf;
#[cfg(feature = "textures")]
mod image;
pub mod obj;
#[cfg(feature = "ply")]
pub mod ply;
#[cfg(feature = "threemf")]
pub mod threemf;
mod polygon;
mod shapes;
#[cfg(feature = "gltf")]
mod tangents;
mod def;
pub mod stl;

use std::path::Path;

use std::sync::Arc;

use glam::{Mat4, Vec3, Vec4};
use rustc_hash::FxHashMap;
use serde::Deserialize;
use toml::Spanned;

pub use builder::SceneBuilder;
pub(crate) use camera::Fit;
pub use camera::{Camera, Projection, View};
use def::*;
pub use file::{FileId, Source};
pub use finish::{Alpha, AlphaMode, Clearcoat, Finish, Layers, Maps, Sheen, Sides, Specular};
pub use light::{Light, LightKind, MAX_LIGHTS};
pub use load::load_geometry;
use load::*;
pub(crate) use load::{Format, Kind};
pub use load_options::{DEFAULT_MAX_TEXELS, DEFAULT_MAX_TRIANGLES, LoadOptions, texture_side_for};
pub use mesh::{Cull, DEFAULT_CREASE, Geometry, MaterialRun, Mesh};
pub use shapes::Shape;

use crate::color::{ColorSpace, Rgb};
use crate::error::{Error, Result};
use crate::transform;

/// Everything there is to draw, in world coordinates. `Scene::default()`
/// is empty, seen by the default camera.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scene {
    /// The colour of uncovered samples; `None` keeps the terminal's own.
    pub background: Option<Rgb>,
    /// Where the scene is seen from.
    pub camera: Camera,
    /// Loose triangles, never culled.
    pub triangles: Vec<Triangle>,
    /// Meshes, each with its transform.
    pub meshes: Vec<Mesh>,
    /// Directional lights (none: colours are drawn unlit).
    pub lights: Vec<Light>,
    /// What metals reflect ([`environment`]): the neutral studio
    /// unless set.
    pub environment: crate::scene::environment::Environment,
    /// What loading found but did not draw (non-finite vertices, line
    /// elements…), one line each, for the user to be told.
    pub notes: Vec<String>,
    /// The files the scene was read from: the scene or model file and
    /// every file it names, each once (empty for a scene made in code).
    /// Whatever rastty writes is refused where it would replace one of
    /// them.
    pub sources: Vec<Source>,
}

/// A triangle and its colouring.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle {
    /// Corners in world space.
    pub vertices: [Vec3; 3],
    /// Its colouring.
    pub color: TriangleColor,
}

/// One colour for the whole triangle, or one per vertex, interpolated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TriangleColor {
    /// One colour.
    Flat(Rgb),
    /// A colour per vertex, interpolated.
    PerVertex([Rgb; 3]),
}

impl TriangleColor {
    /// The colour at each vertex.
    pub fn at_vertices(self) -> [Rgb; 3] {
        match self {
            TriangleColor::Flat(c) => [c; 3],
            TriangleColor::PerVertex(c) => c,
        }
    }
}

/// The smallest orthographic height accepted: with the narrowest view
/// (aspect 1/80,000), `2/width` still fits f32.
pub(crate) const MIN_HEIGHT: f32 = 1e-30;

/// Where a model shown alone is seen from: 30° to the right of its front
/// and 20° above, a unit away (the camera's fit sets the distance).
pub(crate) const THREE_QUARTER: Vec3 = Vec3::new(0.469_846_3, 0.342_020_1, 0.813_797_7);

/// The vertical field of view a model shown alone is seen with, degrees.
pub(crate) const MODEL_FOV: f32 = 30.0;

/// The pose a scene file's `clip` and `time` give a mesh: the first clip
/// at 0 s for a model that has clips and is given neither.
fn pose_of(
    mesh: &Mesh,
    clip: Option<ClipDef>,
    time: Option<f64>,
) -> std::result::Result<Option<anim::Pose>, String> {
    let clips = mesh.rig.as_ref().map_or(&[][..], |r| &r.clips[..]);
    if clips.is_empty() {
        return match (clip, time) {
            (None, None) => Ok(None),
            _ => Err(
                "`clip` and `time` are for a model that moves, and this one has no clips".into(),
            ),
        };
    }
    let time = time.unwrap_or(0.0);
    if !time.is_finite() {
        return Err("a mesh's `time` must be a finite number of seconds".into());
    }
    let clip = match clip {
        None => 0,
        Some(ClipDef::Number(n)) if (n as usize) < clips.len() => n as usize,
        Some(ClipDef::Number(n)) => {
            return Err(format!(
                "clip {n}: the model has {} clips, 0 to {}",
                clips.len(),
                clips.len() - 1
            ));
        }
        Some(ClipDef::Name(name)) => {
            clips.iter().position(|c| c.name == name).ok_or_else(|| {
                format!(
                    "no clip named {} in the model",
                    crate::text::name(&name, 40)
                )
            })?
        }
    };
    Ok(Some(anim::Pose { clip, time }))
}

/// How many poses of each clip a moving model is framed by: evenly
/// spaced through the clip.
const POSES_FRAMED: u32 = 32;

/// The most vertices posed to frame a moving model, over all its clips
/// (a few tenths of a second).
const FRAMING_BUDGET: u64 = 1 << 22;

/// The colour of a mesh whose file gives none.
pub const DEFAULT_MESH_COLOR: Rgb = Rgb::new(0xcc, 0xcc, 0xcc);

impl Scene {
    /// A scene of one model, as `rastty spin MODEL` shows it: centred,
    /// its y axis up, seen from a three-quarter view (
    /// 30° to the right, 20° above) through a 30° lens, framed to fill 90 %
    /// of the view's limiting dimension however it turns about y
    /// ([`Camera::resolved`]), under [`Light::rig`].
    pub fn of_mesh(mesh: Mesh) -> Scene {
        Scene::of_mesh_up(mesh, transform::Axis::Y)
    }

    /// [`Scene::of_mesh`] for a model whose `up` axis points up (STL files
    /// are z-up by convention).
    pub fn of_mesh_up(mut mesh: Mesh, up: transform::Axis) -> Scene {
        mesh.geometry_mut().fit_unit_sphere();
        // The model's up axis onto y, exactly (a permutation, no rounding):
        // z-up is turned −90° about x, (x, y, z) → (x, z, −y), so that its
        // front, −y, faces the viewer; x-up 90° about z, (x, y, z) →
        // (−y, x, z).
        mesh.model = match up {
            transform::Axis::X => Mat4::from_cols(Vec4::Y, -Vec4::X, Vec4::Z, Vec4::W),
            transform::Axis::Y => Mat4::IDENTITY,
            transform::Axis::Z => Mat4::from_cols(Vec4::X, -Vec4::Z, Vec4::Y, Vec4::W),
        };
        // The 13 axes are the same set after any turn of the up axis onto
        // y: the outline can be found before the turn. A model that moves
        // is framed by the union of its poses through every clip, so that
        // the camera holds still as it moves.
        let fit = Fit::of(&mesh.positions);
        let fit = match &mesh.rig {
            Some(rig) if !rig.clips.is_empty() => {
                let mut points = fit.points.to_vec();
                let mut posed = anim::Posed::default();
                let (mut ps, mut ns) = (mesh.positions.clone(), mesh.normals.clone());
                // Fewer poses a clip for a model of many clips and vertices:
                // the framing's work stays within a budget.
                let work = rig.clips.len() as u64 * mesh.positions.len().max(1) as u64;
                let poses = (FRAMING_BUDGET / work).clamp(1, u64::from(POSES_FRAMED)) as u32;
                for (c, clip) in rig.clips.iter().enumerate() {
                    for k in 0..poses {
                        let time = clip.length * f64::from(k) / f64::from(poses);
                        rig.pose_moving_into(
                            anim::Pose { clip: c, time },
                            &mut posed,
                            &mut ps,
                            &mut ns,
                        );
                        points.extend_from_slice(&Fit::of(&ps).points);
                    }
                }
                Fit::of(&points)
            }
            _ => fit,
        }
        .transformed(mesh.model);
        // The file's own lights where it places any (carried as the model
        // is: the up axis's turn is a permutation, no scaling), else the rig.
        let lights = if mesh.geometry.lights.is_empty() {
            Light::rig().to_vec()
        } else {
            let model = mesh.model;
            let own = mesh.geometry.lights.iter().take(MAX_LIGHTS);
            own.map(|l| l.transformed(model, 1.0)).collect()
        };
        Scene {
            background: None,
            camera: Camera {
                // A longer lens than the default: less of the near end's
                // swelling that makes a three-quarter view lopsided.
                projection: Projection::Perspective {
                    fov_y: MODEL_FOV,
                    near: 0.05,
                    far: 100.0,
                },
                eye: THREE_QUARTER,
                fit: Some(fit),
                ..Camera::default()
            },
            triangles: Vec::new(),
            meshes: vec![mesh],
            lights,
            environment: crate::scene::environment::Environment::Studio,
            notes: Vec::new(),
            sources: Vec::new(),
        }
    }

    /// Loose triangles already in the canonical cube (x right, y up, larger
    /// z nearer), seen through no camera: the viewport maps them straight
    /// onto the samples.
    pub fn in_canonical_cube(triangles: Vec<Triangle>) -> Scene {
        Scene {
            camera: Camera {
                projection: Projection::None,
                ..Camera::default()
            },
            triangles,
            ..Scene::default()
        }
    }

    /// The clips of the scene's first model that has any (empty when no
    /// model moves).
    pub fn clips(&self) -> &[anim::Clip] {
        self.meshes
            .iter()
            .filter_map(|m| m.rig.as_deref())
            .find(|r| !r.clips.is_empty())
            .map_or(&[], |r| &r.clips[..])
    }

    /// Adds to each moving model a clip that plays all its clips at once
    /// ([`anim::Rig::add_all_clips`]); returns its index in the first's
    /// clips ([`Scene::clips`]), `None` where no model moves.
    pub fn add_all_clips(&mut self) -> Option<usize> {
        let mut first = None;
        for mesh in &mut self.meshes {
            if mesh.rig.as_ref().is_some_and(|r| !r.clips.is_empty()) {
                let g = mesh.geometry_mut();
                if let Some(rig) = g.rig.as_mut() {
                    let i = Arc::make_mut(rig).add_all_clips();
                    first = first.or(Some(i));
                }
            }
        }
        first
    }

    /// Draws every moving model at `time` seconds into its clip `clip`
    /// (one without that clip at rest).
    pub fn set_pose(&mut self, clip: usize, time: f64) {
        for m in &mut self.meshes {
            m.pose = m
                .rig
                .as_ref()
                .filter(|r| clip < r.clips.len())
                .map(|_| anim::Pose { clip, time });
        }
    }

    /// A model file (`.obj` or `.stl`) or, when `name` is one, a built-in
    /// shape, as [`Scene::of_mesh`].
    pub fn of_model(name: &Path) -> Result<Scene> {
        Scene::of_model_within(name, &LoadOptions::default())
    }

    /// [`Scene::of_model`], the file read with `options`.
    pub fn of_model_within(name: &Path, options: &LoadOptions) -> Result<Scene> {
        let files = file::Files::new(options.max_bytes);
        let scene = Scene::of_model_in(name, options, &files)?;
        Ok(scene.read_from(&files))
    }

    /// `self` with the files it was read from and what reading them said.
    fn read_from(mut self, files: &file::Files) -> Scene {
        self.sources = files.sources();
        self.notes.extend(files.take_notes());
        self
    }

    /// [`Scene::of_model_within`], every file opened through `files`.
    fn of_model_in(name: &Path, options: &LoadOptions, files: &file::Files) -> Result<Scene> {
        let (format, note) = Format::of(name)?;
        let (geometry, notes) = load_as(name, format, note, options, files)?;
        // STL is z-up by convention, and 3MF by its spec; OBJ, glTF and
        // the shapes are y-up.
        let z_up = matches!(format, Format::Stl | Format::ThreeMf);
        let up = options.up.unwrap_or(if z_up {
            transform::Axis::Z
        } else {
            transform::Axis::Y
        });
        let mut scene = Scene::of_mesh_up(Mesh::of(geometry, DEFAULT_MESH_COLOR), up);
        scene.notes = notes;
        // A model that moves is drawn at the start of its first clip.
        if !scene.clips().is_empty() {
            scene.set_pose(0, 0.0);
        }
        Ok(scene)
    }

    /// What `path` names: a model, a scene, or (without an extension, when
    /// no such file exists) a built-in shape. See [`Format::of`].
    pub(crate) fn kind(path: &Path) -> Result<Kind> {
        Ok(match Format::of(path)?.0 {
            Format::Toml => Kind::Scene,
            _ => Kind::Model,
        })
    }

    /// Whether `path` names a model rather than a scene file, by the
    /// format its first bytes and its extension say (a TOML file is a
    /// scene; a built-in shape's name is a model).
    pub fn is_model(path: &Path) -> bool {
        matches!(Scene::kind(path), Ok(Kind::Model))
    }

    /// A scene file or a model, told apart as [`Scene::is_model`] says.
    pub fn open(path: &Path) -> Result<Scene> {
        Scene::open_within(path, &LoadOptions::default())
    }

    /// [`Scene::open`], every file read with `options`.
    pub fn open_within(path: &Path, options: &LoadOptions) -> Result<Scene> {
        let files = file::Files::new(options.max_bytes);
        let scene = match Scene::kind(path)? {
            Kind::Model => Scene::of_model_in(path, options, &files)?,
            Kind::Scene => Scene::load_in(path, options, &files)?,
        }
        .read_from(&files);
        // Loaders refuse what they would expand past the budget; a model
        // read whole is held to it too.
        let n = scene.triangle_count() as u64;
        if n > options.max_triangles {
            return Err(Error::Invalid(format!(
                "{}: {n} triangles, more than the triangle budget of {} (--max-triangles raises it)",
                path.display(),
                options.max_triangles
            )));
        }
        Ok(scene)
    }

    /// The number of triangles, loose and in meshes.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len() + self.meshes.iter().map(|m| m.faces.len()).sum::<usize>()
    }

    /// Reads and parses a scene file.
    pub fn load(path: &Path) -> Result<Scene> {
        Scene::load_within(path, &LoadOptions::default())
    }

    /// [`Scene::load`], every file read with `options`.
    pub fn load_within(path: &Path, options: &LoadOptions) -> Result<Scene> {
        let files = file::Files::new(options.max_bytes);
        let scene = Scene::load_in(path, options, &files)?;
        Ok(scene.read_from(&files))
    }

    /// [`Scene::load_within`], every file opened through `files`.
    fn load_in(path: &Path, options: &LoadOptions, files: &file::Files) -> Result<Scene> {
        let bytes = files.read(path)?;
        let name = path.display().to_string();
        let src = String::from_utf8(bytes).map_err(|e| {
            let text = String::from_utf8_lossy(e.as_bytes()).into_owned();
            Error::parse_at(&name, &text, e.utf8_error().valid_up_to(), "not UTF-8 text")
        })?;
        Scene::parse_in_files(&src, &name, path.parent(), options, files)
    }

    /// Parses a scene from TOML text; `name` is used in error messages.
    /// Mesh paths are taken relative to the current directory.
    pub fn parse(src: &str, name: &str) -> Result<Scene> {
        Scene::parse_in(src, name, None)
    }

    /// Parses a scene whose mesh paths are relative to `dir`.
    pub fn parse_in(src: &str, name: &str, dir: Option<&Path>) -> Result<Scene> {
        Scene::parse_with(src, name, dir, &LoadOptions::default())
    }

    /// Parses a scene whose mesh paths are relative to `dir`, its model
    /// files read with `options`.
    ///
    /// The text is read in chunks of whole tables of about 64 KiB, each
    /// deserialized on its own, so that memory stays a small multiple of
    /// the file (a TOML document tree of 200,000 triangles at once is 40
    /// times its text). A model file named by several meshes, and a shape,
    /// is loaded once and shared.
    pub fn parse_with(
        src: &str,
        name: &str,
        dir: Option<&Path>,
        options: &LoadOptions,
    ) -> Result<Scene> {
        let files = file::Files::new(options.max_bytes);
        let scene = Scene::parse_in_files(src, name, dir, options, &files)?;
        Ok(scene.read_from(&files))
    }

    /// [`Scene::parse_with`], every model file opened through `files`.
    fn parse_in_files(
        src: &str,
        name: &str,
        dir: Option<&Path>,
        options: &LoadOptions,
        files: &file::Files,
    ) -> Result<Scene> {
        let mut scene = Scene::default();
        let mut camera_at: Option<usize> = None;
        // Each model file once, however many meshes name it, by any name.
        let mut loaded: FxHashMap<file::FileId, Arc<Geometry>> = FxHashMap::default();
        // The budgets are the scene's: each model loaded spends texels
        // from what is left, each mesh placed spends its triangles.
        let mut options = *options;
        let mut placed: u64 = 0;
        // TOML allows no control character but tab anywhere, not even in
        // strings or comments: one scan refuses a binary file before the
        // parser makes anything of it.
        if let Some(at) = src
            .bytes()
            .position(|b| (b < 0x20 && !matches!(b, b'\t' | b'\n' | b'\r')) || b == 0x7f)
        {
            return Err(Error::parse_at(
                name,
                src,
                at,
                format!(
                    "a control character ({}), which TOML does not allow: is this a scene file?",
                    crate::text::escape(&src[at..at + 1])
                ),
            ));
        }
        for (start, end) in chunks(src, CHUNK) {
            let text = &src[start..end];
            let def: SceneDef = toml::from_str(text).map_err(|e| {
                let offset = start + e.span().map_or(0, |s| s.start);
                Error::parse_at(name, src, offset, e.message().trim_end())
            })?;
            let at = |span: std::ops::Range<usize>, msg: String| {
                Error::parse_at(name, src, start + span.start, msg)
            };
            if let Some(b) = def.background {
                scene.background = Some(b);
            }
            if let Some(c) = def.camera {
                let span = c.span();
                if camera_at.is_some() {
                    return Err(at(span, "a second [camera]: a scene has one".into()));
                }
                camera_at = Some(start + span.start);
                let camera = c.into_inner().into_camera();
                camera.check().map_err(|m| at(span, m))?;
                scene.camera = camera;
            }
            for t in def.triangle {
                let span = t.span();
                let t = t.into_inner();
                if t.vertices
                    .0
                    .iter()
                    .flat_map(|v| v.0)
                    .any(|c| !c.is_finite())
                {
                    return Err(at(span, "triangle vertices must be finite numbers".into()));
                }
                let color = match (t.color, t.colors) {
                    (Some(_), Some(_)) => {
                        return Err(at(
                            span,
                            "a triangle takes `color` or `colors`, not both".into(),
                        ));
                    }
                    (Some(c), None) => TriangleColor::Flat(c),
                    (None, Some(c)) => TriangleColor::PerVertex(c.0),
                    (None, None) => TriangleColor::Flat(Rgb::WHITE),
                };
                scene.triangles.push(Triangle {
                    vertices: t.vertices.0.map(Vec3::from),
                    color,
                });
            }
            for m in def.mesh {
                let span = m.span();
                let m = m.into_inner();
                let finite = Vec3::from(m.translate).is_finite()
                    && Vec3::from(m.rotate).is_finite()
                    && m.scale.vec().is_finite();
                if !finite {
                    return Err(at(
                        span,
                        "mesh translate, rotate and scale must be finite numbers".into(),
                    ));
                }
                let color = m.color.unwrap_or(DEFAULT_MESH_COLOR);
                let geometry = match (&m.path, &m.shape) {
                    (Some(p), None) => {
                        let p = dir.map_or_else(|| Path::new(p).to_path_buf(), |d| d.join(p));
                        if Scene::kind(&p)? != Kind::Model || p.extension().is_none() {
                            return Err(at(
                                span,
                                format!(
                                    "{}: a mesh's path names a model file (.obj or .stl)",
                                    p.display()
                                ),
                            ));
                        }
                        let id = file::FileId::at(&p);
                        match id.as_ref().and_then(|id| loaded.get(id)) {
                            Some(g) => Arc::clone(g),
                            None => {
                                let (g, notes) = load_geometry_in(&p, &options, files)?;
                                options.max_texels =
                                    options.max_texels.saturating_sub(texels_of(&g));
                                scene.notes.extend(notes);
                                if let Some(id) = id {
                                    loaded.insert(id, Arc::clone(&g));
                                }
                                g
                            }
                        }
                    }
                    (None, Some(s)) => Shape::from_name(s)
                        .ok_or_else(|| {
                            at(
                                span.clone(),
                                match Shape::nearest(s) {
                                    Some(near) => format!(
                                        "unknown shape {s:?}: did you mean \"{}\"? (the shapes are \"cube\", \"sphere\" and \"torus\")",
                                        near.name()
                                    ),
                                    None => format!(
                                        "unknown shape {s:?}: expected \"cube\", \"sphere\" or \"torus\""
                                    ),
                                },
                            )
                        })?
                        .geometry(),
                    _ => {
                        return Err(at(
                            span,
                            "a mesh takes `path` or `shape`, exactly one".into(),
                        ));
                    }
                };
                placed += geometry.faces.len() as u64;
                if placed > options.max_triangles {
                    return Err(at(
                        span,
                        format!(
                            "the scene places {placed} triangles by this mesh, more than the triangle budget of {} (--max-triangles raises it)",
                            options.max_triangles
                        ),
                    ));
                }
                let mut mesh = Mesh::of(geometry, color);
                mesh.model =
                    transform::model(m.scale.vec(), Vec3::from(m.rotate), Vec3::from(m.translate));
                if let Some(cull) = m.cull {
                    mesh.cull = cull.into();
                }
                mesh.pose = pose_of(&mesh, m.clip, m.time).map_err(|e| at(span, e))?;
                scene.meshes.push(mesh);
            }
            for l in def.light {
                let span = l.span();
                if scene.lights.len() == MAX_LIGHTS {
                    return Err(at(span, format!("at most {} lights", MAX_LIGHTS)));
                }
                let light = light_of(l.into_inner()).map_err(|e| at(span.clone(), e))?;
                light.check().map_err(|e| at(span, e))?;
                scene.lights.push(Light {
                    direction: light.direction.normalize(),
                    ..light
                });
            }
        }
        if scene.triangles.is_empty() && scene.meshes.is_empty() {
            return Err(Error::parse_at(
                name,
                src,
                0,
                "nothing to draw: no [[triangle]] or [[mesh]]",
            ));
        }
        Ok(scene)
    }
}

/// A scene file's `[[light]]`: a directional light needs a direction, a
/// point light a position, a spot both (its cone in degrees, glTF's
/// defaults 0° and 45°).
fn light_of(l: LightDef) -> std::result::Result<Light, String> {
    let position = l.position.map(Vec3::from);
    let direction = l.direction.map(Vec3::from);
    let needs = |kind: &str, keys: &str| format!("a {kind} light needs {keys}");
    let kind = match l.kind {
        LightKindDef::Directional => {
            if position.is_some() || l.range.is_some() {
                return Err("a directional light has no `position` or `range`".into());
            }
            LightKind::Directional
        }
        LightKindDef::Point => LightKind::Point {
            position: position.ok_or_else(|| needs("point", "`position`"))?,
            range: l.range,
        },
        LightKindDef::Spot => LightKind::Spot {
            position: position.ok_or_else(|| needs("spot", "`position` and `direction`"))?,
            range: l.range,
            inner: l.inner_cone.unwrap_or(0.0).to_radians(),
            outer: l.outer_cone.unwrap_or(45.0).to_radians(),
        },
    };
    if l.kind != LightKindDef::Spot && (l.inner_cone.is_some() || l.outer_cone.is_some()) {
        return Err("only a spot light has `inner_cone` and `outer_cone`".into());
    }
    let direction = match (l.kind, direction) {
        (LightKindDef::Point, None) => Vec3::NEG_Y,
        (LightKindDef::Point, Some(_)) => return Err("a point light has no `direction`".into()),
        (LightKindDef::Directional, None) => return Err(needs("directional", "`direction`")),
        (LightKindDef::Spot, None) => return Err(needs("spot", "`position` and `direction`")),
        (_, Some(d)) => d,
    };
    Ok(Light {
        direction,
        color: l.color,
        ambient: l.ambient,
        kind,
        intensity: l.intensity,
    })
}

/// The texels a model's images held as decoded, as the texel budget counts
/// them.
fn texels_of(g: &Geometry) -> u64 {
    g.textures
        .iter()
        .map(|t| {
            let (w, h) = t.original_size();
            u64::from(w) * u64::from(h)
        })
        .sum()
}

/// The scene `rastty render` draws when it is given none.
pub const DEFAULT_SCENE: &str = include_str!("../../examples/scenes/default.toml");

/// [`DEFAULT_SCENE`], parsed.
pub fn default_scene() -> Scene {
    Scene::parse(DEFAULT_SCENE, "<built-in default scene>").expect("the built-in scene parses")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(src: &str) -> String {
        Scene::parse(src, "s.toml").unwrap_err().to_string()
    }

    #[test]
    fn an_unknown_shape_suggests_the_nearest() {
        assert_eq!(
            err("[[mesh]]\nshape = \"torsu\"\n"),
            "s.toml:1:1: unknown shape \"torsu\": did you mean \"torus\"? (the shapes are \"cube\", \"sphere\" and \"torus\")"
        );
        assert_eq!(
            err("[[mesh]]\nshape = \"teapot\"\n"),
            "s.toml:1:1: unknown shape \"teapot\": expected \"cube\", \"sphere\" or \"torus\""
        );
    }

    #[test]
    fn parses_the_documented_example() {
        let src = include_str!("../../examples/scenes/triangle.toml");
        let s = Scene::parse(src, "triangle.toml").unwrap();
        assert_eq!(s.background, Some(Rgb::BLACK));
        assert_eq!(s.triangles.len(), 1);
        assert_eq!(
            s.triangles[0].color,
            TriangleColor::Flat(Rgb([0xff, 0x88, 0]))
        );
        assert_eq!(s.camera, Camera::default());
    }

    #[test]
    fn defaults_and_per_vertex_colours() {
        let s = Scene::parse(
            "[[triangle]]\nvertices = [[0,0,0],[1,0,0],[0,1,0]]\ncolors = [\"#ff0000\", \"#00ff00\", \"#0000ff\"]\n",
            "s",
        );
        // Integers are taken where floats are expected.
        assert_eq!(s.unwrap().triangles[0].vertices[1], Vec3::X);
        let s = Scene::parse(
            "[[triangle]]\nvertices = [[0.0,0.0,0.0],[1.0,0.0,0.0],[0.0,1.0,0.0]]\ncolors = [\"#ff0000\", \"#00ff00\", \"#0000ff\"]\n",
            "s",
        )
        .unwrap();
        assert_eq!(s.background, None);
        assert!(matches!(s.triangles[0].color, TriangleColor::PerVertex(_)));
    }

    #[test]
    fn errors_name_the_file_line_and_key() {
        let e = err("background = \"#000000\"\nbogus = 1\n");
        assert!(e.starts_with("s.toml:2:1: unknown field `bogus`"), "{e}");
        let e = err("[camera]\nfov_y = \"wide\"\n");
        assert!(e.starts_with("s.toml:2:9: "), "{e}");
        let e = err("background = \"black\"\n");
        assert!(e.contains("s.toml:1:14: invalid colour \"black\""), "{e}");
        let e = err("[camera]\nprojection = \"fisheye\"\n");
        assert!(
            e.starts_with("s.toml:2:14: unknown variant `fisheye`"),
            "{e}"
        );
        let e = err("[[triangle]]\nvertices = [[0.0,0.0,0.0],[1.0,0.0,0.0]]\n");
        assert!(e.starts_with("s.toml:2:12: "), "{e}");
        let e = err("x = [\n");
        assert!(e.starts_with("s.toml:"), "{e}");
    }

    #[test]
    fn semantic_errors_point_at_their_table() {
        let e = err("# c\n[camera]\nnear = 0.0\n");
        assert!(e.starts_with("s.toml:2:1: near must be > 0"), "{e}");
        let e = err("[camera]\nfar = 0.05\n");
        assert!(
            e.contains("far (0.05) must be finite and greater than near (0.1)"),
            "{e}"
        );
        let e = err("[camera]\nup = [0.0, 0.0, 1.0]\n");
        assert!(e.contains("up must not be parallel"), "{e}");
        let e = err("\n[[triangle]]\nvertices = [[nan,0.0,0.0],[1.0,0.0,0.0],[0.0,1.0,0.0]]\n");
        assert!(
            e.starts_with("s.toml:2:1: triangle vertices must be finite"),
            "{e}"
        );
        let e = err(
            "[[triangle]]\nvertices = [[0.0,0.0,0.0],[1.0,0.0,0.0],[0.0,1.0,0.0]]\ncolor = \"#ffffff\"\ncolors = [\"#ff0000\", \"#00ff00\", \"#0000ff\"]\n",
        );
        assert!(e.contains("not both"), "{e}");
    }
}
