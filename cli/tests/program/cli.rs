//! The `rastty` binary as a user meets it: frames on stdout, and for bad
//! input one `error:` line on stderr naming the file (and line), a non-zero
//! exit, and never a panic.

use rastty::Choice;
use std::process::{Command, Output};

fn rastty(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rastty"))
        .args(args)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .env_remove("NO_COLOR")
        .output()
        .expect("runs")
}

/// Runs a command that must fail; returns its stderr.
fn fails(args: &[&str]) -> String {
    let out = rastty(args);
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(!out.status.success(), "{args:?} succeeded");
    assert!(out.stdout.is_empty(), "{args:?} printed a frame");
    assert!(stderr.starts_with("error: "), "{args:?}: {stderr}");
    assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    stderr
}

fn stdout(args: &[&str]) -> String {
    let out = rastty(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn render_prints_the_default_scene_80_by_24_when_piped() {
    let text = stdout(&["render"]);
    assert_eq!(text.lines().count(), 24);
    assert!(text.lines().all(|l| l.chars().count() == 80));
    // Piped, auto colour is none: plain text, no escape sequences.
    assert!(!text.contains('\x1b'));
    // No arguments at all renders the same frame.
    assert_eq!(stdout(&[]), text);
}

#[test]
fn render_a_scene_file_in_plain_text() {
    insta::assert_snapshot!(stdout(&[
        "render",
        "examples/scenes/shared-edge.toml",
        "--cols",
        "30",
        "--rows",
        "10",
        "--glyphs",
        "ascii",
        "--color",
        "none"
    ]));
}

#[test]
fn explicit_truecolor_wins_over_a_pipe() {
    let text = stdout(&[
        "render",
        "examples/scenes/triangle.toml",
        "--color",
        "truecolor",
        "--cols",
        "20",
        "--rows",
        "8",
    ]);
    assert!(text.contains("\x1b[48;2;255;136;0m"), "{text:?}");
    assert!(text.lines().all(|l| l.ends_with("\x1b[m")));
}

#[test]
fn the_three_traversals_print_the_same_frame() {
    let base = [
        "render",
        "examples/scenes/perspective.toml",
        "--cols",
        "50",
        "--rows",
        "16",
        "--color",
        "none",
    ];
    let frames: Vec<String> = ["scan", "bounding-box", "incremental"]
        .iter()
        .map(|t| stdout(&[&base[..], &["--traversal", t]].concat()))
        .collect();
    assert_eq!(frames[0], frames[1]);
    assert_eq!(frames[1], frames[2]);
}

#[test]
fn cell_aspect_changes_the_projection() {
    let args = |r| {
        [
            "render",
            "examples/scenes/triangle.toml",
            "--cols",
            "40",
            "--rows",
            "12",
            "--cell-aspect",
            r,
            "--color",
            "none",
        ]
    };
    let narrow = stdout(&args("0.5"));
    let square = stdout(&args("1.0"));
    // Square cells: the triangle needs half as many columns.
    let width = |f: &str| f.lines().map(|l| l.trim().chars().count()).max().unwrap();
    assert!(
        width(&square) * 2 <= width(&narrow) + 2,
        "{narrow}\n{square}"
    );
}

#[test]
fn missing_scene_file() {
    insta::assert_snapshot!(fails(&["render", "no/such/scene.toml"]));
}

#[test]
fn directory_instead_of_a_scene() {
    insta::assert_snapshot!(fails(&["render", "examples"]));
}

#[test]
fn wrong_type_names_file_line_and_column() {
    insta::assert_snapshot!(fails(&["render", "tests/data/bad-type.toml"]));
}

#[test]
fn unknown_key_names_the_key_and_line() {
    insta::assert_snapshot!(fails(&["render", "tests/data/unknown-key.toml"]));
}

#[test]
fn malformed_toml() {
    insta::assert_snapshot!(fails(&["render", "tests/data/malformed.toml"]));
}

/// A bad command line gets clap's own message: what was wrong, the
/// possible values, a suggestion where one is close; exit status 2.
#[test]
fn unknown_option_values_and_absurd_sizes() {
    let mut report = String::new();
    for args in [
        &["render", "--glyphs", "octnt"][..],
        &["render", "--color", "sepia"],
        &["render", "--cols", "0"],
        &["render", "--rows", "0"],
        &["render", "--cols", "100000"],
        &["render", "--cols", "-3"],
        &["render", "--cell-aspect", "0"],
        &["render", "--cell-aspect", "nan"],
        &["render", "--frobnicate"],
        &["spin", "--fps", "0"],
    ] {
        let out = rastty(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = fails(args);
        report.push_str(&format!("$ rastty {}\n{err}\n", args.join(" ")));
    }
    insta::assert_snapshot!(report);
}

#[test]
fn a_model_named_where_a_command_belongs_gets_the_command_that_shows_it() {
    let out = rastty(&["tests/models/bunny.obj"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.starts_with("error: 'tests/models/bunny.obj' is not a command; to show it, run\n\n  rastty spin tests/models/bunny.obj\n"),
        "{err}"
    );
    assert!(fails(&["bogus"]).starts_with("error: unrecognized subcommand 'bogus'"));
}

/// Every setting's name, as the status line and notices write it, is one
/// the command line accepts.
#[test]
fn settings_are_named_as_the_command_line_names_them() {
    let tiny = ["render", "--cols", "4", "--rows", "2"];
    let accepted = |flag: &str, name: &str| {
        stdout(&[&tiny[..], &[flag, name]].concat());
    };
    for &mode in rastty::GlyphMode::ALL {
        accepted("--glyphs", mode.name());
    }
    for &shading in rastty::Shading::ALL {
        accepted("--shading", shading.name());
    }
    for &t in rastty::raster::Traversal::ALL {
        accepted("--traversal", t.name());
    }
    for &p in rastty::raster::Precision::ALL {
        accepted("--precision", p.name());
    }
    for &aa in rastty::Aa::ALL {
        accepted("--aa", aa.name());
    }
    for depth in rastty::color::ColorDepth::ALL {
        stdout(&[
            "render",
            "--color",
            depth.name(),
            "--cols",
            "4",
            "--rows",
            "2",
        ]);
    }
}

#[test]
fn every_glyph_mode_with_every_colour_depth() {
    for glyphs in [
        "ascii", "block", "half", "quadrant", "sextant", "octant", "braille",
    ] {
        for color in ["none", "16", "256", "truecolor"] {
            let text = stdout(&[
                "render", "--glyphs", glyphs, "--color", color, "--cols", "24", "--rows", "8",
            ]);
            assert_eq!(text.lines().count(), 8, "{glyphs} {color}");
            assert_eq!(color == "none", !text.contains('\x1b'), "{glyphs} {color}");
        }
    }
}

#[test]
fn auto_colour_is_none_when_piped_even_with_colorterm() {
    let out = Command::new(env!("CARGO_BIN_EXE_rastty"))
        .args(["render", "--cols", "10", "--rows", "3"])
        .env("COLORTERM", "truecolor")
        .env("TERM", "xterm-256color")
        .output()
        .unwrap();
    assert!(!out.stdout.contains(&0x1b));
}

#[test]
fn spin_help_shows_everyday_options_first_in_groups() {
    let help = String::from_utf8(rastty(&["spin", "-h"]).stdout).unwrap();
    let headings: Vec<&str> = help
        .lines()
        .filter(|l| !l.starts_with(' ') && l.ends_with(':'))
        .collect();
    assert_eq!(
        headings,
        [
            "Options:",
            "View:",
            "Camera:",
            "Spin:",
            "Model:",
            "Output:",
            "Accuracy and speed knobs:",
            "Budgets:",
            "Keys and mouse:"
        ]
    );
    let after = |heading: &str, option: &str| {
        let h = help.find(heading).unwrap();
        let o = help.find(option).unwrap();
        assert!(o > h, "{option} under {heading}");
    };
    for knob in [
        "--traversal",
        "--precision",
        "--split",
        "--interpolation",
        "--full-pipeline",
    ] {
        after("Accuracy and speed knobs:", knob);
    }
    after("Budgets:", "--max-texels");
    assert!(
        help.contains(".gltf") && help.contains(".ply"),
        "[SCENE] lists every format"
    );
}

#[test]
fn an_option_before_the_command_gets_a_hint() {
    let out = rastty(&["--hud", "--cols", "40"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.ends_with("hint: options follow a command: rastty spin --hud --cols 40\n"),
        "{err}"
    );
}

#[test]
fn background_paints_the_uncovered_cells() {
    let frame = |bg: &str| {
        String::from_utf8(
            rastty(&[
                "render",
                "cube",
                "--cols",
                "30",
                "--rows",
                "8",
                "--color",
                "truecolor",
                "--background",
                bg,
            ])
            .stdout,
        )
        .unwrap()
    };
    assert!(frame("#102030").contains("48;2;16;32;48"));
    assert!(!frame("terminal").contains("48;2;16;32;48"));
    let bad = rastty(&["render", "cube", "--background", "grey"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&bad.stderr)
            .contains("\"grey\" is not a colour: #rrggbb, or `terminal`")
    );
}

#[test]
fn color_24bit_and_direct_are_truecolor() {
    let frame = |c: &str| {
        rastty(&[
            "render", "torus", "--cols", "30", "--rows", "8", "--color", c,
        ])
        .stdout
    };
    let truecolor = frame("truecolor");
    assert!(truecolor.windows(5).any(|w| w == b"[38;2"));
    assert_eq!(frame("24bit"), truecolor);
    assert_eq!(frame("direct"), truecolor);
}

#[test]
fn an_obj_without_its_mtl_is_drawn_in_the_default_colour_with_a_note() {
    let out = Command::new(env!("CARGO_BIN_EXE_rastty"))
        .args([
            "render",
            "tests/data/missing-mtl.obj",
            "--cols",
            "20",
            "--rows",
            "6",
        ])
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    assert_eq!(
        String::from_utf8(out.stderr).unwrap(),
        "note: tests/data/missing-mtl.obj:1:8: material library \"nowhere.mtl\" not found: drawn in the default colour\n"
    );
    // The same frame as the model without its `mtllib` line.
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("no-mtllib");
    std::fs::create_dir_all(&dir).unwrap();
    let src = std::fs::read_to_string("../tests/data/missing-mtl.obj").unwrap();
    let plain = dir.join("plain.obj");
    std::fs::write(&plain, src.replace("mtllib nowhere.mtl\n", "")).unwrap();
    let want = Command::new(env!("CARGO_BIN_EXE_rastty"))
        .args([
            "render",
            plain.to_str().unwrap(),
            "--cols",
            "20",
            "--rows",
            "6",
        ])
        .output()
        .unwrap();
    assert_eq!(out.stdout, want.stdout);
}

/// Every kind of bad input: one line on stderr naming the file (and the
/// line where the format has lines), a non-zero exit, no panic.
#[test]
fn bad_input_gets_one_clear_line() {
    let mut report = String::new();
    for (what, args) in [
        (
            "OBJ with a bad number",
            &["render", "tests/data/bad-number.obj"][..],
        ),
        (
            "OBJ face of two vertices",
            &["render", "tests/data/short-face.obj"],
        ),
        (
            "OBJ index out of range",
            &["render", "tests/data/out-of-range.obj"],
        ),
        (
            "truncated binary STL",
            &["render", "tests/data/truncated.stl"],
        ),
        (
            "ASCII STL with a bad number",
            &["render", "tests/data/bad-ascii.stl"],
        ),
        ("empty OBJ", &["render", "tests/data/empty.obj"]),
        ("empty STL", &["render", "tests/data/empty.stl"]),
        ("empty scene", &["render", "tests/data/empty.toml"]),
        ("a directory as a model", &["render", "tests/models/"]),
        (
            "a directory named like a model",
            &["spin", "tests/data/dir.obj", "--frames", "1"],
        ),
        ("NaN in a scene", &["render", "tests/data/nan-eye.toml"]),
        (
            "infinity in a scene",
            &["render", "tests/data/inf-vertex.toml"],
        ),
        (
            "wrong type in a scene",
            &["render", "tests/data/bad-type.toml"],
        ),
        (
            "unknown key in a scene",
            &["render", "tests/data/unknown-key.toml"],
        ),
        ("not a model", &["render", "README.md"]),
    ] {
        let err = fails(args);
        assert_eq!(err.lines().count(), 1, "{what}: {err}");
        report.push_str(&format!("{what}\n  {err}"));
    }
    insta::assert_snapshot!(report);
}

#[test]
fn a_path_that_is_not_utf8_is_named_as_best_it_can() {
    use std::os::unix::ffi::OsStrExt;
    let name = std::ffi::OsStr::from_bytes(b"tests/data/\xff\xfe.toml");
    let out = Command::new(env!("CARGO_BIN_EXE_rastty"))
        .arg("render")
        .arg(name)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(
        err,
        "error: tests/data/\u{fffd}\u{fffd}.toml: No such file or directory (os error 2)\n"
    );
}

/// `--frames` is a count, never a capacity: the largest is streamed until
/// the reader goes away, with no allocation sized by it.
#[test]
fn a_huge_frame_count_streams_until_the_reader_stops() {
    use std::io::Read;
    for frames in ["18446744073709551615", "100000000000"] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_rastty"))
            .args(["spin", "--frames", frames, "--cols", "20", "--rows", "6"])
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        let mut out = child.stdout.take().unwrap();
        let mut first = [0u8; 1];
        out.read_exact(&mut first).unwrap();
        drop(out);
        let status = child.wait().unwrap();
        let mut err = String::new();
        child
            .stderr
            .take()
            .unwrap()
            .read_to_string(&mut err)
            .unwrap();
        assert!(status.success(), "{frames}: {status:?} {err}");
        assert!(err.is_empty(), "{frames}: {err}");
    }
}

#[test]
fn explain_says_which_colour_depth_and_why() {
    let colour_line = |args: &[&str]| {
        let out = rastty(args);
        assert!(out.status.success());
        let err = String::from_utf8(out.stderr).unwrap();
        err.lines()
            .find(|l| l.starts_with("colour: "))
            .unwrap_or_else(|| panic!("no colour line in {err}"))
            .to_string()
    };
    let base = ["render", "--explain", "--cols", "8", "--rows", "3"];
    assert_eq!(
        colour_line(&base),
        "colour: none (stdout is not a terminal)"
    );
    assert_eq!(
        colour_line(&[&base[..], &["--color", "256"]].concat()),
        "colour: 256 (--color says so), matched in oklch, dithering ordered"
    );
    assert_eq!(
        colour_line(&[&base[..], &["--color", "16", "--dither", "none"]].concat()),
        "colour: 16 (--color says so), matched in oklch, dithering none"
    );
}

/// The README's and the usage page's tables of keys, `spin --help` and
/// the help box (`?`) are one list: `rastty::animate::KEYS`.
#[test]
fn the_keys_tables_and_help_list_every_key_the_help_box_lists() {
    let table: String = std::iter::once("| key in `spin` | does |\n|---|---|\n".to_string())
        .chain(
            rastty::animate::KEYS
                .iter()
                .map(|(k, what)| format!("| {k} | {what} |\n")),
        )
        .collect();
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    for page in ["README.md", "docs/usage.md"] {
        let text = std::fs::read_to_string(format!("{root}/{page}")).unwrap();
        assert!(
            text.contains(&table),
            "{page} lacks the keys table:\n{table}"
        );
    }
    let out = Command::new(env!("CARGO_BIN_EXE_rastty"))
        .args(["spin", "--help"])
        .output()
        .unwrap();
    let help = String::from_utf8(out.stdout).unwrap();
    assert!(help.contains(&rastty::animate::keys_text()), "{help}");
    assert!(
        help.contains("  ?                      show or hide these keys"),
        "{help}"
    );
}

/// A file manager's preview (`render FILE --cols W --rows H --preview`)
/// of a file that cannot be read gets one line within its width: the
/// file's name and what is wrong, cut with `…`.
#[test]
fn a_preview_that_cannot_be_read_gets_one_line_within_its_width() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    for (file, cols, want) in [
        (
            "/nonexistent/dir/model.obj",
            "40",
            "error: model.obj: No such file or direc…\n",
        ),
        ("README.md", "30", "error: README.md: rastty does…\n"),
        (
            "tests/data/short-face.obj",
            "200",
            "error: tests/data/short-face.obj:4:1: a face needs at least 3 vertices, found 2\n",
        ),
    ] {
        let out = Command::new(env!("CARGO_BIN_EXE_rastty"))
            .args(["render", file, "--cols", cols, "--rows", "10", "--preview"])
            .current_dir(root)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(1));
        assert!(out.stdout.is_empty());
        assert_eq!(String::from_utf8(out.stderr).unwrap(), want);
    }
}
