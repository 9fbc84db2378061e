//! The columns of a measured table: where its grains' sizes and orientations are, by
//! the scene's dimension (ellipsoids: `d` or `a1, a2, a3`, and `qw..qz`; ellipses:
//! `d` or `a1, a2`, and `angle`), and the columns of the other dimension refused.

use crate::contact::Dimension;

/// Where a table gives a grain's size: its diameter, or its semi-axes.
#[derive(Clone, Copy)]
pub(super) enum Shape {
    Diameter(usize),
    Ellipsoid([usize; 3]),
    Ellipse([usize; 2]),
}

/// Where a table gives a grain's orientation, if it does.
#[derive(Clone, Copy)]
pub(super) enum Turn {
    None,
    Quaternion([usize; 4]),
    /// An ellipse's angle from x, in degrees.
    Angle(usize),
}

/// The size and orientation columns of a 3D table: `d` or `a1, a2, a3`; `qw..qz`.
pub(super) fn three_columns(header: &[String], d: Option<usize>) -> Result<(Shape, Turn), String> {
    let shape = match (d, columns(header, &["a1", "a2", "a3"])) {
        (Some(_), Ok(Some(_)) | Err(_)) => return Err("give d or a1, a2, a3, not both".into()),
        (None, Err(_)) => return Err("a1, a2 and a3 go together".into()),
        (None, Ok(None)) => {
            return Err("needs a column d (equivalent diameter) or a1, a2, a3 (semi-axes)".into())
        }
        (None, Ok(Some(c))) => Shape::Ellipsoid(c),
        (Some(c), Ok(None)) => Shape::Diameter(c),
    };
    let turn = match columns(header, &["qw", "qx", "qy", "qz"]) {
        Ok(Some(c)) => Turn::Quaternion(c),
        Ok(None) => Turn::None,
        Err(_) => return Err("qw, qx, qy and qz go together".into()),
    };
    Ok((shape, turn))
}

/// The size and orientation columns of a 2D table: `d` (the equivalent-circle
/// diameter) or `a1, a2`; `angle`.
pub(super) fn two_columns(header: &[String], d: Option<usize>) -> Result<(Shape, Turn), String> {
    let shape = match (d, columns(header, &["a1", "a2"])?) {
        (Some(_), Some(_)) => return Err("give d or a1, a2, not both".into()),
        (None, None) => {
            return Err(
                "needs a column d (equivalent-circle diameter) or a1, a2 (semi-axes)".into(),
            )
        }
        (None, Some(c)) => Shape::Ellipse(c),
        (Some(c), None) => Shape::Diameter(c),
    };
    let turn = match header.iter().position(|h| h == "angle") {
        Some(c) => Turn::Angle(c),
        None => Turn::None,
    };
    Ok((shape, turn))
}

/// The columns that belong to the other dimension's tables, refused: `a3` and
/// `qw..qz` in a 2D scene; `angle`, or `a1`, `a2` without `a3`, in a 3D one.
pub(super) fn check_dimension(header: &[String], dimension: Dimension) -> Result<(), String> {
    let has = |name: &str| header.iter().any(|h| h == name);
    match dimension {
        Dimension::Two => match ["a3", "qw", "qx", "qy", "qz"].into_iter().find(|c| has(c)) {
            Some("a3") => Err("a3 has no meaning in a 2D scene (box.size = [Lx, Ly]): an \
                               ellipse's table gives d or a1, a2"
                .into()),
            Some(c) => Err(format!(
                "{c} has no meaning in a 2D scene (box.size = [Lx, Ly]): an ellipse's table \
                 gives its orientation as angle (degrees from x)"
            )),
            None => Ok(()),
        },
        Dimension::Three if has("angle") || (has("a1") && has("a2") && !has("a3")) => Err(
            "is a 2D table of ellipses (angle, or a1, a2 without a3), but the scene's box has \
             three lengths: give box.size = [Lx, Ly], or a3 and qw, qx, qy, qz"
                .into(),
        ),
        Dimension::Three => Ok(()),
    }
}

/// The positions of the columns `names` in `header`: all of them, or `None` if none
/// is there; an error if only some are.
pub(super) fn columns<const N: usize>(
    header: &[String],
    names: &[&str; N],
) -> Result<Option<[usize; N]>, String> {
    let found = names.map(|n| header.iter().position(|h| h == n));
    if found.iter().all(Option::is_some) {
        Ok(Some(found.map(|c| c.expect("all found"))))
    } else if found.iter().any(Option::is_some) {
        Err(format!("{} go together", names.join(", ")))
    } else {
        Ok(None)
    }
}
