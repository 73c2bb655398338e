//! What every method's settings have in common: a count of generations that makes a run's
//! budget, and a check of their values.

use std::fmt::Debug;

use serde::Serialize;
use serde::de::DeserializeOwned;

use super::error::SettingsError;
use super::run::Budget;
use crate::genome::Limits;

/// A search method's settings, as scene files give them ([`Optimizer::Settings`](
/// super::Optimizer::Settings)).
///
/// Every method runs in generations: the GA's generations, SMC's steps, RJMCMC's
/// iterations. [`GENERATIONS`](Self::GENERATIONS) names the field that counts them, so
/// that a scene's `optimizer.generations` (or the command line's `--generations`) sets it
/// whatever the method calls it.
///
/// ```
/// use shapegen_runtime::optimize::{Budget, McmcSettings, Settings};
///
/// let mut s = McmcSettings::default();
/// s.set_generations(300);
/// assert_eq!((McmcSettings::GENERATIONS, s.iterations), ("iterations", 300));
/// assert_eq!(s.budget(), Budget::generations(300));
/// let bad = McmcSettings { chains: 0, ..s };
/// assert_eq!(bad.validate().unwrap_err().field, "chains");
/// ```
pub trait Settings: Clone + Debug + PartialEq + Serialize + DeserializeOwned {
    /// The field that counts the generations, by its name in scene files.
    const GENERATIONS: &'static str;

    /// The generations a run of these settings takes.
    fn generations(&self) -> u64;

    /// Sets the generations a run takes.
    fn set_generations(&mut self, generations: u64);

    /// Checks every field; the error names the first one out of range.
    fn validate(&self) -> Result<(), SettingsError>;

    /// The limits that every genome a run of these settings scores keeps, when the run
    /// is given `limits` (the scene's): the given limits themselves, unless the method
    /// follows a rule of the original implementation that keeps fewer of them (its GA's
    /// operators bound length but not depth; its SMC and RJMCMC bound neither). The run's
    /// best is the best genome it scored, so it keeps these limits too; a debug build
    /// checks every recorded population against them.
    ///
    /// ```
    /// use shapegen_runtime::genome::{DEPTH_CAP, Limits};
    /// use shapegen_runtime::ops::OperatorVariant;
    /// use shapegen_runtime::optimize::{GaSettings, Settings};
    ///
    /// let scene = Limits::new(4, 400, 12).unwrap();
    /// assert_eq!(GaSettings::default().kept_limits(scene), scene);
    /// let original = GaSettings { operators: OperatorVariant::Original, ..GaSettings::default() };
    /// assert_eq!(original.kept_limits(scene), Limits { max_depth: DEPTH_CAP, ..scene });
    /// ```
    fn kept_limits(&self, limits: Limits) -> Limits {
        limits
    }

    /// A budget of [`generations`](Self::generations) generations.
    fn budget(&self) -> Budget {
        Budget::generations(self.generations())
    }
}

/// Writes the generation items of a [`Settings`] impl for settings whose generations are
/// counted by the field at `$path`, named `$name` in scene files:
/// `generations_field!("steps", steps);` or, for settings that wrap the GA's,
/// `generations_field!("generations", ga.generations);`.
macro_rules! generations_field {
    ($name:literal, $($path:ident).+) => {
        const GENERATIONS: &'static str = $name;

        fn generations(&self) -> u64 {
            self.$($path).+
        }

        fn set_generations(&mut self, generations: u64) {
            self.$($path).+ = generations;
        }
    };
}

pub(crate) use generations_field;
