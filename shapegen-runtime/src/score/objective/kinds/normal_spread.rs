//! [`NormalSpread`]: how far apart the model's distinct face normals are.

use crate::score::objective::normals_kind::normals_kind;

normals_kind! {
    /// Sum over the distinct normals (as for [`UniqueNormals`](super::UniqueNormals)) of
    /// the angle in radians to the nearest other distinct normal
    /// ([`Sense::Maximize`](crate::evaluate::Sense::Maximize)); 0 with fewer than two. A
    /// cube: `6 * pi / 2`. Its table: `kind = "normal_spread"` and `tolerance_deg` (1 when
    /// left out).
    ///
    /// ```
    /// use glam::Affine3A;
    /// use shapegen_runtime::score::objective::{NormalSpread, ObjectiveKind, ObjectiveScratch, Surface};
    /// use shapegen_runtime::{CUBE, Instance, MeshLibrary};
    ///
    /// let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
    /// let cube = Surface::from_instances(&[Instance { transform: Affine3A::IDENTITY, mesh: CUBE }], &meshes);
    /// let spread = NormalSpread { tolerance_deg: 1.0 }.measure(&cube, &mut ObjectiveScratch::default());
    /// assert!((spread - 3.0 * std::f64::consts::PI).abs() < 1e-6);
    /// # Ok::<(), shapegen_runtime::MeshError>(())
    /// ```
    NormalSpread,
    |scratch, surface, tolerance| scratch.spread(surface, tolerance)
}
