//! A frame's pixels ([`crate::Pixels`]) as a terminal that shows images
//! takes them: the kitty graphics protocol ([`kitty`]: kitty, Ghostty,
//! WezTerm, Konsole), sixel ([`sixel`]: foot, WezTerm, xterm as a VT340,
//! Konsole, Windows Terminal) and iTerm2's inline images ([`iterm`]:
//! iTerm2, WezTerm, VS Code). Each writes bytes to put at the cursor; none
//! knows how the pixels were drawn, and the stages know nothing of them.
//!
//! What each keeps of a picture: kitty and iTerm2 take every pixel as it
//! is, alpha included (a pixel nothing covers is transparent, showing the
//! terminal's own background); sixel takes at most the terminal's colour
//! registers, so its pixels are mapped onto xterm's 256 colours (or 16)
//! with the same ordered dithering the character cells use at that depth,
//! and a transparent pixel is left unpainted.

pub mod iterm;
pub mod kitty;
pub mod sixel;

/// Which protocol a terminal shows pixels by.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Protocol {
    /// The kitty graphics protocol.
    Kitty,
    /// DEC sixel graphics.
    Sixel,
    /// iTerm2's inline images (OSC 1337).
    Iterm,
}

crate::choice::choice!(Protocol {
    Kitty => "kitty": "The kitty graphics protocol: kitty, Ghostty, WezTerm, Konsole",
    Sixel => "sixel": "DEC sixel graphics: foot, WezTerm, xterm -ti vt340, Konsole, Windows Terminal",
    Iterm => "iterm": "iTerm2's inline images: iTerm2, WezTerm, VS Code",
});

/// Appends `bytes` as standard base64 (with padding) to `out`.
pub(crate) fn base64_into(bytes: &[u8], out: &mut Vec<u8>) {
    use base64::Engine;
    let start = out.len();
    out.resize(start + bytes.len().div_ceil(3) * 4, 0);
    let n = base64::engine::general_purpose::STANDARD
        .encode_slice(bytes, &mut out[start..])
        .expect("sized for the encoding");
    out.truncate(start + n);
}
