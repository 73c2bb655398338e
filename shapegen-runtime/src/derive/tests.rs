//! The scope operations as grammar rules see them, through [`Shape`].

use glam::{vec2, vec3};

use super::{Derivation, GeneView, Grammar, Shape, Site};
use crate::geometry::closed::tests::{assert_watertight, volume as signed_volume};
use crate::geometry::{
    Axis, Face, Instance, Margins, MeshId, Part, Polygon, RoofMeshes, RoofShape,
};
use crate::graph::{GeneratorGraph, NodeDesc};

/// The graph of a grammar of one node type, `$name`, without parameters or children,
/// drawing the meshes `$meshes`.
macro_rules! one_node_graph {
    ($name:literal, $key:literal, $meshes:expr) => {
        GeneratorGraph {
            name: $name,
            key: $key,
            axiom: 0,
            nodes: &[NodeDesc {
                name: $name,
                params: &[],
                slots: &[],
                links: 0,
                param_words: 0,
            }],
            meshes: $meshes,
        }
    };
}

/// A one-node grammar whose rule builds a small house: walls cut into a ground floor
/// and an upper floor with repeated windows, and a roof slab extruded from the top.
struct House;

static HOUSE: GeneratorGraph = one_node_graph!("House", "house", &["cube"]);

impl Grammar for House {
    const GRAPH: &'static GeneratorGraph = &HOUSE;

    fn derive_gene<'a>(shape: Shape<'a, Self>, _gene: GeneView<'a>) {
        let house = shape.with_size(vec3(8.0, 6.0, 4.0));
        for (face, wall) in house.faces() {
            match face {
                Face::Top => wall.extrude(0.5).emit(crate::geometry::CUBE),
                Face::Bottom => {}
                _ => {
                    let floors = [Part::Abs(2.0), Part::Float(1.0)];
                    let mut floors = wall.split(Axis::Y, &floors);
                    floors
                        .next()
                        .unwrap()
                        .extrude(0.1)
                        .emit(crate::geometry::CUBE);
                    for window in floors.next().unwrap().repeat(Axis::X, 1.5) {
                        window
                            .resize(vec3(0.5, 0.5, 1.0))
                            .extrude(-0.2)
                            .emit(crate::geometry::CUBE);
                    }
                }
            }
        }
    }
}

#[test]
fn shapes_split_repeat_and_take_faces() {
    let mut out: Vec<Instance> = Vec::new();
    Derivation::run::<House>(&[0, 0], &Site::NONE, &mut out);
    // Roof + per side wall (front, back: 8 wide; left, right: 4 wide) a ground floor
    // and round(w / 1.5) windows: 5, 5, 3, 3.
    assert_eq!(out.len(), 1 + 4 + 5 + 5 + 3 + 3);
    let roof = out[out.len() - 1].transform;
    assert_eq!(
        roof.transform_point3(glam::Vec3::ZERO),
        vec3(0.0, 3.25, 0.0)
    );
    // The front ground floor: 8 x 2 slab 0.1 deep standing on z = 2, from y = -3 to -1.
    let ground = out[0].transform;
    assert_eq!(
        ground.transform_point3(glam::Vec3::ZERO),
        vec3(0.0, -2.0, 2.05)
    );
    assert_eq!(
        ground.transform_vector3(glam::Vec3::ONE),
        vec3(8.0, 2.0, 0.1)
    );
    // The first front window: 1.6 x 4 tile scaled to 0.8 x 2, sunk 0.2 into the wall.
    let window = out[1].transform;
    assert!(
        window
            .transform_point3(glam::Vec3::ZERO)
            .abs_diff_eq(vec3(-3.2, 1.0, 1.9), 1e-6)
    );
    assert!(
        window
            .transform_vector3(glam::Vec3::ONE)
            .abs_diff_eq(vec3(0.8, 2.0, 0.2), 1e-6)
    );
}

/// A one-node grammar whose rule stands a 10 x 4 x 6 mass and puts a hip roof on it.
struct Hipped;

static HIPPED: GeneratorGraph =
    one_node_graph!("Hipped", "hipped", &["cube", "roof_gable", "roof_hip_end"]);

impl Grammar for Hipped {
    const GRAPH: &'static GeneratorGraph = &HIPPED;

    fn derive_gene<'a>(shape: Shape<'a, Self>, _gene: GeneView<'a>) {
        let mass = shape.with_size(vec3(10.0, 4.0, 6.0));
        mass.emit(crate::geometry::CUBE);
        let pieces = RoofMeshes {
            gable: MeshId(1),
            shed: MeshId(1),
            pyramid: MeshId(1),
            hip_end: MeshId(2),
        };
        mass.roof(RoofShape::Hip { pitch: 0.5 }, 0.0, &pieces)
            .expect("a valid pitch");
        // A pitch out of range emits nothing.
        assert!(
            mass.roof(RoofShape::Hip { pitch: 2.0 }, 0.0, &pieces)
                .is_err()
        );
    }
}

#[test]
fn shapes_put_roofs_on_their_tops() {
    let mut out: Vec<Instance> = Vec::new();
    Derivation::run::<Hipped>(&[0, 0], &Site::NONE, &mut out);
    let meshes: Vec<u32> = out.iter().map(|i| i.mesh.0).collect();
    assert_eq!(meshes, [0, 1, 2, 2]);
    // The gable prism over the middle: 10 - 6 long, 3 tan(0.5) high, on the top at y = 2.
    let h = 3.0 * 0.5f32.tan();
    let middle = out[1].transform;
    assert!(
        middle
            .transform_point3(glam::Vec3::ZERO)
            .abs_diff_eq(vec3(0.0, 2.0 + h / 2.0, 0.0), 1e-6)
    );
    assert!(
        middle
            .transform_vector3(glam::Vec3::ONE)
            .abs_diff_eq(vec3(4.0, h, 6.0), 1e-6)
    );
}

/// A one-node grammar whose rule builds a 12 x 9 x 8 block from its walls and caps,
/// its front split into three floors of four tiles, each inset as a window, one as a
/// door.
struct Block;

static BLOCK: GeneratorGraph = one_node_graph!("Block", "block", &["cube", "wall", "window"]);

impl Grammar for Block {
    const GRAPH: &'static GeneratorGraph = &BLOCK;

    fn derive_gene<'a>(shape: Shape<'a, Self>, _gene: GeneView<'a>) {
        let footprint = Polygon::rectangle(vec2(12.0, 8.0)).unwrap();
        let block = shape
            .translate(vec3(3.0, 4.5, -2.0))
            .rotate_y(0.6)
            .with_size(vec3(12.0, 9.0, 8.0));
        let (wall, window) = (MeshId(1), MeshId(2));
        for (face, side) in block.walls(&footprint, 9.0) {
            if face != Face::Front {
                assert_eq!(side.emit_rect(wall), 2);
                continue;
            }
            for (floor, level) in side.repeat(Axis::Y, 3.0).enumerate() {
                for (k, tile) in level.repeat(Axis::X, 3.0).enumerate() {
                    assert_eq!(tile.size(), vec3(3.0, 3.0, 0.0));
                    let margins = if floor == 0 && k == 1 {
                        Margins::door(0.8, 0.6)
                    } else {
                        Margins::new(0.75, 0.75, 0.8, 0.6)
                    };
                    let inset = tile.inset(margins, 0.25).unwrap();
                    for part in inset.frame.into_iter().chain(inset.reveals) {
                        part.emit_rect(wall);
                    }
                    inset.opening.emit_rect(window);
                }
            }
        }
        assert_eq!(block.top_cap(&footprint, 9.0, wall), 2);
        assert_eq!(block.bottom_cap(&footprint, wall), 2);
        assert!(block.inset(Margins::uniform(7.0), 0.1).is_none());
    }
}

#[test]
fn shapes_build_a_closed_facade() {
    let mut out: Vec<Instance> = Vec::new();
    Derivation::run::<Block>(&[0, 0], &Site::NONE, &mut out);
    assert_eq!(out.iter().filter(|i| i.mesh == MeshId(2)).count(), 12 * 2);
    assert_watertight(&out);
    // Eleven windows 1.5 x 1.6 and a door 1.4 x 2.4, 0.25 deep.
    let recesses = 0.25 * (11.0 * 1.5 * 1.6 + 1.4 * 2.4);
    let volume = signed_volume(&out);
    assert!(
        (volume - (12.0 * 8.0 * 9.0 - recesses)).abs() < 1e-3,
        "{volume}"
    );
}
