//! A module's contents: its generators (the [`Catalog`] kept as `_catalog`), the classes,
//! the exceptions, and the functions that find generators and open or build scenes.

use std::path::PathBuf;
use std::sync::Arc;

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyModule};
use shapegen::registry::RegistryError;
use shapegen::scene::Sources;

use crate::arrays;
use crate::catalog::Catalog;
use crate::compared::{ComparedRun, Comparison, Front, FrontMember, FrontProgress, MethodSummary};
use crate::error::{self, Error};
use crate::objects::{Generator, Genome, Model, Progress, Run};
use crate::scene::{Origin, Scene, overrides};

/// The generators of a module.
#[pyclass(frozen, name = "Catalog")]
struct Held(Arc<Catalog>);

/// Fills `module` with the generators `fill` adds, the classes, exceptions and functions.
///
/// # Errors
/// When `fill` fails (a name taken twice), raised as `GeneratorError` on import.
pub fn init(
    module: &Bound<'_, PyModule>,
    fill: impl FnOnce(&mut Catalog) -> Result<(), RegistryError>,
) -> PyResult<()> {
    let py = module.py();
    let mut catalog = Catalog::default();
    fill(&mut catalog).map_err(Error::from)?;
    module.add("_catalog", Held(Arc::new(catalog)))?;
    module.add("__version__", env!("CARGO_PKG_VERSION"))?;
    module.add_class::<ComparedRun>()?;
    module.add_class::<Comparison>()?;
    module.add_class::<Front>()?;
    module.add_class::<FrontMember>()?;
    module.add_class::<FrontProgress>()?;
    module.add_class::<Generator>()?;
    module.add_class::<Genome>()?;
    module.add_class::<MethodSummary>()?;
    module.add_class::<Model>()?;
    module.add_class::<Progress>()?;
    module.add_class::<Run>()?;
    module.add_class::<Scene>()?;
    module.add("ShapegenError", py.get_type::<error::ShapegenError>())?;
    module.add("SceneError", py.get_type::<error::SceneError>())?;
    module.add("GenomeError", py.get_type::<error::GenomeError>())?;
    module.add("SearchError", py.get_type::<error::SearchError>())?;
    module.add("GeneratorError", py.get_type::<error::GeneratorError>())?;
    module.add_function(wrap_pyfunction!(self::generators, module)?)?;
    module.add_function(wrap_pyfunction!(generator, module)?)?;
    module.add_function(wrap_pyfunction!(open_scene, module)?)?;
    module.add_function(wrap_pyfunction!(resume, module)?)?;
    module.add_function(wrap_pyfunction!(scene_from_toml, module)?)?;
    module.add_function(wrap_pyfunction!(volume_scene, module)?)?;
    module.add_function(wrap_pyfunction!(silhouette_scene, module)?)?;
    Ok(())
}

/// The module's generators.
fn catalog(module: &Bound<'_, PyModule>) -> PyResult<Arc<Catalog>> {
    Ok(Arc::clone(
        &module.getattr("_catalog")?.cast::<Held>()?.get().0,
    ))
}

/// The names of the generators this module knows.
#[pyfunction]
#[pyo3(pass_module)]
fn generators(module: &Bound<'_, PyModule>) -> PyResult<Vec<String>> {
    let catalog = catalog(module)?;
    Ok(catalog
        .registry()
        .entries()
        .iter()
        .map(|e| e.name.clone())
        .collect())
}

/// The generator named `name` (or whose grammar is `name`).
#[pyfunction]
#[pyo3(pass_module)]
fn generator(module: &Bound<'_, PyModule>, name: &str) -> PyResult<Generator> {
    let catalog = catalog(module)?;
    let (entry, erased) = catalog.find(name).map_err(Error::from)?;
    Ok(Generator {
        name: entry.name.clone(),
        grammar: entry.grammar,
        parts: entry.mesh_names,
        limits: entry.defaults.limits,
        meshes: entry.defaults.meshes.clone(),
        erased,
    })
}

/// Opens the scene file at `path` (paths in it are relative to its folder); the keyword
/// arguments override its `[optimizer]` as the tool's flags do, and `set` any key as
/// `--set` does.
#[pyfunction]
#[pyo3(pass_module, signature = (path, **settings))]
fn open_scene(
    module: &Bound<'_, PyModule>,
    path: PathBuf,
    settings: Option<&Bound<'_, PyDict>>,
) -> PyResult<Scene> {
    let overrides = overrides(settings)?;
    Scene::read(&catalog(module)?, Origin::File(path), overrides)
}

/// Goes on with the search saved in run folder `folder` (its `checkpoint.json`, written
/// by `Scene.run(checkpoint=...)` or by `shapegen run`) to its budget, saving there as
/// it goes; the keyword arguments override the settings it was started with, as the
/// tool's flags do with `--resume`.
#[pyfunction]
#[pyo3(pass_module, signature = (folder, *, threads = None, progress = None, backend = "auto", **settings))]
fn resume(
    module: &Bound<'_, PyModule>,
    folder: PathBuf,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
    backend: &str,
    settings: Option<&Bound<'_, PyDict>>,
) -> PyResult<Run> {
    let saved = crate::checkpoint::read(&folder)?;
    let scene = Scene::read(
        &catalog(module)?,
        Origin::File(saved.scene),
        saved.overrides,
    )?;
    scene.run(
        module.py(),
        threads,
        progress,
        backend,
        Some(folder),
        true,
        settings,
    )
}

/// The scene written in `text` (a scene file's TOML), read as if from `path` (paths in
/// it are relative to its folder; `scene.toml` in the working folder by default).
/// `meshes` maps names to `(vertices, faces)` arrays and `images` names to image arrays:
/// a `[[volume.target]] mesh` or `[[silhouette.target]] image` that names one takes it
/// instead of a file.
#[pyfunction]
#[pyo3(pass_module, signature = (text, *, path = None, meshes = None, images = None))]
fn scene_from_toml(
    module: &Bound<'_, PyModule>,
    text: String,
    path: Option<PathBuf>,
    meshes: Option<&Bound<'_, PyDict>>,
    images: Option<&Bound<'_, PyDict>>,
) -> PyResult<Scene> {
    let mut sources = Sources::new();
    for (name, value) in meshes.into_iter().flat_map(|d| d.iter()) {
        let name: String = name.extract()?;
        let (vertices, faces): (Bound<'_, PyAny>, Bound<'_, PyAny>) =
            value.extract().map_err(|_| {
                Error::Value(format!("meshes[{name:?}] must be a pair (vertices, faces)"))
            })?;
        let mesh = arrays::mesh(&name, &vertices, &faces)?;
        sources = sources.mesh(name, mesh);
    }
    for (name, value) in images.into_iter().flat_map(|d| d.iter()) {
        let name: String = name.extract()?;
        let image = arrays::image(&name, &value)?;
        sources = sources.image(name, image);
    }
    let origin = Origin::Text {
        text,
        path: path.unwrap_or_else(|| PathBuf::from("scene.toml")),
        sources,
    };
    Scene::read(&catalog(module)?, origin, Default::default())
}

/// `extra` merged into `table`: tables key by key, other values replaced.
fn merge(table: &mut toml::Table, extra: toml::Table) {
    for (key, value) in extra {
        match (table.get_mut(&key), value) {
            (Some(toml::Value::Table(inner)), toml::Value::Table(more)) => merge(inner, more),
            (_, value) => {
                table.insert(key, value);
            }
        }
    }
}

/// The scene of `generator` with `goal` (its `[volume]` or `[silhouette]` table) and
/// `settings` merged in, the generator's own limits where they give none, its targets
/// from `sources`.
fn build(
    module: &Bound<'_, PyModule>,
    generator: &str,
    goal: (&str, toml::Table),
    settings: Option<&Bound<'_, PyDict>>,
    sources: Sources,
) -> PyResult<Scene> {
    let catalog = catalog(module)?;
    let limits = catalog
        .find(generator)
        .map_err(Error::from)?
        .0
        .defaults
        .limits;
    let mut table = toml::Table::new();
    table.insert("generator".into(), generator.into());
    let mut written = toml::Table::new();
    written.insert("min_len".into(), i64::from(limits.min_len).into());
    written.insert("max_len".into(), i64::from(limits.max_len).into());
    written.insert("max_depth".into(), i64::from(limits.max_depth).into());
    table.insert("limits".into(), toml::Value::Table(written));
    table.insert(goal.0.into(), toml::Value::Table(goal.1));
    if let Some(settings) = settings {
        merge(&mut table, arrays::toml_table("", settings)?);
    }
    let text = toml::to_string(&table)
        .map_err(|err| Error::Value(format!("the scene cannot be written as TOML: {err}")))?;
    let origin = Origin::Text {
        text,
        path: PathBuf::from("scene.toml"),
        sources,
    };
    Scene::read(&catalog, origin, Default::default())
}

/// A scene whose goal is to fill the mesh of `vertices` (N x 3) and `faces` (M x 3) with
/// `generator`'s models: a `[volume]` over the mesh's bounding box grown by `margin` of
/// its size on each side, in cubic voxels, `resolution` along its longest side. `target`
/// adds keys to the `[[volume.target]]` table (`inside`, `outside`, `fill = "winding"`
/// for an open mesh), `settings` to the scene (`{"optimizer": {"method": "ga"}}`,
/// `{"fitness": {"form": "iou"}}`, `{"limits": {...}}`; the generator's own limits
/// otherwise). The mesh is used where it is:
/// place it where the generator builds.
#[pyfunction]
#[pyo3(pass_module, signature = (generator, vertices, faces, *, resolution = 64, margin = 0.05, target = None, settings = None))]
#[allow(clippy::too_many_arguments)]
fn volume_scene(
    module: &Bound<'_, PyModule>,
    generator: String,
    vertices: &Bound<'_, PyAny>,
    faces: &Bound<'_, PyAny>,
    resolution: u32,
    margin: f64,
    target: Option<&Bound<'_, PyDict>>,
    settings: Option<&Bound<'_, PyDict>>,
) -> PyResult<Scene> {
    let mesh = arrays::mesh("target", vertices, faces)?;
    if resolution == 0 || !(margin.is_finite() && margin >= 0.0) {
        return Err(Error::Value(format!(
            "resolution ({resolution}) must be at least 1 voxel and margin ({margin}) a \
             number >= 0"
        ))
        .into());
    }
    let (lo, hi) = mesh.bounds().expect("a validated mesh has triangles");
    let size = (hi - lo).as_dvec3();
    let longest = size.max_element().max(1e-6) * (1.0 + 2.0 * margin);
    let cell = longest / f64::from(resolution);
    let mut grid_min = Vec::new();
    let mut grid_max = Vec::new();
    let mut cells = Vec::new();
    for axis in 0..3 {
        let span = size[axis] * (1.0 + 2.0 * margin);
        let n = (span / cell).ceil().max(1.0);
        let centre = f64::from(lo[axis] + hi[axis]) / 2.0;
        grid_min.push(toml::Value::Float(centre - n * cell / 2.0));
        grid_max.push(toml::Value::Float(centre + n * cell / 2.0));
        cells.push(toml::Value::Integer(n as i64));
    }
    let mut grid = toml::Table::new();
    grid.insert("min".into(), toml::Value::Array(grid_min));
    grid.insert("max".into(), toml::Value::Array(grid_max));
    grid.insert("resolution".into(), toml::Value::Array(cells));
    let mut target_table = toml::Table::new();
    target_table.insert("mesh".into(), "target".into());
    if let Some(target) = target {
        merge(&mut target_table, arrays::toml_table("target", target)?);
    }
    let mut volume = toml::Table::new();
    volume.insert("grid".into(), toml::Value::Table(grid));
    volume.insert(
        "target".into(),
        toml::Value::Array(vec![toml::Value::Table(target_table)]),
    );
    let sources = Sources::new().mesh("target", mesh);
    build(module, &generator, ("volume", volume), settings, sources)
}

/// A scene whose goal is the silhouette `image` (an H x W array: grey levels, the
/// target black; booleans, the target `True`; or RGB/RGBA) seen through `camera`, a
/// dictionary as a scene's `camera` table (`{"phi", "theta", "radius", "lookat", "fov",
/// "near", "far", "width", "height"}`, or `{"view", "projection", "width", "height"}`,
/// the matrices as 4 x 4 nested lists), whose size must be the image's. `target` adds
/// keys to the `[[silhouette.target]]` table (`threshold`, `alpha`, `kind`), `settings`
/// to the scene.
#[pyfunction]
#[pyo3(pass_module, signature = (generator, image, camera, *, target = None, settings = None))]
fn silhouette_scene(
    module: &Bound<'_, PyModule>,
    generator: String,
    image: &Bound<'_, PyAny>,
    camera: &Bound<'_, PyDict>,
    target: Option<&Bound<'_, PyDict>>,
    settings: Option<&Bound<'_, PyDict>>,
) -> PyResult<Scene> {
    let image = arrays::image("image", image)?;
    let mut target_table = toml::Table::new();
    target_table.insert("image".into(), "target".into());
    target_table.insert(
        "camera".into(),
        toml::Value::Table(arrays::toml_table("camera", camera)?),
    );
    if let Some(target) = target {
        merge(&mut target_table, arrays::toml_table("target", target)?);
    }
    let mut silhouette = toml::Table::new();
    silhouette.insert(
        "target".into(),
        toml::Value::Array(vec![toml::Value::Table(target_table)]),
    );
    let sources = Sources::new().image("target", image);
    build(
        module,
        &generator,
        ("silhouette", silhouette),
        settings,
        sources,
    )
}
