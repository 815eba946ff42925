//! `cdpr capacity`: the capacity margin of a required wrench set at a pose.

use super::{CliError, Numbers, external_wrench, load_robot, pose, print_json};
use cdpr::polytope::{RequiredWrenchSet, hyperplane_shifting, limiting_facet};
use nalgebra::DVector;
use serde_json::json;
use std::path::PathBuf;

/// Capacity margin (Guay et al. 2014) of a required set of external wrenches at one pose.
///
/// The required set R is centred on --wrench (default zero) PLUS the platform's gravity from the
/// robot file, and is one of:
///   --wrench-box H1,…   a box of half-widths per wrench component (N for forces, N·m for
///                       moments);
///   --force-radius F [--moment-radius M]   every force ‖f‖ ≤ F (N) together with every moment
///                       ‖m‖ ≤ M (N·m, default 0): units kept apart;
///   --wrench-ball R     a Euclidean ball √(‖f‖² + ‖m‖²) ≤ R in the wrench space, forces in N
///                       and moments in N·m taken as plain numbers (a length scale of 1 m; for
///                       point robots it is simply a force ball in N);
/// with none of them, R is that single wrench. The margin is
/// min over the facets n_k·w <= d_k of the available wrench set {W t} of d_k − max_{w∈R}(−n_k·w):
/// positive iff every wrench of R can be balanced (W t + w = 0) with tensions in bounds, and
/// then the distance by which R could grow in every direction. Negative: R sticks out by that
/// much (an answer, exit code 0). The margin is a distance in the wrench space along the unit
/// normal of the limiting facet: N for point robots; for planar/spatial robots N and N·m
/// combined with a length scale of 1 m (as in Guay et al. 2014).
///
/// JSON fields: `capacity_margin` (see above), `feasible` (margin >= 0), `limiting_facet`
/// {`index`, `normal`, `offset`} (the facet reached first), `required` {`shape` (\"point\",
/// \"box\", \"ball\" or \"force-moment-balls\"), `centre` (N, N·m), `half_widths`, `radius`, or
/// `force_radius` (N) and `moment_radius` (N·m)}, `facets`.
#[derive(clap::Args)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    /// Robot file: .toml, CASPR NAME_cables.xml or WireCenter .wcrfx.
    robot: PathBuf,
    /// Platform pose (motion-pattern coordinates), e.g. --pose 0.1,-0.2,0.
    #[arg(long, allow_hyphen_values = true)]
    pose: Numbers,
    /// Centre of the required set before gravity: an external wrench (DOF numbers; default 0).
    #[arg(long, allow_hyphen_values = true)]
    wrench: Option<Numbers>,
    /// Required box: half-widths per wrench component (DOF numbers >= 0), e.g. 10,10,1.
    #[arg(long, allow_hyphen_values = true, conflicts_with = "wrench_ball")]
    wrench_box: Option<Numbers>,
    /// Required ball: radius R >= 0 around the centre, Euclidean over the wrench components
    /// (N and N·m as plain numbers; prefer --force-radius/--moment-radius for rotating robots).
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["force_radius", "moment_radius"])]
    wrench_ball: Option<f64>,
    /// Required forces: every force of magnitude ≤ F (N) added to the centre.
    #[arg(
        long,
        allow_hyphen_values = true,
        conflicts_with = "wrench_box",
        value_name = "F"
    )]
    force_radius: Option<f64>,
    /// Required moments (planar and spatial robots): every moment of magnitude ≤ M (N·m), with
    /// the forces of --force-radius (default 0 N).
    #[arg(
        long,
        allow_hyphen_values = true,
        conflicts_with = "wrench_box",
        value_name = "M"
    )]
    moment_radius: Option<f64>,
    /// Write one JSON object on stdout.
    #[arg(long)]
    json: bool,
}

/// Runs the command.
pub fn run(args: Args) -> Result<(), CliError> {
    let robot = load_robot(&args.robot)?;
    cdpr::wrench::require_enough_cables(&robot.robot, "the capacity margin (wrench closure)")?;
    let p = pose(&robot, &args.pose)?;
    let centre = external_wrench(&robot, &p, args.wrench.as_deref())?;
    let dof = centre.len();
    let motion = robot.robot.motion();
    let split = (args.force_radius.is_some() || args.moment_radius.is_some()).then(|| {
        (
            args.force_radius.unwrap_or(0.0),
            args.moment_radius.unwrap_or(0.0),
        )
    });
    for (name, v) in [
        ("--wrench-ball", args.wrench_ball),
        ("--force-radius", args.force_radius),
        ("--moment-radius", args.moment_radius),
    ] {
        if let Some(v) = v.filter(|v| !(v.is_finite() && *v >= 0.0)) {
            return Err(format!("{name}: the radius must be a finite number ≥ 0, got {v}").into());
        }
    }
    if args.moment_radius.is_some() && !motion.has_orientation() {
        return Err(format!(
            "--moment-radius: a `{}` robot takes no moments (use --force-radius)",
            motion.name()
        )
        .into());
    }
    let (required, shape) = match (&args.wrench_box, args.wrench_ball) {
        _ if split.is_some() => {
            let (f, m) = split.unwrap_or_default();
            (
                RequiredWrenchSet::force_and_moment_balls(
                    centre.clone(),
                    motion.translation_dof(),
                    f,
                    m,
                )?,
                "force-moment-balls",
            )
        }
        (Some(h), _) => {
            if h.len() != dof {
                return Err(format!(
                    "--wrench-box needs {dof} half-widths (one per wrench component), got {}",
                    h.len()
                )
                .into());
            }
            (
                RequiredWrenchSet::boxed(centre.clone(), DVector::from_column_slice(h))?,
                "box",
            )
        }
        (None, Some(r)) => (RequiredWrenchSet::ball(centre.clone(), r)?, "ball"),
        (None, None) => (RequiredWrenchSet::point(centre.clone())?, "point"),
    };
    let w = robot.robot.inverse_kinematics(&p)?.wrench_matrix();
    let aws = hyperplane_shifting::available_wrench_set(&w, &robot.bounds)?;
    let limit = limiting_facet(&aws, &required)?;
    let margin = limit.map_or(f64::INFINITY, |(_, m)| m);
    let feasible = margin >= 0.0;
    if args.json {
        let mut req = json!({ "shape": shape, "centre": centre.as_slice() });
        if let Some(h) = required.half_widths() {
            req["half_widths"] = json!(h);
        }
        if let Some(r) = required.radius() {
            req["radius"] = json!(r);
        }
        if let Some((f, m)) = required.force_and_moment_radii() {
            req["force_radius"] = json!(f);
            req["moment_radius"] = json!(m);
        }
        return print_json(&json!({
            "robot": robot.name,
            "pose": args.pose.0,
            "required": req,
            "capacity_margin": margin.is_finite().then_some(margin),
            "feasible": feasible,
            "limiting_facet": limit.map(|(k, _)| {
                let f = &aws.facets()[k];
                json!({ "index": k, "normal": f.normal.as_slice(), "offset": f.offset })
            }),
            "facets": aws.facets().len(),
        }));
    }
    let forces = motion.translation_dof();
    println!(
        "robot {}, pose {}",
        robot.name,
        super::pose_text(&args.pose.0, motion.space_dim())
    );
    println!(
        "required {shape} of external wrenches centred on {} (--wrench + gravity){}",
        super::wrench_text(centre.as_slice(), forces),
        match (
            required.half_widths(),
            required.radius(),
            required.force_and_moment_radii()
        ) {
            (Some(h), _, _) => format!(", half-widths {}", super::wrench_text(h, forces)),
            (None, Some(r), _) if r > 0.0 => format!(
                ", radius {} ({})",
                super::num(r),
                if forces == dof {
                    "N"
                } else {
                    "N and N·m combined, length scale 1 m"
                }
            ),
            (_, _, Some((f, m))) => format!(", forces up to {f} N and moments up to {m} N·m"),
            _ => String::new(),
        }
    );
    println!(
        "capacity margin: {margin:.6} {}",
        if forces == dof {
            "N"
        } else {
            "(N and N·m combined, length scale 1 m)"
        }
    );
    println!(
        "{}",
        if feasible {
            "feasible: every required wrench can be balanced with tensions in bounds"
        } else {
            "infeasible: part of the required set cannot be balanced"
        }
    );
    if let Some((k, _)) = limit {
        let f = &aws.facets()[k];
        println!(
            "limiting facet {} of {}: unit normal {}, offset {:.6}",
            k + 1,
            aws.facets().len(),
            super::nums(f.normal.as_slice()),
            f.offset
        );
    }
    Ok(())
}
