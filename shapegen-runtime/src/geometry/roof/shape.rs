//! The shapes of roofs ([`RoofShape`]), their checks, and why a roof could not be built
//! ([`RoofError`]).

/// Which roof, with its shape's measure. Angles are in radians.
///
/// A roof stands on its polygon's plane (`z = 0`) and rises along `+z`. Its eave is the
/// polygon moved outward by the overhang ([`Polygon::offset`](crate::geometry::Polygon::offset), mitred corners) and lies
/// `overhang * tan(pitch)` below the plane, so that a roof face of the given pitch passes
/// through the polygon's edge at `z = 0`: the wall's top. The solid is the roof surface
/// with the eave polygon as its floor; every roof, on every simple polygon, is closed
/// and wound with its normals outward: each is checked, and where one does not close,
/// a simpler shape is built instead and [`Roof::shape`](crate::geometry::Roof::shape) says so.
///
/// ```text
///   flat          shed            gable            hip             pyramid
///  ______                          /\             ____               /\
/// |______|      __----|          /    \         /      \           /    \
///              |______|        /________\     /__________\       /________\
/// ```
///
/// | shape | over a rectangle | over any simple polygon |
/// |---|---|---|
/// | [`Flat`](RoofShape::Flat) | a slab of the given thickness | the same |
/// | [`Shed`](RoofShape::Shed) | one plane rising toward `+y` | the same |
/// | [`Hip`](RoofShape::Hip) | four faces, a ridge along the long side | one face per edge, from the straight skeleton |
/// | [`Gable`](RoofShape::Gable) | two faces and two vertical gable ends on the short sides | the hip roof with the edges whose hip faces are triangles made vertical gable ends (no two neighbours) |
/// | [`Pyramid`](RoofShape::Pyramid) | four triangles to one apex | one triangle per edge to an apex that sees every edge (in the polygon's kernel); a polygon with no kernel gets a hip roof |
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RoofShape {
    /// A slab of `thickness` over the eave polygon.
    Flat {
        /// The slab's thickness, `>= 0`.
        thickness: f32,
    },
    /// One plane rising at `pitch` toward the polygon plane's `+y`, over vertical walls.
    Shed {
        /// The plane's slope angle, in radians, in `[0, pi/2)`.
        pitch: f32,
    },
    /// Sloped faces at `pitch` and vertical gable ends.
    Gable {
        /// The faces' slope angle, in radians, in `[0, pi/2)`.
        pitch: f32,
    },
    /// One face at `pitch` per edge.
    Hip {
        /// The faces' slope angle, in radians, in `[0, pi/2)`.
        pitch: f32,
    },
    /// Triangles to one apex; `pitch` is the slope of the steepest.
    Pyramid {
        /// The steepest face's slope angle, in radians, in `[0, pi/2)`.
        pitch: f32,
    },
}

impl RoofShape {
    /// The slope angle of the shape's faces; zero for a flat roof.
    pub fn pitch(self) -> f32 {
        match self {
            RoofShape::Flat { .. } => 0.0,
            RoofShape::Shed { pitch }
            | RoofShape::Gable { pitch }
            | RoofShape::Hip { pitch }
            | RoofShape::Pyramid { pitch } => pitch,
        }
    }
}

/// Why a roof could not be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum RoofError {
    /// A pitch outside `[0, pi/2)` radians, a negative thickness or overhang, or a
    /// non-finite one.
    #[error("{what} is {value}; valid: {valid}")]
    Measure {
        /// Which measure.
        what: &'static str,
        /// Its value.
        value: f32,
        /// What is valid.
        valid: &'static str,
    },
    /// No roof closes over the polygon, not even the simplest one built instead: the
    /// polygon is too degenerate.
    #[error("no roof closes over the {points}-point polygon: it is too degenerate")]
    Degenerate {
        /// The polygon's points.
        points: usize,
    },
}

/// Checks the shape's measure and the overhang.
pub(super) fn check(shape: RoofShape, overhang: f32) -> Result<(), RoofError> {
    if !(overhang.is_finite() && overhang >= 0.0) {
        return Err(RoofError::Measure {
            what: "the overhang",
            value: overhang,
            valid: "a finite length >= 0",
        });
    }
    match shape {
        RoofShape::Flat { thickness } if !(thickness.is_finite() && thickness >= 0.0) => {
            Err(RoofError::Measure {
                what: "the flat roof's thickness",
                value: thickness,
                valid: "a finite length >= 0",
            })
        }
        RoofShape::Flat { .. } => Ok(()),
        _ => {
            let pitch = shape.pitch();
            if pitch.is_finite() && (0.0..std::f32::consts::FRAC_PI_2).contains(&pitch) {
                Ok(())
            } else {
                Err(RoofError::Measure {
                    what: "the pitch",
                    value: pitch,
                    valid: "an angle in [0, pi/2) radians",
                })
            }
        }
    }
}
