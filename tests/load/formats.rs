//! glTF, GLB and PLY models, written by the tests themselves: node
//! transforms, strips and fans, vertex colours, the three PLY encodings,
//! and bad files, each with an exact expectation.

use std::path::Path;

use crate::common;

use base64::Engine as _;
use common::{f32s, glb, quad_ply};
use rastty::color::Lin;
use rastty::glam::Vec3;
use rastty::scene::LoadOptions;
use rastty::scene::{gltf, ply};

/// A one-triangle-list file: positions (and an optional second accessor),
/// `nodes` and `extra` JSON spliced in.
fn triangle_json(buffer: &str, len: usize, nodes: &str, prim: &str, extra: &str) -> String {
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":{nodes},
        "meshes":[{{"primitives":[{prim}]}}],
        "buffers":[{{{buffer}"byteLength":{len}}}],
        "bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":{len}}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}}]{extra}}}"#
    )
}

const TRI: [f32; 9] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];

fn parse_glb(bytes: &[u8]) -> rastty::Result<rastty::scene::obj::Loaded> {
    gltf::parse(bytes, None, "t.glb", &LoadOptions::default())
}

#[test]
fn node_transforms_compose_down_the_tree() {
    // Root: translate (10, 0, 0), scale 2; child: a matrix turning x into y
    // (a quarter turn about z), holding the mesh.
    let nodes = r#"[{"translation":[10,0,0],"scale":[2,2,2],"children":[1]},
                    {"matrix":[0,1,0,0, -1,0,0,0, 0,0,1,0, 0,0,0,1],"mesh":0}]"#;
    let json = triangle_json("", 36, nodes, r#"{"attributes":{"POSITION":0}}"#, "");
    let loaded = parse_glb(&glb(&json, &f32s(&TRI))).unwrap();
    let g = &loaded.geometry;
    // (x, y, z) → child (−y, x, z) → root 2·(−y, x, z) + (10, 0, 0).
    assert_eq!(
        g.positions,
        vec![
            Vec3::new(10.0, 0.0, 0.0),
            Vec3::new(10.0, 2.0, 0.0),
            Vec3::new(8.0, 0.0, 0.0)
        ]
    );
    assert_eq!(g.faces, vec![[0, 1, 2]]);
    assert!(loaded.notes.is_empty(), "{:?}", loaded.notes);
}

#[test]
fn a_mirroring_node_rewinds_its_triangles() {
    let nodes = r#"[{"scale":[-1,1,1],"mesh":0}]"#;
    let json = triangle_json("", 36, nodes, r#"{"attributes":{"POSITION":0}}"#, "");
    let g = parse_glb(&glb(&json, &f32s(&TRI))).unwrap().geometry;
    assert_eq!(g.faces, vec![[0, 2, 1]]);
}

#[test]
fn strips_and_fans_become_triangles_and_points_are_points() {
    // Five positions on a zigzag; no indices.
    let pos: Vec<f32> = (0..5)
        .flat_map(|i| [i as f32, (i % 2) as f32, 0.0])
        .collect();
    // A fan around a hub, every triangle counter-clockwise.
    let hub: Vec<f32> = vec![
        0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0, -1.0, 1.0, 0.0,
    ];
    for (mode, pos, faces) in [
        (5, &pos, vec![[0, 1, 2], [2, 1, 3], [2, 3, 4]]),
        (6, &hub, vec![[0, 1, 2], [0, 2, 3], [0, 3, 4]]),
    ] {
        let json = format!(
            r#"{{"asset":{{"version":"2.0"}},"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
            "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"mode":{mode}}},{{"attributes":{{"POSITION":0}},"mode":0}}]}}],
            "buffers":[{{"byteLength":60}}],"bufferViews":[{{"buffer":0,"byteLength":60}}],
            "accessors":[{{"bufferView":0,"componentType":5126,"count":5,"type":"VEC3","min":[-1,0,0],"max":[4,1,0]}}]}}"#
        );
        let loaded = parse_glb(&glb(&json, &f32s(pos))).unwrap();
        assert_eq!(loaded.geometry.faces, faces, "mode {mode}");
        // The points (the second primitive, its five positions after the
        // first's) are lines of no length, one a point.
        let points: Vec<[u32; 2]> = (5..10).map(|i| [i, i]).collect();
        let lines: Vec<[u32; 2]> = loaded.geometry.lines.iter().map(|l| l.0).collect();
        assert_eq!(lines, points);
        assert!(loaded.notes.is_empty(), "{:?}", loaded.notes);
    }
}

#[test]
fn vertex_colours_are_linear_and_multiplied_by_the_base_colour() {
    // COLOR_0 as normalized bytes (RGBA), the material's factor halves red.
    let mut bin = f32s(&TRI);
    bin.extend_from_slice(&[255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255]);
    let json = r#"{"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0,"COLOR_0":1},"material":0}]}],
        "materials":[{"pbrMetallicRoughness":{"baseColorFactor":[0.5,1,1,1]}}],
        "buffers":[{"byteLength":48}],
        "bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":12}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
                     {"bufferView":1,"componentType":5121,"normalized":true,"count":3,"type":"VEC4"}]}"#;
    let g = parse_glb(&glb(json, &bin)).unwrap().geometry;
    assert_eq!(
        g.colors,
        Some(vec![
            Lin([32768, 0, 0]),
            Lin([0, 65535, 0]),
            Lin([0, 0, 65535])
        ])
    );
    assert_eq!(g.materials.len(), 1);
    assert_eq!(g.materials[0].color, Some(Lin([32768, 65535, 65535])));
}

#[test]
fn buffers_load_from_data_uris_and_files_beside_the_gltf() {
    let uri = format!(
        r#""uri":"data:application/octet-stream;base64,{}","#,
        base64::engine::general_purpose::STANDARD.encode(f32s(&TRI))
    );
    let nodes = r#"[{"mesh":0}]"#;
    let prim = r#"{"attributes":{"POSITION":0}}"#;
    let json = triangle_json(&uri, 36, nodes, prim, "");
    let g = gltf::parse(json.as_bytes(), None, "t.gltf", &LoadOptions::default())
        .unwrap()
        .geometry;
    assert_eq!(g.positions[1], Vec3::X);

    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("gltf-files");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("tri.bin"), f32s(&TRI)).unwrap();
    let json = triangle_json(r#""uri":"tri.bin","#, 36, nodes, prim, "");
    std::fs::write(dir.join("tri.gltf"), &json).unwrap();
    let g = gltf::load(&dir.join("tri.gltf"), &LoadOptions::default())
        .unwrap()
        .geometry;
    assert_eq!(g.positions[2], Vec3::Y);

    // The .bin gone: one error naming the file.
    std::fs::remove_file(dir.join("tri.bin")).unwrap();
    let err = rastty::scene::Scene::of_model(&dir.join("tri.gltf"))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("tri.gltf: ") && err.contains("tri.bin"),
        "{err}"
    );
}

#[test]
fn bad_gltf_files_get_one_error_naming_what_is_wrong() {
    let nodes = r#"[{"mesh":0}]"#;
    let prim = r#"{"attributes":{"POSITION":0}}"#;
    let good = glb(&triangle_json("", 36, nodes, prim, ""), &f32s(&TRI));
    let cases: Vec<(Vec<u8>, &str)> = vec![
        (good[..good.len() - 20].to_vec(), "t.glb: "),
        (
            // The accessor claims 4 vertices in a 36-byte view.
            glb(&triangle_json("", 36, nodes, prim, "").replace(r#""count":3"#, r#""count":4"#), &f32s(&TRI)),
            "t.glb: mesh 0 primitive 0: POSITION (accessor 0) is out of range: it needs 48 bytes of buffer view 0",
        ),
        (
            glb(
                &triangle_json("", 36, nodes, r#"{"attributes":{"POSITION":0},"indices":1}"#, "")
                    .replace(
                        r#""type":"VEC3","min":[0,0,0],"max":[1,1,0]}]"#,
                        r#""type":"VEC3","min":[0,0,0],"max":[1,1,0]},{"bufferView":0,"byteOffset":12,"componentType":5125,"count":3,"type":"SCALAR"}]"#,
                    ),
                &f32s(&TRI),
            ),
            "t.glb: mesh 0 primitive 0: index 1065353216 is out of range for 3 vertices",
        ),
        (
            glb(
                &triangle_json("", 36, nodes, prim, r#","extensionsUsed":["KHR_texture_transform","KHR_texture_basisu"],"extensionsRequired":["KHR_texture_transform","KHR_texture_basisu"]"#),
                &f32s(&TRI),
            ),
            "t.glb: needs the extension KHR_texture_basisu, which rastty does not read",
        ),
        (b"not a model at all".to_vec(), "t.glb: "),
    ];
    for (bytes, want) in cases {
        let err = parse_glb(&bytes).unwrap_err().to_string();
        assert!(err.starts_with(want), "{err}");
        assert!(!err.contains('\n'), "{err}");
    }
    // An extension rastty draws may be required.
    let required = glb(
        &triangle_json(
            "",
            36,
            nodes,
            prim,
            r#","extensionsUsed":["KHR_texture_transform"],"extensionsRequired":["KHR_texture_transform"]"#,
        ),
        &f32s(&TRI),
    );
    assert_eq!(parse_glb(&required).unwrap().geometry.faces.len(), 1);
}

#[test]
fn ply_in_ascii_and_both_binary_orders_reads_the_same_coloured_quad() {
    for format in ["ascii", "binary_little_endian", "binary_big_endian"] {
        let g = ply::parse(&quad_ply(format), "q.ply").unwrap().geometry;
        assert_eq!(g.positions.len(), 4, "{format}");
        assert_eq!(g.positions[2], Vec3::new(1.0, 1.0, 0.0), "{format}");
        assert_eq!(g.faces, vec![[0, 1, 2], [0, 2, 3]], "{format}");
        assert_eq!(
            g.colors,
            Some(vec![
                Lin([65535, 0, 0]),
                Lin([0, 65535, 0]),
                Lin([0, 0, 65535]),
                Lin::WHITE
            ]),
            "{format}"
        );
    }
}

#[test]
fn bad_ply_files_get_one_error() {
    let mut out_of_range = quad_ply("ascii");
    let n = out_of_range.len();
    out_of_range.splice(n - 10.., b"4 0 1 2 9\n".iter().copied());
    let cloud = b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n";
    let truncated = &quad_ply("binary_little_endian")[..200];
    for (bytes, want) in [
        (
            &out_of_range[..],
            "q.ply: face 0 names a vertex out of range (there are 4 vertices)",
        ),
        (
            &cloud[..],
            "q.ply: no face element: a point cloud has nothing to draw",
        ),
        (truncated, "q.ply:"),
    ] {
        let err = ply::parse(bytes, "q.ply").unwrap_err().to_string();
        assert!(err.starts_with(want), "{err}");
    }
}
