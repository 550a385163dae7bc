//! Writes a torus of about N triangles as an OBJ file to stdout: quads on
//! a grid of positions with six decimals, as exporters write them; for
//! measuring how loading grows with size (`scripts/figures.sh`,
//! `benches/load.rs`).
//!
//!   cargo run --release -p rastty-measure --bin torus_obj -- 1000000 > torus-1m.obj

use std::io::Write;

/// Writes a torus of about `triangles` triangles (quads, two each).
pub fn write_torus(triangles: usize, out: &mut impl Write) -> std::io::Result<()> {
    // u around the ring, v around the tube, u = 2v: 2uv = 4v² triangles.
    let v = ((triangles as f64 / 4.0).sqrt().round() as usize).max(3);
    let u = 2 * v;
    let (big, small) = (1.0f64, 0.35f64);
    for i in 0..u {
        let a = std::f64::consts::TAU * i as f64 / u as f64;
        for j in 0..v {
            let b = std::f64::consts::TAU * j as f64 / v as f64;
            let r = big + small * b.cos();
            writeln!(
                out,
                "v {:.6} {:.6} {:.6}",
                r * a.cos(),
                small * b.sin(),
                -r * a.sin()
            )?;
        }
    }
    let at = |i: usize, j: usize| (i % u) * v + (j % v) + 1;
    for i in 0..u {
        for j in 0..v {
            writeln!(
                out,
                "f {} {} {} {}",
                at(i, j),
                at(i + 1, j),
                at(i + 1, j + 1),
                at(i, j + 1)
            )?;
        }
    }
    Ok(())
}

#[allow(dead_code)]
fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(1_000_000);
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    write_torus(n, &mut out).expect("stdout");
}
