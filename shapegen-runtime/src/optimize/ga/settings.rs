//! The settings of the GA ([`GaSettings`]) and its parent selection
//! ([`ParentSelection`]).

use crate::optimize::settings::generations_field;
use serde::{Deserialize, Serialize};

use crate::derive::Grammar;
use crate::genome::Limits;
use crate::ops::{OperatorVariant, Operators};
use crate::optimize::driver::Held;
use crate::optimize::error::{OptimizeError, SettingsError};
use crate::optimize::error::{check_positive, check_range};
use crate::optimize::polish;
use crate::optimize::settings::Settings;

/// Settings of the [`Ga`](super::Ga). Loads from scene files with serde; missing fields take the
/// [`Default`] values, unknown fields are errors.
///
/// The default is the good setting of the CESCG study (Haubenwallner, CESCG 2017):
/// population 200, elitism 30, initial length 20, 50 generations, mutation 30% with
/// uniform grow / cut / alter, tournament of 10, with the weighted operators. The
/// published generators carry the original's settings for their paper scenes
/// (`generators::spaceship::paper_ga`, ...), with the original's operators and breeding.
///
/// ```
/// use shapegen_runtime::ops::OperatorVariant;
/// use shapegen_runtime::optimize::GaSettings;
///
/// let s: GaSettings = serde_json::from_str(r#"{"operators": "original", "population": 50}"#)?;
/// assert_eq!(s.operators, OperatorVariant::Original);
/// assert!(!s.cross_array_index);
/// # Ok::<(), serde_json::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct GaSettings {
    /// Individuals per generation; at least 2.
    pub population: u32,
    /// Best individuals copied unchanged into the next generation (their fitness is
    /// kept, not recomputed); less than `population`.
    pub elitism: u32,
    /// Initial genomes are grown from the axiom: with the weighted operators to a length
    /// drawn uniformly from `[L/2, 3L/2]` around this `L` (within the limits), with the
    /// original's to exactly `L` genes, as the original does; at least 1.
    pub initial_length: u32,
    /// Generations after the initial one, the default generation budget.
    pub generations: u64,
    /// Chance that a pair of parents is mutated instead of crossed over; in `[0, 1]`.
    pub mutation_probability: f64,
    /// Relative weight of grow among mutations; finite and not negative.
    pub grow_weight: f64,
    /// Relative weight of cut among mutations; finite and not negative.
    pub cut_weight: f64,
    /// Relative weight of alter among mutations; finite and not negative. The three
    /// weights must not all be 0.
    pub alter_weight: f64,
    /// Size of the tournaments that choose parents (see
    /// [`selection`](Self::selection)); at least 1.
    pub tournament: u32,
    /// How the two parents of a pair are chosen (scene key `selection`:
    /// `"tournament_roulette"`, the default and the paper's, `"tournament"`,
    /// `"roulette"` or `"random"`); see [`ParentSelection`].
    pub selection: ParentSelection,
    /// The rules of the operators and of the breeding around them (scene key
    /// `operators`: `"weighted"`, the default, or `"original"`); see
    /// [`OperatorVariant`] and [`Ga`](super::Ga).
    pub operators: OperatorVariant,
    /// Whether crossover may exchange subtrees hanging from different indices of an array
    /// slot, which moves, say, a city lot's building to another lot (scene key
    /// `cross_array_index`). `false`, the default: `lots[i]` meets only `lots[i]`, as
    /// the original's one symbol per lot does.
    pub cross_array_index: bool,
    /// Candidates a separable CMA-ES draws each generation to tune the continuous
    /// parameters of the population's best (see [`Ga`](super::Ga)); 0, the default,
    /// polishes nothing, otherwise at least 2.
    pub polish: u32,
    /// The step size a new polishing strategy starts with, as a share of each
    /// parameter's range; in `(0, 1]`.
    pub polish_sigma: f64,
}

impl Default for GaSettings {
    fn default() -> Self {
        GaSettings {
            population: 200,
            elitism: 30,
            initial_length: 20,
            generations: 50,
            mutation_probability: 0.3,
            grow_weight: 1.0,
            cut_weight: 1.0,
            alter_weight: 1.0,
            tournament: 10,
            selection: ParentSelection::TournamentRoulette,
            operators: OperatorVariant::Weighted,
            cross_array_index: false,
            polish: 0,
            polish_sigma: 0.1,
        }
    }
}

/// How the [`Ga`](super::Ga) chooses the two parents of each pair it breeds. Tournaments are of
/// [`GaSettings::tournament`] entrants; the roulette wheel weighs each individual by its
/// fitness above the population's worst (see [`Ga`](super::Ga) for NaN and infinities).
///
/// The CESCG study compared these schemes (Haubenwallner, CESCG 2017); the paper's GA and
/// the original implementation use the first.
///
/// ```
/// use shapegen_runtime::optimize::{GaSettings, ParentSelection};
///
/// let s: GaSettings = serde_json::from_str(r#"{"selection": "roulette"}"#)?;
/// assert_eq!(s.selection, ParentSelection::Roulette);
/// assert_eq!(GaSettings::default().selection, ParentSelection::TournamentRoulette);
/// # Ok::<(), serde_json::Error>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ParentSelection {
    /// Parent 1 by tournament, parent 2 by roulette (`"tournament_roulette"`): the
    /// paper's Algorithm 1 and the original's `createNewGeneration`.
    #[default]
    TournamentRoulette,
    /// Both parents by tournament (`"tournament"`).
    Tournament,
    /// Both parents by roulette (`"roulette"`).
    Roulette,
    /// Both parents drawn uniformly from the population, ignoring fitness (`"random"`).
    Random,
}

impl Settings for GaSettings {
    generations_field!("generations", generations);

    /// The given limits with the weighted operators; with the original's, which bound
    /// no depth, the given lengths at any depth (random genomes keep `max_depth`, but
    /// their children may grow deeper, as the original's do).
    fn kept_limits(&self, limits: Limits) -> Limits {
        match self.operators {
            OperatorVariant::Weighted => limits,
            OperatorVariant::Original => limits.without_depth(),
        }
    }

    /// Checks every field; the error names the first one out of range.
    ///
    /// ```
    /// use shapegen_runtime::optimize::{GaSettings, Settings};
    ///
    /// let bad = GaSettings { elitism: 200, ..GaSettings::default() };
    /// assert_eq!(bad.validate().unwrap_err().field, "elitism");
    /// ```
    fn validate(&self) -> Result<(), SettingsError> {
        if self.population < 2 {
            return Err(SettingsError::new(
                "population",
                self.population,
                "at least 2",
            ));
        }
        if self.elitism >= self.population {
            return Err(SettingsError::new(
                "elitism",
                self.elitism,
                "less than the population",
            ));
        }
        check_positive("initial_length", self.initial_length)?;
        check_range(
            "mutation_probability",
            self.mutation_probability,
            0.0,
            1.0,
            "between 0 and 1",
        )?;
        let valid = "finite and not negative";
        check_range("grow_weight", self.grow_weight, 0.0, f64::MAX, valid)?;
        check_range("cut_weight", self.cut_weight, 0.0, f64::MAX, valid)?;
        check_range("alter_weight", self.alter_weight, 0.0, f64::MAX, valid)?;
        let total = self.grow_weight + self.cut_weight + self.alter_weight;
        if !(total > 0.0 && total.is_finite()) {
            return Err(SettingsError::new(
                "alter_weight",
                self.alter_weight,
                "positive when grow_weight and cut_weight are 0 (the weights' sum must be finite and positive)",
            ));
        }
        check_positive("tournament", self.tournament)?;
        polish::check_settings(self.polish, self.polish_sigma)
    }
}

impl GaSettings {
    /// The genomes `populations` GAs of these settings hold: each its population, the
    /// next generation and a checkpoint's copy.
    pub(crate) fn held(&self, populations: u64) -> Held {
        Held::per(
            "optimizer.population",
            self.population,
            3 * populations,
            populations,
        )
    }

    /// The children bred each generation, each evaluated: `population - elitism`.
    pub(crate) fn children(&self) -> u64 {
        u64::from(self.population - self.elitism)
    }

    /// Checks the settings against the genome limits: the original's breeding keeps only
    /// children within `[min_len, max_len)`, which must not be empty.
    pub(crate) fn check_limits(&self, limits: &Limits) -> Result<(), SettingsError> {
        if self.operators == OperatorVariant::Original && limits.min_len.max(1) >= limits.max_len {
            return Err(SettingsError::new(
                "limits.max_len",
                limits.max_len,
                "above limits.min_len with operators = \"original\", whose GA keeps only \
                 children shorter than max_len",
            ));
        }
        Ok(())
    }

    /// The operators these settings breed with, keeping to `limits`.
    pub(crate) fn build_operators<G: Grammar>(
        &self,
        limits: Limits,
    ) -> Result<Operators<G>, OptimizeError> {
        self.check_limits(&limits)?;
        Ok(Operators::new(limits)?
            .with_variant(self.operators)
            .with_cross_array_index(self.cross_array_index))
    }
}
