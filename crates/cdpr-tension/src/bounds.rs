//! # Tension bounds
//!
//! Per-cable limits t_min,i ≤ t_i ≤ t_max,i (thesis eq. (6.21); Krut, Company & Pierrot 2004, eq. (3)).

use crate::TensionError;
use nalgebra::DVector;

/// Lower and upper cable tension limits, one pair per cable (N, or the robot's force unit).
#[derive(Debug, Clone, PartialEq)]
pub struct TensionBounds {
    min: DVector<f64>,
    max: DVector<f64>,
}

impl TensionBounds {
    /// Per-cable bounds. Errors if lengths differ, a value is NaN, or some t_min > t_max.
    /// Infinite t_max is allowed (no upper limit); t_min must be finite.
    ///
    /// ```
    /// use cdpr_tension::TensionBounds;
    /// let b = TensionBounds::new(vec![5.0, 5.0], vec![100.0, 80.0]).unwrap();
    /// assert_eq!(b.max()[1], 80.0);
    /// assert!(TensionBounds::new(vec![5.0], vec![1.0]).is_err());
    /// ```
    pub fn new(min: Vec<f64>, max: Vec<f64>) -> Result<Self, TensionError> {
        if min.len() != max.len() {
            return Err(TensionError::DimensionMismatch {
                what: "tension bounds (max vs min)",
                expected: min.len(),
                found: max.len(),
            });
        }
        for (i, (&lo, &hi)) in min.iter().zip(&max).enumerate() {
            if !lo.is_finite() || hi.is_nan() || hi == f64::NEG_INFINITY {
                return Err(TensionError::NotFinite {
                    what: "tension bound",
                    index: i,
                    value: if lo.is_finite() { hi } else { lo },
                });
            }
            if lo > hi {
                return Err(TensionError::InvertedBounds {
                    cable: i,
                    min: lo,
                    max: hi,
                });
            }
        }
        Ok(Self {
            min: DVector::from_vec(min),
            max: DVector::from_vec(max),
        })
    }

    /// The same bounds `[t_min, t_max]` for all `n` cables.
    pub fn uniform(n: usize, t_min: f64, t_max: f64) -> Result<Self, TensionError> {
        Self::new(vec![t_min; n], vec![t_max; n])
    }

    /// Lower limits t_min.
    #[inline]
    pub fn min(&self) -> &DVector<f64> {
        &self.min
    }

    /// Upper limits t_max.
    #[inline]
    pub fn max(&self) -> &DVector<f64> {
        &self.max
    }

    /// Number of cables.
    #[inline]
    pub fn len(&self) -> usize {
        self.min.len()
    }

    /// Whether there are no cables.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.min.is_empty()
    }
}
