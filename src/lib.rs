//! rastty makes the terminal's character grid a raster display.
//!
//! It runs the pipeline of GAMES101 Lecture 5 ("Rasterization 1:
//! Triangles") for real, one stage after another:
//!
//! | stage | where | in → out |
//! |---|---|---|
//! | 1 | [`scene`] | TOML, a model file or [`Scene::builder`](scene::Scene::builder) → [`Scene`](scene::Scene) (triangles, meshes, camera, lights) |
//! | 2 | [`transform`] | model, view, projection, viewport matrices |
//! | 3 | [`clip`] | clip-space triangles → clipped convex polygons |
//! | 4 | [`raster`] | screen triangles → covered samples, exactly |
//! | 5 | [`Framebuffer`] | one colour (and depth) per sample |
//! | 6 | [`GlyphMode`] | a cell's samples → one glyph and two colours: a [`Cell`] of a [`Frame`] |
//! | 7 | [`encode`] | a frame → ANSI bytes for any `io::Write`, only what changed |
//!
//! A [`Renderer`] runs stages 1–6 as its [`Plan`] says (a stage a scene does
//! not need is skipped, and the frame is bit for bit the full pipeline's);
//! [`RenderOptions`] holds everything about a frame that is not the scene,
//! each accuracy knob at its exact setting by default. [`animate`] turns a
//! scene frame after frame, with or without a terminal.
//!
//! [`render()`] is the one-call form, and returns a [`Frame`] whose
//! `Display` is plain text, ready for a snapshot
//! (`insta::assert_snapshot!(frame.to_string())`):
//!
//! ```
//! use rastty::{render, RenderOptions, scene::Scene, GlyphMode, color::ColorDepth};
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
//! Frame after frame, [`Renderer::render_into`] draws into the caller's
//! [`Frame`] and allocates nothing once the sizes are stable; an
//! [`Encoder`](encode::Encoder) sends each frame as the bytes that change the last one into
//! it.
//!
//! # Cargo features
//!
//! | feature | default | what it adds |
//! |---|---|---|
//! | `share` | yes | `picture`: a frame as PNG or SVG; `cast`: frames as an asciicast v2 recording |
//! | `gltf` | yes | `scene::gltf`: glTF 2.0 and GLB models, with their textures |
//! | `ply` | yes | `scene::ply`: PLY models |
//! | `textures` | yes | PNG and JPEG images for OBJ `map_Kd` textures |
//! | `parallel` | yes | frames of 600×180 cells or more drawn in bands of rows on every core (rayon); the same frame, bit for bit ([`Threads`]) |
//! | `ratatui` | no | `ratatui::SceneWidget`: a scene drawn into a ratatui buffer |
//!
//! With `default-features = false` the crate is the renderer alone (glam,
//! the model loaders and the scene format). The `rastty` program (command
//! line, terminal, live loop, bench) is another crate, `rastty-cli`, none of
//! whose dependencies a library user gets.
//!
//! # Where things are
//!
//! Each public item has one path. The root holds the renderer and what
//! sets it up ([`Renderer`], [`RenderOptions`] and its settings, [`Plan`],
//! [`Frame`], [`GlyphMode`], [`Error`]); each public module is the one
//! path to its own items: [`scene`] (scenes, meshes, cameras, loaders by
//! format), [`color`] (colours, depths, palettes), [`encode`] (the
//! encoder), [`texture`], [`transform`], and the low-level stages kept
//! public for experiments and the accuracy bench ([`fixed`], [`clip`],
//! [`raster`], [`accuracy`]). `tests/render/architecture.rs` checks that no item
//! is reachable two ways.
//!
//! Conventions: y points up (sample row 0 is the bottom; terminal row `r`
//! shows sample row `H − 1 − r`), sample `(x, y)` sits at `(x + 0.5, y + 0.5)`,
//! and the projection is given the physical aspect of the view
//! ([`RenderOptions::aspect`]), since cells are not square.

#![warn(missing_docs, missing_debug_implementations)]

// Modules are declared in layers, and a module uses only modules declared
// before it (tests/render/architecture.rs checks this): foundations, then the
// stages in data-flow order, then what runs them, then where frames go.

// Foundations: errors, colours, fixed point, matrices and the sample grid,
// textures.
pub mod text;
mod choice;
mod error;
pub mod color;
pub mod fixed;
pub mod transform;
pub mod texture;
pub mod accuracy;

// The stages, in data-flow order.
pub mod scene;
mod shade;
pub mod clip;
pub mod raster;
mod framebuffer;
mod fill;
mod frame;
mod pixels;
mod blit;
pub mod encode;
#[cfg(feature = "graphics")]
pub mod graphics;

// What runs them: the options, the planner that decides, the renderer that
// obeys, and the animation loop's core.
mod options;
mod output;
mod stats;
mod plan;
mod render;
pub mod animate;

// Where frames go: a picture, a recording, or a ratatui buffer (the
// terminal itself is the program's, in cli/).
pub mod outfile;
#[cfg(feature = "share")]
pub mod picture;
#[cfg(feature = "share")]
pub mod cast;
#[cfg(feature = "ratatui")]
pub mod ratatui;

pub use glam;

pub use blit::{GlyphFamily, GlyphMode, GlyphSupport, Split};
pub use choice::Choice;
pub use error::{Error, Result};
pub use frame::{Cell, Frame, WithColors};
pub use framebuffer::Framebuffer;
pub use options::{
    Aa, DEFAULT_MAX_SAMPLES, Highlights, Interpolation, MAX_CELL_PIXELS, MAX_CELLS, MAX_THREADS,
    PARALLEL_CELLS, PARALLEL_PIXELS, Pipeline, RenderOptions, Threads, Wire,
};
pub use pixels::{PixelRect, Pixels, Rgba};
pub use plan::{Bands, Decision, Effect, Extras, Plan};
pub use render::{Renderer, render, try_render};
pub use shade::{
    Lights, Shading, reflection_reference, sheen_albedo_reference, sheen_reference,
    specular_reference,
};
pub use stats::{FrameStats, FrameTimes};
