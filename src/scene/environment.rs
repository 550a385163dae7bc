//! Light from an environment: what a metal reflects. A metal has no
//! diffuse colour, so lit by a few lights alone it is black but for their
//! highlights; in common viewers it mirrors a studio around it. A scene's
//! [`Environment`] is that studio (the default, [`Environment::Studio`]:
//! a neutral grey room, brighter above, with three soft boxes), an
//! equirectangular image of one (a Radiance `.hdr` file, through the image
//! crate), or none.
//!
//! Reflected as the split sum does (Karis, "Real Shading in Unreal Engine
//! 4", 2013): the environment's radiance around the reflected direction,
//! prefiltered once for a few roughnesses by the GGX lobe ([`EnvMap`]),
//! times the lobe's integral over the hemisphere as a scale and bias of the
//! reflectance, from Karis' analytic fit for mobile ("Physically Based
//! Shading on Mobile", 2014). [`crate::reflection_reference`] is the same
//! integral in f64, quadrature over the whole sphere with the renderer's
//! own lobe; the tests hold the two together.
//!
//! Trade-offs. Only metals reflect the environment (a material's metallic
//! share, [`crate::scene::Specular::metallic`]): a dielectric's reflection
//! of a grey room is a few per cent of it but at grazing angles, and its
//! highlights are the lights'; leaving it out keeps every scene without a
//! metal drawn as it was, at the cost it was. Reflections are of the
//! environment alone, not of the model (no self-reflection), and the
//! environment is at infinity, turning with the view (a model that spins
//! turns under a fixed studio, as a turntable does). The maps are small
//! (64×32 texels at the sharpest, 32×16 for rough lobes): a terminal cell
//! of a reflection covers several degrees of it.

use std::sync::{Arc, OnceLock};

use glam::{DVec3, Vec3, Vec3A};

/// What a scene's metals reflect.
#[derive(Clone, Debug, Default)]
pub enum Environment {
    /// Nothing: metals are lit by the lights alone.
    None,
    /// A neutral studio ([`studio_radiance`]), prefiltered once a process.
    #[default]
    Studio,
    /// An equirectangular image, prefiltered when read.
    Map(Arc<EnvMap>),
}

impl PartialEq for Environment {
    fn eq(&self, other: &Environment) -> bool {
        match (self, other) {
            (Environment::None, Environment::None) => true,
            (Environment::Studio, Environment::Studio) => true,
            (Environment::Map(a), Environment::Map(b)) => Arc::ptr_eq(a, b),
            _ => false,
        }
    }
}

impl Environment {
    /// Whether there is one (without making the studio's maps).
    pub fn is_some(&self) -> bool {
        !matches!(self, Environment::None)
    }

    /// Its prefiltered maps (`None` for no environment): the studio's are
    /// made the first time they are asked for.
    pub fn maps(&self) -> Option<&EnvMap> {
        match self {
            Environment::None => None,
            Environment::Studio => Some(studio()),
            Environment::Map(m) => Some(m),
        }
    }
}

/// The roughnesses the maps are prefiltered for: 0, 0.2, …, 1.
pub const LEVELS: usize = 6;
/// The sharpest map's size (the environment itself, resampled).
const SHARP: [usize; 2] = [64, 32];
/// The rougher maps' size.
const ROUGH: [usize; 2] = [32, 16];

/// An environment prefiltered for [`LEVELS`] roughnesses, each an
/// equirectangular map of linear radiance (1 a channel: a white light's
/// radiance), `+y` up, the middle column looking down `−z`.
#[derive(Clone, Debug)]
pub struct EnvMap {
    levels: Vec<Level>,
}

#[derive(Clone, Debug)]
struct Level {
    w: usize,
    h: usize,
    texels: Vec<Vec3A>,
}

/// The direction through the middle of texel (`x`, `y`) of a `w × h` map.
pub(crate) fn direction(x: f64, y: f64, w: usize, h: usize) -> DVec3 {
    let phi = (x / w as f64 - 0.5) * std::f64::consts::TAU;
    let theta = y / h as f64 * std::f64::consts::PI;
    DVec3::new(
        theta.sin() * phi.sin(),
        theta.cos(),
        -theta.sin() * phi.cos(),
    )
}

/// The neutral studio's radiance towards direction `d` (unit): a room
/// brighter above than below, a key soft box above and left of the front,
/// a fill to the right, and a rim behind.
pub fn studio_radiance(d: DVec3) -> f64 {
    let smooth = |e0: f64, e1: f64, x: f64| {
        let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
        t * t * (3.0 - 2.0 * t)
    };
    let room = 0.12 + 0.5 * smooth(-0.15, 0.7, d.y);
    let softbox = |towards: DVec3, radius_deg: f64, power: f64| {
        let c = d.dot(towards.normalize());
        let edge = radius_deg.to_radians().cos();
        power * smooth(edge - 0.03, edge + 0.03, c)
    };
    room + softbox(DVec3::new(-0.6, 0.7, 0.6), 22.0, 2.5)
        + softbox(DVec3::new(0.8, 0.25, 0.5), 25.0, 1.0)
        + softbox(DVec3::new(0.1, 0.35, -1.0), 18.0, 1.5)
}

/// The studio's maps, made the first time they are asked for.
fn studio() -> &'static EnvMap {
    static STUDIO: OnceLock<EnvMap> = OnceLock::new();
    STUDIO.get_or_init(|| {
        // Each sharp texel the mean of 4×4 points over it.
        let [w, h] = SHARP;
        let texels = (0..w * h)
            .map(|i| {
                let (x, y) = ((i % w) as f64, (i / w) as f64);
                let mut sum = 0.0;
                for k in 0..16 {
                    let (dx, dy) = ((k % 4) as f64 + 0.5, (k / 4) as f64 + 0.5);
                    sum += studio_radiance(direction(x + dx / 4.0, y + dy / 4.0, w, h));
                }
                Vec3A::splat((sum / 16.0) as f32)
            })
            .collect();
        EnvMap::prefiltered(Level { w, h, texels })
    })
}

impl EnvMap {
    /// The maps of an equirectangular image of `w × h` linear RGB texels
    /// (rows from the top), resampled to the sharp map's size by the mean
    /// of the texels over each of its texels.
    pub fn from_equirect(w: usize, h: usize, rgb: &[[f32; 3]]) -> EnvMap {
        let [sw, sh] = SHARP;
        let mut sums = vec![(Vec3A::ZERO, 0u32); sw * sh];
        for (i, c) in rgb.iter().enumerate().take(w * h) {
            let (x, y) = (i % w, i / w);
            let c = Vec3A::from(*c);
            // Non-finite or negative radiance (a damaged file) is dark.
            let c = if c.is_finite() {
                c.max(Vec3A::ZERO)
            } else {
                Vec3A::ZERO
            };
            let at = (y * sh / h.max(1)) * sw + x * sw / w.max(1);
            sums[at].0 += c;
            sums[at].1 += 1;
        }
        let texels = (0..sw * sh)
            .map(|i| {
                // A map smaller than the sharp one: its nearest texel.
                let (s, n) = sums[i];
                if n > 0 {
                    s / n as f32
                } else {
                    let (x, y) = (i % sw, i / sw);
                    let j = (y * h / sh).min(h - 1) * w + (x * w / sw).min(w - 1);
                    rgb.get(j)
                        .map_or(Vec3A::ZERO, |c| Vec3A::from(*c).max(Vec3A::ZERO))
                }
            })
            .collect();
        EnvMap::prefiltered(Level {
            w: sw,
            h: sh,
            texels,
        })
    }

    /// `sharp` as the first level, and the rougher ones convolved with the
    /// GGX lobe about each direction (the split sum's prefilter, with the
    /// normal and the eye along the reflected direction).
    fn prefiltered(sharp: Level) -> EnvMap {
        // The sources: the sharp map, and a half-size one for rough lobes.
        let [rw, rh] = ROUGH;
        let half = Level {
            w: rw,
            h: rh,
            texels: (0..rw * rh)
                .map(|i| {
                    let (x, y) = (i % rw, i / rw);
                    let at = |dx, dy| sharp.texels[(2 * y + dy) * sharp.w + 2 * x + dx];
                    (at(0, 0) + at(1, 0) + at(0, 1) + at(1, 1)) * 0.25
                })
                .collect(),
        };
        let mut levels = vec![sharp];
        for k in 1..LEVELS {
            let roughness = k as f64 / (LEVELS - 1) as f64;
            let source = if k == 1 { &levels[0] } else { &half };
            let texels = convolved(source, roughness, rw, rh);
            levels.push(Level {
                w: rw,
                h: rh,
                texels,
            });
        }
        EnvMap { levels }
    }

    /// The prefiltered radiance about unit direction `r` for a lobe of
    /// `roughness` (perceptual, in [0, 1]): bilinear in each of the two
    /// nearest levels, and between them.
    #[inline]
    pub fn radiance(&self, r: Vec3A, roughness: f32) -> Vec3A {
        let k = (roughness.clamp(0.0, 1.0) * (LEVELS - 1) as f32).min((LEVELS - 1) as f32);
        let lo = (k as usize).min(LEVELS - 2);
        let t = k - lo as f32;
        let (u, v) = equirect(r);
        let a = self.levels[lo].bilinear(u, v);
        let b = self.levels[lo + 1].bilinear(u, v);
        a + (b - a) * t
    }

    /// The light a metal surface of unit normal `n`, seen from unit
    /// direction `v`, of reflectance `f0` and perceptual `roughness`,
    /// reflects of the environment towards the eye (linear, a white
    /// light's radiance 1): the prefiltered radiance about the reflected
    /// direction times the lobe's integral, `f0·A + B`.
    #[inline]
    pub fn reflect(&self, n: Vec3A, v: Vec3A, f0: Vec3A, roughness: f32) -> Vec3A {
        let nv = n.dot(v);
        if nv.is_nan() || nv <= 0.0 {
            return Vec3A::ZERO;
        }
        // The lobe's dominant direction: a rough lobe leans from the
        // mirror direction towards the normal (Lagarde and de Rousiers,
        // "Moving Frostbite to PBR", 2014).
        let mirror = n * (2.0 * nv) - v;
        let a = roughness * roughness;
        let towards_mirror = (1.0 - a) * ((1.0 - a).sqrt() + a);
        let r = (n + (mirror - n) * towards_mirror).normalize_or(mirror);
        let (a, b) = env_brdf(nv, roughness);
        self.radiance(r, roughness) * (f0 * a + Vec3A::splat(b))
    }
}

/// The map coordinates of unit direction `d`: `u` across from the back,
/// `v` down from the top, both in [0, 1].
#[inline]
fn equirect(d: Vec3A) -> (f32, f32) {
    let u = d.x.atan2(-d.z) * (0.5 / std::f32::consts::PI) + 0.5;
    let v = d.y.clamp(-1.0, 1.0).acos() * std::f32::consts::FRAC_1_PI;
    (u, v)
}

impl Level {
    /// Bilinear between texel centres, wrapping across, clamped down.
    #[inline]
    fn bilinear(&self, u: f32, v: f32) -> Vec3A {
        let x = u * self.w as f32 - 0.5;
        let y = (v * self.h as f32 - 0.5).clamp(0.0, (self.h - 1) as f32);
        let (x0, y0) = (x.floor(), y.floor());
        let (tx, ty) = (x - x0, y - y0);
        let wrap = |x: f32| (x as i64).rem_euclid(self.w as i64) as usize;
        let (xa, xb) = (wrap(x0), wrap(x0 + 1.0));
        let (ya, yb) = (y0 as usize, (y0 as usize + 1).min(self.h - 1));
        let at = |x: usize, y: usize| self.texels[y * self.w + x];
        let top = at(xa, ya) + (at(xb, ya) - at(xa, ya)) * tx;
        let bottom = at(xa, yb) + (at(xb, yb) - at(xa, yb)) * tx;
        top + (bottom - top) * ty
    }
}

/// Each texel of a `w × h` map: `source`'s radiance weighted by the GGX
/// lobe of `roughness` about its direction (`D(n·h)·(n·l)` with the normal
/// and the eye along it) and by each source texel's solid angle.
fn convolved(source: &Level, roughness: f64, w: usize, h: usize) -> Vec<Vec3A> {
    let a = roughness * roughness;
    let a2 = a * a;
    let dirs: Vec<(DVec3, f64)> = (0..source.w * source.h)
        .map(|i| {
            let (x, y) = ((i % source.w) as f64 + 0.5, (i / source.w) as f64 + 0.5);
            let d = direction(x, y, source.w, source.h);
            let solid = (y / source.h as f64 * std::f64::consts::PI).sin();
            (d, solid)
        })
        .collect();
    (0..w * h)
        .map(|i| {
            let n = direction((i % w) as f64 + 0.5, (i / w) as f64 + 0.5, w, h);
            let (mut sum, mut total) = (glam::DVec3::ZERO, 0.0);
            for (j, &(l, solid)) in dirs.iter().enumerate() {
                let nl = n.dot(l);
                if nl <= 0.0 {
                    continue;
                }
                let nh = (n + l).normalize_or_zero().dot(n);
                let k = nh * nh * (a2 - 1.0) + 1.0;
                let weight = a2 / (k * k) * nl * solid;
                sum += source.texels[j].as_dvec3() * weight;
                total += weight;
            }
            if total > 0.0 {
                (sum / total).as_vec3().into()
            } else {
                Vec3A::ZERO
            }
        })
        .collect()
}

/// The split sum's scale and bias of the reflectance, `(A, B)`: the GGX
/// lobe's integral over the hemisphere is `f0·A + B`, for the renderer's
/// own lobe (GGX, Smith's height-correlated visibility, Schlick's
/// Fresnel), tabulated once over `n·v` and roughness ([`dfg`]) and read
/// bilinearly.
#[inline]
fn env_brdf(nv: f32, roughness: f32) -> (f32, f32) {
    let table = dfg();
    let x = (nv.clamp(0.0, 1.0) * (DFG - 1) as f32).min((DFG - 1) as f32);
    let y = (roughness.clamp(0.0, 1.0) * (DFG - 1) as f32).min((DFG - 1) as f32);
    let (x0, y0) = ((x as usize).min(DFG - 2), (y as usize).min(DFG - 2));
    let (tx, ty) = (x - x0 as f32, y - y0 as f32);
    let at = |x: usize, y: usize| table[y * DFG + x];
    let lerp =
        |a: [f32; 2], b: [f32; 2], t: f32| [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t];
    let top = lerp(at(x0, y0), at(x0 + 1, y0), tx);
    let bottom = lerp(at(x0, y0 + 1), at(x0 + 1, y0 + 1), tx);
    let [a, b] = lerp(top, bottom, ty);
    (a, b)
}

/// The table's side: `n·v` and roughness each from 0 to 1 in this many
/// steps.
const DFG: usize = 32;

/// `(A, B)` at each `n·v` and roughness of the table, by importance
/// sampling the GGX distribution (256 Hammersley points an entry, in
/// f64): the estimator of `∫ f·(n·l)` is `4·V·(n·l)·(v·h) / (n·h)` with
/// `F = f0 + (1 − f0)·(1 − v·h)⁵`.
fn dfg() -> &'static [[f32; 2]] {
    static TABLE: OnceLock<Vec<[f32; 2]>> = OnceLock::new();
    TABLE.get_or_init(|| {
        const N: u32 = 256;
        (0..DFG * DFG)
            .map(|i| {
                let nv = ((i % DFG) as f64 / (DFG - 1) as f64).max(1e-3);
                let roughness = ((i / DFG) as f64 / (DFG - 1) as f64)
                    .max(f64::from(crate::scene::Specular::MIN_ROUGHNESS));
                let a = roughness * roughness;
                let a2 = a * a;
                let v = DVec3::new((1.0 - nv * nv).sqrt(), 0.0, nv);
                let (mut sa, mut sb) = (0.0, 0.0);
                for k in 0..N {
                    let (u1, u2) = (
                        (f64::from(k) + 0.5) / f64::from(N),
                        f64::from(k.reverse_bits()) / 2f64.powi(32),
                    );
                    // h from D·(n·h): cos²θ = (1 − u) / (1 + (a² − 1)·u).
                    let cos2 = (1.0 - u1) / (1.0 + (a2 - 1.0) * u1);
                    let (cos, sin) = (cos2.sqrt(), (1.0 - cos2).max(0.0).sqrt());
                    let phi = std::f64::consts::TAU * u2;
                    let h = DVec3::new(sin * phi.cos(), sin * phi.sin(), cos);
                    let vh = v.dot(h);
                    let l = h * (2.0 * vh) - v;
                    let (nl, nh) = (l.z, h.z);
                    if nl <= 0.0 || vh <= 0.0 {
                        continue;
                    }
                    let vis = 0.5
                        / (nl * (nv * nv * (1.0 - a2) + a2).sqrt()
                            + nv * (nl * nl * (1.0 - a2) + a2).sqrt());
                    let g = 4.0 * vis * nl * vh / nh;
                    let fc = (1.0 - vh).powi(5);
                    sa += (1.0 - fc) * g;
                    sb += fc * g;
                }
                [(sa / f64::from(N)) as f32, (sb / f64::from(N)) as f32]
            })
            .collect()
    })
}

impl From<Vec3> for Environment {
    /// A uniform environment of radiance `c` everywhere (tests, and
    /// scenes that want a flat reflection).
    fn from(c: Vec3) -> Environment {
        let c = Vec3A::from(c.max(Vec3::ZERO));
        let [w, h] = SHARP;
        Environment::Map(Arc::new(EnvMap::prefiltered(Level {
            w,
            h,
            texels: vec![c; w * h],
        })))
    }
}

/// An environment read from an equirectangular Radiance `.hdr` file
/// (linear radiance, as the format stores it), opened with the model's
/// checks and decoded only where its texels fit `options.max_texels`; and
/// the file, for the scene's sources.
#[cfg(feature = "textures")]
pub fn load(
    path: &std::path::Path,
    options: &crate::scene::LoadOptions,
) -> crate::error::Result<(Environment, crate::scene::Source)> {
    use image::ImageDecoder as _;
    let bad = |what: String| crate::error::Error::Invalid(format!("{}: {what}", path.display()));
    let file = crate::scene::file::open(path, options.max_bytes)?;
    let source = crate::scene::Source {
        path: path.to_path_buf(),
        id: file.id().clone(),
    };
    let decoder = image::codecs::hdr::HdrDecoder::new(std::io::BufReader::new(file))
        .map_err(|e| bad(format!("not a Radiance HDR image: {e}")))?;
    let (w, h) = decoder.dimensions();
    let texels = u64::from(w) * u64::from(h);
    if texels > options.max_texels {
        return Err(bad(format!(
            "{w}×{h} texels, more than the budget of {} (--max-texels raises it)",
            options.max_texels
        )));
    }
    if w == 0 || h == 0 {
        return Err(bad("an image of no texels".into()));
    }
    let mut bytes = vec![0u8; decoder.total_bytes() as usize];
    decoder
        .read_image(&mut bytes)
        .map_err(|e| bad(format!("not a Radiance HDR image: {e}")))?;
    let rgb: Vec<[f32; 3]> = bytes
        .chunks_exact(12)
        .map(|c| {
            let f = |i: usize| f32::from_ne_bytes([c[i], c[i + 1], c[i + 2], c[i + 3]]);
            [f(0), f(4), f(8)]
        })
        .collect();
    let map = EnvMap::from_equirect(w as usize, h as usize, &rgb);
    Ok((Environment::Map(Arc::new(map)), source))
}
