//! `distribution = "table"`: a tabulated CDF by number or by volume.

use crate::contact::Dimension;
use crate::io::scene::error::{SceneError, Source};
use crate::io::scene::raw::RawDistribution;
use crate::laws::{Distribution, TableBasis, TableError, TableInterpolation, TableLaw};
use std::ops::Range;
use toml::Spanned;

/// The table-only keys given in a distribution, with their spans.
pub(super) fn table_keys(r: &RawDistribution) -> [Option<(&'static str, Range<usize>)>; 4] {
    [
        r.x.as_ref().map(|v| ("x", v.span())),
        r.cdf.as_ref().map(|v| ("cdf", v.span())),
        r.by.as_ref().map(|v| ("by", v.span())),
        r.interpolation
            .as_ref()
            .map(|v| ("interpolation", v.span())),
    ]
}

/// `distribution = "table"`: `x`, `cdf`, `by` (`"number"`, default, or `"volume"`;
/// `"area"` instead of `"volume"` in a 2D scene), `interpolation` (`"linear"`, default,
/// or `"log"`).
pub(super) fn table(
    src: &Source,
    key: &str,
    raw: &Spanned<RawDistribution>,
    dimension: Dimension,
) -> Result<Distribution, SceneError> {
    let r = raw.get_ref();
    if let Some((name, Some(v))) = r.params().into_iter().find(|(_, v)| v.is_some()) {
        return Err(src.invalid_at(
            format!("{key}.{name}"),
            v,
            "does not apply to distribution = \"table\", which takes x, cdf, by, interpolation \
             (its cutoffs are the table's ends)",
        ));
    }
    fn need<'a>(
        src: &Source,
        key: &str,
        raw: &Spanned<RawDistribution>,
        name: &str,
        v: &'a Option<Spanned<Vec<f64>>>,
    ) -> Result<&'a Spanned<Vec<f64>>, SceneError> {
        v.as_ref().ok_or_else(|| {
            src.missing(
                format!("{key}.{name}"),
                raw.span(),
                "distribution = \"table\" needs x = [...] and cdf = [...]",
            )
        })
    }
    let x = need(src, key, raw, "x", &r.x)?;
    let cdf = need(src, key, raw, "cdf", &r.cdf)?;
    let basis =
        match r.by.as_ref() {
            None => TableBasis::Number,
            Some(b) => {
                let measure = match dimension {
                    Dimension::Three => "volume",
                    Dimension::Two => "area",
                };
                match b.get_ref().as_str() {
                    "number" => TableBasis::Number,
                    "volume" | "area" if b.get_ref() != measure => {
                        return Err(src.invalid_at(
                            format!("{key}.by"),
                            b,
                            match dimension {
                                Dimension::Two => {
                                    "has no meaning in a 2D scene (box.size = [Lx, \
                                 Ly]): its grains have areas; give by = \"area\" (area fraction \
                                 passing x)"
                                }
                                Dimension::Three => {
                                    "by = \"area\" applies to 2D scenes (box.size \
                                 = [Lx, Ly]); give by = \"volume\" (volume fraction passing x)"
                                }
                            },
                        ))
                    }
                    "area" if key.ends_with(".size") => TableBasis::Area,
                    // A volume fraction weighs grains by d³: it means something for sizes only.
                    "volume" if key.ends_with(".size") => TableBasis::Volume,
                    "area" => return Err(src.invalid_at(
                        format!("{key}.by"),
                        b,
                        "by = \"area\" applies to size only (an area fraction weighs grains by \
                         their diameter squared); a shape ratio's table is by number",
                    )),
                    _ if dimension == Dimension::Two => {
                        return Err(src.invalid_at(
                            format!("{key}.by"),
                            b,
                            "must be \"number\" (fraction of grains below x) or \"area\" (area \
                         fraction passing x)",
                        ))
                    }
                    "volume" => return Err(src.invalid_at(
                        format!("{key}.by"),
                        b,
                        "by = \"volume\" applies to size only (a volume fraction weighs grains by \
                     their diameter cubed); a shape ratio's table is by number",
                    )),
                    _ => return Err(src.invalid_at(
                        format!("{key}.by"),
                        b,
                        "must be \"number\" (fraction of grains below x) or \"volume\" (volume \
                     fraction passing x, a sieve curve)",
                    )),
                }
            }
        };
    let interpolation = match r.interpolation.as_ref() {
        None => TableInterpolation::Linear,
        Some(i) => match i.get_ref().as_str() {
            "linear" => TableInterpolation::Linear,
            "log" => TableInterpolation::Log,
            _ => {
                return Err(src.invalid_at(
                    format!("{key}.interpolation"),
                    i,
                    "must be \"linear\" (in x) or \"log\" (in ln x)",
                ))
            }
        },
    };
    let law = TableLaw::new(x.get_ref(), cdf.get_ref(), basis, interpolation).map_err(
        |TableError {
             key: which,
             index,
             reason,
         }| {
            let at = if which == "x" { x.span() } else { cdf.span() };
            let path = match index {
                Some(i) => format!("{key}.{which}[{i}]"),
                None => format!("{key}.{which}"),
            };
            src.invalid(path, at, reason)
        },
    )?;
    Ok(Distribution::Table(law))
}
