//! Regressions found by the 10⁶-problem soak (`cargo xtask soak --problems 1000000`, seed
//! 20261122): false "no feasible tension" with fixed cables (t_min = t_max), where the
//! rounding of t0 = −W⁺ w_ext (which grows with the other tensions) put the fixed cable
//! 1.5·10⁻¹⁰ (relative) off its bound, beyond the clipping tolerance. Clarabel and the exact
//! solution find certified tensions; every complete method must too.

use cdpr_tension::{Method, TensionBounds, TensionOutcome, TensionProblem, TensionSolver};
use nalgebra::{DMatrix, DVector};

const INF: f64 = f64::INFINITY;

fn assert_all_feasible(w: &DMatrix<f64>, we: &DVector<f64>, b: &TensionBounds, methods: &[Method]) {
    let p = TensionProblem::new(w, we, b);
    for &m in methods {
        match TensionSolver::new(m).solve(&p).unwrap() {
            TensionOutcome::Feasible(s) => {
                let r = (w * &s.tensions + we).amax();
                assert!(r < 1e-6, "{m:?}: residual {r}");
            }
            other => panic!("{m:?}: {other:?}"),
        }
    }
}

/// Soak problem 203901: planar, n = DOF = 3, cable 1 fixed at 3.29 N (t0 is 4.9·10⁻¹⁰ N off).
/// vertex-centroid judged its one candidate, t0, with the feasible-set tolerance (10⁻¹⁰) and
/// found "no vertex" on a set of depth 0.05.
#[test]
fn redundancy_0_fixed_cable_203901() {
    let w = DMatrix::from_column_slice(
        3,
        3,
        &[
            0.05184496806694612,
            -0.9986551453260216,
            -0.025115115161044203,
            -0.018288949015058,
            -0.9998327431845411,
            -0.0959233011368781,
            -0.17359181232146995,
            0.9848176900802237,
            -0.09817529120574883,
        ],
    );
    let we = DVector::from_vec(vec![
        284.67128853357235,
        -69.74169055849211,
        280.8252811783681,
    ]);
    let b = TensionBounds::new(
        vec![3.29096794908185, 6.841676107209507, 7.9668285137458525],
        vec![3.29096794908185, 1600.2615401314677, 1571.5462442339722],
    )
    .unwrap();
    use Method::*;
    assert_all_feasible(
        &w,
        &we,
        &b,
        &[
            Exact,
            L1,
            L1Max,
            L2,
            L2Max,
            Linf,
            PottClosedForm,
            L2Mid,
            VertexCentroid,
            OptimallySafe,
        ],
    );
}

/// Soak problem 487284: planar, n = DOF = 3, cable 3 fixed at 18.84 N (t0 is 3.5·10⁻⁹ N off).
#[test]
fn redundancy_0_fixed_cable_487284() {
    let w = DMatrix::from_column_slice(
        3,
        3,
        &[
            0.9802691410881412,
            -0.1976674253141319,
            0.046275571063895155,
            0.9994210155750956,
            0.034024015442693664,
            -0.09572946589213875,
            -0.9993773455674052,
            -0.03528344040264817,
            0.09648968864088765,
        ],
    );
    let we = DVector::from_vec(vec![
        -476.37472198720417,
        54.83402243870762,
        2.522849451448051,
    ]);
    let b = TensionBounds::new(
        vec![12.564726665903827, 6.89311423466493, 18.836654469229735],
        vec![1772.2258542450936, 914.5952024903324, 18.836654469229735],
    )
    .unwrap();
    use Method::*;
    assert_all_feasible(&w, &we, &b, &[Exact, L1, L1Max, L2, L2Max, Linf]);
}

/// Soak problem 196728: spatial, 7 cables (r = 1), cables 1 and 6 fixed: their zero-width
/// intervals of Algorithm 6.1 missed each other by rounding (closed-form, l1, l1-max).
#[test]
fn redundancy_1_two_fixed_cables_196728() {
    let w = DMatrix::from_column_slice(
        6,
        7,
        &[
            0.44425997201947476,
            -0.2661669434630065,
            0.8554462200914889,
            -0.04494616603771695,
            -0.09994907258126914,
            -0.007756602962030925,
            0.4194041607676728,
            0.2744860293802013,
            -0.8653077889432497,
            0.09866852349371391,
            -0.03732348191125417,
            0.03598397626309206,
            0.5006711215470352,
            -0.6872812032754002,
            -0.5262822205558081,
            0.012916640168843543,
            -0.021911114036169528,
            0.04090217130478723,
            -0.8933938310082251,
            -0.44640897280787595,
            -0.05066055381718721,
            0.0008553696125753541,
            0.0077053007536119775,
            -0.08298166942415403,
            -0.8800465159151544,
            0.1868898241501061,
            -0.436566516644074,
            0.01941996086593246,
            0.01387859640658183,
            -0.03320616653982897,
            -0.676809308899427,
            -0.5049903842921806,
            -0.5356434179185962,
            0.11307509909078517,
            -0.04127757949510792,
            -0.10396001719551738,
            0.8960275670426856,
            0.019144184517745542,
            0.44358550393212365,
            -0.014356572112672595,
            0.1381988878533915,
            0.023035422216010702,
        ],
    );
    let we = DVector::from_vec(vec![
        -1864.5469461918801,
        -331.959906214272,
        1001.3885881226637,
        -160.47122528673555,
        -157.81747405557587,
        -77.42544292100717,
    ]);
    let b = TensionBounds::new(
        vec![
            17.114862786846167,
            11.560710890347503,
            12.256708199399371,
            4.677646757687797,
            8.303778184714224,
            9.941700020217208,
            16.101703570302437,
        ],
        vec![
            17.114862786846167,
            INF,
            606.9511601537137,
            697.533557585728,
            INF,
            9.941700020217208,
            INF,
        ],
    )
    .unwrap();
    use Method::*;
    assert_all_feasible(&w, &we, &b, &[ClosedForm, L1, L2, L2Max, Linf]);
}

/// Soak problem 51618 (100 000-problem soak, seed 20261122): spatial, n = DOF = 6, cable 6
/// fixed at 4.97 N. The dense active set checked the cable (its null-space row is empty at
/// r = 0) against its own 10⁻¹² feasibility tolerance instead of the certificate's 10⁻⁹, and
/// l2-mid (which takes the dense path at every redundancy) answered "no feasible tension".
#[test]
fn redundancy_0_fixed_cable_51618_peers() {
    let w = DMatrix::from_column_slice(
        6,
        6,
        &[
            0.7001917230467704,
            -0.709228835970226,
            -0.08201225033562455,
            -0.04566358181686431,
            -0.05397580344901987,
            0.07691453645100914,
            0.8848807412311642,
            0.22859895695275836,
            -0.4058677009547524,
            -0.055234690211171646,
            0.008937786717502345,
            -0.115389681870421,
            -0.24848488805761337,
            0.6966474457617274,
            0.6730063868349664,
            0.0990657375313903,
            0.06851061026662063,
            -0.03434054029958762,
            -0.9178844225406054,
            -0.2789823256836497,
            0.2822358035640436,
            -0.013859496007083883,
            -0.036467009669583245,
            -0.08112034819253275,
            0.6621066181194082,
            -0.7240464227281544,
            0.19331736594792226,
            -0.02999387235974698,
            0.0408932888875154,
            0.2558889662211614,
            0.8338550302102513,
            -0.4999427572121762,
            0.23397228063201833,
            -0.021487810535606777,
            0.06138649944201499,
            0.20774877502011863,
        ],
    );
    let we = DVector::from_vec(vec![
        -510.83657712575365,
        -279.8337518373939,
        -64.49084512837875,
        1.1819906260740056,
        -29.6837515460837,
        64.14216878877905,
    ]);
    let b = TensionBounds::new(
        vec![
            4.035572005394858,
            0.614722835665783,
            11.025680249177274,
            7.988217741124001,
            14.008438751277378,
            4.968729850725372,
        ],
        vec![
            110.94854095591563,
            807.5509571586316,
            710.927751575289,
            269.40240480938076,
            779.6296402499914,
            4.968729850725372,
        ],
    )
    .unwrap();
    use Method::*;
    assert_all_feasible(
        &w,
        &we,
        &b,
        &[Exact, L2, L2Mid, Dykstra, VertexCentroid, OptimallySafe],
    );
}
