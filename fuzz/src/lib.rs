//! # Shared helpers of the cdpr fuzz targets
//!
//! - [`Numbers`]: decodes f64 values from the fuzz bytes with the special values the issue asks
//!   for (NaN, ±∞, ±0, huge, tiny, duplicates of earlier values) mixed with ordinary magnitudes;
//! - [`TensionCase`]: a whole tension problem (DOF ∈ {2, 3, 6}, n ∈ [1, 10], W with zero and
//!   duplicate columns, wrench, bounds possibly inverted);
//! - [`check_certificate`]: an independent re-implementation of the certificate of
//!   `cdpr_tension::certificate` (equilibrium residual ≤ 10⁻⁹·scale with
//!   scale = max(1, ‖w_ext‖∞, ‖W‖∞·max|t_i|), bounds within 10⁻⁹·max(1, |bound|)).
//!
//! The targets call these and panic on any violated invariant; libFuzzer reports the panic.

use arbitrary::{Result, Unstructured};
use cdpr_kinematics::{Cable, MotionPattern, Pose, PoseKinematics, Robot};
use nalgebra::{DMatrix, DVector, Vector3};

/// Relative tolerance of the equilibrium residual (same value as the library's certificate).
pub const EQUILIBRIUM_TOLERANCE: f64 = 1e-9;
/// Relative tolerance of the bounds.
pub const BOUND_TOLERANCE: f64 = 1e-9;

/// A decoder of f64 values: one tag byte chooses a special value, a duplicate of an earlier value
/// or an ordinary number (mantissa from two bytes, decimal exponent in [−3, 3]).
pub struct Numbers<'a, 'b> {
    u: &'b mut Unstructured<'a>,
    seen: Vec<f64>,
    /// Whether the last special value was produced (NaN, ±∞, huge, tiny): tracks "well-scaled".
    pub wild: bool,
}

impl<'a, 'b> Numbers<'a, 'b> {
    /// A decoder reading from `u`.
    pub fn new(u: &'b mut Unstructured<'a>) -> Self {
        Self {
            u,
            seen: Vec::new(),
            wild: false,
        }
    }

    /// The underlying byte source.
    pub fn bytes(&mut self) -> &mut Unstructured<'a> {
        self.u
    }

    /// The next value (any of the special ones possible).
    pub fn any(&mut self) -> Result<f64> {
        let tag: u8 = self.u.arbitrary()?;
        let v = match tag {
            0..=3 => {
                self.wild = true;
                [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, -f64::NAN][tag as usize]
            }
            4..=7 => [0.0, -0.0, 1.0, -1.0][tag as usize - 4],
            8..=11 => {
                self.wild = true;
                [1e300, -1e300, 1e-300, f64::MIN_POSITIVE][tag as usize - 8]
            }
            12..=15 => {
                self.wild = true;
                [1e15, -1e15, 1e-15, f64::EPSILON][tag as usize - 12]
            }
            16..=31 if !self.seen.is_empty() => {
                let i = self.u.choose_index(self.seen.len())?;
                self.seen[i]
            }
            32..=39 => {
                // Raw bits: anything at all, including subnormals and signalling NaNs.
                let bits: u64 = self.u.arbitrary()?;
                let v = f64::from_bits(bits);
                if !(v.is_finite() && (v == 0.0 || (1e-3..=1e3).contains(&v.abs()))) {
                    self.wild = true;
                }
                v
            }
            _ => self.ordinary()?,
        };
        self.seen.push(v);
        Ok(v)
    }

    /// An ordinary finite value: ±(mantissa / 1000) · 10^e, e ∈ [−3, 3]... in [1e-6, 6.6e4].
    pub fn ordinary(&mut self) -> Result<f64> {
        let m: i16 = self.u.arbitrary()?;
        let e: u8 = self.u.arbitrary()?;
        let e = (e % 7) as i32 - 3;
        Ok(f64::from(m) / 1000.0 * 10f64.powi(e))
    }

    /// A finite value of moderate size (for geometry that must be valid).
    pub fn finite(&mut self) -> Result<f64> {
        let v = self.any()?;
        Ok(if v.is_finite() && v.abs() < 1e6 {
            v
        } else {
            self.ordinary()?
        })
    }
}

/// A decoded tension problem.
#[derive(Debug, Clone)]
pub struct TensionCase {
    /// Rows of W.
    pub dof: usize,
    /// W (DOF × n), possibly with NaN, ∞, zero and duplicate columns.
    pub w: DMatrix<f64>,
    /// External wrench (length DOF).
    pub w_ext: DVector<f64>,
    /// Lower bounds (possibly NaN, ∞, above `t_max`).
    pub t_min: Vec<f64>,
    /// Upper bounds.
    pub t_max: Vec<f64>,
    /// Whether every number is finite and of moderate size (|x| ∈ {0} ∪ [1e-3, 1e3]·10^±3).
    pub well_scaled: bool,
}

/// The motion pattern used for a DOF.
pub fn motion_for(dof: usize, alt: bool) -> MotionPattern {
    match dof {
        2 => MotionPattern::Point2,
        3 if alt => MotionPattern::Point3,
        3 => MotionPattern::Planar,
        _ => MotionPattern::Spatial,
    }
}

impl TensionCase {
    /// Decodes DOF ∈ `dofs`, n ∈ [1, 10], W, w_ext and bounds.
    pub fn decode(u: &mut Unstructured, dofs: &[usize]) -> Result<Self> {
        let dof = dofs[u.choose_index(dofs.len())?];
        let n = u.int_in_range(1..=10usize)?;
        let flags: u8 = u.arbitrary()?;
        let mut num = Numbers::new(u);
        let mut w = DMatrix::zeros(dof, n);
        for j in 0..n {
            for i in 0..dof {
                w[(i, j)] = num.any()?;
            }
        }
        // Structural degeneracies: a zero column and a duplicated column.
        if flags & 1 != 0 {
            let j = num.bytes().choose_index(n)?;
            w.column_mut(j).fill(0.0);
        }
        if flags & 2 != 0 && n > 1 {
            let a = num.bytes().choose_index(n)?;
            let b = num.bytes().choose_index(n)?;
            let col = w.column(a).clone_owned();
            w.set_column(b, &col);
        }
        if flags & 4 != 0 && n > 1 {
            // A negated column (antipodal cables).
            let a = num.bytes().choose_index(n)?;
            let b = num.bytes().choose_index(n)?;
            let col = -w.column(a).clone_owned();
            w.set_column(b, &col);
        }
        let w_ext = DVector::from_iterator(
            dof,
            (0..dof).map(|_| num.any()).collect::<Result<Vec<_>>>()?,
        );
        let (mut t_min, mut t_max) = (Vec::with_capacity(n), Vec::with_capacity(n));
        if flags & 8 != 0 {
            // Uniform bounds, as in every robot file.
            let (lo, hi) = (num.any()?, num.any()?);
            t_min = vec![lo; n];
            t_max = vec![hi; n];
        } else {
            for _ in 0..n {
                let lo = num.any()?;
                // Mostly an interval above t_min; sometimes independent (so t_min > t_max occurs).
                let hi = if flags & 16 != 0 {
                    num.any()?
                } else {
                    lo.abs() + num.any()?.abs()
                };
                t_min.push(lo);
                t_max.push(hi);
            }
        }
        if flags & 32 != 0 {
            // No upper limit on some cable.
            let j = num.bytes().choose_index(n)?;
            t_max[j] = f64::INFINITY;
        }
        let well_scaled = !num.wild;
        Ok(Self {
            dof,
            w,
            w_ext,
            t_min,
            t_max,
            well_scaled,
        })
    }
}

/// A robot with `n` cables for `motion` built from the bytes, its kinematics at a pose and
/// its wrench matrix; `None` if the decoded geometry is rejected (an error is fine).
pub fn decode_robot(
    num: &mut Numbers,
    motion: MotionPattern,
    n: usize,
) -> Result<Option<(Robot, PoseKinematics, DMatrix<f64>)>> {
    let d = motion.space_dim();
    let mut cables = Vec::with_capacity(n);
    for _ in 0..n {
        let mut frame = Vector3::zeros();
        let mut platform = Vector3::zeros();
        for k in 0..d {
            frame[k] = num.finite()?;
            if motion.has_orientation() {
                platform[k] = num.finite()? * 0.1;
            }
        }
        cables.push(Cable {
            frame,
            platform,
            pulley: None,
        });
    }
    let Ok(robot) = Robot::new(motion, cables) else {
        return Ok(None);
    };
    let q: Vec<f64> = (0..motion.dof())
        .map(|_| Ok(num.finite()? * 0.01))
        .collect::<Result<_>>()?;
    let Ok(pose) = Pose::from_coordinates(motion, &q) else {
        return Ok(None);
    };
    let Ok(kin) = robot.inverse_kinematics(&pose) else {
        return Ok(None);
    };
    let w = kin.wrench_matrix();
    Ok(Some((robot, kin, w)))
}

/// What [`check_certificate`] found wrong, if anything.
#[derive(Debug, Clone, PartialEq)]
pub enum CertificateFailure {
    /// Wrong number of tensions.
    Length {
        /// n.
        expected: usize,
        /// Tensions returned.
        found: usize,
    },
    /// A NaN or infinite tension.
    NotFinite {
        /// Cable.
        cable: usize,
        /// Its tension.
        tension: f64,
    },
    /// ‖W t + w_ext‖∞ above 10⁻⁹·scale.
    Equilibrium {
        /// Residual.
        residual: f64,
        /// Scale.
        scale: f64,
    },
    /// A bound broken by more than 10⁻⁹ relative.
    Bound {
        /// Cable.
        cable: usize,
        /// Tension.
        tension: f64,
        /// t_min.
        min: f64,
        /// t_max.
        max: f64,
    },
}

/// Independent re-check of a "feasible" verdict (see the crate docs for the definition).
pub fn check_certificate(
    w: &DMatrix<f64>,
    w_ext: &DVector<f64>,
    t_min: &[f64],
    t_max: &[f64],
    t: &[f64],
) -> std::result::Result<(), CertificateFailure> {
    let (m, n) = w.shape();
    if t.len() != n {
        return Err(CertificateFailure::Length {
            expected: n,
            found: t.len(),
        });
    }
    if let Some((cable, &tension)) = t.iter().enumerate().find(|(_, x)| !x.is_finite()) {
        return Err(CertificateFailure::NotFinite { cable, tension });
    }
    let mut residual = 0.0f64;
    let mut w_inf = 0.0f64;
    for k in 0..m {
        let mut s = w_ext[k];
        let mut row = 0.0;
        for i in 0..n {
            s += w[(k, i)] * t[i];
            row += w[(k, i)].abs();
        }
        residual = if s.is_nan() {
            f64::INFINITY
        } else {
            residual.max(s.abs())
        };
        w_inf = w_inf.max(row);
    }
    let t_abs = t.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let scale = 1f64.max(w_ext.amax()).max(w_inf * t_abs);
    if residual.is_nan() || residual > EQUILIBRIUM_TOLERANCE * scale {
        return Err(CertificateFailure::Equilibrium { residual, scale });
    }
    for i in 0..n {
        let (lo, hi, ti) = (t_min[i], t_max[i], t[i]);
        let below = ti < lo - BOUND_TOLERANCE * lo.abs().max(1.0);
        let above = hi.is_finite() && ti > hi + BOUND_TOLERANCE * hi.abs().max(1.0);
        if below || above {
            return Err(CertificateFailure::Bound {
                cable: i,
                tension: ti,
                min: lo,
                max: hi,
            });
        }
    }
    Ok(())
}
