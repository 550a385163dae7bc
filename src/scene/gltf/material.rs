//! What a glTF material, sampler and light say, as rastty's types: the
//! finish (metallic-roughness, emissive, unlit), the sampler's filters and
//! wrap modes, and `KHR_lights_punctual` lights placed by their nodes.
//!
//! Trade-offs: each is read once at load into a small value the renderer
//! uses as it is, so nothing glTF-specific reaches the frame.

use ::gltf::texture::{MagFilter, MinFilter, WrappingMode};
use glam::{Mat4, Vec3};

use crate::color::Lin;
use crate::scene::mesh::{Light, LightKind};
use crate::texture::{Filter, Mipmap, Sampler, Wrap};

/// A glTF sampler as rastty's (an unset filter is the best there is).
pub(super) fn sampler(s: &::gltf::texture::Sampler) -> Sampler {
    let wrap = |w| match w {
        WrappingMode::Repeat => Wrap::Repeat,
        WrappingMode::MirroredRepeat => Wrap::MirroredRepeat,
        WrappingMode::ClampToEdge => Wrap::ClampToEdge,
    };
    let (min, mipmap) = match s.min_filter() {
        Some(MinFilter::Nearest) => (Filter::Nearest, Mipmap::None),
        Some(MinFilter::Linear) => (Filter::Linear, Mipmap::None),
        Some(MinFilter::NearestMipmapNearest) => (Filter::Nearest, Mipmap::Nearest),
        Some(MinFilter::LinearMipmapNearest) => (Filter::Linear, Mipmap::Nearest),
        Some(MinFilter::NearestMipmapLinear) => (Filter::Nearest, Mipmap::Linear),
        Some(MinFilter::LinearMipmapLinear) | None => (Filter::Linear, Mipmap::Linear),
    };
    Sampler {
        wrap_u: wrap(s.wrap_s()),
        wrap_v: wrap(s.wrap_t()),
        mag: match s.mag_filter() {
            Some(MagFilter::Nearest) => Filter::Nearest,
            Some(MagFilter::Linear) | None => Filter::Linear,
        },
        min,
        mipmap,
    }
}

/// A `KHR_lights_punctual` light placed by a node of transform `world`: it
/// shines down the node's −z from the node's origin. Its linear colour is
/// kept as a colour whose largest channel is full (sRGB-encoded) and an
/// intensity that carries the rest.
pub(super) fn light_of(
    light: &::gltf::khr_lights_punctual::Light<'_>,
    world: Mat4,
) -> std::result::Result<Light, String> {
    use ::gltf::khr_lights_punctual::Kind;
    let c = Vec3::from(light.color());
    let peak = c.max_element();
    if !(c.is_finite() && c.min_element() >= 0.0) {
        return Err(format!(
            "its colour {c} is not three finite numbers of at least 0"
        ));
    }
    let unit = if peak > 0.0 { c / peak } else { Vec3::ZERO };
    let position = world.transform_point3(Vec3::ZERO);
    let kind = match light.kind() {
        Kind::Directional => LightKind::Directional,
        Kind::Point => LightKind::Point {
            position,
            range: light.range(),
        },
        Kind::Spot {
            inner_cone_angle,
            outer_cone_angle,
        } => LightKind::Spot {
            position,
            range: light.range(),
            inner: inner_cone_angle,
            outer: outer_cone_angle,
        },
    };
    let l = Light {
        direction: world.transform_vector3(Vec3::NEG_Z).normalize_or_zero(),
        color: Lin::from_unit(unit.to_array()).to_srgb(),
        ambient: 0.0,
        kind,
        intensity: light.intensity() * peak,
    };
    l.check()?;
    Ok(l)
}

/// A material's finish: its metallic-roughness factors where they are not
/// both glTF's defaults (1 and 1, a rough metal, drawn matte: see
/// [`crate::scene::Finish`]) or a metallic-roughness texture is given, its
/// emissive factor times `KHR_materials_emissive_strength`, and
/// `KHR_materials_unlit`. Factors are linear, as glTF's colours are.
pub(super) fn finish(material: &::gltf::Material<'_>) -> crate::scene::Finish {
    let pbr = material.pbr_metallic_roughness();
    let (metallic, roughness) = (pbr.metallic_factor(), pbr.roughness_factor());
    let said = (metallic, roughness) != (1.0, 1.0) || pbr.metallic_roughness_texture().is_some();
    let strength = material.emissive_strength().unwrap_or(1.0);
    let e = material.emissive_factor().map(|c| c * strength);
    crate::scene::Finish {
        specular: said
            .then(|| crate::scene::Specular::metallic_roughness(metallic, roughness))
            .flatten(),
        emissive: Lin::from_unit(e),
        unlit: material.unlit(),
        alpha: alpha(material),
    }
}

/// A material's `alphaMode`, `alphaCutoff` and base colour alpha (JSON has
/// no NaN; a factor outside [0, 1] is held to it). The texture's alpha is
/// the primitive's to add, once the image is read.
fn alpha(material: &::gltf::Material<'_>) -> crate::scene::Alpha {
    use crate::scene::AlphaMode;
    let mode = match material.alpha_mode() {
        ::gltf::material::AlphaMode::Opaque => AlphaMode::Opaque,
        ::gltf::material::AlphaMode::Mask => AlphaMode::Mask {
            cutoff: material.alpha_cutoff().unwrap_or(0.5).max(0.0),
        },
        ::gltf::material::AlphaMode::Blend => AlphaMode::Blend,
    };
    crate::scene::Alpha {
        mode,
        factor: material.pbr_metallic_roughness().base_color_factor()[3].clamp(0.0, 1.0),
        texture: None,
    }
}
