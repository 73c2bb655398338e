//! A scene's scorers for one grammar, and the backend that counts them: whole populations
//! counted at once, on the CPU or the GPU, and their counts turned into fitness.

use serde::Serialize;
use shapegen_runtime::gpu::{GpuContext, GpuError, wgpu};
use shapegen_runtime::optimize::{EvaluateError, Evaluator};
use shapegen_runtime::score::silhouette::{
    GpuSilhouetteScorer, SilhouetteCounts, SilhouetteScorer,
};
use shapegen_runtime::score::volume::{GpuVolumeScorer, VolumeCounts, VolumeScorer};
use shapegen_runtime::score::{InstanceBatch, LengthPenalty, Scorer, count_batch};
use shapegen_runtime::{Genome, Grammar};

use super::{Scene, SceneError};

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

/// What one model of a scene covers, per scorer.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct SceneCounts {
    /// The volume scorer's counts, when the scene has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub volume: Option<VolumeCounts>,
    /// The silhouette scorer's counts, when the scene has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub silhouette: Option<SilhouetteCounts>,
}

/// A scene's scorers for one grammar, counting on the CPU; [`on`](Self::on) gives the
/// backend that counts whole populations.
#[derive(Clone, Debug)]
pub struct SceneScorer {
    /// The volume scorer, when the scene has one.
    pub volume: Option<VolumeScorer>,
    /// The silhouette scorer, when the scene has one.
    pub silhouette: Option<SilhouetteScorer>,
    /// The genome-length term.
    pub length: LengthPenalty,
}

impl SceneScorer {
    /// The scene's scorers for grammar `G`, which must be the scene's generator.
    ///
    /// # Errors
    /// [`SceneError::Invalid`] when the scene's meshes lack one the grammar uses, a
    /// target cannot be used, or the scene's goal is [`objectives`](Scene::objectives).
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
            .map_err(|err| scene.invalid("meshes", shapegen_runtime::error_chain(&err)))?;
        let volume = scene
            .volume
            .as_ref()
            .map(|goal| {
                VolumeScorer::new(goal.grid, &goal.targets, &meshes, goal.form)
                    .map_err(|err| scene.invalid("volume", shapegen_runtime::error_chain(&err)))
            })
            .transpose()?;
        let silhouette = scene
            .silhouette
            .as_ref()
            .map(|goal| {
                SilhouetteScorer::new(goal.targets.clone(), &meshes, goal.form)
                    .map_err(|err| scene.invalid("silhouette", shapegen_runtime::error_chain(&err)))
            })
            .transpose()?;
        Ok(SceneScorer {
            volume,
            silhouette,
            length: scene.length,
        })
    }

    /// The backend `choice` asks for. `gpu` is the device, opened by the caller (`None`
    /// when there is none: [`BackendChoice::Auto`] then counts on the CPU). `Auto` passes
    /// over software adapters, which are slower than the CPU path.
    ///
    /// # Errors
    /// [`SceneError::Backend`] for [`BackendChoice::Gpu`] without a device, or when the
    /// scene cannot run on it.
    pub fn on<'a>(
        &'a self,
        choice: BackendChoice,
        gpu: Option<&'a GpuContext>,
    ) -> Result<Backend<'a>, SceneError> {
        let cpu = |why: &str| Backend {
            scorer: self,
            volume: None,
            silhouette: None,
            description: format!("CPU{why}"),
        };
        let context = match (choice, gpu) {
            (BackendChoice::Cpu, _) => return Ok(cpu("")),
            (BackendChoice::Gpu, None) => {
                return Err(SceneError::Backend(
                    "--gpu asks for the GPU, but no GPU adapter was found".into(),
                ));
            }
            (BackendChoice::Auto, None) => return Ok(cpu(" (no GPU adapter)")),
            (BackendChoice::Auto, Some(context))
                if context.info.device_type == wgpu::DeviceType::Cpu =>
            {
                return Ok(cpu(&format!(" (passed over {})", context.describe())));
            }
            (_, Some(context)) => context,
        };
        match self.gpu_paths(context) {
            Ok((volume, silhouette)) => Ok(Backend {
                scorer: self,
                volume,
                silhouette,
                description: format!("GPU: {}", context.describe()),
            }),
            Err(err) if choice == BackendChoice::Gpu => Err(SceneError::Backend(err.to_string())),
            Err(err) => Ok(cpu(&format!(" ({err})"))),
        }
    }

    #[allow(clippy::type_complexity)]
    fn gpu_paths<'a>(
        &'a self,
        context: &'a GpuContext,
    ) -> Result<(Option<GpuVolumeScorer<'a>>, Option<GpuSilhouetteScorer<'a>>), GpuError> {
        let volume = self
            .volume
            .as_ref()
            .map(|v| GpuVolumeScorer::new(context, v))
            .transpose()?;
        let silhouette = self
            .silhouette
            .as_ref()
            .map(|s| GpuSilhouetteScorer::new(context, s))
            .transpose()?;
        Ok((volume, silhouette))
    }

    /// The fitness of a model of `genes` genes with these counts: the scorers' parts, less
    /// the genome-length term.
    pub fn fitness(&self, counts: &SceneCounts, genes: usize) -> f64 {
        let volume = match (&self.volume, &counts.volume) {
            (Some(s), Some(c)) => s.fitness(c),
            _ => 0.0,
        };
        let silhouette = match (&self.silhouette, &counts.silhouette) {
            (Some(s), Some(c)) => s.fitness(c),
            _ => 0.0,
        };
        volume + silhouette - self.length.apply(genes)
    }
}

/// A scene's scorers on the backend that counts them.
pub struct Backend<'a> {
    scorer: &'a SceneScorer,
    volume: Option<GpuVolumeScorer<'a>>,
    silhouette: Option<GpuSilhouetteScorer<'a>>,
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

    /// Counts every model of `batch` into `out`, resized to the batch.
    ///
    /// # Errors
    /// When the GPU fails while counting.
    pub fn count(&self, batch: &InstanceBatch, out: &mut Vec<SceneCounts>) -> Result<(), GpuError> {
        let n = batch.len();
        out.clear();
        out.resize(n, SceneCounts::default());
        if let Some(volume) = &self.scorer.volume {
            let mut counts = vec![VolumeCounts::default(); n];
            match &self.volume {
                Some(gpu) => gpu.count_batch(batch, &mut counts)?,
                None => count_batch(volume, batch, &mut counts),
            }
            for (slot, c) in out.iter_mut().zip(counts) {
                slot.volume = Some(c);
            }
        }
        if let Some(silhouette) = &self.scorer.silhouette {
            let mut counts = vec![SilhouetteCounts::default(); n];
            match &self.silhouette {
                Some(gpu) => gpu.count_batch(batch, &mut counts)?,
                None => count_batch(silhouette, batch, &mut counts),
            }
            for (slot, c) in out.iter_mut().zip(counts) {
                slot.silhouette = Some(c);
            }
        }
        Ok(())
    }
}

/// Scores populations for an optimizer with a scene's scorers on a backend: derives
/// every genome into one reused batch, counts it, and subtracts the length term.
pub struct SceneEvaluator<'a> {
    backend: &'a Backend<'a>,
    batch: InstanceBatch,
    counts: Vec<SceneCounts>,
}

impl<'a> SceneEvaluator<'a> {
    /// An evaluator counting on `backend`.
    pub fn new(backend: &'a Backend<'a>) -> Self {
        SceneEvaluator {
            backend,
            batch: InstanceBatch::new(),
            counts: Vec::new(),
        }
    }
}

impl<G: Grammar> Evaluator<G> for SceneEvaluator<'_> {
    fn evaluate(&mut self, genomes: &[Genome<G>], out: &mut [f64]) -> Result<(), EvaluateError> {
        self.batch.clear();
        for genome in genomes {
            self.batch.push_genome(genome);
        }
        self.backend
            .count(&self.batch, &mut self.counts)
            .map_err(|err| EvaluateError(err.to_string()))?;
        let scorer = self.backend.scorer();
        for ((slot, counts), genome) in out.iter_mut().zip(&self.counts).zip(genomes) {
            *slot = scorer.fitness(counts, genome.len());
        }
        Ok(())
    }
}
