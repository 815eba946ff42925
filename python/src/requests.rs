//! # Single poses through the requests of `cdpr-api`
//!
//! One pose (or one set of cable lengths) is the command line's case: the Python methods build
//! the same typed request as `cdpr … --json` (`cdpr_api::TensionRequest`, …) from their keyword
//! arguments, run it and turn its report into the Python result, so that Python and the command
//! line share one code path and one answer. Batches stay on the allocation-free loops of the
//! analysis modules.
//!
//! ## References
//! - docs/architecture.md, "Requests and reports" (issue 25).

use crate::arrays::to_numpy;
use crate::model::Robot;
use crate::value_error;
use numpy::PyArrayDyn;
use pyo3::prelude::*;

/// The robot of a request: this robot's description (a copy; one pose costs far more).
pub fn api_robot(robot: &Robot) -> cdpr_api::Robot {
    cdpr_api::Robot::from_description((*robot.desc).clone())
}

/// Rows of a report's matrix (`rows` × `cols`) as a numpy array of that shape.
pub fn matrix<'py>(py: Python<'py>, rows: &[Vec<f64>], cols: usize) -> Bound<'py, PyArrayDyn<f64>> {
    let data: Vec<f64> = rows.iter().flatten().copied().collect();
    to_numpy(py, &[rows.len(), cols], data)
}

/// Points of a report (2 or 3 coordinates each) as an (n, 3) array, z = 0 in the plane.
pub fn points3<'py>(py: Python<'py>, points: &[Vec<f64>]) -> Bound<'py, PyArrayDyn<f64>> {
    let mut data = vec![0.0; 3 * points.len()];
    for (row, p) in data.chunks_mut(3).zip(points) {
        row[..p.len()].copy_from_slice(p);
    }
    to_numpy(py, &[points.len(), 3], data)
}

/// A request's error as the `ValueError` of bad input.
pub fn api_error(e: cdpr_api::ApiError) -> PyErr {
    value_error(e)
}

/// A request's error with the command line's option names (`--box`, `--grid M`, …) spelled as
/// the keyword arguments of the Python call (`names`: pairs of option and keyword, longer options
/// first where one begins another).
pub fn keyword_error(e: cdpr_api::ApiError, names: &[(&str, &str)]) -> PyErr {
    let mut message = e.to_string();
    for (option, keyword) in names {
        message = message.replace(option, keyword);
    }
    value_error(message)
}
