//! The glTF/GLB loader on arbitrary bytes: an error is fine, a panic is
//! not. (Files the bytes name are looked for in a directory that has none.)
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let options = rastty::scene::LoadOptions::default();
    let _ = rastty::scene::gltf::parse(data, Some(std::path::Path::new("/nonexistent")), "fuzz.glb", &options);
});
