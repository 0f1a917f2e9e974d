//! The stability map: per method family, a grid of coefficient (x) against
//! stiffness ratio and step count (y), each cell coloured by the verdict on
//! the finest mesh and labelled with the failure's kind and how many mesh
//! levels converged.

use super::{draw_empty, Chart};
use crate::engine::{RunRecord, StudyResult};
use crate::method::{short_number, MethodFamily};
use crate::outcome::Status;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

pub struct StabilityMap<'a> {
    pub result: &'a StudyResult,
}

fn status_color(s: Status) -> RGBColor {
    match s {
        Status::Converged => RGBColor(120, 200, 120),
        Status::Wrong => RGBColor(250, 180, 60),
        Status::Failed => RGBColor(220, 70, 70),
        Status::Unsupported => RGBColor(190, 190, 190),
    }
}

/// The families present in the spec, in spec order.
fn families(result: &StudyResult) -> Vec<MethodFamily> {
    let mut out: Vec<MethodFamily> = Vec::new();
    for m in &result.spec.methods {
        if !out.contains(&m.family()) {
            out.push(m.family());
        }
    }
    out
}

/// The record on the finest mesh of a cell (coarse meshes are inaccurate
/// whatever the method: that is the convergence chart's business), with how
/// many of the cell's runs converged.
fn finest<'a>(cell: &[&'a RunRecord]) -> Option<(&'a RunRecord, usize)> {
    let ok = cell
        .iter()
        .filter(|r| r.status == Status::Converged)
        .count();
    cell.iter()
        .copied()
        .max_by_key(|r| r.point.refine)
        .map(|r| (r, ok))
}

impl Chart for StabilityMap<'_> {
    fn kind(&self) -> &'static str {
        "stability"
    }

    fn size(&self) -> (u32, u32) {
        let n = families(self.result).len().max(1) as u32;
        let rows = n.div_ceil(2);
        (1200, 120 + 380 * rows)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let r = self.result;
        let fams = families(r);
        let title = format!(
            "{}: stability map (verdict on the finest mesh, refine {})",
            r.spec.name,
            r.spec.refine.iter().max().copied().unwrap_or(0)
        );
        if fams.is_empty() {
            return draw_empty(root, &title, "no method in the study");
        }
        let (top, rest) = root.split_vertically(70);
        top.titled(&title, ("sans-serif", 24))
            .map_err(|e| e.to_string())?;
        draw_legend(&top)?;
        let cols = if fams.len() > 1 { 2 } else { 1 };
        let rows = fams.len().div_ceil(cols);
        let panels = rest.split_evenly((rows, cols));
        // y categories: the settings (stiffness ratio, steps, μ).
        let ys = r.spec.settings();
        let y_labels: Vec<String> = ys.iter().map(|s| s.label(&r.spec)).collect();
        for (family, panel) in fams.iter().zip(panels.iter()) {
            let xs: Vec<Option<f64>> = r
                .spec
                .methods
                .iter()
                .filter(|m| m.family() == *family)
                .map(|m| m.coefficient())
                .collect();
            let x_labels: Vec<String> = xs
                .iter()
                .map(|c| c.map(short_number).unwrap_or_else(|| "—".into()))
                .collect();
            // Drawn in pixels: a categorical grid needs no axis machinery.
            let (w, h) = panel.dim_in_pixel();
            let (w, h) = (w as i32, h as i32);
            let (left, top, right, bottom) = (120, 34, 10, 30);
            let cw = (w - left - right).max(1) / xs.len().max(1) as i32;
            let ch = (h - top - bottom).max(1) / ys.len().max(1) as i32;
            let centered = |size: u32| {
                ("sans-serif", size)
                    .into_font()
                    .color(&BLACK)
                    .pos(Pos::new(HPos::Center, VPos::Center))
            };
            let caption = match family.coefficient_name() {
                Some(name) => format!("{} (columns: {name})", family.name()),
                None => family.name().to_string(),
            };
            panel
                .draw_text(&caption, &centered(18), (w / 2, top / 2))
                .map_err(|e| e.to_string())?;
            for (i, label) in x_labels.iter().enumerate() {
                let x = left + cw * i as i32 + cw / 2;
                panel
                    .draw_text(label, &centered(12), (x, h - bottom / 2))
                    .map_err(|e| e.to_string())?;
            }
            for (j, label) in y_labels.iter().enumerate() {
                // Row 0 at the bottom, like an axis.
                let y = h - bottom - ch * j as i32 - ch / 2;
                let style = ("sans-serif", 12)
                    .into_font()
                    .color(&BLACK)
                    .pos(Pos::new(HPos::Right, VPos::Center));
                panel
                    .draw_text(label, &style, (left - 6, y))
                    .map_err(|e| e.to_string())?;
            }
            for (i, coef) in xs.iter().enumerate() {
                for (j, setting) in ys.iter().enumerate() {
                    let cell: Vec<&RunRecord> = r
                        .records
                        .iter()
                        .filter(|x| {
                            x.point.method.family() == *family
                                && x.point.method.coefficient() == *coef
                                && x.point.setting() == *setting
                        })
                        .collect();
                    let Some((fine, ok)) = finest(&cell) else {
                        continue;
                    };
                    let x0 = left + cw * i as i32;
                    let y1 = h - bottom - ch * j as i32;
                    let corners = [(x0 + 1, y1 - ch + 1), (x0 + cw - 1, y1 - 1)];
                    panel
                        .draw(&Rectangle::new(corners, status_color(fine.status).filled()))
                        .map_err(|e| e.to_string())?;
                    let kind = fine.kind.map(|k| k.name()).unwrap_or("ok");
                    let count = format!("{ok}/{}", cell.len());
                    let (cx, cy) = (x0 + cw / 2, y1 - ch / 2);
                    panel
                        .draw_text(kind, &centered(12), (cx, cy - 8))
                        .map_err(|e| e.to_string())?;
                    panel
                        .draw_text(&count, &centered(11), (cx, cy + 8))
                        .map_err(|e| e.to_string())?;
                }
            }
        }
        Ok(())
    }
}

fn draw_legend<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>) -> Result<(), String> {
    let entries = [
        (Status::Converged, "converged"),
        (Status::Wrong, "converged to a wrong answer"),
        (Status::Failed, "failed"),
        (Status::Unsupported, "not available"),
    ];
    let mut x = 20;
    for (status, text) in entries {
        area.draw(&Rectangle::new(
            [(x, 45), (x + 16, 61)],
            status_color(status).filled(),
        ))
        .map_err(|e| e.to_string())?;
        area.draw_text(
            text,
            &("sans-serif", 14).into_font().color(&BLACK),
            (x + 22, 46),
        )
        .map_err(|e| e.to_string())?;
        x += 30 + 8 * text.len() as i32;
    }
    area.draw_text(
        "cell text: failure on the finest mesh; meshes converged / meshes",
        &("sans-serif", 14).into_font().color(&BLACK),
        (x + 20, 46),
    )
    .map_err(|e| e.to_string())
}
