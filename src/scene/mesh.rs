//! Meshes and lights: indexed triangles with per-face colours, per-vertex
//! normals, and the transform that places them in the world.
//!
//! Normals missing from a file are computed: each vertex gets the sum of
//! the normals of the faces around it, each weighted by the face's angle at
//! that vertex (so that a vertex's normal does not depend on how the
//! surface around it happens to be split into triangles). Polygons of more
//! than three vertices are cut into triangles by ear clipping, which is
//! right for non-convex polygons where a fan is not.

use glam::{Mat4, Vec2, Vec3};

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
    /// Closed (every edge shared by exactly two faces, walked in opposite
    /// directions), consistently wound, and convex (every position on the
    /// inner side of every face's plane). Its faces seen from one side then
    /// never overlap on screen, which lets the planner skip the depth
    /// buffer. `false` when unsure (including meshes too big to check).
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
        self.shape = MeshShape {
            bounds,
            closed_convex: finite
                && closed(&self.positions, &self.faces)
                && convex(&self.positions, &self.faces),
        };
    }

    /// The centre and radius of a sphere around all positions (the centre of
    /// the bounding box, and the farthest position from it).
    pub fn bounds(&self) -> (Vec3, f32) {
        let finite = self.positions.iter().filter(|p| p.is_finite());
        let (lo, hi) = finite.fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &p| {
            (lo.min(p), hi.max(p))
        });
        if lo.x > hi.x {
            return (Vec3::ZERO, 1.0);
        }
        let centre = (lo + hi) / 2.0;
        let radius = self
            .positions
            .iter()
            .filter(|p| p.is_finite())
            .map(|p| p.distance(centre))
            .fold(0.0f32, f32::max);
        (centre, radius)
    }

    /// Centres the mesh on the origin and scales it to fit the unit sphere
    /// (the model transform, which is replaced).
    pub fn fit_unit_sphere(&mut self) {
        let (centre, radius) = self.bounds();
        let scale = if radius > 0.0 && radius.is_finite() {
            1.0 / radius
        } else {
            1.0
        };
        self.model = Mat4::from_scale(Vec3::splat(scale)) * Mat4::from_translation(-centre);
    }
}

/// Whether every edge is shared by exactly two faces walking it in opposite
/// directions. Corners are matched by position, so a cube whose faces have
/// vertices of their own still counts as closed.
fn closed(positions: &[Vec3], faces: &[[u32; 3]]) -> bool {
    use std::collections::HashMap;
    // −0.0 and 0.0 are the same position.
    let key = |i: u32| {
        positions[i as usize]
            .to_array()
            .map(|v| (v + 0.0).to_bits())
    };
    let mut ids: HashMap<[u32; 3], u32> = HashMap::with_capacity(positions.len());
    let id: Vec<u32> = (0..positions.len() as u32)
        .map(|i| {
            let n = ids.len() as u32;
            *ids.entry(key(i)).or_insert(n)
        })
        .collect();
    // For each undirected edge, how often it is walked low→high and
    // high→low: closed and consistently wound is exactly once each way.
    let mut edges: HashMap<(u32, u32), [u32; 2]> = HashMap::with_capacity(faces.len() * 3);
    for f in faces {
        let v = f.map(|i| id[i as usize]);
        if v[0] == v[1] || v[1] == v[2] || v[2] == v[0] {
            return false;
        }
        for k in 0..3 {
            let (a, b) = (v[k], v[(k + 1) % 3]);
            let e = edges.entry((a.min(b), a.max(b))).or_insert([0, 0]);
            e[(a > b) as usize] += 1;
        }
    }
    !faces.is_empty() && edges.values().all(|&e| e == [1, 1])
}

/// Whether every position lies on the inner side of every face's plane
/// (within a tolerance relative to the mesh's size). Quadratic, so meshes
/// of more than 4,000 faces are reported as not convex.
fn convex(positions: &[Vec3], faces: &[[u32; 3]]) -> bool {
    if faces.len() > 4000 {
        return false;
    }
    let scale = positions
        .iter()
        .fold(0.0f32, |m, p| m.max(p.abs().max_element()))
        .max(1e-30);
    faces.iter().all(|f| {
        let [a, b, c] = f.map(|i| positions[i as usize]);
        let n = (b - a).cross(c - a);
        let len = n.length();
        len == 0.0
            || positions
                .iter()
                .all(|&p| n.dot(p - a) <= 1e-5 * scale * len)
    })
}

/// Angle-weighted vertex normals; a vertex on no face (or only degenerate
/// ones) gets +z.
pub fn vertex_normals(positions: &[Vec3], faces: &[[u32; 3]]) -> Vec<Vec3> {
    let mut sum = vec![Vec3::ZERO; positions.len()];
    for f in faces {
        let p = f.map(|i| positions[i as usize]);
        let n = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero();
        if !n.is_finite() {
            continue;
        }
        for k in 0..3 {
            let a = (p[(k + 1) % 3] - p[k]).normalize_or_zero();
            let b = (p[(k + 2) % 3] - p[k]).normalize_or_zero();
            let angle = a.dot(b).clamp(-1.0, 1.0).acos();
            sum[f[k] as usize] += n * angle;
        }
    }
    sum.into_iter()
        .map(|n| {
            let n = n.normalize_or_zero();
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
        let far = m
            .positions
            .iter()
            .map(|&p| m.model.transform_point3(p).length())
            .fold(0.0, f32::max);
        assert!((far - 1.0).abs() < 1e-6);
    }
}
