//! Sheen (glTF's `KHR_materials_sheen`): the light cloth's fibres scatter
//! back at grazing angles. The lobe is the spec's: the "Charlie"
//! distribution (Estevez and Kulla, "Production Friendly Microfacet Sheen
//! BRDF", 2017), `D = (2 + 1/α)·sin(θh)^(1/α) / 2π`, with their fitted
//! visibility `1 / ((1 + Λ(n·v) + Λ(n·l))·4·(n·v)·(n·l))`, α the sheen
//! roughness squared. What is beneath is dimmed by the sheen's directional
//! albedo `E(n·v)` (the lobe integrated over the hemisphere), tabulated
//! once a process from the same f64 lobe ([`sheen_reference`]).
//!
//! Trade-offs. The visibility's fit costs two `exp` and two `powf` a light
//! a sample: paid on sheen runs alone (the plan's `sheen` decision). The
//! albedo table is 16 × 16 entries read bilinearly, within 0.01 of the
//! integral between its nodes (tested).

use std::sync::OnceLock;

use glam::Vec3A;

use super::Lights;

/// The spec's fit of Λ's exponent for `x` = cos θ and α.
#[inline]
fn lambda_fit(x: f32, alpha: f32) -> f32 {
    let t = (1.0 - alpha) * (1.0 - alpha);
    let mix = |a: f32, b: f32| a + (b - a) * t;
    let a = mix(21.5473, 25.3245);
    let b = mix(3.82987, 3.32435);
    let c = mix(0.19823, 0.16801);
    let d = mix(-1.97760, -1.27393);
    let e = mix(-4.32054, -4.85967);
    a / (1.0 + b * x.powf(c)) + d * x + e
}

/// Λ(cos θ) of the spec's visibility.
#[inline]
fn lambda(cos: f32, alpha: f32) -> f32 {
    if cos < 0.5 {
        lambda_fit(cos, alpha).exp()
    } else {
        (2.0 * lambda_fit(0.5, alpha) - lambda_fit(1.0 - cos, alpha)).exp()
    }
}

/// The sheen lobe times π and `n·l` (the renderer's units: Lambert's is
/// the plain `n·l`), for a white sheen: `π·D·V·(n·l)`. `nl`, `nv` in
/// (0, 1].
#[inline]
pub(crate) fn lobe(nh: f32, nl: f32, nv: f32, alpha: f32) -> f32 {
    let sin2 = (1.0 - nh * nh).max(0.0);
    let pi_d = (2.0 + 1.0 / alpha) * sin2.powf(0.5 / alpha) * 0.5;
    let vis =
        (1.0 / ((1.0 + lambda(nv, alpha) + lambda(nl, alpha)) * 4.0 * nv * nl)).clamp(0.0, 1.0);
    pi_d * vis * nl
}

impl Lights {
    /// The sheen of `color` and perceptual `roughness` at a surface of
    /// unit normal `n` seen from unit `v`, at `p`, in the units of
    /// [`Lights::lambert`]: each light's colour times its direct share
    /// times [`lobe`]. Zero where the eye or a light is behind.
    #[inline]
    pub(crate) fn sheen_a(
        &self,
        n: Vec3A,
        v: Vec3A,
        p: Vec3A,
        color: Vec3A,
        roughness: f32,
    ) -> Vec3A {
        let nv = n.dot(v);
        let mut sum = Vec3A::ZERO;
        if nv.is_nan() || nv <= 0.0 {
            return sum;
        }
        let alpha = roughness * roughness;
        for i in 0..self.len {
            let (l, share) = self.incident_a(i, p);
            let nl = n.dot(l);
            if nl.is_nan() || nl <= 0.0 {
                continue;
            }
            let nh = n.dot((l + v).normalize_or_zero()).max(0.0);
            sum += self.color[i] * (lobe(nh, nl, nv, alpha) * (1.0 - self.ambient[i]) * share);
        }
        sum * color
    }
}

/// The sheen lobe as the renderer adds it, `π·D·V·(n·l)`, for a white
/// sheen of perceptual `roughness` and one white light without ambient, in
/// f64 from the spec's formulas: what the renderer's f32 is measured
/// against. `n`, `l`, `v` unit.
pub fn sheen_reference(n: glam::DVec3, l: glam::DVec3, v: glam::DVec3, roughness: f64) -> f64 {
    let (nv, nl) = (n.dot(v), n.dot(l));
    if !(nv > 0.0 && nl > 0.0) {
        return 0.0;
    }
    let alpha = roughness * roughness;
    let nh = n.dot((l + v).normalize_or_zero()).max(0.0);
    let fit = |x: f64| {
        let t = (1.0 - alpha) * (1.0 - alpha);
        let mix = |a: f64, b: f64| a + (b - a) * t;
        mix(21.5473, 25.3245) / (1.0 + mix(3.82987, 3.32435) * x.powf(mix(0.19823, 0.16801)))
            + mix(-1.97760, -1.27393) * x
            + mix(-4.32054, -4.85967)
    };
    let lambda = |c: f64| {
        if c < 0.5 {
            fit(c).exp()
        } else {
            (2.0 * fit(0.5) - fit(1.0 - c)).exp()
        }
    };
    let d =
        (2.0 + 1.0 / alpha) * (1.0 - nh * nh).max(0.0).powf(0.5 / alpha) / std::f64::consts::TAU;
    let vis = (1.0 / ((1.0 + lambda(nv) + lambda(nl)) * 4.0 * nv * nl)).clamp(0.0, 1.0);
    std::f64::consts::PI * d * vis * nl
}

/// The sheen's directional albedo for `n·v` and perceptual `roughness`:
/// the white lobe over the hemisphere (so `1 − max(colour)·E` of what is
/// beneath is left), in f64 on a grid of `steps × 4·steps` directions.
pub fn sheen_albedo_reference(nv: f64, roughness: f64, steps: usize) -> f64 {
    let n = glam::DVec3::Z;
    let nv = nv.clamp(1e-4, 1.0);
    let v = glam::DVec3::new((1.0 - nv * nv).sqrt(), 0.0, nv);
    let (w, h) = (4 * steps, steps);
    let mut sum = 0.0;
    for i in 0..w * h {
        let (x, y) = ((i % w) as f64 + 0.5, (i / w) as f64 + 0.5);
        let (theta, phi) = (
            y / h as f64 * std::f64::consts::FRAC_PI_2,
            x / w as f64 * std::f64::consts::TAU,
        );
        let l = glam::DVec3::new(
            theta.sin() * phi.cos(),
            theta.sin() * phi.sin(),
            theta.cos(),
        );
        let solid = theta.sin()
            * (std::f64::consts::FRAC_PI_2 / h as f64)
            * (std::f64::consts::TAU / w as f64);
        sum += sheen_reference(n, l, v, roughness) * solid;
    }
    sum / std::f64::consts::PI
}

/// Entries of the albedo table a side.
const SIDE: usize = 16;

/// [`sheen_albedo_reference`] tabulated over `n·v` and roughness in
/// [0, 1], once a process.
fn table() -> &'static [[f32; SIDE]; SIDE] {
    static TABLE: OnceLock<[[f32; SIDE]; SIDE]> = OnceLock::new();
    TABLE.get_or_init(|| {
        let at = |i: usize| i as f64 / (SIDE - 1) as f64;
        std::array::from_fn(|r| {
            let roughness = at(r).max(f64::from(crate::scene::Sheen::MIN_ROUGHNESS));
            std::array::from_fn(|c| sheen_albedo_reference(at(c), roughness, 24) as f32)
        })
    })
}

/// The sheen's directional albedo at `nv` and `roughness`, read
/// bilinearly from the table.
#[inline]
pub(crate) fn albedo(nv: f32, roughness: f32) -> f32 {
    let t = table();
    let scale = (SIDE - 1) as f32;
    let (x, y) = (
        nv.clamp(0.0, 1.0) * scale,
        roughness.clamp(0.0, 1.0) * scale,
    );
    let (x0, y0) = ((x as usize).min(SIDE - 2), (y as usize).min(SIDE - 2));
    let (fx, fy) = (x - x0 as f32, y - y0 as f32);
    let row = |r: &[f32; SIDE]| r[x0] + (r[x0 + 1] - r[x0]) * fx;
    let (a, b) = (row(&t[y0]), row(&t[y0 + 1]));
    a + (b - a) * fy
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_albedo_table_is_the_integral_between_its_nodes() {
        for (nv, roughness) in [(0.9f32, 0.5f32), (0.3, 0.8), (0.55, 0.25), (0.1, 1.0)] {
            let want = sheen_albedo_reference(f64::from(nv), f64::from(roughness), 24);
            let got = albedo(nv, roughness);
            assert!(
                (f64::from(got) - want).abs() < 0.01,
                "{nv} {roughness}: {got} against {want}"
            );
        }
    }

    #[test]
    fn the_f32_lobe_is_the_f64_reference() {
        let (n, v) = (glam::DVec3::Z, glam::DVec3::new(0.6, 0.0, 0.8));
        for l in [
            glam::DVec3::new(-0.6, 0.0, 0.8),
            glam::DVec3::new(0.0, 0.96, 0.28),
            glam::DVec3::Z,
        ] {
            for r in [0.2, 0.5, 1.0] {
                let want = sheen_reference(n, l, v, r);
                let nh = n.dot((l + v).normalize()) as f32;
                let got = lobe(nh, l.z as f32, v.z as f32, (r * r) as f32);
                assert!(
                    (f64::from(got) - want).abs() <= 1e-5 * want.max(1.0),
                    "{l} {r}: {got} {want}"
                );
            }
        }
    }
}
