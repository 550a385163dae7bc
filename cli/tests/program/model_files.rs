//! Model and scene files as people have them: every valid file loads, as
//! it is meant; polygons are cut without covering what they do not; hostile
//! files are refused before a byte is read; nothing read is lost without a
//! word. Through the loaders the command line uses (and the binary itself
//! where what matters is the exit, the message or the memory).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use glam::Vec3;
use rastty::color::Lin;
use rastty::scene::Geometry;
use rastty::scene::{Scene, obj, stl};

/// A fresh directory for one test's files.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn load(src: &str) -> obj::Loaded {
    obj::parse(src.as_bytes(), "t.obj", Path::new(".")).unwrap_or_else(|e| panic!("{e}"))
}

fn error(src: &str) -> String {
    obj::parse(src.as_bytes(), "t.obj", Path::new("."))
        .unwrap_err()
        .to_string()
}

fn rastty(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rastty"))
        .args(args)
        .output()
        .expect("runs")
}

/// Runs the binary on arguments that must fail with one `error:` line;
/// returns the line.
fn fails(args: &[&str]) -> String {
    let out = rastty(args);
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
    assert!(out.stdout.is_empty(), "{args:?}");
    assert_eq!(err.lines().count(), 1, "{err}");
    err.trim_end().to_string()
}

const TRIANGLE: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

// --- 5. Every valid file loads ---------------------------------------------

#[test]
fn a_comment_after_data_is_a_comment() {
    let m = load("v 0 0 0 # origin\nv 1 0 0\nv 0 1 0#no space\nf 1 2 3 # tri\n");
    assert_eq!(m.geometry.faces, vec![[0, 1, 2]]);
    assert_eq!(m.geometry.positions[2], Vec3::new(0.0, 1.0, 0.0));
}

#[test]
fn a_byte_order_mark_and_tabs_after_keywords_are_read_past() {
    let m = load("\u{feff}v\t0 0 0\nv\t1\t0\t0\r\nv 0 1 0\nf\t1 2 3\n");
    assert_eq!(m.geometry.faces.len(), 1);
    assert_eq!(m.geometry.positions[1], Vec3::X);
}

#[test]
fn texture_coordinates_of_one_to_three_numbers_are_read() {
    let m = load(&format!(
        "{TRIANGLE}vt 0.5\nvt 0.5 0.25\nvt 0 1 0\nf 1/1 2/2 3/3\n"
    ));
    assert_eq!(m.geometry.faces.len(), 1);
    assert_eq!(
        error(&format!("{TRIANGLE}vt\nf 1 2 3\n")),
        "t.obj:4:1: `vt` needs at least 1 number"
    );
}

#[test]
fn a_vertex_with_w_or_with_a_colour_is_read_and_the_colours_used() {
    let m = load("v 0 0 0 1\nv 1 0 0 1.0\nv 0 1 0 0.5\nf 1 2 3\n");
    assert_eq!(m.geometry.positions[1], Vec3::X);
    assert_eq!(m.geometry.colors, None);
    let m = load("v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n");
    assert_eq!(
        m.geometry.colors,
        Some(vec![
            Lin([65535, 0, 0]),
            Lin([0, 65535, 0]),
            Lin([0, 0, 65535])
        ])
    );
    // And they reach the picture: unlit, the frame has cells of mostly
    // red, green and blue near the corners (blended in linear light, a
    // corner's other channels rise quickly in sRGB).
    let dir = scratch("vertex-colours");
    let path = dir.join("rgb.obj");
    std::fs::write(
        &path,
        "v -1 -1 0 1 0 0\nv 1 -1 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n",
    )
    .unwrap();
    let out = rastty(&[
        "render",
        path.to_str().unwrap(),
        "--shading",
        "none",
        "--color",
        "truecolor",
        "--glyphs",
        "block",
        "--cols",
        "40",
        "--rows",
        "20",
    ]);
    let frame = String::from_utf8(out.stdout).unwrap();
    let colours: Vec<[u8; 3]> = frame
        .split("\x1b[")
        .filter_map(|s| s.strip_prefix("38;2;").or_else(|| s.strip_prefix("48;2;")))
        .filter_map(|s| {
            let mut it = s.split([';', 'm']).map(|v| v.parse::<u8>().ok());
            Some([it.next()??, it.next()??, it.next()??])
        })
        .collect();
    for k in 0..3 {
        assert!(
            colours
                .iter()
                .any(|c| c[k] >= 200 && c[(k + 1) % 3] < 100 && c[(k + 2) % 3] < 100),
            "no cell near channel {k}: {colours:?}"
        );
    }
    // x y z w r g b: the colour after the w.
    let m = load("v 0 0 0 1 1 0 0\nv 1 0 0 1 1 0 0\nv 0 1 0 1 1 0 0\nf 1 2 3\n");
    assert_eq!(m.geometry.colors, Some(vec![Lin([65535, 0, 0]); 3]));
}

#[test]
fn mtllib_names_several_libraries() {
    let dir = scratch("mtllib");
    std::fs::write(dir.join("a.mtl"), "newmtl red\nKd 1 0 0\n").unwrap();
    std::fs::write(dir.join("b.mtl"), "newmtl blue\nKd 0 0 1\n").unwrap();
    std::fs::write(dir.join("my colours.mtl"), "newmtl green\nKd 0 1 0\n").unwrap();
    let src = format!(
        "mtllib a.mtl b.mtl\nmtllib my colours.mtl\n{TRIANGLE}v 1 1 0\nusemtl red\nf 1 2 3\nusemtl blue\nf 2 4 3\nusemtl green\nf 1 2 4\n"
    );
    let m = obj::parse(src.as_bytes(), "t.obj", &dir).unwrap();
    let g = &m.geometry;
    assert_eq!(g.face_color(0, Lin::WHITE), Lin([65535, 0, 0]));
    assert_eq!(g.face_color(1, Lin::WHITE), Lin([0, 0, 65535]));
    assert_eq!(g.face_color(2, Lin::WHITE), Lin([0, 65535, 0]));
    let m = obj::parse(
        b"mtllib a.mtl none.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
        "t.obj",
        &dir,
    )
    .unwrap();
    assert_eq!(
        m.notes,
        ["t.obj:1:8: material library \"a.mtl none.mtl\" not found: drawn in the default colour"]
    );
}

#[test]
fn a_backslash_separates_folders_as_windows_tools_write_them() {
    let dir = scratch("backslash");
    std::fs::create_dir_all(dir.join("mats")).unwrap();
    std::fs::create_dir_all(dir.join("model")).unwrap();
    std::fs::write(dir.join("mats/a.mtl"), "newmtl red\nKd 1 0 0\n").unwrap();
    let src = format!("mtllib mats\\a.mtl\n{TRIANGLE}usemtl red\nf 1 2 3\n");
    let m = obj::parse(src.as_bytes(), "t.obj", &dir).unwrap();
    assert_eq!(m.geometry.face_color(0, Lin::WHITE), Lin([65535, 0, 0]));
    assert!(m.notes.is_empty(), "{:?}", m.notes);
    // `..\` climbs out of the folder, as `../` does: said.
    let src = format!("mtllib ..\\mats\\a.mtl\n{TRIANGLE}usemtl red\nf 1 2 3\n");
    let m = obj::parse(src.as_bytes(), "t.obj", &dir.join("model")).unwrap();
    assert_eq!(m.geometry.face_color(0, Lin::WHITE), Lin([65535, 0, 0]));
    assert_eq!(
        m.notes,
        ["t.obj: \"..\\mats\\a.mtl\" is read from outside its folder"]
    );
    // A file whose name holds the backslash is read first.
    std::fs::write(dir.join("mats\\a.mtl"), "newmtl red\nKd 0 0 1\n").unwrap();
    let src = format!("mtllib mats\\a.mtl\n{TRIANGLE}usemtl red\nf 1 2 3\n");
    let m = obj::parse(src.as_bytes(), "t.obj", &dir).unwrap();
    assert_eq!(m.geometry.face_color(0, Lin::WHITE), Lin([0, 0, 65535]));
}

#[test]
fn a_name_in_another_case_is_read_with_a_note() {
    // A model made where case does not matter names `mats/A.MTL`; the
    // folder holds `Mats/a.mtl`.
    let dir = scratch("case");
    std::fs::create_dir_all(dir.join("Mats")).unwrap();
    std::fs::write(dir.join("Mats/a.mtl"), "newmtl red\nKd 1 0 0\n").unwrap();
    let src = format!("mtllib mats\\A.MTL\n{TRIANGLE}usemtl red\nf 1 2 3\n");
    let m = obj::parse(src.as_bytes(), "t.obj", &dir).unwrap();
    assert_eq!(m.geometry.face_color(0, Lin::WHITE), Lin([65535, 0, 0]));
    assert_eq!(
        m.notes,
        ["t.obj: \"mats\\A.MTL\" is read as \"Mats/a.mtl\", its name in another case"]
    );
    // A name that is there as written is read without a word.
    std::fs::write(dir.join("A.MTL"), "newmtl red\nKd 0 0 1\n").unwrap();
    std::fs::write(dir.join("a.mtl"), "newmtl red\nKd 0 1 0\n").unwrap();
    let src = format!("mtllib A.MTL\n{TRIANGLE}usemtl red\nf 1 2 3\n");
    let m = obj::parse(src.as_bytes(), "t.obj", &dir).unwrap();
    assert_eq!(m.geometry.face_color(0, Lin::WHITE), Lin([0, 0, 65535]));
    assert!(m.notes.is_empty(), "{:?}", m.notes);
}

#[test]
fn a_material_no_library_defines_is_noted_once() {
    let dir = scratch("unknown-material");
    std::fs::write(dir.join("a.mtl"), "newmtl red\nKd 1 0 0\n").unwrap();
    let faces = "f 1 2 3\n";
    let src = format!(
        "mtllib a.mtl\n{TRIANGLE}usemtl blue\n{faces}usemtl red\n{faces}usemtl green\n{faces}usemtl blue\n{faces}"
    );
    let m = obj::parse(src.as_bytes(), "t.obj", &dir).unwrap();
    let g = &m.geometry;
    assert_eq!(g.face_color(0, Lin::WHITE), Lin::WHITE);
    assert_eq!(g.face_color(1, Lin::WHITE), Lin([65535, 0, 0]));
    assert_eq!(
        m.notes,
        [
            "t.obj:5:8: material \"blue\" is in none of the material libraries read (nor is 1 other name `usemtl` gives): drawn in the default colour"
        ]
    );
}

const FACET: &str = "facet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n endloop\nendfacet\n";

#[test]
fn an_ascii_stl_solid_without_a_name_loads() {
    let m = stl::parse(format!("solid\n{FACET}endsolid\n").as_bytes(), "t.stl").unwrap();
    assert_eq!(m.geometry.faces.len(), 1);
    let m = stl::parse(
        format!("solid part 7\n{FACET}endsolid part 7\n").as_bytes(),
        "t.stl",
    )
    .unwrap();
    assert_eq!(m.geometry.faces.len(), 1);
}

/// A binary STL of `n` facets whose 80-byte header reads `header`.
fn binary_stl(header: &[u8], n: u32) -> Vec<u8> {
    let mut b = vec![b' '; 80];
    b[..header.len()].copy_from_slice(header);
    b.extend(n.to_le_bytes());
    for i in 0..n {
        let x = i as f32;
        for v in [
            [0.0f32, 0.0, 1.0],
            [x, 0.0, 0.0],
            [x + 1.0, 0.0, 0.0],
            [x, 1.0, 0.0],
        ] {
            for c in v {
                b.extend(c.to_le_bytes());
            }
        }
        b.extend([0, 0]);
    }
    b
}

#[test]
fn a_binary_stl_whose_header_starts_with_solid_is_binary() {
    let bytes = binary_stl(b"solid exported by a tool that writes this", 3);
    let m = stl::parse(&bytes, "t.stl").unwrap();
    assert_eq!(m.geometry.faces.len(), 3);
    // Its size says so: 84 + 50 per facet. One byte less is not binary, and
    // not ASCII either.
    let e = stl::parse(&bytes[..bytes.len() - 1], "t.stl")
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("t.stl:"), "{e}");
}

#[test]
fn lines_and_points_are_not_faces_and_are_counted() {
    let m = load(&format!("{TRIANGLE}l 1 2\nl 1 2 3\np 1\nf 1 2 3\n"));
    assert_eq!(m.geometry.faces.len(), 1);
    assert_eq!(
        m.notes,
        vec!["t.obj: 3 line and point elements (`l`, `p`) are not faces and are not drawn"]
    );
    // Only lines: no faces, never a filled polygon.
    assert_eq!(
        error(&format!("{TRIANGLE}l 1 2 3 1\np 2\n")),
        "t.obj:5:1: no faces in the file (only 2 line and point elements)"
    );
}

#[test]
fn errors_name_the_real_line_and_column() {
    for (src, want) in [
        (
            "v 0 0 0\nv 1 0 x\n",
            "t.obj:2:7: `v`: \"x\" is not a number",
        ),
        (
            "v 0 0 0\n\tv 1 0 x\n",
            "t.obj:2:8: `v`: \"x\" is not a number",
        ),
        (
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2   9\n",
            "t.obj:4:9: face vertex index 9 is out of range (1 to 3 so far)",
        ),
        (
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2/1 3\n",
            "t.obj:4:5: face texture coordinate index 1: no texture coordinate is given before it",
        ),
        (
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3//x\n",
            "t.obj:4:7: face vertex \"3//x\" is not an index",
        ),
        (
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 1/2/3/4\n",
            "t.obj:4:7: face vertex \"1/2/3/4\" has more than 3 parts",
        ),
        ("vn 0 1\n", "t.obj:1:1: `vn` needs 3 numbers, found 2"),
        ("# é\nv 0 é 0\n", "t.obj:2:5: `v`: \"é\" is not a number"),
    ] {
        assert_eq!(error(src), want, "{src:?}");
    }
    let e = stl::parse(
        b"solid x\nfacet normal 0 0 1\n outer loop\n  vertex 0 0 zero\n",
        "t.stl",
    )
    .unwrap_err()
    .to_string();
    assert_eq!(e, "t.stl:4:14: `vertex`: \"zero\" is not a number");
}

// --- 6. Polygons -------------------------------------------------------------

/// The area of triangle `t` of `g` in the z = 0 plane, signed: positive
/// counter-clockwise.
fn area(g: &Geometry, t: [u32; 3]) -> f64 {
    let p = t.map(|i| g.positions[i as usize].as_dvec3());
    ((p[1] - p[0]).cross(p[2] - p[0])).z / 2.0
}

/// Whether point `q` is inside `outline` by the even-odd rule.
fn inside(outline: &[[f64; 2]], q: [f64; 2]) -> bool {
    let mut odd = false;
    for (i, a) in outline.iter().enumerate() {
        let b = outline[(i + 1) % outline.len()];
        if (a[1] > q[1]) != (b[1] > q[1]) {
            let x = a[0] + (q[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            odd ^= q[0] < x;
        }
    }
    odd
}

/// Loads the polygon with corners `outline` (z = 0) as one face; returns
/// the geometry, after checking that every triangle's centre is inside the
/// outline by the even-odd rule.
fn polygon(outline: &[[f64; 2]]) -> Geometry {
    let mut src: String = outline
        .iter()
        .map(|p| format!("v {} {} 0\n", p[0], p[1]))
        .collect();
    src.push('f');
    for i in 1..=outline.len() {
        src.push_str(&format!(" {i}"));
    }
    let g = load(&src).geometry;
    for t in &g.faces {
        let p = t.map(|i| g.positions[i as usize].as_dvec3());
        let c = (p[0] + p[1] + p[2]) / 3.0;
        assert!(inside(outline, [c.x, c.y]), "a triangle outside: {p:?}");
    }
    g
}

#[test]
fn a_u_shaped_face_with_a_repeated_corner_covers_its_own_area() {
    // A 3×3 square with a 1×2 notch from the top: area 7. The corner
    // (3, 0) is given twice.
    let u = [
        [0.0, 0.0],
        [3.0, 0.0],
        [3.0, 0.0],
        [3.0, 3.0],
        [2.0, 3.0],
        [2.0, 1.0],
        [1.0, 1.0],
        [1.0, 3.0],
        [0.0, 3.0],
    ];
    let g = polygon(&u);
    let areas: Vec<f64> = g.faces.iter().map(|&t| area(&g, t)).collect();
    assert!(areas.iter().all(|&a| a > 0.0), "{areas:?}");
    assert_eq!(areas.iter().sum::<f64>(), 7.0);
    assert_eq!(g.faces.len(), 6, "eight distinct corners: six triangles");
}

#[test]
fn collinear_corners_are_no_trouble() {
    // A 2×1 rectangle with a corner in the middle of each long side.
    let g = polygon(&[
        [0.0, 0.0],
        [1.0, 0.0],
        [2.0, 0.0],
        [2.0, 1.0],
        [1.0, 1.0],
        [0.0, 1.0],
    ]);
    assert_eq!(g.faces.iter().map(|&t| area(&g, t)).sum::<f64>(), 2.0);
    assert!(g.faces.iter().all(|&t| area(&g, t) > 0.0));
}

#[test]
fn a_bowtie_covers_its_two_lobes_and_nothing_between() {
    // Corners (0,0) (2,2) (2,0) (0,2): the edges cross at (1,1). By the
    // even-odd rule the inside is the two lobes, each of area 1, the
    // triangles (0,0) (1,1) (0,2) and (1,1) (2,2) (2,0)… which by the
    // outline's own order are the left and right ones.
    let g = polygon(&[[0.0, 0.0], [2.0, 2.0], [2.0, 0.0], [0.0, 2.0]]);
    let areas: Vec<f64> = g.faces.iter().map(|&t| area(&g, t)).collect();
    assert_eq!(areas.iter().map(|a| a.abs()).sum::<f64>(), 2.0, "{areas:?}");
    // One facing for all: the plane's, never both.
    assert!(
        areas.iter().all(|&a| a > 0.0) || areas.iter().all(|&a| a < 0.0),
        "{areas:?}"
    );
    // The crossing became a vertex of the mesh.
    assert!(g.positions.contains(&Vec3::new(1.0, 1.0, 0.0)));
}

#[test]
fn a_folded_quad_is_cut_along_a_diagonal_so_a_closed_surface_stays_closed() {
    // A regular tetrahedron whose faces ABC and ACD are written as one quad
    // A B C D, folded 109.5° along AC. Projected onto one plane its edges
    // cross (its halves face apart by both diagonals), but in space they do
    // not meet: the file means the two faces. Cut along A–C, the quad's
    // four edges are each shared with a triangle, and the mesh is closed.
    let g = load(
        "v 1 1 1\nv 1 -1 -1\nv -1 1 -1\nv -1 -1 1\n\
         f 1 2 3 4\nf 1 4 2\nf 2 4 3\n",
    )
    .geometry;
    // Two triangles for the quad. The even-odd cut also made two, its
    // lobes, but around a new corner where two edges seem to cross, which
    // no neighbour shares: the surface was open.
    assert_eq!(g.faces.len(), 4);
    assert!(g.closed);
}

#[test]
fn tux_is_closed_so_its_back_faces_are_culled() {
    // Its one folded quad (`f 8751 19047 14039 3159`, line 70190) was cut
    // by the even-odd rule, which opened the surface and drew both sides.
    let tux = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../tests/models/linux-mascot-tux.obj"
    );
    let out = rastty(&["render", tux, "--explain"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stderr).unwrap();
    let raster = text.lines().find(|l| l.starts_with("raster:")).unwrap();
    assert_eq!(
        raster,
        "raster: 2650 triangles set up, 35942 found empty, 2592 culled, 0 degenerate, \
         0 not finite; 2652 samples tested, 918 covered"
    );
}

#[test]
fn a_face_of_100k_corners_is_cut_in_n_minus_2_triangles() {
    let n = 100_000;
    let circle: Vec<[f64; 2]> = (0..n)
        .map(|i| {
            let t = std::f64::consts::TAU * i as f64 / n as f64;
            // As a file holds them: six decimals.
            let r = |x: f64| (x * 1e6).round() / 1e6;
            [r(t.cos()), r(t.sin())]
        })
        .collect();
    let mut src: String = circle
        .iter()
        .map(|p| format!("v {} {} 0\n", p[0], p[1]))
        .collect();
    src.push('f');
    for i in 1..=n {
        src.push_str(&format!(" {i}"));
    }
    let g = load(&src).geometry;
    // Rounding to six decimals leaves no two corners equal and every
    // corner convex or flat: a fan's worth of triangles, none outside.
    assert_eq!(g.faces.len(), n - 2);
    let shoelace: f64 = (0..n)
        .map(|i| {
            let (a, b) = (
                g.positions[i].as_dvec3(),
                g.positions[(i + 1) % n].as_dvec3(),
            );
            a.x * b.y - a.y * b.x
        })
        .sum::<f64>()
        / 2.0;
    let sum: f64 = g.faces.iter().map(|&t| area(&g, t)).sum();
    assert!(
        (sum - shoelace).abs() < 1e-9 * shoelace,
        "{sum} vs {shoelace}"
    );
}

// --- 7. Hostile files ------------------------------------------------------

#[test]
fn a_fifo_a_device_and_a_directory_are_refused_before_reading() {
    let dir = scratch("fifo");
    for ext in ["obj", "stl", "toml"] {
        let fifo = dir.join(format!("pipe.{ext}"));
        let ok = Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success();
        assert!(ok);
        let f = fifo.to_str().unwrap();
        assert_eq!(
            fails(&["render", f]),
            format!("error: {f}: is a named pipe, not a file")
        );
    }
    assert_eq!(
        fails(&["render", "/dev/zero"]),
        "error: /dev/zero: is a device, not a file"
    );
    let d = dir.to_str().unwrap();
    assert_eq!(
        fails(&["render", d]),
        format!("error: {d}: is a directory, not a file")
    );
}

#[test]
fn a_sparse_4_gib_file_is_refused_by_its_size_and_the_flag_lifts_the_limit() {
    let dir = scratch("sparse");
    for ext in ["obj", "stl", "toml"] {
        let path = dir.join(format!("huge.{ext}"));
        std::fs::File::create(&path)
            .unwrap()
            .set_len(4 << 30)
            .unwrap();
        let p = path.to_str().unwrap();
        assert_eq!(
            fails(&["render", p]),
            format!(
                "error: {p}: 4.0 GiB is more than the limit of 1.0 GiB (--max-file-size raises it)"
            )
        );
        std::fs::remove_file(&path).unwrap();
    }
    // A small limit refuses a real model; a large one lets it through.
    let tux = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../tests/models/linux-mascot-tux.obj"
    );
    assert_eq!(
        fails(&["render", tux, "--max-file-size", "1M"]),
        format!(
            "error: {tux}: 2.9 MiB is more than the limit of 1.0 MiB (--max-file-size raises it)"
        )
    );
    let out = rastty(&[
        "render",
        tux,
        "--max-file-size",
        "3MiB",
        "--cols",
        "8",
        "--rows",
        "4",
    ]);
    assert!(out.status.success());
}

/// Whether every mesh of `scene` holds the very same geometry.
fn one_geometry(scene: &Scene) -> bool {
    let first = &scene.meshes[0].geometry;
    scene
        .meshes
        .iter()
        .all(|m| std::sync::Arc::ptr_eq(&m.geometry, first))
}

#[test]
fn twenty_thousand_meshes_naming_one_shape_share_one_geometry() {
    let src: String = (0..20_000)
        .map(|i| {
            format!(
                "[[mesh]]\nshape = \"torus\"\ntranslate = [{}.0, 0.0, 0.0]\n",
                i % 7
            )
        })
        .collect();
    let scene = Scene::parse(&src, "many.toml").unwrap();
    assert_eq!(scene.meshes.len(), 20_000);
    assert!(one_geometry(&scene));
}

#[test]
fn many_meshes_naming_one_file_read_it_once() {
    let dir = scratch("one-file");
    std::fs::write(dir.join("t.obj"), format!("{TRIANGLE}f 1 2 3\n")).unwrap();
    let src: String = (0..500).map(|_| "[[mesh]]\npath = \"t.obj\"\n").collect();
    let scene = Scene::parse_in(&src, "s.toml", Some(&dir)).unwrap();
    assert!(one_geometry(&scene));
}

// --- 8. Nothing lost without a word -----------------------------------------

#[test]
fn a_vertex_that_is_not_a_number_drops_its_faces_and_says_so() {
    let dir = scratch("nan");
    let path = dir.join("nan.obj");
    std::fs::write(
        &path,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 1 0\nv 1 inf 0\nf 1 2 3\nf 2 4 3\nf 1 5 2\n",
    )
    .unwrap();
    let p = path.to_str().unwrap();
    let out = rastty(&[
        "render", p, "--cols", "20", "--rows", "8", "--color", "none",
    ]);
    assert!(out.status.success());
    assert_eq!(
        String::from_utf8(out.stderr).unwrap(),
        format!(
            "note: {p}:4: 2 vertices are not finite numbers; the 2 faces that use them are not drawn\n"
        )
    );
    // The face that is whole is drawn.
    let frame = String::from_utf8(out.stdout).unwrap();
    assert!(frame.chars().any(|c| !c.is_whitespace()), "{frame}");
    // A normal that is not a number likewise.
    let m = load(&format!(
        "{TRIANGLE}vn 0 0 1\nvn nan 0 1\nf 1//1 2//1 3//1\nf 1//1 2//2 3//1\n"
    ));
    assert_eq!(m.geometry.faces.len(), 1);
    assert_eq!(
        m.notes,
        vec!["t.obj: 1 faces use normals that are not finite numbers and are not drawn"]
    );
}

#[test]
#[cfg(all(feature = "ply", feature = "gltf"))]
fn a_format_is_told_by_its_first_bytes_where_its_name_is_missing_or_lies() {
    let quad = b"ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
    let dir = scratch("sniff");
    let tri = "# a triangle\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let put = |name: &str, bytes: &[u8]| {
        let p = dir.join(name);
        std::fs::write(&p, bytes).unwrap();
        p.to_str().unwrap().to_string()
    };
    // No extension: OBJ statements, PLY's signature.
    let obj = put("triangle", tri.as_bytes());
    let with_ext = put("triangle.obj", tri.as_bytes());
    let ply = put("quad", quad);
    for p in [&obj, &ply] {
        let out = rastty(&["render", p, "--cols", "20", "--rows", "6"]);
        assert!(
            out.status.success(),
            "{p}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(
            out.stderr.is_empty(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    assert_eq!(
        rastty(&["render", &obj, "--cols", "20", "--rows", "6"]).stdout,
        rastty(&["render", &with_ext, "--cols", "20", "--rows", "6"]).stdout
    );
    // A name that lies: read by its bytes, with a note.
    let lying = put("quad.glb", quad);
    let out = rastty(&["render", &lying, "--cols", "20", "--rows", "6"]);
    assert!(out.status.success());
    assert_eq!(
        String::from_utf8(out.stderr).unwrap(),
        format!("note: {lying}: read as PLY (its first bytes say so), not as its name says\n")
    );
    // Text that is none of them; a GLB that is not one; a shape misspelt.
    let passwd = put("passwd", b"root:x:0:0:root:/root:/bin/bash\n");
    assert_eq!(
        fails(&["render", &passwd]),
        format!(
            "error: {passwd}: not a model or a scene: its first bytes are not OBJ, STL, PLY, glTF or TOML"
        )
    );
    let fake = put("fake.glb", b"root:x:0:0:root:/root:/bin/bash\n");
    assert_eq!(
        fails(&["render", &fake]),
        format!(
            "error: {fake}: not glTF: a GLB starts with `glTF` and a .gltf file is a JSON object"
        )
    );
    assert_eq!(
        fails(&["render", "torsu"]),
        "error: torsu: no such file or shape; did you mean torus?"
    );
}

#[test]
fn an_extension_rastty_does_not_read_is_an_error_listing_those_it_does() {
    let dir = scratch("ext");
    for ext in ["3ds", "dae", "fbx"] {
        let path = dir.join(format!("model.{ext}"));
        std::fs::write(&path, b"MM\x00\x00 a model in another format").unwrap();
        let p = path.to_str().unwrap();
        assert_eq!(
            fails(&["render", p]),
            format!(
                "error: {p}: rastty does not read .{ext} files; it reads models (.obj with its .mtl, .stl, .gltf, .glb, .ply, .3mf), scenes (.toml) and the shapes cube, sphere and torus"
            )
        );
    }
}

#[test]
#[cfg(feature = "gltf")]
fn a_textured_model_reads_its_texture_as_filter_says() {
    let crate_glb = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/models/crate.glb");
    let run = |filter: Option<&str>| {
        let mut args = vec!["render", crate_glb, "--cols", "40", "--rows", "16"];
        args.extend(["--color", "truecolor", "--explain"]);
        if let Some(f) = filter {
            args.extend(["--filter", f]);
        }
        let out = rastty(&args);
        assert!(out.status.success());
        (out.stdout, String::from_utf8(out.stderr).unwrap())
    };
    let (own, explain) = run(None);
    assert!(
        explain.contains("texturing      run   a material has a texture"),
        "{explain}"
    );
    assert!(
        explain.contains("samples read a texture (each texture's own filter)"),
        "{explain}"
    );
    let (nearest, explain) = run(Some("nearest"));
    assert!(
        explain.contains("samples read a texture (nearest)"),
        "{explain}"
    );
    // The file asks for trilinear when minified, as here: nearest differs,
    // and forcing trilinear changes nothing.
    assert_ne!(own, nearest);
    assert_eq!(run(Some("trilinear")).0, own);
}

#[test]
#[cfg(feature = "textures")]
fn a_texture_that_does_not_decode_is_one_error_line() {
    let dir = scratch("bad-texture");
    let obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl t\nf 1/1 2/2 3/3\n";
    std::fs::write(dir.join("m.obj"), obj).unwrap();
    std::fs::write(dir.join("m.mtl"), "newmtl t\nmap_Kd wood.png\n").unwrap();
    std::fs::write(dir.join("wood.png"), b"\x89PNG\r\n\x1a\nnot really").unwrap();
    let p = dir.join("m.obj");
    let err = fails(&["render", p.to_str().unwrap()]);
    let (mtl, png) = (dir.join("m.mtl"), dir.join("wood.png"));
    assert!(
        err.starts_with(&format!(
            "error: {}:2:8: {}: ",
            mtl.display(),
            png.display()
        )),
        "{err}"
    );
}
