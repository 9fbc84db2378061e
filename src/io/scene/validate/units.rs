//! `[units]`, and the warnings about values its units make implausible.

use crate::io::scene::error::{SceneError, Source};
use crate::io::scene::raw::{RawElastic, RawScene};
use crate::scene::{
    Domain, LengthUnit, StressUnit, Units, PLAUSIBLE_BOX_M, PLAUSIBLE_CRYSTAL_STIFFNESS_PA,
    PLAUSIBLE_MODULUS_PA,
};
use std::ops::Range;
use toml::Spanned;

/// `[units]`: `length` and `stress`, each one of its unit's accepted names, defaults
/// [`Units::default`].
pub(super) fn units(src: &Source, raw: &RawScene) -> Result<Units, SceneError> {
    let mut units = Units::default();
    let Some(table) = &raw.units else {
        return Ok(units);
    };
    let table = table.get_ref();
    if let Some(name) = &table.length {
        units.length = find(&LengthUnit::NAMES, name.get_ref())
            .ok_or_else(|| src.invalid_at("units.length", name, expected(&LengthUnit::NAMES)))?;
    }
    if let Some(name) = &table.stress {
        units.stress = find(&StressUnit::NAMES, name.get_ref())
            .ok_or_else(|| src.invalid_at("units.stress", name, expected(&StressUnit::NAMES)))?;
    }
    Ok(units)
}

fn find<T: Copy>(names: &[(&str, T)], name: &str) -> Option<T> {
    names.iter().find(|(n, _)| *n == name).map(|&(_, u)| u)
}

fn expected<T>(names: &[(&str, T)]) -> String {
    let list: Vec<String> = names.iter().map(|(n, _)| format!("\"{n}\"")).collect();
    format!("must be one of {} (case matters)", list.join(", "))
}

/// Warnings about values the scene's units make implausible: a box side outside
/// [`PLAUSIBLE_BOX_M`] once in metres, a Young's modulus (`[phase.elastic]`,
/// `[matrix.elastic]`) outside [`PLAUSIBLE_MODULUS_PA`] once in pascals, and a
/// diagonal stiffness constant (`C_11` … `C_66`) of a `[phase.damask]` or
/// `[matrix.damask]` entry's `mechanical.elastic` outside
/// [`PLAUSIBLE_CRYSTAL_STIFFNESS_PA`] as written (DAMASK reads pascals whatever
/// `[units]` says). Each names the file, line, key and value.
pub(super) fn warnings(src: &Source, raw: &RawScene, units: Units, domain: &Domain) -> Vec<String> {
    let mut out = Vec::new();
    let (lo, hi) = PLAUSIBLE_BOX_M;
    let length = units.length.symbol();
    let size = &raw.domain.get_ref().size;
    // The rectangle's two sides in 2D.
    let sides = domain.sides();
    let metres: Vec<f64> = sides.iter().map(|&side| units.length.to_si(side)).collect();
    if metres.iter().any(|m| !(lo..=hi).contains(m)) {
        out.push(warning(
            src,
            "box.size",
            size.span(),
            format!(
                "{sides:?} {length}{}, outside [{lo:e}, {hi:e}] m: is units.length \
                 (\"{length}\") what the lengths are in?",
                if units.length == LengthUnit::Metre {
                    String::new()
                } else {
                    let m: Vec<String> = metres.iter().map(|m| format!("{m:e}")).collect();
                    format!(" = [{}] m", m.join(", "))
                }
            ),
        ));
    }
    let stress = units.stress;
    let elastic = |key: String, e: &RawElastic, out: &mut Vec<String>| {
        let given = *e.young.get_ref();
        let pascals = stress.to_si(given);
        if let Some(why) = implausible_modulus(pascals) {
            out.push(warning(
                src,
                &format!("{key}.E"),
                e.young.span(),
                format!(
                    "{given} {}{}, {why}: is units.stress (\"{}\") what it is in?",
                    stress.symbol(),
                    if stress == StressUnit::Pascal {
                        String::new()
                    } else {
                        format!(" = {pascals:e} Pa")
                    },
                    stress.symbol()
                ),
            ));
        }
    };
    let damask = |key: String, table: &Spanned<toml::Table>, out: &mut Vec<String>| {
        let constants = table
            .get_ref()
            .get("mechanical")
            .and_then(|m| m.get("elastic"))
            .and_then(toml::Value::as_table);
        for (name, value) in constants.into_iter().flatten() {
            let pascals = match value {
                toml::Value::Float(v) => *v,
                toml::Value::Integer(v) => *v as f64,
                _ => continue,
            };
            // Off-diagonal constants may be small or negative in a real crystal.
            if !DIAGONAL.contains(&name.as_str()) {
                continue;
            }
            let (lo, hi) = PLAUSIBLE_CRYSTAL_STIFFNESS_PA;
            if !(lo..=hi).contains(&pascals) {
                let why = format!(
                    "outside [{lo:e}, {hi:e}] Pa, the diagonal stiffness constants of \
                     crystals from caesium to diamond"
                );
                out.push(warning(
                    src,
                    &format!("{key}.mechanical.elastic.{name}"),
                    table.span(),
                    format!(
                        "{pascals:e} Pa, {why}: DAMASK reads it in pascals, as written \
                         (units.stress does not apply to [damask] tables)"
                    ),
                ));
            }
        }
    };
    for (i, p) in raw.phase.iter().enumerate() {
        let p = p.get_ref();
        if let Some(e) = &p.elastic {
            elastic(format!("phase[{i}].elastic"), e.get_ref(), &mut out);
        }
        if let Some(d) = &p.damask {
            damask(format!("phase[{i}].damask"), d, &mut out);
        }
    }
    if let Some(m) = &raw.matrix {
        let m = m.get_ref();
        if let Some(e) = &m.elastic {
            elastic("matrix.elastic".into(), e.get_ref(), &mut out);
        }
        if let Some(d) = &m.damask {
            damask("matrix.damask".into(), d, &mut out);
        }
    }
    out
}

/// The diagonal stiffness constants of a DAMASK `Hooke` phase.
const DIAGONAL: [&str; 6] = ["C_11", "C_22", "C_33", "C_44", "C_55", "C_66"];

/// Why a modulus of `pascals` is implausible, if it is.
fn implausible_modulus(pascals: f64) -> Option<String> {
    let (lo, hi) = PLAUSIBLE_MODULUS_PA;
    (!(lo..=hi).contains(&pascals)).then(|| {
        format!("outside [{lo:e}, {hi:e}] Pa, the moduli of solids from soft gels to diamond")
    })
}

/// `file:line:column: key = value: reason`, as errors read.
fn warning(src: &Source, key: &str, span: Range<usize>, reason: String) -> String {
    let (line, column) = src.line_column(span.start);
    format!(
        "{}:{line}:{column}: {key} = {}: {reason}",
        src.file,
        src.snippet(&span)
    )
}

#[cfg(test)]
mod tests {
    use crate::scene::Scene;

    const BOX: &str = "grains = 2\n[box]\nsize = [40, 40, 40]\n[[phase]]\n\
                       size = { distribution = \"constant\", value = 5 }\n";

    #[test]
    fn units_default_to_micrometres_and_megapascals() {
        let scene = Scene::from_str(BOX, "s.toml").unwrap();
        assert_eq!(scene.units, crate::scene::Units::default());
        assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    }

    #[test]
    fn every_spelling_of_a_unit_is_read() {
        for (name, unit) in crate::scene::LengthUnit::NAMES {
            let text = format!("{BOX}[units]\nlength = \"{name}\"\n");
            let scene = Scene::from_str(&text, "s.toml").unwrap();
            assert_eq!(scene.units.length, unit);
        }
        let text = format!("{BOX}[units]\nstress = \"GPa\"\n");
        let scene = Scene::from_str(&text, "s.toml").unwrap();
        assert_eq!(scene.units.stress, crate::scene::StressUnit::Gigapascal);
    }
}
