//! The build's working buffers, owned by the tree between builds.

/// A sphere being sorted into tree order.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Item {
    pub centre: [f64; 3],
    pub radius: f64,
    pub id: u32,
}

/// Buffers of the build, kept by the tree so that [`Octree::rebuild`](super::Octree::rebuild) allocates nothing.
#[derive(Debug, Clone, Default)]
pub(super) struct Scratch {
    pub a: Vec<Item>,
    pub b: Vec<Item>,
    pub codes: Vec<u8>,
}
