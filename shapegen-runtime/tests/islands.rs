//! The island model: one island is the GA, a run gives the same result on any number of
//! processes dividing its islands (threads standing in for processes), migrants replace
//! the worst of the next island, resumed runs end as uninterrupted ones whatever the
//! processes, and a stop on one process stops all.

mod support {
    pub mod evaluators;
    pub mod threads;
}

use std::sync::atomic::{AtomicBool, Ordering};

use generators::{City, Spaceship, city, spaceship};
use shapegen_runtime::ops::OperatorVariant;
use shapegen_runtime::optimize::islands::{
    Alone, Exchange, IslandGa, IslandGaSettings, IslandGaState, IslandSettings,
};
use shapegen_runtime::optimize::*;
use shapegen_runtime::prelude::*;
use support::evaluators::{BoxTarget, Skyline, timeless};
use support::threads::on_ranks;

fn limits() -> Limits {
    Limits::new(1, 120, 40).unwrap()
}

/// The paper's city settings, smaller, with `operators`.
fn ga(operators: OperatorVariant) -> GaSettings {
    GaSettings {
        population: 24,
        elitism: 4,
        initial_length: 30,
        operators,
        ..city::paper_ga()
    }
}

fn islands(count: u32, migrants: u32, interval: u64) -> IslandGaSettings {
    IslandGaSettings {
        ga: ga(OperatorVariant::Original),
        islands: IslandSettings {
            count,
            migrants,
            interval,
        },
    }
}

/// What two runs must share to be the same run: best genome and fitness bits,
/// evaluations, generations, and the history without its times.
type Key = (Genome<City>, u64, u64, u64, Vec<(u64, u64, u64, u64, u64)>);

fn key(r: &RunResult<City>) -> Key {
    (
        r.best.clone(),
        r.best_fitness.to_bits(),
        r.evaluations,
        r.generations,
        timeless(&r.history),
    )
}

/// A run of `settings` on `processes` threads to `budget`: each rank's result.
fn spread(settings: IslandGaSettings, processes: usize, budget: Budget) -> Vec<RunResult<City>> {
    on_ranks(processes, |exchange| {
        let mut run = IslandGa::<City>::new_on(settings, limits(), 5, Box::new(exchange)).unwrap();
        run.run(&mut Skyline::new(), &budget, &mut Silent).unwrap()
    })
}

#[test]
fn one_island_is_the_ga_to_the_bit() {
    for operators in OperatorVariant::ALL {
        let settings = IslandGaSettings {
            ga: ga(operators),
            islands: IslandSettings {
                count: 1,
                ..IslandSettings::default()
            },
        };
        let budget = Budget::generations(12);
        let mut plain = Ga::<City>::new(settings.ga, limits(), 9).unwrap();
        let plain = plain
            .run(&mut Skyline::new(), &budget, &mut Silent)
            .unwrap();
        let mut one = IslandGa::<City>::new(settings, limits(), 9).unwrap();
        let one = one.run(&mut Skyline::new(), &budget, &mut Silent).unwrap();
        assert_eq!(key(&one), key(&plain), "{operators:?}");
    }
}

#[test]
fn any_number_of_processes_dividing_the_islands_gives_the_same_run() {
    let settings = islands(4, 2, 3);
    let budget = Budget::generations(10);
    let mut alone = IslandGa::<City>::new(settings, limits(), 5).unwrap();
    let alone = alone
        .run(&mut Skyline::new(), &budget, &mut Silent)
        .unwrap();
    assert_eq!(alone.evaluations, 4 * 24 + 10 * 4 * 20);
    for processes in [1, 2, 4] {
        for (rank, result) in spread(settings, processes, budget).iter().enumerate() {
            assert_eq!(
                key(result),
                key(&alone),
                "{processes} processes, rank {rank}"
            );
        }
    }
    // Another generator, another evaluator.
    let ship = IslandGaSettings {
        ga: GaSettings {
            population: 20,
            elitism: 4,
            ..spaceship::paper_ga()
        },
        ..settings
    };
    let ships = on_ranks(2, |exchange| {
        let mut run = IslandGa::<Spaceship>::new_on(ship, limits(), 3, Box::new(exchange)).unwrap();
        let r = run
            .run(&mut BoxTarget::new(), &budget, &mut Silent)
            .unwrap();
        (r.best, r.best_fitness.to_bits(), timeless(&r.history))
    });
    let mut one = IslandGa::<Spaceship>::new(ship, limits(), 3).unwrap();
    let one = one
        .run(&mut BoxTarget::new(), &budget, &mut Silent)
        .unwrap();
    for ship in ships {
        assert_eq!(
            ship,
            (
                one.best.clone(),
                one.best_fitness.to_bits(),
                timeless(&one.history)
            )
        );
    }
    // Migration matters: the islands apart end elsewhere.
    let mut apart = IslandGa::<City>::new(islands(4, 0, 3), limits(), 5).unwrap();
    let apart = apart
        .run(&mut Skyline::new(), &budget, &mut Silent)
        .unwrap();
    assert_ne!(timeless(&apart.history), timeless(&alone.history));
}

#[test]
fn islands_that_processes_cannot_share_evenly_are_refused() {
    let errors = on_ranks(3, |exchange| {
        IslandGa::<City>::new_on(islands(4, 2, 3), limits(), 5, Box::new(exchange))
            .unwrap_err()
            .to_string()
    });
    for err in errors {
        assert!(
            err.contains("islands.count") && err.contains("multiple"),
            "{err}"
        );
    }
    let bad = |s: IslandGaSettings| s.validate().unwrap_err().field;
    assert_eq!(bad(islands(0, 2, 3)), "islands.count");
    assert_eq!(bad(islands(4, 24, 3)), "islands.migrants");
    assert_eq!(bad(islands(4, 2, 0)), "islands.interval");
}

/// The state after `generations` generations of `settings` on one process.
fn state_after(settings: IslandGaSettings, generations: u64) -> IslandGaState<City> {
    let mut run = IslandGa::<City>::new(settings, limits(), 5).unwrap();
    run.run(
        &mut Skyline::new(),
        &Budget::generations(generations),
        &mut Silent,
    )
    .unwrap();
    run.checkpoint()
}

#[test]
fn migrants_replace_the_worst_of_the_next_island() {
    // Up to the first migration, after generation 3, the two runs are the same.
    let apart = state_after(islands(3, 0, 3), 3);
    let together = state_after(islands(3, 2, 3), 3);
    let rank = |fitness: &[f64]| {
        let mut order: Vec<usize> = (0..fitness.len()).collect();
        // Best first, NaN last, ties in index order, as the GA ranks.
        order.sort_by(|&a, &b| {
            let (a, b) = (fitness[a], fitness[b]);
            b.partial_cmp(&a)
                .unwrap_or_else(|| a.is_nan().cmp(&b.is_nan()))
        });
        order
    };
    let mut replaced = 0;
    for k in 0..3 {
        let previous = &apart.islands[(k + 2) % 3];
        let island = &apart.islands[k];
        let mut expected = island.clone();
        let best = &rank(&previous.fitness)[..2];
        let worst = &rank(&island.fitness)[24 - 2..];
        for (&b, &w) in best.iter().zip(worst) {
            expected.population[w] = previous.population[b].clone();
            expected.fitness[w] = previous.fitness[b];
            replaced += usize::from(island.population[w] != previous.population[b]);
        }
        assert_eq!(together.islands[k], expected, "island {k}");
    }
    assert!(replaced > 0, "the migrants changed nothing");
    // Migrants are copies: the best so far stays; the record of generation 3 is of the
    // islands after they landed.
    let (a, t) = (&apart.progress, &together.progress);
    assert_eq!(
        (a.evaluations, &a.record.best),
        (t.evaluations, &t.record.best)
    );
    let history = |p: &Progress<Best<City>>| timeless(&p.record.history);
    assert_eq!(history(a)[..3], history(t)[..3]);
    assert_ne!(
        history(a)[3].3,
        history(t)[3].3,
        "the mean moves with the migrants"
    );
}

#[test]
fn a_resumed_run_ends_as_an_uninterrupted_one_on_any_processes() {
    let settings = islands(4, 2, 3);
    let budget = Budget::generations(10);
    let uninterrupted = spread(settings, 2, budget).remove(0);
    // Interrupted after generation 5 on two processes; rank 0 keeps the checkpoint.
    let saved: Vec<Option<String>> = on_ranks(2, |exchange| {
        let rank = exchange.rank();
        let run = IslandGa::<City>::new_on(settings, limits(), 5, Box::new(exchange)).unwrap();
        let mut at_five = |s: &Snapshot<'_, City>| {
            if s.generation == 5 {
                Control::Stop
            } else {
                Control::Continue
            }
        };
        let mut state = None;
        let result = Session::new(run, budget)
            .on_progress(&mut at_five)
            .on_save(|save| {
                state = Some(serde_json::to_string(&save.state).unwrap());
                Ok::<(), std::io::Error>(())
            })
            .run(&mut Skyline::new())
            .unwrap();
        assert_eq!(
            (result.stopped, result.generations),
            (StopReason::Observer, 5)
        );
        state.filter(|_| rank == 0)
    });
    let json = saved[0].clone().expect("rank 0 saved");
    let state: IslandGaState<City> = serde_json::from_str(&json).unwrap();
    assert_eq!((state.islands.len(), state.progress.generation), (4, 5));
    for processes in [1, 4] {
        let results = on_ranks(processes, |exchange| {
            let state: IslandGaState<City> = serde_json::from_str(&json).unwrap();
            let run = IslandGa::resume_on(state, Box::new(exchange)).unwrap();
            Session::new(run, budget).run(&mut Skyline::new()).unwrap()
        });
        for result in &results {
            assert_eq!(key(result), key(&uninterrupted), "resumed on {processes}");
        }
    }
    // And through the one-process API.
    let mut alone = IslandGa::<City>::resume(serde_json::from_str(&json).unwrap()).unwrap();
    let alone = alone
        .run(&mut Skyline::new(), &budget, &mut Silent)
        .unwrap();
    assert_eq!(key(&alone), key(&uninterrupted));
}

#[test]
fn a_stop_flag_set_on_one_process_stops_every_process_at_the_same_generation() {
    let settings = islands(4, 2, 3);
    let ends = on_ranks(2, |exchange| {
        let rank = exchange.rank();
        let stop = AtomicBool::new(false);
        let mut saved = Vec::new();
        let mut on_rank_one = |s: &Snapshot<'_, City>| {
            if rank == 1 && s.generation == 4 {
                stop.store(true, Ordering::SeqCst);
            }
            Control::Continue
        };
        let run = IslandGa::<City>::new_on(settings, limits(), 5, Box::new(exchange)).unwrap();
        let result = Session::new(run, Budget::generations(50))
            .stop_flag(&stop)
            .on_progress(&mut on_rank_one)
            .save_every(std::time::Duration::ZERO)
            .on_save(|save| {
                saved.push((save.progress.generation, save.state.islands.len()));
                Ok::<(), std::io::Error>(())
            })
            .run(&mut Skyline::new())
            .unwrap();
        (result.stopped, result.generations, saved)
    });
    for (rank, (stopped, generations, saved)) in ends.iter().enumerate() {
        assert_eq!(
            (*stopped, *generations),
            (StopReason::Observer, 4),
            "rank {rank}"
        );
        // Saved together after every generation, the last at the stop; rank 0 holds
        // every island, rank 1 its own two.
        let islands = if rank == 0 { 4 } else { 2 };
        let expected: Vec<(u64, usize)> = (0..=4).map(|g| (g, islands)).collect();
        assert_eq!(saved, &expected, "rank {rank}");
    }
}

#[test]
fn one_process_alone_exchanges_with_itself() {
    let settings = islands(2, 1, 2);
    let budget = Budget::generations(6);
    let mut on_alone = IslandGa::<City>::new_on(settings, limits(), 5, Box::new(Alone)).unwrap();
    let a = on_alone
        .run(&mut Skyline::new(), &budget, &mut Silent)
        .unwrap();
    let b = spread(settings, 1, budget).remove(0);
    assert_eq!(key(&a), key(&b));
}
