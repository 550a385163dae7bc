//! The vertex stage, four vertices at a time.
//!
//! [`vertex`] takes one vertex through the stage: the model-view-projection
//! product, the clip test, the divide, the viewport and the snap, and for
//! smooth shading the normal's transform, its normalisation and the
//! lights. Most of that is the same arithmetic on x, y and z, so here four
//! vertices go through it together, structure of arrays: the x of four
//! clip positions in one vector, their y in another, and so on, each
//! operation done once for four (the frame's cost is in docs/figures.md). The
//! snap's rounding and the centre keys are done in four `i32` lanes (the
//! `wide` crate: SSE2's integer instructions, with no `unsafe` here, and
//! plain code on targets without them). The normals' scaling by powers of
//! two (`pow2_unit`) is one pair of factors for all four lanes when they
//! share the first one's binade, and four scalar look-ups only otherwise.
//!
//! **The same numbers, bit for bit.** Each lane does exactly the operations
//! [`vertex`] does, in the same order: glam's matrix products are a product
//! per column and then sums from the first column to the last, the dot
//! product `(x·x' + y·y') + z·z'`, the normal is scaled by the same two
//! powers of two before it is normalised, and nothing is fused (no
//! multiply-add). Lane arithmetic is IEEE arithmetic per lane, so the
//! vertices are those of [`vertex`]; a property test compares them field
//! by field, and the frames of the test suite do not move.
//!
//! **Only the common case.** Four vertices take the lanes when all four are
//! inside every clip plane, finite, snap to the grid, and (for smooth
//! shading) have normals whose transform is finite and not zero or
//! subnormal. Any other four go through [`vertex`] one at a time, as does
//! a mesh's last one to three vertices and every mesh under flat shading
//! or point and spot lights (which need world positions, and are not the
//! default). Deciding costs a
//! few lane comparisons; the edge cases keep their single, tested path.

use glam::{Vec3, Vec4};

use super::Stage;
use super::vertex::{Core, Deep, Kept, More, Rest, Transforms, Vert, VertexWork, vertex};
use crate::fixed::FixedPoint;
use crate::plan::Effect;
use crate::plan::Extras;
use crate::raster::CentreKey;
use crate::shade::Shading;
use crate::transform;

/// Appends the vertex stage's result for each of `positions` with its
/// normal, in order, to `out` (and their extras to `kept`, as much of them
/// as `keep` says): what `vertex` gives for each; returns what it did,
/// counted from the paths it took.
#[inline(always)]
pub(super) fn vertices(
    stage: &Stage<'_>,
    t: &Transforms,
    (positions, normals): (&[Vec3], &[Vec3]),
    clip_tests: bool,
    out: &mut Core,
    (kept, keep): (&mut Kept, Extras),
) -> VertexWork {
    let n = positions.len().min(normals.len());
    let (positions, normals) = (&positions[..n], &normals[..n]);
    let shading = stage.plan.shading;
    // `vertex` and the lanes light a vertex exactly when shading is smooth,
    // and test it exactly when `clip_tests` says.
    // Without extras kept, the light is found at set-up (`Lazy`).
    let (rest, keep) = (keep == Extras::All, keep != Extras::Found);
    let mut work = VertexWork {
        vertices: n as u64,
        lit: if shading == Shading::Smooth && keep {
            n as u64
        } else {
            0
        },
        clip_tested: if clip_tests { n as u64 } else { 0 },
        off_path: 0,
    };
    if keep {
        kept.deep.reserve(n);
    }
    if rest {
        kept.rest.reserve(n);
    }
    out.reserve(n);
    let mut off_path = 0;
    let mut one = |out: &mut Core, kept: &mut Kept, p: Vec3, n: Vec3| {
        let (v, m) = vertex(stage, t, p, n, clip_tests);
        off_path += (v.code != 0) as u64;
        out.push(v);
        if keep {
            kept.push(&m, rest);
        }
    };
    if n < 4 || shading == Shading::Flat || stage.plan[Effect::Falloff].run {
        // A loose triangle's three vertices, flat shading, or lights whose
        // light depends on where a vertex is.
        for (&p, &n) in positions.iter().zip(normals) {
            one(out, kept, p, n);
        }
        work.off_path = off_path;
        return work;
    }
    let smooth = shading == Shading::Smooth;
    for (p, nn) in positions.chunks_exact(4).zip(normals.chunks_exact(4)) {
        let (p, nn) = (as_four(p), as_four(nn));
        match four(stage, t, p, nn, clip_tests, smooth && keep) {
            Some((v, m)) => {
                out.push4(v.map(|v| v.key), v.map(|v| v.fixed32));
                if keep {
                    kept.deep.extend(m.each_ref().map(|m| m.deep));
                }
                if rest {
                    kept.rest.extend(m.each_ref().map(|m| m.rest));
                }
            }
            None => {
                for (&p, &n) in p.iter().zip(nn) {
                    one(out, kept, p, n);
                }
            }
        }
    }
    let start = n - n % 4;
    for (&p, &n) in positions[start..].iter().zip(&normals[start..]) {
        one(out, kept, p, n);
    }
    work.off_path = off_path;
    work
}

/// A chunk of four as an array.
#[inline(always)]
fn as_four(v: &[Vec3]) -> &[Vec3; 4] {
    v.try_into().expect("chunks of four")
}

/// One coordinate of four vectors, in lanes.
#[inline(always)]
fn lanes(v: &[Vec3; 4], c: usize) -> Vec4 {
    Vec4::new(v[0][c], v[1][c], v[2][c], v[3][c])
}

/// Four vertices through the stage in lanes, or `None` when one of them is
/// not the common case (see the module doc).
#[inline(always)]
fn four(
    stage: &Stage<'_>,
    t: &Transforms,
    p: &[Vec3; 4],
    n: &[Vec3; 4],
    clip_tests: bool,
    smooth: bool,
) -> Option<([Vert; 4], [More; 4])> {
    let (px, py, pz) = (lanes(p, 0), lanes(p, 1), lanes(p, 2));
    // `mvp * p.extend(1.0)`: the last column times 1, which is itself.
    let m = &t.mvp;
    let s = Vec4::splat;
    let clip =
        |c: usize| s(m.x_axis[c]) * px + s(m.y_axis[c]) * py + s(m.z_axis[c]) * pz + s(m.w_axis[c]);
    let (cx, cy, cz, cw) = (clip(0), clip(1), clip(2), clip(3));
    let (nx, ny, nz) = (lanes(n, 0), lanes(n, 1), lanes(n, 2));
    // Every lane finite, told at once: a sum times zero is zero exactly
    // when each term is finite and the sum does not overflow (NaN
    // otherwise); a sum that overflows sends the four one at a time,
    // which costs time, not bits.
    let finite = ((cx + cy + cz + cw + nx + ny + nz) * Vec4::ZERO).cmpeq(Vec4::ZERO);
    if !finite.all() || (clip_tests && !stage.clipper.inside4(cx, cy, cz, cw)) {
        return None;
    }
    let inv_w = Vec4::ONE / cw;
    let [x, y] = stage.viewport.apply4(cx * inv_w, cy * inv_w);
    let snapped = FixedPoint::snap4(x, y)?;
    let pairs = snapped.pairs();
    let keys = CentreKey::of4(pairs);
    let fixed: [[i32; 2]; 4] = wide::bytemuck::cast(pairs);
    let (normal, light) = if smooth {
        let unit = directions(&t.normal, nx, ny, nz)?;
        (unit, stage.lights.lambert4(unit))
    } else {
        ([Vec4::ZERO; 3], [Vec4::ZERO; 3])
    };
    // Unread where the extras are not kept (`smooth` is then false too).
    let z = cz * inv_w;
    let (xs, ys, zs, ws) = (x.to_array(), y.to_array(), z.to_array(), inv_w.to_array());
    let [n0, n1, n2] = normal;
    let [l0, l1, l2] = light;
    let (n0, n1, n2) = (n0.to_array(), n1.to_array(), n2.to_array());
    let (l0, l1, l2) = (l0.to_array(), l1.to_array(), l2.to_array());
    let vert = |i: usize| Vert {
        code: 0,
        fixed32: fixed[i],
        key: keys[i],
    };
    let more = |i: usize| More {
        deep: Deep {
            light: Vec3::new(l0[i], l1[i], l2[i]),
            z: zs[i],
            inv_w: ws[i],
        },
        rest: Rest {
            world: Vec3::ZERO,
            normal: Vec3::new(n0[i], n1[i], n2[i]),
            xy: [xs[i], ys[i]],
        },
    };
    Some((
        [vert(0), vert(1), vert(2), vert(3)],
        [more(0), more(1), more(2), more(3)],
    ))
}

/// The [`super::vertex::deep`] of four vertices (positions `p`, normals
/// `n`), in lanes: the operations [`four`] does for their depth, `1/w` and
/// light, so the same bits; `None` where a lane is not the common case
/// (a normal [`directions`] refuses, or lights that fall off), for the
/// caller to find one at a time. Out of line, so that inlining it into
/// `Lazy::deep3` does not change how the compiler lays out the face loops
/// of meshes that keep their extras.
#[inline(never)]
pub(super) fn deep4(
    stage: &Stage<'_>,
    t: &Transforms,
    p: &[Vec3; 4],
    n: &[Vec3; 4],
) -> Option<[Deep; 4]> {
    if stage.plan[Effect::Falloff].run {
        return None;
    }
    let (px, py, pz) = (lanes(p, 0), lanes(p, 1), lanes(p, 2));
    let m = &t.mvp;
    let s = Vec4::splat;
    let clip =
        |c: usize| s(m.x_axis[c]) * px + s(m.y_axis[c]) * py + s(m.z_axis[c]) * pz + s(m.w_axis[c]);
    let inv_w = Vec4::ONE / clip(3);
    let z = clip(2) * inv_w;
    let [l0, l1, l2] = if stage.plan.shading == Shading::Smooth {
        let unit = directions(&t.normal, lanes(n, 0), lanes(n, 1), lanes(n, 2))?;
        stage.lights.lambert4(unit)
    } else {
        [Vec4::ZERO; 3]
    };
    let (zs, ws) = (z.to_array(), inv_w.to_array());
    let (l0, l1, l2) = (l0.to_array(), l1.to_array(), l2.to_array());
    Some(std::array::from_fn(|i| Deep {
        light: Vec3::new(l0[i], l1[i], l2[i]),
        z: zs[i],
        inv_w: ws[i],
    }))
}

/// `transform::direction(k * n)` for four normals in lanes, or `None` when
/// one of them is not finite, or zero or subnormal at its largest.
#[inline(always)]
fn directions(k: &glam::Mat3, nx: Vec4, ny: Vec4, nz: Vec4) -> Option<[Vec4; 3]> {
    let s = Vec4::splat;
    let row = |c: usize| s(k.x_axis[c]) * nx + s(k.y_axis[c]) * ny + s(k.z_axis[c]) * nz;
    let (x, y, z) = (row(0), row(1), row(2));
    // Each finite (as in [`four`]: a sum that overflows says no).
    if !((x + y + z) * Vec4::ZERO).cmpeq(Vec4::ZERO).all() {
        return None;
    }
    let (x, y, z) = pow2_units(x, y, z)?;
    // `normalize_or_zero`: never zero here, the largest entry is in [1, 2).
    let rcp = Vec4::ONE / (x * x + y * y + z * z).sqrt();
    Some([x * rcp, y * rcp, z * rcp])
}

/// `transform::pow2_unit` of four vectors in lanes (each lane times the
/// powers of two that bring its largest entry into [1, 2)), or `None` when
/// one of them is zero or subnormal at its largest, or not finite.
#[inline(always)]
fn pow2_units(x: Vec4, y: Vec4, z: Vec4) -> Option<(Vec4, Vec4, Vec4)> {
    let max = x.abs().max(y.abs()).max(z.abs());
    // Most often all four are in one binade, the first's: its factors
    // serve all four (`lo` and `2·lo` are exact powers of two; a NaN fails
    // both comparisons). Otherwise each lane's own.
    let (a0, b0) = transform::pow2_factors(max.x)?;
    let lo = 1.0 / (a0 * b0);
    let (a, b) = if (max.cmpge(Vec4::splat(lo)) & max.cmplt(Vec4::splat(2.0 * lo))).all() {
        (Vec4::splat(a0), Vec4::splat(b0))
    } else {
        let max = max.to_array();
        let (mut a, mut b) = ([0.0; 4], [0.0; 4]);
        for i in 0..4 {
            (a[i], b[i]) = transform::pow2_factors(max[i])?;
        }
        (Vec4::from_array(a), Vec4::from_array(b))
    };
    Some((x * a * b, y * a * b, z * a * b))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::clip::Clipper;
    use crate::color::Rgb;
    use crate::options::RenderOptions;
    use crate::plan::Plan;
    use crate::render::Eye;
    use crate::render::vertex::{Transforms, deep};
    use crate::scene::{Scene, Shape};
    use crate::shade::Lights;
    use crate::transform::Viewport;
    use proptest::prelude::*;

    /// A coordinate: mostly in the unit cube the model spans, sometimes
    /// far outside it, on the camera's side of it, or not finite.
    fn coord() -> impl Strategy<Value = f32> + Clone {
        prop_oneof![
            12 => -1.2f32..1.2,
            1 => -40f32..40.0,
            1 => prop::sample::select(vec![0.0, -0.0, 1e-40, 3e38, f32::NAN, f32::INFINITY]),
        ]
    }

    /// A normal entry: mostly of ordinary size, sometimes zero, subnormal,
    /// huge or not finite.
    fn normal() -> impl Strategy<Value = f32> + Clone {
        prop_oneof![
            12 => -1f32..1.0,
            1 => prop::sample::select(vec![0.0, 1e-39, -1e-45, 1e30, f32::NAN, f32::NEG_INFINITY]),
        ]
    }

    fn vec3(c: impl Strategy<Value = f32> + Clone) -> impl Strategy<Value = Vec3> {
        (c.clone(), c.clone(), c).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    /// A vertex's fields as bits, so that equal means the same bits.
    fn bits((v, m): (&Vert, &More)) -> Vec<u64> {
        let f = |x: f32| x.to_bits() as u64;
        let mut b = vec![v.code as u64, v.fixed().x.0 as u64, v.fixed().y.0 as u64];
        b.extend(
            [m.rest.world, m.rest.normal, m.deep.light]
                .iter()
                .flat_map(|v| v.to_array().map(f)),
        );
        b.extend([m.rest.xy[0], m.rest.xy[1], m.deep.z, m.deep.inv_w].map(f));
        b
    }

    /// The stage for the cube's scene seen at `cols × rows`, and its
    /// transforms.
    fn with_stage(
        shading: Shading,
        cols: u16,
        rows: u16,
        turn: Vec3,
        f: impl FnOnce(&Stage<'_>, &Transforms),
    ) {
        let scene = Scene::of_mesh(Shape::Cube.mesh(Rgb::WHITE));
        let opts = RenderOptions {
            cols,
            rows,
            shading,
            turn,
            ..Default::default()
        };
        let grid = opts.grid();
        let cam = (scene.camera).resolved_turning(opts.aspect(), opts.turn, opts.turn_axis);
        let vp = cam.view_projection(opts.aspect());
        let clipper = Clipper::for_projection(grid.width, grid.height, &cam.projection);
        let turn = transform::rotation(opts.turn);
        let plan = Plan::new(&scene, &opts, vp, turn, &clipper);
        let stage = Stage {
            exact: false,
            clipper,
            plan: &plan,
            viewport: Viewport::new(grid.width as f32, grid.height as f32),
            lights: Lights::new(&scene.lights),
            traversal: opts.traversal,
            highlights: opts.highlights,
            precision: opts.precision,
            eye: Eye::Towards(Vec3::Z),
            behind: crate::color::Lin::BLACK,
            edge_bias: Default::default(),
            environment: None,
        };
        f(&stage, &Transforms::new(vp, turn * scene.meshes[0].model));
    }

    /// Four ordinary vertices (inside the view, finite, unit normals) do
    /// take the lanes, with and without clip tests and smooth or no
    /// shading, and come out as one at a time: the property test below
    /// compares the two paths wherever they are taken, which this test makes
    /// sure includes the lanes.
    #[test]
    fn ordinary_vertices_take_the_lanes() {
        let p = [
            Vec3::new(0.5, 0.5, 0.5),
            Vec3::new(-0.5, 0.25, 0.0),
            Vec3::new(0.0, -0.75, 0.5),
            Vec3::new(0.25, 0.0, -0.5),
        ];
        // Normals of no special direction, whose products round.
        let n = [
            Vec3::new(0.3127, 0.5411, 0.7809),
            Vec3::new(-0.6173, 0.2291, 0.7533),
            Vec3::new(0.1103, -0.9137, 0.3911),
            Vec3::new(0.7023, 0.1235, -0.6963),
        ];
        for shading in [Shading::Smooth, Shading::None] {
            with_stage(shading, 80, 24, Vec3::new(10.0, 20.0, 0.0), |stage, t| {
                for clip_tests in [false, true] {
                    let smooth = shading == Shading::Smooth;
                    let (four, more) =
                        four(stage, t, &p, &n, clip_tests, smooth).expect("the lanes");
                    for i in 0..4 {
                        let (one, one_more) = vertex(stage, t, p[i], n[i], clip_tests);
                        assert_eq!(
                            bits((&four[i], &more[i])),
                            bits((&one, &one_more)),
                            "vertex {i}"
                        );
                    }
                }
            });
        }
    }

    proptest! {
        /// Four at a time in lanes, the vertex stage gives every vertex the
        /// same bits as one at a time: for any turn, size, shading and clip
        /// tests on or off, with vertices outside the view or not finite and
        /// normals zero, subnormal or not finite among them, and meshes of
        /// any length (not only multiples of four).
        #[test]
        fn four_at_a_time_is_one_at_a_time(
            vertices_in in prop::collection::vec((vec3(coord()), vec3(normal())), 0..14),
            shading in prop::sample::select(vec![Shading::Smooth, Shading::None, Shading::Flat]),
            clip_tests: bool,
            turn in vec3(-180f32..180.0),
            (cols, rows) in (1u16..300, 1u16..100),
        ) {
            let (positions, normals): (Vec<Vec3>, Vec<Vec3>) = vertices_in.into_iter().unzip();
            let (mut four, mut kept, mut one) = (Core::default(), Kept::default(), Vec::new());
            let mut deep = Kept::default();
            with_stage(shading, cols, rows, turn, |stage, t| {
                let vs = (&positions[..], &normals[..]);
                vertices(stage, t, vs, clip_tests, &mut four, (&mut kept, Extras::All));
                one.extend(
                    positions.iter().zip(&normals).map(|(&p, &n)| vertex(stage, t, p, n, clip_tests)),
                );
                // With less kept, the same vertices, and the same depth
                // and light where those are kept.
                let verts = |v: &[Vert]| v.iter().map(|v| bits((v, &More::default()))).collect::<Vec<_>>();
                let (mut alone, mut lean) = (Core::default(), Core::default());
                let mut none = Kept::default();
                vertices(stage, t, vs, clip_tests, &mut alone, (&mut none, Extras::Found));
                vertices(stage, t, vs, clip_tests, &mut lean, (&mut deep, Extras::Deep));
                assert_eq!(verts(&alone.to_vec()), verts(&four.to_vec()));
                assert_eq!(verts(&lean.to_vec()), verts(&four.to_vec()));
                assert_eq!((none.deep.len(), none.rest.len(), deep.rest.len()), (0, 0, 0));
            });
            prop_assert_eq!(four.len(), one.len());
            prop_assert_eq!(kept.deep.len(), one.len());
            prop_assert_eq!(kept.rest.len(), one.len());
            let deep_bits = |d: &[Deep]| {
                d.iter()
                    .flat_map(|d| [d.light.x, d.light.y, d.light.z, d.z, d.inv_w].map(f32::to_bits))
                    .collect::<Vec<_>>()
            };
            prop_assert_eq!(deep_bits(&deep.deep), deep_bits(&kept.deep));
            let more = kept.deep.iter().zip(&kept.rest).map(|(&deep, &rest)| More { deep, rest });
            for (i, ((a, m), (b, n))) in four.to_vec().iter().zip(more).zip(&one).enumerate() {
                prop_assert_eq!(bits((a, &m)), bits((b, n)), "vertex {}: {:?} {:?}", i, a, b);
            }
        }
    }

    proptest! {
        /// The depth, `1/w` and light found again at set-up four at a time
        /// ([`deep4`], for a mesh whose vertex stage keeps none) are each
        /// vertex's own ([`deep`]), bit for bit, wherever the lanes take
        /// them; and ordinary vertices do take them.
        #[test]
        fn deep_found_four_at_a_time_is_one_at_a_time(
            vertices_in in prop::collection::vec((vec3(coord()), vec3(normal())), 4),
            shading in prop::sample::select(vec![Shading::Smooth, Shading::None]),
            turn in vec3(-180f32..180.0),
            ordinary: bool,
        ) {
            let (mut p, mut n): (Vec<Vec3>, Vec<Vec3>) = vertices_in.into_iter().unzip();
            if ordinary {
                // Inside the cube, normals of ordinary size.
                p.iter_mut().for_each(|p| *p = p.clamp(Vec3::splat(-1.0), Vec3::splat(1.0)));
                n.iter_mut().for_each(|n| *n = Vec3::new(0.25, -0.5, 0.75) + n.clamp(Vec3::splat(-0.2), Vec3::splat(0.2)));
            }
            let (p, n): ([Vec3; 4], [Vec3; 4]) = (p.try_into().unwrap(), n.try_into().unwrap());
            let deep_bits = |d: &Deep| [d.light.x, d.light.y, d.light.z, d.z, d.inv_w].map(f32::to_bits);
            with_stage(shading, 80, 24, turn, |stage, t| {
                let lanes = deep4(stage, t, &p, &n);
                assert!(lanes.is_some() || !ordinary, "ordinary vertices take the lanes");
                for (i, d) in lanes.iter().flatten().enumerate() {
                    assert_eq!(deep_bits(d), deep_bits(&deep(stage, t, p[i], n[i])), "vertex {i}");
                }
            });
        }
    }

    /// Four vectors scaled in lanes are each scaled as `pow2_unit` scales
    /// one: all four in one binade (the shared factors), across binades,
    /// at their edges (exact powers of two and the floats below them), at
    /// the largest and smallest normal exponents, and `None` exactly when a
    /// lane is zero, subnormal or not finite at its largest.
    #[test]
    fn four_scaled_in_lanes_are_each_scaled_alone() {
        let edges = |e: i32| {
            let p = 2f32.powi(e);
            [
                p,
                f32::from_bits(p.to_bits() - 1),
                f32::from_bits(p.to_bits() + 1),
            ]
        };
        let mut values: Vec<f32> = [-126, -64, -1, 0, 1, 2, 63, 127]
            .into_iter()
            .flat_map(edges)
            .collect();
        values.extend([
            0.7,
            -0.9,
            1.5,
            3.0,
            f32::MAX,
            0.0,
            1e-40,
            f32::NAN,
            f32::INFINITY,
        ]);
        let n = values.len();
        // Lanes drawn from the values (the same one in many lanes, so that
        // shared binades are common), each vector's largest in x, y or z.
        let mut seed = 0x9e37_79b9u32;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 17;
            seed ^= seed << 5;
            seed as usize
        };
        for _ in 0..20_000 {
            let base = next() % n;
            let v: [Vec3; 4] = std::array::from_fn(|_| {
                // Two lanes in three share the draw's binade, on average.
                let k = next();
                let big = if k % 3 != 0 {
                    values[base]
                } else {
                    values[k % n]
                };
                let small = values[next() % n] * 0.25;
                match next() % 3 {
                    0 => Vec3::new(big, small, -small),
                    1 => Vec3::new(small, -big, small),
                    _ => Vec3::new(-small, small, big),
                }
            });
            let lane = |c: usize| Vec4::new(v[0][c], v[1][c], v[2][c], v[3][c]);
            let got = pow2_units(lane(0), lane(1), lane(2));
            let alone: Vec<Option<Vec3>> = v
                .iter()
                .map(|v| {
                    transform::pow2_factors(v.abs().max_element()).map(|_| transform::pow2_unit(*v))
                })
                .collect();
            match got {
                None => assert!(alone.iter().any(Option::is_none), "{v:?}"),
                Some((x, y, z)) => {
                    let (x, y, z) = (x.to_array(), y.to_array(), z.to_array());
                    for (i, one) in alone.iter().enumerate() {
                        let one = one.expect("every lane scales");
                        let bits = |v: Vec3| v.to_array().map(f32::to_bits);
                        assert_eq!(bits(Vec3::new(x[i], y[i], z[i])), bits(one), "{v:?}");
                    }
                }
            }
        }
    }
}
