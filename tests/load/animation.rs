//! Models that move, end to end: glTF files written here (skins, morph
//! targets, node animations with every interpolation) loaded, posed and
//! drawn, against the same shapes modelled in the pose, against values
//! computed by hand, and the planned frame against the full pipeline's.

use crate::common;

use std::sync::Arc;

use common::Doc;
use glam::Vec3;
use proptest::prelude::*;
use rastty::Effect;
use rastty::scene::anim::Posed;
use rastty::scene::{Camera, Geometry, LoadOptions, Mesh, Projection, Scene, gltf};
use rastty::{Choice, Pipeline, RenderOptions, Renderer, Threads, color::Rgb};

/// A box from `lo` to `hi`: 8 corners, 12 triangles wound outwards.
fn cuboid(lo: [f32; 3], hi: [f32; 3], first: u16) -> (Vec<[f32; 3]>, Vec<[u16; 3]>) {
    let c = |i: u16| {
        [
            if i & 1 == 0 { lo[0] } else { hi[0] },
            if i & 2 == 0 { lo[1] } else { hi[1] },
            if i & 4 == 0 { lo[2] } else { hi[2] },
        ]
    };
    let quads = [
        [0, 2, 3, 1], // z = lo
        [4, 5, 7, 6], // z = hi
        [0, 1, 5, 4], // y = lo
        [2, 6, 7, 3], // y = hi
        [0, 4, 6, 2], // x = lo
        [1, 3, 7, 5], // x = hi
    ];
    let faces = quads
        .iter()
        .flat_map(|q: &[u16; 4]| {
            [
                [q[0] + first, q[1] + first, q[2] + first],
                [q[0] + first, q[2] + first, q[3] + first],
            ]
        })
        .collect();
    ((0..8).map(c).collect(), faces)
}

fn load(glb: &[u8], name: &str) -> Geometry {
    gltf::parse(glb, None, name, &LoadOptions::default())
        .unwrap_or_else(|e| panic!("{name}: {e}"))
        .geometry
}

/// An arm along x: a forearm from 0 to 2, a hand from 2 to 4, each
/// 0.5 thick; the hand bent `bent` (true: 90° up about z at x = 2) or
/// straight.
fn arm_boxes(bent: bool) -> (Vec<[f32; 3]>, Vec<[u16; 3]>) {
    let (mut p, mut f) = cuboid([0.0, -0.25, -0.25], [2.0, 0.25, 0.25], 0);
    let (p2, f2) = if bent {
        cuboid([1.75, 0.0, -0.25], [2.25, 2.0, 0.25], 8)
    } else {
        cuboid([2.0, -0.25, -0.25], [4.0, 0.25, 0.25], 8)
    };
    p.extend(p2);
    f.extend(f2);
    (p, f)
}

/// The straight arm skinned by two joints (the forearm's vertices wholly
/// the first's, the hand's the second's, at x = 2), whose clip "wave"
/// turns the second joint from straight at 0 s to 90° about z at 1 s and
/// back at 2 s (where the clip loops). `examples/models/arm.glb`.
fn skinned_arm() -> Vec<u8> {
    let s = std::f32::consts::FRAC_1_SQRT_2;
    skinned_arm_with(
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, s, s, 0.0, 0.0, s, s],
    )
}

/// [`skinned_arm`] with the hand's vertices weighted `hand` between the
/// two joints (in that order), and the clip's three rotation keys `turns`.
fn skinned_arm_with(hand: [f32; 4], turns: [f32; 12]) -> Vec<u8> {
    let mut d = Doc::default();
    let (p, f) = arm_boxes(false);
    let pos = d.vec3(&p);
    let idx = d.indices(&f);
    let joints: Vec<u8> = (0..16u16)
        .flat_map(|v| [u16::from(v >= 8), 0, 0, 0])
        .flat_map(u16::to_le_bytes)
        .collect();
    let joints = d.add(joints, 16, "VEC4", 5123);
    let weights: Vec<f32> = (0..16)
        .flat_map(|v| if v >= 8 { hand } else { [1.0, 0.0, 0.0, 0.0] })
        .collect();
    let weights = d.floats(&weights, "VEC4", 4);
    let mut ibm = glam::Mat4::IDENTITY.to_cols_array().to_vec();
    ibm.extend(glam::Mat4::from_translation(Vec3::new(-2.0, 0.0, 0.0)).to_cols_array());
    let ibm = d.floats(&ibm, "MAT4", 16);
    let times = d.floats(&[0.0, 1.0, 2.0], "SCALAR", 1);
    let turns = d.floats(&turns, "VEC4", 4);
    d.glb(&format!(
        r#""meshes":[{{"primitives":[{{"attributes":{{"POSITION":{pos},"JOINTS_0":{joints},"WEIGHTS_0":{weights}}},"indices":{idx}}}]}}],
"skins":[{{"joints":[1,2],"inverseBindMatrices":{ibm}}}],
"nodes":[{{"mesh":0,"skin":0}},{{"children":[2]}},{{"translation":[2,0,0]}}],
"scenes":[{{"nodes":[0,1]}}],"scene":0,
"animations":[{{"name":"wave","channels":[{{"sampler":0,"target":{{"node":2,"path":"rotation"}}}}],"samplers":[{{"input":{times},"output":{turns}}}]}}]"#
    ))
}

/// A model without a skin or a clip: `positions` and `faces` as given.
fn still(positions: &[[f32; 3]], faces: &[[u16; 3]], normals: Option<&[[f32; 3]]>) -> Vec<u8> {
    let mut d = Doc::default();
    let pos = d.vec3(positions);
    let idx = d.indices(faces);
    let normal = normals.map_or(String::new(), |n| format!(r#","NORMAL":{}"#, d.vec3(n)));
    d.glb(&format!(
        r#""meshes":[{{"primitives":[{{"attributes":{{"POSITION":{pos}{normal}}},"indices":{idx}}}]}}],
"nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0"#
    ))
}

/// `geometry` seen from the front through a fixed camera (not framed, so
/// that two shapes are seen alike), at time `time` of clip 0.
fn scene_of(geometry: Geometry, time: f64) -> Scene {
    let mesh = Mesh::of(Arc::new(geometry), Rgb::new(200, 120, 60)).at(0, time);
    Scene::builder()
        .camera(Camera {
            projection: Projection::Perspective {
                fov_y: 40.0,
                near: 0.1,
                far: 50.0,
            },
            eye: Vec3::new(1.5, 0.75, 9.0),
            target: Vec3::new(1.5, 0.75, 0.0),
            ..Camera::default()
        })
        .mesh(mesh)
        .build()
        .unwrap()
}

fn opts() -> RenderOptions {
    RenderOptions {
        cols: 80,
        rows: 30,
        ..RenderOptions::default()
    }
}

/// Which samples are covered.
fn coverage(scene: &Scene, opts: &RenderOptions) -> Vec<bool> {
    let mut r = Renderer::new();
    r.render(scene, opts);
    r.framebuffer()
        .samples()
        .iter()
        .map(Option::is_some)
        .collect()
}

#[test]
fn a_two_joint_arm_bent_90_degrees_covers_the_samples_of_the_arm_modelled_bent() {
    let skinned = load(&skinned_arm(), "arm.glb");
    let (p, f) = arm_boxes(true);
    let modelled = load(&still(&p, &f, None), "bent.glb");
    let bent = coverage(&scene_of(skinned.clone(), 1.0), &opts());
    assert_eq!(bent, coverage(&scene_of(modelled, 0.0), &opts()));
    assert!(bent.iter().filter(|&&c| c).count() > 100);
    // At 0 s the clip holds the arm straight: the straight arm's samples.
    let (p, f) = arm_boxes(false);
    let straight = load(&still(&p, &f, None), "straight.glb");
    assert_eq!(
        coverage(&scene_of(skinned, 0.0), &opts()),
        coverage(&scene_of(straight, 0.0), &opts())
    );
}

/// A square of two triangles facing +z, with one morph target that lifts
/// and tilts it; the weight steps from 0 to 1 at 1 s and holds to 2 s.
fn morphing_square() -> (Vec<u8>, Vec<[f32; 3]>, Vec<[f32; 3]>) {
    let base = [
        [0.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [2.0, 2.0, 0.0],
        [0.0, 2.0, 0.0],
    ];
    let up = [[0.0, 0.0, 1.0]; 4];
    let dp = [
        [0.0, 0.5, 0.0],
        [0.5, 0.0, 0.0],
        [0.5, 1.0, 1.0],
        [0.0, 1.0, 1.0],
    ];
    let dn = [[0.0, -0.5, 0.0]; 4];
    let mut d = Doc::default();
    let pos = d.vec3(&base);
    let nrm = d.vec3(&up);
    let idx = d.indices(&[[0, 1, 2], [0, 2, 3]]);
    let tp = d.vec3(&dp);
    let tn = d.vec3(&dn);
    let times = d.floats(&[0.0, 1.0, 2.0], "SCALAR", 1);
    let weights = d.floats(&[0.0, 1.0, 1.0], "SCALAR", 1);
    let glb = d.glb(&format!(
        r#""meshes":[{{"primitives":[{{"attributes":{{"POSITION":{pos},"NORMAL":{nrm}}},"indices":{idx},"targets":[{{"POSITION":{tp},"NORMAL":{tn}}}]}}]}}],
"nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0,
"animations":[{{"channels":[{{"sampler":0,"target":{{"node":0,"path":"weights"}}}}],"samplers":[{{"input":{times},"output":{weights},"interpolation":"STEP"}}]}}]"#
    ));
    let target: Vec<[f32; 3]> = (0..4)
        .map(|i| std::array::from_fn(|k| base[i][k] + dp[i][k]))
        .collect();
    let normals: Vec<[f32; 3]> = (0..4)
        .map(|i| std::array::from_fn(|k| up[i][k] + dn[i][k]))
        .collect();
    (glb, target, normals)
}

#[test]
fn a_morph_at_weight_one_is_the_target_mesh_sample_for_sample() {
    let (glb, target, normals) = morphing_square();
    let morphing = load(&glb, "morph.glb");
    let modelled = load(
        &still(&target, &[[0, 1, 2], [0, 2, 3]], Some(&normals)),
        "target.glb",
    );
    let draw = |scene: &Scene| {
        let mut r = Renderer::new();
        r.render(scene, &opts());
        (r.framebuffer().samples().to_vec(), r.frame().clone())
    };
    let at_one = draw(&scene_of(morphing.clone(), 1.0));
    assert_eq!(at_one, draw(&scene_of(modelled, 0.0)));
    // Before the step, the base square.
    let base = load(
        &still(
            &[
                [0.0, 0.0, 0.0],
                [2.0, 0.0, 0.0],
                [2.0, 2.0, 0.0],
                [0.0, 2.0, 0.0],
            ],
            &[[0, 1, 2], [0, 2, 3]],
            Some(&[[0.0, 0.0, 1.0]; 4]),
        ),
        "base.glb",
    );
    assert_eq!(draw(&scene_of(morphing, 0.5)), draw(&scene_of(base, 0.0)));
}

/// One triangle carried by its node's translation, keyed at 0 s and 2 s
/// with `interpolation`: x goes 1 → 3 (a cubic spline's out-tangent 4 and
/// in-tangent −2 a second), y and z stay 0.
fn translated(interpolation: &str) -> Vec<u8> {
    let mut d = Doc::default();
    let pos = d.vec3(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let idx = d.indices(&[[0, 1, 2]]);
    let times = d.floats(&[0.0, 2.0], "SCALAR", 1);
    let values: Vec<f32> = if interpolation == "CUBICSPLINE" {
        // Key 0: in, value, out; key 1 likewise.
        vec![
            9.0, 9.0, 9.0, 1.0, 0.0, 0.0, 4.0, 0.0, 0.0, //
            -2.0, 0.0, 0.0, 3.0, 0.0, 0.0, 9.0, 9.0, 9.0,
        ]
    } else {
        vec![1.0, 0.0, 0.0, 3.0, 0.0, 0.0]
    };
    let out = d.floats(&values, "VEC3", 3);
    d.glb(&format!(
        r#""meshes":[{{"primitives":[{{"attributes":{{"POSITION":{pos}}},"indices":{idx}}}]}}],
"nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0,
"animations":[{{"name":"slide","channels":[{{"sampler":0,"target":{{"node":0,"path":"translation"}}}}],"samplers":[{{"input":{times},"output":{out},"interpolation":"{interpolation}"}}]}}]"#
    ))
}

/// Vertex 0's x (it sits at the node's origin) at `time` into the clip.
fn x_at(geometry: &Geometry, time: f64) -> f32 {
    let rig = geometry.rig.as_ref().expect("a rig");
    let (mut p, mut n) = (geometry.positions.clone(), geometry.normals.clone());
    let pose = rastty::scene::anim::Pose { clip: 0, time };
    rig.pose_into(Some(pose), &mut Posed::default(), &mut p, &mut n);
    assert_eq!((p[0].y, p[0].z), (0.0, 0.0));
    p[0].x
}

#[test]
fn every_interpolation_gives_the_values_computed_by_hand_at_and_between_keys() {
    let step = load(&translated("STEP"), "step.glb");
    let linear = load(&translated("LINEAR"), "linear.glb");
    let cubic = load(&translated("CUBICSPLINE"), "cubic.glb");
    // The rest pose is the file's node transform: none.
    assert_eq!(step.positions[0], Vec3::ZERO);
    for (time, s, l, c) in [
        (0.0, 1.0, 1.0, 1.0),
        (0.5, 1.0, 1.5, 2.625),
        (1.0, 1.0, 2.0, 3.5),
        (1.5, 1.0, 2.5, 3.625),
        // The clip is 2 s long: 2 s is its start again, and 1e6 s is 0 s
        // into a loop (1e6 is even), exactly.
        (2.0, 1.0, 1.0, 1.0),
        (1e6 + 0.5, 1.0, 1.5, 2.625),
    ] {
        assert_eq!(x_at(&step, time), s, "STEP at {time}");
        assert_eq!(x_at(&linear, time), l, "LINEAR at {time}");
        assert_eq!(x_at(&cubic, time), c, "CUBICSPLINE at {time}");
    }
}

#[test]
fn a_malformed_sampler_is_an_error_naming_the_animation_and_sampler() {
    let bad = |times: &[f32], values: &[f32]| {
        let mut d = Doc::default();
        let pos = d.vec3(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
        let t = d.floats(times, "SCALAR", 1);
        let v = d.floats(values, "VEC3", 3);
        let glb = d.glb(&format!(
            r#""meshes":[{{"primitives":[{{"attributes":{{"POSITION":{pos}}}}}]}}],
"nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0,
"animations":[{{"name":"walk","channels":[{{"sampler":0,"target":{{"node":0,"path":"translation"}}}}],"samplers":[{{"input":{t},"output":{v}}}]}}]"#
        ));
        match gltf::parse(&glb, None, "bad.glb", &LoadOptions::default()) {
            Ok(_) => panic!("accepted"),
            Err(e) => e.to_string(),
        }
    };
    assert_eq!(
        bad(&[0.0, 1.0, 1.0], &[0.0; 9]),
        "bad.glb: animation 0 (\"walk\") sampler 0: key 2's time is not after key 1's"
    );
    assert_eq!(
        bad(&[0.0, f32::NAN], &[0.0; 6]),
        "bad.glb: animation 0 (\"walk\") sampler 0: a key time or value is not a finite number"
    );
    // A channel on a node that does not exist, or on a path that is none
    // of the four (the crate unwraps both; found by fuzzing).
    let bad_target = |target: &str| {
        let mut d = Doc::default();
        let pos = d.vec3(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
        let t = d.floats(&[0.0, 1.0], "SCALAR", 1);
        let v = d.floats(&[0.0; 6], "VEC3", 3);
        let glb = d.glb(&format!(
            r#""meshes":[{{"primitives":[{{"attributes":{{"POSITION":{pos}}}}}]}}],
"nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0,
"animations":[{{"channels":[{{"sampler":0,"target":{target}}}],"samplers":[{{"input":{t},"output":{v}}}]}}]"#
        ));
        match gltf::parse(&glb, None, "bad.glb", &LoadOptions::default()) {
            Ok(_) => panic!("accepted"),
            Err(e) => e.to_string(),
        }
    };
    assert_eq!(
        bad_target(r#"{"node":9,"path":"translation"}"#),
        "bad.glb: animation 0 channel 0 targets node 9, which does not exist"
    );
    assert_eq!(
        bad_target(r#"{"node":0,"path":"pointer"}"#),
        "bad.glb: animation 0 channel 0 animates a property rastty does not know (not translation, rotation, scale or weights)"
    );
    assert_eq!(
        bad(&[0.0, 1.0], &[0.0; 9]),
        "bad.glb: animation 0 (\"walk\") sampler 0: it has 9 output numbers where its keys call for 6"
    );
}

/// Two triangles, each carried by its own node; the clip slides the first
/// (x 0 → 2 over 1 s) and leaves the second still.
fn one_of_two_moving() -> Vec<u8> {
    let mut d = Doc::default();
    let pos = d.vec3(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let times = d.floats(&[0.0, 1.0], "SCALAR", 1);
    let out = d.floats(&[0.0, 0.0, 0.0, 2.0, 0.0, 0.0], "VEC3", 3);
    d.glb(&format!(
        r#""meshes":[{{"primitives":[{{"attributes":{{"POSITION":{pos}}}}}]}}],
"nodes":[{{"mesh":0}},{{"mesh":0,"translation":[1,1,0]}}],"scenes":[{{"nodes":[0,1]}}],"scene":0,
"animations":[{{"channels":[{{"sampler":0,"target":{{"node":0,"path":"translation"}}}}],"samplers":[{{"input":{times},"output":{out}}}]}}]"#
    ))
}

/// The four moving models: skinned, morphed, carried by a node, and one
/// part of two carried.
fn movers() -> Vec<Geometry> {
    vec![
        load(&skinned_arm(), "arm.glb"),
        load(&morphing_square().0, "morph.glb"),
        load(&translated("CUBICSPLINE"), "cubic.glb"),
        load(&one_of_two_moving(), "two.glb"),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    /// The planned frame (which poses only a mesh its clip moves, and a
    /// paused clip once) is the full pipeline's (which poses every
    /// mesh), bit for bit, at any time; and one band draws what three do.
    #[test]
    fn posed_frames_are_the_same_planned_or_full_and_in_bands(
        which in 0usize..4,
        time in prop_oneof![-10.0f64..10.0, 0.0f64..1e7],
        glyphs in proptest::sample::select(rastty::GlyphMode::ALL.to_vec()),
    ) {
        let scene = scene_of(movers().swap_remove(which), time);
        let o = RenderOptions { glyphs, threads: Threads::Exactly(1), ..opts() };
        let mut planned = Renderer::new();
        planned.render(&scene, &o);
        let mut full = Renderer::new();
        full.render(&scene, &RenderOptions { pipeline: Pipeline::Full, ..o });
        prop_assert_eq!(planned.framebuffer().samples(), full.framebuffer().samples());
        prop_assert_eq!(planned.frame(), full.frame());
        let mut bands = Renderer::new();
        bands.render(&scene, &RenderOptions { threads: Threads::Exactly(3), ..o });
        prop_assert_eq!(planned.frame(), bands.frame());
        // The same renderer again at the same time: posed once, drawn the
        // same.
        let again = planned.render(&scene, &o).clone();
        prop_assert_eq!(&again, full.frame());
        prop_assert_eq!(planned.stats().posed_vertices, 0);
    }
}

#[test]
fn a_clip_that_moves_no_vertex_costs_nothing_and_is_drawn_at_rest() {
    // The triangle's node is still; the clip moves an empty node beside it.
    let mut d = Doc::default();
    let pos = d.vec3(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let times = d.floats(&[0.0, 1.0], "SCALAR", 1);
    let out = d.floats(&[0.0, 0.0, 0.0, 5.0, 0.0, 0.0], "VEC3", 3);
    let glb = d.glb(&format!(
        r#""meshes":[{{"primitives":[{{"attributes":{{"POSITION":{pos}}}}}]}}],
"nodes":[{{"mesh":0}},{{}}],"scenes":[{{"nodes":[0,1]}}],"scene":0,
"animations":[{{"channels":[{{"sampler":0,"target":{{"node":1,"path":"translation"}}}}],"samplers":[{{"input":{times},"output":{out}}}]}}]"#
    ));
    let geometry = load(&glb, "aside.glb");
    assert!(!geometry.rig.as_ref().unwrap().moves(0));
    let scene = scene_of(geometry, 0.5);
    let mut planned = Renderer::new();
    planned.render(&scene, &opts());
    let plan = planned.plan().unwrap();
    assert!(!plan[Effect::Pose].run && !plan.poses(0));
    assert_eq!(planned.stats().posed_vertices, 0);
    // The full pipeline poses it anyway, to the same frame.
    let mut full = Renderer::new();
    full.render(
        &scene,
        &RenderOptions {
            pipeline: Pipeline::Full,
            ..opts()
        },
    );
    assert_eq!(full.stats().posed_vertices, 3);
    assert_eq!(planned.frame(), full.frame());
    assert_eq!(
        planned.framebuffer().samples(),
        full.framebuffer().samples()
    );
}

#[test]
fn the_example_arm_is_what_its_builder_makes() {
    let path = common::example_model("arm.glb", skinned_arm());
    let loaded = gltf::load(&path, &LoadOptions::default()).unwrap();
    assert!(loaded.notes.is_empty(), "{:?}", loaded.notes);
    let rig = loaded.geometry.rig.as_ref().unwrap();
    assert_eq!((rig.clips.len(), rig.skins[0].joints.len()), (1, 2));
    assert_eq!(
        (rig.clips[0].name.as_str(), rig.clips[0].length),
        ("wave", 2.0)
    );
}

/// Two triangles, each carried by its own node: the first's translation
/// keyed over 1 s (x 0 → 1), the second's over 3 s (x 0 → 3), in one clip.
#[test]
fn a_shorter_channel_holds_its_last_value_until_the_clip_loops() {
    let mut d = Doc::default();
    let pos = d.vec3(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let short = d.floats(&[0.0, 1.0], "SCALAR", 1);
    let long = d.floats(&[0.0, 3.0], "SCALAR", 1);
    let to1 = d.floats(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0], "VEC3", 3);
    let to3 = d.floats(&[0.0, 0.0, 0.0, 3.0, 0.0, 0.0], "VEC3", 3);
    let glb = d.glb(&format!(
        r#""meshes":[{{"primitives":[{{"attributes":{{"POSITION":{pos}}}}}]}}],
"nodes":[{{"mesh":0}},{{"mesh":0}}],"scenes":[{{"nodes":[0,1]}}],"scene":0,
"animations":[{{"channels":[{{"sampler":0,"target":{{"node":0,"path":"translation"}}}},{{"sampler":1,"target":{{"node":1,"path":"translation"}}}}],
"samplers":[{{"input":{short},"output":{to1}}},{{"input":{long},"output":{to3}}}]}}]"#
    ));
    let g = load(&glb, "two.glb");
    let rig = g.rig.as_ref().unwrap();
    assert_eq!(rig.clips[0].length, 3.0);
    let xs = |time: f64| {
        let (mut p, mut n) = (g.positions.clone(), g.normals.clone());
        let pose = rastty::scene::anim::Pose { clip: 0, time };
        rig.pose_into(Some(pose), &mut Posed::default(), &mut p, &mut n);
        // Each triangle's first vertex sits at its node's origin; in
        // order of x (the parts are in the order the tree is walked).
        let mut firsts: Vec<f32> = rig
            .parts
            .iter()
            .map(|part| p[part.first as usize].x)
            .collect();
        firsts.sort_by(f32::total_cmp);
        firsts
    };
    assert_eq!(xs(0.5), [0.5, 0.5]);
    // The short channel has ended; the clip has not.
    assert_eq!(xs(2.0), [1.0, 2.0]);
    assert_eq!(xs(2.5), [1.0, 2.5]);
    // Both loop together at 3 s.
    assert_eq!(xs(3.5), [0.5, 0.5]);
}

#[test]
fn a_scene_file_names_each_moving_mesh_clip_and_time() {
    let dir = std::env::temp_dir().join(format!("rastty-anim-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let arm = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/models/arm.glb");
    let scene = |mesh: &str| {
        let path = dir.join("s.toml");
        std::fs::write(&path, format!("[[mesh]]\n{mesh}\n")).unwrap();
        Scene::open(&path).map_err(|e| e.to_string().replace(&path.display().to_string(), "s.toml"))
    };
    let at = |mesh: &str| scene(mesh).map(|s| s.meshes[0].pose);
    let path = format!("path = {:?}", arm.display().to_string());
    let pose = |clip, time| Some(rastty::scene::anim::Pose { clip, time });
    assert_eq!(at(&path), Ok(pose(0, 0.0)));
    assert_eq!(
        at(&format!("{path}\nclip = \"wave\"\ntime = 1.5")),
        Ok(pose(0, 1.5))
    );
    assert_eq!(
        at(&format!("{path}\nclip = 0\ntime = -2.0")),
        Ok(pose(0, -2.0))
    );
    assert_eq!(
        at(&format!("{path}\nclip = 3")),
        Err("s.toml:1:1: clip 3: the model has 1 clips, 0 to 0".into())
    );
    assert_eq!(
        at(&format!("{path}\nclip = \"walk\"")),
        Err("s.toml:1:1: no clip named \"walk\" in the model".into())
    );
    assert_eq!(
        at("shape = \"cube\"\ntime = 1.0"),
        Err(
            "s.toml:1:1: `clip` and `time` are for a model that moves, and this one has no clips"
                .into()
        )
    );
    // The pose drawn is the one named: the arm bent at 1 s.
    let bent = scene(&format!("{path}\ntime = 1.0")).unwrap();
    let straight = scene(&path).unwrap();
    assert_ne!(coverage(&bent, &opts()), coverage(&straight, &opts()));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--explain`'s clip line: a clip of a few channels lists each; a
/// skeleton's clip of many is summed up by path and interpolation, so a
/// 50-joint figure's clip stays one line.
#[test]
fn explain_lists_a_few_channels_and_sums_up_many() {
    let clip_line = |glb: &[u8]| {
        let scene = scene_of(load(glb, "e.glb"), 0.5);
        let mut r = Renderer::new();
        r.render(&scene, &opts());
        let report = r.explain(&scene, &opts(), std::time::Duration::ZERO, 0);
        report
            .lines()
            .find(|l| l.starts_with("  clip 0 "))
            .expect("a clip line")
            .to_string()
    };
    assert_eq!(
        clip_line(&skinned_arm()),
        r#"  clip 0 "wave": 2.000 s, 1 channels (node 2 rotation 3 keys LINEAR)"#
    );
    let mut d = Doc::default();
    let pos = d.vec3(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let two = d.floats(&[0.0, 1.0], "SCALAR", 1);
    let three = d.floats(&[0.0, 1.0, 2.0], "SCALAR", 1);
    let slide = d.floats(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0], "VEC3", 3);
    let turn = d.floats(&[0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1.], "VEC4", 4);
    // Seven channels on nodes 0 and 1: four slides (LINEAR), three turns (STEP).
    let channels: Vec<String> = (0..7)
        .map(|k| {
            format!(
                r#"{{"sampler":{},"target":{{"node":{},"path":"{}"}}}}"#,
                k % 2,
                k % 2,
                ["translation", "rotation"][k % 2]
            )
        })
        .collect();
    let glb = d.glb(&format!(
        r#""meshes":[{{"primitives":[{{"attributes":{{"POSITION":{pos}}}}}]}}],
"nodes":[{{"mesh":0}},{{"mesh":0}}],"scenes":[{{"nodes":[0,1]}}],"scene":0,
"animations":[{{"name":"many","channels":[{}],
"samplers":[{{"input":{two},"output":{slide}}},{{"input":{three},"output":{turn},"interpolation":"STEP"}}]}}]"#,
        channels.join(",")
    ));
    assert_eq!(
        clip_line(&glb),
        r#"  clip 0 "many": 2.000 s, 7 channels (on 2 nodes: 4 translation, 3 rotation; 2 to 3 keys; 4 LINEAR, 3 STEP)"#
    );
}

/// A planned frame poses only the part its clip moves; the full pipeline
/// poses both; the frames are the same.
#[test]
fn a_planned_frame_poses_only_the_parts_its_clip_moves() {
    let geometry = load(&one_of_two_moving(), "two.glb");
    // One part moves, one stands (in the order the tree is walked).
    let mut moves = geometry.rig.as_ref().unwrap().clips[0].moves.clone();
    moves.sort_unstable();
    assert_eq!(moves, [false, true]);
    let scene = scene_of(geometry, 0.25);
    let mut planned = Renderer::new();
    planned.render(&scene, &opts());
    assert_eq!(planned.stats().posed_vertices, 3);
    let mut full = Renderer::new();
    full.render(
        &scene,
        &RenderOptions {
            pipeline: Pipeline::Full,
            ..opts()
        },
    );
    assert_eq!(full.stats().posed_vertices, 6);
    assert_eq!(planned.frame(), full.frame());
    assert_eq!(
        planned.framebuffer().samples(),
        full.framebuffer().samples()
    );
}

/// Whether a frame of `r` leaves its outermost rows and columns of
/// samples empty (nothing cut off at an edge), having drawn something.
fn inside_the_edges(r: &Renderer) -> bool {
    let g = r.framebuffer().grid();
    let (w, h) = (g.width as usize, g.height as usize);
    let s = r.framebuffer().samples();
    let at = |x: usize, y: usize| s[y * w + x].is_some();
    s.iter().any(Option::is_some)
        && (0..w).all(|x| !at(x, 0) && !at(x, h - 1))
        && (0..h).all(|y| !at(0, y) && !at(w - 1, y))
}

#[test]
fn a_model_tilted_or_turning_about_x_or_z_is_framed_whole() {
    // A box four times as long (z) as it is wide and high: framed for a
    // turn about y, its length lies across the view.
    let mut mesh = rastty::scene::Shape::Cube.mesh(Rgb::WHITE);
    for p in &mut mesh.geometry_mut().positions {
        p.z *= 4.0;
    }
    let scene = Scene::of_mesh(mesh);
    let opts = RenderOptions {
        cols: 60,
        rows: 20,
        ..RenderOptions::default()
    };
    let mut r = Renderer::new();
    // Still frames tilted (its length turned upright) and rolled.
    for turn in [
        Vec3::ZERO,
        Vec3::new(90.0, 0.0, 0.0),
        Vec3::new(60.0, 30.0, 45.0),
    ] {
        r.render(&scene, &RenderOptions { turn, ..opts });
        assert!(inside_the_edges(&r), "turned {turn}");
    }
    // Every frame of a turn about x, and about z, from a tilt: framed the
    // same, none cut off.
    for (axis, unit) in [
        (rastty::transform::Axis::X, Vec3::X),
        (rastty::transform::Axis::Z, Vec3::Z),
    ] {
        for k in 0..24 {
            let turn = Vec3::new(10.0, 20.0, 30.0) + unit * (15.0 * k as f32 + 7.0);
            r.render(
                &scene,
                &RenderOptions {
                    turn,
                    turn_axis: axis,
                    ..opts
                },
            );
            assert!(inside_the_edges(&r), "about {axis:?}, turned {turn}");
        }
    }
}

#[test]
fn weights_near_f32s_largest_are_normalised_as_the_spec_says() {
    // [3e38, 3e38, 0, 0] sums past f32's range: normalised in f64 it is a
    // half for each joint, as [0.5, 0.5, 0, 0] is (in f32 it was zeros).
    let s = std::f32::consts::FRAC_1_SQRT_2;
    let turns = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, s, s, 0.0, 0.0, s, s];
    let huge = load(&skinned_arm_with([3e38, 3e38, 0.0, 0.0], turns), "huge.glb");
    let half = load(&skinned_arm_with([0.5, 0.5, 0.0, 0.0], turns), "half.glb");
    let whole = load(&skinned_arm_with([0.0, 1.0, 0.0, 0.0], turns), "whole.glb");
    for time in [0.5, 1.0, 1.5] {
        let at = |g: &Geometry| coverage(&scene_of(g.clone(), time), &opts());
        assert_eq!(at(&huge), at(&half), "{time} s");
        assert_ne!(at(&half), at(&whole), "{time} s: the weights matter");
    }
}

#[test]
fn a_rotation_key_of_four_zeros_is_no_rotation() {
    let s = std::f32::consts::FRAC_1_SQRT_2;
    let identity = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, s, s, 0.0, 0.0, 0.0, 1.0];
    let zeros = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, s, s, 0.0, 0.0, 0.0, 0.0];
    let one = load(&skinned_arm_with([1.0, 0.0, 0.0, 0.0], identity), "one.glb");
    let zero = load(&skinned_arm_with([1.0, 0.0, 0.0, 0.0], zeros), "zero.glb");
    for time in [0.0, 0.5, 1.0, 1.5] {
        let at = |g: &Geometry| coverage(&scene_of(g.clone(), time), &opts());
        assert_eq!(at(&zero), at(&one), "{time} s");
    }
    let notes = rastty::scene::gltf::parse(
        &skinned_arm_with([1.0, 0.0, 0.0, 0.0], zeros),
        None,
        "zero.glb",
        &Default::default(),
    )
    .unwrap()
    .notes;
    assert_eq!(
        notes,
        ["2 rotation keys of animations are four zeros, which is no rotation: taken as none"]
    );
}
