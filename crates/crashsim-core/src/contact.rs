//! Contact parameters of a vehicle pair: every field states its default, unit and effect.

use crate::error::{require_finite, require_finite_vector, Error, Place, Result};
use crate::impulse::RestitutionMode;
use crate::math::{Point, Real, Vector};
use crate::stiffness::{Face, Stiffness};

/// Largest accepted depth-of-penetration time (s).
pub const MAX_DEPTH_OF_PENETRATION: Real = 0.060;
/// The seed's typical range of dt_p (s): an automatic value outside it is reported.
pub const TYPICAL_DEPTH_OF_PENETRATION: (Real, Real) = (0.010, 0.060);

/// Footprint (m^2) the overlap must cover, seen from above, before the automatic normal of a
/// first exchange is read: its extent along the horizontal approach direction times its
/// extent across it. Default 0.018 m^2; a constant of the model (not a pair parameter).
///
/// The normal is read once the overlap is [`NORMAL_DEPTH`](crate::world::NORMAL_DEPTH) deep
/// *and* covers this footprint. A wide contact covers it by 2 cm of depth (a 0.9 m wide, 50 %
/// offset frontal exactly: 0.02 m x 0.9 m; a full-width frontal or a side impact sooner), so
/// its normal is read at 2 cm as before. A narrow overlap (a corner clip, a glancing pass with
/// lateral overlap d) has to sink 0.018 / d deep first; by then its side walls, which sank into
/// each other, turn the normal by atan(0.018 / d^2) toward the glance, so a corner clip slides
/// off instead of stopping both vehicles. The length scale is sqrt(0.018) = 13 cm of overlap.
/// Read at a set crushed footprint rather than a set depth, the normal is taken after about
/// the same crush work whatever the overlap's width (CRASH3's force per width A, 35-60 kN/m,
/// times the footprint: 0.6-1.1 kJ).
///
/// Measured (docs/glancing.md, benches/glancing_study.py): two boxes head-on at 20 m/s each
/// with lateral overlap d went, with 2 cm alone, from a 0.7 m/s slide at d = 1 mm to a full
/// stop (19.7 m/s) at 20 mm, up to 1.4 m/s per mm of d; with this footprint delta-V grows
/// monotonically, about as d^2 (0.5 m/s at 20 mm, 11.8 at 0.1 m), to the full impact at
/// 0.13-0.15 m, at most 0.3 m/s per mm. 0.018 m^2 is the largest footprint that keeps the
/// model's contract (docs/model.md, the 50 % offset frontal's normal within 1.3 deg, read at 2 cm); the
/// small-overlap crash data (glance-off common below about 30 % overlap) would argue for more.
pub const NORMAL_FOOTPRINT: Real = 0.018;

/// The automatic normal of a first exchange is read no deeper than where the overlap's vector
/// area (mesh 1's surface inside 2 minus 2's inside 1, m^2) is still sound: its magnitude at
/// least this fraction of the largest it reaches at the probed shallower depths, and its
/// direction within acos(-this) = 120 deg of the normal of the shallowest overlap (the faces
/// that met). Default 1/2, a constant of the model.
///
/// While one body dents another the vector area grows with depth (and may turn, as a corner
/// clip develops into a scrape along the sides). Once a thin part (a wall, a plate, a post
/// thinner than the reading depth) has been cut through, the faces that met have left the
/// overlap: the part's two faces cancel against a long body (a 1 cm wall read 2 cm deep:
/// from 2 x 1.8 m x 1.4 m to the noise of the side strips, the normal turned sideways and no
/// exchange) or point back against the faces that met when both parts are thin (a plate
/// through a plate); a small part wholly inside the other has none at all (a closed
/// surface's vector area is zero: a 1 cm cube 2 cm into a car). Then the reading moves to the
/// deepest shallower probe that is sound.
pub const NORMAL_COLLAPSE: Real = 0.5;

/// Number of shallower depths probed for a thin part: NORMAL_DEPTH / NORMAL_PROBE_RATIO^k,
/// k = 1 ..= this (5 mm, 1.25 mm ... down to 5 um). Bounded: at most this many overlap
/// regions per first overlap, each over an overlap no deeper than 2 cm. Each costs about
/// 2 ms at 20k triangles: 12 probes a factor 2 apart made the step with a first overlap of the
/// 20k seed scene 28 ms; 6 a factor 4 apart find the same thin parts
/// (tests/integration/thin_parts.rs).
pub const NORMAL_PROBES: usize = 6;
/// The ratio of neighbouring probe depths.
pub const NORMAL_PROBE_RATIO: Real = 4.0;

/// Instants sampled across a timer to find out whether the overlap ends before the exchange
/// (a thin part passing through, a corner clipping a post): dt_p / this apart. Default 16
/// (about 2 ms for 30 ms). An overlap shorter than a sample spacing is still found when it is
/// the first one (the first sample is already apart); the end is then bisected to 1e-9 s.
pub const OVERLAP_SAMPLES: usize = 16;

/// Iterations of the golden-section search for the deepest overlap of an overlap that ends
/// before its timer expires (after the best of [`OVERLAP_SAMPLES`] samples): the bracket
/// shrinks to 0.618^40 = 4e-9 of two sample spacings. Bounded by construction.
pub const DEEPEST_ITERATIONS: usize = 40;

/// How long the meshes pass through each other before the exchange.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DepthOfPenetration {
    /// A fixed time (s) in [0, 0.060].
    Fixed(Real),
    /// Per impact, dt_p = sqrt(m'/k') from the reduced effective mass m' along the normal at
    /// the centroid and the series stiffness k' of the struck faces (k = B W, W the overlap
    /// width), evaluated at the exchange itself; clamped to [0, 0.060] s. Needs face
    /// stiffness on both bodies; a fixed obstacle without any is rigid (k infinite, so k' is
    /// the vehicle's own B W), as the report already takes it.
    ///
    /// Against a rigid barrier a narrow overlap is a soft spring (W small): the 25 % IIHS
    /// small-overlap frontal of the CF11002 Ford Fusion (sedan class B 0.77 MN/m^2, W 0.71 m,
    /// m' 1,603 kg) gets dt_p 54 ms and 0.93 m of crush at the exchange, where the fixed 30 ms
    /// crushes 0.52 m (docs/glancing.md section 7, benches/small_overlap.py).
    Auto,
}

/// Where the impulse centroid P goes.
#[derive(Clone, Debug, PartialEq, Default)]
pub enum CentroidMode {
    /// Centre of the overlap region's box in the contact frame (default).
    #[default]
    Auto,
    /// A fixed world point (m).
    World(Point),
    /// A point fixed in a body's frame (m from its CG); `body` is the pair's body index in
    /// the world (it must be one of the pair).
    Body {
        /// World index of the body whose frame holds the point.
        body: usize,
        /// The point, body frame (m).
        point: Point,
    },
    /// The automatic centroid moved along n inside the overlap region so that the crush
    /// splits as C1 : C2 = k2 : k1 (seed eqs. 34-35). Needs face stiffness on both bodies; a
    /// fixed obstacle without any is rigid and takes no crush, so P lies on its surface: the
    /// common-tangent plane (normal n) through its part of the overlap, e.g. a barrier's
    /// edge.
    ///
    /// Measured against Brach's fits of three IIHS small-overlap tests of a Ford Fusion
    /// (impulse centre 1.10-1.28 m ahead of the CG, 0.57-0.62 m to the struck side,
    /// restitution 0): with `depth_of_penetration = Auto` the engine's P is (1.40, 0.55) m
    /// and its yaw-rate change 133 deg/s (tests: 103, 157, 196 deg/s); the automatic centroid
    /// at 30 ms, the middle of the crushed volume, is (2.07, 0.68) m and 104 deg/s
    /// (docs/glancing.md section 7).
    Stiffness,
}

/// How the contact normal n (from body 1 into body 2) is chosen.
#[derive(Clone, Debug, PartialEq)]
pub enum NormalMode {
    /// The horizontal part of the volume normal, tilted up by `pitch` rad (default pitch 0:
    /// the contact plane stands vertical).
    Horizontal {
        /// Tilt of the normal above the horizontal (rad), in [-pi/2, pi/2].
        pitch: Real,
    },
    /// The full 3-D volume normal (override and underride).
    Volume,
    /// A user-given world direction (normalized here).
    Fixed(Vector),
}

impl Default for NormalMode {
    fn default() -> Self {
        NormalMode::Horizontal { pitch: 0.0 }
    }
}

/// Parameters of one vehicle pair.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactParams {
    /// Time from first overlap to the impulse exchange; default Fixed(0.030 s).
    pub depth_of_penetration: DepthOfPenetration,
    /// Coefficient of restitution; default 0.1, in [0, 1].
    pub restitution: Real,
    /// Inter-vehicle friction coefficient; default 0.6, >= 0.
    pub friction: Real,
    /// Restitution convention; default Kudlich-Slibar (total).
    pub restitution_mode: RestitutionMode,
    /// Impulse centroid placement; default automatic.
    pub centroid: CentroidMode,
    /// Contact normal; default horizontal volume normal.
    pub normal: NormalMode,
}

impl Default for ContactParams {
    fn default() -> Self {
        ContactParams {
            depth_of_penetration: DepthOfPenetration::Fixed(0.030),
            restitution: 0.1,
            friction: 0.6,
            restitution_mode: RestitutionMode::Total,
            centroid: CentroidMode::Auto,
            normal: NormalMode::default(),
        }
    }
}

impl ContactParams {
    /// True when the parameters need face stiffness on both bodies.
    pub fn needs_stiffness(&self) -> bool {
        self.depth_of_penetration == DepthOfPenetration::Auto
            || self.centroid == CentroidMode::Stiffness
    }

    /// An error when these parameters need face stiffness (auto depth of penetration, the
    /// stiffness centroid) that a body of the pair lacks: each side is (its body index, its
    /// stiffness, whether it is a fixed obstacle). A fixed obstacle with no stiffness at all
    /// is rigid and needs none. The error is placed at the body that lacks it.
    pub fn check_stiffness(&self, sides: [(usize, &Stiffness, bool); 2]) -> Result<()> {
        if !self.needs_stiffness() {
            return Ok(());
        }
        for (i, s, obstacle) in sides {
            if obstacle && s.is_none() {
                continue;
            }
            if let Some(face) = Face::ALL.iter().find(|f| s.face(**f).is_none()) {
                let fix = if obstacle {
                    "give the obstacle's other faces a stiffness too, or none at all for a rigid \
                     obstacle"
                } else {
                    "give the vehicle a stiffness (or build it from a vehicle class), or use a \
                     fixed dt_p and the automatic centroid"
                };
                return Err(Error::invalid(format!(
                    "it has no stiffness on its {} face: depth_of_penetration = auto and \
                     centroid = stiffness need CRASH3 A and B on every face of both bodies, or \
                     none on a fixed obstacle (rigid); {fix}",
                    face.name()
                ))
                .at(Place::body(i)));
            }
        }
        Ok(())
    }

    /// Checks every field's range.
    pub fn validate(&self) -> Result<()> {
        if let DepthOfPenetration::Fixed(dtp) = self.depth_of_penetration {
            require_finite("depth_of_penetration", dtp)?;
            if !(0.0..=MAX_DEPTH_OF_PENETRATION).contains(&dtp) {
                return Err(Error::parameter(
                    "depth_of_penetration",
                    dtp,
                    "it must lie in [0, 0.060] s (the seed's range; default 0.030 s) or be auto",
                ));
            }
        }
        require_finite("restitution", self.restitution)?;
        if !(0.0..=1.0).contains(&self.restitution) {
            return Err(Error::parameter(
                "restitution",
                self.restitution,
                "a coefficient of restitution must lie in [0, 1]",
            ));
        }
        require_finite("friction", self.friction)?;
        if self.friction < 0.0 {
            return Err(Error::parameter(
                "friction",
                self.friction,
                "a friction coefficient must be >= 0",
            ));
        }
        match &self.centroid {
            CentroidMode::World(p) | CentroidMode::Body { point: p, .. } => {
                require_finite_vector("centroid", &p.coords)?
            }
            CentroidMode::Auto | CentroidMode::Stiffness => {}
        }
        match &self.normal {
            NormalMode::Horizontal { pitch } => {
                require_finite("pitch", *pitch)?;
                if pitch.abs() > std::f64::consts::FRAC_PI_2 {
                    return Err(Error::parameter(
                        "pitch",
                        pitch,
                        "it must lie in [-pi/2, pi/2] rad",
                    ));
                }
            }
            NormalMode::Fixed(v) => {
                require_finite_vector("normal", v)?;
                if v.norm() == 0.0 {
                    return Err(Error::invalid(
                        "the normal vector is zero: give a direction from vehicle 1 into vehicle 2",
                    ));
                }
            }
            NormalMode::Volume => {}
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::{error_kind, ErrorKind};

    #[test]
    fn out_of_range_parameters_are_refused() {
        let ok = ContactParams::default();
        assert!(ok.validate().is_ok());
        for bad in [
            ContactParams {
                depth_of_penetration: DepthOfPenetration::Fixed(0.061),
                ..ok.clone()
            },
            ContactParams {
                depth_of_penetration: DepthOfPenetration::Fixed(-0.001),
                ..ok.clone()
            },
            ContactParams {
                depth_of_penetration: DepthOfPenetration::Fixed(Real::NAN),
                ..ok.clone()
            },
            ContactParams {
                restitution: 1.01,
                ..ok.clone()
            },
            ContactParams {
                restitution: -0.1,
                ..ok.clone()
            },
            ContactParams {
                friction: -0.1,
                ..ok.clone()
            },
            ContactParams {
                friction: Real::INFINITY,
                ..ok.clone()
            },
            ContactParams {
                normal: NormalMode::Fixed(Vector::zeros()),
                ..ok.clone()
            },
        ] {
            assert!(
                error_kind(&bad.validate()) == Some(ErrorKind::Parameter),
                "{bad:?}"
            );
        }
        for edge in [0.0, 0.060] {
            assert!(ContactParams {
                depth_of_penetration: DepthOfPenetration::Fixed(edge),
                ..ok.clone()
            }
            .validate()
            .is_ok());
        }
    }
}
