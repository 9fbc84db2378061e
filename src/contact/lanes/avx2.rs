//! [`super::F`] as two AVX2 registers of four lanes; masks as two registers of
//! all-ones or all-zeros lanes.
//!
//! Compiled only where the build targets these instructions (see the `cfg` of `imp` in
//! `lanes`); each `unsafe` block says why it is sound.

use std::arch::x86_64::*;

pub type Raw = [__m256d; 2];
pub type RawMask = [__m256d; 2];

#[inline(always)]
fn both(f: impl Fn(usize) -> __m256d) -> Raw {
    [f(0), f(1)]
}

#[inline(always)]
pub fn splat(x: f64) -> Raw {
    // SAFETY: a register-only intrinsic (no memory access); AVX2 with FMA is enabled at
    // compile time (the module's cfg), so every machine the build runs on has it.
    unsafe { [_mm256_set1_pd(x); 2] }
}

#[inline(always)]
pub fn load(x: [f64; 8]) -> Raw {
    // SAFETY: for h in {0, 1}, `x[4 * h..]` holds at least the four doubles the unaligned
    // load reads; AVX2 with FMA is enabled at compile time (the module's cfg).
    both(|h| unsafe { _mm256_loadu_pd(x[4 * h..].as_ptr()) })
}

#[inline(always)]
pub fn store(x: Raw) -> [f64; 8] {
    let mut out = [0.0; 8];
    for (h, v) in x.iter().enumerate() {
        // SAFETY: for h in {0, 1}, `out[4 * h..]` has room for the four doubles the
        // unaligned store writes; AVX2 with FMA is enabled at compile time (module cfg).
        unsafe { _mm256_storeu_pd(out[4 * h..].as_mut_ptr(), *v) };
    }
    out
}

/// `pub fn name(x, y)` as one intrinsic on each half.
macro_rules! binary {
    ($($name:ident => $intrinsic:ident $(::<$c:ident>)?),* $(,)?) => {$(
        #[inline(always)]
        pub fn $name(x: Raw, y: Raw) -> Raw {
            // SAFETY: a register-only intrinsic (no memory access); AVX2 with FMA is
            // enabled at compile time (the module's cfg), so every machine the build runs
            // on has it.
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
    // SAFETY: a register-only intrinsic (no memory access); AVX2 with FMA is enabled at
    // compile time (the module's cfg), so every machine the build runs on has it.
    both(|h| unsafe { _mm256_fmadd_pd(x[h], y[h], z[h]) })
}

#[inline(always)]
pub fn sqrt(x: Raw) -> Raw {
    // SAFETY: a register-only intrinsic (no memory access); AVX2 with FMA is enabled at
    // compile time (the module's cfg), so every machine the build runs on has it.
    both(|h| unsafe { _mm256_sqrt_pd(x[h]) })
}

/// The sign bit cleared.
#[inline(always)]
pub fn abs(x: Raw) -> Raw {
    // SAFETY: a register-only intrinsic (no memory access); AVX2 with FMA is enabled at
    // compile time (the module's cfg), so every machine the build runs on has it.
    both(|h| unsafe { _mm256_andnot_pd(_mm256_set1_pd(-0.0), x[h]) })
}

/// The sign bit flipped, as `-x` does (also for zeros and NaNs).
#[inline(always)]
pub fn neg(x: Raw) -> Raw {
    // SAFETY: a register-only intrinsic (no memory access); AVX2 with FMA is enabled at
    // compile time (the module's cfg), so every machine the build runs on has it.
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
    // SAFETY: a register-only intrinsic (no memory access); AVX2 with FMA is enabled at
    // compile time (the module's cfg), so every machine the build runs on has it.
    both(|h| unsafe { _mm256_blendv_pd(no[h], yes[h], m[h]) })
}

#[inline(always)]
pub fn mask_from(b: [bool; 8]) -> RawMask {
    let lane = |k: usize| -i64::from(b[k]);
    // SAFETY: a register-only intrinsic (no memory access); AVX2 with FMA is enabled at
    // compile time (the module's cfg), so every machine the build runs on has it.
    both(|h| unsafe {
        let [a, b, c, d] = [0, 1, 2, 3].map(|i| lane(4 * h + i));
        _mm256_castsi256_pd(_mm256_set_epi64x(d, c, b, a))
    })
}

#[inline(always)]
pub fn mask_get(m: RawMask, k: usize) -> bool {
    // SAFETY: a register-only intrinsic (no memory access); AVX2 with FMA is enabled at
    // compile time (the module's cfg), so every machine the build runs on has it.
    let bits = unsafe { _mm256_movemask_pd(m[k / 4]) };
    (bits >> (k % 4)) & 1 == 1
}

#[inline(always)]
pub fn and(a: RawMask, b: RawMask) -> RawMask {
    // SAFETY: a register-only intrinsic (no memory access); AVX2 with FMA is enabled at
    // compile time (the module's cfg), so every machine the build runs on has it.
    both(|h| unsafe { _mm256_and_pd(a[h], b[h]) })
}

#[inline(always)]
pub fn or(a: RawMask, b: RawMask) -> RawMask {
    // SAFETY: a register-only intrinsic (no memory access); AVX2 with FMA is enabled at
    // compile time (the module's cfg), so every machine the build runs on has it.
    both(|h| unsafe { _mm256_or_pd(a[h], b[h]) })
}

#[inline(always)]
pub fn not(a: RawMask) -> RawMask {
    // SAFETY: a register-only intrinsic (no memory access); AVX2 with FMA is enabled at
    // compile time (the module's cfg), so every machine the build runs on has it.
    both(|h| unsafe { _mm256_xor_pd(a[h], _mm256_castsi256_pd(_mm256_set1_epi64x(-1))) })
}
