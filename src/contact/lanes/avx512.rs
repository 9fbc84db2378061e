//! [`super::F`] as one AVX-512 register.
//!
//! Compiled only where the build targets these instructions (see the `cfg` of `imp` in
//! `lanes`); each `unsafe` block says why it is sound.

use std::arch::x86_64::*;

pub type Raw = __m512d;
pub type RawMask = __mmask8;

#[inline(always)]
pub fn splat(x: f64) -> Raw {
    // SAFETY: a register-only intrinsic (no memory access); AVX-512F is enabled at compile
    // time (the module's cfg), so every machine the build runs on has it.
    unsafe { _mm512_set1_pd(x) }
}

#[inline(always)]
pub fn load(x: [f64; 8]) -> Raw {
    // SAFETY: `x` holds exactly the eight doubles the unaligned load reads; AVX-512F is
    // enabled at compile time (the module's cfg).
    unsafe { _mm512_loadu_pd(x.as_ptr()) }
}

#[inline(always)]
pub fn store(x: Raw) -> [f64; 8] {
    let mut out = [0.0; 8];
    // SAFETY: `out` has room for exactly the eight doubles the unaligned store writes;
    // AVX-512F is enabled at compile time (the module's cfg).
    unsafe { _mm512_storeu_pd(out.as_mut_ptr(), x) };
    out
}

/// `pub fn name(x, y)` as one intrinsic.
macro_rules! binary {
    ($($name:ident => $intrinsic:ident $(::<$c:ident>)?: $out:ty),* $(,)?) => {$(
        #[inline(always)]
        pub fn $name(x: Raw, y: Raw) -> $out {
            // SAFETY: a register-only intrinsic (no memory access); AVX-512F is enabled at
            // compile time (the module's cfg), so every machine the build runs on has it.
            unsafe { $intrinsic$(::<$c>)?(x, y) }
        }
    )*};
}

binary!(
    add => _mm512_add_pd: Raw,
    sub => _mm512_sub_pd: Raw,
    mul => _mm512_mul_pd: Raw,
    div => _mm512_div_pd: Raw,
);

#[inline(always)]
pub fn mul_add(x: Raw, y: Raw, z: Raw) -> Raw {
    // SAFETY: a register-only intrinsic (no memory access); AVX-512F is enabled at compile
    // time (the module's cfg), so every machine the build runs on has it.
    unsafe { _mm512_fmadd_pd(x, y, z) }
}

#[inline(always)]
pub fn sqrt(x: Raw) -> Raw {
    // SAFETY: a register-only intrinsic (no memory access); AVX-512F is enabled at compile
    // time (the module's cfg), so every machine the build runs on has it.
    unsafe { _mm512_sqrt_pd(x) }
}

#[inline(always)]
pub fn abs(x: Raw) -> Raw {
    // SAFETY: a register-only intrinsic (no memory access); AVX-512F is enabled at compile
    // time (the module's cfg), so every machine the build runs on has it.
    unsafe { _mm512_abs_pd(x) }
}

/// The sign bit flipped, as `-x` does (also for zeros and NaNs).
#[inline(always)]
pub fn neg(x: Raw) -> Raw {
    // SAFETY: a register-only intrinsic (no memory access); AVX-512F is enabled at compile
    // time (the module's cfg), so every machine the build runs on has it.
    unsafe {
        let sign = _mm512_set1_epi64(i64::MIN);
        _mm512_castsi512_pd(_mm512_xor_si512(_mm512_castpd_si512(x), sign))
    }
}

// Ordered, quiet comparisons: false where either side is NaN, as in Rust.
binary!(
    lt => _mm512_cmp_pd_mask::<_CMP_LT_OQ>: RawMask,
    le => _mm512_cmp_pd_mask::<_CMP_LE_OQ>: RawMask,
    eq => _mm512_cmp_pd_mask::<_CMP_EQ_OQ>: RawMask,
);

#[inline(always)]
pub fn select(m: RawMask, yes: Raw, no: Raw) -> Raw {
    // SAFETY: a register-only intrinsic (no memory access); AVX-512F is enabled at compile
    // time (the module's cfg), so every machine the build runs on has it.
    unsafe { _mm512_mask_blend_pd(m, no, yes) }
}

#[inline(always)]
pub fn mask_from(b: [bool; 8]) -> RawMask {
    b.iter().rev().fold(0, |m, &x| (m << 1) | u8::from(x))
}

#[inline(always)]
pub fn mask_get(m: RawMask, k: usize) -> bool {
    (m >> k) & 1 == 1
}

#[inline(always)]
pub fn and(a: RawMask, b: RawMask) -> RawMask {
    a & b
}

#[inline(always)]
pub fn or(a: RawMask, b: RawMask) -> RawMask {
    a | b
}

#[inline(always)]
pub fn not(a: RawMask) -> RawMask {
    !a
}
