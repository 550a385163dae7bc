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
//! | texture filtering | nearest, bilinear, trilinear | largest and mean colour error (0–255) against an f64 reference supersampled 16×16 per sample, on a textured floor running away from the eye |
//! | two-colour cells | exhaustive split, widest-channel split | mean RMS colour error (0–255) of a cell's samples against the two colours drawn |
//! | palette matching | 256 and 16 colours, nearest in RGB, OKLab or OKLCh | mean OKLab distance to the colour sent; greys sent to a colour; hues moved over 45° |
//! | dithering | 256 and 16 colours, none or ordered | OKLab error of 2×2-cell areas against truecolor; bytes of a first and a next frame |

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
use rastty::{Aa, Interpolation, RenderOptions};
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
                include_str!("../../examples/scenes/tiles.toml"),
                "tiles.toml",
            )
            .expect("tiles parse"),
        },
        Workload {
            name: "textured floor".into(),
            scene: textured_floor(),
        },
    ];
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

/// Random triangles over a `w × h` cell area, a third each small (about a
/// cell), medium and large.
fn random_triangles(n: usize, w: f64, h: f64) -> Vec<[[f64; 2]; 3]> {
    let mut rng = Rng(0x2545_F491_4F6C_DD1D);
    (0..n)
        .map(|i| {
            let size = [1.5, 6.0, 25.0][i % 3];
            let (cx, cy) = (rng.next() * w, rng.next() * h);
            std::array::from_fn(|_| {
                [
                    cx + (rng.next() - 0.5) * size,
                    cy + (rng.next() - 0.5) * size * 0.5,
                ]
            })
        })
        .collect()
}

/// How many random triangles the coverage knob is measured on.
const COVERAGE_TRIANGLES: usize = 300;

/// The coverage knob's error measures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CoverageError {
    /// Mean and largest absolute error of a cell's coverage, each triangle
    /// alone.
    pub mean: f64,
    /// Largest absolute error of a cell's coverage, each triangle alone.
    pub max: f64,
    /// Largest error where two triangles overlap (the union's coverage):
    /// what `--aa exact`, which ignores depth, gets wrong.
    pub overlap_max: f64,
}

/// `tris` (in cells, y up, on a 40×12-cell screen) rendered by the
/// renderer in `glyphs` with `aa`: every cell's coverage (the mean of its
/// samples' coverage as [`Renderer::coverage`] reports it) against the
/// exact area, each triangle alone, then overlapping a copy of itself moved
/// by a third of a cell, against the exact area of their union.
pub fn coverage_error(tris: &[[[f64; 2]; 3]], glyphs: GlyphMode, aa: Aa) -> CoverageError {
    let (cols, rows) = (40u16, 12u16);
    let opts = RenderOptions {
        cols,
        rows,
        glyphs,
        aa,
        color: ColorDepth::TrueColor,
        ..RenderOptions::default()
    };
    let (w, h) = glyphs.cell_size();
    let grid = glyphs.grid(cols, rows);
    let ndc = |t: &[[f64; 2]; 3]| {
        t.map(|[x, y]| {
            Vec3::new(
                (2.0 * x / cols as f64 - 1.0) as f32,
                (2.0 * y / rows as f64 - 1.0) as f32,
                0.0,
            )
        })
    };
    // What the renderer was given, back in cells (its f32 rounding is part
    // of the scene, not of the error).
    let cells = |v: [Vec3; 3]| {
        v.map(|p| {
            [
                (p.x as f64 + 1.0) * cols as f64 / 2.0,
                (p.y as f64 + 1.0) * rows as f64 / 2.0,
            ]
        })
    };
    let mut renderer = Renderer::new();
    let mut cov = Vec::new();
    let mut measure = |tris: &[[Vec3; 3]], exact: &dyn Fn([f64; 2], [f64; 2]) -> f64| {
        let scene = Scene::in_canonical_cube(
            tris.iter()
                .map(|&vertices| Triangle {
                    vertices,
                    color: TriangleColor::Flat(Rgb::WHITE),
                })
                .collect(),
        );
        renderer.render(&scene, &opts);
        renderer.coverage(&mut cov);
        let mut errors = Vec::new();
        for cy in 0..rows as u32 {
            for cx in 0..cols as u32 {
                let mut sum = 0.0;
                for y in cy * h..(cy + 1) * h {
                    for x in cx * w..(cx + 1) * w {
                        sum += cov[(y * grid.width + x) as usize] as f64;
                    }
                }
                let estimate = sum / (w * h) as f64;
                let want = exact([cx as f64, cy as f64], [cx as f64 + 1.0, cy as f64 + 1.0]);
                if want > 0.0 || estimate > 0.0 {
                    errors.push((estimate - want).abs());
                }
            }
        }
        errors
    };
    let (mut sum, mut n, mut max) = (0.0, 0usize, 0.0f64);
    for t in tris {
        let v = ndc(t);
        let c = cells(v);
        for e in measure(&[v], &|lo, hi| area_in_rect(c, lo, hi)) {
            sum += e;
            n += 1;
            max = max.max(e);
        }
    }
    let mut overlap_max = 0.0f64;
    for t in tris {
        // The triangle and itself moved by a third of a cell: they overlap
        // everywhere but along a thin band at their edges.
        let moved = t.map(|[x, y]| [x + 1.0 / 3.0, y + 0.25]);
        let (a, b) = (ndc(t), ndc(&moved));
        let (pa, pb) = (Poly::new(&cells(a)), Poly::new(&cells(b)));
        let both = pa.intersect(&pb);
        if both.area() == 0.0 {
            continue;
        }
        let union = |lo, hi| {
            pa.in_rect(lo, hi).area() + pb.in_rect(lo, hi).area() - both.in_rect(lo, hi).area()
        };
        for e in measure(&[a, b], &union) {
            overlap_max = overlap_max.max(e);
        }
    }
    CoverageError {
        mean: sum / n.max(1) as f64,
        max,
        overlap_max,
    }
}

/// Tilings of a 64×48-sample screen, each drawn by the renderer (as a
/// flat scene in the canonical cube, one sample a cell) with `precision`:
/// samples covered no times (cracks: left empty) and more than once (double
/// hits: the renderer's covered count beyond the samples drawn). Half are
/// jittered quad grids (vertices anywhere, either diagonal), where edges
/// seldom pass near a sample centre; half are fans around a sample centre
/// whose spokes run through further sample centres (their far ends, at
/// thirds of a sample, are not exact in binary): there the unsnapped edge
/// functions of two neighbours round differently.
pub fn precision_errors(precision: Precision) -> (u64, u64) {
    let (w, h) = (64u32, 48u32);
    let grid = Grid::new(w, h);
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let mut tilings = Vec::new();
    for _ in 0..10 {
        let (nx, ny) = (23usize, 17usize);
        let (sx, sy) = ((w as f64 + 6.0) / nx as f64, (h as f64 + 6.0) / ny as f64);
        let mut v = vec![[0.0f32; 2]; (nx + 1) * (ny + 1)];
        for j in 0..=ny {
            for i in 0..=nx {
                let inner = i > 0 && i < nx && j > 0 && j < ny;
                let (jx, jy) = if inner {
                    (
                        (rng.next() - 0.5) * 0.45 * sx,
                        (rng.next() - 0.5) * 0.45 * sy,
                    )
                } else {
                    (0.0, 0.0)
                };
                v[j * (nx + 1) + i] = [
                    (-3.0 + i as f64 * sx + jx) as f32,
                    (-3.0 + j as f64 * sy + jy) as f32,
                ];
            }
        }
        let mut tris = Vec::new();
        for j in 0..ny {
            for i in 0..nx {
                let at = |i: usize, j: usize| v[j * (nx + 1) + i];
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                if rng.next() < 0.5 {
                    tris.push([a, b, c]);
                    tris.push([a, c, d]);
                } else {
                    tris.push([a, b, d]);
                    tris.push([b, c, d]);
                }
            }
        }
        tilings.push(tris);
    }
    for k in 0..10u32 {
        let centre = [(20 + 2 * k) as f32 + 0.5, (14 + k) as f32 + 0.5];
        // Primitive directions (p, q), |p|, |q| ≤ 3, by angle.
        let mut dirs: Vec<(i32, i32)> = (-3..=3)
            .flat_map(|p| (-3..=3).map(move |q| (p, q)))
            .filter(|&(p, q): &(i32, i32)| {
                (p, q) != (0, 0) && gcd(p.unsigned_abs(), q.unsigned_abs()) == 1
            })
            .collect();
        dirs.sort_by(|a, b| {
            (a.1 as f64)
                .atan2(a.0 as f64)
                .total_cmp(&(b.1 as f64).atan2(b.0 as f64))
        });
        let s = (200 + k) as f32 / 3.0;
        let ends: Vec<[f32; 2]> = dirs
            .iter()
            .map(|&(p, q)| [centre[0] + s * p as f32, centre[1] + s * q as f32])
            .collect();
        tilings.push(
            (0..ends.len())
                .map(|i| [centre, ends[i], ends[(i + 1) % ends.len()]])
                .collect(),
        );
    }
    let opts = RenderOptions {
        cols: w as u16,
        rows: h as u16,
        glyphs: GlyphMode::Block,
        precision,
        ..RenderOptions::default()
    };
    let mut renderer = Renderer::new();
    let (mut cracks, mut doubles) = (0, 0);
    for tris in &tilings {
        let scene = Scene::in_canonical_cube(
            tris.iter()
                .map(|t| Triangle {
                    vertices: t.map(|[x, y]| {
                        Vec3::new(2.0 * x / w as f32 - 1.0, 2.0 * y / h as f32 - 1.0, 0.0)
                    }),
                    color: TriangleColor::Flat(Rgb::WHITE),
                })
                .collect(),
        );
        renderer.render(&scene, &opts);
        let drawn = renderer
            .framebuffer()
            .samples()
            .iter()
            .filter(|s| s.is_some())
            .count() as u64;
        cracks += grid.len() as u64 - drawn;
        doubles += renderer.stats().raster.samples_covered - drawn;
    }
    (cracks, doubles)
}

fn gcd(a: u32, b: u32) -> u32 {
    if b == 0 { a } else { gcd(b, a % b) }
}

/// Samples of every workload's frame drawn differently by `traversal` than
/// by the default one (spans).
fn traversal_mismatch(workloads: &[Workload], traversal: Traversal) -> u64 {
    let opts = RenderOptions {
        cols: 80,
        rows: 24,
        ..base()
    };
    workloads
        .iter()
        .map(|w| {
            let mut a = Renderer::new();
            let mut b = Renderer::new();
            a.render(&w.scene, &opts);
            b.render(&w.scene, &RenderOptions { traversal, ..opts });
            a.framebuffer()
                .samples()
                .iter()
                .zip(b.framebuffer().samples())
                .filter(|(x, y)| x != y)
                .count() as u64
        })
        .sum()
}

/// A floor from 1 to 8 units in front of the eye, red near, blue far:
/// every drawn sample's colour against the colour of the floor point behind
/// it, found by casting the ray in f64. Largest and mean error, 0–255 in
/// linear light (where colours are interpolated).
pub fn interpolation_error(interpolation: Interpolation) -> (f64, f64) {
    let near = Vec3::new(0.0, -1.0, -1.0);
    let far = Vec3::new(0.0, -1.0, -8.0);
    let camera = Camera {
        projection: Projection::Perspective {
            fov_y: 90.0,
            near: 0.5,
            far: 20.0,
        },
        eye: Vec3::ZERO,
        target: Vec3::new(0.0, 0.0, -1.0),
        up: Vec3::Y,
        fit: None,
    };
    let (l, r) = (Vec3::X * 3.0, Vec3::X * -3.0);
    let (red, blue) = (Rgb::new(255, 0, 0), Rgb::new(0, 0, 255));
    let scene = Scene {
        camera,
        triangles: vec![
            Triangle {
                vertices: [near + r, near + l, far + l],
                color: TriangleColor::PerVertex([red, red, blue]),
            },
            Triangle {
                vertices: [near + r, far + l, far + r],
                color: TriangleColor::PerVertex([red, blue, blue]),
            },
        ],
        ..Scene::default()
    };
    let opts = RenderOptions {
        cols: 64,
        rows: 32,
        glyphs: GlyphMode::Block,
        interpolation,
        cell_aspect: 1.0,
        ..RenderOptions::default()
    };
    let mut renderer = Renderer::new();
    renderer.render(&scene, &opts);
    let fb = renderer.framebuffer();
    let grid = fb.grid();
    let inv = camera.view_projection(opts.aspect()).as_dmat4().inverse();
    let (mut max, mut sum, mut n) = (0.0f64, 0.0, 0);
    for y in 0..grid.height {
        for x in 0..grid.width {
            let Some(c) = fb.get(x, y) else { continue };
            let ndc = |v: u32, n: u32| (v as f64 + 0.5) / n as f64 * 2.0 - 1.0;
            let p0 = inv.project_point3(glam::DVec3::new(
                ndc(x, grid.width),
                ndc(y, grid.height),
                1.0,
            ));
            let p1 = inv.project_point3(glam::DVec3::new(
                ndc(x, grid.width),
                ndc(y, grid.height),
                -1.0,
            ));
            let t = (-1.0 - p0.y) / (p1.y - p0.y);
            let s = ((p0.z + t * (p1.z - p0.z)) + 1.0) / -7.0;
            // Colours interpolate in linear light: compared there, in
            // 0–255 units.
            let want = [255.0 * (1.0 - s), 0.0, 255.0 * s];
            let got = c.to_f32().map(|v| v / 257.0);
            let e = (0..3)
                .map(|k| (got[k] as f64 - want[k]).abs())
                .fold(0.0, f64::max);
            max = max.max(e);
            sum += e;
            n += 1;
        }
    }
    (max, sum / n.max(1) as f64)
}

/// The textured floor's checkerboard: 32×32 texels, squares of 8, light
/// grey and blue; texel `(i, j)`'s linear colour.
fn checker(i: u32, j: u32) -> [f32; 3] {
    let light = (i / 8 + j / 8).is_multiple_of(2);
    let c = if light {
        [230, 230, 230]
    } else {
        [40, 70, 160]
    };
    Lin::from_srgb(Rgb(c)).to_f32().map(|v| v / 65535.0)
}

/// The textured floor's extent in x and z, and its texture coordinates
/// there (8 repeats across, 40 deep: squares half a unit on a side).
const FLOOR_X: f64 = 8.0;
const FLOOR_Z: [f64; 2] = [-1.0, -81.0];
fn floor_uv(x: f64, z: f64) -> [f64; 2] {
    [(x + FLOOR_X) / 2.0, (FLOOR_Z[0] - z) / 2.0]
}

/// A checkerboard floor at y = −1 from 1 to 81 units in front of the eye,
/// seen from the origin with the horizon in view: near the eye a texel
/// covers several samples, far off a sample covers many texels.
pub fn textured_floor() -> Scene {
    use rastty::scene::{Geometry, MaterialRun, Mesh};
    use rastty::texture::{Sampler, Texture};
    use std::sync::Arc;
    let corners = [
        (-FLOOR_X, FLOOR_Z[0]),
        (FLOOR_X, FLOOR_Z[0]),
        (FLOOR_X, FLOOR_Z[1]),
        (-FLOOR_X, FLOOR_Z[1]),
    ];
    let positions = corners
        .iter()
        .map(|&(x, z)| Vec3::new(x as f32, -1.0, z as f32))
        .collect();
    let mut g = Geometry::new("textured floor", positions, vec![[0, 1, 2], [0, 2, 3]]);
    g.uvs = Some(
        corners
            .iter()
            .map(|&(x, z)| glam::Vec2::from(floor_uv(x, z).map(|t| t as f32)))
            .collect(),
    );
    let texels = (0..32 * 32).map(|k| checker(k % 32, k / 32)).collect();
    g.textures = vec![Arc::new(Texture::from_linear(
        "checkerboard",
        32,
        32,
        texels,
        Sampler::default(),
    ))];
    g.materials = vec![MaterialRun {
        first: 0,
        color: None,
        texture: Some(0),
    }];
    Scene {
        camera: Camera {
            projection: Projection::Perspective {
                fov_y: 60.0,
                near: 0.5,
                far: 200.0,
            },
            eye: Vec3::ZERO,
            target: Vec3::new(0.0, -0.3, -1.0),
            up: Vec3::Y,
            fit: None,
        },
        meshes: vec![Mesh::of(Arc::new(g), Rgb::WHITE)],
        ..Scene::default()
    }
}

/// The textured floor drawn with `filter` on a 64×32 grid, each sample
/// against the mean of 16×16 rays cast through its square in f64, each
/// reading the texel it hits: the largest and mean colour error (0–255,
/// linear light) over the samples whose square lies wholly on the floor.
pub fn filter_error(filter: FilterMode) -> (f64, f64) {
    const SUB: u32 = 16;
    let scene = textured_floor();
    let opts = RenderOptions {
        cols: 64,
        rows: 32,
        glyphs: GlyphMode::Block,
        cell_aspect: 1.0,
        filter: Some(filter),
        ..RenderOptions::default()
    };
    let mut renderer = Renderer::new();
    renderer.render(&scene, &opts);
    let fb = renderer.framebuffer();
    let grid = fb.grid();
    let inv = scene.camera.view_projection64(opts.aspect()).inverse();
    let (mut max, mut sum, mut n) = (0.0f64, 0.0, 0);
    for y in 0..grid.height {
        'sample: for x in 0..grid.width {
            let Some(c) = fb.get(x, y) else { continue };
            let mut want = [0.0f64; 3];
            for k in 0..SUB * SUB {
                let ndc = |v: f64, n: u32| v / n as f64 * 2.0 - 1.0;
                let sx = x as f64 + ((k % SUB) as f64 + 0.5) / SUB as f64;
                let sy = y as f64 + ((k / SUB) as f64 + 0.5) / SUB as f64;
                let (nx, ny) = (ndc(sx, grid.width), ndc(sy, grid.height));
                let p0 = inv.project_point3(glam::DVec3::new(nx, ny, -1.0));
                let p1 = inv.project_point3(glam::DVec3::new(nx, ny, 1.0));
                let t = (-1.0 - p0.y) / (p1.y - p0.y);
                let hit = p0 + (p1 - p0) * t;
                let inside = (0.0..=1.0).contains(&t)
                    && hit.x.abs() <= FLOOR_X
                    && (FLOOR_Z[1]..=FLOOR_Z[0]).contains(&hit.z);
                if !inside {
                    continue 'sample;
                }
                let [u, v] = floor_uv(hit.x, hit.z);
                let texel = |t: f64| ((t.rem_euclid(1.0) * 32.0) as u32).min(31);
                let c = checker(texel(u), texel(v));
                for ch in 0..3 {
                    want[ch] += c[ch] as f64 / (SUB * SUB) as f64;
                }
            }
            let got = c.to_f32().map(|v| v as f64 / 257.0);
            let e = (0..3)
                .map(|k| (got[k] - want[k] * 255.0).abs())
                .fold(0.0, f64::max);
            max = max.max(e);
            sum += e;
            n += 1;
        }
    }
    (max, sum / n.max(1) as f64)
}

/// Every workload rendered in octant mode and blitted with `split` (the
/// blitter itself): for every cell whose samples hold more than two
/// colours, the RMS distance (0–255) of each sample's colour to the colour
/// the cell shows at that sample (the glyph's foreground where its pattern
/// covers the sample, else its background); the mean over those cells.
/// Undrawn samples count as the scene's background, or black.
fn split_error(workloads: &[Workload], split: Split) -> f64 {
    let opts = RenderOptions {
        cols: 80,
        rows: 24,
        glyphs: GlyphMode::Octant,
        split,
        ..base()
    };
    let (mut sum, mut n) = (0.0, 0usize);
    for w in workloads {
        let mut r = Renderer::new();
        r.render(&w.scene, &opts);
        let (fb, frame) = (r.framebuffer(), r.frame());
        let bg = w.scene.background.unwrap_or(Rgb::BLACK);
        let height = fb.grid().height;
        // Measured on the encoded colours, as the cell's are.
        for cy in 0..opts.rows {
            for cx in 0..opts.cols {
                let colors: [Rgb; 8] = std::array::from_fn(|i| {
                    let (x, y) = (
                        cx as u32 * 2 + i as u32 % 2,
                        height - 1 - (cy as u32 * 4 + i as u32 / 2),
                    );
                    fb.get(x, y).map_or(bg, |c| c.to_srgb())
                });
                if colors.iter().map(|c| c.0).collect::<BTreeSet<_>>().len() <= 2 {
                    continue;
                }
                let cell = frame.get(cx, cy);
                let Some(mask) = GlyphMode::Octant.pattern(cell.ch) else {
                    continue;
                };
                let sq: f32 = (0..8)
                    .map(|i| {
                        let shown = if mask >> i & 1 == 1 { cell.fg } else { cell.bg };
                        let [r, g, b] = shown.unwrap_or(bg).to_f32();
                        let c = colors[i].to_f32();
                        (c[0] - r).powi(2) + (c[1] - g).powi(2) + (c[2] - b).powi(2)
                    })
                    .sum();
                sum += (sq / 8.0).sqrt() as f64;
                n += 1;
            }
        }
    }
    sum / n.max(1) as f64
}

/// The median time to encode each workload's frame in `palette` (the
/// quantizer's work, where the palette costs).
fn encode_times(workloads: &[Workload], palette: Palette, reps: usize) -> Vec<Duration> {
    workloads
        .iter()
        .map(|w| {
            let frame = rastty::render(&w.scene, &base());
            median((0..reps).map(|_| {
                let mut e = Encoder::new(palette.depth)
                    .with_metric(palette.metric)
                    .with_dither(palette.dither);
                let t = Instant::now();
                e.prepare(&frame);
                t.elapsed()
            }))
        })
        .collect()
}

/// How well a metric matches colours to a palette.
pub struct MatchingError {
    /// Mean OKLab distance to the colour sent, over random colours.
    pub mean: f64,
    /// Of near-greys (OKLab chroma below `GREY_CHROMA`),
    /// the share sent to a chromatic entry, in %.
    pub greys_coloured: f64,
    /// Of clearly chromatic colours (chroma 0.08 or more), the share sent
    /// to an entry whose hue is more than 45° away (or to a grey), in %.
    pub hues_moved: f64,
}

/// Seeded random colours (4,096 of any kind, 4,096 near-greys) mapped to
/// `depth` by `metric`.
pub fn matching_error(depth: ColorDepth, metric: Metric) -> MatchingError {
    use color::{GREY_CHROMA, chroma};
    let lab = |c: Rgb| {
        let [r, g, b] = c.0;
        let l = oklab::srgb_to_oklab(oklab::Rgb { r, g, b });
        [l.l, l.a, l.b]
    };
    let mut rng = Rng(0xD1B5_4A32_D192_ED03);
    let (mut sum, mut n, mut chromatic, mut moved) = (0.0f64, 0usize, 0usize, 0usize);
    for _ in 0..4096 {
        let c = Rgb([0, 0, 0].map(|_: u8| (rng.next() * 256.0) as u8));
        let sent = color::xterm256(color::nearest(depth, metric, c));
        sum += color::oklab_distance(c, sent) as f64;
        n += 1;
        if chroma(c) >= 0.08 {
            chromatic += 1;
            let (p, q) = (lab(c), lab(sent));
            let turn = (p[2].atan2(p[1]) - q[2].atan2(q[1])).abs();
            let turn = turn.min(std::f32::consts::TAU - turn);
            if chroma(sent) < GREY_CHROMA || turn > std::f32::consts::FRAC_PI_4 {
                moved += 1;
            }
        }
    }
    let (mut greys, mut coloured) = (0usize, 0usize);
    while greys < 4096 {
        let v = rng.next() * 256.0;
        let jitter = |_: u8| (v + (rng.next() - 0.5) * 12.0).clamp(0.0, 255.0) as u8;
        let c = Rgb([0, 0, 0].map(jitter));
        if chroma(c) >= GREY_CHROMA {
            continue;
        }
        greys += 1;
        let sent = color::xterm256(color::nearest(depth, metric, c));
        coloured += (chroma(sent) >= GREY_CHROMA) as usize;
    }
    MatchingError {
        mean: sum / n as f64,
        greys_coloured: 100.0 * coloured as f64 / greys as f64,
        hues_moved: 100.0 * moved as f64 / chromatic.max(1) as f64,
    }
}

/// What dithering costs and gains, over the workloads.
pub struct DitherCost {
    /// Mean OKLab distance between the truecolor frame and the frame as
    /// sent, each averaged (in linear light) over areas of 2×2 cells, as
    /// the eye averages a pattern seen from a little way off.
    pub error: f64,
    /// Mean bytes of a first frame and of the next one (turned 3°).
    pub full_bytes: f64,
    /// Mean bytes of the next frame.
    pub next_bytes: f64,
}

/// [`DitherCost`] of `palette` over the workloads, in half blocks at
/// 200×60 cells.
pub fn dither_cost(workloads: &[Workload], palette: Palette) -> DitherCost {
    let opts = base();
    let (mut err, mut blocks, mut full, mut next) = (0.0f64, 0usize, 0usize, 0usize);
    for w in workloads {
        let frame = rastty::render(&w.scene, &opts);
        let mut e = Encoder::new(palette.depth)
            .with_metric(palette.metric)
            .with_dither(palette.dither);
        e.prepare(&frame);
        full += e.last_bytes().len();
        let turned = RenderOptions {
            turn: opts.turn + Vec3::new(0.0, 3.0, 0.0),
            ..opts
        };
        e.prepare(&rastty::render(&w.scene, &turned));
        next += e.last_bytes().len();
        // Each cell's light: its two colours weighted by the glyph's share.
        let mut q = color::Quantizer::of(palette);
        let bg = w.scene.background.unwrap_or(Rgb::BLACK);
        let light = |c: Option<Rgb>| Vec3::from(Lin::from_srgb(c.unwrap_or(bg)).to_f32());
        // Each cell's light: its two colours weighted by the glyph's share,
        // as sent (through the encoder's own cell mapping) or as drawn.
        let share = |ch: char| match ch {
            ' ' => 0.0,
            '█' => 1.0,
            _ => 0.5,
        };
        let cell_light = |x: u16, y: u16, q: &mut Option<&mut color::Quantizer>| {
            let (ch, fg, bg_) = match q {
                Some(q) => {
                    let t = TermCell::at(&frame, q, x, y);
                    let ink = |i: Ink| match i {
                        Ink::Indexed(i) => Some(color::xterm256(i)),
                        Ink::Rgb(c) => Some(c),
                        Ink::Default => None,
                    };
                    (t.ch, ink(t.fg), ink(t.bg))
                }
                None => {
                    let cell = frame.get(x, y);
                    (cell.ch, cell.fg, cell.bg)
                }
            };
            light(fg) * share(ch) + light(bg_) * (1.0 - share(ch))
        };
        for by in 0..frame.rows() / 2 {
            for bx in 0..frame.cols() / 2 {
                let (mut want, mut got) = (Vec3::ZERO, Vec3::ZERO);
                for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                    let (x, y) = (bx * 2 + dx, by * 2 + dy);
                    want += cell_light(x, y, &mut None);
                    got += cell_light(x, y, &mut Some(&mut q));
                }
                let enc = |v: Vec3| Lin::from_f32((v / 4.0).to_array()).to_srgb();
                let (a, b) = (enc(want), enc(got));
                if a != bg || b != bg {
                    err += color::oklab_distance(a, b) as f64;
                    blocks += 1;
                }
            }
        }
    }
    let k = workloads.len().max(1) as f64;
    DitherCost {
        error: err / blocks.max(1) as f64,
        full_bytes: full as f64 / k,
        next_bytes: next as f64 / k,
    }
}

impl Report {
    /// The table, one section per knob.
    pub fn markdown(&self) -> String {
        let mut out = String::new();
        let mut knob = "";
        for row in &self.rows {
            if row.knob != knob {
                knob = row.knob;
                let _ = writeln!(out, "\n### {knob}\n");
                let errors: Vec<&str> = row.errors.iter().map(|e| e.0).collect();
                let _ = writeln!(
                    out,
                    "| setting | {} | {} |",
                    errors.join(" | "),
                    self.workloads
                        .iter()
                        .map(|w| format!("{w} (ms)"))
                        .collect::<Vec<_>>()
                        .join(" | ")
                );
                let _ = writeln!(
                    out,
                    "|---|{}{}",
                    "---:|".repeat(errors.len()),
                    "---:|".repeat(self.workloads.len())
                );
            }
            let errors: Vec<String> = row.errors.iter().map(|e| fmt_error(e.1)).collect();
            let times: Vec<String> = row
                .times
                .iter()
                .map(|t| format!("{:.2}", t.as_secs_f64() * 1e3))
                .collect();
            let _ = writeln!(
                out,
                "| {} | {} | {} |",
                row.setting,
                errors.join(" | "),
                times.join(" | ")
            );
        }
        out
    }

    /// An SVG plot: for each knob, its settings' first error measure
    /// (relative to the knob's worst) against time per frame on the
    /// workload where the knob's settings differ most in time (texture
    /// filtering costs nothing on a scene without textures).
    pub fn svg(&self, path: &Path) -> Result<(), String> {
        use plotters::prelude::*;
        let root = SVGBackend::new(path, (960, 640)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        // Per knob, the workload whose times spread the most (relatively).
        let mut on: std::collections::BTreeMap<&str, usize> = Default::default();
        for knob in self.rows.iter().map(|r| r.knob) {
            let rows = || self.rows.iter().filter(|r| r.knob == knob);
            let spread = |w: usize| {
                let t = || {
                    rows()
                        .filter_map(|r| r.times.get(w))
                        .map(Duration::as_secs_f64)
                };
                let (lo, hi) = (t().fold(f64::INFINITY, f64::min), t().fold(0.0, f64::max));
                if lo > 0.0 { hi / lo } else { 0.0 }
            };
            let best = (0..self.workloads.len())
                .max_by(|&a, &b| spread(a).total_cmp(&spread(b)))
                .unwrap_or(0);
            on.insert(knob, best);
        }
        let ms = |r: &Row| {
            r.times
                .get(on.get(r.knob).copied().unwrap_or(0))
                .map_or(0.0, |t| t.as_secs_f64() * 1e3)
        };
        let x_max = self.rows.iter().map(ms).fold(0.0, f64::max) * 2.0 + 1e-3;
        let x_min = self
            .rows
            .iter()
            .map(ms)
            .filter(|&t| t > 0.0)
            .fold(f64::INFINITY, f64::min)
            .min(x_max)
            / 2.0;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                "rastty: error against time per frame, one series per knob",
                ("sans-serif", 22),
            )
            .margin(16)
            .x_label_area_size(44)
            .y_label_area_size(56)
            .build_cartesian_2d((x_min..x_max).log_scale(), -0.02..1.05)
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc(
                "time per frame (ms, log scale) on the scene where the knob's settings differ most",
            )
            .y_desc("error, relative to the knob's worst setting")
            .draw()
            .map_err(|e| e.to_string())?;
        let knobs: Vec<&str> = self
            .rows
            .iter()
            .map(|r| r.knob)
            .collect::<BTreeSet<_>>()
            .into_iter()
            .collect();
        for (i, knob) in knobs.iter().enumerate() {
            let color = Palette99::pick(i).to_rgba();
            let rows: Vec<&Row> = self.rows.iter().filter(|r| r.knob == *knob).collect();
            let worst = rows.iter().map(|r| r.errors[0].1).fold(0.0, f64::max);
            let mut pts: Vec<(f64, f64)> = rows
                .iter()
                .map(|r| {
                    (
                        ms(r).max(x_min),
                        if worst > 0.0 {
                            r.errors[0].1 / worst
                        } else {
                            0.0
                        },
                    )
                })
                .collect();
            // The frontier reads left to right: sorted by time.
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            chart
                .draw_series(pts.iter().map(|&p| Circle::new(p, 5, color.filled())))
                .map_err(|e| e.to_string())?
                .label(format!(
                    "{knob} ({})",
                    self.workloads
                        .get(on.get(knob).copied().unwrap_or(0))
                        .map_or("", String::as_str)
                ))
                .legend(move |(x, y)| Circle::new((x, y), 5, color.filled()));
            chart
                .draw_series(LineSeries::new(pts.clone(), color.stroke_width(1)))
                .map_err(|e| e.to_string())?;
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(|e| e.to_string())?;
        root.present().map_err(|e| e.to_string())
    }
}

fn fmt_error(e: f64) -> String {
    if e == e.trunc() && e.abs() < 1e9 {
        format!("{e:.0}")
    } else if e.abs() >= 0.1 {
        format!("{e:.2}")
    } else if e.abs() >= 1e-4 {
        format!("{e:.4}")
    } else {
        format!("{e:.1e}")
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
