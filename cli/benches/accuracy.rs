//! The accuracy knobs of `rastty bench`, under criterion, for tracking
//! regressions: a frame of the bunny at 200×60 cells with each coverage,
//! interpolation, two-colour and precision setting, and a frame's encoding
//! with each colour depth and metric. (Traversals: the library's `benches/raster.rs`.)
//!
//! `cargo bench --bench accuracy`

use std::path::Path;

#[allow(dead_code, unused_imports)]
#[path = "../src/bench/mod.rs"]
mod bench;

use criterion::{Criterion, criterion_group, criterion_main};
use rastty::Choice;
use rastty::Split;
use rastty::color::Metric;
use rastty::encode::Encoder;
use rastty::raster::Precision;
use rastty::{Aa, Interpolation};
use rastty::{GlyphMode, RenderOptions, Renderer, color::ColorDepth, scene::Scene};

fn knobs(c: &mut Criterion) {
    let scene = Scene::of_model(Path::new(&format!(
        "{}/../tests/models/bunny.obj",
        env!("CARGO_MANIFEST_DIR")
    )))
    .unwrap();
    let base = bench::base();
    let mut group = c.benchmark_group("accuracy");
    let mut frame = |name: String, opts: RenderOptions| {
        let mut r = Renderer::new();
        group.bench_function(name, |b| b.iter(|| r.render(&scene, &opts).cols()));
    };
    for glyphs in bench::COVERAGE_MODES {
        for &aa in Aa::ALL {
            frame(
                format!("coverage/{glyphs:?}/{aa:?}"),
                RenderOptions { glyphs, aa, ..base },
            );
        }
    }
    for interpolation in [Interpolation::Affine, Interpolation::Perspective] {
        frame(
            format!("interpolation/{interpolation:?}"),
            RenderOptions {
                interpolation,
                ..base
            },
        );
    }
    for split in [Split::WidestChannel, Split::Exhaustive] {
        frame(
            format!("split/{split:?}"),
            RenderOptions {
                glyphs: GlyphMode::Octant,
                split,
                ..base
            },
        );
    }
    for &precision in Precision::ALL {
        frame(
            format!("precision/{}", precision.name()),
            RenderOptions { precision, ..base },
        );
    }
    let rendered = rastty::render(&scene, &base);
    for depth in [ColorDepth::Ansi256, ColorDepth::Ansi16] {
        for metric in [Metric::Rgb, Metric::Oklab] {
            group.bench_function(format!("quantisation/{depth:?}/{metric:?}"), |b| {
                b.iter(|| {
                    let mut e = Encoder::new(depth).with_metric(metric);
                    e.prepare(&rendered);
                    e.last_bytes().len()
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, knobs);
criterion_main!(benches);
