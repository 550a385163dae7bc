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

thread_local! {
    // The largest block this thread has asked for, since last reset.
    static LARGEST: Cell<usize> = const { Cell::new(0) };
}

fn count_size(size: usize) {
    LARGEST.with(|l| l.set(l.get().max(size)));
    count();
}

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
        count_size(layout.size());
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count_size(new_size);
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

/// The largest block this thread asks for while `f` runs.
fn largest_block(f: impl FnOnce()) -> usize {
    LARGEST.with(|l| l.set(0));
    f();
    LARGEST.with(Cell::get)
}

#[test]
fn every_size_at_and_past_each_budget_is_an_error_never_an_abort() {
    let scene = Scene::of_mesh(Shape::Cube.mesh(Rgb::WHITE));
    let small = RenderOptions {
        max_samples: 200,
        max_triangles: 24,
        ..RenderOptions::default()
    };
    let sized = |cols, rows, glyphs| RenderOptions {
        cols,
        rows,
        glyphs,
        ..small
    };
    // At each budget: drawn.
    for opts in [
        sized(10, 10, GlyphMode::Half),  // 200 sample tests
        sized(25, 1, GlyphMode::Octant), // 200
        sized(4096, 1, GlyphMode::Ascii).with_samples(4096),
        sized(1, 4096, GlyphMode::Ascii).with_samples(4096),
    ] {
        let mut frame = Frame::default();
        Renderer::new()
            .try_render_into(&scene, &opts, &mut frame)
            .unwrap_or_else(|e| panic!("{opts:?}: {e}"));
        assert_eq!((frame.cols(), frame.rows()), (opts.cols, opts.rows));
        assert!(rastty::try_render(&scene, &opts).is_ok());
    }
    // Past it: an error, before anything the size of the frame is
    // allocated. 65535×65535 octants would be 34 GB of samples.
    let past = [
        (
            sized(10, 11, GlyphMode::Half),
            "a frame of 10×11 cells at 2 samples a cell and 1 pass(es) of --aa none is 220 sample tests, more than the budget of 200 (--max-samples raises it)",
        ),
        (
            sized(4097, 1, GlyphMode::Ascii).with_samples(u64::MAX),
            "a frame of 4097×1 cells: each side may be at most 4096 cells",
        ),
        (
            sized(1, 65535, GlyphMode::Half).with_samples(u64::MAX),
            "a frame of 1×65535 cells: each side may be at most 4096 cells",
        ),
        (
            sized(65535, 65535, GlyphMode::Octant).with_samples(u64::MAX),
            "a frame of 65535×65535 cells: each side may be at most 4096 cells",
        ),
        (
            RenderOptions {
                aa: Aa::X16,
                ..sized(4096, 4096, GlyphMode::Octant)
            }
            .with_samples((1 << 31) - 1),
            "a frame of 4096×4096 cells at 8 samples a cell and 16 pass(es) of --aa 16x is 2147483648 sample tests, more than the budget of 2147483647 (--max-samples raises it)",
        ),
        (
            RenderOptions {
                cell_aspect: f32::NAN,
                ..sized(2, 2, GlyphMode::Half)
            },
            "a cell aspect of NaN: it must be a finite number above 0",
        ),
        (
            RenderOptions {
                max_triangles: 23,
                ..sized(2, 2, GlyphMode::Half)
            },
            "the scene has 24 triangles (or vertices), more than the triangle budget of 23 (--max-triangles, RenderOptions::max_triangles, raises it)",
        ),
    ];
    for (opts, want) in past {
        let mut frame = Frame::default();
        let mut renderer = Renderer::new();
        let largest = largest_block(|| {
            let e = renderer
                .try_render_into(&scene, &opts, &mut frame)
                .unwrap_err();
            assert_eq!(e.to_string(), want, "{opts:?}");
            assert_eq!(
                renderer.try_render(&scene, &opts).unwrap_err().to_string(),
                want
            );
            assert_eq!(
                rastty::try_render(&scene, &opts).unwrap_err().to_string(),
                want
            );
        });
        assert!(largest < 1 << 16, "{largest} bytes for {opts:?}");
        // The forms without `try_` panic with the same words, not abort
        // (quietly: the hook says nothing for this thread meanwhile).
        let panicked = quietly(|| {
            let _ = rastty::render(&scene, &opts);
        });
        assert_eq!(
            panicked.downcast_ref::<String>().map(String::as_str),
            Some(want)
        );
    }
}

/// Options with a sample budget of `n`.
trait WithSamples {
    fn with_samples(self, n: u64) -> Self;
}

impl WithSamples for RenderOptions {
    fn with_samples(self, n: u64) -> Self {
        RenderOptions {
            max_samples: n,
            ..self
        }
    }
}

thread_local! {
    static QUIET: Cell<bool> = const { Cell::new(false) };
}

/// The payload of the panic `f` makes, the panic hook silent on this
/// thread while it runs (and as it was for every other thread).
fn quietly(f: impl FnOnce()) -> Box<dyn std::any::Any + Send> {
    static HOOK: std::sync::Once = std::sync::Once::new();
    HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !QUIET.with(Cell::get) {
                previous(info);
            }
        }));
    });
    QUIET.with(|q| q.set(true));
    let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(f));
    QUIET.with(|q| q.set(false));
    r.expect_err("it panics")
}
