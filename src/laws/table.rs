//! Tabulated laws: a CDF given at points (a sieve curve, a measured size curve), and
//! the empirical law of a list of values (a measured grain table).
//!
//! A table gives `F(xᵢ)` at increasing `xᵢ`, either the **number** fraction of grains
//! below `xᵢ` or the **volume** fraction (a sieve curve: the mass passing a sieve of
//! opening `xᵢ`). Between points `F` is interpolated linearly in `x` or in `ln x`.
//! Grains are drawn by number, so a volume table is converted: where the volume
//! density is `f_v(x)`, the number density is `∝ f_v(x)/x³`. A 2D scene's table may
//! be by **area** (the fraction of the ellipses' area below `x`), converted with
//! `x²`. In each interval the number density is then a power `k xᵖ`, with
//!
//! | by \ interpolation | linear | log |
//! |--------------------|--------|-----|
//! | number             | p = 0  | −1  |
//! | volume             | p = −3 | −4  |
//! | area               | p = −2 | −3  |
//!
//! so the CDF, its inverse and every moment are exact (no quadrature). The law is
//! truncated to the table's ends: `F` is rescaled to run from 0 at the first point to
//! 1 at the last.

use std::sync::Arc;

/// What a table's fractions count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TableBasis {
    /// Fraction of the number of grains.
    Number,
    /// Fraction of the grain volume (a sieve curve: volume or mass passing).
    Volume,
    /// Fraction of the grain area, in 2D (the area passing by equivalent-circle
    /// diameter, as image analysis of a section measures it).
    Area,
}

impl TableBasis {
    /// The power of the diameter a grain's weight grows with: 0 (count), 3 or 2.
    pub fn weight_power(self) -> i32 {
        match self {
            Self::Number => 0,
            Self::Volume => 3,
            Self::Area => 2,
        }
    }
}

/// How a table's fractions are interpolated between points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TableInterpolation {
    /// Linear in `x`.
    Linear,
    /// Linear in `ln x` (a grading curve drawn on a log axis).
    Log,
}

/// A tabulated CDF, converted to the number law that grains are drawn from.
#[derive(Debug, Clone, PartialEq)]
pub struct TableLaw {
    /// The points `xᵢ`, strictly increasing and positive.
    pub x: Arc<[f64]>,
    /// The fractions as given, rescaled to run from 0 to 1.
    pub fraction: Arc<[f64]>,
    /// What the fractions count.
    pub basis: TableBasis,
    /// How they are interpolated.
    pub interpolation: TableInterpolation,
    /// Number CDF at each point (0 first, 1 last).
    number_cdf: Arc<[f64]>,
}

/// `∫ₐᵇ xᵠ dx` (q an integer, `0 < a ≤ b`).
fn power_integral(q: i32, a: f64, b: f64) -> f64 {
    if q == -1 {
        (b / a).ln()
    } else {
        let q1 = f64::from(q + 1);
        (b.powf(q1) - a.powf(q1)) / q1
    }
}

/// The `x` in `[a, b]` with `∫ₐˣ tᵖ dt = t · ∫ₐᵇ tᵖ dt`.
fn invert_power_integral(p: i32, a: f64, b: f64, t: f64) -> f64 {
    let x = if p == -1 {
        a * (b / a).powf(t)
    } else {
        let p1 = f64::from(p + 1);
        (a.powf(p1) + t * (b.powf(p1) - a.powf(p1))).powf(1.0 / p1)
    };
    x.clamp(a, b)
}

/// Why a table is not a law, naming the entry (0-based index) at fault.
#[derive(Debug, Clone, PartialEq)]
pub struct TableError {
    /// The key: `"x"` or `"cdf"`.
    pub key: &'static str,
    /// The entry at fault, if one.
    pub index: Option<usize>,
    /// What is wrong.
    pub reason: String,
}

impl TableLaw {
    /// A table from points `x` and fractions `fraction` (any scale: percent or
    /// fractions; only their increase matters). Checks that there are at least two
    /// points, as many fractions, `x` positive, finite and strictly increasing, and the
    /// fractions finite, non-decreasing and not all equal.
    pub fn new(
        x: &[f64],
        fraction: &[f64],
        basis: TableBasis,
        interpolation: TableInterpolation,
    ) -> Result<Self, TableError> {
        let err = |key, index, reason: String| TableError { key, index, reason };
        if x.len() < 2 {
            return Err(err("x", None, "needs at least two points".into()));
        }
        if fraction.len() != x.len() {
            return Err(err(
                "cdf",
                None,
                format!("has {} entries but x has {}", fraction.len(), x.len()),
            ));
        }
        for (i, &v) in x.iter().enumerate() {
            if !(v.is_finite() && v > 0.0) {
                return Err(err(
                    "x",
                    Some(i),
                    format!("{v} must be positive and finite"),
                ));
            }
            if i > 0 && v <= x[i - 1] {
                return Err(err(
                    "x",
                    Some(i),
                    format!(
                        "{v} is not above the previous point {}: x must increase",
                        x[i - 1]
                    ),
                ));
            }
        }
        for (i, &f) in fraction.iter().enumerate() {
            if !f.is_finite() || f < 0.0 {
                return Err(err(
                    "cdf",
                    Some(i),
                    format!("{f} must be a finite fraction ≥ 0"),
                ));
            }
            if i > 0 && f < fraction[i - 1] {
                return Err(err(
                    "cdf",
                    Some(i),
                    format!(
                        "{f} is below the previous value {}: a CDF never decreases",
                        fraction[i - 1]
                    ),
                ));
            }
        }
        let (f0, f1) = (fraction[0], fraction[fraction.len() - 1]);
        if f1 <= f0 {
            return Err(err(
                "cdf",
                None,
                "all values are equal: the table holds no grains".into(),
            ));
        }
        let scaled: Vec<f64> = fraction.iter().map(|f| (f - f0) / (f1 - f0)).collect();
        let p = exponent(basis, interpolation);
        // Number mass of each interval: the given fraction for a number table; for a
        // volume (area) table, ΔF / ∫x^{p+3} · ∫x^p (x^{p+2}).
        let mass: Vec<f64> = (0..x.len() - 1)
            .map(|i| {
                let df = scaled[i + 1] - scaled[i];
                match basis {
                    TableBasis::Number => df,
                    TableBasis::Volume | TableBasis::Area => {
                        let w = basis.weight_power();
                        df * power_integral(p, x[i], x[i + 1])
                            / power_integral(p + w, x[i], x[i + 1])
                    }
                }
            })
            .collect();
        let total: f64 = mass.iter().sum();
        let mut number_cdf = Vec::with_capacity(x.len());
        let mut acc = 0.0;
        number_cdf.push(0.0);
        for m in &mass {
            acc += m / total;
            number_cdf.push(acc);
        }
        *number_cdf.last_mut().expect("two points or more") = 1.0;
        Ok(Self {
            x: x.into(),
            fraction: scaled.into(),
            basis,
            interpolation,
            number_cdf: number_cdf.into(),
        })
    }

    /// The exponent `p` of the number density `∝ xᵖ` in each interval.
    fn p(&self) -> i32 {
        exponent(self.basis, self.interpolation)
    }

    /// First and last point.
    pub fn support(&self) -> (f64, f64) {
        (self.x[0], self.x[self.x.len() - 1])
    }

    /// The interval holding `x` (clamped to the table).
    fn interval(&self, x: f64) -> usize {
        let i = self.x.partition_point(|&v| v <= x);
        i.clamp(1, self.x.len() - 1) - 1
    }

    /// The number CDF `P(X ≤ x)` of the law grains are drawn from.
    pub fn cdf(&self, x: f64) -> f64 {
        let (lo, hi) = self.support();
        if x < lo {
            return 0.0;
        }
        if x >= hi {
            return 1.0;
        }
        let i = self.interval(x);
        let (a, b) = (self.x[i], self.x[i + 1]);
        let t = power_integral(self.p(), a, x) / power_integral(self.p(), a, b);
        self.number_cdf[i] + t * (self.number_cdf[i + 1] - self.number_cdf[i])
    }

    /// The table's own curve at `x`: the interpolated fraction (by number or by volume,
    /// as given), 0 below the table and 1 above.
    pub fn given_cdf(&self, x: f64) -> f64 {
        let (lo, hi) = self.support();
        if x < lo {
            return 0.0;
        }
        if x >= hi {
            return 1.0;
        }
        let i = self.interval(x);
        let (a, b) = (self.x[i], self.x[i + 1]);
        let t = match self.interpolation {
            TableInterpolation::Linear => (x - a) / (b - a),
            TableInterpolation::Log => (x / a).ln() / (b / a).ln(),
        };
        self.fraction[i] + t * (self.fraction[i + 1] - self.fraction[i])
    }

    /// The number density: the derivative of [`TableLaw::cdf`].
    pub fn pdf(&self, x: f64) -> f64 {
        let (lo, hi) = self.support();
        if !(lo..=hi).contains(&x) {
            return 0.0;
        }
        let i = self.interval(x);
        let (a, b) = (self.x[i], self.x[i + 1]);
        (self.number_cdf[i + 1] - self.number_cdf[i]) * x.powi(self.p())
            / power_integral(self.p(), a, b)
    }

    /// The value whose number CDF is `u` in `[0, 1]` (the inverse of
    /// [`TableLaw::cdf`]); a uniform `u` gives a draw of the law.
    pub fn quantile(&self, u: f64) -> f64 {
        let i = self
            .number_cdf
            .partition_point(|&c| c <= u)
            .clamp(1, self.x.len() - 1)
            - 1;
        let (c0, c1) = (self.number_cdf[i], self.number_cdf[i + 1]);
        let t = if c1 > c0 { (u - c0) / (c1 - c0) } else { 0.0 };
        invert_power_integral(self.p(), self.x[i], self.x[i + 1], t.clamp(0.0, 1.0))
    }

    /// The raw moment `E[Xᵏ]` of the number law, exact.
    pub fn moment(&self, k: u32) -> f64 {
        let p = self.p();
        (0..self.x.len() - 1)
            .map(|i| {
                let (a, b) = (self.x[i], self.x[i + 1]);
                let m = self.number_cdf[i + 1] - self.number_cdf[i];
                m * power_integral(p + k as i32, a, b) / power_integral(p, a, b)
            })
            .sum()
    }
}

fn exponent(basis: TableBasis, interpolation: TableInterpolation) -> i32 {
    match (basis, interpolation) {
        (TableBasis::Number, TableInterpolation::Linear) => 0,
        (TableBasis::Number, TableInterpolation::Log) => -1,
        (TableBasis::Volume, TableInterpolation::Linear) => -3,
        (TableBasis::Volume, TableInterpolation::Log) => -4,
        (TableBasis::Area, TableInterpolation::Linear) => -2,
        (TableBasis::Area, TableInterpolation::Log) => -3,
    }
}

/// The empirical law of a list of values (a measured grain table's column): each value
/// has probability `1/n`.
#[derive(Debug, Clone, PartialEq)]
pub struct EmpiricalLaw {
    /// The values, sorted ascending; at least one.
    pub sorted: Arc<[f64]>,
}

impl EmpiricalLaw {
    /// The law of `values` (finite, at least one).
    pub fn new(values: &[f64]) -> Self {
        let mut v = values.to_vec();
        v.sort_by(f64::total_cmp);
        Self { sorted: v.into() }
    }

    /// `P(X ≤ x)`: the share of values at or below `x`.
    pub fn cdf(&self, x: f64) -> f64 {
        self.sorted.partition_point(|&v| v <= x) as f64 / self.sorted.len() as f64
    }

    /// `E[Xᵏ]`.
    pub fn moment(&self, k: u32) -> f64 {
        self.sorted.iter().map(|v| v.powi(k as i32)).sum::<f64>() / self.sorted.len() as f64
    }

    /// Smallest and largest value.
    pub fn support(&self) -> (f64, f64) {
        (self.sorted[0], self.sorted[self.sorted.len() - 1])
    }
}

#[cfg(test)]
mod tests;
