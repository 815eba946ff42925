//! The force-polytope layer on arbitrary W / bounds / required wrench sets: the available wrench
//! set by hyperplane shifting (and Krut's vertex projection for small n), the maximum isotropic
//! force, the capacity margin. Invariants:
//! - no panic, no hang (errors for bad input are fine);
//! - soundness of the H-representation: W t lies in the AWS for tensions t in the box (corners
//!   and a random point), up to 10⁻⁹ of the wrench scale;
//! - the allocation-free evaluators (`isotropic_force_of`, `CapacityMargin`) agree with the
//!   functions of the facet list;
//! - a tension distribution certified feasible for w_ext means −w_ext is (within tolerance) in
//!   the AWS, i.e. its capacity margin is not clearly negative.
#![no_main]

use arbitrary::Unstructured;
use cdpr_fuzz::{Numbers, TensionCase, motion_for};
use cdpr_polytope::{
    CapacityMargin, RequiredWrenchSet, capacity_margin, hyperplane_shifting, isotropic_force,
    isotropic_force_of, isotropic_wrench_radius, isotropic_wrench_radius_of,
    krut_vertex_projection, largest_inscribed_ellipse,
};
use cdpr_tension::{Method, TensionBounds, TensionProblem, TensionSolver};
use libfuzzer_sys::fuzz_target;
use nalgebra::DVector;

/// |a − b| ≤ tol, treating equal infinities as equal.
fn close(a: f64, b: f64, tol: f64) -> bool {
    a == b || (a - b).abs() <= tol
}

fuzz_target!(|data: &[u8]| {
    let mut u = Unstructured::new(data);
    let Ok(case) = TensionCase::decode(&mut u, &[1, 2, 3, 4, 6]) else {
        return;
    };
    let (dof, n) = case.w.shape();
    let Ok(bounds) = TensionBounds::new(case.t_min.clone(), case.t_max.clone()) else {
        return;
    };
    let alt: bool = u.arbitrary().unwrap_or(false);
    let shape: u8 = u.arbitrary().unwrap_or(0);
    let mut num = Numbers::new(&mut u);
    let radius = num.any().unwrap_or(0.0);
    let half: Vec<f64> = (0..dof).map(|_| num.any().unwrap_or(0.0)).collect();
    let required = match shape % 3 {
        0 => RequiredWrenchSet::point(case.w_ext.clone()),
        1 => RequiredWrenchSet::ball(case.w_ext.clone(), radius),
        _ => RequiredWrenchSet::boxed(case.w_ext.clone(), DVector::from_vec(half)),
    };
    let sample: Vec<f64> = (0..n).map(|_| num.ordinary().unwrap_or(0.0)).collect();
    // Krut's method enumerates C(2ⁿ, DOF) candidates; keep each run fast (≤ 10⁵ candidates).
    let candidates: f64 = (0..dof).fold(1.0, |c, i| {
        c * ((1u64 << n) as f64 - i as f64) / (i + 1) as f64
    });
    let krut = n <= 6 && candidates <= 1e5 && num.bytes().arbitrary::<bool>().unwrap_or(false);

    if std::env::var_os("CDPR_FUZZ_DEBUG").is_some() {
        // Replaying an artifact: show the decoded input.
        eprintln!(
            "W = {:?}\nw_ext = {:?}\nbounds = {bounds:?}\nkrut = {krut}",
            case.w, case.w_ext
        );
    }
    let aws = hyperplane_shifting::available_wrench_set(&case.w, &bounds);
    let mut margin_eval = CapacityMargin::new(dof, n);
    let streamed_margin = required
        .as_ref()
        .ok()
        .map(|r| margin_eval.margin(&case.w, &bounds, r));
    let motion = (dof == 2 || dof == 3 || dof == 6).then(|| motion_for(dof, alt));
    let streamed_force = motion.map(|m| isotropic_force_of(m, &case.w, &bounds));
    let streamed_radius = isotropic_wrench_radius_of(&case.w, &bounds);

    let Ok(aws) = aws else {
        // The streaming evaluators must fail too (same engine).
        assert!(
            streamed_radius.is_err(),
            "AWS failed but the radius did not"
        );
        return;
    };
    let w_abs = case.w.amax();
    let t_abs = bounds
        .min()
        .iter()
        .chain(bounds.max().iter())
        .filter(|x| x.is_finite())
        .fold(1f64, |a, x| a.max(x.abs()));
    let scale = (w_abs * t_abs * n as f64).max(f64::MIN_POSITIVE);
    let tol = 1e-9 * scale;

    // Soundness: W t ∈ AWS for t in the box (corners picked by the sample's signs, and a
    // point inside), when every t_max is finite.
    if bounds.max().iter().all(|x| x.is_finite()) && scale.is_finite() {
        let corner = DVector::from_iterator(
            n,
            (0..n).map(|i| {
                if sample[i] >= 0.0 {
                    bounds.max()[i]
                } else {
                    bounds.min()[i]
                }
            }),
        );
        let inside = DVector::from_iterator(
            n,
            (0..n).map(|i| {
                let s = (sample[i].abs() / 66.0).fract();
                bounds.min()[i] + s * (bounds.max()[i] - bounds.min()[i])
            }),
        );
        for t in [corner, inside] {
            let wt = &case.w * &t;
            if wt.iter().all(|x| x.is_finite()) {
                let v = aws.violation(&wt);
                assert!(
                    v <= tol,
                    "W t outside the AWS by {v:e} (tol {tol:e})\nW = {:?}\nbounds = {bounds:?}\nt = {t:?}\nfacets = {:?}",
                    case.w,
                    aws.facets()
                );
            }
        }
    }

    // The streaming evaluators agree with the set's own indices (both use every supporting
    // half-space, unmerged).
    let radius_facets = isotropic_wrench_radius(&aws);
    let streamed_radius = streamed_radius.expect("AWS built but the streamed radius failed");
    assert!(
        close(
            radius_facets,
            streamed_radius,
            tol.max(1e-12 * radius_facets.abs())
        ),
        "isotropic wrench radius: facets {radius_facets} vs streamed {streamed_radius}"
    );
    if let (Some(m), Some(streamed)) = (motion, streamed_force) {
        let f = isotropic_force(&aws, m).expect("dimension agrees");
        let streamed = streamed.expect("AWS built but the streamed force failed");
        assert!(
            close(f, streamed, tol.max(1e-12 * f.abs().max(streamed.abs()))),
            "isotropic force: facets {f} vs streamed {streamed}"
        );
    }
    if let (Ok(r), Some(streamed)) = (&required, streamed_margin) {
        let m = capacity_margin(&aws, r).expect("dimension agrees");
        let streamed = streamed.expect("AWS built but the streamed margin failed");
        let slack = tol.max(1e-6 * (m.abs().max(streamed.abs()) + r.centre().amax()));
        assert!(
            close(m, streamed, slack) || (m.is_nan() && streamed.is_nan()),
            "capacity margin: facets {m} vs streamed {streamed}"
        );
    }

    // A certified tension distribution for w_ext ⇒ −w_ext ∈ AWS (up to tolerance).
    if case.well_scaled && case.w_ext.iter().all(|x| x.is_finite()) {
        let problem = TensionProblem::new(&case.w, &case.w_ext, &bounds);
        if let Ok(out) = TensionSolver::new(Method::L2).solve(&problem)
            && let Some(t) = out.tensions()
        {
            let wt = &case.w * t;
            let v = aws.violation(&wt);
            assert!(
                v <= tol.max(1e-9 * case.w_ext.amax()),
                "l2 found tensions but W t is outside the AWS by {v:e}"
            );
        }
    }

    // Krut's vertex projection builds the same polytope (small n only: it is exhaustive). Its
    // half-spaces are sound, and its facet minimum equals hyperplane shifting's whenever the
    // AWS has an interior (a flat AWS is LowerDimensional for Krut's method).
    if krut
        && case.well_scaled
        && let Ok(k) = krut_vertex_projection::available_wrench_set(&case.w, &bounds)
    {
        let rk = isotropic_wrench_radius(&k);
        let slack = 1e-6 * scale.max(1.0);
        assert!(
            close(rk, radius_facets, slack),
            "Krut radius {rk} vs hyperplane shifting {radius_facets}\nW = {:?}\nbounds = {bounds:?}",
            case.w
        );
    }
    if dof == 2 && case.well_scaled {
        let _ = largest_inscribed_ellipse(&aws);
    }
});
