//! From a generator's name to its grammar type: each command's generic body is a
//! [`Visit`], and [`Generators::visit`] runs it with the grammar registered under the
//! name, through one small trait object per generator.

use std::collections::BTreeMap;
use std::marker::PhantomData;

use shapegen_runtime::Grammar;

use super::{compare, export, genome, memory, render, run, sample, score, sweep, target};
use crate::registry::{Defaults, Entry, Registry, RegistryError};

/// A command's body, generic over the grammar of the generator it works on.
pub trait Visit {
    /// Runs with grammar `G`, registered as `entry`.
    fn visit<G: Grammar>(self, entry: &Entry) -> anyhow::Result<()>;
}

/// Declares [`Job`], one variant per command body, and the dispatch from a `Job` to the
/// grammar a [`Typed`] holds.
macro_rules! jobs {
    ($($variant:ident($ty:ty)),* $(,)?) => {
        /// A command body waiting for its grammar.
        pub enum Job<'a> {
            $(
                #[doc = concat!("`", stringify!($ty), "`.")]
                $variant($ty),
            )*
        }

        $(
            impl<'a> From<$ty> for Job<'a> {
                fn from(visit: $ty) -> Self {
                    Job::$variant(visit)
                }
            }
        )*

        impl<G: Grammar> Dispatch for Typed<G> {
            fn dispatch(&self, job: Job<'_>, entry: &Entry) -> anyhow::Result<()> {
                match job {
                    $(Job::$variant(visit) => visit.visit::<G>(entry),)*
                }
            }
        }
    };
}

jobs! {
    Sample(sample::Sample<'a>),
    Score(score::Score<'a>),
    Target(target::Target<'a>),
    Render(render::Render<'a>),
    Run(run::Run<'a>),
    Compare(compare::Compare<'a>),
    Cell(sweep::cell::CellRun<'a>),
    Memory(memory::MemoryCheck<'a>),
    Export(export::Export<'a>),
    Convert(genome::Convert<'a>),
}

/// Runs a [`Job`] with one grammar.
trait Dispatch: Send + Sync {
    fn dispatch(&self, job: Job<'_>, entry: &Entry) -> anyhow::Result<()>;
}

/// The grammar `G`, as a [`Dispatch`] object.
struct Typed<G>(PhantomData<fn() -> G>);

/// The generators the tool knows: their [`Registry`] entries and their grammars.
#[derive(Default)]
pub struct Generators {
    registry: Registry,
    typed: BTreeMap<String, Box<dyn Dispatch>>,
}

impl Generators {
    /// Adds grammar `G` as `name`.
    pub fn add<G: Grammar>(&mut self, name: &str, defaults: Defaults) -> Result<(), RegistryError> {
        self.registry.add::<G>(name, defaults)?;
        self.typed
            .insert(name.to_owned(), Box::new(Typed::<G>(PhantomData)));
        Ok(())
    }

    /// The registry, to read scenes with.
    pub fn registry(&self) -> &Registry {
        &self.registry
    }

    /// The generator named `name`, or whose grammar is `name` (as genome files name it).
    pub fn find(&self, name: &str) -> anyhow::Result<&Entry> {
        self.registry.find(name).ok_or_else(|| {
            anyhow::anyhow!(
                "unknown generator `{name}`; the generators are {}",
                self.registry.names()
            )
        })
    }

    /// Runs `job` with the grammar of the generator [`find`](Self::find) finds.
    pub fn visit<'a>(&self, name: &str, job: impl Into<Job<'a>>) -> anyhow::Result<()> {
        let entry = self.find(name)?;
        let typed = self
            .typed
            .get(&entry.name)
            .expect("every registered generator has its grammar");
        typed.dispatch(job.into(), entry)
    }
}
