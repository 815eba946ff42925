//! `cdpr capacity`: the capacity margin of a required wrench set at a pose.

use super::{CliError, Numbers, print_report, request_robot};
use cdpr::api::{CapacityReport, CapacityRequest};
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

/// Runs the command: the request, its report, rendered as JSON or text.
pub fn run(args: Args) -> Result<(), CliError> {
    let request = CapacityRequest {
        robot: request_robot(&args.robot)?,
        pose: args.pose.0,
        wrench: args.wrench.map(|w| w.0),
        wrench_box: args.wrench_box.map(|w| w.0),
        wrench_ball: args.wrench_ball,
        force_radius: args.force_radius,
        moment_radius: args.moment_radius,
    };
    let report = request.run()?;
    if args.json {
        return print_report(&report);
    }
    let motion = request.robot.robot.motion();
    print_text(&report, motion.translation_dof(), motion.space_dim());
    Ok(())
}

/// The report as text (`forces` force components, `dim` position coordinates).
fn print_text(r: &CapacityReport, forces: usize, dim: usize) {
    let q = &r.required;
    let dof = q.centre.len();
    println!("robot {}, pose {}", r.robot, super::pose_text(&r.pose, dim));
    println!(
        "required {} of external wrenches centred on {} (--wrench + gravity){}",
        q.shape,
        super::wrench_text(&q.centre, forces),
        match (&q.half_widths, q.radius, q.force_radius, q.moment_radius) {
            (Some(h), _, _, _) => format!(", half-widths {}", super::wrench_text(h, forces)),
            (None, Some(r), _, _) if r > 0.0 => format!(
                ", radius {} ({})",
                super::num(r),
                if forces == dof {
                    "N"
                } else {
                    "N and N·m combined, length scale 1 m"
                }
            ),
            (_, _, Some(f), Some(m)) => {
                format!(", forces up to {f} N and moments up to {m} N·m")
            }
            _ => String::new(),
        }
    );
    println!(
        "capacity margin: {:.6} {}",
        r.capacity_margin.unwrap_or(f64::INFINITY),
        if forces == dof {
            "N"
        } else {
            "(N and N·m combined, length scale 1 m)"
        }
    );
    println!(
        "{}",
        if r.feasible {
            "feasible: every required wrench can be balanced with tensions in bounds"
        } else {
            "infeasible: part of the required set cannot be balanced"
        }
    );
    if let Some(f) = &r.limiting_facet {
        println!(
            "limiting facet {} of {}: unit normal {}, offset {:.6}",
            f.index + 1,
            r.facets,
            super::nums(&f.normal),
            f.offset
        );
    }
}
