//! # Tension distribution methods
//!
//! The names of the methods, as used on the command line and in reports.

use crate::TensionError;
use std::fmt;
use std::str::FromStr;

/// A tension distribution method (see the crate documentation for the table of methods).
///
/// `Display`, `Debug` and [`Method::name`] all give the command-line name (`closed-form`), so a
/// method prints the same in a log, a report and on the command line.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    /// n = DOF: t = −W⁻¹ w_ext (thesis eq. (6.12)).
    Exact,
    /// Minimum-norm t = −W⁺ w_ext, bounds only checked (thesis eq. (6.14)).
    Pinv,
    /// Algorithm 6.1 of the thesis chapter on planar tendon-driven manipulators (redundancy 1): the minimum-‖t‖₁ end of the feasible interval.
    ClosedForm,
    /// Constrained minimum ‖t‖₁ (LP, thesis eq. (6.19)).
    L1,
    /// Constrained maximum ‖t‖₁ (LP).
    L1Max,
    /// Constrained minimum ‖t‖₂² (QP, thesis eq. (6.17)).
    L2,
    /// Constrained maximum ‖t‖₂² (concave; solved exactly over the vertices).
    L2Max,
    /// Minimum of the largest tension (LP).
    Linf,
    /// Pott (2014): mean tension plus minimum-norm correction, saturating cables iteratively.
    ImprovedClosedForm,
    /// Area centroid of the feasible polygon, redundancy 2 (Lamaury & Gouttefarde 2013).
    Barycenter,
    /// Stiffness-oriented tension distribution, redundancy 2 (Picard, Caro, Plestan & Claveau 2020, Algorithm 1).
    Sotda,
}

impl Method {
    /// Every method, in the order of the table.
    pub const ALL: [Method; 11] = [
        Self::Exact,
        Self::Pinv,
        Self::ClosedForm,
        Self::L1,
        Self::L1Max,
        Self::L2,
        Self::L2Max,
        Self::Linf,
        Self::ImprovedClosedForm,
        Self::Barycenter,
        Self::Sotda,
    ];

    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Exact => "exact",
            Self::Pinv => "pinv",
            Self::ClosedForm => "closed-form",
            Self::L1 => "l1",
            Self::L1Max => "l1-max",
            Self::L2 => "l2",
            Self::L2Max => "l2-max",
            Self::Linf => "linf",
            Self::ImprovedClosedForm => "improved-closed-form",
            Self::Barycenter => "barycenter",
            Self::Sotda => "sotda",
        }
    }
}

impl Method {
    /// One line saying what the method computes and when it applies (the `--method` list of
    /// `cdpr tension --help`). n cables, DOF degrees of freedom, redundancy r = n − DOF.
    pub fn summary(self) -> &'static str {
        match self {
            Self::Exact => "t = −W⁻¹ w_ext, the only solution when n = DOF (thesis eq. 6.12)",
            Self::Pinv => {
                "minimum-norm t = −W⁺ w_ext, bounds only checked afterwards (thesis eq. 6.14)"
            }
            Self::ClosedForm => {
                "minimum ‖t‖₁ in bounds in closed form, redundancy r = 1 (thesis Algorithm 6.1)"
            }
            Self::L1 => "minimum ‖t‖₁ in bounds, a linear program, any r (thesis eq. 6.19)",
            Self::L1Max => "maximum ‖t‖₁ in bounds, a linear program, any r",
            Self::L2 => "minimum ‖t‖₂ in bounds, a quadratic program, any r (thesis eq. 6.17)",
            Self::L2Max => "maximum ‖t‖₂ in bounds, over the vertices of the feasible set, any r",
            Self::Linf => "minimum largest tension max_i t_i in bounds, a linear program, any r",
            Self::ImprovedClosedForm => {
                "mean tension plus minimum-norm correction, saturating cables (Pott 2014), any r"
            }
            Self::Barycenter => {
                "centroid of the feasible polygon, r = 2 (Lamaury & Gouttefarde 2013)"
            }
            Self::Sotda => {
                "stiffness-oriented distribution on the feasible polygon, r = 2, needs \
                 axial_stiffness (Picard, Caro, Plestan & Claveau 2020, Algorithm 1)"
            }
        }
    }
}

impl fmt::Debug for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Method {
    type Err = TensionError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| TensionError::UnknownMethod(s.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for m in Method::ALL {
            assert_eq!(m.name().parse::<Method>().unwrap(), m);
            assert_eq!(m.to_string(), m.name());
            assert_eq!(format!("{m:?}"), m.name());
            assert_eq!(format!("{m:?}"), format!("{m}"));
            assert!(!m.summary().is_empty());
        }
        assert!(matches!(
            "l3".parse::<Method>(),
            Err(TensionError::UnknownMethod(_))
        ));
    }
}
