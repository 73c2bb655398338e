//! What the kinds measured on distinct normals (`unique_normals`, `normal_spread`)
//! share: their table, its check, and their [`ObjectiveKind`](super::ObjectiveKind)
//! (`normals_kind!`).

/// Declares `$kind`, a kind of objective measured on the model's distinct normals at a
/// tolerance: a struct of `tolerance_deg` (1 when its table leaves it out, checked to lie
/// from 0 to 180 degrees), read as written, better when larger, whose value is
/// `$measure` with the objective's scratch, the surface and the tolerance bound to the
/// names given.
macro_rules! normals_kind {
    (
        $(#[$doc:meta])*
        $kind:ident,
        |$scratch:ident, $surface:ident, $tolerance:ident| $measure:expr
    ) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq, serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        pub struct $kind {
            /// Largest angle, in degrees (0 to 180), between normals counted as one.
            #[serde(default = "crate::score::objective::normals_kind::one_degree")]
            pub tolerance_deg: f32,
        }

        impl $crate::score::objective::kind::AsWritten for $kind {}

        impl $crate::score::objective::kind::ObjectiveKind for $kind {
            const SENSE: $crate::evaluate::Sense = $crate::evaluate::Sense::Maximize;

            /// A tolerance from 0 to 180 degrees.
            fn validate(&self) -> Result<(), $crate::score::objective::error::ObjectiveError> {
                let angle = |t: f32| (0.0..=180.0).contains(&t);
                let valid = "an angle from 0 to 180 degrees";
                $crate::score::objective::error::ObjectiveError::check(
                    "tolerance_deg",
                    self.tolerance_deg,
                    angle,
                    valid,
                )
            }

            fn measure(
                &self,
                $surface: &$crate::score::objective::surface::Surface,
                $scratch: &mut $crate::score::objective::scratch::ObjectiveScratch,
            ) -> f64 {
                let $tolerance = self.tolerance_deg;
                $measure
            }
        }
    };
}

pub(super) use normals_kind;

/// The tolerance of a table that leaves it out.
pub(super) fn one_degree() -> f32 {
    1.0
}
