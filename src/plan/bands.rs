//! How many bands of sample rows a frame is drawn in: the plan's
//! threading, decided from the frame's size and the machine's cores.

use std::fmt;

use crate::options::{Aa, MAX_THREADS, PARALLEL_CELLS, PARALLEL_PIXELS, RenderOptions, Threads};
use crate::raster::{Precision, Traversal};
use crate::transform::MAX_GRID;

/// How many bands of sample rows a frame is drawn in (each by a thread of
/// its own, with the `parallel` feature), and why. Speed alone: every
/// band sets up each triangle that reaches it, clamped to its rows, and the
/// set-up's edge values are exact integers from any row, so the bands draw
/// exactly the samples one thread would, in the same order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Bands {
    /// Bands, one or more; never more than the frame's cell rows.
    pub count: u16,
    /// Why.
    pub why: &'static str,
}

impl fmt::Display for Bands {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:<4}  {}", self.count, self.why)
    }
}

/// The threads this process may run at once (asked once: the answer reads
/// files on Linux).
fn cores() -> u16 {
    static CORES: std::sync::OnceLock<u16> = std::sync::OnceLock::new();
    *CORES.get_or_init(|| {
        std::thread::available_parallelism().map_or(1, |n| n.get().min(MAX_THREADS as usize) as u16)
    })
}

/// How many bands `opts` asks for and allows.
pub(super) fn bands(opts: &RenderOptions) -> Bands {
    let one = |why| Bands { count: 1, why };
    if opts.aa != Aa::None {
        return one("anti-aliasing accumulates over the whole grid");
    }
    if opts.precision != Precision::Fixed {
        return one("the f64 and f32 set-ups draw the whole grid (comparison modes)");
    }
    if opts.traversal == Traversal::Scan {
        return one("a scan tests every sample of the grid");
    }
    let (w, h) = opts.cell_samples();
    if opts.cols == 0 || opts.rows == 0 {
        return one("an empty frame");
    }
    if opts.cols as u32 * w > MAX_GRID || opts.rows as u32 * h > MAX_GRID {
        // The grid is cut to its largest side, not to whole cells.
        return one("a frame beyond the largest grid");
    }
    let rows = opts.rows.max(1);
    let pixels = opts.cols as u32 * w * opts.rows as u32 * h;
    match opts.threads {
        Threads::Exactly(n) => Bands {
            count: n.clamp(1, MAX_THREADS).min(rows),
            why: "as many as asked for, at most one a cell row",
        },
        Threads::Auto if !cfg!(feature = "parallel") => one("built without the parallel feature"),
        Threads::Auto if opts.cell_pixels.is_some() && pixels < PARALLEL_PIXELS => {
            one("a frame under 640×360 pixels is faster on one thread")
        }
        Threads::Auto
            if opts.cell_pixels.is_none()
                && (opts.cols as u32 * opts.rows as u32) < PARALLEL_CELLS =>
        {
            one("a frame under 600×180 cells is faster on one thread")
        }
        Threads::Auto if cores() < 2 => one("one core"),
        Threads::Auto => Bands {
            count: cores().min(rows),
            why: "one a core, for a frame of 600×180 cells or 640×360 pixels or more",
        },
    }
}
