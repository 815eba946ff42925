//! # Parallel or sequential evaluation
//!
//! Grids, boundary meshes and orientation sweeps evaluate independent points. With the
//! `parallel` feature (on by default) they run on rayon's thread pool; without it, on the
//! calling thread, and the crate does not depend on rayon. Every evaluation depends on its own
//! point only and results are collected in input order, so both builds give identical results.

#[cfg(feature = "parallel")]
use rayon::prelude::*;

/// Number of threads the evaluations are spread over (rayon's pool; 1 without `parallel`).
pub(crate) fn current_num_threads() -> usize {
    #[cfg(feature = "parallel")]
    {
        rayon::current_num_threads().max(1)
    }
    #[cfg(not(feature = "parallel"))]
    {
        1
    }
}

/// Index of the pool thread running the caller (`None` outside the pool; always `Some(0)`
/// without `parallel`).
pub(crate) fn current_thread_index() -> Option<usize> {
    #[cfg(feature = "parallel")]
    {
        rayon::current_thread_index()
    }
    #[cfg(not(feature = "parallel"))]
    {
        Some(0)
    }
}

/// Calls `f(task, chunk)` for each `len`-long chunk of `out` (the last may be shorter), chunk
/// `task` starting at index `task * len`.
pub(crate) fn for_each_chunk_mut<T, F>(out: &mut [T], len: usize, f: F)
where
    T: Send,
    F: Fn(usize, &mut [T]) + Sync + Send,
{
    #[cfg(feature = "parallel")]
    out.par_chunks_mut(len)
        .enumerate()
        .for_each(|(task, chunk)| f(task, chunk));
    #[cfg(not(feature = "parallel"))]
    out.chunks_mut(len)
        .enumerate()
        .for_each(|(task, chunk)| f(task, chunk));
}

/// `(0..n).map(|i| f(state, i))` collected in order, with a state made by `init` for each task
/// (rayon's `map_init`; a single state without `parallel`).
pub(crate) fn map_init<S, R, I, F>(n: usize, init: I, f: F) -> Vec<R>
where
    R: Send,
    I: Fn() -> S + Sync + Send,
    F: Fn(&mut S, usize) -> R + Sync + Send,
{
    #[cfg(feature = "parallel")]
    {
        (0..n).into_par_iter().map_init(init, f).collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        let mut state = init();
        (0..n).map(|i| f(&mut state, i)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chunks_cover_the_slice_once_with_their_offsets() {
        let mut out = vec![0usize; 103];
        for_each_chunk_mut(&mut out, 10, |task, chunk| {
            for (k, v) in chunk.iter_mut().enumerate() {
                *v += task * 10 + k + 1;
            }
        });
        assert_eq!(out, (1..=103).collect::<Vec<_>>());
    }

    #[test]
    fn map_init_keeps_the_input_order() {
        let squares = map_init(
            1000,
            || 0usize,
            |calls, i| {
                *calls += 1;
                i * i
            },
        );
        assert_eq!(squares, (0..1000).map(|i| i * i).collect::<Vec<_>>());
        assert!(current_num_threads() >= 1);
    }
}
