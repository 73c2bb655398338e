//! `run.json`: what the viewer shows of a run while it goes on, rewritten at every save
//! of a single-objective or a multi-objective run. The page holds a request for this
//! file until it changes, so it follows a run with one request per save.

use serde::Serialize;

/// The contents of `run.json`.
///
/// ```
/// use shapegen::cli::view::Live;
///
/// let live = Live {
///     generator: "spaceship",
///     method: "hybrid",
///     seed: 1,
///     generation: 3,
///     evaluations: 500,
///     elapsed_s: 0.5,
///     best_fitness: Some(1.5),
///     front: None,
///     running: true,
/// };
/// let json = serde_json::to_string(&live)?;
/// assert!(json.contains(r#""best_fitness":1.5"#) && !json.contains("front"));
/// # Ok::<(), serde_json::Error>(())
/// ```
#[derive(Debug, Serialize)]
pub struct Live<'a> {
    /// The scene's generator.
    pub generator: &'a str,
    /// The method's name.
    pub method: &'a str,
    /// The run's seed.
    pub seed: u64,
    /// Generations done after the initial population.
    pub generation: u64,
    /// Evaluations done.
    pub evaluations: u64,
    /// Seconds the run has searched.
    pub elapsed_s: f64,
    /// The best fitness so far (a single-objective run).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub best_fitness: Option<f64>,
    /// The models on the front (a multi-objective run).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub front: Option<usize>,
    /// False once the run has ended (its `summary.json` is written).
    pub running: bool,
}

impl Live<'_> {
    /// `run.json`'s bytes.
    pub fn to_bytes(&self) -> anyhow::Result<Vec<u8>> {
        Ok(serde_json::to_vec_pretty(self)?)
    }
}
