//! iTerm2's inline images: `ESC ] 1337 ; File = keys : base64 BEL`, the
//! image a PNG (alpha kept), shown over `cols × rows` cells at the cursor
//! without keeping its own aspect (the cells' pixels are the frame's).

use std::io::Write as _;

use super::base64_into;
use crate::pixels::Pixels;

/// Appends `pixels` as one inline image over `cols × rows` cells.
///
/// # Errors
///
/// Where the PNG cannot be made (a side of 0 pixels).
pub fn still(pixels: &Pixels, cols: u16, rows: u16, out: &mut Vec<u8>) -> crate::error::Result<()> {
    let png = png_of(pixels)?;
    let _ = write!(
        out,
        "\x1b]1337;File=inline=1;size={};width={cols};height={rows};preserveAspectRatio=0;doNotMoveCursor=1:",
        png.len()
    );
    base64_into(&png, out);
    out.push(0x07);
    Ok(())
}

/// `pixels` as a PNG file's bytes (RGBA, 8 bits a channel).
pub fn png_of(pixels: &Pixels) -> crate::error::Result<Vec<u8>> {
    let mut png = Vec::new();
    let mut enc = png::Encoder::new(&mut png, pixels.width(), pixels.height());
    enc.set_color(png::ColorType::Rgba);
    enc.set_depth(png::BitDepth::Eight);
    enc.set_compression(png::Compression::Fast);
    let bad =
        |e: png::EncodingError| crate::error::Error::Invalid(format!("a PNG of the frame: {e}"));
    let mut w = enc.write_header().map_err(bad)?;
    w.write_image_data(pixels.bytes()).map_err(bad)?;
    w.finish().map_err(bad)?;
    Ok(png)
}
