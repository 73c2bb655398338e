//! A building on a polygon lot, grown as CGA grows one: the lot's footprint extruded
//! into a mass, the mass split into its walls (`comp`), each wall split into floors and
//! tiles with inset windows and a door, a straight-skeleton roof on top, or a setback
//! storey standing on it. Evolution chooses the storeys' heights and setbacks, the
//! facades' rhythms (floor height, tile width, window proportions and depth, a door) and
//! the roofs' shapes, pitches and overhangs.
//!
//! The lot is the site's ([`Site`](shapegen_runtime::Site), a scene's `[lot]` table):
//! any simple polygon, concave ones included; without one, [`DEFAULT_LOT`]. Every model
//! is a closed surface of facets (walls, floor slabs, roofs, and windows and doors set
//! back into their walls), so the volume scorer counts its inside and the glTF and OBJ
//! exports hold one material per part: `wall`, `roof`, `window`, `door` and `slab`.
//!
//! # Nodes
//!
//! | node | parameters | children | geometry |
//! |---|---|---|---|
//! | [`Lot`] | `front`, `sides` | `mass` | the lot set back by `front` from its edges facing the front and by `sides` from the others; the mass on it (a [`DEFAULT_HEIGHT`] block when absent) |
//! | [`Mass`] | `height` | `front`, `sides`, `roof`, `upper` | the footprint extruded by `height`; `front` dresses the walls facing `+z`, `sides` the others (plain walls when absent); `upper` stands on top, else `roof`, else a flat roof |
//! | [`Setback`] | `depth` | `mass` | the footprint moved inward by `depth`; nothing where the lot is too narrow for it |
//! | [`Roof`] | `shape`, `pitch`, `overhang` | none | a flat, shed, gable, hip or pyramid roof over the footprint |
//! | [`Facade`] | `floor_height`, `tile_width` | `window`, `door` | floors and tiles; the ground floor's middle tile holds the door, every other tile a window (plain wall when absent) |
//! | [`Window`] | `width`, `height`, `sill`, `depth` | none | an opening of the given shares of its tile, set back by `depth` |
//! | [`Door`] | `width`, `height`, `depth` | none | an opening on the tile's bottom |
//!
//! ```
//! use generators::lot_building::{self, LotBuilding};
//! use shapegen_runtime::prelude::*;
//! use shapegen_runtime::Site;
//!
//! // The L-shaped lot, a 9-high mass with windows on the front and a hip roof.
//! let l = lot_building::L_LOT.clone();
//! let lot = lot_building::Lot { front: 0.0, sides: 0.0 };
//! let mut g = Genome::<LotBuilding>::with_root(lot)?;
//! let mass = g.attach(0, "mass", lot_building::Mass { height: 9.0 })?;
//! let facade = lot_building::Facade { floor_height: 3.0, tile_width: 2.0 };
//! let front = g.attach(mass, "front", facade)?;
//! let window = lot_building::Window { width: 0.5, height: 0.5, sill: 0.4, depth: 0.2 };
//! g.attach(front, "window", window)?;
//! let roof = lot_building::Roof { shape: 3, pitch: 30f32.to_radians(), overhang: 0.4 };
//! g.attach(mass, "roof", roof)?;
//!
//! let mut instances = Vec::new();
//! g.derive_on(&Site::with_lot(l), &mut instances);
//! let meshes = generators::default_meshes().bind(LotBuilding::GRAPH)?;
//! let windows = instances.iter().filter(|i| i.mesh == lot_building::WINDOW).count();
//! // The one wall facing the front, 16 wide: 8 tiles on each of 3 floors, a window
//! // each of two facets.
//! assert_eq!(windows, 8 * 3 * 2);
//! assert_eq!(meshes.name(lot_building::ROOF), Some("roof"));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::sync::LazyLock;

use shapegen_runtime::generator;
use shapegen_runtime::genome::Limits;
use shapegen_runtime::geometry::{Margins, Polygon};
use shapegen_runtime::prelude::*;

use crate::building::{capped_tile, roof_shape};

/// The lot without a site: a 10 x 10 square centred on the origin, [`Building`]'s
/// lot.
///
/// [`Building`]: crate::Building
pub static DEFAULT_LOT: LazyLock<Polygon> = LazyLock::new(|| {
    Polygon::rectangle(crate::building::LOT).expect("a 10 x 10 square is a polygon")
});

/// An L-shaped lot, the one of the project's building scene
/// (`scenes/lots/l_lot.geojson`): 16 x 12 centred on the origin, less its 8 x 6 corner
/// at `x > 0`, `y > 0`.
pub static L_LOT: LazyLock<Polygon> = LazyLock::new(|| {
    Polygon::new([
        vec2(-8.0, -6.0),
        vec2(8.0, -6.0),
        vec2(8.0, 0.0),
        vec2(0.0, 0.0),
        vec2(0.0, 6.0),
        vec2(-8.0, 6.0),
    ])
    .expect("the L is a simple polygon")
});

/// The height of the block a lot without a mass holds.
pub const DEFAULT_HEIGHT: f32 = 3.0;

/// The genome limits of buildings on lots: length 2 to 200, depth 16 (seven storeys).
pub const LIMITS: Limits = Limits {
    min_len: 2,
    max_len: 200,
    max_depth: 16,
};

generator! {
    /// A building on a polygon lot: storeys extruded from the lot and set back from it,
    /// dressed with facades of floors, tiles, windows and a door, and roofed.
    pub LotBuilding {
        axiom Lot;
        meshes {
            /// Walls: the facades' wall surfaces and the recesses' sides.
            WALL = "wall",
            /// Roofs, flat ones and terraces included.
            ROOF = "roof",
            /// Window panes.
            WINDOW = "window",
            /// Doors.
            DOOR = "door",
            /// Floor slabs hidden inside the building: its bottom, and the top of a
            /// storey under a pitched roof.
            SLAB = "slab",
        }

        /// The axiom: the site's lot, or [`DEFAULT_LOT`], set back from the street: the
        /// building's footprint is the lot with its edges facing the front (`+z`) moved
        /// inward by `front` and the others by `sides` (the whole lot where that leaves
        /// no polygon of the same edges).
        node Lot {
            params {
                /// The setback from the edges facing the front.
                front: f32 ~ uniform(0.0, 4.0),
                /// The setback from the other edges.
                sides: f32 ~ uniform(0.0, 2.0),
            }
            children {
                /// The ground storey.
                mass: Mass = 1.0,
            }
            derive(s) {
                let lot: &Polygon = s.site().lot().unwrap_or(&DEFAULT_LOT);
                // A flat box on the ground: the footprint lies on its bottom face.
                let ground = s.with_size(Vec3::ZERO).on_footprint(lot);
                let ground = ground
                    .setback_edges(|i| if faces_front(lot, i) { front } else { sides })
                    .unwrap_or(ground);
                let footprint = ground.footprint().unwrap_or(lot);
                match mass {
                    Some(mass) => ground.derive(mass),
                    None => {
                        ground.extrude_polygon(footprint, DEFAULT_HEIGHT, WALL);
                    }
                }
            }
        }

        /// A storey: the footprint extruded by `height` (CGA's `extrude`), its walls
        /// dressed by the facades (`comp(f)`), with a storey set back on top, or a roof.
        node Mass {
            params {
                /// The storey's height.
                height: f32 ~ uniform(3.0, 15.0),
            }
            children {
                /// The facade of the walls facing the front (`+z`).
                front: Facade = 0.8,
                /// The facade of the other walls.
                sides: Facade = 0.6,
                /// The roof, where no storey stands on this one.
                roof: Roof = 0.7,
                /// A storey on top, set back from this one's walls.
                upper: Setback = 0.35,
            }
            derive(s) {
                let Some(footprint) = s.footprint() else {
                    return;
                };
                let size = s.size();
                let block = s
                    .translate(vec3(0.0, (height - size.y) / 2.0, 0.0))
                    .with_size(vec3(size.x, height, size.z));
                for (face, wall) in block.walls(footprint, height) {
                    let facade = if face == Face::Front { front } else { sides };
                    match facade {
                        Some(facade) => wall.derive(facade),
                        None => {
                            wall.emit_rect(WALL);
                        }
                    }
                }
                block.bottom_cap(footprint, SLAB);
                // The next storey stands on the top face.
                let top = block
                    .translate(vec3(0.0, height / 2.0, 0.0))
                    .with_size(vec3(size.x, 0.0, size.z));
                let pitched = upper.is_none() && roof.is_some();
                block.top_cap(footprint, height, if pitched { SLAB } else { ROOF });
                match (upper, roof) {
                    (Some(upper), _) => top.derive(upper),
                    (None, Some(roof)) => block.derive(roof),
                    (None, None) => {}
                }
            }
        }

        /// A storey set back from the walls below by `depth` on every side (CGA's
        /// `setback`): nothing where the footprint is too narrow for it.
        node Setback {
            params {
                /// How far the walls move inward.
                depth: f32 ~ uniform(0.5, 3.0),
            }
            children {
                /// The storey on the smaller footprint.
                mass: Mass = 0.9,
            }
            derive(s) {
                if let (Some(inner), Some(mass)) = (s.setback(depth), mass) {
                    inner.derive(mass);
                }
            }
        }

        /// A roof over the footprint on the top of the storey (CGA's `roofGable`,
        /// `roofHip`, `roofPyramid`, `roofShed`, a flat roof a slab): a straight-skeleton
        /// roof on any simple polygon.
        node Roof {
            params {
                /// The shape: 0 flat, 1 shed, 2 gable, 3 hip, 4 pyramid.
                shape: u32 ~ weighted([1.0, 1.0, 2.0, 2.0, 1.0]),
                /// The slope of the roof's faces.
                pitch: f32 ~ degrees(15.0, 60.0),
                /// How far the eave reaches past the walls.
                overhang: f32 ~ uniform(0.0, 0.8),
            }
            derive(s) {
                if let Some(footprint) = s.footprint() {
                    // Out of range only in a hand-edited genome: then no roof.
                    let _ = s.roof_polygon(footprint, roof_shape(shape, pitch), overhang, ROOF);
                }
            }
        }

        /// A facade on one wall: floors of about `floor_height` from the bottom, each
        /// split into tiles of about `tile_width` (at most
        /// [`MAX_TILES`](crate::building::MAX_TILES) of each; CGA's `split(y) { ~f : Floor }*` and
        /// `split(x) { ~t : Tile }*`); the middle tile of the ground floor holds the door,
        /// every other tile a window.
        node Facade {
            params {
                /// Height of a floor, before rounding the count to fill the wall.
                floor_height: f32 ~ uniform(2.6, 4.5),
                /// Width of a tile, before rounding the count to fill the floor.
                tile_width: f32 ~ uniform(1.5, 4.0),
            }
            children {
                /// The window of every tile but the door's (plain wall when absent).
                window: Window = 0.85,
                /// The door (plain wall, or a window, when absent).
                door: Door = 0.5,
            }
            derive(s) {
                let floor_height = capped_tile(s.size().y, floor_height);
                for (i, floor) in s.repeat(Axis::Y, floor_height).enumerate() {
                    let tiles = floor.repeat(Axis::X, capped_tile(floor.size().x, tile_width));
                    let middle = tiles.len() / 2;
                    for (j, tile) in tiles.enumerate() {
                        match (door, window) {
                            (Some(door), _) if i == 0 && j == middle => tile.derive(door),
                            (_, Some(window)) => tile.derive(window),
                            _ => {
                                tile.emit_rect(WALL);
                            }
                        }
                    }
                }
            }
        }

        /// A window set back into its tile (CGA's `inset`): an opening of `width` and
        /// `height` shares of the tile, centred across it, `sill` the share of the height
        /// left under it, `depth` deep.
        node Window {
            params {
                /// The opening's share of the tile's width.
                width: f32 ~ uniform(0.3, 0.8),
                /// The opening's share of the tile's height.
                height: f32 ~ uniform(0.3, 0.7),
                /// The share of the rest of the height that lies under the opening.
                sill: f32 ~ uniform(0.2, 0.6),
                /// How far the pane lies behind the wall.
                depth: f32 ~ uniform(0.05, 0.4),
            }
            derive(s) {
                let (w, h) = (s.size().x, s.size().y);
                let side = w * (1.0 - width) / 2.0;
                let rest = h * (1.0 - height);
                let margins = Margins::new(side, side, rest * sill, rest * (1.0 - sill));
                opening(s, margins, depth, WINDOW);
            }
        }

        /// A door set back into its tile, standing on the tile's bottom.
        node Door {
            params {
                /// The opening's share of the tile's width.
                width: f32 ~ uniform(0.3, 0.7),
                /// The opening's share of the tile's height.
                height: f32 ~ uniform(0.6, 0.9),
                /// How far the door lies behind the wall.
                depth: f32 ~ uniform(0.05, 0.4),
            }
            derive(s) {
                let (w, h) = (s.size().x, s.size().y);
                let side = w * (1.0 - width) / 2.0;
                opening(s, Margins::door(side, h * (1.0 - height)), depth, DOOR);
            }
        }
    }
}

/// How deep, at most `depth`, a recess may reach into a storey on `footprint` and stay
/// inside it: the largest of `depth` and its halves (down to a 256th, else 0) by which
/// every wall can move inward and leave a polygon of the same walls. A very thin storey
/// gets shallow windows rather than windows that pierce the wall behind.
fn deepest_recess(footprint: Option<&Polygon>, depth: f32) -> f32 {
    footprint.map_or(depth, |f| {
        let (reach, _) = f.offset_at_most(-f64::from(depth));
        -reach as f32
    })
}

/// Whether edge `i` of `footprint` faces the front (`+z`, south in map coordinates):
/// its outward normal is nearer `+z` than any other horizontal axis.
fn faces_front(footprint: &Polygon, i: usize) -> bool {
    // Map `y` is north, world `-z`: facing `+z` is an inward normal pointing north.
    let inward = footprint.inward_normal(i);
    inward.y >= inward.x.abs()
}

/// Emits the tile `s` with an opening of `margins` set back by `depth` (less where the
/// storey is too thin for it: see [`deepest_recess`]), its wall parts as [`WALL`] and
/// the opening as `pane`; a plain wall where the margins leave no opening.
fn opening(s: Shape<'_, LotBuilding>, margins: Margins, depth: f32, pane: MeshId) {
    match s.inset(margins, depth.min(deepest_recess(s.footprint(), depth))) {
        Some(inset) => {
            for part in inset.frame.iter().chain(&inset.reveals) {
                part.emit_rect(WALL);
            }
            inset.opening.emit_rect(pane);
        }
        None => {
            s.emit_rect(WALL);
        }
    }
}
