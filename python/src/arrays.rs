//! Values between Python and Rust: numpy arrays of vertices, faces and images in, numpy
//! arrays out, and Python dictionaries as TOML tables of a scene.

use image::{DynamicImage, GrayImage, RgbImage, RgbaImage};
use numpy::ndarray::Array2;
use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use shapegen::Mesh;

use crate::error::Error;

/// `value` as a numpy array of `dtype` (`numpy.asarray`), for any array-like.
fn as_array<'py>(value: &Bound<'py, PyAny>, dtype: &str) -> PyResult<Bound<'py, PyAny>> {
    let numpy = value.py().import("numpy")?;
    numpy.call_method1("asarray", (value, numpy.getattr(dtype)?))
}

/// A triangle mesh from `vertices` (N x 3 numbers) and `faces` (M x 3 vertex indices),
/// named `name` in errors; its normals are computed as for a mesh file's.
pub fn mesh(name: &str, vertices: &Bound<'_, PyAny>, faces: &Bound<'_, PyAny>) -> PyResult<Mesh> {
    let vertices: PyReadonlyArray2<'_, f32> = as_array(vertices, "float32")
        .and_then(|a| Ok(a.cast_into::<PyArray2<f32>>()?.readonly()))
        .map_err(|_| {
            Error::Value(format!(
                "{name}: vertices must be an N x 3 array of numbers"
            ))
        })?;
    let faces: PyReadonlyArray2<'_, i64> = as_array(faces, "int64")
        .and_then(|a| Ok(a.cast_into::<PyArray2<i64>>()?.readonly()))
        .map_err(|_| {
            Error::Value(format!(
                "{name}: faces must be an M x 3 array of vertex indices"
            ))
        })?;
    let (vertices, faces) = (vertices.as_array(), faces.as_array());
    if vertices.ncols() != 3 {
        return Err(Error::Value(format!(
            "{name}: vertices must be N x 3 (x, y, z), not {:?}",
            vertices.shape()
        ))
        .into());
    }
    if faces.ncols() != 3 {
        return Err(Error::Value(format!(
            "{name}: faces must be M x 3 (one triangle per row; split quads and polygons), \
             not {:?}",
            faces.shape()
        ))
        .into());
    }
    let n = vertices.nrows();
    let mut indices = Vec::with_capacity(faces.len());
    for (row, face) in faces.rows().into_iter().enumerate() {
        for &i in face {
            if i < 0 || i as usize >= n {
                return Err(Error::Value(format!(
                    "{name}: face {row} names vertex {i}, but the vertices are numbered 0 \
                     to {}",
                    n as i64 - 1
                ))
                .into());
            }
            indices.push(i as u32);
        }
    }
    let positions = vertices
        .rows()
        .into_iter()
        .map(|r| glam::vec3(r[0], r[1], r[2]))
        .collect();
    let mut mesh = Mesh {
        normals: vec![glam::Vec3::ZERO; n],
        positions,
        indices,
    };
    mesh.validate(name).map_err(Error::scene)?;
    mesh.compute_normals(Mesh::DEFAULT_CREASE_ANGLE);
    Ok(mesh)
}

/// An image from a numpy array: H x W grey levels, or H x W x 3 (RGB) or x 4 (RGBA), of
/// `uint8`; or H x W booleans, `True` where the target is (black), `False` elsewhere
/// (white).
pub fn image(name: &str, value: &Bound<'_, PyAny>) -> PyResult<DynamicImage> {
    let numpy = value.py().import("numpy")?;
    let array = numpy.call_method1("asarray", (value,))?;
    let dtype: String = array.getattr("dtype")?.getattr("name")?.extract()?;
    let shape: Vec<usize> = array.getattr("shape")?.extract()?;
    let bad = || {
        Error::Value(format!(
            "{name}: an image must be an H x W array of uint8 grey levels or booleans (True \
             on the target), or H x W x 3 or H x W x 4 of uint8 (RGB, RGBA); this one is \
             {shape:?} of {dtype}"
        ))
    };
    let bytes = match dtype.as_str() {
        "uint8" => array,
        "bool" if shape.len() == 2 => numpy.call_method1("where", (array, 0u8, 255u8))?,
        _ => return Err(bad().into()),
    };
    let bytes: Vec<u8> = numpy
        .call_method1("ascontiguousarray", (bytes, numpy.getattr("uint8")?))?
        .call_method0("tobytes")?
        .extract()?;
    let (h, w) = match shape[..] {
        [h, w] | [h, w, _] => (u32::try_from(h).ok(), u32::try_from(w).ok()),
        _ => return Err(bad().into()),
    };
    let (Some(h), Some(w)) = (h, w) else {
        return Err(bad().into());
    };
    let image = match shape.get(2) {
        None => GrayImage::from_raw(w, h, bytes).map(DynamicImage::from),
        Some(3) => RgbImage::from_raw(w, h, bytes).map(DynamicImage::from),
        Some(4) => RgbaImage::from_raw(w, h, bytes).map(DynamicImage::from),
        Some(_) => None,
    };
    Ok(image.ok_or_else(bad)?)
}

/// Rows of three as an N x 3 numpy array.
pub fn rows<'py, T: numpy::Element + Copy>(
    py: Python<'py>,
    rows: &[[T; 3]],
) -> Bound<'py, PyArray2<T>> {
    let flat: Vec<T> = rows.iter().flatten().copied().collect();
    let array = Array2::from_shape_vec((rows.len(), 3), flat).expect("rows of three");
    PyArray2::from_owned_array(py, array)
}

/// Rows of `columns` values each as an N x `columns` numpy array.
pub fn matrix<'py>(
    py: Python<'py>,
    rows: &[&[f64]],
    columns: usize,
) -> Result<Bound<'py, PyArray2<f64>>, Error> {
    let flat: Vec<f64> = rows.iter().flat_map(|r| r.iter()).copied().collect();
    let array = Array2::from_shape_vec((rows.len(), columns), flat)
        .map_err(|err| Error::Value(format!("rows of unequal lengths: {err}")))?;
    Ok(PyArray2::from_owned_array(py, array))
}

/// A vector as a numpy array.
pub fn vector<'py, T: numpy::Element>(py: Python<'py>, values: Vec<T>) -> Bound<'py, PyArray1<T>> {
    PyArray1::from_vec(py, values)
}

/// A Python value (numbers, strings, booleans, lists, tuples, dictionaries, numpy
/// arrays) as a TOML value; `key` names it in errors.
pub fn toml_value(key: &str, value: &Bound<'_, PyAny>) -> PyResult<toml::Value> {
    if value.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(value.extract()?));
    }
    if value.is_instance_of::<PyInt>() {
        return Ok(toml::Value::Integer(value.extract()?));
    }
    if value.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(value.extract()?));
    }
    if value.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(value.extract()?));
    }
    if let Ok(dict) = value.cast::<PyDict>() {
        return toml_table(key, dict).map(toml::Value::Table);
    }
    if value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() {
        let items = value
            .try_iter()?
            .enumerate()
            .map(|(i, item)| toml_value(&format!("{key}[{i}]"), &item?))
            .collect::<PyResult<Vec<_>>>()?;
        return Ok(toml::Value::Array(items));
    }
    if value.hasattr("tolist")? {
        // numpy arrays and numpy scalars
        return toml_value(key, &value.call_method0("tolist")?);
    }
    Err(Error::Value(format!(
        "{key}: {} cannot be a scene value; use numbers, strings, booleans, lists and \
         dictionaries",
        value.get_type().name()?
    ))
    .into())
}

/// A Python dictionary of string keys as a TOML table; `key` names it in errors.
pub fn toml_table(key: &str, dict: &Bound<'_, PyDict>) -> PyResult<toml::Table> {
    let mut table = toml::Table::new();
    for (k, v) in dict.iter() {
        let Ok(k) = k.extract::<String>() else {
            return Err(Error::Value(format!("{key}: the keys must be strings")).into());
        };
        let path = if key.is_empty() {
            k.clone()
        } else {
            format!("{key}.{k}")
        };
        table.insert(k, toml_value(&path, &v)?);
    }
    Ok(table)
}
