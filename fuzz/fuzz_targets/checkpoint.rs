//! Checkpoints as `shapegen run --resume DIR` reads them: `checkpoint.json` holds the
//! scene, the overrides and the search's state, read as each method's state of each
//! published grammar. A state that reads is resumed (unless its settings hold more
//! genomes than the tool's memory check would let through), and a resumed search is run
//! one more generation (scored by genome length), as a resumed run goes on.

#![no_main]

use std::path::PathBuf;

use generators::{Building, City, Spaceship, Tree};
use libfuzzer_sys::fuzz_target;
use serde::Deserialize;
use serde::de::DeserializeOwned;
use shapegen::scene::Overrides;
use shapegen_runtime::optimize::islands::IslandGa;
use shapegen_runtime::optimize::multi::MultiGa;
use shapegen_runtime::optimize::{
    Best, Budget, Checkpoint as _, EvaluateError, FnEvaluator, Ga, Mcmc, MultiEvaluator, Optimizer,
    Sense, Session, Smc,
};
use shapegen_runtime::{Genome, Grammar};

/// `checkpoint.json`, as the command-line tool writes it.
#[derive(Deserialize)]
#[allow(dead_code)]
struct Checkpoint<S> {
    scene: PathBuf,
    overrides: Overrides,
    search: S,
}

/// Most genomes a resumed state may hold here: the command-line tool refuses a
/// checkpoint whose settings hold more than the memory allows before resuming it
/// (`check_resumed` in `src/cli/memory.rs`); this stands in for that check.
const MAX_GENOMES: u64 = 100_000;

/// The state of `O`, if `json` is a checkpoint of it.
fn state<G: Grammar, O: Optimizer<G>>(json: &[u8]) -> Option<O>
where
    O::State: DeserializeOwned,
{
    let checkpoint: Checkpoint<O::State> = serde_json::from_slice(json).ok()?;
    let held = O::genomes_held(checkpoint.search.settings());
    if held.iter().map(|h| h.genomes).sum::<u64>() > MAX_GENOMES {
        return None;
    }
    O::resume(checkpoint.search).ok()
}

/// One more generation of a single-fitness search, if `json` is a checkpoint of one.
fn single<G: Grammar, O: Optimizer<G, Record = Best<G>>>(json: &[u8])
where
    O::State: DeserializeOwned,
{
    if let Some(optimizer) = state::<G, O>(json) {
        let next = optimizer.progress().generation + 1;
        let mut by_length = FnEvaluator(|g: &Genome<G>| g.len() as f64);
        let _ = Session::new(optimizer, Budget::generations(next)).run(&mut by_length);
    }
}

/// Two objectives: the genome's length, and its first gene's node.
struct Lengths;

impl<G: Grammar> MultiEvaluator<G> for Lengths {
    fn senses(&self) -> &[Sense] {
        &[Sense::Maximize, Sense::Minimize]
    }

    fn evaluate(&mut self, genomes: &[Genome<G>], out: &mut [f64]) -> Result<(), EvaluateError> {
        for (g, o) in genomes.iter().zip(out.chunks_mut(2)) {
            o[0] = g.len() as f64;
            o[1] = (g.len() % 7) as f64;
        }
        Ok(())
    }
}

fn grammar<G: Grammar>(json: &[u8]) {
    single::<G, Ga<G>>(json);
    single::<G, IslandGa<G>>(json);
    single::<G, Smc<G>>(json);
    single::<G, Mcmc<G>>(json);
    if let Some(optimizer) = state::<G, MultiGa<G>>(json) {
        let next = optimizer.progress().generation + 1;
        let _ = Session::new(optimizer, Budget::generations(next)).run(&mut Lengths);
    }
}

fuzz_target!(|data: &[u8]| {
    grammar::<Spaceship>(data);
    grammar::<Tree>(data);
    grammar::<City>(data);
    grammar::<Building>(data);
});
