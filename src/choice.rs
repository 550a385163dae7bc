//! Settings chosen by name: every enum a user picks on the command line,
//! in a scene file or reads in `--explain` implements [`Choice`], so the
//! names live beside the values they name and a front end (the `rastty`
//! program's clap parser, a config file, a menu) lists and parses them
//! without a copy of its own.

/// A setting with a fixed set of named values.
pub trait Choice: Copy + Sized + 'static {
    /// Every value, in the order a list of them shows.
    const ALL: &'static [Self];

    /// The value's name (`--glyphs octant`).
    fn name(self) -> &'static str;

    /// One line saying what the value does.
    fn about(self) -> &'static str;

    /// The value named `name`, if there is one.
    fn named(name: &str) -> Option<Self> {
        Self::ALL.iter().copied().find(|v| v.name() == name)
    }
}

/// Implements [`Choice`] for an enum from a table of `Variant => "name":
/// "about"` rows.
macro_rules! choice {
    ($t:ty { $($v:ident => $name:literal : $about:literal),+ $(,)? }) => {
        impl $crate::choice::Choice for $t {
            const ALL: &'static [Self] = &[$(<$t>::$v),+];
            fn name(self) -> &'static str {
                match self { $(<$t>::$v => $name),+ }
            }
            fn about(self) -> &'static str {
                match self { $(<$t>::$v => $about),+ }
            }
        }
    };
}
pub(crate) use choice;
