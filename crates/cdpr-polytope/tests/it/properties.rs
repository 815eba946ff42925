//! Property tests: Krut's method vs hyperplane shifting, the index vs independent LPs solved by
//! Clarabel, invariances, monotonicity, vertices, capacity margin, inscribed ellipse.

use cdpr_kinematics::strategies::{arb_pose, arb_robot, arb_robot_and_pose};
use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};
use cdpr_polytope::{
    AvailableWrenchSet, CapacityMargin, CapacityMarginEvaluator, Facet, PolytopeError,
    RequiredWrenchSet, capacity_margin, hyperplane_shifting, isotropic_force, isotropic_force_of,
    isotropic_wrench_radius, krut_vertex_projection, largest_inscribed_ellipse, limiting_facet,
};
use cdpr_tension::TensionBounds;
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, SolverStatus, SupportedConeT,
};
use nalgebra::{DMatrix, DVector, Rotation3, Vector2, Vector3};
use proptest::prelude::*;

/// Per-cable bounds: t_min ∈ [0, 20], t_max − t_min ∈ [1, 200].
fn arb_bounds(n: usize) -> impl Strategy<Value = TensionBounds> {
    (
        prop::collection::vec(0.0f64..20.0, n),
        prop::collection::vec(1.0f64..200.0, n),
    )
        .prop_map(|(lo, width)| {
            let hi = lo.iter().zip(&width).map(|(a, b)| a + b).collect();
            TensionBounds::new(lo, hi).unwrap()
        })
}

fn arb_case(
    extra: std::ops::RangeInclusive<usize>,
) -> impl Strategy<Value = (Robot, Pose, TensionBounds)> {
    arb_robot_and_pose(extra).prop_flat_map(|(r, p)| {
        let n = r.cable_count();
        (Just(r), Just(p), arb_bounds(n))
    })
}

fn wrench(robot: &Robot, pose: &Pose) -> DMatrix<f64> {
    robot.inverse_kinematics(pose).unwrap().wrench_matrix()
}

/// Condition number of W (σ_max / σ_min).
fn condition(w: &DMatrix<f64>) -> f64 {
    let s = w.singular_values();
    s.max() / s.min()
}

/// Independent check: max α such that W t = α d with t_min ≤ t ≤ t_max (Clarabel LP);
/// `None` if infeasible (the origin is not in the set along this line).
fn lp_ray(w: &DMatrix<f64>, b: &TensionBounds, d: &DVector<f64>) -> Option<f64> {
    let (m, n) = w.shape();
    let (mut ri, mut ci, mut v) = (vec![], vec![], vec![]);
    for i in 0..m {
        for j in 0..n {
            ri.push(i);
            ci.push(j);
            v.push(w[(i, j)]);
        }
        ri.push(i);
        ci.push(n);
        v.push(-d[i]);
    }
    let mut rhs = vec![0.0; m];
    for j in 0..n {
        ri.push(m + j);
        ci.push(j);
        v.push(1.0);
        rhs.push(b.max()[j]);
    }
    for j in 0..n {
        ri.push(m + n + j);
        ci.push(j);
        v.push(-1.0);
        rhs.push(-b.min()[j]);
    }
    let a = CscMatrix::new_from_triplets(m + 2 * n, n + 1, ri, ci, v);
    let p = CscMatrix::zeros((n + 1, n + 1));
    let mut q = vec![0.0; n + 1];
    q[n] = -1.0;
    let cones = [
        SupportedConeT::ZeroConeT(m),
        SupportedConeT::NonnegativeConeT(2 * n),
    ];
    let settings = DefaultSettingsBuilder::default()
        .verbose(false)
        .tol_gap_abs(1e-10)
        .tol_gap_rel(1e-10)
        .tol_feas(1e-10)
        .build()
        .unwrap();
    let mut s = DefaultSolver::new(&p, &q, &a, &rhs, &cones, settings).unwrap();
    s.solve();
    match s.solution.status {
        SolverStatus::Solved | SolverStatus::AlmostSolved => Some(s.solution.x[n]),
        SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => None,
        other => panic!("LP status {other:?}"),
    }
}

/// Unit vector from an angle pair (3-D) or angle (2-D), padded with zeros to `dim` (the moment
/// part for the zero-moment slice).
fn direction(force_dim: usize, dim: usize, theta: f64, z: f64) -> DVector<f64> {
    let mut d = DVector::zeros(dim);
    if force_dim == 2 {
        d[0] = theta.cos();
        d[1] = theta.sin();
    } else {
        let r = (1.0 - z * z).sqrt();
        d[0] = r * theta.cos();
        d[1] = r * theta.sin();
        d[2] = z;
    }
    d
}

/// Facets of `a` and `b` coincide (same unit normals, same offsets up to `tol`).
fn same_facets(a: &AvailableWrenchSet, b: &AvailableWrenchSet, tol: f64) -> Result<(), String> {
    for (x, y) in [(a, b), (b, a)] {
        for f in x.facets() {
            let g = y
                .facets()
                .iter()
                .find(|g| (&g.normal - &f.normal).amax() < 1e-6)
                .ok_or_else(|| format!("facet {:?} missing", f.normal.as_slice()))?;
            if (g.offset - f.offset).abs() > tol {
                return Err(format!("offsets {} vs {}", f.offset, g.offset));
            }
        }
    }
    Ok(())
}

fn rotate_robot(robot: &Robot, pose: &Pose, r: &Rotation3<f64>) -> (Robot, Pose) {
    let cables = robot
        .cables()
        .iter()
        .map(|c| Cable {
            frame: r * c.frame,
            platform: c.platform,
            pulley: None,
        })
        .collect();
    (
        Robot::new(robot.motion(), cables).unwrap(),
        Pose::new(r * pose.position, r * pose.rotation),
    )
}

proptest! {
    // Case count from PROPTEST_CASES (64 in CI); poses where the origin is outside are rejected
    // by the LP comparisons, hence the generous reject budget.
    #![proptest_config(ProptestConfig { max_global_rejects: 100_000, ..ProptestConfig::default() })]

    /// Krut's steps 1–6 and hyperplane shifting give the same facets (DOF 2 and 3, n ≤ 6).
    #[test]
    fn krut_equals_hyperplane_shifting(
        (robot, pose, b) in prop_oneof![
            arb_robot(MotionPattern::Point2, 2..=6).prop_flat_map(|r| (Just(r), arb_pose(MotionPattern::Point2))),
            arb_robot(MotionPattern::Planar, 3..=6).prop_flat_map(|r| (Just(r), arb_pose(MotionPattern::Planar))),
            arb_robot(MotionPattern::Point3, 3..=6).prop_flat_map(|r| (Just(r), arb_pose(MotionPattern::Point3))),
        ].prop_flat_map(|(r, p)| { let n = r.cable_count(); (Just(r), Just(p), arb_bounds(n)) })
    ) {
        let w = wrench(&robot, &pose);
        prop_assume!(condition(&w) < 1e6);
        let krut = krut_vertex_projection::available_wrench_set(&w, &b).unwrap();
        let hs = hyperplane_shifting::available_wrench_set(&w, &b).unwrap();
        let scale = b.max().max();
        prop_assert_eq!(krut.facets().len(), hs.facets().len());
        if let Err(e) = same_facets(&krut, &hs, 1e-7 * scale) {
            return Err(TestCaseError::fail(e));
        }
        prop_assert_eq!(krut.vertices().map(|v| v.len()), hs.vertices().map(|v| v.len()));
    }

    /// The force index equals the minimum over directions d of the LP "largest force along d
    /// that the cables can produce at zero moment" (random directions and each facet's force
    /// direction, where the minimum is attained); a negative index means W t = 0 is infeasible.
    #[test]
    fn index_equals_min_of_directional_lps(
        (robot, pose, b) in arb_case(0..=3),
        dirs in prop::collection::vec((0.0..std::f64::consts::TAU, -1.0f64..1.0), 12),
    ) {
        let w = wrench(&robot, &pose);
        prop_assume!(condition(&w) < 1e6);
        let motion = robot.motion();
        let aws = hyperplane_shifting::available_wrench_set(&w, &b).unwrap();
        let index = isotropic_force(&aws, motion).unwrap();
        prop_assert!((index - isotropic_force_of(motion, &w, &b).unwrap()).abs() <= 1e-9 * b.max().max());
        let scale = b.max().max() * robot.cable_count() as f64;
        let fd = motion.translation_dof();
        let dim = motion.dof();
        if index > 1e-6 * scale {
            let mut min_ray = f64::INFINITY;
            for &(t, z) in &dirs {
                let ray = lp_ray(&w, &b, &direction(fd, dim, t, z)).expect("origin inside");
                prop_assert!(ray >= index - 1e-6 * scale, "ray {} < index {}", ray, index);
                min_ray = min_ray.min(ray);
            }
            for f in aws.facets() {
                let nf = f.normal.rows(0, fd).norm();
                if nf > 1e-9 {
                    let mut d = DVector::zeros(dim);
                    d.rows_mut(0, fd).copy_from(&(f.normal.rows(0, fd) / nf));
                    let ray = lp_ray(&w, &b, &d).expect("origin inside");
                    prop_assert!(ray >= index - 1e-6 * scale);
                    min_ray = min_ray.min(ray);
                }
            }
            prop_assert!((min_ray - index).abs() <= 1e-6 * scale, "min ray {} vs index {}", min_ray, index);
        } else if index < -1e-6 * scale {
            // The origin is outside the zero-moment slice: no admissible t with W t = 0.
            prop_assert!(!reachable(&w, &b, &DVector::zeros(dim)));
        }
    }

    /// The same for the ball in the full wrench space: min over facet normals and random
    /// wrench directions of the LP ray.
    #[test]
    fn wrench_radius_equals_min_of_directional_lps(
        (robot, pose, b) in arb_case(0..=2),
        dirs in prop::collection::vec(prop::collection::vec(-1.0f64..1.0, 6), 8),
    ) {
        let w = wrench(&robot, &pose);
        prop_assume!(condition(&w) < 1e6);
        let aws = hyperplane_shifting::available_wrench_set(&w, &b).unwrap();
        let radius = isotropic_wrench_radius(&aws);
        let scale = b.max().max() * robot.cable_count() as f64;
        prop_assume!(radius > 1e-6 * scale);
        let dim = robot.dof();
        let mut min_ray = f64::INFINITY;
        let mut check = |d: DVector<f64>| -> Result<(), TestCaseError> {
            let ray = lp_ray(&w, &b, &d).expect("origin inside");
            prop_assert!(ray >= radius - 1e-6 * scale);
            min_ray = min_ray.min(ray);
            Ok(())
        };
        for v in &dirs {
            let d = DVector::from_column_slice(&v[..dim]);
            if d.norm() > 1e-3 {
                check(d.normalize())?;
            }
        }
        for f in aws.facets() {
            check(f.normal.clone())?;
        }
        prop_assert!((min_ray - radius).abs() <= 1e-6 * scale);
    }

    /// Rotating the whole robot (frame anchors and pose) leaves every index unchanged.
    #[test]
    fn indices_are_invariant_under_rotation(
        (robot, pose, b) in arb_case(0..=3),
        angles in (0.0..std::f64::consts::TAU, -1.0f64..1.0, 0.0..std::f64::consts::TAU),
    ) {
        let w = wrench(&robot, &pose);
        prop_assume!(condition(&w) < 1e6);
        let rot = if robot.motion().space_dim() == 2 {
            Rotation3::from_axis_angle(&Vector3::z_axis(), angles.0)
        } else {
            Rotation3::from_euler_angles(angles.0, angles.1.asin(), angles.2)
        };
        let (r2, p2) = rotate_robot(&robot, &pose, &rot);
        let w2 = wrench(&r2, &p2);
        let m = robot.motion();
        let scale = 1e-8 * b.max().max() * robot.cable_count() as f64;
        let f1 = isotropic_force_of(m, &w, &b).unwrap();
        let f2 = isotropic_force_of(m, &w2, &b).unwrap();
        prop_assert!((f1 - f2).abs() <= scale, "{} vs {}", f1, f2);
        let a1 = hyperplane_shifting::available_wrench_set(&w, &b).unwrap();
        let a2 = hyperplane_shifting::available_wrench_set(&w2, &b).unwrap();
        prop_assert!((isotropic_wrench_radius(&a1) - isotropic_wrench_radius(&a2)).abs() <= scale);
        prop_assert_eq!(a1.facets().len(), a2.facets().len());
    }

    /// Raising t_max never lowers the index nor the capacity margin of a fixed load.
    #[test]
    fn index_grows_with_t_max(
        (robot, pose, b) in arb_case(0..=3),
        raise in prop::collection::vec(0.0f64..100.0, 9),
        load in prop::collection::vec(-50.0f64..50.0, 6),
    ) {
        let w = wrench(&robot, &pose);
        prop_assume!(condition(&w) < 1e6);
        let n = robot.cable_count();
        let b2 = TensionBounds::new(
            b.min().as_slice().to_vec(),
            b.max().iter().zip(&raise).map(|(x, r)| x + r).collect(),
        ).unwrap();
        let m = robot.motion();
        let tol = 1e-9 * b2.max().max() * n as f64;
        prop_assert!(isotropic_force_of(m, &w, &b2).unwrap() >= isotropic_force_of(m, &w, &b).unwrap() - tol);
        let req = RequiredWrenchSet::point(DVector::from_column_slice(&load[..m.dof()])).unwrap();
        let mut cm = CapacityMargin::new(m.dof(), n);
        prop_assert!(cm.margin(&w, &b2, &req).unwrap() >= cm.margin(&w, &b, &req).unwrap() - tol);
    }

    /// Every AWS vertex satisfies every facet, is the image of a box corner, and every box
    /// corner's image is inside (DOF 2 and 3).
    #[test]
    fn vertices_satisfy_every_facet(
        (robot, pose, b) in prop_oneof![
            arb_robot(MotionPattern::Point2, 2..=6).prop_flat_map(|r| (Just(r), arb_pose(MotionPattern::Point2))),
            arb_robot(MotionPattern::Planar, 3..=6).prop_flat_map(|r| (Just(r), arb_pose(MotionPattern::Planar))),
            arb_robot(MotionPattern::Point3, 3..=6).prop_flat_map(|r| (Just(r), arb_pose(MotionPattern::Point3))),
        ].prop_flat_map(|(r, p)| { let n = r.cable_count(); (Just(r), Just(p), arb_bounds(n)) })
    ) {
        let w = wrench(&robot, &pose);
        prop_assume!(condition(&w) < 1e6);
        let n = robot.cable_count();
        let aws = hyperplane_shifting::available_wrench_set(&w, &b).unwrap();
        let tol = 1e-8 * b.max().max() * n as f64;
        let corners: Vec<DVector<f64>> = (0..1usize << n)
            .map(|bits| {
                let t = DVector::from_fn(n, |j, _| if (bits >> j) & 1 == 1 { b.max()[j] } else { b.min()[j] });
                &w * t
            })
            .collect();
        for c in &corners {
            prop_assert!(aws.violation(c) <= tol);
        }
        let vertices = aws.vertices().unwrap();
        prop_assert!(vertices.len() > robot.dof());
        for v in vertices {
            for f in aws.facets() {
                prop_assert!(f.normal.dot(v) <= f.offset + tol);
            }
            let nearest = corners.iter().map(|c| (c - v).norm()).fold(f64::INFINITY, f64::min);
            prop_assert!(nearest <= tol, "vertex {:?} is {} from every corner", v.as_slice(), nearest);
        }
    }

    /// Krut's candidate listing (Krut, Company & Pierrot 2004, Fig. 8) against brute force over the 2ⁿ corner
    /// images W τ: C(2ⁿ, DOF) candidates; each hyperplane passes through its vertices' images;
    /// each border has every image inside and is a facet found by hyperplane shifting, any other
    /// hyperplane is not; the borders are exactly `available_wrench_set`'s supporting
    /// half-spaces (DOF 2 with n ≤ 6, DOF 3 with n ≤ 5).
    #[test]
    fn candidate_hyperplanes_against_brute_force(
        (robot, pose, b) in prop_oneof![
            arb_robot(MotionPattern::Point2, 2..=6).prop_flat_map(|r| (Just(r), arb_pose(MotionPattern::Point2))),
            arb_robot(MotionPattern::Point3, 3..=5).prop_flat_map(|r| (Just(r), arb_pose(MotionPattern::Point3))),
        ].prop_flat_map(|(r, p)| { let n = r.cable_count(); (Just(r), Just(p), arb_bounds(n)) })
    ) {
        let w = wrench(&robot, &pose);
        prop_assume!(condition(&w) < 1e6);
        let (dof, n) = w.shape();
        let candidates = krut_vertex_projection::candidate_hyperplanes(&w, &b).unwrap();
        let binomial = (0..dof).fold(1.0, |c, k| c * ((1usize << n) - k) as f64 / (k + 1) as f64);
        prop_assert_eq!(candidates.len() as f64, binomial);
        let tol = 1e-8 * b.max().max() * n as f64;
        let image = |bits: usize| {
            &w * DVector::from_fn(n, |j, _| if (bits >> j) & 1 == 1 { b.max()[j] } else { b.min()[j] })
        };
        let images: Vec<DVector<f64>> = (0..1usize << n).map(image).collect();
        let hs = hyperplane_shifting::available_wrench_set(&w, &b).unwrap();
        let is_facet = |f: &Facet| {
            hs.facets().iter().any(|g| (&g.normal - &f.normal).amax() < 1e-6 && (g.offset - f.offset).abs() <= tol)
        };
        let mut borders = Vec::new();
        for c in &candidates {
            prop_assert_eq!(c.vertices.len(), dof);
            let Some(f) = &c.hyperplane else {
                prop_assert!(!c.border);
                continue;
            };
            prop_assert!((f.normal.norm() - 1.0).abs() < 1e-12);
            for &v in &c.vertices {
                prop_assert!((f.normal.dot(&images[v]) - f.offset).abs() <= tol, "{:?}", c);
            }
            prop_assert_eq!(is_facet(f), c.border, "{:?}", c);
            if c.border {
                for x in &images {
                    prop_assert!(f.normal.dot(x) <= f.offset + tol);
                }
                borders.push(f.clone());
            }
        }
        let lexicographic = |a: &Facet, b: &Facet| {
            a.normal.iter().zip(b.normal.iter()).map(|(x, y)| x.total_cmp(y)).find(|o| o.is_ne())
                .unwrap_or(std::cmp::Ordering::Equal).then(a.offset.total_cmp(&b.offset))
        };
        borders.sort_by(lexicographic);
        let krut = krut_vertex_projection::available_wrench_set(&w, &b).unwrap();
        prop_assert_eq!(&borders[..], krut.supporting_halfspaces());
    }

    /// Capacity margin: a ball of radius 0 at the origin gives the wrench isotropy radius; a
    /// ball of radius ρ gives the point margin − ρ; for a box, margin > 0 iff every corner of
    /// the box is balanceable (checked by LP), and the fast evaluator agrees with the AWS one.
    #[test]
    fn capacity_margin_properties(
        (robot, pose, b) in arb_case(0..=3),
        centre in prop::collection::vec(-40.0f64..40.0, 6),
        half in prop::collection::vec(0.0f64..30.0, 6),
        rho in 0.0f64..20.0,
    ) {
        let w = wrench(&robot, &pose);
        prop_assume!(condition(&w) < 1e6);
        let (dof, n) = w.shape();
        let aws = hyperplane_shifting::available_wrench_set(&w, &b).unwrap();
        let tol = 1e-9 * b.max().max() * n as f64;
        let zero = RequiredWrenchSet::ball(DVector::zeros(dof), 0.0).unwrap();
        prop_assert!((capacity_margin(&aws, &zero).unwrap() - isotropic_wrench_radius(&aws)).abs() <= tol);
        let c = DVector::from_column_slice(&centre[..dof]);
        let point = RequiredWrenchSet::point(c.clone()).unwrap();
        let ball = RequiredWrenchSet::ball(c.clone(), rho).unwrap();
        prop_assert!((capacity_margin(&aws, &ball).unwrap() - (capacity_margin(&aws, &point).unwrap() - rho)).abs() <= tol);
        let h = DVector::from_column_slice(&half[..dof]);
        let bx = RequiredWrenchSet::boxed(c.clone(), h.clone()).unwrap();
        let margin = capacity_margin(&aws, &bx).unwrap();
        let mut cm = CapacityMargin::new(dof, n);
        prop_assert!((cm.margin(&w, &b, &bx).unwrap() - margin).abs() <= tol);
        let ev = CapacityMarginEvaluator::new(&b, &bx).unwrap();
        prop_assert!((ev.margin(&w).unwrap() - margin).abs() <= tol);
        // The limiting facet's own slack d_k − max_{w ∈ box} (−n_k · w), recomputed here.
        let (k, lim) = limiting_facet(&aws, &bx).unwrap().unwrap();
        let fk = &aws.facets()[k];
        let slack = fk.offset + fk.normal.dot(&c) - fk.normal.abs().dot(&h);
        prop_assert!((slack - margin).abs() <= tol && (lim - margin).abs() <= tol);
        let big = 1e-6 * b.max().max() * n as f64;
        if margin.abs() > big {
            // All 2^dof corners of the box of external wrenches: balanced iff −w_ext ∈ {W t}.
            let mut all = true;
            for bits in 0..1usize << dof {
                let w_ext = DVector::from_fn(dof, |i, _| c[i] + if (bits >> i) & 1 == 1 { h[i] } else { -h[i] });
                all &= reachable(&w, &b, &(-w_ext));
            }
            prop_assert_eq!(all, margin > 0.0, "margin {}", margin);
        }
    }

    /// The inscribed ellipse (Clarabel SOCP) is inside the AWS and as large as the best ellipse
    /// of a brute-force search over orientations (exact for each orientation).
    #[test]
    fn ellipse_beats_brute_force(
        robot in arb_robot(MotionPattern::Point2, 3..=6),
        pose in arb_pose(MotionPattern::Point2),
    ) {
        let n = robot.cable_count();
        let w = wrench(&robot, &pose);
        prop_assume!(condition(&w) < 1e6);
        let b = TensionBounds::uniform(n, 1.0, 100.0).unwrap();
        let aws = hyperplane_shifting::available_wrench_set(&w, &b).unwrap();
        prop_assume!(isotropic_force(&aws, MotionPattern::Point2).unwrap() > 1e-3);
        let e = largest_inscribed_ellipse(&aws).unwrap().unwrap();
        for f in aws.facets() {
            prop_assert!(e.support(&Vector2::new(f.normal[0], f.normal[1])) <= f.offset * (1.0 + 1e-9));
        }
        // Brute force over the orientation θ of the axes. For fixed θ, with m_k = Rᵀ n_k, the
        // constraints read x m_k1² + y m_k2² ≤ d_k² in (x, y) = (semi-axes)², linear, and
        // area = π √(xy): the maximum of xy over that polygon is at a vertex or at the middle
        // of an edge (x = d²/(2a), y = d²/(2b)), enumerated exactly.
        let facets: Vec<(Vector2<f64>, f64)> = aws.facets().iter()
            .map(|f| (Vector2::new(f.normal[0], f.normal[1]), f.offset)).collect();
        let area_at = |th: f64| -> f64 {
            let lin: Vec<(f64, f64, f64)> = facets.iter().map(|(nk, d)| {
                let m1 = nk[0] * th.cos() + nk[1] * th.sin();
                let m2 = -nk[0] * th.sin() + nk[1] * th.cos();
                (m1 * m1, m2 * m2, d * d)
            }).collect();
            let feasible = |x: f64, y: f64| x >= 0.0 && y >= 0.0
                && lin.iter().all(|(a, b, c)| a * x + b * y <= c * (1.0 + 1e-12));
            let mut best = 0.0f64;
            for (k, &(a, b, c)) in lin.iter().enumerate() {
                if a > 0.0 && b > 0.0 && feasible(c / (2.0 * a), c / (2.0 * b)) {
                    best = best.max(c * c / (4.0 * a * b));
                }
                for &(a2, b2, c2) in &lin[k + 1..] {
                    let det = a * b2 - a2 * b;
                    if det.abs() > 1e-14 {
                        let (x, y) = ((c * b2 - c2 * b) / det, (a * c2 - a2 * c) / det);
                        if feasible(x, y) { best = best.max(x * y); }
                    }
                }
            }
            std::f64::consts::PI * best.sqrt()
        };
        let steps = 3600;
        let h = std::f64::consts::PI / steps as f64;
        let (mut best, mut bt) = (0.0f64, 0.0);
        for i in 0..steps {
            let a = area_at(i as f64 * h);
            if a > best { (best, bt) = (a, i as f64 * h); }
        }
        // Golden-section refinement around the best grid angle.
        let (mut lo, mut hi) = (bt - h, bt + h);
        let g = (5f64.sqrt() - 1.0) / 2.0;
        for _ in 0..60 {
            let (m1, m2) = (hi - g * (hi - lo), lo + g * (hi - lo));
            if area_at(m1) > area_at(m2) { hi = m2 } else { lo = m1 }
        }
        best = best.max(area_at(0.5 * (lo + hi)));
        // The solver's ellipse touches the polygon (its scale is maximal for its shape) and the
        // exact-per-angle search does not beat it by more than the solver's tolerance.
        let own = area_at(e.angle);
        prop_assert!(own >= e.area() * (1.0 - 1e-6), "{} vs {}", own, e.area());
        prop_assert!(e.area() >= best * (1.0 - 1e-6) && e.area() <= best * (1.0 + 1e-6),
            "solver {} vs brute force {}", e.area(), best);
    }
}

/// Whether `target` = W t for some t_min ≤ t ≤ t_max (Clarabel feasibility LP).
fn reachable(w: &DMatrix<f64>, b: &TensionBounds, target: &DVector<f64>) -> bool {
    let (m, n) = w.shape();
    let (mut ri, mut ci, mut v) = (vec![], vec![], vec![]);
    for i in 0..m {
        for j in 0..n {
            ri.push(i);
            ci.push(j);
            v.push(w[(i, j)]);
        }
    }
    let mut rhs: Vec<f64> = target.iter().copied().collect();
    for j in 0..n {
        ri.push(m + j);
        ci.push(j);
        v.push(1.0);
        rhs.push(b.max()[j]);
        ri.push(m + n + j);
        ci.push(j);
        v.push(-1.0);
    }
    rhs.extend(b.min().iter().map(|x| -x));
    let a = CscMatrix::new_from_triplets(m + 2 * n, n, ri, ci, v);
    let p = CscMatrix::zeros((n, n));
    let q = vec![0.0; n];
    let cones = [
        SupportedConeT::ZeroConeT(m),
        SupportedConeT::NonnegativeConeT(2 * n),
    ];
    let settings = DefaultSettingsBuilder::default()
        .verbose(false)
        .build()
        .unwrap();
    let mut s = DefaultSolver::new(&p, &q, &a, &rhs, &cones, settings).unwrap();
    s.solve();
    match s.solution.status {
        SolverStatus::Solved | SolverStatus::AlmostSolved => true,
        SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => false,
        other => panic!("LP status {other:?}"),
    }
}

#[test]
fn rank_deficient_poses_are_reported_not_crashed_on() {
    // Spatial robot whose cables all pass through one line: W has rank < 6.
    let cables = (0..8)
        .map(|i| Cable {
            frame: Vector3::new(if i % 2 == 0 { 2.0 } else { -2.0 }, 0.0, 0.0),
            platform: Vector3::zeros(),
            pulley: None,
        })
        .collect();
    let robot = Robot::new(MotionPattern::Spatial, cables).unwrap();
    let w = wrench(&robot, &Pose::point(0.0, 0.0, 0.0));
    let b = TensionBounds::uniform(8, 1.0, 10.0).unwrap();
    assert!(matches!(
        hyperplane_shifting::available_wrench_set(&w, &b),
        Err(PolytopeError::LowerDimensional { rank: 1, dof: 6 })
    ));
    let req = RequiredWrenchSet::point(DVector::zeros(6)).unwrap();
    assert!(matches!(
        CapacityMargin::new(6, 8).margin(&w, &b, &req),
        Err(PolytopeError::LowerDimensional { .. })
    ));
}
