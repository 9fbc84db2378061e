//! Files in and out: contact cases (CSV), and later scenes, exports and reports.

pub mod atomic;
pub mod cases;
pub mod decks;
pub mod mesh;
pub mod plots;
pub mod report;
pub mod scene;
pub mod texture;
pub mod voxel;
pub mod vtk;
mod zlib_blocks;
