//! Contact geometry of an overlapping pair: the overlap region, the automatic normal (taken
//! early for a first exchange), the contact frame, the centroid, the struck faces, the overlap
//! width and the automatic depth of penetration sqrt(m'/k').

use super::{Pair, World, NORMAL_DEPTH, TIME_TOLERANCE};
use crate::bisect::bisect;
use crate::body::RigidBody;
use crate::contact::{
    CentroidMode, NormalMode, MAX_DEPTH_OF_PENETRATION, NORMAL_COLLAPSE, NORMAL_FOOTPRINT,
    NORMAL_PROBES, NORMAL_PROBE_RATIO, TYPICAL_DEPTH_OF_PENETRATION,
};
use crate::math::{Isometry, Matrix, Point, Real, Vector};
use crate::overlap::{overlap_areas, overlap_points, overlap_region, OverlapRegion};
use crate::shape::MeshShape;
use crate::stiffness::{crush_share, effective_mass, series_rate, Face};

/// The time tolerance (s) of the end of a narrow overlap that ends before it covers the
/// footprint: 40 um of approach at 40 m/s.
const FOOTPRINT_TOLERANCE: Real = 1e-6;
/// Where a narrow overlap first covers NORMAL_FOOTPRINT is bracketed to this fraction of its
/// depth, then interpolated linearly in the footprint across the bracket. The depth is bracketed by
/// doubling from NORMAL_DEPTH and then bisected: about 5 overlap regions instead of the 17 a
/// bisection of the whole timer to 1 us took (each costs 2-9 ms at 20k triangles; they were
/// 0.13 s of the two-sedan side impact's first-overlap step).
const FOOTPRINT_DEPTH_TOLERANCE: Real = 0.05;
/// Samples of a narrow overlap that ends before it covers NORMAL_FOOTPRINT, for its largest
/// footprint.
const FOOTPRINT_SAMPLES: usize = 8;

/// The overlap's footprint seen from above (m^2): the extent of the region S along the
/// horizontal approach direction a times its extent along z x a. a is the horizontal part
/// of body 1's point velocity relative to body 2's at the centre of S's box, or of the line
/// from body 1's CG to body 2's when that is (nearly) zero. 0 for an empty region.
pub(super) fn footprint(region: &OverlapRegion, b1: &RigidBody, b2: &RigidBody) -> Real {
    let Some(first) = region.points.first() else {
        return 0.0;
    };
    let (mut lo, mut hi) = (*first, *first);
    for p in &region.points {
        lo = lo.inf(p);
        hi = hi.sup(p);
    }
    let centre = nalgebra::center(&lo, &hi);
    let horizontal = |v: Vector| Vector::new(v.x, v.y, 0.0);
    let u = horizontal(b1.point_velocity(&centre) - b2.point_velocity(&centre));
    let a = if u.norm() > 1e-9 {
        u.normalize()
    } else {
        let c = horizontal(b2.position() - b1.position());
        if c.norm() > 0.0 {
            c.normalize()
        } else {
            Vector::x()
        }
    };
    let across = Vector::z().cross(&a);
    let extent = |dir: &Vector| {
        let (mut lo, mut hi) = (Real::INFINITY, Real::NEG_INFINITY);
        for p in &region.points {
            let s = p.coords.dot(dir);
            lo = lo.min(s);
            hi = hi.max(s);
        }
        hi - lo
    };
    extent(&a) * extent(&across)
}

/// Where and how a pair touches at one instant (world frame, SI).
#[derive(Clone, Debug)]
pub(super) struct ContactGeometry {
    pub(super) region: OverlapRegion,
    pub(super) normal: Vector,
    /// Rows n, t, b.
    pub(super) frame: Matrix,
    pub(super) region_min: Vector,
    pub(super) region_max: Vector,
    pub(super) centroid: Point,
    pub(super) faces: [Face; 2],
    pub(super) width: Real,
    /// k = B W of the struck faces (N/m); infinite for a rigid fixed obstacle (one without
    /// stiffness data); None when a vehicle's struck face has no data.
    pub(super) spring_rates: Option<[Real; 2]>,
    pub(super) effective_mass: [Real; 2],
    /// When the volume normal was taken, if not at these states.
    pub(super) normal_time: Option<Real>,
}

impl ContactGeometry {
    /// sqrt(m'/k') (s) from the reduced effective mass and the series spring rate (the
    /// vehicle's own against a rigid obstacle); infinite without stiffness data or contact
    /// width.
    fn spring_time(&self) -> Real {
        let Some([k1, k2]) = self.spring_rates else {
            return Real::INFINITY;
        };
        let [m1, m2] = self.effective_mass;
        let k = series_rate(k1, k2);
        // The reduced mass; against an immovable obstacle (infinite mass), the other's.
        let m = match (m1.is_infinite(), m2.is_infinite()) {
            (false, false) => m1 * m2 / (m1 + m2),
            (true, false) => m2,
            (false, true) => m1,
            (true, true) => Real::INFINITY,
        };
        if k > 0.0 && m.is_finite() {
            (m / k).sqrt()
        } else {
            Real::INFINITY
        }
    }
}

impl World {
    /// The volume normal (body 1's frame) of pair `pi`'s overlap for a first exchange, the
    /// time it is read, and a note when a thin part moved it shallower. None when the meshes
    /// do not overlap at any probed depth or the normal vanishes.
    ///
    /// The motion during the timer is free, so the overlap is examined ahead, at the timer's
    /// start (`started`), no later than `cap` s after it. Depth here is the approach since the
    /// first overlap: the fastest two surface points can approach now (m/s) times the time.
    /// The rule (docs/glancing.md, contact.rs):
    /// 1. read it once the overlap is NORMAL_DEPTH deep and covers NORMAL_FOOTPRINT seen from
    ///    above (a narrow overlap is read deeper: bisection on the footprint, to 1e-6 s; one
    ///    that ends first, where its footprint is largest among FOOTPRINT_SAMPLES samples);
    /// 2. but no deeper than where its vector area is still sound: at least NORMAL_COLLAPSE
    ///    of the largest at NORMAL_PROBES shallower depths NORMAL_DEPTH / 4^k, and within
    ///    acos(-NORMAL_COLLAPSE) = 120 deg of the shallowest overlap's normal (else a thin
    ///    part was cut through, or a small one is wholly inside: the deepest sound probe).
    pub(super) fn early_normal(
        &self,
        pi: usize,
        started: Real,
        cap: Real,
    ) -> Option<(Vector, Real, Option<String>)> {
        let pair = &self.pairs[pi];
        let (wb1, wb2) = (&self.bodies[pair.body1], &self.bodies[pair.body2]);
        let speed = (wb1.body().velocity() - wb2.body().velocity()).norm()
            + wb1.body().angular_velocity().norm() * wb1.shape.radius()
            + wb2.body().angular_velocity().norm() * wb2.shape.radius();
        let time_for = |depth: Real| -> Real {
            if speed > 0.0 {
                (depth / speed).min(cap)
            } else {
                cap
            }
        };
        let base = started - self.time;
        // The overlap region `dt` s after `started` (`query`: overlap_region, or
        // overlap_points where only the footprint is read), with the bodies then.
        type Query = fn(&MeshShape, &Isometry, &MeshShape, &Isometry) -> OverlapRegion;
        let at = |query: Query, dt: Real| -> (OverlapRegion, RigidBody, RigidBody) {
            let b1 = self.predicted(pair.body1, base + dt);
            let b2 = self.predicted(pair.body2, base + dt);
            (
                query(&wb1.shape, &b1.pose(), &wb2.shape, &b2.pose()),
                b1.into_owned(),
                b2.into_owned(),
            )
        };
        let region_at = |dt: Real| at(overlap_region, dt);
        let points_at = |dt: Real| at(overlap_points, dt);
        let areas_at = |dt: Real| at(overlap_areas, dt);
        let reading = |r: &OverlapRegion, b1: &RigidBody, dt: Real| {
            r.volume_normal()
                .map(|n| (b1.pose().inverse_transform_vector(&n), started + dt))
        };
        let dt0 = time_for(NORMAL_DEPTH);
        let (r0, b1_0, b2_0) = region_at(dt0);
        // 2. Thin parts: the vector area at shallower depths. Cut through, a thin part's two
        // faces cancel (a wall against a car's sides: the magnitude collapses) or reverse (a
        // plate through a plate: it points back against the faces that met, the normal of
        // the shallowest overlap). A contact that only turns (a corner developing into a
        // scrape along the sides) is neither. Only a probe's vector area is read.
        let mut probes = Vec::with_capacity(NORMAL_PROBES);
        for k in 1..=NORMAL_PROBES {
            let dt = dt0 / NORMAL_PROBE_RATIO.powi(k as i32);
            let (r, b1, _) = areas_at(dt);
            probes.push((dt, r, b1));
        }
        let vector = |r: &OverlapRegion| r.area_normal_1_in_2 - r.area_normal_2_in_1;
        let first_faces = probes.iter().rev().find_map(|(_, r, _)| r.volume_normal());
        let largest = probes
            .iter()
            .map(|(_, r, _)| vector(r).norm())
            .fold(vector(&r0).norm(), Real::max);
        let sound = |r: &OverlapRegion| {
            let a = vector(r);
            let m = a.norm();
            m > 0.0
                && m >= NORMAL_COLLAPSE * largest
                && first_faces.is_none_or(|n| a.dot(&n) >= -NORMAL_COLLAPSE * m)
        };
        if largest > 0.0 && !sound(&r0) {
            let m0 = vector(&r0).norm();
            let Some((dt, r, b1)) = probes.into_iter().find(|(_, r, _)| sound(r)) else {
                let (n, t) = reading(&r0, &b1_0, dt0)?;
                return Some((n, t, None));
            };
            let (n, t) = reading(&r, &b1, dt)?;
            let note = format!(
                "contact normal read {:.2} mm deep, not at {:.0} mm: deeper, the overlap's \
                 vector area had {} (a thin part cut through, or a small one wholly inside)",
                dt * speed * 1e3,
                NORMAL_DEPTH * 1e3,
                if m0 < NORMAL_COLLAPSE * largest {
                    format!("collapsed to {:.0} % of its largest", 100.0 * m0 / largest)
                } else {
                    "turned back against the faces that met".to_string()
                }
            );
            return Some((n, t, Some(note)));
        }
        // 1. A narrow overlap is read once it covers the footprint.
        if r0.is_empty() || dt0 >= cap || footprint(&r0, &b1_0, &b2_0) >= NORMAL_FOOTPRINT {
            let (n, t) = reading(&r0, &b1_0, dt0)?;
            return Some((n, t, None));
        }
        let dt = narrow_reading_time(&points_at, dt0, footprint(&r0, &b1_0, &b2_0), cap);
        let (r, b1, _) = region_at(dt);
        if r.is_empty() || !sound(&r) {
            // The narrow overlap was cut through on the way: keep the 2 cm reading.
            let (n, t) = reading(&r0, &b1_0, dt0)?;
            return Some((n, t, None));
        }
        // The reading's time (Impact::normal_time) says how deep it was read; the deeper
        // reading of a narrow overlap is the rule, not an event, so no note.
        let (n, t) = reading(&r, &b1, dt)?;
        Some((n, t, None))
    }

    /// The automatic dt_p of pair `pi` whose timer starts at `started`: the dt in
    /// (0, 0.060] s with dt = sqrt(m'/k') evaluated at started + dt, where the bodies will be
    /// (they move freely while the timer runs). Bisection to `TIME_TOLERANCE`; clamped to
    /// 0.060 s, with a note, when sqrt(m'/k') is still longer there.
    pub(super) fn auto_depth_of_penetration(
        &self,
        pi: usize,
        started: Real,
        early_normal: Option<(Vector, Real)>,
    ) -> (Real, Vec<String>) {
        let pair = &self.pairs[pi];
        let offset = started - self.time;
        let spring_time = |dt: Real| -> Real {
            let b1 = self.predicted(pair.body1, offset + dt);
            let b2 = self.predicted(pair.body2, offset + dt);
            // Before the early normal's instant the overlap's own normal is used.
            let normal = early_normal
                .filter(|(_, t)| *t <= started + dt)
                .map(|(n, t)| (b1.pose() * n, t));
            self.contact_geometry(pair, &b1, &b2, normal)
                .map_or(Real::INFINITY, |g| g.spring_time())
        };
        let max = MAX_DEPTH_OF_PENETRATION;
        let at_max = spring_time(max);
        if at_max >= max {
            return (
                max,
                vec![format!(
                    "automatic depth of penetration: sqrt(m'/k') = {:.1} ms at 60 ms after the \
                     first overlap, longer than the accepted 60 ms; clamped to 60 ms",
                    at_max * 1e3
                )],
            );
        }
        let hi = bisect(0.0, max, TIME_TOLERANCE, |dt| dt >= spring_time(dt));
        let mut notes = Vec::new();
        let (typical_lo, typical_hi) = TYPICAL_DEPTH_OF_PENETRATION;
        if hi < typical_lo || hi > typical_hi {
            notes.push(format!(
                "automatic depth of penetration {:.2} ms lies outside the typical 10-60 ms",
                hi * 1e3
            ));
        }
        (hi, notes)
    }

    /// The pair's contact geometry with its bodies at the given states (world frame): the
    /// overlap region, normal, contact frame, centroid, struck faces, width, spring rates and
    /// effective masses. `volume_normal` replaces the region's own volume normal (world frame,
    /// with the time it was taken). None when the meshes do not overlap.
    pub(super) fn contact_geometry(
        &self,
        pair: &Pair,
        b1: &RigidBody,
        b2: &RigidBody,
        volume_normal: Option<(Vector, Real)>,
    ) -> Option<ContactGeometry> {
        let (w1, w2) = (&self.bodies[pair.body1], &self.bodies[pair.body2]);
        let (pose1, pose2) = (b1.pose(), b2.pose());
        let region = overlap_region(&w1.shape, &pose1, &w2.shape, &pose2);
        if region.is_empty() {
            return None;
        }
        let (volume_normal, normal_time) = volume_normal.map_or_else(
            || (own_volume_normal(&region, b1, b2), None),
            |(n, t)| (n, Some(t)),
        );
        let normal = chosen_normal(&pair.params.normal, volume_normal);
        let frame = contact_frame(&normal);
        let (rmin, rmax) = extent_in_frame(&region, &frame);
        let faces = [
            Face::facing(&pose1.inverse_transform_vector(&normal)),
            Face::facing(&pose2.inverse_transform_vector(&-normal)),
        ];
        let width = rmax.y - rmin.y;
        let spring_rates = self.spring_rates(pair, faces, width);
        let centroid = match &pair.params.centroid {
            CentroidMode::Auto => Point::from(frame.transpose() * ((rmin + rmax) * 0.5)),
            CentroidMode::Stiffness => stiffness_centroid(&frame, rmin, rmax, spring_rates),
            CentroidMode::World(p) => *p,
            CentroidMode::Body { body, point } => {
                if *body == pair.body1 {
                    pose1 * point
                } else {
                    pose2 * point
                }
            }
        };
        let effective_mass = [
            self.felt_mass(pair.body1, b1, &centroid, &normal),
            self.felt_mass(pair.body2, b2, &centroid, &normal),
        ];
        Some(ContactGeometry {
            region,
            normal,
            frame,
            region_min: rmin,
            region_max: rmax,
            centroid,
            faces,
            width,
            spring_rates,
            effective_mass,
            normal_time,
        })
    }

    /// k = B W (N/m) of the pair's struck `faces` over the overlap `width` (m); infinite for
    /// a rigid fixed obstacle; None when either body's struck face has no stiffness data.
    fn spring_rates(&self, pair: &Pair, faces: [Face; 2], width: Real) -> Option<[Real; 2]> {
        // A fixed obstacle without stiffness data is rigid: an infinite rate (contact.rs).
        let rate = |i: usize, face: Face| match self.bodies[i].stiffness.face(face) {
            Some(s) => Some(s.spring_rate(width)),
            None if self.is_rigid(i) => Some(Real::INFINITY),
            None => None,
        };
        match (rate(pair.body1, faces[0]), rate(pair.body2, faces[1])) {
            (Some(k1), Some(k2)) => Some([k1, k2]),
            _ => None,
        }
    }

    /// The effective mass (kg) of body `i` (state `b`) at `centroid` (world, m) along the
    /// unit `normal` (world). A mechanism's member feels the mass the joints bring along (its
    /// point's mobility through them, at the members' current poses).
    fn felt_mass(&self, i: usize, b: &RigidBody, centroid: &Point, normal: &Vector) -> Real {
        if self.mechanism_of.get(i).copied().flatten().is_some() {
            1.0 / normal.dot(&(self.point_mobility(i, centroid) * normal))
        } else {
            effective_mass(
                b.props().mass(),
                &b.world_inverse_inertia(),
                &(centroid - b.position()),
                normal,
            )
        }
    }
}

/// The overlap's own volume normal (world, unit) with the bodies at `b1`, `b2`; without a
/// usable inside area (e.g. open meshes), the approach direction at the centre of the
/// region's box, else the line from body 1's CG to body 2's. `region` is not empty.
fn own_volume_normal(region: &OverlapRegion, b1: &RigidBody, b2: &RigidBody) -> Vector {
    let bbox_center = {
        let (mut lo, mut hi) = (region.points[0], region.points[0]);
        for p in &region.points {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
        nalgebra::center(&lo, &hi)
    };
    region.volume_normal().unwrap_or_else(|| {
        // No usable inside area (e.g. open meshes): fall back on the approach direction.
        let u = b1.point_velocity(&bbox_center) - b2.point_velocity(&bbox_center);
        if u.norm() > 0.0 {
            u.normalize()
        } else {
            (b2.position() - b1.position()).normalize()
        }
    })
}

/// The corners of the box of a non-empty `region` in contact coordinates (`frame`'s rows:
/// n, t, b; m): the least and the largest of each coordinate over its points.
fn extent_in_frame(region: &OverlapRegion, frame: &Matrix) -> (Vector, Vector) {
    let (mut rmin, mut rmax) = (
        frame * region.points[0].coords,
        frame * region.points[0].coords,
    );
    for p in &region.points {
        let c = frame * p.coords;
        rmin = rmin.inf(&c);
        rmax = rmax.sup(&c);
    }
    (rmin, rmax)
}

/// The centroid (world, m) that splits the crush along the normal in the inverse ratio of
/// the `spring_rates` (N/m), the middle of the region's box (`rmin`, `rmax`, contact
/// coordinates of `frame`, m) across it; the box's middle without stiffness data.
fn stiffness_centroid(
    frame: &Matrix,
    rmin: Vector,
    rmax: Vector,
    spring_rates: Option<[Real; 2]>,
) -> Point {
    // Body 1's undeformed surface is at the region's far end along +n, body 2's at
    // the near end: C1 = rmax.n - P.n, C2 = P.n - rmin.n, C1 : C2 = k2 : k1. A
    // rigid obstacle takes no crush: P is on its surface, the common-tangent plane
    // through its part of the region (a barrier's edge).
    let mut c = (rmin + rmax) * 0.5;
    if let Some(share) = spring_rates.and_then(|[k1, k2]| crush_share(k1, k2)) {
        c.x = rmax.x - share * (rmax.x - rmin.x);
    }
    Point::from(frame.transpose() * c)
}

/// The exchange's normal (world, unit) by the pair's normal mode, from the overlap's volume
/// normal (world, unit): that normal, a fixed direction, or its horizontal part pitched by
/// `pitch` rad (the volume normal itself when it is vertical).
fn chosen_normal(mode: &NormalMode, volume_normal: Vector) -> Vector {
    match mode {
        NormalMode::Volume => volume_normal,
        NormalMode::Fixed(v) => v.normalize(),
        NormalMode::Horizontal { pitch } => {
            let h = Vector::new(volume_normal.x, volume_normal.y, 0.0);
            if h.norm() < 1e-9 {
                volume_normal
            } else {
                h.normalize() * pitch.cos() + Vector::z() * pitch.sin()
            }
        }
    }
}

/// The contact frame (rows: the normal, a horizontal tangent z x n, the binormal n x t;
/// world to contact coordinates) of a unit normal; the tangent from x when n is vertical.
fn contact_frame(normal: &Vector) -> Matrix {
    let tangent = {
        let t = Vector::z().cross(normal);
        if t.norm() > 1e-9 {
            t.normalize()
        } else {
            Vector::x().cross(normal).normalize()
        }
    };
    let binormal = normal.cross(&tangent);
    Matrix::from_rows(&[
        normal.transpose(),
        tangent.transpose(),
        binormal.transpose(),
    ])
}

/// Rule 1 of [`World::early_normal`] for a narrow overlap (one whose footprint at the 2 cm
/// reading, `footprint0` m^2 at `dt0` s, is under NORMAL_FOOTPRINT): the time after the
/// timer's start (s, at most `cap`) at which it is read. `points_at(dt)` is the overlap
/// region's point set (its vector areas are not read here) and the two bodies `dt` s after
/// the timer's start.
fn narrow_reading_time(
    points_at: &dyn Fn(Real) -> (OverlapRegion, RigidBody, RigidBody),
    dt0: Real,
    footprint0: Real,
    cap: Real,
) -> Real {
    // The footprint at each time tried (s, m^2).
    let tried = std::cell::RefCell::new(vec![(dt0, footprint0)]);
    let covers = |dt: Real| {
        let (r, b1, b2) = points_at(dt);
        let f = footprint(&r, &b1, &b2);
        tried.borrow_mut().push((dt, f));
        f >= NORMAL_FOOTPRINT
    };
    // Bracket by doubling the depth, then bisect to FOOTPRINT_DEPTH_TOLERANCE and
    // interpolate the footprint linearly across the last bracket (so the reading moves
    // continuously with the geometry, not by the bracket's jumps).
    let (mut lo, mut hi) = (dt0, (2.0 * dt0).min(cap));
    let mut covered = covers(hi);
    while !covered && hi < cap {
        (lo, hi) = (hi, (2.0 * hi).min(cap));
        covered = covers(hi);
    }
    if covered {
        let hi = bisect(lo, hi, FOOTPRINT_DEPTH_TOLERANCE * lo, &covers);
        let tried = tried.borrow();
        let below = tried
            .iter()
            .filter(|(t, f)| *t < hi && *f < NORMAL_FOOTPRINT)
            .fold((dt0, 0.0), |a, &b| if b.0 > a.0 { b } else { a });
        let at_hi = tried
            .iter()
            .find(|(t, _)| *t == hi)
            .map_or(NORMAL_FOOTPRINT, |x| x.1);
        if at_hi > below.1 {
            let s = ((NORMAL_FOOTPRINT - below.1) / (at_hi - below.1)).clamp(0.0, 1.0);
            below.0 + s * (hi - below.0)
        } else {
            hi
        }
    } else if !points_at(cap).0.is_empty() {
        cap
    } else {
        // The narrow overlap ends before it covers the footprint (a corner passing by):
        // read it where its footprint is largest, among samples up to its end.
        let end = bisect(dt0, cap, FOOTPRINT_TOLERANCE, |dt| {
            points_at(dt).0.is_empty()
        });
        (1..=FOOTPRINT_SAMPLES)
            .map(|k| dt0 + (end - dt0) * k as Real / (FOOTPRINT_SAMPLES + 1) as Real)
            .map(|dt| {
                let (r, b1, b2) = points_at(dt);
                (dt, footprint(&r, &b1, &b2))
            })
            .fold((dt0, 0.0), |best, x| if x.1 > best.1 { x } else { best })
            .0
    }
}
