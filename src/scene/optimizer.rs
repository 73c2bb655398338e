//! The `[optimizer]` table: which method searches, with what settings, seed and budget.

use std::time::Duration;

use crate::registry::Presets;
use serde::{Deserialize, Serialize};
use shapegen_runtime::Grammar;
use shapegen_runtime::optimize::islands::{IslandGaSettings, IslandSettings};
use shapegen_runtime::optimize::multi::MultiGaSettings;
use shapegen_runtime::optimize::{Budget, Settings};

use super::error::SetError;
use super::method::{Method, MethodJob, MethodSettings, SettingsCause, SettingsKeyError};

/// The `[optimizer]` table, resolved. Keys the method does not know are refused.
///
/// ```toml
/// [optimizer]
/// method = "hybrid"      # a [`Method`]'s name (the hybrid by default; the GA with
///                        # [islands] or [[objective]] tables)
/// seed = 1
/// seconds = 60           # wall-time budget (optional)
/// evaluations = 100000   # evaluation budget (optional)
/// generations = 100      # GA generations, SMC steps, RJMCMC iterations
///                        # then the method's own settings: for the GA population,
/// population = 100       # elitism, initial_length, generations, mutation_probability,
///                        # grow_weight, cut_weight, alter_weight, tournament,
///                        # selection ("tournament_roulette", "tournament",
///                        # "roulette" or "random"),
///                        # operators ("original" or "weighted"), cross_array_index
///                        # (true or false); for SMC and SOSMC particles, steps,
///                        # variant ("original" or "generative"),
///                        # step_back_probability, max_grows_per_step; for RJMCMC
///                        # variant ("original" or "tempered"), chains, iterations,
///                        # initial_length, jump_probability, ...; polish and
///                        # polish_sigma for every method but random search; each
///                        # method's fields are those of its settings type
///                        # ([`MethodSettings`])
/// ```
///
/// The paper's GA settings use the original's operators and breeding
/// (`operators = "original"`); `operators = "weighted"` gives the paper's weighted
/// operators (see `shapegen_runtime::ops::OperatorVariant`).
///
/// Settings the table leaves out are the paper's for the method and the scene's
/// generator.
#[derive(Clone, Debug, PartialEq)]
pub struct OptimizerGoal {
    /// Seed of every random stream of the run.
    pub seed: u64,
    /// Wall-time budget.
    pub seconds: Option<f64>,
    /// Evaluation budget.
    pub evaluations: Option<u64>,
    /// The method and its settings.
    pub settings: MethodSettings,
    /// The island model the GA runs as (a scene's `[islands]`, `--islands`); only with
    /// the GA.
    pub islands: Option<IslandSettings>,
}

impl OptimizerGoal {
    /// The method.
    pub fn method(&self) -> Method {
        self.settings.method()
    }

    /// Generations (steps, iterations) the method's settings ask for.
    pub fn generations(&self) -> u64 {
        self.settings.generations()
    }

    /// Sets the generations (steps, iterations) the method's settings ask for.
    pub fn set_generations(&mut self, n: u64) {
        self.settings.set_generations(n);
    }

    /// The run's budget: the settings' generations, and the time and evaluation limits
    /// when given.
    pub fn budget(&self) -> Budget {
        let mut budget = Budget::generations(self.generations());
        if let Some(s) = self.seconds {
            budget = budget.and_wall_time(Duration::from_secs_f64(s));
        }
        if let Some(n) = self.evaluations {
            budget = budget.and_evaluations(n);
        }
        budget
    }

    /// The settings of the GA's island model ([`IslandGa`](shapegen_runtime::optimize::islands::IslandGa)) that
    /// searches this goal: the GA's with the islands, when the goal has islands (which
    /// only the GA has). The one place where the model is derived.
    pub fn island_settings(&self) -> Option<IslandGaSettings> {
        match (self.islands, self.settings) {
            (Some(islands), MethodSettings::Ga(ga)) => Some(IslandGaSettings { ga, islands }),
            _ => None,
        }
    }

    /// Runs `job` with the optimizer that searches this goal: the method's, or the GA's
    /// island model when the goal has islands ([`MethodJob::run_islands`]).
    pub fn run<G: Grammar, J: MethodJob<G>>(&self, job: J) -> J::Output {
        match self.island_settings() {
            Some(islands) => job.run_islands(islands),
            None => self.settings.run(job),
        }
    }
}

/// What the command line sets over a scene: typed flags (`--method`, `--seed`,
/// `--seconds`, `--evaluations`, `--generations`, `--islands`), which take the place of
/// the `[optimizer]` keys of the same names (`islands.count` for `--islands`), and free `key=value` overrides (`--set`), which
/// are applied to the scene's TOML before it is read, so that they are checked exactly
/// as the file's own keys are.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Overrides {
    /// The search method (`optimizer.method`).
    pub method: Option<Method>,
    /// The seed (`optimizer.seed`).
    pub seed: Option<u64>,
    /// The wall-time budget in seconds (`optimizer.seconds`).
    pub seconds: Option<f64>,
    /// The evaluation budget (`optimizer.evaluations`).
    pub evaluations: Option<u64>,
    /// Generations, steps or iterations (`optimizer.generations`).
    pub generations: Option<u64>,
    /// Islands of the GA (`islands.count`).
    pub islands: Option<u32>,
    /// `key=value` overrides of any scene key, in order.
    pub sets: Vec<String>,
}

impl Overrides {
    /// `self` with `later` over it: its flags where given, its `--set`s after these.
    pub fn then(mut self, later: &Overrides) -> Overrides {
        self.method = later.method.or(self.method);
        self.seed = later.seed.or(self.seed);
        self.seconds = later.seconds.or(self.seconds);
        self.evaluations = later.evaluations.or(self.evaluations);
        self.generations = later.generations.or(self.generations);
        self.islands = later.islands.or(self.islands);
        self.sets.extend(later.sets.iter().cloned());
        self
    }
}

/// The range of a budget in seconds.
const SECONDS: &str = "a number of seconds > 0";

/// The range of a budget of evaluations.
const EVALUATIONS: &str = "a whole number > 0";

/// `value` if it can be a budget in seconds.
fn budget_seconds(value: f64) -> Option<f64> {
    (value.is_finite() && value > 0.0).then_some(value)
}

/// `value`, printed, out of the range `valid`.
fn out_of_range(value: impl ToString, valid: &'static str) -> SettingsCause {
    SettingsCause::OutOfRange {
        value: value.to_string(),
        valid,
    }
}

/// The error of `key` of the `[optimizer]` table.
fn key_error(key: &str, cause: SettingsCause) -> SettingsKeyError {
    SettingsKeyError::new(format!("optimizer.{key}"), cause)
}

/// Resolves the `[optimizer]` table over the generator's `presets` for the method, with
/// the `[islands]` table and the typed `overrides` in place of the keys they name.
pub(super) fn resolve(
    presets: &Presets,
    mut table: toml::Table,
    islands: Option<IslandSettings>,
    overrides: &Overrides,
) -> Result<OptimizerGoal, SettingsKeyError> {
    let written = take_method(&mut table)?;
    let islands = island_model(islands, overrides);
    let method = overrides
        .method
        .or(written)
        .unwrap_or(if islands.is_some() {
            Method::Ga
        } else {
            Method::DEFAULT
        });
    if islands.is_some() && method != Method::Ga {
        return Err(SettingsKeyError::new(
            "islands",
            SettingsCause::IslandsNeedGa(method),
        ));
    }
    let seed = match table.remove("seed") {
        None => 1,
        Some(toml::Value::Integer(s)) if s >= 0 => s as u64,
        Some(other) => {
            return Err(key_error(
                "seed",
                out_of_range(other, "a whole number >= 0"),
            ));
        }
    };
    let (seconds, evaluations) = take_budget(&mut table, overrides)?;
    let settings = method.preset(presets).read(table)?;
    let mut goal = OptimizerGoal {
        seed: overrides.seed.unwrap_or(seed),
        seconds,
        evaluations,
        settings,
        islands,
    };
    if let Some(model) = goal.island_settings() {
        model.validate().map_err(|err| {
            let flag = err.field == "islands.count" && overrides.islands.is_some();
            SettingsKeyError::new(if flag { "--islands" } else { err.field }, err)
        })?;
    }
    if let Some(g) = overrides.generations {
        goal.set_generations(g);
    }
    Ok(goal)
}

/// Takes `method` out of an `[optimizer]` table: the method it names, if any.
fn take_method(table: &mut toml::Table) -> Result<Option<Method>, SettingsKeyError> {
    match table.remove("method") {
        None => Ok(None),
        Some(toml::Value::String(m)) => m
            .parse()
            .map(Some)
            .map_err(|e| key_error("method", SettingsCause::UnknownMethod(e))),
        Some(other) => Err(key_error("method", SettingsCause::NotAMethod(other))),
    }
}

/// The island model of the `[islands]` table as `written`, with `--islands` for its
/// count; `None` when neither gives one.
fn island_model(written: Option<IslandSettings>, overrides: &Overrides) -> Option<IslandSettings> {
    match (written, overrides.islands) {
        (None, None) => None,
        (written, count) => {
            let mut islands = written.unwrap_or_default();
            islands.count = count.unwrap_or(islands.count);
            Some(islands)
        }
    }
}

/// Takes the budgets, `seconds` and `evaluations`, out of an `[optimizer]` table, with
/// the flags `--seconds` and `--evaluations` in their place where given.
fn take_budget(
    table: &mut toml::Table,
    overrides: &Overrides,
) -> Result<(Option<f64>, Option<u64>), SettingsKeyError> {
    let written_seconds = match table.remove("seconds") {
        None => None,
        Some(v) => match v
            .as_float()
            .or(v.as_integer().map(|i| i as f64))
            .and_then(budget_seconds)
        {
            Some(s) => Some(s),
            None => return Err(key_error("seconds", out_of_range(v, SECONDS))),
        },
    };
    let written_evaluations = match table.remove("evaluations") {
        None => None,
        Some(toml::Value::Integer(n)) if n > 0 => Some(n as u64),
        Some(other) => return Err(key_error("evaluations", out_of_range(other, EVALUATIONS))),
    };
    let seconds = match overrides.seconds {
        None => written_seconds,
        Some(s) => Some(
            budget_seconds(s)
                .ok_or_else(|| SettingsKeyError::new("--seconds", out_of_range(s, SECONDS)))?,
        ),
    };
    let evaluations = match overrides.evaluations {
        Some(0) => {
            return Err(SettingsKeyError::new(
                "--evaluations",
                out_of_range(0, EVALUATIONS),
            ));
        }
        Some(n) => Some(n),
        None => written_evaluations,
    };
    Ok((seconds, evaluations))
}

/// Takes `archive` (the multi-objective GA's archive size) out of an `[optimizer]`
/// table: its value, or the default of [`MultiGaSettings`].
pub(super) fn take_archive(table: &mut toml::Table) -> Result<u32, SettingsKeyError> {
    match table.remove("archive") {
        None => Ok(MultiGaSettings::default().archive),
        Some(toml::Value::Integer(n)) if (1..=i64::from(u32::MAX)).contains(&n) => Ok(n as u32),
        Some(other) => Err(SettingsKeyError::new(
            "optimizer.archive",
            out_of_range(other, "a whole number >= 1"),
        )),
    }
}

/// Applies `key=value` overrides (`--set optimizer.population=200`) to a scene's TOML
/// tree. The value is read as TOML (a number, a boolean, an array, a quoted string) or,
/// when it is none of those, as a bare string.
pub(super) fn apply_overrides(root: &mut toml::Table, sets: &[String]) -> Result<(), SetError> {
    for set in sets {
        let Some((path, value)) = set.split_once('=') else {
            return Err(SetError::NotKeyValue { set: set.clone() });
        };
        let value = toml::from_str::<toml::Table>(&format!("v = {value}"))
            .ok()
            .and_then(|mut t| t.remove("v"))
            .unwrap_or_else(|| toml::Value::String(value.to_owned()));
        let keys: Vec<&str> = path.trim().split('.').collect();
        if keys.iter().any(|k| k.is_empty()) {
            return Err(SetError::NotDottedKey {
                set: set.clone(),
                key: path.to_owned(),
            });
        }
        let mut table = &mut *root;
        for k in &keys[..keys.len() - 1] {
            let entry = table
                .entry(k.to_string())
                .or_insert_with(|| toml::Value::Table(toml::Table::new()));
            table = entry.as_table_mut().ok_or_else(|| SetError::NotATable {
                set: set.clone(),
                part: k.to_string(),
            })?;
        }
        table.insert(keys[keys.len() - 1].to_owned(), value);
    }
    Ok(())
}

#[cfg(test)]
mod mcmc_tests {
    use super::*;
    use shapegen_runtime::optimize::{McmcSettings, McmcVariant, Order};

    fn presets(name: &str) -> Presets {
        crate::registry::Registry::published()
            .get(name)
            .unwrap()
            .defaults
            .presets
    }

    fn mcmc(generator: &str, text: &str) -> Result<McmcSettings, SettingsKeyError> {
        let table: toml::Table = toml::from_str(text).unwrap();
        match resolve(&presets(generator), table, None, &Overrides::default())?.settings {
            MethodSettings::Rjmcmc(s) => Ok(s),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn rjmcmc_takes_its_variant_over_the_originals_settings() {
        let m = "method = \"rjmcmc\"\n";
        for (generator, paper) in [
            ("spaceship", generators::spaceship::paper_rjmcmc()),
            ("tree", generators::tree::paper_rjmcmc()),
            ("city", generators::city::paper_rjmcmc()),
        ] {
            assert_eq!(mcmc(generator, m).unwrap(), paper);
            assert_eq!(paper.variant, McmcVariant::Original);
            let tempered = mcmc(generator, &format!("{m}variant = \"tempered\"\n")).unwrap();
            let want = McmcSettings {
                variant: McmcVariant::Tempered,
                ..paper
            };
            assert_eq!(tempered, want);
            let original = mcmc(generator, &format!("{m}variant = \"original\"\n")).unwrap();
            assert_eq!(original, paper);
        }
        for bad in ["\"talton\"", "1"] {
            let text = format!("{m}variant = {bad}\n");
            let SettingsKeyError { key, cause } = mcmc("tree", &text).unwrap_err();
            assert_eq!(key, "optimizer.variant");
            let reason = cause.to_string();
            assert!(reason.contains("\"original\" and \"tempered\""), "{reason}");
        }
        // The tempered variant's own fields are checked when it runs.
        let odd = format!("{m}hot_acceptance = 1.0\n");
        assert!(mcmc("spaceship", &odd).is_ok());
        let text = format!("{odd}variant = \"tempered\"\n");
        let key = mcmc("spaceship", &text).unwrap_err().key;
        assert_eq!(key, "optimizer.hot_acceptance");
    }

    #[test]
    fn set_overrides_reach_the_variant() {
        let text = "[optimizer]\nmethod = \"rjmcmc\"\n";
        let mut root: toml::Table = toml::from_str(text).unwrap();
        apply_overrides(&mut root, &["optimizer.variant=tempered".to_owned()]).unwrap();
        let table = root["optimizer"].as_table().unwrap().clone();
        let settings = resolve(&presets("spaceship"), table, None, &Overrides::default())
            .unwrap()
            .settings;
        let MethodSettings::Rjmcmc(s) = settings else {
            panic!("{settings:?}");
        };
        assert_eq!(s.variant, McmcVariant::Tempered);
    }

    #[test]
    fn typed_flags_set_the_fields_their_keys_name() {
        let spaceship = presets("spaceship");
        let flags = Overrides {
            method: Some(Method::Sosmc),
            seed: Some(9),
            seconds: Some(2.5),
            evaluations: Some(1000),
            generations: Some(7),
            islands: None,
            sets: Vec::new(),
        };
        let goal = resolve(&spaceship, toml::Table::new(), None, &flags).unwrap();
        let text = "method = \"sosmc\"\nseed = 9\nseconds = 2.5\nevaluations = 1000\n\
                    generations = 7\n";
        let keys = resolve(
            &spaceship,
            toml::from_str(text).unwrap(),
            None,
            &Overrides::default(),
        );
        assert_eq!(goal, keys.unwrap());
        let MethodSettings::Sosmc(s) = goal.settings else {
            panic!("{goal:?}");
        };
        assert_eq!((s.order, s.steps), (Order::Stochastic, 7));
        // Flags win over the table's keys.
        let table = toml::from_str("method = \"ga\"\nseed = 3\n").unwrap();
        let goal = resolve(&spaceship, table, None, &flags).unwrap();
        assert_eq!((goal.method(), goal.seed), (Method::Sosmc, 9));
        for (bad, key) in [
            (
                Overrides {
                    seconds: Some(-1.0),
                    ..Overrides::default()
                },
                "--seconds",
            ),
            (
                Overrides {
                    evaluations: Some(0),
                    ..Overrides::default()
                },
                "--evaluations",
            ),
        ] {
            let k = resolve(&spaceship, toml::Table::new(), None, &bad)
                .unwrap_err()
                .key;
            assert_eq!(k, key);
        }
    }

    #[test]
    fn a_value_of_the_wrong_type_is_refused_under_its_own_key() {
        let table = toml::from_str("population = \"abc\"\nelitism = 3\n").unwrap();
        let SettingsKeyError { key, cause } =
            resolve(&presets("spaceship"), table, None, &Overrides::default()).unwrap_err();
        assert_eq!(key, "optimizer.population");
        let reason = cause.to_string();
        assert!(reason.contains("abc"), "{reason}");
    }

    #[test]
    fn the_islands_flag_sets_the_count_over_the_table() {
        let spaceship = presets("spaceship");
        let written = IslandSettings {
            count: 2,
            migrants: 3,
            interval: 5,
        };
        let flag = Overrides {
            islands: Some(6),
            ..Overrides::default()
        };
        for (islands, overrides, count) in [
            (Some(written), &Overrides::default(), 2),
            (Some(written), &flag, 6),
            (None, &flag, 6),
        ] {
            let goal = resolve(&spaceship, toml::Table::new(), islands, overrides).unwrap();
            let (Some(s), MethodSettings::Ga(ga)) = (goal.islands, goal.settings) else {
                panic!("{goal:?}");
            };
            assert_eq!(s.count, count);
            assert_eq!(ga, spaceship.ga);
            let migrants = if islands.is_some() { 3 } else { 2 };
            assert_eq!(s.migrants, migrants, "the table's, or the default");
        }
        let plain = resolve(&spaceship, toml::Table::new(), None, &Overrides::default());
        assert!(matches!(plain.unwrap().settings, MethodSettings::Hybrid(_)));
        let rjmcmc = toml::from_str("method = \"rjmcmc\"\n").unwrap();
        let SettingsKeyError { key, cause } = resolve(&spaceship, rjmcmc, None, &flag).unwrap_err();
        assert_eq!(key, "islands");
        let reason = cause.to_string();
        assert!(reason.contains("runs the GA"), "{reason}");
    }
}

#[cfg(test)]
mod polish_tests {
    use super::*;

    #[test]
    fn every_single_fitness_method_reads_polish_and_the_original_rjmcmc_refuses_it() {
        let presets = crate::registry::Registry::published()
            .get("spaceship")
            .unwrap()
            .defaults
            .presets;
        let read = |text: &str| {
            let table: toml::Table = toml::from_str(text).unwrap();
            resolve(&presets, table, None, &Overrides::default()).map(|g| g.settings)
        };
        let with =
            |method: &str| format!("method = \"{method}\"\npolish = 8\npolish_sigma = 0.2\n");
        let polish = match read(&with("ga")).unwrap() {
            MethodSettings::Ga(s) => (s.polish, s.polish_sigma),
            other => panic!("{other:?}"),
        };
        assert_eq!(polish, (8, 0.2));
        for method in ["smc", "sosmc"] {
            let (MethodSettings::Smc(s) | MethodSettings::Sosmc(s)) = read(&with(method)).unwrap()
            else {
                panic!("{method}");
            };
            assert_eq!((s.polish, s.polish_sigma), (8, 0.2), "{method}");
        }
        let tempered = read(&(with("rjmcmc") + "variant = \"tempered\"\n")).unwrap();
        assert!(matches!(tempered, MethodSettings::Rjmcmc(s) if s.polish == 8));
        let SettingsKeyError { key, cause } = read(&with("rjmcmc")).unwrap_err();
        assert_eq!(key, "optimizer.polish");
        assert!(cause.to_string().contains("tempered"), "{cause}");
        let SettingsKeyError { key, .. } = read("method = \"ga\"\npolish = 1\n").unwrap_err();
        assert_eq!(key, "optimizer.polish");
    }
}

#[cfg(test)]
mod hybrid_tests {
    use super::*;
    use shapegen_runtime::optimize::{GaSettings, HybridSettings};

    fn hybrid(text: &str) -> Result<HybridSettings, SettingsKeyError> {
        let presets = crate::registry::Registry::published()
            .get("spaceship")
            .unwrap()
            .defaults
            .presets;
        let table: toml::Table = toml::from_str(&format!("method = \"hybrid\"\n{text}")).unwrap();
        match resolve(&presets, table, None, &Overrides::default())?.settings {
            MethodSettings::Hybrid(s) => Ok(s),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn hybrid_keys_are_its_own_or_its_gas() {
        let paper = generators::spaceship::paper_ga();
        let d = hybrid("").unwrap();
        assert_eq!(d, HybridSettings::over(paper));
        let s = hybrid(
            "refine = 2\nseed_steps = 5\nseed_share = 1.0\njump_probability = 0.2\n\
             population = 60\n",
        )
        .unwrap();
        assert_eq!(
            (s.refine, s.seed_steps, s.seed_share, s.jump_probability),
            (2, 5, 1.0, 0.2)
        );
        assert_eq!(
            s.ga,
            GaSettings {
                population: 60,
                polish: HybridSettings::POLISH,
                ..paper
            }
        );
        for (text, key) in [
            ("jump_probability = 2.0", "optimizer.jump_probability"),
            ("seed_steps = -1", "optimizer.seed_steps"),
            ("seed_share = 1.5", "optimizer.seed_share"),
            ("refine = -1", "optimizer.refine"),
            ("refine = 500", "optimizer.refine"),
            ("jump_probability = \"x\"", "optimizer.jump_probability"),
            ("elitism = 900", "optimizer.elitism"),
            ("operators = \"paper\"", "optimizer.operators"),
        ] {
            let SettingsKeyError { key: k, cause } = hybrid(text).unwrap_err();
            assert_eq!(k, key, "{text}: {cause}");
        }
        let reason = hybrid("refines = 2").unwrap_err().cause.to_string();
        assert!(reason.contains("refines"), "{reason}");
    }
}
