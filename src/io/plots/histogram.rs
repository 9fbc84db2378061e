//! Histograms normalised as densities, with a bin count chosen from the data.

/// The fewest bins a histogram gets.
pub const MIN_BINS: usize = 5;

/// The most bins a histogram gets: beyond about 40 bars a panel 600 pixels wide shows
/// noise rather than shape, whatever the sample size.
pub const MAX_BINS: usize = 40;

/// A histogram on `bins` equal bins over `[lo, hi]`, normalised as a density.
///
/// A value `x` falls in bin `⌊(x − lo)/w⌋` (the last bin is closed, so `hi` counts);
/// values outside `[lo, hi]` and non-finite ones are counted in `outside` only. The
/// density of bin `k` is `counts[k] / (n w)` with `n` the values inside, so the bars
/// have total area 1.
///
/// ```
/// use grainpack::io::plots::Histogram;
/// let h = Histogram::new(&[0.1, 0.2, 0.6, 1.0, 7.0], 0.0, 1.0, 2);
/// assert_eq!((h.counts.as_slice(), h.outside), (&[2, 2][..], 1));
/// assert_eq!(h.density(), vec![1.0, 1.0]);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Histogram {
    /// Left edge of the first bin.
    pub lo: f64,
    /// Right edge of the last bin.
    pub hi: f64,
    /// Values in each bin.
    pub counts: Vec<usize>,
    /// Values left out: outside `[lo, hi]` or not finite.
    pub outside: usize,
}

impl Histogram {
    /// Bins `values` on `bins` equal bins over `[lo, hi]` (at least one bin; an empty or
    /// reversed interval leaves every value outside).
    pub fn new(values: &[f64], lo: f64, hi: f64, bins: usize) -> Self {
        let bins = bins.max(1);
        let mut counts = vec![0; bins];
        let mut outside = 0;
        let width = (hi - lo) / bins as f64;
        for &x in values {
            if !(width > 0.0 && x >= lo && x <= hi) {
                outside += 1;
                continue;
            }
            // Rounding can put x = hi, or a value just below it, one past the end.
            let k = (((x - lo) / width) as usize).min(bins - 1);
            counts[k] += 1;
        }
        Self {
            lo,
            hi,
            counts,
            outside,
        }
    }

    /// The width of a bin.
    pub fn width(&self) -> f64 {
        (self.hi - self.lo) / self.counts.len() as f64
    }

    /// The number of values inside the bins.
    pub fn inside(&self) -> usize {
        self.counts.iter().sum()
    }

    /// The density of each bin, `counts[k] / (n w)`; all zero when no value is inside.
    pub fn density(&self) -> Vec<f64> {
        let n = self.inside();
        if n == 0 {
            return vec![0.0; self.counts.len()];
        }
        let scale = 1.0 / (n as f64 * self.width());
        self.counts.iter().map(|&c| c as f64 * scale).collect()
    }

    /// The bars: `(left edge, right edge, density)` of each bin.
    pub fn bars(&self) -> Vec<(f64, f64, f64)> {
        let w = self.width();
        self.density()
            .into_iter()
            .enumerate()
            .map(|(k, d)| (self.lo + k as f64 * w, self.lo + (k + 1) as f64 * w, d))
            .collect()
    }

    /// The outline of the bars as a closed step path from `(lo, 0)` to `(hi, 0)`.
    pub fn outline(&self) -> Vec<(f64, f64)> {
        let mut path = vec![(self.lo, 0.0)];
        for (a, b, d) in self.bars() {
            path.push((a, d));
            path.push((b, d));
        }
        path.push((self.hi, 0.0));
        path
    }
}

/// The number of bins for `values` over `[lo, hi]` by the Freedman–Diaconis rule, bin
/// width `2 IQR n^{−1/3}` (Freedman & Diaconis, *Z. Wahrscheinlichkeitstheorie* 57,
/// 453–476, 1981), clamped to [`MIN_BINS`]`..=`[`MAX_BINS`]. Sturges' rule
/// `⌈log₂ n⌉ + 1` replaces it when the interquartile range is zero (fewer than two
/// distinct values in the middle half). Non-finite values are ignored.
///
/// ```
/// use grainpack::io::plots::freedman_diaconis_bins;
/// let values: Vec<f64> = (0..1000).map(|i| i as f64 / 1000.0).collect();
/// // IQR ≈ 0.5 and n^{-1/3} = 0.1: bins of width about 0.1 on [0, 1].
/// let bins = freedman_diaconis_bins(&values, 0.0, 1.0);
/// assert!((10..=11).contains(&bins));
/// ```
pub fn freedman_diaconis_bins(values: &[f64], lo: f64, hi: f64) -> usize {
    let mut sorted: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    sorted.sort_by(f64::total_cmp);
    let n = sorted.len();
    let sturges = || (n.max(1) as f64).log2().ceil() as usize + 1;
    let bins = if n < 2 {
        sturges()
    } else {
        let iqr = quantile(&sorted, 0.75) - quantile(&sorted, 0.25);
        let width = 2.0 * iqr / (n as f64).cbrt();
        let bins = ((hi - lo) / width).ceil();
        if width > 0.0 && bins.is_finite() {
            bins.min(MAX_BINS as f64) as usize
        } else {
            sturges()
        }
    };
    bins.clamp(MIN_BINS, MAX_BINS)
}

/// A grid of equal bins `(lo, hi, bins)` for `values` whose bin edges fall on the
/// cutoffs `[a, b]` of their law: [`freedman_diaconis_bins`] bins on `[a, b]`, then as
/// many bins of the same width on either side as it takes to reach `[lo, hi]`, the
/// interval holding every value. A bin then never straddles a cutoff, where the
/// density jumps. If more than [`MAX_BINS`] bins would be added (values far outside
/// the cutoffs), the grid is [`freedman_diaconis_bins`] bins on `[lo, hi]` instead.
///
/// ```
/// use grainpack::io::plots::aligned_bins;
/// let values = [1.0, 1.5, 2.0, 2.5, 3.0, 3.2];
/// let (lo, hi, bins) = aligned_bins(&values, (1.0, 3.0), (1.0, 3.2));
/// let width = (hi - lo) / bins as f64;
/// assert!(lo == 1.0 && hi >= 3.2);
/// // 3.0 is an edge: a whole number of bins from 1.0.
/// assert!(((3.0 - lo) / width - ((3.0 - lo) / width).round()).abs() < 1e-9);
/// ```
pub fn aligned_bins(values: &[f64], (a, b): (f64, f64), (lo, hi): (f64, f64)) -> (f64, f64, usize) {
    let inner = freedman_diaconis_bins(values, a, b);
    let width = (b - a) / inner as f64;
    let below = ((a - lo) / width).ceil().max(0.0);
    let above = ((hi - b) / width).ceil().max(0.0);
    if !(width > 0.0 && below + above <= MAX_BINS as f64) {
        return (lo, hi, freedman_diaconis_bins(values, lo, hi));
    }
    (
        a - below * width,
        b + above * width,
        inner + below as usize + above as usize,
    )
}

/// The `p`-quantile of sorted, non-empty `values` by linear interpolation between order
/// statistics (Hyndman & Fan's type 7, numpy's default).
fn quantile(sorted: &[f64], p: f64) -> f64 {
    let h = p * (sorted.len() - 1) as f64;
    let (k, frac) = (h.floor() as usize, h.fract());
    match sorted.get(k + 1) {
        Some(&next) => sorted[k] + frac * (next - sorted[k]),
        None => sorted[k],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn sample(n: usize, seed: u64) -> Vec<f64> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        // A skewed sample on [2, 10]: 2 + 8 u².
        (0..n)
            .map(|_| 2.0 + 8.0 * rng.random::<f64>().powi(2))
            .collect()
    }

    #[test]
    fn counts_sum_to_n_and_density_integrates_to_one() {
        for (n, bins) in [(1, 5), (17, 7), (1000, 23), (5000, 40)] {
            let values = sample(n, n as u64);
            let h = Histogram::new(&values, 2.0, 10.0, bins);
            assert_eq!(h.counts.len(), bins);
            assert_eq!(h.inside() + h.outside, n);
            assert_eq!(h.outside, 0);
            let area: f64 = h.density().iter().map(|d| d * h.width()).sum();
            // A sum of at most 40 rounded products.
            assert!((area - 1.0).abs() < 1e-13, "n={n}: {area}");
        }
    }

    #[test]
    fn values_fall_in_the_bin_that_contains_them() {
        let values = sample(2000, 5);
        let h = Histogram::new(&values, 2.0, 10.0, 16);
        for (k, (a, b, _)) in h.bars().into_iter().enumerate() {
            // Counted independently: half-open bins, the last one closed.
            let want = values
                .iter()
                .filter(|&&x| x >= a && (x < b || (k == 15 && x <= b)))
                .count();
            assert_eq!(h.counts[k], want, "bin {k} [{a}, {b})");
        }
    }

    #[test]
    fn values_outside_or_not_finite_are_left_out_and_counted() {
        let h = Histogram::new(&[1.0, f64::NAN, 3.0, 3.0, f64::INFINITY, -2.0], 0.0, 3.0, 3);
        assert_eq!(h.counts, vec![0, 1, 2]);
        assert_eq!(h.outside, 3);
        let empty = Histogram::new(&[], 0.0, 1.0, 4);
        assert_eq!(empty.density(), vec![0.0; 4]);
        // A degenerate interval holds nothing.
        assert_eq!(Histogram::new(&[1.0], 1.0, 1.0, 4).outside, 1);
    }

    #[test]
    fn outline_follows_the_bars() {
        let h = Histogram::new(&[0.5, 1.5, 1.6], 0.0, 2.0, 2);
        let d = h.density();
        assert_eq!(
            h.outline(),
            vec![
                (0.0, 0.0),
                (0.0, d[0]),
                (1.0, d[0]),
                (1.0, d[1]),
                (2.0, d[1]),
                (2.0, 0.0)
            ]
        );
    }

    #[test]
    fn freedman_diaconis_grows_with_n_and_stays_within_the_caps() {
        let few = freedman_diaconis_bins(&sample(50, 1), 2.0, 10.0);
        let many = freedman_diaconis_bins(&sample(5000, 2), 2.0, 10.0);
        assert!(few < many, "{few} vs {many}");
        // n^{1/3} grows by 100^{1/3} ≈ 4.6 from 50 to 5000 draws (before the cap).
        assert!((MIN_BINS..=MAX_BINS).contains(&few));
        assert_eq!(
            freedman_diaconis_bins(&sample(1_000_000, 3), 2.0, 10.0),
            MAX_BINS
        );
        // All equal: IQR 0, Sturges' rule, here ⌈log₂ 100⌉ + 1 = 8.
        assert_eq!(freedman_diaconis_bins(&[4.0; 100], 3.0, 5.0), 8);
        assert_eq!(freedman_diaconis_bins(&[], 0.0, 1.0), MIN_BINS);
    }

    #[test]
    fn aligned_bins_put_edges_on_the_cutoffs_and_cover_every_value() {
        let values: Vec<f64> = sample(1000, 9).iter().map(|x| 1.1 * x).collect();
        let (a, b) = (2.0, 10.0);
        let (lo, hi) = (2.2, 11.0 - 1e-3);
        let (glo, ghi, bins) = aligned_bins(&values, (a, b), (lo, hi));
        let width = (ghi - glo) / bins as f64;
        assert!(glo <= lo && ghi >= hi, "[{glo}, {ghi}]");
        // Grid edges glo + k·width: a and b among them, to rounding of a few ulps of
        // the edge count.
        for cut in [a, b] {
            let k = (cut - glo) / width;
            assert!((k - k.round()).abs() < 1e-9, "{cut} at bin {k}");
        }
        // Every value inside.
        assert_eq!(Histogram::new(&values, glo, ghi, bins).outside, 0);
        // Values far outside the cutoffs fall back to a grid on their own range.
        let far = aligned_bins(&[0.0, 1e6], (2.0, 10.0), (0.0, 1e6));
        assert_eq!((far.0, far.1), (0.0, 1e6));
    }

    #[test]
    fn quantile_interpolates_between_order_statistics() {
        let v = [1.0, 2.0, 4.0, 8.0];
        assert_eq!(quantile(&v, 0.0), 1.0);
        assert_eq!(quantile(&v, 1.0), 8.0);
        // h = 0.5 · 3 = 1.5: halfway between 2 and 4.
        assert_eq!(quantile(&v, 0.5), 3.0);
    }
}
