//! LS-DYNA keyword deck (fe-cards.md §1): `*MAT_JOHNSON_COOK` (MAT_015) with
//! `*EOS_LINEAR_POLYNOMIAL`, `*MAT_THERMAL_ISOTROPIC_TD_LC` with `*DEFINE_CURVE`s, `*PART`s, and
//! `*CONTACT_SURFACE_TO_SURFACE_THERMAL_FRICTION` whose Eq 17 law is FS = 2 with a `*DEFINE_TABLE`
//! of mu(P) and VC = m0 k (fe-cards.md §1.6), or Coulomb FS = FD = mu.
//!
//! The 3-D `_THERMAL_FRICTION` contact (not `AUTOMATIC_..._THERMAL`) is used because both PyDyna
//! and dynars have a class for it (fe-cards.md §6 pitfall 5); `_ID` is not used because dynars does
//! not offset its fields for the ID card.

use handlebars::Handlebars;
use serde::Serialize;
use serde_json::Value;

use crate::physics::{MaterialTables, Prepared};
use crate::units::{kelvin, Factors};
use crate::{templates, ExportError, ExportFile, ExportInput, HeaderCtx};

/// Load-curve ids: 201/202 workpiece heat capacity / conductivity, 203/204 tool; table 300,
/// its curves 301.. in pressure order (fe-cards.md §6 pitfall 4: curves follow the table in order).
const TABLE_ID: i64 = 300;

#[derive(Serialize)]
struct PartMat {
    name: String,
    ro: f64,
    e: f64,
    pr: f64,
    hclc: i64,
    tclc: i64,
    t_from: f64,
    t_to: f64,
}

#[derive(Serialize)]
struct JcCard {
    g: f64,
    a: f64,
    b: f64,
    n: f64,
    c: f64,
    m: f64,
    tm: f64,
    tr: f64,
    epso: f64,
    cp: f64,
}

#[derive(Serialize)]
struct Curve {
    lcid: i64,
    title: String,
    points: Vec<[f64; 2]>,
}

#[derive(Serialize)]
struct MuRow {
    p: f64,
    mu: f64,
    lcid: i64,
}

#[derive(Serialize)]
struct Eq17 {
    m0: f64,
    beta: f64,
    /// k at the contact temperature, stress unit.
    k: f64,
    /// The contact temperature, degC and K.
    tc_c: f64,
    tc_k: f64,
    tc_source: String,
    tbid: i64,
    rows: Vec<MuRow>,
    /// k(T)/k(Tc): the exact temperature factor of Eq 17 (mu(P, T) = mu(P, Tc) k(T)/k(Tc)),
    /// written as an unreferenced curve (see the header).
    ratio_lcid: i64,
    ratio: Vec<[f64; 2]>,
}

#[derive(Serialize)]
struct Coulomb {
    mu: f64,
}

#[derive(Serialize)]
struct ContactCard {
    fs: Value,
    fd: Value,
    vc: f64,
    /// Contact death time (LS-DYNA default 1e20: never).
    dt: f64,
}

#[derive(Serialize)]
struct Ctx {
    h: HeaderCtx,
    title: String,
    stress_unit: &'static str,
    wp: PartMat,
    mat: JcCard,
    pc: f64,
    eos_c1: f64,
    tools: Vec<PartMat>,
    curves: Vec<Curve>,
    eq17: Vec<Eq17>,
    coulomb: Vec<Coulomb>,
    contact: ContactCard,
    h0: f64,
    lmax: f64,
    vmax: f64,
    fwork: f64,
    /// EFMIN, the lower bound of the JC failure strain (LS-DYNA default 1e-6).
    efmin: f64,
    /// D1 of the JC failure strain with D2..D5 = 0: a failure strain far above any strain of a
    /// cut, so JC failure is off (no D1-D5 was identified).
    d1_off: f64,
    /// Initial temperature of every node: Tr of the JC set, K.
    t_init_k: f64,
    /// Initial thermal time step (s, or the time unit), see `initial_thermal_step_s`.
    its: f64,
    /// Termination time (time unit), when a cutting speed is given.
    endtim: Vec<Endtim>,
}

#[derive(Serialize)]
struct Endtim {
    endtim: f64,
    speed_m_min: f64,
}

/// Load-curve id of the k(T)/k(Tc) curve.
const RATIO_LCID: i64 = 400;

/// Failure strain D1 with which JC failure is off: 1e6 is orders of magnitude above the largest
/// strains of a cut (chip strains of order 1-10; paper Fig 4).
const FAILURE_OFF_D1: f64 = 1e6;

/// Length of the cut, m (paper Sec 5.1: "an 8-mm cut is considered").
pub(crate) const CUT_LENGTH_M: f64 = 8e-3;

/// Minimum element size of the paper's mesh, m (paper Sec 5.1: 0.005 mm).
pub(crate) const MIN_ELEMENT_M: f64 = 5e-6;

/// Initial thermal time step: the diffusion time `h^2 rho cp / (2 k)` of the paper's 5 um element
/// at the lowest table temperature, so the first
/// thermal step resolves conduction over one element. LS-DYNA then adapts it (TS = 1).
///
/// **Source:** the 1-D explicit conduction limit Fourier number `alpha dt / h^2 = 1/2`
/// (Incropera & DeWitt, Fundamentals of Heat and Mass Transfer, Sec 5.10), with
/// `alpha = k / (rho cp)` and h the paper's minimum element size (Sec 5.1).
fn initial_thermal_step_s(t: &MaterialTables) -> f64 {
    let k0 = t.conductivity.first().copied().unwrap_or(f64::NAN);
    let rc0 = t.rho_cp.first().copied().unwrap_or(f64::NAN);
    MIN_ELEMENT_M * MIN_ELEMENT_M * rc0 / (2.0 * k0)
}

fn part_mat(t: &MaterialTables, f: &Factors, hclc: i64, who: &str) -> Result<PartMat, ExportError> {
    let (e, pr) = t.elastic.ok_or_else(|| ExportError::Missing {
        dialect: "lsdyna".into(),
        what: format!("elastic constants of the {who} {}", t.name),
    })?;
    Ok(PartMat {
        name: t.name.clone(),
        ro: t.density_room * f.density,
        e: e * f.stress,
        pr,
        hclc,
        tclc: hclc + 1,
        t_from: kelvin(t.temps_c[0]),
        t_to: kelvin(*t.temps_c.last().unwrap_or(&t.temps_c[0])),
    })
}

/// Heat-capacity and conductivity curves; HC(T) = rho(T) cp(T) / TRO (fe-cards.md §1.5).
fn thermal_curves(t: &MaterialTables, f: &Factors, hclc: i64) -> Vec<Curve> {
    let temps: Vec<f64> = t.temps_c.iter().map(|c| kelvin(*c)).collect();
    vec![
        Curve {
            lcid: hclc,
            title: format!("{} heat capacity rho(T) cp(T)/TRO vs T", t.name),
            points: temps.iter().zip(&t.rho_cp).map(|(tk, rc)| [*tk, rc / t.density_room * f.specific_heat]).collect(),
        },
        Curve {
            lcid: hclc + 1,
            title: format!("{} conductivity vs T", t.name),
            points: temps.iter().zip(&t.conductivity).map(|(tk, k)| [*tk, k * f.conductivity]).collect(),
        },
    ]
}

pub(crate) fn render(
    hb: &Handlebars<'_>,
    p: &Prepared,
    input: &ExportInput<'_>,
) -> Result<Vec<ExportFile>, ExportError> {
    let value = context(p, input)?;
    Ok(vec![ExportFile { name: format!("{}_lsdyna.k", p.stem), contents: templates::render(hb, "lsdyna", &value)? }])
}

/// The template context of the LS-DYNA cards, shared with the complete 2-D decks
/// ([`crate::deck2d`]), so both write the same material, thermal and friction data.
pub(crate) fn context(p: &Prepared, input: &ExportInput<'_>) -> Result<Value, ExportError> {
    let units = input.options.units;
    let f = units.factors();
    let wp = part_mat(&p.wp, &f, 201, "workpiece")?;
    let tools = p.tool.iter().map(|t| part_mat(t, &f, 203, "tool")).collect::<Result<Vec<_>, _>>()?;
    let mut curves = thermal_curves(&p.wp, &f, 201);
    if let Some(t) = &p.tool {
        curves.extend(thermal_curves(t, &f, 203));
    }
    let jc = &p.jc;
    let (e, pr) = (wp.e, wp.pr);
    let eq17: Vec<Eq17> = p
        .mu_table
        .iter()
        .map(|m| {
            let c = &m.at_contact;
            Eq17 {
                m0: m.m0,
                beta: m.beta_per_pa / f.stress,
                k: c.k_pa * f.stress,
                tc_c: c.temp_c,
                tc_k: kelvin(c.temp_c),
                tc_source: m.contact_source.clone(),
                tbid: TABLE_ID,
                rows: c
                    .points
                    .iter()
                    .zip(1..)
                    .map(|((pr, mu), i)| MuRow { p: pr * f.stress, mu: *mu, lcid: TABLE_ID + i })
                    .collect(),
                ratio_lcid: RATIO_LCID,
                ratio: m.by_temperature.iter().map(|r| [kelvin(r.temp_c), r.k_pa / c.k_pa]).collect(),
            }
        })
        .collect();
    let contact = match (&p.mu_table, p.coulomb_mu) {
        (Some(m), _) => ContactCard {
            fs: Value::from(2.0),
            fd: Value::from(TABLE_ID),
            vc: m.m0 * m.at_contact.k_pa * f.stress,
            dt: 1e20,
        },
        (None, Some(mu)) => ContactCard { fs: Value::from(mu), fd: Value::from(mu), vc: 0.0, dt: 1e20 },
        (None, None) => {
            return Err(ExportError::Missing { dialect: "lsdyna".into(), what: "a friction law".into() });
        }
    };
    let title = format!("{} Johnson-Cook export by cutcal (units {})", p.wp.name, units.stress_unit());
    let ctx = Ctx {
        h: HeaderCtx::new(input, units.label()),
        title,
        stress_unit: units.stress_unit(),
        mat: JcCard {
            g: e / (2.0 * (1.0 + pr)),
            a: jc.a_pa * f.stress,
            b: jc.b_pa * f.stress,
            n: jc.n,
            c: jc.c,
            m: jc.m,
            tm: kelvin(jc.tm_c),
            tr: kelvin(jc.tr_c),
            epso: jc.eps0_per_s,
            cp: p.wp.specific_heat_room * f.specific_heat,
        },
        pc: -1e10 * f.stress,
        eos_c1: e / (3.0 * (1.0 - 2.0 * pr)),
        wp,
        tools,
        curves,
        eq17,
        coulomb: p.coulomb_mu.iter().map(|mu| Coulomb { mu: *mu }).collect(),
        contact,
        h0: p.htc * f.heat_transfer,
        lmax: 1e-5 * f.length,
        vmax: 1e3 * f.velocity,
        fwork: input.options.inelastic_heat_fraction,
        efmin: 1e-6,
        d1_off: FAILURE_OFF_D1,
        t_init_k: kelvin(jc.tr_c),
        its: ExportError::finite("initial thermal time step", initial_thermal_step_s(&p.wp))?,
        endtim: input
            .options
            .cutting_speed_m_per_s
            .iter()
            .map(|v| Endtim { endtim: CUT_LENGTH_M / v, speed_m_min: v * 60.0 })
            .collect(),
    };
    serde_json::to_value(&ctx).map_err(|e| ExportError::Template { template: "lsdyna".into(), message: e.to_string() })
}
