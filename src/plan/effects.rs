//! Every stage and effect the planner decides on, each declared once:
//! its name, when it runs and when it is skipped (the table of
//! docs/planner.md, which a test holds to this list), the work
//! `--explain` reports of it and the counter that work is, and a witness,
//! a scene in which it runs, on which a test holds the planned frame to the
//! full pipeline's. Adding an effect is a line here, its decision in
//! [`super::Plan::replan`], and the code that draws it.

use crate::choice::Choice;
use crate::options::RenderOptions;
use crate::scene::Scene;
use crate::stats::FrameStats;

use super::Plan;

macro_rules! effects {
    ($(
        $(#[$doc:meta])*
        $variant:ident $name:literal {
            runs: $runs:literal,
            skipped: $skipped:literal,
            counter: $counter:expr,
            work: $work:expr,
            witness: $witness:literal $(with $tweak:expr)?,
        }
    )*) => {
        /// A stage or effect the planner decides on, run or skipped, for
        /// each frame ([`Plan`]'s decisions, indexed by it).
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum Effect {
            $( $(#[$doc])* $variant, )*
        }

        impl Effect {
            /// Every effect, in the order `--explain` reports them.
            pub const ALL: &'static [Effect] = &[$(Effect::$variant),*];

            /// How many there are.
            pub const COUNT: usize = Effect::ALL.len();

            /// Its name, as `--explain` and the docs say it.
            pub fn name(self) -> &'static str {
                match self { $(Effect::$variant => $name,)* }
            }

            /// When it runs.
            pub fn runs_when(self) -> &'static str {
                match self { $(Effect::$variant => $runs,)* }
            }

            /// When it is skipped.
            pub fn skipped_when(self) -> &'static str {
                match self { $(Effect::$variant => $skipped,)* }
            }

            /// The counter of its work in a frame's statistics, where it
            /// has one: above zero in its witness's frame.
            pub fn counter(self, stats: &FrameStats) -> Option<u64> {
                match self {
                    $(Effect::$variant => {
                        let counter: Option<fn(&FrameStats) -> u64> = $counter;
                        counter.map(|c| c(stats))
                    })*
                }
            }

            /// What it did in the last frame, as `--explain` says it.
            pub(crate) fn work(
                self,
                stats: &FrameStats,
                scene: &Scene,
                opts: &RenderOptions,
                plan: &Plan,
            ) -> String {
                match self {
                    $(Effect::$variant => {
                        let work: fn(&FrameStats, &Scene, &RenderOptions, &Plan) -> String = $work;
                        work(stats, scene, opts, plan)
                    })*
                }
            }

            /// A scene in which it runs (a scene file, a model or a shape
            /// named as `rastty render` takes them, from the repository's
            /// root), and the options to draw it with: its test draws it
            /// planned and full, and finds the same frame.
            pub fn witness(self) -> (&'static str, RenderOptions) {
                match self {
                    $(Effect::$variant => {
                        #[allow(unused_mut)]
                        let mut opts = RenderOptions { cols: 48, rows: 16, ..RenderOptions::default() };
                        $( let tweak: fn(&mut RenderOptions) = $tweak; tweak(&mut opts); )?
                        ($witness, opts)
                    })*
                }
            }
        }
    };
}

effects! {
    /// Posing: a moving model's vertices skinned, morphed or carried by
    /// their nodes before the vertex stage.
    Pose "pose" {
        runs: "a clip moves a mesh: its vertices are posed (morphed, skinned or carried by their nodes) before the vertex stage",
        skipped: "no mesh moves: without a clip, or one that moves none of its vertices, a model is drawn at rest",
        counter: Some(|s| s.posed_vertices),
        work: |s, _, _, _| format!("{} vertices posed", s.posed_vertices),
        witness: "examples/models/arm.glb",
    }
    /// Clip tests: vertices tested against the clip planes.
    Clip "clip" {
        runs: "a mesh's (or the loose triangles') bounding box reaches a clip plane or leaves the guard band",
        skipped: "the whole box is inside, with room for the vertex stage's f32 rounding, so no vertex in it can be found outside",
        counter: Some(|s| s.clip_tests),
        work: |s, _, _, _| format!(
            "{} vertices tested, {} triangles cut, {} removed",
            s.clip_tests, s.clipped, s.clip_rejected
        ),
        witness: "examples/scenes/near-plane.toml",
    }
    /// Lighting: the scene's lights evaluated.
    Lighting "lighting" {
        runs: "the scene has lights and the shading uses them (never for culled triangles or ones that cover no sample)",
        skipped: "no lights, or `--shading none`",
        counter: Some(|s| s.lighting_evaluations),
        work: |s, _, _, _| format!("{} evaluations", s.lighting_evaluations),
        witness: "torus",
    }
    /// Falloff: point and spot lights, whose light falls off with distance.
    Falloff "falloff" {
        runs: "a light is a point or a spot: vertices keep their world positions and each light's share (inverse square, range window, cone) is found where the surface is",
        skipped: "every light is directional (the full pipeline finds every light's share, exactly 1 for a directional light: the same colours), or nothing lit",
        counter: None,
        work: |_, scene, _, _| {
            let near = scene.lights.iter().filter(|l| l.kind.position().is_some());
            format!("{} point or spot lights", near.count())
        },
        witness: "examples/scenes/lamps.toml",
    }
    /// A rim light on lit surfaces (`--rim`).
    Rim "rim" {
        runs: "`--rim COLOR` was given and the scene is lit",
        skipped: "no rim asked for (none is computed or added; a frame pays one test a triangle), or nothing lit",
        counter: None,
        work: |_, _, opts, _| opts.rim.map_or("no colour".into(), |c| format!("colour {c}")),
        witness: "torus" with |o| o.rim = Some(crate::color::Rgb::new(0xff, 0x80, 0x20)),
    }
    /// The depth buffer.
    Depth "depth" {
        runs: "primitives may overlap at different depths",
        skipped: "a single primitive; a flat 2D scene (every vertex at one depth)",
        counter: Some(|s| s.depth_tests),
        work: |s, _, _, _| format!("{} depth tests", s.depth_tests),
        witness: "examples/scenes/overlap.toml",
    }
    /// Attributes interpolated over triangles.
    Interpolation "interpolation" {
        runs: "an attribute varies over a triangle (per-vertex colours, smooth shading, texture coordinates, a highlight's normal)",
        skipped: "every triangle is one colour: written with no barycentrics",
        counter: Some(|s| s.interpolated_samples),
        work: |s, _, _, _| format!("{} samples interpolated", s.interpolated_samples),
        witness: "torus",
    }
    /// Perspective-correct interpolation, through `1/w`.
    Perspective "perspective" {
        runs: "a perspective view, and something is interpolated",
        skipped: "parallel views (`w = 1` exactly, so affine weights are the same numbers), or nothing interpolated",
        counter: Some(|s| s.perspective_samples),
        work: |s, _, _, _| format!("{} samples through 1/w", s.perspective_samples),
        witness: "torus",
    }
    /// Textures read.
    Texturing "texturing" {
        runs: "a material has a texture: its triangles, and only they, read it",
        skipped: "no triangle has a texture (the full pipeline reads a white texel, exactly 1.0, for every untextured sample: the same colours)",
        counter: Some(|s| s.textured_samples),
        work: |s, _, _, plan| format!(
            "{} samples read a texture ({})",
            s.textured_samples,
            plan.filter.map_or("each texture's own filter", |f| f.name())
        ),
        witness: "examples/models/crate.glb",
    }
    /// Emitted light added after lighting.
    Glow "glow" {
        runs: "a material gives off light (emissive): added to its faces' colours after lighting",
        skipped: "no material glows (the full pipeline adds a glow of zero to every triangle: the same colours)",
        counter: Some(|s| s.glowing_triangles),
        work: |s, _, _, _| format!("{} triangles given emitted light", s.glowing_triangles),
        witness: "examples/models/finishes.glb",
    }
    /// Specular highlights, found per sample.
    Specular "specular" {
        runs: "a lit material shines: its triangles, and only they, go through the specular fill, which finds the highlight at each sample (`--highlights vertex`: at the corners, interpolated)",
        skipped: "no material shines, nothing is lit, or exact coverage (the full pipeline sends every run through the specular fill, matte ones adding nothing: the same colours)",
        counter: Some(|s| s.specular_samples),
        work: |s, _, opts, _| format!(
            "{} samples given a highlight (found {})",
            s.specular_samples,
            match opts.highlights {
                crate::options::Highlights::Sample => "at each sample",
                crate::options::Highlights::Vertex => "at each vertex, interpolated",
            }
        ),
        witness: "tests/models/fox.obj",
    }
    /// Light from the environment, reflected by metals.
    Environment "environment" {
        runs: "a shining material is metal, or a material is coated, and the scene has an environment (the studio unless `--environment none`): its metal share (or its coat) reflects it, the prefiltered radiance about the reflected direction times the lobe's integral (the split sum), per sample with its highlight",
        skipped: "no metal or coat, no environment, or no highlights; not forced by the full pipeline: a reflection is what a metal or a coat asks for, so both pipelines reflect exactly the metal and coated runs",
        counter: Some(|s| s.reflecting_samples),
        work: |s, scene, _, _| format!(
            "{} samples reflect the {}",
            s.reflecting_samples,
            match scene.environment {
                crate::scene::environment::Environment::None => "nothing",
                crate::scene::environment::Environment::Studio => "studio",
                crate::scene::environment::Environment::Map(_) => "environment map",
            }
        ),
        witness: "examples/models/metals.glb",
    }
    /// A clear coat's lobe over its material (`KHR_materials_clearcoat`).
    Clearcoat "clearcoat" {
        runs: "a lit material is coated: its triangles, and only they, are shaded per sample (the mapped fill), the coat's GGX lobe of reflectance 0.04 over the geometry's normal added and what is beneath dimmed by its Fresnel; with an environment, the coat reflects it too",
        skipped: "no material is coated, or nothing is lit, or exact coverage; not forced by the full pipeline: a coat is what a material asks for, so both pipelines coat exactly the coated runs",
        counter: Some(|s| s.coated_samples),
        work: |s, _, _, _| format!("{} samples given a clear coat", s.coated_samples),
        witness: "examples/models/layers.glb",
    }
    /// Sheen over its material (`KHR_materials_sheen`).
    Sheen "sheen" {
        runs: "a lit material has sheen: its triangles, and only they, are shaded per sample (the mapped fill), the Charlie lobe in the sheen's colour added and what is beneath dimmed by the sheen's albedo",
        skipped: "no material has sheen, or nothing is lit, or exact coverage; not forced by the full pipeline: sheen is what a material asks for, so both pipelines add it to exactly the runs with it",
        counter: Some(|s| s.sheen_samples),
        work: |s, _, _, _| format!("{} samples given sheen", s.sheen_samples),
        witness: "examples/models/layers.glb",
    }
    /// Masked and blended materials.
    Alpha "alpha" {
        runs: "a material is masked or blended: its triangles, and only they, go through the see-through fill (a mask's cut decided per sample before the depth test; blended runs drawn after every other, back to front)",
        skipped: "every material is opaque, or exact coverage (the full pipeline sends every run through the see-through fill, opaque ones writing what the other fills write: the same colours)",
        counter: Some(|s| s.alpha_samples),
        work: |s, _, _, _| format!("{} samples drawn by their alpha", s.alpha_samples),
        witness: "examples/models/finishes.glb",
    }
    /// Material maps (normal, metallic-roughness, occlusion, emissive),
    /// shaded per sample.
    Maps "maps" {
        runs: "a material has normal, metallic-roughness, occlusion or emissive textures: its triangles, and only they, are shaded per sample from them (the mapped fill)",
        skipped: "no material has maps, or exact coverage; not forced by the full pipeline: shading per sample is what such a material asks for, so both pipelines shade exactly the mapped runs so",
        counter: Some(|s| s.mapped_samples),
        work: |s, _, _, _| format!("{} samples shaded from their maps", s.mapped_samples),
        witness: "examples/models/finishes.glb",
    }
    /// Meshes' faces drawn.
    Faces "faces" {
        runs: "meshes' faces are drawn (always, but for a wireframe of lines alone)",
        skipped: "`--wire lines`: meshes' edges alone (loose triangles are drawn as they are)",
        counter: None,
        work: |_, _, opts, _| format!("wire {}", opts.wire.name()),
        witness: "cube",
    }
    /// Meshes' edges drawn as lines (`--wire`).
    Edges "edges" {
        runs: "`--wire lines` or `--wire edges`: each mesh's edges, found once and welded by position, drawn once each as lines one sample wide through the same rasterizer; over the faces a little nearer, so edges behind a face are hidden",
        skipped: "no wireframe asked for, exact coverage, or no mesh; a picture asked for, not a stage: the full pipeline draws exactly the edges the planned one does",
        counter: Some(|s| s.edges),
        work: |s, _, _, _| format!(
            "{} edges drawn, each once, as a line {} sample wide",
            s.edges,
            crate::options::LINE_WIDTH
        ),
        witness: "cube" with |o| o.wire = crate::options::Wire::Edges,
    }
    /// A model's own line and point primitives.
    Lines "lines" {
        runs: "a model has line or point primitives (glTF's LINES, LINE_STRIP, LINE_LOOP, POINTS): drawn as the wireframe draws edges, one sample wide, unlit in their colour, at their own depth; a point as one sample",
        skipped: "no model has lines or points, or exact coverage; what the file draws, not a stage: the full pipeline draws exactly the lines the planned one does",
        counter: Some(|s| s.lines),
        work: |s, _, _, _| format!("{} lines and points drawn", s.lines),
        witness: "examples/models/lines.gltf",
    }
    /// The lean path: triangles inside every clip plane culled, sized and
    /// found empty from their snapped vertices, lit and filled only where
    /// they cover a sample. Speed alone: the general path draws the same
    /// samples and counts the same work.
    Lean "lean path" {
        runs: "the planned pipeline with the fixed-point set-up: triangles culled, sized and found empty from their snapped vertices, lit and filled only where they cover a sample",
        skipped: "the full pipeline, exact coverage, the f64 and f32 set-ups or a scan of every sample (comparison modes): every triangle set up in the options' precision and walked with their traversal",
        counter: None,
        work: |_, _, opts, _| format!("{} set-up, {} walk", opts.precision.name(), opts.traversal.name()),
        witness: "torus",
    }
}
