//! Whether an objective is to be made large or small.

use std::cmp::Ordering;

use serde::{Deserialize, Serialize};

/// The direction of one objective of a multi-objective search.
///
/// ```
/// use shapegen_runtime::optimize::Sense;
///
/// assert!(Sense::Minimize.better(1.0, 2.0));
/// assert_eq!(Sense::Minimize.oriented(2.0), -2.0);
/// assert!(Sense::Maximize.oriented(f64::NAN).is_nan());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Sense {
    /// Higher values are better.
    Maximize,
    /// Lower values are better.
    Minimize,
}

impl Sense {
    /// The value in the higher-is-better convention: itself, or its negation.
    pub fn oriented(self, value: f64) -> f64 {
        match self {
            Sense::Maximize => value,
            Sense::Minimize => -value,
        }
    }

    /// Whether `a` is strictly better than `b` (NaN is never better, and every number is
    /// better than NaN).
    pub fn better(self, a: f64, b: f64) -> bool {
        super::fitness::compare(self.oriented(a), self.oriented(b)) == Ordering::Greater
    }
}
