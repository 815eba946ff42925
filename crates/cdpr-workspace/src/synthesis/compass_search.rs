//! # Compass search with restarts
//!
//! The derivative-free option for the noisy, piecewise-constant area objective of eq. (6.29): a
//! compass (pattern) search on the merit φ = −A + μ Σ max(0, β_min − s_ij). Each poll tries
//! x ± h v for the directions v of the generating set, starting with the last successful one,
//! and moves to the first point that strictly decreases φ; a poll without success halves h. The
//! generating set holds the coordinate directions e_i and, because eq. (6.29) bounds differences
//! of neighbouring angles, e_i + e_{i+1} for every constrained pair (moving a pair rigidly keeps
//! its separation) and the rigid rotation Σ e_k: with one active separation constraint (the case
//! of every published optimum) these span its tangent cone, so the search does not stall on the
//! constraint, as a pure coordinate search on a non-smooth penalty does (Kolda et al. §8.2). Plateaus of the staircase
//! objective are crossed by the initial step h_0, which is wider than a grid cell's footprint in
//! design space. After convergence the search restarts (`restarts` times) from the best point
//! moved by a deterministic pseudo-random offset in [−r, r]^n, keeping the best answer: a cheap
//! global element against the local maxima reported in Tables 6.6, 6.8–6.10. Polls and restart
//! offsets that change the cyclic order of the anchors (crossed cables, see the module docs of
//! [`super`]) are rejected; a restart offset is drawn again, up to 64 times.
//!
//! ## References
//! - T. G. Kolda, R. M. Lewis and V. Torczon, "Optimization by direct search: new perspectives on
//!   some classical and modern methods", *SIAM Review* 45 (2003) 385–482, §3 (compass search).
//! - S. Vigna, "splitmix64" (the pseudo-random generator of the restart offsets).

use super::objective::{Merit, Objective};
use super::{Evaluations, SynthesisError, SynthesisResult, Termination, invalid};

/// Settings of [`maximise`].
#[derive(Debug, Clone, PartialEq)]
pub struct CompassSettings {
    /// Initial poll step h_0 (rad).
    pub initial_step: f64,
    /// Stop a local search when h < this (rad).
    pub min_step: f64,
    /// Restarts after the first local search.
    pub restarts: usize,
    /// Half-width r of the restart offsets (rad); 0 restarts from the best point itself.
    pub restart_radius: f64,
    /// Budget of objective evaluations over all local searches.
    pub max_evaluations: usize,
    /// Seed of the restart offsets (runs are deterministic).
    pub seed: u64,
}

impl Default for CompassSettings {
    fn default() -> Self {
        Self {
            initial_step: 0.05,
            min_step: 2e-3,
            restarts: 2,
            restart_radius: 0.05,
            max_evaluations: 400,
            seed: 0x05EE_D629,
        }
    }
}

impl CompassSettings {
    /// Checks every setting's domain.
    pub fn validate(&self) -> Result<(), SynthesisError> {
        if !(self.initial_step > 0.0 && self.initial_step.is_finite()) {
            return Err(invalid(
                "initial_step",
                self.initial_step,
                "need a finite h_0 > 0",
            ));
        }
        if !(self.min_step > 0.0 && self.min_step <= self.initial_step) {
            return Err(invalid(
                "min_step",
                self.min_step,
                "need 0 < min_step ≤ initial_step",
            ));
        }
        if !(self.restart_radius >= 0.0 && self.restart_radius.is_finite()) {
            return Err(invalid(
                "restart_radius",
                self.restart_radius,
                "need a finite r ≥ 0",
            ));
        }
        if self.max_evaluations == 0 {
            return Err(invalid("max_evaluations", 0.0, "need at least 1"));
        }
        Ok(())
    }
}

/// Draws of a restart offset before the restart is skipped (each draw that changes the cyclic
/// order of the anchors is rejected).
const RESTART_DRAWS: usize = 64;

/// splitmix64: a tiny deterministic generator for the restart offsets.
pub(crate) struct SplitMix(pub(crate) u64);

impl SplitMix {
    pub(crate) fn next_unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        // 53 random bits → [0, 1).
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The generating set: ±(sum of e_k over a cyclic run of consecutive anchors) for every run of
/// length 1 and 2 (for n > 2) and the whole design (a rigid rotation), coordinates first.
fn generating_set(n: usize) -> Vec<Vec<f64>> {
    let mut runs = Vec::new();
    for len in 1..n.clamp(2, 3) {
        for first in 0..n {
            let mut v = vec![0.0; n];
            for k in 0..len {
                v[(first + k) % n] = 1.0;
            }
            runs.push(v);
        }
    }
    if n > 1 {
        runs.push(vec![1.0; n]);
    }
    runs.into_iter()
        .flat_map(|v| {
            let minus = v.iter().map(|x| -x).collect();
            [v, minus]
        })
        .collect()
}

/// One local compass search from (x, φ, area); returns the number of polls.
#[allow(clippy::too_many_arguments)]
fn local<O: Objective + ?Sized>(
    merit: &mut Merit<'_, O>,
    x: &mut [f64],
    phi: &mut f64,
    area: &mut f64,
    settings: &CompassSettings,
    directions: &[Vec<f64>],
    trial: &mut [f64],
) -> (usize, Termination) {
    let mut h = settings.initial_step;
    let mut last = 0;
    let mut polls = 0;
    while h >= settings.min_step {
        polls += 1;
        let mut moved = false;
        for k in 0..directions.len() {
            if merit.evaluations >= settings.max_evaluations {
                return (polls, Termination::Budget);
            }
            let dir = (last + k) % directions.len();
            for ((t, xi), v) in trial.iter_mut().zip(x.iter()).zip(&directions[dir]) {
                *t = xi + h * v;
            }
            if !merit.admissible(trial) {
                continue; // a poll past a neighbouring anchor: crossed cables
            }
            let a = merit.area(trial);
            let p = merit.merit(trial, a);
            if p < *phi {
                x.copy_from_slice(trial);
                *phi = p;
                *area = a;
                last = dir;
                moved = true;
                break;
            }
        }
        if !moved {
            h *= 0.5;
        }
    }
    (polls, Termination::Converged)
}

/// Maximises `objective` from `start` subject to eq. (6.29) (β_min = `min_separation`, rad,
/// exact penalty μ = `penalty`). Settings are assumed valid ([`CompassSettings::validate`]).
pub fn maximise<O: Objective + ?Sized>(
    objective: &mut O,
    start: &[f64],
    min_separation: f64,
    penalty: f64,
    settings: &CompassSettings,
) -> SynthesisResult {
    maximise_clear_of(objective, start, min_separation, penalty, settings, None)
}

/// [`maximise`], rejecting also the polls whose cables enter the polygon of the platform
/// attachments `platform` at the reference pose ([`super::design::cables_clear_platform`]).
pub fn maximise_clear_of<O: Objective + ?Sized>(
    objective: &mut O,
    start: &[f64],
    min_separation: f64,
    penalty: f64,
    settings: &CompassSettings,
    platform: Option<&[[f64; 2]]>,
) -> SynthesisResult {
    let n = start.len();
    let mut merit = Merit::new(objective, start, min_separation, penalty);
    merit.platform = platform.map(<[_]>::to_vec);
    let mut trial = vec![0.0; n];
    let directions = generating_set(n);
    let mut best = start.to_vec();
    let mut best_area = merit.area(&best);
    let mut best_phi = merit.merit(&best, best_area);
    let (mut iterations, mut termination) = local(
        &mut merit,
        &mut best,
        &mut best_phi,
        &mut best_area,
        settings,
        &directions,
        &mut trial,
    );
    let mut rng = SplitMix(settings.seed);
    let mut x = vec![0.0; n];
    for _ in 0..settings.restarts {
        if termination == Termination::Budget {
            break;
        }
        // Offsets that change the cyclic order of the anchors are drawn again.
        let mut admissible = false;
        for _ in 0..RESTART_DRAWS {
            for (xi, bi) in x.iter_mut().zip(&best) {
                *xi = bi + settings.restart_radius * (2.0 * rng.next_unit() - 1.0);
            }
            admissible = merit.admissible(&x);
            if admissible {
                break;
            }
        }
        if !admissible {
            continue;
        }
        let mut area = merit.area(&x);
        let mut phi = merit.merit(&x, area);
        let (polls, t) = local(
            &mut merit,
            &mut x,
            &mut phi,
            &mut area,
            settings,
            &directions,
            &mut trial,
        );
        iterations += polls;
        termination = t;
        if phi < best_phi {
            best.copy_from_slice(&x);
            best_phi = phi;
            best_area = area;
        }
    }
    let constraint_violation = super::design::separation_violation(&best, min_separation);
    SynthesisResult {
        design: best,
        area: best_area,
        constraint_violation,
        evaluations: Evaluations {
            function: merit.evaluations,
            gradient: 0,
        },
        iterations,
        termination,
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_functions::*;
    use super::*;

    #[test]
    fn generating_set_for_three_anchors() {
        let g = generating_set(3);
        // 3 coordinates, 3 pairs, 1 rotation, each with both signs.
        assert_eq!(g.len(), 14);
        assert_eq!(g[0], vec![1.0, 0.0, 0.0]);
        assert_eq!(g[1], vec![-1.0, 0.0, 0.0]);
        assert!(g.contains(&vec![1.0, 0.0, 1.0])); // the wrap pair (3, 1)
        assert!(g.contains(&vec![-1.0, -1.0, -1.0]));
        assert_eq!(generating_set(4).len(), 18);
        assert_eq!(generating_set(2).len(), 6);
        assert_eq!(generating_set(1).len(), 2);
    }

    #[test]
    fn restarts_are_deterministic_and_never_lose_the_best() {
        let c = [0.5, 2.5, 4.5];
        let s = CompassSettings::default();
        let run = || {
            maximise(
                &mut staircase(&c, 0.01),
                &[0.3, 2.8, 4.2],
                BETA_MIN,
                1e3,
                &s,
            )
        };
        let (a, b) = (run(), run());
        assert_eq!(a, b);
        let no_restart = CompassSettings {
            restarts: 0,
            ..CompassSettings::default()
        };
        let c0 = maximise(
            &mut staircase(&c, 0.01),
            &[0.3, 2.8, 4.2],
            BETA_MIN,
            1e3,
            &no_restart,
        );
        assert!(a.area >= c0.area);
        assert!(a.evaluations.function > c0.evaluations.function);
    }

    #[test]
    fn restarts_never_cross_cables() {
        // The bowl's peak [0.5, 4.5, 2.5] puts anchor 3 between anchors 1 and 2: reaching it from
        // [0.5, 2.5, 4.5] takes a jump past a neighbour, which wide restarts would make.
        let peak = [0.5, 4.5, 2.5];
        let start = [0.5, 2.5, 4.5];
        let s = CompassSettings {
            restarts: 40,
            restart_radius: 3.0,
            max_evaluations: 20_000,
            ..CompassSettings::default()
        };
        let r = maximise(&mut bowl(&peak), &start, BETA_MIN, 1e3, &s);
        assert!(super::super::design::same_cyclic_order(&r.design, &start));
        assert!(r.constraint_violation < 1e-12);
        // Without the order rule the search reaches the peak (area 1); with it, the best design of
        // the start's topology is worse than the bowl's crossed peak.
        assert!(r.area < 0.9, "area {} at {:?}", r.area, r.design);
        assert!(r.evaluations.function > 100);
    }

    #[test]
    fn budget_is_respected() {
        let c = [0.5, 2.5, 4.5];
        let s = CompassSettings {
            max_evaluations: 10,
            ..CompassSettings::default()
        };
        let r = maximise(&mut bowl(&c), &[0.0, 2.0, 4.0], BETA_MIN, 1e3, &s);
        assert_eq!(r.termination, Termination::Budget);
        assert!(r.evaluations.function <= 11);
    }
}
