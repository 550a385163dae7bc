//! The report: a Markdown table per knob and an SVG plot of error
//! against time.

use super::*;

impl Report {
    /// The table, one section per knob.
    pub fn markdown(&self) -> String {
        let mut out = String::new();
        let mut knob = "";
        for row in &self.rows {
            if row.knob != knob {
                knob = row.knob;
                let _ = writeln!(out, "\n### {knob}\n");
                let errors: Vec<&str> = row.errors.iter().map(|e| e.0).collect();
                let _ = writeln!(
                    out,
                    "| setting | {} | {} |",
                    errors.join(" | "),
                    self.workloads
                        .iter()
                        .map(|w| format!("{w} (ms)"))
                        .collect::<Vec<_>>()
                        .join(" | ")
                );
                let _ = writeln!(
                    out,
                    "|---|{}{}",
                    "---:|".repeat(errors.len()),
                    "---:|".repeat(self.workloads.len())
                );
            }
            let errors: Vec<String> = row.errors.iter().map(|e| fmt_error(e.1)).collect();
            let times: Vec<String> = row
                .times
                .iter()
                .map(|t| format!("{:.2}", t.as_secs_f64() * 1e3))
                .collect();
            let _ = writeln!(
                out,
                "| {} | {} | {} |",
                row.setting,
                errors.join(" | "),
                times.join(" | ")
            );
        }
        out
    }

    /// An SVG plot: for each knob, its settings' first error measure
    /// (relative to the knob's worst) against time per frame on the
    /// workload where the knob's settings differ most in time (texture
    /// filtering costs nothing on a scene without textures).
    pub fn svg(&self) -> Result<String, String> {
        use plotters::prelude::*;
        let mut out = String::new();
        let root = SVGBackend::with_string(&mut out, (960, 640)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        // Per knob, the workload whose times spread the most (relatively).
        let mut on: std::collections::BTreeMap<&str, usize> = Default::default();
        for knob in self.rows.iter().map(|r| r.knob) {
            let rows = || self.rows.iter().filter(|r| r.knob == knob);
            let spread = |w: usize| {
                let t = || {
                    rows()
                        .filter_map(|r| r.times.get(w))
                        .map(Duration::as_secs_f64)
                };
                let (lo, hi) = (t().fold(f64::INFINITY, f64::min), t().fold(0.0, f64::max));
                if lo > 0.0 { hi / lo } else { 0.0 }
            };
            let best = (0..self.workloads.len())
                .max_by(|&a, &b| spread(a).total_cmp(&spread(b)))
                .unwrap_or(0);
            on.insert(knob, best);
        }
        let ms = |r: &Row| {
            r.times
                .get(on.get(r.knob).copied().unwrap_or(0))
                .map_or(0.0, |t| t.as_secs_f64() * 1e3)
        };
        let x_max = self.rows.iter().map(ms).fold(0.0, f64::max) * 2.0 + 1e-3;
        let x_min = self
            .rows
            .iter()
            .map(ms)
            .filter(|&t| t > 0.0)
            .fold(f64::INFINITY, f64::min)
            .min(x_max)
            / 2.0;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                "rastty: error against time per frame, one series per knob",
                ("sans-serif", 22),
            )
            .margin(16)
            .x_label_area_size(44)
            .y_label_area_size(56)
            .build_cartesian_2d((x_min..x_max).log_scale(), -0.02..1.05)
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc(
                "time per frame (ms, log scale) on the scene where the knob's settings differ most",
            )
            .y_desc("error, relative to the knob's worst setting")
            .draw()
            .map_err(|e| e.to_string())?;
        let knobs: Vec<&str> = self
            .rows
            .iter()
            .map(|r| r.knob)
            .collect::<BTreeSet<_>>()
            .into_iter()
            .collect();
        for (i, knob) in knobs.iter().enumerate() {
            let color = Palette99::pick(i).to_rgba();
            let rows: Vec<&Row> = self.rows.iter().filter(|r| r.knob == *knob).collect();
            let worst = rows.iter().map(|r| r.errors[0].1).fold(0.0, f64::max);
            let mut pts: Vec<(f64, f64)> = rows
                .iter()
                .map(|r| {
                    (
                        ms(r).max(x_min),
                        if worst > 0.0 {
                            r.errors[0].1 / worst
                        } else {
                            0.0
                        },
                    )
                })
                .collect();
            // The frontier reads left to right: sorted by time.
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            chart
                .draw_series(pts.iter().map(|&p| Circle::new(p, 5, color.filled())))
                .map_err(|e| e.to_string())?
                .label(format!(
                    "{knob} ({})",
                    self.workloads
                        .get(on.get(knob).copied().unwrap_or(0))
                        .map_or("", String::as_str)
                ))
                .legend(move |(x, y)| Circle::new((x, y), 5, color.filled()));
            chart
                .draw_series(LineSeries::new(pts.clone(), color.stroke_width(1)))
                .map_err(|e| e.to_string())?;
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(|e| e.to_string())?;
        root.present().map_err(|e| e.to_string())?;
        drop(chart);
        drop(root);
        Ok(out)
    }
}

pub(super) fn fmt_error(e: f64) -> String {
    if e == e.trunc() && e.abs() < 1e9 {
        format!("{e:.0}")
    } else if e.abs() >= 0.1 {
        format!("{e:.2}")
    } else if e.abs() >= 1e-4 {
        format!("{e:.4}")
    } else {
        format!("{e:.1e}")
    }
}
