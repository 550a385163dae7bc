//! `EXT_meshopt_compression` (gltfpack's output): buffer views whose bytes
//! are meshoptimizer's vertex or index codec, decoded by the
//! `meshoptimizer-rs` crate (a port of the reference decoders without
//! `unsafe` in its codecs, each decode held to a byte limit).
//!
//! Trade-offs. Decoding happens once, before anything reads the views:
//! each compressed view is pointed at a buffer of its own, which holds its
//! decoded bytes, so the accessor reader, the indices, skins and clips
//! read them as any other view's. The decoded sizes (count × stride) are
//! what the file declares: their sum is held to the load's byte budget
//! before a byte is decoded. A fallback buffer (the uncompressed copy the
//! extension lets a file leave out) is not read.

use ::gltf::json;
use meshoptimizer_rs::codec::{Filter, Mode};

use super::buffers::Buffer;

/// The extension's name.
pub(super) const EXTENSION: &str = "EXT_meshopt_compression";

/// One compressed view: where its stream is, how to decode it, and the
/// buffer its decoded bytes go to.
pub(super) struct Compressed {
    view: usize,
    buffer: usize,
    offset: usize,
    length: usize,
    count: usize,
    stride: usize,
    mode: Mode,
    filter: Filter,
    into: usize,
}

/// What [`rewrite`] found: the compressed views and the buffers not to be
/// read (fallbacks, and the decoded views' own, filled by [`decode`]).
#[derive(Default)]
pub(super) struct Plan {
    pub(super) views: Vec<Compressed>,
    pub(super) unread: Vec<usize>,
}

/// Points each compressed view of `root` at a new buffer of its decoded
/// size, as glTF would have it uncompressed; the views' decoded bytes
/// held to `budget` in all.
pub(super) fn rewrite(root: &mut json::Root, budget: u64) -> Result<Plan, String> {
    let mut plan = Plan::default();
    for (b, buffer) in root.buffers.iter().enumerate() {
        let ext = buffer
            .extensions
            .as_ref()
            .and_then(|e| e.others.get(EXTENSION));
        if ext
            .and_then(|e| e.get("fallback"))
            .and_then(|f| f.as_bool())
            == Some(true)
        {
            plan.unread.push(b);
        }
    }
    let mut total = 0u64;
    for (v, view) in root.buffer_views.iter().enumerate() {
        let Some(ext) = view
            .extensions
            .as_ref()
            .and_then(|e| e.others.get(EXTENSION))
        else {
            continue;
        };
        let at = |what: &str| format!("buffer view {v}: its {EXTENSION} {what}");
        let number = |key: &str| {
            (ext.get(key).and_then(|n| n.as_u64()))
                .and_then(|n| usize::try_from(n).ok())
                .ok_or_else(|| at(&format!("has no {key}")))
        };
        let mode = match ext.get("mode").and_then(|m| m.as_str()) {
            Some("ATTRIBUTES") => Mode::Attributes,
            Some("TRIANGLES") => Mode::Triangles,
            Some("INDICES") => Mode::Indices,
            _ => return Err(at("mode is not ATTRIBUTES, TRIANGLES or INDICES")),
        };
        let filter = match ext.get("filter").and_then(|m| m.as_str()) {
            None | Some("NONE") => Filter::None,
            Some("OCTAHEDRAL") => Filter::Octahedral,
            Some("QUATERNION") => Filter::Quaternion,
            Some("EXPONENTIAL") => Filter::Exponential,
            Some(_) => return Err(at("filter is not one of the four")),
        };
        let (count, stride) = (number("count")?, number("byteStride")?);
        let bytes = (count as u64).saturating_mul(stride as u64);
        total = total.saturating_add(bytes);
        if total > budget {
            return Err(format!(
                "its compressed buffer views decode to more than the budget of {budget} bytes (--max-bytes raises it)"
            ));
        }
        plan.views.push(Compressed {
            view: v,
            buffer: number("buffer")?,
            offset: ext
                .get("byteOffset")
                .map_or(Ok(0), |_| number("byteOffset"))?,
            length: number("byteLength")?,
            count,
            stride,
            mode,
            filter,
            into: root.buffers.len() + plan.views.len(),
        });
    }
    for c in &plan.views {
        let view = &mut root.buffer_views[c.view];
        let bytes = (c.count * c.stride) as u64;
        view.buffer = json::Index::new(c.into as u32);
        view.byte_offset = Some(json::validation::USize64(0));
        view.byte_length = json::validation::USize64(bytes);
        plan.unread.push(c.into);
    }
    for c in &plan.views {
        root.buffers.push(json::Buffer {
            byte_length: json::validation::USize64((c.count * c.stride) as u64),
            name: None,
            uri: None,
            extensions: None,
            extras: Default::default(),
        });
    }
    Ok(plan)
}

/// Decodes `plan`'s views from `buffers` into the buffers [`rewrite`] made
/// for them.
pub(super) fn decode(plan: &Plan, buffers: &mut [Buffer]) -> Result<(), String> {
    for c in &plan.views {
        let at = |what: String| format!("buffer view {}: {what}", c.view);
        let source = (buffers.get(c.buffer))
            .and_then(|b| b.get(c.offset..)?.get(..c.length))
            .ok_or_else(|| {
                at(format!(
                    "its {EXTENSION} stream is outside buffer {}",
                    c.buffer
                ))
            })?;
        let limits = meshoptimizer_rs::Limits {
            max_bytes: (c.count.saturating_mul(c.stride))
                .saturating_mul(2)
                .max(1 << 16),
            ..Default::default()
        };
        let mut workspace = meshoptimizer_rs::Workspace::new(limits);
        let decoded = meshoptimizer_rs::codec::decode_buffer_view(
            c.mode,
            c.filter,
            c.count,
            c.stride,
            source,
            &mut workspace,
        )
        .map_err(|e| at(format!("its {EXTENSION} stream could not be decoded: {e}")))?;
        let slot = buffers
            .get_mut(c.into)
            .ok_or_else(|| at("has no buffer".into()))?;
        *slot = super::buffers::padded(decoded);
    }
    Ok(())
}
