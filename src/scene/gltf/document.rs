//! The document: its JSON checked as the `gltf` crate checks it (but for
//! what glTF allows and the crate does not), its errors in words, and the
//! extensions rastty draws.

use super::{draco, instances, meshopt};

/// An attribute's name as the file spells it, or `(unknown)`.
pub(super) fn semantic_name(
    s: &::gltf::json::validation::Checked<::gltf::json::mesh::Semantic>,
) -> String {
    match s {
        ::gltf::json::validation::Checked::Valid(s) => s.to_string(),
        ::gltf::json::validation::Checked::Invalid => "(unknown)".into(),
    }
}

/// A `gltf` error in words (its own, with the JSON path for validation).
pub(super) fn describe(e: &::gltf::Error) -> String {
    match e {
        ::gltf::Error::Validation(errors) => errors
            .iter()
            .map(|(path, err)| format!("{path}: {err}"))
            .collect::<Vec<_>>()
            .join("; "),
        other => other.to_string(),
    }
}

/// The crate's validation of `root`, but for an accessor without a buffer
/// view, which glTF allows (its elements are zeros, or a Draco stream's)
/// and the crate does not.
pub(super) fn validated(
    root: ::gltf::json::Root,
) -> std::result::Result<::gltf::Document, ::gltf::Error> {
    use ::gltf::json::validation::{Error, Validate};
    let mut errors = Vec::new();
    root.validate(&root, ::gltf::json::Path::new, &mut |path, error| {
        let path = path();
        let p = path.as_str();
        let viewless = p.starts_with("accessors[") && p.ends_with("].bufferView");
        if !(viewless && matches!(error, Error::Missing)) {
            errors.push((path, error));
        }
    });
    if errors.is_empty() {
        Ok(::gltf::Document::from_json_without_validation(root))
    } else {
        Err(::gltf::Error::Validation(errors))
    }
}

/// The extensions rastty draws (others are noted as not drawn).
pub(super) const DRAWN_EXTENSIONS: &[&str] = &[
    "KHR_materials_unlit",
    "KHR_materials_emissive_strength",
    "KHR_lights_punctual",
    "KHR_texture_transform",
    "KHR_materials_pbrSpecularGlossiness",
    "KHR_mesh_quantization",
    instances::EXTENSION,
    "KHR_materials_transmission",
    "KHR_materials_ior",
    "KHR_materials_specular",
    "KHR_materials_clearcoat",
    "KHR_materials_sheen",
    draco::EXTENSION,
    meshopt::EXTENSION,
];
