//! Welding positions: one id per distinct position.

use std::collections::HashMap;

use glam::Vec3;

/// Numbers positions by exact value, in order of first appearance: one id per
/// distinct position, and the number of distinct positions.
pub(crate) fn weld(positions: &[Vec3]) -> (Vec<u32>, usize) {
    let mut ids: HashMap<[u32; 3], u32> = HashMap::with_capacity(positions.len());
    let welded = positions
        .iter()
        .map(|p| {
            let next = ids.len() as u32;
            // +0.0 folds -0.0 into 0.0.
            *ids.entry((*p + 0.0).to_array().map(f32::to_bits))
                .or_insert(next)
        })
        .collect();
    (welded, ids.len())
}
