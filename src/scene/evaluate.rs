//! A scene's scorers for one grammar ([`SceneScorer::new`]) and the backend that counts
//! them: whole populations counted at once, on the CPU or the GPU, and their counts
//! turned into fitness. The kinds of scorer are listed in `scorer.rs`.

use shapegen_runtime::gpu::{GpuContext, GpuError, wgpu};
use shapegen_runtime::optimize::{Bred, EvaluateError, Evaluator, Held};
use shapegen_runtime::score::InstanceBatch;
use shapegen_runtime::score::retained::{Retention, RetentionStats};
use shapegen_runtime::score::silhouette::GpuRetention;
use shapegen_runtime::{Genome, Grammar};

use super::error::{BackendError, SceneError};
use super::loaded::Scene;
use super::scorer::{AnyCounts, AnyGpuScorer, AnyScorer, SceneCounts, SceneScorer};

/// Which backend counts: the CPU path always exists; the GPU path needs an adapter.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BackendChoice {
    /// The GPU when a hardware adapter is found and supports the scene, else the CPU.
    #[default]
    Auto,
    /// The CPU, on all worker threads.
    Cpu,
    /// The GPU, any adapter (a software one too); an error when there is none or the
    /// scene cannot run on it.
    Gpu,
}

impl SceneScorer {
    /// The scene's scorers for grammar `G`, which must be the scene's generator.
    ///
    /// # Errors
    /// [`SceneError::Value`] when the scene's meshes lack one the grammar uses or a
    /// target cannot be used, [`SceneError::Invalid`] when the scene's goal is
    /// [`objectives`](Scene::objectives).
    pub fn new<G: Grammar>(scene: &Scene) -> Result<SceneScorer, SceneError> {
        if scene.objectives.is_some() {
            return Err(scene.invalid(
                "objective",
                "the scene's goal is several objectives, which have no single fitness: \
                 search it with the multi-objective GA (`shapegen run` does) and measure \
                 it with an ObjectiveEvaluator"
                    .into(),
            ));
        }
        let meshes = scene
            .meshes
            .bind(G::GRAPH)
            .map_err(|err| scene.refused("meshes", err))?;
        let scorers = scene
            .scorers
            .iter()
            .map(|goal| {
                goal.scorer(&meshes)
                    .map_err(|cause| scene.refused(goal.kind().name(), cause))
            })
            .collect::<Result<_, _>>()?;
        Ok(SceneScorer {
            scorers,
            length: scene.length,
            site: scene.site.clone(),
        })
    }

    /// The backend `choice` asks for. `gpu` is the device, opened by the caller (`None`
    /// when there is none: [`BackendChoice::Auto`] then counts on the CPU). `Auto` passes
    /// over software adapters, which are slower than the CPU path.
    ///
    /// # Errors
    /// [`SceneError::Backend`] for [`BackendChoice::Gpu`]: [`BackendError::NoAdapter`]
    /// without a device, [`BackendError::Gpu`] when the scene cannot run on it.
    pub fn on<'a>(
        &'a self,
        choice: BackendChoice,
        gpu: Option<&'a GpuContext>,
    ) -> Result<Backend<'a>, SceneError> {
        let cpu = |why: &str| Backend {
            scorer: self,
            gpu: Vec::new(),
            description: format!("CPU{why}"),
        };
        let context = match (choice, gpu) {
            (BackendChoice::Cpu, _) => return Ok(cpu("")),
            (BackendChoice::Gpu, None) => return Err(BackendError::NoAdapter.into()),
            (BackendChoice::Auto, None) => return Ok(cpu(" (no GPU adapter)")),
            (BackendChoice::Auto, Some(context))
                if context.info.device_type == wgpu::DeviceType::Cpu =>
            {
                return Ok(cpu(&format!(" (passed over {})", context.describe())));
            }
            (_, Some(context)) => context,
        };
        let paths: Result<Vec<_>, _> = self.scorers.iter().map(|s| s.gpu(context)).collect();
        // A kind without a GPU path counts on the CPU beside the others.
        match paths {
            Ok(gpu) => Ok(Backend {
                scorer: self,
                gpu,
                description: format!("GPU: {}", context.describe()),
            }),
            Err(err) if choice == BackendChoice::Gpu => Err(BackendError::Gpu(err).into()),
            Err(err) => Ok(cpu(&format!(" ({err})"))),
        }
    }
}

/// A scene's scorers on the backend that counts them.
pub struct Backend<'a> {
    scorer: &'a SceneScorer,
    /// Each scorer's GPU path, in the scorers' order (`None` for a kind that has none);
    /// empty on the CPU.
    gpu: Vec<Option<AnyGpuScorer<'a>>>,
    description: String,
}

impl Backend<'_> {
    /// The backend in words: `CPU (no GPU adapter)`, `GPU: NVIDIA H200
    /// (vulkan, discrete GPU)`, ...
    pub fn describe(&self) -> &str {
        &self.description
    }

    /// The scorers.
    pub fn scorer(&self) -> &SceneScorer {
        self.scorer
    }

    /// Checks, before a run allocates its populations, that the GPU can count `models`
    /// models at once, the most a batch of the run holds; `setting` names what sets their
    /// number, as `key = value`. Always passes on the CPU.
    ///
    /// # Errors
    /// [`SceneError::Backend`] with [`BackendError::Batch`]: the setting, the number and
    /// the device's bound.
    pub fn check_batch(&self, models: u64, setting: &str) -> Result<(), SceneError> {
        let max = self.gpu.iter().flatten().map(AnyGpuScorer::max_batch).min();
        match max {
            Some(max) if models > max as u64 => Err(BackendError::Batch {
                setting: setting.to_owned(),
                models,
                max,
                backend: self.description.clone(),
            }
            .into()),
            _ => Ok(()),
        }
    }

    /// Checks [`check_batch`](Self::check_batch) for each batch a method holds at once
    /// ([`Optimizer::genomes_held`](shapegen_runtime::optimize::Optimizer::genomes_held)):
    /// the models a checkpoint saves of it, named by the setting that sets them.
    pub fn check_held(&self, held: &[Held]) -> Result<(), SceneError> {
        for h in held {
            self.check_batch(h.saved, &format!("{} = {}", h.setting, h.value))?;
        }
        Ok(())
    }

    /// Counts every model of `batch` into `out`, resized to the batch.
    ///
    /// # Errors
    /// When the GPU fails while counting.
    pub fn count(&self, batch: &InstanceBatch, out: &mut Vec<SceneCounts>) -> Result<(), GpuError> {
        out.resize_with(batch.len(), SceneCounts::default);
        for slot in out.iter_mut() {
            slot.parts.clear();
        }
        for (i, scorer) in self.scorer.scorers.iter().enumerate() {
            scorer.count(self.gpu.get(i).and_then(Option::as_ref), batch, out)?;
        }
        Ok(())
    }

    /// The GPU path that keeps the models it counts on the device, for their bred
    /// children ([`AnyGpuScorer::retention`]): its index among the scorers, and what it
    /// keeps. The first such path, when counting on the GPU.
    fn gpu_retention(&self) -> Option<(usize, GpuRetention)> {
        self.gpu.iter().enumerate().find_map(|(i, gpu)| {
            let retention = gpu.as_ref()?.retention()?;
            Some((i, retention))
        })
    }

    /// Counts the bred `children` (the models of `batch`) into `out` as
    /// [`count`](Self::count) does, but the counts of scorer `kept` from what
    /// `retention` kept of their `parents` (child `i` bred from `parents[from[i]]`).
    fn count_bred<G: Grammar>(
        &self,
        (kept, retention): (usize, &mut GpuRetention),
        bred: Bred<'_, G>,
        batch: &InstanceBatch,
        out: &mut Vec<SceneCounts>,
    ) -> Result<(), GpuError> {
        out.resize_with(batch.len(), SceneCounts::default);
        for slot in out.iter_mut() {
            slot.parts.clear();
        }
        for (i, scorer) in self.scorer.scorers.iter().enumerate() {
            match self.gpu.get(i).and_then(Option::as_ref) {
                Some(gpu) if i == kept => gpu.count_bred(retention, bred, batch, out)?,
                gpu => scorer.count(gpu, batch, out)?,
            }
        }
        Ok(())
    }
}

/// Scores populations for an optimizer with a scene's scorers on a backend: derives
/// every genome into one reused batch, counts it, and subtracts the length term.
///
/// Children bred from a scored population ([`evaluate_bred`](Evaluator::evaluate_bred))
/// are counted incrementally, from what was kept of their parents, with exactly the
/// counts of counting them from nothing: on the CPU every scorer's ([`Retention`]), on
/// the GPU that of the first kind whose GPU path keeps them on the device (the
/// silhouette scorer's slots of per-pixel counts, [`GpuRetention`]; the others count
/// every model from nothing).
/// [`with_incremental(false)`](Self::with_incremental) counts every child from nothing.
pub struct SceneEvaluator<'a> {
    backend: &'a Backend<'a>,
    batch: InstanceBatch,
    counts: Vec<SceneCounts>,
    retention: Option<Retention<AnyScorer>>,
    gpu_retention: Option<(usize, GpuRetention)>,
    parts: Vec<AnyCounts>,
}

impl<'a> SceneEvaluator<'a> {
    /// An evaluator counting on `backend`, incrementally where it can.
    pub fn new(backend: &'a Backend<'a>) -> Self {
        SceneEvaluator {
            backend,
            batch: InstanceBatch::new().on_site(backend.scorer().site().clone()),
            counts: Vec::new(),
            retention: None,
            gpu_retention: None,
            parts: Vec::new(),
        }
        .with_incremental(true)
    }

    /// Whether bred children are counted from their parents' kept state (the default).
    /// On the GPU, a scene without a kind whose GPU path keeps models (the silhouette
    /// scorer), or whose one model's per-pixel counts exceed the device's largest
    /// binding, counts every child from nothing.
    pub fn with_incremental(mut self, incremental: bool) -> Self {
        let gpu = !self.backend.gpu.is_empty();
        self.retention = (incremental && !gpu).then(Retention::new);
        self.gpu_retention = if incremental {
            self.backend.gpu_retention()
        } else {
            None
        };
        self
    }

    /// Whether bred children are counted incrementally.
    pub fn incremental(&self) -> bool {
        self.retention.is_some() || self.gpu_retention.is_some()
    }

    /// How the bred children were counted so far, and the bytes of state kept now (on
    /// the GPU, the device memory of the slots); `None` when not counting
    /// incrementally.
    pub fn retention(&self) -> Option<(RetentionStats, usize)> {
        if let Some((_, gpu)) = &self.gpu_retention {
            let bytes = usize::try_from(gpu.memory()).unwrap_or(usize::MAX);
            return Some((gpu.stats(), bytes));
        }
        let retention = self.retention.as_ref()?;
        Some((
            retention.stats(),
            retention.memory(self.backend.scorer.scorers()),
        ))
    }

    /// Writes the fitness of each of `genomes` from its counts.
    fn write_fitness<G: Grammar>(&self, genomes: &[Genome<G>], out: &mut [f64]) {
        let scorer = self.backend.scorer();
        for ((slot, counts), genome) in out.iter_mut().zip(&self.counts).zip(genomes) {
            *slot = scorer.fitness(counts, genome.len());
        }
    }
}

impl<G: Grammar> Evaluator<G> for SceneEvaluator<'_> {
    fn evaluate(&mut self, genomes: &[Genome<G>], out: &mut [f64]) -> Result<(), EvaluateError> {
        self.batch.set_genomes(genomes);
        self.backend
            .count(&self.batch, &mut self.counts)
            .map_err(|err| EvaluateError(err.to_string()))?;
        self.write_fitness(genomes, out);
        Ok(())
    }

    fn evaluate_bred(&mut self, bred: Bred<'_, G>, out: &mut [f64]) -> Result<(), EvaluateError> {
        let genomes = bred.children;
        if let Some((kept, retention)) = &mut self.gpu_retention {
            self.batch.set_genomes(genomes);
            let (batch, counts) = (&self.batch, &mut self.counts);
            self.backend
                .count_bred((*kept, retention), bred, batch, counts)
                .map_err(|err| EvaluateError(err.to_string()))?;
            self.write_fitness(genomes, out);
            return Ok(());
        }
        if self.retention.is_none() {
            return self.evaluate(genomes, out);
        }
        self.batch.set_genomes(genomes);
        let scorer = self.backend.scorer();
        let scorers = scorer.scorers();
        let k = scorers.len();
        self.parts.clear();
        for _ in genomes {
            self.parts.extend(scorers.iter().map(AnyScorer::nothing));
        }
        let retention = self.retention.as_mut().expect("checked above");
        retention.count_bred(scorers, bred, &self.batch, &mut self.parts);
        for (i, (slot, genome)) in out.iter_mut().zip(genomes).enumerate() {
            *slot = scorer.fitness_of_parts(&self.parts[i * k..(i + 1) * k], genome.len());
        }
        Ok(())
    }
}
