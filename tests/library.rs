//! rastty as a library: frame after frame into the caller's memory, with no
//! allocation once the sizes are stable, counted by a global allocator that
//! counts this thread's allocations and those of rayon's threads (which
//! only a frame drawn in bands uses here).

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicU64, Ordering};

use rastty::glam::Vec3;
use rastty::scene::Shape;
use rastty::{
    Aa, Frame, GlyphMode, RenderOptions, Renderer, Shading, Threads, color::ColorDepth, color::Rgb,
    encode::Encoder, scene::Scene,
};

struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<u64> = const { Cell::new(0) };
}

/// Allocations made on rayon's threads.
static WORKER_ALLOCATIONS: AtomicU64 = AtomicU64::new(0);

fn count() {
    if rayon::current_thread_index().is_some() {
        WORKER_ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
    } else {
        ALLOCATIONS.with(|n| n.set(n.get() + 1));
    }
}

// SAFETY: every call is passed on to the system allocator unchanged; the
// counters are an atomic and a const-initialised thread local, and rayon's
// thread index is a const-initialised thread local too: none allocates.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations made on this thread while `f` runs.
fn allocations(f: impl FnOnce()) -> u64 {
    let before = ALLOCATIONS.with(Cell::get);
    f();
    ALLOCATIONS.with(Cell::get) - before
}

/// Allocations made on this thread and on rayon's while `f` runs (only the
/// test of bands uses rayon, so no other test's count can land here).
fn allocations_with_rayon(f: impl FnOnce()) -> u64 {
    let before = WORKER_ALLOCATIONS.load(Ordering::Relaxed);
    allocations(f) + WORKER_ALLOCATIONS.load(Ordering::Relaxed) - before
}

/// A cube with a 4×4 texture, its coordinates the positions' x and y.
fn textured_cube() -> rastty::scene::Mesh {
    use rastty::texture::{Sampler, Texture};
    let mut g = Shape::Cube.mesh(Rgb::WHITE).geometry.as_ref().clone();
    g.uvs = Some(g.positions.iter().map(|p| p.truncate() * 2.0).collect());
    let texels = (0..16).map(|i| [(i % 4) as f32 / 3.0, 0.5, (i / 4) as f32 / 3.0]);
    g.textures = vec![std::sync::Arc::new(Texture::from_linear(
        "t",
        4,
        4,
        texels.collect(),
        Sampler::default(),
    ))];
    g.materials = vec![rastty::scene::MaterialRun {
        first: 0,
        color: None,
        texture: Some(0),
        finish: Default::default(),
    }];
    rastty::scene::Mesh::of(std::sync::Arc::new(g), Rgb::new(0x40, 0x90, 0xff))
}

/// A shaded torus, a textured cube cut by the near plane (the clip path)
/// and a triangle with a colour at each vertex.
fn scene() -> Scene {
    Scene::builder()
        .look_at(Vec3::new(0.0, 0.5, 3.0), Vec3::ZERO)
        .mesh(Shape::Torus.mesh(Rgb::new(0xff, 0x90, 0x40)))
        .mesh(
            textured_cube().with_model(rastty::glam::Mat4::from_translation(Vec3::new(
                0.6, 0.0, 2.6,
            ))),
        )
        .triangle_colors(
            [
                Vec3::new(-2.0, -1.0, -1.0),
                Vec3::new(2.0, -1.0, -1.0),
                Vec3::new(0.0, 1.5, -1.0),
            ],
            [
                Rgb::new(255, 0, 0),
                Rgb::new(0, 255, 0),
                Rgb::new(0, 0, 255),
            ],
        )
        .light(rastty::scene::Light::default())
        .build()
        .unwrap()
}

fn settings() -> [(GlyphMode, Shading, Aa); 3] {
    [
        (GlyphMode::Half, Shading::Smooth, Aa::None),
        (GlyphMode::Octant, Shading::Flat, Aa::X4),
        (GlyphMode::Braille, Shading::Smooth, Aa::Exact),
    ]
}

#[test]
fn render_into_allocates_nothing_once_warmed() {
    let scene = scene();
    for (glyphs, shading, aa) in settings() {
        let opts = RenderOptions {
            cols: 100,
            rows: 30,
            glyphs,
            shading,
            aa,
            color: ColorDepth::TrueColor,
            ..Default::default()
        };
        let (mut renderer, mut frame) = (Renderer::new(), Frame::default());
        renderer.render_into(&scene, &opts, &mut frame);
        let (mut clipped, mut textured) = (0, 0);
        let n = allocations(|| {
            for k in 1..=8 {
                let opts = RenderOptions {
                    turn: Vec3::new(0.0, 7.0 * k as f32, 0.0),
                    ..opts
                };
                renderer.render_into(&scene, &opts, &mut frame);
                clipped += renderer.stats().clipped;
                textured += renderer.stats().textured_samples;
            }
        });
        assert_eq!(n, 0, "{glyphs:?} {shading:?} {aa:?}");
        // The frames went through the clip path and read the texture too.
        assert!(clipped > 0 && textured > 0, "{glyphs:?}");
    }
}

#[test]
fn a_frame_drawn_in_bands_allocates_only_rayons_queue_blocks_once_warmed() {
    let scene = scene();
    let opts = RenderOptions {
        cols: 100,
        rows: 30,
        color: ColorDepth::TrueColor,
        threads: Threads::Exactly(3),
        ..Default::default()
    };
    let (mut renderer, mut frame) = (Renderer::new(), Frame::default());
    renderer.render_into(&scene, &opts, &mut frame);
    assert_eq!(renderer.plan().unwrap().bands.count, 3);
    let mut clipped = 0;
    let n = allocations_with_rayon(|| {
        for k in 1..=630 {
            let opts = RenderOptions {
                turn: Vec3::new(0.0, 7.0 * k as f32, 0.0),
                ..opts
            };
            renderer.render_into(&scene, &opts, &mut frame);
            clipped += renderer.stats().clipped;
        }
    });
    // The renderer allocates nothing; rayon's queue for jobs sent from
    // outside its pool (one a frame) takes a new block of 63 slots every
    // 63 jobs.
    assert!(n <= 630 / 63 + 1, "{n} allocations in 630 frames");
    assert!(clipped > 0);
}

#[test]
fn render_into_draws_what_render_draws() {
    let scene = scene();
    let mut renderer = Renderer::new();
    let mut frame = Frame::new(3, 3);
    for (glyphs, shading, aa) in settings() {
        let opts = RenderOptions {
            cols: 64,
            rows: 20,
            glyphs,
            shading,
            aa,
            color: ColorDepth::TrueColor,
            ..Default::default()
        };
        renderer.render_into(&scene, &opts, &mut frame);
        assert_eq!(frame, rastty::render(&scene, &opts), "{glyphs:?}");
    }
}

#[test]
fn encoding_frame_after_frame_allocates_nothing_once_warmed() {
    let scene = scene();
    for depth in ColorDepth::ALL {
        let opts = RenderOptions {
            cols: 80,
            rows: 24,
            color: depth,
            ..Default::default()
        };
        let (mut renderer, mut frame) = (Renderer::new(), Frame::default());
        let mut encoder = Encoder::new(depth);
        let mut out = Vec::with_capacity(1 << 20);
        // Two turns seen: every colour of the later frames is cached.
        for yaw in [0.0, 3.0, 0.0, 3.0] {
            let opts = RenderOptions {
                turn: Vec3::new(0.0, yaw, 0.0),
                ..opts
            };
            renderer.render_into(&scene, &opts, &mut frame);
            encoder.encode(&frame, &mut out).unwrap();
        }
        let n = allocations(|| {
            for yaw in [0.0, 3.0, 0.0] {
                let opts = RenderOptions {
                    turn: Vec3::new(0.0, yaw, 0.0),
                    ..opts
                };
                renderer.render_into(&scene, &opts, &mut frame);
                out.clear();
                encoder.encode(&frame, &mut out).unwrap();
                assert!(!out.is_empty());
            }
        });
        assert_eq!(n, 0, "{depth:?}");
    }
}

#[cfg(feature = "ratatui")]
#[test]
fn the_stateful_widget_allocates_nothing_once_warmed() {
    use rastty::ratatui::{SceneState, SceneWidget};
    use ratatui_core::buffer::Buffer;
    use ratatui_core::layout::Rect;
    use ratatui_core::widgets::StatefulWidget;

    let scene = scene();
    for depth in [
        ColorDepth::TrueColor,
        ColorDepth::Ansi256,
        ColorDepth::Ansi16,
    ] {
        let opts = RenderOptions {
            color: depth,
            ..Default::default()
        };
        let mut state = SceneState::new();
        let mut buf = Buffer::empty(Rect::new(0, 0, 90, 28));
        let draw = |yaw: f32, buf: &mut Buffer, state: &mut SceneState| {
            let opts = RenderOptions {
                turn: Vec3::new(0.0, yaw, 0.0),
                ..opts
            };
            SceneWidget::new(&scene, &opts).render(buf.area, buf, state);
        };
        for yaw in [0.0, 4.0] {
            draw(yaw, &mut buf, &mut state);
        }
        let n = allocations(|| {
            for yaw in [0.0, 4.0, 0.0] {
                draw(yaw, &mut buf, &mut state);
            }
        });
        assert_eq!(n, 0, "{depth:?}");
    }
}
