//! The one place that names the float width and the linear-algebra types.
//!
//! Every other module uses these aliases, so the engine's precision is set here.
//! Units are SI throughout the core: m, kg, s, N, rad.

/// The engine's scalar: 64-bit IEEE float.
pub type Real = f64;
/// A 3-vector (a direction, a velocity, an impulse ...).
pub type Vector = nalgebra::Vector3<Real>;
/// A 3-D point.
pub type Point = nalgebra::Point3<Real>;
/// A 3x3 matrix (an inertia tensor, a rotation matrix, the collision matrix K).
pub type Matrix = nalgebra::Matrix3<Real>;
/// A unit quaternion rotating body-frame vectors into the world frame.
pub type Rotation = nalgebra::UnitQuaternion<Real>;
/// A rigid transform body -> world (rotation, then the CG translation).
pub type Isometry = nalgebra::Isometry3<Real>;
/// An axis-aligned bounding box (parry's).
pub type Aabb = parry3d_f64::bounding_volume::Aabb;

/// The skew-symmetric matrix `[r]x` such that `[r]x v = r x v`.
#[inline]
pub fn cross_matrix(r: &Vector) -> Matrix {
    r.cross_matrix()
}

/// True when every component of `v` is finite.
#[inline]
pub fn is_finite_vector(v: &Vector) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// The signed per-axis gap from box 1 to box 2 (0 on axes where they overlap): every pair
/// of points, one in each box, is at least |g| apart along g / |g|.
#[inline]
pub fn box_gap(box1: &Aabb, box2: &Aabb) -> Vector {
    let mut g = Vector::zeros();
    for k in 0..3 {
        if box2.mins[k] > box1.maxs[k] {
            g[k] = box2.mins[k] - box1.maxs[k];
        } else if box1.mins[k] > box2.maxs[k] {
            g[k] = box2.maxs[k] - box1.mins[k];
        }
    }
    g
}

/// The world-frame AABB of a body-frame AABB moved by `pose`.
#[inline]
pub fn transformed_aabb(aabb: &Aabb, pose: &Isometry) -> Aabb {
    aabb.transform_by(pose)
}

/// A rigid map (rotation matrix, its element-wise absolute value, translation) built once
/// from an isometry, for transforming many points and boxes: a matrix product instead of a
/// quaternion rotation per point, and a box's extents through |R| (as parry's
/// `Aabb::transform_by`, without rebuilding the matrix every call).
#[derive(Clone, Copy, Debug)]
pub struct RigidMap {
    rot: Matrix,
    abs_rot: Matrix,
    trans: Vector,
}

impl RigidMap {
    /// The map of `iso`.
    #[inline]
    pub fn new(iso: &Isometry) -> RigidMap {
        let rot = iso.rotation.to_rotation_matrix().into_inner();
        RigidMap {
            rot,
            abs_rot: rot.abs(),
            trans: iso.translation.vector,
        }
    }

    /// The image of a point.
    #[inline]
    pub fn point(&self, p: &Point) -> Point {
        Point::from(self.rot * p.coords + self.trans)
    }

    /// The axis-aligned box holding the image of a box.
    #[inline]
    pub fn aabb(&self, b: &Aabb) -> Aabb {
        let center = self.rot * b.center().coords + self.trans;
        let half = self.abs_rot * b.half_extents();
        Aabb::new(Point::from(center - half), Point::from(center + half))
    }
}
