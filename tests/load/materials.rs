//! Materials as the file says, end to end: glTF and OBJ finishes read,
//! and drawn through the pipeline users run, against colours computed by
//! hand; the planned frame against the full pipeline's.

use crate::common;

use std::sync::Arc;

use common::Doc;
use glam::Vec3;
use rastty::Effect;
use rastty::color::{Lin, Rgb};
use rastty::scene::{Camera, Geometry, LoadOptions, Mesh, Projection, Scene, gltf, obj};
use rastty::{Choice, Pipeline, RenderOptions, Renderer, Threads};

/// A square of side 2 about the origin in the plane z = 0, facing +z,
/// with the glTF `material` (JSON) and normals.
fn square(material: &str) -> Vec<u8> {
    let mut d = Doc::default();
    let pos = d.vec3(&[
        [-1.0, -1.0, 0.0],
        [1.0, -1.0, 0.0],
        [1.0, 1.0, 0.0],
        [-1.0, 1.0, 0.0],
    ]);
    let normal = d.vec3(&[[0.0, 0.0, 1.0]; 4]);
    let idx = d.indices(&[[0, 1, 2], [0, 2, 3]]);
    d.glb(&format!(
        r#""extensionsUsed":["KHR_materials_unlit","KHR_materials_emissive_strength","KHR_materials_pbrSpecularGlossiness"],
"materials":[{material}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":{pos},"NORMAL":{normal}}},"indices":{idx},"material":0}}]}}],
"nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0"#
    ))
}

fn load(glb: &[u8]) -> Geometry {
    let loaded = gltf::parse(glb, None, "square.glb", &LoadOptions::default()).unwrap();
    assert!(loaded.notes.is_empty(), "{:?}", loaded.notes);
    loaded.geometry
}

/// `geometry` seen face on, filling the middle of the frame, under
/// `lights` (direction, colour, ambient).
fn scene(geometry: Geometry, lights: &[(Vec3, Rgb, f32)]) -> Scene {
    let mut b = Scene::builder()
        .camera(Camera {
            projection: Projection::Perspective {
                fov_y: 60.0,
                near: 0.1,
                far: 20.0,
            },
            eye: Vec3::new(0.0, 0.0, 4.0),
            target: Vec3::ZERO,
            ..Camera::default()
        })
        .mesh(Mesh::of(Arc::new(geometry), Rgb::new(255, 255, 255)));
    for &(direction, color, ambient) in lights {
        b = b.light(rastty::scene::Light {
            direction,
            color,
            ambient,
            ..Default::default()
        });
    }
    // The lights alone: no environment for a metal to reflect (its
    // reflection is tested in `environment.rs`).
    Scene {
        environment: rastty::scene::environment::Environment::None,
        ..b.build().unwrap()
    }
}

fn opts() -> RenderOptions {
    RenderOptions {
        cols: 40,
        rows: 20,
        ..RenderOptions::default()
    }
}

/// The colours of the covered samples, each once, in order.
fn colours(scene: &Scene) -> Vec<Lin> {
    common::colours(scene, opts().cols, opts().rows)
}

const WHITE_FROM_FRONT: (Vec3, Rgb, f32) =
    (Vec3::new(0.0, 0.0, -1.0), Rgb::new(255, 255, 255), 0.0);
const DIM_FROM_SIDE: (Vec3, Rgb, f32) = (Vec3::new(1.0, 0.0, -1.0), Rgb::new(90, 40, 200), 0.1);

#[test]
fn an_unlit_material_is_its_colour_whatever_the_lights() {
    let unlit = r#"{"pbrMetallicRoughness":{"baseColorFactor":[0.5,0.25,0.125,1]},"extensions":{"KHR_materials_unlit":{}}}"#;
    let base = Lin::from_unit([0.5, 0.25, 0.125]);
    for lights in [
        &[WHITE_FROM_FRONT][..],
        &[DIM_FROM_SIDE],
        &[WHITE_FROM_FRONT, DIM_FROM_SIDE],
    ] {
        assert_eq!(colours(&scene(load(&square(unlit)), lights)), [base]);
    }
    // The same material lit is not its colour: the test can fail.
    let lit = r#"{"pbrMetallicRoughness":{"baseColorFactor":[0.5,0.25,0.125,1]}}"#;
    assert_ne!(
        colours(&scene(load(&square(lit)), &[DIM_FROM_SIDE])),
        [base]
    );
}

#[test]
fn a_specular_glossiness_material_is_drawn_by_its_diffuse_colour_and_specular() {
    // Its diffuse colour stands for the base colour (which says green).
    let matte = r#"{"pbrMetallicRoughness":{"baseColorFactor":[0,1,0,1]},"extensions":{"KHR_materials_pbrSpecularGlossiness":{"diffuseFactor":[0.5,0.25,0.125,1],"specularFactor":[0,0,0]}}}"#;
    let g = load(&square(matte));
    assert_eq!(g.materials[0].finish.specular, None);
    assert_eq!(
        colours(&scene(g, &[WHITE_FROM_FRONT])),
        [Lin::from_unit([0.5, 0.25, 0.125])]
    );
    // Its specular colour is the reflectance, 1 − glossiness the
    // roughness, of a surface that is no metal.
    let shiny = r#"{"extensions":{"KHR_materials_pbrSpecularGlossiness":{"specularFactor":[0.5,0.25,1],"glossinessFactor":0.75}}}"#;
    let s = load(&square(shiny)).materials[0].finish.specular.unwrap();
    assert_eq!(
        (s.reflectance, s.metallic, s.roughness),
        (Vec3::new(0.5, 0.25, 1.0), 0.0, 0.25)
    );
}

#[test]
fn emitted_light_is_added_after_lighting() {
    // Black lit by anything is black: what is left is the glow.
    let black =
        r#"{"pbrMetallicRoughness":{"baseColorFactor":[0,0,0,1]},"emissiveFactor":[0.2,0.4,0.6]}"#;
    let glow = Lin::from_unit([0.2, 0.4, 0.6]);
    assert_eq!(
        colours(&scene(load(&square(black)), &[DIM_FROM_SIDE])),
        [glow]
    );
    // KHR_materials_emissive_strength scales it (linear light is held
    // to the full intensity of a primary: 0.6 × 2 is 1).
    let strong = r#"{"pbrMetallicRoughness":{"baseColorFactor":[0,0,0,1]},"emissiveFactor":[0.2,0.4,0.6],"extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":2}}}"#;
    assert_eq!(
        colours(&scene(load(&square(strong)), &[DIM_FROM_SIDE])),
        [Lin::from_unit([0.4, 0.8, 1.0])]
    );
    // Grey lit head-on by white without ambient is its own colour; the
    // glow adds to it, channel by channel.
    let grey = r#"{"pbrMetallicRoughness":{"baseColorFactor":[0.25,0.25,0.25,1]},"emissiveFactor":[0.5,0,0]}"#;
    let lit = Lin::from_unit([0.25, 0.25, 0.25]).0.map(u32::from);
    let add = Lin::from_unit([0.5, 0.0, 0.0]).0.map(u32::from);
    let sum = Lin([0, 1, 2].map(|i| (lit[i] + add[i]) as u16));
    assert_eq!(
        colours(&scene(load(&square(grey)), &[WHITE_FROM_FRONT])),
        [sum]
    );
}

#[test]
fn a_glowing_frame_is_the_same_planned_or_full_and_in_bands() {
    let grey = r#"{"pbrMetallicRoughness":{"baseColorFactor":[0.25,0.5,0.25,1]},"emissiveFactor":[0.1,0,0.3]}"#;
    let s = scene(load(&square(grey)), &[DIM_FROM_SIDE, WHITE_FROM_FRONT]);
    for &glyphs in rastty::GlyphMode::ALL {
        let o = RenderOptions {
            glyphs,
            threads: Threads::Exactly(1),
            ..opts()
        };
        let mut planned = Renderer::new();
        planned.render(&s, &o);
        assert!(planned.plan().unwrap()[Effect::Glow].run);
        let mut full = Renderer::new();
        full.render(
            &s,
            &RenderOptions {
                pipeline: Pipeline::Full,
                ..o
            },
        );
        assert_eq!(
            planned.framebuffer().samples(),
            full.framebuffer().samples()
        );
        let mut bands = Renderer::new();
        bands.render(
            &s,
            &RenderOptions {
                threads: Threads::Exactly(3),
                ..o
            },
        );
        assert_eq!(planned.frame(), bands.frame());
    }
    // A scene that glows nowhere skips the stage.
    let plain = scene(load(&square("{}")), &[WHITE_FROM_FRONT]);
    let mut r = Renderer::new();
    r.render(&plain, &opts());
    assert!(!r.plan().unwrap()[Effect::Glow].run);
    assert_eq!(r.stats().glowing_triangles, 0);
}

/// An OBJ square with the material library `mtl`.
fn obj_square(mtl: &str) -> obj::Loaded {
    let dir = std::env::temp_dir().join(format!("rastty-mtl-{}-{}", std::process::id(), mtl.len()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("m.mtl"), mtl).unwrap();
    let src = "mtllib m.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nusemtl m\nf 1 2 3 4\n";
    obj::parse(src.as_bytes(), "square.obj", &dir).unwrap()
}

#[test]
fn an_obj_material_glows_with_ke_and_shines_with_ks_unless_illum_says_not() {
    let loaded =
        obj_square("newmtl m\nKd 0 0 0\nKe 0.2 0.4 0.6\nKs 0.5 0.5 0.5\nNs 98\nillum 2\nd 1\n");
    assert!(loaded.notes.is_empty(), "{:?}", loaded.notes);
    let finish = loaded.geometry.materials[0].finish;
    let s = finish.specular.expect("a highlight");
    // Ks is a colour like Kd: 16-bit linear light, as a fraction.
    let half = Vec3::from(Lin::from_unit([0.5; 3]).to_f32()) / 65535.0;
    assert_eq!((s.reflectance, s.metallic), (half, 0.0));
    assert_eq!(s.roughness, (0.02f32).sqrt().sqrt());
    // Without a highlight, black lit by anything shows its glow alone.
    let glowing = obj_square("newmtl m\nKd 0 0 0\nKe 0.2 0.4 0.6\n").geometry;
    assert_eq!(
        colours(&scene(glowing, &[DIM_FROM_SIDE])),
        [Lin::from_unit([0.2, 0.4, 0.6])]
    );
    // illum 1: no highlight; d below 1: blended (tests/load/alpha.rs); a `d`
    // outside [0, 1] is noted as not drawn.
    let loaded = obj_square("newmtl m\nKs 1 1 1\nillum 1\nd 0.5\n");
    assert_eq!(loaded.geometry.materials[0].finish.specular, None);
    assert!(loaded.notes.is_empty(), "{:?}", loaded.notes);
    let loaded = obj_square("newmtl m\nd 1.5\n");
    let dir = std::env::temp_dir().display().to_string();
    let notes: Vec<String> = loaded
        .notes
        .iter()
        .map(|n| n.replace(&dir, "TMP"))
        .collect();
    assert_eq!(notes.len(), 1);
    let sep = std::path::MAIN_SEPARATOR;
    assert!(
        notes[0].ends_with(&format!("{sep}m.mtl: not drawn: `d`")),
        "{notes:?}"
    );
}

#[test]
fn a_colour_as_a_spectral_curve_or_in_xyz_is_noted_and_leaves_the_colour_as_it_was() {
    let plain = obj_square("newmtl m\nKd 0.2 0.4 0.6\n");
    let loaded = obj_square("newmtl m\nKd 0.2 0.4 0.6\nKd spectral red.rfl 2\nKs xyz 1 1 1\n");
    let (m, p) = (&loaded.geometry.materials[0], &plain.geometry.materials[0]);
    assert_eq!((m.color, m.finish.specular), (p.color, None));
    assert!(m.color.is_some());
    assert_eq!(loaded.notes.len(), 1);
    assert!(
        loaded.notes[0].ends_with(&format!(
            "{}m.mtl: not drawn: `Kd spectral`, `Ks xyz`",
            std::path::MAIN_SEPARATOR
        )),
        "{:?}",
        loaded.notes
    );
}

#[test]
fn a_bad_ns_is_an_error_at_its_line_and_column() {
    let dir = std::env::temp_dir().join(format!("rastty-mtl-ns-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("m.mtl"), "newmtl m\nNs shiny\n").unwrap();
    let src = b"mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n";
    let e = obj::parse(src, "t.obj", &dir).unwrap_err().to_string();
    let e = e.replace(&dir.join("m.mtl").display().to_string(), "DIR/m.mtl");
    assert_eq!(e, "DIR/m.mtl:2:4: `Ns`: \"shiny\" is not an exponent");
}

/// A metal of `roughness` in white: no diffuse light, only its highlight.
fn white_metal(roughness: f32) -> rastty::scene::Finish {
    rastty::scene::Finish {
        specular: rastty::scene::Specular::metallic_roughness(1.0, roughness),
        ..Default::default()
    }
}

/// `geometry` with one material of `finish` over every face.
fn finished(mut geometry: Geometry, finish: rastty::scene::Finish) -> Geometry {
    geometry.materials = vec![rastty::scene::MaterialRun {
        first: 0,
        color: None,
        texture: None,
        finish,
    }];
    geometry
}

/// A dim white light travelling along −z: from the eye of [`scene`]
/// (dim, so that the highlights below stay short of full light).
const FROM_THE_EYE: (Vec3, Rgb, f32) = (Vec3::new(0.0, 0.0, -1.0), Rgb::new(8, 8, 8), 0.0);

/// One sample a cell on an odd grid, square samples: the middle sample's
/// centre is the view's centre.
fn odd_grid(highlights: rastty::Highlights) -> RenderOptions {
    RenderOptions {
        cols: 41,
        rows: 41,
        glyphs: rastty::GlyphMode::Block,
        cell_aspect: 1.0,
        highlights,
        ..RenderOptions::default()
    }
}

/// The covered samples' brightness (the channels' sum) by index, and the
/// index of the brightest (`None` if it is not alone).
fn brightest(r: &Renderer) -> (Vec<u32>, Option<usize>) {
    let b: Vec<u32> = r
        .framebuffer()
        .samples()
        .iter()
        .map(|s| s.map_or(0, |c| c.0.iter().map(|&v| u32::from(v)).sum()))
        .collect();
    let max = b.iter().copied().max().unwrap_or(0);
    let at: Vec<usize> = (0..b.len()).filter(|&i| b[i] == max).collect();
    (b, (at.len() == 1).then(|| at[0]))
}

#[test]
fn a_mirror_like_sphere_lit_from_the_eye_has_its_brightest_sample_where_the_reflection_is() {
    // Seen along −z through a parallel view and lit from the eye, a sphere
    // reflects the light back where its normal is +z: the middle of its
    // image, which the middle sample's centre is.
    let sphere = finished(
        (*rastty::scene::Shape::Sphere.geometry()).clone(),
        white_metal(0.3),
    );
    let scene = Scene::builder()
        .camera(Camera {
            projection: Projection::Orthographic {
                height: 3.0,
                near: 0.1,
                far: 20.0,
            },
            eye: Vec3::new(0.0, 0.0, 4.0),
            target: Vec3::ZERO,
            ..Camera::default()
        })
        .mesh(Mesh::of(Arc::new(sphere), Rgb::new(255, 255, 255)))
        .light(rastty::scene::Light {
            direction: FROM_THE_EYE.0,
            color: FROM_THE_EYE.1,
            ambient: FROM_THE_EYE.2,
            ..Default::default()
        })
        .build()
        .unwrap();
    // The light's reflection alone.
    let scene = Scene {
        environment: rastty::scene::environment::Environment::None,
        ..scene
    };
    let mut r = Renderer::new();
    r.render(&scene, &odd_grid(rastty::Highlights::Sample));
    let (b, at) = brightest(&r);
    assert_eq!(
        at,
        Some(20 * 41 + 20),
        "the middle sample alone is brightest"
    );
    // A metal is dark away from its highlight: the rim of the disc.
    assert!(b[20 * 41 + 7] * 4 < b[20 * 41 + 20]);
    assert!(r.stats().specular_samples > 0);
}

#[test]
fn a_highlight_inside_a_triangle_is_drawn_per_sample_and_lost_per_vertex() {
    // A square of two triangles seen face on through a perspective view,
    // lit from the eye: its highlight is in the middle, far from every
    // corner.
    let square = finished(load(&square("{}")), white_metal(0.3));
    let s = scene(square, &[FROM_THE_EYE]);
    let mut per_sample = Renderer::new();
    per_sample.render(&s, &odd_grid(rastty::Highlights::Sample));
    let (b, at) = brightest(&per_sample);
    let middle = 20 * 41 + 20;
    assert_eq!(at, Some(middle));
    let mut per_vertex = Renderer::new();
    per_vertex.render(&s, &odd_grid(rastty::Highlights::Vertex));
    let (v, _) = brightest(&per_vertex);
    // Found at the corners and interpolated, the highlight is all but gone.
    assert!(
        v[middle] * 10 < b[middle],
        "{} against {}",
        v[middle],
        b[middle]
    );
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig { cases: 24, ..Default::default() })]

    /// A shining sphere at any turn and finish, near enough to be cut by
    /// the near plane or far, through either view, with either kind of
    /// highlight: the planned frame (which sends only shining runs through
    /// the specular fill) is the full pipeline's (which sends every run,
    /// matte ones adding nothing), bit for bit; and one band draws what
    /// three do.
    #[test]
    fn shining_frames_are_the_same_planned_or_full_and_in_bands(
        metallic in 0.0f32..=1.0,
        roughness in 0.0f32..=1.0,
        turn in proptest::array::uniform3(-180.0f32..180.0),
        distance in proptest::prop_oneof![1.05f32..1.5, 2.0f32..6.0],
        parallel in proptest::bool::ANY,
        vertex in proptest::bool::ANY,
        glyphs in proptest::sample::select(rastty::GlyphMode::ALL.to_vec()),
    ) {
        let mut sphere = (*rastty::scene::Shape::Sphere.geometry()).clone();
        // Half its faces shine; the rest are matte.
        sphere.materials = vec![
            rastty::scene::MaterialRun { first: 0, color: None, texture: None, finish: Default::default() },
            rastty::scene::MaterialRun {
                first: (sphere.faces.len() / 2) as u32,
                color: Some(Lin::from_unit([0.8, 0.5, 0.2])),
                texture: None,
                finish: rastty::scene::Finish {
                    specular: rastty::scene::Specular::metallic_roughness(metallic, roughness),
                    ..Default::default()
                },
            },
        ];
        let projection = if parallel {
            Projection::Orthographic { height: 3.0, near: 0.1, far: 20.0 }
        } else {
            Projection::Perspective { fov_y: 60.0, near: 0.1, far: 20.0 }
        };
        let scene = Scene::builder()
            .camera(Camera { projection, eye: Vec3::new(0.0, 0.0, distance), target: Vec3::ZERO, ..Camera::default() })
            .mesh(Mesh::of(Arc::new(sphere), Rgb::new(90, 160, 220)))
            .light(rastty::scene::Light { direction: Vec3::new(-1.0, -0.5, -1.0), color: Rgb::new(255, 240, 220), ambient: 0.1, ..Default::default() })
            .light(rastty::scene::Light { direction: Vec3::new(1.0, 0.2, -0.3), color: Rgb::new(80, 90, 160), ambient: 0.0, ..Default::default() })
            .build()
            .unwrap();
        let o = RenderOptions {
            glyphs,
            turn: Vec3::from(turn),
            highlights: if vertex { rastty::Highlights::Vertex } else { rastty::Highlights::Sample },
            threads: Threads::Exactly(1),
            ..opts()
        };
        let mut planned = Renderer::new();
        planned.render(&scene, &o);
        let mut full = Renderer::new();
        full.render(&scene, &RenderOptions { pipeline: Pipeline::Full, ..o });
        proptest::prop_assert_eq!(planned.framebuffer().samples(), full.framebuffer().samples());
        proptest::prop_assert_eq!(planned.frame(), full.frame());
        let mut bands = Renderer::new();
        bands.render(&scene, &RenderOptions { threads: Threads::Exactly(3), ..o });
        proptest::prop_assert_eq!(planned.frame(), bands.frame());
    }
}
