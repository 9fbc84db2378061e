//! `pack`: a scene run by `grainpack::run::run` on a worker thread while the calling
//! thread, with the GIL released between polls, relays progress and watches for Ctrl-C.

use crate::errors::chain;
use crate::packing::PyPacking;
use crate::scene::PyScene;
use grainpack::packing::Progress;
use grainpack::run::{run, RunError, RunOptions};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use std::num::NonZeroUsize;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{channel, Receiver, RecvTimeoutError};
use std::time::{Duration, Instant};

/// How often the calling thread wakes to check for signals (Ctrl-C) while packing.
/// The loop polls its stop flag once per FIRE step, so a KeyboardInterrupt is raised
/// within this plus one step.
const POLL: Duration = Duration::from_millis(50);

/// Shortest time between two progress reports handed to Python (as the CLI's bar).
const PROGRESS_INTERVAL: Duration = Duration::from_millis(100);

/// Packs `scene` (see `grainpack.pack` for the arguments). `progress` is called with
/// `(step, scale, fraction, overlaps)` at most every 0.1 s.
#[pyfunction]
#[pyo3(signature = (scene, seed=None, threads=None, progress=None))]
pub fn pack_scene(
    py: Python<'_>,
    scene: Py<PyScene>,
    seed: Option<u64>,
    threads: Option<usize>,
    progress: Option<Bound<'_, PyAny>>,
) -> PyResult<PyPacking> {
    let threads = match threads {
        None => None,
        Some(n) => Some(NonZeroUsize::new(n).ok_or_else(|| {
            PyValueError::new_err("threads = 0: must be at least 1 (or None: one per core)")
        })?),
    };
    let scene_ref = scene.get();
    let stop = AtomicBool::new(false);
    let (tx, rx) = channel::<Progress>();
    let mut raised: Option<PyErr> = None;
    let outcome = std::thread::scope(|s| {
        let stop = &stop;
        let worker = s.spawn(move || {
            let mut last: Option<Instant> = None;
            let mut report = |p: &Progress| {
                if last.is_none_or(|t| t.elapsed() >= PROGRESS_INTERVAL) {
                    last = Some(Instant::now());
                    let _ = tx.send(*p);
                }
            };
            run(
                &scene_ref.inner,
                RunOptions {
                    seed,
                    threads,
                    progress: Some(&mut report),
                    interrupt: Some(stop),
                    ..RunOptions::default()
                },
            )
        });
        let mut rx = Some(rx);
        loop {
            let (message, back) = wait(py, rx.take().expect("kept between polls"));
            rx = Some(back);
            match message {
                Ok(p) => {
                    if let (Some(callback), None) = (&progress, &raised) {
                        let args = (p.step, p.scale, p.fraction, p.overlaps);
                        if let Err(e) = callback.call1(args) {
                            stop.store(true, Ordering::SeqCst);
                            raised = Some(e);
                        }
                    }
                }
                Err(RecvTimeoutError::Timeout) => {}
                Err(RecvTimeoutError::Disconnected) => break,
            }
            if raised.is_none() {
                if let Err(e) = py.check_signals() {
                    stop.store(true, Ordering::SeqCst);
                    raised = Some(e);
                }
            }
        }
        py.detach(|| worker.join())
    });
    if let Some(e) = raised {
        return Err(e);
    }
    let result = outcome
        .map_err(|_| PyRuntimeError::new_err("the packing thread panicked: this is a bug"))?
        .map_err(|e| run_error(&e))?;
    Ok(PyPacking::new(scene_ref.inner.clone(), result))
}

/// The next progress report, or a timeout after [`POLL`], with the GIL released.
fn wait(
    py: Python<'_>,
    rx: Receiver<Progress>,
) -> (Result<Progress, RecvTimeoutError>, Receiver<Progress>) {
    py.detach(move || (rx.recv_timeout(POLL), rx))
}

/// A failed run as a Python exception, with the CLI's message.
fn run_error(error: &RunError) -> PyErr {
    match error {
        RunError::TooManyThreads { .. } => PyValueError::new_err(chain(error)),
        _ => PyRuntimeError::new_err(chain(error)),
    }
}
