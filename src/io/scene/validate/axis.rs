//! Axes and directions as a scene file gives them: `"x"`, `"y"`, `"z"` or `[x, y, z]`.

use crate::io::scene::error::{SceneError, Source};
use crate::scene::Axis;
use toml::Spanned;

pub(super) fn named_axis(value: &toml::Value) -> Option<Axis> {
    match value.as_str()? {
        "x" => Some(Axis::X),
        "y" => Some(Axis::Y),
        "z" => Some(Axis::Z),
        _ => None,
    }
}

/// `"x"`, `"y"`, `"z"` or a non-zero `[x, y, z]`, as a unit vector.
pub(super) fn direction(
    src: &Source,
    key: &str,
    raw: &Spanned<toml::Value>,
) -> Result<[f64; 3], SceneError> {
    if let Some(axis) = named_axis(raw.get_ref()) {
        return Ok(axis.unit());
    }
    let bad = || {
        src.invalid_at(
            key,
            raw,
            "must be \"x\", \"y\", \"z\" or a non-zero vector [x, y, z]",
        )
    };
    let items = raw
        .get_ref()
        .as_array()
        .filter(|a| a.len() == 3)
        .ok_or_else(bad)?;
    let mut v = [0.0; 3];
    for (slot, item) in v.iter_mut().zip(items) {
        *slot = item
            .as_float()
            .or_else(|| item.as_integer().map(|i| i as f64))
            .filter(|x| x.is_finite())
            .ok_or_else(bad)?;
    }
    let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    if !(norm > 0.0 && norm.is_finite()) {
        return Err(bad());
    }
    Ok(v.map(|x| x / norm))
}
