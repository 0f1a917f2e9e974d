//! Error against mesh size, log-log, with the fitted slope per method.

use super::{draw_empty, family_color, log_bounds, sci, series_legend, Chart};
use crate::engine::StudyResult;
use crate::stats;
use plotters::coord::Shift;
use plotters::prelude::*;

pub struct ConvergenceChart<'a> {
    pub result: &'a StudyResult,
}

impl Chart for ConvergenceChart<'_> {
    fn kind(&self) -> &'static str {
        "convergence"
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let r = self.result;
        let title = format!("{}: error against mesh size", r.spec.name);
        let series = stats::convergence_series(r);
        let all = || series.iter().flat_map(|c| c.points.iter().copied());
        let (Some((h0, h1)), Some((e0, e1))) = (
            log_bounds(all().map(|p| p.0)),
            log_bounds(all().map(|p| p.1)),
        ) else {
            return draw_empty(root, &title, "no method converged on two mesh sizes");
        };
        let mut chart = ChartBuilder::on(root)
            .caption(&title, ("sans-serif", 24))
            .margin(15)
            .x_label_area_size(50)
            .y_label_area_size(80)
            .build_cartesian_2d((h0..h1).log_scale(), (e0..e1).log_scale())
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc("mesh size h near the contact")
            .y_desc(format!("relative error of {}", r.quantity))
            .x_label_formatter(&sci)
            .y_label_formatter(&sci)
            .draw()
            .map_err(|e| e.to_string())?;
        let several_settings = r.spec.settings().len() > 1;
        for (i, c) in series.iter().enumerate() {
            // Family colour, lightened along the family's coefficients.
            let base = family_color(c.method.family());
            let k = series[..i]
                .iter()
                .filter(|o| o.method.family() == c.method.family())
                .count();
            let color = base.mix(1.0 - 0.12 * (k % 6) as f64);
            let mut label = c.method.label();
            if several_settings {
                label.push_str(&format!(", {}", c.setting.label(&r.spec)));
            }
            if let Some(s) = c.slope {
                label.push_str(&format!(": slope {s:.2}"));
            }
            chart
                .draw_series(LineSeries::new(c.points.clone(), color.stroke_width(2)))
                .map_err(|e| e.to_string())?
                .label(label)
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
            chart
                .draw_series(c.points.iter().map(|&p| Circle::new(p, 4, color.filled())))
                .map_err(|e| e.to_string())?;
        }
        series_legend(&mut chart, SeriesLabelPosition::LowerRight, 13)
    }
}
