//! # Gauge fixing
//!
//! Cable lengths are distances: moving the whole frame (anchors and poses together) by a
//! rigid motion leaves every length unchanged, and so does a rigid change of the platform
//! frame (attachments and poses together). Self-calibration (unknown poses) therefore
//! determines the frame only up to this gauge, g = 6 parameters in space (3 translations,
//! 3 rotations) and 3 in the plane, and as many again for the attachments of an oriented
//! platform. The gauge is fixed by holding g coordinates at their nominal values (a "3-2-1"
//! datum, as in geodetic network adjustment): with e₁ along anchor b − anchor a, e₃ normal to
//! the plane of anchors a, b, c and e₂ = e₃ × e₁, anchor a is held entirely, anchor b moves
//! only along e₁, anchor c only in the (e₁, e₂) plane (in the plane: a held, b along e₁).
//! The calibrated frame is expressed in that datum: anchor a is the nominal one. Quantities
//! free of the gauge (distances between anchors, offsets, gains) do not depend on the choice.
//!
//! Readings relative to a known reference pose x_ref without unknown offsets (the Hangprinter
//! workflow) see translations of the frame (l(x_ref) changes); only rotations about the
//! reference point remain, g = 3 in space (anchor a moves only along the line from x_ref,
//! anchor b only in the plane of x_ref, a, b) and 1 in the plane (anchor a along its line).
//!
//! ## References
//! - Borgstrom, Jordan, Borgstrom, Stealey, Sukhatme, Batalin & Kaiser 2009, *NIMS-PL: A
//!   cable-driven robot with self-calibration capabilities*, IEEE T-RO 25(5).
//! - Miermeister & Pott 2012, *Auto-calibration method for overconstrained cable-driven
//!   parallel robots*, ICRA.
//! - Triggs, McLauchlan, Hartley & Fitzgibbon 2000, *Bundle adjustment — a modern synthesis*
//!   (gauge freedom, §9).

use crate::{CalibrationError, Parameters, Unknowns};
use cdpr_kinematics::MotionPattern;
use cdpr_kinematics::nalgebra::Vector3;

/// One free parameter of the calibration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Parameter {
    /// The anchor of `cable` moved along the unit vector `direction` (m).
    Frame {
        /// Cable index (0-based).
        cable: usize,
        /// Unit direction, base frame.
        direction: Vector3<f64>,
    },
    /// The attachment of `cable` moved along `direction` (m, platform frame).
    Platform {
        /// Cable index (0-based).
        cable: usize,
        /// Unit direction, platform frame.
        direction: Vector3<f64>,
    },
    /// The offset of `cable` (m).
    Offset {
        /// Cable index (0-based).
        cable: usize,
    },
    /// The gain of `cable`.
    Gain {
        /// Cable index (0-based).
        cable: usize,
    },
}

impl Parameter {
    /// The cable the parameter belongs to.
    pub fn cable(&self) -> usize {
        match *self {
            Self::Frame { cable, .. }
            | Self::Platform { cable, .. }
            | Self::Offset { cable }
            | Self::Gain { cable } => cable,
        }
    }
}

/// Which motions of the frame the lengths cannot see.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Gauge {
    /// None: known poses fix the base frame.
    None,
    /// Rigid motions (6 in space, 3 in the plane).
    Rigid,
    /// Rotations about this point (3 in space, 1 in the plane): relative readings.
    RotationsAbout(Vector3<f64>),
}

/// The free parameters, in order: per cable frame, platform, offset, gain; and the
/// coordinates held by the gauge (described in words).
#[derive(Debug, Clone, PartialEq)]
pub struct ParameterSpace {
    /// The free parameters.
    pub parameters: Vec<Parameter>,
    /// What the gauge holds at the nominal values (empty without a gauge).
    pub fixed: Vec<String>,
    /// Number of coordinates held by the gauge.
    pub gauge: usize,
}

impl ParameterSpace {
    /// The parameters of `unknowns` with the datum of the module documentation for `gauge`
    /// (the attachments of an oriented platform always get a rigid datum when `gauge` is not
    /// [`Gauge::None`]).
    pub fn new(
        motion: MotionPattern,
        nominal: &Parameters,
        unknowns: Unknowns,
        gauge: Gauge,
    ) -> Result<Self, CalibrationError> {
        let n = nominal.frame.len();
        let dim = motion.space_dim();
        let axes: Vec<Vector3<f64>> = (0..dim).map(|k| Vector3::ith(k, 1.0)).collect();
        let mut frame_dirs: Vec<Vec<Vector3<f64>>> = vec![axes.clone(); n];
        let mut platform_dirs: Vec<Vec<Vector3<f64>>> = vec![axes.clone(); n];
        let mut fixed = Vec::new();
        let mut held = 0;
        match gauge {
            Gauge::Rigid if unknowns.frame => {
                held += datum(
                    &nominal.frame,
                    dim,
                    "anchors",
                    "anchor",
                    &mut frame_dirs,
                    &mut fixed,
                )?;
            }
            Gauge::RotationsAbout(o) if unknowns.frame => {
                held += rotation_datum(&nominal.frame, o, dim, &mut frame_dirs, &mut fixed)?;
            }
            _ => {}
        }
        if gauge != Gauge::None && unknowns.platform {
            held += datum(
                &nominal.platform,
                dim,
                "platform attachments",
                "attachment",
                &mut platform_dirs,
                &mut fixed,
            )?;
        }
        let mut parameters = Vec::new();
        for i in 0..n {
            if unknowns.frame {
                for d in &frame_dirs[i] {
                    parameters.push(Parameter::Frame {
                        cable: i,
                        direction: *d,
                    });
                }
            }
            if unknowns.platform {
                for d in &platform_dirs[i] {
                    parameters.push(Parameter::Platform {
                        cable: i,
                        direction: *d,
                    });
                }
            }
            if unknowns.offsets {
                parameters.push(Parameter::Offset { cable: i });
            }
            if unknowns.gains {
                parameters.push(Parameter::Gain { cable: i });
            }
        }
        Ok(Self {
            parameters,
            fixed,
            gauge: held,
        })
    }

    /// The parameters moved by δ (one value per free parameter).
    pub fn apply(&self, p: &Parameters, delta: &[f64]) -> Parameters {
        let mut out = p.clone();
        for (q, d) in self.parameters.iter().zip(delta) {
            match *q {
                Parameter::Frame { cable, direction } => out.frame[cable] += *d * direction,
                Parameter::Platform { cable, direction } => out.platform[cable] += *d * direction,
                Parameter::Offset { cable } => out.offsets[cable] += d,
                Parameter::Gain { cable } => out.gains[cable] += d,
            }
        }
        out
    }
}

/// Rotations about `o`: anchor a along the line from o, anchor b in the plane (o, a, b).
fn rotation_datum(
    points: &[Vector3<f64>],
    o: Vector3<f64>,
    dim: usize,
    dirs: &mut [Vec<Vector3<f64>>],
    fixed: &mut Vec<String>,
) -> Result<usize, CalibrationError> {
    let scale = points
        .iter()
        .map(|p| p.norm())
        .fold(o.norm().max(1.0), f64::max);
    let eps = 1e-9 * scale;
    let Some(a) = (0..points.len()).find(|&j| (points[j] - o).norm() > eps) else {
        return Err(CalibrationError::DegenerateGauge {
            what: "anchors",
            reason: "all at the reference point",
        });
    };
    let e1 = (points[a] - o).normalize();
    dirs[a] = vec![e1];
    fixed.push(format!(
        "anchor {} across the line from the reference point (moves only along it)",
        a + 1
    ));
    if dim == 2 {
        return Ok(1);
    }
    let Some(b) = (0..points.len()).find(|&j| j != a && e1.cross(&(points[j] - o)).norm() > eps)
    else {
        return Err(CalibrationError::DegenerateGauge {
            what: "anchors",
            reason: "collinear with the reference point",
        });
    };
    let e3 = e1.cross(&(points[b] - o)).normalize();
    dirs[b] = vec![e1, e3.cross(&e1)];
    fixed.push(format!(
        "anchor {} normal to the plane of the reference point and anchors {} and {} (moves only in it)",
        b + 1,
        a + 1,
        b + 1
    ));
    // Anchor a's line has 2 directions held in space.
    Ok(3)
}

/// Chooses anchors a, b, c (the first three in general position) and restricts their
/// directions; returns the number of coordinates held.
fn datum(
    points: &[Vector3<f64>],
    dim: usize,
    what: &'static str,
    one: &str,
    dirs: &mut [Vec<Vector3<f64>>],
    fixed: &mut Vec<String>,
) -> Result<usize, CalibrationError> {
    let scale = points.iter().map(|p| p.norm()).fold(1.0, f64::max);
    let eps = 1e-9 * scale;
    let a = 0;
    let Some(b) = (1..points.len()).find(|&j| (points[j] - points[a]).norm() > eps) else {
        return Err(CalibrationError::DegenerateGauge {
            what,
            reason: "all at one point",
        });
    };
    let e1 = (points[b] - points[a]).normalize();
    dirs[a].clear();
    dirs[b] = vec![e1];
    fixed.push(format!("{one} {} (all coordinates)", a + 1));
    if dim == 2 {
        fixed.push(format!(
            "{one} {} across the line from {one} {} (moves only along it)",
            b + 1,
            a + 1
        ));
        return Ok(3);
    }
    fixed.push(format!(
        "{one} {} in the 2 directions across the line from {one} {} (moves only along it)",
        b + 1,
        a + 1
    ));
    let Some(c) =
        (1..points.len()).find(|&j| j != b && e1.cross(&(points[j] - points[a])).norm() > eps)
    else {
        return Err(CalibrationError::DegenerateGauge {
            what,
            reason: "collinear",
        });
    };
    let e3 = e1.cross(&(points[c] - points[a])).normalize();
    let e2 = e3.cross(&e1);
    dirs[c] = vec![e1, e2];
    fixed.push(format!(
        "{one} {} normal to the plane of {one}s {}, {}, {} (moves only in it)",
        c + 1,
        a + 1,
        b + 1,
        c + 1
    ));
    Ok(6)
}
