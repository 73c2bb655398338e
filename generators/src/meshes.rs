//! The project's own part meshes for the published generators, built into the crate.

use std::f32::consts::{PI, TAU};

use shapegen_runtime::geometry::RoofPiece;
use shapegen_runtime::prelude::{Vec3, vec3};
use shapegen_runtime::{Mesh, MeshLibrary};

/// The tree's branch mesh: a closed eight-sided prism spanning `[-0.5, 0.5]`.
pub const TRUNK_OBJ: &str = include_str!("../meshes/trunk.obj");

/// The tree's leaf mesh: a closed lens-shaped leaf about 0.48 x 0.98 x 0.15, centred,
/// its tip towards +y, as written. [`default_meshes`] normalizes it to unit extent, as
/// the original does with its leaf; the tree emits it unscaled.
pub const LEAF_OBJ: &str = include_str!("../meshes/leaf.obj");

/// Segments of [`low_poly_sphere`] around its vertical axis.
const SPHERE_SEGMENTS: u32 = 8;
/// Bands of [`low_poly_sphere`] from pole to pole.
const SPHERE_BANDS: u32 = 4;

/// A mesh library holding every mesh the published generators use: the built-in `cube`,
/// `trunk`, `leaf` and `sphere`, the roof pieces of
/// [`RoofedBuilding`](crate::building::roofed::RoofedBuilding) ([`RoofPiece`]), and the
/// parts of [`LotBuilding`](crate::LotBuilding), `wall`, `roof`, `window`, `door` and
/// `slab`, each the unit facet ([`Mesh::facet`]) that its generated triangles place. `trunk` and `leaf` are normalized as every generator
/// mesh loaded from OBJ is ([`Mesh::from_obj_str_normalized`]).
///
/// ```
/// use shapegen_runtime::Grammar;
///
/// let library = generators::default_meshes();
/// assert_eq!(library.names().count(), 13);
/// let bound = library.bind(<generators::Tree as Grammar>::GRAPH).unwrap();
/// assert_eq!(bound.len(), 3);
/// let bound = library.bind(<generators::Building as Grammar>::GRAPH).unwrap();
/// assert_eq!(bound.len(), 2);
/// ```
pub fn default_meshes() -> MeshLibrary {
    let mut library = MeshLibrary::new();
    for (name, file, text) in [
        ("trunk", "trunk.obj", TRUNK_OBJ),
        ("leaf", "leaf.obj", LEAF_OBJ),
    ] {
        let mesh = Mesh::from_obj_str_normalized(file, text)
            .unwrap_or_else(|e| panic!("the built-in mesh {file} is broken: {e}"));
        library
            .register(name, mesh)
            .unwrap_or_else(|e| panic!("the built-in mesh {file} is broken: {e}"));
    }
    library
        .register("sphere", low_poly_sphere())
        .unwrap_or_else(|e| panic!("the built-in sphere mesh is broken: {e}"));
    for piece in RoofPiece::ALL {
        library
            .register(piece.name(), piece.mesh())
            .unwrap_or_else(|e| panic!("the built-in {} mesh is broken: {e}", piece.name()));
    }
    for part in ["wall", "roof", "window", "door", "slab"] {
        library
            .register(part, Mesh::facet())
            .unwrap_or_else(|e| panic!("the built-in {part} facet is broken: {e}"));
    }
    library
}

/// The building's `sphere` mesh: a flat-shaded low-poly sphere of radius 0.5 centred at
/// the origin, spanning `[-0.5, 0.5]` on every axis. Eight segments around the y axis
/// and four bands from pole to pole (latitudes -90, -45, 0, 45, 90 degrees) make 48
/// triangles, each with its own three vertices and its outward face normal.
///
/// ```
/// let sphere = generators::low_poly_sphere();
/// assert_eq!((sphere.triangle_count(), sphere.vertex_count()), (48, 144));
/// let (lo, hi) = sphere.bounds().unwrap();
/// assert!(lo.abs_diff_eq(glam::Vec3::splat(-0.5), 1e-6));
/// assert!(hi.abs_diff_eq(glam::Vec3::splat(0.5), 1e-6));
/// ```
pub fn low_poly_sphere() -> Mesh {
    let point = |segment: u32, band: u32| {
        let (lat, lon) = (
            PI * (band as f32 / SPHERE_BANDS as f32 - 0.5),
            TAU * segment as f32 / SPHERE_SEGMENTS as f32,
        );
        0.5 * vec3(lat.cos() * lon.cos(), lat.sin(), -lat.cos() * lon.sin())
    };
    let mut mesh = Mesh::default();
    let mut triangle = |corners: [Vec3; 3]| {
        let [a, b, c] = corners;
        let normal = (b - a).cross(c - a).normalize();
        let base = mesh.positions.len() as u32;
        mesh.positions.extend(corners);
        mesh.normals.extend([normal; 3]);
        mesh.indices.extend([base, base + 1, base + 2]);
    };
    for band in 0..SPHERE_BANDS {
        for segment in 0..SPHERE_SEGMENTS {
            // The quad between latitudes `band` and `band + 1`, counter-clockwise seen
            // from outside; at the poles it shrinks to a triangle.
            let (a, b) = (point(segment, band), point(segment + 1, band));
            let (c, d) = (point(segment + 1, band + 1), point(segment, band + 1));
            if band > 0 {
                triangle([a, b, d]);
            }
            if band + 1 < SPHERE_BANDS {
                triangle([b, c, d]);
            }
        }
    }
    mesh
}
