//! VTK's compressed array layout (`compressor="vtkZLibDataCompressor"`), shared by
//! `rve.vti` and the VTK grain files: the array cut into blocks of equal uncompressed
//! size (the last may be shorter), each an independent zlib stream, behind a `UInt64`
//! header `[blocks, block size, size of a partial last block (0 if full), compressed
//! size of each block]`.

use flate2::write::ZlibEncoder;
use flate2::Compression;
use std::io::{self, Write};

/// One block as its own zlib stream, at zlib's fast level (the arrays are large and
/// mostly repetitive: a higher level saves a few percent for twice the time).
pub(crate) fn compress(block: &[u8]) -> io::Result<Vec<u8>> {
    let mut z = ZlibEncoder::new(Vec::with_capacity(block.len() / 4), Compression::fast());
    z.write_all(block)?;
    z.finish()
}

/// The header's bytes (little-endian `UInt64`) for an array of `total` uncompressed
/// bytes in blocks of `block_bytes`, compressed to `sizes`.
pub(crate) fn header(block_bytes: usize, total: usize, sizes: &[u64]) -> Vec<u8> {
    [
        sizes.len() as u64,
        block_bytes as u64,
        (total % block_bytes) as u64,
    ]
    .iter()
    .chain(sizes)
    .flat_map(|v| v.to_le_bytes())
    .collect()
}
