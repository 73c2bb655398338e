//! `[bounds]`: a penalty for the part of the model outside a box, to keep it on its lot
//! or site. Each instance's world bounding box counts with its volume outside the box;
//! the fitness loses `weight` per cubic unit of it. Counted on the CPU on every backend.
//!
//! ```toml
//! [bounds]
//! min = [-8, 0, -6]                  # the box's corners, in world units
//! max = [8, 30, 6]
//! weight = 1.0                       # fitness lost per cubic unit outside (default 1)
//! ```

use std::convert::Infallible;

use glam::Vec3;
use serde::{Deserialize, Serialize};
use shapegen_runtime::Instance;
use shapegen_runtime::geometry::BoundMeshes;
use shapegen_runtime::score::Scorer;
use shapegen_runtime::score::retained::{CellCounts, Overflow, RetainedScorer};

use crate::scene::error::{SceneError, ValueError};
use crate::scene::resolver::Resolver;
use crate::scene::scorer_kind::{FormName, SceneScorerKind, ScorerMemory};

/// The volume counts' unit: a millionth of a cubic unit (a cubic centimetre in metres).
const PER_CUBIC_UNIT: f64 = 1e6;

/// The `[bounds]` kind of scorer.
pub struct Bounds;

/// `[bounds]`
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoundsFile {
    min: [f32; 3],
    max: [f32; 3],
    #[serde(default = "one")]
    weight: f64,
}

fn one() -> f64 {
    1.0
}

/// The `[bounds]` table, resolved: the box and the weight of the volume outside it.
#[derive(Clone, Debug)]
pub struct BoundsGoal {
    /// The box's lowest corner.
    pub min: Vec3,
    /// The box's highest corner, above `min` on every axis.
    pub max: Vec3,
    /// Fitness lost per cubic unit outside the box, at least 0.
    pub weight: f64,
}

/// What of one model lies outside the box.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct BoundsCounts {
    /// The volume of the instances' world bounding boxes outside the box, summed over
    /// the instances, in millionths of a cubic unit (each instance's rounded).
    pub outside: u64,
    /// The instances whose bounding box reaches outside the box.
    pub instances: u32,
}

/// Counts the volume of each instance's world bounding box outside a box.
///
/// ```
/// use shapegen::scene::Scene;
/// use shapegen_runtime::score::Scorer;
///
/// let text = r#"
/// generator = "spaceship"
/// [limits]
/// min_len = 4
/// max_len = 100
/// max_depth = 15
/// [bounds]
/// min = [-0.5, -10, -10]
/// max = [10, 10, 10]
/// weight = 2
/// "#;
/// let scene = Scene::parse(text, std::path::Path::new("scene.toml"))?;
/// let scorer = shapegen::scene::SceneScorer::new::<generators::Spaceship>(&scene)?;
/// let bounds = scorer.bounds().unwrap();
/// // The unit cube scaled by 2 spans [-1, 1]: half a unit of x of it is outside.
/// let cube = shapegen_runtime::Instance {
///     transform: glam::Affine3A::from_scale(glam::Vec3::splat(2.0)),
///     mesh: shapegen_runtime::MeshId(0),
/// };
/// let counts = bounds.count(&[cube], &mut bounds.scratch());
/// assert_eq!((counts.outside, counts.instances), (2_000_000, 1));
/// assert_eq!(bounds.fitness(&counts), -4.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct BoundsScorer {
    goal: BoundsGoal,
    /// Each mesh's bounding box in its own space, by mesh id; `None` for an empty mesh.
    meshes: Vec<Option<(Vec3, Vec3)>>,
}

impl BoundsScorer {
    /// The scorer of `goal` for models made of `meshes`.
    pub fn new(goal: BoundsGoal, meshes: &BoundMeshes) -> Self {
        let meshes = meshes.iter().map(|(_, _, mesh)| mesh.bounds()).collect();
        BoundsScorer { goal, meshes }
    }

    /// The volume of `instance`'s world bounding box outside the box, in millionths of
    /// a cubic unit.
    fn outside(&self, instance: &Instance) -> u64 {
        let Some(Some((lo, hi))) = self.meshes.get(instance.mesh.0 as usize) else {
            return 0;
        };
        let corners = (0..8).map(|i| {
            let pick = |bit: usize, axis: usize| if i >> bit & 1 == 0 { lo[axis] } else { hi[axis] };
            let corner = Vec3::new(pick(0, 0), pick(1, 1), pick(2, 2));
            instance.transform.transform_point3(corner)
        });
        let (min, max) = corners.fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(a, b), p| {
            (a.min(p), b.max(p))
        });
        let volume = |lo: Vec3, hi: Vec3| -> f64 {
            let size = (hi - lo).max(Vec3::ZERO);
            f64::from(size.x) * f64::from(size.y) * f64::from(size.z)
        };
        let inside = volume(min.max(self.goal.min), max.min(self.goal.max));
        let outside = (volume(min, max) - inside).max(0.0);
        (outside * PER_CUBIC_UNIT).round() as u64
    }

    /// The counts of `instances` alone.
    fn tally(&self, instances: &[Instance]) -> BoundsCounts {
        let mut counts = BoundsCounts::default();
        for instance in instances {
            let outside = self.outside(instance);
            counts.outside += outside;
            counts.instances += u32::from(outside > 0);
        }
        counts
    }
}

impl Scorer for BoundsScorer {
    type Counts = BoundsCounts;
    type Scratch = ();

    fn scratch(&self) {}

    fn count(&self, instances: &[Instance], (): &mut ()) -> BoundsCounts {
        self.tally(instances)
    }

    fn fitness(&self, counts: &BoundsCounts) -> f64 {
        -self.goal.weight * (counts.outside as f64 / PER_CUBIC_UNIT)
    }
}

impl RetainedScorer for BoundsScorer {
    type State = BoundsCounts;

    fn count_retained(&self, instances: &[Instance], (): &mut ()) -> Result<BoundsCounts, Overflow> {
        Ok(self.count(instances, &mut ()))
    }

    fn update(
        &self,
        state: &mut BoundsCounts,
        removed: &[Instance],
        added: &[Instance],
        (): &mut (),
    ) -> Result<(), Overflow> {
        let (gone, new) = (self.tally(removed), self.tally(added));
        state.outside = state.outside - gone.outside + new.outside;
        state.instances = state.instances - gone.instances + new.instances;
        Ok(())
    }

    fn state_counts(&self, state: &BoundsCounts) -> BoundsCounts {
        *state
    }

    fn visit_cells(&self, _: &BoundsCounts, _: &mut dyn FnMut(&CellCounts)) {}

    fn visit_blocks(&self, _: &BoundsCounts, _: &mut dyn FnMut(usize, usize)) {}
}

impl SceneScorerKind for Bounds {
    type File = BoundsFile;
    type Goal = BoundsGoal;
    type Scorer = BoundsScorer;
    type Counts = BoundsCounts;
    type Gpu<'a> = Infallible;

    fn resolve(r: &Resolver<'_>, file: &BoundsFile, _: FormName) -> Result<BoundsGoal, SceneError> {
        for (key, corner) in [("bounds.min", file.min), ("bounds.max", file.max)] {
            if let Some(v) = corner.iter().find(|v| !v.is_finite()) {
                return Err(r.invalid(key, format!("{v} is not a finite number")));
            }
        }
        let (min, max) = (Vec3::from(file.min), Vec3::from(file.max));
        if !min.cmplt(max).all() {
            return Err(r.invalid(
                "bounds.max",
                format!("{max} must be above bounds.min = {min} on every axis"),
            ));
        }
        let weight = r.non_negative("bounds.weight", file.weight)?;
        Ok(BoundsGoal { min, max, weight })
    }

    fn memory(_: &BoundsGoal, _: usize) -> ScorerMemory {
        ScorerMemory::default()
    }

    fn make(goal: &BoundsGoal, meshes: &BoundMeshes) -> Result<BoundsScorer, ValueError> {
        Ok(BoundsScorer::new(goal.clone(), meshes))
    }
}
