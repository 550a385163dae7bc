//! Point and spot lights end to end: falloff, range and cone through the
//! pipeline users run, against an f64 evaluation of the same formulas;
//! scene files' `[[light]]` and glTF's `KHR_lights_punctual` read.

use std::sync::Arc;

use glam::Vec3;
use rastty::color::Rgb;
use rastty::scene::{Camera, Geometry, LightKind, Mesh, Projection, Scene};
use rastty::{RenderOptions, Renderer};

/// Half the side of the little white square about the origin facing +z:
/// small enough that its corners are as far from a light 1 away as its
/// middle to one part in 10⁶, far below a step of linear light.
const HALF: f32 = 1e-3;

/// The square seen face on through an orthographic box it fills, lit by
/// `light` alone; the least and the most linear red of its samples.
fn lit_square(light: rastty::scene::Light) -> (f64, f64) {
    let square = Geometry::new(
        "square",
        vec![
            Vec3::new(-HALF, -HALF, 0.0),
            Vec3::new(HALF, -HALF, 0.0),
            Vec3::new(HALF, HALF, 0.0),
            Vec3::new(-HALF, HALF, 0.0),
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    );
    let scene = Scene::builder()
        .camera(Camera {
            projection: Projection::Orthographic {
                height: HALF,
                near: 0.5,
                far: 8.0,
            },
            eye: Vec3::new(0.0, 0.0, 4.0),
            target: Vec3::ZERO,
            ..Camera::default()
        })
        .mesh(Mesh::of(Arc::new(square), Rgb::WHITE))
        .light(light)
        .build()
        .unwrap();
    let mut r = Renderer::new();
    r.render(
        &scene,
        &RenderOptions {
            cols: 8,
            rows: 4,
            ..RenderOptions::default()
        },
    );
    // Every sample is covered (the box is inside the square).
    let mut reds: Vec<u16> = r
        .framebuffer()
        .samples()
        .iter()
        .map(|s| s.expect("the square covers every sample").0[0])
        .collect();
    reds.sort_unstable();
    (f64::from(reds[0]), f64::from(reds[reds.len() - 1]))
}

/// A white light of `kind` and `intensity` shining down −z along
/// `direction`, without ambient.
fn light(kind: LightKind, direction: Vec3, intensity: f32) -> rastty::scene::Light {
    rastty::scene::Light {
        direction,
        color: Rgb::WHITE,
        ambient: 0.0,
        kind,
        intensity,
    }
}

fn point(z: f32, range: Option<f32>) -> rastty::scene::Light {
    let position = Vec3::new(0.0, 0.0, z);
    light(LightKind::Point { position, range }, Vec3::NEG_Z, 0.5)
}

/// Whether `want` is within one step of linear light (65535 is full) of
/// the samples' values.
fn near((least, most): (f64, f64), want: f64) -> bool {
    least - 1.0 <= want && want <= most + 1.0
}

#[test]
fn a_point_lights_falloff_at_distances_1_and_2_is_4_to_1() {
    let (one, two) = (lit_square(point(1.0, None)), lit_square(point(2.0, None)));
    // The square is so small that it is lit evenly, to a step.
    assert!(
        one.1 - one.0 <= 1.0 && two.1 - two.0 <= 1.0,
        "{one:?} {two:?}"
    );
    // Half intensity, head on: 0.5 / d² of full.
    assert!(near(one, 65535.0 * 0.5), "{one:?}");
    assert!(near(two, 65535.0 * 0.5 / 4.0), "{two:?}");
    // And 4:1 to within the two steps' rounding.
    assert!(
        (one.0 / two.0 - 4.0).abs() < 4.0 * 2.0 / two.0,
        "{one:?} / {two:?}"
    );
}

#[test]
fn a_range_fades_a_point_light_to_nothing_at_its_end() {
    // glTF's window: 1 − (d / range)⁴, clamped to [0, 1].
    let window = |d: f64, r: f64| (1.0 - (d / r).powi(4)).clamp(0.0, 1.0);
    let got = lit_square(point(1.0, Some(2.0)));
    assert!(near(got, 65535.0 * 0.5 * window(1.0, 2.0)), "{got:?}");
    // The corners are a hair nearer than the middle: the last of it.
    assert!(lit_square(point(2.0, Some(2.0))).1 <= 1.0);
    assert_eq!(lit_square(point(3.0, Some(2.0))), (0.0, 0.0));
}

#[test]
fn a_spot_lights_all_inside_its_inner_cone_none_outside_its_outer_and_between_smoothly() {
    let (inner, outer) = (10f64.to_radians(), 20f64.to_radians());
    // A spot 1 above the square's middle, its axis turned `tilt` degrees
    // away from the square: the middle is `tilt` off the axis.
    let spot = |tilt: f64| {
        let t = tilt.to_radians() as f32;
        let kind = LightKind::Spot {
            position: Vec3::Z,
            range: None,
            inner: inner as f32,
            outer: outer as f32,
        };
        lit_square(light(kind, Vec3::new(t.sin(), 0.0, -t.cos()), 1.0))
    };
    assert!(near(spot(0.0), 65535.0));
    assert!(near(spot(5.0), 65535.0));
    assert_eq!(spot(25.0), (0.0, 0.0));
    // glTF's smooth step between: ((cos θ − cos outer) / (cos inner − cos
    // outer))², clamped.
    let s = (15f64.to_radians().cos() - outer.cos()) / (inner.cos() - outer.cos());
    let got = spot(15.0);
    // The middle sample is off the axis by the tilt; the square's corners
    // a little more or less, so the samples straddle the expectation.
    assert!(
        near(got, 65535.0 * s * s),
        "{got:?} against {}",
        65535.0 * s * s
    );
}

/// A scene file of one lit triangle and `light`'s keys.
fn scene_with(light: &str) -> rastty::Result<Scene> {
    Scene::parse(
        &format!(
            "[[triangle]]\nvertices = [[-1,-1,0],[1,-1,0],[0,1,0]]\ncolor = \"#ffffff\"\n\n[[light]]\n{light}"
        ),
        "lights.toml",
    )
}

#[test]
fn a_scene_files_point_and_spot_lights_are_read_with_their_cones_in_degrees() {
    let scene = scene_with(
        "kind = \"spot\"\nposition = [0, 3, 0]\ndirection = [0, -2, 0]\nrange = 10.0\ninner_cone = 10.0\nouter_cone = 30.0\nintensity = 2.5\n",
    )
    .unwrap();
    let l = &scene.lights[0];
    assert_eq!(l.direction, Vec3::NEG_Y);
    assert_eq!(l.intensity, 2.5);
    assert_eq!(
        l.kind,
        LightKind::Spot {
            position: Vec3::new(0.0, 3.0, 0.0),
            range: Some(10.0),
            inner: 10f32.to_radians(),
            outer: 30f32.to_radians(),
        }
    );
    let p = scene_with("kind = \"point\"\nposition = [1, 2, 3]\n").unwrap();
    assert_eq!(
        p.lights[0].kind,
        LightKind::Point {
            position: Vec3::new(1.0, 2.0, 3.0),
            range: None
        }
    );
}

#[test]
fn a_light_missing_or_misplacing_a_key_is_an_error_at_its_line() {
    for (keys, says) in [
        ("kind = \"point\"\n", "a point light needs `position`"),
        (
            "kind = \"spot\"\nposition = [0, 1, 0]\n",
            "a spot light needs `position` and `direction`",
        ),
        (
            "kind = \"point\"\nposition = [0, 1, 0]\ndirection = [0, -1, 0]\n",
            "a point light has no `direction`",
        ),
        (
            "direction = [0, -1, 0]\nposition = [0, 1, 0]\n",
            "a directional light has no `position` or `range`",
        ),
        (
            "kind = \"point\"\nposition = [0, 1, 0]\nouter_cone = 30.0\n",
            "only a spot light has `inner_cone` and `outer_cone`",
        ),
        (
            "kind = \"spot\"\nposition = [0, 1, 0]\ndirection = [0, -1, 0]\ninner_cone = 40.0\nouter_cone = 30.0\n",
            "cone",
        ),
        (
            "kind = \"point\"\nposition = [0, 1, 0]\nrange = -1.0\n",
            "range",
        ),
        (
            "kind = \"point\"\nposition = [0, 1, 0]\nintensity = -1.0\n",
            "intensity",
        ),
    ] {
        let e = scene_with(keys).unwrap_err().to_string();
        assert!(e.contains("lights.toml:5:"), "{keys:?}: {e}");
        assert!(e.contains(says), "{keys:?}: {e}");
    }
    // A kind that is not one is an error at its own line and column.
    let e = scene_with("kind = \"lamp\"\n").unwrap_err().to_string();
    assert!(
        e.starts_with("lights.toml:6:8: unknown variant `lamp`"),
        "{e}"
    );
}

#[cfg(feature = "gltf")]
#[test]
fn a_gltf_point_light_is_placed_by_its_node_and_lights_the_model_view() {
    use crate::common::Doc;
    use rastty::scene::{LoadOptions, gltf};
    let mut d = Doc::default();
    let pos = d.vec3(&[
        [-1.0, -1.0, 0.0],
        [1.0, -1.0, 0.0],
        [1.0, 1.0, 0.0],
        [-1.0, 1.0, 0.0],
    ]);
    let idx = d.indices(&[[0, 1, 2], [0, 2, 3]]);
    let glb = d.glb(&format!(
        r#""extensionsUsed":["KHR_lights_punctual"],
"extensions":{{"KHR_lights_punctual":{{"lights":[{{"type":"point","color":[1,0.5,0],"intensity":3,"range":9}},{{"type":"spot","spot":{{"innerConeAngle":0.1,"outerConeAngle":0.5}}}}]}}}},
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":{pos}}},"indices":{idx}}}]}}],
"nodes":[{{"mesh":0}},{{"translation":[0,0,2],"extensions":{{"KHR_lights_punctual":{{"light":0}}}}}},{{"translation":[0,1,0],"rotation":[-0.7071068,0,0,0.7071068],"extensions":{{"KHR_lights_punctual":{{"light":1}}}}}}],
"scenes":[{{"nodes":[0,1,2]}}],"scene":0"#
    ));
    let loaded = gltf::parse(&glb, None, "lit.glb", &LoadOptions::default()).unwrap();
    assert!(loaded.notes.is_empty(), "{:?}", loaded.notes);
    let lights = &loaded.geometry.lights;
    assert_eq!(lights.len(), 2);
    let point = lights
        .iter()
        .find(|l| matches!(l.kind, LightKind::Point { .. }))
        .unwrap();
    let spot = lights
        .iter()
        .find(|l| matches!(l.kind, LightKind::Spot { .. }))
        .unwrap();
    // The colour is kept with its largest channel full, the rest in the
    // intensity: linear [1, 0.5, 0] is sRGB (255, 188, 0).
    assert_eq!(point.color, Rgb::new(255, 188, 0));
    assert_eq!(point.intensity, 3.0);
    assert_eq!(
        point.kind,
        LightKind::Point {
            position: Vec3::new(0.0, 0.0, 2.0),
            range: Some(9.0)
        }
    );
    // The spot's node is turned −90° about x: its −z points down −y.
    assert!(
        spot.direction.abs_diff_eq(Vec3::NEG_Y, 1e-6),
        "{}",
        spot.direction
    );
    assert_eq!(
        spot.kind,
        LightKind::Spot {
            position: Vec3::Y,
            range: None,
            inner: 0.1,
            outer: 0.5
        }
    );
    // The model view lights the model with the file's lights, not the rig.
    let scene = Scene::of_mesh(Mesh::of(Arc::new(loaded.geometry), Rgb::WHITE));
    assert_eq!(scene.lights.len(), 2);
    assert!(
        scene
            .lights
            .iter()
            .all(|l| l.kind != LightKind::Directional)
    );
}
