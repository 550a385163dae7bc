//! rastty makes the terminal's character grid a raster display.
//!
//! It runs the pipeline of GAMES101 Lecture 5 ("Rasterization 1:
//! Triangles") for real, one module per stage in data-flow order:
//!
//! | stage | module | in → out |
//! |---|---|---|
//! | 1 | [`scene`] | TOML → [`Scene`] (world-space triangles, camera) |
//! | 2 | [`transform`] | model, view, projection, viewport matrices |
//! | 3 | [`clip`] | clip-space triangles → clipped convex polygons |
//! | 4 | [`raster`] | screen triangles → covered samples, exactly |
//! | 5 | [`framebuffer`] | one colour per sample |
//! | 6 | [`blit`] | a cell's samples → one glyph and its colours ([`Frame`]) |
//! | 7 | [`encode`] | a frame → ANSI bytes for any `io::Write` |
//! | 8 | [`terminal`] | the terminal's size, cell shape and colours |
//!
//! [`animate`] turns a scene frame after frame through stages 1–7, with or
//! without a terminal.
//!
//! [`render`](render::render) runs stages 1–6 and returns a [`Frame`] whose
//! `Display` is plain text, ready for a snapshot:
//!
//! ```
//! use rastty::{render, RenderOptions, Scene, GlyphMode, ColorDepth};
//!
//! let scene = Scene::parse(r##"
//!     [camera]
//!     projection = "none"
//!     [[triangle]]
//!     vertices = [[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [-1.0, 1.0, 0.0]]
//! "##, "inline").unwrap();
//! let opts = RenderOptions { cols: 4, rows: 4, glyphs: GlyphMode::Ascii, color: ColorDepth::None, ..Default::default() };
//! let frame = render(&scene, &opts);
//! // The hypotenuse runs through sample centres; it is not a top or left edge,
//! // so the samples on it stay out.
//! assert_eq!(frame.to_string(), "    \n@   \n@@  \n@@@ \n");
//! ```
//!
//! Conventions: y points up (sample row 0 is the bottom; terminal row `r`
//! shows sample row `H − 1 − r`), sample `(x, y)` sits at `(x + 0.5, y + 0.5)`,
//! and the projection is given the physical aspect of the view
//! ([`RenderOptions::aspect`]), since cells are not square.

// Modules are declared in layers, and a module uses only modules declared
// before it (tests/architecture.rs checks this): foundations, then the
// stages in data-flow order, then what runs them, then where frames go.

// Foundations: errors, colours, fixed point, matrices and the sample grid.
mod accuracy;
pub mod color;
mod error;
pub mod fixed;
pub mod transform;

// The stages, in data-flow order.
mod blit;
pub mod clip;
pub mod encode;
mod frame;
mod framebuffer;
pub mod raster;
pub mod scene;
mod shade;

// What runs them: the options, the planner that decides, the renderer that
// obeys, the animation loop's core, and the measurements.
pub mod animate;
#[cfg(feature = "bench")]
pub mod bench;
mod options;
mod plan;
mod render;

// Where frames go: a terminal (the program), or a ratatui buffer.
#[cfg(feature = "cli")]
pub mod live;
#[cfg(feature = "ratatui")]
pub mod ratatui;
#[cfg(feature = "cli")]
pub mod terminal;

pub use glam;

pub use blit::{GlyphMode, Split};
pub use color::{ColorDepth, Rgb};
pub use encode::Encoder;
pub use error::{Error, Result};
pub use frame::{Cell, Frame};
pub use framebuffer::Framebuffer;
pub use options::{Aa, Interpolation, MAX_CELLS, Pipeline, RenderOptions};
pub use plan::{Decision, Plan};
pub use raster::{Precision, Traversal};
pub use render::{FrameStats, FrameTimes, Renderer, render};
pub use scene::{Camera, Cull, Light, Mesh, Projection, Scene};
pub use shade::{Lights, Shading};

/// The scene `rastty render` draws when it is given none.
pub const DEFAULT_SCENE: &str = include_str!("../examples/scenes/default.toml");

/// [`DEFAULT_SCENE`], parsed.
pub fn default_scene() -> Scene {
    Scene::parse(DEFAULT_SCENE, "<built-in default scene>").expect("the built-in scene parses")
}
