//! The narrow phase over numpy arrays: `r12` (n, 3), `q1` and `q2` (n, 6), C-contiguous
//! float64 (the Python wrapper in `grainpack/__init__.py` converts and checks shapes);
//! or ellipses, `r12` (n, 2) and 2×2 forms (n, 3), answered as the embedded pairs
//! (`embed_pair`), with errors naming the 2D entries.
//!
//! Every function computes all rows with the GIL released, then reports the first row
//! that has no answer as an exception naming it (see `row_error`).

use grainpack::contact::{
    contact_functions, contact_geometry, embed_pair, in_plane_terms, overlaps, Contact,
    ContactError, ContactGeometry, Stop, Sym3, Vec3,
};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::{PyArithmeticError, PyValueError};
use pyo3::prelude::*;

/// Pairs handed to the batch code at a time: small enough that the copies stay in
/// cache, large enough that the call overhead does not show.
const CHUNK: usize = 4096;

/// The pairs of the three arrays, row by row: ellipsoids, or ellipses when `plane`.
struct Pairs<'a> {
    r12: &'a [f64],
    q1: &'a [f64],
    q2: &'a [f64],
    plane: bool,
}

impl Pairs<'_> {
    fn len(&self) -> usize {
        self.r12.len() / if self.plane { 2 } else { 3 }
    }

    /// Row `i`, a 2D row as the pair it embeds as.
    fn get(&self, i: usize) -> (Vec3, Sym3, Sym3) {
        if self.plane {
            let r = [self.r12[2 * i], self.r12[2 * i + 1]];
            let form = |q: &[f64]| -> [f64; 3] { q[3 * i..3 * i + 3].try_into().expect("3") };
            return embed_pair(&r, &form(self.q1), &form(self.q2));
        }
        let r: Vec3 = self.r12[3 * i..3 * i + 3].try_into().expect("3 columns");
        let q1: Sym3 = self.q1[6 * i..6 * i + 6].try_into().expect("6 columns");
        let q2: Sym3 = self.q2[6 * i..6 * i + 6].try_into().expect("6 columns");
        (r, q1, q2)
    }

    /// An error about row `i`'s (embedded) pair, naming the entries as given.
    fn restated(&self, i: usize, e: ContactError) -> (usize, ContactError) {
        if !self.plane {
            return (i, e);
        }
        let form = |q: &[f64]| -> [f64; 3] { q[3 * i..3 * i + 3].try_into().expect("3") };
        (i, in_plane_terms(e, &form(self.q1), &form(self.q2)))
    }

    /// `f` of every row, or the first row without an answer and its error.
    fn each<T>(
        &self,
        f: impl Fn(&Vec3, &Sym3, &Sym3) -> Result<T, ContactError>,
    ) -> Result<Vec<T>, (usize, ContactError)> {
        (0..self.len())
            .map(|i| {
                let (r, a, b) = self.get(i);
                f(&r, &a, &b).map_err(|e| self.restated(i, e))
            })
            .collect()
    }
}

/// Checks the shapes (the wrapper already did; this keeps the native functions safe
/// when called directly) and borrows the rows.
fn pairs<'a>(
    r12: &'a PyReadonlyArray2<'_, f64>,
    q1: &'a PyReadonlyArray2<'_, f64>,
    q2: &'a PyReadonlyArray2<'_, f64>,
) -> PyResult<Pairs<'a>> {
    let n = r12.shape()[0];
    // Ellipses when the forms have 3 columns (r12 must then have 2).
    let plane = q1.shape().get(1) == Some(&3);
    let (r_cols, q_cols) = if plane { (2, 3) } else { (3, 6) };
    for (name, a, cols) in [("r12", r12, r_cols), ("q1", q1, q_cols), ("q2", q2, q_cols)] {
        if a.shape() != [n, cols] {
            return Err(PyValueError::new_err(format!(
                "{name} has shape {:?}, expected ({n}, {cols})",
                a.shape()
            )));
        }
    }
    let slice = |name: &str, a: &'a PyReadonlyArray2<'_, f64>| {
        a.as_slice()
            .map_err(|_| PyValueError::new_err(format!("{name} is not C-contiguous")))
    };
    Ok(Pairs {
        r12: slice("r12", r12)?,
        q1: slice("q1", q1)?,
        q2: slice("q2", q2)?,
        plane,
    })
}

/// The first row without an answer, as the exception to raise: `ValueError` for
/// invalid input (the library's message, which names `r12`, `q1` or `q2` and the
/// value), `ArithmeticError` when the solver ran out of iterations or overflowed.
fn row_error(row: usize, error: &ContactError) -> PyErr {
    let message = format!("row {row}: {error}");
    match error {
        ContactError::NotConverged { .. } | ContactError::Overflow { .. } => {
            PyArithmeticError::new_err(message)
        }
        _ => PyValueError::new_err(message),
    }
}

/// μ² and λ of every row with the batch (eight-lane) code, or the first bad row.
fn contact_rows(p: &Pairs) -> Result<(Vec<f64>, Vec<f64>), (usize, ContactError)> {
    let n = p.len();
    let (mut mu2, mut lambda) = (Vec::with_capacity(n), Vec::with_capacity(n));
    let mut chunk = Vec::with_capacity(CHUNK.min(n));
    for start in (0..n).step_by(CHUNK) {
        chunk.clear();
        chunk.extend((start..n.min(start + CHUNK)).map(|i| p.get(i)));
        for (k, result) in contact_functions(&chunk).into_iter().enumerate() {
            let c: Contact = result.map_err(|e| p.restated(start + k, e))?;
            if c.stop == Stop::MaxIterations {
                let iterations = c.iterations;
                return Err((start + k, ContactError::NotConverged { iterations }));
            }
            mu2.push(c.mu2);
            lambda.push(c.lambda);
        }
    }
    Ok((mu2, lambda))
}

/// Two float64 columns.
type Column2<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

/// `(mu2, lambda)` of every row: the accurate contact function, eight rows at a time.
#[pyfunction]
pub fn contact_function_rows<'py>(
    py: Python<'py>,
    r12: PyReadonlyArray2<'py, f64>,
    q1: PyReadonlyArray2<'py, f64>,
    q2: PyReadonlyArray2<'py, f64>,
) -> PyResult<Column2<'py>> {
    let p = pairs(&r12, &q1, &q2)?;
    let (mu2, lambda) = py
        .detach(|| contact_rows(&p))
        .map_err(|(row, e)| row_error(row, &e))?;
    Ok((mu2.into_pyarray(py), lambda.into_pyarray(py)))
}

/// Whether each row's ellipsoids overlap (the certified yes/no test).
#[pyfunction]
pub fn overlaps_rows<'py>(
    py: Python<'py>,
    r12: PyReadonlyArray2<'py, f64>,
    q1: PyReadonlyArray2<'py, f64>,
    q2: PyReadonlyArray2<'py, f64>,
) -> PyResult<Bound<'py, PyArray1<bool>>> {
    let p = pairs(&r12, &q1, &q2)?;
    let answers = py
        .detach(|| p.each(overlaps))
        .map_err(|(row, e)| row_error(row, &e))?;
    Ok(answers.into_pyarray(py))
}

type GeometryArrays<'py> = (
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray1<f64>>,
);

/// `(mu2, lambda, point (n, 3), normal (n, 3), gap)` of every row.
#[pyfunction]
pub fn contact_geometry_rows<'py>(
    py: Python<'py>,
    r12: PyReadonlyArray2<'py, f64>,
    q1: PyReadonlyArray2<'py, f64>,
    q2: PyReadonlyArray2<'py, f64>,
) -> PyResult<GeometryArrays<'py>> {
    let p = pairs(&r12, &q1, &q2)?;
    let n = p.len();
    let rows = py
        .detach(|| p.each(contact_geometry))
        .map_err(|(row, e)| row_error(row, &e))?;
    let matrix = |v: Vec<f64>| {
        Array2::from_shape_vec((n, 3), v)
            .expect("3 values per row")
            .into_pyarray(py)
    };
    let column =
        |f: fn(&ContactGeometry) -> f64| rows.iter().map(f).collect::<Vec<f64>>().into_pyarray(py);
    Ok((
        column(|g| g.mu2),
        column(|g| g.lambda),
        matrix(rows.iter().flat_map(|g| g.point).collect()),
        matrix(rows.iter().flat_map(|g| g.normal).collect()),
        column(|g| g.gap),
    ))
}

/// For `python/benches/contact.py`: the seconds one call of the library's batch
/// (`contact_functions`) takes on all the rows at once, already in its own layout, for
/// each of `rounds` rounds: the baseline the Python function is compared with.
#[pyfunction]
pub fn _rust_batch_seconds(
    py: Python<'_>,
    r12: PyReadonlyArray2<'_, f64>,
    q1: PyReadonlyArray2<'_, f64>,
    q2: PyReadonlyArray2<'_, f64>,
    rounds: usize,
) -> PyResult<Vec<f64>> {
    let p = pairs(&r12, &q1, &q2)?;
    let rows: Vec<(Vec3, Sym3, Sym3)> = (0..p.len()).map(|i| p.get(i)).collect();
    Ok(py.detach(|| {
        (0..rounds)
            .map(|_| {
                let started = std::time::Instant::now();
                let answers = contact_functions(&rows);
                let seconds = started.elapsed().as_secs_f64();
                std::hint::black_box(answers);
                seconds
            })
            .collect()
    }))
}
