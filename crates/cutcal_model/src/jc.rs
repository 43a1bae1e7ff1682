//! The Johnson-Cook flow stress (paper Eq 16 with the degradation function of Eq 14) and its derivatives.

use serde::{Deserialize, Serialize};

use crate::error::{check_finite, ModelError};

/// A Johnson-Cook parameter set, stresses in Pa, temperatures in degC.
///
/// `sigma = (A + B eps^n) (1 + C ln(epsdot/eps0)) g(T)`, `g(T) = 1 - ((T - Tr)/(Tm - Tr))^m`
/// (paper Eqs 14 and 16; natural logarithm).
///
/// Conventions (the law as the FE solvers implement it, the one the exported cards carry):
/// - rate term: `1 + C ln(epsdot/eps0)` for `epsdot > eps0`, and 1 at or below `eps0`
///   (Abaqus Analysis User's Guide, "Rate-dependent yield", Johnson-Cook rate dependence:
///   `R = 1 + C ln(epsdot/eps0)` for `epsdot >= eps0`, `R = 1` below; and the
///   same convention for LS-DYNA *MAT_015 (Keyword Manual Vol II) as the project brief states it);
/// - temperature: below the reference (transition) temperature `Tr` the homologous temperature is
///   0, so `g = 1` (no hardening from cooling), and at or above `Tm` it is 1, so the stress is 0
///   (Abaqus "Johnson-Cook plasticity", `theta_hat = 0` below the transition temperature and
///   1 above melting; LS-DYNA *MAT_015 melting criterion).
///
/// The paper's own law leaves the rate term unclamped ([`RateTerm::Unclamped`]); it is used only by
/// the `paper` identification preset to reproduce Table 4.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct JcParams {
    /// Yield stress A, Pa.
    pub a_pa: f64,
    /// Hardening modulus B, Pa.
    pub b_pa: f64,
    /// Hardening exponent n, dimensionless.
    pub n: f64,
    /// Strain-rate constant C, dimensionless.
    pub c: f64,
    /// Thermal softening exponent m, dimensionless.
    pub m: f64,
    /// Reference strain rate, 1/s.
    pub eps0_per_s: f64,
    /// Melting temperature Tm, degC.
    pub tm_c: f64,
    /// Reference (room) temperature Tr, degC.
    pub tr_c: f64,
}

/// How the rate term `1 + C ln(epsdot/eps0)` of Eq 16 is evaluated below `eps0`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RateTerm {
    /// 1 at or below `eps0` (Abaqus, LS-DYNA): the law of the exported cards, the default.
    Clamped,
    /// The paper's literal Eq 16: `1 + C ln(epsdot/eps0)` at every rate (falls below 1, and below
    /// 0 for `epsdot < eps0 exp(-1/C)`). Used only by the `paper` preset.
    Unclamped,
}

impl RateTerm {
    /// `ln(epsdot/eps0)` as it enters the law: clamped at 0 for [`RateTerm::Clamped`].
    #[must_use]
    pub fn log_ratio(self, strain_rate_per_s: f64, eps0_per_s: f64) -> f64 {
        let l = (strain_rate_per_s / eps0_per_s).ln();
        match self {
            RateTerm::Clamped => l.max(0.0),
            RateTerm::Unclamped => l,
        }
    }
}

/// Partial derivatives of the JC stress with respect to its five parameters `[A, B, n, C, m]`.
pub type JcGradient = [f64; 5];

impl JcParams {
    /// Validating constructor.
    ///
    /// Returns an error if a value is NaN/infinite, A < 0, B < 0, n < 0, C < 0, m <= 0,
    /// eps0 <= 0 or Tm <= Tr.
    ///
    /// # Example
    /// ```
    /// use cutcal_model::JcParams;
    /// // Table 5 (paper), C38.
    /// let jc = JcParams::new(589e6, 145e6, 0.25, 0.069, 1.1, 1.0, 1460.0, 20.0).unwrap();
    /// assert!((jc.flow_stress(0.0, 1.0, 20.0) - 589e6).abs() < 1e-6);
    /// ```
    #[allow(clippy::too_many_arguments)] // the eight JC constants are one physical set, named at the call
    pub fn new(
        a_pa: f64,
        b_pa: f64,
        n: f64,
        c: f64,
        m: f64,
        eps0_per_s: f64,
        tm_c: f64,
        tr_c: f64,
    ) -> Result<Self, ModelError> {
        let jc = Self { a_pa, b_pa, n, c, m, eps0_per_s, tm_c, tr_c };
        jc.validate()?;
        Ok(jc)
    }

    /// Checks every field (see [`JcParams::new`]).
    pub fn validate(&self) -> Result<(), ModelError> {
        for (name, v) in [
            ("a_pa", self.a_pa),
            ("b_pa", self.b_pa),
            ("n", self.n),
            ("c", self.c),
            ("m", self.m),
            ("eps0_per_s", self.eps0_per_s),
            ("tm_c", self.tm_c),
            ("tr_c", self.tr_c),
        ] {
            check_finite(name, v)?;
        }
        if self.a_pa < 0.0 {
            return Err(ModelError::out_of_range("a_pa", self.a_pa, "A >= 0 Pa"));
        }
        if self.b_pa < 0.0 {
            return Err(ModelError::out_of_range("b_pa", self.b_pa, "B >= 0 Pa"));
        }
        if !(0.0..=2.0).contains(&self.n) {
            return Err(ModelError::out_of_range("n", self.n, "0 <= n <= 2"));
        }
        if self.c < 0.0 {
            return Err(ModelError::out_of_range("c", self.c, "C >= 0"));
        }
        if self.m <= 0.0 || self.m > 10.0 {
            return Err(ModelError::out_of_range("m", self.m, "0 < m <= 10"));
        }
        if self.eps0_per_s <= 0.0 {
            return Err(ModelError::out_of_range("eps0_per_s", self.eps0_per_s, "eps0 > 0 1/s"));
        }
        if self.tm_c <= self.tr_c {
            return Err(ModelError::Inconsistent(format!(
                "melting temperature tm_c = {} degC must exceed the reference temperature tr_c = {} degC",
                self.tm_c, self.tr_c
            )));
        }
        Ok(())
    }

    /// Homologous temperature `(T - Tr)/(Tm - Tr)`, clamped to `[0, 1]`.
    #[must_use]
    pub fn homologous(&self, temperature_c: f64) -> f64 {
        ((temperature_c - self.tr_c) / (self.tm_c - self.tr_c)).clamp(0.0, 1.0)
    }

    /// Thermal degradation `g(T) = 1 - theta^m` (paper Eq 14).
    #[must_use]
    pub fn softening(&self, temperature_c: f64) -> f64 {
        1.0 - self.homologous(temperature_c).powf(self.m)
    }

    /// Strain-hardening term `A + B eps^n` (paper Eq 16), Pa.
    #[must_use]
    pub fn hardening(&self, strain: f64) -> f64 {
        self.a_pa + self.b_pa * pow_n(strain, self.n)
    }

    /// Strain-rate term `1 + C ln(epsdot/eps0)` (paper Eq 16), 1 at or below `eps0` (the solvers'
    /// convention, see [`JcParams`]).
    #[must_use]
    pub fn rate_factor(&self, strain_rate_per_s: f64) -> f64 {
        self.rate_factor_with(RateTerm::Clamped, strain_rate_per_s)
    }

    /// Strain-rate term under an explicit [`RateTerm`] (paper Eq 16).
    #[must_use]
    pub fn rate_factor_with(&self, term: RateTerm, strain_rate_per_s: f64) -> f64 {
        1.0 + self.c * term.log_ratio(strain_rate_per_s, self.eps0_per_s)
    }

    /// Flow stress under an explicit [`RateTerm`], Pa (paper Eq 16 with Eq 14).
    #[must_use]
    pub fn flow_stress_with(&self, term: RateTerm, strain: f64, strain_rate_per_s: f64, temperature_c: f64) -> f64 {
        self.hardening(strain) * self.rate_factor_with(term, strain_rate_per_s) * self.softening(temperature_c)
    }

    /// Johnson-Cook flow stress in Pa (paper Eq 16 with Eq 14).
    ///
    /// `strain` >= 0 (effective plastic strain), `strain_rate_per_s` > 0, `temperature_c` in degC.
    #[must_use]
    pub fn flow_stress(&self, strain: f64, strain_rate_per_s: f64, temperature_c: f64) -> f64 {
        self.hardening(strain) * self.rate_factor(strain_rate_per_s) * self.softening(temperature_c)
    }

    /// Derivative of the flow stress with respect to strain (Pa).
    #[must_use]
    pub fn d_strain(&self, strain: f64, strain_rate_per_s: f64, temperature_c: f64) -> f64 {
        let dh = if strain > 0.0 { self.b_pa * self.n * strain.powf(self.n - 1.0) } else { 0.0 };
        dh * self.rate_factor(strain_rate_per_s) * self.softening(temperature_c)
    }

    /// Derivative of the flow stress with respect to strain rate (Pa s); 0 at or below `eps0`.
    #[must_use]
    pub fn d_strain_rate(&self, strain: f64, strain_rate_per_s: f64, temperature_c: f64) -> f64 {
        if strain_rate_per_s <= self.eps0_per_s {
            return 0.0;
        }
        self.hardening(strain) * self.c / strain_rate_per_s * self.softening(temperature_c)
    }

    /// Derivative of the flow stress with respect to temperature (Pa/K); 0 outside `(Tr, Tm)`.
    #[must_use]
    pub fn d_temperature(&self, strain: f64, strain_rate_per_s: f64, temperature_c: f64) -> f64 {
        let span = self.tm_c - self.tr_c;
        let theta = (temperature_c - self.tr_c) / span;
        if theta <= 0.0 || theta >= 1.0 {
            return 0.0;
        }
        let dg = -self.m * theta.powf(self.m - 1.0) / span;
        self.hardening(strain) * self.rate_factor(strain_rate_per_s) * dg
    }

    /// Gradient of the flow stress with respect to `[A, B, n, C, m]` (A, B in Pa; result in Pa per unit).
    #[must_use]
    pub fn gradient(&self, strain: f64, strain_rate_per_s: f64, temperature_c: f64) -> JcGradient {
        let en = pow_n(strain, self.n);
        let h = self.a_pa + self.b_pa * en;
        let lnr = RateTerm::Clamped.log_ratio(strain_rate_per_s, self.eps0_per_s);
        let rf = 1.0 + self.c * lnr;
        let theta = self.homologous(temperature_c);
        let tm = theta.powf(self.m);
        let g = 1.0 - tm;
        let d_n = if strain > 0.0 { self.b_pa * en * strain.ln() } else { 0.0 };
        let d_m = if theta > 0.0 { -tm * theta.ln() } else { 0.0 };
        [rf * g, en * rf * g, d_n * rf * g, h * lnr * g, h * rf * d_m]
    }
}

/// `x^n` with `0^0 = 1` and `0^n = 0` for n > 0.
fn pow_n(x: f64, n: f64) -> f64 {
    if x > 0.0 {
        x.powf(n)
    } else if n == 0.0 {
        1.0
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn c38() -> JcParams {
        // Table 5 (paper): C38 calibrated set.
        JcParams::new(589e6, 145e6, 0.25, 0.069, 1.1, 1.0, 1460.0, 20.0).unwrap()
    }

    #[test]
    fn flow_stress_matches_hand_calculation() {
        // (589 + 145 * 1^0.25) * (1 + 0.069 ln(1e4)) * (1 - (480/1440)^1.1), evaluated by hand:
        // 734 * 1.635510 * (1 - 0.298630) = 841.94 MPa
        // (python: 734*(1+0.069*math.log(1e4))*(1-(480/1440)**1.1) = 841.944).
        let s = c38().flow_stress(1.0, 1e4, 500.0);
        let h = 734.0 * (1.0 + 0.069 * 1e4f64.ln()) * (1.0 - (480.0f64 / 1440.0).powf(1.1));
        assert!((s / 1e6 - h).abs() < 1e-9);
        assert!((h - 841.944).abs() < 1e-3);
    }

    #[test]
    fn below_reference_temperature_no_softening() {
        let jc = c38();
        assert!((jc.softening(0.0) - 1.0).abs() < 1e-15);
        assert!(jc.softening(1460.0).abs() < 1e-15);
    }

    #[test]
    fn rate_term_is_one_at_and_below_eps0_when_clamped() {
        let jc = c38();
        // Clamped (Abaqus/LS-DYNA): exactly the static stress at and below eps0 = 1/s.
        for rate in [1e-6, 0.01, 0.5, 1.0] {
            assert_eq!(jc.rate_factor(rate), 1.0);
            assert_eq!(jc.d_strain_rate(0.5, rate, 300.0), 0.0);
            assert_eq!(jc.gradient(0.5, rate, 300.0)[3], 0.0);
        }
        // Unclamped (paper Eq 16 literally): 1 + 0.069 ln(0.01) = 0.682243 (python: 1+0.069*math.log(0.01)).
        assert!((jc.rate_factor_with(RateTerm::Unclamped, 0.01) - (1.0 + 0.069 * 0.01f64.ln())).abs() < 1e-15);
        assert!((jc.rate_factor_with(RateTerm::Unclamped, 0.01) - 0.682243).abs() < 1e-6);
        // Above eps0 both agree.
        assert_eq!(jc.rate_factor(1e4), jc.rate_factor_with(RateTerm::Unclamped, 1e4));
    }

    #[test]
    fn constructor_rejects_nonphysical_values() {
        assert!(JcParams::new(f64::NAN, 1.0, 0.2, 0.01, 1.0, 1.0, 1460.0, 20.0).is_err());
        assert!(JcParams::new(500e6, -1.0, 0.2, 0.01, 1.0, 1.0, 1460.0, 20.0).is_err());
        assert!(JcParams::new(500e6, 1.0, 0.2, 0.01, 1.0, 1.0, 20.0, 20.0).is_err());
    }

    proptest! {
        // Every analytic derivative equals a central difference at random admissible points. The
        // clamped rate term has a kink at eps0 (ln of the rate 0), where no derivative exists: a
        // central difference there straddles it, and just above it the C-gradient (proportional
        // to ln of the rate) falls below the difference's rounding (about 1e-16 s / step, 0.2 Pa
        // at the hottest point), so the rate is drawn from ln 0.05 upwards. At 0.0 the test failed
        // in one CI run in many (forty-second session; proptest's minimal case had ln rate 0).
        // The tolerance is relative (1e-5) plus the central difference's rounding, 64 ulps of the
        // stress over the step (Press et al. 2007, Sec 5.7): where a derivative is tiny beside the
        // stress it is below what the difference can resolve. A fixed 1e-3 Pa failed 5 seeds of a
        // 1000-seed audit (forty-third session): dsigma/dn = B eps^n ln(eps) times the rate and
        // thermal factors, at eps = 1.00007, B = 10 MPa and 40 degC, is about 620 Pa, and the
        // difference's rounding at sigma 690 MPa and step 5e-8 is about 3 Pa.
        #[test]
        fn derivatives_match_central_differences(
            a in 100e6..1000e6f64, b in 10e6..1000e6f64, n in 0.05..0.7f64, c in 0.001..0.2f64,
            m in 0.7..1.3f64, eps in 0.05..3.0f64, lrate in 0.05..12.0f64, t in 40.0..1400.0f64,
        ) {
            let jc = JcParams::new(a, b, n, c, m, 1.0, 1460.0, 20.0).unwrap();
            let rate = lrate.exp();
            let s = |e: f64, r: f64, t: f64| jc.flow_stress(e, r, t);
            let sigma = s(eps, rate, t);
            let rel = |an: f64, fd: f64, step: f64| {
                (an - fd).abs() <= 1e-5 * (an.abs() + fd.abs()) + 64.0 * f64::EPSILON * sigma.abs() / step
            };
            let h = 1e-6 * eps;
            prop_assert!(rel(jc.d_strain(eps, rate, t), (s(eps + h, rate, t) - s(eps - h, rate, t)) / (2.0 * h), h));
            let hr = 1e-6 * rate;
            prop_assert!(rel(jc.d_strain_rate(eps, rate, t), (s(eps, rate + hr, t) - s(eps, rate - hr, t)) / (2.0 * hr), hr));
            let ht = 1e-4;
            prop_assert!(rel(jc.d_temperature(eps, rate, t), (s(eps, rate, t + ht) - s(eps, rate, t - ht)) / (2.0 * ht), ht));
            let g = jc.gradient(eps, rate, t);
            let p = [a, b, n, c, m];
            for (k, gk) in g.iter().enumerate() {
                let step = 1e-6 * p[k];
                let mut up = p; up[k] += step;
                let mut dn = p; dn[k] -= step;
                let f = |q: [f64; 5]| JcParams { a_pa: q[0], b_pa: q[1], n: q[2], c: q[3], m: q[4], ..jc }.flow_stress(eps, rate, t);
                prop_assert!(rel(*gk, (f(up) - f(dn)) / (2.0 * step), step), "param {k}");
            }
        }

        // Flow stress rises with strain and falls with temperature (for B, n > 0).
        #[test]
        fn monotone_in_strain_and_temperature(eps in 0.01..3.0f64, t in 20.0..1400.0f64) {
            let jc = c38();
            prop_assert!(jc.flow_stress(eps * 1.1, 1e4, t) > jc.flow_stress(eps, 1e4, t));
            prop_assert!(jc.flow_stress(eps, 1e4, t + 10.0) < jc.flow_stress(eps, 1e4, t));
        }
    }
}
