//! A frame as pixels: one sample a pixel, for terminals that show images
//! (the kitty graphics protocol, sixel, iTerm2's inline images) and for
//! pictures of the pipeline's own samples. The pixels are the samples of
//! the options' grid ([`crate::RenderOptions::grid`]; with
//! [`crate::RenderOptions::cell_pixels`] each cell is a block of the
//! terminal's pixels), encoded to sRGB, rows from the top. A pixel nothing
//! was drawn on is the scene's background, or transparent (alpha 0) where
//! the scene has none, so that a model sits on the terminal's own
//! background.
//!
//! The renderer fills it through the output seam ([`crate::output`]),
//! each band its own rows, as it fills a frame of cells;
//! [`crate::graphics`] turns it into a terminal's bytes.

/// One pixel: red, green, blue (sRGB) and alpha (0 transparent, 255
/// opaque).
pub type Rgba = [u8; 4];

/// A rectangle of pixels: its top left corner and its size.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct PixelRect {
    /// Left column.
    pub x: u32,
    /// Top row.
    pub y: u32,
    /// Width, in pixels.
    pub width: u32,
    /// Height, in pixels.
    pub height: u32,
}

/// A frame's pixels, rows from the top.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Pixels {
    width: u32,
    height: u32,
    rgba: Vec<Rgba>,
}

impl Pixels {
    /// No pixels: the renderer sizes it.
    pub fn new() -> Pixels {
        Pixels::default()
    }

    /// `width × height` pixels of one colour.
    pub fn filled(width: u32, height: u32, c: Rgba) -> Pixels {
        Pixels {
            width,
            height,
            rgba: vec![c; width as usize * height as usize],
        }
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Every pixel, row by row from the top.
    pub fn rgba(&self) -> &[Rgba] {
        &self.rgba
    }

    /// Every pixel's four bytes, row by row from the top (a PNG's or the
    /// kitty protocol's RGBA order).
    pub fn bytes(&self) -> &[u8] {
        self.rgba.as_flattened()
    }

    /// Pixel `(x, y)`, from the top left.
    pub fn get(&self, x: u32, y: u32) -> Rgba {
        self.rgba[y as usize * self.width as usize + x as usize]
    }

    /// Row `y` from the top.
    pub fn row(&self, y: u32) -> &[Rgba] {
        let w = self.width as usize;
        &self.rgba[y as usize * w..(y as usize + 1) * w]
    }

    /// Sets every pixel from `bytes`, RGBA rows from the top (a decoded
    /// PNG's).
    ///
    /// # Panics
    ///
    /// Where `bytes` is not four bytes a pixel.
    pub fn copy_from_bytes(&mut self, bytes: &[u8]) {
        assert_eq!(bytes.len(), self.rgba.len() * 4, "four bytes a pixel");
        self.rgba.as_flattened_mut().copy_from_slice(bytes);
    }

    /// Whether every pixel is opaque (alpha 255).
    pub fn opaque(&self) -> bool {
        self.rgba.iter().all(|p| p[3] == 255)
    }

    /// Resizes to `width × height`; the pixels are then the renderer's to
    /// fill.
    pub(crate) fn resize(&mut self, width: u32, height: u32) {
        self.width = width;
        self.height = height;
        self.rgba.resize(width as usize * height as usize, [0; 4]);
    }

    /// The pixels, to fill.
    pub(crate) fn rgba_mut(&mut self) -> &mut [Rgba] {
        &mut self.rgba
    }

    /// The smallest rectangle holding every pixel that differs from
    /// `before`'s (all of them where the sizes differ), or `None` where
    /// none does: what an encoder that sends only what changed sends.
    pub fn changed_since(&self, before: &Pixels) -> Option<PixelRect> {
        if (self.width, self.height) != (before.width, before.height) {
            return (self.width > 0 && self.height > 0).then_some(PixelRect {
                x: 0,
                y: 0,
                width: self.width,
                height: self.height,
            });
        }
        let w = self.width as usize;
        let (mut x0, mut x1, mut y0, mut y1) = (usize::MAX, 0, usize::MAX, 0);
        for (y, (a, b)) in self
            .rgba
            .chunks_exact(w.max(1))
            .zip(before.rgba.chunks_exact(w.max(1)))
            .enumerate()
        {
            if a == b {
                continue;
            }
            let first = a.iter().zip(b).position(|(p, q)| p != q).unwrap_or(0);
            let last = w
                - 1
                - a.iter()
                    .rev()
                    .zip(b.iter().rev())
                    .position(|(p, q)| p != q)
                    .unwrap_or(0);
            x0 = x0.min(first);
            x1 = x1.max(last);
            y0 = y0.min(y);
            y1 = y;
        }
        (y0 != usize::MAX).then(|| PixelRect {
            x: x0 as u32,
            y: y0 as u32,
            width: (x1 - x0 + 1) as u32,
            height: (y1 - y0 + 1) as u32,
        })
    }
}
