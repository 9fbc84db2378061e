//! [`super::F`] as a plain array, lane by lane.

pub type Raw = [f64; 8];
pub type RawMask = [bool; 8];

#[inline(always)]
fn lanes<T>(f: impl FnMut(usize) -> T) -> [T; 8] {
    std::array::from_fn(f)
}

#[inline(always)]
pub fn splat(x: f64) -> Raw {
    [x; 8]
}

#[inline(always)]
pub fn load(x: [f64; 8]) -> Raw {
    x
}

#[inline(always)]
pub fn store(x: Raw) -> [f64; 8] {
    x
}

#[inline(always)]
pub fn add(x: Raw, y: Raw) -> Raw {
    lanes(|k| x[k] + y[k])
}

#[inline(always)]
pub fn sub(x: Raw, y: Raw) -> Raw {
    lanes(|k| x[k] - y[k])
}

#[inline(always)]
pub fn mul(x: Raw, y: Raw) -> Raw {
    lanes(|k| x[k] * y[k])
}

#[inline(always)]
pub fn div(x: Raw, y: Raw) -> Raw {
    lanes(|k| x[k] / y[k])
}

#[inline(always)]
pub fn mul_add(x: Raw, y: Raw, z: Raw) -> Raw {
    lanes(|k| x[k].mul_add(y[k], z[k]))
}

#[inline(always)]
pub fn sqrt(x: Raw) -> Raw {
    x.map(f64::sqrt)
}

#[inline(always)]
pub fn abs(x: Raw) -> Raw {
    x.map(f64::abs)
}

#[inline(always)]
pub fn neg(x: Raw) -> Raw {
    x.map(|v| -v)
}

#[inline(always)]
pub fn lt(x: Raw, y: Raw) -> RawMask {
    lanes(|k| x[k] < y[k])
}

#[inline(always)]
pub fn le(x: Raw, y: Raw) -> RawMask {
    lanes(|k| x[k] <= y[k])
}

#[inline(always)]
pub fn eq(x: Raw, y: Raw) -> RawMask {
    lanes(|k| x[k] == y[k])
}

#[inline(always)]
pub fn select(m: RawMask, yes: Raw, no: Raw) -> Raw {
    lanes(|k| if m[k] { yes[k] } else { no[k] })
}

#[inline(always)]
pub fn mask_from(b: [bool; 8]) -> RawMask {
    b
}

#[inline(always)]
pub fn mask_get(m: RawMask, k: usize) -> bool {
    m[k]
}

#[inline(always)]
pub fn and(a: RawMask, b: RawMask) -> RawMask {
    lanes(|k| a[k] & b[k])
}

#[inline(always)]
pub fn or(a: RawMask, b: RawMask) -> RawMask {
    lanes(|k| a[k] | b[k])
}

#[inline(always)]
pub fn not(a: RawMask) -> RawMask {
    a.map(|x| !x)
}
