//! What the integration tests share, one module per subject. Each test binary uses its
//! own part, hence the `dead_code` allowance.
#![allow(dead_code)]

pub mod files;
pub mod octree;
pub mod packed;
pub mod scene;
pub mod voxel;
pub mod vtk;
