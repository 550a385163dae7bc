//! The glTF core spec whole, on files the tests write: sparse accessors
//! and `KHR_mesh_quantization`'s integer attributes read as the same
//! floats, and drawn as the same samples, as the plain float file.

use crate::common;

use std::sync::Arc;

use common::Doc;
use glam::Vec3;
use rastty::color::Rgb;
use rastty::scene::{Camera, Geometry, LoadOptions, Mesh, Projection, Scene, gltf};
use rastty::{RenderOptions, Renderer};

/// A square of side 2 in z = 0, tilted to the light by its normals.
const CORNERS: [[f32; 3]; 4] = [
    [-1.0, -1.0, 0.0],
    [1.0, -1.0, 0.0],
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
];
const NORMALS: [[f32; 3]; 4] = [
    [0.0, 0.0, 1.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
];

fn glb(d: &Doc, pos: usize, normal: usize, idx: usize, extra: &str) -> Vec<u8> {
    d.glb(&format!(
        r#"{extra}"meshes":[{{"primitives":[{{"attributes":{{"POSITION":{pos},"NORMAL":{normal}}},"indices":{idx}}}]}}],
"nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0"#
    ))
}

fn plain() -> Vec<u8> {
    let mut d = Doc::default();
    let pos = d.vec3(&CORNERS);
    let normal = d.vec3(&NORMALS);
    let idx = d.indices(&[[0, 1, 2], [0, 2, 3]]);
    glb(&d, pos, normal, idx, "")
}

fn load(glb: &[u8]) -> Geometry {
    let loaded = gltf::parse(glb, None, "t.glb", &LoadOptions::default()).unwrap();
    assert!(loaded.notes.is_empty(), "{:?}", loaded.notes);
    loaded.geometry
}

/// The frame's samples, as the renderer users run draws `g`.
fn samples(g: Geometry) -> Vec<Option<rastty::color::Lin>> {
    let scene = Scene::builder()
        .camera(Camera {
            projection: Projection::Perspective {
                fov_y: 60.0,
                near: 0.1,
                far: 20.0,
            },
            eye: Vec3::new(0.5, 0.3, 4.0),
            target: Vec3::ZERO,
            ..Camera::default()
        })
        .mesh(Mesh::of(Arc::new(g), Rgb::new(200, 150, 100)))
        .build()
        .unwrap();
    let mut r = Renderer::new();
    r.render(
        &scene,
        &RenderOptions {
            cols: 40,
            rows: 20,
            ..RenderOptions::default()
        },
    );
    r.framebuffer().samples().to_vec()
}

fn le<T: Copy, const N: usize>(v: &[T], f: fn(T) -> [u8; N]) -> Vec<u8> {
    v.iter().flat_map(|&x| f(x)).collect()
}

#[test]
fn quantized_positions_and_normals_read_as_the_same_floats_and_samples() {
    let want = load(&plain());
    assert!(samples(want.clone()).iter().any(Option::is_some));
    // Positions as shorts (plain integers: −1, 1), normals as normalized
    // bytes (127 is 1), with the extension's name, as gltfpack writes.
    let mut d = Doc::default();
    let shorts: Vec<i16> = CORNERS.as_flattened().iter().map(|&v| v as i16).collect();
    // Each position padded to 4-byte alignment: 8 bytes a vertex.
    let padded: Vec<u8> = shorts
        .chunks(3)
        .flat_map(|p| le(p, i16::to_le_bytes).into_iter().chain([0, 0]))
        .collect();
    let view = d.view(&padded);
    let pos = d.accessor(format!(
        r#"{{"bufferView":{view},"byteOffset":0,"componentType":5122,"count":4,"type":"VEC3","min":[-1,-1,0],"max":[1,1,0]}}"#
    ));
    // A stride of 8 for the padded positions: written on the view.
    let normal_bytes: Vec<u8> = NORMALS
        .iter()
        .flat_map(|n| n.map(|v| (v * 127.0) as i8 as u8).into_iter().chain([0]))
        .collect();
    let nview = d.view(&normal_bytes);
    let normal = d.accessor(format!(
        r#"{{"bufferView":{nview},"componentType":5120,"normalized":true,"count":4,"type":"VEC3"}}"#
    ));
    let idx = d.indices(&[[0, 1, 2], [0, 2, 3]]);
    let mut file = glb(
        &d,
        pos,
        normal,
        idx,
        r#""extensionsUsed":["KHR_mesh_quantization"],"extensionsRequired":["KHR_mesh_quantization"],"#,
    );
    // The views' strides (Doc writes none): 8 bytes and 4.
    file = restride(&file, &[(view, 8), (nview, 4)]);
    let got = load(&file);
    assert_eq!(got.positions, want.positions);
    assert_eq!(got.normals, want.normals);
    assert_eq!(samples(got), samples(want));
}

#[test]
fn sparse_positions_and_normals_read_as_the_same_floats_and_samples() {
    let want = load(&plain());
    // Positions: a base of four zeros, corners 1 and 2 replaced; corner 0
    // and 3 replaced too, in a second accessor with no base at all.
    let mut d = Doc::default();
    let base = [[-1.0, -1.0, 0.0], [0.0; 3], [0.0; 3], [-1.0, 1.0, 0.0]];
    let base_view = d.view(&common::f32s(base.as_flattened()));
    let idx_view = d.view(&le(&[1u16, 2], u16::to_le_bytes));
    let val_view = d.view(&common::f32s([CORNERS[1], CORNERS[2]].as_flattened()));
    let pos = d.accessor(format!(
        r#"{{"bufferView":{base_view},"componentType":5126,"count":4,"type":"VEC3","min":[-1,-1,0],"max":[1,1,0],
"sparse":{{"count":2,"indices":{{"bufferView":{idx_view},"componentType":5123}},"values":{{"bufferView":{val_view}}}}}}}"#
    ));
    // Normals with no base: zeros, all four given, as bytes indices.
    let nidx = d.view(&[0, 1, 2, 3]);
    let nval = d.view(&common::f32s(NORMALS.as_flattened()));
    let normal = d.accessor(format!(
        r#"{{"componentType":5126,"count":4,"type":"VEC3",
"sparse":{{"count":4,"indices":{{"bufferView":{nidx},"componentType":5121}},"values":{{"bufferView":{nval}}}}}}}"#
    ));
    let idx = d.indices(&[[0, 1, 2], [0, 2, 3]]);
    let got = load(&glb(&d, pos, normal, idx, ""));
    assert_eq!(got.positions, want.positions);
    assert_eq!(got.normals, want.normals);
    assert_eq!(samples(got), samples(want));
}

#[test]
fn sparse_indices_out_of_order_or_past_the_end_are_refused_by_name() {
    for (indices, says) in [
        ([2u16, 1], "sparse index 1 is 1, out of order"),
        ([1, 4], "sparse index 1 is 4, past its elements"),
    ] {
        let mut d = Doc::default();
        let base_view = d.view(&common::f32s(CORNERS.as_flattened()));
        let idx_view = d.view(&le(&indices, u16::to_le_bytes));
        let val_view = d.view(&common::f32s([CORNERS[1], CORNERS[2]].as_flattened()));
        let pos = d.accessor(format!(
            r#"{{"bufferView":{base_view},"componentType":5126,"count":4,"type":"VEC3","min":[-1,-1,0],"max":[1,1,0],
"sparse":{{"count":2,"indices":{{"bufferView":{idx_view},"componentType":5123}},"values":{{"bufferView":{val_view}}}}}}}"#
        ));
        let normal = d.vec3(&NORMALS);
        let idx = d.indices(&[[0, 1, 2], [0, 2, 3]]);
        let err = gltf::parse(
            &glb(&d, pos, normal, idx, ""),
            None,
            "t.glb",
            &LoadOptions::default(),
        )
        .unwrap_err()
        .to_string();
        assert_eq!(
            err,
            format!(
                "t.glb: mesh 0 primitive 0: POSITION (accessor 0): {says} (they must increase, below 4)"
            )
        );
    }
}

/// `file` with `"byteStride"` set on the given buffer views (the GLB's
/// JSON chunk rewritten, padded with spaces).
fn restride(file: &[u8], strides: &[(usize, usize)]) -> Vec<u8> {
    let json_len = u32::from_le_bytes(file[12..16].try_into().unwrap()) as usize;
    let json = std::str::from_utf8(&file[20..20 + json_len]).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(json.trim_end()).unwrap();
    for &(view, stride) in strides {
        v["bufferViews"][view]["byteStride"] = stride.into();
    }
    let bin_json_len = 20 + json_len;
    let bin = &file[bin_json_len + 8..];
    common::glb(&v.to_string(), bin)
}

/// Two squares side by side facing +z (x in [−2, 0] and [0, 2]), each its
/// own primitive and material, `doubleSided` as given.
fn two_squares(left: bool, right: bool) -> Geometry {
    let mut d = Doc::default();
    let mut prims = Vec::new();
    for (k, x0) in [-2.0f32, 0.0].into_iter().enumerate() {
        let pos = d.vec3(&[
            [x0, -1.0, 0.0],
            [x0 + 2.0, -1.0, 0.0],
            [x0 + 2.0, 1.0, 0.0],
            [x0, 1.0, 0.0],
        ]);
        let normal = d.vec3(&[[0.0, 0.0, 1.0]; 4]);
        let idx = d.indices(&[[0, 1, 2], [0, 2, 3]]);
        prims.push(format!(
            r#"{{"attributes":{{"POSITION":{pos},"NORMAL":{normal}}},"indices":{idx},"material":{k}}}"#
        ));
    }
    load(&d.glb(&format!(
        r#""materials":[{{"doubleSided":{left}}},{{"doubleSided":{right}}}],
"meshes":[{{"primitives":[{}]}}],"nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0"#,
        prims.join(",")
    )))
}

/// The colours of the covered samples left and right of the frame's
/// middle, seen from `eye` on the z axis, lit along `light`; `cull` as
/// `--cull` would set it.
fn halves(
    g: Geometry,
    eye: f32,
    light: Vec3,
    cull: Option<rastty::scene::Cull>,
) -> [Vec<rastty::color::Lin>; 2] {
    let scene = Scene::builder()
        .camera(Camera {
            projection: Projection::Orthographic {
                height: 3.0,
                near: 0.1,
                far: 20.0,
            },
            eye: Vec3::new(0.0, 0.0, eye),
            target: Vec3::ZERO,
            ..Camera::default()
        })
        .mesh(Mesh::of(Arc::new(g), Rgb::new(200, 150, 100)))
        .light(rastty::scene::Light {
            direction: light,
            color: Rgb::new(255, 255, 255),
            ambient: 0.0,
            ..Default::default()
        })
        .build()
        .unwrap();
    let opts = RenderOptions {
        cols: 40,
        rows: 20,
        cull,
        ..RenderOptions::default()
    };
    let mut r = Renderer::new();
    r.render(&scene, &opts);
    let w = opts.grid().width as usize;
    let mut out = [Vec::new(), Vec::new()];
    for (i, s) in r.framebuffer().samples().iter().enumerate() {
        if let Some(c) = s {
            out[usize::from(i % w >= w / 2)].push(*c);
        }
    }
    for h in &mut out {
        h.sort_by_key(|c| c.0);
        h.dedup();
    }
    out
}

#[test]
fn a_single_sided_back_face_is_culled_and_a_double_sided_one_drawn_lit_on_its_seen_side() {
    // From the front, lit from the front: both squares the same colour.
    let front = halves(
        two_squares(false, true),
        4.0,
        Vec3::new(0.0, 0.0, -1.0),
        None,
    );
    assert_eq!(front[0].len(), 1, "{front:?}");
    assert_eq!(front[0], front[1]);
    // From behind, lit from behind: seen from behind, the left square is
    // to the right. The single-sided one culled, the double-sided one
    // lit as its flipped normal says: as the front was from the front.
    let back = halves(
        two_squares(false, true),
        -4.0,
        Vec3::new(0.0, 0.0, 1.0),
        None,
    );
    assert_eq!(
        back,
        [front[0].clone(), vec![]],
        "double-sided on the left, as seen"
    );
    // Lit from the front instead, the back face is dark (no ambient).
    let dark = halves(
        two_squares(false, true),
        -4.0,
        Vec3::new(0.0, 0.0, -1.0),
        None,
    );
    assert_eq!(dark[1], vec![]);
    assert_ne!(dark[0], front[0]);
    // --cull none draws both; --cull back culls both.
    let none = halves(
        two_squares(false, true),
        -4.0,
        Vec3::new(0.0, 0.0, 1.0),
        Some(rastty::scene::Cull::None),
    );
    assert_eq!(none, [front[0].clone(), front[0].clone()]);
    let back_culled = halves(
        two_squares(false, true),
        -4.0,
        Vec3::new(0.0, 0.0, 1.0),
        Some(rastty::scene::Cull::Back),
    );
    assert_eq!(back_culled, [vec![], vec![]]);
    // Both single-sided: nothing from behind, though the mesh is open.
    let g = two_squares(false, false);
    assert_eq!(g.sides, rastty::scene::Sides::Single);
    assert!(!g.closed);
    assert_eq!(
        halves(g, -4.0, Vec3::new(0.0, 0.0, 1.0), None),
        [vec![], vec![]]
    );
    // Both double-sided: both drawn.
    assert_eq!(
        halves(
            two_squares(true, true),
            -4.0,
            Vec3::new(0.0, 0.0, 1.0),
            None
        ),
        [front[0].clone(), front[0].clone()]
    );
}

#[test]
fn an_instanced_mesh_is_drawn_once_an_instance_each_placed_before_its_node() {
    // A triangle, three instances: moved 10 along x, turned a quarter
    // about z, and scaled 2 (its rotation a normalized short quaternion);
    // the node then moves everything 100 along y.
    let mut d = Doc::default();
    let pos = d.vec3(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let idx = d.indices(&[[0, 1, 2]]);
    let t = d.vec3(&[[10.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]);
    let h = (std::f32::consts::FRAC_1_SQRT_2 * 32767.0).round() as i16;
    let shorts: Vec<u8> = [0, 0, 0, 32767, 0, 0, h, h, 0, 0, 0, 32767]
        .iter()
        .flat_map(|v: &i16| v.to_le_bytes())
        .collect();
    let view = d.view(&shorts);
    let r = d.accessor(format!(
        r#"{{"bufferView":{view},"componentType":5122,"normalized":true,"count":3,"type":"VEC4"}}"#
    ));
    let s = d.vec3(&[[1.0, 1.0, 1.0], [1.0, 1.0, 1.0], [2.0, 2.0, 2.0]]);
    let glb = d.glb(&format!(
        r#""extensionsUsed":["EXT_mesh_gpu_instancing"],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":{pos}}},"indices":{idx}}}]}}],
"nodes":[{{"mesh":0,"translation":[0,100,0],"extensions":{{"EXT_mesh_gpu_instancing":{{"attributes":{{"TRANSLATION":{t},"ROTATION":{r},"SCALE":{s}}}}}}}}}],
"scenes":[{{"nodes":[0]}}],"scene":0"#
    ));
    let g = load(&glb);
    assert_eq!(g.faces.len(), 3);
    let round = |v: Vec3| (v * 1e4).round() / 1e4;
    let got: Vec<Vec3> = g.positions.iter().map(|&p| round(p)).collect();
    assert_eq!(
        got,
        [
            [10.0, 100.0, 0.0],
            [11.0, 100.0, 0.0],
            [10.0, 101.0, 0.0],
            [0.0, 100.0, 0.0],
            [0.0, 101.0, 0.0],
            [-1.0, 100.0, 0.0],
            [0.0, 100.0, 0.0],
            [2.0, 100.0, 0.0],
            [0.0, 102.0, 0.0],
        ]
        .map(Vec3::from)
    );
}

#[test]
fn line_and_point_primitives_are_drawn_one_sample_wide_in_their_colours() {
    let path = common::example_model("lines.gltf", common::lines_gltf());
    let loaded = gltf::load(&path, &LoadOptions::default()).unwrap();
    assert!(loaded.notes.is_empty(), "{:?}", loaded.notes);
    let g = loaded.geometry;
    assert_eq!(g.faces.len(), 1);
    // A loop of 4, 2 diagonals, a strip of 7 (6 lines), 25 points.
    assert_eq!(g.lines.len(), 4 + 2 + 6 + 25);
    let first = |k: usize| g.lines[k].1.unwrap();
    assert_eq!(first(0), rastty::color::Lin::from_unit([1.0, 0.0, 0.0]));
    assert_eq!(
        g.lines[12],
        (
            [18, 18],
            Some(rastty::color::Lin::from_unit([1.0, 1.0, 1.0]))
        )
    );
    // Seen face on, unlit: a point is one sample of white; the square's
    // lines are red; the triangle grey.
    let scene = Scene::builder()
        .camera(Camera {
            projection: Projection::Orthographic {
                height: 3.2,
                near: 0.1,
                far: 20.0,
            },
            eye: Vec3::new(0.0, 0.0, 4.0),
            target: Vec3::ZERO,
            ..Camera::default()
        })
        .mesh(Mesh::of(Arc::new(g), Rgb::new(9, 9, 9)))
        .build()
        .unwrap();
    let mut r = Renderer::new();
    r.render(
        &scene,
        &RenderOptions {
            cols: 64,
            rows: 32,
            ..RenderOptions::default()
        },
    );
    let count = |c: [f32; 3]| {
        let c = rastty::color::Lin::from_unit(c);
        r.framebuffer()
            .samples()
            .iter()
            .filter(|s| **s == Some(c))
            .count()
    };
    // 25 points, less those the square's lines or the triangle cover.
    let white = count([1.0, 1.0, 1.0]);
    assert!((16..=25).contains(&white), "{white} white samples");
    assert!(count([1.0, 0.0, 0.0]) > 4 * 30, "the square's four sides");
    assert!(
        count([0.0, 1.0, 0.0]) > 2 * 30,
        "the diagonals: {}",
        count([0.0, 1.0, 0.0])
    );
    assert!(count([0.0, 0.2, 1.0]) > 20, "the zigzag");
    assert!(count([0.5, 0.5, 0.5]) > 50, "the triangle");
}

/// A square textured with a 2×2 image of four colours (nearest), its
/// proper coordinates on set `set` and zeros on the other, the texture
/// read through `set`.
fn textured_square(set: u32) -> Vec<u8> {
    let mut d = Doc::default();
    let pos = d.vec3(&CORNERS);
    let normal = d.vec3(&[[0.0, 0.0, 1.0]; 4]);
    let proper: Vec<f32> = [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]].concat();
    let uv = d.floats(&proper, "VEC2", 2);
    let zeros = d.floats(&[0.0; 8], "VEC2", 2);
    let (uv0, uv1) = if set == 0 { (uv, zeros) } else { (zeros, uv) };
    let idx = d.indices(&[[0, 1, 2], [0, 2, 3]]);
    let png = common::png_rgb(
        2,
        2,
        &[[255, 0, 0], [0, 255, 0], [0, 0, 255], [255, 255, 0]],
    );
    let view = d.view(&png);
    d.glb(&format!(
        r#""materials":[{{"pbrMetallicRoughness":{{"baseColorTexture":{{"index":0,"texCoord":{set}}}}}}}],
"samplers":[{{"magFilter":9728,"minFilter":9728}}],
"images":[{{"bufferView":{view},"mimeType":"image/png"}}],"textures":[{{"source":0,"sampler":0}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":{pos},"NORMAL":{normal},"TEXCOORD_0":{uv0},"TEXCOORD_1":{uv1}}},"indices":{idx},"material":0}}]}}],
"nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0"#
    ))
}

#[test]
fn a_texture_on_the_second_coordinate_set_is_read_through_it() {
    let (on0, on1) = (load(&textured_square(0)), load(&textured_square(1)));
    assert_eq!(on1.uvs, on0.uvs);
    let (a, b) = (samples(on0), samples(on1));
    assert_eq!(a, b);
    // Four colours, not the one texel the zeros would read.
    let mut seen: Vec<_> = a.iter().flatten().map(|c| c.0).collect();
    seen.sort_unstable();
    seen.dedup();
    assert!(seen.len() >= 4, "{seen:?}");
}

#[test]
fn textures_kept_to_the_side_a_frame_can_show_draw_the_same_picture() {
    assert_eq!(rastty::scene::texture_side_for((120, 80), 1.0), 256);
    assert_eq!(rastty::scene::texture_side_for((960, 540), 1.0), 2048);
    assert_eq!(rastty::scene::texture_side_for((200, 120), 3.0), 2048);
    assert_eq!(rastty::scene::texture_side_for((300, 120), 1.0), 1024);
    // A 512² texture of stripes and noise on the square, trilinear, drawn
    // at 40×20 cells: kept to 256 it is the same picture, sample for
    // sample.
    let texels: Vec<[u8; 3]> = (0..512 * 512u32)
        .map(|i| {
            let (x, y) = (i % 512, i / 512);
            [
                ((x / 8) % 2 * 255) as u8,
                (y * 7 % 256) as u8,
                ((x ^ y) % 256) as u8,
            ]
        })
        .collect();
    let png = common::png_rgb(512, 512, &texels);
    let mut d = Doc::default();
    let pos = d.vec3(&CORNERS);
    let normal = d.vec3(&[[0.0, 0.0, 1.0]; 4]);
    let uv = d.floats(
        &[[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]].concat(),
        "VEC2",
        2,
    );
    let idx = d.indices(&[[0, 1, 2], [0, 2, 3]]);
    let view = d.view(&png);
    let glb = d.glb(&format!(
        r#""materials":[{{"pbrMetallicRoughness":{{"baseColorTexture":{{"index":0}}}}}}],
"images":[{{"bufferView":{view},"mimeType":"image/png"}}],"textures":[{{"source":0}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":{pos},"NORMAL":{normal},"TEXCOORD_0":{uv}}},"indices":{idx},"material":0}}]}}],
"nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0"#
    ));
    let with = |side| {
        let options = LoadOptions {
            max_texture_side: side,
            ..LoadOptions::default()
        };
        gltf::parse(&glb, None, "t.glb", &options).unwrap().geometry
    };
    let (full, kept) = (with(rastty::texture::MAX_SIDE), with(256));
    assert_eq!(full.textures[0].size(), (512, 512));
    assert_eq!(kept.textures[0].size(), (256, 256));
    assert_eq!(kept.textures[0].original_size(), (512, 512));
    assert_eq!(samples(kept), samples(full));
}

#[test]
fn a_transmissive_material_is_drawn_see_through_with_a_note_that_refraction_is_not() {
    for (material, mode, factor) in [
        (
            r#"{"extensions":{"KHR_materials_transmission":{"transmissionFactor":1}}}"#,
            "blend",
            0.25,
        ),
        (
            r#"{"alphaMode":"BLEND","pbrMetallicRoughness":{"baseColorFactor":[1,1,1,0.8]},"extensions":{"KHR_materials_transmission":{"transmissionFactor":0.5}}}"#,
            "blend",
            0.8 * 0.625,
        ),
        (
            r#"{"extensions":{"KHR_materials_transmission":{"transmissionFactor":0}}}"#,
            "opaque",
            1.0,
        ),
    ] {
        let mut d = Doc::default();
        let pos = d.vec3(&CORNERS);
        let idx = d.indices(&[[0, 1, 2], [0, 2, 3]]);
        let glb = d.glb(&format!(
            r#""extensionsUsed":["KHR_materials_transmission"],"materials":[{material}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":{pos}}},"indices":{idx},"material":0}}]}}],
"nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0"#
        ));
        let loaded = gltf::parse(&glb, None, "t.glb", &LoadOptions::default()).unwrap();
        assert_eq!(
            loaded.notes,
            ["t.glb: not drawn: 1 transmissive primitives' refraction (drawn see-through)"]
        );
        let alpha = loaded.geometry.materials[0].finish.alpha;
        let got = match alpha.mode {
            rastty::scene::AlphaMode::Blend => "blend",
            rastty::scene::AlphaMode::Opaque => "opaque",
            rastty::scene::AlphaMode::Mask { .. } => "mask",
        };
        assert_eq!((got, alpha.factor), (mode, factor), "{material}");
    }
}

#[test]
fn all_clips_play_at_once_each_moving_its_own_node() {
    // Two triangles, each its node's; clip 0 moves node 0 along x, clip 1
    // node 1 along y, over a second (the second clip half as long).
    let mut d = Doc::default();
    let pos = d.vec3(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let idx = d.indices(&[[0, 1, 2]]);
    let times = d.floats(&[0.0, 1.0], "SCALAR", 1);
    let short = d.floats(&[0.0, 0.5], "SCALAR", 1);
    let along_x = d.vec3(&[[0.0, 0.0, 0.0], [4.0, 0.0, 0.0]]);
    let along_y = d.vec3(&[[0.0, 0.0, 0.0], [0.0, 4.0, 0.0]]);
    let glb = d.glb(&format!(
        r#""meshes":[{{"primitives":[{{"attributes":{{"POSITION":{pos}}},"indices":{idx}}}]}}],
"nodes":[{{"mesh":0}},{{"mesh":0,"translation":[0,0,10]}}],"scenes":[{{"nodes":[0,1]}}],"scene":0,
"animations":[
 {{"channels":[{{"sampler":0,"target":{{"node":0,"path":"translation"}}}}],"samplers":[{{"input":{times},"output":{along_x}}}]}},
 {{"channels":[{{"sampler":0,"target":{{"node":1,"path":"translation"}}}}],"samplers":[{{"input":{short},"output":{along_y}}}]}}]"#
    ));
    let g = load(&glb);
    let mut rig = (**g.rig.as_ref().unwrap()).clone();
    assert_eq!(rig.clips.len(), 2);
    let all = rig.add_all_clips();
    assert_eq!(
        (all, rig.clips[all].name.as_str(), rig.clips[all].length),
        (2, "all", 1.0)
    );
    let pose = |clip, time| {
        let (mut ps, mut ns) = (g.positions.clone(), g.normals.clone());
        let pose = rastty::scene::anim::Pose { clip, time };
        rig.pose_into(Some(pose), &mut Default::default(), &mut ps, &mut ns);
        // Each triangle's first corner.
        [ps[0], ps[3]]
    };
    // The walk places node 1 first. At a quarter of a second: node 0 a
    // quarter of the way along x, node 1 half of the way along y (its clip
    // is half as long; the clip's translation replaces its own).
    let (x, y) = (Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0));
    assert_eq!(pose(all, 0.25), [y, x]);
    // Each clip alone moves its own node only.
    assert_eq!(pose(0, 0.25), [Vec3::new(0.0, 0.0, 10.0), x]);
    assert_eq!(pose(1, 0.25), [y, Vec3::ZERO]);
}

/// The square of [`plain`] as a Draco stream (positions and normals as
/// floats, unquantized; `method` 0 sequential, 1 Edgebreaker) in a glb
/// whose accessors have no buffer view, as `KHR_draco_mesh_compression`
/// writes it; `edit` changes the stream's bytes first.
fn draco_square(method: i32, mut edit: impl FnMut(&mut Vec<u8>)) -> Vec<u8> {
    use draco_core::{
        DataType, EncoderBuffer, EncoderOptions, FaceIndex, GeometryAttributeType, MeshEncoder,
        PointAttribute, PointIndex,
    };
    let mut mesh = draco_core::Mesh::new();
    for (kind, values) in [
        (GeometryAttributeType::Position, CORNERS),
        (GeometryAttributeType::Normal, NORMALS),
    ] {
        let mut a = PointAttribute::new();
        a.init(kind, 3, DataType::Float32, false, 4);
        for (i, v) in values.iter().enumerate() {
            a.buffer_mut().write(i * 12, &le(v, f32::to_le_bytes));
        }
        mesh.add_attribute(a);
    }
    mesh.set_num_faces(2);
    for (f, [a, b, c]) in [[0, 1, 2], [0, 2, 3]].into_iter().enumerate() {
        mesh.set_face(
            FaceIndex(f as u32),
            [PointIndex(a), PointIndex(b), PointIndex(c)],
        );
    }
    let mut encoder = MeshEncoder::new();
    encoder.set_mesh(mesh);
    let mut options = EncoderOptions::new();
    options.set_encoding_method(method);
    let mut out = EncoderBuffer::new();
    encoder.encode(&options, &mut out).unwrap();
    let mut stream = out.data().to_vec();
    edit(&mut stream);
    let mut d = Doc::default();
    let view = d.view(&stream);
    let pos = d.accessor(
        r#"{"componentType":5126,"count":4,"type":"VEC3","min":[-1,-1,0],"max":[1,1,0]}"#.into(),
    );
    let normal = d.accessor(r#"{"componentType":5126,"count":4,"type":"VEC3"}"#.into());
    let idx = d.accessor(r#"{"componentType":5123,"count":6,"type":"SCALAR"}"#.into());
    d.glb(&format!(
        r#""extensionsUsed":["KHR_draco_mesh_compression"],"extensionsRequired":["KHR_draco_mesh_compression"],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":{pos},"NORMAL":{normal}}},"indices":{idx},
"extensions":{{"KHR_draco_mesh_compression":{{"bufferView":{view},"attributes":{{"POSITION":0,"NORMAL":1}}}}}}}}]}}],
"nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0"#
    ))
}

#[test]
fn a_draco_stream_reads_as_the_same_floats_and_samples() {
    let want = load(&plain());
    for method in [0, 1] {
        let got = load(&draco_square(method, |_| {}));
        // Edgebreaker orders the points as it walks the faces: the same
        // vertices, in another order.
        let vertices = |g: &Geometry| {
            let mut v: Vec<[u32; 6]> = (g.positions.iter().zip(&g.normals))
                .map(|(p, n)| [p.x, p.y, p.z, n.x, n.y, n.z].map(f32::to_bits))
                .collect();
            v.sort();
            v
        };
        assert_eq!(vertices(&got), vertices(&want), "method {method}");
        assert_eq!(samples(got), samples(want.clone()), "method {method}");
    }
}

#[test]
fn damaged_draco_streams_are_refused_never_drawn_as_another_mesh() {
    let want = load(&plain());
    let parse = |file: &[u8]| gltf::parse(file, None, "t.glb", &LoadOptions::default());
    // A header that claims more faces than the accessors: refused before
    // decoding (the sequential stream's face count is its 12th byte, a
    // varint).
    let more = draco_square(0, |s| s[11] = 200);
    let Err(e) = parse(&more) else {
        panic!("a stream of more faces than its accessors was read")
    };
    let e = e.to_string();
    assert!(e.contains("more than its accessors'"), "{e}");
    // Bytes flipped and streams cut short: each read as the square, or
    // refused with a message; never a panic, never another mesh.
    let mut seed = 7u64;
    let mut refused = 0;
    for t in 0..200 {
        let file = draco_square(t % 2, |s| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let i = (seed >> 33) as usize % s.len();
            if t % 3 == 0 {
                s.truncate(i);
            } else {
                s[i] ^= (seed >> 20) as u8 | 1;
            }
        });
        match parse(&file) {
            Ok(got) => assert_eq!(got.geometry.faces.len(), want.faces.len()),
            Err(e) => {
                assert!(e.to_string().contains("Draco"), "{e}");
                refused += 1;
            }
        }
    }
    assert!(refused > 50, "{refused} of 200 refused");
}

/// The square of [`plain`] with its views compressed by meshoptimizer's
/// codecs as `EXT_meshopt_compression` writes them (gltfpack's output):
/// positions as floats (no filter), normals as octahedral bytes with
/// `KHR_mesh_quantization` (its filter), indices as triangles; the
/// uncompressed copy a fallback buffer the file leaves out. `edit` changes
/// the compressed bytes first.
fn meshopt_square(mut edit: impl FnMut(&mut Vec<u8>)) -> Vec<u8> {
    use meshoptimizer_rs::Workspace;
    use meshoptimizer_rs::codec::{
        IndexEncoding, VertexEncoding, encode_filter_oct, encode_index_buffer, encode_vertex_buffer,
    };
    let mut w = Workspace::default();
    let v0 = VertexEncoding::new(0, 2).unwrap();
    let positions = le(CORNERS.as_flattened(), f32::to_le_bytes);
    let pos = encode_vertex_buffer(&positions, 4, 12, v0, &mut w).unwrap();
    let oct = encode_filter_oct(
        4,
        4,
        8,
        &NORMALS.map(|n| [n[0], n[1], n[2], 0.0]).concat(),
        &mut w,
    )
    .unwrap();
    let normals = encode_vertex_buffer(&oct, 4, 4, v0, &mut w).unwrap();
    let idx = encode_index_buffer(&[0, 1, 2, 0, 2, 3], IndexEncoding::DEFAULT, &mut w).unwrap();
    let mut bin = Vec::new();
    let mut views = Vec::new();
    for (bytes, count, stride, mode, filter) in [
        (pos, 4, 12, "ATTRIBUTES", "NONE"),
        (normals, 4, 4, "ATTRIBUTES", "OCTAHEDRAL"),
        (idx, 6, 2, "TRIANGLES", "NONE"),
    ] {
        let mut bytes = bytes;
        edit(&mut bytes);
        let offset = bin.len();
        bin.extend_from_slice(&bytes);
        while bin.len() % 4 != 0 {
            bin.push(0);
        }
        views.push(format!(
            r#"{{"buffer":1,"byteLength":{},"byteStride":{stride},"extensions":{{"EXT_meshopt_compression":{{"buffer":0,"byteOffset":{offset},"byteLength":{},"byteStride":{stride},"count":{count},"mode":"{mode}","filter":"{filter}"}}}}}}"#,
            count * stride,
            bytes.len()
        ));
    }
    // The index view has no stride in glTF: only in the extension.
    views[2] = views[2].replacen(r#","byteStride":2,"ext"#, r#","ext"#, 1);
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},
"extensionsUsed":["EXT_meshopt_compression","KHR_mesh_quantization"],"extensionsRequired":["EXT_meshopt_compression","KHR_mesh_quantization"],
"buffers":[{{"byteLength":{}}},{{"byteLength":96,"extensions":{{"EXT_meshopt_compression":{{"fallback":true}}}}}}],
"bufferViews":[{}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[-1,-1,0],"max":[1,1,0]}},
{{"bufferView":1,"componentType":5120,"normalized":true,"count":4,"type":"VEC3"}},
{{"bufferView":2,"componentType":5123,"count":6,"type":"SCALAR"}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"NORMAL":1}},"indices":2}}]}}],
"nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0}}"#,
        bin.len(),
        views.join(",")
    );
    common::glb(&json, &bin)
}

#[test]
fn meshopt_compressed_views_read_as_the_same_floats_and_samples() {
    let want = load(&plain());
    let got = load(&meshopt_square(|_| {}));
    assert_eq!(got.positions, want.positions);
    // Octahedral bytes: each axis-aligned normal exactly.
    assert_eq!(got.normals, want.normals);
    assert_eq!(samples(got), samples(want));
}

#[test]
fn damaged_meshopt_streams_are_refused_never_drawn_as_another_mesh() {
    let want = load(&plain());
    let mut seed = 11u64;
    let mut refused = 0;
    for t in 0..200 {
        let file = meshopt_square(|s| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let i = (seed >> 33) as usize % s.len();
            if t % 3 == 0 {
                s.truncate(i);
            } else {
                s[i] ^= (seed >> 20) as u8 | 1;
            }
        });
        match gltf::parse(&file, None, "t.glb", &LoadOptions::default()) {
            Ok(got) => assert_eq!(got.geometry.faces.len(), want.faces.len()),
            Err(e) => {
                assert!(
                    e.to_string().contains("could not be decoded")
                        || e.to_string().contains("out of range"),
                    "{e}"
                );
                refused += 1;
            }
        }
    }
    assert!(refused > 50, "{refused} of 200 refused");
}

/// A white square with an emissive map of a 2×2 image of four colours
/// (nearest), read through `set`: the base colour texture (one white
/// texel) on set 0, whose coordinates are the square's; set 1's the same
/// mirrored in u. `mirrored`: the image mirrored in u too.
fn glowing_square(set: u32, mirrored: bool) -> Vec<u8> {
    let mut d = Doc::default();
    let pos = d.vec3(&CORNERS);
    let normal = d.vec3(&[[0.0, 0.0, 1.0]; 4]);
    let proper = [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
    let uv0 = d.floats(&proper.concat(), "VEC2", 2);
    let uv1 = d.floats(&proper.map(|[u, v]| [1.0 - u, v]).concat(), "VEC2", 2);
    let idx = d.indices(&[[0, 1, 2], [0, 2, 3]]);
    let mut texels = [[255, 0, 0], [0, 255, 0], [0, 0, 255], [255, 255, 0]];
    if mirrored {
        texels.swap(0, 1);
        texels.swap(2, 3);
    }
    let glow = d.view(&common::png_rgb(2, 2, &texels));
    let white = d.view(&common::png_rgb(1, 1, &[[255, 255, 255]]));
    d.glb(&format!(
        r#""materials":[{{"pbrMetallicRoughness":{{"baseColorFactor":[0,0,0,1],"baseColorTexture":{{"index":1}}}},"emissiveFactor":[1,1,1],"emissiveTexture":{{"index":0,"texCoord":{set}}}}}],
"samplers":[{{"magFilter":9728,"minFilter":9728}}],
"images":[{{"bufferView":{glow},"mimeType":"image/png"}},{{"bufferView":{white},"mimeType":"image/png"}}],"textures":[{{"source":0,"sampler":0}},{{"source":1,"sampler":0}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":{pos},"NORMAL":{normal},"TEXCOORD_0":{uv0},"TEXCOORD_1":{uv1}}},"indices":{idx},"material":0}}]}}],
"nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0"#
    ))
}

#[test]
fn a_map_on_another_set_than_the_base_colours_is_read_through_it() {
    // The glow read through set 1 (mirrored coordinates) is the mirrored
    // image read through set 0, sample for sample; and not the image
    // read through set 0.
    let second = load(&glowing_square(1, false));
    assert!(second.uvs2.is_some());
    let (a, b) = (samples(second), samples(load(&glowing_square(0, true))));
    assert!(
        a == b,
        "the mirrored image through set 0 draws another picture"
    );
    let colours = |s: &[Option<rastty::color::Lin>]| {
        let mut c: Vec<_> = s.iter().flatten().map(|c| c.0).collect();
        c.sort_unstable();
        c.dedup();
        c.len()
    };
    assert_eq!(colours(&a), 4, "the four texels glow");
    assert!(
        a != samples(load(&glowing_square(0, false))),
        "set 1 read as set 0"
    );
}
