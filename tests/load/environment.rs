//! Metals lit by an environment, end to end: the example model is what
//! its builder makes, a metal sphere's samples reflect the studio as the
//! f64 integral of the renderer's own lobe says, and a scene without a
//! metal (or with `--environment none`) is drawn as without one.

use crate::common;

use std::sync::Arc;

use glam::{DVec3, Vec3};
use rastty::color::{Lin, Rgb};
use rastty::reflection_reference;
use rastty::scene::environment::{Environment, studio_radiance};
use rastty::scene::{Camera, LoadOptions, Mesh, Projection, Scene, gltf};
use rastty::{RenderOptions, Renderer};

#[test]
fn the_example_metals_are_what_their_builder_makes() {
    let path = common::example_model("metals.glb", common::metals_glb());
    let loaded = gltf::load(&path, &LoadOptions::default()).unwrap();
    assert!(loaded.notes.is_empty(), "{:?}", loaded.notes);
    let metals: Vec<f32> = (loaded.geometry.materials.iter())
        .map(|m| m.finish.specular.unwrap().metallic)
        .collect();
    assert_eq!(metals, [1.0, 1.0, 1.0]);
}

/// A metal square of reflectance 1 (white) and `roughness`, facing `n`,
/// seen face on from +z through a parallel view, lit by a black light (so
/// that highlights are drawn, and add nothing): the colour of its samples
/// as the renderer draws them, and the f64 integral of the studio through
/// the renderer's own lobe.
fn reflected(n: Vec3, roughness: f32) -> (Vec<Lin>, f64) {
    let n = n.normalize();
    let (t, b) = n.any_orthonormal_pair();
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .map(|(u, v)| t * u * 0.5 + b * v * 0.5);
    let mut d = common::Doc::default();
    let pos = d.vec3(&corners.map(|c| c.to_array()));
    let normal = d.vec3(&[n.to_array(); 4]);
    // Wound to face +z.
    let idx = if t.cross(b).z > 0.0 {
        d.indices(&[[0, 1, 2], [0, 2, 3]])
    } else {
        d.indices(&[[0, 2, 1], [0, 3, 2]])
    };
    let glb = d.glb(&format!(
        r#""materials":[{{"pbrMetallicRoughness":{{"baseColorFactor":[1,1,1,1],"metallicFactor":1,"roughnessFactor":{roughness}}},"doubleSided":true}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":{pos},"NORMAL":{normal}}},"indices":{idx},"material":0}}]}}],
"nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0"#
    ));
    let g = gltf::parse(&glb, None, "square.glb", &LoadOptions::default())
        .unwrap()
        .geometry;
    let scene = Scene::builder()
        .camera(Camera {
            projection: Projection::Orthographic {
                height: 2.0,
                near: 0.1,
                far: 20.0,
            },
            eye: Vec3::new(0.0, 0.0, 4.0),
            target: Vec3::ZERO,
            ..Camera::default()
        })
        .mesh(Mesh::of(Arc::new(g), Rgb::WHITE))
        .light(rastty::scene::Light {
            color: Rgb::BLACK,
            ambient: 0.0,
            ..Default::default()
        })
        .build()
        .unwrap();
    let c = common::colours(&scene, 20, 10);
    let a = f64::from(roughness) * f64::from(roughness);
    let want = reflection_reference(&studio_radiance, n.as_dvec3(), DVec3::Z, 1.0, a * a, 512);
    (c, want * 65535.0)
}

#[test]
fn a_metal_reflects_the_studio_as_the_f64_integral_of_its_lobe_says() {
    // Normals facing the eye, up into the room, aside towards the fill,
    // and down towards the floor; each square one colour throughout.
    let normals = [
        Vec3::Z,
        Vec3::new(0.8, 0.2, 0.6),
        Vec3::new(0.0, -0.7, 0.7),
        Vec3::new(0.3, 0.9, 0.4),
    ];
    // The split sum's error, measured: within 12 % of the integral for
    // polished and brushed metals; for a rough one at grazing angles,
    // where the true lobe leans further from the mirror direction than
    // the split sum's dominant direction does, within 30 %.
    for (roughness, within) in [(0.1f32, 0.12), (0.4, 0.12), (0.8, 0.30)] {
        for n in normals {
            let (got, want) = reflected(n, roughness);
            assert_eq!(got.len(), 1, "one colour: {got:?}");
            let [r, g, b] = got[0].0;
            assert!(r == g && g == b, "a white metal in a grey room: {got:?}");
            let ratio = f64::from(r) / want;
            assert!(
                (ratio - 1.0).abs() <= within,
                "roughness {roughness}, normal {n}: {r} against {want:.0} ({ratio:.3})"
            );
        }
    }
}

#[test]
fn scenes_without_a_metal_are_drawn_as_without_an_environment() {
    let draw = |path: &str, environment: Environment| {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(path);
        let scene = Scene {
            environment,
            ..Scene::of_model(&path).unwrap()
        };
        let mut r = Renderer::new();
        r.render(
            &scene,
            &RenderOptions {
                cols: 60,
                rows: 24,
                ..RenderOptions::default()
            },
        );
        r.framebuffer().samples().to_vec()
    };
    // The fox shines (a dielectric): the same with the studio or none.
    for model in ["tests/models/fox.obj", "examples/models/finishes.glb"] {
        assert_eq!(
            draw(model, Environment::Studio),
            draw(model, Environment::None),
            "{model}"
        );
    }
    // The metals do not: a polished gold is black but for its highlights
    // without one.
    let (studio, none) = (
        draw("examples/models/metals.glb", Environment::Studio),
        draw("examples/models/metals.glb", Environment::None),
    );
    let differ = studio.iter().zip(&none).filter(|(a, b)| a != b).count();
    assert!(differ > 100, "{differ} samples differ");
    let lit = |s: &[Option<Lin>]| s.iter().flatten().map(|c| u64::from(c.0[0])).sum::<u64>();
    assert!(lit(&studio) > 2 * lit(&none));
}
