//! Eight `f64` lanes with lane-by-lane arithmetic, for evaluating eight pairs at once.
//!
//! Every operation is the IEEE operation of the scalar code, lane by lane (`mul_add`
//! rounds once, like `f64::mul_add`), so results are bitwise those of the scalar
//! functions; the batch tests check it. With AVX-512 a value is one register and each
//! operation one instruction, with AVX2 two of each; otherwise an array does the same
//! lane by lane. (Not `std::simd`, which is not stable; LLVM does not vectorise the
//! array form well.)

use std::ops::{Add, Div, Mul, Neg, Sub};

/// Lanes per batch.
pub(crate) const LANES: usize = 8;

/// One `f64` per lane.
#[derive(Debug, Clone, Copy)]
pub(crate) struct F(imp::Raw);

/// One `bool` per lane.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Mask(imp::RawMask);

impl F {
    #[inline(always)]
    pub fn splat(x: f64) -> Self {
        Self(imp::splat(x))
    }

    #[inline(always)]
    pub fn from_array(x: [f64; LANES]) -> Self {
        Self(imp::load(x))
    }

    #[inline(always)]
    pub fn to_array(self) -> [f64; LANES] {
        imp::store(self.0)
    }

    #[inline(always)]
    pub fn from_fn(f: impl FnMut(usize) -> f64) -> Self {
        Self::from_array(std::array::from_fn(f))
    }

    /// `self · b + c` with one rounding, lane by lane.
    #[inline(always)]
    pub fn mul_add(self, b: Self, c: Self) -> Self {
        Self(imp::mul_add(self.0, b.0, c.0))
    }

    #[inline(always)]
    pub fn sqrt(self) -> Self {
        Self(imp::sqrt(self.0))
    }

    #[inline(always)]
    pub fn abs(self) -> Self {
        Self(imp::abs(self.0))
    }

    /// Set where the lane is neither infinite nor NaN.
    #[inline(always)]
    pub fn is_finite(self) -> Mask {
        self.abs().lt(F::splat(f64::INFINITY))
    }

    #[inline(always)]
    pub fn lt(self, o: Self) -> Mask {
        Mask(imp::lt(self.0, o.0))
    }

    #[inline(always)]
    pub fn le(self, o: Self) -> Mask {
        Mask(imp::le(self.0, o.0))
    }

    #[inline(always)]
    pub fn gt(self, o: Self) -> Mask {
        o.lt(self)
    }

    #[inline(always)]
    pub fn ge(self, o: Self) -> Mask {
        o.le(self)
    }

    #[inline(always)]
    pub fn eq(self, o: Self) -> Mask {
        Mask(imp::eq(self.0, o.0))
    }
}

impl Mask {
    #[inline(always)]
    pub fn splat(b: bool) -> Self {
        Self::from_fn(|_| b)
    }

    #[inline(always)]
    pub fn from_fn(f: impl FnMut(usize) -> bool) -> Self {
        Self(imp::mask_from(std::array::from_fn(f)))
    }

    #[inline(always)]
    pub fn get(self, k: usize) -> bool {
        imp::mask_get(self.0, k)
    }

    /// `yes` where set, `no` elsewhere.
    #[inline(always)]
    pub fn select(self, yes: F, no: F) -> F {
        F(imp::select(self.0, yes.0, no.0))
    }

    #[inline(always)]
    pub fn and(self, o: Self) -> Self {
        Self(imp::and(self.0, o.0))
    }

    #[inline(always)]
    pub fn or(self, o: Self) -> Self {
        Self(imp::or(self.0, o.0))
    }

    #[inline(always)]
    pub fn not(self) -> Self {
        Self(imp::not(self.0))
    }

    #[inline(always)]
    pub fn any(self) -> bool {
        (0..LANES).any(|k| self.get(k))
    }
}

/// `N` values of each of eight items, as `N` lane vectors: lane `k` of vector `i` is
/// `f(&items[k])[i]`.
#[inline(always)]
pub(crate) fn gather<R, const N: usize>(items: &[R; LANES], f: impl Fn(&R) -> [f64; N]) -> [F; N] {
    let rows: [[f64; N]; LANES] = std::array::from_fn(|k| f(&items[k]));
    std::array::from_fn(|i| F::from_fn(|k| rows[k][i]))
}

macro_rules! lanewise {
    ($trait:ident, $f:ident) => {
        impl $trait for F {
            type Output = F;
            #[inline(always)]
            fn $f(self, o: F) -> F {
                F(imp::$f(self.0, o.0))
            }
        }
        impl $trait<F> for f64 {
            type Output = F;
            #[inline(always)]
            fn $f(self, o: F) -> F {
                F(imp::$f(imp::splat(self), o.0))
            }
        }
        impl $trait<f64> for F {
            type Output = F;
            #[inline(always)]
            fn $f(self, o: f64) -> F {
                F(imp::$f(self.0, imp::splat(o)))
            }
        }
    };
}

lanewise!(Add, add);
lanewise!(Sub, sub);
lanewise!(Mul, mul);
lanewise!(Div, div);

impl Neg for F {
    type Output = F;
    #[inline(always)]
    fn neg(self) -> F {
        F(imp::neg(self.0))
    }
}

// One implementation per build: AVX-512, else AVX2 with FMA, else plain arrays.
#[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
mod avx512;
#[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
use avx512 as imp;

#[cfg(all(
    target_arch = "x86_64",
    target_feature = "avx2",
    target_feature = "fma",
    not(target_feature = "avx512f")
))]
mod avx2;
#[cfg(all(
    target_arch = "x86_64",
    target_feature = "avx2",
    target_feature = "fma",
    not(target_feature = "avx512f")
))]
use avx2 as imp;

#[cfg(not(all(
    target_arch = "x86_64",
    any(
        target_feature = "avx512f",
        all(target_feature = "avx2", target_feature = "fma")
    )
)))]
mod portable;
#[cfg(not(all(
    target_arch = "x86_64",
    any(
        target_feature = "avx512f",
        all(target_feature = "avx2", target_feature = "fma")
    )
)))]
use portable as imp;

/// Whether the build targets vector registers for the lanes (AVX-512, or AVX2 with
/// FMA); without, they are plain arrays.
pub(crate) const IN_REGISTERS: bool = cfg!(all(
    target_arch = "x86_64",
    any(
        target_feature = "avx512f",
        all(target_feature = "avx2", target_feature = "fma")
    )
));

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn operations_are_lane_by_lane() {
        let a = F::from_fn(|k| k as f64);
        let b = F::splat(2.0);
        assert_eq!((a * b + 1.0).to_array()[3], 7.0);
        assert_eq!((1.0 - a / b).to_array()[4], -1.0);
        assert_eq!(a.mul_add(b, -a).to_array()[5], 5.0);
        let m = a.lt(F::splat(3.0));
        let picked = m.select(a, -a).to_array();
        assert_eq!(picked, [0.0, 1.0, 2.0, -3.0, -4.0, -5.0, -6.0, -7.0]);
        assert!(m.get(2) && !m.get(3) && m.or(m.not()).and(Mask::splat(true)).any());
    }

    /// Negation flips the sign of zeros, and comparisons with NaN are false, as in Rust.
    #[test]
    fn signs_and_nans_behave_as_scalars() {
        let z = -F::splat(0.0);
        assert!(z.to_array().iter().all(|x| x.is_sign_negative()));
        let nan = F::splat(f64::NAN);
        let one = F::splat(1.0);
        for m in [
            nan.lt(one),
            nan.le(one),
            nan.gt(one),
            nan.ge(one),
            nan.eq(nan),
        ] {
            assert!(!m.any());
        }
        assert_eq!(F::splat(-2.5).abs().to_array(), [2.5; 8]);
        let odd = F::from_array([
            1.0,
            f64::NAN,
            f64::INFINITY,
            -f64::INFINITY,
            0.0,
            -1e308,
            5e-324,
            2.0,
        ]);
        let finite = odd.is_finite();
        assert_eq!(
            (0..8).map(|k| finite.get(k)).collect::<Vec<_>>(),
            [true, false, false, false, true, true, true, true]
        );
    }
}
