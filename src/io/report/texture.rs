//! The achieved texture of each phase against its target law, for `summary.json`:
//! a digest of what [`measure_textures`](crate::io::texture::measure_textures)
//! measured.

use crate::io::texture::{ks_critical_5pct, AngleLaw, TextureMeasure};
use crate::scene::{Scene, Texture};
use serde::Serialize;

/// One phase's crystal orientations as written, against its texture.
#[derive(Debug, Clone, Serialize)]
pub struct TextureSummary {
    /// The phase's name.
    pub phase: String,
    /// `"random"`, `"fixed"`, `"fibre"` or `"file"`; `"measured"` for a measured table
    /// with crystal orientations (measured against the table's rows, as a file).
    pub kind: &'static str,
    /// Whether the texture is in the grains' own frames (then measured there).
    pub relative_to_shape: bool,
    /// Grains of the phase.
    pub grains: usize,
    /// The angle measured: `"rotation angle"` (random: its SO(3) law has CDF
    /// `(ω − sin ω)/π`; file: against the weighted rotation angles of the file's
    /// rows), `"angle to the fibre"` (fibre: the von Mises–Fisher law's),
    /// `"angle from the fixed orientation"` (fixed: 0).
    pub measure: Option<&'static str>,
    /// Mean of the measured angle over the grains, degrees.
    pub mean_deg: Option<f64>,
    /// Its mean under the target law, degrees.
    pub target_mean_deg: Option<f64>,
    /// Largest measured angle, degrees.
    pub max_deg: Option<f64>,
    /// Kolmogorov–Smirnov distance of the measured angles from the target law (random,
    /// fibre, file).
    pub ks_distance: Option<f64>,
    /// The KS distance a sample of this size exceeds with probability 5 %: `1.358/√n`
    /// (conservative for the file's law, which has atoms).
    pub ks_critical_5pct: Option<f64>,
    /// Rows of the orientation file (file) or of the measured table (measured).
    pub file_rows: Option<usize>,
}

/// The texture summary of every phase, from its measure (`measures[p]` for phase `p`).
pub fn texture_summaries(scene: &Scene, measures: &[TextureMeasure]) -> Vec<TextureSummary> {
    scene
        .phases
        .iter()
        .zip(measures)
        .map(|(phase, m)| {
            let t = &phase.texture;
            let n = m.angles.len();
            let table = phase.measured.as_ref().filter(|m| m.has_crystals());
            let deg = |x: f64| x.to_degrees();
            TextureSummary {
                phase: phase.name.clone(),
                kind: table.map_or(t.texture.kind(), |_| "measured"),
                relative_to_shape: t.relative_to_shape,
                grains: n,
                measure: Some(m.measure),
                mean_deg: (n > 0).then(|| deg(m.angles.iter().sum::<f64>() / n as f64)),
                target_mean_deg: Some(deg(m.law.moments().mean)),
                max_deg: m.angles.iter().copied().reduce(f64::max).map(deg),
                ks_distance: m.ks_distance,
                ks_critical_5pct: m.ks_distance.map(|_| ks_critical_5pct(n)),
                file_rows: match (table, &t.texture, &m.law) {
                    (Some(table), ..) => Some(table.grains.len()),
                    (None, Texture::File { orientations, .. }, AngleLaw::Atoms { .. }) => {
                        Some(orientations.len())
                    }
                    _ => None,
                },
            }
        })
        .collect()
}
