//! One function per fuzz target, from the input bytes to the properties checked.
//!
//! Properties, not only "no crash": bad input is a typed error that names its place
//! (file, line, key or row); a valid scene packs overlap-free or stops with a reason;
//! a contact answer is finite and obeys the symmetries to its documented bound. A
//! failed property is a panic with the input in its message, which libFuzzer and the
//! replay test report as a crash.

mod contact;
mod generate;
mod mesh;
mod pools;
mod scene;
mod tables;

pub use contact::{check_pair, check_pair_2d};
pub use generate::{scene_from_choices, Choices};
pub use mesh::MESH_EDITS;
pub use scene::{check_scene, SCENE_NAME};

/// Raw bytes as a scene file: read, validated, and packed when valid and tiny.
pub fn scene_bytes(data: &[u8]) {
    if let Ok(text) = std::str::from_utf8(data) {
        check_scene(text, SCENE_NAME);
    }
}

/// A scene made from the documented keys with values at and past their limits
/// ([`scene_from_choices`]), the bytes choosing which.
pub fn scene_keys(data: &[u8]) {
    let text = scene_from_choices(&mut Choices::new(data));
    check_scene(&text, SCENE_NAME);
}

/// Raw bytes as a `pack contact` case file, every row answered by every method.
pub fn contact_csv(data: &[u8]) {
    tables::contact_csv(data);
}

/// Raw bytes as the measured grain table of `[phase.measured]`; the first byte picks
/// the mode and the phase selection.
pub fn measured_table(data: &[u8]) {
    tables::measured_table(data);
}

/// Raw bytes as the orientation (EBSD) file of `[phase.texture] kind = "file"`.
pub fn orientation_file(data: &[u8]) {
    tables::orientation_file(data);
}

/// Arbitrary bit patterns as `r12`, `q1`, `q2` (15 doubles, little-endian), and one
/// byte for the power of two `r12` is scaled by.
pub fn contact_bits(data: &[u8]) {
    let mut x = [0.0; 15];
    for (v, chunk) in x.iter_mut().zip(data.chunks(8)) {
        let mut bytes = [0; 8];
        bytes[..chunk.len()].copy_from_slice(chunk);
        *v = f64::from_bits(u64::from_le_bytes(bytes));
    }
    let k = data.get(120).map_or(1, |&b| i32::from(b % 16) - 8);
    let r = [x[0], x[1], x[2]];
    let q1 = [x[3], x[4], x[5], x[6], x[7], x[8]];
    let q2 = [x[9], x[10], x[11], x[12], x[13], x[14]];
    check_pair(&r, &q1, &q2, if k == 0 { 1 } else { k });
}

/// Arbitrary bit patterns as a pair of ellipses: `r12`, `q1`, `q2` (8 doubles,
/// little-endian), and one byte for the power of two `r12` is scaled by.
pub fn contact_bits_2d(data: &[u8]) {
    let mut x = [0.0; 8];
    for (v, chunk) in x.iter_mut().zip(data.chunks(8)) {
        let mut bytes = [0; 8];
        bytes[..chunk.len()].copy_from_slice(chunk);
        *v = f64::from_bits(u64::from_le_bytes(bytes));
    }
    let k = data.get(64).map_or(1, |&b| i32::from(b % 16) - 8);
    check_pair_2d(
        &[x[0], x[1]],
        &[x[2], x[3], x[4]],
        &[x[5], x[6], x[7]],
        if k == 0 { 1 } else { k },
    );
}
