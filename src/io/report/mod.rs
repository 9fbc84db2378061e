//! What a packing run writes: the grain table (`grains.csv`), the VTK exports
//! (`grains.vtu`, `centers.vtp`, see [`crate::io::vtk`]) and the run's summary
//! (`summary.json`), with the statistics of the packed grains against the scene's laws.
//!
//! Each file is written to a temporary name beside it and renamed when complete
//! ([`write_atomically`](crate::io::atomic::write_atomically)), so a reader never sees a partial file; `summary.json` is
//! written last.
//!
//! ```no_run
//! use grainpack::io::report::write_outputs;
//! use grainpack::run::{run, RunOptions};
//! use grainpack::scene::Scene;
//!
//! let scene = Scene::from_path("configs/grains.toml".as_ref())?;
//! let result = run(&scene, RunOptions::default())?;
//! let written = write_outputs(&scene, &result)?;
//! println!("wrote {} files in {:.2} s", written.files.len(), written.seconds);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod derived;
mod files;
mod grains_csv;
mod summary;
mod texture;

pub use derived::{
    write_derived, Crystals, Packed, RveSummary, RVE_GRAINS_CSV, RVE_VTI, SECTIONS_PNG,
    STATISTICS_PNG,
};

pub use crate::io::texture::crystal_orientations;
pub use files::{create_dir, OutputFiles};
pub use grains_csv::{
    grains_header, write_grains_csv, CRYSTAL_HEADER, GRAINS_CSV, GRAINS_HEADER, GRAINS_HEADER_2D,
};
pub use summary::{CounterSummary, Summary, TimingSummary, UnitsSummary};
pub use texture::{texture_summaries, TextureSummary};

use crate::contact::Dimension;
use crate::io::decks::{
    write_abaqus_deck, write_load_yaml, write_material_yaml, write_umat_sections, LOAD_YAML,
    MATERIAL_YAML, RVE_INP, RVE_UMAT_INP,
};
use crate::io::mesh::{python, write_mesh, MeshError, MeshStats, MESH_INP, MESH_MSH, MESH_VTU};
use crate::io::plots::{render_packing_png, render_pole_figures_png};
use crate::io::texture::measure_textures;
use crate::io::vtk::{write_centers_vtp, write_grains_vtu, CENTERS_VTP, GRAINS_VTU};
use crate::run::RunResult;
use crate::scene::{PhaseTexture, Scene};
use std::io::{self, Write};
use std::path::PathBuf;

/// File name of the pole figures of the crystal orientations, written with
/// `statistics_png` when a phase has a texture other than the default (random) or
/// `damask` or `abaqus` is on.
pub const POLE_FIGURES_PNG: &str = "pole_figures.png";

/// File name of the picture of a 2D packing (`packing_png`).
pub const PACKING_PNG: &str = "packing.png";

/// File name of the summary.
pub const SUMMARY_JSON: &str = "summary.json";

/// Why the outputs could not be written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ReportError {
    /// The output directory could not be created.
    #[error("cannot create the output directory {}", path.display())]
    CreateDir {
        /// The directory.
        path: PathBuf,
        /// What the operating system said.
        #[source]
        source: io::Error,
    },
    /// A file could not be written (nothing was left under its name).
    #[error("cannot write {}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        #[source]
        source: io::Error,
    },
    /// The conforming mesh could not be made (no mesh file was left).
    #[error("cannot write the conforming mesh")]
    Mesh(#[from] MeshError),
}

/// Writes the summary as pretty-printed JSON, ending with a newline.
pub fn write_summary_json(out: &mut dyn Write, summary: &Summary) -> io::Result<()> {
    serde_json::to_writer_pretty(&mut *out, summary)?;
    out.write_all(b"\n")
}

/// What [`write_outputs`] wrote.
#[derive(Debug, Clone)]
pub struct Written {
    /// The paths written, in order.
    pub files: Vec<PathBuf>,
    /// How well the voxel RVE renders the grains, when one was written.
    pub rve: Option<RveSummary>,
    /// What the conforming mesh measured, when one was written.
    pub mesh: Option<MeshStats>,
    /// Each phase's crystal orientations against its texture (as in the summary).
    pub textures: Vec<TextureSummary>,
    /// Seconds spent writing everything before `summary.json`.
    pub seconds: f64,
}

/// Creates `scene.output.dir` if needed and writes the files `scene.output` enables
/// for `result`, each to a temporary name renamed when complete, in this order:
/// [`GRAINS_CSV`], [`GRAINS_VTU`], [`CENTERS_VTP`], [`PACKING_PNG`] (2D), the
/// outputs of [`write_derived`], and [`SUMMARY_JSON`] last, so that a summary means the other
/// files are complete.
pub fn write_outputs(scene: &Scene, result: &RunResult) -> Result<Written, ReportError> {
    let started = std::time::Instant::now();
    let (output, domain) = (&scene.output, &scene.domain);
    let grains = &result.packing.grains;
    if output.writes_anything() {
        create_dir(&output.dir)?;
    }
    let mut files = OutputFiles::new(&output.dir);
    // Computed once, for every file that shows them.
    let crystals = crystal_orientations(scene, result);
    let measures = measure_textures(scene, result, &crystals);
    if output.grains_csv {
        files.write(GRAINS_CSV, |w| {
            write_grains_csv(w, grains, &crystals, domain.dimension)
        })?;
    }
    if let Some(vtk) = &output.vtk {
        files.write(GRAINS_VTU, |w| {
            write_grains_vtu(w, grains, domain, vtk, Some(&crystals))
        })?;
    }
    if output.centers {
        files.write(CENTERS_VTP, |w| {
            write_centers_vtp(w, grains, Some(&crystals), domain.dimension)
        })?;
    }
    if output.packing_png && domain.dimension == Dimension::Two {
        files.write(PACKING_PNG, |w| {
            render_packing_png(
                w,
                &scene.phases,
                grains,
                domain,
                scene.units.length.symbol(),
            )
            .map_err(io::Error::other)
        })?;
    }
    // Where it helps: a texture was asked for, or orientations go to a solver.
    let textured = scene
        .phases
        .iter()
        .any(|p| p.texture != PhaseTexture::default());
    if output.statistics_png && (textured || output.damask || output.abaqus) {
        files.write(POLE_FIGURES_PNG, |w| {
            render_pole_figures_png(w, &scene.phases, grains, &crystals).map_err(io::Error::other)
        })?;
    }
    // The same condition for the texture panels and rve.vti's orientations.
    let shown = (textured || output.damask || output.abaqus).then_some(Crystals {
        orientations: &crystals,
        measures: &measures,
    });
    let packed = Packed {
        phases: &scene.phases,
        domain,
        units: scene.units,
        grains,
        statistics: Some(&result.statistics.phases),
    };
    let rve = write_derived(output, packed, shown, &mut files, |grid, files| {
        if output.damask {
            files.write(MATERIAL_YAML, |w| {
                write_material_yaml(w, scene, grains, &crystals, grid)
            })?;
            files.write(LOAD_YAML, |w| write_load_yaml(w, grid))?;
        }
        if output.abaqus {
            files.write(RVE_INP, |w| write_abaqus_deck(w, scene, grid))?;
            files.write(RVE_UMAT_INP, |w| {
                write_umat_sections(w, scene, grains, &crystals, grid)
            })?;
        }
        Ok(())
    })?;
    let mesh = match output.mesh {
        Some(_) => {
            let stats = write_mesh(scene, grains, &output.dir, result.threads, &python())?;
            for name in [MESH_MSH, MESH_INP, MESH_VTU] {
                files.record(output.dir.join(name));
            }
            Some(stats)
        }
        None => None,
    };
    let seconds = started.elapsed().as_secs_f64();
    let textures = texture_summaries(scene, &measures);
    if output.summary_json {
        let mut summary = Summary::new(scene, result, rve.as_ref(), textures.clone(), seconds);
        summary.mesh = mesh.as_ref();
        files.write(SUMMARY_JSON, |w| write_summary_json(w, &summary))?;
    }
    Ok(Written {
        files: files.into_written(),
        rve,
        mesh,
        textures,
        seconds,
    })
}
