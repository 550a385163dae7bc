//! Memory a scene file costs, measured on the binary as a user runs it.
//! Alone in its test binary: a child's peak memory as the kernel reports
//! it includes the parent's at the moment it was started, so the parent
//! here stays small (the file is written a line at a time).

#[path = "support/run.rs"]
mod support;

use std::io::Write;
use std::path::{Path, PathBuf};

#[test]
fn a_scene_of_200k_loose_triangles_takes_memory_within_twice_its_size() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("loose");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("loose.toml");
    let mut out = std::io::BufWriter::new(std::fs::File::create(&path).unwrap());
    writeln!(out, "[camera]\neye = [0.0, 0.0, 4.0]").unwrap();
    let mut x = 12345u32;
    let mut r = || {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        (x % 20000) as f32 / 10000.0 - 1.0
    };
    for _ in 0..200_000 {
        let v: Vec<String> = (0..3)
            .map(|_| format!("[{:.4}, {:.4}, {:.4}]", r(), r(), r()))
            .collect();
        writeln!(
            out,
            "[[triangle]]\nvertices = [{}]\ncolor = \"#336699\"",
            v.join(", ")
        )
        .unwrap();
    }
    drop(out);
    let size = std::fs::metadata(&path).unwrap().len();
    let r = render(&path);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    assert!(r.peak < 2 * size, "{} bytes for a file of {size}", r.peak);
}

/// A file at `name` in this binary's directory, written in pieces by
/// `fill` (never held whole by the test).
fn write(name: &str, fill: impl FnOnce(&mut dyn Write)) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("memory");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    let mut out = std::io::BufWriter::new(std::fs::File::create(&path).unwrap());
    fill(&mut out);
    out.flush().unwrap();
    path
}

/// `rastty render PATH` in a small frame, its peak less that of drawing
/// a cube (the program itself, and what the kernel counts of this test
/// process at the spawn: see `support`).
fn render(path: &Path) -> support::Run {
    let base = base_peak();
    render_above(base, path, &[])
}

/// The peak of drawing a cube.
fn base_peak() -> u64 {
    support::run(&["render", "cube", "--cols", "20", "--rows", "6"]).peak
}

/// [`render`] with `more` arguments, its peak less `base`.
fn render_above(base: u64, path: &Path, more: &[&str]) -> support::Run {
    let args = [
        &[
            "render",
            path.to_str().unwrap(),
            "--cols",
            "20",
            "--rows",
            "6",
        ][..],
        more,
    ]
    .concat();
    let mut r = support::run(&args);
    r.peak = r.peak.saturating_sub(base);
    r
}

#[test]
fn one_20_mb_ply_line_is_refused_as_it_is_read() {
    let path = write("long.ply", |out| {
        out.write_all(b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n").unwrap();
        for _ in 0..1000 {
            out.write_all(&b"0 ".repeat(10_000)).unwrap();
        }
    });
    let r = render(&path);
    assert_eq!(
        r.stderr,
        format!(
            "error: {}: line 10: longer than 4194304 bytes\n",
            path.display()
        )
    );
    // At most the 4 MiB line and its tokens, not the 20 MB.
    assert!(r.peak < 48 << 20, "{} bytes", r.peak);
}

#[test]
fn a_scene_of_20_mb_of_nul_bytes_is_refused_at_its_first_byte() {
    let path = write("nul.toml", |out| {
        for _ in 0..20 {
            out.write_all(&[0u8; 1 << 20]).unwrap();
        }
    });
    let r = render(&path);
    assert_eq!(
        r.stderr,
        format!(
            "error: {}:1:1: a control character (\\x00), which TOML does not allow: is this a scene file?\n",
            path.display()
        )
    );
    // The file, read once.
    assert!(r.peak < 24 << 20, "{} bytes", r.peak);
}

#[test]
fn a_20_mb_toml_key_gives_a_short_error_in_a_few_times_the_file() {
    let size = 20u64 << 20;
    let path = write("key.toml", |out| {
        for _ in 0..20 {
            out.write_all(&[b'k'; 1 << 20]).unwrap();
        }
        out.write_all(b" = 1\n").unwrap();
    });
    let r = render(&path);
    assert_eq!(r.stderr.lines().count(), 1);
    assert!(r.stderr.chars().count() < 400, "{}", r.stderr);
    assert!(r.stderr.contains(" characters cut] … "), "{}", r.stderr);
    // The text, the parser's key and its message: three times the file.
    assert!(r.peak < 3 * size + (4 << 20), "{} bytes", r.peak);
}

#[test]
fn a_ply_of_a_million_vertices_takes_a_few_times_its_size() {
    let n = 1_000_000;
    let path = write("many.ply", |out| {
        write!(out, "ply\nformat ascii 1.0\nelement vertex {n}\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n").unwrap();
        for i in 0..n {
            writeln!(out, "{}.125 {}.25 0.5", i % 1000, i / 1000).unwrap();
        }
        out.write_all(b"3 0 1 2\n").unwrap();
    });
    let size = std::fs::metadata(&path).unwrap().len();
    let r = render(&path);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    // Vertices as read (28 bytes, and the vector's doubling), positions
    // and normals (24), then the renderer's per-vertex buffers (about 80
    // bytes a vertex): seven times this dense 19 MB file.
    assert!(r.peak < 8 * size, "{} bytes for a file of {size}", r.peak);
}

#[test]
fn a_file_that_grows_while_it_is_read_is_read_to_the_size_it_had() {
    // Vertex lines of 32 bytes, 128 to a 4 KiB page: the file is written a
    // page at a time, so its size is always a whole number of lines.
    let line = b"v 0.1234567 0.1234567 0.1234567\n";
    assert_eq!(line.len(), 32);
    let page: Vec<u8> = line.repeat(128);
    let path = write("grow.obj", |out| {
        let mut head = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".to_vec();
        head.resize(4096, b'#');
        head[4095] = b'\n';
        out.write_all(&head).unwrap();
        for _ in 0..1024 {
            out.write_all(&page).unwrap(); // 4 MiB
        }
    });
    let base = base_peak();
    // Another thread appends, a page at a time, up to 96 MiB more, until
    // the run is over.
    let done = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let writer = {
        let (done, path) = (done.clone(), path.clone());
        std::thread::spawn(move || {
            let mut f = std::fs::OpenOptions::new()
                .append(true)
                .open(&path)
                .unwrap();
            for _ in 0..96 * 256 {
                if done.load(std::sync::atomic::Ordering::Relaxed) {
                    break;
                }
                f.write_all(&page).unwrap();
            }
        })
    };
    let r = render_above(base, &path, &["--max-file-size", "24M"]);
    done.store(true, std::sync::atomic::Ordering::Relaxed);
    writer.join().unwrap();
    // Read to the size it had when opened, and said; or refused, if it
    // was past the limit by then. Never read on as it grows.
    let name = path.display().to_string();
    match r.code {
        Some(0) => assert!(
            r.stderr
                .starts_with(&format!("note: {name}: grew while it was read: its first "))
                && r.stderr
                    .ends_with(" bytes, its size when opened, were read\n"),
            "{}",
            r.stderr
        ),
        _ => assert!(
            r.stderr
                .contains("is more than the limit of 24.0 MiB (--max-file-size raises it)"),
            "{}",
            r.stderr
        ),
    }
    assert!(r.peak < 40 << 20, "{} bytes", r.peak);
    std::fs::remove_file(&path).unwrap();
}

#[test]
fn a_polygon_crossing_itself_everywhere_takes_memory_by_its_corners() {
    // 3,000 corners at random: nearly every edge crosses hundreds of
    // others (about a million crossings in all). Cut by the even-odd rule
    // it would take some 330 MB; past n + 64 crossings it is cut as a fan.
    let mut x = 7u32;
    let mut r = || {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        f64::from(x % 1_000_000) / 1e6
    };
    let path = write("crossed.obj", |out| {
        for _ in 0..3000 {
            writeln!(out, "v {:.6} {:.6} 0", r(), r()).unwrap();
        }
        out.write_all(b"f").unwrap();
        for i in 1..=3000 {
            write!(out, " {i}").unwrap();
        }
        out.write_all(b"\n").unwrap();
    });
    let r = render(&path);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    assert_eq!(
        r.stderr,
        format!(
            "note: {}: 1 polygon(s) crossing themselves at more points than they have corners (and 64) were cut as fans from their first corner\n",
            path.display()
        )
    );
    assert!(r.peak < 16 << 20, "{} bytes", r.peak);
}
