//! Why a GeoJSON file does not hold a scene's lot.

/// Why a GeoJSON file does not hold one lot.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum LotError {
    /// The file cannot be read.
    #[error("cannot read `{}`: {source}", path.display())]
    Io {
        /// The file.
        path: std::path::PathBuf,
        /// What the system said.
        #[source]
        source: std::io::Error,
    },
    /// The file is not GeoJSON.
    #[error("`{}` is not GeoJSON: {message}", path.display())]
    Syntax {
        /// The file.
        path: std::path::PathBuf,
        /// The parser's message.
        message: String,
    },
    /// The file holds no polygon, or more than one.
    #[error(
        "`{}` holds {polygons} polygons; a lot is one Polygon (a geometry, a feature, or \
         a collection of one feature)",
        path.display()
    )]
    Polygons {
        /// The file.
        path: std::path::PathBuf,
        /// How many it holds.
        polygons: usize,
    },
    /// The polygon has holes.
    #[error(
        "`{}`: the polygon has {holes} holes; a lot is an outline without holes \
         (its exterior ring only)",
        path.display()
    )]
    Holes {
        /// The file.
        path: std::path::PathBuf,
        /// How many interior rings.
        holes: usize,
    },
}
