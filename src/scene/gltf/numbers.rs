//! glTF's numbers at the edge of f32. The gltf crate reads every number of
//! the JSON as an `f32`, so `1e39` (a valid JSON number) becomes infinity
//! without a word, and a node translated by it, or a weight, draws
//! nothing. The JSON is walked once before it is used: a number past
//! f32's range (±3.4 × 10^38) anywhere outside `extras` is an error that
//! names the field by its path (`nodes[3].translation[1]`). The walk
//! borrows the text's strings (a `data:` URI of megabytes is not copied).

use std::fmt;

use serde::de::{DeserializeSeed, IgnoredAny, MapAccess, SeqAccess, Visitor};

/// The JSON of a `.gltf` file, or of a GLB's first chunk.
pub(super) fn json_of(bytes: &[u8]) -> Option<&[u8]> {
    if !bytes.starts_with(b"glTF") {
        return Some(bytes);
    }
    let word = |at: usize| {
        bytes
            .get(at..at + 4)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize)
    };
    let len = word(12)?;
    bytes.get(20..20usize.checked_add(len)?)
}

/// Refuses a JSON number past f32's range outside `extras`, naming where
/// it is; JSON the walk cannot read is left to the gltf crate's errors.
pub(super) fn check(json: &[u8]) -> Result<(), String> {
    let mut path = Vec::new();
    let mut de = serde_json::Deserializer::from_slice(json);
    match (Walk { path: &mut path }).deserialize(&mut de) {
        Ok(Some(e)) => Err(e),
        _ => Ok(()),
    }
}

/// A place in the document, read so far: keys and indices.
enum Step {
    Key(String),
    Index(usize),
}

/// Shows a path as `nodes[3].translation[1]`.
fn shown(path: &[Step]) -> String {
    let mut out = String::new();
    for step in path {
        match step {
            Step::Key(k) => {
                if !out.is_empty() {
                    out.push('.');
                }
                if k.chars().count() > 40 {
                    out.push_str(&crate::text::name(k, 40));
                } else {
                    out.push_str(&crate::text::escape(k));
                }
            }
            Step::Index(i) => out.push_str(&format!("[{i}]")),
        }
    }
    out
}

/// One value's walk: `Some(error)` at the first number out of range.
struct Walk<'p> {
    path: &'p mut Vec<Step>,
}

impl<'de> DeserializeSeed<'de> for Walk<'_> {
    type Value = Option<String>;

    fn deserialize<D: serde::Deserializer<'de>>(self, d: D) -> Result<Self::Value, D::Error> {
        d.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for Walk<'_> {
    type Value = Option<String>;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("JSON")
    }

    fn visit_f64<E>(self, v: f64) -> Result<Self::Value, E> {
        Ok((v.abs() > f64::from(f32::MAX)).then(|| {
            format!(
                "{}: {v:e} is past the range of the 32-bit floats glTF's numbers are read as (±3.4e38)",
                shown(self.path)
            )
        }))
    }

    fn visit_i64<E>(self, _: i64) -> Result<Self::Value, E> {
        Ok(None)
    }

    fn visit_u64<E>(self, _: u64) -> Result<Self::Value, E> {
        Ok(None)
    }

    fn visit_bool<E>(self, _: bool) -> Result<Self::Value, E> {
        Ok(None)
    }

    fn visit_str<E>(self, _: &str) -> Result<Self::Value, E> {
        Ok(None)
    }

    fn visit_unit<E>(self) -> Result<Self::Value, E> {
        Ok(None)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
        let mut i = 0;
        let mut found = None;
        loop {
            if found.is_some() {
                // The rest read without a look: the error is the first.
                if seq.next_element::<IgnoredAny>()?.is_none() {
                    return Ok(found);
                }
                continue;
            }
            self.path.push(Step::Index(i));
            let next = seq.next_element_seed(Walk {
                path: &mut *self.path,
            })?;
            match next {
                None => {
                    self.path.pop();
                    return Ok(None);
                }
                Some(Some(e)) => found = Some(e),
                Some(None) => {
                    self.path.pop();
                }
            }
            i += 1;
        }
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
        let mut found = None;
        while let Some(key) = map.next_key::<std::borrow::Cow<'de, str>>()? {
            if found.is_some() || key == "extras" {
                // What an application keeps in `extras` is its own.
                map.next_value::<IgnoredAny>()?;
                continue;
            }
            self.path.push(Step::Key(key.into_owned()));
            match map.next_value_seed(Walk {
                path: &mut *self.path,
            })? {
                Some(e) => found = Some(e),
                None => {
                    self.path.pop();
                }
            }
        }
        Ok(found)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_number_past_f32_is_named_by_its_path() {
        let json = br#"{"asset":{"version":"2.0"},"nodes":[{"name":"a"},{"translation":[0,1e39,0]}],"extras":{"big":1e300}}"#;
        assert_eq!(
            check(json).unwrap_err(),
            "nodes[1].translation[1]: 1e39 is past the range of the 32-bit floats glTF's numbers are read as (±3.4e38)"
        );
        assert_eq!(
            check(br#"{"nodes":[{"scale":[3.4e38,-3.4e38,1]}],"extras":[1e300]}"#),
            Ok(())
        );
        let deep = br#"{"materials":[{"pbrMetallicRoughness":{"baseColorFactor":[1,1,1,-2e38]}},{"emissiveFactor":[1,-4e38,0]}]}"#;
        assert_eq!(
            check(deep).unwrap_err(),
            "materials[1].emissiveFactor[1]: -4e38 is past the range of the 32-bit floats glTF's numbers are read as (±3.4e38)"
        );
    }
}
