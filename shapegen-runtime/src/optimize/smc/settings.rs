//! What an [`Smc`](super::Smc) runs with: its order, variant and settings, and a
//! particle's growth bookkeeping.

use serde::{Deserialize, Serialize};

use crate::genome::Limits;
use crate::optimize::error::{SettingsError, check_positive, check_range};
use crate::optimize::polish;
use crate::optimize::settings::{Settings, generations_field};

/// Which unexpressed child a step grows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Order {
    /// SMC. Generative variant: links are decided in chromosome order (genes in buffer
    /// order, links in order); each is expressed with its generator probability or left
    /// empty for good. Original variant: the newest gene that can still take a child,
    /// or with [`step_back_probability`](SmcSettings::step_back_probability) one before
    /// it, and so on.
    Chromosome,
    /// SOSMC: a link among the unexpressed ones (the "stochastic futures") is expressed.
    /// Generative variant: drawn uniformly among those that may grow. Original variant:
    /// a gene drawn among those that can still take a child, then one of its free links.
    Stochastic,
}

/// Which SMC an [`Smc`](super::Smc) runs.
///
/// In scene files and JSON: `"original"` or `"generative"`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SmcVariant {
    /// The original implementation's SMC and SOSMC (`SMC.h`, `SOSMC.h`, with the grows of
    /// `SMCOperators.cpp` and `SOSMCOperators.cpp` and their `SMCSelection` and
    /// `SoSmcSelection`, which are the same), reproduced with their oddities.
    ///
    /// A node's *possible children* are its links in link order, each taking at most one
    /// child, as every possible child of the published grammars has `max_num` 1. A gene
    /// *can take a child* when it has an empty link. The original's gene order is
    /// pre-order, each gene's children in the order they were added: it renumbers a
    /// genome so whenever it copies one, and it copies every particle before growing it.
    ///
    /// - Particles start as the axiom and one grow (the original's
    ///   `createRandomGenome(grammar, 2)`), and are evaluated.
    /// - Each step, every particle grows by exactly one gene and is evaluated: one
    ///   evaluation per particle per step. Nothing else happens to a particle that cannot
    ///   grow; it is evaluated all the same.
    /// - A grow in chromosome order ([`Order::Chromosome`], `SMCGrowMutation`) lists the
    ///   genes that can take a child and lie above level `max_depth` (the root is level
    ///   0, so the original's trees reach level `max_depth`, one deeper than
    ///   [`Limits::max_depth`] allows elsewhere, the root counting as depth 1), in gene
    ///   order, starts from the last one and steps back one gene at a time with
    ///   probability [`step_back_probability`](SmcSettings::step_back_probability) (the
    ///   original's `basic_prob`, 0 in all published configurations: always the last),
    ///   never past the first.
    /// - A grow with stochastic futures ([`Order::Stochastic`], `SoSmcGrowMutation`)
    ///   draws among all genes that can take a child, with no depth bound.
    /// - Either then draws one of the gene's empty links uniformly, ignoring the
    ///   generator's probabilities (the original's "TODO: pay attention to percentage
    ///   values"), and appends a child there with parameters drawn from their
    ///   distributions.
    /// - From the second step on, before growing, the particles are resampled from the
    ///   previous step's grown particles: ranked best first, each of the `n` new
    ///   particles is drawn by its own `U` in `[0, 1)` as the first particle in rank
    ///   order whose cumulative relative fitness `sum_{j <= k} (f_j + offset) / S`
    ///   reaches `U`, or the last one if none does, where `offset = -f_worst` when the
    ///   worst fitness is not negative and 0 otherwise, and `S = sum_j (f_j + offset)`;
    ///   the new particles are ordered best first. The first step grows the initial
    ///   particles themselves. (The original resamples at the end of each step instead,
    ///   the last one included; the particles evaluated are the same, and checkpoints
    ///   hold them as grown and scored.)
    ///
    /// Oddities of the original, reproduced:
    /// - its integer draw `getRandomValue(0, n - 1)` truncates `(n - 1) U`, so the last of
    ///   `n >= 2` candidates is never taken: the stochastic grow never grows from the last
    ///   gene in gene order, and neither order takes a gene's last empty link unless it is
    ///   the only one;
    /// - the offset is the opposite of what its comment says: a non-negative worst is
    ///   lifted to 0 (the worst then weighs nothing), a negative one is left as it is, so
    ///   negative fitness weighs negatively. The cumulative values then rise above 1 and
    ///   come back, and the weaker particles whose range lies past 1 are never drawn;
    ///   when `S` is negative the wheel turns around and only the worst particles are
    ///   drawn; when all particles have the same non-negative fitness every relative
    ///   value is `0 / 0`, no draw reaches one, and all new particles are copies of the
    ///   last one in rank order;
    /// - nothing bounds a genome's length: particles grow past [`Limits::max_len`] (one
    ///   gene per step), and [`Limits::min_len`] is not enforced (the limits this
    ///   variant keeps, [`Settings::kept_limits`], bound neither length nor depth).
    ///
    /// As the original, the resampling works in `f32` (fitness values are converted);
    /// ties in rank keep their index order (the original's sort leaves it unspecified).
    /// Beyond the original: only finite fitness values enter the wheel: NaN and `-inf`
    /// particles are drawn only when every particle is NaN or `-inf` (then the last in
    /// rank order is), and if some particles are at `+inf` the draws are uniform among
    /// them. Genomes stay within [`DEPTH_CAP`](crate::genome::DEPTH_CAP): no gene at that
    /// depth takes a child. Not reproduced: the original redraws the axiom's parameters
    /// whenever it copies a genome (none of the published grammars' axioms has any).
    Original,
    /// This project's SMC: particles grow as the generator would, from the axiom, each
    /// step until the model shows new geometry.
    ///
    /// Particles start as the axiom alone. A step first resamples the particles
    /// multinomially by fitness (roulette weights as the GA's: `f - f_min`, NaN weighs
    /// 0), then grows every particle until its model emits more instances than before
    /// (the whole model is derived after each added gene to see it), at most
    /// [`max_grows_per_step`](SmcSettings::max_grows_per_step) genes, or until nothing
    /// can grow (a finished particle stays as it is), and scores all of them as partial
    /// models. A grow in chromosome order decides the links in chromosome order, each
    /// expressed with its generator probability; one with stochastic futures expresses a
    /// link drawn uniformly among the empty ones of genes above the maximum depth with a
    /// non-zero probability. Genomes stay within [`Limits::max_len`] and
    /// [`Limits::max_depth`]; particles may be shorter than [`Limits::min_len`] while
    /// they grow, and one that can grow no more while shorter gets a NaN fitness, so
    /// that it is never drawn again.
    Generative,
}

impl SmcVariant {
    /// Every variant.
    pub const ALL: [SmcVariant; 2] = [SmcVariant::Original, SmcVariant::Generative];

    /// Its name in scene files and settings.
    pub const fn name(self) -> &'static str {
        match self {
            SmcVariant::Original => "original",
            SmcVariant::Generative => "generative",
        }
    }
}

/// Settings of [`Smc`](super::Smc). Loads from scene files with serde; missing fields take the
/// [`Default`] values, unknown fields are errors.
///
/// The default is the [generative](SmcVariant::Generative) variant with the spaceship
/// scene's sizes; the published generators carry the original's configuration files with
/// the [original](SmcVariant::Original) variant (`generators::spaceship::paper_smc`, ...).
///
/// ```
/// use shapegen_runtime::optimize::{Order, SmcSettings, SmcVariant};
///
/// let s: SmcSettings = serde_json::from_str(r#"{"variant": "original", "particles": 50}"#)?;
/// assert_eq!((s.variant, s.particles), (SmcVariant::Original, 50));
/// assert_eq!(SmcSettings::default().variant, SmcVariant::Generative);
/// # Ok::<(), serde_json::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SmcSettings {
    /// Number of particles; at least 1.
    pub particles: u32,
    /// Steps, the default generation budget.
    pub steps: u64,
    /// SMC or SOSMC.
    pub order: Order,
    /// Which SMC runs.
    pub variant: SmcVariant,
    /// Original variant only, chromosome order: the chance that a grow steps back from a
    /// gene to the one before it; in `[0, 1]`.
    pub step_back_probability: f64,
    /// Generative variant only: most genes a step adds while waiting for new geometry;
    /// at least 1.
    pub max_grows_per_step: u32,
    /// Candidates a separable CMA-ES draws each step to tune the continuous parameters
    /// of the best particle (see [`Smc`](super::Smc)); 0, the default, polishes nothing, otherwise at
    /// least 2.
    pub polish: u32,
    /// The step size a new polishing strategy starts with, as a share of each
    /// parameter's range; in `(0, 1]`.
    pub polish_sigma: f64,
}

impl Default for SmcSettings {
    fn default() -> Self {
        SmcSettings {
            particles: 500,
            steps: 40,
            order: Order::Chromosome,
            variant: SmcVariant::Generative,
            step_back_probability: 0.0,
            max_grows_per_step: 64,
            polish: 0,
            polish_sigma: 0.1,
        }
    }
}

impl Settings for SmcSettings {
    generations_field!("steps", steps);

    /// The original's particles grow one gene a step from the axiom, bounded by neither
    /// length nor depth; the generative variant's keep the given limits but may be
    /// shorter than `min_len` while they grow.
    fn kept_limits(&self, limits: Limits) -> Limits {
        match self.variant {
            SmcVariant::Original => limits.without_length().without_depth(),
            SmcVariant::Generative => limits.without_min_len(),
        }
    }

    /// Checks every field the variant reads; the error names the first one out of range.
    fn validate(&self) -> Result<(), SettingsError> {
        check_positive("particles", self.particles)?;
        match self.variant {
            SmcVariant::Original => check_range(
                "step_back_probability",
                self.step_back_probability,
                0.0,
                1.0,
                "between 0 and 1",
            )?,
            SmcVariant::Generative => {
                check_positive("max_grows_per_step", self.max_grows_per_step)?;
            }
        }
        polish::check_settings(self.polish, self.polish_sigma)
    }
}

/// One particle's growth bookkeeping in the [generative](SmcVariant::Generative) variant.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Cursor {
    /// Chromosome order: word position of the gene whose links are being decided.
    pub pos: u32,
    /// Chromosome order: the next link of that gene to decide.
    pub link: u32,
    /// Instances the particle's model emitted when last derived.
    pub emitted: u32,
}
