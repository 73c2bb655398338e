//! The run viewer: `shapegen view DIR` (and `shapegen run --view`) serves a page that
//! shows a run's folder live, and `shapegen report DIR` writes the same page with
//! everything inline.
//!
//! The page is `assets/viewer/` (its HTML, script and style, and the vendored three.js
//! and uPlot), embedded in the binary. It reads only the files a run already writes
//! (`run.json`, `fitness.csv`, `best.glb`, the targets, and the tables of multi-objective,
//! `compare` and `sweep` folders), polling them once a second; the server answers from
//! the folder, read-only.

mod assets;
mod listing;
mod live;
mod path;
mod report;
mod server;

pub use assets::{ASSETS, Asset, MODULES, Module, asset};
pub use listing::{Listing, listing};
pub use live::Live;
pub use path::{MAX_TARGET, Refusal, RequestPath};
pub use report::report_html;
pub use server::Viewer;
