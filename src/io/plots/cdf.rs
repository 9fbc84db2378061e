//! A CDF panel: the packed grains' passing fraction (by number or by volume) as a
//! step curve against a tabulated CDF, with the table's points and the packed
//! fraction passing each tabulated size marked.

use super::draw::{axes, failed, legend, tick_decimals, PACKED, TARGET, X_MARGIN};
use super::PlotError;
use plotters::coord::Shift;
use plotters::prelude::*;

/// A cumulative panel: what a sieve curve or a tabulated number CDF is compared with.
#[derive(Debug, Clone)]
pub(super) struct CdfPanel {
    /// Caption.
    pub title: String,
    /// x axis label, with the unit.
    pub x_label: &'static str,
    /// y axis label.
    pub y_label: &'static str,
    /// Legend entry of the table.
    pub law: String,
    /// The table's interpolated curve, `(x, F(x))`.
    pub target: Vec<(f64, f64)>,
    /// The table's own points.
    pub table_points: Vec<(f64, f64)>,
    /// The packed grains' CDF: `(xᵢ, W(xᵢ))` at each grain, ascending; `None` without
    /// grains.
    pub packed_steps: Option<Vec<(f64, f64)>>,
    /// The packed fraction passing each tabulated size (from the run's statistics).
    pub packed_at_table: Option<Vec<(f64, f64)>>,
    /// Number of packed grains.
    pub grains: usize,
    /// KS distance of the packed CDF to the table (from the run's statistics).
    pub ks_distance: Option<f64>,
    /// Largest deviation at the tabulated sizes (from the run's statistics).
    pub max_deviation: Option<f64>,
}

/// The y axis runs to this, leaving room for the legend above a CDF that ends at 1
/// (the legend sits lower right, where a CDF is high, so it needs no headroom; this
/// keeps the top of the curve off the frame).
const Y_TOP: f64 = 1.05;

/// Radius of the markers of tabulated points, in pixels.
const MARKER: i32 = 4;

/// Draws a CDF panel into `area`.
pub(super) fn draw_cdf_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    panel: &CdfPanel,
) -> Result<(), PlotError> {
    let what = panel.title.as_str();
    let xs = panel
        .target
        .iter()
        .map(|p| p.0)
        .chain(panel.packed_steps.iter().flatten().map(|p| p.0))
        .filter(|x| x.is_finite());
    let (lo, hi) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
        (a.min(x), b.max(x))
    });
    let (lo, hi) = if lo < hi { (lo, hi) } else { (0.0, 1.0) };
    let pad = X_MARGIN * (hi - lo);
    let mut chart = axes(
        area,
        what,
        (panel.x_label, panel.y_label),
        ((lo - pad)..(hi + pad), 0.0..Y_TOP),
        (tick_decimals(hi - lo + 2.0 * pad, 7), 1),
    )?;

    if let Some(steps) = &panel.packed_steps {
        // A right-continuous step: flat from each value to the next, rising at each.
        let mut path = vec![(lo - pad, 0.0)];
        let mut level = 0.0;
        for &(x, w) in steps {
            path.push((x, level));
            path.push((x, w));
            level = w;
        }
        path.push((hi + pad, level));
        let line = PACKED.stroke_width(2);
        let mut label = format!("packed grains, n = {}", panel.grains);
        if let Some(d) = panel.ks_distance {
            label += &format!(": KS = {d:.3}");
        }
        chart
            .draw_series(std::iter::once(PathElement::new(path, line)))
            .map_err(failed(what))?
            .label(label)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], line));
    }
    let line = TARGET.stroke_width(2);
    chart
        .draw_series(LineSeries::new(panel.target.clone(), line))
        .map_err(failed(what))?
        .label(panel.law.clone())
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], line));
    chart
        .draw_series(
            panel
                .table_points
                .iter()
                .map(|&p| Circle::new(p, MARKER, TARGET.filled())),
        )
        .map_err(failed(what))?;
    if let Some(points) = &panel.packed_at_table {
        let mut label = "packed, at the tabulated sizes".to_string();
        if let Some(d) = panel.max_deviation {
            label += &format!(": max |\u{394}| = {d:.3}");
        }
        chart
            .draw_series(
                points
                    .iter()
                    .map(|&p| Circle::new(p, MARKER, PACKED.stroke_width(2))),
            )
            .map_err(failed(what))?
            .label(label)
            .legend(move |(x, y)| Circle::new((x + 10, y), MARKER, PACKED.stroke_width(2)));
    }
    legend(&mut chart, SeriesLabelPosition::LowerRight, what)
}
