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
//! **Ordered dithering** ([`Dither::Ordered`]) draws a colour between two
//! palette entries as a pattern of both, cell by cell: the pair and its
//! proportion are those whose blend (in linear light, as the eye mixes
//! neighbouring cells) comes nearest, by the same metric, less a penalty
//! for pairs far apart ([`mix`]); a 4×4 Bayer matrix indexed by the cell's
//! column and row decides which cell shows which. The pattern is fixed to the screen, so a still picture does not
//! shimmer, and a colour that is a palette entry is never dithered.
//! It costs bytes: neighbouring cells differ where they did not. `auto`,
//! the default, dithers 16 colours, where matching alone loses most, and
//! not 256 (see the measurements in docs/accuracy.md).

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
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
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

impl Metric {
    /// Every metric.
    pub const ALL: [Metric; 3] = [Metric::Rgb, Metric::Oklab, Metric::Oklch];

    /// The name the command line uses.
    pub const fn name(self) -> &'static str {
        match self {
            Metric::Rgb => "rgb",
            Metric::Oklab => "oklab",
            Metric::Oklch => "oklch",
        }
    }
}

/// Whether colours between palette entries are drawn as patterns of two.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Dither {
    /// Ordered for 16 colours, none for 256 (and truecolor never needs it).
    #[default]
    Auto,
    /// Each colour to its nearest entry.
    None,
    /// A 4×4 Bayer pattern of the two entries that mix to the colour.
    Ordered,
}

impl Dither {
    /// Every setting.
    pub const ALL: [Dither; 3] = [Dither::Auto, Dither::None, Dither::Ordered];

    /// The name the command line uses.
    pub const fn name(self) -> &'static str {
        match self {
            Dither::Auto => "auto",
            Dither::None => "none",
            Dither::Ordered => "ordered",
        }
    }

    /// What `auto` is at `depth`.
    pub fn resolve(self, depth: ColorDepth) -> Dither {
        match (self, depth) {
            (Dither::Auto, ColorDepth::Ansi16) => Dither::Ordered,
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
/// all of it (ΔH = C). Chosen by `rastty bench`'s measures (see the
/// docs/accuracy.md): hues moved over 45° fall from 21.6 % (plain OKLab) to 6.1 % in
/// 16 colours and from 0.84 % to none in 256, for 7 % more mean distance.
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
#[cfg_attr(not(feature = "bench"), allow(dead_code))]
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

/// How a colour is dithered: between entries `a` and `b`, `b` in
/// `level` of every 16 cells.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mix {
    pub a: u8,
    pub b: u8,
    pub level: u8,
}

/// How many of the nearest entries a mix is made from.
pub const MIX_CANDIDATES: usize = 8;
/// What a pair's own distance adds to a mix's error: two entries far apart
/// make a pattern that reads as two colours rather than their blend
/// (Yliluoma's penalty), so that an orange is drawn as red and yellow, not
/// red and green.
pub const MIX_SPREAD: f32 = 0.05;

/// The mix for `c`: two of its [`MIX_CANDIDATES`] nearest entries (by
/// `metric`, among those it allows: greys mix only with greys) and the
/// level (0–16) whose blend, mixed in linear light as the eye mixes
/// neighbouring cells, is nearest `c` by `metric` too, counting the pair's
/// spread ([`MIX_SPREAD`]). A colour nearer an entry than any mix gets
/// level 0: never dithered.
pub fn mix(depth: ColorDepth, metric: Metric, c: Rgb) -> Mix {
    let p = lab(c);
    let cp = p[1].hypot(p[2]);
    // The candidates, nearest first (ties to the lower index), kept in a
    // fixed array by insertion: a mix is found on a palette cache miss,
    // while a frame is encoded, which must not allocate.
    let mut kept = [(0.0f32, 0u8); MIX_CANDIDATES];
    let mut len = 0;
    for i in range(depth) {
        let Some(d) = distance(metric, c, p, cp, i) else {
            continue;
        };
        // Entries come in increasing index: a tie goes after those kept.
        let at = kept[..len].partition_point(|k| k.0.total_cmp(&d).is_le());
        if at < MIX_CANDIDATES {
            let end = len.min(MIX_CANDIDATES - 1);
            kept.copy_within(at..end, at + 1);
            kept[at] = (d, i);
            len = (len + 1).min(MIX_CANDIDATES);
        }
    }
    let near = &kept[..len];
    let Some(&(first, a)) = near.first() else {
        return Mix {
            a: 0,
            b: 0,
            level: 0,
        };
    };
    let lin = |c: Rgb| glam::Vec3::from(Lin::from_srgb(c).to_f32());
    let target = lin(c);
    let mut best = (first, Mix { a, b: a, level: 0 });
    for (k, &(_, i)) in near.iter().enumerate() {
        let (ei, from) = (entries()[i as usize], lin(xterm256(i)));
        for &(_, j) in &near[k + 1..] {
            let ej = entries()[j as usize];
            let spread = distance_to(metric, xterm256(i), ei.lab, ei.chroma, xterm256(j), ej.lab);
            let d = lin(xterm256(j)) - from;
            // The level whose blend is nearest in linear light, and its
            // neighbours, judged by the metric.
            let t = ((target - from).dot(d) / d.length_squared()).clamp(0.0, 1.0);
            let centre = (t * 16.0).round() as i32;
            for level in (centre - 1).max(1)..=(centre + 1).min(15) {
                let blend = from + d * (level as f32 / 16.0);
                let shown = Lin::from_f32(blend.to_array()).to_srgb();
                let err = distance_to(metric, c, p, cp, shown, lab(shown)) + MIX_SPREAD * spread;
                if err < best.0 {
                    let level = level as u8;
                    best = (err, Mix { a: i, b: j, level });
                }
            }
        }
    }
    best.1
}

/// The 4×4 Bayer matrix: cell `(x, y)` shows the second colour of a mix
/// at `level` when `level > BAYER[y % 4][x % 4]`.
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
    cache: Vec<(u32, Mix)>,
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
        }
    }

    /// The same, dithering as `dither` says.
    pub fn with_dither(mut self, dither: Dither) -> Quantizer {
        self.dither = dither.resolve(self.depth);
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

    /// The ink for a colour (`None`: the terminal's default), undithered.
    pub fn ink(&mut self, c: Option<Rgb>) -> Ink {
        self.ink_at(c, 0, 0)
    }

    /// The ink for a colour in the cell at column `x`, row `y` (where the
    /// dithering pattern is anchored).
    #[inline(always)]
    pub fn ink_at(&mut self, c: Option<Rgb>, x: u16, y: u16) -> Ink {
        let Some(c) = c else { return Ink::Default };
        match self.depth {
            ColorDepth::None => Ink::Default,
            ColorDepth::TrueColor => Ink::Rgb(c),
            depth => self.palette_ink(depth, c, x, y),
        }
    }

    /// [`Quantizer::ink_at`] for a palette: out of line, so that the
    /// truecolor case inlines to a copy.
    #[inline(never)]
    fn palette_ink(&mut self, depth: ColorDepth, c: Rgb, x: u16, y: u16) -> Ink {
        if self.cache.is_empty() {
            let empty = Mix {
                a: 0,
                b: 0,
                level: 0,
            };
            self.cache = vec![(0, empty); 1 << CACHE_BITS];
        }
        let [r, g, b] = c.0;
        let key = (r as u32) << 16 | (g as u32) << 8 | b as u32;
        let slot = (key.wrapping_mul(0x9E37_79B1) >> (32 - CACHE_BITS)) as usize;
        let (k, cached) = self.cache[slot];
        let m = if k == key | VALID {
            cached
        } else {
            let m = if self.dither == Dither::Ordered {
                mix(depth, self.metric, c)
            } else {
                let a = nearest(depth, self.metric, c);
                Mix { a, b: a, level: 0 }
            };
            self.cache[slot] = (key | VALID, m);
            m
        };
        let second = m.level > BAYER[(y % 4) as usize][(x % 4) as usize];
        Ink::Indexed(if second { m.b } else { m.a })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
        for metric in Metric::ALL {
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
        // Dithered too: every mix of a grey is of greys.
        for v in 0..=255u8 {
            let m = mix(ColorDepth::Ansi16, Metric::Oklch, Rgb([v, v, v]));
            assert!(
                [0, 7, 8, 15].contains(&m.a) && [0, 7, 8, 15].contains(&m.b),
                "{v}"
            );
        }
        // Plain OKLab sends some greys to cyan (6).
        let oklab: std::collections::BTreeSet<u8> = (0..=255u8)
            .map(|v| nearest(ColorDepth::Ansi16, Metric::Oklab, Rgb([v, v, v])))
            .collect();
        assert!(oklab.contains(&6), "{oklab:?}");
    }

    #[test]
    fn a_palette_colour_is_never_dithered_and_a_mix_is_of_neighbours() {
        for i in 0..16u8 {
            let m = mix(ColorDepth::Ansi16, Metric::Oklch, ANSI16[i as usize]);
            assert_eq!((m.a, m.level), (i, 0));
        }
        // Mid grey between 8 (127) and 7 (229): a pattern of the two.
        let m = mix(ColorDepth::Ansi16, Metric::Oklch, Rgb([190, 190, 190]));
        assert_eq!([m.a.min(m.b), m.a.max(m.b)], [7, 8]);
        assert!(m.level > 0 && m.level < 16);
    }

    #[test]
    fn the_pattern_is_anchored_to_the_screen() {
        let grey = Rgb([190, 190, 190]);
        let c = Some(grey);
        let mut q = Quantizer::new(ColorDepth::Ansi16, Metric::Oklch).with_dither(Dither::Ordered);
        let m = mix(ColorDepth::Ansi16, Metric::Oklch, grey);
        let second = (0..16u16)
            .filter(|&k| q.ink_at(c, k % 4, k / 4) == Ink::Indexed(m.b))
            .count();
        // Of the 16 cells of the matrix, `level` show the second entry, and
        // the same cell always shows the same.
        assert_eq!(second, m.level as usize);
        assert_eq!(q.ink_at(c, 5, 9), q.ink_at(c, 1, 1));
    }

    #[test]
    fn quantizer_caches_without_changing_answers() {
        let mut q = Quantizer::new(ColorDepth::Ansi256, Metric::Oklab);
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
