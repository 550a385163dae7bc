//! The kitty graphics protocol: pixels sent as RGBA (`f=32`), compressed
//! with zlib (`o=z`), in base64, in chunks of at most 4096 bytes (the
//! protocol's limit), each an APC sequence `ESC _ G keys ; data ESC \`.
//!
//! A still ([`still`]) is one image placed at the cursor over `cols × rows`
//! cells (`c`, `r`), the cursor moved past it as text moves it, and the
//! terminal's answers silenced (`q=2`). An animation ([`Animation`])
//! transmits and places its first frame as image `id`, the cursor left
//! where it was (`C=1`); every later frame
//! edits that image's one frame in place (`a=f`, `r=1`), only the
//! rectangle of pixels that changed, replacing them rather than blending
//! (`X=1`: a pixel that became transparent clears), then shows the edit
//! (`a=a`, `c=1`). The image stays placed, so nothing flickers, and the
//! terminal draws a frame when it has it whole: nothing queues behind a
//! frame that is late. A change of size transmits the image anew.
//! [`delete`] removes the image and its placements, as every way out of
//! `spin` does.

use std::io::Write as _;

use flate2::{Compress, Compression, FlushCompress, Status};

use super::base64_into;
use crate::pixels::{PixelRect, Pixels};

/// The most base64 bytes one sequence carries.
const CHUNK: usize = 4096;

/// Appends `data` (already base64) as sequences with keys `keys` on the
/// first, `cont` on the others, `m=1` on every one but the last. A frame's
/// continuations repeat its action (`a=f,r=1,i=…`): kitty 0.26 takes a
/// continuation without it for a new image's.
fn chunked(keys: &str, cont: &str, data: &[u8], out: &mut Vec<u8>) {
    let mut chunks = data.chunks(CHUNK).peekable();
    let mut first = true;
    if chunks.peek().is_none() {
        let _ = write!(out, "\x1b_G{keys};\x1b\\");
        return;
    }
    while let Some(chunk) = chunks.next() {
        let more = u8::from(chunks.peek().is_some());
        out.extend_from_slice(b"\x1b_G");
        if first {
            let _ = write!(out, "{keys},m={more};");
            first = false;
        } else {
            let _ = write!(out, "{cont}m={more};");
        }
        out.extend_from_slice(chunk);
        out.extend_from_slice(b"\x1b\\");
    }
}

/// A zlib stream kept from frame to frame: one compressor reset for each
/// payload, and an output buffer initialised once and reused, so a frame
/// neither allocates nor clears the compressor's tables or its output.
#[derive(Debug)]
struct Zlib {
    compress: Compress,
    /// Initialised bytes; the first `len` of a payload are its stream.
    buf: Vec<u8>,
}

impl Zlib {
    fn new() -> Self {
        Self {
            compress: Compress::new(Compression::fast(), true),
            buf: Vec::new(),
        }
    }

    /// Compresses `input` into `buf` from the compressor's output so far,
    /// growing `buf` (the only time it is written with zeros) when full;
    /// returns once `input` is taken (or, finishing, the stream has ended).
    fn feed(&mut self, mut input: &[u8], flush: FlushCompress) {
        loop {
            let written = self.compress.total_out() as usize;
            if written == self.buf.len() {
                let grown = (self.buf.len() * 2).max(64 * 1024);
                self.buf.resize(grown, 0);
            }
            let before = self.compress.total_in();
            let status = self
                .compress
                .compress(input, &mut self.buf[written..], flush)
                .expect("deflate into a buffer with room");
            let used = (self.compress.total_in() - before) as usize;
            input = &input[used..];
            let done = match flush {
                FlushCompress::Finish => status == Status::StreamEnd,
                _ => input.is_empty(),
            };
            if done {
                return;
            }
        }
    }

    /// The pixels of `rect` (all of `pixels` for `None`), RGBA rows from
    /// the top, zlib-compressed (fast: most of a frame is transparent or
    /// repeated), then base64 appended to `out`.
    fn payload(&mut self, pixels: &Pixels, rect: PixelRect, out: &mut Vec<u8>) {
        self.compress.reset();
        for y in rect.y..rect.y + rect.height {
            let row = &pixels.row(y)[rect.x as usize..(rect.x + rect.width) as usize];
            self.feed(row.as_flattened(), FlushCompress::None);
        }
        self.feed(&[], FlushCompress::Finish);
        let len = self.compress.total_out() as usize;
        base64_into(&self.buf[..len], out);
    }
}

fn whole(pixels: &Pixels) -> PixelRect {
    PixelRect {
        x: 0,
        y: 0,
        width: pixels.width(),
        height: pixels.height(),
    }
}

/// Appends `pixels` as one image placed at the cursor over `cols × rows`
/// cells, the cursor moved past it: `render --graphics kitty`.
pub fn still(pixels: &Pixels, cols: u16, rows: u16, out: &mut Vec<u8>) {
    let mut data = Vec::new();
    Zlib::new().payload(pixels, whole(pixels), &mut data);
    let keys = format!(
        "a=T,f=32,o=z,s={},v={},c={cols},r={rows},q=2",
        pixels.width(),
        pixels.height()
    );
    chunked(&keys, "", &data, out);
}

/// Appends the command that deletes image `id` and its placements, freeing
/// its memory in the terminal.
pub fn delete(id: u32, out: &mut Vec<u8>) {
    let _ = write!(out, "\x1b_Ga=d,d=I,i={id},q=2\x1b\\");
}

/// Frames of one image, each sending what changed since the last.
#[derive(Debug)]
pub struct Animation {
    id: u32,
    /// What the terminal shows, and at how many cells.
    shown: Option<(Pixels, u16, u16)>,
    /// Placed below the text (`z=-1`): text written over it shows.
    below: bool,
    zlib: Zlib,
    data: Vec<u8>,
}

impl Animation {
    /// An animation shown as image `id` (choose one no other program in
    /// the terminal uses).
    pub fn new(id: u32) -> Animation {
        Animation {
            id,
            shown: None,
            below: false,
            zlib: Zlib::new(),
            data: Vec::new(),
        }
    }

    /// Places the image below the text (`z=-1`), so that text written over
    /// it shows (a help box), and blanks in the terminal's default colours
    /// let it through.
    pub fn below_text(mut self) -> Animation {
        self.below = true;
        self
    }

    /// The image's id.
    pub fn id(&self) -> u32 {
        self.id
    }

    /// Appends `pixels` as the next frame, placed at the cursor over `cols
    /// × rows` cells where it is the first (or its size changed), else the
    /// rectangle that changed edited in place; nothing where nothing
    /// changed. Returns the rectangle sent.
    pub fn frame(
        &mut self,
        pixels: &Pixels,
        cols: u16,
        rows: u16,
        out: &mut Vec<u8>,
    ) -> Option<PixelRect> {
        let same_size = self.shown.as_ref().is_some_and(|(p, c, r)| {
            (p.width(), p.height(), *c, *r) == (pixels.width(), pixels.height(), cols, rows)
        });
        let rect = if same_size {
            let (before, _, _) = self.shown.as_ref().expect("shown");
            let rect = pixels.changed_since(before)?;
            self.data.clear();
            self.zlib.payload(pixels, rect, &mut self.data);
            let keys = format!(
                "a=f,r=1,i={},f=32,o=z,x={},y={},s={},v={},X=1,q=2",
                self.id, rect.x, rect.y, rect.width, rect.height
            );
            let cont = format!("a=f,r=1,i={},q=2,", self.id);
            chunked(&keys, &cont, &self.data, out);
            let _ = write!(out, "\x1b_Ga=a,c=1,i={},q=2\x1b\\", self.id);
            rect
        } else {
            if self.shown.is_some() {
                delete(self.id, out);
            }
            let rect = whole(pixels);
            self.data.clear();
            self.zlib.payload(pixels, rect, &mut self.data);
            let keys = format!(
                "a=T,i={},p=1,f=32,o=z,s={},v={},c={cols},r={rows},C=1,q=2{}",
                self.id,
                pixels.width(),
                pixels.height(),
                if self.below { ",z=-1" } else { "" }
            );
            chunked(&keys, "", &self.data, out);
            rect
        };
        match &mut self.shown {
            Some((p, c, r)) => {
                p.clone_from(pixels);
                (*c, *r) = (cols, rows);
            }
            None => self.shown = Some((pixels.clone(), cols, rows)),
        }
        Some(rect)
    }

    /// Forgets what the terminal shows: the next frame is sent whole.
    pub fn forget(&mut self) {
        self.shown = None;
    }

    /// Appends the command that deletes the image, and forgets it.
    pub fn delete(&mut self, out: &mut Vec<u8>) {
        delete(self.id, out);
        self.shown = None;
    }
}
