//! The triangle stage: a mesh's faces, and the loose triangles, from
//! their vertices to the fill stage.
//!
//! A triangle whose three vertices are inside every clip plane goes
//! straight to the rasterizer; one that is not is clipped in homogeneous
//! space first ([`crate::clip`]). Culling is decided on the snapped
//! screen-space winding, exactly. Where the plan says so
//! ([`crate::Effect::Lean`]), untextured triangles inside every plane take a
//! lean path: no clip-path arguments are gathered, the signed area
//! (culled, no area) is found first and handed on, a bounding box of at
//! most eight samples is tested sample by sample at set-up
//! (`raster::SmallSetup`), and a triangle that covers no sample is neither
//! lit nor filled, nor are its colours read. The trade-off: a second code
//! path beside the general one, kept equal to it by tests of the set-up
//! (`raster`), of the planned pipeline against the full one and of one
//! band against several (`tests/render/plan.rs`).
//!
//! Lighting is evaluated here per face for flat shading, and per corner
//! for what the vertex stage did not light (back faces, the rim). Colours
//! are rounded to whole steps of linear light before they are
//! interpolated, so that a one-colour triangle interpolated (the full
//! pipeline) is the planned pipeline's plain write, bit for bit.

use glam::{DMat4, Mat4, Vec2, Vec3, Vec3A};

use super::vertex::{BAD_NORMAL, Deep, PLANES, Transforms, V, Verts};
use super::{Painter, Pass, Stage, Surface};
use crate::clip::{ClipVertex, Clipped, Snapped};
use crate::color::Lin;
use crate::fill::{self, Attributes, ScreenTriangle, Shine, UvPlanes};
use crate::options::{Highlights, RenderOptions};
use crate::plan::Effect;
use crate::plan::Extras;
use crate::raster::{
    self, CentreKey, Coverage, Culling, FloatSetup, Precision, Rejected, Setup, SnappedTriangle,
};
use crate::scene::{AlphaMode, Cull, Mesh, Scene};
use crate::shade::Shading;
use crate::texture::{Sampler, Texture};
use crate::transform;

/// A shining triangle's corners' unit normals and positions in the turned
/// world, for the specular fill; `None` for a triangle of another run.
pub(super) type Shining = Option<Corners>;

/// A triangle's corners' unit normals and positions in the turned world.
pub(super) type Corners = ([Vec3; 3], [Vec3; 3]);

/// Where a triangle's model-space vertices are, and the matrix taking them
/// to clip space: read only if it must be clipped.
#[derive(Clone, Copy)]
pub(super) struct Model<'a> {
    pub(super) positions: &'a [Vec3],
    pub(super) face: [u32; 3],
    pub(super) mvp: &'a DMat4,
    /// Model to the turned world, where facing is told.
    pub(super) world: &'a Mat4,
}

/// A triangle's texture, how to read it, and its vertices' coordinates.
#[derive(Clone, Copy)]
pub(super) struct Tex<'a> {
    pub(super) texture: &'a Texture,
    pub(super) sampler: Sampler,
    pub(super) uv: [Vec2; 3],
}

/// One mesh's faces as the triangle stage needs them.
pub(super) struct Faces<'a> {
    pub(super) mesh: &'a Mesh,
    /// Its model-space positions this frame (posed, or its own).
    pub(super) positions: &'a [Vec3],
    pub(super) transforms: &'a Transforms,
    pub(super) cull: Cull,
}

impl Painter<'_> {
    /// Draws one mesh's faces, whose vertices went through the vertex stage
    /// into `verts`.
    pub(super) fn faces(&mut self, stage: &Stage<'_>, f: &Faces<'_>, verts: Verts<'_>, pass: Pass) {
        let p = stage.plan;
        let mesh = f.mesh;
        for run in mesh.runs(Lin::from_srgb(mesh.color)) {
            let f = &Faces {
                cull: p.run_cull(mesh, &run.finish),
                ..*f
            };
            let blend = p[Effect::Alpha].run && run.finish.alpha.mode == AlphaMode::Blend;
            if blend != (pass == Pass::Blend) {
                continue;
            }
            let texture = p.texture(run.texture);
            // The plan's path; a run with a texture takes the general one,
            // which on the lean path skips (and counts) a triangle that
            // covers no sample once it is set up.
            let maps = p.per_sample(&run.finish, mesh.uvs.is_some());
            self.mapping.set = maps.map(|maps| {
                fill::MapSet::new(maps, &run.finish, &mesh.geometry.textures, |t| {
                    p.texture(Some(t)).map_or(t.sampler, |(_, s)| s)
                })
            });
            self.surface = match maps {
                Some(_) => Surface::mapped(),
                None => Surface::of(&run.finish, run.color, p),
            };
            if p.sees_through(&run.finish.alpha) {
                // Its alpha texture is read through the base texture's
                // coordinates: none without one.
                let alpha_texture = (run.finish.alpha.texture)
                    .filter(|_| texture.is_some())
                    .and_then(|i| mesh.geometry.textures.get(i as usize).cloned());
                self.surface.see = Some((run.finish.alpha, alpha_texture));
            }
            let lean = p[Effect::Lean].run
                && texture.is_none()
                && self.surface.see.is_none()
                && self.mapping.set.is_none();
            // A metal's colour is not lit diffusely: its share, once a run.
            let diffuse = self.surface.diffuse;
            // Converted to lanes once a run, not once a face.
            let run_color = run.color.to_lanes() * diffuse;
            // Every face is handed to the pipeline: counted once a run.
            self.stats.triangles_in += run.faces.len() as u64;
            let mut sorted = std::mem::take(self.sorted);
            let faces = if blend {
                super::back_to_front(run.faces.clone(), f, &mut sorted);
                &sorted.faces[..]
            } else {
                &mesh.faces[run.faces.clone()]
            };
            // Two copies of the loop: a matte run's carries no trace of the
            // specular fill (its frames cost what they did before it); and
            // a mapped run's loop of its own.
            if self.mapping.set.is_some() {
                let ids = if blend {
                    super::Ids::Listed(&sorted.ids)
                } else {
                    super::Ids::Range(run.faces)
                };
                self.run_mapped(stage, f, verts, ids, (texture, run_color));
            } else {
                // A shining run keeps its extras (`Plan::vertex_extras`).
                let run = (lean, texture, run_color, diffuse);
                const ALL: u8 = Extras::All as u8;
                const DEEP: u8 = Extras::Deep as u8;
                const FOUND: u8 = Extras::Found as u8;
                let s = stage;
                match (self.surface.shiny, verts.kept.extras()) {
                    (true, _) => self.run_faces::<true, ALL>(s, f, verts, faces, run),
                    (false, Extras::Found) => {
                        self.run_faces::<false, FOUND>(s, f, verts, faces, run)
                    }
                    (false, Extras::Deep) => self.run_faces::<false, DEEP>(s, f, verts, faces, run),
                    (false, Extras::All) => self.run_faces::<false, ALL>(s, f, verts, faces, run),
                }
            }
            *self.sorted = sorted;
        }
    }

    /// Draws one run's faces: `SHINY` says whether they go through the
    /// specular fill (the surface's `shiny`, as a constant), `KEEP` what
    /// their corners keep (an `Extras` as `u8`: with none, depth and light found here).
    #[inline(never)]
    #[allow(clippy::type_complexity)]
    fn run_faces<const SHINY: bool, const KEEP: u8>(
        &mut self,
        stage: &Stage<'_>,
        f: &Faces<'_>,
        verts: Verts<'_>,
        faces: &[[u32; 3]],
        (lean, texture, run_color, diffuse): (bool, Option<(&Texture, Sampler)>, Vec3A, f32),
    ) {
        let mesh = f.mesh;
        let verts = verts.trimmed::<KEEP>();
        // Where the corners' depth and light are found, when not kept.
        let mut scratch = Deep::SCRATCH;
        let culling = Culling::of(f.cull);
        let core = &verts.core;
        // No sample centre in its box (from the keys): nothing drawn,
        // whatever its area or winding; told first, as most common, in a
        // loop of its own that passes over such faces, counted once the run
        // is done. A vertex outside a plane has a key that tells nothing
        // (`CentreKey::NEVER_EMPTY`), so a face past it is inside them all.
        let keys = |f: &[u32; 3]| f.map(|i| core.keys[i as usize]);
        let mut rest = faces.iter();
        let mut passed = 0;
        while let Some(face) = if lean {
            rest.find(|f| !CentreKey::box_is_empty(keys(f)))
        } else {
            rest.next()
        } {
            passed += 1;
            let base = || base_colors(mesh, face, run_color, diffuse);
            let inside = core.code(face[0]) | core.code(face[1]) | core.code(face[2]) == 0;
            if inside && lean {
                // Then culled or without area: rejected as its set-up
                // would reject it (snapped, so in range).
                let t = match SnappedTriangle::culled_by(face.map(|i| core.fixed(i)), culling) {
                    Ok(t) => t,
                    Err(r) => {
                        self.stats.raster.count_rejected(r);
                        continue;
                    }
                };
                self.stats.raster.triangles_drawn += 1;
                if KEEP == Extras::Found as u8 {
                    // Its corners found (and lit) only if it covers a
                    // sample; a shining run keeps them all.
                    debug_assert!(!SHINY);
                    self.lean_found(
                        stage,
                        f,
                        (&verts, face, &mut scratch),
                        (run_color, diffuse),
                        &t,
                    );
                    continue;
                }
                self.count_lazy(stage, &verts);
                // A shining run's normals and positions, found only once
                // it covers a sample.
                let shine = SHINY.then_some(Model {
                    positions: f.positions,
                    face: *face,
                    mvp: &f.transforms.mvp64,
                    world: &f.transforms.model,
                });
                self.inside_triangle::<KEEP>(
                    stage,
                    (&verts, face, &mut scratch),
                    (base, shine),
                    &t,
                );
                continue;
            }
            let base = base();
            let tex = texture.map(|(texture, sampler)| Tex {
                texture,
                sampler,
                uv: match &mesh.uvs {
                    Some(uv) => face.map(|i| uv[i as usize]),
                    None => [Vec2::ZERO; 3],
                },
            });
            let model = Model {
                positions: f.positions,
                face: *face,
                mvp: &f.transforms.mvp64,
                world: &f.transforms.model,
            };
            self.count_lazy(stage, &verts);
            let v = verts.of_as::<KEEP>(*face, &mut scratch);
            self.triangle::<SHINY, false>(stage, v, base, f.cull, model, tex);
        }
        if lean {
            self.stats.raster.found_empty += (faces.len() - passed) as u64;
        }
    }

    /// Draws the loose triangles, each through the vertex stage on its own.
    pub(super) fn loose(
        &mut self,
        scene: &Scene,
        opts: &RenderOptions,
        stage: &Stage<'_>,
        vp: Mat4,
        turn: Mat4,
    ) {
        let p = stage.plan;
        let cull = opts.cull.unwrap_or(Cull::None);
        let loose = Transforms::new(vp, turn);
        let loose_tests = p.clip_tests(scene.meshes.len());
        // Loose triangles have no material: the plain finish.
        self.surface = Surface::default();
        self.mapping.set = None;
        self.stats.triangles_in += scene.triangles.len() as u64;
        for tri in &scene.triangles {
            let [a, b, c] = tri.vertices;
            let normal = transform::face_normal(a, b, c);
            self.verts.clear();
            self.kept.clear();
            let vertices = (&tri.vertices[..], &[normal; 3][..]);
            self.vertex_stage(stage, &loose, vertices, loose_tests, Extras::All);
            let (verts, kept) = (std::mem::take(self.verts), std::mem::take(self.kept));
            let v = Verts::new((verts.all(), kept.all()), vertices, &loose, stage);
            self.triangle::<false, false>(
                stage,
                v.of([0, 1, 2], &mut { Deep::SCRATCH }),
                tri.color
                    .at_vertices()
                    .map(|c| Lin::from_srgb(c).to_lanes()),
                cull,
                Model {
                    positions: &tri.vertices,
                    face: [0, 1, 2],
                    mvp: &loose.mvp64,
                    world: &loose.model,
                },
                p.texture(None).map(|(texture, sampler)| Tex {
                    texture,
                    sampler,
                    uv: [Vec2::ZERO; 3],
                }),
            );
            (*self.verts, *self.kept) = (verts, kept);
        }
    }

    /// Sets up, lights, clips if it must, and rasterizes one triangle;
    /// `model` is its vertices' model-space positions and the matrix taking
    /// them to clip space, for the clip path. The caller counts it in
    /// [`super::FrameStats::triangles_in`].
    /// `MAPPED`: a mapped run's (see `mapped.rs`), whose fill is the
    /// mapped fill; its own copy of this and the functions below it, so
    /// that the unmapped copies carry no branch for maps.
    pub(super) fn triangle<const SHINY: bool, const MAPPED: bool>(
        &mut self,
        stage: &Stage<'_>,
        v: [V<'_>; 3],
        base: [Vec3A; 3],
        cull: Cull,
        model: Model<'_>,
        tex: Option<Tex<'_>>,
    ) {
        let (texture, uv) = match tex {
            Some(t) => (Some((t.texture, t.sampler)), t.uv),
            None => (None, [Vec2::ZERO; 3]),
        };
        if (v[0].code | v[1].code | v[2].code) & BAD_NORMAL != 0 {
            self.stats.dropped_non_finite_normals += 1;
            return;
        }
        if v[0].code & v[1].code & v[2].code & PLANES != 0 {
            self.stats.clip_rejected += 1;
            return;
        }
        let shiny = SHINY;
        if v[0].code | v[1].code | v[2].code == 0 {
            // Inside every clip plane: set up first, so that culled
            // triangles and those covering no sample are never lit (the
            // full pipeline lights them all, first).
            let early = stage
                .plan
                .full
                .then(|| self.shade(stage, v, base, !front_facing(v)));
            let fixed = v.map(|v| v.fixed());
            let xy = v.map(|v| v.xy().map(f64::from));
            let screen = |color| ScreenTriangle {
                xy,
                z: v.map(|v| v.deep().z),
                inv_w: v.map(|v| v.deep().inv_w),
                color,
                uv,
                // Found once a triangle is set up and lit, not for one culled.
                shine: corners(shiny, stage, v, &model),
            };
            let grid = self.fb.grid();
            match stage.precision {
                Precision::Fixed => {
                    let band = self.fb.band();
                    let setup =
                        SnappedTriangle::new(fixed, cull).map(|t| Setup::of(&t, grid, band));
                    self.inside_setup::<_, MAPPED>(
                        stage,
                        &setup,
                        (v, base),
                        early,
                        screen,
                        texture,
                    );
                }
                Precision::F64 => {
                    let setup = FloatSetup::<f64>::new(xy, grid, cull);
                    self.inside_setup::<_, MAPPED>(
                        stage,
                        &setup,
                        (v, base),
                        early,
                        screen,
                        texture,
                    );
                }
                Precision::F32 => {
                    let setup = FloatSetup::<f32>::new(xy, grid, cull);
                    self.inside_setup::<_, MAPPED>(
                        stage,
                        &setup,
                        (v, base),
                        early,
                        screen,
                        texture,
                    );
                }
            }
            return;
        }
        // Clipped: lit before clipping (colours are interpolated along the
        // cut edges), facing told in the world.
        let shine = corners(shiny, stage, v, &model);
        let Model {
            positions,
            face,
            mvp,
            world,
        } = model;
        let w = face.map(|i| world.transform_point3(positions[i as usize]));
        let normal = transform::face_normal(w[0], w[1], w[2]);
        let back = normal.dot(transform::direction(stage.eye.to_eye(w[0]))) < 0.0;
        let color = self.shade(stage, v, base, back);
        let verts = [0, 1, 2].map(|i| ClipVertex {
            pos: positions[face[i] as usize].as_dvec3().extend(1.0),
            color: color[i],
            uv: uv[i],
            weights: Vec3::AXES[i],
            snapped: (v[i].code == 0).then_some(Snapped {
                fixed: v[i].fixed(),
                xy: v[i].xy(),
                z: v[i].deep().z,
                inv_w: v[i].deep().inv_w,
            }),
        });
        let mut poly = *self.poly;
        match stage.clipper.clip(&verts, mvp, &stage.viewport, &mut poly) {
            Clipped::Rejected => self.stats.clip_rejected += 1,
            Clipped::Clipped | Clipped::Inside => {
                self.stats.clipped += 1;
                for tri in poly.triangles() {
                    // A piece's normals and positions, from its corners'
                    // weights in the whole triangle.
                    let shine = shine.map(|(n, p)| {
                        let at = |w: Vec3, a: [Vec3; 3]| a[0] * w.x + a[1] * w.y + a[2] * w.z;
                        (
                            tri.map(|v| at(v.weights, n).normalize_or_zero()),
                            tri.map(|v| at(v.weights, p)),
                        )
                    });
                    let screen = ScreenTriangle {
                        xy: tri.map(|v| v.xy),
                        z: tri.map(|v| v.z),
                        inv_w: tri.map(|v| v.inv_w),
                        color: tri.map(|v| v.color),
                        uv: tri.map(|v| v.uv),
                        shine,
                    };
                    let grid = self.fb.grid();
                    match stage.precision {
                        Precision::Fixed => {
                            let band = self.fb.band();
                            let setup = SnappedTriangle::new(tri.map(|v| v.fixed), cull)
                                .map(|t| Setup::of(&t, grid, band));
                            self.set_up_and_fill::<_, MAPPED>(&setup, &screen, stage, texture);
                        }
                        Precision::F64 => {
                            let setup = FloatSetup::<f64>::new(screen.xy, grid, cull);
                            self.set_up_and_fill::<_, MAPPED>(&setup, &screen, stage, texture);
                        }
                        Precision::F32 => {
                            let setup = FloatSetup::<f32>::new(screen.xy, grid, cull);
                            self.set_up_and_fill::<_, MAPPED>(&setup, &screen, stage, texture);
                        }
                    }
                }
            }
        }
        *self.poly = poly;
    }

    /// A triangle inside every clip plane, set up with the frame's
    /// precision, on the general path: counted, then lit (unless the full
    /// pipeline lit it `early`) and filled. On the lean path (textured and
    /// loose triangles) one that covers no sample is neither lit nor filled
    /// (the full pipeline fills it anyway: the same nothing), and is
    /// counted as its walk would count it.
    #[inline(always)]
    pub(super) fn inside_setup<C: Coverage, const MAPPED: bool>(
        &mut self,
        stage: &Stage<'_>,
        setup: &Result<C, Rejected>,
        (v, base): ([V<'_>; 3], [Vec3A; 3]),
        early: Option<[Vec3; 3]>,
        screen: impl Fn([Vec3; 3]) -> ScreenTriangle,
        texture: Option<(&Texture, Sampler)>,
    ) {
        if let Some(s) = self.setup(setup) {
            if stage.plan[Effect::Lean].run && !s.covers_any() {
                self.stats.raster.samples_tested += s.bbox_samples();
                return;
            }
            let c = early.unwrap_or_else(|| self.shade(stage, v, base, !s.ccw()));
            self.fill::<_, MAPPED>(s, &screen(c), stage, texture);
        }
    }

    /// A clipped piece, set up with the frame's precision: counted and
    /// filled (it was lit before clipping).
    #[inline(always)]
    pub(super) fn set_up_and_fill<C: Coverage, const MAPPED: bool>(
        &mut self,
        setup: &Result<C, Rejected>,
        screen: &ScreenTriangle,
        stage: &Stage<'_>,
        texture: Option<(&Texture, Sampler)>,
    ) {
        if let Some(s) = self.setup(setup) {
            self.fill::<_, MAPPED>(s, screen, stage, texture);
        }
    }

    /// The triangle's colour at each vertex. `back`: seen from behind, so
    /// lit on its other side (two-sided lighting).
    /// Colours are linear light in [0, 65535], rounded to whole steps, so
    /// that interpolating three equal colours gives back exactly that
    /// colour (the full pipeline's interpolation of a one-colour triangle
    /// then matches the planned pipeline's plain write, bit for bit).
    #[inline(always)]
    pub(super) fn shade(
        &mut self,
        stage: &Stage<'_>,
        v: [V<'_>; 3],
        base: [Vec3A; 3],
        back: bool,
    ) -> [Vec3; 3] {
        let round = |c: Vec3A| Vec3::from(Lin::round_lanes(c));
        let c = if self.surface.unlit {
            base
        } else {
            self.light(stage, v, base, back)
        };
        if stage.plan[Effect::Glow].run {
            // Emitted light is added after lighting (zero for a run that
            // gives off none, which changes nothing: colours are not
            // negative).
            self.stats.glowing_triangles += 1;
            let e = self.surface.emissive;
            return [round(c[0] + e), round(c[1] + e), round(c[2] + e)];
        }
        [round(c[0]), round(c[1]), round(c[2])]
    }

    /// [`Painter::shade`] before rounding, in SIMD lanes (the same
    /// operations per channel as three f32s).
    #[inline(always)]
    pub(super) fn light(
        &mut self,
        stage: &Stage<'_>,
        v: [V<'_>; 3],
        base: [Vec3A; 3],
        back: bool,
    ) -> [Vec3A; 3] {
        let b = |i: usize| base[i];
        match stage.plan.shading {
            Shading::None => [b(0), b(1), b(2)],
            Shading::Flat => {
                self.stats.lighting_evaluations += 1;
                let side = if back { -1.0 } else { 1.0 };
                let face = transform::face_normal(v[0].world(), v[1].world(), v[2].world());
                let light = if stage.plan[Effect::Falloff].run {
                    lit_at_centre(stage, v, face * side)
                } else {
                    stage.lights.lambert_a(face * side)
                };
                let lit = [b(0) * light, b(1) * light, b(2) * light];
                if !stage.plan[Effect::Rim].run {
                    return lit;
                }
                let rim = stage.lights.rim_a(face * side);
                lit.map(|c| c + rim)
            }
            Shading::Smooth if back && stage.plan[Effect::Falloff].run => {
                self.stats.lighting_evaluations += 3;
                back_lit_at(stage, v, base)
            }
            Shading::Smooth if back => {
                self.stats.lighting_evaluations += 3;
                let rim = stage.plan[Effect::Rim].run;
                let l = |i: usize| {
                    let lit = b(i) * stage.lights.lambert_a(-v[i].normal());
                    if rim {
                        lit + stage.lights.rim_a(-v[i].normal())
                    } else {
                        lit
                    }
                };
                [l(0), l(1), l(2)]
            }
            Shading::Smooth if stage.plan[Effect::Rim].run => {
                // The rim from each corner's normal, here rather than in the
                // vertex stage: a frame without a rim keeps its vertices as
                // small and its vertex loop as short as before.
                let l = |i: usize| {
                    b(i) * Vec3A::from(v[i].deep().light) + stage.lights.rim_a(v[i].normal())
                };
                [l(0), l(1), l(2)]
            }
            Shading::Smooth => {
                let l = |i: usize| b(i) * Vec3A::from(v[i].deep().light);
                [l(0), l(1), l(2)]
            }
        }
    }

    /// A set-up screen triangle, counted; `None` when it was rejected.
    /// Borrowed, not moved: a set-up triangle is a few hundred bytes.
    #[inline(always)]
    pub(super) fn setup<'s, C: Coverage>(
        &mut self,
        setup: &'s Result<C, Rejected>,
    ) -> Option<&'s C> {
        match setup {
            Ok(s) => {
                self.stats.raster.triangles_drawn += 1;
                Some(s)
            }
            Err(r) => {
                self.stats.raster.count_rejected(*r);
                None
            }
        }
    }

    /// Walks a set-up triangle and writes its samples: depth-tested, or
    /// (when the plan skips depth) only where still empty; one colour, or
    /// interpolated, through `1/w` where the plan asks for it; times its
    /// texture, where it has one.
    pub(super) fn fill<C: Coverage, const MAPPED: bool>(
        &mut self,
        setup: &C,
        t: &ScreenTriangle,
        stage: &Stage,
        texture: Option<(&Texture, Sampler)>,
    ) {
        if stage.exact {
            let done = fill::accumulate_exact(self.acc, self.fb.grid(), t, texture);
            self.stats.textured_samples += done.written;
            self.stats.raster.samples_covered += done.covered;
            self.stats.raster.samples_tested += done.tested;
            return;
        }
        let o = setup.order();
        let a = Attributes::new(
            o,
            setup.inv_area(),
            [t.z, t.inv_w],
            t.color,
            stage.plan[Effect::Perspective].run,
        );
        let flat = !stage.plan.interpolates(&t.color);
        if MAPPED || self.surface.see.is_some() {
            self.fill_special(setup, t, &a, flat, stage, texture);
            return;
        }
        if let Some(corners) = t.shine {
            let corners = in_order(o, corners);
            let planes = texture.map(|_| UvPlanes::new(t, stage.plan[Effect::Perspective].run));
            let tex = texture.zip(planes.as_ref()).map(|((t, s), p)| (t, s, p));
            self.fill_shiny(setup, &a, flat, (tex, corners), stage);
            return;
        }
        match texture {
            Some((texture, sampler)) => {
                // Texture coordinates are planes over the screen, found
                // from the triangle as given (their order does not matter).
                let planes = UvPlanes::new(t, stage.plan[Effect::Perspective].run);
                let done = self
                    .sink(stage)
                    .textured(setup, &a, flat, (texture, sampler, &planes));
                self.stats.textured_samples += done.written;
                // Texture coordinates are interpolated, whatever the colour.
                self.stats.count_fill(done);
            }
            None => self.fill_colour(setup, &a, flat, stage),
        }
    }

    /// Where a triangle's samples go, as the plan says to test them.
    #[inline(always)]
    pub(super) fn sink(&mut self, stage: &Stage) -> fill::Sink<'_> {
        fill::Sink {
            fb: self.fb.reborrow(),
            depth: stage.plan[Effect::Depth].run,
            traversal: stage.traversal,
        }
    }

    /// [`Painter::fill`] of a triangle of a shining run (with its texture,
    /// if any, and its corners' normals and positions), counted.
    #[inline(always)]
    pub(super) fn fill_shiny<C: Coverage>(
        &mut self,
        setup: &C,
        a: &Attributes,
        flat: bool,
        (tex, corners): (Option<(&Texture, Sampler, &UvPlanes)>, Corners),
        stage: &Stage,
    ) {
        let shine = Shine::new(
            corners,
            self.surface.shine,
            (&stage.lights, stage.eye),
            stage.highlights == Highlights::Vertex,
            stage.environment.zip(self.surface.reflect),
        );
        let done = self.sink(stage).shiny(setup, a, flat, tex, Some(&shine));
        if tex.is_some() {
            self.stats.textured_samples += done.written;
        }
        if self.surface.shine.is_some() {
            self.stats.specular_samples += done.written;
        }
        if stage.environment.is_some() && self.surface.reflect.is_some() {
            self.stats.reflecting_samples += done.written;
        }
        self.stats.count_fill(done);
    }

    /// [`Painter::fill`] of a triangle without a texture, counted.
    #[inline(always)]
    pub(super) fn fill_colour<C: Coverage>(
        &mut self,
        setup: &C,
        a: &Attributes,
        flat: bool,
        stage: &Stage,
    ) {
        let done = self.sink(stage).colour(setup, a, flat);
        self.stats.count_fill(done);
    }
}

/// A face's base colours: its corners' own (times the run's diffuse
/// share), or the run's.
#[inline(always)]
pub(super) fn base_colors(
    mesh: &Mesh,
    face: &[u32; 3],
    run_color: Vec3A,
    diffuse: f32,
) -> [Vec3A; 3] {
    match &mesh.colors {
        Some(c) if diffuse != 1.0 => face.map(|i| c[i as usize].to_lanes() * diffuse),
        Some(c) => face.map(|i| c[i as usize].to_lanes()),
        None => [run_color; 3],
    }
}

/// Whether the snapped screen triangle is counter-clockwise (the same
/// signed area every set-up finds).
fn front_facing(v: [V<'_>; 3]) -> bool {
    raster::signed_area2(&v.map(|v| v.fixed())) > 0
}

/// What the specular fill reads of a triangle of a shiny run: its corners'
/// unit normals (smooth shading's, or the face's) and positions in the
/// turned world; `None` for other runs.
#[inline(always)]
pub(super) fn corners(shiny: bool, stage: &Stage<'_>, v: [V<'_>; 3], model: &Model<'_>) -> Shining {
    if !shiny {
        return None;
    }
    let world = model
        .face
        .map(|i| model.world.transform_point3(model.positions[i as usize]));
    let normal = match stage.plan.shading {
        Shading::Smooth => v.map(|v| v.normal()),
        _ => [transform::face_normal(world[0], world[1], world[2]); 3],
    };
    Some((normal, world))
}

/// A triangle's corners in the set-up's vertex `order`.
#[inline(always)]
pub(super) fn in_order(order: [usize; 3], (normal, world): Corners) -> Corners {
    (order.map(|i| normal[i]), order.map(|i| world[i]))
}

/// The light on a flat face of normal `n` at its centre, from lights
/// whose light depends on where the surface is (out of line, as
/// [`back_lit_at`], for the same reason).
#[inline(never)]
fn lit_at_centre(stage: &Stage<'_>, v: [V<'_>; 3], n: Vec3) -> Vec3A {
    let centre = (v[0].world() + v[1].world() + v[2].world()) / 3.0;
    stage.lights.lambert_at(n, centre)
}

/// A smooth triangle's back lit at its corners by lights whose light
/// depends on where a corner is ([`Painter::light`]'s rare arm, out of
/// line so that the common arms stay as short as they were).
#[inline(never)]
fn back_lit_at(stage: &Stage<'_>, v: [V<'_>; 3], base: [Vec3A; 3]) -> [Vec3A; 3] {
    let l = |i: usize| {
        let lit = base[i] * stage.lights.lambert_at(-v[i].normal(), v[i].world());
        if stage.plan[Effect::Rim].run {
            lit + stage.lights.rim_a(-v[i].normal())
        } else {
            lit
        }
    };
    [l(0), l(1), l(2)]
}
