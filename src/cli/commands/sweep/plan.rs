//! A study's plan, `plan.json`: what is swept, over which runs and budget, and from it
//! the list of cells, each one run of one grid point.
//!
//! Grid points are the combinations of the `--grid` values in the order given, the
//! first key outermost: with `--grid a=1,2 --grid b=x,y` the points are (1, x), (1, y),
//! (2, x), (2, y). Cell `p * runs + r` is run `r` of point `p`, on seed `seed + r`, so
//! the cell indices are fixed by the plan alone.

use std::path::{Path, PathBuf};
use std::time::Duration;

use anyhow::Context;
use serde::{Deserialize, Serialize};
use shapegen::optimize::Budget;
use shapegen::scene::{Method, Overrides, Scene};

use crate::cli::backend::BackendArgs;
use crate::cli::files::{atomic_write, read};
use crate::registry::Registry;

/// The file a study's plan is saved in, in the study's folder.
const PLAN_FILE: &str = "plan.json";

/// Scene keys a grid or `--set` may not name: every cell has the same budget, and its
/// seed is the plan's seed plus its run.
const RESERVED: [(&str, &str); 4] = [
    (
        "optimizer.seed",
        "each run's seed is --seed + r; vary seeds with --runs",
    ),
    (
        "optimizer.seconds",
        "every cell has the budget --seconds, --evaluations or --generations gives",
    ),
    (
        "optimizer.evaluations",
        "every cell has the budget --seconds, --evaluations or --generations gives",
    ),
    (
        "optimizer.generations",
        "every cell has the budget --seconds, --evaluations or --generations gives",
    ),
];

/// One swept key and its values, as given (`--grid KEY=V1,V2,..`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Axis {
    /// A scene key, as `--set` takes it.
    pub key: String,
    /// Its values, each as `--set` takes a value.
    pub values: Vec<String>,
}

impl Axis {
    /// Reads `KEY=V1,V2,..`. Values are split at commas outside brackets and quotes, so
    /// that arrays and quoted strings with commas stay one value.
    pub fn parse(text: &str) -> anyhow::Result<Axis> {
        let usage =
            || format!("--grid {text}: write it as KEY=V1,V2,.., e.g. optimizer.population=50,100");
        let (key, values) = text.split_once('=').with_context(usage)?;
        let key = key.trim();
        anyhow::ensure!(!key.is_empty(), "{}", usage());
        let values: Vec<String> = split_values(values);
        anyhow::ensure!(
            values.iter().all(|v| !v.is_empty()),
            "--grid {text}: a value is empty; {}",
            usage()
        );
        for (i, v) in values.iter().enumerate() {
            anyhow::ensure!(
                !values[..i].contains(v),
                "--grid {text}: the value `{v}` is listed twice"
            );
        }
        Ok(Axis {
            key: key.to_owned(),
            values,
        })
    }
}

/// `text` split at the commas outside `[..]`, `{..}` and quotes, each part trimmed.
fn split_values(text: &str) -> Vec<String> {
    let mut parts = vec![String::new()];
    let (mut depth, mut quote) = (0i32, None);
    for c in text.chars() {
        match (quote, c) {
            (Some(q), _) if c == q => quote = None,
            (None, '"' | '\'') => quote = Some(c),
            (None, '[' | '{') => depth += 1,
            (None, ']' | '}') => depth -= 1,
            (None, ',') if depth == 0 => {
                parts.push(String::new());
                continue;
            }
            _ => {}
        }
        parts.last_mut().expect("never empty").push(c);
    }
    parts.iter().map(|p| p.trim().to_owned()).collect()
}

/// Each cell's budget: the one limit of its run.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum StudyBudget {
    /// Wall time in seconds: results depend on the machine's speed and load.
    Seconds(f64),
    /// Fitness evaluations.
    Evaluations(u64),
    /// Generations (steps, iterations) after the initial population.
    Generations(u64),
}

impl StudyBudget {
    /// The budget from the flags, of which exactly one must be given.
    pub fn from_flags(
        seconds: Option<f64>,
        evaluations: Option<u64>,
        generations: Option<u64>,
    ) -> anyhow::Result<StudyBudget> {
        let budget = match (seconds, evaluations, generations) {
            (Some(s), None, None) => {
                anyhow::ensure!(
                    s.is_finite() && s > 0.0,
                    "--seconds {s}: give a wall-time budget of more than 0 seconds"
                );
                StudyBudget::Seconds(s)
            }
            (None, Some(n), None) => {
                anyhow::ensure!(n > 0, "--evaluations 0: give at least 1 evaluation");
                StudyBudget::Evaluations(n)
            }
            (None, None, Some(n)) => StudyBudget::Generations(n),
            _ => anyhow::bail!(
                "give each run's budget by one of --evaluations, --generations or --seconds"
            ),
        };
        Ok(budget)
    }

    /// The run's budget: this one limit alone (a scene's or method's own generations,
    /// seconds or evaluations do not stop a cell).
    pub fn budget(self) -> Budget {
        match self {
            StudyBudget::Seconds(s) => Budget {
                wall_time: Some(Duration::from_secs_f64(s)),
                ..Budget::default()
            },
            StudyBudget::Evaluations(n) => Budget::evaluations(n),
            StudyBudget::Generations(n) => Budget::generations(n),
        }
    }

    /// In words, for a summary: "40000 evaluations", say.
    pub fn describe(self) -> String {
        match self {
            StudyBudget::Seconds(s) => format!("{s} s of wall time"),
            StudyBudget::Evaluations(n) => format!("{n} evaluations"),
            StudyBudget::Generations(n) => format!("{n} generations"),
        }
    }
}

/// A study: what `plan.json` holds. Two commands that make the same plan make the same
/// study, and the second goes on with the first's cells.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Plan {
    /// The version of shapegen that made the plan; another version refuses it.
    pub version: String,
    /// The scene file, as an absolute path.
    pub scene: PathBuf,
    /// The swept keys, the first outermost.
    pub grid: Vec<Axis>,
    /// Runs of each grid point.
    pub runs: u64,
    /// Each run's budget.
    pub budget: StudyBudget,
    /// Run `r` of every grid point uses seed `seed + r`.
    pub seed: u64,
    /// The method of every run (`--method`), unless the grid or the scene names it.
    pub method: Option<Method>,
    /// `--set` overrides of every run, before the grid's.
    pub sets: Vec<String>,
    /// The backend flags.
    pub backend: BackendArgs,
    /// The scene's optimum (`fitness.optimum`), when it gives one, the same at every
    /// grid point.
    #[serde(default)]
    pub optimum: Option<f64>,
}

/// One cell of a plan: run `run` of grid point `point`, on seed `seed`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Cell {
    /// Its index in the plan.
    pub index: u64,
    /// Its grid point's index.
    pub point: u64,
    /// Its run, from 0.
    pub run: u64,
    /// Its seed.
    pub seed: u64,
}

impl Plan {
    /// The version this binary writes into plans.
    pub const VERSION: &'static str = env!("CARGO_PKG_VERSION");

    /// Checks a new plan: its keys and every grid point's scene, loaded before any run
    /// starts so that a bad value fails at once, naming the point. A plan made without
    /// `--seed` takes the scene's `optimizer.seed` (`seed: None`).
    pub fn checked(mut self, seed: Option<u64>, registry: &Registry) -> anyhow::Result<Plan> {
        anyhow::ensure!(self.runs >= 1, "--runs {}: give at least 1 run", self.runs);
        anyhow::ensure!(
            !self.grid.is_empty(),
            "give at least one --grid KEY=V1,V2,.., e.g. --grid optimizer.population=50,100"
        );
        for (i, axis) in self.grid.iter().enumerate() {
            anyhow::ensure!(
                !self.grid[..i].iter().any(|a| a.key == axis.key),
                "--grid {}: the key is swept twice; give all its values in one --grid",
                axis.key
            );
            if axis.key == "optimizer.method" {
                anyhow::ensure!(
                    self.method.is_none(),
                    "--grid optimizer.method and --method both set the method; give one"
                );
            }
        }
        let given =
            self.grid
                .iter()
                .map(|a| ("--grid", a.key.as_str()))
                .chain(self.sets.iter().map(|s| {
                    (
                        "--set",
                        s.split_once('=').map_or(s.as_str(), |(k, _)| k.trim()),
                    )
                }));
        for (flag, key) in given {
            if let Some((_, why)) = RESERVED.iter().find(|(k, _)| *k == key) {
                anyhow::bail!("{flag} {key}: a sweep sets it: {why}");
            }
        }
        self.seed = seed.unwrap_or(0);
        for point in 0..self.points() {
            let overrides = self.overrides_at(point, None);
            let scene = Scene::open(&self.scene, registry, &overrides)
                .with_context(|| format!("grid point {}", self.describe(point)))?;
            anyhow::ensure!(
                scene.objectives.is_none(),
                "`{}` has [[objective]] tables: a sweep measures runs by one fitness, and a \
                 multi-objective scene is searched by the multi-objective GA (`shapegen run`)",
                self.scene.display()
            );
            if point == 0 {
                if seed.is_none() {
                    self.seed = scene.optimizer.seed;
                }
                self.optimum = scene.optimum;
            }
            anyhow::ensure!(
                scene.optimum == self.optimum,
                "grid point {}: fitness.optimum is {:?} there and {:?} at the first point; \
                 a sweep measures every point against one optimum",
                self.describe(point),
                scene.optimum,
                self.optimum
            );
        }
        anyhow::ensure!(
            self.seed.checked_add(self.runs - 1).is_some(),
            "--seed {}: with {} runs the seeds would pass {}",
            self.seed,
            self.runs,
            u64::MAX
        );
        Ok(self)
    }

    /// Grid points: the product of the axes' value counts.
    pub fn points(&self) -> u64 {
        self.grid.iter().map(|a| a.values.len() as u64).product()
    }

    /// Cells: runs of every grid point.
    pub fn cells(&self) -> u64 {
        self.points() * self.runs
    }

    /// Cell `index`; it must be below [`cells`](Self::cells).
    pub fn cell(&self, index: u64) -> Cell {
        let (point, run) = (index / self.runs, index % self.runs);
        Cell {
            index,
            point,
            run,
            seed: self.seed + run,
        }
    }

    /// The value index of each axis at grid point `point`, the first axis first.
    pub fn coordinates(&self, point: u64) -> Vec<usize> {
        let mut rest = point;
        let mut coordinates = vec![0; self.grid.len()];
        for (c, axis) in coordinates.iter_mut().zip(&self.grid).rev() {
            let n = axis.values.len() as u64;
            *c = (rest % n) as usize;
            rest /= n;
        }
        coordinates
    }

    /// Each axis's value at grid point `point`.
    pub fn values(&self, point: u64) -> Vec<&str> {
        self.coordinates(point)
            .iter()
            .zip(&self.grid)
            .map(|(&c, axis)| axis.values[c].as_str())
            .collect()
    }

    /// Grid point `point` as `key=value, key=value`.
    pub fn describe(&self, point: u64) -> String {
        self.grid
            .iter()
            .zip(self.values(point))
            .map(|(axis, v)| format!("{}={v}", axis.key))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// What cell `cell` runs with over the scene: the plan's flags and `--set`s, then its
    /// grid point's values, and its seed.
    pub fn overrides(&self, cell: Cell) -> Overrides {
        self.overrides_at(cell.point, Some(cell.seed))
    }

    /// What the cells of grid point `point` run with, seed aside (`seed`: the cell's).
    pub fn overrides_at(&self, point: u64, seed: Option<u64>) -> Overrides {
        let (mut seconds, mut evaluations, mut generations) = (None, None, None);
        match self.budget {
            StudyBudget::Seconds(s) => seconds = Some(s),
            StudyBudget::Evaluations(n) => evaluations = Some(n),
            StudyBudget::Generations(n) => generations = Some(n),
        }
        let grid = self
            .grid
            .iter()
            .zip(self.values(point))
            .map(|(axis, v)| format!("{}={v}", axis.key));
        Overrides {
            method: self.method,
            seed,
            seconds,
            evaluations,
            generations,
            sets: self.sets.iter().cloned().chain(grid).collect(),
            ..Overrides::default()
        }
    }

    /// Writes the plan into study folder `dir`, or, when `dir` holds one already, checks
    /// that it is this plan: a different study there is refused, saying what differs.
    pub fn save_or_match(&self, dir: &Path) -> anyhow::Result<()> {
        let path = dir.join(PLAN_FILE);
        if !path.exists() {
            return atomic_write(&path, serde_json::to_string_pretty(self)?.as_bytes());
        }
        let saved = Plan::load(dir)?;
        let differences = saved.differences(self)?;
        anyhow::ensure!(
            differences.is_empty(),
            "`{}` holds another study: {}. Rerun that study's own command to go on with it, \
             give --force to replace it with this one, or give this one a new --out",
            dir.display(),
            differences.join("; ")
        );
        Ok(())
    }

    /// The plan saved in study folder `dir`, made by this version of shapegen.
    pub fn load(dir: &Path) -> anyhow::Result<Plan> {
        let path = dir.join(PLAN_FILE);
        let plan: Plan = serde_json::from_str(&read(&path)?).with_context(|| {
            format!(
                "`{}` is not a sweep plan (of this version of shapegen, {})",
                path.display(),
                Plan::VERSION
            )
        })?;
        anyhow::ensure!(
            plan.version == Plan::VERSION,
            "`{}` was made by shapegen {}, and this is {}: its cells would not be comparable; \
             run the study with that version, or again from the start with a new --out",
            path.display(),
            plan.version,
            Plan::VERSION
        );
        Ok(plan)
    }

    /// The fields in which `other` differs from this plan, each as `field: this there,
    /// that now`.
    fn differences(&self, other: &Plan) -> anyhow::Result<Vec<String>> {
        let (serde_json::Value::Object(saved), serde_json::Value::Object(given)) =
            (serde_json::to_value(self)?, serde_json::to_value(other)?)
        else {
            anyhow::bail!("a plan is a JSON object");
        };
        Ok(saved
            .iter()
            .filter(|&(field, value)| given.get(field) != Some(value))
            .map(|(field, value)| {
                let now = given.get(field).unwrap_or(&serde_json::Value::Null);
                format!("{field} is {value} there and {now} now")
            })
            .collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plan(grid: &[&str], runs: u64) -> Plan {
        Plan {
            version: Plan::VERSION.to_owned(),
            scene: PathBuf::from("/scene.toml"),
            grid: grid.iter().map(|g| Axis::parse(g).unwrap()).collect(),
            runs,
            budget: StudyBudget::Evaluations(1000),
            seed: 5,
            method: None,
            sets: vec!["optimizer.tournament=3".to_owned()],
            backend: BackendArgs::default(),
            optimum: None,
        }
    }

    #[test]
    fn values_split_at_commas_outside_brackets_and_quotes() {
        let axis = Axis::parse("volume.grid.resolution=[10, 20, 10], [20,40,20]").unwrap();
        assert_eq!(axis.key, "volume.grid.resolution");
        assert_eq!(axis.values, ["[10, 20, 10]", "[20,40,20]"]);
        let axis = Axis::parse(r#"a.b="x,y",z"#).unwrap();
        assert_eq!(axis.values, [r#""x,y""#, "z"]);
        for bad in ["population", "=1,2", "a=1,,2", "a=1,2,1"] {
            assert!(Axis::parse(bad).is_err(), "{bad}");
        }
        assert!(
            Axis::parse("a=1,2,1")
                .unwrap_err()
                .to_string()
                .contains("`1` is listed twice")
        );
    }

    #[test]
    fn cells_run_inner_and_the_first_key_outermost() {
        let p = plan(&["a=1,2", "b=x,y,z"], 2);
        assert_eq!((p.points(), p.cells()), (6, 12));
        assert_eq!(p.values(0), ["1", "x"]);
        assert_eq!(p.values(2), ["1", "z"]);
        assert_eq!(p.values(3), ["2", "x"]);
        assert_eq!(p.describe(5), "a=2, b=z");
        let cell = p.cell(7);
        assert_eq!(
            cell,
            Cell {
                index: 7,
                point: 3,
                run: 1,
                seed: 6
            }
        );
        let o = p.overrides(cell);
        assert_eq!(o.seed, Some(6));
        assert_eq!(o.evaluations, Some(1000));
        assert_eq!(o.sets, ["optimizer.tournament=3", "a=2", "b=x"]);
    }

    #[test]
    fn differences_name_each_field() {
        let a = plan(&["a=1,2"], 2);
        let mut b = plan(&["a=1,3"], 2);
        assert!(a.differences(&a).unwrap().is_empty());
        b.runs = 3;
        let d = a.differences(&b).unwrap();
        assert_eq!(d.len(), 2, "{d:?}");
        assert!(d[0].starts_with("grid is "), "{d:?}");
        assert_eq!(d[1], "runs is 2 there and 3 now");
    }

    #[test]
    fn one_budget_is_given() {
        assert_eq!(
            StudyBudget::from_flags(None, Some(5), None).unwrap(),
            StudyBudget::Evaluations(5)
        );
        assert!(StudyBudget::from_flags(None, None, None).is_err());
        assert!(StudyBudget::from_flags(Some(1.0), Some(5), None).is_err());
        assert!(StudyBudget::from_flags(Some(-1.0), None, None).is_err());
        let b = StudyBudget::Generations(4).budget();
        assert_eq!(
            (b.generations, b.evaluations, b.wall_time),
            (Some(4), None, None)
        );
    }
}
