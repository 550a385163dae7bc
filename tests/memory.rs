//! Memory a scene file costs, measured on the binary as a user runs it.
//! Alone in its test binary: a child's peak memory as the kernel reports
//! it includes the parent's at the moment it was started, so the parent
//! here stays small (the file is written a line at a time).

use std::io::Write;
use std::path::Path;
use std::process::Command;

/// The peak memory of the children this process has waited for, in bytes.
fn children_peak_rss() -> u64 {
    // SAFETY: a zeroed rusage is a valid value, which getrusage fills.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: the pointer is to a live rusage.
    assert_eq!(
        unsafe { libc::getrusage(libc::RUSAGE_CHILDREN, &mut usage) },
        0
    );
    usage.ru_maxrss as u64 * 1024
}

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
    let run = Command::new(env!("CARGO_BIN_EXE_rastty"))
        .args([
            "render",
            path.to_str().unwrap(),
            "--cols",
            "20",
            "--rows",
            "5",
        ])
        .output()
        .unwrap();
    assert!(run.status.success());
    let peak = children_peak_rss();
    assert!(peak < 2 * size, "{peak} bytes for a file of {size}");
}
