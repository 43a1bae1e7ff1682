//! An orthogonal cutting test: conditions and what was measured, validated on construction.

use serde::{Deserialize, Serialize};

use crate::error::{check_range, ModelError};

/// What was measured in a cutting test; `None` means not measured.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Measured {
    /// Cutting force per unit width of cut, N/m (N/mm x 1e3).
    pub cutting_force_n_per_m: Option<f64>,
    /// Feed (thrust) force per unit width of cut, N/m.
    pub feed_force_n_per_m: Option<f64>,
    /// Chip thickness t_c, m.
    pub chip_thickness_m: Option<f64>,
    /// Tool-chip interface temperature, degC.
    pub interface_temperature_c: Option<f64>,
    /// Standard deviations of the measurements, where the data state them.
    pub sd: MeasuredSd,
}

/// Standard deviations of the measured quantities (same units as [`Measured`]); `None` means the
/// data do not state one and callers fall back to their documented default noise model.
///
/// Filled from the tests CSV columns `fc_sd_n_per_mm`, `ft_sd_n_per_mm`, `chip_sd_mm` (for instance
/// as written by `cutcal recordings`) and `t_int_sd_c`, or from the spread of repeated tests at one
/// condition.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct MeasuredSd {
    /// Standard deviation of the cutting force per unit width, N/m.
    pub cutting_force_n_per_m: Option<f64>,
    /// Standard deviation of the feed force per unit width, N/m.
    pub feed_force_n_per_m: Option<f64>,
    /// Standard deviation of the chip thickness, m.
    pub chip_thickness_m: Option<f64>,
    /// Standard deviation of the tool-chip interface temperature, K (the thermocouple's or the
    /// camera's stated uncertainty).
    #[serde(default)]
    pub interface_temperature_c: Option<f64>,
}

/// An orthogonal cutting test.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CuttingTest {
    /// Test identifier (e.g. `3`).
    pub id: String,
    /// Cutting speed V, m/s.
    pub speed_m_per_s: f64,
    /// Uncut chip thickness t_u (feed in orthogonal turning), m.
    pub uncut_chip_thickness_m: f64,
    /// Width of cut w (depth of cut in the paper), m.
    pub width_m: f64,
    /// Rake angle alpha, rad.
    pub rake_rad: f64,
    /// Measurements.
    pub measured: Measured,
    /// Cutting-edge radius, m, where known.
    pub edge_radius_m: Option<f64>,
    /// Flank wear land VB, m, where known.
    pub flank_wear_m: Option<f64>,
    /// Run order, where known.
    pub order: Option<u32>,
}

impl CuttingTest {
    /// Validating constructor for the cutting conditions.
    ///
    /// Returns an error if `0 < V <= 200 m/s`, `0 < t_u <= 5 mm`, `0 < w <= 1 m` or
    /// `-45 deg < alpha < 45 deg` does not hold.
    ///
    /// # Example
    /// ```
    /// use cutcal_model::CuttingTest;
    /// // C38 test 3 (paper Table 2): 240 m/min, 0.075 mm, 1.95 mm, 0 deg rake.
    /// let t = CuttingTest::new("3", 4.0, 0.075e-3, 1.95e-3, 0.0).unwrap();
    /// assert!(CuttingTest::new("x", -4.0, 0.075e-3, 1.95e-3, 0.0).is_err());
    /// # let _ = t;
    /// ```
    pub fn new(
        id: impl Into<String>,
        speed_m_per_s: f64,
        uncut_chip_thickness_m: f64,
        width_m: f64,
        rake_rad: f64,
    ) -> Result<Self, ModelError> {
        check_range("speed_m_per_s", speed_m_per_s, 0.0, 200.0, "0 < V <= 200 m/s")?;
        check_range("uncut_chip_thickness_m", uncut_chip_thickness_m, 0.0, 5e-3, "0 < t_u <= 5e-3 m")?;
        check_range("width_m", width_m, 0.0, 1.0, "0 < w <= 1 m")?;
        let lim = 45f64.to_radians();
        if !(rake_rad.is_finite() && rake_rad > -lim && rake_rad < lim) {
            return Err(ModelError::out_of_range("rake_rad", rake_rad, "-45 deg < alpha < 45 deg"));
        }
        Ok(Self {
            id: id.into(),
            speed_m_per_s,
            uncut_chip_thickness_m,
            width_m,
            rake_rad,
            measured: Measured::default(),
            edge_radius_m: None,
            flank_wear_m: None,
            order: None,
        })
    }

    /// Sets the measured forces per unit width (N/m); each must be positive and below 1e7 N/m.
    pub fn with_forces(mut self, cutting_n_per_m: Option<f64>, feed_n_per_m: Option<f64>) -> Result<Self, ModelError> {
        if let Some(fc) = cutting_n_per_m {
            check_range("cutting_force_n_per_m", fc, 0.0, 1e7, "0 < Fc <= 1e7 N/m")?;
        }
        if let Some(ft) = feed_n_per_m {
            check_range("feed_force_n_per_m", ft, 0.0, 1e7, "0 < Ft <= 1e7 N/m")?;
        }
        self.measured.cutting_force_n_per_m = cutting_n_per_m;
        self.measured.feed_force_n_per_m = feed_n_per_m;
        Ok(self)
    }

    /// Sets the measured chip thickness (m); it must give a shear angle in (0, 90) deg.
    pub fn with_chip_thickness(mut self, chip_m: Option<f64>) -> Result<Self, ModelError> {
        if let Some(tc) = chip_m {
            check_range("chip_thickness_m", tc, 0.0, 0.05, "0 < t_c <= 0.05 m")?;
            crate::kinematics::shear_angle_from_chip(self.uncut_chip_thickness_m, tc, self.rake_rad)?;
        }
        self.measured.chip_thickness_m = chip_m;
        Ok(self)
    }

    /// Sets the measured tool-chip interface temperature, degC.
    pub fn with_interface_temperature(mut self, t_c: Option<f64>) -> Result<Self, ModelError> {
        if let Some(t) = t_c {
            check_range("interface_temperature_c", t, -273.15, 5000.0, "-273.15 < T <= 5000 degC")?;
        }
        self.measured.interface_temperature_c = t_c;
        Ok(self)
    }

    /// Sets the standard deviations of the measurements (N/m, N/m, m, K); each must be finite and > 0.
    ///
    /// Returns an error naming the field if a value is not finite or not positive.
    pub fn with_measurement_sd(mut self, sd: MeasuredSd) -> Result<Self, ModelError> {
        for (field, v) in [
            ("cutting_force_sd_n_per_m", sd.cutting_force_n_per_m),
            ("feed_force_sd_n_per_m", sd.feed_force_n_per_m),
            ("chip_thickness_sd_m", sd.chip_thickness_m),
            ("interface_temperature_sd_c", sd.interface_temperature_c),
        ] {
            if let Some(x) = v {
                check_range(field, x, 0.0, 1e7, "0 < sd <= 1e7 (SI)")?;
            }
        }
        self.measured.sd = sd;
        Ok(self)
    }

    /// Sets the tool condition: edge radius and flank wear land, m.
    pub fn with_tool_condition(
        mut self,
        edge_radius_m: Option<f64>,
        flank_wear_m: Option<f64>,
    ) -> Result<Self, ModelError> {
        if let Some(r) = edge_radius_m {
            if !(r.is_finite() && (0.0..=1e-3).contains(&r)) {
                return Err(ModelError::out_of_range("edge_radius_m", r, "0 <= r_e <= 1e-3 m"));
            }
        }
        if let Some(vb) = flank_wear_m {
            if !(vb.is_finite() && (0.0..=2e-3).contains(&vb)) {
                return Err(ModelError::out_of_range("flank_wear_m", vb, "0 <= VB <= 2e-3 m"));
            }
        }
        self.edge_radius_m = edge_radius_m;
        self.flank_wear_m = flank_wear_m;
        Ok(self)
    }
}
