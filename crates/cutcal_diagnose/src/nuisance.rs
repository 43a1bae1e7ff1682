//! The nuisance of the Mode A baseline (issue 10, item 3: nuisance before physics): what every
//! simulation is uncertain about, each bounded by what its stated uncertainty can produce.
//!
//! The stated uncertainties (issue 10, items 3 and 5) are ranges: Oxley's temperature factors eta
//! and psi +-3 %, the material's thermal constants (rho, cp, K) +-5 % each, and each Johnson-Cook
//! parameter (A, B, n, C, m) +-5 %. A range is read as +-2 standard deviations of a normal prior
//! (the pseudo-residual `(x - x0) / sd` of the least squares) and the parameter is bounded at the
//! range itself: a shift that needs more is not nuisance, it is something the simulation left out.
//! Each bound below is the largest change of the knob that its constants' ranges produce:
//!
//! - flow-stress level: the JC flow stress `(A + B eps^n)(1 + C ln eps*)(1 - T*^m)` (Johnson &
//!   Cook 1983) is linear in A and B, so A and B +-5 % move it by at most +-5 %; n +-5 % moves
//!   `eps^n` by `n |ln eps| 5 %`, under 1 % at the primary zone's equivalent strain 0.5-1.5 with
//!   n <= 0.4; C +-5 % moves the rate term by `C ln eps* 5 % / (1 + C ln eps*)`, under 1 % for
//!   C <= 0.02 and `ln eps*` <= 12. Bound: `ln 1.05 + 0.01 + 0.01` = 0.069 (the thermal exponent m
//!   has its own knob);
//! - eta, psi: 0.9 +-3 % = +-0.027 (Oxley 1989's factors, as in Lalwani, Mehta & Jain 2009);
//! - rho Cp: rho and cp +-5 % each, so their product within `2 ln 1.05` = +-0.098 in ln;
//! - K: +-5 %, `ln 1.05` = 0.049 in ln;
//! - JC thermal exponent m: +-5 %, 0.049 in ln.
//!
//! The flow-stress level is fitted only with at least three conditions (with fewer it would take
//! every force misfit). The calibrated null (`crate::null`) refits the same parameters with the
//! same priors and bounds, so its replicates absorb exactly what the data's baseline may absorb.

use crate::simulator::ParamSpec;

/// Stated relative uncertainty (half-width of the range) of eta and psi (issue 10, item 3).
pub const ETA_PSI_RANGE: f64 = 0.03;

/// Stated relative uncertainty of each thermal constant and each JC parameter (issue 10, item 5).
pub const CONSTANT_RANGE: f64 = 0.05;

/// Oxley's nominal eta and psi (Oxley 1989; Lalwani, Mehta & Jain 2009).
pub const ETA_PSI_NOMINAL: f64 = 0.9;

/// Bound of the ln flow-stress level from the JC ranges (module docs): A and B at most
/// `ln(1 + CONSTANT_RANGE)`, n and C at most 1 % each.
#[must_use]
pub fn level_bound() -> f64 {
    (1.0 + CONSTANT_RANGE).ln() + 0.01 + 0.01
}

/// A nuisance parameter centred at `start`, bounded at `start +- range`, prior sd `range / 2`.
fn ranged(name: &str, start: f64, range: f64) -> ParamSpec {
    ParamSpec {
        name: name.into(),
        unit: "-".into(),
        start,
        lower: start - range,
        upper: start + range,
        prior_sd: Some(0.5 * range),
    }
}

/// The nuisance parameters of the Mode A baseline, in the order the shadow reads them: the
/// flow-stress level (when `level_free`), eta, psi, ln rho Cp, ln K, ln JC m.
#[must_use]
pub fn mode_a_params(level_free: bool) -> Vec<ParamSpec> {
    let ln_const = (1.0 + CONSTANT_RANGE).ln();
    let mut params = Vec::new();
    if level_free {
        params.push(ranged("ln_flow_stress_level", 0.0, level_bound()));
    }
    let eta_psi = ETA_PSI_NOMINAL * ETA_PSI_RANGE;
    params.push(ranged("eta", ETA_PSI_NOMINAL, eta_psi));
    params.push(ranged("psi", ETA_PSI_NOMINAL, eta_psi));
    params.push(ranged("ln_rho_cp_scale", 0.0, 2.0 * ln_const));
    params.push(ranged("ln_conductivity_scale", 0.0, ln_const));
    params.push(ranged("ln_jc_m_scale", 0.0, ln_const));
    params
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_are_the_stated_ranges() {
        let p = mode_a_params(true);
        let names: Vec<&str> = p.iter().map(|q| q.name.as_str()).collect();
        assert_eq!(
            names,
            ["ln_flow_stress_level", "eta", "psi", "ln_rho_cp_scale", "ln_conductivity_scale", "ln_jc_m_scale"]
        );
        // Level: ln 1.05 = 0.04879 plus 0.02 (n and C, module docs).
        assert!((p[0].upper - 0.06879).abs() < 1e-4 && (p[0].lower + 0.06879).abs() < 1e-4);
        // eta: 0.9 +- 0.027, prior sd 0.0135.
        assert!((p[1].upper - 0.927).abs() < 1e-12 && (p[1].lower - 0.873).abs() < 1e-12);
        assert!((p[1].prior_sd.unwrap() - 0.0135).abs() < 1e-12);
        // rho Cp: two constants of +-5 %: 2 ln 1.05 = 0.09758.
        assert!((p[3].upper - 0.09758).abs() < 1e-4);
        // K and m: ln 1.05.
        assert!((p[4].upper - 0.04879).abs() < 1e-4 && (p[5].lower + 0.04879).abs() < 1e-4);
        for q in &p {
            assert!(q.lower < q.start && q.start < q.upper);
            assert!((q.prior_sd.unwrap() - 0.5 * (q.upper - q.start)).abs() < 1e-12);
        }
        assert_eq!(mode_a_params(false).len(), 5);
    }
}
