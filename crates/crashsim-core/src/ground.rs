//! The ground: the plane z = h or a terrain mesh, with friction zones.
//!
//! The ground answers, for a world point, the ground point straight below it (or above it,
//! when the point is underground), the ground's upward unit normal there and the tyre-road
//! friction. Gravity (9.80665 m/s^2 along -z) acts in a world that has a ground.

use std::sync::Arc;

use crate::bvh::MAX_DEPTH;
use crate::error::{require_coordinate, require_finite, Error, Place, Result};
use crate::math::{Point, Real, Vector};
use crate::shape::MeshShape;

mod columns;
use columns::Columns;

/// Default tyre-road friction outside every zone: 0.8, dry asphalt (docs/ground.md;
/// the sourced table of surfaces is the Python package's `ground_surfaces`).
pub const DEFAULT_TYRE_FRICTION: Real = 0.8;
/// Default friction of a vehicle's body sliding on the road (roof, side, underbody): 0.45,
/// inside the 0.4-0.5 reconstruction texts give (docs/ground.md).
pub const DEFAULT_BODY_FRICTION: Real = 0.45;
/// Largest friction coefficient accepted for a surface.
const MAX_FRICTION: Real = 2.0;

/// What the ground is made of.
#[derive(Clone, Debug)]
pub enum Surface {
    /// The horizontal plane z = height (m).
    Plane {
        /// Height of the plane (m).
        height: Real,
    },
    /// A terrain mesh in world coordinates (m): its upper surface, seen from above, is the
    /// ground. A point with no terrain straight above or below it is off the terrain.
    Terrain(Arc<MeshShape>),
}

/// A ground polygon (seen from above) with its own tyre-road friction.
#[derive(Clone, Debug, PartialEq)]
pub struct FrictionZone {
    /// The polygon's corners (x, y) in order (m, world), at least 3, not self-crossing.
    pub polygon: Vec<[Real; 2]>,
    /// Tyre-road friction inside it, in (0, 2].
    pub friction: Real,
}

impl FrictionZone {
    /// The zone's own rules: its friction in (0, 2] and a polygon of at least 3 finite
    /// corners that does not cross itself (a ground also refuses zones that overlap).
    pub fn check(&self) -> Result<()> {
        check_friction("friction", self.friction)?;
        check_polygon(&self.polygon)
    }
}

/// The ground point under (or over) a world point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GroundPoint {
    /// The point on the ground (m, world).
    pub point: Point,
    /// The ground's upward unit normal there.
    pub normal: Vector,
}

/// A plane that bounds the ground from above over a region seen from above: every ground
/// point `g` whose (x, y) lies in the region has `normal . g <= offset` (m). `normal` is a
/// unit vector with a positive z, so a point `p` with `normal . p > offset` lies above the
/// ground straight below it (they differ by a vertical offset only).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GroundBound {
    /// Unit normal of the bounding plane (z > 0).
    pub normal: Vector,
    /// Largest `normal . g` over the region's ground points (m); minus infinity when the
    /// region has no ground (off the terrain).
    pub offset: Real,
}

/// The least z of the terrain's mean normal over a box that the bound over it takes as its
/// plane's normal: a steeper mean (a wall's faces) gives a poor bound, and z is used.
const MIN_BOUND_NORMAL_Z: Real = 0.2;

/// The ground of a world.
#[derive(Clone, Debug)]
pub struct Ground {
    surface: Surface,
    /// A terrain's triangles by column (None for the plane, or for a terrain whose columns
    /// would be too large: the mesh's tree is searched then).
    columns: Option<Arc<Columns>>,
    zones: Vec<FrictionZone>,
    tyre_friction: Real,
    body_friction: Real,
}

impl Default for Ground {
    fn default() -> Self {
        Ground::plane(0.0).expect("the plane z = 0 is valid")
    }
}

/// A tyre-road friction coefficient's rule: finite, in (0, 2]; the error names it `name`.
pub fn check_friction(name: &str, mu: Real) -> Result<()> {
    check_coefficient(name, mu, "dry asphalt about 0.8")
}

/// The rule of a body's friction sliding on the ground (the ground's body friction, or a
/// body's own: a person's clothing): finite, in (0, 2]; the error names it `name`.
pub fn check_body_friction(name: &str, mu: Real) -> Result<()> {
    check_coefficient(
        name,
        mu,
        "a car body on asphalt about 0.45, a clothed person about 0.66",
    )
}

/// Finite and in (0, 2]; `typical` says what values are usual.
fn check_coefficient(name: &str, mu: Real, typical: &str) -> Result<()> {
    require_finite(name, mu)?;
    if !(mu > 0.0 && mu <= MAX_FRICTION) {
        return Err(Error::parameter(
            name,
            mu,
            &format!("a friction coefficient must lie in (0, 2] ({typical})"),
        ));
    }
    Ok(())
}

impl Ground {
    /// The plane z = `height` (m) with the default frictions.
    pub fn plane(height: Real) -> Result<Ground> {
        require_coordinate("ground height", height)?;
        Ok(Ground {
            surface: Surface::Plane { height },
            columns: None,
            zones: Vec::new(),
            tyre_friction: DEFAULT_TYRE_FRICTION,
            body_friction: DEFAULT_BODY_FRICTION,
        })
    }

    /// A terrain mesh (world coordinates, m) with the default frictions.
    pub fn terrain(mesh: Arc<MeshShape>) -> Result<Ground> {
        let b = mesh.aabb();
        for x in b.mins.iter().chain(b.maxs.iter()) {
            require_coordinate("a terrain vertex coordinate", *x)?;
        }
        if b.maxs.x - b.mins.x <= 0.0 || b.maxs.y - b.mins.y <= 0.0 {
            return Err(Error::mesh(
                "the terrain mesh has no extent seen from above: give a surface spread in x and y",
            ));
        }
        Ok(Ground {
            columns: Columns::new(&mesh).map(Arc::new),
            surface: Surface::Terrain(mesh),
            zones: Vec::new(),
            tyre_friction: DEFAULT_TYRE_FRICTION,
            body_friction: DEFAULT_BODY_FRICTION,
        })
    }

    /// Sets the tyre-road friction outside every zone and the body-ground friction.
    pub fn with_friction(mut self, tyre: Real, body: Real) -> Result<Ground> {
        check_friction("tyre-road friction", tyre)?;
        check_body_friction("body-ground friction", body)?;
        self.tyre_friction = tyre;
        self.body_friction = body;
        Ok(self)
    }

    /// Adds friction zones: each a simple polygon; zones may share edges but not overlap.
    pub fn with_zones(mut self, zones: Vec<FrictionZone>) -> Result<Ground> {
        for (k, z) in zones.iter().enumerate() {
            z.check().map_err(|e| e.at(Place::Zone(k)))?;
        }
        for i in 0..zones.len() {
            for j in 0..i {
                if polygons_overlap(&zones[i].polygon, &zones[j].polygon) {
                    return Err(Error::invalid(
                        "they overlap: a point of the road must have one friction (split them \
                         so they only share edges)",
                    )
                    .at(Place::Zones(j, i)));
                }
            }
        }
        self.zones = zones;
        Ok(self)
    }

    /// Tyre-road friction outside every zone.
    pub fn tyre_friction(&self) -> Real {
        self.tyre_friction
    }

    /// The surface.
    pub fn surface(&self) -> &Surface {
        &self.surface
    }

    /// The friction zones.
    pub fn zones(&self) -> &[FrictionZone] {
        &self.zones
    }

    /// Body-ground friction.
    pub fn body_friction(&self) -> Real {
        self.body_friction
    }

    /// Tyre-road friction at (x, y): the zone's that holds the point (the first one for a
    /// point on a shared edge), else the default.
    pub fn tyre_friction_at(&self, x: Real, y: Real) -> Real {
        self.zones
            .iter()
            .find(|z| point_in_polygon(x, y, &z.polygon))
            .map_or(self.tyre_friction, |z| z.friction)
    }

    /// The ground point straight below (or above) world point `p`; None off the terrain.
    pub fn below(&self, p: &Point) -> Option<GroundPoint> {
        match &self.surface {
            Surface::Plane { height } => Some(GroundPoint {
                point: Point::new(p.x, p.y, *height),
                normal: Vector::z(),
            }),
            Surface::Terrain(mesh) => terrain_below(mesh, self.columns.as_deref(), p),
        }
    }

    /// A plane bounding the ground over the box `lo`..`hi` (x, y; m, world) from above: for a
    /// terrain, a plane along the mean slope of the triangles over the box (their area-weighted
    /// normal) moved up to the highest ground in the box (each triangle clipped to it); for the
    /// plane z = h, that plane. A body above it touches nothing in the box.
    pub fn bound_under(&self, lo: [Real; 2], hi: [Real; 2]) -> GroundBound {
        match &self.surface {
            Surface::Plane { height } => GroundBound {
                normal: Vector::z(),
                offset: *height,
            },
            Surface::Terrain(mesh) => terrain_bound(mesh, lo, hi),
        }
    }

    /// Height of the ground at (x, y) (m); None off the terrain.
    pub fn height_at(&self, x: Real, y: Real) -> Option<Real> {
        self.below(&Point::new(x, y, 0.0)).map(|g| g.point.z)
    }
}

/// The highest terrain point straight above or below `p` (a ray cast down from above the
/// terrain's box), with the upward normal of its triangle: found in `p`'s column when the
/// terrain has columns, else by a descent through the mesh's tree.
fn terrain_below(mesh: &MeshShape, columns: Option<&Columns>, p: &Point) -> Option<GroundPoint> {
    let top = mesh.aabb().maxs.z + 1.0;
    let depth = top - mesh.aabb().mins.z + 1.0;
    let (toi, normal) = match columns {
        Some(columns) => {
            let (toi, t) = columns.hit_below(mesh, p, top, depth)?;
            (toi, columns.normal(t)?)
        }
        None => {
            let (toi, t) = tree_hit_below(mesh, p, top, depth)?;
            (toi, upward_normal(mesh.triangle(t))?)
        }
    };
    Some(GroundPoint {
        point: Point::new(p.x, p.y, top - toi),
        normal,
    })
}

/// The unit normal of triangle `tri` on its upper side (n.z >= 0); None for a degenerate one.
fn upward_normal(tri: [Point; 3]) -> Option<Vector> {
    let [a, b, c] = tri;
    let mut normal = (b - a).cross(&(c - a));
    let len = normal.norm();
    if len == 0.0 || !len.is_finite() {
        return None;
    }
    normal /= len;
    if normal.z < 0.0 {
        normal = -normal;
    }
    Some(normal)
}

/// [`Columns::hit_below`] by a descent through the mesh's tree. The ray is vertical, so a box
/// it can meet is one whose (x, y) extent holds (p.x, p.y) and whose top is within reach below
/// `top`, and a triangle is cast against only when its (x, y) extent, widened by a margin far
/// above rounding, holds the point. The reach is widened by the margin too: a triangle that
/// ties with the best hit at a vertex on its box's top is still cast against, so the tie goes
/// to the lower index whatever the order of the descent.
fn tree_hit_below(mesh: &MeshShape, p: &Point, top: Real, depth: Real) -> Option<(Real, u32)> {
    let from = Point::new(p.x, p.y, top);
    let margin = 1e-9 * (1.0 + p.x.abs().max(p.y.abs()));
    let nodes = mesh.bvh().nodes();
    let mut stack = [0u32; MAX_DEPTH];
    let mut n = 1;
    let mut best: Option<(Real, u32)> = None;
    while n > 0 {
        n -= 1;
        let node = &nodes[stack[n] as usize];
        let reach = best.map_or(depth, |(d, _)| d);
        let b = &node.aabb;
        if p.x < b.mins.x
            || p.x > b.maxs.x
            || p.y < b.mins.y
            || p.y > b.maxs.y
            || top - b.maxs.z > reach + margin
        {
            continue;
        }
        if node.is_leaf() {
            for &t in mesh.bvh().leaf_primitives(node) {
                columns::keep_nearer(&mut best, mesh, t, &from, depth, margin);
            }
        } else {
            let (l, r) = mesh.bvh().children(stack[n]);
            stack[n] = l;
            stack[n + 1] = r;
            n += 2;
        }
    }
    best
}

/// The terrain's [`GroundBound`] over the box `lo`..`hi` seen from above (see
/// [`Ground::bound_under`]).
fn terrain_bound(mesh: &MeshShape, lo: [Real; 2], hi: [Real; 2]) -> GroundBound {
    // The triangles over the box (their boxes overlap it), and their mean upward normal
    // weighted by area: the mean slope, so bumps cost only their height.
    let mut inside = Vec::new();
    let mut sum = Vector::zeros();
    let nodes = mesh.bvh().nodes();
    let mut stack = [0u32; MAX_DEPTH];
    let mut n = 1;
    while n > 0 {
        n -= 1;
        let node = &nodes[stack[n] as usize];
        let b = &node.aabb;
        if b.maxs.x < lo[0] || b.mins.x > hi[0] || b.maxs.y < lo[1] || b.mins.y > hi[1] {
            continue;
        }
        if node.is_leaf() {
            for &t in mesh.bvh().leaf_primitives(node) {
                let [a, b, c] = mesh.triangle(t);
                let (tlo, thi) = (
                    a.coords.inf(&b.coords).inf(&c.coords),
                    a.coords.sup(&b.coords).sup(&c.coords),
                );
                if thi.x < lo[0] || tlo.x > hi[0] || thi.y < lo[1] || tlo.y > hi[1] {
                    continue;
                }
                let area = (b - a).cross(&(c - a));
                sum += if area.z < 0.0 { -area } else { area };
                inside.push(t);
            }
        } else {
            let (l, r) = mesh.bvh().children(stack[n]);
            stack[n] = l;
            stack[n + 1] = r;
            n += 2;
        }
    }
    let normal = Some(sum)
        .filter(|s| s.norm() > 0.0)
        .map(|s| s.normalize())
        .filter(|n| n.z >= MIN_BOUND_NORMAL_Z)
        .unwrap_or_else(Vector::z);
    // The highest ground along it: each triangle's part over the box.
    let mut offset = Real::NEG_INFINITY;
    let mut poly = [Point::origin(); CLIPPED_MAX];
    for t in inside {
        let k = clip_to_box(mesh.triangle(t), lo, hi, &mut poly);
        for v in &poly[..k] {
            offset = offset.max(normal.dot(&v.coords));
        }
    }
    GroundBound { normal, offset }
}

/// Most corners of a triangle clipped by the four sides of a box: 3 + 4.
const CLIPPED_MAX: usize = 7;

/// The part of triangle `tri` inside the vertical prism over the box `lo`..`hi` (x, y), as a
/// convex polygon written to `out`; returns its number of corners (0: no part inside).
fn clip_to_box(
    tri: [Point; 3],
    lo: [Real; 2],
    hi: [Real; 2],
    out: &mut [Point; CLIPPED_MAX],
) -> usize {
    let mut a = [Point::origin(); CLIPPED_MAX];
    a[..3].copy_from_slice(&tri);
    let mut na = 3;
    // Each side: (axis, bound, keep the side where coordinate >= bound).
    for (axis, bound, above) in [
        (0, lo[0], true),
        (0, hi[0], false),
        (1, lo[1], true),
        (1, hi[1], false),
    ] {
        let inside = |p: &Point| {
            if above {
                p[axis] >= bound
            } else {
                p[axis] <= bound
            }
        };
        let mut nb = 0;
        for i in 0..na {
            let (p, q) = (a[i], a[(i + 1) % na]);
            let (pin, qin) = (inside(&p), inside(&q));
            if pin {
                out[nb] = p;
                nb += 1;
            }
            if pin != qin {
                // The edge crosses the side: the crossing point (p and q differ along axis).
                let s = (bound - p[axis]) / (q[axis] - p[axis]);
                let mut c = p + (q - p) * s;
                c[axis] = bound;
                out[nb] = c;
                nb += 1;
            }
        }
        a[..nb].copy_from_slice(&out[..nb]);
        na = nb;
        if na == 0 {
            return 0;
        }
    }
    out[..na].copy_from_slice(&a[..na]);
    na
}

/// Crossing-number test; points on an edge count as inside.
pub fn point_in_polygon(x: Real, y: Real, poly: &[[Real; 2]]) -> bool {
    let n = poly.len();
    let mut inside = false;
    for i in 0..n {
        let [x1, y1] = poly[i];
        let [x2, y2] = poly[(i + 1) % n];
        // On the edge?
        let cross = (x2 - x1) * (y - y1) - (y2 - y1) * (x - x1);
        if cross == 0.0 && x >= x1.min(x2) && x <= x1.max(x2) && y >= y1.min(y2) && y <= y1.max(y2)
        {
            return true;
        }
        if (y1 > y) != (y2 > y) && x < x1 + (y - y1) * (x2 - x1) / (y2 - y1) {
            inside = !inside;
        }
    }
    inside
}

/// Orientation of the triangle (a, b, c): > 0 counter-clockwise.
fn orient(a: [Real; 2], b: [Real; 2], c: [Real; 2]) -> Real {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// True when the segments cross at a point inside both (not at an end, not collinear).
fn segments_cross(a: [Real; 2], b: [Real; 2], c: [Real; 2], d: [Real; 2]) -> bool {
    let (o1, o2) = (orient(a, b, c), orient(a, b, d));
    let (o3, o4) = (orient(c, d, a), orient(c, d, b));
    o1 * o2 < 0.0 && o3 * o4 < 0.0
}

fn check_polygon(poly: &[[Real; 2]]) -> Result<()> {
    if poly.len() < 3 {
        return Err(Error::invalid(format!(
            "it has {} corners: a polygon needs at least 3",
            poly.len()
        )));
    }
    if poly.iter().flatten().any(|v| !v.is_finite()) {
        return Err(Error::invalid(
            "it has a corner that is not a finite number",
        ));
    }
    let n = poly.len();
    // Crossing edges first: a symmetric bow-tie also has no signed area, and "its corners
    // are in a line" misled.
    for i in 0..n {
        for j in i + 1..n {
            if j == i + 1 || (i == 0 && j == n - 1) {
                continue;
            }
            let (a, b) = (poly[i], poly[(i + 1) % n]);
            let (c, d) = (poly[j], poly[(j + 1) % n]);
            if segments_cross(a, b, c, d) {
                return Err(Error::invalid(format!(
                    "it crosses itself (edges {i} and {j}): give its corners in order around it"
                )));
            }
        }
    }
    let area: Real = (0..n)
        .map(|i| orient([0.0, 0.0], poly[i], poly[(i + 1) % n]))
        .sum();
    if area == 0.0 {
        return Err(Error::invalid(
            "it encloses no area (its corners are in a line)",
        ));
    }
    Ok(())
}

/// A point strictly inside a simple polygon: the midpoint of an edge moved a hair inward.
fn interior_point(poly: &[[Real; 2]]) -> [Real; 2] {
    let n = poly.len();
    let area: Real = (0..n)
        .map(|i| orient([0.0, 0.0], poly[i], poly[(i + 1) % n]))
        .sum();
    let (a, b) = (poly[0], poly[1]);
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len = (dx * dx + dy * dy).sqrt();
    // The inward normal: left of the edge for a counter-clockwise polygon.
    let s = if area > 0.0 { 1.0 } else { -1.0 };
    let h = 1e-6 * len;
    [
        0.5 * (a[0] + b[0]) - s * dy / len * h,
        0.5 * (a[1] + b[1]) + s * dx / len * h,
    ]
}

/// True when two simple polygons share interior points.
fn polygons_overlap(p: &[[Real; 2]], q: &[[Real; 2]]) -> bool {
    let strictly_inside = |x: [Real; 2], poly: &[[Real; 2]]| {
        point_in_polygon(x[0], x[1], poly) && {
            // not on an edge of poly
            let n = poly.len();
            (0..n).all(|i| {
                let (a, b) = (poly[i], poly[(i + 1) % n]);
                orient(a, b, x) != 0.0
                    || x[0] < a[0].min(b[0])
                    || x[0] > a[0].max(b[0])
                    || x[1] < a[1].min(b[1])
                    || x[1] > a[1].max(b[1])
            })
        }
    };
    for i in 0..p.len() {
        for j in 0..q.len() {
            let (a, b) = (p[i], p[(i + 1) % p.len()]);
            let (c, d) = (q[j], q[(j + 1) % q.len()]);
            if segments_cross(a, b, c, d) {
                return true;
            }
        }
    }
    p.iter().any(|&v| strictly_inside(v, q))
        || q.iter().any(|&v| strictly_inside(v, p))
        || strictly_inside(interior_point(p), q)
        || strictly_inside(interior_point(q), p)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x0: Real, y0: Real, s: Real) -> Vec<[Real; 2]> {
        vec![[x0, y0], [x0 + s, y0], [x0 + s, y0 + s], [x0, y0 + s]]
    }

    #[test]
    fn zones_give_their_friction_and_must_not_overlap() {
        let wet = FrictionZone {
            polygon: square(0.0, 0.0, 10.0),
            friction: 0.5,
        };
        let grass = FrictionZone {
            polygon: square(10.0, 0.0, 10.0), // shares an edge with the wet square
            friction: 0.35,
        };
        let g = Ground::plane(0.0)
            .unwrap()
            .with_zones(vec![wet.clone(), grass.clone()])
            .unwrap();
        assert_eq!(g.tyre_friction_at(5.0, 5.0), 0.5);
        assert_eq!(g.tyre_friction_at(15.0, 5.0), 0.35);
        assert_eq!(g.tyre_friction_at(25.0, 5.0), DEFAULT_TYRE_FRICTION);
        let overlapping = FrictionZone {
            polygon: square(5.0, 5.0, 10.0),
            friction: 0.55,
        };
        let err = Ground::plane(0.0)
            .unwrap()
            .with_zones(vec![wet.clone(), overlapping])
            .unwrap_err();
        assert!(err.to_string().contains("overlap"), "{err}");
        let same = Ground::plane(0.0)
            .unwrap()
            .with_zones(vec![wet.clone(), wet.clone()]);
        assert!(same.is_err());
        let inner = FrictionZone {
            polygon: square(2.0, 2.0, 1.0),
            friction: 0.3,
        };
        assert!(Ground::plane(0.0)
            .unwrap()
            .with_zones(vec![wet.clone(), inner])
            .is_err());
        let bowtie = FrictionZone {
            polygon: vec![[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]],
            friction: 0.5,
        };
        assert!(Ground::plane(0.0)
            .unwrap()
            .with_zones(vec![bowtie.clone()])
            .is_err());
        let bad_mu = FrictionZone {
            polygon: square(0.0, 0.0, 1.0),
            friction: -0.5,
        };
        // a ground refuses a zone with the zone's own rules, placed at its index
        let alone = bad_mu.check().unwrap_err();
        assert_eq!(alone.loc, [Place::Parameter("friction".into())]);
        let in_ground = Ground::plane(0.0)
            .unwrap()
            .with_zones(vec![wet.clone(), bad_mu])
            .unwrap_err();
        assert_eq!(in_ground, alone.at(Place::Zone(1)));
        assert!(bowtie.check().is_err() && wet.check().is_ok());
    }

    #[test]
    fn a_terrain_gives_its_height_and_normal_and_nothing_off_its_edge() {
        // A ramp: z = 0.1 x over 0 <= x, y <= 10.
        let v = vec![
            Point::new(0.0, 0.0, 0.0),
            Point::new(10.0, 0.0, 1.0),
            Point::new(10.0, 10.0, 1.0),
            Point::new(0.0, 10.0, 0.0),
        ];
        let mesh = MeshShape::new(v, vec![[0, 1, 2], [0, 2, 3]]).unwrap();
        let g = Ground::terrain(Arc::new(mesh)).unwrap();
        let p = g.below(&Point::new(4.0, 3.0, 5.0)).unwrap();
        assert!((p.point.z - 0.4).abs() < 1e-12);
        let n = Vector::new(-0.1, 0.0, 1.0).normalize();
        assert!((p.normal - n).norm() < 1e-12);
        assert!(g.below(&Point::new(-1.0, 3.0, 0.0)).is_none());
        assert!(
            g.below(&Point::new(4.0, 3.0, -2.0)).is_some(),
            "below the terrain too"
        );
    }

    #[test]
    fn the_bound_under_a_box_follows_the_mean_slope_up_to_the_highest_ground() {
        // The ramp z = 0.1 x: the bound over any box on it is the ramp's own plane.
        let v = vec![
            Point::new(0.0, 0.0, 0.0),
            Point::new(10.0, 0.0, 1.0),
            Point::new(10.0, 10.0, 1.0),
            Point::new(0.0, 10.0, 0.0),
        ];
        let ramp = Ground::terrain(Arc::new(
            MeshShape::new(v.clone(), vec![[0, 1, 2], [0, 2, 3]]).unwrap(),
        ))
        .unwrap();
        let b = ramp.bound_under([2.0, 3.0], [6.5, 4.0]);
        let n = Vector::new(-0.1, 0.0, 1.0).normalize();
        assert!((b.normal - n).norm() < 1e-12);
        assert!(
            b.offset.abs() < 1e-12,
            "the ramp's plane passes through the origin"
        );
        // A tent (ridge along y at x = 5, 1 m high): across the ridge the flanks' mean is
        // level and the bound goes through the ridge; over one flank it is the flank's plane.
        let mut tent = v;
        tent[1].z = 0.0;
        tent[2].z = 0.0;
        tent.push(Point::new(5.0, 0.0, 1.0));
        tent.push(Point::new(5.0, 10.0, 1.0));
        let tent = Ground::terrain(Arc::new(
            MeshShape::new(tent, vec![[0, 4, 5], [0, 5, 3], [4, 1, 2], [4, 2, 5]]).unwrap(),
        ))
        .unwrap();
        let across = tent.bound_under([3.0, 4.0], [8.0, 6.0]);
        assert!((across.normal - Vector::z()).norm() < 1e-12);
        assert!((across.offset - 1.0).abs() < 1e-12);
        let right = tent.bound_under([6.0, 4.0], [8.0, 6.0]);
        let n = Vector::new(0.2, 0.0, 1.0).normalize();
        assert!((right.normal - n).norm() < 1e-12);
        assert!((right.offset - n.dot(&Vector::new(5.0, 0.0, 1.0))).abs() < 1e-12);
        // Off the terrain there is no ground: nothing to bound.
        let off = tent.bound_under([20.0, 20.0], [21.0, 21.0]);
        assert_eq!(off.offset, Real::NEG_INFINITY);
        // The plane z = h is its own bound.
        let plane = Ground::plane(-2.5)
            .unwrap()
            .bound_under([0.0, 0.0], [1.0, 1.0]);
        assert_eq!((plane.normal, plane.offset), (Vector::z(), -2.5));
    }

    #[test]
    fn a_triangle_clipped_to_a_box_keeps_its_part_over_the_box() {
        // z = x over the triangle x, y >= 0, x + y <= 10.
        let tri = [
            Point::new(0.0, 0.0, 0.0),
            Point::new(10.0, 0.0, 10.0),
            Point::new(0.0, 10.0, 0.0),
        ];
        let mut poly = [Point::origin(); CLIPPED_MAX];
        let area = |p: &[Point]| {
            let n = p.len();
            0.5 * (0..n)
                .map(|i| {
                    orient(
                        [0.0, 0.0],
                        [p[i].x, p[i].y],
                        [p[(i + 1) % n].x, p[(i + 1) % n].y],
                    )
                })
                .sum::<Real>()
                .abs()
        };
        // A box wholly over it: the box itself, on the plane.
        let k = clip_to_box(tri, [2.0, 1.0], [4.0, 3.0], &mut poly);
        assert_eq!(k, 4);
        assert!((area(&poly[..k]) - 4.0).abs() < 1e-12);
        assert!(poly[..k].iter().all(|p| (p.z - p.x).abs() < 1e-12));
        // A box across the long edge: the part x + y <= 10 of [6, 9] x [2, 5], area 2, its
        // highest corner (8, 2, 8).
        let k = clip_to_box(tri, [6.0, 2.0], [9.0, 5.0], &mut poly);
        assert!((area(&poly[..k]) - 2.0).abs() < 1e-12);
        let top = poly[..k]
            .iter()
            .map(|p| p.z)
            .fold(Real::NEG_INFINITY, Real::max);
        assert!((top - 8.0).abs() < 1e-12);
        // A box beside it: nothing.
        assert_eq!(clip_to_box(tri, [11.0, 0.0], [12.0, 1.0], &mut poly), 0);
    }
}
