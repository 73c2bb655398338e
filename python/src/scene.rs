//! Scenes as Python objects: opened from a file, or built from TOML and arrays; their
//! searches, run with the GIL released; scoring, sampling and models in their terms.

use std::path::PathBuf;
use std::sync::atomic::AtomicBool;
use std::sync::{Arc, OnceLock};

use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict};
use shapegen::Limits;
use shapegen::gpu::GpuContext;
use shapegen::optimize::Control;
use shapegen::scene::{BackendChoice, Method, Overrides, Scene as Goal, Sources};

use crate::catalog::Catalog;
use crate::checkpoint;
use crate::compared::{ComparedRun, Comparison, Front, FrontMember, FrontProgress, MethodSummary};
use crate::error::Error;
use crate::objects::{self, Genome, Model, Progress, Run, limits_dict};
use crate::typed::{ComparedText, Counting, Erased, FrontStep, Step};
use shapegen::search::{Compare, CompareError, SaveHook};

/// Where a scene was read from, to read it again with other overrides.
#[derive(Clone)]
pub enum Origin {
    /// A scene file.
    File(PathBuf),
    /// TOML text as if read from `path`, with targets in memory.
    Text {
        /// The text.
        text: String,
        /// The path it is read as.
        path: PathBuf,
        /// Its targets in memory.
        sources: Sources,
    },
}

impl Origin {
    /// Reads the scene with `overrides`.
    pub fn read(&self, catalog: &Catalog, overrides: &Overrides) -> Result<Goal, Error> {
        let registry = catalog.registry();
        match self {
            Origin::File(path) => Goal::open(path, registry, overrides),
            Origin::Text {
                text,
                path,
                sources,
            } => Goal::parse_with(text, path, registry, overrides, sources),
        }
        .map_err(Error::scene)
    }
}

/// A scene: the generator, its targets and limits, and the search's method, settings,
/// seed and budget.
#[pyclass(frozen, name = "Scene")]
pub struct Scene {
    catalog: Arc<Catalog>,
    origin: Origin,
    overrides: Overrides,
    goal: Goal,
    erased: Arc<dyn Erased>,
}

/// The keyword arguments that override a scene's settings, as the tool's flags.
const SETTINGS: &str = "method, seed, seconds, evaluations, generations and set";

/// The overrides of a scene's settings that keyword arguments give: `method`, `seed`,
/// `seconds`, `evaluations` and `generations` as the tool's flags, `set` as its
/// `--set`s.
pub fn overrides(settings: Option<&Bound<'_, PyDict>>) -> PyResult<Overrides> {
    let mut overrides = Overrides::default();
    for (key, value) in settings.into_iter().flat_map(|d| d.iter()) {
        let key: String = key.extract()?;
        let value = &value;
        let bad = |what: &str| Error::Value(format!("{key} must be {what}"));
        match key.as_str() {
            _ if value.is_none() => {}
            "method" => {
                let name: String = value.extract().map_err(|_| bad("a method's name"))?;
                let method = name.parse::<Method>();
                overrides.method = Some(method.map_err(|err| Error::Value(err.to_string()))?);
            }
            "seed" => {
                overrides.seed = Some(value.extract().map_err(|_| bad("a whole number >= 0"))?)
            }
            "seconds" => {
                overrides.seconds = Some(value.extract().map_err(|_| bad("a number of seconds"))?)
            }
            "evaluations" => {
                overrides.evaluations =
                    Some(value.extract().map_err(|_| bad("a whole number > 0"))?);
            }
            "generations" => {
                overrides.generations =
                    Some(value.extract().map_err(|_| bad("a whole number >= 0"))?);
            }
            "set" => {
                overrides.sets = value
                    .extract()
                    .map_err(|_| bad("a list of \"key=value\" strings"))?;
            }
            _ => {
                return Err(Error::Value(format!(
                    "unknown setting `{key}`; the settings are {SETTINGS}"
                ))
                .into());
            }
        }
    }
    Ok(overrides)
}

/// A run folder a search saves its checkpoint in, and the state it goes on from.
pub struct Folder {
    /// The folder.
    pub dir: PathBuf,
    /// The overrides the checkpoint records.
    pub overrides: Overrides,
    /// The saved state to resume from, as JSON.
    pub resume: Option<String>,
}

/// The GPU, opened once per process; `None` where there is none.
fn gpu() -> Option<&'static GpuContext> {
    static GPU: OnceLock<Option<GpuContext>> = OnceLock::new();
    GPU.get_or_init(|| GpuContext::new().ok()).as_ref()
}

/// The backend a `backend` argument names, and the GPU where it may be used.
fn counting(backend: &str) -> Result<Counting<'static>, Error> {
    let choice = match backend {
        "auto" => BackendChoice::Auto,
        "cpu" => BackendChoice::Cpu,
        "gpu" => BackendChoice::Gpu,
        other => {
            return Err(Error::Value(format!(
                "backend {other:?} is not one of \"auto\" (a hardware GPU when there is one, \
                 else the CPU), \"cpu\" and \"gpu\""
            )));
        }
    };
    let gpu = if choice == BackendChoice::Cpu {
        None
    } else {
        gpu()
    };
    Ok(Counting { choice, gpu })
}

/// A pool of `threads` worker threads, or `None` for rayon's global pool (all cores).
fn pool(threads: Option<usize>) -> Result<Option<rayon::ThreadPool>, Error> {
    match threads {
        Some(0) => Err(Error::Value("threads must be at least 1".into())),
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .map(Some)
            .map_err(|err| Error::Search(format!("could not start the threads: {err}"))),
        None => Ok(None),
    }
}

/// Runs `work` on `pool`, or where it is called without one.
fn on_pool<T: Send>(pool: Option<&rayon::ThreadPool>, work: impl FnOnce() -> T + Send) -> T {
    match pool {
        Some(pool) => pool.install(work),
        None => work(),
    }
}

/// Calls `callback` with `argument` (with the GIL): whether it asked to stop (returned
/// `False`); an exception it raised, or a pending signal (Ctrl-C), is kept in `failure`,
/// and stops too.
fn call_back<T: pyo3::PyClass + Into<PyClassInitializer<T>>>(
    callback: &Py<PyAny>,
    argument: impl FnOnce(Python<'_>) -> PyResult<T>,
    failure: &mut Option<PyErr>,
) -> Control {
    Python::attach(|py| {
        let called = (|| {
            py.check_signals()?;
            let reply = callback.call1(py, (Py::new(py, argument(py)?)?,))?;
            let reply = reply.bind(py);
            Ok::<_, PyErr>(reply.is_instance_of::<PyBool>() && !reply.is_truthy()?)
        })();
        match called {
            Ok(false) => Control::Continue,
            Ok(true) => Control::Stop,
            Err(err) => {
                *failure = Some(err);
                Control::Stop
            }
        }
    })
}

impl Scene {
    /// The scene read from `origin` with `overrides`.
    pub fn read(catalog: &Arc<Catalog>, origin: Origin, overrides: Overrides) -> PyResult<Scene> {
        let goal = origin.read(catalog, &overrides)?;
        let (_, erased) = catalog.find(&goal.generator).map_err(Error::from)?;
        Ok(Scene {
            catalog: Arc::clone(catalog),
            origin,
            overrides,
            goal,
            erased,
        })
    }

    fn genomes<'a>(&self, genomes: &'a [PyRef<'_, Genome>]) -> PyResult<Vec<&'a str>> {
        genomes
            .iter()
            .map(|g| {
                g.check(&self.goal.generator)?;
                Ok(g.text.json.as_str())
            })
            .collect()
    }

    /// Runs the search of `goal` with the GIL released; `progress` is called with the
    /// GIL after every generation.
    fn search(
        &self,
        py: Python<'_>,
        goal: &Goal,
        counting: Counting<'_>,
        threads: Option<usize>,
        progress: Option<Py<PyAny>>,
        folder: Option<Folder>,
    ) -> PyResult<Run> {
        if goal.objectives.is_some() {
            return Err(Error::Scene(format!(
                "`{}` has [[objective]] tables: its front of non-dominated models is searched \
                 by Scene.run_front",
                goal.path.display()
            ))
            .into());
        }
        let pool = pool(threads)?;
        let stop = AtomicBool::new(false);
        let mut failure: Option<PyErr> = None;
        let mut best: Option<Py<Genome>> = None;
        let (generator, erased) = (&self.goal.generator, &self.erased);
        let mut observer = |step: Step| {
            let Some(callback) = &progress else {
                return Control::Continue;
            };
            Python::attach(|py| {
                let called = (|| {
                    py.check_signals()?;
                    if let Some(text) = step.best.clone() {
                        best = Some(Py::new(py, Genome::new(generator, erased, text))?);
                    }
                    let shown = best.as_ref().map(|b| b.clone_ref(py));
                    let shown = shown.ok_or_else(|| Error::Search("no best model yet".into()))?;
                    let reply = callback.call1(py, (Progress { step, best: shown },))?;
                    let reply = reply.bind(py);
                    Ok::<_, PyErr>(reply.is_instance_of::<PyBool>() && !reply.is_truthy()?)
                })();
                match called {
                    Ok(false) => Control::Continue,
                    Ok(true) => Control::Stop,
                    Err(err) => {
                        failure = Some(err);
                        Control::Stop
                    }
                }
            })
        };
        let resume = folder.as_ref().and_then(|f| f.resume.as_deref());
        let mut save = |state: &str| -> Result<(), Box<dyn std::error::Error + Send + Sync>> {
            let Some(f) = &folder else { return Ok(()) };
            checkpoint::write(&f.dir, &goal.path, &f.overrides, state)
                .map_err(|err| err.to_string().into())
        };
        let saves = folder.is_some();
        let outcome = py.detach(|| {
            let run = || {
                let save: Option<&mut SaveHook<'_>> = if saves { Some(&mut save) } else { None };
                erased.search(goal, counting, &stop, &mut observer, resume, save)
            };
            on_pool(pool.as_ref(), run)
        });
        if let Some(err) = failure {
            return Err(err);
        }
        let outcome = outcome?;
        let best = Py::new(py, Genome::new(generator, erased, outcome.best.clone()))?;
        Ok(Run { outcome, best })
    }

    /// The scene as `settings` override it, read again when they change anything.
    fn overridden(&self, settings: &Overrides) -> PyResult<std::borrow::Cow<'_, Goal>> {
        if *settings == Overrides::default() {
            return Ok(std::borrow::Cow::Borrowed(&self.goal));
        }
        let all = self.overrides.clone().then(settings);
        Ok(std::borrow::Cow::Owned(
            self.origin.read(&self.catalog, &all)?,
        ))
    }

    /// A finished run of a comparison as a Python object.
    fn compared_run(&self, py: Python<'_>, text: ComparedText) -> PyResult<ComparedRun> {
        let best = Genome::new(
            &self.goal.generator,
            &self.erased,
            text.outcome.best.clone(),
        );
        Ok(ComparedRun {
            text,
            best: Py::new(py, best)?,
        })
    }
}

#[pymethods]
impl Scene {
    /// The generator whose models the scene scores.
    #[getter]
    fn generator(&self) -> &str {
        &self.goal.generator
    }

    /// The scene file, or the path the scene's text was read as.
    #[getter]
    fn path(&self) -> PathBuf {
        self.goal.path.clone()
    }

    /// The search method: `ga`, `smc`, `sosmc`, `rjmcmc`, `hybrid` or `random`.
    #[getter]
    fn method(&self) -> &str {
        self.goal.optimizer.method().name()
    }

    /// The seed of the search.
    #[getter]
    fn seed(&self) -> u64 {
        self.goal.optimizer.seed
    }

    /// The genome limits of the search.
    #[getter]
    fn limits<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        limits_dict(py, self.goal.limits)
    }

    /// The objectives' names of a multi-objective scene (its `[[objective]]` tables, in
    /// order), searched by `run_front`; empty for a scene with one fitness.
    #[getter]
    fn objectives(&self) -> Vec<String> {
        self.goal
            .objectives
            .as_ref()
            .map(|o| o.set.names().map(str::to_owned).collect())
            .unwrap_or_default()
    }

    /// The same scene with other settings: the `[optimizer]` keys the keyword arguments
    /// name, and `set`, `key=value` overrides of any scene key (as the tool's `--set`).
    #[pyo3(signature = (**settings))]
    fn with_settings(&self, settings: Option<&Bound<'_, PyDict>>) -> PyResult<Scene> {
        let later = overrides(settings)?;
        let overrides = self.overrides.clone().then(&later);
        Scene::read(&self.catalog, self.origin.clone(), overrides)
    }

    /// Searches for the model that best meets the scene's goal, to its budget (the
    /// keyword arguments override the scene's `[optimizer]`, as the tool's flags do).
    /// `threads` worker threads count (all cores by default; the result does not depend
    /// on it). `progress(p)` is called after every generation with a `Progress`; it
    /// stops the run by returning `False`, and an exception it raises stops the run and
    /// is raised here. Other Python threads run meanwhile. With `checkpoint` (a folder)
    /// the search saves `checkpoint.json` there as `shapegen run` does (every second and
    /// at the end), and with `resume=True` it goes on from the one there, to the same end
    /// as a search never interrupted.
    #[pyo3(signature = (*, threads = None, progress = None, backend = "auto", checkpoint = None, resume = false, **settings))]
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn run(
        &self,
        py: Python<'_>,
        threads: Option<usize>,
        progress: Option<Py<PyAny>>,
        backend: &str,
        checkpoint: Option<PathBuf>,
        resume: bool,
        settings: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Run> {
        let counting = counting(backend)?;
        let later = overrides(settings)?;
        let all = self.overrides.clone().then(&later);
        let folder = match (checkpoint, resume) {
            (None, true) => {
                return Err(Error::Value(
                    "resume=True goes on from the checkpoint in a folder: give checkpoint=".into(),
                )
                .into());
            }
            (None, false) => None,
            (Some(dir), resume) => {
                let resume = resume
                    .then(|| checkpoint::read(&dir).map(|saved| saved.state))
                    .transpose()?;
                Some(Folder {
                    dir,
                    overrides: all.clone(),
                    resume,
                })
            }
        };
        if later == Overrides::default() {
            return self.search(py, &self.goal, counting, threads, progress, folder);
        }
        let goal = self.origin.read(&self.catalog, &all)?;
        self.search(py, &goal, counting, threads, progress, folder)
    }

    /// Compares `methods` (their names, in the order they run; every method by default)
    /// as `shapegen compare` does: `runs` runs of each, run `r` of every method on seed
    /// `seed + r` (the scene's seed by default), run-major, each to `seconds` of wall
    /// time and to the evaluation budget (`evaluations`, or the scene's; give one or
    /// both), the methods' own generation counts no limit. Each method takes its settings
    /// as `run(method=...)` would (`set` overrides any key, read as each method's).
    /// `progress(run)` is called after every finished run with its `ComparedRun`;
    /// returning `False` ends the comparison there, and an exception it raises ends it
    /// and is raised here. The result holds every run and each method's summary, the
    /// numbers of the tool's `runs.csv` and `summary.json` (equal to them for the same
    /// scene, seed and evaluation budget).
    #[pyo3(signature = (methods = None, *, runs = 3, seed = None, seconds = None, evaluations = None, set = None, threads = None, progress = None, backend = "auto"))]
    #[allow(clippy::too_many_arguments)]
    fn compare(
        &self,
        py: Python<'_>,
        methods: Option<Vec<String>>,
        runs: u64,
        seed: Option<u64>,
        seconds: Option<f64>,
        evaluations: Option<u64>,
        set: Option<Vec<String>>,
        threads: Option<usize>,
        progress: Option<Py<PyAny>>,
        backend: &str,
    ) -> PyResult<Comparison> {
        let counting = counting(backend)?;
        let methods = match methods {
            None => Method::ALL.to_vec(),
            Some(names) => names
                .iter()
                .map(|name| {
                    name.parse::<Method>()
                        .map_err(|err| Error::Value(err.to_string()))
                })
                .collect::<Result<Vec<_>, _>>()?,
        };
        // The scene read as a search with the first method reads it (`set` keys may be
        // a method's own), as the tool's compare reads it.
        let settings = Overrides {
            method: methods.first().copied(),
            evaluations,
            sets: set.unwrap_or_default(),
            ..Overrides::default()
        };
        let all = self.overrides.clone().then(&settings);
        let goal = self.origin.read(&self.catalog, &all)?;
        let pool = pool(threads)?;
        let stop = AtomicBool::new(false);
        let plan = Compare::new(&goal, &methods, runs, seed, seconds)
            .map_err(|err| match err {
                CompareError::Scene(err) => Error::scene(err),
                other => Error::Value(other.to_string()),
            })?
            .backend(counting.choice, counting.gpu)
            .stop_flag(&stop);
        let mut failure: Option<PyErr> = None;
        let mut finished = |text: &ComparedText| {
            let Some(callback) = &progress else {
                return Control::Continue;
            };
            let text = text.clone();
            call_back(callback, |py| self.compared_run(py, text), &mut failure)
        };
        let erased = &self.erased;
        let outcome = py.detach(|| on_pool(pool.as_ref(), || erased.compare(&plan, &mut finished)));
        if let Some(err) = failure {
            return Err(err);
        }
        let outcome = outcome?;
        let runs = outcome
            .runs
            .into_iter()
            .map(|text| Py::new(py, self.compared_run(py, text)?))
            .collect::<PyResult<Vec<_>>>()?;
        let summaries = outcome
            .summaries
            .into_iter()
            .map(|summary| Py::new(py, MethodSummary { summary }))
            .collect::<PyResult<Vec<_>>>()?;
        Ok(Comparison {
            methods: outcome.methods,
            seeds: outcome.seeds,
            seconds: outcome.seconds,
            backend: outcome.backend,
            optimum: outcome.optimum,
            runs,
            summaries,
            complete: outcome.complete,
            interrupted: outcome.interrupted,
        })
    }

    /// Searches the front of a multi-objective scene (one with `[[objective]]` tables)
    /// as `shapegen run` does: the multi-objective GA to the budget (the keyword
    /// arguments override the scene's `[optimizer]` as `run`'s do), each model measured
    /// by every objective on the CPU, with the GIL released. The same scene and seed
    /// give the front the tool writes (`front.csv`, `front.genomes.json`), for any
    /// `threads`. `progress(p)` is called after every generation with a
    /// `FrontProgress`; returning `False` stops the search, an exception it raises stops
    /// it and is raised here.
    #[pyo3(signature = (*, threads = None, progress = None, **settings))]
    fn run_front(
        &self,
        py: Python<'_>,
        threads: Option<usize>,
        progress: Option<Py<PyAny>>,
        settings: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Front> {
        let settings = overrides(settings)?;
        let goal = self.overridden(&settings)?;
        let Some(objectives) = &goal.objectives else {
            return Err(Error::Scene(format!(
                "`{}` has no [[objective]] tables: its one fitness is searched by Scene.run",
                goal.path.display()
            ))
            .into());
        };
        let names: Vec<String> = objectives.set.names().map(str::to_owned).collect();
        let pool = pool(threads)?;
        let stop = AtomicBool::new(false);
        let mut failure: Option<PyErr> = None;
        let mut observer = |step: FrontStep| {
            let Some(callback) = &progress else {
                return Control::Continue;
            };
            let objectives = names.clone();
            let argument = |_: Python<'_>| Ok(FrontProgress { step, objectives });
            call_back(callback, argument, &mut failure)
        };
        let erased = &self.erased;
        let searched: &Goal = &goal;
        let outcome = py.detach(|| {
            on_pool(pool.as_ref(), || {
                erased.front(searched, &stop, &mut observer)
            })
        });
        if let Some(err) = failure {
            return Err(err);
        }
        let outcome = outcome?;
        let members = outcome
            .members
            .iter()
            .map(|(text, values)| {
                let genome = Genome::new(&goal.generator, erased, text.clone());
                Py::new(
                    py,
                    FrontMember {
                        genome: Py::new(py, genome)?,
                        values: values.clone(),
                        objectives: outcome.objectives.clone(),
                    },
                )
            })
            .collect::<PyResult<Vec<_>>>()?;
        Ok(Front {
            members,
            generator: goal.generator.clone(),
            meshes: goal.meshes.clone(),
            site: goal.site.clone(),
            outcome,
        })
    }

    /// The fitness of each genome in this scene, as `shapegen score` gives it.
    #[pyo3(signature = (genomes, *, backend = "auto"))]
    fn score(
        &self,
        py: Python<'_>,
        genomes: Vec<PyRef<'_, Genome>>,
        backend: &str,
    ) -> PyResult<Vec<f64>> {
        let counting = counting(backend)?;
        let texts = self.genomes(&genomes)?;
        Ok(py.detach(|| self.erased.score(&self.goal, &texts, counting))?)
    }

    /// Random models within the scene's limits (from one gene), model `i` from stream
    /// `i` of `seed`.
    #[pyo3(signature = (count = 1, *, seed = 0))]
    fn sample(&self, py: Python<'_>, count: u32, seed: u64) -> PyResult<Vec<Genome>> {
        let limits = Limits {
            min_len: 1,
            ..self.goal.limits
        };
        objects::sample(py, &self.goal.generator, &self.erased, limits, count, seed)
    }

    /// Reads a genome of the scene's generator from JSON of either form.
    fn genome(&self, json: &str) -> PyResult<Genome> {
        let text = self.erased.read(json)?;
        Ok(Genome::new(&self.goal.generator, &self.erased, text))
    }

    /// The model of `genome` with the scene's meshes, on its lot.
    fn model(&self, py: Python<'_>, genome: &Genome) -> PyResult<Model> {
        objects::model(
            py,
            &self.goal.generator,
            &self.goal.meshes,
            &self.goal.site,
            genome,
        )
    }

    fn __repr__(&self) -> String {
        format!(
            "Scene({:?}, generator={:?}, method={:?})",
            self.goal.path.display().to_string(),
            self.goal.generator,
            self.goal.optimizer.method().name()
        )
    }
}
