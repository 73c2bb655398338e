//! Why a key of a scene's `[optimizer]` table, or the command-line flag in its place,
//! cannot be used.

use shapegen_runtime::optimize::SettingsError;

use super::{Method, UnknownMethod};

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
    pub(in crate::scene) fn new(key: impl Into<String>, cause: impl Into<SettingsCause>) -> Self {
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
