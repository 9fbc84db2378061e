//! `[phase.measured]`: a phase's grains from a CSV table.
//!
//! The table has a header row. Columns, in the box's length unit: `d` (equivalent
//! diameter) or `a1`, `a2`, `a3` (semi-axes); optionally `qw`, `qx`, `qy`, `qz` (unit
//! quaternion, semi-axis k along column k of its rotation) and `phase` (an index or a
//! name, selected by the `phase` key); optionally the crystal orientation, `o0..o3`
//! (unit quaternion, scalar first) or else `phi1`, `Phi`, `phi2` (Bunge Euler angles,
//! degrees). Other columns (`id`, `x`, `y`, `z`, ...) are ignored, so a `grains.csv`
//! written by `pack` reads back as it is, crystal orientations included.
//!
//! A 2D scene's table is of ellipses: `d` (equivalent-circle diameter) or `a1`, `a2`
//! (semi-axes), and optionally `angle` (of `a1` from x, degrees) instead of the
//! quaternion; `a3` and `qw..qz` are refused there, and `angle` or `a1`, `a2` without
//! `a3` in a 3D scene.

use crate::contact::{ellipse_quaternion, ellipse_semi_axes, Dimension, QUATERNION_NORM_TOL};
use crate::io::scene::error::{DataFileError, SceneError, Source};
use crate::io::scene::raw::RawMeasured;
use crate::laws::{Distribution, EmpiricalLaw};
use crate::scene::{euler_to_quaternion, Measured, MeasuredGrain, MeasuredMode};
use std::path::Path;
use toml::Spanned;

/// `[phase.measured]` at key path `key`: the table read and checked, and the phase's
/// size law (the empirical law of its diameters).
pub(super) fn measured(
    src: &Source,
    key: &str,
    raw: &Spanned<RawMeasured>,
    dimension: Dimension,
) -> Result<(Measured, Distribution), SceneError> {
    let r = raw.get_ref();
    let file = r.file.get_ref();
    let path = Path::new(src.file)
        .parent()
        .unwrap_or(Path::new(""))
        .join(file);
    let mode = match r.mode.as_ref() {
        None => MeasuredMode::Draw,
        Some(m) => match m.get_ref().as_str() {
            "draw" => MeasuredMode::Draw,
            "exact" => MeasuredMode::Exact,
            _ => {
                return Err(src.invalid_at(
                    format!("{key}.mode"),
                    m,
                    "must be \"draw\" (grains drawn from the table with replacement) or \
                     \"exact\" (exactly the table's grains)",
                ))
            }
        },
    };
    let select = r.phase.as_ref().map(|p| match p.get_ref() {
        toml::Value::String(s) => Ok(s.clone()),
        toml::Value::Integer(i) => Ok(i.to_string()),
        _ => Err(src.invalid_at(
            format!("{key}.phase"),
            p,
            "must be a phase index or name as the table's phase column gives it",
        )),
    });
    let select = select.transpose()?;
    let text = std::fs::read_to_string(&path).map_err(|e| {
        src.invalid_at(
            format!("{key}.file"),
            &r.file,
            format!("cannot read {}: {e}", path.display()),
        )
    })?;
    let table_file = path.display().to_string();
    let grains = read_table(&text, select.as_deref(), dimension).map_err(
        |(line, column, value, reason)| {
            SceneError::DataFile(Box::new(DataFileError {
                file: src.file.to_owned(),
                key: format!("{key}.file"),
                path: table_file.clone(),
                line,
                column,
                value,
                reason,
            }))
        },
    )?;
    if grains.is_empty() {
        return Err(src.invalid_at(
            format!("{key}.file"),
            &r.file,
            match &select {
                Some(s) => format!("{} has no grain of phase {s}", path.display()),
                None => format!("{} has no grains", path.display()),
            },
        ));
    }
    let diameters: Vec<f64> = grains.iter().map(|g| g.diameter).collect();
    let size = Distribution::Empirical(EmpiricalLaw::new(&diameters));
    Ok((
        Measured {
            grains: grains.into(),
            mode,
            dimension,
        },
        size,
    ))
}

/// How far from 1 the norm of a unit quaternion read from 17 digits can be: its four
/// components each carry a relative rounding of `ε/2` (17 digits read back exactly),
/// and the sum of squares and the root add a few more `ε/2`; `8 ε` bounds them.
const UNIT_ROUNDING: f64 = 8.0 * f64::EPSILON;

/// A bad cell: line (1-based), column name, value, reason.
type Bad = (usize, String, String, String);

/// Reads the table's rows (of phase `select`, if given), of ellipsoids or ellipses.
fn read_table(
    text: &str,
    select: Option<&str>,
    dimension: Dimension,
) -> Result<Vec<MeasuredGrain>, Bad> {
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let header: Vec<String> = reader
        .headers()
        .map_err(|e| (1, "(header)".into(), String::new(), e.to_string()))?
        .iter()
        .map(str::to_owned)
        .collect();
    let find = |name: &str| header.iter().position(|h| h == name);
    let bad_header = |reason: &str| {
        (
            1,
            "(header)".to_owned(),
            header.join(","),
            reason.to_owned(),
        )
    };
    check_dimension(&header, dimension).map_err(|e| bad_header(&e))?;
    let d = find("d");
    let (shape, turn) = match dimension {
        Dimension::Three => three_columns(&header, d).map_err(|e| bad_header(&e))?,
        Dimension::Two => two_columns(&header, d).map_err(|e| bad_header(&e))?,
    };
    // Crystal orientations: o0..o3 (a unit quaternion, as pack writes them), else
    // phi1, Phi, phi2 (Bunge Euler angles in degrees).
    let crystal_quat = columns(&header, &["o0", "o1", "o2", "o3"]).map_err(|e| bad_header(&e))?;
    let euler = match crystal_quat {
        Some(_) => None,
        None => columns(&header, &["phi1", "Phi", "phi2"]).map_err(|e| bad_header(&e))?,
    };
    let phase_col = find("phase");
    if select.is_some() && phase_col.is_none() {
        return Err(bad_header(
            "has no phase column, but [phase.measured] selects a phase",
        ));
    }
    let mut grains = Vec::new();
    for record in reader.records() {
        let record = record.map_err(|e| {
            let line = e.position().map_or(0, |p| p.line() as usize);
            (line, "(row)".into(), String::new(), e.to_string())
        })?;
        let line = record.position().map_or(0, |p| p.line() as usize);
        if let (Some(sel), Some(c)) = (select, phase_col) {
            if record.get(c) != Some(sel) {
                continue;
            }
        }
        let cell = Cell {
            record: &record,
            header: &header,
            line,
        };
        let q = match turn {
            Turn::None => None,
            Turn::Quaternion(c) => {
                let q = [
                    cell.number(c[0])?,
                    cell.number(c[1])?,
                    cell.number(c[2])?,
                    cell.number(c[3])?,
                ];
                let norm = q.iter().map(|v| v * v).sum::<f64>().sqrt();
                if !((norm - 1.0).abs() <= QUATERNION_NORM_TOL) {
                    return Err((
                        line,
                        "qw".into(),
                        format!("[{}, {}, {}, {}]", q[0], q[1], q[2], q[3]),
                        format!(
                            "qw, qx, qy, qz must be a unit quaternion (norm {norm}, tolerance \
                             {QUATERNION_NORM_TOL:e})"
                        ),
                    ));
                }
                Some(cell.unit(q, "qw")?)
            }
            Turn::Angle(c) => Some(ellipse_quaternion(cell.number(c)?.to_radians())),
        };
        let crystal = match (crystal_quat, euler) {
            (Some(c), _) => Some(cell.unit(
                [
                    cell.number(c[0])?,
                    cell.number(c[1])?,
                    cell.number(c[2])?,
                    cell.number(c[3])?,
                ],
                "o0",
            )?),
            (None, Some(c)) => Some(euler_to_quaternion(
                [cell.number(c[0])?, cell.number(c[1])?, cell.number(c[2])?].map(f64::to_radians),
            )),
            (None, None) => None,
        };
        let mut grain = match shape {
            Shape::Ellipsoid(c) => MeasuredGrain::with_semi_axes(
                [
                    cell.positive(c[0])?,
                    cell.positive(c[1])?,
                    cell.positive(c[2])?,
                ],
                q,
            ),
            Shape::Ellipse(c) => {
                let axes = ellipse_semi_axes(cell.positive(c[0])?, cell.positive(c[1])?);
                MeasuredGrain {
                    diameter: Dimension::Two.equivalent_diameter(axes),
                    semi_axes: Some(axes),
                    quaternion: q,
                    crystal: None,
                }
            }
            Shape::Diameter(c) => MeasuredGrain {
                diameter: cell.positive(c)?,
                semi_axes: None,
                quaternion: q,
                crystal: None,
            },
        };
        grain.crystal = crystal;
        grains.push(grain);
    }
    Ok(grains)
}

/// Where a table gives a grain's size: its diameter, or its semi-axes.
#[derive(Clone, Copy)]
enum Shape {
    Diameter(usize),
    Ellipsoid([usize; 3]),
    Ellipse([usize; 2]),
}

/// Where a table gives a grain's orientation, if it does.
#[derive(Clone, Copy)]
enum Turn {
    None,
    Quaternion([usize; 4]),
    /// An ellipse's angle from x, in degrees.
    Angle(usize),
}

/// The size and orientation columns of a 3D table: `d` or `a1, a2, a3`; `qw..qz`.
fn three_columns(header: &[String], d: Option<usize>) -> Result<(Shape, Turn), String> {
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
fn two_columns(header: &[String], d: Option<usize>) -> Result<(Shape, Turn), String> {
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
fn check_dimension(header: &[String], dimension: Dimension) -> Result<(), String> {
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

/// One row's cells, read as numbers with errors naming line and column.
struct Cell<'a> {
    record: &'a csv::StringRecord,
    header: &'a [String],
    line: usize,
}

impl Cell<'_> {
    fn number(&self, c: usize) -> Result<f64, Bad> {
        let cell = self.record.get(c).unwrap_or("");
        cell.parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| {
                (
                    self.line,
                    self.header[c].clone(),
                    cell.into(),
                    "not a finite number".into(),
                )
            })
    }

    fn positive(&self, c: usize) -> Result<f64, Bad> {
        let v = self.number(c)?;
        if v > 0.0 {
            Ok(v)
        } else {
            Err((
                self.line,
                self.header[c].clone(),
                v.to_string(),
                "must be positive".into(),
            ))
        }
    }

    /// `q` as a unit quaternion (column `name` blamed): kept as written within
    /// rounding of unit norm (a `grains.csv` then reads back exactly), normalised
    /// within [`QUATERNION_NORM_TOL`].
    fn unit(&self, q: [f64; 4], name: &str) -> Result<[f64; 4], Bad> {
        let norm = q.iter().map(|v| v * v).sum::<f64>().sqrt();
        if !((norm - 1.0).abs() <= QUATERNION_NORM_TOL) {
            return Err((
                self.line,
                name.into(),
                format!("[{}, {}, {}, {}]", q[0], q[1], q[2], q[3]),
                format!(
                    "must be a unit quaternion (norm {norm}, tolerance {QUATERNION_NORM_TOL:e})"
                ),
            ));
        }
        Ok(if (norm - 1.0).abs() <= UNIT_ROUNDING {
            q
        } else {
            q.map(|v| v / norm)
        })
    }
}

/// The positions of the columns `names` in `header`: all of them, or `None` if none
/// is there; an error if only some are.
fn columns<const N: usize>(
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_cells_name_line_and_column() {
        let text = "id,d\n0,3.0\n1,-2.0\n";
        let err = read_table(text, None, Dimension::Three).unwrap_err();
        assert_eq!((err.0, err.1.as_str()), (3, "d"));
        let text = "a1,a2,a3,qw,qx,qy,qz\n3,2,1,1,0,0,0\n3,2,x,1,0,0,0\n";
        let err = read_table(text, None, Dimension::Three).unwrap_err();
        assert_eq!((err.0, err.1.as_str(), err.2.as_str()), (3, "a3", "x"));
        let text = "a1,a2,a3,qw,qx,qy,qz\n3,2,1,0.5,0,0,0\n";
        assert_eq!(
            read_table(text, None, Dimension::Three).unwrap_err().1,
            "qw"
        );
        assert_eq!(
            read_table("x,y\n1,2\n", None, Dimension::Three)
                .unwrap_err()
                .0,
            1
        );
    }

    #[test]
    fn rows_are_selected_by_phase_and_keep_their_values() {
        let text = "id,phase,a1,a2,a3\n0,0,3,2,1\n1,1,4,4,4\n2,0,2,2,2\n";
        let g = read_table(text, Some("0"), Dimension::Three).unwrap();
        assert_eq!(g.len(), 2);
        assert_eq!(g[0].semi_axes, Some([3.0, 2.0, 1.0]));
        // 2 (a1 a2 a3)^{1/3} = 2·6^{1/3}, to an ulp or two of the cube root.
        assert!((g[0].diameter - 2.0 * 6f64.cbrt()).abs() < 1e-14);
    }
}
