//! The two-tree descent the overlap queries share: mesh 2's leaves mapped into mesh 1's
//! frame, and the leaf pairs whose boxes meet.

use crate::bvh::{BvhNode, LEAF_SIZE};
use crate::math::{Aabb, Isometry, RigidMap};
use crate::shape::MeshShape;
use crate::triangle::Tri;
use parry3d_f64::bounding_volume::BoundingVolume;

#[inline]
pub(super) fn map_tri(t: &Tri, m: &RigidMap) -> Tri {
    [m.point(&t[0]), m.point(&t[1]), m.point(&t[2])]
}

/// The triangles of leaf `node` of `mesh` (at most [`crate::bvh::LEAF_SIZE`]) mapped by `m`,
/// with their indices, in the leaf's order.
#[inline]
pub(super) fn mapped_leaf(
    mesh: &MeshShape,
    node: &BvhNode,
    m: &RigidMap,
) -> [Option<(u32, Tri)>; LEAF_SIZE] {
    let mut out = [None; LEAF_SIZE];
    for (slot, &t) in out.iter_mut().zip(mesh.bvh().leaf_primitives(node)) {
        *slot = Some((t, map_tri(&mesh.triangle(t), m)));
    }
    out
}

/// Simultaneous descent of two trees (2 in 1's frame by `pose12`): calls `leaf` on every leaf
/// pair whose boxes meet; `leaf` returns true to stop early. Returns true if stopped early.
/// A node pair is passed over when node 2's box, mapped into 1's frame, is apart from node 1's
/// box there (3 of the 15 separating axes of two boxes), and, with `both_frames`, also when
/// node 1's box mapped into 2's frame is apart from node 2's (6 axes): fewer pairs, in the
/// same order, where the poses turn one tree against the other (a query wanting one crossing
/// pair takes it; the region, which reads every pair's triangles, does not).
pub(super) fn traverse_pairs(
    s1: &MeshShape,
    s2: &MeshShape,
    pose12: &Isometry,
    stack: &mut Vec<(u32, u32)>,
    both_frames: bool,
    mut leaf: impl FnMut(&BvhNode, &BvhNode) -> bool,
) -> bool {
    let (n1, n2) = (s1.bvh().nodes(), s2.bvh().nodes());
    let map = RigidMap::new(pose12);
    let back = RigidMap::new(&pose12.inverse());
    // The last node mapped into the other's frame, by tree: a node's box is tested against
    // both children of the other node one after the other (they are pushed together), so it
    // is mapped once for both (benches/COMPARISON.md, "The near-miss query").
    let mut mapped2: (u32, Aabb) = (u32::MAX, n2[0].aabb);
    let mut mapped1: (u32, Aabb) = (u32::MAX, n1[0].aabb);
    stack.clear();
    stack.push((0, 0));
    while let Some((i, j)) = stack.pop() {
        let (a, b) = (&n1[i as usize], &n2[j as usize]);
        if mapped2.0 != j {
            mapped2 = (j, map.aabb(&b.aabb));
        }
        if !a.aabb.intersects(&mapped2.1) {
            continue;
        }
        if both_frames {
            if mapped1.0 != i {
                mapped1 = (i, back.aabb(&a.aabb));
            }
            if !b.aabb.intersects(&mapped1.1) {
                continue;
            }
        }
        match (a.is_leaf(), b.is_leaf()) {
            (true, true) => {
                if leaf(a, b) {
                    return true;
                }
            }
            (false, true) => {
                let (l, r) = s1.bvh().children(i);
                stack.push((r, j));
                stack.push((l, j));
            }
            (true, false) => {
                let (l, r) = s2.bvh().children(j);
                stack.push((i, r));
                stack.push((i, l));
            }
            (false, false) => {
                // Descend the larger box first keeps the pairs balanced.
                if a.aabb.volume() >= b.aabb.volume() {
                    let (l, r) = s1.bvh().children(i);
                    stack.push((r, j));
                    stack.push((l, j));
                } else {
                    let (l, r) = s2.bvh().children(j);
                    stack.push((i, r));
                    stack.push((i, l));
                }
            }
        }
    }
    false
}
