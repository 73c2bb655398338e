//! The genetic operators on hand-built genomes: exact results, the probabilities they
//! choose with, limits, and determinism.

mod support {
    pub mod city_expanded;
    pub mod known;
    pub mod spaceship_expanded;
}

use rand::{Rng, RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use shapegen_runtime::Grammar;
use shapegen_runtime::genome::{Genome, GenomeError, Limits};
use shapegen_runtime::ops::Operators;
use support::city_expanded::{self as city, City};
use support::known::*;
use support::spaceship_expanded::{Body, Spaceship, Start};

fn new_ops<G: Grammar>(min_len: u32, max_len: u32, max_depth: u32) -> Operators<G> {
    Operators::new(Limits::new(min_len, max_len, max_depth).unwrap()).unwrap()
}

fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// The (parent position, link) the gene at `pos` hangs from.
fn hang<G: Grammar>(g: &Genome<G>, pos: u32) -> (u32, u32) {
    let parent = g.gene(pos).parent().unwrap();
    let pnode = g.node(g.gene(parent));
    let link = (0..pnode.links)
        .find(|&l| g.gene(parent).link(l) == Some(pos))
        .unwrap();
    (parent, link)
}

/// Pearson's chi-square statistic of `observed` counts against `expected` probabilities.
fn chi_square(observed: &[u64], expected: &[f64]) -> f64 {
    let n: u64 = observed.iter().sum();
    observed
        .iter()
        .zip(expected)
        .map(|(&o, &p)| {
            let e = p * n as f64;
            (o as f64 - e).powi(2) / e
        })
        .sum()
}

/// Chi-square critical values at p = 0.001 for 1..=6 degrees of freedom.
const CHI2_999: [f64; 6] = [10.83, 13.82, 16.27, 18.47, 20.52, 22.46];

fn assert_fits(observed: &[u64], expected: &[f64]) {
    let x2 = chi_square(observed, expected);
    let dof = observed.len() - 1;
    assert!(
        x2 < CHI2_999[dof - 1],
        "chi-square {x2:.2} with {dof} dof: observed {observed:?}, expected {expected:?}"
    );
}

// --- grow -------------------------------------------------------------------------------

#[test]
fn grow_appends_one_child_at_an_open_link() {
    let mut ops = new_ops::<Spaceship>(1, 100, 20);
    let mut r = rng(1);
    let mut g = Genome::<Spaceship>::with_root(Start {}).unwrap();
    assert!(ops.grow(&mut g, &mut r));
    // Start's only link is `body`: the Body lands at word 3.
    assert_eq!(&g.words()[..8], &[0, 0, 3, 1, (-3i32) as u32, 0, 0, 0]);
    assert_eq!(g.len(), 2);
    g.validate().unwrap();
    let before = g.clone();
    assert!(ops.grow(&mut g, &mut r));
    // Appended after the old words, with one link of its parent patched.
    let old = before.words().len();
    let diffs = (0..old)
        .filter(|&i| g.words()[i] != before.words()[i])
        .count();
    assert_eq!(diffs, 1);
    assert_eq!(g.len(), 3);
    assert_eq!(g.gene(11).parent(), Some(3));
    g.validate().unwrap();
}

#[test]
fn grow_stops_at_max_len_and_when_nothing_can_grow() {
    let mut r = rng(2);
    let mut g = ship();
    assert!(!new_ops::<Spaceship>(1, 7, 20).grow(&mut g, &mut r));
    assert_eq!(g, ship());
    let mut axiom = Genome::<Spaceship>::axiom(&mut r);
    assert!(!new_ops::<Spaceship>(1, 7, 1).grow(&mut axiom, &mut r));
    assert_eq!(axiom.len(), 1);
    // A full city three deep: every lot holds a building, and buildings may not grow.
    let mut c = Genome::<City>::with_root(city::Start {}).unwrap();
    for i in 0..100 {
        let lot = c.attach_at(0, "lots", i, city::Lot {}).unwrap();
        c.attach(lot, "building", building(3.0)).unwrap();
    }
    let mut ops3 = new_ops::<City>(1, 1000, 3);
    assert!(!ops3.grow(&mut c, &mut r));
    assert_eq!(c.len(), 201);
    assert!(new_ops::<City>(1, 1000, 4).grow(&mut c, &mut r));
}

#[test]
fn grow_respects_max_depth() {
    // ship() is 5 deep; at max depth 4 only the genes at depth 2 and 3 may grow:
    // Body @3 (top) and Body @11 (next, wing). Wing @19 and Top @33 lie at depth 3 but
    // their only links are taken.
    let mut ops = new_ops::<Spaceship>(1, 100, 4);
    let mut r = rng(3);
    let base = ship();
    let mut g = base.clone();
    let mut seen = std::collections::BTreeSet::new();
    for _ in 0..300 {
        g.clone_from(&base);
        assert!(ops.grow(&mut g, &mut r));
        let new = base.words().len() as u32;
        seen.insert(hang(&g, new));
    }
    assert_eq!(
        seen.into_iter().collect::<Vec<_>>(),
        vec![(3, 2), (11, 0), (11, 1)]
    );
}

#[test]
fn grow_frequencies_follow_the_probabilities() {
    // Open links of ship(): Body @3 top (1/3), Body @11 next and wing (1/3 each),
    // WingNext @26 next (0.9), TopNext @39 next (1.0).
    let cats = [(3, 2), (11, 0), (11, 1), (26, 0), (39, 0)];
    let weights = [1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0, 0.9, 1.0];
    let total: f64 = weights.iter().sum();
    let expected: Vec<f64> = weights.iter().map(|w| w / total).collect();
    let mut ops = new_ops::<Spaceship>(1, 100, 20);
    let mut r = rng(4);
    let base = ship();
    let mut g = base.clone();
    let mut counts = [0u64; 5];
    for _ in 0..40_000 {
        g.clone_from(&base);
        assert!(ops.grow(&mut g, &mut r));
        let at = hang(&g, base.words().len() as u32);
        counts[cats.iter().position(|&c| c == at).unwrap()] += 1;
    }
    assert_fits(&counts, &expected);
}

// --- cut --------------------------------------------------------------------------------

#[test]
fn cut_at_removes_exactly_the_subtree() {
    let mut ops = new_ops::<Spaceship>(1, 100, 20);
    // The wing subtree (Wing @19, WingNext @26): Top and TopNext move down 14 words.
    let mut g = ship();
    assert_eq!(ops.cut_at(&mut g, 19), Ok(2));
    let mut expected = Genome::<Spaceship>::with_root(Start {}).unwrap();
    let body = expected.attach(0, "body", BODY_A).unwrap();
    let next = expected.attach(body, "next", BODY_B).unwrap();
    let top = expected.attach(next, "top", TOP_A).unwrap();
    expected.attach(top, "next", TOP_NEXT_A).unwrap();
    assert_eq!(g, expected);
    assert_eq!(g.words().len(), 31);
    assert_eq!(&g.words()[3..8], &[1, (-3i32) as u32, 8, 0, 0]); // wing link cleared
    assert_eq!(&g.words()[11..16], &[1, (-8i32) as u32, 0, 0, 8]); // top moved to 19
    assert_eq!(&g.words()[19..22], &[2, (-8i32) as u32, 6]);
    assert_eq!(&g.words()[25..28], &[3, (-6i32) as u32, 0]);
    g.validate().unwrap();

    // The next body's subtree (Body @11, Top @33, TopNext @39), interleaved with the wing.
    let mut g = ship();
    assert_eq!(ops.cut_at(&mut g, 11), Ok(3));
    let mut expected = Genome::<Spaceship>::with_root(Start {}).unwrap();
    let body = expected.attach(0, "body", BODY_A).unwrap();
    let wing = expected.attach(body, "wing", WING_A).unwrap();
    expected.attach(wing, "next", WING_NEXT_A).unwrap();
    assert_eq!(g, expected);

    // A roof and its spire in the city.
    let mut ops = new_ops::<City>(1, 300, 20);
    let mut t = town();
    assert_eq!(ops.cut_at(&mut t, 116), Ok(2));
    let mut expected = Genome::<City>::with_root(city::Start {}).unwrap();
    let lot = expected.attach_at(0, "lots", 3, city::Lot {}).unwrap();
    expected.attach(lot, "building", building(4.0)).unwrap();
    let lot = expected.attach_at(0, "lots", 10, city::Lot {}).unwrap();
    expected.attach(lot, "building", building(7.0)).unwrap();
    assert_eq!(t, expected);
    assert_eq!(t.words()[2 + 10], 116);
}

#[test]
fn cut_at_refuses_the_root_non_genes_and_going_below_min_len() {
    let mut ops = new_ops::<Spaceship>(5, 100, 20);
    let mut g = ship();
    assert_eq!(ops.cut_at(&mut g, 0), Err(GenomeError::IsRoot));
    assert!(matches!(
        ops.cut_at(&mut g, 12),
        Err(GenomeError::NotAGene { pos: 12, .. })
    ));
    assert_eq!(
        ops.cut_at(&mut g, 11),
        Err(GenomeError::TooShort { len: 4, min_len: 5 })
    );
    assert_eq!(g, ship());
}

#[test]
fn cut_never_cuts_probability_one_links_and_keeps_min_len() {
    let mut r = rng(5);
    let mut ops1 = new_ops::<Spaceship>(1, 100, 20);
    let mut g = Genome::<Spaceship>::with_root(Start {}).unwrap();
    g.attach(0, "body", BODY_A).unwrap();
    assert!(!ops1.cut(&mut g, &mut r)); // Start -> body has p = 1
    assert_eq!(g.len(), 2);

    // min_len 5: cutting the next body (3 genes) would leave 4, so only the wing or the
    // top subtree (2 genes each) may go, with equal weights 2/3.
    let mut ops5 = new_ops::<Spaceship>(5, 100, 20);
    let (mut no_wing, mut no_top) = (ship(), ship());
    ops1.cut_at(&mut no_wing, 19).unwrap();
    ops1.cut_at(&mut no_top, 33).unwrap();
    let mut counts = [0u64; 2];
    let base = ship();
    for _ in 0..4000 {
        g.clone_from(&base);
        assert!(ops5.cut(&mut g, &mut r));
        if g == no_wing {
            counts[0] += 1;
        } else {
            assert_eq!(g, no_top);
            counts[1] += 1;
        }
        assert!(!ops5.cut(&mut g, &mut r), "at min_len nothing is cuttable");
    }
    assert_fits(&counts, &[0.5, 0.5]);

    // min_len 6: every cuttable subtree of ship() has 2 or 3 genes.
    let mut ops6 = new_ops::<Spaceship>(6, 100, 20);
    let mut g = ship();
    for _ in 0..50 {
        assert!(!ops6.cut(&mut g, &mut r));
    }
    assert_eq!(g, ship());
}

#[test]
fn cut_frequencies_follow_the_probabilities() {
    // town(): lots[3] (cut weight 0.67, 4 genes), roof (0.5, 2 genes), spire (0.6),
    // lots[10] (0.67, 2 genes); the Lot -> Building links have p = 1.
    let base = town();
    let mut helper = new_ops::<City>(1, 300, 20);
    let outcomes: Vec<Genome<City>> = [102, 116, 120, 124]
        .iter()
        .map(|&pos| {
            let mut g = base.clone();
            helper.cut_at(&mut g, pos).unwrap();
            g
        })
        .collect();
    let weights = [0.67, 0.5, 0.6, 0.67];
    let mut r = rng(6);
    for (min_len, allowed) in [
        (1, [true, true, true, true]),
        (5, [false, true, true, true]),
    ] {
        let mut ops = new_ops::<City>(min_len, 300, 20);
        let mut counts = [0u64; 4];
        let mut g = base.clone();
        for _ in 0..30_000 {
            g.clone_from(&base);
            assert!(ops.cut(&mut g, &mut r));
            counts[outcomes.iter().position(|o| *o == g).unwrap()] += 1;
        }
        let total: f64 = (0..4).filter(|&i| allowed[i]).map(|i| weights[i]).sum();
        let (obs, exp): (Vec<u64>, Vec<f64>) = (0..4)
            .filter(|&i| allowed[i])
            .map(|i| (counts[i], weights[i] / total))
            .unzip();
        if !allowed[0] {
            assert_eq!(counts[0], 0);
        }
        assert_fits(&obs, &exp);
    }
}

// --- alter ------------------------------------------------------------------------------

#[test]
fn alter_redraws_the_parameters_of_one_gene() {
    let mut ops = new_ops::<Spaceship>(1, 100, 20);
    let mut r = rng(7);
    let mut g = Genome::<Spaceship>::with_root(Start {}).unwrap();
    g.attach(0, "body", BODY_A).unwrap();
    let before = g.clone();
    assert!(ops.alter(&mut g, &mut r));
    assert_eq!(&g.words()[..8], &before.words()[..8]);
    assert_ne!(&g.words()[8..], &before.words()[8..]);
    g.validate().unwrap();

    // Uniform over the six genes with parameters; the structure never changes.
    let base = ship();
    let param_genes: Vec<u32> = base.genes().map(|v| v.pos()).filter(|&p| p != 0).collect();
    let mut counts = vec![0u64; param_genes.len()];
    for _ in 0..12_000 {
        g.clone_from(&base);
        assert!(ops.alter(&mut g, &mut r));
        let changed: Vec<usize> = param_genes
            .iter()
            .enumerate()
            .filter(|&(_, &p)| gene_words(&g, p) != gene_words(&base, p))
            .map(|(i, _)| i)
            .collect();
        assert_eq!(changed.len(), 1);
        counts[changed[0]] += 1;
        assert_eq!(g.len(), base.len());
        g.validate().unwrap();
    }
    assert_fits(&counts, &[1.0 / 6.0; 6]);
}

fn gene_words<G: Grammar>(g: &Genome<G>, pos: u32) -> &[u32] {
    let size = g.node(g.gene(pos)).gene_words() as usize;
    &g.words()[pos as usize..][..size]
}

// --- crossover --------------------------------------------------------------------------

#[test]
fn crossover_at_swaps_exact_subtrees() {
    let mut ops = new_ops::<Spaceship>(1, 100, 20);
    // ship()'s wing (Wing @19 with WingNext @26) for small()'s wing (Wing @11, alone).
    let (c, d) = ops.crossover_at(&ship(), 19, &small(), 11).unwrap();
    let mut expected_c = Genome::<Spaceship>::with_root(Start {}).unwrap();
    let body = expected_c.attach(0, "body", BODY_A).unwrap();
    let next = expected_c.attach(body, "next", BODY_B).unwrap();
    let top = expected_c.attach(next, "top", TOP_A).unwrap();
    expected_c.attach(top, "next", TOP_NEXT_A).unwrap();
    expected_c.attach(body, "wing", WING_A).unwrap();
    assert_eq!(c, expected_c);
    let mut expected_d = Genome::<Spaceship>::with_root(Start {}).unwrap();
    let body = expected_d.attach(0, "body", BODY_A).unwrap();
    let wing = expected_d.attach(body, "wing", WING_A).unwrap();
    expected_d.attach(wing, "next", WING_NEXT_A).unwrap();
    assert_eq!(d, expected_d);

    // The next body of ship() (Body @11 with Top @33 and TopNext @39, interleaved with the
    // wing) for the next body of `donor` (Body @11 with Wing @19).
    let mut donor = Genome::<Spaceship>::with_root(Start {}).unwrap();
    let body = donor.attach(0, "body", BODY_B).unwrap();
    let next = donor.attach(body, "next", BODY_A).unwrap();
    donor.attach(next, "wing", WING_A).unwrap();
    let (c, d) = ops.crossover_at(&ship(), 11, &donor, 11).unwrap();
    c.validate().unwrap();
    d.validate().unwrap();
    let mut expected_c = Genome::<Spaceship>::with_root(Start {}).unwrap();
    let body = expected_c.attach(0, "body", BODY_A).unwrap();
    let wing = expected_c.attach(body, "wing", WING_A).unwrap();
    expected_c.attach(wing, "next", WING_NEXT_A).unwrap();
    let next = expected_c.attach(body, "next", BODY_A).unwrap();
    expected_c.attach(next, "wing", WING_A).unwrap();
    assert_eq!(c, expected_c);
    let mut expected_d = Genome::<Spaceship>::with_root(Start {}).unwrap();
    let body = expected_d.attach(0, "body", BODY_B).unwrap();
    let next = expected_d.attach(body, "next", BODY_B).unwrap();
    let top = expected_d.attach(next, "top", TOP_A).unwrap();
    expected_d.attach(top, "next", TOP_NEXT_A).unwrap();
    assert_eq!(d, expected_d);
}

#[test]
fn crossover_at_checks_edges_and_limits() {
    let mut ops = new_ops::<Spaceship>(1, 100, 20);
    let err = ops.crossover_at(&ship(), 33, &small(), 11).unwrap_err();
    assert_eq!(
        err.to_string(),
        "gene 5 (`Top` @33) hangs from slot `top` of `Body` but gene 2 (`Wing` @11) from slot \
         `wing` of `Body`; only subtrees on the same edge of the generator graph can be swapped"
    );
    assert_eq!(
        ops.crossover_at(&ship(), 0, &small(), 3).unwrap_err(),
        GenomeError::IsRoot
    );
    // Swapping the Start's bodies: ship() gets small()'s 2-gene body.
    let mut ops = new_ops::<Spaceship>(4, 100, 20);
    assert_eq!(
        ops.crossover_at(&ship(), 3, &small(), 3).unwrap_err(),
        GenomeError::TooShort { len: 3, min_len: 4 }
    );
    let mut ops = new_ops::<Spaceship>(1, 100, 4);
    let err = ops.crossover_at(&small(), 3, &ship(), 3).unwrap_err();
    assert!(
        matches!(err, GenomeError::DeeperThanLimit { depth: 5, .. }),
        "{err}"
    );
}

#[test]
fn crossover_matches_array_slots_across_indices() {
    let mut other = Genome::<City>::with_root(city::Start {}).unwrap();
    let lot = other.attach_at(0, "lots", 50, city::Lot {}).unwrap();
    other.attach(lot, "building", building(9.0)).unwrap();
    let mut ops = new_ops::<City>(1, 300, 20);
    // town()'s lots[3] subtree (4 genes) for other's lots[50] subtree (2 genes).
    let (c, d) = ops.crossover_at(&town(), 102, &other, 102).unwrap();
    let mut expected_c = Genome::<City>::with_root(city::Start {}).unwrap();
    let lot = expected_c.attach_at(0, "lots", 10, city::Lot {}).unwrap();
    expected_c.attach(lot, "building", building(7.0)).unwrap();
    let lot = expected_c.attach_at(0, "lots", 3, city::Lot {}).unwrap();
    expected_c.attach(lot, "building", building(9.0)).unwrap();
    assert_eq!(c, expected_c);
    let mut expected_d = Genome::<City>::with_root(city::Start {}).unwrap();
    let lot = expected_d.attach_at(0, "lots", 50, city::Lot {}).unwrap();
    let b = expected_d.attach(lot, "building", building(4.0)).unwrap();
    let roof = expected_d
        .attach(b, "roof", city::Roof { pitch: 0.3 })
        .unwrap();
    expected_d
        .attach(roof, "spire", city::Roof { pitch: 0.9 })
        .unwrap();
    assert_eq!(d, expected_d);

    // Random crossovers between the two only ever pair lots with lots, buildings with
    // buildings and roofs with roofs; all children are valid.
    let mut r = rng(9);
    let mut hits = 0;
    for _ in 0..500 {
        if let Some((c, d)) = ops.crossover(&town(), &other, &mut r) {
            hits += 1;
            c.validate().unwrap();
            d.validate().unwrap();
            assert_eq!(c.len() + d.len(), town().len() + other.len());
        }
    }
    assert!(hits > 400, "{hits}");
}

#[test]
fn crossover_gives_up_when_no_swap_fits() {
    let mut a = Genome::<City>::with_root(city::Start {}).unwrap();
    a.attach_at(0, "lots", 0, city::Lot {}).unwrap();
    let mut b = a.clone();
    b.attach(102, "building", building(2.0)).unwrap();
    let mut r = rng(10);
    // The only common edge is Start -> lots; swapping gives a 3-gene child.
    assert!(
        new_ops::<City>(1, 2, 10)
            .crossover(&a, &b, &mut r)
            .is_none()
    );
    assert!(
        new_ops::<City>(1, 3, 10)
            .crossover(&a, &b, &mut r)
            .is_some()
    );
    // Nothing to pick in a genome that is only its root.
    let root = Genome::<City>::with_root(city::Start {}).unwrap();
    assert!(
        new_ops::<City>(1, 3, 10)
            .crossover(&root, &b, &mut r)
            .is_none()
    );
    // No link of b on the edges a offers (Building -> roof): every retry fails.
    let mut c = b.clone();
    c.attach(105, "roof", city::Roof { pitch: 0.5 }).unwrap();
    let mut ops = new_ops::<City>(1, 4, 10);
    let mut found = 0;
    for _ in 0..200 {
        if let Some((x, y)) = ops.crossover(&c, &b, &mut r) {
            found += 1;
            x.validate_limits(ops.limits()).unwrap();
            y.validate_limits(ops.limits()).unwrap();
        }
    }
    // Picks of the roof link always fail (b has no roof); the lot and building links of
    // c swap into children of 4 and 3 genes, within the limits.
    assert!(found > 0 && found < 200, "{found}");
}

// --- random and sample -------------------------------------------------------------------

#[test]
fn random_equals_repeated_grow() {
    fn check<G: Grammar>(limits: Limits, initial: u32, seeds: std::ops::Range<u64>) {
        let mut ops = Operators::<G>::new(limits).unwrap();
        for seed in seeds {
            let (mut r1, mut r2) = (rng(seed), rng(seed));
            let fast = ops.random(initial, &mut r1);
            let target = ops.random_len(initial, &mut r2);
            let mut slow = Genome::<G>::axiom(&mut r2);
            while slow.len() < target as usize && ops.grow(&mut slow, &mut r2) {}
            assert_eq!(fast, slow, "seed {seed}");
            assert_eq!(r1.next_u64(), r2.next_u64(), "the same draws were made");
            fast.validate().unwrap();
            fast.validate_limits(ops.limits()).unwrap();
        }
    }
    check::<Spaceship>(Limits::new(1, 400, 1024).unwrap(), 100, 0..20);
    check::<Spaceship>(Limits::new(4, 60, 5).unwrap(), 50, 20..40);
    check::<City>(Limits::new(4, 300, 8).unwrap(), 50, 40..60);
    check::<City>(Limits::new(1, 150, 3).unwrap(), 200, 60..70);
}

#[test]
fn grow_to_continues_an_existing_genome_like_grow() {
    let mut ops = new_ops::<Spaceship>(1, 200, 9);
    for seed in 0..10 {
        let (mut r1, mut r2) = (rng(seed), rng(seed));
        let (mut a, mut b) = (ship(), ship());
        assert_eq!(ops.grow_to(&mut a, 60, &mut r1), 53);
        for _ in 0..53 {
            assert!(ops.grow(&mut b, &mut r2));
        }
        assert_eq!(a, b);
    }
}

#[test]
fn random_lengths_spread_around_the_initial_length() {
    let mut ops = new_ops::<Spaceship>(1, 1000, 1024);
    let mut r = rng(11);
    let mut counts = [0u64; 3];
    for _ in 0..3000 {
        let g = ops.random(20, &mut r);
        let len = g.len();
        assert!((10..=30).contains(&len), "{len}");
        counts[(len - 10) * 3 / 21] += 1;
    }
    assert_fits(&counts, &[7.0 / 21.0; 3]);
    // Clamped into the limits.
    let mut ops = new_ops::<Spaceship>(25, 28, 1024);
    for _ in 0..100 {
        assert!((25..=28).contains(&ops.random(20, &mut r).len()));
    }
}

#[test]
fn sample_follows_the_generator_within_limits() {
    let mut ops = new_ops::<Spaceship>(1, 40, 6);
    let mut r = rng(12);
    let (mut with_next, mut with_wing, mut n) = (0u64, 0u64, 0u64);
    for _ in 0..6000 {
        let g = ops.sample(&mut r);
        g.validate().unwrap();
        assert!(g.len() <= 40 && g.depth() <= 6);
        // Start -> body has p = 1.
        let body = g.root().link(0).expect("p = 1");
        n += 1;
        with_next += u64::from(g.gene(body).link(0).is_some());
        with_wing += u64::from(g.gene(body).link(1).is_some());
        // Wing -> next has p = 1 and the depth allows it.
        if let Some(wing) = g.gene(body).link(1) {
            assert!(g.gene(wing).link(0).is_some());
        }
    }
    assert_fits(&[with_next, n - with_next], &[1.0 / 3.0, 2.0 / 3.0]);
    assert_fits(&[with_wing, n - with_wing], &[1.0 / 3.0, 2.0 / 3.0]);

    // TopNext -> next has p = 1: samples run to the depth or length limit.
    let mut ops = new_ops::<Spaceship>(10, 12, 1024);
    for _ in 0..200 {
        assert!(ops.sample(&mut r).len() <= 12);
        let g = ops.sample_at_least(1000, &mut r).unwrap();
        assert!((10..=12).contains(&g.len()));
    }
    // A city sample: about a third of the lots.
    let mut ops = new_ops::<City>(1, 1000, 10);
    let lots: usize = (0..200)
        .map(|_| {
            let g = ops.sample(&mut r);
            (0..100).filter(|&l| g.root().link(l).is_some()).count()
        })
        .sum();
    assert!((6300..6900).contains(&lots), "{lots}");
}

// --- determinism ------------------------------------------------------------------------

#[test]
fn the_same_seed_gives_the_same_genomes() {
    fn run(seed: u64) -> Vec<Genome<Spaceship>> {
        let mut ops = new_ops::<Spaceship>(4, 80, 10);
        let mut r = rng(seed);
        let mut pop: Vec<_> = (0..8).map(|_| ops.random(30, &mut r)).collect();
        for step in 0..400 {
            let i = r.random_range(0..pop.len());
            match step % 4 {
                0 => {
                    ops.grow(&mut pop[i], &mut r);
                }
                1 => {
                    ops.cut(&mut pop[i], &mut r);
                }
                2 => {
                    ops.alter(&mut pop[i], &mut r);
                }
                _ => {
                    let j = r.random_range(0..pop.len());
                    if let Some((a, b)) = ops.crossover(&pop[i], &pop[j], &mut r) {
                        pop[i] = a;
                        pop[j] = b;
                    }
                }
            }
        }
        pop.push(ops.sample(&mut r));
        pop
    }
    assert_eq!(run(13), run(13));
    assert_ne!(run(13), run(14));
}

#[test]
fn operators_refuse_impossible_limits() {
    let err = Operators::<Spaceship>::new(Limits {
        min_len: 9,
        max_len: 3,
        max_depth: 4,
    })
    .unwrap_err();
    assert_eq!(
        err.to_string(),
        "min_len 9 is larger than max_len 3; min_len must be at most max_len"
    );
    let mut ops = new_ops::<Spaceship>(1, 10, 4);
    assert!(
        ops.set_limits(Limits {
            min_len: 1,
            max_len: 10,
            max_depth: 0
        })
        .is_err()
    );
    assert_eq!(ops.limits().max_depth, 4);
    let _ = Body {
        size: v3(1.0, 1.0, 1.0),
    };
}
