//! Textures: an image as linear-light texels with its mipmaps, and the
//! sampler that reads it.
//!
//! **Colour.** Images are sRGB-encoded (as glTF says of a base colour
//! texture, and as PNG and JPEG files are); texels are decoded once, at
//! load, to linear light in [0, 1] (f32), so that filtering averages light
//! and a texel multiplies a lit colour like any other factor. A texel of
//! full white is exactly 1.0: a white texture leaves every colour as it was,
//! bit for bit (the planner relies on it: see [`crate::Plan`]).
//!
//! **Mipmaps** are built at load by halving each side (a box filter of
//! exact fractional coverage, so sides that are not powers of two lose
//! nothing) down to 1×1: a third more memory. An image larger than
//! [`MAX_SIDE`] on a side is reduced the same way until it fits, so a
//! texture never takes more than about 67 MB; a terminal's sample grid
//! would read no finer level anyway.
//!
//! **Sampling.** `u` runs to the right and `v` down the image, texel
//! centres at `(i + ½)/W` (glTF's convention; OBJ's `v` runs up and its
//! loader flips it). Wrap modes are repeat, mirrored repeat and clamp to
//! edge. The level of detail is `λ = log2 ρ`, `ρ` the longer of the two
//! texel-space steps from one sample to the next (the UV derivatives
//! along x and y, which the renderer computes exactly from the
//! perspective-correct plane equations): `λ ≤ 0` magnifies (the `mag`
//! filter on level 0), `λ > 0` minifies (the `min` filter, on level 0, the
//! nearest level, or a blend of the two around `λ`). A terminal's sample
//! grid is coarse, so minification is the common case: nearest sampling
//! of a textured floor shimmers and aliases, trilinear averages what each
//! sample covers (`rastty bench` measures both against a supersampled
//! reference).
//!
//! Trade-offs: isotropic filtering (one `ρ`, the longer step) blurs
//! surfaces seen at a grazing angle, where anisotropic filtering would not;
//! alpha is read and ignored (no blending: a surface is opaque).

use crate::choice::Choice;
use std::fmt;
use std::str::FromStr;

use glam::{Vec2, Vec3};

use crate::color::srgb;

/// The largest side of a texture's finest level: larger images are halved
/// at load until they fit.
pub const MAX_SIDE: u32 = 2048;

/// A pixel of 8-bit sRGB `channels` (grey, grey and alpha, RGB, RGBA) as
/// a linear texel: alpha ignored.
pub fn srgb_texel(channels: usize) -> impl Fn(&[u8]) -> [f32; 3] {
    let decode = |v: u8| f32::from(srgb::DECODE[v as usize]) / 65535.0;
    move |p: &[u8]| match channels {
        1 | 2 => [decode(p[0]); 3],
        _ => [decode(p[0]), decode(p[1]), decode(p[2])],
    }
}

/// What a coordinate outside [0, 1] reads.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Wrap {
    /// The image repeats.
    #[default]
    Repeat,
    /// The image repeats, every other copy mirrored.
    MirroredRepeat,
    /// The edge texel continues.
    ClampToEdge,
}

/// How texels are combined within one level.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Filter {
    /// The texel the sample falls in.
    Nearest,
    /// The four texels around the sample, weighted by distance.
    #[default]
    Linear,
}

/// How mipmap levels are chosen when minifying.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Mipmap {
    /// The finest level only.
    None,
    /// The level nearest the level of detail.
    Nearest,
    /// The two levels around the level of detail, blended.
    #[default]
    Linear,
}

/// How a texture is read: glTF's sampler.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Sampler {
    /// Wrapping along `u`.
    pub wrap_u: Wrap,
    /// Wrapping along `v`.
    pub wrap_v: Wrap,
    /// The filter when magnifying.
    pub mag: Filter,
    /// The filter within a level when minifying.
    pub min: Filter,
    /// The levels read when minifying.
    pub mipmap: Mipmap,
}

/// The filtering `--filter` forces on every texture (wrap modes stay the
/// file's).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FilterMode {
    /// The nearest texel of the finest level.
    Nearest,
    /// Four texels of the finest level.
    Bilinear,
    /// Four texels of each of the two levels around the level of detail.
    Trilinear,
}

crate::choice::choice!(FilterMode {
    Nearest => "nearest": "The nearest texel of the finest level",
    Bilinear => "bilinear": "Four texels of the finest level",
    Trilinear => "trilinear": "Four texels of each of the two levels around the level of detail",
});

impl FilterMode {
    /// `sampler` filtered this way.
    pub fn apply(self, sampler: Sampler) -> Sampler {
        let (filter, mipmap) = match self {
            FilterMode::Nearest => (Filter::Nearest, Mipmap::None),
            FilterMode::Bilinear => (Filter::Linear, Mipmap::None),
            FilterMode::Trilinear => (Filter::Linear, Mipmap::Linear),
        };
        Sampler {
            mag: filter,
            min: filter,
            mipmap,
            ..sampler
        }
    }
}

impl fmt::Display for FilterMode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for FilterMode {
    type Err = String;

    fn from_str(s: &str) -> Result<FilterMode, String> {
        FilterMode::named(s)
            .ok_or_else(|| format!("unknown filter {s:?} (nearest, bilinear or trilinear)"))
    }
}

/// One mipmap level: linear texels in [0, 1], row by row from the top.
#[derive(Clone, Debug, PartialEq)]
struct Level {
    width: u32,
    height: u32,
    texels: Vec<[f32; 3]>,
}

impl Level {
    #[inline]
    fn texel(&self, x: usize, y: usize) -> Vec3 {
        Vec3::from(self.texels[y * self.width as usize + x])
    }
}

/// An image ready to sample: linear texels and their mipmaps, and the
/// sampler its file gave it.
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    /// Where it came from, for messages.
    pub name: String,
    /// How the file says to read it.
    pub sampler: Sampler,
    levels: Vec<Level>,
    /// The image's size before it was reduced to fit [`MAX_SIDE`].
    original: (u32, u32),
}

impl Texture {
    /// A texture from 8-bit sRGB pixels, `channels` a pixel (1: grey, 2:
    /// grey and alpha, 3: RGB, 4: RGBA; alpha is ignored), row by row from
    /// the top. An error names what does not fit.
    pub fn from_srgb8(
        name: impl Into<String>,
        width: u32,
        height: u32,
        channels: usize,
        pixels: &[u8],
        sampler: Sampler,
    ) -> Result<Texture, String> {
        Texture::from_pixels(
            name,
            (width, height, channels),
            pixels,
            sampler,
            srgb_texel(channels),
            MAX_SIDE,
        )
    }

    /// A texture from 8-bit pixels of `channels` each (`size` is width,
    /// height and channels), row by row from the top, each pixel made a
    /// linear texel by `texel`, its finest level at most `max_side` on a
    /// side (at least 1): a larger image is halved as its rows are read,
    /// so the whole image is never held as texels (12 bytes each), the
    /// same texels as converting first and halving after. An error names
    /// what does not fit.
    pub fn from_pixels(
        name: impl Into<String>,
        (width, height, channels): (u32, u32, usize),
        pixels: &[u8],
        sampler: Sampler,
        texel: impl Fn(&[u8]) -> [f32; 3],
        max_side: u32,
    ) -> Result<Texture, String> {
        let name = name.into();
        let max_side = max_side.max(1);
        if width == 0 || height == 0 {
            return Err(format!("{name}: the image is empty ({width}×{height})"));
        }
        if !(1..=4).contains(&channels) {
            return Err(format!("{name}: {channels} channels a pixel"));
        }
        let n = width as usize * height as usize;
        if pixels.len() != n * channels {
            return Err(format!(
                "{name}: {} bytes for {width}×{height} pixels of {channels} channels",
                pixels.len()
            ));
        }
        let row = |y: usize, out: &mut Vec<[f32; 3]>| {
            let w = width as usize * channels;
            out.clear();
            out.extend(
                pixels[y * w..(y + 1) * w]
                    .chunks_exact(channels)
                    .map(&texel),
            );
        };
        let first = if width > max_side || height > max_side {
            Level::halve(width as usize, height as usize, row)
        } else {
            let mut texels = Vec::with_capacity(n);
            let mut line = Vec::with_capacity(width as usize);
            for y in 0..height as usize {
                row(y, &mut line);
                texels.extend_from_slice(&line);
            }
            Level {
                width,
                height,
                texels,
            }
        };
        let mut texture = Texture::from_level(name, first, sampler, max_side);
        texture.original = (width, height);
        Ok(texture)
    }

    /// A texture from linear texels in [0, 1], row by row from the top.
    ///
    /// # Panics
    /// If `texels` is not `width × height` long or a side is zero.
    pub fn from_linear(
        name: impl Into<String>,
        width: u32,
        height: u32,
        texels: Vec<[f32; 3]>,
        sampler: Sampler,
    ) -> Texture {
        assert!(width > 0 && height > 0, "an empty texture");
        assert_eq!(texels.len(), width as usize * height as usize);
        Texture::from_level(
            name.into(),
            Level {
                width,
                height,
                texels,
            },
            sampler,
            MAX_SIDE,
        )
    }

    fn from_level(name: String, mut first: Level, sampler: Sampler, max_side: u32) -> Texture {
        let original = (first.width, first.height);
        while first.width > max_side || first.height > max_side {
            first = first.halved();
        }
        let mut levels = vec![first];
        while let Some(last) = levels.last()
            && (last.width > 1 || last.height > 1)
        {
            let next = last.halved();
            levels.push(next);
        }
        Texture {
            name,
            sampler,
            levels,
            original,
        }
    }

    /// The finest level's size.
    pub fn size(&self) -> (u32, u32) {
        (self.levels[0].width, self.levels[0].height)
    }

    /// The image's size as it was read, before any reduction to fit
    /// [`MAX_SIDE`].
    pub fn original_size(&self) -> (u32, u32) {
        self.original
    }

    /// How many mipmap levels it has (1 for a 1×1 texture).
    pub fn levels(&self) -> usize {
        self.levels.len()
    }

    /// A 1×1 texture of full white (1.0 exactly): what the full pipeline
    /// reads for triangles without a texture, changing nothing.
    pub fn white() -> &'static Texture {
        static WHITE: std::sync::LazyLock<Texture> = std::sync::LazyLock::new(|| {
            Texture::from_linear("white", 1, 1, vec![[1.0; 3]], Sampler::default())
        });
        &WHITE
    }

    /// Texel `(x, y)` of level `level`, linear in [0, 1].
    ///
    /// # Panics
    /// If the level or texel does not exist.
    pub fn texel(&self, level: usize, x: u32, y: u32) -> Vec3 {
        let l = &self.levels[level];
        assert!(x < l.width && y < l.height, "no texel ({x}, {y})");
        l.texel(x as usize, y as usize)
    }

    /// The texture's colour at `uv`, linear in [0, 1], read with `s`; `dx`
    /// and `dy` are how far `uv` moves from one sample to the next along x
    /// and y (they choose between magnifying and minifying, and the
    /// mipmap level).
    #[inline]
    pub fn sample(&self, s: &Sampler, uv: Vec2, dx: Vec2, dy: Vec2) -> Vec3 {
        let lod = self.lod(dx, dy);
        // NaN or ≤ 0: magnified.
        if lod.is_nan() || lod <= 0.0 {
            return self.filtered(0, s.mag, s, uv);
        }
        let last = self.levels.len() - 1;
        match s.mipmap {
            Mipmap::None => self.filtered(0, s.min, s, uv),
            Mipmap::Nearest => {
                let level = ((lod + 0.5).floor() as usize).min(last);
                self.filtered(level, s.min, s, uv)
            }
            Mipmap::Linear => {
                let floor = lod.floor();
                let lo = (floor as usize).min(last);
                let hi = (lo + 1).min(last);
                let a = self.filtered(lo, s.min, s, uv);
                if hi == lo {
                    return a;
                }
                let b = self.filtered(hi, s.min, s, uv);
                a + (b - a) * (lod - floor)
            }
        }
    }

    /// The level of detail for these UV steps: log2 of the longer step in
    /// texels of the finest level.
    #[inline]
    pub fn lod(&self, dx: Vec2, dy: Vec2) -> f32 {
        let l = &self.levels[0];
        let size = Vec2::new(l.width as f32, l.height as f32);
        let rho2 = (dx * size)
            .length_squared()
            .max((dy * size).length_squared());
        0.5 * rho2.log2()
    }

    /// One level read with one filter.
    #[inline]
    fn filtered(&self, level: usize, filter: Filter, s: &Sampler, uv: Vec2) -> Vec3 {
        let l = &self.levels[level];
        let (w, h) = (i64::from(l.width), i64::from(l.height));
        let x = uv.x * l.width as f32;
        let y = uv.y * l.height as f32;
        match filter {
            Filter::Nearest => l.texel(wrap(floor(x), w, s.wrap_u), wrap(floor(y), h, s.wrap_v)),
            Filter::Linear => {
                let (x, y) = (x - 0.5, y - 0.5);
                let (x0, y0) = (floor(x), floor(y));
                let (fx, fy) = (fraction(x), fraction(y));
                let (xa, xb) = (
                    wrap(x0, w, s.wrap_u),
                    wrap(x0.saturating_add(1), w, s.wrap_u),
                );
                let (ya, yb) = (
                    wrap(y0, h, s.wrap_v),
                    wrap(y0.saturating_add(1), h, s.wrap_v),
                );
                let top = lerp(l.texel(xa, ya), l.texel(xb, ya), fx);
                let bottom = lerp(l.texel(xa, yb), l.texel(xb, yb), fx);
                lerp(top, bottom, fy)
            }
        }
    }
}

/// `a` to `b` by `t`, exactly `a` when they are equal (so a uniform texture
/// reads back its own value, bit for bit).
#[inline]
fn lerp(a: Vec3, b: Vec3, t: f32) -> Vec3 {
    a + (b - a) * t
}

/// `x − ⌊x⌋`, 0 where that is not a number (`x` infinite or NaN).
#[inline]
fn fraction(x: f32) -> f32 {
    let f = x - x.floor();
    if f.is_nan() { 0.0 } else { f }
}

/// ⌊x⌋ as an integer, saturating; NaN is 0.
#[inline]
fn floor(x: f32) -> i64 {
    x.floor() as i64
}

/// Texel index `i` of a row of `n`, wrapped.
#[inline]
fn wrap(i: i64, n: i64, mode: Wrap) -> usize {
    (match mode {
        Wrap::Repeat => i.rem_euclid(n),
        Wrap::MirroredRepeat => {
            let m = i.rem_euclid(2 * n);
            if m < n { m } else { 2 * n - 1 - m }
        }
        Wrap::ClampToEdge => i.clamp(0, n - 1),
    }) as usize
}

impl Level {
    /// The next mipmap level: each side halved (rounded down, at least 1),
    /// each texel the mean of the texels under it, fractions counted.
    fn halved(&self) -> Level {
        let w = self.width as usize;
        Level::halve(w, self.height as usize, |y, out| {
            out.clear();
            out.extend_from_slice(&self.texels[y * w..(y + 1) * w]);
        })
    }

    /// [`Level::halved`] of a `w`×`h` level whose rows `row(y, out)` makes,
    /// one at a time.
    fn halve(w: usize, h: usize, mut row: impl FnMut(usize, &mut Vec<[f32; 3]>)) -> Level {
        let (nw, nh) = ((w / 2).max(1), (h / 2).max(1));
        // Along x, then along y.
        let mut rows = vec![[0.0f32; 3]; nw * h];
        let mut line = Vec::with_capacity(w);
        for y in 0..h {
            row(y, &mut line);
            resample(&line, 1, &mut rows[y * nw..(y + 1) * nw], 1);
        }
        let mut texels = vec![[0.0f32; 3]; nw * nh];
        for x in 0..nw {
            resample(&rows[x..], nw, &mut texels[x..], nw);
        }
        Level {
            width: nw as u32,
            height: nh as u32,
            texels,
        }
    }
}

/// Box-filters a line of texels (every `step`-th of `src`, `n` of them
/// where `src` holds them) onto a shorter one (every `step`-th of `dst`):
/// output `i` is the mean over source texels `[i·n/m, (i+1)·n/m)`, partial
/// texels weighted by the part covered.
fn resample(src: &[[f32; 3]], src_step: usize, dst: &mut [[f32; 3]], dst_step: usize) {
    let n = src.len().div_ceil(src_step);
    let m = dst.len().div_ceil(dst_step);
    if m == n {
        for i in 0..m {
            dst[i * dst_step] = src[i * src_step];
        }
        return;
    }
    let ratio = n as f64 / m as f64;
    for i in 0..m {
        let (a, b) = (i as f64 * ratio, (i + 1) as f64 * ratio);
        let mut sum = [0.0f64; 3];
        let mut j = a.floor() as usize;
        while (j as f64) < b && j < n {
            let cover = (b.min(j as f64 + 1.0) - a.max(j as f64)).max(0.0);
            let t = src[j * src_step];
            for k in 0..3 {
                sum[k] += f64::from(t[k]) * cover;
            }
            j += 1;
        }
        dst[i * dst_step] = sum.map(|s| (s / ratio) as f32);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gray(w: u32, h: u32, values: &[f32]) -> Texture {
        Texture::from_linear(
            "t",
            w,
            h,
            values.iter().map(|&v| [v; 3]).collect(),
            Sampler::default(),
        )
    }

    #[test]
    fn mipmaps_average_exactly_down_to_one_texel() {
        let t = gray(4, 2, &[0.0, 1.0, 0.5, 0.5, 1.0, 0.0, 0.25, 0.75]);
        assert_eq!(t.levels(), 3);
        assert_eq!(t.texel(1, 0, 0).x, 0.5);
        assert_eq!(t.texel(1, 1, 0).x, 0.5);
        assert_eq!(t.texel(2, 0, 0).x, 0.5);
        // Three texels onto one: each counts a third.
        let t = gray(3, 1, &[0.0, 0.3, 0.9]);
        assert_eq!(t.levels(), 2);
        assert!((t.texel(1, 0, 0).x - 0.4).abs() < 1e-7);
    }

    #[test]
    fn wrap_modes_fold_indices_as_the_spec_says() {
        let r: Vec<usize> = (-3..6).map(|i| wrap(i, 3, Wrap::Repeat)).collect();
        assert_eq!(r, [0, 1, 2, 0, 1, 2, 0, 1, 2]);
        let m: Vec<usize> = (-3..6).map(|i| wrap(i, 3, Wrap::MirroredRepeat)).collect();
        assert_eq!(m, [2, 1, 0, 0, 1, 2, 2, 1, 0]);
        let c: Vec<usize> = (-3..6).map(|i| wrap(i, 3, Wrap::ClampToEdge)).collect();
        assert_eq!(c, [0, 0, 0, 0, 1, 2, 2, 2, 2]);
        // Far out, and NaN, still inside.
        assert_eq!(wrap(floor(1e30), 3, Wrap::Repeat), (i64::MAX % 3) as usize);
        assert_eq!(wrap(floor(f32::NAN), 3, Wrap::ClampToEdge), 0);
    }

    proptest::proptest! {
        /// Any coordinates and steps, finite or not, read a colour between
        /// the darkest and lightest texel, whatever the sampler.
        #[test]
        fn sampling_stays_within_the_texels(
            uv in proptest::array::uniform2(proptest::num::f32::ANY),
            dx in proptest::array::uniform2(proptest::num::f32::ANY),
            dy in proptest::array::uniform2(proptest::num::f32::ANY),
            wrap in 0usize..3,
            mode in 0usize..3,
        ) {
            let t = gray(3, 2, &[0.25, 0.5, 0.75, 0.3, 0.6, 0.7]);
            let wrap = [Wrap::Repeat, Wrap::MirroredRepeat, Wrap::ClampToEdge][wrap];
            let s = FilterMode::ALL[mode].apply(Sampler { wrap_u: wrap, wrap_v: wrap, ..Sampler::default() });
            let c = t.sample(&s, Vec2::from(uv), Vec2::from(dx), Vec2::from(dy));
            proptest::prop_assert!((0.25..=0.75).contains(&c.x), "{c}");
        }
    }

    #[test]
    fn a_large_image_is_halved_to_fit() {
        let t = gray(MAX_SIDE * 2 + 1, 1, &vec![0.5; (MAX_SIDE * 2 + 1) as usize]);
        assert_eq!(t.size(), (MAX_SIDE, 1));
        assert_eq!(t.original_size(), (MAX_SIDE * 2 + 1, 1));
        assert_eq!(t.texel(0, 7, 0).x, 0.5);
    }

    #[test]
    fn a_large_srgb_image_halved_as_it_is_read_equals_converting_first() {
        // 2·MAX_SIDE + 3 by 5, odd both ways, three channels of varied bytes.
        let (w, h) = (MAX_SIDE * 2 + 3, 5);
        let pixels: Vec<u8> = (0..w * h * 3).map(|i| (i * 37 % 251) as u8).collect();
        let read = Texture::from_srgb8("t", w, h, 3, &pixels, Sampler::default()).unwrap();
        let decode = |v: u8| f32::from(srgb::DECODE[v as usize]) / 65535.0;
        let linear = pixels
            .chunks_exact(3)
            .map(|p| [decode(p[0]), decode(p[1]), decode(p[2])])
            .collect();
        let first = Texture::from_linear("t", w, h, linear, Sampler::default());
        assert_eq!(read.original_size(), (w, h));
        assert_eq!(read.levels.len(), first.levels.len());
        for (a, b) in read.levels.iter().zip(&first.levels) {
            assert_eq!((a.width, a.height), (b.width, b.height));
            assert!(
                a.texels
                    .iter()
                    .zip(&b.texels)
                    .all(|(x, y)| x.map(f32::to_bits) == y.map(f32::to_bits))
            );
        }
    }

    #[test]
    fn an_image_kept_to_a_smaller_side_is_the_full_texture_from_that_level_on() {
        // 37×23 bytes of RGB, kept to 8 texels a side: its levels are the
        // full texture's from the first that fits (9×5 halved once more is
        // not; 37→18→9→4: level 3, 4×2), texel for texel, to 1×1.
        let (w, h) = (37u32, 23u32);
        let pixels: Vec<u8> = (0..w * h * 3).map(|i| (i * 37 % 251) as u8).collect();
        let make = |side| {
            Texture::from_pixels(
                "t",
                (w, h, 3),
                &pixels,
                Sampler::default(),
                srgb_texel(3),
                side,
            )
            .unwrap()
        };
        let (full, kept) = (make(MAX_SIDE), make(8));
        assert_eq!(kept.size(), (4, 2));
        assert_eq!(kept.original_size(), (w, h));
        assert_eq!(kept.levels(), full.levels() - 3);
        for level in 0..kept.levels() {
            let l = &kept.levels[level];
            let f = &full.levels[level + 3];
            assert_eq!((l.width, l.height), (f.width, f.height));
            assert!(
                l.texels
                    .iter()
                    .zip(&f.texels)
                    .all(|(a, b)| a.map(f32::to_bits) == b.map(f32::to_bits))
            );
        }
    }
}
