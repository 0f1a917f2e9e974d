//! The three charts of a study, each as SVG and PNG: the error/time Pareto
//! front, the convergence in mesh size and the stability map; and the line
//! chart of curves that `aster plot` draws from tables and functions.
//!
//! Text is drawn with `ab_glyph` from an embedded DejaVu Sans (licence in
//! `assets/`), so no system font library (fontconfig, freetype) is needed.

mod convergence;
mod lines;
mod pareto;
mod stability;

pub use lines::{write_line_chart, LineChart, Series};

use crate::engine::StudyResult;
use crate::error::StudyError;
use crate::method::MethodFamily;
use plotters::coord::{CoordTranslate, Shift};
use plotters::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

static FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");

/// Registers the embedded font once; plotters looks fonts up by family.
fn ensure_font() -> Result<(), String> {
    static REGISTERED: OnceLock<Result<(), String>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            for family in ["sans-serif", "serif", "monospace"] {
                plotters::style::register_font(family, FontStyle::Normal, FONT)
                    .map_err(|_| "the embedded DejaVu Sans font is not a valid TTF".to_string())?;
            }
            Ok(())
        })
        .clone()
}

/// A chart drawable on any plotters backend.
trait Chart {
    /// File stem suffix, e.g. `pareto`.
    fn kind(&self) -> &'static str;
    fn size(&self) -> (u32, u32) {
        (1000, 700)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String>;
}

/// Writes `<out>/<study>-<kind>.svg` and `.png`.
fn render<C: Chart>(chart: &C, out: &Path, study: &str) -> Result<Vec<PathBuf>, StudyError> {
    let mut files = Vec::new();
    for ext in ["svg", "png"] {
        let path = out.join(format!("{study}-{}.{ext}", chart.kind()));
        render_file(chart, &path)?;
        files.push(path);
    }
    Ok(files)
}

/// Writes one chart to `path`: SVG or PNG after its extension.
fn render_file<C: Chart>(chart: &C, path: &Path) -> Result<(), StudyError> {
    let fail = |message: String| StudyError::Chart {
        path: path.to_path_buf(),
        message,
    };
    ensure_font().map_err(fail)?;
    let size = chart.size();
    match path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .as_deref()
    {
        Some("svg") => draw_on(chart, &SVGBackend::new(path, size).into_drawing_area()),
        Some("png") => draw_on(chart, &BitMapBackend::new(path, size).into_drawing_area()),
        _ => Err("a chart is written as .svg or .png".to_string()),
    }
    .map_err(fail)
}

fn draw_on<C: Chart, DB: DrawingBackend>(
    chart: &C,
    root: &DrawingArea<DB, Shift>,
) -> Result<(), String> {
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    chart.draw(root)?;
    root.present().map_err(|e| e.to_string())
}

/// Draws the three charts of a study into `out`; returns the files written.
pub fn write_all(result: &StudyResult, out: &Path) -> Result<Vec<PathBuf>, StudyError> {
    let name = &result.spec.name;
    let mut files = render(&pareto::Pareto { result }, out, name)?;
    files.extend(render(
        &convergence::ConvergenceChart { result },
        out,
        name,
    )?);
    files.extend(render(&stability::StabilityMap { result }, out, name)?);
    Ok(files)
}

/// The legend box of the charts: each series' label on a light background.
fn series_legend<'a, DB: DrawingBackend + 'a, CT: CoordTranslate>(
    chart: &mut ChartContext<'a, DB, CT>,
    position: SeriesLabelPosition,
    font_size: u32,
) -> Result<(), String> {
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(position)
        .label_font(("sans-serif", font_size))
        .draw()
        .map_err(|e| e.to_string())
}

/// One colour per method family, the same on every chart.
fn family_color(f: MethodFamily) -> RGBColor {
    match f {
        MethodFamily::DiscreteContrainte => RGBColor(31, 119, 180),
        MethodFamily::DiscretePenalisation => RGBColor(255, 127, 14),
        MethodFamily::DiscreteGcp => RGBColor(44, 160, 44),
        MethodFamily::ContinuousStandard => RGBColor(148, 103, 189),
        MethodFamily::ContinuousPenalisation => RGBColor(214, 39, 40),
        MethodFamily::LiaisonUnil => RGBColor(140, 86, 75),
        MethodFamily::LiaisonUnilPenalisation => RGBColor(227, 119, 194),
        MethodFamily::DiscreteFrictionPenalisation => RGBColor(188, 189, 34),
        MethodFamily::ContinuousFrictionStandard => RGBColor(23, 190, 207),
        MethodFamily::ContinuousFrictionPenalisation => RGBColor(127, 127, 127),
    }
}

/// A log range covering `values` with a little room on both sides.
fn log_bounds(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !(lo.is_finite() && hi > 0.0) {
        return None;
    }
    let (lo, hi) = if hi / lo < 10.0 {
        let mid = (lo * hi).sqrt();
        (mid / 4.0, mid * 4.0)
    } else {
        (lo / 1.5, hi * 1.5)
    };
    Some((lo, hi))
}

/// A chart with nothing to plot still says why, instead of being blank.
fn draw_empty<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    why: &str,
) -> Result<(), String> {
    root.draw_text(
        title,
        &("sans-serif", 24).into_font().color(&BLACK),
        (20, 20),
    )
    .map_err(|e| e.to_string())?;
    root.draw_text(why, &("sans-serif", 18).into_font().color(&BLACK), (20, 70))
        .map_err(|e| e.to_string())
}

/// `1e-3`-style tick labels for log axes.
fn sci(v: &f64) -> String {
    format!("{v:.0e}")
}
