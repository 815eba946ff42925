//! Property tests on random robots, poses, wrenches and bounds (cdpr_kinematics::strategies).
//!
//! Verdict tolerance: our own methods share one feasibility test up to 10⁻¹² (relative, on the
//! tension bounds) and certify answers to 10⁻⁹; Clarabel decides to ~10⁻¹⁰. Random data lands
//! within those margins of the feasible-set boundary with negligible probability, so verdicts
//! are compared exactly.

use cdpr_kinematics::strategies::arb_robot_and_pose;
use cdpr_kinematics::{Pose, Robot};
use cdpr_tension::{
    FeasiblePolygon, Method, Objective, TensionBounds, TensionOutcome, TensionProblem,
    TensionSolver, feasible_interval, interior_point,
};
use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;

/// A random problem: W from a robot and pose, bounds lo ∈ [0, 5], hi = lo + [1, 100],
/// w_ext = −W t_r + δ for t_r inside the bounds and a perturbation δ that makes some problems
/// infeasible.
#[derive(Debug, Clone)]
struct Case {
    w: DMatrix<f64>,
    we: DVector<f64>,
    b: TensionBounds,
}

fn arb_case(extra: std::ops::RangeInclusive<usize>) -> impl Strategy<Value = Case> {
    (
        arb_robot_and_pose(extra),
        prop::collection::vec(0.0f64..5.0, 12),
        prop::collection::vec(1.0f64..100.0, 12),
        prop::collection::vec(0.0f64..1.0, 12),
        prop::collection::vec(-1.0f64..1.0, 6),
        prop_oneof![Just(0.0), 0.0f64..60.0],
    )
        .prop_map(|((robot, pose), lo, span, frac, dir, mag)| {
            build(&robot, &pose, &lo, &span, &frac, &dir, mag)
        })
}

fn build(
    robot: &Robot,
    pose: &Pose,
    lo: &[f64],
    span: &[f64],
    frac: &[f64],
    dir: &[f64],
    mag: f64,
) -> Case {
    let w = robot.inverse_kinematics(pose).unwrap().wrench_matrix();
    let (m, n) = w.shape();
    let lo: Vec<f64> = lo[..n].to_vec();
    let hi: Vec<f64> = (0..n).map(|i| lo[i] + span[i]).collect();
    let tr = DVector::from_fn(n, |i, _| lo[i] + frac[i] * span[i]);
    let we = -(&w * tr) + DVector::from_fn(m, |k, _| mag * dir[k]);
    Case {
        w,
        we,
        b: TensionBounds::new(lo, hi).unwrap(),
    }
}

fn solve(m: Method, p: &TensionProblem) -> TensionOutcome {
    TensionSolver::new(m).solve(p).unwrap()
}

/// Independent check of equilibrium and bounds.
fn check(p: &TensionProblem, t: &DVector<f64>) {
    let scale = 1f64
        .max(p.external_wrench.amax())
        .max(p.wrench_matrix.abs().row_sum().amax() * t.amax());
    assert!((p.wrench_matrix * t + p.external_wrench).amax() <= 1e-9 * scale);
    for i in 0..t.len() {
        assert!(t[i] >= p.bounds.min()[i] - 1e-9 * p.bounds.min()[i].abs().max(1.0));
        assert!(t[i] <= p.bounds.max()[i] + 1e-9 * p.bounds.max()[i].abs().max(1.0));
    }
}

fn rel_eq(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * a.abs().max(b.abs()).max(1.0)
}

fn linf(t: &DVector<f64>) -> f64 {
    t.max()
}

/// Random feasible points t0 + N λ of the feasible set (r = 1, 2): random λ in the bounding box
/// of the vertices, kept when they satisfy the bounds, plus random convex combinations of
/// vertices.
fn random_feasible(p: &TensionProblem, seed: &[f64]) -> Vec<DVector<f64>> {
    let mut out = Vec::new();
    let ok = |t: &DVector<f64>| {
        (0..t.len()).all(|i| t[i] >= p.bounds.min()[i] && t[i] <= p.bounds.max()[i])
    };
    match p.redundancy() {
        1 => {
            if let Ok(iv) = feasible_interval(p).unwrap() {
                let (a, b) = iv.lambda;
                for s in seed {
                    let t = iv.tensions_at(a - 0.1 * (b - a) + 1.2 * s * (b - a));
                    if ok(&t) {
                        out.push(t);
                    }
                }
            }
        }
        2 => {
            if let Ok(poly) = FeasiblePolygon::compute(p).unwrap() {
                let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
                for v in &poly.vertices {
                    for d in 0..2 {
                        lo[d] = lo[d].min(v[d]);
                        hi[d] = hi[d].max(v[d]);
                    }
                }
                for pair in seed.chunks(2) {
                    let l = nalgebra::Vector2::new(
                        lo[0] + pair[0] * (hi[0] - lo[0]),
                        lo[1] + pair[pair.len() - 1] * (hi[1] - lo[1]),
                    );
                    let t = poly.tensions_at(&l);
                    if ok(&t) {
                        out.push(t);
                    }
                }
                let k = poly.vertices.len();
                for (j, s) in seed.iter().enumerate() {
                    let (a, b) = (
                        &poly.tension_vertices[j % k],
                        &poly.tension_vertices[(j + 1) % k],
                    );
                    let c = poly.barycenter();
                    out.push((a * *s + b * (1.0 - *s)) * 0.5 + c * 0.5);
                }
            }
        }
        _ => {}
    }
    out
}

/// The bounds of `case` as they are (variant 0), with t_max,which = ∞ (1), with cable `which`
/// fixed (t_min = t_max) at its l2 tension when the problem is feasible (2), or with every
/// t_max = ∞ (3).
fn variant_bounds(case: &Case, variant: usize, which: usize) -> TensionBounds {
    let which = which % case.w.ncols();
    let (mut lo, mut hi) = (
        case.b.min().as_slice().to_vec(),
        case.b.max().as_slice().to_vec(),
    );
    match variant {
        1 => hi[which] = f64::INFINITY,
        2 => {
            let p = TensionProblem::new(&case.w, &case.we, &case.b);
            if let TensionOutcome::Feasible(s) = solve(Method::L2, &p) {
                lo[which] = s.tensions[which];
                hi[which] = s.tensions[which];
            }
        }
        3 => hi.iter_mut().for_each(|h| *h = f64::INFINITY),
        _ => {}
    }
    TensionBounds::new(lo, hi).unwrap()
}

/// min ‖t‖² over a bounded feasible polygon by brute force: ‖t0‖² when t0 = −W⁺ w_ext is
/// inside the bounds (the unconstrained minimum), else the closest point of an edge (tension
/// space).
fn polygon_l2(poly: &FeasiblePolygon, b: &TensionBounds) -> f64 {
    let t0 = &poly.particular;
    if (0..t0.len()).all(|i| t0[i] >= b.min()[i] && t0[i] <= b.max()[i]) {
        return t0.norm_squared();
    }
    let k = poly.tension_vertices.len();
    let mut best = f64::INFINITY;
    for j in 0..k {
        let (a, c) = (
            &poly.tension_vertices[j],
            &poly.tension_vertices[(j + 1) % k],
        );
        let d = c - a;
        let dd = d.norm_squared();
        let s = if dd > 0.0 {
            (-a.dot(&d) / dd).clamp(0.0, 1.0)
        } else {
            0.0
        };
        best = best.min((a + d * s).norm_squared());
    }
    best
}

proptest! {
    #![proptest_config(ProptestConfig { failure_persistence: None, ..ProptestConfig::default() })]

    /// r = 1, 2: every answer is certified; verdicts of all complete methods (and Clarabel)
    /// agree; optima match Clarabel; no random feasible point beats an optimum.
    #[test]
    fn optima_verdicts_and_certificates(case in arb_case(1..=2), seed in prop::collection::vec(0.0f64..1.0, 40)) {
        let p = TensionProblem::new(&case.w, &case.we, &case.b);
        let r = p.redundancy();
        let mut complete = vec![Method::L1, Method::L1Max, Method::L2, Method::L2Max, Method::Linf];
        complete.push(if r == 1 { Method::ClosedForm } else { Method::Barycenter });
        let outs: Vec<_> = complete.iter().map(|&m| solve(m, &p)).collect();
        let oracle = interior_point(&p, Objective::L2).unwrap();
        for (m, o) in complete.iter().zip(&outs) {
            prop_assert_eq!(o.is_feasible(), oracle.is_ok(), "{} vs clarabel: {:?}", m, o);
            if let Some(t) = o.tensions() { check(&p, t); }
        }
        for m in [Method::Pinv, Method::ImprovedClosedForm] {
            let o = solve(m, &p);
            if let Some(t) = o.tensions() {
                check(&p, t);
                prop_assert!(oracle.is_ok(), "{} feasible where the set is empty", m);
            }
        }
        let Ok(t_ip) = oracle else { return Ok(()) };
        let t = |k: usize| outs[k].tensions().unwrap().clone();
        let (l1, l1max, l2, l2max, li) = (t(0), t(1), t(2), t(3), t(4));
        // Clarabel oracle.
        // ‖t‖² is 1-strongly convex, so for the optimum t*: ‖t − t*‖² ≤ ‖t‖² − ‖t*‖² for every
        // feasible t. Clarabel stops at a relative gap of 10⁻¹⁰, i.e. up to ~10⁻⁵ away from t*
        // on a ‖t‖² of 10⁴: compare through that inequality, not entry by entry.
        let (f2, f_ip) = (l2.norm_squared(), t_ip.norm_squared());
        prop_assert!(f2 <= f_ip * (1.0 + 1e-10) + 1e-12, "l2 {} vs {}", l2, t_ip);
        let s = 1e-7 * t_ip.amax().max(1.0);
        prop_assert!((&l2 - &t_ip).norm_squared() <= (f_ip - f2).max(0.0) * (1.0 + 1e-6) + s * s, "l2 {} vs {}", l2, t_ip);
        let ip = |o| interior_point(&p, o).unwrap().unwrap();
        prop_assert!(rel_eq(l1.sum(), ip(Objective::L1).sum(), 1e-7));
        prop_assert!(rel_eq(l1max.sum(), ip(Objective::L1Max).sum(), 1e-7));
        prop_assert!(rel_eq(linf(&li), linf(&ip(Objective::Linf)), 1e-7));
        // Closed form = l1 (min), and its interval's best end = l1-max.
        if r == 1 {
            prop_assert!(rel_eq(t(5).sum(), l1.sum(), 1e-9));
            let iv = feasible_interval(&p).unwrap().unwrap();
            let best = iv.tensions_low.sum().max(iv.tensions_high.sum());
            prop_assert!(rel_eq(best, l1max.sum(), 1e-9));
        }
        // No random feasible point beats an optimum.
        for q in random_feasible(&p, &seed) {
            let tol = 1e-9 * q.amax().max(1.0);
            prop_assert!(l1.sum() <= q.sum() + tol * q.len() as f64);
            prop_assert!(l1max.sum() >= q.sum() - tol * q.len() as f64);
            prop_assert!(l2.norm_squared() <= q.norm_squared() * (1.0 + 1e-9) + tol);
            prop_assert!(l2max.norm_squared() >= q.norm_squared() * (1.0 - 1e-9) - tol);
            prop_assert!(linf(&li) <= linf(&q) + tol);
        }
    }

    /// The choice of null-space basis does not matter: premultiplying the equilibrium by an
    /// invertible M (M W t + M w_ext = 0 has the same solutions) changes the QR and so N, but
    /// not the optimal tensions (l2, barycentre) or optimal values (l1, linf).
    #[test]
    fn results_do_not_depend_on_the_basis(case in arb_case(2..=2), mix in prop::collection::vec(-0.5f64..0.5, 36)) {
        let m = case.w.nrows();
        let mm = DMatrix::from_fn(m, m, |i, j| if i == j { 2.0 } else { 0.0 } + mix[i * 6 + j]);
        prop_assume!(mm.clone().try_inverse().is_some() && mm.determinant().abs() > 0.1);
        let (w2, we2) = (&mm * &case.w, &mm * &case.we);
        let p1 = TensionProblem::new(&case.w, &case.we, &case.b);
        let p2 = TensionProblem::new(&w2, &we2, &case.b);
        for method in [Method::L2, Method::Barycenter, Method::L1, Method::Linf] {
            let (a, b) = (solve(method, &p1), solve(method, &p2));
            prop_assert_eq!(a.is_feasible(), b.is_feasible());
            if let (Some(x), Some(y)) = (a.tensions(), b.tensions()) {
                let s = x.amax().max(1.0);
                match method {
                    Method::L1 => prop_assert!(rel_eq(x.sum(), y.sum(), 1e-9)),
                    Method::Linf => prop_assert!(rel_eq(x.max(), y.max(), 1e-9)),
                    _ => prop_assert!((x - y).amax() <= 1e-8 * s, "{}: {} vs {}", method, x, y),
                }
            }
        }
    }

    /// r = 3 (interior-point path): answers are certified and ordered l2 ≤ l2-max, l1 ≤ l1-max.
    #[test]
    fn high_redundancy(case in arb_case(3..=3)) {
        let p = TensionProblem::new(&case.w, &case.we, &case.b);
        let outs: Vec<_> = [Method::L1, Method::L1Max, Method::L2, Method::L2Max, Method::Linf]
            .iter().map(|&m| solve(m, &p)).collect();
        let feasible = outs[0].is_feasible();
        for o in &outs {
            prop_assert_eq!(o.is_feasible(), feasible, "{:?}", o);
            if let Some(t) = o.tensions() { check(&p, t); }
        }
        if feasible {
            let t = |k: usize| outs[k].tensions().unwrap().clone();
            prop_assert!(t(0).sum() <= t(1).sum() * (1.0 + 1e-9));
            prop_assert!(t(2).norm() <= t(3).norm() * (1.0 + 1e-9));
            prop_assert!(t(2).norm() <= t(0).norm() * (1.0 + 1e-7));
        }
    }

    /// `is_feasible` gives the same verdict as `solve`, with one solver reused across problems.
    #[test]
    fn is_feasible_matches_solve(cases in prop::collection::vec(arb_case(1..=2), 4)) {
        for method in Method::ALL.iter().filter(|m| **m != Method::Sotda) {
            let mut s = TensionSolver::new(*method);
            for c in &cases {
                let p = TensionProblem::new(&c.w, &c.we, &c.b);
                if !method.applies_to(p.redundancy()) {
                    prop_assert!(s.is_feasible(&p).is_err() && s.solve(&p).is_err());
                    continue;
                }
                let v = s.is_feasible(&p).unwrap();
                prop_assert_eq!(v, s.solve(&p).unwrap().is_feasible());
                prop_assert_eq!(v, TensionSolver::new(*method).solve(&p).unwrap().is_feasible());
            }
        }
    }

    /// Fixed cables (t_min = t_max, issue 13): cable `fixed` is fixed at its tension in a
    /// known feasible t_r, and cable `open` gets t_max = ∞. The set is non-empty, so every
    /// complete minimiser (l1, l2, linf; barycenter at r = 2) must answer feasible, certified.
    #[test]
    fn fixed_cables_keep_feasible_problems_feasible(
        (robot, pose) in arb_robot_and_pose(0..=3),
        frac in prop::collection::vec(0.0f64..1.0, 12),
        fixed in 0usize..12,
        open in prop::option::of(0usize..12),
    ) {
        let w = robot.inverse_kinematics(&pose).unwrap().wrench_matrix();
        let (m, n) = w.shape();
        let (fixed, open) = (fixed % n, open.map(|o| o % n).filter(|&o| o != fixed));
        let lo: Vec<f64> = (0..n).map(|i| 1.0 + 4.0 * frac[i]).collect();
        let mut hi: Vec<f64> = lo.iter().map(|l| l + 500.0).collect();
        let tr = DVector::from_fn(n, |i, _| lo[i] + frac[(i + 5) % 12] * 500.0);
        let mut lo = lo;
        lo[fixed] = tr[fixed];
        hi[fixed] = tr[fixed];
        if let Some(o) = open { hi[o] = f64::INFINITY; }
        let we = -(&w * &tr);
        let _ = m;
        let b = TensionBounds::new(lo, hi).unwrap();
        let p = TensionProblem::new(&w, &we, &b);
        let mut methods = vec![Method::L1, Method::L2, Method::Linf];
        if n == m { methods.push(Method::Exact); }
        if p.redundancy() == 2 { methods.push(Method::Barycenter); }
        for method in methods {
            let out = solve(method, &p);
            if let Some(cdpr_tension::Infeasibility::SingularPose { .. }) = out.infeasibility() {
                continue;
            }
            prop_assert!(out.is_feasible(), "{}: {:?}", method, out);
            check(&p, out.tensions().unwrap());
        }
    }

    /// Issue 17: l2 at r = 2 runs the planar active set (module `planar_active_set`) instead of
    /// projecting onto the clipped polygon. It must give the polygon's verdict and the minimum
    /// of ‖t‖ over the polygon, found here by brute force over the polygon's vertices and edges
    /// in tension space (or Clarabel when an infinite t_max leaves the polygon unbounded), with
    /// one or all t_max infinite and with a fixed cable (t_min = t_max) too.
    #[test]
    fn l2_at_redundancy_2_matches_the_polygon(case in arb_case(2..=2), variant in 0usize..4, which in 0usize..12) {
        let b = variant_bounds(&case, variant, which);
        let p = TensionProblem::new(&case.w, &case.we, &b);
        let out = solve(Method::L2, &p);
        let poly = FeasiblePolygon::compute(&p).unwrap();
        match (&out, &poly) {
            (TensionOutcome::Infeasible(cdpr_tension::Infeasibility::SingularPose { .. }), _) => {}
            (TensionOutcome::Feasible(s), Ok(poly)) => {
                check(&p, &s.tensions);
                let (got, best) = (s.tensions.norm_squared(), polygon_l2(poly, &b));
                prop_assert!(rel_eq(got, best, 1e-8), "l2 {got} against the polygon's {best}");
            }
            (TensionOutcome::Feasible(s), Err(cdpr_tension::Infeasibility::Unbounded { .. })) => {
                check(&p, &s.tensions);
                // Also the optimum under t_max = 10 (1 + max t) instead of ∞, a bounded polygon.
                let cap = 10.0 * (1.0 + s.tensions.max());
                let hi: Vec<f64> = b.max().iter().map(|&h| if h.is_finite() { h } else { cap }).collect();
                let capped = TensionBounds::new(b.min().as_slice().to_vec(), hi).unwrap();
                let q = TensionProblem::new(&case.w, &case.we, &capped);
                let poly = FeasiblePolygon::compute(&q).unwrap().unwrap();
                let (got, best) = (s.tensions.norm_squared(), polygon_l2(&poly, &capped));
                prop_assert!(rel_eq(got, best, 1e-8), "l2 {got} against the capped polygon's {best}");
            }
            (TensionOutcome::Infeasible(reason), Err(theirs)) => {
                prop_assert_eq!(reason, theirs);
            }
            (out, poly) => prop_assert!(false, "l2 {:?} against the polygon {:?}", out, poly),
        }
    }

    /// Issue 17: l1 and l1-max at r = 2 run the simplex method in the plane from the l2 optimum
    /// (module `planar_active_set`) instead of scanning the clipped polygon's vertices. They
    /// must give the polygon's verdict and the optimum of Σ t over its vertices (brute force),
    /// with a fixed cable (t_min = t_max) and an infinite t_max too (both handed to the
    /// polygon).
    #[test]
    fn l1_at_redundancy_2_matches_the_polygon(case in arb_case(2..=2), variant in 0usize..3, which in 0usize..12) {
        let b = variant_bounds(&case, variant, which);
        let p = TensionProblem::new(&case.w, &case.we, &b);
        let poly = FeasiblePolygon::compute(&p).unwrap();
        for method in [Method::L1, Method::L1Max] {
            let out = solve(method, &p);
            match (&out, &poly) {
                (TensionOutcome::Infeasible(cdpr_tension::Infeasibility::SingularPose { .. }), _) => {}
                (TensionOutcome::Feasible(s), Ok(poly)) => {
                    check(&p, &s.tensions);
                    let sums = poly.tension_vertices.iter().map(|t| t.sum());
                    let best = if method == Method::L1 {
                        sums.fold(f64::INFINITY, f64::min)
                    } else {
                        sums.fold(f64::NEG_INFINITY, f64::max)
                    };
                    let got = s.tensions.sum();
                    prop_assert!(rel_eq(got, best, 1e-9), "{method} {got} against the polygon's {best}");
                }
                // Unbounded polygon (infinite t_max): l1 is bounded below (t ≥ t_min); l1-max
                // must say unbounded as the polygon does.
                (TensionOutcome::Feasible(s), Err(cdpr_tension::Infeasibility::Unbounded { .. })) if method == Method::L1 => {
                    check(&p, &s.tensions);
                    let ip = interior_point(&p, Objective::L1).unwrap();
                    if let Ok(ip) = ip {
                        prop_assert!(rel_eq(s.tensions.sum(), ip.sum(), 1e-6));
                    }
                }
                (TensionOutcome::Infeasible(reason), Err(theirs)) => {
                    if method == Method::L1Max {
                        prop_assert_eq!(reason, theirs);
                    } else {
                        prop_assert_eq!(reason, &cdpr_tension::Infeasibility::NoFeasibleTension);
                    }
                }
                (out, poly) => prop_assert!(false, "{} {:?} against the polygon {:?}", method, out, poly),
            }
        }
    }

    /// Issue 17: the barycentre at r = 2 walks the polygon's edges from the l1 vertex (module
    /// `planar_active_set`) instead of clipping. Same verdict and the same area centroid as
    /// the clipped polygon of `FeasiblePolygon` (up to rounding), with a fixed cable and an
    /// infinite t_max too (both handed to the clipping).
    #[test]
    fn barycenter_walk_matches_the_clipped_polygon(case in arb_case(2..=2), variant in 0usize..3, which in 0usize..12) {
        let b = variant_bounds(&case, variant, which);
        let p = TensionProblem::new(&case.w, &case.we, &b);
        let out = solve(Method::Barycenter, &p);
        match (&out, FeasiblePolygon::compute(&p).unwrap()) {
            (TensionOutcome::Infeasible(cdpr_tension::Infeasibility::SingularPose { .. }), _) => {}
            (TensionOutcome::Feasible(s), Ok(poly)) => {
                check(&p, &s.tensions);
                let c = poly.barycenter();
                let scale = 1f64.max(c.amax());
                prop_assert!((&s.tensions - &c).amax() <= 1e-8 * scale, "{} against {}", s.tensions, c);
            }
            (TensionOutcome::Infeasible(reason), Err(theirs)) => prop_assert_eq!(reason, &theirs),
            (out, poly) => prop_assert!(false, "barycenter {:?} against the polygon {:?}", out, poly),
        }
    }

    /// Issue 13 §7: at r = 1, l1 and l1-max take Algorithm 6.1's path (the same arithmetic as
    /// closed-form, so identical tensions) and reach the optimum of the general LP (Clarabel,
    /// an independent interior-point solver) and of every random feasible point.
    #[test]
    fn l1_at_redundancy_1_is_algorithm_6_1(case in arb_case(1..=1), seed in prop::collection::vec(0.0f64..1.0, 20)) {
        let p = TensionProblem::new(&case.w, &case.we, &case.b);
        let (l1, l1max, cf) = (solve(Method::L1, &p), solve(Method::L1Max, &p), solve(Method::ClosedForm, &p));
        prop_assert_eq!(&l1, &cf);
        let oracle = interior_point(&p, Objective::L1).unwrap();
        prop_assert_eq!(l1.is_feasible(), oracle.is_ok(), "{:?} vs {:?}", l1, oracle);
        prop_assert_eq!(l1max.is_feasible(), oracle.is_ok());
        let Ok(t_ip) = oracle else { return Ok(()) };
        let (a, b) = (l1.tensions().unwrap(), l1max.tensions().unwrap());
        check(&p, a);
        check(&p, b);
        prop_assert!(rel_eq(a.sum(), t_ip.sum(), 1e-7), "{} vs {}", a.sum(), t_ip.sum());
        let t_max = interior_point(&p, Objective::L1Max).unwrap().unwrap();
        prop_assert!(rel_eq(b.sum(), t_max.sum(), 1e-7), "{} vs {}", b.sum(), t_max.sum());
        for q in random_feasible(&p, &seed) {
            let tol = 1e-9 * q.amax().max(1.0) * q.len() as f64;
            prop_assert!(a.sum() <= q.sum() + tol && b.sum() >= q.sum() - tol);
        }
    }
}

/// t1 + t2 + t3 = s with t ∈ [0, 1]³ for s within 2·10⁻⁹ of 3 and of 0, where the feasible
/// set shrinks to a point and the certificate's tolerance (10⁻⁹) exceeds the polygon's: the
/// verdict of `is_feasible` (which may take the point nearest the middle of the bounds) is the
/// verdict of `solve` for every redundancy-2 method.
#[test]
fn is_feasible_matches_solve_beside_a_vertex() {
    let w = DMatrix::from_row_slice(1, 3, &[1.0, 1.0, 1.0]);
    let b = TensionBounds::uniform(3, 0.0, 1.0).unwrap();
    for method in [
        Method::L1,
        Method::L1Max,
        Method::L2,
        Method::L2Max,
        Method::Linf,
        Method::Barycenter,
    ] {
        let mut s = TensionSolver::new(method);
        for k in -200..=200 {
            for centre in [0.0, 3.0] {
                let we = DVector::from_vec(vec![-(centre + 1e-11 * k as f64)]);
                let p = TensionProblem::new(&w, &we, &b);
                let v = s.is_feasible(&p).unwrap();
                assert_eq!(v, s.solve(&p).unwrap().is_feasible(), "{method:?}, k = {k}");
            }
        }
    }
}

proptest! {
    /// `is_feasible_four_6x8` (four null spaces in SIMD lanes; for l2 the central point and its
    /// certificate in lanes too) gives each problem's `is_feasible` verdict, errors included
    /// (NaN or ∞ in W or w_ext), for every method that applies at redundancy 2, on random poses
    /// of an 8-cable spatial robot, with W scaled by up to 10⁶ (residuals beyond the first
    /// residual test of the certificate).
    #[test]
    fn four_at_a_time_verdicts_equal_is_feasible(
        poses in prop::collection::vec(
            (-1.0f64..1.0, -1.0f64..1.0, 0.0f64..2.0, -0.3f64..0.3, -0.3f64..0.3, -0.3f64..0.3),
            4,
        ),
        wanted in prop::collection::vec(prop::bool::weighted(0.9), 4),
        load in prop::collection::vec(-300.0f64..300.0, 6),
        lo in 0.0f64..50.0,
        span in 10.0f64..2000.0,
        poison in 0usize..6,
        kind in 0usize..4,
        scale in prop::collection::vec(prop_oneof![3 => Just(0i32), 1 => 0i32..7], 4),
    ) {
        let robot = cdpr_kinematics::reference_robots::ipanema_like_8();
        let mut columns = [[[0.0; 4]; 6]; 8];
        let mut matrices = Vec::new();
        for (l, &(x, y, z, a, b, c)) in poses.iter().enumerate() {
            let pose = Pose::spatial(nalgebra::Vector3::new(x, y, z), a, b, c);
            let mut w = robot.inverse_kinematics(&pose).unwrap().wrench_matrix();
            w *= 10f64.powi(scale[l]);
            if l == poison {
                w[(2, 5)] = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 1.0][kind];
            }
            for j in 0..8 {
                for i in 0..6 {
                    columns[j][i][l] = w[(i, j)];
                }
            }
            matrices.push(w);
        }
        let mut we = DVector::from_vec(load);
        if kind == 3 && poison == 5 {
            we[1] = f64::INFINITY;
        }
        let b = TensionBounds::uniform(8, lo, lo + span).unwrap();
        let wanted: [bool; 4] = std::array::from_fn(|l| wanted[l]);
        let mut scratch = DMatrix::zeros(1, 1);
        for method in [Method::L1, Method::L1Max, Method::L2, Method::L2Max, Method::Linf, Method::Barycenter] {
            let mut four = TensionSolver::new(method);
            let mut one = TensionSolver::new(method);
            let got = four.is_feasible_four_6x8(&columns, wanted, &we, &b, &mut scratch);
            for l in 0..4 {
                let expected = if wanted[l] {
                    one.is_feasible(&TensionProblem::new(&matrices[l], &we, &b))
                } else {
                    Ok(false)
                };
                prop_assert_eq!(format!("{:?}", got[l]), format!("{expected:?}"), "{} lane {}", method, l);
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// One l2 solver reused along lines of poses, four at a time, as a workspace grid uses it:
    /// its memory of the last separating triple and wrench-space direction (tried on the next
    /// poses before their null spaces) never changes a verdict. Each verdict equals a fresh
    /// solver's `is_feasible` and `solve`; the lines cross feasible and infeasible regions.
    #[test]
    #[allow(clippy::needless_range_loop)]
    fn a_reused_solver_along_grid_lines_keeps_every_verdict(
        start in (-1.2f64..1.2, -1.2f64..1.2, -0.2f64..2.2),
        step in (-0.1f64..0.1, -0.1f64..0.1, -0.1f64..0.1),
        tilt in (-0.3f64..0.3, -0.3f64..0.3, -0.3f64..0.3),
        mass in 1.0f64..40.0,
        lo in 0.5f64..50.0,
        span in 200.0f64..1500.0,
    ) {
        let robot = cdpr_kinematics::reference_robots::ipanema_like_8();
        let we = DVector::from_vec(vec![0.0, 0.0, -9.80665 * mass, 0.0, 0.0, 0.0]);
        let b = TensionBounds::uniform(8, lo, lo + span).unwrap();
        let mut four = TensionSolver::new(Method::L2);
        let mut scratch = DMatrix::zeros(1, 1);
        for group in 0..24 {
            let (columns, matrices) = four_along_a_line(&robot, start, step, tilt, group);
            let got = four.is_feasible_four_6x8(&columns, [true; 4], &we, &b, &mut scratch);
            for l in 0..4 {
                let p = TensionProblem::new(&matrices[l], &we, &b);
                let expected = TensionSolver::new(Method::L2).is_feasible(&p).unwrap();
                prop_assert_eq!(*got[l].as_ref().unwrap(), expected, "group {} lane {}", group, l);
                prop_assert_eq!(expected, solve(Method::L2, &p).is_feasible());
            }
        }
    }
}

/// The workspace grid of the issue-17 bench (25³ poses over the frame of the 8-cable robot,
/// 10 kg, bounds [1, 1000] N), in grid order, four poses at a time through one l2 solver:
/// every verdict is a fresh solver's `is_feasible`, and the grid has both verdicts in numbers
/// (11 004 feasible poses, as the bench reports), so the solver's memory of separating
/// triples and directions is exercised.
#[test]
fn the_bench_grid_through_one_solver_keeps_every_verdict() {
    let robot = cdpr_kinematics::reference_robots::ipanema_like_8();
    let (lo, hi) = robot.frame_bounding_box();
    let we = DVector::from_vec(vec![0.0, 0.0, -9.80665 * 10.0, 0.0, 0.0, 0.0]);
    let b = TensionBounds::uniform(8, 1.0, 1000.0).unwrap();
    let mut four = TensionSolver::new(Method::L2);
    let mut scratch = DMatrix::zeros(1, 1);
    // `Grid::coordinate` (x fastest, as the grid visits its points).
    let at = |i: usize, a: f64, b: f64| {
        if i == 24 {
            b
        } else {
            a + (i as f64 / 24.0) * (b - a)
        }
    };
    let points: Vec<nalgebra::Vector3<f64>> = (0..25usize.pow(3))
        .map(|f| {
            let (i, j, k) = (f % 25, f / 25 % 25, f / 625);
            nalgebra::Vector3::new(at(i, lo.x, hi.x), at(j, lo.y, hi.y), at(k, lo.z, hi.z))
        })
        .collect();
    let mut feasible = 0;
    for group in points.chunks(4) {
        let mut columns = [[[0.0; 4]; 6]; 8];
        let mut matrices = Vec::new();
        for (l, p) in group.iter().enumerate() {
            let pose = Pose::spatial(*p, 0.0, 0.0, 0.0);
            let w = robot.inverse_kinematics(&pose).unwrap().wrench_matrix();
            for j in 0..8 {
                for i in 0..6 {
                    columns[j][i][l] = w[(i, j)];
                }
            }
            matrices.push(w);
        }
        let wanted: [bool; 4] = std::array::from_fn(|l| l < group.len());
        let got = four.is_feasible_four_6x8(&columns, wanted, &we, &b, &mut scratch);
        for (l, w) in matrices.iter().enumerate() {
            let p = TensionProblem::new(w, &we, &b);
            let expected = TensionSolver::new(Method::L2).is_feasible(&p).unwrap();
            assert_eq!(*got[l].as_ref().unwrap(), expected, "pose {:?}", group[l]);
            feasible += usize::from(expected);
        }
    }
    assert_eq!(feasible, 11_004);
}

proptest! {
    /// Along a straight path of an 8-cable spatial robot, four poses at a time through ONE
    /// solver (l2: the warm candidate of the previous verdicts is tried where the central point
    /// fails), every verdict is `solve`'s, and it does not depend on the solver's history: a
    /// fresh solver, and one warmed on an unrelated path, give the same verdicts group by
    /// group.
    #[test]
    #[allow(clippy::needless_range_loop)]
    fn warm_verdicts_equal_solve_along_a_path(
        start in (-1.0f64..1.0, -1.0f64..1.0, 0.0f64..2.0),
        step in (-0.08f64..0.08, -0.08f64..0.08, -0.08f64..0.08),
        other in (-1.0f64..1.0, -1.0f64..1.0, 0.0f64..2.0),
        mass in 1.0f64..40.0,
        lo in 0.5f64..20.0,
        span in 200.0f64..2000.0,
    ) {
        let robot = cdpr_kinematics::reference_robots::ipanema_like_8();
        let we = DVector::from_vec(vec![0.0, 0.0, -9.81 * mass, 0.0, 0.0, 0.0]);
        let b = TensionBounds::uniform(8, lo, lo + span).unwrap();
        let flat = (0.0, 0.0, 0.0);
        let lanes = |origin, group| four_along_a_line(&robot, origin, step, flat, group);
        let mut scratch = DMatrix::zeros(1, 1);
        let mut path = TensionSolver::new(Method::L2);
        let mut warmed = TensionSolver::new(Method::L2);
        for group in 0..8 {
            let (columns, _) = lanes(other, group);
            let _ = warmed.is_feasible_four_6x8(&columns, [true; 4], &we, &b, &mut scratch);
        }
        let mut one = TensionSolver::new(Method::L2);
        for group in 0..8 {
            let (columns, matrices) = lanes(start, group);
            let got = path.is_feasible_four_6x8(&columns, [true; 4], &we, &b, &mut scratch);
            let fresh = TensionSolver::new(Method::L2)
                .is_feasible_four_6x8(&columns, [true; 4], &we, &b, &mut scratch);
            let after = warmed.is_feasible_four_6x8(&columns, [true; 4], &we, &b, &mut scratch);
            for l in 0..4 {
                let expected = one.solve(&TensionProblem::new(&matrices[l], &we, &b)).unwrap().is_feasible();
                prop_assert_eq!(got[l].as_ref().ok(), Some(&expected), "group {} lane {}", group, l);
                prop_assert_eq!(fresh[l].as_ref().ok(), Some(&expected), "group {} lane {}", group, l);
                prop_assert_eq!(after[l].as_ref().ok(), Some(&expected), "group {} lane {}", group, l);
            }
        }
    }
}

/// The wrench matrices of the poses start + k·step, k = 4·group … 4·group + 3, at the
/// orientation `tilt` (XYZ angles, rad) of `robot` (6 × 8), in lanes (`columns[j][i][l]`) and
/// one by one: four neighbours of a grid line.
#[allow(clippy::needless_range_loop)]
fn four_along_a_line(
    robot: &cdpr_kinematics::Robot,
    start: (f64, f64, f64),
    step: (f64, f64, f64),
    tilt: (f64, f64, f64),
    group: usize,
) -> ([[[f64; 4]; 6]; 8], Vec<DMatrix<f64>>) {
    let mut columns = [[[0.0; 4]; 6]; 8];
    let mut matrices = Vec::new();
    for l in 0..4 {
        let k = (4 * group + l) as f64;
        let centre = nalgebra::Vector3::new(
            start.0 + k * step.0,
            start.1 + k * step.1,
            start.2 + k * step.2,
        );
        let pose = Pose::spatial(centre, tilt.0, tilt.1, tilt.2);
        let w = robot.inverse_kinematics(&pose).unwrap().wrench_matrix();
        for j in 0..8 {
            for i in 0..6 {
                columns[j][i][l] = w[(i, j)];
            }
        }
        matrices.push(w);
    }
    (columns, matrices)
}
