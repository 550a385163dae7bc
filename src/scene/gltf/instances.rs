//! `EXT_mesh_gpu_instancing`: a node drawing its mesh many times, each
//! instance a translation, rotation and scale (accessors of one element an
//! instance) applied before the node's own transform.

use ::gltf::accessor::{DataType, Dimensions};
use glam::{Mat4, Quat, Vec3};

use super::accessor;
use super::buffers::Buffer;

/// The extension's name.
pub(super) const EXTENSION: &str = "EXT_mesh_gpu_instancing";

/// The accessors of the instances' `TRANSLATION`, `ROTATION` and `SCALE`,
/// where `node` has the extension.
fn attributes(node: &::gltf::Node) -> Option<[Option<usize>; 3]> {
    let attributes = node.extension_value(EXTENSION)?.get("attributes")?;
    let index = |name: &str| {
        attributes
            .get(name)
            .and_then(serde_json::Value::as_u64)
            .map(|i| i as usize)
    };
    Some([index("TRANSLATION"), index("ROTATION"), index("SCALE")])
}

/// How many instances `node` draws (1 without the extension), from its
/// accessors' counts, for the triangle budget.
pub(super) fn count(node: &::gltf::Node, document: &::gltf::Document) -> u128 {
    let Some(attributes) = attributes(node) else {
        return 1;
    };
    (attributes.iter().flatten())
        .filter_map(|&i| document.accessors().nth(i))
        .map(|a| a.count() as u128)
        .max()
        .unwrap_or(1)
}

/// Each instance's transform in the node's space (one identity without the
/// extension); an error names an accessor that is missing, of a type the
/// extension does not allow, or of another count than the others.
pub(super) fn of(
    node: &::gltf::Node,
    document: &::gltf::Document,
    buffers: &[Buffer],
    budget: u64,
) -> Result<Vec<Mat4>, String> {
    let Some([t, r, s]) = attributes(node) else {
        return Ok(vec![Mat4::IDENTITY]);
    };
    let read = |index: Option<usize>, what: &str, types: &[DataType], dims: Dimensions| {
        let Some(i) = index else {
            return Ok(None);
        };
        let acc = document.accessors().nth(i).ok_or_else(|| {
            format!("{EXTENSION}'s {what} names accessor {i}, which does not exist")
        })?;
        let at = format!("{EXTENSION}'s {what}");
        accessor::floats(&acc, buffers, types, &[dims], &at, budget).map(Some)
    };
    let t = read(t, "TRANSLATION", &accessor::QUANTIZED, Dimensions::Vec3)?;
    let r = read(r, "ROTATION", &accessor::SIGNED, Dimensions::Vec4)?;
    let s = read(s, "SCALE", &accessor::QUANTIZED, Dimensions::Vec3)?;
    let counts = [(&t, 3), (&r, 4), (&s, 3)].map(|(a, w)| a.as_ref().map(|v| v.len() / w));
    let n = counts.iter().flatten().copied().max().unwrap_or(0);
    if counts.iter().flatten().any(|&c| c != n) {
        return Err(format!(
            "{EXTENSION}: its attributes have {} elements, not one count",
            counts
                .iter()
                .flatten()
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    if n == 0 {
        return Ok(vec![Mat4::IDENTITY]);
    }
    Ok((0..n)
        .map(|i| {
            let t = t
                .as_ref()
                .map_or(Vec3::ZERO, |v| Vec3::from_slice(&v[3 * i..]));
            let r = r.as_ref().map_or(Quat::IDENTITY, |v| {
                let q = Quat::from_slice(&v[4 * i..]);
                // A zero quaternion is no rotation, as for a node's.
                if q.length_squared() > 0.0 {
                    q.normalize()
                } else {
                    Quat::IDENTITY
                }
            });
            let s = s
                .as_ref()
                .map_or(Vec3::ONE, |v| Vec3::from_slice(&v[3 * i..]));
            Mat4::from_scale_rotation_translation(s, r, t)
        })
        .collect())
}
