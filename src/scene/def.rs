//! The scene file's TOML tables as serde reads them, strictly (unknown
//! keys and arrays of the wrong length are errors), before
//! [`Scene::parse`] checks and turns them into a scene.

use super::*;

/// An array of exactly `N` (serde's own arrays ignore what follows the
/// `N`th element, so `eye = [0, 0, 1, 2]` would pass unseen).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Exact<T, const N: usize>(pub(super) [T; N]);

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
pub(super) struct SceneDef {
    pub(super) background: Option<Rgb>,
    pub(super) camera: Option<Spanned<CameraDef>>,
    #[serde(default)]
    pub(super) triangle: Vec<Spanned<TriangleDef>>,
    #[serde(default)]
    pub(super) mesh: Vec<Spanned<MeshDef>>,
    #[serde(default)]
    pub(super) light: Vec<Spanned<LightDef>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MeshDef {
    pub(super) path: Option<String>,
    pub(super) shape: Option<String>,
    pub(super) color: Option<Rgb>,
    #[serde(default)]
    pub(super) translate: Exact<f32, 3>,
    #[serde(default)]
    pub(super) rotate: Exact<f32, 3>,
    #[serde(default)]
    pub(super) scale: ScaleDef,
    pub(super) cull: Option<CullDef>,
    /// The clip a moving model plays: its number or its name.
    pub(super) clip: Option<ClipDef>,
    /// Seconds into the clip.
    pub(super) time: Option<f64>,
}

/// `clip = 2` or `clip = "walk"`.
#[derive(Deserialize, Clone)]
#[serde(
    untagged,
    expecting = "expected a clip's number, 0 or more (clip = 2), or its name (clip = \"walk\")"
)]
pub(super) enum ClipDef {
    Number(u32),
    Name(String),
}

/// `scale = 2.0` or `scale = [1.0, 2.0, 1.0]`.
#[derive(Deserialize, Clone, Copy)]
#[serde(
    untagged,
    expecting = "expected a scale: one number (scale = 2.0) or three, one an axis (scale = [1.0, 2.0, 1.0])"
)]
pub(super) enum ScaleDef {
    Uniform(f32),
    Axes(Exact<f32, 3>),
}

impl Default for ScaleDef {
    fn default() -> Self {
        ScaleDef::Uniform(1.0)
    }
}

impl ScaleDef {
    pub(super) fn vec(self) -> Vec3 {
        match self {
            ScaleDef::Uniform(s) => Vec3::splat(s),
            ScaleDef::Axes(a) => Vec3::from(a),
        }
    }
}

#[derive(Deserialize, Clone, Copy)]
#[serde(rename_all = "lowercase")]
pub(super) enum CullDef {
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
pub(super) struct LightDef {
    #[serde(default)]
    pub(super) kind: LightKindDef,
    pub(super) direction: Option<Exact<f32, 3>>,
    #[serde(default = "white")]
    pub(super) color: Rgb,
    #[serde(default = "default_ambient")]
    pub(super) ambient: f32,
    #[serde(default = "one")]
    pub(super) intensity: f32,
    pub(super) position: Option<Exact<f32, 3>>,
    pub(super) range: Option<f32>,
    /// Degrees.
    pub(super) inner_cone: Option<f32>,
    /// Degrees.
    pub(super) outer_cone: Option<f32>,
}

#[derive(Deserialize, Clone, Copy, Default, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub(super) enum LightKindDef {
    #[default]
    Directional,
    Point,
    Spot,
}

pub(super) fn one() -> f32 {
    1.0
}

pub(super) fn white() -> Rgb {
    Rgb::WHITE
}

pub(super) fn default_ambient() -> f32 {
    0.15
}

#[derive(Deserialize, Clone, Copy)]
#[serde(rename_all = "lowercase")]
pub(super) enum ProjectionDef {
    Perspective,
    Orthographic,
    None,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields, default)]
pub(super) struct CameraDef {
    pub(super) projection: ProjectionDef,
    pub(super) fov_y: f32,
    pub(super) near: f32,
    pub(super) far: f32,
    pub(super) eye: Exact<f32, 3>,
    pub(super) target: Exact<f32, 3>,
    pub(super) up: Exact<f32, 3>,
    pub(super) height: f32,
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
    pub(super) fn into_camera(self) -> Camera {
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
            shift: glam::Vec2::ZERO,
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
pub(super) struct TriangleDef {
    pub(super) vertices: Exact<Exact<f32, 3>, 3>,
    pub(super) color: Option<Rgb>,
    pub(super) colors: Option<Exact<Rgb, 3>>,
}
