//! The generators the tool knows: the library's [`Registry`], and for each generator how
//! to run a command's body with its grammar.
//!
//! A command's body is a [`Visit`], generic over the grammar. The tool's set of bodies
//! is one type, a [`Jobs`] (the `Job` enum of the tool's `commands`); when a generator
//! is added, [`Generators`] keeps for it a runner of every job with its grammar, and
//! [`Generators::visit`] looks the generator up by name in the registry and runs a job
//! with it. The commands see only [`Jobs`], so they do not depend on the list of
//! commands that dispatches them.

use std::collections::BTreeMap;
use std::marker::PhantomData;

use shapegen_runtime::Grammar;

use crate::registry::{AddGrammar, Defaults, Entry, Registry, RegistryError};

/// A command's body, generic over the grammar of the generator it works on.
pub trait Visit {
    /// Runs with grammar `G`, registered as `entry`.
    fn visit<G: Grammar>(self, entry: &Entry) -> anyhow::Result<()>;
}

/// Every command body the tool can run, as one type: [`Job`](Self::Job) holds one of
/// them, and [`run`](Self::run) runs it with a grammar.
pub trait Jobs: 'static {
    /// One of the bodies, with what it borrows.
    type Job<'a>;
    /// Runs `job` with grammar `G`, registered as `entry`.
    fn run<G: Grammar>(job: Self::Job<'_>, entry: &Entry) -> anyhow::Result<()>;
}

/// Runs the jobs of `J` with one grammar.
trait Runner<J: Jobs>: Send + Sync {
    fn run(&self, job: J::Job<'_>, entry: &Entry) -> anyhow::Result<()>;
}

/// The grammar `G`, as a [`Runner`].
struct Typed<G>(PhantomData<fn() -> G>);

impl<J: Jobs, G: Grammar> Runner<J> for Typed<G> {
    fn run(&self, job: J::Job<'_>, entry: &Entry) -> anyhow::Result<()> {
        J::run::<G>(job, entry)
    }
}

/// The generators the tool knows, with a runner of the jobs `J` for each.
pub struct Generators<J: Jobs> {
    registry: Registry,
    runners: BTreeMap<String, Box<dyn Runner<J>>>,
}

impl<J: Jobs> Default for Generators<J> {
    fn default() -> Self {
        Generators {
            registry: Registry::new(),
            runners: BTreeMap::new(),
        }
    }
}

impl<J: Jobs> AddGrammar for Generators<J> {
    fn add<G: Grammar>(&mut self, name: &str, defaults: Defaults) -> Result<(), RegistryError> {
        self.registry.add::<G>(name, defaults)?;
        self.runners
            .insert(name.to_owned(), Box::new(Typed::<G>(PhantomData)));
        Ok(())
    }
}

impl<J: Jobs> Generators<J> {
    /// The registry, to read scenes and genome files with.
    pub fn registry(&self) -> &Registry {
        &self.registry
    }

    /// Runs `job` with the grammar of the generator named `name`, or whose grammar is
    /// `name` (as genome files name it) ([`Registry::find`]).
    pub fn visit<'a>(&self, name: &str, job: impl Into<J::Job<'a>>) -> anyhow::Result<()> {
        let entry = self.registry.find(name)?;
        let runner = self
            .runners
            .get(&entry.name)
            .expect("every registered generator has its runner");
        runner.run(job.into(), entry)
    }
}
