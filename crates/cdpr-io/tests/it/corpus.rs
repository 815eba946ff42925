//! Every published model of the corpus (tests/data: CASPR and WireCenter files with their
//! licences): the readers accept the ones cdpr models and name the element and line of the ones
//! it does not; import → convert (TOML, and .wcrfx where the format holds the robot) →
//! re-import gives the same robot, bounds, platform, stiffness and names, and the same lengths
//! and wrench matrix W at several poses.

use cdpr_io::{LoadOptions, RobotDescription, RobotFileError};
use cdpr_kinematics::{MotionPattern, Pose};
use std::path::{Path, PathBuf};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data")
}

/// Every CASPR cables file and .wcrfx file of the corpus.
fn corpus() -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(&p, out);
            } else {
                let name = p.file_name().unwrap().to_string_lossy().into_owned();
                if name.ends_with("_cables.xml") || name.ends_with(".wcrfx") {
                    out.push(p);
                }
            }
        }
    }
    let mut out = Vec::new();
    walk(&data(), &mut out);
    out.sort();
    out
}

/// The cable set ids of a CASPR cables file (by a plain text scan, independent of the reader).
fn cable_sets(path: &Path) -> Vec<Option<String>> {
    if path.extension().unwrap() != "xml" {
        return vec![None];
    }
    let text = std::fs::read_to_string(path).unwrap();
    text.split("<cable_set id=\"")
        .skip(1)
        .map(|s| Some(s.split('"').next().unwrap().to_string()))
        .collect()
}

/// Files (and cable sets) cdpr does not model, with the element its error must name.
const NOT_MODELLED: &[(&str, Option<&str>, &str)] = &[
    (
        "2_DoF_VSD_cables.xml",
        Some("basic"),
        "cable_vsd_torsion_spring",
    ),
    ("Myorob_shoulder_cables.xml", None, "joint"),
];

fn not_modelled(path: &Path, set: Option<&str>) -> Option<&'static str> {
    let name = path.file_name().unwrap().to_string_lossy().into_owned();
    NOT_MODELLED
        .iter()
        .find(|(f, s, _)| *f == name && (s.is_none() || *s == set))
        .map(|(_, _, element)| *element)
}

/// Poses around the home pose (or the frame's centre at z = 0.3 of its height).
fn poses(d: &RobotDescription) -> Vec<Pose> {
    let motion = d.robot.motion();
    let (lo, hi) = d.robot.frame_bounding_box();
    let centre = (lo + hi) / 2.0;
    let size = (hi - lo).norm().max(1e-3);
    let home = d.home_pose.clone().unwrap_or_else(|| match motion {
        MotionPattern::Point2 => vec![centre.x, centre.y],
        MotionPattern::Planar => vec![centre.x, centre.y, 0.0],
        MotionPattern::Point3 => vec![centre.x, centre.y, lo.z + 0.3 * (hi.z - lo.z)],
        MotionPattern::Spatial => vec![
            centre.x,
            centre.y,
            lo.z + 0.3 * (hi.z - lo.z),
            0.0,
            0.0,
            0.0,
        ],
    });
    let offsets: [[f64; 6]; 4] = [
        [0.0; 6],
        [0.05, -0.03, 0.02, 0.1, -0.05, 0.2],
        [-0.04, 0.06, -0.05, -0.08, 0.12, -0.3],
        [0.02, 0.02, 0.06, 0.3, 0.0, 0.0],
    ];
    offsets
        .iter()
        .map(|o| {
            let q: Vec<f64> = home
                .iter()
                .enumerate()
                .map(|(i, &h)| {
                    let linear = i < motion.space_dim();
                    h + o[i] * if linear { size } else { 1.0 }
                })
                .collect();
            Pose::from_coordinates(motion, &q).unwrap()
        })
        .collect()
}

/// Same lengths and W at every pose.
fn same_kinematics(a: &RobotDescription, b: &RobotDescription, what: &str) -> usize {
    let mut checked = 0;
    for pose in poses(a) {
        let (ka, kb) = match (
            a.robot.inverse_kinematics(&pose),
            b.robot.inverse_kinematics(&pose),
        ) {
            (Ok(ka), Ok(kb)) => (ka, kb),
            (Err(_), Err(_)) => continue,
            (x, y) => panic!("{what}: one side fails: {:?} / {:?}", x.err(), y.err()),
        };
        let (la, lb): (Vec<f64>, Vec<f64>) = (ka.lengths().collect(), kb.lengths().collect());
        assert_eq!(la, lb, "{what}: lengths");
        assert_eq!(ka.wrench_matrix(), kb.wrench_matrix(), "{what}: W");
        checked += 1;
    }
    checked
}

#[test]
fn every_corpus_file_reads_or_names_what_is_not_modelled() {
    let files = corpus();
    assert!(files.len() >= 30, "corpus: {} files", files.len());
    let (mut read, mut refused) = (0, 0);
    for path in &files {
        for set in cable_sets(path) {
            let mut options = LoadOptions::default();
            options.cable_set = set.clone();
            let result = RobotDescription::load_with(path, &options);
            let default_set = set.is_some() && {
                let text = std::fs::read_to_string(path).unwrap();
                text.contains(&format!(
                    "default_cable_set=\"{}\"",
                    set.as_deref().unwrap()
                ))
            };
            let expect = not_modelled(path, set.as_deref()).or_else(|| {
                if default_set {
                    not_modelled(path, None)
                } else {
                    None
                }
            });
            match (result, expect) {
                (Ok(d), None) => {
                    assert_eq!(d.bounds.len(), d.robot.cable_count());
                    assert_eq!(d.cable_names.len(), d.robot.cable_count());
                    read += 1;
                }
                (Err(e), Some(element)) => {
                    let msg = e.to_string();
                    assert!(
                        msg.starts_with(&path.display().to_string())
                            || msg.contains("_bodies.xml:"),
                        "{msg}"
                    );
                    assert!(msg.contains(&format!("<{element}>")), "{msg}");
                    assert!(
                        matches!(e, RobotFileError::Unsupported { line, .. } | RobotFileError::Element { line, .. } if line > 0),
                        "{msg}"
                    );
                    refused += 1;
                }
                (Ok(_), Some(element)) => panic!(
                    "{} [{set:?}] read, expected an error at <{element}>",
                    path.display()
                ),
                (Err(e), None) => panic!("{} [{set:?}]: {e}", path.display()),
            }
        }
    }
    eprintln!("{read} models read, {refused} refused with the element named");
    assert!(read >= 36 && refused >= 2, "read {read}, refused {refused}");
}

#[test]
fn import_convert_reimport_keeps_every_number() {
    let dir = tempdir();
    let (mut toml_trips, mut wcrfx_trips, mut poses_checked) = (0, 0, 0);
    for path in corpus() {
        for set in cable_sets(&path) {
            let mut options = LoadOptions::default();
            options.cable_set = set.clone();
            let Ok(d) = RobotDescription::load_with(&path, &options) else {
                continue;
            };
            let what = format!("{} [{set:?}]", path.display());
            // TOML: exact.
            let toml_path = dir.join("robot.toml");
            d.save(&toml_path, "round trip").unwrap();
            let t = RobotDescription::load(&toml_path).unwrap();
            assert_eq!(t.robot, d.robot, "{what}: robot");
            assert_eq!(t.bounds, d.bounds, "{what}: bounds");
            assert_eq!(t.platform, d.platform, "{what}: platform");
            assert_eq!(t.axial_stiffness, d.axial_stiffness, "{what}: stiffness");
            assert_eq!(t.linear_density, d.linear_density, "{what}: linear density");
            assert_eq!(t.cable_names, d.cable_names, "{what}: names");
            assert_eq!(t.inertia, d.inertia, "{what}: inertia");
            assert_eq!(t.home_pose, d.home_pose, "{what}: home pose");
            assert_eq!(t.name, d.name, "{what}: name");
            assert_eq!(
                t.passive_springs, d.passive_springs,
                "{what}: passive springs"
            );
            assert_eq!(
                t.passive_spring_names, d.passive_spring_names,
                "{what}: spring names"
            );
            poses_checked += same_kinematics(&d, &t, &what);
            toml_trips += 1;
            // .wcrfx, where it holds the robot (one tension range, one cable type).
            let w_path = dir.join("robot.wcrfx");
            match d.save(&w_path, "") {
                Ok(_) => {
                    let w = RobotDescription::load(&w_path).unwrap();
                    assert_eq!(w.robot, d.robot, "{what}: robot via wcrfx");
                    assert_eq!(w.bounds, d.bounds, "{what}: bounds via wcrfx");
                    assert_eq!(w.platform.mass, d.platform.mass);
                    assert_eq!(w.platform.centre_of_mass, d.platform.centre_of_mass);
                    assert_eq!(w.inertia, d.inertia, "{what}: inertia via wcrfx");
                    assert_eq!(w.cable_names.len(), d.cable_names.len());
                    assert_eq!(
                        w.linear_density, d.linear_density,
                        "{what}: density via wcrfx"
                    );
                    match (&w.axial_stiffness, &d.axial_stiffness) {
                        (Some(a), Some(b)) => {
                            for (x, y) in a.iter().zip(b) {
                                assert!((x - y).abs() <= 1e-14 * y, "{what}: E·S {x} vs {y}");
                            }
                        }
                        (None, None) => {}
                        (a, b) => panic!("{what}: stiffness {a:?} vs {b:?}"),
                    }
                    poses_checked += same_kinematics(&d, &w, &what);
                    wcrfx_trips += 1;
                }
                Err(RobotFileError::Unrepresentable { message, .. }) => {
                    assert!(
                        message.contains("differ") || message.contains("passive spring"),
                        "{what}: {message}"
                    );
                }
                Err(e) => panic!("{what}: {e}"),
            }
        }
    }
    eprintln!(
        "{toml_trips} TOML and {wcrfx_trips} .wcrfx round trips, {poses_checked} pose comparisons"
    );
    assert!(toml_trips >= 30 && wcrfx_trips >= 25 && poses_checked >= 200);
}

fn tempdir() -> PathBuf {
    let dir = // Cargo's scratch directory for integration tests (target/tmp), reused by every run, so
    // that no run leaves a directory behind in the system's temporary directory.
    std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("corpus");
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Every published robot shipped in examples/robots/ is its source file, converted: same
/// robot, bounds, platform, inertia, stiffness, names and home pose (the `# source:` line says
/// which file and cable set).
#[test]
fn shipped_published_robots_equal_their_sources() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut checked = 0;
    for e in std::fs::read_dir(root.join("examples/robots")).unwrap() {
        let path = e.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        let Some(line) = text.lines().find_map(|l| l.strip_prefix("# source: ")) else {
            continue;
        };
        let mut words = line.split_whitespace();
        let source = root.join(words.next().unwrap());
        let mut options = LoadOptions::default();
        if words.next() == Some("--cable-set") {
            options.cable_set = words.next().map(str::to_string);
        }
        let shipped = RobotDescription::load(&path).unwrap();
        let original = RobotDescription::load_with(&source, &options).unwrap();
        let what = path.display();
        assert_eq!(shipped.robot, original.robot, "{what}");
        assert_eq!(shipped.bounds, original.bounds, "{what}");
        assert_eq!(shipped.platform, original.platform, "{what}");
        assert_eq!(shipped.inertia, original.inertia, "{what}");
        assert_eq!(shipped.axial_stiffness, original.axial_stiffness, "{what}");
        assert_eq!(shipped.linear_density, original.linear_density, "{what}");
        assert_eq!(shipped.cable_names, original.cable_names, "{what}");
        assert_eq!(shipped.home_pose, original.home_pose, "{what}");
        checked += 1;
    }
    assert!(checked >= 28, "{checked} shipped published robots");
}
