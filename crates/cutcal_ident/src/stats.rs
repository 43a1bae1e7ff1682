//! Small statistics kernel: normal, Student t and F tail probabilities, the t quantile, AICc and the
//! Wilson interval. Closed forms and continued fractions only, so identification and diagnosis need no
//! stats crate.
//!
//! **Sources:** regularised incomplete beta by Lentz's continued fraction and the Lanczos log-gamma
//! (Press et al., *Numerical Recipes*, 3rd ed., Secs 6.1 and 6.4); erfc by the Chebyshev fit of
//! Numerical Recipes Sec 6.2 (relative error < 1.2e-7); AICc (Hurvich & Tsai 1989); Wilson score
//! interval (Wilson 1927).

/// Natural log of the gamma function for `x > 0` (Lanczos, g = 7, 9 terms).
#[must_use]
pub fn ln_gamma(x: f64) -> f64 {
    const G: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        // Reflection formula.
        let pi = std::f64::consts::PI;
        return (pi / (pi * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let mut a = G[0];
    let t = x + 7.5;
    for (i, g) in G.iter().enumerate().skip(1) {
        a += g / (x + i as f64);
    }
    0.5 * (2.0 * std::f64::consts::PI).ln() + (x + 0.5) * t.ln() - t + a.ln()
}

/// Regularised incomplete beta function `I_x(a, b)` for `a, b > 0`, `0 <= x <= 1`.
#[must_use]
pub fn beta_inc(a: f64, b: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    if x >= 1.0 {
        return 1.0;
    }
    let ln_front = ln_gamma(a + b) - ln_gamma(a) - ln_gamma(b) + a * x.ln() + b * (1.0 - x).ln();
    if x < (a + 1.0) / (a + b + 2.0) {
        ln_front.exp() * beta_cf(a, b, x) / a
    } else {
        1.0 - ln_front.exp() * beta_cf(b, a, 1.0 - x) / b
    }
}

fn beta_cf(a: f64, b: f64, x: f64) -> f64 {
    const TINY: f64 = 1e-300;
    let (qab, qap, qam) = (a + b, a + 1.0, a - 1.0);
    let mut c = 1.0;
    let mut d = 1.0 - qab * x / qap;
    if d.abs() < TINY {
        d = TINY;
    }
    d = 1.0 / d;
    let mut h = d;
    for m in 1..300 {
        let m = m as f64;
        let m2 = 2.0 * m;
        let aa = m * (b - m) * x / ((qam + m2) * (a + m2));
        d = 1.0 + aa * d;
        if d.abs() < TINY {
            d = TINY;
        }
        c = 1.0 + aa / c;
        if c.abs() < TINY {
            c = TINY;
        }
        d = 1.0 / d;
        h *= d * c;
        let aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2));
        d = 1.0 + aa * d;
        if d.abs() < TINY {
            d = TINY;
        }
        c = 1.0 + aa / c;
        if c.abs() < TINY {
            c = TINY;
        }
        d = 1.0 / d;
        let del = d * c;
        h *= del;
        if (del - 1.0).abs() < 1e-14 {
            break;
        }
    }
    h
}

/// Complementary error function (Numerical Recipes Chebyshev fit, relative error < 1.2e-7).
#[must_use]
pub fn erfc(x: f64) -> f64 {
    let z = x.abs();
    let t = 1.0 / (1.0 + 0.5 * z);
    let r = t
        * (-z * z - 1.265_512_23
            + t * (1.000_023_68
                + t * (0.374_091_96
                    + t * (0.096_784_18
                        + t * (-0.186_288_06
                            + t * (0.278_868_07
                                + t * (-1.135_203_98
                                    + t * (1.488_515_87 + t * (-0.822_152_23 + t * 0.170_872_77)))))))))
            .exp();
    if x >= 0.0 {
        r
    } else {
        2.0 - r
    }
}

/// Upper tail `P(Z > z)` of the standard normal.
#[must_use]
pub fn normal_sf(z: f64) -> f64 {
    0.5 * erfc(z / std::f64::consts::SQRT_2)
}

/// The standard normal upper quantile: `z` with `P(Z > z) = p`, by bisection on [`normal_sf`] over
/// [-40, 40], stopped once the bracket is two adjacent floats (capped at 200 halvings).
#[must_use]
pub fn normal_isf(p: f64) -> f64 {
    let (mut lo, mut hi) = (-40.0_f64, 40.0_f64);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid.to_bits() == lo.to_bits() || mid.to_bits() == hi.to_bits() {
            break;
        }
        if normal_sf(mid) > p {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Regularised upper incomplete gamma `Q(a, x)` (series for `x < a + 1`, continued fraction otherwise).
#[must_use]
pub fn gamma_q(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    let gln = ln_gamma(a);
    if x < a + 1.0 {
        let (mut ap, mut sum) = (a, 1.0 / a);
        let mut del = sum;
        for _ in 0..500 {
            ap += 1.0;
            del *= x / ap;
            sum += del;
            if del.abs() < sum.abs() * 1e-15 {
                break;
            }
        }
        1.0 - sum * (-x + a * x.ln() - gln).exp()
    } else {
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..500 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < tiny {
                d = tiny;
            }
            c = b + an / c;
            if c.abs() < tiny {
                c = tiny;
            }
            d = 1.0 / d;
            let del = d * c;
            h *= del;
            if (del - 1.0).abs() < 1e-15 {
                break;
            }
        }
        (-x + a * x.ln() - gln).exp() * h
    }
}

/// Upper tail `P(X > x)` of the chi-square distribution with `df` degrees of freedom.
#[must_use]
pub fn chi2_sf(x: f64, df: f64) -> f64 {
    if df <= 0.0 {
        return 1.0;
    }
    gamma_q(0.5 * df, 0.5 * x)
}

/// Two-sided p-value of a Student t statistic with `df` degrees of freedom.
#[must_use]
pub fn t_two_sided_p(t: f64, df: f64) -> f64 {
    if df <= 0.0 {
        return 1.0;
    }
    beta_inc(0.5 * df, 0.5, df / (df + t * t))
}

/// Upper tail `P(F > f)` of the F distribution with `(d1, d2)` degrees of freedom.
#[must_use]
pub fn f_sf(f: f64, d1: f64, d2: f64) -> f64 {
    if f <= 0.0 || d1 <= 0.0 || d2 <= 0.0 {
        return 1.0;
    }
    beta_inc(0.5 * d2, 0.5 * d1, d2 / (d2 + d1 * f))
}

/// Two-sided `1 - alpha` quantile of Student t: the `t` with `P(|T| > t) = alpha` (bisection).
#[must_use]
pub fn t_quantile_two_sided(alpha: f64, df: f64) -> f64 {
    let (mut lo, mut hi) = (0.0_f64, 1e3_f64);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        // Once the bracket is two adjacent floats the midpoint is one of them: nothing moves.
        if mid.to_bits() == lo.to_bits() || mid.to_bits() == hi.to_bits() {
            break;
        }
        if t_two_sided_p(mid, df) > alpha {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Small-sample corrected Akaike criterion for a Gaussian least-squares fit:
/// `n ln(RSS/n) + 2k + 2k(k+1)/(n-k-1)` (Hurvich & Tsai 1989). Infinite when `n <= k + 1`.
#[must_use]
pub fn aicc(rss: f64, n: usize, k: usize) -> f64 {
    let (nf, kf) = (n as f64, k as f64);
    if n <= k + 1 || rss <= 0.0 {
        return f64::INFINITY;
    }
    nf * (rss / nf).ln() + 2.0 * kf + 2.0 * kf * (kf + 1.0) / (nf - kf - 1.0)
}

/// Wilson score interval for `k` successes in `n` trials at normal quantile `z` (1.96 for 95 %).
#[must_use]
pub fn wilson(k: usize, n: usize, z: f64) -> (f64, f64) {
    if n == 0 {
        return (0.0, 1.0);
    }
    let (kf, nf) = (k as f64, n as f64);
    let p = kf / nf;
    let den = 1.0 + z * z / nf;
    let centre = (p + z * z / (2.0 * nf)) / den;
    let half = z * (p * (1.0 - p) / nf + z * z / (4.0 * nf * nf)).sqrt() / den;
    ((centre - half).max(0.0), (centre + half).min(1.0))
}

/// Holm step-down adjustment of p-values (returned in the input order).
#[must_use]
pub fn holm(p: &[f64]) -> Vec<f64> {
    let mut idx: Vec<usize> = (0..p.len()).collect();
    idx.sort_by(|a, b| p[*a].total_cmp(&p[*b]));
    let m = p.len();
    let mut out = vec![1.0; m];
    let mut running: f64 = 0.0;
    for (rank, &i) in idx.iter().enumerate() {
        let adj = ((m - rank) as f64 * p[i]).min(1.0);
        running = running.max(adj);
        out[i] = running;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normal_tail_matches_tables() {
        // Standard normal table: P(Z > 1.959964) = 0.025, P(Z > 0) = 0.5.
        assert!((normal_sf(1.959_964) - 0.025).abs() < 1e-6);
        assert!((normal_sf(0.0) - 0.5).abs() < 1e-7);
        // And its inverse (to the tail approximation's accuracy): z_0.975 = 1.959964, z_0.5 = 0.
        assert!((normal_isf(0.025) - 1.959_964).abs() < 1e-6 && normal_isf(0.5).abs() < 1e-6);
    }

    #[test]
    fn t_and_f_tails_match_tables() {
        // t table: two-sided 5 % critical value for df = 10 is 2.228139 (scipy.stats.t.ppf(0.975, 10)).
        assert!((t_two_sided_p(2.228_139, 10.0) - 0.05).abs() < 1e-6);
        assert!((t_quantile_two_sided(0.05, 10.0) - 2.228_139).abs() < 1e-5);
        // F table: F(0.95; 2, 10) = 4.102821 (scipy.stats.f.ppf(0.95, 2, 10)).
        assert!((f_sf(4.102_821, 2.0, 10.0) - 0.05).abs() < 1e-6);
        // F(1, d2) = t(d2)^2.
        assert!((f_sf(2.228_139f64.powi(2), 1.0, 10.0) - 0.05).abs() < 1e-6);
    }

    #[test]
    fn chi2_tail_matches_tables() {
        // chi-square table: P(X > 3.841459) = 0.05 for df 1; P(X > 18.307038) = 0.05 for df 10;
        // P(X > 2) = exp(-1) for df 2 (closed form).
        assert!((chi2_sf(3.841_459, 1.0) - 0.05).abs() < 1e-6);
        assert!((chi2_sf(18.307_038, 10.0) - 0.05).abs() < 1e-6);
        assert!((chi2_sf(2.0, 2.0) - (-1.0f64).exp()).abs() < 1e-12);
    }

    #[test]
    fn wilson_interval_matches_hand_calculation() {
        // 0 of 60 at z = 1.96: upper = z^2/n / (1 + z^2/n) = 0.0640/1.0640 = 0.06015.
        let (lo, hi) = wilson(0, 60, 1.96);
        assert!(lo.abs() < 1e-12 && (hi - 0.060_15).abs() < 1e-4);
    }

    #[test]
    fn holm_is_monotone_and_scaled() {
        // p = (0.01, 0.04, 0.03): sorted 0.01*3 = 0.03, 0.03*2 = 0.06, 0.04*1 -> max(0.06, 0.04) = 0.06.
        let a = holm(&[0.01, 0.04, 0.03]);
        assert!((a[0] - 0.03).abs() < 1e-12 && (a[2] - 0.06).abs() < 1e-12 && (a[1] - 0.06).abs() < 1e-12);
    }
}
