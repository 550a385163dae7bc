//! Normals at load: angle-weighted, with the crease rule, from the
//! connectivity of `topology.rs`. The layout and the reasons are in
//! `mesh.rs`.
//!
//! **Normals** are summed in passes over the faces in order, each face's
//! normal and its three corner angles found once, rather than once for each
//! of its corners from the positions' side: the sums come out in the same
//! order, and the frames of every shared model are the same bytes (a
//! property test holds every corner to the definition, computed corner by
//! corner). A position's sum and its sum of weights are one `[f32; 4]`,
//! one read and one write a corner, which become the vertices' normals in
//! place and are narrowed to a `Vec3` each into the same allocation. Four
//! faces are found at once, a face a SIMD lane ([`face_weights4`]), and
//! four positions' means at once ([`direction4`]): each lane runs the
//! operations of the one-at-a-time code in its order, so the same bits,
//! which property tests hold them to (the transposes in and out cost less
//! than the shuffles a face's three lanes of four needed). Whether a position's
//! faces stay within half the crease of their mean is first bounded from
//! the sums alone (see [`smooth_normals`]); only the positions the bound
//! does not settle are tested face by face, and only creased ones (and those
//! on a face of no area) take the per-position pass. What it costs is in
//! docs/figures.md ("Loading").

use glam::{Vec3, Vec3A, Vec4};

use super::topology::{Own, Topology, Welded};

/// Positions with more faces around them than this are smoothed without
/// creases (the crease test is quadratic in the faces around a position).
pub(super) const MAX_CREASE_FAN: usize = 256;

/// The angles whose sines and cosines are `sin` ≥ 0 and `cos`, lane by
/// lane (each pair up to a common positive factor: only their ratio
/// counts), in radians, within 1e-6: the arctangent of the smaller over
/// the larger, by an odd minimax polynomial of degree 15 on [0, 1] (error
/// below 4e-8 before f32 rounding), then reflected into place. A weight,
/// where libm's `atan2` cost a seventh of loading a large model; a face's
/// three corners in one go.
pub(super) fn angles(sin: Vec4, cos: Vec4) -> Vec4 {
    use std::f32::consts::{FRAC_PI_2, PI};
    const C: [f32; 8] = [
        0.999_999_3,
        -0.333_298_56,
        0.199_465_36,
        -0.139_085_33,
        0.096_420_04,
        -0.055_909_886,
        0.021_861_23,
        -0.004_054_058,
    ];
    let (a, b) = (sin.abs(), cos.abs());
    let t = a.min(b) / a.max(b);
    let t2 = t * t;
    let r = t * C
        .iter()
        .rev()
        .fold(Vec4::ZERO, |p, &c| p * t2 + Vec4::splat(c));
    let r = Vec4::select(a.cmpgt(b), Vec4::splat(FRAC_PI_2) - r, r);
    Vec4::select(cos.cmplt(Vec4::ZERO), Vec4::splat(PI) - r, r)
}

/// A face's unit normal and its edges `b − a`, `c − b`, `a − c` scaled
/// together by the power of two that brings their largest component into
/// [1, 2) (exact, so any scale gives the same bits; see
/// `transform::pow2_unit`), or `None` for a face of no area (or not
/// finite). Lanes: x, y, z; SSE where the target has it.
#[inline]
fn face_frame(a: Vec3, b: Vec3, c: Vec3) -> Option<(Vec3A, f32, [Vec3A; 3])> {
    let (a, b, c) = (Vec3A::from(a), Vec3A::from(b), Vec3A::from(c));
    let (ab, bc, ca) = (b - a, c - b, a - c);
    let max = ab.abs().max(bc.abs()).max(ca.abs()).max_element();
    let (s, t) = crate::transform::pow2_factors(max)?;
    let (ab, bc, ca) = (ab * s * t, bc * s * t, ca * s * t);
    let cross = ab.cross(-ca);
    let twice_area = cross.length();
    // No component of the cross product is longer than it, and none
    // overflows with the largest edge component below 2: a finite, positive
    // length gives a finite unit normal.
    (twice_area > 0.0 && twice_area < f32::INFINITY)
        .then(|| (cross / twice_area, twice_area, [ab, bc, ca]))
}

/// A face's unit normal and its angle at each corner (see [`face_frame`]):
/// one cross product gives the normal and, as its length, twice the area,
/// the sine at every corner up to the product of the corner's edge
/// lengths, which cancels in the angle's ratio, as it does in the dots'
/// cosine.
#[inline]
pub(super) fn face_weights(a: Vec3, b: Vec3, c: Vec3) -> Option<(Vec3A, Vec3A)> {
    let (n, twice_area, [ab, bc, ca]) = face_frame(a, b, c)?;
    let cos = Vec4::new(-ab.dot(ca), -bc.dot(ab), -ca.dot(bc), 0.0);
    Some((n, angles(Vec4::splat(twice_area), cos).truncate().into()))
}

/// [`crate::transform::pow2_factors`] of four numbers at once, lane by
/// lane the same integer steps on the exponent (which the compiler lays out
/// in SIMD lanes): the two factors (1 where there are none) and which lanes
/// have them, a bit each.
#[inline(always)]
pub(super) fn pow2_factors4(max: Vec4) -> (Vec4, Vec4, u32) {
    let bits = [
        max.x.to_bits(),
        max.y.to_bits(),
        max.z.to_bits(),
        max.w.to_bits(),
    ];
    let mut s = [0u32; 4];
    let mut t = [0u32; 4];
    let mut normal = 0u32;
    for j in 0..4 {
        let exponent = bits[j] >> 23 & 0xff;
        // Normal: a biased exponent from 1 to 254.
        let ok = exponent.wrapping_sub(1) < 254;
        let e = exponent as i32 - 127;
        // −e / 2, rounded toward zero, as Rust's `/` rounds.
        let a = (-e + ((-e) as u32 >> 31) as i32) >> 1;
        let b = -e - a;
        // Without branches: all ones where normal.
        let keep = 0u32.wrapping_sub(ok as u32);
        let one = 1.0f32.to_bits() & !keep;
        s[j] = (((a + 127) as u32) << 23) & keep | one;
        t[j] = (((b + 127) as u32) << 23) & keep | one;
        normal |= (ok as u32) << j;
    }
    let f = |v: [u32; 4]| {
        Vec4::new(
            f32::from_bits(v[0]),
            f32::from_bits(v[1]),
            f32::from_bits(v[2]),
            f32::from_bits(v[3]),
        )
    };
    (f(s), f(t), normal)
}

/// [`crate::transform::direction`] of four vectors at once, a vector a
/// lane (`[x, y, z]`), lane by lane the same steps: brought to a largest
/// component in [1, 2) by two powers of two (by 1 where there are none,
/// which changes nothing), then divided by the length's reciprocal times
/// itself, or zero where that reciprocal is not finite and positive.
#[inline(always)]
pub(super) fn direction4([x, y, z]: [Vec4; 3]) -> [Vec4; 3] {
    // `max` as glam's scalar max_element takes it: the second where the
    // first is not larger (as SSE's max does).
    let (s, t, _) = pow2_factors4(x.abs().max(y.abs().max(z.abs())));
    let (x, y, z) = (x * s * t, y * s * t, z * s * t);
    let rcp = Vec4::ONE / (x * x + y * y + z * z).sqrt();
    let ok = rcp.cmplt(Vec4::INFINITY) & rcp.cmpgt(Vec4::ZERO);
    let keep = |v: Vec4| Vec4::select(ok, v * rcp, Vec4::ZERO);
    [keep(x), keep(y), keep(z)]
}

/// Four faces at once, a face a lane: `corner[k][axis]` holds that
/// coordinate of corner `k` of each face.
pub(super) type Corners4 = [[Vec4; 3]; 3];

/// What [`face_weights4`] finds for four faces.
pub(super) struct Weights4 {
    /// `corner[k][j]`: at corner `k` of face `j`, the face's unit normal
    /// times its angle there (x, y, z) and the angle (w).
    pub(super) corner: [[Vec4; 4]; 3],
    /// Which faces have area, a bit each (the others' numbers mean
    /// nothing).
    pub(super) area: u32,
}

/// [`face_weights`] of four faces at once, lane by lane the same
/// operations in the same order, so the same bits (a test holds them to
/// it): each step of one face runs on four faces' numbers in one SIMD
/// operation, where [`face_weights`] fills three lanes of four and
/// shuffles them for its cross and dot products.
#[inline(always)]
pub(super) fn face_weights4([a, b, c]: Corners4) -> Weights4 {
    let sub = |p: [Vec4; 3], q: [Vec4; 3]| [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
    let (ab, bc, ca) = (sub(b, a), sub(c, b), sub(a, c));
    // The largest component's magnitude: a NaN it drops makes the cross
    // product NaN below, and the face one of no area, as in face_frame.
    let max = [ab, bc, ca]
        .iter()
        .flatten()
        .fold(Vec4::ZERO, |m, v| m.max(v.abs()));
    let (s, t, mut area) = pow2_factors4(max);
    // (Not `[T; N]::map`, which is not always inlined.)
    let scale = |[x, y, z]: [Vec4; 3]| [x * s * t, y * s * t, z * s * t];
    let (ab, bc, ca) = (scale(ab), scale(bc), scale(ca));
    // ab × (−ca), each component as glam's cross makes it.
    let v = [-ca[0], -ca[1], -ca[2]];
    let cross = [
        ab[1] * v[2] - v[1] * ab[2],
        ab[2] * v[0] - v[2] * ab[0],
        ab[0] * v[1] - v[0] * ab[1],
    ];
    // Dot products as glam's: (x + y) + z.
    let dot = |p: [Vec4; 3], q: [Vec4; 3]| p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
    let twice_area = dot(cross, cross).sqrt();
    area &= (twice_area.cmpgt(Vec4::ZERO) & twice_area.cmplt(Vec4::INFINITY)).bitmask();
    let n = [
        cross[0] / twice_area,
        cross[1] / twice_area,
        cross[2] / twice_area,
    ];
    let angle = [
        angles(twice_area, -dot(ab, ca)),
        angles(twice_area, -dot(bc, ab)),
        angles(twice_area, -dot(ca, bc)),
    ];
    // Lanes to faces: one transpose a corner.
    let corner = |w: Vec4| {
        let m = glam::Mat4::from_cols(n[0] * w, n[1] * w, n[2] * w, w).transpose();
        [m.x_axis, m.y_axis, m.z_axis, m.w_axis]
    };
    Weights4 {
        corner: [corner(angle[0]), corner(angle[1]), corner(angle[2])],
        area,
    }
}

/// Per position: proven one smooth fan, to be tested, or creased.
const SMOOTH: u8 = 0;
const TEST: u8 = 1;
const CREASED: u8 = 2;

/// The first pass's tables, each indexed by welded position.
struct Sums<'a> {
    /// Each position's sum of weighted face normals (x, y, z) and of the
    /// weights (w): one read and one write a corner.
    sums: &'a mut [[f32; 4]],
    /// Each position's least weight.
    least: &'a mut [f32],
    /// Each position's state (`SMOOTH`, `TEST` or `CREASED`).
    state: &'a mut [u8],
}

impl Sums<'_> {
    /// Adds every face to the sums, in order: four at a time, a face a
    /// lane; the last few padded with copies of the last face, whose sums
    /// are not added.
    fn add_all(&mut self, positions: &[Vec3], ids: impl Welded, faces: &[[u32; 3]]) {
        let fours = faces.as_chunks::<4>();
        for four in fours.0 {
            self.add_four(positions, ids, four, 4);
        }
        if let Some(&last) = fours.1.last() {
            let mut four = [last; 4];
            four[..fours.1.len()].copy_from_slice(fours.1);
            self.add_four(positions, ids, &four, fours.1.len());
        }
    }

    /// Adds the first `len` of faces `four` to the sums, in order (faces
    /// of no area mark their positions for the per-position pass).
    #[inline(always)]
    fn add_four(&mut self, positions: &[Vec3], ids: impl Welded, four: &[[u32; 3]; 4], len: usize) {
        // One length for each kind of table, so that one bounds check
        // serves all of a kind.
        let n = self.sums.len();
        let (sums, least, state) = (&mut *self.sums, &mut self.least[..n], &mut self.state[..n]);
        let ids = ids.first(positions.len());
        let mut at = [[0usize; 3]; 4];
        // Corner k of the four faces: four positions, transposed to lanes.
        let mut corner = |k: usize| {
            let mut p = [Vec4::ZERO; 4];
            for j in 0..4 {
                let v = four[j][k] as usize;
                p[j] = Vec3A::from(positions[v]).extend(0.0);
                at[j][k] = ids.of(v as u32) as usize;
            }
            let m = glam::Mat4::from_cols(p[0], p[1], p[2], p[3]).transpose();
            [m.x_axis, m.y_axis, m.z_axis]
        };
        let w = face_weights4([corner(0), corner(1), corner(2)]);
        // Face by face, in order.
        for (j, p) in at.into_iter().enumerate().take(len) {
            if w.area >> j & 1 == 0 {
                p.iter().for_each(|&p| state[p] = CREASED);
                continue;
            }
            for k in 0..3 {
                let v = w.corner[k][j];
                let sum = &mut sums[p[k]];
                *sum = (Vec4::from_array(*sum) + v).to_array();
                // `min`, as one comparison: the least is never NaN (it
                // starts at infinity), and a NaN weight leaves it as `min`
                // does.
                let l = &mut least[p[k]];
                *l = if v.w < *l { v.w } else { *l };
            }
        }
    }
}

/// Angle-weighted normals per position with creases (see the module doc):
/// one per vertex, and the corners `(face, corner, normal)` that need a
/// vertex of their own because their vertex index is shared across a
/// crease. A vertex on no face (or only degenerate ones) gets +z.
///
/// In three passes over the faces, in order, with no per-corner storage:
/// the weighted normals summed per welded position (in corner order, the
/// order the per-position pass adds them in); then every corner tested
/// against its position's mean, which marks the few positions with a crease
/// (or a face of no area) for the per-position pass over their corners
/// alone; then each vertex given its position's mean.
// Out of line: the inliner took it into `Geometry::compute_normals` after
// unrelated changes elsewhere in the crate, where it cost more (the
// normals row of docs/figures.md).
#[inline(never)]
pub(super) fn smooth_normals(
    topo: &Topology,
    positions: &[Vec3],
    faces: &[[u32; 3]],
    crease: f32,
) -> (Vec<Vec3>, Vec<(u32, u8, Vec3)>) {
    use crate::transform::direction;
    let cos_crease = crease.to_radians().cos();
    let cos_half = (crease / 2.0).to_radians().cos();
    let id = |v: u32| topo.id(v) as usize;
    let corners = |f: &[u32; 3]| f.map(|v| positions[v as usize]);
    // The normals, one per vertex, are first each position's sum of
    // weighted face normals and of the weights, then its mean (position
    // `p` at index `p`, which no vertex before it needs: ids are numbered
    // in order of first appearance, so `ids[v] <= v`), then, in place,
    // each vertex's, narrowed at last into the same allocation: no buffer
    // of sums beside them (at load, this is where memory peaks).
    let mut sums = vec![[0.0f32; 4]; positions.len()];
    // Per position: the least weight.
    let mut least = vec![f32::INFINITY; topo.welded()];
    let mut state = vec![SMOOTH; topo.welded()];
    {
        let mut sums = Sums {
            sums: &mut sums[..topo.welded()],
            least: &mut least,
            state: &mut state,
        };
        // Four faces at a time, a face a lane; the last few padded with
        // copies of the last face, whose sums are not added.
        match &topo.ids {
            Some(ids) => sums.add_all(positions, ids.as_slice(), faces),
            None => sums.add_all(positions, Own, faces),
        }
    }
    // One smooth fan when every face is within half the crease angle of
    // the mean (so any two are within the crease of each other): the common
    // case. Each face's normal is a unit vector, so the sum's length is
    // Σ w·(n·mean) ≤ W − w_f·(1 − n_f·mean) for any face f: a sum longer
    // than W − w_least·(1 − cos_half) (with a margin far above the f32
    // rounding of a fan of 256) proves that no face is as far out as half
    // the crease, and only the positions it does not prove are tested face
    // by face, with the very test the per-position pass made.
    let mut test = false;
    // The sums become the means, in place, four at a time (a position a
    // lane), then the last few one by one: the same bits either way.
    let bound = |total: f32, least: f32| total - least * (1.0 - cos_half) + 1e-4 * total;
    let bound4 = |total: Vec4, least: Vec4| total - least * (1.0 - cos_half) + 1e-4 * total;
    let mut settle = |p: usize, state: &mut u8, length_within: bool| {
        if length_within && *state == SMOOTH && topo.fan(p) <= MAX_CREASE_FAN {
            *state = TEST;
            test = true;
        }
    };
    let welded = topo.welded();
    let (means, leasts, states) = (&mut sums[..welded], &least[..welded], &mut state[..welded]);
    let (four_sums, rest) = means.as_chunks_mut::<4>();
    for (i, four) in four_sums.iter_mut().enumerate() {
        let p = i * 4;
        let m = glam::Mat4::from_cols_array_2d(four).transpose();
        let (x, y, z, total) = (m.x_axis, m.y_axis, m.z_axis, m.w_axis);
        let length = (x * x + y * y + z * z).sqrt();
        let within = length
            .cmple(bound4(total, Vec4::from_slice(&leasts[p..p + 4])))
            .bitmask();
        for (j, state) in states[p..p + 4].iter_mut().enumerate() {
            settle(p + j, state, within >> j & 1 == 1);
        }
        let [x, y, z] = direction4([x, y, z]);
        *four = glam::Mat4::from_cols(x, y, z, Vec4::ZERO)
            .transpose()
            .to_cols_array_2d();
    }
    let first = welded - rest.len();
    for (k, sum) in rest.iter_mut().enumerate() {
        let p = first + k;
        let total = sum[3];
        let sum3 = xyz(*sum);
        settle(p, &mut states[p], sum3.length() <= bound(total, leasts[p]));
        *sum = direction(sum3).extend(0.0).to_array();
    }
    drop(least);
    if test {
        for f in faces {
            let p = f.map(id);
            if p.iter().all(|&p| state[p] != TEST) {
                continue;
            }
            if let Some((n, ..)) = face_frame_of(corners(f)) {
                for p in p {
                    if state[p] == TEST && Vec3::from(n).dot(xyz(sums[p])) < cos_half {
                        state[p] = CREASED;
                    }
                }
            }
        }
    }
    let creased = |p: usize| state[p] == CREASED;
    let any_creased = state.contains(&CREASED);
    // (In lanes: both tests one comparison each.)
    let fix = |n: Vec3| {
        let a = Vec3A::from(n);
        if a.cmpeq(Vec3A::ZERO).all() || !a.is_finite() {
            Vec3::Z
        } else {
            n
        }
    };
    // The means the per-position pass reads (of creased positions with
    // too many faces to test), kept before the means give way to the
    // vertices' normals: few or none.
    let mut big: Vec<(u32, Vec3)> = (0..topo.welded())
        .filter(|&p| creased(p) && topo.fan(p) > MAX_CREASE_FAN)
        .map(|p| (p as u32, xyz(sums[p])))
        .collect();
    big.shrink_to_fit();
    let mean = |p: usize| big[big.partition_point(|&(q, _)| (q as usize) < p)].1;
    // Each vertex's normal: +z for one no face uses; not yet set (NaN)
    // for a creased position's. Narrowed to one `Vec3` a vertex as it
    // goes, then shrunk to fit: the standard library collects a vector's
    // own iterator, mapped to items no larger and of the same alignment,
    // into the same allocation (an optimisation it does not promise; were
    // it not made, the peak memory rows of docs/figures.md would show it).
    let mut normals: Vec<Vec3> = match (&topo.used, &topo.ids) {
        (Some(used), Some(ids)) => {
            // From the last down (see above: vertex `v` reads position
            // `ids[v] <= v`, not yet overwritten).
            for v in (0..positions.len()).rev() {
                let p = ids[v] as usize;
                let n = if used[v / 64] >> (v % 64) & 1 == 0 {
                    Vec3::Z
                } else if creased(p) {
                    Vec3::NAN
                } else {
                    fix(xyz(sums[p]))
                };
                sums[v] = n.extend(0.0).to_array();
            }
            sums.into_iter().map(xyz).collect()
        }
        // Each vertex its own position: one that no face uses has a sum
        // of zero, so a mean of zero, so +z (its position is never
        // creased).
        _ if !any_creased => sums.into_iter().map(|s| fix(xyz(s))).collect(),
        _ => sums
            .into_iter()
            .enumerate()
            .map(|(p, s)| if creased(p) { Vec3::NAN } else { fix(xyz(s)) })
            .collect(),
    };
    normals.shrink_to_fit();
    // The corners at creased positions, by position and in order at each
    // (the order the corners around a position are listed in): the
    // per-position pass's, without keeping every position's corners.
    let at = |c: u32| id(faces[(c / 3) as usize][(c % 3) as usize]);
    let mut creased_corners: Vec<u32> = Vec::new();
    if any_creased {
        // By a counting sort: each creased position's first slot, from the
        // sizes of the fans before it; then the corners in order, each to
        // its position's next slot.
        let mut next = vec![0u32; topo.welded()];
        let mut total = 0u32;
        for (p, slot) in next.iter_mut().enumerate() {
            *slot = total;
            if creased(p) {
                total += topo.fan(p) as u32;
            }
        }
        creased_corners = vec![0; total as usize];
        for (c, &v) in faces.iter().flatten().enumerate() {
            let p = id(v);
            if creased(p) {
                creased_corners[next[p] as usize] = c as u32;
                next[p] += 1;
            }
        }
    }
    let mut splits = Vec::new();
    // The faces around one creased position: unit normal and the angle there.
    let mut fan: Vec<(Vec3, f32)> = Vec::new();
    for around in creased_corners.chunk_by(|&a, &b| at(a) == at(b)) {
        let p = at(around[0]);
        fan.clear();
        fan.extend(around.iter().map(|&c| {
            let f = &faces[(c / 3) as usize];
            face_weights_of(corners(f))
                .map_or((Vec3::ZERO, 0.0), |(n, w)| (n.into(), w[(c % 3) as usize]))
        }));
        let one_fan = around.len() > MAX_CREASE_FAN;
        for (&c, &(nf, _)) in around.iter().zip(&fan) {
            let n = if one_fan && nf != Vec3::ZERO {
                mean(p)
            } else {
                direction(
                    fan.iter()
                        .filter(|(g, _)| g.dot(nf) >= cos_crease)
                        .fold(Vec3::ZERO, |s, &(g, w)| s + g * w),
                )
            };
            let n = fix(n);
            let (f, k) = (c / 3, (c % 3) as u8);
            let v = faces[f as usize][k as usize] as usize;
            if normals[v].is_nan() {
                normals[v] = n;
            } else if normals[v] != n {
                splits.push((f, k, n));
            }
        }
    }
    if any_creased {
        for n in &mut normals {
            if n.is_nan() {
                *n = Vec3::Z;
            }
        }
    }
    (normals, splits)
}

/// The x, y and z of a sum or mean kept as `[x, y, z, w]`.
#[inline(always)]
fn xyz([x, y, z, _]: [f32; 4]) -> Vec3 {
    Vec3::new(x, y, z)
}

/// [`face_weights`] of a face's three corners.
#[inline]
fn face_weights_of([a, b, c]: [Vec3; 3]) -> Option<(Vec3A, Vec3A)> {
    face_weights(a, b, c)
}

/// [`face_frame`] of a face's three corners.
#[inline]
fn face_frame_of([a, b, c]: [Vec3; 3]) -> Option<(Vec3A, f32, [Vec3A; 3])> {
    face_frame(a, b, c)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Geometry;
    use proptest::prelude::*;

    /// The normals as the module doc defines them, corner by corner, with
    /// nothing shared between corners: at a corner, the sum of the unit
    /// normals times the angles of the faces around its position (in the
    /// faces' order) whose normal is within the crease of its own face's,
    /// then its direction; +z where that is none.
    fn by_definition(positions: &[Vec3], faces: &[[u32; 3]], crease: f32) -> Vec<[Vec3; 3]> {
        let key = |v: u32| {
            positions[v as usize]
                .to_array()
                .map(|c| (c + 0.0).to_bits())
        };
        let weights: Vec<(Vec3, [f32; 3])> = faces
            .iter()
            .map(|f| {
                let [a, b, c] = f.map(|v| positions[v as usize]);
                face_weights(a, b, c)
                    .map_or((Vec3::ZERO, [0.0; 3]), |(n, w)| (n.into(), w.to_array()))
            })
            .collect();
        let cos = crease.to_radians().cos();
        faces
            .iter()
            .enumerate()
            .map(|(f, face)| {
                [0, 1, 2].map(|k| {
                    let at = key(face[k]);
                    let own = weights[f].0;
                    let mut sum = Vec3::ZERO;
                    for (g, other) in faces.iter().enumerate() {
                        for (&v, &w) in other.iter().zip(&weights[g].1) {
                            let n = weights[g].0;
                            if key(v) == at && n.dot(own) >= cos {
                                sum += n * w;
                            }
                        }
                    }
                    let n = crate::transform::direction(sum);
                    if n == Vec3::ZERO || !n.is_finite() {
                        Vec3::Z
                    } else {
                        n
                    }
                })
            })
            .collect()
    }

    /// A coordinate from a few values: positions repeat (welded), faces
    /// fold at many angles, some have no area.
    fn coordinate() -> impl Strategy<Value = f32> {
        prop::sample::select(vec![0.0, -0.0, 1.0, -1.0, 2.0, 0.5])
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(1500))]
        /// The loader's normals, found in passes over the faces with the
        /// positions' sums in lanes, are bit for bit the definition's at
        /// every corner (its vertex split off where the crease asks), on
        /// small meshes of repeated positions; each vertex no face uses
        /// gets +z.
        #[test]
        fn normals_are_the_definition_at_every_corner(
            xyz in prop::collection::vec([coordinate(), coordinate(), coordinate()], 3..16),
            corners in prop::collection::vec([0u32..16, 0u32..16, 0u32..16], 1..24),
            // Not an angle two faces of these coordinates can make
            // exactly (45°, 60°, 90°, 120°, 180° all occur): at exactly
            // the crease, f32's rounding of the cosines, not the rule,
            // decides.
            crease in prop::sample::select(vec![23.0f32, 37.0, 73.0, 101.0, 119.0, 163.0]),
        ) {
            let positions: Vec<Vec3> = xyz.iter().map(|&p| Vec3::from_array(p)).collect();
            let n = positions.len() as u32;
            let faces: Vec<[u32; 3]> = corners.iter().map(|f| f.map(|v| v % n)).collect();
            let mut g = Geometry::new_raw("random", positions.clone(), faces.clone());
            g.compute_normals(crease);
            let want = by_definition(&positions, &faces, crease);
            let bits = |v: Vec3| v.to_array().map(f32::to_bits);
            prop_assert_eq!(g.faces.len(), faces.len());
            for (f, face) in faces.iter().enumerate() {
                for k in 0..3 {
                    let v = g.faces[f][k] as usize;
                    prop_assert_eq!(bits(g.positions[v]), bits(positions[face[k] as usize]));
                    prop_assert_eq!(bits(g.normals[v]), bits(want[f][k]), "face {} corner {}", f, k);
                }
            }
            for v in 0..n {
                if !faces.iter().flatten().any(|&u| u == v) {
                    prop_assert_eq!(g.normals[v as usize], Vec3::Z, "vertex {}", v);
                }
            }
        }
    }
}
