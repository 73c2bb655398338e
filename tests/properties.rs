//! Properties of the published generators (spaceship, tree, city, buildings) under their paper
//! limits: any sequence of genetic operators keeps every genome valid and derivable into
//! finite instances, and the weighted operators keep it within the limits; JSON
//! round-trips random genomes exactly; derivation and the operators (of both variants)
//! are deterministic; and grow and cut choose with the frequencies their formulas give.
//!
//! Everything runs from fixed seeds, so a failure names the seed and step that reproduce
//! it.

use generators::{GeneratorVisitor, Published, Spaceship, city, spaceship};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use shapegen::genome::{Genome, GenomeSet, Limits};
use shapegen::graph::HEADER_WORDS;
use shapegen::ops::{OperatorVariant, Operators};
use shapegen::prelude::{Vec3, vec3};
use shapegen::{Grammar, Instance};

/// Genomes in the population the operator sequences work on.
const POPULATION: usize = 8;

fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// The initial genome length of the generator's GA presets, at least 50 (the buildings'
/// thesis settings start from 20 genes).
fn paper_initial_len(g: Published) -> u32 {
    g.presets().ga.initial_length.max(50)
}

/// Checks one genome fully: layout, limits (when given), and a derivation into finite
/// instances of the grammar's meshes.
fn check<G: Grammar>(g: &Genome<G>, limits: Option<&Limits>, out: &mut Vec<Instance>, what: &str) {
    if let Err(e) = g.validate() {
        panic!("{what}: invalid genome: {e}\n{g:?}");
    }
    if let Some(Err(e)) = limits.map(|l| g.validate_limits(l)) {
        panic!("{what}: limits broken: {e}\n{g:?}");
    }
    g.derive_into(out);
    let meshes = G::GRAPH.meshes.len() as u32;
    for i in out.iter() {
        assert!(
            i.transform.is_finite() && i.mesh.0 < meshes,
            "{what}: bad instance {i:?}\n{g:?}"
        );
    }
}

/// The words of a genome that are not parameters: kinds, parent and child offsets.
fn structure<G: Grammar>(g: &Genome<G>) -> Vec<u32> {
    g.genes()
        .flat_map(|gene| {
            let n = (HEADER_WORDS + g.node(gene).links) as usize;
            g.words()[gene.pos() as usize..][..n].iter().copied()
        })
        .collect()
}

/// What a run of [`Sequences`] did, per operator: grow, cut, alter, crossover, random,
/// sample.
#[derive(Debug, Default)]
struct Tally {
    /// Operations applied.
    applied: [usize; 6],
    /// Operations that changed a genome (grew, cut, altered, crossed, replaced).
    changed: [usize; 6],
    /// The longest genome seen.
    longest: usize,
}

/// Random operator sequences on a population of one grammar.
struct Sequences {
    /// First seed; seeds `seed .. seed + runs` each run one sequence.
    seed: u64,
    runs: u64,
    steps: usize,
    initial_len: u32,
    variant: OperatorVariant,
}

impl GeneratorVisitor for Sequences {
    type Output = Tally;

    fn visit<G: Grammar>(self, limits: Limits) -> Tally {
        let mut ops = Operators::<G>::new(limits)
            .unwrap()
            .with_variant(self.variant);
        let original = self.variant == OperatorVariant::Original;
        // The original's operators ignore the limits.
        let kept = (!original).then_some(&limits);
        let mut out = Vec::new();
        let mut tally = Tally::default();
        for seed in self.seed..self.seed + self.runs {
            let mut rng = rng(seed);
            // Initial lengths from a handful of genes up to twice the paper's.
            let mut pop: Vec<Genome<G>> = (0..POPULATION)
                .map(|i| ops.random(self.initial_len * (i as u32 + 1) / 4, &mut rng))
                .collect();
            for (i, g) in pop.iter().enumerate() {
                check(g, kept, &mut out, &format!("seed {seed}: initial {i}"));
            }
            let mut before = pop[0].clone();
            for step in 0..self.steps {
                let what = |op: &str| format!("seed {seed}, step {step}: {op}");
                let i = rng.random_range(0..POPULATION);
                before.clone_from(&pop[i]);
                match rng.random_range(0..100u32) {
                    0..30 => {
                        tally.applied[0] += 1;
                        if ops.grow(&mut pop[i], &mut rng) {
                            tally.changed[0] += 1;
                            assert_eq!(pop[i].len(), before.len() + 1, "{}", what("grow"));
                        } else {
                            assert!(pop[i] == before, "{}", what("failed grow changed it"));
                        }
                        check(&pop[i], kept, &mut out, &what("grow"));
                    }
                    30..60 => {
                        tally.applied[1] += 1;
                        if ops.cut(&mut pop[i], &mut rng) {
                            tally.changed[1] += 1;
                            // The original's cut grows the root alone once again.
                            let regrown = original && pop[i].len() == 2;
                            assert!(pop[i].len() < before.len() || regrown, "{}", what("cut"));
                        } else {
                            assert!(pop[i] == before, "{}", what("failed cut changed it"));
                        }
                        check(&pop[i], kept, &mut out, &what("cut"));
                    }
                    60..75 => {
                        tally.applied[2] += 1;
                        if ops.alter(&mut pop[i], &mut rng) {
                            tally.changed[2] += 1;
                        }
                        assert_eq!(structure(&pop[i]), structure(&before), "{}", what("alter"));
                        check(&pop[i], kept, &mut out, &what("alter"));
                    }
                    75..92 => {
                        tally.applied[3] += 1;
                        let j = rng.random_range(0..POPULATION);
                        if let Some((c, d)) = ops.crossover(&pop[i], &pop[j], &mut rng) {
                            tally.changed[3] += 1;
                            assert_eq!(
                                c.len() + d.len(),
                                pop[i].len() + pop[j].len(),
                                "{}",
                                what("crossover")
                            );
                            check(&c, kept, &mut out, &what("crossover, first child"));
                            check(&d, kept, &mut out, &what("crossover, second child"));
                            pop[i] = c;
                            pop[j] = d;
                        }
                    }
                    92..96 => {
                        tally.applied[4] += 1;
                        tally.changed[4] += 1;
                        let len = rng.random_range(1..=2 * self.initial_len);
                        ops.random_into(len, &mut pop[i], &mut rng);
                        if original {
                            assert_eq!(pop[i].len(), len as usize, "{}", what("random"));
                        }
                        check(&pop[i], kept, &mut out, &what("random"));
                    }
                    _ => {
                        tally.applied[5] += 1;
                        // Samples ignore min_len; the rest of the limits hold.
                        let s = ops.sample(&mut rng);
                        if let Err(e) = s.validate() {
                            panic!("{}: {e}\n{s:?}", what("sample"));
                        }
                        assert!(
                            s.len() <= limits.max_len as usize && s.depth() <= limits.max_depth,
                            "{}",
                            what("sample")
                        );
                        if let Some(s) = ops.sample_at_least(50, &mut rng) {
                            tally.changed[5] += 1;
                            check(&s, Some(&limits), &mut out, &what("sample_at_least"));
                            pop[i] = s;
                        }
                    }
                }
                tally.longest = tally.longest.max(pop[i].len());
            }
        }
        tally
    }
}

/// Runs `runs` sequences of `steps` operations of `variant` on `generator` and checks
/// that they all ran, that every operator did change genomes, and that genomes grew long.
fn operator_sequences(
    generator: Published,
    variant: OperatorVariant,
    seed: u64,
    runs: u64,
    steps: usize,
) {
    let tally = generator.visit(Sequences {
        seed,
        runs,
        steps,
        initial_len: paper_initial_len(generator),
        variant,
    });
    assert_eq!(tally.applied.iter().sum::<usize>(), runs as usize * steps);
    assert!(
        tally.changed.iter().all(|&n| n > 0),
        "an operator never changed anything: {tally:?}"
    );
    // Long genomes were reached: a third of max_len (a city holds at most 201 genes of
    // its 300).
    let max_len = generator.paper_limits().max_len as usize;
    assert!(tally.longest > max_len / 3, "{tally:?}");
    eprintln!("{generator:?}: {tally:?}");
}

// With the counts below the three generators see 106 000 weighted operations and
// 46 000 of the original's in all, each followed by a full check of the genomes it
// touched. The tree's genomes are the largest (up to 400 genes, or more with the
// original's operators), so it runs fewer.

#[test]
fn spaceship_operator_sequences_stay_valid() {
    operator_sequences(
        Published::Spaceship,
        OperatorVariant::Weighted,
        1000,
        30,
        2000,
    );
}

#[test]
fn tree_operator_sequences_stay_valid() {
    operator_sequences(Published::Tree, OperatorVariant::Weighted, 2000, 8, 2000);
}

#[test]
fn city_operator_sequences_stay_valid() {
    operator_sequences(Published::City, OperatorVariant::Weighted, 3000, 15, 2000);
}

#[test]
fn spaceship_original_operator_sequences_stay_valid() {
    operator_sequences(
        Published::Spaceship,
        OperatorVariant::Original,
        4000,
        10,
        2000,
    );
}

#[test]
fn tree_original_operator_sequences_stay_valid() {
    operator_sequences(Published::Tree, OperatorVariant::Original, 5000, 5, 2000);
}

#[test]
fn city_original_operator_sequences_stay_valid() {
    operator_sequences(Published::City, OperatorVariant::Original, 6000, 8, 2000);
}

// --- JSON ---------------------------------------------------------------------------------

struct JsonRoundTrip {
    seed: u64,
}

impl GeneratorVisitor for JsonRoundTrip {
    type Output = ();

    fn visit<G: Grammar>(self, limits: Limits) {
        let mut ops = Operators::<G>::new(limits).unwrap();
        let mut r = rng(self.seed);
        let mut all = Vec::new();
        let (mut a, mut b) = (Vec::new(), Vec::new());
        for k in 0..40u32 {
            let g = if k % 4 == 3 {
                ops.sample(&mut r)
            } else {
                ops.random(1 + k * limits.max_len / 40, &mut r)
            };
            let back = Genome::<G>::from_json(&g.to_json()).unwrap();
            assert!(back == g, "round trip of\n{g:?}\ngave\n{back:?}");
            assert_eq!(back.words(), g.words());
            let compact = serde_json::to_string(&g).unwrap();
            assert!(serde_json::from_str::<Genome<G>>(&compact).unwrap() == g);
            // Equal words derive to bit-identical instances.
            g.derive_into(&mut a);
            back.derive_into(&mut b);
            assert_eq!(a, b);
            all.push(g);
        }
        let set = GenomeSet::new(all);
        let back = GenomeSet::<G>::from_json(&set.to_json()).unwrap();
        assert_eq!(back.genomes.len(), set.genomes.len());
        assert!(back == set);
        let compact = serde_json::to_string(&set).unwrap();
        assert!(serde_json::from_str::<GenomeSet<G>>(&compact).unwrap() == set);
    }
}

#[test]
fn json_round_trips_random_genomes_exactly() {
    for (i, g) in Published::ALL.into_iter().enumerate() {
        g.visit(JsonRoundTrip {
            seed: 40 + i as u64,
        });
    }
}

#[test]
fn json_names_the_generator() {
    let mut ops = Operators::<Spaceship>::new(spaceship::PAPER_LIMITS).unwrap();
    let ship = ops.random(20, &mut rng(5));
    assert!(Genome::<generators::Tree>::from_json(&ship.to_json()).is_err());
    let set = GenomeSet::new(vec![ship]);
    assert!(GenomeSet::<generators::City>::from_json(&set.to_json()).is_err());
}

// --- determinism ----------------------------------------------------------------------------

struct Determinism {
    seed: u64,
}

impl GeneratorVisitor for Determinism {
    type Output = ();

    fn visit<G: Grammar>(self, limits: Limits) {
        // A run of every operator from one seed, on operators whose scratch buffers
        // start empty (`fresh`) or hold whatever an earlier, unrelated run left.
        fn run<G: Grammar>(ops: &mut Operators<G>, seed: u64) -> Vec<Genome<G>> {
            let mut r = rng(seed);
            let mut pop: Vec<Genome<G>> = (0..4).map(|_| ops.random(60, &mut r)).collect();
            for _ in 0..300 {
                let i = r.random_range(0..pop.len());
                let j = r.random_range(0..pop.len());
                match r.random_range(0..6u32) {
                    0 => {
                        ops.grow(&mut pop[i], &mut r);
                    }
                    1 => {
                        ops.cut(&mut pop[i], &mut r);
                    }
                    2 => {
                        ops.alter(&mut pop[i], &mut r);
                    }
                    3 => {
                        if let Some((c, d)) = ops.crossover(&pop[i], &pop[j], &mut r) {
                            pop[i] = c;
                            pop[j] = d;
                        }
                    }
                    4 => ops.random_into(40, &mut pop[i], &mut r),
                    _ => pop[i] = ops.sample(&mut r),
                }
            }
            pop
        }
        let mut a = Vec::new();
        for variant in OperatorVariant::ALL {
            let ops = || Operators::<G>::new(limits).unwrap().with_variant(variant);
            let (mut fresh, mut used) = (ops(), ops());
            run(&mut used, self.seed ^ 0xdead_beef);
            a = run(&mut fresh, self.seed);
            let b = run(&mut used, self.seed);
            let c = run(&mut fresh.clone(), self.seed);
            assert!(
                a == b && a == c,
                "{variant:?}: the same seed gave different genomes"
            );
            assert!(run(&mut fresh, self.seed + 1) != a);
        }

        // The same genome derives to the same instances, every time.
        let (mut x, mut y) = (Vec::new(), Vec::new());
        for g in &a {
            g.derive_into(&mut x);
            g.derive_into(&mut y);
            assert_eq!(x, y);
            let copy = Genome::<G>::from_json(&g.to_json()).unwrap();
            copy.derive_into(&mut y);
            assert_eq!(x, y);
        }
        // An empty output and a reused one give the same.
        let mut z = Vec::new();
        a[0].derive_into(&mut z);
        a[0].derive_into(&mut x);
        assert_eq!(x, z);
    }
}

#[test]
fn operators_and_derivation_are_deterministic() {
    for (i, g) in Published::ALL.into_iter().enumerate() {
        g.visit(Determinism {
            seed: 70 + i as u64,
        });
    }
}

// --- frequencies ----------------------------------------------------------------------------

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

/// Checks `observed` against `weights` (normalised here) with a chi-square test at
/// p = 0.001; the seeds are fixed, so the outcome is too.
fn assert_fits(observed: &[u64], weights: &[f64]) {
    let total: f64 = weights.iter().sum();
    let expected: Vec<f64> = weights.iter().map(|w| w / total).collect();
    let x2 = chi_square(observed, &expected);
    let dof = observed.len() - 1;
    assert!(
        x2 < CHI2_999[dof - 1],
        "chi-square {x2:.2} with {dof} dof: observed {observed:?}, expected {expected:?}"
    );
}

/// The (parent position, link) the gene at `pos` hangs from.
fn hang<G: Grammar>(g: &Genome<G>, pos: u32) -> (u32, u32) {
    let parent = g.gene(pos).parent().unwrap();
    let links = g.node(g.gene(parent)).links;
    let link = (0..links)
        .find(|&l| g.gene(parent).link(l) == Some(pos))
        .unwrap();
    (parent, link)
}

const THIRD: f64 = 1.0 / 3.0;

#[test]
fn spaceship_grow_picks_open_links_by_probability() {
    use spaceship::{Body, Start, Wing};
    let mut ops = Operators::<Spaceship>::new(spaceship::PAPER_LIMITS).unwrap();
    let mut r = rng(11);
    // One Body: its three links (next, wing, top) are open, each with p = 1/3.
    let mut base = Genome::<Spaceship>::with_root(Start {}).unwrap();
    let body = base.attach(0, "body", Body { size: Vec3::ONE }).unwrap();
    let mut counts = [0u64; 3];
    let mut g = base.clone();
    for _ in 0..6000 {
        g.clone_from(&base);
        assert!(ops.grow(&mut g, &mut r));
        let (parent, link) = hang(&g, base.words().len() as u32);
        assert_eq!(parent, body);
        counts[link as usize] += 1;
    }
    assert_fits(&counts, &[THIRD, THIRD, THIRD]);

    // Add a Wing: its WingNext link (p = 1) joins the Body's remaining next and top
    // (1/3 each), so grow picks it 3/5 of the time.
    let wing = base
        .attach(
            body,
            "wing",
            Wing {
                size: Vec3::ONE * 0.5,
                shift: 0.0,
            },
        )
        .unwrap();
    let mut counts = [0u64; 3];
    for _ in 0..6000 {
        g.clone_from(&base);
        assert!(ops.grow(&mut g, &mut r));
        counts[match hang(&g, base.words().len() as u32) {
            (p, 0) if p == body => 0,
            (p, 2) if p == body => 1,
            (p, 0) if p == wing => 2,
            other => panic!("grew at {other:?}"),
        }] += 1;
    }
    assert_fits(&counts, &[THIRD, THIRD, 1.0]);
}

#[test]
fn spaceship_cut_weighs_links_by_one_minus_p() {
    use spaceship::{Body, Start, Top, TopNext, Wing, WingNext};
    // Start -> b0 { next: b1, wing: w -> wn1 -> wn2, top: t -> tn1 -> tn2 }: 9 genes.
    // Cuttable links: b0.next, b0.wing, b0.top (1 - 1/3 each) and wn1.next (1 - 0.9);
    // Start.body, w.next, t.next and tn1.next have p = 1 and are never cut.
    let body = Body { size: Vec3::ONE };
    let wing_next = WingNext {
        size: vec3(1.0, 1.0, 1.0),
        shift: 0.0,
    };
    let top_next = TopNext {
        size: vec3(1.0, 1.0, 1.0),
    };
    let mut base = Genome::<Spaceship>::with_root(Start {}).unwrap();
    let b0 = base.attach(0, "body", body).unwrap();
    let b1 = base.attach(b0, "next", body).unwrap();
    let w = base
        .attach(
            b0,
            "wing",
            Wing {
                size: vec3(0.5, 0.3, 0.5),
                shift: 0.0,
            },
        )
        .unwrap();
    let wn1 = base.attach(w, "next", wing_next).unwrap();
    let wn2 = base.attach(wn1, "next", wing_next).unwrap();
    let t = base
        .attach(
            b0,
            "top",
            Top {
                size: vec3(0.5, 0.15, 0.5),
            },
        )
        .unwrap();
    let tn1 = base.attach(t, "next", top_next).unwrap();
    base.attach(tn1, "next", top_next).unwrap();
    assert_eq!(base.len(), 9);

    let cuts = [b1, w, t, wn2];
    let weights = [2.0 * THIRD, 2.0 * THIRD, 2.0 * THIRD, 0.1];
    let mut helper = Operators::<Spaceship>::new(Limits::new(1, 100, 15).unwrap()).unwrap();
    let outcomes: Vec<Genome<Spaceship>> = cuts
        .iter()
        .map(|&pos| {
            let mut g = base.clone();
            helper.cut_at(&mut g, pos).unwrap();
            g
        })
        .collect();
    let mut r = rng(12);
    // Paper limits (min_len 4): every candidate may go. min_len 7: only subtrees of at
    // most 2 genes, b1 and wn2.
    for (limits, allowed) in [
        (spaceship::PAPER_LIMITS, [true, true, true, true]),
        (Limits::new(7, 100, 15).unwrap(), [true, false, false, true]),
    ] {
        let mut ops = Operators::<Spaceship>::new(limits).unwrap();
        let mut counts = [0u64; 4];
        let mut g = base.clone();
        for _ in 0..8000 {
            g.clone_from(&base);
            assert!(ops.cut(&mut g, &mut r));
            let k = outcomes
                .iter()
                .position(|o| *o == g)
                .unwrap_or_else(|| panic!("an unexpected cut:\n{g}"));
            counts[k] += 1;
        }
        let (obs, exp): (Vec<u64>, Vec<f64>) = (0..4)
            .filter(|&k| allowed[k])
            .map(|k| (counts[k], weights[k]))
            .unzip();
        for k in 0..4 {
            if !allowed[k] {
                assert_eq!(counts[k], 0, "cut {k} leaves fewer than min_len genes");
            }
        }
        assert_fits(&obs, &exp);
    }
}

#[test]
fn city_grow_weighs_lots_against_a_building() {
    // Lot 0 without its building: its `building` link (p = 1) against the 99 empty lots
    // (p = 0.33 each).
    let mut base = Genome::<city::City>::with_root(city::Start {}).unwrap();
    let lot0 = base.attach_at(0, "lots", 0, city::Lot {}).unwrap();
    let mut ops = Operators::<city::City>::new(city::PAPER_LIMITS).unwrap();
    let mut r = rng(13);
    // Categories: the building; lots 1..=33, 34..=66, 67..=99.
    let mut counts = [0u64; 4];
    let mut g = base.clone();
    for _ in 0..8000 {
        g.clone_from(&base);
        assert!(ops.grow(&mut g, &mut r));
        counts[match hang(&g, base.words().len() as u32) {
            (p, 0) if p == lot0 => 0,
            (0, lot @ 1..=99) => 1 + (lot as usize - 1) / 33,
            other => panic!("grew at {other:?}"),
        }] += 1;
    }
    let group = 33.0 * 0.33;
    assert_fits(&counts, &[1.0, group, group, group]);
}
