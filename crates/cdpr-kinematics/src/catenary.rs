//! # Elastic catenary (Irvine 1981)
//!
//! A real cable between its frame exit point A and its platform attachment B: heavy (weight
//! w = ρ g per *unstrained* metre, N/m) and elastic (axial stiffness EA, N), so it sags below
//! its chord and stretches. In the cable's vertical plane — A at the origin, x horizontal
//! towards B, z up — with L0 the unstrained length and (F_x, F_z) the cable tension at B along
//! A → B (Irvine, *Cable Structures*, 1981, eqs. (2.29)–(2.30); Kozak, Zhou & Wang 2006, eq. (6)):
//!
//! ```text
//!   x_B = F_x L0/EA + (|F_x|/w) [asinh(F_z/F_x) − asinh((F_z − w L0)/F_x)]
//!   z_B = F_z L0/EA − w L0²/(2 EA) + (1/w) [√(F_x² + F_z²) − √(F_x² + (F_z − w L0)²)]
//!   T_A = √(F_x² + (F_z − w L0)²),   T_B = √(F_x² + F_z²).
//! ```
//!
//! ## Evaluation without cancellation
//! Written as above the bracketed differences cancel as w → 0. With V = F_z − w L0 (the
//! vertical tension at A), T_B − T_A = w L0 (F_z + V)/(T_A + T_B) and
//! asinh(F_z/F_x) − asinh(V/F_x) = ln(1 + w L0 m), m = (1 + P/Q)/(T_A + T_B), where
//! P = F_z + T_B and Q = V + T_A are formed without subtraction (P = F_x²/(T_B − F_z) when
//! F_z < 0). Hence, with φ(u) = ln(1 + u)/u (φ(0) = 1),
//!
//! ```text
//!   x_B = L0 F_x [1/EA + m φ(w L0 m)],      z_B = L0 (F_z + V) [1/(2 EA) + 1/(T_A + T_B)],
//! ```
//!
//! which is the elastic straight cable x_B = L0 (1 + T/EA) F_x/T at w = 0 and the inextensible
//! catenary at 1/EA = 0 (an infinite `axial_stiffness` is accepted): both limits are continuous.
//!
//! ## The inverse problems and the taut branch
//! The flexibility matrix ∂(x_B, z_B)/∂(F_x, F_z) is symmetric positive definite (the Hessian
//! of the complementary energy), so a span and an unstrained length fix the end force uniquely:
//! [`ElasticCatenary::solve_for_length`] finds it by Newton's method with backtracking. Given
//! the *tension* T_B at the platform instead ([`ElasticCatenary::solve_for_tension`], unknowns
//! the angle θ of F and L0), two catenaries may fit the span: a taut one and a deeply sagging
//! one, separated by the fold where det ∂(x_B, z_B)/∂(θ, L0) = 0. The taut branch — the one
//! connected to the straight cable, where the determinant is −L0 (1 + T/EA)² < 0 — is the one
//! kept: Newton starts on the straight cable and never leaves det < 0. Below the smallest
//! tension that can hold the cable across the span there is no solution
//! ([`CatenaryError::Unreachable`]).
//!
//! A vertical span (x_B = 0) is solved in closed form (F_x = 0).
//!
//! ## References
//! - Irvine, *Cable Structures*, MIT Press 1981, §2.3 (the elastic catenary, eqs. (2.29)–(2.30)).
//! - Kozak, Zhou & Wang 2006, "Static analysis of cable-driven manipulators with non-negligible
//!   cable mass", IEEE T-RO 22(3), eqs. (6)–(8).
//! - Peyrot & Goulois 1979, "Analysis of cable structures", Computers & Structures 10 (the
//!   starting catenary parameter λ0).

use nalgebra::{Matrix2, Matrix2x3, Vector2, Vector3};
use thiserror::Error;

/// Why a catenary could not be formed or solved. [`crate::KinematicsError::Catenary`] wraps it
/// with the cable's index.
#[derive(Debug, Clone, Copy, PartialEq, Error)]
#[non_exhaustive]
pub enum CatenaryError {
    /// A negative (or non-finite) weight per length w (N/m) or linear density ρ (kg/m).
    #[error("negative or non-finite cable weight: {value} (linear density ≥ 0 kg/m)")]
    NegativeDensity {
        /// The value given.
        value: f64,
    },
    /// An axial stiffness EA that is not > 0 (infinity is the inextensible cable).
    #[error("axial stiffness must be > 0 N, got {value}")]
    NegativeStiffness {
        /// The value given (N).
        value: f64,
    },
    /// A span, length, force or tension that is NaN or infinite, or out of its range (a
    /// non-positive unstrained length or tension, a negative horizontal force).
    #[error("{what} is not valid ({value})")]
    InvalidInput {
        /// Which quantity.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// No taut cable of this model reaches the span: an inextensible cable not longer than the
    /// chord, a weightless cable not shorter than it (slack), or a platform-end tension too
    /// small to hold the cable up across the span.
    #[error(
        "no taut cable reaches the span ({horizontal} m horizontal, {vertical} m vertical): {reason}"
    )]
    Unreachable {
        /// Horizontal span x_B (m).
        horizontal: f64,
        /// Vertical span z_B (m, up).
        vertical: f64,
        /// Why.
        reason: &'static str,
    },
    /// No unstrained length in floating point gives this platform-end tension: T_B(L0) jumps
    /// past it between two adjacent lengths (a cable nearly straight along the vertical).
    #[error(
        "the platform-end tension {tension} N cannot be resolved: the nearest taut catenary has {closest} N"
    )]
    Unresolvable {
        /// The tension asked for (N).
        tension: f64,
        /// The platform-end tension of the closest catenary found (N).
        closest: f64,
    },
    /// Newton's method stopped without meeting the tolerance.
    #[error("catenary solve did not converge in {iterations} iterations (residual {residual:e} m)")]
    NotConverged {
        /// Iterations made.
        iterations: usize,
        /// Final residual ‖(x, z) − span‖ (m).
        residual: f64,
    },
}

/// One cable's elastic-catenary model: weight per unstrained length w = ρ g (N/m) and
/// compliance 1/EA (1/N). `w = 0` is the elastic straight cable, `EA = ∞` the inextensible
/// catenary.
///
/// ```
/// use cdpr_kinematics::ElasticCatenary;
/// // Issue 29's example: F = (100, −50) N at B, L0 = 11 m, w = 0.5 N/m, EA = 10⁶ N.
/// let cable = ElasticCatenary::new(0.5, 1e6).unwrap();
/// let end = cable.end_point(11.0, 100.0, -50.0);
/// assert!((end.x - 9.730114663).abs() < 1e-9 && (end.y + 5.131623707).abs() < 1e-9);
/// assert!((cable.frame_end_tension(11.0, 100.0, -50.0) - 114.3689).abs() < 1e-4);
/// // Back from the span and the platform-end tension to L0 and the force (taut branch).
/// let sol = cable.solve_for_tension(end.x, end.y, 100f64.hypot(50.0)).unwrap();
/// assert!((sol.unstrained_length - 11.0).abs() < 1e-9);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElasticCatenary {
    weight: f64,
    compliance: f64,
}

/// A solved catenary: the unstrained length and the end forces (taut branch).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CatenarySolution {
    /// L0: the unstrained length (m).
    pub unstrained_length: f64,
    /// F_x: the horizontal tension, the same all along the cable (N, ≥ 0).
    pub horizontal_force: f64,
    /// F_z: the vertical component of the tension at B along A → B (N, up positive).
    pub vertical_force: f64,
    /// T_A = √(F_x² + (F_z − w L0)²): tension at the frame end (N).
    pub frame_end_tension: f64,
    /// T_B = √(F_x² + F_z²): tension at the platform end (N).
    pub platform_end_tension: f64,
    /// Newton iterations used (0 for a closed-form vertical span).
    pub iterations: usize,
}

/// φ(u) = ln(1 + u)/u, φ(0) = 1 (u ≥ 0).
#[inline]
fn log1p_ratio(u: f64) -> f64 {
    if u < 1e-5 {
        // Error O(u³) < 1e-15.
        1.0 - u * (0.5 - u / 3.0)
    } else {
        u.ln_1p() / u
    }
}

/// How the search on L0 ended without a solution.
enum SearchEnd {
    /// At the fold: the least platform-end tension seen (N).
    Fold(f64),
    /// A solve for the length failed.
    Failed(CatenaryError),
}

/// The end state of the forward map and what its Jacobian reuses.
#[derive(Clone, Copy)]
struct Forward {
    x: f64,
    z: f64,
    ta: f64,
    tb: f64,
}

impl ElasticCatenary {
    /// A cable of weight `weight` per unstrained metre (N/m, ≥ 0: ρ g) and axial stiffness
    /// `axial_stiffness` (EA in N, > 0; `f64::INFINITY` for an inextensible cable).
    pub fn new(weight: f64, axial_stiffness: f64) -> Result<Self, CatenaryError> {
        if !(weight.is_finite() && weight >= 0.0) {
            return Err(CatenaryError::NegativeDensity { value: weight });
        }
        if axial_stiffness.is_nan() || axial_stiffness <= 0.0 {
            return Err(CatenaryError::NegativeStiffness {
                value: axial_stiffness,
            });
        }
        Ok(Self {
            weight,
            compliance: 1.0 / axial_stiffness,
        })
    }

    /// A cable of linear density ρ (kg/m) under gravity g (m/s²): w = ρ g.
    pub fn from_density(
        linear_density: f64,
        gravity: f64,
        axial_stiffness: f64,
    ) -> Result<Self, CatenaryError> {
        if !(linear_density.is_finite() && linear_density >= 0.0) {
            return Err(CatenaryError::NegativeDensity {
                value: linear_density,
            });
        }
        Self::new(linear_density * gravity.abs(), axial_stiffness)
    }

    /// w, the weight per unstrained length (N/m).
    pub fn weight(&self) -> f64 {
        self.weight
    }

    /// EA, the axial stiffness (N; infinite for an inextensible cable).
    pub fn axial_stiffness(&self) -> f64 {
        1.0 / self.compliance
    }

    /// The forward map, cancellation-free form (module docs).
    #[inline]
    fn forward(&self, l0: f64, fx: f64, fz: f64) -> Forward {
        let (w, c) = (self.weight, self.compliance);
        let v = fz - w * l0;
        // √(a² + b²) rather than `hypot` (several times faster; forces are far from overflow).
        let tb = (fx * fx + fz * fz).sqrt();
        let ta = (fx * fx + v * v).sqrt();
        let sum = ta + tb;
        let x = if fx > 0.0 {
            // P/Q with P = F_z + T_B, Q = V + T_A formed without subtraction.
            let ratio = match (fz >= 0.0, v >= 0.0) {
                (true, true) => (fz + tb) / (v + ta),
                (false, false) => (ta - v) / (tb - fz),
                _ => (fz + tb) * (ta - v) / (fx * fx),
            };
            let m = (1.0 + ratio) / sum;
            l0 * fx * (c + m * log1p_ratio(w * l0 * m))
        } else {
            0.0
        };
        let z = l0 * (fz + v) * (0.5 * c + 1.0 / sum);
        Forward { x, z, ta, tb }
    }

    /// (x_B, z_B) (m): where a cable of unstrained length `l0` (m) ends when the tension at B is
    /// (F_x, F_z) = (`fx`, `fz`) (N, F_x ≥ 0); Irvine 1981 eqs. (2.29)–(2.30).
    pub fn end_point(&self, l0: f64, fx: f64, fz: f64) -> Vector2<f64> {
        let f = self.forward(l0, fx, fz);
        Vector2::new(f.x, f.z)
    }

    /// T_A = √(F_x² + (F_z − w L0)²): the tension at the frame end (N).
    pub fn frame_end_tension(&self, l0: f64, fx: f64, fz: f64) -> f64 {
        fx.hypot(fz - self.weight * l0)
    }

    /// The point of the (strained) cable at unstrained arc length `s` ∈ [0, L0] from A: the
    /// forward map of the piece [0, s], whose tension at its end is (F_x, F_z − w (L0 − s)).
    pub fn point_at(&self, sol: &CatenarySolution, s: f64) -> Vector2<f64> {
        let vs = sol.vertical_force - self.weight * (sol.unstrained_length - s);
        self.end_point(s, sol.horizontal_force, vs)
    }

    /// The analytic Jacobian ∂(x_B, z_B)/∂(F_x, F_z, L0) (m/N, m/N, m/m): its left 2 × 2 block is
    /// the symmetric flexibility matrix. Kozak, Zhou & Wang 2006, eq. (8), in the
    /// cancellation-free form of the module docs.
    pub fn jacobian(&self, l0: f64, fx: f64, fz: f64) -> Matrix2x3<f64> {
        let f = self.forward(l0, fx, fz);
        self.jacobian_at(l0, fx, fz, &f)
    }

    fn jacobian_at(&self, l0: f64, fx: f64, fz: f64, f: &Forward) -> Matrix2x3<f64> {
        let (w, c) = (self.weight, self.compliance);
        let v = fz - w * l0;
        let (ta, tb) = (f.ta, f.tb);
        let sum = ta + tb;
        // (T_A − T_B)/w = −L0 (F_z + V)/(T_A + T_B).
        let dt_over_w = -l0 * (fz + v) / sum;
        let xz = fx * dt_over_w / (ta * tb);
        // dg = (F_z/T_B − V/T_A)/w, cancellation-free.
        let dg = if fz * v > 0.0 {
            fx * fx * l0 * (fz + v) / ((v * tb + fz * ta) * ta * tb)
        } else if fz == 0.0 && v == 0.0 {
            l0 / tb
        } else {
            l0 * (fz * ta - v * tb) / ((fz - v) * ta * tb)
        };
        // ∂x/∂F_x = L0/EA + Δ/w − dg, Δ/w = x_geom/F_x.
        let x_geom_over_fx = if fx > 0.0 {
            f.x / fx - l0 * c
        } else {
            // F_x → 0 with F_z, V of one sign: Δ/w → (1/w) ln(P/Q) = L0 m φ(w L0 m) in the limit.
            let ratio = if fz >= 0.0 {
                (fz + tb) / (v + ta)
            } else {
                (ta - v) / (tb - fz)
            };
            let m = (1.0 + ratio) / sum;
            l0 * m * log1p_ratio(w * l0 * m)
        };
        Matrix2x3::new(
            l0 * c + x_geom_over_fx - dg,
            xz,
            fx * (c + 1.0 / ta),
            xz,
            l0 * c + dg,
            v * (c + 1.0 / ta),
        )
    }

    /// Residual tolerance (m) for a span of chord `chord`.
    fn tolerance(chord: f64) -> f64 {
        1e-13 * chord.max(1e-3)
    }

    fn check_span(x: f64, z: f64) -> Result<f64, CatenaryError> {
        if !(x.is_finite() && x >= 0.0) {
            return Err(CatenaryError::InvalidInput {
                what: "horizontal span (m, ≥ 0)",
                value: x,
            });
        }
        if !z.is_finite() {
            return Err(CatenaryError::InvalidInput {
                what: "vertical span (m)",
                value: z,
            });
        }
        let chord = x.hypot(z);
        if chord == 0.0 {
            return Err(CatenaryError::InvalidInput {
                what: "chord length (m, > 0)",
                value: chord,
            });
        }
        Ok(chord)
    }

    fn solution(&self, l0: f64, fx: f64, fz: f64, iterations: usize) -> CatenarySolution {
        CatenarySolution {
            unstrained_length: l0,
            horizontal_force: fx,
            vertical_force: fz,
            frame_end_tension: self.frame_end_tension(l0, fx, fz),
            platform_end_tension: fx.hypot(fz),
            iterations,
        }
    }

    /// The end force of a cable of unstrained length `l0` (m) spanning (x_B, z_B) = (`x`, `z`)
    /// (m, x ≥ 0): Newton's method on the flexibility matrix with backtracking (unique
    /// solution: the flexibility matrix is positive definite).
    pub fn solve_for_length(
        &self,
        x: f64,
        z: f64,
        l0: f64,
    ) -> Result<CatenarySolution, CatenaryError> {
        self.solve_for_length_from(x, z, l0, None)
    }

    /// [`ElasticCatenary::solve_for_length`] started from the end force `start` = (F_x, F_z)
    /// (N, F_x > 0) when given: a nearby solution (the previous iterate of an outer loop) makes
    /// Newton's method converge in one or two steps. The solution is the same (unique).
    pub fn solve_for_length_from(
        &self,
        x: f64,
        z: f64,
        l0: f64,
        start: Option<(f64, f64)>,
    ) -> Result<CatenarySolution, CatenaryError> {
        let chord = Self::check_span(x, z)?;
        if !(l0.is_finite() && l0 > 0.0) {
            return Err(CatenaryError::InvalidInput {
                what: "unstrained length (m, > 0)",
                value: l0,
            });
        }
        let (w, c) = (self.weight, self.compliance);
        let unreachable = |reason| CatenaryError::Unreachable {
            horizontal: x,
            vertical: z,
            reason,
        };
        if c == 0.0 && l0 <= chord {
            return Err(unreachable(
                "an inextensible cable must be longer than the chord",
            ));
        }
        if w == 0.0 && l0 >= chord {
            return Err(unreachable(
                "a weightless cable not shorter than the chord is slack",
            ));
        }
        if x <= 1e-12 * chord {
            return self.vertical_for_length(x, z, l0, chord);
        }
        // Start: the larger of the elastic straight cable's horizontal force and the
        // catenary's of Peyrot & Goulois 1979.
        let t_elastic = if c > 0.0 && l0 < chord {
            (chord / l0 - 1.0) / c
        } else {
            0.0
        };
        let lambda = if l0 * l0 <= chord * chord {
            0.2
        } else {
            (3.0 * ((l0 * l0 - z * z) / (x * x) - 1.0)).sqrt().max(0.2)
        };
        let fx_catenary = w * x / (2.0 * lambda);
        let (mut fx, mut fz) = match start {
            Some((fx, fz)) if fx > 0.0 && fx.is_finite() && fz.is_finite() => (fx, fz),
            _ if t_elastic * x / chord >= fx_catenary => {
                (t_elastic * x / chord, t_elastic * z / chord + 0.5 * w * l0)
            }
            _ => (fx_catenary, 0.5 * w * (l0 + z / lambda.tanh())),
        };
        let tol = Self::tolerance(chord);
        let target = Vector2::new(x, z);
        let mut f = self.forward(l0, fx, fz);
        let mut r = Vector2::new(f.x, f.z) - target;
        let mut norm = r.norm();
        let mut refinements = 0;
        for it in 0..100 {
            let j = self.jacobian_at(l0, fx, fz, &f);
            let k = Matrix2::new(j[(0, 0)], j[(0, 1)], j[(1, 0)], j[(1, 1)]);
            let step = k.lu().solve(&r);
            if norm <= tol {
                // The span is met, but the force is only known to ‖r‖/λ_min(K): a nearly
                // straight inextensible cable's flexibility matrix is nearly singular (λ_min ≈
                // 10⁻⁸ m/N for 4 m at 270 N), so 10⁻¹³ of the chord leaves 10⁻⁷ of the force.
                // Full Newton steps refine it while they shrink and do not raise the residual.
                match step {
                    Some(d) if refinements < 4 && d.norm() > 1e-14 * fx.hypot(fz) => {
                        let (nfx, nfz) = (fx - d.x, fz - d.y);
                        let nf = self.forward(l0, nfx, nfz);
                        let nr = Vector2::new(nf.x, nf.z) - target;
                        if nfx > 0.0 && nr.norm() <= norm {
                            (fx, fz, f, r, norm) = (nfx, nfz, nf, nr, nr.norm());
                            refinements += 1;
                            continue;
                        }
                        return Ok(self.solution(l0, fx, fz, it));
                    }
                    _ => return Ok(self.solution(l0, fx, fz, it)),
                }
            }
            let Some(step) = step else { break };
            let mut alpha = 1.0;
            // Keep F_x > 0, then halve until the residual decreases.
            while fx - alpha * step.x <= 0.0 {
                alpha *= 0.5;
            }
            let mut accepted = false;
            for _ in 0..40 {
                let (nfx, nfz) = (fx - alpha * step.x, fz - alpha * step.y);
                let nf = self.forward(l0, nfx, nfz);
                let nr = Vector2::new(nf.x, nf.z) - target;
                let nn = nr.norm();
                if nn.is_finite() && nn < norm {
                    (fx, fz, f, r, norm) = (nfx, nfz, nf, nr, nn);
                    accepted = true;
                    break;
                }
                alpha *= 0.5;
            }
            if !accepted {
                if norm <= 1e3 * tol {
                    return Ok(self.solution(l0, fx, fz, it));
                }
                break;
            }
        }
        if norm <= 1e3 * tol {
            return Ok(self.solution(l0, fx, fz, 100));
        }
        Err(CatenaryError::NotConverged {
            iterations: 100,
            residual: norm,
        })
    }

    /// A vertical span, given L0: F_x = 0, closed form.
    fn vertical_for_length(
        &self,
        x: f64,
        z: f64,
        l0: f64,
        chord: f64,
    ) -> Result<CatenarySolution, CatenaryError> {
        let (w, c) = (self.weight, self.compliance);
        // Taut below A (F_z, V < 0): z = −L0 + c L0 (F_z − w L0/2); above A (V > 0):
        // z = L0 + c L0 (F_z − w L0/2).
        let (fz, ok) = if z < 0.0 {
            let fz = (z + l0) / (c * l0) + 0.5 * w * l0;
            (fz, fz < 0.0)
        } else {
            let fz = (z - l0) / (c * l0) + 0.5 * w * l0;
            (fz, fz - w * l0 > 0.0)
        };
        if !ok || !fz.is_finite() {
            return Err(CatenaryError::Unreachable {
                horizontal: x,
                vertical: z,
                reason: "a vertical cable of this length is slack",
            });
        }
        let _ = chord;
        Ok(self.solution(l0, 0.0, fz, 0))
    }

    /// A vertical span, given the platform-end tension: F_x = 0, L0 from a quadratic (its
    /// smaller root: the taut branch).
    fn vertical_for_tension(
        &self,
        x: f64,
        z: f64,
        t: f64,
    ) -> Result<CatenarySolution, CatenaryError> {
        let (w, c) = (self.weight, self.compliance);
        let b = 1.0 + c * t;
        if z < 0.0 {
            // (c w/2) L0² + (1 + c T) L0 + z = 0.
            let l0 = -2.0 * z / (b + (b * b - 2.0 * c * w * z).sqrt());
            return Ok(self.solution(l0, 0.0, -t, 0));
        }
        // (c w/2) L0² − (1 + c T) L0 + z = 0, and T − w L0 > 0.
        let disc = b * b - 2.0 * c * w * z;
        let l0 = 2.0 * z / (b + disc.max(0.0).sqrt());
        if disc < 0.0 || t - w * l0 <= 0.0 {
            return Err(CatenaryError::Unreachable {
                horizontal: x,
                vertical: z,
                reason: "the tension cannot hold a vertical cable of this height",
            });
        }
        Ok(self.solution(l0, 0.0, t, 0))
    }

    /// The taut catenary spanning (x_B, z_B) = (`x`, `z`) (m, x ≥ 0) with tension `tension` at
    /// B (N, > 0): its unstrained length and end forces. Newton's method on (θ, L0) with
    /// F = T_B (cos θ, sin θ), started on the straight cable and kept on the taut branch
    /// (det ∂(x, z)/∂(θ, L0) < 0, module docs).
    ///
    /// When that fast path fails (heavy cables far from straight), a safeguarded Newton–bisection
    /// on L0 alone decides: T_B(L0), each value from [`ElasticCatenary::solve_for_length`],
    /// decreases from +∞ at the shortest possible cable to a minimum (the fold) and the taut
    /// branch is its first crossing of `tension`; a minimum above `tension` is
    /// [`CatenaryError::Unreachable`].
    pub fn solve_for_tension(
        &self,
        x: f64,
        z: f64,
        tension: f64,
    ) -> Result<CatenarySolution, CatenaryError> {
        self.solve_for_tension_from(x, z, tension, None)
    }

    /// [`ElasticCatenary::solve_for_tension`] with Newton's method started from `start` (a
    /// nearby taut solution: the previous iterate of an outer loop, whose angle and unstrained
    /// length it reuses) instead of the straight cable. The fallback and the answer are the
    /// same: the start is kept only while Newton stays on the taut branch.
    pub fn solve_for_tension_from(
        &self,
        x: f64,
        z: f64,
        tension: f64,
        start: Option<&CatenarySolution>,
    ) -> Result<CatenarySolution, CatenaryError> {
        let chord = Self::check_span(x, z)?;
        self.solve_for_tension_checked(x, z, chord, tension, start)
    }

    /// [`ElasticCatenary::solve_for_tension_from`] on a span checked by `check_span`, whose
    /// chord (m) it was given.
    fn solve_for_tension_checked(
        &self,
        x: f64,
        z: f64,
        chord: f64,
        tension: f64,
        start: Option<&CatenarySolution>,
    ) -> Result<CatenarySolution, CatenaryError> {
        if !(tension.is_finite() && tension >= 0.0) {
            return Err(CatenaryError::InvalidInput {
                what: "platform-end tension (N, ≥ 0)",
                value: tension,
            });
        }
        if tension == 0.0 {
            // A slack weightless cable is straight at its natural length; a heavy one cannot
            // reach B without tension.
            if self.weight == 0.0 {
                return Ok(self.solution(chord, 0.0, 0.0, 0));
            }
            return Err(CatenaryError::Unreachable {
                horizontal: x,
                vertical: z,
                reason: "a heavy cable needs tension to reach the platform",
            });
        }
        if x <= 1e-12 * chord {
            return self.vertical_for_tension(x, z, tension);
        }
        let warm = start
            .filter(|s| {
                s.horizontal_force > 0.0
                    && s.unstrained_length > 0.0
                    && s.platform_end_tension.is_finite()
            })
            .map(|s| {
                // T_B = √(F_x² + F_z²) of that solution: its direction (cos θ, sin θ).
                let norm = s.platform_end_tension;
                (
                    (s.horizontal_force / norm, s.vertical_force / norm),
                    s.unstrained_length,
                )
            });
        if let Some(w) = warm
            && let Ok(sol) = self.tension_newton(x, z, tension, chord, Some(w))
        {
            return Ok(sol);
        }
        match self.tension_newton(x, z, tension, chord, None) {
            Ok(sol) => Ok(sol),
            Err(_) => self.tension_by_length(x, z, tension, chord),
        }
    }

    /// The safeguarded one-dimensional search on L0 of [`ElasticCatenary::solve_for_tension`].
    fn tension_by_length(
        &self,
        x: f64,
        z: f64,
        t: f64,
        chord: f64,
    ) -> Result<CatenarySolution, CatenaryError> {
        self.length_search(x, z, t, chord).map_err(|e| match e {
            SearchEnd::Failed(e) => e,
            SearchEnd::Fold(_) => CatenaryError::Unreachable {
                horizontal: x,
                vertical: z,
                reason: "the platform-end tension is too small to hold the cable across the span",
            },
        })
    }

    /// The least platform-end tension (N) with which a taut cable of this model spans
    /// (x_B, z_B): the fold of T_B(L0) (module docs). Any tension above it is reachable on the
    /// taut branch. Zero for a weightless cable or a vertical span hanging down.
    pub fn least_tension(&self, x: f64, z: f64) -> Result<f64, CatenaryError> {
        let chord = Self::check_span(x, z)?;
        if self.weight == 0.0 || (x <= 1e-12 * chord && z < 0.0) {
            return Ok(0.0);
        }
        if x <= 1e-12 * chord {
            // Straight up: T_B > w L0 with L0 the smaller root (module docs); at the limit
            // T_B = w L0(T_B), solved by a few fixed-point steps from the inextensible w z.
            let mut t = self.weight * z;
            for _ in 0..100 {
                let b = 1.0 + self.compliance * t;
                let l0 = 2.0 * z
                    / (b + (b * b - 2.0 * self.compliance * self.weight * z)
                        .max(0.0)
                        .sqrt());
                let next = self.weight * l0;
                if (next - t).abs() <= 1e-15 * t {
                    break;
                }
                t = next;
            }
            return Ok(t);
        }
        match self.length_search(x, z, 0.0, chord) {
            Err(SearchEnd::Fold(t)) => Ok(t),
            Err(SearchEnd::Failed(e)) => Err(e),
            Ok(sol) => Ok(sol.platform_end_tension),
        }
    }

    /// Safeguarded Newton–bisection on L0 for T_B(L0) = t on the taut branch; ends at the fold
    /// (with the least T_B) when t is below it.
    fn length_search(
        &self,
        x: f64,
        z: f64,
        t: f64,
        chord: f64,
    ) -> Result<CatenarySolution, SearchEnd> {
        let c = self.compliance;
        // T_B → ∞ as L0 → lo (the chord for an inextensible cable, 0 otherwise).
        let mut lo = if c == 0.0 { chord } else { 0.0 };
        let mut hi = f64::INFINITY;
        let mut bracketed = false;
        let mut l0 = if c == 0.0 {
            chord * (1.0 + 1e-3)
        } else {
            chord / (1.0 + c * t)
        };
        if self.weight == 0.0 {
            return self.solve_for_length(x, z, l0).map_err(SearchEnd::Failed);
        }
        let mut least = f64::INFINITY;
        // The solve with the smallest |T_B − t| so far.
        let mut best = None;
        for it in 0..200 {
            let sol = self.solve_for_length(x, z, l0).map_err(SearchEnd::Failed)?;
            least = least.min(sol.platform_end_tension);
            let g = sol.platform_end_tension - t;
            if g.abs() <= 1e-12 * t {
                return Ok(CatenarySolution {
                    iterations: it,
                    ..sol
                });
            }
            if best.is_none_or(|(b, _): (f64, CatenarySolution)| g.abs() < b) {
                best = Some((g.abs(), sol));
            }
            // dT_B/dL0 = (F/T_B) · dF/dL0, dF/dL0 = −K⁻¹ ∂(x, z)/∂L0 (span fixed).
            let (fx, fz) = (sol.horizontal_force, sol.vertical_force);
            let j = self.jacobian(l0, fx, fz);
            let k = Matrix2::new(j[(0, 0)], j[(0, 1)], j[(1, 0)], j[(1, 1)]);
            let df = k
                .lu()
                .solve(&Vector2::new(j[(0, 2)], j[(1, 2)]))
                .map(|d| -d)
                .unwrap_or_else(Vector2::zeros);
            let dg = (fx * df.x + fz * df.y) / sol.platform_end_tension;
            let decreasing = dg < 0.0;
            if decreasing && g > 0.0 {
                lo = l0;
            } else {
                hi = l0;
                bracketed |= decreasing;
            }
            let newton = if decreasing { l0 - g / dg } else { f64::NAN };
            l0 = if newton > lo && newton < hi {
                newton
            } else if hi.is_finite() {
                0.5 * (lo + hi)
            } else {
                2.0 * l0
            };
            if hi.is_finite() && hi - lo <= 1e-13 * hi {
                if bracketed {
                    // T_B crosses t between two lengths a few ulps apart: where T_B(L0) is
                    // steep (a heavy cable hanging nearly straight down, dT_B/dL0 ≈ 10⁴ N/m)
                    // one ulp of L0 moves T_B by more than 10⁻¹² t. The closer end is the root.
                    // Unless no length resolves t (a cable along the vertical, whose T_B jumps
                    // by more than 10⁻⁹ t per ulp of L0).
                    if let Some((gap, sol)) = best {
                        if gap <= 1e-9 * t {
                            return Ok(CatenarySolution {
                                iterations: it,
                                ..sol
                            });
                        }
                        return Err(SearchEnd::Failed(CatenaryError::Unresolvable {
                            tension: t,
                            closest: sol.platform_end_tension,
                        }));
                    }
                }
                // Converged on the fold with T_B > T: no taut catenary.
                break;
            }
        }
        Err(SearchEnd::Fold(least))
    }

    /// Newton's method on (θ, L0) from the straight cable (the fast path). The angle θ of
    /// F = T_B (cos θ, sin θ) is carried as (cos θ, sin θ); a step δ along θ moves it to
    /// (cos θ − δ sin θ, sin θ + δ cos θ)/√(1 + δ²), the angle θ + atan δ (= θ + δ + O(δ³):
    /// Newton's quadratic convergence is kept, without a sine, cosine or arctangent per step).
    fn tension_newton(
        &self,
        x: f64,
        z: f64,
        tension: f64,
        chord: f64,
        start: Option<((f64, f64), f64)>,
    ) -> Result<CatenarySolution, CatenaryError> {
        let (w, c, t) = (self.weight, self.compliance, tension);
        let target = Vector2::new(x, z);
        let ((mut co, mut s), mut l0) = match start {
            Some(s) => s,
            None => {
                // The straight cable, its end force tilted by half the weight.
                let l0 = chord / (1.0 + c * t);
                let sin0 = (z / chord + 0.5 * w * l0 / t).clamp(-0.999, 0.999);
                (((1.0 - sin0 * sin0).sqrt(), sin0), l0)
            }
        };
        let eval = |co: f64, s: f64, l0: f64| {
            let f = self.forward(l0, t * co, t * s);
            (f, Vector2::new(f.x, f.z) - target)
        };
        // The solution at (θ, L0): T_B is the tension given, T_A the forward map's.
        let solved = |l0: f64, co: f64, s: f64, f: &Forward, iterations| CatenarySolution {
            unstrained_length: l0,
            horizontal_force: t * co,
            vertical_force: t * s,
            frame_end_tension: f.ta,
            platform_end_tension: t,
            iterations,
        };
        let tol = Self::tolerance(chord);
        let (mut f, mut r) = eval(co, s, l0);
        let mut norm = r.norm();
        let unreachable = CatenaryError::Unreachable {
            horizontal: x,
            vertical: z,
            reason: "the platform-end tension is too small to hold the cable across the span",
        };
        for it in 0..100 {
            if norm <= tol {
                return Ok(solved(l0, co, s, &f, it));
            }
            let jf = self.jacobian_at(l0, t * co, t * s, &f);
            let dth = Vector2::new(
                t * (-s * jf[(0, 0)] + co * jf[(0, 1)]),
                t * (-s * jf[(1, 0)] + co * jf[(1, 1)]),
            );
            let dl = Vector2::new(jf[(0, 2)], jf[(1, 2)]);
            let det = dth.x * dl.y - dth.y * dl.x;
            if det >= 0.0 || !det.is_finite() {
                // Past the fold: the taut branch has no solution here.
                return Err(unreachable);
            }
            // Solve [dth dl] (δθ, δL0) = r.
            let d_theta = (r.x * dl.y - r.y * dl.x) / det;
            let d_l0 = (dth.x * r.y - dth.y * r.x) / det;
            let mut alpha = 1.0;
            let mut accepted = false;
            for _ in 0..40 {
                let delta = -alpha * d_theta;
                let scale = 1.0 / (1.0 + delta * delta).sqrt();
                let (nco, ns) = ((co - delta * s) * scale, (s + delta * co) * scale);
                let nl0 = l0 - alpha * d_l0;
                // |θ| < π/2: the force keeps pointing away from A horizontally.
                if nl0 > 0.0 && nco > 0.0 {
                    let (nf, nr) = eval(nco, ns, nl0);
                    let nn = nr.norm();
                    if nn.is_finite() && nn < norm {
                        (co, s, l0, f, r, norm) = (nco, ns, nl0, nf, nr, nn);
                        accepted = true;
                        break;
                    }
                }
                alpha *= 0.5;
            }
            if !accepted {
                if norm <= 1e3 * tol {
                    return Ok(solved(l0, co, s, &f, it));
                }
                // Newton stalls against the fold when the tension is too low.
                return Err(if w > 0.0 {
                    unreachable
                } else {
                    CatenaryError::NotConverged {
                        iterations: it,
                        residual: norm,
                    }
                });
            }
        }
        Err(CatenaryError::NotConverged {
            iterations: 100,
            residual: norm,
        })
    }

    /// The largest distance of the cable below its chord (m), and the angle between the
    /// cable's tangent at B and the chord (rad). The deepest point is where the tangent is
    /// parallel to the chord: V(s) = F_x z_B/x_B, s = (F_x z_B/x_B − V_A)/w.
    pub fn sag(&self, sol: &CatenarySolution, x: f64, z: f64) -> (f64, f64) {
        self.sag_with_chord(sol, x, z, x.hypot(z))
    }

    /// [`ElasticCatenary::sag`] with the chord √(x² + z²) (m) already known.
    fn sag_with_chord(&self, sol: &CatenarySolution, x: f64, z: f64, chord: f64) -> (f64, f64) {
        let (fx, fz) = (sol.horizontal_force, sol.vertical_force);
        let angle = (fx * z - fz * x).abs().atan2(fx * x + fz * z);
        if self.weight == 0.0 || x == 0.0 || chord == 0.0 {
            return (0.0, angle);
        }
        let va = fz - self.weight * sol.unstrained_length;
        let s = ((fx * z / x - va) / self.weight).clamp(0.0, sol.unstrained_length);
        let p = self.point_at(sol, s);
        ((p.x * z - p.y * x) / chord, angle)
    }
}

/// A cable of a robot in three dimensions as an elastic catenary: the span from the frame exit
/// point A to the attachment B split into its vertical plane (`up`, a unit vector against
/// gravity).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SaggingCable {
    /// L0: unstrained length (m); with a pulley the whole cable's, the wrapped arc included
    /// (ρ β/(1 + T_A/EA) plus the free segment's `solution.unstrained_length`).
    pub unstrained_length: f64,
    /// ‖B − A‖: the chord (m); with a pulley that of the free segment, from the tangent point.
    pub chord_length: f64,
    /// ρ β: the arc wrapped on the cable's pulley (m; 0 without a pulley). A frictionless
    /// pulley carries the frame-end tension T_A of the free segment along the whole arc.
    pub wrapped_length: f64,
    /// T_A (N).
    pub frame_end_tension: f64,
    /// T_B (N).
    pub platform_end_tension: f64,
    /// The smallest tension along the cable (N): F_x where the tangent turns horizontal
    /// inside the span, else the smaller end tension.
    pub lowest_tension: f64,
    /// Largest distance below the chord (m).
    pub max_sag: f64,
    /// Angle between the cable at B and the chord (rad).
    pub angle_to_chord: f64,
    /// The unit force the cable applies to the platform at B (towards the cable, base
    /// coordinates): the column direction of the sag-aware wrench matrix.
    pub unit: Vector3<f64>,
    /// The plane solution (with a pulley, of the free segment from the tangent point to B).
    pub solution: CatenarySolution,
}

impl SaggingCable {
    /// The catenary from `frame_point` A to `attachment_point` B (m, base coordinates) with
    /// tension `tension` at B (N): taut branch of [`ElasticCatenary::solve_for_tension`].
    pub fn with_tension(
        model: &ElasticCatenary,
        frame_point: &Vector3<f64>,
        attachment_point: &Vector3<f64>,
        up: &Vector3<f64>,
        tension: f64,
    ) -> Result<Self, CatenaryError> {
        Self::with_tension_from(model, frame_point, attachment_point, up, tension, None)
    }

    /// [`SaggingCable::with_tension`] warm-started from a nearby solution
    /// ([`ElasticCatenary::solve_for_tension_from`]).
    pub fn with_tension_from(
        model: &ElasticCatenary,
        frame_point: &Vector3<f64>,
        attachment_point: &Vector3<f64>,
        up: &Vector3<f64>,
        tension: f64,
        start: Option<&CatenarySolution>,
    ) -> Result<Self, CatenaryError> {
        let (x, z, horizontal) = plane_span(frame_point, attachment_point, up);
        let sol = model.solve_for_tension_from(x, z, tension, start)?;
        Ok(Self::from_solution(model, &sol, x, z, &horizontal, up))
    }

    /// The catenary from A to B of unstrained length `l0` (m).
    pub fn with_length(
        model: &ElasticCatenary,
        frame_point: &Vector3<f64>,
        attachment_point: &Vector3<f64>,
        up: &Vector3<f64>,
        l0: f64,
    ) -> Result<Self, CatenaryError> {
        let (x, z, horizontal) = plane_span(frame_point, attachment_point, up);
        let sol = model.solve_for_length(x, z, l0)?;
        Ok(Self::from_solution(model, &sol, x, z, &horizontal, up))
    }

    /// `count` ≥ 2 points of the cable from its frame point A to its attachment B (m, base
    /// coordinates), evenly spaced in unstrained arc length: point k is A plus the forward map
    /// of the piece [0, s_k] of the catenary ([`ElasticCatenary::point_at`], Irvine 1981
    /// eqs. (2.29)–(2.30)) in the cable's vertical plane, `up` the unit vertical. For drawing
    /// a sagging cable (the HTML viewer and the 3-D plots).
    pub fn polyline(
        &self,
        model: &ElasticCatenary,
        frame_point: &Vector3<f64>,
        attachment_point: &Vector3<f64>,
        up: &Vector3<f64>,
        count: usize,
    ) -> Vec<Vector3<f64>> {
        let (_, _, horizontal) = plane_span(frame_point, attachment_point, up);
        let count = count.max(2);
        let l0 = self.solution.unstrained_length;
        (0..count)
            .map(|k| {
                if k + 1 == count {
                    return *attachment_point;
                }
                let p = model.point_at(&self.solution, l0 * k as f64 / (count - 1) as f64);
                frame_point + horizontal * p.x + up * p.y
            })
            .collect()
    }

    pub(crate) fn from_solution(
        model: &ElasticCatenary,
        sol: &CatenarySolution,
        x: f64,
        z: f64,
        horizontal: &Vector3<f64>,
        up: &Vector3<f64>,
    ) -> Self {
        let mut cable = Self::forces_with_chord(model, sol, x, z, x.hypot(z), horizontal, up);
        cable.fill_sag(model, x, z);
        cable
    }

    /// [`SaggingCable::from_solution`] without the sag (`max_sag` and `angle_to_chord` NaN),
    /// the chord √(x² + z²) (m) known.
    fn forces_with_chord(
        model: &ElasticCatenary,
        sol: &CatenarySolution,
        x: f64,
        z: f64,
        chord_length: f64,
        horizontal: &Vector3<f64>,
        up: &Vector3<f64>,
    ) -> Self {
        let t = sol.platform_end_tension;
        let v_a = sol.vertical_force - model.weight() * sol.unstrained_length;
        let lowest_tension = if v_a < 0.0 && sol.vertical_force > 0.0 {
            sol.horizontal_force
        } else {
            sol.frame_end_tension.min(t)
        };
        let unit = if t > 0.0 {
            -(horizontal * sol.horizontal_force + up * sol.vertical_force) / t
        } else {
            // No force: the chord's direction (towards A) keeps W's column defined.
            -(horizontal * x + up * z) / chord_length
        };
        Self {
            unstrained_length: sol.unstrained_length,
            chord_length,
            frame_end_tension: sol.frame_end_tension,
            platform_end_tension: t,
            lowest_tension,
            max_sag: f64::NAN,
            angle_to_chord: f64::NAN,
            unit,
            wrapped_length: 0.0,
            solution: *sol,
        }
    }

    /// The cable wrapped by the arc ρ β = `arc` (m) on a frictionless pulley before its free
    /// segment: the arc, stretched under the free segment's frame-end tension T_A, adds
    /// ρ β/(1 + T_A/EA) to the unstrained length (issue 29; docs/algorithms.md, "Elastic
    /// cables over pulleys").
    pub(crate) fn wrapped(mut self, model: &ElasticCatenary, arc: f64) -> Self {
        self.wrapped_length = arc;
        self.unstrained_length += arc / (1.0 + model.compliance * self.frame_end_tension);
        self
    }

    /// `max_sag` and `angle_to_chord` from the solution and the plane span (x, z).
    fn fill_sag(&mut self, model: &ElasticCatenary, x: f64, z: f64) {
        (self.max_sag, self.angle_to_chord) =
            model.sag_with_chord(&self.solution, x, z, self.chord_length);
    }
}

/// (x_B, z_B, ê_h): the span of A → B in the vertical plane and its horizontal unit vector
/// (zero for a vertical span).
pub fn plane_span(
    frame_point: &Vector3<f64>,
    attachment_point: &Vector3<f64>,
    up: &Vector3<f64>,
) -> (f64, f64, Vector3<f64>) {
    let d = attachment_point - frame_point;
    let z = d.dot(up);
    let h = d - up * z;
    let x = h.norm();
    let e = if x > 0.0 { h / x } else { Vector3::zeros() };
    (x, z, e)
}

/// How cables are modelled (the CLI's `--cable-model`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CableModel {
    /// Massless, inextensible straight segments (the classical model).
    #[default]
    Straight,
    /// Massless elastic straight cables: L0 = l/(1 + t/EA) (needs `axial_stiffness`).
    Elastic,
    /// Heavy elastic cables: Irvine's elastic catenary (needs `axial_stiffness` and
    /// `linear_density`).
    Catenary,
}

impl CableModel {
    /// The command-line spelling.
    pub fn name(self) -> &'static str {
        match self {
            Self::Straight => "straight",
            Self::Elastic => "elastic",
            Self::Catenary => "catenary",
        }
    }
}

impl std::str::FromStr for CableModel {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "straight" => Ok(Self::Straight),
            "elastic" => Ok(Self::Elastic),
            "catenary" => Ok(Self::Catenary),
            _ => Err(format!(
                "unknown cable model `{s}` (expected straight, elastic or catenary)"
            )),
        }
    }
}

/// Every cable of a robot as an [`ElasticCatenary`], and the vertical: the sag-aware
/// inverse kinematics of a pose (issue 29).
///
/// ```
/// use cdpr_kinematics::catenary::RobotCatenaries;
/// use cdpr_kinematics::nalgebra::Vector3;
/// use cdpr_kinematics::reference_robots::ipanema_like_8;
/// use cdpr_kinematics::Pose;
/// let robot = ipanema_like_8();
/// // 20 g/m, E·S = 60 kN, gravity 9.81 m/s² along −z.
/// let model = RobotCatenaries::new(&[0.02; 8], &[6e4; 8], &Vector3::new(0.0, 0.0, -9.81)).unwrap();
/// let kin = robot.inverse_kinematics(&Pose::spatial(Vector3::new(0.0, 0.0, 1.0), 0.0, 0.0, 0.0)).unwrap();
/// let mut cables = Vec::new();
/// model.with_tensions(&kin, &[100.0; 8], &mut cables).unwrap();
/// // A cable stretches under 100 N and sags: L0 < chord.
/// assert!(cables.iter().all(|c| c.unstrained_length < c.chord_length && c.max_sag > 0.0));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct RobotCatenaries {
    cables: Vec<ElasticCatenary>,
    up: Vector3<f64>,
}

impl RobotCatenaries {
    /// Per cable the linear density ρ (kg/m, ≥ 0) and axial stiffness EA (N, > 0, may be
    /// infinite); `gravity` (m/s², base coordinates) gives w = ρ ‖g‖ and the vertical
    /// −g/‖g‖. Errors name the cable; a zero gravity with a heavy cable is an error.
    pub fn new(
        linear_density: &[f64],
        axial_stiffness: &[f64],
        gravity: &Vector3<f64>,
    ) -> Result<Self, crate::KinematicsError> {
        if linear_density.len() != axial_stiffness.len() {
            return Err(crate::KinematicsError::WrongDimension {
                what: "axial stiffnesses (one per linear density)".into(),
                motion: "any",
                expected: linear_density.len(),
                found: axial_stiffness.len(),
            });
        }
        let g = gravity.norm();
        if !g.is_finite() || (g == 0.0 && linear_density.iter().any(|&r| r != 0.0)) {
            return Err(crate::KinematicsError::InvalidSetting {
                what: "gravity (m/s², finite and non-zero for heavy cables)",
                value: g,
            });
        }
        let cables = linear_density
            .iter()
            .zip(axial_stiffness)
            .enumerate()
            .map(|(cable, (&rho, &ea))| {
                ElasticCatenary::from_density(rho, g, ea)
                    .map_err(|source| crate::KinematicsError::Catenary { cable, source })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let up = if g > 0.0 { -gravity / g } else { Vector3::z() };
        Ok(Self { cables, up })
    }

    /// Weightless elastic cables (`--cable-model elastic`): ρ = 0.
    pub fn elastic(axial_stiffness: &[f64]) -> Result<Self, crate::KinematicsError> {
        Self::new(
            &vec![0.0; axial_stiffness.len()],
            axial_stiffness,
            &Vector3::zeros(),
        )
    }

    /// The cables' models, in order.
    pub fn cables(&self) -> &[ElasticCatenary] {
        &self.cables
    }

    /// The unit vertical (against gravity).
    pub fn up(&self) -> Vector3<f64> {
        self.up
    }

    /// Frame exit point A and attachment B of cable i at a pose (with a pulley, A is the
    /// tangent point of the straight model).
    fn ends(kin: &crate::PoseKinematics, i: usize) -> (Vector3<f64>, Vector3<f64>) {
        let c = &kin.cables()[i];
        (c.attachment_point + c.vector, c.attachment_point)
    }

    /// ρ β, the arc wrapped on cable i's pulley (m; the pulley model's length minus its free
    /// length), `None` without a pulley.
    fn arc(kin: &crate::PoseKinematics, i: usize) -> Option<f64> {
        kin.pulley(i)
            .map(|p| (kin.cables()[i].length - p.free_length).max(0.0))
    }

    /// An error naming the first heavy cable (w > 0) that runs over a pulley (`has_pulley(i)`):
    /// the elastic catenary over a pulley is not modelled.
    pub(crate) fn check_pulleys(
        &self,
        has_pulley: impl Fn(usize) -> bool,
    ) -> Result<(), crate::KinematicsError> {
        match self
            .cables
            .iter()
            .enumerate()
            .find(|(i, c)| c.weight > 0.0 && has_pulley(*i))
        {
            Some((cable, _)) => Err(crate::KinematicsError::UnsupportedPulley {
                cable,
                reason: "the elastic catenary (a heavy cable) over a pulley is not modelled; use the elastic model (no cable weight) or the robot without pulleys",
            }),
            None => Ok(()),
        }
    }

    fn check_count(
        &self,
        kin: &crate::PoseKinematics,
        given: usize,
    ) -> Result<(), crate::KinematicsError> {
        if kin.cable_count() == self.cables.len() {
            self.check_pulleys(|i| kin.pulley(i).is_some())?;
        }
        for (what, found) in [
            ("cable models", self.cables.len()),
            ("tensions or lengths", given),
        ] {
            if found != kin.cable_count() {
                return Err(crate::KinematicsError::WrongDimension {
                    what: what.into(),
                    motion: kin.motion().name(),
                    expected: kin.cable_count(),
                    found,
                });
            }
        }
        Ok(())
    }

    /// Each cable's catenary at the pose of `kin` with platform-end tensions `tensions` (N),
    /// written into `out` (resized; no allocation once it has the capacity).
    pub fn with_tensions(
        &self,
        kin: &crate::PoseKinematics,
        tensions: &[f64],
        out: &mut Vec<SaggingCable>,
    ) -> Result<(), crate::KinematicsError> {
        self.check_count(kin, tensions.len())?;
        out.clear();
        for (i, (model, &t)) in self.cables.iter().zip(tensions).enumerate() {
            let (a, b) = Self::ends(kin, i);
            let mut s = SaggingCable::with_tension(model, &a, &b, &self.up, t)
                .map_err(|source| crate::KinematicsError::Catenary { cable: i, source })?;
            if let Some(arc) = Self::arc(kin, i) {
                s = s.wrapped(model, arc);
            }
            out.push(s);
        }
        Ok(())
    }

    /// [`RobotCatenaries::with_tensions`], each cable's solve started from its catenary in
    /// `previous` (the last iterate of a fixed point at the same pose; ignored unless it has one
    /// entry per cable).
    pub fn with_tensions_from(
        &self,
        kin: &crate::PoseKinematics,
        tensions: &[f64],
        previous: &[SaggingCable],
        out: &mut Vec<SaggingCable>,
    ) -> Result<(), crate::KinematicsError> {
        self.forces_with_tensions_from(kin, tensions, previous, out)?;
        self.fill_sag(kin, out);
        Ok(())
    }

    /// [`RobotCatenaries::with_tensions_from`] without the sag, for the iterations of a fixed
    /// point that only need the end forces: `max_sag` and `angle_to_chord` are NaN until
    /// [`RobotCatenaries::fill_sag`] (the other fields are those of `with_tensions_from`, bit
    /// for bit).
    pub fn forces_with_tensions_from(
        &self,
        kin: &crate::PoseKinematics,
        tensions: &[f64],
        previous: &[SaggingCable],
        out: &mut Vec<SaggingCable>,
    ) -> Result<(), crate::KinematicsError> {
        self.check_count(kin, tensions.len())?;
        let warm = previous.len() == tensions.len();
        out.clear();
        for (i, (model, &t)) in self.cables.iter().zip(tensions).enumerate() {
            let (a, b) = Self::ends(kin, i);
            let start = warm.then(|| &previous[i].solution);
            let (x, z, horizontal) = plane_span(&a, &b, &self.up);
            let sol = ElasticCatenary::check_span(x, z)
                .and_then(|chord| {
                    let sol = model.solve_for_tension_checked(x, z, chord, t, start)?;
                    Ok(SaggingCable::forces_with_chord(
                        model,
                        &sol,
                        x,
                        z,
                        chord,
                        &horizontal,
                        &self.up,
                    ))
                })
                .map_err(|source| crate::KinematicsError::Catenary { cable: i, source })?;
            out.push(match Self::arc(kin, i) {
                Some(arc) => sol.wrapped(model, arc),
                None => sol,
            });
        }
        Ok(())
    }

    /// Fills `max_sag` and `angle_to_chord` of `cables`, the catenaries of the cables of this
    /// model at the pose of `kin` (as [`RobotCatenaries::forces_with_tensions_from`] leaves
    /// them).
    pub fn fill_sag(&self, kin: &crate::PoseKinematics, cables: &mut [SaggingCable]) {
        for (i, (model, cable)) in self.cables.iter().zip(cables.iter_mut()).enumerate() {
            let (a, b) = Self::ends(kin, i);
            let (x, z, _) = plane_span(&a, &b, &self.up);
            cable.fill_sag(model, x, z);
        }
    }

    /// Each cable's catenary at the pose of `kin` with unstrained lengths `lengths` (m). With a
    /// pulley (weightless cables only) the length is the whole cable's: the tension
    /// T = EA (l/L0 − 1) is the same along it, so the free segment of length l_f has the
    /// unstrained length L0 l_f/l.
    pub fn with_lengths(
        &self,
        kin: &crate::PoseKinematics,
        lengths: &[f64],
        out: &mut Vec<SaggingCable>,
    ) -> Result<(), crate::KinematicsError> {
        self.check_count(kin, lengths.len())?;
        out.clear();
        for (i, (model, &l0)) in self.cables.iter().zip(lengths).enumerate() {
            let (a, b) = Self::ends(kin, i);
            let arc = Self::arc(kin, i);
            let free = match arc {
                Some(_) => l0 * kin.free_length(i) / kin.cables()[i].length,
                None => l0,
            };
            let mut s = SaggingCable::with_length(model, &a, &b, &self.up, free)
                .map_err(|source| crate::KinematicsError::Catenary { cable: i, source })?;
            if let Some(arc) = arc {
                s = s.wrapped(model, arc);
                s.unstrained_length = l0;
            }
            out.push(s);
        }
        Ok(())
    }
}

/// The sag-aware wrench matrix: column i is [u_i; a_i × u_i] (restricted to the motion
/// pattern's components) with u_i the unit force of the catenary at the platform
/// ([`SaggingCable::unit`]) instead of the chord direction. Resized only if its shape differs.
pub fn write_sagging_wrench_matrix(
    kin: &crate::PoseKinematics,
    cables: &[SaggingCable],
    w: &mut nalgebra::DMatrix<f64>,
) {
    let (dof, n) = (kin.motion().dof(), kin.cable_count());
    if w.shape() != (dof, n) {
        *w = nalgebra::DMatrix::zeros(dof, n);
    }
    for (i, (c, s)) in kin.cables().iter().zip(cables).enumerate() {
        let (u, a) = (&s.unit, &c.attachment);
        let mut col = w.column_mut(i);
        match kin.motion() {
            crate::MotionPattern::Point2 => {
                (col[0], col[1]) = (u.x, u.y);
            }
            crate::MotionPattern::Planar => {
                (col[0], col[1], col[2]) = (u.x, u.y, a.x * u.y - a.y * u.x);
            }
            crate::MotionPattern::Point3 => {
                (col[0], col[1], col[2]) = (u.x, u.y, u.z);
            }
            crate::MotionPattern::Spatial => {
                let m = a.cross(u);
                (col[0], col[1], col[2]) = (u.x, u.y, u.z);
                (col[3], col[4], col[5]) = (m.x, m.y, m.z);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn issue_example() {
        let cable = ElasticCatenary::new(0.5, 1e6).unwrap();
        let b = cable.end_point(11.0, 100.0, -50.0);
        assert!((b.x - 9.730114663).abs() < 5e-10, "{}", b.x);
        assert!((b.y + 5.131623707).abs() < 5e-10, "{}", b.y);
        let ta = cable.frame_end_tension(11.0, 100.0, -50.0);
        assert!((ta - 114.3689).abs() < 5e-5, "{ta}");
    }

    #[test]
    fn weightless_limit_is_the_elastic_straight_cable() {
        let ea = 2e4;
        let cable = ElasticCatenary::new(0.0, ea).unwrap();
        let (fx, fz, l0) = (30.0, -40.0, 2.0);
        let b = cable.end_point(l0, fx, fz);
        let stretch = l0 * (1.0 + 50.0 / ea);
        assert!((b.x - stretch * 0.6).abs() < 1e-15 && (b.y + stretch * 0.8).abs() < 1e-15);
        let sol = cable.solve_for_tension(b.x, b.y, 50.0).unwrap();
        assert!((sol.unstrained_length - l0).abs() < 1e-13);
        // L0 = l/(1 + t/EA).
        assert!((sol.unstrained_length - b.norm() / (1.0 + 50.0 / ea)).abs() < 1e-13);
    }

    #[test]
    fn bad_input_is_an_error() {
        assert!(matches!(
            ElasticCatenary::new(-1.0, 1.0),
            Err(CatenaryError::NegativeDensity { .. })
        ));
        assert!(matches!(
            ElasticCatenary::new(1.0, -1.0),
            Err(CatenaryError::NegativeStiffness { .. })
        ));
        assert!(ElasticCatenary::new(1.0, f64::INFINITY).is_ok());
        let c = ElasticCatenary::new(1.0, f64::INFINITY).unwrap();
        assert!(matches!(
            c.solve_for_length(3.0, 4.0, 5.0),
            Err(CatenaryError::Unreachable { .. })
        ));
        assert!(matches!(
            c.solve_for_tension(f64::NAN, 4.0, 5.0),
            Err(CatenaryError::InvalidInput { .. })
        ));
        // 10 m of 1 N/m cable across 10 m cannot hang from 0.1 N.
        assert!(matches!(
            c.solve_for_tension(10.0, 0.0, 0.1),
            Err(CatenaryError::Unreachable { .. })
        ));
    }
}
