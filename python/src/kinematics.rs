//! # Inverse kinematics over a batch
//!
//! Per pose, every cable's length l_i, unit vector ℓ^i / l_i and attachment point, and the
//! DOF × n wrench matrix W with W t + w_ext = 0 (thesis eqs. (6.2)–(6.4), (6.11); the
//! `cdpr kinematics` command at one pose).

use crate::arrays::{Rows, batch_shape, out_array, to_numpy, writable, zeros};
use crate::model::Robot;
use crate::requests::{api_error, api_robot, matrix, points3};
use crate::{map_poses, row, run_batch, value_error};
use cdpr_api::KinematicsRequest;
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
///
/// Pass a result back as ``out=`` to have the next batch of the same size written into its
/// arrays (no new memory: filling fresh pages costs more than the kinematics itself for large
/// batches).
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

/// Output elements from which `inverse_kinematics` allocates its arrays in Rust (1 MiB).
const LARGE_OUTPUT: usize = 1 << 17;

/// Parses pose k (already checked finite) for `robot`.
pub fn pose_at(robot: &Robot, q: &[f64], k: usize) -> Result<Pose, String> {
    Pose::from_coordinates(robot.motion_pattern(), q).map_err(|e| format!("poses[{k}]: {e}"))
}

pub fn inverse_kinematics(
    robot: &Robot,
    py: Python<'_>,
    poses: &Bound<'_, PyAny>,
    out: Option<Bound<'_, KinematicsResult>>,
) -> PyResult<Py<KinematicsResult>> {
    let geo = robot.geometry();
    let (dof, n) = (geo.dof(), geo.cable_count());
    let rows = Rows::new(poses, dof, "poses", robot.pose_hint())?;
    let count = rows.count;
    let data = rows.array.data();
    if rows.single && out.is_none() {
        let request = KinematicsRequest {
            robot: api_robot(robot),
            pose: data.to_vec(),
        };
        return kinematics_at(py, &request);
    }
    let widths = [n, 3 * n, dof * n, 3 * n];
    let shape = |rest: &[usize]| batch_shape(rows.single, count, rest);
    let shapes = [
        shape(&[n]),
        shape(&[n, 3]),
        shape(&[dof, n]),
        shape(&[n, 3]),
    ];
    let fill = |outs: Vec<&mut [f64]>| {
        run_batch(py, count, || {
            map_poses(
                count,
                &widths,
                outs,
                || (PoseKinematics::for_robot(geo), DMatrix::zeros(dof, n)),
                |state, k, j, blocks| {
                    ik_pose(robot, state, &data[k * dof..(k + 1) * dof], (k, j), blocks)
                },
            )
            .map_err(value_error)
        })
    };
    if let Some(out) = out {
        fill_out(py, &out, &shapes, fill)?;
        return Ok(out.unbind());
    }
    // Large outputs: Rust buffers handed to numpy without a copy, rather than `numpy.zeros`.
    // numpy advises transparent huge pages for large arrays, and on a first touch the kernel's
    // huge-page allocation (compaction, 2 MB clears) cost 20–25 % more CPU than 4 KiB pages in
    // `python/benchmarks/bench.py` (10⁶ poses, 832 MB of output). Small outputs: `numpy.zeros`
    // (from numpy's cache; wrapping a Vec costs a Python object per array, about 1 µs per call).
    let total: usize = shapes.iter().map(|s| s.iter().product::<usize>()).sum();
    let [lengths, unit_vectors, wrench_matrix, attachment_points] = if total >= LARGE_OUTPUT {
        let mut buffers = shapes.clone().map(|s| vec![0.0; s.iter().product()]);
        fill(buffers.iter_mut().map(Vec::as_mut_slice).collect())?;
        let mut it = buffers.into_iter().zip(&shapes);
        [(); 4].map(|()| {
            let (b, s) = it.next().expect("four outputs");
            to_numpy(py, s, b).unbind()
        })
    } else {
        let mut arrays = shapes.map(|s| zeros(py, &s));
        fill(writable(&mut arrays))?;
        arrays.map(Bound::unbind)
    };
    Py::new(
        py,
        KinematicsResult {
            lengths,
            unit_vectors,
            wrench_matrix,
            attachment_points,
        },
    )
}

/// Inverse kinematics of pose k (coordinates `q`) into row j of the four outputs (lengths, unit
/// vectors, wrench matrix, attachment points).
fn ik_pose(
    robot: &Robot,
    (kin, w): &mut (PoseKinematics, DMatrix<f64>),
    q: &[f64],
    (k, j): (usize, usize),
    blocks: &mut [&mut [f64]],
) -> Result<(), String> {
    let (dof, n) = (robot.geometry().dof(), robot.geometry().cable_count());
    let pose = pose_at(robot, q, k)?;
    robot
        .geometry()
        .update_kinematics(&pose, kin)
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
    Ok(())
}

/// Runs `fill` on the arrays of an earlier result (``out=``), checked against `shapes`.
fn fill_out<R>(
    py: Python<'_>,
    out: &Bound<'_, KinematicsResult>,
    shapes: &[Vec<usize>; 4],
    fill: impl FnOnce(Vec<&mut [f64]>) -> PyResult<R>,
) -> PyResult<()> {
    let result = out.get();
    let names = [
        "lengths",
        "unit_vectors",
        "wrench_matrix",
        "attachment_points",
    ];
    let arrays = [
        result.lengths.bind(py),
        result.unit_vectors.bind(py),
        result.wrench_matrix.bind(py),
        result.attachment_points.bind(py),
    ];
    let mut borrowed = Vec::with_capacity(4);
    for ((a, s), name) in arrays.iter().zip(shapes).zip(names) {
        borrowed.push(out_array(a, s, name)?);
    }
    let outs = borrowed
        .iter_mut()
        .map(|b| b.as_slice_mut().expect("checked C-contiguous"))
        .collect();
    fill(outs)?;
    drop(borrowed);
    Ok(())
}

/// One pose without ``out=``: the `cdpr kinematics` request and its report.
fn kinematics_at(py: Python<'_>, request: &KinematicsRequest) -> PyResult<Py<KinematicsResult>> {
    let r = request.run().map_err(api_error)?;
    let n = r.lengths.len();
    Py::new(
        py,
        KinematicsResult {
            lengths: to_numpy(py, &[n], r.lengths).unbind(),
            unit_vectors: points3(py, &r.unit_vectors).unbind(),
            wrench_matrix: matrix(py, &r.wrench_matrix, n).unbind(),
            attachment_points: points3(py, &r.attachment_points).unbind(),
        },
    )
}

/// Output buffers of [`_ik_reference_loop`], allocated and written once (every page touched)
/// by `_ik_reference_buffers`, so that the loop's clock and the caller's CPU clock see no page
/// faults: the reference of a call with ``out=``.
#[pyclass(module = "cdpr._cdpr")]
pub struct IkBuffers {
    buffers: [Vec<f64>; 4],
}

/// Buffers for `count` poses of `robot`, every page touched.
#[pyfunction]
pub fn _ik_reference_buffers(robot: &Robot, count: usize) -> IkBuffers {
    let geo = robot.geometry();
    let (dof, n) = (geo.dof(), geo.cable_count());
    IkBuffers {
        buffers: [n, 3 * n, dof * n, 3 * n].map(|w| vec![1.0; count * w]),
    }
}

/// The plain Rust loop that `inverse_kinematics` runs for a batch, on the calling thread with
/// no numpy or Python in it: the reference of the benchmark (`python/benchmarks/bench.py`) in
/// the same process and conditions. Returns seconds.
///
/// Without `buffers` the four outputs are allocated inside the timed region (fresh memory, as a
/// call without ``out=`` gets) and freed after it (as the benchmark keeps the package's result
/// alive until its clock stops). With `buffers` (from `_ik_reference_buffers`) the loop writes
/// into memory already touched, as a call with ``out=`` does.
#[pyfunction]
#[pyo3(signature = (robot, poses, buffers=None))]
pub fn _ik_reference_loop(
    py: Python<'_>,
    robot: &Robot,
    poses: &Bound<'_, PyAny>,
    buffers: Option<&Bound<'_, IkBuffers>>,
) -> PyResult<f64> {
    let geo = robot.geometry();
    let (dof, n) = (geo.dof(), geo.cable_count());
    let rows = Rows::new(poses, dof, "poses", robot.pose_hint())?;
    let data = rows.array.data();
    let count = rows.count;
    let mut warm = buffers.map(|b| b.borrow_mut());
    if let Some(b) = &warm
        && b.buffers[0].len() != count * n
    {
        return Err(value_error("buffers: made for another number of poses"));
    }
    let warm = warm.as_deref_mut().map(|b| &mut b.buffers);
    py.detach(|| {
        let start = std::time::Instant::now();
        let mut fresh = None;
        let [l, u, wm, a] = match warm {
            Some(b) => b,
            None => fresh.insert([n, 3 * n, dof * n, 3 * n].map(|w| vec![0.0; count * w])),
        };
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
        let elapsed = start.elapsed().as_secs_f64();
        drop(fresh);
        Ok(elapsed)
    })
}
