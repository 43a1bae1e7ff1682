//! Structured quadrilateral meshes of a 2-D orthogonal cut (paper Sec 5.1): the workpiece strip and
//! the tool, in metres, for [`crate::deck2d`].
//!
//! Geometry (x along the cut, y up, the uncut surface at y = 0, the edge path at y = -t1):
//! - **workpiece**: x in [0, L] with L = 8 mm cut (paper Sec 5.1) + [`BACK_MARGIN_M`], y in
//!   [-H, 0] with H = [`DEPTH_FACTOR`] t1. Columns are uniform at the fine size h (<= 5 um, the
//!   paper's minimum element size) over the whole length, so the chip/cut layer is fine wherever
//!   the edge passes. Rows: h from the surface down to [`FINE_DEPTH_FACTOR`] t1 (the uncut layer
//!   and one t1 below the edge path), then growing geometrically by [`GROWTH`] to the bottom.
//! - **tool**: the rake face leaves the edge along (sin a, cos a) (rake angle a, positive rake
//!   leans away from the uncut material), the flank face along (cos g, sin g) with the clearance
//!   g = 7 deg; the wedge angle is 90 deg - a - g (Shaw, Metal Cutting Principles, 2nd ed., Ch. 2).
//!   An edge radius r rounds the corner with an arc tangent to both faces; the arc's lowest point
//!   (or the sharp corner) lies on the edge path y = -t1. The tool is meshed in layers that are
//!   scaled copies of the working boundary (flank, arc, rake) about a point inside the wedge, with the edge initially [`TOOL_START_GAP_FACTOR`] t1 to the right of the
//!   workpiece (x = L + gap).

use std::f64::consts::PI;

/// The paper's clearance angle of the tool, rad (issue 12 Build 4: 7 deg).
pub const CLEARANCE_RAD: f64 = 7.0 * PI / 180.0;
/// Workpiece length behind the 8 mm cut (never cut; the fixed back), m.
pub const BACK_MARGIN_M: f64 = 2e-3;
/// Workpiece height H / t1.
pub const DEPTH_FACTOR: f64 = 5.0;
/// Depth of the fine layer / t1 (uncut layer plus one t1 below the edge path).
pub const FINE_DEPTH_FACTOR: f64 = 2.0;
/// Geometric growth of the row heights below the fine layer.
pub const GROWTH: f64 = 1.2;
/// Rake-face length / t1 (longer than the chip contact length, 1-3 chip thicknesses).
pub const RAKE_LENGTH_FACTOR: f64 = 10.0;
/// Flank-face length / t1.
pub const FLANK_LENGTH_FACTOR: f64 = 5.0;
/// Twice the distance of the tool layers' centre K from the sharp corner / t1.
pub const TOOL_DEPTH_FACTOR: f64 = 4.0;
/// Scale of the innermost tool layer about its centre K (0: the layers would meet at K).
pub const TOOL_INNER_SCALE: f64 = 0.15;
/// Initial gap between the tool's right-most point of contact and the workpiece end / t1, plus
/// the rake overhang of a negative rake.
pub const TOOL_START_GAP_FACTOR: f64 = 0.5;

/// A mesh input out of range: names the input, its value and the rule.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct BadMeshInput(pub String);

/// A structured quad mesh: nodes (m) and elements (0-based node indices, counter-clockwise).
#[derive(Debug, Clone, PartialEq)]
pub struct QuadMesh {
    /// Node coordinates (x, y), m.
    pub nodes: Vec<[f64; 2]>,
    /// Elements, counter-clockwise node indices into `nodes`.
    pub elements: Vec<[usize; 4]>,
}

/// The two meshes of one cut and the facts the deck states.
#[derive(Debug, Clone, PartialEq)]
pub struct CutMesh {
    /// Workpiece strip.
    pub workpiece: QuadMesh,
    /// Tool.
    pub tool: QuadMesh,
    /// Workpiece nodes on the bottom (y = -H), indices into `workpiece.nodes`.
    pub bottom: Vec<usize>,
    /// Workpiece nodes on the back (x = 0).
    pub back: Vec<usize>,
    /// Fine element size h, m.
    pub fine_m: f64,
    /// Largest row height (bottom row), m.
    pub coarsest_row_m: f64,
    /// Workpiece length L and height H, m.
    pub length_m: f64,
    /// Workpiece height H, m.
    pub height_m: f64,
    /// Initial x of the tool's lowest point, m (the tool travels `travel_m` in -x).
    pub tool_start_x_m: f64,
    /// Tool travel: initial gap + the 8 mm cut, m.
    pub travel_m: f64,
    /// Rake and flank face unit directions (leaving the edge).
    pub rake_dir: [f64; 2],
    /// Flank face direction.
    pub flank_dir: [f64; 2],
}

/// Signed area of a quad (shoelace formula), m^2; positive when counter-clockwise.
#[must_use]
pub fn quad_area(m: &QuadMesh, e: &[usize; 4]) -> f64 {
    (0..4)
        .map(|i| {
            let (a, b) = (m.nodes[e[i]], m.nodes[e[(i + 1) % 4]]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
        / 2.0
}

/// Row heights of the workpiece from the top down: h to the fine depth, then geometric growth.
fn row_heights(t1: f64, h: f64) -> Vec<f64> {
    let fine_rows = (FINE_DEPTH_FACTOR * t1 / h).ceil() as usize;
    let hf = FINE_DEPTH_FACTOR * t1 / fine_rows as f64;
    let mut rows = vec![hf; fine_rows];
    let mut rest = (DEPTH_FACTOR - FINE_DEPTH_FACTOR) * t1;
    let mut next = hf * GROWTH;
    while rest > 1e-12 * t1 {
        let dy = if rest < 1.5 * next { rest } else { next };
        rows.push(dy);
        rest -= dy;
        next *= GROWTH;
    }
    rows
}

/// A grid of (nx + 1) x (ny + 1) nodes `at(i, j)` and its quads, counter-clockwise when `at` maps
/// (i, j) to a right-handed frame.
fn grid(nx: usize, ny: usize, at: impl Fn(usize, usize) -> [f64; 2]) -> QuadMesh {
    let mut nodes = Vec::with_capacity((nx + 1) * (ny + 1));
    for j in 0..=ny {
        for i in 0..=nx {
            nodes.push(at(i, j));
        }
    }
    let id = |i: usize, j: usize| j * (nx + 1) + i;
    let mut elements = Vec::with_capacity(nx * ny);
    for j in 0..ny {
        for i in 0..nx {
            elements.push([id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    QuadMesh { nodes, elements }
}

/// Points along the tool's working boundary from the flank end, round the edge, to the rake end,
/// with spacing at most `h`, relative to the sharp-corner point (0, 0).
fn working_boundary(rake: f64, radius: f64, t1: f64, h: f64) -> Vec<[f64; 2]> {
    let r = [rake.sin(), rake.cos()];
    let f = [CLEARANCE_RAD.cos(), CLEARANCE_RAD.sin()];
    let wedge = PI / 2.0 - rake - CLEARANCE_RAD;
    let tan_len = if radius > 0.0 { radius / (wedge / 2.0).tan() } else { 0.0 };
    let mut pts = Vec::new();
    // Flank: from its far end to the tangent point.
    let lf = FLANK_LENGTH_FACTOR * t1;
    let n = ((lf - tan_len) / h).ceil().max(1.0) as usize;
    for k in 0..n {
        let s = lf - (lf - tan_len) * k as f64 / n as f64;
        pts.push([f[0] * s, f[1] * s]);
    }
    if radius > 0.0 {
        let b = [f[0] + r[0], f[1] + r[1]];
        let bn = b[0].hypot(b[1]);
        let d = radius / (wedge / 2.0).sin();
        let c = [b[0] / bn * d, b[1] / bn * d];
        // Outward normals at the flank and rake tangent points; the arc turns clockwise through
        // PI - wedge from the first to the second.
        let a0 = (-f[0]).atan2(f[1]);
        let sweep = PI - wedge;
        let m = ((radius * sweep) / h).ceil().max(2.0) as usize;
        for k in 0..m {
            let a = a0 - sweep * k as f64 / m as f64;
            pts.push([c[0] + radius * a.cos(), c[1] + radius * a.sin()]);
        }
    }
    let lr = RAKE_LENGTH_FACTOR * t1;
    let n = ((lr - tan_len) / h).ceil().max(1.0) as usize;
    for k in 0..=n {
        let s = tan_len + (lr - tan_len) * k as f64 / n as f64;
        pts.push([r[0] * s, r[1] * s]);
    }
    pts
}

/// Builds the workpiece and tool meshes of one cut.
///
/// `t1` uncut chip thickness (m), `rake` rad, `radius` edge radius (m, 0 = sharp), `fine` the
/// element size of the chip/cut layer (m), `cut` the cut length (m).
///
/// Returns an error naming the value when `t1` is not in (0, 5 mm], the rake not in (-30, 45) deg,
/// the radius not in [0, t1], `fine` not in (0, t1/2] or the mesh would exceed 2 million elements.
pub fn build(t1: f64, rake: f64, radius: f64, fine: f64, cut: f64) -> Result<CutMesh, BadMeshInput> {
    let bad = |what: &str, v: f64, rule: &str| Err(BadMeshInput(format!("{what} = {v}: {rule}")));
    if !(t1 > 0.0 && t1 <= 5e-3) {
        return bad("uncut chip thickness (m)", t1, "must be in (0, 5 mm]");
    }
    if !(rake > -30f64.to_radians() && rake < 45f64.to_radians()) {
        return bad("rake angle (rad)", rake, "must be in (-30, 45) deg for a 7 deg clearance wedge");
    }
    if !(radius >= 0.0 && radius <= t1) {
        return bad("edge radius (m)", radius, "must be in [0, t1]");
    }
    if !(fine > 0.0 && fine <= t1 / 2.0) {
        return bad("fine element size (m)", fine, "must be in (0, t1/2]");
    }
    if !(cut > 0.0 && cut.is_finite()) {
        return bad("cut length (m)", cut, "must be positive");
    }
    let length = cut + BACK_MARGIN_M;
    let nx = (length / fine).ceil() as usize;
    let dx = length / nx as f64;
    let rows = row_heights(t1, dx.min(fine));
    let ny = rows.len();
    if nx * ny > 2_000_000 {
        return bad("elements", (nx * ny) as f64, "more than 2 million: use a larger fine size");
    }
    let mut ys = vec![0.0];
    for dy in &rows {
        ys.push(ys.last().copied().unwrap_or(0.0) - dy);
    }
    ys.reverse(); // bottom first, so that rows go up (counter-clockwise quads)
    let height = -ys[0];
    let workpiece = grid(nx, ny, |i, j| [i as f64 * dx, ys[j]]);
    let bottom = (0..=nx).collect();
    let back = (0..=ny).map(|j| j * (nx + 1)).collect();

    // Tool: working boundary relative to the sharp corner, shifted so that its lowest point is on
    // the edge path and its lowest-right... start gap to the right of the workpiece end.
    let s1 = working_boundary(rake, radius, t1, fine);
    let min_y = s1.iter().map(|p| p[1]).fold(f64::INFINITY, f64::min);
    let min_x = s1.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min);
    // The point that gave the minimum, found again bit for bit.
    let low = s1.iter().find(|p| p[1].to_bits() == min_y.to_bits()).copied().unwrap_or([0.0, 0.0]);
    let gap = TOOL_START_GAP_FACTOR * t1 + (low[0] - min_x);
    let shift = [length + gap - low[0], -t1 - min_y];
    let s1: Vec<[f64; 2]> = s1.iter().map(|p| [p[0] + shift[0], p[1] + shift[1]]).collect();
    let r = [rake.sin(), rake.cos()];
    let f = [CLEARANCE_RAD.cos(), CLEARANCE_RAD.sin()];
    // Layers: homothetic copies of the working boundary S1 towards a centre K inside the tool, on
    // the wedge bisector TOOL_DEPTH_FACTOR/2 t1 from the sharp corner: P(i, j) = K + lambda_j (S1_i - K),
    // lambda from 1 (the boundary) down to TOOL_INNER_SCALE. S1 is convex and K lies on its
    // concave side, so every ray from K meets S1 once and each quad is a trapezoid (two sides on
    // rays, two parallel to an S1 segment): no inverted element.
    let bis = [f[0] + r[0], f[1] + r[1]];
    let bn = bis[0].hypot(bis[1]);
    let k =
        [shift[0] + bis[0] / bn * TOOL_DEPTH_FACTOR / 2.0 * t1, shift[1] + bis[1] / bn * TOOL_DEPTH_FACTOR / 2.0 * t1];
    let nu = s1.len() - 1;
    let nv = 16;
    let tool = grid(nu, nv, |i, j| {
        let lambda = 1.0 - (1.0 - TOOL_INNER_SCALE) * (j as f64 / nv as f64).powf(1.5);
        [k[0] + lambda * (s1[i][0] - k[0]), k[1] + lambda * (s1[i][1] - k[1])]
    });
    // Counter-clockwise: flip every element when the grid's (i, j) frame is left-handed.
    let flip = tool.elements.first().is_some_and(|e| quad_area(&tool, e) < 0.0);
    let tool = if flip {
        QuadMesh { elements: tool.elements.iter().map(|e| [e[0], e[3], e[2], e[1]]).collect(), ..tool }
    } else {
        tool
    };
    Ok(CutMesh {
        workpiece,
        tool,
        bottom,
        back,
        fine_m: dx.max(rows[0]),
        coarsest_row_m: rows.iter().copied().fold(0.0, f64::max),
        length_m: length,
        height_m: height,
        tool_start_x_m: length + gap,
        travel_m: gap + cut,
        rake_dir: r,
        flank_dir: f,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const CUT: f64 = 8e-3;

    fn angle_deg(a: [f64; 2], b: [f64; 2]) -> f64 {
        (a[0] * b[0] + a[1] * b[1]).clamp(-1.0, 1.0).acos().to_degrees()
    }

    /// The meshes of C38 test 1 (paper Table 2: t1 = 0.075 mm, rake 0, edge radius 25 um, Sec 2)
    /// and an AA6082-like condition with another rake and no radius.
    fn cases() -> Vec<(f64, f64, f64)> {
        vec![(0.075e-3, 0.0, 25e-6), (0.2e-3, 8f64.to_radians(), 0.0), (0.05e-3, -6f64.to_radians(), 10e-6)]
    }

    #[test]
    fn element_count_is_columns_times_rows() {
        for (t1, rake, r) in cases() {
            let m = build(t1, rake, r, 5e-6, CUT).unwrap();
            // Columns: ceil(10 mm / 5 um) = 2000; rows: ceil(2 t1 / 5 um) fine rows + the graded rows.
            let nx = 2000;
            let fine_rows = (2.0 * t1 / 5e-6_f64).ceil() as usize;
            let graded = row_heights(t1, 5e-6).len() - fine_rows;
            assert!(graded >= 1);
            assert_eq!(m.workpiece.elements.len(), nx * (fine_rows + graded));
            assert_eq!(m.workpiece.nodes.len(), (nx + 1) * (fine_rows + graded + 1));
            assert!((m.length_m - 10e-3).abs() < 1e-12 && (m.height_m - 5.0 * t1).abs() < 1e-12 * t1 * 1e3);
        }
    }

    #[test]
    fn elements_near_the_edge_path_are_at_most_5_um() {
        for (t1, rake, r) in cases() {
            let m = build(t1, rake, r, 5e-6, CUT).unwrap();
            let w = &m.workpiece;
            let mut near = 0;
            for e in &w.elements {
                let ys: Vec<f64> = e.iter().map(|n| w.nodes[*n][1]).collect();
                let xs: Vec<f64> = e.iter().map(|n| w.nodes[*n][0]).collect();
                let yc = ys.iter().sum::<f64>() / 4.0;
                // The chip/cut layer: from the surface to one t1 below the edge path y = -t1.
                if yc > -2.0 * t1 {
                    near += 1;
                    let dy = ys.iter().copied().fold(f64::MIN, f64::max) - ys.iter().copied().fold(f64::MAX, f64::min);
                    let dx = xs.iter().copied().fold(f64::MIN, f64::max) - xs.iter().copied().fold(f64::MAX, f64::min);
                    assert!(dx <= 5e-6 * (1.0 + 1e-9) && dy <= 5e-6 * (1.0 + 1e-9), "{dx} {dy}");
                }
            }
            assert!(near >= 2000 * 2 * (t1 / 5e-6) as usize - 1);
            assert!(m.fine_m <= 5e-6 * (1.0 + 1e-9));
            // Graded below: the bottom row is the coarsest and at most GROWTH x its neighbour (or 1.5x).
            assert!(m.coarsest_row_m > m.fine_m);
        }
    }

    #[test]
    fn no_inverted_element_and_numbering_is_consistent() {
        for (t1, rake, r) in cases() {
            let m = build(t1, rake, r, 5e-6, CUT).unwrap();
            for mesh in [&m.workpiece, &m.tool] {
                let mut used = vec![false; mesh.nodes.len()];
                for e in &mesh.elements {
                    assert!(quad_area(mesh, e) > 0.0, "inverted element {e:?} (t1 {t1}, rake {rake}, r {r})");
                    // Every corner of a convex-or-not quad turns left: no bow-tie.
                    for k in 0..4 {
                        let (a, b, c) = (mesh.nodes[e[k]], mesh.nodes[e[(k + 1) % 4]], mesh.nodes[e[(k + 2) % 4]]);
                        let cross = (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]);
                        assert!(
                            cross > 0.0,
                            "non-convex corner in {e:?} of {} nodes: {a:?} {b:?} {c:?}",
                            mesh.nodes.len()
                        );
                    }
                    for n in e {
                        used[*n] = true;
                    }
                }
                assert!(used.iter().all(|u| *u), "a node belongs to no element");
            }
            assert!(m.bottom.iter().all(|n| (m.workpiece.nodes[*n][1] + m.height_m).abs() < 1e-15));
            assert!(m.back.iter().all(|n| m.workpiece.nodes[*n][0] == 0.0));
            // Tool and workpiece do not overlap at the start.
            let tool_min_x = m.tool.nodes.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min);
            assert!(tool_min_x > m.length_m);
            // The tool's lowest point is on the edge path.
            let low = m.tool.nodes.iter().map(|p| p[1]).fold(f64::INFINITY, f64::min);
            assert!((low + t1).abs() < 1e-12, "{low}");
        }
    }

    #[test]
    fn tool_angles_equal_the_test_rake_and_7_deg_clearance() {
        for (t1, rake, r) in cases() {
            let m = build(t1, rake, r, 5e-6, CUT).unwrap();
            // Rake angle: between the rake face and the normal to the cutting direction (y axis).
            assert!((angle_deg(m.rake_dir, [0.0, 1.0]) - rake.abs().to_degrees()).abs() < 1e-9);
            assert_eq!(m.rake_dir[0].signum() * rake.signum(), rake.signum().abs());
            // Clearance: between the flank and the machined surface (x axis).
            assert!((angle_deg(m.flank_dir, [1.0, 0.0]) - 7.0).abs() < 1e-9);
            // The meshed faces: the last two boundary nodes of the rake face and the first two of
            // the flank (row v = 0 of the tool patch) lie along these directions.
            let s1: Vec<[f64; 2]> = working_boundary(rake, r, t1, 5e-6);
            let n = s1.len();
            let rake_face = [s1[n - 1][0] - s1[n - 2][0], s1[n - 1][1] - s1[n - 2][1]];
            let flank_face = [s1[0][0] - s1[1][0], s1[0][1] - s1[1][1]];
            let norm = |v: [f64; 2]| [v[0] / v[0].hypot(v[1]), v[1] / v[0].hypot(v[1])];
            assert!((angle_deg(norm(rake_face), [0.0, 1.0]) - rake.abs().to_degrees()).abs() < 1e-6);
            assert!((angle_deg(norm(flank_face), [1.0, 0.0]) - 7.0).abs() < 1e-6);
            // A rounded edge: the points inside the tangent length lie at r from the centre on the
            // bisector at r / sin(wedge/2) from the sharp corner.
            if r > 0.0 {
                let wedge = PI / 2.0 - rake - CLEARANCE_RAD;
                let b = norm([m.flank_dir[0] + m.rake_dir[0], m.flank_dir[1] + m.rake_dir[1]]);
                let d = r / (wedge / 2.0).sin();
                let arc: Vec<_> = s1.iter().filter(|p| p[0].hypot(p[1]) < r / (wedge / 2.0).tan() * 0.999).collect();
                assert!(arc.len() >= 2);
                for p in arc {
                    assert!(((p[0] - b[0] * d).hypot(p[1] - b[1] * d) - r).abs() < 1e-9 * r * 1e3, "{p:?}");
                }
            }
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(24))]
        /// Over the range users will use (t1 0.02-0.5 mm, rake -25..40 deg, radius 0..t1/2), every
        /// tool quad is convex and counter-clockwise, the workpiece quads are positive, and the
        /// tool's lowest point is on the edge path. (Fine size t1/4 keeps the case small; the tool
        /// mesh is built the same way at any size.)
        #[test]
        fn every_tool_in_range_meshes_without_inversion(
            t1_um in 20.0f64..500.0, rake_deg in -25.0f64..40.0, r_frac in 0.0f64..0.5
        ) {
            let t1 = t1_um * 1e-6;
            let m = build(t1, rake_deg.to_radians(), r_frac * t1, t1 / 4.0, CUT).unwrap();
            for e in &m.tool.elements {
                for k in 0..4 {
                    let (a, b, c) = (m.tool.nodes[e[k]], m.tool.nodes[e[(k + 1) % 4]], m.tool.nodes[e[(k + 2) % 4]]);
                    let cross = (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]);
                    proptest::prop_assert!(cross > 0.0, "corner of {:?}", e);
                }
            }
            proptest::prop_assert!(m.workpiece.elements.iter().all(|e| quad_area(&m.workpiece, e) > 0.0));
            let low = m.tool.nodes.iter().map(|p| p[1]).fold(f64::INFINITY, f64::min);
            proptest::prop_assert!((low + t1).abs() < 1e-9 * t1);
            proptest::prop_assert!(m.tool.nodes.iter().all(|p| p[0] > m.length_m));
        }
    }

    #[test]
    fn bad_inputs_are_errors_naming_the_value() {
        assert!(build(0.0, 0.0, 0.0, 5e-6, CUT).unwrap_err().0.contains("uncut chip thickness"));
        assert!(build(0.1e-3, 1.0, 0.0, 5e-6, CUT).unwrap_err().0.contains("rake"));
        assert!(build(0.1e-3, 0.0, 0.2e-3, 5e-6, CUT).unwrap_err().0.contains("edge radius"));
        assert!(build(0.1e-3, 0.0, 0.0, f64::NAN, CUT).unwrap_err().0.contains("fine"));
    }
}
