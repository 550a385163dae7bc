//! A scene inside a ratatui app: [`SceneWidget`] renders a [`Scene`] into
//! the area it is given, two colours per cell, through the same renderer,
//! glyphs and colour mapping as `rastty render`.
//!
//! ratatui's own `Canvas` gives its sub-cell markers (braille, half blocks)
//! one colour per cell; a rastty cell has a glyph, a foreground and a
//! background chosen together from the cell's samples, so edges between
//! two surfaces keep both colours.
//!
//! **Colours** go through the encoder's own mapping ([`TermCell::of`]): at
//! truecolor a cell gets [`Color::Rgb`]; at 256 colours the palette entry
//! the encoder would send (matched in OKLCh, dithered by the pattern
//! anchored to the cell's place in the view), as [`Color::Indexed`] for
//! 16–255 and as ratatui's named colours for 0–15 (which its back ends send
//! as SGR 30–37 and 90–97, as rastty's encoder does); at 16 colours the
//! named colours. Where rastty leaves the terminal's default (uncovered
//! cells of a scene without a background, a blank's foreground, every
//! colour at [`ColorDepth::None`](crate::color::ColorDepth::None)), the widget leaves the buffer's colour
//! as it was, so a `Block`'s background shows through.
//!
//! A model that moves is drawn at its meshes' poses: call
//! [`Scene::set_pose`] with the clip and the time before each draw to play
//! it (the viewer example does); a [`SceneState`]'s renderer poses it only
//! when the time changes.
//!
//! An area or a scene over the options' budgets (wider or taller than
//! [`MAX_CELLS`](crate::MAX_CELLS), more sample tests than
//! [`RenderOptions::max_samples`], more triangles than
//! [`RenderOptions::max_triangles`]) is not drawn: the buffer is left as
//! it was, and [`SceneState::error`] says why.
//!
//! The stateless [`SceneWidget`] renders with a fresh renderer each time;
//! [`SceneState`] keeps a renderer, a frame and a colour cache between
//! frames (`render_stateful_widget`), so that a steady view allocates
//! nothing per frame.
//!
//! ```
//! use ratatui_core::{buffer::Buffer, layout::Rect, widgets::Widget};
//! use rastty::ratatui::SceneWidget;
//! use rastty::{color::ColorDepth, GlyphMode, RenderOptions, color::Rgb, scene::Scene, scene::Shape};
//!
//! let scene = Scene::of_mesh(Shape::Torus.mesh(Rgb::new(0xff, 0x90, 0x40)));
//! let options = RenderOptions { glyphs: GlyphMode::Quadrant, color: ColorDepth::TrueColor, ..Default::default() };
//! let mut buf = Buffer::empty(Rect::new(0, 0, 40, 12));
//! SceneWidget::new(&scene, &options).render(buf.area, &mut buf);
//! assert!(buf.content.iter().any(|c| c.symbol() != " "));
//! ```

use ratatui_core::buffer::Buffer;
use ratatui_core::layout::Rect;
use ratatui_core::style::Color;
use ratatui_core::widgets::{StatefulWidget, Widget};

use crate::color::{Ink, Palette, Quantizer};
use crate::encode::TermCell;
use crate::frame::Frame;
use crate::options::RenderOptions;
use crate::render::Renderer;
use crate::scene::Scene;

/// A scene drawn into a ratatui buffer: the area's width and height in
/// cells replace the options' `cols` and `rows`; everything else (glyphs,
/// colour depth, turn, shading, every knob) is the options'.
#[derive(Clone, Copy, Debug)]
#[must_use = "a widget draws nothing until it is rendered"]
pub struct SceneWidget<'a> {
    scene: &'a Scene,
    options: &'a RenderOptions,
    palette: Palette,
}

impl<'a> SceneWidget<'a> {
    /// A widget showing `scene` drawn with `options`, its colours matched
    /// to the options' depth as `rastty render` matches them.
    pub fn new(scene: &'a Scene, options: &'a RenderOptions) -> SceneWidget<'a> {
        SceneWidget {
            scene,
            options,
            palette: Palette::from(options.color),
        }
    }

    /// Matches and dithers colours as `palette` says (its depth replaces
    /// the options').
    pub fn palette(self, palette: Palette) -> SceneWidget<'a> {
        SceneWidget { palette, ..self }
    }
}

/// What a [`SceneWidget`] keeps between frames: the renderer's working
/// memory, the frame, and the palette's colour cache.
#[derive(Debug, Default)]
pub struct SceneState {
    renderer: Renderer,
    frame: Frame,
    /// The palette of the last frame and its quantizer (whose cache of
    /// matched colours is kept while the palette stays the same).
    quantizer: Option<(Palette, Quantizer)>,
    /// Why the last frame was not drawn, if it was not.
    error: Option<crate::error::Error>,
}

impl SceneState {
    /// A state with nothing kept yet.
    pub fn new() -> SceneState {
        SceneState::default()
    }

    /// The renderer, to read the last frame's statistics or plan.
    pub fn renderer(&self) -> &Renderer {
        &self.renderer
    }

    /// The last frame drawn, as `rastty render` would print it.
    pub fn frame(&self) -> &Frame {
        &self.frame
    }

    /// Why the last render drew nothing: the area or the scene over the
    /// options' budgets ([`crate::Renderer::try_render`]'s error).
    pub fn error(&self) -> Option<&crate::error::Error> {
        self.error.as_ref()
    }
}

impl Widget for SceneWidget<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        StatefulWidget::render(self, area, buf, &mut SceneState::new());
    }
}

impl StatefulWidget for SceneWidget<'_> {
    type State = SceneState;

    fn render(self, area: Rect, buf: &mut Buffer, state: &mut SceneState) {
        // Only the part of the area inside the buffer is drawn, and the
        // frame is rendered at that size.
        let area = area.intersection(buf.area);
        if area.is_empty() {
            return;
        }
        let options = RenderOptions {
            cols: area.width,
            rows: area.height,
            color: self.palette.depth,
            ..*self.options
        };
        state.error = state
            .renderer
            .try_render_into(self.scene, &options, &mut state.frame)
            .err();
        if state.error.is_some() {
            return;
        }
        let (_, q) = match &mut state.quantizer {
            Some(kept) if kept.0 == self.palette => kept,
            slot => slot.insert((self.palette, Quantizer::of(self.palette))),
        };
        let frame = &state.frame;
        for y in 0..frame.rows() {
            for x in 0..frame.cols() {
                let t = TermCell::at(frame, q, x, y);
                let Some(out) = buf.cell_mut((area.x + x, area.y + y)) else {
                    continue;
                };
                out.set_char(t.ch);
                if let Some(fg) = color(t.fg) {
                    out.set_fg(fg);
                }
                if let Some(bg) = color(t.bg) {
                    out.set_bg(bg);
                }
            }
        }
    }
}

/// The ratatui colour of an ink; `None` for the terminal's default, which
/// leaves the buffer's colour as it is.
fn color(ink: Ink) -> Option<Color> {
    const NAMED: [Color; 16] = [
        Color::Black,
        Color::Red,
        Color::Green,
        Color::Yellow,
        Color::Blue,
        Color::Magenta,
        Color::Cyan,
        Color::Gray,
        Color::DarkGray,
        Color::LightRed,
        Color::LightGreen,
        Color::LightYellow,
        Color::LightBlue,
        Color::LightMagenta,
        Color::LightCyan,
        Color::White,
    ];
    match ink {
        Ink::Default => None,
        Ink::Indexed(i) if i < 16 => Some(NAMED[i as usize]),
        Ink::Indexed(i) => Some(Color::Indexed(i)),
        Ink::Rgb(c) => {
            let [r, g, b] = c.0;
            Some(Color::Rgb(r, g, b))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn palette_entries_map_to_the_sgr_the_encoder_sends() {
        // Named colour i is sent by ratatui's back ends as SGR 30+i (0–7)
        // or 90+(i−8) (8–15), as rastty's encoder sends index i.
        assert_eq!(color(Ink::Indexed(0)), Some(Color::Black));
        assert_eq!(color(Ink::Indexed(7)), Some(Color::Gray));
        assert_eq!(color(Ink::Indexed(8)), Some(Color::DarkGray));
        assert_eq!(color(Ink::Indexed(15)), Some(Color::White));
        assert_eq!(color(Ink::Indexed(16)), Some(Color::Indexed(16)));
        assert_eq!(color(Ink::Indexed(255)), Some(Color::Indexed(255)));
        assert_eq!(
            color(Ink::Rgb(crate::color::Rgb::new(1, 2, 3))),
            Some(Color::Rgb(1, 2, 3))
        );
        assert_eq!(color(Ink::Default), None);
    }
}
