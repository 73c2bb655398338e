//! The original variant of SMC and SOSMC, run by run: initial particles of two genes,
//! one gene and one evaluation per particle per step, the depth bound of chromosome
//! order only, and resampling from the second step on.

use shapegen_runtime::optimize::*;
use shapegen_runtime::prelude::*;

generator! {
    /// A chain of blocks of random heights.
    pub Chain {
        axiom Seg;
        node Seg {
            params { h: f32 ~ uniform(0.5, 1.5) }
            children { next: Seg = 0.3 }
            derive(s) {
                let s = s.resize(vec3(1.0, h, 1.0));
                s.emit(CUBE);
                if let Some(next) = next { s.translate(vec3(0.0, h, 0.0)).derive(next); }
            }
        }
    }
}

/// Scores the first genome of every batch 1 and the others 0, and keeps every genome it
/// was given.
#[derive(Default)]
struct FirstWins {
    batches: Vec<Vec<Genome<Chain>>>,
}

impl Evaluator<Chain> for FirstWins {
    fn evaluate(
        &mut self,
        genomes: &[Genome<Chain>],
        out: &mut [f64],
    ) -> Result<(), EvaluateError> {
        self.batches.push(genomes.to_vec());
        for (i, o) in out.iter_mut().enumerate() {
            *o = if i == 0 { 1.0 } else { 0.0 };
        }
        Ok(())
    }
}

fn original(order: Order, particles: u32) -> SmcSettings {
    SmcSettings {
        particles,
        ..generators::city::paper_smc(order)
    }
}

/// The root gene's words: the parameters tell particles apart.
fn root(g: &Genome<Chain>) -> &[u32] {
    &g.words()[..Genome::<Chain>::graph().nodes[0].gene_words() as usize]
}

#[test]
fn particles_start_at_two_genes_and_grow_one_per_step_past_the_maximum_length() {
    for order in [Order::Chromosome, Order::Stochastic] {
        let limits = Limits::new(1, 5, 30).unwrap();
        let mut smc = Smc::<Chain>::new(original(order, 6), limits, 3).unwrap();
        let mut eval = FirstWins::default();
        let r = smc
            .run(&mut eval, &Budget::generations(0), &mut Silent)
            .unwrap();
        assert_eq!(r.evaluations, 6);
        assert!(smc.checkpoint().particles.iter().all(|g| g.len() == 2));
        let r = smc
            .run(&mut eval, &Budget::generations(10), &mut Silent)
            .unwrap();
        // One evaluation per particle per step, the initial particles' included.
        assert_eq!((r.generations, r.evaluations), (10, 66));
        assert_eq!(eval.batches.len(), 11);
        for (step, batch) in eval.batches.iter().enumerate() {
            assert_eq!(batch.len(), 6);
            assert!(
                batch.iter().all(|g| g.len() == 2 + step),
                "{order:?} {step}"
            );
        }
    }
}

#[test]
fn only_chromosome_order_stops_at_the_maximum_depth() {
    // Levels 0 to max_depth: chains of max_depth + 1 genes.
    let limits = Limits::new(1, 100, 4).unwrap();
    let mut eval = FirstWins::default();
    let r = Smc::<Chain>::new(original(Order::Chromosome, 4), limits, 1)
        .unwrap()
        .run(&mut eval, &Budget::generations(8), &mut Silent)
        .unwrap();
    // Particles that cannot grow are evaluated all the same.
    assert_eq!(r.evaluations, 4 * 9);
    let lens: Vec<usize> = eval.batches.iter().map(|b| b[0].len()).collect();
    assert_eq!(lens, [2, 3, 4, 5, 5, 5, 5, 5, 5]);
    let mut eval = FirstWins::default();
    Smc::<Chain>::new(original(Order::Stochastic, 4), limits, 1)
        .unwrap()
        .run(&mut eval, &Budget::generations(8), &mut Silent)
        .unwrap();
    assert_eq!(eval.batches.last().unwrap()[0].len(), 10);
}

#[test]
fn the_first_step_grows_the_initial_particles_and_later_steps_resample() {
    for order in [Order::Chromosome, Order::Stochastic] {
        let mut eval = FirstWins::default();
        Smc::<Chain>::new(original(order, 8), Limits::new(1, 100, 30).unwrap(), 2)
            .unwrap()
            .run(&mut eval, &Budget::generations(2), &mut Silent)
            .unwrap();
        let [initial, first, second] = &eval.batches[..] else {
            panic!("three batches");
        };
        // Step 1 grows each initial particle: all eight roots stay, in their order.
        for (a, b) in initial.iter().zip(first) {
            assert_eq!(root(a), root(b));
        }
        let mut roots: Vec<&[u32]> = first.iter().map(root).collect();
        roots.dedup();
        assert_eq!(roots.len(), 8, "{order:?}: the initial particles differ");
        // Step 2 resamples step 1's particles first: only the first scored above 0, and
        // the worst scored 0, which the offset keeps at weight 0.
        assert!(
            second.iter().all(|g| root(g) == root(&first[0])),
            "{order:?}"
        );
    }
}
