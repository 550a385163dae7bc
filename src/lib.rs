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

pub mod accuracy;
pub mod animate;
pub mod bench;
pub mod blit;
pub mod clip;
pub mod color;
pub mod encode;
pub mod error;
pub mod frame;
pub mod framebuffer;
pub mod live;
pub mod plan;
pub mod raster;
pub mod render;
pub mod scene;
pub mod shade;
pub mod terminal;
pub mod transform;

pub use blit::GlyphMode;
pub use color::{ColorDepth, Rgb};
pub use error::{Error, Result};
pub use frame::{Cell, Frame};
pub use raster::Traversal;
pub use render::{MAX_CELLS, RenderOptions, Renderer, render};
pub use scene::Scene;

/// The scene `rastty render` draws when it is given none.
pub const DEFAULT_SCENE: &str = include_str!("../examples/scenes/default.toml");

/// [`DEFAULT_SCENE`], parsed.
pub fn default_scene() -> Scene {
    Scene::parse(DEFAULT_SCENE, "<built-in default scene>").expect("the built-in scene parses")
}
