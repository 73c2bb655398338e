//! A grammar of generated geometry: pavilions on polygon footprints (L, U, triangle,
//! rectangle), each an extruded footprint with a straight-skeleton roof, all placed as
//! facets, next to plain boxes.

use glam::DVec2;
use shapegen_runtime::geometry::{Mesh, MeshLibrary, Polygon, RoofShape};
use shapegen_runtime::prelude::*;
use shapegen_runtime::score::silhouette::{Camera, ImageTarget, OrbitCamera, Weighting};
use shapegen_runtime::{BoundMeshes, generator};

/// The footprint of shape `k`, `size` across.
pub fn footprint(k: u32, size: f32) -> Polygon {
    let s = f64::from(size) / 2.0;
    let points: &[[f64; 2]] = match k % 4 {
        0 => &[
            [-1.0, -1.0],
            [1.0, -1.0],
            [1.0, 0.0],
            [0.0, 0.0],
            [0.0, 1.0],
            [-1.0, 1.0],
        ],
        1 => &[
            [-1.0, -1.0],
            [1.0, -1.0],
            [1.0, 1.0],
            [0.4, 1.0],
            [0.4, -0.2],
            [-0.4, -0.2],
            [-0.4, 1.0],
            [-1.0, 1.0],
        ],
        2 => &[[-1.0, -0.8], [1.0, -0.8], [0.1, 1.0]],
        _ => &[[-1.0, -0.6], [1.0, -0.6], [1.0, 0.6], [-1.0, 0.6]],
    };
    let points: Vec<DVec2> = points
        .iter()
        .map(|&[x, y]| DVec2::new(x * s, y * s))
        .collect();
    Polygon::from_f64(&points).expect("a simple footprint")
}

/// Roof shape `k`.
pub fn roof_shape(k: u32, pitch: f32) -> RoofShape {
    match k % 5 {
        0 => RoofShape::Flat { thickness: 0.4 },
        1 => RoofShape::Shed { pitch },
        2 => RoofShape::Gable { pitch },
        3 => RoofShape::Hip { pitch },
        _ => RoofShape::Pyramid { pitch },
    }
}

generator! {
    /// Pavilions on polygon footprints, their walls and roofs generated, and boxes.
    pub Pavilions {
        axiom Site;
        meshes {
            /// Generated walls.
            FACET_WALL = "facet_wall",
            /// Generated roofs.
            FACET_ROOF = "facet_roof",
        }

        /// The site: up to four pavilions and a box.
        node Site {
            children {
                /// The pavilions.
                pavilions: [Pavilion; 4] = 0.6,
                /// A box.
                annex: Annex = 0.4,
            }
            derive(s) {
                for (_, p) in pavilions.iter() {
                    s.derive(p);
                }
                if let Some(a) = annex {
                    s.derive(a);
                }
            }
        }

        /// A pavilion: an extruded footprint with a roof.
        node Pavilion {
            params {
                /// The footprint's shape.
                shape: u32 ~ uniform(0..=3),
                /// Where it stands.
                at: Vec2 ~ uniform([-6.0, -6.0], [6.0, 6.0]),
                /// Its size across.
                size: f32 ~ uniform(3.0, 9.0),
                /// Its walls' height.
                height: f32 ~ uniform(2.0, 12.0),
                /// Its turn about the vertical.
                turn: f32 ~ degrees(0.0, 90.0),
                /// The roof's shape.
                roof: u32 ~ uniform(0..=4),
                /// The roof's pitch.
                pitch: f32 ~ degrees(15.0, 60.0),
                /// The roof's overhang.
                overhang: f32 ~ uniform(0.0, 0.8),
            }
            derive(s) {
                let base = s
                    .translate(vec3(at.x, height / 2.0, at.y))
                    .rotate_y(turn)
                    .with_size(vec3(size, height, size));
                let footprint = footprint(shape, size);
                base.extrude_polygon(&footprint, height, FACET_WALL);
                let _ = base.roof_polygon(&footprint, roof_shape(roof, pitch), overhang, FACET_ROOF);
            }
        }

        /// A box.
        node Annex {
            params {
                /// Its size.
                size: Vec3 ~ uniform([1.0, 1.0, 1.0], [6.0, 10.0, 6.0]),
            }
            derive(s) {
                s.translate(vec3(0.0, size.y / 2.0, 0.0)).with_size(size).emit(CUBE);
            }
        }
    }
}

/// The limits the pavilions are grown within.
pub const LIMITS: Limits = Limits {
    min_len: 1,
    max_len: 6,
    max_depth: 3,
};

/// The pavilions' meshes: the cube and the facets.
pub fn meshes() -> BoundMeshes {
    let mut library = MeshLibrary::new();
    library.register("facet_wall", Mesh::facet()).unwrap();
    library.register("facet_roof", Mesh::facet()).unwrap();
    library.bind(Pavilions::GRAPH).unwrap()
}

/// A 160 x 120 silhouette target seen from the front and a little above: a block in the
/// middle of the image.
#[allow(dead_code)] // not every test target that includes this module uses it
pub fn front_target() -> ImageTarget {
    let camera = Camera::Orbit(OrbitCamera {
        phi: -1.2,
        theta: 0.3,
        radius: 45.0,
        lookat: vec3(0.0, 6.0, 0.0),
        fov_degrees: 50.0,
        near: 0.1,
        far: 200.0,
    });
    let image = image::DynamicImage::ImageLuma8(image::GrayImage::from_fn(160, 120, |x, y| {
        image::Luma([if (40..120).contains(&x) && y > 40 {
            0
        } else {
            255
        }])
    }));
    ImageTarget::new("front".into(), &image, camera, Weighting::mask(1.0, -1.0)).unwrap()
}
