//! Textures, end to end, on models the tests write themselves: a
//! checkerboard floor in perspective against an f64 ray cast, the three
//! wrap modes and the filters with exact expectations, OBJ `map_Kd`, the
//! planner's skip, and files that do not decode.

use std::path::Path;
use std::sync::Arc;

use crate::common;

use common::{TexturedMesh, glb, png_rgb};
use rastty::Effect;
use rastty::color::Lin;
use rastty::glam::{DVec3, DVec4, Vec3};
use rastty::scene::{Camera, LoadOptions, Mesh, Projection, Scene, gltf, obj};
use rastty::texture::FilterMode;
use rastty::{GlyphMode, RenderOptions, Renderer, color::Rgb};

/// The floor: 4 wide (x from −2 to 2), 20 deep (z from 0 to −20), at
/// y = 0; `u = x + 2`, `v = −z`, so that a 2×2 checkerboard texture,
/// repeated, makes squares half a unit on a side.
const FLOOR: [[f32; 3]; 4] = [
    [-2.0, 0.0, 0.0],
    [2.0, 0.0, 0.0],
    [2.0, 0.0, -20.0],
    [-2.0, 0.0, -20.0],
];
const FLOOR_UV: [[f32; 2]; 4] = [[0.0, 0.0], [4.0, 0.0], [4.0, 20.0], [0.0, 20.0]];

/// Black and white, white at texel (0, 0).
fn checker_png() -> Vec<u8> {
    let (b, w) = ([0, 0, 0], [255, 255, 255]);
    png_rgb(2, 2, &[w, b, b, w])
}

fn floor_glb(sampler: &str) -> Vec<u8> {
    TexturedMesh {
        positions: &FLOOR,
        uvs: &FLOOR_UV,
        indices: &[0, 1, 2, 0, 2, 3],
        png: &checker_png(),
        sampler,
        base_color: [1.0; 4],
    }
    .glb()
}

/// A scene of one loaded model, unlit, seen by `camera`.
fn scene_of(loaded: obj::Loaded, camera: Camera) -> Scene {
    Scene {
        camera,
        meshes: vec![Mesh::of(Arc::new(loaded.geometry), Rgb::WHITE)],
        ..Scene::default()
    }
}

fn floor_camera() -> Camera {
    Camera {
        shift: rastty::glam::Vec2::ZERO,
        projection: Projection::Perspective {
            fov_y: 60.0,
            near: 0.1,
            far: 100.0,
        },
        eye: Vec3::new(0.3, 1.0, 1.0),
        target: Vec3::new(0.0, 0.0, -6.0),
        up: Vec3::Y,
        fit: None,
    }
}

fn opts(filter: Option<FilterMode>) -> RenderOptions {
    RenderOptions {
        cols: 80,
        rows: 24,
        glyphs: GlyphMode::Half,
        filter,
        ..RenderOptions::default()
    }
}

/// Where the eye's ray through sample `(x, y)`'s centre meets the floor
/// (y = 0), in f64, by the inverse of the camera's matrix: the floor's
/// `(u, v)` there, or `None` when it misses.
fn ray_cast(camera: &Camera, o: &RenderOptions, x: u32, y: u32) -> Option<(f64, f64)> {
    let (w, h) = (o.cols as f64, o.rows as f64 * 2.0);
    let inv = camera.view_projection64(o.aspect()).inverse();
    let ndc = [
        (x as f64 + 0.5) / w * 2.0 - 1.0,
        (y as f64 + 0.5) / h * 2.0 - 1.0,
    ];
    let at = |z: f64| {
        let p: DVec4 = inv * DVec4::new(ndc[0], ndc[1], z, 1.0);
        p.truncate() / p.w
    };
    let (a, b): (DVec3, DVec3) = (at(-1.0), at(1.0));
    let t = -a.y / (b.y - a.y);
    if !(0.0..=1.0).contains(&t) {
        return None;
    }
    let p = a + (b - a) * t;
    let (u, v) = (p.x + 2.0, -p.z);
    ((0.0..=4.0).contains(&u) && (0.0..=20.0).contains(&v)).then_some((u, v))
}

#[test]
fn a_checkerboard_floor_in_perspective_matches_an_f64_ray_cast() {
    let camera = floor_camera();
    let loaded = gltf::parse(&floor_glb("{}"), None, "floor.glb", &LoadOptions::default()).unwrap();
    let scene = scene_of(loaded, camera);
    let o = opts(Some(FilterMode::Nearest));
    let mut r = Renderer::new();
    r.render(&scene, &o);
    let fb = r.framebuffer();
    let grid = fb.grid();
    let (mut checked, mut white, mut boundary) = (0, 0, 0);
    for y in 0..grid.height {
        for x in 0..grid.width {
            let got = fb.get(x, y);
            let Some((u, v)) = ray_cast(&camera, &o, x, y) else {
                continue;
            };
            // Texel coordinates: two texels per unit of u and v.
            let (tu, tv) = (u * 2.0, v * 2.0);
            let near_edge = |t: f64, hi: f64| {
                let f = t - t.round();
                f.abs() < 0.01 || t < 0.01 || t > hi - 0.01
            };
            if near_edge(tu, 8.0) || near_edge(tv, 40.0) {
                boundary += 1;
                continue;
            }
            let is_white = (tu.floor() as i64 + tv.floor() as i64) % 2 == 0;
            let want = if is_white { Lin::WHITE } else { Lin::BLACK };
            assert_eq!(got, Some(want), "sample ({x}, {y}) at uv ({u}, {v})");
            checked += 1;
            white += is_white as u32;
        }
    }
    // Most of the floor was checked, both colours, far rows included.
    assert!(
        checked > 1500,
        "{checked} checked, {boundary} at boundaries"
    );
    assert!(white > 500 && checked - white > 500);
    assert!(boundary < checked / 20, "{boundary} at boundaries");
}

/// A quad filling the canonical square (no projection), `u` from `u0` to
/// `u1` left to right and `v` from `v0` (top) to `v1` (bottom).
fn screen_quad(png: &[u8], sampler: &str, u: [f32; 2], v: [f32; 2]) -> Scene {
    let uvs = [[u[0], v[1]], [u[1], v[1]], [u[1], v[0]], [u[0], v[0]]];
    let glb = square(png, &uvs, sampler).glb();
    let loaded = gltf::parse(&glb, None, "quad.glb", &LoadOptions::default()).unwrap();
    unprojected(loaded)
}

/// The canonical square as a textured mesh, its corners (counter-clockwise
/// from the bottom left) at `uvs` of `png`, read through `sampler`.
fn square<'a>(png: &'a [u8], uvs: &'a [[f32; 2]], sampler: &'a str) -> TexturedMesh<'a> {
    TexturedMesh {
        positions: &[
            [-1.0, -1.0, 0.0],
            [1.0, -1.0, 0.0],
            [1.0, 1.0, 0.0],
            [-1.0, 1.0, 0.0],
        ],
        uvs,
        indices: &[0, 1, 2, 0, 2, 3],
        png,
        sampler,
        base_color: [1.0; 4],
    }
}

/// `loaded` seen without a projection: the canonical square fills the view.
fn unprojected(loaded: obj::Loaded) -> Scene {
    let camera = Camera {
        projection: Projection::None,
        ..Camera::default()
    };
    scene_of(loaded, camera)
}

/// Renders at 48 × 16 samples (48 columns, 8 rows, half blocks) and
/// returns the samples, row by row from the bottom.
fn samples(scene: &Scene, filter: Option<FilterMode>) -> (Vec<Option<Lin>>, Renderer) {
    let o = RenderOptions {
        cols: 48,
        rows: 8,
        glyphs: GlyphMode::Half,
        filter,
        ..RenderOptions::default()
    };
    let mut r = Renderer::new();
    r.render(scene, &o);
    (r.framebuffer().samples().to_vec(), r)
}

const RED: [u8; 3] = [255, 0, 0];
const BLUE: [u8; 3] = [0, 0, 255];

fn lin(c: [u8; 3]) -> Lin {
    Lin::from_srgb(Rgb(c))
}

#[test]
fn wrap_modes_repeat_mirror_and_clamp_as_the_sampler_says() {
    // Two texels, red then blue; u runs from −1 to 2 across 48 samples, so
    // sample x reads u = −1 + (x + ½)/16, never on a texel edge. The
    // sampler's own filters (nearest) are honoured.
    let png = png_rgb(2, 1, &[RED, BLUE]);
    for (mode, code) in [("repeat", 10497), ("mirrored", 33648), ("clamp", 33071)] {
        let sampler = format!(r#"{{"magFilter":9728,"minFilter":9728,"wrapS":{code}}}"#);
        let scene = screen_quad(&png, &sampler, [-1.0, 2.0], [0.0, 1.0]);
        let (got, _) = samples(&scene, None);
        for x in 0..48u32 {
            let u = -1.0 + (x as f64 + 0.5) / 16.0;
            let i = (u * 2.0).floor() as i64;
            let texel = match mode {
                "repeat" => i.rem_euclid(2),
                "mirrored" => {
                    let m = i.rem_euclid(4);
                    if m < 2 { m } else { 3 - m }
                }
                _ => i.clamp(0, 1),
            };
            let want = lin(if texel == 0 { RED } else { BLUE });
            for y in 0..16 {
                assert_eq!(got[y * 48 + x as usize], Some(want), "{mode}: ({x}, {y})");
            }
        }
    }
}

#[test]
fn bilinear_magnification_weighs_the_two_nearest_texels() {
    // Black and white texels, clamped; u from 0 to 1 across 48 samples:
    // texel space x = 2u − ½, the weight of white its fraction, clamped to
    // the edges.
    let png = png_rgb(2, 1, &[[0; 3], [255; 3]]);
    let scene = screen_quad(&png, r#"{"wrapS":33071}"#, [0.0, 1.0], [0.0, 1.0]);
    let (got, r) = samples(&scene, Some(FilterMode::Bilinear));
    for (i, s) in got.iter().enumerate() {
        let x = i % 48;
        let t = (2.0 * (x as f64 + 0.5) / 48.0 - 0.5).clamp(0.0, 1.0);
        let want = (t * 65535.0).round() as i64;
        let g = s.unwrap().0[0] as i64;
        assert!((g - want).abs() <= 1, "sample {i}: {g}, want {want}");
    }
    assert_eq!(r.stats().textured_samples, 48 * 16);
}

#[test]
fn minified_nearest_aliases_and_trilinear_averages() {
    // A 4×4 checkerboard, u and v running one whole texture per sample:
    // every sample centre lands on texel (2, 2), white, so nearest shows
    // white everywhere (the aliasing a coarse grid invites); trilinear
    // reads the 1×1 level (λ = log2 4 = 2 exactly), the mean: half light.
    let checker: Vec<[u8; 3]> = (0..16)
        .map(|i| {
            if (i % 4 + i / 4) % 2 == 0 {
                [255; 3]
            } else {
                [0; 3]
            }
        })
        .collect();
    let png = png_rgb(4, 4, &checker);
    let scene = screen_quad(&png, "{}", [0.0, 48.0], [0.0, 16.0]);
    let (nearest, _) = samples(&scene, Some(FilterMode::Nearest));
    assert!(nearest.iter().all(|&s| s == Some(Lin::WHITE)));
    let (trilinear, _) = samples(&scene, Some(FilterMode::Trilinear));
    let half = Lin::from_f32([0.5 * 65535.0; 3]);
    assert!(
        trilinear.iter().all(|&s| s == Some(half)),
        "{:?}",
        trilinear[0]
    );
    // The file's sampler says nothing: trilinear is the default.
    assert_eq!(samples(&scene, None).0, trilinear);
}

#[test]
fn affine_interpolation_puts_the_floors_squares_in_the_wrong_places() {
    let camera = floor_camera();
    let loaded = gltf::parse(&floor_glb("{}"), None, "floor.glb", &LoadOptions::default()).unwrap();
    let scene = scene_of(loaded, camera);
    let o = RenderOptions {
        interpolation: rastty::Interpolation::Affine,
        ..opts(Some(FilterMode::Nearest))
    };
    let mut r = Renderer::new();
    r.render(&scene, &o);
    let fb = r.framebuffer();
    let (mut wrong, mut checked) = (0, 0);
    for y in 0..fb.grid().height {
        for x in 0..fb.grid().width {
            if let Some((u, v)) = ray_cast(&camera, &o, x, y) {
                let white = ((u * 2.0).floor() as i64 + (v * 2.0).floor() as i64) % 2 == 0;
                checked += 1;
                wrong += (fb.get(x, y) != Some(if white { Lin::WHITE } else { Lin::BLACK })) as u32;
            }
        }
    }
    // Affine weights put the squares in the wrong places over much of the
    // floor (the perspective test above finds none out of place).
    assert!(wrong > checked / 5, "{wrong} of {checked}");
}

#[test]
fn skipping_texturing_where_there_is_none_changes_nothing() {
    // A textured quad on the left, an untextured one on the right, lit
    // and smooth-shaded: the planned frame reads the texture only on the
    // left; the full pipeline reads a white texel everywhere else: the
    // same samples, bit for bit.
    let png = png_rgb(2, 1, &[RED, BLUE]);
    let mut scene = screen_quad(&png, "{}", [0.0, 1.0], [0.0, 1.0]);
    let left = scene.meshes[0]
        .clone()
        .with_model(rastty::glam::Mat4::from_scale(Vec3::new(0.5, 1.0, 1.0)));
    let right = Mesh::of(
        Arc::new(
            rastty::scene::Shape::Cube
                .mesh(Rgb::WHITE)
                .geometry
                .as_ref()
                .clone(),
        ),
        Rgb::new(200, 120, 40),
    )
    .with_model(
        rastty::glam::Mat4::from_translation(Vec3::new(0.6, 0.0, 0.0))
            * rastty::glam::Mat4::from_scale(Vec3::splat(0.3)),
    );
    scene.meshes = vec![left, right];
    scene.lights = rastty::scene::Light::rig().to_vec();
    let o = RenderOptions {
        cols: 48,
        rows: 8,
        ..RenderOptions::default()
    };
    let mut planned = Renderer::new();
    planned.render(&scene, &o);
    let mut full = Renderer::new();
    full.render(
        &scene,
        &RenderOptions {
            pipeline: rastty::Pipeline::Full,
            ..o
        },
    );
    assert_eq!(
        planned.framebuffer().samples(),
        full.framebuffer().samples()
    );
    let textured = planned.stats().textured_samples;
    // Exactly the left quad's samples: 24 columns × 16 rows.
    assert_eq!(textured, 24 * 16);
    assert!(full.stats().textured_samples > textured);
    assert!(planned.plan().unwrap()[Effect::Texturing].run);
    // Without the texture, the plan skips texturing.
    let mut plain = scene.clone();
    plain.meshes.remove(0);
    planned.render(&plain, &o);
    assert!(!planned.plan().unwrap()[Effect::Texturing].run);
    assert_eq!(planned.stats().textured_samples, 0);
}

/// Writes `files` into a fresh directory under the target directory.
fn dir_with(name: &str, files: &[(&str, &[u8])]) -> std::path::PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for (f, bytes) in files {
        std::fs::write(dir.join(f), bytes).unwrap();
    }
    dir
}

const OBJ_QUAD: &str = "mtllib q.mtl
v -1 -1 0
v 1 -1 0
v 1 1 0
v -1 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
usemtl tex
f 1/1 2/2 3/3 4/4
";

#[test]
fn obj_map_kd_textures_the_faces_with_v_running_up() {
    // Red above blue: OBJ's v runs up the image's rows from the bottom, so
    // the top of the quad (v = 1) is the image's top row, red.
    let png = png_rgb(1, 2, &[RED, BLUE]);
    let mtl = b"newmtl tex\nKd 1 1 1\nmap_Kd -clamp on -s 1 1 1 my image.png\n";
    let dir = dir_with(
        "obj-map-kd",
        &[
            ("q.obj", OBJ_QUAD.as_bytes()),
            ("q.mtl", mtl),
            ("my image.png", &png),
        ],
    );
    let loaded = obj::load(&dir.join("q.obj"), &LoadOptions::default()).unwrap();
    let g = &loaded.geometry;
    let uvs = g.uvs.as_ref().unwrap();
    assert_eq!(uvs[0], rastty::glam::Vec2::new(0.0, 1.0));
    assert_eq!(uvs[2], rastty::glam::Vec2::new(1.0, 0.0));
    assert_eq!(g.textures.len(), 1);
    assert_eq!(g.textures[0].size(), (1, 2));
    assert_eq!(
        g.textures[0].sampler.wrap_u,
        rastty::texture::Wrap::ClampToEdge
    );
    let camera = Camera {
        projection: Projection::None,
        ..Camera::default()
    };
    let (got, _) = samples(&scene_of(loaded, camera), Some(FilterMode::Nearest));
    // Row 0 is the bottom.
    assert!(got[..8 * 48].iter().all(|&s| s == Some(lin(BLUE))));
    assert!(got[8 * 48..].iter().all(|&s| s == Some(lin(RED))));
}

#[test]
fn map_kd_options_are_read_past_and_those_that_move_the_texture_are_noted() {
    // `-o` with two of its three numbers, then a name with a space; a
    // scale of 1 and an offset of 0 move nothing.
    let png = png_rgb(1, 2, &[RED, BLUE]);
    let files = |mtl: &'static [u8], name: &str| {
        let dir = dir_with(
            name,
            &[
                ("q.obj", OBJ_QUAD.as_bytes()),
                ("q.mtl", mtl),
                ("my image.png", &png),
            ],
        );
        obj::load(&dir.join("q.obj"), &LoadOptions::default()).unwrap()
    };
    let moved = files(
        b"newmtl tex\nmap_Kd -o 0.5 0.25 -s 1 1 1 -mm 0 1 -t 0 -cc on -clamp on my image.png\n",
        "obj-map-kd-moved",
    );
    assert_eq!(moved.geometry.textures.len(), 1);
    assert_eq!(moved.notes.len(), 1, "{:?}", moved.notes);
    assert!(
        moved.notes[0].ends_with(&format!(
            "{}q.mtl: not drawn: `map_Kd -o`, `map_Kd -cc`",
            std::path::MAIN_SEPARATOR
        )),
        "{:?}",
        moved.notes
    );
    let still = files(
        b"newmtl tex\nmap_Kd -o 0 0 -s 1 1 -bm 2 -cc off -blendu on my image.png\n",
        "obj-map-kd-still",
    );
    assert_eq!(still.geometry.textures.len(), 1);
    assert_eq!(still.notes, Vec::<String>::new());
}

#[test]
fn a_texture_that_does_not_decode_is_one_error_naming_it() {
    let mut png = png_rgb(2, 2, &[RED, BLUE, BLUE, RED]);
    png.truncate(png.len() - 20);
    // glTF: the image inside the GLB.
    let glb = TexturedMesh {
        positions: &FLOOR,
        uvs: &FLOOR_UV,
        indices: &[0, 1, 2],
        png: &png,
        sampler: "{}",
        base_color: [1.0; 4],
    }
    .glb();
    let e = gltf::parse(&glb, None, "t.glb", &LoadOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("t.glb: mesh 0 primitive 0: texture 0: image 0: "),
        "{e}"
    );
    assert!(!e.contains('\n'), "{e}");
    // OBJ: at the MTL line naming the file.
    let mtl = b"newmtl tex\nmap_Kd broken.png\n";
    let dir = dir_with(
        "obj-broken",
        &[
            ("q.obj", OBJ_QUAD.as_bytes()),
            ("q.mtl", mtl),
            ("broken.png", &png),
        ],
    );
    let e = obj::load(&dir.join("q.obj"), &LoadOptions::default())
        .unwrap_err()
        .to_string();
    let mtl_path = dir.join("q.mtl").display().to_string();
    let png_path = dir.join("broken.png").display().to_string();
    assert!(
        e.starts_with(&format!("{mtl_path}:2:8: {png_path}: ")),
        "{e}"
    );
    // Not an image at all.
    std::fs::write(dir.join("broken.png"), b"hello").unwrap();
    let e = obj::load(&dir.join("q.obj"), &LoadOptions::default())
        .unwrap_err()
        .to_string();
    assert_eq!(
        e,
        format!("{mtl_path}:2:8: {png_path}: not a PNG or JPEG image")
    );
}

#[test]
fn a_missing_image_is_one_error_naming_the_file() {
    // glTF: an image file beside the .gltf that is not there.
    let (json, bin) = TexturedMesh {
        positions: &FLOOR,
        uvs: &FLOOR_UV,
        indices: &[0, 1, 2],
        png: &[],
        sampler: "{}",
        base_color: [1.0; 4],
    }
    .parts(Some("gone.png"));
    let dir = dir_with("gltf-missing-image", &[]);
    let e = gltf::parse(
        &glb(&json, &bin),
        Some(&dir),
        "t.glb",
        &LoadOptions::default(),
    )
    .unwrap_err()
    .to_string();
    let gone = dir.join("gone.png").display().to_string();
    assert!(
        e.starts_with(&format!(
            "t.glb: mesh 0 primitive 0: texture 0: image 0 (\"gone.png\"): {gone}: "
        )),
        "{e}"
    );
    // OBJ: the MTL names a file that is not there.
    let dir = dir_with(
        "obj-missing-image",
        &[
            ("q.obj", OBJ_QUAD.as_bytes()),
            ("q.mtl", b"newmtl tex\nmap_Kd gone.png\n"),
        ],
    );
    let e = obj::load(&dir.join("q.obj"), &LoadOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with(&format!("{}:2:8: ", dir.join("q.mtl").display())),
        "{e}"
    );
    assert!(e.contains("gone.png"), "{e}");
}

#[test]
fn an_image_view_out_of_range_is_refused() {
    let file = TexturedMesh {
        positions: &FLOOR,
        uvs: &FLOOR_UV,
        indices: &[0, 1, 2],
        png: &checker_png(),
        sampler: "{}",
        base_color: [1.0; 4],
    }
    .glb();
    // Claim the image is far longer than the buffer.
    let json_len = u32::from_le_bytes(file[12..16].try_into().unwrap()) as usize;
    let json = std::str::from_utf8(&file[20..20 + json_len]).unwrap();
    let n = checker_png().len();
    let bad = json.replacen(
        &format!("\"byteLength\":{n}}}"),
        "\"byteLength\":100000}",
        1,
    );
    assert_ne!(bad, json);
    let bin_at = 20 + json_len + 8;
    let e = gltf::parse(
        &glb(&bad, &file[bin_at..]),
        None,
        "t.glb",
        &LoadOptions::default(),
    )
    .unwrap_err()
    .to_string();
    assert_eq!(
        e,
        "t.glb: buffer view 3 (100000 bytes at offset 92) runs past the 168 bytes of buffer 0"
    );
}

#[test]
fn the_example_crate_is_what_its_builder_makes() {
    let path = common::example_model("crate.glb", common::crate_glb());
    let loaded = gltf::load(&path, &LoadOptions::default()).unwrap();
    let g = &loaded.geometry;
    assert_eq!((g.faces.len(), g.textures.len()), (12, 1));
    assert_eq!(g.textures[0].size(), (64, 64));
    assert!(g.closed, "a closed cube");
    assert!(loaded.notes.is_empty(), "{:?}", loaded.notes);
}

#[test]
fn the_example_crate_in_ascii_shows_its_planks_and_brace() {
    // Without colour, the ascii ramp shows the texture's light and dark:
    // the frame, the brace and the plank seams.
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/models/crate.glb");
    let scene = Scene::of_model(&path).unwrap();
    let o = RenderOptions {
        cols: 60,
        rows: 26,
        glyphs: GlyphMode::Ascii,
        color: rastty::color::ColorDepth::None,
        ..RenderOptions::default()
    };
    insta::assert_snapshot!(rastty::render(&scene, &o).to_string());
}

#[test]
fn a_gltf_with_its_buffer_and_image_as_data_uris_reads_the_same_texture() {
    use base64::Engine as _;
    let b64 = |b: &[u8]| base64::engine::general_purpose::STANDARD.encode(b);
    let png = checker_png();
    let (json, bin) = TexturedMesh {
        positions: &FLOOR,
        uvs: &FLOOR_UV,
        indices: &[0, 1, 2, 0, 2, 3],
        png: &png,
        sampler: "{}",
        base_color: [1.0; 4],
    }
    .parts(Some(&format!("data:image/png;base64,{}", b64(&png))));
    let json = json.replacen(
        r#""buffers":[{"#,
        &format!(
            r#""buffers":[{{"uri":"data:application/octet-stream;base64,{}","#,
            b64(&bin)
        ),
        1,
    );
    let from_uris = gltf::parse(
        json.as_bytes(),
        Some(Path::new(".")),
        "f.gltf",
        &LoadOptions::default(),
    )
    .unwrap()
    .geometry;
    let from_glb = gltf::parse(&floor_glb("{}"), None, "f.glb", &LoadOptions::default())
        .unwrap()
        .geometry;
    assert_eq!(from_uris.textures, from_glb.textures);
    assert_eq!(from_uris.uvs, from_glb.uvs);
    assert_eq!(from_uris.textures[0].texel(0, 0, 0), Vec3::ONE);
    assert_eq!(from_uris.textures[0].texel(0, 1, 0), Vec3::ZERO);
}

#[test]
fn a_jpeg_texture_is_read() {
    // A flat colour survives JPEG at full quality to within a few steps.
    let mut jpeg = Vec::new();
    let pixels: Vec<u8> = [200u8, 120, 40].repeat(16 * 16);
    image::codecs::jpeg::JpegEncoder::new_with_quality(&mut jpeg, 100)
        .encode(&pixels, 16, 16, image::ExtendedColorType::Rgb8)
        .unwrap();
    let dir = dir_with(
        "obj-jpeg",
        &[
            ("q.obj", OBJ_QUAD.as_bytes()),
            ("q.mtl", b"newmtl tex\nmap_Kd wood.jpg\n"),
            ("wood.jpg", &jpeg),
        ],
    );
    let g = obj::load(&dir.join("q.obj"), &LoadOptions::default())
        .unwrap()
        .geometry;
    let t = &g.textures[0];
    assert_eq!(t.size(), (16, 16));
    let want = Lin::from_srgb(Rgb::new(200, 120, 40))
        .to_f32()
        .map(|v| v / 65535.0);
    let got = t.texel(0, 8, 8).to_array();
    for k in 0..3 {
        assert!((got[k] - want[k]).abs() < 0.02, "{got:?} {want:?}");
    }
}

#[test]
fn a_scene_file_places_a_textured_gltf_as_the_library_does() {
    // `[[mesh]] path = "floor.glb"` with the floor's camera: the same
    // samples as the scene built in code above.
    let dir = dir_with("scene-floor", &[("floor.glb", &floor_glb("{}"))]);
    let toml = "[camera]\nprojection = \"perspective\"\nfov_y = 60.0\nnear = 0.1\nfar = 100.0\n\
                eye = [0.3, 1.0, 1.0]\ntarget = [0.0, 0.0, -6.0]\n[[mesh]]\npath = \"floor.glb\"\n";
    std::fs::write(dir.join("floor.toml"), toml).unwrap();
    let from_file = Scene::load(&dir.join("floor.toml")).unwrap();
    let loaded = gltf::parse(&floor_glb("{}"), None, "floor.glb", &LoadOptions::default()).unwrap();
    let in_code = Scene {
        lights: from_file.lights.clone(),
        ..scene_of(loaded, floor_camera())
    };
    let o = opts(None);
    let (mut a, mut b) = (Renderer::new(), Renderer::new());
    a.render(&from_file, &o);
    b.render(&in_code, &o);
    assert_eq!(a.framebuffer().samples(), b.framebuffer().samples());
    assert!(a.stats().textured_samples > 1000);
}

/// The canonical-square quad of [`screen_quad`] with its corners' UVs
/// given, its base colour texture's `textureInfo` extended by `transform`
/// (`KHR_texture_transform` JSON) when there is one.
fn quad_with_uvs(png: &[u8], uvs: &[[f32; 2]; 4], transform: Option<&str>) -> Scene {
    let (mut json, bin) = square(png, uvs, NEAREST).parts(None);
    if let Some(t) = transform {
        json = json.replace(
            r#""baseColorTexture":{"index":0}"#,
            &format!(
                r#""baseColorTexture":{{"index":0,"extensions":{{"KHR_texture_transform":{t}}}}}"#
            ),
        );
        json = json.replacen('{', r#"{"extensionsUsed":["KHR_texture_transform"],"#, 1);
    }
    let loaded = gltf::parse(&glb(&json, &bin), None, "quad.glb", &LoadOptions::default()).unwrap();
    assert!(loaded.notes.is_empty(), "{:?}", loaded.notes);
    unprojected(loaded)
}

/// Nearest texels, within a level and between levels.
const NEAREST: &str = r#"{"magFilter":9728,"minFilter":9728}"#;

#[test]
fn a_specular_glossiness_diffuse_texture_is_the_base_colour_texture() {
    // The quad textured through KHR_materials_pbrSpecularGlossiness's
    // diffuse texture (no highlight) is the quad textured through its base
    // colour texture, sample for sample.
    let png = png_rgb(2, 2, &[RED, BLUE, [0, 255, 0], [255; 3]]);
    let corners = [[0.0f32, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
    let (want, _) = samples(&quad_with_uvs(&png, &corners, None), None);
    let (json, bin) = square(&png, &corners, NEAREST).parts(None);
    let base = r#""materials":[{"pbrMetallicRoughness":{"baseColorFactor":[1.0, 1.0, 1.0, 1.0],"baseColorTexture":{"index":0}}}]"#;
    assert!(json.contains(base), "{json}");
    let json = json
        .replace(
            base,
            r#""materials":[{"extensions":{"KHR_materials_pbrSpecularGlossiness":{"diffuseTexture":{"index":0},"specularFactor":[0,0,0]}}}]"#,
        )
        .replacen('{', r#"{"extensionsUsed":["KHR_materials_pbrSpecularGlossiness"],"#, 1);
    let loaded = gltf::parse(&glb(&json, &bin), None, "quad.glb", &LoadOptions::default()).unwrap();
    assert!(loaded.notes.is_empty(), "{:?}", loaded.notes);
    let (got, _) = samples(&unprojected(loaded), None);
    assert_eq!(got, want);
}

#[test]
fn a_texture_transform_moves_the_lookup_as_the_same_uvs_moved_by_hand() {
    // Four texels, repeated; the quad's UVs run over [0, 1]². The
    // extension's T · R · S, with R turning the texture counter-clockwise
    // as the file is seen (the UV rotation (u, v) → (u cos r + v sin r,
    // −u sin r + v cos r)), gives the same frame as those UVs written out.
    let png = png_rgb(2, 2, &[RED, BLUE, [0, 255, 0], [255; 3]]);
    let corners = [[0.0f32, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
    let moved = |offset: [f32; 2], r: f32, scale: [f32; 2]| {
        corners.map(|[u, v]| {
            let (u, v) = (u * scale[0], v * scale[1]);
            let (s, c) = r.sin_cos();
            [u * c + v * s + offset[0], -u * s + v * c + offset[1]]
        })
    };
    let cases = [
        (
            r#"{"offset":[0.5,0.25]}"#,
            moved([0.5, 0.25], 0.0, [1.0, 1.0]),
        ),
        (r#"{"scale":[3,0.5]}"#, moved([0.0, 0.0], 0.0, [3.0, 0.5])),
        (
            r#"{"rotation":1.5707963267948966}"#,
            [[1.0, 0.0], [1.0, -1.0], [0.0, -1.0], [0.0, 0.0]],
        ),
        (
            r#"{"offset":[-0.2,-0.1],"rotation":0.3,"scale":[1.5,1.5]}"#,
            moved([-0.2, -0.1], 0.3, [1.5, 1.5]),
        ),
    ];
    let (plain, _) = samples(&quad_with_uvs(&png, &corners, None), None);
    for (transform, by_hand) in cases {
        let (got, _) = samples(&quad_with_uvs(&png, &corners, Some(transform)), None);
        let (want, _) = samples(&quad_with_uvs(&png, &by_hand, None), None);
        assert_eq!(got, want, "{transform}");
        assert_ne!(got, plain, "{transform} moves the texture");
    }
}
