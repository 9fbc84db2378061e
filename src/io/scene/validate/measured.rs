//! `[phase.measured]`: a phase's grains from a CSV table.
//!
//! The table has a header row. Columns, in the box's length unit: `d` (equivalent
//! diameter) or `a1`, `a2`, `a3` (semi-axes); optionally `qw`, `qx`, `qy`, `qz` (unit
//! quaternion, semi-axis k along column k of its rotation) and `phase` (an index or a
//! name, selected by the `phase` key); optionally the crystal orientation, `o0..o3`
//! (unit quaternion, scalar first) or else `phi1`, `Phi`, `phi2` (Bunge Euler angles,
//! degrees). Other columns (`id`, `x`, `y`, `z`, ...) are ignored, so a `grains.csv`
//! written by `pack` reads back as it is, crystal orientations included.

use crate::contact::QUATERNION_NORM_TOL;
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
    let grains =
        read_table(&text, select.as_deref()).map_err(|(line, column, value, reason)| {
            SceneError::DataFile(Box::new(DataFileError {
                file: src.file.to_owned(),
                key: format!("{key}.file"),
                path: table_file.clone(),
                line,
                column,
                value,
                reason,
            }))
        })?;
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

/// Reads the table's rows (of phase `select`, if given).
fn read_table(text: &str, select: Option<&str>) -> Result<Vec<MeasuredGrain>, Bad> {
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
    let d = find("d");
    let axes: Vec<Option<usize>> = ["a1", "a2", "a3"].iter().map(|n| find(n)).collect();
    let quat: Vec<Option<usize>> = ["qw", "qx", "qy", "qz"].iter().map(|n| find(n)).collect();
    let axes = match (
        d,
        axes.iter().all(Option::is_some),
        axes.iter().any(Option::is_some),
    ) {
        (Some(_), _, true) => {
            return Err(bad_header("give d or a1, a2, a3, not both"));
        }
        (None, true, _) => Some([axes[0].unwrap(), axes[1].unwrap(), axes[2].unwrap()]),
        (None, false, true) => return Err(bad_header("a1, a2 and a3 go together")),
        (None, false, false) => {
            return Err(bad_header(
                "needs a column d (equivalent diameter) or a1, a2, a3 (semi-axes)",
            ))
        }
        (Some(_), _, false) => None,
    };
    let quat = match (
        quat.iter().all(Option::is_some),
        quat.iter().any(Option::is_some),
    ) {
        (true, _) => Some([
            quat[0].unwrap(),
            quat[1].unwrap(),
            quat[2].unwrap(),
            quat[3].unwrap(),
        ]),
        (false, true) => return Err(bad_header("qw, qx, qy and qz go together")),
        (false, false) => None,
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
        let number = |c: usize| -> Result<f64, Bad> {
            let cell = record.get(c).unwrap_or("");
            cell.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    (
                        line,
                        header[c].clone(),
                        cell.into(),
                        "not a finite number".into(),
                    )
                })
        };
        let positive = |c: usize| -> Result<f64, Bad> {
            let v = number(c)?;
            if v > 0.0 {
                Ok(v)
            } else {
                Err((
                    line,
                    header[c].clone(),
                    v.to_string(),
                    "must be positive".into(),
                ))
            }
        };
        let q = match quat {
            None => None,
            Some(cols) => {
                let q = [
                    number(cols[0])?,
                    number(cols[1])?,
                    number(cols[2])?,
                    number(cols[3])?,
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
                // Within rounding of unit norm, kept as written: the round trip of a
                // grains.csv is then exact.
                if (norm - 1.0).abs() <= UNIT_ROUNDING {
                    Some(q)
                } else {
                    Some(q.map(|v| v / norm))
                }
            }
        };
        let unit = |q: [f64; 4], name: &str| -> Result<[f64; 4], Bad> {
            let norm = q.iter().map(|v| v * v).sum::<f64>().sqrt();
            if !((norm - 1.0).abs() <= QUATERNION_NORM_TOL) {
                return Err((
                    line,
                    name.into(),
                    format!("[{}, {}, {}, {}]", q[0], q[1], q[2], q[3]),
                    format!("must be a unit quaternion (norm {norm}, tolerance {QUATERNION_NORM_TOL:e})"),
                ));
            }
            // Within rounding of unit norm, kept as written (an exact round trip).
            Ok(if (norm - 1.0).abs() <= UNIT_ROUNDING {
                q
            } else {
                q.map(|v| v / norm)
            })
        };
        let crystal = match (crystal_quat, euler) {
            (Some(c), _) => Some(unit(
                [number(c[0])?, number(c[1])?, number(c[2])?, number(c[3])?],
                "o0",
            )?),
            (None, Some(c)) => Some(euler_to_quaternion(
                [number(c[0])?, number(c[1])?, number(c[2])?].map(f64::to_radians),
            )),
            (None, None) => None,
        };
        let mut grain = match axes {
            Some(cols) => MeasuredGrain::with_semi_axes(
                [positive(cols[0])?, positive(cols[1])?, positive(cols[2])?],
                q,
            ),
            None => MeasuredGrain {
                diameter: positive(d.expect("d or semi-axes"))?,
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
        let err = read_table(text, None).unwrap_err();
        assert_eq!((err.0, err.1.as_str()), (3, "d"));
        let text = "a1,a2,a3,qw,qx,qy,qz\n3,2,1,1,0,0,0\n3,2,x,1,0,0,0\n";
        let err = read_table(text, None).unwrap_err();
        assert_eq!((err.0, err.1.as_str(), err.2.as_str()), (3, "a3", "x"));
        let text = "a1,a2,a3,qw,qx,qy,qz\n3,2,1,0.5,0,0,0\n";
        assert_eq!(read_table(text, None).unwrap_err().1, "qw");
        assert_eq!(read_table("x,y\n1,2\n", None).unwrap_err().0, 1);
    }

    #[test]
    fn rows_are_selected_by_phase_and_keep_their_values() {
        let text = "id,phase,a1,a2,a3\n0,0,3,2,1\n1,1,4,4,4\n2,0,2,2,2\n";
        let g = read_table(text, Some("0")).unwrap();
        assert_eq!(g.len(), 2);
        assert_eq!(g[0].semi_axes, Some([3.0, 2.0, 1.0]));
        // 2 (a1 a2 a3)^{1/3} = 2·6^{1/3}, to an ulp or two of the cube root.
        assert!((g[0].diameter - 2.0 * 6f64.cbrt()).abs() < 1e-14);
    }
}
