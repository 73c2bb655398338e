//! What one model covers in each target image.

use serde::Serialize;

/// Most targets one [`SilhouetteScorer`](super::SilhouetteScorer) scores against.
pub const MAX_TARGETS: usize = 8;

/// What one model covers in one target image, in pixels.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct TargetCounts {
    /// Pixels the model covers.
    pub covered: u32,
    /// Covered pixels that are target pixels (positive weight).
    pub on_target: u32,
    /// Covered pixels that are not target pixels: `covered - on_target`.
    pub off_target: u32,
    /// Sum of the grey levels (`0..=255`, a mask's as 0 or 255) of the covered pixels.
    pub level_sum: u64,
}

/// What one model covers in each target of a scorer: [`targets`](Self::targets) gives
/// one [`TargetCounts`] per target, in the scorer's order.
///
/// ```
/// use shapegen_runtime::score::silhouette::{SilhouetteCounts, TargetCounts};
///
/// let one = TargetCounts { covered: 3, on_target: 2, off_target: 1, level_sum: 255 };
/// let counts = SilhouetteCounts::new(&[one]).unwrap();
/// assert_eq!(counts.targets(), [one]);
/// assert!(SilhouetteCounts::new(&[one; 9]).is_none());
/// assert_eq!(
///     serde_json::to_string(&counts).unwrap(),
///     r#"[{"covered":3,"on_target":2,"off_target":1,"level_sum":255}]"#
/// );
/// ```
///
/// It serializes as the list of its targets' counts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SilhouetteCounts {
    len: u8,
    per_target: [TargetCounts; MAX_TARGETS],
}

impl Serialize for SilhouetteCounts {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.targets())
    }
}

impl SilhouetteCounts {
    /// Counts for `targets.len()` targets, or `None` when there are more than
    /// [`MAX_TARGETS`].
    pub fn new(targets: &[TargetCounts]) -> Option<Self> {
        if targets.len() > MAX_TARGETS {
            return None;
        }
        let mut counts = SilhouetteCounts::zeroed(targets.len());
        counts.per_target[..targets.len()].copy_from_slice(targets);
        Some(counts)
    }

    /// Zero counts for `len` targets (at most [`MAX_TARGETS`]).
    pub(super) fn zeroed(len: usize) -> Self {
        SilhouetteCounts {
            len: len as u8,
            ..Default::default()
        }
    }

    /// One entry per target, in the scorer's order.
    pub fn targets(&self) -> &[TargetCounts] {
        &self.per_target[..self.len as usize]
    }

    /// Mutable access to the entries, for backends that count.
    pub(super) fn targets_mut(&mut self) -> &mut [TargetCounts] {
        &mut self.per_target[..self.len as usize]
    }
}
