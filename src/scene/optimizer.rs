//! The `[optimizer]` table: which method searches, with what settings, seed and budget.

use std::time::Duration;

use generators::Published;
use serde::Serialize;
use serde::de::DeserializeOwned;
use shapegen_runtime::ops::OperatorVariant;
use shapegen_runtime::optimize::multi::MultiGaSettings;
use shapegen_runtime::optimize::{
    Budget, GaSettings, McmcSettings, McmcVariant, Order, SettingsError, SmcSettings, SmcVariant,
};

/// The search methods.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// The genetic algorithm.
    Ga,
    /// Sequential Monte Carlo, growing in chromosome order.
    Smc,
    /// Sequential Monte Carlo with stochastic futures.
    Sosmc,
    /// Reversible-jump MCMC with parallel tempering.
    Rjmcmc,
}

impl Method {
    /// Every method.
    pub const ALL: [Method; 4] = [Method::Ga, Method::Smc, Method::Sosmc, Method::Rjmcmc];

    /// Its name in scene files and on the command line.
    pub const fn name(self) -> &'static str {
        match self {
            Method::Ga => "ga",
            Method::Smc => "smc",
            Method::Sosmc => "sosmc",
            Method::Rjmcmc => "rjmcmc",
        }
    }
}

/// A method with its settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MethodSettings {
    /// The genetic algorithm.
    Ga(GaSettings),
    /// SMC or SOSMC (its `order` says which).
    Smc(SmcSettings),
    /// Reversible-jump MCMC.
    Mcmc(McmcSettings),
}

/// The `[optimizer]` table, resolved. Keys the method does not know are refused.
///
/// ```toml
/// [optimizer]
/// method = "ga"          # ga, smc, sosmc or rjmcmc
/// seed = 1
/// seconds = 60           # wall-time budget (optional)
/// evaluations = 100000   # evaluation budget (optional)
/// generations = 100      # GA generations, SMC steps, RJMCMC iterations
///                        # then the method's own settings: for the GA population,
/// population = 100       # elitism, initial_length, generations, mutation_probability,
///                        # grow_weight, cut_weight, alter_weight, tournament,
///                        # operators ("original" or "weighted"), cross_array_index
///                        # (true or false); for SMC and SOSMC particles, steps,
///                        # variant ("original" or "generative"),
///                        # step_back_probability, max_grows_per_step; for RJMCMC
///                        # variant ("original" or "tempered"), chains, iterations,
///                        # initial_length, jump_probability, ...
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
    /// The method.
    pub method: Method,
    /// Seed of every random stream of the run.
    pub seed: u64,
    /// Wall-time budget.
    pub seconds: Option<f64>,
    /// Evaluation budget.
    pub evaluations: Option<u64>,
    /// The method's settings.
    pub settings: MethodSettings,
}

impl OptimizerGoal {
    /// Generations (steps, iterations) the method's settings ask for.
    pub fn generations(&self) -> u64 {
        match self.settings {
            MethodSettings::Ga(s) => s.generations,
            MethodSettings::Smc(s) => s.steps,
            MethodSettings::Mcmc(s) => s.iterations,
        }
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
}

/// The paper's settings of `method` for `generator`'s scene.
fn paper(method: Method, generator: Published) -> MethodSettings {
    use Published::{Building, City, Spaceship, Tree};
    let order = if method == Method::Sosmc {
        Order::Stochastic
    } else {
        Order::Chromosome
    };
    match (method, generator) {
        (Method::Ga, Spaceship) => MethodSettings::Ga(GaSettings::paper_spaceship()),
        (Method::Ga, Tree) => MethodSettings::Ga(GaSettings::paper_tree()),
        (Method::Ga, City) => MethodSettings::Ga(GaSettings::paper_city()),
        (Method::Ga, Building) => MethodSettings::Ga(MultiGaSettings::thesis().ga),
        (Method::Smc | Method::Sosmc, Spaceship) => {
            MethodSettings::Smc(SmcSettings::paper_spaceship(order))
        }
        (Method::Smc | Method::Sosmc, Tree) => MethodSettings::Smc(SmcSettings::paper_tree(order)),
        (Method::Smc | Method::Sosmc, City | Building) => {
            MethodSettings::Smc(SmcSettings::paper_city(order))
        }
        (Method::Rjmcmc, Spaceship) => MethodSettings::Mcmc(McmcSettings::paper_spaceship()),
        (Method::Rjmcmc, Tree) => MethodSettings::Mcmc(McmcSettings::paper_tree()),
        (Method::Rjmcmc, City | Building) => MethodSettings::Mcmc(McmcSettings::paper_city()),
    }
}

/// `base` with the keys of `table` over it, checked by `validate`.
fn merged<T: Serialize + DeserializeOwned>(
    base: T,
    table: toml::Table,
    validate: impl Fn(&T) -> Result<(), SettingsError>,
) -> Result<T, (String, String)> {
    let mut merged =
        toml::Table::try_from(base).map_err(|err| (String::from("optimizer"), err.to_string()))?;
    merged.extend(table);
    let settings: T = toml::Value::Table(merged)
        .try_into()
        .map_err(|err: toml::de::Error| (String::from("optimizer"), err.message().to_owned()))?;
    validate(&settings).map_err(|err| (format!("optimizer.{}", err.field), err.to_string()))?;
    Ok(settings)
}

/// Resolves the `[optimizer]` table over the paper's settings for the method and the
/// generator; errors are `(key, reason)`.
pub(super) fn resolve(
    generator: Published,
    mut table: toml::Table,
) -> Result<OptimizerGoal, (String, String)> {
    let key = |k: &str| format!("optimizer.{k}");
    let method = match table.remove("method") {
        None => Method::Ga,
        Some(toml::Value::String(m)) => Method::ALL
            .into_iter()
            .find(|x| x.name() == m)
            .ok_or_else(|| {
                (
                    key("method"),
                    format!("\"{m}\" is not a method; the methods are ga, smc, sosmc and rjmcmc"),
                )
            })?,
        Some(other) => {
            return Err((
                key("method"),
                format!("{other} is not a method; the methods are ga, smc, sosmc and rjmcmc"),
            ));
        }
    };
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
    // `generations` names the GA's generations, SMC's steps and RJMCMC's iterations.
    let rename = |table: &mut toml::Table, to: &str| {
        if let Some(g) = table.remove("generations") {
            table.insert(to.to_owned(), g);
        }
    };
    let settings = match paper(method, generator) {
        MethodSettings::Ga(base) => {
            check_ga_keys(&table)?;
            MethodSettings::Ga(merged(base, table, GaSettings::validate)?)
        }
        MethodSettings::Smc(base) => {
            if table.contains_key("order") {
                return Err((
                    key("order"),
                    "is set by the method: \"smc\" or \"sosmc\"".into(),
                ));
            }
            check_smc_variant(&table)?;
            rename(&mut table, "steps");
            MethodSettings::Smc(merged(base, table, SmcSettings::validate)?)
        }
        MethodSettings::Mcmc(base) => {
            check_mcmc_variant(&table)?;
            rename(&mut table, "iterations");
            MethodSettings::Mcmc(merged(base, table, McmcSettings::validate)?)
        }
    };
    Ok(OptimizerGoal {
        method,
        seed,
        seconds,
        evaluations,
        settings,
    })
}

/// Checks the GA's keys whose serde errors would not name them: `operators` must name an
/// operator variant and `cross_array_index` be a boolean; errors are `(key, reason)`.
fn check_ga_keys(table: &toml::Table) -> Result<(), (String, String)> {
    let names = OperatorVariant::ALL.map(OperatorVariant::name);
    match table.get("operators") {
        None => {}
        Some(toml::Value::String(v)) if names.contains(&v.as_str()) => {}
        Some(other) => {
            return Err((
                "optimizer.operators".into(),
                format!(
                    "{other} is not an operator variant; the variants are \"{}\"",
                    names.join("\" and \"")
                ),
            ));
        }
    }
    match table.get("cross_array_index") {
        None | Some(toml::Value::Boolean(_)) => Ok(()),
        Some(other) => Err((
            "optimizer.cross_array_index".into(),
            format!("{other} must be true or false"),
        )),
    }
}

/// Checks that SMC's `variant`, whose serde error would not name it, names an SMC
/// variant; errors are `(key, reason)`.
fn check_smc_variant(table: &toml::Table) -> Result<(), (String, String)> {
    let names = SmcVariant::ALL.map(SmcVariant::name);
    match table.get("variant") {
        None => Ok(()),
        Some(toml::Value::String(v)) if names.contains(&v.as_str()) => Ok(()),
        Some(other) => Err((
            "optimizer.variant".into(),
            format!(
                "{other} is not an SMC variant; the variants are \"{}\"",
                names.join("\" and \"")
            ),
        )),
    }
}

/// Checks RJMCMC's `variant`, whose serde error would not name it: it must name a
/// [`McmcVariant`]; errors are `(key, reason)`.
fn check_mcmc_variant(table: &toml::Table) -> Result<(), (String, String)> {
    let names = McmcVariant::ALL.map(McmcVariant::name);
    match table.get("variant") {
        None => Ok(()),
        Some(toml::Value::String(v)) if names.contains(&v.as_str()) => Ok(()),
        Some(other) => Err((
            "optimizer.variant".into(),
            format!(
                "{other} is not an RJMCMC variant; the variants are \"{}\"",
                names.join("\" and \"")
            ),
        )),
    }
}

/// Takes `archive` (the multi-objective GA's archive size) out of an `[optimizer]`
/// table: its value, or the default of [`MultiGaSettings`]; errors are `(key, reason)`.
pub(super) fn take_archive(table: &mut toml::Table) -> Result<u32, (String, String)> {
    match table.remove("archive") {
        None => Ok(MultiGaSettings::default().archive),
        Some(toml::Value::Integer(n)) if (1..=i64::from(u32::MAX)).contains(&n) => Ok(n as u32),
        Some(other) => Err((
            "optimizer.archive".into(),
            format!("{other} must be a whole number >= 1"),
        )),
    }
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

#[cfg(test)]
mod mcmc_tests {
    use super::*;

    fn mcmc(generator: Published, text: &str) -> Result<McmcSettings, (String, String)> {
        let table: toml::Table = toml::from_str(text).unwrap();
        match resolve(generator, table)?.settings {
            MethodSettings::Mcmc(s) => Ok(s),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn rjmcmc_takes_its_variant_over_the_originals_settings() {
        let m = "method = \"rjmcmc\"\n";
        for (generator, paper) in [
            (Published::Spaceship, McmcSettings::paper_spaceship()),
            (Published::Tree, McmcSettings::paper_tree()),
            (Published::City, McmcSettings::paper_city()),
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
            let (key, reason) = mcmc(Published::Tree, &text).unwrap_err();
            assert_eq!(key, "optimizer.variant");
            assert!(reason.contains("\"original\" and \"tempered\""), "{reason}");
        }
        // The tempered variant's own fields are checked when it runs.
        let odd = format!("{m}hot_acceptance = 1.0\n");
        assert!(mcmc(Published::Spaceship, &odd).is_ok());
        let text = format!("{odd}variant = \"tempered\"\n");
        let (key, _) = mcmc(Published::Spaceship, &text).unwrap_err();
        assert_eq!(key, "optimizer.hot_acceptance");
    }

    #[test]
    fn set_overrides_reach_the_variant() {
        let text = "[optimizer]\nmethod = \"rjmcmc\"\n";
        let mut root: toml::Table = toml::from_str(text).unwrap();
        apply_overrides(&mut root, &["optimizer.variant=tempered".to_owned()]).unwrap();
        let table = root["optimizer"].as_table().unwrap().clone();
        let settings = resolve(Published::Spaceship, table).unwrap().settings;
        let MethodSettings::Mcmc(s) = settings else {
            panic!("{settings:?}");
        };
        assert_eq!(s.variant, McmcVariant::Tempered);
    }
}
