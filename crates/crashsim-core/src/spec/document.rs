//! A [`SceneSpec`] as a serde document (feature `serde`) and JSON through serde_json.
//!
//! The document mirrors the spec with plain values: meshes once each (shared meshes are
//! written once and referred to by index) as vertices (m) and triangles; quaternions as
//! (w, x, y, z); matrices as rows; every enum externally tagged in snake case. Reading it
//! back goes through the same constructors and checks as the setup methods (a document
//! edited by hand gets the engine's messages), and gives the same bits: meshes rebuild the
//! same hierarchy, a unit quaternion is kept as written (another is normalised), the inertia
//! is the spec's own (already symmetric).

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use super::{BodyMotion, BodySpec, RunSpec, SceneSpec};
use crate::body::{BodyState, MassProperties};
use crate::contact::{CentroidMode, ContactParams, DepthOfPenetration, NormalMode};
use crate::error::{Error, Place, Result};
use crate::ground::{FrictionZone, Ground, Surface};
use crate::impulse::RestitutionMode;
use crate::math::{Isometry, Matrix, Point, Real, Rotation, Vector};
use crate::shape::MeshShape;
use crate::soft::SoftContact;
use crate::stiffness::{Face, FaceStiffness, Stiffness};
use crate::vehicle::{
    AntiRollBar, Braking, DriverInputs, SteerInput, Steering, Table, Trigger, Tyre, VehicleSpec,
    WheelSpec, WheelState, WheelSwitch,
};
use crate::world::RunOptions;

#[path = "document_joints.rs"]
mod joints;
use joints::{joint, joint_doc, JointDoc};

/// The document's format name and version (a reader refuses others).
const FORMAT: &str = "crashsim-scene-spec";
/// 2 (2026-11): tyres with the cornering coefficient and the combined-slip law, the steering
/// linkage, per-wheel steering. 3: joints, a vehicle's coupling point, hitch load and load
/// groups. 4: pairs of bodies that never collide (`no_contact`), soft contacts
/// (`soft_contacts`). 5: a joint's passive moments (`passive`, written only when it has
/// some). 6: a moving body's own friction with the ground (`ground_friction`, written only
/// when set). Versions 2 to 5, which lack the later fields, are read too.
const VERSION: u32 = 6;

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Document {
    format: String,
    version: u32,
    meshes: Vec<MeshDoc>,
    bodies: Vec<BodyDoc>,
    contacts: Vec<ContactDoc>,
    ground: Option<GroundDoc>,
    run: RunDoc,
    #[serde(default)]
    joints: Vec<JointDoc>,
    /// Pairs of bodies that never collide (body indices).
    #[serde(default)]
    no_contact: Vec<(usize, usize)>,
    /// Pairs with a compliant contact: (body 1, body 2, stiffness N/m, damping ratio).
    #[serde(default)]
    soft_contacts: Vec<(usize, usize, Real, Real)>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct MeshDoc {
    vertices: Vec<[Real; 3]>,
    triangles: Vec<[u32; 3]>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct BodyDoc {
    name: String,
    mesh: usize,
    /// (A N/m, B N/m^2) per face: front, rear, left, right.
    stiffness: [Option<[Real; 2]>; 4],
    motion: MotionDoc,
    /// Its own friction with the ground (None: the ground's body friction).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    ground_friction: Option<Real>,
}

#[derive(Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
enum MotionDoc {
    Moving {
        mass: Real,
        inertia: [[Real; 3]; 3],
        position: [Real; 3],
        orientation: [Real; 4],
        velocity: [Real; 3],
        angular_velocity: [Real; 3],
        vehicle: Option<Box<VehicleDoc>>,
    },
    Fixed {
        position: [Real; 3],
        orientation: [Real; 4],
    },
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct VehicleDoc {
    wheels: Vec<WheelDoc>,
    tyre: Tyre,
    steering: Steering,
    anti_roll: Vec<AntiRollBar>,
    abs: bool,
    steer: Option<SteerInput>,
    brake: Vec<Option<Braking>>,
    drive: Vec<Option<Vec<[Real; 2]>>>,
    switches: Vec<SwitchDoc>,
    #[serde(default)]
    coupling: Option<[Real; 3]>,
    #[serde(default)]
    hitch_load: Option<([Real; 3], Real)>,
    #[serde(default)]
    load_groups: Vec<Vec<usize>>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct WheelDoc {
    center: [Real; 3],
    radius: Real,
    steerable: bool,
    static_load: Real,
    spring_rate: Real,
    damping: Real,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct SwitchDoc {
    wheel: usize,
    at: TriggerDoc,
    state: WheelStateDoc,
}

#[derive(Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
enum TriggerDoc {
    Time(Real),
    Exchange(usize),
}

#[derive(Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
enum WheelStateDoc {
    Free,
    Locked,
    Braked(Real),
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct ContactDoc {
    body1: usize,
    body2: usize,
    params: ParamsDoc,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct ParamsDoc {
    depth_of_penetration: DepthDoc,
    restitution: Real,
    friction: Real,
    restitution_mode: ModeDoc,
    centroid: CentroidDoc,
    normal: NormalDoc,
}

#[derive(Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
enum DepthDoc {
    Fixed(Real),
    Auto,
}

#[derive(Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
enum ModeDoc {
    Total,
    Normal,
}

#[derive(Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
enum CentroidDoc {
    Auto,
    Stiffness,
    World([Real; 3]),
    Body { body: usize, point: [Real; 3] },
}

#[derive(Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
enum NormalDoc {
    Horizontal { pitch: Real },
    Volume,
    Vector([Real; 3]),
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct GroundDoc {
    surface: SurfaceDoc,
    tyre_friction: Real,
    body_friction: Real,
    zones: Vec<ZoneDoc>,
}

#[derive(Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
enum SurfaceDoc {
    Plane { height: Real },
    Terrain { mesh: usize },
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct ZoneDoc {
    polygon: Vec<[Real; 2]>,
    friction: Real,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct RunDoc {
    duration: Real,
    dt: Real,
    record_interval: Option<Real>,
    max_history_bytes: u64,
    until_rest: bool,
    history: bool,
}

// -- spec -> document ------------------------------------------------------------------------

/// The meshes written so far (each `Arc` once).
#[derive(Default)]
struct Meshes {
    shapes: Vec<Arc<MeshShape>>,
}

impl Meshes {
    fn index(&mut self, shape: &Arc<MeshShape>) -> usize {
        if let Some(k) = self.shapes.iter().position(|s| Arc::ptr_eq(s, shape)) {
            return k;
        }
        self.shapes.push(shape.clone());
        self.shapes.len() - 1
    }
}

fn v3(v: &Vector) -> [Real; 3] {
    [v.x, v.y, v.z]
}

fn quat(q: &Rotation) -> [Real; 4] {
    [q.w, q.i, q.j, q.k]
}

fn table(t: &Table) -> Vec<[Real; 2]> {
    t.points().map(|(a, b)| [a, b]).collect()
}

fn vehicle_doc(v: &VehicleSpec) -> VehicleDoc {
    VehicleDoc {
        wheels: v
            .wheels
            .iter()
            .map(|w| WheelDoc {
                center: v3(&w.center.coords),
                radius: w.radius,
                steerable: w.steerable,
                static_load: w.static_load,
                spring_rate: w.spring_rate,
                damping: w.damping,
            })
            .collect(),
        tyre: v.tyre.clone(),
        steering: v.steering.clone(),
        anti_roll: v.anti_roll.clone(),
        abs: v.abs,
        steer: v.inputs.steer.clone(),
        brake: v.inputs.brake.clone(),
        drive: v
            .inputs
            .drive
            .iter()
            .map(|d| d.as_ref().map(table))
            .collect(),
        switches: v
            .inputs
            .switches
            .iter()
            .map(|s| SwitchDoc {
                wheel: s.wheel,
                at: match s.at {
                    Trigger::Time(t) => TriggerDoc::Time(t),
                    Trigger::Exchange(k) => TriggerDoc::Exchange(k),
                },
                state: match s.state {
                    WheelState::Free => WheelStateDoc::Free,
                    WheelState::Locked => WheelStateDoc::Locked,
                    WheelState::Braked(f) => WheelStateDoc::Braked(f),
                },
            })
            .collect(),
        coupling: v.coupling.map(|c| v3(&c.coords)),
        hitch_load: v.hitch_load.map(|(p, f)| (v3(&p.coords), f)),
        load_groups: v.load_groups.clone(),
    }
}

fn params_doc(p: &ContactParams) -> ParamsDoc {
    ParamsDoc {
        depth_of_penetration: match p.depth_of_penetration {
            DepthOfPenetration::Fixed(t) => DepthDoc::Fixed(t),
            DepthOfPenetration::Auto => DepthDoc::Auto,
        },
        restitution: p.restitution,
        friction: p.friction,
        restitution_mode: match p.restitution_mode {
            RestitutionMode::Total => ModeDoc::Total,
            RestitutionMode::Normal => ModeDoc::Normal,
        },
        centroid: match &p.centroid {
            CentroidMode::Auto => CentroidDoc::Auto,
            CentroidMode::Stiffness => CentroidDoc::Stiffness,
            CentroidMode::World(q) => CentroidDoc::World(v3(&q.coords)),
            CentroidMode::Body { body, point } => CentroidDoc::Body {
                body: *body,
                point: v3(&point.coords),
            },
        },
        normal: match &p.normal {
            NormalMode::Horizontal { pitch } => NormalDoc::Horizontal { pitch: *pitch },
            NormalMode::Volume => NormalDoc::Volume,
            NormalMode::Fixed(v) => NormalDoc::Vector(v3(v)),
        },
    }
}

/// A body's document; its mesh is indexed in `meshes` (added when new).
fn body_doc(b: &BodySpec, meshes: &mut Meshes) -> BodyDoc {
    BodyDoc {
        name: b.name.clone(),
        mesh: meshes.index(&b.shape),
        stiffness: Face::ALL.map(|f| b.stiffness.face(f).map(|s| [s.a, s.b])),
        ground_friction: b.ground_friction,
        motion: match &b.motion {
            BodyMotion::Moving {
                props,
                state,
                vehicle,
            } => {
                let i = props.inertia();
                MotionDoc::Moving {
                    mass: props.mass(),
                    inertia: [0, 1, 2].map(|r| [i[(r, 0)], i[(r, 1)], i[(r, 2)]]),
                    position: v3(&state.position.coords),
                    orientation: quat(&state.orientation),
                    velocity: v3(&state.velocity),
                    angular_velocity: v3(&state.angular_velocity),
                    vehicle: vehicle.as_ref().map(|v| Box::new(vehicle_doc(v))),
                }
            }
            BodyMotion::Fixed { pose } => MotionDoc::Fixed {
                position: v3(&pose.translation.vector),
                orientation: quat(&pose.rotation),
            },
        },
    }
}

/// The ground's document; a terrain's mesh is indexed in `meshes` (added when new).
fn ground_doc(g: &Ground, meshes: &mut Meshes) -> GroundDoc {
    GroundDoc {
        surface: match g.surface() {
            Surface::Plane { height } => SurfaceDoc::Plane { height: *height },
            Surface::Terrain(mesh) => SurfaceDoc::Terrain {
                mesh: meshes.index(mesh),
            },
        },
        tyre_friction: g.tyre_friction(),
        body_friction: g.body_friction(),
        zones: g
            .zones()
            .iter()
            .map(|z| ZoneDoc {
                polygon: z.polygon.clone(),
                friction: z.friction,
            })
            .collect(),
    }
}

fn document(spec: &SceneSpec) -> Document {
    let mut meshes = Meshes::default();
    let bodies = spec
        .bodies
        .iter()
        .map(|b| body_doc(b, &mut meshes))
        .collect();
    let ground = spec.ground.as_ref().map(|g| ground_doc(g, &mut meshes));
    let o = &spec.run.options;
    Document {
        format: FORMAT.into(),
        version: VERSION,
        meshes: meshes
            .shapes
            .iter()
            .map(|s| MeshDoc {
                vertices: s.vertices().iter().map(|p| v3(&p.coords)).collect(),
                triangles: s.triangles().to_vec(),
            })
            .collect(),
        bodies,
        contacts: spec
            .contacts
            .iter()
            .map(|c| ContactDoc {
                body1: c.body1,
                body2: c.body2,
                params: params_doc(&c.params),
            })
            .collect(),
        ground,
        no_contact: spec.no_contact.clone(),
        soft_contacts: spec
            .soft_contacts
            .iter()
            .map(|&(a, b, s)| (a, b, s.stiffness, s.damping_ratio))
            .collect(),
        joints: spec.joints.iter().map(joint_doc).collect(),
        run: RunDoc {
            duration: spec.run.duration,
            dt: spec.run.dt,
            record_interval: o.record_interval,
            max_history_bytes: o.max_history_bytes,
            until_rest: o.until_rest,
            history: o.history,
        },
    }
}

// -- document -> spec ------------------------------------------------------------------------

fn point(a: [Real; 3]) -> Point {
    Point::new(a[0], a[1], a[2])
}

/// A rotation from (w, x, y, z): kept bit for bit when it is a unit quaternion to round-off,
/// normalised otherwise; zero or non-finite is an error.
fn rotation(q: [Real; 4]) -> Result<Rotation> {
    let q = nalgebra::Quaternion::new(q[0], q[1], q[2], q[3]);
    let norm = q.norm();
    if !norm.is_finite() || norm == 0.0 {
        return Err(Error::invalid(
            "orientation must be a finite, non-zero quaternion (w, x, y, z)",
        ));
    }
    if (norm - 1.0).abs() <= 1e-12 {
        Ok(Rotation::new_unchecked(q))
    } else {
        Ok(Rotation::new_normalize(q))
    }
}

fn points(what: &str, rows: &[[Real; 2]]) -> Result<Table> {
    let p: Vec<(Real, Real)> = rows.iter().map(|r| (r[0], r[1])).collect();
    Table::new(what, &p)
}

fn vehicle(v: VehicleDoc) -> Result<VehicleSpec> {
    let wheels = v
        .wheels
        .iter()
        .map(|w| WheelSpec {
            center: point(w.center),
            radius: w.radius,
            steerable: w.steerable,
            static_load: w.static_load,
            spring_rate: w.spring_rate,
            damping: w.damping,
        })
        .collect();
    let tyre = v.tyre;
    let brake = v.brake;
    let mut drive = Vec::with_capacity(v.drive.len());
    for (k, d) in v.drive.iter().enumerate() {
        drive.push(match d {
            None => None,
            Some(t) => Some(points("drive force", t).map_err(|e| e.at(Place::Wheel(k)))?),
        });
    }
    let inputs = DriverInputs {
        steer: v.steer,
        brake,
        drive,
        switches: v
            .switches
            .iter()
            .map(|s| WheelSwitch {
                wheel: s.wheel,
                at: match s.at {
                    TriggerDoc::Time(t) => Trigger::Time(t),
                    TriggerDoc::Exchange(k) => Trigger::Exchange(k),
                },
                state: match s.state {
                    WheelStateDoc::Free => WheelState::Free,
                    WheelStateDoc::Locked => WheelState::Locked,
                    WheelStateDoc::Braked(f) => WheelState::Braked(f),
                },
            })
            .collect(),
    };
    Ok(VehicleSpec {
        wheels,
        tyre,
        steering: v.steering,
        anti_roll: v.anti_roll,
        abs: v.abs,
        inputs,
        coupling: v.coupling.map(point),
        hitch_load: v.hitch_load.map(|(p, f)| (point(p), f)),
        load_groups: v.load_groups,
    })
}

fn params(p: ParamsDoc) -> ContactParams {
    ContactParams {
        depth_of_penetration: match p.depth_of_penetration {
            DepthDoc::Fixed(t) => DepthOfPenetration::Fixed(t),
            DepthDoc::Auto => DepthOfPenetration::Auto,
        },
        restitution: p.restitution,
        friction: p.friction,
        restitution_mode: match p.restitution_mode {
            ModeDoc::Total => RestitutionMode::Total,
            ModeDoc::Normal => RestitutionMode::Normal,
        },
        centroid: match p.centroid {
            CentroidDoc::Auto => CentroidMode::Auto,
            CentroidDoc::Stiffness => CentroidMode::Stiffness,
            CentroidDoc::World(q) => CentroidMode::World(point(q)),
            CentroidDoc::Body { body, point: q } => CentroidMode::Body {
                body,
                point: point(q),
            },
        },
        normal: match p.normal {
            NormalDoc::Horizontal { pitch } => NormalMode::Horizontal { pitch },
            NormalDoc::Volume => NormalMode::Volume,
            NormalDoc::Vector(v) => NormalMode::Fixed(Vector::new(v[0], v[1], v[2])),
        },
    }
}

/// The meshes of the document, each checked and built (`MeshError` names the first broken
/// one).
fn mesh_shapes(meshes: Vec<MeshDoc>) -> Result<Vec<Arc<MeshShape>>> {
    let mut shapes = Vec::with_capacity(meshes.len());
    for (k, m) in meshes.into_iter().enumerate() {
        let v = m.vertices.into_iter().map(point).collect();
        let shape = MeshShape::new(v, m.triangles)
            .map_err(|e| Error::mesh(format!("scene spec mesh {k}: {e}")))?;
        shapes.push(Arc::new(shape));
    }
    Ok(shapes)
}

/// Mesh `k` of the document's `shapes`; an error when there is none.
fn mesh_at(shapes: &[Arc<MeshShape>], k: usize) -> Result<Arc<MeshShape>> {
    shapes.get(k).cloned().ok_or_else(|| {
        Error::invalid(format!(
            "the scene spec refers to mesh {k} but has {} meshes",
            shapes.len()
        ))
    })
}

/// Adds body `b` (its mesh `shape`) to `out`: a moving body (with its vehicle, if any) or
/// an obstacle, then its stiffness.
fn add_body(out: &mut SceneSpec, b: BodyDoc, shape: Arc<MeshShape>) -> Result<()> {
    let name = Some(b.name);
    let ground_friction = b.ground_friction;
    let i = match b.motion {
        MotionDoc::Moving {
            mass,
            inertia,
            position,
            orientation,
            velocity,
            angular_velocity,
            vehicle: v,
        } => {
            let props = MassProperties::new(mass, Matrix::from_fn(|r, c| inertia[r][c]))?;
            let state = BodyState {
                position: point(position),
                orientation: rotation(orientation)?,
                velocity: point(velocity).coords,
                angular_velocity: point(angular_velocity).coords,
            };
            let i = out.add_body(name, shape, props, state)?;
            if let Some(v) = v {
                out.set_vehicle(i, vehicle(*v)?)?;
            }
            i
        }
        MotionDoc::Fixed {
            position,
            orientation,
        } => {
            let pose = Isometry::from_parts(point(position).into(), rotation(orientation)?);
            out.add_obstacle(name, shape, pose)?
        }
    };
    let mut s = Stiffness::none();
    for (face, value) in Face::ALL.iter().zip(b.stiffness) {
        if let Some([a, bb]) = value {
            s = s.with(*face, FaceStiffness::new(a, bb)?);
        }
    }
    if let Some(mu) = ground_friction {
        out.set_ground_friction(i, mu)?;
    }
    out.set_stiffness(i, s)
}

/// The ground of `g` (a terrain's mesh from the document's `shapes`).
fn ground(g: GroundDoc, shapes: &[Arc<MeshShape>]) -> Result<Ground> {
    let base = match g.surface {
        SurfaceDoc::Plane { height } => Ground::plane(height)?,
        SurfaceDoc::Terrain { mesh: k } => Ground::terrain(mesh_at(shapes, k)?)?,
    };
    let zones = g
        .zones
        .into_iter()
        .map(|z| FrictionZone {
            polygon: z.polygon,
            friction: z.friction,
        })
        .collect();
    base.with_friction(g.tyre_friction, g.body_friction)?
        .with_zones(zones)
}

fn spec(doc: Document) -> Result<SceneSpec> {
    if doc.format != FORMAT || !(2..=VERSION).contains(&doc.version) {
        return Err(Error::invalid(format!(
            "not a scene spec this engine reads: format {:?} version {} (expected {FORMAT:?} \
             version {VERSION})",
            doc.format, doc.version
        )));
    }
    let shapes = mesh_shapes(doc.meshes)?;
    let mut out = SceneSpec::new();
    for b in doc.bodies {
        let shape = mesh_at(&shapes, b.mesh)?;
        add_body(&mut out, b, shape)?;
    }
    for c in doc.contacts {
        out.set_contact(c.body1, c.body2, params(c.params))?;
    }
    for (a, b) in doc.no_contact {
        out.set_no_contact(a, b)?;
    }
    for (a, b, stiffness, damping_ratio) in doc.soft_contacts {
        out.set_soft_contact(
            a,
            b,
            SoftContact {
                stiffness,
                damping_ratio,
            },
        )?;
    }
    for j in doc.joints {
        out.add_joint(joint(j)?)?;
    }
    if let Some(g) = doc.ground {
        out.set_ground(ground(g, &shapes)?);
    }
    out.run = RunSpec {
        duration: doc.run.duration,
        dt: doc.run.dt,
        options: RunOptions {
            record_interval: doc.run.record_interval,
            max_history_bytes: doc.run.max_history_bytes,
            until_rest: doc.run.until_rest,
            history: doc.run.history,
        },
    };
    Ok(out)
}

/// The spec as JSON text.
pub fn to_json(spec: &SceneSpec) -> String {
    serde_json::to_string(&document(spec)).expect("a scene spec document always serialises")
}

/// A spec from JSON text (a ParameterError, or a MeshError for a broken mesh, says what is
/// wrong).
pub fn from_json(text: &str) -> Result<SceneSpec> {
    let doc: Document = serde_json::from_str(text)
        .map_err(|e| Error::invalid(format!("the scene spec JSON is invalid: {e}")))?;
    spec(doc)
}

impl Serialize for SceneSpec {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        document(self).serialize(s)
    }
}

impl<'de> Deserialize<'de> for SceneSpec {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        let doc = Document::deserialize(d)?;
        spec(doc).map_err(serde::de::Error::custom)
    }
}

#[cfg(test)]
#[path = "document_tests.rs"]
mod tests;
