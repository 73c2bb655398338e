//! Pictures of the CGA-style operations on scopes and polygons, one per operation, for
//! `docs/cga-operations.md`: the extrusion of an L footprint, its walls (CGA's `comp`)
//! with the front ones picked out, a setback tower on a podium, a facade of floors and
//! tiles with inset windows and a door, and the five roofs over an L with an overhang.
//!
//! ```sh
//! cargo run --release --example cga_gallery    # writes docs/cga/*.png
//! ```

use std::path::Path;

use glam::{DVec2, Vec3, vec3};
use shapegen::export::{Model, Palette, Preview};
use shapegen::geometry::{Margins, Mesh, MeshId, MeshLibrary, Polygon, RoofShape};
use shapegen::{Axis, BoundMeshes, Face, Instance, Scope};

/// The facet meshes, by name: every one is [`Mesh::facet`], coloured by the palette.
const NAMES: [&str; 7] = ["cube", "wall", "front", "roof", "window", "door", "tower"];
const WALL: MeshId = MeshId(1);
const FRONT: MeshId = MeshId(2);
const ROOF: MeshId = MeshId(3);
const WINDOW: MeshId = MeshId(4);
const DOOR: MeshId = MeshId(5);
const TOWER: MeshId = MeshId(6);

/// Picture size in pixels.
const SIZE: u32 = 320;

/// An L, 16 across, its arms 8 wide.
fn l_footprint() -> Polygon {
    let points = [
        [-8.0, -8.0],
        [8.0, -8.0],
        [8.0, 0.0],
        [0.0, 0.0],
        [0.0, 8.0],
        [-8.0, 8.0],
    ]
    .map(|[x, y]| DVec2::new(x, y));
    Polygon::from_f64(&points).expect("a simple L")
}

/// A lot of `size` standing on the ground (its bottom face at y = 0).
fn lot(size: Vec3) -> Scope {
    Scope::UNIT
        .with_size(size)
        .translate(vec3(0.0, size.y / 2.0, 0.0))
}

/// CGA's `extrude`: the L as a prism 10 high.
fn extrude() -> Vec<Instance> {
    let mut out = Vec::new();
    lot(vec3(16.0, 10.0, 16.0)).extrude_polygon(&l_footprint(), 10.0, WALL, &mut out);
    out
}

/// CGA's `comp(f)`: the L's walls, the front ones (facing the lot's +z) in their own
/// colour, and its caps.
fn comp() -> Vec<Instance> {
    let (l, lot, mut out) = (l_footprint(), lot(vec3(16.0, 10.0, 16.0)), Vec::new());
    for (face, wall) in lot.walls(&l, 10.0) {
        wall.emit_rect(if face == Face::Front { FRONT } else { WALL }, &mut out);
    }
    lot.top_cap(&l, 10.0, ROOF, &mut out);
    lot.bottom_cap(&l, WALL, &mut out);
    out
}

/// CGA's `setback`: a podium 4 high on the L, its top the setback's strips, and a tower
/// 12 high on the remainder.
fn setback() -> Vec<Instance> {
    let (l, mut out) = (l_footprint(), Vec::new());
    let setback = l.setback(2.0).expect("the L's arms are 8 wide");
    let podium = lot(vec3(16.0, 4.0, 16.0));
    for (_, wall) in podium.walls(&l, 4.0) {
        wall.emit_rect(WALL, &mut out);
    }
    podium.bottom_cap(&l, WALL, &mut out);
    for strip in &setback.strips {
        podium.top_cap(strip, 4.0, ROOF, &mut out);
    }
    let tower = lot(vec3(16.0, 12.0, 16.0)).translate(vec3(0.0, 4.0, 0.0));
    let remainder = &setback.remainder;
    for (_, wall) in tower.walls(remainder, 12.0) {
        wall.emit_rect(TOWER, &mut out);
    }
    tower.top_cap(remainder, 12.0, ROOF, &mut out);
    out
}

/// A facade: a 12 x 9 x 8 block whose walls are split into floors 3 high and tiles
/// about 3 wide, each tile a window inset 0.3 deep, one of the front's a door.
fn facade() -> Vec<Instance> {
    let footprint = Polygon::rectangle(glam::vec2(12.0, 8.0)).expect("a rectangle");
    let (block, mut out) = (lot(vec3(12.0, 9.0, 8.0)), Vec::new());
    for (face, wall) in block.walls(&footprint, 9.0) {
        for (floor, level) in wall.repeat(Axis::Y, 3.0).enumerate() {
            for (k, tile) in level.repeat(Axis::X, 3.0).enumerate() {
                let door = face == Face::Front && floor == 0 && k == 1;
                let (margins, opening) = if door {
                    (Margins::door(0.8, 0.6), DOOR)
                } else {
                    (Margins::new(0.75, 0.75, 0.8, 0.6), WINDOW)
                };
                let inset = tile.inset(margins, 0.3).expect("a tile 3 x 3");
                for part in inset.frame.into_iter().chain(inset.reveals) {
                    part.emit_rect(WALL, &mut out);
                }
                inset.opening.emit_rect(opening, &mut out);
            }
        }
    }
    block.top_cap(&footprint, 9.0, ROOF, &mut out);
    block.bottom_cap(&footprint, WALL, &mut out);
    out
}

/// A house on the L, walls 5 high, under `shape` with an overhang of 0.8.
fn roof(shape: RoofShape) -> Vec<Instance> {
    let (l, house, mut out) = (l_footprint(), lot(vec3(16.0, 5.0, 16.0)), Vec::new());
    house.extrude_polygon(&l, 5.0, WALL, &mut out);
    house
        .roof_polygon(&l, shape, 0.8, ROOF, &mut out)
        .expect("measures in range");
    out
}

fn save(dir: &Path, name: &str, instances: &[Instance], meshes: &BoundMeshes) {
    let palette = Palette::new()
        .with("wall", [0.85, 0.8, 0.7])
        .with("front", [0.4, 0.62, 0.38])
        .with("roof", [0.62, 0.3, 0.22])
        .with("window", [0.25, 0.4, 0.6])
        .with("door", [0.35, 0.2, 0.1])
        .with("tower", [0.6, 0.7, 0.8]);
    let path = dir.join(format!("{name}.png"));
    Preview::framing(instances, meshes, SIZE, SIZE)
        .render(Model::new(instances, meshes, &palette))
        .expect("every mesh bound")
        .save(&path)
        .expect("a writable docs/cga");
    println!("{}: {} facets", path.display(), instances.len());
}

fn main() {
    let mut library = MeshLibrary::new();
    for name in &NAMES[1..] {
        library.register(*name, Mesh::facet()).expect("a facet");
    }
    let meshes = library.bind_names("Gallery", &NAMES).expect("registered");
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/cga");
    std::fs::create_dir_all(&dir).expect("a writable docs folder");

    save(&dir, "extrude", &extrude(), &meshes);
    save(&dir, "comp", &comp(), &meshes);
    save(&dir, "setback", &setback(), &meshes);
    save(&dir, "facade", &facade(), &meshes);
    let pitch = 35f32.to_radians();
    let roofs = [
        ("flat", RoofShape::Flat { thickness: 0.6 }),
        ("shed", RoofShape::Shed { pitch }),
        ("gable", RoofShape::Gable { pitch }),
        ("hip", RoofShape::Hip { pitch }),
        ("pyramid", RoofShape::Pyramid { pitch }),
    ];
    for (name, shape) in roofs {
        save(&dir, &format!("roof_{name}"), &roof(shape), &meshes);
    }
}
