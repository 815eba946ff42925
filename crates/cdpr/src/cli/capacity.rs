//! `cdpr capacity`: the capacity margin of a required wrench set at a pose.

use super::{CliError, Numbers, external_wrench, load_robot, pose, print_json};
use cdpr::polytope::{RequiredWrenchSet, hyperplane_shifting, limiting_facet};
use nalgebra::DVector;
use serde_json::json;
use std::path::PathBuf;

/// Capacity margin (Guay et al. 2014) of a required set of external wrenches at one pose.
///
/// The required set R is a box (--wrench-box: half-widths per wrench component) or a ball
/// (--wrench-ball: Euclidean radius) centred on --wrench (default zero) PLUS the platform's
/// gravity from the robot file; with neither option, R is that single wrench. The margin is
/// min over the facets n_k·w <= d_k of the available wrench set {W t} of d_k − max_{w∈R}(−n_k·w):
/// positive iff every wrench of R can be balanced (W t + w = 0) with tensions in bounds, and
/// then the distance by which R could grow in every direction. Negative: R sticks out by that
/// much (an answer, exit code 0). Units mix N and N·m for planar/spatial robots.
///
/// JSON fields: `capacity_margin`, `feasible` (margin >= 0), `limiting_facet` {`index`, `normal`,
/// `offset`} (the facet reached first), `required` {`shape`, `centre`, `half_widths` or
/// `radius`}, `facets`.
#[derive(clap::Args)]
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
    /// Required ball: radius R >= 0 around the centre (wrench units).
    #[arg(long, allow_hyphen_values = true)]
    wrench_ball: Option<f64>,
    /// Write one JSON object on stdout.
    #[arg(long)]
    json: bool,
}

/// Runs the command.
pub fn run(args: Args) -> Result<(), CliError> {
    let robot = load_robot(&args.robot)?;
    let p = pose(&robot, &args.pose)?;
    let centre = external_wrench(&robot, &p, args.wrench.as_deref())?;
    let dof = centre.len();
    let (required, shape) = match (&args.wrench_box, args.wrench_ball) {
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
    println!("robot {}, pose {:?}", robot.name, args.pose.0);
    println!(
        "required {shape} of external wrenches centred on {:?} (--wrench + gravity){}",
        centre.as_slice(),
        match (required.half_widths(), required.radius()) {
            (Some(h), _) => format!(", half-widths {h:?}"),
            (None, Some(r)) if r > 0.0 => format!(", radius {r}"),
            _ => String::new(),
        }
    );
    println!("capacity margin: {margin:.6}");
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
            "limiting facet {k} of {}: normal {:?}, offset {:.6}",
            aws.facets().len(),
            f.normal.as_slice(),
            f.offset
        );
    }
    Ok(())
}
