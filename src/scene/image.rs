//! Image files for textures (an OBJ material's `map_Kd`): PNG and JPEG,
//! decoded by the `image` crate (feature `textures`) and turned into a
//! [`Texture`] (linear texels and mipmaps).
//!
//! The format is told by the bytes, not the name. An image's size is read
//! from its header and held to the texel budget
//! ([`super::LoadOptions::max_texels`]) before a pixel is decoded: a 33 KB
//! PNG that says 16384² (268 million texels, 3 GB as linear light) is an
//! error at once. The decoder is also held to
//! [`MAX_IMAGE_SIDE`] pixels a side and [`MAX_DECODE_BYTES`] of memory, so
//! a header that claims a huge image is refused before anything that size
//! is allocated; an image that fits but is larger than
//! [`crate::texture::MAX_SIDE`] is then reduced at load.

use std::io::Cursor;
use std::path::Path;

use image::{ImageFormat, ImageReader, Limits};

use super::file;
use crate::texture::{Sampler, Texture};

/// The widest and tallest image decoded.
pub const MAX_IMAGE_SIDE: u32 = 16384;
/// The most memory the decoder may take for one image.
pub const MAX_DECODE_BYTES: u64 = 512 << 20;

/// Reads and decodes the image `file` at `path` (opened as the model
/// itself is), within `max_texels`, its finest level at most `max_side` on
/// a side; the error says what is wrong, naming the file.
pub fn load(
    mut file: file::Opened<'_>,
    path: &Path,
    sampler: Sampler,
    (max_texels, max_side): (u64, u32),
) -> Result<Texture, String> {
    use std::io::Read;
    let name = path.display().to_string();
    let mut bytes = Vec::with_capacity(usize::try_from(file.size()).unwrap_or(0));
    file.read_to_end(&mut bytes)
        .map_err(|e| format!("{name}: {e}"))?;
    decode(&bytes, &name, sampler, (max_texels, max_side)).map_err(|e| format!("{name}: {e}"))
}

/// An image's 8-bit pixels as decoded (grey, grey and alpha, RGB or RGBA:
/// no copy for an 8-bit image), with its size and channels.
fn pixels(image: &image::DynamicImage) -> (std::borrow::Cow<'_, [u8]>, (u32, u32, usize)) {
    use image::DynamicImage as D;
    let (w, h) = (image.width(), image.height());
    match image {
        D::ImageLuma8(i) => (i.as_raw().into(), (w, h, 1)),
        D::ImageLumaA8(i) => (i.as_raw().into(), (w, h, 2)),
        D::ImageRgb8(i) => (i.as_raw().into(), (w, h, 3)),
        D::ImageRgba8(i) => (i.as_raw().into(), (w, h, 4)),
        other => (other.to_rgba8().into_raw().into(), (w, h, 4)),
    }
}

/// Decodes PNG or JPEG bytes into a texture named `name`, refusing (from
/// the header, before decoding) an image of more than `max_texels` pixels,
/// its finest level at most `max_side` on a side.
pub fn decode(
    bytes: &[u8],
    name: &str,
    sampler: Sampler,
    (max_texels, max_side): (u64, u32),
) -> Result<Texture, String> {
    let image = open(bytes, max_texels)?;
    let (raw, size) = pixels(&image);
    let texel = crate::texture::srgb_texel(size.2);
    Texture::from_pixels(name, size, &raw, sampler, texel, max_side)
}

/// Decodes PNG or JPEG bytes whose numbers are not colours (a normal,
/// metallic-roughness or occlusion map) into a texture of their values
/// over 255, not sRGB-decoded; under the same checks and budget as
/// [`decode`].
#[cfg(feature = "gltf")]
pub fn decode_linear(
    bytes: &[u8],
    name: &str,
    sampler: Sampler,
    (max_texels, max_side): (u64, u32),
) -> Result<Texture, String> {
    let image = open(bytes, max_texels)?;
    let (raw, size) = pixels(&image);
    let value = |v: u8| f32::from(v) / 255.0;
    let texel = |p: &[u8]| match p.len() {
        1 | 2 => [value(p[0]); 3],
        _ => [value(p[0]), value(p[1]), value(p[2])],
    };
    Texture::from_pixels(name, size, &raw, sampler, texel, max_side)
}

/// The alpha channel of a PNG image as a texture (linear, as alpha is, in
/// every channel), `None` for an image without one; under the same checks
/// and budget as [`decode`].
#[cfg(feature = "gltf")]
pub fn decode_alpha(
    bytes: &[u8],
    name: &str,
    sampler: Sampler,
    (max_texels, max_side): (u64, u32),
) -> Result<Option<Texture>, String> {
    let image = open(bytes, max_texels)?;
    if !image.color().has_alpha() {
        return Ok(None);
    }
    let (raw, size) = pixels(&image);
    let alpha = |p: &[u8]| [f32::from(p[p.len() - 1]) / 255.0; 3];
    Texture::from_pixels(
        format!("{name} (alpha)"),
        size,
        &raw,
        sampler,
        alpha,
        max_side,
    )
    .map(Some)
}

/// A PNG or JPEG image decoded within the side, allocation and texel limits.
fn open(bytes: &[u8], max_texels: u64) -> Result<image::DynamicImage, String> {
    use image::ImageDecoder as _;
    let format = match image::guess_format(bytes) {
        Ok(f @ (ImageFormat::Png | ImageFormat::Jpeg)) => f,
        Ok(other) => {
            return Err(format!(
                "a {other:?} image, which rastty does not read (PNG or JPEG)"
            ));
        }
        Err(_) => return Err("not a PNG or JPEG image".into()),
    };
    let mut reader = ImageReader::with_format(Cursor::new(bytes), format);
    let mut limits = Limits::default();
    limits.max_image_width = Some(MAX_IMAGE_SIDE);
    limits.max_image_height = Some(MAX_IMAGE_SIDE);
    limits.max_alloc = Some(MAX_DECODE_BYTES);
    reader.limits(limits);
    let decoder = reader.into_decoder().map_err(in_words)?;
    let (w, h) = decoder.dimensions();
    let texels = u64::from(w) * u64::from(h);
    if texels > max_texels {
        return Err(format!(
            "a {w}×{h} image is {texels} texels, more than the {max_texels} left in the texel budget (--max-texels raises it)"
        ));
    }
    image::DynamicImage::from_decoder(decoder).map_err(in_words)
}

/// A decoder's error in words: what is wrong with the image, never the
/// decoder's own types (`ChunkType { type: IHDR, … }`) or its line breaks.
fn in_words(e: image::ImageError) -> String {
    use image::ImageError;
    match e {
        ImageError::Decoding(d) => {
            let format = match d.format_hint() {
                image::error::ImageFormatHint::Exact(ImageFormat::Png) => "PNG",
                image::error::ImageFormatHint::Exact(ImageFormat::Jpeg) => "JPEG",
                _ => "an",
            };
            let why =
                std::error::Error::source(&d).map_or(String::new(), |s| plain(&s.to_string()));
            let article = if format == "an" { "" } else { "a " };
            let what = if format == "an" {
                "a damaged image".to_string()
            } else {
                format!("{article}damaged {format} image")
            };
            if why.is_empty() {
                what
            } else {
                format!("{what} ({why})")
            }
        }
        ImageError::Limits(_) => format!(
            "an image that needs more memory to decode than the {} MiB allowed, or more than {MAX_IMAGE_SIDE} pixels a side",
            MAX_DECODE_BYTES >> 20
        ),
        ImageError::Unsupported(u) => {
            format!("an image rastty cannot read ({})", plain(&u.to_string()))
        }
        ImageError::IoError(e) => plain(&e.to_string()),
        other => plain(&other.to_string()),
    }
}

/// A decoder's message on one line, in words: line breaks and tabs taken
/// out, a type shown by its `Debug` (`ChunkType { type: IHDR, … }`) by
/// its name, the decoders' prefixes (`I/O errors`) dropped.
fn plain(message: &str) -> String {
    let mut s: String = message
        .split(['\n', '\r', '\t'])
        .map(str::trim)
        .filter(|p| !p.is_empty())
        .collect::<Vec<_>>()
        .join("; ");
    while let Some(i) = s.find("ChunkType { type: ") {
        let rest = &s[i + "ChunkType { type: ".len()..];
        let name = rest.split([',', ' ', '}']).next().unwrap_or("").to_string();
        let end = rest
            .find('}')
            .map_or(s.len(), |j| i + "ChunkType { type: ".len() + j + 1);
        s.replace_range(i..end, &name);
    }
    let s = s.trim_start_matches("I/O errors").trim();
    let s = s.trim_end_matches('.');
    // A sentence's capital dropped (not an acronym's: `CRC error`).
    let mut chars = s.chars();
    match (chars.next(), chars.next()) {
        (Some(c), Some(d)) if d.is_lowercase() => {
            c.to_lowercase().chain([d]).chain(chars).collect()
        }
        _ => s.to_string(),
    }
}
