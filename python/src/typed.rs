//! One generator's grammar behind an interface without type parameters: what the Python
//! objects ask of a generator (search a scene, score, sample, read genomes, make models),
//! with genomes passed as their packed JSON.

use std::marker::PhantomData;
use std::sync::atomic::AtomicBool;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use shapegen::export::Palette;
use shapegen::gpu::GpuContext;
use shapegen::optimize::multi::{MultiHistoryEntry, MultiSnapshot};
use shapegen::optimize::{Control, HistoryEntry, RunResult, Snapshot};
use shapegen::scene::{BackendChoice, Metrics, Scene, SceneScorer};
use shapegen::score::InstanceBatch;
use shapegen::search::{
    Compare, CompareObserver, Comparison, FrontSearch, MethodSummary, SaveHook, Search,
};
use shapegen::{Genome, Grammar, Limits, MeshLibrary, Operators, Site};

use crate::error::Error;

/// A genome as it crosses the interface: its packed JSON and its length in genes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GenomeText {
    /// The packed form (`Genome::to_json`).
    pub json: String,
    /// Its genes.
    pub genes: usize,
}

impl GenomeText {
    fn of<G: Grammar>(genome: &Genome<G>) -> GenomeText {
        GenomeText {
            json: genome.to_json(),
            genes: genome.len(),
        }
    }
}

/// Where and how a search or a scoring counts.
#[derive(Clone, Copy)]
pub struct Counting<'a> {
    /// The backend asked for.
    pub choice: BackendChoice,
    /// The GPU, where one was opened.
    pub gpu: Option<&'a GpuContext>,
}

/// A generation of a run, as the progress callback sees it.
#[derive(Clone, Debug)]
pub struct Step {
    /// Generations done after the initial population.
    pub generation: u64,
    /// Wall time in seconds.
    pub elapsed_s: f64,
    /// Evaluations done.
    pub evaluations: u64,
    /// The best fitness so far.
    pub best_fitness: f64,
    /// The population's mean fitness.
    pub mean: f64,
    /// The best genome so far, when it changed since the last step (always at the first).
    pub best: Option<GenomeText>,
}

/// What a search found.
#[derive(Clone, Debug)]
pub struct Outcome {
    /// The best genome.
    pub best: GenomeText,
    /// Its fitness.
    pub best_fitness: f64,
    /// Evaluations done.
    pub evaluations: u64,
    /// Generations done after the initial population.
    pub generations: u64,
    /// One entry per generation.
    pub history: Vec<HistoryEntry>,
    /// Why it ended: `generations`, `evaluations`, `time` or `interrupted`.
    pub stopped: &'static str,
    /// The backend that counted.
    pub backend: String,
}

impl Outcome {
    fn of<G: Grammar>(result: &RunResult<G>, backend: &str) -> Outcome {
        Outcome {
            best: GenomeText::of(&result.best),
            best_fitness: result.best_fitness,
            evaluations: result.evaluations,
            generations: result.generations,
            history: result.history.clone(),
            stopped: result.stopped.name(),
            backend: backend.to_owned(),
        }
    }
}

/// One finished run of a comparison.
#[derive(Clone, Debug)]
pub struct ComparedText {
    /// Its method's name.
    pub method: &'static str,
    /// Its number among the method's runs, from 0.
    pub run: u64,
    /// Its seed.
    pub seed: u64,
    /// What it found.
    pub outcome: Outcome,
    /// The best model's measures against the scene's targets.
    pub metrics: Metrics,
}

impl ComparedText {
    fn of<G: Grammar>(run: &shapegen::search::ComparedRun<G>, backend: &str) -> ComparedText {
        ComparedText {
            method: run.method.name(),
            run: run.run,
            seed: run.seed,
            outcome: Outcome::of(&run.result, backend),
            metrics: run.metrics.clone(),
        }
    }
}

/// What a comparison did.
#[derive(Clone, Debug)]
pub struct Compared {
    /// The methods' names, in the order they ran.
    pub methods: Vec<&'static str>,
    /// Each run's seed, by run number.
    pub seeds: Vec<u64>,
    /// The wall-time budget of every run.
    pub seconds: Option<f64>,
    /// The backend that counted.
    pub backend: String,
    /// The scene's optimum, when it gives one.
    pub optimum: Option<f64>,
    /// The finished runs, run-major.
    pub runs: Vec<ComparedText>,
    /// Each method's summary, in the order they ran.
    pub summaries: Vec<MethodSummary>,
    /// Whether every planned run finished.
    pub complete: bool,
    /// The run that was interrupted, by its method's name and number.
    pub interrupted: Option<(&'static str, u64)>,
}

/// A generation of a multi-objective search, as the progress callback sees it.
#[derive(Clone, Debug)]
pub struct FrontStep {
    /// Generations done after the initial population.
    pub generation: u64,
    /// Wall time in seconds.
    pub elapsed_s: f64,
    /// Evaluations done.
    pub evaluations: u64,
    /// Members of the front.
    pub front: usize,
    /// Per objective, the best value evaluated so far.
    pub best: Vec<f64>,
}

/// What a multi-objective search found.
#[derive(Clone, Debug)]
pub struct FrontOutcome {
    /// The objectives' names, in the scene's order.
    pub objectives: Vec<String>,
    /// Their kinds, as scene files name them.
    pub kinds: Vec<&'static str>,
    /// Whether each is maximized (`true`) or minimized.
    pub maximized: Vec<bool>,
    /// The selection's ranking, as scene files name it.
    pub ranking: &'static str,
    /// The front's members in the order of the tool's files: genome and values.
    pub members: Vec<(GenomeText, Vec<f64>)>,
    /// Evaluations done.
    pub evaluations: u64,
    /// Generations done after the initial population.
    pub generations: u64,
    /// One entry per generation.
    pub history: Vec<MultiHistoryEntry>,
    /// Why it ended.
    pub stopped: &'static str,
}

/// A model's triangles in world space, each with the part (mesh) it belongs to.
#[derive(Clone, Debug, Default)]
pub struct Triangles {
    /// Vertex positions.
    pub vertices: Vec<[f32; 3]>,
    /// Triangles, counter-clockwise seen from outside.
    pub faces: Vec<[u32; 3]>,
    /// The part of each triangle: an index into `part_names`.
    pub parts: Vec<u32>,
    /// The generator's meshes, by id.
    pub part_names: Vec<String>,
    /// Each part's colour in the exports (linear RGB).
    pub part_colors: Vec<[f32; 3]>,
    /// Mesh instances the model places.
    pub instances: usize,
}

/// What the Python objects ask of one generator.
pub trait Erased: Send + Sync {
    /// Runs `scene`'s search (its generator is this one) to its budget, from the saved
    /// state `resume` if given, saving its state through `save` if given.
    fn search(
        &self,
        scene: &Scene,
        counting: Counting<'_>,
        stop: &AtomicBool,
        observer: &mut dyn FnMut(Step) -> Control,
        resume: Option<&str>,
        save: Option<&mut SaveHook<'_>>,
    ) -> Result<Outcome, Error>;

    /// Runs `compare`'s runs (its scene's generator is this one), calling `finished`
    /// after each.
    fn compare(
        &self,
        compare: &Compare<'_>,
        finished: &mut dyn FnMut(&ComparedText) -> Control,
    ) -> Result<Compared, Error>;

    /// Searches the front of multi-objective `scene` (its generator is this one) to its
    /// budget.
    fn front(
        &self,
        scene: &Scene,
        stop: &AtomicBool,
        observer: &mut dyn FnMut(FrontStep) -> Control,
    ) -> Result<FrontOutcome, Error>;

    /// The fitness of each of `genomes` in `scene`.
    fn score(
        &self,
        scene: &Scene,
        genomes: &[&str],
        counting: Counting<'_>,
    ) -> Result<Vec<f64>, Error>;

    /// `count` random models of the generator's own distribution within `limits`,
    /// model `i` drawn from stream `i` of `seed` (as `shapegen sample` draws them).
    fn sample(&self, limits: Limits, count: u32, seed: u64) -> Result<Vec<GenomeText>, Error>;

    /// Reads a genome of this generator from JSON of either form, checking it.
    fn read(&self, json: &str) -> Result<GenomeText, Error>;

    /// The nested JSON form of a packed genome.
    fn nested(&self, json: &str) -> Result<String, Error>;

    /// The model of a genome, with `meshes`, grown on `site`.
    fn model(&self, meshes: &MeshLibrary, site: &Site, json: &str) -> Result<Triangles, Error>;
}

/// Grammar `G` as an [`Erased`].
pub struct Typed<G>(PhantomData<fn() -> G>);

impl<G> Default for Typed<G> {
    fn default() -> Self {
        Typed(PhantomData)
    }
}

/// Reads a genome of `G`.
fn genome<G: Grammar>(json: &str) -> Result<Genome<G>, Error> {
    Genome::<G>::from_json(json).map_err(Error::genome)
}

impl<G: Grammar> Erased for Typed<G> {
    fn search(
        &self,
        scene: &Scene,
        counting: Counting<'_>,
        stop: &AtomicBool,
        observer: &mut dyn FnMut(Step) -> Control,
        resume: Option<&str>,
        save: Option<&mut SaveHook<'_>>,
    ) -> Result<Outcome, Error> {
        let mut shown = f64::NAN;
        let mut watch = |s: &Snapshot<'_, G>| {
            let changed = shown.to_bits() != s.best_fitness.to_bits();
            shown = s.best_fitness;
            observer(Step {
                generation: s.generation,
                elapsed_s: s.elapsed.as_secs_f64(),
                evaluations: s.evaluations,
                best_fitness: s.best_fitness,
                mean: s.mean,
                best: changed.then(|| GenomeText::of(s.best)),
            })
        };
        let mut search = Search::new(scene)
            .backend(counting.choice, counting.gpu)
            .stop_flag(stop);
        if let Some(state) = resume {
            search = search.resume(state);
        }
        let found = search
            .run_saving::<G>(&mut watch, save)
            .map_err(Error::search)?;
        Ok(Outcome::of(&found.result, &found.backend))
    }

    fn compare(
        &self,
        compare: &Compare<'_>,
        finished: &mut dyn FnMut(&ComparedText) -> Control,
    ) -> Result<Compared, Error> {
        /// Shows each finished run.
        struct Watch<'f>(&'f mut dyn FnMut(&ComparedText) -> Control);
        impl<G: Grammar> CompareObserver<G> for Watch<'_> {
            fn finished(&mut self, so_far: &Comparison<G>) -> Control {
                match so_far.runs.last() {
                    Some(run) => (self.0)(&ComparedText::of(run, &so_far.backend)),
                    None => Control::Continue,
                }
            }
        }
        let done = compare
            .run::<G>(&mut Watch(finished))
            .map_err(Error::search)?;
        Ok(Compared {
            methods: done.methods.iter().map(|m| m.name()).collect(),
            seeds: done.seeds.clone(),
            seconds: done.seconds,
            backend: done.backend.clone(),
            optimum: done.optimum,
            runs: done
                .runs
                .iter()
                .map(|r| ComparedText::of(r, &done.backend))
                .collect(),
            summaries: done.summaries(),
            complete: done.complete(),
            interrupted: done.interrupted.map(|(m, r)| (m.name(), r)),
        })
    }

    fn front(
        &self,
        scene: &Scene,
        stop: &AtomicBool,
        observer: &mut dyn FnMut(FrontStep) -> Control,
    ) -> Result<FrontOutcome, Error> {
        let mut watch = |s: &MultiSnapshot<'_, G>| {
            observer(FrontStep {
                generation: s.generation,
                elapsed_s: s.elapsed.as_secs_f64(),
                evaluations: s.evaluations,
                front: s.front.len(),
                best: s.best.to_vec(),
            })
        };
        let found = FrontSearch::new(scene)
            .stop_flag(stop)
            .run::<G>(&mut watch)
            .map_err(Error::search)?;
        let members = found
            .sorted()
            .into_iter()
            .map(|m| (GenomeText::of(&m.genome), m.values.clone()))
            .collect();
        let result = found.result;
        Ok(FrontOutcome {
            objectives: found.objectives,
            kinds: found.kinds,
            maximized: found
                .senses
                .iter()
                .map(|s| *s == shapegen::optimize::Sense::Maximize)
                .collect(),
            ranking: found.ranking,
            members,
            evaluations: result.evaluations,
            generations: result.generations,
            history: result.history,
            stopped: result.stopped.name(),
        })
    }

    fn score(
        &self,
        scene: &Scene,
        genomes: &[&str],
        counting: Counting<'_>,
    ) -> Result<Vec<f64>, Error> {
        let genomes = genomes
            .iter()
            .map(|json| genome::<G>(json))
            .collect::<Result<Vec<_>, _>>()?;
        let scorer = SceneScorer::new::<G>(scene).map_err(Error::scene)?;
        let backend = scorer
            .on(counting.choice, counting.gpu)
            .map_err(Error::scene)?;
        let mut batch = InstanceBatch::new().on_site(scene.site.clone());
        for genome in &genomes {
            batch.push_genome(genome);
        }
        let mut counts = Vec::new();
        backend.count(&batch, &mut counts).map_err(Error::search)?;
        Ok(genomes
            .iter()
            .zip(&counts)
            .map(|(genome, counts)| scorer.fitness(counts, genome.len()))
            .collect())
    }

    fn sample(&self, limits: Limits, count: u32, seed: u64) -> Result<Vec<GenomeText>, Error> {
        let ops = Operators::<G>::new(limits).map_err(|err| Error::Value(err.to_string()))?;
        Ok((0..count)
            .into_par_iter()
            .map_init(
                || ops.clone(),
                |ops, i| {
                    let mut rng = ChaCha8Rng::seed_from_u64(seed);
                    rng.set_stream(u64::from(i));
                    GenomeText::of(&ops.sample(&mut rng))
                },
            )
            .collect())
    }

    fn read(&self, json: &str) -> Result<GenomeText, Error> {
        genome::<G>(json).map(|g| GenomeText::of(&g))
    }

    fn nested(&self, json: &str) -> Result<String, Error> {
        genome::<G>(json).map(|g| g.to_nested_json())
    }

    fn model(&self, meshes: &MeshLibrary, site: &Site, json: &str) -> Result<Triangles, Error> {
        let genome = genome::<G>(json)?;
        let meshes = meshes.bind(G::GRAPH).map_err(Error::scene)?;
        let mut instances = Vec::new();
        genome.derive_on(site, &mut instances);
        let palette = Palette::new();
        let mut out = Triangles {
            instances: instances.len(),
            ..Triangles::default()
        };
        for (id, name, _) in meshes.iter() {
            out.part_names.push(name.to_owned());
            out.part_colors.push(palette.color(id, name));
        }
        for instance in &instances {
            let Some(mesh) = meshes.get(instance.mesh) else {
                continue;
            };
            let base = out.vertices.len() as u32;
            let flip = instance.transform.matrix3.determinant() < 0.0;
            out.vertices.extend(
                mesh.positions
                    .iter()
                    .map(|&p| instance.transform.transform_point3(p).to_array()),
            );
            for [a, b, c] in mesh.triangles() {
                let (b, c) = if flip { (c, b) } else { (b, c) };
                out.faces.push([base + a, base + b, base + c]);
                out.parts.push(instance.mesh.0);
            }
        }
        Ok(out)
    }
}
