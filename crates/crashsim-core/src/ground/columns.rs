//! The terrain's triangles binned in columns seen from above, for the ground point under a
//! world point: a vertical ray meets only triangles whose (x, y) extent holds the point, and
//! those are all in the point's column. On a fine terrain this finds the ground under a wheel
//! in a few triangle tests instead of a descent through the mesh's tree (which cost 40 % of a
//! run on 1 m triangles: benches/README.md, "Terrain against the plane").

use super::upward_normal;
use crate::math::{Point, Real, Vector};
use crate::shape::MeshShape;

/// Columns per triangle aimed at: one, so on a regular grid (two triangles a cell) a column
/// is about 0.7 of a cell wide. Measured on benches/terrain_speed.py's 1 m grid
/// (`profile_spec`, 2 s): 0.5 column per triangle with the grid on the terrain's corner (a
/// column a cell wide, holding 8-18 triangles) 20 ms; with the offset below, 1 or 2 columns
/// per triangle 16 ms, 8 columns 23 ms (the entries no longer stay in cache).
const COLUMNS_PER_TRIANGLE: Real = 1.0;
/// The grid starts this fraction of a column before the terrain's box (1/pi): a terrain laid
/// out on round coordinates (a regular grid from its corner) then has no triangle edge on a
/// column's edge, where the margin would put its triangles into the next column too.
const GRID_OFFSET: Real = std::f64::consts::FRAC_1_PI;
/// Most columns a terrain gets (16 MiB of column starts).
const MAX_COLUMNS: usize = 1 << 22;
/// Most column entries per triangle, summed over the terrain, before the columns are given up
/// for the tree (a terrain of a few large triangles among many small ones, whose large ones
/// would fill every column).
const MAX_ENTRIES_PER_TRIANGLE: usize = 16;

/// A terrain's triangles by column: a regular grid over the terrain's (x, y) box, each column
/// listing (in ascending order) every triangle whose (x, y) extent, widened by `margin`,
/// reaches into it.
#[derive(Debug)]
pub(crate) struct Columns {
    /// The grid's corner (x, y; m, world): [`GRID_OFFSET`] of a column before the terrain
    /// box's least corner.
    origin: [Real; 2],
    /// A column's width along x and y (m).
    width: [Real; 2],
    /// Columns along x and y.
    count: [usize; 2],
    /// Column k's triangles are `entries[starts[k]..starts[k + 1]]`; `k = i * count[1] + j`.
    starts: Vec<u32>,
    entries: Vec<u32>,
    /// Each triangle's upward unit normal ([`upward_normal`]), computed once: the square root
    /// and division per query cost 4 % of a run on the bumpy slope.
    normals: Vec<Option<Vector>>,
    /// How far (m) a triangle's (x, y) extent is widened: a ray's hit can fall outside it by
    /// rounding only (about 1e-16 of the coordinates), and this is many times that.
    margin: Real,
}

impl Columns {
    /// The columns of `mesh`'s triangles; None when they would take more memory than
    /// [`MAX_ENTRIES_PER_TRIANGLE`] allows (the tree is used then).
    pub(crate) fn new(mesh: &MeshShape) -> Option<Columns> {
        let b = mesh.aabb();
        let n = mesh.triangles().len();
        let (w, h) = (b.maxs.x - b.mins.x, b.maxs.y - b.mins.y);
        if n == 0 || !(w > 0.0 && h > 0.0) {
            return None;
        }
        let wanted = ((n as Real) * COLUMNS_PER_TRIANGLE).clamp(1.0, MAX_COLUMNS as Real);
        let side = (w * h / wanted).sqrt();
        // One column more than the box needs along each axis, for the offset.
        let along = |extent: Real| ((extent / side).ceil() as usize).clamp(1, MAX_COLUMNS) + 1;
        let (nx, ny) = (along(w), along(h));
        if nx.saturating_mul(ny) > MAX_COLUMNS {
            return None;
        }
        let largest = [b.mins.x, b.mins.y, b.maxs.x, b.maxs.y]
            .iter()
            .fold(0.0, |m: Real, v| m.max(v.abs()));
        let width = [w / (nx - 1) as Real, h / (ny - 1) as Real];
        let mut columns = Columns {
            origin: [
                b.mins.x - GRID_OFFSET * width[0],
                b.mins.y - GRID_OFFSET * width[1],
            ],
            width,
            count: [nx, ny],
            starts: vec![0; nx * ny + 1],
            entries: Vec::new(),
            normals: Vec::new(),
            margin: 1e-9 * (1.0 + largest),
        };
        // Two passes: count each column's triangles, then place them (in triangle order).
        let mut total = 0usize;
        for t in 0..n as u32 {
            let ([i0, i1], [j0, j1]) = columns.span(mesh.triangle(t));
            for i in i0..=i1 {
                for j in j0..=j1 {
                    columns.starts[i * ny + j + 1] += 1;
                }
            }
            total += (i1 - i0 + 1) * (j1 - j0 + 1);
            if total > MAX_ENTRIES_PER_TRIANGLE * n + 1024 || total > u32::MAX as usize {
                return None;
            }
        }
        for k in 0..nx * ny {
            columns.starts[k + 1] += columns.starts[k];
        }
        let mut next: Vec<u32> = columns.starts[..nx * ny].to_vec();
        columns.entries = vec![0; total];
        for t in 0..n as u32 {
            let ([i0, i1], [j0, j1]) = columns.span(mesh.triangle(t));
            for i in i0..=i1 {
                for j in j0..=j1 {
                    let slot = &mut next[i * ny + j];
                    columns.entries[*slot as usize] = t;
                    *slot += 1;
                }
            }
        }
        columns.normals = (0..n as u32)
            .map(|t| upward_normal(mesh.triangle(t)))
            .collect();
        Some(columns)
    }

    /// Triangle `t`'s upward unit normal; None for a degenerate triangle.
    pub(crate) fn normal(&self, t: u32) -> Option<Vector> {
        self.normals[t as usize]
    }

    /// The column index along x (`axis` 0) or y (1) of coordinate `v`, clamped to the grid.
    /// It never decreases as `v` grows, so a point inside a widened extent is in a column the
    /// extent's ends span.
    fn index(&self, axis: usize, v: Real) -> usize {
        let k = ((v - self.origin[axis]) / self.width[axis]).floor();
        if k >= 0.0 {
            (k as usize).min(self.count[axis] - 1)
        } else {
            0
        }
    }

    /// The columns (first and last along x, along y) triangle `tri`'s widened extent reaches.
    fn span(&self, tri: [Point; 3]) -> ([usize; 2], [usize; 2]) {
        let [a, b, c] = tri;
        let m = self.margin;
        (
            [
                self.index(0, a.x.min(b.x).min(c.x) - m),
                self.index(0, a.x.max(b.x).max(c.x) + m),
            ],
            [
                self.index(1, a.y.min(b.y).min(c.y) - m),
                self.index(1, a.y.max(b.y).max(c.y) + m),
            ],
        )
    }

    /// The nearest hit of the vertical ray down from `top` through (p.x, p.y) on `mesh`
    /// within `depth` (m), as (distance from `top`, triangle); ties go to the lower triangle
    /// index. The triangles cast against include every one whose widened (x, y) extent holds
    /// the point: every triangle the ray can meet.
    pub(crate) fn hit_below(
        &self,
        mesh: &MeshShape,
        p: &Point,
        top: Real,
        depth: Real,
    ) -> Option<(Real, u32)> {
        let m = self.margin;
        let (lo, hi) = (mesh.aabb().mins, mesh.aabb().maxs);
        if p.x < lo.x - m || p.x > hi.x + m || p.y < lo.y - m || p.y > hi.y + m {
            return None;
        }
        let k = self.index(0, p.x) * self.count[1] + self.index(1, p.y);
        let from = Point::new(p.x, p.y, top);
        let mut best: Option<(Real, u32)> = None;
        for &t in &self.entries[self.starts[k] as usize..self.starts[k + 1] as usize] {
            keep_nearer(&mut best, mesh, t, &from, depth, m);
        }
        best
    }
}

/// Casts the vertical ray down from `from` at triangle `t` of `mesh` when the triangle's
/// (x, y) extent, widened by `margin` (m), holds the ray, and keeps in `best` the nearer of
/// its hit and `best` (distance down from `from`, triangle; ties to the lower index, so the
/// answer does not depend on the order the triangles come in); `depth` (m) is the reach when
/// there is no hit yet.
pub(crate) fn keep_nearer(
    best: &mut Option<(Real, u32)>,
    mesh: &MeshShape,
    t: u32,
    from: &Point,
    depth: Real,
    margin: Real,
) {
    let tri = mesh.triangle(t);
    if !extent_holds(tri, from, margin) {
        return;
    }
    let reach = best.map_or(depth, |(d, _)| d);
    if let Some(toi) = cast_down(tri, from, reach) {
        if best.is_none_or(|(d, bt)| toi < d || (toi == d && t < bt)) {
            *best = Some((toi, t));
        }
    }
}

/// Whether triangle `tri`'s (x, y) extent, widened by `margin` (m), holds (p.x, p.y): the
/// test before a vertical ray is cast against the triangle.
pub(crate) fn extent_holds(tri: [Point; 3], p: &Point, margin: Real) -> bool {
    let [a, b, c] = tri;
    p.x >= a.x.min(b.x).min(c.x) - margin
        && p.x <= a.x.max(b.x).max(c.x) + margin
        && p.y >= a.y.min(b.y).min(c.y) - margin
        && p.y <= a.y.max(b.y).max(c.y) + margin
}

/// The distance (m) down from `from` along -z to triangle `tri` (either side), if within
/// `reach`. The arithmetic is parry's ray-triangle cast (Triangle::cast_local_ray: the
/// normal n = ab x ac, the ray's side of the plane, the barycentric tests, t / |d|) with the
/// direction's zero components taken out, so it gives the same bits; it skips the unit normal
/// parry also computes (a square root and three divisions), which a vertical query discards.
/// The core test against parry's cast on every triangle keeps the two equal.
fn cast_down(tri: [Point; 3], from: &Point, reach: Real) -> Option<Real> {
    let [a, b, c] = tri;
    let (ab, ac) = (b - a, c - a);
    let n = ab.cross(&ac);
    // d = n . (0, 0, -1)
    let d = -n.z;
    if d == 0.0 {
        return None;
    }
    let ap = from - a;
    let t = ap.dot(&n);
    if (t < 0.0 && d < 0.0) || (t > 0.0 && d > 0.0) {
        return None;
    }
    let d = d.abs();
    // With e = -(0, 0, -1) x ap = (-ap.y, ap.x, 0): the barycentric numerators ac . e and
    // -(ab . e), the signs flipped when the ray meets the triangle's back.
    let (cv, cw) = (ac.y * ap.x - ac.x * ap.y, ab.x * ap.y - ab.y * ap.x);
    let (v, w) = if t < 0.0 { (-cv, -cw) } else { (cv, cw) };
    if v < 0.0 || v > d || w < 0.0 || v + w > d {
        return None;
    }
    let toi = if t < 0.0 { -t } else { t } * (1.0 / d);
    (toi <= reach).then_some(toi)
}

#[cfg(test)]
mod tests {
    use rand::rngs::SmallRng;
    use rand::{Rng, SeedableRng};

    use std::sync::Arc;

    use parry3d_f64::query::{Ray, RayCast};
    use parry3d_f64::shape::Triangle;

    use super::*;
    use crate::ground::tree_hit_below;

    /// A bumpy 30 x 20 grid of 1 m cells on round coordinates, a bridge (a second sheet 3 m
    /// above part of it), a vertical wall, and random triangles large and small.
    fn layered_terrain(rng: &mut SmallRng) -> MeshShape {
        let mut v = Vec::new();
        let mut t = Vec::new();
        let (nx, ny) = (31u32, 21u32);
        for i in 0..nx {
            for j in 0..ny {
                let z = 0.1 * i as Real + rng.random_range(-0.05..0.05);
                v.push(Point::new(i as Real - 10.0, j as Real - 5.0, z));
            }
        }
        for i in 0..nx - 1 {
            for j in 0..ny - 1 {
                let (a, b) = (i * ny + j, (i + 1) * ny + j);
                t.push([a, b, b + 1]);
                t.push([a, b + 1, a + 1]);
            }
        }
        let quad = |v: &mut Vec<Point>, t: &mut Vec<[u32; 3]>, c: [Point; 4]| {
            let k = v.len() as u32;
            v.extend(c);
            t.push([k, k + 1, k + 2]);
            t.push([k, k + 2, k + 3]);
        };
        let z = 5.0;
        quad(
            &mut v,
            &mut t,
            [
                Point::new(2.0, -5.0, z),
                Point::new(6.0, -5.0, z),
                Point::new(6.0, 15.0, z),
                Point::new(2.0, 15.0, z),
            ],
        );
        quad(
            &mut v,
            &mut t,
            [
                Point::new(-4.0, 0.0, 0.0),
                Point::new(-4.0, 8.0, 0.0),
                Point::new(-4.0, 8.0, 4.0),
                Point::new(-4.0, 0.0, 4.0),
            ],
        );
        for _ in 0..30 {
            let size = if rng.random_bool(0.2) { 15.0 } else { 0.3 };
            let c = Point::new(
                rng.random_range(-10.0..20.0),
                rng.random_range(-5.0..15.0),
                0.0,
            );
            let k = v.len() as u32;
            for _ in 0..3 {
                let d = Vector::new(
                    rng.random_range(-size..size),
                    rng.random_range(-size..size),
                    rng.random_range(0.0..6.0),
                );
                v.push(c + d);
            }
            t.push([k, k + 1, k + 2]);
        }
        MeshShape::new(v, t).expect("a valid mesh")
    }

    /// The nearest hit over every triangle of the mesh, ties to the lower index.
    fn every_hit_below(mesh: &MeshShape, p: &Point, top: Real, depth: Real) -> Option<(Real, u32)> {
        let ray = Ray::new(Point::new(p.x, p.y, top), -Vector::z());
        (0..mesh.triangles().len() as u32)
            .filter_map(|t| {
                let [a, b, c] = mesh.triangle(t);
                Triangle::new(a, b, c)
                    .cast_local_ray(&ray, depth, false)
                    .map(|d| (d, t))
            })
            .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)))
    }

    #[test]
    fn the_columns_and_the_tree_find_the_nearest_hit_of_all_triangles_bit_for_bit() {
        let mut rng = SmallRng::seed_from_u64(11);
        for _ in 0..4 {
            let mesh = layered_terrain(&mut rng);
            let columns = Columns::new(&mesh).expect("columns for a layered terrain");
            let top = mesh.aabb().maxs.z + 1.0;
            let depth = top - mesh.aabb().mins.z + 1.0;
            // Random points (some off the terrain), every vertex and every edge's midpoint:
            // the points where the ray meets several triangles at once.
            let mut points: Vec<Point> = (0..3000)
                .map(|_| {
                    Point::new(
                        rng.random_range(-12.0..37.0),
                        rng.random_range(-7.0..33.0),
                        0.0,
                    )
                })
                .collect();
            points.extend(mesh.vertices().iter().copied());
            for tri in mesh.triangles() {
                let [a, b, c] = tri.map(|k| mesh.vertices()[k as usize]);
                points.extend(
                    [a, b, c]
                        .iter()
                        .zip([b, c, a])
                        .map(|(p, q)| nalgebra::center(p, &q)),
                );
            }
            let mut hits = 0;
            for p in &points {
                let every = every_hit_below(&mesh, p, top, depth);
                let fast = columns.hit_below(&mesh, p, top, depth);
                let tree = tree_hit_below(&mesh, p, top, depth);
                let bits = |h: Option<(Real, u32)>| h.map(|(d, t)| (d.to_bits(), t));
                assert_eq!(bits(fast), bits(every), "columns at {p:?}");
                assert_eq!(bits(tree), bits(every), "tree at {p:?}");
                hits += usize::from(fast.is_some());
            }
            assert!(
                hits > points.len() / 2,
                "most points are over the terrain: {hits}"
            );
        }
    }

    #[test]
    fn the_vertical_cast_gives_parrys_bits_on_every_kind_of_triangle() {
        // Random triangles of every orientation (up, down, steep, vertical, slivers), rays
        // through random points, through their vertices, along their edges and near their
        // plane, within and past the reach.
        let mut rng = SmallRng::seed_from_u64(5);
        let mut compared = [0usize; 2];
        for case in 0..20_000 {
            let mut corner = || {
                Point::new(
                    rng.random_range(-3.0..3.0),
                    rng.random_range(-3.0..3.0),
                    rng.random_range(-1.0..1.0),
                )
            };
            let mut tri = [corner(), corner(), corner()];
            match case % 5 {
                1 => tri[2].z = tri[0].z,                         // level edge
                2 => (tri[1].x, tri[1].y) = (tri[0].x, tri[0].y), // vertical edge
                3 => tri[2] = nalgebra::center(&tri[0], &tri[1]), // degenerate
                _ => {}
            }
            let [a, b, c] = tri;
            let (u, v) = (rng.random_range(-0.2..1.2), rng.random_range(-0.2..1.2));
            let mut p = a + (b - a) * u + (c - a) * v;
            match case % 7 {
                0 => p = [a, b, c][case % 3],
                1 => p = nalgebra::center(&a, &b),
                _ => {}
            }
            let top = rng.random_range(-1.5..2.0);
            let reach = rng.random_range(0.0..4.0);
            let from = Point::new(p.x, p.y, top);
            let ray = Ray::new(from, -Vector::z());
            let parry = Triangle::new(a, b, c).cast_local_ray(&ray, reach, false);
            let ours = cast_down(tri, &from, reach);
            assert_eq!(
                ours.map(Real::to_bits),
                parry.map(Real::to_bits),
                "case {case}: {tri:?} from {from:?}"
            );
            compared[usize::from(parry.is_some())] += 1;
        }
        assert!(compared[0] > 2000 && compared[1] > 2000, "{compared:?}");
    }

    #[test]
    fn a_terrain_whose_columns_would_be_too_large_is_searched_by_its_tree() {
        // 40 triangles across the whole box among 1,000 small ones: each large one is in every
        // column, past the entries allowed.
        let mut v = Vec::new();
        let mut t = Vec::new();
        for k in 0..1000 {
            let (x, y) = ((k % 40) as Real, (k / 40) as Real);
            let n = v.len() as u32;
            v.extend([
                Point::new(x, y, 0.0),
                Point::new(x + 0.5, y, 0.0),
                Point::new(x, y + 0.5, 0.0),
            ]);
            t.push([n, n + 1, n + 2]);
        }
        for k in 0..40 {
            let n = v.len() as u32;
            let z = 1.0 + k as Real;
            v.extend([
                Point::new(-1.0, -1.0, z),
                Point::new(90.0, -1.0, z),
                Point::new(-1.0, 60.0, z),
            ]);
            t.push([n, n + 1, n + 2]);
        }
        let mesh = Arc::new(MeshShape::new(v, t).expect("a valid mesh"));
        assert!(Columns::new(&mesh).is_none());
        let ground = crate::ground::Ground::terrain(mesh).expect("a terrain");
        let g = ground
            .below(&Point::new(10.2, 5.1, 0.0))
            .expect("ground there");
        assert_eq!(g.point.z, 40.0, "the highest of the large triangles");
    }
}
