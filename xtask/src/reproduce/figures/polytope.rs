//! Figures of the polytope area: seed 001 Fig. 9 (maximum isotropic force of the 3-motor
//! point robot over the plane) and Fig. 10 (4, 5 and 6 motors regularly spaced on a circle),
//! from `examples/robots/krut-{3,4,5,6}.toml` (motors at 1000 mm, tensions in [50, 500] N).

use super::Figure;
use cdpr::RobotDescription;
use cdpr::kinematics::Pose;
use cdpr::plot::{HeatMap, save};
use cdpr::polytope::IsotropicForce;
use std::path::Path;

/// Grid intervals per side: 121 × 121 poses over [−1000, 1000]² mm.
const GRID: usize = 120;
/// Half-width of the mapped square (the motors' circle radius, mm).
const HALF: f64 = 1000.0;

/// Writes this area's figures into `dir`.
pub fn figures(dir: &Path) -> Result<Vec<Figure>, String> {
    let root = dir
        .parent()
        .and_then(Path::parent)
        .ok_or("figures directory must be <root>/docs/figures")?;
    render(root, dir)
}

/// The map of one robot: (values row-major x fastest, centre value, max, fraction ≥ 0).
struct Map {
    values: Vec<f64>,
    centre: f64,
    max: f64,
    positive: f64,
}

fn map(robot: &RobotDescription) -> Result<Map, String> {
    let mut index = IsotropicForce::new(&robot.robot, &robot.bounds).map_err(|e| e.to_string())?;
    let k = GRID + 1;
    let at = |i: usize| -HALF + 2.0 * HALF * i as f64 / GRID as f64;
    let mut values = Vec::with_capacity(k * k);
    for j in 0..k {
        for i in 0..k {
            // Undefined where a cable has zero length (at a motor): NaN, drawn white.
            values.push(
                index
                    .force_at_pose(&Pose::point(at(i), at(j), 0.0))
                    .unwrap_or(f64::NAN),
            );
        }
    }
    let centre = index
        .force_at_pose(&Pose::point(0.0, 0.0, 0.0))
        .map_err(|e| e.to_string())?;
    let max = values
        .iter()
        .copied()
        .filter(|v| !v.is_nan())
        .fold(f64::NEG_INFINITY, f64::max);
    let positive = values.iter().filter(|&&v| v >= 0.0).count() as f64 / values.len() as f64;
    Ok(Map {
        values,
        centre,
        max,
        positive,
    })
}

/// Renders the four maps of `root/examples/robots/krut-N.toml` into `out`.
fn render(root: &Path, out: &Path) -> Result<Vec<Figure>, String> {
    // Hand-derived centre values: s_i = t_i − 275 ∈ [−225, 225] and Σ 275 u_i = 0, so the AWS
    // is the zonotope Σ s_i u_i; its facet normal ⟂ u_k is at distance 225 Σ_j |sin(θ_j − θ_k)|.
    let hand = |n: usize| -> f64 {
        (1..n)
            .map(|j| {
                225.0
                    * (2.0 * std::f64::consts::PI * j as f64 / n as f64)
                        .sin()
                        .abs()
            })
            .sum()
    };
    let mut figs = Vec::new();
    let mut centres = Vec::new();
    for n in 3..=6 {
        let robot = RobotDescription::load(root.join(format!("examples/robots/krut-{n}.toml")))
            .map_err(|e| e.to_string())?;
        let m = map(&robot)?;
        if (m.centre - hand(n)).abs() > 1e-5 * hand(n) {
            return Err(format!(
                "krut-{n}: centre value {} differs from the hand-derived {}",
                m.centre,
                hand(n)
            ));
        }
        centres.push(m.centre);
        let fig = HeatMap {
            title: format!(
                "Seed 001 Fig. {}: maximum isotropic force, {n} motors",
                if n == 3 { 9 } else { 10 }
            ),
            labels: ("x (mm)".into(), "y (mm)".into()),
            value_label: "maximum isotropic force (N)".into(),
            x_range: (-HALF, HALF),
            y_range: (-HALF, HALF),
            shape: (GRID + 1, GRID + 1),
            values: m.values,
            blank_below: 0.0,
            markers: robot
                .robot
                .cables()
                .iter()
                .map(|c| (c.frame.x, c.frame.y))
                .collect(),
            outlines: Vec::new(),
            highlight: vec![((0.0, 0.0), format!("{:.1} N", m.centre))],
        };
        let file = format!("polytope-seed001-isotropic-{n}-motors.png");
        save(&fig, out.join(&file)).map_err(|e| e.to_string())?;
        let common = format!(
            "Our map: {}² positions over [−1000, 1000]² mm, white where the index is negative \
             (the pose cannot hold even a zero load with t ≥ 50 N) or undefined (at a motor); \
             tensions in [50, 500] N. Centre value {:.1} N (hand-derived zonotope apothem {:.1} N), \
             maximum {:.1} N, {:.0} % of the square has a non-negative index.",
            GRID + 1,
            m.centre,
            hand(n),
            m.max,
            100.0 * m.positive
        );
        figs.push(if n == 3 {
            Figure {
                file,
                source: "Seed 001 Fig. 9".into(),
                caption: format!(
                    "The paper maps the maximum isotropic force f_min (eq. 19) of the 3-motor \
                     point robot over its workspace, drawing f_min < 0 in white; the theoretical \
                     workspace is where f_min ≥ 0. {common} The largest value is at the centre \
                     (225·√3 ≈ 389.7 N: the force polytope is a regular hexagon there), ridges \
                     run towards the motors where two facets tie, and the workspace is slightly \
                     smaller than the motors' triangle, as in the paper."
                ),
            }
        } else {
            Figure {
                file,
                source: format!("Seed 001 Fig. 10 ({n} motors)"),
                caption: format!(
                    "The paper maps f_min for {n} motors regularly spaced on a circle of radius \
                     l (here 1000 mm, first motor at 30°) and observes that more motors give a \
                     larger index in the middle of the workspace and that the workspace is not \
                     exactly a regular polygon because tensions must stay above t_min > 0. \
                     {common} Our centre values grow with n as in the paper: {}.",
                    centres
                        .iter()
                        .enumerate()
                        .map(|(i, c)| format!("{} motors {c:.1} N", i + 3))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            }
        });
    }
    Ok(figs)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed001_maps_are_written_and_grow_with_the_motor_count() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap();
        // POLYTOPE_FIG_DIR keeps the images for inspection.
        let keep = std::env::var_os("POLYTOPE_FIG_DIR");
        let out = keep.clone().map(Into::into).unwrap_or_else(|| {
            std::env::temp_dir().join(format!("cdpr-polytope-figs-{}", std::process::id()))
        });
        std::fs::create_dir_all(&out).unwrap();
        let t0 = std::time::Instant::now();
        let figs = render(root, &out).unwrap();
        eprintln!("polytope figures: {:?}", t0.elapsed());
        assert_eq!(figs.len(), 4);
        for f in &figs {
            assert!(std::fs::metadata(out.join(&f.file)).unwrap().len() > 10_000);
        }
        assert!(figs[3].caption.contains("3 motors 389.7 N"));
        if keep.is_none() {
            std::fs::remove_dir_all(&out).ok();
        }
    }
}
