//! The smallest distance between two posed surfaces: branch and bound over the two trees.

use super::traverse::{map_tri, mapped_leaf};
use super::QueryWorkspace;
use crate::math::{Aabb, Isometry, Real, RigidMap, Vector};
use crate::shape::MeshShape;
use crate::triangle::triangle_triangle_distance_sq;

/// Distance between two boxes (0 when they meet).
#[inline]
fn aabb_distance(a: &Aabb, b: &Aabb) -> Real {
    let gap = (a.mins - b.maxs)
        .sup(&(b.mins - a.maxs))
        .sup(&Vector::zeros());
    gap.norm()
}

/// The smallest distance between the two posed surfaces (m), or `cap` if that is smaller.
/// 0 when they touch or cross. Branch and bound over the two trees, nearest pairs first.
pub fn surface_distance(
    s1: &MeshShape,
    pose1: &Isometry,
    s2: &MeshShape,
    pose2: &Isometry,
    cap: Real,
    ws: &mut QueryWorkspace,
) -> Real {
    surface_distance_from(s1, pose1, s2, pose2, cap, None, ws).0
}

/// [`surface_distance`] warm-started from a pair of triangles (of mesh 1, mesh 2) likely to
/// be near the closest, e.g. the closest at a previous query: their distance bounds the
/// search from the start, so far fewer node pairs are opened when the surfaces are close.
/// The distance is the same; also returns the closest pair found (None when nothing is
/// nearer than `cap`).
pub fn surface_distance_from(
    s1: &MeshShape,
    pose1: &Isometry,
    s2: &MeshShape,
    pose2: &Isometry,
    cap: Real,
    hint: Option<(u32, u32)>,
    ws: &mut QueryWorkspace,
) -> (Real, Option<(u32, u32)>) {
    let pose12 = pose1.inv_mul(pose2);
    let map = RigidMap::new(&pose12);
    let (n1, n2) = (s1.bvh().nodes(), s2.bvh().nodes());
    let stack = &mut ws.bounded_pairs;
    stack.clear();
    let mut best = cap;
    let mut closest = None;
    if let Some((t1, t2)) = hint {
        if (t1 as usize) < s1.triangles().len() && (t2 as usize) < s2.triangles().len() {
            let d =
                triangle_triangle_distance_sq(&s1.triangle(t1), &map_tri(&s2.triangle(t2), &map))
                    .sqrt();
            if d < best {
                best = d;
                closest = Some((t1, t2));
                if best == 0.0 {
                    return (0.0, closest);
                }
            }
        }
    }
    let bound = |i: u32, j: u32| -> Real {
        aabb_distance(&n1[i as usize].aabb, &map.aabb(&n2[j as usize].aabb))
    };
    stack.push((bound(0, 0), 0, 0));
    while let Some((lb, i, j)) = stack.pop() {
        if lb >= best {
            continue;
        }
        let (a, b) = (&n1[i as usize], &n2[j as usize]);
        if a.is_leaf() && b.is_leaf() {
            // b's triangles in 1's frame and their boxes, once per leaf pair
            let leaf2 = mapped_leaf(s2, b, &map)
                .map(|e| e.map(|(t2, tri2)| (t2, tri2, Aabb::from_points(tri2.iter().copied()))));
            for &t1 in s1.bvh().leaf_primitives(a) {
                let tri1 = s1.triangle(t1);
                let box1 = Aabb::from_points(tri1.iter().copied());
                for (t2, tri2, box2) in leaf2.iter().flatten() {
                    let (t2, tri2) = (*t2, *tri2);
                    // The boxes' distance bounds the triangles' from below: a cheap reject.
                    if aabb_distance(&box1, box2) >= best {
                        continue;
                    }
                    let d = triangle_triangle_distance_sq(&tri1, &tri2).sqrt();
                    if d < best {
                        best = d;
                        closest = Some((t1, t2));
                        if best == 0.0 {
                            return (0.0, closest);
                        }
                    }
                }
            }
            continue;
        }
        let split_first = !a.is_leaf() && (b.is_leaf() || a.aabb.volume() >= b.aabb.volume());
        let ((i1, j1), (i2, j2)) = if split_first {
            let (l, r) = s1.bvh().children(i);
            ((l, j), (r, j))
        } else {
            let (l, r) = s2.bvh().children(j);
            ((i, l), (i, r))
        };
        let (d1, d2) = (bound(i1, j1), bound(i2, j2));
        // Push the farther first so the nearer is explored first.
        if d1 <= d2 {
            if d2 < best {
                stack.push((d2, i2, j2));
            }
            if d1 < best {
                stack.push((d1, i1, j1));
            }
        } else {
            if d1 < best {
                stack.push((d1, i1, j1));
            }
            if d2 < best {
                stack.push((d2, i2, j2));
            }
        }
    }
    (best, closest)
}
