//! Pixels through the program: `render --graphics` writes one frame in the
//! protocol (its kitty pixels are the pixels `--output x.png` writes),
//! `spin --graphics` sends frames in synchronized output and takes its
//! image away on every way out, and `auto` draws cells where stdout is not
//! a terminal, whatever the environment claims.

use std::io::Read as _;
use std::process::Command;
use std::time::Duration;

use base64::Engine as _;
use expectrl::Expect;
use expectrl::session::OsSession as Session;

const BIN: &str = env!("CARGO_BIN_EXE_rastty");
const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
const FOX: &str = "tests/models/fox.obj";

fn rastty(args: &[&str]) -> Vec<u8> {
    let out = Command::new(BIN)
        .args(args)
        .current_dir(ROOT)
        .env("TERM", "xterm-kitty")
        .env("KITTY_WINDOW_ID", "1")
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
}

/// Each APC graphics command's keys (of its first chunk) and its payload,
/// base64 and zlib undone.
fn kitty_commands(bytes: &[u8]) -> Vec<(String, Vec<u8>)> {
    let text = String::from_utf8_lossy(bytes);
    let (mut out, mut keys, mut data) = (Vec::new(), String::new(), String::new());
    let mut rest = &text[..];
    while let Some(i) = rest.find("\x1b_G") {
        let body = &rest[i + 3..];
        let end = body.find("\x1b\\").unwrap();
        let (k, d) = body[..end].split_once(';').unwrap_or((&body[..end], ""));
        if keys.is_empty() {
            keys = k.to_string();
        }
        data.push_str(d);
        if !k.split(',').any(|kv| kv == "m=1") {
            let raw = if data.is_empty() {
                Vec::new()
            } else {
                let z = base64::engine::general_purpose::STANDARD
                    .decode(&data)
                    .unwrap();
                let mut raw = Vec::new();
                flate2::read::ZlibDecoder::new(&z[..])
                    .read_to_end(&mut raw)
                    .unwrap();
                raw
            };
            out.push((std::mem::take(&mut keys), raw));
            data.clear();
        }
        rest = &body[end + 2..];
    }
    out
}

#[test]
fn render_in_kitty_pixels_is_the_picture_its_png_holds() {
    let args = [
        "render",
        FOX,
        "--cols",
        "40",
        "--rows",
        "12",
        "--cell-size",
        "8x16",
    ];
    let bytes = rastty(&[&args[..], &["--graphics", "kitty"]].concat());
    assert!(bytes.ends_with(b"\x1b\\\n"), "the image, then a new line");
    let cmds = kitty_commands(&bytes);
    assert_eq!(cmds.len(), 1);
    assert!(
        cmds[0].0.starts_with("a=T,f=32,o=z,s=320,v=192,c=40,r=12"),
        "{}",
        cmds[0].0
    );
    let dir = std::env::temp_dir().join(format!("rastty-pixels-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let png = dir.join("fox.png");
    rastty(
        &[
            &args[..],
            &["--graphics", "kitty", "--output", png.to_str().unwrap()],
        ]
        .concat(),
    );
    let mut reader = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&png).unwrap()))
        .read_info()
        .unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!((info.width, info.height), (320, 192));
    assert_eq!(&buf[..info.buffer_size()], &cmds[0].1[..]);
    // Some pixels are the fox, the rest transparent.
    let alpha: Vec<u8> = cmds[0].1.chunks(4).map(|p| p[3]).collect();
    assert!(alpha.contains(&255) && alpha.contains(&0));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn auto_draws_cells_where_stdout_is_not_a_terminal() {
    let bytes = rastty(&["render", FOX, "--cols", "40", "--rows", "12"]);
    let text = String::from_utf8_lossy(&bytes);
    assert!(!text.contains("\x1b_G") && text.contains('▀'), "{text}");
}

#[test]
fn spin_in_kitty_pixels_edits_one_image_and_deletes_it_at_the_end() {
    let bytes = rastty(&[
        "spin",
        FOX,
        "--cols",
        "40",
        "--rows",
        "13",
        "--cell-size",
        "8x16",
        "--graphics",
        "kitty",
        "--frames",
        "4",
    ]);
    let cmds = kitty_commands(&bytes);
    let keys: Vec<&str> = cmds.iter().map(|(k, _)| k.as_str()).collect();
    // Placed once, below the text, over every row but the status line's;
    // then each frame an edit and the frame shown; then deleted.
    assert!(
        keys[0].starts_with("a=T,i=") && keys[0].contains(",s=320,v=192,c=40,r=12,C=1,q=2,z=-1"),
        "{keys:?}"
    );
    let id = keys[0]
        .split(',')
        .find_map(|k| k.strip_prefix("i="))
        .unwrap();
    assert_eq!(keys.len(), 1 + 3 * 2 + 1, "{keys:?}");
    for pair in keys[1..7].chunks(2) {
        assert!(pair[0].starts_with(&format!("a=f,r=1,i={id},")), "{pair:?}");
        assert_eq!(pair[1], format!("a=a,c=1,i={id},q=2"));
    }
    assert_eq!(*keys.last().unwrap(), format!("a=d,d=I,i={id},q=2"));
    // Each frame in synchronized output.
    let text = String::from_utf8_lossy(&bytes);
    assert_eq!(text.matches("\x1b[?2026h").count(), 4);
    assert_eq!(text.matches("\x1b[?2026l").count(), 4);
}

#[test]
fn q_in_a_pixel_spin_deletes_the_image_and_restores_the_terminal() {
    let mut cmd = Command::new(BIN);
    cmd.args([
        "spin",
        FOX,
        "--graphics",
        "kitty",
        "--cell-size",
        "8x16",
        "--no-probe",
        "--hud",
    ])
    .current_dir(ROOT)
    .env("TERM", "xterm-256color");
    let mut s = Session::spawn(cmd).expect("a pty");
    s.get_process_mut().set_window_size(60, 20).unwrap();
    s.set_expect_timeout(Some(Duration::from_secs(20)));
    let found = s.expect("\x1b[?2026l").expect("a first frame");
    let mut seen: Vec<u8> = found
        .before()
        .iter()
        .chain(found.get(0).unwrap())
        .copied()
        .collect();
    s.send("q").unwrap();
    let mut buf = [0u8; 4096];
    loop {
        match s.read(&mut buf) {
            Ok(0) | Err(_) => break,
            Ok(n) => seen.extend_from_slice(&buf[..n]),
        }
    }
    let text = String::from_utf8_lossy(&seen);
    let placed = text.find("\x1b_Ga=T,i=").expect("an image placed");
    let deleted = text.rfind("\x1b_Ga=d,d=I,i=").expect("the image deleted");
    let left = text
        .rfind("\x1b[?1049l")
        .expect("the alternate screen left");
    assert!(
        placed < deleted && deleted < left,
        "placed, deleted, then the screen restored"
    );
    let mut vt = crate::common::terminal(20, 60);
    vt.process(&seen);
    assert!(!vt.screen().alternate_screen() && !vt.screen().hide_cursor());
}
