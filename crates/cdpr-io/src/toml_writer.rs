//! # Writing cdpr TOML
//!
//! The inverse of the TOML reader: every number the description models is written with the
//! shortest decimal text that reads back as the same `f64` (so a round trip is exact), the
//! gravity is always stated explicitly (CASPR's and WireLib's 9.81 m/s² differ from cdpr's
//! default 9.80665 m/s²), and per-cable bounds are written where they differ from the first
//! cable's.

use crate::RobotDescription;
use cdpr_kinematics::MotionPattern;
use nalgebra::{Matrix3, Vector3};
use std::fmt::Write;

fn num(v: f64) -> String {
    format!("{v:?}")
}

fn string(s: &str) -> String {
    toml::Value::String(s.to_string()).to_string()
}

fn vector(v: &Vector3<f64>, dim: usize) -> String {
    let parts: Vec<String> = v.iter().take(dim).map(|&x| num(x)).collect();
    format!("[{}]", parts.join(", "))
}

fn matrix(m: &Matrix3<f64>) -> String {
    let rows: Vec<String> = m.row_iter().map(|r| vector(&r.transpose(), 3)).collect();
    format!("[{}]", rows.join(", "))
}

impl RobotDescription {
    /// The robot as cdpr TOML; each line of `header` becomes a leading `#` comment (e.g. the
    /// source of a converted model).
    ///
    /// ```
    /// use cdpr_io::RobotDescription;
    /// let file = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/robots/tdpm-4.toml");
    /// let robot = RobotDescription::load(file).unwrap();
    /// let again = RobotDescription::parse(&robot.to_toml("copy"), "copy.toml").unwrap();
    /// assert_eq!(again.robot, robot.robot);
    /// assert_eq!(again.bounds, robot.bounds);
    /// ```
    pub fn to_toml(&self, header: &str) -> String {
        let motion = self.robot.motion();
        let dim = motion.space_dim();
        let mut s = String::new();
        for line in header.lines() {
            let _ = writeln!(s, "{}", format!("# {line}").trim_end());
        }
        let _ = writeln!(s, "name = {}", string(&self.name));
        let _ = writeln!(s, "motion = {}", string(motion.name()));
        if let Some(q) = &self.home_pose {
            let parts: Vec<String> = q.iter().map(|&x| num(x)).collect();
            let _ = writeln!(s, "home_pose = [{}]", parts.join(", "));
        }
        let (lo, hi) = (self.bounds.min(), self.bounds.max());
        let _ = writeln!(s, "\n[tension]\nmin = {}\nmax = {}", num(lo[0]), num(hi[0]));
        if self.limits != Default::default() {
            let _ = writeln!(s, "\n[limits]");
            if let Some(l) = self.limits.min_cable_length {
                let _ = writeln!(s, "min_cable_length = {}", num(l));
            }
            if let Some(d) = self.limits.min_jacobian_det {
                let _ = writeln!(s, "min_jacobian_det = {}", num(d));
            }
        }
        let p = &self.platform;
        let _ = writeln!(s, "\n[platform]\nmass = {}", num(p.mass));
        let _ = writeln!(s, "centre_of_mass = {}", vector(&p.centre_of_mass, dim));
        let _ = writeln!(s, "gravity = {}", vector(&p.gravity, dim));
        if let Some(i) = &self.inertia {
            let _ = writeln!(s, "inertia = {}", matrix(i));
        }
        if let Some(shape) = &self.platform_shape {
            let vertices: Vec<String> = shape.vertices().iter().map(|v| vector(v, 3)).collect();
            let _ = writeln!(s, "shape = {{ vertices = [{}] }}", vertices.join(", "));
        }
        for (i, c) in self.robot.cables().iter().enumerate() {
            let _ = writeln!(s, "\n[[cables]]");
            if let Some(Some(name)) = self.cable_names.get(i) {
                let _ = writeln!(s, "name = {}", string(name));
            }
            let _ = writeln!(s, "frame = {}", vector(&c.frame, dim));
            if motion.has_orientation() {
                let _ = writeln!(s, "platform = {}", vector(&c.platform, dim));
            }
            if let Some(es) = &self.axial_stiffness {
                let _ = writeln!(s, "axial_stiffness = {}", num(es[i]));
            }
            if let Some(rho) = &self.linear_density {
                let _ = writeln!(s, "linear_density = {}", num(rho[i]));
            }
            if let Some(e) = &self.encoders {
                let _ = writeln!(s, "offset = {}", num(e.offsets[i]));
                let _ = writeln!(s, "gain = {}", num(e.gains[i]));
            }
            if lo[i] != lo[0] {
                let _ = writeln!(s, "min = {}", num(lo[i]));
            }
            if hi[i] != hi[0] {
                let _ = writeln!(s, "max = {}", num(hi[i]));
            }
            if let Some(w) = self.winches.as_ref().map(|w| w[i]) {
                let mut fields = vec![
                    format!("drum_radius = {}", num(w.drum_radius)),
                    format!("gear_ratio = {}", num(w.gear_ratio)),
                    format!("motor_inertia = {}", num(w.motor_inertia)),
                ];
                if let Some(v) = w.max_torque {
                    fields.push(format!("max_torque = {}", num(v)));
                }
                if let Some(v) = w.max_speed {
                    fields.push(format!("max_speed = {}", num(v)));
                }
                if let Some(v) = w.cable_diameter {
                    fields.push(format!("cable_diameter = {}", num(v)));
                }
                if let Some(l) = w.layers {
                    fields.push(format!("turns_per_layer = {}", l.turns_per_layer));
                    fields.push(format!("cable_length = {}", num(l.cable_length)));
                }
                let _ = writeln!(s, "winch = {{ {} }}", fields.join(", "));
            }
            if let Some(pulley) = &c.pulley {
                debug_assert_eq!(motion, MotionPattern::Spatial);
                let _ = writeln!(
                    s,
                    "pulley = {{ radius = {}, orientation = {} }}",
                    num(pulley.radius),
                    matrix(&pulley.orientation)
                );
            }
        }
        if let Some(springs) = &self.passive_springs {
            let (k, l0) = (springs.stiffness(), springs.free_length());
            for (j, c) in springs.geometry().cables().iter().enumerate() {
                let _ = writeln!(s, "\n[[passive_springs]]");
                if let Some(Some(name)) = self.passive_spring_names.get(j) {
                    let _ = writeln!(s, "name = {}", string(name));
                }
                let _ = writeln!(s, "frame = {}", vector(&c.frame, dim));
                if motion.has_orientation() {
                    let _ = writeln!(s, "platform = {}", vector(&c.platform, dim));
                }
                let _ = writeln!(s, "stiffness = {}", num(k[j]));
                let _ = writeln!(s, "free_length = {}", num(l0[j]));
            }
        }
        s
    }
}
