//! What a run returns: impulse exchanges, the contact log and the sampled states.

use crate::body::BodyState;
use crate::contact::DepthOfPenetration;
use crate::math::{Matrix, Point, Real, Rotation, Vector};
use crate::motion::WheelSample;
use crate::stiffness::Face;

/// What happened to a pair, besides impulse exchanges (serialized as its snake-case name
/// under "kind", a skipped exchange's reason under "reason").
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize),
    serde(tag = "kind", content = "reason", rename_all = "snake_case")
)]
pub enum ContactEventKind {
    /// The meshes first overlap; a timer starts.
    FirstOverlap,
    /// The relative velocity at the centroid turned closing while engaged; a timer starts.
    ClosingAgain,
    /// The meshes no longer overlap.
    Separation,
    /// The timer expired but no impulse was exchanged (the reason says why).
    NoExchange(String),
}

/// One entry of the contact log (serialized field by field as [`Impact`] is, its kind's
/// "kind" and "reason" beside the others).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct ContactEvent {
    /// World index of body 1 of the pair.
    pub body1: usize,
    /// World index of body 2.
    pub body2: usize,
    /// When (s).
    pub time: Real,
    /// What.
    #[cfg_attr(feature = "serde", serde(flatten))]
    pub kind: ContactEventKind,
}

/// One impulse exchange, world frame, SI.
///
/// With the `serde` feature it serializes field by field, each under its own name (vectors and
/// points as [x, y, z], per-body pairs as [body 1, body 2], the contact frame as its rows, the
/// faces and the dt_p mode by name): the binding hands that on to Python as it is
/// (python/crashsim/records.py reads it), so a new field needs no binding code.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Impact {
    /// World index of body 1 (the normal points from it into body 2).
    pub body1: usize,
    /// World index of body 2.
    pub body2: usize,
    /// When the timer started (s): the first overlap, or the closing-again instant.
    pub first_contact_time: Real,
    /// The exchange instant (s).
    pub time: Real,
    /// The depth-of-penetration time used (s): exchange time minus timer start.
    pub depth_of_penetration: Real,
    /// How it was chosen: the pair's fixed value, or automatic (sqrt(m'/k')); by name,
    /// "fixed" or "auto".
    #[cfg_attr(feature = "serde", serde(serialize_with = "serialize::mode_name"))]
    pub depth_of_penetration_mode: DepthOfPenetration,
    /// True for an exchange after the first one of an engagement.
    pub secondary: bool,
    /// Impulse centroid P (m).
    pub centroid: Point,
    /// Unit normal from body 1 into body 2.
    pub normal: Vector,
    /// Impulse on body 2 (N s); body 1 receives its negative.
    pub impulse: Vector,
    /// True for a sliding impact.
    pub sliding: bool,
    /// CG velocities of bodies 1 and 2 before and after (m/s).
    pub velocity_before: [Vector; 2],
    /// See `velocity_before`.
    pub velocity_after: [Vector; 2],
    /// Angular velocities before and after (rad/s).
    pub angular_velocity_before: [Vector; 2],
    /// See `angular_velocity_before`.
    pub angular_velocity_after: [Vector; 2],
    /// u at P before: body 1's point velocity minus body 2's (m/s).
    pub relative_velocity_before: Vector,
    /// u at P after (m/s).
    pub relative_velocity_after: Vector,
    /// Kinetic energy lost (J).
    pub energy_dissipated: Real,
    /// The overlap region S (m).
    pub region_points: Vec<Point>,
    /// Contact frame: rows n, t (horizontal tangent), b = n x t.
    #[cfg_attr(feature = "serde", serde(serialize_with = "serialize::rows"))]
    pub contact_frame: Matrix,
    /// Extent of S in the contact frame: minimum (m).
    pub region_min: Vector,
    /// Extent of S in the contact frame: maximum (m).
    pub region_max: Vector,
    /// The struck face of body 1 (facing +n) and of body 2 (facing -n).
    pub struck_faces: [Face; 2],
    /// Overlap width W: extent of S along the contact tangent t (m).
    pub overlap_width: Real,
    /// Spring rates k_i = B_i W of the struck faces (N/m), when both have stiffness data.
    pub spring_rates: Option<[Real; 2]>,
    /// Effective masses of bodies 1 and 2 along n at the centroid (kg).
    pub effective_mass: [Real; 2],
    /// When the overlap's volume normal behind `normal` was taken (s): early in the timer
    /// for a first exchange (overlap [`NORMAL_DEPTH`](super::NORMAL_DEPTH) deep, deeper for a
    /// narrow overlap until it covers [`NORMAL_FOOTPRINT`](crate::contact::NORMAL_FOOTPRINT),
    /// shallower for a thin part cut through, which `notes` record), else the exchange.
    pub normal_time: Real,
    /// Remarks on this exchange (e.g. an automatic dt_p outside the typical 10-60 ms).
    pub notes: Vec<String>,
    /// Each body's velocity change in its own frame at the exchange (m/s; ISO 8855: x
    /// forward, y left, z up; an event data recorder's lateral, +right, is -y): see
    /// [`delta_v_in_body`]. The report's EDR components and a batch's columns read it.
    pub delta_v_body: [Vector; 2],
    /// Each body's principal direction of force (SAE J224, deg in [0, 360)) from
    /// `delta_v_body`: see [`pdof_deg`].
    pub pdof_deg: [Option<Real>; 2],
}

impl Impact {
    /// Body `k`'s (0: body 1, 1: body 2) CG velocity change, world (m/s).
    pub fn delta_v(&self, k: usize) -> Vector {
        self.velocity_after[k] - self.velocity_before[k]
    }
}

/// A body's velocity change `delta_v` (world, m/s) in its frame of orientation `q` (body ->
/// world; an impulse does not change it): the one computation of [`Impact::delta_v_body`].
pub fn delta_v_in_body(q: &Rotation, delta_v: &Vector) -> Vector {
    q.inverse_transform_vector(delta_v)
}

/// How [`Impact`] serializes the values that are not plain numbers or vectors.
#[cfg(feature = "serde")]
mod serialize {
    use super::{DepthOfPenetration, Matrix};

    /// The dt_p mode by name: "fixed" or "auto".
    pub fn mode_name<S: serde::Serializer>(
        mode: &DepthOfPenetration,
        s: S,
    ) -> Result<S::Ok, S::Error> {
        s.serialize_str(match mode {
            DepthOfPenetration::Fixed(_) => "fixed",
            DepthOfPenetration::Auto => "auto",
        })
    }

    /// A 3x3 matrix as its three rows (nalgebra's own serialization is column-major).
    pub fn rows<S: serde::Serializer>(m: &Matrix, s: S) -> Result<S::Ok, S::Error> {
        use serde::Serialize;
        let row = |i: usize| [m[(i, 0)], m[(i, 1)], m[(i, 2)]];
        [row(0), row(1), row(2)].serialize(s)
    }
}

/// |v| as sqrt(x x + y y + z z) in that order (m/s for a velocity): the one definition of a
/// speed or a delta-V magnitude, so Python (plain float arithmetic, result.py `_magnitude`)
/// gives the same bits.
pub fn magnitude(v: &Vector) -> Real {
    (v.x * v.x + v.y * v.y + v.z * v.z).sqrt()
}

/// Degrees from radians, as Python's `math.degrees` (x * (180 / pi)).
pub fn degrees(rad: Real) -> Real {
    rad * (180.0 / std::f64::consts::PI)
}

/// Python's float `x % 360.0` (the result takes the divisor's sign; -0.0 becomes 0.0).
fn modulo_360(x: Real) -> Real {
    let r = x % 360.0;
    if r == 0.0 {
        0.0
    } else if r < 0.0 {
        r + 360.0
    } else {
        r
    }
}

/// The SAE principal direction of force (deg, in [0, 360)) from a delta-V in the ISO body
/// frame (m/s): the direction FROM which the force acts, in the body's x-y plane, clockwise
/// seen from above from straight ahead (0 ahead, 90 right, 180 behind, 270 left):
/// atan2(dv_y, -dv_x). None without a horizontal part (exactly zero, or below 1e-12 of
/// |delta-V|). Bit for bit the arithmetic of analysis/report.py's `pdof`.
pub fn pdof_deg(dv_body: &Vector) -> Option<Real> {
    let horizontal = dv_body.x.hypot(dv_body.y);
    if horizontal == 0.0 || horizontal <= 1e-12 * magnitude(dv_body) {
        return None;
    }
    let angle = modulo_360(degrees(dv_body.y.atan2(-dv_body.x)));
    Some(if angle >= 360.0 { 0.0 } else { angle })
}

/// Yaw of a body's x axis from world x (rad, counter-clockwise seen from above, in
/// (-pi, pi]): `atan2(R[1][0], R[0][0])` of the unit quaternion, in the arithmetic of
/// result.py's `_heading`.
pub fn heading(q: &Rotation) -> Real {
    let (w, x, y, z) = (q.w, q.i, q.j, q.k);
    (2.0 * (x * y + w * z)).atan2(1.0 - 2.0 * (y * y + z * z))
}

/// What a run returns: samples of every body's state and the logs.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RunOutput {
    /// Sample times (s): the start, every kept grid step end (see [`RunOptions`]), every first
    /// overlap, every exchange and the end.
    ///
    /// [`RunOptions`]: super::RunOptions
    pub times: Vec<Real>,
    /// Bodies per sample.
    pub body_count: usize,
    /// The interval between kept grid samples (s): a whole number of steps.
    pub record_interval: Real,
    /// The states, sample after sample: body i at `times[k]` is `states[k * body_count + i]`
    /// (after any exchange at that instant). One flat vector: no allocation per sample.
    pub states: Vec<BodyState>,
    /// Wheels per body that run on the ground (0 for the others), in body order.
    pub wheel_counts: Vec<usize>,
    /// The wheels, sample after sample: every body's wheels in body order (see
    /// `wheel_counts`), at the same samples as `states`.
    pub wheels: Vec<WheelSample>,
    /// Per body on the ground, when it came to rest (s: the start of the final stretch in
    /// which it stayed slow), or None when it was still moving at the end.
    pub rest: Vec<Option<Real>>,
    /// Impulse exchanges in time order.
    pub impacts: Vec<Impact>,
    /// First overlaps, separations, closings and skipped exchanges in time order.
    pub contacts: Vec<ContactEvent>,
    /// Joint limits hit, in time order.
    pub joint_events: Vec<super::JointEvent>,
    /// Joints per sample.
    pub joint_count: usize,
    /// The joints, sample after sample (each sample's `joint_count` in the order added), at
    /// the same samples as `states`.
    pub joints: Vec<crate::joint::JointSample>,
}

impl RunOutput {
    /// The states of every body at sample `k`.
    pub fn sample(&self, k: usize) -> &[BodyState] {
        &self.states[k * self.body_count..(k + 1) * self.body_count]
    }

    /// The wheels of every body at sample `k` (see `wheel_counts`).
    pub fn wheels_at(&self, k: usize) -> &[WheelSample] {
        let n: usize = self.wheel_counts.iter().sum();
        &self.wheels[k * n..(k + 1) * n]
    }

    /// The joints at sample `k`.
    pub fn joints_at(&self, k: usize) -> &[crate::joint::JointSample] {
        &self.joints[k * self.joint_count..(k + 1) * self.joint_count]
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.times.len()
    }

    /// True when nothing was recorded.
    pub fn is_empty(&self) -> bool {
        self.times.is_empty()
    }
}
