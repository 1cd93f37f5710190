//! A vehicle's shape: a triangle mesh in its body frame (origin at the CG, m), with its BVH,
//! the per-node dipoles of the fast generalized winding number, and one representative
//! vertex per shell for the whole-inside test.
//!
//! Meshes are taken as they come: triangle soups, open bodies and many shells are fine.
//! "Inside" is decided by the generalized winding number (> 0.5), which degrades gracefully
//! on open meshes, unlike ray parity.

use crate::bvh::{Bvh, MAX_DEPTH};
use crate::error::{Error, Result};
use std::sync::OnceLock;

use crate::math::{Aabb, Matrix, Point, Real, Vector};
use crate::triangle::{scaled_normal, solid_angle, Tri};

/// Largest coordinate magnitude a mesh may have (m): beyond it the winding number's
/// products of three distances overflow (1e300 m gave NaN); a million kilometres is far
/// beyond any scene.
pub const MAX_COORDINATE: Real = 1e12;

/// Far-field acceptance: a node is approximated by its dipole when the query point is more
/// than `WINDING_BETA` times the node's radius away from the node's centre.
const WINDING_BETA: Real = 2.5;

/// First-order (dipole) summary of a BVH node for the winding number.
#[derive(Clone, Debug)]
struct Dipole {
    /// Sum of the triangles' vector areas (m^2), outward normals times area.
    area_normal: Vector,
    /// Area-weighted centre of the triangles (m).
    center: Point,
    /// Radius of a ball about `center` holding the node's box (m).
    radius: Real,
}

/// One connected shell: a vertex of it and its box, body frame.
#[derive(Clone, Debug)]
pub struct Shell {
    /// Index of one vertex of the shell.
    pub vertex: u32,
    /// Box of the shell's vertices.
    pub aabb: Aabb,
}

/// An immutable triangle mesh in a body frame with everything the overlap queries need.
#[derive(Clone, Debug)]
pub struct MeshShape {
    vertices: Vec<Point>,
    triangles: Vec<[u32; 3]>,
    bvh: Bvh,
    dipoles: Vec<Dipole>,
    shells: Vec<Shell>,
    radius: Real,
    topology: Topology,
    /// Oriented boxes of the BVH's nodes, each made on first use (see [`MeshShape::node_obb`]).
    obbs: Vec<OnceLock<Obb>>,
    /// The convex hull, made on first use (see [`MeshShape::convex_hull`]).
    hull: OnceLock<std::result::Result<ConvexHull, String>>,
}

/// A convex hull: vertices (m, body frame) and outward triangles.
pub type ConvexHull = (Vec<Point>, Vec<[u32; 3]>);

/// An oriented box holding a BVH node's triangles (body frame, m): centre, unit axes (the
/// columns of `axes`, the principal axes of the node's vertices) and half extents along
/// them. A patch of a vehicle's surface is thin along its normal whatever its slant, where
/// the axis-aligned box of a slanted patch is as thick as it is long.
#[derive(Clone, Debug)]
pub struct Obb {
    /// Centre (m, body frame).
    pub center: Point,
    /// Unit axes as columns (body frame).
    pub axes: Matrix,
    /// Half extents along the axes (m).
    pub half: Vector,
}

/// Which triangles share an edge, one triangle at each vertex, and whether the mesh is
/// closed (every directed edge met once by its reverse): inside and outside then change
/// only across the surface, so a patch of triangles no other surface cuts is wholly inside or
/// wholly outside (the overlap region classifies such patches once).
#[derive(Clone, Debug)]
struct Topology {
    /// Per triangle t, the triangles it shares an edge with, `partners[start[t]..start[t + 1]]`
    /// (for an edge of k > 2 triangles, a chain of k - 1 pairs: each its neighbours in it).
    partner_start: Vec<u32>,
    partners: Vec<u32>,
    /// One triangle having the vertex, or u32::MAX for an unused vertex.
    vertex_triangle: Vec<u32>,
    /// The triangle across edge k (vertex k to vertex k + 1) of each triangle, or u32::MAX
    /// when the edge has no other triangle or more than one.
    neighbors: Vec<[u32; 3]>,
    closed: bool,
}

fn build_topology(n_vertices: usize, triangles: &[[u32; 3]]) -> Topology {
    // Directed edges (from, to, triangle, edge slot), sorted by their undirected key and then
    // triangle: deterministic.
    let mut edges: Vec<(u32, u32, u32, u8)> = Vec::with_capacity(3 * triangles.len());
    let mut vertex_triangle = vec![u32::MAX; n_vertices];
    for (ti, t) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            edges.push((a, b, ti as u32, k as u8));
            let slot = &mut vertex_triangle[a as usize];
            if *slot == u32::MAX {
                *slot = ti as u32;
            }
        }
    }
    let key = |e: &(u32, u32, u32, u8)| (e.0.min(e.1), e.0.max(e.1));
    edges.sort_unstable_by_key(|e| (key(e), e.2, e.3));
    let mut edge_pairs = Vec::new();
    let mut neighbors = vec![[u32::MAX; 3]; triangles.len()];
    let mut closed = true;
    let mut i = 0;
    while i < edges.len() {
        let mut j = i + 1;
        while j < edges.len() && key(&edges[j]) == key(&edges[i]) {
            edge_pairs.push((edges[j - 1].2, edges[j].2));
            j += 1;
        }
        if j - i == 2 {
            let (e0, e1) = (edges[i], edges[i + 1]);
            neighbors[e0.2 as usize][e0.3 as usize] = e1.2;
            neighbors[e1.2 as usize][e1.3 as usize] = e0.2;
        }
        // Closed: exactly two uses, in opposite directions.
        if j - i != 2 || edges[i].0 == edges[i + 1].0 || edges[i].0 == edges[i].1 {
            closed = false;
        }
        i = j;
    }
    // The pairs as per-triangle lists (compressed rows), each in the pairs' order.
    let mut partner_start = vec![0u32; triangles.len() + 1];
    for &(a, b) in &edge_pairs {
        partner_start[a as usize + 1] += 1;
        partner_start[b as usize + 1] += 1;
    }
    for t in 0..triangles.len() {
        partner_start[t + 1] += partner_start[t];
    }
    let mut fill = partner_start.clone();
    let mut partners = vec![0u32; 2 * edge_pairs.len()];
    for &(a, b) in &edge_pairs {
        partners[fill[a as usize] as usize] = b;
        fill[a as usize] += 1;
        partners[fill[b as usize] as usize] = a;
        fill[b as usize] += 1;
    }
    Topology {
        partner_start,
        partners,
        vertex_triangle,
        neighbors,
        closed,
    }
}

impl MeshShape {
    /// Builds a shape from body-frame vertices (m) and triangles (vertex indices).
    ///
    /// Errors: no triangles, a non-finite vertex or one beyond [`MAX_COORDINATE`], an index
    /// out of range, or no triangle with a non-zero area.
    pub fn new(vertices: Vec<Point>, triangles: Vec<[u32; 3]>) -> Result<MeshShape> {
        if triangles.is_empty() {
            return Err(Error::mesh(
                "the mesh has no triangles: give at least one face (a vehicle needs a surface)",
            ));
        }
        if let Some(i) = vertices
            .iter()
            .position(|v| !v.iter().all(|c| c.is_finite()))
        {
            return Err(Error::mesh(format!(
                "vertex {i} is not finite ({:?}): remove or repair NaN/inf vertices",
                vertices[i].coords.as_slice()
            )));
        }
        if let Some(i) = vertices
            .iter()
            .position(|v| v.iter().any(|c| c.abs() > MAX_COORDINATE))
        {
            return Err(Error::mesh(format!(
                "vertex {i} ({:?}) lies beyond {MAX_COORDINATE:e} m of the body origin: give \
                 the mesh in metres, about its own centre",
                vertices[i].coords.as_slice()
            )));
        }
        let n = vertices.len() as u64;
        if let Some((i, t)) = triangles
            .iter()
            .enumerate()
            .find(|(_, t)| t.iter().any(|&k| k as u64 >= n))
        {
            return Err(Error::mesh(format!(
                "triangle {i} refers to vertex {:?} but the mesh has only {n} vertices",
                t
            )));
        }
        let tri = |t: &[u32; 3]| -> Tri {
            [
                vertices[t[0] as usize],
                vertices[t[1] as usize],
                vertices[t[2] as usize],
            ]
        };
        if triangles
            .iter()
            .all(|t| scaled_normal(&tri(t)).norm_squared() == 0.0)
        {
            return Err(Error::mesh(
                "every triangle of the mesh has zero area: the mesh has no surface",
            ));
        }
        let boxes: Vec<Aabb> = triangles
            .iter()
            .map(|t| Aabb::from_points(tri(t).iter().copied()))
            .collect();
        let bvh = Bvh::build(&boxes);
        let dipoles = build_dipoles(&bvh, &vertices, &triangles);
        let shells = find_shells(&vertices, &triangles);
        let topology = build_topology(vertices.len(), &triangles);
        let radius = vertices
            .iter()
            .map(|v| v.coords.norm())
            .fold(0.0, Real::max);
        let obbs = (0..bvh.nodes().len()).map(|_| OnceLock::new()).collect();
        Ok(MeshShape {
            vertices,
            triangles,
            bvh,
            dipoles,
            shells,
            radius,
            topology,
            obbs,
            hull: OnceLock::new(),
        })
    }

    /// A closed, outward-oriented box (12 triangles) centred at `c` (body frame, m) with
    /// half extents `h` (m, all positive).
    pub fn cuboid(c: Vector, h: Vector) -> MeshShape {
        let mut v = Vec::new();
        for i in 0..8 {
            let s = Vector::new(
                if i & 1 == 0 { -1.0 } else { 1.0 },
                if i & 2 == 0 { -1.0 } else { 1.0 },
                if i & 4 == 0 { -1.0 } else { 1.0 },
            );
            v.push(Point::from(c + h.component_mul(&s)));
        }
        let t = vec![
            [0, 2, 1],
            [1, 2, 3], // z-
            [4, 5, 6],
            [5, 7, 6], // z+
            [0, 1, 4],
            [1, 5, 4], // y-
            [2, 6, 3],
            [3, 6, 7], // y+
            [0, 4, 2],
            [2, 4, 6], // x-
            [1, 3, 5],
            [3, 7, 5], // x+
        ];
        MeshShape::new(v, t).expect("a box with positive extents is a valid mesh")
    }

    /// Body-frame vertices (m).
    #[inline]
    pub fn vertices(&self) -> &[Point] {
        &self.vertices
    }

    /// Triangles as vertex indices.
    #[inline]
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// The triangle `i` as points, body frame.
    #[inline]
    pub fn triangle(&self, i: u32) -> Tri {
        let t = &self.triangles[i as usize];
        [
            self.vertices[t[0] as usize],
            self.vertices[t[1] as usize],
            self.vertices[t[2] as usize],
        ]
    }

    /// The hierarchy over the triangles.
    #[inline]
    pub fn bvh(&self) -> &Bvh {
        &self.bvh
    }

    /// Box of the whole mesh, body frame.
    #[inline]
    pub fn aabb(&self) -> &Aabb {
        self.bvh.root_aabb()
    }

    /// The convex hull of the vertices (parry's), made on first use and kept: every world
    /// built from a scene on the ground asks for it (a body's contact points with the ground),
    /// and the variants of a batch share the mesh. An error says why it failed (a flat or
    /// degenerate mesh).
    pub fn convex_hull(&self) -> std::result::Result<&ConvexHull, &str> {
        self.hull
            .get_or_init(|| {
                parry3d_f64::transformation::try_convex_hull(&self.vertices)
                    .map_err(|e| format!("{e:?}"))
            })
            .as_ref()
            .map_err(|e| e.as_str())
    }

    /// The oriented box of BVH node `i` (indexed as [`Bvh::nodes`]), made on first use and
    /// kept: the clearance front's node gaps. Only the nodes a front reaches are ever made
    /// (all of them: about 15 ms for 20k triangles).
    pub fn node_obb(&self, i: u32) -> &Obb {
        self.obbs[i as usize].get_or_init(|| self.obb_of(self.bvh.subtree_primitives(i)))
    }

    /// The oriented box of some triangles: principal axes of their vertices (each counted
    /// once per triangle using it), extents from the vertices' projections.
    fn obb_of(&self, triangles: &[u32]) -> Obb {
        let points = || {
            triangles
                .iter()
                .flat_map(|&t| self.triangles[t as usize].iter())
                .map(|&v| self.vertices[v as usize])
        };
        let n = (3 * triangles.len()) as Real;
        let mean = points().fold(Vector::zeros(), |a, p| a + p.coords) / n;
        let cov = points().fold(Matrix::zeros(), |a, p| {
            let d = p.coords - mean;
            a + d * d.transpose()
        });
        let axes = nalgebra::SymmetricEigen::new(cov).eigenvectors;
        let (mut lo, mut hi) = (
            Vector::repeat(Real::INFINITY),
            Vector::repeat(-Real::INFINITY),
        );
        for p in points() {
            let c = axes.tr_mul(&p.coords);
            lo = lo.inf(&c);
            hi = hi.sup(&c);
        }
        Obb {
            center: Point::from(axes * (0.5 * (lo + hi))),
            axes,
            half: 0.5 * (hi - lo),
        }
    }

    /// Largest distance from the body origin (the CG) to a vertex (m).
    #[inline]
    pub fn radius(&self) -> Real {
        self.radius
    }

    /// True when every edge is shared by exactly two triangles in opposite directions (a
    /// closed, consistently wound surface).
    #[inline]
    pub fn is_closed(&self) -> bool {
        self.topology.closed
    }

    /// The triangles sharing an edge with triangle `t` (for an edge of k > 2 triangles, its
    /// neighbours in a chain of the k).
    #[inline]
    pub fn edge_partners(&self, t: u32) -> &[u32] {
        let s = &self.topology.partner_start;
        &self.topology.partners[s[t as usize] as usize..s[t as usize + 1] as usize]
    }

    /// The triangles across the edges of triangle `t` (edge k runs from its vertex k to
    /// vertex k + 1); u32::MAX where an edge has no other triangle or more than one.
    #[inline]
    pub fn neighbors(&self, t: u32) -> [u32; 3] {
        self.topology.neighbors[t as usize]
    }

    /// One triangle having vertex `v` (u32::MAX when no triangle uses it).
    #[inline]
    pub fn vertex_triangle(&self, v: u32) -> u32 {
        self.topology.vertex_triangle[v as usize]
    }

    /// Connected shells (by shared vertices).
    #[inline]
    pub fn shells(&self) -> &[Shell] {
        &self.shells
    }

    /// Generalized winding number of a body-frame point: about 1 inside a closed outward
    /// mesh, 0 outside, in between near holes of an open one. Exact near the surface, the
    /// dipole approximation far from it.
    pub fn winding_number(&self, q: &Point) -> Real {
        let nodes = self.bvh.nodes();
        let mut stack = [0u32; MAX_DEPTH];
        let mut top = 1;
        let mut omega = 0.0;
        while top > 0 {
            top -= 1;
            let i = stack[top];
            let node = &nodes[i as usize];
            let d = &self.dipoles[i as usize];
            let r = d.center - q;
            let dist = r.norm();
            if dist > WINDING_BETA * d.radius {
                omega += d.area_normal.dot(&r) / (dist * dist * dist);
            } else if node.is_leaf() {
                for &t in self.bvh.leaf_primitives(node) {
                    omega += solid_angle(&self.triangle(t), q);
                }
            } else {
                let (l, rr) = self.bvh.children(i);
                stack[top] = l;
                stack[top + 1] = rr;
                top += 2;
            }
        }
        omega / (4.0 * std::f64::consts::PI)
    }

    /// Volume, centroid and inertia of the mesh as a uniform solid of unit density (body
    /// frame); meaningful for a closed, outward-wound mesh (see [`crate::mass`]). An error
    /// when the mesh encloses no volume.
    pub fn solid_properties(&self) -> Result<crate::mass::SolidProperties> {
        crate::mass::solid_properties(&self.vertices, &self.triangles)
    }

    /// Distances (m, ascending) along the ray from `origin` in the unit direction `dir` (body
    /// frame) at which it crosses the mesh's triangles, up to `max_distance`. A ray through a
    /// shared edge or vertex counts once (hits closer than 1e-12 m relative are merged).
    pub fn ray_hits(&self, origin: &Point, dir: &Vector, max_distance: Real) -> Vec<Real> {
        use parry3d_f64::query::{Ray, RayCast};
        use parry3d_f64::shape::Triangle;
        let ray = Ray::new(*origin, *dir);
        let nodes = self.bvh.nodes();
        let mut stack = [0u32; MAX_DEPTH];
        let mut top = 1;
        let mut hits = Vec::new();
        while top > 0 {
            top -= 1;
            let i = stack[top];
            let node = &nodes[i as usize];
            if !node.aabb.intersects_local_ray(&ray, max_distance) {
                continue;
            }
            if node.is_leaf() {
                for &t in self.bvh.leaf_primitives(node) {
                    let [a, b, c] = self.triangle(t);
                    if let Some(toi) =
                        Triangle::new(a, b, c).cast_local_ray(&ray, max_distance, false)
                    {
                        hits.push(toi);
                    }
                }
            } else {
                let (l, r) = self.bvh.children(i);
                stack[top] = l;
                stack[top + 1] = r;
                top += 2;
            }
        }
        hits.sort_by(|a, b| a.total_cmp(b));
        hits.dedup_by(|b, a| (*b - *a).abs() <= 1e-12 * a.abs().max(1.0));
        hits
    }

    /// [`MeshShape::winding_number`] of many body-frame points, in parallel (each value is
    /// computed alone, so the result does not depend on the thread count).
    pub fn winding_numbers(&self, points: &[Point]) -> Vec<Real> {
        use rayon::prelude::*;
        points
            .par_iter()
            .with_min_len(256)
            .map(|p| self.winding_number(p))
            .collect()
    }

    /// True when the body-frame point is inside (winding number above one half). A point
    /// outside the mesh's box is outside without its winding number: the box holds the
    /// convex hull, beyond which a closed mesh's winding number is 0 (and an open one's
    /// below one half, unless its faces seen from the point lie over one another with the
    /// same orientation), as the overlap's box culling already assumes.
    #[inline]
    pub fn contains_point(&self, q: &Point) -> bool {
        self.aabb().contains_local_point(q) && self.winding_number(q) > 0.5
    }
}

fn build_dipoles(bvh: &Bvh, vertices: &[Point], triangles: &[[u32; 3]]) -> Vec<Dipole> {
    let nodes = bvh.nodes();
    let mut dipoles = vec![
        Dipole {
            area_normal: Vector::zeros(),
            center: Point::origin(),
            radius: 0.0,
        };
        nodes.len()
    ];
    // Area-weighted sums; children come after their parent, so go backwards.
    let mut weights = vec![0.0; nodes.len()];
    let mut weighted_centers = vec![Vector::zeros(); nodes.len()];
    for i in (0..nodes.len()).rev() {
        let node = &nodes[i];
        if node.is_leaf() {
            for &t in bvh.leaf_primitives(node) {
                let tr = triangles[t as usize];
                let (a, b, c) = (
                    vertices[tr[0] as usize],
                    vertices[tr[1] as usize],
                    vertices[tr[2] as usize],
                );
                let an = (b - a).cross(&(c - a)) * 0.5;
                let area = an.norm();
                dipoles[i].area_normal += an;
                weights[i] += area;
                weighted_centers[i] += (a.coords + b.coords + c.coords) * (area / 3.0);
            }
        } else {
            let (l, r) = bvh.children(i as u32);
            let (l, r) = (l as usize, r as usize);
            dipoles[i].area_normal = dipoles[l].area_normal + dipoles[r].area_normal;
            weights[i] = weights[l] + weights[r];
            weighted_centers[i] = weighted_centers[l] + weighted_centers[r];
        }
    }
    for (i, node) in nodes.iter().enumerate() {
        let center = if weights[i] > 0.0 {
            Point::from(weighted_centers[i] / weights[i])
        } else {
            node.aabb.center()
        };
        let radius = node
            .aabb
            .vertices()
            .iter()
            .map(|v| (v - center).norm())
            .fold(0.0, Real::max);
        dipoles[i].center = center;
        dipoles[i].radius = radius;
    }
    dipoles
}

fn find_shells(vertices: &[Point], triangles: &[[u32; 3]]) -> Vec<Shell> {
    // Union-find over vertices joined by triangle edges.
    let mut parent: Vec<u32> = (0..vertices.len() as u32).collect();
    fn root(parent: &mut [u32], mut x: u32) -> u32 {
        while parent[x as usize] != x {
            parent[x as usize] = parent[parent[x as usize] as usize];
            x = parent[x as usize];
        }
        x
    }
    for t in triangles {
        for k in 1..3 {
            let (a, b) = (root(&mut parent, t[0]), root(&mut parent, t[k]));
            if a != b {
                let (lo, hi) = (a.min(b), a.max(b));
                parent[hi as usize] = lo;
            }
        }
    }
    let mut used = vec![false; vertices.len()];
    for t in triangles {
        for &k in t {
            used[k as usize] = true;
        }
    }
    let mut shells: Vec<Shell> = Vec::new();
    let mut index_of_root = vec![u32::MAX; vertices.len()];
    for v in 0..vertices.len() as u32 {
        if !used[v as usize] {
            continue;
        }
        let r = root(&mut parent, v);
        let p = vertices[v as usize];
        match index_of_root[r as usize] {
            u32::MAX => {
                index_of_root[r as usize] = shells.len() as u32;
                shells.push(Shell {
                    vertex: v,
                    aabb: Aabb::new(p, p),
                });
            }
            s => shells[s as usize].aabb.take_point(p),
        }
    }
    shells
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::error::{error_kind, ErrorKind};

    /// A closed, outward-oriented box with its centre at `c` and half extents `h`.
    pub fn box_mesh(c: Vector, h: Vector) -> MeshShape {
        MeshShape::cuboid(c, h)
    }

    /// `mesh` without its triangles whose three vertices lie above the height `z` (m): a
    /// closed box opened at its top.
    pub fn without_top(mesh: &MeshShape, z: Real) -> MeshShape {
        let top = |t: &[u32; 3]| t.iter().all(|&v| mesh.vertices()[v as usize].z > z);
        let kept: Vec<[u32; 3]> = mesh
            .triangles()
            .iter()
            .copied()
            .filter(|t| !top(t))
            .collect();
        MeshShape::new(mesh.vertices().to_vec(), kept).unwrap()
    }

    #[test]
    fn winding_number_of_a_box_is_one_inside_and_zero_outside() {
        let b = box_mesh(Vector::zeros(), Vector::new(2.0, 1.0, 0.5));
        assert!((b.winding_number(&Point::new(0.3, 0.2, 0.1)) - 1.0).abs() < 1e-12);
        assert!(b.winding_number(&Point::new(3.0, 0.0, 0.0)).abs() < 1e-3);
        assert!(b.winding_number(&Point::new(30.0, 10.0, 0.0)).abs() < 1e-6);
        assert!(b.contains_point(&Point::new(1.99, 0.99, 0.49)));
        assert!(!b.contains_point(&Point::new(2.01, 0.0, 0.0)));
    }

    /// contains_point answers outside the box without a winding number: the same answer as
    /// the winding number's, on a grid around a closed box and an open one (the box without
    /// its two top triangles, whose winding number is near one half by the hole).
    #[test]
    fn outside_the_box_is_outside_as_the_winding_number_says() {
        let closed = box_mesh(Vector::zeros(), Vector::new(2.0, 1.0, 0.5));
        let open = without_top(&closed, 0.0);
        assert_eq!(open.triangles().len(), 10);
        assert!(!open.is_closed());
        let mut outside_box = 0;
        for mesh in [&closed, &open] {
            for i in -12..=12 {
                for j in -8..=8 {
                    for k in -6..=6 {
                        let q = Point::new(i as Real * 0.25, j as Real * 0.2, k as Real * 0.15);
                        if !mesh.aabb().contains_local_point(&q) {
                            outside_box += 1;
                            assert!(mesh.winding_number(&q) < 0.5, "{q}");
                        }
                        assert_eq!(mesh.contains_point(&q), mesh.winding_number(&q) > 0.5);
                    }
                }
            }
        }
        assert!(outside_box > 1000);
    }

    #[test]
    fn empty_nan_and_out_of_range_meshes_are_refused() {
        let p = Point::origin();
        assert!(error_kind(&MeshShape::new(vec![p; 3], vec![])) == Some(ErrorKind::Mesh));
        let nan = Point::new(Real::NAN, 0.0, 0.0);
        assert_eq!(
            error_kind(&MeshShape::new(vec![nan, p, p], vec![[0, 1, 2]])),
            Some(ErrorKind::Mesh)
        );
        assert_eq!(
            error_kind(&MeshShape::new(vec![p, p, p], vec![[0, 1, 3]])),
            Some(ErrorKind::Mesh)
        );
        assert_eq!(
            error_kind(&MeshShape::new(vec![p, p, p], vec![[0, 1, 2]])),
            Some(ErrorKind::Mesh)
        );
    }

    #[test]
    fn a_ray_through_a_box_hits_both_walls() {
        let b = box_mesh(Vector::zeros(), Vector::new(2.0, 1.0, 0.5));
        let hits = b.ray_hits(&Point::new(-5.0, 0.1, 0.2), &Vector::x(), 100.0);
        assert_eq!(hits.len(), 2, "{hits:?}");
        assert!((hits[0] - 3.0).abs() < 1e-12 && (hits[1] - 7.0).abs() < 1e-12);
        assert!(b.ray_hits(&Point::origin(), &Vector::y(), 0.5).is_empty());
        // Through the top face's diagonal (shared by its two triangles): one hit.
        let from_inside = b.ray_hits(&Point::origin(), &Vector::z(), 10.0);
        assert_eq!(from_inside.len(), 1, "{from_inside:?}");
        assert!((from_inside[0] - 0.5).abs() < 1e-12);
    }

    #[test]
    fn two_disjoint_boxes_make_two_shells() {
        let a = box_mesh(Vector::zeros(), Vector::new(1.0, 1.0, 1.0));
        let b = box_mesh(Vector::new(5.0, 0.0, 0.0), Vector::new(1.0, 1.0, 1.0));
        let mut v = a.vertices().to_vec();
        v.extend_from_slice(b.vertices());
        let mut t = a.triangles().to_vec();
        t.extend(b.triangles().iter().map(|t| [t[0] + 8, t[1] + 8, t[2] + 8]));
        let m = MeshShape::new(v, t).unwrap();
        assert_eq!(m.shells().len(), 2);
        assert!(m.contains_point(&Point::new(5.2, 0.0, 0.0)));
    }
}
