//! `[lot]`: the footprint a scene's building stands on, as a list of points or a GeoJSON
//! file.

use std::path::Path;
use std::str::FromStr;

use geojson::{GeoJson, Geometry, GeometryValue, PolygonType};
use glam::DVec2;
use shapegen_runtime::Site;
use shapegen_runtime::geometry::Polygon;

use super::error::{LotError, SceneError};
use super::file::{Coordinates, LotFile};
use super::resolve::Resolver;

/// WGS 84: the semi-major axis in metres and the flattening.
const WGS84_A: f64 = 6_378_137.0;
const WGS84_F: f64 = 1.0 / 298.257_223_563;

impl Resolver<'_> {
    /// The site of a scene's `[lot]` table.
    pub(super) fn lot(&self, lot: &LotFile) -> Result<Site, SceneError> {
        let (key, points) = match (&lot.points, &lot.geojson) {
            (Some(points), None) => {
                let points = points
                    .iter()
                    .enumerate()
                    .map(|(i, p)| match p[..] {
                        [x, y] => Ok(DVec2::new(x, y)),
                        _ => Err(self.invalid(
                            format!("lot.points[{i}]"),
                            format!("{p:?} has {} numbers; a point is [x, y]", p.len()),
                        )),
                    })
                    .collect::<Result<_, _>>()?;
                ("lot.points", points)
            }
            (None, Some(written)) => {
                let path = self.file("lot.geojson", written)?;
                let ring = read_geojson(&path).map_err(|err| self.refused("lot.geojson", err))?;
                ("lot.geojson", ring)
            }
            _ => {
                return Err(self.invalid(
                    "lot",
                    "give the lot's outline either as `points = [[x, y], ..]` or as \
                     `geojson = \"file.geojson\"`, one of the two",
                ));
            }
        };
        let points = match lot.coordinates {
            Coordinates::Metres if lot.centre => centred(&points),
            Coordinates::Metres => points,
            Coordinates::Degrees => to_metres(&points).map_err(|(i, p)| {
                self.invalid(
                    match key {
                        "lot.points" => format!("lot.points[{i}]"),
                        _ => key.to_owned(),
                    },
                    format!(
                        "point {i}, [{}, {}], is not [longitude, latitude] in degrees; \
                         with coordinates = \"degrees\" a longitude lies in [-180, 180] and \
                         a latitude in [-90, 90] (for metres leave `coordinates` out)",
                        p.x, p.y
                    ),
                )
            })?,
        };
        let polygon = Polygon::from_f64(&points).map_err(|err| self.refused(key, err))?;
        Ok(Site::with_lot(polygon))
    }
}

/// The middle of `points`' bounding box.
fn middle(points: &[DVec2]) -> DVec2 {
    let (lo, hi) = points.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    (lo + hi) / 2.0
}

/// `points` moved so that the middle of their bounding box is the origin.
fn centred(points: &[DVec2]) -> Vec<DVec2> {
    let middle = middle(points);
    points.iter().map(|&p| p - middle).collect()
}

/// Longitudes and latitudes in degrees (WGS 84) as metres east and north of the middle
/// of their bounding box, on the plane touching the ellipsoid there: each degree of
/// longitude is `N cos(lat0)` and each of latitude `M` (the ellipsoid's radii of
/// curvature at the middle's latitude `lat0`). Against PROJ's geodesics on WGS 84, the
/// edges of a lot about 330 m across at 60 degrees of latitude come out within 5e-5 of
/// their lengths, those of one 1 km across within 1.5e-4 (the scene tests hold it to
/// these). A lot crossing the antimeridian is kept whole. Fails with the index of a
/// point that is no longitude and latitude.
fn to_metres(points: &[DVec2]) -> Result<Vec<DVec2>, (usize, DVec2)> {
    if let Some(i) = points
        .iter()
        .position(|p| !(p.x.abs() <= 180.0 && p.y.abs() <= 90.0))
    {
        return Err((i, points[i]));
    }
    // Longitudes as offsets from the first point's, each within half a turn of it.
    let first = points.first().map_or(0.0, |p| p.x);
    let unwrapped: Vec<DVec2> = points
        .iter()
        .map(|p| DVec2::new(first + (p.x - first + 540.0).rem_euclid(360.0) - 180.0, p.y))
        .collect();
    let middle = middle(&unwrapped);
    let lat0 = middle.y.to_radians();
    let e2 = WGS84_F * (2.0 - WGS84_F);
    let w = (1.0 - e2 * lat0.sin().powi(2)).sqrt();
    let metres = DVec2::new(WGS84_A / w * lat0.cos(), WGS84_A * (1.0 - e2) / w.powi(3));
    Ok(unwrapped
        .iter()
        .map(|&p| metres * ((p - middle) * (std::f64::consts::PI / 180.0)))
        .collect())
}

/// The exterior ring of the one polygon of the GeoJSON file at `path`.
fn read_geojson(path: &Path) -> Result<Vec<DVec2>, LotError> {
    let text = std::fs::read_to_string(path).map_err(|source| LotError::Io {
        path: path.to_owned(),
        source,
    })?;
    geojson_outline(path, &text)
}

/// The outline of the lot in `text`, a GeoJSON file's contents (the file is `path`, which
/// errors name): the exterior ring of its one polygon, a `Polygon` geometry (or a
/// `MultiPolygon` of one) on its own, in a feature, or in a collection of one feature.
/// Coordinates are used as they are, `[x, y]` with `y` north (an altitude is ignored):
/// give a lot in metres of a local or projected system, not in degrees of longitude and
/// latitude.
///
/// ```
/// use std::path::Path;
/// use shapegen::scene::geojson_outline;
///
/// let text = r#"{"type": "Feature", "properties": {}, "geometry": {"type": "Polygon",
///     "coordinates": [[[0, 0], [8, 0], [8, 6], [0, 6], [0, 0]]]}}"#;
/// let ring = geojson_outline(Path::new("lot.geojson"), text)?;
/// assert_eq!(ring.len(), 5);
/// let hole = r#"{"type": "Polygon", "coordinates": [[[0, 0], [8, 0], [8, 6], [0, 0]],
///     [[1, 1], [2, 1], [2, 2], [1, 1]]]}"#;
/// let err = geojson_outline(Path::new("lot.geojson"), hole).unwrap_err();
/// assert!(err.to_string().contains("1 holes"));
/// # Ok::<(), shapegen::scene::LotError>(())
/// ```
pub fn geojson_outline(path: &Path, text: &str) -> Result<Vec<DVec2>, LotError> {
    let json = GeoJson::from_str(text).map_err(|err| LotError::Syntax {
        path: path.to_owned(),
        message: err.to_string(),
    })?;
    let mut polygons = Vec::new();
    match &json {
        GeoJson::Geometry(g) => collect(g, &mut polygons),
        GeoJson::Feature(f) => f.geometry.iter().for_each(|g| collect(g, &mut polygons)),
        GeoJson::FeatureCollection(c) => c
            .features
            .iter()
            .flat_map(|f| &f.geometry)
            .for_each(|g| collect(g, &mut polygons)),
    }
    let [rings] = polygons[..] else {
        return Err(LotError::Polygons {
            path: path.to_owned(),
            polygons: polygons.len(),
        });
    };
    if rings.len() > 1 {
        return Err(LotError::Holes {
            path: path.to_owned(),
            holes: rings.len() - 1,
        });
    }
    // A position holds at least two numbers (the parser refuses shorter ones).
    Ok(rings
        .first()
        .map(|ring| {
            ring.iter()
                .filter_map(|p| match *p.as_slice() {
                    [x, y, ..] => Some(DVec2::new(x, y)),
                    _ => None,
                })
                .collect()
        })
        .unwrap_or_default())
}

/// Appends the polygons of `geometry` to `out`.
fn collect<'a>(geometry: &'a Geometry, out: &mut Vec<&'a PolygonType>) {
    match &geometry.value {
        GeometryValue::Polygon { coordinates } => out.push(coordinates),
        GeometryValue::MultiPolygon { coordinates } => out.extend(coordinates),
        GeometryValue::GeometryCollection { geometries } => {
            geometries.iter().for_each(|g| collect(g, out));
        }
        _ => {}
    }
}
