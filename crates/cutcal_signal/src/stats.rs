//! Autocorrelation-aware statistics on a series of batch means: integrated autocorrelation time,
//! effective sample size, and a least-squares drift slope with an autocorrelation-corrected test.

/// Integrated autocorrelation time `tau = 1 + 2 sum_{t>=1} rho_t` of a series, by Geyer's initial
/// positive sequence estimator (Geyer 1992, "Practical Markov chain Monte Carlo", Statistical
/// Science 7(4):473-483, Sec. 3.3): sums of adjacent autocorrelation pairs
/// `Gamma_k = rho_2k + rho_2k+1` are added while positive, `tau = -1 + 2 sum_k Gamma_k`.
/// Returned clamped to `[1, n]` (conservative: never below the independent-sample value).
pub fn integrated_autocorrelation_time(x: &[f64]) -> f64 {
    let n = x.len();
    if n < 4 {
        return 1.0;
    }
    let mean = x.iter().sum::<f64>() / n as f64;
    let c0: f64 = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n as f64;
    if c0 <= 0.0 {
        return 1.0;
    }
    let rho = |lag: usize| -> f64 {
        let s: f64 = x[..n - lag].iter().zip(&x[lag..]).map(|(a, b)| (a - mean) * (b - mean)).sum();
        s / n as f64 / c0
    };
    let mut sum = 0.0;
    let mut k = 0;
    while 2 * k + 1 < n / 2 {
        let g = rho(2 * k) + rho(2 * k + 1);
        if g <= 0.0 {
            break;
        }
        sum += g;
        k += 1;
    }
    (-1.0 + 2.0 * sum).clamp(1.0, n as f64)
}

/// Least-squares line through `(t, y)` with the slope's standard error inflated by the residuals'
/// integrated autocorrelation time (the effective-sample-size trend test of Santer et al. 2000,
/// "Statistical significance of trends and trend differences in layer-average atmospheric
/// temperature time series", J. Geophys. Res. 105(D6):7337-7356, Eq. 3-6, with Geyer's tau in
/// place of the AR(1) factor).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Trend {
    /// Slope, units of y per unit of t.
    pub slope: f64,
    /// Standard error of the slope (autocorrelation-corrected).
    pub slope_se: f64,
    /// `slope / slope_se`.
    pub z: f64,
    /// Integrated autocorrelation time of the residuals.
    pub tau: f64,
}

/// Fit the trend; `None` below 4 points or with a degenerate time axis.
pub fn trend(t: &[f64], y: &[f64]) -> Option<Trend> {
    let n = t.len().min(y.len());
    if n < 4 {
        return None;
    }
    let nf = n as f64;
    let tm = t.iter().sum::<f64>() / nf;
    let ym = y.iter().sum::<f64>() / nf;
    let stt: f64 = t.iter().map(|v| (v - tm).powi(2)).sum();
    if stt <= 0.0 {
        return None;
    }
    let sty: f64 = t.iter().zip(y).map(|(a, b)| (a - tm) * (b - ym)).sum();
    let slope = sty / stt;
    let res: Vec<f64> = t.iter().zip(y).map(|(a, b)| b - ym - slope * (a - tm)).collect();
    let s2 = res.iter().map(|r| r * r).sum::<f64>() / (nf - 2.0);
    let tau = integrated_autocorrelation_time(&res);
    let slope_se = (s2 * tau / stt).sqrt();
    let z = if slope_se > 0.0 {
        slope / slope_se
    } else if slope.abs() < f64::MIN_POSITIVE {
        0.0
    } else {
        f64::MAX.copysign(slope)
    };
    Some(Trend { slope, slope_se, z, tau })
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    #[test]
    fn ar1_tau_matches_its_closed_form() {
        // AR(1) with phi = 0.8 has tau = (1 + phi) / (1 - phi) = 9 (e.g. Geyer 1992, Sec. 3.1).
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let mut x = 0.0;
        let v: Vec<f64> = (0..200_000)
            .map(|_| {
                let u: f64 = rng.gen::<f64>() - 0.5;
                x = 0.8 * x + u;
                x
            })
            .collect();
        let tau = integrated_autocorrelation_time(&v);
        assert!((tau - 9.0).abs() < 0.9, "tau = {tau}");
    }

    #[test]
    fn trend_recovers_a_known_slope() {
        let t: Vec<f64> = (0..100).map(|i| i as f64 * 0.01).collect();
        let y: Vec<f64> =
            t.iter().enumerate().map(|(i, t)| 5.0 + 2.0 * t + if i % 2 == 0 { 0.01 } else { -0.01 }).collect();
        let tr = trend(&t, &y).unwrap();
        assert!((tr.slope - 2.0).abs() < 1e-3, "{tr:?}");
        assert!(tr.z > 100.0);
    }
}
