//! [`FrontMatch`]: how well the model seen from the front matches a target image.

use crate::score::objective::projected::projection_kind;
use crate::score::objective::projection::{ProjectionMatch, View};

/// Fraction of the pixels of the orthographic projection from the front (onto x/y) that
/// match a target image, in `[0, 1]`
/// ([`Sense::Maximize`](crate::evaluate::Sense::Maximize)); see [`ProjectionMatch`]. Made
/// from its table (`kind = "front_match"`, `image`, `min`, `max`), or from a match whose
/// view is [`View::Front`] by [`Objective::from`](super::Objective::from).
///
/// ```
/// use glam::{Affine3A, Vec2};
/// use shapegen_runtime::score::objective::{Objective, ObjectiveScratch, ProjectionMatch, Surface, View};
/// use shapegen_runtime::{CUBE, Instance, MeshLibrary};
///
/// let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
/// let cube = Surface::from_instances(&[Instance { transform: Affine3A::IDENTITY, mesh: CUBE }], &meshes);
/// // A 4 x 4 image of [-1, 1]^2 whose middle 2 x 2 pixels are black: the unit cube.
/// let mask: Vec<bool> = (0..16).map(|i| (1..3).contains(&(i % 4)) && (1..3).contains(&(i / 4))).collect();
/// let front = ProjectionMatch::new(View::Front, Vec2::splat(-1.0), Vec2::splat(1.0), 4, 4, &mask)?;
/// let objective = Objective::from(front);
/// assert_eq!(objective.name(), "front_match");
/// let mut scratch = ObjectiveScratch::default();
/// assert_eq!(objective.measure(&cube, &mut scratch), 1.0);
/// assert_eq!(objective.measure(&Surface::new(), &mut scratch), 0.75);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct FrontMatch(pub(super) ProjectionMatch);

projection_kind!(FrontMatch, View::Front);
