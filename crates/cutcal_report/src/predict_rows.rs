//! The report of a prediction: one row per test against its measurement (forces over the width in
//! N, chip thickness in mm, % errors, the tool-condition terms), the JSON document of
//! `cutcal predict --json`, and its readable table.

use std::fmt::Write as _;

use cutcal_model::oxley::{OxleyOptions, OxleyPrediction};
use cutcal_model::CuttingTest;
use serde::Serialize;

/// One test's prediction against its measurement.
#[derive(Debug, Clone, Serialize)]
pub struct PredictRow {
    /// Test id.
    pub test: String,
    /// Predicted cutting force over the width, N.
    pub fc_n: Option<f64>,
    /// Measured cutting force over the width, N.
    pub fc_measured_n: Option<f64>,
    /// (pred - meas)/meas, %.
    pub fc_error_pct: Option<f64>,
    /// Predicted feed force over the width, N.
    pub ft_n: Option<f64>,
    /// Measured feed force, N.
    pub ft_measured_n: Option<f64>,
    /// %.
    pub ft_error_pct: Option<f64>,
    /// Predicted chip thickness, mm.
    pub tc_mm: Option<f64>,
    /// Measured chip thickness, mm.
    pub tc_measured_mm: Option<f64>,
    /// %.
    pub tc_error_pct: Option<f64>,
    /// Measured interface temperature, degC.
    pub t_int_measured_c: Option<f64>,
    /// Edge radius used, um (None: sharp edge).
    pub edge_radius_um: Option<f64>,
    /// Flank wear land used, mm (None: no wear land).
    pub flank_wear_mm: Option<f64>,
    /// Edge-ploughing cutting force over the width, N (Waldorf, DeVor & Kapoor 1998).
    pub edge_fc_n: Option<f64>,
    /// Edge-ploughing feed force over the width, N.
    pub edge_ft_n: Option<f64>,
    /// Wear-land cutting force over the width, N (Smithey, Kapoor & DeVor 2001).
    pub wear_fc_n: Option<f64>,
    /// Wear-land feed force over the width, N.
    pub wear_ft_n: Option<f64>,
    /// The full prediction (SI), if the solve succeeded.
    pub prediction: Option<OxleyPrediction>,
    /// The solver error, if it failed.
    pub error: Option<String>,
}

/// The JSON document of `cutcal predict --json`.
#[derive(Debug, Clone, Serialize)]
pub struct PredictReport {
    /// Material name.
    pub material: String,
    /// Options used.
    pub options: OxleyOptions,
    /// Work temperature, degC.
    pub work_temperature_c: f64,
    /// `true` with `--sharp`: stated edge radii and wear lands were ignored.
    pub sharp: bool,
    /// One row per test.
    pub rows: Vec<PredictRow>,
}

pub(crate) fn pct(pred: f64, meas: Option<f64>) -> Option<f64> {
    meas.map(|m| 100.0 * (pred - m) / m)
}

impl PredictRow {
    /// The tool-condition terms in words, e.g. `edge r_e 25 um: Fc +37.2 N (13 %), Ft +93.0 N (40 %)`;
    /// empty for a sharp, unworn tool.
    #[must_use]
    pub fn tool_note(&self) -> String {
        let mut parts = Vec::new();
        let share = |part: f64, total: Option<f64>| total.filter(|t| t.abs() > 0.0).map(|t| 100.0 * part / t);
        let fmt = |what: String, c: Option<f64>, t: Option<f64>| -> Option<String> {
            let (c, t) = (c?, t?);
            let pc = share(c, self.fc_n).map_or_else(String::new, |p| format!(" ({p:.0} % of Fc)"));
            let pt = share(t, self.ft_n).map_or_else(String::new, |p| format!(" ({p:.0} % of Ft)"));
            Some(format!("{what}: Fc +{c:.1} N{pc}, Ft +{t:.1} N{pt}"))
        };
        if let Some(r) = self.edge_radius_um {
            parts.extend(fmt(format!("edge r_e {r:.0} um (Waldorf 1998)"), self.edge_fc_n, self.edge_ft_n));
        }
        if let Some(vb) = self.flank_wear_mm {
            parts.extend(fmt(format!("wear VB {vb:.3} mm (Smithey 2001)"), self.wear_fc_n, self.wear_ft_n));
        }
        parts.join("; ")
    }
}

/// A row for one test from its prediction (or error).
pub fn row(test: &CuttingTest, result: Result<OxleyPrediction, String>) -> PredictRow {
    let w = test.width_m;
    let m = &test.measured;
    let fc_meas = m.cutting_force_n_per_m.map(|v| v * w);
    let ft_meas = m.feed_force_n_per_m.map(|v| v * w);
    let tc_meas = m.chip_thickness_m.map(|v| v * 1e3);
    match result {
        Ok(p) => {
            let tc = p.chip_thickness_m * 1e3;
            PredictRow {
                test: test.id.clone(),
                fc_n: Some(p.cutting_force_n),
                fc_measured_n: fc_meas,
                fc_error_pct: pct(p.cutting_force_n, fc_meas),
                ft_n: Some(p.feed_force_n),
                ft_measured_n: ft_meas,
                ft_error_pct: pct(p.feed_force_n, ft_meas),
                tc_mm: Some(tc),
                tc_measured_mm: tc_meas,
                tc_error_pct: pct(tc, tc_meas),
                t_int_measured_c: m.interface_temperature_c,
                edge_radius_um: p.edge_radius_m.map(|r| r * 1e6),
                flank_wear_mm: p.flank_wear_m.map(|v| v * 1e3),
                edge_fc_n: p.edge_radius_m.map(|_| p.edge_cutting_force_n_per_m * w),
                edge_ft_n: p.edge_radius_m.map(|_| p.edge_feed_force_n_per_m * w),
                wear_fc_n: p.flank_wear_m.map(|_| p.wear_cutting_force_n_per_m * w),
                wear_ft_n: p.flank_wear_m.map(|_| p.wear_feed_force_n_per_m * w),
                prediction: Some(p),
                error: None,
            }
        }
        Err(e) => PredictRow {
            test: test.id.clone(),
            fc_n: None,
            fc_measured_n: fc_meas,
            fc_error_pct: None,
            ft_n: None,
            ft_measured_n: ft_meas,
            ft_error_pct: None,
            tc_mm: None,
            tc_measured_mm: tc_meas,
            tc_error_pct: None,
            t_int_measured_c: m.interface_temperature_c,
            edge_radius_um: None,
            flank_wear_mm: None,
            edge_fc_n: None,
            edge_ft_n: None,
            wear_fc_n: None,
            wear_ft_n: None,
            prediction: None,
            error: Some(e),
        },
    }
}

fn cell(v: Option<f64>, digits: usize) -> String {
    v.map_or_else(|| "-".into(), |x| format!("{x:.digits$}"))
}

/// The readable table of a report.
pub fn table(report: &PredictReport) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "extended Oxley (Lalwani 2009) for {}: eta {}, psi {}, work {} degC",
        report.material, report.options.eta, report.options.psi, report.work_temperature_c
    );
    let _ = writeln!(
        s,
        "{}",
        if report.sharp {
            "tool: sharp and unworn (--sharp): stated edge radii and wear lands ignored"
        } else {
            "tool: edge ploughing (Waldorf, DeVor & Kapoor 1998) and wear land (Smithey, Kapoor & DeVor 2001) \
             included where a test states r_e / VB"
        }
    );
    let _ = writeln!(
        s,
        "{:<6} {:>8} {:>8} {:>7} | {:>8} {:>8} {:>7} | {:>7} {:>7} {:>7} | {:>6} {:>6} {:>6} {:>5} {:>7} {:>6}  flags",
        "test",
        "Fc N",
        "meas",
        "err %",
        "Ft N",
        "meas",
        "err %",
        "tc mm",
        "meas",
        "err %",
        "phi",
        "C0",
        "delta",
        "T_AB",
        "T_int",
        "T_meas"
    );
    for r in &report.rows {
        if let Some(e) = &r.error {
            let _ = writeln!(s, "{:<6} failed: {e}", r.test);
            continue;
        }
        let Some(p) = &r.prediction else { continue };
        let mut flags = Vec::new();
        let f = p.flags;
        for (on, name) in [
            (f.phi_at_bound, "phi-at-bound"),
            (f.c0_at_bound, "C0-at-bound"),
            (f.delta_at_bound, "delta-at-bound"),
            (f.delta_poorly_determined, "delta-flat"),
            (f.heat_partition_extrapolated, "beta-extrapolated"),
            (f.multiple_phi_roots, "multiple-phi-roots"),
        ] {
            if on {
                flags.push(name);
            }
        }
        let _ = writeln!(
            s,
            "{:<6} {:>8} {:>8} {:>7} | {:>8} {:>8} {:>7} | {:>7} {:>7} {:>7} | {:>6.2} {:>6.2} {:>6.3} {:>5.0} {:>7.0} {:>6}  {}",
            r.test,
            cell(r.fc_n, 1),
            cell(r.fc_measured_n, 1),
            cell(r.fc_error_pct, 1),
            cell(r.ft_n, 1),
            cell(r.ft_measured_n, 1),
            cell(r.ft_error_pct, 1),
            cell(r.tc_mm, 3),
            cell(r.tc_measured_mm, 3),
            cell(r.tc_error_pct, 1),
            p.phi_rad.to_degrees(),
            p.c0,
            p.delta,
            p.temperature_ab_c,
            p.temperature_int_c,
            cell(r.t_int_measured_c, 0),
            flags.join(",")
        );
        let note = r.tool_note();
        if !note.is_empty() {
            let _ = writeln!(s, "{:<6} {note}", "");
        }
    }
    s
}
