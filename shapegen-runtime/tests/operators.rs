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
use shapegen_runtime::ops::{OperatorVariant, Operators};
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
fn crossover_matches_array_slots_on_their_own_index_unless_told() {
    let mut other = Genome::<City>::with_root(city::Start {}).unwrap();
    let lot = other.attach_at(0, "lots", 50, city::Lot {}).unwrap();
    other.attach(lot, "building", building(9.0)).unwrap();
    // By default lots[3] and lots[50] are different edges.
    let mut ops = new_ops::<City>(1, 300, 20);
    assert!(!ops.cross_array_index());
    let err = ops.crossover_at(&town(), 102, &other, 102).unwrap_err();
    assert_eq!(
        err.to_string(),
        "gene 1 (`Lot` @102) hangs from slot `lots[3]` of `Start` but gene 1 (`Lot` @102) \
         from slot `lots[50]` of `Start`; only subtrees on the same edge of the generator \
         graph can be swapped"
    );
    // Across indices when told: town()'s lots[3] subtree (4 genes) for other's lots[50]
    // subtree (2 genes).
    let mut ops = new_ops::<City>(1, 300, 20).with_cross_array_index(true);
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

/// Start -> lots[`index`]: Lot, holding a Building of `height` if given.
fn one_lot(index: u32, height: Option<f32>) -> Genome<City> {
    let mut g = Genome::<City>::with_root(city::Start {}).unwrap();
    let lot = g.attach_at(0, "lots", index, city::Lot {}).unwrap();
    if let Some(h) = height {
        g.attach(lot, "building", building(h)).unwrap();
    }
    g
}

/// The children of one crossover, `None` when it found none.
type Children<G> = Option<(Genome<G>, Genome<G>)>;

/// Counts the distinct outcomes of `draws` crossovers of `a` and `b`, checking every
/// child.
fn crossover_outcomes<G: Grammar>(
    ops: &mut Operators<G>,
    a: &Genome<G>,
    b: &Genome<G>,
    draws: u32,
    seed: u64,
) -> Vec<(Children<G>, u64)> {
    let mut r = rng(seed);
    let mut seen: Vec<(Children<G>, u64)> = Vec::new();
    for _ in 0..draws {
        let out = ops.crossover(a, b, &mut r);
        if let Some((c, d)) = &out {
            c.validate().unwrap();
            d.validate().unwrap();
            assert_eq!(c.len() + d.len(), a.len() + b.len());
        }
        match seen.iter_mut().find(|(o, _)| *o == out) {
            Some((_, n)) => *n += 1,
            None => seen.push((out, 1)),
        }
    }
    seen
}

#[test]
fn a_lot_subtree_meets_only_its_own_index_in_both_variants() {
    // a: lots[3] alone; b: lots[50] with a building. a's only non-root gene is its Lot.
    let a = one_lot(3, None);
    let b = one_lot(50, Some(9.0));
    let moved = || (one_lot(3, Some(9.0)), one_lot(50, None));
    let original = || new_ops::<City>(1, 300, 20).with_variant(OperatorVariant::Original);

    // Weighted: no lots[3] in b, so every attempt fails.
    let out = crossover_outcomes(&mut new_ops::<City>(1, 300, 20), &a, &b, 200, 20);
    assert_eq!(out, vec![(None, 200)]);
    // Original: `Lot_3` is only taken by b's Start, which has no such child: a's lot is
    // grafted onto b's lots[3].
    let mut grafted = b.clone();
    grafted.attach_at(0, "lots", 3, city::Lot {}).unwrap();
    let root = Genome::<City>::with_root(city::Start {}).unwrap();
    let out = crossover_outcomes(&mut original(), &a, &b, 200, 21);
    assert_eq!(out, vec![(Some((root, grafted)), 200)]);
    // Across indices, both variants exchange the lots, moving the building to lots[3].
    for mut ops in [
        new_ops::<City>(1, 300, 20).with_cross_array_index(true),
        original().with_cross_array_index(true),
    ] {
        let out = crossover_outcomes(&mut ops, &a, &b, 200, 22);
        assert_eq!(out, vec![(Some(moved()), 200)], "{:?}", ops.variant());
    }
}

#[test]
fn buildings_move_between_lots_through_their_own_edge() {
    // A Building hangs from `Lot.building` whatever the lot's index: in the original all
    // lots take the one symbol `Builing`, and the weighted rules see one edge.
    let a = one_lot(3, Some(4.0));
    let b = one_lot(10, Some(7.0));
    let swapped = (one_lot(3, Some(7.0)), one_lot(10, Some(4.0)));
    let out = crossover_outcomes(&mut new_ops::<City>(1, 300, 20), &a, &b, 400, 23);
    // Lots never meet (3 against 10): only the buildings swap, unless all 4 attempts
    // draw the lot (1/16).
    assert_eq!(out.len(), 2, "{out:?}");
    for (o, _) in &out {
        assert!(o.is_none() || *o == Some(swapped.clone()), "{o:?}");
    }
    // Original: the building swaps (its symbol meets b's lot), or the lot, whose symbol
    // `Lot_3` only b's Start takes, is grafted there.
    let mut ops = new_ops::<City>(1, 300, 20).with_variant(OperatorVariant::Original);
    let mut grafted = b.clone();
    let lot = grafted.attach_at(0, "lots", 3, city::Lot {}).unwrap();
    grafted.attach(lot, "building", building(4.0)).unwrap();
    let root = Genome::<City>::with_root(city::Start {}).unwrap();
    let out = crossover_outcomes(&mut ops, &a, &b, 4000, 24);
    assert_eq!(out.len(), 2, "{out:?}");
    let count = |o: &Children<City>| out.iter().find(|(x, _)| x == o).map_or(0, |(_, n)| *n);
    assert_fits(
        &[count(&Some(swapped)), count(&Some((root, grafted)))],
        &[0.5, 0.5],
    );
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

// --- the original's rules ----------------------------------------------------------------

fn original_ops<G: Grammar>() -> Operators<G> {
    // Limits the original's operators ignore: any genome here breaks them.
    new_ops::<G>(6, 6, 2).with_variant(OperatorVariant::Original)
}

/// Counts how often each (parent, link) gets the gene `grow` appends to `base`.
fn grow_counts<G: Grammar>(
    ops: &mut Operators<G>,
    base: &Genome<G>,
    cats: &[(u32, u32)],
    draws: u32,
    seed: u64,
) -> Vec<u64> {
    let mut r = rng(seed);
    let mut g = base.clone();
    let mut counts = vec![0u64; cats.len()];
    for _ in 0..draws {
        g.clone_from(base);
        assert!(ops.grow(&mut g, &mut r));
        g.validate().unwrap();
        let at = hang(&g, base.words().len() as u32);
        let i = cats.iter().position(|&c| c == at);
        counts[i.unwrap_or_else(|| panic!("grew at {at:?}"))] += 1;
    }
    counts
}

#[test]
fn original_grow_ignores_probabilities_and_never_draws_the_last_candidate() {
    let mut ops = original_ops::<Spaceship>();
    // ship()'s genes with an empty link, in gene order: Body @3 (top), Body @11 (next,
    // wing), WingNext @26 (next, p = 0.9), TopNext @39 (next, p = 1). The original draws
    // uniformly among all but the last gene, then among all but the last empty link:
    // Body @11 always grows `next`, never `wing`; TopNext @39 never grows.
    let cats = [(3, 2), (11, 0), (26, 0), (11, 1), (39, 0)];
    let counts = grow_counts(&mut ops, &ship(), &cats, 30_000, 40);
    assert_eq!(&counts[3..], &[0, 0], "{counts:?}");
    assert_fits(&counts[..3], &[1.0 / 3.0; 3]);

    // A body with all three links empty, the only gene that can grow: `next` or `wing`,
    // equally; the top only once the other two are taken.
    let mut g = Genome::<Spaceship>::with_root(Start {}).unwrap();
    g.attach(0, "body", BODY_A).unwrap();
    let counts = grow_counts(&mut ops, &g, &[(3, 0), (3, 1), (3, 2)], 20_000, 41);
    assert_eq!(counts[2], 0, "{counts:?}");
    assert_fits(&counts[..2], &[0.5, 0.5]);
    // With its next body @11 and wing @19 in place, Body @3 may grow its top: the genes
    // that can grow are Body @3 (top), Body @11 (next, wing, top) and Wing @19 (next).
    let mut full = g.clone();
    full.attach(3, "next", BODY_B).unwrap();
    full.attach(3, "wing", WING_A).unwrap();
    let cats = [(3, 2), (11, 0), (11, 1), (19, 0), (11, 2)];
    let counts = grow_counts(&mut ops, &full, &cats, 20_000, 42);
    assert_eq!(&counts[3..], &[0, 0], "{counts:?}");
    assert_fits(&counts[..3], &[0.5, 0.25, 0.25]);

    // Beyond the limits (max_len 6, max_depth 2) and up to nothing left to grow.
    let mut g = ship();
    let mut r = rng(43);
    for _ in 0..50 {
        assert!(ops.grow(&mut g, &mut r));
    }
    assert_eq!(g.len(), 57);
    g.validate().unwrap();
    let mut c = Genome::<City>::with_root(city::Start {}).unwrap();
    for i in 0..100 {
        let lot = c.attach_at(0, "lots", i, city::Lot {}).unwrap();
        let b = c.attach(lot, "building", building(3.0)).unwrap();
        let roof = c.attach(b, "roof", city::Roof { pitch: 0.3 }).unwrap();
        c.attach(roof, "spire", city::Roof { pitch: 0.3 }).unwrap();
    }
    let mut ops = original_ops::<City>();
    assert!(ops.grow(&mut c, &mut r), "the last spire can still grow");
}

#[test]
fn original_cut_draws_any_non_root_gene_and_regrows_a_bare_root() {
    // ship()'s six non-root genes, each with probability 1/6: Body @3 and TopNext @39
    // hang from links of probability 1, which the weighted cut never takes.
    let mut helper = new_ops::<Spaceship>(1, 100, 20);
    let outcomes: Vec<Genome<Spaceship>> = [11, 19, 26, 33, 39]
        .iter()
        .map(|&pos| {
            let mut g = ship();
            helper.cut_at(&mut g, pos).unwrap();
            g
        })
        .collect();
    let mut ops = original_ops::<Spaceship>();
    let mut r = rng(44);
    let mut counts = [0u64; 6];
    let mut g = ship();
    for _ in 0..24_000 {
        g.clone_from(&ship());
        assert!(ops.cut(&mut g, &mut r));
        g.validate().unwrap();
        match outcomes.iter().position(|o| *o == g) {
            Some(i) => counts[i + 1] += 1,
            None => {
                // Cutting Body @3 leaves the root alone, which grows once more: a new body.
                assert_eq!(g.len(), 2, "{g:?}");
                assert_ne!(g, small());
                assert!(g.root().link(0).is_some());
                counts[0] += 1;
            }
        }
    }
    assert_fits(&counts, &[1.0 / 6.0; 6]);
    // min_len does not hold it back, and the root alone cannot be cut.
    let mut g = ship();
    while g.len() > 2 {
        assert!(ops.cut(&mut g, &mut r));
    }
    let mut root = Genome::<Spaceship>::with_root(Start {}).unwrap();
    assert!(!ops.cut(&mut root, &mut r));
    assert_eq!(root.len(), 1);
}

shapegen_runtime::generator! {
    /// An axiom with a parameter, a child without parameters and leaves.
    pub Knob {
        axiom Root;
        node Root {
            params { turn: f32 ~ uniform(0.0, 1.0) }
            children { left: Leaf = 0.2, mid: Bare = 1.0 }
        }
        node Bare { children { leaf: Leaf = 0.5 } }
        node Leaf { params { size: f32 ~ uniform(1.0, 2.0) } }
    }
}

#[test]
fn original_alter_draws_any_non_root_gene_parameters_or_not() {
    // Root (with a parameter) -> left Leaf @?, mid Bare -> leaf Leaf. The original draws
    // among the three non-root genes: a leaf each 1/3, the bare gene (a no-op) 1/3; the
    // root never.
    let mut g = Genome::<Knob>::with_root(Root { turn: 0.5 }).unwrap();
    let left = g.attach(0, "left", Leaf { size: 1.5 }).unwrap();
    let mid = g.attach(0, "mid", Bare {}).unwrap();
    let leaf = g.attach(mid, "leaf", Leaf { size: 1.5 }).unwrap();
    let base = g.clone();
    let mut ops = original_ops::<Knob>();
    let mut r = rng(45);
    let mut counts = [0u64; 3]; // left, leaf, no-op
    for _ in 0..12_000 {
        g.clone_from(&base);
        let changed = ops.alter(&mut g, &mut r);
        assert_eq!(
            gene_words(&g, 0),
            gene_words(&base, 0),
            "the root is never altered"
        );
        assert_eq!(g.len(), base.len());
        let which = [left, leaf].map(|p| gene_words(&g, p) != gene_words(&base, p));
        match which {
            [true, false] => counts[0] += 1,
            [false, true] => counts[1] += 1,
            [false, false] => counts[2] += 1,
            _ => panic!("two genes altered"),
        }
        assert_eq!(changed, counts[2] == 0 || which != [false, false]);
        g.validate().unwrap();
    }
    assert_fits(&counts, &[1.0 / 3.0; 3]);
    // The weighted alter draws among the genes with parameters, the root included.
    let mut weighted = new_ops::<Knob>(1, 10, 10);
    let root_altered = (0..300).any(|_| {
        g.clone_from(&base);
        weighted.alter(&mut g, &mut r);
        gene_words(&g, 0) != gene_words(&base, 0)
    });
    assert!(root_altered);
}

/// Start -> lots[3]: Lot -> Building(4) -> roof: Roof(0.3) -> spire: Roof(0.9) ... with
/// `spires` Roofs in all.
fn roofed(spires: u32) -> Genome<City> {
    let mut g = one_lot(3, Some(4.0));
    let mut at = g.attach(105, "roof", city::Roof { pitch: 0.3 }).unwrap();
    for _ in 1..spires {
        at = g.attach(at, "spire", city::Roof { pitch: 0.9 }).unwrap();
    }
    g
}

#[test]
fn original_crossover_matches_symbols_across_parent_types_and_grafts() {
    // a: lots[3] @102 -> Building(4) @105 -> roof: Roof @116 -> spire: Roof @120.
    // b: lots[3] @102 -> Building(9) @105, lots[5] @116 -> Building(8) @119; no roofs.
    let a = roofed(2);
    let mut b = one_lot(3, Some(9.0));
    let lot5 = b.attach_at(0, "lots", 5, city::Lot {}).unwrap();
    b.attach(lot5, "building", building(8.0)).unwrap();
    // a's Lot (symbol `Lot_3`, only taken by b's Start) exchanges with b's lots[3].
    let lot_c = one_lot(3, Some(9.0));
    let mut lot_d = one_lot(5, Some(8.0));
    let bd = lot_d.attach_at(0, "lots", 3, city::Lot {}).unwrap();
    let bd = lot_d.attach(bd, "building", building(4.0)).unwrap();
    let r1 = lot_d.attach(bd, "roof", city::Roof { pitch: 0.3 }).unwrap();
    lot_d
        .attach(r1, "spire", city::Roof { pitch: 0.9 })
        .unwrap();
    // a's Building: both of b's lots take it, but the original never draws the last
    // candidate: always lots[3]'s building is exchanged.
    let mut bld_d = Genome::<City>::with_root(city::Start {}).unwrap();
    let l3 = bld_d.attach_at(0, "lots", 3, city::Lot {}).unwrap();
    let l5 = bld_d.attach_at(0, "lots", 5, city::Lot {}).unwrap();
    bld_d.attach(l5, "building", building(8.0)).unwrap();
    let bd = bld_d.attach(l3, "building", building(4.0)).unwrap();
    let r1 = bld_d.attach(bd, "roof", city::Roof { pitch: 0.3 }).unwrap();
    bld_d
        .attach(r1, "spire", city::Roof { pitch: 0.9 })
        .unwrap();
    // a Roof, from `Building.roof` or from `Roof.spire` alike: b's Buildings take Roofs;
    // the first has none, so the subtree is grafted onto its roof link and a only loses
    // it.
    let mut helper = new_ops::<City>(1, 300, 20);
    let mut graft = |cut: u32, pitches: &[f32]| {
        let mut c = a.clone();
        helper.cut_at(&mut c, cut).unwrap();
        let mut d = b.clone();
        let mut at = 105;
        for (i, &pitch) in pitches.iter().enumerate() {
            let link = if i == 0 { "roof" } else { "spire" };
            at = d.attach(at, link, city::Roof { pitch }).unwrap();
        }
        (c, d)
    };
    let roof = graft(116, &[0.3, 0.9]);
    let spire = graft(120, &[0.9]);
    assert_eq!((roof.0.len(), roof.1.len()), (3, 7)); // len(a) - 2, len(b) + 2
    assert_eq!((spire.0.len(), spire.1.len()), (4, 6)); // len(a) - 1, len(b) + 1
    let expected = [(lot_c.clone(), lot_d), (lot_c, bld_d), roof, spire];
    let mut ops = original_ops::<City>();
    let out = crossover_outcomes(&mut ops, &a, &b, 8000, 46);
    let counts: Vec<u64> = expected
        .iter()
        .map(|want| {
            out.iter()
                .find(|(o, _)| o.as_ref() == Some(want))
                .map_or(0, |(_, n)| *n)
        })
        .collect();
    assert_eq!(counts.iter().sum::<u64>(), 8000, "{out:?}");
    assert_fits(&counts, &[0.25; 4]);

    // The weighted crossover never moves a spire under a building.
    let mut weighted = new_ops::<City>(1, 300, 20);
    let out = crossover_outcomes(&mut weighted, &a, &b, 500, 47);
    assert!(out.iter().all(|(o, _)| o.as_ref() != Some(&expected[3])));
}

#[test]
fn original_crossover_makes_three_attempts_then_gives_up() {
    // a: a lot, its building and 8 roofs; b: the root alone. Only a's Lot (1 of its 10
    // non-root genes) has a symbol b takes (its Start, on lots[3]): each attempt fails
    // with probability 9/10, all three with 0.729 (four would be 0.656).
    let a = roofed(8);
    let b = Genome::<City>::with_root(city::Start {}).unwrap();
    let mut ops = original_ops::<City>();
    let out = crossover_outcomes(&mut ops, &a, &b, 6000, 48);
    let failed = out.iter().find(|(o, _)| o.is_none()).map_or(0, |(_, n)| *n);
    // The graft: a keeps its root alone, b gets a's whole lot.
    let root = Genome::<City>::with_root(city::Start {}).unwrap();
    assert_eq!(out.len(), 2, "{out:?}");
    assert!(
        out.iter()
            .any(|(o, _)| *o == Some((root.clone(), a.clone())))
    );
    assert_fits(&[failed, 6000 - failed], &[0.729, 0.271]);
    // Nothing to draw in a root alone.
    assert!(ops.crossover(&root, &a, &mut rng(49)).is_none());
}

#[test]
fn original_random_genomes_have_exactly_the_initial_length() {
    fn check<G: Grammar>(lengths: &[u32]) {
        let mut ops = original_ops::<G>();
        let mut r = rng(50);
        for &len in lengths {
            for _ in 0..5 {
                let g = ops.random(len, &mut r);
                assert_eq!(g.len(), len as usize);
                g.validate().unwrap();
            }
        }
        // The axiom, then grows: the same draws as growing one gene at a time.
        for seed in 0..10 {
            let (mut r1, mut r2) = (rng(seed), rng(seed));
            let fast = ops.random(40, &mut r1);
            let mut slow = Genome::<G>::axiom(&mut r2);
            for _ in 1..40 {
                assert!(ops.grow(&mut slow, &mut r2));
            }
            assert_eq!(fast, slow);
            assert_eq!(r1.next_u64(), r2.next_u64());
            let mut more = fast.clone();
            assert_eq!(ops.grow_to(&mut more, 60, &mut r1), 20);
            for _ in 40..60 {
                assert!(ops.grow(&mut slow, &mut r2));
            }
            assert_eq!(more, slow);
        }
    }
    // Beyond max_len 6 and max_depth 2, which the original's operators ignore.
    check::<Spaceship>(&[1, 2, 7, 50, 400]);
    check::<City>(&[1, 50, 150, 301]);
    check::<generators::Tree>(&[250, 1000]);
}

/// A derivation tree in the order its genes were made: per gene its parent (an earlier
/// gene), its link and its node's number of links.
struct Made {
    genes: Vec<(Option<usize>, u32, u32)>,
}

impl Made {
    fn of<G: Grammar>(g: &Genome<G>) -> Made {
        let pos: Vec<u32> = g.genes().map(|v| v.pos()).collect();
        let genes = g
            .genes()
            .map(|v| {
                let links = g.node(v).links;
                match v.parent() {
                    None => (None, 0, links),
                    Some(p) => {
                        let (_, link) = hang(g, v.pos());
                        (Some(pos.binary_search(&p).unwrap()), link, links)
                    }
                }
            })
            .collect();
        Made { genes }
    }

    /// Replays the growth and counts the steps that broke the original's grow rules:
    /// the parent was the last gene with an empty link while there were several, or the
    /// link was the parent's last empty one while it had several. Also returns the steps.
    fn broken_rules(&self) -> (usize, usize) {
        let mut taken: Vec<Vec<bool>> = Vec::new();
        let mut broken = 0;
        for (i, &(parent, link, links)) in self.genes.iter().enumerate() {
            if let Some(p) = parent {
                let open: Vec<usize> = (0..i).filter(|&j| taken[j].contains(&false)).collect();
                let empty: Vec<u32> = (0..self.genes[p].2)
                    .filter(|&l| !taken[p][l as usize])
                    .collect();
                assert!(open.contains(&p) && empty.contains(&link), "gene {i}");
                let last_gene = open.len() > 1 && open.last() == Some(&p);
                let last_link = empty.len() > 1 && empty.last() == Some(&link);
                broken += usize::from(last_gene || last_link);
                taken[p][link as usize] = true;
            }
            taken.push(vec![false; links as usize]);
        }
        (broken, self.genes.len() - 1)
    }
}

#[test]
fn original_random_genomes_grow_as_the_original_grows_them() {
    // The original's genomes (`generators/tests/golden`, made by its createRandomGenome)
    // list genes by `ref`, their creation order; a packed random genome keeps its creation
    // order too.
    let golden =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../generators/tests/golden");
    let mut checked = 0;
    for name in ["spaceship", "tree", "city"] {
        let path = golden.join(format!("{name}.json.gz"));
        let reader = std::fs::File::open(&path).unwrap_or_else(|e| {
            panic!(
                "the original's genomes `{}` are missing: {e}",
                path.display()
            )
        });
        let file: serde_json::Value = serde_json::from_reader(flate2::read::GzDecoder::new(
            std::io::BufReader::new(reader),
        ))
        .unwrap_or_else(|e| panic!("`{}`: {e}", path.display()));
        let links = |symbol: &str| {
            let s = file["symbols"].as_array().unwrap().iter();
            let s = s.clone().find(|s| s["name"] == symbol).unwrap();
            s["possible_children"].as_array().unwrap().len() as u32
        };
        for genome in file["genomes"].as_array().unwrap() {
            if genome["origin"]["kind"] != "random" {
                continue;
            }
            // (ref, parent ref, slot, links)
            let mut nodes = Vec::new();
            let mut stack = vec![(&genome["tree"], None)];
            while let Some((node, parent)) = stack.pop() {
                let r = node["ref"].as_u64().unwrap();
                let slot = node["slot"].as_u64().unwrap_or(0) as u32;
                nodes.push((r, parent, slot, links(node["symbol"].as_str().unwrap())));
                for child in node["children"].as_array().unwrap() {
                    stack.push((child, Some(r)));
                }
            }
            nodes.sort();
            let index = |r: u64| nodes.iter().position(|n| n.0 == r).unwrap();
            let made = Made {
                genes: nodes
                    .iter()
                    .map(|&(_, p, slot, links)| (p.map(index), slot, links))
                    .collect(),
            };
            let (broken, steps) = made.broken_rules();
            assert_eq!(broken, 0, "{}: {steps} grows", genome["id"]);
            checked += steps;
        }
    }
    // Every grow of the 75 random genomes (25 a generator) was checked.
    assert_eq!(checked, 7305, "grows of the original checked");

    // This crate's original random genomes keep the same rules; the weighted ones break
    // them.
    fn ours<G: Grammar>(variant: OperatorVariant, len: u32) -> (usize, usize) {
        let mut ops = new_ops::<G>(1, 1000, 1000).with_variant(variant);
        let mut r = rng(51);
        let mut total = (0, 0);
        for _ in 0..20 {
            let (broken, steps) = Made::of(&ops.random(len, &mut r)).broken_rules();
            total = (total.0 + broken, total.1 + steps);
        }
        total
    }
    assert_eq!(ours::<Spaceship>(OperatorVariant::Original, 100).0, 0);
    assert_eq!(
        ours::<generators::Tree>(OperatorVariant::Original, 300).0,
        0
    );
    assert_eq!(ours::<City>(OperatorVariant::Original, 150).0, 0);
    let (broken, steps) = ours::<generators::Tree>(OperatorVariant::Weighted, 300);
    assert!(broken > steps / 10, "{broken} of {steps}");
}
