//! `rastty bench`: every accuracy knob's time and error on the same
//! scenes (`crate::bench`), as a table on stdout and a plot in a file.

use std::io::Write as _;

use crate::bench;
use crate::say::{say, say_lines, stdout, stdout_error};
use rastty::outfile::OutFile;

/// `rastty bench`: the table on stdout, the plot in its file.
pub fn bench(args: &crate::cli::BenchArgs) -> rastty::Result<()> {
    // The plot's file is begun before the work, which takes minutes.
    let mut svg = OutFile::create(&args.svg)?;
    let models = match &args.models {
        Some(dir) if !dir.is_dir() => {
            return Err(rastty::Error::Invalid(format!(
                "{}: not a folder of models (--models)",
                dir.display()
            )));
        }
        Some(dir) => dir.clone(),
        None => std::path::PathBuf::from("../shared/models"),
    };
    let (workloads, notes) = if models.is_dir() {
        bench::workloads(&models)
    } else {
        (
            bench::workloads(&models).0,
            vec![format!(
                "{}: not found: the built-in scenes alone are timed (--models names a folder)",
                models.display()
            )],
        )
    };
    for note in &notes {
        say("note", note);
    }
    let mut out = stdout()?;
    let report = bench::run(&workloads, args.reps as usize);
    writeln!(
        out,
        "Time per frame at 200×60 cells (median of {} frames; rendering, or encoding for quantisation), and each knob's error.",
        args.reps
    )
    .and_then(|()| write!(out, "{}", report.markdown()))
    .map_err(stdout_error)?;
    let plot = report
        .svg()
        .map_err(|e| rastty::Error::Invalid(format!("{}: {e}", args.svg.display())))?;
    svg.write_all(plot.as_bytes())
        .map_err(|e| rastty::Error::io(&args.svg, e))?;
    svg.commit()?;
    say_lines(&format!(
        "wrote {}",
        rastty::text::line(&args.svg.display().to_string())
    ));
    Ok(())
}
