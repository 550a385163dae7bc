//! The renderer end to end, in one test binary (a binary each would be
//! linked each on its own): hard cases and their promises, shared edges,
//! the planner against the full pipeline, meshes and scene files as
//! snapshots, the encoder read back by an emulator, pictures, lights,
//! wireframes, colour fidelity, the ratatui widget, and the crate's shape.

#[path = "../common/mod.rs"]
mod common;

mod architecture;
mod hard_cases;
mod lights;
mod meshes;
mod pictures;
mod plan;
mod roundtrip;
mod snapshots;
mod watertight;
mod wire;
#[cfg(feature = "share")]
mod fidelity;
#[cfg(feature = "ratatui")]
mod widget;
#[cfg(feature = "graphics")]
mod graphics;
