//! Reading the genome files the commands take.

use std::path::Path;

use anyhow::Context;
use shapegen::genome::GenomeSet;
use shapegen::{Genome, Grammar};

/// The genomes in `path`: a set (`genomes.json` of `shapegen sample`) or a single genome
/// (`best.genome.json`).
pub fn load_genomes<G: Grammar>(path: &Path) -> anyhow::Result<Vec<Genome<G>>> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("cannot read genomes `{}`", path.display()))?;
    let is_set = serde_json::from_str::<serde_json::Value>(&text)
        .map(|v| v.get("genomes").is_some())
        .unwrap_or(false);
    let genomes = if is_set {
        GenomeSet::<G>::from_json(&text).map(|set| set.genomes)
    } else {
        Genome::<G>::from_json(&text).map(|genome| vec![genome])
    };
    genomes.with_context(|| format!("cannot load genomes `{}`", path.display()))
}

/// The genome at `index` of `path`.
pub fn load_genome<G: Grammar>(path: &Path, index: usize) -> anyhow::Result<Genome<G>> {
    let mut genomes = load_genomes::<G>(path)?;
    let count = genomes.len();
    anyhow::ensure!(
        index < count,
        "`{}` holds {count} genomes; --index must be below {count}",
        path.display()
    );
    Ok(genomes.swap_remove(index))
}
