//! # Workspace criteria as written
//!
//! The text form of the workspace criteria shared by `cdpr workspace --criteria` and the Python
//! package's `criteria=`: comma-separated tokens `tension`, `length[:L]`, `det[:D]`,
//! `wrench-closure`, `capacity[:M]`, `isotropic:F`, `stiffness:K`, `stiffness:KT,KR`,
//! `interference[:D]`, `dynamic` (the thesis' eqs. (6.21), (6.22), (6.24); Picard, Caro, Plestan &
//! Claveau 2020 for the stiffness floors). A [`CriterionSpec`] carries the numbers only; the
//! external wrench is bound when an evaluator is built.
//!
//! ## References
//! - The thesis chapter on planar tendon-driven manipulators, eqs. (6.21)–(6.24).
//! - Picard, Caro, Plestan & Claveau 2020 (stiffness).

use cdpr_kinematics::MotionPattern;
use thiserror::Error;

/// One criterion as written (the load is bound later).
#[derive(Debug, Clone, PartialEq)]
pub enum CriterionSpec {
    /// Tensions in bounds (eq. 6.21).
    Tension,
    /// l_i ≥ l_min (eq. 6.22).
    Length(f64),
    /// |det J| ≥ D_min (eq. 6.24).
    Det(f64),
    /// Positive spanning.
    WrenchClosure,
    /// Capacity margin ≥ the value (N, N·m), for a required wrench box given separately.
    Capacity(f64),
    /// Isotropic force ≥ the value (N).
    Isotropic(f64),
    /// λ_min(sym K) ≥ the value (mixed units).
    Stiffness(f64),
    /// sym(K) − diag(k_t I, k_r I) ⪰ 0: (k_t N/m, k_r N·m/rad).
    StiffnessFloor(f64, f64),
    /// Cables at least the value apart (m), none through the platform shape.
    Interference(f64),
    /// Dynamic feasibility: every acceleration of a box (given separately) balanced within the
    /// bounds (Gagliardini, Gouttefarde & Caro 2016; `cdpr_dynamics::DynamicFeasibility`).
    Dynamic,
}

impl CriterionSpec {
    /// Name with its value, as written (`length:0.1`), for reports.
    pub fn label(&self) -> String {
        match self {
            Self::Tension => "tension".into(),
            Self::Length(l) => format!("length:{l}"),
            Self::Det(d) => format!("det:{d}"),
            Self::WrenchClosure => "wrench-closure".into(),
            Self::Capacity(m) => format!("capacity:{m}"),
            Self::Isotropic(f) => format!("isotropic:{f}"),
            Self::Stiffness(k) => format!("stiffness:{k}"),
            Self::StiffnessFloor(kt, kr) => format!("stiffness:{kt},{kr}"),
            Self::Interference(d) => format!("interference:{d}"),
            Self::Dynamic => "dynamic".into(),
        }
    }
}

/// A criteria text that does not parse (the caller prefixes its option name).
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum CriteriaError {
    /// A value that is not a number.
    #[error("`{token}`: `{value}` is not a number")]
    NotANumber {
        /// The token.
        token: String,
        /// Its value part.
        value: String,
    },
    /// A value that is NaN or infinite.
    #[error("`{token}`: the value must be finite")]
    NotFinite {
        /// The token.
        token: String,
    },
    /// `stiffness:KT,KR` on a robot that does not rotate, or with a non-finite KR.
    #[error("stiffness:{kt},{kr}: {reason}")]
    BadRotationalFloor {
        /// KT (N/m).
        kt: f64,
        /// KR as written.
        kr: String,
        /// Why.
        reason: String,
    },
    /// `length` or `det` without a value, on a robot without that limit.
    #[error("{criterion}: the robot has no [limits] {key} (give one as {example})")]
    NoLimit {
        /// `length` or `det`.
        criterion: &'static str,
        /// The robot-file key.
        key: &'static str,
        /// The written form with a value.
        example: &'static str,
    },
    /// `interference:D` with D < 0.
    #[error("`{token}`: the clearance D (m) must be ≥ 0")]
    NegativeClearance {
        /// The token.
        token: String,
    },
    /// `isotropic` or `stiffness` without its floor.
    #[error("{name} needs a floor, e.g. {name}:10")]
    NeedsFloor {
        /// The criterion.
        name: String,
    },
    /// A name that is not a criterion.
    #[error(
        "unknown criterion `{token}` (known: tension, length[:L], det[:D], wrench-closure, capacity[:M], isotropic:F, stiffness:KT,KR, stiffness:K, interference[:D])"
    )]
    Unknown {
        /// The token.
        token: String,
    },
    /// No criterion at all.
    #[error("give at least one criterion")]
    Empty,
}

fn number(token: &str, value: &str) -> Result<f64, CriteriaError> {
    let v: f64 = value.parse().map_err(|_| CriteriaError::NotANumber {
        token: token.into(),
        value: value.into(),
    })?;
    if !v.is_finite() {
        return Err(CriteriaError::NotFinite {
            token: token.into(),
        });
    }
    Ok(v)
}

/// The criteria of `texts` (each a comma-separated list; `None`: the default, `tension` plus
/// `length` and `det` where the robot file has those limits) for a `motion` robot with the
/// limits `min_cable_length` (m) and `min_jacobian_det`.
///
/// ```
/// use cdpr_kinematics::MotionPattern;
/// use cdpr_workspace::{CriterionSpec, parse_criteria};
/// let c = parse_criteria(Some(["tension,length", "stiffness:1e4,50"]), MotionPattern::Planar, Some(0.1), None)
///     .unwrap();
/// assert_eq!(c, [CriterionSpec::Tension, CriterionSpec::Length(0.1), CriterionSpec::StiffnessFloor(1e4, 50.0)]);
/// assert!(parse_criteria(Some(["det"]), MotionPattern::Planar, None, None).is_err());
/// ```
pub fn parse_criteria<'a>(
    texts: Option<impl IntoIterator<Item = &'a str>>,
    motion: MotionPattern,
    min_cable_length: Option<f64>,
    min_jacobian_det: Option<f64>,
) -> Result<Vec<CriterionSpec>, CriteriaError> {
    let Some(texts) = texts else {
        let mut s = vec![CriterionSpec::Tension];
        s.extend(min_cable_length.map(CriterionSpec::Length));
        s.extend(min_jacobian_det.map(CriterionSpec::Det));
        return Ok(s);
    };
    let mut out: Vec<CriterionSpec> = Vec::new();
    for token in texts
        .into_iter()
        .flat_map(|t| t.split(','))
        .map(str::trim)
        .filter(|t| !t.is_empty())
    {
        // `stiffness:KT,KR`: a bare number after `stiffness:KT` is its KR.
        if let (Some(CriterionSpec::Stiffness(kt)), Ok(kr)) = (out.last(), token.parse::<f64>()) {
            let kt = *kt;
            let bad = |reason: String| CriteriaError::BadRotationalFloor {
                kt,
                kr: token.into(),
                reason,
            };
            if !kr.is_finite() {
                return Err(bad("KR must be finite (N·m/rad)".into()));
            }
            if !motion.has_orientation() {
                return Err(bad(format!(
                    "a `{}` robot does not rotate; give stiffness:KT (N/m) only",
                    motion.name()
                )));
            }
            *out.last_mut().expect("just matched") = CriterionSpec::StiffnessFloor(kt, kr);
            continue;
        }
        let (name, value) = match token.split_once(':') {
            Some((n, v)) => (n, Some(v)),
            None => (token, None),
        };
        out.push(match (name, value) {
            ("tension", None) => CriterionSpec::Tension,
            ("length", Some(v)) => CriterionSpec::Length(number(token, v)?),
            ("length", None) => {
                CriterionSpec::Length(min_cable_length.ok_or(CriteriaError::NoLimit {
                    criterion: "length",
                    key: "min_cable_length",
                    example: "length:L",
                })?)
            }
            ("det", Some(v)) => CriterionSpec::Det(number(token, v)?),
            ("det", None) => {
                CriterionSpec::Det(min_jacobian_det.ok_or(CriteriaError::NoLimit {
                    criterion: "det",
                    key: "min_jacobian_det",
                    example: "det:D",
                })?)
            }
            ("wrench-closure", None) => CriterionSpec::WrenchClosure,
            ("dynamic", None) => CriterionSpec::Dynamic,
            ("capacity", v) => {
                CriterionSpec::Capacity(v.map(|v| number(token, v)).transpose()?.unwrap_or(0.0))
            }
            ("isotropic", Some(v)) => CriterionSpec::Isotropic(number(token, v)?),
            ("stiffness", Some(v)) => CriterionSpec::Stiffness(number(token, v)?),
            ("interference", v) => {
                let d = v.map(|v| number(token, v)).transpose()?.unwrap_or(0.0);
                if d < 0.0 {
                    return Err(CriteriaError::NegativeClearance {
                        token: token.into(),
                    });
                }
                CriterionSpec::Interference(d)
            }
            ("isotropic" | "stiffness", None) => {
                return Err(CriteriaError::NeedsFloor { name: name.into() });
            }
            _ => {
                return Err(CriteriaError::Unknown {
                    token: token.into(),
                });
            }
        });
    }
    if out.is_empty() {
        return Err(CriteriaError::Empty);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str, motion: MotionPattern) -> Result<Vec<CriterionSpec>, CriteriaError> {
        parse_criteria(Some([text]), motion, None, None)
    }

    #[test]
    fn every_criterion_and_its_label() {
        let c = parse(
            "tension, length:0.1,det:1e-3,wrench-closure,capacity,capacity:2,isotropic:10,stiffness:5,interference,interference:0.02",
            MotionPattern::Point3,
        )
        .unwrap();
        let labels: Vec<String> = c.iter().map(CriterionSpec::label).collect();
        assert_eq!(
            labels,
            [
                "tension",
                "length:0.1",
                "det:0.001",
                "wrench-closure",
                "capacity:0",
                "capacity:2",
                "isotropic:10",
                "stiffness:5",
                "interference:0",
                "interference:0.02"
            ]
        );
        let d = parse_criteria(
            None::<[&str; 0]>,
            MotionPattern::Planar,
            Some(0.2),
            Some(0.5),
        )
        .unwrap();
        assert_eq!(
            d,
            [
                CriterionSpec::Tension,
                CriterionSpec::Length(0.2),
                CriterionSpec::Det(0.5)
            ]
        );
    }

    #[test]
    fn bad_criteria_are_named() {
        let e = |t: &str, m| parse(t, m).unwrap_err().to_string();
        assert_eq!(
            e("length:x", MotionPattern::Planar),
            "`length:x`: `x` is not a number"
        );
        assert_eq!(
            e("isotropic:inf", MotionPattern::Planar),
            "`isotropic:inf`: the value must be finite"
        );
        assert!(e("stiffness:5,7", MotionPattern::Point2).contains("does not rotate"));
        assert_eq!(
            e("det", MotionPattern::Planar),
            "det: the robot has no [limits] min_jacobian_det (give one as det:D)"
        );
        assert!(e("interference:-1", MotionPattern::Planar).contains("must be ≥ 0"));
        assert_eq!(
            e("isotropic", MotionPattern::Planar),
            "isotropic needs a floor, e.g. isotropic:10"
        );
        assert!(e("volume", MotionPattern::Planar).starts_with("unknown criterion `volume`"));
        assert_eq!(
            e(" , ", MotionPattern::Planar),
            "give at least one criterion"
        );
    }
}
