//! Genome files in both JSON forms (packed `genes`, nested `tree`), one genome or a set,
//! for each published grammar. A genome that reads derives its model; what is written of
//! it in the packed form reads back as the same genome, and in the nested form (which
//! leaves the buffer's layout to the reader) as one with the same tree and model.

#![no_main]

use generators::{Building, City, Spaceship, Tree};
use libfuzzer_sys::fuzz_target;
use shapegen_runtime::genome::GenomeSet;
use shapegen_runtime::{Genome, Grammar};

/// Checks the round trips of `genome`.
fn round_trips<G: Grammar>(genome: &Genome<G>) {
    let mut instances = Vec::new();
    genome.derive_into(&mut instances);
    let packed = genome.to_json();
    assert_eq!(
        Genome::<G>::from_json(&packed).ok().as_ref(),
        Some(genome),
        "{packed}"
    );
    let nested = genome.to_nested_json();
    let read = Genome::<G>::from_json(&nested).expect("the nested form reads back");
    assert_eq!(read.to_nested_json(), nested);
    let mut again = Vec::new();
    read.derive_into(&mut again);
    assert!(
        again == instances,
        "the same model from the nested form: {nested}"
    );
}

fn check<G: Grammar>(json: &str) {
    if let Ok(genome) = Genome::<G>::from_json(json) {
        round_trips(&genome);
    }
    if let Ok(set) = GenomeSet::<G>::from_json(json) {
        let packed = set.to_json();
        assert_eq!(
            GenomeSet::<G>::from_json(&packed).ok().as_ref(),
            Some(&set),
            "{packed}"
        );
        set.genomes.iter().for_each(round_trips);
    }
}

fuzz_target!(|data: &[u8]| {
    let Ok(json) = std::str::from_utf8(data) else {
        return;
    };
    check::<Spaceship>(json);
    check::<Tree>(json);
    check::<City>(json);
    check::<Building>(json);
});
