//! Physics shared by every dialect: validation of the input, temperature sampling of the Table 3
//! polynomials, the workpiece shear strength k, the Eq 17 mu(P) table and JC flow-stress tables.
//!
//! Everything here is SI with temperatures in degC; dialects convert units when they build their
//! template context.

use cutcal_model::{Friction, JcParams, Material};

use crate::{ExportError, ExportInput};

/// Default tool-chip contact temperature (degC) for the dialects that need one constant k
/// (the LS-DYNA FS = 2 table): the homologous temperature `T* = (T - Tr)/(Tm - Tr) = 0.5` of the
/// JC set. **This is a stated default, not a measured or predicted value**: give the interface
/// temperature of the cutting condition (a measurement, or the extended Oxley prediction of
/// `cutcal predict`) when it is known. Paper Eq 16 defines T*; the value 0.5 is ours.
///
/// # Example
/// ```
/// use cutcal_model::JcParams;
/// // C38 Table 5 set: Tr = 20, Tm = 1460 degC -> 740 degC.
/// let jc = JcParams::new(589e6, 145e6, 0.25, 0.069, 1.1, 1.0, 1460.0, 20.0).unwrap();
/// assert!((cutcal_export::physics::default_contact_temperature_c(&jc) - 740.0).abs() < 1e-9);
/// ```
#[must_use]
pub fn default_contact_temperature_c(jc: &JcParams) -> f64 {
    jc.tr_c + 0.5 * (jc.tm_c - jc.tr_c)
}

/// Homologous temperature of the last flow-stress block of tabular cards, T* = 0.99 (paper Eq 16
/// defines T*): the JC flow stress there is 1 - 0.99^m (about 1 %) of the cold value.
pub const NEAR_MELTING_HOMOLOGOUS: f64 = 0.99;

/// The temperature (degC) of T* = [`NEAR_MELTING_HOMOLOGOUS`] of the JC set.
#[must_use]
pub fn near_melting_c(jc: &JcParams) -> f64 {
    jc.tr_c + NEAR_MELTING_HOMOLOGOUS * (jc.tm_c - jc.tr_c)
}

/// Reference effective strain at which the Eq 17 shear strength k(T) is evaluated from the JC law.
///
/// **Source:** the chip material at the tool-chip interface has passed the primary zone, whose exit
/// strain is 1.1-1.5 for the paper's tests (paper Fig 4: 1.48 for C38 test 3), and is sheared
/// further in the secondary zone; 2 is a round value in that range. The choice is stated in every
/// card header.
pub const FRICTION_REFERENCE_STRAIN: f64 = 2.0;

/// Reference strain rate (1/s) at which the Eq 17 shear strength k(T) is evaluated.
///
/// **Source:** the order of the interface strain rate of Oxley's machining theory (Oxley 1989;
/// 10^4-10^5 1/s at the paper's conditions); the lower end is taken. Stated in every card header.
pub const FRICTION_REFERENCE_STRAIN_RATE_PER_S: f64 = 1e4;

/// Local shear flow stress of the workpiece at the contact temperature `temp_c` (degC), Pa:
/// `k(T) = sigma_JC(eps_ref, epsdot_ref, T) / sqrt(3)` (von Mises), with the references
/// [`FRICTION_REFERENCE_STRAIN`] and [`FRICTION_REFERENCE_STRAIN_RATE_PER_S`].
///
/// **Source:** paper Eq 17, whose k is "the shear flow stress of the workpiece", evaluated with
/// the identified JC law (paper Eq 16) at the interface temperature. It is 0 at and above Tm.
///
/// # Example
/// ```
/// use cutcal_model::JcParams;
/// // Paper Table 5, C38, at 600 degC: (589 + 145 2^0.25)(1 + 0.069 ln 1e4)(1 - (580/1440)^1.1)/sqrt(3)
/// // = 454.57 MPa (python: (589+145*2**0.25)*(1+0.069*math.log(1e4))*(1-(580/1440)**1.1)/3**0.5).
/// let jc = JcParams::new(589e6, 145e6, 0.25, 0.069, 1.1, 1.0, 1460.0, 20.0).unwrap();
/// let k = cutcal_export::physics::local_shear_strength_pa(&jc, 600.0);
/// assert!((k / 1e6 - 454.57).abs() < 0.01);
/// ```
#[must_use]
pub fn local_shear_strength_pa(jc: &JcParams, temp_c: f64) -> f64 {
    (jc.flow_stress(FRICTION_REFERENCE_STRAIN, FRICTION_REFERENCE_STRAIN_RATE_PER_S, temp_c) / 3f64.sqrt()).max(0.0)
}

/// Effective friction coefficient of paper Eq 17 at contact pressure `pressure_pa`:
/// `mu(P) = tau_f / P = m0 k (1 - exp(-beta P)) / P`, with the limit `m0 k beta` at `P = 0`.
///
/// **Source:** paper Eq 17, mapped to a pressure table as in fe-cards.md §1.6. Units: `k` and `P`
/// in Pa, `beta` in 1/Pa; the result is dimensionless.
///
/// # Example
/// ```
/// // m0 = 1, beta = 0.0045/MPa (paper Sec 5.1), k = 340 MPa, P = 100 MPa:
/// // 340 (1 - e^-0.45) / 100 = 1.23209.
/// let mu = cutcal_export::physics::eq17_mu(1.0, 0.0045e-6, 340e6, 100e6);
/// assert!((mu - 1.232_065).abs() < 1e-5);
/// ```
#[must_use]
pub fn eq17_mu(m0: f64, beta_per_pa: f64, k_pa: f64, pressure_pa: f64) -> f64 {
    let x = beta_per_pa * pressure_pa;
    if x < 1e-8 {
        // Series of (1 - e^-x)/x = 1 - x/2 + x^2/6 avoids 0/0 at P = 0.
        m0 * k_pa * beta_per_pa * (1.0 - x / 2.0 + x * x / 6.0)
    } else {
        m0 * k_pa * (-(-x).exp_m1()) / pressure_pa
    }
}

/// Temperature-sampled properties of one material (SI, degC).
#[derive(Debug, Clone)]
pub(crate) struct MaterialTables {
    /// Material name as given.
    pub name: String,
    /// Sample temperatures, degC.
    pub temps_c: Vec<f64>,
    /// Density, kg/m^3.
    pub density: Vec<f64>,
    /// Specific heat, J/(kg K).
    pub specific_heat: Vec<f64>,
    /// Volumetric heat capacity, J/(m^3 K).
    pub rho_cp: Vec<f64>,
    /// Conductivity, W/(m K).
    pub conductivity: Vec<f64>,
    /// Density at the room temperature, kg/m^3.
    pub density_room: f64,
    /// Specific heat at the room temperature, J/(kg K).
    pub specific_heat_room: f64,
    /// Young's modulus (Pa) and Poisson's ratio, when known.
    pub elastic: Option<(f64, f64)>,
}

/// The Eq 17 table: pressures (Pa) and mu values.
#[derive(Debug, Clone)]
pub(crate) struct MuTable {
    pub m0: f64,
    pub beta_per_pa: f64,
    /// The rows at the one contact temperature of [`crate::ExportOptions::contact_temperature_c`],
    /// for the dialect that cannot take a temperature-dependent table (LS-DYNA FS = 2).
    pub at_contact: MuRowsAtT,
    /// Where the contact temperature of `at_contact` comes from.
    pub contact_source: String,
    /// The temperature-dependent law: per contact temperature (degC, below Tm) the local k(T) (Pa)
    /// and the (P, mu) rows with that k.
    pub by_temperature: Vec<MuRowsAtT>,
}

/// The Eq 17 mu(P) rows at one contact temperature.
#[derive(Debug, Clone)]
pub(crate) struct MuRowsAtT {
    pub temp_c: f64,
    pub k_pa: f64,
    pub points: Vec<(f64, f64)>,
}

/// Everything a dialect needs, validated and sampled once.
#[derive(Debug, Clone)]
pub(crate) struct Prepared {
    /// File stem (lower-case workpiece name).
    pub stem: String,
    pub wp: MaterialTables,
    pub tool: Option<MaterialTables>,
    pub jc: JcParams,
    /// Temperatures of flow-stress tables (the workpiece grid, strictly below Tm), degC.
    pub flow_temps_c: Vec<f64>,
    /// Eq 17 table when the interface uses Eq 17.
    pub mu_table: Option<MuTable>,
    /// Coulomb mu when the interface is Coulomb.
    pub coulomb_mu: Option<f64>,
    /// Heat transfer coefficient, W/(m^2 K).
    pub htc: f64,
}

/// Checks a name for use in cards: ASCII letters, digits, `_` and `-`, 1 to 40 characters.
pub(crate) fn check_name(name: &str) -> Result<(), ExportError> {
    let ok =
        !name.is_empty() && name.len() <= 40 && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    if ok {
        Ok(())
    } else {
        Err(ExportError::BadName {
            name: name.to_string(),
            reason: "use 1-40 ASCII letters, digits, '_' or '-' (card names and titles)".into(),
        })
    }
}

/// Checks a provenance text for card headers: printable ASCII without commas, <= 60 characters.
pub(crate) fn check_label(label: &str) -> Result<(), ExportError> {
    let ok = !label.is_empty() && label.len() <= 60 && label.chars().all(|c| (' '..='~').contains(&c) && c != ',');
    if ok {
        Ok(())
    } else {
        Err(ExportError::BadName {
            name: label.to_string(),
            reason: "header labels must be 1-60 printable ASCII characters without commas".into(),
        })
    }
}

fn sample_grid(from_c: f64, to_c: f64, step_c: f64) -> Vec<f64> {
    let mut out = Vec::new();
    let mut i = 0u32;
    loop {
        let t = from_c + step_c * f64::from(i);
        if t > to_c - 1e-9 * step_c {
            break;
        }
        out.push(t);
        i += 1;
    }
    out.push(to_c);
    out
}

fn tables(m: &Material, input: &ExportInput<'_>) -> Result<MaterialTables, ExportError> {
    check_name(&m.name)?;
    m.validate().map_err(|e| ExportError::invalid(format!("material {}", m.name), e))?;
    let g = &input.options.temperatures;
    let from = g.from_c.max(m.thermal.valid_from_c);
    let to = g.to_c.min(m.thermal.valid_to_c);
    // NaN-safe: a NaN bound fails `to > from` and is rejected too.
    if to.partial_cmp(&from) != Some(std::cmp::Ordering::Greater) {
        return Err(ExportError::BadOption {
            field: "temperatures".into(),
            value: format!("[{}, {}] degC", g.from_c, g.to_c),
            expected: format!(
                "a range overlapping the validity range [{}, {}] degC of {}",
                m.thermal.valid_from_c, m.thermal.valid_to_c, m.name
            ),
        });
    }
    let temps_c = sample_grid(from, to, g.step_c);
    let th = &m.thermal;
    let mut t = MaterialTables {
        name: m.name.clone(),
        density: temps_c.iter().map(|&x| th.density.value(x)).collect(),
        specific_heat: temps_c.iter().map(|&x| th.specific_heat(x)).collect(),
        rho_cp: temps_c.iter().map(|&x| th.rho_cp.value(x)).collect(),
        conductivity: temps_c.iter().map(|&x| th.conductivity.value(x)).collect(),
        density_room: th.density.value(m.room_c),
        specific_heat_room: th.specific_heat(m.room_c),
        elastic: m.elastic.map(|e| (e.youngs_pa, e.poisson)),
        temps_c,
    };
    for (what, v) in [("density", &t.density), ("specific heat", &t.specific_heat), ("conductivity", &t.conductivity)] {
        for (x, val) in t.temps_c.iter().zip(v) {
            ExportError::finite(&format!("{} {what} at {x} degC", m.name), *val)?;
        }
    }
    t.density_room = ExportError::finite(&format!("{} density at room temperature", m.name), t.density_room)?;
    t.specific_heat_room =
        ExportError::finite(&format!("{} specific heat at room temperature", m.name), t.specific_heat_room)?;
    Ok(t)
}

/// Validates the whole input and samples every table.
pub(crate) fn prepare(input: &ExportInput<'_>) -> Result<Prepared, ExportError> {
    let o = input.options;
    let g = &o.temperatures;
    if !(g.from_c.is_finite() && g.to_c.is_finite() && g.step_c.is_finite() && g.step_c > 0.0 && g.to_c > g.from_c) {
        return Err(ExportError::BadOption {
            field: "temperatures".into(),
            value: format!("from {} to {} step {} degC", g.from_c, g.to_c, g.step_c),
            expected: "finite, from < to, step > 0".into(),
        });
    }
    if (g.to_c - g.from_c) / g.step_c > 200.0 {
        return Err(ExportError::BadOption {
            field: "temperatures.step_c".into(),
            value: g.step_c.to_string(),
            expected: "at most 200 temperature points".into(),
        });
    }
    let strictly_increasing = |v: &[f64]| v.windows(2).all(|w| w[1] > w[0]) && v.iter().all(|x| x.is_finite());
    if o.plastic_strains.len() < 2 || !strictly_increasing(&o.plastic_strains) || o.plastic_strains[0].abs() > 0.0 {
        return Err(ExportError::BadOption {
            field: "plastic_strains".into(),
            value: format!("{:?}", o.plastic_strains),
            expected: "at least two strictly increasing strains starting at 0".into(),
        });
    }
    if o.flow_strain_rates_per_s.is_empty() || !strictly_increasing(&o.flow_strain_rates_per_s) {
        return Err(ExportError::BadOption {
            field: "flow_strain_rates_per_s".into(),
            value: format!("{:?}", o.flow_strain_rates_per_s),
            expected: "strictly increasing strain rates".into(),
        });
    }
    if o.contact_pressures_pa.len() < 2
        || !strictly_increasing(&o.contact_pressures_pa)
        || o.contact_pressures_pa[0] < 0.0
    {
        return Err(ExportError::BadOption {
            field: "contact_pressures_pa".into(),
            value: format!("{:?}", o.contact_pressures_pa),
            expected: "at least two strictly increasing pressures >= 0".into(),
        });
    }
    if !(o.inelastic_heat_fraction.is_finite() && o.inelastic_heat_fraction > 0.0 && o.inelastic_heat_fraction <= 1.0) {
        return Err(ExportError::BadOption {
            field: "inelastic_heat_fraction".into(),
            value: o.inelastic_heat_fraction.to_string(),
            expected: "0 < fraction <= 1".into(),
        });
    }
    let jc = *input.jc;
    jc.validate().map_err(|e| ExportError::invalid("jc set", e))?;
    let rate_ok = |r: f64| r.is_finite() && r > 0.0 && jc.rate_factor(r) > 0.0;
    if !rate_ok(o.tabular_strain_rate_per_s) || !o.flow_strain_rates_per_s.iter().all(|r| rate_ok(*r)) {
        return Err(ExportError::BadOption {
            field: "strain rates".into(),
            value: format!("{} and {:?}", o.tabular_strain_rate_per_s, o.flow_strain_rates_per_s),
            expected: "positive rates with a positive JC rate factor 1 + C ln(rate/eps0)".into(),
        });
    }
    for (label, text) in [
        ("cutcal_version", &input.provenance.cutcal_version),
        ("source_test", &input.provenance.source_test),
        ("model_variant", &input.provenance.model_variant),
    ] {
        check_label(text).map_err(|e| match e {
            ExportError::BadName { name, reason } => {
                ExportError::BadName { name, reason: format!("{label}: {reason}") }
            }
            other => other,
        })?;
    }
    let wp = tables(input.workpiece, input)?;
    let tool = input.tool.map(|t| tables(t, input)).transpose()?;
    let mut flow_temps_c: Vec<f64> = wp.temps_c.iter().copied().filter(|t| *t < jc.tm_c).collect();
    // A last block near melting, so that the constant extrapolation of tabular cards (Abaqus, DEFORM)
    // and of the k(T) rows does not keep a hot-but-solid flow stress up to Tm.
    let near_melting = near_melting_c(&jc);
    if flow_temps_c.last().is_some_and(|t| *t < near_melting) {
        flow_temps_c.push(near_melting);
    }
    if flow_temps_c.is_empty() {
        return Err(ExportError::BadOption {
            field: "temperatures".into(),
            value: format!("[{}, {}] degC", g.from_c, g.to_c),
            expected: format!("at least one temperature below Tm = {} degC", jc.tm_c),
        });
    }
    let iface = input.interface;
    iface.friction.validate().map_err(|e| ExportError::invalid("interface friction", e))?;
    let htc = iface.heat_transfer_w_per_m2_k;
    if !(htc.is_finite() && htc > 0.0) {
        return Err(ExportError::NonFinite { field: "heat_transfer_w_per_m2_k".into(), value: htc });
    }
    let (tc, tc_source) = match &o.contact_temperature {
        Some(c) => (c.temp_c, c.source.clone()),
        None => (default_contact_temperature_c(&jc), "default T* = 0.5 (no interface temperature given)".to_string()),
    };
    if !(tc.is_finite() && tc >= jc.tr_c && tc < jc.tm_c) {
        return Err(ExportError::BadOption {
            field: "contact_temperature_c".into(),
            value: tc.to_string(),
            expected: format!("a contact temperature in [Tr, Tm) = [{}, {}) degC of the JC set", jc.tr_c, jc.tm_c),
        });
    }
    check_label(&tc_source).map_err(|e| match e {
        ExportError::BadName { name, reason } => {
            ExportError::BadName { name, reason: format!("contact_temperature_source: {reason}") }
        }
        other => other,
    })?;
    if let Some(v) = o.cutting_speed_m_per_s {
        if !(v.is_finite() && v > 0.0) {
            return Err(ExportError::BadOption {
                field: "cutting_speed_m_per_s".into(),
                value: v.to_string(),
                expected: "a positive cutting speed".into(),
            });
        }
    }
    let (mu_table, coulomb_mu) = match iface.friction {
        Friction::PressureDependentShear { m0, beta_per_pa } => {
            let rows_at = |t: f64| -> Result<MuRowsAtT, ExportError> {
                let k_t = ExportError::finite("local shear strength k(T)", local_shear_strength_pa(&jc, t))?;
                let points = o
                    .contact_pressures_pa
                    .iter()
                    .map(|&p| Ok((p, ExportError::finite("mu(P, T)", eq17_mu(m0, beta_per_pa, k_t, p))?)))
                    .collect::<Result<Vec<_>, ExportError>>()?;
                Ok(MuRowsAtT { temp_c: t, k_pa: k_t, points })
            };
            let mut by_temperature = Vec::new();
            for &t in &flow_temps_c {
                let rows = rows_at(t)?;
                if rows.k_pa > 0.0 {
                    by_temperature.push(rows);
                }
            }
            let at_contact = rows_at(tc)?;
            if at_contact.k_pa <= 0.0 {
                return Err(ExportError::BadOption {
                    field: "contact_temperature_c".into(),
                    value: tc.to_string(),
                    expected: "a temperature where the JC shear strength k(T) is positive".into(),
                });
            }
            (Some(MuTable { m0, beta_per_pa, at_contact, contact_source: tc_source, by_temperature }), None)
        }
        Friction::Coulomb { mu } => (None, Some(mu)),
    };
    Ok(Prepared {
        stem: input.workpiece.name.to_ascii_lowercase(),
        wp,
        tool,
        jc,
        flow_temps_c,
        mu_table,
        coulomb_mu,
        htc,
    })
}

impl Prepared {
    /// JC flow stress (Pa) at each plastic strain for one rate and temperature; errors if a value
    /// is not finite or not positive (a zero yield stress is not a usable table entry).
    pub(crate) fn flow_curve(&self, strains: &[f64], rate: f64, temp_c: f64) -> Result<Vec<f64>, ExportError> {
        strains
            .iter()
            .map(|&e| {
                let s = self.jc.flow_stress(e, rate, temp_c);
                if s.is_finite() && s > 0.0 {
                    Ok(s)
                } else {
                    Err(ExportError::NonFinite {
                        field: format!("JC flow stress at strain {e}, rate {rate} 1/s, {temp_c} degC"),
                        value: s,
                    })
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests;
