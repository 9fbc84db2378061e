//! `[phase.texture]` (crystal orientations, with their orientation files) and
//! `[phase.elastic]`.

use crate::contact::QUATERNION_NORM_TOL;
use crate::io::scene::error::{DataFileError, SceneError, Source};
use crate::io::scene::raw::{RawElastic, RawTexture, RawTextureKind};
use crate::scene::{euler_to_quaternion, Elastic, PhaseTexture, Texture};
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// `[phase.texture]` at key path `key`. `spherical`: the phase's grains are spheres
/// (constant aspect ratio 1), which have no shape frame to be relative to.
pub(super) fn texture(
    src: &Source,
    key: &str,
    raw: &Spanned<RawTexture>,
    spherical: bool,
) -> Result<PhaseTexture, SceneError> {
    let t = raw.get_ref();
    let kind = *t.kind.get_ref();
    let given: [(&str, Option<Range<usize>>); 6] = [
        ("quaternion", t.quaternion.as_ref().map(Spanned::span)),
        ("euler", t.euler.as_ref().map(Spanned::span)),
        (
            "crystal_direction",
            t.crystal_direction.as_ref().map(Spanned::span),
        ),
        (
            "sample_direction",
            t.sample_direction.as_ref().map(Spanned::span),
        ),
        ("kappa", t.kappa.as_ref().map(Spanned::span)),
        ("file", t.file.as_ref().map(Spanned::span)),
    ];
    let (name, takes): (_, &[&str]) = match kind {
        RawTextureKind::Random => ("random", &[]),
        RawTextureKind::Fixed => ("fixed", &["quaternion", "euler"]),
        RawTextureKind::Fibre => ("fibre", &["crystal_direction", "sample_direction", "kappa"]),
        RawTextureKind::File => ("file", &["file"]),
    };
    super::grain::foreign_keys(
        src,
        key,
        name,
        &given,
        takes,
        "no other key but relative_to_shape",
    )?;
    let relative_to_shape = match &t.relative_to_shape {
        Some(r) if *r.get_ref() && kind == RawTextureKind::Random => {
            return Err(src.invalid_at(
                format!("{key}.relative_to_shape"),
                r,
                "does not apply to kind = \"random\": a random orientation composed with \
                 the shape's is random",
            ))
        }
        Some(r) if *r.get_ref() && spherical => {
            return Err(src.invalid_at(
                format!("{key}.relative_to_shape"),
                r,
                "does not apply to a phase of spheres (aspect_ratio constant 1): they have \
                 no shape axes",
            ))
        }
        r => r.as_ref().is_some_and(|r| *r.get_ref()),
    };
    let texture = match kind {
        RawTextureKind::Random => Texture::Random,
        RawTextureKind::Fixed => fixed(src, key, raw)?,
        RawTextureKind::Fibre => fibre(src, key, raw)?,
        RawTextureKind::File => {
            let file = t.file.as_ref().ok_or_else(|| {
                src.missing(
                    format!("{key}.file"),
                    raw.span(),
                    "kind = \"file\" needs file = \"orientations.csv\"",
                )
            })?;
            let dir = Path::new(src.file).parent().unwrap_or(Path::new(""));
            read_orientations(src, &format!("{key}.file"), dir.join(file.get_ref()))?
        }
    };
    Ok(PhaseTexture {
        texture,
        relative_to_shape,
    })
}

fn fixed(src: &Source, key: &str, raw: &Spanned<RawTexture>) -> Result<Texture, SceneError> {
    let t = raw.get_ref();
    let quaternion = match (&t.quaternion, &t.euler) {
        (Some(_), Some(e)) => {
            return Err(src.invalid_at(
                format!("{key}.euler"),
                e,
                "give either quaternion or euler, not both",
            ))
        }
        (None, None) => {
            return Err(src.missing(
                format!("{key}.quaternion"),
                raw.span(),
                "kind = \"fixed\" needs quaternion = [q0, q1, q2, q3] or euler = [φ1, Φ, φ2] \
                 (Bunge, degrees)",
            ))
        }
        (Some(q), None) => unit_quaternion(*q.get_ref())
            .map_err(|reason| src.invalid_at(format!("{key}.quaternion"), q, reason))?,
        (None, Some(e)) => euler_degrees(*e.get_ref())
            .map_err(|reason| src.invalid_at(format!("{key}.euler"), e, reason))?,
    };
    Ok(Texture::Fixed { quaternion })
}

fn fibre(src: &Source, key: &str, raw: &Spanned<RawTexture>) -> Result<Texture, SceneError> {
    let t = raw.get_ref();
    let need = |name: &str| {
        src.missing(
            format!("{key}.{name}"),
            raw.span(),
            "kind = \"fibre\" needs crystal_direction = [u, v, w], sample_direction and kappa",
        )
    };
    let c = t
        .crystal_direction
        .as_ref()
        .ok_or_else(|| need("crystal_direction"))?;
    let crystal = unit(*c.get_ref()).ok_or_else(|| {
        src.invalid_at(
            format!("{key}.crystal_direction"),
            c,
            "must be a non-zero, finite direction [u, v, w]",
        )
    })?;
    let s = t
        .sample_direction
        .as_ref()
        .ok_or_else(|| need("sample_direction"))?;
    let sample = super::axis::direction(src, &format!("{key}.sample_direction"), s)?;
    let k = t.kappa.as_ref().ok_or_else(|| need("kappa"))?;
    let kappa = *k.get_ref();
    if !(kappa.is_finite() && kappa >= 0.0) {
        return Err(src.invalid_at(
            format!("{key}.kappa"),
            k,
            "must be finite and at least 0 (0: the direction is uniform on the sphere)",
        ));
    }
    Ok(Texture::Fibre {
        crystal,
        sample,
        kappa,
    })
}

/// `[phase.elastic]` or `[matrix.elastic]` at key path `key`.
pub(super) fn elastic(src: &Source, key: &str, raw: &RawElastic) -> Result<Elastic, SceneError> {
    let e = Elastic {
        young: *raw.young.get_ref(),
        poisson: *raw.nu.get_ref(),
    };
    match e.check() {
        None => Ok(e),
        Some(("E", reason)) => Err(src.invalid_at(format!("{key}.E"), &raw.young, reason)),
        Some((_, reason)) => Err(src.invalid_at(format!("{key}.nu"), &raw.nu, reason)),
    }
}

fn unit(v: [f64; 3]) -> Option<[f64; 3]> {
    let n = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    (n > 0.0 && n.is_finite()).then(|| v.map(|x| x / n))
}

/// A quaternion within [`QUATERNION_NORM_TOL`] of unit norm, normalised, `q0 ≥ 0`.
fn unit_quaternion(q: [f64; 4]) -> Result<[f64; 4], String> {
    let norm = q.iter().map(|v| v * v).sum::<f64>().sqrt();
    if !((norm - 1.0).abs() <= QUATERNION_NORM_TOL) {
        return Err(format!(
            "must be a unit quaternion [q0, q1, q2, q3] (norm {norm}, tolerance \
             {QUATERNION_NORM_TOL:e})"
        ));
    }
    let sign = if q[0] < 0.0 { -1.0 } else { 1.0 };
    Ok(q.map(|v| sign * v / norm))
}

/// Bunge Euler angles in degrees, `φ1, φ2 ∈ [0, 360]`, `Φ ∈ [0, 180]` (DAMASK's ranges).
fn euler_degrees(e: [f64; 3]) -> Result<[f64; 4], String> {
    let ok = |a: f64, max: f64| (0.0..=max).contains(&a);
    if !(ok(e[0], 360.0) && ok(e[1], 180.0) && ok(e[2], 360.0)) {
        return Err(
            "Bunge Euler angles [φ1, Φ, φ2] in degrees must lie in [0, 360] × [0, 180] × \
             [0, 360]"
                .to_owned(),
        );
    }
    Ok(euler_to_quaternion(e.map(f64::to_radians)))
}

/// The columns an orientation file may have (lower case); others are ignored.
const QUATERNION_COLUMNS: [&str; 4] = ["q0", "q1", "q2", "q3"];
const EULER_COLUMNS: [&str; 3] = ["phi1", "phi", "phi2"];

/// Reads an orientation file: CSV with a header, `q0,q1,q2,q3` or `phi1,Phi,phi2`
/// (Bunge, degrees), optionally `weight`; other columns ignored, `#` lines comments.
fn read_orientations(src: &Source, key: &str, path: PathBuf) -> Result<Texture, SceneError> {
    let shown = path.display().to_string();
    let error = |line: usize, column: &str, value: &str, reason: String| {
        SceneError::DataFile(Box::new(DataFileError {
            file: src.file.to_owned(),
            key: key.to_owned(),
            path: shown.clone(),
            line,
            column: column.to_owned(),
            value: value.to_owned(),
            reason,
        }))
    };
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .from_path(&path)
        .map_err(|e| error(0, "(file)", &shown, format!("cannot read it: {e}")))?;
    let header: Vec<String> = reader
        .headers()
        .map_err(|e| error(1, "(header)", "", format!("cannot read the header: {e}")))?
        .iter()
        .map(str::to_lowercase)
        .collect();
    let find = |name: &str| header.iter().position(|h| h == name);
    let quaternion: Option<Vec<usize>> = QUATERNION_COLUMNS.iter().map(|c| find(c)).collect();
    let euler: Option<Vec<usize>> = EULER_COLUMNS.iter().map(|c| find(c)).collect();
    let (columns, names, is_euler): (Vec<usize>, &[&str], bool) = match (quaternion, euler) {
        (Some(q), None) => (q, &QUATERNION_COLUMNS, false),
        (None, Some(e)) => (e, &["phi1", "Phi", "phi2"], true),
        _ => {
            return Err(error(
                1,
                "(header)",
                &header.join(","),
                "needs the columns q0,q1,q2,q3 (a quaternion) or phi1,Phi,phi2 (Bunge Euler \
                 angles in degrees), not both, and optionally weight"
                    .to_owned(),
            ))
        }
    };
    let weight = find("weight");
    let (mut orientations, mut weights) = (Vec::new(), Vec::new());
    for record in reader.records() {
        let record = record.map_err(|e| {
            error(
                e.position().map_or(0, |p| p.line() as usize),
                "(row)",
                "",
                e.to_string(),
            )
        })?;
        let line = record.position().map_or(0, |p| p.line() as usize);
        let number = |i: usize, name: &str| {
            let text = record.get(i).unwrap_or("");
            text.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| error(line, name, text, "is not a finite number".to_owned()))
        };
        let values = columns
            .iter()
            .zip(names)
            .map(|(&i, name)| number(i, name))
            .collect::<Result<Vec<f64>, _>>()?;
        let shown = || {
            format!(
                "[{}]",
                values
                    .iter()
                    .map(f64::to_string)
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        };
        let q = if is_euler {
            euler_degrees([values[0], values[1], values[2]])
                .map_err(|reason| error(line, "phi1,Phi,phi2", &shown(), reason))?
        } else {
            unit_quaternion([values[0], values[1], values[2], values[3]])
                .map_err(|reason| error(line, "q0,q1,q2,q3", &shown(), reason))?
        };
        let w = match weight {
            None => 1.0,
            Some(i) => {
                let w = number(i, "weight")?;
                if w < 0.0 {
                    let text = record.get(i).unwrap_or("");
                    return Err(error(
                        line,
                        "weight",
                        text,
                        "must not be negative".to_owned(),
                    ));
                }
                w
            }
        };
        orientations.push(q);
        weights.push(w);
    }
    if orientations.is_empty() {
        return Err(error(
            0,
            "(file)",
            &shown,
            "has no orientation rows".to_owned(),
        ));
    }
    if !(weights.iter().sum::<f64>() > 0.0) {
        return Err(error(
            0,
            "weight",
            "0",
            "the weights sum to zero".to_owned(),
        ));
    }
    Ok(Texture::File {
        path,
        orientations,
        weights,
    })
}
