//! The contact benchmark's report: error statistics of one method on one set, the
//! markdown rows of `BENCHMARKS.md`, and the error-against-time plot.

use super::{Answers, Set, TANGENCY};
use plotters::prelude::*;
use std::collections::BTreeMap;

/// Error statistics of one subject on a subset of pairs.
#[derive(Default, Clone)]
pub struct Stats {
    pub n: usize,
    pub failed: usize,
    pub max: f64,
    pub median: f64,
    pub p99: f64,
    pub under: [usize; 3],
    /// Decisions: judged pairs and wrong answers among them.
    pub judged: usize,
    pub wrong: usize,
}

const THRESHOLDS: [f64; 3] = [1e-15, 1e-12, 1e-10];

pub fn stats(answers: &Answers, set: &Set, keep: impl Fn(usize) -> bool) -> Stats {
    let mut s = Stats::default();
    match answers {
        Answers::Values(v) => {
            let mut errs = vec![];
            for (i, a) in v.iter().enumerate().filter(|(i, _)| keep(*i)) {
                s.n += 1;
                match a {
                    Some(mu2) if mu2.is_finite() => {
                        errs.push(((mu2 - set.mu2[i]) / set.mu2[i]).abs())
                    }
                    _ => s.failed += 1,
                }
            }
            errs.sort_by(f64::total_cmp);
            if !errs.is_empty() {
                s.max = errs[errs.len() - 1];
                s.median = errs[errs.len() / 2];
                s.p99 = errs[(errs.len() * 99 / 100).min(errs.len() - 1)];
            }
            for (k, t) in THRESHOLDS.iter().enumerate() {
                s.under[k] = errs.iter().filter(|&&e| e < *t).count();
            }
        }
        Answers::Decisions(v) => {
            for (i, a) in v.iter().enumerate().filter(|(i, _)| keep(*i)) {
                s.n += 1;
                match a {
                    None => s.failed += 1,
                    Some(o) if (set.mu2[i] - 1.0).abs() > TANGENCY => {
                        s.judged += 1;
                        if *o != (set.mu2[i] < 1.0) {
                            s.wrong += 1;
                        }
                    }
                    Some(_) => {}
                }
            }
        }
    }
    s
}

fn pct(k: usize, n: usize) -> String {
    format!("{:.1}%", 100.0 * k as f64 / n.max(1) as f64)
}

pub fn row(name: &str, label: &str, ns: Option<f64>, s: &Stats, decision: bool) -> String {
    let ns = ns.map_or("".into(), |t| format!("{t:.0}"));
    if decision {
        format!(
            "| {name} | {label} | {ns} | wrong decisions: {} of {} judged (|μ²−1| > 1e-12) | | | | | | {} |\n",
            s.wrong, s.judged, s.failed
        )
    } else {
        format!(
            "| {name} | {label} | {ns} | {:.1e} | {:.1e} | {:.1e} | {} | {} | {} | {} |\n",
            s.max,
            s.median,
            s.p99,
            pct(s.under[0], s.n - s.failed),
            pct(s.under[1], s.n - s.failed),
            pct(s.under[2], s.n - s.failed),
            s.failed
        )
    }
}

pub const HEADER: &str = "| method | set | ns/call (median) | max rel. error | median | p99 | < 1e-15 | < 1e-12 | < 1e-10 | errors |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";

/// Max relative error against median time, log–log, one marker per method and set.
pub fn plot(path: &str, points: &[(String, &str, f64, f64)]) {
    let font = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
    plotters::style::register_font("sans-serif", FontStyle::Normal, font)
        .map_err(|_| ())
        .unwrap();
    std::fs::create_dir_all(std::path::Path::new(path).parent().unwrap()).unwrap();
    let tmp = format!("{path}.tmp.png");
    {
        let root = BitMapBackend::new(&tmp, (900, 600)).into_drawing_area();
        root.fill(&WHITE).unwrap();
        let floor = 1e-17;
        let (tmin, tmax) = points
            .iter()
            .fold((f64::MAX, 0.0f64), |(a, b), p| (a.min(p.2), b.max(p.2)));
        let mut chart = ChartBuilder::on(&root)
            .caption(
                "Contact function: max relative error of μ² against time per call",
                ("sans-serif", 22),
            )
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(
                (tmin * 0.5..tmax.max(1450.0) * 2.0).log_scale(),
                (floor..1.0).log_scale(),
            )
            .unwrap();
        chart
            .configure_mesh()
            .x_desc("median ns per call (one core)")
            .y_desc("max relative error (floor 1e-17)")
            .x_label_formatter(&|x| format!("{x:.0}"))
            .y_label_formatter(&|y| format!("{y:.0e}"))
            .label_style(("sans-serif", 15))
            .draw()
            .unwrap();
        // The C reference library's figures as quoted in the issue (not measured here):
        // 1.2–1.7 µs per call, 1.2e-13 typical and 3e-9 extreme relative error.
        let quoted = [(1450.0, 1.2e-13), (1450.0, 3e-9)];
        chart
            .draw_series(
                quoted
                    .iter()
                    .map(|&(x, y)| Circle::new((x, y), 7, BLACK.stroke_width(2))),
            )
            .unwrap()
            .label("pw85 C library (quoted, not measured here)")
            .legend(|(x, y)| Circle::new((x, y), 6, BLACK.stroke_width(2)));
        let mut by_method: BTreeMap<&str, Vec<&(String, &str, f64, f64)>> = BTreeMap::new();
        for p in points {
            by_method.entry(p.0.as_str()).or_default().push(p);
        }
        for (k, (name, pts)) in by_method.iter().enumerate() {
            let color = Palette99::pick(k).to_rgba();
            let series: Vec<(f64, f64)> = pts.iter().map(|p| (p.2, p.3.max(floor))).collect();
            chart
                .draw_series(series.iter().zip(pts).map(|(&(x, y), p)| {
                    let marker: DynElement<_, _> = if p.1 == "typical" {
                        Circle::new((x, y), 7, color.filled()).into_dyn()
                    } else {
                        TriangleMarker::new((x, y), 9, color.filled()).into_dyn()
                    };
                    marker
                }))
                .unwrap()
                .label(format!("{name} (● typical, ▲ extreme)"))
                .legend(move |(x, y)| Circle::new((x, y), 6, color.filled()));
            chart
                .draw_series(LineSeries::new(series.clone(), color.stroke_width(1)))
                .unwrap();
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .label_font(("sans-serif", 15))
            .draw()
            .unwrap();
        root.present().unwrap();
    }
    std::fs::rename(tmp, path).unwrap();
}
