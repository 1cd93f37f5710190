//! Inside tests of the overlap queries: the nudge that settles the side of a point on the
//! other surface, a vertex nudged by it, and a shell of one mesh inside the other.

use crate::math::{Aabb, Isometry, Point, Real, RigidMap};
use crate::shape::MeshShape;
use crate::triangle::{inward_nudge, PLANE_TOLERANCE};

/// True when a shell of `inner` lies inside `outer` (its representative vertex, nudged by
/// `nudge` m into a triangle of it and its solid, has a winding number above one half);
/// `pose_io` maps inner's frame into outer's.
pub(super) fn shell_inside(
    outer: &MeshShape,
    inner: &MeshShape,
    pose_io: &Isometry,
    nudge: Real,
) -> bool {
    let bounds = outer.aabb();
    inner.shells().iter().any(|s| {
        let p = nudged_vertex(inner, s.vertex, nudge);
        let p = pose_io * p;
        bounds.contains_local_point(&p) && outer.contains_point(&p)
    })
}

/// Vertex `vi` of `mesh` (own frame) nudged `nudge` m into a triangle at it and into the
/// solid ([`inward_nudge`]); the vertex itself when that triangle has no area.
pub(super) fn nudged_vertex(mesh: &MeshShape, vi: u32, nudge: Real) -> Point {
    let v = mesh.vertices()[vi as usize];
    let ti = mesh.vertex_triangle(vi);
    if ti == u32::MAX {
        return v;
    }
    inward_nudge(&mesh.triangle(ti), &v).map_or(v, |w| v + w * nudge)
}

/// How far (m) points lying on the other surface are nudged to settle their side: 2^8 times
/// the band within which the crossing tests count a vertex as on a plane
/// ([`PLANE_TOLERANCE`] of the largest coordinate either mesh has in either body frame), so
/// a nudged point is clear of the band, yet close enough to be on the side the crossing
/// tests put it (a few 1e-10 m for vehicles; the winding number is exact that near a face).
pub(super) fn nudge_length(s1: &MeshShape, s2: &MeshShape, pose12: &Isometry) -> Real {
    let magnitude = |b: &Aabb| b.mins.coords.amax().max(b.maxs.coords.amax());
    let to1 = RigidMap::new(pose12);
    let to2 = RigidMap::new(&pose12.inverse());
    let scale = magnitude(s1.aabb())
        .max(magnitude(&to1.aabb(s2.aabb())))
        .max(magnitude(s2.aabb()))
        .max(magnitude(&to2.aabb(s1.aabb())));
    NUDGE_BANDS * PLANE_TOLERANCE * scale
}

/// The nudge length in plane bands (see [`nudge_length`]).
const NUDGE_BANDS: Real = 256.0;
