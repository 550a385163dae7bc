//! Tangents for normal maps: each face corner's, from the file where it
//! gives them per vertex, else MikkTSpace's (`bevy_mikktspace`, a safe
//! port that gives the reference implementation's bits), which is what
//! the tools that bake normal maps (Blender, Substance, xNormal) assume
//! and what glTF asks for when a file has none.
//!
//! glTF's `v` runs down the image and a normal map's green up it, so the
//! bitangent a normal map means is where `v` falls: MikkTSpace's sign
//! (where `v` grows) is turned over.
//!
//! Trade-offs. Kept per corner, not per vertex: MikkTSpace gives a vertex
//! on a line where UVs are mirrored a different tangent on each side, and
//! splitting such vertices would have to split everything else a vertex
//! carries (colours, skins, morph targets) too. A corner MikkTSpace leaves
//! without a tangent (a face of no area in UV space, with no neighbour to
//! borrow one from) gets one perpendicular to its normal, so a map still
//! bends it the same way whichever way the face turns.

use bevy_mikktspace::{Geometry as Mikk, TangentSpace, generate_tangents};
use glam::{Vec3, Vec4};

use super::mesh::Geometry;

/// Each face's corners' tangents: `file`'s per vertex (one a position),
/// or MikkTSpace's from the positions, normals and UVs.
pub(super) fn of(g: &Geometry, file: Option<&[Vec4]>) -> Vec<[Vec4; 3]> {
    if let Some(t) = file {
        return g.faces.iter().map(|f| f.map(|i| t[i as usize])).collect();
    }
    let mut m = Corners {
        g,
        out: vec![[Vec4::ZERO; 3]; g.faces.len()],
    };
    // The crate's error type has no variants: it cannot fail.
    let _ = generate_tangents(&mut m);
    let Corners { mut out, .. } = m;
    for (face, ts) in g.faces.iter().zip(&mut out) {
        for (k, t) in ts.iter_mut().enumerate() {
            if *t == Vec4::ZERO {
                let n = g.normals[face[k] as usize];
                *t = n.any_orthonormal_vector().extend(1.0);
            }
        }
    }
    out
}

/// The geometry as MikkTSpace reads it, and where its answers go.
struct Corners<'a> {
    g: &'a Geometry,
    out: Vec<[Vec4; 3]>,
}

impl Corners<'_> {
    fn vertex(&self, face: usize, vert: usize) -> usize {
        self.g.faces[face][vert] as usize
    }
}

impl Mikk for Corners<'_> {
    fn num_faces(&self) -> usize {
        self.g.faces.len()
    }

    fn num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }

    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.g.positions[self.vertex(face, vert)].to_array()
    }

    fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
        self.g.normals[self.vertex(face, vert)].to_array()
    }

    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        let uvs = self.g.uvs.as_deref().unwrap_or(&[]);
        uvs.get(self.vertex(face, vert))
            .map_or([0.0; 2], |uv| uv.to_array())
    }

    fn set_tangent(&mut self, t: Option<TangentSpace>, face: usize, vert: usize) {
        if let Some(t) = t {
            let [x, y, z, w] = t.tangent_encoded();
            let xyz = Vec3::new(x, y, z);
            if xyz.is_finite() && xyz != Vec3::ZERO {
                // MikkTSpace's bitangent is where v grows, glTF's where
                // it falls (its v runs down the image, a normal map's y
                // up it): the sign turned, as three.js turns it for glTF.
                self.out[face][vert] = xyz.extend(-w);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec2;

    /// A unit square in the xy plane facing +z, its UVs `u = x` and
    /// `v = 1 − y` (v down the image, as glTF has it), the left half's
    /// mirrored in u when `mirror`.
    fn square(mirror: bool) -> Geometry {
        let positions = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ];
        let mut g = Geometry::new("square", positions.clone(), vec![[0, 1, 2], [0, 2, 3]]);
        g.normals = vec![Vec3::Z; 4];
        g.uvs = Some(
            positions
                .iter()
                .map(|p| Vec2::new(if mirror { 1.0 - p.x } else { p.x }, 1.0 - p.y))
                .collect(),
        );
        g
    }

    #[test]
    fn a_square_whose_u_runs_along_x_has_x_for_its_tangent() {
        // u along +x, v down (−y): the bitangent cross(n, t) = +y points
        // up the image, against v, as a normal map's green does: w = 1.
        for ts in of(&square(false), None) {
            for t in ts {
                assert!((t.truncate() - Vec3::X).length() < 1e-6, "{t}");
                assert_eq!(t.w, 1.0);
            }
        }
    }

    #[test]
    fn mirrored_uvs_turn_the_tangent_and_its_sign() {
        for ts in of(&square(true), None) {
            for t in ts {
                assert!((t.truncate() + Vec3::X).length() < 1e-6, "{t}");
                assert_eq!(t.w, -1.0);
            }
        }
    }

    #[test]
    fn the_files_tangents_are_kept() {
        let t = [Vec4::new(0.0, 1.0, 0.0, -1.0); 4];
        let g = square(false);
        assert_eq!(of(&g, Some(&t)), vec![[t[0]; 3]; 2]);
    }
}
