//! `rastty bench`: every knob that trades accuracy for speed, measured on
//! the same scenes, as a Markdown table and an SVG plot of error against
//! time.
//!
//! Times are medians of several frames at 200×60 cells (rendering, or for
//! colour quantisation encoding), wall clock on this machine. Errors are
//! exact measures on fixed, seeded workloads:
//!
//! | knob | settings | error measures |
//! |---|---|---|
//! | coverage | samples per cell (1, 2, 4, 6, 8) × `--aa none, 4x, 16x`, and `--aa exact` | mean and largest absolute error of each cell's coverage against the analytic area (`src/accuracy.rs`), over random triangles |
//! | precision | unsnapped f32 and f64 edge functions, the exact i64 fixed point | cracks and double hits on random tilings of the screen |
//! | traversal | scan, bounding box, incremental, spans | samples that differ from spans, the default (must be 0) |
//! | interpolation | affine, perspective-correct | largest and mean colour error (0–255) against an f64 ray cast, on a floor running away from the eye |
//! | highlights | per vertex, per sample | largest and mean colour error (0–255) against the same specular lobe in f64 at the true sphere's normal, on a white metal sphere |
//! | environment | none, studio | largest and mean colour error (0–255) of a white metal sphere lit by the studio alone against the f64 integral of the studio through the same lobe at the true sphere's normal; time on the metals example |
//! | effects | planned, full pipeline | samples unlike the planned frame (must be 0): the time column is what drawing highlights, masks, blends, glow and textures on runs whose materials have none would cost, and what the planner saves |
//! | texture filtering | nearest, bilinear, trilinear | largest and mean colour error (0–255) against an f64 reference supersampled 16×16 per sample, on a textured floor running away from the eye |
//! | two-colour cells | exhaustive split, widest-channel split | mean RMS colour error (0–255) of a cell's samples against the two colours drawn |
//! | palette matching | 256 and 16 colours, nearest in RGB, OKLab or OKLCh | mean OKLab distance to the colour sent; greys sent to a colour; hues moved over 45° |
//! | dithering | 256 and 16 colours, none or ordered | OKLab error of 2×2-cell areas against truecolor; bytes of a first and a next frame |

mod colour;
mod coverage;
mod raster;
mod report;
mod texture;

use colour::*;
use coverage::*;
use raster::*;
use texture::*;

use rastty::Choice;
use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::path::Path;
use std::time::{Duration, Instant};

use glam::Vec3;

use rastty::Renderer;
use rastty::accuracy::{Poly, area_in_rect};
use rastty::color::{self, ColorDepth, Dither, Ink, Lin, Metric, Palette, Rgb};
use rastty::encode::{Encoder, TermCell};
use rastty::raster::{Precision, Traversal};
use rastty::scene::{Camera, Projection, Scene, Triangle, TriangleColor};
use rastty::texture::FilterMode;
use rastty::transform::Grid;
use rastty::{Aa, Highlights, Interpolation, Pipeline, RenderOptions};
use rastty::{GlyphMode, Split};

/// A scene to time, and whether it turns from frame to frame.
pub struct Workload {
    /// What the table calls it.
    pub name: String,
    /// What is drawn.
    pub scene: Scene,
}

/// One knob setting: its time per frame on each workload and its errors.
pub struct Row {
    /// The knob's name.
    pub knob: &'static str,
    /// Its setting.
    pub setting: String,
    /// Median time per frame, one per workload.
    pub times: Vec<Duration>,
    /// Each error measure's name and value.
    pub errors: Vec<(&'static str, f64)>,
}

/// Everything `rastty bench` measured.
pub struct Report {
    /// The workloads' names, in the order of each row's times.
    pub workloads: Vec<String>,
    /// One row per knob setting.
    pub rows: Vec<Row>,
}

/// The built-in scenes, and the models found in `models` (any of bunny,
/// teapot, fox, shiba-inu, linux-mascot-tux), with a note for each model
/// that could not be read.
pub fn workloads(models: &Path) -> (Vec<Workload>, Vec<String>) {
    let mut notes = Vec::new();
    let mut w = vec![
        Workload {
            name: "torus (built-in)".into(),
            scene: rastty::scene::default_scene(),
        },
        Workload {
            name: "tiles (2D)".into(),
            scene: Scene::parse(
                include_str!("../../../examples/scenes/tiles.toml"),
                "tiles.toml",
            )
            .expect("tiles parse"),
        },
        Workload {
            name: "textured floor".into(),
            scene: textured_floor(),
        },
    ];
    // The metals example, carried in the program: metals lit by the
    // environment.
    #[cfg(feature = "gltf")]
    match rastty::scene::gltf::parse(
        include_bytes!("../../../examples/models/metals.glb"),
        None,
        "metals.glb",
        &Default::default(),
    ) {
        Ok(loaded) => w.push(Workload {
            name: "metals".into(),
            scene: Scene::of_mesh(rastty::scene::Mesh::of(
                std::sync::Arc::new(loaded.geometry),
                rastty::color::Rgb::WHITE,
            )),
        }),
        Err(e) => notes.push(format!("left out: {e}")),
    }
    for file in [
        "bunny.obj",
        "teapot.obj",
        "fox.obj",
        "shiba-inu.obj",
        "linux-mascot-tux.obj",
    ] {
        match Scene::of_model(&models.join(file)) {
            Ok(scene) => w.push(Workload {
                name: file.trim_end_matches(".obj").into(),
                scene,
            }),
            Err(e) => notes.push(format!("left out: {e}")),
        }
    }
    (w, notes)
}

/// One glyph mode for each number of samples per cell: 1, 2, 4, 6, 8.
pub const COVERAGE_MODES: [GlyphMode; 5] = [
    GlyphMode::Block,
    GlyphMode::Half,
    GlyphMode::Quadrant,
    GlyphMode::Sextant,
    GlyphMode::Octant,
];

const COLS: u16 = 200;
const ROWS: u16 = 60;

/// The frame every knob is timed on: 200×60 cells, truecolor, the scene
/// turned a little.
pub fn base() -> RenderOptions {
    RenderOptions {
        cols: COLS,
        rows: ROWS,
        color: ColorDepth::TrueColor,
        turn: Vec3::new(15.0, 30.0, 0.0),
        ..RenderOptions::default()
    }
}

/// The median time of `reps` renders (after one to warm up).
fn render_time(scene: &Scene, opts: &RenderOptions, reps: usize) -> Duration {
    let mut r = Renderer::new();
    r.render(scene, opts);
    median((0..reps).map(|_| {
        let t = Instant::now();
        r.render(scene, opts);
        t.elapsed()
    }))
}

fn median(times: impl Iterator<Item = Duration>) -> Duration {
    let mut v: Vec<Duration> = times.collect();
    v.sort();
    v.get(v.len() / 2).copied().unwrap_or_default()
}

/// A small deterministic generator (xorshift), so every run measures the
/// same workload.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Runs every knob on every workload; `reps` frames per timing.
pub fn run(workloads: &[Workload], reps: usize) -> Report {
    let mut rows = Vec::new();
    let time_all = |opts: &RenderOptions| {
        workloads
            .iter()
            .map(|w| render_time(&w.scene, opts, reps))
            .collect::<Vec<_>>()
    };

    // 1. Coverage.
    let tris = random_triangles(COVERAGE_TRIANGLES, 40.0, 12.0);
    let settings = COVERAGE_MODES
        .iter()
        .flat_map(|&g| [Aa::None, Aa::X4, Aa::X16].map(|aa| (g, aa)))
        .chain([(GlyphMode::Half, Aa::Exact)]);
    for (glyphs, aa) in settings {
        let c = coverage_error(&tris, glyphs, aa);
        let (w, h) = glyphs.cell_size();
        rows.push(Row {
            knob: "coverage",
            setting: if aa == Aa::Exact {
                "exact area (aa exact)".into()
            } else {
                format!("{} samples/cell, aa {}", w * h, aa.name())
            },
            times: time_all(&RenderOptions {
                glyphs,
                aa,
                ..base()
            }),
            errors: vec![
                ("mean abs. error", c.mean),
                ("max abs. error", c.max),
                ("max abs. error, overlapping pairs", c.overlap_max),
            ],
        });
    }

    // 2. Precision.
    for &precision in Precision::ALL {
        let (cracks, doubles) = precision_errors(precision);
        rows.push(Row {
            knob: "precision",
            setting: precision.name().into(),
            times: time_all(&RenderOptions {
                precision,
                ..base()
            }),
            errors: vec![("cracks", cracks as f64), ("double hits", doubles as f64)],
        });
    }

    // 3. Traversal.
    for &traversal in Traversal::ALL {
        rows.push(Row {
            knob: "traversal",
            setting: traversal.name().into(),
            times: time_all(&RenderOptions {
                traversal,
                ..base()
            }),
            errors: vec![(
                "samples unlike spans (the default)",
                traversal_mismatch(workloads, traversal) as f64,
            )],
        });
    }

    // 4. Interpolation.
    for interpolation in [Interpolation::Affine, Interpolation::Perspective] {
        let (max, mean) = interpolation_error(interpolation);
        rows.push(Row {
            knob: "interpolation",
            setting: interpolation.name().into(),
            times: time_all(&RenderOptions {
                interpolation,
                ..base()
            }),
            errors: vec![("max colour error", max), ("mean colour error", mean)],
        });
    }

    // 4b. Highlights.
    for highlights in [Highlights::Vertex, Highlights::Sample] {
        let (max, mean) = highlight_error(highlights);
        rows.push(Row {
            knob: "highlights",
            setting: highlights.name().into(),
            times: time_all(&RenderOptions {
                highlights,
                ..base()
            }),
            errors: vec![("max colour error", max), ("mean colour error", mean)],
        });
    }

    // 4b'. The environment metals reflect: its time on the metals
    // example, its error on a white metal sphere against the f64 integral.
    for (setting, environment) in [
        (
            "none: metals lit by the lights alone",
            rastty::scene::environment::Environment::None,
        ),
        (
            "studio: the split sum, prefiltered",
            rastty::scene::environment::Environment::Studio,
        ),
    ] {
        let (max, mean) = environment_error(environment.clone());
        let times = workloads
            .iter()
            .map(|w| {
                let scene = Scene {
                    environment: environment.clone(),
                    ..w.scene.clone()
                };
                render_time(&scene, &base(), reps)
            })
            .collect();
        rows.push(Row {
            knob: "environment",
            setting: setting.into(),
            times,
            errors: vec![("max colour error", max), ("mean colour error", mean)],
        });
    }

    // 4c. Effects: what the planner saves by running each stage and effect
    // only where the scene calls for it (none of the workloads' materials
    // mask, blend or carry maps), and that skipping changes no sample.
    for pipeline in [Pipeline::Planned, Pipeline::Full] {
        rows.push(Row {
            knob: "effects",
            setting: match pipeline {
                Pipeline::Planned => "planned: each where a material calls for it".into(),
                Pipeline::Full => "full pipeline: every stage and effect on every run".into(),
            },
            times: time_all(&RenderOptions { pipeline, ..base() }),
            errors: vec![(
                "samples unlike the planned frame",
                samples_unlike(workloads, |o| RenderOptions { pipeline, ..o }) as f64,
            )],
        });
    }

    // 5. Texture filtering.
    for &filter in FilterMode::ALL {
        let (max, mean) = filter_error(filter);
        rows.push(Row {
            knob: "texture filtering",
            setting: filter.name().into(),
            times: time_all(&RenderOptions {
                filter: Some(filter),
                ..base()
            }),
            errors: vec![("max colour error", max), ("mean colour error", mean)],
        });
    }

    // 6. Two-colour cells.
    for split in [Split::WidestChannel, Split::Exhaustive] {
        rows.push(Row {
            knob: "two-colour cells",
            setting: split.name().into(),
            times: time_all(&RenderOptions {
                glyphs: GlyphMode::Octant,
                split,
                ..base()
            }),
            errors: vec![("mean RMS error per cell", split_error(workloads, split))],
        });
    }

    // 7. Palette matching.
    for depth in [ColorDepth::Ansi256, ColorDepth::Ansi16] {
        for &metric in Metric::ALL {
            let q = matching_error(depth, metric);
            let palette = Palette {
                depth,
                metric,
                dither: Dither::None,
            };
            rows.push(Row {
                knob: "palette matching",
                setting: format!("{} colours, nearest in {}", depth.name(), metric.name()),
                times: encode_times(workloads, palette, reps),
                errors: vec![
                    ("mean OKLab distance", q.mean),
                    ("greys sent to a colour (%)", q.greys_coloured),
                    ("hues moved over 45° (%)", q.hues_moved),
                ],
            });
        }
    }

    // 8. Dithering.
    for depth in [ColorDepth::Ansi256, ColorDepth::Ansi16] {
        for dither in [Dither::None, Dither::Ordered] {
            let palette = Palette {
                depth,
                metric: Metric::Oklch,
                dither,
            };
            let d = dither_cost(workloads, palette);
            rows.push(Row {
                knob: "dithering",
                setting: format!("{} colours, {}", depth.name(), dither.name()),
                times: encode_times(workloads, palette, reps),
                errors: vec![
                    ("mean OKLab error of 2×2-cell areas", d.error),
                    ("bytes, first frame", d.full_bytes),
                    ("bytes, next frame (3° on)", d.next_bytes),
                ],
            });
        }
    }

    Report {
        workloads: workloads.iter().map(|w| w.name.clone()).collect(),
        rows,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn more_samples_measure_coverage_better_and_exact_is_exact_until_triangles_overlap() {
        let tris = random_triangles(40, 40.0, 12.0);
        let one = coverage_error(&tris, GlyphMode::Block, Aa::None);
        let sixteen = coverage_error(&tris, GlyphMode::Block, Aa::X16);
        let octant16 = coverage_error(&tris, GlyphMode::Octant, Aa::X16);
        assert!(
            one.mean > sixteen.mean && sixteen.mean > octant16.mean,
            "{one:?} {sixteen:?} {octant16:?}"
        );
        assert!(octant16.max <= 1.0 && one.max <= 1.0);
        // The exact mode, through the renderer: exact but for f32 sums,
        // alone; wrong where triangles overlap (it adds their areas).
        let exact = coverage_error(&tris, GlyphMode::Half, Aa::Exact);
        assert!(exact.max < 1e-5, "{exact:?}");
        assert!(exact.overlap_max > 0.1, "{exact:?}");
        // Sub-samples count a covered sample once, overlaps or not.
        assert!(sixteen.overlap_max < 0.3, "{sixteen:?}");
    }

    #[test]
    fn only_the_fixed_point_rasterizer_is_watertight() {
        assert_eq!(precision_errors(Precision::Fixed), (0, 0));
        let (cracks, doubles) = precision_errors(Precision::F32);
        assert!(
            cracks > 0 && doubles > 0,
            "f32: {cracks} cracks, {doubles} double hits"
        );
    }

    #[test]
    fn the_split_error_is_measured_through_the_blitter() {
        let w = vec![Workload {
            name: "torus".into(),
            scene: rastty::scene::default_scene(),
        }];
        let exhaustive = split_error(&w, Split::Exhaustive);
        let widest = split_error(&w, Split::WidestChannel);
        assert!(
            exhaustive > 0.0 && exhaustive < widest,
            "{exhaustive} {widest}"
        );
    }

    #[test]
    fn affine_interpolation_is_visibly_wrong_and_perspective_is_not() {
        let (affine, _) = interpolation_error(Interpolation::Affine);
        let (perspective, _) = interpolation_error(Interpolation::Perspective);
        assert!(perspective <= 2.0, "{perspective}");
        assert!(affine > 40.0, "{affine}");
    }

    #[test]
    fn the_full_pipeline_draws_every_sample_the_planner_draws() {
        // The textured floor found a difference once: a one-colour triangle
        // interpolated (as the full pipeline does) to a hair under its
        // colour, times a white texel, rounded down a step.
        let w = vec![Workload {
            name: "textured floor".into(),
            scene: textured_floor(),
        }];
        let full = |o| RenderOptions {
            pipeline: Pipeline::Full,
            ..o
        };
        assert_eq!(samples_unlike(&w, full), 0);
        // The measure sees a change: affine interpolation moves samples.
        let affine = |o| RenderOptions {
            interpolation: Interpolation::Affine,
            ..o
        };
        assert!(samples_unlike(&w, affine) > 0);
    }

    #[test]
    fn highlights_found_per_sample_err_less_than_per_vertex() {
        let (vertex, vertex_mean) = highlight_error(Highlights::Vertex);
        let (sample, sample_mean) = highlight_error(Highlights::Sample);
        assert!(
            sample < vertex && sample_mean < vertex_mean / 2.0,
            "{sample} {vertex}"
        );
        assert!(sample <= 2.0, "{sample}");
    }

    #[test]
    fn trilinear_filtering_errs_least_on_the_receding_floor() {
        let [nearest, bilinear, trilinear]: [_; 3] =
            std::array::from_fn(|i| filter_error(FilterMode::ALL[i]));
        assert!(trilinear.1 < bilinear.1 && bilinear.1 < nearest.1);
        assert!(trilinear.1 < nearest.1 / 2.0);
    }

    #[test]
    fn oklch_keeps_greys_grey_and_hues_in_their_family() {
        for depth in [ColorDepth::Ansi256, ColorDepth::Ansi16] {
            let rgb = matching_error(depth, Metric::Rgb);
            let lab = matching_error(depth, Metric::Oklab);
            let lch = matching_error(depth, Metric::Oklch);
            assert!(lab.mean < rgb.mean, "{depth:?}");
            assert_eq!(lch.greys_coloured, 0.0, "{depth:?}");
            assert!(
                lch.hues_moved < lab.hues_moved,
                "{depth:?}: {} vs {}",
                lch.hues_moved,
                lab.hues_moved
            );
        }
        // In 16 colours plain OKLab sends greys to colours.
        assert!(matching_error(ColorDepth::Ansi16, Metric::Oklab).greys_coloured > 0.0);
    }

    #[test]
    fn perspective_correct_colours_match_f64_and_differ_from_affine() {
        // A floor from 1 to 8 units in front of the eye (w differs eightfold),
        // red near and blue far; every drawn sample against the floor point
        // behind it, found by casting the ray in f64 (the measure of the
        // table).
        let (max, mean) = interpolation_error(rastty::Interpolation::Perspective);
        assert!(
            max <= 2.0 && mean <= 0.5,
            "perspective-correct: max {max}, mean {mean}"
        );
        let (affine_max, affine_mean) = interpolation_error(rastty::Interpolation::Affine);
        assert!(
            affine_max > 100.0 && affine_mean > 40.0,
            "affine: max {affine_max}, mean {affine_mean}"
        );
    }
}
