//! The conforming mesh (`[output] mesh = true`): the packed grains and the matrix
//! between them as body-fitted tetrahedra (triangles of the rectangle in 2D, for a
//! plane-strain deck), periodic in a periodic box, made by gmsh.
//!
//! grainpack drives gmsh through its Python API: `gmsh_mesh.py`, embedded in this
//! library, runs in a Python with the `gmsh` package (`pip install gmsh==4.15.2`):
//! for `pack` the `python3` on `PATH` or `$GRAINPACK_PYTHON` ([`python`]), for the
//! Python module's `Packing.mesh` its own interpreter. Why this and not the C API or a `.geo`
//! script: docs/architecture.md ("The conforming mesh"). The script receives a job
//! (`job.rs`: the box, the grains, the options, the materials) and writes
//! [`MESH_MSH`], [`MESH_INP`] and [`MESH_VTU`] to temporary names that are renamed
//! here only when all three are complete; on failure nothing is left.
//!
//! Numbering and sets of `mesh.inp` follow `rve.inp` (`crate::io::decks`): element
//! sets `GRAIN_<id>`, `PHASE<i>_<NAME>` and the matrix, node sets of the faces, edges
//! and corners, reference nodes `RPX`, `RPY`, `RPZ` after the mesh's nodes, periodic
//! `*Equation`s `u(node) − u(image) − Σ u(RP_d) = 0`, the same step template. Node 1
//! is the corner at the mesh's origin, which the template fixes.
//!
//! In a periodic box the meshed window is the box shifted (`MeshStats::origin`) so
//! that every grain's tangent planes clear the faces by the largest margin found: a
//! grain that barely crosses a face leaves a cap too thin to mesh (issue 29).

mod job;

pub use job::mesh_job;

use crate::packing::PackedGrain;
use crate::scene::Scene;
use serde::{Deserialize, Serialize};
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// File name of the gmsh mesh (format 4.1).
pub const MESH_MSH: &str = "mesh.msh";
/// File name of the Abaqus/CalculiX deck on the conforming mesh.
pub const MESH_INP: &str = "mesh.inp";
/// File name of the mesh for ParaView/PyVista (cell data `grain`, `phase`, `sicn`).
pub const MESH_VTU: &str = "mesh.vtu";

/// The gmsh release the script is written and tested against (`.ci/run` installs it).
pub const GMSH_VERSION: &str = "4.15.2";

/// How to get gmsh, printed when it is missing.
pub const GMSH_INSTALL_HINT: &str = "install gmsh's Python package into the python3 on \
     PATH (`python3 -m pip install gmsh==4.15.2`), or point $GRAINPACK_PYTHON at a Python \
     that has it";

/// Exit code of the script when gmsh could not mesh the packing (its message on
/// stderr); `EXIT_MESH_FAILED` in `gmsh_mesh.py`.
const SCRIPT_MESH_FAILED: i32 = 3;

/// The mesher's Python modules (name, source), embedded so that `pack` needs no file
/// beside it; `LOADER` makes them importable and runs `gmsh_mesh.main()`.
const MODULES: [(&str, &str); 9] = [
    ("gmsh_mesh", include_str!("gmsh_mesh.py")),
    ("mesh_common", include_str!("mesh_common.py")),
    ("mesh_geometry", include_str!("mesh_geometry.py")),
    ("mesh_nodes", include_str!("mesh_nodes.py")),
    ("mesh_write", include_str!("mesh_write.py")),
    ("mesh_plane", include_str!("mesh_plane.py")),
    ("mesh_quadratic", include_str!("mesh_quadratic.py")),
    ("mesh_surface", include_str!("mesh_surface.py")),
    ("mesh_fill", include_str!("mesh_fill.py")),
];

/// Run as `python -c LOADER job.json`, with [`MODULES`] as a JSON object on stdin.
const LOADER: &str = include_str!("loader.py");

/// Why the mesh could not be made.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum MeshError {
    /// No Python, or no gmsh in it.
    #[error("output.mesh = true needs gmsh, which {python} cannot import ({detail}): {GMSH_INSTALL_HINT}")]
    GmshMissing {
        /// The Python tried.
        python: String,
        /// What it said.
        detail: String,
    },
    /// gmsh could not mesh the packing (nothing written).
    #[error("gmsh could not mesh the packing (no mesh file written): {message}")]
    Failed {
        /// gmsh's message, or the pipeline's.
        message: String,
    },
    /// The job or a result could not be written or read.
    #[error("mesh files in {}", dir.display())]
    Io {
        /// The output directory.
        dir: PathBuf,
        /// What went wrong.
        #[source]
        source: std::io::Error,
    },
}

/// What the mesher measured, as `summary.json` reports it (`mesh`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MeshStats {
    /// Elements: tetrahedra, triangles in 2D.
    pub elements: usize,
    /// Nodes (the reference nodes not counted).
    pub nodes: usize,
    /// Element order (1: C3D4, 2: C3D10; in 2D 1: CPE3, 2: CPE6).
    pub order: u8,
    /// Largest element edge asked of gmsh, in the scene's length unit.
    pub element_size: f64,
    /// Smallest signed inverse condition number over the elements (gmsh's `minSICN`;
    /// 1 for a regular tetrahedron, ≤ 0 inverted, which is refused).
    pub min_sicn: f64,
    /// Its first percentile.
    pub p1_sicn: f64,
    /// Seconds to build the geometry (OCC fragments, periodic pairing).
    pub geometry_seconds: f64,
    /// Seconds to mesh it (surfaces, volumes, periodic snapping).
    pub mesh_seconds: f64,
    /// Whether gmsh's first attempt failed and the mesh is the second one's: the
    /// geometry rebuilt in a new gmsh session, with sizes from curvature (its seconds
    /// count in `geometry_seconds`).
    pub retried_with_curvature: bool,
    /// gmsh's error in the first attempt, when the mesh is the second one's.
    #[serde(default)]
    pub first_attempt_error: Option<String>,
    /// The repairs of the surface mesh where gmsh failed on it (`mesh_surface.py`):
    /// Delaunay on a surface gmsh left invalid, more nodes on a curve whose periodic
    /// copy mismatched or whose two surfaces held the same triangles. Empty when the
    /// first surface mesh was sound.
    #[serde(default)]
    pub surface_repairs: Vec<String>,
    /// Lower corner of the meshed window of the periodic packing (two coordinates in
    /// 2D, where the mesh lies in the plane z = 0).
    pub origin: Vec<f64>,
    /// Per axis, the least distance from a box face to a grain's tangent plane
    /// (periodic box only; two axes in 2D).
    pub face_margin: Option<Vec<f64>>,
    /// Pairs of opposite face pieces made periodic (in 2D, pieces of the edges).
    pub periodic_face_pairs: usize,
    /// Nodes tied to an image by periodic equations.
    pub periodic_nodes: usize,
    /// Largest distance a periodic node moved when snapped onto its master plus the
    /// box length.
    pub largest_snap: f64,
    /// Quadratic elements only: middle nodes put back on their edge's straight midpoint
    /// because, on the curved surface, they inverted an element (with their periodic
    /// partners); 0 for linear elements.
    #[serde(default)]
    pub straightened_middle_nodes: usize,
    /// Per phase (the matrix last), the volume fraction (area fraction in 2D) of the
    /// mesh's elements against the packing's exact one: they differ by the chordal
    /// error of the elements.
    pub phase_volume_fractions: Vec<PhaseVolume>,
    /// gmsh's version.
    pub gmsh: String,
}

/// One phase's volume fraction in the mesh and in the packing.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PhaseVolume {
    /// Phase index (the number of phases for the matrix).
    pub phase: usize,
    /// Σ element volumes / box volume (straight-sided elements; areas in 2D).
    pub mesh: f64,
    /// Σ (4π/3) a1 a2 a3 / box volume (in 2D Σ π a1 a2 / rectangle area; the matrix:
    /// the rest).
    pub exact: f64,
}

/// The Python that runs the mesher: `$GRAINPACK_PYTHON`, else `python3`.
pub fn python() -> String {
    std::env::var("GRAINPACK_PYTHON").unwrap_or_else(|_| "python3".to_owned())
}

/// gmsh's version in the Python `python` (as [`python`] gives it), or why it cannot be
/// used. Called before packing, so that a missing gmsh fails at once.
pub fn gmsh_version(python: &str) -> Result<String, MeshError> {
    let missing = |detail: String| MeshError::GmshMissing {
        python: python.to_owned(),
        detail,
    };
    let out = Command::new(python)
        .args(["-c", "import gmsh; print(gmsh.__version__)"])
        .output()
        .map_err(|e| missing(e.to_string()))?;
    if !out.status.success() {
        let err = String::from_utf8_lossy(&out.stderr);
        return Err(missing(
            err.lines().last().unwrap_or("no message").to_owned(),
        ));
    }
    Ok(String::from_utf8_lossy(&out.stdout).trim().to_owned())
}

/// Meshes `grains` (packed in `scene`) into `dir` with gmsh in the Python `python`:
/// [`MESH_MSH`], [`MESH_INP`], [`MESH_VTU`], all or none.
pub fn write_mesh(
    scene: &Scene,
    grains: &[PackedGrain],
    dir: &Path,
    threads: usize,
    python: &str,
) -> Result<MeshStats, MeshError> {
    let io = |source| MeshError::Io {
        dir: dir.to_path_buf(),
        source,
    };
    let pid = std::process::id();
    // The extension last: gmsh picks the format by it.
    let tmp = |name: &str| dir.join(format!(".tmp-{pid}-{name}"));
    let names = [MESH_MSH, MESH_INP, MESH_VTU];
    let (job_path, stats_path) = (tmp("mesh_job.json"), tmp("mesh_stats.json"));
    let job = mesh_job(scene, grains, threads, names.map(tmp), &stats_path);
    let cleanup = || {
        for p in names.map(tmp).iter().chain([&job_path, &stats_path]) {
            let _ = fs::remove_file(p);
        }
    };
    let result = (|| {
        let text = serde_json::to_vec(&job).map_err(|e| io(std::io::Error::other(e)))?;
        fs::write(&job_path, text).map_err(io)?;
        let out = run_script(python, &job_path).map_err(|e| MeshError::GmshMissing {
            python: python.to_owned(),
            detail: e.to_string(),
        })?;
        if !out.status.success() {
            let err = String::from_utf8_lossy(&out.stderr).trim().to_owned();
            return Err(match out.status.code() {
                Some(SCRIPT_MESH_FAILED) => MeshError::Failed { message: err },
                _ => MeshError::Failed {
                    message: format!("the mesher stopped ({}): {err}", out.status),
                },
            });
        }
        let stats: MeshStats = serde_json::from_slice(&fs::read(&stats_path).map_err(io)?)
            .map_err(|e| io(std::io::Error::other(e)))?;
        for name in names {
            fs::rename(tmp(name), dir.join(name)).map_err(io)?;
        }
        Ok(stats)
    })();
    cleanup();
    result
}

/// Runs the mesher on the job at `job` in `python`: [`LOADER`] on the command line,
/// [`MODULES`] on its stdin (which the loader reads whole before anything else).
fn run_script(python: &str, job: &Path) -> std::io::Result<std::process::Output> {
    let sources: serde_json::Map<String, serde_json::Value> = MODULES
        .iter()
        .map(|&(name, source)| (name.to_owned(), source.into()))
        .collect();
    let mut child = Command::new(python)
        .arg("-c")
        .arg(LOADER)
        .arg(job)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()?;
    let mut stdin = child.stdin.take().expect("stdin is piped");
    let written = serde_json::to_writer(&mut stdin, &sources).map_err(std::io::Error::other);
    // Closed before waiting, so the loader sees the end of its input.
    drop(stdin);
    let out = child.wait_with_output()?;
    written.map(|()| out)
}
