//! DEFORM-style output (fe-cards.md §3): a KEY-like material block with tabular flow stress
//! (`FSTRES` type 2), conductivity, volumetric heat capacity and density, plus a readable sheet
//! with the JC constants, the Eq 17 friction, the heat transfer coefficient and the units.
//!
//! The KEY format is not public: the block is **unverified** and its header says so. Units are
//! DEFORM's SI-mm system: MPa, mm, s, degC, N/(s degC), N/(mm^2 degC), N/(s mm degC).

use handlebars::Handlebars;
use serde::Serialize;
use serde_json::Value;

use crate::physics::Prepared;
use crate::{templates, ExportError, ExportFile, ExportInput, HeaderCtx};

/// DEFORM SI-mm unit statement.
const UNITS: &str = "DEFORM SI-mm: stress MPa, length mm, time s, temperature degC, conductivity N/(s degC), \
                     volumetric heat capacity N/(mm^2 degC), heat transfer N/(s mm degC)";

#[derive(Serialize)]
struct Jc {
    a: f64,
    b: f64,
    n: f64,
    c: f64,
    m: f64,
    eps0: f64,
    tm: f64,
    tr: f64,
}

#[derive(Serialize)]
struct MRow {
    p: f64,
    m: f64,
}

#[derive(Serialize)]
struct Eq17 {
    m0: f64,
    beta: f64,
    rows: Vec<MRow>,
}

#[derive(Serialize)]
struct Coulomb {
    mu: f64,
}

#[derive(Serialize)]
struct ThermRow {
    t: f64,
    k: f64,
    rc: f64,
    rho: f64,
}

#[derive(Serialize)]
struct MatRows {
    name: String,
    role: &'static str,
    rows: Vec<ThermRow>,
}

#[derive(Serialize)]
struct Young {
    e: f64,
    nu: f64,
}

#[derive(Serialize)]
struct Ctx {
    h: HeaderCtx,
    stem: String,
    name: String,
    ihf: f64,
    n_strain: usize,
    n_rate: usize,
    n_temp: usize,
    n_prop: usize,
    strain_rows: Vec<Vec<f64>>,
    rate_rows: Vec<Vec<f64>>,
    temp_rows: Vec<Vec<f64>>,
    stress_rows: Vec<Vec<f64>>,
    conductivity: Vec<[f64; 2]>,
    heat_capacity: Vec<[f64; 2]>,
    density: Vec<[f64; 2]>,
    young: Vec<Young>,
    jc: Jc,
    eq17: Vec<Eq17>,
    coulomb: Vec<Coulomb>,
    htc: f64,
    materials: Vec<MatRows>,
}

fn rows5(v: &[f64]) -> Vec<Vec<f64>> {
    v.chunks(5).map(<[f64]>::to_vec).collect()
}

pub(crate) fn render(
    hb: &Handlebars<'_>,
    p: &Prepared,
    input: &ExportInput<'_>,
) -> Result<Vec<ExportFile>, ExportError> {
    let o = input.options;
    let strains = &o.plastic_strains;
    let rates = &o.flow_strain_rates_per_s;
    let mut stresses = Vec::with_capacity(strains.len() * rates.len() * p.flow_temps_c.len());
    for &t in &p.flow_temps_c {
        for &r in rates {
            stresses.extend(p.flow_curve(strains, r, t)?.iter().map(|s| s * 1e-6));
        }
    }
    let w = &p.wp;
    let pair =
        |v: &[f64], factor: f64| -> Vec<[f64; 2]> { w.temps_c.iter().zip(v).map(|(t, x)| [*t, x * factor]).collect() };
    let mat_rows = |t: &crate::physics::MaterialTables, role: &'static str| MatRows {
        name: t.name.clone(),
        role,
        rows: t
            .temps_c
            .iter()
            .enumerate()
            .map(|(i, tc)| ThermRow { t: *tc, k: t.conductivity[i], rc: t.rho_cp[i] * 1e-6, rho: t.density[i] })
            .collect(),
    };
    let mut materials = vec![mat_rows(w, "workpiece")];
    if let Some(t) = &p.tool {
        materials.push(mat_rows(t, "tool"));
    }
    let jc = &p.jc;
    let ctx = Ctx {
        h: HeaderCtx::new(input, UNITS),
        stem: p.stem.clone(),
        name: w.name.to_ascii_uppercase(),
        ihf: o.inelastic_heat_fraction,
        n_strain: strains.len(),
        n_rate: rates.len(),
        n_temp: p.flow_temps_c.len(),
        n_prop: w.temps_c.len(),
        strain_rows: rows5(strains),
        rate_rows: rows5(rates),
        temp_rows: rows5(&p.flow_temps_c),
        stress_rows: rows5(&stresses),
        conductivity: pair(&w.conductivity, 1.0),
        heat_capacity: pair(&w.rho_cp, 1e-6),
        density: pair(&w.density, 1e-12),
        young: w.elastic.iter().map(|(e, nu)| Young { e: e * 1e-6, nu: *nu }).collect(),
        jc: Jc {
            a: jc.a_pa * 1e-6,
            b: jc.b_pa * 1e-6,
            n: jc.n,
            c: jc.c,
            m: jc.m,
            eps0: jc.eps0_per_s,
            tm: jc.tm_c,
            tr: jc.tr_c,
        },
        eq17: p
            .mu_table
            .iter()
            .map(|m| Eq17 {
                m0: m.m0,
                beta: m.beta_per_pa * 1e6,
                // m(P) = tau_f / k = m0 (1 - exp(-beta P)) (paper Eq 17 in DEFORM's local-k form).
                rows: m
                    .at_contact
                    .points
                    .iter()
                    .map(|(pr, mu)| MRow { p: pr * 1e-6, m: mu * pr / m.at_contact.k_pa })
                    .collect(),
            })
            .collect(),
        coulomb: p.coulomb_mu.iter().map(|mu| Coulomb { mu: *mu }).collect(),
        htc: p.htc * 1e-3,
        materials,
    };
    let value: Value = serde_json::to_value(&ctx)
        .map_err(|e| ExportError::Template { template: "deform".into(), message: e.to_string() })?;
    Ok(vec![
        ExportFile { name: format!("{}_deform.key", p.stem), contents: templates::render(hb, "deform_key", &value)? },
        ExportFile {
            name: format!("{}_deform_sheet.txt", p.stem),
            contents: templates::render(hb, "deform_sheet", &value)?,
        },
    ])
}
