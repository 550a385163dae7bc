//! Meshes and lights: indexed triangles, per-vertex normals, colours by
//! material, and the transform that places them in the world.
//!
//! **Layout.** A [`Mesh`] is a [`Geometry`] (shared: twenty thousand
//! `[[mesh]]` entries naming one shape or file hold one copy) plus what is
//! its own: a colour, a transform, a culling choice. Geometry is stored
//! flat, in the smallest form the renderer reads directly:
//!
//! | data | bytes | |
//! |---|---:|---|
//! | positions | 12 a vertex | f32 x, y, z |
//! | normals | 12 a vertex | f32, unit length |
//! | vertex colours | 3 a vertex | only when the file has them |
//! | faces | 12 a triangle | u32 vertex indices |
//! | materials | 8 a run | consecutive faces of one colour share a run |
//!
//! so a loaded mesh of `T` triangles on about `T/2` vertices takes about
//! 24 bytes a triangle.
//!
//! **Normals** missing from a file are computed per position, not per vertex
//! index: vertices at the same position (a seam where texture coordinates
//! or normals differ, a model exported with its faces unwelded) share their
//! surroundings, so no seam shows. Each face contributes its normal weighted
//! by its angle at the position (so the normal does not depend on how the
//! surface happens to be split into triangles), but only to corners of
//! faces within the crease angle of it ([`DEFAULT_CREASE`], 60°): the edges
//! of a cube stay sharp, a sphere's seam disappears. A vertex index shared
//! across a crease is split so that each side gets its own normal.
//!
//! **Closed** (every edge walked once each way) is found at load, in linear
//! time by hashing the edges of the welded positions: a model that is not
//! closed shows its inside through the gaps, so it is drawn from both sides
//! by default. **Convex** is decided only when the planner asks (a scene of
//! one closed mesh culled at the back, where it would let the depth test
//! go), and then exactly (see [`Geometry::is_convex`]).

use std::sync::{Arc, OnceLock};

use glam::{DVec3, Mat4, Vec3};
use rustc_hash::FxHashMap;

use crate::color::Rgb;
use crate::raster::Cull;

/// The crease angle: faces meeting at a sharper angle than this keep their
/// own normals at the edge between them.
pub const DEFAULT_CREASE: f32 = 60.0;

/// Faces of one colour, from `first` to the next run's first.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MaterialRun {
    pub first: u32,
    /// The material's colour; `None`: the mesh's own colour.
    pub color: Option<Rgb>,
}

/// A mesh's shape, in model coordinates: what is shared between meshes.
#[derive(Debug)]
pub struct Geometry {
    /// Where it came from: a file name or a shape, for messages.
    pub name: String,
    pub positions: Vec<Vec3>,
    /// One unit normal per position.
    pub normals: Vec<Vec3>,
    /// One colour per position, when the source has them; they override
    /// the face colours.
    pub colors: Option<Vec<Rgb>>,
    pub faces: Vec<[u32; 3]>,
    /// The faces' colours, as runs in face order; empty: every face in the
    /// mesh's colour.
    pub materials: Vec<MaterialRun>,
    /// The bounding box of the positions, `[min, max]` (`None` when a
    /// position is not finite, or there are none).
    pub bounds: Option<[Vec3; 2]>,
    /// Every edge (corners matched by position) shared by exactly two faces
    /// walking it in opposite directions: closed and consistently wound.
    pub closed: bool,
    convex: OnceLock<bool>,
}

impl Clone for Geometry {
    fn clone(&self) -> Geometry {
        Geometry {
            name: self.name.clone(),
            positions: self.positions.clone(),
            normals: self.normals.clone(),
            colors: self.colors.clone(),
            faces: self.faces.clone(),
            materials: self.materials.clone(),
            bounds: self.bounds,
            closed: self.closed,
            convex: self.convex.clone(),
        }
    }
}

impl PartialEq for Geometry {
    fn eq(&self, o: &Geometry) -> bool {
        self.positions == o.positions
            && self.normals == o.normals
            && self.colors == o.colors
            && self.faces == o.faces
            && self.materials == o.materials
    }
}

impl Geometry {
    /// Geometry from positions and faces, with normals computed (see the
    /// module doc) and the facts the planner reads.
    pub fn new(name: impl Into<String>, positions: Vec<Vec3>, faces: Vec<[u32; 3]>) -> Geometry {
        let mut g = Geometry {
            name: name.into(),
            positions,
            normals: Vec::new(),
            colors: None,
            faces,
            materials: Vec::new(),
            bounds: None,
            closed: false,
            convex: OnceLock::new(),
        };
        g.compute_normals(DEFAULT_CREASE);
        g.analyze();
        g
    }

    /// Geometry as given, normals not computed and facts not found: for
    /// loaders, which set the normals and then call [`Geometry::analyze`].
    pub fn new_raw(
        name: impl Into<String>,
        positions: Vec<Vec3>,
        faces: Vec<[u32; 3]>,
    ) -> Geometry {
        Geometry {
            name: name.into(),
            positions,
            normals: Vec::new(),
            colors: None,
            faces,
            materials: Vec::new(),
            bounds: None,
            closed: false,
            convex: OnceLock::new(),
        }
    }

    /// Recomputes the bounds and closedness (and forgets convexity); call
    /// it after changing the positions or faces.
    pub fn analyze(&mut self) {
        self.bounds = bounds(&self.positions);
        self.closed = self.bounds.is_some() && {
            let (ids, _) = weld(&self.positions);
            closed(&ids, &self.faces)
        };
        self.convex = OnceLock::new();
    }

    /// The faces in runs of one colour, in order, for a mesh coloured
    /// `color`: `(faces, colour)`.
    pub fn runs(&self, color: Rgb) -> impl Iterator<Item = (std::ops::Range<usize>, Rgb)> + '_ {
        let n = self.faces.len();
        let first = self
            .materials
            .first()
            .map_or(n, |r| r.first as usize)
            .min(n);
        let head = (first > 0).then_some((0..first, color));
        head.into_iter()
            .chain(self.materials.iter().enumerate().map(move |(k, r)| {
                let end = self
                    .materials
                    .get(k + 1)
                    .map_or(n, |s| s.first as usize)
                    .min(n);
                ((r.first as usize).min(end)..end, r.color.unwrap_or(color))
            }))
    }

    /// The colour of face `f` in a mesh coloured `color`.
    pub fn face_color(&self, f: usize, color: Rgb) -> Rgb {
        let run = self.materials.partition_point(|r| r.first as usize <= f);
        run.checked_sub(1)
            .and_then(|r| self.materials[r].color)
            .unwrap_or(color)
    }

    /// Closed and convex: its faces seen from one side never overlap on
    /// screen. Decided on first use, exactly: the surface is convex when it
    /// is locally convex everywhere: at every edge the far corner of one
    /// face lies on the inner side of the other face's plane (or on it), by
    /// Shewchuk's exact orientation predicate on the f32 positions, so a
    /// dent of any depth anywhere is found, however far the mesh is from
    /// the origin; at every vertex the faces turn once around it (their
    /// angles sum to at most 2π); and the surface is one piece with the
    /// topology of a sphere (V − E + F = 2). A closed surface that is
    /// locally convex at every point bounds a convex body (Tietze; van
    /// Heijenoort for immersed surfaces). A degenerate face or any doubt
    /// makes the answer no.
    pub fn is_convex(&self) -> bool {
        *self
            .convex
            .get_or_init(|| self.closed && self.bounds.is_some() && convex(self))
    }

    /// Computes the normals per position, splitting at creases sharper
    /// than `crease` degrees (see the module doc); vertex indices shared
    /// across a crease are split, which appends vertices.
    pub fn compute_normals(&mut self, crease: f32) {
        let (normals, splits) = smooth_normals(&self.positions, &self.faces, crease);
        self.normals = normals;
        // One new vertex for each vertex and normal it must also have.
        let mut copies: FxHashMap<(u32, [u32; 3]), u32> = FxHashMap::default();
        for (face, corner, normal) in splits {
            let v = self.faces[face as usize][corner as usize];
            let key = (v, normal.to_array().map(f32::to_bits));
            let next = self.positions.len() as u32;
            let copy = *copies.entry(key).or_insert(next);
            if copy == next {
                self.positions.push(self.positions[v as usize]);
                if let Some(c) = &mut self.colors {
                    c.push(c[v as usize]);
                }
                self.normals.push(normal);
            }
            self.faces[face as usize][corner as usize] = copy;
        }
    }

    /// The centre and radius of a sphere around all finite positions (the
    /// centre of the bounding box, and the farthest position from it), in
    /// f64: any f32 positions, from subnormal to f32's largest, neither
    /// overflow nor underflow here. `None` without a finite position.
    pub fn bounding_sphere(&self) -> Option<(DVec3, f64)> {
        let mut finite = self.positions.iter().filter(|p| p.is_finite());
        let first = finite.next()?.as_dvec3();
        let (lo, hi) = finite.fold((first, first), |(lo, hi), p| {
            (lo.min(p.as_dvec3()), hi.max(p.as_dvec3()))
        });
        let centre = lo * 0.5 + hi * 0.5;
        let radius = self
            .positions
            .iter()
            .filter(|p| p.is_finite())
            .map(|p| p.as_dvec3().distance(centre))
            .fold(0.0f64, f64::max);
        Some((centre, radius))
    }

    /// Centres the positions on the origin and scales them to fit the unit
    /// sphere, computed in f64 and rounded once, so a model of any size the
    /// file can hold is seen whole.
    pub fn fit_unit_sphere(&mut self) {
        let Some((centre, radius)) = self.bounding_sphere() else {
            return;
        };
        let scale = if radius > 0.0 { 1.0 / radius } else { 1.0 };
        for p in &mut self.positions {
            *p = ((p.as_dvec3() - centre) * scale).as_vec3();
        }
        // The same surface, moved and scaled: closedness stands; the bounds
        // and any convexity found are redone.
        self.bounds = bounds(&self.positions);
        self.convex = OnceLock::new();
    }
}

/// A triangle mesh placed in the world: shared geometry, and its own
/// colour, transform and culling.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    pub geometry: Arc<Geometry>,
    /// The colour of faces whose material gives none.
    pub color: Rgb,
    /// Model to world.
    pub model: Mat4,
    /// Which windings to discard.
    pub cull: Cull,
}

impl std::ops::Deref for Mesh {
    type Target = Geometry;
    fn deref(&self) -> &Geometry {
        &self.geometry
    }
}

impl Mesh {
    /// A mesh from positions and faces, with normals computed, every face
    /// in `color`, the identity transform and back faces culled.
    pub fn new(
        name: impl Into<String>,
        positions: Vec<Vec3>,
        faces: Vec<[u32; 3]>,
        color: Rgb,
    ) -> Mesh {
        Mesh::of(Arc::new(Geometry::new(name, positions, faces)), color)
    }

    /// A mesh of `geometry` in `color`, identity transform, back faces
    /// culled if the geometry is closed (an open one shows its inside).
    pub fn of(geometry: Arc<Geometry>, color: Rgb) -> Mesh {
        let cull = if geometry.closed {
            Cull::Back
        } else {
            Cull::None
        };
        Mesh {
            geometry,
            color,
            model: Mat4::IDENTITY,
            cull,
        }
    }

    /// The geometry, to change (copied first if another mesh shares it).
    pub fn geometry_mut(&mut self) -> &mut Geometry {
        Arc::make_mut(&mut self.geometry)
    }

    /// The colour of face `f`.
    pub fn face_color(&self, f: usize) -> Rgb {
        self.geometry.face_color(f, self.color)
    }
}

/// A directional light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light {
    /// The direction the light travels (unit length).
    pub direction: Vec3,
    pub color: Rgb,
    /// The share of the light that reaches every surface whatever its
    /// facing, in [0, 1].
    pub ambient: f32,
}

impl Default for Light {
    /// The light `rastty` uses for a model given on the command line: white,
    /// from the upper right, in front.
    fn default() -> Self {
        Light {
            direction: Vec3::new(-0.5, -1.0, -0.7).normalize(),
            color: Rgb::WHITE,
            ambient: 0.15,
        }
    }
}

/// The bounding box `[min, max]` of `positions`; `None` when one is not
/// finite, or there are none.
fn bounds(positions: &[Vec3]) -> Option<[Vec3; 2]> {
    let finite = !positions.is_empty() && positions.iter().all(|p| p.is_finite());
    finite.then(|| {
        let lo = positions.iter().fold(Vec3::INFINITY, |a, &p| a.min(p));
        let hi = positions.iter().fold(Vec3::NEG_INFINITY, |a, &p| a.max(p));
        [lo, hi]
    })
}

/// One id per distinct position (−0.0 and 0.0 are one), for each
/// position index, in linear time; and how many there are.
pub fn weld(positions: &[Vec3]) -> (Vec<u32>, usize) {
    let mut ids: FxHashMap<[u32; 3], u32> = FxHashMap::default();
    ids.reserve(positions.len());
    let id = positions
        .iter()
        .map(|p| {
            let n = ids.len() as u32;
            *ids.entry(p.to_array().map(|v| (v + 0.0).to_bits()))
                .or_insert(n)
        })
        .collect();
    (id, ids.len())
}

/// An undirected edge between two welded positions, and which way a face
/// walked it.
fn edge_key(a: u32, b: u32) -> (u64, bool) {
    (((a.min(b) as u64) << 32) | a.max(b) as u64, a > b)
}

/// Whether every edge is walked exactly once in each direction.
fn closed(ids: &[u32], faces: &[[u32; 3]]) -> bool {
    if faces.is_empty() {
        return false;
    }
    // For each undirected edge, how often it is walked low→high and
    // high→low: closed and consistently wound is exactly once each way.
    let mut edges: FxHashMap<u64, [u8; 2]> = FxHashMap::default();
    edges.reserve(faces.len() * 3 / 2);
    for f in faces {
        let v = f.map(|i| ids[i as usize]);
        if v[0] == v[1] || v[1] == v[2] || v[2] == v[0] {
            return false;
        }
        for k in 0..3 {
            let (key, back) = edge_key(v[k], v[(k + 1) % 3]);
            let e = edges.entry(key).or_insert([0, 0]);
            e[back as usize] = e[back as usize].saturating_add(1);
        }
    }
    edges.values().all(|&e| e == [1, 1])
}

/// The exact convexity test of [`Geometry::is_convex`], for a closed mesh.
fn convex(g: &Geometry) -> bool {
    let (ids, _) = weld(&g.positions);
    // Every directed edge, with its face and the corner opposite it.
    let mut edges: FxHashMap<u64, [(u32, u8); 2]> = FxHashMap::default();
    edges.reserve(g.faces.len() * 3 / 2);
    for (f, face) in g.faces.iter().enumerate() {
        let v = face.map(|i| ids[i as usize]);
        for k in 0..3 {
            let (key, back) = edge_key(v[k], v[(k + 1) % 3]);
            edges.entry(key).or_insert([(0, 0); 2])[back as usize] =
                (f as u32, ((k + 2) % 3) as u8);
        }
    }
    // One piece, a sphere's topology: V − E + F = 2 over the positions used.
    let mut used = vec![false; g.positions.len()];
    g.faces
        .iter()
        .flatten()
        .for_each(|&i| used[ids[i as usize] as usize] = true);
    let v = used.iter().filter(|&&u| u).count() as i64;
    if v - edges.len() as i64 + g.faces.len() as i64 != 2 {
        return false;
    }
    let point = |i: u32| {
        let p = g.positions[i as usize];
        robust::Coord3D {
            x: p.x as f64,
            y: p.y as f64,
            z: p.z as f64,
        }
    };
    // Locally convex at every edge: the far corner of the second face on
    // or below (inside) the first face's plane.
    for pair in edges.values() {
        let (f, g2) = (g.faces[pair[0].0 as usize], g.faces[pair[1].0 as usize]);
        let far = g2[pair[1].1 as usize];
        if robust::orient3d(point(f[0]), point(f[1]), point(f[2]), point(far)) < 0.0 {
            return false;
        }
    }
    // At every vertex the faces turn once around it: their angles there
    // sum to at most 2π (a flat vertex inside a face sums to 2π, up to
    // rounding; a cone wound twice, to nearly 4π).
    let mut angle = vec![0.0f64; g.positions.len()];
    for face in &g.faces {
        let p = face.map(|i| g.positions[i as usize].as_dvec3());
        for k in 0..3 {
            let (a, b) = (p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]);
            let turn = a.cross(b).length().atan2(a.dot(b));
            if turn.is_nan() || turn <= 0.0 {
                return false;
            }
            angle[ids[face[k] as usize] as usize] += turn;
        }
    }
    let full = std::f64::consts::TAU * (1.0 + 1e-9);
    angle.iter().all(|&a| a <= full)
}

/// Positions with more faces around them than this are smoothed without
/// creases (the crease test is quadratic in the faces around a position).
const MAX_CREASE_FAN: usize = 256;

/// Angle-weighted normals per position with creases (see the module doc):
/// one per vertex, and the corners `(face, corner, normal)` that need a
/// vertex of their own because their vertex index is shared across a
/// crease. A vertex on no face (or only degenerate ones) gets +z.
fn smooth_normals(
    positions: &[Vec3],
    faces: &[[u32; 3]],
    crease: f32,
) -> (Vec<Vec3>, Vec<(u32, u8, Vec3)>) {
    use crate::transform::{direction, face_normal};
    let (ids, n_ids) = weld(positions);
    // Each face's unit normal, and each corner's angle.
    let face_n: Vec<Vec3> = faces
        .iter()
        .map(|f| {
            let p = f.map(|i| positions[i as usize]);
            let n = face_normal(p[0], p[1], p[2]);
            if n.is_finite() { n } else { Vec3::ZERO }
        })
        .collect();
    let corner_angle = |f: usize, k: usize| {
        let p = faces[f].map(|i| positions[i as usize]);
        let a = direction(p[(k + 1) % 3] - p[k]);
        let b = direction(p[(k + 2) % 3] - p[k]);
        a.dot(b).clamp(-1.0, 1.0).acos()
    };
    // The corners around each welded position (CSR).
    let mut start = vec![0u32; n_ids + 1];
    for f in faces {
        for &i in f {
            start[ids[i as usize] as usize + 1] += 1;
        }
    }
    for k in 0..n_ids {
        start[k + 1] += start[k];
    }
    let mut fill = start.clone();
    let mut around = vec![(0u32, 0u8); faces.len() * 3];
    for (fi, f) in faces.iter().enumerate() {
        for (k, &i) in f.iter().enumerate() {
            let slot = &mut fill[ids[i as usize] as usize];
            around[*slot as usize] = (fi as u32, k as u8);
            *slot += 1;
        }
    }
    let cos_crease = crease.to_radians().cos();
    let mut normals: Vec<Option<Vec3>> = vec![None; positions.len()];
    let mut splits = Vec::new();
    for id in 0..n_ids {
        let corners = &around[start[id] as usize..start[id + 1] as usize];
        let weights: Vec<f32> = corners
            .iter()
            .map(|&(f, k)| corner_angle(f as usize, k as usize))
            .collect();
        let all_smooth = corners.len() > MAX_CREASE_FAN;
        for &(f, k) in corners {
            let nf = face_n[f as usize];
            let sum = corners
                .iter()
                .zip(&weights)
                .filter(|&(&(g, _), _)| all_smooth || face_n[g as usize].dot(nf) >= cos_crease)
                .fold(Vec3::ZERO, |s, (&(g, _), &w)| s + face_n[g as usize] * w);
            let n = direction(sum);
            let n = if n == Vec3::ZERO || !n.is_finite() {
                Vec3::Z
            } else {
                n
            };
            let v = faces[f as usize][k as usize] as usize;
            match normals[v] {
                None => normals[v] = Some(n),
                Some(m) if m == n => {}
                Some(_) => splits.push((f, k, n)),
            }
        }
    }
    (
        normals.into_iter().map(|n| n.unwrap_or(Vec3::Z)).collect(),
        splits,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::shapes::Shape;

    #[test]
    fn closed_convex_is_found_only_where_true() {
        let cube = Shape::Cube.mesh(Rgb::WHITE);
        assert!(cube.closed && cube.is_convex());
        assert!(Shape::Sphere.mesh(Rgb::WHITE).is_convex());
        let torus = Shape::Torus.mesh(Rgb::WHITE);
        assert!(torus.closed && !torus.is_convex(), "closed but not convex");
        // A cube with a face missing is not closed.
        let mut open = cube.clone();
        open.geometry_mut().faces.pop();
        open.geometry_mut().analyze();
        assert!(!open.closed && !open.is_convex());
        // A cube with one face wound the wrong way is not consistent.
        let mut flipped = cube.clone();
        let g = flipped.geometry_mut();
        g.faces[0].swap(1, 2);
        g.faces[1].swap(1, 2);
        g.analyze();
        assert!(!flipped.is_convex());
        // A dented cube is closed but not convex.
        let mut dented = cube.clone();
        let g = dented.geometry_mut();
        for p in &mut g.positions {
            if p.y > 0.5 && p.x > 0.5 && p.z > 0.5 {
                *p *= 0.5;
            }
        }
        g.analyze();
        assert!(dented.closed && !dented.is_convex());
        assert_eq!(cube.bounds, Some([Vec3::splat(-0.6), Vec3::splat(0.6)]));
    }

    #[test]
    fn normals_of_a_flat_square_point_up_and_fit_is_unit() {
        let p = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(2.0, 2.0, 0.0),
            Vec3::new(0.0, 2.0, 0.0),
        ];
        let mut m = Geometry::new("sq", p, vec![[0, 1, 2], [0, 2, 3]]);
        assert!(m.normals.iter().all(|n| (*n - Vec3::Z).length() < 1e-6));
        m.fit_unit_sphere();
        let far = m.positions.iter().map(|p| p.length()).fold(0.0, f32::max);
        assert!((far - 1.0).abs() < 1e-6);
        // Any size an f32 can hold fits the same.
        for size in [1e-30f32, 1e-23, 1e20, 1e30, f32::MAX] {
            let p = vec![
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(size, 0.0, 0.0),
                Vec3::new(size, size, 0.0),
            ];
            let mut m = Geometry::new("t", p, vec![[0, 1, 2]]);
            m.fit_unit_sphere();
            let far = m.positions.iter().map(|p| p.length()).fold(0.0, f32::max);
            assert!((far - 1.0).abs() < 1e-6, "{size}: {far}");
        }
    }

    #[test]
    fn normals_are_shared_at_a_seam_and_split_at_a_crease() {
        // Two faces of a shallow roof meeting at a ridge, each with its own
        // copies of the ridge's vertices: one smooth normal at the ridge.
        let roof = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.5, 0.1, 1.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(0.5, -0.1, -1.0),
        ];
        let g = Geometry::new("roof", roof, vec![[0, 1, 2], [3, 4, 5]]);
        assert_eq!(g.normals[0], g.normals[4], "the seam is smooth");
        assert_eq!(g.normals[1], g.normals[3]);
        assert_eq!(g.positions.len(), 6);
        // A cube on 8 shared corners: every corner split three ways, each
        // face flat.
        let c = |i: u32| Vec3::new((i & 1) as f32, (i >> 1 & 1) as f32, (i >> 2 & 1) as f32);
        let faces = vec![
            [0, 2, 3],
            [0, 3, 1],
            [4, 5, 7],
            [4, 7, 6],
            [0, 1, 5],
            [0, 5, 4],
            [2, 6, 7],
            [2, 7, 3],
            [0, 4, 6],
            [0, 6, 2],
            [1, 3, 7],
            [1, 7, 5],
        ];
        let g = Geometry::new("cube", (0..8).map(c).collect(), faces);
        assert_eq!(g.positions.len(), 24, "three normals at each corner");
        for f in &g.faces {
            let n = crate::transform::face_normal(
                g.positions[f[0] as usize],
                g.positions[f[1] as usize],
                g.positions[f[2] as usize],
            );
            assert!(
                f.iter()
                    .all(|&i| (g.normals[i as usize] - n).length() < 1e-6)
            );
        }
        assert!(g.closed && g.is_convex());
    }

    #[test]
    fn twenty_thousand_meshes_of_one_shape_share_one_geometry() {
        let a = Shape::Torus.mesh(Rgb::WHITE);
        let b = Shape::Torus.mesh(Rgb::BLACK);
        assert!(Arc::ptr_eq(&a.geometry, &b.geometry));
        assert_eq!(b.face_color(3), Rgb::BLACK);
    }
}
