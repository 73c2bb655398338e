//! Targets given in memory: [`Sources`].

use std::collections::BTreeMap;

use image::DynamicImage;
use shapegen_runtime::geometry::Mesh;

/// Targets given in memory: meshes and images that a scene's text names in place of
/// files, for programs that hold their targets as arrays (the Python package, an editor).
///
/// A name written where the scene reads a file (`[[volume.target]] mesh`,
/// `[[silhouette.target]] image`) is looked up in the [`Sources`] first; a name they do
/// not hold is read as a path, as usual. Everything else about the target (weights, fill
/// rule, mask rule, the camera's size) is read and checked as for a file.
///
/// ```
/// use std::path::Path;
/// use shapegen::geometry::Mesh;
/// use shapegen::registry::Registry;
/// use shapegen::scene::{Overrides, Scene, ScorerGoal, Sources};
///
/// let text = r#"
/// generator = "spaceship"
/// [limits]
/// min_len = 1
/// max_len = 50
/// max_depth = 10
/// [volume]
/// grid = { min = [-1, -1, -1], max = [1, 1, 1], resolution = [16, 16, 16] }
/// [[volume.target]]
/// mesh = "block"
/// "#;
/// let sources = Sources::new().mesh("block", Mesh::unit_cube());
/// let scene = Scene::parse_with(
///     text,
///     Path::new("block.toml"),
///     &Registry::published(),
///     &Overrides::default(),
///     &sources,
/// )?;
/// let ScorerGoal::Volume(volume) = &scene.scorers()[0] else { unreachable!() };
/// assert_eq!(volume.targets[0].name, "block");
/// // Without the source, `block` is a file that is not there.
/// assert!(Scene::parse(text, Path::new("block.toml")).is_err());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, Default)]
pub struct Sources {
    meshes: BTreeMap<String, Mesh>,
    images: BTreeMap<String, DynamicImage>,
}

impl Sources {
    /// No sources: every name is a path.
    pub fn new() -> Sources {
        Sources::default()
    }

    /// `self` with `mesh` under `name` (replacing one of the same name).
    pub fn mesh(mut self, name: impl Into<String>, mesh: Mesh) -> Sources {
        self.meshes.insert(name.into(), mesh);
        self
    }

    /// `self` with `image` under `name` (replacing one of the same name).
    pub fn image(mut self, name: impl Into<String>, image: DynamicImage) -> Sources {
        self.images.insert(name.into(), image);
        self
    }

    /// The mesh given as `name`.
    pub fn get_mesh(&self, name: &str) -> Option<&Mesh> {
        self.meshes.get(name)
    }

    /// The image given as `name`.
    pub fn get_image(&self, name: &str) -> Option<&DynamicImage> {
        self.images.get(name)
    }
}
