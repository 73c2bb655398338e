//! A building generator in the style of CGA shape grammars, whose derivation tree is the
//! building program: evolving its genomes is genetic programming over building programs.
//!
//! The axiom [`Lot`] stands a mass of its base height on a fixed [`LOT`] footprint and
//! hands that scope to a [`Program`]. A program runs each of its operations (extrude,
//! split, repeat, rotate, twist, scale, insert) on its own copy of the scope, and each
//! operation hands the scope or scopes it makes to the programs in its child slots.
//!
//! # Scopes
//!
//! Every scope is an oriented box standing on its bottom face: the lot's scope spans
//! `[-5, 5] x [0, base_height] x [-5, 5]`, and every operation keeps the bottom of what it
//! changes (an extrusion grows upward, a scale is about the bottom centre) or divides the
//! box into slabs that tile it exactly (split, repeat, twist).
//!
//! # Operations
//!
//! | node | parameters | children | geometry |
//! |---|---|---|---|
//! | [`Lot`] | `base_height` | `program` | the scope `LOT.x x base_height x LOT.y`, bottom at `y = 0`, centred on the origin |
//! | [`Program`] | none | one optional slot per operation | each present operation runs on the same scope (push / pop); with none, a box fills the scope |
//! | [`Extrude`] | `height` | `next` | the scope grows upward by `height`, keeping its bottom |
//! | [`Split`] | `axis`, `count`, `ratios` | `parts: [Program; 4]` | `count` (2 to 4) consecutive slabs along `axis`, part 0 of weight 1 and part `i` of weight `ratios[i - 1]`; part `i` runs `parts[i]` |
//! | [`Repeat`] | `axis`, `tile` | `tile_program` | equal tiles of about `tile` along `axis` (at most [`MAX_TILES`]), each running the same program |
//! | [`RotateY`] | `angle` | `next` | the scope turned by `angle` about its vertical centre line |
//! | [`Twist`] | `floor_height`, `angle` | `floor` | floors of about `floor_height` (at most [`MAX_TILES`]), floor `i` turned by `i * angle` about the vertical centre line, each running the same program |
//! | [`Scale`] | `factor` | `next` | the size multiplied by `factor` (each component in `[0, 2]`) about the bottom centre |
//! | [`Insert`] | `mesh` | none | the mesh ([`CUBE`] or [`SPHERE`]) scaled to fill the scope |
//!
//! Every path of a program ends in geometry: an operation whose child program is absent
//! fills each scope it makes with a box, and so does a program without operations. So
//! every genome is a building, however it was grown or cut.
//!
//! ```
//! use generators::building::{self, Building};
//! use rand::SeedableRng;
//! use shapegen_runtime::prelude::*;
//!
//! let mut ops = Operators::<Building>::new(building::LIMITS)?;
//! let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
//! let genome = ops.random(40, &mut rng);
//! let mut instances = Vec::new();
//! genome.derive_into(&mut instances);
//! assert!(!instances.is_empty());
//!
//! // The same program written by hand: a 4-high lot extruded by 6, split along x
//! // into two halves, the left half a box and the right half a sphere.
//! let mut g = Genome::<Building>::with_root(building::Lot { base_height: 4.0 })?;
//! let program = g.attach(0, "program", building::Program {})?;
//! let extrude = g.attach(program, "extrude", building::Extrude { height: 6.0 })?;
//! let next = g.attach(extrude, "next", building::Program {})?;
//! let split = building::Split { axis: 0, count: 2, ratios: Vec3::ONE };
//! let split = g.attach(next, "split", split)?;
//! let right = g.attach_at(split, "parts", 1, building::Program {})?;
//! g.attach(right, "insert", building::Insert { mesh: 1 })?;
//! g.derive_into(&mut instances);
//! assert_eq!(instances.len(), 2);
//! assert_eq!(instances[0].mesh, CUBE);
//! assert_eq!(instances[1].mesh, building::SPHERE);
//! // The right half: 5 wide, 10 high, 10 deep, centred at (2.5, 5, 0).
//! assert_eq!(instances[1].transform.translation, vec3(2.5, 5.0, 0.0).into());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::ops::RangeInclusive;

use shapegen_runtime::generator;
use shapegen_runtime::genome::Limits;
use shapegen_runtime::geometry::RoofShape;
use shapegen_runtime::optimize::multi::MultiGaSettings;
use shapegen_runtime::prelude::*;

use crate::presets::Presets;

/// The lot's footprint: width along x and depth along z, centred on the origin.
pub const LOT: Vec2 = Vec2::new(10.0, 10.0);

/// The range of the lot's base height ([`Lot::base_height`]).
pub const BASE_HEIGHT: RangeInclusive<f32> = 3.0..=12.0;

/// Most tiles a [`Repeat`] makes, and most floors a [`Twist`] makes: when the scope
/// holds more tiles of the gene's size, the tiles are made longer to fit this many.
pub const MAX_TILES: u32 = 24;

/// The building grammar, declared once for [`Building`] and [`RoofedBuilding`]: the
/// grammar named `$name` with, when `$roof: $Roof` and the roof pieces' meshes are given,
/// a roof operation in every program's slot `$roof`.
macro_rules! building_grammar {
    (
        $(#[$doc:meta])*
        $name:ident $(, $roof:ident: $Roof:ident, meshes { $($meshes:tt)* })?
    ) => {
        generator! {
            $(#[$doc])*
            pub $name {
                axiom Lot;
                meshes {
                    /// A low-poly sphere ([`low_poly_sphere`](crate::low_poly_sphere) in
                    /// [`default_meshes`](crate::default_meshes)), scaled to fill its scope.
                    SPHERE = "sphere",
                    $($($meshes)*)?
                }

                /// The axiom: the lot, a mass of the base height on the [`LOT`] footprint.
                node Lot {
                    params {
                        /// Height of the mass the program starts from ([`BASE_HEIGHT`]).
                        base_height: f32 ~ uniform(3.0, 12.0),
                    }
                    children {
                        /// The building program on the lot's mass.
                        program: Program = 1.0,
                    }
                    derive(s) {
                        let s = s
                            .with_size(vec3(LOT.x, base_height, LOT.y))
                            .translate(vec3(0.0, base_height / 2.0, 0.0));
                        run(s, program);
                    }
                }

                /// A building program on one scope: each present operation runs on its own copy
                /// of the scope, as CGA's push / pop (`[ op ] [ op ] ..`), so their geometry is
                /// the union of theirs. A program without operations fills the scope with a box.
                node Program {
                    children {
                        /// Grow the scope upward.
                        extrude: Extrude = 0.3,
                        /// Split the scope into parts.
                        split: Split = 0.2,
                        /// Tile the scope.
                        repeat: Repeat = 0.12,
                        /// Turn the scope about the vertical.
                        rotate: RotateY = 0.1,
                        /// Stack twisted floors in the scope.
                        twist: Twist = 0.08,
                        /// Scale the scope about its bottom centre.
                        scale: Scale = 0.15,
                        /// Fill the scope with a mesh.
                        insert: Insert = 0.15,
                        $(
                            /// Fill the scope with a box and put a roof on its top.
                            $roof: $Roof = 0.2,
                        )?
                    }
                    derive(s) {
                        if extrude.is_none()
                            && split.is_none()
                            && repeat.is_none()
                            && rotate.is_none()
                            && twist.is_none()
                            && scale.is_none()
                            && insert.is_none()
                            $(&& $roof.is_none())?
                        {
                            s.emit(CUBE);
                        }
                        if let Some(op) = extrude {
                            s.derive(op);
                        }
                        if let Some(op) = split {
                            s.derive(op);
                        }
                        if let Some(op) = repeat {
                            s.derive(op);
                        }
                        if let Some(op) = rotate {
                            s.derive(op);
                        }
                        if let Some(op) = twist {
                            s.derive(op);
                        }
                        if let Some(op) = scale {
                            s.derive(op);
                        }
                        if let Some(op) = insert {
                            s.derive(op);
                        }
                        $(
                            if let Some(op) = $roof {
                                s.derive(op);
                            }
                        )?
                    }
                }

                /// Grows the scope upward by `height`, keeping its bottom (CGA's `extrude`).
                node Extrude {
                    params {
                        /// How much taller the scope becomes.
                        height: f32 ~ uniform(1.0, 12.0),
                    }
                    children {
                        /// The program on the grown scope.
                        next: Program = 0.7,
                    }
                    derive(s) {
                        let size = s.size() + vec3(0.0, height, 0.0);
                        run(s.translate(vec3(0.0, height / 2.0, 0.0)).with_size(size), next);
                    }
                }

                /// Splits the scope along one of its axes into `count` consecutive parts, from
                /// the negative end: part 0 has weight 1 and part `i > 0` weight `ratios[i - 1]`,
                /// and each part's length is its share of the scope's by weight (CGA's
                /// `split(axis) { ~1 : A | ~r : B | .. }`). Slots past `count` are not derived.
                node Split {
                    params {
                        /// The axis: 0 for x, 1 for y (floors and setbacks), 2 for z.
                        axis: u32 ~ weighted([1.0, 1.0, 1.0]),
                        /// Number of parts.
                        count: u32 ~ uniform(2..=4),
                        /// Weights of parts 1 to 3, relative to part 0's.
                        ratios: Vec3 ~ uniform([0.25; 3], [2.0; 3]),
                    }
                    children {
                        /// The program of each part.
                        parts: [Program; 4] = 0.5,
                    }
                    derive(s) {
                        let weights = [1.0, ratios.x, ratios.y, ratios.z].map(Part::Float);
                        let count = count.clamp(2, 4) as usize;
                        for (i, part) in s.split(axis_of(axis), &weights[..count]).enumerate() {
                            run(part, parts.get(i));
                        }
                    }
                }

                /// Tiles the scope along one of its axes with equal tiles of about `tile`, and
                /// runs one program on every tile (CGA's `split(axis) { ~tile : A }*`).
                node Repeat {
                    params {
                        /// The axis: 0 for x, 1 for y (floors), 2 for z.
                        axis: u32 ~ weighted([1.0, 2.0, 1.0]),
                        /// Length of a tile, before rounding the count to fill the scope.
                        tile: f32 ~ uniform(2.0, 6.0),
                    }
                    children {
                        /// The program run on each tile.
                        tile_program: Program = 0.6,
                    }
                    derive(s) {
                        let axis = axis_of(axis);
                        for t in s.repeat(axis, capped_tile(s.size()[axis.index()], tile)) {
                            run(t, tile_program);
                        }
                    }
                }

                /// Turns the scope by `angle` about its vertical centre line (CGA's
                /// `rotate(y)`).
                node RotateY {
                    params {
                        /// The turn, counter-clockwise seen from above.
                        angle: f32 ~ degrees(-45.0, 45.0),
                    }
                    children {
                        /// The program on the turned scope.
                        next: Program = 0.7,
                    }
                    derive(s) {
                        run(s.rotate_y(angle), next);
                    }
                }

                /// The twisting stack: floors of about `floor_height` tiling the scope from the
                /// bottom, floor `i` turned by `i * angle` about the vertical centre line, each
                /// running one program.
                node Twist {
                    params {
                        /// Height of a floor, before rounding the count to fill the scope.
                        floor_height: f32 ~ uniform(2.0, 5.0),
                        /// Turn of each floor relative to the one below.
                        angle: f32 ~ degrees(-15.0, 15.0),
                    }
                    children {
                        /// The program run on each floor.
                        floor: Program = 0.5,
                    }
                    derive(s) {
                        let tile = capped_tile(s.size().y, floor_height);
                        for (i, f) in s.repeat(Axis::Y, tile).enumerate() {
                            run(f.rotate_y(i as f32 * angle), floor);
                        }
                    }
                }

                /// Scales the scope by `factor` about its bottom centre (CGA's `s(..)` with
                /// relative sizes).
                node Scale {
                    params {
                        /// Factor on the scope's width, height and depth.
                        factor: Vec3 ~ uniform([0.0; 3], [2.0; 3]),
                    }
                    children {
                        /// The program on the scaled scope.
                        next: Program = 0.7,
                    }
                    derive(s) {
                        let size = s.size() * factor;
                        let rise = (size.y - s.size().y) / 2.0;
                        run(s.translate(vec3(0.0, rise, 0.0)).with_size(size), next);
                    }
                }

                /// Fills the scope with a mesh (CGA's `i(..)`).
                node Insert {
                    params {
                        /// The mesh: 0 for [`CUBE`], 1 for [`SPHERE`].
                        mesh: u32 ~ weighted([3.0, 1.0]),
                    }
                    derive(s) {
                        s.emit(mesh_of(mesh));
                    }
                }
                $(
                    /// Fills the scope with a box and puts a roof on its top (CGA's `roofGable`,
                    /// `roofHip`, `roofPyramid`, `roofShed`; a flat roof is a slab), as
                    /// instances of the roof pieces ([`Scope::roof`]): the ridge along the longer
                    /// side, a shed rising toward the back.
                    node $Roof {
                        params {
                            /// The shape: 0 flat, 1 shed, 2 gable, 3 hip, 4 pyramid.
                            shape: u32 ~ weighted([1.0, 1.0, 2.0, 2.0, 1.0]),
                            /// The slope of the roof's faces.
                            pitch: f32 ~ degrees(15.0, 60.0),
                            /// How far the eave reaches past the walls.
                            overhang: f32 ~ uniform(0.0, 1.0),
                        }
                        derive(s) {
                            s.emit(CUBE);
                            // Out of range only in a hand-edited genome: then no roof.
                            let _ = s.roof(roof_shape(shape, pitch), overhang, &ROOF_PIECES);
                        }
                    }
                )?
            }
        }

        /// Runs `program` on `s`, or fills `s` with a box when there is none.
        fn run<'a>(s: Shape<'a, $name>, program: Option<Child<'a, Program>>) {
            match program {
                Some(program) => s.derive(program),
                None => s.emit(CUBE),
            }
        }
    };
}

building_grammar! {
    /// A building on one lot, grown by a building program of CGA-style operations.
    Building
}

/// The axis of an `axis` parameter: 0 is x, 1 is y, anything else z.
fn axis_of(axis: u32) -> Axis {
    match axis {
        0 => Axis::X,
        1 => Axis::Y,
        _ => Axis::Z,
    }
}

/// The mesh of an [`Insert::mesh`] parameter: 0 is the cube, anything else the sphere.
fn mesh_of(mesh: u32) -> MeshId {
    match mesh {
        0 => CUBE,
        _ => SPHERE,
    }
}

/// The tile length to repeat with along a side of `length`: `tile`, or longer where that
/// would make more than [`MAX_TILES`] tiles.
pub(crate) fn capped_tile(length: f32, tile: f32) -> f32 {
    tile.max(length / MAX_TILES as f32)
}

/// The roof of a `shape` parameter (a roof node's, here and in
/// [`lot_building`](crate::lot_building)): 0 flat (a slab of 0.3), 1 shed, 2 gable,
/// 3 hip, anything else a pyramid.
pub(crate) fn roof_shape(shape: u32, pitch: f32) -> RoofShape {
    match shape {
        0 => RoofShape::Flat { thickness: 0.3 },
        1 => RoofShape::Shed { pitch },
        2 => RoofShape::Gable { pitch },
        3 => RoofShape::Hip { pitch },
        _ => RoofShape::Pyramid { pitch },
    }
}

/// The genome limits of building programs: length 2 to 300, depth 20 (ten operations
/// deep, a program and an operation per level).
pub const LIMITS: Limits = Limits {
    min_len: 2,
    max_len: 300,
    max_depth: 20,
};

/// Each method's settings for the building generators, which have no paper scene: the
/// thesis's GA ([`MultiGaSettings::thesis`]) and the city's settings of the other methods
/// ([`city::paper_smc`](crate::city::paper_smc),
/// [`city::paper_rjmcmc`](crate::city::paper_rjmcmc)).
pub fn presets() -> Presets {
    Presets::paper(
        MultiGaSettings::thesis().ga,
        crate::city::paper_smc,
        crate::city::paper_rjmcmc(),
    )
}

/// The building generator with roofs: [`Building`]'s programs, each with one more
/// optional operation, [`Roof`](roofed::Roof), which fills its scope with a box and puts
/// a flat, shed, gable, hip or pyramid roof of an evolved pitch and overhang on its top.
/// [`Building`] is unchanged by it: its genomes, samples and scenes are as before.
///
/// ```
/// use generators::building::{self, roofed::{self, RoofedBuilding}};
/// use rand::SeedableRng;
/// use shapegen_runtime::geometry::RoofPiece;
/// use shapegen_runtime::prelude::*;
///
/// // A 6-high lot with a gable roof at 40 degrees.
/// let mut g = Genome::<RoofedBuilding>::with_root(roofed::Lot { base_height: 6.0 })?;
/// let program = g.attach(0, "program", roofed::Program {})?;
/// let roof = roofed::Roof { shape: 2, pitch: 40f32.to_radians(), overhang: 0.5 };
/// g.attach(program, "roof", roof)?;
/// let mut instances = Vec::new();
/// g.derive_into(&mut instances);
/// assert_eq!(instances.len(), 2);
/// assert_eq!((instances[0].mesh, instances[1].mesh), (CUBE, roofed::ROOF_GABLE));
///
/// // Random roofed buildings, with their meshes bound from the published library.
/// let meshes = generators::default_meshes().bind(RoofedBuilding::GRAPH)?;
/// assert_eq!(meshes.name(roofed::ROOF_HIP_END), Some(RoofPiece::HipEnd.name()));
/// let mut ops = Operators::<RoofedBuilding>::new(building::LIMITS)?;
/// let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
/// ops.random(40, &mut rng).derive_into(&mut instances);
/// assert!(!instances.is_empty());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub mod roofed {
    use shapegen_runtime::geometry::RoofMeshes;

    use super::*;

    building_grammar! {
        /// A building on one lot, grown by a building program of CGA-style operations
        /// that include roofs.
        RoofedBuilding,
        roof: Roof,
        meshes {
            /// [`RoofPiece::Gable`](shapegen_runtime::geometry::RoofPiece::Gable).
            ROOF_GABLE = "roof_gable",
            /// [`RoofPiece::Shed`](shapegen_runtime::geometry::RoofPiece::Shed).
            ROOF_SHED = "roof_shed",
            /// [`RoofPiece::Pyramid`](shapegen_runtime::geometry::RoofPiece::Pyramid).
            ROOF_PYRAMID = "roof_pyramid",
            /// [`RoofPiece::HipEnd`](shapegen_runtime::geometry::RoofPiece::HipEnd).
            ROOF_HIP_END = "roof_hip_end",
        }
    }

    /// The roof pieces' meshes in this grammar.
    pub const ROOF_PIECES: RoofMeshes = RoofMeshes {
        gable: ROOF_GABLE,
        shed: ROOF_SHED,
        pyramid: ROOF_PYRAMID,
        hip_end: ROOF_HIP_END,
    };
}
