//! rastty's promises about hard cases, each with an exact expectation, in
//! the spirit of the D3D rasterization rules and the dEQP/VK-GL-CTS
//! fill-rule tests. docs/promises.md lists them with the test behind each.

use rastty::Choice;
use rastty::Effect;
use std::collections::BTreeSet;

use glam::{Vec3, Vec4};
use proptest::prelude::*;
use rastty::clip::{ClipVertex, Clipper, Polygon};
use rastty::raster::{RasterStats, Setup, rasterize};
use rastty::scene::{Camera, Projection, Triangle, TriangleColor};
use rastty::transform::Grid;
use rastty::transform::Viewport;
use rastty::{GlyphMode, RenderOptions, Renderer, color::ColorDepth, color::Rgb, scene::Scene};
use rastty::{raster::Traversal, scene::Cull};

type Tri = [[f32; 2]; 3];

/// The samples a triangle covers, as a set.
fn covered(t: Tri, grid: Grid) -> BTreeSet<(u32, u32)> {
    let mut set = BTreeSet::new();
    rasterize(
        t,
        grid,
        Cull::None,
        Traversal::Incremental,
        &mut RasterStats::default(),
        |x, y, _| {
            assert!(set.insert((x, y)), "({x}, {y}) twice in one triangle");
        },
    );
    set
}

/// Per-sample hit counts of many triangles.
fn counts(tris: &[Tri], grid: Grid) -> Vec<u32> {
    let mut c = vec![0; grid.len()];
    for &t in tris {
        for (x, y) in covered(t, grid) {
            c[(y * grid.width + x) as usize] += 1;
        }
    }
    c
}

fn quad(a: [f32; 2], b: [f32; 2], c: [f32; 2], d: [f32; 2]) -> [Tri; 2] {
    [[a, b, c], [a, c, d]]
}

fn rect(x0: f32, y0: f32, x1: f32, y1: f32) -> BTreeSet<(u32, u32)> {
    let g = Grid::new(8, 8);
    let [t1, t2] = quad([x0, y0], [x1, y0], [x1, y1], [x0, y1]);
    let (a, b) = (covered(t1, g), covered(t2, g));
    assert!(a.is_disjoint(&b));
    a.union(&b).copied().collect()
}

fn set(cells: impl IntoIterator<Item = (u32, u32)>) -> BTreeSet<(u32, u32)> {
    cells.into_iter().collect()
}

// 1. Shared edges, exactly once.

#[test]
fn a_screen_filling_quad_turned_through_15_angles_covers_each_sample_once() {
    let g = Grid::new(32, 24);
    let (cx, cy) = (16.3, 12.1);
    for k in 0..15 {
        let a = k as f32 * 6.1f32.to_radians();
        let (s, c) = a.sin_cos();
        // Big enough to cover the screen at any angle.
        let corner = |x: f32, y: f32| [cx + 40.0 * (c * x - s * y), cy + 40.0 * (s * x + c * y)];
        let tris = quad(
            corner(-1.0, -1.0),
            corner(1.0, -1.0),
            corner(1.0, 1.0),
            corner(-1.0, 1.0),
        );
        assert!(counts(&tris, g).iter().all(|&n| n == 1), "angle {k}");
    }
}

#[test]
fn strips_cover_each_sample_once() {
    // A triangle strip zig-zagging across the screen, vertices on sample
    // centres and on edges between them.
    let g = Grid::new(20, 6);
    let mut pts = Vec::new();
    for i in 0..=14 {
        let x = -5.0 + i as f32 * 2.0;
        pts.push([x, if i % 2 == 0 { -1.0 } else { 7.0 }]);
    }
    let tris: Vec<Tri> = pts.windows(3).map(|w| [w[0], w[1], w[2]]).collect();
    let c = counts(&tris, g);
    assert!(c.iter().all(|&n| n == 1), "{c:?}");
}

/// The clip and divide path of the renderer, for triangles given in clip
/// space (with z = 0): what a projection with varying w produces. The
/// clipper works in model space, so each vertex goes in as the model point
/// (x, y, w), which a matrix takes to clip space (x, y, 0, w).
fn projected_counts(tris: &[[Vec4; 3]], grid: Grid) -> Vec<u32> {
    let mvp = glam::DMat4::from_cols_array_2d(&[
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 0.0, 1.0],
        [0.0, 0.0, 0.0, 0.0],
    ]);
    let clipper = Clipper::new(grid.width, grid.height);
    let vp = Viewport::new(grid.width as f32, grid.height as f32);
    let mut c = vec![0; grid.len()];
    let mut poly = Polygon::default();
    for t in tris {
        assert!(t.iter().all(|p| p.z == 0.0));
        let verts = t.map(|p| ClipVertex {
            pos: glam::DVec4::new(p.x as f64, p.y as f64, p.w as f64, 1.0),
            color: Vec3::ZERO,
            uv: glam::Vec2::ZERO,
            weights: Vec3::ZERO,
            snapped: None,
        });
        clipper.clip(&verts, &mvp, &vp, &mut poly);
        for sub in poly.triangles() {
            if let Ok(s) = Setup::from_fixed(sub.map(|v| v.fixed), grid, Cull::None) {
                s.walk(grid, Traversal::Incremental, |x, y, _| {
                    c[(y * grid.width + x) as usize] += 1
                });
            }
        }
    }
    c
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(
        std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(128)
    ))]

    /// A jittered grid of quads over the screen, in clip space with a
    /// random w per vertex in [0.1, 4]: shared edges stay exact through
    /// the divide.
    #[test]
    fn projected_grids_with_random_w_cover_each_sample_once(
        ws in prop::collection::vec(0.1f32..4.0, 49),
        jitter in prop::collection::vec((-0.2f32..0.2, -0.2f32..0.2), 49),
        diagonals in prop::collection::vec(any::<bool>(), 36),
    ) {
        let g = Grid::new(24, 16);
        // 7×7 vertices over NDC [-1.2, 1.2]², outer ones fixed.
        let vertex = |i: usize, j: usize| {
            let k = j * 7 + i;
            let inner = (1..6).contains(&i) && (1..6).contains(&j);
            let (jx, jy) = if inner { jitter[k] } else { (0.0, 0.0) };
            let x = -1.2 + 0.4 * i as f32 + jx * 0.4;
            let y = -1.2 + 0.4 * j as f32 + jy * 0.4;
            let w = ws[k];
            Vec4::new(x * w, y * w, 0.0, w)
        };
        let mut tris = Vec::new();
        for j in 0..6 {
            for i in 0..6 {
                let (a, b, c, d) = (vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1), vertex(i, j + 1));
                if diagonals[j * 6 + i] {
                    tris.push([a, b, c]);
                    tris.push([a, c, d]);
                } else {
                    tris.push([a, b, d]);
                    tris.push([b, c, d]);
                }
            }
        }
        let c = projected_counts(&tris, g);
        prop_assert!(c.iter().all(|&n| n == 1), "{:?}", c);
    }

    /// 3. An independent reference: i128 arithmetic on the same snapped
    /// coordinates, with the top-left rule stated another way.
    #[test]
    fn random_triangles_match_an_i128_reference(
        v in prop::array::uniform3((-3000i32..9000, -3000i32..7000)),
        scale in prop::sample::select(vec![1i32, 8, 64, 512]),
    ) {
        let g = Grid::new(24, 16);
        let centre = (12 * 256, 8 * 256);
        let p = v.map(|(x, y)| (centre.0 + (x - centre.0) / scale, centre.1 + (y - centre.1) / scale));
        let tri = p.map(|(x, y)| [x as f32 / 256.0, y as f32 / 256.0]);
        let expected = reference(p.map(|(x, y)| (x as i128, y as i128)), g);
        prop_assert_eq!(covered(tri, g), expected);
    }

    /// 11. Determinism: the same frame whatever vertex the triangle starts
    /// from.
    #[test]
    fn vertex_order_does_not_change_the_frame(
        v in prop::array::uniform3((-1.3f32..1.3, -1.3f32..1.3, -0.9f32..0.9)),
        colors in any::<[[u8; 3]; 3]>(),
        glyphs in prop::sample::select(GlyphMode::ALL.to_vec()),
    ) {
        let frame = |rot: usize| {
            let vs = [0, 1, 2].map(|i| Vec3::from(v[(i + rot) % 3]));
            let cs = [0, 1, 2].map(|i| Rgb(colors[(i + rot) % 3]));
            let scene = Scene {
                camera: Camera { projection: Projection::Perspective { fov_y: 60.0, near: 0.1, far: 10.0 }, eye: Vec3::new(0.3, 0.2, 3.0), ..Camera::default() },
                triangles: vec![Triangle { vertices: vs, color: TriangleColor::PerVertex(cs) }],
                ..Scene::default()
            };
            let mut r = Renderer::new();
            r.render(&scene, &RenderOptions { cols: 20, rows: 8, glyphs, color: ColorDepth::TrueColor, ..RenderOptions::default() });
            r.framebuffer().samples().to_vec()
        };
        let abc = frame(0);
        prop_assert_eq!(&abc, &frame(1));
        prop_assert_eq!(&abc, &frame(2));
    }

    /// 12. Moving a triangle by whole samples moves its coverage by exactly
    /// that.
    #[test]
    fn translation_by_whole_samples_moves_coverage_exactly(
        v in prop::array::uniform3((0i32..4000, 0i32..3000)),
        (dx, dy) in (-8i32..8, -6i32..6),
    ) {
        let g = Grid::new(32, 24);
        let tri = |ox: i32, oy: i32| v.map(|(x, y)| [(x + ox * 256) as f32 / 256.0, (y + oy * 256) as f32 / 256.0]);
        let moved = covered(tri(dx, dy), g);
        let shifted: BTreeSet<(u32, u32)> = covered(tri(0, 0), g)
            .into_iter()
            .map(|(x, y)| (x as i32 + dx, y as i32 + dy))
            .filter(|&(x, y)| x >= 0 && y >= 0 && x < 32 && y < 24)
            .map(|(x, y)| (x as u32, y as u32))
            .collect();
        // Samples moved in from off the screen are the only difference.
        let edge = |&(x, y): &(u32, u32)| {
            let (sx, sy) = (x as i32 - dx, y as i32 - dy);
            sx < 0 || sy < 0 || sx >= 32 || sy >= 24
        };
        let moved_from_screen: BTreeSet<_> = moved.iter().filter(|s| !edge(s)).copied().collect();
        prop_assert_eq!(moved_from_screen, shifted);
    }
}

/// The reference rasterizer: for each sample, the three edge functions in
/// i128 (from the triangle's orientation as given), and the tie rule as
/// "the interior lies to the right of a left edge, below a top edge".
fn reference(p: [(i128, i128); 3], g: Grid) -> BTreeSet<(u32, u32)> {
    let cross = |a: (i128, i128), b: (i128, i128), c: (i128, i128)| {
        (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0)
    };
    let area = cross(p[0], p[1], p[2]);
    let mut out = BTreeSet::new();
    if area == 0 {
        return out;
    }
    for y in 0..g.height {
        for x in 0..g.width {
            let s = (x as i128 * 256 + 128, y as i128 * 256 + 128);
            let inside = (0..3).all(|i| {
                let (a, b) = (p[i], p[(i + 1) % 3]);
                // Oriented so the interior is positive.
                let e = cross(a, b, s) * area.signum();
                if e != 0 {
                    return e > 0;
                }
                // On the edge: walk it with the interior on the left; the
                // interior is below (top edge) if it runs towards −x
                // horizontally, to its right... in screen terms: a left edge
                // goes down.
                let (dx, dy) = if area > 0 {
                    (b.0 - a.0, b.1 - a.1)
                } else {
                    (a.0 - b.0, a.1 - b.1)
                };
                dy < 0 || (dy == 0 && dx < 0)
            });
            if inside {
                out.insert((x, y));
            }
        }
    }
    out
}

// 2. Samples exactly on edges and vertices (the D3D examples).

#[test]
fn d3d_square_split_on_its_diagonal_is_15_and_10() {
    let g = Grid::new(5, 5);
    let lower = covered([[0.0, 0.0], [5.0, 0.0], [5.0, 5.0]], g);
    let upper = covered([[0.0, 0.0], [5.0, 5.0], [0.0, 5.0]], g);
    assert_eq!((lower.len(), upper.len()), (15, 10));
    assert!(lower.is_disjoint(&upper));
    assert_eq!(lower.union(&upper).count(), 25);
    // The diagonal's samples belong to the lower triangle (its left edge).
    assert!((0..5).all(|i| lower.contains(&(i, i))));
}

#[test]
fn d3d_rectangles_on_sample_centres_and_between_them() {
    // (0.5, 0.5)–(2.5, 4.5): the left edge x = 0.5 and the top edge y = 4.5
    // (y up) pass through sample centres and own them; the right and the
    // bottom edges do not.
    let expected = set((0..2).flat_map(|x| (1..5).map(move |y| (x, y))));
    assert_eq!(rect(0.5, 0.5, 2.5, 4.5), expected);
    // (1, 1)–(3, 5): edges between sample centres: columns 1–2, rows 1–4.
    let expected = set((1..3).flat_map(|x| (1..5).map(move |y| (x, y))));
    assert_eq!(rect(1.0, 1.0, 3.0, 5.0), expected);
}

// 4. Degenerate triangles.

#[test]
fn degenerate_triangles_draw_nothing_and_say_so() {
    let g = Grid::new(8, 8);
    let mut stats = RasterStats::default();
    for t in [
        [[1.0, 1.0], [4.0, 4.0], [7.0, 7.0]], // collinear
        [[2.5, 2.5], [2.5, 2.5], [6.0, 1.0]], // repeated vertex
        [[3.0, 3.0], [3.0, 3.0], [3.0, 3.0]], // a point
        [[1.0, 1.0], [7.0, 1.0 + 1.0 / 1024.0], [13.0, 1.0]], // collinear after snapping
    ] {
        rasterize(
            t,
            g,
            Cull::None,
            Traversal::Incremental,
            &mut stats,
            |_, _, _| panic!("drew {t:?}"),
        );
    }
    assert_eq!(stats.dropped_degenerate, 4);
    // Through the renderer: nothing written, no NaN.
    let scene = Scene::in_canonical_cube(vec![Triangle {
        vertices: [
            Vec3::new(-0.5, -0.5, 0.0),
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(0.5, 0.5, 0.0),
        ],
        color: TriangleColor::PerVertex([Rgb::WHITE, Rgb::BLACK, Rgb::WHITE]),
    }]);
    let mut r = Renderer::new();
    r.render(&scene, &RenderOptions::default());
    assert!(r.framebuffer().samples().iter().all(Option::is_none));
    assert_eq!(r.stats().raster.dropped_degenerate, 1);
}

// 5. The near plane and w.

#[test]
fn vertices_behind_the_eye_never_show() {
    let g = Grid::new(16, 16);
    for w in [-1.0, 0.0, 1e-30, -1e-30] {
        // One vertex at w ≤ 0 (or nearly): its mirror image would cover the
        // screen's upper right; clipping keeps only what is in front.
        let t = [
            Vec4::new(-0.5, -0.5, 0.0, 1.0),
            Vec4::new(0.5, -0.5, 0.0, 1.0),
            Vec4::new(0.8 * w, 0.8 * w, 0.0, w),
        ];
        let c = projected_counts(&[t], g);
        // What remains lies within the part of the plane in front of the
        // eye: no sample in the upper-right quadrant beyond the vertices.
        for y in 12..16 {
            for x in 12..16 {
                assert_eq!(c[(y * 16 + x) as usize], 0, "w = {w}: ({x}, {y})");
            }
        }
        assert!(c.iter().all(|&n| n <= 1));
    }
    // All three behind: nothing.
    let behind = [
        Vec4::new(0.0, 0.0, 0.0, -1.0),
        Vec4::new(1.0, 0.0, 0.0, -1.0),
        Vec4::new(0.0, 1.0, 0.0, -2.0),
    ];
    assert!(projected_counts(&[behind], g).iter().all(|&n| n == 0));
}

#[test]
fn neighbours_cut_by_the_near_plane_stay_watertight() {
    // A floor from in front of the eye to behind it, as a fan of triangles
    // around a point on it: every triangle crosses or touches the near plane.
    let scene = |triangles| Scene {
        camera: Camera {
            shift: rastty::glam::Vec2::ZERO,
            projection: Projection::Perspective {
                fov_y: 70.0,
                near: 0.5,
                far: 50.0,
            },
            eye: Vec3::new(0.0, 1.0, 0.0),
            target: Vec3::new(0.0, 0.6, -3.0),
            up: Vec3::Y,
            fit: None,
        },
        triangles,
        ..Scene::default()
    };
    let hub = Vec3::new(0.2, 0.0, -2.0);
    let ring: Vec<Vec3> = (0..12)
        .map(|k| {
            let a = k as f32 / 12.0 * std::f32::consts::TAU;
            hub + Vec3::new(a.cos(), 0.0, a.sin()) * 9.0
        })
        .collect();
    let tris: Vec<Triangle> = (0..12)
        .map(|k| Triangle {
            vertices: [hub, ring[k], ring[(k + 1) % 12]],
            color: TriangleColor::Flat(Rgb::WHITE),
        })
        .collect();
    let opts = RenderOptions {
        cols: 48,
        rows: 20,
        glyphs: GlyphMode::Block,
        ..RenderOptions::default()
    };
    // Count coverage per sample with each triangle alone.
    let grid = opts.glyphs.grid(opts.cols, opts.rows);
    let mut count = vec![0u32; grid.len()];
    for t in &tris {
        let mut r = Renderer::new();
        r.render(&scene(vec![*t]), &opts);
        for (i, s) in r.framebuffer().samples().iter().enumerate() {
            count[i] += s.is_some() as u32;
        }
    }
    let mut r = Renderer::new();
    r.render(&scene(tris), &opts);
    assert!(r.stats().clipped > 0, "the near plane cut something");
    // The floor covers the lower part of the screen with no hole and no
    // double hit, and the whole picture is exactly the union.
    assert!(count.iter().all(|&n| n <= 1));
    let bottom = &count[..grid.width as usize];
    assert!(bottom.iter().all(|&n| n == 1), "the nearest row is covered");
    for (i, s) in r.framebuffer().samples().iter().enumerate() {
        assert_eq!(s.is_some(), count[i] == 1);
    }
}

// 6. Huge coordinates.

/// Renders one triangle given in samples through the whole pipeline
/// (canonical cube, no camera) on a `w × h` sample grid.
fn render_samples(t: [[f64; 2]; 3], cols: u16, rows: u16) -> (BTreeSet<(u32, u32)>, RasterStats) {
    let (w, h) = (cols as f64, rows as f64);
    let ndc =
        t.map(|[x, y]| Vec3::new((2.0 * x / w - 1.0) as f32, (2.0 * y / h - 1.0) as f32, 0.0));
    let scene = Scene::in_canonical_cube(vec![Triangle {
        vertices: ndc,
        color: TriangleColor::Flat(Rgb::WHITE),
    }]);
    let (set, r) = rendered(&scene, cols, rows, GlyphMode::Block);
    (set, r.stats().raster)
}

/// The samples `scene` covers, rendered `cols × rows` in `glyphs`, and the
/// renderer (for its counts).
fn rendered(
    scene: &Scene,
    cols: u16,
    rows: u16,
    glyphs: GlyphMode,
) -> (BTreeSet<(u32, u32)>, Renderer) {
    let mut r = Renderer::new();
    r.render(
        scene,
        &RenderOptions {
            cols,
            rows,
            glyphs,
            ..RenderOptions::default()
        },
    );
    let fb = r.framebuffer();
    let g = fb.grid();
    let set = (0..g.height)
        .flat_map(|y| (0..g.width).map(move |x| (x, y)))
        .filter(|&(x, y)| fb.get(x, y).is_some())
        .collect();
    (set, r)
}

#[test]
fn huge_coordinates_neither_overflow_nor_move_the_edges() {
    // A triangle with one corner on screen and two edges running out to
    // `far` samples along directions chosen so that no edge passes within
    // 0.05 of a sample centre; the reference tests each centre against the
    // edges' lines in f64, from the corner and the directions alone.
    let (cols, rows) = (40u16, 30u16);
    let apex = [13.37, 9.71];
    let dirs = [[1.0, 0.2131], [0.3117, 1.0]];
    let mut expected = BTreeSet::new();
    for y in 0..rows as u32 {
        for x in 0..cols as u32 {
            let s = [x as f64 + 0.5 - apex[0], y as f64 + 0.5 - apex[1]];
            let side = |d: [f64; 2]| d[0] * s[1] - d[1] * s[0];
            if side(dirs[0]) > 0.0 && side(dirs[1]) < 0.0 {
                expected.insert((x, y));
            }
        }
    }
    assert!(expected.len() > 300);
    for far in [1e3, 1e6, 1e12, 1e30] {
        let t = [
            apex,
            [apex[0] + far * dirs[0][0], apex[1] + far * dirs[0][1]],
            [apex[0] + far * dirs[1][0], apex[1] + far * dirs[1][1]],
        ];
        let (got, stats) = render_samples(t, cols, rows);
        assert_eq!(got, expected, "far = {far}");
        assert_eq!(stats.dropped_out_of_range, 0);
        // And the mirror image, all three far away.
        let huge = [[-far, -far], [far, -far * 0.5], [0.0, far]];
        let (got, _) = render_samples(huge, cols, rows);
        assert_eq!(
            got.len(),
            cols as usize * rows as usize,
            "far = {far}: covers the screen"
        );
    }
}

/// The sizes the sweeps use: every power of ten from 1e2 to 1e38, and
/// f32's largest.
fn sweep() -> Vec<f32> {
    (2..=38)
        .map(|e| format!("1e{e}").parse().unwrap())
        .chain([f32::MAX])
        .collect()
}

/// The samples a scene file covers, rendered `cols × rows` in half blocks
/// (square samples, so the projections keep 45° at 45°).
fn covered_by(src: &str, cols: u16, rows: u16) -> BTreeSet<(u32, u32)> {
    let scene = Scene::parse(src, "sweep.toml").unwrap();
    rendered(&scene, cols, rows, GlyphMode::Half).0
}

const PROJECTIONS: [&str; 3] = [
    "projection = \"none\"",
    "projection = \"orthographic\"",
    "projection = \"perspective\"",
];

#[test]
fn a_hypotenuse_through_the_centre_stays_there_from_1e2_to_f32_max_in_every_projection() {
    // Vertices (−s, −s), (s, −s), (−s, s): the hypotenuse runs through the
    // screen's centre for every s. The grid (41 × 24 samples) is chosen so
    // that no sample centre lies on it (checked), so the exact answer needs
    // no tie-break: the samples strictly on the (−s, −s) side.
    let (cols, rows) = (41u16, 12u16);
    let (w, h) = (cols as i64, 2 * rows as i64);
    for projection in PROJECTIONS {
        // The hypotenuse's direction on screen, from the camera's matrices:
        // (1, −1) in the world becomes (m00 − m01, m10 − m11) in clip space
        // (w is the same at every vertex), then the viewport's scale.
        let scene = Scene::parse(
            &format!("[camera]\n{projection}\n[[triangle]]\nvertices = [[-1.0,-1.0,0.0],[1.0,-1.0,0.0],[-1.0,1.0,0.0]]\n"),
            "s",
        )
        .unwrap();
        let aspect = cols as f32 * 0.5 / rows as f32;
        let m = scene.camera.view_projection(aspect).as_dmat4();
        let d = [
            (m.x_axis.x - m.y_axis.x) * w as f64,
            (m.x_axis.y - m.y_axis.y) * h as f64,
        ];
        let side = |u: f64, v: f64| d[0] * v - d[1] * u;
        // The interior's side: towards (−1, −1).
        let inner = side(
            -(m.x_axis.x + m.y_axis.x) * w as f64,
            -(m.x_axis.y + m.y_axis.y) * h as f64,
        )
        .signum();
        let mut expected = BTreeSet::new();
        for y in 0..h {
            for x in 0..w {
                let (u, v) = (
                    x as f64 + 0.5 - w as f64 / 2.0,
                    y as f64 + 0.5 - h as f64 / 2.0,
                );
                let e = side(u, v) / (d[0] * d[0] + d[1] * d[1]).sqrt();
                assert!(
                    e.abs() > 0.01,
                    "{projection}: sample ({x}, {y}) is on the line"
                );
                if e.signum() == inner {
                    expected.insert((x as u32, y as u32));
                }
            }
        }
        assert!(expected.len() > 400 && expected.len() < 600);
        for s in sweep() {
            let src = format!(
                "[camera]\n{projection}\n[[triangle]]\nvertices = [[-{s:e},-{s:e},0.0],[{s:e},-{s:e},0.0],[-{s:e},{s:e},0.0]]\n"
            );
            assert_eq!(
                covered_by(&src, cols, rows),
                expected,
                "{projection}, s = {s:e}"
            );
        }
    }
}

/// Rows `0..rows/2` of every column: the lower half of the screen.
fn lower_half(w: u32, h: u32) -> BTreeSet<(u32, u32)> {
    (0..h / 2)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .collect()
}

#[test]
fn a_floor_out_to_f32_max_fills_the_lower_half_exactly() {
    // The eye at (0, 0, 5), the floor at y = −1 reaching ±s in x and z:
    // each sample row below the centre sees it (at a distance of 2.5 to 58
    // units, within near and far, and within ±s for s ≥ 100); no row above
    // does. As two loose triangles, and as a mesh: a cube flattened into a
    // slab, scale = [s, 0.01, s].
    let (cols, rows) = (40u16, 12u16);
    let expected = lower_half(40, 24);
    for s in sweep() {
        let floor = format!(
            "[[triangle]]\nvertices = [[-{s:e},-1.0,-{s:e}],[{s:e},-1.0,-{s:e}],[{s:e},-1.0,{s:e}]]\n\
             [[triangle]]\nvertices = [[-{s:e},-1.0,-{s:e}],[{s:e},-1.0,{s:e}],[-{s:e},-1.0,{s:e}]]\n"
        );
        assert_eq!(covered_by(&floor, cols, rows), expected, "floor, s = {s:e}");
        let slab = format!(
            "[[mesh]]\nshape = \"cube\"\nscale = [{s:e}, 0.01, {s:e}]\ntranslate = [0.0, -1.006, 0.0]\n"
        );
        assert_eq!(covered_by(&slab, cols, rows), expected, "slab, s = {s:e}");
    }
}

/// A lit scene of overlapping, colour-interpolated triangles seen in
/// perspective, every length multiplied by `k`.
fn scene_at_scale(k: f32) -> String {
    let p = |x: f32, y: f32, z: f32| format!("[{:e},{:e},{:e}]", x * k, y * k, z * k);
    format!(
        "[camera]\neye = {}\ntarget = {}\nnear = {:e}\nfar = {:e}\n\
         [[triangle]]\nvertices = [{}, {}, {}]\ncolors = [\"#ff0000\", \"#00ff00\", \"#0000ff\"]\n\
         [[triangle]]\nvertices = [{}, {}, {}]\ncolor = \"#ffcc00\"\n\
         [[light]]\ndirection = [-1.0, -1.0, -1.0]\n",
        p(0.5, 1.0, 5.0),
        p(0.0, 0.0, 0.0),
        0.5 * k,
        50.0 * k,
        p(-1.5, -1.0, 0.0),
        p(1.5, -1.0, -1.0),
        p(0.0, 1.5, 0.5),
        p(-1.0, 1.0, -0.5),
        p(1.0, 0.8, 0.6),
        p(0.2, -1.2, 0.2),
    )
}

#[test]
fn cameras_are_judged_by_direction_and_relative_size() {
    // The same scene at every power-of-two scale from 2^-100 (1e-30) to
    // 2^100 (1e30): f32 arithmetic scales exactly by powers of two, so the
    // frames are identical, cell for cell, colours included.
    let opts = RenderOptions {
        cols: 40,
        rows: 14,
        glyphs: GlyphMode::Half,
        ..RenderOptions::default()
    };
    let frame = |k: f32| {
        let scene = Scene::parse(&scene_at_scale(k), "scaled.toml").unwrap();
        rastty::render(&scene, &opts)
    };
    let unit = frame(1.0);
    assert!(unit.cells().iter().filter(|c| c.bg.is_some()).count() > 50);
    for e in [-100, -60, -20, 20, 60, 100] {
        let scaled = frame(2f32.powi(e));
        assert_eq!(scaled.to_string(), unit.to_string(), "scale 2^{e}");
        assert!(scaled == unit, "scale 2^{e}: the colours differ");
    }
    // What is really wrong is said so.
    let err = |src: &str| Scene::parse(src, "c.toml").unwrap_err().to_string();
    let tri = "[[triangle]]\nvertices = [[0.0,0.0,0.0],[1.0,0.0,0.0],[0.0,1.0,0.0]]\n";
    assert!(
        err(&format!("[camera]\nnear = 1e-40\n{tri}")).contains("near = 1e-40 is subnormal"),
        "{}",
        err(&format!("[camera]\nnear = 1e-40\n{tri}"))
    );
    assert!(
        err(&format!(
            "[camera]\nprojection = \"orthographic\"\nheight = 1e-40\n{tri}"
        ))
        .contains("height = 1e-40 is too small")
    );
    assert!(
        err(&format!(
            "[camera]\neye = [0.0, 0.0, 1e30]\nup = [0.0, 0.0, 1.0]\n{tri}"
        ))
        .contains("up must not be parallel")
    );
    assert!(
        err(&format!(
            "[camera]\neye = [1e30, 0.0, 0.0]\ntarget = [1e30, 0.0, 0.0]\n{tri}"
        ))
        .contains("eye and target are the same point")
    );
    // An eye 1e30 away, or 1e-30 from its target, is not wrong.
    for eye in [
        "[0.0, 0.0, 1e30]",
        "[0.0, 0.0, 1e-30]",
        "[1e-30, 1e-30, 1e-30]",
    ] {
        Scene::parse(&format!("[camera]\neye = {eye}\n{tri}"), "c.toml").unwrap();
    }
}

/// A temporary directory of the test's own.
fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("rastty-hard-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The built-in cube as OBJ text, its top face cut into four triangles
/// around its centre, which is pushed in by `dent`, every position moved
/// by `offset`.
fn cube_obj(dent: f32, offset: Vec3) -> String {
    let cube = rastty::scene::Shape::Cube.mesh(Rgb::WHITE);
    let mut positions = cube.positions.clone();
    let mut faces = Vec::new();
    for pair in cube.faces.chunks(2) {
        let quad = [pair[0][0], pair[0][1], pair[0][2], pair[1][2]];
        if quad.iter().all(|&i| cube.positions[i as usize].y > 0.5) {
            positions.push(Vec3::new(0.0, 0.6 - dent, 0.0));
            let centre = positions.len() as u32 - 1;
            for k in 0..4 {
                faces.push([quad[k], quad[(k + 1) % 4], centre]);
            }
        } else {
            faces.extend_from_slice(pair);
        }
    }
    let mut text = String::new();
    for p in positions {
        let p = p + offset;
        text += &format!("v {:e} {:e} {:e}\n", p.x, p.y, p.z);
    }
    for f in faces {
        text += &format!("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
    }
    text
}

#[test]
fn a_dented_cube_far_from_the_origin_is_drawn_with_its_depth_test() {
    // Through a model file and a scene file, as a user would: the cube's
    // positions a million units out (where f32 steps by 1/16), its top
    // face dented by an eighth of a unit (a fifth of its half-width),
    // and `translate` bringing it back. The planner must see the dent.
    let dir = scratch("dent");
    let far = Vec3::new(1e6, 0.0, 0.0);
    std::fs::write(dir.join("dented.obj"), cube_obj(0.125, far)).unwrap();
    let src = "[[mesh]]\npath = \"dented.obj\"\ntranslate = [-1e6, 0.0, 0.0]\nrotate = [30.0, 40.0, 0.0]\n\
               [[light]]\ndirection = [-1.0, -1.0, -1.0]\n";
    let scene = Scene::parse_in(src, "dent.toml", Some(&dir)).unwrap();
    assert!(!scene.meshes[0].is_convex());
    let opts = RenderOptions {
        cols: 40,
        rows: 14,
        ..RenderOptions::default()
    };
    let mut planned = Renderer::new();
    planned.render(&scene, &opts);
    assert!(planned.plan().unwrap()[Effect::Depth].run);
    let mut full = Renderer::new();
    full.render(
        &scene,
        &RenderOptions {
            pipeline: rastty::Pipeline::Full,
            ..opts
        },
    );
    assert_eq!(planned.frame(), full.frame());
    // Undented it is convex, far out or not, and the depth test is skipped.
    std::fs::write(dir.join("cube.obj"), cube_obj(0.0, far)).unwrap();
    let cube = Scene::parse_in(&src.replace("dented", "cube"), "cube.toml", Some(&dir)).unwrap();
    assert!(cube.meshes[0].is_convex());
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn a_model_of_any_size_fits_the_view_the_same() {
    // The same model at every scale an f32 can hold, written exactly (the
    // scales are powers of two), fitted in f64: the same frame.
    let dir = scratch("fit");
    let opts = RenderOptions {
        cols: 40,
        rows: 14,
        ..RenderOptions::default()
    };
    let frame_at = |e: i32| {
        let k = 2f32.powi(e);
        let mut text = String::new();
        for (x, y, z) in [
            (-1.0f32, -0.5, 0.2),
            (1.0, -0.7, -0.3),
            (0.1, 1.2, 0.0),
            (0.3, 0.1, 0.9),
        ] {
            text += &format!("v {:e} {:e} {:e}\n", x * k, y * k, z * k);
        }
        text += "f 1 2 3\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";
        let path = dir.join(format!("m{e}.obj"));
        std::fs::write(&path, text).unwrap();
        rastty::render(&Scene::of_model(&path).unwrap(), &opts)
    };
    let unit = frame_at(0);
    let drawn = unit
        .cells()
        .iter()
        .filter(|c| c.ch != ' ' || c.bg.is_some());
    assert!(drawn.count() > 20);
    // 1.3e-23, 7.4e19, 1.3e30, and the largest power of two below f32's max.
    for e in [-76, 66, 100, 126] {
        let scaled = frame_at(e);
        assert_eq!(scaled.to_string(), unit.to_string(), "2^{e}");
        assert!(scaled == unit, "2^{e}: the colours differ");
    }
    std::fs::remove_dir_all(dir).ok();
}

// 7. NaN and infinity.

#[test]
fn nan_and_infinity_drop_the_primitive_and_are_counted() {
    let g = Grid::new(8, 8);
    let mut stats = RasterStats::default();
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        rasterize(
            [[1.0, 1.0], [bad, 2.0], [6.0, 6.0]],
            g,
            Cull::None,
            Traversal::Incremental,
            &mut stats,
            |_, _, _| panic!(),
        );
    }
    assert_eq!(stats.dropped_non_finite, 3);
    // Positions through the renderer: removed at the clip stage.
    for bad in [f32::NAN, f32::INFINITY] {
        let scene = Scene::in_canonical_cube(vec![Triangle {
            vertices: [
                Vec3::new(-0.5, -0.5, 0.0),
                Vec3::new(bad, 0.5, 0.0),
                Vec3::new(0.5, -0.5, 0.0),
            ],
            color: TriangleColor::Flat(Rgb::WHITE),
        }]);
        let mut r = Renderer::new();
        r.render(&scene, &RenderOptions::default());
        assert!(r.framebuffer().samples().iter().all(Option::is_none));
        assert_eq!(r.stats().clip_rejected, 1);
    }
    // Normals: a mesh with one NaN normal loses exactly the faces using it.
    let mut mesh = rastty::scene::Shape::Cube.mesh(Rgb::WHITE);
    mesh.geometry_mut().normals[0] = Vec3::NAN;
    let users = mesh.faces.iter().filter(|f| f.contains(&0)).count() as u64;
    let mut scene = Scene::of_mesh(mesh);
    scene.meshes[0].cull = Cull::None;
    let mut r = Renderer::new();
    r.render(&scene, &RenderOptions::default());
    assert_eq!(r.stats().dropped_non_finite_normals, users);
}

// 8. Tiny triangles and slivers.

#[test]
fn tiny_triangles_and_slivers() {
    let g = Grid::new(8, 8);
    // Smaller than a sample, around a sample centre: covers it; beside it:
    // nothing.
    assert_eq!(
        covered([[2.4, 3.4], [2.6, 3.45], [2.5, 3.6]], g),
        set([(2, 3)])
    );
    assert!(covered([[2.6, 3.6], [2.9, 3.6], [2.7, 3.9]], g).is_empty());
    // 1e-3 by 1000 samples, across a row of centres: thinner than the
    // 1/256 snap, it snaps to a line (zero area) and draws nothing.
    let wide = Grid::new(1000, 4);
    let mut stats = RasterStats::default();
    let sliver = [
        [0.0, 1.5 - 0.0005],
        [1000.0, 1.5 - 0.0005],
        [1000.0, 1.5 + 0.0005],
    ];
    rasterize(
        sliver,
        wide,
        Cull::None,
        Traversal::Incremental,
        &mut stats,
        |_, _, _| panic!("drew a sub-snap sliver"),
    );
    assert_eq!(stats.dropped_degenerate, 1);
    // One snap unit thick, its top edge on the centres of row 1: it owns
    // all 1000 of them (a top edge), and nothing else.
    let top = covered(
        [[0.0, 1.5], [500.0, 1.5 - 1.0 / 256.0], [1000.0, 1.5]],
        wide,
    );
    assert_eq!(top, set((0..1000).map(|x| (x, 1))));
    // The same sliver upside down: its edge on the centres is a bottom
    // edge, which owns none of them.
    assert!(
        covered(
            [[0.0, 1.5], [1000.0, 1.5], [500.0, 1.5 + 1.0 / 256.0]],
            wide
        )
        .is_empty()
    );
}

#[test]
fn the_near_touching_pair_leaves_no_hole_on_the_diagonal() {
    let g = Grid::new(8, 8);
    // 0.49993896484375 and 6.50006103515625, exactly.
    let (lo, hi): (f32, f32) = (0.5 - 1.0 / 16384.0, 6.5 + 1.0 / 16384.0);
    assert_eq!((lo as f64, hi as f64), (0.49993896484375, 6.50006103515625));
    let a = [0.5, lo];
    let b = [0.5, 6.5];
    let c = [hi, lo];
    let d = [hi, 6.5];
    let c = counts(&[[a, b, c], [b, d, c]], g);
    // The pair snaps to the square (0.5, 0.5)–(6.5, 6.5): columns 0–5, rows
    // 1–6, every sample exactly once, the diagonal's included.
    for y in 0..8 {
        for x in 0..8 {
            let want = ((0..6).contains(&x) && (1..7).contains(&y)) as u32;
            assert_eq!(c[(y * 8 + x) as usize], want, "({x}, {y})");
        }
    }
}

// 9. Perspective-correct interpolation.

// Perspective-correct colours against an f64 ray cast: `rastty bench`'s
// own measure, tested beside it (cli/src/bench/).

// 10. Depth.

#[test]
fn depth_stays_within_its_vertices_and_coplanar_overlaps_resolve_the_same_way() {
    // Two overlapping coplanar triangles of different colours on a tilted
    // plane, over a third farther back: the first listed wins wherever they
    // overlap, every time, and nothing of the back one shows between them.
    let plane = |x: f32, y: f32| Vec3::new(x, y, -3.0 + 0.4 * x + 0.2 * y);
    let a = Triangle {
        vertices: [plane(-1.5, -1.0), plane(1.0, -1.0), plane(-0.2, 1.2)],
        color: TriangleColor::Flat(Rgb::new(250, 0, 0)),
    };
    let b = Triangle {
        vertices: [plane(-1.0, -1.2), plane(1.5, -0.8), plane(0.6, 1.0)],
        color: TriangleColor::Flat(Rgb::new(0, 250, 0)),
    };
    let back = Triangle {
        vertices: [
            Vec3::new(-5.0, -5.0, -6.0),
            Vec3::new(5.0, -5.0, -6.0),
            Vec3::new(0.0, 5.0, -6.0),
        ],
        color: TriangleColor::Flat(Rgb::new(0, 0, 250)),
    };
    let scene = |tris| Scene {
        camera: Camera::default(),
        triangles: tris,
        ..Scene::default()
    };
    let opts = RenderOptions {
        cols: 60,
        rows: 24,
        glyphs: GlyphMode::Block,
        ..RenderOptions::default()
    };
    let mut r = Renderer::new();
    // Rotating each triangle's vertices changes nothing either.
    let rot = |t: Triangle| Triangle {
        vertices: [t.vertices[1], t.vertices[2], t.vertices[0]],
        ..t
    };
    let rotated = Renderer::new()
        .render(&scene(vec![back, rot(a), rot(b)]), &opts)
        .clone();
    let first = r.render(&scene(vec![back, a, b]), &opts).clone();
    let again = r.render(&scene(vec![back, a, b]), &opts).clone();
    assert_eq!(first, again);
    assert_eq!(first, rotated);
    let fb = r.framebuffer();
    let grid = fb.grid();
    let (mut overlap, mut zs) = (0, Vec::new());
    // Coverage of a and b alone, to find their overlap.
    let alone = |t: Triangle| {
        let mut r = Renderer::new();
        r.render(&scene(vec![t]), &opts);
        r.framebuffer().samples().to_vec()
    };
    let (sa, sb) = (alone(a), alone(b));
    for y in 0..grid.height {
        for x in 0..grid.width {
            let i = (y * grid.width + x) as usize;
            if sa[i].is_some() && sb[i].is_some() {
                overlap += 1;
                let c = fb.get(x, y);
                assert!(
                    c == sa[i] || c == sb[i],
                    "one of the two coplanar triangles shows"
                );
            }
            if sa[i].is_some() || sb[i].is_some() {
                assert_ne!(
                    fb.get(x, y).map(|c| c.to_srgb()),
                    Some(Rgb::new(0, 0, 250)),
                    "no speckle of the back triangle at ({x}, {y})"
                );
                zs.push(fb.depth(x, y));
            }
        }
    }
    assert!(overlap > 20);
    // Depths within the vertices' range (in the canonical cube).
    let vp = Camera::default().view_projection(opts.aspect());
    let vz: Vec<f32> = [a, b]
        .iter()
        .flat_map(|t| t.vertices)
        .map(|p| {
            let c = vp * p.extend(1.0);
            c.z / c.w
        })
        .collect();
    let (lo, hi) = (
        vz.iter().copied().fold(f32::INFINITY, f32::min),
        vz.iter().copied().fold(f32::NEG_INFINITY, f32::max),
    );
    assert!(zs.iter().all(|&z| z >= lo && z <= hi), "{lo}..{hi}");
}

#[test]
fn a_reused_renderer_draws_the_same_frame_as_a_fresh_one() {
    // Rendering the same frame twice, with a fresh renderer and a reused
    // one, is bit for bit the same. (The same with any thread count:
    // `tests/render/plan.rs`, `random_scenes_are_the_same_with_any_thread_count`.)
    let scene = rastty::scene::default_scene();
    let opts = RenderOptions {
        cols: 50,
        rows: 16,
        ..RenderOptions::default()
    };
    let mut reused = Renderer::new();
    reused.render(
        &scene,
        &RenderOptions {
            cols: 13,
            rows: 7,
            ..opts
        },
    );
    let a = reused.render(&scene, &opts).clone();
    assert_eq!(a, rastty::render(&scene, &opts));
    // A framing camera is placed once for an aspect and kept while neither
    // changes: orbited and zoomed, at the same aspect, it is placed anew.
    let mut model = Scene::of_mesh(rastty::scene::Shape::Torus.mesh(rastty::color::Rgb::WHITE));
    assert!(model.camera.fit.is_some());
    reused.render(&model, &opts);
    model.camera = model.camera.orbited(40.0, 20.0, 0.7);
    let b = reused.render(&model, &opts).clone();
    assert_eq!(b, rastty::render(&model, &opts));
    assert_ne!(
        b,
        rastty::render(
            &Scene::of_mesh(rastty::scene::Shape::Torus.mesh(rastty::color::Rgb::WHITE)),
            &opts
        )
    );
}
