//! The overlap region S of two posed meshes (docs/model.md, "The overlap region"): the
//! crossing segments' ends, the vertices inside, the inside vector areas and the volume
//! normal.

use super::inside::nudge_length;
use super::intersect::{box_of, boxes_apart};
use super::surface_inside::{surface_inside, Crossing};
use super::traverse::{map_tri, mapped_leaf, traverse_pairs};
use crate::math::{Isometry, Point, RigidMap, Vector};
use crate::shape::MeshShape;
use crate::triangle::{triangle_triangle_contact, TriangleContact};

/// The overlap region of two posed meshes (world frame).
#[derive(Clone, Debug, Default)]
pub struct OverlapRegion {
    /// The set S: end points of all triangle-triangle crossing segments and the vertices of
    /// each mesh inside the other (m, world). Where the surfaces merely touch (see
    /// [`surfaces_intersect`](super::surfaces_intersect)) nothing is added: a point on both surfaces must not widen the
    /// region beyond the overlap.
    pub points: Vec<Point>,
    /// Vector area (m^2, world) of mesh 1's surface inside mesh 2, outward normals.
    pub area_normal_1_in_2: Vector,
    /// Vector area (m^2, world) of mesh 2's surface inside mesh 1, outward normals.
    pub area_normal_2_in_1: Vector,
    /// Number of crossing segments (touches not counted).
    pub segment_count: usize,
    /// Number of vertices of either mesh inside the other.
    pub inside_vertex_count: usize,
    /// Of those, mesh 1's (inside mesh 2). `points` holds the crossings' end points (2 per
    /// segment), then mesh 1's vertices inside mesh 2, then mesh 2's inside mesh 1.
    pub inside_1_count: usize,
}

impl OverlapRegion {
    /// True when the meshes do not overlap at all.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// The centre of the region's box (m, world); None when it is empty.
    pub fn center(&self) -> Option<Point> {
        let first = *self.points.first()?;
        let (lo, hi) = self
            .points
            .iter()
            .fold((first, first), |(lo, hi), p| (lo.inf(p), hi.sup(p)));
        Some(nalgebra::center(&lo, &hi))
    }

    /// The volume normal from mesh 1 into mesh 2, unit; None when it vanishes.
    pub fn volume_normal(&self) -> Option<Vector> {
        let n = self.area_normal_1_in_2 - self.area_normal_2_in_1;
        let len = n.norm();
        (len > 0.0 && len.is_finite()).then(|| n / len)
    }
}

/// The overlap region S of two posed meshes and their inside vector areas.
pub fn overlap_region(
    s1: &MeshShape,
    pose1: &Isometry,
    s2: &MeshShape,
    pose2: &Isometry,
) -> OverlapRegion {
    overlap_region_with(s1, pose1, s2, pose2, true, RegionParts::All)
}

/// The overlap region's point set S and its counts alone, the vector areas left at zero:
/// where only the region's extent is needed (the early normal's footprint), this skips
/// deciding which part of each cut triangle is inside, most of a region's work against an
/// open mesh. The points are [`overlap_region`]'s.
pub fn overlap_points(
    s1: &MeshShape,
    pose1: &Isometry,
    s2: &MeshShape,
    pose2: &Isometry,
) -> OverlapRegion {
    overlap_region_with(s1, pose1, s2, pose2, true, RegionParts::Points)
}

/// The overlap region's two inside vector areas alone (and so its volume normal), the point
/// set and its counts left empty: where only the normal is read (the early normal's
/// thin-part probes), this skips deciding which vertices are inside. The areas are
/// [`overlap_region`]'s, bit for bit.
pub fn overlap_areas(
    s1: &MeshShape,
    pose1: &Isometry,
    s2: &MeshShape,
    pose2: &Isometry,
) -> OverlapRegion {
    overlap_region_with(s1, pose1, s2, pose2, true, RegionParts::Areas)
}

/// Which parts of the overlap region a query computes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum RegionParts {
    /// The point set, its counts and the vector areas ([`overlap_region`]).
    All,
    /// The point set and its counts ([`overlap_points`]).
    Points,
    /// The vector areas ([`overlap_areas`]).
    Areas,
}

/// [`overlap_region`], deciding inside and outside per patch (`use_patches`, for closed
/// meshes) or per triangle and vertex (the reference the patches are tested against),
/// computing the `parts` asked for.
pub(super) fn overlap_region_with(
    s1: &MeshShape,
    pose1: &Isometry,
    s2: &MeshShape,
    pose2: &Isometry,
    use_patches: bool,
    parts: RegionParts,
) -> OverlapRegion {
    let areas = parts != RegionParts::Points;
    let points = parts != RegionParts::Areas;
    let pose12 = pose1.inv_mul(pose2);
    let pose21 = pose12.inverse();
    // The same map as `surfaces_intersect`, so both see bit-identical triangles.
    let (map12, map21) = (RigidMap::new(&pose12), RigidMap::new(&pose21));
    let nudge = nudge_length(s1, s2, &pose12);
    let mut stack = Vec::new();
    // Where the triangles meet, in frame 1: the segment oriented along n1 x n2, and whether
    // triangle 1 and triangle 2 are crossed (not merely touched) by the other.
    let mut segs: Vec<(u32, u32, TriangleContact)> = Vec::new();
    traverse_pairs(s1, s2, &pose12, &mut stack, false, |a, b| {
        let leaf2 = mapped_leaf(s2, b, &map12);
        let box2 = box_of(leaf2.iter().flatten().map(|(_, t)| t));
        for &t1 in s1.bvh().leaf_primitives(a) {
            let tri1 = s1.triangle(t1);
            if boxes_apart(&box_of([&tri1]), &box2) {
                continue; // no triangle of b's leaf comes near this one
            }
            for &(t2, tri2) in leaf2.iter().flatten() {
                if let Some(c) = triangle_triangle_contact(&tri1, &tri2) {
                    segs.push((t1, t2, c));
                }
            }
        }
        false
    });
    let mut region = OverlapRegion::default();
    // Only crossings are in S: where the surfaces merely touch (faces resting on each other)
    // nothing overlaps. Touching triangles still count as met for the patches below. (No
    // points for the vector areas alone.)
    for (_, _, c) in segs.iter() {
        if points && c.is_crossing() {
            region.segment_count += 1;
            region.points.push(pose1 * c.start);
            region.points.push(pose1 * c.end);
        }
    }
    // Mesh 1's side, in frame 1.
    let mut by_1: Vec<Crossing> = segs
        .iter()
        .map(|&(t1, t2, c)| (t1, t2, c.start, c.end, c.a_crossed, c.a_on_plane))
        .collect();
    by_1.sort_by_key(|c| (c.0, c.1));
    let (va1, inside1) = surface_inside(
        s1,
        s2,
        &pose21,
        &by_1,
        |o| map_tri(&s2.triangle(o), &map12),
        use_patches,
        areas,
        points,
        nudge,
    );
    // Mesh 2's side, in frame 2: its triangles' segments run the other way (n2 x n1).
    let mut by_2: Vec<Crossing> = segs
        .iter()
        .map(|&(t1, t2, c)| {
            let (p, q) = (map21.point(&c.end), map21.point(&c.start));
            (t2, t1, p, q, c.b_crossed, c.b_on_plane)
        })
        .collect();
    by_2.sort_by_key(|c| (c.0, c.1));
    let (va2, inside2) = surface_inside(
        s2,
        s1,
        &pose12,
        &by_2,
        |o| map_tri(&s1.triangle(o), &map21),
        use_patches,
        areas,
        points,
        nudge,
    );
    region.inside_vertex_count = inside1.len() + inside2.len();
    region.inside_1_count = inside1.len();
    region.points.extend(inside1.iter().map(|p| pose1 * p));
    region.points.extend(inside2.iter().map(|p| pose2 * p));
    region.area_normal_1_in_2 = pose1.rotation * va1;
    region.area_normal_2_in_1 = pose2.rotation * va2;
    region
}
