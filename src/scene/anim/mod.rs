//! Models that move: a node hierarchy, skins, morph targets and the clips
//! that animate them (glTF's), and the pose of a model's vertices at a
//! time in a clip.
//!
//! A [`Rig`] belongs to a [`super::Geometry`] whose vertices move. The
//! geometry keeps its rest pose (every node at its own transform, morph
//! weights at their defaults), computed by the same code that poses it
//! ([`Rig::pose_into`]), so that a frame at rest is the same bit for bit
//! whether or not the pose is computed: that is what lets the planner skip
//! posing a mesh that the clip does not move. The rig keeps, for each part
//! of the geometry (one glTF primitive as one node places it), its
//! vertices in the mesh's own space and how they move: rigidly with their
//! node, skinned by a skin's joints (any number of weighted joints a
//! vertex, the weights normalised), and morphed by targets (positions and
//! normals) before either.
//!
//! Trade-offs. Posing is plain f32 arithmetic per vertex: a morph adds each
//! target's weighted offset, a skin blends its joints' affine matrices by
//! the weights and applies the blend, and a normal is transformed by the
//! blend's cofactor matrix (its inverse transpose times its determinant),
//! which is right under any scale, uniform or not, without a division;
//! then normalised. A vertex of one joint takes that joint's matrices,
//! found once a frame, with no blend. Node transforms are composed once a frame, in parents'
//! order. A clip's channels share one time; the clip loops when its
//! longest channel ends, and the time is wrapped into it in f64.

mod sampler;

use glam::{Affine3A, DVec3, Mat3A, Mat4, Quat, Vec3, Vec3A};

pub use sampler::{Interpolation, Invalid, Sampler};

/// The largest number of morph targets read on one primitive.
pub const MAX_TARGETS: usize = 256;

/// What a channel animates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Property {
    /// The node's translation.
    Translation,
    /// The node's rotation.
    Rotation,
    /// The node's scale.
    Scale,
    /// The morph weights of the node's mesh.
    Weights,
}

impl Property {
    /// The name glTF gives it.
    pub fn name(self) -> &'static str {
        match self {
            Property::Translation => "translation",
            Property::Rotation => "rotation",
            Property::Scale => "scale",
            Property::Weights => "weights",
        }
    }
}

/// One animated property of one node.
#[derive(Clone, Debug, PartialEq)]
pub struct Channel {
    /// The node, an index into the rig's nodes.
    pub node: u32,
    /// What of it.
    pub property: Property,
    /// Its keyframes.
    pub sampler: Sampler,
}

/// A named animation: channels that share one time.
#[derive(Clone, Debug, PartialEq)]
pub struct Clip {
    /// Its name (escaped before it is shown), or empty.
    pub name: String,
    /// Its channels.
    pub channels: Vec<Channel>,
    /// How long it runs: its longest channel's last key.
    pub length: f64,
    /// For each of its rig's parts, whether it moves a vertex of it
    /// ([`Rig::settle`] finds it; empty before, which poses every part).
    pub moves: Vec<bool>,
}

impl Clip {
    /// `time` (seconds, any finite number) wrapped into the clip: the clip
    /// loops when its longest channel ends.
    pub fn local(&self, time: f64) -> f64 {
        if self.length > 0.0 && time.is_finite() {
            time.rem_euclid(self.length)
        } else {
            0.0
        }
    }
}

/// A node's transform relative to its parent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Trs {
    /// Translation.
    pub translation: Vec3,
    /// Rotation, a unit quaternion.
    pub rotation: Quat,
    /// Scale.
    pub scale: Vec3,
}

impl Trs {
    /// The transform as a matrix: translation × rotation × scale.
    pub fn matrix(&self) -> Mat4 {
        Mat4::from_scale_rotation_translation(self.scale, self.rotation, self.translation)
    }
}

/// A node of the hierarchy.
#[derive(Clone, Debug, PartialEq)]
pub struct Node {
    /// Its parent, an index before its own; `None` at a root.
    pub parent: Option<u32>,
    /// Its own transform: a matrix (never animated, as the format says) or
    /// translation, rotation and scale.
    pub rest: Result<Trs, Mat4>,
    /// The morph weights of its mesh at rest (empty without targets).
    pub weights: Vec<f32>,
    /// Its index in the file it was read from, which `--explain` names;
    /// `None` for a rig built in code.
    pub source: Option<u32>,
}

/// A skin: the joints that move its vertices, and the matrices that take
/// a vertex from the mesh's space to each joint's.
#[derive(Clone, Debug, PartialEq)]
pub struct Skin {
    /// The joints, indices into the rig's nodes.
    pub joints: Vec<u32>,
    /// One inverse bind matrix a joint.
    pub inverse_bind: Vec<Mat4>,
}

/// How a part's vertices move.
#[derive(Clone, Debug, PartialEq)]
pub enum Binding {
    /// With node `n`, rigidly.
    Node(u32),
    /// By skin `skin`'s joints: vertex `v`'s are `influences[starts[v] ..
    /// starts[v + 1]]`, `(joint, weight)`, the weights summing to one (a
    /// vertex without weight moves with the node that places the mesh).
    Skin {
        /// The skin, an index into the rig's skins.
        skin: u32,
        /// Where each vertex's influences start (one more than the
        /// vertices).
        starts: Vec<u32>,
        /// Joints (indices into the skin's) and their weights.
        influences: Vec<(u16, f32)>,
        /// The node that places the mesh, for vertices without weight.
        node: u32,
    },
}

/// Morph targets of a part: each a position offset (and a normal offset)
/// a vertex.
#[derive(Clone, Debug, PartialEq)]
pub struct Morph {
    /// The node whose weights drive them.
    pub node: u32,
    /// Target `k`'s offset of vertex `v`: `positions[k · n + v]`.
    pub positions: Vec<Vec3>,
    /// Normal offsets, laid out likewise, when every target has them.
    pub normals: Option<Vec<Vec3>>,
}

/// One primitive as one node places it: a run of the geometry's vertices.
#[derive(Clone, Debug, PartialEq)]
pub struct Part {
    /// The geometry's first vertex of the part.
    pub first: u32,
    /// Its positions in the mesh's own space (the part's vertex count).
    pub positions: Vec<Vec3>,
    /// Its normals in the mesh's own space.
    pub normals: Vec<Vec3>,
    /// How they move.
    pub binding: Binding,
    /// Its morph targets.
    pub morph: Option<Morph>,
}

/// A moving model: nodes, skins, clips and the parts of its geometry they
/// move (see the module's documentation).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Rig {
    /// Parents before children.
    pub nodes: Vec<Node>,
    /// The skins.
    pub skins: Vec<Skin>,
    /// The clips.
    pub clips: Vec<Clip>,
    /// The parts of the geometry that move.
    pub parts: Vec<Part>,
    /// What the geometry's positions were moved and scaled by, in order
    /// (`(p − centre) · scale`, to fit a unit sphere): posed positions
    /// are, too.
    pub fitted: Vec<(DVec3, f64)>,
}

/// A time in a clip.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// The clip, an index into the rig's clips.
    pub clip: usize,
    /// Seconds from the clip's start (wrapped into it as it loops).
    pub time: f64,
}

/// What posing works with: each node's transforms and morph weights for
/// one pose, kept between frames so that a frame allocates nothing.
#[derive(Clone, Debug, Default)]
pub struct Posed {
    trs: Vec<Option<Trs>>,
    locals: Vec<Mat4>,
    worlds: Vec<Mat4>,
    weights: Vec<Vec<f32>>,
    joints: Vec<(Affine3A, Mat3A)>,
}

impl Rig {
    /// Adds a clip that plays every clip at once (their channels together,
    /// looping at the longest; where two move the same node's property the
    /// later clip's wins), named `all`, and returns its index: the one clip
    /// where there is only one.
    pub fn add_all_clips(&mut self) -> usize {
        if self.clips.len() < 2 {
            return 0;
        }
        let all = Clip {
            name: "all".into(),
            channels: self
                .clips
                .iter()
                .flat_map(|c| c.channels.iter().cloned())
                .collect(),
            length: self.clips.iter().map(|c| c.length).fold(0.0, f64::max),
            moves: (0..self.parts.len())
                .map(|k| self.clips.iter().any(|c| c.moves.get(k).is_none_or(|&m| m)))
                .collect(),
        };
        self.clips.push(all);
        self.clips.len() - 1
    }

    /// Whether clip `clip` moves any vertex (as [`Rig::settle`] found).
    pub fn moves(&self, clip: usize) -> bool {
        self.clips
            .get(clip)
            .is_some_and(|c| c.moves.iter().any(|&m| m))
    }

    /// Finds, for each clip, which parts it moves: those whose placing
    /// node, skin's joint (or an ancestor of either) or morph weights it
    /// animates. Posing leaves the others as they stand, which is at rest.
    /// Call it once the rig is built.
    pub fn settle(&mut self) {
        let moves: Vec<Vec<bool>> = self.clips.iter().map(|c| self.clip_moves(c)).collect();
        for (c, m) in self.clips.iter_mut().zip(moves) {
            c.moves = m;
        }
    }

    fn clip_moves(&self, c: &Clip) -> Vec<bool> {
        let mut animated = vec![false; self.nodes.len()];
        for ch in &c.channels {
            if let Some(a) = animated.get_mut(ch.node as usize) {
                *a = true;
            }
        }
        // Down the tree: a node moves if it or an ancestor is animated.
        let mut moved = vec![false; self.nodes.len()];
        for (i, n) in self.nodes.iter().enumerate() {
            moved[i] = animated[i] || n.parent.is_some_and(|p| moved[p as usize]);
        }
        self.parts
            .iter()
            .map(|p| {
                let by_weights = p.morph.as_ref().is_some_and(|m| {
                    c.channels
                        .iter()
                        .any(|ch| ch.node == m.node && ch.property == Property::Weights)
                });
                by_weights
                    || match &p.binding {
                        Binding::Node(n) => moved[*n as usize],
                        Binding::Skin { skin, node, .. } => {
                            moved[*node as usize]
                                || self.skins[*skin as usize]
                                    .joints
                                    .iter()
                                    .any(|&j| moved[j as usize])
                        }
                    }
            })
            .collect()
    }

    /// The node transforms and weights of `pose` (`None`: at rest) into
    /// `posed`.
    fn evaluate(&self, pose: Option<Pose>, posed: &mut Posed) {
        let n = self.nodes.len();
        posed.locals.clear();
        posed.weights.resize_with(n, Vec::new);
        let trs = &mut posed.trs;
        trs.clear();
        for (i, node) in self.nodes.iter().enumerate() {
            trs.push(node.rest.ok());
            posed.weights[i].clear();
            posed.weights[i].extend_from_slice(&node.weights);
        }
        if let Some(pose) = pose
            && let Some(clip) = self.clips.get(pose.clip)
        {
            let t = clip.local(pose.time);
            for ch in &clip.channels {
                let i = ch.node as usize;
                let mut v = [0.0f32; 3];
                match ch.property {
                    Property::Translation => {
                        ch.sampler.sample(t, &mut v);
                        if let Some(trs) = &mut trs[i] {
                            trs.translation = Vec3::from(v);
                        }
                    }
                    Property::Scale => {
                        ch.sampler.sample(t, &mut v);
                        if let Some(trs) = &mut trs[i] {
                            trs.scale = Vec3::from(v);
                        }
                    }
                    Property::Rotation => {
                        if let Some(trs) = &mut trs[i] {
                            trs.rotation = ch.sampler.sample_rotation(t);
                        }
                    }
                    Property::Weights => {
                        let w = &mut posed.weights[i];
                        w.resize(ch.sampler.width(), 0.0);
                        ch.sampler.sample(t, w);
                    }
                }
            }
        }
        posed.worlds.clear();
        for (i, node) in self.nodes.iter().enumerate() {
            let local = match (&trs[i], node.rest) {
                (Some(t), _) => t.matrix(),
                (None, Err(m)) => m,
                (None, Ok(t)) => t.matrix(),
            };
            posed.locals.push(local);
            let world = match node.parent {
                Some(p) => posed.worlds[p as usize] * local,
                None => local,
            };
            posed.worlds.push(world);
        }
    }

    /// Writes the geometry's positions and normals at `pose` (`None`: at
    /// rest) for every part into `positions` and `normals` (the geometry's
    /// arrays or copies of them; vertices outside the parts are left
    /// alone); returns the vertices posed.
    pub fn pose_into(
        &self,
        pose: Option<Pose>,
        posed: &mut Posed,
        positions: &mut [Vec3],
        normals: &mut [Vec3],
    ) -> u64 {
        self.pose_parts(pose, false, posed, positions, normals)
    }

    /// As [`Rig::pose_into`], but only the parts the pose's clip moves
    /// ([`Rig::settle`]): the others are left as `positions` and `normals`
    /// hold them, which for copies of the geometry's own arrays is at rest,
    /// where the clip leaves them, bit for bit. What a planned frame does.
    pub fn pose_moving_into(
        &self,
        pose: Pose,
        posed: &mut Posed,
        positions: &mut [Vec3],
        normals: &mut [Vec3],
    ) -> u64 {
        self.pose_parts(Some(pose), true, posed, positions, normals)
    }

    fn pose_parts(
        &self,
        pose: Option<Pose>,
        only_moving: bool,
        posed: &mut Posed,
        positions: &mut [Vec3],
        normals: &mut [Vec3],
    ) -> u64 {
        self.evaluate(pose, posed);
        let moves = pose
            .and_then(|p| self.clips.get(p.clip))
            .filter(|_| only_moving)
            .map_or(&[][..], |c| &c.moves[..]);
        let mut count = 0;
        for (k, part) in self.parts.iter().enumerate() {
            if moves.get(k) == Some(&false) {
                continue;
            }
            let n = part.positions.len();
            let first = part.first as usize;
            let (out_p, out_n) = (
                &mut positions[first..first + n],
                &mut normals[first..first + n],
            );
            // Morph targets first, in the mesh's space.
            let weights = part
                .morph
                .as_ref()
                .map_or(&[][..], |m| &posed.weights[m.node as usize][..]);
            for v in 0..n {
                let (mut p, mut nv) = (part.positions[v], part.normals[v]);
                if let Some(m) = &part.morph {
                    for (k, &w) in weights.iter().enumerate() {
                        if w != 0.0 {
                            if let Some(d) = m.positions.get(k * n + v) {
                                p += w * *d;
                            }
                            if let Some(d) = m.normals.as_ref().and_then(|ns| ns.get(k * n + v)) {
                                nv += w * *d;
                            }
                        }
                    }
                }
                out_p[v] = p;
                out_n[v] = nv;
            }
            match &part.binding {
                Binding::Node(node) => {
                    let (m, cof) = affine(posed.worlds[*node as usize]);
                    for v in 0..n {
                        out_p[v] = m.transform_point3(out_p[v]);
                        out_n[v] = (cof * out_n[v]).normalize_or_zero();
                    }
                }
                Binding::Skin {
                    skin,
                    starts,
                    influences,
                    node,
                } => {
                    let skin = &self.skins[*skin as usize];
                    // Each joint's matrix and its normals' matrix, once.
                    posed.joints.clear();
                    posed.joints.extend(
                        skin.joints
                            .iter()
                            .zip(&skin.inverse_bind)
                            .map(|(&j, ibm)| affine(posed.worlds[j as usize] * *ibm)),
                    );
                    let placed = affine(posed.worlds[*node as usize]);
                    for v in 0..n {
                        let inf = &influences[starts[v] as usize..starts[v + 1] as usize];
                        // One joint (a weight of exactly one): its own
                        // matrices; several: the blend and its cofactor.
                        let (m, cof) = match inf {
                            [] => placed,
                            [(j, _)] => posed.joints[*j as usize],
                            _ => {
                                let (mut m3, mut t) = (Mat3A::ZERO, Vec3A::ZERO);
                                for &(j, w) in inf {
                                    let a = posed.joints[j as usize].0;
                                    m3 += a.matrix3 * w;
                                    t += a.translation * w;
                                }
                                let m = Affine3A::from_mat3_translation(m3.into(), t.into());
                                (m, cofactor(m))
                            }
                        };
                        out_p[v] = m.transform_point3(out_p[v]);
                        out_n[v] = (cof * out_n[v]).normalize_or_zero();
                    }
                }
            }
            for &(centre, scale) in &self.fitted {
                for p in out_p.iter_mut() {
                    *p = ((p.as_dvec3() - centre) * scale).as_vec3();
                }
            }
            count += n as u64;
        }
        count
    }
}

/// An affine transform and the matrix its normals go through.
fn affine(m: Mat4) -> (Affine3A, Mat3A) {
    let a = Affine3A::from_mat4(m);
    (a, cofactor(a))
}

/// The matrix that takes a normal through `m`'s linear part: its cofactor
/// matrix (the inverse transpose times the determinant), its sign flipped
/// where `m` mirrors, so that an outward normal stays outward.
fn cofactor(m: Affine3A) -> Mat3A {
    let (x, y, z) = (m.matrix3.x_axis, m.matrix3.y_axis, m.matrix3.z_axis);
    let c = Mat3A::from_cols(y.cross(z), z.cross(x), x.cross(y));
    // The determinant is x · (y × z).
    if x.dot(c.x_axis) < 0.0 { -c } else { c }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn node(parent: Option<u32>, t: Vec3) -> Node {
        Node {
            parent,
            rest: Ok(Trs {
                translation: t,
                rotation: Quat::IDENTITY,
                scale: Vec3::ONE,
            }),
            weights: Vec::new(),
            source: None,
        }
    }

    #[test]
    fn the_cofactor_keeps_normals_normal_under_any_scale() {
        // A plane x = y, scaled 3× along x: its normal is no longer
        // (1, −1, 0) turned the same way but (1, −3, 0) normalised.
        let m = Mat4::from_scale(Vec3::new(3.0, 1.0, 1.0));
        let n = (affine(m).1 * Vec3::new(1.0, -1.0, 0.0)).normalize();
        let tangent = m.transform_vector3(Vec3::new(1.0, 1.0, 0.0));
        assert!(n.dot(tangent).abs() < 1e-6);
        // A mirror keeps an outward normal outward.
        let mirror = Mat4::from_scale(Vec3::new(-1.0, 1.0, 1.0));
        assert_eq!(affine(mirror).1 * Vec3::X, -Vec3::X);
    }

    #[test]
    fn a_clip_loops_at_its_longest_channel_and_moves_only_what_it_animates() {
        let lin = Interpolation::Linear;
        let clip = Clip {
            name: "walk".into(),
            channels: vec![
                Channel {
                    node: 1,
                    property: Property::Translation,
                    sampler: Sampler::new(vec![0.0, 1.0], vec![0.0; 6], 3, lin).unwrap(),
                },
                Channel {
                    node: 1,
                    property: Property::Scale,
                    sampler: Sampler::new(vec![0.0, 3.5], vec![1.0; 6], 3, lin).unwrap(),
                },
            ],
            length: 3.5,
            moves: Vec::new(),
        };
        assert_eq!(clip.local(1.0), 1.0);
        assert_eq!(clip.local(3.5), 0.0);
        assert_eq!(clip.local(4.0), 0.5);
        // A million seconds in: as exact as the first loop (3.5 is exact
        // in binary, and so is 1e6 mod 3.5 = 1.0).
        assert_eq!(clip.local(1_000_000.0), 1.0);
        assert_eq!(clip.local(-1.0), 2.5);
        let part = |binding| Part {
            first: 0,
            positions: vec![Vec3::ZERO],
            normals: vec![Vec3::Y],
            binding,
            morph: None,
        };
        let mut rig = Rig {
            nodes: vec![
                node(None, Vec3::ZERO),
                node(Some(0), Vec3::X),
                node(None, Vec3::Y),
            ],
            clips: vec![clip],
            parts: vec![part(Binding::Node(2))],
            ..Rig::default()
        };
        rig.settle();
        assert!(!rig.moves(0));
        rig.parts.push(part(Binding::Node(1)));
        rig.settle();
        assert!(rig.moves(0));
        assert!(!rig.moves(1));
    }
}
