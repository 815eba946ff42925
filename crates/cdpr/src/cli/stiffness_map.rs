//! `cdpr stiffness-map`: the stiffness-oriented study of Picard, Caro, Plestan & Claveau 2020 at one pose (Fig. 4).

use super::{CliError, Numbers, print_report, request_robot};
use cdpr::api::{MapReport, StiffnessMapRequest};
use cdpr::plot::HeatMap;
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

/// Runs the command: parse → request → run → render.
pub fn run(args: Args) -> Result<(), CliError> {
    let mut request = StiffnessMapRequest::new(request_robot(&args.robot)?, args.pose.0.clone());
    let numbers = |n: &Option<Numbers>| n.as_ref().map(|n| n.0.clone());
    (request.wrench, request.direction) = (numbers(&args.wrench), numbers(&args.direction));
    (request.grid, request.nu_samples) = (args.grid, args.nu_samples);
    request.corners = args.corners;
    let report = request.run()?;
    let Some(map) = &report.map else {
        if args.json {
            return print_report(&report);
        }
        let reason = report.reason.as_deref().unwrap_or_default();
        println!("no feasible polygon at this pose: {reason}");
        return Ok(());
    };
    if let Some(path) = &args.plot {
        save_map_plot(&report.robot, map, path)?;
    }
    if args.json {
        return print_report(&report);
    }
    print_map(&request, map);
    Ok(())
}

/// The heat map of `--plot` (Picard, Caro, Plestan & Claveau 2020, Fig. 4 left).
fn save_map_plot(name: &str, map: &MapReport, path: &std::path::Path) -> Result<(), CliError> {
    let g = &map.grid;
    let n = g.lambda1.len();
    let range = |v: &[f64]| (v[0], v[v.len() - 1]);
    let [bx, by] = map.barycenter_lambda;
    let [ox, oy] = map.optimum_lambda;
    let fig = HeatMap {
        title: format!(
            "{name}: |d·δp| over the feasible polygon (reduction {:.1} %)",
            map.reduction_percent
        ),
        labels: ("λ1 (N)".into(), "λ2 (N)".into()),
        value_label: "|d·δp| (mm)".into(),
        x_range: range(&g.lambda1),
        y_range: range(&g.lambda2),
        shape: (n, g.lambda2.len()),
        values: g
            .values
            .iter()
            .flatten()
            .map(|v| v.unwrap_or(f64::NAN))
            .collect(),
        blank_below: f64::NEG_INFINITY,
        markers: Vec::new(),
        outlines: vec![map.polygon.iter().map(|v| (v[0], v[1])).collect()],
        highlight: vec![
            (
                (bx, by),
                format!("barycentre {:.3} mm", map.displacement_barycenter),
            ),
            (
                (ox, oy),
                format!("SOTDA optimum {:.3} mm", map.displacement_optimum),
            ),
        ],
    };
    cdpr::plot::save(&fig, path)?;
    Ok(())
}

/// The text answer.
fn print_map(request: &StiffnessMapRequest, map: &MapReport) {
    let desc = request.robot.description();
    let motion = desc.robot.motion();
    let forces = motion.translation_dof();
    println!(
        "robot {}, pose {}, w_ext {} (tensions), load {} (displacement), direction {}",
        desc.name,
        super::pose_text(&request.pose, motion.space_dim()),
        super::wrench_text(&map.external_wrench, forces),
        map.load
            .as_ref()
            .map_or_else(|| "none".to_string(), |p| super::wrench_text(p, forces)),
        super::nums(&map.direction)
    );
    println!("feasible polygon: {} vertices", map.polygon.len());
    println!("displacement |d·δp| in {}:", map.unit);
    println!("  barycentre      {:.6}", map.displacement_barycenter);
    println!("  SOTDA optimum   {:.6}", map.displacement_optimum);
    println!("  reduction       {:.3} %", map.reduction_percent);
    println!(
        "  grid min / max  {:.6} / {:.6} (spread {:.6})",
        map.grid_min, map.grid_max, map.spread
    );
    println!("{:>6} {:>12}", "nu", "|d·δp|");
    for [nu, d] in &map.nu_curve {
        println!("{nu:>6.3} {d:>12.6}");
    }
}
