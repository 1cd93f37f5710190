//! A static binary bounding-volume hierarchy over a mesh's triangles (body frame).
//!
//! Why not parry's `Bvh`: the engine needs per-node aggregates aligned with the tree (the
//! dipoles of the fast winding number) and simultaneous two-tree traversals with custom
//! node tests in a relative frame; parry 0.25 keeps its node array private. This tree is
//! built once per mesh, deterministically (median split, ties broken by index), and laid out
//! depth-first: an internal node's left child is the next node.

use crate::math::{Aabb, Point, Real};
use parry3d_f64::bounding_volume::BoundingVolume;

/// Triangles per leaf at most.
pub const LEAF_SIZE: usize = 4;
/// Deepest traversal stack the engine's trees can need (depth is about log2(n / 4) + 1).
pub const MAX_DEPTH: usize = 96;

/// One node: its box and either a leaf's primitive range or an internal node's right child.
#[derive(Clone, Debug)]
pub struct BvhNode {
    /// Bounding box of everything below, body frame (m).
    pub aabb: Aabb,
    /// Leaf: first index into [`Bvh::primitives`]. Internal: index of the right child.
    pub start_or_right: u32,
    /// Leaf: number of primitives (>= 1). Internal: 0.
    pub count: u32,
}

impl BvhNode {
    /// True for a leaf.
    #[inline]
    pub fn is_leaf(&self) -> bool {
        self.count > 0
    }
}

/// The hierarchy: nodes in depth-first order (root at 0) and the primitive permutation.
#[derive(Clone, Debug)]
pub struct Bvh {
    nodes: Vec<BvhNode>,
    primitives: Vec<u32>,
}

impl Bvh {
    /// Builds the tree over primitives given by their boxes. `boxes` must not be empty.
    pub fn build(boxes: &[Aabb]) -> Bvh {
        assert!(!boxes.is_empty(), "a BVH needs at least one primitive");
        let centers: Vec<Point> = boxes.iter().map(|b| b.center()).collect();
        let mut primitives: Vec<u32> = (0..boxes.len() as u32).collect();
        let mut nodes = Vec::with_capacity(2 * boxes.len() / LEAF_SIZE + 1);
        build_range(&mut nodes, &mut primitives, 0, boxes, &centers);
        Bvh { nodes, primitives }
    }

    /// All nodes, depth-first; node 0 is the root.
    #[inline]
    pub fn nodes(&self) -> &[BvhNode] {
        &self.nodes
    }

    /// The primitive indices of a leaf.
    #[inline]
    pub fn leaf_primitives(&self, node: &BvhNode) -> &[u32] {
        let s = node.start_or_right as usize;
        &self.primitives[s..s + node.count as usize]
    }

    /// The primitive indices of everything below node `i` (a subtree's primitives are
    /// contiguous: the tree is laid out depth-first over a permutation split in place).
    pub fn subtree_primitives(&self, i: u32) -> &[u32] {
        let (mut first, mut last) = (i, i);
        while !self.nodes[first as usize].is_leaf() {
            first += 1; // the left child follows its parent
        }
        while !self.nodes[last as usize].is_leaf() {
            last = self.nodes[last as usize].start_or_right;
        }
        let start = self.nodes[first as usize].start_or_right as usize;
        let end = self.nodes[last as usize].start_or_right as usize
            + self.nodes[last as usize].count as usize;
        &self.primitives[start..end]
    }

    /// The two children of internal node `i`.
    #[inline]
    pub fn children(&self, i: u32) -> (u32, u32) {
        (i + 1, self.nodes[i as usize].start_or_right)
    }

    /// The root box.
    #[inline]
    pub fn root_aabb(&self) -> &Aabb {
        &self.nodes[0].aabb
    }
}

fn build_range(
    nodes: &mut Vec<BvhNode>,
    prims: &mut [u32],
    offset: usize,
    boxes: &[Aabb],
    centers: &[Point],
) -> u32 {
    let mut aabb = boxes[prims[0] as usize];
    for &p in prims.iter().skip(1) {
        aabb.merge(&boxes[p as usize]);
    }
    let me = nodes.len() as u32;
    if prims.len() <= LEAF_SIZE {
        nodes.push(BvhNode {
            aabb,
            start_or_right: offset as u32,
            count: prims.len() as u32,
        });
        return me;
    }
    // Split at the median centre along the widest axis of the centres.
    let mut cmin = centers[prims[0] as usize];
    let mut cmax = cmin;
    for &p in prims.iter() {
        let c = &centers[p as usize];
        cmin = cmin.inf(c);
        cmax = cmax.sup(c);
    }
    let ext = cmax - cmin;
    let axis = if ext.x >= ext.y && ext.x >= ext.z {
        0
    } else if ext.y >= ext.z {
        1
    } else {
        2
    };
    let mid = prims.len() / 2;
    prims.select_nth_unstable_by(mid, |&a, &b| {
        let ka: Real = centers[a as usize][axis];
        let kb: Real = centers[b as usize][axis];
        ka.total_cmp(&kb).then(a.cmp(&b))
    });
    nodes.push(BvhNode {
        aabb,
        start_or_right: 0,
        count: 0,
    });
    let (left, right) = prims.split_at_mut(mid);
    let l = build_range(nodes, left, offset, boxes, centers);
    debug_assert_eq!(l, me + 1);
    let r = build_range(nodes, right, offset + mid, boxes, centers);
    nodes[me as usize].start_or_right = r;
    me
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_primitive_is_in_exactly_one_leaf_and_boxes_nest() {
        let boxes: Vec<Aabb> = (0..1000)
            .map(|i| {
                let x = ((i * 7919) % 1000) as Real * 0.01;
                let y = ((i * 104729) % 997) as Real * 0.01;
                Aabb::new(Point::new(x, y, 0.0), Point::new(x + 0.05, y + 0.05, 0.1))
            })
            .collect();
        let bvh = Bvh::build(&boxes);
        let mut seen = vec![0u32; boxes.len()];
        for (i, n) in bvh.nodes().iter().enumerate() {
            if n.is_leaf() {
                for &p in bvh.leaf_primitives(n) {
                    seen[p as usize] += 1;
                    assert!(n.aabb.contains(&boxes[p as usize]));
                }
            } else {
                let (l, r) = bvh.children(i as u32);
                assert!(n.aabb.contains(&bvh.nodes()[l as usize].aabb));
                assert!(n.aabb.contains(&bvh.nodes()[r as usize].aabb));
            }
        }
        assert!(seen.iter().all(|&c| c == 1));
    }
}
