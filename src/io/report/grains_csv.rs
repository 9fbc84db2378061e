//! The grain table, `grains.csv`: one row per packed grain, its shape, place and
//! crystal orientation, to 17 significant digits.

use crate::contact::{ellipse_angle, Dimension};
use crate::io::cases::format_17;
use crate::packing::PackedGrain;
use crate::scene::quaternion_to_euler;
use rayon::prelude::*;
use std::io::{self, Write};

#[cfg(doc)]
use super::crystal_orientations;

/// File name of the grain table.
pub const GRAINS_CSV: &str = "grains.csv";

/// Columns of `grains.csv` for a 3D scene: id, phase index, centre, semi-axes, unit
/// quaternion `[w, x, y, z]` (Hamilton; semi-axis `k` along column `k` of its rotation
/// matrix).
pub const GRAINS_HEADER: [&str; 12] = [
    "id", "phase", "x", "y", "z", "a1", "a2", "a3", "qw", "qx", "qy", "qz",
];

/// Columns of `grains.csv` for a 2D scene: id, phase index, centre in the plane,
/// semi-axes, and the angle in degrees, in `(−90, 90]`, of the first semi-axis from x,
/// counter-clockwise ([`ellipse_angle`]).
pub const GRAINS_HEADER_2D: [&str; 7] = ["id", "phase", "x", "y", "a1", "a2", "angle"];

/// Columns appended to `grains.csv` (after [`GRAINS_HEADER`]): the grain's crystal
/// orientation in the sample frame, as a unit quaternion `o0..o3` (scalar first,
/// `o0 ≥ 0`, DAMASK's convention: see [`crate::scene::euler_to_quaternion`]) and as
/// Bunge Euler angles in degrees.
pub const CRYSTAL_HEADER: [&str; 7] = ["o0", "o1", "o2", "o3", "phi1", "Phi", "phi2"];

/// The shape columns of `grains.csv` in `dimension`: [`GRAINS_HEADER`] or
/// [`GRAINS_HEADER_2D`].
pub fn grains_header(dimension: Dimension) -> &'static [&'static str] {
    match dimension {
        Dimension::Two => &GRAINS_HEADER_2D,
        Dimension::Three => &GRAINS_HEADER,
    }
}

/// The values of a grain's shape columns after `id` and `phase`: centre, semi-axes and
/// quaternion in 3D; in 2D the ellipse in the plane (the embedded grain's `z` and third
/// semi-axis dropped, its quaternion about z as an angle in degrees).
fn shape_values(g: &PackedGrain, dimension: Dimension) -> Vec<f64> {
    match dimension {
        Dimension::Two => vec![
            g.centre[0],
            g.centre[1],
            g.semi_axes[0],
            g.semi_axes[1],
            ellipse_angle(g.quaternion).to_degrees(),
        ],
        Dimension::Three => g
            .centre
            .iter()
            .chain(&g.semi_axes)
            .chain(&g.quaternion)
            .copied()
            .collect(),
    }
}

/// Writes the grain table: [`grains_header`] then [`CRYSTAL_HEADER`], one row per grain
/// (`crystals[i]` for `grains[i]`, from [`crystal_orientations`]) with integers for `id`
/// and `phase` and 17 significant digits ([`format_17`]) for the rest, which read back
/// to the same doubles. Rows are formatted in parallel, `ROWS_PER_BATCH` at a time,
/// and written in order: the same bytes as one row after the other.
pub fn write_grains_csv(
    out: &mut dyn Write,
    grains: &[PackedGrain],
    crystals: &[[f64; 4]],
    dimension: Dimension,
) -> io::Result<()> {
    let mut writer = csv::Writer::from_writer(&mut *out);
    let header = grains_header(dimension);
    writer.write_record(header.iter().chain(&CRYSTAL_HEADER))?;
    writer.flush()?;
    drop(writer);
    let batches = grains
        .chunks(ROWS_PER_BATCH)
        .zip(crystals.chunks(ROWS_PER_BATCH));
    for (grains, crystals) in batches {
        let parts = (grains.par_chunks(ROWS_PER_TASK))
            .zip(crystals.par_chunks(ROWS_PER_TASK))
            .map(|(g, c)| grain_rows(g, c, dimension))
            .collect::<io::Result<Vec<Vec<u8>>>>()?;
        for part in &parts {
            out.write_all(part)?;
        }
    }
    out.flush()
}

/// Grains formatted between two writes of [`write_grains_csv`]: bounds the formatted
/// rows held (about 380 bytes a grain in 3D) whatever the scene's size.
const ROWS_PER_BATCH: usize = 1 << 16;
/// Grains one rayon task of [`write_grains_csv`] formats.
const ROWS_PER_TASK: usize = 1 << 11;

/// The rows of `grains` (without the header), as [`write_grains_csv`] writes them.
fn grain_rows(
    grains: &[PackedGrain],
    crystals: &[[f64; 4]],
    dimension: Dimension,
) -> io::Result<Vec<u8>> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    let columns = grains_header(dimension).len() + CRYSTAL_HEADER.len();
    let mut row = Vec::with_capacity(columns);
    for (g, o) in grains.iter().zip(crystals) {
        row.clear();
        row.push(g.id.to_string());
        row.push(g.phase.to_string());
        let euler = quaternion_to_euler(*o).map(f64::to_degrees);
        row.extend(
            shape_values(g, dimension)
                .iter()
                .chain(o)
                .chain(&euler)
                .map(|&v| format_17(v)),
        );
        writer.write_record(&row)?;
    }
    writer.into_inner().map_err(|e| e.into_error())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grains_csv_has_the_header_and_17_digit_values_that_read_back_exactly() {
        let grain = PackedGrain {
            id: 0,
            phase: 1,
            centre: [0.1, 2.0 / 3.0, 1e-300],
            semi_axes: [3.0, 1.5, 1.5],
            quaternion: [0.5f64.sqrt(), 0.0, 0.0, -(0.5f64.sqrt())],
        };
        let mut out = Vec::new();
        let crystal = [0.5, 0.5, -0.5, 0.5];
        write_grains_csv(&mut out, &[grain], &[crystal], Dimension::Three).unwrap();
        let text = String::from_utf8(out).unwrap();
        let mut lines = text.lines();
        assert_eq!(
            lines.next(),
            Some("id,phase,x,y,z,a1,a2,a3,qw,qx,qy,qz,o0,o1,o2,o3,phi1,Phi,phi2")
        );
        let row: Vec<&str> = lines.next().unwrap().split(',').collect();
        assert_eq!(&row[..2], ["0", "1"]);
        let values: Vec<f64> = row[2..].iter().map(|v| v.parse().unwrap()).collect();
        let want: Vec<f64> = grain
            .centre
            .iter()
            .chain(&grain.semi_axes)
            .chain(&grain.quaternion)
            .chain(&crystal)
            .copied()
            .collect();
        assert_eq!(values[..14], want[..]);
        assert_eq!(row[3], "6.6666666666666663e-1");
        assert_eq!(lines.next(), None);
    }

    #[test]
    fn grains_csv_of_ellipses_has_the_plane_columns_and_the_angle_in_degrees() {
        use crate::contact::{ellipse_quaternion, ellipse_semi_axes};
        // 2.0 rad is past a quarter turn: the same ellipse as 2 − π.
        let grains = [0.3, 2.0].map(|theta| PackedGrain {
            id: 0,
            phase: 0,
            centre: [1.5, 2.5, 5.0],
            semi_axes: ellipse_semi_axes(2.0, 0.5),
            quaternion: ellipse_quaternion(theta),
        });
        let mut out = Vec::new();
        let crystal = [1.0, 0.0, 0.0, 0.0];
        write_grains_csv(&mut out, &grains, &[crystal; 2], Dimension::Two).unwrap();
        let text = String::from_utf8(out).unwrap();
        let mut lines = text.lines();
        assert_eq!(
            lines.next(),
            Some("id,phase,x,y,a1,a2,angle,o0,o1,o2,o3,phi1,Phi,phi2")
        );
        for want in [0.3, 2.0 - std::f64::consts::PI] {
            let row: Vec<f64> = lines
                .next()
                .unwrap()
                .split(',')
                .map(|v| v.parse().unwrap())
                .collect();
            assert_eq!(row[2..6], [1.5, 2.5, 2.0, 0.5]);
            // sin_cos, atan2 and the conversion to degrees: a few ε of 180°.
            assert!((row[6] - want.to_degrees()).abs() < 1e-12, "{}", row[6]);
            assert_eq!(row[7..11], crystal);
        }
        assert_eq!(lines.next(), None);
    }
}
