//! Tables 6.5–6.10: every published design re-evaluated, and our optimiser re-run from every
//! published start.

use super::conventions::Conventions;
use super::published::{PublishedTable, TABLES, angles, area, cell_area, points_off, rounding};
use cdpr_workspace::synthesis::objective::THESIS_LOADS;
use cdpr_workspace::synthesis::{DextrousArea, SynthesisResult, SynthesisSettings, synthesise};

/// Whether some point of the rounding box of a printed design attains the published area.
pub struct RoundingCheck {
    /// Designs sampled (box corners, centre and pseudo-random interior points).
    pub samples: usize,
    /// Smallest and largest area met in the box.
    pub min_area: f64,
    pub max_area: f64,
    /// A sample with exactly the published area (to the grid point).
    pub attained: bool,
}

/// Our optimiser re-run from a published start.
pub struct Reoptimised {
    /// Dynamic-Q alone (the thesis' method and settings).
    pub dynamic_q: SynthesisResult,
    /// Dynamic-Q followed by the compass search.
    pub polished: SynthesisResult,
    /// `polished` followed by the global stage (order-preserving multi-start): the final answer.
    pub global: SynthesisResult,
}

/// One published design (a start d⁰ or an optimum d*).
pub struct Row {
    pub table: &'static str,
    pub run: &'static str,
    pub cables: usize,
    pub load: usize,
    /// "start" or "optimum".
    pub design: &'static str,
    pub printed: &'static [&'static str],
    pub betas: Vec<f64>,
    pub published_gradients: usize,
    pub published_printed: &'static str,
    pub published_area: f64,
    pub computed_area: f64,
    /// Published A_d* of the run (for comparing our re-run).
    pub published_optimum_area: f64,
    /// The largest published A_d* of the run's table.
    pub best_of_table: f64,
    /// Only when computed ≠ published.
    pub rounding: Option<RoundingCheck>,
    /// Only on start rows.
    pub reoptimised: Option<Reoptimised>,
}

impl Row {
    /// Computed − published, in grid points (0 within the published area's print precision).
    pub fn difference_points(&self) -> i64 {
        points_off(self.computed_area, self.published_printed, self.cables)
    }

    /// Whether an area of our re-run is at least the published A_d* of this run.
    pub fn reaches(&self, area: f64) -> bool {
        area >= self.published_optimum_area - 1e-9
    }

    /// Whether an area of our re-run is at least the best published A_d* of this run's table.
    pub fn reaches_best(&self, area: f64) -> bool {
        area >= self.best_of_table - 1e-9
    }

    /// How many grid points `area` lies below `target` (0 or negative when it does not).
    pub fn points_below(&self, area: f64, target: f64) -> i64 {
        ((target - area) / cell_area(self.cables)).round() as i64
    }
}

/// splitmix64 in [0, 1), for the rounding-box samples.
fn unit(state: &mut u64) -> f64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
}

fn rounding_check(
    objective: &DextrousArea,
    printed: &[&str],
    published: &str,
    cables: usize,
) -> RoundingCheck {
    let centre = angles(printed);
    let half = rounding(printed);
    let n = centre.len();
    let mut designs: Vec<Vec<f64>> = (0..1usize << n)
        .map(|mask| {
            (0..n)
                .map(|i| {
                    centre[i]
                        + if mask >> i & 1 == 1 {
                            half[i]
                        } else {
                            -half[i]
                        }
                })
                .collect()
        })
        .collect();
    let mut state = 0x6_29u64;
    for _ in 0..24 {
        designs.push(
            (0..n)
                .map(|i| centre[i] + half[i] * (2.0 * unit(&mut state) - 1.0))
                .collect(),
        );
    }
    let (mut lo, mut hi, mut attained) = (f64::INFINITY, f64::NEG_INFINITY, false);
    for d in &designs {
        let a = objective.area(d).expect("valid design");
        lo = lo.min(a);
        hi = hi.max(a);
        attained |= points_off(a, published, cables) == 0;
    }
    RoundingCheck {
        samples: designs.len(),
        min_area: lo,
        max_area: hi,
        attained,
    }
}

/// Synthesis settings of §6.6.2 for n cables (ρ = 0.1; Γ = 0.05 for 3 cables, 0.1 for 4).
pub fn settings(cables: usize) -> SynthesisSettings {
    let mut s = SynthesisSettings::default();
    s.dynamic_q.move_limit = 0.1;
    s.dynamic_q.fd_interval = if cables == 3 { 0.05 } else { 0.1 };
    s.dynamic_q.max_gradient_evaluations = 60;
    // A 4-cable grid cell is 0.04 wide: finer polls than 4 mrad rarely change a grid point.
    s.compass.min_step = if cables == 3 { 2e-3 } else { 4e-3 };
    // A noisy, multimodal objective: restart the compass search from wider offsets around the
    // best design so far (deterministic seed) to leave the local maxima the thesis reports.
    s.compass.restarts = 5;
    s.compass.restart_radius = 0.25;
    s.compass.max_evaluations = 900;
    // The global stage (order-preserving multi-start, `cdpr_workspace::synthesis::multi_start`).
    s.multi_start.compass.min_step = s.compass.min_step;
    // Four angles span a 4-D admissible set with wide basins: 512 samples, and 5 polished
    // samples at least 0.6 rad apart with 200 evaluations each. With 256 samples and 3 polishes
    // (0.3 or 0.6 rad apart), Table 6.10 runs 3 and 4 ended in the basin of A_d = 1.2128, 55 grid
    // points below the table's best 1.3008.
    if cables > 3 {
        s.multi_start.samples = 512;
        s.multi_start.polished = 5;
        s.multi_start.separation = 0.6;
        s.multi_start.compass.max_evaluations = 200;
    }
    s
}

fn reoptimise(objective: &DextrousArea, start: &[f64], cables: usize) -> Reoptimised {
    use cdpr_workspace::synthesis::{Method, multi_start};
    let mut base = settings(cables);
    base.multi_start.platform = Some(objective.platform.clone());
    let mut obj = objective.clone();
    let dq = SynthesisSettings {
        method: Method::DynamicQ,
        ..base.clone()
    };
    let dynamic_q = synthesise(&mut obj, start, &dq).expect("valid settings and start");
    let cs = SynthesisSettings {
        method: Method::CompassSearch,
        ..base
    };
    let mut polished = synthesise(&mut obj, &dynamic_q.design, &cs).expect("valid settings");
    polished.evaluations += dynamic_q.evaluations;
    polished.iterations += dynamic_q.iterations;
    let global = multi_start::maximise(
        &mut obj,
        polished.clone(),
        cs.min_separation,
        cs.penalty,
        &cs.multi_start,
    );
    Reoptimised {
        dynamic_q,
        polished,
        global,
    }
}

fn table_rows(t: &PublishedTable, conventions: &Conventions, rows: &mut Vec<Row>) {
    let objective = conventions.objective(t.cables, THESIS_LOADS[t.load]);
    let best_of_table = t
        .runs
        .iter()
        .map(|r| area(r.optimum_area).0)
        .fold(f64::NEG_INFINITY, f64::max);
    for r in t.runs {
        for (design, printed, printed_area) in [
            ("start", r.start, r.start_area),
            ("optimum", r.optimum, r.optimum_area),
        ] {
            let betas = angles(printed);
            let computed = objective.area(&betas).expect("valid design");
            let rounding = (points_off(computed, printed_area, t.cables) != 0)
                .then(|| rounding_check(&objective, printed, printed_area, t.cables));
            let reoptimised = (design == "start").then(|| reoptimise(&objective, &betas, t.cables));
            rows.push(Row {
                table: t.table,
                run: r.run,
                cables: t.cables,
                load: t.load,
                design,
                printed,
                betas,
                published_gradients: r.gradients,
                published_printed: printed_area,
                published_area: area(printed_area).0,
                computed_area: computed,
                published_optimum_area: area(r.optimum_area).0,
                best_of_table,
                rounding,
                reoptimised,
            });
        }
    }
}

/// All rows of Tables 6.5–6.10 under the settled conventions. The six tables run on concurrent
/// threads: each area evaluation is a short rayon job, and keeping the pool's queue full uses
/// both cores between jobs.
pub fn reproduce(conventions: &Conventions) -> Vec<Row> {
    let per_table: Vec<Vec<Row>> = std::thread::scope(|scope| {
        let handles: Vec<_> = TABLES
            .iter()
            .map(|t| {
                scope.spawn(move || {
                    let clock = std::time::Instant::now();
                    let mut rows = Vec::new();
                    table_rows(t, conventions, &mut rows);
                    eprintln!(
                        "  Table {} done after {:.1} s",
                        t.table,
                        clock.elapsed().as_secs_f64()
                    );
                    rows
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().expect("table thread"))
            .collect()
    });
    per_table.into_iter().flatten().collect()
}

/// Shared by the JSON writer: our re-run's evaluation counts.
pub fn evaluations_json(r: &SynthesisResult) -> serde_json::Value {
    serde_json::json!({ "function": r.evaluations.function, "gradient": r.evaluations.gradient })
}

#[cfg(test)]
mod tests {
    use super::*;
    use cdpr_tension::Method;

    /// Table 6.10 run 3: the thesis' Dynamic-Q ends in a local maximum (published A_d* 0.8304,
    /// the table's best 1.3008), and so did our Dynamic-Q + compass search (0.7936). The global
    /// stage reaches at least the table's best, keeping the start's cyclic order and the cables
    /// clear of the platform.
    #[test]
    fn global_stage_lifts_table_6_10_run_3_to_the_best_of_its_table() {
        let t = TABLES.iter().find(|t| t.table == "6.10").unwrap();
        let run = t.runs.iter().find(|r| r.run == "3").unwrap();
        let objective = DextrousArea::thesis(4, THESIS_LOADS[t.load], Method::ClosedForm).unwrap();
        let start = angles(run.start);
        let re = reoptimise(&objective, &start, 4);
        assert!(re.polished.area < 0.8304, "{}", re.polished.area);
        assert!(re.global.area >= 1.3008 - 1e-9, "{:?}", re.global);
        assert!(cdpr_workspace::synthesis::same_cyclic_order(
            &re.global.design,
            &start
        ));
        assert!(cdpr_workspace::synthesis::cables_clear_platform(
            &re.global.design,
            &objective.platform
        ));
        assert!(re.global.constraint_violation < 1e-12);
    }

    /// Every published design of Tables 6.5–6.10 (48: 24 starts d⁰, 24 optima d*), re-evaluated
    /// with the thesis' settings (`DextrousArea::thesis`: exact tensions and |det J| ≥ 10⁻³ for 3
    /// cables, closed-form ℓ1 for 4), lands within 2 grid points of its printed area, the printed
    /// angles being rounded to 4 digits. The one exception is Table 6.5 run 2 d⁰: printed 0.0880,
    /// but every design of its rounding box gives 0.0088–0.0096 (a probable misprint of 0.0088).
    /// At least 27 designs reproduce their area to the grid point (27 when this test was written).
    #[test]
    fn published_designs_reproduce_their_areas() {
        let (mut exact, mut total) = (0, 0);
        for t in &TABLES {
            let method = if t.cables == 3 {
                Method::Exact
            } else {
                Method::ClosedForm
            };
            let objective = DextrousArea::thesis(t.cables, THESIS_LOADS[t.load], method).unwrap();
            for r in t.runs {
                for (which, printed, printed_area) in [
                    ("d0", r.start, r.start_area),
                    ("d*", r.optimum, r.optimum_area),
                ] {
                    let a = objective.area(&angles(printed)).unwrap();
                    let off = points_off(a, printed_area, t.cables);
                    total += 1;
                    exact += usize::from(off == 0);
                    if (t.table, r.run, which) == ("6.5", "2", "d0") {
                        assert!(off < -150, "the misprint case now gives {a}");
                        assert!((0.0088..=0.0096).contains(&a), "{a}");
                        continue;
                    }
                    assert!(
                        off.abs() <= 2,
                        "Table {} run {} {which}: {a} vs printed {printed_area} ({off} points)",
                        t.table,
                        r.run
                    );
                }
            }
        }
        assert_eq!(total, 48);
        assert!(exact >= 27, "{exact}/48 exact");
    }
}
