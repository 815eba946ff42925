//! Tension profiles along paths: continuity of barycentre, ℓ2 and SOTDA (ν < 1) inside the
//! workspace, and the jump of thesis Fig. 6.6.

use cdpr_kinematics::{Cable, MotionPattern, Path, Robot, Sampling};
use cdpr_tension::profile::tension_profile;
use cdpr_tension::{Method, SotdaSettings, TensionBounds, TensionSolver};
use nalgebra::{DVector, Vector3};

fn eight_cable() -> Robot {
    let mut cables = Vec::new();
    for (z, pz) in [(2.0, -0.05), (0.0, 0.05)] {
        for (x, y) in [(2.0f64, 1.5f64), (-2.0, 1.5), (-2.0, -1.5), (2.0, -1.5)] {
            cables.push(Cable {
                frame: Vector3::new(x, y, z),
                platform: Vector3::new(0.1f64.copysign(x), 0.1f64.copysign(y), pz),
                pulley: None,
            });
        }
    }
    Robot::new(MotionPattern::Spatial, cables).unwrap()
}

/// Largest per-cable jump along the path with `count` samples.
fn max_jump(solver: &mut TensionSolver, count: usize) -> f64 {
    let robot = eight_cable();
    let path = Path::from_coordinates(
        MotionPattern::Spatial,
        &[
            vec![-0.4, -0.3, 0.8, 0.0, 0.0, -0.05],
            vec![0.4, 0.3, 1.2, 0.05, 0.0, 0.05],
        ],
    )
    .unwrap();
    let bounds = TensionBounds::uniform(8, 10.0, 1000.0).unwrap();
    let es = [60_000.0; 8];
    let wrench = DVector::from_vec(vec![0.0, 50.0, -49.0, 0.0, 0.0, 0.0]);
    let samples = path.sample(Sampling::Count(count)).unwrap();
    let profile = tension_profile(&robot, &samples, &bounds, solver, Some(&es), |_| {
        wrench.clone()
    })
    .unwrap();
    assert_eq!(
        profile.feasible_count(),
        count,
        "path must stay inside the workspace: {:?}",
        profile.reasons
    );
    profile.max_jump.iter().copied().fold(0.0, f64::max)
}

#[test]
fn barycenter_l2_and_sotda_profiles_are_continuous() {
    let sotda = SotdaSettings {
        nu: 0.5,
        ..SotdaSettings::default()
    };
    for mut solver in [
        TensionSolver::new(Method::Barycenter),
        TensionSolver::new(Method::L2),
        TensionSolver::sotda(sotda),
    ] {
        let coarse = max_jump(&mut solver, 50);
        let fine = max_jump(&mut solver, 400);
        // A continuous (piecewise smooth) profile: 8× more samples, jumps at least 4× smaller.
        assert!(
            fine < coarse / 4.0,
            "{:?}: max jump {coarse} with 50 samples, {fine} with 400",
            solver.method()
        );
    }
}

/// Thesis Fig. 6.6: c = [±1, ±0.1], platform of Table 6.1, load L1, φ = 0, section x = 0.54.
/// The thesis draws t3, t4 jumping at y = 0, on the workspace boundary. In our model the section
/// leaves the workspace at y ≈ −0.85 mm, and within the last centimetre before it (most in the last
/// 2 mm) the ℓ2 tensions change by
/// tens of newtons (the active set switches as cables 3 and 4 become horizontal): on any plot with
/// a step coarser than a millimetre this is the thesis' jump. The profile flags it, with the
/// infeasible samples beyond it reported, not hidden.
#[test]
fn fig_6_6_section_shows_the_jump() {
    let s = 0.1 / 2f64.sqrt();
    let c = |f: [f64; 2], a: [f64; 2]| Cable {
        frame: Vector3::new(f[0], f[1], 0.0),
        platform: Vector3::new(a[0], a[1], 0.0),
        pulley: None,
    };
    let robot = Robot::new(
        MotionPattern::Planar,
        vec![
            c([1.0, 0.1], [s, s]),
            c([-1.0, 0.1], [-s, s]),
            c([-1.0, -0.1], [-0.1, -0.1]),
            c([1.0, -0.1], [0.1, -0.1]),
        ],
    )
    .unwrap();
    let bounds = TensionBounds::uniform(4, 5.0, 100.0).unwrap();
    let l1 = DVector::from_vec(vec![0.0, -10.0, 0.0]);
    let mut solver = TensionSolver::new(Method::L2);
    // y from −0.2 to +0.05 in steps of 0.1 mm.
    let path = Path::from_coordinates(
        MotionPattern::Planar,
        &[vec![0.54, -0.2, 0.0], vec![0.54, 0.05, 0.0]],
    )
    .unwrap();
    let samples = path.sample(Sampling::Count(2501)).unwrap();
    let y = |k: usize| samples[k].pose.position.y;
    let profile =
        tension_profile(&robot, &samples, &bounds, &mut solver, None, |_| l1.clone()).unwrap();
    // Beyond the boundary near y = 0 every sample is infeasible, with its parameter and reason.
    let first_out = (0..samples.len())
        .find(|&k| profile.tensions[k].is_none() && y(k) > -0.1)
        .unwrap();
    assert!(
        y(first_out).abs() < 2e-3,
        "section leaves the workspace at y = {}",
        y(first_out)
    );
    assert!(
        (first_out..samples.len())
            .all(|k| profile.tensions[k].is_none() && profile.reasons[k].is_some())
    );
    // The flagged steps all lie within about a centimetre of y = 0 ...
    let flagged = profile.discontinuities(20.0);
    assert!(!flagged.is_empty());
    assert!(
        flagged.iter().all(|&k| y(k).abs() < 1.2e-2),
        "flagged at {:?}",
        flagged.iter().map(|&k| y(k)).collect::<Vec<_>>()
    );
    // ... where t3 climbs by more than 50 N within 2 mm, while over the 5 cm before it changes
    // by less than 10 N.
    let t3 = |k: usize| profile.tensions[k].as_ref().unwrap()[2];
    let last = first_out - 1;
    let k_2mm = (0..last).rev().find(|&k| y(k) < y(last) - 2e-3).unwrap();
    let k_5cm = (0..last).rev().find(|&k| y(k) < y(k_2mm) - 0.05).unwrap();
    let rise: f64 = (k_2mm..last).map(|k| (t3(k + 1) - t3(k)).abs()).sum();
    let before = (t3(k_2mm) - t3(k_5cm)).abs();
    assert!(
        rise > 50.0 && before < 10.0,
        "rise {rise} N in the last 2 mm, {before} N over the 5 cm before"
    );
}
