//! The command line's `--set key=value` overrides.

/// Why a `--set` override cannot be applied to a scene's TOML.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum SetError {
    /// There is no `=`.
    #[error("--set {set}: write it as key=value, e.g. optimizer.seed=3")]
    NotKeyValue {
        /// The override as given.
        set: String,
    },
    /// The key has an empty part (`optimizer..seed`, `=3`).
    #[error("--set {set}: `{key}` is not a dotted key")]
    NotDottedKey {
        /// The override as given.
        set: String,
        /// Its key.
        key: String,
    },
    /// A part of the key names a value that is not a table.
    #[error("--set {set}: `{part}` is not a table")]
    NotATable {
        /// The override as given.
        set: String,
        /// The part of its key that names a value, not a table.
        part: String,
    },
}
