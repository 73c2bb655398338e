//! Fitness forms: how counts become a number.

/// The smoothstep of the original implementation:
/// `t^3 (t (6t - 15) + 10)` with `t = clamp((x - a) / (b - a), 0, 1)`.
///
/// An empty range (`a >= b`) is a step at `a`: 0 below it, 1 from it on.
///
/// ```
/// use shapegen_runtime::score::smoothstep;
///
/// assert_eq!(smoothstep(2.0, 4.0, 1.0), 0.0);
/// assert_eq!(smoothstep(2.0, 4.0, 3.0), 0.5);
/// assert_eq!(smoothstep(2.0, 4.0, 9.0), 1.0);
/// assert_eq!(smoothstep(0.0, 0.0, 0.0), 1.0);
/// ```
pub fn smoothstep(a: f64, b: f64, x: f64) -> f64 {
    if a >= b {
        return if x >= a { 1.0 } else { 0.0 };
    }
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * t * (t * (6.0 * t - 15.0) + 10.0)
}

/// `part / whole`, 0 when the whole is empty: an IoU is the intersection's share of
/// the union, a precision the share of the model's surface near the target's.
pub(crate) fn share(part: u64, whole: u64) -> f64 {
    if whole == 0 {
        0.0
    } else {
        part as f64 / whole as f64
    }
}

/// The harmonic mean of `precision` and `recall`, 0 when both are 0.
pub(crate) fn f_score(precision: f64, recall: f64) -> f64 {
    if precision + recall > 0.0 {
        2.0 * precision * recall / (precision + recall)
    } else {
        0.0
    }
}

/// How a scorer turns its counts into fitness.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Form {
    /// The paper's weighted sum of what the model covers: each covered voxel or pixel
    /// adds the target weight there; `overlap` is subtracted for every voxel covered
    /// more than once (volumes only; 0 ignores self-intersection).
    Weighted {
        /// Weight subtracted per repeated voxel hit (`w_self`).
        overlap: f64,
    },
    /// The original implementation's form, which produced the published curves:
    /// `good * S(0, T, on) - bad * S(0, k T, off)`, where `S` is [`smoothstep`], `T` the
    /// number of target voxels or pixels, `on` those the model covers and `off` what it
    /// covers elsewhere (for volumes: outside, repeated and out-of-grid voxels, `k = 2`;
    /// for images `k = 1`).
    Smooth {
        /// Weight of covering the target.
        good: f64,
        /// Weight of covering anything else.
        bad: f64,
    },
    /// The measure runs report: `good` times the intersection over union of the model
    /// with the target, `on / (T + off)`, where `T` is the number of target voxels or
    /// pixels, `on` those the model covers and `off` the others it covers (for volumes,
    /// what it covers beyond the grid included; see
    /// [`VolumeScorer`](super::volume::VolumeScorer)). Target weights other than their
    /// sign, shaping and self-intersection do not enter it.
    Iou {
        /// The fitness of a model that covers exactly the target.
        good: f64,
    },
    /// Volumes only: `good` times the F-score at `threshold` of the model's surface
    /// against the target's, counted on voxel centres (see
    /// [`volume`](super::volume#the-f-score-form)): the harmonic mean of the share of the
    /// model's surface within `threshold` of the target's surface and the share of the
    /// target's surface within `threshold` of the model's.
    FScore {
        /// The fitness of a model whose surface lies within `threshold` of the
        /// target's everywhere, and the target's of it.
        good: f64,
        /// The distance, in world units, within which two surfaces match.
        threshold: f64,
    },
}

/// The genome-length term of the smoothstep form: `weight * S(from, to, genes)`,
/// subtracted once from a model's fitness however many scorers it has.
///
/// ```
/// use shapegen_runtime::score::LengthPenalty;
///
/// let p = LengthPenalty { weight: 0.2, from: 40.0, to: 100.0 };
/// assert_eq!(p.apply(30), 0.0);
/// assert_eq!(p.apply(70), 0.1);
/// assert_eq!(LengthPenalty::NONE.apply(1000), 0.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LengthPenalty {
    /// The penalty at and beyond `to`.
    pub weight: f64,
    /// Genome length (genes) where the penalty starts: the scene's optimal length.
    pub from: f64,
    /// Genome length where the penalty is full: the scene's maximum length.
    pub to: f64,
}

impl LengthPenalty {
    /// No penalty at any length.
    pub const NONE: LengthPenalty = LengthPenalty {
        weight: 0.0,
        from: 0.0,
        to: 0.0,
    };

    /// The penalty of a genome of `genes` genes.
    pub fn apply(&self, genes: usize) -> f64 {
        if self.weight == 0.0 {
            return 0.0;
        }
        self.weight * smoothstep(self.from, self.to, genes as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smoothstep_is_monotone_and_symmetric() {
        let mut last = 0.0;
        for i in 0..=100 {
            let x = f64::from(i) / 100.0;
            let y = smoothstep(0.0, 1.0, x);
            assert!(y >= last, "not monotone at {x}");
            assert!((y + smoothstep(0.0, 1.0, 1.0 - x) - 1.0).abs() < 1e-12);
            last = y;
        }
    }

    #[test]
    fn shares_and_f_scores_are_zero_when_empty() {
        assert_eq!(share(3, 12), 0.25);
        assert_eq!(share(0, 0), 0.0);
        assert_eq!(f_score(0.5, 1.0), 2.0 / 3.0);
        assert_eq!(f_score(0.0, 0.0), 0.0);
    }
}
