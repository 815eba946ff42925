//! `cdpr tension`: a tension distribution at one pose.

use super::{CliError, Numbers, check_method, load_robot, print_report};
use cdpr::RobotDescription;
use cdpr::api::{BindingReport, Robot, TensionReport, TensionRequest};
use cdpr::tension::Method;
use std::path::PathBuf;

/// Cable tensions t with W t + w_ext = 0 and t_min ≤ t ≤ t_max at one pose.
///
/// Methods (--method): exact (n = DOF, eq. 6.12), pinv (minimum norm, eq. 6.14), closed-form
/// (Algorithm 6.1, redundancy 1, minimum ‖t‖₁), l1 / l1-max (eq. 6.19), l2 / l2-max (eq. 6.17),
/// linf (minimum largest tension), improved-closed-form (Pott 2014), barycenter (centroid of the
/// feasible polygon, redundancy 2), sotda (stiffness-oriented, Picard, Caro, Plestan & Claveau 2020: --direction, --nu),
/// pott-closed-form, pott-closed-form-ee, puncture (--interior), dykstra (--alternating),
/// l2-mid, vertex-centroid, p-norm (--p), optimally-safe (--alpha).
///
/// The external wrench is --wrench plus the platform's gravity from the robot file.
/// Every "feasible" answer is certified (equilibrium residual and bounds to 1e-9 relative);
/// "infeasible" comes with its reason and exit code 0.
///
/// JSON fields: `feasible`, `tensions` (or null), `residual`, `method`, `reason` (or null);
/// `polygon` for barycenter and sotda; `displacement`, `nu` and `sotda_search` for sotda;
/// `binding_cables` {`violation` (N), `cables` [{`cable`, `tension` (N), `bound` (N), `which`}]}
/// when the feasible set is empty: the balancing tensions closest to the bounds and the cables
/// that break them most there (text: "cable 3 would need 157 N, below its t_min of 200 N").
/// --nu, --direction and --full are SOTDA's: refused with another method (exit 2).
/// With `--cable-model elastic|catenary`: `tensions` at the platform end, `unstrained_lengths`,
/// `frame_end_tensions` (and the other per-cable fields of `cdpr kinematics`), certified with the
/// catenary forces and the bounds at both ends of every cable.
#[derive(clap::Args)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    /// Robot file: .toml, CASPR NAME_cables.xml or WireCenter .wcrfx.
    robot: PathBuf,
    /// Platform pose (motion-pattern coordinates), e.g. --pose 0.1,-0.2,0.
    #[arg(long, allow_hyphen_values = true)]
    pose: Numbers,
    /// External wrench w_e applied to the platform (DOF numbers; default zero), e.g. --wrench 0,-10,0.
    #[arg(long, allow_hyphen_values = true)]
    wrench: Option<Numbers>,
    /// Tension distribution method: exact, pinv, closed-form, l1, l1-max, l2, l2-max, linf,
    /// improved-closed-form, barycenter, sotda, pott-closed-form, pott-closed-form-ee,
    /// puncture, dykstra, l2-mid, vertex-centroid, p-norm, optimally-safe (one line each in
    /// --help).
    #[arg(long, default_value = "l2", long_help = super::method_help())]
    method: Method,
    /// SOTDA: direction d of the displacement to minimise (2 or 3 numbers; default +y).
    /// Refused with another method.
    #[arg(long, allow_hyphen_values = true)]
    direction: Option<Numbers>,
    /// SOTDA: ν ∈ [0, 1] between the barycentre (0) and the stiffness-oriented optimum (1);
    /// default 1. Refused with another method.
    #[arg(long, value_parser = super::unit_interval)]
    nu: Option<f64>,
    /// SOTDA: which points of the feasible polygon are evaluated. corners: Picard, Caro, Plestan & Claveau's (2020) real-time
    /// variant, the vertices with a cable at t_max; vertices: every vertex; full: a grid over
    /// the whole polygon refined by a pattern search.
    #[arg(long, value_enum, default_value = "corners", conflicts_with = "full")]
    sotda_search: SotdaSearch,
    /// SOTDA: search the whole polygon (same as --sotda-search full).
    #[arg(long)]
    full: bool,
    #[command(flatten)]
    peer: PeerOptions,
    #[command(flatten)]
    cable_model: super::cable_model::CableModelArgs,
    /// Draw the robot at the pose with each cable's tension: .svg or .png (2-D robots seen
    /// from +z, 3-D robots an isometric view with three sections; tensions in the anchor
    /// labels) or .html (an interactive 3-D view, cables coloured by tension).
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Write one JSON object on stdout.
    #[arg(long)]
    json: bool,
}

/// The options of the methods of issue 26 (each belongs to one method; given with another
/// it is a usage error, exit 2).
#[derive(clap::Args, Clone, Debug, Default)]
pub struct PeerOptions {
    /// puncture: the interior point aimed at from the minimum-norm t₀: icf (improved closed
    /// form, default) or cf (closed form of Pott, Bruckmann & Mikelsons 2009).
    #[arg(long)]
    interior: Option<String>,
    /// dykstra: plain (von Neumann) alternating projections, as WireLib and cdpyr.
    #[arg(long)]
    alternating: bool,
    /// p-norm: the exponent p ≥ 2 (default 4).
    #[arg(long)]
    p: Option<f64>,
    /// optimally-safe: the weight α > 0 of the upper margin t_max − t ≥ α s (default 1).
    #[arg(long)]
    alpha: Option<f64>,
}

impl PeerOptions {
    /// The request's options of the peers' methods.
    pub fn to_api(&self) -> cdpr::api::PeerOptions {
        cdpr::api::PeerOptions {
            interior: self.interior.clone(),
            alternating: self.alternating,
            p: self.p,
            alpha: self.alpha,
        }
    }
}

/// The text lines of the binding cables.
fn print_binding(c: &BindingReport) {
    println!(
        "binding cables (the balancing tensions closest to the bounds break them by {} N):",
        super::num(c.violation)
    );
    for b in &c.cables {
        let bound = cdpr::tension::BindingBound {
            cable: b.cable - 1,
            tension: b.tension,
            bound: b.bound,
        };
        println!("  {bound}");
    }
}

/// `--nu`, `--direction` and `--full` belong to SOTDA: with another method they would be
/// ignored, so they are a usage error (exit 2) naming the method
/// ([`cdpr::api::refuse_sotda_options`]).
pub fn refuse_sotda_options(
    method: Method,
    nu: Option<f64>,
    direction: bool,
    full: bool,
) -> Result<(), CliError> {
    Ok(cdpr::api::refuse_sotda_options(
        method,
        nu.is_some(),
        direction,
        full,
    )?)
}

/// `--sotda-search`: the points of the feasible polygon SOTDA evaluates ([`SotdaVariant`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum SotdaSearch {
    /// Picard, Caro, Plestan & Claveau's (2020) real-time variant: the vertices with a cable at t_max.
    Corners,
    /// Every vertex of the polygon.
    Vertices,
    /// A grid over the whole polygon refined by a pattern search.
    Full,
}

impl SotdaSearch {
    /// The search chosen by `--sotda-search` and the older `--full` switch.
    pub fn from_args(search: SotdaSearch, full: bool) -> Self {
        if full { SotdaSearch::Full } else { search }
    }

    /// The request's spelling.
    pub fn to_api(self) -> cdpr::api::SotdaSearch {
        match self {
            SotdaSearch::Corners => cdpr::api::SotdaSearch::Corners,
            SotdaSearch::Vertices => cdpr::api::SotdaSearch::Vertices,
            SotdaSearch::Full => cdpr::api::SotdaSearch::Full,
        }
    }
}

/// Runs the command: the request, its report, rendered as JSON or a table.
pub fn run(args: Args) -> Result<(), CliError> {
    let robot = load_robot(&args.robot)?;
    refuse_sotda_options(args.method, args.nu, args.direction.is_some(), args.full)?;
    if let Some(path) = &args.plot {
        super::robot_plot::check_path(path)?;
    }
    if args.cable_model.catenaries(&robot)?.is_some() {
        if args.plot.is_some() {
            return Err(
                "--plot is not drawn with --cable-model elastic|catenary (straight cables only)"
                    .into(),
            );
        }
        return run_sagging(&args, robot);
    }
    let request = TensionRequest {
        robot: Robot::from_description(robot),
        pose: args.pose.0.clone(),
        wrench: args.wrench.as_ref().map(|w| w.0.clone()),
        method: args.method,
        direction: args.direction.as_ref().map(|d| d.0.clone()),
        nu: args.nu.unwrap_or(1.0),
        sotda_search: SotdaSearch::from_args(args.sotda_search, args.full).to_api(),
        options: args.peer.to_api(),
    };
    let report = request.run()?;
    if let Some(path) = &args.plot {
        plot(&request, &report, path)?;
    }
    if args.json {
        print_report(&report)
    } else {
        print_text(&request.robot, &report);
        Ok(())
    }
}

/// `--plot`: the robot at the pose, each cable with its tension ([`super::robot_plot`]).
fn plot(
    request: &TensionRequest,
    r: &TensionReport,
    path: &std::path::Path,
) -> Result<(), CliError> {
    let desc = request.robot.description();
    let motion = desc.robot.motion();
    let pose = super::pose(desc, &request.pose)?;
    let verdict = match (r.feasible, &r.reason) {
        (true, _) => "feasible".to_string(),
        (false, reason) => format!("infeasible: {}", reason.as_deref().unwrap_or_default()),
    };
    super::robot_plot::RobotFigure {
        desc,
        pose: &pose,
        title: format!(
            "{}: tensions at pose {}",
            r.robot,
            super::pose_text(&r.pose, motion.space_dim())
        ),
        notes: vec![
            format!("method {}, {verdict}", r.method),
            format!(
                "w_ext {}",
                super::wrench_text(&r.external_wrench, motion.translation_dof())
            ),
        ],
        tensions: r.tensions.as_deref().filter(|_| r.feasible),
    }
    .save(path)
}

/// `--cable-model elastic|catenary`: the sag-aware statics (cli/cable_model.rs).
fn run_sagging(args: &Args, robot: RobotDescription) -> Result<(), CliError> {
    check_method(&robot, args.method)?;
    args.peer.to_api().for_method(args.method)?;
    let w = args.wrench.as_deref();
    super::cable_model::tension(
        robot,
        &args.cable_model,
        args.method,
        w,
        &args.pose,
        args.json,
    )
}

/// The report as a table.
fn print_text(robot: &RobotDescription, r: &TensionReport) {
    let motion = robot.robot.motion();
    println!(
        "robot {}, pose {}, w_ext {}, method {}",
        r.robot,
        super::pose_text(&r.pose, motion.space_dim()),
        super::wrench_text(&r.external_wrench, motion.translation_dof()),
        r.method
    );
    let (min, max) = (robot.bounds.min(), robot.bounds.max());
    match (r.feasible, &r.tensions) {
        (true, Some(t)) => {
            println!("feasible (residual {:.3e})", r.residual.unwrap_or(0.0));
            println!(
                "{:>6} {:>14} {:>10} {:>10}",
                "cable", "tension (N)", "t_min (N)", "t_max (N)"
            );
            for (i, t) in t.iter().enumerate() {
                println!(
                    "{:>6} {:>14.6} {:>10} {:>10}",
                    i + 1,
                    t,
                    super::num(min[i]),
                    super::num(max[i])
                );
            }
            if let Some(d) = r.sotda.as_ref().and_then(|s| s.displacement) {
                println!("displacement along the direction: {d:.6e} m");
            }
        }
        (_, t) => {
            println!("infeasible: {}", r.reason.as_deref().unwrap_or_default());
            if let Some(c) = &r.binding_cables {
                print_binding(c);
            }
            if let Some(t) = t {
                println!("the solution t = −W⁺ w_ext (balances the wrench, breaks the bounds):");
                println!(
                    "{:>6} {:>14} {:>10} {:>10}",
                    "cable", "tension", "t_min", "t_max"
                );
                for (i, t) in t.iter().enumerate() {
                    println!("{:>6} {:>14.6} {:>10} {:>10}", i + 1, t, min[i], max[i]);
                }
            }
        }
    }
}
