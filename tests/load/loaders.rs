//! The loaders never panic: random bytes, and real files with random bytes
//! changed, come back as a mesh or a scene or as an error. (The cargo-fuzz
//! targets in `fuzz/` run the same entry points for as long as you like.)

use std::path::Path;

use crate::common;
use proptest::prelude::*;

use rastty::scene::{LoadOptions, Scene, gltf, obj, ply, stl};

fn model(name: &str) -> Vec<u8> {
    std::fs::read(format!(
        "{}/tests/models/{name}",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap()
}

/// `base` with some bytes replaced and the tail cut at `cut`.
fn mutate(mut base: Vec<u8>, edits: &[(usize, u8)], cut: usize) -> Vec<u8> {
    if base.is_empty() {
        return base;
    }
    for &(at, b) in edits {
        let i = at % base.len();
        base[i] = b;
    }
    let keep = cut % (base.len() + 1);
    base.truncate(keep);
    base
}

fn all_loaders(bytes: &[u8]) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/models");
    let _ = obj::parse(bytes, "fuzz.obj", &dir);
    let _ = stl::parse(bytes, "fuzz.stl");
    let nowhere = Path::new("/nonexistent");
    let _ = gltf::parse(bytes, Some(nowhere), "fuzz.glb", &LoadOptions::default());
    let _ = ply::parse(bytes, "fuzz.ply");
    let _ = Scene::parse(&String::from_utf8_lossy(bytes), "fuzz.toml");
}

/// A GLB of one triangle with vertex colours and indices.
fn triangle_glb() -> Vec<u8> {
    let mut bin = common::f32s(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]);
    bin.extend_from_slice(&[255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 0, 1, 2, 0]);
    let json = r#"{"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0,"children":[1]},{"mesh":0,"scale":[-1,1,1]}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0,"COLOR_0":1},"indices":2,"mode":5}]}],
        "buffers":[{"byteLength":52}],
        "bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":12},{"buffer":0,"byteOffset":48,"byteLength":3}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
                     {"bufferView":1,"componentType":5121,"normalized":true,"count":3,"type":"VEC4"},
                     {"bufferView":2,"componentType":5121,"count":3,"type":"SCALAR"}]}"#;
    common::glb(json, &bin)
}

#[test]
fn the_damaged_files_start_whole() {
    assert_eq!(
        gltf::parse(&triangle_glb(), None, "t.glb", &LoadOptions::default())
            .unwrap()
            .geometry
            .faces
            .len(),
        2
    );
    assert_eq!(
        ply::parse(&common::quad_ply("binary_big_endian"), "q.ply")
            .unwrap()
            .geometry
            .faces
            .len(),
        2
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(
        std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(200)
    ))]

    #[test]
    fn random_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..2048)) {
        all_loaders(&bytes);
    }

    #[test]
    fn damaged_files_never_panic(
        which in 0usize..8,
        edits in prop::collection::vec((any::<usize>(), any::<u8>()), 0..8),
        cut in any::<usize>(),
    ) {
        let base = match which {
            0 => model("fox.obj"),
            1 => model("shiba-inu-binary.stl"),
            2 => model("shiba-inu-ascii.stl"),
            3 => common::quad_ply("ascii"),
            4 => common::quad_ply("binary_big_endian"),
            5 => triangle_glb(),
            6 => common::crate_glb(),
            _ => std::fs::read(format!("{}/examples/scenes/overlap.toml", env!("CARGO_MANIFEST_DIR"))).unwrap(),
        };
        all_loaders(&mutate(base, &edits, cut));
    }

    /// Random OBJ-shaped text: statements with random numbers and indices.
    #[test]
    fn random_obj_statements_never_panic(lines in prop::collection::vec(
        (prop::sample::select(vec!["v", "vn", "vt", "f", "usemtl", "o", "g", "s", "mtllib"]),
         prop::collection::vec(prop_oneof![any::<i32>().prop_map(|i| (i % 20).to_string()), any::<f32>().prop_map(|f| f.to_string()), Just("1/2/3".to_string()), Just("-1//2".to_string()), Just("nan".to_string())], 0..6)),
        0..40,
    )) {
        let text: String = lines.iter().map(|(k, args)| format!("{k} {}\n", args.join(" "))).collect();
        all_loaders(text.as_bytes());
    }
}
