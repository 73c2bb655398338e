//! Lots: a scene's `[lot]` table, as points or as a GeoJSON file, is the footprint its
//! building generator builds on, in every evaluator; mistakes are refused with the file,
//! the key and the reason.

use std::fs;
use std::path::Path;

use generators::LotBuilding;
use shapegen::optimize::multi::MultiEvaluator;
use shapegen::scene::{ObjectiveEvaluator, Scene, SceneError};
use shapegen::{Genome, Grammar, Instance};

use super::Fixture;

/// A scene of the lot building measuring the models' height, with `lot` as its `[lot]`
/// table.
fn scene_text(lot: &str) -> String {
    format!(
        r#"
generator = "lot_building"
{lot}
[limits]
min_len = 2
max_len = 100
max_depth = 12
[[objective]]
name = "extent"
kind = "footprint_excess"
min = [0, 0]
max = [0, 0]
"#
    )
}

const L_POINTS: &str = "[lot]\npoints = [[-8, -6], [8, -6], [8, 0], [0, 0], [0, 6], [-8, 6]]";

const L_GEOJSON: &str = r#"{"type": "Feature", "properties": {"name": "L"},
  "geometry": {"type": "Polygon",
    "coordinates": [[[-8, -6], [8, -6], [8, 0], [0, 0], [0, 6], [-8, 6], [-8, -6]]]}}"#;

/// The scene of [`scene_text`] with `lot`, in `fixture`'s folder.
fn load(fixture: &Fixture, lot: &str) -> Result<Scene, SceneError> {
    fixture.load(&scene_text(lot))
}

/// Loads the scene with `lot`, expecting an error about `key` that says `reason`.
fn refuses(fixture: &Fixture, lot: &str, key: &str, reason: &str) {
    fixture.refuses(&scene_text(lot), key, reason);
}

/// Writes `text` to the file `name` in `fixture`'s folder.
fn write(fixture: &Fixture, name: &str, text: &str) {
    fs::write(fixture.dir.path().join(name), text).unwrap();
}

/// A one-storey building of `height` with plain walls and a flat roof.
fn block(height: f32) -> Genome<LotBuilding> {
    use generators::lot_building::{Lot, Mass};
    let lot = Lot {
        front: 0.0,
        sides: 0.0,
    };
    let mut g = Genome::<LotBuilding>::with_root(lot).unwrap();
    g.attach(0, "mass", Mass { height }).unwrap();
    g
}

/// The x/z extent of `instances`' facets.
fn extent(instances: &[Instance]) -> (f32, f32, f32, f32) {
    instances.iter().fold(
        (f32::MAX, f32::MIN, f32::MAX, f32::MIN),
        |(x0, x1, z0, z1), i| {
            let t = i.transform;
            let corners =
                [glam::Vec3::ZERO, glam::Vec3::X, glam::Vec3::Y].map(|p| t.transform_point3(p));
            corners
                .iter()
                .fold((x0, x1, z0, z1), |(x0, x1, z0, z1), p| {
                    (x0.min(p.x), x1.max(p.x), z0.min(p.z), z1.max(p.z))
                })
        },
    )
}

#[test]
fn a_lot_of_points_or_geojson_is_the_footprint_built_on() {
    let fixture = Fixture::new();
    let scene = load(&fixture, L_POINTS).unwrap();
    let lot = scene.site.lot().expect("the scene has a lot");
    assert_eq!((lot.len(), lot.area()), (6, 16.0 * 12.0 - 8.0 * 6.0));

    write(&fixture, "l.geojson", L_GEOJSON);
    let from_file = load(&fixture, "[lot]\ngeojson = \"l.geojson\"").unwrap();
    assert_eq!(from_file.site, scene.site);

    // Map coordinates: x east, y north, laid on the ground as z = -y.
    let mut instances = Vec::new();
    block(6.0).derive_on(&scene.site, &mut instances);
    let (x0, x1, z0, z1) = extent(&instances);
    assert_eq!((x0, x1, z0, z1), (-8.0, 8.0, -6.0, 6.0));
    block(6.0).derive_into(&mut instances);
    assert_eq!(
        extent(&instances),
        (-5.0, 5.0, -5.0, 5.0),
        "the default lot"
    );

    // No lot: the site has none.
    assert!(load(&fixture, "").unwrap().site.lot().is_none());
}

#[test]
fn evaluators_build_on_the_scene_s_lot() {
    let fixture = Fixture::new();
    let on_l = load(&fixture, L_POINTS).unwrap();
    let bare = load(&fixture, "").unwrap();
    let measure = |scene: &Scene| {
        let mut evaluator = ObjectiveEvaluator::new::<LotBuilding>(scene).unwrap();
        let mut value = [0.0];
        MultiEvaluator::<LotBuilding>::evaluate(&mut evaluator, &[block(5.0)], &mut value).unwrap();
        value[0]
    };
    // The extent beyond the point (0, 0): the L's 8 + 8 + 6 + 6, the square's 4 x 5.
    assert_eq!(measure(&on_l), 28.0);
    assert_eq!(measure(&bare), 20.0);
}

#[test]
fn lot_mistakes_are_refused() {
    let fixture = Fixture::new();
    refuses(
        &fixture,
        "[lot]",
        "lot",
        "either as `points = [[x, y], ..]`",
    );
    write(&fixture, "l.geojson", L_GEOJSON);
    refuses(
        &fixture,
        &format!("{L_POINTS}\ngeojson = \"l.geojson\""),
        "lot",
        "one of the two",
    );
    refuses(
        &fixture,
        "[lot]\npoints = [[0, 0], [4, 4], [4, 0], [0, 4]]",
        "lot.points",
        "edges 0 and 2 cross or touch",
    );
    refuses(
        &fixture,
        "[lot]\npoints = [[0, 0], [4, 0], [8, 0]]",
        "lot.points",
        "at least 3 distinct points not all on one line",
    );
    refuses(
        &fixture,
        "[lot]\npoints = [[0, 0, 1]]",
        "lot.points[0]",
        "[0.0, 0.0, 1.0] has 3 numbers; a point is [x, y]",
    );
    refuses(
        &fixture,
        "[lot]\nwidth = 3",
        "width",
        "unknown field `width`",
    );
    refuses(
        &fixture,
        "[lot]\ngeojson = \"missing.geojson\"",
        "lot.geojson",
        "is not a file",
    );
    write(
        &fixture,
        "broken.geojson",
        "{\"type\": \"Polygon\", \"coordinates\": [[[0, 0]",
    );
    refuses(
        &fixture,
        "[lot]\ngeojson = \"broken.geojson\"",
        "lot.geojson",
        "is not GeoJSON",
    );
    let two = r#"{"type": "MultiPolygon", "coordinates": [
        [[[0, 0], [1, 0], [1, 1], [0, 0]]], [[[2, 0], [3, 0], [3, 1], [2, 0]]]]}"#;
    write(&fixture, "two.geojson", two);
    refuses(
        &fixture,
        "[lot]\ngeojson = \"two.geojson\"",
        "lot.geojson",
        "holds 2 polygons",
    );
    let point = r#"{"type": "Point", "coordinates": [0, 0]}"#;
    write(&fixture, "point.geojson", point);
    refuses(
        &fixture,
        "[lot]\ngeojson = \"point.geojson\"",
        "lot.geojson",
        "holds 0 polygons",
    );
    let court = r#"{"type": "Polygon", "coordinates": [[[0, 0], [9, 0], [9, 9], [0, 9], [0, 0]],
        [[3, 3], [6, 3], [6, 6], [3, 6], [3, 3]]]}"#;
    write(&fixture, "court.geojson", court);
    refuses(
        &fixture,
        "[lot]\ngeojson = \"court.geojson\"",
        "lot.geojson",
        "the polygon has 1 holes",
    );
}

#[test]
fn the_project_s_lot_is_an_l() {
    let lots = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/lots");
    let text = fs::read_to_string(lots.join("l_lot.geojson")).unwrap();
    let ring = shapegen::scene::geojson_outline(&lots.join("l_lot.geojson"), &text).unwrap();
    let lot = shapegen::geometry::Polygon::from_f64(&ring).unwrap();
    assert_eq!((lot.len(), lot.area()), (6, 144.0));
    assert_eq!(LotBuilding::GRAPH.key, "lot_building");
}
