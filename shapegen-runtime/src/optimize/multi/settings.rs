//! Settings of the multi-objective GA, as scene files give them.

use crate::genome::Limits;
use crate::optimize::settings::generations_field;
use serde::{Deserialize, Serialize};

use crate::optimize::error::SettingsError;
use crate::optimize::error::{check_positive, check_range};
use crate::optimize::ga::GaSettings;
use crate::optimize::settings::Settings;

/// How a population's objective vectors become one selection fitness (see
/// [`selection_fitness`](super::selection_fitness)).
#[derive(Clone, Debug, PartialEq)]
pub enum Ranking {
    /// The weighted sum of the oriented objective values (minimized objectives count
    /// negated), one weight per objective, finite and not negative, not all 0.
    WeightedSum {
        /// One weight per objective.
        weights: Vec<f64>,
    },
    /// Non-dominated fronts, ties within a front broken by crowding distance.
    Pareto,
    /// The sum of the per-objective ranks.
    SummedRank,
    /// The sum of the per-objective ranks, each divided by its objective's largest rank.
    NormalizedSummedRank,
}

/// The selection of the multi-objective GA: a [`Ranking`] and a diversity penalty.
///
/// In a scene file (TOML shown; the default is Pareto ranking with penalty 20):
///
/// ```toml
/// [selection]
/// ranking = "weighted_sum"     # or "pareto", "summed_rank", "normalized_summed_rank"
/// weights = [1.0, 0.5]         # only, and required, with "weighted_sum"
/// diversity_penalty = 20.0     # optional, default 20
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "SelectionFields", into = "SelectionFields")]
pub struct Selection {
    /// The ranking.
    pub ranking: Ranking,
    /// Subtracted from the selection fitness of every individual whose objective vector
    /// equals an earlier one's; finite and not negative (0: no penalty).
    pub diversity_penalty: f64,
}

impl Default for Selection {
    /// Pareto ranking with the thesis's penalty of 20.
    fn default() -> Self {
        Selection {
            ranking: Ranking::Pareto,
            diversity_penalty: 20.0,
        }
    }
}

/// The names of the rankings in scene files.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
enum RankingName {
    WeightedSum,
    Pareto,
    SummedRank,
    NormalizedSummedRank,
}

/// [`Selection`] as a flat table.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct SelectionFields {
    ranking: RankingName,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    weights: Option<Vec<f64>>,
    #[serde(default = "default_penalty")]
    diversity_penalty: f64,
}

fn default_penalty() -> f64 {
    Selection::default().diversity_penalty
}

impl TryFrom<SelectionFields> for Selection {
    type Error = SettingsError;

    fn try_from(f: SelectionFields) -> Result<Self, SettingsError> {
        let ranking = match (f.ranking, f.weights) {
            (RankingName::WeightedSum, Some(weights)) => Ranking::WeightedSum { weights },
            (RankingName::WeightedSum, None) => {
                return Err(SettingsError::new(
                    "selection.weights",
                    "nothing",
                    "given (one per objective) with ranking = \"weighted_sum\"",
                ));
            }
            (_, Some(w)) => {
                return Err(SettingsError::new(
                    "selection.weights",
                    format!("{w:?}"),
                    "given only with ranking = \"weighted_sum\"",
                ));
            }
            (RankingName::Pareto, None) => Ranking::Pareto,
            (RankingName::SummedRank, None) => Ranking::SummedRank,
            (RankingName::NormalizedSummedRank, None) => Ranking::NormalizedSummedRank,
        };
        Ok(Selection {
            ranking,
            diversity_penalty: f.diversity_penalty,
        })
    }
}

impl From<Selection> for SelectionFields {
    fn from(s: Selection) -> Self {
        let (ranking, weights) = match s.ranking {
            Ranking::WeightedSum { weights } => (RankingName::WeightedSum, Some(weights)),
            Ranking::Pareto => (RankingName::Pareto, None),
            Ranking::SummedRank => (RankingName::SummedRank, None),
            Ranking::NormalizedSummedRank => (RankingName::NormalizedSummedRank, None),
        };
        SelectionFields {
            ranking,
            weights,
            diversity_penalty: s.diversity_penalty,
        }
    }
}

impl Selection {
    /// Checks the penalty and the weights; the error names the field.
    ///
    /// ```
    /// use shapegen_runtime::optimize::multi::{Ranking, Selection};
    ///
    /// let bad = Selection { ranking: Ranking::WeightedSum { weights: vec![1.0, -1.0] }, diversity_penalty: 0.0 };
    /// assert_eq!(bad.validate().unwrap_err().field, "selection.weights");
    /// ```
    pub fn validate(&self) -> Result<(), SettingsError> {
        check_range(
            "selection.diversity_penalty",
            self.diversity_penalty,
            0.0,
            f64::MAX,
            "finite and not negative",
        )?;
        if let Ranking::WeightedSum { weights } = &self.ranking
            && (weights.iter().any(|w| !(w.is_finite() && *w >= 0.0))
                || weights.iter().all(|&w| w == 0.0))
        {
            return Err(SettingsError::new(
                "selection.weights",
                format!("{weights:?}"),
                "finite and not negative, at least one positive",
            ));
        }
        Ok(())
    }

    /// Checks that the ranking fits `k` objectives (a weighted sum needs one weight per
    /// objective).
    pub fn check_objectives(&self, k: usize) -> Result<(), SettingsError> {
        match &self.ranking {
            Ranking::WeightedSum { weights } if weights.len() != k => Err(SettingsError::new(
                "selection.weights",
                format!("{} weights", weights.len()),
                "one weight per objective of the evaluator",
            )),
            _ => Ok(()),
        }
    }
}

/// Settings of the [`MultiGa`](super::MultiGa): the GA's breeding settings, the
/// selection, and the archive's size. Missing fields take the [`Default`], which is
/// [`MultiGaSettings::thesis`]; unknown fields are errors.
///
/// In a scene file (TOML shown):
///
/// ```toml
/// archive = 300                # most models kept in the non-dominated archive
/// [ga]                         # GaSettings' fields; a missing table means the thesis's
/// population = 300             # values, fields missing in a given table GaSettings'
/// generations = 30             # own defaults
/// [selection]
/// ranking = "pareto"
/// diversity_penalty = 20.0
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MultiGaSettings {
    /// Population, elitism, initial length, generations, mutation and tournament, as in
    /// the single-objective GA. Elites are the best by selection fitness.
    pub ga: GaSettings,
    /// How the objective vectors become a selection fitness.
    pub selection: Selection,
    /// Most members of the archive of non-dominated models; at least 1.
    pub archive: u32,
}

impl Default for MultiGaSettings {
    fn default() -> Self {
        MultiGaSettings::thesis()
    }
}

impl Settings for MultiGaSettings {
    generations_field!("generations", ga.generations);

    /// Its GA's.
    fn kept_limits(&self, limits: Limits) -> Limits {
        self.ga.kept_limits(limits)
    }

    /// Checks every field; the error names the first one out of range (the GA's fields
    /// by their names in [`GaSettings`]).
    ///
    /// ```
    /// use shapegen_runtime::optimize::Settings;
    /// use shapegen_runtime::optimize::multi::MultiGaSettings;
    ///
    /// let bad = MultiGaSettings { archive: 0, ..MultiGaSettings::thesis() };
    /// assert_eq!(bad.validate().unwrap_err().field, "archive");
    /// ```
    fn validate(&self) -> Result<(), SettingsError> {
        self.ga.validate()?;
        crate::optimize::polish::refuse(
            self.ga.polish,
            "0 with several objectives, which have no single best to polish",
        )?;
        self.selection.validate()?;
        check_positive("archive", self.archive)?;
        Ok(())
    }
}

impl MultiGaSettings {
    /// The thesis's GP settings in this GA: population 300,
    /// 30 generations, tournament 3, elitism 2% (6), mutation instead of crossover for
    /// 10% of the pairs (crossover 0.9) with uniform grow / cut / alter, initial length
    /// 20; Pareto ranking with a diversity penalty of 20; an archive of 300.
    pub fn thesis() -> Self {
        MultiGaSettings {
            ga: GaSettings {
                population: 300,
                elitism: 6,
                initial_length: 20,
                generations: 30,
                mutation_probability: 0.1,
                grow_weight: 1.0,
                cut_weight: 1.0,
                alter_weight: 1.0,
                tournament: 3,
                ..GaSettings::default()
            },
            selection: Selection::default(),
            archive: 300,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scene_tables_parse() {
        let s: MultiGaSettings = toml::from_str(
            "archive = 50\n[ga]\npopulation = 40\nelitism = 4\n\
             [selection]\nranking = \"weighted_sum\"\nweights = [1.0, 2.0]\n",
        )
        .unwrap();
        assert_eq!(s.archive, 50);
        assert_eq!((s.ga.population, s.ga.elitism), (40, 4));
        assert_eq!(s.ga.tournament, GaSettings::default().tournament);
        assert_eq!(
            s.selection,
            Selection {
                ranking: Ranking::WeightedSum {
                    weights: vec![1.0, 2.0]
                },
                diversity_penalty: 20.0
            }
        );
        let s: MultiGaSettings = toml::from_str("").unwrap();
        assert_eq!(s, MultiGaSettings::thesis());
        for (name, ranking) in [
            ("pareto", Ranking::Pareto),
            ("summed_rank", Ranking::SummedRank),
            ("normalized_summed_rank", Ranking::NormalizedSummedRank),
        ] {
            let text = format!("[selection]\nranking = \"{name}\"\ndiversity_penalty = 0.0\n");
            let s: MultiGaSettings = toml::from_str(&text).unwrap();
            assert_eq!(s.selection.ranking, ranking);
            assert_eq!(s.selection.diversity_penalty, 0.0);
            let back: MultiGaSettings = toml::from_str(&toml::to_string(&s).unwrap()).unwrap();
            assert_eq!(back, s);
        }
    }

    #[test]
    fn bad_scene_tables_name_the_field() {
        for (text, field) in [
            (
                "[selection]\nranking = \"weighted_sum\"\n",
                "selection.weights",
            ),
            (
                "[selection]\nranking = \"pareto\"\nweights = [1.0]\n",
                "selection.weights",
            ),
        ] {
            let e = toml::from_str::<MultiGaSettings>(text).unwrap_err();
            assert!(e.to_string().contains(field), "{e}");
        }
        for text in [
            "archiv = 3\n",
            "[selection]\nranking = \"pareto\"\npenalty = 1.0\n",
            "[selection]\nranking = \"crowding\"\n",
            "[ga]\npopulaton = 3\n",
        ] {
            assert!(toml::from_str::<MultiGaSettings>(text).is_err(), "{text}");
        }
    }
}
