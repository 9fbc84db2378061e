//! The outputs derived from the packed grains: the voxel RVE (`rve.vti`, its per-grain
//! table `rve_grains.csv` and `sections.png`) and the statistics figure
//! (`statistics.png`). The RVE's totals are returned for the summary.

use super::{OutputFiles, ReportError};
use crate::contact::{dot, rotation_column, sphere_diameter, Dimension};
use crate::io::plots::{render_run_statistics_png, VoxelSample};
use crate::io::texture::TextureMeasure;
use crate::io::voxel::{
    grain_report, voxelise, write_sections_png, write_vti, VoxelGrid, VoxelReport, VoxelShape,
};
use crate::packing::PackedGrain;
use crate::run::PhaseStatistics;
use crate::scene::{tilt_angle_of, Domain, Orientation, OutputSpec, Phase, RveFill, Units};
use serde::Serialize;
use std::io;
use std::time::Instant;

/// File name of the voxel RVE.
pub const RVE_VTI: &str = "rve.vti";
/// File name of the RVE's per-grain table.
pub const RVE_GRAINS_CSV: &str = "rve_grains.csv";
/// File name of the RVE's mid-sections.
pub const SECTIONS_PNG: &str = "sections.png";
/// File name of the statistics figure.
pub const STATISTICS_PNG: &str = "statistics.png";

/// The crystal orientations of a run, for the files that show them.
#[derive(Debug, Clone, Copy)]
pub struct Crystals<'a> {
    /// Each grain's crystal orientation, in grain id order
    /// ([`crystal_orientations`](crate::io::texture::crystal_orientations)).
    pub orientations: &'a [[f64; 4]],
    /// Each phase's texture, measured on them
    /// ([`measure_textures`](crate::io::texture::measure_textures)).
    pub measures: &'a [TextureMeasure],
}

/// What a run packed, for the files derived from it.
#[derive(Debug, Clone, Copy)]
pub struct Packed<'a> {
    /// The scene's phases.
    pub phases: &'a [Phase],
    /// The box.
    pub domain: &'a Domain,
    /// The scene's units (`rve.vti` is written in metres).
    pub units: Units,
    /// The packed grains, in id order.
    pub grains: &'a [PackedGrain],
    /// The run's statistics, one per phase (the figure's KS distances), when known.
    pub statistics: Option<&'a [PhaseStatistics]>,
}

/// The RVE in `summary.json`: its grid, and how well the voxel grains render the
/// ellipsoids (per grain in `rve_grains.csv`).
#[derive(Debug, Clone, Serialize)]
pub struct RveSummary {
    /// Cells along x, y, z.
    pub cells: [usize; 3],
    /// `"grains"` or `"matrix"`.
    pub fill: RveFill,
    /// Materials in `rve.vti`: one per grain (material k is grain k), plus the matrix
    /// (material = number of grains) when `fill = "matrix"`.
    pub materials: usize,
    /// Largest `|voxel volume / ellipsoid volume − 1|` over the grains.
    pub max_abs_volume_deviation: f64,
    /// Mean of the same.
    pub mean_abs_volume_deviation: f64,
    /// Grains whose voxels form more than one face-connected piece (periodic-aware).
    pub split_grains: usize,
    /// Their ids.
    pub split_grain_ids: Vec<u32>,
    /// Voxels outside their grain's largest piece, over all grains.
    pub stray_voxels: u64,
    /// Grains with no voxel at all (smaller than a voxel).
    pub empty_grains: usize,
    /// Share of the voxels that are matrix (0 for `fill = "grains"`).
    pub matrix_fraction: f64,
    /// Seconds to voxelise.
    pub voxelise_seconds: f64,
    /// For a 2D pixel RVE (one layer along z), the layer's z edge in `rve.vti`
    /// ([`layer_thickness`](crate::io::voxel::layer_thickness), in the scene's length
    /// unit); absent in 3D. Every volume above is then an area.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub layer_thickness: Option<f64>,
}

impl RveSummary {
    fn new(grid: &VoxelGrid, report: &VoxelReport, grains: usize, seconds: f64) -> Self {
        Self {
            cells: report.cells,
            fill: report.fill,
            materials: grains + usize::from(report.fill == RveFill::Matrix),
            max_abs_volume_deviation: report.max_abs_volume_deviation,
            mean_abs_volume_deviation: report.mean_abs_volume_deviation,
            split_grains: report.split_grains.len(),
            split_grain_ids: report.split_grains.clone(),
            stray_voxels: report.stray_voxels,
            empty_grains: report.empty_grains.len(),
            matrix_fraction: report.matrix_fraction,
            voxelise_seconds: seconds,
            layer_thickness: (grid.dimension == Dimension::Two).then_some(grid.size[2]),
        }
    }
}

/// Writes the RVE files and the statistics figure asked for by `output`, calling
/// `beside_rve` with the voxel grid once `rve.vti` is written (for the files written on
/// its cells: DAMASK's and Abaqus'); returns the RVE's totals when one was written.
/// With `crystals` (when crystal orientations are asked for), `rve.vti` has each
/// cell's orientation and the statistics figure each phase's texture;
/// `statistics` (the run's, one per phase) gives the figure's KS distances.
pub fn write_derived(
    output: &OutputSpec,
    packed: Packed,
    crystals: Option<Crystals>,
    files: &mut OutputFiles,
    beside_rve: impl FnOnce(&VoxelGrid, &mut OutputFiles) -> Result<(), ReportError>,
) -> Result<Option<RveSummary>, ReportError> {
    let Packed {
        phases,
        domain,
        units,
        grains,
        statistics,
    } = packed;
    let (mut samples, mut summary) = (None, None);
    if let Some(rve) = &output.rve {
        let fill = rve.fill;
        let start = Instant::now();
        let grid = voxelise(grains, domain, rve.cells, fill, phases.len())
            .map_err(|e| files.error(RVE_VTI, io::Error::other(e)))?;
        let seconds = start.elapsed().as_secs_f64();
        files.write(RVE_VTI, |w| {
            write_vti(&grid, units.length, crystals.map(|c| c.orientations), w)
        })?;
        beside_rve(&grid, files)?;
        let report = grain_report(&grid, grains)
            .map_err(|e| files.error(RVE_GRAINS_CSV, io::Error::other(e)))?;
        files.write(RVE_GRAINS_CSV, |w| write_rve_grains(w, &report))?;
        if rve.sections_png {
            let path = files.path(SECTIONS_PNG);
            write_sections_png(&grid, &path)
                .map_err(|e| files.error(SECTIONS_PNG, io::Error::other(e)))?;
            files.record(path);
        }
        summary = Some(RveSummary::new(&grid, &report, grains.len(), seconds));
        samples = Some(voxel_samples(&report, grains, phases));
    }
    if output.statistics_png {
        files.write(STATISTICS_PNG, |w| {
            let textures = crystals.map_or(&[][..], |c| c.measures);
            render_run_statistics_png(
                w,
                phases,
                grains,
                samples.as_deref(),
                statistics,
                textures,
                domain.dimension,
            )
            .map_err(io::Error::other)
        })?;
    }
    Ok(summary)
}

/// `id,phase,voxels,voxel_volume,ellipsoid_volume,volume_deviation,pieces,stray_voxels`.
fn write_rve_grains(out: &mut dyn io::Write, report: &VoxelReport) -> io::Result<()> {
    let mut w = csv::Writer::from_writer(out);
    w.write_record([
        "id",
        "phase",
        "voxels",
        "voxel_volume",
        "ellipsoid_volume",
        "volume_deviation",
        "pieces",
        "stray_voxels",
    ])?;
    for g in &report.grains {
        w.write_record([
            g.id.to_string(),
            g.phase.to_string(),
            g.voxels.to_string(),
            format!("{:.9e}", g.voxel_volume),
            format!("{:.9e}", g.ellipsoid_volume),
            format!("{:.6e}", g.volume_deviation),
            g.pieces.to_string(),
            g.stray_voxels.to_string(),
        ])?;
    }
    w.flush()
}

/// The voxel grains measured like the packed ones: the equivalent diameter of the
/// voxel volume, and the aspect ratio `a1/a2` and angle from the voxel grain's
/// moment ellipsoid, whose axis closest to the packed grain's first axis plays `a1`
/// (`a2` the geometric mean of the other two, the equatorial radius of a spheroid);
/// the triaxial ratios `b/a`, `c/a`, `c/b` from its sorted semi-axes.
fn voxel_samples(
    report: &VoxelReport,
    grains: &[PackedGrain],
    phases: &[Phase],
) -> Vec<VoxelSample> {
    report
        .grains
        .iter()
        .zip(grains)
        .filter_map(|(v, g)| {
            let shape = v.shape.as_ref()?;
            let first = rotation_column(g.quaternion, 0);
            // The moment axis most parallel to the packed first axis.
            let k = (0..3)
                .max_by(|&a, &b| {
                    let c = |k: usize| dot(&shape.axes[k], &first).abs();
                    c(a).total_cmp(&c(b))
                })
                .unwrap_or(0);
            // The other two, larger first (the moments are sorted largest first).
            let rest: Vec<usize> = (0..3).filter(|&m| m != k).collect();
            let others: Vec<f64> = rest.iter().map(|&m| shape.semi_axes[m]).collect();
            let a1 = shape.semi_axes[k];
            if report.dimension == Dimension::Two {
                return Some(plane_sample(g, shape, k, v.voxel_volume));
            }
            let a2 = (others[0] * others[1]).sqrt();
            let axis = shape.axes[k];
            let axis = if dot(&axis, &first) < 0.0 {
                axis.map(|x| -x)
            } else {
                axis
            };
            let tilt = match &phases.get(g.phase)?.orientation {
                Orientation::Tilt {
                    axis: tilt_axis,
                    angle,
                } => Some(tilt_angle_of(axis, *tilt_axis, angle)),
                // The panel's angle: to the law's mean direction, in [0, π].
                Orientation::Fisher(law) => Some(law.axis_angle(axis)),
                _ => Some(axis[2].abs().min(1.0).acos()),
            };
            let spin = match &phases.get(g.phase)?.orientation {
                Orientation::Fisher(law) => {
                    // The middle axis, signed like the packed second axis.
                    let b = shape.axes[rest[0]];
                    let packed_b = rotation_column(g.quaternion, 1);
                    let b = if dot(&b, &packed_b) < 0.0 {
                        b.map(|x| -x)
                    } else {
                        b
                    };
                    Some(law.spin_angle(axis, b))
                }
                _ => None,
            };
            Some(VoxelSample {
                phase: g.phase,
                // A sphere of the voxel volume: (6V/π)^(1/3).
                equivalent_diameter: sphere_diameter(v.voxel_volume),
                aspect_ratio: a1 / a2,
                tilt,
                shape_ratios: Some([shape.b_over_a, shape.c_over_a, shape.c_over_b]),
                spin,
            })
        })
        .collect()
}

/// A 2D pixel grain measured like the packed ellipse: the equivalent circle of its
/// area, and `a1/a2` from its moment ellipse (`semi_axes` `[a_max, √(a1 a2), a_min]`;
/// `k`, 0 or 2, the in-plane axis nearest the packed first axis, `2 − k` the other).
/// The angle panels of 2D scenes take no voxel samples (`tilt` and `spin` are `None`).
fn plane_sample(g: &PackedGrain, shape: &VoxelShape, k: usize, area: f64) -> VoxelSample {
    VoxelSample {
        phase: g.phase,
        equivalent_diameter: Dimension::Two.diameter_of(area),
        aspect_ratio: shape.semi_axes[k] / shape.semi_axes[2 - k],
        tilt: None,
        shape_ratios: None,
        spin: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    /// A few well-resolved triaxial `fisher` grains, far apart: their voxel shapes
    /// give back their ratios and their spin.
    #[test]
    fn voxel_samples_of_triaxial_fisher_grains_give_their_ratios_and_spin() {
        let scene = Scene::from_str(
            r#"
            seed = 3
            grains = 4
            [box]
            size = [40, 40, 40]
            [[phase]]
            size = { distribution = "constant", value = 12 }
            b_over_a = { distribution = "constant", value = 0.6 }
            c_over_a = { distribution = "constant", value = 0.3 }
            orientation = { kind = "fisher", direction = "x", kappa = 5, spin_reference = "y", spin_kappa = 1 }
            "#,
            "test.toml",
        )
        .unwrap();
        let specs = scene.sample_grains(&mut scene.rng()).unwrap();
        // a1 = 0.8 · 6 · (0.6 · 0.3)^(−1/3) ≈ 8.5: grains at most 17 long, their
        // centres (and periodic images) at least 20·√2 ≈ 28 apart.
        let centres = [
            [10.0, 10.0, 10.0],
            [30.0, 30.0, 10.0],
            [10.0, 30.0, 30.0],
            [30.0, 10.0, 30.0],
        ];
        let grains: Vec<PackedGrain> = specs
            .iter()
            .zip(centres)
            .enumerate()
            .map(|(i, (s, c))| PackedGrain::of_spec(i as u32, s, 0.8, c, s.quaternion))
            .collect();
        let grid = voxelise(&grains, &scene.domain, [100; 3], RveFill::Matrix, 1).unwrap();
        let report = grain_report(&grid, &grains).unwrap();
        let samples = voxel_samples(&report, &grains, &scene.phases);
        assert_eq!(samples.len(), 4);
        let Orientation::Fisher(law) = scene.phases[0].orientation else {
            panic!("fisher")
        };
        for (s, g) in samples.iter().zip(&grains) {
            // c ≈ 2.5 units = 6 voxels across its semi-axis: ratios within a few per cent.
            let [ba, ca, _] = s.shape_ratios.unwrap();
            assert!((ba / 0.6 - 1.0).abs() < 0.06, "{s:?}");
            assert!((ca / 0.3 - 1.0).abs() < 0.08, "{s:?}");
            // The moment axes are those of the ellipsoid to a degree or two.
            let e = rotation_column(g.quaternion, 0);
            let packed = law.spin_angle(e, rotation_column(g.quaternion, 1));
            let d = (s.spin.unwrap() - packed).abs().to_degrees();
            assert!(d < 3.0, "spin {:?} vs {packed}: {d}°", s.spin);
        }
    }
}
