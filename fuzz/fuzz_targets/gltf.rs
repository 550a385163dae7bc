//! The glTF/GLB loader on arbitrary bytes: an error is fine, a panic is
//! not. (Files the bytes name are looked for in a directory that has none.)
//! A model that moves is also posed, in each of its first clips, at a few
//! times (the start, within, far into a loop, before the start), and drawn.
//!
//! Each input is read twice: as it is, and with numbers at the edge of f32
//! put in (`at_the_edge`): in the JSON (nodes' translations, rotations,
//! scales and matrices, weights, factors) numbers past f32's range, and in
//! the binary chunk (positions, inverse bind matrices, morph targets,
//! keyframes, weights) NaN, infinities, f32's largest and smallest, zero.
#![no_main]

use libfuzzer_sys::fuzz_target;
use rastty::scene::anim::{Pose, Posed};

fuzz_target!(|data: &[u8]| {
    load(data);
    if let Some(edged) = at_the_edge(data) {
        load(&edged);
    }
});

fn load(data: &[u8]) {
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
    if let Some(rig) = &g.rig {
        let (mut p, mut n) = (g.positions.clone(), g.normals.clone());
        let mut posed = Posed::default();
        for clip in 0..rig.clips.len().min(3) {
            for time in [0.0, 0.37, 1e9, -2.5] {
                rig.pose_into(Some(Pose { clip, time }), &mut posed, &mut p, &mut n);
            }
        }
    }
    // Drawn, small, as `rastty render` draws a model shown alone.
    let scene = rastty::scene::Scene::of_mesh(rastty::scene::Mesh::of(
        std::sync::Arc::new(loaded.geometry),
        rastty::color::Rgb::WHITE,
    ));
    let opts = rastty::RenderOptions {
        cols: 12,
        rows: 5,
        ..Default::default()
    };
    let _ = rastty::try_render(&scene, &opts);
}

/// Binary values put in: NaN, ±∞, f32's largest either way, its smallest
/// subnormal, zero, and the four zeros of a quaternion come from zeros.
const EDGE_F32: [f32; 7] = [
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    f32::MAX,
    -f32::MAX,
    1e-45,
    0.0,
];
/// JSON numbers put in: past f32's range, at its edge, and tiny.
const EDGE_JSON: [&str; 6] = ["1e39", "-1e39", "3.4028235e38", "-3.5e38", "1e-50", "0"];

/// `data` with numbers at the edge put in, the input's last two bytes
/// choosing which (every `stride`-th number from `start`); `None` for an
/// input too short to say.
fn at_the_edge(data: &[u8]) -> Option<Vec<u8>> {
    let (&stride, rest) = data.split_last()?;
    let (&start, body) = rest.split_last()?;
    let stride = usize::from(stride % 16) + 1;
    let start = usize::from(start);
    let mut out = body.to_vec();
    let json_end = if out.starts_with(b"glTF") {
        let len = u32::from_le_bytes(out.get(12..16)?.try_into().ok()?) as usize;
        let json_end = 20usize.checked_add(len)?.min(out.len());
        // The binary chunk, four bytes a float.
        let bin = json_end.checked_add(8)?;
        if bin < out.len() {
            let n = (out.len() - bin) / 4;
            for (k, i) in (start % n.max(1)..n).step_by(stride).enumerate() {
                let at = bin + 4 * i;
                let v = EDGE_F32[k % EDGE_F32.len()];
                out[at..at + 4].copy_from_slice(&v.to_le_bytes());
            }
        }
        json_end
    } else {
        out.len()
    };
    // JSON numbers: every stride-th from start replaced, in a copy of the
    // text (a GLB's JSON chunk is rebuilt with its new length).
    let head = if out.starts_with(b"glTF") { 20 } else { 0 };
    let json = std::str::from_utf8(out.get(head..json_end)?).ok()?;
    let mut edited = String::with_capacity(json.len() + 64);
    let mut count = 0usize;
    let mut chars = json.char_indices().peekable();
    let mut last = 0;
    while let Some((i, c)) = chars.next() {
        let starts_number = (c == '-' || c.is_ascii_digit())
            && !json[..i].ends_with(|p: char| p.is_ascii_alphanumeric() || p == '.' || p == '"');
        if !starts_number {
            continue;
        }
        let mut end = i + c.len_utf8();
        while let Some(&(j, d)) = chars.peek() {
            if d.is_ascii_digit() || matches!(d, '.' | 'e' | 'E' | '+' | '-') {
                end = j + 1;
                chars.next();
            } else {
                break;
            }
        }
        if count >= start && (count - start) % stride == 0 {
            edited.push_str(&json[last..i]);
            edited.push_str(EDGE_JSON[count % EDGE_JSON.len()]);
            last = end;
        }
        count += 1;
    }
    edited.push_str(&json[last..]);
    if head == 0 {
        return Some(edited.into_bytes());
    }
    while edited.len() % 4 != 0 {
        edited.push(' ');
    }
    let mut glb = out[..12].to_vec();
    glb.extend((edited.len() as u32).to_le_bytes());
    glb.extend(b"JSON");
    glb.extend(edited.as_bytes());
    glb.extend(&out[json_end..]);
    let total = glb.len() as u32;
    glb[8..12].copy_from_slice(&total.to_le_bytes());
    Some(glb)
}
