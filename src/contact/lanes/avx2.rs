//! [`super::F`] as two AVX2 registers of four lanes; masks as two registers of
//! all-ones or all-zeros lanes.
//!
//! SAFETY (every block here): the module is compiled only where the build targets AVX2
//! and FMA; loads and stores touch arrays of exactly eight elements, four at a time.

use std::arch::x86_64::*;

pub type Raw = [__m256d; 2];
pub type RawMask = [__m256d; 2];

#[inline(always)]
fn both(f: impl Fn(usize) -> __m256d) -> Raw {
    [f(0), f(1)]
}

#[inline(always)]
pub fn splat(x: f64) -> Raw {
    unsafe { [_mm256_set1_pd(x); 2] }
}

#[inline(always)]
pub fn load(x: [f64; 8]) -> Raw {
    both(|h| unsafe { _mm256_loadu_pd(x[4 * h..].as_ptr()) })
}

#[inline(always)]
pub fn store(x: Raw) -> [f64; 8] {
    let mut out = [0.0; 8];
    for (h, v) in x.iter().enumerate() {
        unsafe { _mm256_storeu_pd(out[4 * h..].as_mut_ptr(), *v) };
    }
    out
}

/// `pub fn name(x, y)` as one intrinsic on each half.
macro_rules! binary {
    ($($name:ident => $intrinsic:ident $(::<$c:ident>)?),* $(,)?) => {$(
        #[inline(always)]
        pub fn $name(x: Raw, y: Raw) -> Raw {
            both(|h| unsafe { $intrinsic$(::<$c>)?(x[h], y[h]) })
        }
    )*};
}

binary!(
    add => _mm256_add_pd,
    sub => _mm256_sub_pd,
    mul => _mm256_mul_pd,
    div => _mm256_div_pd,
);

#[inline(always)]
pub fn mul_add(x: Raw, y: Raw, z: Raw) -> Raw {
    both(|h| unsafe { _mm256_fmadd_pd(x[h], y[h], z[h]) })
}

#[inline(always)]
pub fn sqrt(x: Raw) -> Raw {
    both(|h| unsafe { _mm256_sqrt_pd(x[h]) })
}

/// The sign bit cleared.
#[inline(always)]
pub fn abs(x: Raw) -> Raw {
    both(|h| unsafe { _mm256_andnot_pd(_mm256_set1_pd(-0.0), x[h]) })
}

/// The sign bit flipped, as `-x` does (also for zeros and NaNs).
#[inline(always)]
pub fn neg(x: Raw) -> Raw {
    both(|h| unsafe { _mm256_xor_pd(_mm256_set1_pd(-0.0), x[h]) })
}

// Ordered, quiet comparisons: false where either side is NaN, as in Rust. (Masks are
// `Raw` too: all-ones or all-zeros lanes.)
binary!(
    lt => _mm256_cmp_pd::<_CMP_LT_OQ>,
    le => _mm256_cmp_pd::<_CMP_LE_OQ>,
    eq => _mm256_cmp_pd::<_CMP_EQ_OQ>,
);

#[inline(always)]
pub fn select(m: RawMask, yes: Raw, no: Raw) -> Raw {
    both(|h| unsafe { _mm256_blendv_pd(no[h], yes[h], m[h]) })
}

#[inline(always)]
pub fn mask_from(b: [bool; 8]) -> RawMask {
    let lane = |k: usize| -i64::from(b[k]);
    both(|h| unsafe {
        let [a, b, c, d] = [0, 1, 2, 3].map(|i| lane(4 * h + i));
        _mm256_castsi256_pd(_mm256_set_epi64x(d, c, b, a))
    })
}

#[inline(always)]
pub fn mask_get(m: RawMask, k: usize) -> bool {
    let bits = unsafe { _mm256_movemask_pd(m[k / 4]) };
    (bits >> (k % 4)) & 1 == 1
}

#[inline(always)]
pub fn and(a: RawMask, b: RawMask) -> RawMask {
    both(|h| unsafe { _mm256_and_pd(a[h], b[h]) })
}

#[inline(always)]
pub fn or(a: RawMask, b: RawMask) -> RawMask {
    both(|h| unsafe { _mm256_or_pd(a[h], b[h]) })
}

#[inline(always)]
pub fn not(a: RawMask) -> RawMask {
    both(|h| unsafe { _mm256_xor_pd(a[h], _mm256_castsi256_pd(_mm256_set1_epi64x(-1))) })
}
