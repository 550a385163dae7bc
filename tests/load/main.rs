//! The model loaders end to end, in one test binary: every format read,
//! damaged files that must not panic, moving models, materials, alpha,
//! maps and textures, on files the tests write.

#[path = "../common/mod.rs"]
mod common;

#[cfg(all(feature = "gltf", feature = "ply"))]
mod loaders;
#[cfg(all(feature = "gltf", feature = "ply"))]
mod formats;
#[cfg(feature = "gltf")]
mod animation;
#[cfg(feature = "gltf")]
mod alpha;
#[cfg(feature = "gltf")]
mod maps;
#[cfg(feature = "gltf")]
mod materials;
#[cfg(feature = "gltf")]
mod spec;
#[cfg(feature = "gltf")]
mod environment;
#[cfg(feature = "gltf")]
mod layers;
#[cfg(feature = "threemf")]
mod threemf;
#[cfg(all(feature = "gltf", feature = "textures"))]
mod textures;
