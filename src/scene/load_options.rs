//! How model and scene files are read: the loaders' budgets and choices.

use super::{ColorSpace, file, mesh, transform};

/// How model and scene files are read.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoadOptions {
    /// The largest file read, in bytes (a larger one is refused before it
    /// is opened).
    pub max_bytes: u64,
    /// How MTL `Kd` numbers are read: linear light by default, as
    /// exporters write them.
    pub mtl_colors: ColorSpace,
    /// The crease angle of computed normals, in degrees: faces meeting at
    /// a sharper angle keep their own normals along the edge.
    pub crease: f32,
    /// For a model shown alone: which of its axes points up (`None`: the
    /// format's convention, y for OBJ, z for STL).
    pub up: Option<transform::Axis>,
    /// The most texels decoded, across all of a scene's images
    /// ([`DEFAULT_MAX_TEXELS`]); each costs its linear texel, its mipmaps'
    /// share and, while it is decoded, its 8-bit pixel. An image's size is
    /// read from its header and refused before it is decoded.
    pub max_texels: u64,
    /// The most triangles a scene may draw once every glTF node and every
    /// scene mesh is counted as often as it is placed
    /// ([`DEFAULT_MAX_TRIANGLES`]), counted before anything is expanded.
    pub max_triangles: u64,
    /// The largest side of a texture's finest level
    /// ([`crate::texture::MAX_SIDE`] by default): an image larger is
    /// halved as it is decoded until it fits, so a scene's textures take
    /// the memory the frames that show them need (see
    /// [`texture_side_for`]).
    pub max_texture_side: u32,
}

/// The largest texture side a frame of `samples` (across, down) can read
/// the finest level of, where a model may be zoomed up to `zoom` times its
/// fitted size: a texture mapped over the whole model at one texel a sample
/// at that zoom, twice over (a texture whose coordinates cover part of it,
/// an atlas, reads finer); a power of two from 256 to
/// [`crate::texture::MAX_SIDE`].
pub fn texture_side_for(samples: (u32, u32), zoom: f32) -> u32 {
    let longest = samples.0.max(samples.1) as f32 * zoom.max(1.0) * 2.0;
    let side = if longest.is_finite() {
        longest as u32
    } else {
        u32::MAX
    };
    side.clamp(256, crate::texture::MAX_SIDE)
        .next_power_of_two()
        .min(crate::texture::MAX_SIDE)
}

/// The default texel budget: 64 Mi texels (an 8192² image, or four of
/// 4096²), about 1 GiB of linear texels with their mipmaps.
pub const DEFAULT_MAX_TEXELS: u64 = 1 << 26;
/// The default triangle budget: 256 Mi triangles placed (the largest
/// shared model has 41 thousand; a frame of that many takes seconds).
pub const DEFAULT_MAX_TRIANGLES: u64 = 1 << 28;

impl Default for LoadOptions {
    fn default() -> Self {
        LoadOptions {
            max_bytes: file::DEFAULT_MAX_BYTES,
            mtl_colors: ColorSpace::Linear,
            crease: mesh::DEFAULT_CREASE,
            up: None,
            max_texels: DEFAULT_MAX_TEXELS,
            max_triangles: DEFAULT_MAX_TRIANGLES,
            max_texture_side: crate::texture::MAX_SIDE,
        }
    }
}
