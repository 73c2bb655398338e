//! The site a derivation grows on.

use crate::geometry::Polygon;

/// What a derivation grows on, read by the rules through [`Shape::site`](crate::Shape::site):
/// the lot a building stands on, say. A generator that reads no site, or a site without a
/// lot, builds as it always does; a generator that builds on lots uses its own default
/// lot where the site has none.
///
/// The lot is a footprint in map coordinates: `x` east and `y` north, in world units,
/// laid on the ground as world `x = x`, `z = -y` (north is away from a viewer looking
/// from the front, `+z`), counter-clockwise seen from above.
///
/// ```
/// use glam::vec2;
/// use shapegen_runtime::derive::Site;
/// use shapegen_runtime::geometry::Polygon;
///
/// assert!(Site::NONE.lot().is_none());
/// let l = Polygon::new([
///     vec2(-6.0, -4.0), vec2(6.0, -4.0), vec2(6.0, 0.0),
///     vec2(0.0, 0.0), vec2(0.0, 4.0), vec2(-6.0, 4.0),
/// ])?;
/// let site = Site::with_lot(l);
/// assert_eq!(site.lot().map(Polygon::len), Some(6));
/// # Ok::<(), shapegen_runtime::geometry::PolygonError>(())
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Site {
    lot: Option<Polygon>,
}

impl Site {
    /// The site with nothing on it: every generator builds as without a site.
    pub const NONE: Site = Site { lot: None };

    /// The site of one lot.
    pub fn with_lot(lot: Polygon) -> Site {
        Site { lot: Some(lot) }
    }

    /// The lot, if the site has one.
    pub fn lot(&self) -> Option<&Polygon> {
        self.lot.as_ref()
    }
}
