//! # Grids mapped row by row
//!
//! A function evaluated at every point of a grid (x fastest, then y, then z), rows of M + 1
//! points in parallel (rayon, feature `parallel`; in order without it), one clone of the
//! caller's state per task, `row_done` called after every row (a front end's progress bar).
//!
//! ## References
//! - Thesis Algorithm 6.2 (the grid).

use cdpr_workspace::Grid;
use nalgebra::Vector3;

/// `f(state, point)` at every point of `grid`, in grid order.
pub fn map_rows<S, T, F>(
    state: &S,
    grid: &Grid,
    dim: usize,
    row_done: &(dyn Fn() + Sync),
    f: F,
) -> Vec<T>
where
    S: Clone + Send + Sync,
    T: Send + Copy + Default,
    F: Fn(&mut S, Vector3<f64>) -> T + Sync,
{
    map_row_blocks(state, grid, dim, row_done, |s, points, out| {
        for (o, &u) in out.iter_mut().zip(points) {
            *o = f(s, u);
        }
    })
}

/// [`map_rows`] a row at a time: `f(state, points, values)` fills the values of one row's
/// points (`T::default()` on entry).
pub fn map_row_blocks<S, T, F>(
    state: &S,
    grid: &Grid,
    dim: usize,
    row_done: &(dyn Fn() + Sync),
    f: F,
) -> Vec<T>
where
    S: Clone + Send + Sync,
    T: Send + Copy + Default,
    F: Fn(&mut S, &[Vector3<f64>], &mut [T]) + Sync,
{
    let row = grid.points_per_axis();
    let total = grid.point_count(dim);
    let one_row = |(s, points): &mut (S, Vec<Vector3<f64>>), r: usize| -> Vec<T> {
        points.clear();
        points.extend((r * row..((r + 1) * row).min(total)).map(|idx| grid.point(dim, idx)));
        let mut out = vec![T::default(); points.len()];
        f(s, points, &mut out);
        row_done();
        out
    };
    #[cfg(feature = "parallel")]
    let rows: Vec<Vec<T>> = {
        use rayon::prelude::*;
        (0..total.div_ceil(row))
            .into_par_iter()
            .map_init(|| (state.clone(), Vec::new()), one_row)
            .collect()
    };
    #[cfg(not(feature = "parallel"))]
    let rows: Vec<Vec<T>> = {
        let mut s = (state.clone(), Vec::new());
        (0..total.div_ceil(row))
            .map(|r| one_row(&mut s, r))
            .collect()
    };
    rows.concat()
}
