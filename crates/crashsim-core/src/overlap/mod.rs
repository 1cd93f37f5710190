//! Queries between two posed meshes: do they overlap, how far apart are they, and the
//! overlap region S with its volume normal (docs/model.md, "The overlap region").
//!
//! A pose maps body-frame points into the world. The two-tree traversals work in mesh 1's
//! body frame: mesh 2's node boxes are carried over by the relative pose and re-boxed
//! (a conservative box), so pruning never drops a real contact.
//!
//! One query per file: intersect.rs (do the surfaces cross, do the meshes overlap),
//! distance.rs (how far apart), region.rs (the overlap region and its normal); beneath them
//! traverse.rs (the two-tree descent), inside.rs (the nudge, shells inside) and
//! surface_inside.rs (the part of one mesh's surface inside the other); tests.rs.

use crate::math::Real;

mod distance;
mod inside;
mod intersect;
mod region;
mod surface_inside;
#[cfg(test)]
mod tests;
mod traverse;

pub use distance::{surface_distance, surface_distance_from};
pub use intersect::{shapes_overlap, shapes_overlap_hinted, surfaces_intersect};
pub use region::{overlap_areas, overlap_points, overlap_region, OverlapRegion};

/// Reusable traversal storage, so per-step queries do not allocate once warmed up.
#[derive(Default, Debug)]
pub struct QueryWorkspace {
    pairs: Vec<(u32, u32)>,
    bounded_pairs: Vec<(Real, u32, u32)>,
}
