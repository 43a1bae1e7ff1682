//! Inputs of the extended Oxley model besides the material: cutting conditions, solver options
//! (Oxley's empirical constants, search ranges, tolerances, caps) and the extra-physics hooks.

use serde::{Deserialize, Serialize};

use crate::cutting_test::CuttingTest;
use crate::error::{check_range, ModelError};

use super::edge::{EdgePloughing, FlankWear};

/// The conditions of one orthogonal cut, validated on construction.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CuttingConditions {
    /// Cutting speed V, m/s.
    pub speed_m_per_s: f64,
    /// Uncut chip thickness t1, m.
    pub uncut_chip_thickness_m: f64,
    /// Width of cut w, m (forces per unit width are multiplied by it for totals).
    pub width_m: f64,
    /// Rake angle alpha, rad.
    pub rake_rad: f64,
    /// Initial work-material temperature T_w, degC.
    pub work_temperature_c: f64,
}

impl CuttingConditions {
    /// Validating constructor.
    ///
    /// Returns an error unless `0 < V <= 200 m/s`, `0 < t1 <= 5 mm`, `0 < w <= 1 m`,
    /// `-45 deg < alpha < 45 deg` and `-273.15 < T_w <= 3000 degC`.
    ///
    /// # Example
    /// ```
    /// use cutcal_model::oxley::CuttingConditions;
    /// // Lalwani et al. 2009, AISI 1045 case 1: 200 m/min, 0.15 mm, 1.6 mm, -7 deg, 25 degC.
    /// let c = CuttingConditions::new(200.0 / 60.0, 0.15e-3, 1.6e-3, (-7f64).to_radians(), 25.0).unwrap();
    /// assert!((c.speed_m_per_s - 3.3333).abs() < 1e-3);
    /// assert!(CuttingConditions::new(3.3, -0.1e-3, 1.6e-3, 0.0, 25.0).is_err());
    /// ```
    pub fn new(
        speed_m_per_s: f64,
        uncut_chip_thickness_m: f64,
        width_m: f64,
        rake_rad: f64,
        work_temperature_c: f64,
    ) -> Result<Self, ModelError> {
        check_range("speed_m_per_s", speed_m_per_s, 0.0, 200.0, "0 < V <= 200 m/s")?;
        check_range("uncut_chip_thickness_m", uncut_chip_thickness_m, 0.0, 5e-3, "0 < t1 <= 5e-3 m")?;
        check_range("width_m", width_m, 0.0, 1.0, "0 < w <= 1 m")?;
        let lim = 45f64.to_radians();
        if !(rake_rad.is_finite() && rake_rad > -lim && rake_rad < lim) {
            return Err(ModelError::out_of_range("rake_rad", rake_rad, "-45 deg < alpha < 45 deg"));
        }
        check_range("work_temperature_c", work_temperature_c, -273.15, 3000.0, "-273.15 < T_w <= 3000 degC")?;
        Ok(Self { speed_m_per_s, uncut_chip_thickness_m, width_m, rake_rad, work_temperature_c })
    }

    /// The conditions of a [`CuttingTest`] with the given work temperature, degC.
    pub fn from_test(test: &CuttingTest, work_temperature_c: f64) -> Result<Self, ModelError> {
        Self::new(test.speed_m_per_s, test.uncut_chip_thickness_m, test.width_m, test.rake_rad, work_temperature_c)
    }
}

/// Solver options and Oxley's empirical constants. No `Default`: pick a documented constructor.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OxleyOptions {
    /// eta: fraction of the primary-zone temperature rise reached at AB (Oxley 1989: 0.9).
    pub eta: f64,
    /// psi: ratio of the mean to the maximum secondary-zone temperature rise (Oxley 1989: 0.9).
    pub psi: f64,
    /// Search range of the shear angle phi, rad.
    pub phi_range_rad: [f64; 2],
    /// Search range of Oxley's primary-zone strain-rate constant C0 (= l_AB / zone thickness).
    pub c0_range: [f64; 2],
    /// Search range of delta (secondary-zone thickness / chip thickness).
    pub delta_range: [f64; 2],
    /// Tolerance on the two equilibrium residuals, each normalised by k_AB (dimensionless).
    pub residual_tolerance: f64,
    /// Tolerance of the temperature fixed points, degC.
    pub temperature_tolerance_c: f64,
    /// Cap on the Newton iterations of the (phi, C0) system at one delta.
    pub max_newton_iterations: usize,
    /// Cap on the iterations of every one-dimensional root or minimum search.
    pub max_bracket_iterations: usize,
    /// Grid points of the phi scan used when Newton fails (bracketing fallback).
    pub phi_scan_points: usize,
    /// Grid points of the C0 scan used when Newton fails (bracketing fallback).
    pub c0_scan_points: usize,
    /// Grid points (geometric) of the delta scan that brackets the minimum of Fc.
    pub delta_scan_points: usize,
    /// Relative tolerance of the delta refinement (log-delta), dimensionless.
    pub delta_tolerance: f64,
    /// Fc change below which the Fc(delta) minimum counts as flat (Lalwani-type cases: < 0.003).
    pub delta_flat_tolerance: f64,
    /// Half-width of the probe band around delta*, relative: probes at delta*(1 -/+ band).
    pub delta_flat_band: f64,
    /// Discrete delta choice: `Some(step)` evaluates delta only at `low, low + step, ..., high` and
    /// takes the one with the least Fc, without refinement (Lalwani et al. 2009, Sec. 3: delta in
    /// steps of 0.005). `None`: geometric scan, then Brent's minimiser in ln(delta).
    pub delta_grid_step: Option<f64>,
}

impl OxleyOptions {
    /// The constants, search ranges and discrete delta choice of Lalwani, Mehta & Jain 2009 (Sec. 3):
    /// eta = psi = 0.9, C0 in [2, 10], phi in [8, 45] deg, delta in [0.005, 0.2] in steps of 0.005,
    /// delta the step with the least Fc (the `lalwani` preset).
    ///
    /// These ranges are too narrow for some materials (C38 with Table 5 needs C0 ~ 10.5-13.8);
    /// prefer [`OxleyOptions::wide`] unless reproducing the paper.
    #[must_use]
    pub fn lalwani2009() -> Self {
        Self {
            phi_range_rad: [8f64.to_radians(), 45f64.to_radians()],
            c0_range: [2.0, 10.0],
            delta_range: [0.005, 0.2],
            delta_grid_step: Some(0.005),
            ..Self::wide()
        }
    }

    /// eta = psi = 0.9 (Oxley 1989) with search ranges wider than Lalwani's:
    /// C0 in [1.2, 30], phi in [3, 65] deg, delta in [0.002, 0.5].
    ///
    /// Solver settings: residuals to 1e-8 of k_AB, temperatures to 1e-8 degC, at most 40 Newton
    /// and 100 bracketing iterations; 25 phi, 12 C0 and 5 delta scan points (a factor 4.0 apart; 80 give the same least Fc wherever
    /// it is not flagged at a bound, `tests/it/oxley_scan_density.rs`); ln(delta) refined to 5e-3;
    /// the minimum is "flat" if Fc changes by less than 0.3 % at delta*(1 -/+ 0.25).
    #[must_use]
    pub fn wide() -> Self {
        Self {
            eta: 0.9,
            psi: 0.9,
            phi_range_rad: [3f64.to_radians(), 65f64.to_radians()],
            c0_range: [1.2, 30.0],
            delta_range: [0.002, 0.5],
            residual_tolerance: 1e-8,
            temperature_tolerance_c: 1e-8,
            max_newton_iterations: 40,
            max_bracket_iterations: 100,
            phi_scan_points: 25,
            c0_scan_points: 12,
            delta_scan_points: 5,
            delta_tolerance: 5e-3,
            delta_flat_tolerance: 0.003,
            delta_flat_band: 0.25,
            delta_grid_step: None,
        }
    }

    /// Replaces the three search ranges (phi in rad), validated.
    pub fn with_ranges(
        mut self,
        phi_range_rad: [f64; 2],
        c0_range: [f64; 2],
        delta_range: [f64; 2],
    ) -> Result<Self, ModelError> {
        self.phi_range_rad = phi_range_rad;
        self.c0_range = c0_range;
        self.delta_range = delta_range;
        self.validate()?;
        Ok(self)
    }

    /// Replaces eta and psi, validated (each in (0, 1]).
    pub fn with_eta_psi(mut self, eta: f64, psi: f64) -> Result<Self, ModelError> {
        self.eta = eta;
        self.psi = psi;
        self.validate()?;
        Ok(self)
    }

    /// Checks every field; the error names the field, its value and the allowed range.
    pub fn validate(&self) -> Result<(), ModelError> {
        check_range("eta", self.eta, 0.0, 1.0, "0 < eta <= 1")?;
        check_range("psi", self.psi, 0.0, 1.0, "0 < psi <= 1")?;
        let ordered = |name: &str, r: [f64; 2], lo: f64, hi: f64, rule: &str| -> Result<(), ModelError> {
            if r[0].is_finite() && r[1].is_finite() && r[0] > lo && r[0] < r[1] && r[1] < hi {
                Ok(())
            } else {
                Err(ModelError::Inconsistent(format!("{name} = [{}, {}] must satisfy {rule}", r[0], r[1])))
            }
        };
        ordered("phi_range_rad", self.phi_range_rad, 0.0, std::f64::consts::FRAC_PI_2, "0 < low < high < pi/2")?;
        ordered("c0_range", self.c0_range, 0.0, 1e3, "0 < low < high < 1000")?;
        ordered("delta_range", self.delta_range, 0.0, 1.0, "0 < low < high < 1")?;
        check_range("residual_tolerance", self.residual_tolerance, 0.0, 1e-2, "0 < tol <= 1e-2")?;
        check_range("temperature_tolerance_c", self.temperature_tolerance_c, 0.0, 1.0, "0 < tol <= 1 degC")?;
        check_range("delta_tolerance", self.delta_tolerance, 0.0, 0.1, "0 < tol <= 0.1")?;
        check_range("delta_flat_tolerance", self.delta_flat_tolerance, 0.0, 0.5, "0 < tol <= 0.5")?;
        check_range("delta_flat_band", self.delta_flat_band, 0.0, 0.9, "0 < band <= 0.9")?;
        if let Some(step) = self.delta_grid_step {
            let span = self.delta_range[1] - self.delta_range[0];
            if !(step.is_finite() && step > 0.0 && step <= span && span / step <= 10_000.0) {
                return Err(ModelError::out_of_range(
                    "delta_grid_step",
                    step,
                    format!("0 < step <= {span} (the delta range) with at most 10000 steps"),
                ));
            }
        }
        for (name, v, lo) in [
            ("max_newton_iterations", self.max_newton_iterations, 1),
            ("max_bracket_iterations", self.max_bracket_iterations, 5),
            ("phi_scan_points", self.phi_scan_points, 3),
            ("c0_scan_points", self.c0_scan_points, 3),
            ("delta_scan_points", self.delta_scan_points, 3),
        ] {
            if !(lo..=10_000).contains(&v) {
                return Err(ModelError::out_of_range(name, v as f64, format!("{lo} <= {name} <= 10000")));
            }
        }
        Ok(())
    }
}

/// Additive edge (ploughing) forces per unit width, N/m (discrepancy note M1; Albrecht 1960).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct EdgeForce {
    /// Edge force along the cutting direction, N/m.
    pub cutting_n_per_m: f64,
    /// Edge force along the feed (thrust) direction, N/m.
    pub feed_n_per_m: f64,
}

/// Extra physics beyond Oxley's theory. Every hook has its own parameters; [`Physics::baseline`]
/// switches all of them off (the plain extended Oxley model). No `Default`: the choice is explicit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Physics {
    /// Fixed additive edge forces (M1, the diagnosis's fitted form), or `None`.
    pub edge_force: Option<EdgeForce>,
    /// Edge ploughing by an edge of radius r_e (Waldorf, DeVor & Kapoor 1998), scaled by k_AB and
    /// phi of the solution, or `None` (sharp edge).
    pub edge_ploughing: Option<EdgePloughing>,
    /// Interface friction factor m_f: the tool-chip shear stress is `m_f k_chip` (M4);
    /// 1 = Oxley's full sticking.
    pub interface_friction_factor: f64,
    /// Scale on Boothroyd's heat partition beta (M6); 1 = Oxley. The scaled beta is clamped to [0, 1].
    pub heat_partition_scale: f64,
    /// Share of the tool-chip frictional heat that goes into the chip (M6, the interface part of the
    /// heat partition): it scales the maximum interface rise dT_M, so that `T_int = T_w + dT_SZ +
    /// psi s dT_M`. 1 = Oxley 1989 (all frictional heat into the chip); below 1 the tool takes the
    /// rest (Loewen & Shaw 1954; Komanduri & Hou 2001); above 1 corrects a dT_M correlation that runs
    /// low. Within (0, 2].
    #[serde(default = "one")]
    pub interface_heat_share: f64,
    /// Thermal-softening coupling kappa_T (M7): the flow stress is evaluated at
    /// `T_w + kappa_T (T - T_w)`; 1 = coupled (Oxley), 0 = thermal softening off, above 1 = softening
    /// stronger than the JC law's (Ertuerk, Malakizadi & Larsson 2020 report such coupling), at most 3.
    pub thermal_softening_scale: f64,
    /// Flank-wear land forces (M3; Smithey, Kapoor & DeVor 2001), scaled by k_AB, or `None`.
    pub flank_wear: Option<FlankWear>,
    /// Scale on the strain-rate constant C0 that Oxley's normal-stress condition gives at each phi
    /// (`sigma_N = sigma_N'`, Oxley 1989 Sec. 4.2): C0 = l_AB / (primary-zone thickness), so a
    /// scale s makes the primary zone 1/s times as thick as Oxley's closure puts it, and the
    /// normal-stress condition is then no longer met. 1 = Oxley. Not a mechanism: it lets cutcal's
    /// model emulate another code's primary zone (a fixed-thickness zone, or an FE run's zone set by
    /// its mesh), whose resultant direction `tan(theta) = 1 + 2 (pi/4 - phi) - C0 n_eq` differs.
    /// Within [0.01, 10].
    #[serde(default = "one")]
    pub c0_scale: f64,
}

/// Serde default of a neutral multiplier.
fn one() -> f64 {
    1.0
}

impl Physics {
    /// All hooks off: the extended Oxley model of Lalwani et al. 2009.
    #[must_use]
    pub fn baseline() -> Self {
        Self {
            edge_force: None,
            edge_ploughing: None,
            interface_friction_factor: 1.0,
            heat_partition_scale: 1.0,
            interface_heat_share: 1.0,
            thermal_softening_scale: 1.0,
            flank_wear: None,
            c0_scale: 1.0,
        }
    }

    /// Baseline physics plus the tool's stated condition with the nominal published models:
    /// edge ploughing for `edge_radius_m` ([`EdgePloughing::waldorf1998`]) and the wear land for
    /// `flank_wear_m` ([`FlankWear::smithey2001`]). `None` (or 0) leaves that term off.
    ///
    /// # Example
    /// ```
    /// use cutcal_model::oxley::Physics;
    /// let p = Physics::with_tool(Some(25e-6), None).unwrap();
    /// assert!(p.edge_ploughing.is_some() && p.flank_wear.is_none());
    /// assert!(Physics::with_tool(Some(-1e-6), None).is_err());
    /// ```
    pub fn with_tool(edge_radius_m: Option<f64>, flank_wear_m: Option<f64>) -> Result<Self, ModelError> {
        let mut p = Self::baseline();
        p.edge_ploughing = edge_radius_m.map(EdgePloughing::waldorf1998).transpose()?.filter(|e| e.edge_radius_m > 0.0);
        p.flank_wear = flank_wear_m.map(FlankWear::smithey2001).transpose()?.filter(|f| f.land_m > 0.0);
        Ok(p)
    }

    /// Checks every hook parameter; the error names the field, value and range.
    pub fn validate(&self) -> Result<(), ModelError> {
        if let Some(e) = self.edge_force {
            for (name, v) in [("edge cutting_n_per_m", e.cutting_n_per_m), ("edge feed_n_per_m", e.feed_n_per_m)] {
                if !(v.is_finite() && (-1e6..=1e6).contains(&v)) {
                    return Err(ModelError::out_of_range(name, v, "|F_edge| <= 1e6 N/m"));
                }
            }
        }
        check_range("interface_friction_factor", self.interface_friction_factor, 0.0, 1.0, "0 < m_f <= 1")?;
        check_range("heat_partition_scale", self.heat_partition_scale, 0.0, 3.0, "0 < kappa_beta <= 3")?;
        check_range("interface_heat_share", self.interface_heat_share, 0.0, 2.0, "0 < s <= 2")?;
        let c = self.c0_scale;
        if !(c.is_finite() && (0.01..=10.0).contains(&c)) {
            return Err(ModelError::out_of_range("c0_scale", c, "0.01 <= s_C0 <= 10"));
        }
        let s = self.thermal_softening_scale;
        if !(s.is_finite() && (0.0..=3.0).contains(&s)) {
            return Err(ModelError::out_of_range("thermal_softening_scale", s, "0 <= kappa_T <= 3"));
        }
        if let Some(e) = self.edge_ploughing {
            e.validate()?;
        }
        if let Some(f) = self.flank_wear {
            f.validate()?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lalwani_ranges_are_the_papers_and_validate() {
        // Lalwani et al. 2009, Sec. 3: C0 in [2, 10], phi in [8, 45] deg, delta in [0.005, 0.2].
        let o = OxleyOptions::lalwani2009();
        o.validate().unwrap();
        assert!((o.c0_range[1] - 10.0).abs() < 1e-12);
        assert!((o.phi_range_rad[1].to_degrees() - 45.0).abs() < 1e-9);
        assert!((o.delta_range[0] - 0.005).abs() < 1e-12);
        // The wide set must contain C0 = 14 (C38 with Table 5 needs up to ~13.8, issue 3).
        assert!(OxleyOptions::wide().c0_range[1] > 14.0);
    }

    #[test]
    fn inverted_ranges_and_bad_hooks_are_rejected() {
        let err = OxleyOptions::wide().with_ranges([0.5, 0.1], [2.0, 10.0], [0.01, 0.2]).unwrap_err();
        assert!(err.to_string().contains("phi_range_rad"), "{err}");
        assert!(OxleyOptions::wide().with_eta_psi(1.2, 0.9).is_err());
        let mut p = Physics::baseline();
        p.validate().unwrap();
        p.interface_friction_factor = 0.0;
        assert!(p.validate().is_err());
        p = Physics::baseline();
        p.thermal_softening_scale = 3.5;
        assert!(p.validate().is_err());
        p.thermal_softening_scale = 1.5;
        p.validate().unwrap();
        p.interface_heat_share = 2.5;
        assert!(p.validate().unwrap_err().to_string().contains("interface_heat_share"));
        p.interface_heat_share = 0.6;
        p.validate().unwrap();
    }
}
