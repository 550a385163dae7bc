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
//! | coverage | samples per cell (1, 2, 4, 6, 8) × `--aa none, 4x, 16x`, and `--aa exact` | mean and largest absolute error of each cell's coverage against the analytic area ([`crate::accuracy`]), over random triangles |
//! | precision | unsnapped f32 and f64 edge functions, the exact i64 fixed point | cracks and double hits on random tilings of the screen |
//! | traversal | scan, bounding box, incremental | samples that differ from incremental (must be 0) |
//! | interpolation | affine, perspective-correct | largest and mean colour error (0–255) against an f64 ray cast, on a floor running away from the eye |
//! | two-colour cells | exhaustive split, widest-channel split | mean RMS colour error (0–255) of a cell's samples against the two colours drawn |
//! | quantisation | 256 and 16 colours, nearest in RGB or in OKLab | mean and largest OKLab distance to the colour sent |

use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::path::Path;
use std::time::{Duration, Instant};

use glam::Vec3;

use crate::accuracy::area_in_rect;
use crate::blit::{self, GlyphMode, Split};
use crate::color::{self, ColorDepth, Metric, Rgb};
use crate::encode::Encoder;
use crate::raster::{Cull, Grid, Setup, Traversal};
use crate::render::{Aa, Interpolation, RenderOptions, Renderer};
use crate::scene::{Camera, Projection, Scene, Triangle, TriangleColor};

/// A scene to time, and whether it turns from frame to frame.
pub struct Workload {
    pub name: String,
    pub scene: Scene,
}

/// One knob setting: its time per frame on each workload and its errors.
pub struct Row {
    pub knob: &'static str,
    pub setting: String,
    pub times: Vec<Duration>,
    pub errors: Vec<(&'static str, f64)>,
}

/// Everything `rastty bench` measured.
pub struct Report {
    pub workloads: Vec<String>,
    pub rows: Vec<Row>,
}

/// The built-in scenes, and the models found in `models` (any of bunny,
/// teapot, fox, shiba-inu, linux-mascot-tux).
pub fn workloads(models: &Path) -> Vec<Workload> {
    let mut w = vec![
        Workload {
            name: "torus (built-in)".into(),
            scene: crate::default_scene(),
        },
        Workload {
            name: "tiles (2D)".into(),
            scene: Scene::parse(include_str!("../examples/scenes/tiles.toml"), "tiles.toml")
                .expect("tiles parse"),
        },
    ];
    for file in [
        "bunny.obj",
        "teapot.obj",
        "fox.obj",
        "shiba-inu.obj",
        "linux-mascot-tux.obj",
    ] {
        if let Ok(scene) = Scene::of_model(&models.join(file)) {
            w.push(Workload {
                name: file.trim_end_matches(".obj").into(),
                scene,
            });
        }
    }
    w
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
    let tris = random_triangles(300, 40.0, 12.0);
    for glyphs in COVERAGE_MODES {
        for aa in [Aa::None, Aa::X4, Aa::X16] {
            let (mean, max) = coverage_error(&tris, glyphs, aa);
            let (w, h) = glyphs.cell_size();
            rows.push(Row {
                knob: "coverage",
                setting: format!("{} samples/cell, aa {}", w * h, aa_name(aa)),
                times: time_all(&RenderOptions {
                    glyphs,
                    aa,
                    ..base()
                }),
                errors: vec![("mean abs. error", mean), ("max abs. error", max)],
            });
        }
    }
    rows.push(Row {
        knob: "coverage",
        setting: "exact area (aa exact)".into(),
        times: time_all(&RenderOptions {
            glyphs: GlyphMode::Half,
            aa: Aa::Exact,
            ..base()
        }),
        errors: vec![("mean abs. error", 0.0), ("max abs. error", 0.0)],
    });

    // 2. Precision.
    for precision in Precision::ALL {
        let (cracks, doubles, time) = precision_errors(precision, reps);
        rows.push(Row {
            knob: "precision",
            setting: format!("{precision:?}"),
            times: vec![time; workloads.len()],
            errors: vec![("cracks", cracks as f64), ("double hits", doubles as f64)],
        });
    }

    // 3. Traversal.
    for traversal in Traversal::ALL {
        rows.push(Row {
            knob: "traversal",
            setting: format!("{traversal:?}"),
            times: time_all(&RenderOptions {
                traversal,
                ..base()
            }),
            errors: vec![(
                "samples unlike incremental",
                traversal_mismatch(workloads, traversal) as f64,
            )],
        });
    }

    // 4. Interpolation.
    for interpolation in [Interpolation::Affine, Interpolation::Perspective] {
        let (max, mean) = interpolation_error(interpolation);
        rows.push(Row {
            knob: "interpolation",
            setting: format!("{interpolation:?}"),
            times: time_all(&RenderOptions {
                interpolation,
                ..base()
            }),
            errors: vec![("max colour error", max), ("mean colour error", mean)],
        });
    }

    // 5. Two-colour cells.
    for split in [Split::WidestChannel, Split::Exhaustive] {
        rows.push(Row {
            knob: "two-colour cells",
            setting: format!("{split:?}"),
            times: time_all(&RenderOptions {
                glyphs: GlyphMode::Octant,
                split,
                ..base()
            }),
            errors: vec![("mean RMS error per cell", split_error(workloads, split))],
        });
    }

    // 6. Quantisation.
    for depth in [ColorDepth::Ansi256, ColorDepth::Ansi16] {
        for metric in [Metric::Rgb, Metric::Oklab] {
            let (mean, max) = quantisation_error(depth, metric);
            let times = workloads
                .iter()
                .map(|w| {
                    let frame = crate::render(&w.scene, &base());
                    median((0..reps).map(|_| {
                        let mut e = Encoder::new(depth).with_metric(metric);
                        let t = Instant::now();
                        e.prepare(&frame);
                        t.elapsed()
                    }))
                })
                .collect();
            rows.push(Row {
                knob: "quantisation",
                setting: format!(
                    "{} colours, nearest in {metric:?}",
                    if depth == ColorDepth::Ansi16 { 16 } else { 256 }
                ),
                times,
                errors: vec![("mean OKLab distance", mean), ("max OKLab distance", max)],
            });
        }
    }

    Report {
        workloads: workloads.iter().map(|w| w.name.clone()).collect(),
        rows,
    }
}

fn aa_name(aa: Aa) -> &'static str {
    match aa {
        Aa::None => "none",
        Aa::X4 => "4x",
        Aa::X16 => "16x",
        Aa::Exact => "exact",
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

/// Each triangle alone on a 40×12-cell screen: the coverage of every cell it
/// touches, estimated by the samples of `glyphs` (and `aa`'s sub-samples),
/// against the exact area. Mean and largest absolute error.
fn coverage_error(tris: &[[[f64; 2]; 3]], glyphs: GlyphMode, aa: Aa) -> (f64, f64) {
    let (cols, rows) = (40usize, 12usize);
    let (w, h) = glyphs.cell_size();
    let grid = Grid::new(cols as u32 * w, rows as u32 * h);
    let offsets = aa.offsets();
    let per_cell = (w * h) as f64 * offsets.len() as f64;
    let (mut sum, mut max, mut n) = (0.0f64, 0.0f64, 0usize);
    let mut hits = vec![0u32; cols * rows];
    for t in tris {
        hits.iter_mut().for_each(|c| *c = 0);
        // Cell coordinates to sample coordinates, shifted per sub-sample.
        for &(ox, oy) in offsets {
            let v = t.map(|[x, y]| {
                [
                    (x * w as f64) as f32 + 0.5 - ox,
                    (y * h as f64) as f32 + 0.5 - oy,
                ]
            });
            if let Ok(s) = Setup::new(v, grid, Cull::None) {
                s.walk(grid, Traversal::Incremental, |x, y, _| {
                    hits[(y / h) as usize * cols + (x / w) as usize] += 1;
                });
            }
        }
        for cy in 0..rows {
            for cx in 0..cols {
                let exact = area_in_rect(
                    *t,
                    [cx as f64, cy as f64],
                    [cx as f64 + 1.0, cy as f64 + 1.0],
                );
                let estimate = hits[cy * cols + cx] as f64 / per_cell;
                if exact > 0.0 || estimate > 0.0 {
                    let e = (estimate - exact).abs();
                    sum += e;
                    max = max.max(e);
                    n += 1;
                }
            }
        }
    }
    (sum / n.max(1) as f64, max)
}

/// How edge functions are evaluated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Precision {
    /// Unsnapped, in f32.
    F32,
    /// Unsnapped, in f64.
    F64,
    /// Snapped to 1/256, in i64: the rasterizer.
    Fixed,
}

impl Precision {
    pub const ALL: [Precision; 3] = [Precision::F32, Precision::F64, Precision::Fixed];
}

/// Tilings of a 64×48 screen drawn with `precision`: samples covered no
/// times (cracks) and more than once (double hits), and the time to draw
/// the lot. Half are jittered quad grids (vertices anywhere, either
/// diagonal), where edges seldom pass near a sample centre; half are fans
/// around a sample centre whose spokes run through further sample centres
/// (their far ends, at thirds of a sample, are not exact in binary): there
/// the unsnapped edge functions of two neighbours round differently.
pub fn precision_errors(precision: Precision, reps: usize) -> (u64, u64, Duration) {
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
    let mut counts = vec![0u32; grid.len()];
    let (mut cracks, mut doubles) = (0, 0);
    for tris in &tilings {
        counts.iter_mut().for_each(|c| *c = 0);
        for t in tris {
            draw_with(precision, *t, grid, &mut counts);
        }
        cracks += counts.iter().filter(|&&c| c == 0).count() as u64;
        doubles += counts.iter().filter(|&&c| c > 1).count() as u64;
    }
    let time = median((0..reps).map(|_| {
        let t = Instant::now();
        for tris in &tilings {
            for tri in tris {
                draw_with(precision, *tri, grid, &mut counts);
            }
        }
        t.elapsed() / tilings.len() as u32
    }));
    (cracks, doubles, time)
}

fn gcd(a: u32, b: u32) -> u32 {
    if b == 0 { a } else { gcd(b, a % b) }
}

fn draw_with(precision: Precision, t: [[f32; 2]; 3], grid: Grid, counts: &mut [u32]) {
    match precision {
        Precision::Fixed => {
            if let Ok(s) = Setup::new(t, grid, Cull::None) {
                s.walk(grid, Traversal::Incremental, |x, y, _| {
                    counts[(y * grid.width + x) as usize] += 1
                });
            }
        }
        Precision::F32 => float_raster(t.map(|p| p.map(|c| c)), grid, counts),
        Precision::F64 => float_raster(t.map(|p| p.map(|c| c as f64)), grid, counts),
    }
}

/// The notes' rasterizer without the snap: edge functions of the unsnapped
/// vertices, in `F` (f32 or f64), the top-left rule for exact zeros.
fn float_raster<F>(t: [[F; 2]; 3], grid: Grid, counts: &mut [u32])
where
    F: Copy
        + PartialOrd
        + std::ops::Sub<Output = F>
        + std::ops::Mul<Output = F>
        + From<f32>
        + Into<f64>,
{
    let zero = F::from(0.0);
    let cross = |a: [F; 2], b: [F; 2], p: [F; 2]| {
        (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])
    };
    let area = cross(t[0], t[1], t[2]);
    if area == zero {
        return;
    }
    let ccw = area > zero;
    let (lo, hi) = (
        [0, 1].map(|k| t.iter().map(|p| p[k].into()).fold(f64::INFINITY, f64::min)),
        [0, 1].map(|k| {
            t.iter()
                .map(|p| p[k].into())
                .fold(f64::NEG_INFINITY, f64::max)
        }),
    );
    let x0 = (lo[0] - 0.5).ceil().max(0.0) as u32;
    let y0 = (lo[1] - 0.5).ceil().max(0.0) as u32;
    let x1 = ((hi[0] - 0.5).floor().min(grid.width as f64 - 1.0)).max(-1.0) as i64;
    let y1 = ((hi[1] - 0.5).floor().min(grid.height as f64 - 1.0)).max(-1.0) as i64;
    for y in y0 as i64..=y1 {
        for x in x0 as i64..=x1 {
            let p = [F::from(x as f32 + 0.5), F::from(y as f32 + 0.5)];
            let inside = (0..3).all(|i| {
                let (a, b) = if ccw {
                    (t[i], t[(i + 1) % 3])
                } else {
                    (t[(i + 1) % 3], t[i])
                };
                let e = cross(a, b, p);
                let dy = b[1] - a[1];
                let dx = b[0] - a[0];
                e > zero || (e == zero && (dy < zero || (dy == zero && dx < zero)))
            });
            if inside {
                counts[(y as u32 * grid.width + x as u32) as usize] += 1;
            }
        }
    }
}

/// Samples of every workload's frame drawn differently by `traversal` than
/// by the incremental one.
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
/// it, found by casting the ray in f64. Largest and mean error, 0–255.
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
            let want = [255.0 * (1.0 - s), 0.0, 255.0 * s];
            let got = c.to_f32();
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

/// Every octant cell of every workload's frame: the RMS distance of its
/// samples to the colour of the side `split` puts them on; the mean over
/// cells of more than two colours.
fn split_error(workloads: &[Workload], split: Split) -> f64 {
    let opts = RenderOptions {
        cols: 80,
        rows: 24,
        glyphs: GlyphMode::Octant,
        ..base()
    };
    let (mut sum, mut n) = (0.0, 0usize);
    for w in workloads {
        let mut r = Renderer::new();
        r.render(&w.scene, &opts);
        let fb = r.framebuffer();
        let bg = w.scene.background.unwrap_or(Rgb::BLACK);
        for cy in 0..opts.rows as u32 {
            for cx in 0..opts.cols as u32 {
                let colors: [Rgb; 8] = std::array::from_fn(|i| {
                    let (x, y) = (
                        cx * 2 + i as u32 % 2,
                        fb.grid().height - 1 - (cy * 4 + i as u32 / 2),
                    );
                    fb.get(x, y).unwrap_or(bg)
                });
                if colors.iter().map(|c| c.0).collect::<BTreeSet<_>>().len() <= 2 {
                    continue;
                }
                let mask = match split {
                    Split::Exhaustive => blit::split(&colors),
                    Split::WidestChannel => blit::split_widest_channel(&colors),
                };
                let mean = |side: u8| {
                    let members: Vec<[f32; 3]> = (0..8)
                        .filter(|&i| (mask >> i) & 1 == side)
                        .map(|i| colors[i].to_f32())
                        .collect();
                    let k = members.len().max(1) as f32;
                    std::array::from_fn::<f32, 3, _>(|c| {
                        members.iter().map(|m| m[c]).sum::<f32>() / k
                    })
                };
                let (m0, m1) = (mean(0), mean(1));
                let sq: f32 = (0..8)
                    .map(|i| {
                        let m = if (mask >> i) & 1 == 1 { m1 } else { m0 };
                        let c = colors[i].to_f32();
                        (0..3).map(|k| (c[k] - m[k]).powi(2)).sum::<f32>()
                    })
                    .sum();
                sum += (sq / 8.0).sqrt() as f64;
                n += 1;
            }
        }
    }
    sum / n.max(1) as f64
}

/// 4,096 seeded random colours mapped to `depth` by `metric`: the mean and
/// largest OKLab distance to the colour sent.
fn quantisation_error(depth: ColorDepth, metric: Metric) -> (f64, f64) {
    let mut rng = Rng(0xD1B5_4A32_D192_ED03);
    let (mut sum, mut max) = (0.0f64, 0.0f64);
    let n = 4096;
    for _ in 0..n {
        let c = Rgb([0, 0, 0].map(|_: u8| (rng.next() * 256.0) as u8));
        let sent = color::xterm256(color::nearest(depth, metric, c));
        let d = color::oklab_distance(c, sent) as f64;
        sum += d;
        max = max.max(d);
    }
    (sum / n as f64, max)
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
    /// (relative to the knob's worst) against time per frame on the first
    /// workload.
    pub fn svg(&self, path: &Path) -> Result<(), String> {
        use plotters::prelude::*;
        let root = SVGBackend::new(path, (960, 640)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let ms = |r: &Row| r.times.first().map_or(0.0, |t| t.as_secs_f64() * 1e3);
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
            .x_desc(format!(
                "time per frame on {} (ms, log scale)",
                self.workloads.first().map_or("", String::as_str)
            ))
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
                .label(*knob)
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
    } else {
        format!("{e:.4}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn more_samples_measure_coverage_better_and_exact_is_exact() {
        let tris = random_triangles(60, 40.0, 12.0);
        let one = coverage_error(&tris, GlyphMode::Block, Aa::None);
        let sixteen = coverage_error(&tris, GlyphMode::Block, Aa::X16);
        let octant16 = coverage_error(&tris, GlyphMode::Octant, Aa::X16);
        assert!(
            one.0 > sixteen.0 && sixteen.0 > octant16.0,
            "{one:?} {sixteen:?} {octant16:?}"
        );
        assert!(octant16.1 <= 1.0 && one.1 <= 1.0);
    }

    #[test]
    fn only_the_fixed_point_rasterizer_is_watertight() {
        let (cracks, doubles, _) = precision_errors(Precision::Fixed, 1);
        assert_eq!((cracks, doubles), (0, 0));
    }

    #[test]
    fn affine_interpolation_is_visibly_wrong_and_perspective_is_not() {
        let (affine, _) = interpolation_error(Interpolation::Affine);
        let (perspective, _) = interpolation_error(Interpolation::Perspective);
        assert!(perspective <= 2.0, "{perspective}");
        assert!(affine > 40.0, "{affine}");
    }

    #[test]
    fn oklab_quantisation_is_perceptually_closer() {
        for depth in [ColorDepth::Ansi256, ColorDepth::Ansi16] {
            let (rgb, _) = quantisation_error(depth, Metric::Rgb);
            let (ok, _) = quantisation_error(depth, Metric::Oklab);
            assert!(ok < rgb, "{depth:?}: {ok} vs {rgb}");
        }
    }
}
