//! Figures of the workspace area: thesis Figs. 6.4 and 6.5 (constant-orientation workspaces of
//! the 3- and 4-cable manipulators by discretisation, Algorithm 6.2) and Figs. 6.8 and 6.9 (the
//! same workspaces by the chord method, §6.4.3), each a 3 × 3 grid of panels: rows L1–L3
//! (Table 6.3), columns three orientations φ.

use super::Figure;
use cdpr::RobotDescription;
use cdpr::plot::{Panels, WorkspacePlot, save};
use cdpr_kinematics::{Pose, Robot};
use cdpr_tension::Method;
use cdpr_workspace::synthesis::objective::THESIS_LOADS;
use cdpr_workspace::{
    ChordSettings, ChordWorkspace, Criterion, Grid, GridWorkspace, PoseEvaluator, Region,
    chord_workspace, planar_workspace,
};
use nalgebra::DVector;
use std::path::Path;

/// Orientations of the columns: Fig. 6.4 (3 cables) as printed; Fig. 6.5 (4 cables) does not
/// list its cases in the thesis chapter, we choose φ ∈ {−0.2, 0, 0.2} (the synthesis range).
const PHI_3: [f64; 3] = [0.0, 0.05, 0.1];
const PHI_4: [f64; 3] = [-0.2, 0.0, 0.2];
const LOADS: [&str; 3] = ["L1", "L2", "L3"];
const PANEL: (u32, u32) = (440, 470);

/// Writes this area's figures into `dir`.
pub fn figures(dir: &Path) -> Result<Vec<Figure>, String> {
    let root = dir
        .parent()
        .and_then(Path::parent)
        .ok_or("figures directory must be <root>/docs/figures")?;
    let load = |name: &str| {
        RobotDescription::load(root.join("examples/robots").join(name)).map_err(|e| e.to_string())
    };
    let (r3, r4) = (load("tdpm-3.toml")?, load("tdpm-4.toml")?);
    let grid3 = grids(&r3.robot, 3, &PHI_3)?;
    let grid4 = grids(&r4.robot, 4, &PHI_4)?;
    let chord3 = chords(&r3.robot, 3, &PHI_3)?;
    let chord4 = chords(&r4.robot, 4, &PHI_4)?;
    let mut out = Vec::new();

    let file = "thesis-fig6.4-workspaces-3-cables-grid.png";
    draw(
        dir,
        file,
        "Fig. 6.4: 3-cable TDPM, discretisation (Alg. 6.2, m = 50)",
        &r3.robot,
        &PHI_3,
        &grid3,
        None,
    )?;
    out.push(Figure {
        file: file.into(),
        source: "Thesis Fig. 6.4".into(),
        caption: format!(
            "Constant-orientation workspaces of the 3-cable TDPM (Tables 6.1, 6.2; t ∈ [5, 100], \
             l_min = 0.1, |det J| ≥ 10⁻³, exact tensions) by discretisation with m = 50 over the \
             anchors' bounding box, columns φ = 0, 0.05, 0.1, rows L1–L3. The thesis stresses that \
             the workspace depends strongly on load and orientation and that at φ = 0 the singular \
             line x = 0 splits it into two regions bounded by D_min; ours shows the same. Areas \
             (rows L1–L3, columns φ): {}.",
            area_table(&grid3.iter().map(|w| w.area).collect::<Vec<_>>())
        ),
    });

    let file = "thesis-fig6.5-workspaces-4-cables-grid.png";
    draw(
        dir,
        file,
        "Fig. 6.5: 4-cable TDPM, discretisation (Alg. 6.2, m = 50, constrained ℓ2)",
        &r4.robot,
        &PHI_4,
        &grid4,
        None,
    )?;
    out.push(Figure {
        file: file.into(),
        source: "Thesis Fig. 6.5".into(),
        caption: format!(
            "Constant-orientation workspaces of the 4-cable TDPM by discretisation, m = 50 over \
             the anchors' bounding box [−1, 1] × [−0.5, 0.5], constrained ℓ2 tensions (eq. 6.17), \
             l_min = 0.1. The thesis chapter does not list the cases of this figure: we chose \
             φ = −0.2, 0, 0.2 (columns) × L1–L3 (rows). As the thesis observes, the 4-cable \
             workspace is larger than the 3-cable one and less sensitive to orientation and \
             load. The flat edges at y = −0.5 are the search box of Algorithm 6.2 step 2 (the \
             anchors' bounding box), not a constraint. Areas: {}.",
            area_table(&grid4.iter().map(|w| w.area).collect::<Vec<_>>())
        ),
    });

    let file = "thesis-fig6.8-workspaces-3-cables-chord.png";
    draw(
        dir,
        file,
        "Fig. 6.8: 3-cable TDPM, chord method (d = 0.05; 0.03, 0.02 where the thesis says)",
        &r3.robot,
        &PHI_3,
        &grid3,
        Some(&chord3),
    )?;
    out.push(Figure {
        file: file.into(),
        source: "Thesis Fig. 6.8".into(),
        caption: format!(
            "The cases of Fig. 6.4 by the chord method: d = 0.05, except d = 0.03 at φ = 0 under \
             L2 and L3 and d = 0.02 for L1 at φ = 0.05 (the thesis uses 0.02 for the small \
             left-hand part only; we use it for the whole workspace), ε^u = 10⁻⁸, every region \
             seeded from a 40 × 40 coarse grid. The thesis finds the chord boundaries more \
             accurate than the grid, and so do we: compare the smooth outlines, corners \
             included, with the staircase of Fig. 6.4. Chord areas (regions): {}; the m = 50 grid estimates of Fig. 6.4 \
             differ by {:.1} % at most.",
            chord_table(&chord3),
            max_rel_diff(&chord3, &grid3)
        ),
    });

    let file = "thesis-fig6.9-workspaces-4-cables-chord.png";
    draw(
        dir,
        file,
        "Fig. 6.9: 4-cable TDPM, chord method (d = 0.05; 0.02 for L3, φ = −0.2)",
        &r4.robot,
        &PHI_4,
        &grid4,
        Some(&chord4),
    )?;
    out.push(Figure {
        file: file.into(),
        source: "Thesis Fig. 6.9".into(),
        caption: format!(
            "The cases of our Fig. 6.5 by the chord method with d = 0.05 (d = 0.02 for L3 at \
             φ = −0.2, as in the thesis), constrained ℓ2 tensions. The thesis needed 30 s per \
             workspace with ℓ2 tensions; ours take milliseconds. Chord areas (regions): {}; the \
             m = 50 grid estimates differ by {:.1} % at most.",
            chord_table(&chord4),
            max_rel_diff(&chord4, &grid4)
        ),
    });
    out.push(bifurcation_figure(dir, &r3.robot)?);
    out.push(manipulators_figure(dir, &r3.robot, &r4.robot)?);
    Ok(out)
}

/// Thesis Fig. 6.2: the 3- and 4-cable manipulators of Tables 6.1 and 6.2, drawn from the
/// robot files at one pose.
fn manipulators_figure(dir: &Path, r3: &Robot, r4: &Robot) -> Result<Figure, String> {
    const POSE: (f64, f64, f64) = (0.2, -0.1, 0.3);
    let round = |x: f64| (x * 1e4).round() / 1e4 + 0.0; // + 0.0: no "-0"
    let point = |v: &nalgebra::Vector3<f64>| format!("[{}, {}]", round(v.x), round(v.y));
    let panel = |robot: &Robot| -> Result<WorkspacePlot, String> {
        let pose = Pose::planar(POSE.0, POSE.1, POSE.2);
        let kin = robot.inverse_kinematics(&pose).map_err(|e| e.to_string())?;
        let n = robot.cable_count();
        Ok(WorkspacePlot {
            title: format!("{n}-cable TDPM"),
            notes: vec![
                format!(
                    "frame anchors c^i: {}",
                    robot
                        .cables()
                        .iter()
                        .map(|c| point(&c.frame))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
                format!(
                    "platform attachments ā^i: {}",
                    robot
                        .cables()
                        .iter()
                        .map(|c| point(&c.platform))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
                format!(
                    "drawn at u = [{}, {}], φ_P = {} rad: cable lengths l_i = {}",
                    POSE.0,
                    POSE.1,
                    POSE.2,
                    kin.lengths()
                        .map(|l| format!("{l:.3}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            ],
            markers: kin
                .cables()
                .iter()
                .map(|c| (c.attachment_point.x, c.attachment_point.y))
                .collect(),
            frame: vec![(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)],
            axis_names: Some((
                "x (thesis length unit)".into(),
                "y (thesis length unit)".into(),
            )),
            ..WorkspacePlot::default()
        }
        .with_robot(robot, &pose))
    };
    let fig = Panels {
        notes: Vec::new(),
        title: "Fig. 6.2: the planar tendon-driven manipulators (Tables 6.1, 6.2)".into(),
        columns: 2,
        panel_size: (620, 660),
        panels: vec![panel(r3)?, panel(r4)?],
    };
    let file = "thesis-fig6.2-manipulators.png";
    save(&fig, dir.join(file)).map_err(|e| e.to_string())?;
    Ok(Figure {
        file: file.into(),
        source: "Thesis Fig. 6.2".into(),
        caption: format!(
            "The 3- and 4-cable manipulators of the thesis, drawn from examples/robots/tdpm-3.toml \
             and tdpm-4.toml: frame anchors c^i (Table 6.2) on the 2 × 2 frame, platform \
             attachments ā^i (Table 6.1, rings) at the pose u = [{}, {}], φ_P = {} rad, and the \
             cables between them.",
            POSE.0, POSE.1, POSE.2
        ),
    })
}

/// φ and the coarse chord d of Fig. 6.7.
const FIG67_PHI: f64 = 0.05;
const FIG67_CHORD: f64 = 0.2;

/// The workspaces of Fig. 6.7: [reference (d = 0.005), chords of d only, chords refined].
fn bifurcation_cases(robot: &Robot) -> Result<[ChordWorkspace; 3], String> {
    let eval = evaluator(robot, 3, 0)?;
    let region = Region::frame_bounding_box(robot);
    let levels = ChordSettings::default().refinement_levels;
    let run = |chord: f64, refinement_levels: u32| {
        let settings = ChordSettings {
            chord,
            refinement_levels,
            ..ChordSettings::default()
        };
        chord_workspace(&eval, FIG67_PHI, &region, &settings).map_err(|e| e.to_string())
    };
    Ok([
        run(0.005, levels)?,
        run(FIG67_CHORD, 0)?,
        run(FIG67_CHORD, levels)?,
    ])
}

/// Thesis Fig. 6.7: why the chord method needs its bifurcation-point procedure. The 3-cable
/// workspace under L1 at φ = 0.05 by chords of d = 0.1 (twice the thesis' d, so that the effect
/// shows), (a) without refinement and (b) with the chord halved near sharp turns (Appendix C,
/// reconstructed: `ChordSettings::refinement_levels`), against a fine reference (d = 0.005).
fn bifurcation_figure(dir: &Path, robot: &Robot) -> Result<Figure, String> {
    let [reference, plain, refined] = bifurcation_cases(robot)?;
    let outline = |w: &ChordWorkspace| -> Vec<Vec<(f64, f64)>> {
        w.boundaries
            .iter()
            .map(|b| b.vertices.iter().map(|v| (v[0], v[1])).collect())
            .collect()
    };
    let closed = |w: &ChordWorkspace| -> Vec<Vec<(f64, f64)>> {
        outline(w)
            .into_iter()
            .map(|mut b| {
                if let Some(&first) = b.first() {
                    b.push(first);
                }
                b
            })
            .collect()
    };
    let bifurcations: Vec<(f64, f64)> = refined
        .boundaries
        .iter()
        .flat_map(|b| {
            b.bifurcations
                .iter()
                .map(|&i| (b.vertices[i][0], b.vertices[i][1]))
        })
        .collect();
    let error = |w: &ChordWorkspace| 100.0 * (w.area - reference.area).abs() / reference.area;
    let vertices =
        |w: &ChordWorkspace| w.boundaries.iter().map(|b| b.vertices.len()).sum::<usize>();
    let panel = |title: &str, w: &ChordWorkspace, markers: Vec<(f64, f64)>| {
        WorkspacePlot {
            title: title.into(),
            boundaries: outline(w),
            fill_boundaries: true,
            chained_lines: closed(&reference),
            markers,
            notes: vec![format!(
                "A = {:.4} ({:.2} % off the reference {:.4}), {} region(s), {} chord points, \
                 {} evaluations",
                w.area,
                error(w),
                reference.area,
                w.boundaries.len(),
                vertices(w),
                w.evaluations
            )],
            frame: vec![(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)],
            axis_names: Some((
                "x (thesis length unit)".into(),
                "y (thesis length unit)".into(),
            )),
            ..WorkspacePlot::default()
        }
        .with_robot(robot, &Pose::planar(0.0, 0.0, FIG67_PHI))
    };
    let fig = Panels {
        notes: Vec::new(),
        title:
            "Fig. 6.7: bifurcation points and the chord method (3 cables, L1, φ = 0.05, d = 0.2)"
                .into(),
        columns: 2,
        panel_size: (620, 660),
        panels: vec![
            panel("(a) chords of d only", &plain, Vec::new()),
            panel(
                "(b) chord halved near turns; bifurcation points (rings)",
                &refined,
                bifurcations.clone(),
            ),
        ],
    };
    let file = "thesis-fig6.7-bifurcation-points.png";
    save(&fig, dir.join(file)).map_err(|e| e.to_string())?;
    Ok(Figure {
        file: file.into(),
        source: "Thesis Fig. 6.7".into(),
        caption: format!(
            "The chord method maps the boundary with chords of fixed length d, so a boundary \
             corner (a bifurcation point, where two constraints meet) is cut off (thesis \
             Fig. 6.7(a)). 3-cable TDPM, load L1, φ = 0.05, exact tensions, |det J| ≥ 10⁻³, \
             l_min = 0.1, d = 0.2 (four times the thesis' 0.05, to make the effect visible); chained \
             line: a fine reference boundary (d = 0.005, A = {:.4}, {} regions). (a) Chords of d \
             only: A = {:.4}, {:.2} % off, {} region(s) ({} walk(s) abandoned: a region thinner \
             than the chord cannot be followed). (b) With our reconstruction of the thesis' bifurcation \
             procedure (its Appendix C is not in the thesis chapter): the chord is halved, down to d/2⁶, \
             where the boundary turns by more than 0.3 rad, and the vertex that remains at the \
             finest chord is reported as a bifurcation point: A = {:.4}, {:.2} % off, {} \
             bifurcation point(s) marked.",
            reference.area,
            reference.boundaries.len(),
            plain.area,
            error(&plain),
            plain.boundaries.len(),
            plain.abandoned,
            refined.area,
            error(&refined),
            bifurcations.len()
        ),
    })
}

/// The evaluator of Figs. 6.4–6.9 for load index `l`.
fn evaluator(robot: &Robot, cables: usize, l: usize) -> Result<PoseEvaluator, String> {
    let mut criteria = vec![
        Criterion::TensionFeasible {
            method: if cables == 3 {
                Method::Exact
            } else {
                Method::L2
            },
            wrench: DVector::from_row_slice(&THESIS_LOADS[l]),
        },
        Criterion::MinCableLength(0.1),
    ];
    if cables == 3 {
        criteria.push(Criterion::MinJacobianDeterminant(1e-3));
    }
    let bounds =
        cdpr_tension::TensionBounds::uniform(cables, 5.0, 100.0).map_err(|e| e.to_string())?;
    PoseEvaluator::new(robot.clone(), bounds, criteria).map_err(|e| e.to_string())
}

/// The nine grid workspaces, row-major (load, φ).
fn grids(robot: &Robot, cables: usize, phis: &[f64; 3]) -> Result<Vec<GridWorkspace>, String> {
    let grid = Grid::over_frame(robot, 50);
    let mut out = Vec::new();
    for l in 0..3 {
        let eval = evaluator(robot, cables, l)?;
        for &phi in phis {
            out.push(planar_workspace(&eval, phi, &grid).map_err(|e| e.to_string())?);
        }
    }
    Ok(out)
}

/// Chord length used by the thesis for each case (§6.4.3).
fn chord_length(cables: usize, l: usize, phi: f64) -> f64 {
    match (cables, l) {
        (3, 1 | 2) if phi == 0.0 => 0.03,
        (3, 0) if phi == 0.05 => 0.02,
        (4, 2) if phi == -0.2 => 0.02,
        _ => 0.05,
    }
}

/// The nine chord workspaces, row-major (load, φ).
fn chords(robot: &Robot, cables: usize, phis: &[f64; 3]) -> Result<Vec<ChordWorkspace>, String> {
    let region = Region::frame_bounding_box(robot);
    let mut out = Vec::new();
    for l in 0..3 {
        let eval = evaluator(robot, cables, l)?;
        for &phi in phis {
            let settings = ChordSettings {
                chord: chord_length(cables, l, phi),
                ..ChordSettings::default()
            };
            out.push(chord_workspace(&eval, phi, &region, &settings).map_err(|e| e.to_string())?);
        }
    }
    Ok(out)
}

/// Draws a 3 × 3 figure; with `chord`, the polygons filled over faint grid cells.
fn draw(
    dir: &Path,
    file: &str,
    title: &str,
    robot: &Robot,
    phis: &[f64; 3],
    grid: &[GridWorkspace],
    chord: Option<&[ChordWorkspace]>,
) -> Result<(), String> {
    let mut panels = Vec::new();
    for (l, load) in LOADS.iter().enumerate() {
        for (k, &phi) in phis.iter().enumerate() {
            let i = 3 * l + k;
            let ws = &grid[i];
            let ext = ws.grid.region.extent();
            let m = ws.grid.resolution as f64;
            let (note, boundaries, feasible) = match chord {
                None => (
                    format!("A = {:.4} ({} points)", ws.area, ws.feasible_points),
                    Vec::new(),
                    ws.feasible_positions().map(|p| (p.x, p.y)).collect(),
                ),
                Some(c) => (
                    format!(
                        "A = {:.4}, {} region(s), d = {}",
                        c[i].area,
                        regions(&c[i]),
                        chord_length(if phis == &PHI_3 { 3 } else { 4 }, l, phi)
                    ),
                    c[i].boundaries
                        .iter()
                        .map(|b| b.vertices.iter().map(|v| (v[0], v[1])).collect())
                        .collect(),
                    Vec::new(),
                ),
            };
            panels.push(
                WorkspacePlot {
                    title: format!("{load}, φ = {phi}"),
                    feasible_points: feasible,
                    cell: (ext.x / m, ext.y / m),
                    fill_boundaries: chord.is_some(),
                    boundaries,
                    notes: vec![note],
                    frame: vec![(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)],
                    axis_names: Some((
                        "x (thesis length unit)".into(),
                        "y (thesis length unit)".into(),
                    )),
                    ..WorkspacePlot::default()
                }
                .with_robot(robot, &Pose::planar(0.0, 0.0, phi)),
            );
        }
    }
    let fig = Panels {
        notes: Vec::new(),
        title: title.into(),
        columns: 3,
        panel_size: PANEL,
        panels,
    };
    save(&fig, dir.join(file)).map_err(|e| e.to_string())
}

fn regions(c: &ChordWorkspace) -> usize {
    c.boundaries
        .iter()
        .filter(|b| b.signed_area() > 0.0)
        .count()
}

fn area_table(a: &[f64]) -> String {
    (0..3)
        .map(|l| {
            format!(
                "{} [{}]",
                LOADS[l],
                a[3 * l..3 * l + 3]
                    .iter()
                    .map(|v| format!("{v:.4}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        })
        .collect::<Vec<_>>()
        .join("; ")
}

fn chord_table(c: &[ChordWorkspace]) -> String {
    (0..3)
        .map(|l| {
            format!(
                "{} [{}]",
                LOADS[l],
                c[3 * l..3 * l + 3]
                    .iter()
                    .map(|w| format!("{:.4} ({})", w.area, regions(w)))
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        })
        .collect::<Vec<_>>()
        .join("; ")
}

fn max_rel_diff(c: &[ChordWorkspace], g: &[GridWorkspace]) -> f64 {
    c.iter()
        .zip(g)
        .filter(|(c, _)| c.area > 0.0)
        .map(|(c, g)| 100.0 * (c.area - g.area).abs() / c.area)
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    /// Fig. 6.7's claim: the refinement recovers the corners the plain chords cut off.
    #[test]
    fn bifurcation_refinement_recovers_the_corners() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let r3 = cdpr::RobotDescription::load(root.join("examples/robots/tdpm-3.toml")).unwrap();
        let [reference, plain, refined] = super::bifurcation_cases(&r3.robot).unwrap();
        let err = |a: f64| (a - reference.area).abs() / reference.area;
        assert!(
            err(refined.area) < 0.01,
            "{} vs {}",
            refined.area,
            reference.area
        );
        assert!(err(plain.area) > 5.0 * err(refined.area));
        let corners: usize = refined
            .boundaries
            .iter()
            .map(|b| b.bifurcations.len())
            .sum();
        assert!(corners >= 4, "{corners} bifurcation points");
        assert_eq!(reference.boundaries.len(), 2);
    }

    /// Writes the figures into docs/figures (run with `cargo test -p xtask --release
    /// figures_workspace -- --ignored --nocapture` and look at them).
    #[test]
    #[ignore]
    fn figures_workspace() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .parent()
            .unwrap();
        let dir = root.join("docs/figures");
        std::fs::create_dir_all(&dir).unwrap();
        let t = std::time::Instant::now();
        let figs = super::figures(&dir).unwrap();
        eprintln!(
            "{} figures in {:.2} s",
            figs.len(),
            t.elapsed().as_secs_f64()
        );
        for f in figs {
            eprintln!("{}: {}", f.file, f.caption);
        }
    }
}
