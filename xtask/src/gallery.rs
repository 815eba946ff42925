//! # `cargo xtask gallery`
//!
//! Writes `docs/robots.md`: for every published robot shipped in `examples/robots/`
//! (`caspr-*.toml`, `wirecenter-*.toml`) a row with DOF, cables, frame size and platform mass, and
//! what cdpr computes at its home pose and over its frame — cable tensions under its own weight
//! (ℓ2-optimal, eq. 6.17 of the thesis chapter on planar tendon-driven manipulators), the
//! capacity margin of its own weight (hyperplane shifting, Picard, Caro, Plestan & Claveau
//! 2020), the constant-orientation wrench-feasible workspace on a coarse grid (Algorithm 6.2,
//! extended to 3-D), and the extreme eigenvalues of the translational block of the stiffness
//! matrix K = Kp + Ka (seed 002 eq. (4)) where the file gives the cables' E·S — with one
//! picture each.
//!
//! Every number comes from running the `cdpr` binary (release build) with `--json`, and the
//! page prints each command, so anyone can reproduce any number. Coarse grids keep the run
//! short: 8 intervals per side in space ((8+1)³ = 729 points), 20 in the plane (441 points).

use nalgebra::{DMatrix, Matrix2, Matrix3, Vector3};
use serde_json::Value;
use std::fmt::Write;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use cdpr::RobotDescription;
use cdpr::kinematics::MotionPattern;

/// Grid intervals per side of the workspace grid, in space and in the plane.
const GRID_SPACE: usize = 8;
const GRID_PLANE: usize = 20;

/// One robot's results.
struct Row {
    file: String,
    name: String,
    source: String,
    motion: MotionPattern,
    cables: usize,
    frame: [f64; 3],
    mass: f64,
    pulleys: usize,
    pose: Vec<f64>,
    pose_from_file: bool,
    tensions: Option<(f64, f64)>,
    tension_reason: String,
    margin: Option<f64>,
    volume: f64,
    volume_unit: &'static str,
    /// The same workspace with straight cables (`--kinematics standard`), for files with pulleys.
    volume_straight: Option<f64>,
    feasible_points: u64,
    total_points: u64,
    stiffness: Option<(f64, f64)>,
    commands: Vec<String>,
    picture: String,
}

fn join(q: &[f64]) -> String {
    q.iter()
        .map(|v| format!("{v}"))
        .collect::<Vec<_>>()
        .join(",")
}

fn run_json(bin: &Path, root: &Path, args: &[String]) -> Result<Value, String> {
    let out = Command::new(bin)
        .args(args)
        .current_dir(root)
        .output()
        .map_err(|e| format!("running {}: {e}", bin.display()))?;
    if !out.status.success() {
        return Err(format!(
            "cdpr {}: {}",
            args.join(" "),
            String::from_utf8_lossy(&out.stderr)
        ));
    }
    serde_json::from_slice(&out.stdout).map_err(|e| format!("cdpr {}: {e}", args.join(" ")))
}

/// Extreme eigenvalues of the symmetric part of the translational block of K.
fn translational_extremes(k: &Value, dim: usize) -> Option<(f64, f64)> {
    let rows = k.as_array()?;
    let n = rows.len();
    let m = DMatrix::from_fn(n, n, |i, j| rows[i][j].as_f64().unwrap_or(f64::NAN));
    let eig: Vec<f64> = if dim == 3 {
        let b = Matrix3::from_fn(|i, j| 0.5 * (m[(i, j)] + m[(j, i)]));
        b.symmetric_eigenvalues().iter().copied().collect()
    } else {
        let b = Matrix2::from_fn(|i, j| 0.5 * (m[(i, j)] + m[(j, i)]));
        b.symmetric_eigenvalues().iter().copied().collect()
    };
    let lo = eig.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = eig.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    lo.is_finite().then_some((lo, hi))
}

/// The region "over its frame": the default region of every front end
/// ([`cdpr::kinematics::Robot::default_region`]): the bounding box of the frame anchors, except
/// that a spatial frame whose anchors span less than a quarter of its width in height (all
/// anchors near one level: CAROCA, CoGiRo, FAST, ACROBOT, HRPCables) is given a height of half
/// its width below its highest anchor, where the platform hangs.
fn frame_box(desc: &RobotDescription) -> (Vector3<f64>, Vector3<f64>) {
    desc.robot.default_region()
}

fn robot_row(bin: &Path, root: &Path, path: &Path) -> Result<Row, String> {
    let desc = RobotDescription::load(path).map_err(|e| e.to_string())?;
    let rel = path
        .strip_prefix(root)
        .unwrap_or(path)
        .display()
        .to_string();
    let file = path.file_stem().unwrap().to_string_lossy().into_owned();
    let text = std::fs::read_to_string(path).map_err(|e| e.to_string())?;
    let source = text
        .lines()
        .next()
        .and_then(|l| l.strip_prefix("# "))
        .and_then(|l| l.split(':').next())
        .unwrap_or(&desc.name)
        .to_string();
    let motion = desc.robot.motion();
    let dim = motion.space_dim();
    let (lo, hi) = frame_box(&desc);
    let centre = (lo + hi) / 2.0;
    let (pose, pose_from_file) = match &desc.home_pose {
        Some(q) => (q.clone(), true),
        None => (
            match motion {
                MotionPattern::Point2 => vec![centre.x, centre.y],
                MotionPattern::Planar => vec![centre.x, centre.y, 0.0],
                MotionPattern::Point3 => vec![centre.x, centre.y, centre.z],
                MotionPattern::Spatial => vec![centre.x, centre.y, centre.z, 0.0, 0.0, 0.0],
            },
            false,
        ),
    };
    let p = join(&pose);
    let mut commands = Vec::new();
    let mut cmd = |args: Vec<String>| -> Result<Value, String> {
        commands.push(format!("cdpr {}", args.join(" ")));
        run_json(bin, root, &args)
    };
    let s = |v: &[&str]| v.iter().map(|x| x.to_string()).collect::<Vec<_>>();
    // Tensions under the platform's own weight (ℓ2).
    let t = cmd(s(&[
        "tension", &rel, "--pose", &p, "--method", "l2", "--json",
    ]))?;
    let tensions_vec: Option<Vec<f64>> = t["tensions"]
        .as_array()
        .map(|a| a.iter().filter_map(Value::as_f64).collect());
    let tensions = tensions_vec.as_ref().map(|v| {
        (
            v.iter().copied().fold(f64::INFINITY, f64::min),
            v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        )
    });
    let tension_reason = t["reason"].as_str().unwrap_or("").to_string();
    // Capacity margin of the own weight (a required set of one wrench: a ball of radius 0).
    let c = cmd(s(&[
        "capacity",
        &rel,
        "--pose",
        &p,
        "--wrench-ball",
        "0",
        "--json",
    ]))?;
    let margin = c["capacity_margin"].as_f64();
    // Constant-orientation wrench-feasible workspace over the frame's bounding box.
    let grid = if dim == 3 { GRID_SPACE } else { GRID_PLANE };
    let picture = format!("robots/{file}.png");
    let mut ws_args = s(&["workspace", &rel, "--grid", &grid.to_string()]);
    if dim == 3 {
        // The certified boundary mesh: its volume converges far faster than the grid count.
        ws_args.extend(s(&["--boundary", "mesh"]));
    }
    let (alo, ahi) = desc.robot.frame_bounding_box();
    if (lo, hi) != (alo, ahi) {
        let b: Vec<f64> = (0..dim).flat_map(|k| [lo[k], hi[k]]).collect();
        ws_args.extend(s(&["--box", &join(&b)]));
    }
    if motion.has_orientation() {
        let zero = if motion == MotionPattern::Spatial {
            "0,0,0"
        } else {
            "0"
        };
        ws_args.extend(s(&["--orientation", zero]));
    }
    ws_args.extend(s(&["--plot", &format!("docs/{picture}"), "--json"]));
    let w = cmd(ws_args.clone())?;
    let (volume, volume_unit) = if dim == 3 {
        (w["volume"].as_f64().unwrap_or(f64::NAN), "m³")
    } else {
        (w["area"].as_f64().unwrap_or(f64::NAN), "m²")
    };
    // With pulleys, the same workspace with straight cables.
    let has_pulleys = desc.robot.cables().iter().any(|c| c.pulley.is_some());
    let volume_straight = if has_pulleys {
        let mut a: Vec<String> = ws_args
            .iter()
            .take_while(|x| x.as_str() != "--plot")
            .cloned()
            .collect();
        a.extend(s(&["--kinematics", "standard", "--json"]));
        let w = cmd(a)?;
        w[if dim == 3 { "volume" } else { "area" }].as_f64()
    } else {
        None
    };
    // Stiffness at the home pose under those tensions, where the file gives E·S.
    let stiffness = match (&tensions_vec, &desc.axial_stiffness) {
        (Some(tv), Some(_)) => {
            let k = cmd(s(&[
                "stiffness",
                &rel,
                "--pose",
                &p,
                "--tensions",
                &join(tv),
                "--json",
            ]))?;
            translational_extremes(&k["stiffness"], dim)
        }
        _ => None,
    };
    Ok(Row {
        file,
        name: desc.name.clone(),
        source,
        motion,
        cables: desc.robot.cable_count(),
        frame: {
            let (a, b) = desc.robot.frame_bounding_box();
            [b.x - a.x, b.y - a.y, b.z - a.z]
        },
        mass: desc.platform.mass,
        pulleys: desc
            .robot
            .cables()
            .iter()
            .filter(|c| c.pulley.is_some())
            .count(),
        pose,
        pose_from_file,
        tensions,
        tension_reason,
        margin,
        volume,
        volume_unit,
        volume_straight,
        feasible_points: w["feasible_points"].as_u64().unwrap_or(0),
        total_points: w["total_points"].as_u64().unwrap_or(0),
        stiffness,
        commands,
        picture,
    })
}

fn fmt(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if v.abs() >= 1e5 || v.abs() < 1e-2 {
        format!("{v:.3e}")
    } else {
        format!("{v:.3}")
    }
}

fn markdown(rows: &[Row]) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# Published cable robots in cdpr\n\n\
         Generated by `cargo xtask gallery` (also run by `cargo xtask reproduce`) \
         from the robot files in `examples/robots/` — the published models of CASPR and WireCenter, \
         converted by `cdpr convert` from the originals in `crates/cdpr-io/tests/data/` (each file's \
         header names its source, licence and publication; `docs/robot-file.md` explains the \
         conversion). Every number below is printed by the `cdpr` command listed under the robot.\n"
    );
    let _ = writeln!(
        s,
        "**Columns.** *frame*: size of the bounding box of the frame anchors (m). *mass*: platform \
         mass from the file (kg). *home pose*: the file's initial pose (CASPR `q_initial`), else \
         the centre of the region below with zero orientation (marked †). *tensions*: \
         smallest and largest cable tension (N) balancing the platform's own weight at the home \
         pose, ℓ2-optimal within the file's tension bounds (`cdpr tension --method l2`); \
         *infeasible* when no tensions within the bounds exist. *margin*: capacity margin of the \
         own-weight wrench at the home pose (`cdpr capacity --wrench-ball 0`; wrench units N and \
         N·m; negative: the weight is not sustainable there). *WFW*: constant-orientation \
         wrench-feasible workspace (own weight, file bounds, zero orientation) over the frame: \
         the bounding box of the frame anchors, or, when the anchors span less than a quarter of \
         the frame's width in height, that box extended to half the width below the highest \
         anchor (the `--box` printed with the command; the same rule, `Robot::default_region`, is the \
         default region of `cdpr workspace`, `dextrous`, `synthesize` and Python's `workspace()`, and \
         places the hanging starts of `cdpr forward`) — on a coarse grid of {GRID_SPACE} intervals per side in space \
         ({} points), {GRID_PLANE} in the plane ({} points): in space the volume (m³) enclosed by \
         the boundary mesh seeded by that grid, every vertex bisected onto the boundary to 1e-8 \
         of the box (`--boundary mesh`); in the plane the area (m²) by the cell convention; and \
         the share of feasible grid points. *K*: smallest and largest \
         eigenvalue (N/m) of the translational block of the stiffness matrix K = Kp + Ka at the \
         home pose under those tensions (`cdpr stiffness`), where the file gives the cables' E·S.\n",
        (GRID_SPACE + 1).pow(3),
        (GRID_PLANE + 1).pow(2)
    );
    let _ = writeln!(
        s,
        "**Pulleys.** Files with swivel pulleys (every WireCenter file, CASPR CAROCA's rotating \
         pulleys) are evaluated with the pulley model (Pott 2018: each cable wraps its pulley and \
         leaves it tangentially; cdpr's default when a file has pulleys), and their workspace is \
         also computed with straight cables from the pulley points (`--kinematics standard`, \
         the second workspace command): the WFW column gives both and the change the pulleys \
         make.\n"
    );
    let _ = writeln!(
        s,
        "**Platform data.** The numbers are the files' own. Many WireCenter files carry WireCenter's \
         default platform rather than the robot's (25 kg, centre of gravity (0, 1, 0.2) m, \
         Ixx = 14 kg·m², named \"Kaelbertraenke\" in some) and no `<application>` loads, so cdpr \
         uses the winch's f_max (0–720 N); a centre of gravity 1 m off the platform centre makes \
         the weight unsustainable at most poses (*infeasible*, negative margins): the gallery \
         shows the files as published, it does not correct them.\n"
    );
    let _ = writeln!(
        s,
        "| robot | source | DOF | cables | pulleys | frame (m) | mass (kg) | home pose | tensions (N) | margin | WFW | K (N/m) |\n|---|---|---|---|---|---|---|---|---|---|---|---|"
    );
    for r in rows {
        let frame = if r.motion.space_dim() == 3 {
            format!("{:.2} × {:.2} × {:.2}", r.frame[0], r.frame[1], r.frame[2])
        } else {
            format!("{:.2} × {:.2}", r.frame[0], r.frame[1])
        };
        let pose = format!(
            "({}){}",
            r.pose
                .iter()
                .map(|v| fmt(*v))
                .collect::<Vec<_>>()
                .join(", "),
            if r.pose_from_file { "" } else { " †" }
        );
        let tensions = match r.tensions {
            Some((a, b)) => format!("{} – {}", fmt(a), fmt(b)),
            None => "infeasible".into(),
        };
        let margin = r.margin.map(fmt).unwrap_or_else(|| "—".into());
        let mut wfw = format!(
            "{} {} ({:.0} %)",
            fmt(r.volume),
            r.volume_unit,
            100.0 * r.feasible_points as f64 / r.total_points.max(1) as f64
        );
        if let Some(v) = r.volume_straight {
            let change = if v > 0.0 {
                format!("{:+.1} %", 100.0 * (r.volume - v) / v)
            } else {
                "—".into()
            };
            let _ = write!(
                wfw,
                "; straight cables {} {}, pulleys {change}",
                fmt(v),
                r.volume_unit
            );
        }
        let k = match r.stiffness {
            Some((a, b)) => format!("{} – {}", fmt(a), fmt(b)),
            None => "—".into(),
        };
        let _ = writeln!(
            s,
            "| [{}](#{}) | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            r.name,
            r.file,
            r.source,
            r.motion.dof(),
            r.cables,
            r.pulleys,
            frame,
            fmt(r.mass),
            pose,
            tensions,
            margin,
            wfw,
            k
        );
    }
    for r in rows {
        let _ = writeln!(s, "\n## {}\n", r.file);
        let _ = writeln!(
            s,
            "{} — `examples/robots/{}.toml` ({}, {} cables).{}\n",
            r.source,
            r.file,
            r.motion,
            r.cables,
            if r.tensions.is_none() && !r.tension_reason.is_empty() {
                format!(" At the home pose: {}.", r.tension_reason)
            } else {
                String::new()
            }
        );
        let _ = writeln!(s, "```sh");
        for c in &r.commands {
            let _ = writeln!(s, "{c}");
        }
        let _ = writeln!(s, "```\n");
        let _ = writeln!(s, "![{} workspace]({})", r.name, r.picture);
    }
    s
}

/// Builds the `cdpr` binary, evaluates every shipped published robot and writes
/// docs/robots.md and its pictures in docs/robots/.
pub fn run(root: &Path) -> Result<(), String> {
    let clock = Instant::now();
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let status = Command::new(cargo)
        .args(["build", "--release", "-p", "cdpr", "--bin", "cdpr"])
        .current_dir(root)
        .status()
        .map_err(|e| format!("building cdpr: {e}"))?;
    if !status.success() {
        return Err("building cdpr failed".into());
    }
    let bin = root.join("target/release/cdpr");
    std::fs::create_dir_all(root.join("docs/robots")).map_err(|e| e.to_string())?;
    let mut files: Vec<PathBuf> = std::fs::read_dir(root.join("examples/robots"))
        .map_err(|e| e.to_string())?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            let n = p.file_name().unwrap().to_string_lossy();
            (n.starts_with("caspr-") || n.starts_with("wirecenter-")) && n.ends_with(".toml")
        })
        .collect();
    files.sort();
    let mut rows = Vec::new();
    for f in &files {
        eprintln!("  {}", f.display());
        rows.push(robot_row(&bin, root, f)?);
    }
    let seconds = clock.elapsed().as_secs_f64();
    let md = root.join("docs/robots.md");
    std::fs::write(&md, markdown(&rows)).map_err(|e| e.to_string())?;
    eprintln!(
        "wrote {} ({} robots) in {seconds:.1} s",
        md.display(),
        rows.len()
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn translational_extremes_of_a_hand_made_stiffness() {
        // K = diag(3, 1, 2, 100, 100, 100) with a symmetric coupling 0.5 between x and y: the
        // translational block [[3, .5, 0], [.5, 1, 0], [0, 0, 2]] has eigenvalues 2 ± √1.25 and 2.
        let k = serde_json::json!([
            [3.0, 0.5, 0.0, 0.0, 0.0, 0.0],
            [0.5, 1.0, 0.0, 0.0, 0.0, 0.0],
            [0.0, 0.0, 2.0, 0.0, 0.0, 0.0],
            [0.0, 0.0, 0.0, 100.0, 0.0, 0.0],
            [0.0, 0.0, 0.0, 0.0, 100.0, 0.0],
            [0.0, 0.0, 0.0, 0.0, 0.0, 100.0]
        ]);
        let (lo, hi) = translational_extremes(&k, 3).unwrap();
        assert!((lo - (2.0 - 1.25f64.sqrt())).abs() < 1e-12);
        assert!((hi - (2.0 + 1.25f64.sqrt())).abs() < 1e-12);
    }

    #[test]
    fn a_flat_frame_gets_a_height_of_half_its_width() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let caroca =
            RobotDescription::load(root.join("examples/robots/caspr-caroca.toml")).unwrap();
        let (lo, hi) = frame_box(&caroca);
        // CAROCA's anchors: x ±1.659, y ±3.159, all at z = 3.221.
        assert_eq!(hi.z, 3.221);
        assert!((lo.z - (3.221 - 0.5 * 6.318)).abs() < 1e-12);
        let ipanema =
            RobotDescription::load(root.join("examples/robots/caspr-ipanema-1.toml")).unwrap();
        assert_eq!(frame_box(&ipanema), ipanema.robot.frame_bounding_box());
    }
}
