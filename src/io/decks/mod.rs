//! Solver input sets written on the voxel RVE's cells: DAMASK's `material.yaml` and
//! `load.yaml` ([`write_material_yaml`], [`write_load_yaml`]), and an Abaqus/CalculiX
//! deck `rve.inp` ([`write_abaqus_deck`]) with per-grain UMAT sections beside it
//! ([`write_umat_sections`]).
//!
//! Materials are numbered as in `rve.vti`: grain `k` is material `k` (DAMASK's
//! material index, the deck's `GRAIN_k` element set), the matrix of
//! `rve_fill = "matrix"` last.

mod abaqus;
mod boundary;
mod damask;
mod names;

pub use abaqus::{
    write_abaqus_deck, write_plane_step, write_umat_sections, PLANE_THICKNESS, RVE_INP,
    RVE_UMAT_INP, STEP_MARKER, TEMPLATE_STRAIN,
};
pub use damask::{
    write_load_yaml, write_material_yaml, LOAD_YAML, MATERIAL_YAML, PLACEHOLDER_ELASTIC,
};
pub use names::{matrix_name, section_name};
