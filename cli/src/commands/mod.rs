//! The commands, one module each: `render`, `spin` and `bench`.

pub mod bench;
pub mod render;
pub mod spin;
