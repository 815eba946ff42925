//! # cdpr (Python)
//!
//! The native module `cdpr._cdpr` behind the Python package `cdpr`: a [`model::Robot`] class
//! wrapping a robot file's [`cdpr_io::RobotDescription`], whose methods take numpy arrays of
//! poses, run the crates' algorithms over the batch in parallel (rayon) with the GIL released,
//! and return result objects holding numpy arrays.
//!
//! Boundary rules: bad input (shapes, NaN/inf, unknown names, file errors) raises `ValueError`
//! with the Rust message; a panic is caught ([`std::panic::catch_unwind`]) and raised as
//! `RuntimeError` so that no panic unwinds into the interpreter.

mod arrays;
mod calibration;
mod dynamics;
mod forward;
mod kinematics;
mod model;
mod polytope;
mod requests;
mod robot;
mod sagging;
mod tension;
mod trajectory;
mod workspace;

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use rayon::{ThreadPool, ThreadPoolBuilder};
use std::fmt::Display;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::{Arc, Mutex};

/// A `ValueError` carrying the Rust error's message.
pub(crate) fn value_error(e: impl Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// A count given from Python (`resolution`, `samples`, `max_iterations`): an `int` ≥ 0, a
/// negative one is a `ValueError` naming the argument (not the `OverflowError` of a `usize`
/// conversion).
pub(crate) fn count(value: i64, name: &str) -> PyResult<usize> {
    usize::try_from(value)
        .map_err(|_| value_error(format!("{name} = {value}: expected an integer ≥ 0")))
}

/// Runs `f` and turns a panic into a `RuntimeError` (the last line of defence: library code
/// reports bad input as errors; a panic is a bug, reported as such).
pub(crate) fn guarded<T>(f: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(r) => r,
        Err(payload) => {
            let msg = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".into());
            Err(PyRuntimeError::new_err(format!(
                "internal error in cdpr (please report): {msg}"
            )))
        }
    }
}

/// Batches at least this large run on the rayon pool with the GIL released; smaller ones run on
/// the calling thread (rayon's dispatch costs microseconds, more than a single pose).
pub(crate) const PARALLEL_THRESHOLD: usize = 64;

/// The thread pool of this process. Not rayon's global pool: a process forked after the pool
/// started (`multiprocessing` with the fork start method) has none of its threads, so a
/// child builds its own instead of waiting forever for threads that do not exist.
fn pool() -> Arc<ThreadPool> {
    static POOL: Mutex<Option<(u32, Arc<ThreadPool>)>> = Mutex::new(None);
    let pid = std::process::id();
    let mut slot = POOL.lock().unwrap_or_else(|e| e.into_inner());
    match &*slot {
        Some((p, pool)) if *p == pid => pool.clone(),
        _ => {
            let pool = Arc::new(
                ThreadPoolBuilder::new()
                    .build()
                    .expect("rayon thread pool (RAYON_NUM_THREADS must be a number)"),
            );
            *slot = Some((pid, pool.clone()));
            pool
        }
    }
}

/// Runs `f` on this process's thread pool with the GIL released and panics caught.
pub(crate) fn parallel<T: Send>(
    py: Python<'_>,
    f: impl FnOnce() -> PyResult<T> + Send,
) -> PyResult<T> {
    let pool = pool();
    py.detach(|| pool.install(|| guarded(f)))
}

/// Runs `f` with the GIL released on the thread pool (and panics caught) when the batch is
/// large enough, else on the calling thread.
pub(crate) fn run_batch<T: Send>(
    py: Python<'_>,
    count: usize,
    f: impl FnOnce() -> PyResult<T> + Send,
) -> PyResult<T> {
    if count >= PARALLEL_THRESHOLD {
        parallel(py, f)
    } else {
        guarded(f)
    }
}

/// Poses per rayon task (amortises the task's cost and the per-task state).
const BLOCK: usize = 256;

/// Calls `f(state, k, j, outputs)` for every pose k < `count`, in parallel when the batch is
/// large: `outputs[o]` is the block of rows of output o (width `widths[o]`) that holds pose k
/// at row j. Returns the values of `f` in pose order, or the error of the first failing pose
/// (in pose order). `state` is per task (one `init()` per block), so hot loops do not allocate.
pub(crate) fn map_poses<S, R, E>(
    count: usize,
    widths: &[usize],
    outputs: Vec<&mut [f64]>,
    init: impl Fn() -> S + Sync + Send,
    f: impl Fn(&mut S, usize, usize, &mut [&mut [f64]]) -> Result<R, E> + Sync + Send,
) -> Result<Vec<R>, E>
where
    R: Send,
    E: Send,
{
    use rayon::prelude::*;
    let run = |state: &mut S, (b, mut outs): (usize, Vec<&mut [f64]>)| -> Result<Vec<R>, E> {
        let start = b * BLOCK;
        let end = (start + BLOCK).min(count);
        (start..end)
            .map(|k| f(state, k, k - start, &mut outs))
            .collect()
    };
    if count <= BLOCK {
        // One block: no splitting, no pool.
        return run(&mut init(), (0, outputs));
    }
    let mut chunks: Vec<_> = outputs
        .into_iter()
        .zip(widths)
        .map(|(o, &w)| o.chunks_mut((BLOCK * w).max(1)))
        .collect();
    let blocks: Vec<Vec<&mut [f64]>> = (0..count.div_ceil(BLOCK))
        .map(|_| {
            chunks
                .iter_mut()
                .map(|c| c.next().unwrap_or_default())
                .collect()
        })
        .collect();
    let per_block: Vec<Result<Vec<R>, E>> = if count >= PARALLEL_THRESHOLD {
        blocks
            .into_par_iter()
            .enumerate()
            .map_init(&init, run)
            .collect()
    } else {
        let mut state = init();
        blocks
            .into_iter()
            .enumerate()
            .map(|x| run(&mut state, x))
            .collect()
    };
    let mut out = Vec::with_capacity(count);
    for r in per_block {
        out.extend(r?);
    }
    Ok(out)
}

/// The row `j` of width `w` of a block.
#[inline]
pub(crate) fn row(block: &mut [f64], j: usize, w: usize) -> &mut [f64] {
    &mut block[j * w..(j + 1) * w]
}

/// The number of threads batches run on (``RAYON_NUM_THREADS``, default one per core).
#[pyfunction]
fn thread_count() -> usize {
    pool().current_num_threads()
}

#[pymodule]
fn _cdpr(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<model::Robot>()?;
    m.add_class::<kinematics::KinematicsResult>()?;
    m.add_class::<forward::ForwardResult>()?;
    m.add_class::<tension::TensionResult>()?;
    m.add_class::<polytope::CapacityResult>()?;
    m.add_class::<polytope::IsotropicResult>()?;
    m.add_class::<polytope::StiffnessResult>()?;
    m.add_class::<workspace::WorkspaceResult>()?;
    m.add_class::<trajectory::TrajectoryResult>()?;
    m.add_class::<sagging::SaggingResult>()?;
    m.add_class::<trajectory::TimedTrajectoryResult>()?;
    m.add_class::<dynamics::SimulationResult>()?;
    m.add_function(wrap_pyfunction!(thread_count, m)?)?;
    m.add_function(wrap_pyfunction!(calibration::calibrate, m)?)?;
    m.add_function(wrap_pyfunction!(kinematics::_ik_reference_loop, m)?)?;
    m.add_function(wrap_pyfunction!(kinematics::_ik_reference_buffers, m)?)?;
    m.add_class::<kinematics::IkBuffers>()?;
    m.add("METHODS", tension::method_names())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
