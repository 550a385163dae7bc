//! The planner never changes a picture: random scenes and every example
//! scene, rendered with the plan and with every stage forced on, give the
//! same frame and the same samples, bit for bit. And a skipped stage does
//! no work at all.

use rastty::Choice;
use rastty::Effect;
use std::path::Path;
use std::sync::Arc;

use glam::Vec3;
use proptest::prelude::*;
use rastty::Aa;
use rastty::Pipeline;
use rastty::Shading;
use rastty::raster::Traversal;
use rastty::scene::{Camera, Light, LightKind, Projection, Shape, Triangle, TriangleColor};
use rastty::scene::{Cull, Sides};
use rastty::{
    Frame, GlyphMode, RenderOptions, Renderer, Threads, color::ColorDepth, color::Rgb,
    encode::Encoder, scene::Scene,
};

/// Renders both ways; returns the planned renderer's statistics.
fn same_both_ways(scene: &Scene, opts: &RenderOptions) -> Result<rastty::FrameStats, String> {
    let mut planned = Renderer::new();
    let mut full = Renderer::new();
    let a = planned
        .render(
            scene,
            &RenderOptions {
                pipeline: Pipeline::Planned,
                ..*opts
            },
        )
        .clone();
    let b = full
        .render(
            scene,
            &RenderOptions {
                pipeline: Pipeline::Full,
                ..*opts
            },
        )
        .clone();
    if planned.framebuffer().samples() != full.framebuffer().samples() {
        let i = planned
            .framebuffer()
            .samples()
            .iter()
            .zip(full.framebuffer().samples())
            .position(|(x, y)| x != y);
        let at = |r: &Renderer| i.map(|i| r.framebuffer().samples()[i]);
        return Err(format!(
            "samples differ at {i:?} ({:?} planned, {:?} full); plan: {:?}",
            at(&planned),
            at(&full),
            planned.plan()
        ));
    }
    if a != b {
        return Err("frames differ".into());
    }
    Ok(*planned.stats())
}

/// Renders with one band, then with 2 to 7 (one reused renderer): the
/// frame, every sample, every depth (where tested) and every count are the
/// same, except per-face lighting, which each band does for itself.
fn same_with_any_thread_count(scene: &Scene, opts: &RenderOptions) -> Result<(), String> {
    let mut one = Renderer::new();
    let opts = |n| RenderOptions {
        threads: Threads::Exactly(n),
        ..*opts
    };
    let frame = one.render(scene, &opts(1)).clone();
    let plan = one.plan().unwrap();
    if plan.bands.count != 1 {
        return Err(format!("one thread asked for, {} bands", plan.bands.count));
    }
    let depth = plan[Effect::Depth].run;
    let fb = one.framebuffer();
    let grid = fb.grid();
    let depths = |fb: &rastty::Framebuffer| -> Vec<u32> {
        (0..grid.height)
            .flat_map(|y| (0..grid.width).map(move |x| (x, y)))
            .map(|(x, y)| fb.depth(x, y).to_bits())
            .collect()
    };
    let mut reused = Renderer::new();
    for n in 2..=7 {
        let banded = reused.render(scene, &opts(n)).clone();
        let bands = reused.plan().unwrap().bands.count;
        let rows = opts(n).rows;
        if opts(n).aa == Aa::None && bands != n.min(rows) {
            return Err(format!(
                "{n} threads asked for, {bands} bands of {rows} rows"
            ));
        }
        if banded != frame {
            return Err(format!("{n} threads: frames differ"));
        }
        if reused.framebuffer().samples() != fb.samples() {
            return Err(format!("{n} threads: samples differ"));
        }
        if depth && depths(reused.framebuffer()) != depths(fb) {
            return Err(format!("{n} threads: depths differ"));
        }
        let (a, b) = (*one.stats(), *reused.stats());
        // Lighting and glow are each band's own work (see
        // `FrameStats::add_band`): not compared.
        let unlit = |s: rastty::FrameStats| rastty::FrameStats {
            lighting_evaluations: 0,
            glowing_triangles: 0,
            ..s
        };
        if unlit(a) != unlit(b) {
            return Err(format!("{n} threads: counts differ: {a:?} {b:?}"));
        }
    }
    Ok(())
}

fn color() -> impl Strategy<Value = Rgb> {
    any::<[u8; 3]>().prop_map(Rgb)
}

fn triangle(flat_z: bool) -> impl Strategy<Value = Triangle> {
    let v = move || {
        (-1.5f32..1.5, -1.5f32..1.5, -1.5f32..1.5)
            .prop_map(move |(x, y, z)| Vec3::new(x, y, if flat_z { 0.25 } else { z }))
    };
    (v(), v(), v(), color(), prop::option::of((color(), color()))).prop_map(
        |(a, b, c, c0, more)| Triangle {
            vertices: [a, b, c],
            color: match more {
                None => TriangleColor::Flat(c0),
                Some((c1, c2)) => TriangleColor::PerVertex([c0, c1, c2]),
            },
        },
    )
}

fn mesh() -> impl Strategy<Value = rastty::scene::Mesh> {
    (
        prop::sample::select(Shape::ALL.to_vec()),
        color(),
        (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0),
        (0.0f32..360.0, 0.0f32..360.0),
        0.3f32..1.5,
        prop::sample::select(vec![Cull::Back, Cull::None, Cull::Front]),
        alpha(),
        prop::option::weighted(0.25, (0u8..16, 0.0f32..1.0)),
        prop::option::weighted(0.25, 0.0f32..1.0),
        prop::sample::select(vec![
            Sides::Unsaid,
            Sides::Unsaid,
            Sides::Single,
            Sides::Double,
        ]),
        prop::option::weighted(0.2, (1u8..4, 0.0f32..1.0)),
    )
        .prop_map(
            |(shape, c, (x, y, z), (rx, ry), s, cull, alpha, maps, texture, sides, layers)| {
                let mut m = shape.mesh(c);
                if alpha.is_some()
                    || maps.is_some()
                    || texture.is_some()
                    || sides != Sides::Unsaid
                    || layers.is_some()
                {
                    // The second half of its faces masked or blended, with
                    // maps (and UVs and tangents to read them by) or not, with
                    // a base colour texture or not, its sides said or not
                    // (glTF's `doubleSided`).
                    let g = m.geometry_mut();
                    // A clear coat, sheen or both (the bits of `which`),
                    // over a dielectric that shines or not.
                    let layers =
                        layers.map_or_else(Default::default, |(which, k)| rastty::scene::Layers {
                            clearcoat: (which & 1 != 0)
                                .then(|| rastty::scene::Clearcoat::new(0.3 + k * 0.7, k))
                                .flatten(),
                            sheen: (which & 2 != 0)
                                .then(|| {
                                    rastty::scene::Sheen::new(Vec3::new(k, 0.5, 1.0 - k), 1.0 - k)
                                })
                                .flatten(),
                        });
                    let mut finish = rastty::scene::Finish {
                        alpha: alpha.unwrap_or_default(),
                        sides,
                        layers,
                        specular: rastty::scene::Specular::metallic_roughness(0.0, 0.5)
                            .filter(|_| layers.sheen.is_some()),
                        ..Default::default()
                    };
                    if let Some((which, k)) = maps {
                        finish = mapped(g, finish, which, k);
                    }
                    let texture = texture.map(|k| texture_2x2(g, k));
                    g.materials = vec![rastty::scene::MaterialRun {
                        first: (g.faces.len() / 2) as u32,
                        color: None,
                        texture,
                        finish,
                    }];
                    g.analyze();
                }
                m.model = rastty::transform::model(
                    Vec3::splat(s),
                    Vec3::new(rx, ry, 0.0),
                    Vec3::new(x, y, z),
                );
                m.cull = cull;
                m
            },
        )
}

/// `finish` with the maps of the bits of `which` (normal, occlusion,
/// emissive, metallic-roughness), each a 2×2 texture made from `k`, and
/// the UVs (x and y) and tangents (along x) of `g` to read them by.
fn mapped(
    g: &mut rastty::scene::Geometry,
    mut finish: rastty::scene::Finish,
    which: u8,
    k: f32,
) -> rastty::scene::Finish {
    g.tangents = Some(vec![
        [rastty::glam::Vec4::new(1.0, 0.0, 0.0, 1.0); 3];
        g.faces.len()
    ]);
    let t = texture_2x2(g, k);
    let maps = &mut finish.maps;
    maps.normal = (which & 1 != 0).then_some((t, 1.0 - k));
    maps.occlusion = (which & 2 != 0).then_some((t, k));
    maps.emissive = (which & 4 != 0).then_some(t);
    maps.metallic_roughness = (which & 8 != 0).then_some(t);
    if which & 8 != 0 {
        finish.specular = rastty::scene::Specular::metallic_roughness(k, 1.0 - k);
    }
    if which & 4 != 0 {
        finish.emissive = rastty::color::Lin::from_f32([20000.0, 5000.0, 0.0]);
    }
    finish
}

/// A 2×2 texture made from `k` (a white texel among them: one that a
/// colour a hair under its own, interpolated, would round down a step)
/// added to `g`, and the UVs (x and y) to read it by; its index.
fn texture_2x2(g: &mut rastty::scene::Geometry, k: f32) -> u32 {
    use rastty::texture::{Sampler, Texture};
    g.uvs = Some(g.positions.iter().map(|p| p.truncate() * 2.0).collect());
    let texels = [
        [k, 0.5, 1.0],
        [1.0 - k, k, 0.8],
        [0.3, 1.0 - k, 0.9],
        [k, k, k],
    ];
    g.textures.push(Arc::new(Texture::from_linear(
        "map",
        2,
        2,
        texels.to_vec(),
        Sampler::default(),
    )));
    g.textures.len() as u32 - 1
}

/// Opaque (no material) mostly; else a mask or a blend of some alpha.
fn alpha() -> impl Strategy<Value = Option<rastty::scene::Alpha>> {
    use rastty::scene::{Alpha, AlphaMode};
    prop_oneof![
        3 => Just(None),
        1 => (0.0f32..=1.0, 0.0f32..=1.0).prop_map(|(cutoff, factor)| Some(Alpha {
            mode: AlphaMode::Mask { cutoff },
            factor,
            texture: None,
        })),
        1 => (0.0f32..=1.0).prop_map(|factor| Some(Alpha {
            mode: AlphaMode::Blend,
            factor,
            texture: None,
        })),
    ]
}

/// A cube or a sphere with one corner pushed in (by as little as a
/// millionth of its size: convex to the eye, not to the planner), its
/// positions moved far from the origin and the model transform bringing
/// them back.
fn near_convex_mesh() -> impl Strategy<Value = rastty::scene::Mesh> {
    (
        prop::sample::select(vec![Shape::Cube, Shape::Sphere]),
        color(),
        prop_oneof![Just(0.0f32), 1e-6f32..1e-3, 1e-3f32..0.3],
        any::<prop::sample::Index>(),
        prop::sample::select(vec![0.0f32, 1e3, 1e5, 1e6]),
        (0.0f32..360.0, 0.0f32..360.0),
        prop::sample::select(vec![Cull::Back, Cull::None]),
    )
        .prop_map(|(shape, c, dent, corner, far, (rx, ry), cull)| {
            let mut m = shape.mesh(c);
            let g = m.geometry_mut();
            let target = g.positions[corner.index(g.positions.len())];
            let offset = Vec3::new(far, -0.5 * far, 0.25 * far);
            for p in &mut g.positions {
                if *p == target {
                    *p *= 1.0 - dent;
                }
                *p += offset;
            }
            g.analyze();
            m.model = rastty::transform::model(Vec3::ONE, Vec3::new(rx, ry, 0.0), Vec3::ZERO)
                * glam::Mat4::from_translation(-offset);
            m.cull = cull;
            m
        })
}

fn camera() -> impl Strategy<Value = Camera> {
    (
        prop::sample::select(vec![0u8, 1, 2]),
        (-4.0f32..4.0, -4.0f32..4.0, 0.5f32..6.0),
        20.0f32..100.0,
        0.05f32..2.0,
    )
        .prop_map(|(kind, (x, y, z), fov, near)| Camera {
            shift: rastty::glam::Vec2::ZERO,
            projection: match kind {
                0 => Projection::Perspective {
                    fov_y: fov,
                    near,
                    far: 40.0,
                },
                1 => Projection::Orthographic {
                    height: 3.0,
                    near,
                    far: 40.0,
                },
                _ => Projection::None,
            },
            eye: Vec3::new(x, y, z),
            target: Vec3::ZERO,
            up: Vec3::Y,
            fit: None,
        })
}

fn light() -> impl Strategy<Value = Light> {
    (
        (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..-0.1),
        color(),
        0.0f32..0.5,
        kind(),
        0.25f32..4.0,
    )
        .prop_map(|((x, y, z), color, ambient, kind, intensity)| Light {
            direction: Vec3::new(x, y, z).normalize(),
            color,
            ambient,
            kind,
            intensity,
        })
}

/// Directional, point and spot lights, placed about the scene's middle,
/// with and without a range.
fn kind() -> impl Strategy<Value = LightKind> {
    let position =
        (-3.0f32..3.0, -3.0f32..3.0, -1.0f32..4.0).prop_map(|(x, y, z)| Vec3::new(x, y, z));
    let range = prop::option::of(0.5f32..8.0);
    prop_oneof![
        Just(LightKind::Directional),
        (position.clone(), range.clone())
            .prop_map(|(position, range)| LightKind::Point { position, range }),
        (position, range, 0.0f32..0.6, 0.05f32..0.9).prop_map(|(position, range, inner, gap)| {
            LightKind::Spot {
                position,
                range,
                inner,
                outer: (inner + gap).min(std::f32::consts::FRAC_PI_2),
            }
        }),
    ]
}

/// Loose triangles, meshes, a camera, lights and a background.
fn scene() -> impl Strategy<Value = Scene> {
    (
        prop::collection::vec(triangle(false), 0..5),
        prop::collection::vec(mesh(), 0..3),
        camera(),
        prop::collection::vec(light(), 0..3),
        prop::option::of(color()),
    )
        .prop_map(|(triangles, meshes, camera, lights, background)| Scene {
            background,
            camera,
            triangles,
            meshes,
            lights,
            ..Scene::default()
        })
}

fn options() -> impl Strategy<Value = RenderOptions> {
    (
        prop::sample::select(GlyphMode::ALL.to_vec()),
        prop::sample::select(Shading::ALL.to_vec()),
        prop::option::of(prop::sample::select(vec![
            Cull::None,
            Cull::Back,
            Cull::Front,
        ])),
        (0.0f32..360.0, 0.0f32..360.0, 0.0f32..360.0),
        // The smallest, for meshes of so many vertices a sample that their
        // corners' depth and light are found at set-up
        // (`Plan::DEFER_PER_SAMPLE`).
        prop::sample::select(vec![(12u16, 6u16), (23, 9), (6, 3)]),
        prop::sample::select(Aa::ALL.to_vec()),
        // A rim light, a third of the time.
        prop::option::weighted(0.33, (0u8..=255, 0u8..=255, 0u8..=255)),
        // A wireframe, a quarter of the time.
        prop_oneof![
            6 => Just(rastty::Wire::Solid),
            1 => Just(rastty::Wire::Lines),
            1 => Just(rastty::Wire::Edges),
        ],
    )
        .prop_map(
            |(glyphs, shading, cull, (p, y, r), (cols, rows), aa, rim, wire)| RenderOptions {
                cols,
                rows,
                glyphs,
                color: ColorDepth::TrueColor,
                shading,
                cull,
                turn: Vec3::new(p, y, r),
                aa,
                rim: rim.map(|(r, g, b)| Rgb::new(r, g, b)),
                wire,
                ..RenderOptions::default()
            },
        )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(
        std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(96)
    ))]

    #[test]
    fn random_scenes_are_the_same_planned_or_full(scene in scene(), opts in options()) {
        if let Err(e) = same_both_ways(&scene, &opts) {
            prop_assert!(false, "{}", e);
        }
    }

    /// Every triangle handed to the pipeline is counted once a pass in
    /// `triangles_in` (anti-aliasing draws the scene once per sub-sample):
    /// every mesh's faces and the loose triangles, whatever the path each
    /// takes (lean, general, clipped), the pipeline and the number of
    /// bands; none of a mesh's when it is drawn as lines alone.
    #[test]
    fn every_triangle_handed_in_is_counted_once(
        scene in scene(),
        opts in options(),
        full in any::<bool>(),
        threads in 1u16..4,
    ) {
        let pipeline = if full { Pipeline::Full } else { Pipeline::Planned };
        let opts = RenderOptions { pipeline, threads: Threads::Exactly(threads), ..opts };
        let mut r = Renderer::new();
        r.render(&scene, &opts);
        // A wireframe of lines alone hands in no mesh's face (the plan
        // says so).
        let faces = if r.plan().unwrap()[Effect::Faces].run {
            scene.meshes.iter().map(|m| m.faces.len()).sum::<usize>()
        } else {
            0
        };
        let handed_in = faces + scene.triangles.len();
        prop_assert_eq!(r.stats().triangles_in, handed_in as u64 * opts.aa.passes());
    }

    /// Promise 11: the same frame, bit for bit, drawn by one thread or in
    /// bands by several, in every glyph mode, with clipping, depth,
    /// culling, lighting and the full pipeline.
    #[test]
    fn random_scenes_are_the_same_with_any_thread_count(
        scene in scene(),
        opts in options(),
        full in any::<bool>(),
    ) {
        let pipeline = if full { Pipeline::Full } else { Pipeline::Planned };
        // Anti-aliased frames are drawn on one thread (and checked to be).
        let opts = RenderOptions { aa: Aa::None, pipeline, ..opts };
        same_with_any_thread_count(&scene, &opts).map_err(TestCaseError::fail)?;
    }

    /// Only what was drawn is cleared, blitted and compared with what the
    /// terminal shows: a renderer and an encoder used frame after frame,
    /// on scenes of every kind and size (with and without depth or a
    /// background, in bands or not), give every frame the samples, depths
    /// and cells a fresh renderer gives, and the bytes an encoder gives
    /// for the same cells written into a frame by hand (which then knows
    /// nothing of where they were drawn).
    #[test]
    fn a_reused_renderer_and_encoder_give_what_fresh_ones_give(
        frames in prop::collection::vec((scene(), options(), 1u16..4), 2..6),
        depth in prop::sample::select(vec![ColorDepth::TrueColor, ColorDepth::Ansi256, ColorDepth::Ansi16]),
    ) {
        let mut reused = Renderer::new();
        let (mut known, mut by_hand) = (Encoder::new(depth), Encoder::new(depth));
        for (scene, opts, threads) in &frames {
            let opts = RenderOptions { threads: Threads::Exactly(*threads), ..*opts };
            let frame = reused.render(scene, &opts).clone();
            let mut fresh = Renderer::new();
            prop_assert_eq!(&frame, fresh.render(scene, &opts));
            prop_assert_eq!(reused.framebuffer().samples(), fresh.framebuffer().samples());
            if fresh.plan().unwrap()[Effect::Depth].run {
                let depths = |r: &Renderer| -> Vec<u32> {
                    let fb = r.framebuffer();
                    let g = fb.grid();
                    (0..g.height)
                        .flat_map(|y| (0..g.width).map(move |x| fb.depth(x, y).to_bits()))
                        .collect()
                };
                prop_assert_eq!(depths(&reused), depths(&fresh));
            }
            let mut copy = Frame::new(frame.cols(), frame.rows());
            copy.set_plain(frame.plain());
            for r in 0..frame.rows() {
                copy.row_mut(r).copy_from_slice(frame.row(r));
            }
            known.encode(&frame, &mut Vec::new()).unwrap();
            by_hand.encode(&copy, &mut Vec::new()).unwrap();
            prop_assert_eq!(
                String::from_utf8_lossy(known.last_bytes()),
                String::from_utf8_lossy(by_hand.last_bytes())
            );
        }
    }

    /// The depth-free path's favourite case, flat 2D scenes; and one
    /// convex mesh alone, once a depth-free case too.
    #[test]
    fn flat_scenes_and_lone_convex_meshes_are_the_same_planned_or_full(
        triangles in prop::collection::vec(triangle(true), 2..8),
        mesh in mesh(),
        camera in camera(),
        lights in prop::collection::vec(light(), 0..2),
        opts in options(),
    ) {
        let flat = Scene::in_canonical_cube(triangles);
        let flat_opts = RenderOptions { turn: Vec3::ZERO, ..opts };
        let stats = same_both_ways(&flat, &flat_opts).map_err(TestCaseError::fail)?;
        prop_assert_eq!(stats.depth_tests, 0);
        let lone = Scene { camera, meshes: vec![mesh], lights, ..Scene::default() };
        same_both_ways(&lone, &opts).map_err(TestCaseError::fail)?;
    }

    /// Lone meshes that are nearly convex, far from the origin, turned back
    /// near the camera: the f32 vertex stage cancels large numbers, and
    /// clip tests are skipped only where that rounding cannot take a vertex
    /// out of the clip volume.
    #[test]
    fn lone_near_convex_meshes_far_from_the_origin_are_the_same_planned_or_full(
        mesh in near_convex_mesh(),
        camera in camera(),
        lights in prop::collection::vec(light(), 0..2),
        opts in options(),
    ) {
        let lone = Scene { camera, meshes: vec![mesh], lights, ..Scene::default() };
        same_both_ways(&lone, &opts).map_err(TestCaseError::fail)?;
    }
}

#[test]
fn every_example_scene_is_the_same_with_any_thread_count() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes");
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let scene = Scene::load(&path).unwrap();
        for &glyphs in GlyphMode::ALL {
            let opts = RenderOptions {
                cols: 40,
                rows: 14,
                glyphs,
                turn: Vec3::new(10.0, 35.0, 5.0),
                ..RenderOptions::default()
            };
            same_with_any_thread_count(&scene, &opts)
                .unwrap_or_else(|e| panic!("{} {glyphs:?}: {e}", path.display()));
        }
    }
}

#[test]
fn threads_are_planned_from_the_frame_and_the_options() {
    let scene = rastty::scene::default_scene();
    let bands = |opts: RenderOptions| {
        let mut r = Renderer::new();
        r.render(&scene, &opts);
        r.plan().unwrap().bands
    };
    let big = RenderOptions {
        cols: 600,
        rows: 180,
        ..RenderOptions::default()
    };
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get()) as u16;
    let auto = bands(big);
    if cfg!(feature = "parallel") {
        assert_eq!(auto.count, cores.min(rastty::MAX_THREADS), "{}", auto.why);
    } else {
        assert_eq!(auto.count, 1, "{}", auto.why);
    }
    // One column short of 600×180: one thread.
    let small = RenderOptions { cols: 599, ..big };
    assert_eq!(bands(small).count, 1);
    // As many as asked for, at most one a cell row.
    let exactly = |n| RenderOptions {
        threads: Threads::Exactly(n),
        rows: 5,
        ..small
    };
    assert_eq!(bands(exactly(3)).count, 3);
    assert_eq!(bands(exactly(64)).count, 5);
    // What only one thread can draw.
    for opts in [
        RenderOptions {
            aa: Aa::X4,
            ..exactly(3)
        },
        RenderOptions {
            aa: Aa::Exact,
            ..exactly(3)
        },
        RenderOptions {
            precision: rastty::raster::Precision::F32,
            ..exactly(3)
        },
        RenderOptions {
            traversal: rastty::raster::Traversal::Scan,
            ..exactly(3)
        },
    ] {
        let b = bands(opts);
        assert_eq!(b.count, 1, "{opts:?}");
        assert!(!b.why.is_empty());
    }
    // An empty frame is drawn by one thread; one taller than MAX_CELLS
    // is refused, not cut.
    let empty = RenderOptions {
        cols: 0,
        rows: 5,
        ..exactly(3)
    };
    assert_eq!(bands(empty).count, 1);
    let tall = RenderOptions {
        cols: 1,
        rows: 30_000,
        glyphs: GlyphMode::Sextant,
        ..exactly(3)
    };
    assert_eq!(
        Renderer::new()
            .try_render(&scene, &tall)
            .unwrap_err()
            .to_string(),
        "a frame of 1×30000 cells: each side may be at most 4096 cells"
    );
    assert_eq!("auto".parse::<Threads>(), Ok(Threads::Auto));
    assert_eq!("7".parse::<Threads>(), Ok(Threads::Exactly(7)));
    for bad in ["0", "65", "-1", "two", ""] {
        assert!(bad.parse::<Threads>().is_err(), "{bad}");
    }
}

#[test]
fn a_shallow_dent_far_from_the_origin_keeps_the_depth_test() {
    // The case: a cube whose top corner is pushed in by a
    // thousandth, its positions a million units out. Not convex: the
    // depth test runs, and the frame is the full pipeline's.
    let mut m = Shape::Cube.mesh(Rgb::WHITE);
    let corner = Vec3::splat(0.6);
    let offset = Vec3::new(1e6, 0.0, 0.0);
    let g = m.geometry_mut();
    for p in &mut g.positions {
        if *p == corner {
            *p *= 0.999;
        }
        *p += offset;
    }
    g.analyze();
    assert!(m.closed && !m.is_convex());
    m.model = glam::Mat4::from_translation(-offset);
    let scene = Scene {
        meshes: vec![m],
        lights: vec![Light::default()],
        ..Scene::default()
    };
    let opts = RenderOptions {
        cols: 40,
        rows: 14,
        turn: Vec3::new(30.0, 40.0, 0.0),
        ..RenderOptions::default()
    };
    same_both_ways(&scene, &opts).unwrap();
    let mut r = Renderer::new();
    r.render(&scene, &opts);
    assert!(r.plan().unwrap()[Effect::Depth].run);
    // The same cube undented is convex, however far out.
    let mut cube = Shape::Cube.mesh(Rgb::WHITE);
    let g = cube.geometry_mut();
    g.positions.iter_mut().for_each(|p| *p += offset);
    g.analyze();
    assert!(cube.is_convex());
}

fn example(name: &str) -> Scene {
    Scene::load(Path::new(&format!(
        "{}/examples/scenes/{name}.toml",
        env!("CARGO_MANIFEST_DIR")
    )))
    .unwrap()
}

#[test]
fn every_example_scene_is_the_same_planned_or_full() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes");
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let scene = Scene::load(&path).unwrap();
        for &glyphs in GlyphMode::ALL {
            for turn in [Vec3::ZERO, Vec3::new(10.0, 35.0, 5.0)] {
                let opts = RenderOptions {
                    cols: 40,
                    rows: 14,
                    glyphs,
                    turn,
                    ..RenderOptions::default()
                };
                same_both_ways(&scene, &opts).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            }
        }
    }
}

/// The stages the plan skips report no work: depth tests, clip tests,
/// interpolated and perspective samples and lighting are counted by the
/// loops that do them (the vertex stage's paths, the fill stage's loops),
/// not from the plan's decisions, so a count of zero means no loop that
/// does the work ran.
#[test]
fn skipped_stages_do_no_work() {
    let opts = RenderOptions {
        cols: 40,
        rows: 14,
        ..RenderOptions::default()
    };
    // A flat 2D scene of one-colour triangles, inside the screen, unlit.
    let mut r = Renderer::new();
    r.render(&example("shared-edge"), &opts);
    let (s, p) = (*r.stats(), r.plan().unwrap().clone());
    assert!(
        !p[Effect::Depth].run
            && !p[Effect::Clip].run
            && !p[Effect::Interpolation].run
            && !p[Effect::Perspective].run
            && !p[Effect::Lighting].run
    );
    assert_eq!(
        (
            s.depth_tests,
            s.clip_tests,
            s.interpolated_samples,
            s.perspective_samples,
            s.lighting_evaluations
        ),
        (0, 0, 0, 0, 0)
    );
    assert!(s.raster.samples_covered > 0);
    // The same scene through the full pipeline does that work.
    r.render(
        &example("shared-edge"),
        &RenderOptions {
            pipeline: Pipeline::Full,
            ..opts
        },
    );
    let f = *r.stats();
    assert!(
        f.depth_tests > 0
            && f.clip_tests > 0
            && f.interpolated_samples > 0
            && f.perspective_samples > 0
    );

    // One convex mesh, culled: the depth test still runs (snapped, a nearly
    // edge-on front face can fold over its neighbour); inside the view: no
    // clip test.
    let cube = Scene::of_model(Path::new("cube")).unwrap();
    r.render(
        &cube,
        &RenderOptions {
            shading: Shading::Flat,
            ..opts
        },
    );
    let (s, p) = (*r.stats(), r.plan().unwrap().clone());
    assert!(
        p[Effect::Depth].run
            && !p[Effect::Clip].run
            && !p[Effect::Interpolation].run
            && p[Effect::Lighting].run
    );
    assert_eq!((s.clip_tests, s.interpolated_samples), (0, 0));
    assert!(s.depth_tests > 0);
    assert!(s.lighting_evaluations > 0);

    // The torus is not convex: depth runs; smooth shading interpolates.
    r.render(&rastty::scene::default_scene(), &opts);
    let (s, p) = (*r.stats(), r.plan().unwrap().clone());
    assert!(p[Effect::Depth].run && p[Effect::Interpolation].run && p[Effect::Perspective].run);
    assert!(s.depth_tests > 0 && s.perspective_samples > 0);

    // Orthographic: interpolation without 1/w.
    let mut ortho = rastty::scene::default_scene();
    ortho.camera.projection = Projection::Orthographic {
        height: 3.0,
        near: 0.1,
        far: 50.0,
    };
    r.render(&ortho, &opts);
    let (s, p) = (*r.stats(), r.plan().unwrap().clone());
    assert!(p[Effect::Interpolation].run && !p[Effect::Perspective].run);
    assert!(s.interpolated_samples > 0);
    assert_eq!(s.perspective_samples, 0);

    // The near-plane scene reaches the near plane: clip tests run.
    r.render(&example("near-plane"), &opts);
    assert!(r.plan().unwrap()[Effect::Clip].run && r.stats().clip_tests > 0);
}

/// Triangles small on screen, most of whose boxes hold no sample centre,
/// take the plan's lean path, draw the full pipeline's frame (which sets
/// every triangle up) and count its samples; each face is counted once,
/// those told empty from their keys as found empty, not set up or culled;
/// the same for a textured mesh; and a scan, which tests every sample,
/// takes the general path and counts exactly as the full pipeline.
#[test]
fn small_triangles_take_the_lean_path_and_every_face_and_sample_is_counted_once() {
    let sphere = Scene::of_mesh(Shape::Sphere.mesh(Rgb::WHITE));
    #[cfg_attr(not(feature = "gltf"), allow(unused_mut))]
    let mut cases = vec![
        (sphere.clone(), 12, 4, Traversal::Incremental, true),
        (sphere.clone(), 30, 10, Traversal::Incremental, true),
        (sphere.clone(), 120, 40, Traversal::Incremental, true),
        (sphere, 12, 4, Traversal::Scan, false),
    ];
    #[cfg(feature = "gltf")]
    {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/models/crate.glb");
        let textured = Scene::of_model(&path).unwrap();
        assert!(textured.meshes.iter().all(|m| m.textured()));
        cases.push((textured.clone(), 6, 2, Traversal::Incremental, true));
        cases.push((textured, 40, 12, Traversal::Incremental, true));
    }
    for (scene, cols, rows, traversal, lean) in &cases {
        let (scene, cols, rows, traversal, lean) = (scene, *cols, *rows, *traversal, *lean);
        let opts = RenderOptions {
            cols,
            rows,
            traversal,
            turn: Vec3::new(10.0, 35.0, 5.0),
            ..RenderOptions::default()
        };
        let mut planned = Renderer::new();
        planned.render(scene, &opts);
        assert_eq!(
            planned.plan().unwrap()[Effect::Lean].run,
            lean,
            "{cols}×{rows}"
        );
        let mut full = Renderer::new();
        full.render(
            scene,
            &RenderOptions {
                pipeline: Pipeline::Full,
                ..opts
            },
        );
        assert!(!full.plan().unwrap()[Effect::Lean].run);
        assert_eq!(
            planned.framebuffer().samples(),
            full.framebuffer().samples()
        );
        assert_eq!(planned.frame(), full.frame());
        let (p, f) = (planned.stats(), full.stats());
        if lean {
            // The lean path tells a face whose box holds no sample centre
            // before its winding and area: every face is counted once, in
            // one place, and every sample as the set-up counts it.
            let (p, f) = (p.raster, f.raster);
            let faces = |r: &rastty::raster::RasterStats| {
                r.triangles_drawn
                    + r.found_empty
                    + r.culled
                    + r.dropped_degenerate
                    + r.dropped_non_finite
                    + r.dropped_out_of_range
            };
            assert_eq!(faces(&p), faces(&f), "{cols}×{rows}");
            assert_eq!(f.found_empty, 0);
            assert!(p.triangles_drawn <= f.triangles_drawn && p.culled <= f.culled);
            assert_eq!(
                (p.samples_tested, p.samples_covered),
                (f.samples_tested, f.samples_covered)
            );
        } else {
            assert_eq!(p.raster, f.raster, "{cols}×{rows}");
        }
        assert_eq!(p.triangles_in, f.triangles_in);
        assert!(p.raster.triangles_drawn > 0 && p.raster.samples_covered > 0);
    }
}

#[test]
fn every_declared_effect_runs_in_its_witness_and_changes_no_frame() {
    // Each effect names a scene in which it runs (`Effect::witness`):
    // there the planned frame is the full pipeline's, sample for sample,
    // the decision is to run it, and its counter, where it has one, counts
    // work.
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    for &e in Effect::ALL {
        let (what, opts) = e.witness();
        if (what.ends_with(".glb") || what.ends_with(".gltf")) && !cfg!(feature = "gltf") {
            continue;
        }
        let path = if what.contains('/') {
            root.join(what)
        } else {
            std::path::PathBuf::from(what)
        };
        let scene = Scene::open(&path).unwrap_or_else(|err| panic!("{}: {err}", e.name()));
        let mut planned = Renderer::new();
        let frame = planned.render(&scene, &opts).clone();
        let plan = planned.plan().unwrap();
        assert!(plan[e].run, "{}: {}", e.name(), plan[e].why);
        if let Some(work) = e.counter(planned.stats()) {
            assert!(work > 0, "{}: no work counted", e.name());
        }
        let full_opts = RenderOptions {
            pipeline: rastty::Pipeline::Full,
            ..opts
        };
        let mut full = Renderer::new();
        let full_frame = full.render(&scene, &full_opts).clone();
        assert_eq!(
            planned.framebuffer().samples(),
            full.framebuffer().samples(),
            "{}: the samples",
            e.name()
        );
        assert_eq!(frame, full_frame, "{}", e.name());
    }
}
