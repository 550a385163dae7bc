//! Vertex and animation values read as floats, the whole of what glTF
//! allows for them: any component type the attribute may have (with
//! `KHR_mesh_quantization`, bytes and shorts, normalized or not), any byte
//! stride, and sparse accessors (a base, or zeros, with the values at the
//! listed indices replaced).
//!
//! The `gltf` crate's readers take every attribute's components as its
//! usual type (a quantized position would be read as floats from the
//! wrong bytes) and skip a sparse index out of order without a word, so
//! these values are read here. Every byte range is checked before it is
//! read, sparse indices must increase and lie inside the accessor, and a
//! sparse accessor with no buffer view (its base all zeros), whose size no
//! buffer bounds, is held to the load's byte budget.

use ::gltf::Accessor;
use ::gltf::accessor::{DataType, Dimensions};

use super::buffers::{Buffer, check_range};

/// The component types `KHR_mesh_quantization` allows for positions,
/// texture coordinates, and an instance's translation and scale: floats,
/// or bytes and shorts of either sign.
pub(super) const QUANTIZED: [DataType; 5] = [
    DataType::F32,
    DataType::I8,
    DataType::U8,
    DataType::I16,
    DataType::U16,
];

/// The component types it allows for directions (normals, tangents,
/// rotations): floats, or signed bytes and shorts.
pub(super) const SIGNED: [DataType; 3] = [DataType::F32, DataType::I8, DataType::I16];

/// The components of each element.
fn width(d: Dimensions) -> usize {
    match d {
        Dimensions::Scalar => 1,
        Dimensions::Vec2 => 2,
        Dimensions::Vec3 => 3,
        Dimensions::Vec4 | Dimensions::Mat2 => 4,
        Dimensions::Mat3 => 9,
        Dimensions::Mat4 => 16,
    }
}

/// One component at the start of `b`, as the spec turns it into a float:
/// a normalized integer into [0, 1] (unsigned) or [−1, 1] (signed, the
/// most negative clamped), another as its value.
fn component(t: DataType, normalized: bool, b: &[u8]) -> f32 {
    match (t, normalized) {
        (DataType::F32, _) => f32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        (DataType::I8, true) => (f32::from(b[0] as i8) / 127.0).max(-1.0),
        (DataType::I8, false) => f32::from(b[0] as i8),
        (DataType::U8, true) => f32::from(b[0]) / 255.0,
        (DataType::U8, false) => f32::from(b[0]),
        (DataType::I16, n) => {
            let v = f32::from(i16::from_le_bytes([b[0], b[1]]));
            if n { (v / 32767.0).max(-1.0) } else { v }
        }
        (DataType::U16, n) => {
            let v = f32::from(u16::from_le_bytes([b[0], b[1]]));
            if n { v / 65535.0 } else { v }
        }
        (DataType::U32, _) => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f32,
    }
}

/// Appends `count` elements of `comps` components of type `t` from
/// `bytes` (element `i` at `i × stride`) to `out`.
fn elements(
    bytes: &[u8],
    stride: usize,
    count: usize,
    (t, normalized, comps): (DataType, bool, usize),
    out: &mut Vec<f32>,
) {
    let size = t.size();
    for i in 0..count {
        let at = &bytes[i * stride..];
        out.extend((0..comps).map(|c| component(t, normalized, &at[c * size..])));
    }
}

/// The floats of `acc`, element after element (`count × components`), of
/// one of `types` and `dims`; `what` names it in messages, and `budget`
/// bounds in bytes what an accessor no buffer bounds may hold.
pub(super) fn floats(
    acc: &Accessor,
    buffers: &[Buffer],
    types: &[DataType],
    dims: &[Dimensions],
    what: &str,
    budget: u64,
) -> Result<Vec<f32>, String> {
    let at = || format!("{what} (accessor {})", acc.index());
    let (t, d) = (acc.data_type(), acc.dimensions());
    if !types.contains(&t) || !dims.contains(&d) {
        return Err(format!(
            "{} is {t:?} {d:?}, not a type rastty reads there",
            at()
        ));
    }
    let comps = width(d);
    let form = (t, acc.normalized(), comps);
    let count = acc.count();
    if count == 0 {
        return Err(format!(
            "{} has a count of 0 (glTF requires at least 1)",
            at()
        ));
    }
    let mut out = Vec::new();
    match acc.view() {
        Some(view) => {
            let (bytes, stride) = check_range(acc, &view, buffers, &at)?;
            out.reserve_exact(count * comps);
            elements(bytes, stride, count, form, &mut out);
        }
        None if acc.sparse().is_some() => {
            let need = (count as u64).saturating_mul(4 * comps as u64);
            if need > budget {
                return Err(format!(
                    "{} is {count} elements of zeros, {need} bytes, more than the budget of {budget}",
                    at()
                ));
            }
            out.resize(count * comps, 0.0);
        }
        None => return Err(format!("{} has no buffer view", at())),
    }
    if let Some(sparse) = acc.sparse() {
        let n = sparse.count();
        if n == 0 || n > count {
            return Err(format!(
                "{} replaces {n} of its {count} elements (sparse: at least 1, at most all)",
                at()
            ));
        }
        let indices = sparse.indices();
        let it = match indices.index_type() {
            ::gltf::accessor::sparse::IndexType::U8 => DataType::U8,
            ::gltf::accessor::sparse::IndexType::U16 => DataType::U16,
            ::gltf::accessor::sparse::IndexType::U32 => DataType::U32,
        };
        let bytes = packed(
            buffers,
            &indices.view(),
            indices.offset(),
            n * it.size(),
            &|| format!("{}'s sparse indices", at()),
        )?;
        let mut index = Vec::with_capacity(n);
        elements(bytes, it.size(), n, (it, false, 1), &mut index);
        let values = sparse.values();
        let size = comps * t.size();
        let bytes = packed(buffers, &values.view(), values.offset(), n * size, &|| {
            format!("{}'s sparse values", at())
        })?;
        let mut last = None;
        for (k, &i) in index.iter().enumerate() {
            let i = i as usize;
            if i >= count || last.is_some_and(|l| i <= l) {
                return Err(format!(
                    "{}: sparse index {k} is {i}, {} (they must increase, below {count})",
                    at(),
                    if i >= count {
                        "past its elements"
                    } else {
                        "out of order"
                    }
                ));
            }
            last = Some(i);
            let mut one = Vec::with_capacity(comps);
            elements(&bytes[k * size..], size, 1, form, &mut one);
            out[i * comps..(i + 1) * comps].copy_from_slice(&one);
        }
    }
    Ok(out)
}

/// `len` tightly packed bytes at `offset` of buffer view `view`, checked.
fn packed<'b>(
    buffers: &'b [Buffer],
    view: &::gltf::buffer::View,
    offset: usize,
    len: usize,
    at: &dyn Fn() -> String,
) -> Result<&'b [u8], String> {
    let buffer = buffers
        .get(view.buffer().index())
        .ok_or_else(|| format!("{}: its buffer is missing", at()))?;
    let start = view.offset().checked_add(offset);
    let end = start.and_then(|s| s.checked_add(len));
    let view_end = view.offset().checked_add(view.length());
    match (start, end, view_end) {
        (Some(s), Some(e), Some(v))
            if offset.checked_add(len).is_some_and(|x| x <= view.length()) && v <= buffer.len() =>
        {
            Ok(&buffer[s..e])
        }
        _ => Err(format!(
            "{} is out of range: {len} bytes at offset {offset} of buffer view {} ({} bytes)",
            at(),
            view.index(),
            view.length()
        )),
    }
}
