//! The generators a module knows: the facade's [`Registry`], and for each generator its
//! grammar behind the [`Erased`] interface that the Python objects call.

use std::collections::BTreeMap;
use std::sync::Arc;

use shapegen::Grammar;
use shapegen::registry::{AddGrammar, Defaults, Entry, Registry, RegistryError};

use crate::typed::{Erased, Typed};

/// The generators of one Python module, by name.
#[derive(Default)]
pub struct Catalog {
    registry: Registry,
    grammars: BTreeMap<String, Arc<dyn Erased>>,
}

impl AddGrammar for Catalog {
    fn add<G: Grammar>(&mut self, name: &str, defaults: Defaults) -> Result<(), RegistryError> {
        self.registry.add::<G>(name, defaults)?;
        self.grammars
            .insert(name.to_owned(), Arc::new(Typed::<G>::default()));
        Ok(())
    }
}

impl Catalog {
    /// The registry, to read scenes with.
    pub fn registry(&self) -> &Registry {
        &self.registry
    }

    /// The generator named `name`, or whose grammar is `name` ([`Registry::find`]), with
    /// its grammar.
    ///
    /// # Errors
    /// [`RegistryError::Unknown`], naming the generators there are.
    pub(crate) fn find(&self, name: &str) -> Result<(&Entry, Arc<dyn Erased>), RegistryError> {
        let entry = self.registry.find(name)?;
        let grammar = Arc::clone(
            self.grammars
                .get(&entry.name)
                .expect("every registered generator has its grammar"),
        );
        Ok((entry, grammar))
    }
}
