//! What the projection kinds (`top_match`, `front_match`) share: their table's keys, how
//! a [`ProjectionMatch`] is made from it, and their [`ObjectiveKind`](super::ObjectiveKind)
//! (`projection_kind!`).

use glam::Vec2;
use serde::Deserialize;

use super::kind::ObjectiveSource;
use super::projection::{ProjectionMatch, View};

/// The keys of a `top_match` or `front_match` table.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProjectionFile {
    /// The target image; black = covered.
    pub image: String,
    /// The view plane's area the image covers: (x, z) from above, (x, y) from the front;
    /// its smallest corner.
    pub min: [f32; 2],
    /// Its largest corner.
    pub max: [f32; 2],
}

impl ProjectionFile {
    /// The match through `view` against the table's image, read through `source`; an
    /// image that cannot be used is an error of the key `image`.
    pub(super) fn resolve<S: ObjectiveSource>(
        self,
        view: View,
        source: &S,
    ) -> Result<ProjectionMatch, S::Error> {
        let image = source.image("image", &self.image)?;
        let (min, max) = (Vec2::from(self.min), Vec2::from(self.max));
        ProjectionMatch::from_image(view, min, max, &image)
            .map_err(|err| source.refused("image", err))
    }
}

/// Makes `$kind`, a tuple struct of the [`ProjectionMatch`] it holds, the projection kind
/// of objective seen through `$view`: read from a [`ProjectionFile`], measured as the
/// fraction of matching pixels ([`Sense::Maximize`](crate::evaluate::Sense::Maximize)).
macro_rules! projection_kind {
    ($kind:ident, $view:expr) => {
        impl $crate::score::objective::kind::FromTable for $kind {
            type File = $crate::score::objective::projected::ProjectionFile;

            fn resolve<S: $crate::score::objective::kind::ObjectiveSource>(
                file: Self::File,
                source: &S,
            ) -> Result<Self, S::Error> {
                file.resolve($view, source).map($kind)
            }
        }

        impl $crate::score::objective::kind::ObjectiveKind for $kind {
            const SENSE: $crate::evaluate::Sense = $crate::evaluate::Sense::Maximize;

            fn measure(
                &self,
                surface: &$crate::score::objective::surface::Surface,
                scratch: &mut $crate::score::objective::scratch::ObjectiveScratch,
            ) -> f64 {
                self.0.score_with(surface, scratch.coverage())
            }

            fn projection(&self) -> Option<&$crate::score::objective::projection::ProjectionMatch> {
                Some(&self.0)
            }
        }
    };
}

pub(super) use projection_kind;
