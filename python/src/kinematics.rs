//! # Inverse kinematics over a batch
//!
//! Per pose, every cable's length l_i, unit vector ℓ^i / l_i and attachment point, and the
//! DOF × n wrench matrix W with W t + w_ext = 0 (thesis eqs. (6.2)–(6.4), (6.11); the
//! `cdpr kinematics` command at one pose).

use crate::arrays::{Rows, batch_shape, writable, zeros};
use crate::robot::Robot;
use crate::{map_poses, row, run_batch, value_error};
use cdpr_kinematics::{Pose, PoseKinematics};
use nalgebra::DMatrix;
use numpy::PyArrayDyn;
use pyo3::prelude::*;

/// The inverse kinematics of a batch of poses.
///
/// ``lengths`` (N, n) in m; ``unit_vectors`` (N, n, 3): unit vector of each cable from its
/// platform attachment towards its frame anchor (z = 0 for planar robots);
/// ``wrench_matrix`` (N, DOF, n): W with W t + w_ext = 0; ``attachment_points`` (N, n, 3):
/// attachments in base coordinates (m). One pose in gives the same without the leading axis.
#[pyclass(module = "cdpr", frozen, get_all)]
pub struct KinematicsResult {
    pub lengths: Py<PyArrayDyn<f64>>,
    pub unit_vectors: Py<PyArrayDyn<f64>>,
    pub wrench_matrix: Py<PyArrayDyn<f64>>,
    pub attachment_points: Py<PyArrayDyn<f64>>,
}

#[pymethods]
impl KinematicsResult {
    fn __repr__(&self, py: Python<'_>) -> String {
        format!(
            "KinematicsResult(lengths.shape={:?})",
            numpy::PyUntypedArrayMethods::shape(self.lengths.bind(py))
        )
    }
}

/// Parses pose k (already checked finite) for `robot`.
pub fn pose_at(robot: &Robot, q: &[f64], k: usize) -> Result<Pose, String> {
    Pose::from_coordinates(robot.motion_pattern(), q).map_err(|e| format!("poses[{k}]: {e}"))
}

pub fn inverse_kinematics(
    robot: &Robot,
    py: Python<'_>,
    poses: &Bound<'_, PyAny>,
) -> PyResult<KinematicsResult> {
    let geo = robot.geometry();
    let (dof, n) = (geo.dof(), geo.cable_count());
    let rows = Rows::new(poses, dof, "poses", robot.pose_hint())?;
    let count = rows.count;
    let data = rows.array.data();
    let widths = [n, 3 * n, dof * n, 3 * n];
    let shape = |rest: &[usize]| batch_shape(rows.single, count, rest);
    let mut arrays = [
        zeros(py, &shape(&[n])),
        zeros(py, &shape(&[n, 3])),
        zeros(py, &shape(&[dof, n])),
        zeros(py, &shape(&[n, 3])),
    ];
    let outs = writable(&mut arrays);
    run_batch(py, count, || {
        map_poses(
            count,
            &widths,
            outs,
            || (PoseKinematics::for_robot(geo), DMatrix::zeros(dof, n)),
            |(kin, w), k, j, blocks| {
                let pose = pose_at(robot, &data[k * dof..(k + 1) * dof], k)?;
                geo.update_kinematics(&pose, kin)
                    .map_err(|e| format!("poses[{k}]: {e}"))?;
                kin.write_wrench_matrix(w);
                let [l, u, wm, a] = blocks else {
                    unreachable!("four outputs")
                };
                let (l, u) = (row(l, j, n), row(u, j, 3 * n));
                for (i, c) in kin.cables().iter().enumerate() {
                    l[i] = c.length;
                    u[3 * i..3 * i + 3].copy_from_slice(c.unit.as_slice());
                }
                let a = row(a, j, 3 * n);
                for (i, c) in kin.cables().iter().enumerate() {
                    a[3 * i..3 * i + 3].copy_from_slice(c.attachment_point.as_slice());
                }
                let wm = row(wm, j, dof * n);
                for r in 0..dof {
                    for c in 0..n {
                        wm[r * n + c] = w[(r, c)];
                    }
                }
                Ok::<(), String>(())
            },
        )
        .map_err(value_error)
    })?;
    let [lengths, unit_vectors, wrench_matrix, attachment_points] = arrays.map(Bound::unbind);
    Ok(KinematicsResult {
        lengths,
        unit_vectors,
        wrench_matrix,
        attachment_points,
    })
}

/// The plain Rust loop that `inverse_kinematics` runs for a batch, on the calling thread with
/// fresh output buffers and no numpy or Python in it: the reference of the benchmark
/// (`python/benchmarks/bench.py`) in the same process and conditions. Returns seconds.
#[pyfunction]
pub fn _ik_reference_loop(
    py: Python<'_>,
    robot: &Robot,
    poses: &Bound<'_, PyAny>,
) -> PyResult<f64> {
    let geo = robot.geometry();
    let (dof, n) = (geo.dof(), geo.cable_count());
    let rows = Rows::new(poses, dof, "poses", robot.pose_hint())?;
    let data = rows.array.data();
    let count = rows.count;
    py.detach(|| {
        let start = std::time::Instant::now();
        let (mut l, mut u, mut wm, mut a) = (
            vec![0.0; count * n],
            vec![0.0; count * 3 * n],
            vec![0.0; count * dof * n],
            vec![0.0; count * 3 * n],
        );
        let mut kin = PoseKinematics::for_robot(geo);
        let mut w = DMatrix::zeros(dof, n);
        for k in 0..count {
            let pose = pose_at(robot, &data[k * dof..(k + 1) * dof], k).map_err(value_error)?;
            geo.update_kinematics(&pose, &mut kin)
                .map_err(value_error)?;
            kin.write_wrench_matrix(&mut w);
            for (i, c) in kin.cables().iter().enumerate() {
                l[k * n + i] = c.length;
                u[3 * (k * n + i)..3 * (k * n + i) + 3].copy_from_slice(c.unit.as_slice());
                a[3 * (k * n + i)..3 * (k * n + i) + 3]
                    .copy_from_slice(c.attachment_point.as_slice());
            }
            for r in 0..dof {
                for c in 0..n {
                    wm[k * dof * n + r * n + c] = w[(r, c)];
                }
            }
        }
        std::hint::black_box((&l, &u, &wm, &a));
        Ok(start.elapsed().as_secs_f64())
    })
}
