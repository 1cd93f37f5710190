//! Whether two posed meshes cross or overlap: the surfaces' crossing test, the overlap
//! test (a crossing or a shell inside the other) and its hinted form.

use super::inside::{nudge_length, shell_inside};
use super::traverse::{map_tri, mapped_leaf, traverse_pairs};
use super::QueryWorkspace;
use crate::math::{Aabb, Isometry, Real, RigidMap};
use crate::shape::MeshShape;
use crate::triangle::{triangle_triangle_contact, Tri, PLANE_TOLERANCE};
use parry3d_f64::bounding_volume::BoundingVolume;

/// True when the two posed surfaces cross: a triangle of one, nudged a hair into its own
/// solid and interior, is crossed by a triangle of the other (see
/// [`crate::triangle::triangle_triangle_contact`]). Surfaces that merely touch (faces
/// resting on each other, coplanar faces, an edge on a face from outside) do not intersect;
/// [`surface_distance`](super::surface_distance) is 0 for them. This is the test [`overlap_region`](super::overlap_region) takes its crossing
/// segments by, so the region is not empty whenever it holds.
pub fn surfaces_intersect(
    s1: &MeshShape,
    pose1: &Isometry,
    s2: &MeshShape,
    pose2: &Isometry,
    ws: &mut QueryWorkspace,
) -> bool {
    first_crossing(s1, pose1, s2, pose2, ws).is_some()
}

/// The first pair of triangles (of s1, of s2) whose surfaces cross that the traversal of
/// [`surfaces_intersect`] meets, or None.
fn first_crossing(
    s1: &MeshShape,
    pose1: &Isometry,
    s2: &MeshShape,
    pose2: &Isometry,
    ws: &mut QueryWorkspace,
) -> Option<(u32, u32)> {
    let pose12 = pose1.inv_mul(pose2);
    let map = RigidMap::new(&pose12);
    let mut found = None;
    traverse_pairs(s1, s2, &pose12, &mut ws.pairs, true, |a, b| {
        // b's triangles in 1's frame, mapped once per leaf pair (not once per triangle of a)
        let leaf2 = mapped_leaf(s2, b, &map);
        let box2 = box_of(leaf2.iter().flatten().map(|(_, t)| t));
        for &t1 in s1.bvh().leaf_primitives(a) {
            let tri1 = s1.triangle(t1);
            if boxes_apart(&box_of([&tri1]), &box2) {
                continue; // no triangle of b's leaf comes near this one
            }
            for &(t2, tri2) in leaf2.iter().flatten() {
                if triangle_triangle_contact(&tri1, &tri2).is_some_and(|c| c.is_crossing()) {
                    found = Some((t1, t2));
                    return true;
                }
            }
        }
        false
    });
    found
}

/// The box of triangles' vertices (m, their frame): from the vertices themselves, not a box
/// mapped from another frame.
#[inline]
pub(super) fn box_of<'a>(tris: impl IntoIterator<Item = &'a Tri>) -> Aabb {
    let mut b = Aabb::new_invalid();
    for t in tris {
        for p in t {
            b.take_point(*p);
        }
    }
    b
}

/// True when two boxes (one frame, m) are apart along an axis by more than the triangle
/// test's snapping band could bridge (4 of its [`PLANE_TOLERANCE`] at the coordinates'
/// scale): triangles inside them cannot cross, and [`triangle_triangle_contact`] is not
/// asked. (The band is only worked out for boxes apart at all: most pairs tested are not.)
#[inline]
pub(super) fn boxes_apart(a: &Aabb, b: &Aabb) -> bool {
    let gap = (0..3)
        .map(|k| Real::max(a.mins[k] - b.maxs[k], b.mins[k] - a.maxs[k]))
        .fold(Real::NEG_INFINITY, Real::max);
    if gap <= 0.0 {
        return false;
    }
    let scale = (0..3)
        .flat_map(|k| [a.mins[k], a.maxs[k], b.mins[k], b.maxs[k]])
        .fold(0.0, |m: Real, x| m.max(x.abs()));
    gap > 4.0 * PLANE_TOLERANCE * scale
}

/// [`shapes_overlap`] that first tries the pair of triangles `hint` (of s1, of s2): when they
/// still cross, the surfaces intersect and no traversal is needed. `hint` is left at a
/// crossing pair found (None when the surfaces do not cross). The answer is
/// [`shapes_overlap`]'s: a crossing pair is one whichever way it is found. An engaged pair
/// (meshes pushed into each other) keeps crossing at the same triangles from step to step:
/// two boxes' seed impact, 1 s at 1 ms, tested about 100 triangle pairs a step without it.
pub fn shapes_overlap_hinted(
    s1: &MeshShape,
    pose1: &Isometry,
    s2: &MeshShape,
    pose2: &Isometry,
    ws: &mut QueryWorkspace,
    hint: &mut Option<(u32, u32)>,
) -> bool {
    // The hinted pair first: where two triangles cross, the meshes' boxes meet.
    if let Some((t1, t2)) = *hint {
        let map = RigidMap::new(&pose1.inv_mul(pose2));
        let tri2 = map_tri(&s2.triangle(t2), &map);
        if triangle_triangle_contact(&s1.triangle(t1), &tri2).is_some_and(|c| c.is_crossing()) {
            return true;
        }
    }
    if !s1
        .aabb()
        .transform_by(pose1)
        .intersects(&s2.aabb().transform_by(pose2))
    {
        return false;
    }
    *hint = first_crossing(s1, pose1, s2, pose2, ws);
    if hint.is_some() {
        return true;
    }
    let pose12 = pose1.inv_mul(pose2);
    let nudge = nudge_length(s1, s2, &pose12);
    shell_inside(s1, s2, &pose12, nudge) || shell_inside(s2, s1, &pose12.inverse(), nudge)
}

/// True when the two posed meshes overlap: their surfaces cross ([`surfaces_intersect`]), or
/// a shell of one lies inside the other.
pub fn shapes_overlap(
    s1: &MeshShape,
    pose1: &Isometry,
    s2: &MeshShape,
    pose2: &Isometry,
    ws: &mut QueryWorkspace,
) -> bool {
    if !s1
        .aabb()
        .transform_by(pose1)
        .intersects(&s2.aabb().transform_by(pose2))
    {
        return false;
    }
    if surfaces_intersect(s1, pose1, s2, pose2, ws) {
        return true;
    }
    let pose12 = pose1.inv_mul(pose2);
    let nudge = nudge_length(s1, s2, &pose12);
    shell_inside(s1, s2, &pose12, nudge) || shell_inside(s2, s1, &pose12.inverse(), nudge)
}
