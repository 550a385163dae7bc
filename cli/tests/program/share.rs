//! Sharing frames: `spin --record` and `render --record` write asciicast v2
//! files that replay to what `render` shows; `render --output` writes PNG
//! and SVG pictures whose pixels follow each cell's colours and glyph, and
//! ANSI or plain text.
//!
//! Recordings are read back as JSON by serde_json and replayed through the
//! `vt100` emulator; PNG files are decoded by the `png` crate; the SVG is
//! parsed by `roxmltree`. What a cell should look like comes from the same
//! frame written as ANSI and read back through `vt100`.

use crate::common;

use rastty::Choice;
use std::path::{Path, PathBuf};
use std::process::Command;

use common::{as_displayed, cells, terminal};
use rastty::GlyphMode;
use serde_json::Value;

const BIN: &str = env!("CARGO_BIN_EXE_rastty");
const FOX: &str = "tests/models/fox.obj";

/// Runs rastty with a fixed environment; returns stdout, or panics with
/// stderr.
fn run(args: &[&str]) -> Vec<u8> {
    let out = rastty(args).output().unwrap();
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
}

fn rastty(args: &[&str]) -> Command {
    let mut cmd = Command::new(BIN);
    cmd.args(args)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .env("TERM", "xterm-256color")
        .env("SHELL", "/bin/zsh")
        .env("SOURCE_DATE_EPOCH", "1700000000");
    cmd
}

/// A fresh directory for one test's files.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A recording's header and its events, each line parsed as JSON.
fn read_cast(path: &Path) -> (Value, Vec<(f64, String, String)>) {
    // Reading it as a String checks that it is UTF-8.
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Value = serde_json::from_str(lines.next().unwrap()).unwrap();
    let events = lines
        .map(|l| {
            let v: Value = serde_json::from_str(l).unwrap_or_else(|e| panic!("{e}: {l}"));
            let a = v.as_array().expect("an event is an array");
            assert_eq!(a.len(), 3, "{l}");
            (
                a[0].as_f64().unwrap(),
                a[1].as_str().unwrap().to_string(),
                a[2].as_str().unwrap().to_string(),
            )
        })
        .collect();
    (header, events)
}

/// The screen a recording leaves, replayed through vt100.
fn replay(header: &Value, events: &[(f64, String, String)]) -> vt100::Parser {
    let size = |k: &str| header[k].as_u64().unwrap() as u16;
    let mut vt = terminal(size("height"), size("width"));
    for (_, code, data) in events {
        assert_eq!(code, "o");
        vt.process(data.as_bytes());
    }
    vt
}

/// What `render ARGS` shows on a terminal of `rows × cols`.
fn rendered(args: &[&str], rows: u16, cols: u16) -> vt100::Parser {
    let mut vt = terminal(rows, cols);
    vt.process(&as_displayed(&run(&[&["render"][..], args].concat())));
    vt
}

#[test]
fn a_spin_recording_is_asciicast_v2_and_replays_to_the_render_at_the_last_angle() {
    let dir = scratch("spin-cast");
    let cast = dir.join("fox.cast");
    let view = ["--cols", "48", "--rows", "14", "--glyphs", "quadrant"];
    let out = run(&[
        &[
            "spin", FOX, "--frames", "10", "--fps", "8", "--step", "9", "--record",
        ][..],
        &[cast.to_str().unwrap()],
        &view,
    ]
    .concat());
    assert!(out.is_empty(), "the frames go to the file, not stdout");

    let (header, events) = read_cast(&cast);
    assert_eq!(
        header,
        serde_json::json!({
            "version": 2, "width": 48, "height": 14, "timestamp": 1700000000u64,
            "env": {"TERM": "xterm-256color", "SHELL": "/bin/zsh"}
        })
    );
    // Every frame turns the fox, so each is an event, frame k at k/8 s;
    // then the end, at the last frame's time: colours reset, the cursor
    // below the picture and shown, for the shell after `asciinema play`.
    let (end, events) = events.split_last().unwrap();
    let times: Vec<f64> = events.iter().map(|e| e.0).collect();
    assert_eq!(times, (0..10).map(|k| k as f64 / 8.0).collect::<Vec<_>>());
    assert!(events[0].2.starts_with("\x1b[?25l"), "the cursor is hidden");
    assert_eq!(
        (end.0, end.1.as_str(), end.2.as_str()),
        (9.0 / 8.0, "o", "\x1b[0m\x1b[14;1H\r\n\x1b[?25h")
    );

    // Frame 9 is turned by 81 degrees; with no terminal, --color auto is
    // truecolor in a recording.
    let replayed = replay(&header, events);
    let expected = rendered(
        &[&[FOX, "--yaw", "81", "--color", "truecolor"][..], &view].concat(),
        14,
        48,
    );
    assert_eq!(cells(replayed.screen()), cells(expected.screen()));

    // The same file every time.
    let again = dir.join("again.cast");
    run(&[
        &[
            "spin", FOX, "--frames", "10", "--fps", "8", "--step", "9", "--record",
        ][..],
        &[again.to_str().unwrap()],
        &view,
    ]
    .concat());
    assert_eq!(
        std::fs::read(&cast).unwrap(),
        std::fs::read(&again).unwrap()
    );
}

#[test]
fn a_render_recording_is_one_frame_at_time_zero() {
    let dir = scratch("render-cast");
    let cast = dir.join("one.cast");
    let view = ["--cols", "30", "--rows", "10", "--color", "256"];
    let stdout = run(&[
        &["render", FOX, "--record", cast.to_str().unwrap()][..],
        &view,
    ]
    .concat());
    let (header, events) = read_cast(&cast);
    assert_eq!(
        (header["width"].as_u64(), header["height"].as_u64()),
        (Some(30), Some(10))
    );
    assert_eq!(events.len(), 2);
    assert_eq!(events[0].0, 0.0);
    assert_eq!(
        events[1],
        (0.0, "o".into(), "\x1b[0m\x1b[10;1H\r\n\x1b[?25h".into())
    );
    let events = &events[..1];
    // The frame is still printed, and the recording shows the same.
    let mut printed = terminal(10, 30);
    printed.process(&as_displayed(&stdout));
    assert_eq!(
        cells(replay(&header, events).screen()),
        cells(printed.screen())
    );
}

/// A decoded PNG: width, height, RGB bytes.
fn decode_png(path: &Path) -> (u32, u32, Vec<u8>) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb);
    assert_eq!(info.bit_depth, png::BitDepth::Eight);
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

/// A vt100 colour as RGB: the picture's default theme is xterm's light grey
/// on black.
fn rgb(c: vt100::Color, foreground: bool) -> [u8; 3] {
    match c {
        vt100::Color::Rgb(r, g, b) => [r, g, b],
        vt100::Color::Default if foreground => [229, 229, 229],
        vt100::Color::Default => [0, 0, 0],
        vt100::Color::Idx(i) => panic!("an indexed colour {i} in a truecolor frame"),
    }
}

/// Part edges of a cell: `⌊i·px/n⌋`, as the picture module documents.
fn edge(i: u32, px: u32, n: u32) -> u32 {
    i * px / n
}

/// Checks every pixel of a picture of `mode` against the cells `render`
/// prints for the same arguments: each sub-cell's pixels are the
/// foreground where the glyph covers it, the background elsewhere; a
/// braille cell's dot centres are the foreground where a dot is raised and
/// its corners the background.
fn check_png(mode: GlyphMode, cell: (u32, u32)) {
    let dir = scratch(&format!("png-{}-{}x{}", mode.name(), cell.0, cell.1));
    let path = dir.join("fox.png");
    let (cols, rows) = (40u32, 12u32);
    let px = format!("{}x{}", cell.0, cell.1);
    let view = [
        FOX,
        "--cols",
        "40",
        "--rows",
        "12",
        "--glyphs",
        mode.name(),
        "--color",
        "truecolor",
        // The frame the picture is painted from is drawn for its cell
        // shape; the printed one is told the same.
        "--cell-aspect",
        &format!("{}", cell.0 as f32 / cell.1 as f32),
    ];
    run(&[
        &["render"][..],
        &view,
        &["--cell-px", &px, "--output", path.to_str().unwrap()],
    ]
    .concat());
    let (w, h, pixels) = decode_png(&path);
    assert_eq!((w, h), (cols * cell.0, rows * cell.1));
    let at = |x: u32, y: u32| -> [u8; 3] {
        let i = ((y * w + x) * 3) as usize;
        [pixels[i], pixels[i + 1], pixels[i + 2]]
    };
    let screen = rendered(&view, rows as u16, cols as u16);
    let (sw, sh) = mode.cell_size();
    let mut covered = 0;
    for row in 0..rows {
        for col in 0..cols {
            let c = screen.screen().cell(row as u16, col as u16).unwrap();
            let ch = c.contents().chars().next().unwrap_or(' ');
            let (fg, bg) = (rgb(c.fgcolor(), true), rgb(c.bgcolor(), false));
            let mask = if ch == ' ' {
                0
            } else {
                mode.pattern(ch).expect("a glyph of the mode")
            };
            // Block mode paints cells with their background alone.
            covered += (mask != 0 || bg != [0, 0, 0]) as u32;
            let (x0, y0) = (col * cell.0, row * cell.1);
            for r in 0..sh {
                for k in 0..sw {
                    let on = mask >> (r * sw + k) & 1 == 1;
                    let (a, b) = (x0 + edge(k, cell.0, sw), x0 + edge(k + 1, cell.0, sw));
                    let (t, u) = (y0 + edge(r, cell.1, sh), y0 + edge(r + 1, cell.1, sh));
                    if mode == GlyphMode::Braille {
                        // The dot's centre, and the sub-cell's top-left corner.
                        let want = if on { fg } else { bg };
                        assert_eq!(
                            at((a + b) / 2, (t + u) / 2),
                            want,
                            "{ch} at {col},{row} dot {r},{k}"
                        );
                        assert_eq!(at(a, t), bg, "{ch} at {col},{row}: corner of dot {r},{k}");
                        continue;
                    }
                    let want = if on { fg } else { bg };
                    for y in t..u {
                        for x in a..b {
                            assert_eq!(at(x, y), want, "{ch:?} at cell {col},{row}, pixel {x},{y}");
                        }
                    }
                }
            }
        }
    }
    assert!(covered > 40, "the fox is in the picture ({covered} cells)");
}

#[test]
fn a_png_paints_each_sub_cell_in_the_colour_its_glyph_gives_it() {
    for mode in [
        GlyphMode::Block,
        GlyphMode::Half,
        GlyphMode::Quadrant,
        GlyphMode::Sextant,
        GlyphMode::Octant,
    ] {
        check_png(mode, (8, 16));
    }
    // Cells that do not divide evenly: sextant rows of 4, 5 and 5 pixels.
    check_png(GlyphMode::Sextant, (7, 14));
    check_png(GlyphMode::Octant, (5, 11));
}

#[test]
fn a_png_draws_braille_as_dots() {
    check_png(GlyphMode::Braille, (8, 16));
    check_png(GlyphMode::Braille, (10, 20));
}

#[test]
fn an_svg_parses_as_xml_at_the_picture_size_in_the_frame_colours() {
    let dir = scratch("svg");
    let path = dir.join("fox.svg");
    let view = [
        FOX, "--cols", "40", "--rows", "12", "--glyphs", "sextant", "--color", "256",
    ];
    run(&[
        &["render"][..],
        &view,
        &["--output", path.to_str().unwrap(), "--cell-px", "6x12"],
    ]
    .concat());
    let text = std::fs::read_to_string(&path).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    let svg = doc.root_element();
    assert_eq!(svg.tag_name().name(), "svg");
    assert_eq!(
        svg.tag_name().namespace(),
        Some("http://www.w3.org/2000/svg")
    );
    assert_eq!(
        (svg.attribute("width"), svg.attribute("height")),
        (Some("240"), Some("144"))
    );

    // Every colour it paints is one the terminal is told (256 colours: an
    // xterm palette entry), and every foreground of the frame is painted.
    let screen = rendered(&[&view[..], &["--cell-aspect", "0.5"]].concat(), 12, 40);
    let palette = |c: vt100::Color| match c {
        vt100::Color::Idx(i) => Some(rastty::color::xterm256(i).to_string()),
        _ => None,
    };
    let mut told = std::collections::BTreeSet::new();
    let mut foregrounds = std::collections::BTreeSet::new();
    for (text, fg, bg) in cells(screen.screen()) {
        told.extend(palette(bg));
        if text != " " {
            told.extend(palette(fg));
            foregrounds.extend(palette(fg));
        }
    }
    let painted: std::collections::BTreeSet<String> = svg
        .descendants()
        .filter_map(|n| n.attribute("fill"))
        .filter(|&f| f != "#000000")
        .map(str::to_string)
        .collect();
    assert!(painted.is_subset(&told), "{painted:?} ⊄ {told:?}");
    assert!(
        foregrounds.is_subset(&painted),
        "{foregrounds:?} ⊄ {painted:?}"
    );
}

#[test]
fn ans_and_txt_outputs_are_what_render_prints() {
    let dir = scratch("ans-txt");
    let view = [FOX, "--cols", "30", "--rows", "9", "--glyphs", "octant"];
    let ans = dir.join("fox.ans");
    let txt = dir.join("fox.TXT");
    let out = run(&[
        &["render"][..],
        &view,
        &["--color", "16", "-o", ans.to_str().unwrap()],
    ]
    .concat());
    assert!(out.is_empty());
    run(&[&["render"][..], &view, &["-o", txt.to_str().unwrap()]].concat());
    assert_eq!(
        std::fs::read(&ans).unwrap(),
        run(&[&["render"][..], &view, &["--color", "16"]].concat())
    );
    assert_eq!(
        std::fs::read(&txt).unwrap(),
        run(&[&["render"][..], &view, &["--color", "none"]].concat())
    );
}

#[test]
fn bad_outputs_are_refused_with_one_line_and_no_file() {
    let dir = scratch("bad-output");
    let cases: [(&[&str], &str); 4] = [
        (
            &["-o", "x.jpg"],
            "x.jpg: the output format comes from the extension: .png, .svg, .ans or .txt\n",
        ),
        (
            &["-o", "x.png", "--cell-px", "0x16"],
            "'0' in '0x16' is not a whole number of pixels from 1 to 256",
        ),
        (
            &[
                "-o",
                "x.png",
                "--cols",
                "1000",
                "--rows",
                "1000",
                "--cell-px",
                "16x32",
            ],
            "error: a picture of 1000×1000 cells at 16×32 pixels a cell would be 16000×32000 pixels, more than 67108864",
        ),
        (
            &["-o", "no/such/dir/x.png"],
            "error: no/such/dir/x.png: No such file or directory",
        ),
    ];
    for (args, message) in cases {
        let out = rastty(&[&["render"][..], args].concat())
            .current_dir(&dir)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?}");
        assert!(err.contains(message), "{args:?}: {err}");
        assert!(out.stdout.is_empty());
    }
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        0,
        "no file was made"
    );
}

/// What a folder holds: each entry's name, and its bytes (a file), where
/// it points (a link), or what else it is.
fn contents(dir: &Path) -> std::collections::BTreeMap<String, String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            let path = e.path();
            let kind = e.file_type().unwrap();
            let what = if kind.is_symlink() {
                format!("link to {}", std::fs::read_link(&path).unwrap().display())
            } else if kind.is_file() {
                format!("{:?}", std::fs::read(&path).unwrap())
            } else {
                format!("{kind:?}")
            };
            (e.file_name().to_string_lossy().into_owned(), what)
        })
        .collect()
}

/// A folder as a user has it: a textured OBJ (its MTL and PNG), a second
/// name of the model (a hard link), a link to the texture, an existing
/// `out.EXT` and a link to it.
fn users_folder(name: &str, ext: &str) -> PathBuf {
    let dir = scratch(name);
    std::fs::write(
        dir.join("model.obj"),
        "mtllib model.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3\n",
    )
    .unwrap();
    std::fs::write(dir.join("model.mtl"), "newmtl m\nmap_Kd tex.png\n").unwrap();
    std::fs::write(
        dir.join("tex.png"),
        common::png_rgb(2, 2, &[[255, 0, 0], [0, 255, 0], [0, 0, 255], [9, 9, 9]]),
    )
    .unwrap();
    std::fs::hard_link(dir.join("model.obj"), dir.join("hard.obj")).unwrap();
    std::os::unix::fs::symlink("tex.png", dir.join("tex-link.png")).unwrap();
    std::fs::write(dir.join(format!("out.{ext}")), "old").unwrap();
    std::os::unix::fs::symlink(format!("out.{ext}"), dir.join(format!("link.{ext}"))).unwrap();
    dir
}

/// Every writing flag, as `(name, extension, arguments writing to TARGET,
/// the same failing after the work has begun)`.
fn writing_flags() -> Vec<(
    &'static str,
    &'static str,
    Vec<&'static str>,
    Vec<&'static str>,
)> {
    let view = ["--cols", "8", "--rows", "3"];
    let render = |flag| [&["render", "model.obj"][..], &view, &[flag, "TARGET"]].concat();
    let spin = [
        &["spin", "model.obj", "--frames", "2"][..],
        &view,
        &["--record", "TARGET"],
    ]
    .concat();
    // The camera is refused once the model is read: the file to write has
    // been begun by then.
    let late = |mut args: Vec<&'static str>| {
        args.extend(["--distance", "1e38"]);
        args
    };
    vec![
        (
            "render --output",
            "png",
            render("--output"),
            late(render("--output")),
        ),
        (
            "render --record",
            "cast",
            render("--record"),
            late(render("--record")),
        ),
        ("spin --record", "cast", spin.clone(), late(spin)),
        (
            "bench --svg",
            "svg",
            vec!["bench", "--reps", "1", "--models", ".", "--svg", "TARGET"],
            vec![
                "bench", "--reps", "1", "--models", "nothing", "--svg", "TARGET",
            ],
        ),
    ]
}

/// `args` run in `dir` with `TARGET` replaced by `target`.
fn write_to(dir: &Path, args: &[&str], target: &str) -> std::process::Output {
    let args: Vec<&str> = args
        .iter()
        .map(|&a| if a == "TARGET" { target } else { a })
        .collect();
    rastty(&args)
        .current_dir(dir)
        .stdin(std::process::Stdio::null())
        .output()
        .unwrap()
}

#[test]
fn a_failed_run_leaves_every_file_as_it_was_and_a_good_one_changes_only_its_target() {
    for (name, ext, good, bad) in writing_flags() {
        let dir = users_folder(&format!("keep-{ext}-{}", name.len()), ext);
        let before = contents(&dir);
        let out = format!("out.{ext}");
        for target in [out.as_str(), "new.x", "link.x"].map(|t| t.replace(".x", &format!(".{ext}")))
        {
            let r = write_to(&dir, &bad, &target);
            assert!(!r.status.success(), "{name} {target}");
            assert_eq!(contents(&dir), before, "{name} {target}: a failed run");
        }
        // Written through the link: the link stays, the file it names is
        // replaced, nothing else changes and nothing is left beside it.
        let r = write_to(&dir, &good, &format!("link.{ext}"));
        assert!(
            r.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&r.stderr)
        );
        let after = contents(&dir);
        assert_ne!(after[&out], before[&out], "{name}");
        let mut others = after.clone();
        others.insert(out.clone(), before[&out].clone());
        assert_eq!(others, before, "{name}: only the target changes");
        if ext == "cast" {
            assert!(
                std::fs::read_to_string(dir.join(&out))
                    .unwrap()
                    .starts_with("{\"version\":2"),
                "{name}"
            );
        }
    }
}

#[test]
fn a_file_the_model_reads_is_never_written_whatever_it_is_called() {
    for (name, ext, good, _) in writing_flags() {
        if name.starts_with("bench") {
            continue; // bench reads no model.
        }
        let dir = users_folder(&format!("sources-{ext}-{}", name.len()), ext);
        let before = contents(&dir);
        for target in [
            "model.obj",
            "./model.obj",
            "hard.obj",
            "model.mtl",
            "tex.png",
            "tex-link.png",
        ] {
            let r = write_to(&dir, &good, target);
            let err = String::from_utf8_lossy(&r.stderr);
            assert_eq!(r.status.code(), Some(1), "{name} {target}: {err}");
            // A picture is named by its extension: `--output model.obj` is
            // refused for that before anything.
            let by_identity = name != "render --output" || target.ends_with(".png");
            assert!(
                !by_identity
                    || (err.starts_with(&format!("error: {target}: "))
                        && err.ends_with(
                            "rastty writes nothing over a file it reads (name another)\n"
                        )),
                "{name} {target}: {err}"
            );
            assert_eq!(contents(&dir), before, "{name} {target}");
        }
    }
    // Two outputs naming one file.
    let dir = users_folder("two-outputs", "cast");
    let r = write_to(
        &dir,
        &[
            "render",
            "model.obj",
            "-o",
            "out.cast.txt",
            "--record",
            "./out.cast.txt",
        ],
        "",
    );
    assert_eq!(
        String::from_utf8_lossy(&r.stderr),
        "error: out.cast.txt and ./out.cast.txt name the same file: give each output its own\n"
    );
}

#[test]
fn a_pipe_or_a_device_is_written_through_and_never_removed() {
    let dir = users_folder("streams", "cast");
    // A FIFO, read by another process as it is written.
    let fifo = dir.join("out.fifo");
    let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success());
    let reader = Command::new("cat")
        .arg(&fifo)
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let r = write_to(
        &dir,
        &["render", "model.obj", "--record", "TARGET"],
        "out.fifo",
    );
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let read = reader.wait_with_output().unwrap().stdout;
    assert!(read.starts_with(b"{\"version\":2"));
    use std::os::unix::fs::FileTypeExt;
    assert!(std::fs::metadata(&fifo).unwrap().file_type().is_fifo());
    // /dev/stdout is the descriptor as it is: the recording follows the
    // frame on the same pipe.
    let r = write_to(
        &dir,
        &[
            "render",
            "model.obj",
            "--cols",
            "8",
            "--rows",
            "3",
            "--record",
            "TARGET",
        ],
        "/dev/stdout",
    );
    assert!(r.status.success());
    let text = String::from_utf8_lossy(&r.stdout);
    assert!(text.contains("{\"version\":2"), "{text}");
    // A device, failed and not: in a mount namespace of the test's own, a
    // device node made for it (as root; /dev/null itself is not risked).
    if Command::new("unshare")
        .args(["-m", "true"])
        .status()
        .is_ok_and(|s| s.success())
    {
        let script = format!(
            "mount -t tmpfs none {d} && mknod {d}/null c 1 3 && cd {m} && \
             {bin} render model.obj --record {d}/null --distance 1e38; \
             {bin} render model.obj --record {d}/null --cols 8 --rows 3 >/dev/null && test -c {d}/null && echo kept",
            d = dir.join("dev").display(),
            m = dir.display(),
            bin = BIN
        );
        std::fs::create_dir_all(dir.join("dev")).unwrap();
        let out = Command::new("unshare")
            .args(["-m", "sh", "-c", &script])
            .output()
            .unwrap();
        assert_eq!(
            String::from_utf8_lossy(&out.stdout),
            "kept\n",
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    } else {
        eprintln!(
            "no mount namespace here (not root): the device case is checked through /dev/null alone"
        );
        let r = write_to(
            &dir,
            &["render", "model.obj", "--record", "TARGET"],
            "/dev/null",
        );
        assert!(r.status.success());
    }
}
