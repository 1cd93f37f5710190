//! crashsim-core: the collision engine of crashsim, pure Rust (parry3d-f64 + nalgebra).
//!
//! Vehicles are rigid bodies with triangle meshes ([`shape::MeshShape`]). When two meshes
//! first overlap a depth-of-penetration timer starts; when it expires one pair of impulses is
//! exchanged at the impulse centroid by the Kudlich-Slibar model ([`impulse`]). The
//! [`world::World`] steps everything and logs every exchange. Frames and units:
//! docs/model.md (SI; world z up; body frame at the CG, x forward, y left, z up).

pub mod batch;
pub mod bisect;
pub mod body;
pub mod bvh;
pub mod contact;
pub mod error;
pub mod ground;
pub mod impulse;
pub mod joint;
pub mod mass;
pub mod math;
pub mod motion;
pub mod overlap;
pub mod shape;
pub mod soft;
pub mod spec;
pub mod stiffness;
pub mod triangle;
pub mod vehicle;
pub mod world;

pub use body::{BodyState, MassProperties, RigidBody};
pub use contact::{CentroidMode, ContactParams, DepthOfPenetration, NormalMode};
pub use error::{error_kind, Error, ErrorKind, Place, Result};
pub use impulse::RestitutionMode;
pub use mass::SolidProperties;
pub use shape::MeshShape;
pub use soft::SoftContact;
pub use spec::{BodyMotion, BodySpec, ContactSpec, RunSpec, SceneSpec};
pub use stiffness::{Face, FaceStiffness, Stiffness};
pub use world::{
    ContactEvent, ContactEventKind, Impact, RunOptions, RunOutput, World, DEFAULT_MAX_HISTORY_BYTES,
};
