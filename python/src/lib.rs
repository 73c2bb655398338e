//! The `shapegen` Python package, and the macro that makes such a package for a crate's
//! own generators.
//!
//! [`module!`] makes a whole Python module (generators, scenes, searches, models and
//! genomes as Python objects, numpy arrays for geometry, Python exceptions for errors)
//! for the generators it is given. The `shapegen` wheel is this crate built by maturin
//! with its feature `module`, which is the macro applied to the published generators:
//!
//! ```ignore
//! shapegen_python::module!(shapegen, published);
//! ```
//!
//! A crate with its own generators builds its own wheel the same way: a `cdylib`
//! depending on this crate (and on `pyo3` for its build), built by maturin, whose
//! `lib.rs` names its generators (`examples/python-tower` in the repository is such a
//! crate):
//!
//! ```ignore
//! use shapegen::prelude::*;
//!
//! generator! {
//!     /// A tower of boxes.
//!     pub Tower {
//!         axiom Floor;
//!         node Floor {
//!             children { up: Floor = 0.8 }
//!             derive(s) {
//!                 s.emit(CUBE);
//!                 if let Some(up) = up { s.translate(vec3(0.0, 1.0, 0.0)).derive(up); }
//!             }
//!         }
//!     }
//! }
//!
//! // `import tower` in Python: `tower.generators() == ["tower"]`; with `published,`
//! // before the list, the published generators too.
//! shapegen_python::module!(tower, [Tower]);
//! ```
//!
//! The crate must be a dependency under its own name, `shapegen_python`, since the
//! expansion names it so. Each generator is registered under its grammar's key (`Tower` as `tower`) with
//! [`Defaults::default`](shapegen::registry::Defaults); scenes and genome files name it
//! so. The Python API itself is described in `shapegen.pyi` beside this crate.

// The macro's expansion names this crate as its users do.
extern crate self as shapegen_python;

mod arrays;
mod catalog;
mod checkpoint;
mod compared;
mod error;
mod module;
mod objects;
mod scene;
mod typed;

pub use catalog::Catalog;

/// What [`module!`]'s expansion uses; not a public API.
#[doc(hidden)]
pub mod __private {
    pub use crate::module::init;
    pub use pyo3;
    pub use shapegen::Grammar;
    pub use shapegen::registry::{AddGrammar, Defaults, add_published};
}

/// Makes the Python module `name` for the given generators: `module!(name, [A, B])` for
/// grammars `A` and `B`, each under its grammar's key, `module!(name, published)` for
/// the published generators, and `module!(name, published, [A, B])` for both. See the
/// [crate documentation](crate).
#[macro_export]
macro_rules! module {
    ($name:ident, published $(, [$($grammar:ty),* $(,)?])? $(,)?) => {
        $crate::module!(@make $name, |catalog| {
            $crate::__private::add_published(&mut *catalog)?;
            $($($crate::module!(@add catalog, $grammar);)*)?
            Ok(())
        });
    };
    ($name:ident, [$($grammar:ty),* $(,)?] $(,)?) => {
        $crate::module!(@make $name, |catalog| {
            $($crate::module!(@add catalog, $grammar);)*
            Ok(())
        });
    };
    (@add $catalog:ident, $grammar:ty) => {
        $crate::__private::AddGrammar::add::<$grammar>(
            &mut *$catalog,
            <$grammar as $crate::__private::Grammar>::GRAPH.key,
            $crate::__private::Defaults::default(),
        )?;
    };
    (@make $name:ident, $fill:expr) => {
        // PyO3's expansion calls its unsafe entry point as written for edition 2021.
        #[allow(unsafe_op_in_unsafe_fn)]
        #[doc(hidden)]
        mod __shapegen_python_module {
            #[allow(unused_imports)]
            use super::*;

            /// The Python module of these generators.
            #[$crate::__private::pyo3::pymodule]
            #[pyo3(crate = "::shapegen_python::__private::pyo3")]
            fn $name(
                module: &$crate::__private::pyo3::Bound<'_, $crate::__private::pyo3::types::PyModule>,
            ) -> $crate::__private::pyo3::PyResult<()> {
                $crate::__private::init(module, $fill)
            }
        }
    };
}

#[cfg(feature = "module")]
module!(shapegen, published);
