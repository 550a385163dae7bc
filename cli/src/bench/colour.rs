//! The colour knobs: two-colour cells, palette matching and dithering
//! (their errors, and the encoder's bytes and time).

use super::*;

/// Every workload rendered in octant mode and blitted with `split` (the
/// blitter itself): for every cell whose samples hold more than two
/// colours, the RMS distance (0–255) of each sample's colour to the colour
/// the cell shows at that sample (the glyph's foreground where its pattern
/// covers the sample, else its background); the mean over those cells.
/// Undrawn samples count as the scene's background, or black.
pub(super) fn split_error(workloads: &[Workload], split: Split) -> f64 {
    let opts = RenderOptions {
        cols: 80,
        rows: 24,
        glyphs: GlyphMode::Octant,
        split,
        ..base()
    };
    let (mut sum, mut n) = (0.0, 0usize);
    for w in workloads {
        let mut r = Renderer::new();
        r.render(&w.scene, &opts);
        let (fb, frame) = (r.framebuffer(), r.frame());
        let bg = w.scene.background.unwrap_or(Rgb::BLACK);
        let height = fb.grid().height;
        // Measured on the encoded colours, as the cell's are.
        for cy in 0..opts.rows {
            for cx in 0..opts.cols {
                let colors: [Rgb; 8] = std::array::from_fn(|i| {
                    let (x, y) = (
                        cx as u32 * 2 + i as u32 % 2,
                        height - 1 - (cy as u32 * 4 + i as u32 / 2),
                    );
                    fb.get(x, y).map_or(bg, |c| c.to_srgb())
                });
                if colors.iter().map(|c| c.0).collect::<BTreeSet<_>>().len() <= 2 {
                    continue;
                }
                let cell = frame.get(cx, cy);
                let Some(mask) = GlyphMode::Octant.pattern(cell.ch) else {
                    continue;
                };
                let sq: f32 = (0..8)
                    .map(|i| {
                        let shown = if mask >> i & 1 == 1 { cell.fg } else { cell.bg };
                        let [r, g, b] = shown.unwrap_or(bg).to_f32();
                        let c = colors[i].to_f32();
                        (c[0] - r).powi(2) + (c[1] - g).powi(2) + (c[2] - b).powi(2)
                    })
                    .sum();
                sum += (sq / 8.0).sqrt() as f64;
                n += 1;
            }
        }
    }
    sum / n.max(1) as f64
}

/// The median time to encode each workload's frame in `palette` (the
/// quantizer's work, where the palette costs).
pub(super) fn encode_times(workloads: &[Workload], palette: Palette, reps: usize) -> Vec<Duration> {
    workloads
        .iter()
        .map(|w| {
            let frame = rastty::render(&w.scene, &base());
            median((0..reps).map(|_| {
                let mut e = Encoder::new(palette.depth)
                    .with_metric(palette.metric)
                    .with_dither(palette.dither);
                let t = Instant::now();
                e.prepare(&frame);
                t.elapsed()
            }))
        })
        .collect()
}

/// How well a metric matches colours to a palette.
pub struct MatchingError {
    /// Mean OKLab distance to the colour sent, over random colours.
    pub mean: f64,
    /// Of near-greys (OKLab chroma below `GREY_CHROMA`),
    /// the share sent to a chromatic entry, in %.
    pub greys_coloured: f64,
    /// Of clearly chromatic colours (chroma 0.08 or more), the share sent
    /// to an entry whose hue is more than 45° away (or to a grey), in %.
    pub hues_moved: f64,
}

/// Seeded random colours (4,096 of any kind, 4,096 near-greys) mapped to
/// `depth` by `metric`.
pub fn matching_error(depth: ColorDepth, metric: Metric) -> MatchingError {
    use color::{GREY_CHROMA, chroma};
    let lab = |c: Rgb| {
        let [r, g, b] = c.0;
        let l = oklab::srgb_to_oklab(oklab::Rgb { r, g, b });
        [l.l, l.a, l.b]
    };
    let mut rng = Rng(0xD1B5_4A32_D192_ED03);
    let (mut sum, mut n, mut chromatic, mut moved) = (0.0f64, 0usize, 0usize, 0usize);
    for _ in 0..4096 {
        let c = Rgb([0, 0, 0].map(|_: u8| (rng.next() * 256.0) as u8));
        let sent = color::xterm256(color::nearest(depth, metric, c));
        sum += color::oklab_distance(c, sent) as f64;
        n += 1;
        if chroma(c) >= 0.08 {
            chromatic += 1;
            let (p, q) = (lab(c), lab(sent));
            let turn = (p[2].atan2(p[1]) - q[2].atan2(q[1])).abs();
            let turn = turn.min(std::f32::consts::TAU - turn);
            if chroma(sent) < GREY_CHROMA || turn > std::f32::consts::FRAC_PI_4 {
                moved += 1;
            }
        }
    }
    let (mut greys, mut coloured) = (0usize, 0usize);
    while greys < 4096 {
        let v = rng.next() * 256.0;
        let jitter = |_: u8| (v + (rng.next() - 0.5) * 12.0).clamp(0.0, 255.0) as u8;
        let c = Rgb([0, 0, 0].map(jitter));
        if chroma(c) >= GREY_CHROMA {
            continue;
        }
        greys += 1;
        let sent = color::xterm256(color::nearest(depth, metric, c));
        coloured += (chroma(sent) >= GREY_CHROMA) as usize;
    }
    MatchingError {
        mean: sum / n as f64,
        greys_coloured: 100.0 * coloured as f64 / greys as f64,
        hues_moved: 100.0 * moved as f64 / chromatic.max(1) as f64,
    }
}

/// What dithering costs and gains, over the workloads.
pub struct DitherCost {
    /// Mean OKLab distance between the truecolor frame and the frame as
    /// sent, each averaged (in linear light) over areas of 2×2 cells, as
    /// the eye averages a pattern seen from a little way off.
    pub error: f64,
    /// Mean bytes of a first frame and of the next one (turned 3°).
    pub full_bytes: f64,
    /// Mean bytes of the next frame.
    pub next_bytes: f64,
}

/// [`DitherCost`] of `palette` over the workloads, in half blocks at
/// 200×60 cells.
pub fn dither_cost(workloads: &[Workload], palette: Palette) -> DitherCost {
    let opts = base();
    let (mut err, mut blocks, mut full, mut next) = (0.0f64, 0usize, 0usize, 0usize);
    for w in workloads {
        let frame = rastty::render(&w.scene, &opts);
        let mut e = Encoder::new(palette.depth)
            .with_metric(palette.metric)
            .with_dither(palette.dither);
        e.prepare(&frame);
        full += e.last_bytes().len();
        let turned = RenderOptions {
            turn: opts.turn + Vec3::new(0.0, 3.0, 0.0),
            ..opts
        };
        e.prepare(&rastty::render(&w.scene, &turned));
        next += e.last_bytes().len();
        // Each cell's light: its two colours weighted by the glyph's share.
        let mut q = color::Quantizer::of(palette);
        let bg = w.scene.background.unwrap_or(Rgb::BLACK);
        let light = |c: Option<Rgb>| Vec3::from(Lin::from_srgb(c.unwrap_or(bg)).to_f32());
        // Each cell's light: its two colours weighted by the glyph's share,
        // as sent (through the encoder's own cell mapping) or as drawn.
        let share = |ch: char| match ch {
            ' ' => 0.0,
            '█' => 1.0,
            _ => 0.5,
        };
        let cell_light = |x: u16, y: u16, q: &mut Option<&mut color::Quantizer>| {
            let (ch, fg, bg_) = match q {
                Some(q) => {
                    let t = TermCell::at(&frame, q, x, y);
                    let ink = |i: Ink| match i {
                        Ink::Indexed(i) => Some(color::xterm256(i)),
                        Ink::Rgb(c) => Some(c),
                        Ink::Default => None,
                    };
                    (t.ch, ink(t.fg), ink(t.bg))
                }
                None => {
                    let cell = frame.get(x, y);
                    (cell.ch, cell.fg, cell.bg)
                }
            };
            light(fg) * share(ch) + light(bg_) * (1.0 - share(ch))
        };
        for by in 0..frame.rows() / 2 {
            for bx in 0..frame.cols() / 2 {
                let (mut want, mut got) = (Vec3::ZERO, Vec3::ZERO);
                for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                    let (x, y) = (bx * 2 + dx, by * 2 + dy);
                    want += cell_light(x, y, &mut None);
                    got += cell_light(x, y, &mut Some(&mut q));
                }
                let enc = |v: Vec3| Lin::from_f32((v / 4.0).to_array()).to_srgb();
                let (a, b) = (enc(want), enc(got));
                if a != bg || b != bg {
                    err += color::oklab_distance(a, b) as f64;
                    blocks += 1;
                }
            }
        }
    }
    let k = workloads.len().max(1) as f64;
    DitherCost {
        error: err / blocks.max(1) as f64,
        full_bytes: full as f64 / k,
        next_bytes: next as f64 / k,
    }
}
