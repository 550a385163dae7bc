//! The triangle stage's out-of-line paths: runs shaded per sample from
//! their material's maps (each face's tangent frame found here, in the
//! turned world), and the fill of triangles that are mapped, masked or
//! blended.
//!
//! Trade-offs. These runs are few and their samples dear, so they take
//! the general path (set up, then lit and filled) through loops of their
//! own, kept out of line: the loops that draw every other run are the
//! same code as before they existed, and cost the same.

use glam::{Vec3, Vec3A, Vec4};

use super::triangle::{Corners, Faces, Model, Tex, in_order};
use super::vertex::Verts;
use super::{Painter, Stage};
use crate::fill::{self, AlphaFill, Attributes, Mapped, MappedCorners, ScreenTriangle, Shine};
use crate::options::Highlights;
use crate::plan::Effect;
use crate::raster::Coverage;
use crate::scene::Alpha;
use crate::texture::{Sampler, Texture};

/// Which faces of a mesh a mapped run draws, in order.
pub(super) enum Ids<'a> {
    /// A run of faces, in the mesh's order.
    Range(std::ops::Range<usize>),
    /// A blended run's, back to front.
    Listed(&'a [u32]),
}

/// A mapped run's maps and the face being drawn's frame: scratch the
/// painter keeps beside its surface (which stays as small as it was).
#[derive(Debug, Default)]
pub(super) struct Mapping {
    /// The run's maps; `None` for a run without.
    pub(super) set: Option<fill::MapSet>,
    /// The face being drawn's.
    frame: Frame,
}

/// The face being drawn's corners in the turned world: where they are,
/// and their tangents and bitangents (scaled to unit length).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Frame {
    world: [Vec3; 3],
    tangent: [Vec3; 3],
    bitangent: [Vec3; 3],
    /// The second coordinate set's, where a map reads it.
    uv2: [glam::Vec2; 3],
}

impl Painter<'_> {
    /// Draws a mapped run's faces `ids` (with `texture`, the base colour's,
    /// and `run_color`, the run's colour in lanes), each with its tangent
    /// frame.
    #[inline(never)]
    pub(super) fn run_mapped(
        &mut self,
        stage: &Stage<'_>,
        f: &Faces<'_>,
        verts: Verts<'_>,
        ids: Ids<'_>,
        (texture, run_color): (Option<(&Texture, Sampler)>, Vec3A),
    ) {
        let mesh = f.mesh;
        // Every map is read through the coordinates: a run without a base
        // texture reads white's (a product by exactly 1).
        let (texture, sampler) = texture.unwrap_or((Texture::white(), Sampler::default()));
        let uvs = mesh.uvs.as_deref().unwrap_or(&[]);
        let draw = |me: &mut Self, id: usize| {
            let face = mesh.faces[id];
            let mut scratch = super::vertex::Deep::SCRATCH;
            let v = verts.of(face, &mut scratch);
            me.count_lazy(stage, &verts);
            let base = match &mesh.colors {
                Some(c) => face.map(|i| c[i as usize].to_lanes()),
                None => [run_color; 3],
            };
            me.mapping.frame = frame(f, face, mesh.tangents.as_ref().map(|t| t[id]));
            if let Some(uvs2) = &mesh.uvs2 {
                me.mapping.frame.uv2 =
                    face.map(|i| uvs2.get(i as usize).copied().unwrap_or_default());
            }
            let tex = Tex {
                texture,
                sampler,
                uv: face.map(|i| uvs.get(i as usize).copied().unwrap_or_default()),
            };
            let model = Model {
                positions: f.positions,
                face,
                mvp: &f.transforms.mvp64,
                world: &f.transforms.model,
            };
            me.triangle::<true, true>(stage, v, base, f.cull, model, Some(tex));
        };
        match ids {
            Ids::Range(r) => r.for_each(|id| draw(self, id)),
            Ids::Listed(l) => l.iter().for_each(|&id| draw(self, id as usize)),
        }
    }

    /// [`Painter::fill`] of a triangle of a mapped, masked or blended run
    /// (with its texture, highlight and maps, if any), counted. Out of
    /// line: the fills inlined beside it stay as they were.
    #[inline(never)]
    pub(super) fn fill_special<C: Coverage>(
        &mut self,
        setup: &C,
        t: &ScreenTriangle,
        a: &Attributes,
        flat: bool,
        stage: &Stage,
        texture: Option<(&Texture, Sampler)>,
    ) {
        let planes = texture.map(|_| fill::UvPlanes::new(t, stage.plan[Effect::Perspective].run));
        let tex = texture.zip(planes.as_ref()).map(|((t, s), p)| (t, s, p));
        let (alpha, alpha_texture) = match &self.surface.see {
            Some((alpha, texture)) => (*alpha, texture.as_deref()),
            None => (Alpha::default(), None),
        };
        let fill = AlphaFill {
            mode: alpha.mode,
            factor: alpha.factor,
            texture: alpha_texture
                .zip(tex)
                .map(|(at, (_, sampler, planes))| (at, sampler, planes)),
            behind: stage.behind,
        };
        // The sink built from the fields (as `sink` does), beside the
        // borrowed surface.
        let mut sink = fill::Sink {
            fb: self.fb.reborrow(),
            depth: stage.plan[Effect::Depth].run,
            traversal: stage.traversal,
        };
        let done = match (&self.mapping.set, t.shine, &planes) {
            (Some(set), Some(corners), Some(planes)) => {
                // The second set at this piece's corners, from where they
                // are in the whole face.
                let frame = &self.mapping.frame;
                let planes2 = set.reads_second().then(|| {
                    let uv2 = corners.1.map(|p| {
                        let w = weights_in(p, frame.world);
                        frame.uv2[0] * w.x + frame.uv2[1] * w.y + frame.uv2[2] * w.z
                    });
                    fill::UvPlanes::of(t, uv2, stage.plan[Effect::Perspective].run)
                });
                let mapped = Mapped {
                    set,
                    corners: mapped_corners(setup.order(), corners, frame),
                    base: texture.filter(|(t, _)| !std::ptr::eq(*t, Texture::white())),
                    planes,
                    planes2: planes2.as_ref(),
                    lights: stage.plan[Effect::Lighting]
                        .run
                        .then_some((&stage.lights, stage.eye)),
                    rim: stage.plan[Effect::Rim].run,
                    environment: stage.environment.filter(|_| {
                        set.layers().clearcoat.is_some() || stage.plan.reflects(set.metallic())
                    }),
                };
                let done = sink.see_through(setup, a, |x, y, e| mapped.at(a, flat, x, y, e), &fill);
                if set.has_maps() {
                    self.stats.mapped_samples += done.written;
                }
                if set.layers().clearcoat.is_some() {
                    self.stats.coated_samples += done.written;
                }
                if set.layers().sheen.is_some() {
                    self.stats.sheen_samples += done.written;
                }
                if mapped.environment.is_some() {
                    self.stats.reflecting_samples += done.written;
                }
                // White, where the run has no base texture, is not read.
                if mapped.base.is_some() {
                    self.stats.textured_samples += done.written;
                }
                done
            }
            _ => {
                let shine = t.shine.map(|corners| {
                    Shine::new(
                        in_order(setup.order(), corners),
                        self.surface.shine,
                        (&stage.lights, stage.eye),
                        stage.highlights == Highlights::Vertex,
                        stage.environment.zip(self.surface.reflect),
                    )
                });
                let shade = |x, y, e| fill::surface_at(a, flat, tex, shine.as_ref(), x, y, e);
                let done = sink.see_through(setup, a, shade, &fill);
                if self.surface.shine.is_some() {
                    self.stats.specular_samples += done.written;
                }
                if stage.environment.is_some() && self.surface.reflect.is_some() {
                    self.stats.reflecting_samples += done.written;
                }
                if tex.is_some() {
                    self.stats.textured_samples += done.written;
                }
                done
            }
        };
        if self.surface.see.is_some() {
            self.stats.alpha_samples += done.written;
        }
        self.stats.count_fill(done);
    }
}

/// Face `face`'s corners in the turned world, with their tangent frames
/// from `tangents` (model space; none: along x).
fn frame(f: &Faces<'_>, face: [u32; 3], tangents: Option<[Vec4; 3]>) -> Frame {
    let m = f.transforms.model;
    let tangents = tangents.unwrap_or([Vec4::new(1.0, 0.0, 0.0, 1.0); 3]);
    let normals = &f.mesh.normals;
    let turn = |d: Vec3| m.transform_vector3(d).normalize_or_zero();
    let mut out = Frame::default();
    for k in 0..3 {
        let i = face[k] as usize;
        // The same product the corners' positions are found with, so that
        // a corner's weights in its own triangle are exactly one and zero.
        out.world[k] = m.transform_point3(f.positions[i]);
        let t = tangents[k].truncate();
        let n = normals.get(i).copied().unwrap_or(Vec3::Z);
        out.tangent[k] = turn(t);
        out.bitangent[k] = turn(n.cross(t) * tangents[k].w);
    }
    out
}

/// The mapped fill's corners of a triangle (or a clipped piece of one)
/// whose corners' normals and positions are `corners`, in the set-up's
/// `order`: each corner's tangent and bitangent interpolated in the whole
/// face (`frame`) at its weights there, found from where it is.
fn mapped_corners(order: [usize; 3], (normal, world): Corners, frame: &Frame) -> MappedCorners {
    let weights = world.map(|p| weights_in(p, frame.world));
    let at = |c: &[Vec3; 3], w: Vec3| c[0] * w.x + c[1] * w.y + c[2] * w.z;
    let tangent = weights.map(|w| at(&frame.tangent, w));
    let bitangent = weights.map(|w| at(&frame.bitangent, w));
    MappedCorners {
        normal: order.map(|i| normal[i]),
        world: order.map(|i| world[i]),
        tangent: order.map(|i| tangent[i]),
        bitangent: order.map(|i| bitangent[i]),
    }
}

/// The barycentric weights of `p` (in the plane of `[a, b, c]`) in that
/// triangle; a corner's own are exactly one and zeros. A triangle of no
/// area gives its first corner all the weight.
fn weights_in(p: Vec3, [a, b, c]: [Vec3; 3]) -> Vec3 {
    let n = (b - a).cross(c - a);
    let d = n.length_squared();
    if d.is_nan() || d <= 0.0 {
        return Vec3::X;
    }
    Vec3::new(
        (b - p).cross(c - p).dot(n) / d,
        (c - p).cross(a - p).dot(n) / d,
        (a - p).cross(b - p).dot(n) / d,
    )
}
