//! [`UniqueNormals`]: how many distinct face normals the model has.

use crate::score::objective::normals_kind::normals_kind;

normals_kind! {
    /// Number of distinct face normals
    /// ([`Sense::Maximize`](crate::evaluate::Sense::Maximize)). The surface's normals are
    /// clustered greedily in triangle order: each joins the first distinct normal found
    /// so far within `tolerance_deg` of it (`n . r >= cos(tolerance)`), else it is a new
    /// distinct normal. Any two distinct normals are thus more than the tolerance apart;
    /// a unit cube has 6; an empty model 0. Use a tolerance above rounding (a degree,
    /// say), so that the two triangles of a rotated quad agree. Its table:
    /// `kind = "unique_normals"` and `tolerance_deg` (1 when left out).
    ///
    /// ```
    /// use glam::{Affine3A, Quat};
    /// use shapegen_runtime::score::objective::{ObjectiveKind, ObjectiveScratch, Surface, UniqueNormals};
    /// use shapegen_runtime::{CUBE, Instance, MeshLibrary};
    ///
    /// let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
    /// let tilted = Affine3A::from_quat(Quat::from_rotation_y(0.01));
    /// let model = [
    ///     Instance { transform: Affine3A::IDENTITY, mesh: CUBE },
    ///     Instance { transform: tilted, mesh: CUBE },
    /// ];
    /// let surface = Surface::from_instances(&model, &meshes);
    /// let mut scratch = ObjectiveScratch::default();
    /// // Turned by about 0.57 degrees, the second cube's sides are within 1 degree.
    /// assert_eq!(UniqueNormals { tolerance_deg: 1.0 }.measure(&surface, &mut scratch), 6.0);
    /// # Ok::<(), shapegen_runtime::MeshError>(())
    /// ```
    UniqueNormals,
    |scratch, surface, tolerance| scratch.distinct(surface, tolerance).len() as f64
}
