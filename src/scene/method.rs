//! The search methods a scene can name, each declared once, in the `methods!` table at
//! the end of this file: its name in scene files and on the command line, its optimizer
//! and settings types, its colour in the pictures, its settings where a scene leaves
//! them out (from the generator's [`Presets`]) and how its keys of the `[optimizer]`
//! table are read. Everything that lists or dispatches on methods is derived from the
//! table: [`Method`] and [`MethodSettings`], the scene's `[optimizer]` parsing, the
//! command line's `--method` and `--methods`, `compare`'s and `sweep`'s runs, the
//! memory estimate ([`Optimizer::genomes_held`]) and the run itself
//! ([`OptimizerGoal::run`](super::OptimizerGoal::run)).
//!
//! Two searches are the GA's row run otherwise, each derived in one place: a goal with
//! islands runs the GA's island model ([`IslandGa`], through
//! [`MethodJob::run_islands`]; see [`OptimizerGoal::run`](super::OptimizerGoal::run)), and
//! a scene with objectives the multi-objective GA, whose record is a front rather than a
//! best ([`MultiGa`](shapegen_runtime::optimize::multi::MultiGa), through [`SearchJob::run_front`]; see
//! [`Scene::search`](super::Scene::search)). Work that runs every search, `shapegen
//! run`'s and the memory estimate's, is a [`SearchJob`]; work on one fitness (`compare`,
//! `sweep`, [`Search`](crate::search::Search)) a [`MethodJob`].
//!
//! A method of one's own is an [`Optimizer`] with a [`Settings`] type; adding it to the
//! table is one row.
//!
//! Why a key of the `[optimizer]` table, or the command-line flag in its place, cannot be
//! used ([`SettingsKeyError`], [`SettingsCause`]) is told beside the table that reads the
//! keys, as the causes name the methods.
//!
//! ```
//! use shapegen::scene::{Method, MethodSettings};
//!
//! let hybrid: Method = "hybrid".parse()?;
//! assert_eq!(hybrid.name(), "hybrid");
//! assert!(Method::ALL.contains(&hybrid));
//! assert!("pso".parse::<Method>().unwrap_err().to_string().contains(&Method::names()));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use serde::{Deserialize, Serialize};
use shapegen_runtime::Grammar;
use shapegen_runtime::genome::Limits;
use shapegen_runtime::ops::OperatorVariant;
use shapegen_runtime::optimize::islands::{IslandGa, IslandGaSettings};
use shapegen_runtime::optimize::multi::{Front, MultiGaSettings};
use shapegen_runtime::optimize::{
    self, Best, GaSettings, HybridSettings, McmcSettings, McmcVariant, Optimizer, Order, Settings,
    SettingsError, SmcSettings, SmcVariant,
};

use crate::registry::Presets;

/// Work generic over the optimizer of a method that searches one fitness: a command's
/// run, a memory estimate. [`MethodSettings::run`] runs it with the method's optimizer,
/// [`OptimizerGoal::run`](super::OptimizerGoal::run) with the island model too.
pub trait MethodJob<G: Grammar> {
    /// What the work returns.
    type Output;
    /// Does the work with optimizer `O`, whose settings the scene gives as `settings`.
    fn run<O: Optimizer<G, Record = Best<G>>>(self, settings: O::Settings) -> Self::Output;

    /// Does the work with the GA's island model ([`IslandGa`]), whose settings the
    /// scene's GA settings and `[islands]` table give: by default as with any optimizer
    /// (`shapegen run` spreads the islands over its processes instead, under `mpirun`).
    fn run_islands(self, settings: IslandGaSettings) -> Self::Output
    where
        Self: Sized,
    {
        self.run::<IslandGa<G>>(settings)
    }
}

/// Work generic over the optimizer of any search, of one fitness or of objective vectors:
/// `shapegen run`, the memory estimate. [`Scene::search`](super::Scene::search) runs it
/// with the optimizer that searches a scene.
pub trait SearchJob<G: Grammar>: MethodJob<G> {
    /// Does the work with optimizer `O`, which records a front of objective vectors with
    /// the multi-objective GA's settings ([`MultiGa`](shapegen_runtime::optimize::multi::MultiGa)), given as `settings`.
    fn run_front<O>(self, settings: MultiGaSettings) -> Self::Output
    where
        O: Optimizer<G, Record = Front<G>, Settings = MultiGaSettings>;
}

/// A method's settings read from a scene's `[optimizer]` table: the keys of `table` over
/// `base`.
type Read<S> = fn(S, toml::Table) -> Result<S, SettingsKeyError>;

/// Declares the search methods, each once:
///
/// ```text
/// /// docs
/// Variant("name"): path::to::Optimizer, Settings, colour [r, g, b],
///     preset |presets| settings where a scene leaves them out, read a Read<Settings>;
/// ```
///
/// It expands into [`Method`] (with [`ALL`](Method::ALL), [`name`](Method::name) and
/// [`colour`](Method::colour)), [`MethodSettings`] (one variant per method, with the
/// dispatch to its optimizer) and the reading of the `[optimizer]` table.
macro_rules! methods {
    ($(
        $(#[doc = $doc:literal])*
        $variant:ident($name:literal): $($optimizer:ident)::+, $settings:ty, colour $colour:expr,
            preset |$p:ident| $preset:expr, read $read:expr;
    )*) => {
        /// A search method.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
        pub enum Method {
            $($(#[doc = $doc])* $variant,)*
        }

        impl Method {
            /// Every method, in the order the table lists them (and `compare` runs them).
            pub const ALL: &[Method] = &[$(Method::$variant),*];

            /// Its name in scene files and on the command line.
            pub const fn name(self) -> &'static str {
                match self {
                    $(Method::$variant => $name,)*
                }
            }

            /// Its colour in the pictures, the same in every comparison.
            pub const fn colour(self) -> [u8; 3] {
                match self {
                    $(Method::$variant => $colour,)*
                }
            }

            /// Its settings where a scene leaves them out: from the generator's
            /// `presets`.
            pub fn preset(self, presets: &Presets) -> MethodSettings {
                match self {
                    $(Method::$variant => {
                        let $p = presets;
                        MethodSettings::$variant($preset)
                    })*
                }
            }
        }

        /// A method with its settings.
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub enum MethodSettings {
            $($(#[doc = $doc])* $variant($settings),)*
        }

        impl MethodSettings {
            /// The method.
            pub fn method(&self) -> Method {
                match self {
                    $(MethodSettings::$variant(_) => Method::$variant,)*
                }
            }

            /// The generations (steps, iterations) the settings ask for.
            pub fn generations(&self) -> u64 {
                match self {
                    $(MethodSettings::$variant(s) => s.generations(),)*
                }
            }

            /// The limits every genome a run of these settings scores keeps, given the
            /// scene's ([`Settings::kept_limits`](crate::optimize::Settings::kept_limits)).
            pub fn kept_limits(&self, limits: Limits) -> Limits {
                match self {
                    $(MethodSettings::$variant(s) => s.kept_limits(limits),)*
                }
            }

            /// Sets the generations (steps, iterations) the settings ask for.
            pub fn set_generations(&mut self, generations: u64) {
                match self {
                    $(MethodSettings::$variant(s) => s.set_generations(generations),)*
                }
            }

            /// The settings with the keys of an `[optimizer]` table over them (without
            /// the keys every method shares: `method`, `seed`, `seconds`,
            /// `evaluations`); `generations` sets the field that counts the method's
            /// generations.
            pub(super) fn read(self, mut table: toml::Table) -> Result<MethodSettings, SettingsKeyError> {
                match self {
                    $(MethodSettings::$variant(base) => {
                        rename_generations::<$settings>(&mut table);
                        let read: Read<$settings> = $read;
                        read(base, table).map(MethodSettings::$variant)
                    })*
                }
            }

            /// Runs `job` with the method's optimizer and these settings.
            pub fn run<G: Grammar, J: MethodJob<G>>(self, job: J) -> J::Output {
                match self {
                    $(MethodSettings::$variant(s) => job.run::<$($optimizer)::+<G>>(s),)*
                }
            }
        }
    };
}

impl Method {
    /// The method of a scene that names none (and has neither islands nor objectives,
    /// which the GA searches): the hybrid, which led or was level at every budget and on
    /// every scene measured (`benches/README.md`, "The hybrid method").
    pub const DEFAULT: Method = Method::Hybrid;

    /// Every method's name, for messages: `ga, smc, ... and hybrid`.
    pub fn names() -> String {
        let names: Vec<&str> = Method::ALL.iter().map(|m| m.name()).collect();
        match names.split_last() {
            Some((last, rest)) if !rest.is_empty() => format!("{} and {last}", rest.join(", ")),
            _ => names.concat(),
        }
    }
}

/// A method name that names no method.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("\"{0}\" is not a method; the methods are {names}", names = Method::names())]
pub struct UnknownMethod(pub String);

impl std::str::FromStr for Method {
    type Err = UnknownMethod;

    fn from_str(s: &str) -> Result<Method, UnknownMethod> {
        Method::ALL
            .iter()
            .copied()
            .find(|m| m.name() == s)
            .ok_or_else(|| UnknownMethod(s.to_owned()))
    }
}

impl Serialize for Method {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

impl<'de> Deserialize<'de> for Method {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Method, D::Error> {
        let name = String::deserialize(deserializer)?;
        name.parse().map_err(serde::de::Error::custom)
    }
}

/// Moves the table's `generations` to the key that counts `S`'s generations (SMC's
/// `steps`, RJMCMC's `iterations`).
fn rename_generations<S: Settings>(table: &mut toml::Table) {
    if S::GENERATIONS != "generations"
        && let Some(g) = table.remove("generations")
    {
        table.insert(S::GENERATIONS.to_owned(), g);
    }
}

/// `base` with the keys of `table` over it, checked by [`Settings::validate`]; an error
/// names the first key that is wrong on its own.
fn merged<S: Settings>(base: S, table: toml::Table) -> Result<S, SettingsKeyError> {
    let base =
        toml::Table::try_from(base).map_err(|err| SettingsKeyError::new("optimizer", err))?;
    let read = |keys: &toml::Table| -> Result<S, toml::de::Error> {
        let mut merged = base.clone();
        merged.extend(keys.clone());
        toml::Value::Table(merged).try_into()
    };
    let settings: S = read(&table).map_err(|err| {
        // Name the key that is wrong: the first that fails on its own.
        let key = table
            .iter()
            .find(|(k, v)| read(&toml::Table::from_iter([((*k).clone(), (*v).clone())])).is_err())
            .map_or_else(|| "optimizer".to_owned(), |(k, _)| format!("optimizer.{k}"));
        SettingsKeyError::new(key, SettingsCause::Toml(err))
    })?;
    settings
        .validate()
        .map_err(|err| SettingsKeyError::new(format!("optimizer.{}", err.field), err))?;
    Ok(settings)
}

/// The GA's settings, after checking the keys whose serde errors would not name them.
fn read_ga(base: GaSettings, table: toml::Table) -> Result<GaSettings, SettingsKeyError> {
    check_ga_keys(&table)?;
    merged(base, table)
}

/// SMC's or SOSMC's settings: the method sets the order, and `variant` must name an SMC
/// variant.
fn read_smc(base: SmcSettings, table: toml::Table) -> Result<SmcSettings, SettingsKeyError> {
    if table.contains_key("order") {
        return Err(SettingsKeyError::new(
            "optimizer.order",
            SettingsCause::OrderSetByMethod,
        ));
    }
    check_variant(&table, "an SMC", &SmcVariant::ALL.map(SmcVariant::name))?;
    merged(base, table)
}

/// RJMCMC's settings, `variant` naming an RJMCMC variant.
fn read_mcmc(base: McmcSettings, table: toml::Table) -> Result<McmcSettings, SettingsKeyError> {
    check_variant(
        &table,
        "an RJMCMC",
        &McmcVariant::ALL.map(McmcVariant::name),
    )?;
    merged(base, table)
}

/// The hybrid's settings: its own keys (`seed_steps`, `refine`, ...) read as its own and
/// every other key as its GA's.
fn read_hybrid(
    base: HybridSettings,
    mut table: toml::Table,
) -> Result<HybridSettings, SettingsKeyError> {
    let own: toml::Table = toml::Table::try_from(base)
        .map_err(|err| SettingsKeyError::new("optimizer", err))?
        .into_iter()
        .filter(|(k, _)| k != "ga")
        .filter_map(|(k, _)| table.remove_entry(&k))
        .collect();
    let ga = read_ga(base.ga, table)?;
    merged(HybridSettings { ga, ..base }, own)
}

/// Checks the GA's keys whose serde errors would not name them: `operators` must name an
/// operator variant and `cross_array_index` be a boolean.
fn check_ga_keys(table: &toml::Table) -> Result<(), SettingsKeyError> {
    let names = OperatorVariant::ALL.map(OperatorVariant::name);
    match table.get("operators") {
        None => {}
        Some(toml::Value::String(v)) if names.contains(&v.as_str()) => {}
        Some(other) => {
            return Err(SettingsKeyError::new(
                "optimizer.operators",
                SettingsCause::UnknownVariant {
                    value: other.clone(),
                    what: "an operator",
                    variants: names.to_vec(),
                },
            ));
        }
    }
    match table.get("cross_array_index") {
        None | Some(toml::Value::Boolean(_)) => Ok(()),
        Some(other) => Err(SettingsKeyError::new(
            "optimizer.cross_array_index",
            SettingsCause::NotABool(other.clone()),
        )),
    }
}

/// Checks that `variant`, whose serde error would not name it, is one of `names`, the
/// variants of `what` method.
fn check_variant(
    table: &toml::Table,
    what: &'static str,
    names: &[&'static str],
) -> Result<(), SettingsKeyError> {
    match table.get("variant") {
        None => Ok(()),
        Some(toml::Value::String(v)) if names.contains(&v.as_str()) => Ok(()),
        Some(other) => Err(SettingsKeyError::new(
            "optimizer.variant",
            SettingsCause::UnknownVariant {
                value: other.clone(),
                what,
                variants: names.to_vec(),
            },
        )),
    }
}

methods! {
    /// The genetic algorithm.
    Ga("ga"): optimize::Ga, GaSettings, colour [30, 80, 200],
        preset |p| p.ga, read read_ga;
    /// Sequential Monte Carlo, growing in chromosome order.
    Smc("smc"): optimize::Smc, SmcSettings, colour [230, 120, 20],
        preset |p| SmcSettings { order: Order::Chromosome, ..p.smc }, read read_smc;
    /// Sequential Monte Carlo with stochastic futures.
    Sosmc("sosmc"): optimize::Smc, SmcSettings, colour [30, 150, 60],
        preset |p| SmcSettings { order: Order::Stochastic, ..p.sosmc }, read read_smc;
    /// Reversible-jump MCMC with parallel tempering.
    Rjmcmc("rjmcmc"): optimize::Mcmc, McmcSettings, colour [200, 30, 40],
        preset |p| p.rjmcmc, read read_mcmc;
    /// The GA with its first population seeded by SOSMC and its best refined by short
    /// RJMCMC chains.
    Hybrid("hybrid"): optimize::Hybrid, HybridSettings, colour [130, 60, 170],
        preset |p| HybridSettings::over(p.ga), read read_hybrid;
    /// Plain random search, the baseline: models drawn from the generator's own
    /// distribution, as many each generation as the GA scores, the best kept.
    Random("random"): optimize::RandomSearch, optimize::RandomSearchSettings, colour [120, 120, 120],
        preset |p| optimize::RandomSearchSettings {
            samples: p.ga.population - p.ga.elitism,
            generations: p.ga.generations,
        }, read merged;
}

/// A key of the `[optimizer]` or `[islands]` table, or the flag in its place, that cannot
/// be used: the key, and the cause as the `source()`.
///
/// ```
/// use shapegen::registry::Registry;
/// use shapegen::scene::{Method, Overrides, Scene, SceneError, SettingsCause};
///
/// let overrides = Overrides { seconds: Some(-1.0), ..Overrides::default() };
/// let path = "scenes/paper/spaceship_volume.toml";
/// let err = Scene::open(path, &Registry::published(), &overrides).unwrap_err();
/// let SceneError::Optimizer { error, .. } = &err else { panic!("{err}") };
/// assert_eq!(error.key, "--seconds");
/// assert!(matches!(error.cause, SettingsCause::OutOfRange { .. }));
/// assert!(err.to_string().ends_with("`--seconds`: -1 must be a number of seconds > 0"));
/// ```
#[derive(Debug, thiserror::Error)]
#[error("`{key}`")]
pub struct SettingsKeyError {
    /// The key at fault: a dotted key (`optimizer.population`, `islands.count`), a table
    /// (`optimizer`, `islands`) or a flag (`--seconds`, `--islands`).
    pub key: String,
    /// What is wrong with its value and what would be valid.
    #[source]
    pub cause: SettingsCause,
}

impl SettingsKeyError {
    /// The error of `key`, for `cause`.
    pub(super) fn new(key: impl Into<String>, cause: impl Into<SettingsCause>) -> Self {
        SettingsKeyError {
            key: key.into(),
            cause: cause.into(),
        }
    }
}

/// What is wrong with a key of the `[optimizer]` or `[islands]` table, or the flag in its
/// place.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SettingsCause {
    /// The method's settings check refuses the value: the field, the value and the valid
    /// range.
    #[error(transparent)]
    Settings(#[from] SettingsError),
    /// The value is of the wrong type for the field, or the key is not one of the
    /// method's fields, in serde's words.
    #[error("{}", .0.message())]
    Toml(toml::de::Error),
    /// The method's settings could not be written as a table to read the keys over.
    #[error(transparent)]
    Table(#[from] toml::ser::Error),
    /// `method` names no method.
    #[error(transparent)]
    UnknownMethod(#[from] UnknownMethod),
    /// `method` is not a name.
    #[error("{0} is not a method; the methods are {names}", names = Method::names())]
    NotAMethod(toml::Value),
    /// `order`, which the method sets: SMC grows in chromosome order, SOSMC in a
    /// stochastic one.
    #[error("is set by the method: \"smc\" or \"sosmc\"")]
    OrderSetByMethod,
    /// `variant` or `operators` names none of the variants.
    #[error(
        "{value} is not {what} variant; the variants are \"{}\"",
        variants.join("\" and \"")
    )]
    UnknownVariant {
        /// The value given.
        value: toml::Value,
        /// Whose variants, with the article: `an SMC`, `an operator`.
        what: &'static str,
        /// The variants' names.
        variants: Vec<&'static str>,
    },
    /// A value that must be a boolean is not.
    #[error("{0} must be true or false")]
    NotABool(toml::Value),
    /// A seed, a budget or a size out of its range: `seed`, `seconds`, `evaluations`,
    /// `archive`, `--seconds`, `--evaluations`.
    #[error("{value} must be {valid}")]
    OutOfRange {
        /// The value given, printed.
        value: String,
        /// The valid range, in words: `a whole number > 0`.
        valid: &'static str,
    },
    /// Islands (`[islands]`, `--islands`) with a method other than the GA, which the
    /// island model runs.
    #[error(
        "the island model runs the GA, and the method is \"{}\"; leave out [islands] and \
         --islands, or use method \"ga\"",
        .0.name()
    )]
    IslandsNeedGa(Method),
}
