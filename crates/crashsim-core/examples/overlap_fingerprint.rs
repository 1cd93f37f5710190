//! A fingerprint of the two-mesh queries (crate::overlap): every public query run over a fixed
//! set of mesh pairs and poses, each f64 result's bits (and each flag, count and triangle
//! index) fed to FNV-1a, one digest printed per query and one for all. Equal digests before
//! and after a refactoring of the queries: the same bits.
//!
//!     cargo run --release -p crashsim-core --example overlap_fingerprint
//!
//! Meshes (body frame, m): boxes, a subdivided box (coplanar triangles), a UV sphere, an open
//! box (no top), two boxes as one two-shell mesh, and the repository's generated sedan and
//! SUV (meshes/*.ply). Poses: a seeded pseudo-random set per pair (near contact, deep, apart;
//! turned about z by quarter turns, so faces lie coplanar, or freely) plus exact touches and
//! coplanar placements.

use crashsim_core::math::{Isometry, Point, Real, Rotation, Vector};
use crashsim_core::overlap::{
    overlap_region, shapes_overlap, shapes_overlap_hinted, surface_distance, surface_distance_from,
    surfaces_intersect, OverlapRegion, QueryWorkspace,
};
use crashsim_core::MeshShape;
use std::collections::HashMap;
use std::f64::consts::{FRAC_PI_2, PI};
use std::path::Path;

/// FNV-1a over 64-bit words (little-endian bytes).
struct Fnv(u64);

impl Fnv {
    fn new() -> Fnv {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
    fn word(&mut self, w: u64) {
        for byte in w.to_le_bytes() {
            self.0 = (self.0 ^ byte as u64).wrapping_mul(0x0100_0000_01b3);
        }
    }
    fn real(&mut self, x: Real) {
        self.word(x.to_bits());
    }
    fn point(&mut self, p: &Point) {
        p.coords.iter().for_each(|&x| self.real(x));
    }
    fn vector(&mut self, v: &Vector) {
        v.iter().for_each(|&x| self.real(x));
    }
    fn pair(&mut self, p: Option<(u32, u32)>) {
        match p {
            Some((a, b)) => {
                self.word(1);
                self.word(a as u64);
                self.word(b as u64);
            }
            None => self.word(0),
        }
    }
}

/// SplitMix64: a seeded stream of uniform numbers, independent of any crate's version.
struct Stream(u64);

impl Stream {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// Uniform in [lo, hi).
    fn uniform(&mut self, lo: Real, hi: Real) -> Real {
        lo + (hi - lo) * ((self.next() >> 11) as Real / (1u64 << 53) as Real)
    }
}

/// Reads the repository's generated meshes: binary little-endian PLY, vertices as three
/// doubles, faces as a uchar-counted list of int (the layout scripts/make_meshes.py writes).
fn read_generated_ply(path: &Path) -> MeshShape {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let end = bytes
        .windows(11)
        .position(|w| w == b"end_header\n")
        .expect("a PLY header");
    let header = std::str::from_utf8(&bytes[..end]).expect("a text header");
    let count = |name: &str| -> usize {
        header
            .lines()
            .find_map(|l| l.strip_prefix(&format!("element {name} ")))
            .and_then(|n| n.trim().parse().ok())
            .unwrap_or_else(|| panic!("{}: no element {name}", path.display()))
    };
    let layout = "property double x\nproperty double y\nproperty double z\n";
    assert!(
        header.contains(layout) && header.contains("property list uchar int vertex_indices"),
        "{}: not the generated meshes' layout",
        path.display()
    );
    let (nv, nf) = (count("vertex"), count("face"));
    let mut at = end + 11;
    let f64_at = |at: &mut usize| {
        let x = f64::from_le_bytes(bytes[*at..*at + 8].try_into().unwrap());
        *at += 8;
        x
    };
    let vertices: Vec<Point> = (0..nv)
        .map(|_| Point::new(f64_at(&mut at), f64_at(&mut at), f64_at(&mut at)))
        .collect();
    let mut triangles = Vec::with_capacity(nf);
    for _ in 0..nf {
        assert_eq!(
            bytes[at],
            3,
            "{}: a face that is no triangle",
            path.display()
        );
        at += 1;
        let mut t = [0u32; 3];
        for k in &mut t {
            *k = i32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()) as u32;
            at += 4;
        }
        triangles.push(t);
    }
    MeshShape::new(vertices, triangles).expect("a valid mesh")
}

/// `m` with every triangle split into four, `times` times (midpoints shared).
fn refine(m: &MeshShape, times: usize) -> MeshShape {
    let (mut v, mut t) = (m.vertices().to_vec(), m.triangles().to_vec());
    for _ in 0..times {
        let mut mid = HashMap::new();
        let mut nt = Vec::new();
        let mut midpoint = |a: u32, b: u32, v: &mut Vec<Point>| -> u32 {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                v.push(nalgebra::center(&v[a as usize], &v[b as usize]));
                (v.len() - 1) as u32
            })
        };
        for &[a, b, c] in &t {
            let (ab, bc, ca) = (
                midpoint(a, b, &mut v),
                midpoint(b, c, &mut v),
                midpoint(c, a, &mut v),
            );
            nt.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
        }
        t = nt;
    }
    MeshShape::new(v, t).expect("a refined box is a valid mesh")
}

/// A closed UV sphere of radius `r` (m) about the origin, outward, `rings` x `segments`.
fn sphere(r: Real, rings: u32, segments: u32) -> MeshShape {
    let mut v = vec![Point::new(0.0, 0.0, r)];
    for i in 1..rings {
        let theta = PI * i as Real / rings as Real;
        for j in 0..segments {
            let phi = 2.0 * PI * j as Real / segments as Real;
            let s = theta.sin();
            v.push(Point::new(
                r * s * phi.cos(),
                r * s * phi.sin(),
                r * theta.cos(),
            ));
        }
    }
    v.push(Point::new(0.0, 0.0, -r));
    let bottom = v.len() as u32 - 1;
    let at = |i: u32, j: u32| 1 + (i - 1) * segments + j % segments;
    let mut t = Vec::new();
    for j in 0..segments {
        t.push([0, at(1, j), at(1, j + 1)]);
        t.push([bottom, at(rings - 1, j + 1), at(rings - 1, j)]);
    }
    for i in 1..rings - 1 {
        for j in 0..segments {
            t.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            t.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    let m = MeshShape::new(v, t).expect("a sphere is a valid mesh");
    assert!(m.is_closed() && m.contains_point(&Point::origin()));
    m
}

/// A box without its top (z+) face: an open mesh.
fn open_box(h: Vector) -> MeshShape {
    let b = MeshShape::cuboid(Vector::zeros(), h);
    let t: Vec<[u32; 3]> = b.triangles()[..2]
        .iter()
        .chain(&b.triangles()[4..])
        .copied()
        .collect();
    let m = MeshShape::new(b.vertices().to_vec(), t).expect("an open box is a valid mesh");
    assert!(!m.is_closed());
    m
}

/// Two boxes 3 m apart along x as one mesh of two shells.
fn two_boxes() -> MeshShape {
    let (a, b) = (
        MeshShape::cuboid(Vector::new(-1.5, 0.0, 0.0), Vector::new(0.6, 0.5, 0.4)),
        MeshShape::cuboid(Vector::new(1.5, 0.0, 0.0), Vector::new(0.4, 0.4, 0.4)),
    );
    let mut v = a.vertices().to_vec();
    v.extend_from_slice(b.vertices());
    let off = a.vertices().len() as u32;
    let mut t = a.triangles().to_vec();
    t.extend(b.triangles().iter().map(|tri| tri.map(|k| k + off)));
    let m = MeshShape::new(v, t).expect("two boxes are a valid mesh");
    assert_eq!(m.shells().len(), 2);
    m
}

fn pose(x: Real, y: Real, z: Real, roll: Real, pitch: Real, yaw: Real) -> Isometry {
    Isometry::from_parts(
        nalgebra::Translation3::new(x, y, z),
        Rotation::from_euler_angles(roll, pitch, yaw),
    )
}

/// Half the diagonal of a mesh's box (m): the reach the random offsets are scaled by.
fn reach(m: &MeshShape) -> Real {
    0.5 * (m.aabb().maxs - m.aabb().mins).norm()
}

/// The poses (of mesh 1, of mesh 2) of one pair: `count` seeded ones and the given exact ones.
fn poses(
    s1: &MeshShape,
    s2: &MeshShape,
    seed: u64,
    count: usize,
    exact: &[(Isometry, Isometry)],
) -> Vec<(Isometry, Isometry)> {
    let mut rng = Stream(seed);
    let r = reach(s1) + reach(s2);
    let mut out = exact.to_vec();
    for k in 0..count {
        let p1 = pose(
            rng.uniform(-5.0, 5.0),
            rng.uniform(-5.0, 5.0),
            rng.uniform(0.0, 1.0),
            rng.uniform(-0.1, 0.1),
            rng.uniform(-0.1, 0.1),
            rng.uniform(-PI, PI),
        );
        // Offsets from deep overlap to apart: the first half within 0.6 r, the rest to 1.1 r.
        let spread = if k < count / 2 { 0.6 * r } else { 1.1 * r };
        let offset = Vector::new(
            rng.uniform(-spread, spread),
            rng.uniform(-spread, spread),
            rng.uniform(-0.3 * spread, 0.3 * spread),
        );
        let relative = if k % 2 == 0 {
            // Quarter turns about z, no tilt: faces of boxes lie coplanar.
            let quarter = (rng.next() % 4) as Real * FRAC_PI_2;
            pose(offset.x, offset.y, 0.0, 0.0, 0.0, quarter)
        } else {
            pose(
                offset.x,
                offset.y,
                offset.z,
                rng.uniform(-0.5, 0.5),
                rng.uniform(-0.5, 0.5),
                rng.uniform(-PI, PI),
            )
        };
        out.push((p1, p1 * relative));
    }
    // A push: mesh 2 driven into mesh 1 in small steps, so the hinted test's last crossing
    // pair and the distance's last closest pair are often still the answer.
    let p1 = pose(1.0, -2.0, 0.3, 0.0, 0.0, 0.4);
    for k in 0..12 {
        let x = (0.9 - 0.05 * k as Real) * r;
        out.push((p1, p1 * pose(x, 0.1 * r, 0.0, 0.0, 0.0, 0.01 * k as Real)));
    }
    out
}

/// A named pair of meshes and their poses (of mesh 1, of mesh 2).
type Pair<'a> = (
    &'a str,
    &'a MeshShape,
    &'a MeshShape,
    Vec<(Isometry, Isometry)>,
);

/// One digest per query and the number of poses where the meshes overlap.
struct Digests {
    overlap: Fnv,
    hinted: Fnv,
    intersect: Fnv,
    distance: Fnv,
    distance_from: Fnv,
    region: Fnv,
    overlapping: usize,
    region_points: usize,
}

fn eat_region(h: &mut Fnv, r: &OverlapRegion) {
    h.word(r.points.len() as u64);
    r.points.iter().for_each(|p| h.point(p));
    h.vector(&r.area_normal_1_in_2);
    h.vector(&r.area_normal_2_in_1);
    h.word(r.segment_count as u64);
    h.word(r.inside_vertex_count as u64);
    h.word(r.inside_1_count as u64);
    h.word(r.is_empty() as u64);
    match r.center() {
        Some(c) => h.point(&c),
        None => h.word(u64::MAX),
    }
    match r.volume_normal() {
        Some(n) => h.vector(&n),
        None => h.word(u64::MAX),
    }
}

/// Every query on one pair at every pose, both ways round.
fn run_pair(s1: &MeshShape, s2: &MeshShape, poses: &[(Isometry, Isometry)], d: &mut Digests) {
    let mut ws = QueryWorkspace::default();
    let (mut hint12, mut hint21) = (None, None);
    let mut closest = None;
    let Digests {
        overlap: ho,
        hinted: hh,
        intersect: hi,
        distance: hd,
        distance_from: hf,
        region: hr,
        overlapping,
        region_points,
    } = d;
    for (p1, p2) in poses {
        let overlap = shapes_overlap(s1, p1, s2, p2, &mut ws);
        ho.word(overlap as u64);
        ho.word(shapes_overlap(s2, p2, s1, p1, &mut ws) as u64);
        hh.word(shapes_overlap_hinted(s1, p1, s2, p2, &mut ws, &mut hint12) as u64);
        hh.pair(hint12);
        hh.word(shapes_overlap_hinted(s2, p2, s1, p1, &mut ws, &mut hint21) as u64);
        hh.pair(hint21);
        hi.word(surfaces_intersect(s1, p1, s2, p2, &mut ws) as u64);
        hi.word(surfaces_intersect(s2, p2, s1, p1, &mut ws) as u64);
        hd.real(surface_distance(s1, p1, s2, p2, 1e9, &mut ws));
        hd.real(surface_distance(s2, p2, s1, p1, 1e9, &mut ws));
        hd.real(surface_distance(s1, p1, s2, p2, 0.05, &mut ws));
        let (dist, pair) = surface_distance_from(s1, p1, s2, p2, 1e9, closest, &mut ws);
        hf.real(dist);
        hf.pair(pair);
        closest = pair;
        let (dist, pair) = surface_distance_from(s1, p1, s2, p2, 0.2, None, &mut ws);
        hf.real(dist);
        hf.pair(pair);
        let r12 = overlap_region(s1, p1, s2, p2);
        eat_region(hr, &r12);
        eat_region(hr, &overlap_region(s2, p2, s1, p1));
        *overlapping += overlap as usize;
        *region_points += r12.points.len();
    }
}

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../meshes");
    let sedan = read_generated_ply(&root.join("sedan.ply"));
    let suv = read_generated_ply(&root.join("suv.ply"));
    let car = MeshShape::cuboid(Vector::zeros(), Vector::new(2.25, 0.9, 0.7));
    let small = MeshShape::cuboid(Vector::zeros(), Vector::new(0.5, 0.5, 0.5));
    let fine = refine(
        &MeshShape::cuboid(Vector::zeros(), Vector::new(2.0, 0.85, 0.6)),
        3,
    );
    let ball = sphere(0.8, 12, 24);
    let open = open_box(Vector::new(1.0, 0.8, 0.6));
    let twin = two_boxes();
    let id = Isometry::identity();
    let at = |x: Real, y: Real, z: Real, yaw: Real| pose(x, y, z, 0.0, 0.0, yaw);
    // Exact placements: faces touching, coplanar bottoms and tops, one inside the other.
    let box_exact = [
        (id, at(2.75, 0.0, 0.0, 0.0)),
        (id, at(2.75, 0.3, -0.2, 0.0)),
        (id, at(2.5, 0.0, 0.0, 0.0)),
        (id, at(0.1, 0.0, 0.0, 0.2)),
        (at(-4.05, 0.0, 0.7, 0.0), at(0.0, 0.0, 0.7, FRAC_PI_2)),
    ];
    let fine_exact = [
        (at(-4.05, 0.0, 0.7, 0.0), at(0.0, 0.0, 0.6, 0.0)),
        (at(-4.05, 0.0, 0.6, 0.0), at(0.0, 0.0, 0.6, 0.0)),
        (id, at(4.25, 0.0, 0.0, 0.0)),
        (id, at(0.0, 0.0, 0.0, PI)),
    ];
    let pairs: Vec<Pair> = vec![
        (
            "box/box",
            &car,
            &small,
            poses(&car, &small, 1, 120, &box_exact),
        ),
        (
            "box/fine box",
            &car,
            &fine,
            poses(&car, &fine, 2, 120, &fine_exact),
        ),
        (
            "fine box/sphere",
            &fine,
            &ball,
            poses(&fine, &ball, 3, 80, &[]),
        ),
        (
            "sphere/sphere",
            &ball,
            &ball,
            poses(&ball, &ball, 4, 60, &[(id, id)]),
        ),
        (
            "box/open box",
            &car,
            &open,
            poses(&car, &open, 5, 80, &[(id, id)]),
        ),
        (
            "two shells/box",
            &twin,
            &small,
            poses(&twin, &small, 6, 80, &[(id, at(1.5, 0.0, 0.0, 0.1))]),
        ),
        ("sedan/suv", &sedan, &suv, poses(&sedan, &suv, 7, 40, &[])),
        (
            "sedan/sedan",
            &sedan,
            &sedan,
            poses(&sedan, &sedan, 8, 30, &[(id, id)]),
        ),
        ("box/sedan", &car, &sedan, poses(&car, &sedan, 9, 30, &[])),
    ];
    let mut d = Digests {
        overlap: Fnv::new(),
        hinted: Fnv::new(),
        intersect: Fnv::new(),
        distance: Fnv::new(),
        distance_from: Fnv::new(),
        region: Fnv::new(),
        overlapping: 0,
        region_points: 0,
    };
    let mut count = 0;
    for (name, s1, s2, ps) in &pairs {
        let before = (d.overlapping, d.region_points);
        run_pair(s1, s2, ps, &mut d);
        count += ps.len();
        println!(
            "{name}: {} poses, {} overlapping, {} region points (1 in 2)",
            ps.len(),
            d.overlapping - before.0,
            d.region_points - before.1
        );
    }
    let mut all = Fnv::new();
    for (name, h) in [
        ("shapes_overlap", &d.overlap),
        ("shapes_overlap_hinted", &d.hinted),
        ("surfaces_intersect", &d.intersect),
        ("surface_distance", &d.distance),
        ("surface_distance_from", &d.distance_from),
        ("overlap_region", &d.region),
    ] {
        let v = h.0;
        all.word(v);
        println!("{name:24} {v:016x}");
    }
    println!("{count} poses; all queries' digest {:016x}", all.0);
}
