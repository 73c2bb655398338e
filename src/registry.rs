//! The generators a scene can name, with what each brings besides its grammar: the
//! meshes it uses when a scene gives none, the genome limits `shapegen sample` uses, and
//! each search method's settings where a scene's `[optimizer]` table leaves them out.
//!
//! [`Registry::published`] holds the four published generators with the original's
//! settings; a user's own generators are added with [`Registry::add`] (the command-line
//! tool's `Cli::generator` does it).
//!
//! ```
//! use shapegen::prelude::*;
//! use shapegen::registry::{AddGrammar, Defaults, Registry};
//!
//! generator! {
//!     /// A stack of blocks.
//!     pub Stack {
//!         axiom Block;
//!         node Block {
//!             children { next: Block = 0.7 }
//!             derive(s) {
//!                 s.emit(CUBE);
//!                 if let Some(next) = next { s.translate(vec3(0.0, 1.0, 0.0)).derive(next); }
//!             }
//!         }
//!     }
//! }
//!
//! let mut registry = Registry::published();
//! registry.add::<Stack>("stack", Defaults::default())?;
//! assert_eq!(registry.get("stack").unwrap().grammar, "Stack");
//! // Genome files name their generator by its grammar (`"stack"`, or `"Stack"`), scenes
//! // by its registered name.
//! assert_eq!(registry.find("Stack").unwrap().name, "stack");
//! assert_eq!(registry.get("stack").unwrap().key, "stack");
//! // Its meshes, by id: what the parts of its scenes' objectives are looked up in.
//! assert_eq!(registry.get("stack").unwrap().mesh_names, ["cube"]);
//! assert!(registry.add::<Stack>("spaceship", Defaults::default()).is_err());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub use generators::Presets;
use generators::{GeneratorVisitor, Published};
use shapegen_runtime::Grammar;
use shapegen_runtime::genome::Limits;
use shapegen_runtime::geometry::MeshLibrary;

/// What a generator brings besides its grammar.
#[derive(Clone, Debug)]
pub struct Defaults {
    /// The meshes its models use, by name; a scene's `[meshes]` table replaces or adds
    /// to them. The built-in `cube` is always there.
    pub meshes: MeshLibrary,
    /// The genome limits `shapegen sample` draws within unless told otherwise.
    pub limits: Limits,
    /// Each method's settings where a scene leaves them out.
    pub presets: Presets,
}

impl Default for Defaults {
    /// The built-in meshes only, genomes of at most 200 genes and 30 levels, and every
    /// method's own settings.
    fn default() -> Self {
        Defaults {
            meshes: MeshLibrary::new(),
            limits: Limits {
                min_len: 1,
                max_len: 200,
                max_depth: 30,
            },
            presets: Presets::default(),
        }
    }
}

/// A generator known by name.
#[derive(Clone, Debug)]
pub struct Entry {
    /// The name scenes and the command line use (`generator = "tower"`).
    pub name: String,
    /// The grammar's own name (`Tower`).
    pub grammar: &'static str,
    /// The grammar's name in snake case, which genome files record
    /// (`"generator": "tower"`; [`GeneratorGraph::key`](shapegen_runtime::GeneratorGraph::key)).
    pub key: &'static str,
    /// The names of the grammar's meshes, in id order
    /// ([`GeneratorGraph::meshes`](shapegen_runtime::GeneratorGraph::meshes)): what the
    /// parts a scene's objectives name are resolved against.
    pub mesh_names: &'static [&'static str],
    /// Its defaults.
    pub defaults: Defaults,
}

/// A name is already taken, or is not usable.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum RegistryError {
    /// Two generators under one name.
    #[error("a generator named `{0}` is already registered; give the new one another name")]
    Taken(String),
    /// A name that scene files could not write plainly.
    #[error(
        "`{0}` cannot name a generator: use letters, digits, `_` and `-`, starting with a letter"
    )]
    BadName(String),
    /// No generator has the name.
    #[error("unknown generator `{name}`; the generators are {known}")]
    Unknown {
        /// The name looked up.
        name: String,
        /// The names there are ([`Registry::names`]).
        known: String,
    },
}

/// Something generators are added to, each with its grammar type: a [`Registry`], or
/// the command-line tool's registry of runnable generators.
pub trait AddGrammar {
    /// Adds grammar `G` under `name` with `defaults`.
    ///
    /// # Errors
    /// When `name` is taken (names compare without case) or is not a plain identifier.
    fn add<G: Grammar>(&mut self, name: &str, defaults: Defaults) -> Result<(), RegistryError>;
}

/// Adds the published generators to `to`, each under its grammar's key (`spaceship`,
/// `tree`, `city`, `building`, `roofed_building`, `lot_building`), with its own meshes,
/// its paper scene's limits and the original's settings of every method (the buildings,
/// which have no paper scene, take the thesis's GA).
///
/// # Errors
/// When a published generator's name is taken in `to`.
pub fn add_published(to: &mut impl AddGrammar) -> Result<(), RegistryError> {
    let meshes = generators::default_meshes();
    for generator in Published::ALL {
        generator.visit(Add {
            to: &mut *to,
            defaults: published_defaults(generator, &meshes),
        })?;
    }
    Ok(())
}

/// The generators a run can name; see the [module documentation](self).
#[derive(Clone, Debug, Default)]
pub struct Registry {
    entries: Vec<Entry>,
}

impl Registry {
    /// No generators.
    pub fn new() -> Self {
        Registry::default()
    }

    /// The published generators ([`Published`]: the paper's `spaceship`, `tree` and
    /// `city`, the buildings and the others), with their own meshes, their limits and
    /// their presets (the original's settings of every method for the paper's; the
    /// buildings, which have no paper scene, take the thesis's GA).
    pub fn published() -> Self {
        let mut registry = Registry::new();
        add_published(&mut registry).expect("the published generators have distinct plain names");
        registry
    }

    /// The generator registered as `name` (without regard to case).
    pub fn get(&self, name: &str) -> Option<&Entry> {
        self.entries
            .iter()
            .find(|e| e.name.eq_ignore_ascii_case(name))
    }

    /// The generator named `name`, or whose grammar is `name` in either spelling
    /// (genome files record `"spaceship"`, older ones `"Spaceship"`), without regard to
    /// case.
    ///
    /// # Errors
    /// [`RegistryError::Unknown`], naming the generators there are.
    pub fn find(&self, name: &str) -> Result<&Entry, RegistryError> {
        let by_grammar =
            |e: &&Entry| e.grammar.eq_ignore_ascii_case(name) || e.key.eq_ignore_ascii_case(name);
        self.get(name)
            .or_else(|| self.entries.iter().find(by_grammar))
            .ok_or_else(|| RegistryError::Unknown {
                name: name.to_owned(),
                known: self.names(),
            })
    }

    /// Every generator, in the order they were added.
    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }

    /// The names, for messages: `spaceship, tree, city, building, roofed_building and
    /// lot_building`.
    pub fn names(&self) -> String {
        let names: Vec<&str> = self.entries.iter().map(|e| e.name.as_str()).collect();
        match names.split_last() {
            None => "none".to_owned(),
            Some((last, [])) => (*last).to_owned(),
            Some((last, rest)) => format!("{} and {last}", rest.join(", ")),
        }
    }
}

impl AddGrammar for Registry {
    fn add<G: Grammar>(&mut self, name: &str, defaults: Defaults) -> Result<(), RegistryError> {
        let plain = name.chars().next().is_some_and(|c| c.is_ascii_alphabetic())
            && name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
        if !plain {
            return Err(RegistryError::BadName(name.to_owned()));
        }
        if self.get(name).is_some() {
            return Err(RegistryError::Taken(name.to_owned()));
        }
        self.entries.push(Entry {
            name: name.to_owned(),
            grammar: G::GRAPH.name,
            key: G::GRAPH.key,
            mesh_names: G::GRAPH.meshes,
            defaults,
        });
        Ok(())
    }
}

/// What published `generator` brings: `meshes` (the published generators' own,
/// [`generators::default_meshes`]), its paper scene's limits, and the original's settings of
/// every method for that scene.
fn published_defaults(generator: Published, meshes: &MeshLibrary) -> Defaults {
    Defaults {
        meshes: meshes.clone(),
        limits: generator.paper_limits(),
        presets: generator.presets(),
    }
}

/// Adds the grammar a [`Published`] generator visits with, under its key.
struct Add<'a, A> {
    to: &'a mut A,
    defaults: Defaults,
}

impl<A: AddGrammar> GeneratorVisitor for Add<'_, A> {
    type Output = Result<(), RegistryError>;

    fn visit<G: Grammar>(self, _: Limits) -> Self::Output {
        self.to.add::<G>(G::GRAPH.key, self.defaults)
    }
}
