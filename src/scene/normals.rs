//! Connectivity and normals at load: positions welded by a compact hash
//! set ([`PositionSet`]), around each welded position the positions its
//! edges lead to (for whether the mesh is closed) or its corners (for
//! whether it is convex, when the planner asks) listed by a counting sort;
//! the angle-weighted normals with the
//! crease rule. The layout and the reasons are in `mesh.rs`.
//!
//! **Normals** are summed in passes over the faces in order, each face's
//! normal and its three corner angles found once (one cross product, the
//! angles in three SIMD lanes), rather than once for each of its corners
//! from the positions' side: the sums come out in the same order, and the
//! frames of every shared model are the same bytes. Whether a position's
//! faces stay within half the crease of their mean is first bounded from
//! the sums alone (see [`smooth_normals`]); only the positions the bound
//! does not settle are tested face by face, and only creased ones (and those
//! on a face of no area) take the per-position pass. What it costs is in
//! docs/figures.md ("Loading").

use glam::{Vec3, Vec3A};

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
        let k = Self::key(p);
        self.get_or_insert_keyed((k, Self::hash(k)), new, at)
    }

    /// [`PositionSet::get_or_insert`] of the position whose key and hash
    /// are `(k, h)`.
    #[inline]
    fn get_or_insert_keyed(
        &mut self,
        (k, h): ([u32; 3], u32),
        new: u32,
        at: impl Fn(u32) -> Vec3,
    ) -> (u32, bool) {
        if (self.len + 1) * 2 > self.slots.len() {
            self.grow();
        }
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

    /// Reads the slots where the positions of keys and hashes `keyed`
    /// would go, so that their cache misses overlap rather than each
    /// waiting for the last.
    #[inline]
    fn touch(&self, keyed: &[([u32; 3], u32)]) {
        let mut sum = 0u64;
        for &(_, h) in keyed {
            sum = sum.wrapping_add(self.slots[self.home(h)]);
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
    let mut keyed = [([0u32; 3], 0u32); 16];
    for (block, chunk) in positions.chunks(16).enumerate() {
        // Touch the slots of the next sixteen first: their cache misses
        // overlap, rather than each waiting for the last. Their keys and
        // hashes are found once, for both.
        for (kh, &p) in keyed.iter_mut().zip(chunk) {
            let k = PositionSet::key(p);
            *kh = (k, PositionSet::hash(k));
        }
        let keyed = &keyed[..chunk.len()];
        set.touch(keyed);
        for (k, &kh) in keyed.iter().enumerate() {
            let next = first.len() as u32;
            let (id, new) =
                set.get_or_insert_keyed(kh, next, |id| positions[first[id as usize] as usize]);
            if new {
                first.push((block * 16 + k) as u32);
            }
            ids.push(id);
        }
    }
    (ids, first.len())
}

/// The connectivity of a mesh, built once in linear time and dropped after
/// use: which welded position each vertex is at, and around each welded
/// position either its corners (for convexity, which walks across edges)
/// or the welded position each of its corners' edges leads to (for
/// closedness, which needs nothing else). No edge table is ever hashed: an
/// edge's other side is found among the few entries around its end.
pub(super) struct Topology {
    /// The welded position of each vertex.
    pub(super) ids: Vec<u32>,
    /// The entries around welded position `p` are
    /// `list[start[p]..start[p + 1]]`.
    start: Vec<u32>,
    list: Vec<u32>,
    listing: Listing,
    /// Which vertices a face uses, a bit each (found in the pass that
    /// counts the corners; the normals give the others +z).
    pub(super) used: Vec<u64>,
}

/// What [`Topology`] lists around each welded position.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Listing {
    /// Each corner there, as `face * 3 + k`.
    Corners,
    /// For each corner there, the welded position at the next corner of
    /// its face: where its outgoing edge leads.
    Next,
}

impl Topology {
    /// At most this many faces: corners are numbered in a u32.
    const MAX_FACES: usize = (u32::MAX / 3) as usize;

    pub(super) fn new(positions: &[Vec3], faces: &[[u32; 3]], listing: Listing) -> Topology {
        assert!(faces.len() <= Self::MAX_FACES, "too many faces");
        let (ids, welded) = weld(positions);
        // Counting sort of the corners by welded position.
        let mut start = vec![0u32; welded + 1];
        let mut used = vec![0u64; positions.len().div_ceil(64)];
        // Face by face, its three corners unrolled (a flattened iterator
        // costs twice the instructions here).
        for face in faces {
            for &i in face {
                start[ids[i as usize] as usize + 1] += 1;
                used[i as usize / 64] |= 1 << (i % 64);
            }
        }
        for p in 0..welded {
            start[p + 1] += start[p];
        }
        let mut list = vec![0u32; faces.len() * 3];
        for (f, face) in faces.iter().enumerate() {
            let w = face.map(|i| ids[i as usize]);
            for k in 0..3 {
                let slot = &mut start[w[k] as usize];
                list[*slot as usize] = match listing {
                    Listing::Corners => (f * 3 + k) as u32,
                    Listing::Next => w[if k == 2 { 0 } else { k + 1 }],
                };
                *slot += 1;
            }
        }
        // Each slot now holds its successor's start: shift back.
        start.rotate_right(1);
        start[0] = 0;
        Topology {
            ids,
            start,
            list,
            listing,
            used,
        }
    }

    /// How many welded positions there are.
    pub(super) fn welded(&self) -> usize {
        self.start.len() - 1
    }

    /// How many corners there are around welded position `p` (also once
    /// the lists are forgotten).
    pub(super) fn fan(&self, p: usize) -> usize {
        (self.start[p + 1] - self.start[p]) as usize
    }

    /// Frees the lists around each position (12 bytes a triangle), once
    /// what reads them (closedness) is done: the normals need only the
    /// welded positions and each fan's size.
    pub(super) fn forget_corners(&mut self) {
        self.list = Vec::new();
    }

    /// The range of `list` around welded position `p`.
    fn range(&self, p: usize) -> std::ops::Range<usize> {
        self.start[p] as usize..self.start[p + 1] as usize
    }

    /// The corners around welded position `p` (of a [`Listing::Corners`]
    /// topology).
    pub(super) fn around(&self, p: usize) -> &[u32] {
        debug_assert_eq!(self.listing, Listing::Corners);
        &self.list[self.range(p)]
    }

    /// The welded position at corner `c` (`face * 3 + k`).
    pub(super) fn at(&self, faces: &[[u32; 3]], c: u32) -> u32 {
        self.ids[faces[(c / 3) as usize][(c % 3) as usize] as usize]
    }

    /// Whether every edge is walked exactly once in each direction (closed
    /// and consistently wound), from a [`Listing::Next`] topology, whose
    /// lists it sorts in place: no position leads to itself or twice to
    /// the same position, and each position one leads to leads back. (Then
    /// the edges form a set that is its own reverse, which is what the
    /// words say.) Only edges to a higher position need looking up the
    /// other way (see the code). A list of up to 16 (every position of most meshes) is
    /// sorted by insertion, a dozen steps for six or so; a position that
    /// leads back is found by a scan of a short list, a binary search of a
    /// long one.
    pub(super) fn closed(&mut self, faces: &[[u32; 3]]) -> bool {
        const SMALL: usize = 16;
        assert_eq!(self.listing, Listing::Next);
        if faces.is_empty() {
            return false;
        }
        for p in 0..self.welded() {
            let range = self.range(p);
            let next = &mut self.list[range];
            let p = p as u32;
            let ok = if next.len() <= SMALL {
                // Sorted as it is checked: a repeat lands just after its twin.
                let mut ok = true;
                for i in 0..next.len() {
                    let x = next[i];
                    let at = insert(next, i, x);
                    ok &= x != p && (at == 0 || next[at - 1] != x);
                }
                ok
            } else {
                next.sort_unstable();
                next.windows(2).all(|w| w[0] != w[1]) && next.binary_search(&p).is_err()
            };
            if !ok {
                return false;
            }
        }
        // Only edges up (to a higher position) are looked for the other way.
        // Each corner is an edge out of its position and one into it, so
        // at every position as many edges leave as arrive, and so do the
        // edges without their reverse: if there are any, they go round in
        // cycles, and a cycle goes up somewhere.
        (0..self.welded()).all(|p| {
            let p = p as u32;
            self.list[self.range(p as usize)]
                .iter()
                .filter(|&&q| q > p)
                .all(|&q| {
                    let back = &self.list[self.range(q as usize)];
                    if back.len() <= SMALL {
                        back.contains(&p)
                    } else {
                        back.binary_search(&p).is_ok()
                    }
                })
        })
    }

    /// For a closed mesh: whether its surface is one piece with a sphere's
    /// topology, V − E + F = 2, where E = 3F/2 (every edge has two sides).
    pub(super) fn sphere_like(&self, faces: &[[u32; 3]]) -> bool {
        let used = (0..self.welded()).filter(|&p| self.fan(p) > 0).count() as i64;
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

/// Puts `x` into `sorted[..len]` in order (one step of an insertion sort),
/// and says where.
#[inline]
fn insert(sorted: &mut [u32], len: usize, x: u32) -> usize {
    let mut i = len;
    while i > 0 && sorted[i - 1] > x {
        sorted[i] = sorted[i - 1];
        i -= 1;
    }
    sorted[i] = x;
    i
}

/// The exact convexity test of [`Geometry::is_convex`], for a closed mesh
/// with a sphere's topology.
pub(super) fn convex(g: &Geometry) -> bool {
    let topo = Topology::new(&g.positions, &g.faces, Listing::Corners);
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

/// The angles whose sines and cosines are `sin` ≥ 0 and `cos`, lane by
/// lane (each pair up to a common positive factor: only their ratio
/// counts), in radians, within 1e-6: the arctangent of the smaller over
/// the larger, by an odd minimax polynomial of degree 15 on [0, 1] (error
/// below 4e-8 before f32 rounding), then reflected into place. A weight,
/// where libm's `atan2` cost a seventh of loading a large model; a face's
/// three corners in one go.
pub(super) fn angles(sin: Vec3A, cos: Vec3A) -> Vec3A {
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
        .fold(Vec3A::ZERO, |p, &c| p * t2 + Vec3A::splat(c));
    let r = Vec3A::select(a.cmpgt(b), Vec3A::splat(FRAC_PI_2) - r, r);
    Vec3A::select(cos.cmplt(Vec3A::ZERO), Vec3A::splat(PI) - r, r)
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
    let cos = Vec3A::new(-ab.dot(ca), -bc.dot(ab), -ca.dot(bc));
    Some((n, angles(Vec3A::splat(twice_area), cos)))
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
pub(super) fn smooth_normals(
    topo: &Topology,
    positions: &[Vec3],
    faces: &[[u32; 3]],
    crease: f32,
) -> (Vec<Vec3>, Vec<(u32, u8, Vec3)>) {
    use crate::transform::direction;
    let cos_crease = crease.to_radians().cos();
    let cos_half = (crease / 2.0).to_radians().cos();
    let ids = &topo.ids;
    let corners = |f: &[u32; 3]| f.map(|v| positions[v as usize]);
    // The normals, one per vertex, are first each position's sum of
    // weighted face normals, then its mean (position `p` at index `p`,
    // which no vertex before it needs: ids are numbered in order of first
    // appearance, so `ids[v] <= v`), then, in place, each vertex's: no
    // buffer of sums beside them (at load, this is where memory peaks).
    let mut normals = vec![Vec3::ZERO; positions.len()];
    // Per position: the weights' sum, and the least weight.
    let mut total = vec![0.0f32; topo.welded()];
    let mut least = vec![f32::INFINITY; topo.welded()];
    // Per position: proven one smooth fan, to be tested, or creased.
    const SMOOTH: u8 = 0;
    const TEST: u8 = 1;
    const CREASED: u8 = 2;
    let mut state = vec![SMOOTH; topo.welded()];
    for f in faces {
        let p = f.map(|v| ids[v as usize] as usize);
        match face_weights_of(corners(f)) {
            Some((n, w)) => {
                for k in 0..3 {
                    normals[p[k]] += Vec3::from(n * w[k]);
                    total[p[k]] += w[k];
                    // `min`, as one comparison: the least is never NaN
                    // (it starts at infinity), and a NaN weight leaves it
                    // as `min` does.
                    let l = &mut least[p[k]];
                    *l = if w[k] < *l { w[k] } else { *l };
                }
            }
            // A face of no area: its corners take the per-position pass.
            None => p.iter().for_each(|&p| state[p] = CREASED),
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
    // The sums become the means, in place.
    for (p, (((sum, &total), &least), state)) in normals
        .iter_mut()
        .zip(&total)
        .zip(&least)
        .zip(&mut state)
        .enumerate()
    {
        let length = sum.length();
        if *state == SMOOTH
            && topo.fan(p) <= MAX_CREASE_FAN
            && length <= total - least * (1.0 - cos_half) + 1e-4 * total
        {
            *state = TEST;
            test = true;
        }
        *sum = direction(*sum);
    }
    drop((total, least));
    if test {
        for f in faces {
            let p = f.map(|v| ids[v as usize] as usize);
            if p.iter().all(|&p| state[p] != TEST) {
                continue;
            }
            if let Some((n, ..)) = face_frame_of(corners(f)) {
                for p in p {
                    if state[p] == TEST && Vec3::from(n).dot(normals[p]) < cos_half {
                        state[p] = CREASED;
                    }
                }
            }
        }
    }
    let creased = |p: usize| state[p] == CREASED;
    let fix = |n: Vec3| {
        if n == Vec3::ZERO || !n.is_finite() {
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
        .map(|p| (p as u32, normals[p]))
        .collect();
    big.shrink_to_fit();
    let mean = |p: usize| big[big.partition_point(|&(q, _)| (q as usize) < p)].1;
    // Which vertices a face uses: the others are +z.
    let used = &topo.used;
    // Each vertex's normal, from the last down (see above: vertex `v`
    // reads position `ids[v] <= v`, not yet overwritten). Not yet set (a
    // creased position's): NaN.
    for v in (0..positions.len()).rev() {
        let p = ids[v] as usize;
        normals[v] = if used[v / 64] >> (v % 64) & 1 == 0 {
            Vec3::Z
        } else if creased(p) {
            Vec3::NAN
        } else {
            fix(normals[p])
        };
    }
    // The corners at creased positions, by position and in order at each
    // (the order the corners around a position are listed in): the
    // per-position pass's, without keeping every position's corners.
    let at = |c: u32| ids[faces[(c / 3) as usize][(c % 3) as usize] as usize];
    let mut creased_corners: Vec<u32> = Vec::new();
    if state.contains(&CREASED) {
        for (c, &v) in faces.iter().flatten().enumerate() {
            if creased(ids[v as usize] as usize) {
                creased_corners.push(c as u32);
            }
        }
        creased_corners.sort_by_key(|&c| at(c));
    }
    let mut splits = Vec::new();
    // The faces around one creased position: unit normal and the angle there.
    let mut fan: Vec<(Vec3, f32)> = Vec::new();
    for around in creased_corners.chunk_by(|&a, &b| at(a) == at(b)) {
        let p = at(around[0]) as usize;
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
    for n in &mut normals {
        if n.is_nan() {
            *n = Vec3::Z;
        }
    }
    (normals, splits)
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
