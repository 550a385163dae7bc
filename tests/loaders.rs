//! The loaders never panic: random bytes, and real files with random bytes
//! changed, come back as a mesh or a scene or as an error. (The cargo-fuzz
//! targets in `fuzz/` run the same entry points for as long as you like.)

use std::path::Path;

use proptest::prelude::*;
use rastty::scene::{Scene, obj, stl};

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
    let _ = Scene::parse(&String::from_utf8_lossy(bytes), "fuzz.toml");
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
        which in 0usize..4,
        edits in prop::collection::vec((any::<usize>(), any::<u8>()), 0..8),
        cut in any::<usize>(),
    ) {
        let base = match which {
            0 => model("fox.obj"),
            1 => model("shiba-inu-binary.stl"),
            2 => model("shiba-inu-ascii.stl"),
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
