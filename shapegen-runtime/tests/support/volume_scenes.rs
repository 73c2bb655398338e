//! Boxes, targets, the paper's grid and scorers on them, shared by the volume tests on the CPU and on the
//! GPU.

use glam::{Affine3A, Quat, Vec3};
use shapegen_runtime::score::Form;
use shapegen_runtime::score::volume::{Fill, Grid, VolumeScorer, VolumeTarget};
use shapegen_runtime::{BoundMeshes, CUBE, Grammar, Instance, Mesh, MeshLibrary};

use super::city_expanded::City;
use super::scenes::scenes;

/// The unit cube mesh moved to span `lo ..= hi`.
pub fn block(lo: Vec3, hi: Vec3) -> Mesh {
    let mut m = Mesh::unit_cube();
    for p in &mut m.positions {
        *p = lo + (*p + 0.5) * (hi - lo);
    }
    m
}

pub fn target(name: &str, mesh: Mesh, inside: f64, outside: f64) -> VolumeTarget {
    VolumeTarget {
        name: name.into(),
        mesh,
        inside,
        outside,
        fill: Fill::Parity,
    }
}

/// A box spanning `lo ..= hi`, axis-aligned.
pub fn aabb(lo: Vec3, hi: Vec3) -> Instance {
    Instance {
        transform: Affine3A::from_scale_rotation_translation(
            hi - lo,
            Quat::IDENTITY,
            (lo + hi) / 2.0,
        ),
        mesh: CUBE,
    }
}

/// A box turned about all three axes, around `(1.5, 0.2, 0.5)`.
pub fn turned_box() -> Instance {
    Instance {
        transform: Affine3A::from_scale_rotation_translation(
            Vec3::new(2.3, 0.7, 3.1),
            Quat::from_euler(glam::EulerRot::XYZ, 0.3, 0.9, -0.2),
            Vec3::new(1.5, 0.2, 0.5),
        ),
        mesh: CUBE,
    }
}

/// The grid of the paper's spaceship scene.
pub fn paper_grid() -> Grid {
    Grid::new(
        Vec3::new(-5.0, -5.0, -2.0),
        Vec3::new(5.0, 5.0, 18.0),
        [100, 200, 100],
    )
    .unwrap()
}

/// The paper's spaceship target on the paper's grid, in the smooth form, for the
/// spaceship grammar bound to `bound`.
pub fn paper_ship_scorer(bound: &BoundMeshes) -> VolumeScorer {
    let ship = Mesh::from_obj(scenes().join("spaceship_volume/spaceship_target.obj")).unwrap();
    VolumeScorer::new(
        paper_grid(),
        &[target("ship", ship, 1.0, -1.0)],
        bound,
        Form::Smooth {
            good: 2.0,
            bad: 15.0,
        },
    )
    .unwrap()
}

/// A tower block over the city's middle lots on `grid`, overlaps costing 1 each.
pub fn city_tower_scorer(grid: Grid) -> VolumeScorer {
    let bound = MeshLibrary::new().bind(City::GRAPH).unwrap();
    let t = target(
        "tower",
        block(Vec3::new(-3.0, 0.0, -3.0), Vec3::new(3.0, 8.0, 3.0)),
        1.0,
        -1.0,
    );
    VolumeScorer::new(grid, &[t], &bound, Form::Weighted { overlap: 1.0 }).unwrap()
}
