//! The plots of a pipeline report: PSZ fields (paper Fig 4), DPZD vs fitted JC stress, flow curves.

use crate::error::Result;
use cutcal_model::dpzd::ZoneSolution;
use cutcal_model::JcParams;

use crate::svg::{Plot, Series};

fn field(z: &ZoneSolution, f: impl Fn(&cutcal_model::dpzd::ZonePoint) -> f64) -> Result<Vec<(f64, f64)>> {
    Ok(z.profile(201)?.iter().map(|p| (p.x_m * 1e3, f(p))).collect())
}

/// PSZ fields of the original vs the enhanced model over x (paper Fig 4): effective stress,
/// temperature, effective strain and strain rate. Returns `(file name, svg)` pairs.
pub fn zone_fields(original: &ZoneSolution, enhanced: &ZoneSolution, label: &str) -> Result<Vec<(String, String)>> {
    let pair = |title: &str, y: &str, f: &dyn Fn(&cutcal_model::dpzd::ZonePoint) -> f64| -> Result<String> {
        Ok(Plot {
            title: format!("{label}: {title}"),
            x_label: "x across the zone [mm] (EF = -h/2, CD = +h/2)".into(),
            y_label: y.into(),
            series: vec![
                Series::dashed("original DPZD", field(original, f)?),
                Series::line("enhanced DPZD", field(enhanced, f)?),
            ],
            diagonal: false,
        }
        .render())
    };
    Ok(vec![
        (
            "fig4_stress.svg".into(),
            pair("effective stress sqrt(3) tau_e (Eq 8)", "stress [MPa]", &|p| p.effective_stress_pa / 1e6)?,
        ),
        ("fig4_temperature.svg".into(), pair("temperature (Eq 12)", "T [degC]", &|p| p.temperature_c)?),
        ("fig4_strain.svg".into(), pair("effective strain (Eq 5)", "strain [-]", &|p| p.strain)?),
        (
            "fig4_strain_rate.svg".into(),
            pair("effective strain rate (Eq 2)", "strain rate [1/s]", &|p| p.strain_rate_per_s)?,
        ),
    ])
}

/// DPZD effective stress vs the identified JC stress over x (the Eq 15 fit).
pub fn fit_over_x(zone: &ZoneSolution, jc: &JcParams, label: &str) -> Result<String> {
    let pts = zone.interior_points(101)?;
    Ok(Plot {
        title: format!("{label}: DPZD stress vs fitted JC stress"),
        x_label: "x [mm]".into(),
        y_label: "effective stress [MPa]".into(),
        series: vec![
            Series::line(
                "DPZD sqrt(3) tau_e",
                pts.iter().map(|p| (p.x_m * 1e3, p.effective_stress_pa / 1e6)).collect(),
            ),
            Series::dashed(
                "JC (Eq 16) at DPZD eps, epsdot, T",
                pts.iter()
                    .map(|p| (p.x_m * 1e3, jc.flow_stress(p.strain, p.strain_rate_per_s, p.temperature_c) / 1e6))
                    .collect(),
            ),
        ],
        diagonal: false,
    }
    .render())
}

/// Flow curves sigma(eps) of a JC set at several temperatures and strain rates.
#[must_use]
pub fn flow_curves(jc: &JcParams, label: &str, temperatures_c: &[f64], rates_per_s: &[f64]) -> String {
    let mut series = Vec::new();
    for &t in temperatures_c {
        for &r in rates_per_s {
            let pts = (0..=60).map(|i| {
                let e = 2.0 * i as f64 / 60.0;
                (e, jc.flow_stress(e, r, t) / 1e6)
            });
            series.push(Series::line(format!("{t:.0} degC, {r:.0e} 1/s"), pts.collect()));
        }
    }
    Plot {
        title: format!("{label}: JC flow curves"),
        x_label: "effective plastic strain [-]".into(),
        y_label: "flow stress [MPa]".into(),
        series,
        diagonal: false,
    }
    .render()
}
