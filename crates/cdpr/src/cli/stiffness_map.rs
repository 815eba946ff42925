//! `cdpr stiffness-map`: the stiffness-oriented study of Picard, Caro, Plestan & Claveau 2020 at one pose (Fig. 4).

use super::tension::{SotdaSearch, sotda_settings};
use super::{
    CliError, Numbers, check_method, external_wrench, load_robot, pose, print_json, wrench,
};
use cdpr::RobotDescription;
use cdpr::plot::HeatMap;
use cdpr::tension::{
    FeasiblePolygon, SotdaSettings, StiffnessData, TensionOutcome, TensionProblem, TensionSolver,
    sotda_displacement,
};
use nalgebra::{DVector, Vector2};
use serde_json::json;
use std::path::PathBuf;

/// Platform displacement over the feasible polygon (Picard, Caro, Plestan & Claveau 2020, Fig. 4).
///
/// At one pose of a robot with redundancy n − DOF = 2, every equilibrium tension is
/// t = t0 + N λ, λ in the feasible polygon (Picard, Caro, Plestan & Claveau 2020, eqs. (5)–(6)). For each tension the platform
/// moves by δX = K(t)⁻¹ δw under the load δw, with K = Kp + Ka (eq. (4), k_i = E·S / l_i from the
/// robot file's `axial_stiffness`). This command evaluates |d · δp| on a grid over the polygon
/// (Fig. 4 left), at the barycentre and at the SOTDA optimum (eq. (7)), along the intermediate
/// solutions t(ν) = t_bary + ν (t_opt − t_bary), ν ∈ [0, 1] (Fig. 4 right, simulated), and reports
/// the reduction 100 (δ_bary − δ_opt) / δ_bary in %.
///
/// The tensions balance --wrench plus the platform's gravity; the displacement is the response to
/// --wrench alone (the lateral load of the paper; a unit force along d if --wrench is zero).
/// Displacements are printed in thousandths of the robot's length unit: mm for a robot in metres
/// with forces in N.
///
/// JSON fields: `displacement_barycenter`, `displacement_optimum`, `reduction_percent`,
/// `spread` (largest − smallest grid value), `polygon` (vertices λ), `barycenter_lambda`,
/// `optimum_lambda`, `tensions_barycenter`, `tensions_optimum`, `nu_curve` ([ν, displacement]
/// pairs), `grid` (`lambda1`, `lambda2`, `values[j][i]` at (lambda1[i], lambda2[j]), null outside
/// the polygon), `unit`; `feasible` false with `reason` when the polygon is empty.
#[derive(clap::Args)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    /// Robot file: .toml, CASPR NAME_cables.xml or WireCenter .wcrfx with redundancy 2 and `axial_stiffness` on every cable.
    robot: PathBuf,
    /// Platform pose (motion-pattern coordinates), e.g. --pose 1.5,0.35,0.59,0,0,0.
    #[arg(long, allow_hyphen_values = true)]
    pose: Numbers,
    /// External wrench w_e (DOF numbers; default zero), e.g. --wrench 0,50,0,0,0,0.
    #[arg(long, allow_hyphen_values = true)]
    wrench: Option<Numbers>,
    /// Direction d of the displacement (2 or 3 numbers; default +y as in Picard, Caro, Plestan & Claveau 2020).
    #[arg(long, allow_hyphen_values = true)]
    direction: Option<Numbers>,
    /// Grid resolution per λ axis over the polygon's bounding box.
    #[arg(long, default_value_t = 80, value_parser = super::count)]
    grid: usize,
    /// Number of ν values in [0, 1] for the intermediate-solution curve.
    #[arg(long, default_value_t = 21, value_parser = super::count)]
    nu_samples: usize,
    /// Use SOTDA's real-time variant (only the polygon corners with a cable at t_max) for the
    /// optimum instead of the full search (grid + pattern search).
    #[arg(long)]
    corners: bool,
    /// Heat map of the displacement over the polygon (.svg or .png).
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Write one JSON object on stdout.
    #[arg(long)]
    json: bool,
}

/// Runs the command.
pub fn run(args: Args) -> Result<(), CliError> {
    let robot = load_robot(&args.robot)?;
    let es = check(&args, &robot)?;
    let pose = pose(&robot, &args.pose)?;
    let w_e = wrench(&robot, args.wrench.as_deref())?;
    let w_ext = external_wrench(&robot, &pose, args.wrench.as_deref())?;
    let kin = robot.robot.inverse_kinematics(&pose)?;
    let w = kin.wrench_matrix();
    let mut settings = sotda_settings(
        args.direction.as_deref(),
        1.0,
        if args.corners {
            SotdaSearch::Corners
        } else {
            SotdaSearch::Full
        },
    )?;
    if w_e.amax() > 0.0 {
        settings.perturbation = Some(w_e.clone());
    }
    let mut problem = TensionProblem::new(&w, &w_ext, &robot.bounds);
    problem.stiffness = Some(StiffnessData {
        kinematics: &kin,
        axial_stiffness: &es,
    });
    let polygon = match FeasiblePolygon::compute(&problem)? {
        Ok(p) => p,
        Err(reason) => {
            return report_infeasible(&args, &robot.name, &reason.to_string());
        }
    };
    let optimum = match TensionSolver::sotda(settings.clone()).solve(&problem)? {
        TensionOutcome::Feasible(s) => s.tensions,
        TensionOutcome::Infeasible(reason) => {
            return report_infeasible(&args, &robot.name, &reason.to_string());
        }
    };
    let stiff = problem.stiffness.expect("set above");
    let disp = |t: &DVector<f64>| -> Result<f64, CliError> {
        Ok(sotda_displacement(&stiff, &settings, &w_ext, t.as_slice())?.unwrap_or(f64::NAN) * 1e3)
    };
    let map = StiffnessMap::compute(&args, &robot.bounds, polygon, optimum, disp)?;
    if let Some(path) = &args.plot {
        save_map_plot(&args, &robot.name, &map, path)?;
    }
    if args.json {
        print_json(&map_json(&args, &robot.name, &map, &settings, &w_ext))
    } else {
        print_map(&args, &robot, &map, &settings, &w_ext);
        Ok(())
    }
}

/// Checks the robot and the options; the cables' axial stiffness E·S (N).
fn check(args: &Args, robot: &RobotDescription) -> Result<Vec<f64>, CliError> {
    robot.require_no_passive_springs(
        "the stiffness map (cables only; the springs' K would add to it)",
    )?;
    check_method(robot, cdpr::tension::Method::Sotda)?;
    if !(2..=2000).contains(&args.grid) {
        return Err("--grid must lie in [2, 2000]".into());
    }
    if !(2..=10_000).contains(&args.nu_samples) {
        return Err("--nu-samples must lie in [2, 10000]".into());
    }
    let es = robot
        .axial_stiffness
        .clone()
        .ok_or("stiffness-map needs `axial_stiffness` (E·S, N) on every cable of the robot file")?;
    let r = robot.robot.cable_count() as isize - robot.robot.dof() as isize;
    if r != 2 {
        return Err(format!(
            "stiffness-map needs redundancy n − DOF = 2 (the feasible polygon), this robot has {r}"
        )
        .into());
    }
    Ok(es)
}

/// The unit of the displacements printed.
const UNIT: &str = "mm (1e-3 of the robot's length unit)";

/// What the command finds: the displacement at the barycentre, at the SOTDA optimum, along
/// t(ν) and over the polygon.
struct StiffnessMap {
    polygon: FeasiblePolygon,
    optimum: DVector<f64>,
    t_bary: DVector<f64>,
    l_bary: Vector2<f64>,
    l_opt: Vector2<f64>,
    d_bary: f64,
    d_opt: f64,
    /// 100 (δ_bary − δ_opt) / δ_bary (%).
    reduction: f64,
    nu_curve: Vec<[f64; 2]>,
    grid: Grid,
    gmin: f64,
    gmax: f64,
}

impl StiffnessMap {
    fn compute(
        args: &Args,
        bounds: &cdpr::tension::TensionBounds,
        polygon: FeasiblePolygon,
        optimum: DVector<f64>,
        disp: impl Fn(&DVector<f64>) -> Result<f64, CliError>,
    ) -> Result<Self, CliError> {
        let t_bary = polygon.barycenter();
        let l_bary = polygon.barycenter_lambda();
        let l_opt = {
            let v = polygon.null_space.transpose() * (&optimum - &polygon.particular);
            Vector2::new(v[0], v[1])
        };
        let d_bary = disp(&t_bary)?;
        let d_opt = disp(&optimum)?;
        let nu_curve = (0..args.nu_samples)
            .map(|k| {
                let nu = k as f64 / (args.nu_samples - 1) as f64;
                let t = &t_bary + (&optimum - &t_bary) * nu;
                Ok([nu, disp(&t)?])
            })
            .collect::<Result<Vec<_>, CliError>>()?;
        let grid = stiffness_grid(&polygon, bounds, args.grid, &disp)?;
        let (gmin, gmax) = grid
            .values
            .iter()
            .filter(|v| v.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                (a.min(v), b.max(v))
            });
        Ok(Self {
            polygon,
            optimum,
            t_bary,
            l_bary,
            l_opt,
            d_bary,
            d_opt,
            reduction: 100.0 * (d_bary - d_opt) / d_bary,
            nu_curve,
            grid,
            gmin,
            gmax,
        })
    }
}

/// The heat map of `--plot` (Picard, Caro, Plestan & Claveau 2020, Fig. 4 left).
fn save_map_plot(
    args: &Args,
    name: &str,
    map: &StiffnessMap,
    path: &std::path::Path,
) -> Result<(), CliError> {
    let fig = HeatMap {
        title: format!(
            "{name}: |d·δp| over the feasible polygon (reduction {:.1} %)",
            map.reduction
        ),
        labels: ("λ1 (N)".into(), "λ2 (N)".into()),
        value_label: "|d·δp| (mm)".into(),
        x_range: map.grid.x_range,
        y_range: map.grid.y_range,
        shape: (args.grid, args.grid),
        values: map.grid.values.clone(),
        blank_below: f64::NEG_INFINITY,
        markers: Vec::new(),
        outlines: vec![map.polygon.vertices.iter().map(|v| (v.x, v.y)).collect()],
        highlight: vec![
            (
                (map.l_bary.x, map.l_bary.y),
                format!("barycentre {:.3} mm", map.d_bary),
            ),
            (
                (map.l_opt.x, map.l_opt.y),
                format!("SOTDA optimum {:.3} mm", map.d_opt),
            ),
        ],
    };
    cdpr::plot::save(&fig, path)?;
    Ok(())
}

/// The `--json` answer.
fn map_json(
    args: &Args,
    name: &str,
    map: &StiffnessMap,
    settings: &SotdaSettings,
    w_ext: &DVector<f64>,
) -> serde_json::Value {
    let n = args.grid;
    let row = |j: usize| -> Vec<Option<f64>> {
        map.grid.values[j * n..(j + 1) * n]
            .iter()
            .map(|v| v.is_finite().then_some(*v))
            .collect()
    };
    json!({
        "robot": name,
        "pose": args.pose.0,
        "feasible": true,
        "direction": settings.direction.as_slice(),
        "external_wrench": w_ext.as_slice(),
        "load": settings.perturbation.as_ref().map(|p| p.as_slice().to_vec()),
        "method": if args.corners { "sotda (corners)" } else { "sotda (full search)" },
        "unit": UNIT,
        "displacement_barycenter": map.d_bary,
        "displacement_optimum": map.d_opt,
        "reduction_percent": map.reduction,
        "spread": map.gmax - map.gmin,
        "grid_min": map.gmin,
        "grid_max": map.gmax,
        "polygon": map.polygon.vertices.iter().map(|v| [v.x, v.y]).collect::<Vec<_>>(),
        "barycenter_lambda": [map.l_bary.x, map.l_bary.y],
        "optimum_lambda": [map.l_opt.x, map.l_opt.y],
        "tensions_barycenter": map.t_bary.as_slice(),
        "tensions_optimum": map.optimum.as_slice(),
        "nu_curve": map.nu_curve,
        "grid": {
            "lambda1": map.grid.axis(0, n),
            "lambda2": map.grid.axis(1, n),
            "values": (0..n).map(row).collect::<Vec<_>>(),
        },
    })
}

/// The text answer.
fn print_map(
    args: &Args,
    robot: &RobotDescription,
    map: &StiffnessMap,
    settings: &SotdaSettings,
    w_ext: &DVector<f64>,
) {
    let forces = robot.robot.motion().translation_dof();
    println!(
        "robot {}, pose {}, w_ext {} (tensions), load {} (displacement), direction {}",
        robot.name,
        super::pose_text(&args.pose.0, robot.robot.motion().space_dim()),
        super::wrench_text(w_ext.as_slice(), forces),
        settings.perturbation.as_ref().map_or_else(
            || "none".to_string(),
            |p| super::wrench_text(p.as_slice(), forces)
        ),
        super::nums(settings.direction.as_slice())
    );
    println!("feasible polygon: {} vertices", map.polygon.vertices.len());
    println!("displacement |d·δp| in {UNIT}:");
    println!("  barycentre      {:.6}", map.d_bary);
    println!("  SOTDA optimum   {:.6}", map.d_opt);
    println!("  reduction       {:.3} %", map.reduction);
    println!(
        "  grid min / max  {:.6} / {:.6} (spread {:.6})",
        map.gmin,
        map.gmax,
        map.gmax - map.gmin
    );
    println!("{:>6} {:>12}", "nu", "|d·δp|");
    for [nu, d] in &map.nu_curve {
        println!("{nu:>6.3} {d:>12.6}");
    }
}

fn report_infeasible(args: &Args, name: &str, reason: &str) -> Result<(), CliError> {
    if args.json {
        print_json(&json!({
            "robot": name,
            "pose": args.pose.0,
            "feasible": false,
            "reason": reason,
        }))
    } else {
        println!("no feasible polygon at this pose: {reason}");
        Ok(())
    }
}

/// Values of `f(t(λ))` on an n × n grid over the polygon's bounding box (NaN outside).
struct Grid {
    x_range: (f64, f64),
    y_range: (f64, f64),
    values: Vec<f64>,
}

impl Grid {
    fn axis(&self, k: usize, n: usize) -> Vec<f64> {
        let (a, b) = if k == 0 { self.x_range } else { self.y_range };
        (0..n)
            .map(|i| a + (b - a) * i as f64 / (n - 1) as f64)
            .collect()
    }
}

fn stiffness_grid(
    polygon: &FeasiblePolygon,
    bounds: &cdpr::tension::TensionBounds,
    n: usize,
    mut f: impl FnMut(&DVector<f64>) -> Result<f64, CliError>,
) -> Result<Grid, CliError> {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for v in &polygon.vertices {
        for d in 0..2 {
            lo[d] = lo[d].min(v[d]);
            hi[d] = hi[d].max(v[d]);
        }
    }
    let mut values = vec![f64::NAN; n * n];
    for j in 0..n {
        for i in 0..n {
            let l = Vector2::new(
                lo[0] + (hi[0] - lo[0]) * i as f64 / (n - 1) as f64,
                lo[1] + (hi[1] - lo[1]) * j as f64 / (n - 1) as f64,
            );
            if polygon.contains(&l, bounds) {
                values[j * n + i] = f(&polygon.tensions_at(&l))?;
            }
        }
    }
    Ok(Grid {
        x_range: (lo[0], hi[0]),
        y_range: (lo[1], hi[1]),
        values,
    })
}
