//! `shapegen sweep`: a parameter study. Every combination of the `--grid` values (a grid
//! point) runs `--runs` times on seeds `seed + r`, each run (a *cell*) with the same
//! budget; the cells run in parallel on this machine, or as a Slurm job array.
//!
//! The study lives in its folder `DIR`: `plan.json` ([`plan`]), one folder per finished
//! cell ([`cell`]), and the tables ([`tables`]) and plots ([`figures`]) made from the
//! finished cells, rewritten after each. The same command run again goes on where the
//! study stopped; `--plan-only` writes the plan and a Slurm script ([`slurm`]) instead of
//! running, `--cell DIR I` runs one cell of a saved plan, and `--collect DIR` makes the
//! tables and plots of whatever cells are finished.

pub mod cell;
mod figures;
mod plan;
mod slurm;
mod tables;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

use anyhow::Context;
use clap::Args;
use shapegen::gpu::GpuContext;
use shapegen::scene::{Method, Scene};

use crate::cli::backend::BackendArgs;
use crate::cli::folder::{Existing, Folder, Kind};
use crate::cli::generators::{Generators, Jobs};
use crate::cli::interrupt;
use crate::cli::memory::{MemoryArgs, MemoryCheck, threads_per_job};
use cell::{CellRun, Finished};
use plan::{Axis, Plan, StudyBudget};
use slurm::SlurmArgs;

/// Arguments of `shapegen sweep`.
#[derive(Debug, Args)]
pub struct SweepArgs {
    /// The scene file (TOML).
    #[arg(required_unless_present_any = ["cell", "collect"], conflicts_with_all = ["cell", "collect"])]
    scene: Option<PathBuf>,
    /// A swept key and its values: any key `--set` takes, e.g.
    /// `optimizer.population=50,100,200` or `optimizer.selection=tournament,random`;
    /// repeatable, every combination is a grid point (the first key outermost). Commas
    /// inside brackets or quotes do not split values.
    #[arg(long, value_name = "KEY=V1,V2,..")]
    grid: Vec<String>,
    /// Runs of every grid point; run r uses seed + r.
    #[arg(long)]
    runs: Option<u64>,
    /// Each run's budget in wall-time seconds: results then depend on the machine's
    /// speed, its load and --jobs.
    #[arg(long, group = "budget")]
    seconds: Option<f64>,
    /// Each run's budget in fitness evaluations: results independent of the machine and
    /// of --jobs.
    #[arg(long, group = "budget")]
    evaluations: Option<u64>,
    /// Each run's budget in generations (the GA's generations, SMC's steps, RJMCMC's
    /// iterations): results independent of the machine and of --jobs.
    #[arg(long, group = "budget")]
    generations: Option<u64>,
    /// Base seed: run r of every grid point uses seed + r (default: `optimizer.seed`).
    #[arg(long)]
    seed: Option<u64>,
    /// The search method of every run (overrides `optimizer.method`; or sweep
    /// `--grid optimizer.method=..`).
    #[arg(long, help = crate::cli::method::method_help(
        "The search method of every run (overrides `optimizer.method`; or sweep \
         `--grid optimizer.method=..`)"
    ))]
    method: Option<Method>,
    /// Overrides a scene value in every run, e.g. `--set optimizer.tournament=3`;
    /// repeatable; the grid's values come after these.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    sets: Vec<String>,
    #[command(flatten)]
    backend: BackendArgs,
    /// The study's folder; created if missing. The same command again goes on with the
    /// study in it (finished cells are kept); another study there is refused.
    #[arg(long, required_unless_present_any = ["cell", "collect"])]
    out: Option<PathBuf>,
    /// Start the study in --out afresh: the outputs there (this study's cells, another
    /// study, a run's or a comparison's) are removed, and listed, first.
    #[arg(long)]
    force: bool,
    /// Cells run at once (default: one per core); the worker threads (--threads) are
    /// shared among them.
    #[arg(long, value_name = "J")]
    jobs: Option<usize>,
    #[command(flatten)]
    memory: MemoryArgs,
    /// Write the plan and `DIR/sweep.sbatch`, a Slurm job array of one task per cell, and
    /// run nothing; submit it with `sbatch DIR/sweep.sbatch`.
    #[arg(long)]
    plan_only: bool,
    #[command(flatten)]
    slurm: SlurmArgs,
    /// Run cell I of the study saved in DIR (by --plan-only or a sweep), as the sweep
    /// would, and write its folder; a finished cell is left as it is. What a Slurm task
    /// runs.
    #[arg(long, num_args = 2, value_names = ["DIR", "I"], conflicts_with = "collect")]
    cell: Option<Vec<String>>,
    /// Write the tables and plots of the study in DIR from its finished cells, and say
    /// which are missing (failing when any is).
    #[arg(long, value_name = "DIR")]
    collect: Option<PathBuf>,
}

/// Runs `shapegen sweep`.
pub fn run<J: Jobs>(args: &SweepArgs, tool: &Generators<J>) -> anyhow::Result<()>
where
    for<'a> J::Job<'a>: From<CellRun<'a>> + From<MemoryCheck<'a>>,
{
    if let Some(cell) = &args.cell {
        refuse_study_flags(args, "--cell")?;
        let dir = Path::new(&cell[0]);
        let index: u64 = cell[1].parse().with_context(|| {
            format!("--cell {} {}: the cell is a whole number", cell[0], cell[1])
        })?;
        return run_cell(dir, index, tool, args.memory);
    }
    if let Some(dir) = &args.collect {
        refuse_study_flags(args, "--collect")?;
        return collect(dir);
    }
    args.slurm.check()?;
    let (scene, out) = match (&args.scene, &args.out) {
        (Some(scene), Some(out)) => (scene, out),
        _ => anyhow::bail!("give the scene and --out"),
    };
    let runs = args
        .runs
        .context("give the runs of every grid point with --runs")?;
    let grid = args
        .grid
        .iter()
        .map(|g| Axis::parse(g))
        .collect::<anyhow::Result<Vec<_>>>()?;
    let scene = std::fs::canonicalize(scene)
        .with_context(|| format!("cannot read scene `{}`", scene.display()))?;
    let plan = Plan {
        version: Plan::VERSION.to_owned(),
        scene,
        grid,
        runs,
        budget: StudyBudget::from_flags(args.seconds, args.evaluations, args.generations)?,
        seed: 0,
        method: args.method,
        sets: args.sets.clone(),
        backend: args.backend.clone(),
        optimum: None,
    }
    .checked(args.seed, tool.registry())?;
    let jobs = match args.jobs {
        Some(0) => anyhow::bail!("--jobs 0: give at least 1"),
        Some(j) => j,
        None => std::thread::available_parallelism().map_or(1, usize::from),
    };
    if !args.plan_only {
        let jobs = jobs.min(usize::try_from(plan.cells()).unwrap_or(usize::MAX));
        check_memory(&plan, tool, jobs, args.memory)?;
    }
    // A study goes on with the cells of its own plan; save_or_match refuses another plan.
    let _folder = Folder::claim(out, Kind::Sweep, Existing::from_flags(args.force, true))?;
    plan.save_or_match(out)?;
    if args.plan_only {
        return plan_only(&plan, out, &args.slurm);
    }
    run_local(&plan, out, jobs, tool)
}

/// Refuses a study whose cells, `jobs` at a time, each with its share of the worker
/// threads, would not fit in memory: each grid point's, as if all `jobs` cells at once
/// were of that point.
fn check_memory<J: Jobs>(
    plan: &Plan,
    tool: &Generators<J>,
    jobs: usize,
    limit: MemoryArgs,
) -> anyhow::Result<()>
where
    for<'a> J::Job<'a>: From<CellRun<'a>> + From<MemoryCheck<'a>>,
{
    let jobs = jobs.max(1);
    for point in 0..plan.points() {
        let scene = Scene::open(
            &plan.scene,
            tool.registry(),
            &plan.overrides_at(point, None),
        )?;
        tool.visit(
            &scene.generator,
            MemoryCheck::scene(&scene, jobs, &plan.backend, limit),
        )
        .with_context(|| format!("grid point {}", plan.describe(point)))?;
    }
    Ok(())
}

/// Refuses the flags that make a study when `mode` (`--cell`, `--collect`) works on a
/// saved one.
fn refuse_study_flags(args: &SweepArgs, mode: &str) -> anyhow::Result<()> {
    let given = [
        ("--grid", !args.grid.is_empty()),
        ("--runs", args.runs.is_some()),
        ("--seconds", args.seconds.is_some()),
        ("--evaluations", args.evaluations.is_some()),
        ("--generations", args.generations.is_some()),
        ("--seed", args.seed.is_some()),
        ("--method", args.method.is_some()),
        ("--set", !args.sets.is_empty()),
        (
            "--cpu, --gpu or --no-incremental",
            args.backend != BackendArgs::default(),
        ),
        ("--out", args.out.is_some()),
        ("--jobs", args.jobs.is_some()),
        ("--plan-only", args.plan_only),
        ("--force", args.force),
    ];
    if let Some((flag, _)) = given.iter().find(|(_, given)| *given) {
        anyhow::bail!(
            "{mode} works on the study saved in its folder: {flag} cannot be given with it"
        );
    }
    Ok(())
}

/// `--plan-only`: the Slurm script beside the plan.
fn plan_only(plan: &Plan, dir: &Path, slurm: &SlurmArgs) -> anyhow::Result<()> {
    let dir =
        std::fs::canonicalize(dir).with_context(|| format!("cannot read `{}`", dir.display()))?;
    let logs = dir.join("logs");
    std::fs::create_dir_all(&logs)
        .with_context(|| format!("cannot create `{}`", logs.display()))?;
    let exe = std::env::current_exe().context("cannot find the running shapegen binary")?;
    let script = dir.join("sweep.sbatch");
    crate::cli::files::atomic_write(&script, slurm.script(plan.cells(), &dir, &exe).as_bytes())?;
    println!(
        "wrote plan.json ({} cells: {} grid points x {} runs) and sweep.sbatch to {}; \
         submit the study with\n    sbatch {}",
        plan.cells(),
        plan.points(),
        plan.runs,
        dir.display(),
        script.display()
    );
    Ok(())
}

/// `--cell DIR I`: runs cell `index` of the study in `dir`, unless it is done.
fn run_cell<J: Jobs>(
    dir: &Path,
    index: u64,
    tool: &Generators<J>,
    limit: MemoryArgs,
) -> anyhow::Result<()>
where
    for<'a> J::Job<'a>: From<CellRun<'a>> + From<MemoryCheck<'a>>,
{
    let plan = Plan::load(dir)?;
    anyhow::ensure!(
        index < plan.cells(),
        "--cell {} {index}: the study has cells 0 to {}",
        dir.display(),
        plan.cells() - 1
    );
    let folder = cell::folder(&plan, dir, index);
    if cell::load(&plan, dir, index)?.is_some() {
        println!("cell {index} is done already: {}", folder.display());
        return Ok(());
    }
    let cell = plan.cell(index);
    let scene = Scene::open(&plan.scene, tool.registry(), &plan.overrides(cell))?;
    tool.visit(
        &scene.generator,
        MemoryCheck::scene(&scene, 1, &plan.backend, limit),
    )?;
    let stop = interrupt::flag();
    let gpu = plan.backend.open();
    eprintln!(
        "cell {index} of {}: {}, run {} (seed {})",
        plan.cells(),
        plan.describe(cell.point),
        cell.run,
        cell.seed
    );
    match cell::run(&plan, dir, index, tool, gpu.as_ref(), &stop)? {
        Some(finished) => {
            println!("{}; wrote {}", outcome(&finished), folder.display());
            Ok(())
        }
        None => anyhow::bail!("interrupted: cell {index} was not written"),
    }
}

/// `--collect DIR`: the tables and plots of the finished cells.
fn collect(dir: &Path) -> anyhow::Result<()> {
    let plan = Plan::load(dir)?;
    let done = cell::load_all(&plan, dir)?;
    write_outputs(&plan, dir, &done)?;
    let missing = tables::missing(&plan, &done);
    let list = tables::ranges(&missing);
    anyhow::ensure!(
        missing.is_empty(),
        "wrote the tables and plots of the {} finished cells of {} to {}, but {} cells are \
         missing: {list}. Run each with `shapegen sweep --cell {} I`, or on Slurm with \
         `sbatch --array={list} {}`",
        done.len(),
        plan.cells(),
        dir.display(),
        missing.len(),
        dir.display(),
        dir.join("sweep.sbatch").display()
    );
    println!(
        "collected all {} cells; wrote sweep.csv, summary.md and the plots to {}",
        plan.cells(),
        dir.display()
    );
    Ok(())
}

/// The tables and plots of a study for its finished cells `done`.
fn write_outputs(plan: &Plan, dir: &Path, done: &BTreeMap<u64, Finished>) -> anyhow::Result<()> {
    tables::write(plan, dir, done)?;
    figures::write(plan, dir, done)
}

/// A finished cell in a line.
fn outcome(finished: &Finished) -> String {
    let r = &finished.record;
    format!(
        "best {:.5}  {} evaluations  {} generations  {:.1} s",
        r.best, r.evaluations, r.generations, r.seconds
    )
}

/// Runs the study's unfinished cells here, `jobs` at a time, each with its share of the
/// worker threads, rewriting the tables and plots after each.
fn run_local<J: Jobs>(
    plan: &Plan,
    dir: &Path,
    jobs: usize,
    tool: &Generators<J>,
) -> anyhow::Result<()>
where
    for<'a> J::Job<'a>: From<CellRun<'a>> + From<MemoryCheck<'a>>,
{
    let done = cell::load_all(plan, dir)?;
    let pending: Vec<u64> = (0..plan.cells())
        .filter(|i| !done.contains_key(i))
        .collect();
    let total = plan.cells();
    if !done.is_empty() {
        eprintln!(
            "{} of {total} cells are done in {}; running the other {}",
            done.len(),
            dir.display(),
            pending.len()
        );
        write_outputs(plan, dir, &done)?;
    }
    let jobs = jobs.min(pending.len()).max(1);
    let threads = threads_per_job(jobs);
    let gpu = if pending.is_empty() {
        None
    } else {
        eprintln!(
            "sweeping {} grid points x {} runs of {} ({} per run): {} cells, {jobs} at a \
             time, worker threads per cell: {threads}",
            plan.points(),
            plan.runs,
            plan.scene.display(),
            plan.budget.describe(),
            pending.len()
        );
        plan.backend.open()
    };
    let cells = LocalCells {
        plan,
        dir,
        tool,
        gpu: gpu.as_ref(),
        pending,
        threads,
        stop: interrupt::flag(),
        next: AtomicUsize::new(0),
        done: Mutex::new(done),
    };
    let done = cells.run(jobs)?;
    anyhow::ensure!(
        done.len() as u64 == total,
        "interrupted: {} of {total} cells are done and their tables written to {}; run the \
         same command again to go on",
        done.len(),
        dir.display()
    );
    println!(
        "swept {total} cells; wrote sweep.csv, summary.md, {} and curves.png (each chart with its SVG) to {}",
        plan.grid
            .iter()
            .map(|a| figures::final_file(&a.key))
            .collect::<Vec<_>>()
            .join(", "),
        dir.display()
    );
    Ok(())
}

/// The cells a local sweep runs, shared by its workers: each takes the next pending
/// cell until none is left or the run is stopped.
struct LocalCells<'a, J: Jobs> {
    plan: &'a Plan,
    dir: &'a Path,
    tool: &'a Generators<J>,
    gpu: Option<&'a GpuContext>,
    pending: Vec<u64>,
    threads: usize,
    stop: Arc<AtomicBool>,
    /// Index into `pending` of the next cell to take.
    next: AtomicUsize,
    done: Mutex<BTreeMap<u64, Finished>>,
}

impl<J: Jobs> LocalCells<'_, J>
where
    for<'a> J::Job<'a>: From<CellRun<'a>>,
{
    /// Runs the cells on `jobs` workers; returns every finished cell, those found done
    /// included. A failing worker stops the others: their running cells are interrupted.
    fn run(self, jobs: usize) -> anyhow::Result<BTreeMap<u64, Finished>> {
        let outcomes: Vec<anyhow::Result<()>> = std::thread::scope(|scope| {
            let handles: Vec<_> = (0..jobs)
                .map(|_| {
                    scope.spawn(|| {
                        self.worker()
                            .inspect_err(|_| self.stop.store(true, Ordering::SeqCst))
                    })
                })
                .collect();
            handles
                .into_iter()
                .map(|h| {
                    h.join()
                        .unwrap_or_else(|_| Err(anyhow::anyhow!("a cell panicked")))
                })
                .collect()
        });
        outcomes.into_iter().collect::<anyhow::Result<()>>()?;
        Ok(self.done.into_inner().expect("the workers have ended"))
    }

    /// One worker: runs cells in its own thread pool until none is left or the run is
    /// stopped, rewriting the tables after each.
    fn worker(&self) -> anyhow::Result<()> {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(self.threads)
            .build()
            .context("could not start the worker threads")?;
        while !self.stop.load(Ordering::SeqCst) {
            let Some(&index) = self.pending.get(self.next.fetch_add(1, Ordering::SeqCst)) else {
                break;
            };
            let (plan, dir) = (self.plan, self.dir);
            let finished =
                pool.install(|| cell::run(plan, dir, index, self.tool, self.gpu, &self.stop));
            let finished = match finished {
                Ok(Some(finished)) => finished,
                Ok(None) => break,
                Err(err) => return Err(err.context(format!("cell {index}"))),
            };
            let mut done = self
                .done
                .lock()
                .expect("no cell panicked while holding the results");
            let cell = plan.cell(index);
            eprintln!(
                "cell {index} ({}, run {}, seed {}): {}  [{}/{}]",
                plan.describe(cell.point),
                cell.run,
                cell.seed,
                outcome(&finished),
                done.len() + 1,
                plan.cells()
            );
            done.insert(index, finished);
            write_outputs(plan, dir, &done)?;
        }
        Ok(())
    }
}
