//! Reading the genome files the commands take: a single genome or a set, in the packed
//! or the nested JSON form, of the generator the file names.

use std::path::{Path, PathBuf};

use anyhow::Context;
use shapegen::genome::{GenomeSet, JsonLayout};
use shapegen::{Genome, Grammar};

use crate::registry::{Entry, Registry};

/// A genome file read into memory, with what its top-level keys tell: the generator it
/// names, whether it is a set (`genomes`) and whether it is in the nested form (`tree`).
pub struct GenomeFile {
    path: PathBuf,
    text: String,
    /// What the file's keys tell.
    pub layout: JsonLayout,
}

impl GenomeFile {
    /// Reads `path`, telling its kind from its keys; a fault in the text is left for
    /// [`genomes`](Self::genomes) to report.
    pub fn read(path: &Path) -> anyhow::Result<GenomeFile> {
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("cannot read genomes `{}`", path.display()))?;
        Ok(GenomeFile {
            path: path.to_owned(),
            layout: JsonLayout::of(&text),
            text,
        })
    }

    /// The generator of `tool` the file names (as `"spaceship"`, or `"Spaceship"`).
    pub fn generator<'r>(&self, registry: &'r Registry) -> anyhow::Result<&'r Entry> {
        let name = self.layout.generator.as_deref().with_context(|| {
            format!(
                "`{}` names no generator; a genome file names it as `\"generator\": \
                 \"spaceship\"`",
                self.path.display()
            )
        })?;
        registry
            .find(name)
            .with_context(|| format!("`{}`", self.path.display()))
    }

    /// Every genome of the file, checked fully.
    pub fn genomes<G: Grammar>(&self) -> anyhow::Result<Vec<Genome<G>>> {
        let genomes = if self.layout.set {
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
