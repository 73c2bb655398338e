//! Multi-objective search (the scoring of the thesis that evolved CGA building programs):
//! models are scored on `k` objectives at once, each maximized or minimized
//! ([`Sense`]), and selected on one scalar computed from the whole population's objective
//! vectors.
//!
//! - [`rank`](self#functions): dominance, non-dominated [`Fronts`], [`crowding`]
//!   distance, [`summed_rank`] (optionally normalized), [`weighted_sum`], the clone
//!   penalty ([`penalize_clones`]) and the [`selection_fitness`] combining them as a
//!   [`Selection`] says;
//! - [`MultiGaSettings`], [`Selection`] and [`Ranking`]: the scene-file settings;
//! - [`MultiGa`]: the GA breeding on that selection fitness, with an archive of the
//!   non-dominated models found ([`Member`]s) kept in its record ([`Front`]),
//!   checkpoints ([`MultiGaState`]) and a [`MultiObserver`]; it is an
//!   [`Optimizer`](super::Optimizer), run by the same driver as the single-objective
//!   methods.
//!
//! ```
//! use shapegen_runtime::optimize::Sense;
//! use shapegen_runtime::optimize::multi::{RankScratch, Ranking, Selection, selection_fitness};
//!
//! // Three models scored on size (maximized) and cost (minimized).
//! let values = [10.0, 5.0, /**/ 8.0, 1.0, /**/ 7.0, 6.0];
//! let senses = [Sense::Maximize, Sense::Minimize];
//! let summed = Selection { ranking: Ranking::SummedRank, diversity_penalty: 0.0 };
//! let mut fitness = [0.0; 3];
//! selection_fitness(&summed, &values, 2, &senses, &mut fitness, &mut RankScratch::default());
//! assert_eq!(fitness, [-3.0, -3.0, -6.0]);
//! ```
//!
//! [`Sense`]: super::Sense

mod ga;
mod rank;
mod record;
mod settings;
mod state;

pub use crate::evaluate::MultiEvaluator;
pub use ga::MultiGa;
pub use rank::{
    Fronts, RankScratch, crowding, dominates, pareto_fitness, penalize_clones, selection_fitness,
    summed_rank, weighted_sum,
};
pub use record::{Front, Member, MultiHistoryEntry, MultiObserver, MultiResult, MultiSnapshot};
pub use settings::{MultiGaSettings, Ranking, Selection};
pub use state::MultiGaState;
