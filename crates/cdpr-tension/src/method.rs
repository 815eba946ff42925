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
    /// Pott, Bruckmann & Mikelsons (2009): t = t_m − W⁺(w_ext + W t_m), feasible iff in bounds.
    PottClosedForm,
    /// The closed form with t_ref lowered until a cable reaches t_min (WireLib
    /// `ClosedFormEnergyEfficient`).
    PottClosedFormEe,
    /// The puncture method (Müller, Reichert & Bruckmann 2014).
    Puncture,
    /// Dykstra's alternating projections from t_m (Hassan & Khajepour 2007).
    Dykstra,
    /// min ‖t − t_m‖₂ in bounds, exactly (QP).
    L2Mid,
    /// Mean of the feasible polytope's vertices (Mikelsons et al. 2008), any r.
    VertexCentroid,
    /// min Σ|t_i − t_m,i|^p with log barriers (Gosselin & Grenier 2011).
    PNorm,
    /// max s with t − t_min ≥ s, t_max − t ≥ α s (Borgstrom et al. 2009), an LP.
    OptimallySafe,
}

/// Where the puncture method aims from the minimum-norm t₀ (`--interior`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum PunctureInterior {
    /// The improved closed form (Pott 2014), CASPR `id_cf_ipm` (`icf`, the default).
    #[default]
    ImprovedClosedForm,
    /// The closed form of Pott, Bruckmann & Mikelsons (2009), CASPR `id_cf_pm` (`cf`).
    ClosedForm,
}

impl PunctureInterior {
    /// The command-line name (`icf`, `cf`).
    pub fn name(self) -> &'static str {
        match self {
            Self::ImprovedClosedForm => "icf",
            Self::ClosedForm => "cf",
        }
    }
}

impl FromStr for PunctureInterior {
    type Err = TensionError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "icf" => Ok(Self::ImprovedClosedForm),
            "cf" => Ok(Self::ClosedForm),
            _ => Err(TensionError::InvalidOption {
                option: "interior",
                detail: format!("{s:?}: expected icf or cf"),
            }),
        }
    }
}

/// Options of the methods that have some (`--interior`, `--alternating`, `--p`, `--alpha`);
/// every other method ignores them. [`MethodOptions::validate`] checks the numbers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MethodOptions {
    /// puncture: the interior point it aims at.
    pub interior: PunctureInterior,
    /// dykstra: plain (von Neumann) alternating projections instead of Dykstra's corrections.
    pub alternating: bool,
    /// p-norm: the exponent p ≥ 2 (default 4).
    pub p: f64,
    /// optimally-safe: the weight α > 0 of the upper margin (default 1).
    pub alpha: f64,
    /// dykstra and p-norm: the iteration cap (default 5 000, WireLib's).
    pub max_iterations: usize,
}

impl Default for MethodOptions {
    fn default() -> Self {
        Self {
            interior: PunctureInterior::default(),
            alternating: false,
            p: 4.0,
            alpha: 1.0,
            max_iterations: 5_000,
        }
    }
}

impl MethodOptions {
    /// `Ok` when p is finite and ≥ 2, α finite and > 0 and the cap at least 1.
    pub fn validate(&self) -> Result<(), TensionError> {
        if !(self.p.is_finite() && self.p >= 2.0) {
            return Err(TensionError::InvalidOption {
                option: "p",
                detail: format!("{}: expected a finite exponent p ≥ 2", self.p),
            });
        }
        if !(self.alpha.is_finite() && self.alpha > 0.0) {
            return Err(TensionError::InvalidOption {
                option: "alpha",
                detail: format!("{}: expected a finite weight α > 0", self.alpha),
            });
        }
        if self.max_iterations == 0 {
            return Err(TensionError::InvalidOption {
                option: "max_iterations",
                detail: "0: expected at least 1".to_string(),
            });
        }
        Ok(())
    }
}

impl Method {
    /// Every method, in the order of the table.
    pub const ALL: [Method; 19] = [
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
        Self::PottClosedForm,
        Self::PottClosedFormEe,
        Self::Puncture,
        Self::Dykstra,
        Self::L2Mid,
        Self::VertexCentroid,
        Self::PNorm,
        Self::OptimallySafe,
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
            Self::PottClosedForm => "pott-closed-form",
            Self::PottClosedFormEe => "pott-closed-form-ee",
            Self::Puncture => "puncture",
            Self::Dykstra => "dykstra",
            Self::L2Mid => "l2-mid",
            Self::VertexCentroid => "vertex-centroid",
            Self::PNorm => "p-norm",
            Self::OptimallySafe => "optimally-safe",
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
            Self::PottClosedForm => {
                "t = t_m − W⁺(w_ext + W t_m), feasible iff in bounds, any r (Pott, Bruckmann & \
                 Mikelsons 2009)"
            }
            Self::PottClosedFormEe => {
                "the closed form with t_ref lowered until a cable reaches t_min, any r (WireLib \
                 ClosedFormEnergyEfficient)"
            }
            Self::Puncture => {
                "from the minimum-norm t₀ towards an interior point (--interior icf|cf) into the \
                 bounds, any r (Müller, Reichert & Bruckmann 2014)"
            }
            Self::Dykstra => {
                "Dykstra's projections between equilibrium and bounds from t_m (--alternating: \
                 von Neumann's), any r (Hassan & Khajepour 2007)"
            }
            Self::L2Mid => "minimum ‖t − t_m‖₂ in bounds, t_m = (t_min + t_max)/2, a QP, any r",
            Self::VertexCentroid => {
                "mean of the feasible polytope's vertices, any r (Mikelsons et al. 2008)"
            }
            Self::PNorm => {
                "minimum Σ|t_i − t_m,i|^p (--p, default 4) with log barriers, Newton, any r \
                 (Gosselin & Grenier 2011)"
            }
            Self::OptimallySafe => {
                "maximum margin s: t − t_min ≥ s, t_max − t ≥ α s (--alpha), an LP, any r \
                 (Borgstrom et al. 2009)"
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
    ///
    /// (The options of [`MethodOptions`] belong to one method each: see
    /// [`Method::takes_option`].)
    pub fn required_redundancy(self) -> RequiredRedundancy {
        match self {
            Self::Exact => RequiredRedundancy::Exactly(0),
            Self::ClosedForm => RequiredRedundancy::Exactly(1),
            Self::Barycenter | Self::Sotda => RequiredRedundancy::Exactly(2),
            _ => RequiredRedundancy::AtLeastZero,
        }
    }

    /// Whether the method needs a finite t_max for every cable (it starts from the middle of
    /// the bounds t_m or enumerates the vertices of the feasible set):
    /// [`TensionError::NeedsFiniteBounds`] otherwise.
    pub fn needs_finite_bounds(self) -> bool {
        matches!(
            self,
            Self::ImprovedClosedForm
                | Self::PottClosedForm
                | Self::PottClosedFormEe
                | Self::Puncture
                | Self::Dykstra
                | Self::L2Mid
                | Self::VertexCentroid
                | Self::PNorm
        )
    }

    /// Whether `option` (`interior`, `alternating`, `p`, `alpha`) is one of this method's
    /// options (the CLI refuses the others).
    pub fn takes_option(self, option: &str) -> bool {
        matches!(
            (self, option),
            (Self::Puncture, "interior")
                | (Self::Dykstra, "alternating")
                | (Self::PNorm, "p")
                | (Self::OptimallySafe, "alpha")
        )
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
        assert_eq!(
            "cf".parse::<PunctureInterior>().unwrap(),
            PunctureInterior::ClosedForm
        );
        assert!("x".parse::<PunctureInterior>().is_err());
        assert!(MethodOptions::default().validate().is_ok());
        for bad in [
            MethodOptions {
                p: 1.5,
                ..Default::default()
            },
            MethodOptions {
                alpha: 0.0,
                ..Default::default()
            },
            MethodOptions {
                max_iterations: 0,
                ..Default::default()
            },
        ] {
            assert!(matches!(
                bad.validate(),
                Err(TensionError::InvalidOption { .. })
            ));
        }
        assert!(Method::Puncture.takes_option("interior"));
        assert!(!Method::L2.takes_option("p"));
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
            vec![
                Exact,
                Pinv,
                L1,
                L1Max,
                L2,
                L2Max,
                Linf,
                ImprovedClosedForm,
                PottClosedForm,
                PottClosedFormEe,
                Puncture,
                Dykstra,
                L2Mid,
                VertexCentroid,
                PNorm,
                OptimallySafe
            ]
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
                ImprovedClosedForm,
                PottClosedForm,
                PottClosedFormEe,
                Puncture,
                Dykstra,
                L2Mid,
                VertexCentroid,
                PNorm,
                OptimallySafe
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
                Sotda,
                PottClosedForm,
                PottClosedFormEe,
                Puncture,
                Dykstra,
                L2Mid,
                VertexCentroid,
                PNorm,
                OptimallySafe
            ]
        );
        assert!(Method::applicable(-1).is_empty());
        assert_eq!(
            ClosedForm.check_redundancy(2).unwrap_err().to_string(),
            "method closed-form needs redundancy 1; this robot has n − DOF = 2; methods that apply: \
             pinv, l1, l1-max, l2, l2-max, linf, improved-closed-form, barycenter, sotda, \
             pott-closed-form, pott-closed-form-ee, puncture, dykstra, l2-mid, vertex-centroid, \
             p-norm, optimally-safe"
        );
        assert_eq!(
            L1.check_redundancy(-1).unwrap_err().to_string(),
            "method l1 needs redundancy ≥ 0; this robot has n − DOF = -1; methods that apply: none"
        );
    }
}
