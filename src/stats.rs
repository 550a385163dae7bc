//! What a frame cost: the deterministic counts ([`FrameStats`]) every
//! path keeps as its work would (the planned pipeline's counts equal the
//! full pipeline's), and the wall-clock split ([`FrameTimes`]), kept apart
//! because it is not deterministic.

use std::time::Duration;

use crate::fill;
use crate::raster::RasterStats;

/// What one frame cost.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameStats {
    /// Triangles handed to the pipeline.
    pub triangles_in: u64,
    /// Vertices transformed.
    pub vertices: u64,
    /// Vertices posed by a clip (morphed, skinned or carried by a node)
    /// before the vertex stage.
    pub posed_vertices: u64,
    /// Triangles the clip stage cut.
    pub clipped: u64,
    /// Triangles the clip stage removed entirely (outside, or not finite).
    pub clip_rejected: u64,
    /// Edges drawn as lines (each once, whatever shares it), the part of
    /// each inside the clip planes ([`crate::Wire`]).
    pub edges: u64,
    /// Lambert evaluations (per vertex or per face).
    pub lighting_evaluations: u64,
    /// Triangles whose colours had their material's emitted light added
    /// (after lighting; every triangle shaded where the plan adds glow).
    pub glowing_triangles: u64,
    /// Samples a masked or blended material's alpha decided (those it
    /// drew; the full pipeline counts every run's).
    pub alpha_samples: u64,
    /// Samples shaded from their material's maps (normal,
    /// metallic-roughness, occlusion, emissive), those drawn.
    pub mapped_samples: u64,
    /// Per-sample depth comparisons.
    pub depth_tests: u64,
    /// Samples written with an interpolated colour (not a flat write): a
    /// sample the depth test hides is not coloured, so not counted.
    pub interpolated_samples: u64,
    /// Samples written with a texel (read only for those).
    pub textured_samples: u64,
    /// Samples written with a specular highlight found for them.
    pub specular_samples: u64,
    /// Samples written with the environment's reflection (metals).
    pub reflecting_samples: u64,
    /// Samples written with a clear coat.
    pub coated_samples: u64,
    /// Samples written with sheen.
    pub sheen_samples: u64,
    /// Line and point primitives drawn (glTF's).
    pub lines: u64,
    /// Of those, samples interpolated through `1/w`.
    pub perspective_samples: u64,
    /// Vertices tested against the clip planes.
    pub clip_tests: u64,
    /// Triangles dropped for a NaN or infinite normal.
    pub dropped_non_finite_normals: u64,
    /// What the rasterizer did.
    pub raster: RasterStats,
}

impl FrameStats {
    /// Adds one band's counts (see [`crate::Plan::bands`]) to a frame
    /// drawn in bands. Every band sees every triangle, so the triangle
    /// counts are the first band's; samples belong to one band each, so
    /// their counts are the sums, and equal one thread's. Lighting (and
    /// glow) per face is each band's own work, summed: a triangle may be lit by two bands,
    /// or by none where each band's part of its box is small enough to be
    /// found empty before lighting (one thread tests only small boxes).
    pub(crate) fn add_band(&mut self, band: &FrameStats, first: bool) {
        if first {
            self.triangles_in += band.triangles_in;
            self.clipped += band.clipped;
            self.clip_rejected += band.clip_rejected;
            self.edges += band.edges;
            self.dropped_non_finite_normals += band.dropped_non_finite_normals;
            // The loose triangles' vertices, transformed by every band.
            self.vertices += band.vertices;
            self.clip_tests += band.clip_tests;
            let r = &band.raster;
            self.raster.triangles_drawn += r.triangles_drawn;
            self.raster.dropped_non_finite += r.dropped_non_finite;
            self.raster.dropped_out_of_range += r.dropped_out_of_range;
            self.raster.dropped_degenerate += r.dropped_degenerate;
            self.raster.culled += r.culled;
            self.raster.found_empty += r.found_empty;
        }
        self.lighting_evaluations += band.lighting_evaluations;
        self.glowing_triangles += band.glowing_triangles;
        self.alpha_samples += band.alpha_samples;
        self.mapped_samples += band.mapped_samples;
        self.depth_tests += band.depth_tests;
        self.interpolated_samples += band.interpolated_samples;
        self.textured_samples += band.textured_samples;
        self.specular_samples += band.specular_samples;
        self.reflecting_samples += band.reflecting_samples;
        self.coated_samples += band.coated_samples;
        self.sheen_samples += band.sheen_samples;
        self.lines += band.lines;
        self.perspective_samples += band.perspective_samples;
        self.raster.samples_tested += band.raster.samples_tested;
        self.raster.samples_covered += band.raster.samples_covered;
    }
}

/// Where one frame's time went (wall clock; kept apart from
/// [`FrameStats`], which is deterministic).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameTimes {
    /// Planning.
    pub plan: Duration,
    /// Transforms, clip tests and per-vertex lighting.
    pub vertices: Duration,
    /// Setup, clipping, per-face lighting, traversal, depth tests,
    /// interpolation and writes; for a frame drawn in bands, everything
    /// the bands do, their blits included.
    pub triangles: Duration,
    /// Turning samples into cells (zero for a frame drawn in bands, whose
    /// bands blit their own rows).
    pub blit: Duration,
}

impl FrameStats {
    /// Counts what one fill did, as the fill stage counted it: `covered`
    /// samples, `depth_tested` of them depth-tested, `written` of them
    /// written with an interpolated colour, `perspective` of those through
    /// `1/w`; `tested` samples tested for coverage.
    #[inline]
    pub(crate) fn count_fill(&mut self, done: fill::Filled) {
        let fill::Filled {
            covered,
            depth_tested,
            written: interpolated,
            perspective,
            tested,
        } = done;
        let stats = self;
        stats.depth_tests += depth_tested;
        stats.interpolated_samples += interpolated;
        stats.perspective_samples += perspective;
        stats.raster.samples_tested += tested;
        stats.raster.samples_covered += covered;
    }
}
