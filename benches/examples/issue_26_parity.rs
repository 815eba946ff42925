//! Issue 26's parity counts on its fixture (`cdpr_benches::issue_26`, WireLib's
//! `CIPAnema1Design`, 20 000 poses): for every method of the issue, how many poses are
//! feasible, how many of those the LP (`l1`) finds infeasible (false feasible: must be 0), and
//! the other verdicts (give-ups, heuristic misses); for `pott-closed-form` the largest
//! difference from t = t_m − W⁺(w + W t_m) with W⁺ from nalgebra's SVD. Run with
//! `cargo run --release -p cdpr-benches --example issue_26_parity [POSES]`.

use cdpr_benches::issue_26::{SEED, fixture, poses};
use cdpr_tension::{Infeasibility, Method, MethodOptions, TensionProblem, TensionSolver};
use nalgebra::{DMatrix, DVector};
use std::collections::BTreeMap;

fn main() {
    let count: usize = std::env::args()
        .nth(1)
        .map_or(20_000, |s| s.parse().expect("POSES"));
    let mut f = fixture();
    f.poses = poses(count, SEED);
    let ws: Vec<DMatrix<f64>> = f
        .poses
        .iter()
        .map(|p| f.robot.inverse_kinematics(p).unwrap().wrench_matrix())
        .collect();
    let mut lp = TensionSolver::new(Method::L1);
    let feasible: Vec<bool> = ws
        .iter()
        .map(|w| {
            lp.is_feasible(&TensionProblem::new(w, &f.load, &f.bounds))
                .unwrap()
        })
        .collect();
    let lp_count = feasible.iter().filter(|&&b| b).count();
    println!("poses {count}, LP (l1) feasible {lp_count}");
    let alternating = MethodOptions {
        alternating: true,
        ..Default::default()
    };
    let cf = MethodOptions {
        interior: cdpr_tension::PunctureInterior::ClosedForm,
        ..Default::default()
    };
    let runs: Vec<(&str, Method, MethodOptions)> = vec![
        (
            "pott-closed-form",
            Method::PottClosedForm,
            Default::default(),
        ),
        (
            "pott-closed-form-ee",
            Method::PottClosedFormEe,
            Default::default(),
        ),
        ("puncture (icf)", Method::Puncture, Default::default()),
        ("puncture (cf)", Method::Puncture, cf),
        ("dykstra", Method::Dykstra, Default::default()),
        ("dykstra --alternating", Method::Dykstra, alternating),
        ("l2-mid", Method::L2Mid, Default::default()),
        (
            "vertex-centroid",
            Method::VertexCentroid,
            Default::default(),
        ),
        ("p-norm", Method::PNorm, Default::default()),
        ("optimally-safe", Method::OptimallySafe, Default::default()),
        (
            "improved-closed-form",
            Method::ImprovedClosedForm,
            Default::default(),
        ),
        ("barycenter", Method::Barycenter, Default::default()),
    ];
    for (name, method, options) in runs {
        let mut solver = TensionSolver::new(method).with_options(options).unwrap();
        let (mut ok, mut false_feasible, mut missed) = (0, 0, 0);
        let mut reasons: BTreeMap<String, usize> = BTreeMap::new();
        let mut iterations = 0usize;
        let mut worst_pinv = 0f64;
        for (w, &lp_ok) in ws.iter().zip(&feasible) {
            let p = TensionProblem::new(w, &f.load, &f.bounds);
            let out = solver.solve(&p).unwrap();
            iterations = iterations.max(solver.iterations());
            if method == Method::PottClosedForm
                && let Some(t) = out.balancing_tensions()
            {
                let tm = DVector::from_element(8, 500.5);
                let pinv = w.clone().pseudo_inverse(1e-14).unwrap();
                let reference = &tm - pinv * (&f.load + w * &tm);
                worst_pinv = worst_pinv.max((t - reference).amax());
            }
            match out.infeasibility() {
                None => {
                    ok += 1;
                    false_feasible += usize::from(!lp_ok);
                }
                Some(reason) => {
                    missed += usize::from(lp_ok);
                    let key = match reason {
                        Infeasibility::GaveUp { reason, .. } => format!("gave up: {reason}"),
                        Infeasibility::BoundsViolated { .. } => "bounds violated".to_string(),
                        Infeasibility::Inconclusive { .. } => "inconclusive".to_string(),
                        Infeasibility::NoFeasibleTension => "no feasible tension".to_string(),
                        other => format!("{other}"),
                    };
                    *reasons.entry(key).or_default() += 1;
                }
            }
        }
        println!(
            "{name:24} feasible {ok:6}  false feasible {false_feasible}  LP-feasible missed {missed:5}  max iterations {iterations}  {reasons:?}"
        );
        if method == Method::PottClosedForm {
            println!("{:24} max |t − t_pinv(SVD)| = {worst_pinv:.3e} N", "");
        }
        let _ = name;
    }
}
