//! The start filter of the multistart ([`crate::multistart`]): multi-level single linkage (MLSL,
//! Rinnooy Kan and Timmer, Math. Programming 39 (1987) 57-78, Sec 3). The objective is evaluated at
//! every sample point first, and a local search is started from a sample point only if no sample
//! point with a lower objective lies within the critical distance
//! `r_k = pi^{-1/2} (Gamma(1 + d/2) sigma ln k / k)^{1/d}` (their Eq 4, unit box of the `d` free
//! parameters, `k` sample points; `sigma` = [`MLSL_SIGMA`] in the DPZD identification, chosen by
//! measurement).

use nalgebra::DVector;

use crate::lm::{Bounds, Problem};

/// The sample filter of the multistart (module docs).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SampleFilter {
    /// The caller's default: off in the generic [`crate::multistart::multistart`], MLSL with `sigma` =
    /// [`MLSL_SIGMA`] in the DPZD identification ([`crate::dpzd_fit::identify`]).
    Auto,
    /// A local search from every sample point.
    Off,
    /// MLSL with this `sigma` (> 0) in the critical distance.
    Mlsl {
        /// `sigma` of Rinnooy Kan and Timmer's critical distance (their Eq 4).
        sigma: f64,
    },
}

impl SampleFilter {
    /// The `sigma` this filter applies, given the caller's default for [`SampleFilter::Auto`].
    #[must_use]
    pub fn sigma(self, auto: Option<f64>) -> Option<f64> {
        match self {
            Self::Auto => auto,
            Self::Off => None,
            Self::Mlsl { sigma } => Some(sigma),
        }
    }
}

/// `sigma` of the MLSL critical distance in the DPZD identification: 1, chosen by measurement.
///
/// Rinnooy Kan and Timmer (1987) prove that every local minimum is found with probability 1 as
/// the sample grows for any `sigma > 0`, that the chance of a new search at a stage tends to 0
/// for `sigma > 2`, and that the expected number of searches is finite for `sigma > 4`. With the
/// few tens of points a user runs, the asymptotics do not decide. Measured on the projected
/// problem of random JC truths (the generator of `tests/varpro.rs`; a miss is a best SSR above the
/// exhaustive multistart's): `sigma = 4` missed in 21/400 truths at 16 starts and 2/400 at 32;
/// `sigma = 2` in 23/1500 at 16 and 4/1500 at 32; `sigma = 1.5` in 1/1500 at 50 and in one
/// `CUTCAL_FUZZ_CASES=2000` proptest case at 16 (SSR 2e-3 relative, a flat n-m valley);
/// `sigma = 1` (with the basin radius [`crate::multistart::DPZD_BASIN_RADIUS`]) in none of 1500 at each of 16, 32
/// and 50 starts nor of 3000 proptest cases, searching 8.1, 11.0 and 12.6 of the points on
/// average (docs/identification-speed.md).
pub const MLSL_SIGMA: f64 = 1.0;

/// MLSL's critical distance for `k` sample points in the unit box of `d` free parameters
/// (`d >= 1`, `k >= 2`; otherwise 0, which filters nothing).
///
/// **Source:** Rinnooy Kan and Timmer (1987), Eq 4 (`m(S) = 1`).
#[must_use]
pub fn mlsl_critical_distance(d: usize, k: usize, sigma: f64) -> f64 {
    if d == 0 || k < 2 || !(sigma > 0.0) {
        return 0.0;
    }
    // Gamma(1 + d/2) by the recursion Gamma(1 + x) = x Gamma(x), down to Gamma(1) or Gamma(1/2).
    let mut x = d as f64 / 2.0;
    let mut gamma = 1.0;
    while x > 0.75 {
        gamma *= x;
        x -= 1.0;
    }
    if x > 0.25 {
        gamma *= 0.5 * std::f64::consts::PI.sqrt();
    }
    let kf = k as f64;
    (gamma * sigma * kf.ln() / kf).powf(1.0 / d as f64) / std::f64::consts::PI.sqrt()
}

/// MLSL's sample filter (module docs): `true` for every sample point (but start 0) with a sample
/// point of lower objective within `rk` (unit box; ties broken by index). A point whose objective
/// cannot be evaluated is never filtered (its local search reports the failure).
///
/// **Source:** Rinnooy Kan and Timmer (1987), Sec 3.
pub(crate) fn mlsl_filter<P: Problem + ?Sized>(
    problem: &P,
    bounds: &Bounds,
    units: &[DVector<f64>],
    rk: f64,
) -> Vec<bool> {
    // Only a point with another within `rk` can filter or be filtered: the others' objective is
    // not needed (a Monte-Carlo sample's 2 starts usually lie farther apart than `rk`).
    let near = |i: usize| (0..units.len()).any(|j| j != i && distance(&units[j], &units[i]) <= rk);
    let mut r = DVector::zeros(problem.residual_count());
    let f: Vec<Option<f64>> = (0..units.len())
        .map(|i| {
            if !near(i) {
                return None;
            }
            problem.residuals(&bounds.from_unit(&units[i]), &mut r).ok()?;
            let ssr = r.norm_squared();
            ssr.is_finite().then_some(ssr)
        })
        .collect();
    let lower = |j: usize, i: usize| match (f[j], f[i]) {
        // `None`: not evaluated (no point within `rk`) or failed; never filters nor is filtered.
        // An exact tie is broken by index (the lower one counts as lower).
        #[allow(clippy::float_cmp)]
        (Some(fj), Some(fi)) => fj < fi || (fj == fi && j < i),
        _ => false,
    };
    (0..units.len())
        .map(|i| {
            i > 0
                && f[i].is_some()
                && (0..units.len()).any(|j| j != i && lower(j, i) && distance(&units[j], &units[i]) <= rk)
        })
        .collect()
}

/// Euclidean distance of two points (no allocation).
pub(crate) fn distance(a: &DVector<f64>, b: &DVector<f64>) -> f64 {
    a.iter().zip(b.iter()).map(|(x, y)| (x - y) * (x - y)).sum::<f64>().sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn critical_distance_matches_eq_4_by_hand() {
        // Independent values (Python's math.gamma): d = 1: Gamma(1.5) = sqrt(pi)/2, so
        // r = sigma ln k / (2 k); d = 2: Gamma(2) = 1, r = sqrt(sigma ln k / k / pi).
        for (d, k, sigma, want) in [
            (1, 10, 1.0, 0.115_129_254_649_702_32),
            (2, 10, 1.0, 0.270_727_833_604_051_1),
            (3, 50, 4.0, 0.421_179_856_794_686_06),
            (3, 32, 1.0, 0.295_700_659_128_123_4),
            (5, 20, 2.0, 0.563_690_745_764_305_8),
        ] {
            let got = mlsl_critical_distance(d, k, sigma);
            assert!((got - want).abs() < 1e-12, "d {d} k {k} sigma {sigma}: {got} vs {want}");
        }
        assert_eq!(mlsl_critical_distance(0, 10, 1.0), 0.0);
        assert_eq!(mlsl_critical_distance(3, 1, 1.0), 0.0);
        assert_eq!(mlsl_critical_distance(3, 10, f64::NAN), 0.0);
    }

    /// `r = (x - 0.3)`: one minimum at 0.3.
    struct Bowl;
    impl Problem for Bowl {
        fn parameter_count(&self) -> usize {
            1
        }
        fn residual_count(&self) -> usize {
            1
        }
        fn residuals(&self, p: &DVector<f64>, out: &mut DVector<f64>) -> Result<(), crate::IdentError> {
            out[0] = p[0] - 0.3;
            Ok(())
        }
    }

    #[test]
    fn a_point_with_a_better_neighbour_is_filtered_and_start_0_never() {
        let b = Bounds::new(vec!["x".into()], vec![0.0], vec![1.0]).unwrap();
        let units: Vec<DVector<f64>> =
            [0.9, 0.32, 0.35, 0.6, 0.95].iter().map(|x| DVector::from_element(1, *x)).collect();
        // Radius 0.1: 0.35 has 0.32 (better) within 0.03, and 0.95 has 0.9 (|0.9 - 0.3| = 0.6 <
        // 0.65) within 0.05: both filtered; 0.6 has no point within 0.1; 0.32 is the best; start
        // 0 (0.9) is always kept.
        let f = mlsl_filter(&Bowl, &b, &units, 0.1);
        assert_eq!(f, vec![false, false, true, false, true]);
        // Radius 0.7: every point but the best and start 0 has a better one within reach.
        assert_eq!(mlsl_filter(&Bowl, &b, &units, 0.7), vec![false, false, true, true, true]);
    }
}
