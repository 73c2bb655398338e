//! The published spaceship, declared with `generator!`, matches its hand-written
//! expansion (`shapegen-runtime/tests/support/spaceship_expanded.rs`): same generator graph, and the same instances from
//! the same genomes, whether drawn from one seed, changed by the same operators or copied
//! from one grammar to the other through JSON.

#[path = "../../shapegen-runtime/tests/support/spaceship_expanded.rs"]
mod hand;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use shapegen_runtime::graph::{GeneratorGraph, NodeDesc};
use shapegen_runtime::{Genome, Grammar, NodeParams};

use generators::Spaceship;

fn assert_nodes_equal(a: &NodeDesc, b: &NodeDesc) {
    assert_eq!(a.name, b.name);
    assert_eq!(a.links, b.links, "links of {}", a.name);
    assert_eq!(a.param_words, b.param_words, "param_words of {}", a.name);
    assert_eq!(a.params.len(), b.params.len(), "params of {}", a.name);
    for (p, q) in a.params.iter().zip(b.params) {
        assert_eq!(p.name, q.name, "param of {}", a.name);
        assert_eq!(p.offset, q.offset, "offset of {}.{}", a.name, p.name);
        assert_eq!(p.dist, q.dist, "distribution of {}.{}", a.name, p.name);
    }
    assert_eq!(a.slots.len(), b.slots.len(), "slots of {}", a.name);
    for (s, t) in a.slots.iter().zip(b.slots) {
        assert_eq!(s.name, t.name, "slot of {}", a.name);
        assert_eq!(s.child, t.child, "child of {}.{}", a.name, s.name);
        assert_eq!(
            s.probability.to_bits(),
            t.probability.to_bits(),
            "probability of {}.{}",
            a.name,
            s.name
        );
        assert_eq!(s.count, t.count, "count of {}.{}", a.name, s.name);
        assert_eq!(
            s.first_link, t.first_link,
            "first link of {}.{}",
            a.name, s.name
        );
    }
}

fn assert_graphs_equal(a: &GeneratorGraph, b: &GeneratorGraph) {
    assert_eq!(a.name, b.name);
    assert_eq!(a.axiom, b.axiom);
    assert_eq!(a.meshes, b.meshes);
    assert_eq!(a.nodes.len(), b.nodes.len());
    for (m, n) in a.nodes.iter().zip(b.nodes) {
        assert_nodes_equal(m, n);
    }
}

#[test]
fn graph_equals_the_hand_expansion() {
    assert_graphs_equal(Spaceship::GRAPH, hand::Spaceship::GRAPH);
    assert!(Spaceship::GRAPH.layout_is_consistent());
}

#[test]
fn node_params_agree_with_the_hand_expansion() {
    macro_rules! same {
        ($($node:ident),*) => {$(
            assert_eq!(
                <generators::spaceship::$node as NodeParams>::KIND,
                <hand::$node as NodeParams>::KIND
            );
            assert_eq!(
                <generators::spaceship::$node as NodeParams>::LINKS,
                <hand::$node as NodeParams>::LINKS
            );
            assert_eq!(
                <generators::spaceship::$node as NodeParams>::WORDS,
                <hand::$node as NodeParams>::WORDS
            );
        )*};
    }
    same!(Start, Body, Top, TopNext, Wing, WingNext);
    let words = [1.0f32, 2.0, 3.0, 0.25].map(f32::to_bits);
    let wing = <generators::spaceship::WingNext as NodeParams>::read(&words);
    assert_eq!(wing.size, glam::vec3(1.0, 2.0, 3.0));
    assert_eq!(wing.shift, 0.25);
    let mut back = [0u32; 4];
    wing.write(&mut back);
    assert_eq!(back, words);
}

#[test]
fn axiom_genomes_derive_identically() {
    for seed in 0..64 {
        let a = Genome::<Spaceship>::axiom(&mut ChaCha8Rng::seed_from_u64(seed));
        let b = Genome::<hand::Spaceship>::axiom(&mut ChaCha8Rng::seed_from_u64(seed));
        assert_eq!(a.words(), b.words(), "seed {seed}");
        let (mut out_a, mut out_b) = (Vec::new(), Vec::new());
        a.derive_into(&mut out_a);
        b.derive_into(&mut out_b);
        assert_eq!(out_a, out_b, "seed {seed}");
    }
}

/// Derives both genomes and checks the instances are identical, bit for bit.
fn assert_same_derivation(
    a: &Genome<Spaceship>,
    b: &Genome<hand::Spaceship>,
    out_a: &mut Vec<shapegen_runtime::Instance>,
    out_b: &mut Vec<shapegen_runtime::Instance>,
    what: &str,
) {
    assert_eq!(a.words(), b.words(), "{what}: words");
    a.derive_into(out_a);
    b.derive_into(out_b);
    assert_eq!(out_a.len(), expected_boxes(a), "{what}");
    assert_eq!(out_a, out_b, "{what}: instances");
}

/// The number of boxes a spaceship derives to: one per Body, Top and TopNext, two per
/// Wing and WingNext (each wing is derived twice, mirrored); Start emits nothing.
fn expected_boxes(g: &Genome<Spaceship>) -> usize {
    g.genes()
        .map(|gene| match g.node(gene).name {
            "Body" | "Top" | "TopNext" => 1,
            "Wing" | "WingNext" => 2,
            _ => 0,
        })
        .sum()
}

#[test]
fn random_genomes_derive_identically() {
    use rand::RngExt;
    use shapegen_runtime::genome::Limits;
    use shapegen_runtime::ops::Operators;

    let limits = Limits::new(4, 100, 15).unwrap();
    let mut ops = Operators::<Spaceship>::new(limits).unwrap();
    let mut hops = Operators::<hand::Spaceship>::new(limits).unwrap();
    let (mut out_a, mut out_b) = (Vec::new(), Vec::new());
    for seed in 0..40 {
        // The graphs are equal, so one seed draws the same words in both grammars.
        let (mut r, mut hr) = (
            ChaCha8Rng::seed_from_u64(seed),
            ChaCha8Rng::seed_from_u64(seed),
        );
        let initial = 5 + 5 * seed as u32;
        let mut a = ops.random(initial, &mut r);
        let mut b = hops.random(initial, &mut hr);
        assert_same_derivation(&a, &b, &mut out_a, &mut out_b, &format!("seed {seed}"));
        let (mut a2, mut b2) = (ops.sample(&mut r), hops.sample(&mut hr));
        assert_same_derivation(&a2, &b2, &mut out_a, &mut out_b, "sample");
        // Then the same operators on both, step by step.
        for step in 0..50 {
            let what = format!("seed {seed}, step {step}");
            let op = r.random_range(0..4u32);
            assert_eq!(op, hr.random_range(0..4u32));
            match op {
                0 => assert_eq!(ops.grow(&mut a, &mut r), hops.grow(&mut b, &mut hr)),
                1 => assert_eq!(ops.cut(&mut a, &mut r), hops.cut(&mut b, &mut hr)),
                2 => assert_eq!(ops.alter(&mut a, &mut r), hops.alter(&mut b, &mut hr)),
                _ => {
                    let x = ops.crossover(&a, &a2, &mut r);
                    let y = hops.crossover(&b, &b2, &mut hr);
                    assert_eq!(x.is_some(), y.is_some(), "{what}");
                    if let (Some((c, d)), Some((e, f))) = (x, y) {
                        (a, a2, b, b2) = (c, d, e, f);
                        assert_same_derivation(&a2, &b2, &mut out_a, &mut out_b, &what);
                    }
                }
            }
            assert_same_derivation(&a, &b, &mut out_a, &mut out_b, &what);
        }
    }
}

#[test]
fn genomes_copied_through_json_derive_identically() {
    use shapegen_runtime::genome::{GenomeSet, Limits};
    use shapegen_runtime::ops::Operators;

    // Both grammars are named `Spaceship`, with the same node and slot names, so a genome
    // saved by one loads into the other.
    let mut hops = Operators::<hand::Spaceship>::new(Limits::new(1, 200, 20).unwrap()).unwrap();
    let mut r = ChaCha8Rng::seed_from_u64(99);
    let hand_genomes: Vec<_> = (0..30).map(|k| hops.random(1 + 6 * k, &mut r)).collect();
    let set = GenomeSet::new(hand_genomes);
    let copied = GenomeSet::<Spaceship>::from_json(&set.to_json()).unwrap();
    let (mut out_a, mut out_b) = (Vec::new(), Vec::new());
    for (a, b) in copied.genomes.iter().zip(&set.genomes) {
        assert_same_derivation(a, b, &mut out_a, &mut out_b, "copied set");
        let back = Genome::<hand::Spaceship>::from_json(&a.to_json()).unwrap();
        assert!(back == *b);
    }
}
