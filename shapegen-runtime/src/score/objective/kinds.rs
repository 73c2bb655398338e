//! The kinds of objective, each declared once, in the `objective_kinds!` table at the end
//! of this file: a row names the kind's variant of [`Objective`], its `kind` in scene
//! files and its type, an [`ObjectiveKind`] in a file of its own in `kinds/`. Everything
//! that lists or dispatches on kinds is derived from the table: [`Objective`] (with
//! [`NAMES`](Objective::NAMES), [`name`](Objective::name), [`sense`](Objective::sense),
//! [`validate`](Objective::validate) and [`measure`](Objective::measure)),
//! [`ObjectiveFile`] (the serde form of an `[[objective]]` table, with its
//! [`resolve`](ObjectiveFile::resolve)) and the modules of the kinds.
//!
//! Adding a kind is one file in `kinds/` and one row.

use serde::Deserialize;

use super::error::ObjectiveError;
use super::kind::{FromTable, ObjectiveKind, ObjectiveSource};
use super::projection::{ProjectionMatch, View};
use super::scratch::ObjectiveScratch;
use super::surface::Surface;
use crate::evaluate::Sense;

/// Declares the kinds of objective, each once:
///
/// ```text
/// /// docs
/// Variant("name"): module::Type;
/// ```
///
/// `name` is the kind's `kind` in scene files (and the default name of its objective),
/// `module` the file of `kinds/` that defines `Type`, an [`ObjectiveKind`]; the module's
/// public items are re-exported. It expands into [`Objective`] (one variant per kind,
/// holding its type, and the dispatch to the type's methods), a `From<Type>` for each,
/// and [`ObjectiveFile`] (one variant per kind, holding its [`File`](FromTable::File)).
macro_rules! objective_kinds {
    ($(
        $(#[doc = $doc:literal])*
        $variant:ident($name:literal): $module:ident::$kind:ident;
    )*) => {
        $(mod $module;
        pub use self::$module::*;)*

        /// One geometric objective: a raw value measured on a model's [`Surface`], with
        /// the direction ([`sense`](Self::sense)) in which it is better; one variant per
        /// kind, each holding its [`ObjectiveKind`].
        ///
        /// ```
        /// use glam::{Affine3A, Vec2};
        /// use shapegen_runtime::evaluate::Sense;
        /// use shapegen_runtime::score::objective::{
        ///     FootprintExcess, Height, Objective, ObjectiveScratch, Surface, UniqueNormals,
        /// };
        /// use shapegen_runtime::{CUBE, Instance, MeshLibrary};
        ///
        /// let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
        /// let cube = Surface::from_instances(&[Instance { transform: Affine3A::IDENTITY, mesh: CUBE }], &meshes);
        /// let mut scratch = ObjectiveScratch::default();
        ///
        /// let height = Objective::Height(Height { target: 2.0 });
        /// assert_eq!(height.measure(&cube, &mut scratch), 1.5);
        /// assert_eq!((height.name(), height.sense()), ("height", Sense::Minimize));
        ///
        /// let normals = Objective::from(UniqueNormals { tolerance_deg: 1.0 });
        /// assert_eq!(normals.measure(&cube, &mut scratch), 6.0);
        ///
        /// let footprint = FootprintExcess { min: Vec2::splat(-0.25), max: Vec2::splat(1.0) };
        /// assert_eq!(Objective::from(footprint).measure(&cube, &mut scratch), 0.5);
        /// assert!(Objective::NAMES.contains(&"footprint_excess"));
        /// # Ok::<(), shapegen_runtime::MeshError>(())
        /// ```
        #[derive(Clone, Debug, PartialEq)]
        pub enum Objective {
            $($(#[doc = $doc])* $variant($module::$kind),)*
        }

        impl Objective {
            /// Every kind's name in scene files, in the order of the table.
            pub const NAMES: &[&str] = &[$($name),*];

            /// The kind of objective, its `kind` in scene files: one of
            /// [`NAMES`](Self::NAMES).
            pub fn name(&self) -> &'static str {
                match self {
                    $(Objective::$variant(_) => $name,)*
                }
            }

            /// The direction in which the objective's value is better.
            pub fn sense(&self) -> Sense {
                match self {
                    $(Objective::$variant(_) => <$module::$kind as ObjectiveKind>::SENSE,)*
                }
            }

            /// Checks the parameters (see each kind's [`ObjectiveKind::validate`]).
            pub fn validate(&self) -> Result<(), ObjectiveError> {
                match self {
                    $(Objective::$variant(kind) => kind.validate(),)*
                }
            }

            /// The projection that a `top_match` or `front_match` objective matches.
            pub fn projection(&self) -> Option<&ProjectionMatch> {
                match self {
                    $(Objective::$variant(kind) => kind.projection(),)*
                }
            }

            /// [`measure`](Self::measure), reusing the distinct normals `scratch` holds
            /// if they were clustered for this `surface` (the caller calls
            /// [`forget`](ObjectiveScratch::forget) between surfaces).
            pub(super) fn measure_same(
                &self,
                surface: &Surface,
                scratch: &mut ObjectiveScratch,
            ) -> f64 {
                match self {
                    $(Objective::$variant(kind) => ObjectiveKind::measure(kind, surface, scratch),)*
                }
            }
        }

        $(impl From<$module::$kind> for Objective {
            fn from(kind: $module::$kind) -> Objective {
                Objective::$variant(kind)
            }
        })*

        /// One `[[objective]]` table as written, less its optional `name`: `kind` picks
        /// the variant, whose keys are its kind's [`File`](FromTable::File)'s (any
        /// other is refused, and serde's message lists the valid ones).
        ///
        /// ```
        /// use shapegen_runtime::score::objective::ObjectiveFile;
        ///
        /// let file: ObjectiveFile = toml::from_str("kind = \"height\"\ntarget = 12")?;
        /// assert_eq!(file.name(), "height");
        /// let err = toml::from_str::<ObjectiveFile>("kind = \"height\"\ntall = 12").unwrap_err();
        /// assert!(err.message().starts_with("unknown field `tall`, expected `target`"));
        /// # Ok::<(), toml::de::Error>(())
        /// ```
        #[derive(Debug, Deserialize)]
        #[serde(tag = "kind", deny_unknown_fields)]
        pub enum ObjectiveFile {
            $($(#[doc = $doc])* #[serde(rename = $name)]
            $variant(<$module::$kind as FromTable>::File),)*
        }

        impl ObjectiveFile {
            /// Its kind's name, as [`Objective::name`].
            pub fn name(&self) -> &'static str {
                match self {
                    $(ObjectiveFile::$variant(_) => $name,)*
                }
            }

            /// The objective the table describes, its files and meshes read through
            /// `source` (see [`ObjectiveSource`] for an example).
            pub fn resolve<S: ObjectiveSource>(self, source: &S) -> Result<Objective, S::Error> {
                match self {
                    $(ObjectiveFile::$variant(file) => {
                        <$module::$kind as FromTable>::resolve(file, source).map(Objective::$variant)
                    })*
                }
            }
        }
    };
}

impl Objective {
    /// The objective's raw value for `surface` (see each kind for its formula).
    pub fn measure(&self, surface: &Surface, scratch: &mut ObjectiveScratch) -> f64 {
        scratch.forget();
        self.measure_same(surface, scratch)
    }
}

/// A projection objective: `top_match` or `front_match`, as the projection's view.
impl From<ProjectionMatch> for Objective {
    fn from(projection: ProjectionMatch) -> Objective {
        match projection.view() {
            View::Top => Objective::TopMatch(TopMatch(projection)),
            View::Front => Objective::FrontMatch(FrontMatch(projection)),
        }
    }
}

objective_kinds! {
    /// Distance of the model's top to a target height.
    Height("height"): height::Height;
    /// Number of distinct face normals.
    UniqueNormals("unique_normals"): unique_normals::UniqueNormals;
    /// How far apart the distinct face normals are.
    NormalSpread("normal_spread"): normal_spread::NormalSpread;
    /// How far the x/z extent leaves a rectangle.
    FootprintExcess("footprint_excess"): footprint_excess::FootprintExcess;
    /// How well the view from above matches an image.
    TopMatch("top_match"): top_match::TopMatch;
    /// How well the view from the front matches an image.
    FrontMatch("front_match"): front_match::FrontMatch;
    /// How close the surface comes to a point cloud.
    Chamfer("chamfer"): chamfer::ChamferMatch;
    /// How far the share of the area some parts take is from a target.
    AreaShare("area_share"): area_share::AreaShare;
    /// How far the mean pitch of a roof is from a target.
    RoofPitch("roof_pitch"): roof_pitch::RoofPitch;
    /// How far the size of the bounding box is from a target size.
    BoundingBox("bounding_box"): bounding_box::BoundingBox;
}
