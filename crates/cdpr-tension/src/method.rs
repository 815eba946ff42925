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

/// The redundancy r = n − DOF a method needs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RequiredRedundancy {
    /// Exactly this r.
    Exactly(usize),
    /// Any r ≥ 0 (at least as many cables as degrees of freedom).
    AtLeastZero,
}

impl RequiredRedundancy {
    /// Whether redundancy `r` satisfies the requirement.
    #[inline]
    pub fn admits(self, r: isize) -> bool {
        match self {
            Self::Exactly(k) => r == k as isize,
            Self::AtLeastZero => r >= 0,
        }
    }
}

impl fmt::Debug for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl fmt::Display for RequiredRedundancy {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Exactly(k) => write!(f, "{k}"),
            Self::AtLeastZero => f.write_str("≥ 0"),
        }
    }
}

impl Method {
    /// The redundancy r = n − DOF the method is defined for: exact 0, closed-form 1
    /// (Algorithm 6.1), barycenter and sotda 2, every other method any r ≥ 0.
    pub fn required_redundancy(self) -> RequiredRedundancy {
        match self {
            Self::Exact => RequiredRedundancy::Exactly(0),
            Self::ClosedForm => RequiredRedundancy::Exactly(1),
            Self::Barycenter | Self::Sotda => RequiredRedundancy::Exactly(2),
            _ => RequiredRedundancy::AtLeastZero,
        }
    }

    /// Whether the method applies at redundancy r = n − DOF.
    #[inline]
    pub fn applies_to(self, redundancy: isize) -> bool {
        self.required_redundancy().admits(redundancy)
    }

    /// The methods that apply at redundancy r, in the order of [`Method::ALL`].
    pub fn applicable(redundancy: isize) -> Vec<Method> {
        Self::ALL
            .into_iter()
            .filter(|m| m.applies_to(redundancy))
            .collect()
    }

    /// `Ok` if the method applies at redundancy r, else the usage error
    /// [`TensionError::MethodNotApplicable`] (check once, before a grid or a trajectory runs).
    ///
    /// ```
    /// use cdpr_tension::Method;
    /// let e = Method::ClosedForm.check_redundancy(2).unwrap_err();
    /// assert!(e.to_string().starts_with(
    ///     "method closed-form needs redundancy 1; this robot has n − DOF = 2; methods that apply: pinv, l1,"
    /// ));
    /// assert!(Method::L1.check_redundancy(5).is_ok());
    /// ```
    pub fn check_redundancy(self, redundancy: isize) -> Result<(), TensionError> {
        if self.applies_to(redundancy) {
            Ok(())
        } else {
            Err(self.not_applicable(redundancy))
        }
    }

    /// The usage error for redundancy r (cold: it allocates the list of applicable methods).
    #[cold]
    pub(crate) fn not_applicable(self, redundancy: isize) -> TensionError {
        TensionError::MethodNotApplicable {
            method: self,
            needs: self.required_redundancy(),
            redundancy,
            applicable: Self::applicable(redundancy),
        }
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

    #[test]
    fn applicability_by_redundancy() {
        use Method::*;
        assert_eq!(
            Method::applicable(0),
            vec![Exact, Pinv, L1, L1Max, L2, L2Max, Linf, ImprovedClosedForm]
        );
        assert_eq!(
            Method::applicable(1),
            vec![
                Pinv,
                ClosedForm,
                L1,
                L1Max,
                L2,
                L2Max,
                Linf,
                ImprovedClosedForm
            ]
        );
        assert_eq!(
            Method::applicable(2),
            vec![
                Pinv,
                L1,
                L1Max,
                L2,
                L2Max,
                Linf,
                ImprovedClosedForm,
                Barycenter,
                Sotda
            ]
        );
        assert!(Method::applicable(-1).is_empty());
        assert_eq!(
            ClosedForm.check_redundancy(2).unwrap_err().to_string(),
            "method closed-form needs redundancy 1; this robot has n − DOF = 2; methods that apply: \
             pinv, l1, l1-max, l2, l2-max, linf, improved-closed-form, barycenter, sotda"
        );
        assert_eq!(
            L1.check_redundancy(-1).unwrap_err().to_string(),
            "method l1 needs redundancy ≥ 0; this robot has n − DOF = -1; methods that apply: none"
        );
    }
}
