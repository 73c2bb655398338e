//! Errors as text: [`error_chain`].

/// `err`'s message followed by those of its [`source()`](std::error::Error::source)
/// chain, joined by `": "` (what `{:#}` of an `anyhow::Error` prints): for putting an
/// error into a message of its own.
///
/// ```
/// use shapegen_runtime::error_chain;
/// use shapegen_runtime::genome::JsonError;
///
/// let err: JsonError = serde_json::from_str::<u32>("x").unwrap_err().into();
/// assert_eq!(err.to_string(), "not a genome in JSON");
/// assert_eq!(error_chain(&err), "not a genome in JSON: expected value at line 1 column 1");
/// ```
pub fn error_chain(err: &dyn std::error::Error) -> String {
    let mut text = err.to_string();
    let mut source = err.source();
    while let Some(cause) = source {
        text.push_str(": ");
        text.push_str(&cause.to_string());
        source = cause.source();
    }
    text
}
