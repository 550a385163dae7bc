//! The edge stage: a mesh's edges as lines one sample wide, for
//! `--wire lines` and `--wire edges` ([`crate::Wire`]), when the plan
//! draws them ([`crate::Effect::Edges`]).
//!
//! Each edge is drawn once however many faces share it: the mesh's edges
//! are found once, welded by position ([`crate::scene::Geometry::edges`]).
//! An edge is clipped as a segment in homogeneous space (the same planes
//! as a triangle's), then drawn as a rectangle one sample wide, centred on
//! it and reaching half a sample past each end (so that lines meeting at a
//! corner leave no notch), split into two triangles that go through the
//! same snapped fixed-point set-up and top-left rule as faces: the two
//! halves share their diagonal, so no sample of a line is written twice,
//! and a line's samples are exactly those whose centres fall inside its
//! rectangle.
//!
//! The trade-offs: lines are unlit (each mesh's colour, or black over the
//! faces), of one width in samples whatever the glyph mode, and an edge
//! over the faces is drawn as if 1 % of its distance nearer, so that the
//! face it bounds does not hide it (a constant share of the distance in
//! depth, where GPUs scale a bias by the face's slope: an edge where a
//! face meets another at a grazing angle may lose a few samples to it,
//! and one less than 1 % of its distance behind a face shows through).

use glam::{DVec4, Vec3};

use super::vertex::Transforms;
use super::{Painter, Stage, Surface};
use crate::clip::ScreenVertex;
use crate::color::Lin;
use crate::fill::Attributes;
use crate::fixed::FixedPoint;
use crate::options::Wire;
use crate::plan::Effect;
use crate::raster::{Coverage, Setup, SnappedTriangle};
use crate::scene::{Cull, Mesh, Projection};

/// How much nearer than an edge's own depth it is drawn over the faces, as
/// a share of its distance from the eye.
pub const EDGE_NEARER: f64 = 0.01;

/// What an edge's depth is raised by over the faces (depth grows towards
/// the eye, as in the lecture notes: the near plane is +1): `k·(1/w) + c`
/// in normalised depth, `k` and `c` from the projection (`z = A + B/w`
/// under perspective: a distance `δ = ε·w` nearer raises it by `B·ε/w`;
/// a parallel view's depth is linear: by `2δ/(far − near)`, `δ` a share of
/// the view's height; without a projection, a share of the depth range).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct EdgeBias {
    per_inv_w: f32,
    constant: f32,
}

impl EdgeBias {
    /// The bias for a camera's projection.
    pub(super) fn of(projection: &Projection) -> EdgeBias {
        match *projection {
            Projection::Perspective { near, far, .. } => {
                let (n, f) = (f64::from(near), f64::from(far));
                EdgeBias {
                    per_inv_w: (2.0 * f * n / (f - n) * EDGE_NEARER) as f32,
                    constant: 0.0,
                }
            }
            Projection::Orthographic { height, near, far } => EdgeBias {
                per_inv_w: 0.0,
                constant: (2.0 * f64::from(height) * EDGE_NEARER / f64::from(far - near)) as f32,
            },
            // Depth as given, in [−1, 1]: 1 % of that.
            Projection::None => EdgeBias {
                per_inv_w: 0.0,
                constant: (2.0 * EDGE_NEARER) as f32,
            },
        }
    }

    fn nearer(&self, v: &ScreenVertex) -> f32 {
        v.z + self.per_inv_w * v.inv_w + self.constant
    }
}

impl Painter<'_> {
    /// Draws `mesh`'s edges, its vertices at `positions` this frame, as
    /// `wire` asks (see the module doc).
    pub(super) fn edges(
        &mut self,
        stage: &Stage<'_>,
        mesh: &Mesh,
        positions: &[Vec3],
        transforms: &Transforms,
        wire: Wire,
    ) {
        let (colour, bias) = match wire {
            Wire::Edges => (Vec3::ZERO, stage.edge_bias),
            _ => (
                Vec3::from(Lin::from_srgb(mesh.color).to_f32()),
                EdgeBias::default(),
            ),
        };
        // Lines are unlit and opaque, whatever the faces' materials.
        self.surface = Surface::default();
        for &ends in mesh.geometry.edges() {
            if let Some(ends) = segment(stage, positions, transforms, ends) {
                self.stats.edges += 1;
                self.line(stage, ends, colour, bias);
            }
        }
    }

    /// The mesh's own lines and points ([`crate::scene::Geometry::lines`]),
    /// each in its colour (or the mesh's), unlit, one sample wide, at their
    /// own depth; a point is one sample.
    pub(super) fn lines(
        &mut self,
        stage: &Stage<'_>,
        mesh: &Mesh,
        positions: &[Vec3],
        transforms: &Transforms,
    ) {
        self.surface = Surface::default();
        let own = Lin::from_srgb(mesh.color);
        for &(ends, colour) in &mesh.geometry.lines {
            if let Some(ends) = segment(stage, positions, transforms, ends) {
                self.stats.lines += 1;
                let colour = Vec3::from(colour.unwrap_or(own).to_f32());
                self.line(stage, ends, colour, EdgeBias::default());
            }
        }
    }

    /// One line from `s` to `e` (on screen): its rectangle, as two
    /// triangles sharing a diagonal.
    fn line(&mut self, stage: &Stage<'_>, [s, e]: [ScreenVertex; 2], colour: Vec3, bias: EdgeBias) {
        let d = [e.xy[0] - s.xy[0], e.xy[1] - s.xy[1]];
        let len = d[0].hypot(d[1]);
        // Along the line and across it, half a width each; a line of no
        // length is a square.
        let h = crate::options::LINE_WIDTH / 2.0;
        let u = if len > 0.0 {
            [d[0] / len * h, d[1] / len * h]
        } else {
            [h, 0.0]
        };
        let n = [-u[1], u[0]];
        let corner = |p: &ScreenVertex, along: f64, across: f64| {
            [
                p.xy[0] + along * u[0] + across * n[0],
                p.xy[1] + along * u[1] + across * n[1],
            ]
        };
        let xy = [
            corner(&s, -1.0, 1.0),
            corner(&e, 1.0, 1.0),
            corner(&e, 1.0, -1.0),
            corner(&s, -1.0, -1.0),
        ];
        let Some(fixed) = snap_all(xy) else {
            return;
        };
        let (zs, ze) = (bias.nearer(&s), bias.nearer(&e));
        let z = [zs, ze, ze, zs];
        let inv_w = [s.inv_w, e.inv_w, e.inv_w, s.inv_w];
        let grid = self.fb.grid();
        let band = self.fb.band();
        for k in [[0, 1, 2], [0, 2, 3]] {
            let setup = SnappedTriangle::new(k.map(|i| fixed[i]), Cull::None)
                .map(|t| Setup::of(&t, grid, band));
            // One colour, written as it is (in both pipelines): through
            // the colour fill alone, which leaves the faces' own path as
            // the compiler laid it out.
            if let Some(s) = self.setup(&setup) {
                let a = Attributes::new(
                    s.order(),
                    s.inv_area(),
                    [k.map(|i| z[i]), k.map(|i| inv_w[i])],
                    [colour; 3],
                    stage.plan[Effect::Perspective].run,
                );
                self.fill_colour(s, &a, true, stage);
            }
        }
    }
}

/// The four corners snapped, or `None` if one cannot be.
fn snap_all(xy: [[f64; 2]; 4]) -> Option<[FixedPoint; 4]> {
    let [a, b, c, d] = xy.map(FixedPoint::snap64);
    Some([a?, b?, c?, d?])
}

/// The part on screen of the segment between the vertices `ends` (at
/// `positions` this frame), if any: none where a vertex is missing (or,
/// as the clipper says, not finite).
fn segment(
    stage: &Stage<'_>,
    positions: &[Vec3],
    transforms: &Transforms,
    ends: [u32; 2],
) -> Option<[ScreenVertex; 2]> {
    let at = |i: u32| {
        positions
            .get(i as usize)
            .map(|p| DVec4::from((p.as_dvec3(), 1.0)))
    };
    let [a, b] = ends.map(at);
    stage
        .clipper
        .clip_segment([a?, b?], &transforms.mvp64, &stage.viewport)
}
