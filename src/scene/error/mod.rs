//! Why a scene could not be loaded, scored or searched: [`SceneError`], and the typed
//! causes it carries, each in a module of what it is about (those of the `[optimizer]`
//! table, [`SettingsKeyError`](crate::scene::SettingsKeyError), beside the table of
//! methods that reads it).
//!
//! A [`SceneError`]'s message is whole: the file, the key at fault and the cause with its
//! own chain of causes. So that printing the chain (`{:#}` of an `anyhow::Error`) does
//! not repeat the cause, only [`SceneError::Io`] exposes its cause as its
//! [`source()`](std::error::Error::source), and [`SceneError::Backend`] is the
//! backend's error itself; the others keep their cause as a typed field. The causes
//! follow the runtime's convention: a message never repeats what its `source()` gives.

mod backend;
mod image;
mod lot;
mod scene;
mod set;
mod value;

pub use backend::BackendError;
pub use image::{DecodeError, ImageError};
pub use lot::LotError;
pub use scene::SceneError;
pub use set::SetError;
pub use value::ValueError;
