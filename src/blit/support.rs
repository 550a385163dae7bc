//! Which glyph modes a terminal draws one cell wide, asked of it.
//!
//! A terminal draws a character as wide as its own tables say, and those
//! differ: Debian 12's C library gives the Unicode 16 octants no width, so
//! tmux drops them and an octant frame smears. The only way to know is to
//! ask: write a glyph of each family a mode needs at the start of a line
//! and read where the cursor went (a cursor position report). A family
//! whose glyph does not move the cursor by exactly one cell is unusable,
//! and a mode falls back to the best usable one (octant → sextant →
//! quadrant → half; braille → sextant → …).
//!
//! This is the question without the input and output: [`GlyphSupport::ask`]
//! takes a function that writes a glyph and reports the column, so that a
//! ratatui or crossterm application can ask through its own terminal
//! (crossterm's `cursor::position`), as `rastty spin` asks through its own
//! in one round trip with its other queries.

use super::GlyphMode;

/// A family of glyphs beyond the half blocks, which every terminal draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GlyphFamily {
    /// Quadrant block elements (U+2596–U+259F).
    Quadrant,
    /// Sextants (U+1FB00–U+1FB3B).
    Sextant,
    /// Octants (U+1CD00–U+1CDE5) and the Unicode 16 quarter blocks beside
    /// them, and the Unicode 13 middle quarters (U+1FBE6/7).
    Octant,
    /// Braille patterns (U+2800–U+28FF).
    Braille,
}

impl GlyphFamily {
    /// Every family, in the order [`GlyphSupport::families`] keeps them.
    pub const ALL: [GlyphFamily; 4] = [
        GlyphFamily::Quadrant,
        GlyphFamily::Sextant,
        GlyphFamily::Octant,
        GlyphFamily::Braille,
    ];

    /// The characters written to test the family: one from each block of
    /// Unicode the family's table draws from.
    pub fn probes(self) -> &'static [char] {
        match self {
            GlyphFamily::Quadrant => &['\u{259F}'],
            GlyphFamily::Sextant => &['\u{1FB00}'],
            GlyphFamily::Octant => &['\u{1CD00}', '\u{1CEA8}', '\u{1FBE6}'],
            GlyphFamily::Braille => &['\u{28FF}'],
        }
    }

    /// The families a mode's glyphs come from.
    pub fn of(mode: GlyphMode) -> &'static [GlyphFamily] {
        match mode {
            GlyphMode::Ascii | GlyphMode::Block | GlyphMode::Half => &[],
            GlyphMode::Quadrant => &[GlyphFamily::Quadrant],
            GlyphMode::Sextant => &[GlyphFamily::Sextant],
            GlyphMode::Octant => &[GlyphFamily::Octant, GlyphFamily::Quadrant],
            GlyphMode::Braille => &[GlyphFamily::Braille],
        }
    }
}

/// Which glyph families the terminal draws one cell wide; `None` where it
/// did not say (taken as usable, as without asking).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GlyphSupport {
    /// Per family (in [`GlyphFamily::ALL`] order): whether each probe glyph moved
    /// the cursor by exactly one cell.
    pub families: [Option<bool>; 4],
}

impl GlyphSupport {
    /// Asks the terminal: `advance(c)` writes `c` at the first column of a
    /// line (column 0) and returns the column the cursor is at after it,
    /// `None` if the terminal did not say. The first `None` ends the asking
    /// (a terminal that does not answer one will not answer the next: each
    /// would cost the caller's timeout); what was not asked stays unknown.
    pub fn ask<E>(
        mut advance: impl FnMut(char) -> Result<Option<u16>, E>,
    ) -> Result<GlyphSupport, E> {
        let mut columns = Vec::new();
        'ask: for f in GlyphFamily::ALL {
            for &c in f.probes() {
                match advance(c)? {
                    Some(col) => columns.push(col + 1),
                    None => break 'ask,
                }
            }
        }
        Ok(GlyphSupport::from_columns(&columns))
    }

    /// Reads the answers to the probe glyphs written in turn, each at column
    /// 1 (as cursor position reports count): `columns[k]` is where the
    /// cursor was after the `k`-th probe glyph of [`GlyphFamily::ALL`]'s
    /// [`GlyphFamily::probes`]; missing answers leave their families unknown.
    pub fn from_columns(columns: &[u16]) -> GlyphSupport {
        let mut support = GlyphSupport::default();
        let mut cols = columns.iter();
        for (i, f) in GlyphFamily::ALL.iter().enumerate() {
            let mut verdict = Some(true);
            for _ in f.probes() {
                // One cell wide leaves the cursor at column 2.
                match cols.next() {
                    Some(&col) if col != 2 => verdict = Some(false),
                    Some(_) => {}
                    // Unknown, unless one glyph already failed.
                    None if verdict == Some(true) => verdict = None,
                    None => {}
                }
            }
            support.families[i] = verdict;
        }
        support
    }

    /// Whether `mode`'s glyphs are drawn one cell wide (or not known not to
    /// be).
    pub fn usable(&self, mode: GlyphMode) -> bool {
        GlyphFamily::of(mode).iter().all(|f| {
            let i = GlyphFamily::ALL.iter().position(|g| g == f).unwrap_or(0);
            self.families[i] != Some(false)
        })
    }

    /// `mode`, or the best usable mode it falls back to.
    pub fn best(&self, mode: GlyphMode) -> GlyphMode {
        let chain: &[GlyphMode] = match mode {
            GlyphMode::Octant => &[GlyphMode::Octant, GlyphMode::Sextant, GlyphMode::Quadrant],
            GlyphMode::Braille => &[GlyphMode::Braille, GlyphMode::Sextant, GlyphMode::Quadrant],
            GlyphMode::Sextant => &[GlyphMode::Sextant, GlyphMode::Quadrant],
            other => return other,
        };
        chain
            .iter()
            .copied()
            .find(|&m| self.usable(m))
            .unwrap_or(GlyphMode::Half)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn asking_stops_at_the_first_silence_and_reads_widths() {
        // Quadrant and sextant one cell wide, the first octant probe none.
        let mut asked = Vec::new();
        let answers = [Some(1), Some(1), Some(0), None];
        let support = GlyphSupport::ask(|c| {
            asked.push(c);
            Ok::<_, ()>(answers[asked.len() - 1])
        })
        .unwrap();
        assert_eq!(asked, ['\u{259F}', '\u{1FB00}', '\u{1CD00}', '\u{1CEA8}']);
        assert_eq!(
            support.families,
            [Some(true), Some(true), Some(false), None]
        );
        assert_eq!(support.best(GlyphMode::Octant), GlyphMode::Sextant);
        assert_eq!(support.best(GlyphMode::Braille), GlyphMode::Braille);
    }
}
