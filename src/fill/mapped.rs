//! The mapped fill's shading: a sample's colour from its material's maps
//! (glTF's normal, metallic-roughness, occlusion and emissive textures),
//! for the runs whose materials have them and only those (the plan's
//! `maps` decision).
//!
//! Per sample, in linear light: the base colour (interpolated, times its
//! texel); the normal interpolated and bent by the normal map in the
//! tangent frame interpolated from the corners' (the file's tangents, or
//! MikkTSpace's: `scene::tangents`), as glTF's sample viewer bends it
//! (`t·x·scale + b·y·scale + n·z`, normalised; the whole frame turned over
//! on a face seen from behind); metalness and roughness times the
//! texture's blue and green; the Lambert term with each light's ambient
//! share times the occlusion (`1 + strength·(texel − 1)`); the highlight of
//! the same GGX lobe as the specular fill, with the reflectance at normal
//! incidence tinted by the textured base colour where the surface is
//! metal; the material's layers (`KHR_materials_sheen`'s lobe over what
//! is beneath, dimmed by its albedo; then `KHR_materials_clearcoat`'s lobe
//! over the geometry's normal, dimming everything beneath, glow included,
//! by its Fresnel); the rim light from the bent normal; and the emissive
//! factor times its texel.
//!
//! Trade-offs. Everything is found per sample, so a mapped run costs a few
//! texture reads and one lighting evaluation a sample where a Gouraud run
//! costs three evaluations a triangle: the price of detail smaller than a
//! triangle. Highlights are found per sample here whatever
//! `--highlights` says. A posed mesh's tangents are its rest pose's turned
//! by its model matrix, not by its skin (a bend in a skinned limb bends
//! the normal map's frame only as far as its normals say).

use std::sync::Arc;

use glam::{Vec3, Vec3A};

use super::{Attributes, Eye, UvPlanes};
use crate::color::Lin;
use crate::scene::{Layers, Maps, Specular};
use crate::shade::Lights;
use crate::texture::{Sampler, Texture};

/// A texture to read and how (its sampler, under the plan's filter).
type Read = (Arc<Texture>, Sampler);

/// A run's maps, ready to read: set once a run.
#[derive(Clone, Debug)]
pub(crate) struct MapSet {
    /// The normal map and the scale of its x and y.
    normal: Option<(Read, f32)>,
    metallic_roughness: Option<Read>,
    /// The occlusion map and its strength.
    occlusion: Option<(Read, f32)>,
    emissive_map: Option<Read>,
    /// The specular-glossiness texture: its colour and its alpha.
    specular_glossiness: Option<(Read, Read)>,
    /// The emitted colour, in the renderer's linear units.
    emissive: Vec3A,
    /// The metallic-roughness factors (`None`: matte, no highlight).
    specular: Option<Specular>,
    /// Drawn in its colour, whatever the lights.
    unlit: bool,
    /// Its layers, as the plan draws them.
    layers: Layers,
    /// Whether it has a map (not layers alone).
    has_maps: bool,
    /// The maps read through the second coordinate set ([`Maps::second`]).
    second: u8,
}

impl MapSet {
    /// The metal share of its finish (before the metallic map).
    pub(crate) fn metallic(&self) -> f32 {
        self.specular
            .filter(|_| !self.unlit)
            .map_or(0.0, |s| s.metallic)
    }

    /// Whether it has a map (a run with layers alone has none).
    pub(crate) fn has_maps(&self) -> bool {
        self.has_maps
    }

    /// Whether a map reads the second coordinate set.
    pub(crate) fn reads_second(&self) -> bool {
        self.second != 0
    }

    /// Its layers, as the plan draws them.
    pub(crate) fn layers(&self) -> Layers {
        self.layers
    }

    /// `maps` and `layers` of a run of `finish`, the maps' textures taken
    /// from `textures` (an index out of range reads as no map) and read
    /// through `sampler` (the plan's filter applied to each texture's
    /// own).
    pub(crate) fn new(
        (maps, layers): (Maps, Layers),
        finish: &crate::scene::Finish,
        textures: &[Arc<Texture>],
        sampler: impl Fn(&Texture) -> Sampler,
    ) -> MapSet {
        let read = |i: u32| {
            textures.get(i as usize).map(|t| {
                let s = sampler(t);
                (t.clone(), s)
            })
        };
        let with = |m: Option<(u32, f32)>| m.and_then(|(i, k)| read(i).map(|r| (r, k)));
        MapSet {
            normal: with(maps.normal),
            metallic_roughness: maps.metallic_roughness.and_then(read),
            occlusion: with(maps.occlusion),
            emissive_map: maps.emissive.and_then(read),
            specular_glossiness: (maps.specular_glossiness).and_then(|(c, a)| read(c).zip(read(a))),
            emissive: finish.emissive.to_lanes(),
            specular: finish.specular,
            unlit: finish.unlit,
            layers,
            has_maps: !maps.is_empty(),
            second: maps.second,
        }
    }
}

/// A triangle's corners as the mapped fill reads them, in the set-up's
/// vertex order: unit normals, positions, tangents and bitangents in the
/// turned world.
pub(crate) struct Corners {
    pub normal: [Vec3; 3],
    pub world: [Vec3; 3],
    pub tangent: [Vec3; 3],
    pub bitangent: [Vec3; 3],
}

/// What the mapped fill reads of one triangle.
pub(crate) struct Mapped<'a> {
    pub set: &'a MapSet,
    pub corners: Corners,
    /// The base colour's texture, if any, and the coordinates' planes
    /// (every map is read through them).
    pub base: Option<(&'a Texture, Sampler)>,
    pub planes: &'a UvPlanes,
    /// The second coordinate set's planes, where a map reads it.
    pub planes2: Option<&'a UvPlanes>,
    /// The lights and the eye; `None` where nothing is lit.
    pub lights: Option<(&'a Lights, Eye)>,
    /// Whether the rim light is added.
    pub rim: bool,
    /// What its metal share reflects, where the plan draws it.
    pub environment: Option<&'a crate::scene::environment::EnvMap>,
}

impl Mapped<'_> {
    /// The colour at sample (`x`, `y`) of edge weights `e`; `flat`: the
    /// base colour is the triangle's one colour.
    #[inline(always)]
    pub(crate) fn at(&self, a: &Attributes, flat: bool, x: u32, y: u32, e: [f32; 3]) -> Lin {
        // Interpolated, rounded to whole steps as the vertices' colours
        // are: three equal colours give back that colour exactly (their
        // weighted mean can be an ulp off, which the texel and the glow
        // added below would carry into the rounding), so a one-colour
        // triangle is the same written flat or interpolated.
        let mut albedo = if flat {
            a.color[0]
        } else {
            Lin::round_lanes(a.lit(e))
        };
        let (uv, dx, dy) = self.planes.at(x, y);
        let read = |(t, s): &(&Texture, Sampler)| Vec3A::from(t.sample(s, uv, dx, dy));
        let s = self.set;
        let second = self.planes2.map(|p| p.at(x, y));
        // A map's texel, through the set it reads.
        let map_on = |(t, sampler): &Read, bit: u8| match second.filter(|_| s.second & bit != 0) {
            Some((uv, dx, dy)) => Vec3A::from(t.sample(sampler, uv, dx, dy)),
            None => read(&(&**t, *sampler)),
        };
        if let Some(base) = &self.base {
            albedo *= read(base);
        }
        let mut emitted = s.emissive;
        if let Some(m) = &s.emissive_map {
            emitted *= map_on(m, Maps::EMISSIVE);
        }
        let Some((lights, eye)) = self.lights.filter(|_| !s.unlit) else {
            return Lin::from_lanes(albedo + emitted);
        };
        let w = a.shares(e);
        let at = |c: &[Vec3; 3]| c[0] * w[0] + c[1] * w[1] + c[2] * w[2];
        let c = &self.corners;
        let p = at(&c.world);
        let v = eye.to_eye(p).normalize_or_zero();
        let (mut n, mut t, mut b) = (
            at(&c.normal).normalize_or_zero(),
            at(&c.tangent),
            at(&c.bitangent),
        );
        // Two-sided: a face seen from behind is shaded on its seen side,
        // its whole frame turned over.
        if n.dot(v) < 0.0 {
            (n, t, b) = (-n, -t, -b);
        }
        // A clear coat lies over the geometry, not the normal map.
        let geometric = n;
        if let Some((m, scale)) = &s.normal {
            let m = Vec3::from(map_on(m, Maps::NORMAL)) * 2.0 - Vec3::ONE;
            n = (t * (m.x * scale) + b * (m.y * scale) + n * m.z).normalize_or(n);
        }
        let occlusion = s.occlusion.as_ref().map_or(1.0, |(m, strength)| {
            1.0 + strength * (map_on(m, Maps::OCCLUSION).x - 1.0)
        });
        let (mut metallic, mut roughness) =
            s.specular.map_or((0.0, 1.0), |k| (k.metallic, k.roughness));
        if let Some(m) = &s.metallic_roughness {
            let texel = map_on(m, Maps::METALLIC_ROUGHNESS);
            metallic *= texel.z;
            roughness = (roughness * texel.y).max(Specular::MIN_ROUGHNESS);
        }
        let mut reflectance = s.specular.map(|k| Vec3A::from(k.reflectance));
        if let Some((colour, gloss)) = &s.specular_glossiness {
            // Specular colour times the texel; glossiness (1 − roughness)
            // times the texel's alpha.
            let bit = Maps::SPECULAR_GLOSSINESS;
            reflectance = reflectance.map(|r| r * map_on(colour, bit));
            roughness =
                (1.0 - (1.0 - roughness) * map_on(gloss, bit).x).max(Specular::MIN_ROUGHNESS);
        }
        let mut lit = albedo * (lights.lambert_occluded(n, p, occlusion) * (1.0 - metallic));
        if let (Some(k), Some(dielectric)) = (s.specular, reflectance) {
            let f0 = dielectric + (albedo / 65535.0 - dielectric) * metallic;
            let f90 = k.f90 + (1.0 - k.f90) * metallic;
            let a = roughness * roughness;
            if f90 > 0.0 {
                // `f90` times the lobe of `f0 / f90` (both 1 but for
                // `KHR_materials_specular`: exact).
                lit += lights.specular_a(n.into(), v.into(), p.into(), f0 / f90, a * a)
                    * (65535.0 * f90);
            }
            // The metal share's reflection, shadowed as the ambient light
            // is by the occlusion map.
            if let Some(env) = self.environment.filter(|_| metallic > 0.0) {
                let metal = albedo / 65535.0;
                lit += env.reflect(n.into(), v.into(), metal, roughness)
                    * (metallic * occlusion * 65535.0);
            }
        }
        let (n, v, p) = (Vec3A::from(n), Vec3A::from(v), Vec3A::from(p));
        if let Some(sheen) = s.layers.sheen {
            // What is beneath, dimmed by the sheen's albedo seen from `v`.
            let color = Vec3A::from(sheen.color);
            let e = crate::shade::sheen::albedo(n.dot(v), sheen.roughness);
            lit = lit * (1.0 - color.max_element() * e)
                + lights.sheen_a(n, v, p, color, sheen.roughness) * 65535.0;
        }
        if let Some(coat) = s.layers.clearcoat {
            // The coat's Fresnel at `n·v` dims what is beneath, its glow too.
            let nc = Vec3A::from(geometric);
            let m = 1.0 - nc.dot(v).clamp(0.0, 1.0);
            let keep = 1.0 - coat.factor * (0.04 + 0.96 * (m * m) * (m * m) * m);
            let a = coat.roughness * coat.roughness;
            let f0 = Vec3A::splat(0.04);
            let mut coated = lights.specular_a(nc, v, p, f0, a * a);
            if let Some(env) = self.environment {
                coated += env.reflect(nc, v, f0, coat.roughness) * occlusion;
            }
            lit = lit * keep + coated * (coat.factor * 65535.0);
            emitted *= keep;
        }
        if self.rim {
            lit += lights.rim_a(n.into());
        }
        Lin::from_lanes(lit + emitted)
    }
}
