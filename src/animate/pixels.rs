//! A [`Player`]'s frames for a terminal that shows pixels: the picture
//! rendered one sample a pixel ([`crate::Pixels`]) and sent in the
//! terminal's protocol ([`crate::graphics`]) at the top left, the status
//! line and the help box as text, in synchronized output (`CSI ? 2026`),
//! so that a frame appears whole.
//!
//! The image covers every row but the last, which is the status line's:
//! an image that reached the last row would scroll a sixel terminal. With
//! kitty the image is placed once and edited where it changed, below the
//! text (`z=-1`), so the help box is drawn once over it and taken away by
//! writing blanks; sixel and iTerm2 images replace the cells they cover,
//! so each is sent whole when it changed and the help box written again
//! after it; a sixel frame paints the terminal's background where nothing
//! is drawn, since sixel has no way to take a last frame's pixels away.
//! Only the text that changed is written otherwise.

use std::io::Write as _;

use super::{KEYS, LiveStatus, Player, hud};
use crate::color::Rgb;
use crate::frame::{Cell, Frame};
use crate::graphics::{Protocol, iterm, kitty, sixel};
use crate::options::RenderOptions;
use crate::pixels::Pixels;

/// The image id rastty's animation takes in a kitty terminal.
pub const KITTY_ID: u32 = 0x0072_6173;

/// What a terminal that shows pixels is sent, and what it shows.
#[derive(Debug)]
pub(super) struct Screen {
    protocol: Protocol,
    kitty: kitty::Animation,
    sixel: sixel::Encoder,
    pixels: Pixels,
    /// The pixels last sent (sixel and iTerm2 send a frame whole, when it
    /// changed).
    sent: Pixels,
    /// This frame's text, and what the terminal shows of it.
    text: Frame,
    shown: Frame,
    /// Whether the screen is to be cleared first (the first frame, a
    /// resize, a redraw).
    fresh: bool,
    out: Vec<u8>,
    image: Vec<u8>,
}

impl Screen {
    pub(super) fn new(protocol: Protocol, registers: u16, background: Option<Rgb>) -> Screen {
        Screen {
            protocol,
            kitty: kitty::Animation::new(KITTY_ID).below_text(),
            sixel: sixel::Encoder::new(registers).with_background(background),
            pixels: Pixels::new(),
            sent: Pixels::new(),
            text: Frame::default(),
            shown: Frame::default(),
            fresh: true,
            out: Vec::new(),
            image: Vec::new(),
        }
    }

    pub(super) fn protocol(&self) -> Protocol {
        self.protocol
    }

    /// The next frame is sent whole, on a cleared screen.
    pub(super) fn invalidate(&mut self) {
        self.fresh = true;
        self.kitty.forget();
        self.sent = Pixels::new();
        self.shown.reset(0, 0);
    }

    /// The bytes that take the image away (every way out of `spin` sends
    /// them before the terminal is restored).
    pub(super) fn goodbye(&mut self, out: &mut Vec<u8>) {
        if self.protocol == Protocol::Kitty {
            self.kitty.delete(out);
        }
        self.invalidate();
    }

    /// The bytes of a frame whose pixels and text are in place: cells
    /// `cols × rows`, the image over the first `image_rows`.
    fn encode(&mut self, cols: u16, image_rows: u16) -> &[u8] {
        let out = &mut self.out;
        out.clear();
        out.extend_from_slice(b"\x1b[?2026h");
        let start = out.len();
        if self.fresh {
            out.extend_from_slice(b"\x1b[0m\x1b[H\x1b[2J");
        }
        self.image.clear();
        let repaint = match self.protocol {
            Protocol::Kitty => {
                self.kitty
                    .frame(&self.pixels, cols, image_rows, &mut self.image);
                false
            }
            Protocol::Sixel | Protocol::Iterm => {
                if self.fresh || self.pixels != self.sent {
                    match self.protocol {
                        Protocol::Sixel => self.sixel.encode(&self.pixels, &mut self.image),
                        _ => {
                            let _ = iterm::still(&self.pixels, cols, image_rows, &mut self.image);
                        }
                    }
                    self.sent.clone_from(&self.pixels);
                    true
                } else {
                    false
                }
            }
        };
        if !self.image.is_empty() {
            out.extend_from_slice(b"\x1b[H");
            out.extend_from_slice(&self.image);
        }
        // The text that changed; over a repainted image, all of it.
        let fresh_text =
            (self.shown.cols(), self.shown.rows()) != (self.text.cols(), self.text.rows());
        let mut pen: Option<(Option<Rgb>, Option<Rgb>)> = None;
        for row in 0..self.text.rows() {
            let mut col = 0;
            let over_image = row < image_rows;
            while col < self.text.cols() {
                let cell = self.text.get(col, row);
                let was = (!fresh_text).then(|| self.shown.get(col, row));
                let send = was != Some(cell) && (cell != Cell::BLANK || was.is_some())
                    || (repaint && over_image && cell != Cell::BLANK);
                if !send {
                    col += 1;
                    continue;
                }
                let _ = write!(out, "\x1b[{};{}H", row + 1, col + 1);
                while col < self.text.cols() {
                    let cell = self.text.get(col, row);
                    let was = (!fresh_text).then(|| self.shown.get(col, row));
                    let send = was != Some(cell) && (cell != Cell::BLANK || was.is_some())
                        || (repaint && over_image && cell != Cell::BLANK);
                    if !send {
                        break;
                    }
                    if pen != Some((cell.fg, cell.bg)) {
                        sgr(out, cell.fg, cell.bg);
                        pen = Some((cell.fg, cell.bg));
                    }
                    let mut utf8 = [0; 4];
                    out.extend_from_slice(cell.ch.encode_utf8(&mut utf8).as_bytes());
                    col += 1;
                }
            }
        }
        if pen.is_some() {
            out.extend_from_slice(b"\x1b[0m");
        }
        std::mem::swap(&mut self.shown, &mut self.text);
        self.fresh = false;
        if out.len() == start {
            out.clear();
        } else {
            out.extend_from_slice(b"\x1b[?2026l");
        }
        out
    }
}

/// Appends the SGR that sets `fg` on `bg` (`None`: the terminal's own).
fn sgr(out: &mut Vec<u8>, fg: Option<Rgb>, bg: Option<Rgb>) {
    out.extend_from_slice(b"\x1b[0");
    if let Some(Rgb([r, g, b])) = fg {
        let _ = write!(out, ";38;2;{r};{g};{b}");
    }
    if let Some(Rgb([r, g, b])) = bg {
        let _ = write!(out, ";48;2;{r};{g};{b}");
    }
    out.push(b'm');
}

impl Player {
    /// Sends frames as pixels in `protocol`, each cell a block of `cell`
    /// pixels (across, down): the same pipeline at the terminal's pixel
    /// resolution. A sixel terminal's `registers` bound its palette
    /// (fewer than 256: the 16 ANSI colours); its `background` is painted
    /// where nothing is drawn (sixel cannot take a last frame's pixels
    /// away; `None`: black).
    pub fn set_graphics(
        &mut self,
        protocol: Protocol,
        cell: [u16; 2],
        registers: u16,
        background: Option<Rgb>,
    ) {
        self.opts.cell_pixels = Some(cell);
        self.opts.cell_aspect = f32::from(cell[0]) / f32::from(cell[1].max(1));
        let background = background.or(Some(Rgb::BLACK));
        self.screen = Some(Screen::new(protocol, registers, background));
    }

    /// Changes the pixels a cell holds (the terminal's font or its zoom
    /// changed); the next frame is sent whole.
    pub fn set_cell_pixels(&mut self, cell: [u16; 2]) {
        if self.screen.is_some() && self.opts.cell_pixels != Some(cell) {
            self.opts.cell_pixels = Some(cell);
            self.opts.cell_aspect = f32::from(cell[0]) / f32::from(cell[1].max(1));
            self.invalidate();
        }
    }

    /// Draws each cell with half its pixels across and down, a quarter of
    /// the bytes, where the protocol scales an image to its cells (kitty,
    /// iTerm2): a link too slow for the full image. The cell's shape stays
    /// the terminal's. False where it cannot (sixel, or a cell of fewer
    /// than 2 pixels a side).
    pub fn halve_pixels(&mut self) -> bool {
        let (Some(s), Some([w, h])) = (&self.screen, self.opts.cell_pixels) else {
            return false;
        };
        if s.protocol() == Protocol::Sixel || w < 2 || h < 2 {
            return false;
        }
        self.opts.cell_pixels = Some([w / 2, h / 2]);
        self.invalidate();
        true
    }

    /// Stops sending pixels: character cells from the next frame (a link
    /// too slow for pixels), the image taken away first; `out` gets the
    /// bytes that take it away.
    pub fn stop_graphics(&mut self, out: &mut Vec<u8>) {
        if let Some(mut s) = self.screen.take() {
            s.goodbye(out);
            self.opts.cell_pixels = None;
            self.encoder.invalidate();
        }
    }

    /// The bytes that take the image away, for every way out of `spin`
    /// (nothing in cell mode).
    pub fn goodbye(&mut self, out: &mut Vec<u8>) {
        if let Some(s) = &mut self.screen {
            s.goodbye(out);
        }
    }

    /// [`Player::prepare`] for pixels: `opts` are the image's (its rows
    /// leave the status line's).
    pub(super) fn prepare_pixels(
        &mut self,
        opts: &RenderOptions,
        turn: glam::Vec3,
        live: LiveStatus,
    ) -> &[u8] {
        let status = self.status_line(opts, turn, live);
        let (cols, rows) = (self.opts.cols, self.opts.rows);
        let screen = self.screen.as_mut().expect("pixels");
        if let Err(e) = self
            .renderer
            .try_render_pixels(&self.scene, opts, &mut screen.pixels)
        {
            screen.pixels = Pixels::new();
            self.notice = Some(e.to_string());
        }
        screen.text.reset(cols, rows);
        if let Some(full_row) = status {
            hud::overlay(&mut screen.text, &self.status, full_row);
        }
        if self.help {
            hud::help_box(&mut screen.text, KEYS);
        }
        let bytes = screen.encode(opts.cols, opts.rows);
        self.last_bytes = bytes.len();
        bytes
    }
}
