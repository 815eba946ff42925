//! # Batch inverse kinematics: wrench matrices of many poses
//!
//! Grids, trajectories and the Python package need W (eq. (6.11)) for thousands of poses and
//! nothing else. [`Robot::wrench_matrices`] computes, for every pose, the cable vectors
//! ℓ^i = **c**^i − **T ā**^i − **u** (eq. (6.2)), their unit vectors and the columns
//! `[u_i ; a_i × u_i]` (restricted to the motion pattern, Picard, Caro, Plestan & Claveau 2020,
//! eq. (2)) straight into one flat buffer: one DOF × n column-major block per pose (the storage
//! order of `DMatrix`), without the per-cable [`crate::CableState`] records of
//! [`Robot::update_kinematics`]. The arithmetic is the same expression by expression, so every
//! block equals the single-pose `wrench_matrix()` bit for bit (tested), and a pose is rejected
//! (`valid[k] = false`) exactly when `update_kinematics` fails on it (non-finite position,
//! degenerate cable). Robots with pulleys go through `update_kinematics` pose by pose (the same
//! answers; one `PoseKinematics` allocated per call).
//!
//! ## References
//! - Thesis eqs. (6.2)–(6.4), (6.11). Picard, Caro, Plestan & Claveau 2020, eqs. (1)–(2).

use crate::cable_state::DEGENERATE_LENGTH;
#[cfg(target_arch = "x86_64")]
use crate::lanes::Avx2;
use crate::lanes::{F64x4, Portable};
use crate::{KinematicsError, MotionPattern, Pose, PoseKinematics, Robot};
use nalgebra::Vector3;

impl Robot {
    /// W of every pose in `poses` into `out` (`poses.len()` blocks of DOF · n values, each
    /// column-major like `DMatrix::as_slice`); `valid[k]` tells whether pose k has a wrench
    /// matrix (its block is then written; otherwise the block holds no meaningful values). Returns the
    /// number of valid poses; errors only when `out` or `valid` has the wrong length. Allocates
    /// nothing for robots without pulleys.
    ///
    /// ```
    /// use cdpr_kinematics::{Pose, reference_robots::ipanema_like_8};
    /// let robot = ipanema_like_8();
    /// let poses = [Pose::spatial([0.0, 0.0, 1.0].into(), 0.0, 0.0, 0.0),
    ///              Pose::spatial([0.2, -0.1, 0.8].into(), 0.05, 0.0, -0.1)];
    /// let mut w = vec![0.0; poses.len() * 6 * 8];
    /// let mut valid = [false; 2];
    /// assert_eq!(robot.wrench_matrices(&poses, &mut w, &mut valid).unwrap(), 2);
    /// let single = robot.inverse_kinematics(&poses[1]).unwrap().wrench_matrix();
    /// assert_eq!(&w[48..], single.as_slice());
    /// ```
    pub fn wrench_matrices(
        &self,
        poses: &[Pose],
        out: &mut [f64],
        valid: &mut [bool],
    ) -> Result<usize, KinematicsError> {
        let (dof, n) = (self.motion().dof(), self.cable_count());
        let block = dof * n;
        if out.len() != poses.len() * block {
            return Err(KinematicsError::WrongDimension {
                what: "wrench matrix buffer (poses × DOF × cables)".into(),
                motion: self.motion().name(),
                expected: poses.len() * block,
                found: out.len(),
            });
        }
        if valid.len() != poses.len() {
            return Err(KinematicsError::WrongDimension {
                what: "validity flags (one per pose)".into(),
                motion: self.motion().name(),
                expected: poses.len(),
                found: valid.len(),
            });
        }
        if self.has_pulleys() {
            return Ok(self.wrench_matrices_by_pose(poses, out, valid));
        }
        Ok(match self.motion() {
            MotionPattern::Spatial if self.cable_count() <= MAX_LANE_CABLES => {
                spatial_lanes(self, poses, out, valid, detected_path())
            }
            MotionPattern::Spatial => self.straight::<6>(poses, out, valid, |u, a, col| {
                let m = a.cross(u);
                col[..3].copy_from_slice(u.as_slice());
                col[3..].copy_from_slice(m.as_slice());
            }),
            MotionPattern::Planar => self.straight::<3>(poses, out, valid, |u, a, col| {
                col[0] = u.x;
                col[1] = u.y;
                col[2] = a.x * u.y - a.y * u.x;
            }),
            MotionPattern::Point3 => self.straight::<3>(poses, out, valid, |u, _, col| {
                col.copy_from_slice(u.as_slice());
            }),
            MotionPattern::Point2 => self.straight::<2>(poses, out, valid, |u, _, col| {
                col[0] = u.x;
                col[1] = u.y;
            }),
        })
    }

    /// W of four poses of a spatial robot in structure-of-arrays layout: `out[j][i][l]` is
    /// W(i, j) of pose `l` (cable j's column `[u_j ; a_j × u_j]`, eq. (6.11), one lane per
    /// pose), for consumers that work on four poses at once (SIMD across poses) and would
    /// otherwise transpose [`Robot::wrench_matrices`]'s blocks back. Returns which poses have
    /// a wrench matrix (as `valid` there; the lanes of the others hold no meaningful values).
    /// The values are those of [`Robot::wrench_matrices`], bit for bit (the same kernel).
    /// Errors when the robot is not spatial or `out` has not one column per cable. Robots with
    /// pulleys go through `update_kinematics` pose by pose (one `PoseKinematics` allocated per
    /// call); otherwise nothing is allocated.
    ///
    /// ```
    /// use cdpr_kinematics::{Pose, reference_robots::ipanema_like_8};
    /// let robot = ipanema_like_8();
    /// let poses = [0.0, 0.1, 0.2, 0.3].map(|x| Pose::spatial([x, 0.0, 1.0].into(), 0.0, 0.05, 0.0));
    /// let mut out = [[[0.0; 4]; 6]; 8];
    /// assert_eq!(robot.wrench_matrix_lanes(&poses, &mut out).unwrap(), [true; 4]);
    /// let w = robot.inverse_kinematics(&poses[2]).unwrap().wrench_matrix();
    /// assert_eq!(out[7][4][2], w[(4, 7)]);
    /// ```
    pub fn wrench_matrix_lanes(
        &self,
        poses: &[Pose; LANES],
        out: &mut [[[f64; LANES]; 6]],
    ) -> Result<[bool; LANES], KinematicsError> {
        self.wrench_matrix_lanes_on(poses, out, detected_path())
    }

    /// [`Robot::wrench_matrix_lanes`] through the portable (SSE2) build whatever the CPU, so
    /// that tests can compare it with the AVX2 build. Not API.
    #[doc(hidden)]
    pub fn wrench_matrix_lanes_portable(
        &self,
        poses: &[Pose; LANES],
        out: &mut [[[f64; LANES]; 6]],
    ) -> Result<[bool; LANES], KinematicsError> {
        self.wrench_matrix_lanes_on(poses, out, LanePath::Portable)
    }

    fn wrench_matrix_lanes_on(
        &self,
        poses: &[Pose; LANES],
        out: &mut [[[f64; LANES]; 6]],
        path: LanePath,
    ) -> Result<[bool; LANES], KinematicsError> {
        if self.motion() != MotionPattern::Spatial {
            return Err(KinematicsError::WrongDimension {
                what: "rows of the lane columns (6, spatial robots only)".into(),
                motion: self.motion().name(),
                expected: self.motion().dof(),
                found: 6,
            });
        }
        if out.len() != self.cable_count() {
            return Err(KinematicsError::WrongDimension {
                what: "lane columns (one per cable)".into(),
                motion: self.motion().name(),
                expected: self.cable_count(),
                found: out.len(),
            });
        }
        if self.has_pulleys() {
            let mut w = vec![0.0; LANES * 6 * self.cable_count()];
            let mut valid = [false; LANES];
            self.wrench_matrices_by_pose(poses, &mut w, &mut valid);
            for (l, block) in w.chunks_exact(6 * self.cable_count()).enumerate() {
                for (column, src) in out.iter_mut().zip(block.chunks_exact(6)) {
                    for (row, &v) in column.iter_mut().zip(src) {
                        row[l] = v;
                    }
                }
            }
            return Ok(valid);
        }
        Ok(match path {
            // SAFETY: `Avx2` is chosen only when the CPU reports AVX2 (`detected_path`).
            #[cfg(target_arch = "x86_64")]
            LanePath::Avx2 => unsafe { spatial_group_columns_avx2(self, poses, out) },
            LanePath::Portable => spatial_group_columns(Portable([0.0; LANES]), self, poses, out),
        })
    }

    /// [`Robot::wrench_matrices`] through the portable (SSE2) build of the structure-of-arrays
    /// kernel whatever the CPU, so that tests can compare it with the AVX2 build. Not API.
    #[doc(hidden)]
    pub fn wrench_matrices_portable(
        &self,
        poses: &[Pose],
        out: &mut [f64],
        valid: &mut [bool],
    ) -> Result<usize, KinematicsError> {
        if self.motion() == MotionPattern::Spatial
            && !self.has_pulleys()
            && self.cable_count() <= MAX_LANE_CABLES
            && out.len() == poses.len() * 6 * self.cable_count()
            && valid.len() == poses.len()
        {
            return Ok(spatial_lanes(self, poses, out, valid, LanePath::Portable));
        }
        self.wrench_matrices(poses, out, valid)
    }

    /// The straight-cable loop for DOF = D, with the column formula of the motion pattern.
    #[inline(always)]
    fn straight<const D: usize>(
        &self,
        poses: &[Pose],
        out: &mut [f64],
        valid: &mut [bool],
        column: impl Fn(&Vector3<f64>, &Vector3<f64>, &mut [f64; D]),
    ) -> usize {
        let n = self.cable_count();
        let mut count = 0;
        for ((pose, block), ok) in poses.iter().zip(out.chunks_exact_mut(D * n)).zip(valid) {
            *ok = self.straight_pose::<D>(pose, block, &column);
            count += *ok as usize;
        }
        count
    }

    /// One pose: the expressions of `update_kinematics` and `write_wrench_matrix`.
    #[inline(always)]
    fn straight_pose<const D: usize>(
        &self,
        pose: &Pose,
        block: &mut [f64],
        column: &impl Fn(&Vector3<f64>, &Vector3<f64>, &mut [f64; D]),
    ) -> bool {
        if !pose.position.iter().all(|v| v.is_finite()) {
            return false;
        }
        let r = pose.rotation.matrix();
        let threshold = DEGENERATE_LENGTH * self.length_scale().max(pose.position.norm());
        for (cable, col) in self.cables().iter().zip(block.chunks_exact_mut(D)) {
            let attachment = r * cable.platform;
            let attachment_point = pose.position + attachment;
            let vector = cable.frame - attachment_point;
            let length = vector.norm();
            if length.is_nan() || length <= threshold {
                return false;
            }
            let unit = vector / length;
            let col: &mut [f64; D] = col.try_into().expect("chunks of D");
            column(&unit, &attachment, col);
        }
        true
    }

    /// Robots with pulleys: `update_kinematics` pose by pose.
    #[cold]
    fn wrench_matrices_by_pose(
        &self,
        poses: &[Pose],
        out: &mut [f64],
        valid: &mut [bool],
    ) -> usize {
        let block = self.motion().dof() * self.cable_count();
        let mut kin = PoseKinematics::for_robot(self);
        let mut w = nalgebra::DMatrix::zeros(self.motion().dof(), self.cable_count());
        let mut count = 0;
        for ((pose, dst), ok) in poses.iter().zip(out.chunks_exact_mut(block)).zip(valid) {
            *ok = self.update_kinematics(pose, &mut kin).is_ok();
            if *ok {
                kin.write_wrench_matrix(&mut w);
                dst.copy_from_slice(w.as_slice());
                count += 1;
            }
        }
        count
    }
}

/// Poses per group of the structure-of-arrays kernel (four f64 lanes: one AVX2 register; the
/// stores of [`spatial_group`] are written out for four).
const LANES: usize = 4;
/// Most cables the kernel takes (its loops are unrolled for small robots); larger robots take
/// the pose-by-pose loop.
const MAX_LANE_CABLES: usize = 16;

/// The columns of a group, cable × row × lane: whole lanes are stored as they are computed (so
/// the compiler keeps the arithmetic across lanes), then copied out pose by pose.
type Columns = [[[f64; LANES]; 6]; MAX_LANE_CABLES];

/// Which build of the structure-of-arrays kernel runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum LanePath {
    /// Compiled for AVX2 (chosen at run time when the CPU has it).
    #[cfg(target_arch = "x86_64")]
    Avx2,
    /// Compiled for the baseline target (SSE2 on x86-64).
    Portable,
}

/// The fastest build this CPU runs (`is_x86_feature_detected!` caches its answer).
fn detected_path() -> LanePath {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        return LanePath::Avx2;
    }
    LanePath::Portable
}

/// Spatial robots without pulleys: groups of [`LANES`] poses through [`spatial_group`], the
/// remainder pose by pose. Both builds compile the same source without fused multiply–adds
/// (Rust never contracts `a * b + c`), so they give the same bits as the single-pose path.
fn spatial_lanes(
    robot: &Robot,
    poses: &[Pose],
    out: &mut [f64],
    valid: &mut [bool],
    path: LanePath,
) -> usize {
    let groups = poses.len() / LANES * LANES;
    let block = 6 * robot.cable_count();
    let (head, tail) = out.split_at_mut(groups * block);
    let (ok_head, ok_tail) = valid.split_at_mut(groups);
    let count = match path {
        // SAFETY: `Avx2` is chosen only when the CPU reports AVX2 (`detected_path`, or a test
        // that checks it first).
        #[cfg(target_arch = "x86_64")]
        LanePath::Avx2 => unsafe { spatial_groups_avx2(robot, &poses[..groups], head, ok_head) },
        LanePath::Portable => spatial_groups::<false>(robot, &poses[..groups], head, ok_head),
    };
    count
        + robot.straight::<6>(&poses[groups..], tail, ok_tail, |u, a, col| {
            let m = a.cross(u);
            col[..3].copy_from_slice(u.as_slice());
            col[3..].copy_from_slice(m.as_slice());
        })
}

/// [`spatial_groups`] compiled with AVX2 enabled (four f64 lanes per instruction).
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn spatial_groups_avx2(
    robot: &Robot,
    poses: &[Pose],
    out: &mut [f64],
    valid: &mut [bool],
) -> usize {
    spatial_groups::<true>(robot, poses, out, valid)
}

/// Whole groups of [`LANES`] poses (`poses.len()` a multiple of it), each written straight into
/// the blocks of its poses.
#[inline(always)]
fn spatial_groups<const AVX2: bool>(
    robot: &Robot,
    poses: &[Pose],
    out: &mut [f64],
    valid: &mut [bool],
) -> usize {
    let block = 6 * robot.cable_count();
    let mut scratch = [[[0.0; LANES]; 6]; MAX_LANE_CABLES];
    let mut count = 0;
    for ((group, blocks), ok) in poses
        .chunks_exact(LANES)
        .zip(out.chunks_exact_mut(LANES * block))
        .zip(valid.chunks_exact_mut(LANES))
    {
        let good = spatial_group::<AVX2>(robot, group, blocks, &mut scratch);
        ok.copy_from_slice(&good);
        count += good.iter().filter(|&&g| g).count();
    }
    count
}

/// One group of [`LANES`] poses: [`spatial_group_columns`] into `scratch`, then stored into
/// the pose's block of `blocks`.
#[inline(always)]
fn spatial_group<const AVX2: bool>(
    robot: &Robot,
    group: &[Pose],
    blocks: &mut [f64],
    scratch: &mut Columns,
) -> [bool; LANES] {
    let block = 6 * robot.cable_count();
    let n = robot.cable_count();
    let group: &[Pose; LANES] = group.try_into().expect("a group of LANES poses");
    #[cfg(target_arch = "x86_64")]
    let good = if AVX2 {
        // SAFETY: `AVX2` is true only in `spatial_groups_avx2`, which runs on CPUs with AVX2.
        let v = unsafe { Avx2::new_unchecked() };
        spatial_group_columns(v, robot, group, &mut scratch[..n])
    } else {
        spatial_group_columns(Portable([0.0; LANES]), robot, group, &mut scratch[..n])
    };
    #[cfg(not(target_arch = "x86_64"))]
    let good = spatial_group_columns(Portable([0.0; LANES]), robot, group, &mut scratch[..n]);
    if AVX2 {
        #[cfg(target_arch = "x86_64")]
        // SAFETY: `AVX2` is true only in `spatial_groups_avx2`, which runs on CPUs with AVX2.
        unsafe {
            store_blocks_avx2(&scratch[..n], blocks)
        };
    } else {
        for (l, dst) in blocks.chunks_exact_mut(block).enumerate() {
            for (d, column) in dst.chunks_exact_mut(6).zip(&scratch[..n]) {
                for (v, row) in d.iter_mut().zip(column) {
                    *v = row[l];
                }
            }
        }
    }
    good
}

/// The lanes of `columns` into the blocks of the four poses (the copy loop of
/// [`spatial_group`]: data movement only, the same values), with 4 × 4 transposes in
/// registers: per cable, rows 0–3 of the four poses as four 256-bit stores and rows 4–5 as
/// four 128-bit stores, instead of 24 scalar stores.
///
/// # Safety
/// The CPU must support AVX2 (AVX is enough).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
unsafe fn store_blocks_avx2(columns: &[[[f64; LANES]; 6]], blocks: &mut [f64]) {
    use std::arch::x86_64::{
        _mm_storeu_pd, _mm256_castpd256_pd128, _mm256_extractf128_pd, _mm256_loadu_pd,
        _mm256_permute2f128_pd, _mm256_storeu_pd, _mm256_unpackhi_pd, _mm256_unpacklo_pd,
    };
    let block = 6 * columns.len();
    assert_eq!(blocks.len(), LANES * block, "four blocks of 6 × n");
    let out = blocks.as_mut_ptr();
    for (j, column) in columns.iter().enumerate() {
        // SAFETY: every read is one of the six lane arrays of `column`, every write lies in
        // `blocks` (pose l's entries 6j..6j + 6, l < 4: below 4 · 6n, the length asserted).
        unsafe {
            let [r0, r1, r2, r3, r4, r5] = column.each_ref().map(|r| _mm256_loadu_pd(r.as_ptr()));
            let (t0, t1) = (_mm256_unpacklo_pd(r0, r1), _mm256_unpackhi_pd(r0, r1));
            let (t2, t3) = (_mm256_unpacklo_pd(r2, r3), _mm256_unpackhi_pd(r2, r3));
            let (u0, u1) = (_mm256_unpacklo_pd(r4, r5), _mm256_unpackhi_pd(r4, r5));
            let at = |l: usize| out.add(l * block + 6 * j);
            _mm256_storeu_pd(at(0), _mm256_permute2f128_pd::<0x20>(t0, t2));
            _mm256_storeu_pd(at(1), _mm256_permute2f128_pd::<0x20>(t1, t3));
            _mm256_storeu_pd(at(2), _mm256_permute2f128_pd::<0x31>(t0, t2));
            _mm256_storeu_pd(at(3), _mm256_permute2f128_pd::<0x31>(t1, t3));
            _mm_storeu_pd(at(0).add(4), _mm256_castpd256_pd128(u0));
            _mm_storeu_pd(at(1).add(4), _mm256_castpd256_pd128(u1));
            _mm_storeu_pd(at(2).add(4), _mm256_extractf128_pd::<1>(u0));
            _mm_storeu_pd(at(3).add(4), _mm256_extractf128_pd::<1>(u1));
        }
    }
}

/// [`spatial_group_columns`] compiled with AVX2 enabled.
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn spatial_group_columns_avx2(
    robot: &Robot,
    group: &[Pose; LANES],
    columns: &mut [[[f64; LANES]; 6]],
) -> [bool; LANES] {
    // SAFETY: the CPU supports AVX2 (this function's contract).
    spatial_group_columns(unsafe { Avx2::new_unchecked() }, robot, group, columns)
}

/// One group of [`LANES`] poses, structure of arrays (`columns[j][i][l]`, cable × row × pose): for each cable the expressions of
/// `update_kinematics` (eqs. (6.2)–(6.4)) and of the column `[u_i ; a_i × u_i]`, evaluated in
/// the same order as nalgebra's (**T ā** = ((T₀ ā_x + T₁ ā_y) + T₂ ā_z), ‖ℓ‖² = (x² + y²) + z²,
/// three divisions by ‖ℓ‖), one lane per pose.
/// Returns which poses are valid (finite position, every cable longer than the
/// degenerate-length threshold). On the lanes of `V` (`w` witnesses that its instructions are
/// available): one lane operation per step, no closures.
#[inline(always)]
fn spatial_group_columns<V: F64x4>(
    w: V,
    robot: &Robot,
    group: &[Pose; LANES],
    columns: &mut [[[f64; LANES]; 6]],
) -> [bool; LANES] {
    let mut position = [[0.0; LANES]; 3];
    let mut rotation = [[[0.0; LANES]; 3]; 3];
    let mut threshold = [0.0; LANES];
    let mut good = [false; LANES];
    for (l, pose) in group.iter().enumerate() {
        let m = pose.rotation.matrix();
        for k in 0..3 {
            position[k][l] = pose.position[k];
            for j in 0..3 {
                rotation[k][j][l] = m[(k, j)];
            }
        }
        good[l] = pose.position.iter().all(|v| v.is_finite());
        threshold[l] = DEGENERATE_LENGTH * robot.length_scale().max(pose.position.norm());
    }
    let u = [
        w.load(position[0]),
        w.load(position[1]),
        w.load(position[2]),
    ];
    let mut t = [[w.splat(0.0); 3]; 3];
    for k in 0..3 {
        for j in 0..3 {
            t[k][j] = w.load(rotation[k][j]);
        }
    }
    let threshold = w.load(threshold);
    // Every cable so far longer than the threshold (a NaN length fails `>`).
    let mut long = w.mask(true);
    for (cable, column) in robot.cables().iter().zip(columns) {
        let (p, c) = (&cable.platform, &cable.frame);
        let (px, py, pz) = (w.splat(p.x), w.splat(p.y), w.splat(p.z));
        let mut a = [w.splat(0.0); 3];
        let mut v = [w.splat(0.0); 3];
        for k in 0..3 {
            a[k] = t[k][0].mul(px).add(t[k][1].mul(py)).add(t[k][2].mul(pz));
            v[k] = w.splat(c[k]).sub(u[k].add(a[k]));
        }
        let length = v[0]
            .mul(v[0])
            .add(v[1].mul(v[1]))
            .add(v[2].mul(v[2]))
            .sqrt();
        long = V::and(long, length.gt(threshold));
        let e = [v[0].div(length), v[1].div(length), v[2].div(length)];
        *column = [
            e[0].to_array(),
            e[1].to_array(),
            e[2].to_array(),
            a[1].mul(e[2]).sub(a[2].mul(e[1])).to_array(),
            a[2].mul(e[0]).sub(a[0].mul(e[2])).to_array(),
            a[0].mul(e[1]).sub(a[1].mul(e[0])).to_array(),
        ];
    }
    let long = V::to_bools(long);
    [
        good[0] && long[0],
        good[1] && long[1],
        good[2] && long[2],
        good[3] && long[3],
    ]
}
