//! numpy and Python values <-> core types. Shape and type mistakes become typed errors.

use core::math::{Isometry, Matrix, Point, Rotation, Vector};
use crashsim_core as core;
use numpy::ndarray::{Array1, Array2};
use numpy::{AllowTypeChange, PyArrayLike1, PyArrayLike2};
use pyo3::prelude::*;

use crate::errors;

/// A (3,) float array-like.
pub fn vector3(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Vector> {
    let a: PyArrayLike1<'_, f64, AllowTypeChange> = obj
        .extract()
        .map_err(|_| errors::parameter(format!("{name} must be a sequence of 3 numbers")))?;
    let a = a.as_array();
    if a.len() != 3 {
        return Err(errors::parameter(format!(
            "{name} must have 3 components, got {}",
            a.len()
        )));
    }
    let v = Vector::new(a[0], a[1], a[2]);
    core::error::require_finite_vector(name, &v).map_err(crate::errors::to_py)?;
    Ok(v)
}

/// A (3, 3) float array-like.
pub fn matrix3(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Matrix> {
    let a: PyArrayLike2<'_, f64, AllowTypeChange> = obj
        .extract()
        .map_err(|_| errors::parameter(format!("{name} must be a 3x3 array of numbers")))?;
    let a = a.as_array();
    if a.shape() != [3, 3] {
        return Err(errors::parameter(format!(
            "{name} must be 3x3, got shape {:?}",
            a.shape()
        )));
    }
    Ok(Matrix::from_fn(|i, j| a[[i, j]]))
}

/// A (w, x, y, z) quaternion array-like, normalized. Zero or non-finite is an error.
pub fn rotation(obj: &Bound<'_, PyAny>) -> PyResult<Rotation> {
    let a: PyArrayLike1<'_, f64, AllowTypeChange> = obj.extract().map_err(|_| {
        errors::parameter("orientation must be a quaternion (w, x, y, z) of 4 numbers".into())
    })?;
    let a = a.as_array();
    if a.len() != 4 {
        return Err(errors::parameter(format!(
            "orientation must be a quaternion (w, x, y, z), got {} numbers",
            a.len()
        )));
    }
    let q = nalgebra::Quaternion::new(a[0], a[1], a[2], a[3]);
    let norm = q.norm();
    if !norm.is_finite() || norm == 0.0 {
        return Err(errors::parameter(
            "orientation must be a finite, non-zero quaternion (w, x, y, z)".into(),
        ));
    }
    Ok(Rotation::new_normalize(q))
}

/// A pose from a CG position and a quaternion.
pub fn pose(position: &Bound<'_, PyAny>, orientation: &Bound<'_, PyAny>) -> PyResult<Isometry> {
    let p = vector3(position, "position")?;
    Ok(Isometry::from_parts(p.into(), rotation(orientation)?))
}

/// (n, 3) float vertices.
pub fn vertices(obj: &Bound<'_, PyAny>) -> PyResult<Vec<Point>> {
    let a: PyArrayLike2<'_, f64, AllowTypeChange> = obj
        .extract()
        .map_err(|_| errors::mesh("vertices must be an (n, 3) array of numbers".into()))?;
    let a = a.as_array();
    if a.ncols() != 3 {
        return Err(errors::mesh(format!(
            "vertices must have shape (n, 3), got {:?}",
            a.shape()
        )));
    }
    Ok(a.rows()
        .into_iter()
        .map(|r| Point::new(r[0], r[1], r[2]))
        .collect())
}

/// (m, 3) integer triangles.
pub fn triangles(obj: &Bound<'_, PyAny>) -> PyResult<Vec<[u32; 3]>> {
    let a: PyArrayLike2<'_, i64, AllowTypeChange> = obj
        .extract()
        .map_err(|_| errors::mesh("triangles must be an (m, 3) array of vertex indices".into()))?;
    let a = a.as_array();
    if a.ncols() != 3 {
        return Err(errors::mesh(format!(
            "triangles must have shape (m, 3), got {:?}",
            a.shape()
        )));
    }
    let mut out = Vec::with_capacity(a.nrows());
    for (i, r) in a.rows().into_iter().enumerate() {
        let mut t = [0u32; 3];
        for k in 0..3 {
            t[k] = u32::try_from(r[k]).map_err(|_| {
                errors::mesh(format!("triangle {i} has an invalid vertex index {}", r[k]))
            })?;
        }
        out.push(t);
    }
    Ok(out)
}

/// Points as an (n, 3) array.
pub fn points_to_array(points: &[Point]) -> Array2<f64> {
    Array2::from_shape_fn((points.len(), 3), |(i, k)| points[i][k])
}

/// A vector as a (3,) array.
pub fn vector_to_array(v: &Vector) -> Array1<f64> {
    Array1::from_iter(v.iter().copied())
}

/// The depth of penetration from a time in s, "auto", or None (the default).
fn depth_of_penetration(value: Option<&Bound<'_, PyAny>>) -> PyResult<core::DepthOfPenetration> {
    let Some(value) = value.filter(|v| !v.is_none()) else {
        return Ok(core::ContactParams::default().depth_of_penetration);
    };
    if let Ok(text) = value.extract::<String>() {
        return if text == "auto" {
            Ok(core::DepthOfPenetration::Auto)
        } else {
            Err(errors::parameter(format!(
                "depth_of_penetration = {text:?} is unknown: give a time in s or \"auto\""
            )))
        };
    }
    let seconds = value.extract::<f64>().map_err(|_| {
        errors::parameter("depth_of_penetration must be a time in s (a number) or \"auto\"".into())
    })?;
    Ok(core::DepthOfPenetration::Fixed(seconds))
}

/// Contact parameters from the keyword arguments of World.set_contact.
#[allow(clippy::too_many_arguments)]
pub fn contact_params(
    depth_of_penetration_in: Option<&Bound<'_, PyAny>>,
    restitution: f64,
    friction: f64,
    restitution_mode: &str,
    centroid: &str,
    centroid_point: Option<&Bound<'_, PyAny>>,
    centroid_body: Option<usize>,
    normal: &str,
    normal_vector: Option<&Bound<'_, PyAny>>,
    pitch: f64,
) -> PyResult<core::ContactParams> {
    let restitution_mode = match restitution_mode {
        "total" => core::RestitutionMode::Total,
        "normal" => core::RestitutionMode::Normal,
        other => {
            return Err(errors::parameter(format!(
                "restitution_mode = {other:?} is unknown: use \"total\" (Kudlich-Slibar) or \"normal\" (Newton/Brach)"
            )))
        }
    };
    let point = |name: &str| -> PyResult<Point> {
        let obj = centroid_point.ok_or_else(|| {
            errors::parameter(format!(
                "centroid = {name:?} needs centroid_point (x, y, z) in m"
            ))
        })?;
        Ok(vector3(obj, "centroid_point")?.into())
    };
    let centroid = match centroid {
        "auto" => core::CentroidMode::Auto,
        "stiffness" => core::CentroidMode::Stiffness,
        "world" => core::CentroidMode::World(point("world")?),
        "body" => core::CentroidMode::Body {
            body: centroid_body.ok_or_else(|| {
                errors::parameter("centroid = \"body\" needs centroid_body (a body index)".into())
            })?,
            point: point("body")?,
        },
        other => {
            return Err(errors::parameter(format!(
            "centroid = {other:?} is unknown: use \"auto\", \"stiffness\", \"world\" or \"body\""
        )))
        }
    };
    let normal = match normal {
        "horizontal" => core::NormalMode::Horizontal { pitch },
        "volume" => core::NormalMode::Volume,
        "vector" => core::NormalMode::Fixed(vector3(
            normal_vector.ok_or_else(|| {
                errors::parameter("normal = \"vector\" needs normal_vector (x, y, z)".into())
            })?,
            "normal_vector",
        )?),
        other => {
            return Err(errors::parameter(format!(
                "normal = {other:?} is unknown: use \"horizontal\", \"volume\" or \"vector\""
            )))
        }
    };
    Ok(core::ContactParams {
        depth_of_penetration: depth_of_penetration(depth_of_penetration_in)?,
        restitution,
        friction,
        restitution_mode,
        centroid,
        normal,
    })
}

/// The core's rules of a face's CRASH3 coefficients (FaceStiffness::new): A (N/m) finite
/// and >= 0, B (N/m^2) finite and > 0; ParameterError otherwise (crashsim's FaceStiffness
/// checks itself with them when made).
#[pyfunction]
pub fn check_face_stiffness(a: f64, b: f64) -> PyResult<()> {
    core::FaceStiffness::new(a, b)
        .map(|_| ())
        .map_err(errors::to_py)
}

/// A face's (A, B) pair (N/m, N/m^2) or None.
pub fn face_stiffness(
    value: Option<&Bound<'_, PyAny>>,
    face: &str,
) -> PyResult<Option<core::FaceStiffness>> {
    let Some(value) = value.filter(|v| !v.is_none()) else {
        return Ok(None);
    };
    let (a, b): (f64, f64) = value.extract().map_err(|_| {
        errors::parameter(format!(
            "the {face} stiffness must be a pair (A, B) of numbers in N/m and N/m^2"
        ))
    })?;
    core::FaceStiffness::new(a, b)
        .map(Some)
        .map_err(errors::to_py)
}
