//! Roofs and prisms over polygons: CGA's `extrude` and `roofFlat`, `roofShed`,
//! `roofGable`, `roofHip` and `roofPyramid`, each a closed solid.
//!
//! See [`RoofShape`] for the shapes and where a roof stands.

mod pieces;
mod shape;
mod skeleton;

pub use pieces::{RoofMeshes, RoofPiece};
use shape::check;
pub use shape::{RoofError, RoofShape};

use glam::{DVec2, DVec3};

use super::mesh::Mesh;
use super::polygon::Polygon;
use super::solid::Solid;

/// A roof built over a polygon: the solid and how it was built.
#[derive(Clone, Debug)]
pub struct Roof {
    /// The closed solid, in the polygon's plane coordinates with `+z` up.
    pub mesh: Mesh,
    /// The shape built: the one asked for, or the one built instead where it cannot be.
    /// A pyramid over a polygon with no point that sees all its edges becomes a hip
    /// roof; a gable or hip roof whose straight skeleton does not close (a polygon with
    /// near-coincident events the sweep cannot resolve) becomes a hip or a shed roof.
    pub shape: RoofShape,
    /// The overhang built: the one asked for, or less where a notch of the polygon is
    /// too narrow for it (see [`Polygon::offset_at_most`]).
    pub overhang: f32,
    /// The eave polygon: the polygon moved outward by the overhang.
    pub eave: Polygon,
}

impl Polygon {
    /// The prism of `height` standing on the polygon: a closed solid from `z = 0` to
    /// `z = height` (CGA's `extrude`).
    ///
    /// ```
    /// use glam::vec2;
    /// use shapegen_runtime::geometry::Polygon;
    ///
    /// let l = Polygon::new([
    ///     vec2(0.0, 0.0), vec2(2.0, 0.0), vec2(2.0, 1.0),
    ///     vec2(1.0, 1.0), vec2(1.0, 2.0), vec2(0.0, 2.0),
    /// ])?;
    /// let prism = l.extrude(3.0);
    /// assert!(prism.is_closed());
    /// assert!((prism.volume() - 9.0).abs() < 1e-5);
    /// # Ok::<(), shapegen_runtime::geometry::PolygonError>(())
    /// ```
    pub fn extrude(&self, height: f32) -> Mesh {
        let h = f64::from(height);
        let mut solid = Solid::new(self.tolerance());
        prism(&mut solid, self, |_| 0.0, |_| h);
        solid.finish()
    }

    /// The roof of `shape` over the polygon with `overhang` (see [`RoofShape`] for what
    /// each shape is and where the eave lies).
    ///
    /// ```
    /// use glam::vec2;
    /// use shapegen_runtime::geometry::{Polygon, RoofShape};
    ///
    /// let house = Polygon::rectangle(vec2(8.0, 4.0))?;
    /// let pitch = 45f32.to_radians();
    /// let roof = house.roof(RoofShape::Gable { pitch }, 0.0)?;
    /// assert!(roof.mesh.is_closed());
    /// // A gable over a 4-wide house at 45 degrees: the ridge 2 high, 8 long.
    /// let (_, top) = roof.mesh.bounds().unwrap();
    /// assert!((top.z - 2.0).abs() < 1e-5);
    /// assert!((roof.mesh.volume() - 0.5 * 4.0 * 2.0 * 8.0).abs() < 1e-4);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn roof(&self, shape: RoofShape, overhang: f32) -> Result<Roof, RoofError> {
        check(shape, overhang)?;
        let (overhang, eave) = self.offset_at_most(f64::from(overhang));
        let tolerance = self.tolerance().max(eave.tolerance());
        let z0 = -overhang * f64::from(shape.pitch()).tan();
        let mut shape = shape;
        loop {
            if let Some(mesh) = build(shape, &eave, z0, tolerance) {
                return Ok(Roof {
                    mesh,
                    shape,
                    overhang: overhang as f32,
                    eave,
                });
            }
            shape = fallback(shape).ok_or(RoofError::Degenerate { points: eave.len() })?;
        }
    }

    /// The distance under which two generated corners are one: the one under which
    /// the polygon's own corners were cleaned.
    fn tolerance(&self) -> f64 {
        super::polygon::EPS * self.scale()
    }
}

/// The closed solid of `shape` over `eave` with its floor at `z0`, or `None` where the
/// straight skeleton could not close it (a polygon too degenerate for it).
fn build(shape: RoofShape, eave: &Polygon, z0: f64, tolerance: f64) -> Option<Mesh> {
    let slope = f64::from(shape.pitch()).tan();
    let mut solid = Solid::new(tolerance);
    let hip = vec![1.0; eave.len()];
    let swept = match shape {
        RoofShape::Flat { thickness } => {
            prism(&mut solid, eave, |_| 0.0, |_| f64::from(thickness));
            Ok(())
        }
        RoofShape::Shed { .. } => {
            let low = eave.bounds().0.y;
            let p = eave.points();
            prism(&mut solid, eave, |_| z0, |i| z0 + (p[i].y - low) * slope);
            Ok(())
        }
        RoofShape::Hip { .. } => skeleton_roof(&mut solid, eave, &hip, z0, slope),
        RoofShape::Gable { .. } => {
            skeleton::sweep(eave, &hip, z0, slope, &mut Solid::new(tolerance)).and_then(|hip| {
                let weights = gable_weights(eave, &hip.triangle_face);
                skeleton_roof(&mut solid, eave, &weights, z0, slope)
            })
        }
        RoofShape::Pyramid { .. } => match kernel_point(eave) {
            Some(apex) => {
                pyramid(&mut solid, eave, apex, z0, slope);
                Ok(())
            }
            None => return None,
        },
    };
    let mesh = swept.ok().map(|()| solid.finish());
    mesh.filter(|m| m.is_closed() && m.volume() > 0.0)
}

/// The shape built instead of `shape` where `shape` cannot be: a gable or a pyramid
/// becomes a hip roof, a hip roof a shed roof.
fn fallback(shape: RoofShape) -> Option<RoofShape> {
    match shape {
        RoofShape::Gable { pitch } | RoofShape::Pyramid { pitch } => Some(RoofShape::Hip { pitch }),
        RoofShape::Hip { pitch } => Some(RoofShape::Shed { pitch }),
        RoofShape::Flat { .. } | RoofShape::Shed { .. } => None,
    }
}

/// A closed prism over `polygon` from `bottom(i)` to `top(i)` at point `i` (planar caps
/// expected): floor facing down, top facing up, a wall per edge.
fn prism(
    solid: &mut Solid,
    polygon: &Polygon,
    bottom: impl Fn(usize) -> f64,
    top: impl Fn(usize) -> f64,
) {
    let p = polygon.points();
    solid.cap(polygon, false, &bottom);
    solid.cap(polygon, true, &top);
    for i in 0..p.len() {
        let j = (i + 1) % p.len();
        solid.quad(
            p[i].extend(bottom(i)),
            p[j].extend(bottom(j)),
            p[j].extend(top(j)),
            p[i].extend(top(i)),
        );
    }
}

/// The swept roof over `eave` with its floor.
fn skeleton_roof(
    solid: &mut Solid,
    eave: &Polygon,
    weights: &[f64],
    z0: f64,
    slope: f64,
) -> Result<(), RoofError> {
    solid.cap(eave, false, |_| z0);
    skeleton::sweep(eave, weights, z0, slope, solid).map(|_| ())
}

/// Weights for a gable roof: 0 (vertical gable ends) on the edges whose hip faces are
/// triangles, shortest first, skipping neighbours of edges already chosen (keeping at
/// least one sloped edge between any two gables) and edges that run on nearly straight
/// into a neighbour; 1 elsewhere.
fn gable_weights(eave: &Polygon, triangle_face: &[bool]) -> Vec<f64> {
    let n = eave.len();
    let mut order: Vec<usize> = (0..n).filter(|&i| triangle_face[i]).collect();
    let length = |i: usize| {
        let (a, b) = eave.edge(i);
        (b - a).length()
    };
    order.sort_by(|&a, &b| length(a).total_cmp(&length(b)));
    let mut weights = vec![1.0; n];
    for i in order {
        let before = (i + n - 1) % n;
        let after = (i + 1) % n;
        if weights[before] != 0.0 && weights[after] != 0.0 && turns(eave, i) {
            weights[i] = 0.0;
        }
    }
    weights
}

/// The least turn, in radians, from a gable end into each neighbouring edge: a gable
/// beside an edge that runs on nearly straight would have the sloped face turn about
/// a corner that is hardly there.
const GABLE_TURN: f64 = 0.05;

/// Whether edge `i` turns by at least [`GABLE_TURN`] from both its neighbours.
fn turns(eave: &Polygon, i: usize) -> bool {
    let n = eave.len();
    let dir = |k: usize| {
        let (a, b) = eave.edge(k % n);
        (b - a).normalize()
    };
    let sine = GABLE_TURN.sin();
    dir(i + n - 1).perp_dot(dir(i)).abs() >= sine && dir(i).perp_dot(dir(i + 1)).abs() >= sine
}

/// A point from which every edge is seen from its inner side, well inside the kernel
/// (the centroid of the kernel), or `None` when the kernel has no area.
fn kernel_point(polygon: &Polygon) -> Option<DVec2> {
    let (lo, hi) = polygon.bounds();
    let pad = hi - lo;
    let mut kernel = vec![
        lo - pad,
        DVec2::new(hi.x + pad.x, lo.y - pad.y),
        hi + pad,
        DVec2::new(lo.x - pad.x, hi.y + pad.y),
    ];
    for i in 0..polygon.len() {
        let (a, _) = polygon.edge(i);
        let normal = polygon.inward_normal(i);
        kernel = clip(&kernel, a, normal);
        if kernel.len() < 3 {
            return None;
        }
    }
    let area = super::polygon::signed_area(&kernel);
    if area <= 1e-9 * polygon.area() {
        return None;
    }
    Polygon::from_f64(&kernel).ok().map(|k| k.centroid())
}

/// The convex polygon `points` clipped to the half-plane `(x - a) . normal >= 0`.
fn clip(points: &[DVec2], a: DVec2, normal: DVec2) -> Vec<DVec2> {
    let side = |p: DVec2| (p - a).dot(normal);
    let mut out = Vec::with_capacity(points.len() + 1);
    for i in 0..points.len() {
        let (p, q) = (points[i], points[(i + 1) % points.len()]);
        let (sp, sq) = (side(p), side(q));
        if sp >= 0.0 {
            out.push(p);
        }
        if (sp >= 0.0) != (sq >= 0.0) {
            out.push(p + (q - p) * (sp / (sp - sq)));
        }
    }
    out
}

/// Triangles from each edge of `eave` to the apex over `apex`, whose height makes the
/// steepest face's slope `slope`.
fn pyramid(solid: &mut Solid, eave: &Polygon, apex: DVec2, z0: f64, slope: f64) {
    let nearest = (0..eave.len())
        .map(|i| (apex - eave.edge(i).0).dot(eave.inward_normal(i)))
        .fold(f64::INFINITY, f64::min);
    let top = DVec3::new(apex.x, apex.y, z0 + nearest * slope);
    solid.cap(eave, false, |_| z0);
    for i in 0..eave.len() {
        let (a, b) = eave.edge(i);
        solid.triangle(a.extend(z0), b.extend(z0), top);
    }
}
