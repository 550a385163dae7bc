//! A material's finish: what its surface does with light beyond its colour
//! (a specular highlight, from glTF's metallic-roughness or OBJ's `Ks` and
//! `Ns`), the light it gives off itself (emissive), whether lights reach
//! it at all (unlit), and how much of what is behind shows through (alpha:
//! masked or blended, with the base texture's alpha channel).
//!
//! Trade-offs. A finish is a few numbers a run of faces and, where the
//! file has them, its maps ([`Maps`]: normal, metallic-roughness,
//! occlusion and emissive textures, read through the base colour's
//! coordinates). A run with maps or layers ([`Layers`]: a clear coat,
//! sheen) is shaded per sample (the renderer's mapped fill); one without
//! is shaded per vertex, whatever other runs have. A file that says
//! nothing of its finish is drawn matte: glTF's defaults (metallic 1,
//! roughness 1) describe a rough metal, which lit by lights alone is
//! nearly black, so only factors a file writes make a surface specular.
//! OBJ's Phong
//! exponent `Ns` becomes a roughness by the usual match of the Phong and
//! GGX lobes (α = √(2 / (Ns + 2)), roughness = √α), its `Ks` the colour of
//! the reflection at normal incidence; except in files Blender's exporter
//! wrote (it says so on the first line), which mean by them what Blender's
//! importer reads back: reflectance 0.08·`Ks`, roughness 1 − √`Ns` / 30.

use glam::Vec3;

use crate::color::Lin;

/// A specular surface: the glTF core model's metallic-roughness (a GGX
/// microfacet lobe with Smith's height-correlated visibility and Schlick's
/// Fresnel), evaluated per sample by the renderer (see
/// [`crate::specular_reference`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Specular {
    /// Reflectance at normal incidence of the non-metal part, linear, each
    /// channel in [0, 1]: 0.04 for glTF's dielectrics (`((ior − 1) /
    /// (ior + 1))²` times `KHR_materials_specular`'s colour and factor),
    /// `Ks` for OBJ.
    pub reflectance: Vec3,
    /// Reflectance at grazing incidence of the non-metal part, in [0, 1]:
    /// 1 but for `KHR_materials_specular`'s factor. Schlick's Fresnel is
    /// `f0 + (f90 − f0)·(1 − v·h)⁵`, linear in both, so the renderer finds
    /// it as `f90` times the lobe of `f0 / f90` (of the mix with the
    /// metal's: `f90` is 1 for a metal).
    pub f90: f32,
    /// How much of the surface is metal, in [0, 1]: a metal has no diffuse
    /// colour and reflects in its base colour.
    pub metallic: f32,
    /// Perceptual roughness in [0, 1] (α = roughness²), at least
    /// [`Specular::MIN_ROUGHNESS`]: a perfect mirror lit by a point has a
    /// highlight of no size.
    pub roughness: f32,
}

impl Specular {
    /// The smoothest surface drawn: a highlight of a directional light on
    /// a mirror smoother than this is smaller than any sample.
    pub const MIN_ROUGHNESS: f32 = 0.045;

    /// glTF's metallic-roughness, each factor clamped into [0, 1] (and the
    /// roughness to at least [`Specular::MIN_ROUGHNESS`]); `None` where a
    /// factor is not a number.
    pub fn metallic_roughness(metallic: f32, roughness: f32) -> Option<Specular> {
        (metallic.is_finite() && roughness.is_finite()).then(|| Specular {
            reflectance: Vec3::splat(0.04),
            f90: 1.0,
            metallic: metallic.clamp(0.0, 1.0),
            roughness: roughness.clamp(Self::MIN_ROUGHNESS, 1.0),
        })
    }

    /// Its non-metal part as `KHR_materials_ior` and
    /// `KHR_materials_specular` say: reflectance `((ior − 1) / (ior +
    /// 1))²` times `color` (at most 1) times `factor`, and `factor` at
    /// grazing incidence. glTF's defaults (ior 1.5, white, 1) give 0.04
    /// and 1; an ior of 0 (the spec's "infinite") reflects fully. Numbers
    /// that are not finite leave it as it is.
    pub fn with_dielectric(mut self, ior: f32, color: Vec3, factor: f32) -> Specular {
        if !(ior.is_finite() && color.is_finite() && factor.is_finite()) {
            return self;
        }
        let r = if ior == 0.0 {
            1.0
        } else {
            ((ior - 1.0) / (ior + 1.0)).powi(2)
        };
        let factor = factor.clamp(0.0, 1.0);
        self.reflectance = (Vec3::splat(r) * color.max(Vec3::ZERO)).min(Vec3::ONE) * factor;
        self.f90 = factor;
        self
    }

    /// glTF's `KHR_materials_pbrSpecularGlossiness`: reflectance its
    /// specular colour (linear, clamped into [0, 1]), no metal, roughness
    /// 1 − glossiness (clamped as [`Specular::metallic_roughness`]'s);
    /// `None` where the specular colour is black (no highlight) or a
    /// number is not finite.
    pub fn specular_glossiness(specular: Vec3, glossiness: f32) -> Option<Specular> {
        if !specular.is_finite() || !glossiness.is_finite() || specular.max_element() <= 0.0 {
            return None;
        }
        Some(Specular {
            reflectance: specular.clamp(Vec3::ZERO, Vec3::ONE),
            f90: 1.0,
            metallic: 0.0,
            roughness: (1.0 - glossiness).clamp(Self::MIN_ROUGHNESS, 1.0),
        })
    }

    /// OBJ's Phong terms: `Ks` (linear, clamped into [0, 1]) and the
    /// exponent `Ns` (at least 0); `None` where `Ks` is black (no
    /// highlight) or a number is not finite.
    pub fn phong(ks: Vec3, ns: f32) -> Option<Specular> {
        if !ks.is_finite() || !ns.is_finite() || ks.max_element() <= 0.0 {
            return None;
        }
        let alpha = (2.0 / (ns.max(0.0) + 2.0)).sqrt();
        Some(Specular {
            reflectance: ks.clamp(Vec3::ZERO, Vec3::ONE),
            f90: 1.0,
            metallic: 0.0,
            roughness: alpha.sqrt().clamp(Self::MIN_ROUGHNESS, 1.0),
        })
    }

    /// OBJ's `Ks` and `Ns` as Blender's exporter writes them: `Ks` its
    /// Principled surface's specular (reflectance 0.08·`Ks`), `Ns` its
    /// roughness r as (30·(1 − r))²; `None` where `Ks` is black or a
    /// number is not finite.
    pub fn blender(ks: Vec3, ns: f32) -> Option<Specular> {
        if !ks.is_finite() || !ns.is_finite() || ks.max_element() <= 0.0 {
            return None;
        }
        Some(Specular {
            reflectance: (ks * 0.08).clamp(Vec3::ZERO, Vec3::ONE),
            f90: 1.0,
            metallic: 0.0,
            roughness: (1.0 - ns.max(0.0).sqrt() / 30.0).clamp(Self::MIN_ROUGHNESS, 1.0),
        })
    }
}

/// A clear coat over a material (glTF's `KHR_materials_clearcoat`): a
/// dielectric layer of index 1.5 (reflectance 0.04) with a GGX lobe of its
/// own roughness, over the geometry's normal, that dims what is beneath
/// by its Fresnel (`1 − factor·F(n·v)`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Clearcoat {
    /// How much of the surface is coated, in (0, 1].
    pub factor: f32,
    /// The coat's perceptual roughness, in [[`Specular::MIN_ROUGHNESS`], 1].
    pub roughness: f32,
}

/// Sheen over a material (glTF's `KHR_materials_sheen`): the back-scatter
/// of cloth's fibres, the "Charlie" distribution with Estevez and Kulla's
/// visibility, in its colour; what is beneath dimmed by the sheen's
/// directional albedo (`1 − max(colour)·E(n·v)`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sheen {
    /// The sheen's colour, linear, each channel in [0, 1], not black.
    pub color: Vec3,
    /// Its perceptual roughness, in [[`Sheen::MIN_ROUGHNESS`], 1].
    pub roughness: f32,
}

impl Sheen {
    /// The smoothest sheen drawn (the distribution is undefined at 0).
    pub const MIN_ROUGHNESS: f32 = 0.07;
}

/// A material's layers over its base: each shaded per sample (the mapped
/// fill), and each a plan decision.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Layers {
    /// A clear coat.
    pub clearcoat: Option<Clearcoat>,
    /// Sheen.
    pub sheen: Option<Sheen>,
}

impl Layers {
    /// Whether it has no layer.
    pub fn is_empty(&self) -> bool {
        *self == Layers::default()
    }
}

impl Clearcoat {
    /// glTF's factors, clamped into range; `None` for no coat (a factor of
    /// 0) or a number that is not finite.
    pub fn new(factor: f32, roughness: f32) -> Option<Clearcoat> {
        (factor.is_finite() && roughness.is_finite() && factor > 0.0).then(|| Clearcoat {
            factor: factor.min(1.0),
            roughness: roughness.clamp(Specular::MIN_ROUGHNESS, 1.0),
        })
    }
}

impl Sheen {
    /// glTF's factors (the colour linear), clamped into range; `None` for
    /// no sheen (black) or a number that is not finite.
    pub fn new(color: Vec3, roughness: f32) -> Option<Sheen> {
        let color = color.clamp(Vec3::ZERO, Vec3::ONE);
        (color.is_finite() && roughness.is_finite() && color.max_element() > 0.0).then(|| Sheen {
            color,
            roughness: roughness.clamp(Sheen::MIN_ROUGHNESS, 1.0),
        })
    }
}

/// Which sides of a material's faces are drawn: glTF's `doubleSided`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Sides {
    /// Not said (OBJ, STL, PLY): the mesh's own culling, from its topology
    /// (a closed mesh culls its back faces, an open one shows its inside).
    #[default]
    Unsaid,
    /// Front faces only: a face seen from behind is culled.
    Single,
    /// Both: a face seen from behind is drawn, lit on the side seen (its
    /// normal flipped).
    Double,
}

/// A material's finish; the default is matte, lit, and dark of itself:
/// the surface drawn as it always was.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Finish {
    /// Its specular highlight, if any.
    pub specular: Option<Specular>,
    /// The light it gives off, added after lighting (black: none).
    pub emissive: Lin,
    /// Drawn in its colour whatever the lights (glTF's
    /// `KHR_materials_unlit`).
    pub unlit: bool,
    /// How much of what is behind it shows through.
    pub alpha: Alpha,
    /// Its textures beyond the base colour's.
    pub maps: Maps,
    /// Which sides of its faces are drawn.
    pub sides: Sides,
    /// Its layers: a clear coat and sheen.
    pub layers: Layers,
}

/// A material's textures beyond its base colour's, each an index into
/// [`crate::scene::Geometry::textures`], read through the base colour's
/// texture coordinates (glTF's `texCoord` of the base colour, or of the
/// first map) or, those [`Maps::second`] marks, a second set. Any of them
/// makes its faces shaded per sample.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Maps {
    /// A tangent-space normal map (linear; x right along the tangent, y
    /// along the bitangent, z out of the surface) and the scale of its x
    /// and y.
    pub normal: Option<(u32, f32)>,
    /// Metalness in blue and roughness in green (linear), multiplying the
    /// [`Specular`] factors.
    pub metallic_roughness: Option<u32>,
    /// Ambient occlusion in red (linear) and its strength: how much of a
    /// light's ambient share reaches the sample.
    pub occlusion: Option<(u32, f32)>,
    /// Emitted colour (sRGB-decoded), multiplying [`Finish::emissive`].
    pub emissive: Option<u32>,
    /// `KHR_materials_pbrSpecularGlossiness`'s texture: its specular
    /// colour (sRGB-decoded), multiplying [`Specular::reflectance`], and
    /// its glossiness (the alpha channel, linear, in every channel of the
    /// second), multiplying the glossiness (1 − roughness).
    pub specular_glossiness: Option<(u32, u32)>,
    /// The maps read through the second coordinate set
    /// ([`crate::scene::Geometry::uvs2`]), as bits of [`Maps::NORMAL`] and
    /// the others; the rest through the base colour's.
    pub second: u8,
}

impl Maps {
    /// [`Maps::second`]'s bit for the normal map.
    pub const NORMAL: u8 = 1;
    /// Its bit for the metallic-roughness map.
    pub const METALLIC_ROUGHNESS: u8 = 2;
    /// Its bit for the occlusion map.
    pub const OCCLUSION: u8 = 4;
    /// Its bit for the emissive map.
    pub const EMISSIVE: u8 = 8;
    /// Its bit for the specular-glossiness texture.
    pub const SPECULAR_GLOSSINESS: u8 = 16;

    /// Whether it has no map.
    pub fn is_empty(&self) -> bool {
        *self == Maps::default()
    }
}

/// How a material's coverage (glTF's `alphaMode`) is drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum AlphaMode {
    /// Every covered sample is the surface's (alpha ignored).
    #[default]
    Opaque,
    /// A sample is the surface's where its alpha is at least `cutoff`, and
    /// left as it was (nothing written, not even depth) elsewhere: a
    /// coverage decision per sample, as exact as a triangle's edge.
    Mask {
        /// The least alpha drawn (glTF's `alphaCutoff`, 0.5 by default).
        cutoff: f32,
    },
    /// Composited over what is behind in linear light, `alpha` of the
    /// surface's colour and the rest of the sample's; drawn after every
    /// opaque surface, back to front, testing depth without writing it.
    Blend,
}

/// A material's alpha: its mode, its factor (glTF's `baseColorFactor`'s
/// fourth number, OBJ's `d`) and the texture whose alpha channel
/// multiplies it (an index into [`crate::scene::Geometry::textures`], read
/// through the base colour's coordinates).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Alpha {
    /// How coverage is drawn.
    pub mode: AlphaMode,
    /// The alpha of the whole material, in [0, 1].
    pub factor: f32,
    /// The texture of its alpha channel (held in every channel, linear).
    pub texture: Option<u32>,
}

impl Default for Alpha {
    fn default() -> Alpha {
        Alpha {
            mode: AlphaMode::Opaque,
            factor: 1.0,
            texture: None,
        }
    }
}

impl Finish {
    /// Whether it is the default finish, which adds nothing to a frame.
    pub fn is_plain(&self) -> bool {
        *self == Finish::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn phong_exponents_become_the_matching_roughness() {
        // Ns = 0: α = 1, the roughest; Ns = 98: α = √(2/100).
        let s = Specular::phong(Vec3::splat(0.5), 0.0).unwrap();
        assert_eq!(s.roughness, 1.0);
        let s = Specular::phong(Vec3::ONE, 98.0).unwrap();
        assert_eq!(s.roughness, (0.02f32).sqrt().sqrt());
        // A huge exponent is a mirror, held at the smoothest drawn.
        let s = Specular::phong(Vec3::ONE, 1e12).unwrap();
        assert_eq!(s.roughness, Specular::MIN_ROUGHNESS);
        assert_eq!(Specular::phong(Vec3::ZERO, 10.0), None);
        assert_eq!(Specular::phong(Vec3::ONE, f32::NAN), None);
    }

    #[test]
    fn blenders_defaults_are_its_principled_surface() {
        // Ks 0.5, Ns 225: specular 0.5 (reflectance 0.04), roughness 0.5.
        let s = Specular::blender(Vec3::splat(0.5), 225.0).unwrap();
        assert_eq!((s.reflectance, s.roughness), (Vec3::splat(0.04), 0.5));
    }

    #[test]
    fn metallic_roughness_factors_are_clamped() {
        let s = Specular::metallic_roughness(2.0, -1.0).unwrap();
        assert_eq!((s.metallic, s.roughness), (1.0, Specular::MIN_ROUGHNESS));
        assert_eq!(Specular::metallic_roughness(f32::NAN, 0.5), None);
    }

    #[test]
    fn ior_and_specular_set_the_dielectrics_reflectance() {
        let s = Specular::metallic_roughness(0.0, 0.5).unwrap();
        // glTF's defaults change nothing.
        let same = s.with_dielectric(1.5, Vec3::ONE, 1.0);
        assert!((same.reflectance - Vec3::splat(0.04)).abs().max_element() < 1e-7);
        assert_eq!(same.f90, 1.0);
        // Water: ((1.33 − 1) / 2.33)²; half the specular: half of each.
        let w = s.with_dielectric(1.33, Vec3::ONE, 0.5);
        let r = (0.33f32 / 2.33).powi(2) * 0.5;
        assert!((w.reflectance - Vec3::splat(r)).abs().max_element() < 1e-7);
        assert_eq!(w.f90, 0.5);
        // A colour past 1 is held to 1 after the ior's product.
        let c = s.with_dielectric(0.0, Vec3::new(2.0, 0.5, 0.0), 1.0);
        assert_eq!(c.reflectance, Vec3::new(1.0, 0.5, 0.0));
        assert_eq!(s.with_dielectric(f32::NAN, Vec3::ONE, 1.0), s);
    }

    #[test]
    fn layers_of_nothing_are_none() {
        assert_eq!(Clearcoat::new(0.0, 0.5), None);
        assert_eq!(Sheen::new(Vec3::ZERO, 0.5), None);
        let c = Clearcoat::new(2.0, 0.0).unwrap();
        assert_eq!((c.factor, c.roughness), (1.0, Specular::MIN_ROUGHNESS));
        assert_eq!(
            Sheen::new(Vec3::ONE, 0.0).unwrap().roughness,
            Sheen::MIN_ROUGHNESS
        );
    }
}
