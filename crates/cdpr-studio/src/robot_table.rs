//! # The robot table
//!
//! What the page shows and lets the user edit: frame anchors c_i and platform attachments ā_i
//! (m), tension bounds t_min, t_max (N) and the platform mass m (kg); and what it needs to build
//! its controls: the pose coordinates with their units, a starting pose, the box the sliders
//! span, and the tension methods that apply (with their references). Edits go back through
//! [`Studio::edit`], which rebuilds the robot with the library's own checks; the robot is then
//! downloaded with cdpr-io's writers ([`Studio::to_toml`], [`Studio::to_wcrfx`]).

use crate::{Studio, StudioError};
use cdpr_kinematics::{Cable, MotionPattern, Robot};
use cdpr_tension::{Method, TensionBounds};
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

/// One cable's row.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CableRow {
    /// Name from the robot file, if any.
    pub name: Option<String>,
    /// Frame anchor c_i (base coordinates, m).
    pub frame: [f64; 3],
    /// Platform attachment ā_i (platform coordinates, m).
    pub platform: [f64; 3],
    /// Lower tension bound t_min (N).
    pub t_min: f64,
    /// Upper tension bound t_max (N; null for ∞).
    pub t_max: Option<f64>,
    /// The cable runs over a swivel pulley (its anchor is then not editable here).
    pub pulley: bool,
}

/// A tension method that applies to the robot.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MethodRow {
    /// Command-line name.
    pub name: String,
    /// What it computes, with its reference (the page's hover text).
    pub reference: String,
}

/// The robot as the page shows it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RobotTable {
    /// Robot name.
    pub name: String,
    /// Motion pattern.
    pub motion: String,
    /// Pose coordinates: (name, unit), e.g. ("x", "m"), ("φ", "rad").
    pub coordinates: Vec<(String, String)>,
    /// A starting pose: the file's `home_pose`, else the centre of the anchors' box.
    pub start_pose: Vec<f64>,
    /// The anchors' bounding box (m): where the position sliders go.
    pub region: [[f64; 3]; 2],
    /// One row per cable.
    pub cables: Vec<CableRow>,
    /// Platform mass m (kg).
    pub mass: f64,
    /// The methods that apply (redundancy r = n − DOF).
    pub methods: Vec<MethodRow>,
    /// The file's warnings.
    pub warnings: Vec<String>,
}

fn coordinates(motion: MotionPattern) -> Vec<(String, String)> {
    let names: &[(&str, &str)] = match motion {
        MotionPattern::Point2 => &[("x", "m"), ("y", "m")],
        MotionPattern::Planar => &[("x", "m"), ("y", "m"), ("φ", "rad")],
        MotionPattern::Point3 => &[("x", "m"), ("y", "m"), ("z", "m")],
        _ => &[
            ("x", "m"),
            ("y", "m"),
            ("z", "m"),
            ("α", "rad"),
            ("β", "rad"),
            ("γ", "rad"),
        ],
    };
    names
        .iter()
        .map(|(n, u)| (n.to_string(), u.to_string()))
        .collect()
}

fn arr(v: &Vector3<f64>) -> [f64; 3] {
    [v.x, v.y, v.z]
}

impl Studio {
    /// The robot table.
    pub fn table(&self) -> RobotTable {
        let d = &self.desc;
        let motion = d.robot.motion();
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for c in d.robot.cables() {
            for k in 0..3 {
                lo[k] = lo[k].min(c.frame[k]);
                hi[k] = hi[k].max(c.frame[k]);
            }
        }
        let dim = motion.space_dim();
        let start_pose = d.home_pose.clone().unwrap_or_else(|| {
            let mut q = vec![0.0; motion.dof()];
            for k in 0..dim {
                q[k] = 0.5 * (lo[k] + hi[k]);
            }
            q
        });
        let r = d.robot.cable_count() as isize - d.robot.dof() as isize;
        RobotTable {
            name: d.name.clone(),
            motion: motion.name().into(),
            coordinates: coordinates(motion),
            start_pose,
            region: [lo, hi],
            cables: d
                .robot
                .cables()
                .iter()
                .enumerate()
                .map(|(i, c)| CableRow {
                    name: d.cable_names.get(i).cloned().flatten(),
                    frame: arr(&c.frame),
                    platform: arr(&c.platform),
                    t_min: d.bounds.min()[i],
                    t_max: Some(d.bounds.max()[i]).filter(|t| t.is_finite()),
                    pulley: c.pulley.is_some(),
                })
                .collect(),
            mass: d.platform.mass,
            methods: Method::applicable(r)
                .into_iter()
                .filter(|m| *m != Method::Sotda || d.axial_stiffness.is_some())
                .map(|m| MethodRow {
                    name: m.name().into(),
                    reference: m.summary().into(),
                })
                .collect(),
            warnings: d.warnings.clone(),
        }
    }

    /// Applies an edited table: anchors, attachments, bounds and mass (the other columns are
    /// read-only). The robot is rebuilt with the library's checks; on error nothing changes.
    pub fn edit(&mut self, table: &RobotTable) -> Result<(), StudioError> {
        let d = &self.desc;
        let n = d.robot.cable_count();
        if table.cables.len() != n {
            return Err(StudioError::Table {
                field: "cables",
                row: "robot".into(),
                problem: format!("{} rows for {n} cables", table.cables.len()),
            });
        }
        if !(table.mass.is_finite() && table.mass >= 0.0) {
            return Err(StudioError::Table {
                field: "mass (kg)",
                row: "platform".into(),
                problem: format!("{} is not a finite number ≥ 0", table.mass),
            });
        }
        let mut cables = Vec::with_capacity(n);
        for (i, (old, row)) in d.robot.cables().iter().zip(&table.cables).enumerate() {
            let frame = Vector3::from(row.frame);
            if old.pulley.is_some() && frame != old.frame {
                return Err(StudioError::Table {
                    field: "frame anchor (m)",
                    row: format!("cable {}", i + 1),
                    problem: "the cable runs over a pulley: edit its pulley in the robot file"
                        .into(),
                });
            }
            cables.push(Cable {
                frame,
                platform: Vector3::from(row.platform),
                pulley: old.pulley,
            });
        }
        let robot = Robot::new(d.robot.motion(), cables)?;
        let bounds = TensionBounds::new(
            table.cables.iter().map(|c| c.t_min).collect(),
            table
                .cables
                .iter()
                .map(|c| c.t_max.unwrap_or(f64::INFINITY))
                .collect(),
        )?;
        self.desc.robot = robot;
        self.desc.bounds = bounds;
        self.desc.platform.mass = table.mass;
        Ok(())
    }

    /// The robot as a cdpr TOML file.
    pub fn to_toml(&self) -> String {
        self.desc.to_toml("written by the cdpr studio")
    }

    /// The robot as a WireCenter `.wcrfx` file.
    pub fn to_wcrfx(&self) -> Result<String, StudioError> {
        Ok(self.desc.to_wcrfx(format!("{}.wcrfx", self.desc.name))?)
    }
}

#[cfg(test)]
mod tests {
    use crate::test_support::open;
    use crate::{RobotFileText, Studio};

    #[test]
    fn edits_round_trip_through_the_toml_download() {
        let mut s = open("ipanema-like-8.toml");
        assert!(s.to_wcrfx().unwrap().contains("<"));
        let mut t = s.table();
        assert_eq!(t.coordinates.len(), 6);
        assert!(t.methods.iter().any(|m| m.name == "l2"));
        t.cables[2].frame[2] += 0.25;
        t.cables[0].t_min = 12.0;
        t.mass = 7.5;
        s.edit(&t).unwrap();
        let again = Studio::open(&[RobotFileText {
            name: "copy.toml".into(),
            text: s.to_toml(),
        }])
        .unwrap();
        assert_eq!(again.table().cables, t.cables);
        assert_eq!(again.table().mass, 7.5);
        // .wcrfx has one tension range for all cables: the edited robot is refused, with why.
        let e = s.to_wcrfx().unwrap_err().to_string();
        assert!(e.contains("one range for all cables"), "{e}");
    }

    #[test]
    fn bad_edits_are_refused_and_change_nothing() {
        let mut s = open("tdpm-4.toml");
        let before = s.table();
        let mut t = before.clone();
        t.cables[1].t_min = 1e9; // above t_max
        let e = s.edit(&t).unwrap_err().to_string();
        assert!(e.contains("2") || e.contains("cable"), "{e}");
        t = before.clone();
        t.mass = f64::NAN;
        assert!(s.edit(&t).unwrap_err().to_string().contains("mass"));
        t = before.clone();
        t.cables.pop();
        assert!(s.edit(&t).is_err());
        assert_eq!(s.table(), before);
    }
}
