//! The results of `Scene.compare` and `Scene.run_front` as Python objects: a comparison
//! with its runs and each method's summary; a multi-objective search's front with its
//! members, history and progress.

use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use shapegen::search::MethodSummary as Summary;
use shapegen::{MeshLibrary, Site};

use crate::arrays;
use crate::objects::{Genome, Model, from_json, history, model};
use crate::typed::{ComparedText, FrontOutcome, FrontStep};

/// One finished run of a comparison: a search of the scene with its method and seed.
#[pyclass(frozen, name = "ComparedRun")]
pub struct ComparedRun {
    pub(crate) text: ComparedText,
    pub(crate) best: Py<Genome>,
}

#[pymethods]
impl ComparedRun {
    /// The method's name.
    #[getter]
    fn method(&self) -> &str {
        self.text.method
    }

    /// The run's number among the method's runs, from 0.
    #[getter]
    fn run(&self) -> u64 {
        self.text.run
    }

    /// Its seed: the comparison's base seed plus `run`.
    #[getter]
    fn seed(&self) -> u64 {
        self.text.seed
    }

    /// The best genome.
    #[getter]
    fn best(&self, py: Python<'_>) -> Py<Genome> {
        self.best.clone_ref(py)
    }

    /// Its fitness.
    #[getter]
    fn best_fitness(&self) -> f64 {
        self.text.outcome.best_fitness
    }

    /// Fitness evaluations done.
    #[getter]
    fn evaluations(&self) -> u64 {
        self.text.outcome.evaluations
    }

    /// Generations done after the initial population.
    #[getter]
    fn generations(&self) -> u64 {
        self.text.outcome.generations
    }

    /// Wall time of the run in seconds.
    #[getter]
    fn elapsed_s(&self) -> f64 {
        self.text
            .outcome
            .history
            .last()
            .map_or(0.0, |h| h.elapsed_s)
    }

    /// Why it ended: `"evaluations"` or `"time"`.
    #[getter]
    fn stopped(&self) -> &str {
        self.text.outcome.stopped
    }

    /// The fitness curve as numpy arrays, as `Run.history` (the tool's `compare.csv`
    /// holds its `elapsed_s`, `evaluations` and `best`).
    #[getter]
    fn history<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        history(py, &self.text.outcome.history)
    }

    /// The best model's measures against the scene's targets, as the tool's
    /// `summary.json` gives them: `genes`, `instances`, `triangles`, and where the scene
    /// has such targets `voxel_iou`, `surface` (`chamfer`, `f_score`),
    /// `silhouette_iou` (per target image), `point_clouds`.
    #[getter]
    fn metrics<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.text.metrics)
    }

    fn __repr__(&self) -> String {
        format!(
            "ComparedRun({:?}, run={}, seed={}, best_fitness={}, evaluations={})",
            self.text.method,
            self.text.run,
            self.text.seed,
            self.text.outcome.best_fitness,
            self.text.outcome.evaluations
        )
    }
}

/// One method's summary over its runs, as the tool's `summary.json` gives it.
#[pyclass(frozen, name = "MethodSummary")]
pub struct MethodSummary {
    pub(crate) summary: Summary,
}

#[pymethods]
impl MethodSummary {
    /// The method's name.
    #[getter]
    fn method(&self) -> &str {
        self.summary.method
    }

    /// Its finished runs.
    #[getter]
    fn runs(&self) -> usize {
        self.summary.runs
    }

    /// The mean over runs of each run's final best fitness.
    #[getter]
    fn final_mean(&self) -> f64 {
        self.summary.final_mean
    }

    /// Their sample standard deviation (0 for one run).
    #[getter]
    fn final_std(&self) -> f64 {
        self.summary.final_std
    }

    /// Their first quartile, median and third quartile.
    #[getter]
    fn final_quartiles(&self) -> (f64, f64, f64) {
        let [q1, m, q3] = self.summary.final_quartiles;
        (q1, m, q3)
    }

    /// The best fitness of all runs (the worst is `min(finals)`).
    #[getter]
    fn best(&self) -> f64 {
        self.summary.best
    }

    /// The run that found it.
    #[getter]
    fn best_run(&self) -> Option<u64> {
        self.summary.best_run
    }

    /// The mean evaluations per run.
    #[getter]
    fn evaluations(&self) -> f64 {
        self.summary.evaluations
    }

    /// Each run's final best fitness, by run.
    #[getter]
    fn finals<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arrays::vector(py, self.summary.finals.clone())
    }

    /// Each run's best model's measures, by run (as `ComparedRun.metrics`).
    #[getter]
    fn metrics<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.summary.metrics)
    }

    /// For a scene with an optimum (`fitness.optimum`): per fraction of it (0.9, 0.99,
    /// 0.999) the `level`, the `runs`, how many `reached` it, and the quartiles of the
    /// `seconds` and `evaluations` it took (`None` where too few runs reached it), as
    /// the tool's `targets.csv`; `None` without an optimum.
    #[getter]
    fn targets<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.summary.targets)
    }

    fn __repr__(&self) -> String {
        format!(
            "MethodSummary({:?}, runs={}, final_mean={}, best={})",
            self.summary.method, self.summary.runs, self.summary.final_mean, self.summary.best
        )
    }
}

/// What a comparison did: every finished run, run-major, and each method's summary.
#[pyclass(frozen, name = "Comparison")]
pub struct Comparison {
    pub(crate) methods: Vec<&'static str>,
    pub(crate) seeds: Vec<u64>,
    pub(crate) seconds: Option<f64>,
    pub(crate) backend: String,
    pub(crate) optimum: Option<f64>,
    pub(crate) runs: Vec<Py<ComparedRun>>,
    pub(crate) summaries: Vec<Py<MethodSummary>>,
    pub(crate) complete: bool,
    pub(crate) interrupted: Option<(&'static str, u64)>,
}

#[pymethods]
impl Comparison {
    /// The methods' names, in the order they ran.
    #[getter]
    fn methods(&self) -> Vec<&'static str> {
        self.methods.clone()
    }

    /// The seed of each run, by run number: the base seed and those after it.
    #[getter]
    fn seeds(&self) -> Vec<u64> {
        self.seeds.clone()
    }

    /// The wall-time budget of every run in seconds, if one was given.
    #[getter]
    fn seconds(&self) -> Option<f64> {
        self.seconds
    }

    /// The backend that counted: `"CPU"` or the GPU's name.
    #[getter]
    fn backend(&self) -> &str {
        &self.backend
    }

    /// The scene's optimum (`fitness.optimum`), if it gives one.
    #[getter]
    fn optimum(&self) -> Option<f64> {
        self.optimum
    }

    /// The finished runs, run-major (run 0 of every method, then run 1, ...), as the
    /// rows of the tool's `runs.csv`.
    #[getter]
    fn runs(&self, py: Python<'_>) -> Vec<Py<ComparedRun>> {
        self.runs.iter().map(|r| r.clone_ref(py)).collect()
    }

    /// Each method's summary, by its name, in the order they ran.
    #[getter]
    fn summaries<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        for (name, summary) in self.methods.iter().zip(&self.summaries) {
            dict.set_item(name, summary.clone_ref(py))?;
        }
        Ok(dict)
    }

    /// Whether every planned run finished.
    #[getter]
    fn complete(&self) -> bool {
        self.complete
    }

    /// The run that was interrupted (by `progress`), as `(method, run)`; it is not
    /// among `runs`. `None` when none was.
    #[getter]
    fn interrupted(&self) -> Option<(&'static str, u64)> {
        self.interrupted
    }

    fn __repr__(&self) -> String {
        format!(
            "Comparison(methods={:?}, runs={}, complete={})",
            self.methods,
            self.runs.len(),
            self.complete
        )
    }
}

/// A member of a multi-objective search's front: a genome and its objective values.
#[pyclass(frozen, name = "FrontMember")]
pub struct FrontMember {
    pub(crate) genome: Py<Genome>,
    pub(crate) values: Vec<f64>,
    pub(crate) objectives: Vec<String>,
}

#[pymethods]
impl FrontMember {
    /// Its genome.
    #[getter]
    fn genome(&self, py: Python<'_>) -> Py<Genome> {
        self.genome.clone_ref(py)
    }

    /// Its value of each objective, by the objective's name, in the scene's order.
    #[getter]
    fn values<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        for (name, value) in self.objectives.iter().zip(&self.values) {
            dict.set_item(name, value)?;
        }
        Ok(dict)
    }

    fn __repr__(&self) -> String {
        let values: Vec<String> = self
            .objectives
            .iter()
            .zip(&self.values)
            .map(|(n, v)| format!("{n}={v}"))
            .collect();
        format!("FrontMember({})", values.join(", "))
    }
}

/// What a multi-objective search found: the front of non-dominated models.
#[pyclass(frozen, name = "Front")]
pub struct Front {
    pub(crate) outcome: FrontOutcome,
    pub(crate) members: Vec<Py<FrontMember>>,
    pub(crate) generator: String,
    pub(crate) meshes: MeshLibrary,
    pub(crate) site: Site,
}

#[pymethods]
impl Front {
    /// The objectives' names, in the scene's order.
    #[getter]
    fn objectives(&self) -> Vec<String> {
        self.outcome.objectives.clone()
    }

    /// Each objective's kind, as scene files name it (`top_match`, ...).
    #[getter]
    fn kinds(&self) -> Vec<&'static str> {
        self.outcome.kinds.clone()
    }

    /// Each objective's sense: `"maximize"` or `"minimize"`.
    #[getter]
    fn senses(&self) -> Vec<&'static str> {
        let sense = |&max: &bool| if max { "maximize" } else { "minimize" };
        self.outcome.maximized.iter().map(sense).collect()
    }

    /// The selection's ranking, as scene files name it (`pareto`, ...).
    #[getter]
    fn ranking(&self) -> &str {
        self.outcome.ranking
    }

    /// The front's members, best first by the first objective (then by the others):
    /// the order of the tool's `front.csv` and `front.genomes.json`.
    #[getter]
    fn members(&self, py: Python<'_>) -> Vec<Py<FrontMember>> {
        self.members.iter().map(|m| m.clone_ref(py)).collect()
    }

    /// The members' objective values, N x K `float64`, a row per member (in the order
    /// of `members`) and a column per objective (in the order of `objectives`).
    #[getter]
    fn values<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let rows: Vec<&[f64]> = self
            .outcome
            .members
            .iter()
            .map(|(_, v)| v.as_slice())
            .collect();
        Ok(arrays::matrix(py, &rows, self.outcome.objectives.len())?)
    }

    /// The members' genomes, in the order of `members`.
    #[getter]
    fn genomes(&self, py: Python<'_>) -> Vec<Py<Genome>> {
        self.members
            .iter()
            .map(|m| m.get().genome.clone_ref(py))
            .collect()
    }

    /// The members' models with the scene's meshes, on its lot, in the order of
    /// `members`.
    fn models(&self, py: Python<'_>) -> PyResult<Vec<Model>> {
        self.members
            .iter()
            .map(|m| {
                let genome = m.get().genome.get();
                model(py, &self.generator, &self.meshes, &self.site, genome)
            })
            .collect()
    }

    /// Fitness evaluations done.
    #[getter]
    fn evaluations(&self) -> u64 {
        self.outcome.evaluations
    }

    /// Generations done after the initial population.
    #[getter]
    fn generations(&self) -> u64 {
        self.outcome.generations
    }

    /// Wall time of the search in seconds.
    #[getter]
    fn elapsed_s(&self) -> f64 {
        self.outcome.history.last().map_or(0.0, |h| h.elapsed_s)
    }

    /// Why it ended: `"generations"`, `"evaluations"`, `"time"` or `"interrupted"`.
    #[getter]
    fn stopped(&self) -> &str {
        self.outcome.stopped
    }

    /// The search's history, one entry per generation (the initial population's first),
    /// as numpy arrays: the columns of the tool's `history.csv`, `generation`,
    /// `elapsed_s`, `evaluations`, `front` (its size) and `best_NAME` per objective (the
    /// best value evaluated so far).
    #[getter]
    fn history<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let h = &self.outcome.history;
        let dict = PyDict::new(py);
        dict.set_item(
            "generation",
            arrays::vector(py, h.iter().map(|e| e.generation).collect()),
        )?;
        dict.set_item(
            "elapsed_s",
            arrays::vector(py, h.iter().map(|e| e.elapsed_s).collect()),
        )?;
        dict.set_item(
            "evaluations",
            arrays::vector(py, h.iter().map(|e| e.evaluations).collect()),
        )?;
        dict.set_item(
            "front",
            arrays::vector(py, h.iter().map(|e| e.front).collect()),
        )?;
        for (i, name) in self.outcome.objectives.iter().enumerate() {
            let column = h.iter().map(|e| e.best.get(i).copied().unwrap_or(f64::NAN));
            dict.set_item(format!("best_{name}"), arrays::vector(py, column.collect()))?;
        }
        Ok(dict)
    }

    fn __len__(&self) -> usize {
        self.members.len()
    }

    fn __repr__(&self) -> String {
        format!(
            "Front(members={}, objectives={:?}, generations={}, evaluations={})",
            self.members.len(),
            self.outcome.objectives,
            self.outcome.generations,
            self.outcome.evaluations
        )
    }
}

/// A generation of a multi-objective search, as a progress callback sees it.
#[pyclass(frozen, name = "FrontProgress")]
pub struct FrontProgress {
    pub(crate) step: FrontStep,
    pub(crate) objectives: Vec<String>,
}

#[pymethods]
impl FrontProgress {
    /// Generations done after the initial population (0: the initial population).
    #[getter]
    fn generation(&self) -> u64 {
        self.step.generation
    }

    /// Wall time so far in seconds.
    #[getter]
    fn elapsed_s(&self) -> f64 {
        self.step.elapsed_s
    }

    /// Fitness evaluations so far.
    #[getter]
    fn evaluations(&self) -> u64 {
        self.step.evaluations
    }

    /// Members of the front so far.
    #[getter]
    fn front(&self) -> usize {
        self.step.front
    }

    /// Per objective, by its name, the best value evaluated so far.
    #[getter]
    fn best<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        for (name, value) in self.objectives.iter().zip(&self.step.best) {
            dict.set_item(name, value)?;
        }
        Ok(dict)
    }

    fn __repr__(&self) -> String {
        format!(
            "FrontProgress(generation={}, front={}, evaluations={})",
            self.step.generation, self.step.front, self.step.evaluations
        )
    }
}
