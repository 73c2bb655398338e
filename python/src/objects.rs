//! The Python objects other than scenes: generators, genomes, models, a run's result and
//! its progress.

use std::sync::Arc;

use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use shapegen::{Limits, MeshLibrary, Site};

use crate::arrays;
use crate::error::Error;
use crate::typed::{Erased, GenomeText, Outcome, Step, Triangles};
use shapegen::optimize::HistoryEntry;

/// A generator: its name, its grammar and parts, random models and genomes read from JSON.
#[pyclass(frozen, name = "Generator")]
pub struct Generator {
    pub(crate) name: String,
    pub(crate) grammar: &'static str,
    pub(crate) parts: &'static [&'static str],
    pub(crate) limits: Limits,
    pub(crate) meshes: MeshLibrary,
    pub(crate) erased: Arc<dyn Erased>,
}

/// The limits as a dictionary.
pub fn limits_dict<'py>(py: Python<'py>, limits: Limits) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    dict.set_item("min_len", limits.min_len)?;
    dict.set_item("max_len", limits.max_len)?;
    dict.set_item("max_depth", limits.max_depth)?;
    Ok(dict)
}

/// `count` random genomes of `erased` within `limits`.
pub fn sample(
    py: Python<'_>,
    generator: &str,
    erased: &Arc<dyn Erased>,
    limits: Limits,
    count: u32,
    seed: u64,
) -> PyResult<Vec<Genome>> {
    let texts = py.detach(|| erased.sample(limits, count, seed))?;
    Ok(texts
        .into_iter()
        .map(|text| Genome::new(generator, erased, text))
        .collect())
}

#[pymethods]
impl Generator {
    /// The name scenes use.
    #[getter]
    fn name(&self) -> &str {
        &self.name
    }

    /// The grammar's name in Rust.
    #[getter]
    fn grammar(&self) -> &str {
        self.grammar
    }

    /// The generator's meshes (the parts of its models), by id.
    #[getter]
    fn parts(&self) -> Vec<&'static str> {
        self.parts.to_vec()
    }

    /// The genome limits random models are drawn within by default.
    #[getter]
    fn limits<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        limits_dict(py, self.limits)
    }

    /// Random models from the generator's own distribution, as `shapegen sample` draws
    /// them: model `i` from stream `i` of `seed`.
    #[pyo3(signature = (count = 1, *, seed = 0, max_len = None, max_depth = None))]
    fn sample(
        &self,
        py: Python<'_>,
        count: u32,
        seed: u64,
        max_len: Option<u32>,
        max_depth: Option<u32>,
    ) -> PyResult<Vec<Genome>> {
        let limits = Limits {
            min_len: 1,
            max_len: max_len.unwrap_or(self.limits.max_len),
            max_depth: max_depth.unwrap_or(self.limits.max_depth),
        };
        sample(py, &self.name, &self.erased, limits, count, seed)
    }

    /// Reads a genome of this generator from JSON of either form (packed or nested).
    fn genome(&self, json: &str) -> PyResult<Genome> {
        let text = self.erased.read(json)?;
        Ok(Genome::new(&self.name, &self.erased, text))
    }

    /// The model of `genome` with the generator's own meshes.
    fn model(&self, py: Python<'_>, genome: &Genome) -> PyResult<Model> {
        model(py, &self.name, &self.meshes, &Site::NONE, genome)
    }

    fn __repr__(&self) -> String {
        format!("Generator({:?}, grammar={:?})", self.name, self.grammar)
    }
}

/// The model of `genome`, which must be of `generator`, with `meshes` on `site`.
pub fn model(
    py: Python<'_>,
    generator: &str,
    meshes: &MeshLibrary,
    site: &Site,
    genome: &Genome,
) -> PyResult<Model> {
    genome.check(generator)?;
    let triangles = py.detach(|| genome.erased.model(meshes, site, &genome.text.json))?;
    Ok(Model { triangles })
}

/// A genome: a derivation tree of one generator, in its packed JSON form.
#[pyclass(frozen, name = "Genome")]
#[derive(Clone)]
pub struct Genome {
    pub(crate) generator: String,
    pub(crate) erased: Arc<dyn Erased>,
    pub(crate) text: GenomeText,
}

impl Genome {
    pub(crate) fn new(generator: &str, erased: &Arc<dyn Erased>, text: GenomeText) -> Genome {
        Genome {
            generator: generator.to_owned(),
            erased: Arc::clone(erased),
            text,
        }
    }

    /// Refuses a genome of another generator than `generator`.
    pub(crate) fn check(&self, generator: &str) -> Result<(), Error> {
        if self.generator.eq_ignore_ascii_case(generator) {
            Ok(())
        } else {
            Err(Error::Genome(format!(
                "the genome is one of generator `{}`, not of `{generator}`",
                self.generator
            )))
        }
    }
}

#[pymethods]
impl Genome {
    /// The generator it is a genome of.
    #[getter]
    fn generator(&self) -> &str {
        &self.generator
    }

    /// Its genes.
    #[getter]
    fn genes(&self) -> usize {
        self.text.genes
    }

    /// Its JSON: the packed form, as the tool saves genomes (`best.genome.json`), or
    /// with `nested=True` the nested form, made to be read and edited.
    #[pyo3(signature = (*, nested = false))]
    fn to_json(&self, nested: bool) -> PyResult<String> {
        if nested {
            Ok(self.erased.nested(&self.text.json)?)
        } else {
            Ok(self.text.json.clone())
        }
    }

    fn __len__(&self) -> usize {
        self.text.genes
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other
            .cast::<Genome>()
            .is_ok_and(|o| o.get().generator == self.generator && o.get().text == self.text)
    }

    fn __hash__(&self) -> u64 {
        use std::hash::{Hash, Hasher};
        let mut h = std::collections::hash_map::DefaultHasher::new();
        self.text.json.hash(&mut h);
        h.finish()
    }

    fn __repr__(&self) -> String {
        format!("Genome({:?}, genes={})", self.generator, self.text.genes)
    }
}

/// A model: its triangles in world space as numpy arrays, each with its part.
#[pyclass(frozen, name = "Model")]
pub struct Model {
    triangles: Triangles,
}

#[pymethods]
impl Model {
    /// Vertex positions, N x 3 `float32`.
    #[getter]
    fn vertices<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f32>> {
        arrays::rows(py, &self.triangles.vertices)
    }

    /// Triangles, M x 3 `uint32` vertex indices, counter-clockwise seen from outside.
    #[getter]
    fn faces<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<u32>> {
        arrays::rows(py, &self.triangles.faces)
    }

    /// The part of each triangle, M `uint32` indices into `part_names`.
    #[getter]
    fn parts<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<u32>> {
        arrays::vector(py, self.triangles.parts.clone())
    }

    /// The generator's meshes, by id: the names of the parts (materials).
    #[getter]
    fn part_names(&self) -> Vec<String> {
        self.triangles.part_names.clone()
    }

    /// Each part's colour in the exports, K x 3 `float32` linear RGB.
    #[getter]
    fn part_colors<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f32>> {
        arrays::rows(py, &self.triangles.part_colors)
    }

    /// Mesh instances the model places.
    #[getter]
    fn instances(&self) -> usize {
        self.triangles.instances
    }

    fn __repr__(&self) -> String {
        format!(
            "Model(vertices={}, faces={}, parts={})",
            self.triangles.vertices.len(),
            self.triangles.faces.len(),
            self.triangles.part_names.len()
        )
    }
}

/// A run's history as numpy arrays: the columns of the tool's `fitness.csv`.
pub(crate) fn history<'py>(py: Python<'py>, h: &[HistoryEntry]) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    let column = |f: fn(&HistoryEntry) -> f64| h.iter().map(f).collect();
    dict.set_item(
        "generation",
        arrays::vector(py, h.iter().map(|e| e.generation).collect()),
    )?;
    dict.set_item(
        "elapsed_s",
        arrays::vector::<f64>(py, column(|e| e.elapsed_s)),
    )?;
    dict.set_item(
        "evaluations",
        arrays::vector(py, h.iter().map(|e| e.evaluations).collect()),
    )?;
    dict.set_item("best", arrays::vector::<f64>(py, column(|e| e.best)))?;
    dict.set_item("mean", arrays::vector::<f64>(py, column(|e| e.mean)))?;
    dict.set_item("std", arrays::vector::<f64>(py, column(|e| e.std)))?;
    Ok(dict)
}

/// `value` as Python objects, as `json.loads` reads its JSON (non-finite numbers as
/// `None`, as the tool's JSON files hold them).
pub fn from_json<'py>(
    py: Python<'py>,
    value: &impl serde::Serialize,
) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value)
        .map_err(|err| Error::Value(format!("cannot write the value as JSON: {err}")))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// What a search found.
#[pyclass(frozen, name = "Run")]
pub struct Run {
    pub(crate) outcome: Outcome,
    pub(crate) best: Py<Genome>,
}

#[pymethods]
impl Run {
    /// The best genome.
    #[getter]
    fn best(&self, py: Python<'_>) -> Py<Genome> {
        self.best.clone_ref(py)
    }

    /// Its fitness.
    #[getter]
    fn best_fitness(&self) -> f64 {
        self.outcome.best_fitness
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

    /// The backend that counted: `"CPU"` or the GPU's name.
    #[getter]
    fn backend(&self) -> &str {
        &self.outcome.backend
    }

    /// The fitness curve, one entry per generation (the initial population's first), as
    /// numpy arrays: `generation`, `elapsed_s`, `evaluations`, `best`, `mean` and `std`
    /// (the columns of the tool's `fitness.csv`).
    #[getter]
    fn history<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        history(py, &self.outcome.history)
    }

    fn __repr__(&self) -> String {
        format!(
            "Run(best_fitness={}, generations={}, evaluations={}, stopped={:?})",
            self.outcome.best_fitness,
            self.outcome.generations,
            self.outcome.evaluations,
            self.outcome.stopped
        )
    }
}

/// A generation of a search, as a progress callback sees it.
#[pyclass(frozen, name = "Progress")]
pub struct Progress {
    pub(crate) step: Step,
    pub(crate) best: Py<Genome>,
}

#[pymethods]
impl Progress {
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

    /// The best fitness so far.
    #[getter]
    fn best_fitness(&self) -> f64 {
        self.step.best_fitness
    }

    /// The current population's mean fitness.
    #[getter]
    fn mean(&self) -> f64 {
        self.step.mean
    }

    /// The best genome so far.
    #[getter]
    fn best(&self, py: Python<'_>) -> Py<Genome> {
        self.best.clone_ref(py)
    }

    fn __repr__(&self) -> String {
        format!(
            "Progress(generation={}, best_fitness={}, evaluations={})",
            self.step.generation, self.step.best_fitness, self.step.evaluations
        )
    }
}
