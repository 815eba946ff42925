//! # Cable interference
//!
//! Two ways a cable robot collides with itself:
//!
//! - **cable–cable**: the straight segments of two cables come closer than a clearance D (a
//!   cable diameter, say). The distance between segments [p₀, p₁] and [q₀, q₁] is
//!   min over s, t ∈ [0, 1] of ‖p₀ + s(p₁ − p₀) − q₀ − t(q₁ − q₀)‖: the closed form of the
//!   unconstrained minimum of this convex quadratic, clamped to the unit square (Ericson 2005,
//!   §5.1.9), and — for robustness when the segments are (nearly) parallel or degenerate, where
//!   the interior minimum is ill-conditioned — never more than the four endpoint-to-segment
//!   distances, which are always well conditioned. The minimum of the convex function over the
//!   square is either interior (non-parallel case, unique, the closed form) or on an edge of the
//!   square (an endpoint of one segment against the other segment), so the smaller of the two
//!   is exact up to round-off. The interior candidate is skipped when the segments are within
//!   sin θ ≤ 10⁻⁶ of parallel (ae − b² ≤ 10⁻¹² ae); the answer then exceeds the exact distance by
//!   at most (length of the shorter segment) × sin θ ≤ 10⁻⁶ of that length.
//! - **cable–platform**: a cable enters the platform, a convex polyhedron
//!   P = {x : n_k · x ≤ d_k} (unit outward normals n_k) in platform coordinates. The
//!   penetration of a segment x(t), t ∈ [0, 1], is δ = max_t min_k (d_k − n_k · x(t)): the
//!   depth of its deepest point inside P (negative outside). t ↦ min_k(…) is concave and
//!   piecewise linear, so its maximum is at t = 0, t = 1 or where two of the lines cross: δ is
//!   computed exactly from these candidates. A cable attached on the surface of P (at a
//!   vertex, on an edge or a face) and leaving outwards has δ = 0 at its attachment and δ < 0
//!   beyond: it does not interfere. It interferes when δ > τ, τ = 10⁻⁹ × the size of P, i.e.
//!   when it passes through the interior.
//!
//! **Which segment.** A cable's free segment runs from its platform attachment point
//! **u** + **T ā**^i to **u** + **T ā**^i + ℓ^i ([`cable_segment`]): the frame anchor for a
//! straight cable; when pulley kinematics make ℓ^i end at the point where the cable leaves its
//! pulley, the same function gives the free segment.
//!
//! **Cables that share an endpoint** (a common frame anchor, as on IPAnema 1, or a common
//! platform attachment) meet there by design: the pair is left out of the cable–cable distance
//! unless the two cables leave the shared point in the same direction (they then overlap, and
//! their distance is 0).
//!
//! ## References
//! - C. Ericson, *Real-Time Collision Detection*, Morgan Kaufmann 2005, §5.1.9 (closest points of
//!   two segments).
//! - Perreault, Cardou, Gosselin & Otis (2010), "Geometric determination of the
//!   interference-free constant-orientation workspace of parallel cable-driven mechanisms",
//!   ASME J. Mechanisms Robotics 2(3): cable–cable and cable–platform interference.
//! - Cyrus & Beck (1978): clipping a segment against a convex polyhedron.

use crate::{CableState, KinematicsError, PoseKinematics};
use nalgebra::Vector3;

/// A straight segment from `start` to `end` (m, base coordinates unless said otherwise).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// First endpoint.
    pub start: Vector3<f64>,
    /// Second endpoint.
    pub end: Vector3<f64>,
}

impl Segment {
    /// The segment from `start` to `end`.
    pub fn new(start: Vector3<f64>, end: Vector3<f64>) -> Self {
        Self { start, end }
    }

    /// The point at parameter t ∈ [0, 1].
    pub fn at(&self, t: f64) -> Vector3<f64> {
        self.start + (self.end - self.start) * t
    }

    /// Length ‖end − start‖ (m).
    pub fn length(&self) -> f64 {
        (self.end - self.start).norm()
    }
}

/// The free segment of a cable at a pose: from its platform attachment point to the point where
/// it leaves the frame (the frame anchor of a straight cable; a pulley's leave point once
/// ℓ^i ends there).
#[inline]
pub fn cable_segment(state: &CableState) -> Segment {
    Segment::new(
        state.attachment_point,
        state.attachment_point + state.vector,
    )
}

/// The closest points of two segments.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SegmentDistance {
    /// Distance between the segments (m).
    pub distance: f64,
    /// Parameter s ∈ [0, 1] of the closest point on the first segment.
    pub s: f64,
    /// Parameter t ∈ [0, 1] of the closest point on the second segment.
    pub t: f64,
}

/// Closest point of segment `seg` to point `p`: its parameter and distance.
fn point_segment(p: &Vector3<f64>, seg: &Segment) -> (f64, f64) {
    let d = seg.end - seg.start;
    let dd = d.norm_squared();
    let t = if dd > 0.0 {
        ((p - seg.start).dot(&d) / dd).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (t, (seg.at(t) - p).norm())
}

/// Distance between two segments and its closest points (Ericson 2005 §5.1.9, with the
/// endpoint-to-segment distances as a guard for (nearly) parallel and zero-length segments).
///
/// ```
/// use cdpr_kinematics::{segment_distance, Segment};
/// use nalgebra::Vector3;
/// // Two skew lines 1 m apart: x axis at z = 0 and y axis at z = 1.
/// let a = Segment::new(Vector3::new(-1.0, 0.0, 0.0), Vector3::new(1.0, 0.0, 0.0));
/// let b = Segment::new(Vector3::new(0.0, -1.0, 1.0), Vector3::new(0.0, 1.0, 1.0));
/// let d = segment_distance(&a, &b);
/// assert!((d.distance - 1.0).abs() < 1e-15 && (d.s - 0.5).abs() < 1e-15);
/// ```
pub fn segment_distance(p: &Segment, q: &Segment) -> SegmentDistance {
    let d1 = p.end - p.start;
    let d2 = q.end - q.start;
    let r = p.start - q.start;
    let a = d1.norm_squared();
    let e = d2.norm_squared();
    let f = d2.dot(&r);
    let c = d1.dot(&r);
    let b = d1.dot(&d2);
    // Interior candidate (only when both segments have length and are not parallel).
    let denom = a * e - b * b;
    let mut best = SegmentDistance {
        distance: f64::INFINITY,
        s: 0.0,
        t: 0.0,
    };
    if a > 0.0 && e > 0.0 && denom > 1e-12 * a * e {
        let mut s = ((b * f - c * e) / denom).clamp(0.0, 1.0);
        let mut t = (b * s + f) / e;
        if t < 0.0 {
            t = 0.0;
            s = (-c / a).clamp(0.0, 1.0);
        } else if t > 1.0 {
            t = 1.0;
            s = ((b - c) / a).clamp(0.0, 1.0);
        }
        best = SegmentDistance {
            distance: (p.at(s) - q.at(t)).norm(),
            s,
            t,
        };
    }
    // Endpoint candidates: the minimum over the square lies on its edge when not interior.
    for (s, end) in [(0.0, &p.start), (1.0, &p.end)] {
        let (t, dist) = point_segment(end, q);
        if dist < best.distance {
            best = SegmentDistance {
                distance: dist,
                s,
                t,
            };
        }
    }
    for (t, end) in [(0.0, &q.start), (1.0, &q.end)] {
        let (s, dist) = point_segment(end, p);
        if dist < best.distance {
            best = SegmentDistance {
                distance: dist,
                s,
                t,
            };
        }
    }
    best
}

/// The closest pair of cables at a pose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClosestCables {
    /// The two cables (0-based, first < second).
    pub cables: (usize, usize),
    /// Their distance (m).
    pub distance: f64,
    /// The closest points on each cable (base coordinates, m).
    pub points: (Vector3<f64>, Vector3<f64>),
}

/// Whether two segments share an endpoint (within `tol`) and leave it in different directions:
/// such pairs meet by design and are left out of the cable–cable distance.
fn share_endpoint_only(p: &Segment, q: &Segment, tol: f64) -> bool {
    for (pa, pb) in [(p.start, p.end), (p.end, p.start)] {
        for (qa, qb) in [(q.start, q.end), (q.end, q.start)] {
            if (pa - qa).norm() <= tol {
                let (u, v) = (pb - pa, qb - qa);
                let (nu, nv) = (u.norm(), v.norm());
                // Overlapping (same direction) cables do interfere.
                return nu > 0.0 && nv > 0.0 && u.dot(&v) < (1.0 - 1e-12) * nu * nv;
            }
        }
    }
    false
}

/// The cable pair at minimum distance at the pose of `kin` (pairs sharing an endpoint left out,
/// see the module docs); `None` with fewer than two cables or when every pair shares an endpoint.
pub fn closest_cables(kin: &PoseKinematics) -> Option<ClosestCables> {
    let cables = kin.cables();
    let scale = cables
        .iter()
        .map(|c| {
            c.attachment_point
                .norm()
                .max((c.attachment_point + c.vector).norm())
        })
        .fold(1.0, f64::max);
    let tol = 1e-12 * scale;
    let mut best: Option<ClosestCables> = None;
    for i in 0..cables.len() {
        let p = cable_segment(&cables[i]);
        for (j, cj) in cables.iter().enumerate().skip(i + 1) {
            let q = cable_segment(cj);
            if share_endpoint_only(&p, &q, tol) {
                continue;
            }
            let d = segment_distance(&p, &q);
            if best.is_none_or(|b| d.distance < b.distance) {
                best = Some(ClosestCables {
                    cables: (i, j),
                    distance: d.distance,
                    points: (p.at(d.s), q.at(d.t)),
                });
            }
        }
    }
    best
}

/// The smallest distance between two cables at the pose of `kin` (+∞ when no pair counts);
/// the allocation-free test behind the interference criterion.
pub fn min_cable_distance(kin: &PoseKinematics) -> f64 {
    closest_cables(kin).map_or(f64::INFINITY, |c| c.distance)
}

/// A convex polyhedron: the convex hull of a set of points, kept as its vertices, its faces
/// (polygons, counter-clockwise seen from outside) and its half-spaces n_k · x ≤ d_k.
#[derive(Debug, Clone, PartialEq)]
pub struct ConvexPolyhedron {
    vertices: Vec<Vector3<f64>>,
    faces: Vec<Vec<usize>>,
    planes: Vec<(Vector3<f64>, f64)>,
    size: f64,
}

/// At most this many points define a platform shape (the hull is found by testing every
/// triple of points: O(N⁴)).
pub const MAX_SHAPE_POINTS: usize = 200;

impl ConvexPolyhedron {
    /// The convex hull of `points` (at least 4 not coplanar, at most [`MAX_SHAPE_POINTS`]).
    /// Points strictly inside the hull are dropped. Errors on non-finite or flat input.
    ///
    /// ```
    /// use cdpr_kinematics::ConvexPolyhedron;
    /// use nalgebra::Vector3;
    /// let tetra = ConvexPolyhedron::from_points(&[
    ///     Vector3::zeros(), Vector3::x(), Vector3::y(), Vector3::z(),
    ///     Vector3::new(0.1, 0.1, 0.1), // inside: dropped
    /// ]).unwrap();
    /// assert_eq!((tetra.vertices().len(), tetra.faces().len()), (4, 4));
    /// assert!((tetra.volume() - 1.0 / 6.0).abs() < 1e-15);
    /// ```
    pub fn from_points(points: &[Vector3<f64>]) -> Result<Self, KinematicsError> {
        if let Some(&v) = points
            .iter()
            .flat_map(|p| p.iter())
            .find(|v| !v.is_finite())
        {
            return Err(KinematicsError::NotFinite {
                what: "platform shape vertex".into(),
                value: v,
            });
        }
        if points.len() < 4 || points.len() > MAX_SHAPE_POINTS {
            return Err(KinematicsError::DegenerateShape {
                reason: format!(
                    "{} points: a convex polyhedron needs 4 to {MAX_SHAPE_POINTS}",
                    points.len()
                ),
            });
        }
        let centre = points.iter().sum::<Vector3<f64>>() / points.len() as f64;
        let size = points
            .iter()
            .map(|p| (p - centre).norm())
            .fold(0.0, f64::max);
        let tol = 1e-9 * size.max(f64::MIN_POSITIVE);
        let mut planes: Vec<(Vector3<f64>, f64)> = Vec::new();
        let n = points.len();
        for i in 0..n {
            for j in i + 1..n {
                for k in j + 1..n {
                    let normal = (points[j] - points[i]).cross(&(points[k] - points[i]));
                    let len = normal.norm();
                    if len <= 1e-12 * size * size {
                        continue;
                    }
                    let mut normal = normal / len;
                    let mut d = normal.dot(&points[i]);
                    let (mut above, mut below) = (false, false);
                    for p in points {
                        let h = normal.dot(p) - d;
                        above |= h > tol;
                        below |= h < -tol;
                    }
                    if above && below {
                        continue;
                    }
                    if above {
                        normal = -normal;
                        d = -d;
                    }
                    if !planes
                        .iter()
                        .any(|(m, e)| m.dot(&normal) > 1.0 - 1e-9 && (e - d).abs() <= tol)
                    {
                        planes.push((normal, d));
                    }
                }
            }
        }
        if planes.len() < 4 {
            return Err(KinematicsError::DegenerateShape {
                reason: "the points are coplanar (or collinear): the platform has no volume".into(),
            });
        }
        // Vertices: points on at least three faces, without repeats.
        let mut vertices: Vec<Vector3<f64>> = Vec::new();
        for p in points {
            let on = planes
                .iter()
                .filter(|(m, d)| (m.dot(p) - d).abs() <= tol)
                .count();
            if on >= 3 && !vertices.iter().any(|v| (v - p).norm() <= tol) {
                vertices.push(*p);
            }
        }
        // Faces: the vertices on each plane, sorted counter-clockwise about the outward normal.
        let faces = planes
            .iter()
            .map(|(m, d)| {
                let mut on: Vec<usize> = (0..vertices.len())
                    .filter(|&v| (m.dot(&vertices[v]) - d).abs() <= tol)
                    .collect();
                let c = on.iter().map(|&v| vertices[v]).sum::<Vector3<f64>>() / on.len() as f64;
                let e1 = (vertices[on[0]] - c).normalize();
                let e2 = m.cross(&e1);
                let angle = |v: usize| {
                    let r = vertices[v] - c;
                    r.dot(&e2).atan2(r.dot(&e1))
                };
                on.sort_by(|&a, &b| angle(a).total_cmp(&angle(b)));
                on
            })
            .collect();
        Ok(Self {
            vertices,
            faces,
            planes,
            size,
        })
    }

    /// The box [−lx/2, lx/2] × [−ly/2, ly/2] × [−lz/2, lz/2] (side lengths > 0, m) centred on
    /// `centre`.
    pub fn cuboid(lengths: Vector3<f64>, centre: Vector3<f64>) -> Result<Self, KinematicsError> {
        if let Some(&v) = lengths.iter().find(|v| !(v.is_finite() && **v > 0.0)) {
            return Err(KinematicsError::DegenerateShape {
                reason: format!("box side {v} is not a positive finite number"),
            });
        }
        let h = lengths / 2.0;
        let corners: Vec<Vector3<f64>> = (0..8)
            .map(|k| {
                let sign = |bit: usize| if k & bit == 0 { -1.0 } else { 1.0 };
                centre + Vector3::new(sign(1) * h.x, sign(2) * h.y, sign(4) * h.z)
            })
            .collect();
        Self::from_points(&corners)
    }

    /// The hull's vertices (platform coordinates, m).
    pub fn vertices(&self) -> &[Vector3<f64>] {
        &self.vertices
    }

    /// The faces: indices into [`ConvexPolyhedron::vertices`], counter-clockwise seen from
    /// outside.
    pub fn faces(&self) -> &[Vec<usize>] {
        &self.faces
    }

    /// The half-spaces n_k · x ≤ d_k (unit outward normal n_k, offset d_k in m).
    pub fn planes(&self) -> &[(Vector3<f64>, f64)] {
        &self.planes
    }

    /// Largest distance of a point from the points' centroid (m): the length scale of the
    /// tolerances.
    pub fn size(&self) -> f64 {
        self.size
    }

    /// Volume (m³), by the divergence theorem over the faces.
    pub fn volume(&self) -> f64 {
        let mut v = 0.0;
        for f in &self.faces {
            for k in 1..f.len() - 1 {
                let (a, b, c) = (
                    self.vertices[f[0]],
                    self.vertices[f[k]],
                    self.vertices[f[k + 1]],
                );
                v += a.dot(&b.cross(&c));
            }
        }
        v / 6.0
    }

    /// Depth of `p` inside the polyhedron, min_k (d_k − n_k · p) (m; negative outside).
    pub fn depth(&self, p: &Vector3<f64>) -> f64 {
        self.planes
            .iter()
            .map(|(n, d)| d - n.dot(p))
            .fold(f64::INFINITY, f64::min)
    }

    /// Penetration δ = max over t ∈ [0, 1] of the depth of `seg.at(t)` (m; ≤ 0 when the segment
    /// does not enter the interior), exact: the maximum of the concave piecewise-linear depth
    /// is at an endpoint or where two faces' depth lines cross.
    pub fn penetration(&self, seg: &Segment) -> f64 {
        let dir = seg.end - seg.start;
        // Depth along face k: α_k + β_k t.
        let line = |(n, d): &(Vector3<f64>, f64)| (d - n.dot(&seg.start), -n.dot(&dir));
        let depth_at = |t: f64| {
            self.planes
                .iter()
                .map(|p| {
                    let (a, b) = line(p);
                    a + b * t
                })
                .fold(f64::INFINITY, f64::min)
        };
        let mut best = depth_at(0.0).max(depth_at(1.0));
        for (k, pk) in self.planes.iter().enumerate() {
            let (ak, bk) = line(pk);
            for pl in &self.planes[k + 1..] {
                let (al, bl) = line(pl);
                if bk != bl {
                    let t = (al - ak) / (bk - bl);
                    if (0.0..=1.0).contains(&t) {
                        best = best.max(depth_at(t));
                    }
                }
            }
        }
        best
    }

    /// Whether `seg` passes through the interior: penetration above 10⁻⁹ × size.
    pub fn is_entered_by(&self, seg: &Segment) -> bool {
        self.penetration(seg) > 1e-9 * self.size
    }
}

/// A cable that enters the platform.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlatformInterference {
    /// The cable (0-based).
    pub cable: usize,
    /// How deep its deepest point lies inside the platform (m).
    pub penetration: f64,
}

/// The cable that enters the platform `shape` deepest at the pose of `kin`, if any (shape in
/// platform coordinates; `rotation` and `position` are the pose's).
pub fn platform_interference(
    kin: &PoseKinematics,
    shape: &ConvexPolyhedron,
    position: &Vector3<f64>,
    rotation: &nalgebra::Rotation3<f64>,
) -> Option<PlatformInterference> {
    let to_platform = |x: Vector3<f64>| rotation.inverse_transform_vector(&(x - position));
    let tol = 1e-9 * shape.size();
    let mut worst: Option<PlatformInterference> = None;
    for (i, c) in kin.cables().iter().enumerate() {
        let seg = cable_segment(c);
        let local = Segment::new(to_platform(seg.start), to_platform(seg.end));
        let pen = shape.penetration(&local);
        if pen > tol && worst.is_none_or(|w| pen > w.penetration) {
            worst = Some(PlatformInterference {
                cable: i,
                penetration: pen,
            });
        }
    }
    worst
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn seg(a: [f64; 3], b: [f64; 3]) -> Segment {
        Segment::new(Vector3::from(a), Vector3::from(b))
    }

    /// Brute-force oracle: the minimum over a fine grid of (s, t), a distance that can only
    /// exceed the exact one by at most h·(‖d1‖ + ‖d2‖).
    fn sampled(p: &Segment, q: &Segment, steps: usize) -> f64 {
        let mut best = f64::INFINITY;
        for i in 0..=steps {
            for j in 0..=steps {
                let (s, t) = (i as f64 / steps as f64, j as f64 / steps as f64);
                best = best.min((p.at(s) - q.at(t)).norm());
            }
        }
        best
    }

    #[test]
    fn parallel_segments_by_hand() {
        // Parallel, overlapping in x over [1, 2]: distance 0.5 (the offset).
        let a = seg([0.0, 0.0, 0.0], [2.0, 0.0, 0.0]);
        let b = seg([1.0, 0.5, 0.0], [3.0, 0.5, 0.0]);
        assert_relative_eq!(segment_distance(&a, &b).distance, 0.5, epsilon = 1e-15);
        // Parallel, disjoint in x: endpoints (2,0,0) and (3,0.5,0)... gap of 1 along x, 0.5 across.
        let c = seg([3.0, 0.5, 0.0], [5.0, 0.5, 0.0]);
        assert_relative_eq!(
            segment_distance(&a, &c).distance,
            (1.0f64 + 0.25).sqrt(),
            epsilon = 1e-15
        );
        // Antiparallel collinear overlap: distance 0.
        let d = seg([1.5, 0.0, 0.0], [0.5, 0.0, 0.0]);
        assert_eq!(segment_distance(&a, &d).distance, 0.0);
    }

    #[test]
    fn crossing_touching_and_skew_segments_by_hand() {
        // Crossing at (1, 1, 0).
        let a = seg([0.0, 0.0, 0.0], [2.0, 2.0, 0.0]);
        let b = seg([0.0, 2.0, 0.0], [2.0, 0.0, 0.0]);
        let d = segment_distance(&a, &b);
        assert!(d.distance < 1e-15);
        assert_relative_eq!((d.s, d.t).0, 0.5, epsilon = 1e-15);
        // Touching: an endpoint of b on the interior of a (a T).
        let t = seg([1.0, 1.0, 0.0], [1.0, 5.0, 3.0]);
        assert!(segment_distance(&a, &t).distance < 1e-15);
        // Skew: x axis and a line parallel to y at z = 2, crossing above x = 0.7.
        let s = seg([0.7, -3.0, 2.0], [0.7, 1.0, 2.0]);
        let x = seg([-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]);
        let d = segment_distance(&x, &s);
        assert_relative_eq!(d.distance, 2.0, epsilon = 1e-15);
        assert_relative_eq!(d.s, 0.85, epsilon = 1e-15);
        assert_relative_eq!(d.t, 0.75, epsilon = 1e-15);
        // Skew but the closest points of the lines are outside the segments: clamped.
        let far = seg([3.0, -1.0, 2.0], [3.0, 1.0, 2.0]);
        assert_relative_eq!(
            segment_distance(&x, &far).distance,
            (4.0f64 + 4.0).sqrt(),
            epsilon = 1e-15
        );
        // Degenerate: a point against a segment, and two points.
        let p = seg([0.5, 3.0, 4.0], [0.5, 3.0, 4.0]);
        assert_relative_eq!(segment_distance(&x, &p).distance, 5.0, epsilon = 1e-15);
        assert_relative_eq!(segment_distance(&p, &p).distance, 0.0);
    }

    #[test]
    fn nearly_parallel_segments_are_accurate() {
        // Angle 1e-9 rad between long segments: the interior formula is ill-conditioned; the
        // endpoint guard keeps the answer right (distance between x axis and a line tilted
        // by 1e-9 starting at height 0.3 above the start: 0.3 at s = 0).
        let a = seg([0.0, 0.0, 0.0], [10.0, 0.0, 0.0]);
        let b = seg([0.0, 0.3, 0.0], [10.0, 0.3 + 1e-8, 0.0]);
        assert_relative_eq!(segment_distance(&a, &b).distance, 0.3, epsilon = 1e-14);
    }

    #[test]
    fn distance_agrees_with_sampling() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut rnd = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for _ in 0..200 {
            let mut v = || Vector3::new(rnd(), rnd(), rnd());
            let p = Segment::new(v(), v());
            let q = Segment::new(v(), v());
            let d = segment_distance(&p, &q);
            let steps = 200;
            let s = sampled(&p, &q, steps);
            let h = (p.length() + q.length()) / steps as f64;
            assert!(d.distance <= s + 1e-12, "{} > sampled {}", d.distance, s);
            assert!(d.distance >= s - h, "{} < sampled {} − {h}", d.distance, s);
            assert_relative_eq!((p.at(d.s) - q.at(d.t)).norm(), d.distance, epsilon = 1e-12);
        }
    }

    fn unit_cube() -> ConvexPolyhedron {
        ConvexPolyhedron::cuboid(Vector3::repeat(1.0), Vector3::zeros()).unwrap()
    }

    #[test]
    fn cube_hull_has_eight_vertices_six_square_faces() {
        let c = unit_cube();
        assert_eq!(c.vertices().len(), 8);
        assert_eq!(c.faces().len(), 6);
        assert!(c.faces().iter().all(|f| f.len() == 4));
        assert_relative_eq!(c.volume(), 1.0, epsilon = 1e-14);
        assert_relative_eq!(c.depth(&Vector3::zeros()), 0.5);
        assert!(ConvexPolyhedron::cuboid(Vector3::new(1.0, 0.0, 1.0), Vector3::zeros()).is_err());
        let flat = [
            Vector3::zeros(),
            Vector3::x(),
            Vector3::y(),
            Vector3::new(1.0, 1.0, 0.0),
        ];
        assert!(matches!(
            ConvexPolyhedron::from_points(&flat),
            Err(KinematicsError::DegenerateShape { .. })
        ));
    }

    #[test]
    fn cable_through_the_platform_interferes() {
        let c = unit_cube();
        // Straight through the centre along x: deepest point at the centre, 0.5 deep.
        let through = seg([-2.0, 0.0, 0.0], [2.0, 0.0, 0.0]);
        assert_relative_eq!(c.penetration(&through), 0.5, epsilon = 1e-15);
        assert!(c.is_entered_by(&through));
        // Across the edge x = y = 0.5 along x + y = 0.9: inside for x ∈ [0.4, 0.5], deepest at
        // x = 0.45, min(0.5 − x, 0.5 − y) = 0.05.
        let corner = seg([-0.1, 1.0, 0.0], [1.0, -0.1, 0.0]);
        assert_relative_eq!(c.penetration(&corner), 0.05, epsilon = 1e-15);
        // Missing the cube.
        let miss = seg([-2.0, 0.0, 0.7], [2.0, 0.0, 0.7]);
        assert!(!c.is_entered_by(&miss));
        // Grazing along a face: on the surface, not inside.
        let graze = seg([-2.0, 0.5, 0.0], [2.0, 0.5, 0.0]);
        assert!(!c.is_entered_by(&graze));
    }

    #[test]
    fn cable_leaving_from_a_vertex_outward_does_not_interfere() {
        let c = unit_cube();
        let v = Vector3::new(0.5, 0.5, 0.5);
        // Outward along the diagonal, and along any direction into the outer octant.
        for dir in [
            Vector3::new(1.0, 1.0, 1.0),
            Vector3::new(1.0, 0.0, 0.0),
            Vector3::new(2.0, 1.0, 0.1),
        ] {
            assert!(!c.is_entered_by(&Segment::new(v, v + dir * 3.0)), "{dir}");
        }
        // Along an edge of the cube (tangent): not inside either.
        assert!(!c.is_entered_by(&Segment::new(v, v - Vector3::x() * 3.0)));
        // Back through the cube towards the opposite corner: interferes.
        assert!(c.is_entered_by(&Segment::new(v, -v * 5.0)));
        // From a vertex along a face diagonal, leaving the cube across the face: tangent.
        assert!(!c.is_entered_by(&Segment::new(v, v - Vector3::new(1.0, 1.0, 0.0))));
        // From a vertex slightly inward of a face: enters.
        assert!(c.is_entered_by(&Segment::new(v, v - Vector3::new(1.0, 1.0, 0.01))));
    }

    #[test]
    fn shared_endpoints_meet_by_design() {
        let a = seg([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]);
        let b = seg([0.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        assert!(share_endpoint_only(&a, &b, 1e-12));
        let overlap = seg([0.0, 0.0, 0.0], [2.0, 0.0, 0.0]);
        assert!(!share_endpoint_only(&a, &overlap, 1e-12));
        let apart = seg([0.0, 1.0, 0.0], [1.0, 1.0, 0.0]);
        assert!(!share_endpoint_only(&a, &apart, 1e-12));
    }
}
