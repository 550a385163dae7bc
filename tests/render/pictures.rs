//! Pictures people trust: light adds in linear light, palettes keep greys
//! grey, smooth surfaces have no seams, and a model named alone is seen
//! well. End to end, through scene files, model files and the renderer.

use std::path::{Path, PathBuf};

use rastty::color::Lin;
use rastty::scene::{LoadOptions, Scene};
use rastty::transform::Axis;
use rastty::{Frame, GlyphMode, RenderOptions, Renderer, color::ColorDepth, color::Rgb, render};

/// A fresh directory for one test's files.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn block(cols: u16, rows: u16) -> RenderOptions {
    RenderOptions {
        cols,
        rows,
        glyphs: GlyphMode::Block,
        color: ColorDepth::TrueColor,
        ..RenderOptions::default()
    }
}

/// A white triangle facing the camera, lit by one white light with no
/// ambient, travelling `direction`.
fn lit_triangle(direction: [f32; 3]) -> Scene {
    let src = format!(
        r##"
[camera]
projection = "orthographic"
height = 2.0
[[triangle]]
vertices = [[-3.0, -3.0, 0.0], [3.0, -3.0, 0.0], [0.0, 3.0, 0.0]]
color = "#ffffff"
[[light]]
direction = [{}, {}, {}]
ambient = 0.0
"##,
        direction[0], direction[1], direction[2]
    );
    Scene::parse(&src, "lit.toml").unwrap()
}

#[test]
fn light_adds_in_linear_light_half_the_light_is_bc() {
    // Head on: all the light, #ffffff.
    let f = render(&lit_triangle([0.0, 0.0, -1.0]), &block(8, 4));
    assert_eq!(f.get(4, 2).bg, Some(Rgb::WHITE));
    // At 60° to the normal: cos 60° = half the light, which is sRGB 188
    // (#bcbcbc), not 128.
    let (s, c) = 60f32.to_radians().sin_cos();
    let f = render(&lit_triangle([-s, 0.0, -c]), &block(8, 4));
    let shown = f.get(4, 2).bg.unwrap();
    assert!(
        shown.0.iter().all(|&v| v.abs_diff(0xbc) <= 1),
        "{shown} at 60°"
    );
}

#[test]
fn mtl_kd_is_linear_unless_a_scene_says_srgb() {
    let dir = scratch("kd");
    std::fs::write(dir.join("m.mtl"), "newmtl m\nKd 0.5 0.5 0.5\n").unwrap();
    std::fs::write(
        dir.join("t.obj"),
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n",
    )
    .unwrap();
    let colour = |options: &LoadOptions| {
        let scene = Scene::of_model_within(&dir.join("t.obj"), options).unwrap();
        scene.meshes[0].face_color(0).to_srgb()
    };
    assert_eq!(colour(&LoadOptions::default()), Rgb([0xbc; 3]));
    let srgb = LoadOptions {
        mtl_colors: rastty::color::ColorSpace::Srgb,
        ..LoadOptions::default()
    };
    // 0.5 of 255 is 127.5, which rounds down through linear light.
    assert_eq!(colour(&srgb), Rgb([127; 3]));
}

/// The SGR colour parameters of an ANSI stream (30–37, 90–97, 40–47,
/// 100–107 for 16 colours).
fn sgr_codes(ansi: &str) -> std::collections::BTreeSet<u32> {
    ansi.split("\x1b[")
        .skip(1)
        .filter_map(|s| s.split_once('m').map(|(p, _)| p))
        .flat_map(|p| p.split(';').filter_map(|v| v.parse().ok()))
        .collect()
}

#[test]
fn a_grey_ramp_in_16_colours_is_black_the_two_greys_and_white() {
    // A quad from black on the left to white on the right, unlit.
    let src = r##"
[camera]
projection = "none"
[[triangle]]
vertices = [[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [1.0, 1.0, 0.0]]
colors = ["#000000", "#ffffff", "#ffffff"]
[[triangle]]
vertices = [[-1.0, -1.0, 0.0], [1.0, 1.0, 0.0], [-1.0, 1.0, 0.0]]
colors = ["#000000", "#ffffff", "#000000"]
"##;
    let scene = Scene::parse(src, "ramp.toml").unwrap();
    let frame = render(&scene, &block(64, 8));
    for dither in [rastty::color::Dither::None, rastty::color::Dither::Ordered] {
        let palette = rastty::color::Palette {
            depth: ColorDepth::Ansi16,
            dither,
            ..Default::default()
        };
        let mut out = Vec::new();
        rastty::encode::write_lines(
            &frame,
            palette,
            Default::default(),
            &mut Vec::new(),
            &mut out,
        )
        .unwrap();
        let codes = sgr_codes(&String::from_utf8(out).unwrap());
        // Black 30/40, light grey 37/47, dark grey 90/100, white 97/107,
        // and the resets.
        let allowed = [0, 30, 37, 39, 40, 47, 49, 90, 97, 100, 107];
        assert!(
            codes.iter().all(|c| allowed.contains(c)),
            "{dither:?}: {codes:?}"
        );
        assert!(codes.contains(&100) && codes.contains(&47), "{codes:?}");
    }
}

/// A UV sphere as an OBJ file: `seams` duplicates the vertices along the
/// seam and at the poles, as exporters write them (one vertex per texture
/// coordinate); otherwise every position is one vertex.
fn sphere_obj(seams: bool) -> String {
    let (m, n) = (32usize, 16usize);
    let mut out = String::new();
    let mut index = std::collections::HashMap::new();
    let mut count = 0;
    let mut id = |i: usize, j: usize, out: &mut String| -> usize {
        // The same position: the seam's ends and every vertex of a pole.
        let key = if seams {
            (i, j)
        } else if j == 0 || j == n {
            (0, j)
        } else {
            (i % m, j)
        };
        *index.entry(key).or_insert_with(|| {
            let (u, v) = (
                std::f64::consts::TAU * (i % m) as f64 / m as f64,
                std::f64::consts::PI * j as f64 / n as f64,
            );
            let ring = if j == 0 || j == n { 0.0 } else { v.sin() };
            out.push_str(&format!(
                "v {:.6} {:.6} {:.6}\n",
                ring * u.cos(),
                -v.cos(),
                -ring * u.sin()
            ));
            count += 1;
            count
        })
    };
    let mut faces = String::new();
    for j in 0..n {
        for i in 0..m {
            let [a, b, c, d] =
                [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)].map(|(i, j)| id(i, j, &mut out));
            if j == 0 {
                faces.push_str(&format!("f {a} {c} {d}\n"));
            } else if j == n - 1 {
                faces.push_str(&format!("f {a} {b} {c}\n"));
            } else {
                faces.push_str(&format!("f {a} {b} {c} {d}\n"));
            }
        }
    }
    out + &faces
}

#[test]
fn a_sphere_with_duplicated_seams_renders_as_the_welded_one() {
    let dir = scratch("seams");
    let frame = |seams: bool| {
        let path = dir.join(format!("sphere-{seams}.obj"));
        std::fs::write(&path, sphere_obj(seams)).unwrap();
        let scene = Scene::of_model(&path).unwrap();
        let mut frames = Vec::new();
        // The seam turned towards the viewer and away.
        for yaw in [0.0, 90.0, 180.0, 270.0] {
            let opts = RenderOptions {
                turn: glam::Vec3::new(0.0, yaw, 0.0),
                glyphs: GlyphMode::Half,
                ..block(60, 24)
            };
            frames.push(render(&scene, &opts));
        }
        frames
    };
    let (welded, seamed) = (frame(false), frame(true));
    assert_eq!(welded, seamed);
    // And the welded one is smooth: no two neighbouring cells in a row
    // differ by more than a shading step would.
    for f in &welded {
        for y in 0..f.rows() {
            for x in 1..f.cols() {
                let (a, b) = (f.get(x - 1, y).bg, f.get(x, y).bg);
                if let (Some(a), Some(b)) = (a, b)
                    && a != Rgb::BLACK
                    && b != Rgb::BLACK
                {
                    let d = a.0.iter().zip(b.0).map(|(p, q)| p.abs_diff(q)).max();
                    assert!(d <= Some(24), "a jump of {d:?} at ({x}, {y})");
                }
            }
        }
    }
}

#[test]
fn the_crease_angle_decides_which_edges_stay_sharp() {
    let normals = |crease: f32| {
        let options = LoadOptions {
            crease,
            ..LoadOptions::default()
        };
        let (g, _) = rastty::scene::load_geometry(Path::new("cube"), &options).unwrap();
        let mut set: Vec<[u32; 3]> = g
            .normals
            .iter()
            .map(|n| n.to_array().map(|v| (v * 1000.0).round() as i32 as u32))
            .collect();
        set.sort();
        set.dedup();
        set.len()
    };
    // Below 90°, a cube's edges are creases: six face normals. Above, each
    // corner is smooth: eight corner normals.
    assert_eq!(normals(60.0), 6);
    assert_eq!(normals(100.0), 8);
}

/// A box 0.5 × 1 × 2 (x × y × z) as ASCII STL, z up.
fn box_stl() -> String {
    let (x, y, z) = (0.25f32, 0.5, 1.0);
    let c = |i: u32| {
        [
            (i & 1) as f32 * 2.0 - 1.0,
            (i >> 1 & 1) as f32 * 2.0 - 1.0,
            (i >> 2 & 1) as f32 * 2.0 - 1.0,
        ]
    };
    let faces = [
        [0, 2, 3],
        [0, 3, 1],
        [4, 5, 7],
        [4, 7, 6],
        [0, 1, 5],
        [0, 5, 4],
        [2, 6, 7],
        [2, 7, 3],
        [0, 4, 6],
        [0, 6, 2],
        [1, 3, 7],
        [1, 7, 5],
    ];
    let mut s = String::from("solid box\n");
    for f in faces {
        s.push_str("facet normal 0 0 0\nouter loop\n");
        for i in f {
            let p = c(i);
            s.push_str(&format!("vertex {} {} {}\n", p[0] * x, p[1] * y, p[2] * z));
        }
        s.push_str("endloop\nendfacet\n");
    }
    s + "endsolid box\n"
}

#[test]
fn an_stl_is_z_up_and_up_says_otherwise() {
    let dir = scratch("up");
    std::fs::write(dir.join("box.stl"), box_stl()).unwrap();
    // The same box written y-up as OBJ: (x, y, z) → (x, z, −y).
    let stl = stl_text_to_obj(&box_stl());
    std::fs::write(dir.join("box.obj"), stl).unwrap();
    let opts = block(40, 20);
    let of = |name: &str, up: Option<Axis>| {
        let options = LoadOptions {
            up,
            ..LoadOptions::default()
        };
        render(
            &Scene::of_model_within(&dir.join(name), &options).unwrap(),
            &opts,
        )
    };
    let stl_default = of("box.stl", None);
    assert_eq!(
        stl_default,
        of("box.obj", None),
        "z-up STL shows as the y-up OBJ"
    );
    assert_eq!(stl_default, of("box.stl", Some(Axis::Z)));
    // Read y-up, the box lies on its side: wider than tall on screen.
    let (w, h) = extent(&of("box.stl", Some(Axis::Y)));
    let (w_up, h_up) = extent(&stl_default);
    assert!(h_up > w_up && w > h, "{w_up}×{h_up} up, {w}×{h} lying");
}

/// The OBJ of an ASCII STL's facets, turned from z-up to y-up.
fn stl_text_to_obj(stl: &str) -> String {
    let mut out = String::new();
    let mut n = 0;
    for line in stl.lines() {
        if let Some(rest) = line.strip_prefix("vertex ") {
            let v: Vec<f32> = rest.split(' ').map(|x| x.parse().unwrap()).collect();
            out.push_str(&format!("v {} {} {}\n", v[0], v[2], -v[1]));
            n += 1;
            if n % 3 == 0 {
                out.push_str(&format!("f {} {} {}\n", n - 2, n - 1, n));
            }
        }
    }
    out
}

/// The columns and rows a frame's drawn cells span.
fn extent(f: &Frame) -> (u16, u16) {
    let (mut x0, mut x1, mut y0, mut y1) = (u16::MAX, 0, u16::MAX, 0);
    for y in 0..f.rows() {
        for x in 0..f.cols() {
            if f.get(x, y).bg.is_some() {
                (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
            }
        }
    }
    (x1.saturating_sub(x0) + 1, y1.saturating_sub(y0) + 1)
}

#[test]
fn an_open_mesh_shows_both_sides_and_a_closed_one_is_culled() {
    let dir = scratch("open");
    std::fs::write(
        dir.join("tri.obj"),
        "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n",
    )
    .unwrap();
    let scene = Scene::of_model(&dir.join("tri.obj")).unwrap();
    assert_eq!(scene.meshes[0].cull, rastty::scene::Cull::None);
    for yaw in [0.0, 180.0] {
        let opts = RenderOptions {
            turn: glam::Vec3::new(0.0, yaw, 0.0),
            ..block(20, 10)
        };
        let f = render(&scene, &opts);
        assert!(
            extent(&f).0 > 1,
            "the triangle's side at yaw {yaw} is drawn"
        );
    }
    let cube = Scene::of_model(Path::new("cube")).unwrap();
    assert_eq!(cube.meshes[0].cull, rastty::scene::Cull::Back);
}

#[test]
fn a_model_named_alone_fills_90_percent_of_the_limiting_dimension() {
    // A cube: its corners are its outline, and turned about y they sweep
    // little more than the cube itself covers from a three-quarter view.
    for (cols, rows) in [(120u16, 40u16), (40, 40), (200, 30)] {
        let scene = Scene::of_model(Path::new("cube")).unwrap();
        let opts = RenderOptions {
            glyphs: GlyphMode::Half,
            ..block(cols, rows)
        };
        let mut r = Renderer::new();
        r.render(&scene, &opts);
        let fb = r.framebuffer();
        let g = fb.grid();
        let (mut x0, mut x1, mut y0, mut y1) = (u32::MAX, 0, u32::MAX, 0);
        for y in 0..g.height {
            for x in 0..g.width {
                if fb.get(x, y).is_some() {
                    (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
                }
            }
        }
        let fw = (x1 - x0 + 1) as f32 / g.width as f32;
        let fh = (y1 - y0 + 1) as f32 / g.height as f32;
        let fill = fw.max(fh);
        // 90 % (to a sample) where the height limits; where the width does,
        // a little less: the corners turned about y sweep a little wider
        // than the cube shows from one side.
        let want = if fh >= fw { 0.88..=0.91 } else { 0.84..=0.91 };
        assert!(want.contains(&fill), "{cols}×{rows}: {fw} × {fh}");
    }
}

#[test]
fn the_light_rig_neither_washes_out_nor_goes_black() {
    let scene = Scene::of_model(Path::new("sphere")).unwrap();
    let mut r = Renderer::new();
    r.render(&scene, &block(80, 40));
    let lights: Vec<u8> = r
        .framebuffer()
        .samples()
        .iter()
        .flatten()
        .map(|c| Lin::to_srgb(*c).0[1])
        .collect();
    let (lo, hi) = (*lights.iter().min().unwrap(), *lights.iter().max().unwrap());
    // A #cccccc sphere: its brightest side well below white, its darkest
    // far from black.
    assert!((170..=200).contains(&hi), "brightest {hi}");
    assert!((60..=120).contains(&lo), "darkest {lo}");
}

#[test]
fn a_rim_light_outlines_a_black_model_and_leaves_its_middle_black() {
    let scene = Scene::of_mesh(rastty::scene::Shape::Sphere.mesh(Rgb::BLACK));
    let opts = |rim| RenderOptions {
        rim,
        ..block(24, 12)
    };
    let plain = render(&scene, &opts(None));
    let rimmed = render(&scene, &opts(Some(Rgb::WHITE)));
    // The middle row, left to right: the sphere's cells, drawn.
    let row = |f: &Frame| -> Vec<Rgb> { (0..24).filter_map(|x| f.get(x, 6).bg).collect() };
    let (dark, lit) = (row(&plain), row(&rimmed));
    assert_eq!(dark.len(), lit.len());
    assert!(dark.len() >= 6, "{dark:?}");
    // Without a rim, a black sphere on the terminal's black is black
    // throughout: its silhouette is lost.
    assert!(dark.iter().all(|&c| c == Rgb::BLACK), "{dark:?}");
    // With one, the middle (facing the eye) stays black and the light grows
    // towards either edge, where the sphere turns away.
    let mid = lit.len() / 2;
    assert_eq!(lit[mid], Rgb::BLACK);
    let grey = |c: Rgb| c.0[1];
    assert!(
        grey(lit[0]) > grey(lit[2]) && grey(lit[2]) >= grey(lit[mid]),
        "{lit:?}"
    );
    let last = lit.len() - 1;
    assert!(grey(lit[last]) > grey(lit[last - 2]), "{lit:?}");
    // The outermost cells, sampled a little inside the true edge: about
    // half the rim's light in sRGB.
    assert_eq!(
        (lit[0], lit[last]),
        (Rgb([122; 3]), Rgb([120; 3])),
        "{lit:?}"
    );
}
