//! Pixels through the output seam, and each protocol's bytes decoded back
//! to them: the kitty graphics protocol (base64 of zlib of RGBA, chunked),
//! sixel (a small decoder here) and iTerm2's inline images (base64 of a
//! PNG) give the picture the pipeline rendered, pixel for pixel (sixel
//! within its palette).

use std::io::Read as _;

use base64::Engine as _;
use rastty::color::{ColorDepth, Ink, Rgb};
use rastty::color::{Metric, Quantizer, xterm256};
use rastty::graphics::{iterm, kitty, sixel};
use rastty::scene::{Scene, Shape};
use rastty::{Pixels, RenderOptions, Renderer};

fn scene() -> Scene {
    rastty::scene::default_scene()
}

fn opts(cols: u16, rows: u16, cell: [u16; 2]) -> RenderOptions {
    RenderOptions {
        cols,
        rows,
        cell_pixels: Some(cell),
        ..Default::default()
    }
}

fn pixels_of(scene: &Scene, opts: &RenderOptions) -> (Pixels, Renderer) {
    let mut r = Renderer::new();
    let mut p = Pixels::new();
    r.render_pixels(scene, opts, &mut p);
    (p, r)
}

#[test]
fn each_pixel_is_its_sample_encoded_and_uncovered_ones_are_transparent() {
    let o = opts(40, 12, [8, 16]);
    let (p, r) = pixels_of(&scene(), &o);
    assert_eq!((p.width(), p.height()), (320, 192));
    let fb = r.framebuffer();
    let mut covered = 0;
    for y in 0..p.height() {
        for x in 0..p.width() {
            let want = match fb.get(x, p.height() - 1 - y) {
                Some(c) => {
                    covered += 1;
                    let Rgb([r, g, b]) = c.to_srgb();
                    [r, g, b, 255]
                }
                None => [0; 4],
            };
            assert_eq!(p.get(x, y), want, "pixel {x},{y}");
        }
    }
    assert!(covered > 10_000, "{covered}");
}

#[test]
fn a_scene_background_makes_every_pixel_opaque() {
    let mut s = Scene::of_mesh(Shape::Cube.mesh(Rgb::WHITE));
    s.background = Some(Rgb([10, 20, 30]));
    let (p, _) = pixels_of(&s, &opts(10, 4, [4, 8]));
    assert!(p.opaque());
    assert_eq!(p.get(0, 0), [10, 20, 30, 255]);
}

#[test]
fn pixels_in_bands_are_the_pixels_of_one_thread() {
    let one = RenderOptions {
        threads: rastty::Threads::Exactly(1),
        ..opts(60, 30, [6, 12])
    };
    let five = RenderOptions {
        threads: rastty::Threads::Exactly(5),
        ..one
    };
    assert_eq!(pixels_of(&scene(), &one).0, pixels_of(&scene(), &five).0);
}

#[test]
fn cells_of_pixels_set_the_views_aspect() {
    let o = opts(40, 10, [10, 20]);
    assert_eq!(o.aspect(), 2.0);
    assert_eq!(o.cell_samples(), (10, 20));
    let bad = RenderOptions {
        cell_pixels: Some([0, 20]),
        ..o
    };
    assert!(
        bad.check()
            .unwrap_err()
            .to_string()
            .contains("cells of 0×20 pixels")
    );
}

/// The APC sequences of `bytes`: each one's keys and payload.
fn apcs(bytes: &[u8]) -> Vec<(String, Vec<u8>)> {
    let text = std::str::from_utf8(bytes).unwrap();
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(i) = rest.find("\x1b_G") {
        let body = &rest[i + 3..];
        let end = body.find("\x1b\\").unwrap();
        let (keys, data) = body[..end].split_once(';').unwrap_or((&body[..end], ""));
        out.push((keys.to_string(), data.as_bytes().to_vec()));
        rest = &body[end + 2..];
    }
    out
}

fn key(keys: &str, k: &str) -> Option<u32> {
    keys.split(',')
        .find_map(|kv| kv.strip_prefix(&format!("{k}=")))
        .map(|v| v.parse().unwrap())
}

/// The images a stream of kitty commands transmits or edits: each
/// command's keys (from its first chunk) and its pixels decompressed.
fn kitty_commands(bytes: &[u8]) -> Vec<(String, Vec<u8>)> {
    let mut out: Vec<(String, Vec<u8>)> = Vec::new();
    let mut data = Vec::new();
    let mut keys = String::new();
    for (k, d) in apcs(bytes) {
        assert!(d.len() <= 4096, "a chunk of {} bytes", d.len());
        if keys.is_empty() {
            keys = k.clone();
        }
        data.extend_from_slice(&d);
        if key(&k, "m") != Some(1) {
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
    }
    out
}

#[test]
fn a_kitty_still_is_the_pixels_in_chunks_of_zlib_and_base64() {
    let (p, _) = pixels_of(&scene(), &opts(40, 12, [8, 16]));
    let mut out = Vec::new();
    kitty::still(&p, 40, 12, &mut out);
    let cmds = kitty_commands(&out);
    assert_eq!(cmds.len(), 1);
    let (keys, raw) = &cmds[0];
    assert!(
        keys.starts_with("a=T,f=32,o=z,s=320,v=192,c=40,r=12"),
        "{keys}"
    );
    assert_eq!(raw, p.bytes());
    assert!(apcs(&out).len() > 1, "sent in more than one chunk");
}

#[test]
fn kitty_frames_edit_the_rectangle_that_changed_and_nothing_when_nothing_did() {
    let s = scene();
    let o = opts(40, 12, [8, 16]);
    let mut r = Renderer::new();
    let (mut a, mut b) = (Pixels::new(), Pixels::new());
    r.render_pixels(&s, &o, &mut a);
    let turned = RenderOptions {
        turn: rastty::glam::Vec3::new(0.0, 10.0, 0.0),
        ..o
    };
    r.render_pixels(&s, &turned, &mut b);
    let mut anim = kitty::Animation::new(7);
    let mut out = Vec::new();
    anim.frame(&a, 40, 12, &mut out).unwrap();
    let first = kitty_commands(&out);
    assert!(
        first[0].0.starts_with("a=T,i=7,p=1,f=32,o=z,s=320,v=192"),
        "{}",
        first[0].0
    );
    let mut shown = first[0].1.clone();
    out.clear();
    let rect = anim.frame(&b, 40, 12, &mut out).unwrap();
    let cmds = kitty_commands(&out);
    assert_eq!(cmds.len(), 2, "the edit, then the frame shown");
    // Every chunk of the edit says what it edits (kitty 0.26 takes a bare
    // continuation for a new image's).
    let edits: Vec<_> = apcs(&out)
        .into_iter()
        .filter(|(k, _)| !k.starts_with("a=a"))
        .collect();
    assert!(edits.len() > 1, "the edit in more than one chunk");
    assert!(
        edits.iter().all(|(k, _)| k.starts_with("a=f,r=1,i=7")),
        "{edits:?}"
    );
    let (keys, raw) = &cmds[0];
    assert!(keys.starts_with("a=f,r=1,i=7,f=32,o=z"), "{keys}");
    assert!(
        keys.contains(",X=1"),
        "pixels replaced, not blended: {keys}"
    );
    assert!(rect.width < 320 || rect.height < 192, "{rect:?}");
    assert_eq!(
        (
            key(keys, "x"),
            key(keys, "y"),
            key(keys, "s"),
            key(keys, "v")
        ),
        (
            Some(rect.x),
            Some(rect.y),
            Some(rect.width),
            Some(rect.height)
        )
    );
    // The edit applied to what the first frame showed is the second.
    for row in 0..rect.height as usize {
        let w = rect.width as usize * 4;
        let at = ((rect.y as usize + row) * 320 + rect.x as usize) * 4;
        shown[at..at + w].copy_from_slice(&raw[row * w..(row + 1) * w]);
    }
    assert_eq!(shown, b.bytes());
    assert!(cmds[1].0.starts_with("a=a,c=1,i=7"), "{}", cmds[1].0);
    out.clear();
    assert_eq!(anim.frame(&b, 40, 12, &mut out), None);
    assert!(out.is_empty());
    // A new size is a new image, the old one deleted first.
    let (c, _) = pixels_of(&s, &opts(20, 6, [8, 16]));
    anim.frame(&c, 20, 6, &mut out).unwrap();
    let cmds = kitty_commands(&out);
    assert_eq!(cmds[0].0, "a=d,d=I,i=7,q=2");
    assert!(cmds[1].0.starts_with("a=T,i=7,p=1,f=32,o=z,s=160,v=96"));
    out.clear();
    anim.delete(&mut out);
    assert_eq!(out, b"\x1b_Ga=d,d=I,i=7,q=2\x1b\\");
}

/// A sixel image decoded: its size and each pixel's colour (`None`: not
/// painted), with the registers it defined.
struct SixelImage {
    width: usize,
    pixels: Vec<Option<Rgb>>,
    registers: Vec<u16>,
}

fn decode_sixel(bytes: &[u8]) -> SixelImage {
    let text = std::str::from_utf8(bytes).unwrap();
    let body = text.strip_prefix("\x1bP0;1;0q").expect("DCS 0;1;0 q");
    let body = body.strip_suffix("\x1b\\").expect("ST");
    let body = body.strip_prefix('"').expect("raster attributes");
    let nums = |s: &str| -> Vec<u32> { s.split(';').map(|n| n.parse().unwrap()).collect() };
    let attr_end = body.find(['#', '-']).unwrap_or(body.len());
    let attrs = nums(&body[..attr_end]);
    assert_eq!(&attrs[..2], &[1, 1], "a 1:1 pixel aspect");
    let (w, h) = (attrs[2] as usize, attrs[3] as usize);
    let mut pixels = vec![None; w * h];
    let mut colours = std::collections::HashMap::new();
    let mut registers = Vec::new();
    let (mut x, mut band, mut current) = (0usize, 0usize, None::<u16>);
    let b = &body.as_bytes()[attr_end..];
    let mut i = 0;
    let number = |i: &mut usize| -> u32 {
        let start = *i;
        while *i < b.len() && b[*i].is_ascii_digit() {
            *i += 1;
        }
        body[attr_end..][start..*i].parse().unwrap()
    };
    while i < b.len() {
        match b[i] {
            b'#' => {
                i += 1;
                let reg = number(&mut i) as u16;
                if i < b.len() && b[i] == b';' {
                    i += 1;
                    let mut v = [0u32; 4];
                    for (k, slot) in v.iter_mut().enumerate() {
                        *slot = number(&mut i);
                        if k < 3 {
                            assert_eq!(b[i], b';');
                            i += 1;
                        }
                    }
                    assert_eq!(v[0], 2, "RGB registers");
                    let c = |p: u32| ((p * 255 + 50) / 100) as u8;
                    assert!(
                        colours
                            .insert(reg, Rgb([c(v[1]), c(v[2]), c(v[3])]))
                            .is_none(),
                        "register {reg} defined twice"
                    );
                    registers.push(reg);
                }
                current = Some(reg);
            }
            b'$' => {
                x = 0;
                i += 1;
            }
            b'-' => {
                x = 0;
                band += 1;
                i += 1;
            }
            b'!' => {
                i += 1;
                let n = number(&mut i) as usize;
                let s = b[i] - b'?';
                for _ in 0..n {
                    paint(&mut pixels, w, h, x, band, s, colours[&current.unwrap()]);
                    x += 1;
                }
                i += 1;
            }
            c @ b'?'..=b'~' => {
                paint(
                    &mut pixels,
                    w,
                    h,
                    x,
                    band,
                    c - b'?',
                    colours[&current.unwrap()],
                );
                x += 1;
                i += 1;
            }
            c => panic!("unexpected byte {c}"),
        }
    }
    SixelImage {
        width: w,
        pixels,
        registers,
    }
}

fn paint(pixels: &mut [Option<Rgb>], w: usize, h: usize, x: usize, band: usize, bits: u8, c: Rgb) {
    for r in 0..6 {
        let y = band * 6 + r;
        if bits & (1 << r) != 0 && y < h && x < w {
            pixels[y * w + x] = Some(c);
        }
    }
}

/// The colour rastty's quantizer gives pixel `(x, y)` at `depth` once
/// resolved to sixel's levels, the colour a sixel register is set to.
fn quantized(q: &mut Quantizer, p: [u8; 4], x: u32, y: u32) -> Option<Rgb> {
    (p[3] == 255).then(|| {
        match q.ink_at(
            Some(sixel::resolved(Rgb([p[0], p[1], p[2]]))),
            x as u16,
            y as u16,
        ) {
            Ink::Indexed(i) => xterm256(i),
            other => panic!("{other:?}"),
        }
    })
}

#[test]
fn a_sixel_image_is_the_pixels_in_the_palette_and_leaves_the_uncovered_unpainted() {
    let (p, _) = pixels_of(&scene(), &opts(30, 10, [6, 12]));
    for (registers, depth) in [(256, ColorDepth::Ansi256), (16, ColorDepth::Ansi16)] {
        let mut out = Vec::new();
        sixel::Encoder::new(registers).encode(&p, &mut out);
        let img = decode_sixel(&out);
        assert_eq!((img.width, img.pixels.len()), (180, 180 * 120));
        assert!(
            img.registers.iter().all(|&r| r < registers),
            "{:?}",
            img.registers
        );
        let mut q = Quantizer::new(depth, Metric::Oklch);
        for y in 0..p.height() {
            for x in 0..p.width() {
                let want = quantized(&mut q, p.get(x, y), x, y);
                // Sixel registers are set in percent: within a step.
                let got = img.pixels[(y * p.width() + x) as usize];
                let near = match (want, got) {
                    (Some(Rgb(a)), Some(Rgb(b))) => {
                        a.iter().zip(b).all(|(a, b)| a.abs_diff(b) <= 2)
                    }
                    (a, b) => a == b,
                };
                assert!(
                    near,
                    "pixel {x},{y}: {want:?} against {got:?} ({registers} registers)"
                );
            }
        }
    }
}

#[test]
fn an_iterm_image_is_a_png_of_the_pixels() {
    let (p, _) = pixels_of(&scene(), &opts(30, 10, [6, 12]));
    let mut out = Vec::new();
    iterm::still(&p, 30, 10, &mut out).unwrap();
    let text = std::str::from_utf8(&out).unwrap();
    let body = text.strip_prefix("\x1b]1337;File=inline=1;").unwrap();
    let body = body.strip_suffix('\x07').unwrap();
    let (keys, data) = body.split_once(':').unwrap();
    assert!(
        keys.contains("width=30;height=10;preserveAspectRatio=0"),
        "{keys}"
    );
    let png = base64::engine::general_purpose::STANDARD
        .decode(data)
        .unwrap();
    assert!(keys.contains(&format!("size={}", png.len())), "{keys}");
    let mut reader = png::Decoder::new(std::io::Cursor::new(png))
        .read_info()
        .unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!((info.width, info.height), (180, 120));
    assert_eq!(&buf[..info.buffer_size()], p.bytes());
}

#[test]
fn sixel_resolves_a_channel_within_two_and_keeps_every_palette_colour() {
    for i in 0..=255u8 {
        assert_eq!(sixel::resolved(xterm256(i)), xterm256(i), "entry {i}");
    }
    let mut levels = std::collections::BTreeSet::new();
    for v in 0..=255u8 {
        let r = sixel::resolved(Rgb([v, v, v])).0[0];
        assert!(r.abs_diff(v) <= 2, "{v} resolved to {r}");
        levels.insert(r);
    }
    // 64 groups of four, and the palette's own levels besides.
    assert!(levels.len() <= 64 + 30, "{}", levels.len());
}
