//! Material maps, end to end, on glTF files the tests write: a normal map
//! tilting a flat square shades it as the square tilted, mirrored UVs turn
//! the map with them, occlusion darkens the ambient share alone, an
//! emissive map glows texel by texel, a metallic-roughness map multiplies
//! the factors; and the planned frame against the full pipeline's.

use crate::common;

use std::sync::Arc;

use common::{Doc, png_rgb};
use glam::Vec3;
use rastty::Effect;
use rastty::color::{Lin, Rgb};
use rastty::scene::{Camera, Geometry, LoadOptions, Mesh, Projection, Scene, gltf};
use rastty::{Pipeline, RenderOptions, Renderer, Threads};

/// A square of side 2 facing +z at z = 0, `u` along +x and `v` down
/// (mirrored in `u` when `mirror`), its normals +z, with `material`
/// (JSON) whose textures `0..` are `images` (PNG), read nearest.
fn square(material: &str, images: &[Vec<u8>], mirror: bool) -> Geometry {
    let mut d = Doc::default();
    let corners = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
    let pos = d.vec3(&corners.map(|[x, y]| [x, y, 0.0]));
    let normal = d.vec3(&[[0.0, 0.0, 1.0]; 4]);
    let uv: Vec<f32> = corners
        .iter()
        .flat_map(|&[x, y]| {
            let u = (x + 1.0) / 2.0;
            [if mirror { 1.0 - u } else { u }, (1.0 - y) / 2.0]
        })
        .collect();
    let uv = d.floats(&uv, "VEC2", 2);
    let idx = d.indices(&[[0, 1, 2], [0, 2, 3]]);
    let views: Vec<usize> = images.iter().map(|png| d.view(png)).collect();
    let images_json: Vec<String> = views
        .iter()
        .map(|v| format!(r#"{{"bufferView":{v},"mimeType":"image/png"}}"#))
        .collect();
    let textures: Vec<String> = (0..images.len())
        .map(|i| format!(r#"{{"source":{i},"sampler":0}}"#))
        .collect();
    let glb = d.glb(&format!(
        r#""materials":[{material}],
"samplers":[{{"magFilter":9728,"minFilter":9728}}],
"images":[{}],"textures":[{}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":{pos},"NORMAL":{normal},"TEXCOORD_0":{uv}}},"indices":{idx},"material":0}}]}}],
"nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0"#,
        images_json.join(","),
        textures.join(",")
    ));
    let loaded = gltf::parse(&glb, None, "square.glb", &LoadOptions::default()).unwrap();
    assert!(loaded.notes.is_empty(), "{:?}", loaded.notes);
    loaded.geometry
}

/// One texel of `rgb`.
fn texel(rgb: [u8; 3]) -> Vec<u8> {
    png_rgb(1, 1, &[rgb])
}

/// `geometry`, white, seen face on through an orthographic box, under
/// `lights` (direction, ambient share), white.
fn scene(geometry: Geometry, lights: &[(Vec3, f32)]) -> Scene {
    let mut b = Scene::builder()
        .camera(Camera {
            projection: Projection::Orthographic {
                height: 3.0,
                near: 0.5,
                far: 10.0,
            },
            eye: Vec3::new(0.0, 0.0, 4.0),
            target: Vec3::ZERO,
            ..Camera::default()
        })
        .mesh(Mesh::of(Arc::new(geometry), Rgb::WHITE));
    for &(direction, ambient) in lights {
        b = b.light(rastty::scene::Light {
            direction: direction.normalize(),
            color: Rgb::WHITE,
            ambient,
            ..Default::default()
        });
    }
    b.build().unwrap()
}

/// The frame's samples (40 × 20 cells of half blocks), row by row from
/// the bottom, and the renderer that drew them.
fn draw(scene: &Scene, pipeline: Pipeline) -> (Vec<Option<Lin>>, Renderer) {
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
    (r.framebuffer().samples().to_vec(), r)
}

/// The sample at the middle of the frame.
fn middle(scene: &Scene) -> Lin {
    let (s, _) = draw(scene, Pipeline::Planned);
    s[20 * 40 + 20].expect("the square covers the middle")
}

/// The byte a normal map stores for a component `c` in [−1, 1].
fn byte(c: f32) -> u8 {
    ((c + 1.0) / 2.0 * 255.0).round() as u8
}

/// What a normal map's bytes decode to, as the renderer decodes them.
fn decoded(b: [u8; 3]) -> Vec3 {
    Vec3::from(b.map(|v| f32::from(v) / 255.0)) * 2.0 - Vec3::ONE
}

const LIGHT: (Vec3, f32) = (Vec3::new(-1.0, -0.3, -1.0), 0.0);

/// Asserts that `got` is the colour of the square, untextured, turned
/// from +z to `n` under [`LIGHT`]: per sample against per vertex, the
/// same Lambert term in f32 with the normal normalised once more on one
/// path, so within one step of 65535.
fn assert_shades_as_tilted(got: Lin, n: Vec3) {
    let turn = glam::Quat::from_rotation_arc(Vec3::Z, n);
    let tilted = Geometry::new(
        "tilted",
        [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]]
            .map(|[x, y]| turn * Vec3::new(x, y, 0.0))
            .to_vec(),
        vec![[0, 1, 2], [0, 2, 3]],
    );
    let want = middle(&scene(tilted, &[LIGHT]));
    for k in 0..3 {
        let d = (i32::from(got.0[k]) - i32::from(want.0[k])).abs();
        assert!(d <= 1, "{got:?} against {want:?}");
    }
}

#[test]
fn a_normal_map_tilted_30_degrees_shades_a_flat_square_as_the_square_tilted() {
    // Tilted 30° towards +x (tangent space's x is the square's u, +x),
    // as 8-bit texels store it; the geometric square is turned to the
    // normal those bytes decode to.
    let (s, c) = 30f32.to_radians().sin_cos();
    let bytes = [byte(s), byte(0.0), byte(c)];
    let n = decoded(bytes).normalize();
    let mapped = square(r#"{"normalTexture":{"index":0}}"#, &[texel(bytes)], false);
    assert!(mapped.tangents.is_some());
    let got = middle(&scene(mapped, &[LIGHT]));
    assert_shades_as_tilted(got, n);
    let flat = middle(&scene(square("{}", &[], false), &[LIGHT]));
    assert!(
        flat.0[0] + 2000 < got.0[0],
        "the tilt turns it to the light: {flat:?}, {got:?}"
    );
}

#[test]
fn mirrored_uvs_turn_the_map_with_them() {
    // The same texel on a square whose u runs the other way: its tangent
    // is −x, so the map tilts it the other way, as the square turned to
    // the normal mirrored in x.
    let (s, c) = 30f32.to_radians().sin_cos();
    let bytes = [byte(s), byte(0.0), byte(c)];
    let mirrored = square(r#"{"normalTexture":{"index":0}}"#, &[texel(bytes)], true);
    let n = decoded(bytes).normalize() * Vec3::new(-1.0, 1.0, 1.0);
    assert_shades_as_tilted(middle(&scene(mirrored, &[LIGHT])), n);
}

#[test]
fn occlusion_darkens_the_ambient_share_alone() {
    // Under ambient light alone (share 1, from behind: no direct light),
    // a white square is the light times the occlusion: texel 128 at
    // strength 1, and halfway back to 1 at strength 0.5.
    let behind = (Vec3::new(0.0, 0.0, 1.0), 1.0);
    let occ = 128.0f32 / 255.0;
    for (strength, share) in [(1.0f32, occ), (0.5, 1.0 + 0.5 * (occ - 1.0))] {
        let g = square(
            &format!(r#"{{"occlusionTexture":{{"index":0,"strength":{strength}}}}}"#),
            &[texel([128, 0, 0])],
            false,
        );
        let want = Lin::from_f32([65535.0 * share; 3]);
        assert_eq!(middle(&scene(g, &[behind])), want, "strength {strength}");
    }
    // Lit from the front with no ambient share, occlusion changes nothing.
    let front = (Vec3::new(0.0, 0.0, -1.0), 0.0);
    let g = square(
        r#"{"occlusionTexture":{"index":0}}"#,
        &[texel([0, 0, 0])],
        false,
    );
    assert_eq!(middle(&scene(g, &[front])), Lin::WHITE);
}

#[test]
fn an_emissive_map_glows_texel_by_texel() {
    // A black square without lights is its emitted light: the factor
    // (1, 0.5, 1) times the texel, decoded from sRGB.
    let g = square(
        r#"{"pbrMetallicRoughness":{"baseColorFactor":[0,0,0,1]},"emissiveFactor":[1,0.5,1],"emissiveTexture":{"index":0}}"#,
        &[texel([200, 100, 0])],
        false,
    );
    let t = Lin::from_srgb(Rgb::new(200, 100, 0)).to_f32();
    let want = Lin::from_f32([t[0], t[1] * 0.5, t[2]]);
    assert_eq!(middle(&scene(g, &[])), want);
}

#[test]
fn a_metallic_roughness_map_multiplies_the_factors() {
    // Texel (·, g, b) with factors 1 draws as texel (·, 255, 255) with
    // factors g/255 and b/255, bit for bit; and a metal of it is not
    // the same surface as a dielectric.
    let (g, b) = (140u8, 200u8);
    let mapped = |rough: f32, metal: f32, t: [u8; 3]| {
        square(
            &format!(
                r#"{{"pbrMetallicRoughness":{{"baseColorFactor":[0.8,0.5,0.2,1],"roughnessFactor":{rough},"metallicFactor":{metal},"metallicRoughnessTexture":{{"index":0}}}}}}"#
            ),
            &[texel(t)],
            false,
        )
    };
    let lights = [(Vec3::new(-0.4, -0.2, -1.0), 0.1)];
    let by_map = middle(&scene(mapped(1.0, 1.0, [0, g, b]), &lights));
    let by_factor = middle(&scene(
        mapped(f32::from(g) / 255.0, f32::from(b) / 255.0, [0, 255, 255]),
        &lights,
    ));
    assert_eq!(by_map, by_factor);
    let dielectric = middle(&scene(mapped(1.0, 1.0, [0, g, 0]), &lights));
    assert_ne!(by_map, dielectric);
}

#[test]
fn a_specular_glossiness_texture_multiplies_the_factors() {
    // Texel (specular colour c, glossiness a) with factors 1 (and 0.6
    // glossiness) draws as a white texel of full alpha with factors c
    // (decoded from sRGB) and 0.6·a/255: within a step of rounding (the
    // products are taken in another order).
    let sg = |spec: [f32; 3], gloss: f32, t: [u8; 4]| {
        square(
            &format!(
                r#"{{"extensions":{{"KHR_materials_pbrSpecularGlossiness":{{"diffuseFactor":[0.3,0.3,0.3,1],"specularFactor":{spec:?},"glossinessFactor":{gloss},"specularGlossinessTexture":{{"index":0}}}}}}}}"#
            ),
            &[common::png_rgba(1, 1, &[t])],
            false,
        )
    };
    let lights = [(Vec3::new(-0.3, -0.2, -1.0), 0.1)];
    let (c, a) = ([255u8, 128, 0], 128u8);
    let linear = |b: u8| rastty::color::Lin::from_srgb(Rgb::new(b, b, b)).to_f32()[0] / 65535.0;
    let by_map = middle(&scene(sg([1.0; 3], 0.6, [c[0], c[1], c[2], a]), &lights));
    let by_factor = middle(&scene(
        sg(c.map(linear), 0.6 * f32::from(a) / 255.0, [255; 4]),
        &lights,
    ));
    for i in 0..3 {
        assert!(
            by_map.0[i].abs_diff(by_factor.0[i]) <= 1,
            "{by_map:?} {by_factor:?}"
        );
    }
    // A black specular texel takes the highlight away.
    let dull = middle(&scene(sg([1.0; 3], 0.6, [0, 0, 0, 255]), &lights));
    assert_eq!(dull, Lin([18612; 3]));
    assert!(
        by_map.0[0] > dull.0[0] && by_map.0[1] > dull.0[1],
        "{by_map:?}"
    );
}

#[test]
fn a_mapped_frame_is_the_same_planned_or_full_and_in_bands() {
    let (s, c) = 20f32.to_radians().sin_cos();
    let g = square(
        r#"{"normalTexture":{"index":0},"occlusionTexture":{"index":1},"emissiveFactor":[0.2,0.1,0],"emissiveTexture":{"index":1},"pbrMetallicRoughness":{"metallicRoughnessTexture":{"index":1}}}"#,
        &[
            png_rgb(
                2,
                2,
                &[
                    [byte(s), 128, byte(c)],
                    [128, byte(-s), byte(c)],
                    [128, 128, 255],
                    [byte(-s), 128, byte(c)],
                ],
            ),
            png_rgb(2, 1, &[[255, 100, 0], [120, 200, 255]]),
        ],
        false,
    );
    let scene = scene(g, &[LIGHT, (Vec3::new(0.5, -1.0, -0.5), 0.2)]);
    let (planned, r) = draw(&scene, Pipeline::Planned);
    assert!(r.plan().unwrap()[Effect::Maps].run);
    assert_eq!(
        r.stats().mapped_samples,
        planned.iter().flatten().count() as u64
    );
    // --explain says which faces get which maps.
    let report = r.explain(&scene, &RenderOptions::default(), Default::default(), 0);
    assert!(
        report.contains(
            "faces 0..2: maps (normal, metallic-roughness, occlusion, emissive): shaded per sample"
        ),
        "{report}"
    );
    let (full, _) = draw(&scene, Pipeline::Full);
    assert_eq!(planned, full);
    let mut banded = Renderer::new();
    banded.render(
        &scene,
        &RenderOptions {
            cols: 40,
            rows: 20,
            threads: Threads::Exactly(3),
            ..RenderOptions::default()
        },
    );
    assert_eq!(banded.framebuffer().samples(), &planned[..]);
}

#[test]
fn the_example_finishes_are_what_their_builder_makes() {
    let path = crate::common::example_model("finishes.glb", crate::common::finishes_glb());
    let loaded = gltf::load(&path, &LoadOptions::default()).unwrap();
    assert!(loaded.notes.is_empty(), "{:?}", loaded.notes);
    let g = &loaded.geometry;
    assert_eq!(g.faces.len(), 6);
    let finishes: Vec<_> = g.materials.iter().map(|m| m.finish).collect();
    assert!(finishes[0].emissive != rastty::color::Lin::BLACK);
    assert_eq!(finishes[1].alpha.mode, rastty::scene::AlphaMode::Blend);
    assert!(finishes[2].maps.normal.is_some());
}
