//! Errors as Python exceptions, with the messages the tool prints.
//!
//! Every error is a `shapegen.ShapegenError` (a `ValueError`); its subclasses say what
//! failed: `SceneError` (a scene that cannot be read or used), `GenomeError` (a genome
//! that is not one of the generator's), `SearchError` (a search that could not start or
//! go on) and `GeneratorError` (an unknown generator, a name that is taken).

use pyo3::PyErr;
use pyo3::exceptions::PyValueError;

pyo3::create_exception!(
    shapegen,
    ShapegenError,
    PyValueError,
    "What shapegen refused or could not do; the message says what and why."
);
pyo3::create_exception!(
    shapegen,
    SceneError,
    ShapegenError,
    "A scene that cannot be read or used: the file, the key and the reason."
);
pyo3::create_exception!(
    shapegen,
    GenomeError,
    ShapegenError,
    "A genome that is not one of the generator's: the gene or path at fault."
);
pyo3::create_exception!(
    shapegen,
    SearchError,
    ShapegenError,
    "A search that could not start or go on."
);
pyo3::create_exception!(
    shapegen,
    GeneratorError,
    ShapegenError,
    "An unknown generator, or a name that cannot be registered."
);

/// What failed, with the message to raise.
#[derive(Debug)]
pub enum Error {
    /// A scene.
    Scene(String),
    /// A genome.
    Genome(String),
    /// A search.
    Search(String),
    /// A generator's name.
    Generator(String),
    /// An argument out of range.
    Value(String),
}

impl Error {
    /// `error` as the tool prints it: its message and its causes, joined by `: `.
    pub fn chain(error: &dyn std::error::Error) -> String {
        let mut message = error.to_string();
        let mut source = error.source();
        while let Some(cause) = source {
            let text = cause.to_string();
            if !message.contains(&text) {
                message.push_str(": ");
                message.push_str(&text);
            }
            source = cause.source();
        }
        message
    }

    /// A scene's error.
    pub fn scene(error: impl std::error::Error) -> Error {
        Error::Scene(Error::chain(&error))
    }

    /// A genome's error.
    pub fn genome(error: impl std::error::Error) -> Error {
        Error::Genome(Error::chain(&error))
    }

    /// A search's error.
    pub fn search(error: impl std::error::Error) -> Error {
        Error::Search(Error::chain(&error))
    }
}

impl std::fmt::Display for Error {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Error::Scene(m)
            | Error::Genome(m)
            | Error::Search(m)
            | Error::Generator(m)
            | Error::Value(m) => f.write_str(m),
        }
    }
}

impl From<shapegen::registry::RegistryError> for Error {
    fn from(error: shapegen::registry::RegistryError) -> Self {
        Error::Generator(error.to_string())
    }
}

impl From<Error> for PyErr {
    fn from(error: Error) -> PyErr {
        match error {
            Error::Scene(m) => SceneError::new_err(m),
            Error::Genome(m) => GenomeError::new_err(m),
            Error::Search(m) => SearchError::new_err(m),
            Error::Generator(m) => GeneratorError::new_err(m),
            Error::Value(m) => ShapegenError::new_err(m),
        }
    }
}
