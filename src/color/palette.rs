//! Palettes: sending a colour to a terminal of 16 or 256 colours.
//!
//! **Matching.** Nearest in plain OKLab lets lightness outweigh hue and
//! chroma: a mid grey in 16 colours is nearer cyan (of the right
//! lightness) than either grey, and an orange goes yellow. rastty matches
//! in OKLCh ([`Metric::Oklch`], the default): an achromatic colour (chroma
//! below [`GREY_CHROMA`]) goes only to an achromatic palette entry, so a
//! grey ramp in 16 colours uses black, the two greys and white; a
//! chromatic one is matched by lightness, chroma and hue, the squared
//! difference of hue weighted [`HUE_WEIGHT`] times, a grey counting as
//! losing all of it, so that a colour keeps its hue and does not fade to
//! grey. (`rastty bench` measures all three metrics.)
//!
//! **Ordered dithering** ([`Dither::Ordered`], the default at both
//! depths) draws a colour the palette lacks as a [`Pattern`] of entries
//! whose mean light (the eye mixes neighbouring cells in linear light)
//! comes nearest it by the same metric: in 256 colours two neighbours of
//! the cube in sixteenths ([`pair`]), in 16 as many entries of the hues
//! either side as it takes, in eighths ([`blend`]: a brown is black, red
//! and yellow). A 4×4 Bayer matrix indexed by column and row decides which
//! cell shows which entry; the encoder dithers by half-cells, so a 2×2-cell
//! area shows eight places of the pattern. The pattern is fixed to the
//! screen, so a still picture does not shimmer, and a colour that is a
//! palette entry is never dithered.
//!
//! What it buys, measured on the fox by `tests/render/fidelity.rs` (2×2-cell
//! areas against truecolor, in OKLab): in 256 colours the 95th percentile
//! of error falls from 0.055 to 0.029 and the hue error from 13.8° to
//! 6.2°; in 16 colours from 0.157 to 0.107 and from 41.9° to 15.8°, with
//! no dark area lost to the background. What it costs: bytes, as
//! neighbouring cells differ where they did not (`rastty bench`, the
//! dithering rows); `--dither none` turns it off.

use std::sync::OnceLock;

use super::{ColorDepth, Ink, Lin, Rgb};

/// The xterm defaults for the 16 ANSI colours (terminals differ; these are
/// what "nearest" is measured against).
pub const ANSI16: [Rgb; 16] = [
    Rgb([0, 0, 0]),
    Rgb([205, 0, 0]),
    Rgb([0, 205, 0]),
    Rgb([205, 205, 0]),
    Rgb([0, 0, 238]),
    Rgb([205, 0, 205]),
    Rgb([0, 205, 205]),
    Rgb([229, 229, 229]),
    Rgb([127, 127, 127]),
    Rgb([255, 0, 0]),
    Rgb([0, 255, 0]),
    Rgb([255, 255, 0]),
    Rgb([92, 92, 255]),
    Rgb([255, 0, 255]),
    Rgb([0, 255, 255]),
    Rgb([255, 255, 255]),
];

/// The levels of the xterm 6×6×6 cube.
const CUBE: [u8; 6] = [0, 95, 135, 175, 215, 255];

/// The RGB value of xterm palette index `i` (16–255; 0–15 are
/// [`ANSI16`]).
pub fn xterm256(i: u8) -> Rgb {
    match i {
        0..=15 => ANSI16[i as usize],
        16..=231 => {
            let k = i - 16;
            Rgb([
                CUBE[(k / 36) as usize],
                CUBE[(k / 6 % 6) as usize],
                CUBE[(k % 6) as usize],
            ])
        }
        _ => {
            let v = 8 + 10 * (i - 232);
            Rgb([v, v, v])
        }
    }
}

/// How "nearest" is measured when a colour is mapped onto a palette.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Metric {
    /// Squared distance of the sRGB bytes: cheap, and visibly wrong for
    /// darks and blues.
    Rgb,
    /// Squared distance in OKLab, a perceptually uniform space: lightness
    /// outweighs hue (greys go cyan in 16 colours).
    Oklab,
    /// OKLCh: greys only to greys, hue weighted to stay in its family.
    #[default]
    Oklch,
}

crate::choice::choice!(Metric {
    Rgb => "rgb": "Squared distance of the sRGB bytes: cheap, and visibly wrong for darks and blues",
    Oklab => "oklab": "Squared distance in OKLab, a perceptually uniform space: lightness outweighs hue (greys go cyan in 16 colours)",
    Oklch => "oklch": "OKLCh: greys only to greys, hue weighted to stay in its family",
});

/// Whether colours between palette entries are drawn as patterns of two.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Dither {
    /// Ordered at 16 and 256 colours (truecolor never needs it).
    #[default]
    Auto,
    /// Each colour to its nearest entry.
    None,
    /// A 4×4 Bayer pattern of the entries that mix to the colour.
    Ordered,
}

crate::choice::choice!(Dither {
    Auto => "auto": "Ordered at 16 and 256 colours (truecolor never needs it)",
    None => "none": "Each colour to its nearest entry",
    Ordered => "ordered": "A 4×4 Bayer pattern of the entries that mix to the colour",
});

impl Dither {
    /// What `auto` is at `depth`.
    pub fn resolve(self, depth: ColorDepth) -> Dither {
        match (self, depth) {
            (Dither::Auto, ColorDepth::Ansi16 | ColorDepth::Ansi256) => Dither::Ordered,
            (Dither::Auto, _) => Dither::None,
            (d, _) => d,
        }
    }
}

/// How colours are sent at one depth: matched by `metric`, dithered as
/// `dither` says.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Palette {
    /// How many colours the terminal has.
    pub depth: ColorDepth,
    /// How the nearest palette colour is measured.
    pub metric: Metric,
    /// Whether colours between palette entries are dithered.
    pub dither: Dither,
}

impl From<ColorDepth> for Palette {
    /// The depth with the default matching and dithering.
    fn from(depth: ColorDepth) -> Palette {
        Palette {
            depth,
            ..Palette::default()
        }
    }
}

/// Below this OKLab chroma a colour is achromatic: it goes to a grey.
pub const GREY_CHROMA: f32 = 0.03;
/// How much a squared difference of chroma counts against one of
/// lightness, in [`Metric::Oklch`].
pub const CHROMA_WEIGHT: f32 = 1.0;
/// How much more a squared difference of hue counts than one of lightness,
/// in [`Metric::Oklch`]; a grey has no hue, so a colour sent to one loses
/// all of it (ΔH = C). Chosen by `rastty bench`'s measures
/// (docs/accuracy.md): against plain OKLab it sends far fewer hues more
/// than 45° away, for a little more mean distance.
pub const HUE_WEIGHT: f32 = 4.0;

/// A palette entry in OKLab, with its chroma.
#[derive(Clone, Copy, Debug)]
struct Entry {
    lab: [f32; 3],
    chroma: f32,
}

fn lab(c: Rgb) -> [f32; 3] {
    let [r, g, b] = c.0;
    let l = oklab::srgb_to_oklab(oklab::Rgb { r, g, b });
    [l.l, l.a, l.b]
}

/// The distance between two colours in OKLab (about 0.02 is a just
/// noticeable difference).
pub fn oklab_distance(a: Rgb, b: Rgb) -> f32 {
    let (p, q) = (lab(a), lab(b));
    ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
}

/// A colour's OKLab chroma.
pub fn chroma(c: Rgb) -> f32 {
    let [_, a, b] = lab(c);
    a.hypot(b)
}

/// The 256 palette colours in OKLab, computed once.
fn entries() -> &'static [Entry; 256] {
    static TABLE: OnceLock<[Entry; 256]> = OnceLock::new();
    TABLE.get_or_init(|| {
        std::array::from_fn(|i| {
            let lab = lab(xterm256(i as u8));
            Entry {
                lab,
                chroma: lab[1].hypot(lab[2]),
            }
        })
    })
}

/// The indices a depth chooses among: the cube and greys (16–255) for 256
/// colours, [`ANSI16`] for 16.
fn range(depth: ColorDepth) -> std::ops::RangeInclusive<u8> {
    match depth {
        ColorDepth::Ansi16 => 0..=15u8,
        _ => 16..=255u8,
    }
}

/// How far colour `q` (of OKLab `q_lab`) is from `c` (of OKLab `p` and
/// chroma `cp`), by `metric` (in comparable units: only the order
/// matters).
#[inline]
fn distance_to(metric: Metric, c: Rgb, p: [f32; 3], cp: f32, q: Rgb, q_lab: [f32; 3]) -> f32 {
    let sq = |u: [f32; 3], v: [f32; 3]| {
        (u[0] - v[0]).powi(2) + (u[1] - v[1]).powi(2) + (u[2] - v[2]).powi(2)
    };
    match metric {
        Metric::Rgb => sq(c.to_f32(), q.to_f32()),
        Metric::Oklab => sq(p, q_lab),
        Metric::Oklch => {
            let qc = q_lab[1].hypot(q_lab[2]);
            let dl = p[0] - q_lab[0];
            let dc = cp - qc;
            let dab = (p[1] - q_lab[1]).powi(2) + (p[2] - q_lab[2]).powi(2);
            // ΔH² = Δa² + Δb² − ΔC²; a grey has no hue, so sending a
            // colour to one loses all of it (ΔH = C).
            let dh = if qc < GREY_CHROMA && cp >= GREY_CHROMA {
                cp * cp
            } else {
                (dab - dc * dc).max(0.0)
            };
            dl * dl + CHROMA_WEIGHT * dc * dc + HUE_WEIGHT * dh
        }
    }
}

/// How far palette entry `i` is from `c` (see [`distance_to`]); `None`
/// where the entry is not a candidate (a chromatic entry for a grey, under
/// OKLCh).
#[inline]
fn distance(metric: Metric, c: Rgb, p: [f32; 3], cp: f32, i: u8) -> Option<f32> {
    let q = entries()[i as usize];
    if metric == Metric::Oklch && cp < GREY_CHROMA && q.chroma >= GREY_CHROMA {
        return None;
    }
    Some(distance_to(metric, c, p, cp, xterm256(i), q.lab))
}

/// The palette index nearest to `c` by `metric`: among the cube and greys
/// (16–255) for [`ColorDepth::Ansi256`], among [`ANSI16`] for
/// [`ColorDepth::Ansi16`]. Ties go to the lower index.
pub fn nearest(depth: ColorDepth, metric: Metric, c: Rgb) -> u8 {
    let p = lab(c);
    let cp = p[1].hypot(p[2]);
    let mut best = (f32::INFINITY, *range(depth).start());
    for i in range(depth) {
        if let Some(d) = distance(metric, c, p, cp, i)
            && d < best.0
        {
            best = (d, i);
        }
    }
    best.1
}

/// How many cells a dithering pattern has: the 4×4 Bayer matrix's.
pub const CELLS: usize = 16;

/// How a colour is dithered: the cell whose Bayer threshold is `t` shows
/// palette entry `self.0[t]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Pattern(pub [u8; CELLS]);

impl Pattern {
    /// One entry in every cell: not dithered.
    pub const fn solid(i: u8) -> Pattern {
        Pattern([i; CELLS])
    }
}

/// A colour in linear light, channels in [0, 1].
fn linear(c: Rgb) -> [f32; 3] {
    Lin::from_srgb(c).to_f32().map(|v| v / 65535.0)
}

/// OKLab of a linear-light colour, channels in [0, 1].
fn lab_linear([r, g, b]: [f32; 3]) -> [f32; 3] {
    let l = oklab::linear_srgb_to_oklab(oklab::LinearRgb { r, g, b });
    [l.l, l.a, l.b]
}

/// The dithering pattern for `c` at `depth`: [`pair`] in 256 colours,
/// [`blend`] in 16.
pub fn pattern(depth: ColorDepth, metric: Metric, c: Rgb) -> Pattern {
    match depth {
        ColorDepth::Ansi16 => blend(metric, c),
        _ => pair(depth, metric, c),
    }
}

/// How many of the nearest entries a [`pair`] is chosen from.
pub const PAIR_CANDIDATES: usize = 8;
/// What a pair's own distance adds to its error: two entries far apart
/// make a pattern that reads as two colours rather than their blend
/// (Yliluoma's penalty), so that an orange is drawn as red and yellow, not
/// red and green.
pub const PAIR_SPREAD: f32 = 0.05;

/// A pattern of two of `c`'s [`PAIR_CANDIDATES`] nearest entries (by
/// `metric`, among those it allows: greys mix only with greys) in
/// sixteenths: the pair and proportion whose blend, mixed in linear light
/// as the eye mixes neighbouring cells, is nearest `c` by `metric`,
/// counting the pair's spread ([`PAIR_SPREAD`]). A colour nearer an entry
/// than any blend is that entry in every cell: never dithered. The 256
/// colours' cube has an entry near every colour, and two of them in
/// sixteenths reach it more closely than more of them in eighths
/// ([`blend`]): on the fox, 6.2° of hue error against 9.9°.
pub fn pair(depth: ColorDepth, metric: Metric, c: Rgb) -> Pattern {
    let p = lab(c);
    let cp = p[1].hypot(p[2]);
    // The candidates, nearest first (ties to the lower index), kept in a
    // fixed array by insertion: a pattern is made on a palette cache
    // miss, while a frame is encoded, which must not allocate.
    let mut kept = [(0.0f32, 0u8); PAIR_CANDIDATES];
    let mut len = 0;
    // A colour's blend is never of a grey other than black: grey and a
    // hue make a patchwork, where black only darkens.
    let chromatic = metric == Metric::Oklch && cp >= GREY_CHROMA;
    for i in range(depth) {
        let e = entries()[i as usize];
        if chromatic && e.chroma < GREY_CHROMA && xterm256(i) != Rgb::BLACK {
            continue;
        }
        let Some(d) = distance(metric, c, p, cp, i) else {
            continue;
        };
        // Entries come in increasing index: a tie goes after those kept.
        let at = kept[..len].partition_point(|k| k.0.total_cmp(&d).is_le());
        if at < PAIR_CANDIDATES {
            let end = len.min(PAIR_CANDIDATES - 1);
            kept.copy_within(at..end, at + 1);
            kept[at] = (d, i);
            len = (len + 1).min(PAIR_CANDIDATES);
        }
    }
    let near = &kept[..len];
    let Some(&(first, a)) = near.first() else {
        return Pattern::solid(0);
    };
    let lin = |c: Rgb| glam::Vec3::from(linear(c));
    let target = lin(c);
    // (error, a, b, level): `b` in `level` sixteenths.
    let mut best = (first, a, a, 0);
    for (k, &(_, i)) in near.iter().enumerate() {
        let (ei, from) = (entries()[i as usize], lin(xterm256(i)));
        for &(_, j) in &near[k + 1..] {
            let ej = entries()[j as usize];
            let spread = distance_to(metric, xterm256(i), ei.lab, ei.chroma, xterm256(j), ej.lab);
            let d = lin(xterm256(j)) - from;
            // The level whose blend is nearest in linear light, and its
            // neighbours, judged by the metric.
            let t = ((target - from).dot(d) / d.length_squared()).clamp(0.0, 1.0);
            let centre = (t * CELLS as f32).round() as i32;
            for level in (centre - 1).max(1)..=(centre + 1).min(CELLS as i32 - 1) {
                let blend = from + d * (level as f32 / CELLS as f32);
                let shown = Lin::from_f32((blend * 65535.0).to_array()).to_srgb();
                let err = distance_to(metric, c, p, cp, shown, lab(shown)) + PAIR_SPREAD * spread;
                if err < best.0 {
                    best = (err, i, j, level as usize);
                }
            }
        }
    }
    let (_, a, b, level) = best;
    Pattern(std::array::from_fn(|t| if t < level { b } else { a }))
}

/// How many parts a [`blend`] is made of: eighths, each two cells of the
/// sixteen.
pub const PARTS: usize = CELLS / 2;
/// How far (degrees) beyond the nearest hues either side of a colour's a
/// 16-colour entry may lie and still be in its [`blend`].
pub const HUE_SLACK: f32 = 10.0;
/// What a blend's spread adds to its error: the mean squared OKLab
/// distance of its parts from the colour, times this; it prefers the
/// entries nearest the colour among blends that come equally near.
pub const SPREAD: f32 = 0.02;
/// The OKLab lightness from which a colour is never blended all black: a
/// dark region stays visible against a black background.
pub const VISIBLE: f32 = 0.1;

/// A pattern for 16 colours: eighths of as many entries as it takes, in
/// the proportions whose mean light (the eye adds neighbouring cells in
/// linear light) is nearest `c` by `metric`, counting the blend's spread
/// ([`SPREAD`]). A brown is black, red and yellow, not grey with red dots
/// (two entries cannot make it: the 16 colours have no hue between red
/// and yellow).
///
/// - The entries: under [`Metric::Oklch`] a grey's are the greys; a
///   colour's are the greys and the entries of the hues either side of its
///   own ([`HUE_SLACK`]): a mix of those keeps the hue, where one with a
///   far hue (green in a brown) reads as noise.
/// - The proportions: from all eight parts on the nearest entry, one part
///   at a time moves to the entry that brings the mean nearest, while one
///   does; a colour nearer an entry than any blend is that entry
///   throughout (never dithered). A colour of lightness [`VISIBLE`] or
///   more keeps one part off black.
/// - The cells: each part is two cells, side by side in order of
///   lightness, so that any 2×2 block of the matrix (and so the half-cells
///   of 2×2 terminal cells, as [`TermCell`](crate::encode::TermCell)
///   dithers) holds one of each (thresholds `2k` and `2k + 1` never share
///   one) and shows the whole mix, not a quarter of it.
pub fn blend(metric: Metric, c: Rgb) -> Pattern {
    let depth = ColorDepth::Ansi16;
    let p = lab(c);
    let cp = p[1].hypot(p[2]);
    let grey = metric == Metric::Oklch && cp < GREY_CHROMA;
    let hue = |q: [f32; 3]| q[2].atan2(q[1]).to_degrees();
    let turn = |i: u8| {
        let d = hue(entries()[i as usize].lab) - hue(p);
        (d + 540.0).rem_euclid(360.0) - 180.0
    };
    let achromatic = |i: u8| entries()[i as usize].chroma < GREY_CHROMA;
    let chromatic = || range(depth).filter(|&i| !achromatic(i));
    let below = chromatic()
        .map(turn)
        .filter(|&d| d <= 0.0)
        .fold(-180.0f32, f32::max);
    let above = chromatic()
        .map(turn)
        .filter(|&d| d >= 0.0)
        .fold(180.0f32, f32::min);
    let allowed = |i: u8| {
        achromatic(i)
            || (!grey
                && (metric != Metric::Oklch
                    || (below - HUE_SLACK..=above + HUE_SLACK).contains(&turn(i))))
    };
    let first = nearest(depth, metric, c);
    let mut kept = [first; 16];
    let mut len = 1;
    for i in range(depth).filter(|&i| i != first && allowed(i)) {
        kept[len] = i;
        len += 1;
    }
    let kept = &kept[..len];
    let light: [[f32; 3]; 16] = std::array::from_fn(|k| linear(xterm256(kept[k.min(len - 1)])));
    let spread: [f32; 16] = std::array::from_fn(|k| {
        let q = entries()[kept[k.min(len - 1)] as usize].lab;
        (0..3).map(|j| (p[j] - q[j]).powi(2)).sum::<f32>() * SPREAD / PARTS as f32
    });
    let cost = |sum: [f32; 3], spreads: f32| {
        let mean = sum.map(|v| v / PARTS as f32);
        let shown = Lin::from_f32(mean.map(|v| v * 65535.0)).to_srgb();
        distance_to(metric, c, p, cp, shown, lab_linear(mean)) + spreads
    };
    let mut counts = [0u8; 16];
    counts[0] = PARTS as u8;
    let mut sum = light[0].map(|v| v * PARTS as f32);
    let mut spreads = spread[0] * PARTS as f32;
    let moved = |sum: [f32; 3], from: usize, to: usize| -> [f32; 3] {
        std::array::from_fn(|j| sum[j] - light[from][j] + light[to][j])
    };
    // Each round makes the best single move and must lower the error, so
    // the search ends.
    let mut now = cost(sum, spreads);
    loop {
        let mut best = (now, 0, 0);
        for from in (0..len).filter(|&k| counts[k] > 0) {
            for to in (0..len).filter(|&k| k != from) {
                let e = cost(moved(sum, from, to), spreads - spread[from] + spread[to]);
                if e < best.0 {
                    best = (e, from, to);
                }
            }
        }
        let (e, from, to) = best;
        if e >= now {
            break;
        }
        counts[from] -= 1;
        counts[to] += 1;
        sum = moved(sum, from, to);
        spreads += spread[to] - spread[from];
        now = e;
    }
    // A colour that shows against black is never all black.
    let black = |k: usize| xterm256(kept[k]) == Rgb::BLACK;
    if p[0] >= VISIBLE
        && let Some(from) = (0..len).find(|&k| counts[k] > 0)
        && (0..len).all(|k| counts[k] == 0 || black(k))
        && let Some((_, to)) = (0..len)
            .filter(|&k| !black(k))
            .map(|to| {
                (
                    cost(moved(sum, from, to), spreads - spread[from] + spread[to]),
                    to,
                )
            })
            .min_by(|a, b| a.0.total_cmp(&b.0))
    {
        counts[from] -= 1;
        counts[to] += 1;
    }
    let mut picks = [0u8; CELLS];
    let mut at = 0;
    for (k, &n) in counts[..len].iter().enumerate() {
        picks[at..at + 2 * n as usize].fill(kept[k]);
        at += 2 * n as usize;
    }
    picks.sort_by(|&a, &b| {
        entries()[a as usize].lab[0]
            .total_cmp(&entries()[b as usize].lab[0])
            .then(a.cmp(&b))
    });
    Pattern(picks)
}

/// The 4×4 Bayer matrix: cell `(x, y)` has threshold `BAYER[y % 4][x % 4]`
/// and shows that entry of a [`Pattern`]. Each 2×2 block of it holds one
/// threshold of each quarter (`k, k+4, k+8, k+12`), so a block a little
/// way off shows the pattern's whole range.
const BAYER: [[u8; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];

/// Maps colours to [`Ink`] for one depth, remembering recent answers (the
/// nearest-palette search is up to 240 distance evaluations, a mix up to
/// twice that; a frame has few distinct colours). The cache is
/// direct-mapped and allocated once.
#[derive(Clone, Debug)]
pub struct Quantizer {
    depth: ColorDepth,
    metric: Metric,
    dither: Dither,
    /// `(rgb | VALID, mix)`.
    cache: Vec<(u32, Pattern)>,
    /// The cache holds `1 << cache_bits` colours.
    cache_bits: u32,
}

const CACHE_BITS: u32 = 12;
const VALID: u32 = 1 << 24;

impl Quantizer {
    /// A quantizer for `depth`, matching by `metric`, dithering as `auto`
    /// says for the depth.
    pub fn new(depth: ColorDepth, metric: Metric) -> Quantizer {
        Quantizer {
            depth,
            metric,
            dither: Dither::Auto.resolve(depth),
            cache: Vec::new(),
            cache_bits: CACHE_BITS,
        }
    }

    /// The same, dithering as `dither` says.
    pub fn with_dither(mut self, dither: Dither) -> Quantizer {
        self.dither = dither.resolve(self.depth);
        self
    }

    /// The same, remembering `1 << bits` colours (from 8 to 20; a frame
    /// of pixels has many more colours than one of cells).
    pub fn with_cache_bits(mut self, bits: u32) -> Quantizer {
        self.cache_bits = bits.clamp(8, 20);
        self.cache = Vec::new();
        self
    }

    /// A quantizer for `palette`.
    pub fn of(palette: Palette) -> Quantizer {
        Quantizer::new(palette.depth, palette.metric).with_dither(palette.dither)
    }

    /// The colour depth it maps to.
    pub fn depth(&self) -> ColorDepth {
        self.depth
    }

    /// How it measures nearness.
    pub fn metric(&self) -> Metric {
        self.metric
    }

    /// The dithering in force (`auto` resolved).
    pub fn dither(&self) -> Dither {
        self.dither
    }

    /// Whether colours are drawn as patterns ([`Dither::Ordered`] at a
    /// palette's depth).
    #[inline]
    pub fn dithers(&self) -> bool {
        self.dither == Dither::Ordered
            && matches!(self.depth, ColorDepth::Ansi16 | ColorDepth::Ansi256)
    }

    /// The ink for a colour (`None`: the terminal's default), undithered.
    pub fn ink(&mut self, c: Option<Rgb>) -> Ink {
        self.ink_at(c, 0, 0)
    }

    /// The ink for a colour in the cell at column `x`, row `y` (where the
    /// dithering pattern is anchored).
    #[inline]
    pub fn ink_at(&mut self, c: Option<Rgb>, x: u16, y: u16) -> Ink {
        let Some(c) = c else { return Ink::Default };
        match self.depth {
            ColorDepth::None => Ink::Default,
            ColorDepth::TrueColor => Ink::Rgb(c),
            depth => self.palette_ink(depth, c, x, y),
        }
    }

    /// [`Quantizer::ink_at`], except that where the pattern shows black in
    /// this cell and has a lighter entry, the darkest such entry: for a
    /// colour whose cell shares nothing with the rest of its pattern (a
    /// thin dark edge against the background), which would otherwise
    /// vanish.
    pub fn ink_alone(&mut self, c: Option<Rgb>, x: u16, y: u16) -> Ink {
        let ink = self.ink_at(c, x, y);
        match (ink, c) {
            (Ink::Indexed(i), Some(c)) if self.dithers() && xterm256(i) == Rgb::BLACK => {
                let p = self.pattern_of(self.depth, c);
                match p.0.iter().find(|&&e| xterm256(e) != Rgb::BLACK) {
                    Some(&e) => Ink::Indexed(e),
                    None => ink,
                }
            }
            _ => ink,
        }
    }

    /// [`Quantizer::ink_at`] for a palette: out of line, so that the
    /// truecolor case inlines to a copy.
    #[inline(never)]
    fn palette_ink(&mut self, depth: ColorDepth, c: Rgb, x: u16, y: u16) -> Ink {
        let m = self.pattern_of(depth, c);
        Ink::Indexed(m.0[BAYER[(y % 4) as usize][(x % 4) as usize] as usize])
    }

    /// The pattern for `c` at `depth` (one entry throughout, undithered),
    /// from the cache or made and kept.
    fn pattern_of(&mut self, depth: ColorDepth, c: Rgb) -> Pattern {
        if self.cache.is_empty() {
            self.cache = vec![(0, Pattern::solid(0)); 1 << self.cache_bits];
        }
        let [r, g, b] = c.0;
        let key = (r as u32) << 16 | (g as u32) << 8 | b as u32;
        let slot = (key.wrapping_mul(0x9E37_79B1) >> (32 - self.cache_bits)) as usize;
        let (k, cached) = self.cache[slot];
        if k == key | VALID {
            return cached;
        }
        let m = if self.dither == Dither::Ordered {
            pattern(depth, self.metric, c)
        } else {
            Pattern::solid(nearest(depth, self.metric, c))
        };
        self.cache[slot] = (key | VALID, m);
        m
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::choice::Choice;

    #[test]
    fn xterm_palette_values() {
        assert_eq!(xterm256(16), Rgb([0, 0, 0]));
        assert_eq!(xterm256(196), Rgb([255, 0, 0]));
        assert_eq!(xterm256(231), Rgb([255, 255, 255]));
        assert_eq!(xterm256(232), Rgb([8, 8, 8]));
        assert_eq!(xterm256(255), Rgb([238, 238, 238]));
    }

    #[test]
    fn nearest_finds_exact_palette_colours() {
        for &metric in Metric::ALL {
            for i in 16..=255u8 {
                let c = xterm256(i);
                let j = nearest(ColorDepth::Ansi256, metric, c);
                assert_eq!(xterm256(j), c, "index {i} {metric:?}");
            }
            for (i, &c) in ANSI16.iter().enumerate() {
                assert_eq!(nearest(ColorDepth::Ansi16, metric, c), i as u8);
            }
        }
        assert_eq!(
            nearest(ColorDepth::Ansi16, Metric::Oklab, Rgb([250, 10, 10])),
            9
        );
    }

    #[test]
    fn a_grey_ramp_in_16_colours_uses_only_black_the_two_greys_and_white() {
        let mut used = std::collections::BTreeSet::new();
        for v in 0..=255u8 {
            used.insert(nearest(ColorDepth::Ansi16, Metric::Oklch, Rgb([v, v, v])));
        }
        assert_eq!(used, [0, 7, 8, 15].into_iter().collect());
        // Dithered too: every pattern of a grey is of greys.
        for v in 0..=255u8 {
            let p = pattern(ColorDepth::Ansi16, Metric::Oklch, Rgb([v, v, v]));
            assert!(p.0.iter().all(|i| [0, 7, 8, 15].contains(i)), "{v}: {p:?}");
        }
        // Plain OKLab sends some greys to cyan (6).
        let oklab: std::collections::BTreeSet<u8> = (0..=255u8)
            .map(|v| nearest(ColorDepth::Ansi16, Metric::Oklab, Rgb([v, v, v])))
            .collect();
        assert!(oklab.contains(&6), "{oklab:?}");
    }

    #[test]
    fn a_palette_colour_is_never_dithered_and_a_pattern_mixes_to_the_colour() {
        for i in 0..16u8 {
            let p = pattern(ColorDepth::Ansi16, Metric::Oklch, ANSI16[i as usize]);
            assert_eq!(p, Pattern([i; CELLS]));
        }
        // Mid grey between 8 (127) and 7 (229): a pattern of the two,
        // darker first, each in pairs of cells.
        let p = pattern(ColorDepth::Ansi16, Metric::Oklch, Rgb([190, 190, 190]));
        assert_eq!(p, Pattern([8, 8, 8, 8, 8, 8, 8, 8, 7, 7, 7, 7, 7, 7, 7, 7]));
        // A fox's brown (#8a4a1a) in 16 colours: black, red and yellow,
        // whose mean light is the brown's, and each half of the matrix
        // (any 2×2 block of it) shows the same mix.
        let brown = Rgb([0x8a, 0x4a, 0x1a]);
        let p = pattern(ColorDepth::Ansi16, Metric::Oklch, brown);
        assert_eq!(p, Pattern([0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 3, 3]));
        let mean = |cells: &mut dyn Iterator<Item = u8>, n: f32| {
            cells.fold([0.0f32; 3], |m, i| {
                let l = linear(xterm256(i));
                std::array::from_fn(|k| m[k] + l[k] / n)
            })
        };
        let all = mean(&mut p.0.into_iter(), 16.0);
        // Eighths cannot reach it exactly: the nearest mix is a little
        // lighter, of the same hue.
        let (got, want) = (lab_linear(all), lab(brown));
        let hue = |l: [f32; 3]| l[2].atan2(l[1]).to_degrees();
        let de = (0..3)
            .map(|k| (got[k] - want[k]).powi(2))
            .sum::<f32>()
            .sqrt();
        assert!(
            de < 0.04 && (hue(got) - hue(want)).abs() < 4.0,
            "{got:?} {want:?}"
        );
        let block = mean(
            &mut [0, 8, 12, 4, 3, 11, 15, 7].map(|t| p.0[t]).into_iter(),
            8.0,
        );
        assert!(
            (0..3).all(|k| (block[k] - all[k]).abs() < 1e-6),
            "{block:?} {all:?}"
        );
        // In 256 colours, a pair of the cube's neighbours in sixteenths.
        let p = pattern(ColorDepth::Ansi256, Metric::Oklch, brown);
        println!("{p:?}");
        let used: std::collections::BTreeSet<u8> = p.0.into_iter().collect();
        assert_eq!(used.len(), 2, "{p:?}");
    }

    #[test]
    fn the_pattern_is_anchored_to_the_screen() {
        let grey = Rgb([190, 190, 190]);
        let c = Some(grey);
        let mut q = Quantizer::new(ColorDepth::Ansi16, Metric::Oklch).with_dither(Dither::Ordered);
        let p = pattern(ColorDepth::Ansi16, Metric::Oklch, grey);
        // Of the 16 cells of the matrix, each shows the pattern's entry for
        // its threshold, and the same cell always shows the same.
        for k in 0..16u16 {
            let t = BAYER[(k / 4) as usize][(k % 4) as usize] as usize;
            assert_eq!(q.ink_at(c, k % 4, k / 4), Ink::Indexed(p.0[t]));
        }
        assert_eq!(q.ink_at(c, 5, 9), q.ink_at(c, 1, 1));
    }

    #[test]
    fn quantizer_caches_without_changing_answers() {
        let mut q = Quantizer::new(ColorDepth::Ansi256, Metric::Oklab).with_dither(Dither::None);
        for c in [Rgb([1, 2, 3]), Rgb([200, 100, 50]), Rgb([1, 2, 3])] {
            assert_eq!(
                q.ink(Some(c)),
                Ink::Indexed(nearest(ColorDepth::Ansi256, Metric::Oklab, c))
            );
        }
        assert_eq!(q.ink(None), Ink::Default);
        let mut t = Quantizer::new(ColorDepth::TrueColor, Metric::Oklab);
        assert_eq!(t.ink(Some(Rgb([1, 2, 3]))), Ink::Rgb(Rgb([1, 2, 3])));
    }
}
