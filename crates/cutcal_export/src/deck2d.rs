//! A complete 2-D plane-strain, coupled thermal-structural LS-DYNA deck of one orthogonal cutting
//! test (issue 12 Build 4; paper Sec 5.1): the workpiece strip and tool meshes of
//! [`crate::deck2d_mesh`], the material, thermal and friction data of the LS-DYNA cards (the same
//! template context, [`crate::lsdyna`]), a rigid conducting tool, 2-D thermal contact, tool motion
//! over the paper's 8 mm cut, boundary conditions, output requests and 2-D adaptive remeshing as
//! the chip-separation method. Template `templates/lsdyna_cut2d.k.hbs`; docs/fe-cards.md
//! "Complete 2-D decks".
//!
//! Friction in 2-D: LS-DYNA's 2-D thermal contact takes only FS/FD/DC and the shear cap VC (manual
//! text shipped with PyDyna 0.12.1, `*CONTACT_2D_AUTOMATIC_SURFACE_TO_SURFACE_THERMAL`), so paper
//! Eq 17, `tau = m0 (1 - exp(-beta P)) k`, is written as its two asymptotes (Zorev's
//! sticking-sliding form): `mu = m0 k beta` (the slope of Eq 17 at P = 0) and `VC = m0 k` (its
//! limit), with k = k(Tc) of the cards. The bilinear law `min(mu P, VC)` equals Eq 17 for
//! P -> 0 and P -> inf and overstates it most at P = 1/beta, by `1/(1 - 1/e) - 1 = 58.2 %`
//! (stated in the deck; [`zorev_max_overstatement`]). Coulomb interfaces keep FS = FD = mu.

use handlebars::Handlebars;
use serde::Serialize;
use serde_json::Value;

use crate::deck2d_mesh::{self, CutMesh, QuadMesh, CLEARANCE_RAD};
use crate::lsdyna::{self, CUT_LENGTH_M, MIN_ELEMENT_M};
use crate::physics::{self, Prepared};
use crate::{numfmt, templates, ExportError, ExportFile, ExportInput};
use cutcal_model::CuttingTest;

/// Load-curve id of the tool velocity.
const VELOCITY_LCID: i64 = 500;
/// Remeshing interval: the time the tool takes to travel this many fine elements.
const REMESH_EVERY_ELEMENTS: f64 = 5.0;
/// d3plot states over the run.
const D3PLOT_STATES: f64 = 100.0;
/// RCFORC / GLSTAT outputs over the run.
const FORCE_OUTPUTS: f64 = 2000.0;

/// The largest relative overstatement of Eq 17 by the 2-D Zorev form `min(m0 k beta P, m0 k)`:
/// at P = 1/beta it is `1/(1 - e^-1) - 1` (paper Eq 17 against its two asymptotes).
#[must_use]
pub fn zorev_max_overstatement() -> f64 {
    1.0 / (1.0 - (-1.0f64).exp()) - 1.0
}

#[derive(Serialize)]
struct Deck {
    test_id: String,
    speed_m_min: f64,
    t1_mm: f64,
    width_mm: f64,
    rake_deg: f64,
    clearance_deg: f64,
    edge_radius_um: f64,
    edge_stated: bool,
    fine_um: f64,
    coarsest_um: f64,
    length_mm: f64,
    height_mm: f64,
    n_wp_el: usize,
    n_tool_el: usize,
    travel_mm: f64,
    vel_lcid: i64,
    /// LS-DYNA's "never" times: contact/adaptivity death 1e20, prescribed-motion death 1e28 (defaults).
    never: f64,
    never_motion: f64,
    velocity: f64,
    endtim: f64,
    adpfreq: f64,
    adptol: f64,
    d3plot_dt: f64,
    force_dt: f64,
    fs: f64,
    vc: f64,
    eq17_2d: bool,
    zorev_pct: f64,
    thickness: f64,
    nodes: String,
    elements: String,
    bottom_set: String,
    back_set: String,
}

fn node_lines(out: &mut String, m: &QuadMesh, first_id: usize, length: f64) -> Result<(), ExportError> {
    for (k, p) in m.nodes.iter().enumerate() {
        let x = numfmt::real(p[0] * length, 9)
            .map_err(|e| ExportError::NonFinite { field: "node x".into(), value: e.0 })?;
        let y = numfmt::real(p[1] * length, 9)
            .map_err(|e| ExportError::NonFinite { field: "node y".into(), value: e.0 })?;
        out.push_str(&format!("{:>8}{x:>16}{y:>16}{:>16}{:>8}{:>8}\n", first_id + k, "0.", 0, 0));
    }
    Ok(())
}

fn element_lines(out: &mut String, m: &QuadMesh, first_eid: usize, pid: usize, first_node: usize) {
    for (k, e) in m.elements.iter().enumerate() {
        out.push_str(&format!("{:>8}{pid:>8}", first_eid + k));
        for n in e {
            out.push_str(&format!("{:>8}", first_node + n));
        }
        out.push('\n');
    }
}

/// `*SET_NODE_LIST` data: 8 ids per line in 10 columns.
fn id_lines(ids: &[usize], first_node: usize) -> String {
    ids.chunks(8).map(|c| c.iter().map(|i| format!("{:>10}", first_node + i)).collect::<String>() + "\n").collect()
}

fn bad(field: &str, value: f64, expected: &str) -> ExportError {
    ExportError::BadOption { field: field.into(), value: value.to_string(), expected: expected.into() }
}

/// Builds the meshes of a test: fine size min(5 um (paper Sec 5.1), t1/2), the paper's 8 mm cut.
///
/// Returns an error naming the test and the value when the test cannot be meshed.
pub fn mesh_of(test: &CuttingTest) -> Result<CutMesh, ExportError> {
    let t1 = test.uncut_chip_thickness_m;
    let fine = MIN_ELEMENT_M.min(t1 / 2.0);
    deck2d_mesh::build(t1, test.rake_rad, test.edge_radius_m.unwrap_or(0.0), fine, CUT_LENGTH_M).map_err(|e| {
        ExportError::BadOption {
            field: format!("cutting test {}", test.id),
            value: e.0,
            expected: "a test that can be meshed".into(),
        }
    })
}

/// Renders the complete 2-D LS-DYNA deck of one cutting test, `<material>_cut2d_<test>.k`.
///
/// Needs a tool material (the rigid conducting tool's thermal data). Returns an error if the input
/// fails validation, there is no tool, the test id is not a card name, or the test cannot be meshed.
pub fn render_cut2d(input: &ExportInput<'_>, test: &CuttingTest) -> Result<ExportFile, ExportError> {
    physics::check_name(&test.id)?;
    let prepared: Prepared = physics::prepare(input)?;
    if prepared.tool.is_none() {
        return Err(ExportError::Missing { dialect: "lsdyna cut2d".into(), what: "a tool material".into() });
    }
    let v = test.speed_m_per_s;
    if !(v > 0.0 && v.is_finite()) {
        return Err(bad("cutting speed (m/s)", v, "positive"));
    }
    let mesh = mesh_of(test)?;
    let f = input.options.units.factors();
    let (fs, vc, eq17_2d) = match (&prepared.mu_table, prepared.coulomb_mu) {
        (Some(m), _) => (m.m0 * m.at_contact.k_pa * m.beta_per_pa, m.m0 * m.at_contact.k_pa * f.stress, true),
        (None, Some(mu)) => (mu, 0.0, false),
        (None, None) => {
            return Err(ExportError::Missing { dialect: "lsdyna cut2d".into(), what: "a friction law".into() })
        }
    };
    let endtim = mesh.travel_m / v;
    let nw = mesh.workpiece.nodes.len();
    let ew = mesh.workpiece.elements.len();
    let mut nodes = String::new();
    node_lines(&mut nodes, &mesh.workpiece, 1, f.length)?;
    node_lines(&mut nodes, &mesh.tool, nw + 1, f.length)?;
    let mut elements = String::new();
    element_lines(&mut elements, &mesh.workpiece, 1, 1, 1);
    element_lines(&mut elements, &mesh.tool, ew + 1, 2, nw + 1);
    let deck = Deck {
        test_id: test.id.clone(),
        speed_m_min: v * 60.0,
        t1_mm: test.uncut_chip_thickness_m * 1e3,
        width_mm: test.width_m * 1e3,
        rake_deg: test.rake_rad.to_degrees(),
        clearance_deg: CLEARANCE_RAD.to_degrees(),
        edge_radius_um: test.edge_radius_m.unwrap_or(0.0) * 1e6,
        edge_stated: test.edge_radius_m.is_some(),
        fine_um: mesh.fine_m * 1e6,
        coarsest_um: mesh.coarsest_row_m * 1e6,
        length_mm: mesh.length_m * 1e3,
        height_mm: mesh.height_m * 1e3,
        n_wp_el: ew,
        n_tool_el: mesh.tool.elements.len(),
        travel_mm: mesh.travel_m * 1e3,
        vel_lcid: VELOCITY_LCID,
        never: 1e20,
        never_motion: 1e28,
        velocity: v * f.velocity,
        endtim,
        adpfreq: REMESH_EVERY_ELEMENTS * mesh.fine_m / v,
        adptol: mesh.fine_m * f.length,
        d3plot_dt: endtim / D3PLOT_STATES,
        force_dt: endtim / FORCE_OUTPUTS,
        fs: ExportError::finite("2-D friction coefficient", fs)?,
        vc: ExportError::finite("2-D shear cap VC", vc)?,
        eq17_2d,
        zorev_pct: zorev_max_overstatement() * 100.0,
        thickness: f.length * 1e-3,
        nodes,
        elements,
        bottom_set: id_lines(&mesh.bottom, 1),
        back_set: id_lines(&mesh.back, 1),
    };
    let mut ctx = lsdyna::context(&prepared, input)?;
    let deck = serde_json::to_value(&deck)
        .map_err(|e| ExportError::Template { template: "lsdyna_cut2d".into(), message: e.to_string() })?;
    if let Value::Object(o) = &mut ctx {
        o.insert("deck".into(), deck);
    }
    let hb: Handlebars<'_> = templates::registry()?;
    Ok(ExportFile {
        name: format!("{}_cut2d_{}.k", prepared.stem, test.id),
        contents: templates::render(&hb, "lsdyna_cut2d", &ctx)?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zorev_overstatement_is_at_one_over_beta() {
        // Independent: scan P beta in (0, 20] for the largest min(x, 1)/(1 - e^-x) - 1.
        let worst = (1..=20_000)
            .map(|i| {
                let x = f64::from(i) * 1e-3;
                x.min(1.0) / (1.0 - (-x).exp()) - 1.0
            })
            .fold(0.0, f64::max);
        assert!((worst - zorev_max_overstatement()).abs() < 1e-6, "{worst}");
        assert!((zorev_max_overstatement() - 0.581_976_7).abs() < 1e-6);
    }

    #[test]
    fn id_lines_are_eight_per_line() {
        let s = id_lines(&(0..10).collect::<Vec<_>>(), 1);
        assert_eq!(s.lines().count(), 2);
        assert_eq!(s.lines().next().unwrap().len(), 80);
    }
}
