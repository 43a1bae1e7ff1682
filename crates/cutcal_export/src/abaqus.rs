//! Abaqus keyword cards (fe-cards.md §2): native JC material, tabular `*PLASTIC` variant, tool
//! material, `*SURFACE INTERACTION` with the Eq 17 friction table (or Coulomb), `*GAP CONDUCTANCE`,
//! and a VFRICTION user-subroutine source for the exact Eq 17 law with the local k(T).

use handlebars::Handlebars;
use serde::Serialize;
use serde_json::Value;

use crate::physics::{MaterialTables, Prepared};
use crate::units::kelvin;
use crate::{templates, ExportError, ExportFile, ExportInput, HeaderCtx};

#[derive(Serialize)]
struct MatCtx {
    name: String,
    t_from: f64,
    t_to: f64,
    /// Density at the room temperature (Abaqus/Explicit uses one density in coupled elements).
    density: f64,
    elastic: Vec<[f64; 2]>,
    conductivity: Vec<[f64; 2]>,
    specific_heat: Vec<[f64; 2]>,
}

#[derive(Serialize)]
struct JcCtx {
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
struct MuRow {
    mu: f64,
    p: f64,
    t: f64,
}

#[derive(Serialize)]
struct KRow {
    t: f64,
    k: f64,
}

#[derive(Serialize)]
struct Eq17Ctx {
    m0: f64,
    beta: f64,
    taumax: f64,
    eps_ref: f64,
    rate_ref: f64,
    k_rows: Vec<KRow>,
    rows: Vec<MuRow>,
}

#[derive(Serialize)]
struct CoulombCtx {
    mu: f64,
}

#[derive(Serialize)]
struct Ctx {
    h: HeaderCtx,
    stem: String,
    stress_unit: &'static str,
    wp: MatCtx,
    tools: Vec<MatCtx>,
    ihf: f64,
    jc: JcCtx,
    eq17: Vec<Eq17Ctx>,
    coulomb: Vec<CoulombCtx>,
    gap: Vec<[f64; 2]>,
    rate: f64,
    plastic: Vec<[f64; 3]>,
}

fn material(t: &MaterialTables, prefix: &str, f: &crate::units::Factors) -> MatCtx {
    let rows = |v: &[f64], factor: f64| -> Vec<[f64; 2]> {
        v.iter().zip(&t.temps_c).map(|(x, tc)| [x * factor, kelvin(*tc)]).collect()
    };
    MatCtx {
        name: format!("{prefix}_{}", t.name.to_ascii_uppercase()),
        t_from: kelvin(t.temps_c[0]),
        t_to: kelvin(*t.temps_c.last().unwrap_or(&t.temps_c[0])),
        density: t.density_room * f.density,
        elastic: t.elastic.map(|(e, nu)| [e * f.stress, nu]).into_iter().collect(),
        conductivity: rows(&t.conductivity, f.conductivity),
        // rho(T) cp(T) / rho0: the volumetric heat capacity of the tables with the constant density
        // (Abaqus/Explicit ignores a temperature-dependent density in coupled elements; fe-cards.md
        // §1.5 does the same for LS-DYNA).
        specific_heat: rows(&t.rho_cp.iter().map(|rc| rc / t.density_room).collect::<Vec<_>>(), f.specific_heat),
    }
}

pub(crate) fn render(
    hb: &Handlebars<'_>,
    p: &Prepared,
    input: &ExportInput<'_>,
) -> Result<Vec<ExportFile>, ExportError> {
    let units = input.options.units;
    let f = units.factors();
    if p.wp.elastic.is_none() {
        return Err(ExportError::Missing {
            dialect: "abaqus".into(),
            what: format!("elastic constants of the workpiece {}", p.wp.name),
        });
    }
    let jc = &p.jc;
    let strains = &input.options.plastic_strains;
    let rate = input.options.tabular_strain_rate_per_s;
    let mut plastic = Vec::new();
    for &t in &p.flow_temps_c {
        for (s, e) in p.flow_curve(strains, rate, t)?.iter().zip(strains) {
            plastic.push([s * f.stress, *e, kelvin(t)]);
        }
    }
    let eq17: Vec<Eq17Ctx> = p
        .mu_table
        .iter()
        .map(|m| Eq17Ctx {
            m0: m.m0,
            beta: m.beta_per_pa / f.stress,
            // The coldest row has the largest k: TAUMAX is the cap of the whole table.
            taumax: m.m0 * m.by_temperature.iter().map(|r| r.k_pa).fold(0.0, f64::max) * f.stress,
            eps_ref: crate::physics::FRICTION_REFERENCE_STRAIN,
            rate_ref: crate::physics::FRICTION_REFERENCE_STRAIN_RATE_PER_S,
            k_rows: m.by_temperature.iter().map(|r| KRow { t: kelvin(r.temp_c), k: r.k_pa * f.stress }).collect(),
            rows: m
                .by_temperature
                .iter()
                .flat_map(|r| {
                    r.points.iter().map(move |(pr, mu)| MuRow { mu: *mu, p: pr * f.stress, t: kelvin(r.temp_c) })
                })
                .collect(),
        })
        .collect();
    let pmax = input.options.contact_pressures_pa.last().copied().unwrap_or(0.0) * f.stress;
    let htc = p.htc * f.heat_transfer;
    let ctx = Ctx {
        h: HeaderCtx::new(input, units.label()),
        stem: p.stem.clone(),
        stress_unit: units.stress_unit(),
        wp: material(&p.wp, "WP", &f),
        tools: p.tool.iter().map(|t| material(t, "TOOL", &f)).collect(),
        ihf: input.options.inelastic_heat_fraction,
        jc: JcCtx {
            a: jc.a_pa * f.stress,
            b: jc.b_pa * f.stress,
            n: jc.n,
            c: jc.c,
            m: jc.m,
            eps0: jc.eps0_per_s,
            tm: kelvin(jc.tm_c),
            tr: kelvin(jc.tr_c),
        },
        eq17,
        coulomb: p.coulomb_mu.iter().map(|mu| CoulombCtx { mu: *mu }).collect(),
        gap: vec![[htc, 0.0], [htc, pmax]],
        rate,
        plastic,
    };
    let value: Value = serde_json::to_value(&ctx)
        .map_err(|e| ExportError::Template { template: "abaqus".into(), message: e.to_string() })?;
    let mut files = vec![
        ExportFile { name: format!("{}_abaqus_jc.inp", p.stem), contents: templates::render(hb, "abaqus_jc", &value)? },
        ExportFile {
            name: format!("{}_abaqus_tabular.inp", p.stem),
            contents: templates::render(hb, "abaqus_tabular", &value)?,
        },
    ];
    if let Some(eq) = ctx.eq17.first() {
        let v = serde_json::json!({
            "h": value["h"], "stress_unit": ctx.stress_unit, "m0": eq.m0, "beta": eq.beta,
            "jc": value["jc"], "eps_ref": eq.eps_ref, "rate_ref": eq.rate_ref,
        });
        files.push(ExportFile {
            name: format!("{}_abaqus_vfriction.f", p.stem),
            contents: templates::render(hb, "abaqus_vfriction", &v)?,
        });
    }
    Ok(files)
}
