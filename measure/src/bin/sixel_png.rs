//! A PNG's pixels as sixel on stdout, as `chafa -f sixels` makes one of
//! the same file: scripts/figures.sh counts both, whole process (the PNG
//! decoded, then encoded), side by side.
//!
//! `sixel_png FILE.png [REGISTERS]` (256 by default).

use std::io::Write;

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args.next().expect("sixel_png FILE.png [REGISTERS]");
    let registers: u16 = args
        .next()
        .map_or(256, |r| r.parse().expect("a number of registers"));
    let file = std::fs::File::open(&path).expect("the PNG");
    let mut reader = png::Decoder::new(std::io::BufReader::new(file))
        .read_info()
        .expect("a PNG");
    let mut buf = vec![0; reader.output_buffer_size().expect("a size")];
    let info = reader.next_frame(&mut buf).expect("its pixels");
    assert_eq!(
        info.color_type,
        png::ColorType::Rgba,
        "an RGBA PNG (rastty render --graphics … --output)"
    );
    let mut pixels = rastty::Pixels::filled(info.width, info.height, [0; 4]);
    pixels.copy_from_bytes(&buf[..info.buffer_size()]);
    let mut out = Vec::new();
    rastty::graphics::sixel::Encoder::new(registers).encode(&pixels, &mut out);
    std::io::stdout().write_all(&out).expect("stdout");
}
