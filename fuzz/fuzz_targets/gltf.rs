//! The glTF/GLB loader on arbitrary bytes: an error is fine, a panic is
//! not. (Files the bytes name are looked for in a directory that has none.)
//! A model that moves is also posed, in each of its first clips, at a few
//! times (the start, within, far into a loop, before the start).
#![no_main]

use libfuzzer_sys::fuzz_target;
use rastty::scene::anim::{Pose, Posed};

fuzz_target!(|data: &[u8]| {
    let options = rastty::scene::LoadOptions::default();
    let Ok(loaded) = rastty::scene::gltf::parse(
        data,
        Some(std::path::Path::new("/nonexistent")),
        "fuzz.glb",
        &options,
    ) else {
        return;
    };
    let g = &loaded.geometry;
    let Some(rig) = &g.rig else { return };
    let (mut p, mut n) = (g.positions.clone(), g.normals.clone());
    let mut posed = Posed::default();
    for clip in 0..rig.clips.len().min(3) {
        for time in [0.0, 0.37, 1e9, -2.5] {
            rig.pose_into(Some(Pose { clip, time }), &mut posed, &mut p, &mut n);
        }
    }
});
