//! The primary-zone thickness h of the DPZD identification from the forward model.
//!
//! The paper states no h for Table 4 (the `paper` preset keeps 0.1 mm, the choice that reproduces
//! it). h only reparametrises A, B and C, so an arbitrary h gives an arbitrary A. Oxley's theory
//! gives the zone a thickness: the maximum shear strain rate at AB is `C0 V_s / l_AB` (Oxley 1989,
//! *Mechanics of Machining*, Eq 3.6 with the zone of thickness `l_AB / C0` of Sec 3.2), so
//! `h = l_AB / C0` of the test's own extended-Oxley solution ([`cutcal_model::oxley`]).
//!
//! That solution needs a JC set, and the JC set is what the identification returns; [`self_consistent_h`]
//! makes the two agree by a capped fixed point `h_{k+1} = l_AB/C0 (JC(h_k))`, and reports whether it
//! converged.

use serde::Serialize;

use cutcal_model::oxley::{self, CuttingConditions, OxleyOptions, Physics};
use cutcal_model::{CuttingTest, JcParams, Material};

use crate::error::IdentError;

/// The zone thickness of one Oxley solution.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ZoneThickness {
    /// `h = l_AB / C0`, m.
    pub h_m: f64,
    /// Shear-plane length l_AB, m.
    pub l_ab_m: f64,
    /// Oxley's strain-rate constant C0.
    pub c0: f64,
}

/// `l_AB / C0` of the extended-Oxley solution of `test` with `jc` (Oxley 1989, Sec 3.2).
///
/// The test's edge radius and flank wear are included as in `cutcal predict` (they do not change
/// the chip-formation solution's l_AB and C0 in this model, only the forces).
///
/// Returns an error if the test's conditions are invalid or the forward model has no solution.
pub fn oxley_zone_thickness(
    material: &Material,
    test: &CuttingTest,
    jc: &JcParams,
    options: &OxleyOptions,
    work_temperature_c: f64,
) -> Result<ZoneThickness, IdentError> {
    let c = CuttingConditions::from_test(test, work_temperature_c)?;
    let p = oxley::predict(material, jc, &c, options, &Physics::baseline())?;
    Ok(ZoneThickness { h_m: p.shear_plane_length_m / p.c0, l_ab_m: p.shear_plane_length_m, c0: p.c0 })
}

/// The outcome of the fixed point `h_{k+1} = step(h_k)`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HFixedPoint {
    /// The last h, m.
    pub h_m: f64,
    /// Every h tried, m, starting with the initial value.
    pub history_m: Vec<f64>,
    /// Whether the relative change fell below the tolerance within the cap.
    pub converged: bool,
}

/// Iterates `h_{k+1} = step(h_k)` from `h0_m` until `|h_{k+1} - h_k| <= rel_tol h_k`, at most
/// `max_iterations` steps. A step's error is returned as is; non-convergence is reported in the
/// outcome (`converged = false`), never hidden.
///
/// Returns an error if a step fails or returns a non-positive or non-finite h.
pub fn self_consistent_h<E: From<IdentError>>(
    h0_m: f64,
    rel_tol: f64,
    max_iterations: usize,
    mut step: impl FnMut(f64) -> Result<f64, E>,
) -> Result<HFixedPoint, E> {
    let mut history = vec![h0_m];
    let mut h = h0_m;
    for _ in 0..max_iterations {
        let next = step(h)?;
        if !(next.is_finite() && next > 0.0) {
            return Err(IdentError::InvalidOptions(format!("the zone thickness step returned h = {next} m")).into());
        }
        history.push(next);
        let done = (next - h).abs() <= rel_tol * h;
        h = next;
        if done {
            return Ok(HFixedPoint { h_m: h, history_m: history, converged: true });
        }
    }
    Ok(HFixedPoint { h_m: h, history_m: history, converged: false })
}

#[cfg(test)]
mod tests {
    use super::*;
    use cutcal_model::reference;

    #[test]
    fn a_contraction_converges_and_a_cycle_is_reported() {
        // h -> (h + 2e-5)/2 has the fixed point 2e-5 m.
        let r = self_consistent_h::<IdentError>(1e-4, 1e-6, 50, |h| Ok((h + 2e-5) / 2.0)).unwrap();
        assert!(r.converged && (r.h_m - 2e-5).abs() < 1e-10, "{r:?}");
        // h -> 3e-5 when h < 2e-5 else 1e-5: a 2-cycle never converges; the cap ends it and says so.
        let r = self_consistent_h::<IdentError>(1e-4, 1e-6, 8, |h| Ok(if h < 2e-5 { 3e-5 } else { 1e-5 })).unwrap();
        assert!(!r.converged);
        assert_eq!(r.history_m.len(), 9);
        assert!(self_consistent_h::<IdentError>(1e-4, 1e-6, 8, |_| Ok(-1.0)).is_err());
    }

    #[test]
    fn oxley_zone_of_the_aisi1045_reference_case_is_its_shear_plane_over_c0() {
        // Lalwani case 1 (200 m/min, 0.15 mm, -7 deg) with Jaspers' set: h = l_AB / C0 of the same
        // prediction, and thinner than the uncut chip (Oxley's zone is thin: C0 ~ 5).
        let m = reference::aisi1045_lalwani2009();
        let jc = JcParams::new(553.1e6, 600.8e6, 0.234, 0.0134, 1.0, 1.0, 1460.0, 25.0).unwrap();
        let t = CuttingTest::new("1", 200.0 / 60.0, 0.15e-3, 1.6e-3, (-7f64).to_radians()).unwrap();
        let z = oxley_zone_thickness(&m, &t, &jc, &OxleyOptions::wide(), 25.0).unwrap();
        assert!((z.h_m - z.l_ab_m / z.c0).abs() < 1e-18);
        assert!(z.h_m > 0.0 && z.h_m < 0.15e-3, "{z:?}");
    }
}
