//! Files made by an adversary, opened through the `rastty` binary as a user
//! opens a downloaded model: what reaches the terminal is escaped, what a
//! model refers to is opened with the model's checks, budgets are refused
//! before the work, no file makes it panic, and memory stays bounded (each
//! child's own peak, from `wait4`).

use crate::common;
use crate::support;

use std::path::{Path, PathBuf};

use common::{f32s, glb};
use support::{Run, run, run_with};

/// A fresh directory for one test's files.
fn dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("hostile")
        .join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

const TRI: [f32; 9] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];

/// A glTF triangle whose one buffer is `buffer` (a `"uri":…,` or empty),
/// with `extra` appended to the top-level object.
fn triangle(buffer: &str, extra: &str) -> String {
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}}}]}}],
"buffers":[{{{buffer}"byteLength":36}}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":36}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}}]{extra}}}"#
    )
}

/// Writes `bytes` as `dir/name` and gives its path.
fn put(dir: &Path, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

/// A one-frame render of `model`, small.
fn render(model: &Path, more: &[&str]) -> Run {
    let mut args = vec!["render", s(model), "--cols", "20", "--rows", "6"];
    args.extend_from_slice(more);
    run(&args)
}

/// A one-frame render of `model` that must fail with status 1.
fn refused(model: &Path) -> Run {
    let r = render(model, &[]);
    assert_eq!(r.code, Some(1), "{}", r.stderr);
    r
}

/// The planted sequences: OSC 52 (clipboard), OSC 0 (title), CSI 2 J
/// (clear), a C1 CSI and a bidi override.
const PLANTED: &str = "\u{1b}]52;c;SGVsbG8=\u{7}\u{1b}]0;PWNED\u{7}\u{1b}[2J\u{9b}2J\u{202e}txt";
/// The same, as rastty shows it.
const SHOWN: &str = r"\x1b]52;c;SGVsbG8=\x07\x1b]0;PWNED\x07\x1b[2J\u{9b}2J\u{202e}txt";

fn assert_no_controls(text: &str) {
    assert!(
        !text
            .chars()
            .any(|c| rastty::text::is_unsafe(c) && c != '\n'),
        "{text:?}"
    );
}

#[test]
fn terminal_control_in_a_model_comes_out_escaped_on_stderr() {
    let d = dir("osc");
    let json = triangle(
        "",
        &format!(
            r#","extensionsUsed":[{}]"#,
            serde_json::to_string(PLANTED).unwrap()
        ),
    );
    let model = put(&d, "t.glb", glb(&json, &f32s(&TRI)));
    let r = render(&model, &[]);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    assert_eq!(
        r.stderr,
        format!(
            "note: {}: not drawn: extension \"{SHOWN}\"\n",
            model.display()
        )
    );
}

#[test]
fn names_in_errors_are_escaped_wherever_they_come_from() {
    let d = dir("names");
    // A path on the command line.
    let bad = d.join(format!("{PLANTED}.obj"));
    let r = refused(&bad);
    assert_eq!(
        r.stderr,
        format!(
            "error: {}/{SHOWN}.obj: No such file or directory (os error 2)\n",
            d.display()
        )
    );
    // An MTL `map_Kd` name.
    let obj = put(
        &d,
        "q.obj",
        "mtllib q.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl a\nf 1/1 2/2 3/3\n",
    );
    put(&d, "q.mtl", format!("newmtl a\nmap_Kd {PLANTED}.png\n"));
    let r = refused(&obj);
    assert!(
        r.stderr.contains(r"SGVsbG8=\x07\x1b]0;PWNED"),
        "{}",
        r.stderr
    );
    assert_no_controls(&r.stderr);
    // A TOML key, a PLY line, a glTF URI.
    let toml = put(
        &d,
        "s.toml",
        format!("{} = 1\n", serde_json::to_string(PLANTED).unwrap()),
    );
    let ply = put(
        &d,
        "p.ply",
        format!(
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n{PLANTED}\n"
        ),
    );
    let gltf = put(
        &d,
        "u.gltf",
        triangle(
            &format!(r#""uri":{},"#, serde_json::to_string(PLANTED).unwrap()),
            "",
        ),
    );
    for f in [&toml, &ply, &gltf] {
        let r = render(f, &[]);
        assert_eq!(r.code, Some(1), "{}", r.stderr);
        assert_eq!(r.stderr.lines().count(), 1, "{}", r.stderr);
        assert_no_controls(&r.stderr);
    }
    // clap's own errors quote what they refuse.
    let r = run(&["render", "--glyphs", PLANTED]);
    assert_eq!(r.code, Some(2));
    // (clap drops escape sequences itself; what it keeps is escaped.)
    assert!(r.stderr.contains(r"\u{9b}2J\u{202e}txt"), "{}", r.stderr);
    assert_no_controls(&r.stderr);
}

#[test]
fn a_notice_in_the_status_line_is_drawn_escaped() {
    use rastty::animate::{LiveStatus, Player, Spin};
    let opts = rastty::RenderOptions {
        cols: 60,
        rows: 4,
        color: rastty::color::ColorDepth::TrueColor,
        ..Default::default()
    };
    let mut p = Player::new(
        rastty::scene::default_scene(),
        opts,
        Spin {
            view: Default::default(),
            axis: rastty::transform::Axis::Y,
            step: 3.0,
            play: None,
        },
        rastty::encode::Encoder::new(opts.color),
    );
    p.set_notice(PLANTED);
    let bytes = p.prepare(LiveStatus::default()).to_vec();
    let mut vt = common::terminal(4, 60);
    vt.process(&bytes);
    assert!(
        !bytes.windows(2).any(|w| w == b"\x1b]"),
        "no OSC is written"
    );
    let last: String = vt.screen().rows(0, 60).nth(3).unwrap();
    // The notice starts one cell in.
    assert_eq!(last, format!(" {}", &SHOWN[..59]));
}

#[test]
fn files_a_model_names_are_opened_as_the_model_is() {
    let d = dir("refs");
    let cases = [
        // Read as the name beside the model, as loaders do, and the
        // error says so.
        (
            "/dev/zero",
            "buffer 0: \"/dev/zero\" is an absolute path: \"zero\" beside it is read instead; ",
        ),
        ("/dev/zero", "refs/zero: No such file or directory"),
        (
            "http://example.com/t.bin",
            "is on the network: rastty fetches nothing",
        ),
        ("ftp://example.com/t.bin", "not \"ftp\" URIs"),
    ];
    for (uri, want) in cases {
        let model = put(&d, "t.gltf", triangle(&format!(r#""uri":"{uri}","#), ""));
        let r = render(&model, &[]);
        assert_eq!(r.code, Some(1), "{uri}: {}", r.stderr);
        assert!(r.stderr.contains(want), "{uri}: {}", r.stderr);
    }
    // A FIFO beside the model: refused, not waited on.
    let fifo = d.join("pipe.bin");
    let c = std::ffi::CString::new(s(&fifo)).unwrap();
    // SAFETY: a valid C string; makes a FIFO in the test's directory.
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
    let model = put(&d, "f.gltf", triangle(r#""uri":"pipe.bin","#, ""));
    let r = refused(&model);
    assert_eq!(
        r.stderr,
        format!(
            "error: {}: buffer 0: {}: is a named pipe, not a file\n",
            model.display(),
            fifo.display()
        )
    );
    // A directory named by mtllib, a symlink loop named by a buffer.
    std::fs::create_dir(d.join("m.mtl")).unwrap();
    let obj = put(
        &d,
        "q.obj",
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    );
    let r = refused(&obj);
    assert!(r.stderr.contains("is a directory"), "{}", r.stderr);
    std::os::unix::fs::symlink("loop.bin", d.join("loop.bin")).unwrap();
    let model = put(&d, "l.gltf", triangle(r#""uri":"loop.bin","#, ""));
    let r = refused(&model);
    assert!(r.stderr.contains("symbolic links"), "{}", r.stderr);
    // A /proc file says it is empty and goes on: refused at once.
    std::os::unix::fs::symlink("/proc/self/status", d.join("proc.bin")).unwrap();
    let model = put(&d, "p.gltf", triangle(r#""uri":"proc.bin","#, ""));
    let r = render(&model, &[]);
    assert_eq!(
        r.stderr,
        format!(
            "error: {}: buffer 0: {}: has more than the 0 bytes its size says (a /proc or /sys file?)\n",
            model.display(),
            d.join("proc.bin").display()
        )
    );
    // Relative paths work: percent-encoded, and from outside the folder
    // with a note; an absolute path is tried beside the model, with a note.
    let inner = d.join("inner");
    std::fs::create_dir(&inner).unwrap();
    put(&d, "my buf.bin", f32s(&TRI));
    put(&inner, "abs.bin", f32s(&TRI));
    let model = put(
        &inner,
        "o.gltf",
        triangle(r#""uri":"../my%20buf.bin","#, ""),
    );
    let r = render(&model, &[]);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    assert_eq!(
        r.stderr,
        format!(
            "note: {}: \"../my buf.bin\" is read from outside its folder\n",
            model.display()
        )
    );
    let model = put(
        &inner,
        "a.gltf",
        triangle(r#""uri":"file:///etc/abs.bin","#, ""),
    );
    let r = render(&model, &[]);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    assert_eq!(
        r.stderr,
        format!(
            "note: {}: \"/etc/abs.bin\" is an absolute path: \"abs.bin\" beside it is read instead\n",
            model.display()
        )
    );
    // An OBJ's absolute `map_Kd` and `mtllib` that are not beside it
    // either: the error (or the note) says where they were looked for.
    put(&inner, "abs.mtl", "newmtl m\nmap_Kd /dev/zero\n");
    let obj = put(
        &inner,
        "abs.obj",
        "mtllib abs.mtl\nmtllib C:\\models\\gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl m\nf 1/1 2/1 3/1\n",
    );
    let r = refused(&obj);
    assert_eq!(
        r.stderr,
        format!(
            "error: {}:2:8: \"/dev/zero\" is an absolute path: \"zero\" beside it is read instead; {}: No such file or directory (os error 2)\n",
            inner.join("abs.mtl").display(),
            inner.join("zero").display()
        )
    );
    std::fs::write(
        &obj,
        "mtllib C:\\models\\gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    )
    .unwrap();
    let r = render(&obj, &[]);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    assert_eq!(
        r.stderr,
        format!(
            "note: {}:1:8: \"C:\\models\\gone.mtl\" is an absolute path: \"gone.mtl\" beside it is read instead; material library not found: drawn in the default colour\n",
            obj.display()
        )
    );
}

/// A PNG header for a `w`×`h` 1-bit grey image, with an IDAT that is not
/// there: all a decoder reads before it allocates.
fn png_header(w: u32, h: u32) -> Vec<u8> {
    let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut chunk = |kind: &[u8], data: &[u8]| {
        out.extend((data.len() as u32).to_be_bytes());
        let start = out.len();
        out.extend(kind);
        out.extend(data);
        let crc = crc32(&out[start..]);
        out.extend(crc.to_be_bytes());
    };
    let mut ihdr = Vec::new();
    ihdr.extend(w.to_be_bytes());
    ihdr.extend(h.to_be_bytes());
    ihdr.extend([1, 0, 0, 0, 0]);
    chunk(b"IHDR", &ihdr);
    chunk(b"IDAT", &[0x78, 0x9c, 0x03, 0x00, 0x00, 0x00, 0x00, 0x01]);
    chunk(b"IEND", &[]);
    out
}

fn crc32(bytes: &[u8]) -> u32 {
    let mut c = !0u32;
    for &b in bytes {
        c ^= u32::from(b);
        for _ in 0..8 {
            c = if c & 1 == 1 {
                (c >> 1) ^ 0xedb8_8320
            } else {
                c >> 1
            };
        }
    }
    !c
}

#[test]
fn budgets_are_refused_before_the_work() {
    let d = dir("budgets");
    // A decompression bomb: 16384² texels from a header.
    let obj = put(
        &d,
        "q.obj",
        "mtllib q.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl a\nf 1/1 2/2 3/3\n",
    );
    put(&d, "q.mtl", "newmtl a\nmap_Kd bomb.png\n");
    put(&d, "bomb.png", png_header(16384, 16384));
    let r = refused(&obj);
    assert_eq!(
        r.stderr,
        format!(
            "error: {}:2:8: {}: a 16384×16384 image is 268435456 texels, more than the 67108864 left in the texel budget (--max-texels raises it)\n",
            d.join("q.mtl").display(),
            d.join("bomb.png").display()
        )
    );
    assert!(r.peak < 64 << 20, "{} bytes", r.peak);
    // A node graph bomb: 60 nodes, each the next one's parent twice.
    let nodes: Vec<String> = (0..60)
        .map(|i| {
            if i < 59 {
                format!(r#"{{"children":[{},{}]}}"#, i + 1, i + 1)
            } else {
                r#"{"mesh":0}"#.into()
            }
        })
        .collect();
    let json = triangle("", "").replace(
        r#""nodes":[{"mesh":0}]"#,
        &format!("\"nodes\":[{}]", nodes.join(",")),
    );
    let model = put(&d, "bomb.glb", glb(&json, &f32s(&TRI)));
    let r = refused(&model);
    assert_eq!(
        r.stderr,
        format!(
            "error: {}: its node tree places 576460752303423488 triangles in 1152921504606846975 nodes, more than the budget of 268435456 (--max-triangles raises it)\n",
            model.display()
        )
    );
    assert!(r.peak < 64 << 20, "{} bytes", r.peak);
    // A frame of 2^31 sample tests, and a picture of 2^30 pixels.
    let r = run(&[
        "render", "cube", "--cols", "4096", "--rows", "4096", "--glyphs", "octant", "--aa", "16x",
    ]);
    assert_eq!(r.code, Some(1));
    assert_eq!(
        r.stderr,
        "error: a frame of 4096×4096 cells at 8 samples a cell and 16 pass(es) of --aa 16x is 2147483648 sample tests, more than the budget of 67108864 (--max-samples raises it)\n"
    );
    assert!(r.peak < 64 << 20, "{} bytes", r.peak);
    let png = d.join("big.png");
    let r = run(&[
        "render",
        "cube",
        "--cols",
        "4096",
        "--rows",
        "2048",
        "--output",
        s(&png),
        "--max-samples",
        "1G",
    ]);
    assert_eq!(r.code, Some(1));
    assert!(
        r.stderr.contains("more than 67108864: use fewer cells"),
        "{}",
        r.stderr
    );
    assert!(!png.exists());
    assert!(r.peak < 64 << 20, "{} bytes", r.peak);
    // Each budget can be lowered (and so raised) on the command line.
    put(&d, "small.png", png_header(64, 64));
    put(&d, "q.mtl", "newmtl a\nmap_Kd small.png\n");
    let r = render(&obj, &["--max-texels", "1000"]);
    assert!(
        r.stderr
            .contains("more than the 1000 left in the texel budget"),
        "{}",
        r.stderr
    );
    let r = run(&[
        "render",
        "torus",
        "--cols",
        "20",
        "--rows",
        "6",
        "--max-triangles",
        "100",
    ]);
    assert!(
        r.stderr.contains("more than the triangle budget of 100"),
        "{}",
        r.stderr
    );
}

/// The triangle textured by one image described by `image`.
fn textured(image: &str) -> String {
    triangle(
        "",
        &format!(
            r#","images":[{image}],"textures":[{{"source":0}}],"materials":[{{"pbrMetallicRoughness":{{"baseColorTexture":{{"index":0}}}}}}]"#
        ),
    )
    .replace(
        r#""attributes":{"POSITION":0}}"#,
        r#""attributes":{"POSITION":0,"TEXCOORD_0":1},"material":0}"#,
    )
    .replace(
        r#""max":[1,1,0]}]"#,
        r#""max":[1,1,0]},{"bufferView":0,"componentType":5126,"count":3,"type":"VEC2"}]"#,
    )
}

#[test]
fn no_file_makes_it_panic() {
    let d = dir("panics");
    let accessor = r#""accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}]"#;
    let cases = [
        (
            triangle("", "").replace(
                r#""byteLength":36}],"#,
                r#""byteLength":36,"byteStride":4}],"#,
            ),
            "has a byteStride of 4, less than its 12-byte elements",
        ),
        (
            triangle("", "").replace(r#""POSITION":0"#, r#""POSITION":0,"NORMAL":7"#),
            "accessor 7",
        ),
        (
            textured(r#"{"bufferView":0}"#),
            "image 0: not a PNG or JPEG image",
        ),
        (textured("{}"), "image 0"),
    ];
    assert!(cases[0].0.contains(accessor));
    for (i, (json, want)) in cases.iter().enumerate() {
        let model = put(&d, &format!("p{i}.glb"), glb(json, &f32s(&TRI)));
        let r = render(&model, &[]);
        assert_eq!(r.code, Some(1), "{i}: {}", r.stderr);
        assert!(r.stderr.contains(want), "{i}: {}", r.stderr);
    }
    // A polygon spade cannot triangulate: cut as a fan, with a note.
    let obj = put(
        &d,
        "cdt.obj",
        "v 2 0 3\nv 1 0 1\nv 2 0 0\nv 1 0 1\nv 1 0 3\nv 0 2 2\nv 2 0 0\nv 0 1 0\nf 1 6 3 8 5 4 8 5 8 2\n",
    );
    let r = render(&obj, &[]);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    assert_eq!(
        r.stderr,
        format!(
            "note: {}: 1 polygon(s) too degenerate to triangulate exactly (far off one plane) were cut as fans from their first corner\n",
            obj.display()
        )
    );
    // Inputs the fuzzers found, kept.
    for entry in std::fs::read_dir("../tests/fuzzed").unwrap() {
        let path = entry.unwrap().path();
        let r = render(&path, &[]);
        assert_eq!(r.code, Some(1), "{}: {}", path.display(), r.stderr);
    }
    // A full stderr, a closed stdout: status 1, no panic.
    let r = run_with(
        &[
            "render",
            "cube",
            "--cols",
            "20",
            "--rows",
            "6",
            "bad-model-x.obj",
        ],
        |c| {
            c.stderr(std::fs::File::create("/dev/full").unwrap());
        },
    );
    assert_eq!((r.code, r.signal), (Some(2), None));
    let r = run_with(&["render", "tests/data/short-face.obj"], |c| {
        c.stderr(std::fs::File::create("/dev/full").unwrap());
    });
    assert_eq!(r.code, Some(1));
    let r = run_with(&["render", "cube", "--cols", "20", "--rows", "6"], |c| {
        use std::os::unix::process::CommandExt;
        // SAFETY: closing stdout in the child before it runs.
        unsafe {
            c.pre_exec(|| {
                libc::close(1);
                Ok(())
            });
        }
    });
    assert_eq!(r.code, Some(1));
    assert_eq!(
        r.stderr,
        "error: <stdout>: Bad file descriptor (os error 9)\n"
    );
}

#[test]
fn the_smaller_holes_are_closed() {
    let d = dir("smaller");
    // A recording that cannot be written fails before the frame is drawn.
    let r = run(&[
        "render",
        "cube",
        "--cols",
        "20",
        "--rows",
        "6",
        "--record",
        "/nonexistent/x.cast",
    ]);
    assert_eq!(r.code, Some(1));
    assert!(r.stdout.is_empty());
    assert_eq!(
        r.stderr,
        "error: /nonexistent/x.cast: No such file or directory (os error 2)\n"
    );
    // An array longer than 3.
    let toml = put(&d, "a.toml", "[camera]\neye = [0, 0, 1, 2]\n");
    let r = render(&toml, &[]);
    assert_eq!(
        r.stderr,
        format!(
            "error: {}:2:7: invalid length 4, expected an array of 3\n",
            toml.display()
        )
    );
    // A buffer view past its buffer's byteLength.
    let json = triangle("", "").replace(
        r#""byteOffset":0,"byteLength":36}"#,
        r#""byteOffset":0,"byteLength":40}"#,
    );
    let model = put(&d, "v.glb", glb(&json, &f32s(&[0.0; 10])));
    let r = render(&model, &[]);
    assert_eq!(
        r.stderr,
        format!(
            "error: {}: buffer view 0 (40 bytes at offset 0) runs past the 36 bytes of buffer 0\n",
            model.display()
        )
    );
    // PLY errors are one line.
    let ply = put(
        &d,
        "b.ply",
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\nabc\n",
    );
    let r = refused(&ply);
    assert_eq!(r.stderr.lines().count(), 1, "{}", r.stderr);
    assert!(!r.stderr.contains("abc"), "{}", r.stderr);
    // bench with a folder that is not there.
    let r = run(&["bench", "--models", "/nonexistent", "--reps", "1"]);
    assert_eq!(r.code, Some(1));
    assert_eq!(
        r.stderr,
        "error: /nonexistent: not a folder of models (--models)\n"
    );
}

/// Makes a FIFO at `path`.
fn mkfifo(path: &Path) {
    let c = std::ffi::CString::new(path.to_str().unwrap()).unwrap();
    // SAFETY: a valid C string; mkfifo touches only the file system.
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o644) }, 0);
}

#[test]
fn a_fifo_swapped_in_while_a_model_is_opened_is_refused_within_a_bounded_count_of_tries() {
    use std::sync::atomic::{AtomicBool, Ordering};
    let d = dir("swap");
    let model = d.join("m.obj");
    let pristine = put(&d, "pristine", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    std::fs::copy(&pristine, &model).unwrap();
    let stop = std::sync::Arc::new(AtomicBool::new(false));
    // Swaps the model for a FIFO and back, each by one rename, as fast as
    // it can: a run may look at a file and open a FIFO.
    let swapper = {
        let (stop, d, model, pristine) = (stop.clone(), d.clone(), model.clone(), pristine.clone());
        std::thread::spawn(move || {
            let (file, fifo) = (d.join("next-file"), d.join("next-fifo"));
            while !stop.load(Ordering::Relaxed) {
                std::fs::hard_link(&pristine, &file).unwrap();
                std::fs::rename(&file, &model).unwrap();
                mkfifo(&fifo);
                std::fs::rename(&fifo, &model).unwrap();
            }
        })
    };
    // Every run ends (none waits on the FIFO), with the model drawn or one
    // of two refusals; the one that shows the race is seen within a
    // bounded number of runs.
    const TRIES: usize = 3000;
    let mut seen = None;
    for k in 0..TRIES {
        let r = run(&["render", s(&model), "--cols", "4", "--rows", "2"]);
        let pipe = format!("error: {}: is a named pipe, not a file\n", s(&model));
        let changed = format!(
            "error: {}: changed while being opened: it is now a named pipe\n",
            s(&model)
        );
        match (r.code, r.stderr.as_str()) {
            (Some(0), "") => {}
            (Some(1), e) if e == pipe => {}
            (Some(1), e) if e == changed => {
                seen = Some(k);
                break;
            }
            (code, e) => panic!("run {k}: {code:?} {e}"),
        }
    }
    stop.store(true, Ordering::Relaxed);
    swapper.join().unwrap();
    assert!(
        seen.is_some(),
        "no run opened the FIFO in {TRIES} tries: the race was not met"
    );
}

/// A GLB of two triangles sharing an edge, its four positions `p`, with
/// `node` the one node's JSON members and `mesh` the mesh's.
fn two_triangles(p: [[f32; 3]; 4], node: &str, mesh: &str) -> Vec<u8> {
    let mut bin = f32s(p.as_flattened());
    bin.extend([0u16, 1, 2, 1, 3, 2].iter().flat_map(|i| i.to_le_bytes()));
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0{node}}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]{mesh}}}],
"buffers":[{{"byteLength":{}}}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":48}},{{"buffer":0,"byteOffset":48,"byteLength":12}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}},
{{"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}}]}}"#,
        bin.len().next_multiple_of(4)
    );
    glb(&json, &bin)
}

/// A binary PLY of one triangle whose vertices are `p`.
fn ply_triangle(p: [[f32; 3]; 3]) -> Vec<u8> {
    let mut out = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n".to_vec();
    out.extend(f32s(p.as_flattened()));
    out.push(3);
    out.extend([0i32, 1, 2].iter().flat_map(|i| i.to_le_bytes()));
    out
}

#[test]
fn numbers_at_the_edge_of_f32_are_said_not_drawn_blank() {
    let d = dir("numbers");
    let square = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
    ];
    let mut one_nan = square;
    one_nan[3][0] = f32::NAN;
    let mut all_bad = square;
    all_bad[0][1] = f32::INFINITY;
    all_bad[2][2] = f32::NAN;
    let notes: [(&str, Vec<u8>, &str); 3] = [
        (
            "nan.glb",
            two_triangles(one_nan, "", ""),
            "note: NAME: 1 vertices are not finite numbers; the 1 faces that use them are not drawn\n",
        ),
        (
            "zero.glb",
            two_triangles(square, r#","rotation":[0,0,0,0]"#, ""),
            "note: NAME: node 0 has a rotation of four zeros, which is no rotation: drawn unrotated\n",
        ),
        (
            "tiny.glb",
            two_triangles(square, r#","scale":[3.4e38,3.4e38,1]"#, ""),
            "",
        ),
    ];
    for (name, bytes, want) in notes {
        let p = put(&d, name, bytes);
        let r = render(&p, &[]);
        assert_eq!(r.code, Some(0), "{name}: {}", r.stderr);
        assert_eq!(r.stderr, want.replace("NAME", s(&p)), "{name}");
        assert!(r.stdout.contains(&0xe2), "{name}: something is drawn");
    }
    let errors: [(&str, Vec<u8>, &str); 6] = [
        (
            "all.glb",
            two_triangles(all_bad, "", ""),
            "NAME: no triangles to draw: every one has a vertex that is not a finite number",
        ),
        (
            "far.glb",
            two_triangles(square, r#","translation":[0,1e39,0]"#, ""),
            "NAME: nodes[0].translation[1]: 1e39 is past the range of the 32-bit floats glTF's numbers are read as (±3.4e38)",
        ),
        (
            "matrix.glb",
            two_triangles(
                square,
                r#","matrix":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,-5e38,1]"#,
                "",
            ),
            "NAME: nodes[0].matrix[14]: -5e38 is past the range of the 32-bit floats glTF's numbers are read as (±3.4e38)",
        ),
        (
            "weights.glb",
            two_triangles(square, "", r#","weights":[1e40]"#),
            "NAME: meshes[0].weights[0]: 1e40 is past the range of the 32-bit floats glTF's numbers are read as (±3.4e38)",
        ),
        (
            "nan.ply",
            ply_triangle([[0.0, 0.0, 0.0], [f32::NAN, 0.0, 0.0], [0.0, 1.0, 0.0]]),
            "NAME: no faces to draw: every one has a vertex that is not a finite number",
        ),
        (
            "inf.ply",
            ply_triangle([
                [0.0, 0.0, f32::NEG_INFINITY],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
            ]),
            "NAME: no faces to draw: every one has a vertex that is not a finite number",
        ),
    ];
    for (name, bytes, want) in errors {
        let p = put(&d, name, bytes);
        let r = refused(&p);
        assert_eq!(
            r.stderr,
            format!("error: {}\n", want.replace("NAME", s(&p))),
            "{name}"
        );
    }
    // An eye fitted far away (a narrow lens, a zoom out) takes its far
    // plane with it: the teapot is drawn, as at the default lens.
    let teapot = concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/models/teapot.obj");
    for more in [
        &["--fov", "0.6", "--cols", "20", "--rows", "6"][..],
        &[
            "--fov", "10", "--zoom", "0.05", "--cols", "200", "--rows", "60",
        ],
    ] {
        let r = run(&[&["render", teapot][..], more].concat());
        assert_eq!(r.code, Some(0), "{more:?}: {}", r.stderr);
        assert!(r.stdout.contains(&0xe2), "{more:?}: a blank frame");
    }
}

#[test]
fn errors_from_other_crates_are_said_in_words() {
    let d = dir("words");
    let header = "ply\nformat ascii 1.0\n";
    let texture = |image: &str| {
        put(
            &d,
            &format!("{image}.mtl"),
            format!("newmtl m\nmap_Kd {image}\n"),
        );
        put(
            &d,
            &format!("{image}.obj"),
            format!(
                "mtllib {image}.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3\n"
            ),
        )
    };
    let mut bad_crc = png_header(2, 2);
    bad_crc[29] ^= 1; // the IHDR chunk's CRC
    put(&d, "crc.png", bad_crc);
    let jpeg = b"\xff\xd8\xff\xe0\x00\x10JFIF\x00";
    put(&d, "cut.jpg", jpeg);
    let cases: [(PathBuf, String); 6] = [
        (
            put(&d, "count.ply", format!("{header}element vertex -3\nproperty float x\nend_header\n")),
            "count.ply:3:16: not a header line PLY knows (expected a digit or a space)".into(),
        ),
        (
            put(&d, "word.ply", format!("{header}elemnt vertex 3\nend_header\n")),
            "word.ply:3:1: not a header line PLY knows (expected `comment`, `element`, `end_header`, `format`, `obj_info`, `ply` or `property`)".into(),
        ),
        (
            put(&d, "value.ply", format!("{header}element vertex 3\nproperty uchar x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n300 0 0\n")),
            "value.ply:10:1: \"300\" is too large for its type".into(),
        ),
        (
            put(&d, "clip.toml", "[[mesh]]\nshape = \"cube\"\nclip = -1\n"),
            "clip.toml:3:8: expected a clip's number, 0 or more (clip = 2), or its name (clip = \"walk\")".into(),
        ),
        (
            texture("crc.png"),
            "crc.png.mtl:2:8: DIR/crc.png: a damaged PNG image (CRC error: expected 0x5bcd3089 have 0x5acd3089 while decoding IHDR chunk)".into(),
        ),
        (
            texture("cut.jpg"),
            "cut.jpg.mtl:2:8: DIR/cut.jpg: a damaged JPEG image (not enough bytes, expected 1 but found 0)".into(),
        ),
    ];
    for (path, want) in cases {
        let r = refused(&path);
        let want = want.replace("DIR", s(&d));
        assert_eq!(
            r.stderr,
            format!("error: {}/{want}\n", s(&d)),
            "{}",
            path.display()
        );
        assert!(
            !r.stderr.contains(['{', '}']) || want.contains('{'),
            "{}",
            r.stderr
        );
    }
}

#[test]
fn stdout_that_is_dev_null_opened_read_write_is_written_to() {
    // Python's subprocess.DEVNULL, `1<>/dev/null`, systemd's
    // StandardOutput=null: /dev/null, read and write.
    let r = run_with(&["render", "cube", "--cols", "8", "--rows", "3"], |cmd| {
        let null = std::fs::File::options()
            .read(true)
            .write(true)
            .open("/dev/null")
            .unwrap();
        cmd.stdout(null);
    });
    assert_eq!((r.code, r.stderr.as_str()), (Some(0), ""));
    // Closed, it is refused.
    let r = run_with(&["render", "cube", "--cols", "8", "--rows", "3"], |cmd| {
        use std::os::unix::process::CommandExt;
        // SAFETY: only close(2) runs between fork and exec.
        unsafe {
            cmd.pre_exec(|| {
                libc::close(1);
                Ok(())
            });
        }
    });
    assert_eq!(
        (r.code, r.stderr.as_str()),
        (
            Some(1),
            "error: <stdout>: Bad file descriptor (os error 9)\n"
        )
    );
}

#[test]
fn a_preview_cuts_every_line_to_its_width_and_explain_cuts_the_environment() {
    let d = dir("preview");
    let model = put(
        &d,
        "notes.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 0 0\nf 1 2 3\nf 1 2 4\nl 1 2\n",
    );
    for width in ["5", "12", "30"] {
        let r = run(&[
            "render",
            s(&model),
            "--preview",
            "--cols",
            width,
            "--rows",
            "3",
        ]);
        assert_eq!(r.code, Some(0), "{}", r.stderr);
        let w: usize = width.parse().unwrap();
        assert!(!r.stderr.is_empty());
        for line in r.stderr.lines() {
            assert!(line.chars().count() <= w, "{width}: {line}");
        }
        let r = run(&["render", "typo.obj", "--preview", "--cols", width]);
        assert_eq!(r.code, Some(1));
        assert_eq!(
            r.stderr.trim_end().chars().count(),
            w.min(45),
            "{}",
            r.stderr
        );
    }
    let term = "x".repeat(5000);
    let r = run_with(
        &[
            "render",
            "cube",
            "--cols",
            "8",
            "--rows",
            "3",
            "--explain",
            "--color",
            "auto",
        ],
        |cmd| {
            cmd.env("TERM", &term);
        },
    );
    assert_eq!(r.code, Some(0));
    assert!(
        r.stderr.lines().all(|l| l.chars().count() < 300),
        "{}",
        r.stderr
    );
}
