//! Kinematics of the parallel-sided primary shear zone (paper Sec 3.2, Eqs 2, 3, 5, 6, 9).
//!
//! Coordinates: `x` runs across the zone from the chip side EF (`x = -h/2`) to the workpiece
//! side CD (`x = +h/2`); material enters at CD and leaves at EF with normal velocity
//! `V_n = V sin(phi)`.

use crate::error::ModelError;

/// Shear angle from the chip ratio: `tan(phi) = r_c cos(alpha) / (1 - r_c sin(alpha))`, `r_c = t_u/t_c`.
///
/// **Source:** standard orthogonal-cutting geometry (paper Fig 2). Angles in rad, lengths in m.
///
/// Returns an error unless the result lies in (0, 90) deg.
///
/// # Example
/// ```
/// // C38 test 3: t_u = 0.075 mm, t_c = 0.157 mm, alpha = 0 gives 25.53 deg.
/// let phi = cutcal_model::kinematics::shear_angle_from_chip(0.075e-3, 0.157e-3, 0.0).unwrap();
/// assert!((phi.to_degrees() - 25.53).abs() < 0.01);
/// ```
pub fn shear_angle_from_chip(uncut_m: f64, chip_m: f64, rake_rad: f64) -> Result<f64, ModelError> {
    let rc = uncut_m / chip_m;
    let den = 1.0 - rc * rake_rad.sin();
    let phi = (rc * rake_rad.cos()).atan2(den);
    if rc.is_finite() && phi > 0.0 && phi < std::f64::consts::FRAC_PI_2 {
        Ok(phi)
    } else {
        Err(ModelError::out_of_range(
            "chip_thickness_m",
            chip_m,
            &*format!(
                "a chip ratio t_u/t_c = {rc:.4} giving a shear angle in (0, 90) deg (got {:.2} deg)",
                phi.to_degrees()
            ),
        ))
    }
}

/// Maximum shear stress on AB from the measured forces per unit width, Pa:
/// `tau_max = (F_c cos(phi) - F_t sin(phi)) sin(phi) / t_u`.
///
/// **Source:** paper Eq 9 (printed with the opposite sign; its magnitude is the shear-plane stress).
///
/// Returns an error if the shear-plane force is not positive.
pub fn tau_max_from_forces(
    cutting_n_per_m: f64,
    feed_n_per_m: f64,
    shear_angle_rad: f64,
    uncut_m: f64,
) -> Result<f64, ModelError> {
    let fs = cutting_n_per_m * shear_angle_rad.cos() - feed_n_per_m * shear_angle_rad.sin();
    let tau = fs * shear_angle_rad.sin() / uncut_m;
    if tau.is_finite() && tau > 0.0 {
        Ok(tau)
    } else {
        Err(ModelError::out_of_range(
            "shear-plane force Fc cos(phi) - Ft sin(phi) (N/m)",
            fs,
            "a positive shear force (Eq 9): the feed force is too large for this shear angle",
        ))
    }
}

/// Shear strain on AB: `gamma_AB = cos(alpha) / (2 sin(phi) cos(phi - alpha))`.
///
/// **Source:** paper Eq 6.
#[must_use]
pub fn gamma_ab(shear_angle_rad: f64, rake_rad: f64) -> f64 {
    rake_rad.cos() / (2.0 * shear_angle_rad.sin() * (shear_angle_rad - rake_rad).cos())
}

/// Shear strain rate on AB: `gammadot_AB = V (r+1)/h cos(alpha)/cos(phi - alpha)`, 1/s.
///
/// **Source:** paper Eq 3. `speed_m_per_s` V, `zone_thickness_m` h, exponent `r`.
#[must_use]
pub fn gamma_dot_ab(speed_m_per_s: f64, zone_thickness_m: f64, r: f64, shear_angle_rad: f64, rake_rad: f64) -> f64 {
    speed_m_per_s * (r + 1.0) / zone_thickness_m * rake_rad.cos() / (shear_angle_rad - rake_rad).cos()
}

/// The normalised distance `u` from the nearer boundary toward AB: `u = 1 - 2|x|/h`, in [0, 1].
#[must_use]
pub fn distance_to_boundary(x_m: f64, zone_thickness_m: f64) -> f64 {
    (1.0 - 2.0 * x_m.abs() / zone_thickness_m).clamp(0.0, 1.0)
}

/// Shear strain rate at `x`: `gammadot_AB (1 -/+ 2x/h)^r`, 1/s.
///
/// **Source:** paper Eq 2.
#[must_use]
pub fn gamma_dot(x_m: f64, zone_thickness_m: f64, r: f64, gamma_dot_ab: f64) -> f64 {
    gamma_dot_ab * distance_to_boundary(x_m, zone_thickness_m).powf(r)
}

/// Shear strain at `x`, accumulated from CD (`x = h/2`, `gamma = 0`) to EF (`gamma = 2 gamma_AB`).
///
/// **Source:** paper Eq 5 (integrated in the direction of flow, CD to EF).
#[must_use]
pub fn gamma(x_m: f64, zone_thickness_m: f64, r: f64, gamma_ab: f64) -> f64 {
    gamma_from_power(x_m, distance_to_boundary(x_m, zone_thickness_m).powf(r + 1.0), gamma_ab)
}

/// [`gamma`] from `u^(r+1)`, `u` = [`distance_to_boundary`] (for callers that already hold the
/// power).
///
/// **Source:** paper Eq 5.
#[must_use]
pub fn gamma_from_power(x_m: f64, u_pow_r_plus_1: f64, gamma_ab: f64) -> f64 {
    if x_m >= 0.0 {
        gamma_ab * u_pow_r_plus_1
    } else {
        gamma_ab * (2.0 - u_pow_r_plus_1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn c38_test3_kinematics_match_paper() {
        // C38 test 3 (paper Tables 2 and 6): tu 0.075 mm, tc 0.157 mm, Fc 224 N/mm, Ft 186 N/mm, alpha 0.
        let phi = shear_angle_from_chip(0.075e-3, 0.157e-3, 0.0).unwrap();
        // atan(0.075/0.157) = 25.533 deg (the paper's 25.48 deg corresponds to tc ~ 0.1574 mm).
        assert!((phi.to_degrees() - (0.075f64 / 0.157).atan().to_degrees()).abs() < 1e-12);
        assert!((phi.to_degrees() - 25.53).abs() < 0.005);
        let tau = tau_max_from_forces(224e3, 186e3, phi, 0.075e-3).unwrap();
        assert!((tau / 1e6 - 700.9).abs() < 0.05, "{}", tau / 1e6);
        // Maximum effective strain 2 gamma_AB / sqrt(3) = 1.484.
        let eps_max = gamma(-0.05e-3, 0.1e-3, 4.0, gamma_ab(phi, 0.0)) / 3f64.sqrt();
        assert!((eps_max - 1.484).abs() < 5e-4, "{eps_max}");
    }

    #[test]
    fn strain_is_the_integral_of_rate_over_normal_velocity() {
        // gamma(x) = (1/V_n) int_x^{h/2} gammadot dx' with V_n = V sin(phi): trapezoid check.
        let (v, h, r, phi, alpha) = (4.0, 1e-4, 4.0, 0.45, 0.1);
        let gdot_ab = gamma_dot_ab(v, h, r, phi, alpha);
        let gab = gamma_ab(phi, alpha);
        let n = 200_000;
        let dx = h / n as f64;
        let mut acc = 0.0;
        for i in 0..n {
            let x1 = h / 2.0 - i as f64 * dx;
            let x2 = x1 - dx;
            acc += 0.5 * (gamma_dot(x1, h, r, gdot_ab) + gamma_dot(x2, h, r, gdot_ab)) * dx;
            if i == n / 4 || i == 3 * n / 4 {
                let g = acc / (v * phi.sin());
                assert!((g - gamma(x2, h, r, gab)).abs() < 1e-6 * gab, "at {x2}");
            }
        }
        assert!((acc / (v * phi.sin()) - 2.0 * gab).abs() < 1e-6);
    }

    #[test]
    fn rejects_chip_giving_no_shear_angle() {
        // alpha = 30 deg and t_c = 0.4 t_u: 1 - r_c sin(alpha) < 0, shear angle beyond 90 deg.
        assert!(shear_angle_from_chip(0.1e-3, 0.04e-3, 30f64.to_radians()).is_err());
        assert!(tau_max_from_forces(100e3, 500e3, 0.6, 1e-4).is_err());
    }
}
