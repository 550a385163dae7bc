//! Built-in shapes, counter-clockwise seen from outside, unit-sized.

use std::f32::consts::TAU;

use std::sync::{Arc, OnceLock};

use glam::Vec3;

use super::mesh::{Geometry, Mesh};
use crate::color::Rgb;

/// A built-in shape.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Shape {
    /// A cube with edges of length 1.2, each face its own four vertices (so
    /// its normals stay sharp).
    Cube,
    /// A UV sphere of radius 1.
    Sphere,
    /// A torus of radii 0.7 and 0.3 about the y axis: the default model.
    #[default]
    Torus,
}

impl Shape {
    /// Every shape.
    pub const ALL: [Shape; 3] = [Shape::Cube, Shape::Sphere, Shape::Torus];

    /// Its name in a scene file and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Shape::Cube => "cube",
            Shape::Sphere => "sphere",
            Shape::Torus => "torus",
        }
    }

    /// The shape of that name.
    pub fn from_name(name: &str) -> Option<Shape> {
        Shape::ALL.into_iter().find(|s| s.name() == name)
    }

    /// The shape whose name is nearest `name`, if one is within two edits
    /// of it (for "did you mean": `torsu` is `torus`).
    pub fn nearest(name: &str) -> Option<Shape> {
        Shape::ALL
            .into_iter()
            .map(|s| (edits(name, s.name()), s))
            .filter(|&(d, _)| d <= 2)
            .min_by_key(|&(d, _)| d)
            .map(|(_, s)| s)
    }

    /// A mesh of the shape in `color`. The geometry is built once and
    /// shared by every mesh of the shape.
    pub fn mesh(self, color: Rgb) -> Mesh {
        Mesh::of(self.geometry(), color)
    }

    /// The shape's geometry, built on first use.
    pub fn geometry(self) -> Arc<Geometry> {
        static BUILT: [OnceLock<Arc<Geometry>>; 3] =
            [OnceLock::new(), OnceLock::new(), OnceLock::new()];
        let i = Shape::ALL.iter().position(|&s| s == self).unwrap_or(0);
        Arc::clone(BUILT[i].get_or_init(|| Arc::new(self.build())))
    }

    fn build(self) -> Geometry {
        let (positions, faces) = match self {
            Shape::Cube => cube(),
            Shape::Sphere => grid(48, 24, false, |u, v| {
                let (theta, phi) = (u * TAU, v * std::f32::consts::PI);
                // Exactly on the poles (sin π is not 0 in f32), so that the
                // pole triangles are exactly degenerate and dropped below.
                let ring = if v == 0.0 || v == 1.0 { 0.0 } else { phi.sin() };
                Vec3::new(ring * theta.cos(), -phi.cos(), -ring * theta.sin())
            }),
            Shape::Torus => grid(64, 32, true, |u, v| {
                let (theta, phi) = (u * TAU, v * TAU);
                let r = 0.7 + 0.3 * phi.cos();
                Vec3::new(r * theta.cos(), 0.3 * phi.sin(), -r * theta.sin())
            }),
        };
        Geometry::new(self.name(), positions, faces)
    }
}

fn cube() -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let h = 0.6;
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    // Each face: its normal and two in-plane axes (u × v = normal).
    for n in [
        Vec3::X,
        Vec3::NEG_X,
        Vec3::Y,
        Vec3::NEG_Y,
        Vec3::Z,
        Vec3::NEG_Z,
    ] {
        let u = if n.x != 0.0 {
            Vec3::Y
        } else {
            Vec3::X * n.y.abs() + Vec3::Y * n.z.abs()
        };
        let u = if n.y != 0.0 { Vec3::Z } else { u };
        let v = n.cross(u);
        let base = positions.len() as u32;
        for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            positions.push((n + u * a + v * b) * h);
        }
        faces.push([base, base + 1, base + 2]);
        faces.push([base, base + 2, base + 3]);
    }
    (positions, faces)
}

/// A `nu × nv` grid of quads wrapped by `f(u, v)` over [0,1)², with the seams
/// (and, for the sphere, the poles) sharing vertices. Each quad is cut
/// along the diagonal that folds outwards: the four corners, rounded to
/// f32, are seldom exactly coplanar, and the other diagonal would leave a
/// dent a millionth deep, enough for the sphere not to be convex.
fn grid(
    nu: u32,
    nv: u32,
    wrap_v: bool,
    f: impl Fn(f32, f32) -> Vec3,
) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let mut positions = Vec::new();
    let rings = if wrap_v { nv } else { nv + 1 };
    for j in 0..rings {
        for i in 0..nu {
            positions.push(f(i as f32 / nu as f32, j as f32 / nv as f32));
        }
    }
    // The seams share vertices: u always, v for a torus (its last ring is
    // its first: computing it again would round sin 2π to 1.7e-7, not 0,
    // and leave a crack of a seam along the outer equator).
    let at = |i: u32, j: u32| (j % rings) * nu + i % nu;
    let mut faces = Vec::new();
    for j in 0..nv {
        for i in 0..nu {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            let p = |i: u32| {
                let v = positions[i as usize];
                robust::Coord3D {
                    x: v.x as f64,
                    y: v.y as f64,
                    z: v.z as f64,
                }
            };
            // d on or below (inside) the plane of a, b, c: a–c folds out.
            if robust::orient3d(p(a), p(b), p(c), p(d)) >= 0.0 {
                faces.push([a, b, c]);
                faces.push([a, c, d]);
            } else {
                faces.push([a, b, d]);
                faces.push([b, c, d]);
            }
        }
    }
    // Triangles with two corners on a pole have no area: leave them out.
    let p = &positions;
    faces.retain(|f| {
        let [a, b, c] = f.map(|i| p[i as usize]);
        a != b && b != c && c != a
    });
    (positions, faces)
}

/// The edit distance between `a` and `b` (insertions, deletions,
/// substitutions and swaps of neighbours, each one edit), in characters.
fn edits(a: &str, b: &str) -> usize {
    let (a, b): (Vec<char>, Vec<char>) = (a.chars().collect(), b.chars().collect());
    if a.len().abs_diff(b.len()) > 2 || a.len() > 64 {
        return usize::MAX;
    }
    let mut d = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    for (j, cell) in d[0].iter_mut().enumerate() {
        *cell = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut v = (d[i - 1][j] + 1)
                .min(d[i][j - 1] + 1)
                .min(d[i - 1][j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                v = v.min(d[i - 2][j - 2] + 1);
            }
            d[i][j] = v;
        }
    }
    d[a.len()][b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shapes_face_outwards() {
        for shape in Shape::ALL {
            let m = shape.mesh(Rgb::WHITE);
            let mut outward = 0;
            let mut total = 0;
            for f in &m.faces {
                let [a, b, c] = f.map(|i| m.positions[i as usize]);
                let n = (b - a).cross(c - a);
                assert!(n.length() > 1e-6, "{shape:?}: a degenerate face");
                total += 1;
                let centre = (a + b + c) / 3.0;
                // Outward: away from the centre of the cube and sphere, away
                // from the torus's core circle.
                let core = if shape == Shape::Torus {
                    Vec3::new(centre.x, 0.0, centre.z).normalize() * 0.7
                } else {
                    Vec3::ZERO
                };
                if n.dot(centre - core) > 0.0 {
                    outward += 1;
                }
            }
            assert_eq!(outward, total, "{shape:?}");
            assert!(
                m.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-4),
                "{shape:?}"
            );
        }
    }
}
