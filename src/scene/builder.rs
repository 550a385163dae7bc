//! Building a scene in code: the same scene a TOML file describes, checked
//! the same way when it is built (a camera that can project, at most
//! [`MAX_LIGHTS`] lights, each with a usable direction and ambient share,
//! something to draw), so that a scene made in code cannot reach the
//! renderer in a state a scene file could not.

use glam::Vec3;

use super::{Camera, Light, MAX_LIGHTS, Mesh, Projection, Scene, Triangle, TriangleColor};
use crate::color::Rgb;
use crate::error::{Error, Result};

/// A scene under construction; [`Scene::builder`] starts one, with the
/// default camera (perspective, 45°, at `(0, 0, 5)` looking at the
/// origin), no lights and nothing to draw.
///
/// ```
/// use rastty::glam::{Mat4, Vec3};
/// use rastty::scene::Shape;
/// use rastty::{scene::Light, color::Rgb, scene::Scene};
///
/// let scene = Scene::builder()
///     .look_at(Vec3::new(3.0, 2.0, 4.0), Vec3::ZERO)
///     .mesh(Shape::Cube.mesh(Rgb::new(0x40, 0x90, 0xff)).with_model(Mat4::from_rotation_y(0.3)))
///     .triangle([Vec3::new(-2.0, -1.0, -2.0), Vec3::new(2.0, -1.0, -2.0), Vec3::new(0.0, -1.0, 2.0)], Rgb::WHITE)
///     .light(Light { direction: Vec3::new(-1.0, -2.0, -1.0), ..Light::default() })
///     .build()
///     .unwrap();
/// assert_eq!(scene.triangle_count(), 12 + 1);
/// ```
#[derive(Clone, Debug, Default)]
#[must_use = "a builder does nothing until `build` is called"]
pub struct SceneBuilder {
    scene: Scene,
}

impl Scene {
    /// Starts a scene built in code (see [`SceneBuilder`]).
    pub fn builder() -> SceneBuilder {
        SceneBuilder::default()
    }
}

impl SceneBuilder {
    /// Sees the scene through `camera`.
    pub fn camera(mut self, camera: Camera) -> SceneBuilder {
        self.scene.camera = camera;
        self
    }

    /// Puts the eye at `eye` looking at `target`, y up; the projection
    /// stays as it is.
    pub fn look_at(mut self, eye: Vec3, target: Vec3) -> SceneBuilder {
        self.scene.camera = Camera {
            eye,
            target,
            up: Vec3::Y,
            fit: None,
            ..self.scene.camera
        };
        self
    }

    /// Projects the view with `projection`.
    pub fn projection(mut self, projection: Projection) -> SceneBuilder {
        self.scene.camera.projection = projection;
        self
    }

    /// Paints uncovered samples in `color` (by default they keep the
    /// terminal's own background).
    pub fn background(mut self, color: Rgb) -> SceneBuilder {
        self.scene.background = Some(color);
        self
    }

    /// Adds a mesh (a built-in shape with [`super::Shape::mesh`], a model
    /// file's with [`super::load_geometry`] and [`Mesh::of`], or [`Mesh::new`] from positions
    /// and faces).
    pub fn mesh(mut self, mesh: Mesh) -> SceneBuilder {
        self.scene.meshes.push(mesh);
        self
    }

    /// Adds a loose triangle of one colour (never culled).
    pub fn triangle(self, vertices: [Vec3; 3], color: Rgb) -> SceneBuilder {
        self.push_triangle(vertices, TriangleColor::Flat(color))
    }

    /// Adds a loose triangle with a colour at each vertex, interpolated
    /// over it.
    pub fn triangle_colors(self, vertices: [Vec3; 3], colors: [Rgb; 3]) -> SceneBuilder {
        self.push_triangle(vertices, TriangleColor::PerVertex(colors))
    }

    fn push_triangle(mut self, vertices: [Vec3; 3], color: TriangleColor) -> SceneBuilder {
        self.scene.triangles.push(Triangle { vertices, color });
        self
    }

    /// Adds a directional light (its direction need not be of unit length).
    pub fn light(mut self, light: Light) -> SceneBuilder {
        self.scene.lights.push(light);
        self
    }

    /// The scene, checked as a scene file is: the camera can project,
    /// there are at most [`MAX_LIGHTS`] lights, each with a finite,
    /// non-zero direction (made unit length here) and an ambient share in
    /// [0, 1], and there is something to draw.
    pub fn build(self) -> Result<Scene> {
        let mut scene = self.scene;
        scene.camera.check().map_err(Error::Invalid)?;
        if scene.lights.len() > MAX_LIGHTS {
            return Err(Error::Invalid(format!(
                "{} lights: at most {MAX_LIGHTS}",
                scene.lights.len()
            )));
        }
        for light in &mut scene.lights {
            light.check().map_err(Error::Invalid)?;
            light.direction = light.direction.normalize();
        }
        if scene.triangles.is_empty() && scene.meshes.is_empty() {
            return Err(Error::Invalid(
                "nothing to draw: no triangle or mesh".into(),
            ));
        }
        Ok(scene)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri() -> [Vec3; 3] {
        [Vec3::ZERO, Vec3::X, Vec3::Y]
    }

    #[test]
    fn builds_what_the_scene_file_would() {
        let built = Scene::builder()
            .look_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO)
            .triangle(tri(), Rgb::WHITE)
            .light(Light {
                direction: Vec3::new(0.0, 0.0, -2.0),
                ..Light::default()
            })
            .build()
            .unwrap();
        let parsed = Scene::parse(
            r##"
            [[triangle]]
            vertices = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
            color = "#ffffff"
            [[light]]
            direction = [0.0, 0.0, -2.0]
            "##,
            "t",
        )
        .unwrap();
        assert_eq!(built, parsed);
    }

    #[test]
    fn refuses_what_a_scene_file_refuses() {
        let err = |b: SceneBuilder| b.build().unwrap_err().to_string();
        assert_eq!(
            err(Scene::builder()),
            "nothing to draw: no triangle or mesh"
        );
        let lit = |light| Scene::builder().triangle(tri(), Rgb::WHITE).light(light);
        assert_eq!(
            err(lit(Light {
                direction: Vec3::ZERO,
                ..Light::default()
            })),
            "light direction must be a finite, non-zero vector"
        );
        assert_eq!(
            err(lit(Light {
                ambient: 1.5,
                ..Light::default()
            })),
            "light ambient must be between 0 and 1, not 1.5"
        );
        let nine = (0..9).fold(Scene::builder().triangle(tri(), Rgb::WHITE), |b, _| {
            b.light(Light::default())
        });
        assert_eq!(err(nine), "9 lights: at most 8");
        let camera = Scene::builder()
            .triangle(tri(), Rgb::WHITE)
            .look_at(Vec3::new(f32::NAN, 0.0, 0.0), Vec3::ZERO);
        assert_eq!(err(camera), "camera eye, target and up must be finite");
    }
}
