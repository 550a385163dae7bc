//! Materials that are not opaque, end to end: glTF's `alphaMode` MASK cut
//! per sample where the texture's alpha crosses the cut-off, BLEND
//! composited in linear light behind-to-front, OBJ's `d`; and the planned
//! frame against the full pipeline's.

use crate::common;

use std::sync::Arc;

use common::{TexturedMesh, png_rgba};
use glam::Vec3;
use rastty::color::{Lin, Rgb};
use rastty::scene::{AlphaMode, Camera, Geometry, LoadOptions, Mesh, Projection, Scene, gltf};
use rastty::{Pipeline, RenderOptions, Renderer};

/// A square of side 2 facing +z at depth `z`, its texture a gradient of
/// 256 texels left to right whose red and alpha both rise from 0 to 255,
/// read nearest; `material` is JSON added to the material.
fn gradient_square(z: f32, material: &str, base: [f32; 4]) -> Geometry {
    let texels: Vec<[u8; 4]> = (0..=255u8).map(|i| [i, 0, 0, i]).collect();
    let png = png_rgba(256, 1, &texels);
    let mesh = TexturedMesh {
        positions: &[
            [-1.0, -1.0, z],
            [1.0, -1.0, z],
            [1.0, 1.0, z],
            [-1.0, 1.0, z],
        ],
        uvs: &[[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]],
        indices: &[0, 1, 2, 0, 2, 3],
        png: &png,
        sampler: r#"{"magFilter":9728,"minFilter":9728}"#,
        base_color: base,
    };
    let (json, bin) = mesh.parts(None);
    let json = json.replace(
        r#""baseColorTexture":{"index":0}}"#,
        &format!(r#""baseColorTexture":{{"index":0}}}}{material}"#),
    );
    let loaded = gltf::parse(
        &common::glb(&json, &bin),
        None,
        "alpha.glb",
        &LoadOptions::default(),
    )
    .unwrap();
    assert!(loaded.notes.is_empty(), "{:?}", loaded.notes);
    loaded.geometry
}

/// `meshes` seen face on through an orthographic box, unlit (no lights:
/// each sample is its surface's colour).
fn scene(meshes: Vec<Geometry>) -> Scene {
    let mut b = Scene::builder().camera(Camera {
        projection: Projection::Orthographic {
            height: 1.8,
            near: 0.5,
            far: 10.0,
        },
        eye: Vec3::new(0.0, 0.0, 4.0),
        target: Vec3::ZERO,
        ..Camera::default()
    });
    for g in meshes {
        b = b.mesh(Mesh::of(Arc::new(g), Rgb::WHITE));
    }
    b.build().unwrap()
}

fn samples(scene: &Scene, pipeline: Pipeline) -> Vec<Option<Lin>> {
    let mut r = Renderer::new();
    r.render(
        scene,
        &RenderOptions {
            cols: 40,
            rows: 20,
            pipeline,
            ..RenderOptions::default()
        },
    );
    r.framebuffer().samples().to_vec()
}

#[test]
fn a_mask_cuts_a_gradient_at_the_sample_where_its_alpha_crosses_the_cutoff() {
    // The same square opaque tells which texel each sample reads: its red
    // is the texel's index (sRGB-decoded, rising with it), and so is its
    // alpha.
    let opaque = samples(
        &scene(vec![gradient_square(0.0, "", [1.0; 4])]),
        Pipeline::Planned,
    );
    for (cutoff, first_kept) in [(0.5, 128u8), (0.25, 64)] {
        let masked = gradient_square(
            0.0,
            &format!(r#","alphaMode":"MASK","alphaCutoff":{cutoff}"#),
            [1.0; 4],
        );
        assert_eq!(
            masked.materials[0].finish.alpha.mode,
            AlphaMode::Mask { cutoff }
        );
        let cut = samples(&scene(vec![masked]), Pipeline::Planned);
        let least = Lin::from_srgb(Rgb::new(first_kept, 0, 0)).0[0];
        let (mut kept, mut dropped) = (0, 0);
        for (o, c) in opaque.iter().zip(&cut) {
            let o = o.expect("the square fills the view");
            // Kept where the texel's alpha (its index / 255) is at least
            // the cut-off, and then exactly the opaque colour.
            if o.0[0] >= least {
                assert_eq!(*c, Some(o), "cut-off {cutoff}");
                kept += 1;
            } else {
                assert_eq!(*c, None, "cut-off {cutoff}: red {}", o.0[0]);
                dropped += 1;
            }
        }
        assert!(
            kept > 0 && dropped > 0,
            "the cut is in view: {kept} kept, {dropped} cut"
        );
    }
}

/// A square of side 2 facing +z at depth `z`, of one unlit colour.
fn plain_square(z: f32, color: [f32; 4], blend: bool) -> Geometry {
    let mut d = common::Doc::default();
    let pos = d.vec3(&[
        [-1.0, -1.0, z],
        [1.0, -1.0, z],
        [1.0, 1.0, z],
        [-1.0, 1.0, z],
    ]);
    let idx = d.indices(&[[0, 1, 2], [0, 2, 3]]);
    let mode = if blend { r#","alphaMode":"BLEND""# } else { "" };
    let glb = d.glb(&format!(
        r#""extensionsUsed":["KHR_materials_unlit"],
"materials":[{{"pbrMetallicRoughness":{{"baseColorFactor":{color:?}}},"extensions":{{"KHR_materials_unlit":{{}}}}{mode}}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":{pos}}},"indices":{idx},"material":0}}]}}],
"nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0"#
    ));
    gltf::parse(&glb, None, "square.glb", &LoadOptions::default())
        .unwrap()
        .geometry
}

#[test]
fn half_red_blended_over_blue_is_their_linear_mix_whichever_is_listed_first() {
    let red = || plain_square(1.0, [1.0, 0.0, 0.0, 0.5], true);
    let blue = || plain_square(0.0, [0.0, 0.0, 1.0, 1.0], false);
    // Half of each, in linear light: 65535 / 2 rounded half up.
    let mix = Some(Lin([32768, 0, 32768]));
    for meshes in [vec![red(), blue()], vec![blue(), red()]] {
        for pipeline in [Pipeline::Planned, Pipeline::Full] {
            let s = samples(
                &scene(meshes.iter().map(|g| (*g).clone()).collect()),
                pipeline,
            );
            assert!(s.iter().all(|c| *c == mix), "{pipeline:?}: {:?}", s[0]);
        }
    }
    // Blended behind an opaque square: hidden by the depth test.
    let front = plain_square(2.0, [0.0, 1.0, 0.0, 1.0], false);
    let s = samples(&scene(vec![red(), front]), Pipeline::Planned);
    assert!(s.iter().all(|c| *c == Some(Lin([0, 65535, 0]))));
}

#[test]
fn blended_squares_are_drawn_back_to_front() {
    // Two half-transparent squares over black: the nearer one's colour
    // weighs twice the farther one's, in whichever order they are listed.
    let red = || plain_square(1.0, [1.0, 0.0, 0.0, 0.5], true);
    let green = || plain_square(0.5, [0.0, 1.0, 0.0, 0.5], true);
    // Green over black: half green; red over that: half red, a quarter green.
    let want = Some(Lin([32768, 16384, 0]));
    for meshes in [vec![red(), green()], vec![green(), red()]] {
        let s = samples(&scene(meshes), Pipeline::Planned);
        assert!(s.iter().all(|c| *c == want), "{:?}", s[0]);
    }
}

#[test]
fn an_obj_materials_d_below_1_is_blended() {
    let dir = std::env::temp_dir().join(format!("rastty-alpha-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("m.mtl"),
        "newmtl glass\nKd 1 0 0\nd 0.25\nnewmtl solid\nKd 1 1 1\nTr 0\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("m.obj"),
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl glass\nf 1 2 3\nusemtl solid\nf 1 3 2\n",
    )
    .unwrap();
    let loaded = rastty::scene::obj::load(&dir.join("m.obj"), &LoadOptions::default()).unwrap();
    let alphas: Vec<_> = loaded
        .geometry
        .materials
        .iter()
        .map(|m| m.finish.alpha)
        .collect();
    assert_eq!(alphas[0].mode, AlphaMode::Blend);
    assert_eq!(alphas[0].factor, 0.25);
    assert_eq!(alphas[1].mode, AlphaMode::Opaque);
    std::fs::remove_dir_all(&dir).unwrap();
}
