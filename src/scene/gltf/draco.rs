//! `KHR_draco_mesh_compression`: a primitive whose attributes and indices
//! are one Draco stream in a buffer view, decoded by the `draco-core`
//! crate (a pure-Rust port of Google's decoder: no C++ to build for each
//! target, and fuzzed by its authors and here).
//!
//! Trade-offs. The stream's own face and point counts are read from its
//! header before it is decoded, and must be no more than the glTF
//! accessors declare (which the model's budget has already counted): a
//! stream cannot make the decoder allocate past what the file said. Its
//! attributes are matched to glTF's by the extension's unique ids and
//! converted to floats as the accessors' types say (normalized integers
//! scaled). A stream whose counts differ from its accessors' is refused,
//! never drawn as another mesh.

use ::gltf::Primitive;

use super::buffers::Buffer;

/// The extension's name.
pub(super) const EXTENSION: &str = "KHR_draco_mesh_compression";

/// A primitive's decoded Draco stream.
pub(super) struct Decoded {
    /// Each glTF attribute the extension names (`POSITION`, …): its
    /// values as floats, point by point, and its components a point.
    attributes: Vec<(String, Vec<f32>, usize)>,
    /// Three a triangle.
    pub(super) indices: Vec<u32>,
}

impl Decoded {
    /// Attribute `name`'s floats and components a point, if the stream
    /// has it.
    pub(super) fn get(&self, name: &str) -> Option<(&[f32], usize)> {
        (self.attributes.iter())
            .find(|(n, ..)| n == name)
            .map(|(_, v, k)| (&v[..], *k))
    }
}

/// `prim`'s Draco stream decoded, or `None` for a primitive without one.
pub(super) fn decode(
    prim: &Primitive,
    document: &::gltf::Document,
    buffers: &[Buffer],
) -> Result<Option<Decoded>, String> {
    let Some(ext) = prim.extension_value(EXTENSION) else {
        return Ok(None);
    };
    let at = |what: &str| format!("its {EXTENSION} {what}");
    let view = (ext.get("bufferView").and_then(|v| v.as_u64()))
        .and_then(|i| document.views().nth(i as usize))
        .ok_or_else(|| at("names no buffer view"))?;
    let buffer = (buffers.get(view.buffer().index())).ok_or_else(|| at("buffer is missing"))?;
    let bytes = (buffer.get(view.offset()..))
        .and_then(|b| b.get(..view.length()))
        .ok_or_else(|| at("buffer view is outside its buffer"))?;
    let points = prim
        .get(&::gltf::Semantic::Positions)
        .map_or(0, |a| a.count());
    let indices = prim
        .indices()
        .ok_or_else(|| at("primitive has no indices accessor"))?;
    let faces = indices.count() / 3;
    // The stream's counts, before a byte of it is decoded.
    let (stream_faces, stream_points) =
        counts(bytes).ok_or("its Draco stream's header could not be read")?;
    if stream_faces > faces as u64 || stream_points > (3 * faces).max(points) as u64 {
        return Err(format!(
            "its Draco stream says {stream_faces} faces and {stream_points} points, more than its accessors' {faces} and {points}"
        ));
    }
    let mut mesh = draco_core::Mesh::new();
    let mut input = draco_core::DecoderBuffer::new(bytes);
    draco_core::MeshDecoder::new()
        .decode(&mut input, &mut mesh)
        .map_err(|e| format!("its Draco stream could not be decoded: {e}"))?;
    if mesh.num_faces() != faces || mesh.num_points() != points {
        return Err(format!(
            "its Draco stream has {} faces and {} points, its accessors {faces} and {points}",
            mesh.num_faces(),
            mesh.num_points()
        ));
    }
    let names = (ext.get("attributes").and_then(|a| a.as_object()))
        .ok_or_else(|| at("names no attributes"))?;
    let mut attributes = Vec::new();
    for (name, id) in names {
        let id = id.as_u64().and_then(|i| u32::try_from(i).ok());
        let attribute = id
            .and_then(|id| mesh.attribute_by_unique_id(id))
            .ok_or_else(|| format!("its Draco stream has no attribute {name} names"))?;
        let normalized = (prim.attributes())
            .find(|(s, _)| s.to_string() == *name)
            .is_some_and(|(_, a)| a.normalized());
        let (values, k) = floats(attribute, points, normalized)
            .ok_or_else(|| format!("its Draco attribute {name} could not be read"))?;
        attributes.push((name.clone(), values, k));
    }
    let indices: Vec<u32> = (0..faces)
        .flat_map(|f| mesh.face(draco_core::FaceIndex(f as u32)))
        .map(|p| p.0)
        .collect();
    if let Some(bad) = indices.iter().find(|&&i| i as usize >= points) {
        return Err(format!("its Draco stream names point {bad} of {points}"));
    }
    Ok(Some(Decoded {
        attributes,
        indices,
    }))
}

/// A decoded attribute's values for points `0..points` as floats (integers
/// scaled to [0, 1] or [−1, 1] where `normalized`), and its components.
fn floats(
    a: &draco_core::PointAttribute,
    points: usize,
    normalized: bool,
) -> Option<(Vec<f32>, usize)> {
    use draco_core::DataType as T;
    let k = usize::from(a.num_components());
    let (size, scale) = match a.data_type() {
        T::Float32 => (4, 1.0),
        T::Int8 => (1, 127.0),
        T::Uint8 => (1, 255.0),
        T::Int16 => (2, 32767.0),
        T::Uint16 => (2, 65535.0),
        T::Uint32 => (4, u32::MAX as f32),
        T::Int32 => (4, i32::MAX as f32),
        _ => return None,
    };
    let stride = usize::try_from(a.byte_stride()).ok()?;
    if k == 0 || k > 4 || stride < k * size {
        return None;
    }
    let data = a.buffer().data();
    let mut out = Vec::with_capacity(points * k);
    for p in 0..points {
        let at = a.mapped_index(draco_core::PointIndex(p as u32)).0 as usize;
        let bytes = data.get(at.checked_mul(stride)?..)?.get(..k * size)?;
        for c in bytes.chunks_exact(size) {
            let v = match a.data_type() {
                T::Float32 => f32::from_le_bytes(c.try_into().ok()?),
                T::Int8 => f32::from(c[0] as i8),
                T::Uint8 => f32::from(c[0]),
                T::Int16 => f32::from(i16::from_le_bytes(c.try_into().ok()?)),
                T::Uint16 => f32::from(u16::from_le_bytes(c.try_into().ok()?)),
                T::Int32 => i32::from_le_bytes(c.try_into().ok()?) as f32,
                _ => u32::from_le_bytes(c.try_into().ok()?) as f32,
            };
            let v = if normalized && scale != 1.0 {
                (v / scale).max(-1.0)
            } else {
                v
            };
            out.push(v);
        }
    }
    Some((out, k))
}

/// A Draco mesh stream's face and point counts, from its header (Draco's
/// bitstream 1.x and 2.x; see the format's specification): `None` where
/// the header is not one of a triangle mesh or is cut short, or carries
/// metadata (which comes before the counts and is not read here). For
/// an Edgebreaker stream the points are at most three a face.
fn counts(b: &[u8]) -> Option<(u64, u64)> {
    let mut r = Reader { b, at: 0 };
    if r.take(5)? != b"DRACO" {
        return None;
    }
    let (major, minor) = (r.u8()?, r.u8()?);
    let version = u16::from(major) << 8 | u16::from(minor);
    let (kind, method) = (r.u8()?, r.u8()?);
    if kind != 1 {
        return None;
    }
    // The flags; metadata comes before the counts.
    if r.u16()? & 0x8000 != 0 {
        return None;
    }
    // Counts are u32s before 2.0 (2.2 for a sequential mesh), then
    // varints.
    match method {
        0 => {
            let varint = version >= 0x0202;
            Some((r.count(varint)?, r.count(varint)?))
        }
        1 => {
            let varint = version >= 0x0200;
            // The traversal's kind; before 2.2, the new vertices; the
            // encoded vertices.
            r.u8()?;
            if version < 0x0202 {
                r.count(varint)?;
            }
            r.count(varint)?;
            let faces = r.count(varint)?;
            Some((faces, faces.saturating_mul(3)))
        }
        _ => None,
    }
}

/// Little-endian numbers from a byte slice.
struct Reader<'a> {
    b: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn take(&mut self, n: usize) -> Option<&[u8]> {
        let s = self.b.get(self.at..self.at.checked_add(n)?)?;
        self.at += n;
        Some(s)
    }
    fn u8(&mut self) -> Option<u8> {
        self.take(1).map(|s| s[0])
    }
    fn u16(&mut self) -> Option<u16> {
        self.take(2).map(|s| u16::from_le_bytes([s[0], s[1]]))
    }
    fn u32(&mut self) -> Option<u32> {
        self.take(4)
            .map(|s| u32::from_le_bytes([s[0], s[1], s[2], s[3]]))
    }
    /// A count: a varint, or a u32.
    fn count(&mut self, varint: bool) -> Option<u64> {
        if varint {
            self.varint()
        } else {
            self.u32().map(u64::from)
        }
    }
    /// A LEB128 varint of at most 64 bits.
    fn varint(&mut self) -> Option<u64> {
        let mut v = 0u64;
        for shift in (0..64).step_by(7) {
            let byte = self.u8()?;
            v |= u64::from(byte & 0x7f) << shift;
            if byte & 0x80 == 0 {
                return Some(v);
            }
        }
        None
    }
}
