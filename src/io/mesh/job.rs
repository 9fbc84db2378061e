//! The job handed to `gmsh_mesh.py`: everything it needs, as JSON.
//!
//! A 2D scene's job (`dimension` 2) has the rectangle's two lengths as `box` and the
//! plane-strain step template of `rve.inp` as `plane_step` (written here by
//! `crate::io::decks`, so that both decks have the same step); its grains are the
//! ellipsoids the ellipses are packed as (docs/design-2d.md), of which the mesher uses
//! the first two semi-axes and the turn about z.

use crate::contact::equivalent_diameter;
use crate::contact::Dimension;
use crate::io::decks::{
    matrix_name, section_name, write_plane_step, PLACEHOLDER_ELASTIC, STEP_MARKER, TEMPLATE_STRAIN,
};
use crate::packing::PackedGrain;
use crate::scene::Elastic;
use crate::scene::{Boundary, RveFill, Scene};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// The mesher's input (read by `gmsh_mesh.py`'s `main`).
#[derive(Debug, Serialize)]
pub struct MeshJob<'a> {
    /// 3, or 2 for a 2D scene (a triangle mesh of the rectangle).
    dimension: u8,
    /// The box's edges: three, or the rectangle's two in 2D.
    #[serde(rename = "box")]
    box_size: Vec<f64>,
    periodic: bool,
    grains: Vec<JobGrain>,
    element_size: f64,
    order: u8,
    /// "matrix", or "grains": the elements between the grains shared out among them.
    fill: RveFill,
    threads: usize,
    length_unit: &'static str,
    stress_unit: &'static str,
    /// The phase number of the matrix (the number of phases, as in `rve.vti`).
    matrix_phase: usize,
    materials: Vec<JobMaterial>,
    strain: f64,
    step_marker: &'static str,
    /// 2D only: the step template of the plane-strain deck, from its marker line on.
    #[serde(skip_serializing_if = "Option::is_none")]
    plane_step: Option<String>,
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
    if spec.fill == RveFill::Matrix {
        let m = scene.matrix.elastic.unwrap_or(fallback);
        materials.push(JobMaterial {
            name: section_name("", matrix_name(scene)),
            phase: scene.phases.len(),
            young: m.young,
            poisson: m.poisson,
        });
    }
    let [msh, inp, vtu] = files;
    let periodic = scene.domain.boundary == Boundary::Periodic;
    let plane = scene.domain.dimension == Dimension::Two;
    let plane_step = plane.then(|| {
        let mut step = Vec::new();
        let [lx, ly, _] = scene.domain.size;
        write_plane_step(&mut step, [lx, ly], periodic).expect("writes to a Vec");
        String::from_utf8(step).expect("the step is UTF-8")
    });
    MeshJob {
        dimension: if plane { 2 } else { 3 },
        box_size: scene.domain.sides().to_vec(),
        periodic,
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
        fill: spec.fill,
        threads,
        length_unit: scene.units.length.symbol(),
        stress_unit: scene.units.stress.symbol(),
        matrix_phase: scene.phases.len(),
        materials,
        strain: TEMPLATE_STRAIN,
        step_marker: STEP_MARKER,
        plane_step,
        files: JobFiles { msh, inp, vtu },
        stats,
    }
}
