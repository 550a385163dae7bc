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
//!
//! [[light]]
//! direction = [-1.0, -1.0, -1.0]  # the direction the light travels
//! color = "#ffffff"
//! ambient = 0.15
//! ```
//!
//! Parsing is strict: unknown keys, wrong types, a colour that is not
//! `#rrggbb`, non-finite numbers and impossible cameras are errors that
//! name the file, line and column. Mesh files' own errors name their file
//! and line.

mod builder;
mod file;
mod mesh;
#[cfg(feature = "gltf")]
pub mod gltf;
#[cfg(feature = "textures")]
pub mod image;
pub mod obj;
#[cfg(feature = "ply")]
pub mod ply;
mod polygon;
mod shapes;
pub mod stl;

use std::path::Path;

use std::sync::Arc;

use glam::{Mat4, Vec3, Vec4};
use rustc_hash::FxHashMap;
use serde::Deserialize;
use toml::Spanned;

pub use builder::SceneBuilder;
pub use mesh::{Cull, DEFAULT_CREASE, Geometry, Light, MAX_LIGHTS, MaterialRun, Mesh, Run};
pub use shapes::Shape;
pub use transform::Axis;

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
    /// What loading found but did not draw (non-finite vertices, line
    /// elements…), one line each, for the user to be told.
    pub notes: Vec<String>,
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

/// Where the viewer stands and how the view is projected.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// How the view is projected.
    pub projection: Projection,
    /// Where the eye is.
    pub eye: Vec3,
    /// What it looks at.
    pub target: Vec3,
    /// Which way is up.
    pub up: Vec3,
    /// Frame a model: with this, `eye − target` is a direction and a zoom
    /// (length 1: the model just fits), and the eye's distance is chosen
    /// for each view's aspect ([`Camera::resolved`]).
    pub fit: Option<Fit>,
}

/// What a camera frames: a model's outline, as the points of the model
/// farthest out both ways along 13 axes (the coordinate axes, the face
/// diagonals and the space diagonals of a cube: a 26-sided hull that hugs
/// the model's convex hull, found with additions alone), so that the
/// model's projected extent can be found for any view in a few hundred
/// operations.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fit {
    /// The outline's points.
    pub points: [Vec3; Fit::POINTS],
}

impl Fit {
    /// How many extreme points are kept: two for each of 13 axes.
    pub const POINTS: usize = 26;
    /// The share of the view's limiting dimension a framed model fills.
    pub const FILL: f32 = 0.9;

    /// The outline of `points` (at least one).
    pub fn of(points: &[Vec3]) -> Fit {
        // Along each axis, unnormalised (only the order matters), padded
        // to 16 lanes so that the comparisons below go four at a time.
        let along = |p: Vec3| -> [f32; 16] {
            [
                p.x,
                p.y,
                p.z,
                p.x + p.y,
                p.x - p.y,
                p.x + p.z,
                p.x - p.z,
                p.y + p.z,
                p.y - p.z,
                p.x + p.y + p.z,
                p.x + p.y - p.z,
                p.x - p.y + p.z,
                -p.x + p.y + p.z,
                0.0,
                0.0,
                0.0,
            ]
        };
        let (mut lo, mut hi) = ([f32::INFINITY; 16], [f32::NEG_INFINITY; 16]);
        let (mut lo_at, mut hi_at) = ([0u32; 16], [0u32; 16]);
        for (i, &p) in points.iter().enumerate() {
            if !p.is_finite() {
                continue;
            }
            let s = along(p);
            for k in 0..16 {
                let (below, above) = (s[k] < lo[k], s[k] > hi[k]);
                lo[k] = if below { s[k] } else { lo[k] };
                lo_at[k] = if below { i as u32 } else { lo_at[k] };
                hi[k] = if above { s[k] } else { hi[k] };
                hi_at[k] = if above { i as u32 } else { hi_at[k] };
            }
        }
        let at = |i: u32| points.get(i as usize).copied().unwrap_or(Vec3::ZERO);
        Fit {
            points: std::array::from_fn(|i| {
                if i < 13 {
                    at(lo_at[i])
                } else {
                    at(hi_at[i - 13])
                }
            }),
        }
    }

    /// The outline moved by `m`; exact for a turn that takes the 13 axes
    /// to themselves (a model's up axis turned onto y).
    pub fn transformed(self, m: Mat4) -> Fit {
        Fit {
            points: self.points.map(|p| m.transform_point3(p)),
        }
    }
}

/// The projection into the canonical cube.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// `fov_y` in degrees; `near` and `far` are distances in front of the
    /// eye, `0 < near < far`.
    Perspective {
        /// The vertical field of view, in degrees.
        fov_y: f32,
        /// The near plane's distance.
        near: f32,
        /// The far plane's distance.
        far: f32,
    },
    /// A box `height` tall, as wide as the aspect makes it.
    Orthographic {
        /// The box's height in world units.
        height: f32,
        /// The near plane's distance.
        near: f32,
        /// The far plane's distance.
        far: f32,
    },
    /// The vertices are in the canonical cube already; eye, target and up
    /// are ignored.
    None,
}

impl Default for Camera {
    fn default() -> Self {
        Camera {
            projection: Projection::Perspective {
                fov_y: 45.0,
                near: 0.1,
                far: 100.0,
            },
            eye: Vec3::new(0.0, 0.0, 5.0),
            target: Vec3::ZERO,
            up: Vec3::Y,
            fit: None,
        }
    }
}

impl Camera {
    /// This camera moved around its target: the eye turned `yaw` degrees
    /// about the up axis and `pitch` degrees towards it, and its distance
    /// from the target multiplied by `zoom`. What `spin`'s arrow keys and
    /// the ratatui viewer's mouse do.
    #[must_use]
    pub fn orbited(&self, yaw: f32, pitch: f32, zoom: f32) -> Camera {
        let offset = (self.eye - self.target) * zoom;
        let yaw = glam::Quat::from_axis_angle(self.up.normalize_or_zero(), yaw.to_radians());
        let right = offset.cross(self.up).normalize_or_zero();
        let pitch = glam::Quat::from_axis_angle(right, pitch.to_radians());
        Camera {
            eye: self.target + yaw * (pitch * offset),
            ..*self
        }
    }

    /// Whether two cameras are the same bit for bit (`==` takes −0 for 0):
    /// then [`Camera::resolved`] gives the same camera for both.
    pub(crate) fn same_bits(&self, o: &Camera) -> bool {
        let v = |v: Vec3| v.to_array().map(f32::to_bits);
        let p = |p: Projection| match p {
            Projection::Perspective { fov_y, near, far } => {
                [1, fov_y.to_bits(), near.to_bits(), far.to_bits()]
            }
            Projection::Orthographic { height, near, far } => {
                [2, height.to_bits(), near.to_bits(), far.to_bits()]
            }
            Projection::None => [0; 4],
        };
        let fit = |f: Option<Fit>| f.map(|f| f.points.map(v));
        p(self.projection) == p(o.projection)
            && [self.eye, self.target, self.up].map(v) == [o.eye, o.target, o.up].map(v)
            && fit(self.fit) == fit(o.fit)
    }

    /// This camera for a view of `aspect` (width over height): where it
    /// frames a model ([`Camera::fit`]), the eye moved along `eye − target`
    /// to the distance at which the model's outline, turned any way about
    /// the y axis (as `spin` and `--yaw` turn it), fills [`Fit::FILL`] of
    /// the view's height or width, whichever limits, times the length of
    /// `eye − target` (the zoom); and moved up or down to centre it (not
    /// sideways, so that the turn's axis stays in the middle). Every frame
    /// of a turn is then framed the same and none is cut off; a model
    /// round about its axis fills 90 %, a long one less in any one view.
    /// Otherwise the camera as it is.
    pub fn resolved(&self, aspect: f32) -> Camera {
        let (Some(fit), Projection::Perspective { fov_y, .. }) = (self.fit, self.projection) else {
            return Camera { fit: None, ..*self };
        };
        let offset = self.eye - self.target;
        let zoom = offset.length();
        let back = offset / zoom;
        let right = back.cross(self.up).normalize_or_zero();
        let right = if right == Vec3::ZERO { Vec3::X } else { right };
        let up = right.cross(back);
        let t = (fov_y.to_radians() / 2.0).tan() * Fit::FILL;
        let (kx, ky) = (t * aspect.max(1e-6), t);
        // The outline turned every way about y (as `spin` turns it), 16
        // steps a turn: the framing holds for every frame.
        let target = self.target;
        let outline = &fit.points;
        let swept = || {
            (0..16).flat_map(move |k| {
                let turn = glam::Quat::from_rotation_y(std::f32::consts::TAU * k as f32 / 16.0);
                outline.iter().map(move |&p| turn * p - target)
            })
        };
        // A point p at distance d projects to x / (d − z), which must stay
        // within kx (and y within ky): d ≥ z + |x| / kx. Seen from above
        // (or below) the projection is lopsided, so the view is also moved
        // up or down by `lift`, to centre it (not sideways: the turn's axis
        // stays in the middle).
        let fits = |lift: f32| {
            swept().fold(0.0f32, |d, p| {
                let z = p.dot(back);
                d.max(z + p.dot(right).abs() / kx)
                    .max(z + (p.dot(up) - lift).abs() / ky)
            })
        };
        let mut lift = 0.0f32;
        let mut d = fits(lift);
        for _ in 0..4 {
            // Where the projection's top and bottom are at this distance,
            // as heights at the target's depth.
            let (lo, hi) = swept().fold((f32::MAX, f32::MIN), |(lo, hi), p| {
                let y = (p.dot(up) - lift) * d / (d - p.dot(back));
                (lo.min(y), hi.max(y))
            });
            if !(lo.is_finite() && hi.is_finite()) {
                break;
            }
            lift += (lo + hi) / 2.0;
            d = fits(lift);
        }
        let (d, lift) = if d.is_finite() && d > 0.0 && lift.is_finite() {
            (d, lift)
        } else {
            (1.0, 0.0)
        };
        let target = self.target + up * lift;
        Camera {
            eye: target + back * d * zoom,
            target,
            fit: None,
            ..*self
        }
    }

    /// `M_projection · M_view` for a view whose physical width/height ratio
    /// is `aspect`, composed in f64 and rounded once to f32 (so that an eye
    /// 1e30 away, or a scene 1e-30 across, loses nothing in the product).
    pub fn view_projection(&self, aspect: f32) -> Mat4 {
        self.view_projection64(aspect).as_mat4()
    }

    /// [`Camera::view_projection`] in f64.
    pub fn view_projection64(&self, aspect: f32) -> glam::DMat4 {
        let view = transform::view64(
            self.eye.as_dvec3(),
            self.target.as_dvec3(),
            self.up.as_dvec3(),
        );
        let aspect = aspect as f64;
        match self.projection {
            Projection::Perspective { fov_y, near, far } => {
                transform::perspective64(fov_y as f64, aspect, near as f64, far as f64) * view
            }
            Projection::Orthographic { height, near, far } => {
                transform::orthographic64(height as f64, aspect, near as f64, far as f64) * view
            }
            Projection::None => glam::DMat4::IDENTITY,
        }
    }

    /// Why this camera cannot be used, if it cannot. Judged by direction and
    /// by relative size (in f64), never by absolute size: an eye 1e30 away
    /// and one 1e-30 from its target are both fine.
    pub fn check(&self) -> std::result::Result<(), String> {
        let finite = [self.eye, self.target, self.up]
            .iter()
            .all(|v| v.is_finite());
        if !finite {
            return Err("camera eye, target and up must be finite".into());
        }
        let (near, far) = match self.projection {
            Projection::None => return Ok(()),
            Projection::Perspective { fov_y, near, far } => {
                if !(fov_y > 0.0 && fov_y < 180.0) {
                    return Err(format!(
                        "fov_y must be between 0 and 180 degrees, not {fov_y}"
                    ));
                }
                if near.is_nan() || near <= 0.0 {
                    return Err(format!(
                        "near must be > 0 for a perspective camera, not {near}"
                    ));
                }
                if near < f32::MIN_POSITIVE {
                    return Err(format!(
                        "near = {near:e} is subnormal: f32 keeps no precision there; use a near of at least {:e} (scale the scene up if it is that small)",
                        f32::MIN_POSITIVE
                    ));
                }
                (near, far)
            }
            Projection::Orthographic { height, near, far } => {
                if !(height > 0.0 && height.is_finite()) {
                    return Err(format!("height must be > 0, not {height}"));
                }
                if height < MIN_HEIGHT {
                    return Err(format!(
                        "height = {height:e} is too small: the projection's scale 2/height overflows f32 in a narrow view; use a height of at least {MIN_HEIGHT:e} (scale the scene up if it is that small)"
                    ));
                }
                (near, far)
            }
        };
        if !(far > near && far.is_finite() && near.is_finite()) {
            return Err(format!(
                "far ({far}) must be finite and greater than near ({near})"
            ));
        }
        let (eye, target, up) = (
            self.eye.as_dvec3(),
            self.target.as_dvec3(),
            self.up.as_dvec3(),
        );
        let forward = target - eye;
        if forward == glam::DVec3::ZERO {
            return Err(format!(
                "camera eye and target are the same point, {}",
                self.eye
            ));
        }
        if up == glam::DVec3::ZERO {
            return Err("camera up must not be zero".into());
        }
        // The angle between up and the view direction, scale-free.
        let sin = forward.normalize().cross(up.normalize()).length();
        if sin.is_nan() || sin <= 1e-6 {
            return Err(
                "camera up must not be parallel to the view direction (target − eye)".into(),
            );
        }
        Ok(())
    }
}

/// How model and scene files are read.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoadOptions {
    /// The largest file read, in bytes (a larger one is refused before it
    /// is opened).
    pub max_bytes: u64,
    /// How MTL `Kd` numbers are read: linear light by default, as
    /// exporters write them.
    pub mtl_colors: ColorSpace,
    /// The crease angle of computed normals, in degrees: faces meeting at
    /// a sharper angle keep their own normals along the edge.
    pub crease: f32,
    /// For a model shown alone: which of its axes points up (`None`: the
    /// format's convention, y for OBJ, z for STL).
    pub up: Option<transform::Axis>,
    /// The most texels decoded, across all of a scene's images
    /// ([`DEFAULT_MAX_TEXELS`]); each costs its linear texel, its mipmaps'
    /// share and, while it is decoded, its 8-bit pixel. An image's size is
    /// read from its header and refused before it is decoded.
    pub max_texels: u64,
    /// The most triangles a scene may draw once every glTF node and every
    /// scene mesh is counted as often as it is placed
    /// ([`DEFAULT_MAX_TRIANGLES`]), counted before anything is expanded.
    pub max_triangles: u64,
}

/// The default texel budget: 64 Mi texels (an 8192² image, or four of
/// 4096²), about 1 GiB of linear texels with their mipmaps.
pub const DEFAULT_MAX_TEXELS: u64 = 1 << 26;
/// The default triangle budget: 256 Mi triangles placed (the largest
/// shared model has 41 thousand; a frame of that many takes seconds).
pub const DEFAULT_MAX_TRIANGLES: u64 = 1 << 28;

impl Default for LoadOptions {
    fn default() -> Self {
        LoadOptions {
            max_bytes: file::DEFAULT_MAX_BYTES,
            mtl_colors: ColorSpace::Linear,
            crease: mesh::DEFAULT_CREASE,
            up: None,
            max_texels: DEFAULT_MAX_TEXELS,
            max_triangles: DEFAULT_MAX_TRIANGLES,
        }
    }
}

/// The smallest orthographic height accepted: with the narrowest view
/// (aspect 1/80,000), `2/width` still fits f32.
pub const MIN_HEIGHT: f32 = 1e-30;

/// Where a model shown alone is seen from: 30° to the right of its front
/// and 20° above, a unit away (the camera's fit sets the distance).
pub const THREE_QUARTER: Vec3 = Vec3::new(0.469_846_3, 0.342_020_1, 0.813_797_7);

/// The vertical field of view a model shown alone is seen with, degrees.
pub const MODEL_FOV: f32 = 30.0;

/// The colour of a mesh whose file gives none.
pub const DEFAULT_MESH_COLOR: Rgb = Rgb::new(0xcc, 0xcc, 0xcc);

impl Scene {
    /// A scene of one model, as `rastty spin MODEL` shows it: centred,
    /// its y axis up, seen from a three-quarter view ([`THREE_QUARTER`]:
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
        // y: the outline can be found before the turn.
        let fit = Fit::of(&mesh.positions).transformed(mesh.model);
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
            lights: Light::rig().to_vec(),
            notes: Vec::new(),
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

    /// A model file (`.obj` or `.stl`) or, when `name` is one, a built-in
    /// shape, as [`Scene::of_mesh`].
    pub fn of_model(name: &Path) -> Result<Scene> {
        Scene::of_model_within(name, &LoadOptions::default())
    }

    /// [`Scene::of_model`], the file read with `options`.
    pub fn of_model_within(name: &Path, options: &LoadOptions) -> Result<Scene> {
        let (format, note) = Format::of(name)?;
        let (geometry, notes) = load_as(name, format, note, options)?;
        // STL is z-up by convention; OBJ and the shapes are y-up.
        let stl = format == Format::Stl;
        let up = options.up.unwrap_or(if stl {
            transform::Axis::Z
        } else {
            transform::Axis::Y
        });
        let mut scene = Scene::of_mesh_up(Mesh::of(geometry, DEFAULT_MESH_COLOR), up);
        scene.notes = notes;
        Ok(scene)
    }

    /// What `path` names: a model, a scene, or (without an extension, when
    /// no such file exists) a built-in shape. See [`Format::of`].
    pub fn kind(path: &Path) -> Result<Kind> {
        Ok(match Format::of(path)?.0 {
            Format::Toml => Kind::Scene,
            _ => Kind::Model,
        })
    }

    /// Whether `path` names a model rather than a scene file (see
    /// [`Scene::kind`]).
    pub fn is_model(path: &Path) -> bool {
        matches!(Scene::kind(path), Ok(Kind::Model))
    }

    /// A scene file or a model, told apart by [`Scene::kind`].
    pub fn open(path: &Path) -> Result<Scene> {
        Scene::open_within(path, &LoadOptions::default())
    }

    /// [`Scene::open`], every file read with `options`.
    pub fn open_within(path: &Path, options: &LoadOptions) -> Result<Scene> {
        let scene = match Scene::kind(path)? {
            Kind::Model => Scene::of_model_within(path, options)?,
            Kind::Scene => Scene::load_within(path, options)?,
        };
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
        use std::io::Read;
        let (mut f, size) = file::open(path, options.max_bytes)?;
        let mut bytes = Vec::with_capacity(size as usize);
        f.read_to_end(&mut bytes).map_err(|e| Error::io(path, e))?;
        let name = path.display().to_string();
        let src = String::from_utf8(bytes).map_err(|e| {
            let text = String::from_utf8_lossy(e.as_bytes()).into_owned();
            Error::parse_at(&name, &text, e.utf8_error().valid_up_to(), "not UTF-8 text")
        })?;
        Scene::parse_with(&src, &name, path.parent(), options)
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
        let mut scene = Scene::default();
        let mut camera_at: Option<usize> = None;
        let mut loaded: FxHashMap<std::path::PathBuf, Arc<Geometry>> = FxHashMap::default();
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
                        match loaded.get(&p) {
                            Some(g) => Arc::clone(g),
                            None => {
                                let (g, notes) = load_geometry(&p, &options)?;
                                options.max_texels =
                                    options.max_texels.saturating_sub(texels_of(&g));
                                scene.notes.extend(notes);
                                loaded.insert(p, Arc::clone(&g));
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
                scene.meshes.push(mesh);
            }
            for l in def.light {
                let span = l.span();
                if scene.lights.len() == MAX_LIGHTS {
                    return Err(at(span, format!("at most {} lights", MAX_LIGHTS)));
                }
                let l = l.into_inner();
                let light = Light {
                    direction: Vec3::from(l.direction),
                    color: l.color,
                    ambient: l.ambient,
                };
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

/// A file's format, as its extension says or, where that is missing or
/// lies, as its first bytes say.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Wavefront OBJ.
    Obj,
    /// STL, binary or ASCII.
    Stl,
    /// glTF, as JSON or GLB.
    Gltf,
    /// PLY.
    Ply,
    /// A scene file.
    Toml,
    /// A built-in shape named without an extension.
    Shape(Shape),
}

impl Format {
    /// The format of `path`, and a note when its first bytes overrule its
    /// extension. An extension is believed unless the file starts with
    /// another format's signature (GLB's `glTF`, PLY's `ply`, a binary
    /// STL whose facet count gives its exact size, glTF's JSON object);
    /// without one, a name like a shape's is the shape (when no such
    /// file exists), and a file is told by its first bytes (OBJ
    /// statements, `solid`, a TOML table or key). A file that is none of
    /// them, or a shape misspelt, is an error saying so.
    pub fn of(path: &Path) -> Result<(Format, Option<String>)> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let named = match ext.as_deref() {
            Some("obj") => Some(Format::Obj),
            Some("stl") => Some(Format::Stl),
            #[cfg(feature = "gltf")]
            Some("gltf" | "glb") => Some(Format::Gltf),
            #[cfg(feature = "ply")]
            Some("ply") => Some(Format::Ply),
            Some("toml") => Some(Format::Toml),
            _ => None,
        };
        let regular = std::fs::metadata(path).is_ok_and(|m| m.is_file());
        let head = if regular { head(path) } else { Vec::new() };
        let (signed, guessed) = sniff(&head);
        match (named, ext.as_deref()) {
            (Some(named), _) => match signed {
                Some(actual) if actual != named && readable(actual) => Ok((
                    actual,
                    Some(format!(
                        "{}: read as {} (its first bytes say so), not as its name says",
                        path.display(),
                        actual.name()
                    )),
                )),
                _ => Ok((named, None)),
            },
            (None, Some(other)) if signed.is_none() => Err(Error::Invalid(format!(
                "{}: rastty does not read .{other} files; it reads models ({MODELS}), scenes (.toml) and the shapes cube, sphere and torus",
                path.display()
            ))),
            (None, _) => {
                if !path.exists() {
                    if let Some(shape) = path.to_str().and_then(Shape::from_name) {
                        return Ok((Format::Shape(shape), None));
                    }
                    if let Some(near) = path.to_str().and_then(Shape::nearest) {
                        return Err(Error::Invalid(format!(
                            "{}: no such file or shape; did you mean {}?",
                            path.display(),
                            near.name()
                        )));
                    }
                    // Not there: reading it as a scene says so.
                    return Ok((Format::Toml, None));
                }
                match signed.or(guessed) {
                    Some(f) if readable(f) => Ok((
                        f,
                        ext.map(|_| {
                            format!(
                                "{}: read as {} (its first bytes say so), not as its name says",
                                path.display(),
                                f.name()
                            )
                        }),
                    )),
                    Some(f) => Err(Error::Invalid(format!(
                        "{}: a {} file, which this build of rastty does not read",
                        path.display(),
                        f.name()
                    ))),
                    None if !regular => Ok((Format::Toml, None)),
                    None => Err(Error::Invalid(format!(
                        "{}: not a model or a scene: its first bytes are not OBJ, STL, PLY, glTF or TOML",
                        path.display()
                    ))),
                }
            }
        }
    }

    /// The format's name in messages.
    pub fn name(self) -> &'static str {
        match self {
            Format::Obj => "OBJ",
            Format::Stl => "STL",
            Format::Gltf => "glTF",
            Format::Ply => "PLY",
            Format::Toml => "TOML scene",
            Format::Shape(_) => "built-in shape",
        }
    }
}

/// Whether this build reads `f`.
fn readable(f: Format) -> bool {
    !matches!(f, Format::Gltf if !cfg!(feature = "gltf"))
        && !matches!(f, Format::Ply if !cfg!(feature = "ply"))
}

/// Up to the first 512 bytes of the file at `path` (none if it cannot be
/// read: the loader will say why).
fn head(path: &Path) -> Vec<u8> {
    use std::io::Read;
    let mut head = Vec::with_capacity(512);
    if let Ok(f) = std::fs::File::open(path) {
        let _ = f.take(512).read_to_end(&mut head);
    }
    head
}

/// What a file's first bytes say: a signature (a format that cannot be
/// mistaken), and else a guess from its first statement.
fn sniff(head: &[u8]) -> (Option<Format>, Option<Format>) {
    if head.starts_with(b"glTF") {
        return (Some(Format::Gltf), None);
    }
    if head.starts_with(b"ply\n") || head.starts_with(b"ply\r\n") {
        return (Some(Format::Ply), None);
    }
    let text = head.trim_ascii_start();
    if text.starts_with(b"{") {
        // glTF's JSON must hold an `asset` object, which exporters write
        // first; a brace without it in the first bytes is only a guess (an
        // STL header may start with one).
        let asset = head.windows(7).any(|w| w == b"\"asset\"");
        return if asset {
            (Some(Format::Gltf), None)
        } else {
            (None, Some(Format::Gltf))
        };
    }
    if text.starts_with(b"solid") {
        return (None, Some(Format::Stl));
    }
    // The first line that is not blank or a comment.
    let first = head
        .split(|&b| b == b'\n')
        .map(<[u8]>::trim_ascii)
        .find(|l| !l.is_empty() && !l.starts_with(b"#"));
    let guess = first.and_then(|l| {
        let word = l.split(|b| b.is_ascii_whitespace()).next().unwrap_or(l);
        match word {
            b"v" | b"vn" | b"vt" | b"f" | b"o" | b"g" | b"s" | b"mtllib" | b"usemtl" | b"l"
            | b"p" => Some(Format::Obj),
            _ if l.starts_with(b"[") || l.contains(&b'=') => Some(Format::Toml),
            _ => None,
        }
    });
    (None, guess)
}

/// What a path names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A model file or a built-in shape.
    Model,
    /// A scene file.
    Scene,
}

/// About how much scene text is deserialized at once.
const CHUNK: usize = 64 << 10;

/// The scene text cut into runs of whole top-level tables of about `size`
/// bytes: `(start, end)` offsets. A table starts at a `[` that begins a
/// line outside any string or array; strings (basic, literal, multi-line),
/// comments, arrays and inline tables are stepped over, so a `[` inside
/// one never starts a table.
fn chunks(src: &str, size: usize) -> Vec<(usize, usize)> {
    let b = src.as_bytes();
    let mut starts = vec![0usize];
    let (mut i, mut depth, mut line_start) = (0usize, 0usize, true);
    let find = |from: usize, pat: &[u8]| {
        b[from..]
            .windows(pat.len())
            .position(|w| w == pat)
            .map_or(b.len(), |k| from + k + pat.len())
    };
    while i < b.len() {
        let c = b[i];
        match c {
            b'\n' => {
                line_start = true;
                i += 1;
                continue;
            }
            b' ' | b'\t' | b'\r' => {
                i += 1;
                continue;
            }
            b'#' => {
                i = b[i..]
                    .iter()
                    .position(|&c| c == b'\n')
                    .map_or(b.len(), |k| i + k);
                continue;
            }
            b'"' if b[i..].starts_with(b"\"\"\"") => {
                // To the closing """, past escaped quotes.
                let mut j = i + 3;
                loop {
                    j = find(j, b"\"\"\"");
                    if j >= b.len() || b[j - 4] != b'\\' {
                        break;
                    }
                }
                i = j;
            }
            b'\'' if b[i..].starts_with(b"\'\'\'") => i = find(i + 3, b"\'\'\'"),
            b'"' => {
                let mut j = i + 1;
                while j < b.len() && b[j] != b'"' && b[j] != b'\n' {
                    j += if b[j] == b'\\' { 2 } else { 1 };
                }
                i = j + 1;
            }
            b'\'' => {
                i = b[i + 1..]
                    .iter()
                    .position(|&c| c == b'\'' || c == b'\n')
                    .map_or(b.len(), |k| i + 1 + k + 1);
            }
            b'[' if line_start && depth == 0 => {
                let line = src[..i].rfind('\n').map_or(0, |k| k + 1);
                starts.push(line);
                // The header's own brackets.
                i = b[i..]
                    .iter()
                    .position(|&c| c == b'\n')
                    .map_or(b.len(), |k| i + k);
            }
            b'[' | b'{' => {
                depth += 1;
                i += 1;
            }
            b']' | b'}' => {
                depth = depth.saturating_sub(1);
                i += 1;
            }
            _ => i += 1,
        }
        line_start = false;
    }
    starts.dedup();
    let mut out = Vec::new();
    let mut from = 0;
    for (k, &s) in starts.iter().enumerate().skip(1) {
        if s - from >= size {
            out.push((from, s));
            from = s;
        }
        let _ = k;
    }
    out.push((from, src.len()));
    out
}

/// The model files read, by extension (lower case).
pub const MODEL_EXTENSIONS: &[&str] = &[
    "obj",
    "stl",
    #[cfg(feature = "gltf")]
    "gltf",
    #[cfg(feature = "gltf")]
    "glb",
    #[cfg(feature = "ply")]
    "ply",
];

/// The model formats read, in words.
const MODELS: &str = if cfg!(all(feature = "gltf", feature = "ply")) {
    ".obj with its .mtl, .stl, .gltf, .glb, .ply"
} else if cfg!(feature = "gltf") {
    ".obj with its .mtl, .stl, .gltf, .glb"
} else if cfg!(feature = "ply") {
    ".obj with its .mtl, .stl, .ply"
} else {
    ".obj with its .mtl, .stl"
};

/// Loads a model file by its extension, or a built-in shape by its name:
/// its geometry, and what the loader has to tell.
pub fn load_geometry(path: &Path, options: &LoadOptions) -> Result<(Arc<Geometry>, Vec<String>)> {
    let (format, note) = Format::of(path)?;
    load_as(path, format, note, options)
}

/// [`load_geometry`] of a file whose format is known (`note`: what telling
/// it said, if anything).
fn load_as(
    path: &Path,
    format: Format,
    note: Option<String>,
    options: &LoadOptions,
) -> Result<(Arc<Geometry>, Vec<String>)> {
    let mut loaded = match format {
        Format::Obj => obj::load(path, options)?,
        Format::Stl => stl::load(path, options)?,
        #[cfg(feature = "gltf")]
        Format::Gltf => gltf::load(path, options)?,
        #[cfg(feature = "ply")]
        Format::Ply => ply::load(path, options)?,
        Format::Shape(shape) => {
            let mut g = shape.geometry();
            if options.crease != mesh::DEFAULT_CREASE {
                Arc::make_mut(&mut g).compute_normals(options.crease);
            }
            return Ok((g, Vec::new()));
        }
        #[allow(unreachable_patterns)]
        _ => {
            return Err(Error::Invalid(format!(
                "{}: not a model: expected a model file ({MODELS}), or one of cube, sphere, torus",
                path.display()
            )));
        }
    };
    loaded.notes.splice(0..0, note);
    Ok((Arc::new(loaded.geometry), loaded.notes))
}

/// Loads a mesh file by its extension, or a built-in shape by its name, in
/// `color` where the file gives none.
pub fn load_mesh(path: &Path, color: Rgb) -> Result<Mesh> {
    let (geometry, _) = load_geometry(path, &LoadOptions::default())?;
    Ok(Mesh::of(geometry, color))
}

/// An array of exactly `N` (serde's own arrays ignore what follows the
/// `N`th element, so `eye = [0, 0, 1, 2]` would pass unseen).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Exact<T, const N: usize>([T; N]);

impl<'de, T: Deserialize<'de>, const N: usize> Deserialize<'de> for Exact<T, N> {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        let v: Vec<T> = Vec::deserialize(d)?;
        let n = v.len();
        v.try_into()
            .map(Exact)
            .map_err(|_| serde::de::Error::invalid_length(n, &format!("an array of {N}").as_str()))
    }
}

impl<T: Default + Copy, const N: usize> Default for Exact<T, N> {
    fn default() -> Self {
        Exact([T::default(); N])
    }
}

impl From<Exact<f32, 3>> for Vec3 {
    fn from(a: Exact<f32, 3>) -> Vec3 {
        Vec3::from(a.0)
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneDef {
    background: Option<Rgb>,
    camera: Option<Spanned<CameraDef>>,
    #[serde(default)]
    triangle: Vec<Spanned<TriangleDef>>,
    #[serde(default)]
    mesh: Vec<Spanned<MeshDef>>,
    #[serde(default)]
    light: Vec<Spanned<LightDef>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MeshDef {
    path: Option<String>,
    shape: Option<String>,
    color: Option<Rgb>,
    #[serde(default)]
    translate: Exact<f32, 3>,
    #[serde(default)]
    rotate: Exact<f32, 3>,
    #[serde(default)]
    scale: ScaleDef,
    cull: Option<CullDef>,
}

/// `scale = 2.0` or `scale = [1.0, 2.0, 1.0]`.
#[derive(Deserialize, Clone, Copy)]
#[serde(untagged)]
enum ScaleDef {
    Uniform(f32),
    Axes(Exact<f32, 3>),
}

impl Default for ScaleDef {
    fn default() -> Self {
        ScaleDef::Uniform(1.0)
    }
}

impl ScaleDef {
    fn vec(self) -> Vec3 {
        match self {
            ScaleDef::Uniform(s) => Vec3::splat(s),
            ScaleDef::Axes(a) => Vec3::from(a),
        }
    }
}

#[derive(Deserialize, Clone, Copy)]
#[serde(rename_all = "lowercase")]
enum CullDef {
    None,
    Back,
    Front,
}

impl From<CullDef> for Cull {
    fn from(c: CullDef) -> Cull {
        match c {
            CullDef::None => Cull::None,
            CullDef::Back => Cull::Back,
            CullDef::Front => Cull::Front,
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LightDef {
    direction: Exact<f32, 3>,
    #[serde(default = "white")]
    color: Rgb,
    #[serde(default = "default_ambient")]
    ambient: f32,
}

fn white() -> Rgb {
    Rgb::WHITE
}

fn default_ambient() -> f32 {
    0.15
}

#[derive(Deserialize, Clone, Copy)]
#[serde(rename_all = "lowercase")]
enum ProjectionDef {
    Perspective,
    Orthographic,
    None,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields, default)]
struct CameraDef {
    projection: ProjectionDef,
    fov_y: f32,
    near: f32,
    far: f32,
    eye: Exact<f32, 3>,
    target: Exact<f32, 3>,
    up: Exact<f32, 3>,
    height: f32,
}

impl Default for CameraDef {
    fn default() -> Self {
        CameraDef {
            projection: ProjectionDef::Perspective,
            fov_y: 45.0,
            near: 0.1,
            far: 100.0,
            eye: Exact([0.0, 0.0, 5.0]),
            target: Exact([0.0; 3]),
            up: Exact([0.0, 1.0, 0.0]),
            height: 2.0,
        }
    }
}

impl CameraDef {
    fn into_camera(self) -> Camera {
        let projection = match self.projection {
            ProjectionDef::Perspective => Projection::Perspective {
                fov_y: self.fov_y,
                near: self.near,
                far: self.far,
            },
            ProjectionDef::Orthographic => Projection::Orthographic {
                height: self.height,
                near: self.near,
                far: self.far,
            },
            ProjectionDef::None => Projection::None,
        };
        Camera {
            projection,
            eye: self.eye.into(),
            target: self.target.into(),
            up: self.up.into(),
            fit: None,
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TriangleDef {
    vertices: Exact<Exact<f32, 3>, 3>,
    color: Option<Rgb>,
    colors: Option<Exact<Rgb, 3>>,
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
