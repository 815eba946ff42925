//! # Identifiability: the counting rule
//!
//! k samples of n cable lengths on a robot with d degrees of freedom give k n equations. With
//! unknown poses, each sample spends d of them on its pose, so p parameters with a gauge of g
//! (coordinates no length can see, [`crate::gauge`]) are identifiable only if
//!
//! ```text
//!   k (n − d) ≥ p − g
//! ```
//!
//! and the Jacobian then has full rank p − g + k d (checked numerically at the solution:
//! [`crate::covariance`]). With known poses the rule reads k n ≥ p, cable by cable k ≥ p_i
//! (each cable's parameters enter its own lengths only). A robot with as many cables as DOF
//! (n = d) can never self-calibrate: every sample's lengths are used up by its pose.
//!
//! ## References
//! - Borgstrom et al. 2009, *NIMS-PL: a cable-driven robot with self-calibration
//!   capabilities*, IEEE T-RO 25(5) (the counting argument).
//! - Miermeister & Pott 2012, *Auto-calibration method for overconstrained cable-driven
//!   parallel robots*, ICRA.

/// The counting rule's verdict before any fitting.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Counting {
    /// Unknown parameters p (gauge included).
    pub parameters: usize,
    /// Gauge g: coordinates fixed because no length can see them.
    pub gauge: usize,
    /// Equations k n.
    pub equations: usize,
    /// Unknowns p − g + k d (k d the unknown poses; 0 with known poses).
    pub unknowns: usize,
    /// Whether the count allows identification.
    pub holds: bool,
    /// Smallest k for which the count holds (`None`: never, n = d with unknown poses).
    pub samples_needed: Option<usize>,
    /// Why not, in words (`None` when it holds).
    pub reason: Option<String>,
}

/// The counting rule for k samples of n cables, d DOF, p parameters (gauge g), unknown poses
/// or known ones.
///
/// ```
/// use cdpr_calibration::identifiability::counting_rule;
/// // 8 cables, 6 DOF, anchors (24) and offsets (8), gauge 6: k (8 − 6) ≥ 26 → k ≥ 13.
/// let c = counting_rule(13, 8, 6, 32, 6, false);
/// assert!(c.holds && c.samples_needed == Some(13));
/// assert!(!counting_rule(12, 8, 6, 32, 6, false).holds);
/// // As many cables as DOF: never.
/// assert_eq!(counting_rule(100, 6, 6, 24, 6, false).samples_needed, None);
/// ```
pub fn counting_rule(
    k: usize,
    n: usize,
    d: usize,
    p: usize,
    g: usize,
    known_poses: bool,
) -> Counting {
    let free = p.saturating_sub(g);
    let (per_sample, unknowns) = if known_poses {
        (n, free)
    } else {
        (n.saturating_sub(d), free + k * d)
    };
    let samples_needed = if per_sample == 0 {
        None
    } else if known_poses {
        // Cable by cable: each cable's p / n parameters need as many samples.
        Some(free.div_ceil(n).max(1))
    } else {
        Some(free.div_ceil(per_sample).max(1))
    };
    let holds = samples_needed.is_some_and(|s| k >= s);
    let reason = if holds {
        None
    } else if samples_needed.is_none() {
        Some(format!(
            "a robot with as many cables as degrees of freedom (n = d = {d}) cannot \
             self-calibrate: each sample's {n} lengths are used up by its {d} pose coordinates \
             (k (n − d) = 0 < p − g = {free}); measure the poses (known poses) or add cables"
        ))
    } else if known_poses {
        Some(format!(
            "{k} samples with known poses give each cable {k} equations for its {} parameters: \
             at least {} samples are needed",
            free / n.max(1),
            samples_needed.unwrap_or(0)
        ))
    } else {
        Some(format!(
            "k (n − d) = {k} × ({n} − {d}) = {} < p − g = {p} − {g} = {free}: at least {} \
             samples are needed",
            k * per_sample,
            samples_needed.unwrap_or(0)
        ))
    };
    Counting {
        parameters: p,
        gauge: g,
        equations: k * n,
        unknowns,
        holds,
        samples_needed,
        reason,
    }
}
