//! Mass properties of a closed triangle mesh as a uniform solid of unit density.
//!
//! The divergence theorem turns the volume integrals into a sum over signed tetrahedra
//! (reference point, triangle): volume, first moment and second moment. On a closed,
//! outward-wound mesh the result is exact up to round-off; on an open mesh it is the solid
//! bounded by the mesh and the cones to the reference point, which depends on that point, so
//! callers should only trust it for closed meshes (the Python layer checks closure).

use crate::error::{Error, Result};
use crate::math::{Matrix, Point, Real, Vector};

/// Volume, centroid and inertia of a uniform solid of density 1 kg/m^3 (frame of the mesh).
#[derive(Clone, Debug, PartialEq)]
pub struct SolidProperties {
    /// Signed volume (m^3): positive for an outward-wound closed mesh.
    pub volume: Real,
    /// Centroid (m).
    pub centroid: Point,
    /// Inertia tensor about the centroid, mesh axes, for unit density (kg m^2 per kg/m^3).
    pub inertia: Matrix,
}

/// The mass properties of the solid bounded by the triangles (unit density).
///
/// Each triangle (a, b, c) and the reference point o span a tetrahedron of signed volume
/// det[a-o, b-o, c-o] / 6 whose second moment about o is
/// det/120 (sum_i d_i d_i^T + (sum_i d_i)(sum_i d_i)^T), d_i = vertex_i - o.
/// The reference point is the centre of the used vertices' box, which keeps round-off small.
///
/// Errors (`Error::Mesh`): no triangles, an index out of range, a non-finite vertex, a solid
/// without volume (zero up to the round-off of the sum: an open or flat mesh, whose centroid
/// is undefined), or a result that overflows.
pub fn solid_properties(vertices: &[Point], triangles: &[[u32; 3]]) -> Result<SolidProperties> {
    if triangles.is_empty() {
        return Err(Error::mesh("the mesh has no triangles: it bounds no solid"));
    }
    let n = vertices.len();
    if let Some(t) = triangles
        .iter()
        .find(|t| t.iter().any(|&k| k as usize >= n))
    {
        return Err(Error::mesh(format!(
            "triangle {t:?} refers to a vertex beyond the mesh's {n} vertices"
        )));
    }
    let first = vertices[triangles[0][0] as usize];
    let (mut lo, mut hi) = (first, first);
    for &k in triangles.iter().flatten() {
        let v = &vertices[k as usize];
        if !v.iter().all(|c| c.is_finite()) {
            return Err(Error::mesh(format!(
                "vertex {k} is not finite ({:?}): remove or repair NaN/inf vertices",
                v.coords.as_slice()
            )));
        }
        lo = lo.inf(v);
        hi = hi.sup(v);
    }
    let o = nalgebra::center(&lo, &hi);
    let mut six_volume = 0.0;
    let mut six_volume_abs = 0.0;
    let mut moment = Vector::zeros(); // sum det * (a + b + c), i.e. 24 x the first moment
    let mut second = Matrix::zeros(); // sum det * (...), i.e. 120 x the second moment
    for t in triangles {
        let a = vertices[t[0] as usize] - o;
        let b = vertices[t[1] as usize] - o;
        let c = vertices[t[2] as usize] - o;
        let det = a.dot(&b.cross(&c));
        let s = a + b + c;
        six_volume += det;
        six_volume_abs += det.abs();
        moment += s * det;
        second +=
            (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose()) * det;
    }
    // The sum's round-off is at most a few ulps of the sum of the magnitudes per term.
    let resolved = six_volume.abs() > 64.0 * Real::EPSILON * six_volume_abs;
    if !resolved {
        return Err(Error::mesh(format!(
            "the mesh encloses no volume ({} m^3 with round-off {:.3e} m^3): it is open or \
             flat, so its centroid and inertia are undefined; close it",
            six_volume / 6.0,
            64.0 * Real::EPSILON * six_volume_abs / 6.0
        )));
    }
    let volume = six_volume / 6.0;
    // First moment = moment / 24; centroid offset from o = moment / volume.
    let offset = moment / (24.0 * volume);
    // Second moment about o, then about the centroid (parallel axes on the covariance).
    let covariance_o = second / 120.0;
    let covariance_c = covariance_o - offset * offset.transpose() * volume;
    let inertia = Matrix::identity() * covariance_c.trace() - covariance_c;
    let props = SolidProperties {
        volume,
        centroid: o + offset,
        inertia: (inertia + inertia.transpose()) * 0.5,
    };
    if !(volume.is_finite()
        && props.centroid.iter().all(|c| c.is_finite())
        && props.inertia.iter().all(|c| c.is_finite()))
    {
        return Err(Error::mesh(format!(
            "the mass properties of the mesh overflow (volume {volume} m^3): its coordinates \
             are too large; give them in metres"
        )));
    }
    Ok(props)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::MeshShape;

    #[test]
    fn a_box_has_the_analytic_volume_centroid_and_inertia() {
        let (hx, hy, hz) = (2.25, 0.9, 0.7);
        let b = MeshShape::cuboid(Vector::new(1.0, -2.0, 3.0), Vector::new(hx, hy, hz));
        let p = solid_properties(b.vertices(), b.triangles()).unwrap();
        let (l, w, h) = (2.0 * hx, 2.0 * hy, 2.0 * hz);
        let v = l * w * h;
        assert!((p.volume - v).abs() < 1e-12 * v);
        assert!((p.centroid - Point::new(1.0, -2.0, 3.0)).norm() < 1e-12);
        let expected = Matrix::from_diagonal(&Vector::new(
            v / 12.0 * (w * w + h * h),
            v / 12.0 * (l * l + h * h),
            v / 12.0 * (l * l + w * w),
        ));
        assert!(
            (p.inertia - expected).norm() < 1e-12 * expected.norm(),
            "{}",
            p.inertia
        );
    }

    #[test]
    fn a_rotated_box_has_the_rotated_inertia() {
        let b = MeshShape::cuboid(Vector::zeros(), Vector::new(1.5, 0.5, 0.25));
        let rot = nalgebra::Rotation3::from_euler_angles(0.3, -0.7, 1.1);
        let moved: Vec<Point> = b.vertices().iter().map(|v| rot * v).collect();
        let p0 = solid_properties(b.vertices(), b.triangles()).unwrap();
        let p1 = solid_properties(&moved, b.triangles()).unwrap();
        let expected = rot.matrix() * p0.inertia * rot.matrix().transpose();
        assert!((p1.inertia - expected).norm() < 1e-12 * expected.norm());
        assert!((p1.volume - p0.volume).abs() < 1e-12 * p0.volume);
    }
}
