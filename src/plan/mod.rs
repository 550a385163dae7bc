//! The planner: which stages a frame needs, decided once per frame from
//! bounds and flags (never per sample), so that a scene that needs no depth
//! test, no lighting, no interpolation and no clipping does not pay for
//! them, and a scene that needs them gets them.
//!
//! Each stage or effect it decides on is declared once, in `effects.rs`
//! ([`Effect`]): its name, when it runs and when it is skipped, what
//! `--explain` reports of it, its counter and its witness.
//!
//! Every skip is exact: the frame is bit for bit the one the full pipeline
//! ([`Pipeline::Full`], `--full-pipeline`) draws, which a property test
//! checks on random scenes. Where skipping the depth test is allowed, the
//! renderer writes a sample only if it is still empty, which is what the
//! depth test does for primitives of equal depth (the first drawn stays),
//! and what it does anywhere for primitives that never overlap.
//!
//! When unsure, the planner runs the stage. A lone closed convex mesh with
//! back faces culled keeps its depth test: its exact front faces never
//! overlap, but snapped to the sample grid a nearly edge-on face can fold
//! over its neighbour (a property test found such a sphere), and the clip
//! path's f64 triangles need not meet their f32 neighbours exactly.
//! Clip tests are skipped for a group only when its bounding box is inside
//! every plane with room for the vertex stage's f32 rounding
//! ([`Clipper::box_inside`]).
//!
//! One decision is about speed alone, never about the picture: which path
//! a triangle inside every clip plane takes ([`Effect::Lean`]). On the lean
//! path (the planned pipeline's fixed point, sampled, walked within each
//! box) culling and area come from the snapped vertices, an empty box from
//! their centre keys, and a triangle is lit and filled only if it covers a
//! sample; a triangle it stops early is counted exactly as its set-up and
//! walk would count it (a test compares every count with the full
//! pipeline's). The general path sets up every triangle in the options'
//! precision and walks it with their traversal: the full pipeline, exact
//! coverage and the comparison modes take it.
//!
//! The other speed decision is how many bands of rows the frame is drawn
//! in, one thread each ([`Plan::bands`]): as many as there are cores for
//! frames of [`PARALLEL_CELLS`] cells or more (below that, the per-band
//! set-up of every triangle and starting the threads cost more than they
//! gain), as many as [`Threads::Exactly`] asks for, and one wherever a
//! band could not draw its rows alone: anti-aliasing (its passes accumulate
//! over the whole grid), the f64 and f32 set-ups (comparison modes, whose
//! boxes are clamped to the whole grid only) and the full-grid scan.

use std::fmt;

use glam::{Mat4, Vec3};

use crate::clip::Clipper;
use crate::options::{Aa, Interpolation, Pipeline, RenderOptions, Wire};
use crate::raster::{Precision, Traversal};
use crate::scene::{Projection, Scene, TriangleColor};
use crate::shade::Shading;
use crate::texture::{FilterMode, Sampler, Texture};

mod bands;
mod effects;
pub use bands::Bands;
use bands::bands;
pub use effects::Effect;

/// One stage's decision, and why.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Decision {
    /// Whether the stage runs.
    pub run: bool,
    /// Why.
    pub why: &'static str,
}

impl Decision {
    const fn run(why: &'static str) -> Decision {
        Decision { run: true, why }
    }

    const fn skip(why: &'static str) -> Decision {
        Decision { run: false, why }
    }
}

impl fmt::Display for Decision {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{:<4}  {}",
            if self.run { "run" } else { "skip" },
            self.why
        )
    }
}

/// The stages of one frame: every decision the renderer acts on, made
/// here and nowhere else.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Plan {
    /// Each stage's or effect's decision, indexed by [`Effect`]
    /// (`plan[Effect::Depth].run`).
    decisions: [Decision; Effect::COUNT],
    /// The shading applied: the options' shading when the scene is lit,
    /// [`Shading::None`] otherwise.
    pub shading: Shading,
    /// The filtering forced on every texture (`None`: each sampler's own).
    pub filter: Option<FilterMode>,
    /// The full pipeline: every stage on every primitive.
    pub full: bool,
    /// Per group (each mesh in order, then the loose triangles): whether
    /// its vertices are tested against the clip planes.
    clip_tests: Vec<bool>,
    /// Per mesh: whether it is posed.
    poses: Vec<bool>,
    /// Per mesh: whether it has so many vertices for the frame's samples
    /// ([`Plan::DEFER_PER_SAMPLE`]) that its corners' depth and light are found
    /// at set-up, where a face covers a sample, rather than by the
    /// vertex stage for every vertex (see [`Plan::vertex_extras`]).
    defers: Vec<bool>,
    /// Per mesh: which faces it culls ([`Plan::cull`]).
    culls: Vec<crate::scene::Cull>,
    /// `--cull`: every face culled so, whatever the file says.
    cull_asked: Option<crate::scene::Cull>,
    /// How many bands of rows the frame is drawn in, one thread each.
    pub bands: Bands,
}

/// What the vertex stage keeps of a mesh's vertices beyond the 14 bytes
/// every face reads (snapped position, centre key, outcode), as the plan
/// decides ([`Plan::vertex_extras`]): memory and speed alone, the frame is
/// the same whichever.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum Extras {
    /// Nothing: the depth, `1/w` and light of the corners of a face that
    /// covers a sample are found again at set-up (a large model seen
    /// small).
    Found,
    /// Depth, `1/w` and light (20 bytes), all that a lean face reads: a
    /// model with few vertices for the frame's samples.
    Deep,
    /// Those and the world position, normal and unsnapped screen position
    /// (52 bytes), for faces that may read them.
    All,
}

/// The culling that `sides` asks for, `own` where it says nothing.
fn sides_cull(sides: crate::scene::Sides, own: crate::scene::Cull) -> crate::scene::Cull {
    use crate::scene::{Cull, Sides};
    match sides {
        Sides::Single => Cull::Back,
        Sides::Double => Cull::None,
        Sides::Unsaid => own,
    }
}

/// [`Plan::cull`] of `mesh`.
fn mesh_cull(mesh: &crate::scene::Mesh, asked: Option<crate::scene::Cull>) -> crate::scene::Cull {
    asked.unwrap_or_else(|| {
        let own = mesh.cull;
        let differs = (mesh.materials.iter()).any(|m| sides_cull(m.finish.sides, own) != own);
        if differs {
            crate::scene::Cull::None
        } else {
            own
        }
    })
}

const FORCED: &str = "forced on by the full pipeline";
const FORCED_KEPT: &str = "the full pipeline keeps every vertex's extras";

impl std::ops::Index<Effect> for Plan {
    type Output = Decision;

    fn index(&self, e: Effect) -> &Decision {
        &self.decisions[e as usize]
    }
}

impl Plan {
    /// Vertices a sample above which a mesh's corners' depth and light are
    /// found at set-up rather than kept by the vertex stage
    /// ([`Plan::vertex_extras`]): found again, a corner costs about four times
    /// what a vertex costs in the vertex stage's lanes, and each vertex is the
    /// corner of about six faces, but only a face that covers a sample has
    /// its corners found; so the more vertices a sample, the more finding
    /// them at set-up saves, and about here it starts to (a vertex found
    /// keeps 14 bytes rather than 34).
    pub const DEFER_PER_SAMPLE: usize = 6;

    /// Plans a frame of `scene` drawn with `opts`; `vp` is the camera's
    /// view-projection for this frame, `turn` the scene's turn and
    /// `clipper` the clip planes of the frame's grid.
    #[must_use]
    pub fn new(
        scene: &Scene,
        opts: &RenderOptions,
        vp: Mat4,
        turn: Mat4,
        clipper: &Clipper,
    ) -> Plan {
        let mut plan = Plan {
            decisions: [Decision::run(FORCED); Effect::COUNT],
            filter: opts.filter,
            shading: opts.shading,
            full: true,
            clip_tests: Vec::new(),
            poses: Vec::new(),
            defers: Vec::new(),
            culls: Vec::new(),
            cull_asked: None,
            bands: Bands {
                count: 1,
                why: "not planned yet",
            },
        };
        plan.replan(scene, opts, vp, turn, clipper);
        plan
    }

    /// [`Plan::new`] in place, reusing this plan's memory.
    pub fn replan(
        &mut self,
        scene: &Scene,
        opts: &RenderOptions,
        vp: Mat4,
        turn: Mat4,
        clipper: &Clipper,
    ) {
        let full = opts.pipeline == Pipeline::Full;
        let lit = opts.shading != Shading::None && !scene.lights.is_empty();
        let lighting = if lit {
            Decision::run("the scene has lights and the shading uses them")
        } else if scene.lights.is_empty() {
            Decision::skip("the scene has no lights")
        } else {
            Decision::skip("shading is none")
        };
        let shading = if lit { opts.shading } else { Shading::None };
        // A lit material's layers (an unlit one has none).
        let layered = |has: fn(&crate::scene::Layers) -> bool| {
            (scene.meshes.iter().flat_map(|m| m.materials.iter()))
                .any(|r| !r.finish.unlit && has(&r.finish.layers))
        };
        let rim = if !lit {
            Decision::skip("nothing is lit")
        } else if full {
            Decision::run(FORCED)
        } else if opts.rim.is_some() {
            Decision::run("a rim light was asked for")
        } else {
            Decision::skip("no rim light was asked for")
        };
        let vertex_colors = scene
            .triangles
            .iter()
            .any(|t| matches!(t.color, TriangleColor::PerVertex(_)))
            || scene.meshes.iter().any(|m| m.colors.is_some());
        let textured = scene.meshes.iter().any(|m| m.textured());
        let texturing = if full {
            Decision::run(FORCED)
        } else if textured {
            Decision::run("a material has a texture: its triangles read it")
        } else {
            Decision::skip("no triangle has a texture")
        };
        let glow = if full {
            Decision::run(FORCED)
        } else if scene.meshes.iter().any(|m| m.glows()) {
            Decision::run("a material gives off light: added to its faces after lighting")
        } else {
            Decision::skip("no material gives off light")
        };
        let positional = scene
            .lights
            .iter()
            .take(crate::scene::MAX_LIGHTS)
            .any(|l| l.kind.position().is_some());
        let falloff = if !lit {
            Decision::skip("nothing is lit")
        } else if full {
            Decision::run(FORCED)
        } else if positional {
            Decision::run("a point or spot light: each vertex lit from where it is")
        } else {
            Decision::skip("every light is directional")
        };
        let specular = if !lit {
            Decision::skip("nothing is lit")
        } else if opts.aa == Aa::Exact {
            Decision::skip("exact coverage shades a triangle by its mean colour")
        } else if full {
            Decision::run(FORCED)
        } else if scene.meshes.iter().any(|m| m.shines()) {
            Decision::run("a material shines: its triangles get a highlight found per sample")
        } else {
            Decision::skip("no material shines")
        };
        let alpha = if opts.aa == Aa::Exact {
            Decision::skip("exact coverage draws every material opaque")
        } else if full {
            Decision::run(FORCED)
        } else if scene.meshes.iter().any(|m| m.geometry.sees_through()) {
            Decision::run("a material is masked or blended: its samples decided by its alpha")
        } else {
            Decision::skip("every material is opaque")
        };
        let maps = if opts.aa == Aa::Exact {
            Decision::skip("exact coverage shades a triangle by its mean colour")
        } else if scene.meshes.iter().any(|m| m.geometry.mapped()) {
            Decision::run("a material has maps: its triangles shaded per sample from them")
        } else {
            Decision::skip("no material has maps")
        };
        let interpolation = if full {
            Decision::run(FORCED)
        } else if textured {
            Decision::run("texture coordinates vary over textured triangles")
        } else if specular.run {
            Decision::run("a highlight's normal and position vary over its triangles")
        } else if maps.run {
            Decision::run("a mapped material's coordinates vary over its triangles")
        } else if layered(|l| !l.is_empty()) && lit && opts.aa != Aa::Exact {
            Decision::run("a layered material's normals vary over its triangles")
        } else if shading == Shading::Smooth {
            Decision::run("smooth shading varies the light over each triangle")
        } else if vertex_colors {
            Decision::run("per-vertex colours vary over their triangles")
        } else {
            Decision::skip("every triangle is one colour: written without barycentrics")
        };
        let perspective_view = matches!(scene.camera.projection, Projection::Perspective { .. });
        let perspective = if opts.interpolation == Interpolation::Affine {
            Decision::skip("affine interpolation was asked for")
        } else if full {
            Decision::run(FORCED)
        } else if !interpolation.run {
            Decision::skip("nothing is interpolated")
        } else if perspective_view {
            Decision::run("a perspective view interpolates through 1/w")
        } else {
            Decision::skip("a parallel view has w = 1: affine weights are exact")
        };
        let depth = if full {
            Decision::run(FORCED)
        } else {
            depth(scene, vp, turn)
        };
        // A mesh is posed where its clip moves it; the full pipeline poses
        // every mesh that has a pose, at rest or not (the rest pose is the
        // same code's, so the frame is the same).
        self.poses.clear();
        self.poses.extend(scene.meshes.iter().map(|m| {
            if full {
                m.rig.is_some() && m.pose.is_some()
            } else {
                m.moves()
            }
        }));
        let posed = self.poses.iter().filter(|&&p| p).count();
        let posing = if posed == 0 {
            Decision::skip(
                "no mesh moves: without a clip, or one that moves none of its vertices, a model is drawn at rest",
            )
        } else if full {
            Decision::run(FORCED)
        } else {
            Decision::run(
                "a clip moves the mesh: its vertices are posed (morphed, skinned or carried by their nodes) before the vertex stage",
            )
        };
        self.clip_tests.clear();
        // A posed mesh's vertices leave its rest bounds: tested.
        let groups = scene
            .meshes
            .iter()
            .zip(&self.poses)
            .map(|(m, &posed)| (turn * m.model, if posed { None } else { m.bounds }))
            .chain((!scene.triangles.is_empty()).then(|| (turn, loose_bounds(scene))));
        self.clip_tests.extend(groups.map(|(model, bounds)| {
            // The matrix the vertex stage uses: composed in f64, rounded.
            let mvp = (vp.as_dmat4() * model.as_dmat4()).as_mat4();
            full || !bounds.is_some_and(|[lo, hi]| clipper.box_inside(mvp, lo, hi))
        }));
        let clip = if full {
            Decision::run(FORCED)
        } else if self.clip_tests.contains(&true) {
            Decision::run("geometry reaches a clip plane or leaves the guard band")
        } else {
            Decision::skip("every bounding box is inside the clip volume")
        };
        let grid = opts.grid();
        let samples = grid.width as usize * grid.height as usize;
        self.defers.clear();
        self.defers.extend(
            (scene.meshes.iter())
                .map(|m| m.positions.len() > Plan::DEFER_PER_SAMPLE * samples.max(1)),
        );
        self.culls.clear();
        self.culls
            .extend(scene.meshes.iter().map(|m| mesh_cull(m, opts.cull)));
        let metal = scene.meshes.iter().any(|m| {
            (m.materials.iter())
                .any(|r| !r.finish.unlit && r.finish.specular.is_some_and(|s| s.metallic > 0.0))
        });
        let layer = |has: fn(&crate::scene::Layers) -> bool, what: &'static str| {
            if opts.aa == Aa::Exact {
                Decision::skip("exact coverage shades a triangle by its mean colour")
            } else if !lit {
                Decision::skip("nothing is lit")
            } else if layered(has) {
                Decision::run(what)
            } else {
                Decision::skip("no material has the layer")
            }
        };
        let clearcoat = layer(
            |l| l.clearcoat.is_some(),
            "a lit material is coated: its triangles shaded per sample with the coat's lobe",
        );
        let sheen = layer(
            |l| l.sheen.is_some(),
            "a lit material has sheen: its triangles shaded per sample with the sheen's lobe",
        );
        let environment = if !scene.environment.is_some() {
            Decision::skip("no environment (`--environment none`)")
        } else if clearcoat.run {
            Decision::run("a material is coated: its coat reflects the environment")
        } else if !specular.run {
            Decision::skip("no highlights are drawn")
        } else if metal {
            Decision::run("a shining material is metal: it reflects the environment")
        } else {
            Decision::skip("no material is metal or coated")
        };
        let (faces, edges) = wire(scene, opts);
        let lines = if !scene.meshes.iter().any(|m| !m.lines.is_empty()) {
            Decision::skip("no model has lines or points")
        } else if opts.aa == Aa::Exact {
            Decision::skip("exact coverage adds up faces' areas: no lines")
        } else {
            Decision::run("a model has line or point primitives: drawn one sample wide")
        };
        let lean = lean(opts);
        let decision = |e: Effect| match e {
            Effect::Pose => posing,
            Effect::Clip => clip,
            Effect::Lighting => lighting,
            Effect::Falloff => falloff,
            Effect::Rim => rim,
            Effect::Depth => depth,
            Effect::Interpolation => interpolation,
            Effect::Perspective => perspective,
            Effect::Texturing => texturing,
            Effect::Glow => glow,
            Effect::Specular => specular,
            Effect::Environment => environment,
            Effect::Clearcoat => clearcoat,
            Effect::Sheen => sheen,
            Effect::Alpha => alpha,
            Effect::Maps => maps,
            Effect::Faces => faces,
            Effect::Edges => edges,
            Effect::Lines => lines,
            Effect::Lean => lean,
        };
        *self = Plan {
            decisions: std::array::from_fn(|i| decision(Effect::ALL[i])),
            filter: opts.filter,
            shading,
            full,
            clip_tests: std::mem::take(&mut self.clip_tests),
            poses: std::mem::take(&mut self.poses),
            defers: std::mem::take(&mut self.defers),
            culls: std::mem::take(&mut self.culls),
            cull_asked: opts.cull,
            bands: bands(opts),
        };
    }

    /// Each stage's or effect's decision, in [`Effect::ALL`]'s order.
    pub fn decisions(&self) -> impl Iterator<Item = (Effect, Decision)> + '_ {
        Effect::ALL.iter().map(|&e| (e, self[e]))
    }

    /// Which faces of mesh `i` are culled, for its vertex stage and every
    /// run whose material says nothing: `--cull` where asked; else the
    /// mesh's own ([`crate::scene::Mesh::cull`], from what the file says of
    /// its sides or from its topology), unless some material draws a side
    /// the mesh culls (glTF materials differing in `doubleSided`): then
    /// none, and each run culls its own ([`Plan::run_cull`]).
    pub fn cull(&self, i: usize) -> crate::scene::Cull {
        self.culls.get(i).copied().unwrap_or_default()
    }

    /// Which faces of a run of `mesh` in `finish` are culled: `--cull`
    /// where asked, else its material's sides (glTF's `doubleSided`: a
    /// single-sided face seen from behind is culled, a double-sided one
    /// drawn, lit on the side seen), else the mesh's own.
    pub fn run_cull(
        &self,
        mesh: &crate::scene::Mesh,
        finish: &crate::scene::Finish,
    ) -> crate::scene::Cull {
        self.cull_asked
            .unwrap_or_else(|| sides_cull(finish.sides, mesh.cull))
    }

    /// Whether group `i` (mesh `i`, or the loose triangles after the last
    /// mesh) has its vertices tested against the clip planes.
    pub fn clip_tests(&self, group: usize) -> bool {
        self.clip_tests.get(group).copied().unwrap_or(true)
    }

    /// What the vertex stage keeps of mesh `i`'s vertices (culled as
    /// `cull`) beyond the 14 bytes every face reads ([`Extras`]); where
    /// nothing, [`Plan::deferral`] runs and says why. Memory and speed
    /// alone: the frame is the same either way (and a mesh with a vertex
    /// that takes the f64 path all the same keeps them all; see the vertex
    /// stage).
    pub fn vertex_extras(&self, i: usize, cull: crate::scene::Cull) -> Extras {
        self.extras(i, cull).0
    }

    /// Whether the depth, `1/w` and light of mesh `i`'s vertices (culled
    /// as `cull`) are found again at set-up, for the corners of each face
    /// that covers a sample, rather than kept by the vertex stage for
    /// every vertex (14 bytes a vertex rather than 34 or 66), and why.
    /// Found again only where no face may read a vertex's world position,
    /// normal or unsnapped position (flat shading, lights that fall off, a
    /// rim, highlights, textures, alpha, maps, the general path, the full
    /// pipeline, back faces, which smooth shading lights from the other
    /// side of their normals, and a mesh whose vertices are tested against
    /// the clip planes, whose faces may take the clip path), and only for
    /// a mesh of more than [`Plan::DEFER_PER_SAMPLE`] vertices a sample:
    /// with fewer, most of its vertices are read by faces that cover a
    /// sample, and keeping their depth and light ([`Extras::Deep`]) costs
    /// less.
    pub fn deferral(&self, i: usize, cull: crate::scene::Cull) -> Decision {
        let (extras, why) = self.extras(i, cull);
        Decision {
            run: extras == Extras::Found,
            why,
        }
    }

    /// [`Plan::vertex_extras`] and why.
    fn extras(&self, i: usize, cull: crate::scene::Cull) -> (Extras, &'static str) {
        let all = |why| (Extras::All, why);
        if self.full {
            all(FORCED_KEPT)
        } else if self.clip_tests(i) {
            all(
                "its vertices are tested against the clip planes: a face may take the clip path, which reads every extra",
            )
        } else if self.shading == Shading::Flat {
            all("flat shading lights each face from its corners' world positions")
        } else if self[Effect::Falloff].run {
            all("a light that falls off reads each corner's world position")
        } else if self[Effect::Rim].run {
            all("the rim reads each corner's normal")
        } else if self[Effect::Specular].run {
            all("a highlight reads each corner's normal and world position")
        } else if self[Effect::Texturing].run
            || self[Effect::Alpha].run
            || self[Effect::Maps].run
            || self[Effect::Clearcoat].run
            || self[Effect::Sheen].run
        {
            all("textures, alpha, maps or layers read each corner's unsnapped position")
        } else if !self[Effect::Lean].run {
            all("the general path reads every extra")
        } else if cull != crate::scene::Cull::Back {
            all("back faces are drawn, lit from the other side of each corner's normal")
        } else if !self.defers.get(i).copied().unwrap_or(false) {
            (
                Extras::Deep,
                "at most 6 vertices a sample: most vertices are corners of a face that covers one",
            )
        } else {
            (
                Extras::Found,
                "more than 6 vertices a sample: only the corners of a face that covers a sample are lit, at set-up",
            )
        }
    }

    /// Whether mesh `i` is posed (see [`Effect::Pose`]).
    pub fn poses(&self, mesh: usize) -> bool {
        self.poses.get(mesh).copied().unwrap_or(false)
    }

    /// The texture a run of faces reads, and how: its own (with `--filter`
    /// applied), none where it has none, and in the full pipeline a white
    /// texel (exactly 1.0) for faces without one, so that the property
    /// test proves that skipping texturing there changes nothing.
    pub fn texture<'a>(&self, own: Option<&'a Texture>) -> Option<(&'a Texture, Sampler)> {
        let texture = match own {
            Some(t) => t,
            None if self.full => Texture::white(),
            None => return None,
        };
        let sampler = match self.filter {
            Some(f) => f.apply(texture.sampler),
            None => texture.sampler,
        };
        Some((texture, sampler))
    }

    /// Whether a run of faces goes through the specular fill: one whose
    /// material shines (`shines`), and in the full pipeline every run
    /// (a matte one adding nothing), so that the property test proves that
    /// skipping it for matte runs changes nothing.
    pub fn shines(&self, shines: bool) -> bool {
        self[Effect::Specular].run && (shines || self.full)
    }

    /// Whether a shining run whose metal share is `metallic` reflects the
    /// environment: in both pipelines, exactly the metal runs.
    pub fn reflects(&self, metallic: f32) -> bool {
        self[Effect::Environment].run && metallic > 0.0
    }

    /// The layers of a run of `finish` the plan draws (in both pipelines:
    /// see [`Effect::Clearcoat`] and [`Effect::Sheen`]); none for an unlit
    /// one.
    pub fn layers_of(&self, finish: &crate::scene::Finish) -> crate::scene::Layers {
        let l = finish.layers;
        crate::scene::Layers {
            clearcoat: l
                .clearcoat
                .filter(|_| self[Effect::Clearcoat].run && !finish.unlit),
            sheen: l.sheen.filter(|_| self[Effect::Sheen].run && !finish.unlit),
        }
    }

    /// Whether a run of `finish` is shaded per sample (the mapped fill),
    /// with which maps and layers: its maps where the mesh has coordinates
    /// to read them by (`uvs`), its layers as drawn.
    pub fn per_sample(
        &self,
        finish: &crate::scene::Finish,
        uvs: bool,
    ) -> Option<(crate::scene::Maps, crate::scene::Layers)> {
        let maps = self.maps_of(finish).filter(|_| uvs);
        let layers = self.layers_of(finish);
        let layered = !layers.is_empty();
        maps.or(layered.then(crate::scene::Maps::default))
            .map(|m| (m, layers))
    }

    /// Whether a run of faces of `alpha` goes through the see-through
    /// fill: a masked or blended one, and in the full pipeline every run
    /// (an opaque one writing what the other fills write), so that the
    /// property test proves that skipping it for opaque runs changes
    /// nothing.
    pub fn sees_through(&self, alpha: &crate::scene::Alpha) -> bool {
        self[Effect::Alpha].run && (alpha.mode != crate::scene::AlphaMode::Opaque || self.full)
    }

    /// The maps a run of faces of `finish` is shaded from: its own, where
    /// the plan reads maps (in both pipelines: see [`Effect::Maps`]).
    pub fn maps_of(&self, finish: &crate::scene::Finish) -> Option<crate::scene::Maps> {
        (self[Effect::Maps].run && !finish.maps.is_empty()).then_some(finish.maps)
    }

    /// Whether a triangle whose vertices have these colours is
    /// interpolated: when its colours differ (a triangle of one colour is
    /// written as it is, which is bit for bit what interpolating it gives),
    /// and always in the full pipeline.
    pub fn interpolates<T: PartialEq>(&self, colors: &[T; 3]) -> bool {
        let one = colors[0] == colors[1] && colors[1] == colors[2];
        debug_assert!(
            self[Effect::Interpolation].run || one,
            "the plan skipped interpolation, yet a triangle has several colours"
        );
        self.full || !one
    }
}

/// Whether faces and edges are drawn (see [`Effect::Faces`], [`Effect::Edges`]).
fn wire(scene: &Scene, opts: &RenderOptions) -> (Decision, Decision) {
    let meshes = !scene.meshes.is_empty();
    match opts.wire {
        Wire::Solid => (
            Decision::run("faces are drawn (no wireframe asked for)"),
            Decision::skip("no wireframe asked for"),
        ),
        _ if opts.aa == Aa::Exact => (
            Decision::run("exact coverage adds up faces' areas: no lines"),
            Decision::skip("exact coverage adds up faces' areas: no lines"),
        ),
        _ if !meshes => (
            Decision::run("loose triangles are drawn as they are"),
            Decision::skip("the scene has no mesh: loose triangles have no edges drawn"),
        ),
        Wire::Lines => (
            Decision::skip("a wireframe draws meshes' edges alone"),
            Decision::run("a wireframe: each mesh's edges, once each, one sample wide"),
        ),
        Wire::Edges => (
            Decision::run("faces, with their edges over them"),
            Decision::run("edges over the faces, hidden where a face is nearer"),
        ),
    }
}

/// Which path triangles inside every clip plane take (see [`Effect::Lean`]).
fn lean(opts: &RenderOptions) -> Decision {
    if opts.pipeline == Pipeline::Full {
        Decision::skip("the full pipeline sets up, lights and fills every triangle")
    } else if opts.aa == Aa::Exact {
        Decision::skip("exact coverage adds up every triangle's area")
    } else if opts.precision != Precision::Fixed {
        Decision::skip("the f64 and f32 set-ups are comparison modes")
    } else if opts.traversal == Traversal::Scan {
        Decision::skip("a scan tests every sample of the grid")
    } else {
        Decision::run(
            "culled, sized and found empty from the snapped vertices; lit only if covering a sample",
        )
    }
}

/// Whether samples need a depth test.
fn depth(scene: &Scene, vp: Mat4, turn: Mat4) -> Decision {
    let lines: usize = scene.meshes.iter().map(|m| m.lines.len()).sum();
    if scene.triangle_count().saturating_add(lines) <= 1 {
        return Decision::skip("one primitive cannot overlap another");
    }
    if scene.meshes.is_empty() && scene.camera.projection == Projection::None {
        // Every vertex at one depth: every sample's depth is that value, so
        // the depth test keeps the first triangle drawn, as does writing
        // only empty samples.
        let mut zs = scene.triangles.iter().flat_map(|t| t.vertices).map(|p| {
            let c = vp * turn * p.extend(1.0);
            c.z / c.w
        });
        let first = zs.next();
        if first.is_some_and(|z| z.is_finite()) && zs.all(|z| Some(z) == first) {
            return Decision::skip(
                "a flat 2D scene: one depth everywhere, the first triangle drawn stays",
            );
        }
    }
    Decision::run("primitives may overlap at different depths")
}

/// The bounding box of the loose triangles; `None` if a coordinate is not
/// finite.
fn loose_bounds(scene: &Scene) -> Option<[Vec3; 2]> {
    let mut lo = Vec3::INFINITY;
    let mut hi = Vec3::NEG_INFINITY;
    for p in scene.triangles.iter().flat_map(|t| t.vertices) {
        if !p.is_finite() {
            return None;
        }
        lo = lo.min(p);
        hi = hi.max(p);
    }
    Some([lo, hi])
}

impl fmt::Display for Plan {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "pose           {}", self[Effect::Pose])?;
        writeln!(f, "clip           {}", self[Effect::Clip])?;
        writeln!(f, "lighting       {}", self[Effect::Lighting])?;
        writeln!(f, "rim            {}", self[Effect::Rim])?;
        writeln!(f, "texturing      {}", self[Effect::Texturing])?;
        writeln!(f, "falloff        {}", self[Effect::Falloff])?;
        writeln!(f, "glow           {}", self[Effect::Glow])?;
        writeln!(f, "specular       {}", self[Effect::Specular])?;
        writeln!(f, "alpha          {}", self[Effect::Alpha])?;
        writeln!(f, "maps           {}", self[Effect::Maps])?;
        writeln!(f, "clearcoat      {}", self[Effect::Clearcoat])?;
        writeln!(f, "sheen          {}", self[Effect::Sheen])?;
        writeln!(f, "depth          {}", self[Effect::Depth])?;
        writeln!(f, "interpolation  {}", self[Effect::Interpolation])?;
        writeln!(f, "perspective    {}", self[Effect::Perspective])?;
        writeln!(f, "lean path      {}", self[Effect::Lean])?;
        write!(f, "bands          {}", self.bands)
    }
}
