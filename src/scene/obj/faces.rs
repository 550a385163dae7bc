//! A face's corners made into triangles: each corner's vertex found (the
//! `v` itself, or a vertex of its own where one `v` is used with
//! different texture coordinates or normals), then triangles and quads
//! (nearly every face) cut on the stack, a quad along the diagonal
//! [`polygon::quad_at`] finds, and larger or crossed polygons by the
//! polygon triangulator, which may add vertices on edges ([`Reader::between`]).
//! The reader's two ways in are [`Reader::add_face`] (the corner list, from
//! either path) and [`Reader::add_plain_face`] (the fast path's bare
//! indices, with no corner list); both make the same triangles.

use glam::{Vec2, Vec3};

use super::{EXTRA, MADE, NONE, Reader, UNSET, attrs};
use crate::color::Lin;
use crate::scene::polygon::{self, Point};

impl Reader<'_> {
    /// The face whose corners are in `corners` (resolved, at least 3, `vt`
    /// kept only where textured): its vertices found or made, cut into
    /// triangles; not drawn if a corner is not finite.
    pub(super) fn add_face(&mut self) {
        // Triangles and quads (nearly every face) on the stack.
        match self.corners[..] {
            [a, b, c] => return self.add_small_face([a, b, c]),
            [a, b, c, d] => return self.add_small_face([a, b, c, d]),
            _ => {}
        }
        if self.any_bad && self.corners.iter().any(|&c| self.not_finite(c)) {
            self.dropped_faces += 1;
            return;
        }
        self.ids.clear();
        for k in 0..self.corners.len() {
            let [v, vt, vn] = self.corners[k];
            self.all_normals &= vn != NONE;
            let id = self.vertex(v, vt, vn);
            self.ids.push(id);
        }
        self.cut_face();
    }

    /// Whether corner `[v, vt, vn]`'s position or normal is not finite.
    #[inline(always)]
    fn not_finite(&self, [v, _, vn]: [u32; 3]) -> bool {
        !self.pos[v as usize].is_finite() || (vn != NONE && !self.vn[vn as usize].is_finite())
    }

    /// [`Reader::add_face`] for a triangle or a quad, its corners given
    /// (the corner list is filled only if the polygon triangulator must
    /// cut it).
    #[inline(always)]
    pub(super) fn add_small_face<const N: usize>(&mut self, corners: [[u32; 3]; N]) {
        if self.any_bad && corners.iter().any(|&c| self.not_finite(c)) {
            self.dropped_faces += 1;
            return;
        }
        let ids = self.corner_ids(corners);
        if let Ok(t) = <[u32; 3]>::try_from(&ids[..]) {
            self.triangles.push(t);
            return;
        }
        let mut v = [0; 4];
        let mut q = [0; 4];
        for k in 0..N.min(4) {
            v[k] = corners[k][0];
            q[k] = ids[k];
        }
        if !self.split_quad(q, v) {
            self.corners.clear();
            self.corners.extend_from_slice(&corners);
            self.ids.clear();
            self.ids.extend(q);
            self.cut_face();
        }
    }

    /// A quad of vertices `ids` at positions `v`, cut along the diagonal
    /// that [`polygon::quad`] finds; `false` (nothing added) for one it
    /// leaves to the polygon triangulator.
    #[inline(always)]
    pub(super) fn split_quad(&mut self, ids: [u32; 4], v: [u32; 4]) -> bool {
        let Some(d) = polygon::quad_at(&self.pos, v) else {
            return false;
        };
        // Written out: `map` and `extend` of an array here are calls that
        // are not inlined.
        let (a, b, c, e) = (ids[d], ids[d + 1], ids[d + 2], ids[(d + 3) % 4]);
        self.triangles.extend_from_slice(&[[a, b, c], [a, c, e]]);
        true
    }

    /// [`Reader::add_face`] for a triangle or quad whose corners name
    /// positions `v` alone (`f 1 2 3`, the fast path's commonest line):
    /// the same checks and triangles, without the corner list.
    #[inline(always)]
    pub(super) fn add_plain_face<const N: usize>(&mut self, v: [u32; N]) {
        if self.any_bad && v.iter().any(|&v| !self.pos[v as usize].is_finite()) {
            self.dropped_faces += 1;
            return;
        }
        // No corner names a normal.
        self.all_normals = false;
        if let Ok(t) = <[u32; 3]>::try_from(&v[..]) {
            self.triangles.push(t);
        } else if let Ok(q) = <[u32; 4]>::try_from(&v[..])
            && !self.split_quad(q, q)
        {
            self.corners.clear();
            self.corners.extend(q.map(|v| [v, NONE, NONE]));
            self.ids.clear();
            self.ids.extend(q);
            self.cut_face();
        }
    }

    /// [`Reader::vertex`] for each of a face's corners (`v`, `vt`, `vn`),
    /// noting whether every one names a normal; at once where none names
    /// either (then each vertex is its `v`). A loop, not `map`: `map` here
    /// is a call that is not inlined.
    #[inline(always)]
    pub(super) fn corner_ids<const N: usize>(&mut self, corners: [[u32; 3]; N]) -> [u32; N] {
        let mut ids = [0; N];
        // NONE is the largest u32, so the largest `vn` is NONE where one is,
        // and every `vt` and `vn` ANDed together is NONE where all are.
        let (mut most_vn, mut all) = (0, NONE);
        for k in 0..N {
            let [v, vt, vn] = corners[k];
            ids[k] = v;
            most_vn = most_vn.max(vn);
            all &= vt & vn;
        }
        self.all_normals &= most_vn != NONE;
        if all != NONE {
            for k in 0..N {
                let [v, vt, vn] = corners[k];
                ids[k] = self.vertex(v, vt, vn);
            }
        }
        ids
    }

    /// The face in `corners`, its vertices in `ids`, cut by the polygon
    /// triangulator.
    pub(super) fn cut_face(&mut self) {
        let corners = std::mem::take(&mut self.corners);
        let ids = std::mem::take(&mut self.ids);
        self.corner_pos.clear();
        self.corner_pos
            .extend(corners.iter().map(|&[v, ..]| self.pos[v as usize]));
        self.cut.clear();
        self.cutter.triangulate(&self.corner_pos, &mut self.cut);
        for tri in std::mem::take(&mut self.cut) {
            let t = tri.map(|p| match p {
                Point::Corner(i) => ids[i as usize],
                Point::Between { a, b, t } => self.between(&corners, a as usize, b as usize, t),
            });
            self.triangles.push(t);
        }
        self.corners = corners;
        self.ids = ids;
    }

    /// The output vertex of a corner: the `v` itself, unless the `v` was
    /// first used with another texture coordinate or normal.
    #[inline(always)]
    pub(super) fn vertex(&mut self, v: u32, vt: u32, vn: u32) -> u32 {
        if vt == NONE && vn == NONE {
            return v;
        }
        let attr = attrs(vt, vn);
        match self.attr_of.get_mut(v as usize) {
            Some(first) if *first == attr => v,
            Some(first) if *first == UNSET => {
                *first = attr;
                v
            }
            _ => self.other_vertex(v, attr),
        }
    }

    /// [`Reader::vertex`] when the list of first attributes is short or
    /// the `v` was first used with others.
    #[inline(never)]
    pub(super) fn other_vertex(&mut self, v: u32, attr: u64) -> u32 {
        if self.attr_of.len() <= v as usize {
            self.attr_of.resize(self.pos.len(), UNSET);
        }
        let first = &mut self.attr_of[v as usize];
        if *first == UNSET {
            *first = attr;
        }
        if *first == attr {
            return v;
        }
        let next = self.extra.len() as u32;
        let id = *self.extra_ids.entry((v, attr)).or_insert(next);
        if id == next {
            self.extra.push((v, attr));
        }
        EXTRA | id
    }

    /// A vertex made on the edge between corners `a` and `b`.
    pub(super) fn between(&mut self, corners: &[[u32; 3]], a: usize, b: usize, t: f32) -> u32 {
        let ([va, ta, na], [vb, tb, nb]) = (corners[a], corners[b]);
        let p = self.pos[va as usize].lerp(self.pos[vb as usize], t);
        let color = if self.colors.is_empty() {
            Lin::WHITE
        } else {
            let (ca, cb) = (
                self.colors[va as usize].to_f32(),
                self.colors[vb as usize].to_f32(),
            );
            Lin::from_f32(std::array::from_fn(|k| ca[k] + (cb[k] - ca[k]) * t))
        };
        let normal = if na != NONE && nb != NONE {
            self.vn[na as usize].lerp(self.vn[nb as usize], t)
        } else {
            Vec3::Z
        };
        let uv = if ta != NONE && tb != NONE {
            self.vt[ta as usize].lerp(self.vt[tb as usize], t)
        } else {
            Vec2::ZERO
        };
        self.made.push((p, color, normal, uv));
        MADE | (self.made.len() as u32 - 1)
    }
}
