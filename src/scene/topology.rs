//! Connectivity at load, built once in linear time and dropped after use:
//! positions welded by a compact hash set ([`PositionSet`]); around each
//! welded position, listed by a counting sort, the positions its edges lead
//! to (for whether the mesh is closed) or its corners (for whether it is
//! convex, when the planner asks). No edge table is ever hashed: an edge's
//! other side is found among the few entries around its end. When every
//! vertex is its own position (most files without texture coordinates) no
//! table of welded positions is kept: the passes that would read one are
//! compiled for both cases ([`Welded`]). The normals (`normals.rs`) read the
//! welded positions and each position's number of corners.
//!
//! Closedness reads a list of up to eight (every position of most meshes)
//! as eight SIMD lanes, whatever its length, with the lanes past its end
//! masked: eight entries of slack after the last list, 32 bytes, buy
//! compares without branches or copies (what loading costs is in
//! docs/figures.md, "Memory, loading and start-up").

use glam::Vec3;
use wide::u32x8;

use super::mesh::*;

/// A set of positions for welding, by open addressing over a table of
/// 8-byte slots, at most half full: each holds a handle and 32 bits of its
/// position's hash, so a probe compares positions (kept where the caller
/// keeps them, a random read) only when the hashes agree: 8 bytes a slot
/// against a general hash map's key, value and control bytes, more than
/// twice the memory for a large model. Positions are equal when their bits are, with −0.0
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
/// The set holds each distinct position's first index, whose id is then
/// found among those already given.
pub(super) fn weld(positions: &[Vec3]) -> (Vec<u32>, usize) {
    let mut set = PositionSet::with_capacity(positions.len());
    let mut ids: Vec<u32> = Vec::with_capacity(positions.len());
    let mut welded = 0u32;
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
            let i = (block * 16 + k) as u32;
            let (first, new) = set.get_or_insert_keyed(kh, i, |i| positions[i as usize]);
            ids.push(if new {
                welded += 1;
                welded - 1
            } else {
                ids[first as usize]
            });
        }
    }
    (ids, welded as usize)
}

/// The connectivity of a mesh, built once in linear time and dropped after
/// use: which welded position each vertex is at, and around each welded
/// position either its corners (for convexity, which walks across edges)
/// or the welded position each of its corners' edges leads to (for
/// closedness, which needs nothing else). No edge table is ever hashed: an
/// edge's other side is found among the few entries around its end.
pub(super) struct Topology {
    /// The welded position of each vertex; `None` when every vertex is its
    /// own (vertex `v` at position `v`), as in most files without texture
    /// coordinates: then no table is kept (4 bytes a vertex, at the peak
    /// of loading) or read.
    pub(super) ids: Option<Vec<u32>>,
    /// The entries around welded position `p` are
    /// `list[start[p]..start[p + 1]]`; eight more entries follow the last,
    /// so that any list can be read eight at a time.
    start: Vec<u32>,
    list: Vec<u32>,
    listing: Listing,
    /// Which vertices a face uses, a bit each (found in the pass that
    /// counts the corners; the normals give the others +z); `None` when
    /// every vertex is its own welded position (then a vertex is used when
    /// a face has a corner at its position).
    pub(super) used: Option<Vec<u64>>,
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

/// Where a vertex's welded position is found: in a table of them
/// (`&[u32]`), or the vertex's own number ([`Own`]): each pass that reads
/// them is compiled for each, so the common case reads no table.
pub(super) trait Welded: Copy {
    /// The welded position of vertex `v`.
    fn of(self, v: u32) -> u32;

    /// Those of the first `n` vertices only (a table cut to `n`, so that
    /// one bounds check on a vertex serves it and the positions).
    fn first(self, n: usize) -> Self;
}

/// Every vertex is its own welded position.
#[derive(Clone, Copy)]
pub(super) struct Own;

impl Welded for Own {
    #[inline(always)]
    fn of(self, v: u32) -> u32 {
        v
    }

    fn first(self, _: usize) -> Self {
        self
    }
}

impl Welded for &[u32] {
    #[inline(always)]
    fn of(self, v: u32) -> u32 {
        self[v as usize]
    }

    fn first(self, n: usize) -> Self {
        &self[..n]
    }
}

/// The counting sort of [`Topology::new`]: each welded position's first
/// entry (then, shifted, one past its last) and the entries, and which
/// vertices a face uses where `used` is given.
fn corners_by_position(
    ids: impl Welded,
    welded: usize,
    faces: &[[u32; 3]],
    listing: Listing,
    used: Option<&mut [u64]>,
) -> (Vec<u32>, Vec<u32>) {
    let mut start = vec![0u32; welded + 1];
    // Face by face, its three corners unrolled (a flattened iterator
    // costs twice the instructions here).
    match used {
        Some(used) => {
            for face in faces {
                for &i in face {
                    start[ids.of(i) as usize + 1] += 1;
                    used[i as usize / 64] |= 1 << (i % 64);
                }
            }
        }
        None => {
            for face in faces {
                for &i in face {
                    start[ids.of(i) as usize + 1] += 1;
                }
            }
        }
    }
    for p in 0..welded {
        start[p + 1] += start[p];
    }
    // Eight more entries: a list is read eight at a time (see
    // `Topology::closed`).
    let mut list = vec![0u32; faces.len() * 3 + 8];
    for (f, face) in faces.iter().enumerate() {
        let w = [ids.of(face[0]), ids.of(face[1]), ids.of(face[2])];
        for k in 0..3 {
            let slot = &mut start[w[k] as usize];
            list[*slot as usize] = match listing {
                Listing::Corners => (f * 3 + k) as u32,
                Listing::Next => w[if k == 2 { 0 } else { k + 1 }],
            };
            *slot += 1;
        }
    }
    (start, list)
}

impl Topology {
    /// At most this many faces: corners are numbered in a u32.
    const MAX_FACES: usize = (u32::MAX / 3) as usize;

    pub(super) fn new(positions: &[Vec3], faces: &[[u32; 3]], listing: Listing) -> Topology {
        assert!(faces.len() <= Self::MAX_FACES, "too many faces");
        let (ids, welded) = weld(positions);
        let ids = (welded < positions.len()).then_some(ids);
        let mut used = ids
            .is_some()
            .then(|| vec![0u64; positions.len().div_ceil(64)]);
        let (mut start, list) = match &ids {
            Some(ids) => {
                corners_by_position(ids.as_slice(), welded, faces, listing, used.as_deref_mut())
            }
            None => corners_by_position(Own, welded, faces, listing, None),
        };
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

    /// The welded position of vertex `v`.
    pub(super) fn id(&self, v: u32) -> u32 {
        self.ids.as_ref().map_or(v, |ids| ids[v as usize])
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
        self.id(faces[(c / 3) as usize][(c % 3) as usize])
    }

    /// Whether every edge is walked exactly once in each direction (closed
    /// and consistently wound), from a [`Listing::Next`] topology, whose
    /// long lists it sorts in place: no position leads to itself, and each
    /// edge to a higher position is walked once that way and at least once
    /// back (then every edge is walked once each way: see the code). A list
    /// of up to 8 (every position of most meshes) is read as eight SIMD
    /// lanes, each edge up counted in it and looked for in the list it
    /// leads to without branches; a longer one is sorted in place, its
    /// entries compared with their neighbours and the lists it leads to
    /// searched by halves.
    pub(super) fn closed(&mut self, faces: &[[u32; 3]]) -> bool {
        assert_eq!(self.listing, Listing::Next);
        if faces.is_empty() {
            return false;
        }
        for p in 0..self.welded() {
            let range = self.range(p);
            if range.len() > 8 {
                self.list[range].sort_unstable();
            }
        }
        let (start, list) = (&self.start, &self.list);
        (0..self.welded()).all(|p| {
            let range = start[p] as usize..start[p + 1] as usize;
            let p = p as u32;
            if range.len() <= 8 {
                // Its entries in lanes, and which lanes are its (those
                // past its end belong to the lists after it, or are the
                // eight entries of slack after the last list).
                let (v, mine) = (eight(list, range.start), (1u32 << range.len()) - 1);
                if v.simd_eq(u32x8::splat(p)).to_bitmask() & mine != 0 {
                    return false;
                }
                // Only edges up (to a higher position) are looked at: each
                // walked once, and back at least once. Then every edge is
                // walked once each way: each corner is an edge out of its
                // position and one into it, so at every position as many
                // edges leave as arrive. Counted pair by pair, what is left
                // once each edge up is matched with one back is edges down
                // alone, still as many leaving as arriving everywhere:
                // none, as the highest position such an edge leaves would
                // have none arriving.
                let mut up = v.simd_gt(u32x8::splat(p)).to_bitmask() & mine;
                let lanes = v.to_array();
                while up != 0 {
                    let i = up.trailing_zeros();
                    up &= up - 1;
                    let q = lanes[i as usize];
                    // Walked once up: no other of its lanes leads to `q`.
                    if v.simd_eq(u32x8::splat(q)).to_bitmask() & mine != 1 << i
                        || !leads_back(start, list, q, p)
                    {
                        return false;
                    }
                }
                true
            } else {
                let next = &list[range];
                next.windows(2).all(|w| w[0] != w[1])
                    && next.binary_search(&p).is_err()
                    && next
                        .iter()
                        .filter(|&&q| q > p)
                        .all(|&q| leads_back(start, list, q, p))
            }
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

/// The eight entries of `list` from `s` (past a list's end when it is
/// shorter: the list array has eight entries of slack).
#[inline(always)]
fn eight(list: &[u32], s: usize) -> u32x8 {
    u32x8::new(list[s..s + 8].try_into().expect("eight entries of slack"))
}

/// Whether an edge leads from `q` to `p` (see [`Topology::closed`]): in
/// a list of up to eight, all eight lanes compared at once and those past
/// the list's end masked off; in a longer one, sorted, by halves.
#[inline(always)]
fn leads_back(start: &[u32], list: &[u32], q: u32, p: u32) -> bool {
    let Some(&[s, e]) = start.get(q as usize..q as usize + 2) else {
        return false;
    };
    let (s, e) = (s as usize, e as usize);
    if e - s <= 8 {
        eight(list, s).simd_eq(u32x8::splat(p)).to_bitmask() & ((1 << (e - s)) - 1) != 0
    } else {
        list[s..e].binary_search(&p).is_ok()
    }
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
            if topo.id(face[k as usize]) > topo.at(&g.faces, base + (k + 1) % 3) {
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

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Closedness as the words say it, from every directed edge sorted:
    /// none from a position to itself, none twice, each with its reverse.
    fn closed_by_edges(topo: &Topology, faces: &[[u32; 3]]) -> bool {
        let mut edges: Vec<(u32, u32)> = faces
            .iter()
            .flat_map(|f| {
                let w = f.map(|v| topo.id(v));
                [(w[0], w[1]), (w[1], w[2]), (w[2], w[0])]
            })
            .collect();
        edges.sort_unstable();
        !faces.is_empty()
            && edges.iter().all(|&(p, q)| p != q)
            && edges.windows(2).all(|w| w[0] != w[1])
            && edges
                .iter()
                .all(|&(p, q)| edges.binary_search(&(q, p)).is_ok())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3000))]

        /// A double cone of `sides` sides (apexes with fans of up to 23
        /// faces, past the eight compared in lanes), some of its vertices
        /// doubled (welded back), its faces edited: `closed` agrees with
        /// the edges, and the untouched cone is closed.
        #[test]
        fn closedness_is_what_the_edges_say(
            sides in 3u32..24,
            copies in proptest::collection::vec(0u32..26, 0..6),
            edits in proptest::collection::vec((0u8..5, 0usize..100, 0u32..26), 0..4),
        ) {
            let n = sides;
            let mut positions: Vec<Vec3> = (0..n)
                .map(|i| Vec3::new(i as f32, (i * i) as f32, 1.0))
                .collect();
            positions.extend([Vec3::Y * -5.0, Vec3::Y * 500.0]);
            let mut faces: Vec<[u32; 3]> = (0..n)
                .flat_map(|i| [[i, n, (i + 1) % n], [(i + 1) % n, n + 1, i]])
                .collect();
            // Vertices doubled: a copy at the same position, which the
            // faces' first corners at the original then use.
            for c in copies {
                let v = c % (n + 2);
                positions.push(positions[v as usize]);
                let copy = positions.len() as u32 - 1;
                for f in faces.iter_mut() {
                    if f[0] == v {
                        f[0] = copy;
                    }
                }
            }
            let mut topo = Topology::new(&positions, &faces, Listing::Next);
            prop_assert!(topo.closed(&faces));
            let len = faces.len();
            for (kind, at, v) in edits {
                let i = at % faces.len().max(1);
                match kind {
                    0 if !faces.is_empty() => { faces.remove(i); }
                    1 if !faces.is_empty() => faces[i].swap(1, 2),
                    2 if !faces.is_empty() => { let f = faces[i]; faces.extend([f, [f[0], f[2], f[1]]]); }
                    3 if !faces.is_empty() => faces[i][0] = v % positions.len() as u32,
                    _ if !faces.is_empty() => faces[i].rotate_left(1),
                    _ => {}
                }
            }
            let mut topo = Topology::new(&positions, &faces, Listing::Next);
            prop_assert_eq!(topo.closed(&faces), closed_by_edges(&topo, &faces), "{} faces of {}", faces.len(), len);
        }
    }
}
