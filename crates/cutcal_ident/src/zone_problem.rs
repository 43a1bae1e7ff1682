//! The Eq 15 least-squares problem over a set of DPZD zone points ([`ZoneFitProblem`]): the
//! residuals `sqrt(w_k) (f_k - F_k)` of the JC stress (paper Eq 16) against the DPZD stress
//! (Eq 8) with the analytic Jacobian, the parameter-free logarithms cached once per point, and its
//! variable-projection form ([`crate::varpro`]). The identification that minimises it is
//! [`crate::dpzd_fit`].

use cutcal_model::dpzd::ZonePoint;
use cutcal_model::{JcParams, RateTerm};
use nalgebra::{DMatrix, DVector};
use serde::Serialize;

use crate::error::IdentError;
use crate::lm::{Bounds, Problem};
use crate::varpro::VarproProblem;

/// The constants of the JC law that are not identified.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct JcConstants {
    /// Reference strain rate, 1/s.
    pub eps0_per_s: f64,
    /// Melting temperature, degC.
    pub tm_c: f64,
    /// Reference temperature, degC.
    pub tr_c: f64,
}

impl JcConstants {
    /// JC parameters from an optimisation vector `[A_MPa, B_MPa, n, C, m]`.
    #[must_use]
    pub fn params(&self, p: &DVector<f64>) -> JcParams {
        JcParams {
            a_pa: p[0] * 1e6,
            b_pa: p[1] * 1e6,
            n: p[2],
            c: p[3],
            m: p[4],
            eps0_per_s: self.eps0_per_s,
            tm_c: self.tm_c,
            tr_c: self.tr_c,
        }
    }
}

/// The Eq 15 least-squares problem over a set of zone points.
///
/// The logarithms that do not depend on the parameters (`ln eps`, `ln(epsdot/eps0)`,
/// `ln theta`) are computed once, so a residual costs two `exp` per point; the values equal
/// [`JcParams::flow_stress`] and [`JcParams::gradient`] (checked in the tests).
#[derive(Debug, Clone)]
pub struct ZoneFitProblem {
    points: Vec<ZonePoint>,
    pub(crate) constants: JcConstants,
    rate_term: RateTerm,
    pub(crate) weight_sum: f64,
    cached: Vec<CachedPoint>,
}

/// Parameter-independent parts of the JC law at one point.
#[derive(Debug, Clone, Copy)]
pub(crate) struct CachedPoint {
    /// `ln eps`, or `None` where eps = 0 (then eps^n = 0 for n > 0).
    pub(crate) ln_strain: Option<f64>,
    /// `ln(epsdot/eps0)` as it enters the law (clamped at 0 for [`RateTerm::Clamped`]).
    pub(crate) ln_rate: f64,
    /// Square root of the quadrature weight (1 for the uniform discrete objective).
    pub(crate) sqrt_weight: f64,
    /// `ln theta`, or `None` where the homologous temperature is 0 (no softening).
    pub(crate) ln_theta: Option<f64>,
    /// Target `sqrt(3) tau_e`, MPa.
    pub(crate) target_mpa: f64,
}

impl ZoneFitProblem {
    /// A problem over the given points, unit weights, the solvers' clamped law.
    #[must_use]
    pub fn new(points: Vec<ZonePoint>, constants: JcConstants) -> Self {
        let w = vec![1.0; points.len()];
        Self::weighted(points, &w, constants, RateTerm::Clamped)
    }

    /// A problem with quadrature weights `weights` (>= 0, one per point) and an explicit rate term.
    ///
    /// The residuals are `sqrt(w_k) (f_k - F_k)`, so the SSR is `sum w_k (f_k - F_k)^2`.
    #[must_use]
    pub fn weighted(points: Vec<ZonePoint>, weights: &[f64], constants: JcConstants, rate_term: RateTerm) -> Self {
        let probe = JcParams {
            a_pa: 0.0,
            b_pa: 0.0,
            n: 0.0,
            c: 0.0,
            m: 1.0,
            eps0_per_s: constants.eps0_per_s,
            tm_c: constants.tm_c,
            tr_c: constants.tr_c,
        };
        let cached = points
            .iter()
            .zip(weights)
            .map(|(p, w)| {
                let theta = probe.homologous(p.temperature_c);
                CachedPoint {
                    ln_strain: (p.strain > 0.0).then(|| p.strain.ln()),
                    ln_rate: rate_term.log_ratio(p.strain_rate_per_s, constants.eps0_per_s),
                    sqrt_weight: w.max(0.0).sqrt(),
                    ln_theta: (theta > 0.0).then(|| theta.ln()),
                    target_mpa: p.effective_stress_pa / 1e6,
                }
            })
            .collect();
        let weight_sum = weights.iter().map(|w| w.max(0.0)).sum();
        Self { points, constants, rate_term, weight_sum, cached }
    }

    /// The rate term of the law fitted.
    #[must_use]
    pub fn rate_term(&self) -> RateTerm {
        self.rate_term
    }

    /// Unweighted residuals `f_k - F_k` in MPa at `p` (A, B in MPa).
    #[must_use]
    pub fn raw_residuals(&self, p: &DVector<f64>) -> Vec<f64> {
        self.raw_residuals_iter(p).collect()
    }

    /// [`Self::raw_residuals`] without the allocation, paired with the targets `F_k` (MPa).
    pub(crate) fn raw_residuals_iter<'s>(&'s self, p: &'s DVector<f64>) -> impl Iterator<Item = f64> + 's {
        self.cached.iter().map(move |c| Self::eval(p, c).0 - c.target_mpa)
    }

    /// The targets `F_k = sqrt(3) tau_e` (MPa) of the points.
    pub(crate) fn targets_mpa(&self) -> impl Iterator<Item = f64> + '_ {
        self.cached.iter().map(|c| c.target_mpa)
    }

    /// One problem from parts with the same constants and rate term, each point's weight
    /// multiplied by the weight given with its part (one per point): a quadrature rule assembled
    /// from its panels without re-evaluating the zone points or their logarithms.
    pub(crate) fn from_weighted_parts<'p>(
        parts: impl IntoIterator<Item = (&'p ZoneFitProblem, &'p [f64])>,
        constants: JcConstants,
        rate_term: RateTerm,
    ) -> Self {
        let parts: Vec<_> = parts.into_iter().collect();
        let total = parts.iter().map(|(part, _)| part.points.len()).sum();
        let (mut points, mut cached, mut weight_sum) = (Vec::with_capacity(total), Vec::with_capacity(total), 0.0);
        for (part, weights) in parts {
            debug_assert!(part.rate_term == rate_term && part.constants == constants);
            points.extend_from_slice(&part.points);
            for (c, w) in part.cached.iter().zip(weights) {
                let w = w.max(0.0);
                weight_sum += c.sqrt_weight * c.sqrt_weight * w;
                cached.push(CachedPoint { sqrt_weight: c.sqrt_weight * w.sqrt(), ..*c });
            }
        }
        Self { points, constants, rate_term, weight_sum, cached }
    }

    /// The points.
    #[must_use]
    pub fn points(&self) -> &[ZonePoint] {
        &self.points
    }

    /// The same problem with A and B (MPa) eliminated by variable projection ([`crate::varpro`]).
    #[must_use]
    pub fn projected(&self, a_box_mpa: [f64; 2], b_box_mpa: [f64; 2]) -> VarproProblem<'_> {
        VarproProblem::new(&self.cached, a_box_mpa, b_box_mpa)
    }

    /// JC stress in MPa and its gradient w.r.t. `[A_MPa, B_MPa, n, C, m]` at one cached point.
    #[inline]
    fn eval(p: &DVector<f64>, c: &CachedPoint) -> (f64, [f64; 5]) {
        let (a, b, n, cc, m) = (p[0], p[1], p[2], p[3], p[4]);
        let (en, d_en_dn) = match c.ln_strain {
            Some(l) => {
                let e = (n * l).exp();
                (e, e * l)
            }
            None if n == 0.0 => (1.0, 0.0),
            None => (0.0, 0.0),
        };
        let h = a + b * en;
        let rf = 1.0 + cc * c.ln_rate;
        let (tm, d_tm_dm) = match c.ln_theta {
            Some(l) => {
                let t = (m * l).exp();
                (t, t * l)
            }
            None => (0.0, 0.0),
        };
        let g = 1.0 - tm;
        (h * rf * g, [rf * g, en * rf * g, b * d_en_dn * rf * g, h * c.ln_rate * g, -h * rf * d_tm_dm])
    }
}

impl Problem for ZoneFitProblem {
    fn parameter_count(&self) -> usize {
        5
    }

    fn residual_count(&self) -> usize {
        self.points.len()
    }

    /// `f_k(x) - F_k` in MPa (paper Eq 15).
    fn residuals(&self, p: &DVector<f64>, out: &mut DVector<f64>) -> Result<(), IdentError> {
        for (o, c) in out.iter_mut().zip(&self.cached) {
            *o = c.sqrt_weight * (Self::eval(p, c).0 - c.target_mpa);
        }
        Ok(())
    }

    /// Analytic Jacobian (MPa per parameter unit; A and B are in MPa in the vector).
    fn jacobian(&self, p: &DVector<f64>, _bounds: &Bounds, out: &mut DMatrix<f64>) -> Result<(), IdentError> {
        for (i, c) in self.cached.iter().enumerate() {
            let g = Self::eval(p, c).1;
            for (k, gk) in g.iter().enumerate() {
                out[(i, k)] = c.sqrt_weight * *gk;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn point(strain: f64, rate: f64, t: f64) -> ZonePoint {
        ZonePoint {
            x_m: 0.0,
            gamma: strain * 3f64.sqrt(),
            gamma_dot_per_s: rate * 3f64.sqrt(),
            strain,
            strain_rate_per_s: rate,
            tau_pa: 0.0,
            effective_stress_pa: 0.0,
            work_j_per_m3: 0.0,
            temperature_c: t,
        }
    }

    proptest! {
        // The cached evaluation equals JcParams::flow_stress / gradient (the reference law, Eq 16).
        #[test]
        fn cached_law_equals_reference(
            a in 100.0..1000.0f64, b in 0.0..1000.0f64, n in 0.0..0.7f64, c in 0.0..0.2f64, m in 0.7..1.3f64,
            eps in 0.0..3.0f64, lrate in 0.0..12.0f64, t in 0.0..1400.0f64,
        ) {
            let k = JcConstants { eps0_per_s: 1.0, tm_c: 1460.0, tr_c: 20.0 };
            let prob = ZoneFitProblem::new(vec![point(eps, lrate.exp(), t)], k);
            let pv = DVector::from_vec(vec![a, b, n, c, m]);
            let (s, g) = ZoneFitProblem::eval(&pv, &prob.cached[0]);
            let jc = k.params(&pv);
            let want = jc.flow_stress(eps, lrate.exp(), t) / 1e6;
            prop_assert!((s - want).abs() <= 1e-9 * want.abs().max(1.0));
            let gr = jc.gradient(eps, lrate.exp(), t);
            let scale = [1.0, 1.0, 1e-6, 1e-6, 1e-6];
            for k in 0..5 {
                prop_assert!((g[k] - gr[k] * scale[k]).abs() <= 1e-9 * (gr[k] * scale[k]).abs().max(1e-9), "k {}", k);
            }
        }
    }
}
