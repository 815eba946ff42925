//! Figures of the polytope area: Krut, Company & Pierrot 2004, Fig. 3 (the admissible joint force space, the tension
//! box of the 3-motor robot), Fig. 4 (the operational force polygon of the 3-motor point robot
//! with its largest centred circle and ellipse), Fig. 8 (the candidate frontiers of Krut's
//! step 4 with the borders of test (15)), Fig. 9 (maximum isotropic force of
//! the 3-motor robot over the plane) and Fig. 10 (4, 5 and 6 motors regularly spaced on a
//! circle), from `examples/robots/krut-{3,4,5,6}.toml` (motors at l = 1000 mm = 1 m, tensions in
//! [50, 500] N; lengths in metres).

use super::Figure;
use cdpr::RobotDescription;
use cdpr::kinematics::Pose;
use cdpr::plot::{CandidateLinesPlot, ForcePolygonPlot, HeatMap, Panels, TensionBoxPlot, save};
use cdpr::polytope::{
    InscribedEllipse, IsotropicForce, hyperplane_shifting, isotropic_force, krut_vertex_projection,
    largest_inscribed_ellipse,
};
use std::path::Path;

/// Grid intervals per side: 121 × 121 poses over [−1, 1]² m (the paper: l = 1000 mm).
const GRID: usize = 120;
/// Half-width of the mapped square (the motors' circle radius, m).
const HALF: f64 = 1.0;

/// Writes this area's figures into `dir`.
pub fn figures(dir: &Path) -> Result<Vec<Figure>, String> {
    let root = dir
        .parent()
        .and_then(Path::parent)
        .ok_or("figures directory must be <root>/docs/figures")?;
    let mut out = vec![krut2004_fig3(root, dir)?, krut2004_fig4(root, dir)?];
    out.push(krut2004_fig8(root, dir)?);
    out.extend(render(root, dir)?);
    Ok(out)
}

/// The off-centre pose of Fig. 4 (m): inside the workspace, where the polygon is far from
/// centred on the origin.
const FIG4_POSE: (f64, f64) = (0.3, -0.2);

/// One pose of Fig. 4: the figure panel, the index f_min (eq. 19), the ellipse and the panel's
/// caption text.
fn fig4_panel(
    robot: &RobotDescription,
    (x, y): (f64, f64),
) -> Result<(ForcePolygonPlot, String), String> {
    let err = |e: &dyn std::fmt::Display| e.to_string();
    let motion = robot.robot.motion();
    let w = robot
        .robot
        .inverse_kinematics(&Pose::point(x, y, 0.0))
        .map_err(|e| err(&e))?
        .wrench_matrix();
    let aws = hyperplane_shifting::available_wrench_set(&w, &robot.bounds).map_err(|e| err(&e))?;
    let f_min = isotropic_force(&aws, motion).map_err(|e| err(&e))?;
    let ellipse: InscribedEllipse = largest_inscribed_ellipse(&aws)
        .map_err(|e| err(&e))?
        .ok_or(format!(
            "({x}, {y}): the origin is outside the force polygon"
        ))?;
    // Independent checks: every vertex is W t for some admissible t (the polygon is the image of
    // the tension box, so each vertex must be reached by a box corner), the ellipse lies inside
    // every facet, and its area is at least the circle's (the circle is a candidate ellipse).
    let vertices = aws.vertices().ok_or("unbounded force polygon")?;
    let n = robot.robot.cables().len();
    for v in vertices {
        let hit = (0..1usize << n).any(|mask| {
            let t = nalgebra::DVector::from_fn(n, |i, _| {
                if mask >> i & 1 == 1 {
                    robot.bounds.max()[i]
                } else {
                    robot.bounds.min()[i]
                }
            });
            (&w * t - v).norm() < 1e-6 * v.norm().max(1.0)
        });
        if !hit {
            return Err(format!(
                "({x}, {y}): vertex {v} is not the image of a box corner"
            ));
        }
    }
    for f in aws.facets() {
        let nrm = nalgebra::Vector2::new(f.normal[0], f.normal[1]);
        if ellipse.support(&nrm) > f.offset * (1.0 + 1e-6) {
            return Err(format!("({x}, {y}): the ellipse crosses a facet"));
        }
    }
    if ellipse.area() < std::f64::consts::PI * f_min * f_min * (1.0 - 1e-6) {
        return Err(format!(
            "({x}, {y}): the ellipse is smaller than the circle"
        ));
    }
    let mut fig = ForcePolygonPlot::operational(&aws, Some(&ellipse))
        .ok_or("the force polygon of a point2 robot must be 2-D")?;
    // Outward normals of the highlighted edges (the direction from the origin to each edge's
    // line), in [0°, 360°), and the facets the ellipse touches (support ≥ (1 − 10⁻⁵) d_k).
    let mut normals: Vec<f64> = fig
        .highlighted_edges
        .0
        .iter()
        .map(|&((ax, ay), (bx, by))| {
            let (nx, ny) = (by - ay, ax - bx);
            let s = if nx * ax + ny * ay >= 0.0 { 1.0 } else { -1.0 };
            (s * ny).atan2(s * nx).to_degrees().rem_euclid(360.0)
        })
        .collect();
    normals.sort_by(f64::total_cmp);
    let touching: Vec<String> = normals
        .iter()
        .map(|a| format!("{}°", (a.round() as i64) % 360))
        .collect();
    let ellipse_contacts = aws
        .facets()
        .iter()
        .filter(|f| {
            let nrm = nalgebra::Vector2::new(f.normal[0], f.normal[1]);
            ellipse.support(&nrm) >= f.offset * (1.0 - 1e-5)
        })
        .count();
    fig.title = if x == 0.0 && y == 0.0 {
        "centre (0, 0) m".into()
    } else {
        format!("off-centre ({x}, {y}) m")
    };
    let [a, b] = ellipse.semi_axes;
    let text = format!(
        "at ({x}, {y}) m the polygon has {} vertices, f_min = {f_min:.1} N, the circle touches \
         {} facet(s) (outward normals {}), and the ellipse has semi-axes {a:.1} and {b:.1} N{}",
        vertices.len(),
        touching.len(),
        touching.join(", "),
        if a - b <= 1e-6 * a {
            " (the circle itself)".to_string()
        } else {
            format!(
                ", major axis at {:.1}°, area {:.2}× the circle's, touching {ellipse_contacts} \
                 facets",
                ellipse.angle.to_degrees(),
                ellipse.area() / (std::f64::consts::PI * f_min * f_min)
            )
        }
    );
    Ok((fig, text))
}

/// Krut, Company & Pierrot 2004, Fig. 4: the available force polygon of krut-3 at the centre and off-centre.
fn krut2004_fig4(root: &Path, out: &Path) -> Result<Figure, String> {
    let robot = RobotDescription::load(root.join("examples/robots/krut-3.toml"))
        .map_err(|e| e.to_string())?;
    let (centre, c_text) = fig4_panel(&robot, (0.0, 0.0))?;
    let (off, o_text) = fig4_panel(&robot, FIG4_POSE)?;
    let fig = Panels {
        notes: Vec::new(),
        title: "Krut, Company & Pierrot 2004, Fig. 4: available force polygon {W t : 50 ≤ t ≤ 500 N} of the 3-motor \
                robot (krut-3), largest centred circle and ellipse"
            .into(),
        columns: 2,
        panel_size: (1050, 820),
        panels: vec![centre, off],
    };
    let file = "krut2004-fig4-force-polygon.png";
    save(&fig, out.join(file)).map_err(|e| e.to_string())?;
    Ok(Figure {
        file: file.into(),
        source: "Krut, Company & Pierrot 2004, Fig. 4".into(),
        caption: format!(
            "The paper sketches the admissible operational force polygon (n = 2) with a circle \
             (radius: the largest force the machine can resist in every direction) and an \
             ellipse (the largest-area centred ellipse, §IV-C). Ours is computed for Krut, Company & Pierrot's (2004) \
             3-motor point robot (examples/robots/krut-3.toml: motors at l = 1000 mm = 1 m, 30°, 150°, \
             270°, t ∈ [50, 500] N) at the centre and at an off-centre pose of our choice: the \
             polygon {{W t}} from its vertices (hyperplane shifting; every vertex checked to be \
             the image of a tension-box corner), the origin-centred circle of radius f_min \
             (eq. 19), the facet(s) at distance f_min highlighted, and the largest centred \
             ellipse (a second-order cone program; checked inside every facet and no smaller \
             than the circle). The polygon is the set of forces the cables apply; the loads the \
             platform can resist are its mirror image −{{W t}}, with the same circle and \
             ellipse. Centre: {c_text}. Off-centre: {o_text}. As the paper notes, the ellipse \
             says little once the polygon is not centred on the origin: off-centre it becomes a \
             long thin ellipse squeezed against the facets nearest the origin."
        ),
    })
}

/// "(t₁, t₂, t₃)" of the box vertex `bits` (bit j set: t_j = t_max,j).
fn vertex_label(robot: &RobotDescription, bits: usize) -> String {
    let t: Vec<String> = (0..robot.robot.cables().len())
        .map(|j| {
            let b = if bits >> j & 1 == 1 {
                robot.bounds.max()
            } else {
                robot.bounds.min()
            };
            format!("{}", b[j])
        })
        .collect();
    format!("({})", t.join(", "))
}

/// Krut, Company & Pierrot 2004, Fig. 3: the admissible joint force space {t : t_min ≤ t ≤ t_max} of krut-3.
fn krut2004_fig3(root: &Path, out: &Path) -> Result<Figure, String> {
    let robot = RobotDescription::load(root.join("examples/robots/krut-3.toml"))
        .map_err(|e| e.to_string())?;
    let (lo, hi) = (robot.bounds.min(), robot.bounds.max());
    if lo.len() != 3 {
        return Err(format!("krut-3 has {} cables", lo.len()));
    }
    let mut fig = TensionBoxPlot::new([lo[0], lo[1], lo[2]], [hi[0], hi[1], hi[2]]);
    fig.title =
        "Krut, Company & Pierrot 2004, Fig. 3: admissible joint force space, m = 3 (krut-3)".into();
    fig.notes = vec![
        format!(
            "the box t_min ≤ t ≤ t_max of eq. (3), t_j ∈ [{}, {}] N: 2³ = 8 vertices, 12 edges, \
             6 faces",
            lo[0], hi[0]
        ),
        format!(
            "oblique orthographic view (azimuth {}°, elevation {}°); the three edges at the \
             hidden vertex {} dashed",
            fig.view.0,
            fig.view.1,
            vertex_label(&robot, 0)
        ),
    ];
    let file = "krut2004-fig3-tension-box.png";
    save(&fig, out.join(file)).map_err(|e| e.to_string())?;
    Ok(Figure {
        file: file.into(),
        source: "Krut, Company & Pierrot 2004, Fig. 3".into(),
        caption: format!(
            "The paper draws the admissible joint force space, the box (3) t_min ≤ t ≤ t_max, \
             for m = 3 motors. Ours is the box of Krut, Company & Pierrot's (2004) 3-motor robot \
             (examples/robots/krut-3.toml, t_j ∈ [{}, {}] N) in an oblique orthographic view \
             (azimuth {}° from t₁ towards t₂, elevation {}°), with the three visible faces \
             shaded, the three edges at the hidden vertex {} dashed, the 2³ = 8 vertices labelled \
             with the bounds they take (t₁, t₂, t₃) and the axes t₁, t₂, t₃ drawn from the origin \
             with ticks at t_min and t_max. An isometric view would put {} exactly in front of \
             {}: the viewing direction (1, 1, 1) is also the kernel of W at the centre pose, \
             which is why those two vertices project onto the same point in Fig. 8.",
            lo[0],
            hi[0],
            fig.view.0,
            fig.view.1,
            vertex_label(&robot, 0),
            vertex_label(&robot, 7),
            vertex_label(&robot, 0),
        ),
    })
}

/// Krut, Company & Pierrot 2004, Fig. 8: the projected box vertices of krut-3 at the centre, every candidate line
/// through two of them (Krut's step 4) and the borders of test (15).
fn krut2004_fig8(root: &Path, out: &Path) -> Result<Figure, String> {
    let err = |e: &dyn std::fmt::Display| e.to_string();
    let robot =
        RobotDescription::load(root.join("examples/robots/krut-3.toml")).map_err(|e| err(&e))?;
    let n = robot.robot.cables().len();
    let w = robot
        .robot
        .inverse_kinematics(&Pose::point(0.0, 0.0, 0.0))
        .map_err(|e| err(&e))?
        .wrench_matrix();
    let candidates =
        krut_vertex_projection::candidate_hyperplanes(&w, &robot.bounds).map_err(|e| err(&e))?;
    let aws = hyperplane_shifting::available_wrench_set(&w, &robot.bounds).map_err(|e| err(&e))?;
    // The projected vertices f = W τ of the 2ⁿ box vertices.
    let images: Vec<(f64, f64)> = (0..1usize << n)
        .map(|bits| {
            let t = nalgebra::DVector::from_fn(n, |j, _| {
                if bits >> j & 1 == 1 {
                    robot.bounds.max()[j]
                } else {
                    robot.bounds.min()[j]
                }
            });
            let f = &w * t;
            (f[0], f[1])
        })
        .collect();
    let size = images.iter().map(|p| p.0.hypot(p.1)).fold(0.0, f64::max);
    let tol = 1e-9 * size.max(1.0);
    // Independent checks: every line passes through its two points, each border has all the
    // points on its inner side and is a facet found by hyperplane shifting, each other line has
    // points strictly on both sides.
    for c in &candidates {
        let Some(f) = &c.hyperplane else { continue };
        let side: Vec<f64> = images
            .iter()
            .map(|p| f.normal[0] * p.0 + f.normal[1] * p.1 - f.offset)
            .collect();
        if c.vertices.iter().any(|&v| side[v].abs() > tol) {
            return Err(format!("candidate {:?} misses its vertices", c.vertices));
        }
        let one_sided = side.iter().all(|&x| x <= tol);
        let facet = aws
            .facets()
            .iter()
            .any(|g| (&g.normal - &f.normal).amax() < 1e-9 && (g.offset - f.offset).abs() < tol);
        if c.border != one_sided || c.border != facet {
            return Err(format!(
                "candidate {:?}: border {} but one-sided {one_sided}, facet {facet}",
                c.vertices, c.border
            ));
        }
    }
    let count = candidates.len();
    let no_line = candidates.iter().filter(|c| c.hyperplane.is_none()).count();
    let borders = candidates.iter().filter(|c| c.border).count();
    // Distinct lines: candidates on the same line (normal up to sign, offset with it) merged.
    let mut distinct: Vec<(f64, f64, f64)> = Vec::new();
    let mut through_origin = 0;
    for f in candidates.iter().filter_map(|c| c.hyperplane.as_ref()) {
        let s = if f.normal[0] < -1e-12 || (f.normal[0].abs() <= 1e-12 && f.normal[1] < 0.0) {
            -1.0
        } else {
            1.0
        };
        let key = (s * f.normal[0], s * f.normal[1], s * f.offset);
        if f.offset.abs() <= tol {
            through_origin += 1;
        }
        if !distinct.iter().any(|d| {
            (d.0 - key.0).abs() < 1e-9 && (d.1 - key.1).abs() < 1e-9 && (d.2 - key.2).abs() < tol
        }) {
            distinct.push(key);
        }
    }
    let origin_lines = distinct.iter().filter(|d| d.2.abs() <= tol).count();
    let lines = count - no_line;
    let coincident: Vec<String> = candidates
        .iter()
        .filter(|c| c.hyperplane.is_none())
        .map(|c| {
            let v: Vec<String> = c
                .vertices
                .iter()
                .map(|&b| vertex_label(&robot, b))
                .collect();
            v.join(" and ")
        })
        .collect();
    let polygon: Vec<(f64, f64)> = aws
        .vertices()
        .ok_or("unbounded force polygon")?
        .iter()
        .map(|v| (v[0], v[1]))
        .collect();
    let fig = CandidateLinesPlot {
        title: "Krut, Company & Pierrot 2004, Fig. 8: all the possible frontiers of the force polygon (krut-3, centre)"
            .into(),
        labels: ("f_x (N)".into(), "f_y (N)".into()),
        notes: vec![
            format!(
                "{} box vertices τ mapped to f = W τ; of the C({}, 2) = {count} pairs, \
                 {no_line} coincide ({}) and give no line",
                images.len(),
                images.len(),
                coincident.join("; ")
            ),
            format!(
                "{lines} candidate lines (step 4, eqs. (10)–(14)) on {} distinct lines; \
                 {through_origin} of them, on {origin_lines} lines, pass through the origin \
                 (T_k singular in eq. (14))",
                distinct.len()
            ),
            format!(
                "border test (15): {borders} candidates have every point on one side: the {} \
                 sides of the polygon",
                aws.facets().len()
            ),
        ],
        polygon_label: "available force polygon {W t}".into(),
        polygon,
        lines: candidates
            .iter()
            .filter_map(|c| {
                let f = c.hyperplane.as_ref()?;
                Some(((f.normal[0], f.normal[1]), f.offset, c.border))
            })
            .collect(),
        line_labels: (
            format!("candidate lines ({lines})"),
            format!("borders ({borders}), test (15)"),
        ),
        points: images
            .iter()
            .enumerate()
            .map(|(bits, &p)| (p, vertex_label(&robot, bits)))
            .collect(),
        points_label: "projected vertex W τ,\nlabelled τ = (t₁, t₂, t₃) in N".into(),
        origin: false,
    };
    let file = "krut2004-fig8-candidate-frontiers.png";
    save(&fig, out.join(file)).map_err(|e| e.to_string())?;
    Ok(Figure {
        file: file.into(),
        source: "Krut, Company & Pierrot 2004, Fig. 8".into(),
        caption: format!(
            "The paper draws every hyperplane through n = 2 of the 2^m projected box vertices \
             τ_r (step 4, a line for n = 2): the possible frontiers, among which the border test \
             (15) keeps the sides. Ours is for Krut, Company & Pierrot's (2004) 3-motor robot \
             (examples/robots/krut-3.toml, t ∈ [50, 500] N) at the centre pose, drawn in the \
             operational force plane f = W τ = U S τ_r (step 6: a linear image of the τ_r \
             plane, so points, lines and sides correspond), as listed by \
             `krut_vertex_projection::candidate_hyperplanes`, the code path of our Krut \
             implementation. The {} projected vertices are labelled with their tensions; of the \
             C({}, 2) = {count} pairs, {no_line} coincide ({}: at the centre Σ w_j = 0, so \
             W (1, 1, 1) = 0) and give no line; the other {lines} candidate lines (thin grey, \
             clipped to the plot; several candidates share a line: {} distinct lines) include \
             {through_origin} on the {origin_lines} diameters through the origin, where the \
             paper's eq. (14) has no u_k (we compute every line from vertex differences); \
             {borders} pass the border test (15) and are highlighted: they are the {} sides of \
             the regular hexagon of Fig. 4 (each checked to have all 8 points on its inner side \
             and to be a facet found independently by hyperplane shifting).",
            images.len(),
            images.len(),
            coincident.join("; "),
            distinct.len(),
            aws.facets().len(),
        ),
    })
}

/// The map of one robot: (values row-major x fastest, centre value, max, fraction ≥ 0).
struct Map {
    values: Vec<f64>,
    centre: f64,
    max: f64,
    positive: f64,
}

fn map(robot: &RobotDescription) -> Result<Map, String> {
    let mut index = IsotropicForce::new(&robot.robot, &robot.bounds).map_err(|e| e.to_string())?;
    let k = GRID + 1;
    let at = |i: usize| -HALF + 2.0 * HALF * i as f64 / GRID as f64;
    let mut values = Vec::with_capacity(k * k);
    for j in 0..k {
        for i in 0..k {
            // Undefined where a cable has zero length (at a motor): NaN, drawn white.
            values.push(
                index
                    .force_at_pose(&Pose::point(at(i), at(j), 0.0))
                    .unwrap_or(f64::NAN),
            );
        }
    }
    let centre = index
        .force_at_pose(&Pose::point(0.0, 0.0, 0.0))
        .map_err(|e| e.to_string())?;
    let max = values
        .iter()
        .copied()
        .filter(|v| !v.is_nan())
        .fold(f64::NEG_INFINITY, f64::max);
    let positive = values.iter().filter(|&&v| v >= 0.0).count() as f64 / values.len() as f64;
    Ok(Map {
        values,
        centre,
        max,
        positive,
    })
}

/// Renders the four maps of `root/examples/robots/krut-N.toml` into `out`.
fn render(root: &Path, out: &Path) -> Result<Vec<Figure>, String> {
    // Hand-derived centre values: s_i = t_i − 275 ∈ [−225, 225] and Σ 275 u_i = 0, so the AWS
    // is the zonotope Σ s_i u_i; its facet normal ⟂ u_k is at distance 225 Σ_j |sin(θ_j − θ_k)|.
    let hand = |n: usize| -> f64 {
        (1..n)
            .map(|j| {
                225.0
                    * (2.0 * std::f64::consts::PI * j as f64 / n as f64)
                        .sin()
                        .abs()
            })
            .sum()
    };
    let mut figs = Vec::new();
    let mut centres = Vec::new();
    for n in 3..=6 {
        let robot = RobotDescription::load(root.join(format!("examples/robots/krut-{n}.toml")))
            .map_err(|e| e.to_string())?;
        let m = map(&robot)?;
        if (m.centre - hand(n)).abs() > 1e-5 * hand(n) {
            return Err(format!(
                "krut-{n}: centre value {} differs from the hand-derived {}",
                m.centre,
                hand(n)
            ));
        }
        centres.push(m.centre);
        let fig = HeatMap {
            title: format!(
                "Krut, Company & Pierrot 2004, Fig. {}: maximum isotropic force, {n} motors",
                if n == 3 { 9 } else { 10 }
            ),
            labels: ("x (m)".into(), "y (m)".into()),
            value_label: "maximum isotropic force (N)".into(),
            x_range: (-HALF, HALF),
            y_range: (-HALF, HALF),
            shape: (GRID + 1, GRID + 1),
            values: m.values,
            blank_below: 0.0,
            markers: robot
                .robot
                .cables()
                .iter()
                .map(|c| (c.frame.x, c.frame.y))
                .collect(),
            outlines: Vec::new(),
            highlight: vec![((0.0, 0.0), format!("{:.1} N", m.centre))],
        };
        // The paper's Fig. 9 is the 3-motor map, Fig. 10 the 4- to 6-motor ones.
        let number = if n == 3 { 9 } else { 10 };
        let file = format!("krut2004-fig{number}-isotropic-force-{n}-motors.png");
        save(&fig, out.join(&file)).map_err(|e| e.to_string())?;
        let common = format!(
            "Our map: {}² positions over [−1, 1]² m, white where the index is negative \
             (the pose cannot hold even a zero load with t ≥ 50 N) or undefined (at a motor); \
             tensions in [50, 500] N. Centre value {:.1} N (hand-derived zonotope apothem {:.1} N), \
             maximum {:.1} N, {:.0} % of the square has a non-negative index.",
            GRID + 1,
            m.centre,
            hand(n),
            m.max,
            100.0 * m.positive
        );
        figs.push(if n == 3 {
            Figure {
                file,
                source: "Krut, Company & Pierrot 2004, Fig. 9".into(),
                caption: format!(
                    "The paper maps the maximum isotropic force f_min (eq. 19) of the 3-motor \
                     point robot over its workspace, drawing f_min < 0 in white; the theoretical \
                     workspace is where f_min ≥ 0. {common} The largest value is at the centre \
                     (225·√3 ≈ 389.7 N: the force polytope is a regular hexagon there), ridges \
                     run towards the motors where two facets tie, and the workspace is slightly \
                     smaller than the motors' triangle, as in the paper."
                ),
            }
        } else {
            Figure {
                file,
                source: format!("Krut, Company & Pierrot 2004, Fig. 10 ({n} motors)"),
                caption: format!(
                    "The paper maps f_min for {n} motors regularly spaced on a circle of radius \
                     l (here 1000 mm = 1 m, first motor at 30°) and observes that more motors give a \
                     larger index in the middle of the workspace and that the workspace is not \
                     exactly a regular polygon because tensions must stay above t_min > 0. \
                     {common} Our centre values grow with n as in the paper: {}.",
                    centres
                        .iter()
                        .enumerate()
                        .map(|(i, c)| format!("{} motors {c:.1} N", i + 3))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            }
        });
    }
    Ok(figs)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn krut2004_maps_are_written_and_grow_with_the_motor_count() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap();
        // POLYTOPE_FIG_DIR keeps the images for inspection.
        let keep = std::env::var_os("POLYTOPE_FIG_DIR");
        let out = keep.clone().map(Into::into).unwrap_or_else(|| {
            std::env::temp_dir().join(format!("cdpr-polytope-figs-{}", std::process::id()))
        });
        std::fs::create_dir_all(&out).unwrap();
        let t0 = std::time::Instant::now();
        let figs = render(root, &out).unwrap();
        eprintln!("polytope figures: {:?}", t0.elapsed());
        assert_eq!(figs.len(), 4);
        for f in &figs {
            assert!(std::fs::metadata(out.join(&f.file)).unwrap().len() > 10_000);
        }
        assert!(figs[3].caption.contains("3 motors 389.7 N"));
        if keep.is_none() {
            std::fs::remove_dir_all(&out).ok();
        }
    }

    /// Figs. 3 and 8: written, with the hand-derived counts of the centre pose (6 hexagon
    /// vertices ±450 w_j and 2 points at the origin: 15 + 12 + 1 pairs, 15 distinct lines).
    #[test]
    fn krut2004_figs_3_and_8_are_written_with_the_hand_derived_counts() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap();
        // POLYTOPE_FIG_DIR keeps the images for inspection.
        let keep = std::env::var_os("POLYTOPE_FIG_DIR");
        let out = keep.clone().map(Into::into).unwrap_or_else(|| {
            std::env::temp_dir().join(format!("cdpr-fig38-{}", std::process::id()))
        });
        std::fs::create_dir_all(&out).unwrap();
        let fig3 = krut2004_fig3(root, &out).unwrap();
        let fig8 = krut2004_fig8(root, &out).unwrap();
        for f in [&fig3, &fig8] {
            assert!(std::fs::metadata(out.join(&f.file)).unwrap().len() > 10_000);
        }
        let c = &fig8.caption;
        let coincide = "C(8, 2) = 28 pairs, 1 coincide ((50, 50, 50) and (500, 500, 500)";
        assert!(c.contains(coincide), "{c}");
        assert!(c.contains("the other 27 candidate lines"), "{c}");
        assert!(
            c.contains("15 distinct lines) include 15 on the 3 diameters"),
            "{c}"
        );
        assert!(c.contains("6 pass the border test (15)"), "{c}");
        assert!(c.contains("the 6 sides"), "{c}");
        assert!(
            fig3.caption.contains("t_j ∈ [50, 500] N"),
            "{}",
            fig3.caption
        );
        if keep.is_none() {
            std::fs::remove_dir_all(&out).ok();
        }
    }

    /// Fig. 4: at the centre the polygon is the regular hexagon of apothem 225·√3 ≈ 389.7 N
    /// (hand-derived, see `render`), all six facets touch the circle and the ellipse is that
    /// circle; off-centre a single facet limits.
    #[test]
    fn krut2004_fig4_is_written_with_the_hand_derived_centre() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap();
        let out = std::env::temp_dir().join(format!("cdpr-fig4-{}", std::process::id()));
        std::fs::create_dir_all(&out).unwrap();
        let fig = krut2004_fig4(root, &out).unwrap();
        assert!(std::fs::metadata(out.join(&fig.file)).unwrap().len() > 10_000);
        let c = &fig.caption;
        assert!(
            c.contains("f_min = 389.7 N, the circle touches 6 facet(s)"),
            "{c}"
        );
        assert!(c.contains("0°, 60°, 120°, 180°, 240°, 300°"), "{c}");
        assert!(c.contains("(the circle itself)"), "{c}");
        assert!(c.contains("the circle touches 1 facet(s)"), "{c}");
        std::fs::remove_dir_all(&out).ok();
    }
}
