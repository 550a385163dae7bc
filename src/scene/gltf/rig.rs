//! A glTF model's nodes, skins, morph targets and animations, read into a
//! [`Rig`] (see [`crate::scene::anim`]).
//!
//! Every accessor is checked (type, and every byte inside its buffer) before
//! it is read, as the mesh's are. A skin's joints must be nodes of the
//! scene drawn; a channel whose node is not is left out and said in a note.
//! The data kept (each placed part's vertices in its mesh's space, their
//! joints and weights, the morph targets' offsets, the keyframes) is
//! counted against the loading budget of bytes, since a node tree can
//! place one mesh many times.

use super::accessor::floats;
use super::buffers::Buffer;
use ::gltf::accessor::{DataType, Dimensions};
use ::gltf::animation::{Interpolation as GltfInterpolation, Property as GltfProperty};
use glam::{Mat4, Quat, Vec3};
use rustc_hash::FxHashMap;

use super::buffers::check;
use crate::scene::anim::{
    Binding, Channel, Clip, Interpolation, MAX_TARGETS, Morph, Node, Part, Property, Rig, Sampler,
    Skin, Trs,
};

/// The rig as the node tree is walked: nodes in the order met (parents
/// first), parts as primitives are placed, and the bytes kept so far.
#[derive(Default)]
pub(super) struct RigParts {
    pub(super) rig: Rig,
    /// The rig's index of each glTF node met.
    pub(super) index: FxHashMap<usize, u32>,
    /// Bytes of animation data kept, against `budget`.
    kept: u64,
    budget: u64,
}

/// Where a primitive is placed: the rig's node and the glTF skin it uses.
#[derive(Clone, Copy)]
pub(super) struct Placement {
    pub(super) node: u32,
    pub(super) skin: Option<usize>,
}

impl RigParts {
    /// An empty rig that may keep `budget` bytes.
    pub(super) fn new(budget: u64) -> RigParts {
        RigParts {
            budget,
            ..RigParts::default()
        }
    }

    fn keep(&mut self, bytes: u64) -> Result<(), String> {
        self.kept = self.kept.saturating_add(bytes);
        if self.kept > self.budget {
            return Err(format!(
                "its animation data (vertices as placed, joints, morph targets, keyframes) needs more than the budget of {} bytes (--max-file-size raises it)",
                self.budget
            ));
        }
        Ok(())
    }

    /// Adds glTF node `node` below the rig's node `parent`; returns its
    /// index in the rig.
    pub(super) fn node(&mut self, node: &::gltf::Node, parent: Option<u32>) -> u32 {
        let rest = match node.transform() {
            ::gltf::scene::Transform::Matrix { matrix } => Err(Mat4::from_cols_array_2d(&matrix)),
            ::gltf::scene::Transform::Decomposed {
                translation,
                rotation,
                scale,
            } => Ok(Trs {
                translation: Vec3::from(translation),
                // Four zeros are no rotation (noted where the node is read).
                rotation: if rotation == [0.0; 4] {
                    Quat::IDENTITY
                } else {
                    Quat::from_array(rotation).normalize()
                },
                scale: Vec3::from(scale),
            }),
        };
        let weights = node
            .weights()
            .or_else(|| node.mesh().and_then(|m| m.weights()))
            .map(<[f32]>::to_vec)
            .unwrap_or_else(|| {
                let targets = node.mesh().map_or(0, |m| {
                    m.primitives()
                        .map(|p| p.morph_targets().len())
                        .max()
                        .unwrap_or(0)
                });
                vec![0.0; targets]
            });
        let i = self.rig.nodes.len() as u32;
        self.rig.nodes.push(Node {
            parent,
            rest,
            weights,
            source: u32::try_from(node.index()).ok(),
        });
        self.index.insert(node.index(), i);
        i
    }

    /// The part of a primitive whose vertices, in its mesh's space, are
    /// `positions` and `normals` (read already), starting at the
    /// geometry's vertex `first`.
    pub(super) fn part(
        &mut self,
        prim: &::gltf::Primitive,
        place: Placement,
        (buffers, draco): (&[Buffer], Option<&super::draco::Decoded>),
        (first, positions, normals): (u32, Vec<Vec3>, Vec<Vec3>),
        document: &::gltf::Document,
    ) -> Result<(), String> {
        let n = positions.len();
        self.keep(24 * n as u64)?;
        let reader = prim.reader(|b| buffers.get(b.index()).map(|d| &d[..]));
        let binding = match place.skin {
            Some(s) => {
                let joints = document
                    .skins()
                    .nth(s)
                    .map_or(0, |skin| skin.joints().len());
                let mut starts = Vec::with_capacity(n + 1);
                let mut per_vertex: Vec<Vec<(u16, f32)>> = vec![Vec::new(); n];
                let mut set = 0;
                while let (Some(j), Some(w)) = (
                    prim.get(&::gltf::Semantic::Joints(set)),
                    prim.get(&::gltf::Semantic::Weights(set)),
                ) {
                    let name = |what: &str| format!("{what}_{set}");
                    let packed =
                        draco.and_then(|d| d.get(&name("JOINTS")).zip(d.get(&name("WEIGHTS"))));
                    if packed.is_none() {
                        check(
                            &j,
                            buffers,
                            &[DataType::U8, DataType::U16],
                            &[Dimensions::Vec4],
                            &name("JOINTS"),
                        )?;
                        check(
                            &w,
                            buffers,
                            &[DataType::F32, DataType::U8, DataType::U16],
                            &[Dimensions::Vec4],
                            &name("WEIGHTS"),
                        )?;
                    }
                    if j.count() != n || w.count() != n {
                        return Err(format!(
                            "{} and {} have {} and {} entries for {n} positions",
                            name("JOINTS"),
                            name("WEIGHTS"),
                            j.count(),
                            w.count()
                        ));
                    }
                    let (js, ws): (Vec<[u16; 4]>, Vec<[f32; 4]>) = match packed {
                        // A Draco stream's, four a vertex (joints whole
                        // numbers of 16 bits).
                        Some(((js, 4), (ws, 4))) => {
                            let joint = |x: f32| {
                                (x >= 0.0 && x <= f32::from(u16::MAX) && x.fract() == 0.0)
                                    .then_some(x as u16)
                            };
                            let js = js.chunks_exact(4).map(|j| {
                                let [a, b, c, d] = [j[0], j[1], j[2], j[3]].map(joint);
                                Some([a?, b?, c?, d?])
                            });
                            let js: Option<Vec<[u16; 4]>> = js.collect();
                            let js = js.ok_or("its Draco JOINTS are not joint numbers")?;
                            let ws = ws
                                .chunks_exact(4)
                                .map(|w| [w[0], w[1], w[2], w[3]])
                                .collect();
                            (js, ws)
                        }
                        Some(_) => return Err("its Draco JOINTS or WEIGHTS are not of four".into()),
                        None => {
                            let js = reader.read_joints(set).ok_or("JOINTS could not be read")?;
                            let ws = reader
                                .read_weights(set)
                                .ok_or("WEIGHTS could not be read")?;
                            (js.into_u16().collect(), ws.into_f32().collect())
                        }
                    };
                    if js.len() != n || ws.len() != n {
                        return Err(format!("{} could not be read", name("JOINTS")));
                    }
                    for ((v, j), w) in per_vertex.iter_mut().zip(js).zip(ws) {
                        for k in 0..4 {
                            if !(w[k].is_finite() && w[k] >= 0.0) {
                                return Err(format!(
                                    "{} holds a weight that is not a finite number of 0 or more",
                                    name("WEIGHTS")
                                ));
                            }
                            if w[k] > 0.0 {
                                if usize::from(j[k]) >= joints {
                                    return Err(format!(
                                        "{} names joint {} of a skin of {joints}",
                                        name("JOINTS"),
                                        j[k]
                                    ));
                                }
                                v.push((j[k], w[k]));
                            }
                        }
                    }
                    set += 1;
                }
                if set == 0 {
                    return Err("it is skinned but has no JOINTS_0 and WEIGHTS_0".into());
                }
                let mut influences = Vec::new();
                for v in per_vertex {
                    starts.push(influences.len() as u32);
                    // Normalised, as the format allows weights that sum
                    // to nearly one; in f64, where weights near f32's
                    // largest do not sum to infinity.
                    let sum: f64 = v.iter().map(|&(_, w)| f64::from(w)).sum();
                    influences.extend(v.into_iter().map(|(j, w)| (j, (f64::from(w) / sum) as f32)));
                }
                starts.push(influences.len() as u32);
                self.keep(8 * influences.len() as u64 + 4 * starts.len() as u64)?;
                Binding::Skin {
                    skin: s as u32,
                    starts,
                    influences,
                    node: place.node,
                }
            }
            None => Binding::Node(place.node),
        };
        let targets = prim.morph_targets().len();
        let morph = if targets == 0 {
            None
        } else {
            if targets > MAX_TARGETS {
                return Err(format!(
                    "it has {targets} morph targets, more than the {MAX_TARGETS} read"
                ));
            }
            self.keep(24 * (n * targets) as u64)?;
            let mut offsets = vec![Vec3::ZERO; n * targets];
            let mut normal_offsets = Some(vec![Vec3::ZERO; n * targets]);
            const SIGNED: [DataType; 3] = [DataType::F32, DataType::I8, DataType::I16];
            for (k, t) in prim.morph_targets().enumerate() {
                let what = |a: &str| format!("morph target {k}'s {a}");
                for (acc, a, into) in [
                    (t.positions(), "POSITION", Some(&mut offsets)),
                    (t.normals(), "NORMAL", normal_offsets.as_mut()),
                ] {
                    let Some(acc) = acc else { continue };
                    if acc.count() != n {
                        return Err(format!(
                            "{} has {} entries for {n} positions",
                            what(a),
                            acc.count()
                        ));
                    }
                    let fs = floats(
                        &acc,
                        buffers,
                        &SIGNED,
                        &[Dimensions::Vec3],
                        &what(a),
                        self.budget,
                    )?;
                    if let Some(all) = into {
                        for (v, d) in fs.chunks_exact(3).enumerate() {
                            all[k * n + v] = Vec3::from_slice(d);
                        }
                    }
                }
                if t.normals().is_none() {
                    normal_offsets = None;
                }
            }
            if !offsets.iter().all(|d| d.is_finite()) {
                return Err("a morph target's offset is not a finite number".into());
            }
            Some(Morph {
                node: place.node,
                positions: offsets,
                normals: normal_offsets,
            })
        };
        self.rig.parts.push(Part {
            first,
            positions,
            normals,
            binding,
            morph,
        });
        Ok(())
    }

    /// The document's skins and animations, read once the tree is walked;
    /// notes what could not be drawn into `notes`.
    pub(super) fn finish(
        mut self,
        document: &::gltf::Document,
        buffers: &[Buffer],
        notes: &mut Vec<String>,
    ) -> Result<Rig, String> {
        for skin in document.skins() {
            let joints = skin
                .joints()
                .map(|j| {
                    self.index.get(&j.index()).copied().ok_or_else(|| {
                        format!(
                            "skin {}'s joint, node {}, is not in the scene drawn",
                            skin.index(),
                            j.index()
                        )
                    })
                })
                .collect::<Result<Vec<u32>, String>>()?;
            let inverse_bind = match skin.inverse_bind_matrices() {
                Some(acc) => {
                    let what = format!("skin {}'s inverse bind matrices", skin.index());
                    check(&acc, buffers, &[DataType::F32], &[Dimensions::Mat4], &what)?;
                    if acc.count() < joints.len() {
                        return Err(format!(
                            "{what} are {} for {} joints",
                            acc.count(),
                            joints.len()
                        ));
                    }
                    let reader = skin.reader(|b| buffers.get(b.index()).map(|d| &d[..]));
                    let ms: Vec<Mat4> = reader
                        .read_inverse_bind_matrices()
                        .ok_or(format!("{what} could not be read"))?
                        .map(|m| Mat4::from_cols_array_2d(&m))
                        .take(joints.len())
                        .collect();
                    if !ms.iter().all(|m| m.is_finite()) {
                        return Err(format!("{what} hold a number that is not finite"));
                    }
                    ms
                }
                None => vec![Mat4::IDENTITY; joints.len()],
            };
            self.keep(68 * joints.len() as u64)?;
            self.rig.skins.push(Skin {
                joints,
                inverse_bind,
            });
        }
        let mut left_out = 0;
        let mut zero_rotations = 0;
        for anim in document.animations() {
            let name = anim.name().unwrap_or("");
            let label = if name.is_empty() {
                format!("animation {}", anim.index())
            } else {
                format!(
                    "animation {} ({})",
                    anim.index(),
                    crate::text::name(name, 40)
                )
            };
            // The crate's validation checks neither a channel's node nor its
            // path, and its accessors unwrap them: checked here.
            let json = &document.as_json().animations[anim.index()];
            for (c, ch) in json.channels.iter().enumerate() {
                if ch.target.node.value() >= document.nodes().len() {
                    return Err(format!(
                        "{label} channel {c} targets node {}, which does not exist",
                        ch.target.node.value()
                    ));
                }
                if !matches!(ch.target.path, ::gltf::json::validation::Checked::Valid(_)) {
                    return Err(format!(
                        "{label} channel {c} animates a property rastty does not know (not translation, rotation, scale or weights)"
                    ));
                }
            }
            let mut channels = Vec::new();
            for ch in anim.channels() {
                let target = ch.target();
                let Some(&node) = self.index.get(&target.node().index()) else {
                    left_out += 1;
                    continue;
                };
                let sampler = ch.sampler();
                let at = format!("{label} sampler {}", sampler.index());
                let property = match target.property() {
                    GltfProperty::Translation => Property::Translation,
                    GltfProperty::Rotation => Property::Rotation,
                    GltfProperty::Scale => Property::Scale,
                    GltfProperty::MorphTargetWeights => Property::Weights,
                };
                let interpolation = match sampler.interpolation() {
                    GltfInterpolation::Step => Interpolation::Step,
                    GltfInterpolation::Linear => Interpolation::Linear,
                    GltfInterpolation::CubicSpline => Interpolation::CubicSpline,
                };
                let (input, output) = (sampler.input(), sampler.output());
                check(
                    &input,
                    buffers,
                    &[DataType::F32],
                    &[Dimensions::Scalar],
                    &format!("{at}'s input"),
                )?;
                let (types, dims): (&[DataType], &[Dimensions]) = match property {
                    Property::Translation | Property::Scale => {
                        (&[DataType::F32], &[Dimensions::Vec3])
                    }
                    Property::Rotation => (
                        &[
                            DataType::F32,
                            DataType::I8,
                            DataType::U8,
                            DataType::I16,
                            DataType::U16,
                        ],
                        &[Dimensions::Vec4],
                    ),
                    Property::Weights => (
                        &[
                            DataType::F32,
                            DataType::I8,
                            DataType::U8,
                            DataType::I16,
                            DataType::U16,
                        ],
                        &[Dimensions::Scalar],
                    ),
                };
                let mut values = floats(
                    &output,
                    buffers,
                    types,
                    dims,
                    &format!("{at}'s output"),
                    self.budget,
                )?;
                let reader = ch.reader(|b| buffers.get(b.index()).map(|d| &d[..]));
                let times: Vec<f64> = reader
                    .read_inputs()
                    .ok_or(format!("{at}'s input could not be read"))?
                    .map(f64::from)
                    .collect();
                if property == Property::Rotation {
                    // A key of four zeros is no rotation at all: taken as
                    // none (the identity), and said.
                    let (stride, at) = if interpolation == Interpolation::CubicSpline {
                        (12, 4)
                    } else {
                        (4, 0)
                    };
                    for key in values.chunks_exact_mut(stride) {
                        let q = &mut key[at..at + 4];
                        if q.iter().all(|&x| x == 0.0) {
                            q[3] = 1.0;
                            zero_rotations += 1;
                        }
                    }
                }
                self.keep(8 * times.len() as u64 + 4 * values.len() as u64)?;
                let width = match property {
                    Property::Translation | Property::Scale => 3,
                    Property::Rotation => 4,
                    Property::Weights => {
                        let targets = self.rig.nodes[node as usize].weights.len();
                        if targets == 0 {
                            return Err(format!(
                                "{at} animates the morph weights of a node whose mesh has no targets"
                            ));
                        }
                        targets
                    }
                };
                let sampler = Sampler::new(times, values, width, interpolation)
                    .map_err(|e| format!("{at}: {e}"))?;
                channels.push(Channel {
                    node,
                    property,
                    sampler,
                });
            }
            let length = channels.iter().map(|c| c.sampler.end()).fold(0.0, f64::max);
            self.rig.clips.push(Clip {
                name: name.to_string(),
                channels,
                length,
                moves: Vec::new(),
            });
        }
        if left_out > 0 {
            notes.push(format!(
                "{left_out} animation channels move nodes outside the scene drawn: left out"
            ));
        }
        if zero_rotations > 0 {
            notes.push(format!(
                "{zero_rotations} rotation keys of animations are four zeros, which is no rotation: taken as none"
            ));
        }
        self.rig.settle();
        Ok(self.rig)
    }
}

/// Smooth normals of a part without them: each vertex's the sum of its
/// faces' (area-weighted) normals, normalised; `faces` index `positions`.
pub(super) fn smooth_normals(positions: &[Vec3], faces: &[[u32; 3]], flip: bool) -> Vec<Vec3> {
    let mut sum = vec![Vec3::ZERO; positions.len()];
    for f in faces {
        let [a, b, c] = f.map(|i| positions[i as usize]);
        let n = (b - a).cross(c - a);
        for &i in f {
            sum[i as usize] += n;
        }
    }
    sum.iter()
        .map(|n| {
            let n = n.normalize_or_zero();
            if flip { -n } else { n }
        })
        .collect()
}

/// A node's transform in its parent's space. A rotation of four zeros is
/// no rotation at all (the matrix would flatten the node to a point): it
/// is taken as none, and the node's index added to `unrotated`.
pub(super) fn local(node: &::gltf::Node, unrotated: &mut Vec<usize>) -> Mat4 {
    let transform = match node.transform() {
        ::gltf::scene::Transform::Decomposed {
            translation,
            rotation: [0.0, 0.0, 0.0, 0.0],
            scale,
        } => {
            unrotated.push(node.index());
            ::gltf::scene::Transform::Decomposed {
                translation,
                rotation: [0.0, 0.0, 0.0, 1.0],
                scale,
            }
        }
        t => t,
    };
    Mat4::from_cols_array_2d(&transform.matrix())
}
