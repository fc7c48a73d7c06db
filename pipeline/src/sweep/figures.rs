//! The figures of a sweep: each requested key against one axis, one line per value of the
//! other axes; and a heat map when two axes span a grid.
//!
//! Line charts reuse the paper figures' [`Chart`]; the heat map is one more [`Figure`], so
//! both are written to PNG and SVG by the same `render`. Cells are placed by index (equal
//! widths whatever the spacing of the values) and labelled with their values, so a heat map
//! over a logarithmic axis reads as well as over a linear one.
//!
//! A run that did not reach its end time (failed, timed out, or stopped early by the physics)
//! is no value of the key: a "1 transition" of a run that died at 0.078 s would read as a
//! result. Such runs are left out of the lines (the title counts them) and drawn as grey cells
//! naming why in a heat map. Every line carries markers of its own shape, so that series with
//! equal values stay visible on top of each other.

use std::collections::BTreeMap;
use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::axes::as_number;
use super::expand::Definition;
use super::row::{reference, value, PointStop, Row, Status};
use super::spec::Combine;
use crate::figures::axes::tick_label;
use crate::figures::chart::{colors, render, Chart, DrawResult, Figure};
use crate::figures::line::{Line, Marker, FAMILY};
use crate::output::atomic::WriteError;
use crate::output::cells::Cell;
use equations::record::StopKind;

/// The colours of successive lines.
const PALETTE: [RGBColor; 5] = [
    colors::BLUE,
    colors::RED,
    colors::GREEN,
    colors::PURPLE,
    colors::BLACK,
];

/// A file-name-safe form of a key (`solver.rtol` -> `solver_rtol`).
fn slug(key: &str) -> String {
    key.chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect()
}

/// Whether values spread over enough decades to want a logarithmic axis (zeros, such as the
/// reference run's own error, are left out; a negative value rules it out).
fn wants_log(values: impl Iterator<Item = f64>, decades: f64) -> bool {
    let (mut lo, mut hi, mut any) = (f64::INFINITY, 0.0f64, false);
    for v in values.filter(|v| v.is_finite() && *v != 0.0) {
        if v < 0.0 {
            return false;
        }
        any = true;
        lo = lo.min(v);
        hi = hi.max(v);
    }
    any && hi / lo >= 10f64.powf(decades)
}

/// Draws the figures the sweep asks for into `dir`; returns their stems.
pub fn write_figures(d: &Definition, rows: &[Row], dir: &Path) -> Result<Vec<String>, WriteError> {
    let f = &d.file.figures;
    let Some(x_key) =
        f.x.clone()
            .or_else(|| d.axes.first().map(|a| a.key.clone()))
    else {
        return Ok(Vec::new());
    };
    let Some(x_index) = d.axes.iter().position(|a| a.key == x_key) else {
        return Ok(Vec::new());
    };
    let series_key = f
        .series
        .clone()
        .or_else(|| d.axes.iter().map(|a| a.key.clone()).find(|k| *k != x_key));
    let reference = reference(d, rows);
    let mut stems = Vec::new();
    for key in &f.keys {
        if let Some(chart) = line_chart(d, rows, reference, key, x_index) {
            render(&chart, dir)?;
            stems.push(chart.stem);
        }
        let map = series_key
            .as_ref()
            .and_then(|s| d.axes.iter().position(|a| a.key == *s))
            .and_then(|y_index| heat_map(d, rows, reference, key, x_index, y_index));
        if let Some(map) = map {
            render(&map, dir)?;
            stems.push(map.stem);
        }
    }
    Ok(stems)
}

/// Why `row` is no value of a key: `None` for a run that reached its end time, else the word
/// drawn in its place (`failed`, `timeout`, or the stop reason of an early stop).
fn failure(row: &Row) -> Option<String> {
    match row.status {
        Status::Completed if row.stop_reason == PointStop::Run(StopKind::EndTime) => None,
        Status::Completed => Some(row.stop_reason.to_string()),
        other => Some(other.as_str().to_string()),
    }
}

/// `key` against axis `x_index`, one line per combination of the other axes.
fn line_chart(
    d: &Definition,
    rows: &[Row],
    reference: Option<&Row>,
    key: &str,
    x_index: usize,
) -> Option<Chart> {
    let x_axis = &d.axes[x_index];
    x_axis.numbers()?;
    let mut groups: BTreeMap<String, Vec<(f64, f64)>> = BTreeMap::new();
    let mut left_out = 0;
    for r in rows {
        if failure(r).is_some() {
            left_out += 1;
            continue;
        }
        let (Some(x), Some(y)) = (
            r.values.get(x_index).and_then(as_number),
            value(r, reference, key),
        ) else {
            continue;
        };
        let label = d
            .axes
            .iter()
            .zip(&r.values)
            .enumerate()
            .filter(|(i, _)| *i != x_index)
            .map(|(_, (a, v))| format!("{} = {}", a.key, Cell::from_toml(v).csv()))
            .collect::<Vec<_>>()
            .join(", ");
        groups.entry(label).or_default().push((x, y));
    }
    if groups.is_empty() {
        return None;
    }
    let log_x = wants_log(x_axis.numbers()?.into_iter(), 2.0);
    let log_y = wants_log(groups.values().flatten().map(|p| p.1), 3.0);
    let lines = groups
        .into_iter()
        .enumerate()
        .map(|(i, (label, mut points))| {
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            let label = if label.is_empty() {
                key.to_string()
            } else {
                label
            };
            Line::new(label, points, PALETTE[i % PALETTE.len()])
                .marked(Marker::ALL[i % Marker::ALL.len()])
        })
        .collect();
    let not_drawn = match left_out {
        0 => String::new(),
        1 => " (1 run failed or stopped early: not drawn)".to_string(),
        n => format!(" ({n} runs failed or stopped early: not drawn)"),
    };
    Some(Chart {
        stem: format!("sweep_{}_vs_{}", slug(key), slug(&x_axis.key)),
        title: format!("{}: {key} against {}{not_drawn}", d.name, x_axis.key),
        x_label: x_axis.key.clone(),
        y_label: key.to_string(),
        y2_label: None,
        log_y,
        log_x,
        lines,
        x_range: None,
        empty_note: format!("no finished run has a value of {key}"),
    })
}

/// A heat map of `key` over two axes of a grid.
#[derive(Clone, Debug)]
pub struct HeatMap {
    /// File name without extension.
    pub stem: String,
    /// Title.
    pub title: String,
    /// The x axis' key and value labels.
    pub x: (String, Vec<String>),
    /// The y axis' key and value labels.
    pub y: (String, Vec<String>),
    /// Cell values by (x index, y index) of the runs that reached their end time.
    pub cells: BTreeMap<(usize, usize), f64>,
    /// The other runs' cells, with why (`failed`, `timeout`, `contact_lost`, ...); cells in
    /// neither map are runs not done.
    pub failures: BTreeMap<(usize, usize), String>,
}

/// The heat map of `key` over axes `x_index` × `y_index`, when the sweep is a grid whose
/// other axes have one value each.
fn heat_map(
    d: &Definition,
    rows: &[Row],
    reference: Option<&Row>,
    key: &str,
    x_index: usize,
    y_index: usize,
) -> Option<HeatMap> {
    let others_fixed = d
        .axes
        .iter()
        .enumerate()
        .all(|(i, a)| i == x_index || i == y_index || a.values.len() == 1);
    if d.file.combine != Combine::Grid || x_index == y_index || !others_fixed {
        return None;
    }
    let (xa, ya) = (&d.axes[x_index], &d.axes[y_index]);
    let position = |values: &[toml::Value], v: &toml::Value| values.iter().position(|w| w == v);
    let mut cells = BTreeMap::new();
    let mut failures = BTreeMap::new();
    for r in rows {
        let at = |axis: &super::axes::AxisValues, k: usize| {
            r.values.get(k).and_then(|v| position(&axis.values, v))
        };
        let place = at(xa, x_index).zip(at(ya, y_index));
        let Some(place) = place else {
            continue;
        };
        if let Some(why) = failure(r) {
            failures.insert(place, why);
        } else if let Some(v) = value(r, reference, key) {
            cells.insert(place, v);
        }
    }
    let labels = |a: &super::axes::AxisValues| {
        a.values
            .iter()
            .map(|v| {
                as_number(v).map_or_else(|| Cell::from_toml(v).csv(), |n| tick_label(n, false, 0.0))
            })
            .collect()
    };
    Some(HeatMap {
        stem: format!("sweep_{}_map", slug(key)),
        title: format!("{}: {key}", d.name),
        x: (xa.key.clone(), labels(xa)),
        y: (ya.key.clone(), labels(ya)),
        cells,
        failures,
    })
}

/// A colour from a blue-to-yellow scale (after viridis), `f` in [0, 1].
fn scale_color(f: f64) -> RGBColor {
    const STOPS: [(u8, u8, u8); 5] = [
        (68, 1, 84),
        (59, 82, 139),
        (33, 145, 140),
        (94, 201, 98),
        (253, 231, 37),
    ];
    let f = if f.is_finite() {
        f.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let x = f * (STOPS.len() - 1) as f64;
    let k = (x.floor() as usize).min(STOPS.len() - 2);
    let t = x - k as f64;
    let mix = |a: u8, b: u8| (a as f64 + (b as f64 - a as f64) * t).round() as u8;
    let (a, b) = (STOPS[k], STOPS[k + 1]);
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// A cell's value as printed in it.
fn cell_label(v: f64) -> String {
    if v != 0.0 && (v.abs() < 1e-2 || v.abs() >= 1e5) {
        format!("{v:.2e}")
    } else {
        format!("{v:.4}")
            .trim_end_matches('0')
            .trim_end_matches('.')
            .to_string()
    }
}

impl Figure for HeatMap {
    fn stem(&self) -> &str {
        &self.stem
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        root.fill(&WHITE)?;
        let (nx, ny) = (self.x.1.len(), self.y.1.len());
        let (lo, hi) = self
            .cells
            .values()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
                (l.min(*v), h.max(*v))
            });
        let title = if lo.is_finite() {
            format!("{} ({} … {})", self.title, cell_label(lo), cell_label(hi))
        } else {
            self.title.clone()
        };
        let mut chart = ChartBuilder::on(root)
            .caption(title, (FAMILY, 30).into_font().style(FontStyle::Bold))
            .margin(20)
            .x_label_area_size(70)
            .y_label_area_size(110)
            // A segmented range `0..n` has a segment for n too: the last index is n - 1.
            .build_cartesian_2d(
                (0..nx.saturating_sub(1)).into_segmented(),
                (0..ny.saturating_sub(1)).into_segmented(),
            )?;
        let label = |names: &[String], v: &SegmentValue<usize>| match v {
            SegmentValue::CenterOf(i) => names.get(*i).cloned().unwrap_or_default(),
            _ => String::new(),
        };
        chart
            .configure_mesh()
            .disable_mesh()
            .x_labels(nx + 1)
            .y_labels(ny + 1)
            .x_label_formatter(&|v| label(&self.x.1, v))
            .y_label_formatter(&|v| label(&self.y.1, v))
            .x_desc(self.x.0.as_str())
            .y_desc(self.y.0.as_str())
            .axis_desc_style((FAMILY, 22).into_font())
            .label_style((FAMILY, 18).into_font())
            .draw()?;
        let span = if hi > lo { hi - lo } else { 1.0 };
        let grey = RGBColor(200, 200, 200);
        let cell = |i: usize, j: usize| {
            [
                (SegmentValue::Exact(i), SegmentValue::Exact(j)),
                (SegmentValue::Exact(i + 1), SegmentValue::Exact(j + 1)),
            ]
        };
        chart.draw_series(
            (0..nx)
                .flat_map(|i| (0..ny).map(move |j| (i, j)))
                .map(|(i, j)| {
                    let color = self
                        .cells
                        .get(&(i, j))
                        .map_or(grey, |v| scale_color((v - lo) / span));
                    Rectangle::new(cell(i, j), color.filled())
                }),
        )?;
        let centre = Pos::new(HPos::Center, VPos::Center);
        chart.draw_series(self.failures.iter().map(|(&(i, j), why)| {
            Text::new(
                why.clone(),
                (SegmentValue::CenterOf(i), SegmentValue::CenterOf(j)),
                (FAMILY, 16).into_font().color(&BLACK).pos(centre),
            )
        }))?;
        chart.draw_series(self.cells.iter().map(|(&(i, j), v)| {
            let ink = if (v - lo) / span > 0.6 { BLACK } else { WHITE };
            Text::new(
                cell_label(*v),
                (SegmentValue::CenterOf(i), SegmentValue::CenterOf(j)),
                (FAMILY, 18).into_font().color(&ink).pos(centre),
            )
        }))?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figures::line::Stroke;
    use crate::sweep::expand::plan;
    use crate::sweep::row::SweepStop;
    use crate::sweep::spec::{parse, LoadedSweep};

    /// mu_d x mu_st, 2 x 2, a grid: the built-in paper scene, nothing run.
    fn definition() -> Definition {
        let text = r#"
scene = "tangent-toy-pruned"
[[axis]]
key = "friction.mu_d"
values = [0.1, 0.11]
[[axis]]
key = "friction.mu_st"
values = [0.2, 0.3]
[figures]
keys = ["transitions"]
"#;
        let loaded = LoadedSweep {
            name: "t".into(),
            folder: None,
            file: parse("t", text).unwrap(),
        };
        plan(&loaded, &[]).unwrap().definition
    }

    /// A run that reached its end time.
    const END: PointStop = PointStop::Run(StopKind::EndTime);

    /// Point `point` of `d` ending with `status` and `stop_reason`, `transitions` = `value`.
    fn row(
        d: &Definition,
        point: usize,
        status: Status,
        stop_reason: PointStop,
        value: f64,
    ) -> Row {
        let mut summary = serde_json::Map::new();
        summary.insert("transitions".into(), value.into());
        Row {
            point,
            values: d.points[point].clone(),
            status,
            stop_reason,
            stop_detail: String::new(),
            summary,
            wall_s: 0.0,
            cpu_s: None,
        }
    }

    #[test]
    fn runs_that_did_not_reach_their_end_are_drawn_as_failures() {
        let d = definition();
        let rows = [
            row(&d, 0, Status::Completed, END, 10.0),
            row(
                &d,
                1,
                Status::Completed,
                PointStop::Run(StopKind::ContactLost),
                1.0,
            ),
            row(&d, 2, Status::Failed, PointStop::Run(StopKind::Error), 1.0),
            row(
                &d,
                3,
                Status::Timeout,
                PointStop::Sweep(SweepStop::Timeout),
                1.0,
            ),
        ];
        let map = heat_map(&d, &rows, None, "transitions", 0, 1).unwrap();
        assert_eq!(map.cells.values().collect::<Vec<_>>(), [&10.0]);
        let mut why: Vec<&str> = map.failures.values().map(String::as_str).collect();
        why.sort_unstable();
        assert_eq!(why, ["contact_lost", "failed", "timeout"]);
        let chart = line_chart(&d, &rows, None, "transitions", 0).unwrap();
        let drawn: Vec<(f64, f64)> = chart.lines.iter().flat_map(|l| l.points.clone()).collect();
        assert_eq!(drawn, [(0.1, 10.0)]);
        assert!(
            chart.title.contains("3 runs failed or stopped early"),
            "{}",
            chart.title
        );
    }

    #[test]
    fn every_series_has_markers_of_its_own_shape() {
        let d = definition();
        let rows: Vec<Row> = (0..4)
            .map(|i| row(&d, i, Status::Completed, END, 5.0))
            .collect();
        let chart = line_chart(&d, &rows, None, "transitions", 0).unwrap();
        let strokes: Vec<Stroke> = chart.lines.iter().map(|l| l.stroke).collect();
        assert_eq!(
            strokes,
            [
                Stroke::Marked(Marker::Circle),
                Stroke::Marked(Marker::Triangle)
            ]
        );
    }
}
