//! What a glTF material, its textures, sampler and light say, as
//! rastty's types: the finish (metallic-roughness, emissive, unlit, alpha,
//! maps), each image decoded once each way it is read, the sampler's
//! filters and wrap modes, and `KHR_lights_punctual` lights placed by their
//! nodes.
//!
//! Trade-offs: each is read once at load into a small value the renderer
//! uses as it is, so nothing glTF-specific reaches the frame.

use std::collections::BTreeMap;
use std::sync::Arc;

use super::buffers::Buffer;
use ::gltf::texture::{MagFilter, MinFilter, WrappingMode};
use glam::{Mat4, Vec2, Vec3};

use super::Parts;
use super::buffers::{Located, locate};
use crate::scene::file::Files;

use crate::color::Lin;
use crate::scene::Maps;
use crate::scene::light::{Light, LightKind};
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

/// A material's base colour factor and texture: where it has
/// `KHR_materials_pbrSpecularGlossiness` (older exporters' materials), its
/// diffuse colour and texture, which the extension says are used instead
/// of the metallic-roughness ones; else its metallic-roughness base
/// colour.
pub(super) fn base_color<'a>(
    material: &::gltf::Material<'a>,
) -> ([f32; 4], Option<::gltf::texture::Info<'a>>) {
    match material.pbr_specular_glossiness() {
        Some(sg) => (sg.diffuse_factor(), sg.diffuse_texture()),
        None => {
            let pbr = material.pbr_metallic_roughness();
            (pbr.base_color_factor(), pbr.base_color_texture())
        }
    }
}

/// A material's finish: its metallic-roughness factors where they are not
/// both glTF's defaults (1 and 1, a rough metal, drawn matte: see
/// [`crate::scene::Finish`]) or a metallic-roughness texture is given, its
/// emissive factor times `KHR_materials_emissive_strength`, and
/// `KHR_materials_unlit`. Factors are linear, as glTF's colours are. A
/// material with `KHR_materials_pbrSpecularGlossiness` takes its specular
/// colour and glossiness instead ([`crate::scene::Specular::specular_glossiness`]).
/// `KHR_materials_ior` and `KHR_materials_specular` set its non-metal
/// part's reflectance ([`crate::scene::Specular::with_dielectric`]);
/// `KHR_materials_clearcoat` and `KHR_materials_sheen` give its layers.
pub(super) fn finish(material: &::gltf::Material<'_>) -> crate::scene::Finish {
    let pbr = material.pbr_metallic_roughness();
    let (metallic, roughness) = (pbr.metallic_factor(), pbr.roughness_factor());
    let said = (metallic, roughness) != (1.0, 1.0) || pbr.metallic_roughness_texture().is_some();
    let strength = material.emissive_strength().unwrap_or(1.0);
    let e = material.emissive_factor().map(|c| c * strength);
    let specular = match material.pbr_specular_glossiness() {
        Some(sg) => crate::scene::Specular::specular_glossiness(
            Vec3::from(sg.specular_factor()),
            sg.glossiness_factor(),
        ),
        None => said
            .then(|| crate::scene::Specular::metallic_roughness(metallic, roughness))
            .flatten()
            .map(|s| {
                let ior = extension_number(material, "KHR_materials_ior", "ior").unwrap_or(1.5);
                let specular = "KHR_materials_specular";
                let color = extension_color(material, specular, "specularColorFactor");
                let factor = extension_number(material, specular, "specularFactor");
                s.with_dielectric(ior, color.unwrap_or(Vec3::ONE), factor.unwrap_or(1.0))
            }),
    };
    let coat = "KHR_materials_clearcoat";
    let clearcoat = crate::scene::Clearcoat::new(
        extension_number(material, coat, "clearcoatFactor").unwrap_or(0.0),
        extension_number(material, coat, "clearcoatRoughnessFactor").unwrap_or(0.0),
    );
    let sheen = crate::scene::Sheen::new(
        extension_color(material, "KHR_materials_sheen", "sheenColorFactor").unwrap_or(Vec3::ZERO),
        extension_number(material, "KHR_materials_sheen", "sheenRoughnessFactor").unwrap_or(0.0),
    );
    crate::scene::Finish {
        specular,
        emissive: Lin::from_unit(e),
        unlit: material.unlit(),
        alpha: alpha(material),
        // The primitive's to add, once the images are read.
        maps: crate::scene::Maps::default(),
        sides: if material.double_sided() {
            crate::scene::Sides::Double
        } else {
            crate::scene::Sides::Single
        },
        layers: crate::scene::Layers { clearcoat, sheen },
    }
}

/// Number `key` of extension `extension`'s object on `material`, if it is
/// one (JSON has no NaN; a string or an array is none).
fn extension_number(material: &::gltf::Material<'_>, extension: &str, key: &str) -> Option<f32> {
    let v = material.extension_value(extension)?.get(key)?.as_f64()?;
    Some(v as f32)
}

/// Colour `key` (three numbers, linear) of extension `extension`'s object
/// on `material`, if it is one.
fn extension_color(material: &::gltf::Material<'_>, extension: &str, key: &str) -> Option<Vec3> {
    let v = material.extension_value(extension)?.get(key)?.as_array()?;
    let c: Vec<f32> = v
        .iter()
        .map_while(|x| x.as_f64().map(|x| x as f32))
        .collect();
    match c[..] {
        [r, g, b] => Some(Vec3::new(r, g, b)),
        _ => None,
    }
}

/// The textures of the layer extensions (`extension`, the texture's key),
/// which are noted as not drawn: their factors are.
const LAYER_TEXTURES: &[(&str, &str, &str)] = &[
    (
        "KHR_materials_clearcoat",
        "clearcoatTexture",
        "clearcoat textures",
    ),
    (
        "KHR_materials_clearcoat",
        "clearcoatRoughnessTexture",
        "clearcoat textures",
    ),
    (
        "KHR_materials_clearcoat",
        "clearcoatNormalTexture",
        "clearcoat textures",
    ),
    ("KHR_materials_sheen", "sheenColorTexture", "sheen textures"),
    (
        "KHR_materials_sheen",
        "sheenRoughnessTexture",
        "sheen textures",
    ),
    (
        "KHR_materials_specular",
        "specularTexture",
        "specular textures",
    ),
    (
        "KHR_materials_specular",
        "specularColorTexture",
        "specular textures",
    ),
];

/// How much of its colour a fully transmissive material keeps, drawn as
/// see-through: glass tints what is behind it (refraction is not drawn),
/// and a surface of no alpha would not be seen at all.
pub(super) const GLASS_ALPHA: f32 = 0.25;

/// A material's `alphaMode`, `alphaCutoff` and base colour alpha (JSON has
/// no NaN; a factor outside [0, 1] is held to it). The texture's alpha is
/// the primitive's to add, once the image is read. A transmissive material
/// (`KHR_materials_transmission`) not masked is blended, its alpha times
/// `1 − (1 − GLASS_ALPHA)·transmission`.
fn alpha(material: &::gltf::Material<'_>) -> crate::scene::Alpha {
    use crate::scene::AlphaMode;
    let transmission = (material.transmission())
        .map_or(0.0, |t| t.transmission_factor())
        .clamp(0.0, 1.0);
    let mode = match material.alpha_mode() {
        ::gltf::material::AlphaMode::Opaque if transmission > 0.0 => AlphaMode::Blend,
        ::gltf::material::AlphaMode::Opaque => AlphaMode::Opaque,
        ::gltf::material::AlphaMode::Mask => AlphaMode::Mask {
            cutoff: material.alpha_cutoff().unwrap_or(0.5).max(0.0),
        },
        ::gltf::material::AlphaMode::Blend => AlphaMode::Blend,
    };
    let factor = base_color(material).0[3].clamp(0.0, 1.0);
    let seen = match mode {
        AlphaMode::Blend => 1.0 - (1.0 - GLASS_ALPHA) * transmission,
        _ => 1.0,
    };
    crate::scene::Alpha {
        mode,
        factor: factor * seen,
        texture: None,
    }
}

/// A material's base texture and the coordinate sets its textures are read
/// through.
pub(super) struct Sets {
    /// The base colour's texture.
    pub(super) texture: Option<u32>,
    /// The first set's `KHR_texture_transform`.
    pub(super) uv_transform: Option<glam::Affine2>,
    /// The first set: the base colour's, or the first map's.
    pub(super) chosen: u32,
    /// The second set, where a map reads one, and its transform.
    pub(super) second: Option<(u32, Option<glam::Affine2>)>,
}

impl Parts<'_> {
    /// A material's textures: its base colour's (and, masked or blended,
    /// its alpha) and its maps, each decoded once, onto `finish`; and the
    /// coordinate sets they are read through (`TEXCOORD_n`) with the
    /// `KHR_texture_transform` each is moved by: the base colour's (or
    /// else the first map's), and a second where a map reads another. A
    /// texture on a third set is counted in `ignored` and left out.
    pub(super) fn textures_of(
        &mut self,
        material: &::gltf::Material<'_>,
        finish: &mut crate::scene::Finish,
        buffers: &[Buffer],
        ignored: &mut BTreeMap<&'static str, usize>,
    ) -> std::result::Result<Sets, String> {
        // KHR_texture_transform: the coordinates moved once, here
        // (T · R · S, as the extension says), by the base colour's
        // transform, or the first other map's where the base has none.
        let pbr = material.pbr_metallic_roughness();
        let base_info = base_color(material).1;
        let sg = material.pbr_specular_glossiness();
        // Under specular-glossiness, the metallic-roughness texture is not
        // read, and the specular-glossiness one is noted.
        let metallic_roughness = pbr.metallic_roughness_texture().filter(|_| sg.is_none());
        for &(extension, key, what) in LAYER_TEXTURES {
            if material
                .extension_value(extension)
                .and_then(|e| e.get(key))
                .is_some()
            {
                *ignored.entry(what).or_default() += 1;
            }
        }
        let set = |i: &::gltf::texture::Info| {
            (i.texture_transform().and_then(|t| t.tex_coord())).unwrap_or(i.tex_coord())
        };
        let sg_texture = sg.as_ref().and_then(|sg| sg.specular_glossiness_texture());
        // Two coordinate sets are read: the base colour's (or else the
        // first map's), and the first other a map reads. A texture on a
        // third is noted and left out.
        let sets = [
            base_info.as_ref().map(set),
            metallic_roughness.as_ref().map(set),
            sg_texture.as_ref().map(set),
            material.emissive_texture().as_ref().map(set),
            material.normal_texture().map(|n| n.tex_coord()),
            material.occlusion_texture().map(|o| o.tex_coord()),
        ];
        let mut used = sets.into_iter().flatten();
        let chosen = used.next().unwrap_or(0);
        let other = used.find(|&s| s != chosen);
        // Each set's KHR_texture_transform (T · R · S, as the extension
        // says): the first its textures give, applied once, here.
        let transform_of = |on: u32| {
            [
                &base_info,
                &metallic_roughness,
                &sg_texture,
                &material.emissive_texture(),
            ]
            .into_iter()
            .flatten()
            .filter(|i| set(i) == on)
            .find_map(|i| i.texture_transform())
            .map(|t| {
                glam::Affine2::from_scale_angle_translation(
                    Vec2::from(t.scale()),
                    -t.rotation(),
                    Vec2::from(t.offset()),
                )
            })
        };
        let uv_transform = transform_of(chosen);
        let second_transform = other.and_then(transform_of);
        let mut third = 0;
        // Whether a texture on `set` is read, and through the second set.
        let mut read_on = |set: u32| {
            let on = (set == chosen)
                .then_some(false)
                .or((Some(set) == other).then_some(true));
            third += usize::from(on.is_none());
            on
        };
        let mut bits = 0u8;
        let mut mark = |second: bool, bit: u8| {
            if second {
                bits |= bit;
            }
        };
        let texture = match base_info {
            Some(info) if read_on(set(&info)) == Some(false) => {
                // A mask's or a blend's alpha is the texture's alpha
                // channel times the factor.
                if finish.alpha.mode != crate::scene::AlphaMode::Opaque {
                    finish.alpha.texture = self.texture(&info.texture(), buffers, Decode::Alpha)?;
                }
                self.texture(&info.texture(), buffers, Decode::Colour)?
            }
            _ => None,
        };
        let maps = &mut finish.maps;
        if let Some(info) = metallic_roughness
            && let Some(second) = read_on(set(&info))
        {
            maps.metallic_roughness = self.texture(&info.texture(), buffers, Decode::Values)?;
            mark(second, Maps::METALLIC_ROUGHNESS);
        }
        if let Some(info) = sg_texture
            && let Some(second) = read_on(set(&info))
        {
            let colour = self.texture(&info.texture(), buffers, Decode::Colour)?;
            let gloss = self.texture(&info.texture(), buffers, Decode::Alpha)?;
            maps.specular_glossiness = colour.zip(gloss);
            mark(second, Maps::SPECULAR_GLOSSINESS);
        }
        if let Some(info) = material.emissive_texture()
            && let Some(second) = read_on(set(&info))
        {
            maps.emissive = self.texture(&info.texture(), buffers, Decode::Colour)?;
            mark(second, Maps::EMISSIVE);
        }
        if let Some(n) = material.normal_texture()
            && let Some(second) = read_on(n.tex_coord())
        {
            maps.normal = self
                .texture(&n.texture(), buffers, Decode::Values)?
                .map(|t| (t, n.scale()));
            mark(second, Maps::NORMAL);
        }
        if let Some(o) = material.occlusion_texture()
            && let Some(second) = read_on(o.tex_coord())
        {
            maps.occlusion = self
                .texture(&o.texture(), buffers, Decode::Values)?
                .map(|t| (t, o.strength().clamp(0.0, 1.0)));
            mark(second, Maps::OCCLUSION);
        }
        if third > 0 {
            *ignored
                .entry("textures on a third coordinate set")
                .or_default() += third;
        }
        maps.second = bits;
        let second = (bits != 0).then(|| (other.unwrap_or(0), second_transform));
        Ok(Sets {
            texture,
            uv_transform,
            chosen,
            second,
        })
    }

    /// The texture of glTF texture `t` decoded as `how` says (`None` for
    /// its alpha where the image has none), as an index into
    /// `self.textures`; each image decoded once each way.
    fn texture(
        &mut self,
        t: &::gltf::Texture,
        buffers: &[Buffer],
        how: Decode,
    ) -> std::result::Result<Option<u32>, String> {
        if let Some(&id) = self.images.decoded.get(&(t.index(), how)) {
            return Ok(id);
        }
        let index = t.source().index();
        let json = self
            .images
            .root
            .and_then(|r| r.images.get(index))
            .ok_or("its image is missing")?;
        let what = match (&json.uri, json.buffer_view) {
            (Some(uri), None) if !uri.starts_with("data:") => {
                format!("image {index} ({})", crate::text::name(uri, 80))
            }
            _ => format!("image {index}"),
        };
        let bad = |e: String| format!("texture {}: {what}: {e}", t.index());
        let owned;
        let mut file_key = None;
        let unset = Files::default();
        let bytes: &[u8] = match (&json.uri, json.buffer_view) {
            (None, Some(view)) => {
                let view = self
                    .images
                    .root
                    .and_then(|r| r.buffer_views.get(view.value()))
                    .ok_or_else(|| bad("its buffer view is missing".into()))?;
                let buffer = buffers
                    .get(view.buffer.value())
                    .ok_or_else(|| bad("its buffer is missing".into()))?;
                let offset = view.byte_offset.map_or(0, |o| o.0 as usize);
                let range = offset
                    .checked_add(view.byte_length.0 as usize)
                    .filter(|&end| end <= buffer.len())
                    .map(|end| offset..end)
                    .ok_or_else(|| {
                        bad(format!(
                            "its buffer view ({} bytes at offset {offset}) is out of range of its {}-byte buffer",
                            view.byte_length.0,
                            buffer.len()
                        ))
                    })?;
                &buffer[range]
            }
            (Some(uri), None) => {
                let located = locate(
                    uri,
                    self.images.base,
                    self.images.owner,
                    self.images.files.unwrap_or(&unset),
                    &mut self.images.notes,
                )
                .map_err(bad)?;
                owned = match located {
                    Located::Bytes(bytes) => bytes,
                    Located::File(opened, r) => {
                        // A file that another texture decoded the same way
                        // with the same sampler is not read again.
                        file_key = Some((opened.id().clone(), how, t.sampler().index()));
                        if let Some(&id) = file_key
                            .as_ref()
                            .and_then(|k| self.images.files_decoded.get(k))
                        {
                            self.images.decoded.insert((t.index(), how), id);
                            return Ok(id);
                        }
                        r.read(opened).map_err(bad)?
                    }
                };
                &owned
            }
            (Some(_), Some(_)) => return Err(bad("it has both a uri and a bufferView".into())),
            (None, None) => return Err(bad("it has neither a uri nor a bufferView".into())),
        };
        let (sampler, left) = (
            sampler(&t.sampler()),
            (self.images.texels_left, self.images.max_side),
        );
        let texture = match how {
            Decode::Alpha => {
                crate::scene::image::decode_alpha(bytes, &what, sampler, left).map_err(bad)?
            }
            Decode::Colour => {
                Some(crate::scene::image::decode(bytes, &what, sampler, left).map_err(bad)?)
            }
            Decode::Values => {
                Some(crate::scene::image::decode_linear(bytes, &what, sampler, left).map_err(bad)?)
            }
        };
        let id = texture.map(|texture| {
            let (w, h) = texture.original_size();
            self.images.texels_left -= u64::from(w) * u64::from(h);
            self.textures.push(Arc::new(texture));
            self.textures.len() as u32 - 1
        });
        self.images.decoded.insert((t.index(), how), id);
        if let Some(key) = file_key {
            self.images.files_decoded.insert(key, id);
        }
        Ok(id)
    }
}

/// How an image becomes a texture.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum Decode {
    /// A colour: sRGB-decoded (base colour, emissive).
    Colour,
    /// Its alpha channel.
    Alpha,
    /// Numbers, not colours: each byte over 255 (normal,
    /// metallic-roughness, occlusion).
    Values,
}
