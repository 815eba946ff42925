//! `cdpr tension`: a tension distribution at one pose.

use super::{CliError, Numbers, check_method, external_wrench, load_robot, pose, print_json};
use cdpr::tension::{
    ClosestBalance, FeasiblePolygon, Infeasibility, Method, MethodOptions, PunctureInterior,
    SotdaSettings, SotdaVariant, StiffnessData, TensionOutcome, TensionProblem, TensionSolver,
    closest_balancing_tensions,
};
use nalgebra::Vector3;
use serde_json::json;
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
    /// Write one JSON object on stdout.
    #[arg(long)]
    json: bool,
}

/// The options of the methods of issue 26 (each belongs to one method; given with another
/// it is a usage error, exit 2).
#[derive(clap::Args, Debug, Default)]
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
    /// The [`MethodOptions`] for `method`; an option of another method is refused.
    pub fn for_method(&self, method: Method) -> Result<MethodOptions, CliError> {
        let given = [
            ("interior", self.interior.is_some()),
            ("alternating", self.alternating),
            ("p", self.p.is_some()),
            ("alpha", self.alpha.is_some()),
        ];
        for (name, set) in given {
            if set && !method.takes_option(name) {
                return Err(format!(
                    "--{name} is an option of another method, not of {method} (--interior: \
                     puncture, --alternating: dykstra, --p: p-norm, --alpha: optimally-safe)"
                )
                .into());
            }
        }
        let mut o = MethodOptions {
            alternating: self.alternating,
            ..MethodOptions::default()
        };
        if let Some(i) = &self.interior {
            o.interior = i.parse::<PunctureInterior>()?;
        }
        if let Some(p) = self.p {
            o.p = p;
        }
        if let Some(a) = self.alpha {
            o.alpha = a;
        }
        o.validate()?;
        Ok(o)
    }
}

/// For an empty feasible set: the balancing tensions closest to the bounds and the cables
/// that bind there (module `cdpr_tension::binding`); `None` for other answers.
fn closest_balance(
    problem: &TensionProblem,
    outcome: &TensionOutcome,
) -> Result<Option<ClosestBalance>, CliError> {
    match outcome.infeasibility() {
        Some(Infeasibility::NoFeasibleTension) => Ok(closest_balancing_tensions(problem)?),
        _ => Ok(None),
    }
}

/// JSON `binding_cables`: `violation` (N, the smallest widening of every [t_min, t_max] that
/// balances the wrench) and `cables` [{`cable` (1-based), `tension` (N), `bound` (N), `which`
/// ("t_min" or "t_max")}].
fn binding_json(c: &ClosestBalance) -> serde_json::Value {
    json!({
        "violation": c.violation,
        "cables": c.binding.iter().map(|b| json!({
            "cable": b.cable + 1,
            "tension": b.tension,
            "bound": b.bound,
            "which": if b.below() { "t_min" } else { "t_max" },
        })).collect::<Vec<_>>(),
    })
}

/// The text lines of the binding cables.
fn print_binding(c: &ClosestBalance) {
    println!(
        "binding cables (the balancing tensions closest to the bounds break them by {} N):",
        super::num(c.violation)
    );
    for b in &c.binding {
        println!("  {b}");
    }
}

/// `--nu`, `--direction` and `--full` belong to SOTDA: with another method they would be
/// ignored, so they are a usage error (exit 2) naming the method.
pub fn refuse_sotda_options(
    method: Method,
    nu: Option<f64>,
    direction: bool,
    full: bool,
) -> Result<(), CliError> {
    if method == Method::Sotda {
        return Ok(());
    }
    let given: Vec<&str> = [
        ("--nu", nu.is_some()),
        ("--direction", direction),
        ("--full", full),
    ]
    .into_iter()
    .filter_map(|(name, set)| set.then_some(name))
    .collect();
    match given.as_slice() {
        [] => Ok(()),
        names => Err(format!(
            "{} {} of the sotda method only, and the method is {method} (add --method \
             sotda, or leave {} out)",
            names.join(", "),
            if names.len() == 1 {
                "is an option"
            } else {
                "are options"
            },
            if names.len() == 1 { "it" } else { "them" }
        )
        .into()),
    }
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
    /// The command-line spelling (JSON `sotda_search`).
    pub fn name(self) -> &'static str {
        match self {
            SotdaSearch::Corners => "corners",
            SotdaSearch::Vertices => "vertices",
            SotdaSearch::Full => "full",
        }
    }

    /// The search chosen by `--sotda-search` and the older `--full` switch.
    pub fn from_args(search: SotdaSearch, full: bool) -> Self {
        if full { SotdaSearch::Full } else { search }
    }
}

/// SOTDA settings from the command line (shared with the trajectory command).
pub fn sotda_settings(
    direction: Option<&[f64]>,
    nu: f64,
    search: SotdaSearch,
) -> Result<SotdaSettings, CliError> {
    let mut s = SotdaSettings {
        nu,
        ..SotdaSettings::default()
    };
    if let Some(d) = direction {
        s.direction = match d.len() {
            2 => Vector3::new(d[0], d[1], 0.0),
            3 => Vector3::new(d[0], d[1], d[2]),
            k => return Err(format!("--direction needs 2 or 3 numbers, got {k}").into()),
        };
    }
    s.variant = match search {
        SotdaSearch::Corners => SotdaVariant::Corners,
        SotdaSearch::Vertices => SotdaVariant::Vertices,
        SotdaSearch::Full => SotdaVariant::Full,
    };
    s.validate()?;
    Ok(s)
}

/// Vertices and barycentre of the feasible polygon as JSON (null when there is none).
pub fn polygon_json(problem: &TensionProblem) -> Result<serde_json::Value, CliError> {
    Ok(match FeasiblePolygon::compute(problem)? {
        Ok(p) => json!({
            "vertices_lambda": p.vertices.iter().map(|v| [v.x, v.y]).collect::<Vec<_>>(),
            "vertices_tension": p.tension_vertices.iter().map(|t| t.as_slice().to_vec()).collect::<Vec<_>>(),
            "barycenter_lambda": [p.barycenter_lambda().x, p.barycenter_lambda().y],
            "barycenter": p.barycenter().as_slice().to_vec(),
            "area": p.area(),
        }),
        Err(reason) => json!({ "none": reason.to_string() }),
    })
}

/// Runs the command.
pub fn run(args: Args) -> Result<(), CliError> {
    let robot = load_robot(&args.robot)?;
    check_method(&robot, args.method)?;
    let options = args.peer.for_method(args.method)?;
    refuse_sotda_options(args.method, args.nu, args.direction.is_some(), args.full)?;
    let pose = pose(&robot, &args.pose)?;
    let w_ext = external_wrench(&robot, &pose, args.wrench.as_deref())?;
    let kin = robot.robot.inverse_kinematics(&pose)?;
    if let Some(cables) = args.cable_model.catenaries(&robot)? {
        let name = args.cable_model.model().name();
        let (m, b) = (args.method, &robot.bounds);
        return super::cable_model::tension(
            &robot, &kin, &cables, m, &w_ext, b, name, &args.pose, args.json,
        );
    }
    let w = kin.wrench_matrix();
    let es = robot.axial_stiffness.clone();
    if args.method == Method::Sotda && es.is_none() {
        return Err(
            "sotda needs `axial_stiffness` (E·S, N) on every cable of the robot file".into(),
        );
    }
    let mut problem = TensionProblem::new(&w, &w_ext, &robot.bounds);
    if let Some(es) = &es {
        problem.stiffness = Some(StiffnessData {
            kinematics: &kin,
            axial_stiffness: es,
        });
    }
    let mut solver = if args.method == Method::Sotda {
        TensionSolver::sotda(sotda_settings(
            args.direction.as_deref(),
            args.nu.unwrap_or(1.0),
            SotdaSearch::from_args(args.sotda_search, args.full),
        )?)
    } else {
        TensionSolver::new(args.method).with_options(options)?
    };
    let outcome = solver.solve(&problem)?;
    let displacement = match (&outcome, args.method, &problem.stiffness) {
        (TensionOutcome::Feasible(s), Method::Sotda, Some(st)) => {
            cdpr::tension::sotda_displacement(
                st,
                solver.sotda_settings(),
                &w_ext,
                s.tensions.as_slice(),
            )?
        }
        _ => None,
    };
    let with_polygon = matches!(args.method, Method::Barycenter | Method::Sotda);
    let closest = closest_balance(&problem, &outcome)?;
    if args.json {
        let mut v = json!({
            "robot": robot.name,
            "pose": args.pose.0,
            "external_wrench": w_ext.as_slice(),
            "method": args.method.name(),
            "feasible": outcome.is_feasible(),
            // exact / pinv: t = −W⁺ w_ext even when it breaks a bound (`feasible` false,
            // `reason` names the cable).
            "tensions": outcome.balancing_tensions().map(|t| t.as_slice().to_vec()),
            "residual": match &outcome { TensionOutcome::Feasible(s) => Some(s.residual), _ => None },
            "reason": outcome.infeasibility().map(|r| r.to_string()),
        });
        if with_polygon {
            v["polygon"] = polygon_json(&problem)?;
        }
        if let Some(c) = &closest {
            v["binding_cables"] = binding_json(c);
        }
        if args.method == Method::Sotda {
            v["displacement"] = json!(displacement);
            v["nu"] = json!(args.nu.unwrap_or(1.0));
            v["sotda_search"] = json!(SotdaSearch::from_args(args.sotda_search, args.full).name());
        }
        print_json(&v)
    } else {
        println!(
            "robot {}, pose {}, w_ext {}, method {}",
            robot.name,
            super::pose_text(&args.pose.0, robot.robot.motion().space_dim()),
            super::wrench_text(w_ext.as_slice(), robot.robot.motion().translation_dof()),
            args.method.name()
        );
        match &outcome {
            TensionOutcome::Feasible(s) => {
                println!("feasible (residual {:.3e})", s.residual);
                println!(
                    "{:>6} {:>14} {:>10} {:>10}",
                    "cable", "tension (N)", "t_min (N)", "t_max (N)"
                );
                for (i, t) in s.tensions.iter().enumerate() {
                    println!(
                        "{:>6} {:>14.6} {:>10} {:>10}",
                        i + 1,
                        t,
                        super::num(robot.bounds.min()[i]),
                        super::num(robot.bounds.max()[i])
                    );
                }
                if let Some(d) = displacement {
                    println!("displacement along the direction: {d:.6e} m");
                }
            }
            TensionOutcome::Infeasible(r) => {
                println!("infeasible: {r}");
                if let Some(c) = &closest {
                    print_binding(c);
                }
                if let Some(t) = outcome.balancing_tensions() {
                    println!(
                        "the solution t = −W⁺ w_ext (balances the wrench, breaks the bounds):"
                    );
                    println!(
                        "{:>6} {:>14} {:>10} {:>10}",
                        "cable", "tension", "t_min", "t_max"
                    );
                    for (i, t) in t.iter().enumerate() {
                        println!(
                            "{:>6} {:>14.6} {:>10} {:>10}",
                            i + 1,
                            t,
                            robot.bounds.min()[i],
                            robot.bounds.max()[i]
                        );
                    }
                }
            }
        }
        Ok(())
    }
}
