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
    assert_eq!(lot, *generators::lot_building::L_LOT);
    assert_eq!(LotBuilding::GRAPH.key, "lot_building");
}

/// The lengths of `lot`'s edges, from point 0 on.
fn edge_lengths(lot: &shapegen::geometry::Polygon) -> Vec<f64> {
    let p = lot.points();
    (0..p.len())
        .map(|i| p[i].distance(p[(i + 1) % p.len()]))
        .collect()
}

/// Whether `a` is within `relative` of `b`.
fn near(a: f64, b: f64, relative: f64) -> bool {
    (a - b).abs() <= relative * b.abs()
}

/// A lot in degrees, as `[lot] points`, and what PROJ measures of it: its four edge
/// lengths from point 0 on and its area, the geodesics on WGS 84 of pyproj 3.4.1's
/// `Geod(ellps="WGS84")`, and how near the lot laid out in metres must come to them.
struct Surveyed {
    points: &'static str,
    edges: [f64; 4],
    area: f64,
    within: f64,
}

const SURVEYED: [Surveyed; 4] = [
    // 0.0003 x 0.0002 degrees in Berlin, about 20 x 22 m.
    Surveyed {
        points: "[[13.4050, 52.5200], [13.4053, 52.5200], [13.4053, 52.5202], [13.4050, 52.5202]]",
        edges: [20.363_824, 22.255_443, 20.363_731, 22.255_443],
        area: 453.204_89,
        within: 1e-5,
    },
    // 0.002 x 0.001 degrees across the antimeridian at 60 degrees south.
    Surveyed {
        points: "[[179.999, -60.0005], [-179.999, -60.0005], [-179.999, -59.9995], \
                 [179.999, -59.9995]]",
        edges: [111.598_319, 111.412_287, 111.601_687, 111.412_287],
        area: 12_433.611_63,
        within: 1e-4,
    },
    // 0.006 x 0.003 degrees at 60 degrees north, about 335 x 334 m.
    Surveyed {
        points: "[[10.0, 60.0], [10.006, 60.0], [10.006, 60.003], [10.0, 60.003]]",
        edges: [334.800_009, 334.236_939, 334.769_697, 334.236_939],
        area: 111_897.464_42,
        within: 5e-5,
    },
    // 0.018 x 0.009 degrees at 60 degrees north, about 1 km across.
    Surveyed {
        points: "[[10.0, 60.0], [10.018, 60.0], [10.018, 60.009], [10.0, 60.009]]",
        edges: [1_004.400_025, 1_002.711_275, 1_004.127_205, 1_002.711_275],
        area: 1_006_986.445_29,
        within: 1.5e-4,
    },
];

/// Longitudes and latitudes (GeoJSON's own coordinates) become metres east and north of
/// the lot's middle, as long as PROJ measures them.
#[test]
fn a_lot_in_degrees_is_laid_out_in_metres_around_its_middle() {
    let fixture = Fixture::new();
    for surveyed in &SURVEYED {
        let scene = load(
            &fixture,
            &format!(
                "[lot]\ncoordinates = \"degrees\"\npoints = {}",
                surveyed.points
            ),
        )
        .unwrap();
        let lot = scene.site.lot().unwrap();
        let edges = edge_lengths(lot);
        for (edge, reference) in edges.iter().zip(surveyed.edges) {
            assert!(
                near(*edge, reference, surveyed.within),
                "{}: {edges:?}",
                surveyed.points
            );
        }
        assert!(
            near(lot.area(), surveyed.area, surveyed.within),
            "{}: {}",
            surveyed.points,
            lot.area()
        );
        let (lo, hi) = lot.bounds();
        assert!((lo + hi).length() < 1e-9, "centred: {lo} {hi}");
    }

    // Berlin's lot from a GeoJSON file is the same.
    let berlin = SURVEYED[0].points;
    let scene = load(
        &fixture,
        &format!("[lot]\ncoordinates = \"degrees\"\npoints = {berlin}"),
    )
    .unwrap();
    // x east, y north: the lot is about 20 m wide and 22 m deep.
    let (lo, hi) = scene.site.lot().unwrap().bounds();
    assert!(lo.x < 0.0 && lo.y < 0.0 && hi.x > 10.0 && hi.y > 11.0);
    write(
        &fixture,
        "berlin.geojson",
        &format!(
            r#"{{"type": "Polygon", "coordinates": [[{}, [13.4050, 52.5200]]]}}"#,
            &berlin[1..berlin.len() - 1]
        ),
    );
    let from_file = load(
        &fixture,
        "[lot]\ngeojson = \"berlin.geojson\"\ncoordinates = \"degrees\"",
    )
    .unwrap();
    assert_eq!(from_file.site, scene.site);
}

#[test]
fn a_lot_far_from_the_origin_can_be_centred_on_it() {
    let fixture = Fixture::new();
    // The L of L_POINTS in the coordinates of a projected system.
    let far = "[[499992, 5399994], [500008, 5399994], [500008, 5400000], [500000, 5400000], \
               [500000, 5400006], [499992, 5400006]]";
    let centred = load(&fixture, &format!("[lot]\ncentre = true\npoints = {far}")).unwrap();
    let l = load(&fixture, L_POINTS).unwrap();
    assert_eq!(centred.site, l.site);
    let kept = load(&fixture, &format!("[lot]\npoints = {far}")).unwrap();
    assert_eq!(kept.site.lot().unwrap().bounds().0.x, 499_992.0);
}

#[test]
fn lot_coordinates_mistakes_are_refused() {
    let fixture = Fixture::new();
    refuses(
        &fixture,
        &format!("{L_POINTS}\ncoordinates = \"feet\""),
        "coordinates",
        "unknown variant `feet`, expected `metres` or `degrees`",
    );
    refuses(
        &fixture,
        "[lot]\ncoordinates = \"degrees\"\npoints = [[13.4, 52.5], [13.5, 52.5], [200.0, 52.6]]",
        "lot.points[2]",
        "point 2, [200, 52.6], is not [longitude, latitude] in degrees",
    );
    // A projected system's metres read as degrees.
    write(
        &fixture,
        "utm.geojson",
        &L_GEOJSON.replace("[-8, -6]", "[499992, 5399994]"),
    );
    refuses(
        &fixture,
        "[lot]\ngeojson = \"utm.geojson\"\ncoordinates = \"degrees\"",
        "lot.geojson",
        "point 0, [499992, 5399994], is not [longitude, latitude] in degrees; with \
         coordinates = \"degrees\" a longitude lies in [-180, 180] and a latitude in \
         [-90, 90] (for metres leave `coordinates` out)",
    );
    refuses(
        &fixture,
        "[lot]\ncoordinates = \"degrees\"\npoints = [[13.4, 52.5], [13.5, nan], [13.5, 52.6]]",
        "lot.points[1]",
        "is not [longitude, latitude]",
    );
}
