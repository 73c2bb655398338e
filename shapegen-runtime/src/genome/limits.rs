//! Limits on a genome's size and shape: minimum and maximum length, maximum depth.

use serde::{Deserialize, Serialize};

use super::packed::DEPTH_CAP;

/// Bounds every genetic operator keeps its genomes within.
///
/// Lengths count genes (nodes of the derivation tree); depth counts levels, the root
/// being at depth 1. Loading limits with serde checks them as [`Limits::check`] does.
///
/// ```
/// use shapegen_runtime::genome::Limits;
///
/// // The spaceship scene of the paper: genomes of 4 to 100 genes, at most 12 deep.
/// let limits = Limits::new(4, 100, 12).unwrap();
/// assert_eq!(limits.max_len, 100);
/// assert!(Limits::new(10, 5, 12).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(try_from = "LimitsFields")]
pub struct Limits {
    /// Fewest genes a genome may have. A genome always holds its root, so 0 acts as 1.
    pub min_len: u32,
    /// Most genes a genome may have; at least 1.
    pub max_len: u32,
    /// Deepest a genome's tree may be, the root counting as depth 1; from 1 to
    /// [`DEPTH_CAP`].
    pub max_depth: u32,
}

/// Why a set of [`Limits`] cannot be used.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum LimitsError {
    /// `min_len` is larger than `max_len`.
    #[error("min_len {min_len} is larger than max_len {max_len}; min_len must be at most max_len")]
    MinAboveMax {
        /// The minimum length given.
        min_len: u32,
        /// The maximum length given.
        max_len: u32,
    },
    /// `max_len` is 0.
    #[error("max_len is 0, but every genome holds at least its root gene; use 1 or more")]
    ZeroMaxLen,
    /// `max_depth` is 0 or above [`DEPTH_CAP`].
    #[error(
        "max_depth {max_depth} is out of range: it must be between 1 (the root alone) and {cap}"
    )]
    MaxDepth {
        /// The maximum depth given.
        max_depth: u32,
        /// [`DEPTH_CAP`].
        cap: u32,
    },
}

impl Limits {
    /// Limits with the given bounds, checked by [`check`](Self::check).
    pub fn new(min_len: u32, max_len: u32, max_depth: u32) -> Result<Self, LimitsError> {
        let limits = Limits {
            min_len,
            max_len,
            max_depth,
        };
        limits.check()?;
        Ok(limits)
    }

    /// These limits without their depth bound: any depth up to [`DEPTH_CAP`], which every
    /// genome keeps.
    ///
    /// ```
    /// use shapegen_runtime::genome::{DEPTH_CAP, Limits};
    ///
    /// let scene = Limits::new(4, 400, 12).unwrap();
    /// assert_eq!(scene.without_depth().max_depth, DEPTH_CAP);
    /// assert_eq!(scene.without_length(), Limits::new(0, u32::MAX, 12).unwrap());
    /// assert_eq!(scene.without_min_len().min_len, 0);
    /// ```
    pub const fn without_depth(self) -> Self {
        Limits {
            max_depth: DEPTH_CAP,
            ..self
        }
    }

    /// These limits without their length bounds: any length from the root alone up.
    pub const fn without_length(self) -> Self {
        Limits {
            min_len: 0,
            max_len: u32::MAX,
            ..self
        }
    }

    /// These limits without their minimum length.
    pub const fn without_min_len(self) -> Self {
        Limits { min_len: 0, ..self }
    }

    /// Checks that the bounds can be met together: `min_len <= max_len`, `max_len >= 1`
    /// and `1 <= max_depth <= DEPTH_CAP`.
    pub fn check(&self) -> Result<(), LimitsError> {
        if self.max_len == 0 {
            return Err(LimitsError::ZeroMaxLen);
        }
        if self.min_len > self.max_len {
            return Err(LimitsError::MinAboveMax {
                min_len: self.min_len,
                max_len: self.max_len,
            });
        }
        if self.max_depth == 0 || self.max_depth > DEPTH_CAP {
            return Err(LimitsError::MaxDepth {
                max_depth: self.max_depth,
                cap: DEPTH_CAP,
            });
        }
        Ok(())
    }
}

/// The serialized fields of [`Limits`], checked on the way in.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LimitsFields {
    min_len: u32,
    max_len: u32,
    max_depth: u32,
}

impl TryFrom<LimitsFields> for Limits {
    type Error = LimitsError;

    fn try_from(f: LimitsFields) -> Result<Self, LimitsError> {
        Limits::new(f.min_len, f.max_len, f.max_depth)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn check_rejects_each_impossible_bound() {
        assert_eq!(
            Limits::new(5, 4, 3),
            Err(LimitsError::MinAboveMax {
                min_len: 5,
                max_len: 4
            })
        );
        assert_eq!(Limits::new(0, 0, 3), Err(LimitsError::ZeroMaxLen));
        assert!(matches!(
            Limits::new(1, 4, 0),
            Err(LimitsError::MaxDepth { max_depth: 0, .. })
        ));
        assert!(Limits::new(1, 4, DEPTH_CAP + 1).is_err());
        assert!(Limits::new(0, 1, DEPTH_CAP).is_ok());
        let msg = Limits::new(5, 4, 3).unwrap_err().to_string();
        assert!(
            msg.contains("min_len 5") && msg.contains("max_len 4"),
            "{msg}"
        );
    }

    #[test]
    fn serde_checks_on_load() {
        let ok: Limits =
            serde_json::from_str(r#"{"min_len": 4, "max_len": 100, "max_depth": 12}"#).unwrap();
        assert_eq!(ok, Limits::new(4, 100, 12).unwrap());
        let back: Limits = serde_json::from_str(&serde_json::to_string(&ok).unwrap()).unwrap();
        assert_eq!(back, ok);
        let err =
            serde_json::from_str::<Limits>(r#"{"min_len": 9, "max_len": 4, "max_depth": 12}"#)
                .unwrap_err()
                .to_string();
        assert!(err.contains("min_len 9 is larger than max_len 4"), "{err}");
        assert!(
            serde_json::from_str::<Limits>(
                r#"{"min_len": 1, "max_len": 4, "max_depth": 2, "x": 1}"#
            )
            .is_err()
        );
    }
}
