//! Inputs found by the fuzz target `polytope_index` (fuzz/fuzz_targets/polytope_index.rs).
//! Each test's comment describes the wrong answer the code gave when the input was found; all are
//! fixed. The three root causes were:
//! - merging near-duplicate facets kept one facet's normal with another's offset (unsound by
//!   ~1e-7 of the scale; indices changed): the set now keeps every supporting half-space, merges
//!   whole half-spaces, and computes membership and indices from the unmerged list;
//! - hyperplane shifting let a cable with t_min = t_max (a zero generator) span half-spaces that
//!   are not facets: subsets are now drawn from the generators;
//! - Krut's hyperplanes through DOF projected vertices used eq. (14) literally (T_k u = 1, a
//!   determinant test relative to the distance from the origin): they are now computed from the
//!   vertices' differences, through the box generators (module docs of krut_vertex_projection).

use cdpr_kinematics::MotionPattern;
use cdpr_polytope::{
    hyperplane_shifting, isotropic_force, isotropic_wrench_radius, krut_vertex_projection,
};
use cdpr_tension::TensionBounds;
use nalgebra::{DMatrix, dmatrix, dvector};

/// Both AWS methods give the exact isotropic wrench radius (computed outside this code) within
/// 10⁻⁶ relative.
fn both_methods_give(w: &DMatrix<f64>, b: &TensionBounds, exact: f64) {
    let hs = isotropic_wrench_radius(&hyperplane_shifting::available_wrench_set(w, b).unwrap());
    assert!(
        (hs - exact).abs() <= 1e-6 * exact.abs(),
        "hyperplane shifting {hs} vs exact {exact}"
    );
    let krut =
        isotropic_wrench_radius(&krut_vertex_projection::available_wrench_set(w, b).unwrap());
    assert!(
        (krut - exact).abs() <= 1e-6 * exact.abs(),
        "Krut {krut} vs exact {exact}"
    );
}

/// Zero-width tension box (t_min = t_max = 0 for every cable): the AWS is the single point {0}.
/// Hyperplane shifting describes it correctly (w ≤ 0 and −w ≤ 0).
#[test]
fn zero_width_box_by_hyperplane_shifting_is_a_point() {
    let w = dmatrix![195.04, 9.429, 128.5];
    let b = TensionBounds::uniform(3, 0.0, 0.0).unwrap();
    let aws = hyperplane_shifting::available_wrench_set(&w, &b).unwrap();
    assert!(aws.contains(&dvector![0.0]));
    assert!(!aws.contains(&dvector![1.0]));
    assert!(!aws.contains(&dvector![-1.0]));
}

/// Fuzz finding (crash-5ee4dcbb…, fixed in the working tree since): with a zero-width box every
/// one of the 2ⁿ box vertices projects to the same point, no candidate hyperplane existed, and
/// Krut's method returned an empty facet list, i.e. the *whole* wrench space (isotropic force
/// +∞). It must return `LowerDimensional` or facets describing {0}.
#[test]
fn krut_zero_width_box_is_not_the_whole_space() {
    let w = dmatrix![195.04, 9.429, 128.5];
    let b = TensionBounds::uniform(3, 0.0, 0.0).unwrap();
    if let Ok(aws) = krut_vertex_projection::available_wrench_set(&w, &b) {
        assert!(
            !aws.contains(&dvector![1.0]),
            "Krut's AWS contains 1 but W t = 0 for every admissible t; facets: {:?}",
            aws.facets()
        );
    }
}

/// The same bug in 2-D: cable 2's tension is fixed (t_min = t_max = 2), so the AWS is the
/// segment [0, 1] × {2}; Krut's method returned no facet (AWS = ℝ², isotropic force +∞).
#[test]
fn krut_fixed_tension_cable_gives_a_segment_not_the_plane() {
    let w = dmatrix![1.0, 0.0; 0.0, 1.0];
    let b = TensionBounds::new(vec![0.0, 2.0], vec![1.0, 2.0]).unwrap();
    // Reference: hyperplane shifting gives the segment.
    let hs = hyperplane_shifting::available_wrench_set(&w, &b).unwrap();
    assert!(hs.contains(&dvector![0.5, 2.0]));
    assert!(!hs.contains(&dvector![0.5, 3.0]));
    if let Ok(aws) = krut_vertex_projection::available_wrench_set(&w, &b) {
        assert!(
            !aws.contains(&dvector![0.5, 3.0]),
            "facets: {:?}",
            aws.facets()
        );
        let f = isotropic_force(&aws, MotionPattern::Point2).unwrap();
        assert!(f.is_finite(), "isotropic force {f}");
    }
}

/// Fuzz finding (crash-cc0f5b3d…): cable 1's tension range is 0.001 N and its column has norm
/// 0.054, while other generators w_j (t_max,j − t_min,j) reach ~1.5·10⁶: the facet spanned by
/// generators 1 and 5 is a thin parallelogram, yet a true facet of the zonotope, and it is the
/// one closest to (here: most violated by) the origin. Hyperplane shifting finds it; Krut's
/// vertex projection drops it (the three projected vertices through it fail the 1e-10
/// determinant test), so its isotropic wrench radius is −2.997·10⁶ instead of −3.441·10⁶ (15 %).
/// Reference value: exact rational arithmetic over every pair of generators (cross-product
/// normals, support function Σ max(c·w_j t_min,j, c·w_j t_max,j)), computed outside this code.
#[test]
fn krut_keeps_thin_facets() {
    let w = nalgebra::DMatrix::from_column_slice(
        3,
        6,
        &[
            -0.05406,
            -0.001,
            -0.001,
            -0.05406,
            -0.001,
            -0.05406,
            -0.0,
            -0.0,
            -0.0,
            5171.0,
            -10.872,
            -197.68,
            -32.703,
            -2.6874000000000002,
            -0.001,
            -3.2612000000000005,
            668.2,
            5171.0,
        ],
    );
    let b = TensionBounds::new(
        vec![12.294, -0.05406, -0.001, -0.05406, 1935.9, 676.6],
        vec![
            12.295,
            25.96506,
            0.05506,
            141.55406,
            2230.9700000000003,
            676.6540600000001,
        ],
    )
    .unwrap();
    both_methods_give(&w, &b, -3_441_234.398_963_446_3);
}

/// The hyperplane-shifting half of the finding above, not ignored: it must keep passing.
#[test]
fn hyperplane_shifting_keeps_thin_facets() {
    let w = nalgebra::DMatrix::from_column_slice(
        3,
        6,
        &[
            -0.05406,
            -0.001,
            -0.001,
            -0.05406,
            -0.001,
            -0.05406,
            -0.0,
            -0.0,
            -0.0,
            5171.0,
            -10.872,
            -197.68,
            -32.703,
            -2.6874000000000002,
            -0.001,
            -3.2612000000000005,
            668.2,
            5171.0,
        ],
    );
    let b = TensionBounds::new(
        vec![12.294, -0.05406, -0.001, -0.05406, 1935.9, 676.6],
        vec![
            12.295,
            25.96506,
            0.05506,
            141.55406,
            2230.9700000000003,
            676.6540600000001,
        ],
    )
    .unwrap();
    let hs = isotropic_wrench_radius(&hyperplane_shifting::available_wrench_set(&w, &b).unwrap());
    assert!((hs + 3_441_234.398_963_446_3).abs() <= 1e-3, "{hs}");
}

/// Second thin-facet fuzz finding (crash-8127c50d…): the facet spanned by cables 4 and 6, two
/// generators of norm ≈ 2.07 against a largest generator of 4.8·10⁵ (each ratio 4·10⁻⁶), is
/// the most violated one. Krut's vertex projection drops it (radius −1 050 423.99 instead of
/// −1 051 985.99). Reference: exact rational arithmetic as above.
#[test]
fn krut_keeps_facet_of_two_small_generators() {
    let w = nalgebra::DMatrix::from_column_slice(
        3,
        6,
        &[
            -0.05406, -26.01, 690.4, -0.05406, 690.4, -26.01, 0.0, 0.0, 0.0, 690.4, -26.01,
            -0.006169, -0.0, -0.0, -0.0, -0.006169, -0.006169, 690.4,
        ],
    );
    let b = TensionBounds::new(
        vec![-26.01, 1525.8, -0.006169, -0.001, -0.001, -0.001],
        vec![26.016169, 2216.2, 3.936169, 0.002, 0.002, 0.002],
    )
    .unwrap();
    both_methods_give(&w, &b, -1_051_985.991_830_551_3);
}

/// Fuzz finding (crash-2eb492e9…): cable 4 has t_min = t_max (a zero generator), and the origin
/// lies outside the AWS. The AWS is the parallelogram spanned by generators 1–3 (cables 1 and 2
/// are antiparallel); its facets are normal to columns 1 and 3 only, with signed distances
/// −3500.912…, −21.93…, 21.96…, 3612.14… (exact rational arithmetic, outside this code).
/// Hyperplane shifting also emits the half-spaces normal to column 4, which are supporting but
/// not facets (its module docs: "when W has rank DOF each is a true facet" does not hold for a
/// zero-width cable); one has d = −31 973.75, so `isotropic_wrench_radius` (documented as "the
/// most violated facet's signed distance") returns −31 973.75 where Krut's method returns the
/// facet value −3500.91.
#[test]
fn hyperplane_shifting_has_no_halfspace_normal_to_a_fixed_cable() {
    let w = nalgebra::DMatrix::from_column_slice(
        2,
        4,
        &[
            0.052199999999999996,
            -3.2612000000000005,
            -0.052199999999999996,
            3.2612000000000005,
            -1.3763,
            -14.539,
            10.956,
            0.00064,
        ],
    );
    let b = TensionBounds::new(
        vec![25751.0, 15701.0, 13.746, 0.016449000000000002],
        vec![25753.5532, 16008.0, 13.759112, 0.016449000000000002],
    )
    .unwrap();
    let exact = -3_500.912_236_489_569;
    let krut =
        isotropic_wrench_radius(&krut_vertex_projection::available_wrench_set(&w, &b).unwrap());
    assert!((krut - exact).abs() <= 1e-6 * exact.abs(), "Krut {krut}");
    let hs = isotropic_wrench_radius(&hyperplane_shifting::available_wrench_set(&w, &b).unwrap());
    assert!(
        (hs - exact).abs() <= 1e-6 * exact.abs(),
        "hyperplane shifting {hs} vs exact {exact}"
    );
}

/// Fuzz finding (crash-978b0090…): soundness of hyperplane shifting. For t = t_min (a corner of
/// the admissible box) W t must lie in the AWS, but it violates one half-space by 0.044 (the
/// offsets are ~10⁶; the crate's own `contains` tolerance is 1e-9·max|W|·max|t| ≈ 4.6e-3), so
/// `contains(W t)` is false for a wrench the cables do produce. Likely cause: the support sum
/// d(c) = Σ_j max(c·w_j t_min,j, c·w_j t_max,j) skips the subset's own columns assuming
/// c·w_j = 0 exactly, while c from an ill-conditioned subset (columns 1–2 nearly parallel after
/// scaling) is only approximately orthogonal to them: the omitted terms |c·w_j|·|t_j| are the
/// error. Summing over every column keeps each half-space a supporting one for any c.
#[test]
fn hyperplane_shifting_contains_every_box_corner() {
    let w = nalgebra::DMatrix::from_column_slice(
        3,
        6,
        &[
            -0.05406,
            -26.01,
            690.4,
            -0.05406,
            -26.01,
            -26.01,
            -0.0,
            -0.0,
            -0.0,
            690.4,
            690.4,
            4.4999999999999996e-5,
            668.2,
            -0.05406,
            668.2,
            4.4999999999999996e-5,
            4.4999999999999996e-5,
            1525.8,
        ],
    );
    let b = TensionBounds::new(
        vec![-26.01, -0.05406, -26.01, 690.4, 3003.0, -3.93],
        vec![52.02, 690.45406, 26.06406, 690.45406, 3029.01, 3.931],
    )
    .unwrap();
    let aws = hyperplane_shifting::available_wrench_set(&w, &b).unwrap();
    let wt = &w * b.min();
    let v = aws.violation(&wt);
    assert!(
        v <= 1e-9 * 1525.8 * 3029.01,
        "W t_min outside the AWS by {v:e}"
    );
    assert!(aws.contains(&wt));
}

/// Fuzz finding (timeout-9917bef0…, a libFuzzer timeout > 10 s): 6 DOF, 6 cables, every
/// tension fixed (t_min = t_max = −30.584). All 2⁶ box vertices project to one point, so each of
/// the C(64, 6) = 7.5·10⁷ candidates is singular and goes to the fallback of
/// `candidate_hyperplane` (krut_vertex_projection.rs, a heap-allocated SVD per candidate): the
/// call runs for minutes before returning. Hyperplane shifting answers in microseconds. A rank
/// check of the columns with t_min < t_max before the enumeration would return at once.
#[test]
fn krut_zero_width_box_in_six_dof_is_fast() {
    let w = nalgebra::DMatrix::from_column_slice(
        6,
        6,
        &[
            295.07, 0.007196, 295.07, 0.007196, 295.07, 0.007196, 295.07, 295.07, 295.07, 0.007196,
            295.07, 295.07, 295.07, 295.07, -30.618, -30.584, -30.584, -30.584, -30.584, -30.584,
            -30.684, -30.584, -30.584, -30.584, 4.744, 1830.4, 1.0, 522.0, -3.2612, 141.5, -30.584,
            -2.936, -30.584, -305.84, -0.32703, -2.6874,
        ],
    );
    let b = TensionBounds::uniform(6, -30.584, -30.584).unwrap();
    let start = std::time::Instant::now();
    let hs = hyperplane_shifting::available_wrench_set(&w, &b);
    assert!(start.elapsed().as_secs_f64() < 1.0);
    let start = std::time::Instant::now();
    let krut = krut_vertex_projection::available_wrench_set(&w, &b);
    let secs = start.elapsed().as_secs_f64();
    assert!(secs < 1.0, "Krut took {secs:.1} s");
    // Both describe the single point W t (or refuse it as lower-dimensional).
    if let (Ok(hs), Ok(krut)) = (hs, krut) {
        let p = &w * b.min();
        assert!(hs.contains(&p) && krut.contains(&p));
    }
}

/// Third case of the Krut precision finding (crash-b6459005…): 2 DOF, columns 1 and 4 are
/// identical and generator 4 is 1.6·10⁻⁵ of the largest; the origin is ~5·10⁷ outside the AWS.
/// Exact facet minimum (rational arithmetic): −50 072 706.449 (hyperplane shifting agrees);
/// Krut's method returns −50 078 131.39, a half-space 5.4·10³ off.
#[test]
fn krut_duplicate_column_with_tiny_range() {
    let w = nalgebra::DMatrix::from_column_slice(
        2,
        4,
        &[
            0.021963999999999997,
            -10.872,
            -668.3,
            -668.3,
            691.2,
            -31544.0,
            0.021963999999999997,
            -10.872,
        ],
    );
    let b = TensionBounds::new(
        vec![-665.7, 25841.0, 2197.0, 1.6777000000000002],
        vec![732.85, 25843.3876, 2197.021964, 1.6996640000000003],
    )
    .unwrap();
    both_methods_give(&w, &b, -50_072_706.449_046_71);
}

/// The clearest case of the Krut precision finding (crash-12c18d59…), and its likely root cause:
/// every generator is of ordinary size (1.6–2.8) and conditioning, but cable 6 carries a fixed
/// ~11 051 N so the AWS lies ~10⁵ away from the origin. `candidate_hyperplane` accepts T_k only
/// if |det T_k| > 1e-10 · Π‖τ_r,i‖: the product of the *distances of the vertices from the
/// origin* (~(1.6·10⁵)³ here), not of their separations (~2.7). The facet spanned by the
/// generators of cables 3 and 5 (5·10⁻³ rad apart) gives det ≈ 6·10³ < 4·10⁵ and is dropped;
/// Krut's radius is −98 464.69 instead of the exact −113 332.73 (rational arithmetic; hyperplane
/// shifting agrees). The same test explains `krut_keeps_thin_facets`,
/// `krut_keeps_facet_of_two_small_generators` and `krut_duplicate_column_with_tiny_range`.
/// A fix: measure T_k's singularity on the differences τ_r,i − τ_r,0 (translation-invariant).
#[test]
fn krut_keeps_facets_of_a_far_away_polytope() {
    let w = nalgebra::DMatrix::from_column_slice(
        3,
        6,
        &[
            -0.001,
            -3.0841000000000003,
            -14.457,
            -0.0,
            -0.0,
            -0.0,
            -14.393,
            -14.529,
            -14.393,
            -14.393,
            -0.013823,
            -1e-5,
            -14.393,
            -14.393,
            -14.393,
            -14.393,
            0.11069000000000001,
            0.11051,
        ],
    );
    let b = TensionBounds::new(
        vec![0.11051, 0.11051, 0.11051, 0.11051, 0.11051, 11051.0],
        vec![
            0.22102,
            0.22102,
            0.22102,
            0.22102,
            0.22099999999999997,
            11051.11052,
        ],
    )
    .unwrap();
    both_methods_give(&w, &b, -113_332.730_486_091_21);
}

/// Fuzz finding (crash-d711426e…, minor): `isotropic_force(&available_wrench_set(W), m)` and
/// `isotropic_force_of(m, W)` (documented as the same value without the facet list) differ by
/// 4.7·10⁻⁵ relative (−50 444.41 vs −50 446.81). `from_halfspaces` merges half-spaces whose
/// unit normals differ by < 1e-7 and keeps the first normal with the group's smallest offset;
/// the zero-moment force index divides each offset by the normal's force part ‖n_f‖, so when
/// ‖n_f‖ is small the 1e-7 normal change is amplified. (One t_max is infinite here.)
#[test]
fn isotropic_force_of_matches_the_facet_list() {
    let w = nalgebra::DMatrix::from_column_slice(
        3,
        7,
        &[
            23.517,
            -0.001,
            1e-15,
            -3.928,
            -0.001,
            2729.0,
            0.0,
            0.0,
            0.0,
            -2776.0,
            -1e-5,
            1e-300,
            -0.10421,
            -3023.2,
            -0.26549,
            -0.028557,
            1136.6,
            1.7587000000000002,
            -1268.7,
            1136.6,
            1.7587000000000002,
        ],
    );
    let mut max = vec![-0.028557; 7];
    max[5] = f64::INFINITY;
    let b = TensionBounds::new(vec![-0.26549; 7], max).unwrap();
    let aws = hyperplane_shifting::available_wrench_set(&w, &b).unwrap();
    for m in [MotionPattern::Planar, MotionPattern::Point3] {
        let f = isotropic_force(&aws, m).unwrap();
        let g = cdpr_polytope::isotropic_force_of(m, &w, &b).unwrap();
        assert!(
            f == g || (f - g).abs() <= 1e-6 * f.abs().max(g.abs()),
            "{m:?}: facets {f} vs streamed {g}"
        );
    }
}

/// Fuzz finding (crash-9fdab428…): the origin on the AWS boundary. DOF 1, W = [−0.0138, −0,
/// −21177, −0.0138], t ∈ [−10024, 0]: AWS = [0, 2.12·10⁸], so the isotropic radius is 0
/// (hyperplane shifting: 0). Krut's method returns 2.12·10⁸: the facet −w ≤ 0 passes through
/// the projected vertex τ = 0, which `candidate_hyperplane` rejects (`hadamard == 0`: "a
/// projected vertex at the origin: not a Cramer system"), and the through-origin fallback
/// never sees it.
#[test]
fn krut_keeps_facets_through_the_origin() {
    let w = dmatrix![-0.013826000000000001, -0.0, -21177.0, -0.013826000000000001];
    let b = TensionBounds::uniform(4, -10024.0, 0.0).unwrap();
    let hs = isotropic_wrench_radius(&hyperplane_shifting::available_wrench_set(&w, &b).unwrap());
    assert_eq!(hs, 0.0);
    let krut =
        isotropic_wrench_radius(&krut_vertex_projection::available_wrench_set(&w, &b).unwrap());
    assert!(krut.abs() <= 1e-6, "Krut {krut}, exact 0");
}

/// The same in 2-D with t_min = 0 (every cable slack allowed): AWS = [0, 1]², whose facets
/// x ≥ 0 and y ≥ 0 pass through the projected vertex t = 0. Exact isotropic force: 0; Krut's
/// method returns 1 (it keeps only x ≤ 1 and y ≤ 1).
#[test]
fn krut_unit_square_from_zero_tension() {
    let w = dmatrix![1.0, 0.0; 0.0, 1.0];
    let b = TensionBounds::uniform(2, 0.0, 1.0).unwrap();
    let hs = hyperplane_shifting::available_wrench_set(&w, &b).unwrap();
    assert_eq!(isotropic_force(&hs, MotionPattern::Point2).unwrap(), 0.0);
    let krut = krut_vertex_projection::available_wrench_set(&w, &b).unwrap();
    let f = isotropic_force(&krut, MotionPattern::Point2).unwrap();
    assert!(f.abs() <= 1e-9, "Krut {f}, exact 0");
}

/// Fuzz finding (crash-31ed176d…): a zero column (cable 1) duplicates every projected vertex.
/// Exact facet minimum (rational arithmetic): −580.657 (hyperplane shifting agrees; the origin is
/// just outside a polytope of size ~2·10⁸). Krut's method returns −1 535 618.8: all box corners
/// are inside its set, so the extra half-space is supporting but not a facet (the mirror image
/// of `hyperplane_shifting_has_no_halfspace_normal_to_a_fixed_cable`).
#[test]
fn krut_zero_column() {
    let w = nalgebra::DMatrix::from_column_slice(
        3,
        4,
        &[
            0.0, 0.0, 0.0, -6.683, -0.027901, 12337.0, -12336.0, -12336.0, -1.2336, 12336.0,
            12336.0, 123.39,
        ],
    );
    let b = TensionBounds::uniform(4, 123.39, 12336.0).unwrap();
    let exact = -580.656_760_377_864_2;
    let hs = isotropic_wrench_radius(&hyperplane_shifting::available_wrench_set(&w, &b).unwrap());
    assert!(
        (hs - exact).abs() <= 1e-6 * exact.abs(),
        "hyperplane shifting {hs}"
    );
    let krut_aws = krut_vertex_projection::available_wrench_set(&w, &b).unwrap();
    // Soundness first: every box corner W t lies in Krut's set.
    for bits in 0..16u32 {
        let t =
            nalgebra::DVector::from_fn(4, |j, _| if bits >> j & 1 == 1 { 12336.0 } else { 123.39 });
        let v = krut_aws.violation(&(&w * &t));
        assert!(
            v <= 1e-9 * 12337.0 * 12336.0 * 4.0,
            "corner {bits:04b} outside Krut's AWS by {v:e}"
        );
    }
    let krut = isotropic_wrench_radius(&krut_aws);
    assert!(
        (krut - exact).abs() <= 1e-6 * exact.abs(),
        "Krut {krut} vs exact {exact}"
    );
}

/// Second case of the facet-merging finding (crash-049d6668…): here the two values differ by 1 %
/// (−2.696·10⁸ vs −2.723·10⁸), uniform bounds [0.0194, 13258], 8 cables, the origin outside.
#[test]
fn isotropic_force_of_matches_the_facet_list_8_cables() {
    let w = nalgebra::DMatrix::from_column_slice(
        3,
        8,
        &[
            -8225.0,
            -8225.0,
            -8225.0,
            -8355.0,
            -8225.0,
            -0.009767,
            -97.66999999999999,
            -8225.0,
            -8.225,
            -22.175,
            -881.9000000000001,
            -5906.0,
            97.66,
            -8231.0,
            -0.008225,
            -8225.0,
            -0.001,
            -0.001,
            -0.001,
            -0.001,
            -0.001,
            -0.0,
            -0.0,
            -0.0,
        ],
    );
    let b = TensionBounds::uniform(8, 0.019414999999999998, 13258.0).unwrap();
    let aws = hyperplane_shifting::available_wrench_set(&w, &b).unwrap();
    for m in [MotionPattern::Planar, MotionPattern::Point3] {
        let f = isotropic_force(&aws, m).unwrap();
        let g = cdpr_polytope::isotropic_force_of(m, &w, &b).unwrap();
        assert!(
            f == g || (f - g).abs() <= 1e-6 * f.abs().max(g.abs()),
            "{m:?}: facets {f} vs streamed {g}"
        );
    }
}

/// Third case of the facet-merging finding (crash-201325ad…), now with a *positive* index:
/// 6 DOF, 10 cables (4 zero columns), one t_max infinite. Facet list 4.70·10⁶ vs streamed
/// 3.96·10⁶ (16 %). The zero-moment force index divides by the force part ‖n_f‖ of each normal
/// (kept when > 1e-12): for facets that are nearly pure moment, a 1e-7 change of the normal by
/// merging changes d/‖n_f‖ arbitrarily.
#[test]
fn isotropic_force_of_matches_the_facet_list_spatial() {
    let w = nalgebra::DMatrix::from_column_slice(
        6,
        10,
        &[
            -668.3,
            -0.001,
            -0.001,
            -0.001,
            -0.001,
            -0.001,
            -0.001,
            -0.001,
            -0.001,
            -0.001,
            -668.3,
            -668.3,
            -668.3,
            -668.3,
            31545.0,
            -179.1,
            -177.34000000000003,
            -177.34000000000003,
            -177.34000000000003,
            -177.34000000000003,
            -177.34000000000003,
            -177.34000000000003,
            0.14778,
            0.14648999999999998,
            0.14648999999999998,
            0.14648999999999998,
            -0.001,
            -0.001,
            0.14648999999999998,
            0.14648999999999998,
            -0.0,
            -0.0,
            -0.0,
            -0.0,
            -0.0,
            -0.0,
            -177.34000000000003,
            198.10000000000002,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
        ],
    );
    let mut max = vec![52430.0; 10];
    max[3] = f64::INFINITY;
    let b = TensionBounds::new(vec![-26215.0; 10], max).unwrap();
    let aws = hyperplane_shifting::available_wrench_set(&w, &b).unwrap();
    let f = isotropic_force(&aws, MotionPattern::Spatial).unwrap();
    let g = cdpr_polytope::isotropic_force_of(MotionPattern::Spatial, &w, &b).unwrap();
    assert!(
        f == g || (f - g).abs() <= 1e-6 * f.abs().max(g.abs()),
        "facets {f} vs streamed {g}"
    );
}

/// Fuzz finding (crash-ef7e1152…), with the origin *inside*: 4 DOF, n = 4 (a parallelotope).
/// Exact facet minimum (rational arithmetic over every triple of columns): 28 227.055 on the
/// negative side of the facet pair normal to columns 2–4 (hyperplane shifting agrees). Krut's
/// method returns 56 454.11, the positive side of the same pair: it drops one facet of the pair.
/// Cable 4's range [−29 813, 29 815] dwarfs the others (≈ ±20). Not diagnosed further.
#[test]
fn krut_parallelotope_4_dof() {
    let w = nalgebra::DMatrix::from_column_slice(
        4,
        4,
        &[
            -5.22,
            25532.0,
            2.1945,
            55.0,
            -29813.0,
            -0.001,
            -0.001,
            -29812.0,
            -29813.0,
            -29813.0,
            -29813.0,
            -198.29000000000002,
            -0.32703000000000004,
            -2.6874000000000002,
            -1.8248000000000002,
            -1.8248000000000002,
        ],
    );
    let b = TensionBounds::new(
        vec![-1.8248000000000002, -18.248, -1.8248000000000002, -29813.0],
        vec![3.6496000000000004, 20.0728, 3.6496000000000004, 29814.8248],
    )
    .unwrap();
    both_methods_give(&w, &b, 28_227.055_303_195_54);
}

/// Second, larger case of the soundness finding (crash-b4bfd27a…): 9 cables, four of them
/// identical columns (−19 019, −19 019, −19 019), a box corner t; W t lies 0.038 outside the
/// hyperplane-shifting AWS, 10⁻⁷ of the scale max|W|·max|t|·n ≈ 3.8·10⁵ (100× the fuzz tolerance).
#[test]
fn hyperplane_shifting_contains_every_box_corner_duplicates() {
    let w = nalgebra::DMatrix::from_column_slice(
        3,
        9,
        &[
            2605.0,
            -13.926,
            -3.614,
            -0.05529,
            -0.056,
            2647.1,
            2647.1,
            2647.1,
            -3.2045000000000003,
            -19019.0,
            -19019.0,
            -19019.0,
            -19019.0,
            -19019.0,
            -19019.0,
            -19019.0,
            -19019.0,
            -19019.0,
            -19019.0,
            -19019.0,
            -19019.0,
            -19019.0,
            -19019.0,
            2.2102,
            0.022102,
            2.2102,
            2.2102,
        ],
    );
    let b = TensionBounds::uniform(9, 2.2102, 2.2271).unwrap();
    let t = dvector![
        2.2102, 2.2102, 2.2102, 2.2271, 2.2271, 2.2271, 2.2271, 2.2271, 2.2271
    ];
    let aws = hyperplane_shifting::available_wrench_set(&w, &b).unwrap();
    let v = aws.violation(&(&w * &t));
    assert!(v <= 1e-9 * 19019.0 * 2.2271, "W t outside the AWS by {v:e}");
}

/// Fuzz finding (crash-4e9d8327…, session 2): columns 2 and 6 are exactly antiparallel with the
/// same tension range, so their generators cancel and pairs of box vertices coincide. Computed
/// through the SVD, g₂ + g₆ was a round-off residual instead of zero; Krut's method took its
/// direction as a vertex difference and kept a supporting half-space through an edge (not a
/// facet): radius −1.590·10⁹ instead of the exact −1 146 869 005.598 (rational arithmetic over
/// every pair of generators; hyperplane shifting agrees).
#[test]
fn krut_antiparallel_generators_cancel() {
    let w = nalgebra::DMatrix::from_column_slice(
        3,
        6,
        &[
            -0.05406,
            2613.8,
            3148.0,
            3148.0,
            3148.0,
            21274.0,
            21331.0,
            21331.0,
            21331.0,
            21331.0,
            21331.0,
            -17581.0,
            -2.6874000000000002,
            21331.0,
            15.26,
            -3148.0,
            -3148.0,
            -21274.0,
        ],
    );
    let b = TensionBounds::new(
        vec![21331.0; 6],
        vec![42662.0, 42662.0, 42766.0, 38566.0, 42662.0, 42662.0],
    )
    .unwrap();
    both_methods_give(&w, &b, -1_146_869_005.598_414);
}

/// Fuzz finding (crash-39409e54…, session 2): W has condition number 1.5·10⁷ (singular values
/// 25 752 and 0.00175). Krut's generators were read off the computed Vᵀ, whose small entries
/// carry round-off of order ε·s₁/s₂; the facet normal to the cables along (1, 1) came out turned
/// by 1.2·10⁻⁴ rad and the radius was −590 824 537.98 instead of the exact −590 754 502.876
/// (rational arithmetic; hyperplane shifting agrees). The generators are now S⁻¹Uᵀw_j.
#[test]
fn krut_ill_conditioned_w() {
    let w = nalgebra::DMatrix::from_column_slice(
        2,
        4,
        &[
            -0.001, -0.001, -0.001, -0.001, 0.001, 0.001, 25751.0, -255.32,
        ],
    );
    let b = TensionBounds::new(
        vec![-0.001, 32100.0, 32125.0, 32125.0],
        vec![0.002, 64225.0, 64250.0, 64250.0],
    )
    .unwrap();
    both_methods_give(&w, &b, -590_754_502.875_848_2);
}

/// Fuzz finding (timeout-6d91f0c0…, session 2; the "timeout" was the backtrace of a failed
/// assertion): generator lengths range from 1.6·10⁻⁴ to 4.9·10⁶ (cable 3's range is 21 049 N,
/// cables 1–2 have 0.003 N), one column is zero and two are equal. Krut's border test used a
/// tolerance of 10⁻⁹ of the polytope's size, larger than the polytope's whole thickness in its
/// thin directions, and accepted 60 planes cutting through it: radius −371.54 instead of the
/// exact −300.440 (rational arithmetic; hyperplane shifting agrees). The tolerance is now
/// relative to each vertex's path length from the plane's first vertex.
#[test]
fn krut_border_test_with_generators_of_very_different_lengths() {
    let w = nalgebra::DMatrix::from_column_slice(
        3,
        6,
        &[
            -0.05406, -0.001, -0.001, -0.05406, -0.001, -0.05406, 233.53, -14.197, -0.001, -0.0,
            -0.0, -0.0, -0.001, -0.001, -0.001, -0.001, -0.001, -0.001,
        ],
    );
    let b = TensionBounds::new(
        vec![-0.001, -0.001, 1.8194, 0.0522, -0.14907, -0.14907],
        vec![0.002, 0.002, 21050.8194, 3.3134, 0.29814, 15.05607],
    )
    .unwrap();
    let exact = -300.439_909_915_039_66;
    let hs = hyperplane_shifting::available_wrench_set(&w, &b).unwrap();
    let krut = krut_vertex_projection::available_wrench_set(&w, &b).unwrap();
    for (name, aws) in [("hyperplane shifting", &hs), ("Krut", &krut)] {
        let r = isotropic_wrench_radius(aws);
        assert!(
            (r - exact).abs() <= 1e-6 * exact.abs(),
            "{name} {r} vs exact {exact}"
        );
    }
    assert_eq!(krut.facets().len(), hs.facets().len());
}

/// Fuzz finding (crash-69f9c48a…, session 2): a plane through three box vertices v₀,
/// v₀ + g₆ − g₁ and v₀ + g₆ − g₂ (g₁, g₂ of length ~10⁻⁴, g₆ of length 1513) is tilted about
/// the edge g₆ by the tiny g₁ − g₂; its heights cancel in pairs and it passed the border test
/// within round-off while touching only the edge: Krut's radius −7 750 561.7 instead of the
/// exact −2 997 115.058 (rational arithmetic; hyperplane shifting agrees). A border must now
/// contain DOF − 1 independent generators, and its normal is recomputed from them.
#[test]
fn krut_rejects_planes_touching_only_an_edge() {
    let w = nalgebra::DMatrix::from_column_slice(
        3,
        6,
        &[
            -0.05406, -0.001, -0.001, -0.05406, -0.001, -0.05406, -0.0, -0.0, -0.0, 5171.0,
            -10.872, -197.68, -32.703, -2.6874, -0.001, -3.2612, 668.2, 5171.0,
        ],
    );
    let b = TensionBounds::new(
        vec![-0.05406, -0.05406, 685.7, 1513.0, 1935.9, 676.6],
        vec![0.05506, 0.05506, 2198.7, 1654.5, 2230.97, 2189.6],
    )
    .unwrap();
    let exact = -2_997_115.058_229_63;
    let hs = hyperplane_shifting::available_wrench_set(&w, &b).unwrap();
    let krut = krut_vertex_projection::available_wrench_set(&w, &b).unwrap();
    for (name, aws) in [("hyperplane shifting", &hs), ("Krut", &krut)] {
        let r = isotropic_wrench_radius(aws);
        assert!(
            (r - exact).abs() <= 1e-9 * exact.abs(),
            "{name} {r} vs exact {exact}"
        );
    }
    assert_eq!(krut.facets().len(), hs.facets().len());
}

/// Fuzz finding (crash-751f46fe…, session 3): generators spanning five orders of magnitude
/// (|w_j| from 10⁻³ to 2·10³) and a zero column. The exact facet minimum (rational oracle) is
/// 7.2406e-7: a thin facet spanned by two tiny generators. Krut's method returned 0.0327.
#[test]
fn thin_facet_among_generators_of_very_different_sizes() {
    let w = dmatrix![-0.001, 1917.8000000000002, -0.001, -0.0, 46.260000000000005, -0.001;
                     -0.001, -0.0, -0.0, -0.0, 1917.8000000000002, -0.001;
                     -0.0, 1917.8000000000002, -0.001, -0.0, -0.001, -0.001];
    let b = TensionBounds::uniform(6, -0.001, 0.002).unwrap();
    both_methods_give(&w, &b, 7.240582290327277e-07);
}

/// Issue 13 §1: Krut's vertex projection at extreme scales. W = s·[[1, −1, 0, 0], [0, 0, 1, −1]],
/// t ∈ [1, 10]: the AWS is the square [−9s, 9s]² and the isotropic force is 9·s (hyperplane
/// shifting agrees). For s ≥ 10²⁰⁰ or ≤ 10⁻¹⁶⁰ the method returned no facets and +∞ as Ok.
#[test]
fn krut_vertex_projection_at_extreme_scales() {
    use cdpr_kinematics::MotionPattern;
    use cdpr_polytope::{hyperplane_shifting, isotropic_force, krut_vertex_projection};
    let b = cdpr_tension::TensionBounds::uniform(4, 1.0, 10.0).unwrap();
    for s in [
        1e-300, 1e-200, 1e-160, 1e-100, 1e-20, 1.0, 1e20, 1e100, 1e200, 1e300,
    ] {
        let w = nalgebra::DMatrix::from_row_slice(2, 4, &[s, -s, 0.0, 0.0, 0.0, 0.0, s, -s]);
        let krut = krut_vertex_projection::available_wrench_set(&w, &b).unwrap();
        let shift = hyperplane_shifting::available_wrench_set(&w, &b).unwrap();
        assert_eq!(krut.facets().len(), 4, "s = {s:e}");
        for f in krut.facets() {
            assert!(
                (f.offset / (9.0 * s) - 1.0).abs() < 1e-12,
                "s = {s:e}: {f:?}"
            );
        }
        assert_eq!(krut.vertices().unwrap().len(), 4, "s = {s:e}");
        let (fk, fs) = (
            isotropic_force(&krut, MotionPattern::Point2).unwrap(),
            isotropic_force(&shift, MotionPattern::Point2).unwrap(),
        );
        assert!((fk / (9.0 * s) - 1.0).abs() < 1e-12, "s = {s:e}: {fk:e}");
        assert!((fs / (9.0 * s) - 1.0).abs() < 1e-12, "s = {s:e}: {fs:e}");
    }
}
