//! Tool-condition forces added to Oxley's chip-formation forces: edge ploughing by a rounded cutting
//! edge of radius r_e (Waldorf, DeVor & Kapoor 1998 slip-line field) and the flank-wear land of
//! width VB (Smithey, Kapoor & DeVor 2001 stress distribution). Both are scaled by the shear flow
//! stress k_AB of the SAME Johnson-Cook state the Oxley solution computes at AB, and by its shear
//! angle phi: there is no second copy of the flow-stress physics here.
//!
//! # Edge ploughing (Waldorf, DeVor & Kapoor 1998)
//!
//! D. J. Waldorf, R. E. DeVor, S. G. Kapoor, "A slip-line field for ploughing during orthogonal
//! cutting", J. Manuf. Sci. Eng. 120(4) (1998) 693-699. The ploughing forces per unit width on the
//! slip line CA bounding the stable build-up on the edge are
//!
//! ```text
//! eta   = 1/2 arccos(m)                          (m: friction factor on CA, tau = m k)
//! theta = pi/4 - rho - phi                       (rho: prow angle, phi: shear angle)
//! gamma = eta + phi - arcsin(sqrt2 sin(rho) sin(eta))
//! P_c = k CA [cos(2 eta) cos(phi - gamma + eta) + (1 + 2 theta + 2 gamma + sin 2 eta) sin(phi - gamma + eta)]
//! P_t = k CA [(1 + 2 theta + 2 gamma + sin 2 eta) cos(phi - gamma + eta) - cos(2 eta) sin(phi - gamma + eta)]
//! ```
//!
//! Waldorf et al. give CA proportional to r_e from the geometry of their field. That geometric
//! relation could not be checked against the paper for this implementation, so CA uses a stated
//! closure instead: CA is the horizontal extent of the edge arc below the stagnation point,
//! `CA = r_e sin(theta_s)`, `cos(theta_s) = 1 - min(h_s, t1)/r_e`, with the stagnation height
//! `h_s = c_s r_e`, c_s = 0.3. That value is the middle of the minimum-chip-thickness range
//! h_min = (0.2-0.4) r_e reviewed by Wojciechowski 2022 (Materials 15:59). This makes CA depend on
//! r_e and, for t1 < h_s, on the uncut chip thickness t1. Defaults: prow angle rho = 1.9 deg (Waldorf et
//! al. 1998) and m = 1 (sticking on the build-up, as on Oxley's tool-chip interface). These are
//! nominal model constants, not fitted values, and every one is a public field.
//!
//! # Flank-wear land (Smithey, Kapoor & DeVor 2001)
//!
//! D. W. Smithey, S. G. Kapoor, R. E. DeVor, "A new mechanistic model for predicting worn tool
//! cutting forces", Machining Science and Technology 5(1) (2001) 23-42 (after Waldorf 1996). The
//! normal stress on a land of width VB, with x measured from the cutting edge, is
//!
//! ```text
//! VB >= VB*: sigma(x) = sigma_0                         for 0 <= x <= VB - VB*
//!            sigma(x) = sigma_0 ((VB - x)/VB*)^2        for VB - VB* < x <= VB
//! VB <  VB*: sigma(x) = sigma_0 (VB/VB*) ((VB - x)/VB)^2
//! tau(x) = min(mu_w sigma(x), k)
//! F_t,wear = integral of sigma dx,   F_c,wear = integral of tau dx     (per unit width)
//! ```
//!
//! Here VB* is the land width that flows plastically. Defaults: `sigma_0 = 2 k_AB`, the
//! plane-strain yield pressure of the work (Hill 1950); mu_w = 0.5; VB* = 0.05 mm. These are nominal
//! too and public. The integrals are done in closed form, including the kink where mu_w sigma
//! reaches k.

use serde::{Deserialize, Serialize};

use crate::error::{check_range, ModelError};

/// Edge-ploughing model of Waldorf, DeVor & Kapoor 1998 for an edge of radius r_e.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct EdgePloughing {
    /// Cutting-edge radius r_e, m.
    pub edge_radius_m: f64,
    /// Prow angle rho, rad (Waldorf et al. 1998: 1.9 deg).
    pub prow_angle_rad: f64,
    /// Friction factor m on the slip line CA (tau = m k), 0 < m <= 1.
    pub friction_factor: f64,
    /// Stagnation height over edge radius, c_s = h_s / r_e (closure for CA; see the module docs).
    pub stagnation_height_ratio: f64,
}

impl EdgePloughing {
    /// The model with the nominal constants of the module docs: rho = 1.9 deg, m = 1, c_s = 0.3.
    ///
    /// Returns an error unless `0 <= r_e <= 0.5 mm`.
    pub fn waldorf1998(edge_radius_m: f64) -> Result<Self, ModelError> {
        let e = Self {
            edge_radius_m,
            prow_angle_rad: 1.9f64.to_radians(),
            friction_factor: 1.0,
            stagnation_height_ratio: 0.3,
        };
        e.validate()?;
        Ok(e)
    }

    /// Checks every field; the error names the field, value and range.
    pub fn validate(&self) -> Result<(), ModelError> {
        let r = self.edge_radius_m;
        if !(r.is_finite() && (0.0..=0.5e-3).contains(&r)) {
            return Err(ModelError::out_of_range("edge_radius_m", r, "0 <= r_e <= 5e-4 m"));
        }
        let rho = self.prow_angle_rad;
        if !(rho.is_finite() && (0.0..=20f64.to_radians()).contains(&rho)) {
            return Err(ModelError::out_of_range("edge prow_angle_rad", rho, "0 <= rho <= 20 deg"));
        }
        check_range("edge friction_factor", self.friction_factor, 0.0, 1.0, "0 < m <= 1")?;
        check_range("edge stagnation_height_ratio", self.stagnation_height_ratio, 0.0, 1.0, "0 < c_s <= 1")?;
        Ok(())
    }

    /// Length CA of the slip line along the edge, m: `r_e sin(theta_s)` with
    /// `cos(theta_s) = 1 - min(c_s r_e, t1)/r_e` (closure stated in the module docs).
    #[must_use]
    pub fn contact_length_m(&self, uncut_chip_thickness_m: f64) -> f64 {
        let r = self.edge_radius_m;
        if r <= 0.0 {
            return 0.0;
        }
        let h_s = (self.stagnation_height_ratio * r).min(uncut_chip_thickness_m.max(0.0));
        let cos_s = 1.0 - h_s / r;
        r * (1.0 - cos_s * cos_s).max(0.0).sqrt()
    }

    /// Effective rake angle, rad, that the chip meets on this edge at uncut chip thickness `t1` on a
    /// tool of nominal rake `rake_rad`: the chord from the stagnation point (height `c_s r_e`, the
    /// same closure as [`Self::contact_length_m`]; material below it is ploughed) to the point where
    /// the tool meets the free surface, on the arc or on the rake face beyond the arc's tangent point
    /// (the chord effective rake of an edge-radiused tool, after Manjunathaiah & Endres 2000, J. Manuf.
    /// Sci. Eng. 122, 384, and Kountanya & Endres 2001). At or below the stagnation height, the tangent
    /// there. A sharp edge (r_e = 0) or `t1 >> r_e` gives the nominal rake.
    #[must_use]
    pub fn effective_rake_rad(&self, t1: f64, rake_rad: f64) -> f64 {
        let r = self.edge_radius_m;
        if r <= 0.0 {
            return rake_rad;
        }
        // Edge centre at (0, r), chip on the -x side: the arc point of tangent rake theta is
        // (-r cos theta, r (1 + sin theta)); the rake face is tangent at theta = rake.
        let y_top = r * (1.0 + rake_rad.sin());
        let y_s = (self.stagnation_height_ratio * r).min(y_top);
        let theta_s = (y_s / r - 1.0).clamp(-1.0, 1.0).asin();
        if t1 <= y_s {
            return theta_s;
        }
        if t1 <= y_top {
            // A chord's direction is the mean of the tangent directions at its ends (inscribed angle).
            return 0.5 * (theta_s + (t1 / r - 1.0).clamp(-1.0, 1.0).asin());
        }
        let x_s = -r * theta_s.cos();
        let x_p = -r * rake_rad.cos() + (t1 - y_top) * rake_rad.tan();
        ((x_p - x_s) / (t1 - y_s)).atan()
    }

    /// Ploughing forces per unit width `(P_c, P_t)`, N/m, for shear flow stress `k_pa` and shear
    /// angle `phi_rad` (Waldorf, DeVor & Kapoor 1998, the force equations of their slip-line field).
    #[must_use]
    pub fn forces_n_per_m(&self, k_pa: f64, phi_rad: f64, uncut_chip_thickness_m: f64) -> (f64, f64) {
        let [cut, thrust] = waldorf_factors(phi_rad, self.prow_angle_rad, self.friction_factor);
        let scale = k_pa * self.contact_length_m(uncut_chip_thickness_m);
        (scale * cut, scale * thrust)
    }
}

/// The dimensionless ploughing factors `[P_c, P_t] / (k CA)` of the field
/// (Waldorf, DeVor & Kapoor 1998, the force equations of their slip-line field).
#[must_use]
pub fn waldorf_factors(phi_rad: f64, prow_angle_rad: f64, friction_factor: f64) -> [f64; 2] {
    let eta = 0.5 * friction_factor.clamp(-1.0, 1.0).acos();
    let theta = std::f64::consts::FRAC_PI_4 - prow_angle_rad - phi_rad;
    let gamma = eta + phi_rad - (std::f64::consts::SQRT_2 * prow_angle_rad.sin() * eta.sin()).asin();
    let big = 1.0 + 2.0 * theta + 2.0 * gamma + (2.0 * eta).sin();
    let ang = phi_rad - gamma + eta;
    let c2 = (2.0 * eta).cos();
    [c2 * ang.cos() + big * ang.sin(), big * ang.cos() - c2 * ang.sin()]
}

/// Flank-wear land model of Smithey, Kapoor & DeVor 2001 for a land of width VB.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FlankWear {
    /// Flank wear land width VB, m.
    pub land_m: f64,
    /// sigma_0 over the primary-zone shear flow stress k_AB (default 2: plane-strain yield pressure).
    pub normal_stress_factor: f64,
    /// Friction coefficient on the land, mu_w (tau = min(mu_w sigma, k_AB)).
    pub friction_coefficient: f64,
    /// Plastically flowing length VB* at the land's trailing end, m.
    pub plastic_length_m: f64,
}

impl FlankWear {
    /// The model with the nominal constants of the module docs: sigma_0 = 2 k_AB, mu_w = 0.5,
    /// VB* = 0.05 mm. Returns an error unless `0 <= VB <= 2 mm`.
    pub fn smithey2001(land_m: f64) -> Result<Self, ModelError> {
        let f = Self { land_m, normal_stress_factor: 2.0, friction_coefficient: 0.5, plastic_length_m: 0.05e-3 };
        f.validate()?;
        Ok(f)
    }

    /// Checks every field; the error names the field, value and range.
    pub fn validate(&self) -> Result<(), ModelError> {
        let vb = self.land_m;
        if !(vb.is_finite() && (0.0..=2e-3).contains(&vb)) {
            return Err(ModelError::out_of_range("flank_wear land_m", vb, "0 <= VB <= 2e-3 m"));
        }
        check_range("flank_wear normal_stress_factor", self.normal_stress_factor, 0.0, 10.0, "0 < c_sigma <= 10")?;
        let mu = self.friction_coefficient;
        if !(mu.is_finite() && (0.0..=2.0).contains(&mu)) {
            return Err(ModelError::out_of_range("flank_wear friction_coefficient", mu, "0 <= mu_w <= 2"));
        }
        check_range("flank_wear plastic_length_m", self.plastic_length_m, 0.0, 2e-3, "0 < VB* <= 2e-3 m")?;
        Ok(())
    }

    /// Wear-land forces per unit width `(F_c, F_t)`, N/m, for the shear flow stress `k_pa`
    /// (Smithey, Kapoor & DeVor 2001, the land stress distribution integrated in closed form).
    #[must_use]
    pub fn forces_n_per_m(&self, k_pa: f64) -> (f64, f64) {
        let (vb, vbs) = (self.land_m, self.plastic_length_m);
        if vb <= 0.0 || k_pa <= 0.0 {
            return (0.0, 0.0);
        }
        // Flat part of length a at sigma_0, quadratic tail of length b starting from peak s_0.
        let sigma_full = self.normal_stress_factor * k_pa;
        let (a, b, s0) = if vb >= vbs { (vb - vbs, vbs, sigma_full) } else { (0.0, vb, sigma_full * vb / vbs) };
        let ft = s0 * a + s0 * b / 3.0;
        let mu = self.friction_coefficient;
        let tau0 = (mu * s0).min(k_pa);
        // Tail: tau = min(mu s0 u^2, k) for u in [0, 1]; capped above u* = sqrt(k / (mu s0)).
        let tail = if mu * s0 <= k_pa {
            mu * s0 / 3.0
        } else {
            let u = (k_pa / (mu * s0)).sqrt();
            mu * s0 * u.powi(3) / 3.0 + k_pa * (1.0 - u)
        };
        (tau0 * a + tail * b, ft)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sticking_edge_gives_the_hencky_pressure_on_a_horizontal_slip_line() {
        // m = 1 -> eta = 0 -> gamma = phi: CA is horizontal, P_c = k CA and
        // P_t = k CA (1 + 2 theta + 2 phi) = k CA (1 + pi/2 - 2 rho) (Hencky's pressure change along
        // a slip line turning by pi/4 - rho from the free prow surface; independent calculation).
        for phi in [0.2_f64, 0.4, 0.6] {
            let rho = 1.9f64.to_radians();
            let [c, t] = waldorf_factors(phi, rho, 1.0);
            assert!((c - 1.0).abs() < 1e-12, "{c}");
            assert!((t - (1.0 + std::f64::consts::FRAC_PI_2 - 2.0 * rho)).abs() < 1e-12, "{t}");
        }
    }

    #[test]
    fn ca_grows_with_radius_and_with_t1_below_the_stagnation_height() {
        let e = EdgePloughing::waldorf1998(25e-6).unwrap();
        // c_s = 0.3: cos(theta_s) = 0.7 -> CA = r_e sqrt(1 - 0.49) = 0.71414 r_e for t1 >= 7.5 um.
        assert!((e.contact_length_m(0.1e-3) / 25e-6 - 0.51f64.sqrt()).abs() < 1e-12);
        assert!(e.contact_length_m(2e-6) < e.contact_length_m(5e-6));
        let big = EdgePloughing::waldorf1998(50e-6).unwrap();
        assert!((big.contact_length_m(0.1e-3) / e.contact_length_m(0.1e-3) - 2.0).abs() < 1e-12);
        assert!(EdgePloughing::waldorf1998(-1e-6).is_err());
        assert_eq!(EdgePloughing::waldorf1998(0.0).unwrap().forces_n_per_m(4e8, 0.4, 1e-4), (0.0, 0.0));
    }

    #[test]
    fn effective_rake_matches_the_chord_geometry_by_hand() {
        // Independent coordinates (edge centre (0, r), arc x = -sqrt(r^2 - (y - r)^2)), r = 20 um,
        // c_s = 0.3 so the stagnation point is at 6 um, x_s = -sqrt(400 - 196) = -14.2829 um:
        // - t1 = 40 um, rake 0: the free-surface point is on the rake face at x = -20 um:
        //   atan((-20 + 14.2829) / 34) = -9.54506 deg;
        // - t1 = 20 um, rake 0: at the tangent point: atan(-5.7171 / 14) = -22.21350 deg;
        // - t1 = 10 um: x_p = -sqrt(400 - 100) = -17.3205: atan(-3.0376 / 4) = -37.21350 deg;
        // - t1 = 4 um (below 6 um): the tangent at the stagnation point, asin(-0.7) = -44.42700 deg;
        // - rake 10 deg, t1 = 40 um: y_top = 23.4730 um, x_p = -19.6962 + 16.5270 tan 10 deg =
        //   -16.7820 um: atan(-2.4991 / 34) = -4.20391 deg.
        let e = EdgePloughing::waldorf1998(20e-6).unwrap();
        let deg = |t1_um: f64, rake_deg: f64| e.effective_rake_rad(t1_um * 1e-6, rake_deg.to_radians()).to_degrees();
        for (t1, rake, want) in [
            (40.0, 0.0, -9.545_065),
            (20.0, 0.0, -22.213_502),
            (10.0, 0.0, -37.213_502),
            (4.0, 0.0, -44.427_004),
            (40.0, 10.0, -4.203_908),
        ] {
            assert!((deg(t1, rake) - want).abs() < 1e-5, "t1 {t1} rake {rake}: {} vs {want}", deg(t1, rake));
        }
        // Continuous at the tangent point, and the nominal rake far above the edge or with no edge.
        let top = 20.0 * (1.0 + 10f64.to_radians().sin());
        assert!((deg(top - 1e-9, 10.0) - deg(top + 1e-9, 10.0)).abs() < 1e-6);
        assert!((deg(1e6, 10.0) - 10.0).abs() < 0.01);
        assert_eq!(EdgePloughing::waldorf1998(0.0).unwrap().effective_rake_rad(1e-5, 0.1), 0.1);
    }

    #[test]
    fn wear_land_integrals_match_a_numerical_quadrature() {
        let k = 400e6;
        for (vb, mu, c) in [(0.2e-3, 0.5, 2.0), (0.03e-3, 0.5, 2.0), (0.3e-3, 0.9, 2.0), (0.1e-3, 0.2, 1.5)] {
            let f =
                FlankWear { land_m: vb, normal_stress_factor: c, friction_coefficient: mu, plastic_length_m: 0.05e-3 };
            let (fc, ft) = f.forces_n_per_m(k);
            // Midpoint rule on the stress distribution written out directly from the module docs.
            let n = 200_000;
            let (mut sc, mut st) = (0.0, 0.0);
            let vbs = f.plastic_length_m;
            for i in 0..n {
                let x = (i as f64 + 0.5) / n as f64 * vb;
                let s = if vb >= vbs {
                    if x <= vb - vbs {
                        c * k
                    } else {
                        c * k * ((vb - x) / vbs).powi(2)
                    }
                } else {
                    c * k * (vb / vbs) * ((vb - x) / vb).powi(2)
                };
                st += s * vb / n as f64;
                sc += (mu * s).min(k) * vb / n as f64;
            }
            assert!((ft / st - 1.0).abs() < 1e-6, "{ft} {st}");
            assert!((fc / sc - 1.0).abs() < 1e-6, "{fc} {sc}");
        }
    }
}
