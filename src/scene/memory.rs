//! How much memory a search of a scene takes, estimated before anything is allocated, so
//! that a run too large for the machine is refused at once, naming the setting that
//! makes it so, rather than growing until the kernel kills it ([`MemoryEstimate`]).

use std::mem::size_of;

use shapegen_runtime::graph::{GeneratorGraph, NodeDesc};
use shapegen_runtime::optimize::multi::{Front, MultiGaSettings};
use shapegen_runtime::optimize::{Best, Held, Optimizer};
use shapegen_runtime::score::retained::DEFAULT_MAX_BYTES;
use shapegen_runtime::{Grammar, Instance};

use super::loaded::Scene;
use super::method::{MethodJob, SearchJob};
use super::optimizer::OptimizerGoal;

/// Bytes of checkpoint text per genome word, about: a tree-sketch genome of 380 genes
/// of 11 words takes 64 KiB of JSON, some 15 bytes a word.
pub const JSON_BYTES_PER_WORD: u64 = 16;

/// What a run is, besides its scene, for its memory: its grammar, the genomes its
/// method holds, its worker threads, whether children are counted incrementally and
/// whether it may count on a GPU ([`Scene::run_shape`] makes one).
#[derive(Clone, Debug)]
pub struct RunShape {
    /// The grammar searched.
    pub graph: &'static GeneratorGraph,
    /// The genomes the method holds ([`Optimizer::genomes_held`](
    /// shapegen_runtime::optimize::Optimizer::genomes_held)).
    pub held: Vec<Held>,
    /// The most genes a genome may have: the scene's `limits.max_len`, or a resumed
    /// checkpoint's own.
    pub max_len: u32,
    /// The worker threads scoring models.
    pub threads: usize,
    /// Whether bred children are counted from their parents' kept state.
    pub incremental: bool,
    /// Whether models may be counted on a GPU.
    pub gpu: bool,
}

/// One part of an estimate.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MemoryPart {
    /// What takes the memory.
    pub what: String,
    /// The setting that makes it so, as `key = value`.
    pub setting: String,
    /// Bytes.
    pub bytes: u64,
}

/// A run's memory, estimated by part ([`Scene::memory_estimate`]).
///
/// The estimate is an upper bound of what grows with the settings: every genome at the
/// run's `limits.max_len` genes ([`RunShape::max_len`]) of the grammar's largest gene; the checkpoint's text
/// (about [`JSON_BYTES_PER_WORD`] per genome word); the instances of a whole population
/// derived for scoring (one per gene); the scorers' grids and images, and their scratch
/// buffers per worker thread; and, when children are counted incrementally, the state
/// kept of the models, up to its bound
/// ([`DEFAULT_MAX_BYTES`](shapegen_runtime::score::retained::DEFAULT_MAX_BYTES)).
/// On a GPU, the instances of a batch are copied once more, sorted for the upload; the
/// device's own memory is bounded by its bindings, which the scorers check. Fixed costs
/// (the program, meshes, the GPU driver) are not in the estimate.
///
/// ```
/// use generators::Spaceship;
/// use shapegen::scene::{Overrides, Scene};
/// use shapegen::registry::Registry;
///
/// let sets = vec!["optimizer.population=100000000".to_owned()];
/// let overrides = Overrides { sets, ..Overrides::default() };
/// let scene = Scene::open("scenes/paper/spaceship_volume.toml", &Registry::published(), &overrides)?;
/// let shape = scene.run_shape::<Spaceship>(&scene.optimizer, 2, true, false);
/// let estimate = scene.memory_estimate(&shape);
/// assert!(estimate.total() > 100 << 30);
/// let refused = estimate.check(16 << 30, "that --max-memory allows").unwrap_err();
/// assert_eq!((refused.estimate.total(), refused.limit), (estimate.total(), 16 << 30));
/// let message = refused.to_string();
/// assert!(message.contains("optimizer.population = 100000000"), "{message}");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct MemoryEstimate {
    parts: Vec<MemoryPart>,
}

impl MemoryEstimate {
    /// The parts, largest first.
    pub fn parts(&self) -> &[MemoryPart] {
        &self.parts
    }

    /// All the parts together.
    pub fn total(&self) -> u64 {
        self.parts
            .iter()
            .fold(0u64, |sum, p| sum.saturating_add(p.bytes))
    }

    /// `jobs` runs of this estimate at once (a sweep's cells side by side).
    pub fn times(mut self, jobs: usize) -> MemoryEstimate {
        if jobs == 1 {
            return self;
        }
        for part in &mut self.parts {
            part.bytes = part.bytes.saturating_mul(jobs as u64);
            part.what = format!("{jobs} x {}", part.what);
        }
        self
    }

    /// Checks the estimate against `limit` bytes; `limit_from` says where the limit comes
    /// from, following its size: "that --max-memory allows", "available".
    ///
    /// # Errors
    /// [`MemoryError`] when the estimate is over the limit.
    pub fn check(&self, limit: u64, limit_from: &str) -> Result<(), MemoryError> {
        if self.total() <= limit {
            return Ok(());
        }
        Err(MemoryError {
            estimate: self.clone(),
            limit,
            limit_from: limit_from.to_owned(),
        })
    }

    /// The largest parts, at most four, in words, with their sizes and settings.
    fn largest_parts(&self) -> String {
        let parts: Vec<String> = self
            .parts
            .iter()
            .filter(|p| p.bytes > 0)
            .take(4)
            .map(|p| format!("{} {} ({})", bytes(p.bytes), p.what, p.setting))
            .collect();
        parts.join("; ")
    }

    /// The setting of the largest part; empty for an estimate of no parts.
    fn largest_setting(&self) -> &str {
        self.parts.first().map_or("", |p| &p.setting)
    }
}

/// A run whose estimated memory is over the limit: the estimate, its largest parts and
/// the setting of the largest.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "this run would take about {} of memory, more than the {} {limit_from}: {}. The largest \
     part comes from {}: change it, or give --max-memory SIZE to allow more",
    bytes(estimate.total()),
    bytes(*limit),
    estimate.largest_parts(),
    estimate.largest_setting()
)]
pub struct MemoryError {
    /// The estimate.
    pub estimate: MemoryEstimate,
    /// The limit, in bytes.
    pub limit: u64,
    /// Where the limit comes from, following its size: "that --max-memory allows",
    /// "available (MemAvailable in /proc/meminfo)".
    pub limit_from: String,
}

/// `n` bytes in words: `512 B`, `3.4 MiB`, `1.2 GiB`, ...
fn bytes(n: u64) -> String {
    const UNITS: [&str; 6] = ["B", "KiB", "MiB", "GiB", "TiB", "PiB"];
    let mut value = n as f64;
    let mut unit = 0;
    while value >= 1024.0 && unit + 1 < UNITS.len() {
        value /= 1024.0;
        unit += 1;
    }
    if unit == 0 {
        format!("{n} B")
    } else {
        format!("{value:.1} {}", UNITS[unit])
    }
}

impl Scene {
    /// The genomes a run of `goal` on this scene holds, of grammar `G` (the scene's
    /// generator): those of `goal`'s method, or the multi-objective GA's for a scene
    /// with objectives ([`Optimizer::genomes_held`]).
    pub fn genomes_held<G: Grammar>(&self, goal: &OptimizerGoal) -> Vec<Held> {
        /// Asks the optimizer.
        struct Genomes;
        impl<G: Grammar> MethodJob<G> for Genomes {
            type Output = Vec<Held>;
            fn run<O: Optimizer<G, Record = Best<G>>>(self, settings: O::Settings) -> Self::Output {
                O::genomes_held(&settings)
            }
        }
        impl<G: Grammar> SearchJob<G> for Genomes {
            fn run_front<O>(self, settings: MultiGaSettings) -> Self::Output
            where
                O: Optimizer<G, Record = Front<G>, Settings = MultiGaSettings>,
            {
                O::genomes_held(&settings)
            }
        }
        self.search::<G, _>(goal, Genomes)
    }

    /// The shape of a run of `goal` on this scene, of grammar `G` (the scene's generator),
    /// on `threads` worker threads ([`genomes_held`](Self::genomes_held)).
    pub fn run_shape<G: Grammar>(
        &self,
        goal: &OptimizerGoal,
        threads: usize,
        incremental: bool,
        gpu: bool,
    ) -> RunShape {
        RunShape {
            graph: G::GRAPH,
            held: self.genomes_held::<G>(goal),
            max_len: self.limits.max_len,
            threads,
            incremental,
            gpu,
        }
    }

    /// The estimated memory of a run of this scene shaped as `shape` (see the
    /// [`MemoryEstimate`]).
    pub fn memory_estimate(&self, shape: &RunShape) -> MemoryEstimate {
        let (mut parts, saved) = genome_parts(shape);
        // The cells a scorer or a projection objective counts over: voxels, pixels.
        let mut cells = 0u64;
        for (what, setting, n) in self.counted_cells() {
            cells = cells.saturating_add(n);
            // A byte per cell and bit planes for the targets' weights; per thread, a bit
            // per cell covered and another covered twice, and the words touched.
            parts.push(MemoryPart {
                what: format!("for the scorer of {n} {what}"),
                setting: setting.clone(),
                bytes: n.saturating_mul(2),
            });
            parts.push(MemoryPart {
                what: format!("for {} threads' scratch over {n} {what}", shape.threads),
                setting: format!("{setting}, --threads {}", shape.threads),
                bytes: (n / 2).saturating_mul(shape.threads as u64),
            });
        }
        for goal in self.scorers() {
            let other = goal.memory(shape.threads).other;
            parts.extend(other.into_iter().map(|(what, setting, bytes)| MemoryPart {
                what,
                setting,
                bytes,
            }));
        }
        if shape.incremental && cells > 0 {
            // 16-bit counts of every cell for each model kept, up to the bound.
            let models = 2 * saved;
            parts.push(MemoryPart {
                what: format!("for the incremental state of {models} models"),
                setting: "incremental counting (--no-incremental turns it off)".to_owned(),
                bytes: models
                    .saturating_mul(cells * 2)
                    .min(DEFAULT_MAX_BYTES as u64),
            });
        }
        parts.sort_by_key(|p| std::cmp::Reverse(p.bytes));
        MemoryEstimate { parts }
    }

    /// The cells each scorer or projection objective counts over: what they are, the
    /// setting that sizes them, how many.
    fn counted_cells(&self) -> Vec<(&'static str, String, u64)> {
        let mut cells: Vec<_> = self
            .scorers()
            .iter()
            .filter_map(|goal| goal.memory(1).cells)
            .collect();
        let objectives = self.objectives.iter().flat_map(|o| o.set.entries());
        for (i, (_, objective)) in objectives.enumerate() {
            if let Some(p) = objective.projection() {
                let n = u64::from(p.width()) * u64::from(p.height());
                cells.push(("pixels", format!("objective[{i}].image size"), n));
            }
        }
        cells
    }
}

/// The memory of the genomes a run of `shape` holds, saves and derives at once, and how
/// many it scores at once.
fn genome_parts(shape: &RunShape) -> (Vec<MemoryPart>, u64) {
    let max_len = u64::from(shape.max_len);
    let gene_words = shape
        .graph
        .nodes
        .iter()
        .map(NodeDesc::gene_words)
        .max()
        .map_or(0, u64::from);
    let genome_words = max_len * gene_words;
    let genome_bytes = genome_words * 4 + size_of::<Vec<u32>>() as u64 + 8;
    let mut parts = Vec::new();
    let mut saved = 0u64;
    for held in &shape.held {
        let setting = format!("{} = {}", held.setting, held.value);
        parts.push(MemoryPart {
            what: format!(
                "for {} genomes of up to {max_len} genes of {gene_words} words",
                held.genomes
            ),
            setting: setting.clone(),
            bytes: held.genomes.saturating_mul(genome_bytes),
        });
        parts.push(MemoryPart {
            what: format!("for the checkpoint of {} genomes", held.saved),
            setting: setting.clone(),
            bytes: held
                .saved
                .saturating_mul(genome_words * JSON_BYTES_PER_WORD),
        });
        // Derived for scoring, and on a GPU copied once more, sorted for the upload.
        let copies = if shape.gpu { 2 } else { 1 };
        parts.push(MemoryPart {
            what: format!("for the instances of {} models scored at once", held.saved),
            setting,
            bytes: held
                .saved
                .saturating_mul(copies * max_len * size_of::<Instance>() as u64),
        });
        saved = saved.saturating_add(held.saved);
    }
    (parts, saved)
}

#[cfg(test)]
mod tests {
    use std::mem::size_of;

    use generators::{Building, Spaceship};
    use shapegen_runtime::Grammar;
    use shapegen_runtime::graph::NodeDesc;
    use shapegen_runtime::score::retained::DEFAULT_MAX_BYTES;

    use super::{MemoryEstimate, bytes};
    use crate::registry::Registry;
    use crate::scene::loaded::Scene;
    use crate::scene::optimizer::Overrides;

    /// `path` with `--set`s.
    fn scene(path: &str, sets: &[&str]) -> Scene {
        let overrides = Overrides {
            sets: sets.iter().map(|s| s.to_string()).collect(),
            ..Overrides::default()
        };
        Scene::open(path, &Registry::published(), &overrides).unwrap()
    }

    /// The spaceship's volume scene, with a GA of `population`, on `threads` threads.
    fn spaceship(population: u32, threads: usize, incremental: bool) -> (Scene, MemoryEstimate) {
        let scene = scene(
            "scenes/paper/spaceship_volume.toml",
            &[&format!("optimizer.population={population}")],
        );
        let shape = scene.run_shape::<Spaceship>(&scene.optimizer, threads, incremental, false);
        let estimate = scene.memory_estimate(&shape);
        (scene, estimate)
    }

    /// The bytes of the part whose description starts with `what`.
    fn part(estimate: &MemoryEstimate, what: &str) -> u64 {
        let found = estimate.parts().iter().find(|p| p.what.starts_with(what));
        found
            .unwrap_or_else(|| panic!("no part `{what}` in {estimate:?}"))
            .bytes
    }

    #[test]
    fn genomes_count_the_population_three_times_at_the_longest_genome() {
        let (scene, estimate) = spaceship(100, 1, false);
        let max_len = u64::from(scene.limits.max_len);
        let gene_words = Spaceship::GRAPH
            .nodes
            .iter()
            .map(NodeDesc::gene_words)
            .max()
            .unwrap();
        let genome = max_len * u64::from(gene_words) * 4 + size_of::<Vec<u32>>() as u64 + 8;
        assert_eq!(part(&estimate, "for 300 genomes"), 300 * genome);
        let (_, doubled) = spaceship(200, 1, false);
        assert_eq!(part(&doubled, "for 600 genomes"), 600 * genome);
        assert_eq!(
            part(&doubled, "for the checkpoint of 200 genomes"),
            2 * part(&estimate, "for the checkpoint of 100 genomes")
        );
    }

    #[test]
    fn scratch_grows_with_the_threads_and_the_grid() {
        let (_, one) = spaceship(100, 1, false);
        let (_, four) = spaceship(100, 4, false);
        let scratch = |e: &MemoryEstimate, t: usize| part(e, &format!("for {t} threads' scratch"));
        assert_eq!(scratch(&four, 4), 4 * scratch(&one, 1));
        let scene = scene("scenes/paper/spaceship_volume.toml", &[]);
        let volume = scene.scorers()[0].volume();
        let r = volume
            .expect("the spaceship's scene has a volume")
            .grid
            .resolution();
        let voxels: u64 = r.iter().map(|&x| u64::from(x)).product();
        assert_eq!(part(&one, "for the scorer of"), 2 * voxels);
    }

    #[test]
    fn incremental_state_only_when_counted_so_and_within_its_bound() {
        let (_, full) = spaceship(100, 1, false);
        assert!(
            !full.parts().iter().any(|p| p.what.contains("incremental")),
            "{full:?}"
        );
        let (_, small) = spaceship(100, 1, true);
        // Twice what a checkpoint saves: the population of 100 and the polished best
        // (the scene runs the hybrid, which polishes by default).
        assert!(part(&small, "for the incremental state of 202 models") > 0);
        let (_, huge) = spaceship(1_000_000, 1, true);
        assert_eq!(
            part(&huge, "for the incremental state"),
            DEFAULT_MAX_BYTES as u64
        );
    }

    #[test]
    fn islands_hold_every_island_and_objectives_their_archive_and_images() {
        let (_, one) = spaceship(100, 1, false);
        let islands = scene(
            "scenes/paper/spaceship_volume.toml",
            &["optimizer.population=100", "islands.count=4"],
        );
        let shape = islands.run_shape::<Spaceship>(&islands.optimizer, 1, false, false);
        let four = islands.memory_estimate(&shape);
        assert_eq!(
            part(&four, "for 1200 genomes"),
            4 * part(&one, "for 300 genomes")
        );

        let building = scene(
            "scenes/building.toml",
            &["optimizer.population=50", "optimizer.archive=70"],
        );
        let shape = building.run_shape::<Building>(&building.optimizer, 1, true, false);
        let estimate = building.memory_estimate(&shape);
        let archive = estimate
            .parts()
            .iter()
            .find(|p| p.setting == "optimizer.archive = 70" && p.what.contains("genomes of"))
            .expect("the archive is a part");
        assert!(archive.what.contains("140 genomes"), "{archive:?}");
        let images: Vec<_> = estimate
            .parts()
            .iter()
            .filter(|p| p.what.starts_with("for the scorer of"))
            .collect();
        assert_eq!(images.len(), 2, "the top and front images: {estimate:?}");
        assert!(part(&estimate, "for the incremental state of 240 models") > 0);
    }

    #[test]
    fn a_gpu_copies_the_instances_once_more() {
        let scene = scene("scenes/paper/spaceship_volume.toml", &[]);
        let cpu = scene.run_shape::<Spaceship>(&scene.optimizer, 1, false, false);
        let gpu = scene.run_shape::<Spaceship>(&scene.optimizer, 1, false, true);
        let instances = |e: MemoryEstimate| part(&e, "for the instances");
        assert_eq!(
            instances(scene.memory_estimate(&gpu)),
            2 * instances(scene.memory_estimate(&cpu))
        );
    }

    #[test]
    fn side_by_side_runs_multiply_every_part() {
        let (_, one) = spaceship(100, 1, true);
        let three = one.clone().times(3);
        assert_eq!(three.total(), 3 * one.total());
        assert!(three.parts()[0].what.starts_with("3 x "));
        assert_eq!(one.clone().times(1), one);
    }

    #[test]
    fn a_check_over_the_limit_names_the_largest_parts_setting() {
        let (_, estimate) = spaceship(100_000, 2, true);
        let total = estimate.total();
        assert_eq!(estimate.check(total, "available"), Ok(()));
        let err = estimate
            .check(total - 1, "available")
            .unwrap_err()
            .to_string();
        assert!(err.contains(&bytes(total)), "{err}");
        assert!(
            err.contains("comes from optimizer.population = 100000"),
            "{err}"
        );
        assert!(err.contains("--max-memory SIZE"), "{err}");
    }

    #[test]
    fn sizes_read_in_binary_units() {
        assert_eq!(bytes(512), "512 B");
        assert_eq!(bytes(1536), "1.5 KiB");
        assert_eq!(bytes(3 << 30), "3.0 GiB");
    }
}
