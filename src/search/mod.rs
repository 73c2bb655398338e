//! A scene's searches run from a program, without the tool's files: a program that wants
//! the results as values (the Python package, an editor's add-on) runs these, and gets
//! the same results as the tool for the same scene and seed.
//!
//! - [`Search`] is `shapegen run`: the scene's scorers on the backend chosen, its method
//!   with its settings, seed and budget, and a progress hook that sees every generation
//!   and may stop the run.
//! - [`FrontSearch`] is `shapegen run` on a scene with `[[objective]]` tables: the
//!   multi-objective GA, and the front of non-dominated models it finds.
//! - [`Compare`] is `shapegen compare`: several methods, each run several times on shared
//!   seeds, with every run's result and measures and each method's summary
//!   ([`MethodSummary`], the statistics of [`stats`]); the tool writes its tables from
//!   these.
//!
//! ```
//! use std::path::Path;
//! use shapegen::optimize::{Control, Snapshot};
//! use shapegen::scene::{Overrides, Scene};
//! use shapegen::search::Search;
//! use generators::spaceship::Spaceship;
//!
//! let overrides = Overrides { method: "ga".parse().ok(), evaluations: Some(600), ..Overrides::default() };
//! let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/paper/spaceship_volume.toml");
//! let scene = Scene::open(&path, &shapegen::registry::Registry::published(), &overrides)?;
//! let mut generations = 0;
//! let mut watch = |s: &Snapshot<'_, Spaceship>| {
//!     generations += 1;
//!     if s.generation == 2 { Control::Stop } else { Control::Continue }
//! };
//! let found = Search::new(&scene).run::<Spaceship>(&mut watch)?;
//! assert_eq!((generations, found.result.generations), (3, 2));
//! assert_eq!(found.result.stopped.name(), "interrupted");
//! assert!(found.result.best_fitness.is_finite());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod compare;
mod error;
mod front;
mod single;
pub mod stats;

pub use compare::{Compare, CompareObserver, ComparedRun, Comparison, MethodSummary};
pub use error::{CompareError, SearchError};
pub use front::{FoundFront, FrontSearch, ranking_name, sorted_front};
pub use single::{Found, SaveHook, Search};
