//! What a run's material adds to its lit colour: its finish as the plan
//! draws it, set once a run.

use crate::plan::Plan;
use std::sync::Arc;

/// What a run's material adds to its lit colour, in the renderer's linear
/// units (0–65535 a channel): set once a run.
#[derive(Clone, Debug)]
pub(super) struct Surface {
    /// Its alpha and alpha texture, where the plan draws it through the
    /// see-through fill ([`Plan::sees_through`]).
    pub(super) see: Option<(crate::scene::Alpha, Option<Arc<crate::texture::Texture>>)>,
    /// The light it gives off (zero: none).
    pub(super) emissive: glam::Vec3A,
    /// Drawn in its colour, whatever the lights.
    pub(super) unlit: bool,
    /// Its highlight: reflectance at normal incidence over that at
    /// grazing incidence, α² (roughness to the fourth), and the
    /// reflectance at grazing incidence (see [`crate::scene::Specular::f90`]);
    /// `None`: matte.
    pub(super) shine: Option<(glam::Vec3A, f32, f32)>,
    /// The share of its colour lit diffusely: 1 − metallic.
    pub(super) diffuse: f32,
    /// Its metal share's reflection of the environment, where the plan
    /// draws it ([`Plan::reflects`]): the metal's colour, its share and
    /// its perceptual roughness.
    pub(super) reflect: Option<(glam::Vec3A, f32, f32)>,
    /// Its triangles go through the specular fill (the plan's
    /// [`Plan::shines`]).
    pub(super) shiny: bool,
}

impl Default for Surface {
    fn default() -> Surface {
        Surface {
            see: None,
            emissive: glam::Vec3A::ZERO,
            unlit: false,
            shine: None,
            diffuse: 1.0,
            reflect: None,
            shiny: false,
        }
    }
}

impl Surface {
    /// A run's surface as `plan` draws it; `base` its colour (a metal
    /// reflects in it).
    pub(super) fn of(
        finish: &crate::scene::Finish,
        base: crate::color::Lin,
        plan: &Plan,
    ) -> Surface {
        let shine = finish.specular.filter(|_| !finish.unlit).and_then(|s| {
            let base = glam::Vec3A::from(base.to_f32()) / 65535.0;
            let dielectric = glam::Vec3A::from(s.reflectance);
            let f0 = dielectric + (base - dielectric) * s.metallic;
            // A metal's f90 is 1; a dielectric's of no specular is 0: no
            // highlight.
            let f90 = s.f90 + (1.0 - s.f90) * s.metallic;
            let a = s.roughness * s.roughness;
            (f90 > 0.0).then(|| (f0 / f90, a * a, f90))
        });
        let shiny = plan.shines(shine.is_some());
        let shine = shine.filter(|_| shiny);
        let reflect = finish
            .specular
            .filter(|s| shine.is_some() && plan.reflects(s.metallic))
            .map(|s| {
                (
                    glam::Vec3A::from(base.to_f32()) / 65535.0,
                    s.metallic,
                    s.roughness,
                )
            });
        Surface {
            reflect,
            see: None,
            emissive: finish.emissive.to_lanes(),
            unlit: finish.unlit,
            diffuse: shine.map_or(1.0, |_| 1.0 - finish.specular.map_or(0.0, |s| s.metallic)),
            shine,
            shiny,
        }
    }

    /// A mapped run's surface: its vertices carry its base colour alone
    /// (unlit, without glow or a highlight: the mapped fill adds them per
    /// sample, from [`mapped::Mapping`]), and its triangles' corners'
    /// normals and positions are found (as a shining run's are).
    pub(super) fn mapped() -> Surface {
        Surface {
            unlit: true,
            shiny: true,
            ..Surface::default()
        }
    }
}
