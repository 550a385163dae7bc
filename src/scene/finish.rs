//! A material's finish: what its surface does with light beyond its colour
//! (a specular highlight, from glTF's metallic-roughness or OBJ's `Ks` and
//! `Ns`), the light it gives off itself (emissive), whether lights reach
//! it at all (unlit), and how much of what is behind shows through (alpha:
//! masked or blended, with the base texture's alpha channel).
//!
//! Trade-offs. A finish is a few numbers a run of faces and, where the
//! file has them, its maps ([`Maps`]: normal, metallic-roughness,
//! occlusion and emissive textures, read through the base colour's
//! coordinates). A run with maps is shaded per sample from them (the
//! renderer's mapped fill); one without is shaded per vertex, as before,
//! whatever other runs have. A file that says
//! nothing of its finish is drawn matte, as before: glTF's defaults
//! (metallic 1, roughness 1) describe a rough metal, which without light
//! from its surroundings (no image-based lighting here) is nearly black,
//! so only factors a file writes make a surface specular. OBJ's Phong
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
    /// channel in [0, 1]: 0.04 for glTF's dielectrics, `Ks` for OBJ.
    pub reflectance: Vec3,
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
            metallic: metallic.clamp(0.0, 1.0),
            roughness: roughness.clamp(Self::MIN_ROUGHNESS, 1.0),
        })
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
            metallic: 0.0,
            roughness: (1.0 - ns.max(0.0).sqrt() / 30.0).clamp(Self::MIN_ROUGHNESS, 1.0),
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
}

/// A material's textures beyond its base colour's, each an index into
/// [`crate::scene::Geometry::textures`], read through the base colour's
/// texture coordinates (glTF's `TEXCOORD_0`). Any of them makes its faces
/// shaded per sample.
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
}

impl Maps {
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
}
