//! What a scene's node tree places, counted before anything is read, for
//! the triangle budget: a node counted as often as it is placed (and its
//! mesh once an instance), without walking a tree that places 2^60 nodes.

use ::gltf::mesh::Mode;

use super::{instances, positions_count};

/// A count for a message: exact up to 2^64, a power of two beyond.
pub(super) fn shown(n: u128) -> String {
    if n <= u128::from(u64::MAX) {
        n.to_string()
    } else {
        format!("about 2^{}", 127 - n.leading_zeros())
    }
}

/// How many nodes the scene places and how many triangles they draw, a
/// node counted as often as it is placed: a node's counts are found once
/// and reused wherever it appears (a graph of 60 nodes each holding the
/// next twice places 2^60 nodes, and is counted in 60 steps, not walked).
/// A node that holds itself, directly or not, is an error.
pub(super) fn placed(
    document: &::gltf::Document,
    scene: &::gltf::Scene,
) -> std::result::Result<(u128, u128), String> {
    let meshes: Vec<u128> = document
        .meshes()
        .map(|m| m.primitives().map(|p| triangles_of(&p)).sum())
        .collect();
    let nodes: Vec<::gltf::Node> = document.nodes().collect();
    // Per node: None unvisited, Some(None) in progress, Some(Some(counts)).
    let mut counts: Vec<Option<Option<(u128, u128)>>> = vec![None; nodes.len()];
    let mut total = (0u128, 0u128);
    for root in scene.nodes() {
        // Post-order without recursion: (node, children pushed?).
        let mut stack = vec![(root.index(), false)];
        while let Some((i, expanded)) = stack.pop() {
            if expanded {
                let own = nodes[i]
                    .mesh()
                    .map_or(0, |m| meshes[m.index()])
                    .saturating_mul(instances::count(&nodes[i], document));
                let mut c = (1u128, own);
                for child in nodes[i].children() {
                    let (n, t) = counts[child.index()].flatten().unwrap_or_default();
                    c = (c.0.saturating_add(n), c.1.saturating_add(t));
                }
                counts[i] = Some(Some(c));
                continue;
            }
            match counts[i] {
                Some(Some(_)) => continue,
                Some(None) => return Err(format!("node {i} holds itself (a cycle)")),
                None => {}
            }
            counts[i] = Some(None);
            stack.push((i, true));
            for child in nodes[i].children() {
                match counts[child.index()] {
                    Some(None) => {
                        return Err(format!("node {} holds itself (a cycle)", child.index()));
                    }
                    Some(Some(_)) => {}
                    None => stack.push((child.index(), false)),
                }
            }
        }
        let (n, t) = counts[root.index()].flatten().unwrap_or_default();
        total = (total.0.saturating_add(n), total.1.saturating_add(t));
    }
    Ok(total)
}

/// The triangles a primitive draws (0 for points and lines).
fn triangles_of(p: &::gltf::Primitive) -> u128 {
    let n = p
        .indices()
        .map_or_else(|| positions_count(p), |i| i.count()) as u128;
    match p.mode() {
        Mode::Triangles => n / 3,
        Mode::TriangleStrip | Mode::TriangleFan => n.saturating_sub(2),
        _ => 0,
    }
}
