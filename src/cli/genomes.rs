//! Reading the genome files the commands take: a single genome or a set, in the packed
//! or the nested JSON form, of the generator the file names.

use std::fmt;
use std::path::{Path, PathBuf};

use anyhow::Context;
use generators::Published;
use serde::Deserializer;
use serde::de::{DeserializeSeed, IgnoredAny, MapAccess, SeqAccess, Visitor};
use shapegen::genome::GenomeSet;
use shapegen::{Genome, Grammar};

/// A genome file read into memory, with what its top-level keys tell: the generator it
/// names, whether it is a set (`genomes`) and whether it is in the nested form (`tree`).
pub struct GenomeFile {
    path: PathBuf,
    text: String,
    /// The `generator` named, when it is a string.
    generator: Option<String>,
    /// Whether the file is a set: `{"generator", "genomes": [...]}`.
    pub set: bool,
    /// Whether the file is in the nested form: a `tree` at the top or in a genome of a set.
    pub nested: bool,
}

impl GenomeFile {
    /// Reads `path`, telling its kind from its keys; a fault in the text is left for
    /// [`genomes`](Self::genomes) to report.
    pub fn read(path: &Path) -> anyhow::Result<GenomeFile> {
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("cannot read genomes `{}`", path.display()))?;
        let mut keys = TopKeys::default();
        // A fault ends the reading; the keys seen before it tell the kind.
        let _ = serde_json::Deserializer::from_str(&text).deserialize_map(&mut keys);
        Ok(GenomeFile {
            path: path.to_owned(),
            text,
            generator: keys.generator,
            set: keys.set,
            nested: keys.nested,
        })
    }

    /// The published generator the file names.
    pub fn generator(&self) -> anyhow::Result<Published> {
        let name = self.generator.as_deref().with_context(|| {
            format!(
                "`{}` names no generator; a genome file names it as `\"generator\": \
                 \"Spaceship\"` (or Tree, City, Building)",
                self.path.display()
            )
        })?;
        name.parse()
            .with_context(|| format!("`{}`", self.path.display()))
    }

    /// Every genome of the file, checked fully.
    pub fn genomes<G: Grammar>(&self) -> anyhow::Result<Vec<Genome<G>>> {
        let genomes = if self.set {
            GenomeSet::<G>::from_json(&self.text).map(|set| set.genomes)
        } else {
            Genome::<G>::from_json(&self.text).map(|genome| vec![genome])
        };
        genomes.with_context(|| format!("cannot load genomes `{}`", self.path.display()))
    }

    /// The genome at `index` of the file.
    pub fn genome<G: Grammar>(&self, index: usize) -> anyhow::Result<Genome<G>> {
        let mut genomes = self.genomes::<G>()?;
        let count = genomes.len();
        anyhow::ensure!(
            index < count,
            "`{}` holds {count} genomes; --index must be below {count}",
            self.path.display()
        );
        Ok(genomes.swap_remove(index))
    }
}

/// The genomes in `path`: a set (`genomes.json` of `shapegen sample`) or a single genome
/// (`best.genome.json`), in either form.
pub fn load_genomes<G: Grammar>(path: &Path) -> anyhow::Result<Vec<Genome<G>>> {
    GenomeFile::read(path)?.genomes()
}

/// The genome at `index` of `path`.
pub fn load_genome<G: Grammar>(path: &Path, index: usize) -> anyhow::Result<Genome<G>> {
    GenomeFile::read(path)?.genome(index)
}

/// The keys of a genome file's top object, noted as they are read.
#[derive(Default)]
struct TopKeys {
    generator: Option<String>,
    set: bool,
    nested: bool,
}

impl<'de> Visitor<'de> for &mut TopKeys {
    type Value = ();

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a genome file")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<(), A::Error> {
        while let Some(key) = map.next_key::<String>()? {
            match key.as_str() {
                "generator" => {
                    let name = map.next_value::<serde_json::Value>()?;
                    self.generator = name.as_str().map(str::to_owned);
                }
                "genomes" => {
                    self.set = true;
                    map.next_value_seed(SetGenomes(&mut self.nested))?;
                }
                "tree" => {
                    self.nested = true;
                    map.next_value::<IgnoredAny>()?;
                }
                _ => {
                    map.next_value::<IgnoredAny>()?;
                }
            }
        }
        Ok(())
    }
}

/// A set's `genomes`: notes a `tree` in any genome.
struct SetGenomes<'a>(&'a mut bool);

impl<'de> DeserializeSeed<'de> for SetGenomes<'_> {
    type Value = ();

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<(), D::Error> {
        d.deserialize_seq(self)
    }
}

impl<'de> Visitor<'de> for SetGenomes<'_> {
    type Value = ();

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a list of genomes")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<(), A::Error> {
        while seq.next_element_seed(SetGenome(&mut *self.0))?.is_some() {}
        Ok(())
    }
}

/// One genome of a set: notes a `tree` key.
struct SetGenome<'a>(&'a mut bool);

impl<'de> DeserializeSeed<'de> for SetGenome<'_> {
    type Value = ();

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<(), D::Error> {
        d.deserialize_map(self)
    }
}

impl<'de> Visitor<'de> for SetGenome<'_> {
    type Value = ();

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a genome")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<(), A::Error> {
        while let Some(key) = map.next_key::<String>()? {
            *self.0 |= key == "tree";
            map.next_value::<IgnoredAny>()?;
        }
        Ok(())
    }
}
