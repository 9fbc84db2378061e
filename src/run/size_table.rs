//! A tabulated size law (`distribution = "table"`) against the packed grains, on the
//! table's own terms: the fraction **passing** each tabulated size, counted by number
//! or weighted by grain volume as the table says. For a sieve curve (`by = "volume"`)
//! this is the grading of the packed aggregate, the figure a concrete technologist
//! reads; the number law the grains are drawn from is compared in `diameter`.

use crate::contact::Dimension;
use crate::laws::{Distribution, TableBasis, TableLaw};
use crate::packing::PackedGrain;
use serde::Serialize;

/// The packed grains' passing fractions against a size table.
#[derive(Debug, Clone, Serialize)]
pub struct SizeTableStatistics {
    /// `"number"` or `"volume"`: what the fractions count.
    pub by: &'static str,
    /// The tabulated sizes (equivalent diameters, box units).
    pub sizes: Vec<f64>,
    /// The table's fractions passing each size, rescaled to run from 0 to 1.
    pub target: Vec<f64>,
    /// Share of the packed grains (by number, or by volume) with an equivalent
    /// diameter at or below each size; `null` without grains.
    pub achieved: Option<Vec<f64>>,
    /// Largest `|achieved − target|` over the tabulated sizes; `null` without grains.
    pub max_deviation: Option<f64>,
    /// Kolmogorov–Smirnov distance between the packed grains' (number or
    /// volume-weighted) CDF and the table's interpolated curve, over every size;
    /// `null` without grains.
    pub ks_distance: Option<f64>,
}

/// The table statistics of a phase whose size law is a table; `None` otherwise.
pub(crate) fn size_table(
    size: &Distribution,
    dimension: Dimension,
    grains: &[&PackedGrain],
) -> Option<SizeTableStatistics> {
    let Distribution::Table(table) = size else {
        return None;
    };
    let weighted: Vec<(f64, f64)> = grains
        .iter()
        .map(|g| {
            let w = match table.basis {
                TableBasis::Number => 1.0,
                TableBasis::Volume | TableBasis::Area => dimension.measure(g.semi_axes),
            };
            (dimension.equivalent_diameter(g.semi_axes), w)
        })
        .collect();
    Some(table_statistics(table, &weighted))
}

/// [`SizeTableStatistics`] of `(size, weight)` pairs against `table`.
pub(crate) fn table_statistics(table: &TableLaw, weighted: &[(f64, f64)]) -> SizeTableStatistics {
    let cdf = WeightedCdf::new(weighted);
    let achieved = cdf
        .as_ref()
        .map(|c| table.x.iter().map(|&x| c.at(x)).collect::<Vec<f64>>());
    let max_deviation = achieved.as_ref().map(|a| {
        a.iter()
            .zip(table.fraction.iter())
            .map(|(a, t)| (a - t).abs())
            .fold(0.0, f64::max)
    });
    SizeTableStatistics {
        by: match table.basis {
            TableBasis::Number => "number",
            TableBasis::Volume => "volume",
            TableBasis::Area => "area",
        },
        sizes: table.x.to_vec(),
        target: table.fraction.to_vec(),
        achieved,
        max_deviation,
        ks_distance: cdf.map(|c| c.ks_distance(|x| table.given_cdf(x))),
    }
}

/// The CDF of a weighted sample: `W(x) = Σ_{xᵢ ≤ x} wᵢ / Σ wᵢ`.
#[derive(Debug, Clone)]
pub(crate) struct WeightedCdf {
    /// The values, ascending.
    pub x: Vec<f64>,
    /// `W` at each value (the last is 1).
    pub w: Vec<f64>,
}

impl WeightedCdf {
    /// `None` for an empty sample or one of zero total weight.
    pub(crate) fn new(weighted: &[(f64, f64)]) -> Option<Self> {
        let mut sorted = weighted.to_vec();
        sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
        let total: f64 = sorted.iter().map(|p| p.1).sum();
        if !(total > 0.0) {
            return None;
        }
        let mut acc = 0.0;
        let w = sorted
            .iter()
            .map(|p| {
                acc += p.1;
                acc / total
            })
            .collect();
        Some(Self {
            x: sorted.iter().map(|p| p.0).collect(),
            w,
        })
    }

    /// `W(x)`.
    pub(crate) fn at(&self, x: f64) -> f64 {
        match self.x.partition_point(|&v| v <= x) {
            0 => 0.0,
            i => self.w[i - 1],
        }
    }

    /// `sup |W − G|` for a continuous non-decreasing `G`: reached at a value or just
    /// below one, where `W` jumps from its previous level; of equal values, the last
    /// carries the level after the jump.
    pub(crate) fn ks_distance(&self, g: impl Fn(f64) -> f64) -> f64 {
        let mut d: f64 = 0.0;
        let mut before = 0.0;
        for (i, (&x, &w)) in self.x.iter().zip(&self.w).enumerate() {
            let gx = g(x);
            d = d.max((gx - before).abs());
            if self.x.get(i + 1) != Some(&x) {
                d = d.max((w - gx).abs());
                before = w;
            }
        }
        d
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::laws::TableInterpolation;

    /// Equal weights: the weighted KS distance is the classic one (to rounding of the
    /// running sums, a few ulps of 1).
    #[test]
    fn weighted_ks_with_equal_weights_is_the_classic_distance() {
        let sample = [0.4, 0.1, 0.7, 0.7, 0.2];
        let pairs: Vec<(f64, f64)> = sample.iter().map(|&x| (x, 2.5)).collect();
        let uniform = |x: f64| x.clamp(0.0, 1.0);
        let d = WeightedCdf::new(&pairs).unwrap().ks_distance(uniform);
        let want = crate::laws::ks_distance(&sample, uniform).unwrap();
        assert!((d - want).abs() < 1e-15, "{d} {want}");
    }

    /// One heavy grain and one light one: by volume, the passing fraction at a size
    /// between them is the light grain's share of the volume, not one half.
    #[test]
    fn volume_passing_weighs_grains_by_their_volume() {
        let table = TableLaw::new(
            &[1.0, 2.0],
            &[0.0, 1.0],
            TableBasis::Volume,
            TableInterpolation::Linear,
        )
        .unwrap();
        // Diameters 1 and 2: volumes in the ratio 1 : 8.
        let s = table_statistics(&table, &[(1.0, 1.0), (2.0, 8.0)]);
        assert_eq!(s.by, "volume");
        assert_eq!(s.achieved.as_deref(), Some(&[1.0 / 9.0, 1.0][..]));
        assert_eq!(s.max_deviation, Some(1.0 / 9.0));
        // Just below d = 2 the table is at 1⁻ and the sample at 1/9.
        assert!((s.ks_distance.unwrap() - 8.0 / 9.0).abs() < 1e-15);
        let empty = table_statistics(&table, &[]);
        assert!(empty.achieved.is_none() && empty.ks_distance.is_none());
    }
}
