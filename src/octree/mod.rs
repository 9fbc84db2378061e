//! Broad phase: octree over the box plus bounding spheres.
