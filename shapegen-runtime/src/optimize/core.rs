//! What every method has: its settings, the genome limits and its progress (a
//! [`Core`]), and the checkpoint that saves them with the method's own fields (a
//! [`Checkpoint`], declared with [`checkpoint!`](crate::checkpoint)).

use std::fmt::{Debug, DebugStruct, Formatter};

use serde::Serialize;
use serde::de::DeserializeOwned;

use super::run::Progress;
use super::settings::Settings;
use crate::genome::Limits;

/// What every optimizer holds, whatever its method: the settings `S`, the genome limits
/// and the [`Progress`] of its record `R`. An optimizer gives it to the driver through
/// [`Optimizer::core`](super::Optimizer::core) and
/// [`Optimizer::parts`](super::Optimizer::parts); a checkpoint saves it beside the
/// method's own fields.
#[derive(Clone, Debug, PartialEq)]
pub struct Core<S, R> {
    /// The settings.
    pub settings: S,
    /// The genome limits.
    pub limits: Limits,
    /// The counters and the record.
    pub progress: Progress<R>,
}

impl<S, R: Default> Core<S, R> {
    /// The core of a run of `settings` within `limits` seeded with `seed`, not yet
    /// started.
    pub fn new(settings: S, limits: Limits, seed: u64) -> Self {
        Core {
            settings,
            limits,
            progress: Progress::new(seed),
        }
    }
}

impl<S: Debug, R: Debug> Core<S, R> {
    /// The `Debug` output of an optimizer named `name` holding this core, begun: its
    /// settings and progress.
    pub(crate) fn debug<'a, 'b: 'a>(
        &self,
        f: &'a mut Formatter<'b>,
        name: &str,
    ) -> DebugStruct<'a, 'b> {
        let mut out = f.debug_struct(name);
        out.field("settings", &self.settings)
            .field("progress", &self.progress);
        out
    }
}

/// A checkpoint of an optimizer ([`Optimizer::State`](super::Optimizer::State)): the
/// [`Core`] it was saved from, as the fields `settings`, `limits` and `progress`, then the
/// method's own fields, its *body*. Declare one with [`checkpoint!`](crate::checkpoint).
///
/// The settings and limits say what resuming it will hold before anything is allocated
/// (with [`Optimizer::genomes_held`](super::Optimizer::genomes_held)).
pub trait Checkpoint: Serialize + DeserializeOwned {
    /// The settings of the method.
    type Settings: Settings;
    /// What the method records.
    type Record;
    /// The method's own fields, in order, as a tuple.
    type Body;

    /// The settings the checkpoint was saved with.
    fn settings(&self) -> &Self::Settings;

    /// The genome limits, which resuming it keeps to.
    fn limits(&self) -> &Limits;

    /// The counters and the record.
    fn progress(&self) -> &Progress<Self::Record>;

    /// The checkpoint of `core` with the method's own fields `body`.
    fn from_parts(core: Core<Self::Settings, Self::Record>, body: Self::Body) -> Self;

    /// The core and the body, taken apart.
    fn into_parts(self) -> (Core<Self::Settings, Self::Record>, Self::Body);
}

/// Declares a checkpoint struct, generic over a grammar `G: Grammar`: the fields
/// `settings`, `limits` and `progress` of the method's [`Core`](crate::optimize::Core),
/// then the fields given, in that order; serde's `Serialize` and `Deserialize` (unknown
/// fields are errors), `Clone`, `PartialEq` and `Debug` without asking `G` for them
/// (grammars are bare marker types), and [`Checkpoint`](crate::optimize::Checkpoint),
/// whose body is the tuple of the fields given. The crate using it needs `serde` among
/// its dependencies.
///
/// `struct Name<G>: Settings, Record { fields }` names the settings and record types.
///
/// ```
/// use shapegen_runtime::checkpoint;
/// use shapegen_runtime::optimize::{Best, Checkpoint, Core, GaSettings};
/// use shapegen_runtime::prelude::*;
///
/// generator! {
///     /// One block.
///     pub Block { axiom Seg; node Seg { derive(s) { s.emit(CUBE); } } }
/// }
///
/// checkpoint! {
///     /// A checkpoint holding one genome.
///     pub struct OneState<G>: GaSettings, Best<G> {
///         /// The genome.
///         pub genome: Genome<G>,
///     }
/// }
///
/// let core = Core::new(GaSettings::default(), Limits::new(1, 10, 10)?, 7);
/// let genome = Genome::<Block>::axiom(&mut shapegen_runtime::optimize::stream(7, 0, 0));
/// let state = OneState::from_parts(core, (genome,));
/// let json = serde_json::to_string(&state)?;
/// assert!(json.starts_with(r#"{"settings":{"population":200,"#));
/// let back: OneState<Block> = serde_json::from_str(&json)?;
/// assert_eq!((back.progress().seed, back.limits().max_len), (7, 10));
/// assert_eq!(back.genome, state.genome);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// A checkpoint whose serde layout is its own declares the same with `@struct` before
/// its attributes and derives nothing from serde, implementing `Serialize` and
/// `Deserialize` itself.
#[macro_export]
macro_rules! checkpoint {
    (
        $(#[$attr:meta])*
        $vis:vis struct $name:ident<G>: $settings:ty, $record:ty { $($body:tt)* }
    ) => {
        $crate::checkpoint! {
            @struct
            $(#[$attr])*
            #[derive(::serde::Serialize, ::serde::Deserialize)]
            #[serde(deny_unknown_fields, bound = "")]
            $vis struct $name<G>: $settings, $record { $($body)* }
        }
    };
    (
        @struct
        $(#[$attr:meta])*
        $vis:vis struct $name:ident<G>: $settings:ty, $record:ty {
            $($(#[$field_attr:meta])* $field_vis:vis $field:ident: $ty:ty),* $(,)?
        }
    ) => {
        $(#[$attr])*
        $vis struct $name<G: $crate::derive::Grammar> {
            /// The settings.
            pub settings: $settings,
            /// The genome limits.
            pub limits: $crate::genome::Limits,
            /// Generation, evaluations, wall time, and what the run found so far.
            pub progress: $crate::__private::Progress<$record>,
            $($(#[$field_attr])* $field_vis $field: $ty),*
        }

        $crate::grammar_struct_traits!($name { settings, limits, progress, $($field),* });

        impl<G: $crate::derive::Grammar> $crate::optimize::Checkpoint for $name<G> {
            type Settings = $settings;
            type Record = $record;
            type Body = ($($ty,)*);

            fn settings(&self) -> &$settings {
                &self.settings
            }

            fn limits(&self) -> &$crate::genome::Limits {
                &self.limits
            }

            fn progress(&self) -> &$crate::__private::Progress<$record> {
                &self.progress
            }

            fn from_parts(
                core: $crate::optimize::Core<$settings, $record>,
                ($($field,)*): Self::Body,
            ) -> Self {
                $name {
                    settings: core.settings,
                    limits: core.limits,
                    progress: core.progress,
                    $($field),*
                }
            }

            fn into_parts(self) -> ($crate::optimize::Core<$settings, $record>, Self::Body) {
                let core = $crate::optimize::Core {
                    settings: self.settings,
                    limits: self.limits,
                    progress: self.progress,
                };
                (core, ($(self.$field,)*))
            }
        }
    };
}
