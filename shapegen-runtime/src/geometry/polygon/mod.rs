//! Simple polygons: footprints and faces that are not boxes.
//!
//! A [`Polygon`] is checked and cleaned when it is made: duplicate and collinear points
//! are dropped, a self-intersecting outline is refused, and the points are put in
//! counter-clockwise order. It lives in a plane with coordinates `(x, y)`, as a face
//! scope's local `x` and `y` (see [`Scope::face`](crate::Scope::face)); solids built on it
//! ([`extrude`](Polygon::extrude), [`roof`](Polygon::roof)) rise along the plane's `z`.

mod clean;
mod measure;
mod offset;
mod setback;
mod simple;
mod triangulate;

pub(crate) use clean::EPS;
pub use clean::PolygonError;
pub(crate) use measure::signed_area;
pub use setback::Setback;
pub use simple::Polygon;
