//! Tables 6.5–6.10 of the thesis chapter on planar tendon-driven manipulators, transcribed as printed (angles kept as text so that their
//! printed precision, and hence their rounding box, is known).

/// One optimisation run of a published table.
pub struct PublishedRun {
    /// Run label as printed (Table 6.7 prints "3" twice).
    pub run: &'static str,
    /// Gradient evaluations N^g of Dynamic-Q.
    pub gradients: usize,
    /// Starting design d⁰ (rad), as printed.
    pub start: &'static [&'static str],
    /// A_d⁰, as printed.
    pub start_area: &'static str,
    /// Optimised design d* (rad), as printed.
    pub optimum: &'static [&'static str],
    /// A_d*, as printed.
    pub optimum_area: &'static str,
}

/// One published table.
pub struct PublishedTable {
    /// "6.5" … "6.10".
    pub table: &'static str,
    /// Number of cables n.
    pub cables: usize,
    /// Load case index (0 = L1, 1 = L2, 2 = L3; Table 6.3).
    pub load: usize,
    /// The runs.
    pub runs: &'static [PublishedRun],
}

macro_rules! run {
    ($run:literal, $g:literal, [$($s:literal),*], $a0:literal, [$($o:literal),*], $a:literal) => {
        PublishedRun { run: $run, gradients: $g, start: &[$($s),*], start_area: stringify!($a0), optimum: &[$($o),*], optimum_area: stringify!($a) }
    };
}

/// Tables 6.5–6.10.
pub const TABLES: [PublishedTable; 6] = [
    PublishedTable {
        table: "6.5",
        cables: 3,
        load: 0,
        runs: &[
            run!(
                "1",
                52,
                ["0.6607", "2.748", "4.367"],
                0.0660,
                ["0.7676", "3.430", "3.605"],
                0.3152
            ),
            run!(
                "2",
                34,
                ["0.6725", "2.880", "4.633"],
                0.0880,
                ["0.7631", "3.519", "3.693"],
                0.3168
            ),
            run!(
                "3",
                39,
                ["0.2814", "3.978", "4.278"],
                0.1996,
                ["0.7645", "3.477", "3.651"],
                0.3172
            ),
            run!(
                "4",
                50,
                ["0.735", "2.418", "5.159"],
                0.0024,
                ["-0.3146", "2.379", "5.794"],
                0.3168
            ),
        ],
    },
    PublishedTable {
        table: "6.6",
        cables: 3,
        load: 1,
        runs: &[
            run!(
                "1",
                17,
                ["0.9758", "4.056", "4.225"],
                0.0216,
                ["0.6179", "3.703", "3.878"],
                0.5136
            ),
            run!(
                "2",
                21,
                ["0.5014", "2.808", "3.616"],
                0.0524,
                ["0.7728", "3.348", "3.523"],
                0.5120
            ),
            run!(
                "3",
                41,
                ["0.6861", "2.431", "4.461"],
                0.0812,
                ["0.7667", "3.454", "3.628"],
                0.5228
            ),
            run!(
                "4",
                55,
                ["1.864", "2.621", "4.251"],
                0.0100,
                ["1.683", "1.858", "4.389"],
                0.2504
            ),
        ],
    },
    PublishedTable {
        table: "6.7",
        cables: 3,
        load: 2,
        runs: &[
            run!(
                "1",
                83,
                ["0.7983", "1.281", "3.373"],
                0.0500,
                ["0.6543", "2.357", "4.252"],
                1.024
            ),
            run!(
                "3",
                5,
                ["0.6097", "2.319", "4.197"],
                0.8364,
                ["0.6550", "2.371", "4.215"],
                1.019
            ),
            run!(
                "3",
                48,
                ["0.3040", "1.220", "5.040"],
                0.0028,
                ["0.6358", "2.366", "4.263"],
                1.019
            ),
            run!(
                "4",
                45,
                ["0.5922", "1.718", "4.865"],
                0.1736,
                ["0.6500", "2.369", "4.233"],
                1.021
            ),
        ],
    },
    PublishedTable {
        table: "6.8",
        cables: 4,
        load: 0,
        runs: &[
            run!(
                "1",
                48,
                ["1.829", "2.321", "3.392", "3.741"],
                0.0256,
                ["0.8205", "2.338", "4.595", "4.769"],
                1.1040
            ),
            run!(
                "2",
                47,
                ["2.139", "3.124", "3.216", "5.478"],
                0.1904,
                ["0.7878", "3.112", "3.287", "5.582"],
                0.9568
            ),
            run!(
                "3",
                48,
                ["2.288", "2.601", "3.876", "4.117"],
                0.0144,
                ["0.8207", "2.335", "4.601", "4.775"],
                1.0992
            ),
            run!(
                "4",
                14,
                ["0.7109", "2.219", "4.795", "4.997"],
                0.9472,
                ["0.8123", "2.325", "4.625", "4.799"],
                1.0992
            ),
        ],
    },
    PublishedTable {
        table: "6.9",
        cables: 4,
        load: 1,
        runs: &[
            run!(
                "1",
                34,
                ["0.0924", "2.607", "2.813", "5.982"],
                0.1424,
                ["0.7403", "3.173", "3.348", "5.564"],
                0.9760
            ),
            run!(
                "2",
                39,
                ["1.917", "3.369", "3.745", "3.828"],
                0.0272,
                ["0.8215", "2.334", "4.585", "4.760"],
                1.1504
            ),
            run!(
                "3",
                56,
                ["0.4313", "3.742", "4.899", "5.242"],
                0.0368,
                ["0.8194", "2.334", "4.591", "4.765"],
                1.1504
            ),
            run!(
                "4",
                82,
                ["0.5235", "2.065", "4.784", "4.913"],
                0.5088,
                ["0.8146", "2.326", "4.609", "4.783"],
                1.1472
            ),
        ],
    },
    PublishedTable {
        table: "6.10",
        cables: 4,
        load: 2,
        runs: &[
            run!(
                "1",
                55,
                ["1.347", "1.622", "2.036", "5.416"],
                0.0048,
                ["0.7572", "2.922", "3.097", "5.449"],
                1.3008
            ),
            run!(
                "2",
                17,
                ["0.4202", "2.962", "3.531", "6.158"],
                0.1968,
                ["0.7636", "2.929", "3.104", "5.439"],
                1.2944
            ),
            run!(
                "3",
                37,
                ["0.6810", "0.9393", "3.676", "5.416"],
                0.0016,
                ["1.452", "1.626", "3.843", "5.406"],
                0.8304
            ),
            run!(
                "4",
                23,
                ["0.1010", "2.683", "4.338", "4.407"],
                0.2032,
                ["0.8095", "2.330", "4.444", "4.619"],
                1.1920
            ),
        ],
    },
];

/// Parses printed angles.
pub fn angles(printed: &[&str]) -> Vec<f64> {
    printed
        .iter()
        .map(|s| s.parse().expect("published angles are numbers"))
        .collect()
}

/// Half-width of each printed angle's rounding interval: 0.5 × 10^(−decimals).
pub fn rounding(printed: &[&str]) -> Vec<f64> {
    printed
        .iter()
        .map(|s| {
            let decimals = s.split('.').nth(1).map_or(0, str::len);
            0.5 * 10f64.powi(-(decimals as i32))
        })
        .collect()
}

/// Area of one grid cell of an m × m grid over [−1, 1]².
pub fn cell_area(cables: usize) -> f64 {
    let m = if cables == 3 { 100.0 } else { 50.0 };
    (2.0 / m) * (2.0 / m)
}

/// Distance in grid points from `computed` to the interval of areas that print as `printed`
/// (e.g. "1.019" stands for [1.0185, 1.0195]); 0 inside it.
pub fn points_off(computed: f64, printed: &str, cables: usize) -> i64 {
    let (a, half) = area(printed);
    let excess = if computed > a + half {
        computed - (a + half)
    } else if computed < a - half {
        computed - (a - half)
    } else {
        0.0
    };
    (excess / cell_area(cables)).round() as i64
}

/// A printed area and the half-width of its printed precision.
pub fn area(printed: &str) -> (f64, f64) {
    let a = printed.parse().expect("published areas are numbers");
    (a, rounding(&[printed])[0])
}
