//! Known derivations of the published generators: small genomes built by hand, whose
//! instances are checked against transforms worked out by hand from the geometry the
//! original implementation's grammars give them (`docs/fidelity.md`).
//!
//! An instance `scope_frame * scale(scope_size) * mesh` has as matrix columns the scope's
//! world axes times its size along them, and as translation the scope's centre. The
//! expected values below are those columns and centres, written out as numbers (with the
//! working in the comments) or, for the small twist of the tree's branches, built from
//! `cos` and `sin` of the angle; none of them goes through the runtime's scope code.

use std::f32::consts::{FRAC_PI_2, FRAC_PI_3, FRAC_PI_4, FRAC_PI_6, PI};

use generators::{city, spaceship, tree};
use shapegen_runtime::graph::{AngleUnit, Distribution, GeneratorGraph};
use shapegen_runtime::prelude::*;
use shapegen_runtime::{Grammar, MeshId};

const EPS: f32 = 1e-5;
/// `sqrt(3) / 2`: cos 30, sin 60 degrees.
const S3_2: f32 = 0.866_025_4;

/// An instance as worked out by hand: mesh, the three matrix columns, the translation.
#[derive(Clone, Copy, Debug)]
struct Expected {
    mesh: MeshId,
    x: Vec3,
    y: Vec3,
    z: Vec3,
    centre: Vec3,
}

/// A box of size `size` whose local axes are `axes`, centred at `centre`.
fn boxed(mesh: MeshId, axes: [Vec3; 3], size: Vec3, centre: Vec3) -> Expected {
    Expected {
        mesh,
        x: axes[0] * size.x,
        y: axes[1] * size.y,
        z: axes[2] * size.z,
        centre,
    }
}

/// The world axes.
const WORLD: [Vec3; 3] = [Vec3::X, Vec3::Y, Vec3::Z];

fn matches(actual: &Instance, e: &Expected) -> bool {
    let m = actual.transform.matrix3;
    actual.mesh == e.mesh
        && Vec3::from(m.x_axis).abs_diff_eq(e.x, EPS)
        && Vec3::from(m.y_axis).abs_diff_eq(e.y, EPS)
        && Vec3::from(m.z_axis).abs_diff_eq(e.z, EPS)
        && Vec3::from(actual.transform.translation).abs_diff_eq(e.centre, EPS)
}

fn describe(i: &Instance) -> String {
    let m = i.transform.matrix3;
    format!(
        "mesh {} x {:?} y {:?} z {:?} at {:?}",
        i.mesh.0,
        Vec3::from(m.x_axis),
        Vec3::from(m.y_axis),
        Vec3::from(m.z_axis),
        Vec3::from(i.transform.translation)
    )
}

/// Checks that `actual` holds exactly the `expected` instances, in any order (the paper
/// fixes the geometry, not the order rules emit in).
fn assert_instances(actual: &[Instance], expected: &[Expected]) {
    let listing = || actual.iter().map(describe).collect::<Vec<_>>().join("\n  ");
    assert_eq!(
        actual.len(),
        expected.len(),
        "instance count; got:\n  {}",
        listing()
    );
    let mut used = vec![false; actual.len()];
    for e in expected {
        let found = (0..actual.len()).find(|&i| !used[i] && matches(&actual[i], e));
        match found {
            Some(i) => used[i] = true,
            None => panic!("no instance matches {e:?}; got:\n  {}", listing()),
        }
    }
}

fn derive<G: Grammar>(g: &Genome<G>) -> Vec<Instance> {
    g.validate().expect("hand-built genomes are valid");
    let mut out = Vec::new();
    g.derive_into(&mut out);
    out
}

// --- spaceship --------------------------------------------------------------------------

#[test]
fn spaceship_hull_wings_and_tower() {
    use spaceship::{Body, Start, Top, TopNext, Wing, WingNext};
    let mut g = Genome::<spaceship::Spaceship>::with_root(Start {}).unwrap();
    let b0 = g
        .attach(
            0,
            "body",
            Body {
                size: vec3(1.0, 0.8, 1.2),
            },
        )
        .unwrap();
    g.attach(
        b0,
        "next",
        Body {
            size: vec3(0.8, 1.0, 1.5),
        },
    )
    .unwrap();
    let wing = g
        .attach(
            b0,
            "wing",
            Wing {
                size: vec3(0.5, 0.4, 0.5),
                shift: 0.2,
            },
        )
        .unwrap();
    let wn1 = g
        .attach(
            wing,
            "next",
            WingNext {
                size: vec3(1.1, 1.0, 0.9),
                shift: 0.4,
            },
        )
        .unwrap();
    g.attach(
        wn1,
        "next",
        WingNext {
            size: vec3(0.8, 0.9, 1.2),
            shift: -0.25,
        },
    )
    .unwrap();
    let top = g
        .attach(
            b0,
            "top",
            Top {
                size: vec3(0.5, 0.2, 0.5),
            },
        )
        .unwrap();
    let tn1 = g
        .attach(
            top,
            "next",
            TopNext {
                size: vec3(0.7, 0.9, 0.7),
            },
        )
        .unwrap();
    g.attach(
        tn1,
        "next",
        TopNext {
            size: vec3(0.6, 1.0, 0.8),
        },
    )
    .unwrap();
    assert_eq!(g.len(), 9);

    // Start: resize(b0.size): size (1, 0.8, 1.2) at the origin.
    // Body b0: translate(0, 0, 1.2 / 2) -> centre (0, 0, 0.6); emit.
    let hull0 = boxed(CUBE, WORLD, vec3(1.0, 0.8, 1.2), vec3(0.0, 0.0, 0.6));
    // Next body: translate(0, 0, 0.6) -> (0, 0, 1.2); resize((0.8, 1, 1.5)) -> size
    // (0.8, 0.8, 1.8); its rule: translate(0, 0, 0.9) -> (0, 0, 2.1); emit.
    let hull1 = boxed(CUBE, WORLD, vec3(0.8, 0.8, 1.8), vec3(0.0, 0.0, 2.1));
    // Right wing, from b0's scope: translate(1 / 2, 0, 0) -> (0.5, 0, 0.6).
    // Wing: resize((0.5, 0.4, 0.5)) -> size (0.5, 0.32, 0.6); translate(0, 0, 0.6 * 0.2)
    // -> (0.5, 0, 0.72); translate(0.25, 0, 0) -> (0.75, 0, 0.72); emit.
    let right1 = boxed(CUBE, WORLD, vec3(0.5, 0.32, 0.6), vec3(0.75, 0.0, 0.72));
    // WingNext 1: translate(0.25, 0, 0) -> (1, 0, 0.72); resize((1.1, 1, 0.9)) -> size
    // (0.55, 0.32, 0.54); translate(0, 0, 0.54 * 0.4) -> (1, 0, 0.936);
    // translate(0.275, 0, 0) -> (1.275, 0, 0.936); emit.
    let right2 = boxed(CUBE, WORLD, vec3(0.55, 0.32, 0.54), vec3(1.275, 0.0, 0.936));
    // WingNext 2: translate(0.275, 0, 0) -> (1.55, 0, 0.936); resize((0.8, 0.9, 1.2)) ->
    // size (0.44, 0.288, 0.648); translate(0, 0, 0.648 * -0.25) -> (1.55, 0, 0.774);
    // translate(0.22, 0, 0) -> (1.77, 0, 0.774); emit.
    let right3 = boxed(
        CUBE,
        WORLD,
        vec3(0.44, 0.288, 0.648),
        vec3(1.77, 0.0, 0.774),
    );
    // Left wing: rotate(z, pi) turns the local x and y axes to -x and -y, so every local
    // x step above goes the other way and the boxes' x and y columns flip sign.
    let turned = [-Vec3::X, -Vec3::Y, Vec3::Z];
    let left1 = boxed(CUBE, turned, vec3(0.5, 0.32, 0.6), vec3(-0.75, 0.0, 0.72));
    let left2 = boxed(
        CUBE,
        turned,
        vec3(0.55, 0.32, 0.54),
        vec3(-1.275, 0.0, 0.936),
    );
    let left3 = boxed(
        CUBE,
        turned,
        vec3(0.44, 0.288, 0.648),
        vec3(-1.77, 0.0, 0.774),
    );
    // Top, from b0's scope: translate(0, 0.8 / 2, 0) -> (0, 0.4, 0.6). Top:
    // resize((0.5, 0.2, 0.5)) -> size (0.5, 0.16, 0.6); translate(0, 0.08, 0) ->
    // (0, 0.48, 0.6); emit.
    let tower1 = boxed(CUBE, WORLD, vec3(0.5, 0.16, 0.6), vec3(0.0, 0.48, 0.6));
    // TopNext 1: translate(0, 0.08, 0) -> (0, 0.56, 0.6); resize((0.7, 0.9, 0.7)) ->
    // size (0.35, 0.144, 0.42); translate(0, 0.072, 0) -> (0, 0.632, 0.6); emit.
    let tower2 = boxed(CUBE, WORLD, vec3(0.35, 0.144, 0.42), vec3(0.0, 0.632, 0.6));
    // TopNext 2: translate(0, 0.072, 0) -> (0, 0.704, 0.6); resize((0.6, 1, 0.8)) ->
    // size (0.21, 0.144, 0.336); translate(0, 0.072, 0) -> (0, 0.776, 0.6); emit.
    let tower3 = boxed(CUBE, WORLD, vec3(0.21, 0.144, 0.336), vec3(0.0, 0.776, 0.6));

    let out = derive(&g);
    // Every gene emits a box (wing genes a mirrored pair), in its own parameters.
    assert_instances(
        &out,
        &[
            hull0, hull1, right1, right2, right3, left1, left2, left3, tower1, tower2, tower3,
        ],
    );
    // The rules emit depth first: next, top, wing (right, then left).
    assert!(matches(&out[0], &hull0) && matches(&out[1], &hull1));
    assert!(
        [
            tower1, tower2, tower3, right1, right2, right3, left1, left2, left3
        ]
        .iter()
        .zip(&out[2..])
        .all(|(e, i)| matches(i, e))
    );
}

#[test]
fn spaceship_axiom_and_single_body() {
    use spaceship::{Body, Start};
    // The axiom alone emits nothing: Start has no geometry of its own.
    let g = Genome::<spaceship::Spaceship>::with_root(Start {}).unwrap();
    assert!(derive(&g).is_empty());
    // One body of the largest size: a 1.5 cube whose back face lies on z = 0.
    let mut g = g;
    g.attach(
        0,
        "body",
        Body {
            size: Vec3::ONE * 1.5,
        },
    )
    .unwrap();
    assert_instances(
        &derive(&g),
        &[boxed(CUBE, WORLD, Vec3::splat(1.5), vec3(0.0, 0.0, 0.75))],
    );
}

// --- tree -------------------------------------------------------------------------------

#[test]
fn tree_trunk_branch_and_leaf() {
    use tree::{B1, B2, Start, Trunk};
    let twist = (-2.0f32).to_radians();
    let mut g = Genome::<tree::Tree>::with_root(Start {}).unwrap();
    let trunk = g
        .attach(
            0,
            "trunk",
            Trunk {
                size: vec3(0.8, 1.5, 0.8),
            },
        )
        .unwrap();
    let b1 = g
        .attach(
            trunk,
            "b1",
            B1 {
                size: vec3(0.6, 0.8, 0.7),
                yaw: FRAC_PI_2,
                tilt: FRAC_PI_3,
                twist: 0.0,
            },
        )
        .unwrap();
    g.attach(
        b1,
        "b2",
        B2 {
            size: vec3(0.7, 0.75, 0.6),
            yaw: PI,
            tilt: FRAC_PI_4,
            twist,
        },
    )
    .unwrap();

    // Trunk: resize((0.8, 1.5, 0.8)) of the unit box at the origin; emit.
    let trunk_box = boxed(tree::TRUNK, WORLD, vec3(0.8, 1.5, 0.8), Vec3::ZERO);

    // B1 in the trunk's scope. rotate(y, 90): local x -> (0, 0, -1), z -> (1, 0, 0).
    // translate(0, 0.38 * 1.5, 0) -> centre (0, 0.57, 0).
    // rotate(z, 60): x -> cos 60 x + sin 60 y = (0, 0.866, -0.5),
    //                y -> -sin 60 x + cos 60 y = (0, 0.5, 0.866), z stays (1, 0, 0).
    // resize((0.6, 0.8, 0.7)) -> size (0.48, 1.2, 0.56).
    // translate(0, 1.2 / 2, 0) -> (0, 0.57 + 0.3, 0.6 * 0.866) = (0, 0.87, 0.519615).
    // rotate(y, 0): no change; emit. B1 has a child, so no leaf.
    let b1_axes = [
        vec3(0.0, S3_2, -0.5),
        vec3(0.0, 0.5, S3_2),
        vec3(1.0, 0.0, 0.0),
    ];
    let b1_size = vec3(0.48, 1.2, 0.56);
    let b1_centre = vec3(0.0, 0.87, 0.6 * S3_2);
    let b1_box = boxed(tree::TRUNK, b1_axes, b1_size, b1_centre);

    // B2 in B1's scope. rotate(y, 180): x -> -x1 = (0, -0.866, 0.5), y stays
    // (0, 0.5, 0.866), z -> -z1 = (-1, 0, 0).
    // translate(0, 0.38 * 1.2, 0) = 0.456 along y: centre (0, 0.87 + 0.228,
    // 0.519615 + 0.394908) = (0, 1.098, 0.914523).
    // rotate(z, 45): x -> (x + y) / sqrt 2 = (0, -0.258819, 0.965926) (cos 105, sin 105),
    //                y -> (y - x) / sqrt 2 = (0, 0.965926, 0.258819) (cos 15, sin 15).
    // resize((0.7, 0.75, 0.6)) -> size (0.336, 0.9, 0.336).
    // translate(0, 0.9 / 2, 0) -> centre (0, 1.098 + 0.45 * 0.965926,
    // 0.914523 + 0.45 * 0.258819) = (0, 1.532667, 1.030992).
    let c15 = 0.965_925_8;
    let s15 = 0.258_819_04;
    let x2 = vec3(0.0, -s15, c15);
    let y2 = vec3(0.0, c15, s15);
    let z2 = vec3(-1.0, 0.0, 0.0);
    let b2_centre = vec3(
        0.0,
        1.098 + 0.45 * c15,
        0.6 * S3_2 + 0.456 * S3_2 + 0.45 * s15,
    );
    assert!(b2_centre.abs_diff_eq(vec3(0.0, 1.532_667, 1.030_992), 1e-6));
    // rotate(y, twist) about the branch's own axis: x3 = cos t x2 - sin t z2,
    // z3 = sin t x2 + cos t z2; y and the centre stay.
    let (st, ct) = twist.sin_cos();
    let x3 = x2 * ct - z2 * st;
    let z3 = x2 * st + z2 * ct;
    let b2_box = boxed(
        tree::TRUNK,
        [x3, y2, z3],
        vec3(0.336, 0.9, 0.336),
        b2_centre,
    );
    // B2 has no children: the leaf, translate(0, 0.75 * 0.9, 0) along y2, emitted
    // unscaled: its columns are the unit axes of B2's frame.
    let leaf_centre = b2_centre + y2 * (0.75 * 0.9);
    assert!(leaf_centre.abs_diff_eq(vec3(0.0, 2.184_667, 1.205_694), 1e-6));
    let leaf = boxed(tree::LEAF, [x3, y2, z3], Vec3::ONE, leaf_centre);

    let out = derive(&g);
    assert_instances(&out, &[trunk_box, b1_box, b2_box, leaf]);
    let leaves: Vec<&Instance> = out.iter().filter(|i| i.mesh == tree::LEAF).collect();
    assert_eq!(leaves.len(), 1, "only the childless branch ends in a leaf");
    // Unscaled: a rotation, orthonormal with determinant 1.
    let m = leaves[0].transform.matrix3;
    for axis in [m.x_axis, m.y_axis, m.z_axis] {
        assert!((axis.length() - 1.0).abs() < EPS);
    }
    assert!((m.determinant() - 1.0).abs() < EPS);
}

#[test]
fn tree_trunk_alone_and_a_leaf_on_each_childless_branch() {
    use tree::{B1, B3, Start, Trunk};
    // A bare trunk is not a branch: no leaf.
    let mut g = Genome::<tree::Tree>::with_root(Start {}).unwrap();
    let trunk = g
        .attach(
            0,
            "trunk",
            Trunk {
                size: vec3(0.8, 1.8, 0.8),
            },
        )
        .unwrap();
    assert_instances(
        &derive(&g),
        &[boxed(tree::TRUNK, WORLD, vec3(0.8, 1.8, 0.8), Vec3::ZERO)],
    );
    // Two childless branches from the trunk, both with yaw, tilt and twist 0 where
    // allowed: each ends in its own leaf.
    let branch = B1 {
        size: vec3(0.6, 0.6, 0.6),
        yaw: 0.0,
        tilt: 40f32.to_radians(),
        twist: 0.0,
    };
    g.attach(trunk, "b1", branch).unwrap();
    g.attach(
        trunk,
        "b3",
        B3 {
            size: vec3(0.7, 0.8, 0.7),
            yaw: 1.5 * PI, // 270 degrees
            tilt: FRAC_PI_3,
            twist: 0.0,
        },
    )
    .unwrap();
    // B1: translate(0, 0.38 * 1.8 = 0.684, 0); rotate(z, 40): y -> (-sin 40, cos 40, 0),
    // x -> (cos 40, sin 40, 0); size (0.48, 1.08, 0.48); centre 0.684 y + 0.54 y_axis.
    let (s40, c40) = 40f32.to_radians().sin_cos();
    let (bx, by) = (vec3(c40, s40, 0.0), vec3(-s40, c40, 0.0));
    let b1_centre = vec3(0.0, 0.684, 0.0) + by * 0.54;
    // B3: rotate(y, 270): x -> (0, 0, 1), z -> (-1, 0, 0); rotate(z, 60): x ->
    // (0, 0.866, 0.5), y -> (0, 0.5, -0.866); size (0.56, 1.44, 0.56); centre
    // (0, 0.684, 0) + 0.72 y.
    let (cx, cy, cz) = (
        vec3(0.0, S3_2, 0.5),
        vec3(0.0, 0.5, -S3_2),
        vec3(-1.0, 0.0, 0.0),
    );
    let b3_centre = vec3(0.0, 0.684 + 0.36, -0.72 * S3_2);
    assert_instances(
        &derive(&g),
        &[
            boxed(tree::TRUNK, WORLD, vec3(0.8, 1.8, 0.8), Vec3::ZERO),
            boxed(
                tree::TRUNK,
                [bx, by, Vec3::Z],
                vec3(0.48, 1.08, 0.48),
                b1_centre,
            ),
            // Leaf 0.75 * 1.08 = 0.81 further along the branch.
            boxed(
                tree::LEAF,
                [bx, by, Vec3::Z],
                Vec3::ONE,
                b1_centre + by * 0.81,
            ),
            boxed(tree::TRUNK, [cx, cy, cz], vec3(0.56, 1.44, 0.56), b3_centre),
            // 0.75 * 1.44 = 1.08.
            boxed(tree::LEAF, [cx, cy, cz], Vec3::ONE, b3_centre + cy * 1.08),
        ],
    );
}

// --- city -------------------------------------------------------------------------------

fn building(footprint: Vec2, height: f32, rotation: f32) -> city::Building {
    city::Building {
        footprint,
        height,
        floor_height: 0.3,
        rotation,
    }
}

#[test]
fn city_lots_in_their_grid_places() {
    let mut g = Genome::<city::City>::with_root(city::Start {}).unwrap();
    let lots = [
        (0, building(vec2(1.0, 1.5), 4.0, FRAC_PI_6)),
        (37, building(vec2(0.5, 1.98), 10.0, 0.0)),
        (99, building(vec2(1.2, 0.8), 0.36, FRAC_PI_2)),
    ];
    for (k, b) in lots {
        let lot = g.attach_at(0, "lots", k, city::Lot {}).unwrap();
        g.attach(lot, "building", b).unwrap();
    }
    assert_eq!(g.len(), 7);

    // Lot k (the original's symbol id k + 4) lies in grid cell (cx, cz) =
    // ((k + 4) % 10, (k + 4) / 10), at x = -9.9 + 2.2 cx, z = -9.9 + 2.2 cz, y = 0.
    // Lot 0 (cell (4, 0)): (-1.1, 0, -9.9). rotate(y, 30): x -> (cos 30, 0, -sin 30),
    // z -> (sin 30, 0, cos 30); size (1, 4, 1.5); up 4 / 2.
    let lot0 = boxed(
        CUBE,
        [vec3(S3_2, 0.0, -0.5), Vec3::Y, vec3(0.5, 0.0, S3_2)],
        vec3(1.0, 4.0, 1.5),
        vec3(-1.1, 2.0, -9.9),
    );
    // Lot 37 (cell (1, 4)): (-9.9 + 2.2, 0, -9.9 + 8.8) = (-7.7, 0, -1.1); no rotation;
    // size (0.5, 10, 1.98); up 5.
    let lot37 = boxed(CUBE, WORLD, vec3(0.5, 10.0, 1.98), vec3(-7.7, 5.0, -1.1));
    // Lot 99 (cell (3, 10), on the eleventh row): (-3.3, 0, 12.1). rotate(y, 90):
    // x -> (0, 0, -1), z -> (1, 0, 0); size (1.2, 0.36, 0.8); up 0.18.
    let lot99 = boxed(
        CUBE,
        [vec3(0.0, 0.0, -1.0), Vec3::Y, Vec3::X],
        vec3(1.2, 0.36, 0.8),
        vec3(-3.3, 0.18, 12.1),
    );
    let out = derive(&g);
    assert_instances(&out, &[lot0, lot37, lot99]);
    // Lots derive in slot order.
    assert!(matches(&out[0], &lot0) && matches(&out[1], &lot37) && matches(&out[2], &lot99));
}

#[test]
fn city_every_lot_position() {
    // One unrotated unit-footprint building on every lot: the centres sweep the grid.
    let mut g = Genome::<city::City>::with_root(city::Start {}).unwrap();
    for k in 0..100 {
        let lot = g.attach_at(0, "lots", k, city::Lot {}).unwrap();
        g.attach(lot, "building", building(vec2(1.0, 1.0), 2.0, 0.0))
            .unwrap();
    }
    assert_eq!(g.len(), 201); // the README's maximum genome
    let expected: Vec<Expected> = (0..100)
        .map(|k| {
            let (cx, cz) = (((k + 4) % 10) as f32, ((k + 4) / 10) as f32);
            let centre = vec3(-9.9 + 2.2 * cx, 1.0, -9.9 + 2.2 * cz);
            boxed(CUBE, WORLD, vec3(1.0, 2.0, 1.0), centre)
        })
        .collect();
    let out = derive(&g);
    assert_instances(&out, &expected);
    // The grid is shifted by four cells against a centred one: every x cell holds ten
    // lots, but the z cells hold 6, 10 x 9 and 4 (the eleventh row), so the mean cell is
    // (4.5, 4.9): x = 0, z = -9.9 + 2.2 * 4.9 = 0.88.
    let mean = out
        .iter()
        .map(|i| Vec3::from(i.transform.translation))
        .sum::<Vec3>()
        / 100.0;
    assert!(mean.abs_diff_eq(vec3(0.0, 1.0, 0.88), EPS));
}

// --- the published tables ---------------------------------------------------------------

/// A parameter as the README's tables give it: name and the bounds of each component
/// (angles in degrees).
#[derive(Clone, Copy)]
enum Param {
    Scalar(&'static str, f32, f32),
    Degrees(&'static str, f32, f32),
    Radians(&'static str, f32, f32),
    Vec2(&'static str, [f32; 2], [f32; 2]),
    Vec3(&'static str, [f32; 3], [f32; 3]),
}

/// Checks node `node` of `graph` against the README: its slots as
/// (name, child node, probability, count) and its parameters.
fn assert_node(
    graph: &GeneratorGraph,
    node: &str,
    slots: &[(&str, &str, f64, u32)],
    params: &[Param],
) {
    let kind = graph
        .kind_of(node)
        .unwrap_or_else(|| panic!("no node {node}"));
    let desc = graph.node(kind).unwrap();
    let found: Vec<(&str, &str, f32, u32)> = desc
        .slots
        .iter()
        .map(|s| {
            (
                s.name,
                graph.nodes[s.child as usize].name,
                s.probability,
                s.count,
            )
        })
        .collect();
    let want: Vec<(&str, &str, f32, u32)> = slots
        .iter()
        .map(|&(n, c, p, k)| (n, c, p as f32, k))
        .collect();
    assert_eq!(found, want, "slots of {node}");
    assert_eq!(desc.params.len(), params.len(), "parameters of {node}");
    let close = |a: f32, b: f32| (a - b).abs() <= 1e-6 * b.abs().max(1.0);
    for (p, want) in desc.params.iter().zip(params) {
        let ok = match (*want, p.dist) {
            (Param::Scalar(n, lo, hi), Distribution::Uniform { lo: l, hi: h }) => {
                n == p.name && l == lo && h == hi
            }
            (Param::Degrees(n, lo, hi), Distribution::Angle { lo: l, hi: h, unit }) => {
                n == p.name
                    && unit == AngleUnit::Degrees
                    && close(l, lo.to_radians())
                    && close(h, hi.to_radians())
            }
            (Param::Radians(n, lo, hi), Distribution::Angle { lo: l, hi: h, unit }) => {
                n == p.name && unit == AngleUnit::Radians && close(l, lo) && close(h, hi)
            }
            (Param::Vec2(n, lo, hi), Distribution::UniformVec2 { lo: l, hi: h }) => {
                n == p.name && l == lo && h == hi
            }
            (Param::Vec3(n, lo, hi), Distribution::UniformVec3 { lo: l, hi: h }) => {
                n == p.name && l == lo && h == hi
            }
            _ => false,
        };
        assert!(ok, "parameter {} of {node}: {:?}", p.name, p.dist);
    }
}

#[test]
fn spaceship_graph_matches_the_published_table() {
    let g = <spaceship::Spaceship as Grammar>::GRAPH;
    assert_eq!(g.nodes[g.axiom as usize].name, "Start");
    assert_eq!(g.meshes, ["cube"]);
    let third = 1.0 / 3.0;
    assert_node(g, "Start", &[("body", "Body", 1.0, 1)], &[]);
    assert_node(
        g,
        "Body",
        &[
            ("next", "Body", third, 1),
            ("wing", "Wing", third, 1),
            ("top", "Top", third, 1),
        ],
        &[Param::Vec3("size", [0.6; 3], [1.5; 3])],
    );
    assert_node(
        g,
        "Top",
        &[("next", "TopNext", 1.0, 1)],
        &[Param::Vec3("size", [0.3, 0.1, 0.3], [0.8, 0.2, 0.8])],
    );
    assert_node(
        g,
        "TopNext",
        &[("next", "TopNext", 1.0, 1)],
        &[Param::Vec3("size", [0.6, 0.8, 0.6], [1.1, 1.1, 1.1])],
    );
    assert_node(
        g,
        "Wing",
        &[("next", "WingNext", 1.0, 1)],
        &[
            Param::Vec3("size", [0.3, 0.2, 0.2], [1.2, 0.5, 1.0]),
            Param::Scalar("shift", -0.5, 0.5),
        ],
    );
    assert_node(
        g,
        "WingNext",
        &[("next", "WingNext", 0.9, 1)],
        &[
            Param::Vec3("size", [0.6, 0.9, 0.7], [1.2, 1.0, 1.2]),
            Param::Scalar("shift", -0.5, 0.5),
        ],
    );
    assert_eq!(g.nodes.len(), 6);
    let l = spaceship::PAPER_LIMITS;
    assert_eq!((l.min_len, l.max_len, l.max_depth), (4, 100, 15));
}

#[test]
fn tree_graph_matches_the_published_table() {
    let g = <tree::Tree as Grammar>::GRAPH;
    assert_eq!(g.nodes[g.axiom as usize].name, "Start");
    assert_eq!(g.meshes, ["cube", "trunk", "leaf"]);
    assert_eq!((tree::TRUNK, tree::LEAF), (MeshId(1), MeshId(2)));
    let third = 1.0 / 3.0;
    let branches = [
        ("b1", "B1", third, 1),
        ("b2", "B2", third, 1),
        ("b3", "B3", third, 1),
    ];
    assert_node(g, "Start", &[("trunk", "Trunk", 1.0, 1)], &[]);
    assert_node(
        g,
        "Trunk",
        &branches,
        &[Param::Vec3("size", [0.8, 1.4, 0.8], [0.8, 1.8, 0.8])],
    );
    for (node, yaw_lo, yaw_hi) in [
        ("B1", 0.0, 120.0),
        ("B2", 120.0, 240.0),
        ("B3", 240.0, 360.0),
    ] {
        assert_node(
            g,
            node,
            &branches,
            &[
                Param::Vec3("size", [0.6, 0.6, 0.6], [0.7, 0.801, 0.7]),
                Param::Degrees("yaw", yaw_lo, yaw_hi),
                Param::Degrees("tilt", 35.0, 85.0),
                Param::Degrees("twist", -3.0, 3.0),
            ],
        );
    }
    assert_eq!(g.nodes.len(), 5);
    let l = tree::PAPER_LIMITS;
    assert_eq!((l.min_len, l.max_len, l.max_depth), (4, 400, 12));
}

#[test]
fn city_graph_matches_the_published_table() {
    let g = <city::City as Grammar>::GRAPH;
    assert_eq!(g.nodes[g.axiom as usize].name, "Start");
    assert_eq!(g.meshes, ["cube"]);
    assert_node(g, "Start", &[("lots", "Lot", 0.33, 100)], &[]);
    assert_node(g, "Lot", &[("building", "Building", 1.0, 1)], &[]);
    assert_node(
        g,
        "Building",
        &[],
        &[
            Param::Vec2("footprint", [0.44; 2], [1.98; 2]),
            Param::Scalar("height", 0.36, 10.0),
            Param::Scalar("floor_height", 0.24, 0.36),
            Param::Radians("rotation", 0.0, PI),
        ],
    );
    assert_eq!(g.nodes.len(), 3);
    assert_eq!((city::GRID, city::LOT_SPACING), (10, 2.2));
    let l = city::PAPER_LIMITS;
    assert_eq!((l.min_len, l.max_len, l.max_depth), (4, 300, 8));
}
