//! The `[optimizer]` table: which method searches, with what settings, seed and budget.

use std::time::Duration;

use generators::Published;
use shapegen_runtime::optimize::{Budget, GaSettings};

/// The `[optimizer]` table, resolved. Keys the method does not know are refused.
///
/// ```toml
/// [optimizer]
/// method = "ga"          # the genetic algorithm
/// seed = 1
/// seconds = 60           # wall-time budget (optional)
/// evaluations = 100000   # evaluation budget (optional)
/// generations = 100      # the GA's settings: population, elitism, initial_length,
/// population = 100       # generations, mutation_probability, grow_weight,
///                        # cut_weight, alter_weight, tournament
/// ```
///
/// Settings the table leaves out are the paper's for the scene's generator.
#[derive(Clone, Debug, PartialEq)]
pub struct OptimizerGoal {
    /// Seed of every random stream of the run.
    pub seed: u64,
    /// Wall-time budget.
    pub seconds: Option<f64>,
    /// Evaluation budget.
    pub evaluations: Option<u64>,
    /// The genetic algorithm's settings.
    pub ga: GaSettings,
}

impl OptimizerGoal {
    /// The run's budget: the settings' generations, and the time and evaluation limits
    /// when given.
    pub fn budget(&self) -> Budget {
        let mut budget = self.ga.budget();
        if let Some(s) = self.seconds {
            budget = budget.and_wall_time(Duration::from_secs_f64(s));
        }
        if let Some(n) = self.evaluations {
            budget = budget.and_evaluations(n);
        }
        budget
    }
}

/// The paper's GA settings for `generator`'s scene.
pub(super) fn paper_ga(generator: Published) -> GaSettings {
    match generator {
        Published::Spaceship => GaSettings::paper_spaceship(),
        Published::Tree => GaSettings::paper_tree(),
        Published::City => GaSettings::paper_city(),
    }
}

/// Resolves the `[optimizer]` table over the generator's paper settings; errors are
/// `(key, reason)`.
pub(super) fn resolve(
    generator: Published,
    mut table: toml::Table,
) -> Result<OptimizerGoal, (String, String)> {
    let key = |k: &str| format!("optimizer.{k}");
    match table.remove("method") {
        None => {}
        Some(toml::Value::String(m)) if m == "ga" => {}
        Some(other) => {
            return Err((
                key("method"),
                format!("{other} is not a method; the method is \"ga\""),
            ));
        }
    }
    let seed = match table.remove("seed") {
        None => 1,
        Some(toml::Value::Integer(s)) if s >= 0 => s as u64,
        Some(other) => return Err((key("seed"), format!("{other} must be a whole number >= 0"))),
    };
    let seconds = match table.remove("seconds") {
        None => None,
        Some(v) => match v.as_float().or(v.as_integer().map(|i| i as f64)) {
            Some(s) if s.is_finite() && s > 0.0 => Some(s),
            _ => {
                return Err((
                    key("seconds"),
                    format!("{v} must be a number of seconds > 0"),
                ));
            }
        },
    };
    let evaluations = match table.remove("evaluations") {
        None => None,
        Some(toml::Value::Integer(n)) if n > 0 => Some(n as u64),
        Some(other) => {
            return Err((
                key("evaluations"),
                format!("{other} must be a whole number > 0"),
            ));
        }
    };
    // The paper's settings, with the table's keys over them.
    let mut merged = toml::Table::try_from(paper_ga(generator))
        .map_err(|err| (key("method"), err.to_string()))?;
    merged.extend(table);
    let ga: GaSettings = toml::Value::Table(merged)
        .try_into()
        .map_err(|err: toml::de::Error| (String::from("optimizer"), err.message().to_owned()))?;
    ga.validate()
        .map_err(|err| (key(err.field), err.to_string()))?;
    Ok(OptimizerGoal {
        seed,
        seconds,
        evaluations,
        ga,
    })
}

/// Applies `key=value` overrides (`--set optimizer.population=200`) to a scene's TOML
/// tree. The value is read as TOML (a number, a boolean, an array, a quoted string) or,
/// when it is none of those, as a bare string.
pub(super) fn apply_overrides(root: &mut toml::Table, sets: &[String]) -> Result<(), String> {
    for set in sets {
        let Some((path, value)) = set.split_once('=') else {
            return Err(format!(
                "--set {set}: write it as key=value, e.g. optimizer.seed=3"
            ));
        };
        let value = toml::from_str::<toml::Table>(&format!("v = {value}"))
            .ok()
            .and_then(|mut t| t.remove("v"))
            .unwrap_or_else(|| toml::Value::String(value.to_owned()));
        let keys: Vec<&str> = path.trim().split('.').collect();
        if keys.iter().any(|k| k.is_empty()) {
            return Err(format!("--set {set}: `{path}` is not a dotted key"));
        }
        let mut table = &mut *root;
        for k in &keys[..keys.len() - 1] {
            let entry = table
                .entry(k.to_string())
                .or_insert_with(|| toml::Value::Table(toml::Table::new()));
            table = entry
                .as_table_mut()
                .ok_or_else(|| format!("--set {set}: `{k}` is not a table"))?;
        }
        table.insert(keys[keys.len() - 1].to_owned(), value);
    }
    Ok(())
}
