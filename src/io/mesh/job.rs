//! The job handed to `gmsh_mesh.py`: everything it needs, as JSON.

use crate::contact::equivalent_diameter;
use crate::io::decks::{
    matrix_name, section_name, PLACEHOLDER_ELASTIC, STEP_MARKER, TEMPLATE_STRAIN,
};
use crate::packing::PackedGrain;
use crate::scene::Elastic;
use crate::scene::{Boundary, Scene};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// The mesher's input (read by `gmsh_mesh.py`'s `main`).
#[derive(Debug, Serialize)]
pub struct MeshJob<'a> {
    #[serde(rename = "box")]
    box_size: [f64; 3],
    periodic: bool,
    grains: Vec<JobGrain>,
    element_size: f64,
    order: u8,
    threads: usize,
    length_unit: &'static str,
    stress_unit: &'static str,
    /// The phase number of the matrix (the number of phases, as in `rve.vti`).
    matrix_phase: usize,
    materials: Vec<JobMaterial>,
    strain: f64,
    step_marker: &'static str,
    files: JobFiles,
    stats: &'a Path,
}

#[derive(Debug, Serialize)]
struct JobGrain {
    id: u32,
    phase: usize,
    centre: [f64; 3],
    semi_axes: [f64; 3],
    quaternion: [f64; 4],
}

#[derive(Debug, Serialize)]
struct JobMaterial {
    name: String,
    phase: usize,
    young: f64,
    poisson: f64,
}

#[derive(Debug, Serialize)]
struct JobFiles {
    msh: PathBuf,
    inp: PathBuf,
    vtu: PathBuf,
}

/// The job for `grains` of `scene`, writing to `files` (msh, inp, vtu) and the
/// measured statistics to `stats`. Validation made sure every phase and the matrix
/// have elastic constants; one missing would be a bug, and takes the DAMASK
/// placeholder as in `rve.inp`.
pub fn mesh_job<'a>(
    scene: &Scene,
    grains: &[PackedGrain],
    threads: usize,
    files: [PathBuf; 3],
    stats: &'a Path,
) -> MeshJob<'a> {
    let spec = scene.output.mesh.unwrap_or_default();
    let smallest = grains
        .iter()
        .map(|g| equivalent_diameter(g.semi_axes))
        .fold(f64::INFINITY, f64::min);
    // The placeholder is in Pa; the deck is in the scene's stress unit.
    let fallback = Elastic {
        young: scene.units.stress.from_si(PLACEHOLDER_ELASTIC.young),
        ..PLACEHOLDER_ELASTIC
    };
    let mut materials: Vec<JobMaterial> = scene
        .phases
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let e = p.elastic.unwrap_or(fallback);
            JobMaterial {
                name: section_name(&format!("PHASE{i}_"), &p.name),
                phase: i,
                young: e.young,
                poisson: e.poisson,
            }
        })
        .collect();
    let m = scene.matrix.elastic.unwrap_or(fallback);
    materials.push(JobMaterial {
        name: section_name("", matrix_name(scene)),
        phase: scene.phases.len(),
        young: m.young,
        poisson: m.poisson,
    });
    let [msh, inp, vtu] = files;
    MeshJob {
        box_size: scene.domain.size,
        periodic: scene.domain.boundary == Boundary::Periodic,
        grains: grains
            .iter()
            .map(|g| JobGrain {
                id: g.id,
                phase: g.phase,
                centre: g.centre,
                semi_axes: g.semi_axes,
                quaternion: g.quaternion,
            })
            .collect(),
        element_size: spec.size * smallest,
        order: spec.order,
        threads,
        length_unit: scene.units.length.symbol(),
        stress_unit: scene.units.stress.symbol(),
        matrix_phase: scene.phases.len(),
        materials,
        strain: TEMPLATE_STRAIN,
        step_marker: STEP_MARKER,
        files: JobFiles { msh, inp, vtu },
        stats,
    }
}
