//! What objectives that read which part of a model a triangle belongs to share (the share
//! of the surface area some parts take, the pitch of a roof): the parts, as a set of
//! meshes, and a triangle's area.
//!
//! A triangle's part is the name of its instance's mesh (a building's generator names its
//! facet meshes `wall`, `roof`, `window`, `door`). The names are resolved to mesh ids once,
//! into a [`Parts`] set; measuring then asks a bit mask per triangle.

use glam::Vec3;

use super::error::ObjectiveError;
use crate::geometry::{BoundMeshes, MeshId};

/// Triangles whose unit normal's `y` is at most this are not counted by
/// [`RoofPitch`](super::RoofPitch): they face down or sideways (a pitch above
/// about 89.994 degrees).
pub const MIN_UPWARD_Y: f32 = 1e-4;

/// A set of meshes of one grammar, by [`MeshId`]: the parts an objective measures.
///
/// Made from mesh names with [`named`](Self::named) (against the names of a grammar's
/// meshes, in id order, as [`GeneratorGraph::meshes`](crate::graph::GeneratorGraph::meshes)
/// lists them) or [`bound`](Self::bound) (against [`BoundMeshes`]), or from ids with
/// [`from_ids`](Self::from_ids). Whether a mesh is in the set is one bit.
///
/// ```
/// use shapegen_runtime::geometry::{Mesh, MeshId, MeshLibrary};
/// use shapegen_runtime::score::objective::Parts;
///
/// let names = ["cube", "wall", "window", "door"];
/// let openings = Parts::named(&["window", "door"], &names)?;
/// assert_eq!(openings.ids().collect::<Vec<_>>(), [MeshId(2), MeshId(3)]);
/// assert!(openings.contains(MeshId(3)) && !openings.contains(MeshId(1)));
///
/// let err = Parts::named(&["windows"], &names).unwrap_err();
/// assert_eq!(
///     err.to_string(),
///     "no mesh is named `windows`; the meshes are `cube`, `wall`, `window` and `door`"
/// );
///
/// let mut library = MeshLibrary::new();
/// library.register("wall", Mesh::facet())?;
/// let meshes = library.bind_names("Walls", &["cube", "wall"])?;
/// assert_eq!(Parts::bound(&["wall"], &meshes)?, Parts::from_ids([MeshId(1)]));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Parts {
    /// Bit `i % 64` of word `i / 64` is set when mesh `i` is in the set.
    mask: Vec<u64>,
}

impl Parts {
    /// The meshes `ids`.
    pub fn from_ids(ids: impl IntoIterator<Item = MeshId>) -> Parts {
        let mut parts = Parts::default();
        for MeshId(id) in ids {
            let (word, bit) = (id as usize / 64, id % 64);
            if parts.mask.len() <= word {
                parts.mask.resize(word + 1, 0);
            }
            parts.mask[word] |= 1 << bit;
        }
        parts
    }

    /// The meshes named `wanted`, where mesh `i` is named `meshes[i]` (a name given
    /// twice stands for the first mesh of that name). Fails on the first name that no
    /// mesh has, listing the names there are.
    pub fn named<S: AsRef<str>>(wanted: &[S], meshes: &[&str]) -> Result<Parts, ObjectiveError> {
        let mut ids = Vec::with_capacity(wanted.len());
        for name in wanted {
            let name = name.as_ref();
            let Some(i) = meshes.iter().position(|&m| m == name) else {
                return Err(ObjectiveError::UnknownPart {
                    name: name.to_owned(),
                    meshes: listing(meshes),
                });
            };
            ids.push(MeshId(i as u32));
        }
        Ok(Parts::from_ids(ids))
    }

    /// The meshes of `meshes` named `wanted`; see [`named`](Self::named).
    pub fn bound<S: AsRef<str>>(
        wanted: &[S],
        meshes: &BoundMeshes,
    ) -> Result<Parts, ObjectiveError> {
        let names: Vec<&str> = meshes.iter().map(|(_, name, _)| name).collect();
        Parts::named(wanted, &names)
    }

    /// Whether mesh `id` is in the set.
    #[inline]
    pub fn contains(&self, MeshId(id): MeshId) -> bool {
        self.mask
            .get(id as usize / 64)
            .is_some_and(|word| word & (1 << (id % 64)) != 0)
    }

    /// The meshes of the set, in id order.
    pub fn ids(&self) -> impl Iterator<Item = MeshId> + '_ {
        self.mask.iter().enumerate().flat_map(|(w, &word)| {
            (0..64)
                .filter(move |bit| word & (1 << bit) != 0)
                .map(move |bit| MeshId(w as u32 * 64 + bit))
        })
    }

    /// Whether the set has no mesh.
    pub fn is_empty(&self) -> bool {
        self.mask.iter().all(|&word| word == 0)
    }

    /// `Ok` when the set, the parts parameter `field`, names a mesh; otherwise
    /// [`ObjectiveError::NoParts`].
    pub(crate) fn check_named(&self, field: &'static str) -> Result<(), ObjectiveError> {
        if self.is_empty() {
            return Err(ObjectiveError::NoParts { field });
        }
        Ok(())
    }

    /// Whether every mesh of `self` is in `other`.
    pub fn is_subset(&self, other: &Parts) -> bool {
        self.mask
            .iter()
            .enumerate()
            .all(|(w, &word)| word & !other.mask.get(w).copied().unwrap_or(0) == 0)
    }
}

/// `` `a`, `b` and `c` ``.
fn listing(names: &[&str]) -> String {
    let quoted: Vec<String> = names.iter().map(|n| format!("`{n}`")).collect();
    match quoted.split_last() {
        None => "none".to_owned(),
        Some((last, [])) => last.clone(),
        Some((last, rest)) => format!("{} and {last}", rest.join(", ")),
    }
}

/// The area of triangle `t`, in `f64`.
#[inline]
pub(super) fn area(t: &[Vec3; 3]) -> f64 {
    let [a, b, c] = t.map(|p| p.as_dvec3());
    0.5 * (b - a).cross(c - a).length()
}
