//! Which instances a model lost and gained against a related model.

use crate::geometry::Instance;

/// The instances of a model `child` that a model `base` lacks (`added`) and those of
/// `base` that `child` lacks (`removed`), as multisets of instances equal to the bit:
/// counting `base`, taking away what `removed` covers and adding what `added` covers
/// gives exactly what counting `child` gives, for any two models.
///
/// Derivation writes a model's instances depth first, so a child bred by one operator
/// keeps its parent's instances before and after the subtree that changed: the diff
/// drops the common prefix and suffix, then pairs equal instances in what is left by
/// sorting their keys, so that reordered instances cost nothing either.
///
/// ```
/// use glam::{Affine3A, Vec3};
/// use shapegen_runtime::score::retained::InstanceDiff;
/// use shapegen_runtime::{CUBE, Instance};
///
/// let at = |x: f32| Instance { transform: Affine3A::from_translation(Vec3::X * x), mesh: CUBE };
/// let base = [at(0.0), at(1.0), at(2.0), at(3.0)];
/// let child = [at(0.0), at(5.0), at(3.0), at(1.0)];
/// let mut diff = InstanceDiff::default();
/// diff.between(&base, &child);
/// assert_eq!(diff.removed(), [at(2.0)]);
/// assert_eq!(diff.added(), [at(5.0)]);
/// ```
#[derive(Clone, Debug, Default)]
pub struct InstanceDiff {
    removed: Vec<Instance>,
    added: Vec<Instance>,
    base_keys: Vec<(InstanceKey, u32)>,
    child_keys: Vec<(InstanceKey, u32)>,
}

/// An instance's exact bits: mesh id, then the 12 floats of its transform. Two
/// instances with equal keys cover the same cells.
pub(crate) type InstanceKey = [u32; 13];

/// The key of `instance`.
pub(crate) fn instance_key(instance: &Instance) -> InstanceKey {
    let m = instance.transform.matrix3;
    let t = instance.transform.translation;
    let f = [
        m.x_axis.x, m.x_axis.y, m.x_axis.z, m.y_axis.x, m.y_axis.y, m.y_axis.z, m.z_axis.x,
        m.z_axis.y, m.z_axis.z, t.x, t.y, t.z,
    ];
    let mut k = [instance.mesh.0; 13];
    for (slot, v) in k[1..].iter_mut().zip(f) {
        *slot = v.to_bits();
    }
    k
}

impl InstanceDiff {
    /// Computes the diff from `base` to `child`, reusing this diff's memory.
    pub fn between(&mut self, base: &[Instance], child: &[Instance]) {
        self.removed.clear();
        self.added.clear();
        let same = |a: &Instance, b: &Instance| instance_key(a) == instance_key(b);
        let prefix = base
            .iter()
            .zip(child)
            .take_while(|(a, b)| same(a, b))
            .count();
        let (base, child) = (&base[prefix..], &child[prefix..]);
        let suffix = base
            .iter()
            .rev()
            .zip(child.iter().rev())
            .take_while(|(a, b)| same(a, b))
            .count();
        let base = &base[..base.len() - suffix];
        let child = &child[..child.len() - suffix];
        if base.is_empty() || child.is_empty() {
            self.removed.extend_from_slice(base);
            self.added.extend_from_slice(child);
            return;
        }
        let keyed = |models: &[Instance], keys: &mut Vec<(InstanceKey, u32)>| {
            keys.clear();
            keys.extend(
                models
                    .iter()
                    .enumerate()
                    .map(|(i, m)| (instance_key(m), i as u32)),
            );
            keys.sort_unstable();
        };
        keyed(base, &mut self.base_keys);
        keyed(child, &mut self.child_keys);
        let (mut i, mut j) = (0, 0);
        let (b, c) = (&self.base_keys, &self.child_keys);
        while i < b.len() && j < c.len() {
            match b[i].0.cmp(&c[j].0) {
                std::cmp::Ordering::Less => {
                    self.removed.push(base[b[i].1 as usize]);
                    i += 1;
                }
                std::cmp::Ordering::Greater => {
                    self.added.push(child[c[j].1 as usize]);
                    j += 1;
                }
                std::cmp::Ordering::Equal => {
                    i += 1;
                    j += 1;
                }
            }
        }
        self.removed
            .extend(b[i..].iter().map(|&(_, k)| base[k as usize]));
        self.added
            .extend(c[j..].iter().map(|&(_, k)| child[k as usize]));
    }

    /// The instances of the base that the child lacks.
    pub fn removed(&self) -> &[Instance] {
        &self.removed
    }

    /// The instances of the child that the base lacks.
    pub fn added(&self) -> &[Instance] {
        &self.added
    }

    /// How many instances changed: removed plus added.
    pub fn len(&self) -> usize {
        self.removed.len() + self.added.len()
    }

    /// Whether the two models have the same instances.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}
