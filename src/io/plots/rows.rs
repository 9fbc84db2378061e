//! The statistics figure's rows, one per phase: its sizes, shapes and orientations
//! (module `angles`) against the laws they were drawn from.

use super::angles::{angle_panel, plane_angle_panel};
use super::panel::{Panel, Row};
use super::{PlotError, VoxelSample};
use crate::contact::Dimension;
use crate::packing::PackedGrain;
use crate::scene::{aspect_ratio, Orientation, Phase};

/// The rows of the figure, one per phase, after checking that every grain and voxel
/// sample names a phase of the scene.
pub(super) fn rows(
    phases: &[Phase],
    packed: &[PackedGrain],
    voxel: Option<&[VoxelSample]>,
    dimension: Dimension,
) -> Result<Vec<Row>, PlotError> {
    if let Some(g) = packed.iter().find(|g| g.phase >= phases.len()) {
        return Err(PlotError::GrainPhase {
            id: g.id,
            phase: g.phase,
            phases: phases.len(),
        });
    }
    if let Some((index, s)) = voxel
        .unwrap_or_default()
        .iter()
        .enumerate()
        .find(|(_, s)| s.phase >= phases.len())
    {
        return Err(PlotError::VoxelPhase {
            index,
            phase: s.phase,
            phases: phases.len(),
        });
    }
    let measure = |g: &PackedGrain| dimension.measure(g.semi_axes);
    let (measured, diameter_title) = match dimension {
        Dimension::Two => ("area", "equivalent-circle diameter"),
        Dimension::Three => ("volume", "equivalent diameter"),
    };
    let total_volume: f64 = packed.iter().map(measure).sum();
    Ok(phases
        .iter()
        .enumerate()
        .map(|(index, phase)| {
            let grains: Vec<&PackedGrain> = packed.iter().filter(|g| g.phase == index).collect();
            let samples: Option<Vec<&VoxelSample>> =
                voxel.map(|v| v.iter().filter(|s| s.phase == index).collect());
            let volume: f64 = grains.iter().map(|g| measure(g)).sum();
            let mut title = format!(
                "phase {} \u{201c}{}\u{201d}: {} packed grains, {:.1} % of the grain {measured} \
                 (target {:.1} %)",
                index + 1,
                phase.name,
                grains.len(),
                100.0
                    * if total_volume > 0.0 {
                        volume / total_volume
                    } else {
                        0.0
                    },
                100.0 * phase.share,
            );
            if let Some(s) = &samples {
                title += &format!(", {} voxel grains", s.len());
            }
            let voxel_values = |f: fn(&VoxelSample) -> Option<f64>| {
                samples
                    .as_ref()
                    .map(|s| s.iter().filter_map(|s| f(s)).collect::<Vec<f64>>())
            };
            let diameter = Panel::of_law(
                diameter_title,
                (
                    "equivalent diameter (box units)",
                    "probability density (1/box unit)",
                ),
                &phase.size,
                (grains.iter())
                    .map(|g| dimension.equivalent_diameter(g.semi_axes))
                    .collect(),
                voxel_values(|s| Some(s.equivalent_diameter)),
            );
            let density = "probability density";
            // Triaxial phases: b/a (a2/a1) against its law in place of a1/a2; the
            // summary has c/a and c/b too.
            let aspect = match &phase.triaxial {
                None => Panel::of_law(
                    "aspect ratio",
                    ("aspect ratio a1/a2 (dimensionless)", density),
                    &phase.aspect_ratio,
                    grains.iter().map(|g| aspect_ratio(g.semi_axes)).collect(),
                    voxel_values(|s| Some(s.aspect_ratio)),
                ),
                Some(t) => Panel::of_law(
                    "shape ratio b/a",
                    ("shape ratio b/a = a2/a1 (dimensionless)", density),
                    &t.b_over_a,
                    (grains.iter())
                        .map(|g| g.semi_axes[1] / g.semi_axes[0])
                        .collect(),
                    voxel_values(|s| s.shape_ratios.map(|r| r[0])),
                ),
            };
            let angle = match (dimension, &phase.orientation) {
                // The voxel samples' angle is the axis's to z, not in the plane.
                (Dimension::Two, o) if !matches!(o, Orientation::Tilt { .. }) => {
                    plane_angle_panel(o, &grains)
                }
                (_, o) => Panel {
                    voxel: voxel_values(|s| s.tilt.map(f64::to_degrees)),
                    ..angle_panel(o, &grains)
                },
            };
            Row {
                title,
                panels: [diameter, aspect, angle],
            }
        })
        .collect())
}
