//! Thesis §6.4: the workspaces of Figs. 6.4 (3-cable) and 6.5 (4-cable), as far as the text
//! describes them (the figures themselves are not part of the thesis chapter).
use crate::common;

use cdpr_tension::{Method, TensionBounds};
use cdpr_workspace::{Criterion, Grid, GridWorkspace, PoseEvaluator, planar_workspace};
use common::*;

const PHIS: [f64; 3] = [0.0, 0.05, 0.1];

fn areas(make: impl Fn(usize) -> PoseEvaluator) -> Vec<GridWorkspace> {
    let mut out = Vec::new();
    for load_case in 0..3 {
        let eval = make(load_case);
        for phi in PHIS {
            out.push(planar_workspace(&eval, phi, &Grid::over_frame(eval.robot(), 50)).unwrap());
        }
    }
    out
}

/// Fig. 6.4: every (φ, load) workspace of the 3-cable robot with m = 50 is non-empty, and the
/// workspace is "highly dependent on both the load … as well as the orientation": within each
/// load case, φ moving by 0.1 rad changes the area by a factor above 2.5 (above 9 for L1 and
/// L3), and over all nine cases by a factor above 10.
#[test]
fn fig_6_4_three_cable_is_highly_sensitive_to_orientation_and_load() {
    let ws = areas(three_cable_eval);
    for (k, w) in ws.iter().enumerate() {
        assert!(w.feasible_points > 0, "L{} φ = {}", k / 3 + 1, PHIS[k % 3]);
    }
    for load_case in 0..3 {
        let a: Vec<f64> = ws[3 * load_case..3 * load_case + 3]
            .iter()
            .map(|w| w.area)
            .collect();
        let (lo, hi) = (
            a.iter().cloned().fold(f64::INFINITY, f64::min),
            a.iter().cloned().fold(0.0, f64::max),
        );
        assert!(hi > 2.5 * lo, "L{}: {a:?}", load_case + 1);
        if load_case != 1 {
            assert!(hi > 9.0 * lo, "L{}: {a:?}", load_case + 1);
        }
    }
    let all: Vec<f64> = ws.iter().map(|w| w.area).collect();
    assert!(
        all.iter().cloned().fold(0.0, f64::max)
            > 10.0 * all.iter().cloned().fold(f64::INFINITY, f64::min)
    );
}

/// Fig. 6.4: at φ = 0 the singularity at x = 0 divides the workspace; near it the boundary is
/// set by D_min (6.24): without that criterion the L1 workspace is larger, and only near x = 0.
#[test]
fn fig_6_4_singularity_at_x_zero_and_d_min() {
    let g = Grid::over_frame(&three_cable(), 50);
    for load_case in 0..3 {
        let ws = planar_workspace(&three_cable_eval(load_case), 0.0, &g).unwrap();
        // Column i = 25 is x = 0: empty.
        for j in 0..=50 {
            assert!(!ws.feasible[j * 51 + 25]);
        }
    }
    let without = PoseEvaluator::new(
        three_cable(),
        TensionBounds::uniform(3, T_MIN, T_MAX).unwrap(),
        vec![
            Criterion::TensionFeasible {
                method: Method::Exact,
                wrench: load(0),
            },
            Criterion::MinCableLength(L_MIN),
        ],
    )
    .unwrap();
    let with = planar_workspace(&three_cable_eval(0), 0.0, &g).unwrap();
    let without = planar_workspace(&without, 0.0, &g).unwrap();
    assert!(with.is_subset_of(&without));
    assert!(without.feasible_points > with.feasible_points);
    for i in 0..with.total_points {
        if without.feasible[i] && !with.feasible[i] {
            assert!(with.point(i).x.abs() < 0.1, "{:?}", with.point(i));
        }
    }
}

/// Mirror symmetry: both robots and L1 are symmetric about x = 0, so W(φ) mirrored is W(−φ).
#[test]
fn mirror_symmetry_under_l1() {
    for eval in [three_cable_eval(0), four_cable_eval(0, Method::L2)] {
        let g = Grid::over_frame(eval.robot(), 50);
        for phi in [0.05, 0.1, 0.2] {
            let a = planar_workspace(&eval, phi, &g).unwrap();
            let b = planar_workspace(&eval, -phi, &g).unwrap();
            let mut mismatches = 0;
            for j in 0..=50 {
                for i in 0..=50 {
                    if a.feasible[j * 51 + i] != b.feasible[j * 51 + 50 - i] {
                        mismatches += 1;
                    }
                }
            }
            // Grid coordinates are mirrored to within one rounding: allow boundary flips.
            assert!(mismatches <= 2, "φ = {phi}: {mismatches}");
            assert!(a.feasible_points > 0);
        }
    }
}

/// Fig. 6.5 and its text: the 4-cable workspaces are non-empty, larger than the 3-cable ones
/// (in total over the cases of Fig. 6.4) and far less sensitive to orientation and load.
#[test]
fn fig_6_5_four_cable_is_larger_and_less_sensitive() {
    let three = areas(three_cable_eval);
    let four = areas(|l| four_cable_eval(l, Method::L2));
    for (k, w) in four.iter().enumerate() {
        assert!(w.feasible_points > 0, "L{} φ = {}", k / 3 + 1, PHIS[k % 3]);
    }
    let total = |ws: &[GridWorkspace]| ws.iter().map(|w| w.area).sum::<f64>();
    assert!(total(&four) > 1.5 * total(&three));
    let spread = |ws: &[GridWorkspace]| {
        let a: Vec<f64> = ws.iter().map(|w| w.area).collect();
        a.iter().cloned().fold(0.0, f64::max) / a.iter().cloned().fold(f64::INFINITY, f64::min)
    };
    assert!(spread(&four) < 2.0, "{}", spread(&four));
    assert!(spread(&three) > 10.0, "{}", spread(&three));
    // Also at φ = ±0.2 (Fig. 6.9 uses φ = −0.2 for L3).
    for l in 0..3 {
        let eval = four_cable_eval(l, Method::L2);
        for phi in [-0.2, 0.2] {
            assert!(
                planar_workspace(&eval, phi, &Grid::over_frame(eval.robot(), 50))
                    .unwrap()
                    .feasible_points
                    > 0
            );
        }
    }
}
