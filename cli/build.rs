//! Links the program's hot functions side by side: `hot-functions.ld`, a
//! linker script written by `scripts/hot-functions.sh`, names the sections
//! of the functions the common commands run, in the order they are first
//! needed, and the linker lays them out at the start of `.text`, then the
//! rest as it would. The kernel maps a program's code into memory by
//! blocks of up to 16 pages around each page it runs, so functions
//! scattered through 4 MB of code keep much of it resident: side by side,
//! one frame of Tux peaks at 6.6 MiB, not 8.4, and `rastty --version` at
//! 2.9, not 3.8 (docs/figures.md, "Memory, loading and start-up", against
//! 9d8112f built beside). Nothing else changes: the same machine code, the
//! same instructions.
//!
//! The script is given to LLD alone, Rust's linker for x86-64 Linux from
//! Rust 1.90, with which it was tried. Where the linker may be another (an
//! older compiler, another target, a linker chosen in `RUSTFLAGS`) it is
//! not passed, and the program links as it would without it. A section the
//! script names that the binary lacks (another feature set, another
//! compiler, whose symbols differ) matches nothing, which changes nothing.

use std::path::Path;
use std::process::Command;

fn main() {
    println!("cargo:rerun-if-changed=hot-functions.ld");
    println!("cargo:rerun-if-changed=build.rs");
    if !links_with_lld() {
        return;
    }
    let dir = std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR");
    let file = Path::new(&dir).join("hot-functions.ld");
    if !file.is_file() {
        return;
    }
    println!("cargo:rustc-link-arg-bins=-Wl,-T,{}", file.display());
}

/// Whether the binary is linked by LLD: x86-64 Linux with glibc, Rust 1.90
/// or later, and no linker chosen in the flags.
fn links_with_lld() -> bool {
    let var = |name: &str| std::env::var(name).unwrap_or_default();
    if var("TARGET") != "x86_64-unknown-linux-gnu" {
        return false;
    }
    let flags = var("CARGO_ENCODED_RUSTFLAGS");
    if ["linker", "fuse-ld", "link-self-contained"]
        .iter()
        .any(|f| flags.contains(f))
    {
        return false;
    }
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let Ok(out) = Command::new(rustc).arg("-V").output() else {
        return false;
    };
    // "rustc 1.95.0 (59807616e 2026-04-14)"
    let version = String::from_utf8_lossy(&out.stdout);
    let minor = version
        .split_whitespace()
        .nth(1)
        .and_then(|v| v.split('.').nth(1))
        .and_then(|m| m.parse::<u32>().ok());
    matches!(minor, Some(m) if m >= 90)
}
