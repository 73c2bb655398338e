//! Working memory of one worker counting models.

use super::parity::Voxelizer;

/// Working memory of one worker counting models with a
/// [`VolumeScorer`](super::VolumeScorer): a bitset over the grid of the voxels covered,
/// one of those covered more than once, and the list of the words of the first that are
/// not zero (the second's are a subset); with the F-score form, the model's surface
/// dilated along x.
#[derive(Clone, Debug)]
pub struct VolumeScratch {
    pub(super) covered: Vec<u64>,
    pub(super) twice: Vec<u64>,
    pub(super) touched: Vec<u32>,
    pub(super) voxelizer: Voxelizer,
    pub(super) dilated: Vec<Vec<u64>>,
}

impl VolumeScratch {
    pub(crate) fn new(voxels: u64) -> VolumeScratch {
        let words = voxels.div_ceil(64) as usize;
        VolumeScratch {
            covered: vec![0; words],
            twice: vec![0; words],
            touched: Vec::new(),
            voxelizer: Voxelizer::default(),
            dilated: Vec::new(),
        }
    }
}
