//! Connectivity and normals at load: positions welded by a compact hash
//! set ([`PositionSet`]), the corners around each welded position listed by
//! a counting sort, and from them the angle-weighted normals with the
//! crease rule, whether the mesh is closed, and (when the planner asks)
//! whether it is convex. The layout and the reasons are in `mesh.rs`.

use glam::Vec3;

use super::mesh::*;

/// A set of positions for welding, by open addressing over a table of
/// 8-byte slots, at most half full: each holds a handle and 32 bits of its
/// position's hash, so a probe compares positions (kept where the caller
/// keeps them, a random read) only when the hashes agree: 8 bytes a slot
/// against a general hash map's key, value and control bytes, which for
/// 2M positions was more than twice the memory. Positions are equal when their bits are, with −0.0
/// and 0.0 one.
pub(super) struct PositionSet {
    /// `hash << 32 | handle + 1`, or 0 for empty.
    slots: Vec<u64>,
    len: usize,
}

impl PositionSet {
    /// A set with room for `n` positions before it grows.
    pub(super) fn with_capacity(n: usize) -> PositionSet {
        PositionSet {
            slots: vec![0; (n * 2).next_power_of_two().max(16)],
            len: 0,
        }
    }

    pub(super) fn key(p: Vec3) -> [u32; 3] {
        p.to_array().map(|v| (v + 0.0).to_bits())
    }

    /// The key's 32-bit hash: its top bits pick the slot to start from,
    /// and all of it is kept in the slot.
    #[inline]
    pub(super) fn hash(k: [u32; 3]) -> u32 {
        let h = (k[0] as u64 ^ (k[1] as u64) << 32)
            .wrapping_mul(0x9e37_79b9_7f4a_7c15)
            .rotate_left(29)
            ^ (k[2] as u64).wrapping_mul(0xc2b2_ae3d_27d4_eb4f);
        (h.wrapping_mul(0x1656_67b1_9e37_79f9) >> 32) as u32
    }

    #[inline]
    pub(super) fn home(&self, h: u32) -> usize {
        // At most 2^32 slots: handles are u32.
        (h as u64 >> (32 - self.slots.len().trailing_zeros())) as usize
    }

    /// The handle of position `p`, where `at(handle)` is the position a
    /// handle stands for: an existing one (`false`), or `new` inserted
    /// (`true`).
    #[inline]
    pub(super) fn get_or_insert(
        &mut self,
        p: Vec3,
        new: u32,
        at: impl Fn(u32) -> Vec3,
    ) -> (u32, bool) {
        if (self.len + 1) * 2 > self.slots.len() {
            self.grow();
        }
        let k = Self::key(p);
        let h = Self::hash(k);
        let mask = self.slots.len() - 1;
        let mut i = self.home(h);
        loop {
            let s = self.slots[i];
            if s == 0 {
                self.slots[i] = (h as u64) << 32 | (new as u64 + 1);
                self.len += 1;
                return (new, true);
            }
            let handle = (s as u32).wrapping_sub(1);
            if (s >> 32) as u32 == h && Self::key(at(handle)) == k {
                return (handle, false);
            }
            i = (i + 1) & mask;
        }
    }

    /// Reads the slots where `positions` would go, so that their cache
    /// misses overlap rather than each waiting for the last.
    #[inline]
    pub(super) fn touch(&self, positions: &[Vec3]) {
        let mut sum = 0u64;
        for &p in positions {
            sum = sum.wrapping_add(self.slots[self.home(Self::hash(Self::key(p)))]);
        }
        std::hint::black_box(sum);
    }

    /// Doubles the table, placing each slot by the hash it keeps: no
    /// position is read again.
    pub(super) fn grow(&mut self) {
        let size = (self.slots.len() * 2).max(16);
        let old = std::mem::replace(&mut self.slots, vec![0; size]);
        let mask = size - 1;
        for s in old.into_iter().filter(|&s| s != 0) {
            let mut i = self.home((s >> 32) as u32);
            while self.slots[i] != 0 {
                i = (i + 1) & mask;
            }
            self.slots[i] = s;
        }
    }
}

/// One id per distinct position (see [`PositionSet`]), numbered in order
/// of first appearance, for each position index; and how many there are.
pub(super) fn weld(positions: &[Vec3]) -> (Vec<u32>, usize) {
    let mut set = PositionSet::with_capacity(positions.len());
    // Each id's first position index, to compare against.
    let mut first: Vec<u32> = Vec::new();
    let mut ids = Vec::with_capacity(positions.len());
    for (block, chunk) in positions.chunks(16).enumerate() {
        // Touch the slots of the next sixteen first: their cache misses
        // overlap, rather than each waiting for the last.
        set.touch(chunk);
        for (k, &p) in chunk.iter().enumerate() {
            let next = first.len() as u32;
            let (id, new) = set.get_or_insert(p, next, |id| positions[first[id as usize] as usize]);
            if new {
                first.push((block * 16 + k) as u32);
            }
            ids.push(id);
        }
    }
    (ids, first.len())
}

/// The connectivity of a mesh, built once in linear time and dropped after
/// use: which welded position each vertex is at, and the corners around
/// each welded position. Closedness, convexity and normals all read it, so
/// no edge table is ever hashed: an edge's other side is found among the
/// few corners around its end.
pub(super) struct Topology {
    /// The welded position of each vertex.
    ids: Vec<u32>,
    /// The corners around welded position `p` are
    /// `corners[start[p]..start[p + 1]]`, each as `face * 3 + k`.
    start: Vec<u32>,
    corners: Vec<u32>,
}

impl Topology {
    /// At most this many faces: corners are numbered in a u32.
    const MAX_FACES: usize = (u32::MAX / 3) as usize;

    pub(super) fn new(positions: &[Vec3], faces: &[[u32; 3]]) -> Topology {
        assert!(faces.len() <= Self::MAX_FACES, "too many faces");
        let (ids, welded) = weld(positions);
        // Counting sort of the corners by welded position.
        let mut start = vec![0u32; welded + 1];
        for &i in faces.iter().flatten() {
            start[ids[i as usize] as usize + 1] += 1;
        }
        for p in 0..welded {
            start[p + 1] += start[p];
        }
        let mut corners = vec![0u32; faces.len() * 3];
        for (c, &i) in faces.iter().flatten().enumerate() {
            let slot = &mut start[ids[i as usize] as usize];
            corners[*slot as usize] = c as u32;
            *slot += 1;
        }
        // Each slot now holds its successor's start: shift back.
        start.rotate_right(1);
        start[0] = 0;
        Topology {
            ids,
            start,
            corners,
        }
    }

    /// How many welded positions there are.
    pub(super) fn welded(&self) -> usize {
        self.start.len() - 1
    }

    /// The corners around welded position `p`.
    pub(super) fn around(&self, p: usize) -> &[u32] {
        &self.corners[self.start[p] as usize..self.start[p + 1] as usize]
    }

    /// The welded position at corner `c` (`face * 3 + k`).
    pub(super) fn at(&self, faces: &[[u32; 3]], c: u32) -> u32 {
        self.ids[faces[(c / 3) as usize][(c % 3) as usize] as usize]
    }

    /// Whether every edge is walked exactly once in each direction (closed
    /// and consistently wound): at every position, the positions its
    /// corners lead to and come from are the same set, without repeats.
    pub(super) fn closed(&self, faces: &[[u32; 3]]) -> bool {
        if faces.is_empty() {
            return false;
        }
        let (mut out, mut into) = (Vec::new(), Vec::new());
        (0..self.welded()).all(|p| {
            out.clear();
            into.clear();
            for &c in self.around(p) {
                let base = c - c % 3;
                out.push(self.at(faces, base + (c + 1) % 3));
                into.push(self.at(faces, base + (c + 2) % 3));
            }
            out.sort_unstable();
            into.sort_unstable();
            out == into && out.windows(2).all(|w| w[0] != w[1]) && !out.contains(&(p as u32))
        })
    }

    /// For a closed mesh: whether its surface is one piece with a sphere's
    /// topology, V − E + F = 2, where E = 3F/2 (every edge has two sides).
    pub(super) fn sphere_like(&self, faces: &[[u32; 3]]) -> bool {
        let used = (0..self.welded())
            .filter(|&p| !self.around(p).is_empty())
            .count() as i64;
        used * 2 - faces.len() as i64 == 4
    }

    /// The corner of the face across the edge from corner `c` to the next
    /// corner of its face: the far corner of the face that walks the edge
    /// the other way. `None` if there is none.
    pub(super) fn across(&self, faces: &[[u32; 3]], c: u32) -> Option<u32> {
        let base = c - c % 3;
        let (a, b) = (self.at(faces, c), self.at(faces, base + (c + 1) % 3));
        self.around(b as usize).iter().find_map(|&d| {
            let base = d - d % 3;
            (self.at(faces, base + (d + 1) % 3) == a).then_some(base + (d + 2) % 3)
        })
    }
}

/// The exact convexity test of [`Geometry::is_convex`], for a closed mesh
/// with a sphere's topology.
pub(super) fn convex(g: &Geometry) -> bool {
    let topo = Topology::new(&g.positions, &g.faces);
    let point = |c: u32| {
        let p = g.positions[g.faces[(c / 3) as usize][(c % 3) as usize] as usize];
        robust::Coord3D {
            x: p.x as f64,
            y: p.y as f64,
            z: p.z as f64,
        }
    };
    // Locally convex at every edge (seen from its lower-numbered end): the
    // far corner of the face across it on or below (inside) this face's
    // plane.
    for (f, face) in g.faces.iter().enumerate() {
        let base = f as u32 * 3;
        for k in 0..3 {
            let c = base + k;
            if topo.ids[face[k as usize] as usize] > topo.at(&g.faces, base + (k + 1) % 3) {
                continue;
            }
            let Some(far) = topo.across(&g.faces, c) else {
                return false;
            };
            if robust::orient3d(point(base), point(base + 1), point(base + 2), point(far)) < 0.0 {
                return false;
            }
        }
    }
    // At every vertex the faces turn once around it: their angles there
    // sum to at most 2π (a flat vertex inside a face sums to 2π, up to
    // rounding; a cone wound twice, to nearly 4π).
    let full = std::f64::consts::TAU * (1.0 + 1e-9);
    (0..topo.welded()).all(|p| {
        let mut sum = 0.0f64;
        for &c in topo.around(p) {
            let face = g.faces[(c / 3) as usize].map(|i| g.positions[i as usize].as_dvec3());
            let k = (c % 3) as usize;
            let (a, b) = (face[(k + 1) % 3] - face[k], face[(k + 2) % 3] - face[k]);
            let turn = a.cross(b).length().atan2(a.dot(b));
            if turn.is_nan() || turn <= 0.0 {
                return false;
            }
            sum += turn;
        }
        sum <= full
    })
}

/// Positions with more faces around them than this are smoothed without
/// creases (the crease test is quadratic in the faces around a position).
pub(super) const MAX_CREASE_FAN: usize = 256;

/// The angle whose sine and cosine are `sin` ≥ 0 and `cos` (of unit
/// vectors), in radians, within 1e-6: the arctangent of the smaller over
/// the larger, by an odd minimax polynomial of degree 15 on [0, 1] (error
/// below 4e-8 before f32 rounding), then reflected into place. A weight,
/// where libm's `atan2` cost a seventh of loading a large model.
pub(super) fn angle(sin: f32, cos: f32) -> f32 {
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
    let r = t * C.iter().rev().fold(0.0, |p, &c| p * t2 + c);
    let r = if a > b { FRAC_PI_2 - r } else { r };
    if cos < 0.0 { PI - r } else { r }
}

/// Angle-weighted normals per position with creases (see the module doc):
/// one per vertex, and the corners `(face, corner, normal)` that need a
/// vertex of their own because their vertex index is shared across a
/// crease. A vertex on no face (or only degenerate ones) gets +z.
pub(super) fn smooth_normals(
    topo: &Topology,
    positions: &[Vec3],
    faces: &[[u32; 3]],
    crease: f32,
) -> (Vec<Vec3>, Vec<(u32, u8, Vec3)>) {
    use crate::transform::direction;
    let cos_crease = crease.to_radians().cos();
    let cos_half = (crease / 2.0).to_radians().cos();
    // Not yet set: NaN.
    let mut normals = vec![Vec3::NAN; positions.len()];
    let mut splits = Vec::new();
    // The faces around one position: unit normal and the angle there.
    let mut fan: Vec<(Vec3, f32)> = Vec::new();
    for p in 0..topo.welded() {
        let corners = topo.around(p);
        fan.clear();
        fan.extend(corners.iter().map(|&c| {
            // The face's normal and its angle here, from the two edges
            // leaving the corner in unit length (so any scale works).
            let f = faces[(c / 3) as usize];
            let k = (c % 3) as usize;
            let at = positions[f[k] as usize];
            let a = direction(positions[f[(k + 1) % 3] as usize] - at);
            let b = direction(positions[f[(k + 2) % 3] as usize] - at);
            let cross = a.cross(b);
            let sin = cross.length();
            let n = cross / sin;
            if sin > 0.0 && n.is_finite() {
                (n, angle(sin, a.dot(b)))
            } else {
                (Vec3::ZERO, 0.0)
            }
        }));
        let smooth = direction(fan.iter().fold(Vec3::ZERO, |s, &(n, w)| s + n * w));
        // One smooth fan when every face is within half the crease angle
        // of the mean (so any two are within the crease of each other):
        // the common case, decided in one pass rather than one per corner.
        let one_fan = corners.len() > MAX_CREASE_FAN
            || fan
                .iter()
                .all(|&(g, _)| g == Vec3::ZERO || g.dot(smooth) >= cos_half);
        for (&c, &(nf, _)) in corners.iter().zip(&fan) {
            let n = if one_fan && nf != Vec3::ZERO {
                smooth
            } else {
                direction(
                    fan.iter()
                        .filter(|(g, _)| g.dot(nf) >= cos_crease)
                        .fold(Vec3::ZERO, |s, &(g, w)| s + g * w),
                )
            };
            let n = if n == Vec3::ZERO || !n.is_finite() {
                Vec3::Z
            } else {
                n
            };
            let (f, k) = (c / 3, (c % 3) as u8);
            let v = faces[f as usize][k as usize] as usize;
            if normals[v].is_nan() {
                normals[v] = n;
            } else if normals[v] != n {
                splits.push((f, k, n));
            }
        }
    }
    for n in &mut normals {
        if n.is_nan() {
            *n = Vec3::Z;
        }
    }
    (normals, splits)
}
