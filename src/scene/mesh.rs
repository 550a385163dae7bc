//! Meshes and lights: indexed triangles with per-face colours, per-vertex
//! normals, and the transform that places them in the world.
//!
//! Normals missing from a file are computed: each vertex gets the sum of
//! the normals of the faces around it, each weighted by the face's angle at
//! that vertex (so that a vertex's normal does not depend on how the
//! surface around it happens to be split into triangles). Polygons of more
//! than three vertices are cut into triangles by ear clipping, which is
//! right for non-convex polygons where a fan is not.

use glam::{DVec3, Mat4, Vec2, Vec3};

use crate::color::Rgb;
use crate::raster::Cull;

/// A triangle mesh in model coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    /// Where it came from: a file name or a shape, for messages.
    pub name: String,
    pub positions: Vec<Vec3>,
    /// One unit normal per position.
    pub normals: Vec<Vec3>,
    /// One colour per position, when the source has them; they override
    /// the face colours.
    pub colors: Option<Vec<Rgb>>,
    pub faces: Vec<[u32; 3]>,
    /// One colour per face (a material's diffuse colour, or the mesh's).
    pub face_colors: Vec<Rgb>,
    /// Model to world.
    pub model: Mat4,
    /// Which windings to discard.
    pub cull: Cull,
    /// What [`Mesh::analyze`] found: computed once, read by the planner
    /// every frame.
    pub shape: MeshShape,
}

/// Facts about a mesh's geometry that do not change from frame to frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MeshShape {
    /// The bounding box of the finite positions, `[min, max]` (`None`
    /// when a position is not finite, or there are none).
    pub bounds: Option<[Vec3; 2]>,
    /// Closed: every edge (corners matched by position) shared by exactly
    /// two faces walking it in opposite directions, so consistently wound.
    pub closed: bool,
    /// Closed and convex: its faces seen from one side then never overlap
    /// on screen, which lets the planner skip the depth buffer. Decided
    /// exactly (see [`Mesh::analyze`]); `false` when unsure.
    pub closed_convex: bool,
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

impl Mesh {
    /// A mesh from positions and faces, with normals computed, every face
    /// in `color`, the identity transform and back faces culled.
    pub fn new(
        name: impl Into<String>,
        positions: Vec<Vec3>,
        faces: Vec<[u32; 3]>,
        color: Rgb,
    ) -> Mesh {
        let normals = vertex_normals(&positions, &faces);
        let face_colors = vec![color; faces.len()];
        let mut mesh = Mesh {
            name: name.into(),
            positions,
            normals,
            colors: None,
            faces,
            face_colors,
            model: Mat4::IDENTITY,
            cull: Cull::Back,
            shape: MeshShape::default(),
        };
        mesh.analyze();
        mesh
    }

    /// Recomputes [`Mesh::shape`]; call it after changing the positions or
    /// faces.
    ///
    /// Closed and convex are decided exactly and in `O(n log n)`: corners
    /// are matched by position (a sort), every edge must be walked once in
    /// each direction (a sort of the edge keys), and then the surface is
    /// convex when it is locally convex everywhere: at every edge the far
    /// vertex of one face lies on the inner side of the other face's plane
    /// (or on it), by Shewchuk's exact orientation predicate on the f32
    /// positions, so a dent of any depth anywhere is found, however far the
    /// mesh is from the origin; at every vertex the faces turn once around
    /// it (their angles sum to at most 2π); and the surface is one piece
    /// with the topology of a sphere (V − E + F = 2). A closed surface that
    /// is locally convex at every point bounds a convex body (Tietze; van
    /// Heijenoort for immersed surfaces). A degenerate face or any doubt
    /// makes the answer no.
    pub fn analyze(&mut self) {
        let finite = !self.positions.is_empty() && self.positions.iter().all(|p| p.is_finite());
        let bounds = finite.then(|| {
            let lo = self.positions.iter().fold(Vec3::INFINITY, |a, &p| a.min(p));
            let hi = self
                .positions
                .iter()
                .fold(Vec3::NEG_INFINITY, |a, &p| a.max(p));
            [lo, hi]
        });
        let (closed, convex) = if finite {
            topology(&self.positions, &self.faces)
        } else {
            (false, false)
        };
        self.shape = MeshShape {
            bounds,
            closed,
            closed_convex: convex,
        };
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

    /// Centres the mesh on the origin and scales it to fit the unit sphere,
    /// by moving its positions (computed in f64, then rounded once), so a
    /// model of any size the file can hold is seen whole, and the model
    /// transform stays the identity (no subnormal scale factors).
    pub fn fit_unit_sphere(&mut self) {
        let Some((centre, radius)) = self.bounding_sphere() else {
            return;
        };
        let scale = if radius > 0.0 { 1.0 / radius } else { 1.0 };
        for p in &mut self.positions {
            *p = ((p.as_dvec3() - centre) * scale).as_vec3();
        }
        self.model = Mat4::IDENTITY;
        self.analyze();
    }
}

/// One id per distinct position (−0.0 and 0.0 are one), for each
/// position index; and how many there are.
pub fn weld(positions: &[Vec3]) -> (Vec<u32>, usize) {
    let key = |i: u32| {
        positions[i as usize]
            .to_array()
            .map(|v| (v + 0.0).to_bits())
    };
    let mut order: Vec<u32> = (0..positions.len() as u32).collect();
    order.sort_unstable_by_key(|&i| key(i));
    let mut id = vec![0u32; positions.len()];
    let mut n = 0u32;
    for (k, &i) in order.iter().enumerate() {
        if k > 0 && key(order[k - 1]) != key(i) {
            n += 1;
        }
        id[i as usize] = n;
    }
    (
        id,
        if positions.is_empty() {
            0
        } else {
            n as usize + 1
        },
    )
}

/// Whether the mesh is closed, and whether it is closed and convex (see
/// [`Mesh::analyze`]).
fn topology(positions: &[Vec3], faces: &[[u32; 3]]) -> (bool, bool) {
    if faces.is_empty() {
        return (false, false);
    }
    let (id, _) = weld(positions);
    // Every directed edge: (low id, high id, walked high→low?), face, and
    // the corner opposite it.
    let mut edges: Vec<(u64, u32, u8)> = Vec::with_capacity(faces.len() * 3);
    for (f, face) in faces.iter().enumerate() {
        let v = face.map(|i| id[i as usize]);
        if v[0] == v[1] || v[1] == v[2] || v[2] == v[0] {
            return (false, false);
        }
        for k in 0..3 {
            let (a, b) = (v[k] as u64, v[(k + 1) % 3] as u64);
            let key = (a.min(b) << 33) | (a.max(b) << 1) | (a > b) as u64;
            edges.push((key, f as u32, ((k + 2) % 3) as u8));
        }
    }
    edges.sort_unstable_by_key(|e| e.0);
    // Closed and consistently wound: each undirected edge exactly twice,
    // once each way.
    let pairs = edges.chunks(2);
    let closed = edges.len().is_multiple_of(2)
        && pairs
            .clone()
            .all(|p| p[0].0 | 1 == p[1].0 && p[0].0 & 1 == 0)
        && edges
            .windows(3)
            .step_by(2)
            .all(|w| w[0].0 >> 1 != w[2].0 >> 1);
    if !closed {
        return (false, false);
    }
    // One piece, a sphere's topology: V − E + F = 2 over the positions used.
    let mut used = vec![false; positions.len()];
    faces
        .iter()
        .flatten()
        .for_each(|&i| used[id[i as usize] as usize] = true);
    let v = used.iter().filter(|&&u| u).count() as i64;
    if v - (edges.len() / 2) as i64 + faces.len() as i64 != 2 {
        return (true, false);
    }
    let point = |i: u32| {
        let p = positions[i as usize];
        robust::Coord3D {
            x: p.x as f64,
            y: p.y as f64,
            z: p.z as f64,
        }
    };
    // Locally convex at every edge: the far corner of the second face on
    // or below (inside) the first face's plane.
    for p in pairs {
        let (f, g) = (faces[p[0].1 as usize], faces[p[1].1 as usize]);
        let far = g[p[1].2 as usize];
        if robust::orient3d(point(f[0]), point(f[1]), point(f[2]), point(far)) < 0.0 {
            return (true, false);
        }
    }
    // At every vertex the faces turn once around it: their angles there
    // sum to at most 2π (a flat vertex inside a face sums to 2π, up to
    // rounding; a cone wound twice, to nearly 4π).
    let mut angle = vec![0.0f64; positions.len()];
    for face in faces {
        let p = face.map(|i| positions[i as usize].as_dvec3());
        for k in 0..3 {
            let (a, b) = (p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]);
            let turn = a.cross(b).length().atan2(a.dot(b));
            if turn.is_nan() || turn <= 0.0 {
                return (true, false);
            }
            angle[id[face[k] as usize] as usize] += turn;
        }
    }
    let full = std::f64::consts::TAU * (1.0 + 1e-9);
    (true, angle.iter().all(|&a| a <= full))
}

/// Angle-weighted vertex normals; a vertex on no face (or only degenerate
/// ones) gets +z.
pub fn vertex_normals(positions: &[Vec3], faces: &[[u32; 3]]) -> Vec<Vec3> {
    let mut sum = vec![Vec3::ZERO; positions.len()];
    for f in faces {
        let p = f.map(|i| positions[i as usize]);
        let n = crate::transform::face_normal(p[0], p[1], p[2]);
        if !n.is_finite() {
            continue;
        }
        for k in 0..3 {
            let a = crate::transform::direction(p[(k + 1) % 3] - p[k]);
            let b = crate::transform::direction(p[(k + 2) % 3] - p[k]);
            let angle = a.dot(b).clamp(-1.0, 1.0).acos();
            sum[f[k] as usize] += n * angle;
        }
    }
    sum.into_iter()
        .map(|n| {
            let n = crate::transform::direction(n);
            if n == Vec3::ZERO { Vec3::Z } else { n }
        })
        .collect()
}

/// Cuts a simple polygon (its vertices' indices into `positions`, in order)
/// into triangles by ear clipping, in the plane that best fits it (Newell's
/// normal). Appends to `out`. A polygon that has no ear (self-intersecting,
/// or degenerate) falls back to a fan.
pub fn triangulate(positions: &[Vec3], polygon: &[u32], out: &mut Vec<[u32; 3]>) {
    let n = polygon.len();
    if n < 3 {
        return;
    }
    if n == 3 {
        out.push([polygon[0], polygon[1], polygon[2]]);
        return;
    }
    // Newell's normal, then drop its largest axis to work in 2D.
    let p3: Vec<Vec3> = polygon.iter().map(|&i| positions[i as usize]).collect();
    let mut normal = Vec3::ZERO;
    for i in 0..n {
        let (a, b) = (p3[i], p3[(i + 1) % n]);
        normal += Vec3::new(
            (a.y - b.y) * (a.z + b.z),
            (a.z - b.z) * (a.x + b.x),
            (a.x - b.x) * (a.y + b.y),
        );
    }
    let abs = normal.abs();
    let flat: Vec<Vec2> = p3
        .iter()
        .map(|p| {
            if abs.x >= abs.y && abs.x >= abs.z {
                Vec2::new(p.y * normal.x.signum(), p.z)
            } else if abs.y >= abs.z {
                Vec2::new(p.z * normal.y.signum(), p.x)
            } else {
                Vec2::new(p.x * normal.z.signum(), p.y)
            }
        })
        .collect();
    // Negating one coordinate where the normal points down the dropped axis
    // keeps the projected polygon counter-clockwise.
    let cross = |o: Vec2, a: Vec2, b: Vec2| (a - o).perp_dot(b - o);
    let mut left: Vec<usize> = (0..n).collect();
    let start = out.len();
    let mut guard = 0;
    while left.len() > 3 && guard < n * n {
        guard += 1;
        let m = left.len();
        let ear = (0..m).find(|&k| {
            let (ia, ib, ic) = (left[(k + m - 1) % m], left[k], left[(k + 1) % m]);
            let (a, b, c) = (flat[ia], flat[ib], flat[ic]);
            if cross(a, b, c) <= 0.0 {
                return false; // reflex or degenerate corner
            }
            // No other remaining vertex inside (or on) the ear.
            left.iter().all(|&j| {
                j == ia || j == ib || j == ic || {
                    let p = flat[j];
                    !(cross(a, b, p) >= 0.0 && cross(b, c, p) >= 0.0 && cross(c, a, p) >= 0.0)
                }
            })
        });
        match ear {
            Some(k) => {
                let (ia, ib, ic) = (left[(k + m - 1) % m], left[k], left[(k + 1) % m]);
                out.push([polygon[ia], polygon[ib], polygon[ic]]);
                left.remove(k);
            }
            None => {
                // Not simple: fall back to a fan over the whole polygon.
                out.truncate(start);
                out.extend((1..n - 1).map(|i| [polygon[0], polygon[i], polygon[i + 1]]));
                return;
            }
        }
    }
    if left.len() == 3 {
        out.push([polygon[left[0]], polygon[left[1]], polygon[left[2]]]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area2(p: &[Vec3], t: [u32; 3]) -> f32 {
        let [a, b, c] = t.map(|i| p[i as usize]);
        (b - a).cross(c - a).z
    }

    #[test]
    fn ear_clipping_a_non_convex_polygon_covers_it_exactly() {
        // An L shape, counter-clockwise: area 3. A fan from vertex 0 would
        // cover area outside it.
        let p: Vec<Vec3> = [
            (0.0, 0.0),
            (2.0, 0.0),
            (2.0, 1.0),
            (1.0, 1.0),
            (1.0, 2.0),
            (0.0, 2.0),
        ]
        .iter()
        .map(|&(x, y)| Vec3::new(x, y, 0.0))
        .collect();
        let mut tris = Vec::new();
        triangulate(&p, &[0, 1, 2, 3, 4, 5], &mut tris);
        assert_eq!(tris.len(), 4);
        let total: f32 = tris.iter().map(|&t| area2(&p, t)).sum();
        assert!((total - 6.0).abs() < 1e-5, "{total}");
        assert!(
            tris.iter().all(|&t| area2(&p, t) > 0.0),
            "same winding as the polygon"
        );
        // A concave "arrow" whose fan from vertex 0 would fold over itself.
        let p: Vec<Vec3> = [(0.0, 0.0), (4.0, 0.0), (1.0, 1.0), (0.0, 4.0)]
            .iter()
            .map(|&(x, y)| Vec3::new(x, y, 0.0))
            .collect();
        let mut tris = Vec::new();
        triangulate(&p, &[1, 2, 3, 0], &mut tris);
        let total: f32 = tris.iter().map(|&t| area2(&p, t)).sum();
        assert!((total - 8.0).abs() < 1e-5, "{total}");
        assert!(tris.iter().all(|&t| area2(&p, t) > 0.0));
    }

    #[test]
    fn closed_convex_is_found_only_where_true() {
        use crate::scene::shapes::Shape;
        let cube = Shape::Cube.mesh(Rgb::WHITE);
        assert!(cube.shape.closed_convex);
        assert!(Shape::Sphere.mesh(Rgb::WHITE).shape.closed_convex);
        assert!(
            !Shape::Torus.mesh(Rgb::WHITE).shape.closed_convex,
            "closed but not convex"
        );
        // A cube with a face missing is not closed.
        let mut open = cube.clone();
        open.faces.pop();
        open.analyze();
        assert!(!open.shape.closed_convex);
        // A cube with one face wound the wrong way is not consistent.
        let mut flipped = cube.clone();
        flipped.faces[0].swap(1, 2);
        flipped.faces[1].swap(1, 2);
        flipped.analyze();
        assert!(!flipped.shape.closed_convex);
        // A dented cube is closed but not convex.
        let mut dented = cube.clone();
        let top: Vec<usize> = (0..dented.positions.len())
            .filter(|&i| dented.positions[i].y > 0.5)
            .collect();
        for i in top {
            if dented.positions[i].x > 0.5 && dented.positions[i].z > 0.5 {
                dented.positions[i] *= 0.5;
            }
        }
        dented.analyze();
        assert!(!dented.shape.closed_convex);
        assert_eq!(
            cube.shape.bounds,
            Some([Vec3::splat(-0.6), Vec3::splat(0.6)])
        );
    }

    #[test]
    fn normals_of_a_flat_square_point_up_and_fit_is_unit() {
        let p = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(2.0, 2.0, 0.0),
            Vec3::new(0.0, 2.0, 0.0),
        ];
        let mut m = Mesh::new("sq", p, vec![[0, 1, 2], [0, 2, 3]], Rgb::WHITE);
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
            let mut m = Mesh::new("t", p, vec![[0, 1, 2]], Rgb::WHITE);
            m.fit_unit_sphere();
            let far = m.positions.iter().map(|p| p.length()).fold(0.0, f32::max);
            assert!((far - 1.0).abs() < 1e-6, "{size}: {far}");
            assert_eq!(m.model, Mat4::IDENTITY);
        }
    }
}
