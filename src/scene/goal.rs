//! The goal a scene's objective tables resolve to, which its multi-objective search is
//! made from: [`ObjectiveGoal`] (each kind of scorer's goal is in its file of
//! `scorers/`).

use shapegen_runtime::optimize::multi::Selection;
use shapegen_runtime::score::objective::ObjectiveSet;

/// The `[[objective]]` tables and the `[selection]` table, resolved.
#[derive(Clone, Debug)]
pub struct ObjectiveGoal {
    /// The objectives, under their names, in the file's order.
    pub set: ObjectiveSet,
    /// How their values are ranked for selection.
    pub selection: Selection,
    /// Most models kept in the non-dominated archive (`optimizer.archive`).
    pub archive: u32,
}
