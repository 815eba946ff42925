//! # Mesh and point files
//!
//! Writers for a [`BoundaryMesh`] (binary STL, ASCII PLY with per-vertex normals, Wavefront
//! OBJ) and for grid verdicts (CSV), so that workspaces can be opened in CAD, mesh and
//! post-processing tools. Coordinates are written in the robot file's length unit (m).
//!
//! ## References
//! - 3D Systems (1989), StereoLithography Interface Specification (binary STL: 80-byte header,
//!   u32 count, per triangle a normal and three vertices as little-endian f32, u16 attribute).
//! - Turk (1994), The PLY polygon file format.
//! - Wavefront Technologies, the OBJ file format (`v`, `vn`, `f v//vn`, 1-based indices).

use crate::{BoundaryMesh, GridWorkspace};
use std::io::{self, Write};

impl BoundaryMesh {
    /// Binary STL: one facet per triangle with its outward unit normal (f32, as the format has).
    pub fn write_stl(&self, w: &mut impl Write) -> io::Result<()> {
        let mut header = [b' '; 80];
        let text = b"cdpr workspace boundary mesh (m), normals out of the workspace";
        header[..text.len()].copy_from_slice(text);
        w.write_all(&header)?;
        w.write_all(&(self.triangles.len() as u32).to_le_bytes())?;
        for (t, n) in self.triangles.iter().zip(self.triangle_normals()) {
            for c in n {
                w.write_all(&(c as f32).to_le_bytes())?;
            }
            for &v in t {
                for c in self.vertices[v as usize] {
                    w.write_all(&(c as f32).to_le_bytes())?;
                }
            }
            w.write_all(&0u16.to_le_bytes())?;
        }
        Ok(())
    }

    /// ASCII PLY with per-vertex normals (`nx ny nz`, area-weighted, out of the workspace) and
    /// full double precision, so that the 10⁻⁸ placement survives the file.
    pub fn write_ply(&self, w: &mut impl Write) -> io::Result<()> {
        writeln!(w, "ply")?;
        writeln!(w, "format ascii 1.0")?;
        writeln!(
            w,
            "comment cdpr workspace boundary mesh: coordinates in m, volume {} m^3",
            self.volume
        )?;
        writeln!(w, "element vertex {}", self.vertices.len())?;
        for p in ["x", "y", "z", "nx", "ny", "nz"] {
            writeln!(w, "property double {p}")?;
        }
        writeln!(w, "element face {}", self.triangles.len())?;
        writeln!(w, "property list uchar int vertex_indices")?;
        writeln!(w, "end_header")?;
        for (v, n) in self.vertices.iter().zip(self.vertex_normals()) {
            writeln!(w, "{} {} {} {} {} {}", v[0], v[1], v[2], n[0], n[1], n[2])?;
        }
        for t in &self.triangles {
            writeln!(w, "3 {} {} {}", t[0], t[1], t[2])?;
        }
        Ok(())
    }

    /// Wavefront OBJ with per-vertex normals (`f a//a b//b c//c`, 1-based).
    pub fn write_obj(&self, w: &mut impl Write) -> io::Result<()> {
        writeln!(
            w,
            "# cdpr workspace boundary mesh: coordinates in m, volume {} m^3",
            self.volume
        )?;
        for v in &self.vertices {
            writeln!(w, "v {} {} {}", v[0], v[1], v[2])?;
        }
        for n in self.vertex_normals() {
            writeln!(w, "vn {} {} {}", n[0], n[1], n[2])?;
        }
        for t in &self.triangles {
            let [a, b, c] = t.map(|i| i + 1);
            writeln!(w, "f {a}//{a} {b}//{b} {c}//{c}")?;
        }
        Ok(())
    }
}

impl GridWorkspace {
    /// The grid verdicts as CSV: a header with units (`x (m),y (m)[,z (m)],feasible`), then one
    /// line per grid point (x fastest), `feasible` 1 when every criterion holds, else 0.
    pub fn write_points_csv(&self, w: &mut impl Write) -> io::Result<()> {
        let axes = ["x (m)", "y (m)", "z (m)"];
        writeln!(w, "{},feasible", axes[..self.dim].join(","))?;
        for (idx, &f) in self.feasible.iter().enumerate() {
            let p = self.point(idx);
            for k in 0..self.dim {
                write!(w, "{},", p[k])?;
            }
            writeln!(w, "{}", u8::from(f))?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use crate::{Criterion, CustomCriterion, Grid, MeshSettings, PoseEvaluator, Region};
    use cdpr_kinematics::{Cable, MotionPattern, Robot};
    use cdpr_tension::TensionBounds;
    use nalgebra::{Rotation3, Vector3};

    fn ball_mesh() -> crate::BoundaryMesh {
        let c = |x: f64, y: f64, z: f64| Cable {
            frame: Vector3::new(x, y, z),
            platform: Vector3::zeros(),
            pulley: None,
        };
        let robot = Robot::new(
            MotionPattern::Point3,
            vec![
                c(9.0, 9.0, 9.0),
                c(9.0, -9.0, -9.0),
                c(-9.0, 9.0, -9.0),
                c(-9.0, -9.0, 9.0),
            ],
        )
        .unwrap();
        let eval = PoseEvaluator::new(
            robot,
            TensionBounds::uniform(4, 0.0, 1.0).unwrap(),
            vec![Criterion::Custom(CustomCriterion::new("ball", |ctx| {
                ctx.pose.position.norm() < 0.5
            }))],
        )
        .unwrap();
        let grid = Grid::new(
            6,
            Region::cuboid(Vector3::repeat(-1.0), Vector3::repeat(1.0)),
        );
        crate::boundary_mesh(
            &eval,
            &Rotation3::identity(),
            &grid,
            &MeshSettings::default(),
        )
        .unwrap()
    }

    /// The files read back (by hand-written parsers of each format) give the same triangles.
    #[test]
    fn files_round_trip() {
        let mesh = ball_mesh();
        let nt = mesh.triangles.len();
        assert!(nt > 8);

        let mut stl = Vec::new();
        mesh.write_stl(&mut stl).unwrap();
        assert_eq!(stl.len(), 84 + 50 * nt);
        assert_eq!(
            u32::from_le_bytes(stl[80..84].try_into().unwrap()) as usize,
            nt
        );
        let f = |off: usize| f32::from_le_bytes(stl[off..off + 4].try_into().unwrap()) as f64;
        let last = 84 + 50 * (nt - 1);
        let v = mesh.vertices[mesh.triangles[nt - 1][2] as usize];
        for (k, c) in v.iter().enumerate() {
            assert!((f(last + 12 + 24 + 4 * k) - c).abs() < 1e-6);
        }
        let (normal, a) = (
            Vector3::new(f(last), f(last + 4), f(last + 8)),
            Vector3::new(f(last + 12), f(last + 16), f(last + 20)),
        );
        assert!((normal.norm() - 1.0).abs() < 1e-6);
        assert!(normal.dot(&a) > 0.0, "normal out of the ball");

        let mut ply = Vec::new();
        mesh.write_ply(&mut ply).unwrap();
        let ply = String::from_utf8(ply).unwrap();
        let body: Vec<&str> = ply.split("end_header\n").nth(1).unwrap().lines().collect();
        assert_eq!(body.len(), mesh.vertices.len() + nt);
        let v0: Vec<f64> = body[0].split(' ').map(|x| x.parse().unwrap()).collect();
        assert_eq!(v0[..3], mesh.vertices[0]);
        // Normals of a ball point away from its centre.
        assert!(Vector3::new(v0[0], v0[1], v0[2]).dot(&Vector3::new(v0[3], v0[4], v0[5])) > 0.0);
        let t: Vec<u32> = body[mesh.vertices.len()]
            .split(' ')
            .map(|x| x.parse().unwrap())
            .collect();
        assert_eq!(t[1..], mesh.triangles[0]);

        let mut obj = Vec::new();
        mesh.write_obj(&mut obj).unwrap();
        let obj = String::from_utf8(obj).unwrap();
        assert_eq!(
            obj.lines().filter(|l| l.starts_with("v ")).count(),
            mesh.vertices.len()
        );
        let f0 = obj.lines().find(|l| l.starts_with("f ")).unwrap();
        let [a, b, c] = mesh.triangles[0].map(|i| i + 1);
        assert_eq!(f0, format!("f {a}//{a} {b}//{b} {c}//{c}"));

        let mut csv = Vec::new();
        mesh.grid.write_points_csv(&mut csv).unwrap();
        let csv = String::from_utf8(csv).unwrap();
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines[0], "x (m),y (m),z (m),feasible");
        assert_eq!(lines.len(), 1 + 7 * 7 * 7);
        let ones = lines[1..].iter().filter(|l| l.ends_with(",1")).count();
        assert_eq!(ones, mesh.grid.feasible_points);
        assert_eq!(lines[1], "-1,-1,-1,0");
    }
}
