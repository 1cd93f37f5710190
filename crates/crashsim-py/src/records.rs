//! What a run returns, as typed records: one `Impact` per impulse exchange (world frame,
//! SI; per-body values are rows for body 1 and body 2). python/crashsim/result.py turns them
//! into its own Impact in one place.

use crashsim_core as core;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::prelude::*;

use crate::convert::{points_to_array, vector_to_array};

fn rows(v: [core::math::Vector; 2]) -> Array2<f64> {
    Array2::from_shape_fn((2, 3), |(i, k)| v[i][k])
}

/// One impulse exchange between body1 and body2 (the normal points from 1 into 2; the
/// impulse acts on 2, its negative on 1). Immutable.
#[pyclass(frozen, module = "crashsim._core")]
pub struct Impact {
    pub inner: core::Impact,
}

#[pymethods]
impl Impact {
    #[getter]
    fn body1(&self) -> usize {
        self.inner.body1
    }
    #[getter]
    fn body2(&self) -> usize {
        self.inner.body2
    }
    /// When the timer started (s): the first overlap or the closing again.
    #[getter]
    fn first_contact_time(&self) -> f64 {
        self.inner.first_contact_time
    }
    /// The exchange instant (s).
    #[getter]
    fn time(&self) -> f64 {
        self.inner.time
    }
    /// The depth of penetration used (s).
    #[getter]
    fn depth_of_penetration(&self) -> f64 {
        self.inner.depth_of_penetration
    }
    /// "fixed" or "auto".
    #[getter]
    fn depth_of_penetration_mode(&self) -> &'static str {
        match self.inner.depth_of_penetration_mode {
            core::DepthOfPenetration::Fixed(_) => "fixed",
            core::DepthOfPenetration::Auto => "auto",
        }
    }
    #[getter]
    fn secondary(&self) -> bool {
        self.inner.secondary
    }
    /// Impulse centroid (3,) m.
    #[getter]
    fn centroid<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vector_to_array(&self.inner.centroid.coords).into_pyarray(py)
    }
    /// Unit normal (3,) from body 1 into body 2.
    #[getter]
    fn normal<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vector_to_array(&self.inner.normal).into_pyarray(py)
    }
    /// Impulse on body 2 (3,) N s.
    #[getter]
    fn impulse<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vector_to_array(&self.inner.impulse).into_pyarray(py)
    }
    #[getter]
    fn sliding(&self) -> bool {
        self.inner.sliding
    }
    /// (2, 3) CG velocities before (m/s), rows body 1, body 2.
    #[getter]
    fn velocity_before<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        rows(self.inner.velocity_before).into_pyarray(py)
    }
    #[getter]
    fn velocity_after<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        rows(self.inner.velocity_after).into_pyarray(py)
    }
    #[getter]
    fn angular_velocity_before<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        rows(self.inner.angular_velocity_before).into_pyarray(py)
    }
    #[getter]
    fn angular_velocity_after<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        rows(self.inner.angular_velocity_after).into_pyarray(py)
    }
    /// (2, 3) velocity changes in each body's frame at the exchange (m/s; x forward, y left,
    /// z up): the EDR components.
    #[getter]
    fn delta_v_body<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        rows([self.inner.delta_v_body(0), self.inner.delta_v_body(1)]).into_pyarray(py)
    }
    /// Each body's SAE PDOF (deg in [0, 360)), None without a horizontal delta-V.
    #[getter]
    fn pdof_deg(&self) -> (Option<f64>, Option<f64>) {
        (self.inner.pdof_deg(0), self.inner.pdof_deg(1))
    }
    /// (2, 4) orientations (w, x, y, z) at the exchange.
    #[getter]
    fn orientation<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let q = self.inner.orientation;
        Array2::from_shape_fn((2, 4), |(i, k)| {
            let c = q[i].quaternion();
            [c.w, c.i, c.j, c.k][k]
        })
        .into_pyarray(py)
    }
    #[getter]
    fn relative_velocity_before<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vector_to_array(&self.inner.relative_velocity_before).into_pyarray(py)
    }
    #[getter]
    fn relative_velocity_after<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vector_to_array(&self.inner.relative_velocity_after).into_pyarray(py)
    }
    /// Kinetic energy dissipated (J).
    #[getter]
    fn energy_dissipated(&self) -> f64 {
        self.inner.energy_dissipated
    }
    /// The overlap region S (p, 3) m.
    #[getter]
    fn region_points<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        points_to_array(&self.inner.region_points).into_pyarray(py)
    }
    /// (3, 3) rows n, t, b.
    #[getter]
    fn contact_frame<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let f = &self.inner.contact_frame;
        Array2::from_shape_fn((3, 3), |(i, j)| f[(i, j)]).into_pyarray(py)
    }
    #[getter]
    fn region_min<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vector_to_array(&self.inner.region_min).into_pyarray(py)
    }
    #[getter]
    fn region_max<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vector_to_array(&self.inner.region_max).into_pyarray(py)
    }
    /// (face of body 1, face of body 2).
    #[getter]
    fn struck_faces(&self) -> (&'static str, &'static str) {
        let f = self.inner.struck_faces;
        (f[0].name(), f[1].name())
    }
    #[getter]
    fn overlap_width(&self) -> f64 {
        self.inner.overlap_width
    }
    /// (k1, k2) N/m, or None.
    #[getter]
    fn spring_rates(&self) -> Option<(f64, f64)> {
        self.inner.spring_rates.map(|[a, b]| (a, b))
    }
    /// (m1, m2) kg along n at the centroid.
    #[getter]
    fn effective_mass(&self) -> (f64, f64) {
        (self.inner.effective_mass[0], self.inner.effective_mass[1])
    }
    #[getter]
    fn notes(&self) -> Vec<String> {
        self.inner.notes.clone()
    }
    /// When the normal's volume normal was taken (s).
    #[getter]
    fn normal_time(&self) -> f64 {
        self.inner.normal_time
    }

    fn __repr__(&self) -> String {
        format!(
            "Impact(bodies=({}, {}), time={}, secondary={})",
            self.inner.body1, self.inner.body2, self.inner.time, self.inner.secondary
        )
    }
}
