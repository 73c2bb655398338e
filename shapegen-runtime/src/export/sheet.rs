//! Contact sheets: shaded previews of several models in a grid.

use image::{Rgb, RgbImage};

use super::error::ExportError;
use super::model::Model;
use super::palette::Palette;
use super::render::Preview;
use crate::geometry::{BoundMeshes, Instance};

/// A grid of shaded previews, `columns` across, each `cell` pixels square, all through
/// one camera that frames every model shown ([`Preview::framing`] of them all), so that
/// their sizes compare. Cells are filled row by row in the models' order; the rest of
/// the last row stays white.
///
/// ```
/// use glam::{Affine3A, Vec3};
/// use shapegen_runtime::export::{ContactSheet, ExportError, Palette};
/// use shapegen_runtime::{CUBE, Instance, MeshLibrary};
///
/// let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
/// let at = |x: f32| Instance { transform: Affine3A::from_translation(Vec3::X * x), mesh: CUBE };
/// let models = [vec![at(0.0)], vec![at(0.0), at(2.0)], vec![at(4.0)]];
/// let sheet = ContactSheet { cell: 40, columns: 2 };
/// let image = sheet.render(&models, &meshes, &Palette::new(), |_, _| Ok::<_, ExportError>(()))?;
/// assert_eq!(image.dimensions(), (80, 80));
/// // The fourth cell has no model: white.
/// assert_eq!(image.get_pixel(60, 60).0, [255, 255, 255]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ContactSheet {
    /// Width and height of a cell, in pixels.
    pub cell: u32,
    /// Cells per row (at least one).
    pub columns: usize,
}

impl ContactSheet {
    /// Renders `models` into the sheet; `decorate(i, cell)` draws on model `i`'s cell
    /// (a label, say) before it is placed.
    ///
    /// # Errors
    /// A model's mesh that `meshes` lacks, or what `decorate` returns.
    pub fn render<M, E>(
        &self,
        models: &[M],
        meshes: &BoundMeshes,
        palette: &Palette,
        mut decorate: impl FnMut(usize, &mut RgbImage) -> Result<(), E>,
    ) -> Result<RgbImage, E>
    where
        M: AsRef<[Instance]>,
        E: From<ExportError>,
    {
        let all: Vec<Instance> = models
            .iter()
            .flat_map(|m| m.as_ref().iter().copied())
            .collect();
        let preview = Preview::framing(&all, meshes, self.cell, self.cell);
        let columns = models.len().clamp(1, self.columns.max(1));
        let rows = models.len().div_ceil(columns).max(1);
        let mut sheet = RgbImage::from_pixel(
            self.cell * columns as u32,
            self.cell * rows as u32,
            Rgb([255, 255, 255]),
        );
        for (i, model) in models.iter().enumerate() {
            let mut cell = preview.render(Model::new(model.as_ref(), meshes, palette))?;
            decorate(i, &mut cell)?;
            let (x, y) = ((i % columns) as u32, (i / columns) as u32);
            image::imageops::replace(
                &mut sheet,
                &cell,
                i64::from(x * self.cell),
                i64::from(y * self.cell),
            );
        }
        Ok(sheet)
    }
}
