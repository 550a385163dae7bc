//! The fill stage: a set-up triangle's coverage in, samples out. What the
//! rasterizer finds covered (a [`Coverage`]'s walk, sample by sample, with
//! its edge weights) becomes a depth, a colour and a texel at each sample,
//! tested and written into the framebuffer (or one band of its rows)
//! through a [`Sink`], in the
//! spirit of tiny-skia's `Blitter` and euc's `test_fragment` /
//! `emit_fragment`: the renderer decides, from the plan, which sink and
//! which fill; the fill decides nothing and reports what it did
//! ([`Filled`]), which the renderer counts.
//!
//! Trade-offs. Attributes are set up once a triangle ([`Attributes`],
//! [`UvPlanes`]) and read per sample with a few multiplies: depth in
//! screen space (linear in the edge weights), colours through `1/w` where
//! the plan corrects for perspective, renormalised by the weights' sum so
//! that three equal colours give back that colour exactly (the planned
//! pipeline's flat write and the full pipeline's interpolation agree bit
//! for bit). One tight loop per combination of flat/interpolated and
//! depth-tested/first-wins, so that each inlines without branches inside
//! the walk. Colours are SIMD lanes (`Vec3A`): the same operations per
//! channel as three f32s, so the same results. Exact coverage (`--aa
//! exact`) is not a walk: [`accumulate_exact`] adds each sample square's
//! covered area, with the triangle's mean colour, to an accumulator.
//!
//! A per-sample term is a fill of its own, chosen by the plan: the
//! specular fill ([`Sink::shiny`]) interpolates a shining triangle's
//! normal and position with the same weights as its colour and adds the
//! highlight found there ([`Shine`]), all in `Vec3A` lanes (the same
//! operations per coordinate as `Vec3`, so the same bits, in fewer
//! instructions); a matte run sent through it (the full
//! pipeline sends every run) adds nothing, so it writes what the other
//! fills write, to the bit. A material that is not opaque takes a fill of
//! its own ([`Sink::see_through`]): a mask's coverage decided per sample
//! before the depth test, or blending over what is drawn. A material with
//! maps (normal, metallic-roughness, occlusion, emissive) is shaded per
//! sample from them (`mapped.rs`), through that same fill with its
//! alpha (opaque, for most).

use glam::{Vec2, Vec3, Vec3A};

use crate::color::Lin;
use crate::framebuffer::Target;
use crate::raster::{Coverage, Traversal};
use crate::scene::AlphaMode;
use crate::scene::environment::EnvMap;
use crate::shade::Lights;
use crate::texture::{Sampler, Texture};
use crate::transform::{self, Grid};

mod mapped;

pub(crate) use mapped::{Corners as MappedCorners, MapSet, Mapped};

/// Where a triangle's samples go, and how they are tested: the
/// framebuffer's rows drawn into, whether samples are depth-tested (else written only where
/// still empty: the first drawn stays) and how a set-up triangle is
/// walked. Made by the renderer from the plan's answers.
pub(crate) struct Sink<'a> {
    /// The samples written.
    pub fb: Target<'a>,
    /// Depth-test each sample (the plan's depth decision).
    pub depth: bool,
    /// How coverage is walked.
    pub traversal: Traversal,
}

/// What one fill did, counted by the loop that did it, for the renderer's
/// counts: a path that skips work cannot report it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Filled {
    /// Samples covered.
    pub covered: u64,
    /// Of those, depth-tested: all, by the loops that test depth; none by
    /// the others.
    pub depth_tested: u64,
    /// Samples written with an interpolated colour or a texel (for exact
    /// coverage: the texture reads).
    pub written: u64,
    /// Of those, interpolated through `1/w` (the attributes' weights are
    /// perspective weights).
    pub perspective: u64,
    /// Samples tested for coverage.
    pub tested: u64,
}

impl Filled {
    /// What a loop did: `covered` samples, all depth-tested if it tested
    /// depth, `written` with attributes `a` (through `1/w` if they carry
    /// perspective weights), `tested` for coverage.
    #[inline(always)]
    fn of(covered: u64, depth_tested: bool, written: u64, a: &Attributes, tested: u64) -> Filled {
        Filled {
            covered,
            depth_tested: if depth_tested { covered } else { 0 },
            written,
            perspective: if a.perspective { written } else { 0 },
            tested,
        }
    }
}

impl Sink<'_> {
    /// Fills a set-up triangle with a texture: the lit colour (one, or
    /// interpolated) times the texel, found only for the samples it is
    /// written to (each counted as written, and interpolated: texture
    /// coordinates are, whatever the colour).
    #[inline(always)]
    pub(crate) fn textured<C: Coverage>(
        &mut self,
        setup: &C,
        a: &Attributes,
        flat: bool,
        texture: (&Texture, Sampler, &UvPlanes),
    ) -> Filled {
        self.shiny(setup, a, flat, Some(texture), None)
    }

    /// Fills a set-up triangle whose material shines: the lit colour (one,
    /// or interpolated), times the texel where it has a texture, plus the
    /// specular light found at each sample it is written to from the
    /// interpolated normal and position (each counted as written and
    /// interpolated). A matte run (the full pipeline's) adds nothing, so
    /// its samples are the other fills' to the bit; without a shine it is
    /// the textured fill. Inlined into each caller: its walk loops are
    /// the frame's hottest code, and the inliner's own choice changes with
    /// how many callers it has.
    #[inline(always)]
    pub(crate) fn shiny<C: Coverage>(
        &mut self,
        setup: &C,
        a: &Attributes,
        flat: bool,
        texture: Option<(&Texture, Sampler, &UvPlanes)>,
        shine: Option<&Shine<'_>>,
    ) -> Filled {
        let grid = self.fb.grid();
        let (at, samples, depths) = self.fb.split_mut();
        let (mut covered, mut written) = (0u64, 0u64);
        let shade = move |x: u32, y: u32, e: C::Weights| {
            surface_at(a, flat, texture, shine, x, y, C::f32(e))
        };
        let tr = self.traversal;
        let (tested, depth) = if self.depth {
            let tested = setup.walk_samples(grid, tr, |x, y, e| {
                covered += 1;
                let z = a.depth(C::f32(e));
                let i = at.of(x, y);
                if nearer(z, depths[i]) {
                    written += 1;
                    depths[i] = z;
                    samples[i] = Some(shade(x, y, e));
                }
            });
            (tested, true)
        } else {
            let tested = setup.walk_samples(grid, tr, |x, y, e| {
                covered += 1;
                let i = at.of(x, y);
                if samples[i].is_none() {
                    written += 1;
                    samples[i] = Some(shade(x, y, e));
                }
            });
            (tested, false)
        };
        if written > 0 {
            self.fb.touch(setup.bounds());
        }
        Filled::of(covered, depth, written, a, tested)
    }

    /// Fills a set-up triangle of a material that is not opaque, as
    /// [`Sink::shiny`] does, with `alpha` deciding each covered sample: cut
    /// where a mask's alpha is below its cut-off (nothing written, depth
    /// included), composited in linear light over what the sample holds
    /// where it blends (depth tested, not written).
    /// `shade` finds a sample's colour from its position and edge weights.
    #[inline(never)]
    pub(crate) fn see_through<C: Coverage>(
        &mut self,
        setup: &C,
        a: &Attributes,
        shade: impl Fn(u32, u32, [f32; 3]) -> Lin,
        alpha: &AlphaFill<'_>,
    ) -> Filled {
        let grid = self.fb.grid();
        let depth = self.depth;
        let (at, samples, depths) = self.fb.split_mut();
        let (mut covered, mut written) = (0u64, 0u64);
        let tested = setup.walk_samples(grid, self.traversal, |x, y, e| {
            covered += 1;
            let opacity = alpha.at(x, y);
            let blend = match alpha.mode {
                AlphaMode::Mask { cutoff } if opacity < cutoff => return,
                AlphaMode::Blend => true,
                _ => false,
            };
            let i = at.of(x, y);
            let z = a.depth(C::f32(e));
            if depth && !nearer(z, depths[i]) || !depth && !blend && samples[i].is_some() {
                return;
            }
            written += 1;
            let c = shade(x, y, C::f32(e));
            samples[i] = Some(if blend {
                let under = samples[i].unwrap_or(alpha.behind).to_lanes();
                Lin::from_lanes(under + (c.to_lanes() - under) * opacity)
            } else {
                if depth {
                    depths[i] = z;
                }
                c
            });
        });
        if written > 0 {
            self.fb.touch(setup.bounds());
        }
        Filled::of(covered, depth, written, a, tested)
    }

    /// Fills a set-up triangle without a texture: one colour (`flat`), or
    /// interpolated for the samples it is written to (those alone counted
    /// as written).
    #[inline(always)]
    pub(crate) fn colour<C: Coverage>(&mut self, setup: &C, a: &Attributes, flat: bool) -> Filled {
        let grid = self.fb.grid();
        let (at, samples, depths) = self.fb.split_mut();
        let (mut covered, mut written) = (0u64, 0u64);
        let one = Lin::from_lanes(a.color[0]);
        let interpolate = |e: C::Weights| Lin::from_lanes(a.lit(C::f32(e)));
        let depth = |e: C::Weights| a.depth(C::f32(e));
        let tr = self.traversal;
        // One tight loop per combination, so that each inlines; each says
        // whether it tested depth.
        let (tested, depth_tested) = match (flat, self.depth) {
            (true, false) => {
                let tested = setup.walk_samples(grid, tr, |x, y, _| {
                    covered += 1;
                    let i = at.of(x, y);
                    if samples[i].is_none() {
                        samples[i] = Some(one);
                    }
                });
                (tested, false)
            }
            (true, true) => {
                let tested = setup.walk_samples(grid, tr, |x, y, e| {
                    covered += 1;
                    let z = depth(e);
                    let i = at.of(x, y);
                    if nearer(z, depths[i]) {
                        depths[i] = z;
                        samples[i] = Some(one);
                    }
                });
                (tested, true)
            }
            (false, false) => {
                let tested = setup.walk_samples(grid, tr, |x, y, e| {
                    covered += 1;
                    let i = at.of(x, y);
                    if samples[i].is_none() {
                        written += 1;
                        samples[i] = Some(interpolate(e));
                    }
                });
                (tested, false)
            }
            (false, true) => {
                let tested = setup.walk_samples(grid, tr, |x, y, e| {
                    covered += 1;
                    let z = depth(e);
                    let i = at.of(x, y);
                    if nearer(z, depths[i]) {
                        written += 1;
                        depths[i] = z;
                        samples[i] = Some(interpolate(e));
                    }
                });
                (tested, true)
            }
        };
        if covered > 0 {
            self.fb.touch(setup.bounds());
        }
        Filled::of(covered, depth_tested, written, a, tested)
    }
}

/// What a specular fill reads of a triangle, set up once: its vertices'
/// unit normals and positions in the turned world (in the set-up's vertex
/// order), the run's reflectance and roughness, the lights and the eye.
pub(crate) struct Shine<'a> {
    normal: [Vec3A; 3],
    world: [Vec3A; 3],
    /// Reflectance at normal incidence, `None` for a matte run (the full
    /// pipeline sends every run here: a matte one adds nothing).
    f0: Option<Vec3A>,
    /// α², the roughness to the fourth.
    a2: f32,
    /// Reflectance at grazing incidence, which the lobe of `f0` (over it)
    /// is multiplied by.
    f90: f32,
    lights: &'a Lights,
    /// The eye as `(e, k, d)`, towards it from `p` being `e − k·p + d`:
    /// `(eye, 1, 0)` for a point, `(0, 0, direction)` for a direction; no
    /// branch per sample.
    eye: (Vec3A, f32, Vec3A),
    /// [`crate::Highlights::Vertex`]: the highlight found at each corner,
    /// interpolated.
    corners: Option<[Vec3A; 3]>,
    /// A metal's reflection of the environment: the maps, and the metal's
    /// colour, share and perceptual roughness.
    reflect: Option<(&'a EnvMap, (Vec3A, f32, f32))>,
}

/// Where the viewer is: a point (perspective) or, for parallel views, a
/// unit direction towards it.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Eye {
    /// The eye's position.
    At(Vec3),
    /// The direction towards the eye.
    Towards(Vec3),
}

impl Eye {
    /// The direction from `p` to the eye (not of unit length for a point).
    #[inline(always)]
    pub(crate) fn to_eye(self, p: Vec3) -> Vec3 {
        match self {
            Eye::At(e) => e - p,
            Eye::Towards(d) => d,
        }
    }
}

impl<'a> Shine<'a> {
    /// `normal` and `world` in the set-up's vertex order; `finish` is the
    /// run's `(f0 / f90, α², f90)`.
    /// `per_vertex`: found at the corners and interpolated
    /// ([`crate::Highlights::Vertex`]).
    #[inline(always)]
    pub(crate) fn new(
        (normal, world): ([Vec3; 3], [Vec3; 3]),
        finish: Option<(Vec3A, f32, f32)>,
        (lights, eye): (&'a Lights, Eye),
        per_vertex: bool,
        reflect: Option<(&'a EnvMap, (Vec3A, f32, f32))>,
    ) -> Shine<'a> {
        let mut s = Shine {
            normal: normal.map(Vec3A::from),
            world: world.map(Vec3A::from),
            f0: finish.map(|f| f.0),
            a2: finish.map_or(1.0, |f| f.1),
            f90: finish.map_or(1.0, |f| f.2),
            lights,
            eye: match eye {
                Eye::At(e) => (Vec3A::from(e), 1.0, Vec3A::ZERO),
                Eye::Towards(d) => (Vec3A::ZERO, 0.0, Vec3A::from(d)),
            },
            corners: None,
            reflect,
        };
        if per_vertex && let Some(f0) = s.f0 {
            s.corners = Some([0, 1, 2].map(|i| s.light(s.normal[i], s.world[i], f0)));
        }
        s
    }

    /// The specular light at a sample of vertex shares `w`, in the
    /// renderer's linear units; zero for a matte run.
    #[inline(always)]
    fn at(&self, w: [f32; 3]) -> Vec3A {
        let Some(f0) = self.f0 else {
            return Vec3A::ZERO;
        };
        if let Some([a, b, c]) = self.corners {
            return a * w[0] + b * w[1] + c * w[2];
        }
        let n = self.normal[0] * w[0] + self.normal[1] * w[1] + self.normal[2] * w[2];
        let p = self.world[0] * w[0] + self.world[1] * w[1] + self.world[2] * w[2];
        self.light(n, p, f0)
    }

    /// The specular light at a point `p` of normal `n` (any length).
    #[inline(always)]
    fn light(&self, n: Vec3A, p: Vec3A, f0: Vec3A) -> Vec3A {
        let (e, k, d) = self.eye;
        let v = (e - p * k + d).normalize_or_zero();
        let mut n = n.normalize_or_zero();
        // Two-sided: a surface seen from behind shines on its seen side.
        if n.dot(v) < 0.0 {
            n = -n;
        }
        // Times f90 (1 but for `KHR_materials_specular`: exact).
        let lit = self.lights.specular_a(n, v, p, f0, self.a2) * (65535.0 * self.f90);
        match self.reflect {
            Some((env, (metal, share, roughness))) => {
                lit + env.reflect(n, v, metal, roughness) * (share * 65535.0)
            }
            None => lit,
        }
    }
}

/// A surface's colour at sample (`x`, `y`) of edge weights `e`: the lit
/// colour (one, or interpolated), times the texel where it has a texture,
/// plus the highlight where it shines.
#[inline(always)]
pub(crate) fn surface_at(
    a: &Attributes,
    flat: bool,
    texture: Option<(&Texture, Sampler, &UvPlanes)>,
    shine: Option<&Shine<'_>>,
    x: u32,
    y: u32,
    e: [f32; 3],
) -> Lin {
    let mut lit = if flat { a.color[0] } else { a.lit(e) };
    if let Some((texture, sampler, planes)) = texture {
        let (uv, dx, dy) = planes.at(x, y);
        lit *= Vec3A::from(texture.sample(&sampler, uv, dx, dy));
    }
    if let Some(shine) = shine
        && shine.f0.is_some()
    {
        lit += shine.at(a.shares(e));
    }
    Lin::from_lanes(lit)
}

/// A run's alpha as [`Sink::see_through`] applies it.
pub(crate) struct AlphaFill<'a> {
    /// A mask's cut-off, or blending.
    pub mode: AlphaMode,
    /// The material's alpha.
    pub factor: f32,
    /// Its alpha texture, read as the base colour's texture is (same
    /// coordinates and sampler).
    pub texture: Option<(&'a Texture, Sampler, &'a UvPlanes)>,
    /// What a blended sample with nothing drawn under it is composited
    /// over: the scene's background, or black.
    pub behind: Lin,
}

impl AlphaFill<'_> {
    /// The alpha at sample (`x`, `y`).
    #[inline(always)]
    fn at(&self, x: u32, y: u32) -> f32 {
        match self.texture {
            Some((t, s, planes)) => {
                let (uv, dx, dy) = planes.at(x, y);
                self.factor * t.sample(&s, uv, dx, dy).x
            }
            None => self.factor,
        }
    }
}

/// The depth test: whether depth `z` is nearer than what a sample holds
/// (strictly: of two equal depths the first drawn stays; larger is nearer,
/// and an undrawn sample holds −∞).
#[inline(always)]
fn nearer(z: f32, held: f32) -> bool {
    z > held
}

/// Adds the triangle's exact area in each sample's square, times its
/// mean colour, to the accumulator (`--aa exact`). Depth plays no part:
/// exact for scenes whose visible triangles do not overlap; where they
/// do, their areas add up (and the coverage is capped at 1). A texture
/// is read once, at the triangle's centroid, filtered over the whole
/// triangle.
/// Returns what it did, `written` being the texture reads (one, or
/// none).
pub(crate) fn accumulate_exact(
    acc: &mut [[f32; 4]],
    grid: Grid,
    t: &ScreenTriangle,
    texture: Option<(&Texture, Sampler)>,
) -> Filled {
    let mut done = Filled::default();
    let tri = t.xy;
    let mut color = (t.color[0] + t.color[1] + t.color[2]) / 3.0;
    if let Some((texture, sampler)) = texture {
        let [a, b, c] = t.uv;
        color *= texture.sample(&sampler, (a + b + c) / 3.0, b - a, c - a);
        done.written = 1;
    }
    let lo = |k: usize| {
        tri.iter()
            .map(|p| p[k])
            .fold(f64::INFINITY, f64::min)
            .floor()
            .max(0.0) as u32
    };
    let hi = |k: usize, n: u32| {
        (tri.iter()
            .map(|p| p[k])
            .fold(f64::NEG_INFINITY, f64::max)
            .ceil()
            .max(0.0) as u32)
            .min(n)
    };
    let (x0, x1, y0, y1) = (lo(0), hi(0, grid.width), lo(1), hi(1, grid.height));
    for y in y0..y1 {
        for x in x0..x1 {
            let a = crate::accuracy::area_in_square(tri, [x as f64, y as f64]) as f32;
            if a > 0.0 {
                let acc = &mut acc[(y * grid.width + x) as usize];
                *acc = [
                    acc[0] + color.x * a,
                    acc[1] + color.y * a,
                    acc[2] + color.z * a,
                    acc[3] + a,
                ];
                done.covered += 1;
            }
        }
    }
    done.tested = ((x1.saturating_sub(x0)) * (y1.saturating_sub(y0))) as u64;
    done
}

/// A triangle after the divide: screen positions in samples, depth, `1/w`,
/// colours, texture coordinates.
pub(crate) struct ScreenTriangle {
    pub(crate) xy: [[f64; 2]; 3],
    pub(crate) z: [f32; 3],
    pub(crate) inv_w: [f32; 3],
    pub(crate) color: [Vec3; 3],
    pub(crate) uv: [Vec2; 3],
    /// For the specular fill: unit normals and positions in the turned
    /// world.
    pub(crate) shine: Option<([Vec3; 3], [Vec3; 3])>,
}

/// What a fill reads of a triangle at a sample, set up once: its depths
/// and colours in the set-up's vertex order (which starts from the lowest
/// vertex, so the sums below do not depend on the order the triangle was
/// given in), with the weights' perspective scale.
#[derive(Clone, Copy)]
pub(crate) struct Attributes {
    z: [f32; 3],
    z_lo: f32,
    z_hi: f32,
    inv_area: f32,
    /// `1/w` where the plan corrects for perspective (scaled to [1, 2) at
    /// its largest where one is outside [2^−40, 2^40)), else 1.
    w: [f32; 3],
    /// The first vertex's colour, then the others' differences from it
    /// (so that three equal colours interpolate to exactly that colour:
    /// the planned pipeline's plain write of a one-colour triangle and the
    /// full pipeline's interpolation of it agree bit for bit, also once a
    /// texel multiplies them). In SIMD lanes: the same operations on each
    /// channel as three f32s, so the same results, in fewer instructions.
    color: [Vec3A; 3],
    /// Whether `w` holds perspective weights.
    perspective: bool,
}

impl Attributes {
    /// `order` is the set-up's vertex order; `z_w` the depths and `1/w`
    /// and `color` the colours, in the caller's order.
    #[inline(always)]
    pub(crate) fn new(
        order: [usize; 3],
        inv_area: f32,
        [z, inv_w]: [[f32; 3]; 2],
        color: [Vec3; 3],
        perspective: bool,
    ) -> Attributes {
        let z = order.map(|i| z[i]);
        Attributes {
            z,
            // Plain comparisons rather than `f32::min` and `max`, whose
            // rule for a NaN costs a few instructions each: the depths
            // here are finite (inside the clip volume, or cut to it), where
            // the two agree (up to the sign of a zero, which no depth test
            // tells apart).
            z_lo: lesser(lesser(z[0], z[1]), z[2]),
            z_hi: greater(greater(z[0], z[1]), z[2]),
            inv_area,
            // Weights e_i, or e_i / w_i for perspective correction,
            // renormalised.
            w: if perspective {
                // Written out: `map`'s closure was not always inlined
                // here.
                perspective_weights([inv_w[order[0]], inv_w[order[1]], inv_w[order[2]]])
            } else {
                [1.0; 3]
            },
            color: {
                let [a, b, c] = order.map(|i| Vec3A::from(color[i]));
                [a, b - a, c - a]
            },
            perspective,
        }
    }

    /// The depth at a sample of weights `e`, kept within the vertices'.
    #[inline(always)]
    fn depth(&self, e: [f32; 3]) -> f32 {
        let z = (e[0] * self.z[0] + e[1] * self.z[1] + e[2] * self.z[2]) * self.inv_area;
        // `f32::clamp` without its assertion that the range is ordered
        // (it is: see `new`), so nothing here can panic.
        greater(lesser(z, self.z_hi), self.z_lo)
    }

    /// The weights `e` of a sample made the vertices' shares, through
    /// `1/w` where the plan corrects for perspective, summing to 1.
    #[inline(always)]
    fn shares(&self, e: [f32; 3]) -> [f32; 3] {
        let [a, b, c] = self.w;
        let (wa, wb, wc) = (e[0] * a, e[1] * b, e[2] * c);
        let sum = wa + wb + wc;
        [wa / sum, wb / sum, wc / sum]
    }

    /// The colour at a sample of weights `e`.
    #[inline(always)]
    fn lit(&self, e: [f32; 3]) -> Vec3A {
        let [a, b, c] = self.w;
        let [ca, db, dc] = self.color;
        let (wa, wb, wc) = (e[0] * a, e[1] * b, e[2] * c);
        ca + (db * wb + dc * wc) / (wa + wb + wc)
    }
}

/// The lesser of two finite floats (the second when they are equal).
#[inline(always)]
fn lesser(a: f32, b: f32) -> f32 {
    if a < b { a } else { b }
}

/// The greater of two finite floats (the second when they are equal).
#[inline(always)]
fn greater(a: f32, b: f32) -> f32 {
    if a > b { a } else { b }
}

/// A triangle's texture coordinates as functions of the sample position:
/// `u/w`, `v/w` and `1/w` are linear in screen space (`u`, `v` themselves
/// for affine interpolation), so each is a plane, found once per triangle
/// relative to its first vertex. At a sample, `u = (u/w)/(1/w)`, and the
/// derivatives the sampler needs follow exactly from the quotient rule:
/// `∂u/∂x = (∂(u/w)/∂x − u·∂(1/w)/∂x)/(1/w)`.
pub(crate) struct UvPlanes {
    origin: [f64; 2],
    /// Value at the origin, and slopes along x and y: `u/w`, `v/w`, `1/w`.
    u: [f32; 3],
    v: [f32; 3],
    q: [f32; 3],
}

impl UvPlanes {
    pub(crate) fn new(t: &ScreenTriangle, perspective: bool) -> UvPlanes {
        UvPlanes::of(t, t.uv, perspective)
    }

    /// [`UvPlanes::new`] of coordinates `uv` at `t`'s corners (a second
    /// set's).
    pub(crate) fn of(t: &ScreenTriangle, uv: [Vec2; 3], perspective: bool) -> UvPlanes {
        let [p0, p1, p2] = t.xy;
        let (d1, d2) = (
            [p1[0] - p0[0], p1[1] - p0[1]],
            [p2[0] - p0[0], p2[1] - p0[1]],
        );
        let det = d1[0] * d2[1] - d2[0] * d1[1];
        let plane = |f: [f64; 3]| {
            let (f1, f2) = (f[1] - f[0], f[2] - f[0]);
            [
                f[0] as f32,
                ((f1 * d2[1] - f2 * d1[1]) / det) as f32,
                ((f2 * d1[0] - f1 * d2[0]) / det) as f32,
            ]
        };
        // 1/w scaled by a power of two (exact, and the same u).
        let q = if perspective {
            unit_scale(t.inv_w).map(f64::from)
        } else {
            [1.0; 3]
        };
        UvPlanes {
            origin: p0,
            u: plane([0, 1, 2].map(|i| f64::from(uv[i].x) * q[i])),
            v: plane([0, 1, 2].map(|i| f64::from(uv[i].y) * q[i])),
            q: plane(q),
        }
    }

    /// The coordinates at sample `(x, y)`'s centre, and their steps to the
    /// next sample along x and y.
    #[inline]
    fn at(&self, x: u32, y: u32) -> (Vec2, Vec2, Vec2) {
        let dx = (f64::from(x) + 0.5 - self.origin[0]) as f32;
        let dy = (f64::from(y) + 0.5 - self.origin[1]) as f32;
        let at = |p: [f32; 3]| p[0] + p[1] * dx + p[2] * dy;
        let q = at(self.q);
        let (u, v) = (at(self.u) / q, at(self.v) / q);
        (
            Vec2::new(u, v),
            Vec2::new(self.u[1] - u * self.q[1], self.v[1] - v * self.q[1]) / q,
            Vec2::new(self.u[2] - u * self.q[2], self.v[2] - v * self.q[2]) / q,
        )
    }
}

/// `v` times the power of two that brings its largest entry into [1, 2):
/// exact, and the same weights for a scene and that scene scaled by any
/// power of two (a scene 1e-30 across has `1/w` near 1e30, whose products
/// with the edge values would overflow f32).
#[inline(always)]
fn unit_scale(v: [f32; 3]) -> [f32; 3] {
    let max = v[0].max(v[1]).max(v[2]);
    if max.is_normal() {
        // 2^−e for the exponent e of `max`, the factor `pow2_unit` brings it
        // into [1, 2) with, read from its bits: an f32 exactly (2^−127, for
        // the largest exponents, is subnormal but exact).
        let e = ((max.to_bits() >> 23) & 0xff) as i32 - 127;
        if e == 0 {
            return v;
        }
        let k = if e == 127 {
            f32::from_bits(1 << 22)
        } else {
            f32::from_bits(((127 - e) as u32) << 23)
        };
        return v.map(|x| x * k);
    }
    let scaled = transform::pow2_unit(Vec3::new(max, 0.0, 0.0)).x;
    if scaled == max {
        return v;
    }
    // The same power of two for all three: exact.
    let k = scaled / max;
    v.map(|x| x * k)
}

/// The bits of the least and just above the greatest `1/w` that
/// [`perspective_weights`] takes as they are: 2^−40 and 2^40.
const PLAIN_W: (u32, u32) = ((127 - 40) << 23, (127 + 40) << 23);

/// The perspective weights `[a, b, c]` of [`Attributes::lit`]: `v` as it
/// is where each entry is in [2^−40, 2^40), else [`unit_scale`] of it. The
/// same colours either way: a power of two scales every product and sum
/// in `lit` exactly unless one leaves f32's normal range, and in that
/// range none does, scaled or not (edge values are below 2^61, colours
/// below 2^16; the scaled entries stay above 2^−81). Most triangles of
/// most scenes are in range, and skip `unit_scale`'s few dozen
/// instructions.
#[inline(always)]
fn perspective_weights(v: [f32; 3]) -> [f32; 3] {
    let (lo, hi) = PLAIN_W;
    // As u32, a positive finite f32's bits order as its value does; a
    // negative, NaN or infinite one falls outside (and is scaled).
    let plain = |x: f32| x.to_bits().wrapping_sub(lo) < hi - lo;
    if plain(v[0]) & plain(v[1]) & plain(v[2]) {
        v
    } else {
        unit_scale(v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixed::FixedPoint;
    use crate::framebuffer::Framebuffer;
    use crate::raster::{Setup, SnappedTriangle, Traversal};
    use crate::scene::Cull;
    use glam::Vec3;
    use proptest::prelude::*;

    /// A fill's counts are its loops' own: the loops that test depth count
    /// every covered sample as depth-tested and leave a depth at each, the
    /// others count none and leave none; samples written through
    /// perspective weights are counted as such, and only they.
    #[test]
    fn a_fill_counts_the_depth_tests_and_perspective_writes_it_made() {
        let grid = Grid::new(8, 8);
        let p = [[0.3, 0.2], [7.6, 1.1], [2.2, 7.4]].map(|v| FixedPoint::snap(v).unwrap());
        let s = Setup::of(
            &SnappedTriangle::new(p, Cull::None).unwrap(),
            grid,
            grid.all_rows(),
        );
        let (z, inv_w) = ([0.5, 0.26, 0.75], [1.0, 0.5, 0.26]);
        let colors = [
            Vec3::new(65535.0, 0.0, 0.0),
            Vec3::ZERO,
            Vec3::new(0.0, 0.0, 65535.0),
        ];
        for depth in [false, true] {
            for perspective in [false, true] {
                for flat in [false, true] {
                    let mut fb = Framebuffer::new(grid);
                    fb.reset(grid, depth);
                    let a =
                        Attributes::new(s.order(), s.inv_area(), [z, inv_w], colors, perspective);
                    let mut sink = Sink {
                        fb: fb.target(),
                        depth,
                        traversal: Traversal::Spans,
                    };
                    let done = sink.colour(&s, &a, flat);
                    let case = format!("depth {depth}, perspective {perspective}, flat {flat}");
                    // The triangle's area is 25.4 samples.
                    assert_eq!(done.covered, 26, "{case}");
                    assert_eq!(done.depth_tested, if depth { 26 } else { 0 }, "{case}");
                    // An empty framebuffer: every covered sample is written,
                    // with an interpolated colour unless flat.
                    let written = if flat { 0 } else { 26 };
                    assert_eq!(done.written, written, "{case}");
                    assert_eq!(
                        done.perspective,
                        if perspective { written } else { 0 },
                        "{case}"
                    );
                    let depths = (0..8)
                        .flat_map(|y| (0..8).map(move |x| (x, y)))
                        .filter(|&(x, y)| fb.depth(x, y) != f32::NEG_INFINITY)
                        .count();
                    assert_eq!(depths, if depth { 26 } else { 0 }, "{case}");
                }
            }
        }
    }

    proptest! {
        /// The power of two read from the largest weight's bits is the
        /// factor `pow2_unit` brings it into [1, 2) with: the same three
        /// weights, bit for bit, in every binade (the largest and the
        /// smallest exponents included), for zero, subnormal, infinite and
        /// NaN weights as well.
        #[test]
        fn unit_scale_is_pow2_units_factor(
            bits in prop::array::uniform3(prop_oneof![
                any::<u32>(),
                (0u32..256, 0u32..1 << 23).prop_map(|(e, m)| e << 23 | m),
                prop::sample::select(vec![0, 1, 0x7f80_0000, 0x7fc0_0000, 0x3f80_0000, 0x7f7f_ffff, 0x0080_0000]),
            ]),
        ) {
            let v = bits.map(f32::from_bits);
            let max = v[0].max(v[1]).max(v[2]);
            let scaled = transform::pow2_unit(Vec3::new(max, 0.0, 0.0)).x;
            let expected = if scaled == max { v } else { v.map(|x| x * (scaled / max)) };
            prop_assert_eq!(unit_scale(v).map(f32::to_bits), expected.map(f32::to_bits));
        }

        /// Weights of `1/w` in [2^−40, 2^40) are taken as they are, and
        /// give the colours `unit_scale`'s give, bit for bit: at the ends
        /// of the range together, with edge values up to 2^61 and colours
        /// up to 65,535.
        #[test]
        fn plain_weights_colour_as_scaled_ones(
            w in prop::array::uniform3(prop_oneof![
                (PLAIN_W.0..PLAIN_W.1).prop_map(f32::from_bits),
                0.01f32..1.0,
                prop::sample::select(vec![
                    f32::from_bits(PLAIN_W.0),
                    f32::from_bits(PLAIN_W.1 - 1),
                    1.0,
                ]),
            ]),
            e in prop::array::uniform3(prop_oneof![
                0i64..=1 << 61,
                0i64..1000,
                prop::sample::select(vec![0i64, 1, 1 << 61]),
            ]),
            c in prop::array::uniform3(prop::array::uniform3(prop_oneof![
                0u16..=u16::MAX,
                prop::sample::select(vec![0u16, 1, u16::MAX]),
            ])),
        ) {
            prop_assert_eq!(perspective_weights(w).map(f32::to_bits), w.map(f32::to_bits));
            let color = c.map(|c| Vec3::from(c.map(f32::from)));
            let plain = Attributes::new([0, 1, 2], 1.0, [[0.0; 3], w], color, true);
            let scaled = Attributes { w: unit_scale(w), ..plain };
            let e = e.map(|e| e as f32);
            prop_assert_eq!(
                plain.lit(e).to_array().map(f32::to_bits),
                scaled.lit(e).to_array().map(f32::to_bits)
            );
        }

        /// A sample's depth is the interpolated depth clamped to the
        /// vertices' range as `f32::clamp` clamps it (the same number; a
        /// zero's sign aside), for finite depths of any order, zeros of
        /// either sign and equal depths among them, and weights that
        /// overshoot the triangle.
        #[test]
        fn depth_is_clamped_to_the_vertices_range(
            z in prop::array::uniform3(prop_oneof![
                -1f32..1.0,
                prop::sample::select(vec![0.0f32, -0.0, 1.0, -1.0, 0.5]),
            ]),
            e in prop::array::uniform3(-3f32..4.0),
            inv_area in 0.01f32..2.0,
        ) {
            let a = Attributes::new([0, 1, 2], inv_area, [z, [1.0; 3]], [Vec3::ZERO; 3], false);
            let raw = (e[0] * z[0] + e[1] * z[1] + e[2] * z[2]) * inv_area;
            let (lo, hi) = (z[0].min(z[1]).min(z[2]), z[0].max(z[1]).max(z[2]));
            let got = a.depth(e);
            prop_assert!(got == raw.clamp(lo, hi), "{} against {}", got, raw.clamp(lo, hi));
            prop_assert!(lo <= got && got <= hi);
        }
    }
}
