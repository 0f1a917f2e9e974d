//! Curves against a common abscissa, one line per series with its legend:
//! what `aster plot` draws from the tables and functions a case writes
//! (a force–displacement curve, a contact pressure along a line).

use super::{draw_empty, log_bounds, render_file, sci, series_legend, Chart};
use crate::error::StudyError;
use plotters::coord::ranged1d::{AsRangedCoord, Ranged, ValueFormatter};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// One curve: its legend and its points in drawing order.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
}

/// Curves on shared axes, each axis linear or logarithmic.
#[derive(Clone, Debug, PartialEq)]
pub struct LineChart {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
    pub log_x: bool,
    pub log_y: bool,
}

/// Writes the chart to `path`, SVG or PNG after its extension.
pub fn write_line_chart(chart: &LineChart, path: &Path) -> Result<(), StudyError> {
    render_file(chart, path)
}

/// Marks are drawn on curves of at most this many points (denser curves
/// read better as lines alone).
const MARKED_POINTS: usize = 60;

/// A linear range covering `values`, 5 % wider on each side; a single
/// value gets a range around it.
fn linear_bounds(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !(lo.is_finite() && hi.is_finite()) {
        return None;
    }
    let span = hi - lo;
    if span > 0.0 {
        Some((lo - 0.05 * span, hi + 0.05 * span))
    } else {
        let d = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
        Some((lo - d, hi + d))
    }
}

impl LineChart {
    fn bounds(&self, log: bool, pick: fn(&(f64, f64)) -> f64) -> Option<(f64, f64)> {
        let values = self.series.iter().flat_map(|s| s.points.iter().map(pick));
        if log {
            log_bounds(values)
        } else {
            linear_bounds(values)
        }
    }

    /// The points a series can show on these axes: finite, and positive on
    /// a logarithmic axis.
    fn shown(&self, s: &Series) -> Vec<(f64, f64)> {
        s.points
            .iter()
            .copied()
            .filter(|&(x, y)| {
                x.is_finite()
                    && y.is_finite()
                    && (!self.log_x || x > 0.0)
                    && (!self.log_y || y > 0.0)
            })
            .collect()
    }

    fn draw_in<DB, X, Y>(&self, root: &DrawingArea<DB, Shift>, x: X, y: Y) -> Result<(), String>
    where
        DB: DrawingBackend,
        X: AsRangedCoord<Value = f64>,
        Y: AsRangedCoord<Value = f64>,
        X::CoordDescType: Ranged<ValueType = f64> + ValueFormatter<f64>,
        Y::CoordDescType: Ranged<ValueType = f64> + ValueFormatter<f64>,
    {
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, ("sans-serif", 24))
            .margin(15)
            .x_label_area_size(50)
            .y_label_area_size(90)
            .build_cartesian_2d(x, y)
            .map_err(|e| e.to_string())?;
        let plain = |v: &f64| {
            if *v != 0.0 && (v.abs() >= 1e4 || v.abs() < 1e-2) {
                format!("{v:.2e}")
            } else {
                format!("{}", (v * 1e6).round() / 1e6)
            }
        };
        let x_fmt: &dyn Fn(&f64) -> String = if self.log_x { &sci } else { &plain };
        let y_fmt: &dyn Fn(&f64) -> String = if self.log_y { &sci } else { &plain };
        chart
            .configure_mesh()
            .x_desc(self.x_label.as_str())
            .y_desc(self.y_label.as_str())
            .x_label_formatter(x_fmt)
            .y_label_formatter(y_fmt)
            .draw()
            .map_err(|e| e.to_string())?;
        for (i, s) in self.series.iter().enumerate() {
            let color = Palette99::pick(i).to_rgba();
            let points = self.shown(s);
            chart
                .draw_series(LineSeries::new(points.clone(), color.stroke_width(2)))
                .map_err(|e| e.to_string())?
                .label(s.name.clone())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
            if points.len() <= MARKED_POINTS {
                chart
                    .draw_series(points.iter().map(|&p| Circle::new(p, 3, color.filled())))
                    .map_err(|e| e.to_string())?;
            }
        }
        series_legend(&mut chart, SeriesLabelPosition::UpperRight, 14)
    }
}

impl Chart for LineChart {
    fn kind(&self) -> &'static str {
        "lines"
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let (Some((x0, x1)), Some((y0, y1))) = (
            self.bounds(self.log_x, |p| p.0),
            self.bounds(self.log_y, |p| p.1),
        ) else {
            let why = if self.log_x || self.log_y {
                "no point to draw (a logarithmic axis shows positive values only)"
            } else {
                "no point to draw"
            };
            return draw_empty(root, &self.title, why);
        };
        match (self.log_x, self.log_y) {
            (false, false) => self.draw_in(root, x0..x1, y0..y1),
            (true, false) => self.draw_in(root, (x0..x1).log_scale(), y0..y1),
            (false, true) => self.draw_in(root, x0..x1, (y0..y1).log_scale()),
            (true, true) => self.draw_in(root, (x0..x1).log_scale(), (y0..y1).log_scale()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chart(log_y: bool) -> LineChart {
        LineChart {
            title: "reaction against displacement".into(),
            x_label: "DY".into(),
            y_label: "FY".into(),
            series: vec![
                Series {
                    name: "FY".into(),
                    points: (0..5).map(|i| (i as f64, 2.0 * i as f64 + 1.0)).collect(),
                },
                Series {
                    name: "FY2".into(),
                    points: vec![(0.0, 3.0), (4.0, 0.5)],
                },
            ],
            log_x: false,
            log_y,
        }
    }

    #[test]
    fn svg_holds_each_curve_and_its_legend() {
        let dir = tempfile::tempdir().expect("tempdir");
        let path = dir.path().join("c.svg");
        write_line_chart(&chart(false), &path).expect("written");
        let svg = std::fs::read_to_string(&path).expect("svg");
        assert!(svg.contains("reaction against displacement"));
        let texts: Vec<&str> = svg.lines().map(str::trim).collect();
        assert!(texts.contains(&"FY") && texts.contains(&"FY2"), "legends");
        // Two curves and two legend samples, drawn 2 px wide (axes, 1 px).
        let curves = svg
            .split("<polyline")
            .filter(|p| {
                p.split('>')
                    .next()
                    .is_some_and(|t| t.contains("stroke-width=\"2\""))
            })
            .count();
        assert_eq!(curves, 4, "{svg}");
        // Five marks on the first curve, two on the second.
        assert_eq!(svg.matches("<circle").count(), 7);
    }

    #[test]
    fn png_and_log_axes() {
        let dir = tempfile::tempdir().expect("tempdir");
        let path = dir.path().join("c.png");
        write_line_chart(&chart(true), &path).expect("written");
        let bytes = std::fs::read(&path).expect("png");
        assert_eq!(&bytes[1..4], b"PNG");
    }

    #[test]
    fn unknown_extension_and_nothing_to_draw() {
        let dir = tempfile::tempdir().expect("tempdir");
        let e = write_line_chart(&chart(false), &dir.path().join("c.pdf")).expect_err("pdf");
        assert!(e.to_string().contains(".svg or .png"), "{e}");
        let mut empty = chart(true);
        empty.series = vec![Series {
            name: "neg".into(),
            points: vec![(1.0, -1.0)],
        }];
        let path = dir.path().join("e.svg");
        write_line_chart(&empty, &path).expect("written");
        let svg = std::fs::read_to_string(&path).expect("svg");
        assert!(svg.contains("positive values only"));
    }
}
