//! Error-free transformations and double-double sums, for the accurate contact function.
//!
//! A double-double is an unevaluated sum `hi + lo` with `|lo| ≤ ulp(hi)/2`, about 106
//! bits (Dekker 1971; Ogita, Rump & Oishi 2005 for the compensated dot product).

use super::sym::Arith;

/// `a + b = s + e` exactly (Knuth's TwoSum).
#[inline(always)]
pub(crate) fn two_sum<T: Arith>(a: T, b: T) -> (T, T) {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    (s, e)
}

/// `a · b = p + e` exactly (barring underflow): FMA where the target has it, Dekker's
/// splitting otherwise.
#[inline(always)]
pub(crate) fn two_prod<T: Arith>(a: T, b: T) -> (T, T) {
    let p = a * b;
    #[cfg(target_feature = "fma")]
    {
        (p, a.mul_add(b, -p))
    }
    #[cfg(not(target_feature = "fma"))]
    {
        let (ah, al) = split(a);
        let (bh, bl) = split(b);
        (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
    }
}

#[cfg(not(target_feature = "fma"))]
#[inline(always)]
fn split<T: Arith>(a: T) -> (T, T) {
    // Veltkamp's splitter 2^27 + 1 cuts a double into two halves of 26 bits.
    const SPLITTER: f64 = 134_217_729.0;
    let c = a.times(SPLITTER);
    let hi = c - (c - a);
    (hi, a - hi)
}

/// A double-double accumulator: adds doubles and exact products without losing bits
/// (the running error is kept in `lo` and only rounded at the end).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Acc<T = f64> {
    pub hi: T,
    pub lo: T,
}

impl Acc {
    #[inline(always)]
    pub fn new(x: f64) -> Self {
        Self { hi: x, lo: 0.0 }
    }
}

impl<T: Arith> Acc<T> {
    /// The exact product `a · b`.
    #[inline(always)]
    pub fn from_prod(a: T, b: T) -> Self {
        let (hi, lo) = two_prod(a, b);
        Self { hi, lo }
    }

    /// Adds `x`.
    #[inline(always)]
    pub fn add(&mut self, x: T) {
        let (s, e) = two_sum(self.hi, x);
        self.hi = s;
        self.lo = self.lo + e;
    }

    /// Adds `a · b`, exactly up to the final rounding.
    #[inline(always)]
    pub fn add_prod(&mut self, a: T, b: T) {
        let (p, e) = two_prod(a, b);
        self.add(p);
        self.lo = self.lo + e;
    }

    /// The sum rounded to a double.
    #[inline(always)]
    pub fn value(&self) -> T {
        self.hi + self.lo
    }

    /// The sum renormalised to a double-double `(hi, lo)`.
    #[inline(always)]
    pub fn pair(&self) -> (T, T) {
        two_sum(self.hi, self.lo)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_prod_is_exact() {
        let a = 1.0 + f64::EPSILON;
        let b = 1.0 - f64::EPSILON;
        let (p, e) = two_prod(a, b);
        // (1+ε)(1−ε) = 1 − ε², which rounds to 1 with error −ε².
        assert_eq!(p, 1.0);
        assert_eq!(e, -f64::EPSILON * f64::EPSILON);
    }

    #[test]
    fn accumulator_keeps_cancelled_bits() {
        let mut acc = Acc::new(1e16);
        acc.add(1.0);
        acc.add(-1e16);
        assert_eq!(acc.value(), 1.0);
    }
}
