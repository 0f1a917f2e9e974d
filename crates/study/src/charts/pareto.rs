//! Error against CPU time, log-log, per method: the Pareto front of speed
//! and accuracy.

use super::{draw_empty, family_color, log_bounds, sci, series_legend, Chart};
use crate::engine::StudyResult;
use crate::method::MethodFamily;
use crate::outcome::Status;
use crate::stats;
use plotters::coord::Shift;
use plotters::prelude::*;

pub struct Pareto<'a> {
    pub result: &'a StudyResult,
}

impl Chart for Pareto<'_> {
    fn kind(&self) -> &'static str {
        "pareto"
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let r = self.result;
        let title = format!("{}: error against CPU time", r.spec.name);
        // Converged runs (filled) and wrong answers (crosses) with an error.
        let runs: Vec<_> = r
            .records
            .iter()
            .filter(|x| matches!(x.status, Status::Converged | Status::Wrong))
            .filter(|x| x.error.is_some_and(|e| e > 0.0) && x.seconds() > 0.0)
            .collect();
        let (Some((t0, t1)), Some((e0, e1))) = (
            log_bounds(runs.iter().map(|x| x.seconds())),
            log_bounds(runs.iter().filter_map(|x| x.error)),
        ) else {
            return draw_empty(root, &title, "no run with a positive error to plot");
        };
        let mut chart = ChartBuilder::on(root)
            .caption(&title, ("sans-serif", 24))
            .margin(15)
            .x_label_area_size(50)
            .y_label_area_size(80)
            .build_cartesian_2d((t0..t1).log_scale(), (e0..e1).log_scale())
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc("CPU time (s)")
            .y_desc(format!("relative error of {}", r.quantity))
            .x_label_formatter(&sci)
            .y_label_formatter(&sci)
            .draw()
            .map_err(|e| e.to_string())?;
        for family in MethodFamily::ALL {
            let color = family_color(family);
            let mine: Vec<_> = runs
                .iter()
                .filter(|x| x.point.method.family() == family)
                .collect();
            if mine.is_empty() {
                continue;
            }
            let converged: Vec<(f64, f64)> = mine
                .iter()
                .filter(|x| x.status == Status::Converged)
                .filter_map(|x| Some((x.seconds(), x.error?)))
                .collect();
            chart
                .draw_series(converged.iter().map(|&p| Circle::new(p, 5, color.filled())))
                .map_err(|e| e.to_string())?
                .label(family.name())
                .legend(move |(x, y)| Circle::new((x + 10, y), 5, color.filled()));
            let wrong: Vec<(f64, f64)> = mine
                .iter()
                .filter(|x| x.status == Status::Wrong)
                .filter_map(|x| Some((x.seconds(), x.error?)))
                .collect();
            chart
                .draw_series(
                    wrong
                        .iter()
                        .map(|&p| Cross::new(p, 6, color.stroke_width(2))),
                )
                .map_err(|e| e.to_string())?;
        }
        let front: Vec<(f64, f64)> = stats::pareto_front(r)
            .iter()
            .filter_map(|x| Some((x.seconds(), x.error.filter(|e| *e > 0.0)?)))
            .collect();
        if front.len() >= 2 {
            chart
                .draw_series(LineSeries::new(front, BLACK.stroke_width(1)))
                .map_err(|e| e.to_string())?
                .label("Pareto front (x: wrong answer)")
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK));
        }
        series_legend(&mut chart, SeriesLabelPosition::UpperRight, 14)
    }
}
